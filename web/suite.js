/* aalab dashboard: a finished job as a suite view and a case view, from its results.json (and its
 * baseline's, when the job names one).
 * The suite view is a case x method matrix: each cell's text is the number, its colour that number's
 * sign and size (dB over `none`, dB over the baseline job, or the raw metric); a ring marks a method on
 * its case's front; each row names the case's verdict and its warnings; a click opens the case.
 * The case view draws cost against quality for one case (labels tied to their points, round ticks, a log
 * option, p10-p90 bars, the front as a staircase, method families as lines when the verdict has them),
 * each method's GPU time split by pass, the reference and its convergence, and every number in a table. */
"use strict";

/* A job's cases, each {id, scene, size, doc}: a suite's cases[], or the job itself as its one case. */
function casesOf(doc) {
  const list = doc.cases ? doc.cases : [doc];
  return list.map(c => {
    const id = c.id || [c.scene && c.scene.name, c.path || "default", c.size && c.size.width + "x" + c.size.height].join("/");
    const parts = id.split("/");
    return {id, scene: parts[0], size: parts[parts.length - 1], doc: c};
  });
}

const psnrOf = m => m.metrics && m.metrics.psnr ? (m.metrics.psnr.identical ? Infinity : m.metrics.psnr.mean) : null;
const meanOf = (m, k) => m.metrics && m.metrics[k] && typeof m.metrics[k].mean === "number" ? m.metrics[k].mean : null;
const familyOf = m => m.name === "user" && m.user_method ? m.user_method.name : m.name;
/* m's counterpart in a baseline case, paired as `aalab compare` pairs them: the same label, else the one
 * method of the same name (ssaa:16 against ssaa:4). */
function baseMethod(baseCase, m) {
  if (!baseCase) return null;
  const same = baseCase.methods.find(x => x.label === m.label);
  if (same) return same;
  const named = baseCase.methods.filter(x => x.name === m.name);
  return named.length === 1 ? named[0] : null;
}

/* What a matrix cell shows: [value, text], value null when there is nothing to show. */
const MATRIX_MODES = {
  over_none: {title: "PSNR dB over none (higher is better)", diverging: true, value: (m, c) => {
    const none = c.doc.methods.find(x => x.label === "none"), p = psnrOf(m), q = none ? psnrOf(none) : null;
    if (p === null || q === null || !isFinite(q)) return null;
    return p === Infinity ? Infinity : p - q;
  }},
  over_baseline: {title: "PSNR dB over the baseline job (higher is better)", diverging: true, value: (m, c, base) => {
    const bm = baseMethod(base && base.get(c.id), m);
    const p = psnrOf(m), q = bm ? psnrOf(bm) : null;
    if (p === null || q === null) return null;
    if (p === Infinity && q === Infinity) return 0;
    return p === Infinity || q === Infinity ? null : p - q;
  }},
  psnr: {title: "PSNR dB (higher is better)", value: m => psnrOf(m)},
  flip: {title: "FLIP mean (lower is better)", lowerBetter: true, value: m => meanOf(m, "flip")},
  gpu_ms: {title: "GPU ms per frame, median (lower is better)", lowerBetter: true,
           value: m => m.gpu_ms && typeof m.gpu_ms.median === "number" ? m.gpu_ms.median : null},
};

function fmtCell(mode, v) {
  if (v === null) return "\u2013";
  if (v === Infinity) return "ident.";
  if (mode === "flip") return v.toFixed(3);
  if (mode === "gpu_ms") return v < 10 ? v.toFixed(2) : v.toFixed(1);
  if (Number(v.toFixed(1)) === 0) return "0.0"; /* -0.03 dB is no change: not "-0.0" */
  return (MATRIX_MODES[mode].diverging && v > 0 ? "+" : "") + v.toFixed(1);
}

/* Blue for better, orange for worse (told apart without red-green), stronger with size; a raw metric
 * from worst (pale) to best (deep). */
function cellColour(mode, v, lo, hi) {
  if (v === null) return "#f1f5f9";
  const spec = MATRIX_MODES[mode];
  if (spec.diverging) {
    if (v === Infinity) return "hsl(210 70% 55%)";
    const a = Math.min(1, Math.abs(v) / Math.max(1e-9, Math.max(Math.abs(lo), Math.abs(hi))));
    return v >= 0 ? `hsl(210 70% ${96 - 40 * a}%)` : `hsl(28 90% ${96 - 40 * a}%)`;
  }
  let t = hi > lo ? (Math.min(v, hi) - lo) / (hi - lo) : 1;
  if (spec.lowerBetter) t = 1 - t;
  return `hsl(210 70% ${96 - 40 * t}%)`;
}

/* The matrix of a job's cases (rows) and methods (columns), filtered by scene, size and family. */
function suiteView(job, doc, base, ui, openCase) {
  const cases = casesOf(doc);
  const labels = [], family = new Map();
  for (const c of cases) for (const m of c.doc.methods) if (!family.has(m.label)) { labels.push(m.label); family.set(m.label, familyOf(m)); }
  const scenes = [...new Set(cases.map(c => c.scene))], sizes = [...new Set(cases.map(c => c.size))];
  const families = [...new Set(family.values())];
  const mode = MATRIX_MODES[ui.mode] && (ui.mode !== "over_baseline" || base) ? ui.mode : "over_none";
  const shown = cases.filter(c => (!ui.scene || c.scene === ui.scene) && (!ui.size || c.size === ui.size));
  const cols = labels.filter(l => !ui.family || family.get(l) === ui.family);

  const select = (key, options, all) => {
    const sel = el("select", {id: "matrix-" + key, onchange: () => { ui[key] = sel.value; ui.redraw(); }},
                   ...[["", all]].concat(options).map(([v, t]) => el("option", {value: v}, t)));
    sel.value = ui[key] || "";
    return sel;
  };
  const modes = Object.entries(MATRIX_MODES).filter(([k]) => k !== "over_baseline" || base).map(([k, v]) => [k, v.title]);
  const modeSel = el("select", {id: "matrix-mode", onchange: () => { ui.mode = modeSel.value; ui.redraw(); }},
                     ...modes.map(([v, t]) => el("option", {value: v}, t)));
  modeSel.value = mode;
  const controls = el("p", {class: "controls"}, "colour and number: ", modeSel, " scene ",
                      select("scene", scenes.map(x => [x, x]), "(all)"), " size ", select("size", sizes.map(x => [x, x]), "(all)"),
                      " family ", select("family", families.map(x => [x, x]), "(all)"));

  const values = [];
  for (const c of shown) for (const m of c.doc.methods) if (cols.includes(m.label)) {
    const v = MATRIX_MODES[mode].value(m, c, base);
    if (v !== null && isFinite(v)) values.push(v);
  }
  const lo = values.length ? Math.min(...values) : 0, hi = values.length ? Math.max(...values) : 1;
  const table = el("table", {id: "matrix", class: "matrix"},
    el("thead", {}, el("tr", {}, el("th", {class: "case-head"}, "case"),
       ...cols.map(l => el("th", {class: "method-head", title: l}, el("span", {}, l))), el("th", {class: "verdict-head"}, "verdict and warnings"))));
  const body = el("tbody", {});
  for (const c of shown) {
    const front = new Set((c.doc.verdict && c.doc.verdict.front) || []);
    const row = el("tr", {class: "case-row", "data-case": c.id});
    row.append(el("th", {class: "case-name"}, el("a", {href: "#case=" + encodeURIComponent(c.id),
      onclick: ev => { ev.preventDefault(); openCase(c.id); }}, c.id)));
    for (const l of cols) {
      const m = c.doc.methods.find(x => x.label === l);
      const v = m ? MATRIX_MODES[mode].value(m, c, base) : null;
      const td = el("td", {class: "cell" + (front.has(l) ? " front" : ""), "data-method": l,
        "data-value": v === null ? "" : String(v), style: "background:" + cellColour(mode, v, lo, hi),
        title: c.id + " \u00b7 " + l + ": " + MATRIX_MODES[mode].title.replace(/ \(.*/, "") + " " + fmtCell(mode, v) +
               (front.has(l) ? " \u00b7 on the front" : ""),
        onclick: () => openCase(c.id, l)}, fmtCell(mode, v));
      row.append(td);
    }
    const warnings = c.doc.warnings || [];
    row.append(el("td", {class: "case-verdict"},
      el("div", {class: "headline"}, c.doc.verdict ? c.doc.verdict.headline : "no verdict"),
      warnings.length ? el("div", {class: "warn-codes"}, ...warnings.map(w => el("span", {class: "warn-code",
        title: typeof w === "string" ? w : w.message + " (what to do: " + w.action + ")"}, "\u26a0 " + (w.code || w)))) : null));
    body.append(row);
  }
  table.append(body);
  const key = el("p", {class: "note"}, "Each cell: " + MATRIX_MODES[mode].title + ". " +
    (MATRIX_MODES[mode].diverging ? "Blue is better, orange worse; " : "Deeper blue is better; ") +
    "a ring marks a method on its case's front (the verdict: no other method is both cheaper and better). " +
    "Click a case or a cell to open the case.");
  return [controls, el("div", {class: "matrix-wrap"}, table), key];
}

/* ----------------------------------------------------------------------------------- the case view */

/* Cost (x: GPU ms median, bars p10-p90) against PSNR (y), one labelled point per method. */
function costChart(c, ui, highlight) {
  const W = 1100, H = 500, frame = {L: 62, R: W - 16, T: 30, B: H - 46};
  const methods = c.doc.methods.filter(m => m.gpu_ms && typeof m.gpu_ms.median === "number" && psnrOf(m) !== null);
  const svg = s("svg", {id: "cost-chart", class: "chart", width: W, height: H, viewBox: `0 0 ${W} ${H}`,
                        role: "img", "aria-label": "GPU time against PSNR for " + c.id});
  if (!methods.length) return el("p", {class: "note"}, "No method has both a GPU time and a PSNR to plot.");
  const finite = methods.map(psnrOf).filter(isFinite);
  const anyIdentical = methods.some(m => psnrOf(m) === Infinity);
  const log = !!ui.logCost && methods.every(m => m.gpu_ms.median > 0);
  const xs = methods.flatMap(m => [m.gpu_ms.median, m.gpu_ms.p10, m.gpu_ms.p90]).filter(v => typeof v === "number" && (!log || v > 0));
  const x = scale(log ? Math.min(...xs) * 0.9 : 0, Math.max(...xs) * 1.05, frame.L, frame.R, log);
  const ylo = finite.length ? Math.min(...finite) - 0.5 : 0, yhi = finite.length ? Math.max(...finite) + 0.5 : 50;
  const band = anyIdentical ? 26 : 0; /* identical to the reference (infinite PSNR): a strip above the plot */
  const y = scale(ylo, yhi, frame.B, frame.T + band, false);
  axes(svg, frame, x, y, "GPU ms per frame (median; bar: p10\u2013p90)" + (log ? ", log scale" : ""), "PSNR dB (mean; higher is better)");
  if (band) svg.append(s("line", {class: "band", x1: frame.L, x2: frame.R, y1: frame.T + band, y2: frame.T + band}),
                       s("text", {class: "tick", x: frame.L + 6, y: frame.T + 12}, "identical to the reference (PSNR infinite)"));
  const py = m => psnrOf(m) === Infinity ? frame.T + band / 2 + 4 : y.scale(psnrOf(m));
  const style = new Map(methods.map((m, k) => [m.label, seriesStyle(k)]));
  const at = new Map(methods.map(m => [m.label, [x.scale(m.gpu_ms.median), py(m)]]));

  /* the front: the staircase through the methods no other beats, cheapest first */
  const front = methods.filter(m => ((c.doc.verdict && c.doc.verdict.front) || []).includes(m.label))
    .sort((a, b) => a.gpu_ms.median - b.gpu_ms.median);
  if (front.length > 1) {
    let d = "";
    front.forEach((m, k) => {
      const [px, pyy] = at.get(m.label);
      d += k ? `H${px}V${pyy}` : `M${px} ${pyy}`;
    });
    svg.append(s("path", {class: "front-line", d}));
  }
  /* method families (verdict.families): a thin line through each family's presets by cost */
  for (const [k, f] of ((c.doc.verdict && c.doc.verdict.families) || []).entries()) {
    const pts = (f.methods || []).map(l => at.get(l)).filter(p => p);
    if (pts.length > 1)
      svg.append(s("polyline", {class: "family-line", "data-family": f.family, points: pts.map(p => p.join(",")).join(" "),
                                stroke: PALETTE[(k + 3) % PALETTE.length]}));
  }
  for (const m of methods) {
    const [px, pyy] = at.get(m.label), st = style.get(m.label);
    if (typeof m.gpu_ms.p10 === "number" && typeof m.gpu_ms.p90 === "number" && (!log || m.gpu_ms.p10 > 0))
      svg.append(s("path", {class: "spread", stroke: st.color, "data-method": m.label,
        d: `M${x.scale(m.gpu_ms.p10)} ${pyy}H${x.scale(m.gpu_ms.p90)}M${x.scale(m.gpu_ms.p10)} ${pyy - 4}v8M${x.scale(m.gpu_ms.p90)} ${pyy - 4}v8`}));
  }
  const labels = placeLabels(methods.map(m => ({x: at.get(m.label)[0], y: at.get(m.label)[1], text: m.label})),
                             {x0: frame.L + 2, x1: frame.R - 2, y0: frame.T + 2, y1: frame.B - 2});
  methods.forEach((m, k) => {
    const l = labels[k], [px, pyy] = at.get(m.label), st = style.get(m.label);
    if (l.leader) svg.append(s("line", {class: "leader", x1: l.leader[0], y1: l.leader[1], x2: l.leader[2], y2: l.leader[3], stroke: st.color}));
  });
  methods.forEach((m, k) => {
    const l = labels[k], [px, pyy] = at.get(m.label), st = style.get(m.label);
    const onFront = front.includes(m);
    const p = psnrOf(m);
    const tip = m.label + ": " + m.gpu_ms.median.toFixed(2) + " ms (p10\u2013p90 " + fmt(m.gpu_ms.p10, 2) + "\u2013" +
      fmt(m.gpu_ms.p90, 2) + "), " + (p === Infinity ? "identical" : p.toFixed(2) + " dB") + (onFront ? ", on the front" : "");
    const g = s("g", {class: "point" + (highlight === m.label ? " highlight" : ""), "data-method": m.label, "data-tip": tip});
    if (onFront) g.append(s("circle", {class: "front-ring", cx: px, cy: pyy, r: 9, stroke: st.color}));
    g.append(marker(st.marker, px, pyy, 5, st.color),
             s("rect", {class: "label-box", x: l.x0, y: l.y0, width: l.x1 - l.x0, height: l.y1 - l.y0, rx: 3, stroke: st.color}),
             s("text", {class: "point-label", x: l.tx, y: l.ty}, m.label));
    svg.append(g);
  });
  const fams = (c.doc.verdict && c.doc.verdict.families) || [];
  const legend = fams.length ? el("ul", {class: "legend family-legend"}, ...fams.map((f, k) => el("li", {"data-family": f.family},
    s("svg", {width: 28, height: 10}, s("line", {x1: 1, x2: 27, y1: 5, y2: 5, stroke: PALETTE[(k + 3) % PALETTE.length], "stroke-width": 2})),
    " " + f.family + ": " + (f.methods || []).join(" \u2192 ") + " (front: " + ((f.front || []).join(", ") || "none") + ")"))) : null;
  return el("figure", {class: "card"}, svg, legend, el("figcaption", {},
    "Each point is one method, named beside it or at the end of its line: left is cheaper, up is closer to the reference. " +
    "Bars span the 10th to 90th percentile of the GPU time over every timed render. Ringed points are on the front, " +
    "joined by the grey staircase" + (fams.length ? "; coloured lines join a family's presets by cost." : ".")));
}

function fmt(v, d) {
  return typeof v === "number" && isFinite(v) ? v.toFixed(d) : "\u2013";
}

/* Each method's GPU time split by pass (median per pass), one stacked bar per method; its passes are
 * named in order after the bar, so that no legend of two dozen pass names has to be matched by colour. */
function passBars(c) {
  const methods = c.doc.methods.filter(m => (m.passes || []).length);
  if (!methods.length) return el("p", {class: "note"}, "No per-pass GPU times.");
  const PASS_COLOURS = ["#0072b2", "#e69f00", "#009e73", "#cc79a7", "#56b4e9", "#d55e00", "#8c564b", "#000000"];
  const W = 1340, rowH = 22, L = 130, R = 480, T = 8;
  const H = T + rowH * methods.length + 40;
  const max = Math.max(...methods.map(m => m.passes.reduce((a, p) => a + (p.gpu_ms || 0), 0)));
  const x = scale(0, max, L, R, false);
  const svg = s("svg", {id: "pass-bars", class: "chart", width: W, height: H, viewBox: `0 0 ${W} ${H}`});
  for (const t of x.ticks)
    svg.append(s("line", {class: "grid", x1: x.scale(t), x2: x.scale(t), y1: T, y2: H - 32}),
               s("text", {class: "tick", x: x.scale(t), y: H - 18, "text-anchor": "middle"}, x.text(t)));
  svg.append(s("text", {class: "axis", x: (L + R) / 2, y: H - 2, "text-anchor": "middle"}, "GPU ms per frame, median of each pass"));
  methods.forEach((m, k) => {
    const y0 = T + k * rowH;
    svg.append(s("text", {class: "tick", x: L - 6, y: y0 + 14, "text-anchor": "end"}, m.label));
    let acc = 0;
    const names = s("text", {class: "pass-names", x: R + 12, y: y0 + 14});
    m.passes.forEach((p, i) => {
      const colour = PASS_COLOURS[i % PASS_COLOURS.length];
      const w = x.scale(acc + (p.gpu_ms || 0)) - x.scale(acc);
      const tip = m.label + " \u00b7 " + p.name + ": " + fmt(p.gpu_ms, 2) + " ms (p10\u2013p90 " + fmt(p.p10, 2) + "\u2013" + fmt(p.p90, 2) + ", n " + p.n + ")";
      svg.append(s("rect", {class: "pass", "data-pass": p.name, x: x.scale(acc), y: y0 + 3, width: Math.max(0, w), height: rowH - 6,
        fill: colour, stroke: "#fff", "stroke-width": 0.5, "data-tip": tip}));
      names.append(s("tspan", {fill: colour, "font-weight": 600}, "\u25a0 "), s("tspan", {"data-tip": tip}, p.name + " " + fmt(p.gpu_ms, 2) + (i + 1 < m.passes.length ? "   " : "")));
      acc += p.gpu_ms || 0;
    });
    svg.append(s("text", {class: "tick total", x: x.scale(acc) + 4, y: y0 + 14}, acc.toFixed(2)), names);
  });
  return el("figure", {class: "card"}, svg,
    el("figcaption", {}, "Which pass costs what: each bar is a method's passes end to end, named in order on the right with their median ms (hover for p10\u2013p90)."));
}

function referenceLine(c) {
  const r = c.doc.reference || {};
  const conv = r.convergence_identical ? "identical" : typeof r.convergence_psnr === "number" ? r.convergence_psnr.toFixed(1) + " dB" : "n/a";
  const samples = r.mode === "auto" ? "auto, up to " + r.samples : r.samples;
  return el("p", {id: "reference-line", class: "reference"}, el("b", {}, "Reference: "),
    samples + " samples per pixel (" + (r.pattern || "") + "), convergence PSNR " + conv + ". ",
    el("span", {class: "explain"}, "Convergence PSNR compares the reference's N/2-sample image with its N-sample image: " +
      "the higher, the less noise is left in it; a method's PSNR near or above it measures the reference's noise, not the method " +
      "(under 40 dB, raise reference.samples)."));
}

/* Every number of the case, one row per method. */
function caseTable(c, baseCase) {
  const none = c.doc.methods.find(m => m.label === "none");
  const head = ["method", "verdict", "GPU ms median", "p10\u2013p90", "MiB", "PSNR dB", "\u0394 none dB", "SSIM", "FLIP", "flicker"];
  if (baseCase) head.push("\u0394 baseline dB", "\u0394 baseline GPU");
  const t = el("table", {id: "case-table", class: "numbers"}, el("thead", {}, el("tr", {}, ...head.map((h, k) => el("th", {class: k > 1 ? "n" : ""}, h)))));
  const vm = new Map(((c.doc.verdict && c.doc.verdict.methods) || []).map(m => [m.label, m]));
  const body = el("tbody", {});
  for (const m of c.doc.methods) {
    const v = vm.get(m.label), p = psnrOf(m), pn = none ? psnrOf(none) : null;
    const place = v ? (v.beaten_by ? "beaten by " + v.beaten_by.method : v.place) : "\u2013";
    const cells = [m.label, place, fmt(m.gpu_ms && m.gpu_ms.median, 2),
      m.gpu_ms ? fmt(m.gpu_ms.p10, 2) + "\u2013" + fmt(m.gpu_ms.p90, 2) : "\u2013",
      fmt(m.memory_bytes / 1048576, 1), p === Infinity ? "identical" : fmt(p, 2),
      p === Infinity ? "\u2013" : pn === null || !isFinite(pn) || p === null ? "\u2013" : (p - pn >= 0 ? "+" : "") + (p - pn).toFixed(2),
      fmt(meanOf(m, "ssim"), 4), fmt(meanOf(m, "flip"), 4), fmt(meanOf(m, "flicker"), 3)];
    if (baseCase) {
      const b = baseMethod(baseCase, m);
      const bp = b ? psnrOf(b) : null;
      cells.push(b && p !== null && bp !== null && isFinite(p) && isFinite(bp) ? (p - bp >= 0 ? "+" : "") + (p - bp).toFixed(2) : "\u2013",
                 b && b.gpu_ms && m.gpu_ms && b.gpu_ms.median > 0 ? ((m.gpu_ms.median / b.gpu_ms.median - 1) * 100 >= 0 ? "+" : "") +
                 ((m.gpu_ms.median / b.gpu_ms.median - 1) * 100).toFixed(0) + "%" : "\u2013");
    }
    body.append(el("tr", {"data-method": m.label, class: v && v.place === "front" ? "on-front" : ""},
      ...cells.map((x, k) => el("td", {class: k > 1 ? "n" : ""}, x))));
  }
  t.append(body);
  return el("div", {class: "table-wrap"}, t);
}

function caseView(job, doc, base, caseId, ui, highlight) {
  const c = casesOf(doc).find(x => x.id === caseId) || casesOf(doc)[0];
  const logBox = el("input", {type: "checkbox", id: "log-cost", onchange: () => { ui.logCost = logBox.checked; ui.redraw(); }});
  logBox.checked = !!ui.logCost;
  const choose = el("select", {id: "case-select", onchange: () => { ui.openCase(choose.value); }},
                    ...casesOf(doc).map(x => el("option", {value: x.id}, x.id)));
  choose.value = c.id;
  const warnings = c.doc.warnings || [];
  const verdict = c.doc.verdict;
  return el("section", {id: "case-view", "data-case": c.id},
    el("h3", {}, "Case ", choose, " ", el("label", {}, logBox, " log cost axis")),
    verdict ? el("p", {class: "front"}, "verdict: " + verdict.headline) : null,
    verdict && verdict.lines && verdict.lines.length ? el("ul", {class: "front-lines"}, ...verdict.lines.map(l => el("li", {}, l))) : null,
    warnings.length ? el("ul", {class: "warnings"}, ...warnings.map(w => typeof w === "string" ? el("li", {class: "warning"}, w)
      : el("li", {class: "warning"}, el("b", {}, w.code), ": " + w.message + " (what to do: " + w.action + ")"))) : null,
    referenceLine(c),
    costChart(c, ui, highlight),
    caseTable(c, base && base.get(c.id)),
    el("h4", {}, "GPU time by pass"), passBars(c));
}
