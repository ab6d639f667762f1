#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""keyrot reduce against its guarantee, checked independently.

Dense tracks are generated here (motion-capture-like noise at 120 Hz, a
baked turn of more than 180 degrees, sign flips between keys, a step track,
translation-only changes, constant stretches, a constant track). For each
method and tolerance:
- the kept keys are input keys, to the bit (times, quaternions,
  translations), the first and the last among them (a constant track: one);
- the guarantee, twice: the kept keys played with the method (scipy's Slerp,
  numpy's nlerp, held for step; translations linear) are within --tol of
  every input key at its time, and `keyrot resample` of the kept keys at
  120 fps passes `keyrot compare` with the input at --tol;
- no two consecutive kept keys turn more than 180 degrees apart;
- tolerance 0 drops only keys that replay exactly (the inside of runs of
  equal keys);
- --report json agrees with the output, and its largest errors with the
  replay; bad tolerances are one line, exit 2;
- random keys resampled at 24 fps reduce to those keys, to the frame;
- a glTF file is reduced in place: each sampler's kept keys are the input's
  32-bit floats, and (where installed) the Khronos validator accepts it.

Usage: reduce_test.py KEYROT [VALIDATOR_JS]. Exit 0 when all pass, 1
otherwise, 77 without scipy.
"""
import csv
import io
import json
import math
import os
import struct
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from scipy.spatial.transform import Rotation, Slerp
except ImportError:  # pragma: no cover
    print("reduce_test: numpy/scipy not installed (apt-get install python3-scipy); skipped")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_files  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import fail, ok, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])
VALIDATOR = sys.argv[2] if len(sys.argv) > 2 else None


def run(args, stdin=None):
    p = subprocess.run([KEYROT] + args, input=stdin, capture_output=True)
    return p.returncode, p.stdout.decode(), p.stderr.decode()


def write_csv(path, tracks):
    """tracks: name -> (times, quats wxyz (n x 4), translations (n x 3) or None)."""
    with open(path, "w") as f:
        f.write("track,time,qw,qx,qy,qz,tx,ty,tz\n")
        for name, (times, quats, moves) in tracks.items():
            for i, t in enumerate(times):
                row = [name, repr(float(t))] + [repr(float(v)) for v in quats[i]]
                row += [repr(float(v)) for v in moves[i]] if moves is not None else ["", "", ""]
                f.write(",".join(row) + "\n")


def read_csv(text):
    """name -> list of (time, quat wxyz, translation or None), as floats parsed from the text."""
    out = {}
    for r in csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")):
        move = (float(r["tx"]), float(r["ty"]), float(r["tz"])) if r.get("tx") else None
        out.setdefault(r.get("track", ""), []).append(
            (float(r["time"]), tuple(float(r[c]) for c in ("qw", "qx", "qy", "qz")), move))
    return out


def smooth(rng, n, scale):
    """A smooth random curve (n x 3): sums of a few sines."""
    t = np.arange(n)[:, None] / 120.0
    out = np.zeros((n, 3))
    for _ in range(4):
        out += scale * rng.uniform(0.2, 1) * np.sin(2 * math.pi * rng.uniform(0.1, 0.8, 3) * t + rng.uniform(0, 6, 3))
    return out


def wxyz(rotations):
    q = rotations.as_quat()  # x y z w
    return np.column_stack([q[:, 3], q[:, 0], q[:, 1], q[:, 2]])


def tracks(rng):
    n = 600
    times = np.arange(n) / 120.0
    mocap = Rotation.from_rotvec(np.radians(smooth(rng, n, 15)) + np.radians(rng.normal(0, 0.002, (n, 3))))
    flips = wxyz(Rotation.from_rotvec(np.radians(smooth(rng, n, 30))))
    flips[1::3] *= -1  # the same rotations, every third key's sign flipped
    turn = Rotation.from_euler("z", np.linspace(0, 720, n), degrees=True)  # two whole turns
    step = wxyz(Rotation.from_euler("x", np.repeat(np.arange(n // 40) * 17.0, 40), degrees=True))
    still = np.tile([1.0, 0, 0, 0], (n, 1))
    moving = np.column_stack([np.minimum(times, 2.0), np.zeros(n), np.where(times < 3, 0.0, 0.25)])
    runs = wxyz(Rotation.from_euler("y", np.repeat(rng.uniform(-170, 170, n // 20), 20), degrees=True))
    return {
        "mocap": (times, wxyz(mocap), smooth(rng, n, 0.1)),
        "flips": (times, flips, None),
        "turn": (times, wxyz(turn), None),
        "step": (times, step, None),
        "translation_only": (times, still, moving),
        "runs": (times, runs, None),
        "constant": (times, np.tile([0.5, 0.5, 0.5, 0.5], (n, 1)), np.tile([1.0, 2.0, 3.0], (n, 1))),
    }


def replay(kept, t, method):
    """The kept keys (time, wxyz, translation) played at time t, as the method plays them."""
    times = [k[0] for k in kept]
    j = max(0, min(len(kept) - 2, int(np.searchsorted(times, t, side="right")) - 1)) if len(kept) > 1 else 0
    a = kept[j]
    if len(kept) == 1 or t <= a[0]:
        return np.array(a[1]), a[2]
    b = kept[j + 1]
    if t >= b[0]:
        return np.array(b[1]), b[2]
    h = (t - a[0]) / (b[0] - a[0])
    qa, qb = np.array(a[1]), np.array(b[1])
    move = None if a[2] is None else (1 - h) * np.array(a[2]) + h * np.array(b[2])
    if method == "step":
        return qa, a[2]
    if method == "nlerp":
        if np.dot(qa, qb) < 0:
            qb = -qb
        q = (1 - h) * qa + h * qb
        return q / np.linalg.norm(q), move
    ends = Rotation.from_quat([[qa[1], qa[2], qa[3], qa[0]], [qb[1], qb[2], qb[3], qb[0]]])
    return wxyz(Slerp([0, 1], ends)([h]))[0], move


def angle_deg(p, q):
    p = np.array(p) / np.linalg.norm(p)
    q = np.array(q) / np.linalg.norm(q)
    return math.degrees(2 * math.atan2(np.linalg.norm(p[0] * q[1:] - q[0] * p[1:] - np.cross(p[1:], q[1:])),
                                       abs(float(np.dot(p, q)))))


def check_csv(work, data):
    path = os.path.join(work, "dense.csv")
    write_csv(path, data)
    status, text, err = run(["reduce", path, "--tol", "0"])
    source = read_csv(open(path).read())
    for method in ("slerp", "nlerp", "step", "squad"):
        for tol, tol_t in ((0.01, 0.001), (0.5, 0.01), (0.0, 0.0)):
            out = os.path.join(work, f"reduced_{method}_{tol}.csv")
            status, text, err = run(["reduce", path, "--method", method, "--tol", str(tol), "--tol-translation",
                                     str(tol_t), "-o", out, "--report", "json"])
            label = f"reduce --method {method} --tol {tol}"
            if status != 0:
                fail(f"{label}: status {status}, {err.strip()}")
                continue
            reported = {t["track"]: t for t in json.loads(text)["tracks"]}
            reduced = read_csv(open(out).read())
            problems = []
            counts = []
            for name, keys in source.items():
                kept = reduced.get(name, [])
                counts.append(f"{name} {len(keys)}->{len(kept)}")
                if not set(kept) <= set(keys):
                    problems.append(f"{name}: a kept key that is not an input key")
                if name == "constant":
                    if kept != keys[:1]:
                        problems.append(f"constant: {len(kept)} keys, expected the first alone")
                elif not kept or kept[0] != keys[0] or kept[-1] != keys[-1]:
                    problems.append(f"{name}: the first and last keys not kept")
                for a, b in zip(kept, kept[1:]):
                    if method != "step" and angle_deg(a[1], b[1]) > 180 - 1e-9:
                        problems.append(f"{name}: kept keys {a[0]} and {b[0]} half a turn apart")
                if method == "squad":
                    continue  # (scipy has no squad: compare checks it below)
                worst = worst_t = 0.0
                for t, q, move in keys:
                    p, m = replay(kept, t, method)
                    worst = max(worst, angle_deg(p, q))
                    if move is not None:
                        worst_t = max(worst_t, float(np.linalg.norm(np.array(m) - np.array(move))))
                # 1e-9 deg: scipy's slerp and keyrot's round differently.
                if worst > tol + 1e-9 or worst_t > tol_t + 1e-12:
                    problems.append(f"{name}: replayed {worst:.3g} deg, {worst_t:.3g} away (scipy)")
                # The largest errors reported are the replay's.
                said = reported[name]
                if abs(said["largest_error"] - worst) > 1e-9 or abs(said["largest_translation_error"] - worst_t) > 1e-12:
                    problems.append(f"{name}: reported {said['largest_error']:.12g} deg, "
                                    f"{said['largest_translation_error']:.3g} away; replayed {worst:.12g}, {worst_t:.3g}")
            # The same guarantee through keyrot itself: the kept keys resampled at the keys' rate
            # (but the constant track's one key, which resample gives one frame).
            moving = {name: track for name, track in data.items() if name != "constant"}
            write_csv(os.path.join(work, "moving.csv"), moving)
            status, again, err = run(["resample", out, "--fps", "120", "--method", method])
            again = "\n".join(line for line in again.split("\n") if not line.startswith("constant,"))
            status, summary, err = run(["compare", os.path.join(work, "moving.csv"), "-", "--tol", str(max(tol, 1e-9)),
                                        "--tol-translation", str(max(tol_t, 1e-12))], again.encode())
            if status != 0:
                problems.append(f"compare: {summary.strip()} {err.strip()}")
            if tol == 0 and method in ("slerp", "nlerp") and len(reduced["runs"]) > 3 * len(source["runs"]) // 20:
                problems.append(f"runs: {len(reduced['runs'])} keys kept at tolerance 0, expected the ends of "
                                f"each run of equal keys")
            if problems:
                fail(f"{label}: " + "; ".join(problems[:4]))
            else:
                ok(f"{label}: {', '.join(counts)}; within tolerance (scipy and compare)")


def check_report(work, data):
    path = os.path.join(work, "dense.csv")
    out = os.path.join(work, "reported.csv")
    status, text, err = run(["reduce", path, "--tol", "0.05", "-o", out, "--report", "json"])
    try:
        report = json.loads(text)
    except ValueError:
        return fail(f"--report json: not JSON: {text[:80]!r} ({err.strip()})")
    reduced = read_csv(open(out).read())
    kept = {t["track"]: t["kept"] for t in report["tracks"]}
    if status != 0 or kept != {name: len(keys) for name, keys in reduced.items()} or report["tol"] != 0.05 or \
            report["keys"] != sum(len(v[0]) for v in data.values()):
        fail(f"--report json: {text[:200]}")
    else:
        ok(f"--report json: {report['keys']} keys -> {report['kept']}, per track as written")
    status, _, err = run(["reduce", path, "--tol", "0.05"])
    lines = err.strip().split("\n")
    if len(lines) != len(data) or not all("keys ->" in line and "largest error" in line for line in lines):
        fail(f"summary lines: {err.strip()}")
    else:
        ok(f"a summary line per track on standard error: {lines[0]}")


def check_bad(work):
    path = os.path.join(work, "dense.csv")
    cases = [(["--tol", "-1"], "--tol: expected a tolerance of 0 or more"),
             (["--tol", "nan"], "--tol: expected"),
             (["--tol-translation", "inf"], "--tol-translation: expected a tolerance of 0 or more"),
             (["--report", "json"], "--report json: the report takes standard output"),
             (["--to", "bvh"], "BVH has a line for every frame")]
    bad = [f"{' '.join(args)}: {status} {err.strip()!r}" for args, want in cases
           for status, text, err in [run(["reduce", path] + args)]
           if status != 2 or text or len(err.strip().split("\n")) != 1 or want not in err]
    with open(os.path.join(work, "late.csv"), "w") as f:
        f.write("time,qw,qx,qy,qz\n0,1,0,0,0\n1,1,0,0,0\n2,1,0,0\n")
    status, text, err = run(["reduce", os.path.join(work, "late.csv")])
    if status != 2 or text or "late.csv:4" not in err:
        bad.append(f"a bad line: {status} {text!r} {err.strip()!r}")
    if bad:
        fail("bad input: " + "; ".join(bad))
    else:
        ok(f"{len(cases) + 1} bad inputs: one line, exit 2, nothing written")


def glb_accessors(path):
    """Every accessor of a .glb file (FLOAT only), as float32 arrays."""
    data = open(path, "rb").read()
    json_length = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + json_length])
    binary = data[20 + json_length + 8:]
    out = []
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}
    for a in doc["accessors"]:
        view = doc["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        n = a["count"] * width.get(a["type"], 16)
        out.append(np.frombuffer(binary, "<f4", n, start).reshape(a["count"], -1) if a["componentType"] == 5126
                   else None)
    return doc, out


def check_gltf(work, rng):
    n = 480
    times = np.arange(n) / 120.0
    b = gltf_files.Builder()
    b.skeleton(3)
    channels = []
    for node in range(3):
        q = Rotation.from_rotvec(np.radians(smooth(rng, n, 50))).as_quat()
        channels.append({"node": node, "path": "rotation", "times": times, "values": q})
    channels.append({"node": 0, "path": "translation", "times": times, "values": smooth(rng, n, 0.2)})
    b.animation(channels)
    dense = os.path.join(work, "dense.glb")
    b.write(dense, "glb")
    out = os.path.join(work, "reduced.glb")
    status, _, err = run(["reduce", dense, "--tol", "0.05", "--tol-translation", "0.001", "-o", out])
    if status != 0:
        return fail(f"glTF: status {status}, {err.strip()}")
    doc_in, acc_in = glb_accessors(dense)
    doc_out, acc_out = glb_accessors(out)
    problems, counts = [], []
    for s_in, s_out in zip(doc_in["animations"][0]["samplers"], doc_out["animations"][0]["samplers"]):
        t_in, v_in = acc_in[s_in["input"]][:, 0], acc_in[s_in["output"]]
        t_out, v_out = acc_out[s_out["input"]][:, 0], acc_out[s_out["output"]]
        counts.append(f"{len(t_in)}->{len(t_out)}")
        where = {t.tobytes(): i for i, t in enumerate(t_in)}
        for t, v in zip(t_out, v_out):
            i = where.get(t.tobytes())
            if i is None or v_in[i].tobytes() != v.tobytes():
                problems.append(f"a kept key at {t} is not the input's, to the bit")
                break
    if len(doc_out["animations"]) != 1 or len(doc_out["nodes"]) != len(doc_in["nodes"]):
        problems.append("the rest of the file changed")
    if problems:
        return fail("glTF in place: " + "; ".join(problems))
    ok(f"glTF reduced in place: samplers {', '.join(counts)} keys, the kept ones the input's 32-bit floats")
    if not VALIDATOR:
        print("reduce_test: the glTF Validator is not installed (.ci/deps test): not validated")
        return
    bad = gltf_files.validator_problems(VALIDATOR, [out])
    if bad:
        fail(f"glTF validator: {'; '.join(bad)}")
    else:
        ok("the reduced glTF file passes the Khronos validator")


def check_found_again(work, rng):
    """Random keys 5 frames apart, resampled at 24 fps: reduce finds the keys again, to the frame."""
    keys = 2000
    q = rng.normal(size=(keys, 4))
    q /= np.linalg.norm(q, axis=1)[:, None]
    path = os.path.join(work, "keys.csv")
    with open(path, "w") as f:
        f.write("time,qw,qx,qy,qz\n")
        for i in range(keys):
            f.write(",".join(repr(float(v)) for v in [i * 5 / 24, *q[i]]) + "\n")
    rows, out = os.path.join(work, "rows.csv"), os.path.join(work, "found.csv")
    status, _, err = run(["resample", path, "-o", rows])
    if status != 0:
        return fail(f"resample of random keys: status {status}, {err.strip()}")
    status, text, err = run(["reduce", rows, "--tol", "0.01", "-o", out, "--report", "json"])
    if status != 0:
        return fail(f"reduce of resampled keys: status {status}, {err.strip()}")
    frames = [int(r["frame"]) for r in csv.DictReader(open(out))]
    largest = json.loads(text)["tracks"][0]["largest_error"]
    if frames != [5 * i for i in range(keys)] or not largest < 1e-9:
        fail(f"reduce of resampled keys: kept frames {frames[:6]}... ({len(frames)}), largest error {largest}")
    else:
        ok(f"reduce of {keys} random keys resampled at 24 fps finds them again ({5 * (keys - 1) + 1} rows -> "
           f"{len(frames)}, largest error {largest:.3g} deg)")


def main():
    rng = np.random.default_rng(34)
    with tempfile.TemporaryDirectory() as work:
        data = tracks(rng)
        check_csv(work, data)
        check_report(work, data)
        check_found_again(work, rng)
        check_bad(work)
        check_gltf(work, rng)
    return summary("reduce_test")


if __name__ == "__main__":
    sys.exit(main())
