#!/bin/sh
# A sweep end to end: `--methods none,fxaa:preset=10|20|39,msaa:2|4|8` runs one method per configuration,
# results.json's verdict holds each family's front, recomputed here from the methods' own GPU times, PSNR
# and FLIP by the documented rule (docs/results-format.md, "verdict"), and the terminal prints one line per
# family; the list form of a job file and a suite give the same; a sweep past the limit is refused naming
# the entry and the parameter.
. "$(dirname "$0")/lib.sh"

sweep='none,fxaa:preset=10|20|39,msaa:2|4|8'
expect_status 0 "a sweep runs" -- "$AALAB" run --local --scene thin-wires --methods "$sweep" --size 96x54 \
	--reference-samples 8 --no-images --quiet --out "$TMP/a"
cp "$TMP/out" "$TMP/a.out"

/usr/bin/python3 - "$TMP/a/results.json" "$TMP/a.out" <<'PY' && pass "families: shape, cost order and fronts as recomputed" || fail "families"
import json, math, sys
r = json.load(open(sys.argv[1]))
out = open(sys.argv[2]).read().split("\n")
labels = ["none", "fxaa:preset=10", "fxaa:preset=20", "fxaa:preset=39", "msaa:2", "msaa:4", "msaa:8"]
assert [m["label"] for m in r["methods"]] == labels, [m["label"] for m in r["methods"]]
assert r["job"]["methods"] == labels, r["job"]["methods"]
assert [m["params"].get("preset") for m in r["methods"][1:4]] == [10, 20, 39]
assert [m["params"]["samples"] for m in r["methods"][4:]] == [2, 4, 8]
m = {x["label"]: x for x in r["methods"]}
minimum = r["timing"]["min_timed_renders"]

def ranked(a):
    g = m[a]["gpu_ms"]
    return g["n"] >= minimum and g["p10"] is not None and g["p90"] is not None

def quality(a):
    p = m[a]["metrics"]["psnr"]
    psnr = math.inf if p.get("identical") or p["mean"] is None else p["mean"]
    return psnr, m[a]["metrics"]["flip"]["mean"]

def beats(a, b):  # a beats b: at most its cost (spreads apart or overlapping), at least its quality, better in one
    if not (ranked(a) and ranked(b)):
        return False
    ga, gb = m[a]["gpu_ms"], m[b]["gpu_ms"]
    lower = ga["p90"] < gb["p10"]
    same = not lower and not gb["p90"] < ga["p10"]
    (pa, fa), (pb, fb) = quality(a), quality(b)
    if not (lower or same) or pa < pb or fa > fb:
        return False
    return lower or pa > pb or fa < fb

fam = r["verdict"]["families"]
assert [f["family"] for f in fam] == ["fxaa", "msaa"], fam
for f, members in zip(fam, (labels[1:4], labels[4:])):
    assert sorted(f) == ["family", "front", "methods"], f
    want = sorted(members, key=lambda a: (m[a]["gpu_ms"]["median"], labels.index(a)))
    assert f["methods"] == want, (f["methods"], want)
    front = [a for a in want if ranked(a) and not any(beats(b, a) for b in members if b != a)]
    assert f["front"] == front, (f["family"], f["front"], front)
    line = "  %s family front: %s (of %d configurations, cheapest first)" % (
        f["family"], ", ".join(front[:-1]) + " and " + front[-1] if len(front) > 1 else front[0], len(members))
    assert line in out, (line, out[:12])
# msaa:8 has 4 samples more than msaa:4 and more PSNR: never beaten within its family
assert "msaa:8" in fam[1]["front"], fam[1]
print("fxaa front:", fam[0]["front"], "msaa front:", fam[1]["front"])
PY

# report.html draws what the verdict says: each family's line through its configurations' points in
# ascending cost, its legend entry with its front, the verdict card's family line, and the front's staircase
/usr/bin/python3 - "$TMP/a/results.json" "$TMP/a/report.html" <<'PY' && pass "report.html: a line per family through its points by cost, its front in the legend" || fail "report families"
import html, json, re, sys
r = json.load(open(sys.argv[1]))
page = open(sys.argv[2]).read()
at = {html.unescape(l): (float(x), float(y)) for x, y, l in
      re.findall(r'<circle class="method" cx="([-0-9.]+)" cy="([-0-9.]+)"[^>]*><title>([^<]*?): [-0-9.]+ ms', page)}
assert len(at) == len(r["methods"]), sorted(at)
fam = r["verdict"]["families"]
lines = dict(re.findall(r'<polyline class="family-line" data-family="([^"]+)"[^>]* points="([^"]*)"', page))
assert sorted(lines) == sorted(f["family"] for f in fam), (lines, fam)
for f in fam:
    pts = [tuple(float(v) for v in p.split(",")) for p in lines[f["family"]].split()]
    assert pts == [at[l] for l in f["methods"]], (f["family"], pts, [at[l] for l in f["methods"]])
    li = re.search(r'<li data-family="%s">(.*?)</li>' % f["family"], page).group(1)
    assert html.unescape(re.sub("<[^>]+>", "", li)).endswith(
        " \u2192 ".join(f["methods"]) + " (front: " + ", ".join(f["front"]) + ")"), li
    front = f["front"]
    said = ", ".join(front[:-1]) + " and " + front[-1] if len(front) > 1 else front[0]
    assert "<li>%s family front: %s (of %d configurations" % (f["family"], said, len(f["methods"])) in page, f
front = sorted((at[l] for l in r["verdict"]["front"]), key=lambda p: p[0])
if len(front) > 1:
    d = re.search(r'<path class="front-line" d="([^"]+)"', page).group(1)
    assert d.startswith("M%.1f %.1f" % front[0]) and d.endswith("H%.1fV%.1f" % front[-1]), (d, front)
PY

# the list form of a job file is the same job: same hash, same methods
cat >"$TMP/job.json" <<'EOF'
{"scene": "thin-wires", "size": "96x54", "reference": {"samples": 8},
 "methods": ["none", {"name": "fxaa", "params": {"preset": [10, 20, 39]}}, {"name": "msaa", "params": {"samples": [2, 4, 8]}}]}
EOF
expect_status 0 "the list form runs" -- "$AALAB" run --local "$TMP/job.json" --no-images --quiet --out "$TMP/b"
/usr/bin/python3 - "$TMP/a/results.json" "$TMP/b/results.json" <<'PY' && pass "the list form is the same job as the '|' form" || fail "list form differs"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert a["job_hash"] == b["job_hash"], (a["job_hash"], b["job_hash"])
assert [m["label"] for m in a["methods"]] == [m["label"] for m in b["methods"]]
assert [f["family"] for f in b["verdict"]["families"]] == ["fxaa", "msaa"]
PY

# a suite: each case's verdict has its families, and the terminal a line per family under each case
cat >"$TMP/suite.json" <<'EOF'
{"suite": "sweep", "scenes": ["thin-wires"], "sizes": ["64x36", "96x54"], "reference": {"samples": 8},
 "methods": ["none", "msaa:2|4"]}
EOF
expect_status 0 "a suite with a sweep runs" -- "$AALAB" run --local "$TMP/suite.json" --no-images --quiet --out "$TMP/c"
/usr/bin/python3 - "$TMP/c/results.json" "$TMP/out" <<'PY' && pass "a suite's cases each have their msaa family" || fail "suite families"
import json, sys
r = json.load(open(sys.argv[1]))
out = open(sys.argv[2]).read()
assert len(r["cases"]) == 2
for c in r["cases"]:
    f = c["verdict"]["families"]
    assert len(f) == 1 and f[0]["family"] == "msaa" and sorted(f[0]["methods"]) == ["msaa:2", "msaa:4"], f
assert out.count("  msaa family front: ") == 2, out
PY

# past the limit (40 configurations, over any job's methods): refused before anything runs, naming the
# entry and the parameter
expect_status 2 "a sweep past a job's methods is refused" -- "$AALAB" run --local --methods \
	'none,ssaa,fxaa:preset=10|12|15|20|23|25|29|39,subpix=0|0.25|0.5|0.75|1' --size 96x54 --out "$TMP/d"
expect_stderr "methods\[2\]: fxaa: subpix lists 5 values, which makes the sweep 40 configurations; the job has room for [0-9]+ \(2 taken" \
	"the refusal names the entry, the parameter and the count"
[ ! -e "$TMP/d" ] && pass "nothing written for a refused sweep" || fail "a refused sweep wrote $TMP/d"
finish
