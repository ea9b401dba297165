#!/usr/bin/python3
"""User methods through aalabd (docs/user-methods.md, aalabd(8)): refused unless the configuration allows
them; allowed, a method file and its shaders travel as a bundle payload and nothing is read from the
daemon's disk; GPU work runs in a worker process, so a shader that runs past the job's time limit fails
its job and the next job succeeds on a fresh process, as do a job whose process is killed (a driver
crash) and a hung job that is cancelled; the daemon answers while a job hangs, and nothing accepted before
is lost; a shader that does not compile fails its job with the file and line and keeps the process; the
daemon shuts down with no process left behind, and started again without allow-user-methods it fails the
user jobs it stored rather than run them itself."""
import json
import os
import re
import resource
import signal
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import TOP_SRC, Daemon, check, finish, wait_state, check_log_and_cleanup, crashed

EXAMPLES = os.path.join(TOP_SRC, "examples", "methods")
LIMIT = 12  # seconds: the time limit the hung job meets (it must not come before the test sees the shader run)
LONG_LIMIT = 600  # seconds: every other job's time limit, beyond anything the test waits for
GRACE = 5  # seconds a cancelled job has to reach its next event before its process is killed (aalabd(8))
HANG_SIZE = "320x180"
SMALL = {"scene": "thin-wires", "size": "64x36", "frames": 1, "reference": {"samples": 4}}

# lavapipe ends any shader's loops after 65535 iterations in all (its loop limiter); this loop never meets
# its exit and does 4096 dependent fetches an iteration. Measured with aalab run at 160x90 and 256 fetches:
# 7.5 to 29 s a frame; HANG_SIZE and 4096 make it 64 times that, so that no machine finishes the frame
# within anything the test waits for (LIMIT plus the cancel grace): every case below ends by a kill
HANG = {
    "hang.json": json.dumps({"name": "hang", "passes": [{"name": "spin", "shader": "hang.frag", "reads": ["colour"]}]}),
    "hang.frag": """void main()
{
	vec4 c = texelFetch(colour, aa_pixel, 0);
	uint stop = floatBitsToUint(c.a) | 1u;
	vec4 acc = c;
	for (uint i = 0u; i != stop; i += 2u)
		for (int k = 0; k < 4096; k++)
			acc += texelFetch(colour, ivec2(abs(acc.xy * 7.0 + float(k))) % ivec2(aa_size.xy), 0);
	aa_write(acc);
}
""",
}


def example_files():
    files = {}
    for name in ("edge_blur.json", "edge_blur.frag"):
        with open(os.path.join(EXAMPLES, name)) as f:
            files["m/" + name] = f.read()
    return files


def bundle(files, scene=None):
    b = {"files": files}
    if scene is not None:
        b["scene"] = scene
    return json.dumps(b).encode()


def submit(c, job, files=None):
    if files is None:
        return c.request({"op": "submit", "job": job})
    return c.request({"op": "submit", "job": job, "payload_format": "bundle"}, bundle(files))


def set_time_limit(d, config, seconds):
    """Writes job-time-limit to the configuration file and, with a daemon, reloads it (SIGHUP) and waits
    until the daemon says so."""
    with open(config, "w") as f:
        f.write("job-time-limit = %d\n" % seconds)
    if d:
        reloads = d.read_log().count("configuration reloaded")
        d.proc.send_signal(signal.SIGHUP)
        deadline = time.time() + 60
        while d.read_log().count("configuration reloaded") == reloads and time.time() < deadline:
            time.sleep(0.05)


def rasterizer_cpu_s(pid):
    """CPU seconds that the process's llvmpipe threads (where lavapipe runs shaders) have used."""
    total = 0
    try:
        tids = os.listdir("/proc/%d/task" % pid)
    except FileNotFoundError:
        raise RuntimeError("worker process %d ended (the log says why)" % pid) from None
    for tid in tids:
        try:
            with open("/proc/%d/task/%s/stat" % (pid, tid)) as f:
                comm, rest = f.read().split("(", 1)[1].rsplit(")", 1)
        except OSError:
            continue  # the thread ended
        if comm.startswith("llvmpipe"):
            fields = rest.split()
            total += int(fields[11]) + int(fields[12])  # utime, stime
    return total / os.sysconf("SC_CLK_TCK")


# rasterizer CPU a job's own frames may use before its hung shader: the reference of HANG_SIZE at 4 samples
# takes a few ms of it (measured below with a whole job of that size: 0.02 s under the sanitizers); half a
# second means the shader is running. On two busy cores the rasterizer threads get a small share of them,
# so a higher mark could come after LIMIT has killed the process
INSIDE_SHADER_CPU_S = 0.5


def wait_inside_shader(d, job):
    """Returns once the job's worker process runs the hung shader: after the job_started event the worker
    renders the job's small reference, checks once more for a stop (between two pieces of GPU work) and
    starts the warm-up frame of its one method, the hung shader, which no stop ends. Inside it, the
    process's rasterizer threads use CPU time without end; the reference uses a few ms of it."""
    w = d.connect()
    r = w.request({"op": "watch", "job": job, "frames": "none"})
    assert r.get("ok"), r
    while w.read().get("event") != "job_started":
        pass
    w.close()
    pid = worker_pids(d)[-1]
    start = rasterizer_cpu_s(pid)
    deadline = time.time() + 600
    while rasterizer_cpu_s(pid) - start < INSIDE_SHADER_CPU_S:
        if time.time() > deadline:
            raise RuntimeError("job %s: the worker process's rasterizer did not run its shader" % job)
        time.sleep(0.05)


def worker_pids(d):
    return [int(l.split()[3]) for l in d.read_log().splitlines() if l.startswith("aalabd: worker process ")
            and l.split()[4] == "ready"]


def alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a zombie is dead too
        with open("/proc/%d/stat" % pid) as f:
            return f.read().split(")")[1].split()[0] != "Z"
    except OSError:
        return False


resource.setrlimit(resource.RLIMIT_CORE, (0, 0))  # the aborted worker process leaves no core file behind
d = None
try:
    # ---------------------------------------------------------------- off unless allowed
    d = Daemon()
    c = d.connect()
    r = submit(c, dict(SMALL, methods=["none", "user:file=m/edge_blur.json"]), example_files())
    check(not r["ok"] and r["error"]["code"] == "forbidden" and r["error"]["path"] == "job.methods[1]" and
          "allow-user-methods" in r["error"]["message"], "without allow-user-methods a user method is forbidden: %s" % r)
    r = submit(c, dict(SMALL, methods=[{"name": "user", "params": {"file": "m/edge_blur.json"}}]))
    check(not r["ok"] and r["error"]["code"] == "forbidden", "in the object form too")
    with open(os.path.join(TOP_SRC, "scenes", "thin-wires.json")) as f:
        scene_text = f.read()
    r = c.request({"op": "submit", "job": dict(SMALL, methods=["none"]), "payload_format": "bundle"},
                  bundle({}, scene_text))
    check(r["ok"], "a bundle with a scene alone is a scene payload: %s" % r)
    if r["ok"]:
        check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "and the job runs")
    check("worker process" not in d.read_log(), "no worker process without allow-user-methods")
    c.close()
    check(d.stop() == 0, "daemon stops")
    check_log_and_cleanup(d)

    # ---------------------------------------------------------------- allowed: a worker process
    # job-time-limit is LIMIT only for the job that must hit it (set by a reload, read when a job starts):
    # every other job here runs under a limit far beyond what any waits for, so that neither a slow job
    # on a busy machine nor a cancel's grace ever races it
    tmp = tempfile.mkdtemp(prefix="aalabd-test.")
    config = os.path.join(tmp, "aalabd.conf")
    set_time_limit(None, config, LONG_LIMIT)
    d = Daemon("--allow-user-methods", "yes", "--config", config, "--drain-timeout", "1", tmp=tmp,
               env={"AALAB_CACHE_DIR": "/nonexistent-cache-dir"})
    d.own_tmp = True
    check("user methods allowed: GPU work in a worker process" in d.read_log(), "ready says where GPU work runs")
    first_pid = worker_pids(d)[0]
    c = d.connect()
    # timed once: the job runs within job-time-limit on a loaded machine
    r = submit(c, dict(SMALL, frames=2, timing={"repeat": 1}, methods=["none", "fxaa", "user:file=m/edge_blur.json,strength=0.9"]),
               example_files())
    check(r["ok"], "a user method with its files is queued: %s" % r)
    r_first = r["job"]
    job = wait_state(c, r["job"], ["done", "failed"])
    check(job["state"] == "done", "and done: %s" % job.get("error"))
    check(job["spec"]["methods"][2] == "user:file=m/edge_blur.json,strength=0.9", "status shows the method string")
    labels = [m["label"] for m in job.get("summary", [])]
    check(labels == ["none", "fxaa", "edge-blur:strength=0.9"], "the summary has it beside the built-ins: %s" % labels)
    g = c.request({"op": "get", "job": r["job"], "file": "results.json"})
    res = json.loads(g["_payload"])
    m = res["methods"][2]
    check(m["name"] == "user" and [p["name"] for p in m["passes"]] == ["scene", "blur"] and m["memory_bytes"] > 0
          and m["gpu_ms"]["n"] == 2 and m["metrics"]["psnr"]["mean"] > 0, "results.json: passes, memory, metrics")
    g = c.request({"op": "get", "job": r["job"], "file": "method-files.json"})
    check(g.get("ok") and json.loads(g["_payload"]) == example_files(), "the files are kept with the job")

    # a suite runs in the worker process too (a user method runs nowhere else): every case, its events
    # naming the case, its images in the case's folder; run again with the first as its baseline, the
    # verdict is judged on the daemon's side when the process is done
    suite = dict(SMALL, suite="um", scenes=["thin-wires"], sizes=["64x36", "48x27"], keep_frames=True,
                 methods=["none", "user:file=m/edge_blur.json"])
    del suite["scene"], suite["size"]
    r = submit(c, suite, example_files())
    check(r["ok"], "a suite with a user method is queued: %s" % r)
    s1 = wait_state(c, r["job"], ["done", "failed"])
    check(s1["state"] == "done", "and done: %s" % s1.get("error"))
    g = c.request({"op": "get", "job": s1["id"], "file": "results.json"})
    cases = json.loads(g["_payload"]).get("cases", []) if g.get("ok") else []
    check([k["id"] for k in cases] == ["thin-wires/default/64x36", "thin-wires/default/48x27"] and
          all(k["methods"][1]["name"] == "user" and k["methods"][1]["gpu_ms"]["n"] == 5 for k in cases),
          "results.json has both cases, each with the user method timed: %s" % [k.get("id") for k in cases])
    events, end = c.watch(s1["id"])
    frames = [e for e in events if e["event"] == "method_frame" and e["method"] == "edge-blur"]
    check([e.get("case") for e in frames] == ["thin-wires/default/64x36", "thin-wires/default/48x27"] and
          all(e.get("image", "").startswith("cases/thin-wires_default_%dx%d/" % (e["width"], e["height"]))
              for e in frames), "its frame events name their case and its image: %s" %
          [(e.get("case"), e.get("image")) for e in frames])
    if frames:
        g = c.request({"op": "get", "job": s1["id"], "file": frames[-1]["image"]})
        check(g.get("ok") and g["_payload"][:4] == b"\x89PNG", "a case's image is there")
    r = submit(c, dict(suite, baseline=s1["id"]), example_files())
    s2 = wait_state(c, r["job"], ["done", "failed"]) if r["ok"] else {}
    v = s2.get("compare", {})
    check(s2.get("state") == "done" and v.get("job") == s1["id"] and v.get("verdict") in ("held", "tripped"),
          "run again with it as the baseline, the job has a verdict: %s" % (v or r))
    check(len(worker_pids(d)) == 1, "in the one worker process")

    # the daemon reads user methods from the files sent, never from its disk
    r = submit(c, dict(SMALL, methods=["user:file=%s/edge_blur.json" % EXAMPLES]))
    check(not r["ok"] and r["error"]["code"] == "not_found" and r["error"]["path"] == "job.methods[0]" and
          "not among the files sent with the job" in r["error"]["message"], "a path on the daemon's disk: %s" % r)
    files = example_files()
    del files["m/edge_blur.frag"]
    r = submit(c, dict(SMALL, methods=["user:file=m/edge_blur.json"]), files)
    check(not r["ok"] and "passes[0].shader: m/edge_blur.frag: not among the files" in r["error"]["message"],
          "a shader missing from the bundle is named: %s" % r.get("error"))
    r = c.request({"op": "submit", "job": SMALL, "payload_format": "bundle"}, b"{\"files\": {\"a\": 1}}")
    check(not r["ok"] and r["error"]["path"] == "payload.files", "a bundle's files are texts")

    # a syntax error: accepted (compiling is GPU-side work), then the job fails naming the file and the line;
    # the worker process is not replaced for it
    bad = example_files()
    bad["m/edge_blur.frag"] = bad["m/edge_blur.frag"].replace("aa_write(vec4(mix(c, mean, weight), 1.0));",
                                                              "aa_write(vec4(mix(c, mean, weight), 1.0))")
    check(bad["m/edge_blur.frag"] != example_files()["m/edge_blur.frag"], "the shader was broken")
    r = submit(c, dict(SMALL, methods=["none", "user:file=m/edge_blur.json"]), bad)
    check(r["ok"], "a shader with a syntax error is queued: %s" % r)
    if r["ok"]:
        e = wait_state(c, r["job"], ["done", "failed"])
        err = e.get("error") or {}
        check(e["state"] == "failed" and err.get("code") == "invalid" and err.get("path") == "methods[1]" and
              re.search(r"m/edge_blur\.frag:1[89]: .*syntax error", err.get("message", "")),
              "its job fails with the file and the line: %s" % err)
    check(len(worker_pids(d)) == 1, "a compile error does not cost the worker process")
    done_before = r_first

    # a shader that does not end: its job fails at the time limit; the next jobs run on a fresh process
    set_time_limit(d, config, LIMIT)
    hang = submit(c, dict(SMALL, size=HANG_SIZE, methods=["none", "user:file=hang.json"]), HANG)["job"]
    wait_inside_shader(d, hang)
    set_time_limit(d, config, LONG_LIMIT)  # the jobs after it start with this one
    after = submit(c, dict(SMALL, methods=["none", "fxaa"]))["job"]
    user_after = submit(c, dict(SMALL, methods=["user:file=m/edge_blur.json"]), example_files())["job"]
    t0 = time.time()
    st = c.request({"op": "status", "job": hang})
    check(st["ok"] and st["job"]["state"] == "running" and c.request({"op": "list"})["ok"],
          "the daemon answers while the job's GPU work hangs (%.3f s)" % (time.time() - t0))
    h = wait_state(c, hang, ["done", "failed"], timeout=LIMIT + 120)
    check(h["state"] == "failed" and h["error"]["code"] == "limit" and
          "time limit of %d s" % LIMIT in h["error"]["message"], "the hung job fails at its time limit: %s" % h.get("error"))
    a = wait_state(c, after, ["done", "failed"])
    u = wait_state(c, user_after, ["done", "failed"])
    check(a["state"] == "done" and u["state"] == "done", "the next jobs succeed: %s %s" % (a.get("error"), u.get("error")))
    check(not alive(first_pid), "the hung process is gone")
    check(len(worker_pids(d)) == 2, "one fresh process was started")
    print("measured: worker processes ready %s s after fork" %
          [l.split()[6] for l in d.read_log().splitlines() if l.startswith("aalabd: worker process ")
           and l.split()[4] == "ready"])
    over = h["finished_at"] - (h["started_at"] + LIMIT)
    print("measured: the hung job failed %.3f s after its %d s limit; the next job started %.3f s later" %
          (over, LIMIT, a["started_at"] - h["finished_at"]))
    check(0 <= over < 5, "the job failed soon after its limit (%.3f s)" % over)
    events, end = c.watch(hang)
    check(events[-1]["event"] == "job_failed" and events[-1]["error"]["code"] == "limit", "its log ends with job_failed")

    # what was accepted before is all there: the first job's results, the queued jobs' results
    for j in (done_before, after, user_after):
        g = c.request({"op": "get", "job": j, "file": "results.json"})
        check(g.get("ok") and json.loads(g["_payload"])["methods"], "job %s's results are kept" % j)

    # a crash of the driver: the process dies mid-job; the job fails with the reason, the next succeeds.
    # SIGABRT as a failed assertion in Mesa raises it (ASan, in the sanitizer build, would catch a SIGSEGV
    # itself, report it and exit 1)
    crash = submit(c, dict(SMALL, size=HANG_SIZE, methods=["user:file=hang.json"]), HANG)["job"]
    wait_inside_shader(d, crash)
    victim = worker_pids(d)[-1]
    os.kill(victim, signal.SIGABRT)
    cj = wait_state(c, crash, ["done", "failed"])
    check(cj["state"] == "failed" and cj["error"]["code"] == "gpu" and "worker process died" in cj["error"]["message"]
          and "signal 6" in cj["error"]["message"], "a dead process fails its job: %s" % cj.get("error"))
    r = submit(c, dict(SMALL, methods=["none", "user:file=m/edge_blur.json"]), example_files())
    check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "and the next job succeeds")

    # the margin of wait_inside_shader: a whole job of the hung job's size and reference, with a method that
    # ends, uses a small share of the rasterizer CPU that is taken to mean "inside the hung shader"
    pid = worker_pids(d)[-1]
    before = rasterizer_cpu_s(pid)
    r = submit(c, dict(SMALL, size=HANG_SIZE, methods=["none"]))
    check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "a job of the hung job's size runs")
    used = rasterizer_cpu_s(pid) - before
    print("measured: a whole %s job used %.3f s of rasterizer CPU (taken as inside the shader: %.1f s)"
          % (HANG_SIZE, used, INSIDE_SHADER_CPU_S))
    check(used < INSIDE_SHADER_CPU_S / 4, "a job's own reference stays far below the mark of the hung shader")

    # a hung job that is cancelled does not wait for its time limit
    stuck = submit(c, dict(SMALL, size=HANG_SIZE, methods=["user:file=hang.json"]), HANG)["job"]
    wait_inside_shader(d, stuck)
    t0 = time.time()
    check(c.request({"op": "cancel", "job": stuck})["ok"], "cancel a hung job")
    s = wait_state(c, stuck, ["done", "failed", "cancelled"])
    took = time.time() - t0
    check(s["state"] == "cancelled" and GRACE - 0.5 < took < LONG_LIMIT / 2, "it is cancelled after the %d s "
          "grace, long before its time limit (%.1f s): %s" % (GRACE, took, s.get("error")))
    print("measured: a hung job was cancelled %.2f s after the cancel (grace %d s)" % (took, GRACE))
    check("did not stop when cancelled: worker process killed" in d.read_log(), "its process was killed")
    r = submit(c, dict(SMALL, methods=["none"]))
    check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "and the next job succeeds")

    # shutdown with a hung job running and a user job queued: both stay queued (drain-timeout 1 s, then the
    # hung process is killed after the cancel grace) and the process ends with the daemon
    hung = submit(c, dict(SMALL, size=HANG_SIZE, methods=["user:file=hang.json"]), HANG)["job"]
    queued = submit(c, dict(SMALL, methods=["user:file=m/edge_blur.json"]), example_files())["job"]
    wait_inside_shader(d, hung)
    pids = worker_pids(d)
    c.close()
    check(d.stop() == 0, "daemon stops")
    time.sleep(0.2)
    check(not any(alive(p) for p in pids), "no worker process is left")
    check(not os.path.exists("/nonexistent-cache-dir"), "compiled shaders go to the state directory, not elsewhere")
    check(os.listdir(os.path.join(d.state, "cache", "spirv")), "the SPIR-V cache is in STATE_DIR/cache")

    # started again without allow-user-methods: the stored user jobs fail, never run in the daemon itself
    log_start = len(d.read_log())
    d2 = Daemon(tmp=d.tmp)
    c = d2.connect()
    for j in (hung, queued):
        e = wait_state(c, j, ["done", "failed"])
        check(e["state"] == "failed" and "user methods are off on this daemon now" in e["error"]["message"],
              "job %s, stored while user methods were allowed, fails: %s" % (j, e.get("error")))
    r = submit(c, dict(SMALL, methods=["none"]))
    check(wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "and a built-in job runs")
    check("worker process" not in d2.read_log()[log_start:], "with no worker process")
    c.close()
    check(d2.stop() == 0, "daemon stops")
    check_log_and_cleanup(d2)  # the directory is d's, removed below
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
