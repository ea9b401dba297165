#!/usr/bin/python3
"""One aalabd per state folder (aalabd(8), FILES): the daemon holds an exclusive lock on STATE_DIR/aalabd.lock
while it runs. A second daemon on the same folder (on another socket) exits 2 naming the folder and the PID
of the daemon that holds it, and so does `--check`; the first one goes on serving. The lock goes with its
holder, however it ends: after a SIGTERM or a kill -9, a new daemon starts on the folder at once."""
import os
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALABD, Daemon, check, finish, check_log_and_cleanup, crashed


def second(d, *extra):
    """aalabd on d's state folder and a socket of its own; returns the CompletedProcess (None if it hung)."""
    try:
        return subprocess.run([AALABD, "--socket", os.path.join(d.tmp, "second.sock"), "--state-dir", d.state]
                              + list(extra), capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return None


d = None
try:
    d = Daemon()
    c = d.connect()
    for what, extra in (("a second daemon", ()), ("--check", ("--check",))):
        r = second(d, *extra)
        msg = r.stderr.strip() if r else "(did not end)"
        check(r is not None and r.returncode == 2, "%s on the same state folder exits 2: %s" % (what, msg))
        check(r is not None and d.state in r.stderr and "PID %d" % d.proc.pid in r.stderr,
              "%s names the folder and the PID that holds it: %s" % (what, msg))
    check(not os.path.exists(os.path.join(d.tmp, "second.sock")), "the second daemon opened no socket")
    check(c.request({"op": "ping"}).get("ok"), "the first daemon goes on serving")
    r = c.request({"op": "submit", "job": {"scene": "thin-wires", "methods": ["none"], "frames": 1, "size": "32x18",
                                           "reference": {"samples": 2}}})
    check(r.get("ok") and r["job"] == "000001", "and numbers its jobs from its own store: %s" % r)
    c.close()
    check(d.stop() == 0, "the first daemon stops")

    # the lock goes with its holder: a clean stop, then a kill -9
    r = second(d, "--check")
    check(r is not None and r.returncode == 0, "--check after the stop: %s" % (r.stderr.strip() if r else "hung"))
    d.start()
    check(d.connect().request({"op": "ping"}).get("ok"), "a new daemon starts on the folder after a stop")
    d.proc.send_signal(signal.SIGKILL)
    d.proc.wait()
    d.log.close()
    d.start()
    check(d.connect().request({"op": "ping"}).get("ok"), "and after a kill -9 of its holder")
    check(d.stop() == 0, "daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
