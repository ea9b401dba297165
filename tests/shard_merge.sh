#!/bin/sh
# Shards and merge without Slurm (docs/farm.md): a job run whole and as 3 shards merged gives the same
# results (none and fxaa to the last digit, flicker across the shard borders included; taa equal where its
# warm-up reaches the job's first frame, within the stated tolerance where it does not); merge names the
# missing frames and exits 2, and succeeds once that shard ran; duplicated shards, shards of another job
# or warm-up, and folders that are not shards are refused; aalab slurm's two scripts, run by sh as Slurm
# would run them (SLURM_ARRAY_TASK_ID), merge into the same results; a suite split by whole cases merges
# into the unsharded suite's results; bad flags exit 2 naming the flag.
. "$(dirname "$0")/lib.sh"
PY=/usr/bin/python3
CHECK="$top_srcdir/tests/integration/shard_check.py"

# 12 frames in shards of 4; warm-up 4: shard 1 warms up from frame 0 (equal), shard 2 from frame 4 (not)
cat >"$TMP/job.json" <<'JSON'
{"scene": "moving-sphere", "methods": ["none", "fxaa", "taa"], "frames": 12, "size": "160x90",
 "reference": {"samples": 16}, "shard": {"warmup": 4}}
JSON
expect_status 0 "the unsharded run" -- "$AALAB" run "$TMP/job.json" --local --quiet --out "$TMP/whole"
for i in 0 1 2; do
	expect_status 0 "shard $i of 3" -- "$AALAB" run "$TMP/job.json" --shard "$i/3" --quiet --out "$TMP/s$i"
done
$PY - "$TMP" <<'PY' && pass "each shard is an ordinary result of its frames, naming the whole job" || fail "shard results.json"
import json, sys
t = sys.argv[1]
whole = json.load(open(t + "/whole/results.json"))
for i, first in enumerate((0, 4, 8)):
    r = json.load(open("%s/s%d/results.json" % (t, i)))
    assert r["first_frame"] == first and r["frames"] == 4, (r["first_frame"], r["frames"])
    assert [f["frame"] for f in r["methods"][0]["frames"]] == list(range(first, first + 4))
    s = r["shard"]
    assert (s["index"], s["count"], s["warmup"]) == (i, 3, 4) and s["frames"] == {"first": first, "count": 4}, s
    assert s["job_hash"] == whole["job_hash"] != r["job_hash"], "shard.job_hash is the whole job's"
    assert s["job"] == whole["job"]
    assert len(s["error_threshold_curves"][2]) == 4 and len(s["error_threshold_curves"][2][0]) == 101
    # the first frame of a later shard has no frame before it in the shard: its flicker is the merge's
    assert (r["methods"][0]["frames"][0]["flicker"] is None) == True
PY

expect_status 0 "merge of the 3 shards" -- "$AALAB" merge --out "$TMP/merged" "$TMP/s2" "$TMP/s0" "$TMP/s1"
grep -q "merged 3 shards" "$TMP/out" && pass "merge prints the table and the shard count" || fail "merge output"
[ -f "$TMP/merged/report.html" ] && [ -f "$TMP/merged/frames/taa/0011.png" ] &&
	pass "report and every frame's images, numbered as the unsharded run's" || fail "merged files"
# taa: shards 0 and 1 equal (their warm-up reaches frame 0), shard 2 within the warm-up-4 tolerance
$PY "$CHECK" "$TMP/whole" "$TMP/merged" --exact none,fxaa --tolerant "taa=3,0.05" >"$TMP/check" &&
	pass "merged = unsharded: none and fxaa to the last digit, taa within 3 dB after 4 warm-up frames" ||
	fail "merged results differ from the unsharded run"
sed 's/^/  | /' "$TMP/check"
$PY - "$TMP" <<'PY' && pass "taa: frames 0-7 equal, frames 8-11 (warmed up from frame 4) not" || fail "taa frames"
import json, sys
t = sys.argv[1]
w = json.load(open(t + "/whole/results.json"))["methods"][2]["frames"]
m = json.load(open(t + "/merged/results.json"))["methods"][2]["frames"]
assert all(w[k]["mse"] == m[k]["mse"] for k in range(8)), "frames 0-7"
assert all(w[k]["mse"] != m[k]["mse"] for k in range(8, 12)), "frames 8-11 equal: was the warm-up ignored?"
PY

# a missing shard: named by its frames, exit 2; a folder without results.json counts as missing
expect_status 2 "merge without shard 1" -- "$AALAB" merge --out "$TMP/m2" "$TMP/s0" "$TMP/s2" "$TMP/nothing"
expect_stderr "missing frames 4-7 \(shard 1 of 3\)" "merge names the missing frames"
expect_stderr "nothing: no results.json" "merge names the folder without results"
[ ! -e "$TMP/m2" ] && pass "nothing is written" || fail "a partial merge was written"
expect_status 2 "merge of shard 0 alone" -- "$AALAB" merge --out "$TMP/m2" "$TMP/s0"
expect_stderr "missing frames 4-7 \(shard 1 of 3\), 8-11 \(shard 2 of 3\)" "every missing shard is named"
expect_status 0 "shard 1 run again" -- "$AALAB" run "$TMP/job.json" --shard 1/3 --quiet --out "$TMP/s1b"
expect_status 0 "merge with it" -- "$AALAB" merge --out "$TMP/m2" "$TMP/s0" "$TMP/s1b" "$TMP/s2"
$PY "$CHECK" "$TMP/whole" "$TMP/m2" --exact none,fxaa >/dev/null && pass "and it merges as before" ||
	fail "merge after re-running a shard"

expect_status 2 "a shard given twice" -- "$AALAB" merge --out "$TMP/m3" "$TMP/s0" "$TMP/s1" "$TMP/s1b" "$TMP/s2"
expect_stderr "s1 and .*s1b are both shard 1 of 3" "names both folders"
sed 's/"frames": 12/"frames": 13/' "$TMP/job.json" >"$TMP/other.json"
expect_status 0 "a shard of another job" -- "$AALAB" run "$TMP/other.json" --shard 1/3 --quiet --out "$TMP/o1"
expect_status 2 "merge with it" -- "$AALAB" merge --out "$TMP/m3" "$TMP/s0" "$TMP/o1" "$TMP/s2"
expect_stderr "o1 is shard 1 of 3 of job sha256:[0-9a-f]{64} .*: not shards of one job" "names the foreign shard"
sed 's/"warmup": 4/"warmup": 3/' "$TMP/job.json" >"$TMP/warm3.json"
expect_status 0 "a shard with another warm-up" -- "$AALAB" run "$TMP/warm3.json" --shard 1/3 --quiet --out "$TMP/w1"
expect_status 2 "merge with it" -- "$AALAB" merge --out "$TMP/m3" "$TMP/s0" "$TMP/w1" "$TMP/s2"
expect_stderr "warm-up 3.*warm-up 4|warm-up 4.*warm-up 3" "names the warm-ups"
expect_status 2 "an unsharded result is not a shard" -- "$AALAB" merge --out "$TMP/m3" "$TMP/whole"
expect_stderr "not the results of a shard" "says so"
expect_status 2 "merge without --out" -- "$AALAB" merge "$TMP/s0"

# a suite is split by whole cases, balanced by frames x pixels
cat >"$TMP/suite.json" <<'JSON'
{"suite": "shardtest", "scenes": ["thin-wires", "moving-sphere", "cutout-fence"], "sizes": ["64x36", "96x54"],
 "frames": 2, "reference": {"samples": 4}, "methods": ["none", "fxaa", "taa"]}
JSON
expect_status 0 "the suite unsharded" -- "$AALAB" run "$TMP/suite.json" --local --quiet --out "$TMP/suite"
for i in 0 1 2; do
	expect_status 0 "suite shard $i of 3" -- "$AALAB" run "$TMP/suite.json" --shard "$i/3" --quiet --out "$TMP/u$i"
done
$PY - "$TMP" <<'PY' && pass "suite shards: two whole cases each, in order" || fail "suite shards"
import json, sys
for i, scene in enumerate(("thin-wires", "moving-sphere", "cutout-fence")):
    r = json.load(open("%s/u%d/results.json" % (sys.argv[1], i)))
    assert [c["id"] for c in r["cases"]] == [scene + "/default/64x36", scene + "/default/96x54"], r["cases"]
    assert r["shard"]["cases"] == {"first": 2 * i, "count": 2} and "frames" not in r["shard"]
PY
expect_status 0 "merge of the suite's shards" -- "$AALAB" merge --out "$TMP/suite-merged" "$TMP/u0" "$TMP/u1" "$TMP/u2"
$PY "$CHECK" --all "$TMP/suite" "$TMP/suite-merged" >"$TMP/check" &&
	pass "merged suite = unsharded suite: every value but times (taa too: whole cases need no warm-up)" ||
	{ fail "merged suite"; cat "$TMP/check"; }
[ -f "$TMP/suite-merged/cases/moving-sphere_default_96x54/frames/taa/0001.png" ] &&
	[ -f "$TMP/suite-merged/cases/cutout-fence_default_64x36/report.html" ] &&
	pass "the cases' folders, images and reports" || fail "merged suite files"
expect_status 2 "a suite without shard 1" -- "$AALAB" merge --out "$TMP/sm2" "$TMP/u0" "$TMP/u2"
expect_stderr "missing cases moving-sphere/default/64x36, moving-sphere/default/96x54 \(shard 1 of 3\)" \
	"names the missing cases"
expect_status 2 "more shards than cases" -- "$AALAB" run "$TMP/suite.json" --shard 0/7 --quiet --out "$TMP/x"
expect_stderr "7 shards of a suite of 6 cases" "says why"

# --shard errors
expect_status 2 "--shard 3/3" -- "$AALAB" run "$TMP/job.json" --shard 3/3 --quiet --out "$TMP/x"
expect_stderr "^aalab run: --shard: shard 3 of 3 does not exist; valid: 0 to 2" "names the flag and the range"
expect_status 2 "--shard 1/x" -- "$AALAB" run "$TMP/job.json" --shard 1/x --quiet --out "$TMP/x"
expect_stderr "--shard: expected I/N" "says the form"
expect_status 2 "more shards than frames" -- "$AALAB" run "$TMP/job.json" --shard 0/13 --quiet --out "$TMP/x"
expect_stderr "13 shards of 12 frames" "says why"
echo '{"shard": {"warmup": -2}}' >"$TMP/bad.json"
expect_status 2 "shard.warmup -2" -- "$AALAB" run "$TMP/bad.json" --shard 0/1 --quiet --out "$TMP/x"
expect_stderr "shard.warmup: -2 is out of range" "names the field"

# aalab slurm: the scripts, run as Slurm runs them
expect_status 0 "aalab slurm writes the scripts" -- "$AALAB" slurm "$TMP/job.json" --shards 3 --out "$TMP/farm" \
	--partition gpu --gres gpu:1 --time 10:00
F=$(cd "$TMP/farm" && pwd -P)
grep -q "^#SBATCH --array=0-2$" "$F/shards.sbatch" && grep -q "^#SBATCH --gres=gpu:1$" "$F/shards.sbatch" &&
	grep -q "^#SBATCH --partition=gpu$" "$F/shards.sbatch" && grep -q "^#SBATCH --time=10:00$" "$F/shards.sbatch" &&
	grep -q "^#SBATCH --requeue$" "$F/shards.sbatch" &&
	grep -q -- "--shard \"\$SLURM_ARRAY_TASK_ID/3\" --out \"$F/shards/\$SLURM_ARRAY_TASK_ID\"" "$F/shards.sbatch" &&
	pass "shards.sbatch: an array of 3, requeued, gres, partition and time" ||
	{ fail "shards.sbatch"; cat "$F/shards.sbatch"; }
grep -q "^#SBATCH --kill-on-invalid-dep=yes$" "$F/merge.sbatch" && ! grep -q gres "$F/merge.sbatch" &&
	grep -q "merge --out '$F/merged'" "$F/merge.sbatch" && pass "merge.sbatch: merges into merged/, no GPU" ||
	{ fail "merge.sbatch"; cat "$F/merge.sbatch"; }
grep -q "sbatch --dependency=afterok:\$id $F/merge.sbatch" "$TMP/out" && pass "prints how to submit both" ||
	{ fail "aalab slurm output"; cat "$TMP/out"; }
$PY -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['frames'] == 12 and j['shard'] == {'warmup': 4}" \
	"$F/job.json" && pass "job.json: the job in canonical form" || fail "job.json"
for i in 0 1 2; do
	SLURM_ARRAY_TASK_ID=$i sh "$F/shards.sbatch" >"$TMP/task$i.log" 2>&1 || fail "array task $i"
done
expect_status 0 "merge.sbatch" -- sh "$F/merge.sbatch"
$PY "$CHECK" "$TMP/whole" "$F/merged" --exact none,fxaa >/dev/null && pass "the scripts' merge = the unsharded run" ||
	fail "the scripts' merged results"
# a job file named by a relative path, whose scene file is relative to it: the tasks run elsewhere, so
# job.json names the scene file by its absolute path, and a task started from / finds it
mkdir -p "$TMP/rel/jobs"
cp "$top_srcdir/scenes/spinning-wheel.json" "$TMP/rel/my-scene.json" # (no asset files)
echo '{"scene": "../my-scene.json", "frames": 2, "size": "32x18", "reference": {"samples": 4}, "methods": ["none"]}' \
	>"$TMP/rel/jobs/rel.json"
(cd "$TMP/rel" && "$AALAB" slurm jobs/rel.json --shards 1 --out farm >"$TMP/out" 2>&1) &&
	$PY -c "import json,sys; s=json.load(open(sys.argv[1]))['scene']; assert s.startswith('/') and s.endswith('/my-scene.json'), s" \
		"$TMP/rel/farm/job.json" && pass "aalab slurm: a relative scene file is written by its absolute path" ||
	{ fail "relative scene path in job.json"; cat "$TMP/out" "$TMP/rel/farm/job.json"; }
(cd / && SLURM_ARRAY_TASK_ID=0 sh "$TMP/rel/farm/shards.sbatch" >"$TMP/rel-task.log" 2>&1) &&
	pass "and the task, started from /, renders it" || { fail "task of the relative-scene job"; tail -5 "$TMP/rel-task.log"; }
echo '{"scene": "../missing.json", "frames": 2, "size": "32x18", "methods": ["none"]}' >"$TMP/rel/jobs/missing.json"
(cd "$TMP/rel" && "$AALAB" slurm jobs/missing.json --shards 1 --out farm2 >"$TMP/out" 2>&1); rc=$?
[ $rc -ne 0 ] && grep -q "^aalab slurm: scene: cannot use the scene file 'jobs/../missing.json'" "$TMP/out" &&
	pass "a missing scene file is refused, naming the field and the file" || { fail "missing scene file (exit $rc)"; cat "$TMP/out"; }
expect_status 2 "aalab slurm again into the same folder" -- "$AALAB" slurm "$TMP/job.json" --shards 3 --out "$F"
expect_status 2 "--gres with a space" -- "$AALAB" slurm "$TMP/job.json" --shards 3 --out "$TMP/f2" --gres "gpu 1"
expect_stderr "^aalab slurm: --gres: " "names the flag"
expect_status 2 "--shards 0" -- "$AALAB" slurm "$TMP/job.json" --shards 0 --out "$TMP/f2"
expect_status 2 "--shards 13 of 12 frames" -- "$AALAB" slurm "$TMP/job.json" --shards 13 --out "$TMP/f2"
expect_stderr "^aalab slurm: --shards: 13 shards of 12 frames" "names the flag"
finish
