#!/usr/bin/python3
"""aalabd on a real socket: hello, ping, scenes, methods; 40 malformed requests (bad JSON, wrong types,
unknown ops and keys, huge lines, truncated lines and payloads, path traversal, limits) each get an error
{code, message, path} naming the field, and the daemon keeps serving other clients; TCP needs the token;
SIGHUP reloads the configuration; SIGTERM stops the daemon cleanly (no leaks under ASan)."""
import json
import os
import signal
import socket
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Client, Daemon, SMALL_JOB, check, finish, wait_state, check_log_and_cleanup, crashed

tmp_token = None
d = None
try:
    import tempfile
    tmp = tempfile.mkdtemp(prefix="aalabd-proto.")
    token_file = os.path.join(tmp, "token")
    with open(token_file, "w") as f:
        f.write("s3cret-token-0123456789\n")
    os.chmod(token_file, 0o600)
    config = os.path.join(tmp, "aalabd.conf")
    with open(config, "w") as f:
        f.write("# test configuration\nmax-request-bytes = 65536\nmax-jobs-per-client = 1\n"
                "max-job-budget = 1e9\n")
    d = Daemon("--config", config, "--tcp", "127.0.0.1:0", "--token-file", token_file, tmp=tmp)
    mode = os.stat(d.socket).st_mode & 0o777
    check(mode == 0o660, "socket mode is 0660 (%o)" % mode)

    c = d.connect()
    r = c.request({"op": "hello", "version": 7, "tag": 1})
    check(r["ok"] and r["protocol"] == 1 and r["tag"] == 1, "hello negotiates version 1")
    check(r["limits"]["max_request_bytes"] == 65536, "hello reports limits from the config file")
    check(c.request({"op": "ping", "tag": "x"}) == {"pong": True, "ok": True, "tag": "x"}, "ping echoes its tag")
    scenes = c.request({"op": "scenes"})["scenes"]
    check("thin-wires" in scenes, "scenes lists thin-wires")
    methods = [m["name"] for m in c.request({"op": "methods"})["methods"]]
    check("none" in methods and "ssaa" in methods, "methods lists none and ssaa")

    # a job to refer to, then a long one to keep the client at its limit
    job = c.request({"op": "submit", "job": SMALL_JOB})
    check(job["ok"], "submit a small job")
    jid = job["job"]
    wait_state(c, jid, ["done"])

    bad = [
        (b"not json", "bad_json", ""),
        (b'{"op":', "bad_json", ""),
        (b"[]", "bad_request", ""),
        (b'"ping"', "bad_request", ""),
        (b"42", "bad_request", ""),
        (b"null", "bad_request", ""),
        (b"{}", "bad_request", "op"),
        (b'{"op":5}', "bad_request", "op"),
        (b'{"op":"fly"}', "unknown_op", "op"),
        (b'{"op":"ping","tag":[1]}', "bad_request", "tag"),
        (b'{"op":"ping","extra":1}', "bad_request", "extra"),
        (b'{"op":"ping","op":"ping"}', "bad_json", ""),
        (b'{"op":"\xff\xfe"}', "bad_json", ""),
        (b"[" * 5000 + b"]" * 5000, "bad_json", ""),
        (b'{"op":"status"}', "bad_request", "job"),
        (b'{"op":"status","job":5}', "bad_request", "job"),
        (b'{"op":"status","job":"999999"}', "not_found", "job"),
        (b'{"op":"cancel","job":"' + jid.encode() + b'"}', "invalid", "job"),
        (b'{"op":"submit"}', "bad_request", "job"),
        (b'{"op":"submit","job":[]}', "bad_request", "job"),
        (b'{"op":"submit","job":{"size":"-3x10"}}', "invalid", "job.size"),
        (b'{"op":"submit","job":{"frames":"two"}}', "invalid", "job.frames"),
        (b'{"op":"submit","job":{"methods":["nope"]}}', "not_found", "job.methods[0]"),
        (b'{"op":"submit","job":{"bogus":1}}', "invalid", "job.bogus"),
        (b'{"op":"submit","job":{"scene":"../../etc/passwd"}}', "invalid", "job.scene"),
        (b'{"op":"submit","job":{"scene":"/etc/x/../passwd.json"}}', "invalid", "job.scene"),
        (b'{"op":"submit","job":{"scene":"no-such-scene"}}', "not_found", "job.scene"),
        (b'{"op":"submit","job":{"size":"4096x4096","frames":100}}', "limit", "job"),
        (b'{"op":"watch","job":"' + jid.encode() + b'","after":-1}', "bad_request", "after"),
        (b'{"op":"watch","job":"' + jid.encode() + b'","frames":"jpeg"}', "bad_request", "frames"),
        (b'{"op":"list","state":3}', "bad_request", "state"),
        (b'{"op":"list","limit":0}', "bad_request", "limit"),
        (b'{"op":"get","job":"' + jid.encode() + b'","file":"../../../etc/passwd"}', "invalid", "file"),
        (b'{"op":"get","job":"' + jid.encode() + b'","file":"frames/../job.json"}', "invalid", "file"),
        (b'{"op":"get","job":"' + jid.encode() + b'","file":"frames/none/9999.png"}', "not_found", "file"),
        (b'{"op":"hello","version":0}', "unsupported_version", "version"),
        (b'{"op":"ping","payload":3}\nabc', "bad_request", "payload"),
        (b'{"op":"submit","job":{},"payload":5}\nhello', "bad_request", "payload_format"),
        (b'{"op":"submit","job":{},"payload_format":"scene","payload":9}\n{"bad":1}', "invalid", "payload.bad"),
        (b'{"op":"submit","job":{},"payload":100000}', "too_large", "payload"),
        (b"x" * 70000, "too_large", ""),
    ]
    ctl = d.connect()
    for raw, code, path in bad:
        c.send_raw(raw + b"\n")
        if code == "too_large" and b"payload" in raw:
            c.send_raw(b"\0" * 100000)  # the refused payload is skipped
        r = c.read()
        e = r.get("error", {})
        shown = raw[:50].decode("utf-8", "replace").replace("\n", "\\n")
        check(r.get("ok") is False and e.get("code") == code and e.get("path") == path and e.get("message"),
              "%s -> %s at '%s' (got %s)" % (shown, code, path, json.dumps(r)[:200]))
        check(ctl.request({"op": "ping"}).get("ok"), "another client is still served")
    check(c.request({"op": "ping"}).get("ok"), "the connection that sent them is still usable")

    # errors that end the connection: a bad payload size, a truncated payload, a truncated line
    for raw, code, path in [(b'{"op":"ping","payload":-1}\n', "bad_request", "payload"),
                            (b'{"op":"submit","job":{},"payload_format":"scene","payload":100}\n0123456789',
                             "truncated", "payload"),
                            (b'{"op":"ping"', "truncated", "")]:
        t = d.connect()
        t.send_raw(raw)
        t.sock.shutdown(socket.SHUT_WR)
        r = t.read()
        check(r["error"]["code"] == code and r["error"]["path"] == path, "%s -> %s" % (raw[:40], code))
        t.close()
    check(ctl.request({"op": "ping"}).get("ok"), "the daemon serves after the truncated requests")

    # limits: jobs per client (1 in the config file), then SIGHUP raises it
    long_job = dict(SMALL_JOB, frames=200)
    first = c.request({"op": "submit", "job": long_job})
    r = c.request({"op": "submit", "job": SMALL_JOB})
    check(first["ok"] and r["error"]["code"] == "limit", "max-jobs-per-client refuses a second job")
    with open(config, "a") as f:
        f.write("max-jobs-per-client = 5\n")
    d.proc.send_signal(signal.SIGHUP)
    deadline = time.time() + 10
    while "configuration reloaded" not in d.read_log() and time.time() < deadline:
        time.sleep(0.05)
    r = c.request({"op": "submit", "job": SMALL_JOB})
    check(r.get("ok"), "after SIGHUP the new limit applies")
    second = r.get("job")
    r = c.request({"op": "cancel", "job": second})
    check(r.get("ok") and r["state"] == "cancelled", "cancel a queued job")
    r = c.request({"op": "cancel", "job": first["job"]})
    check(r.get("ok"), "cancel the running job")
    st = wait_state(c, first["job"], ["cancelled"])
    check(st["state"] == "cancelled", "the running job ends cancelled")

    # inline scene as a payload
    scene_path = os.path.join(os.environ["AALAB_SCENE_DIR"], "spinning-wheel.json")  # no asset files
    with open(scene_path, "rb") as f:
        scene = f.read()
    r = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=1, methods=["none"]), "payload_format": "scene"},
                  payload=scene)
    check(r.get("ok"), "submit with the scene as a payload")
    if r.get("ok"):
        st = wait_state(c, r["job"], ["done", "failed"])
        check(st["state"] == "done", "the inline scene renders (%s)" % st.get("error"))

    # TCP: the token is required
    t = Client(tcp=("127.0.0.1", d.tcp_port))
    r = t.request({"op": "ping"})
    check(r["error"]["code"] == "unauthorized" and r["error"]["path"] == "token", "TCP: ping before hello refused")
    r = t.request({"op": "hello", "version": 1, "token": "wrong"})
    check(r["error"]["code"] == "unauthorized" and r["error"]["message"].startswith("wrong token"),
          "TCP: a wrong token is refused as wrong (%s)" % r["error"]["message"])
    t.close()
    t = Client(tcp=("127.0.0.1", d.tcp_port))
    r = t.request({"op": "hello", "version": 1})
    check(r["error"]["code"] == "unauthorized" and r["error"]["message"].startswith("no token") and
          "AALAB_TOKEN" in r["error"]["message"], "TCP: hello without a token is told so, and how to send one")
    t.close()
    # the client: missing and wrong are told apart, with where a refused token came from and how to pass one
    import subprocess
    from daemon_lib import AALAB
    env = {k: v for k, v in os.environ.items() if k not in ("AALAB_TOKEN", "AALAB_TOKEN_FILE")}
    tcp = "tcp:127.0.0.1:%d" % d.tcp_port
    p = subprocess.run([AALAB, "list", "--connect", tcp], env=env, capture_output=True, text=True)
    check(p.returncode == 1 and "none was sent" in p.stderr and "--token-file" in p.stderr and
          "AALAB_TOKEN" in p.stderr, "aalab without a token: says none was sent and how to pass one (%s)" % p.stderr.strip())
    p = subprocess.run([AALAB, "list", "--connect", tcp], env=dict(env, AALAB_TOKEN="wrong"), capture_output=True,
                       text=True)
    check(p.returncode == 1 and "refused the token from $AALAB_TOKEN" in p.stderr,
          "aalab with a wrong token: names where it came from (%s)" % p.stderr.strip())
    p = subprocess.run([AALAB, "list", "--connect", tcp, "--token-file", token_file], env=dict(env, AALAB_TOKEN="wrong"),
                       capture_output=True, text=True)
    check(p.returncode == 0, "aalab list --token-file FILE: the file's token, over $AALAB_TOKEN (%s)" % p.stderr.strip())
    t = Client(tcp=("127.0.0.1", d.tcp_port))
    r = t.request({"op": "hello", "version": 1, "token": "s3cret-token-0123456789"})
    check(r.get("ok"), "TCP: hello with the token")
    check(t.request({"op": "ping"}).get("ok"), "TCP: ping after hello")
    t.close()
    c.close()
    ctl.close()
    status = d.stop()
    check(status == 0, "SIGTERM: aalabd exits 0 (and ASan finds no leak), status %s" % status)
    check(not os.path.exists(d.socket), "the socket file is removed on exit")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
