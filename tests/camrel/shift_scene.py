"""Writes a copy of a scene file with everything placed `offset` units away (objects, point lights, spin
pivots, the camera, its paths' cameras, keys and orbit centres): the far copy of a control scene.
Usage: shift_scene.py IN.json OUT.json DX DY DZ [--shadow --point-light --spin]"""
import json
import sys

src, dst = sys.argv[1], sys.argv[2]
d = [float(v) for v in sys.argv[3:6]]
extras = set(sys.argv[6:])
scene = json.load(open(src))


def moved(p):
    return [p[0] + d[0], p[1] + d[1], p[2] + d[2]]


# the same additions to the control and its far copy: what else must stay relative to the eye
if "--shadow" in extras:
    for light in scene["lights"]:
        if light["type"] == "directional":
            light["casts_shadow"] = True
if "--point-light" in extras:
    scene["lights"].append({"type": "point", "position": [0.0, 1.2, -0.6], "color": "#FFD0A0", "intensity": 10.0})
if "--spin" in extras:
    for o in scene["objects"]:
        if o["name"].startswith("crate"):
            o["animation"] = {"spin": {"axis": [0, 1, 0], "degrees_per_second": 90}}

for o in scene["objects"]:
    o["position"] = moved(o.get("position", [0, 0, 0]))
    spin = o.get("animation", {}).get("spin")
    if spin and "pivot" in spin:
        spin["pivot"] = moved(spin["pivot"])
for light in scene["lights"]:
    if "position" in light:
        light["position"] = moved(light["position"])


def move_camera(c):
    for k in ("position", "target"):
        if k in c:
            c[k] = moved(c[k])


move_camera(scene["camera"])
for path in scene.get("paths", []):
    if "center" in path:
        path["center"] = moved(path["center"])
    move_camera(path.get("camera", {}))
    for key in path.get("keys", []):
        move_camera(key)
scene["name"] += "-moved"
json.dump(scene, open(dst, "w"), indent=1)
