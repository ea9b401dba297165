#!/usr/bin/env python3
"""Generates the assets of the hard-case scenes (docs/hard-cases.md) into scenes/assets/
(standard library only, with the helpers of make_scene_assets.py):
bumps.gltf: a unit quad (xy plane, facing +z) with a shiny metal material and a tangent-space normal map
of fine egg-crate bumps (slopes up to ~32 degrees), its texture repeated 12 times across: the normals vary
far faster than the pixels, so the highlight of a point light aliases on a surface without a single edge.
sparks.gltf: tiny black quads that glow (KHR_materials_emissive_strength 1e3 to 1e5): emitters far
brighter than anything else, for box resolves in linear HDR.
The outputs are committed; rerun after changing this script:  python3 scripts/make_hard_case_assets.py"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_scene_assets import OUT, Gltf, quad  # noqa: E402

BUMP_TEXELS = 64   # texture size
BUMP_PERIOD = 8    # texels per bump
BUMP_HEIGHT = 0.8  # height amplitude in texels: slopes up to atan(2 pi 0.8 / 8) = 32 degrees


def bump_normal(x, y):
    """Tangent-space normal of h = A (sin(2 pi x / P) + sin(2 pi y / P)), encoded as RGB bytes."""
    k = 2 * math.pi / BUMP_PERIOD
    dx = BUMP_HEIGHT * k * math.cos(k * (x + 0.5))
    dy = BUMP_HEIGHT * k * math.cos(k * (y + 0.5))
    n = (-dx, -dy, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(int(round(255 * (0.5 + 0.5 * c / length))) for c in n)


def bumps(path, repeat=12):
    g = Gltf()
    tex = g.texture(g.image(BUMP_TEXELS, BUMP_TEXELS, 3, bump_normal))
    mat = g.material(name="bumpy-metal", normalTexture={"index": tex, "scale": 1.0},
                     pbrMetallicRoughness={"baseColorFactor": [0.9, 0.9, 0.92, 1.0], "metallicFactor": 1.0,
                                           "roughnessFactor": 0.3})
    uv = [(0, 0), (repeat, 0), (repeat, repeat), (0, repeat)]
    g.mesh_node([quad(g, material=mat, uv=uv)], "bumps")
    with open(path, "w") as f:
        f.write(g.json_text())


def halton(index, base):
    f, r = 1.0, 0.0
    while index > 0:
        f /= base
        r += f * (index % base)
        index //= base
    return r


def sparks(path, count=24, size=0.01):
    """count tiny quads on a loose grid in the xy plane, strengths from 1e3 to 1e5 (log-spaced)."""
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    for i in range(count):
        strength = 10 ** (3 + 2 * i / (count - 1))
        hue = [(1.0, 0.85, 0.6), (0.6, 0.8, 1.0), (1.0, 0.5, 0.3)][i % 3]
        mat = g.material(name="spark%d" % i, emissiveFactor=list(hue),
                         pbrMetallicRoughness={"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0.0},
                         extensions={"KHR_materials_emissive_strength": {"emissiveStrength": strength}})
        # a deterministic scatter over [-1, 1] x [-0.5, 0.5] (Halton 2, 3)
        x = -1 + 2 * halton(i + 1, 2)
        y = -0.5 + halton(i + 1, 3)
        g.mesh_node([quad(g, size=size, material=mat)], "spark%d" % i, (x, y, 0))
    with open(path, "w") as f:
        f.write(g.json_text())


def main():
    bumps(os.path.join(OUT, "bumps.gltf"))
    sparks(os.path.join(OUT, "sparks.gltf"))
    print("wrote bumps.gltf sparks.gltf to", os.path.normpath(OUT))


if __name__ == "__main__":
    sys.exit(main())
