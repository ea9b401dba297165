#!/usr/bin/python3
"""Fair output (aalabd(8), client-buffer-bytes): a connection handles at most a few requests a turn of the
loop, and none while more than 64 KiB of its replies wait unsent, so clients that pipeline large replies
(`list` of many jobs) and never read them delay no one else's replies: they are paused (their further
requests wait unread) and dropped after slow-client-timeout. A paused client that starts reading gets
every reply, in order. Latencies are compared with the idle ping of the same daemon, measured beside."""
import json
import os
import socket
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, check, finish, check_log_and_cleanup, crashed

NON_READERS = 8
PINGS = 400
LIST = b'{"op": "list"}\n'


def ping_times(c, n):
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        assert c.request({"op": "ping"}).get("ok")
        times.append(time.perf_counter() - t0)
    return sorted(times)


def p99(times):
    return times[int(len(times) * 0.99) - 1]


def flood(sock, lines):
    """Pipelines `lines` list requests and reads nothing; ends when the daemon stops reading or drops it."""
    try:
        sock.sendall(LIST * lines)
    except OSError:
        pass


d = None
try:
    d = Daemon("--slow-client-timeout", "3")
    c = d.connect()
    # 150 jobs, so that a list reply is large
    for i in range(150):
        r = c.request({"op": "submit", "job": {"scene": "thin-wires", "methods": ["none"], "frames": 1,
                                               "size": "32x18", "reference": {"samples": 2}}})
        c.request({"op": "cancel", "job": r["job"]})
    lists = []
    for _ in range(5):
        t0 = time.perf_counter()
        jobs = len(c.request({"op": "list"})["jobs"])
        lists.append(time.perf_counter() - t0)
    one_list = sorted(lists)[2]
    print("measured: a list of %d jobs takes %.2f ms (median of 5)" % (jobs, one_list * 1000))

    idle = ping_times(c, PINGS)
    # each non-reader asks for far more replies than a connection keeps unsent before it is paused
    lines = 4000
    floods = []
    for _ in range(NON_READERS):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.connect(d.socket)
        s.settimeout(30)
        t = threading.Thread(target=flood, args=(s, lines), daemon=True)
        t.start()
        floods.append((s, t))
    # while they are being paused: each handles a few lists, in turns with everyone else
    t0 = time.perf_counter()
    first = []
    while time.perf_counter() - t0 < 1.0:
        first += ping_times(c, 1)
    first.sort()
    # once they are paused (a second later, well before slow-client-timeout drops them), they cost nothing
    busy = ping_times(c, PINGS)
    still_there = d.read_log().count("nothing read for 3 s") == 0
    print("measured: ping p99 idle %.3f ms; with %d clients that do not read, in their first second max "
          "%.2f ms over %d pings, then p99 %.3f ms (max %.2f ms)" % (p99(idle) * 1000, NON_READERS,
                                                                    first[-1] * 1000, len(first),
                                                                    p99(busy) * 1000, busy[-1] * 1000))
    check(still_there, "the %d non-readers were still connected while the pings were measured" % NON_READERS)
    # a ping waits at most for the requests being handled in one turn (eight lists, one per non-reader),
    # never for a client's pipeline; margin measured under the sanitizer build beside a full `make check`
    check(first[-1] < 32 * one_list, "while they are paused the longest ping wait is below 32 lists "
          "(%.2f ms < 32 x %.2f ms)" % (first[-1] * 1000, one_list * 1000))
    # they are paused (their requests wait unread) and dropped after slow-client-timeout
    deadline = time.time() + 60
    while d.read_log().count("nothing read for 3 s") < NON_READERS and time.time() < deadline:
        time.sleep(0.1)
    check(d.read_log().count("nothing read for 3 s") == NON_READERS,
          "all %d are dropped after slow-client-timeout" % NON_READERS)
    for s, t in floods:
        s.close()
    # the machine may be busier now than before: idle is measured on both sides of the busy pings
    idle_after = ping_times(c, PINGS)
    idle_p99 = max(p99(idle), p99(idle_after))
    print("measured: ping p99 idle again %.3f ms" % (p99(idle_after) * 1000))
    check(p99(busy) <= 2 * idle_p99, "ping p99 with %d paused non-readers within 2x of idle (%.3f ms <= 2 x "
          "%.3f ms)" % (NON_READERS, p99(busy) * 1000, idle_p99 * 1000))

    # a paused client that starts reading gets every reply, in order
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.connect(d.socket)
    s.settimeout(60)
    n = 300
    tagged = b"".join(b'{"op": "list", "tag": %d}\n' % i for i in range(n))
    sender = threading.Thread(target=s.sendall, args=(tagged,), daemon=True)
    sender.start()
    time.sleep(1)  # replies pile up over client-buffer-bytes: paused
    buf, tags = b"", []
    while len(tags) < n:
        chunk = s.recv(1 << 20)
        if not chunk:
            break
        buf += chunk
        while b"\n" in buf:
            line, buf = buf.split(b"\n", 1)
            tags.append(json.loads(line)["tag"])
    s.close()
    check(tags == list(range(n)), "a paused client that reads gets all %d replies in order (%d)" % (n, len(tags)))
    check(c.request({"op": "ping"}).get("ok"), "the daemon answers")
    c.close()
    check(d.stop() == 0, "daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
