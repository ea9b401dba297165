#!/bin/sh
# aalab run --out DIR: a non-empty folder that is not an aalab result is refused, an earlier result is
# replaced only with --force, results appear in DIR only when complete (written beside it and renamed),
# a failed job leaves DIR as it was, and Ctrl-C says what was kept.
. "$(dirname "$0")/lib.sh"
JOB="--local --quiet --scene thin-wires --methods none --frames 1 --size 32x18 --reference-samples 2"

mkdir "$TMP/mine" && echo "my notes" >"$TMP/mine/notes.txt"
expect_status 2 "a non-empty folder that is not an aalab result is refused" -- "$AALAB" run $JOB --out "$TMP/mine"
expect_stderr "mine' is not empty and is not an aalab result" "and the error says why"
[ "$(ls -A "$TMP/mine")" = "notes.txt" ] && pass "the folder is untouched" || fail "the folder was changed: $(ls -A "$TMP/mine")"
expect_status 2 "even with --force" -- "$AALAB" run $JOB --out "$TMP/mine" --force
echo x >"$TMP/file"
expect_status 2 "a file is refused" -- "$AALAB" run $JOB --out "$TMP/file"

mkdir "$TMP/empty"
expect_status 0 "an empty folder is used" -- "$AALAB" run $JOB --out "$TMP/empty"
[ -f "$TMP/empty/results.json" ] && pass "it holds results.json" || fail "no results.json in the empty folder"
expect_status 0 "a new folder is made" -- "$AALAB" run $JOB --out "$TMP/res"
[ -f "$TMP/res/results.json" ] && [ -f "$TMP/res/report.html" ] && pass "with results.json and report.html" \
	|| fail "results missing in $TMP/res"
grep -q "results: $TMP/res/results.json" "$TMP/out" && pass "the table names DIR" || fail "the table does not name DIR"
ls -A "$TMP" | grep -q "aalab-partial\|aalab-old" && fail "temporary folders left: $(ls -A "$TMP")" || pass "no temporary folder left"

touch "$TMP/res/marker"
expect_status 2 "an earlier aalab result is not replaced without --force" -- "$AALAB" run $JOB --out "$TMP/res"
expect_stderr "holds an earlier aalab result; --force replaces it" "and the error says --force"
[ -f "$TMP/res/marker" ] && pass "the earlier result is untouched" || fail "the earlier result was changed"
expect_status 0 "--force replaces it" -- "$AALAB" run $JOB --out "$TMP/res" --force
[ ! -f "$TMP/res/marker" ] && [ -f "$TMP/res/results.json" ] && pass "whole: no file of the earlier run is left" \
	|| fail "the old and the new run are mixed"

# a job that fails (an unknown path) leaves nothing behind
expect_status 2 "a failing job" -- "$AALAB" run $JOB --path nowhere --out "$TMP/failed"
[ ! -e "$TMP/failed" ] && ! ls -A "$TMP" | grep -q "failed.aalab-partial" && pass "leaves no folder" \
	|| fail "a failed job left $(ls -A "$TMP")"

# Ctrl-C during a run: exit 130, DIR untouched, the message names what was kept
"$AALAB" run --local --quiet --scene thin-wires --methods none,ssaa:4 --frames 200 --size 64x36 \
	--reference-samples 4 --out "$TMP/res" --force >"$TMP/out" 2>"$TMP/err" &
pid=$!
for i in $(seq 1 300); do
	ls "$TMP"/.res.aalab-partial.*/frames/none 2>/dev/null | grep -q png && break
	sleep 0.1
done
kill -INT $pid
wait $pid
status=$?
[ "$status" -eq 130 ] && pass "Ctrl-C: exit 130" || fail "Ctrl-C: exit $status"
expect_stderr "interrupted; kept [0-9]+ of 600 frames' images, written so far, in .*\.res\.aalab-partial\.[A-Za-z0-9]+ \(no results.json\); .*res still holds the earlier result" \
	"Ctrl-C says what was kept and where"
[ -f "$TMP/res/results.json" ] && [ ! -f "$TMP/res/marker" ] && pass "DIR still holds the earlier complete result" \
	|| fail "DIR was changed by the interrupted run"

# the same without images: nothing is counted, and a job run in-process does not "go on in aalabd"
"$AALAB" run --local --quiet --no-images --scene thin-wires --methods none,ssaa:4 --frames 5000 --size 160x90 \
	--reference-samples 4 --out "$TMP/res" --force >"$TMP/out" 2>"$TMP/err" &
pid=$!
for i in $(seq 1 300); do
	ls -d "$TMP"/.res.aalab-partial.* >/dev/null 2>&1 && break
	sleep 0.1
done
sleep 1
kill -INT $pid
wait $pid
status=$?
[ "$status" -eq 130 ] && pass "Ctrl-C without images: exit 130" || fail "Ctrl-C without images: exit $status"
expect_stderr "interrupted; what was written so far is in .*\.res\.aalab-partial\.[A-Za-z0-9]+ \(no results.json\); " \
	"Ctrl-C without images says where the partial folder is"
if grep -q aalabd "$TMP/err"; then fail "an in-process run speaks of aalabd: $(cat "$TMP/err")"
else pass "an in-process run does not speak of aalabd"; fi
finish
