#!/usr/bin/python3
"""A full disk and a poison job. The state folder is a 2 MiB tmpfs (the test is skipped where it cannot
mount one): a job that fills it fails with `io`, its partial frames are removed, its `failed` state and
event log are written (the reserve file), a restart does not run it again, and the next job runs. A job
during which the daemon is killed max-job-interruptions times in a row is failed with the reason, not
run forever; events carry the run number so a resuming watcher sees the re-run."""
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, SMALL_JOB, check, finish, wait_state, check_log_and_cleanup, crashed

tmp = tempfile.mkdtemp(prefix="aalabd-disk.")
state = os.path.join(tmp, "state")
os.makedirs(state)
if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=2m", "tmpfs", state],
                                       stderr=subprocess.DEVNULL).returncode != 0:
    print("SKIP: cannot mount a 2 MiB tmpfs here (needs root)")
    shutil.rmtree(tmp, ignore_errors=True)
    sys.exit(77)

d = None
try:
    d = Daemon("--max-job-interruptions", "2", tmp=tmp)
    c = d.connect()
    # 160x90 RGBA16F frames are 115 KB each: 3 x 12 of them do not fit in 2 MiB
    big = dict(SMALL_JOB, size="160x90", frames=12, keep_frames=True, linear_frames=True)
    a = c.request({"op": "submit", "job": big})["job"]
    st = wait_state(c, a, ["done", "failed", "cancelled"])
    check(st["state"] == "failed" and st["error"]["code"] == "io",
          "a job that fills the disk fails with io (%s: %s)" % (st["state"], st.get("error")))
    check(d.state not in st["error"]["message"] and "STATE_DIR" in st["error"]["message"],
          "its error names the file under STATE_DIR, not the server's folder")
    jobdir = os.path.join(d.state, "jobs", a)
    left = [p for p in ("frames", "linear", "diff", "flip", "results.json") if os.path.exists(os.path.join(jobdir, p))]
    check(not left, "its partial output is removed (%s)" % left)
    # status says failed only once job.json and the log are written (daemon/worker_run.c): read them at once
    with open(os.path.join(jobdir, "job.json")) as f:
        saved = json.load(f)
    with open(os.path.join(jobdir, "events.jsonl")) as f:
        events = [json.loads(l) for l in f]
    check(saved["state"] == "failed" and saved["error"]["code"] == "io", "job.json says failed, io")
    check(events and events[0]["event"] == "job_started" and events[-1]["event"] == "job_failed",
          "events.jsonl holds the run, ending in job_failed (%d events)" % len(events))
    b = c.request({"op": "submit", "job": SMALL_JOB})
    check(b.get("ok"), "the next submit is accepted (%s)" % b.get("error"))
    st = wait_state(c, b["job"], ["done", "failed", "cancelled"])
    check(st["state"] == "done", "and runs (%s)" % st["state"])
    # the reference store (STATE_DIR/references by default) never takes the last of the state's disk:
    # on 2 MiB every entry would leave less than its 64 MiB margin, so none is kept
    entries = [f for _, _, fs in os.walk(os.path.join(d.state, "references")) for f in fs if f.endswith(".ref")]
    check(not entries, "the reference store keeps nothing on a disk it would fill (%d entries)" % len(entries))
    c.close()

    # restart: the failed job stays failed
    d.stop()
    d.start()
    log = d.read_log()
    check("job %s was interrupted" % a not in log, "a restart does not run the failed job again")
    c = d.connect()
    st = c.request({"op": "status", "job": a})["job"]
    check(st["state"] == "failed" and st["error"]["code"] == "io" and st["error"]["message"],
          "after the restart it says failed, with the reason")
    nxt = c.request({"op": "submit", "job": SMALL_JOB})["job"]
    check(wait_state(c, nxt, ["done", "failed"])["state"] == "done", "the restarted daemon runs the next job")

    # the disk fills up from outside during a job that keeps no frames: nothing of the job's own can be
    # removed to make room, so its failed state is written into the reserve
    # long enough (seconds) that the status poll sees it running before it ends, on a quiet machine too
    j = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=150, keep_frames=False)})["job"]
    wait_state(c, j, ["running"])
    filler = os.path.join(d.state, "filler")
    with open(filler, "wb", buffering=0) as f:
        try:
            while True:
                f.write(b"x" * 4096)
        except OSError:
            pass
    st = wait_state(c, j, ["done", "failed", "cancelled"])
    check(st["state"] == "failed" and st["error"]["code"] == "io",
          "a full disk during a job: it fails with io (%s: %s)" % (st["state"], st.get("error")))
    d.stop()
    with open(os.path.join(d.state, "jobs", j, "job.json")) as f:
        check(json.load(f)["state"] == "failed", "its failed state was written on the full disk (the reserve)")
    os.unlink(filler)  # free the space, restart
    d.start()
    c = d.connect()
    check("job %s was interrupted" % j not in d.read_log(), "after freeing the space and a restart it is not run again")
    st = c.request({"op": "status", "job": j})["job"]
    check(st["state"] == "failed" and "No space left" in st["error"]["message"],
          "it says failed with the reason (%s)" % st["error"]["message"])
    nxt = c.request({"op": "submit", "job": SMALL_JOB})["job"]
    st = wait_state(c, nxt, ["done", "failed"])
    check(st["state"] == "done", "and the next job runs (%s)" % st.get("error"))
    check(os.path.exists(os.path.join(d.state, "reserve")), "the reserve is set aside again")

    # a poison job: the daemon dies during it twice in a row (max-job-interruptions 2)
    slow = dict(SMALL_JOB, frames=40, keep_frames=False)
    p = c.request({"op": "submit", "job": slow})["job"]
    runs = []
    for attempt in range(2):
        wait_state(c, p, ["running"])
        while c.request({"op": "status", "job": p})["job"]["done"] < 2:
            time.sleep(0.02)
        r = c.request({"op": "watch", "job": p, "after": 0})
        runs.append(r.get("run"))
        d.proc.send_signal(signal.SIGKILL)
        d.proc.wait()
        c.close()
        d.start()
        c = d.connect()
    st = c.request({"op": "status", "job": p})["job"]
    check(runs == [1, 2], "each run of the job has its own run number in watch (%s)" % runs)
    check(st["state"] == "failed" and "2 times in a row" in st["error"]["message"],
          "killed during it twice in a row: the job is failed, not run again (%s)" % st.get("error"))
    events, end = c.watch(p)
    check(all(e.get("run") == 2 for e in events), "its events carry run 2")
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    subprocess.run(["umount", state], stderr=subprocess.DEVNULL)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
