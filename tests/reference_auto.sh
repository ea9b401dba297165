#!/bin/sh
# reference.samples "auto": N doubles until the N/2-vs-N convergence PSNR reaches the target or
# the cap; at the cap it is the fixed-N reference, bit for bit; it stops at the first N that reaches it.
. "$(dirname "$0")/lib.sh"

job="--local --scene thin-wires --methods none --frames 1 --size 64x36 --no-images --quiet"
cat >"$TMP/capped.json" <<'JSON'
{"scene": "thin-wires", "size": "64x36", "frames": 1, "methods": ["none"],
 "reference": {"samples": "auto", "target_psnr": 80, "max_samples": 16}}
JSON
expect_status 0 "auto capped at 16" -- "$AALAB" run --local --quiet "$TMP/capped.json" --out "$TMP/capped"
expect_status 0 "fixed 16" -- "$AALAB" run --local --quiet --scene thin-wires --size 64x36 --frames 1 \
	--methods none --reference-samples 16 --out "$TMP/fixed"
cmp -s "$TMP/capped/frames/reference/0000.png" "$TMP/fixed/frames/reference/0000.png" &&
	pass "auto at its cap is the fixed-N reference, bit for bit" || fail "auto at cap 16 differs from 16 samples"
grep -q "<li><b>reference-capped</b>: 1 frame of the reference reached reference.max_samples" "$TMP/capped/report.html" &&
	pass "the report warns of the frame that stopped at the cap" || fail "no capped warning in report.html"
grep -q "auto: 16 samples" "$TMP/capped/report.html" && pass "the report's Reference card says auto and N" ||
	fail "report card"

expect_status 0 "auto, default target" -- "$AALAB" run $job --reference-samples auto --out "$TMP/auto"
grep -Eq "reference auto: [0-9]+ samples \(target 45.0 dB, cap 256" "$TMP/out" &&
	pass "the table says the N reached" || fail "table: $(head -1 "$TMP/out")"
n=$(/usr/bin/python3 - "$TMP/auto/results.json" <<'PY'
import json, sys
ref = json.load(open(sys.argv[1]))["reference"]
assert ref["mode"] == "auto" and ref["samples"] == 256 and ref["target_psnr"] == 45, ref
f = ref["per_frame"][0]
assert f["samples"] in (8, 16, 32, 64, 128, 256), f
assert f["convergence_identical"] or f["convergence_psnr"] >= 45 or f["samples"] == 256, f
print(f["samples"])
PY
) && pass "results.json: N $n reached 45 dB" || fail "results.json reference fields"
# the same renders with the cap at N/2 (thin-wires has no textures, so the LOD bias changes nothing): short
if [ -n "$n" ] && [ "$n" -gt 8 ]; then
	half=$((n / 2))
	sed "s/\"max_samples\": 16/\"max_samples\": $half/" "$TMP/capped.json" >"$TMP/half.json"
	expect_status 0 "auto capped at $half" -- "$AALAB" run --local --quiet "$TMP/half.json" --out "$TMP/half"
	/usr/bin/python3 - "$TMP/half/results.json" <<'PY' && pass "N/2 = $half was under 45 dB: auto stopped at the first N" || fail "N/2 already converged: auto went too far"
import json, sys
f = json.load(open(sys.argv[1]))["reference"]["per_frame"][0]
assert not f["convergence_identical"] and f["convergence_psnr"] < 45, f
PY
fi

expect_status 2 "reference.samples neither a number nor auto" -- "$AALAB" run $job --reference-samples lots --out "$TMP/o"
expect_stderr "reference.samples" "the error names reference.samples"
echo '{"reference": {"samples": "auto", "max_samples": 100}}' >"$TMP/bad.json"
expect_status 2 "max_samples not a power of two" -- "$AALAB" run --local --quiet "$TMP/bad.json" --out "$TMP/o"
expect_stderr "reference.max_samples" "the error names reference.max_samples"
finish
