#!/usr/bin/python3
"""The token file's rules (aalabd(8), --token-file), the same at start, with --check and on SIGHUP: the first
line, spaces and tabs around it removed, is the token; it must have 16 to 255 characters (a hello, at most
1 MiB, carries it whole), and the file must be a regular file of the daemon's user that its group and
others cannot read. A reload that breaks a rule keeps the token in use and logs why."""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALABD, Client, Daemon, check, finish, check_log_and_cleanup, crashed

TOKEN = "0123456789abcdef0123456789abcdef"
tmp = tempfile.mkdtemp(prefix="aalabd-token.")


def token_file(name, text, mode=0o600):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    os.chmod(path, mode)
    return path


def check_token(path):
    r = subprocess.run([AALABD, "--check", "--socket", os.path.join(tmp, "c.sock"), "--state-dir",
                        os.path.join(tmp, "c-state"), "--tcp", "127.0.0.1:0", "--token-file", path],
                       capture_output=True, text=True, timeout=120)
    return r.returncode, r.stderr.split("\n")[0]


def hello(d, token):
    c = Client(tcp=("127.0.0.1", d.tcp_port), timeout=30)
    ok = c.request({"op": "hello", "version": 1, "token": token}).get("ok")
    c.close()
    return ok


d = None
try:
    cases = [("whitespace only", token_file("blank", " " * 40 + "\n"), "at least 16 characters"),
             ("too short after trimming", token_file("short", "   0123456789   \n"), "at least 16 characters"),
             ("longer than a token may be", token_file("long", "x" * (2600 * 1024) + "\n"), "longer than 255"),
             ("256 characters", token_file("long256", "y" * 256 + "\n"), "longer than 255"),
             ("readable by the group", token_file("group", TOKEN + "\n", 0o640), "readable or writable by others")]
    if os.geteuid() == 0:
        other = token_file("other", TOKEN + "\n")
        os.chown(other, 65534, 65534)
        cases.append(("owned by another user", other, "belongs to uid 65534"))
    for what, path, needle in cases:
        rc, msg = check_token(path)
        check(rc == 2 and needle in msg and "token-file" in msg, "--check refuses a token file %s: %s" % (what, msg))
    rc, msg = check_token(token_file("max", "z" * 255 + "\n"))
    check(rc == 0, "a token of 255 characters is accepted: %s" % msg)
    good = token_file("token", "  \t" + TOKEN + " \t\n")
    rc, msg = check_token(good)
    check(rc == 0, "spaces around a good token do not count: %s" % msg)

    d = Daemon("--tcp", "127.0.0.1:0", "--token-file", good)
    check(hello(d, TOKEN), "the trimmed token is the token")
    check(not hello(d, "  \t" + TOKEN), "the untrimmed text is not")
    # reloads that break a rule keep the token in use and say why
    for what, text, mode, needle in (("whitespace only", " " * 40 + "\n", 0o600, "at least 16 characters"),
                                     ("too long", "x" * 4096 + "\n", 0o600, "longer than 255"),
                                     ("group-readable", "fedcba9876543210fedcba9876543210\n", 0o640, "readable or")):
        with open(good, "w") as f:
            f.write(text)
        os.chmod(good, mode)
        start = len(d.read_log())
        d.proc.send_signal(signal.SIGHUP)
        deadline = time.time() + 60
        while "configuration reloaded" not in d.read_log()[start:] and time.time() < deadline:
            time.sleep(0.05)
        log = d.read_log()[start:]
        check("keeping the token in use" in log and needle in log, "a %s reload is logged with why: %s" %
              (what, [l for l in log.splitlines() if "token" in l]))
        check(hello(d, TOKEN), "and the old token is still the token")
    check(d.stop() == 0, "daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
