#!/usr/bin/python3
"""aalabd running jobs: two clients submit at once and both complete; a third watches a running job from
the middle and gets every later event; frames come as PNG payloads; a client that stops reading does not
delay another client's stream (its frames are dropped with a notice, never its events); HTTP endpoints
answer while a job runs."""
import os
import socket
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, SMALL_JOB, check, finish, http_get, wait_state, check_log_and_cleanup, crashed

d = None
try:
    d = Daemon("--client-buffer-bytes", "65536", http=True)

    # two clients submit at once; both jobs complete
    results = {}

    def submit_and_watch(name):
        c = d.connect()
        r = c.request({"op": "submit", "job": dict(SMALL_JOB, name=name)})
        events, end = c.watch(r["job"])
        results[name] = (r["job"], events)
        c.close()

    threads = [threading.Thread(target=submit_and_watch, args=(n,)) for n in ("a", "b")]
    [t.start() for t in threads]
    [t.join(180) for t in threads]
    for name in ("a", "b"):
        job, events = results.get(name, (None, []))
        check(events and events[-1]["event"] == "job_finished", "client %s: its job %s finished" % (name, job))
        seqs = [e["seq"] for e in events]
        check(seqs == list(range(1, len(seqs) + 1)), "client %s: events numbered 1..%d" % (name, len(seqs)))
        check(os.path.exists(os.path.join(d.state, "jobs", job or "x", "results.json")),
              "client %s: results.json stored" % name)
    check(results["a"][0] != results["b"][0], "two distinct job ids")

    # a longer job: HTTP answers while it runs, a third client joins its stream in the middle
    c = d.connect()
    job = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=8, size="160x90", keep_frames=True)})["job"]
    fast = d.connect()
    fast_events = []
    fast_done = []
    stalled = d.connect()
    stalled.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    stalled.send({"op": "watch", "job": job, "frames": "rgba8"})  # and then reads nothing for a while

    def follow():
        events, end = fast.watch(job, frames="png")
        fast_events.extend(events)
        fast_done.append(time.time())

    follower = threading.Thread(target=follow)
    follower.start()
    wait_state(c, job, ["running"])
    while c.request({"op": "status", "job": job})["job"]["events"] < 4:
        time.sleep(0.05)
    t0 = time.time()
    codes = [http_get(d.http_port, p)[0] for p in ("/healthz", "/metrics", "/v1/jobs", "/v1/jobs/" + job, "/")]
    took = time.time() - t0
    state = c.request({"op": "status", "job": job})["job"]["state"]
    check(codes == [200] * 5 and took < 2.0, "HTTP answers while a job runs (%s in %.2f s, job %s)" % (codes, took, state))

    middle = c.request({"op": "status", "job": job})["job"]["events"]
    later, end = d.connect().watch(job, after=middle)
    full, _ = d.connect().watch(job)
    check([e["seq"] for e in later] == list(range(middle + 1, len(full) + 1)),
          "a watch after event %d gets every later event (%d of them)" % (middle, len(later)))
    check(later == full[middle:], "and they equal the stored events")
    check(full[-1]["event"] == "job_finished", "the stored log ends with job_finished")

    follower.join(120)
    check(fast_done and fast_events[-1]["event"] == "job_finished", "the reading client got the whole stream")
    with_frames = [e for e in fast_events if e.get("payload_format") == "png"]
    check(len(with_frames) == 8 * 3 and all(e["_payload"][:8] == b"\x89PNG\r\n\x1a\n" for e in with_frames),
          "it got every frame as a PNG payload (%d)" % len(with_frames))

    # the stalled client now reads: every event is there, some frames were dropped with a notice
    stalled.sock.settimeout(30)
    r = stalled.read()
    events = []
    while True:
        m = stalled.read()
        if m.get("event") == "watch_end":
            break
        events.append(m)
    check(r.get("ok") and [e["seq"] for e in events] == list(range(1, len(full) + 1)),
          "the stalled client still gets every event in order")
    dropped = [e for e in events if "frame_dropped" in e]
    sent = [e for e in events if e.get("payload_format") == "rgba8"]
    check(len(dropped) > 0 and m["frames_dropped"] == len(dropped),
          "its frames were dropped with a notice (%d dropped, %d sent)" % (len(dropped), len(sent)))
    check(all(len(e["_payload"]) == 160 * 90 * 4 for e in sent), "sent rgba8 frames are width x height x 4 bytes")
    job_dir = os.path.join(d.state, "jobs", job)
    pngs = sum(len(f) for _, _, f in os.walk(os.path.join(job_dir, "frames")))
    check(pngs == 8 * 3, "the stored results keep every frame (%d)" % pngs)

    # HTTP: files of the job
    status, ctype, body = http_get(d.http_port, "/v1/jobs/%s/results.json" % job)
    check(status == 200 and ctype == "application/json" and b'"methods"' in body, "GET results.json")
    status, ctype, body = http_get(d.http_port, "/v1/jobs/%s/frames/ssaa:4/3.png" % job)
    check(status == 200 and body[:4] == b"\x89PNG", "GET frames/ssaa:4/3.png")
    status, _, body = http_get(d.http_port, "/v1/jobs/%s/report.html" % job)
    check(status == 200 and b"<svg" in body, "GET report.html")
    status, _, body = http_get(d.http_port, "/v1/jobs/%s/results.json" % job, method="HEAD")
    check(status == 200 and body == b"", "HEAD has no body")
    for p in ("/v1/jobs/%s/frames/..%%2f..%%2fjob.json/0.png" % job, "/v1/jobs/%s/job.json" % job,
              "/web/../../etc/passwd", "/nope", "/v1/jobs/999999"):
        check(http_get(d.http_port, p)[0] == 404, "GET %s is 404" % p)
    check(http_get(d.http_port, "/v1/jobs", method="POST")[0] == 405, "POST is 405")
    status, _, body = http_get(d.http_port, "/metrics")
    text = body.decode()
    if not check('aalab_jobs{state="done"} 3' in text and "aalab_frames_rendered_total 24" in text and
          "aalab_gpu_busy_seconds_total" in text and "aalab_scene_cache_hits_total 2" in text,
          "metrics count jobs, frames, cache hits and GPU time"):
        print(text)
    check("aalab_frames_dropped_total %d" % len(dropped) in text, "metrics count dropped frames")
    # keep-alive: two requests on one connection
    import http.client
    conn = http.client.HTTPConnection("127.0.0.1", d.http_port, timeout=10)
    conn.request("GET", "/healthz")
    a = conn.getresponse().read()
    conn.request("GET", "/healthz")
    b = conn.getresponse().read()
    conn.close()
    check(a == b == b"ok\n", "HTTP keep-alive serves two requests on one connection")

    # linear frames: a job that keeps them streams raw RGBA16F (little-endian halves), finite, in range
    import struct
    c = d.connect()
    job = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=1, linear_frames=True)})["job"]
    events, end = c.watch(job, frames="rgba16f")
    raw = [e for e in events if e.get("payload_format") == "rgba16f"]
    check(len(raw) == 3, "rgba16f: the reference and both methods' frames are sent (%d)" % len(raw))
    check(all(e["width"] == 64 and e["height"] == 36 and len(e["_payload"]) == 64 * 36 * 8 for e in raw),
          "rgba16f frames are width x height x 8 bytes")
    values = [v for e in raw for v in struct.unpack("<%de" % (64 * 36 * 4), e["_payload"])]
    check(all(v == v and 0.0 <= v <= 64.0 for v in values), "rgba16f values are finite linear colours")
    check(max(values) > 0.05, "rgba16f frames are not black")
    c.close()
    check(d.stop() == 0, "aalabd stops cleanly")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
