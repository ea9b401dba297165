#!/usr/bin/python3
"""The job store survives a crash: kill -9 during a job, start aalabd again on the same state directory,
and the interrupted job runs again from the start and completes with all its results; the job queued
behind it runs too. SIGTERM with a job running drains: the job finishes before the daemon exits."""
import json
import os
import re
import signal
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, SMALL_JOB, check, finish, wait_state, check_log_and_cleanup, crashed

TEMP_FILE = re.compile(r"^\..+\.[A-Za-z0-9]{6}$")

d = None
try:
    d = Daemon()
    c = d.connect()
    long_job = dict(SMALL_JOB, frames=12, keep_frames=True)
    a = c.request({"op": "submit", "job": long_job})["job"]
    b = c.request({"op": "submit", "job": SMALL_JOB})["job"]
    wait_state(c, a, ["running"])
    while c.request({"op": "status", "job": a})["job"]["done"] < 4:
        time.sleep(0.02)
    d.proc.send_signal(signal.SIGKILL)
    d.proc.wait()
    c.close()
    with open(os.path.join(d.state, "jobs", a, "job.json")) as f:
        check(json.load(f)["state"] == "running", "after kill -9 the store says job %s was running" % a)
    with open(os.path.join(d.state, "jobs", b, "job.json")) as f:
        check(json.load(f)["state"] == "queued", "and job %s queued" % b)

    # what a writer cut short by the kill leaves: a temporary file beside its target (planted here too,
    # so that the start-up sweep is tested whether or not the kill fell inside a write)
    planted = [os.path.join(d.state, "jobs", a, ".job.json.Crash1"), os.path.join(d.state, "jobs", b, ".results.json.Crash2"),
               os.path.join(d.state, "references", "ab", "." + "ab" * 32 + ".ref.Crash3")]
    for path in planted:
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write("half a file")

    d.start()
    # the store's is gone once the daemon is ready, long before the re-run's first entry is written (a
    # scan at that write would remove it too)
    check(not os.path.exists(planted[2]), "the reference store's temporary file is removed at start-up")
    check("job %s was interrupted; it will run again" % a in d.read_log(), "the restart says it re-runs the job")
    c = d.connect()
    for job in (a, b):
        st = wait_state(c, job, ["done", "failed", "cancelled"])
        check(st["state"] == "done", "job %s completes after the restart" % job)
    events, end = c.watch(a)
    check(events[0]["event"] == "job_started" and events[-1]["event"] == "job_finished" and
          [e["seq"] for e in events] == list(range(1, len(events) + 1)),
          "the re-run's event log is whole: started .. finished, %d events" % len(events))
    with open(os.path.join(d.state, "jobs", a, "results.json")) as f:
        r = json.load(f)
    frames = [len(m["metrics"]["psnr"]["per_frame"]) for m in r["methods"]]
    check(frames == [12, 12], "results.json has all 12 frames of each method")
    pngs = sum(len(f) for _, _, f in os.walk(os.path.join(d.state, "jobs", a, "frames")))
    check(pngs == 12 * 3, "every frame image is stored (%d)" % pngs)
    # atomic writes go through a temporary ".NAME.XXXXXX" beside NAME (aa_file_write_atomic); those of
    # writers that died are removed at start-up (job folders, the reference store) or when the job runs again
    leftovers = [f for _, _, fs in os.walk(d.state) for f in fs if TEMP_FILE.match(f)]
    check(not leftovers, "no temporary files left, the 3 planted ones included (%s)" % leftovers)

    # SIGTERM while a job runs: the daemon finishes it, then exits 0. The job is big enough to be seen
    # running (6 frames at 64x36 from a warm store can start and finish between two polls)
    job = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=30, size="160x90")})["job"]
    wait_state(c, job, ["running"])
    check(d.stop() == 0, "SIGTERM during a job: aalabd exits 0")
    with open(os.path.join(d.state, "jobs", job, "job.json")) as f:
        check(json.load(f)["state"] == "done", "the running job was finished before exit")
    log = d.read_log()
    check("stopping" in log, "the log says it is stopping")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
