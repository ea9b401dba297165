#!/bin/sh
# Bad input to `aalab run` exits with status 2 and a message naming the bad field, before any rendering.
. "$(dirname "$0")/lib.sh"

expect_status 2 "unknown scene" -- "$AALAB" run --scene nosuch --out "$TMP/o" --quiet
expect_stderr "scene.*nosuch" "unknown scene is named"
expect_status 2 "negative size" -- "$AALAB" run --size -3x10 --out "$TMP/o" --quiet
expect_stderr "^aalab run: size" "bad size names the size field"
expect_status 2 "size without x" -- "$AALAB" run --size 640 --out "$TMP/o" --quiet
expect_stderr "size" "size without x names the size field"
# an unknown option is named by the command, as our own messages are (getopt once said "run: ...")
for cmd in run diff compare submit; do
	expect_status 2 "$cmd --bogus" -- "$AALAB" $cmd --bogus
	expect_stderr "^aalab $cmd: (unrecognized|unknown or incomplete) option '--bogus'" "aalab $cmd names itself and the option"
done
expect_status 2 "unknown method" -- "$AALAB" run --methods fxaa:banana --out "$TMP/o" --quiet
expect_stderr "methods\[0\]" "unknown method names methods[0]"
expect_status 2 "bad ssaa samples" -- "$AALAB" run --methods none,ssaa:7 --out "$TMP/o" --quiet
expect_stderr "methods\[1\].*(4, 9, 16)" "bad parameter lists the valid values"
expect_status 2 "unknown parameter" -- "$AALAB" run --methods ssaa:colour=3 --out "$TMP/o" --quiet
expect_stderr "samples" "unknown parameter lists the valid keys"
expect_status 2 "frames not a number" -- "$AALAB" run --frames ten --out "$TMP/o" --quiet
expect_stderr "frames" "bad frames names the field"
expect_status 2 "zero frames" -- "$AALAB" run --frames 0 --out "$TMP/o" --quiet
expect_stderr "frames" "zero frames names the field"
expect_status 2 "odd reference samples" -- "$AALAB" run --reference-samples 7 --out "$TMP/o" --quiet
expect_stderr "reference" "odd reference samples names the field"
expect_status 2 "unknown camera path" -- "$AALAB" run --path nowhere --size 32x18 --reference-samples 2 --out "$TMP/o" --quiet
expect_stderr "path.*nowhere" "unknown path is named"
printf '{"scene": "thin-wires", "frames": "two"}' >"$TMP/job.json"
expect_status 2 "job file with a wrong type" -- "$AALAB" run "$TMP/job.json" --out "$TMP/o" --quiet
expect_stderr "frames" "job file error names the field"
printf '{"scene": ' >"$TMP/broken.json"
expect_status 2 "truncated job file" -- "$AALAB" run "$TMP/broken.json" --out "$TMP/o" --quiet
expect_stderr "broken.json" "truncated job file is named"
expect_status 2 "unknown command" -- "$AALAB" frobnicate
expect_status 0 "run --help" -- "$AALAB" run --help
expect_status 0 "methods" -- "$AALAB" methods
grep -q "ssaa" "$TMP/out" && pass "methods lists ssaa" || fail "methods does not list ssaa"
grep -q "4, 9, 16, 25, 36, 49, 64" "$TMP/out" && pass "methods lists valid values" || fail "methods lacks valid values"
expect_status 0 "methods fxaa taa: only the methods named" -- "$AALAB" methods fxaa taa
[ "$(grep -c '^[a-z]' "$TMP/out")" -eq 2 ] && grep -q "^fxaa$" "$TMP/out" && grep -q "^taa$" "$TMP/out" &&
	pass "lists fxaa and taa alone" || fail "methods fxaa taa: $(grep '^[a-z]' "$TMP/out" | tr '\n' ' ')"
expect_status 2 "methods of an unknown name" -- "$AALAB" methods fxaa nosuch
expect_stderr "^aalab methods: unknown method 'nosuch' \(methods: none, ssaa, " "names it and lists the methods"
expect_status 0 "scenes" -- "$AALAB" scenes
for s in thin-wires hard-edges horizon moving-sphere; do
	grep -q "^$s " "$TMP/out" && pass "scenes lists $s" || fail "scenes does not list $s"
done
# an unknown option or a second name is an error (they were ignored: exit 0 and the whole list)
for cmd in scenes methods suites; do
	expect_status 2 "$cmd --bogus" -- "$AALAB" $cmd --bogus
	expect_stderr "^aalab $cmd: unknown option '--bogus'" "names the option"
done
expect_status 2 "scenes with two names" -- "$AALAB" scenes thin-wires hard-edges
expect_stderr "^aalab scenes: unexpected argument 'hard-edges'" "names the extra argument"
finish
