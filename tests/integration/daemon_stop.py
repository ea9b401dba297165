#!/usr/bin/python3
"""aalabd stops a job in the middle of a frame (aalabd(8), "Stopping a job"): the GPU work of a frame is
submitted in bounded pieces (the reference's sample batches, each method's render and repeat) and the
worker checks between them, so `cancel`, the drain timeout and a second SIGTERM take effect within a
piece, not at the end of a long frame. An interrupted job stays queued with its frames so far removed,
and runs after a restart. The same with the GPU work in a worker process (allow-user-methods), where the
stop must come from the signal to the process, not from its kill after the cancel grace.

No absolute times: every latency is compared with the time one frame of the same job takes, measured
beside it (a reference frame of many samples, several seconds even on a fast machine)."""
import os
import signal
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, check, finish, wait_state, check_log_and_cleanup, crashed

# a frame is one long reference (512 samples) and a quick method: without pieces, a stop would wait for
# the rest of the frame's reference
LONG = {"scene": "thin-wires", "methods": ["none"], "frames": 3, "size": "480x270",
        "reference": {"samples": 512}, "keep_frames": True}
# a stop must come within this share of one frame's reference time; a piece is 1/30 of it here
SHARE = 0.35


def first_reference_frame(d, job):
    """Waits for the job's first reference_frame event: frame 1's reference is then being rendered (the
    events of frame 0 are sent beside it). Returns that event (its gpu_ms: one frame's reference)."""
    w = d.connect()
    r = w.request({"op": "watch", "job": job, "frames": "none"})
    assert r.get("ok"), r
    while True:
        ev = w.read()
        if ev.get("event") == "reference_frame":
            w.close()
            return ev
        if ev.get("event") in ("watch_end", "job_failed", "job_finished", "job_cancelled"):
            raise RuntimeError("job %s ended before its first reference frame: %s" % (job, ev))


def cancel_latency(d, c, what):
    job = c.request({"op": "submit", "job": LONG})["job"]
    ev = first_reference_frame(d, job)
    frame_s = ev["gpu_ms"] / 1000.0
    t0 = time.time()
    check(c.request({"op": "cancel", "job": job}).get("ok"), "%s: cancel the running job" % what)
    s = wait_state(c, job, ["cancelled", "done", "failed"])
    took = time.time() - t0
    print("measured: %s: cancelled %.2f s after the cancel; one frame's reference takes %.2f s" % (what, took, frame_s))
    check(s["state"] == "cancelled", "%s: the job is cancelled: %s" % (what, s.get("error")))
    check(took < SHARE * frame_s, "%s: within a piece of GPU work, not at the frame's end (%.2f s < %.2f x %.2f s)"
          % (what, took, SHARE, frame_s))
    return frame_s


d = None
try:
    # no store of references: every run of LONG renders its references (a stored one comes at once)
    d = Daemon("--drain-timeout", "1", "--reference-cache", "off")
    c = d.connect()
    frame_s = cancel_latency(d, c, "in the daemon")
    r = c.request({"op": "submit", "job": {"scene": "thin-wires", "methods": ["none"], "frames": 1, "size": "64x36",
                                           "reference": {"samples": 4}}})
    check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "the next job runs")

    # SIGTERM with drain-timeout 1: the job is stopped within a piece after the timeout, stays queued,
    # and its frames so far are gone
    job = c.request({"op": "submit", "job": LONG})["job"]
    first_reference_frame(d, job)
    frames_dir = os.path.join(d.state, "jobs", job, "frames")
    check(os.path.isdir(frames_dir), "frame 0's images are written while the job runs")
    c.close()
    t0 = time.time()
    status = d.stop()
    took = time.time() - t0
    print("measured: SIGTERM with drain-timeout 1: exit %.2f s later; one frame's reference takes %.2f s" %
          (took, frame_s))
    check(status == 0, "the daemon exits 0")
    check(took - 1 < SHARE * frame_s, "after the drain timeout within a piece of GPU work (%.2f s - 1 s)" % took)
    check(not os.path.exists(frames_dir), "the interrupted job's frames are removed")
    d.args[d.args.index("--drain-timeout") + 1] = "600"  # for the second SIGTERM below
    log_start = len(d.read_log())
    d.start()
    c = d.connect()
    st = c.request({"op": "status", "job": job})["job"]
    check(st["state"] in ("queued", "running"), "after the restart the job is queued: %s" % st["state"])
    wait_state(c, job, ["running"])
    ev = first_reference_frame(d, job)
    check(ev["run"] == 2, "and runs again: run %s" % ev["run"])

    # a second SIGTERM while draining: the job stops within a piece, not at the drain timeout
    c.close()
    d.proc.send_signal(signal.SIGTERM)  # drains, for up to 600 s
    deadline = time.time() + 60
    while "aalabd: stopping" not in d.read_log()[log_start:] and time.time() < deadline:
        time.sleep(0.02)  # two signals sent at once may arrive as one
    t0 = time.time()
    status = d.stop()  # a second SIGTERM
    took = time.time() - t0
    print("measured: a second SIGTERM: exit %.2f s later" % took)
    check(status == 0 and took < SHARE * frame_s, "a second SIGTERM stops the job within a piece (%.2f s)" % took)
    check_log_and_cleanup(d)

    # the worker process (allow-user-methods): the cancel reaches it between two pieces of GPU work, well
    # before the cancel grace after which it would be killed
    d = Daemon("--allow-user-methods", "yes", "--job-time-limit", "0", "--reference-cache", "off")
    c = d.connect()
    cancel_latency(d, c, "in the worker process")
    check("did not stop when cancelled" not in d.read_log(), "the worker process stopped the job itself")
    r = c.request({"op": "submit", "job": {"scene": "thin-wires", "methods": ["none"], "frames": 1, "size": "64x36",
                                           "reference": {"samples": 4}}})
    check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "and runs the next job")
    check(len([l for l in d.read_log().splitlines() if " ready in " in l]) == 1, "in the same process")
    c.close()
    check(d.stop() == 0, "daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
