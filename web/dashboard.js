/* aalab dashboard: polls aalabd's /v1 endpoints (docs/protocol.md, "HTTP") and draws the job list, the
 * selected job (its verdict against its baseline, the suite view and the case view, suite.js) and the
 * trends (trends.js). Views are redrawn only when what they show changed, so that a poll never closes a
 * menu under the pointer. */
"use strict";

const POLL_MS = 2000;
const results = new Map(); /* a finished job's results.json, by job id: it never changes */
const ui = {
  job: null, caseId: null, highlight: null, mode: "over_none", scene: "", size: "", family: "", logCost: false,
  jobsShown: 8, drawnDetail: "", drawnTrends: "", jobs: [],
};
ui.redraw = () => { ui.drawnDetail = ""; drawDetail(); };
ui.openCase = (id, method) => {
  ui.caseId = id;
  ui.highlight = method || null;
  ui.redraw();
  const v = document.getElementById("case-view");
  if (v) v.scrollIntoView({block: "start"});
};

const labelsOf = spec => Object.entries(spec.labels || {}).map(([k, v]) => k + "=" + v).join(" ");
const methodsOf = spec => (spec.methods || []).map(m => typeof m === "string" ? m : m.name).join(", ");
/* A suite's jobs are compared and plotted together: its name, or the job hash of a job without one. */
const suiteKey = job => job.spec.suite || job.job_hash;

function drawJobs(jobs) {
  const body = document.querySelector("#jobs tbody");
  const newest = jobs.slice().reverse();
  body.replaceChildren(...newest.slice(0, ui.jobsShown).map(job => {
    const pct = job.total ? Math.round(100 * job.done / job.total) : 0;
    const cases = job.spec.cases;
    const verdict = job.compare ? job.compare.verdict : "";
    const row = el("tr", {class: "job" + (job.id === ui.job ? " selected" : ""), "data-job": job.id},
      el("td", {}, job.id), el("td", {class: "state-" + job.state}, job.state),
      el("td", {}, el("span", {class: "bar"}, el("span", {style: "width:" + pct + "%"})), " " + pct + "%"),
      el("td", {}, cases ? "suite " + (job.spec.suite || "") + " (" + cases.length + " cases)" : job.spec.scene),
      el("td", {}, cases ? [...new Set(cases.map(c => c.size))].join(", ") : job.spec.size),
      el("td", {class: "labels"}, labelsOf(job.spec)), el("td", {class: "verdict-" + verdict}, verdict),
      el("td", {class: "methods"}, methodsOf(job.spec)));
    row.addEventListener("click", () => { ui.job = job.id; ui.caseId = null; ui.highlight = null; ui.drawnDetail = ""; refresh(); });
    return row;
  }));
  const more = document.getElementById("more-jobs");
  more.hidden = jobs.length <= ui.jobsShown;
  more.textContent = "show all " + jobs.length + " jobs";
}
document.getElementById("more-jobs").addEventListener("click", () => { ui.jobsShown = 1e9; drawJobs(ui.jobs); });

async function loadResults(id) {
  if (results.has(id)) return results.get(id);
  results.set(id, null); /* asked once */
  try {
    const r = await fetch("v1/jobs/" + id + "/results.json");
    if (r.ok) results.set(id, await r.json());
  } catch (e) { /* the view says it has no results */ }
  ui.drawnDetail = "";
  drawDetail();
  return results.get(id);
}

function verdictPanel(job) {
  const c = job.compare;
  const p = el("p", {id: "verdict", class: "verdict-" + c.verdict},
               "against baseline " + c.baseline + (c.job ? " (job " + c.job + ")" : "") + ": " + c.verdict);
  if (c.counts) p.append(", " + c.counts.tripped + " of " + c.counts.gates + " gates tripped");
  if (c.message) p.append(": " + c.message);
  const list = el("ul", {class: "tripped"}, ...(c.tripped || []).map(t => el("li", {}, t.case + " \u00b7 " + t.method + ": " + t.message)));
  return [p, list];
}

function drawDetail() {
  const d = document.getElementById("detail");
  const job = ui.jobs.find(j => j.id === ui.job);
  if (!job) { d.replaceChildren(); ui.drawnDetail = ""; return; }
  const doc = results.get(job.id);
  const baseId = job.compare && job.compare.job;
  const baseDoc = baseId ? results.get(baseId) : null;
  const key = [job.id, job.state, job.done, !!doc, !!baseDoc].join("|");
  if (key === ui.drawnDetail) return;
  ui.drawnDetail = key;
  const parts = [el("h2", {}, (job.spec.cases ? "suite " + (job.spec.suite || "") : job.spec.scene) + " \u00b7 job " + job.id + " \u00b7 " + job.state)];
  if (labelsOf(job.spec)) parts.push(el("p", {class: "labels"}, "labels: " + labelsOf(job.spec)));
  if (job.error) parts.push(el("p", {class: "state-failed"}, (job.error.path ? job.error.path + ": " : "") + job.error.message));
  if (job.compare) parts.push(...verdictPanel(job));
  if (job.state === "done") {
    if (doc === undefined) loadResults(job.id);
    if (baseId && baseDoc === undefined) loadResults(baseId);
    if (doc) {
      const base = baseDoc ? new Map(casesOf(baseDoc).map(c => [c.id, c.doc])) : null;
      if (!casesOf(doc).some(c => c.id === ui.caseId)) ui.caseId = casesOf(doc)[0].id;
      parts.push(el("h3", {}, doc.cases ? "Cases \u00d7 methods" : "Methods"), ...suiteView(job, doc, base, ui, ui.openCase),
                 caseView(job, doc, base, ui.caseId, ui, ui.highlight));
    } else {
      parts.push(el("p", {class: "note"}, doc === null ? "results.json could not be read" : "loading results.json\u2026"));
    }
    parts.push(el("p", {}, el("a", {href: "v1/jobs/" + job.id + "/report.html"}, "report"), " \u00b7 ",
                    el("a", {href: "v1/jobs/" + job.id + "/results.json"}, "results.json"),
                    baseId ? [" \u00b7 ", el("a", {href: "v1/jobs/" + job.id + "/compare?baseline=" + encodeURIComponent(baseId)}, "comparison (JSON)")] : null));
  }
  d.replaceChildren(...parts);
}

/* Fills a select, keeping the user's choice; before any choice, `preferred` when it is offered. */
function setOptions(select, options, preferred) {
  const old = select.dataset.filled ? select.value : preferred;
  select.replaceChildren(...options.map(([value, text]) => el("option", {value}, text)));
  select.dataset.filled = "1";
  if (options.some(([v]) => v === old)) select.value = old;
}

async function drawTrends(jobs) {
  const done = jobs.filter(j => j.state === "done");
  const suiteSel = document.getElementById("trend-suite"), labelSel = document.getElementById("trend-label");
  /* the most recent first; the selector opens on the most recent named suite (a one-case job without a
   * suite name has a trend of its own, but is rarely what a trend is opened for) */
  const suites = [...new Set(done.slice().reverse().map(suiteKey))];
  const named = suites.find(k => !k.startsWith("sha256:"));
  setOptions(suiteSel, suites.map(k => [k, k.startsWith("sha256:") ? "job " + k.slice(7, 19) : k]), named || suites[0]);
  const inSuite = done.filter(j => suiteKey(j) === suiteSel.value);
  /* labels that several jobs share (the commit label differs per job, so it is the x axis instead) */
  const labels = [...new Set(inSuite.flatMap(j => Object.entries(j.spec.labels || {})
    .filter(([k]) => k !== "commit").map(([k, v]) => k + "=" + v)))];
  setOptions(labelSel, [["", "(any)"], ...labels.map(l => [l, l])], "branch=main");
  const charts = document.getElementById("trend-charts");
  if (!suiteSel.value) { charts.replaceChildren(el("p", {}, "no finished jobs yet")); ui.drawnTrends = ""; return; }
  const metric = document.getElementById("trend-metric").value, fam = document.getElementById("trend-family").value;
  const key = [suiteSel.value, labelSel.value, metric, fam, inSuite.map(j => j.id + (j.compare ? j.compare.verdict : "")).join(",")].join("|");
  if (key === ui.drawnTrends) return;
  const q = "v1/series?suite=" + encodeURIComponent(suiteSel.value) + "&metric=" + metric +
            (labelSel.value ? "&label=" + encodeURIComponent(labelSel.value) : "");
  const data = await (await fetch(q + "&t=" + Date.now())).json();
  const byCase = new Map();
  for (const x of data.series || []) {
    if (!byCase.has(x.case)) byCase.set(x.case, []);
    byCase.get(x.case).push(x);
  }
  const families = [...new Set((data.series || []).map(x => x.method.split(":")[0]))];
  setOptions(document.getElementById("trend-family"), [["", "(all)"], ...families.map(f => [f, f])], "");
  const byId = new Map(jobs.map(j => [j.id, j]));
  charts.replaceChildren(...[...byCase].map(([c, list]) => trendChart(c, list, data.jobs, metric, byId, fam)));
  ui.drawnTrends = key;
}
for (const id of ["trend-suite", "trend-label", "trend-metric", "trend-family"])
  document.getElementById(id).addEventListener("change", () => { ui.drawnTrends = ""; drawTrends(ui.jobs); });

async function refresh() {
  try {
    const r = await fetch("v1/jobs?t=" + Date.now());
    const jobs = ui.jobs = (await r.json()).jobs;
    if (!ui.job || !jobs.some(j => j.id === ui.job)) {
      const done = jobs.filter(j => j.state === "done");
      ui.job = done.length ? done[done.length - 1].id : (jobs.length ? jobs[jobs.length - 1].id : null);
    }
    drawJobs(jobs);
    drawDetail();
    await drawTrends(jobs);
    document.getElementById("status").textContent = jobs.length + " jobs \u00b7 updated " + new Date().toLocaleTimeString();
  } catch (e) {
    document.getElementById("status").textContent = "cannot reach aalabd: " + e;
  }
}
attachTooltip(document.body);
refresh();
setInterval(refresh, POLL_MS);
