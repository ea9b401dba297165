#!/bin/sh
# The hard-case suite's verdicts end to end (docs/hard-cases.md) on a small subset: the table is printed,
# results.json holds a verdict per case and method, a clean run exits 0, and a method worse than none by
# more than the margin (floor: a constant colour) fails its verdict and the run (exit 1, results kept).
. "$(dirname "$0")/lib.sh"

suite="$top_srcdir/tests/hardcases/small-suite.json"
expect_status 0 "the small hard-case suite holds its verdicts" -- "$AALAB" run --local --quiet "$suite" --out "$TMP/a"
grep -q "0 verdicts failed that must hold" "$TMP/out" && pass "the verdict table is printed" ||
	fail "no verdict summary: $(tail -3 "$TMP/out")"
/usr/bin/python3 - "$TMP/a/results.json" <<'PY' && pass "results.json: a verdict per case and method" || fail "results.json verdicts"
import json, sys
r = json.load(open(sys.argv[1]))
v = r["verdicts"]
assert v["failed"] == 0, v["failed"]
items = v["items"]
assert len(items) == 2 * 5, len(items)
kinds = {"finite", "range", "stuck", "drift", "vs_none", "dip"}
for it in items:
    assert set(it["verdicts"]) == kinds, it
    assert it["verdicts"]["finite"]["state"] == "pass" and it["verdicts"]["range"]["state"] == "pass", it
# the static case judges drift, the moving one does not
static = [it for it in items if it["case"].startswith("specular-aliasing/static")]
assert all(it["verdicts"]["drift"]["state"] == "pass" for it in static), static
moving = [it for it in items if it["case"].startswith("hdr-fireflies")]
assert all(it["verdicts"]["drift"]["state"] == "n/a" for it in moving), moving
# "debug_targets": true reaches every case: each method's intermediates were read back and held no NaN/Inf
for c in r["cases"]:
    for m in c["methods"]:
        for f in m["frames"]:
            i = f["intermediates"]
            assert i["targets_read"] >= 1 and i["invalid_texels"] == 0 and i["invalid_targets"] == [], (c["id"], m["label"], i)
ms = {m["label"] for m in r["cases"][0]["methods"]}
assert "ssaa:4,tonemapped_resolve=true" in ms and "msaa:4,tonemapped_resolve=true" in ms, ms
# SMAA 4x (T2x's history over S2x's two sample images) holds every verdict; on the still case its drift
# verdict is judged (its history must not wander from the picture) and it is not worse than none
smaa = [it for it in items if it["method"] == "smaa:mode=4x"]
assert len(smaa) == 2 and all(v["state"] in ("pass", "n/a") for it in smaa for v in it["verdicts"].values()), smaa
assert [it["verdicts"]["drift"]["state"] for it in smaa if it["case"].startswith("specular-aliasing/static")] == ["pass"], smaa
PY
expect_status 1 "floor (a constant colour) fails vs_none and the run" -- \
	"$AALAB" run --local --quiet "$suite" --methods none,floor --out "$TMP/b"
expect_stderr "verdicts? failed" "the failure is said on stderr"
grep -Eq "floor +pass 0 +pass 0 .*FAIL -[0-9.]+" "$TMP/out" && pass "the table shows floor's FAIL" ||
	fail "table: $(grep floor "$TMP/out")"
[ -s "$TMP/b/results.json" ] && pass "the results of a run with failed verdicts are kept" || fail "results discarded"

# a single job (not a suite) with "verdicts": true judges its one case the same way
echo '{"scene": "hard-edges", "size": "64x36", "frames": 2, "reference": {"samples": 8},
 "methods": ["none", "fxaa", "floor"], "verdicts": true}' >"$TMP/one.json"
expect_status 1 "a single job's verdicts: floor fails, the run exits 1" -- "$AALAB" run --local --quiet "$TMP/one.json" --out "$TMP/one"
/usr/bin/python3 - "$TMP/one/results.json" <<'PY' && pass "a single job's results.json holds its verdicts" || fail "single-job verdicts"
import json, sys
v = json.load(open(sys.argv[1]))["verdicts"]
states = {it["method"]: it["verdicts"]["vs_none"]["state"] for it in v["items"]}
assert v["failed"] >= 1 and states == {"none": "n/a", "fxaa": "pass", "floor": "fail"}, (v["failed"], states)
PY
grep -Eq "verdicts? failed that must hold" "$TMP/out" && pass "and prints the verdict table" || fail "no verdict table for a single job"
# tonemapped_resolve: on hdr-fireflies Karis' weights keep a sub-pixel emitter (1e3-1e5) from filling its
# whole resolve footprint with white, so fewer pixels saturate than with the linear box resolve
expect_status 0 "ssaa and msaa with and without tonemapped_resolve" -- "$AALAB" run --local --quiet \
	--scene hdr-fireflies --size 64x36 --frames 1 --reference-samples 8 --out "$TMP/tm" \
	--methods "ssaa:4,ssaa:samples=4,tonemapped_resolve=true,msaa:4,msaa:samples=4,tonemapped_resolve=true"
/usr/bin/python3 - "$TMP/tm/frames" <<'PY' >"$TMP/tm.txt" && pass "tone-mapped resolves saturate fewer pixels: $(cat "$TMP/tm.txt")" || fail "tonemapped_resolve: $(cat "$TMP/tm.txt")"
import sys
import numpy as np
from skimage import io
def saturated(name):
    a = io.imread("%s/%s/0000.png" % (sys.argv[1], name))[..., :3]
    return int((a.min(axis=2) >= 250).sum())
n = {m: saturated(m) for m in ["ssaa_4", "ssaa_4_tonemapped_resolve-true", "msaa_4", "msaa_4_tonemapped_resolve-true"]}
print(n)
assert n["ssaa_4_tonemapped_resolve-true"] < n["ssaa_4"] and n["msaa_4_tonemapped_resolve-true"] < n["msaa_4"], n
PY
# the temporal methods' tonemapped_resolve (taa's default, asaa's option): a jittered hit on an emitter
# enters history with weight 1/(1 + luma) instead of its 1e4 linear value, so history holds no white blob
# around the emitter: far fewer pixels saturate where the reference does not
expect_status 0 "taa and asaa with and without tonemapped_resolve" -- "$AALAB" run --local --quiet \
	--scene hdr-fireflies --size 64x36 --frames 8 --reference-samples 32 --out "$TMP/tt" \
	--methods "taa:tonemapped_resolve=false,taa,asaa,asaa:tonemapped_resolve=true"
/usr/bin/python3 - "$TMP/tt/frames" <<'PY' >"$TMP/tt.txt" && pass "Karis-weighted histories leave fewer blobs: $(cat "$TMP/tt.txt")" || fail "temporal tonemapped_resolve: $(cat "$TMP/tt.txt")"
import glob, sys
from skimage import io
def blob_pixels(name):
    """pixels saturated in the method's frames where the reference's are not, over every frame"""
    n = 0
    for ref in sorted(glob.glob(sys.argv[1] + "/reference/*.png")):
        r = io.imread(ref)[..., :3].min(axis=2) >= 250
        a = io.imread(ref.replace("/reference/", "/%s/" % name))[..., :3].min(axis=2) >= 250
        n += int((a & ~r).sum())
    return n
n = {m: blob_pixels(m) for m in ["taa_tonemapped_resolve-false", "taa", "asaa", "asaa_tonemapped_resolve-true"]}
print(n)
assert 2 * n["taa"] < n["taa_tonemapped_resolve-false"] and 2 * n["asaa_tonemapped_resolve-true"] < n["asaa"], n
PY
expect_status 2 "taa's seed001 preset refuses tonemapped_resolve=false" -- "$AALAB" run --local --quiet \
	--scene thin-wires --size 32x18 --frames 1 --reference-samples 2 --out "$TMP/s1" \
	--methods "taa:preset=seed001,tonemapped_resolve=false"
expect_stderr "params.tonemapped_resolve" "the error names the parameter"
expect_status 2 "msaa's virtual path refuses tonemapped_resolve" -- "$AALAB" run --local --quiet \
	--scene thin-wires --size 32x18 --frames 1 --reference-samples 2 --out "$TMP/v" \
	--methods "msaa:samples=8,tonemapped_resolve=true"
expect_stderr "tonemapped_resolve" "the error names the parameter"
finish
