#!/bin/sh
# User methods through `aalab run`, as a user would: the examples of examples/methods/ (a single-pass
# spatial filter, a two-pass temporal method) appear in results.json with timings, memory and metrics,
# in the table and in the report's chart; a copied example with a constant changed runs beside fxaa and
# smaa; a syntax error exits 2 with the file and line; a bad method file names its field; the job-file
# form works; the second run takes its SPIR-V from the cache.
. "$(dirname "$0")/lib.sh"
export AALAB_CACHE_DIR="$TMP/cache"
ex="$top_srcdir/examples/methods"

job="--scene moving-sphere --frames 2 --size 160x90 --reference-samples 8 --quiet"
expect_status 0 "the examples run beside none and fxaa" -- "$AALAB" run $job --out "$TMP/a" \
	--methods "none,fxaa,user:file=$ex/edge_blur.json,user:file=$ex/simple_taa.json,feedback=0.8"
grep -q "^edge-blur " "$TMP/out" && grep -q "^simple-taa:feedback=0.8 " "$TMP/out" && pass "the table lists both" ||
	fail "table: $(cat "$TMP/out")"
/usr/bin/python3 - "$TMP/a/results.json" "$ex" <<'PY' && pass "results.json: timings, memory, metrics, plan" || fail "results.json"
import json, sys
r = json.load(open(sys.argv[1]))
ms = {m["label"]: m for m in r["methods"]}
blur, taa = ms["edge-blur"], ms["simple-taa:feedback=0.8"]
for m, passes in ((blur, ["shadow-map", "scene", "blur"]), (taa, ["shadow-map", "scene", "resolve", "sharpen"])):
    assert m["name"] == "user", m["name"]
    assert m["user_method"]["file"].startswith(sys.argv[2]) and len(m["user_method"]["sha256"]) == 64
    assert m["gpu_ms"]["n"] == 6 and m["gpu_ms"]["median"] > 0, m["gpu_ms"]  # 2 frames x timing.repeat "auto" 3
    assert [p["name"] for p in m["passes"]] == passes, m["passes"]
    assert all(p["gpu_ms"] > 0 for p in m["passes"])
    assert m["memory_bytes"] == sum(x["bytes"] for x in m["memory"]) > 0
    for k in ("psnr", "ssim", "flip"):
        assert len(m["metrics"][k]["per_frame"]) == 2 and m["metrics"][k]["mean"] > 0, (k, m["metrics"][k])
    assert all(f["nonfinite"] == 0 for f in m["frames"])
    assert "SPIR-V compiled" in m["path_taken"], m["path_taken"]
assert taa["params"] == {"feedback": 0.8, "sharpen": 0.15}, taa["params"]
# the alpha rule follows how the scene is drawn: at the pixel centre (edge-blur), jittered (simple-taa)
assert (blur["alpha_rule"], taa["alpha_rule"]) == ("per-pixel", "per-sample"), (blur["alpha_rule"], taa["alpha_rule"])
assert [x["name"] for x in taa["memory"]] == ["scene colour", "scene velocity", "scene depth", "resolve A",
                                               "resolve B", "sharpen"], taa["memory"]
assert [x["name"] for x in blur["memory"]] == ["scene colour", "scene depth", "blur"], blur["memory"]
plan = {p["pass"]: p for p in r["passes"]}
assert plan["velocity"]["ran"] and "simple-taa" in plan["velocity"]["reason"], plan["velocity"]
assert plan["history"]["ran"] and not plan["model-ids"]["ran"]
PY
grep -q "edge-blur" "$TMP/a/report.html" && grep -q "simple-taa:feedback=0.8" "$TMP/a/report.html" &&
	pass "report.html shows both" || fail "report.html lacks the user methods"
[ -s "$TMP/a/frames/edge-blur/0001.png" ] && pass "frames under the label" || fail "no frames/edge-blur"

# a user copies an example, changes a constant and runs it beside fxaa and smaa
mkdir -p "$TMP/mine"
sed -e 's/"edge-blur"/"my-blur"/' "$ex/edge_blur.json" >"$TMP/mine/my_blur.json"
sed -e 's/0.25 \* (n + s + w + e)/0.5 * (w + e)/' "$ex/edge_blur.frag" >"$TMP/mine/edge_blur.frag"
cmp -s "$ex/edge_blur.frag" "$TMP/mine/edge_blur.frag" && fail "the copy's constant did not change"
(cd "$TMP/mine" && expect_status 0 "a copied example runs beside fxaa and smaa" -- "$AALAB" run $job \
	--out "$TMP/b" --methods "fxaa,smaa,user:file=my_blur.json,user:file=$ex/edge_blur.json")
grep -q "^my-blur " "$TMP/out" && pass "the copy is in the table" || fail "table: $(cat "$TMP/out")"
grep -q "my-blur" "$TMP/b/report.html" && pass "and in the report" || fail "report lacks my-blur"
# the cost-vs-accuracy chart: one point (a circle titled "LABEL: MS ms ...") per method, the copy among them
for label in fxaa smaa my-blur edge-blur; do
	grep -q "<title>$label: [0-9.]* ms (p10-p90" "$TMP/b/report.html" && pass "a point for $label in the cost-vs-accuracy chart" ||
		fail "no point for $label in the chart"
done
/usr/bin/python3 - "$TMP/b/results.json" <<'PY' && pass "its own numbers; the SPIR-V of the example came from the cache" || fail "the copy's results"
import json, sys
ms = {m["label"]: m for m in json.load(open(sys.argv[1]))["methods"]}
assert ms["my-blur"]["metrics"]["mse"]["mean"] != ms["edge-blur"]["metrics"]["mse"]["mean"]
assert "SPIR-V from the cache" in ms["edge-blur"]["path_taken"], ms["edge-blur"]["path_taken"]
assert "SPIR-V compiled" in ms["my-blur"]["path_taken"], ms["my-blur"]["path_taken"]
PY

# a syntax error: exit 2, the file and the line
sed -e 's/aa_write(vec4(mix(c, mean, weight), 1.0));/aa_write(vec4(mix(c, mean, weight), 1.0)/' \
	"$ex/edge_blur.frag" >"$TMP/mine/edge_blur.frag"
(cd "$TMP/mine" && expect_status 2 "a syntax error is bad input" -- "$AALAB" run $job --out "$TMP/c" \
	--methods "none,user:file=my_blur.json")
expect_stderr "methods\[1\]: edge_blur.frag:1[89]: .*syntax error" "the message names the file and the line"
[ -e "$TMP/c" ] && fail "a failed run left $TMP/c" || pass "and writes no results"

# a bad method file names the file and the field; a parameter outside its range, the range
printf '{"name": "x", "passes": [{"name": "a", "shader": "a.frag", "reads": ["colour", "normal"]}]}' >"$TMP/mine/bad.json"
expect_status 2 "a bad input name is refused" -- "$AALAB" run $job --out "$TMP/c" --methods "user:file=$TMP/mine/bad.json"
expect_stderr "bad.json: passes\[0\]\.reads\[1\]: unknown input \"normal\"" "naming the file and the field"
expect_status 2 "a parameter outside its range" -- "$AALAB" run $job --out "$TMP/c" --methods "user:file=$ex/edge_blur.json,strength=3"
expect_stderr "methods\[0\]: edge-blur: strength=3 is not valid; valid range: 0 to 1" "says the range"

# the object form in a job file; relative paths from the current directory
printf '{"scene": "thin-wires", "size": "64x36", "reference": {"samples": 4}, "methods": ["none", {"name": "user", "params": {"file": "examples/methods/edge_blur.json", "strength": 1}}]}' >"$TMP/job.json"
(cd "$top_srcdir" && expect_status 0 "a job file with the object form" -- "$AALAB" run "$TMP/job.json" --quiet --out "$TMP/d")
grep -q '"label": "edge-blur:strength=1"' "$TMP/d/results.json" && pass "labelled with its parameter" || fail "label in $TMP/d"
finish
