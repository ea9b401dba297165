#!/usr/bin/python3
"""aalabd's errors name scene files as found in their scene folder, never by a path of the server's
(aalabd(8), SCENES): a broken scene, a missing mesh, a FIFO texture and a scene file that is a FIFO fail
their jobs with messages that start from the scene's file name and hold neither the scene folder nor the
state folder. `scenes` lists only what a submit accepts: a symbolic link that leads out of the scene
folder is not listed (a submit of it is refused)."""
import json
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import TOP_SRC, Daemon, check, finish, wait_state, check_log_and_cleanup, crashed

tmp = tempfile.mkdtemp(prefix="aalabd-scenes.")
SMALL = {"methods": ["none"], "frames": 1, "size": "32x18", "reference": {"samples": 2}}

d = None
try:
    scenes = os.path.join(tmp, "scenes")
    shutil.copytree(os.path.join(TOP_SRC, "scenes", "assets"), os.path.join(scenes, "assets"))
    with open(os.path.join(TOP_SRC, "scenes", "hard-edges.json")) as f:
        text = f.read()
    with open(os.path.join(scenes, "good.json"), "w") as f:
        f.write(text)
    with open(os.path.join(scenes, "no-mesh.json"), "w") as f:
        f.write(text.replace("assets/torus.obj", "assets/missing.obj"))
    doc = json.loads(text)
    doc["objects"][0]["position"] = "up"
    with open(os.path.join(scenes, "bad-field.json"), "w") as f:
        json.dump(doc, f)
    with open(os.path.join(TOP_SRC, "scenes", "cutout-fence.json")) as f:
        fence = json.load(f)
    fence["textures"]["chainlink"]["file"] = "assets/fifo.png"
    os.mkfifo(os.path.join(scenes, "assets", "fifo.png"))
    with open(os.path.join(scenes, "fifo-texture.json"), "w") as f:
        json.dump(fence, f)
    os.mkfifo(os.path.join(scenes, "fifo-scene.json"))
    outside = os.path.join(tmp, "outside.json")
    shutil.copy(os.path.join(scenes, "good.json"), outside)
    os.symlink(outside, os.path.join(scenes, "leads-out.json"))
    os.symlink("/etc/passwd", os.path.join(scenes, "passwd.json"))

    d = Daemon(env={"AALAB_SCENE_DIR": scenes})
    c = d.connect()
    listed = c.request({"op": "scenes"})["scenes"]
    check("good" in listed and "bad-field" in listed, "scenes lists the scene files: %s" % listed)
    check("leads-out" not in listed and "passwd" not in listed, "but not the links that lead out of the folder")
    for name in ("leads-out", "passwd"):
        r = c.request({"op": "submit", "job": dict(SMALL, scene=name)})
        check(not r.get("ok") and tmp not in json.dumps(r), "a submit of %s is refused without paths: %s" % (name, r))

    for scene, start, needle in (("bad-field", "bad-field.json: ", "objects[0]"),
                                 ("no-mesh", "no-mesh.json: ", "assets/missing.obj"),
                                 ("fifo-texture", "fifo-texture.json: ", "assets/fifo.png"),
                                 ("fifo-scene", "scene file 'fifo-scene.json'", "not a regular file")):
        r = c.request({"op": "submit", "job": dict(SMALL, scene=scene)})
        if r.get("ok"):
            st = wait_state(c, r["job"], ["done", "failed"], timeout=120)
            err = st.get("error") or {}
        else:
            st, err = {"state": "refused"}, r.get("error") or {}
        msg = err.get("message", "")
        check(st["state"] in ("failed", "refused") and msg.startswith(start) and needle in msg,
              "%s: the error starts from the scene's file name: %s" % (scene, msg))
        check(scenes not in msg and d.state not in msg and tmp not in msg,
              "%s: and shows neither the scene folder nor the state folder" % scene)
    r = c.request({"op": "submit", "job": dict(SMALL, scene="good")})
    check(r.get("ok") and wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "a good scene runs")
    c.close()
    check(d.stop() == 0, "daemon stops")
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
