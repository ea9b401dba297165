#!/bin/sh
# 1,000 still frames of taa, asaa and t2msaa at 32x18 (bench/hard-cases-long runs 10,000 of every
# temporal method; taa-sobel, whose history is taa's, is left out here to keep this fast under sanitizers):
# no drift and no stall (tests/hardcases/long_run_check.py says what each means).
. "$(dirname "$0")/lib.sh"

expect_status 0 "1,000 still frames, verdicts hold" -- \
	"$AALAB" run --local --quiet "$top_srcdir/tests/hardcases/long-static.json" --out "$TMP/long"
if /usr/bin/python3 "$top_srcdir/tests/hardcases/long_run_check.py" "$TMP/long/results.json" >"$TMP/check"; then
	pass "no drift, no stall over 1,000 frames"
else
	fail "long run: $(cat "$TMP/check")"
fi
sed 's/^/  | /' "$TMP/check"
finish
