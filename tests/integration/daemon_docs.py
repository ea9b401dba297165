#!/usr/bin/python3
"""Every example of docs/protocol.md and docs/job-format.md, checked against a running daemon: the inline
request examples (`{"op": ...}` -> reply) get a reply with the documented ok and keys; the error example;
each event's documented fields; the limits hello reports; every JSON job and method object of
job-format.md is accepted (and its canonical form is what the document shows); every row of its error
table gives the documented path and message."""
import json
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import TOP_SRC, Daemon, SMALL_JOB, check, finish, wait_state, check_log_and_cleanup, crashed

PROTOCOL = open(os.path.join(TOP_SRC, "docs", "protocol.md")).read()
JOB_FORMAT = open(os.path.join(TOP_SRC, "docs", "job-format.md")).read()


def top_keys(text):
    """The key names a documented reply shows at its top level: `"name": value` or a bare `"name"` in a
    list of names, at brace depth 1 (placeholders such as {...}, JOB or N are fine)."""
    keys, depth, i = [], 0, 0
    while i < len(text):
        ch = text[i]
        if ch in "{[":
            depth += 1
        elif ch in "}]":
            depth -= 1
        elif ch == '"':
            j = i + 1
            while text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            name = text[i + 1:j]
            after = text[j + 1:].lstrip()
            before = text[:i].rstrip()[-1:]
            if depth == 1 and before in ("{", ",") and (after.startswith(":") or after[:1] in (",", "}")) and \
                    re.fullmatch(r"\w+", name):
                keys.append(name)
            i = j
        i += 1
    return keys


def wildcard_match(pattern, text):
    parts = [re.escape(p) for p in pattern.split("...")]
    return re.fullmatch(".*".join(parts), text, re.S) is not None


d = None
try:
    d = Daemon()
    c = d.connect()
    # a finished job with frames, one that fails, and a blocker that keeps later jobs queued
    done_id = c.request({"op": "submit", "job": dict(SMALL_JOB, keep_frames=True)})["job"]
    failed_id = c.request({"op": "submit", "job": dict(SMALL_JOB, path="nowhere")})["job"]
    wait_state(c, done_id, ["done"])
    wait_state(c, failed_id, ["failed"])
    blocker = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=5000, keep_frames=False)})["job"]
    wait_state(c, blocker, ["running"])

    # ---------------------------------------------------------------- protocol.md inline examples
    pairs = re.findall(r"`(\{\"op\": [^`]*\})`\s*→\s*`(\{[^`]*\})`", PROTOCOL, re.S)
    check(len(pairs) >= 10, "protocol.md has its inline request examples (%d)" % len(pairs))
    conditional = {"status": {"started_at", "finished_at", "summary", "error", "run", "interruptions",
                              "inline_scene"}}
    tried = 0
    for req_text, reply_text in pairs:
        req_text = " ".join(req_text.split())
        reply_text = " ".join(reply_text.split())
        try:
            req = json.loads(req_text.replace("{...}", "{}"))
        except ValueError:
            req = None
        if req is None or req.get("job") == {}:
            continue  # submit with a placeholder job: checked below with the real examples
        req = json.loads(json.dumps(req).replace("000042", done_id))
        if req["op"] == "hello":
            req.pop("token", None)  # a Unix socket needs none
        if req["op"] == "cancel":
            req["job"] = c.request({"op": "submit", "job": SMALL_JOB})["job"]
        if req["op"] == "watch":
            req["frames"] = "none"
        r = c.request(req)
        if req["op"] == "watch" and r.get("ok"):
            while c.read().get("event") != "watch_end":
                pass
        if r.get("payload"):
            pass  # daemon_lib reads the payload with the line
        tried += 1
        want_ok = reply_text.startswith('{"ok": true')
        check(r.get("ok") == want_ok, "%s: ok is %s as documented" % (req_text[:60], want_ok))
        missing = [k for k in top_keys(reply_text) if k not in r and k not in conditional.get(req["op"], ())]
        check(not missing, "%s: the reply has the documented keys (missing %s)" % (req_text[:60], missing))
        if req["op"] == "status":
            job = r["job"]
            missing = [k for k in top_keys(reply_text.split('"job": ', 1)[1]) if k not in job and k != "error"]
            check(not missing and job["bytes"] > 0, "status: the job has the documented fields and bytes > 0 once "
                  "done (missing %s, bytes %s)" % (missing, job.get("bytes")))
    check(tried >= 10, "the inline examples were sent (%d)" % tried)

    # the error example
    m = re.search(r"Every error reply is\s+```json\n(.*?)\n```", PROTOCOL, re.S)
    doc = json.loads(m.group(1).replace('; ...', ''))
    r = c.request({"op": "submit", "tag": 7, "job": {"size": "-3x10"}})
    check(r["tag"] == 7 and r["error"]["code"] == doc["error"]["code"] and r["error"]["path"] == doc["error"]["path"]
          and r["error"]["message"].startswith(doc["error"]["message"]), "the error example is what the daemon says")

    # hello's limits, as listed
    m = re.search(r"`limits` holds (.*?)\.\n", PROTOCOL, re.S)
    listed = re.findall(r"`(\w+)`", m.group(1))
    r = c.request({"op": "hello", "version": 1})
    check(sorted(listed) == sorted(r["limits"]), "hello's limits are the ones listed (%s)" % sorted(r["limits"]))
    check(all(isinstance(v, int) for v in r["limits"].values()), "and every limit is an integer")
    r = c.request({"op": "hello", "version": "1"})
    check(r["error"]["code"] == "bad_request" and r["error"]["path"] == "version",
          "hello with version \"1\" (a string): bad_request on version, as documented")
    check("`version` is an integer" in PROTOCOL, "protocol.md says version is an integer")
    r = c.request({"op": "list", "state": "finished"})
    check(r.get("error", {}).get("path") == "state", "list with an unknown state is refused")

    # events: every documented field is present in the events of the three kinds of job
    rows = re.findall(r"^\| `(\w+)` \| (.*) \|$", PROTOCOL.split("Events (all have", 1)[1].split("\n\n")[0], re.M)
    common = re.findall(r"`(\w+)`", re.search(r"Events \(all have ([^)]*)\)", PROTOCOL).group(1))
    cancelled_id = c.request({"op": "submit", "job": SMALL_JOB})["job"]
    c.request({"op": "cancel", "job": cancelled_id})
    seen = {}
    for job in (done_id, failed_id, cancelled_id):
        events, end = c.watch(job)
        for e in events:
            seen.setdefault(e["event"], e)
        seen["watch_end"] = end
    for name, fields in rows:
        documented = re.findall(r"`(\w+)`", re.sub(r"\([^)]*\)", "", fields)) + common
        e = seen.get(name)
        missing = [f for f in documented if e is not None and f not in e]
        check(e is not None and not missing, "event %s has its documented fields (missing %s)" % (name, missing))
    m = re.search(r"then\s+`(\{\"event\": \"watch_end\"[^`]*\})`", PROTOCOL, re.S)
    wend = top_keys(" ".join(m.group(1).split()))
    r = c.request({"op": "watch", "job": done_id, "tag": "t1"})
    while True:
        e = c.read()
        if e.get("event") == "watch_end":
            break
    check(all(k in e for k in wend) and e.get("tag") == "t1" and "`watch_end` carries the watch's `tag`" in PROTOCOL,
          "watch_end has its documented fields and the watch's tag")
    r = c.request({"op": "get", "job": done_id, "file": "results.json"})
    check(r["payload_format"] == "application/json" and "MIME type" in PROTOCOL, "get's payload_format is a MIME type")
    files = c.request({"op": "get", "job": done_id})["files"]
    png = [f for f in files if f.endswith(".png")][0]
    r = c.request({"op": "get", "job": done_id, "file": png})
    p = r["_payload"]
    check(p[:8] == b"\x89PNG\r\n\x1a\n" and p[24] == 8 and p[25] == 2 and "8-bit RGB" in PROTOCOL,
          "stored PNGs are 8-bit RGB, as documented (depth %d, colour type %d)" % (p[24], p[25]))

    # ---------------------------------------------------------------- job-format.md
    blocks = re.findall(r"```json\n(.*?)\n```", JOB_FORMAT, re.S)
    check(len(blocks) >= 3, "job-format.md has its JSON examples (%d)" % len(blocks))
    canonical = None
    for text in blocks:
        obj = json.loads(text)
        job = {"methods": [obj]} if "params" in obj else obj
        r = c.request({"op": "submit", "job": dict(job, frames=job.get("frames", 1))})
        check(r.get("ok"), "job-format.md example is accepted: %s (%s)" % (" ".join(text.split())[:70], r.get("error")))
        if r.get("ok"):
            spec = c.request({"op": "status", "job": r["job"]})["job"]["spec"]
            c.request({"op": "cancel", "job": r["job"]})
            if "name" in obj and "keep_frames" in obj and "path" in obj and "size" in obj:
                canonical = (obj, spec)
    if canonical:
        shown = json.loads(blocks[-1])
        check(canonical[1] == shown, "the canonical form shown is what the daemon writes for the example "
              "(%s)" % json.dumps(canonical[1]))
    # the method string forms and the labels
    for form in re.findall(r"^\| `(\"[^`]*\")` \| ", JOB_FORMAT, re.M):
        form = form.replace("\\|", "|")  # a table cell escapes a sweep's '|' as '\|'
        r = c.request({"op": "submit", "job": {"methods": [json.loads(form)], "frames": 1}})
        check(r.get("ok"), "method %s is accepted (%s)" % (form, r.get("error")))
        if r.get("ok"):
            c.request({"op": "cancel", "job": r["job"]})
    for given, label in re.findall(r"^\| (`.*`) \| `([^`]*)` \|$", JOB_FORMAT.split("#### Labels", 1)[1].split("## ")[0], re.M):
        for g in re.findall(r"`([^`]*)`", given):
            r = c.request({"op": "submit", "job": {"methods": [json.loads(g)], "frames": 1}})
            ok = r.get("ok") and c.request({"op": "status", "job": r["job"]})["job"]["spec"]["methods"] == [label]
            if r.get("ok"):
                c.request({"op": "cancel", "job": r["job"]})
            check(ok, "%s has the label %s" % (g, label))
    # the error table
    table = JOB_FORMAT.split("Examples, shown as `path: message`:", 1)[1]
    rows = re.findall(r"^\| `(\{.*\})` \| `([^`]*)` \| `(.*)` \|$", table, re.M)
    check(len(rows) >= 10, "job-format.md's error table (%d rows)" % len(rows))
    for job_text, path, shown in rows:
        job_text, shown = job_text.replace("\\|", "|"), shown.replace("\\|", "|")
        r = c.request({"op": "submit", "job": json.loads(job_text)})
        err = r.get("error", {})
        got = "%s: %s" % (err.get("path", "")[4:], err.get("message"))
        check(err.get("path") == "job." + path and wildcard_match(shown, got),
              "%s: %s" % (job_text, "as documented" if wildcard_match(shown, got) else "daemon says " + got))
    m = re.search(r"A method without a main parameter.*?`(([\w-]+): has no main parameter, so \"(\w+)\"[^`]*)`", JOB_FORMAT, re.S)
    r = c.request({"op": "submit", "job": {"methods": ["%s:%s" % (m.group(2), m.group(3))]}})
    check(r.get("error", {}).get("message") == m.group(1), "%s:%s is refused as documented (%s)" %
          (m.group(2), m.group(3), r.get("error")))

    # a cancelled job keeps the done of its last frame event (cancelled once it has rendered frames)
    while c.request({"op": "status", "job": blocker})["job"]["done"] < 2:
        time.sleep(0.05)
    c.request({"op": "cancel", "job": blocker})
    st = wait_state(c, blocker, ["cancelled"])
    events, end = c.watch(blocker)
    last = [e["done"] for e in events if "done" in e][-1]
    check(st["done"] == last, "a cancelled job's done (%d) is its last frame event's (%d)" % (st["done"], last))
    c.close()
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
