#!/usr/bin/python3
"""HTTP request heads as RFC 9112 has them: a bare LF is taken as a line end, and a request without Host
on HTTP/1.1, a header line without a colon or with space before it, obsolete line folding, a bare CR and
a NUL are refused with 400 at once (not after request-timeout), closing the connection. Then watchers:
ten watchers that stop reading rgba8 frames cost the event loop no more than idle ones (ping p99 within
2x of the figure measured in the same run with the same job and no watchers)."""
import os
import socket
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, SMALL_JOB, check, finish, wait_state, check_log_and_cleanup, crashed


def http_raw(port, data, timeout=3.0):
    """Sends data, returns (reply, seconds until the daemon closed), or (reply, None) if it did not close."""
    s = socket.create_connection(("127.0.0.1", port))
    s.settimeout(timeout)
    t0 = time.time()
    s.sendall(data)
    reply = b""
    try:
        while True:
            chunk = s.recv(65536)
            if not chunk:
                return reply, time.time() - t0
            reply += chunk
    except socket.timeout:
        return reply, None
    finally:
        s.close()


def ping_p99(path, count):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.connect(path)
    s.settimeout(10)
    times = []
    for _ in range(count):
        t0 = time.perf_counter()
        s.sendall(b'{"op":"ping"}\n')
        buf = b""
        while b"\n" not in buf:
            buf += s.recv(4096)
        times.append((time.perf_counter() - t0) * 1000)
        time.sleep(0.003)
    s.close()
    times.sort()
    return times[int(len(times) * 0.99) - 1], times[len(times) // 2]


d = None
try:
    d = Daemon("--request-timeout", "20", "--client-buffer-bytes", "1048576", http=True)
    port = d.http_port
    reply, took = http_raw(port, b"GET /healthz HTTP/1.1\nHost: a\n\n")
    check(reply.startswith(b"HTTP/1.1 200") and reply.endswith(b"ok\n"), "a bare-LF request is answered")
    reply, took = http_raw(port, b"GET /healthz HTTP/1.0\r\n\r\n")
    check(reply.startswith(b"HTTP/1.1 200") and took is not None, "HTTP/1.0 needs no Host, and closes")
    refused = {
        "no Host on HTTP/1.1": b"GET /healthz HTTP/1.1\r\n\r\n",
        "two Host headers": b"GET /healthz HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n",
        "a header line without a colon": b"GET /healthz HTTP/1.1\r\nHost: a\r\nno colon here\r\n",
        "space before the colon": b"GET /healthz HTTP/1.1\r\nHost : a\r\n",
        "obsolete line folding": b"GET /healthz HTTP/1.1\r\nHost: a\r\nX-A: 1\r\n  x: continued\r\n",
        "a bare CR": b"GET /healthz HTTP/1.1\r\nHost: a\rX: y\r\n",
        "a NUL byte": b"GET /\x00 HTTP/1.1",
        "a request line that is not one": b"\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03\n",
        "a bad Content-Length": b"GET / HTTP/1.1\r\nHost: a\r\nContent-Length: 1x\r\n\r\n",
    }
    for what, data in refused.items():
        reply, took = http_raw(port, data)
        check(reply.startswith(b"HTTP/1.1 400") and took is not None and took < 1.0,
              "%s: 400 at once and closed (%s)" % (what, "%.2f s" % took if took is not None else "kept open"))
    reply, took = http_raw(port, b"GET /healthz HTTP/2.0\r\nHost: a\r\n\r\n")
    check(reply.startswith(b"HTTP/1.1 505"), "HTTP/2.0 in a request line: 505")
    reply, took = http_raw(port, b"GET /" + b"a" * 3000 + b" HTTP/1.1\r\n")
    check(reply.startswith(b"HTTP/1.1 414"), "a target over 2048 bytes: 414")
    reply, took = http_raw(port, b"GET /healthz HTTP/1.1\r\nHost: a\r\nX: " + b"b" * 20000)
    check(reply.startswith(b"HTTP/1.1 431"), "a header over 16 KiB: 431")
    # pipelined keep-alive requests with a bare LF between them still work
    reply, took = http_raw(port, b"GET /healthz HTTP/1.1\r\nHost: a\r\n\r\nGET /healthz HTTP/1.1\nHost: a\nConnection: close\n\n")
    check(reply.count(b"HTTP/1.1 200") == 2 and took is not None, "two pipelined requests, the second closes")

    # stalled watchers: a running job, first with no watchers, then with ten that read nothing. 320x180
    # rgba8 frames (230 KB) against 1 MiB of client buffer: a stalled watcher's buffer is nearly full, so
    # every later frame of the job is one it cannot take. The machine is shared: a round whose figures
    # were disturbed is run again from the start, up to three rounds; a loop that pays for stalled
    # watchers fails every round.
    c = d.connect()
    for attempt in range(3):
        job = c.request({"op": "submit", "job": dict(SMALL_JOB, size="320x180", frames=3000, keep_frames=True)})["job"]
        wait_state(c, job, ["running"])
        while c.request({"op": "status", "job": job})["job"]["done"] < 10:
            time.sleep(0.05)
        idle_p99, idle_p50 = ping_p99(d.socket, 600)
        stalled = []
        for _ in range(10):
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
            s.connect(d.socket)
            s.sendall(b'{"op":"watch","job":"%s","frames":"rgba8"}\n' % job.encode())
            stalled.append(s)
        time.sleep(1.0)  # their buffers fill; from here on every frame is one they cannot take
        busy_p99, busy_p50 = ping_p99(d.socket, 600)
        running = c.request({"op": "status", "job": job})["job"]["state"] == "running"
        c.request({"op": "cancel", "job": job})
        for s in stalled:
            s.close()
        print("round %d: ping p99 %.2f ms idle, %.2f ms with 10 stalled rgba8 watchers (p50 %.2f / %.2f ms)" %
              (attempt + 1, idle_p99, busy_p99, idle_p50, busy_p50))
        if busy_p99 <= 2 * idle_p99 + 2.0:  # 2x, with 2 ms of slack for sub-millisecond figures
            break
    check(running, "the job was still running when measured")
    check(busy_p99 <= 2 * idle_p99 + 2.0, "10 stalled rgba8 watchers: ping p99 %.2f ms within 2x of idle %.2f ms"
          % (busy_p99, idle_p99))
    c.close()
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
