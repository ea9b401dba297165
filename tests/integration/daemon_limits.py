#!/usr/bin/python3
"""aalabd's limits with clear errors: max-connections, idle and request timeouts, retention of finished
jobs by count, and the scene cache (a changed scene file is loaded again)."""
import os
import re
import shutil
import socket
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import Client, Daemon, SMALL_JOB, check, finish, http_get, wait_state, check_log_and_cleanup, crashed

d = None
tmp = tempfile.mkdtemp(prefix="aalabd-limits.")
try:
    scenes = os.path.join(tmp, "scenes")
    shutil.copytree(os.environ["AALAB_SCENE_DIR"], scenes)
    d = Daemon("--max-connections", "4", "--idle-timeout", "2", "--request-timeout", "2",
               "--retention-jobs", "2", http=True, env={"AALAB_SCENE_DIR": scenes})
    # max-connections: the fifth gets one error line and is closed
    conns = [d.connect() for _ in range(4)]
    for c in conns:
        c.request({"op": "ping"})
    extra = d.connect()
    r = extra.read()
    check(r["error"]["code"] == "limit" and "too many connections" in r["error"]["message"],
          "connection 5 of max 4 gets a limit error")
    extra.close()
    for c in conns:
        c.close()
    time.sleep(0.3)

    # idle timeout: a silent connection is closed after 2 s
    idle = d.connect()
    idle.sock.settimeout(10)
    t0 = time.time()
    closed = idle.sock.recv(1) == b""
    check(closed and 1.5 < time.time() - t0 < 6, "an idle connection is closed after idle-timeout (%.1f s)" % (time.time() - t0))
    # request timeout: half a line, then nothing
    slow = d.connect()
    slow.send_raw(b'{"op": "pi')
    r = slow.read()
    check(r["error"]["code"] == "timeout", "an unfinished line gets a timeout error")

    # retention: three jobs, the oldest is deleted once the third finishes
    c = d.connect()
    ids = []
    for i in range(3):
        ids.append(c.request({"op": "submit", "job": dict(SMALL_JOB, frames=1)})["job"])
        wait_state(c, ids[-1], ["done"])
    # status says done only once retention has run in the same step (daemon/worker_run.c): asked at once
    r = c.request({"op": "status", "job": ids[0]})
    check(not r.get("ok") and r["error"]["code"] == "not_found", "the oldest finished job is gone (retention-jobs 2)")
    check(not os.path.exists(os.path.join(d.state, "jobs", ids[0])), "and its directory")
    check(all(c.request({"op": "status", "job": j})["ok"] for j in ids[1:]), "the two newest are kept")

    # scene cache: hits for the same file, a reload when the file changes
    metrics = http_get(d.http_port, "/metrics")[2].decode()
    check("aalab_scene_cache_misses_total 1\n" in metrics and "aalab_scene_cache_hits_total 2\n" in metrics,
          "three jobs on one scene: one miss, two hits")
    path = os.path.join(scenes, "thin-wires.json")
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(text + "\n")  # same scene, new size and time: the cache must notice
    os.utime(path, (time.time() + 5, time.time() + 5))
    j = c.request({"op": "submit", "job": dict(SMALL_JOB, frames=1)})["job"]
    wait_state(c, j, ["done", "failed"])
    metrics = http_get(d.http_port, "/metrics")[2].decode()
    check("aalab_scene_cache_reloads_total 1\n" in metrics, "a changed scene file is loaded again")

    # and when a file the scene's load read changes: its mesh, its texture (only the scene file was
    # checked, and jobs rendered the old mesh and texture)
    os.makedirs(os.path.join(scenes, "cached"))
    with open(os.path.join(scenes, "cached", "tri.obj"), "w") as f:
        f.write("v -1 0 0\nv 1 0 0\nv 0 1.5 0\nf 1 2 3\n")
    shutil.copy(os.path.join(scenes, "assets", "tiles.png"), os.path.join(scenes, "cached", "tex.png"))
    with open(os.path.join(scenes, "cached.json"), "w") as f:
        f.write('''{"name": "cached", "background": "#202020", "ambient": "#FFFFFF",
 "textures": {"t": {"file": "cached/tex.png"}},
 "materials": {"m": {"color": "#FFFFFF", "specular": 0}, "tm": {"texture": "t", "specular": 0}},
 "objects": [{"name": "tri", "mesh": {"type": "file", "path": "cached/tri.obj"}, "material": "m"},
             {"name": "quad", "mesh": {"type": "plane", "size": 1}, "material": "tm", "position": [2, 0.5, 0],
              "rotation": [90, 0, 0]}],
 "camera": {"position": [0.5, 0.7, 4], "target": [0.5, 0.7, 0], "fov": 50}}''')

    def frame_of_job():
        j = c.request({"op": "submit", "job": {"scene": "cached", "methods": ["none"], "frames": 1, "size": "64x36",
                                               "reference": {"samples": 4}}})["job"]
        check(wait_state(c, j, ["done", "failed"])["state"] == "done", "a job on the scene with files runs")
        return http_get(d.http_port, "/v1/jobs/%s/frames/none/0.png" % j)[2]

    def reloads():
        text = http_get(d.http_port, "/metrics")[2].decode()
        return int(re.search(r"^aalab_scene_cache_reloads_total (\d+)$", text, re.M).group(1))

    first, before = frame_of_job(), reloads()
    check(frame_of_job() == first and reloads() == before, "nothing changed: the cached scene serves, the same frame")
    with open(os.path.join(scenes, "cached", "tri.obj"), "w") as f:
        f.write("v -1 0 0\nv 1 0 0\nv 0.6 0.4 0\nf 1 2 3\n")
    moved = frame_of_job()
    check(reloads() == before + 1 and moved != first, "a changed mesh file is loaded again, and the frame shows it")
    shutil.copy(os.path.join(scenes, "assets", "chainlink.png"), os.path.join(scenes, "cached", "tex.png"))
    check(frame_of_job() != moved and reloads() == before + 2, "a changed texture file is loaded again, and shows")
    c.close()
    check(d.stop() == 0, "aalabd exits 0")
except Exception as e:
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
finish()
