#!/bin/sh
# The client's service commands against a real aalabd: submit, watch, status, list, cancel, get, with
# --connect and --json; `aalab run` uses the daemon when one answers and runs in-process with --local.
. "$(dirname "$0")/../lib.sh"
# the daemon's scenes: the shipped ones and one whose mesh file is missing (it fails when it runs)
cp -r "$AALAB_SCENE_DIR" "$TMP/scenes" && AALAB_SCENE_DIR="$TMP/scenes"
printf '{"objects": [{"mesh": {"type": "file", "path": "missing.obj"}}], "camera": {"position": [0, 0, 5], "target": [0, 0, 0]}}\n' \
	>"$TMP/scenes/lost-mesh.json"
start_daemon
C="--connect unix:$sock"
job="--scene thin-wires --methods none,ssaa:4 --frames 2 --size 64x36 --reference-samples 4"

expect_status 0 "submit prints a job id" -- "$AALAB" submit $job $C
id=$(cat "$TMP/out")
echo "$id" | grep -Eq '^[0-9]{6}$' && pass "job id $id" || fail "job id '$id'"
expect_status 0 "watch follows it to the end" -- "$AALAB" watch "$id" $C
grep -q "job_finished" "$TMP/out" && pass "watch prints plain lines to job_finished" || fail "watch output: $(cat "$TMP/out")"
# the last line: state, wall time, where the results are and the verdict, as results.json says it
headline=$("$AALAB" get "$id" --json $C | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["verdict"]["headline"])')
tail -1 "$TMP/out" | grep -Eq "^job $id done in [0-9]+s; results: aalab get $id \(results.json, report.html\); verdict: " &&
	tail -1 "$TMP/out" | grep -qF "verdict: $headline" && pass "watch ends with state, wall time, results and verdict" ||
	fail "watch's last line: $(tail -1 "$TMP/out") (verdict: $headline)"
# submit --watch outside a terminal follows the job as watch does (it once printed only the id)
expect_status 0 "submit --watch" -- "$AALAB" submit $job --watch $C
head -1 "$TMP/out" | grep -Eq '^[0-9]{6}$' && grep -q " frame 1 ssaa:4 " "$TMP/out" && grep -q "job_finished" "$TMP/out" &&
	tail -1 "$TMP/out" | grep -q " done in .*verdict: " &&
	pass "prints the id, then a line per event to job_finished, then the last line" || fail "submit --watch output: $(cat "$TMP/out")"
expect_status 0 "submit --watch --quiet" -- "$AALAB" submit $job --watch --quiet $C
[ "$(wc -l <"$TMP/out")" -eq 1 ] && pass "prints only the id" || fail "submit --watch --quiet output: $(cat "$TMP/out")"
expect_status 0 "watch --after 3 --json" -- "$AALAB" watch "$id" --after 3 --json $C
/usr/bin/python3 -c '
import json, sys
ev = [json.loads(l) for l in open(sys.argv[1])]
assert ev[0]["seq"] == 4 and ev[-1]["event"] == "job_finished", ev[0]
' "$TMP/out" && pass "--after resumes at event 4, as JSON lines" || fail "watch --after --json: $(head -c 300 "$TMP/out")"
expect_status 0 "status" -- "$AALAB" status "$id" $C
grep -q "done" "$TMP/out" && grep -q "ssaa:4" "$TMP/out" && pass "status shows done and the summary" || fail "status: $(cat "$TMP/out")"
# timing.repeat "auto": 2 frames x 3 repeats gives each method 6 >= 5 timed renders
grep -q "^job $id: done, 14 of 14 renders done$" "$TMP/out" && pass "and counts renders (2 frames x (reference + 2 methods x 3 repeats))" ||
	fail "status progress line: $(grep '^job' "$TMP/out")"
head -1 "$TMP/out" | grep -qF "verdict: $headline" && pass "status prints the verdict first" || fail "status's first line: $(head -1 "$TMP/out")"
grep -q "^warnings (" "$TMP/out" && tail -2 "$TMP/out" | grep -q "what to do: " && pass "and its warnings last (a 4-sample reference)" ||
	fail "status warnings: $(tail -3 "$TMP/out")"
expect_status 0 "status --json" -- "$AALAB" status "$id" --json $C
/usr/bin/python3 -c 'import json,sys; assert json.load(open(sys.argv[1]))["state"] == "done"' "$TMP/out" && pass "status --json parses" || fail "status --json"
expect_status 0 "list" -- "$AALAB" list $C
grep -q "$id *done" "$TMP/out" && pass "list shows the job" || fail "list: $(cat "$TMP/out")"
expect_status 0 "list --state done --json" -- "$AALAB" list --state done --json $C
expect_status 0 "get downloads the results" -- "$AALAB" get "$id" --out "$TMP/got" $C
for f in results.json report.html frames/reference/0000.png frames/ssaa_4/0001.png diff/none/0000.png; do
	[ -s "$TMP/got/$f" ] && pass "got $f" || fail "get did not write $f"
done
expect_status 0 "get --file results.json" -- "$AALAB" get "$id" --file results.json $C
cmp -s "$TMP/out" "$TMP/got/results.json" && pass "get --file prints the file" || fail "get --file differs"
expect_status 2 "status of an unknown job" -- "$AALAB" status 999999 $C
expect_stderr "aalab status: job: no job '999999'" "the error names the field"
# a job that fails when it runs: its error names the field once (it said "objects[0].mesh.path: FILE:
# objects[0].mesh.path: ..."), in submit --watch and in run through the daemon
for cmd in "submit --watch" "run --out $TMP/lost"; do
	expect_status 1 "$cmd of a scene whose mesh file is missing" -- "$AALAB" $cmd --scene lost-mesh --frames 1 --size 32x18 \
		--reference-samples 2 --methods none $C
	expect_stderr "job [0-9]+ failed: [^ ]*lost-mesh.json: objects\[0\]\.mesh\.path: file 'missing.obj' not found" "names the file and the field"
	[ "$(grep -o 'objects\[0\]\.mesh\.path' "$TMP/err" | wc -l)" -eq 1 ] && pass "the field once" || fail "the field twice: $(cat "$TMP/err")"
done
expect_status 2 "submit a bad job" -- "$AALAB" submit --size 0x5 $C
expect_stderr "aalab submit: job.size: " "the daemon's error names job.size"
expect_status 1 "no daemon on another socket" -- "$AALAB" list --connect "unix:$TMP/none.sock"
expect_stderr "cannot connect to $TMP/none.sock" "and says so"

# cancel: a long job, cancelled while queued or running
expect_status 0 "submit a long job" -- "$AALAB" submit $job --frames 400 $C
long=$(cat "$TMP/out")
expect_status 0 "cancel it" -- "$AALAB" cancel "$long" $C
# the state the cancel led to: a running job stops after its frame, and cancel waits for it
grep -qx "job $long: cancelled" "$TMP/out" && pass "cancel prints the new state" || fail "cancel printed: $(cat "$TMP/out")"
expect_status 1 "watch of a cancelled job exits 1" -- "$AALAB" watch "$long" $C
expect_stderr "was cancelled" "watch says it was cancelled"
tail -1 "$TMP/out" | grep -Eq "^job $long cancelled( in [0-9hms]+)?$" && pass "and its last line says so" || fail "watch's last line: $(tail -1 "$TMP/out")"
expect_status 0 "submit another long job" -- "$AALAB" submit $job --frames 400 $C
long=$(cat "$TMP/out")
expect_status 0 "cancel --no-wait" -- "$AALAB" cancel "$long" --no-wait $C
grep -Eqx "job $long: (queued|running|cancelled)" "$TMP/out" && pass "prints the state at once" || fail "cancel --no-wait: $(cat "$TMP/out")"
"$AALAB" watch "$long" --quiet $C
expect_status 2 "cancel of a job that has ended" -- "$AALAB" cancel "$long" $C
expect_stderr "already cancelled" "says it has ended"

# a scene file given to submit goes with the job (the daemon knows scenes by name)
cp "$AALAB_SCENE_DIR/spinning-wheel.json" "$TMP/my-scene.json"
expect_status 0 "submit --scene FILE --watch" -- "$AALAB" submit --scene "$TMP/my-scene.json" --methods none --frames 1 \
	--size 32x18 --reference-samples 2 --watch --quiet $C

# run: through the daemon ($AALAB_CONNECT), and in-process with --local
AALAB_CONNECT="unix:$sock" expect_status 0 "run through the daemon" -- "$AALAB" run $job --out "$TMP/remote"
grep -q "aalab run: job [0-9]* on aalabd" "$TMP/err" && pass "run says it used aalabd" || fail "run did not use aalabd: $(cat "$TMP/err")"
grep -q "aalab run: rendering 14/14 (100%, ETA 0s)" "$TMP/err" && ! grep -q "rendering" "$TMP/out" &&
	pass "and its progress, outside a terminal, as lines on stderr" || fail "run via daemon, progress: $(cat "$TMP/err")"
[ -s "$TMP/remote/results.json" ] && [ -s "$TMP/remote/frames/none/0000.png" ] && pass "run wrote results and frames" || fail "run via daemon: missing files"
head -1 "$TMP/out" | grep -q "^verdict: " && grep -q "^ssaa:4 " "$TMP/out" && pass "run prints the verdict, then the table" ||
	fail "run table: $(cat "$TMP/out")"
cp "$TMP/out" "$TMP/remote.txt"
AALAB_CONNECT="unix:$sock" expect_status 0 "run --local" -- "$AALAB" run $job --local --out "$TMP/local" --quiet
# the same table layout from the daemon and from this process (the numbers differ: times are measured)
[ "$(sed -n '/^method /p' "$TMP/out")" = "$(sed -n '/^method /p' "$TMP/remote.txt")" ] && pass "the same table header both ways" ||
	fail "headers differ: $(grep '^method ' "$TMP/out") / $(grep '^method ' "$TMP/remote.txt")"
grep -q "on aalabd" "$TMP/err" && fail "--local used the daemon" || pass "--local runs in this process"
for f in frames/ssaa_4/0001.png frames/reference/0000.png; do
	cmp -s "$TMP/remote/$f" "$TMP/local/$f" && pass "$f is identical from daemon and in-process" || fail "$f differs"
done

kill -TERM $daemon
wait $daemon
status=$?
[ $status -eq 0 ] && pass "aalabd exits 0 on SIGTERM" || { fail "aalabd exit $status"; tail -20 "$TMP/daemon.log"; }
finish
