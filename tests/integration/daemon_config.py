#!/usr/bin/python3
"""Start-up checks and what a scene name may reach: `aalabd --check` runs every check start-up runs (a TCP
listener without a token file, a token file others can read, a state folder that cannot be written, a bad
address), a loose token file is refused at start and on reload (the token in use stays), and a scene name
that is a symbolic link out of the scene folder is refused without quoting the file it points to."""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALABD, Daemon, Client, SMALL_JOB, check, finish, check_log_and_cleanup, crashed, wait_state

TOKEN = "config-test-token-0123456789"
d = None
tmp = tempfile.mkdtemp(prefix="aalabd-config.")


def aalabd_check(*args):
    r = subprocess.run([AALABD, "--socket", os.path.join(tmp, "check.sock"), "--state-dir",
                        os.path.join(tmp, "state")] + list(args) + ["--check"],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    return r.returncode, r.stdout.decode()


try:
    token = os.path.join(tmp, "token")
    with open(token, "w") as f:
        f.write(TOKEN + "\n")
    os.chmod(token, 0o600)

    rc, out = aalabd_check("--tcp", "127.0.0.1:0")
    check(rc != 0 and "token file is required" in out, "--check: TCP without a token file is not ok (%d)" % rc)
    rc, out = aalabd_check("--tcp", "127.0.0.1:0", "--token-file", token)
    check(rc == 0 and "configuration ok" in out, "--check: TCP with a 0600 token file is ok")
    os.chmod(token, 0o644)
    rc, out = aalabd_check("--tcp", "127.0.0.1:0", "--token-file", token)
    check(rc != 0 and "chmod 600" in out, "--check: a token file others can read is not ok")
    os.chmod(token, 0o640)  # aalabd.8: its group may not read it either
    rc, out = aalabd_check("--tcp", "127.0.0.1:0", "--token-file", token)
    check(rc != 0 and "chmod 600" in out, "--check: a token file its group can read is not ok")
    rc, out = aalabd_check("--http", "127.0.0.1:notaport")
    check(rc != 0 and "http" in out, "--check: a bad HTTP address is not ok")
    # options: an unknown one, one without its value and a stray word each say which (they all once said
    # "unexpected argument ... (options take a value)")
    for args, said in ((["--bogus"], "unknown option '--bogus'"), (["--bogus", "1"], "unknown option '--bogus'"),
                       (["--socket"], "option '--socket' needs a value"), (["foo"], "unexpected argument 'foo'")):
        r = subprocess.run([AALABD, "--check"] + args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60)
        rc, out = r.returncode, r.stdout.decode()
        check(rc == 2 and said in out, "aalabd %s: exit 2, %s (%d: %s)" % (" ".join(args), said, rc, out.strip()[:80]))
    rc, out = aalabd_check("--device", "no-such-gpu-here")
    check(rc != 0 and "device" in out, "--check: a device that is not there is not ok (%s)" % out.strip()[:80])
    r = subprocess.run([AALABD, "--socket", os.path.join(tmp, "c.sock"), "--state-dir",
                        os.path.join(token, "state"), "--check"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    check(r.returncode != 0 and b"state-dir" in r.stdout, "--check: a state folder that cannot be created is not ok")
    try:
        Daemon("--tcp", "127.0.0.1:0", "--token-file", token, tmp=tmp).cleanup()
        check(False, "aalabd refuses to start with a loose token file")
    except RuntimeError as e:
        check("chmod 600" in str(e), "aalabd refuses to start with a loose token file")
    os.chmod(token, 0o600)

    # a loose token file on reload: refused, and the token in use stays (authentication stays on)
    scenes = os.path.join(tmp, "scenes")
    shutil.copytree(os.environ["AALAB_SCENE_DIR"], scenes)
    secret = os.path.join(tmp, "outside.json")
    with open(secret, "w") as f:
        f.write("SECRET-BYTES-OUTSIDE do not show me\n")
    os.symlink(secret, os.path.join(scenes, "passwd.json"))
    os.symlink(os.path.join(scenes, "thin-wires.json"), os.path.join(scenes, "wires-link.json"))
    d = Daemon("--tcp", "127.0.0.1:0", "--token-file", token, tmp=tmp, env={"AALAB_SCENE_DIR": scenes})
    os.chmod(token, 0o644)
    d.proc.send_signal(signal.SIGHUP)
    deadline = time.time() + 10
    while "keeping the token in use" not in d.read_log() and time.time() < deadline:
        time.sleep(0.05)
    check("keeping the token in use" in d.read_log(), "a reload with a loose token file says it keeps the token")
    t = Client(tcp=("127.0.0.1", d.tcp_port))
    r = t.request({"op": "ping"})
    check(r.get("error", {}).get("code") == "unauthorized", "TCP still needs the token after that reload")
    r = t.request({"op": "hello", "version": 1, "token": TOKEN})
    check(r.get("ok"), "and the token still works")
    t.close()

    # scene names stay inside the scene folder
    c = d.connect()
    r = c.request({"op": "submit", "job": dict(SMALL_JOB, scene="passwd")})
    msg = str(r)
    check(not r.get("ok") and r["error"]["path"] == "job.scene", "a scene linked out of the folder is refused (%s)" %
          r.get("error"))
    check("SECRET" not in msg and tmp not in msg, "the error quotes neither the file nor server paths")
    r = c.request({"op": "submit", "job": dict(SMALL_JOB, scene="wires-link", frames=1)})
    check(r.get("ok"), "a link that stays inside the scene folder is fine")
    if r.get("ok"):
        check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "and its job runs")
    c.close()
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
