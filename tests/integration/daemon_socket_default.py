#!/usr/bin/python3
"""aalabd and aalab agree on the default socket without XDG_RUNTIME_DIR (containers, CI, su): the daemon
listens on /tmp/aalabd-UID/aalabd.sock in a folder it creates 0700, and aalab, with no --connect, finds it
there (aalabd(8) --socket, aalab(1) --connect). A fallback folder that is open to others or another
user's is refused, by the daemon and by --check. --check binds every listener it would open: a TCP or HTTP
port another program holds, or a socket another aalabd answers on, fails the check naming the field."""
import os
import shutil
import socket
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALAB, AALABD, Daemon, check, finish, check_log_and_cleanup, crashed

FALLBACK = "/tmp/aalabd-%d" % os.geteuid()
SOCKET = os.path.join(FALLBACK, "aalabd.sock")
ENV = {k: v for k, v in os.environ.items() if k not in ("XDG_RUNTIME_DIR", "RUNTIME_DIRECTORY", "AALAB_CONNECT")}
tmp = tempfile.mkdtemp(prefix="aalabd-socket.")
TOKEN = os.path.join(tmp, "token")
with open(TOKEN, "w") as f:
    f.write("0123456789abcdef0123456789abcdef\n")
os.chmod(TOKEN, 0o600)


def run(cmd, *args):
    try:
        return subprocess.run([cmd] + list(args), capture_output=True, text=True, timeout=120, env=ENV)
    except subprocess.TimeoutExpired:
        return None


def daemon_check(*args):
    return run(AALABD, "--check", "--state-dir", os.path.join(tmp, "check-state"), *args)


d = None
made_fallback = not os.path.exists(FALLBACK)
try:
    if os.path.exists(SOCKET):  # a daemon of this user already there: the test would talk to it
        print("SKIP: %s is in use" % SOCKET)
        sys.exit(77)
    r = daemon_check()
    check(r is not None and r.returncode == 0, "--check without XDG_RUNTIME_DIR: %s" % (r and r.stderr.strip()))
    st = os.lstat(FALLBACK)
    check(st.st_mode & 0o777 == 0o700 and st.st_uid == os.geteuid(),
          "the fallback folder is the user's, 0700 (%03o)" % (st.st_mode & 0o777))
    check(not os.path.exists(SOCKET), "--check leaves no socket behind")

    # the daemon and the CLI, neither told where, find each other
    d = Daemon()  # on a socket of its own, then started again with the defaults
    d.stop()
    d.args = ["--state-dir", d.state]  # no --socket
    d.env = ENV
    d.start()
    check("listening (unix) on %s" % SOCKET in d.read_log(), "the daemon listens on %s" % SOCKET)
    r = run(AALAB, "submit", "--scene", "thin-wires", "--methods", "none", "--size", "32x18",
            "--reference-samples", "2", "--frames", "1")
    check(r is not None and r.returncode == 0 and r.stdout.strip(), "aalab submit finds it: %s %s" %
          (r and r.stdout.strip(), r and r.stderr.strip()))
    r = run(AALAB, "list")
    check(r is not None and r.returncode == 0 and "000001" in r.stdout, "aalab list too: %s" % (r and r.stderr.strip()))
    # a second daemon (another state folder) on the socket the first one answers on: --check fails
    r = daemon_check()
    check(r is not None and r.returncode == 2 and "another aalabd is listening" in r.stderr,
          "--check fails on a socket another aalabd answers on: %s" % (r and r.stderr.strip()))
    check(d.stop() == 0, "daemon stops")

    # a fallback folder that others may enter, or of another user: refused, by --check and at start
    os.chmod(FALLBACK, 0o755)
    r = daemon_check()
    check(r is not None and r.returncode == 2 and FALLBACK in r.stderr and "socket" in r.stderr,
          "an open fallback folder is refused: %s" % (r and r.stderr.strip()))
    r = run(AALABD, "--state-dir", d.state)
    check(r is not None and r.returncode != 0 and FALLBACK in r.stderr, "at start too: %s" % (r and r.stderr.strip()))
    os.chmod(FALLBACK, 0o700)
    if os.geteuid() == 0:
        os.chown(FALLBACK, 65534, 65534)
        r = daemon_check()
        check(r is not None and r.returncode == 2 and "belongs to uid 65534" in r.stderr,
              "another user's fallback folder is refused: %s" % (r and r.stderr.strip()))
        os.chown(FALLBACK, 0, 0)

    # --check binds every listener: a port another program holds fails it, naming the field
    held = socket.socket()
    held.bind(("127.0.0.1", 0))
    held.listen(1)
    port = held.getsockname()[1]
    r = daemon_check("--socket", os.path.join(tmp, "c.sock"), "--tcp", "127.0.0.1:%d" % port, "--token-file", TOKEN)
    check(r is not None and r.returncode == 2 and "tcp:" in r.stderr and str(port) in r.stderr,
          "--check fails on a TCP port in use: %s" % (r and r.stderr.strip()))
    r = daemon_check("--socket", os.path.join(tmp, "c.sock"), "--http", "127.0.0.1:%d" % port)
    check(r is not None and r.returncode == 2 and "http:" in r.stderr and str(port) in r.stderr,
          "--check fails on an HTTP port in use: %s" % (r and r.stderr.strip()))
    held.close()
    r = daemon_check("--socket", os.path.join(tmp, "no-such-folder", "c.sock"))
    check(r is not None and r.returncode == 2 and "no-such-folder" in r.stderr,
          "--check fails on a socket it cannot create: %s" % (r and r.stderr.strip()))
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
    if made_fallback:
        shutil.rmtree(FALLBACK, ignore_errors=True)
finish()
