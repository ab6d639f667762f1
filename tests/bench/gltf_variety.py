#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""glTF files with every kind of channel keyrot's reader merges, for
same_output.sh to run two builds on:
  tests/bench/gltf_variety.py DIR
writes into DIR (made if missing):
- mixed.glb and mixed.gltf (data: URI): channels on different key times;
  LINEAR rotations with two quaternions off unit length (warned about),
  STEP rotations, translations, scales, SHORT rotations interleaved
  (byteStride 12);
- spline.glb: CUBICSPLINE rotations and translations on different key
  times, and rotations with sparse substitutes;
- weights.glb: two animations; LINEAR and CUBICSPLINE morph weights, a
  rotation beside them on other key times.
"""
import os
import sys

import numpy as np
from scipy.spatial.transform import Rotation

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import gltf_files as G  # noqa: E402

rng = np.random.default_rng(7)
TIMES = np.arange(40) / 30.0
OTHER_TIMES = np.arange(25) / 17.0 + 0.01  # (between the others, and past their end)


def rotations(n, spread=1.0):
    """n random unit quaternions as glTF stores them (x, y, z, w)."""
    return Rotation.from_rotvec(rng.normal(size=(n, 3)) * spread).as_quat()


def spline(n, width):
    """CUBICSPLINE outputs: per key an in-tangent, a value and an out-tangent."""
    v = rng.normal(size=(n, 3, width)) * 0.2
    if width == 4:
        v[:, 1, :] = rotations(n)
    return v


def main(out):
    os.makedirs(out, exist_ok=True)
    b = G.Builder()
    b.skeleton(4)
    off_unit = rotations(40)
    off_unit[5] *= 1.5
    off_unit[9] *= 1.00001
    b.animation([
        {"node": 0, "path": "rotation", "times": TIMES, "values": off_unit},
        {"node": 0, "path": "translation", "times": OTHER_TIMES, "values": rng.normal(size=(25, 3))},
        {"node": 1, "path": "scale", "times": OTHER_TIMES, "values": 1 + 0.1 * rng.normal(size=(25, 3))},
        {"node": 1, "path": "rotation", "times": OTHER_TIMES, "values": rotations(25), "interpolation": "STEP"},
        {"node": 2, "path": "translation", "times": TIMES, "values": rng.normal(size=(40, 3))},
        {"node": 3, "path": "rotation", "times": TIMES, "values": rotations(40, 0.3), "component": G.SHORT,
         "stride": 12},
    ])
    b.write(os.path.join(out, "mixed.glb"), "glb")
    b.write(os.path.join(out, "mixed.gltf"), "datauri")

    b = G.Builder()
    b.skeleton(2)
    b.animation([
        {"node": 0, "path": "rotation", "times": TIMES, "values": spline(40, 4), "interpolation": "CUBICSPLINE"},
        {"node": 0, "path": "translation", "times": OTHER_TIMES, "values": spline(25, 3),
         "interpolation": "CUBICSPLINE"},
        {"node": 1, "path": "rotation", "times": OTHER_TIMES, "values": rotations(25), "sparse_every": 4},
    ])
    b.write(os.path.join(out, "spline.glb"), "glb")

    b = G.Builder()
    b.json["nodes"] += [{"name": "face", "mesh": b.morph_mesh(3)}, {"name": "brow", "mesh": b.morph_mesh(2)}]
    b.animation([
        {"node": 0, "path": "weights", "times": OTHER_TIMES, "values": rng.uniform(size=(25 * 3, 1))},
        {"node": 0, "path": "rotation", "times": TIMES, "values": rotations(40)},
        {"node": 1, "path": "weights", "times": TIMES, "values": rng.uniform(size=(40 * 3 * 2, 1)),
         "interpolation": "CUBICSPLINE"},
    ], name="talk")
    b.animation([{"node": 1, "path": "translation", "times": OTHER_TIMES, "values": rng.normal(size=(25, 3))}],
                name="move")
    b.write(os.path.join(out, "weights.glb"), "glb")


if __name__ == "__main__":
    main(sys.argv[1])
