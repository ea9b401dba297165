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
# the bug fuzz_image found: a BMP whose compression does not fit its depth crashed OpenImageIO 2.4 in
# `aalab diff`; it is refused with a message (the corpus input without its first, selector, byte)
tail -c +2 "$top_srcdir/tests/fuzz/corpus/image/crash-bmp-rle8-24bpp" >"$TMP/bad.bmp"
expect_status 2 "aalab diff refuses a BMP with RLE8 at 24 bits per pixel" -- "$AALAB" diff "$TMP/bad.bmp" "$TMP/bad.bmp"
expect_stderr "not valid BMP" "and says why"
finish
