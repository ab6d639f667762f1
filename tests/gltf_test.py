#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""glTF input against an independent reading of the glTF 2.0 specification.

Generated files (skinned skeletons of 20 to 60 joints; LINEAR, STEP and
CUBICSPLINE samplers; float and normalised-integer rotations; interleaved
bufferViews; sparse accessors; a first key after 0 s; keys 180 degrees
apart; w < 0; rotation, translation and scale keyed at different times; several
animations) as .glb, .gltf with a .bin, .gltf with a data: URI, and .glb on
standard input. keyrot's resampled frames are compared with the sampler
semantics written out here: scipy's Slerp for LINEAR rotations, the Hermite
formula in numpy for CUBICSPLINE, the held value for STEP. Then glTF output:
each file resampled into .glb and .gltf (and keyrot's other inputs into new
files) passes the Khronos glTF Validator, reads back as the frames keyrot
writes in CSV (to float32 accuracy), keeps everything else of the input
(nodes, meshes, skins, their bytes), holds no
bytes of the old animation, and resampled again at its own rate gives the
same frames. Then the bad files: each one line naming the file and
the JSON path, exit 2, no output.

Usage: gltf_test.py KEYROT [VALIDATOR_JS]
VALIDATOR_JS: tests/gltf_validate.js, where the validator is installed
(.ci/deps test installs it; without it outputs are not validated, and the
test says so). Exit 0 when all pass, 1 otherwise; 77 (skip) without scipy.
"""
import bisect
import copy
import csv
import io
import json
import math
import os
import resource
import struct
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from scipy.spatial.transform import Rotation, Slerp
except ImportError:  # pragma: no cover
    print("gltf_test: numpy/scipy not installed (apt-get install python3-scipy); skipped")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_files as G  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import fail, passed, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])
VALIDATOR = sys.argv[2] if len(sys.argv) > 2 else None
FLOAT32_DEG = 2e-5  # a quaternion's components rounded to 32-bit floats
ROT_TOL_DEG = 1e-9
POS_TOL = 1e-9


def run(args, stdin=None, memory=None):
    """keyrot's status, output and errors; `memory` caps its address space in bytes."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    p = subprocess.run([KEYROT] + args, input=stdin, capture_output=True, preexec_fn=limit if memory else None)
    return p.returncode, p.stdout.decode(), p.stderr.decode()


# ---------------------------------------------------------------- reference
def near_key(time, fps):
    """How near, in frames, a frame counts as at a key at `time`: 1e-9 frame, or the key's
    32-bit rounding (2^-24 of it), as the README says."""
    return max(1e-9, abs(time) * fps * 2.0**-24)


def curve_value(times, values, interp, t, rotation):
    """A sampler's value at t as the glTF 2.0 specification defines it.
    values: keys x width, or keys x 3 x width (in, value, out) for CUBICSPLINE;
    rotations in x, y, z, w."""
    cubic = interp == "CUBICSPLINE"
    v = (lambda i: values[i][1]) if cubic else (lambda i: values[i])
    if t <= times[0]:
        out = v(0)
    elif t >= times[-1]:
        out = v(len(times) - 1)
    else:
        i = bisect.bisect_right(times, t) - 1
        td = times[i + 1] - times[i]
        h = (t - times[i]) / td
        if times[i] == t or interp == "STEP":
            out = v(i)
        elif cubic:
            out = ((2 * h**3 - 3 * h**2 + 1) * values[i][1] + td * (h**3 - 2 * h**2 + h) * values[i][2]
                   + (-2 * h**3 + 3 * h**2) * values[i + 1][1] + td * (h**3 - h**2) * values[i + 1][0])
        elif rotation and np.dot(v(i), v(i + 1)) == 0:
            # Exactly half a turn apart, the specification's slerp divides 0 by 0; keyrot turns
            # towards the second key as stored (sin(a(1 - h)) v0 + sin(a h) v1 with a = 90 degrees).
            out = math.cos(h * math.pi / 2) * v(i) + math.sin(h * math.pi / 2) * v(i + 1)
        elif rotation:
            out = Slerp([0, 1], Rotation.from_quat([v(i), v(i + 1)]))([h]).as_quat()[0]
        else:
            out = (1 - h) * v(i) + h * v(i + 1)
    out = np.asarray(out, dtype=float)
    return out / np.linalg.norm(out) if rotation else out


def angle_deg(q_xyzw, ref_xyzw):
    a = np.asarray(q_xyzw) / np.linalg.norm(q_xyzw)
    b = np.asarray(ref_xyzw) / np.linalg.norm(ref_xyzw)
    if np.dot(a, b) < 0:
        b = -b
    return math.degrees(4 * math.asin(min(1.0, np.linalg.norm(a - b) / 2)))


def read_csv(text):
    return list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))


class Case:
    """A generated file and what the reference says its tracks are."""

    def __init__(self, name):
        self.name = name
        self.b = G.Builder()
        self.tracks = {}  # track name -> {"rotation": (times, values, interp), "translation", "scale", "weights": ..., "rest": xyzw}

    def channel(self, track, node, path, times, values, interp="LINEAR", component=G.FLOAT, stride=None,
                sparse_every=None):
        """Adds a channel; the reference keeps the values as a reader decodes them."""
        self.pending.append({"node": node, "path": path, "times": times, "values": values,
                             "interpolation": interp, "component": component, "stride": stride,
                             "sparse_every": sparse_every})
        decoded_times = self.b.decoded_times(times)
        decoded = self.b.decoded(np.asarray(values, dtype=float), component)
        self.tracks.setdefault(track, {})[path] = (list(decoded_times), decoded, interp)

    def begin(self):
        self.pending = []

    def end(self, name=None):
        self.b.animation(self.pending, name)


def random_quats(rng, n, spread=1.0):
    """A random walk of unit quaternions (x, y, z, w), signs as they fall (w < 0 included)."""
    r = Rotation.random(random_state=rng)
    out = []
    for _ in range(n):
        r = Rotation.from_rotvec(rng.normal(size=3) * spread) * r
        q = r.as_quat()
        out.append(q if rng.random() < 0.7 else -q)
    return np.array(out)


def key_times(rng, n, start=0.0):
    return np.cumsum(np.concatenate([[start], rng.uniform(0.02, 0.3, n - 1)]))


def cubic_values(rng, quats):
    """keys x 3 x width: in-tangent, value, out-tangent."""
    n, w = quats.shape
    return np.stack([rng.normal(size=(n, w)) * 0.5, quats, rng.normal(size=(n, w)) * 0.5], axis=1)


# ---------------------------------------------------------------- cases
def make_cases(work):
    rng = np.random.default_rng(20261202)
    cases = []

    # A skinned character: LINEAR rotations on 30 joints, root translation on the same times.
    c = Case("walk.glb")
    c.b.skeleton(30)
    c.begin()
    t = key_times(rng, 40, 0.0)
    for j in range(30):
        c.channel(f"joint{j}", j, "rotation", t, random_quats(rng, 40, 0.3))
    c.channel("joint0", 0, "translation", t, rng.normal(size=(40, 3)))
    c.channel("joint1", 1, "scale", t, 1 + 0.2 * rng.normal(size=(40, 3)))
    c.end()
    # A morph target's weights (morph_test.py checks their values).
    body = c.b.json["nodes"][-1]
    c.b.json["meshes"][0]["weights"] = [0.0]
    c.b.json["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": c.b.accessor(np.zeros((3, 3)), minmax=True)}]
    anim = c.b.json["animations"][0]
    anim["samplers"].append({"input": c.b.accessor(t[:5]), "output": c.b.accessor(np.linspace(0, 1, 5))})
    anim["channels"].insert(3, {"sampler": len(anim["samplers"]) - 1,
                                "target": {"node": c.b.json["nodes"].index(body), "path": "weights"}})
    body_track = {"weights": (list(c.b.decoded_times(t[:5])), c.b.decoded(np.linspace(0, 1, 5)).reshape(5, 1), "LINEAR"),
                  "rest": [0.0, 0.0, 0.0, 1.0]}
    c.tracks = dict(list(c.tracks.items())[:3] + [("body", body_track)] + list(c.tracks.items())[3:])
    cases.append((c, "glb"))

    # STEP rotations, a first key after 0 s, in a .gltf with its .bin.
    c = Case("step.gltf")
    c.b.skeleton(20)
    c.begin()
    for j in range(20):
        c.channel(f"joint{j}", j, "rotation", key_times(rng, 12, 0.37), random_quats(rng, 12, 1.0), "STEP")
    c.end()
    cases.append((c, "bin"))

    # CUBICSPLINE rotations and translations, embedded as a data: URI.
    c = Case("cubic.gltf")
    c.b.skeleton(24)
    c.begin()
    for j in range(24):
        t = key_times(rng, 10, 0.1 * (j % 3))
        c.channel(f"joint{j}", j, "rotation", t, cubic_values(rng, random_quats(rng, 10, 0.6)), "CUBICSPLINE")
        if j % 4 == 0:
            c.channel(f"joint{j}", j, "translation", t, cubic_values(rng, rng.normal(size=(10, 3))), "CUBICSPLINE")
        if j % 4 == 1:
            c.channel(f"joint{j}", j, "scale", t, cubic_values(rng, 1 + 0.2 * rng.normal(size=(10, 3))), "CUBICSPLINE")
    c.end()
    cases.append((c, "datauri"))

    # Normalised SHORT and BYTE rotations, interleaved (byteStride) outputs (which the specification does not
    # allow for animation samplers, and keyrot reads all the same), sparse substitutes, keys 180 degrees apart.
    c = Case("quantised.glb")
    c.b.skeleton(20)
    c.begin()
    for j in range(20):
        q = random_quats(rng, 16, 0.8)
        if j < 2:  # each key half a turn (j = 0), or 179.5 degrees, from the one before, about z
            half = math.radians(90 if j == 0 else 89.75)
            q = np.array([[0, 0, math.sin(k * half), math.cos(k * half)] for k in range(16)])
        component = [G.SHORT, G.BYTE, G.FLOAT][j % 3]
        c.channel(f"joint{j}", j, "rotation", key_times(rng, 16), q, component=component, stride=[None, 12, 20][j % 3],
                  sparse_every=3 if j % 4 == 1 else None)  # sparse substitutes, interleaved or not
    c.end()
    cases.append((c, "glb"))

    # Rotation, translation and scale keyed at different times (LINEAR, STEP and CUBICSPLINE),
    # translation-only and scale-only nodes with a rest rotation, unnamed nodes.
    c = Case("offset.glb")
    c.b.skeleton(20, names=False)
    c.b.json["nodes"][5]["rotation"] = [0.0, 0.6, 0.0, 0.8]
    c.begin()
    c.channel("node0", 0, "rotation", key_times(rng, 8, 0.2), random_quats(rng, 8, 0.7))
    c.channel("node0", 0, "translation", key_times(rng, 11, 0.0), rng.normal(size=(11, 3)))
    t1, t2 = key_times(rng, 9, 0.0), key_times(rng, 7, 0.3)
    c.channel("node1", 1, "rotation", t1, cubic_values(rng, random_quats(rng, 9, 0.7)), "CUBICSPLINE")
    c.channel("node1", 1, "translation", t2, cubic_values(rng, rng.normal(size=(7, 3))), "CUBICSPLINE")
    c.channel("node1", 1, "scale", key_times(rng, 5, 0.1), 1 + 0.2 * rng.normal(size=(5, 3)))
    c.channel("node2", 2, "rotation", key_times(rng, 9, 0.5), random_quats(rng, 9, 0.7), "STEP")
    c.channel("node2", 2, "translation", key_times(rng, 6, 0.0), rng.normal(size=(6, 3)))
    c.channel("node5", 5, "translation", key_times(rng, 6, 0.0), rng.normal(size=(6, 3)))
    c.tracks["node5"]["rest"] = [0.0, 0.6, 0.0, 0.8]
    c.channel("node3", 3, "rotation", key_times(rng, 7, 0.0), random_quats(rng, 7, 0.7))
    c.channel("node3", 3, "scale", key_times(rng, 9, 0.25), 1 + 0.2 * rng.normal(size=(9, 3)), "STEP")
    c.channel("node6", 6, "scale", key_times(rng, 6, 0.0), 1 + 0.2 * rng.normal(size=(6, 3)))
    c.tracks["node6"]["rest"] = [0.0, 0.0, 0.0, 1.0]
    c.end()
    cases.append((c, "glb"))

    # A long take: times past 16 s, where a 32-bit float's rounding is more than compare's 1e-6 s.
    c = Case("long.glb")
    c.b.skeleton(20)
    c.begin()
    c.channel("joint3", 3, "rotation", np.arange(500) * 0.1, random_quats(rng, 500, 0.3))
    c.end()
    cases.append((c, "glb"))

    # Two nodes of one name: the second's track is "joint3.2" (no '#' or ',', which CSV readers treat apart).
    c = Case("twins.glb")
    c.b.skeleton(20)
    c.b.json["nodes"][4]["name"] = "joint3"
    c.begin()
    c.channel("joint3", 3, "rotation", key_times(rng, 6), random_quats(rng, 6, 0.5))
    c.channel("joint3.2", 4, "rotation", key_times(rng, 6), random_quats(rng, 6, 0.5))
    c.end()
    cases.append((c, "glb"))

    # A rig as a capture gives it: every joint's rotation and translation on one set of times, the
    # translations still but the root's; and a scale written as a single key (a value for the whole
    # animation, held before and after it as glTF holds a sampler).
    c = Case("rig.glb")
    c.b.skeleton(12)
    c.begin()
    t = np.arange(90) / 60
    for j in range(12):
        c.channel(f"joint{j}", j, "rotation", t, random_quats(rng, 90, 0.1))
        still = np.tile([0.0, 0.1 * (j % 5), 0.0], (90, 1))
        c.channel(f"joint{j}", j, "translation", t, still + (rng.normal(size=(90, 3)) if j == 0 else 0))
    c.channel("joint4", 4, "scale", t[30:31], [[1.0, 2.0, 3.0]])
    c.end()
    cases.append((c, "glb"))

    # Two animations on a 60-joint skeleton: tracks "Walk/joint3", "Run/joint3".
    c = Case("two.glb")
    c.b.skeleton(60)
    for anim in ["Walk", "Run"]:
        c.begin()
        for j in range(0, 60, 3):
            c.channel(f"{anim}/joint{j}", j, "rotation", key_times(rng, 20), random_quats(rng, 20, 0.4))
        c.end(anim)
    cases.append((c, "glb"))

    heavy = []
    for case, how in cases:
        case.path = os.path.join(work, case.name)
        case.b.write(case.path, how)
        # The same animation in a file that a model makes large: resampled into glTF, its tracks are
        # made apart from each other, on threads of their own.
        h = copy.copy(case)
        h.name = "heavy_" + case.name
        h.path = os.path.join(work, h.name)
        h.b = copy.deepcopy(case.b)
        # The rig in a file of 18 MB, which is read in two halves at once.
        h.b.detailed_mesh(HUGE_VERTICES if case.name == "rig.glb" else HEAVY_VERTICES)
        h.b.write(h.path, how)
        heavy.append(h)
    return [case for case, _ in cases], heavy


HEAVY_VERTICES = 30000  # 360 kB of buffer: more than the quarter megabyte from which tracks are made apart
HUGE_VERTICES = 1_500_000  # 18 MB: more than the 16 MiB from which a file is read in two halves at once


VECTORS = {"translation": ("tx", "ty", "tz"), "scale": ("sx", "sy", "sz"), "weights": ("w0",)}


def expected_frames(track, fps):
    """(frame, rotation xyzw, {translation/scale: value}) on keyrot's grid for the track's key range."""
    times = [x for ch in ("rotation", "translation", "scale", "weights") if ch in track for x in track[ch][0]]
    first, last = min(times), max(times)
    frames = []
    keys = sorted(set(times))
    for k in range(math.ceil(first * fps - near_key(first, fps)), math.floor(last * fps + near_key(last, fps)) + 1):
        t = k / fps
        # A frame that near a key of the track (of either channel) is at it.
        t = next((key for key in keys if abs(t - key) * fps <= near_key(key, fps)), t)
        if "rotation" in track:
            ts, vs, interp = track["rotation"]
            q = curve_value(ts, vs, interp, t, True)
        else:
            q = np.array(track["rest"]) / np.linalg.norm(track["rest"])
        vectors = {ch: curve_value(*track[ch], t, False) for ch in VECTORS if ch in track}
        frames.append((k, q, vectors))
    return frames


def check_resample(case, fps, extra=(), stdin=None, animation=None):
    """`animation`: the name of the one animation `extra` picks."""
    args = ["resample", "-" if stdin else case.path, "--to", "csv", "--rep", "quat", "--fps", str(fps)] + list(extra)
    status, out, err = run(args, stdin)
    label = f"{case.name} at {fps} fps {' '.join(extra)}{' (stdin)' if stdin else ''}"
    if status != 0:
        fail(f"{label}: status {status}: {err.strip()}")
        return
    rows = read_csv(out)
    by_track = {}
    for r in rows:
        by_track.setdefault(r["track"], []).append(r)
    wanted = case.tracks if animation is None else {
        name.split("/", 1)[1]: t for name, t in case.tracks.items() if name.startswith(animation + "/")}
    if list(by_track) != list(wanted):
        fail(f"{label}: tracks {list(by_track)[:5]}..., expected {list(wanted)[:5]}...")
        return
    worst_rot, worst_pos = 0.0, 0.0
    for name, track in wanted.items():
        expected = expected_frames(track, fps)
        got = by_track[name]
        if [int(r["frame"]) for r in got] != [k for k, _, _ in expected]:
            fail(f"{label}: track {name}: frames {got[0]['frame']}..{got[-1]['frame']}, expected "
                 f"{expected[0][0]}..{expected[-1][0]}")
            continue
        for r, (k, q, vectors) in zip(got, expected):
            mine = [float(r["qx"]), float(r["qy"]), float(r["qz"]), float(r["qw"])]
            worst_rot = max(worst_rot, angle_deg(mine, q))
            for ch, p in vectors.items():
                columns = VECTORS[ch]
                if r[columns[0]] == "":
                    fail(f"{label}: track {name} frame {k}: no {ch}")
                    break
                worst_pos = max(worst_pos, float(np.max(np.abs(np.array([float(r[c]) for c in columns]) - p))))
    passed()
    if worst_rot > ROT_TOL_DEG or worst_pos > POS_TOL:
        fail(f"{label}: largest difference {worst_rot:.3g} deg, {worst_pos:.3g} in translation or scale")
    else:
        print(f"ok: {label}: {len(rows)} frames, within {worst_rot:.2g} deg and {worst_pos:.2g}")


def check_convert(case):
    """convert writes each channel's keys as stored (normalised rotations)."""
    status, out, err = run(["convert", case.path, "--to", "csv", "--rep", "quat"])
    if status != 0:
        fail(f"convert {case.name}: status {status}: {err.strip()}")
        return
    rows = read_csv(out)
    for name, track in case.tracks.items():
        if "rotation" not in track:
            continue
        ts, vs, interp = track["rotation"]
        mine = [r for r in rows if r["track"] == name]
        for t, v in zip(ts, vs):
            v = v[1] if interp == "CUBICSPLINE" else v
            row = next((r for r in mine if float(r["time"]) == t), None)
            if row is None:
                fail(f"convert {case.name}: track {name}: no key at {t}")
                return
            q = np.array([float(row["qx"]), float(row["qy"]), float(row["qz"]), float(row["qw"])])
            if np.max(np.abs(q - v / np.linalg.norm(v))) > 1e-15:
                fail(f"convert {case.name}: track {name} at {t}: {q}, expected {v / np.linalg.norm(v)}")
                return
    passed()
    print(f"ok: convert {case.name}: keys as stored")


# ---------------------------------------------------------------- glTF output
def accessor_content(doc, binary, i):
    """An accessor as what it holds: its fields but where it is, and its elements' bytes."""
    a = dict(doc["accessors"][i])
    view = doc["bufferViews"][a.pop("bufferView")]
    offset = view.get("byteOffset", 0) + a.pop("byteOffset", 0)
    size = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}[a["componentType"]]
    width = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}[a["type"]]
    stride = view.get("byteStride", size * width)
    elements = b"".join(binary[offset + k * stride: offset + k * stride + size * width] for k in range(a["count"]))
    return json.dumps(a, sort_keys=True), elements


def meshes_by_content(doc, binary):
    """The meshes and skins with each accessor index replaced by what the accessor holds."""
    def resolve(x, key=None):
        if isinstance(x, dict):
            return {k: resolve(v, k) for k, v in x.items()}
        if isinstance(x, list):
            return [resolve(v, key) for v in x]
        if isinstance(x, int) and key in ("POSITION", "JOINTS_0", "WEIGHTS_0", "indices", "inverseBindMatrices"):
            return accessor_content(doc, binary, x)
        return x
    return resolve(doc.get("meshes")), resolve(doc.get("skins"))


def frames_by_key(text):
    """Rows by track and time in 1/1200 s (a multiple of every rate used here): a glTF file
    stores times as 32-bit floats."""
    return {(r["track"], round(float(r["time"]) * 1200)): r for r in read_csv(text)}


def compare_frames(label, expected_text, actual_text, tol_deg):
    """Every frame of the first CSV in the second, within tol_deg and float32 translation accuracy."""
    expected, actual = frames_by_key(expected_text), frames_by_key(actual_text)
    if set(expected) != set(actual):
        fail(f"{label}: frames {len(actual)}, expected {len(expected)} ({sorted(set(expected) ^ set(actual))[:3]})")
        return False
    worst = 0.0
    for k, e in expected.items():
        a = actual[k]
        q = lambda r: [float(r["qx"]), float(r["qy"]), float(r["qz"]), float(r["qw"])]
        worst = max(worst, angle_deg(q(a), q(e)))
        for c in VECTORS["translation"] + VECTORS["scale"] + VECTORS["weights"]:
            if e.get(c) and abs(float(a[c]) - float(e[c])) > 1e-6 * max(1.0, abs(float(e[c]))):
                fail(f"{label}: {k}: {c} {a[c]}, expected {e[c]}")
                return False
    if worst > tol_deg:
        fail(f"{label}: largest difference {worst:.3g} deg")
        return False
    return True


def check_gltf_output(case, fps, how, written):
    """resample into .glb or .gltf: reads back as the CSV frames; the rest of the file kept; no dead bytes."""
    stem = os.path.splitext(case.path)[0]
    out = f"{stem}_{fps}.{how}"
    status, _, err = run(["resample", case.path, "--fps", str(fps), "-o", out])
    if status != 0:
        fail(f"{out}: status {status}: {err.strip()}")
        return
    written.append(out)
    _, direct, _ = run(["resample", case.path, "--fps", str(fps), "--to", "csv", "--rep", "quat"])
    status, back, err = run(["convert", out, "--to", "csv", "--rep", "quat"])
    if status != 0 or not compare_frames(f"{out} read back", direct, back, FLOAT32_DEG):
        if status:
            fail(f"{out}: read back: {err.strip()}")
        return
    # compare matches the frames keyrot writes in CSV with the glTF file's, at any length of take.
    direct_file = out + ".csv"
    with open(direct_file, "w") as f:
        f.write(direct)
    status, _, err = run(["compare", direct_file, out, "--tol", "1e-4"])
    if status != 0:
        fail(f"compare {direct_file} {out}: status {status}: {err.strip()[:300]}")
        return
    din, bin_in = G.parts(case.path)
    dout, bin_out = G.parts(out)
    for key in ("asset", "scene", "scenes", "nodes"):
        if din.get(key) != dout.get(key):
            fail(f"{out}: '{key}' not kept")
            return
    if meshes_by_content(din, bin_in) != meshes_by_content(dout, bin_out):
        fail(f"{out}: meshes or skins (or their accessors' bytes) not kept")
        return
    times_min = [dout["accessors"][s["input"]]["min"][0] for a in dout["animations"] for s in a["samplers"]]
    if any(m == 0 and math.copysign(1, m) < 0 for m in times_min):
        fail(f"{out}: a time of -0")
        return
    used = sum(v["byteLength"] + 3 for v in dout["bufferViews"])
    if len(bin_out) > used:
        fail(f"{out}: {len(bin_out)} bytes of buffer, {used} in its bufferViews: old animation data left behind")
        return
    for anim_in, anim_out in zip(din["animations"], dout["animations"]):
        if len(anim_out["samplers"]) > len(anim_out["channels"]):
            fail(f"{out}: {len(anim_out['samplers'])} samplers for {len(anim_out['channels'])} channels")
            return
        for c_in, c_out in zip(anim_in["channels"], anim_out["channels"]):
            if c_in["target"] != c_out["target"]:
                fail(f"{out}: channel order not kept")
                return
    # Resampled again at its own rate: the same frames (its keys, as 32-bit floats again).
    again = f"{stem}_{fps}_again.{how}"
    run(["resample", out, "--fps", str(fps), "-o", again])
    _, again_csv, _ = run(["convert", again, "--to", "csv", "--rep", "quat"])
    if not compare_frames(f"{again} (from {out} at its own rate)", back, again_csv, FLOAT32_DEG):
        return
    written.append(again)
    passed()
    print(f"ok: {out}: reads back as the frames, the rest of the file kept, {len(bin_out)} bytes of buffer")


def keys_per_channel(doc, node_key):
    """The keys of each channel of the first animation, by (node_key(node), path)."""
    anim = doc["animations"][0]
    return {(node_key(c["target"]["node"]), c["target"]["path"]):
            doc["accessors"][anim["samplers"][c["sampler"]]["output"]]["count"] for c in anim["channels"]}


def check_rig_layout(case, written):
    """resample of a rig into .glb: one time accessor for all channels on one set of times, a
    channel that never changes written as one key; and convert reads such a key on every row."""
    out = f"{os.path.splitext(case.path)[0]}_30.glb"  # (check_gltf_output wrote it)
    if out not in written:
        return
    doc, _ = G.parts(out)
    anim = doc["animations"][0]
    inputs = {anim["samplers"][c["sampler"]]["input"] for c in anim["channels"]}
    counts = keys_per_channel(doc, lambda node: node)
    grid = max(counts.values())
    want = {(j, "translation"): 1 for j in range(1, 12)}
    want.update({(j, "rotation"): grid for j in range(12)})
    want.update({(0, "translation"): grid, (4, "scale"): 1})
    if len(inputs) != 2 or counts != want:
        fail(f"{out}: {len(inputs)} time accessors (expected 2: the frames' and a single key's), "
             f"keys per channel {counts}")
        return
    for read in (case.path, out):
        status, text, err = run(["convert", read, "--to", "csv", "--rep", "quat"])
        rows = read_csv(text)
        if status != 0 or any(r["tx"] == "" for r in rows) or any(
                (r["sx"], r["sy"], r["sz"]) != ("1", "2", "3") for r in rows if r["track"] == "joint4"):
            fail(f"convert {read}: a translation or scale missing from a row, or not the one key's: {err.strip()}")
            return
    passed()
    print(f"ok: {out}: one time accessor for the frames, still channels as one key, read on every row")


def check_new_file_still_channels(work, written):
    """A new file of CSV tracks: a translation or scale that never changes is one key, read back on
    every row; tracks on the same times share their time accessor."""
    source, out = os.path.join(work, "still.csv"), os.path.join(work, "still.glb")
    with open(source, "w") as f:
        f.write("track,time,qw,qx,qy,qz,tx,ty,tz,sx,sy,sz\n")
        for i in range(20):
            a = 0.05 * i
            f.write(f"arm,{i / 24},{math.cos(a)},0,0,{math.sin(a)},0.5,1,2,1,1,1\n")
            f.write(f"leg,{i / 24},{math.cos(a)},{math.sin(a)},0,0,{a},1,2,1,{1 + a},1\n")
    status, _, err = run(["resample", source, "-o", out])
    if status != 0:
        fail(f"{out}: {err.strip()}")
        return
    written.append(out)
    doc, _ = G.parts(out)
    counts = keys_per_channel(doc, lambda node: doc["nodes"][node]["name"])
    want = {("arm", "rotation"): 20, ("arm", "translation"): 1, ("arm", "scale"): 1,
            ("leg", "rotation"): 20, ("leg", "translation"): 20, ("leg", "scale"): 20}
    # The two tracks' frames are one list of times: one accessor, and one for the single keys.
    inputs = {s["input"] for s in doc["animations"][0]["samplers"]}
    _, direct, _ = run(["resample", source, "--to", "csv", "--rep", "quat"])
    _, back, _ = run(["convert", out, "--to", "csv", "--rep", "quat"])
    if counts != want or len(inputs) != 2 or not compare_frames(f"{out} read back", direct, back, FLOAT32_DEG):
        fail(f"{out}: keys per channel {counts}, expected {want}; {len(inputs)} time accessors, expected 2")
        return
    passed()
    print(f"ok: {out}: still channels as one key, one time accessor, read back on every row")


def check_new_files(work, written):
    """Tracks from CSV and JSON into a new glTF file: a node per track, frames as in CSV."""
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
    for name in sorted(os.listdir(data)):
        if not name.endswith((".csv", ".json", ".bvh")):
            continue
        source = os.path.join(data, name)
        for how in ("glb", "gltf"):
            out = os.path.join(work, f"new_{name}.{how}")
            status, _, err = run(["resample", source, "--euler", "ZYX", "-o", out])
            if status != 0:
                fail(f"{out}: {err.strip()}")
                continue
            written.append(out)
            _, direct, _ = run(["resample", source, "--euler", "ZYX", "--to", "csv", "--rep", "quat"])
            _, back, _ = run(["convert", out, "--to", "csv", "--rep", "quat"])
            if "track," not in direct:  # a file without tracks: the one node is "track"
                direct = direct.replace("frame,", "track,frame,", 1)
                direct = "\n".join(line if line.startswith(("#", "track")) or not line else "track," + line
                                   for line in direct.split("\n"))
            if compare_frames(f"{out} read back", direct, back, FLOAT32_DEG):
                passed()
                print(f"ok: {out}: reads back as the frames")
    # On standard output: a .gltf with its buffer as a data: URI.
    out = os.path.join(work, "stdout.gltf")
    status, text, err = run(["resample", os.path.join(data, "walk.csv"), "--to", "gltf"])
    with open(out, "w") as f:
        f.write(text)
    if status != 0 or '"data:application/octet-stream;base64,' not in text:
        fail(f"--to gltf on standard output: status {status}, {err.strip()}")
    else:
        written.append(out)
        passed()


def check_cubic_kept(case, work, written):
    """convert from glTF to glTF keeps CUBICSPLINE samplers, values and tangents to the bit."""
    out = os.path.join(work, "cubic_converted.glb")
    status, _, err = run(["convert", case.path, "-o", out])
    if status != 0:
        fail(f"{out}: {err.strip()}")
        return
    written.append(out)
    din, bin_in = G.parts(case.path)
    dout, bin_out = G.parts(out)
    a_in, a_out = din["animations"][0], dout["animations"][0]
    for c_in, c_out in zip(a_in["channels"], a_out["channels"]):
        s_in, s_out = a_in["samplers"][c_in["sampler"]], a_out["samplers"][c_out["sampler"]]
        if s_out.get("interpolation") != "CUBICSPLINE" or any(
                accessor_content(din, bin_in, s_in[e])[1] != accessor_content(dout, bin_out, s_out[e])[1]
                for e in ("input", "output")):
            fail(f"{out}: channel {c_in['target']} not kept as CUBICSPLINE to the bit")
            return
    passed()
    print(f"ok: {out}: CUBICSPLINE samplers kept to the bit")


def check_step_output(case, work, written):
    out = os.path.join(work, "stepped.glb")
    status, _, err = run(["resample", case.path, "--method", "step", "-o", out])
    doc, _ = G.parts(out) if status == 0 else ({}, b"")
    if status != 0 or any(a["samplers"][c["sampler"]].get("interpolation") != "STEP" for a in doc["animations"]
                          for c in a["channels"] if c["target"]["path"] in ("rotation", "translation", "scale")):
        fail(f"{out}: --method step: expected STEP samplers ({err.strip()})")
        return
    written.append(out)
    passed()


COMPACT_DEG = 0.0035  # 2 asin(2 * 0.5 / 32767) in degrees, with room for the float times


def nearest_shorts(exact, shorts):
    """Per row, whether `shorts` (n x 4 integers) is the nearest in angle to the unit quaternion
    `exact` (n x 4) of the integer vectors next to exact * 32767 (each component rounded down or
    up) whose length is within 1 of 32767 (a tie within 1e-15 of cos^2 either way)."""
    s = exact * 32767
    down = np.clip(np.floor(s), -32767, 32766)
    ups = np.array([[(u >> i) & 1 for i in range(4)] for u in range(16)])
    cands = down[:, None, :] + ups[None, :, :]                      # n x 16 x 4
    dot = np.einsum("nck,nk->nc", cands, exact)
    length2 = (cands ** 2).sum(axis=2)
    ok = (dot > 0) & (length2 >= 32766.0 ** 2) & (length2 <= 32768.0 ** 2)
    cos2 = np.where(ok, dot ** 2 / length2, -1.0)
    got = shorts.astype(float)
    got_cos2 = (got * exact).sum(axis=1) ** 2 / (got ** 2).sum(axis=1)
    within = np.abs(np.sqrt((got ** 2).sum(axis=1)) - 32767) <= 1
    return within & (got_cos2 >= cos2.max(axis=1) - 1e-15) & (np.abs(got - s) < 1).all(axis=1)


def short_rotations(doc, binary):
    """Each LINEAR or STEP rotation channel's (node, key times, quaternions x y z w as stored
    integers); a rotation channel stored otherwise is reported as a failure."""
    out = []
    anim = doc["animations"][0]
    for c in anim["channels"]:
        sampler = anim["samplers"][c["sampler"]]
        if c["target"]["path"] != "rotation" or sampler.get("interpolation") == "CUBICSPLINE":
            continue
        a = doc["accessors"][sampler["output"]]
        if a["componentType"] != 5122 or a.get("normalized") is not True:
            fail(f"--compact: rotation accessor {sampler['output']}: {a}, expected normalised SHORT (5122)")
            continue
        _, elements = accessor_content(doc, binary, sampler["output"])
        _, times = accessor_content(doc, binary, sampler["input"])
        out.append((c["target"]["node"], struct.unpack(f"<{a['count']}f", times),
                    np.array(struct.unpack(f"<{4 * a['count']}h", elements)).reshape(-1, 4)))
    return out


def check_compact(cases, work, written):
    """--compact: LINEAR and STEP rotations as normalised SHORTs, the integers next to q * 32767
    nearest the exact quaternion in angle, kept by another convert --compact; translations, scales
    and CUBICSPLINE samplers as before; every row within COMPACT_DEG of exact, which compare
    checks; other outputs refuse the flag."""
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")
    rig = next(c for c in cases if c.name == "rig.glb")
    jobs = [(os.path.join(data, "walk.csv"), "walk_compact.glb", ["resample"]),
            (os.path.join(data, "walk.csv"), "walk_compact.gltf", ["resample"]),
            (rig.path, "rig_compact.glb", ["resample", "--fps", "60"]),
            (cases[2].path, "cubic_compact.glb", ["convert"])]
    for source, name, command in jobs:
        out = os.path.join(work, name)
        status, _, err = run(command + [source, "--compact", "-o", out])
        if status != 0:
            fail(f"{out}: {err.strip()}")
            continue
        written.append(out)
        doc, binary = G.parts(out)
        _, direct, _ = run(command + [source, "--to", "csv", "--rep", "quat"])
        if "track," not in direct:  # (walk.csv's one track, unnamed: its node is "track")
            direct = "\n".join(line if line.startswith(("#", "frame")) or not line else "track," + line
                               for line in direct.split("\n")).replace("frame,", "track,frame,", 1)
        rows = frames_by_key(direct)
        # The integers stored are those nearest the exact quaternion in angle.
        stored = short_rotations(doc, binary)
        for node, times, shorts in stored:
            track = doc["nodes"][node].get("name", "track")
            exact = np.array([[float(rows[(track, round(t * 1200))][k]) for k in ("qx", "qy", "qz", "qw")]
                              for t in times])
            bad = np.nonzero(~nearest_shorts(exact, shorts))[0]
            if len(bad):
                fail(f"{out}: {track} at {times[bad[0]]} s: stored {list(shorts[bad[0]])}, not the nearest in angle "
                     f"to {list(exact[bad[0]] * 32767)} of the integers next to it")
        # Converted again with --compact, the integers stay (a chain of conversions loses nothing more).
        again = os.path.join(work, "again_" + name)
        run(["convert", out, "--compact", "-o", again])
        if [s.tolist() for _, _, s in stored] != [s.tolist() for _, _, s in short_rotations(*G.parts(again))]:
            fail(f"{again}: convert --compact of {out} changed its rotations' integers")
        floats = [doc["accessors"][a["output"]]["componentType"] for a in doc["animations"][0]["samplers"]
                  if doc["accessors"][a["output"]]["componentType"] != 5122]
        cubic = [s for s in doc["animations"][0]["samplers"] if s.get("interpolation") == "CUBICSPLINE"]
        if any(t != 5126 for t in floats) or (name.startswith("cubic") and not cubic):
            fail(f"{out}: other samplers' outputs {set(floats)}, CUBICSPLINE ones {len(cubic)}: expected FLOAT")
        # Read back, each row within the bound, and some rows near it: the bound is what compare can check.
        _, back, _ = run(["convert", out, "--to", "csv", "--rep", "quat"])
        if not compare_frames(f"{out} read back", direct, back, COMPACT_DEG):
            continue
        reference = os.path.join(work, name + ".csv")
        with open(reference, "w") as f:
            f.write(direct)
        status, _, _ = run(["compare", reference, out, "--tol", str(COMPACT_DEG)])
        tight, _, _ = run(["compare", reference, out, "--tol", "0.0005"])
        if status != 0 or (stored and tight != 1):
            fail(f"{out}: compare --tol {COMPACT_DEG} exit {status} (expected 0), --tol 0.0005 exit {tight} "
                 f"(expected 1: the integers are coarser)")
            continue
        passed()
        print(f"ok: {out}: {len(stored)} rotation channels as normalised SHORTs, within {COMPACT_DEG} deg")
    for target in ("x.csv", "x.bvh"):
        out = os.path.join(work, target)
        status, text, err = run(["resample", os.path.join(data, "walk.csv"), "--compact", "-o", out])
        if status != 2 or text or len(err.splitlines()) != 1 or "--compact" not in err or os.path.exists(out):
            fail(f"--compact -o {target}: status {status}, {err.strip()!r}: expected one line, exit 2, no file")
        else:
            passed()


def validate(files):
    if not VALIDATOR:
        print(f"gltf_test: the glTF Validator is not installed (.ci/deps test): {len(files)} outputs not validated")
        return
    bad = G.validator_problems(VALIDATOR, files)
    if bad:
        fail("glTF Validator: " + "; ".join(bad[:10]))
    else:
        passed()
        print(f"ok: glTF Validator: {len(files)} outputs, no errors, no warnings")


# ---------------------------------------------------------------- bad files
def check_tracks_apart_say(work):
    """Tracks made apart (a large file into glTF) say what the same keys say read in order: a
    warning once, and of two bad keys the first in the file's order, with nothing written."""
    rng = np.random.default_rng(7)
    t = np.arange(200) / 30

    def write(name, change):
        b = G.Builder()
        b.skeleton(8)
        quats = [random_quats(rng, 200, 0.2) for _ in range(8)]
        change(quats)
        b.animation([{"node": j, "path": "rotation", "times": t, "values": quats[j]} for j in range(8)])
        b.detailed_mesh(HEAVY_VERTICES)
        path = os.path.join(work, name)
        b.write(path, "glb")
        return path

    def long_and_zero(quats):
        quats[2][50] *= 1.5  # renormalised, with a warning
        quats[6][5] *= 1.5
        quats[5][120] = 0  # a zero quaternion, and another one in a later track
        quats[7][3] = 0

    def long_only(quats):
        quats[2][50] *= 1.5
        quats[6][5] *= 1.5

    for name, change, status_expected in (("apart_long.glb", long_only, 0), ("apart_zero.glb", long_and_zero, 2)):
        path = write(name, change)
        out, in_order = path + ".out.glb", path + ".out.csv"
        status, _, err = run(["resample", path, "-o", out])
        reference_status, _, reference_err = run(["resample", path, "--rep", "quat", "-o", in_order])
        if status != status_expected or reference_status != status_expected or err != reference_err:
            fail(f"{name} into .glb: status {status}, {err.strip()!r}; into .csv (keys in order): status "
                 f"{reference_status}, {reference_err.strip()!r}")
        elif status == 2 and ("samplers[5].output[120]" not in err.strip().split("\n")[-1] or "samplers[7]" in err
                              or os.path.exists(out)):
            fail(f"{name} into .glb: {err.strip()!r}, expected the error of samplers[5] (the first bad key), "
                 f"and nothing written")
        elif status == 0 and (err.count("warning") != 1 or not compare_frames(
                f"{out} read back", open(in_order).read(), run(["convert", out, "--to", "csv", "--rep", "quat"])[1],
                FLOAT32_DEG)):
            fail(f"{name} into .glb: {err.strip()!r}, expected one warning, or frames not the CSV's")
        else:
            passed()
            print(f"ok: {name} into .glb says what it says into .csv: {err.strip()}")


def small_glb(path, joints, seed):
    """A .glb of `joints` joints, joint 1 turned by three random keys at 0, 0.5 and 1 s."""
    b = G.Builder()
    b.skeleton(joints)
    b.animation([{"node": 1, "path": "rotation", "times": [0.0, 0.5, 1.0],
                  "values": random_quats(np.random.default_rng(seed), 3)}])
    b.write(path, "glb")


def bad_cases(work):
    """(name, bytes or a function writing files, expected piece of the message)."""
    base = os.path.join(work, "base.glb")
    small_glb(base, 3, 1)
    good = open(base, "rb").read()
    text_len = struct.unpack_from("<I", good, 12)[0]
    doc = json.loads(good[20:20 + text_len])
    binary = good[20 + text_len + 8:]

    def with_json(change):
        d = json.loads(json.dumps(doc))
        change(d)
        return G.glb(json.dumps(d).encode(), binary)

    def times_bytes(values):
        d = json.loads(json.dumps(doc))
        view = d["bufferViews"][d["accessors"][d["animations"][0]["samplers"][0]["input"]]["bufferView"]]
        data = bytearray(binary)
        struct.pack_into("<3f", data, view["byteOffset"], *values)
        return G.glb(json.dumps(d).encode(), bytes(data))

    def set_(path, value):
        def change(d):
            target = d
            for p in path[:-1]:
                target = target[p]
            target[path[-1]] = value
        return change

    sampler = ["animations", 0, "samplers", 0]
    out_acc = doc["animations"][0]["samplers"][0]["output"]
    in_acc = doc["animations"][0]["samplers"][0]["input"]

    def unstored(acc, count, sparse=False):
        """Accessor `acc` with no bufferView (all zeros) and `count` elements;
        with `sparse`, one substitute (index 0: the first byte of time 0)."""
        def change(d):
            a = d["accessors"][acc]
            a.pop("bufferView")
            a["count"] = count
            if sparse:
                a["sparse"] = {"count": 1, "values": {"bufferView": doc["accessors"][out_acc]["bufferView"]},
                               "indices": {"bufferView": doc["accessors"][in_acc]["bufferView"],
                                           "componentType": G.UNSIGNED_BYTE}}
        return change

    cases = [
        ("magic.glb", b"glTx" + good[4:], "not a GLB file"),
        ("version.glb", good[:4] + struct.pack("<I", 1) + good[8:], "GLB version 1: expected 2"),
        ("truncated.glb", good[:-16], "truncated GLB: the header says"),
        # A file read whole is truncated, whatever length its header states
        # (from a pipe, a length past --max-bytes is refused before reading on).
        ("stated.glb", good[:8] + struct.pack("<I", 2**32 - 1) + good[12:],
         f"truncated GLB: the header says 4294967295 bytes, the file has {len(good)}"),
        ("header.glb", good[:9], "truncated GLB: 9 bytes"),
        ("chunk.glb", good[:12] + struct.pack("<I", 99999) + good[16:], "runs past the end"),
        ("json.glb", G.glb(b'{"asset": {"version": "2.0"}, "animations": [', binary), "invalid JSON"),
        ("asset.glb", with_json(set_(["asset", "version"], "1.0")), "asset.version: glTF 1.0"),
        ("draco.glb", with_json(set_(["extensionsRequired"], ["KHR_draco_mesh_compression"])),
         "extensionsRequired[0]: \"KHR_draco_mesh_compression\""),
        ("meshopt.glb", with_json(set_(["extensionsRequired"], ["EXT_meshopt_compression"])), "EXT_meshopt_compression"),
        ("accessor.glb", with_json(set_(["accessors", out_acc, "byteOffset"], 40)),
         f"animations[0].samplers[0].output: accessor {out_acc}: 3 elements from byte 40 read past the end of bufferView"),
        # Counts that claim more than the file holds are refused before
        # anything is allocated (2^40 elements would not fit in memory;
        # 2^62 four-component elements overflowed the size).
        ("stored.glb", with_json(set_(["accessors", in_acc, "count"], 2**40)),
         f"samplers[0].input: accessor {in_acc}: 1099511627776 elements from byte 0 read past the end"),
        ("zeros.glb", with_json(unstored(out_acc, 2**40)),
         "samplers[0].output: 1099511627776 elements for 3 key times: expected 3"),
        ("sparse.glb", with_json(unstored(out_acc, 2**62, sparse=True)),
         "samplers[0].output: 4611686018427387904 elements for 3 key times: expected 3"),
        ("zero_times.glb", with_json(unstored(in_acc, 2**40)),
         "samplers[0].input: 1099511627776 key times, 0 of them stored (the rest are 0): expected strictly increasing"),
        ("view.glb", with_json(set_(["bufferViews", doc["accessors"][out_acc]["bufferView"], "byteLength"], 10**6)),
         f"bufferViews[{doc['accessors'][out_acc]['bufferView']}]: bytes "),
        ("times.glb", times_bytes([0.0, 0.5, 0.5]), "samplers[0].input: time 0.5 s at key 2 is not after"),
        ("nan.glb", times_bytes([0.0, float("nan"), 1.0]), "element 1 is not finite"),
        ("vec3.glb", with_json(set_(["accessors", out_acc, "type"], "VEC3")), "type 'VEC3': expected VEC4"),
        ("cubic.glb", with_json(set_(sampler + ["interpolation"], "CUBICSPLINE")),
         "3 elements for 3 key times: expected 9 (CUBICSPLINE"),
        ("interp.glb", with_json(set_(sampler + ["interpolation"], "BEZIER")), "interpolation 'BEZIER'"),
        ("node.glb", with_json(set_(["animations", 0, "channels", 0, "target", "node"], 99)),
         "animations[0].channels[0].target.node: 99: expected an index into nodes"),
        ("sampler.glb", with_json(set_(["animations", 0, "channels", 0, "sampler"], 5)), "channels[0].sampler: 5"),
        ("uint.glb", with_json(set_(["accessors", out_acc, "componentType"], G.UNSIGNED_INT)), "componentType 5125"),
        ("noanim.glb", with_json(lambda d: d.pop("animations")), "no animations"),
        ("nobin.glb", G.glb(json.dumps(doc).encode(), b""), "buffers[0]: no uri, and the file has no GLB BIN chunk"),
        ("twice.glb", G.glb(json.dumps(doc).replace('"samplers": [{', '"samplers": [{"output": 0, ', 1).encode(), binary),
         "animations[0].samplers[0]: 'output' appears twice: expected each name once in an object"),
    ]
    # .gltf files whose buffers are bad: missing, short, bad base64.
    gltf_doc = json.loads(json.dumps(doc))
    gltf_doc["buffers"][0]["uri"] = "missing.bin"
    cases.append(("missing.gltf", json.dumps(gltf_doc).encode(), "cannot read"))
    with open(os.path.join(work, "short.bin"), "wb") as f:
        f.write(binary[:20])
    gltf_doc["buffers"][0]["uri"] = "short.bin"
    cases.append(("short.gltf", json.dumps(gltf_doc).encode(), f"buffers[0]: holds 20 bytes: expected byteLength {len(binary)}"))
    gltf_doc["buffers"][0]["uri"] = "data:application/octet-stream;base64,AAAA*AAA"
    cases.append(("base64.gltf", json.dumps(gltf_doc).encode(), "buffers[0]: uri: expected a base64 data: URI"))
    # A buffer with no end (a relative name for /dev/zero): its byteLength read, no more.
    gltf_doc["buffers"][0]["uri"] = os.path.relpath("/dev/zero", work)
    cases.append(("endless.gltf", json.dumps(gltf_doc).encode(),
                  "samplers[0].input: time 0 s at key 1 is not after the previous key's 0 s"))
    gltf_doc["buffers"][0]["uri"] = "https://example.com/a.bin"
    cases.append(("remote.gltf", json.dumps(gltf_doc).encode(), "expected a file beside the glTF file"))
    return cases


def check_bad(work):
    # A .gltf and its .bin go in place together, or neither does.
    bad_pair = os.path.join(work, "pair.gltf")
    status, _, _ = run(["resample", "-", "--from", "glb", "-o", bad_pair], stdin=b"glTx")
    if status != 2 or os.path.exists(bad_pair) or os.path.exists(os.path.join(work, "pair.bin")):
        fail(f"a bad input into {bad_pair}: status {status}, or a file written")
    else:
        passed()
    # A translation a 32-bit float cannot hold, into glTF.
    big = os.path.join(work, "big.csv")
    with open(big, "w") as f:
        f.write("time,qw,qx,qy,qz,tx,ty,tz\n0,1,0,0,0,1e39,0,0\n1,1,0,0,0,0,0,0\n")
    status, _, err = run(["resample", big, "-o", os.path.join(work, "big.glb")])
    if status != 2 or err.strip() != f"keyrot: {big}: translation 1e+39 is beyond a 32-bit float: expected what glTF can store" \
            or os.path.exists(os.path.join(work, "big.glb")):
        fail(f"big.csv into glTF: status {status}, {err.strip()!r}")
    else:
        passed()
    # In 1 GiB of address space, a bad file (even one naming /dev/zero) ends in its
    # error, never in all the memory. AddressSanitizer cannot start in 1 GiB: a
    # sanitizer build goes without the cap.
    cap = 1 << 30 if run(["--version"], memory=1 << 30)[0] == 0 else None
    for name, data, expected in bad_cases(work):
        path = os.path.join(work, name)
        with open(path, "wb") as f:
            f.write(data)
        target = os.path.join(work, "out.csv")
        status, out, err = run(["resample", path, "-o", target], memory=cap)
        lines = err.strip().split("\n")
        if status != 2 or len(lines) != 1 or expected not in err or not err.startswith(f"keyrot: {path}") or os.path.exists(target):
            fail(f"bad {name}: status {status}, stderr {err.strip()!r}, expected one line with {expected!r}")
            if os.path.exists(target):
                os.remove(target)
        else:
            passed()
            print(f"ok: bad {name}: {err.strip()}")


def check_unstored(work):
    """Accessors with no bufferView (zeros but for sparse substitutes) that
    are valid read as their stored twins: key times 0, 0.5, 1 given as two
    substitutes over a zero, and rotations given wholly as substitutes."""
    stored = os.path.join(work, "stored_twin.glb")
    small_glb(stored, 2, 2)
    doc, binary = G.parts(stored)
    binary = bytearray(binary)
    s = doc["animations"][0]["samplers"][0]

    def view(data):
        binary.extend(b"\0" * (-len(binary) % 4))
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(data)})
        binary.extend(data)
        return len(doc["bufferViews"]) - 1

    times = doc["accessors"][s["input"]]
    times.pop("bufferView")
    times["sparse"] = {"count": 2, "indices": {"bufferView": view(bytes([1, 2])), "componentType": G.UNSIGNED_BYTE},
                       "values": {"bufferView": view(struct.pack("<2f", 0.5, 1.0))}}
    rotations = doc["accessors"][s["output"]]
    old_view = doc["bufferViews"][rotations.pop("bufferView")]
    start = old_view.get("byteOffset", 0) + rotations.pop("byteOffset", 0)
    rotations["sparse"] = {"count": 3, "indices": {"bufferView": view(bytes([0, 1, 2])), "componentType": G.UNSIGNED_BYTE},
                           "values": {"bufferView": view(bytes(binary[start:start + 48]))}}
    doc["buffers"][0]["byteLength"] = len(binary) + (-len(binary) % 4)
    unstored = os.path.join(work, "unstored.glb")
    with open(unstored, "wb") as f:
        f.write(G.glb(json.dumps(doc).encode(), bytes(binary)))
    outputs = []
    for path in (stored, unstored):
        status, out, _ = run(["convert", path, "--rep", "quat", "--to", "csv"])
        outputs.append((status, out))
    if outputs[0][0] != 0 or outputs[1] != outputs[0]:
        fail(f"unstored accessors: {outputs[1]!r}, expected as {stored}: {outputs[0]!r}")
    else:
        passed()


def main():
    with tempfile.TemporaryDirectory() as work:
        cases, heavy = make_cases(work)
        for case in cases:
            for fps in (24, 30, 60):
                check_resample(case, fps)
            check_convert(case)
        two = cases[-1]  # (the two animations)
        check_resample(two, 24, ["--animation", "Run"], animation="Run")
        check_resample(two, 24, ["--animation", "0"], animation="Walk")
        with open(cases[0].path, "rb") as f:
            check_resample(cases[0], 30, stdin=f.read())
        with open(cases[2].path, "rb") as f:  # a .gltf on standard input, its buffer a data: URI
            check_resample(cases[2], 30, stdin=f.read())
        written = []
        for case in cases + heavy:
            check_gltf_output(case, 30, "glb", written)
            check_gltf_output(case, 24, "gltf", written)
        for rig in ("rig.glb", "heavy_rig.glb"):
            check_rig_layout(next(c for c in cases + heavy if c.name == rig), written)
        check_tracks_apart_say(work)
        check_cubic_kept(cases[2], work, written)
        check_step_output(cases[0], work, written)
        check_new_files(work, written)
        check_new_file_still_channels(work, written)
        check_compact(cases, work, written)
        validate(written)
        check_bad(work)
        check_unstored(work)
    return summary("gltf_test")


if __name__ == "__main__":
    sys.exit(main())
