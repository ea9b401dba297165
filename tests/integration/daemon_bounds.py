#!/usr/bin/python3
"""aalabd's limits at their exact bounds: every numeric configuration key accepts its minimum and
maximum and refuses one past either (and fractions of whole numbers), naming the key; a job exactly at
max-job-budget is accepted and one over it refused, the budget counting the reference's samples and each
method's; max-queued-jobs refuses the job that would exceed it, not the one before; `list` with a limit
returns exactly the newest that many."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALABD, Daemon, check, check_log_and_cleanup, crashed, finish, wait_state

# name: (minimum, maximum, whole numbers only); from docs/aalabd.8 and daemon/config.c
KEYS = {
    "max-request-bytes": (1024, 1 << 30, True),
    "max-connections": (1, 100000, True),
    "max-jobs-per-client": (1, 1000000, True),
    "max-queued-jobs": (1, 1000000, True),
    "max-job-budget": (1, 1e18, False),
    "idle-timeout": (1, 86400 * 7, True),
    "slow-client-timeout": (1, 86400, True),
    "request-timeout": (1, 86400, True),
    "client-buffer-bytes": (4096, 1 << 30, True),
    "retention-jobs": (0, 10000000, True),
    "retention-bytes": (0, 1e18, True),
    "scene-cache-bytes": (0, 1e18, True),
    "drain-timeout": (0, 86400, True),
}


def text(v):
    return "%d" % v if float(v).is_integer() else repr(v)


def config_check(*args):
    r = subprocess.run([AALABD, "--check"] + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       text=True, timeout=60)
    return r.returncode, r.stderr


d = None
try:
    # every minimum at once, then every maximum (aalabd stops at the first bad value, so one run each)
    for bound in (0, 1):
        args = [a for key, b in KEYS.items() for a in ("--" + key, text(b[bound]))]
        status, err = config_check(*args)
        check(status == 0, "every key at its %s is accepted (%s)" % (("minimum", "maximum")[bound], err.strip()[:200]))
    for key, (lo, hi, whole) in KEYS.items():
        # one past each bound: a whole number, or for the largest values the next that a double can tell apart
        below = lo - 1 if whole else lo / 2
        above = hi + 1 if hi < 2 ** 52 else hi * 1.5
        bad = [text(below), text(above)] + (["%s.5" % text(lo)] if whole else [])
        for v in bad:
            status, err = config_check("--" + key, v)
            check(status == 2 and key in err, "--%s %s is refused, naming the key (exit %d: %s)" %
                  (key, v, status, err.strip().splitlines()[0][:120] if err.strip() else ""))

    # max-job-budget: width x height x frames x (reference samples + timing.repeat x each method's samples);
    # timing.repeat "auto" times one frame 5 times (two frames 3 times)
    job = {"scene": "thin-wires", "size": "8x8", "frames": 1, "reference": {"samples": 4},
           "methods": ["none", "ssaa:4"]}  # 64 x (4 + 5 x (1 + 4)) = 1856
    d = Daemon("--max-job-budget", "1856")
    c = d.connect()
    r = c.request({"op": "submit", "job": job})
    check(r.get("ok"), "a job of budget exactly max-job-budget (1856) is accepted (%s)" % r.get("error"))
    if r.get("ok"):
        wait_state(c, r["job"], ["done", "failed"])
    for what, change in [("two more reference samples", {"reference": {"samples": 6}}),
                         ("ssaa:9 instead of ssaa:4", {"methods": ["none", "ssaa:9"]}),
                         ("a second frame", {"frames": 2})]:
        r = c.request({"op": "submit", "job": dict(job, **change)})
        e = r.get("error", {})
        check(r.get("ok") is False and e.get("code") == "limit" and e.get("path") == "job" and
              "max-job-budget" in e.get("message", ""), "over the budget by %s: refused (%s)" % (what, e))
    c.close()
    check(d.stop() == 0, "aalabd exits 0")
    check_log_and_cleanup(d)
    d = None

    # max-queued-jobs counts queued and running jobs: with 3, the fourth active job is refused
    d = Daemon("--max-queued-jobs", "3")
    c = d.connect()
    long_job = {"scene": "thin-wires", "size": "8x8", "frames": 5000, "reference": {"samples": 2}, "methods": ["none"]}
    ids = []
    for i in range(3):
        r = c.request({"op": "submit", "job": long_job})
        check(r.get("ok"), "active job %d of 3 is accepted (%s)" % (i + 1, r.get("error")))
        ids.append(r.get("job"))
        if i == 0:
            wait_state(c, ids[0], ["running"])
    r = c.request({"op": "submit", "job": long_job})
    e = r.get("error", {})
    check(r.get("ok") is False and e.get("code") == "limit" and "max-queued-jobs" in e.get("message", ""),
          "the fourth is refused by max-queued-jobs (%s)" % (e or r))
    for j in ids:
        c.request({"op": "cancel", "job": j})
    for j in ids:
        wait_state(c, j, ["cancelled", "done", "failed"])

    # list: without a limit every job, oldest first; with a limit the newest that many, in the same order
    all_jobs = [j["id"] for j in c.request({"op": "list"})["jobs"]]
    check(all_jobs == ids, "list shows the three jobs, oldest first (%s)" % all_jobs)
    for limit in (1, 2, 3, 5):
        got = [j["id"] for j in c.request({"op": "list", "limit": limit})["jobs"]]
        check(got == all_jobs[-limit:], "list with limit %d: the newest %d (%s)" % (limit, min(limit, 3), got))
    c.close()
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
