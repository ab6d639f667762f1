#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""keyrot beside gltfpack on the glTF job, by hand:
  tests/bench/gltf_bench.py KEYROT [--runs N] [--baseline OTHER_KEYROT] [--gltfpack PATH]
A rig of 60 joints with 20,000 keys each at 120 Hz (a rotation per joint,
and a translation per joint that only the root's moves: a 38 MB .glb) is
resampled to 30 fps, glb to glb, by `keyrot resample rig.glb --fps 30 -o
out.glb` and by `gltfpack -i rig.glb -o out.glb -af 30 -noq` (Debian's
gltfpack; -noq keeps 32-bit floats, as keyrot does), taking turns run by
run. Prints the medians of wall time and peak RSS, the output sizes, and
the ratio; keyrot --compact (16-bit rotations, as gltfpack's) beside them;
with --baseline, another keyrot takes turns too.
"""
import argparse
import json
import os
import resource
import statistics
import struct
import subprocess
import sys
import tempfile
import time

JOINTS, KEYS, RATE = 60, 20000, 120


def rig(path):
    # (in a process of its own: a child's peak RSS on Linux counts from its parent's at the fork)
    import numpy as np
    from scipy.spatial.transform import Rotation
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    import gltf_files

    rng = np.random.default_rng(48)
    t = np.arange(KEYS) / RATE
    b = gltf_files.Builder()
    b.skeleton(JOINTS)
    channels = []
    for j in range(JOINTS):
        wave = np.zeros((KEYS, 3))
        for _ in range(4):
            wave += rng.uniform(5, 20) * np.sin(2 * np.pi * rng.uniform(0.1, 0.8, 3) * t[:, None] + rng.uniform(0, 6, 3))
        channels.append({"node": j, "path": "rotation", "times": t,
                         "values": Rotation.from_rotvec(np.radians(wave)).as_quat()})
        offset = np.tile([0.0, 0.1 * (j % 5), 0.0], (KEYS, 1))
        if j == 0:
            offset = offset + np.column_stack([np.sin(t), 0 * t, 0.5 * t])
        channels.append({"node": j, "path": "translation", "times": t, "values": offset})
    b.animation(channels)
    b.write(path, "glb")


def float32_size(path):
    """The size of a .glb were its animation outputs 32-bit floats (gltfpack stores rotations as
    normalised 16-bit integers, even with -noq)."""
    data = open(path, "rb").read()
    doc = json.loads(data[20:20 + struct.unpack_from("<I", data, 12)[0]])
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}
    size = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5126: 4}
    more = 0
    for anim in doc.get("animations", []):
        for s in anim["samplers"]:
            a = doc["accessors"][s["output"]]
            more += a["count"] * width[a["type"]] * (4 - size[a["componentType"]])
    return len(data) + more


def run(argv):
    """Wall seconds and peak RSS (MB) of one run."""
    start = time.perf_counter()
    child = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    seconds = time.perf_counter() - start
    if status != 0:
        sys.exit(f"{' '.join(argv)} failed: {child.stderr.read().decode()}")
    return seconds, usage.ru_maxrss / 1024


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("keyrot")
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--baseline")
    parser.add_argument("--gltfpack", default="gltfpack")
    parser.add_argument("--rig", help=argparse.SUPPRESS)  # writes the rig there, and nothing else
    args = parser.parse_args()
    if args.rig:
        return rig(args.rig)
    with tempfile.TemporaryDirectory() as work:
        src = os.path.join(work, "rig.glb")
        subprocess.run([sys.executable, os.path.abspath(__file__), args.keyrot, "--rig", src], check=True)
        jobs = [("keyrot", [args.keyrot, "resample", src, "--fps", "30", "-o", os.path.join(work, "keyrot.glb")]),
                ("keyrot --compact", [args.keyrot, "resample", src, "--fps", "30", "--compact", "-o",
                                      os.path.join(work, "compact.glb")])]
        if args.baseline:
            jobs.append(("baseline keyrot", [args.baseline, "resample", src, "--fps", "30", "-o",
                                             os.path.join(work, "baseline.glb")]))
        jobs.append(("gltfpack -af 30 -noq", [args.gltfpack, "-i", src, "-o", os.path.join(work, "gltfpack.glb"),
                                             "-af", "30", "-noq"]))
        results = {name: [] for name, _ in jobs}
        for _ in range(args.runs + 1):  # the first turn warms the page cache
            for name, argv in jobs:
                results[name].append(run(argv))
        print(f"rig: {JOINTS} joints x {KEYS} keys at {RATE} Hz, {os.path.getsize(src) / 1e6:.1f} MB; "
              f"to 30 fps, medians of {args.runs}")
        print(f"{'':24} {'wall s':>8} {'peak MB':>8} {'output MB':>10}")
        medians = {}
        for name, argv in jobs:
            runs = results[name][1:]
            medians[name] = statistics.median(s for s, _ in runs)
            out = argv[argv.index("-o") + 1]
            print(f"{name:24} {medians[name]:8.3f} {statistics.median(m for _, m in runs):8.1f} "
                  f"{os.path.getsize(out) / 1e6:10.2f}")
        gltfpack_out = os.path.join(work, "gltfpack.glb")
        print(f"gltfpack's output were its rotations 32-bit floats: {float32_size(gltfpack_out) / 1e6:.2f} MB")
        print(f"keyrot / gltfpack: {medians['keyrot'] / medians['gltfpack -af 30 -noq']:.2f} the time, "
              f"{os.path.getsize(jobs[0][1][-1]) / float32_size(gltfpack_out):.3f} the size at 32-bit floats")
        print(f"keyrot --compact / gltfpack: {medians['keyrot --compact'] / medians['gltfpack -af 30 -noq']:.2f} "
              f"the time, {os.path.getsize(jobs[1][1][-1]) / os.path.getsize(gltfpack_out):.3f} the size")


if __name__ == "__main__":
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    main()
