#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""keyrot reduce beside glTF-Transform's `resample` and gltfpack, by hand:
  npm install --prefix /tmp/peers @gltf-transform/cli gltfpack
  tests/bench/reduce_peers.py KEYROT /tmp/peers/node_modules/.bin
On two dense files (motion-capture-like 120 Hz with 0.001-degree noise, and
animation baked at 24 fps), each peer's output is measured with keyrot:
its largest rotation error at the input's keys (both resampled at the
input's rate, then `keyrot compare`); keyrot reduce is then run with that
error as --tol, and the rotation keys each keeps are counted.
"""
import json
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np
from scipy.spatial.transform import Rotation

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import gltf_files  # noqa: E402

KEYROT, BIN = os.path.abspath(sys.argv[1]), sys.argv[2]


def smooth(rng, n, fps, scale):
    t = np.arange(n)[:, None] / fps
    out = np.zeros((n, 3))
    for _ in range(4):
        out += scale * rng.uniform(0.2, 1) * np.sin(2 * np.pi * rng.uniform(0.1, 0.8, 3) * t + rng.uniform(0, 6, 3))
    return out


def dense(path, fps, seconds, noise_deg, rng, joints=20):
    n = int(fps * seconds)
    b = gltf_files.Builder()
    b.skeleton(joints)
    channels = []
    for j in range(joints):
        angles = np.radians(smooth(rng, n, fps, 15) + rng.normal(0, noise_deg, (n, 3)))
        channels.append({"node": j, "path": "rotation", "times": np.arange(n) / fps,
                         "values": Rotation.from_rotvec(angles).as_quat()})
    b.animation(channels)
    b.write(path, "glb")


def rotation_keys(path):
    data = open(path, "rb").read()
    length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + length])
    return sum(doc["accessors"][s["input"]]["count"]
               for a in doc.get("animations", []) for c, s in zip(a["channels"], a["samplers"])
               if c["target"]["path"] == "rotation")


def error_deg(reference, candidate, fps, work):
    ref, cand = os.path.join(work, "ref.csv"), os.path.join(work, "cand.csv")
    subprocess.run([KEYROT, "resample", reference, "--fps", str(fps), "--rep", "quat", "-o", ref], check=True)
    subprocess.run([KEYROT, "resample", candidate, "--fps", str(fps), "--rep", "quat", "-o", cand], check=True)
    p = subprocess.run([KEYROT, "compare", ref, cand, "--tol", "1000", "--report", "json"], capture_output=True,
                       text=True)
    return json.loads(p.stdout)["max_difference"]


def main():
    rng = np.random.default_rng(34)
    print("| file | peer | its keys | its largest error | keyrot reduce --tol that | keys |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as work:
        for name, fps, noise in (("mocap 120 Hz", 120, 0.001), ("baked 24 fps", 24, 0.0)):
            src = os.path.join(work, "dense.glb")
            dense(src, fps, 20, noise, rng)
            peers = [("gltf-transform resample", [os.path.join(BIN, "gltf-transform"), "resample", src, "{out}",
                                                  "--tolerance", tol], tol) for tol in ("0.0001", "0.001")]
            peers.append(("gltfpack -noq", [os.path.join(BIN, "gltfpack"), "-i", src, "-o", "{out}", "-noq"], ""))
            for peer, args, tol in peers:
                out = os.path.join(work, "peer.glb")
                subprocess.run([a.replace("{out}", out) for a in args], check=True, capture_output=True)
                err = error_deg(src, out, fps, work)
                mine = os.path.join(work, "mine.glb")
                subprocess.run([KEYROT, "reduce", src, "--tol", repr(err), "-o", mine], check=True,
                               capture_output=True)
                print(f"| {name} ({rotation_keys(src)} keys) | {peer} {tol} | {rotation_keys(out)} | {err:.4g} deg "
                      f"| {err:.4g} | {rotation_keys(mine)} |")


if __name__ == "__main__":
    main()
