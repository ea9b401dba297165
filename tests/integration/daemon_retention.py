#!/usr/bin/python3
"""aalabd keeps a job in memory while anything refers to it (the ownership rule in daemon/jobs.h): with
retention-jobs 1, a running job that finishes while a later job was cancelled is deleted by retention at
once, and /metrics scraped all the while (it reads the running job), cancels and reloads must never see
it freed. Run in the sanitizer build, a use-after-free is an ASan report in the daemon's log. Then a
short churn: submits, cancels of queued and running jobs, watches that end or are dropped, reloads and
scrapes at random, after which the daemon still answers and the store holds what retention says."""
import http.client
import os
import random
import signal
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Daemon, check, finish, check_log_and_cleanup, crashed

# the smallest job that runs the whole path (set-up, a frame, results, report): a fraction of a second
TINY = {"scene": "thin-wires", "methods": ["none"], "frames": 1, "size": "16x16", "reference": {"samples": 2}}
ROUNDS = int(os.environ.get("AALAB_RETENTION_ROUNDS", "60"))
CHURN_SECONDS = float(os.environ.get("AALAB_RETENTION_CHURN_SECONDS", "20"))


class Scraper(threading.Thread):
    """GET /metrics on one keep-alive connection as fast as the daemon answers, until stopped."""

    def __init__(self, port):
        super().__init__(daemon=True)
        self.port, self.count, self.errors, self.halt = port, 0, [], threading.Event()

    def run(self):
        conn = None
        while not self.halt.is_set():
            try:
                if conn is None:
                    conn = http.client.HTTPConnection("127.0.0.1", self.port, timeout=30)
                conn.request("GET", "/metrics")
                r = conn.getresponse()
                body = r.read()
                if r.status != 200 or b"aalab_gpu_busy_seconds_total" not in body:
                    self.errors.append("status %d" % r.status)
                self.count += 1
                if r.getheader("Connection", "").lower() == "close":
                    conn.close()
                    conn = None
            except (OSError, http.client.HTTPException) as e:
                self.errors.append(repr(e))
                conn = None
                time.sleep(0.05)


def submitted(c, job):
    r = c.request({"op": "submit", "job": job})
    if not r.get("ok"):
        raise RuntimeError("submit refused: %s" % r)
    return r["job"]


def started_or_gone(c, job, timeout=120):
    """The job's state once it left the queue, or None once retention deleted it: A and then B can both
    finish between two polls, and B's end deletes A."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        r = c.request({"op": "status", "job": job})
        if not r.get("ok"):
            return None
        if r["job"]["state"] != "queued":
            return r["job"]["state"]
        time.sleep(0.02)
    raise RuntimeError("job %s did not start" % job)


def final_or_gone(c, job, timeout=120):
    """The job's state once final, or None once retention deleted it."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        r = c.request({"op": "status", "job": job})
        if not r.get("ok"):
            return None
        if r["job"]["state"] in ("done", "failed", "cancelled"):
            return r["job"]["state"]
        time.sleep(0.02)
    raise RuntimeError("job %s did not end" % job)


d = None
scrapers = []
try:
    d = Daemon("--retention-jobs", "1", http=True)
    scrapers = [Scraper(d.http_port) for _ in range(2)]
    [s.start() for s in scrapers]
    c = d.connect()

    # the reproduction: A runs, B is queued then cancelled, A ends and is at once the oldest of two
    # finished jobs, deleted while the worker's pointer to the running job (what /metrics reads) is set
    deleted = 0
    t0 = time.time()
    for i in range(ROUNDS):
        a, b = (submitted(c, TINY) for _ in "ab")
        started_or_gone(c, a)
        c.request({"op": "cancel", "job": b})
        deleted += final_or_gone(c, a) is None
        if d.proc.poll() is not None:
            break
    print("measured: %d rounds in %.1f s, %d scrapes; job A deleted by retention in %d rounds" %
          (ROUNDS, time.time() - t0, sum(s.count for s in scrapers), deleted))
    check(d.proc.poll() is None, "the daemon is alive after %d rounds of finish-while-scraped" % ROUNDS)
    check(deleted >= ROUNDS // 2, "retention deleted the job that had just finished (%d of %d rounds)" %
          (deleted, ROUNDS))
    r = c.request({"op": "list"})
    finished = [j for j in r["jobs"] if j["state"] in ("done", "failed", "cancelled")]
    check(len(finished) == 1, "retention-jobs 1 keeps one finished job: %s" % [j["id"] for j in finished])

    # churn: every way a job pointer is held or let go, at random, with scrapes and reloads beside
    rng = random.Random(27)
    watchers = []
    ops = {"submit": 0, "cancel": 0, "watch": 0, "drop_watch": 0, "reload": 0}
    active = []
    t0 = time.time()
    while time.time() - t0 < CHURN_SECONDS and d.proc.poll() is None:
        op = rng.choice(["submit", "submit", "cancel", "watch", "drop_watch", "reload"])
        if op == "submit" or not active:
            r = c.request({"op": "submit", "job": dict(TINY, frames=rng.choice([1, 2]))})
            if r.get("ok"):
                active.append(r["job"])
            op = "submit"
        elif op == "cancel":
            c.request({"op": "cancel", "job": active.pop(rng.randrange(len(active)))})
        elif op == "watch":
            w = d.connect()
            w.send({"op": "watch", "job": rng.choice(active), "frames": "none"})
            watchers.append(w)
            if len(watchers) > 16:  # a long churn stays under max-connections-per-peer (64)
                watchers.pop(0).close()
        elif op == "drop_watch" and watchers:
            watchers.pop(rng.randrange(len(watchers))).close()
        elif op == "reload":
            d.proc.send_signal(signal.SIGHUP)
        ops[op] += 1
        active = active[-8:]
        time.sleep(rng.uniform(0, 0.05))
    for w in watchers:
        w.close()
    print("measured: churn of %.1f s: %s" % (time.time() - t0, ops))
    check(d.proc.poll() is None, "the daemon is alive after the churn")
    check(c.request({"op": "ping"}).get("ok"), "and answers ping")
    for j in active:
        final_or_gone(c, j)
    deadline = time.time() + 120
    while time.time() < deadline:
        jobs = c.request({"op": "list"})["jobs"]
        if all(j["state"] in ("done", "failed", "cancelled") for j in jobs):
            break
        time.sleep(0.1)
    time.sleep(0.5)  # the watchers' closes are taken
    jobs = c.request({"op": "list"})["jobs"]
    check(len(jobs) == 1, "after the churn one finished job is kept: %s" % [(j["id"], j["state"]) for j in jobs])
    kept = set(os.listdir(os.path.join(d.state, "jobs")))
    check(kept == {j["id"] for j in jobs}, "and the state folder holds that job only: %s" % sorted(kept))
    for s in scrapers:
        s.halt.set()
    [s.join(30) for s in scrapers]
    errors = [e for s in scrapers for e in s.errors]
    check(not errors, "every scrape was answered: %s" % errors[:5])
    c.close()
    check(d.stop() == 0, "daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    for s in scrapers:
        s.halt.set()
    check_log_and_cleanup(d)
finish()
