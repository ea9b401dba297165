/* aalab dashboard: the drawing helpers every view shares. Elements, round axis ticks, a palette of eight
 * colours told apart by colour-blind readers (Okabe-Ito plus two), dash and marker patterns for more
 * series than colours, text measured as the browser will draw it, and the cost-vs-quality scatter whose
 * labels sit beside their points or at the end of a leader line, never on another label or point. */
"use strict";

const SVG_NS = "http://www.w3.org/2000/svg";

function el(tag, attrs, ...children) {
  const svg = attrs && attrs.svg;
  const e = svg ? document.createElementNS(SVG_NS, tag) : document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "svg" || v === undefined || v === null) continue;
    if (k.startsWith("on")) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children.flat()) if (c !== null && c !== undefined) e.append(c);
  return e;
}
const s = (tag, attrs, ...children) => el(tag, Object.assign({svg: 1}, attrs), ...children);

const PALETTE = ["#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000", "#8c564b"];
const DASHES = ["", "6 3", "2 3", "10 3 2 3"];
const MARKERS = ["circle", "square", "triangle", "diamond"];

/* Series k's look: a colour, and past eight series a dash pattern and a marker shape as well, so that
 * no two of 32 series look alike. */
function seriesStyle(k) {
  const round = Math.floor(k / PALETTE.length) % DASHES.length;
  return {color: PALETTE[k % PALETTE.length], dash: DASHES[round], marker: MARKERS[round]};
}

function marker(shape, x, y, r, color, attrs) {
  const a = Object.assign({fill: color}, attrs || {});
  if (shape === "square") return s("rect", Object.assign({x: x - r, y: y - r, width: 2 * r, height: 2 * r}, a));
  if (shape === "triangle")
    return s("path", Object.assign({d: `M${x} ${y - r * 1.2}L${x + r * 1.1} ${y + r * 0.8}L${x - r * 1.1} ${y + r * 0.8}Z`}, a));
  if (shape === "diamond")
    return s("path", Object.assign({d: `M${x} ${y - r * 1.3}L${x + r * 1.3} ${y}L${x} ${y + r * 1.3}L${x - r * 1.3} ${y}Z`}, a));
  return s("circle", Object.assign({cx: x, cy: y, r: r}, a));
}

/* A legend swatch: a short line in the series' dash with its marker in the middle. */
function swatch(style) {
  return s("svg", {width: 28, height: 12, class: "swatch", viewBox: "0 0 28 12"},
           s("line", {x1: 1, y1: 6, x2: 27, y2: 6, stroke: style.color, "stroke-width": 2,
                      "stroke-dasharray": style.dash || null}),
           marker(style.marker || "circle", 14, 6, 3.5, style.color));
}

/* Ticks at 1, 2 or 5 times a power of ten, about `count` of them, covering [lo, hi]: {lo, hi, ticks, text}. */
function niceTicks(lo, hi, count) {
  if (!isFinite(lo) || !isFinite(hi)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-9 * Math.max(1, Math.abs(hi))) { const pad = Math.max(0.5, Math.abs(hi) * 0.05); lo -= pad; hi += pad; }
  const raw = (hi - lo) / (count || 5), e = Math.pow(10, Math.floor(Math.log10(raw))), f = raw / e;
  const step = (f <= 1 ? 1 : f <= 2 ? 2 : f <= 5 ? 5 : 10) * e;
  const first = Math.floor(lo / step + 1e-9), last = Math.ceil(hi / step - 1e-9);
  const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  const ticks = [];
  for (let k = first; k <= last; k++) ticks.push(Number((k * step).toFixed(decimals)));
  return {lo: first * step, hi: last * step, ticks, text: v => v.toFixed(decimals)};
}

/* Log-axis ticks between lo and hi (lo > 0): 1, 2 and 5 times each power of ten, or only the powers when
 * those alone give four ticks or more (so that a range of 1 to 80 has 1, 2, 5, 10, 20, 50, not 1 and 10);
 * a range too narrow for three of those gets evenly stepped round ticks. */
function logTicks(lo, hi) {
  const a = Math.floor(Math.log10(lo)), b = Math.ceil(Math.log10(hi));
  const within = ms => {
    const ticks = [];
    for (let e = a; e <= b; e++)
      for (const m of ms) {
        const v = Number((m * Math.pow(10, e)).toPrecision(3));
        if (v >= lo * 0.999 && v <= hi * 1.001) ticks.push(v);
      }
    return ticks;
  };
  const powers = within([1]);
  const ticks = powers.length >= 4 ? powers : within([1, 2, 5]);
  if (ticks.length < 3) { /* a narrow range (0.8 to 2.4 ms): evenly stepped round ticks, placed on the log scale */
    const even = niceTicks(lo, hi, 5);
    return {lo, hi, ticks: even.ticks.filter(v => v > 0 && v >= lo * 0.999 && v <= hi * 1.001), text: even.text};
  }
  return {lo: Math.pow(10, Math.log10(lo)), hi, ticks, text: v => v >= 1 ? String(v) : v.toPrecision(1)};
}

let measureCtx = null;
/* The width the browser gives `text` in the charts' label font. */
function textWidth(text, font) {
  if (!measureCtx) measureCtx = document.createElement("canvas").getContext("2d");
  measureCtx.font = font || "12px system-ui, sans-serif";
  return measureCtx.measureText(text).width;
}

const overlaps = (a, b) => a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;

/* Distance from (x, y) to the nearest point of box b (0 inside it). */
const boxDistance = (b, x, y) => Math.hypot(Math.max(b.x0 - x, 0, x - b.x1), Math.max(b.y0 - y, 0, y - b.y1));

/* Places one label per point: beside it if there is room, else at the nearest free spot around it
 * (rings of growing radius, eight directions each), joined to it by a leader line. A spot is free when it
 * overlaps no placed label and no point, stays inside `box`, and no other point is nearer to it than its
 * own (a label beside someone else's point reads as theirs). Points with the most neighbours go first.
 * Each label starts with a GLYPH px wide space for its point's marker, which ties it to its point too.
 * points: [{x, y, text}] -> [{x0, y0, x1, y1, tx, ty, gx, gy, leader}] in the same order. */
const GLYPH = 0; /* room for a marker glyph before the text: none (a glyph read as a second point) */
function placeLabels(points, box, font) {
  const H = 15, PAD = 2, R = 7;
  const dots = points.map(p => ({x0: p.x - R, x1: p.x + R, y0: p.y - R, y1: p.y + R}));
  const crowd = points.map(p => points.filter(q => Math.hypot(q.x - p.x, q.y - p.y) < 60).length);
  const order = points.map((_, i) => i).sort((a, b) => crowd[b] - crowd[a] || points[a].x - points[b].x);
  const placed = new Array(points.length), boxes = [];
  const dirs = [[1, 0], [-1, 0], [1, -1], [1, 1], [-1, -1], [-1, 1], [0, -1], [0, 1]];
  const fits = (i, b, strict) => {
    if (b.x0 < box.x0 || b.x1 > box.x1 || b.y0 < box.y0 || b.y1 > box.y1) return false;
    if (boxes.some(o => overlaps(o, b)) || dots.some(d => overlaps(d, b))) return false;
    if (!strict) return true;
    const own = boxDistance(b, points[i].x, points[i].y);
    return !points.some((q, j) => j !== i && (q.x !== points[i].x || q.y !== points[i].y) &&
                                  boxDistance(b, q.x, q.y) < Math.min(own, 16));
  };
  for (const i of order) {
    const p = points[i], w = GLYPH + textWidth(p.text, font) + 2 * PAD;
    let best = null;
    for (const strict of [true, false])
      for (let r = 9; r <= 240 && !best; r += 10)
        for (const [dx, dy] of dirs) {
          /* the box's edge nearest the point sits r away from it */
          const cx = p.x + dx * r, cy = p.y + dy * r * 0.8;
          const x0 = dx > 0 ? cx : dx < 0 ? cx - w : cx - w / 2;
          const y0 = dy > 0 ? cy : dy < 0 ? cy - H : cy - H / 2;
          const b = {x0, y0, x1: x0 + w, y1: y0 + H};
          if (fits(i, b, strict)) { best = b; break; }
        }
    if (!best) { /* nowhere free: the first spot inside the box, still joined by its line */
      const x0 = Math.min(Math.max(p.x + 9, box.x0), box.x1 - w);
      best = {x0, y0: p.y - H / 2, x1: x0 + w, y1: p.y + H / 2};
    }
    boxes.push(best);
    /* the leader ends at the box's nearest point; a label right beside its point needs none, unless
     * another point is as near to it (a spot taken when nothing strict was free) */
    const ex = Math.min(Math.max(p.x, best.x0), best.x1), ey = Math.min(Math.max(p.y, best.y0), best.y1);
    const own = boxDistance(best, p.x, p.y);
    const far = Math.hypot(ex - p.x, ey - p.y) > R + 4 ||
                points.some((q, j) => j !== i && (q.x !== p.x || q.y !== p.y) && boxDistance(best, q.x, q.y) <= own);
    placed[i] = Object.assign(best, {gx: best.x0 + PAD + GLYPH / 2 - 1, gy: best.y0 + H / 2, tx: best.x0 + PAD + GLYPH,
                                     ty: best.y0 + H - 4, leader: far ? [p.x, p.y, ex, ey] : null});
  }
  return placed;
}

/* An axis frame: the plot rectangle, grid lines and tick labels. x and y are {lo, hi, ticks, text, log}. */
function axes(svg, frame, x, y, xlabel, ylabel) {
  const {L, T, R, B} = frame;
  svg.append(s("rect", {class: "plot", x: L, y: T, width: R - L, height: B - T}));
  for (const t of x.ticks) {
    const px = x.scale(t);
    svg.append(s("line", {class: "grid", x1: px, x2: px, y1: T, y2: B}),
               s("text", {class: "tick x-tick", x: px, y: B + 15, "text-anchor": "middle"}, x.text(t)));
  }
  for (const t of y.ticks) {
    const py = y.scale(t);
    svg.append(s("line", {class: "grid", x1: L, x2: R, y1: py, y2: py}),
               s("text", {class: "tick y-tick", x: L - 6, y: py + 4, "text-anchor": "end"}, y.text(t)));
  }
  svg.append(s("text", {class: "axis", x: (L + R) / 2, y: B + 34, "text-anchor": "middle"}, xlabel),
             s("text", {class: "axis", transform: `translate(14 ${(T + B) / 2}) rotate(-90)`, "text-anchor": "middle"}, ylabel));
}

/* A linear or log scale over a nice range, mapped to pixels [p0, p1]. */
function scale(lo, hi, p0, p1, log) {
  const t = log ? logTicks(lo, hi) : niceTicks(lo, hi, 5);
  const a = log ? Math.log10(t.ticks.length ? Math.min(lo, t.ticks[0]) : lo) : t.lo;
  const b = log ? Math.log10(t.ticks.length ? Math.max(hi, t.ticks[t.ticks.length - 1]) : hi) : t.hi;
  const f = v => log ? Math.log10(v) : v;
  t.scale = v => p0 + (p1 - p0) * (f(v) - a) / (b - a || 1);
  t.log = log;
  return t;
}

/* A floating tooltip shared by every chart: shown beside the pointer over anything with data-tip. */
let tooltip = null;
function attachTooltip(root) {
  if (!tooltip) {
    tooltip = el("div", {id: "tooltip", role: "tooltip"});
    document.body.append(tooltip);
  }
  root.addEventListener("mousemove", ev => {
    const t = ev.target.closest("[data-tip]");
    if (!t) { tooltip.style.display = "none"; return; }
    tooltip.textContent = t.getAttribute("data-tip");
    tooltip.style.display = "block";
    tooltip.style.left = Math.min(ev.pageX + 14, window.scrollX + window.innerWidth - tooltip.offsetWidth - 8) + "px";
    tooltip.style.top = ev.pageY + 14 + "px";
  });
  root.addEventListener("mouseleave", () => { tooltip.style.display = "none"; });
}
