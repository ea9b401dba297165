#!/usr/bin/python3
"""Files that a scene, a job, a configuration or a token names are opened without blocking and only when
they are regular files (engine/util/file_open.h): a FIFO as a scene, a texture, an OBJ mesh (aalab's check
and assimp), its material library (.mtl) or a texture that library names, a glTF mesh or its external
buffer, a token file or a configuration file is refused naming the field, the daemon keeps answering ping
and stops on one SIGTERM; a token file replaced by a FIFO and reloaded keeps the token in use. The
command line refuses a FIFO as a job file, a scene file or a token file instead of waiting on it."""
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from daemon_lib import AALAB, AALABD, TOP_SRC, Client, Daemon, check, finish, wait_state, check_log_and_cleanup, crashed

TOKEN = "0123456789abcdef0123456789abcdef"
tmp = tempfile.mkdtemp(prefix="aalabd-files.")


def check_refused(args, what, needle):
    """aalabd --check with args ends (no hang) with an error that names the field."""
    try:
        r = subprocess.run([AALABD, "--check", "--socket", os.path.join(tmp, "c.sock"), "--state-dir",
                            os.path.join(tmp, "c-state")] + args, capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        check(False, "%s: --check returns (it blocked)" % what)
        return
    check(r.returncode != 0 and needle in r.stderr and "FIFO" in r.stderr,
          "%s: refused naming %s: %s" % (what, needle, r.stderr.strip()))


d = None
try:
    fifo = os.path.join(tmp, "fifo")
    os.mkfifo(fifo)
    check_refused(["--tcp", "127.0.0.1:0", "--token-file", fifo], "a FIFO as the token file", "token-file")
    check_refused(["--config", fifo], "a FIFO as the configuration file", "config")

    # scenes whose files are FIFOs, in a scene folder of their own
    scenes = os.path.join(tmp, "scenes")
    shutil.copytree(os.path.join(TOP_SRC, "scenes", "assets"), os.path.join(scenes, "assets"))
    with open(os.path.join(TOP_SRC, "scenes", "cutout-fence.json")) as f:
        fence = json.load(f)
    fence["textures"]["chainlink"]["file"] = "assets/fifo.png"
    os.mkfifo(os.path.join(scenes, "assets", "fifo.png"))
    with open(os.path.join(scenes, "fifo-texture.json"), "w") as f:
        json.dump(fence, f)
    os.mkfifo(os.path.join(scenes, "fifo-scene.json"))
    os.mkfifo(os.path.join(scenes, "assets", "fifo.obj"))
    with open(os.path.join(TOP_SRC, "scenes", "hard-edges.json")) as f:
        text = f.read()
    check("assets/torus.obj" in text, "hard-edges.json names a mesh file")
    with open(os.path.join(scenes, "fifo-mesh.json"), "w") as f:
        f.write(text.replace("assets/torus.obj", "assets/fifo.obj"))
    # an OBJ whose material library is a FIFO; an OBJ whose library names a FIFO as its texture
    assets = os.path.join(scenes, "assets")
    with open(os.path.join(TOP_SRC, "tests", "assets", "material.obj")) as f:
        obj = f.read()
    with open(os.path.join(assets, "fifo-mtl.obj"), "w") as f:
        f.write(obj.replace("mtllib material.mtl", "mtllib fifo.mtl"))
    os.mkfifo(os.path.join(assets, "fifo.mtl"))
    with open(os.path.join(assets, "fifo-map.obj"), "w") as f:
        f.write(obj.replace("mtllib material.mtl", "mtllib fifo-map.mtl"))
    with open(os.path.join(assets, "fifo-map.mtl"), "w") as f:
        f.write("newmtl painted\nKd 1 1 0.5\nmap_Kd fifo-map.png\n")
    os.mkfifo(os.path.join(assets, "fifo-map.png"))
    # a glTF mesh that is a FIFO; a glTF whose buffer is a FIFO
    os.mkfifo(os.path.join(assets, "fifo.gltf"))
    with open(os.path.join(assets, "box.gltf")) as f:
        box = json.load(f)
    box["buffers"][0]["uri"] = "fifo.bin"
    with open(os.path.join(assets, "fifo-buffer.gltf"), "w") as f:
        json.dump(box, f)
    os.mkfifo(os.path.join(assets, "fifo.bin"))
    for name, mesh in (("fifo-mtl", "assets/fifo-mtl.obj"), ("fifo-map", "assets/fifo-map.obj"),
                       ("fifo-gltf", "assets/fifo.gltf"), ("fifo-buffer", "assets/fifo-buffer.gltf")):
        with open(os.path.join(scenes, name + ".json"), "w") as f:  # the file's own materials
            f.write(text.replace('"assets/torus.obj"}, "material": "torus",', '"%s"},' % mesh))
    token_file = os.path.join(tmp, "token")
    with open(token_file, "w") as f:
        f.write(TOKEN + "\n")
    os.chmod(token_file, 0o600)
    os.makedirs(os.path.join(tmp, "d"))
    d = Daemon("--tcp", "127.0.0.1:0", "--token-file", token_file, tmp=os.path.join(tmp, "d"),
               env={"AALAB_SCENE_DIR": scenes})
    c = d.connect()
    for scene, what in (("fifo-texture", "texture"), ("fifo-mesh", "mesh"), ("fifo-scene", "scene"),
                        ("fifo-mtl", "material library"), ("fifo-map", "texture of a material library"),
                        ("fifo-gltf", "glTF mesh"), ("fifo-buffer", "glTF buffer")):
        t0 = time.time()
        r = c.request({"op": "submit", "job": {"scene": scene, "methods": ["none"], "frames": 1, "size": "32x18",
                                               "reference": {"samples": 2}}})
        if r.get("ok"):
            j = wait_state(c, r["job"], ["done", "failed"], timeout=120)
            err = j.get("error") or {}
        else:
            j, err = {"state": "refused"}, r.get("error") or {}
        check(j["state"] in ("failed", "refused") and ("FIFO" in err.get("message", "") or
                                                       "not a regular file" in err.get("message", "")),
              "a FIFO as the %s is refused: %s" % (what, err))
        check(what == "scene" or err.get("path"), "naming the field: %s" % err.get("path"))
        check(c.request({"op": "ping"}).get("ok"), "the daemon answers ping after the %s (%.1f s)" % (what, time.time() - t0))
    r = c.request({"op": "submit", "job": {"scene": "thin-wires", "methods": ["none"], "frames": 1, "size": "32x18",
                                           "reference": {"samples": 2}}})
    check(r.get("ok") and wait_state(c, r["job"], ["done", "failed"])["state"] == "done", "the next job runs")

    # the token file replaced by a FIFO, then a reload: the old token stays in use, the loop answers
    os.rename(token_file, token_file + ".old")
    os.mkfifo(token_file)
    reloads = d.read_log().count("configuration reloaded")
    d.proc.send_signal(signal.SIGHUP)
    deadline = time.time() + 60
    while d.read_log().count("configuration reloaded") == reloads and time.time() < deadline:
        time.sleep(0.05)
    check("keeping the token in use" in d.read_log() and "FIFO" in d.read_log(), "the reload says why it keeps the token")
    check(c.request({"op": "ping"}).get("ok"), "the daemon answers ping after the reload")
    t = Client(tcp=("127.0.0.1", d.tcp_port), timeout=30)
    check(t.request({"op": "hello", "version": 1, "token": TOKEN}).get("ok"), "the old token is still accepted")
    t.close()

    # the command line: a FIFO as the job file, the scene file or the token file is refused, not waited on
    def aalab(args, env=None):
        try:
            return subprocess.run([AALAB] + args, capture_output=True, text=True, timeout=60,
                                  env=dict(os.environ, **(env or {})))
        except subprocess.TimeoutExpired:
            return None
    r = aalab(["submit", fifo, "--connect", d.socket])
    check(r is not None and r.returncode != 0 and "job" in r.stderr and "FIFO" in r.stderr,
          "aalab submit refuses a FIFO as the job file: %s" % (r and r.stderr.strip()))
    r = aalab(["submit", "--scene-file", fifo, "--connect", d.socket])
    check(r is not None and r.returncode != 0 and "scene-file" in r.stderr and "FIFO" in r.stderr,
          "aalab submit refuses a FIFO as the scene file: %s" % (r and r.stderr.strip()))
    r = aalab(["list", "--connect", "tcp:127.0.0.1:%d" % d.tcp_port, "--token-file", fifo])
    check(r is not None and r.returncode != 0 and "FIFO" in r.stderr,
          "aalab refuses a FIFO as the token file: %s" % (r and r.stderr.strip()))
    c.close()
    t0 = time.time()
    check(d.stop() == 0, "one SIGTERM stops the daemon (%.1f s)" % (time.time() - t0))
except Exception as e:  # noqa: BLE001 - any failure is reported with the daemon's log
    crashed(d, e)
finally:
    check_log_and_cleanup(d)
    shutil.rmtree(tmp, ignore_errors=True)
finish()
