#!/usr/bin/env python3
"""aalab on a real Slurm (docs/farm.md): a throwaway one-node cluster (munged, slurmctld -D, slurmd -D
with a generated slurm.conf, tests/integration/slurm_cluster.py) runs a 4-shard job submitted by
`aalab slurm --submit`. One shard's task fails (its output folder is taken by a file), so Slurm cancels
the merge job that depended on every shard (afterok); `aalab merge` names the missing frames and exits 2;
the shard is submitted again with the merge after it, and the merged results equal an unsharded run's
(none and fxaa to the last digit, taa within the tolerance of docs/farm.md). Every shard shares one store
of references: the same job submitted again renders no reference (the store's counts show only hits,
and the merged results say 24 of 24 frames came from it, with the same metrics). Every daemon is stopped by
its PID, also when a check fails. Skips (exit 77) where Slurm cannot run (not root, not installed),
except when AALAB_REQUIRE_SLURM is set, as .ci/run does: there it fails."""
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import shard_check  # noqa: E402
import slurm_cluster  # noqa: E402

TOP_SRC = os.environ.get("top_srcdir") or os.path.abspath(os.path.join(HERE, "..", ".."))
TOP_BUILD = os.environ.get("top_builddir") or TOP_SRC
AALAB = os.path.join(TOP_BUILD, "aalab")
os.environ.setdefault("AALAB_SCENE_DIR", os.path.join(TOP_SRC, "scenes"))
os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")

# 24 frames at 160x90 in 4 shards of 6; taa's default warm-up (32) reaches frame 0 from every shard
JOB = {"scene": "moving-sphere", "methods": ["none", "fxaa", "taa"], "frames": 24, "size": "160x90",
       "reference": {"samples": 16}}
TAA_TOLERANCE = (0.05, 0.002)  # dB, SSIM per frame: docs/farm.md, "Warm-up"

failures = 0


def check(cond, what):
    global failures
    print(("ok: " if cond else "FAIL: ") + what)
    sys.stdout.flush()
    failures += 0 if cond else 1
    return cond


def aalab(*args, env=None):
    return subprocess.run([AALAB] + list(args), capture_output=True, text=True, env=env, timeout=600)


def stats(refs):
    out = aalab("cache", "stats", "--json", "--reference-cache", refs)
    return json.loads(out.stdout) if out.returncode == 0 else {}


def resubmit(cluster, job, tmp, refs):
    """The job again, into another farm folder, with the same store: every reference is a hit."""
    before = stats(refs)
    farm = os.path.join(tmp, "farm2")
    sub = aalab("slurm", job, "--shards", "4", "--out", farm, "--time", "10:00", "--submit",
                "--reference-cache", refs, env=cluster.env)
    ids = [line.split()[3] for line in sub.stdout.splitlines() if line.startswith(("shards:", "merge:"))]
    if not check(sub.returncode == 0 and len(ids) == 2, "submitted again: " + sub.stdout.strip() + sub.stderr):
        return False
    cluster.wait_jobs(ids, timeout=300)
    after = stats(refs)
    hits, misses = after.get("hits", 0) - before.get("hits", 0), after.get("misses", 0) - before.get("misses", 0)
    check(hits == 24 and misses == 0, "the store's counts over the second submission: %d hits, %d misses" %
          (hits, misses))
    path = os.path.join(farm, "merged", "results.json")
    if not check(os.path.exists(path), "the second submission merged"):
        return False
    with open(path) as f:
        cache = json.load(f)["reference"]["cache"]
    check(cache and cache["hits"] == 24 and cache["misses"] == 0, "merged reference.cache: %s" % cache)
    fails = shard_check.compare(os.path.join(tmp, "farm", "merged"), os.path.join(farm, "merged"),
                                ["none", "fxaa", "taa"], {})
    return hits == 24 and misses == 0 and fails == 0


def main():
    why = slurm_cluster.missing_tools()
    if why:
        print(("FAIL: " if os.environ.get("AALAB_REQUIRE_SLURM") else "SKIP: ") + "no Slurm here: " + why)
        return 1 if os.environ.get("AALAB_REQUIRE_SLURM") else 77
    tmp = tempfile.mkdtemp(prefix="aalab-slurm-test.")
    job = os.path.join(tmp, "job.json")
    with open(job, "w") as f:
        json.dump(JOB, f)
    t0 = time.time()
    with slurm_cluster.Cluster(tmp=os.path.join(tmp, "cluster")) as cluster:
        print("cluster up in %.1f s (%s, %d CPUs); daemons %s" % (time.time() - t0, cluster.host, cluster.cpus,
              ", ".join("%s %d" % (n, p.pid) for n, p in cluster.procs.items())))
        # the unsharded run, in this process, while the cluster is there
        whole = aalab("run", job, "--local", "--quiet", "--out", os.path.join(tmp, "whole"))
        check(whole.returncode == 0, "the unsharded run" + (": " + whole.stderr if whole.returncode else ""))

        farm = os.path.join(tmp, "farm")
        os.makedirs(os.path.join(farm, "shards"))
        with open(os.path.join(farm, "shards", "2"), "w") as f:
            f.write("not a folder: shard 2's task fails\n")
        refs = os.path.join(tmp, "references")  # the farm's shared store of references
        sub = aalab("slurm", job, "--shards", "4", "--out", farm, "--time", "10:00", "--submit", "--force",
                    "--reference-cache", refs, env=cluster.env)
        ids = [line.split()[3] for line in sub.stdout.splitlines() if line.startswith(("shards:", "merge:"))]
        check(sub.returncode == 0 and len(ids) == 2,
              "aalab slurm --submit queues the array and the merge: " + sub.stdout.strip().replace("\n", " | ") +
              sub.stderr)
        if len(ids) != 2:
            return 1
        cluster.wait_jobs(ids[:1], timeout=300)
        try:  # the merge's dependency can never be met: Slurm cancels it (--kill-on-invalid-dep) at once
            cluster.wait_jobs(ids[1:], timeout=60)
            cancelled = True
        except RuntimeError:
            cancelled = False
        log = lambda name: open(os.path.join(farm, "logs", name)).read() \
            if os.path.exists(os.path.join(farm, "logs", name)) else ""
        check(all(os.path.exists(os.path.join(farm, "shards", str(i), "results.json")) for i in (0, 1, 3)),
              "shards 0, 1 and 3 ran as array tasks")
        check("aalab run: rendering" in log("shard-0.log") and "(100%, ETA" in log("shard-0.log"),
              "a shard's log shows its progress to 100%: " + log("shard-0.log").strip()[-200:])
        check("not a folder" in log("shard-2.log") or "shards/2" in log("shard-2.log"),
              "shard 2's task failed: " + log("shard-2.log").strip()[:200])
        check(cancelled and not os.path.exists(os.path.join(farm, "merged")) and not log("merge.log"),
              "Slurm cancelled the merge (afterok, --kill-on-invalid-dep) without running it")

        dirs = [os.path.join(farm, "shards", str(i)) for i in range(4)]
        m = aalab("merge", "--out", os.path.join(tmp, "m1"), *dirs)
        check(m.returncode == 2 and "missing frames 12-17 (shard 2 of 4)" in m.stderr,
              "aalab merge names the missing frames, exit %d: %s" % (m.returncode, m.stderr.strip()))

        os.remove(os.path.join(farm, "shards", "2"))
        again = cluster.run("sbatch", "--parsable", "--array=2", os.path.join(farm, "shards.sbatch")).stdout.strip()
        merge = cluster.run("sbatch", "--parsable", "--dependency=afterok:" + again,
                            os.path.join(farm, "merge.sbatch")).stdout.strip()
        cluster.wait_jobs([again, merge], timeout=300)
        check(os.path.exists(os.path.join(farm, "merged", "results.json")),
              "shard 2 again (sbatch --array=2), then the merge job: " + " | ".join(log("merge.log").strip().splitlines()[-3:-1]))
        if os.path.exists(os.path.join(farm, "merged", "results.json")):
            fails = shard_check.compare(os.path.join(tmp, "whole"), os.path.join(farm, "merged"), ["none", "fxaa"],
                                        {"taa": TAA_TOLERANCE})
            check(fails == 0, "the merged results are the unsharded run's")
            check(resubmit(cluster, job, tmp, refs), "the same job submitted again renders no reference")
        pids = [p.pid for p in cluster.procs.values()]
    check(not any(os.path.exists("/proc/%d" % pid) for pid in pids), "every daemon stopped (PIDs %s)" % pids)
    print("%.1f s in all" % (time.time() - t0))
    if not failures:
        subprocess.run(["rm", "-rf", tmp])
    else:
        print("kept " + tmp)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
