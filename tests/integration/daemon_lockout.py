#!/usr/bin/python3
"""No lockout: every connection the daemon means to close is closed once its reply is sent (HTTP
Connection: close, a TCP hello with a wrong token, a bad payload size), so 1,000 of them in a row leave
the daemon's descriptors at their baseline and a Unix ping answers at once. Limits are per listener and
per peer, and a TCP client that never says hello is dropped after hello-timeout."""
import os
import shutil
import socket
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, check, finish, check_log_and_cleanup, crashed

TOKEN = "lockout-test-token-0123456789"


def fd_count(pid):
    return len(os.listdir("/proc/%d/fd" % pid))


def read_to_eof(sock, timeout=5.0):
    """Everything the daemon sends until it closes; None if it keeps the connection open."""
    sock.settimeout(timeout)
    data = b""
    try:
        while True:
            chunk = sock.recv(65536)
            if not chunk:
                return data
            data += chunk
    except socket.timeout:
        return None
    except ConnectionResetError:
        return data


def http_close(port):
    s = socket.create_connection(("127.0.0.1", port))
    s.sendall(b"GET /healthz HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
    reply = read_to_eof(s)
    s.close()
    return reply is not None and reply.startswith(b"HTTP/1.1 200")


def wrong_token(port):
    s = socket.create_connection(("127.0.0.1", port))
    s.sendall(b'{"op":"hello","version":1,"token":"not-the-token-at-all"}\n')
    reply = read_to_eof(s)
    s.close()
    return reply is not None and b'"unauthorized"' in reply


def bad_payload(path):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.connect(path)
    s.sendall(b'{"op":"submit","job":{},"payload":-5}\n')
    reply = read_to_eof(s)
    s.close()
    return reply is not None and b'"payload"' in reply


def unix_ping_ms(path):
    t0 = time.time()
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(5)
    s.connect(path)
    s.sendall(b'{"op":"ping"}\n')
    reply = s.recv(4096)
    s.close()
    return (time.time() - t0) * 1000, b'"pong":true' in reply


d = None
tmp = tempfile.mkdtemp(prefix="aalabd-lockout.")
try:
    tmp_token = os.path.join(tmp, "token")
    fd = os.open(tmp_token, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    os.write(fd, (TOKEN + "\n").encode())
    os.close(fd)
    # small limits: without the fix the 21st closed-but-not-closed connection would already be refused
    d = Daemon("--tcp", "127.0.0.1:0", "--token-file", tmp_token, "--max-connections", "20",
               "--max-connections-per-peer", "8", "--hello-timeout", "1", http=True, tmp=tmp)
    os.unlink(tmp_token)
    pid = d.proc.pid
    ms, ok = unix_ping_ms(d.socket)
    time.sleep(0.2)
    baseline = fd_count(pid)

    t0 = time.time()
    results = {"http": 0, "token": 0, "payload": 0}
    for i in range(1000):
        kind = ("http", "token", "payload")[i % 3]
        try:
            if kind == "http":
                results[kind] += http_close(d.http_port)
            elif kind == "token":
                results[kind] += wrong_token(d.tcp_port)
            else:
                results[kind] += bad_payload(d.socket)
        except OSError:
            pass  # refused and closed before the request was sent: counted as not answered
    took = time.time() - t0
    check(results == {"http": 334, "token": 333, "payload": 333},
          "1,000 connections the daemon ends are each answered and closed (%s, %.1f s)" % (results, took))
    ms, ok = unix_ping_ms(d.socket)
    check(ok and ms < 1000, "then a Unix ping answers at once (%.0f ms)" % ms)
    deadline = time.time() + 3
    while fd_count(pid) > baseline and time.time() < deadline:
        time.sleep(0.05)
    check(fd_count(pid) == baseline, "the daemon's descriptors are back to the baseline (%d, baseline %d)"
          % (fd_count(pid), baseline))

    # per listener: HTTP's 20 slots all taken (by 3 peers' worth of idle connections from one address
    # would hit the per-peer limit first, so check that limit, then that Unix is untouched)
    idle_http = [socket.create_connection(("127.0.0.1", d.http_port)) for _ in range(8)]
    extra = socket.create_connection(("127.0.0.1", d.http_port))
    reply = read_to_eof(extra) or b""
    check(reply.startswith(b"HTTP/1.1 503") and b"max-connections-per-peer" in reply,
          "the 9th idle HTTP connection from one address is refused (per peer)")
    extra.close()
    ms, ok = unix_ping_ms(d.socket)
    check(ok and ms < 1000, "idle HTTP connections leave the Unix socket answering (%.0f ms)" % ms)
    unix_conns = []
    for _ in range(8):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.connect(d.socket)
        unix_conns.append(s)
    extra = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    extra.connect(d.socket)
    reply = read_to_eof(extra) or b""
    check(b'"limit"' in reply and b"uid:%d" % os.getuid() in reply,
          "the 9th Unix connection of one uid is refused, naming the uid")
    extra.close()
    for s in idle_http + unix_conns:
        s.close()

    # per listener: with the per-peer limit out of the way, 20 HTTP connections fill HTTP's budget only
    d.stop()
    d = Daemon("--max-connections", "20", http=True, tmp=d.tmp)
    idle_http = [socket.create_connection(("127.0.0.1", d.http_port)) for _ in range(20)]
    extra = socket.create_connection(("127.0.0.1", d.http_port))
    reply = read_to_eof(extra) or b""
    check(reply.startswith(b"HTTP/1.1 503"), "the 21st HTTP connection is refused (max-connections 20)")
    extra.close()
    ms, ok = unix_ping_ms(d.socket)
    check(ok and ms < 1000, "with HTTP full, a Unix ping still answers at once (%.0f ms)" % ms)
    for s in idle_http:
        s.close()
    d.stop()

    # hello deadline: a TCP client that says nothing is dropped after hello-timeout
    fd = os.open(tmp_token, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    os.write(fd, (TOKEN + "\n").encode())
    os.close(fd)
    d = Daemon("--tcp", "127.0.0.1:0", "--token-file", tmp_token, "--hello-timeout", "1", tmp=d.tmp)
    os.unlink(tmp_token)
    silent = socket.create_connection(("127.0.0.1", d.tcp_port))
    t0 = time.time()
    reply = read_to_eof(silent, timeout=6)
    took = time.time() - t0
    check(reply is not None and b"hello-timeout" in reply and took < 4,
          "a TCP client without hello is dropped after hello-timeout (%.1f s)" % took)
    silent.close()
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
