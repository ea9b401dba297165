#!/usr/bin/python3
"""render-nice: every thread of aalabd but the protocol loop (the worker thread, the device's threads, and
with allow-user-methods the worker process's) runs render-nice levels below the loop, after a job has
compiled and rendered; the loop keeps its own priority; out-of-range values are refused naming the key."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALABD, Daemon, SMALL_JOB, check, finish, wait_state, check_log_and_cleanup, crashed


def nice_values(pid):
    """{tid: nice} of a process's threads (field 19 of /proc/PID/task/TID/stat, counted after the name)."""
    out = {}
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            stat = open("/proc/%d/task/%s/stat" % (pid, tid)).read()
        except FileNotFoundError:
            continue
        out[int(tid)] = int(stat[stat.rindex(")") + 2:].split()[16])
    return out


def worker_processes(pid):
    kids = []
    for p in os.listdir("/proc"):
        if p.isdigit():
            try:
                stat = open("/proc/%s/stat" % p).read()
                cmd = open("/proc/%s/cmdline" % p, "rb").read()
            except (FileNotFoundError, ProcessLookupError):
                continue
            if int(stat[stat.rindex(")") + 2:].split()[1]) == pid and b"--worker-process" in cmd:
                kids.append(int(p))
    return kids


base = os.getpriority(os.PRIO_PROCESS, 0)
for args, label in ((["--render-nice", "7"], "in-process"), (["--render-nice", "7", "--allow-user-methods", "yes"],
                                                             "worker process")):
    d = None
    try:
        d = Daemon(*args)
        c = d.connect()
        job = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=1)})["job"]
        wait_state(c, job, ["done"])
        c.close()
        pid = d.proc.pid
        threads = nice_values(pid)
        check(threads[pid] == base, "%s: the loop thread keeps nice %d (has %d)" % (label, base, threads[pid]))
        others = {t: n for t, n in threads.items() if t != pid}
        if label == "in-process":
            # the worker thread and the device's threads (lavapipe renders on every core)
            check(len(others) >= 3 and all(n >= min(19, base + 7) for n in others.values()),
                  "%s: every other thread at nice %d or lower (Mesa runs one at 19): %s" % (label, min(19, base + 7), others))
        else:
            kids = worker_processes(pid)
            check(len(kids) == 1, "%s: one worker process (%s)" % (label, kids))
            for k in kids:
                kn = nice_values(k)
                check(len(kn) >= 3 and all(n >= min(19, base + 7) for n in kn.values()),
                      "%s: every thread of the worker process at nice %d or lower: %s" % (label, min(19, base + 7), kn))
        d.stop()
        check_log_and_cleanup(d)
    except Exception as e:
        crashed(d, e)

for bad in ("20", "-1", "x"):
    r = subprocess.run([AALABD, "--render-nice", bad, "--check"], capture_output=True, text=True, timeout=60)
    check(r.returncode == 2 and "render-nice" in r.stderr, "--render-nice %s is refused naming the key: %r" %
          (bad, r.stderr.strip()[:200]))
finish()
