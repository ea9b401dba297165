#!/usr/bin/python3
"""The dashboard in a real browser (headless Debian chromium over the DevTools protocol, cdp.py), served by
aalabd after a single-case job and three labelled jobs of a suite (the third with ssaa:16 standing in for
ssaa:4, which trips the memory gate against the second). Checks from the DOM at 1280 px:
- the trend selector opens on the most recent suite (the newest job is a one-case job without a suite name);
- the matrix: one row per case, one cell per method, each cell's value and text the PSNR over `none` of
  results.json, the front ringed exactly, each case's verdict headline and warning codes shown; the scene,
  size and family filters keep exactly their rows or columns; over the baseline, each cell is the PSNR
  change against the method paired as `aalab compare` pairs it (ssaa:16 with ssaa:4); a click on a cell
  opens that case;
- the case view: every point's x is its GPU ms median on one scale, linear or (with "log cost axis")
  log10, each p10-p90 bar spans exactly its p10 to p90, ticks sit at their values; the reference line
  names the reference's samples and convergence; the per-pass bars have each method's passes in order, end
  to end, widths in proportion to results.json's per-pass times;
- the case view: one point per method (and a chart of 14 crowded methods drawn by the page's code, with
  a method family: its line and legend entry; none without verdict.families); no two labels overlap, no label covers a point, each label is
  nearer its own point than any other or joined to it by a leader line; axis ticks are round (1, 2 or 5
  times a power of ten, evenly stepped);
- every chart fits its card and nothing is wider than the page;
- trends: every series has one legend entry, and within a chart no two entries look alike (colour, dash,
  marker); every line is named at its end, joined to its last point, no two names overlapping; the gate
  markers on the memory trend are exactly the memory gates `aalab compare` trips for the third job against
  the second; every GPU-time point's tooltip names its method, commit and job, its median
  and its p10-p90 spread and count as results.json has them, and a pointer over a point shows it.
Skipped (77) only when chromium is not installed. With --shots DIR it keeps screenshots of each view
(docs/img/dashboard-*.png are these: --shots docs/img)."""
import json
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cdp
from daemon_lib import AALAB, Daemon, check, finish, http_get

WIDTH = 1280


def submit(d, args):
    r = subprocess.run([AALAB, "submit", "--watch", "--quiet", "--connect", "unix:" + d.socket] + args,
                       capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        raise SystemExit("a job failed")
    return r.stdout.split()[0]


def main():
    if not cdp.find_chromium():
        print("SKIP: chromium not installed (scripts/install-deps.sh)")
        sys.exit(77)
    shots = sys.argv[sys.argv.index("--shots") + 1] if "--shots" in sys.argv else None
    d = Daemon(http=True)
    b = None
    try:
        suite = {"suite": "dash", "scenes": ["thin-wires", "hard-edges"], "sizes": ["64x36", "48x27"], "frames": 2,
                 "reference": {"samples": 4}, "timing": {"repeat": 3}, "keep_frames": False,
                 "methods": ["none", "ssaa:4", "msaa:4", "fxaa", "smaa", "taa", "gbaa", "copy", "floor"]}
        path = os.path.join(d.tmp, "suite.json")
        slow = os.path.join(d.tmp, "slow.json")
        json.dump(suite, open(path, "w"))
        suite["methods"][1] = "ssaa:16"
        json.dump(suite, open(slow, "w"))
        ids = [submit(d, [path, "--label", "commit=c1", "--label", "branch=main", "--baseline", "latest:branch=main"]),
               submit(d, [path, "--label", "commit=c2", "--label", "branch=main", "--baseline", "latest:branch=main"]),
               submit(d, [slow, "--label", "commit=c3-slow", "--label", "branch=main", "--baseline", "latest:branch=main"])]
        # the newest job is a one-case job without a suite name: the trends still open on the suite
        submit(d, ["--scene", "thin-wires", "--methods", "none,fxaa", "--frames", "2", "--size", "64x36",
                   "--reference-samples", "4"])
        cmp = subprocess.run([AALAB, "compare", ids[1], ids[2], "--json", "--connect", "unix:" + d.socket],
                             capture_output=True, text=True, timeout=120)
        check(cmp.returncode == 1, "aalab compare: the slow job trips a gate against the one before")
        tripped = json.loads(cmp.stdout)["tripped"]
        every = [json.loads(http_get(d.http_port, "/v1/jobs/%s/results.json" % i)[2]) for i in ids]
        results, before = every[2], every[1]

        b = cdp.Chromium(WIDTH, 900)
        b.navigate("http://127.0.0.1:%d/" % d.http_port)
        check(b.wait_for("!!document.querySelector('#matrix') && !!document.querySelector('#cost-chart') && "
                         "document.querySelectorAll('.trend-chart').length > 0", 60), "the dashboard draws its views")
        check(b.eval("document.getElementById('trend-suite').value") == "dash",
              "the trend selector opens on the most recent suite, though the newest job is a one-case job")
        b.eval("document.querySelector('#jobs tr[data-job=\"%s\"]').click()" % ids[2])
        check(b.wait_for("document.querySelectorAll('#matrix tr.case-row').length === %d" % len(results["cases"]), 20),
              "a click on the suite's job shows its matrix")

        # ------------------------------------------------------------------ the matrix against results.json
        cells = b.eval("""[...document.querySelectorAll('#matrix tr.case-row')].map(r => ({case: r.dataset.case,
            headline: r.querySelector('.headline').textContent,
            warnings: [...r.querySelectorAll('.warn-code')].map(w => w.textContent.replace(/^\\S+ /, '')),
            cells: [...r.querySelectorAll('td.cell')].map(c => ({method: c.dataset.method, value: c.dataset.value,
                     text: c.textContent, front: c.classList.contains('front')}))}))""")
        check([r["case"] for r in cells] == [c["id"] for c in results["cases"]], "the matrix has a row per case")
        bad = []
        for row, case in zip(cells, results["cases"]):
            by = {m["label"]: m for m in case["methods"]}
            none = by["none"]["metrics"]["psnr"]["mean"]
            if [c["method"] for c in row["cells"]] != [m["label"] for m in case["methods"]]:
                bad.append((case["id"], "methods", [c["method"] for c in row["cells"]]))
            for c in row["cells"]:
                p = by[c["method"]]["metrics"]["psnr"]
                want = math.inf if p["identical"] else p["mean"] - none
                got = float(c["value"]) if c["value"] not in ("", "Infinity") else (math.inf if c["value"] else None)
                text = "ident." if want == math.inf else "%+.1f" % want if round(want, 1) != 0 else "%.1f" % abs(want)
                if got is None or (want != math.inf and abs(got - want) > 1e-9) or c["text"].lstrip("+-") != text.lstrip("+-") \
                        or c["text"] in ("-0.0", "+0.0"):
                    bad.append((case["id"], c["method"], c["value"], c["text"], want))
                if c["front"] != (c["method"] in case["verdict"]["front"]):
                    bad.append((case["id"], c["method"], "front", c["front"]))
            if row["headline"] != case["verdict"]["headline"]:
                bad.append((case["id"], "headline", row["headline"]))
            if row["warnings"] != [w["code"] for w in case.get("warnings", [])]:
                bad.append((case["id"], "warnings", row["warnings"]))
        check(not bad, "each matrix cell is results.json's PSNR over none, the front ringed, verdict and warnings "
              "per case: %s" % bad[:4])

        fmt = b.eval("[-0.03, 0.04, 0.06, -0.06].map(v => fmtCell('over_none', v))")
        check(fmt == ["0.0", "0.0", "+0.1", "-0.1"], "a change that rounds to 0.0 dB is written 0.0, never -0.0: %s" % fmt)

        # ------------------------------------------------------------ filters: scene, size, method family
        row_ids = "[...document.querySelectorAll('#matrix tr.case-row')].map(r => r.dataset.case)"
        col_ids = "[...document.querySelectorAll('#matrix tr.case-row')].map(r => [...r.querySelectorAll('td.cell')].map(c => c.dataset.method))"
        pick(b, "matrix-scene", "hard-edges")
        want = [c["id"] for c in results["cases"] if c["id"].split("/")[0] == "hard-edges"]
        check(b.eval(row_ids) == want and 0 < len(want) < len(results["cases"]),
              "the scene filter keeps that scene's cases: %s" % b.eval(row_ids))
        pick(b, "matrix-scene", "")
        pick(b, "matrix-size", "48x27")
        want = [c["id"] for c in results["cases"] if c["id"].split("/")[-1] == "48x27"]
        check(b.eval(row_ids) == want and 0 < len(want) < len(results["cases"]),
              "the size filter keeps that size's cases: %s" % b.eval(row_ids))
        pick(b, "matrix-size", "")
        pick(b, "matrix-family", "ssaa")
        cols = b.eval(col_ids)
        want = [[m["label"] for m in c["methods"] if m["name"] == "ssaa"] for c in results["cases"]]
        check(cols == want and all(w == ["ssaa:16"] for w in want), "the family filter keeps that family's columns: %s" % cols[:2])
        pick(b, "matrix-family", "")
        check(len(b.eval(row_ids)) == len(results["cases"]), "with no filter every case is back")

        # ------------------------------------------------- the matrix over the baseline job, paired as compare pairs
        pick(b, "matrix-mode", "over_baseline")
        cells = b.eval("[...document.querySelectorAll('#matrix tr.case-row')].map(r => [r.dataset.case, "
                       "[...r.querySelectorAll('td.cell')].map(c => [c.dataset.method, c.dataset.value])])")
        bad = []
        base_cases = {c["id"]: c for c in before["cases"]}
        for (cid, row), case in zip(cells, results["cases"]):
            for label, value in row:
                m = next(x for x in case["methods"] if x["label"] == label)
                same = [x for x in base_cases[cid]["methods"] if x["label"] == label] or \
                       [x for x in base_cases[cid]["methods"] if x["name"] == m["name"]]
                p, q = m["metrics"]["psnr"], same[0]["metrics"]["psnr"]
                want = 0.0 if p["identical"] and q["identical"] else None if p["identical"] or q["identical"] else p["mean"] - q["mean"]
                got = None if value == "" else float(value)
                if (want is None) != (got is None) or (want is not None and abs(got - want) > 1e-9):
                    bad.append((cid, label, got, want))
        check(not bad and cells and any(l == "ssaa:16" for _, row in cells for l, _ in row),
              "over the baseline, each cell is PSNR minus the baseline's (ssaa:16 paired with ssaa:4): %s" % bad[:4])
        pick(b, "matrix-mode", "over_none")

        # -------------------------------------------------------------------- a click opens the case
        second = results["cases"][1]["id"]
        b.eval("document.querySelector('#matrix tr.case-row[data-case=\"%s\"] td.cell[data-method=\"fxaa\"]').click()" % second)
        check(b.wait_for("document.querySelector('#case-view').dataset.case === %s" % json.dumps(second), 10),
              "a click on a cell opens its case")
        if shots:
            shoot(b, "#matrix", os.path.join(shots, "dashboard-matrix.png"))
            shoot(b, "#cost-chart", os.path.join(shots, "dashboard-cost-chart.png"))

        # ---------------------------------------------------------- the case view's geometry
        geo = b.eval(GEOMETRY % "document.querySelector('#case-view #cost-chart')")
        case = results["cases"][1]
        check(sorted(p["method"] for p in geo["points"]) == sorted(m["label"] for m in case["methods"]),
              "the case view has one point per method")
        check_labels(geo)
        for axis in ("xticks", "yticks"):
            check(round_ticks(geo[axis]), "%s are round and evenly stepped: %s" % (axis, geo[axis]))
        check_cost_axis(b, case, log=False)
        # the reference line: its samples and convergence, as results.json says
        ref = case["reference"]
        line = b.eval("document.getElementById('reference-line').textContent")
        conv = "identical" if ref.get("convergence_identical") else "%.1f dB" % ref["convergence_psnr"]
        check(("%s samples per pixel" % ref["samples"]) in line and ("convergence PSNR " + conv) in line and "N/2-sample" in line,
              "the case view names the reference's samples and convergence (%s) and explains it" % conv)
        # the log cost axis: x is linear in log10(GPU ms), ticks 1, 2 or 5 times a power of ten
        b.eval("(() => { const c = document.getElementById('log-cost'); c.checked = true; c.dispatchEvent(new Event('change')); })()")
        check(b.wait_for("/log scale/.test(document.querySelector('#cost-chart').textContent)", 10), "'log cost axis' redraws the chart")
        check_cost_axis(b, case, log=True)
        check_labels(b.eval(GEOMETRY % "document.querySelector('#case-view #cost-chart')"), "log axis: ")
        b.eval("(() => { const c = document.getElementById('log-cost'); c.checked = false; c.dispatchEvent(new Event('change')); })()")
        b.wait_for("!/log scale/.test(document.querySelector('#cost-chart').textContent)", 10)
        # GPU time by pass: one bar per method, a segment per pass of results.json, end to end
        bars = b.eval("""[...document.querySelectorAll('#pass-bars')].flatMap(svg => {
            const out = {}; for (const r of svg.querySelectorAll('rect.pass')) {
              const m = r.dataset.tip.split(' \u00b7 ')[0]; (out[m] = out[m] || []).push([r.dataset.pass, +r.getAttribute('x'), +r.getAttribute('width')]); }
            return [out]; })[0]""")
        bad = []
        for m in case["methods"]:
            segs = bars.get(m["label"], [])
            if [s_[0] for s_ in segs] != [p["name"] for p in m.get("passes", [])]:
                bad.append((m["label"], [s_[0] for s_ in segs]))
            elif any(abs(segs[k][1] + segs[k][2] - segs[k + 1][1]) > 0.01 for k in range(len(segs) - 1)):
                bad.append((m["label"], "not end to end"))
            elif segs and m["passes"][0]["gpu_ms"] > 0:
                per_ms = segs[0][2] / m["passes"][0]["gpu_ms"]
                if any(abs(s_[2] - p["gpu_ms"] * per_ms) > 0.05 for s_, p in zip(segs, m["passes"])):
                    bad.append((m["label"], "widths"))
        check(not bad and len(bars) == sum(1 for m in case["methods"] if m.get("passes")),
              "GPU time by pass: a bar per method, its passes in order end to end, widths in proportion: %s" % bad[:3])
        # the same chart of 14 methods crowded within 0.7 ms and 0.4 dB, drawn by the page's own code
        crowd = b.eval(CROWD)
        check(crowd == 14, "a crowded chart of 14 methods is drawn")
        check_labels(b.eval(GEOMETRY % "document.querySelector('#crowd svg')"), "crowded: ")
        fam = b.eval("[...document.querySelectorAll('#crowd polyline.family-line')].map(l => [l.dataset.family,"
                     " l.getAttribute('points').split(' ').length, document.querySelectorAll('#crowd .family-legend li').length])")
        real = b.eval("document.querySelectorAll('#case-view .family-line, #case-view .family-legend').length")
        check(fam == [["fxaa", 2, 1]] and real == 0, "verdict.families draws a line per family through its presets, "
              "with a legend entry; a verdict without families draws none: %s, %s" % (fam, real))

        # -------------------------------------------------------------------------- fits at 1280 px
        fit = b.eval("""(() => {
            const out = [];
            for (const c of document.querySelectorAll('svg.chart, svg.trend-chart, table.matrix, #case-table')) {
              const card = c.closest('.card, .matrix-wrap, .table-wrap, section');
              const r = c.getBoundingClientRect(), p = card.getBoundingClientRect();
              if (r.right > p.right + 0.5 || r.left < p.left - 0.5) out.push([c.id || c.getAttribute('class'), r.right, p.right]);
            }
            return {out, page: document.documentElement.scrollWidth};
        })()""")
        check(not fit["out"] and fit["page"] <= WIDTH, "every chart and table fits its card at %d px (page %s px): %s"
              % (WIDTH, fit["page"], fit["out"][:3]))

        # ------------------------------------------------------------------- trends: legends, markers
        b.eval("(() => { const m = document.getElementById('trend-metric'); m.value = 'memory';"
               " m.dispatchEvent(new Event('change')); })()")
        check(b.wait_for("[...document.querySelectorAll('.trend-chart')].every(s => s.dataset.metric === 'memory')", 20),
              "the memory trends are drawn")
        trends = b.eval("""[...document.querySelectorAll('.trend')].map(t => ({
            case: t.querySelector('svg').dataset.case,
            series: [...t.querySelectorAll('g.series')].map(g => g.dataset.method),
            legend: [...t.querySelectorAll('.trend-legend li')].map(l => [l.dataset.method, l.dataset.color, l.dataset.dash, l.dataset.marker]),
            marks: [...t.querySelectorAll('.gate-mark')].map(m => [m.dataset.job, m.dataset.method, m.dataset.gate])}))""")
        ok = all(sorted(t["series"]) == sorted(l[0] for l in t["legend"]) and
                 len({tuple(l[1:]) for l in t["legend"]}) == len(t["legend"]) for t in trends)
        check(ok and trends and all(len(t["series"]) == 10 for t in trends),
              "every series has a legend entry, each of its own colour and pattern (10 series per chart)")
        ends = b.eval("""[...document.querySelectorAll('.trend svg')].map(svg => {
            const box = e => { const r = e.getBBox(); return [r.x, r.y, r.x + r.width, r.y + r.height]; };
            const vb = svg.viewBox.baseVal;
            return {series: [...svg.querySelectorAll('g.series')].map(g => {
                const pts = [...g.querySelectorAll('.trend-point')].map(p => { const b = box(p); return [(b[0] + b[2]) / 2, (b[1] + b[3]) / 2]; });
                const names = [...g.querySelectorAll('.end-label')];
                const lead = g.querySelector('.end-leader');
                return {method: g.dataset.method, last: pts[pts.length - 1], names: names.map(n => n.textContent),
                        box: names.length ? box(names[0]) : null,
                        leader: lead ? lead.getAttribute('points').split(' ').map(p => p.split(',').map(Number)) : null}; }),
                    size: [vb.width, vb.height]}; })""")
        bad = []
        for chart in ends:
            ser = chart["series"]
            for s_ in ser:
                if s_["names"] != [s_["method"]] or not s_["leader"]:
                    bad.append((s_["method"], "named", s_["names"]))
                    continue
                a, z, bx = s_["leader"][0], s_["leader"][-1], s_["box"]
                if math.hypot(a[0] - s_["last"][0], a[1] - s_["last"][1]) > 1 or not (bx[1] - 1 <= z[1] <= bx[3] + 1 and abs(z[0] - bx[0]) < 6):
                    bad.append((s_["method"], "leader", a, z, bx))
                if bx[0] < 0 or bx[1] < 0 or bx[2] > chart["size"][0] or bx[3] > chart["size"][1]:
                    bad.append((s_["method"], "outside", bx))
            for i, p in enumerate(ser):
                for q in ser[i + 1:]:
                    if p["box"] and q["box"] and p["box"][0] < q["box"][2] and q["box"][0] < p["box"][2] and \
                            p["box"][1] < q["box"][3] - 0.5 and q["box"][1] < p["box"][3] - 0.5:
                        bad.append((p["method"], q["method"], "overlap"))
        check(ends and not bad, "each line is named at its end (one name, joined to its last point by a leader), "
              "no two names overlap, all within the chart: %s" % bad[:4])
        marks = sorted((t["case"], m[1], m[2]) for t in trends for m in t["marks"] if m[0] == ids[2])
        want = sorted((t["case"], t["method"], t["gate"]) for t in tripped if t["gate"].startswith("memory"))
        check(marks == want and want, "the memory trend marks exactly the memory gates aalab compare trips: %s" % marks)
        check(all(m[0] == ids[2] for t in trends for m in t["marks"]), "and marks no other job")
        rings = b.eval("""[...document.querySelectorAll('.trend g.series')].filter(g => g.querySelector('.gate-mark')).map(g => {
            const pts = [...g.querySelectorAll('.trend-point')].map(p => { const r = p.getBBox(); return [r.x + r.width / 2, r.y + r.height / 2]; });
            return [g.querySelectorAll('.gate-mark').length, [...g.querySelectorAll('.gate-ring')].map(r =>
                pts.some(p => Math.hypot(p[0] - r.cx.baseVal.value, p[1] - r.cy.baseVal.value) < 1))]; })""")
        check(rings and all(n == len(r) and all(r) for n, r in rings),
              "each gate marker rings the very point whose gate tripped: %s" % rings)
        if shots:
            shoot(b, ".trend", os.path.join(shots, "dashboard-trend-memory.png"))

        # ------------------------------------------------- trend tooltips: commit, value and spread
        pick(b, "trend-metric", "gpu_ms")
        check(b.wait_for("[...document.querySelectorAll('.trend-chart')].every(s => s.dataset.metric === 'gpu_ms')", 20),
              "the GPU time trends are drawn")
        tips = b.eval("[...document.querySelectorAll('.trend')].flatMap(t => [...t.querySelectorAll('g.series')].map(g => "
                      "[t.querySelector('svg').dataset.case, g.dataset.method, [...g.querySelectorAll('.trend-point')].map(p => p.dataset.tip)]))")
        commits = ["c1", "c2", "c3-slow"]
        bad = []
        for cid, method, ptips in tips:
            want = []
            for k, doc in enumerate(every):
                case_ = next(c for c in doc["cases"] if c["id"] == cid)
                m = next((x for x in case_["methods"] if x["label"] == method), None)
                if m:
                    g = m["gpu_ms"]
                    want.append("%s \u00b7 commit %s (job %s): %.2f GPU ms per frame (p10\u2013p90 %.2f\u2013%.2f, n %d)"
                                % (method, commits[k], ids[k], g["median"], g["p10"], g["p90"], g["n"]))
            if [x.split(" \u00b7 tripped")[0] for x in ptips] != want:
                bad.append((cid, method, ptips[:1], want[:1]))
        check(tips and not bad, "each trend point's tooltip names its method, commit and job, its median GPU ms and "
              "p10-p90 spread as results.json has them: %s" % bad[:2])
        # and a pointer over a point shows that text: the point is found again and the pointer moved to it
        # (half a pixel aside each time, so that it is a move) until the tooltip shows, for up to 10 s, since
        # a poll may redraw the chart between finding the point and the move
        tip_shown = "(() => { const t = document.getElementById('tooltip'); return t && t.style.display === 'block' ? t.textContent : null; })()"
        for attempt in range(20):
            at = b.eval("""(() => { document.querySelector('.trend').scrollIntoView({block: 'center'});
                for (const p of document.querySelectorAll('.trend .trend-point')) {  /* one no other point covers */
                  const r = p.getBoundingClientRect(), x = r.x + r.width / 2, y = r.y + r.height / 2;
                  if (document.elementFromPoint(x, y) === p) return [x, y, p.dataset.tip]; }
                return [0, 0, 'no uncovered point']; })()""")
            b.mouse("mouseMoved", at[0] + 0.5 * (attempt % 2), at[1])
            if b.wait_for(tip_shown, 0.5):
                break
        shown = b.eval(tip_shown)
        check(shown == at[2], "hovering a trend point shows its tooltip: %s" % shown)
    finally:
        if b:
            b.close()
        status = d.stop()
        check(status == 0, "aalabd exits 0")
        d.cleanup()
    finish()


GEOMETRY = """(() => {
    const svg = %s;
    const box = e => { const r = e.getBBox(); return [r.x, r.y, r.x + r.width, r.y + r.height]; };
    return {points: [...svg.querySelectorAll('g.point')].map(g => {
              const m = g.querySelector('circle:not(.front-ring), rect:not(.label-box), path');
              return {method: g.dataset.method, dot: box(m), label: box(g.querySelector('.label-box')),
                      text: box(g.querySelector('.point-label')), textContent: g.querySelector('.point-label').textContent};}),
            leaders: [...svg.querySelectorAll('line.leader')].map(l => [+l.getAttribute('x1'), +l.getAttribute('y1'),
                      +l.getAttribute('x2'), +l.getAttribute('y2')]),
            xticks: [...svg.querySelectorAll('.x-tick')].map(t => t.textContent),
            yticks: [...svg.querySelectorAll('.y-tick')].map(t => t.textContent)};
})()"""

CROWD = """(() => {
    const names = ['none', 'ssaa:4', 'msaa:4', 'fxaa', 'smaa', 'taa', 'gbaa', 'asaa', 't2msaa:0.125', 'rsaa:8', 'copy',
                   'floor', 'fxaa-cs', 'taa-sobel'];
    const methods = names.map((label, k) => ({label, gpu_ms: {median: 1.5 + 0.05 * k, p10: 1.4, p90: 1.9},
                                               metrics: {psnr: {mean: 21 + 0.1 * (k % 5), identical: false}}}));
    const families = [{family: 'fxaa', methods: ['fxaa', 'fxaa-cs'], front: ['fxaa']}];
    const fig = costChart({id: 'crowd', doc: {methods, verdict: {front: ['none'], families}}}, {}, null);
    fig.id = 'crowd';
    document.body.append(fig);
    return fig.querySelectorAll('g.point').length;
})()"""


def pick(b, select, value):
    b.eval("(() => { const s = document.getElementById('%s'); s.value = %s; s.dispatchEvent(new Event('change')); })()"
           % (select, json.dumps(value)))


def check_cost_axis(b, case, log):
    """The cost chart's x axis: each point's x linear in GPU ms median (or its log10), each p10-p90 bar from
    the p10 to the p90 on the same scale, and round ticks (1, 2 or 5 times a power of ten)."""
    what = "log " if log else ""
    got = b.eval("""(() => { const svg = document.querySelector('#case-view #cost-chart');
        const mid = e => { const r = e.getBBox(); return r.x + r.width / 2; };
        return {points: Object.fromEntries([...svg.querySelectorAll('g.point')].map(g => [g.dataset.method,
                  mid(g.querySelector('circle:not(.front-ring), rect:not(.label-box), path'))])),
                spreads: Object.fromEntries([...svg.querySelectorAll('path.spread')].map(p => { const r = p.getBBox();
                  return [p.dataset.method, [r.x, r.x + r.width]]; })),
                ticks: [...svg.querySelectorAll('.x-tick')].map(t => [+t.getAttribute('x'), t.textContent])}; })()""")
    f = (lambda v: math.log10(v) if v > 0 else math.nan) if log else (lambda v: v)
    ms = {m["label"]: m["gpu_ms"] for m in case["methods"]}
    lo, hi = min(ms, key=lambda k: ms[k]["median"]), max(ms, key=lambda k: ms[k]["median"])
    per = (got["points"][hi] - got["points"][lo]) / (f(ms[hi]["median"]) - f(ms[lo]["median"]))
    px = lambda v: got["points"][lo] + per * (f(v) - f(ms[lo]["median"]))
    off = [(k, round(got["points"][k] - px(ms[k]["median"]), 2)) for k in got["points"] if abs(got["points"][k] - px(ms[k]["median"])) > 0.5]
    check(not off and len(got["points"]) == len(ms), what + "cost axis: every point's x is its GPU ms median on one scale: %s" % off)
    bars = [(k, got["spreads"].get(k)) for k in ms if not got["spreads"].get(k) or
            abs(got["spreads"][k][0] - px(ms[k]["p10"])) > 0.5 or abs(got["spreads"][k][1] - px(ms[k]["p90"])) > 0.5]
    check(not bars, what + "cost axis: each method's bar spans its p10 to p90: %s" % bars[:3])
    ticks = [(x, float(v)) for x, v in got["ticks"]]
    misplaced = [v for x, v in ticks if not abs(x - px(v)) <= 0.5]
    check(not misplaced and len(ticks) >= 2, what + "cost axis: ticks sit at their values: %s" % misplaced)
    if log:
        roundish = all(v > 0 and any(abs(v / (mm * 10 ** math.floor(math.log10(v) + 1e-9)) - 1) < 1e-9 for mm in (1, 2, 5)) for _, v in ticks)
        check((roundish or round_ticks([v for _, v in got["ticks"]])) and len(ticks) >= 3,
              "log cost axis: three or more ticks, each 1, 2 or 5 times a power of ten (or, on a narrow range, "
              "evenly stepped round ticks): %s" % [v for _, v in ticks])
    else:
        check(round_ticks([v for _, v in got["ticks"]]), "cost axis ticks are round and evenly stepped")


def check_labels(geo, what=""):
    pts = geo["points"]
    inter = lambda a, b: a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]
    dist = lambda b, x, y: math.hypot(max(b[0] - x, 0, x - b[2]), max(b[1] - y, 0, y - b[3]))
    centre = lambda b: ((b[0] + b[2]) / 2, (b[1] + b[3]) / 2)
    over = [(p["method"], q["method"]) for i, p in enumerate(pts) for q in pts[i + 1:] if inter(p["label"], q["label"])]
    check(not over, what + "no two point labels overlap: %s" % over)
    covers = [(p["method"], q["method"]) for p in pts for q in pts if inter(p["label"], q["dot"])]
    check(not covers, what + "no label covers a point: %s" % covers)
    outside = [p["method"] for p in pts if not (p["text"][0] >= p["label"][0] - 0.5 and p["text"][2] <= p["label"][2] + 0.5)]
    check(not outside, what + "each label's text fits its box: %s" % outside)
    check(all(p["textContent"] == p["method"] for p in pts), what + "each label names its method")
    # tied: the label is nearer its own point than any other's, or a leader line runs from the point to it
    loose = []
    for p in pts:
        px, py = centre(p["dot"])
        own = dist(p["label"], px, py)
        nearest = min((dist(p["label"], *centre(q["dot"])) for q in pts if centre(q["dot"]) != (px, py)), default=1e9)
        led = any(abs(l[0] - px) < 0.5 and abs(l[1] - py) < 0.5 and dist(p["label"], l[2], l[3]) < 0.5 for l in geo["leaders"])
        if not (own < nearest or led):
            loose.append(p["method"])
    check(not loose, what + "each label is tied to its point (nearest, or by a leader line): %s" % loose)


def round_ticks(ticks):
    try:
        v = [float(t) for t in ticks]
    except ValueError:
        return False
    if len(v) < 3:
        return False
    step = v[1] - v[0]
    e = 10 ** math.floor(math.log10(step) + 1e-9)
    if not any(abs(step - m * e) < 1e-9 * e for m in (1, 2, 5)):
        return False
    return all(abs((v[i + 1] - v[i]) - step) < 1e-6 * step for i in range(len(v) - 1)) and \
        all(abs(x / step - round(x / step)) < 1e-6 for x in v)


def shoot(b, selector, path):
    r = b.eval("(() => { const r = document.querySelector('%s').getBoundingClientRect();"
               " return [r.x, r.y + scrollY, r.width, r.height]; })()" % selector)
    b.screenshot(path, {"x": r[0], "y": r[1], "width": r[2], "height": r[3]})


main()
