#!/bin/sh
# The bench scripts run against this build at a tiny size, so a change to the CLI they drive (as the
# refusal of non-empty --out folders once did) breaks a test here and not the next person's benchmark.
# Only that they run and print their ratios is checked: the numbers are timings, never asserted.
. "$(dirname "$0")/lib.sh"
export AALAB

expect_status 0 "bench/methods runs" -- "$top_srcdir/bench/methods" thin-wires 64x36 1 copy,floor,none,fxaa 1
grep -q "extra/copy" "$TMP/out" && grep -Eq "^fxaa +[0-9]" "$TMP/out" && pass "and prints a row per method" \
	|| { fail "bench/methods printed no table"; sed 's/^/  | /' "$TMP/out" | head; }
grep -q "scene pass of none: .* x the floor pass" "$TMP/out" && pass "with the scene pass against the floor" \
	|| fail "bench/methods printed no scene/floor ratio"
# One pair of renders at this size can make the extra negative (it did once in CI): the sign is
# noise, so only the shape is checked, and that the own passes were measured at all.
grep -Eq "^fxaa +-?[0-9.]+ \(-?[0-9.]+--?[0-9.]+\) +1 +[0-9.]+ \(" "$TMP/out" &&
	awk '$1 == "fxaa" && NF == 7 && $5 > 0 { ok = 1 } END { exit !ok }' "$TMP/out" &&
	pass "and fxaa's extra paired per round, with its own passes (not 0)" \
	|| { fail "bench/methods printed no per-round row for fxaa"; grep -A3 "per round" "$TMP/out"; }

expect_status 0 "bench/floor runs" -- "$top_srcdir/bench/floor" thin-wires 64x36 2 2
grep -q "^scene / floor" "$TMP/out" && grep -q "^scene / copy" "$TMP/out" && pass "and prints its ratios" \
	|| { fail "bench/floor printed no ratios"; sed 's/^/  | /' "$TMP/out" | head; }
expect_status 0 "bench/materials runs" -- "$top_srcdir/bench/materials" 64x36 1 1
grep -Eq "^  4-ggx-every-map +[0-9]" "$TMP/out" && pass "and prints a ratio per material" \
	|| { fail "bench/materials printed no ratios"; sed 's/^/  | /' "$TMP/out" | head; }
finish
