"""Helpers of the daemon tests: start aalabd on a temporary socket and state directory, talk the JSON Lines
protocol of docs/protocol.md, and check results. Standard library only."""
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

TOP_SRC = os.environ.get("top_srcdir") or os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
TOP_BUILD = os.environ.get("top_builddir") or TOP_SRC
AALABD = os.path.join(TOP_BUILD, "aalabd")
AALAB = os.path.join(TOP_BUILD, "aalab")
os.environ.setdefault("AALAB_SCENE_DIR", os.path.join(TOP_SRC, "scenes"))
os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")

# A job that takes about a second on lavapipe.
SMALL_JOB = {"scene": "thin-wires", "methods": ["none", "ssaa:4"], "frames": 2, "size": "64x36",
             "reference": {"samples": 4}}

failures = 0


def check(cond, what):
    global failures
    if cond:
        print("ok:", what)
    else:
        failures += 1
        print("FAIL:", what)
    sys.stdout.flush()
    return cond


def finish():
    sys.exit(1 if failures else 0)


class Daemon:
    """aalabd on a temporary socket; stop() sends SIGTERM and returns the exit status."""

    def __init__(self, *args, tmp=None, http=False, env=None):
        self.tmp = tmp or tempfile.mkdtemp(prefix="aalabd-test.")
        self.own_tmp = tmp is None
        self.socket = os.path.join(self.tmp, "aalabd.sock")
        self.state = os.path.join(self.tmp, "state")
        self.log_path = os.path.join(self.tmp, "aalabd.log")
        self.args = ["--socket", self.socket, "--state-dir", self.state] + list(args)
        if http:
            self.args += ["--http", "127.0.0.1:0"]
        self.env = dict(os.environ, **(env or {}))
        self.proc = None
        self.http_port = None
        self.tcp_port = None
        self.start()

    def start(self):
        self.log = open(self.log_path, "a")
        start = len(self.read_log()) if os.path.exists(self.log_path) else 0
        self.proc = subprocess.Popen([AALABD] + self.args, stdout=self.log, stderr=self.log, env=self.env)
        deadline = time.time() + 60
        while time.time() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError("aalabd exited with %d:\n%s" % (self.proc.returncode, self.read_log()))
            if "aalabd: ready" in self.read_log()[start:]:
                break
            time.sleep(0.05)
        else:
            raise RuntimeError("aalabd did not become ready:\n" + self.read_log())
        for line in self.read_log()[start:].splitlines():
            if line.startswith("aalabd: listening (http) on "):
                self.http_port = int(line.rsplit(":", 1)[1])
            if line.startswith("aalabd: listening (tcp) on "):
                self.tcp_port = int(line.rsplit(":", 1)[1])

    def read_log(self):
        with open(self.log_path) as f:
            return f.read()

    def connect(self, **kw):
        return Client(self.socket, **kw)

    def stop(self, sig=signal.SIGTERM, timeout=60):
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        try:
            status = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            status = self.proc.wait()
            print("aalabd did not stop in time")
        self.log.close()
        return status

    def cleanup(self):
        if self.proc and self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if self.own_tmp:
            shutil.rmtree(self.tmp, ignore_errors=True)


class Client:
    """One protocol connection: send(obj) writes a line, read() returns the next message (and its payload)."""

    def __init__(self, path=None, tcp=None, timeout=60):
        if tcp:
            self.sock = socket.create_connection(tcp, timeout=timeout)
        else:
            self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            self.sock.settimeout(timeout)
            self.sock.connect(path)
        self.buf = b""

    def send_raw(self, data):
        self.sock.sendall(data)

    def send(self, obj, payload=None):
        if payload is not None:
            obj = dict(obj, payload=len(payload))
        self.sock.sendall(json.dumps(obj).encode() + b"\n" + (payload or b""))

    def _fill(self):
        chunk = self.sock.recv(65536)
        if not chunk:
            raise EOFError("connection closed")
        self.buf += chunk

    def read(self):
        while b"\n" not in self.buf:
            self._fill()
        line, self.buf = self.buf.split(b"\n", 1)
        msg = json.loads(line)
        if "payload" in msg:
            while len(self.buf) < msg["payload"]:
                self._fill()
            msg["_payload"], self.buf = self.buf[:msg["payload"]], self.buf[msg["payload"]:]
        return msg

    def request(self, obj, payload=None):
        self.send(obj, payload)
        return self.read()

    def watch(self, job, after=0, frames="none"):
        """Returns the events of a job (until watch_end) and the watch_end message."""
        r = self.request({"op": "watch", "job": job, "after": after, "frames": frames})
        assert r.get("ok"), r
        events = []
        while True:
            m = self.read()
            if m.get("event") == "watch_end":
                return events, m
            events.append(m)

    def close(self):
        self.sock.close()


def wait_state(client, job, states, timeout=120):
    deadline = time.time() + timeout
    last = None
    while time.time() < deadline:
        r = client.request({"op": "status", "job": job})
        last = r["job"]["state"] if r.get("ok") else r
        if r.get("ok") and r["job"]["state"] in states:
            return r["job"]
        time.sleep(0.1)
    raise RuntimeError("job %s did not reach %s (last seen: %s)" % (job, states, last))


def http_get(port, path, method="GET", headers=None):
    import http.client
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
    conn.request(method, path, headers=headers or {})
    r = conn.getresponse()
    body = r.read()
    conn.close()
    return r.status, r.getheader("Content-Type"), body


def crashed(d, e):
    """The test body raised: that is a failure; show the daemon's log."""
    import traceback
    traceback.print_exc()
    check(False, "test ran to the end: %s" % e)
    if d:
        print(d.read_log()[-3000:])


def check_log_and_cleanup(d):
    """Fails on any sanitizer report in the daemon's log, then removes the daemon's files."""
    if d:
        log = d.read_log()
        if "Sanitizer" in log or "runtime error" in log:
            check(False, "sanitizer report in the daemon log:\n" + log[-3000:])
        d.cleanup()
