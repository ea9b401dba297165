#!/usr/bin/python3
"""Fair output (aalabd(8), client-buffer-bytes): a connection handles at most a few requests a turn of the
loop, and none while more than 64 KiB of its replies wait unsent, so clients that pipeline large replies
(`list` of many jobs) and never read them delay no one else's replies: they are paused (their further
requests wait unread) and dropped after slow-client-timeout. A paused client that starts reading gets
every reply, in order.
What is counted, not timed: how many of the non-readers' requests the daemon handled before it paused
them (aalab_requests_total). What is timed is compared with an idle daemon of the same build, pinged in
turn with the one under test, so that a busy machine slows both alike."""
import json
import os
import re
import socket
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, check, finish, check_log_and_cleanup, crashed, http_get

NON_READERS = 8
PINGS = 1000
LIST = b'{"op": "list"}\n'


def ping(c):
    t0 = time.perf_counter()
    assert c.request({"op": "ping"}).get("ok")
    return time.perf_counter() - t0


def paired_pings(a, b, n):
    """n pings of each daemon, in turn: the one under test and the idle one see the same machine."""
    ta, tb = [], []
    for _ in range(n):
        ta.append(ping(a))
        tb.append(ping(b))
    return sorted(ta), sorted(tb)


def p99(times):
    return times[int(len(times) * 0.99) - 1]


def requests_total(d):
    return int(re.search(rb"^aalab_requests_total (\d+)$", http_get(d.http_port, "/metrics")[2], re.M).group(1))


def flood(sock, lines):
    """Pipelines `lines` list requests and reads nothing; ends when the daemon stops reading or drops it."""
    try:
        sock.sendall(LIST * lines)
    except OSError:
        pass


d = idle_d = None
try:
    d = Daemon("--slow-client-timeout", "10", http=True)
    idle_d = Daemon()
    c, ci = d.connect(), idle_d.connect()
    # 150 jobs, so that a list reply is large
    for i in range(150):
        r = c.request({"op": "submit", "job": {"scene": "thin-wires", "methods": ["none"], "frames": 1,
                                               "size": "32x18", "reference": {"samples": 2}}})
        c.request({"op": "cancel", "job": r["job"]})
    lists = []
    for _ in range(5):
        t0 = time.perf_counter()
        reply = c.request({"op": "list"})
        lists.append(time.perf_counter() - t0)
    one_list = sorted(lists)[2]
    reply_bytes = len(json.dumps(reply))
    print("measured: a list of %d jobs takes %.2f ms (median of 5), %d bytes" % (len(reply["jobs"]),
                                                                              one_list * 1000, reply_bytes))

    idle_a, idle_b = paired_pings(c, ci, PINGS)
    before = requests_total(d)
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
    first_a, first_b = [], []
    while time.perf_counter() - t0 < 1.0:
        a, b = paired_pings(c, ci, 1)
        first_a += a
        first_b += b
    first_a.sort()
    first_b.sort()
    # once they are paused (a second later, well before slow-client-timeout drops them), they cost nothing:
    # p99 within 2x of the idle daemon's. A p99 of 1,000 pings sits where a busy machine's preemptions
    # begin (a few ms against 0.2), so one more preemption on one side can swing it tenfold: up to three
    # rounds of 1,000 pairs, the best one counts (a daemon that keeps paying for paused clients fails all
    # three; one that does not pause them fails the count below)
    rounds = []
    for _ in range(3):
        busy_a, busy_b = paired_pings(c, ci, PINGS)
        rounds.append((p99(busy_a), p99(busy_b), busy_a[-1], busy_b[-1]))
        if rounds[-1][0] <= 2 * rounds[-1][1]:
            break
    best = min(rounds, key=lambda r: r[0] / r[1])
    # their requests handled: what the daemon received, less this client's pings (and the scrape's none)
    handled = requests_total(d) - before - len(first_a) - PINGS * len(rounds)
    still_there = d.read_log().count("nothing read for 10 s") == 0
    print("measured: ping p99 idle %.3f ms (idle daemon %.3f); with %d clients that do not read, in their first "
          "second max %.2f ms over %d pings (idle daemon %.2f), then p99 %s; %d of their %d requests handled" %
          (p99(idle_a) * 1000, p99(idle_b) * 1000, NON_READERS, first_a[-1] * 1000, len(first_a),
           first_b[-1] * 1000, ", ".join("%.3f ms (idle daemon %.3f, max %.2f against %.2f)" %
                                         tuple(x * 1000 for x in r) for r in rounds),
           handled, NON_READERS * lines))
    check(still_there, "the %d non-readers were still connected while the pings were measured" % NON_READERS)
    # paused once 64 KiB of replies wait unsent: each got what the socket's buffer takes (its default send
    # buffer, counted twice for the kernel's bookkeeping) plus 64 KiB, in whole replies, and a turn more;
    # with the pause at client-buffer-bytes (4 MiB) each would get about 4 MiB of them
    per_client = (2 * 212992 + 65536) // reply_bytes + 4
    check(0 < handled <= NON_READERS * per_client, "each non-reader is paused after a few replies: %d requests "
          "handled, at most %d x %d" % (handled, NON_READERS, per_client))
    # a ping waits at most for the requests being handled in one turn (eight lists, one per non-reader),
    # never for a client's pipeline; what the machine adds shows on the idle daemon pinged in turn
    check(first_a[-1] < 32 * one_list + first_b[-1], "while they are paused the longest ping wait is below 32 "
          "lists plus the idle daemon's longest (%.2f ms < 32 x %.2f + %.2f ms)" %
          (first_a[-1] * 1000, one_list * 1000, first_b[-1] * 1000))
    # once paused they cost no one anything: ping p99 within 2x of the idle daemon's at the same moments
    check(best[0] <= 2 * best[1], "ping p99 with %d paused non-readers within 2x of idle (%.3f ms <= 2 x "
          "%.3f ms, the best of %d rounds)" % (NON_READERS, best[0] * 1000, best[1] * 1000, len(rounds)))
    # they are paused (their requests wait unread) and dropped after slow-client-timeout
    deadline = time.time() + 60
    while d.read_log().count("nothing read for 10 s") < NON_READERS and time.time() < deadline:
        time.sleep(0.1)
    check(d.read_log().count("nothing read for 10 s") == NON_READERS,
          "all %d are dropped after slow-client-timeout" % NON_READERS)
    for s, t in floods:
        s.close()

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
    ci.close()
    check(d.stop() == 0, "daemon stops")
    check(idle_d.stop() == 0, "the idle daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    if idle_d:
        idle_d.cleanup()
    check_log_and_cleanup(d)
finish()
