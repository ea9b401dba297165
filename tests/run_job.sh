#!/bin/sh
# `aalab run` end to end: results.json has the documented fields, images and report are written, and
# running the same job twice gives bitwise-identical images.
. "$(dirname "$0")/lib.sh"

job="--scene thin-wires --methods none,ssaa:4 --frames 2 --size 96x54 --reference-samples 8 --quiet"
expect_status 0 "small job runs" -- "$AALAB" run $job --out "$TMP/a"
grep -q "ssaa:samples=4\|ssaa:4" "$TMP/out" && pass "table lists ssaa" || fail "table lacks ssaa: $(cat "$TMP/out")"
for f in results.json report.html frames/reference/0000.png frames/none/0001.png diff/none/0000.png; do
	[ -s "$TMP/a/$f" ] && pass "wrote $f" || fail "missing $f"
done
grep -q "<svg" "$TMP/a/report.html" && pass "report has an SVG chart" || fail "report has no SVG"

/usr/bin/python3 - "$TMP/a/results.json" <<'PY' && pass "results.json has the documented fields" || fail "results.json fields"
import json, math, sys
r = json.load(open(sys.argv[1]))
def walk(v):
    if isinstance(v, float):
        assert math.isfinite(v), v
    elif isinstance(v, dict):
        [walk(x) for x in v.values()]
    elif isinstance(v, list):
        [walk(x) for x in v]
walk(r)
assert r["reference"]["samples"] == 8
assert "convergence_psnr" in r["reference"]
names = [p["pass"] for p in r["passes"]]
assert "scene-forward" in names and "reference-accumulate" in names, names
ms = {m["label"]: m for m in r["methods"]}
assert len(ms) == 2, ms.keys()
for m in r["methods"]:
    assert m["gpu_ms"]["median"] > 0
    assert m["memory_bytes"] > 0
    assert m["metrics"]["psnr"]["mean"] is None or m["metrics"]["psnr"]["mean"] > 0
    assert 0 < m["metrics"]["ssim"]["mean"] <= 1
    assert len(m["metrics"]["psnr"]["per_frame"]) == 2
none, ssaa = r["methods"][0], r["methods"][1]
assert ssaa["metrics"]["psnr"]["mean"] > none["metrics"]["psnr"]["mean"], "ssaa must beat none"
assert ssaa["memory_bytes"] > none["memory_bytes"]
PY

expect_status 0 "same job again" -- "$AALAB" run $job --out "$TMP/b"
same=1
for f in $(cd "$TMP/a" && find frames diff -name '*.png'); do
	cmp -s "$TMP/a/$f" "$TMP/b/$f" || { same=0; fail "$f differs between two runs"; }
done
[ $same -eq 1 ] && pass "two runs give bitwise-identical images"

expect_status 0 "--json prints results" -- "$AALAB" run $job --no-images --json --out "$TMP/c"
/usr/bin/python3 -c 'import json,sys; json.load(open(sys.argv[1]))' "$TMP/out" && pass "--json output parses" || fail "--json output is not JSON"
[ ! -d "$TMP/c/frames" ] && pass "--no-images writes no frames" || fail "--no-images wrote frames"
/usr/bin/python3 - "$TMP/c/results.json" <<'PY' && pass "--no-images: results.json names no image" || fail "--no-images: results.json names images that were not written"
import json, sys
r = json.load(open(sys.argv[1]))
paths = [f.get(k) for m in r["methods"] for f in m["frames"] for k in ("image", "diff", "flip_map")]
paths += [f.get("image") for f in r["reference"].get("per_frame", [])]
assert paths and all(p is None for p in paths), paths
PY
# progress outside a terminal: a line per tenth of the renders on stderr, the table alone on stdout
expect_status 0 "a run without --quiet, stderr not a terminal" -- "$AALAB" run ${job% --quiet} --frames 5 --no-images --out "$TMP/e"
/usr/bin/python3 - "$TMP/err" "$TMP/out" <<'PY' && pass "progress: a line per tenth on stderr, to 15/15 (100%)" || fail "progress lines: $(cat "$TMP/err")"
import re, sys
lines = [l for l in open(sys.argv[1]).read().splitlines() if l.startswith("aalab run: rendering")]
done = [int(re.match(r"aalab run: rendering (\d+)/15 \((\d+)%, ETA [0-9hms?]+\)$", l).group(1)) for l in lines]
assert 1 <= len(done) <= 10 and done == sorted(done) and done[-1] == 15, lines
assert "rendering" not in open(sys.argv[2]).read()
PY
# the verdict first, the table with FLIP and what its columns are, the warnings after it, as results.json
# has them; a reference of 4 samples is not converged, and one timed render ranks nothing
expect_status 0 "one frame timed once, a 4-sample reference" -- "$AALAB" run --scene hard-edges --methods none,fxaa \
	--size 160x90 --reference-samples 4 --repeat 1 --no-images --quiet --out "$TMP/g"
/usr/bin/python3 - "$TMP/g/results.json" "$TMP/out" <<'PY' && pass "verdict first, the table, then the warnings, as results.json says them" || fail "verdict and warnings: $(cat "$TMP/out")"
import json, sys
r, out = json.load(open(sys.argv[1])), open(sys.argv[2]).read().splitlines()
assert out[0] == "verdict: " + r["verdict"]["headline"], out[0]
assert r["verdict"]["headline"] == "not ranked: n=1 timed render per method, 5 needed to rank costs", r["verdict"]
assert r["verdict"]["ranked"] is False and r["verdict"]["front"] == []
header = [l for l in out if l.startswith("method ")][0]
assert "FLIP" in header and "px >1% off" in header and "p10-p90 ms (n)" in header and "verdict" in header, header
rows = [l for l in out if l.startswith("none ") or l.startswith("fxaa ")]
assert len(rows) == 2 and all("n=1: not ranked" in l for l in rows), rows
codes = [w["code"] for w in r["warnings"]]
assert "reference-not-converged" in codes and "too-few-timed-renders" in codes, codes
at = out.index("warnings (%d):" % len(r["warnings"]))
assert at > out.index(header)
for w in r["warnings"]:
    assert "  %s: %s" % (w["code"], w["message"]) in out and "    what to do: " + w["action"] in out, w
PY
expect_status 0 "--quiet" -- "$AALAB" run $job --no-images --out "$TMP/f"
grep -q "rendering" "$TMP/err" && fail "--quiet printed progress: $(cat "$TMP/err")" || pass "--quiet prints no progress"
expect_status 0 "--no-viewer" -- "$AALAB" run $job --no-viewer --out "$TMP/d"
[ -d "$TMP/d/frames/none" ] && [ ! -e "$TMP/d/viewer" ] && grep -q '"no_images":"No viewer: the job left it out' "$TMP/d/report.html" &&
	pass "--no-viewer keeps the PNGs, writes no viewer/, and the report says why it has no viewer" ||
	fail "--no-viewer: $(ls "$TMP/d")"
finish
