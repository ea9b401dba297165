#!/usr/bin/python3
"""aalabd under systemd, without systemd: a socket passed as LISTEN_FDS (socket activation) is served,
and sd_notify datagrams arrive on NOTIFY_SOCKET: READY=1, WATCHDOG=1 every WATCHDOG_USEC / 2, RELOADING=1
then READY=1 on SIGHUP, STOPPING=1 on SIGTERM."""
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALABD, Client, check, finish

tmp = tempfile.mkdtemp(prefix="aalabd-systemd.")
proc = None
try:
    listen_path = os.path.join(tmp, "activated.sock")
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(listen_path)
    listener.listen(16)
    notify_path = os.path.join(tmp, "notify.sock")
    notify = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    notify.bind(notify_path)
    notify.settimeout(60)
    env = dict(os.environ, NOTIFY_SOCKET=notify_path, LISTEN_FDS="1", LISTEN_FDNAMES="control",
               WATCHDOG_USEC="400000", STATE_DIRECTORY=os.path.join(tmp, "state"))
    fd = listener.fileno()

    def as_fd3():
        os.dup2(fd, 3)

    log = open(os.path.join(tmp, "log"), "w")
    # the shell sets LISTEN_PID to its own pid, which exec hands to aalabd
    proc = subprocess.Popen(["/bin/sh", "-c", 'LISTEN_PID=$$ WATCHDOG_PID=$$ exec "$0"', AALABD], env=env,
                            preexec_fn=as_fd3, pass_fds=(fd,), stdout=log, stderr=log)
    listener.close()

    def messages(until, timeout=60):
        got = []
        deadline = time.time() + timeout
        while time.time() < deadline:
            try:
                m = notify.recv(4096).decode()
            except socket.timeout:
                break
            got.append(m)
            if until in m:
                break
        return got

    m = messages("READY=1")
    check(m and "READY=1" in m[-1], "READY=1 once listening (%s)" % m[-1:] )
    c = Client(listen_path)
    check(c.request({"op": "ping"}).get("ok"), "the socket passed by LISTEN_FDS is served")
    with open(os.path.join(tmp, "log")) as f:
        check("listening (unix) on systemd:control" in f.read(), "the log names the passed socket")
    w = messages("WATCHDOG=1", timeout=5)
    check(w and "WATCHDOG=1" in w[-1], "WATCHDOG=1 is sent")
    proc.send_signal(signal.SIGHUP)
    r = [x for x in messages("READY=1", timeout=10) if "WATCHDOG" not in x]
    check(r and "RELOADING=1" in r[0] and "READY=1" in r[-1], "SIGHUP: RELOADING=1 then READY=1 (%s)" % r)
    proc.send_signal(signal.SIGTERM)
    s = messages("STOPPING=1", timeout=10)
    check(s and "STOPPING=1" in s[-1], "SIGTERM: STOPPING=1")
    check(proc.wait(60) == 0, "aalabd exits 0")
    check(os.path.exists(listen_path), "a socket systemd passed is not unlinked")
    c.close()
except Exception as e:
    import traceback
    traceback.print_exc()
    check(False, "test ran to the end: %s" % e)
finally:
    if proc and proc.poll() is None:
        proc.kill()
        proc.wait()
    try:
        with open(os.path.join(tmp, "log")) as f:
            text = f.read()
        if "Sanitizer" in text or "runtime error" in text:
            check(False, "sanitizer report:\n" + text[-3000:])
    except OSError:
        pass
    shutil.rmtree(tmp, ignore_errors=True)
finish()
