#!/bin/sh
# Every fuzz target replays its corpus (seeds, and the inputs of bugs the fuzzers found) under the
# ordinary build's sanitizers: no crash, no sanitizer report, no leak.
. "$(dirname "$0")/../lib.sh"
for name in protocol http job_spec scene mesh image; do
	dir="$top_srcdir/tests/fuzz/corpus/$name"
	n=$(ls "$dir" | wc -l)
	expect_status 0 "fuzz target $name replays its $n corpus inputs" -- "$top_builddir/tests/fuzz/replay_$name" "$dir"
	if grep -q "Sanitizer\|runtime error" "$TMP/err"; then
		fail "sanitizer report from $name:"; head -30 "$TMP/err"
	fi
done
finish
