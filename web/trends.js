/* aalab dashboard: trends, as asv draws them. For a suite and a label (branch=main), one chart per case of
 * the chosen metric over the jobs in submission order (/v1/series), one line per method: eight colours,
 * then dash and marker patterns, each with its legend entry (hover one to pick its line out); a tooltip
 * per point gives the commit, the value and, for GPU time, its p10-p90 spread (the job's summary); a red
 * triangle marks a point whose gate tripped when its job was compared with its baseline (the job's
 * compare.tripped, the gates `aalab compare` judges). */
"use strict";

/* The metric a gate judges: "gpu_ms > +50%" -> gpu_ms; memory gates name memory_bytes. */
function gateMetric(gate) {
  const m = String(gate || "").split(/[ <>]/)[0];
  return m === "memory_bytes" ? "memory" : m;
}

const METRIC_TEXT = {psnr: "PSNR dB", ssim: "SSIM", flip: "FLIP", flicker: "flicker", gpu_ms: "GPU ms per frame", memory: "memory MiB"};

function trendChart(caseId, series, jobs, metric, byId, familyFilter) {
  const W = 660, H = 300, frame = {L: 58, R: W - 112, T: 12, B: H - 66};
  const shown = series.filter(x => !familyFilter || x.method.split(":")[0] === familyFilter);
  const unit = metric === "memory" ? 1 / 1048576 : 1;
  const vals = shown.flatMap(x => x.values).filter(v => v !== null).map(v => v * unit);
  const svg = s("svg", {class: "trend-chart", width: W, height: H, viewBox: `0 0 ${W} ${H}`, "data-case": caseId, "data-metric": metric});
  const x = {ticks: [], text: String, scale: i => frame.L + 16 + (frame.R - frame.L - 32) * (jobs.length > 1 ? i / (jobs.length - 1) : 0.5)};
  const y = scale(vals.length ? Math.min(...vals) : 0, vals.length ? Math.max(...vals) : 1, frame.B, frame.T, false);
  axes(svg, frame, x, y, "", METRIC_TEXT[metric] || metric);
  const tripped = new Map(); /* job index -> [{case, method, gate}] */
  jobs.forEach((j, i) => {
    const full = byId.get(j.id), cmp = full && full.compare;
    const here = cmp && cmp.verdict === "tripped" ? (cmp.tripped || []).filter(t => t.case === caseId) : [];
    if (here.length) tripped.set(i, here);
    const label = String(j.x).length > 14 ? String(j.x).slice(0, 13) + "\u2026" : String(j.x);
    svg.append(s("text", {class: "commit" + (here.length ? " tripped" : ""), x: x.scale(i), y: frame.B + 14, "text-anchor": "end",
                          transform: `rotate(-35 ${x.scale(i)} ${frame.B + 14})`, "data-tip": "job " + j.id + ", commit " + j.x +
                          (here.length ? "; tripped: " + here.map(t => t.method + " " + t.gate).join("; ") : "")}, label));
  });
  const legend = el("ul", {class: "legend trend-legend"});
  const ends = []; /* each series' last point, for the names at the lines' ends */
  shown.forEach((ser) => {
    const k = series.indexOf(ser), st = seriesStyle(k);
    const g = s("g", {class: "series", "data-method": ser.method});
    const pts = ser.values.map((v, i) => v === null ? null : [x.scale(i), y.scale(v * unit), v * unit, i]).filter(p => p);
    if (pts.length > 1)
      g.append(s("polyline", {class: "trend-line", "data-method": ser.method, fill: "none", stroke: st.color, "stroke-width": 2,
                              "stroke-dasharray": st.dash || null, points: pts.map(p => p[0].toFixed(1) + "," + p[1].toFixed(1)).join(" ")}));
    for (const [px, py, v, i] of pts) {
      const entry = (byId.get(jobs[i].id) && byId.get(jobs[i].id).summary || []).find(e => e.label === ser.method && (e.case || caseId) === caseId);
      const spread = metric === "gpu_ms" && entry && typeof entry.gpu_ms_p10 === "number"
        ? " (p10\u2013p90 " + entry.gpu_ms_p10.toFixed(2) + "\u2013" + entry.gpu_ms_p90.toFixed(2) + ", n " + entry.gpu_ms_n + ")" : "";
      const gate = (tripped.get(i) || []).filter(t => t.method === ser.method);
      const tip = ser.method + " \u00b7 commit " + jobs[i].x + " (job " + jobs[i].id + "): " + (metric === "ssim" || metric === "flip"
        ? v.toFixed(4) : v.toFixed(2)) + " " + (METRIC_TEXT[metric] || metric) + spread +
        (gate.length ? " \u00b7 tripped against the baseline: " + gate.map(t => t.gate).join(", ") : "");
      g.append(marker(st.marker, px, py, 3.5, st.color, {"data-tip": tip, class: "trend-point"}));
      for (const t of gate.filter(t => gateMetric(t.gate) === metric))
        g.append(s("circle", {class: "gate-ring", cx: px, cy: py, r: 7, fill: "none", stroke: "#cf222e", "stroke-width": 2}),
                 s("path", {class: "gate-mark", "data-job": jobs[i].id, "data-method": ser.method, "data-gate": t.gate,
          d: `M${px} ${py - 8}l6 -10h-12z`, "data-tip": "gate " + t.gate + " tripped: " + ser.method + " at commit " + jobs[i].x + ": " + t.message}));
    }
    svg.append(g);
    if (pts.length) ends.push({g, method: ser.method, color: st.color, x: pts[pts.length - 1][0], y: pts[pts.length - 1][1]});
    const item = el("li", {"data-method": ser.method, "data-color": st.color, "data-dash": st.dash, "data-marker": st.marker},
                    swatch(st), ser.method);
    item.addEventListener("mouseenter", () => svg.classList.add("focus") || g.classList.add("on"));
    item.addEventListener("mouseleave", () => { svg.classList.remove("focus"); g.classList.remove("on"); });
    legend.append(item);
  });
  endLabels(ends, frame);
  return el("div", {class: "trend card"}, el("h4", {}, caseId + " \u00b7 " + (METRIC_TEXT[metric] || metric)), svg, legend);
}

/* Names each line at its end, as asv and most plotting guides do: the names stand in a column right of the
 * plot, each as near its line's last point as the names above and below it allow (at least LINE px apart,
 * kept within the chart), joined to that point by a thin line in the series' colour. A reader
 * names a line from the chart alone, without matching colours against the legend. */
function endLabels(ends, frame) {
  const low = frame.B + 56; /* names may run below the plot: the commit names there sit further left */
  const LINE = Math.min(13, (low - frame.T) / Math.max(1, ends.length - 1)), x0 = frame.R + 6, xt = frame.R + 22;
  const order = ends.slice().sort((a, b) => a.y - b.y);
  const top = frame.T + LINE / 2, bottom = Math.max(low, top + LINE * (order.length - 1));
  let y = -Infinity;
  for (const e of order) { e.ly = Math.max(e.y, y + LINE, top); y = e.ly; }
  /* past the bottom: pushed back up, keeping the spacing */
  y = Infinity;
  for (const e of order.slice().reverse()) { e.ly = Math.min(e.ly, y - LINE, bottom); y = e.ly; }
  for (const e of order) {
    e.g.append(s("polyline", {class: "end-leader", fill: "none", stroke: e.color, "stroke-width": 1,
                              points: `${e.x},${e.y} ${x0},${e.y} ${xt - 3},${e.ly}`}),
               s("text", {class: "end-label", "data-method": e.method, x: xt, y: e.ly + 4, fill: e.color}, e.method));
  }
}
