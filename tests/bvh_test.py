#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""BVH input and output against scipy's reading of Euler angles.

Generated files: every rotation channel order on the joints of one file
(mixed orders between joints), 6-channel non-root joints, a joint with one
rotation channel, CRLF line ends, tabs, a Frame Time written as .0083333,
and curves that turn through +-180 degrees. Checked:
- each joint's rotation is scipy's Rotation.from_euler(ORDER, angles) with
  the intrinsic (uppercase) sequence of its channels, its position channels
  the translation, times frame / 120 exactly;
- BVH -> BVH at the same rate keeps the hierarchy byte for byte and gives
  every channel value of every frame back as the number it was;
- BVH -> BVH at 24 fps: each frame the input frame at its time, its values
  as they were, and the rotations of `resample --to csv`;
- resample of the BVH equals convert to quaternion CSV, then resample,
  byte for byte;
- --euler-continuous on CSV output: no jump of a turn in a track of another
  sequence, the input's own angles in a track of the output's, the same
  rotations (bvh_round_trip_test.py takes captures of other tools' styles);
- bad files: one line with file:line, exit 2, nothing written (into a
  file or to standard output);
- BVH to BVH, CSV, JSON, glb and gltf in bounded memory: a take 10 times longer takes about
  the same memory.

Usage: bvh_test.py KEYROT. Exit 0 when all pass, 1 otherwise, 77 without scipy.
"""
import csv
import io
import itertools
import json
import math
import os
import subprocess
import sys
import tempfile

from peak import peak_kb

try:
    import numpy as np
    from scipy.spatial.transform import Rotation
except ImportError:  # pragma: no cover
    print("bvh_test: numpy/scipy not installed (apt-get install python3-scipy); skipped")
    sys.exit(77)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import fail, ok, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])
ORDERS = ["".join(p) for p in itertools.permutations("XYZ")]


def run(args, stdin=None):
    p = subprocess.run([KEYROT] + args, input=stdin, capture_output=True)
    return p.returncode, p.stdout.decode(), p.stderr.decode()


def read_csv(text):
    return list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))


def angle_deg(a, b):
    """Geodesic angle between two scipy rotations, in degrees."""
    return float(np.degrees((a.inv() * b).magnitude()))


class Joint:
    def __init__(self, name, channels, offset):
        self.name, self.channels, self.offset = name, channels, offset
        self.children = []


def skeleton():
    """A root with positions, then a joint of each rotation order, a 6-channel joint, a
    one-rotation joint, End Sites."""
    root = Joint("Hips", ["Xposition", "Yposition", "Zposition", "Zrotation", "Xrotation", "Yrotation"], (0, 0, 0))
    parent = root
    joints = [root]
    for i, order in enumerate(ORDERS):
        j = Joint(f"Joint_{order}", [f"{a}rotation" for a in order], (0, 1.5, 0.25 * i))
        parent.children.append(j)
        joints.append(j)
        parent = j if i % 2 == 0 else parent
    six = Joint("Free Joint", ["Zrotation", "Yposition", "Xrotation", "Xposition", "Yrotation", "Zposition"], (1, 0, 0))
    root.children.append(six)
    one = Joint("Hinge", ["Xrotation"], (0, 0.5, 0))
    six.children.append(one)
    joints += [six, one]
    return root, joints


def hierarchy_text(root, nl, indent="\t"):
    out = ["HIERARCHY"]

    def emit(j, depth, kind):
        pad = indent * depth
        out.append(f"{pad}{kind} {j.name}")
        out.append(f"{pad}{{")
        out.append(f"{pad}{indent}OFFSET {j.offset[0]:.6f} {j.offset[1]:.6f} {j.offset[2]:.6f}")
        out.append(f"{pad}{indent}CHANNELS {len(j.channels)} {' '.join(j.channels)}")
        for c in j.children:
            emit(c, depth + 1, "JOINT")
        if not j.children:
            out.extend([f"{pad}{indent}End Site", f"{pad}{indent}{{", f"{pad}{indent*2}OFFSET 0.0 1.0 0.0", f"{pad}{indent}}}"])
        out.append(f"{pad}}}")

    emit(root, 0, "ROOT")
    return nl.join(out) + nl


def motion(joints, frames, rng):
    """Per joint, per channel, a curve: angles sweeping through +-180 and beyond (written
    wrapped into [-180, 180), as capture files have them), positions drifting."""
    t = np.arange(frames) / 120.0
    values = {}
    for j in joints:
        for c in j.channels:
            if c.endswith("rotation"):
                v = rng.uniform(-180, 180) + rng.uniform(-400, 400) * t + 20 * np.sin(7 * t + rng.uniform(0, 6))
                values[(j.name, c)] = (v + 180) % 360 - 180
            else:
                values[(j.name, c)] = rng.normal() + 0.5 * t
    return values


def write_bvh(path, root, joints, values, frames, frame_time="0.0083333", nl="\n", sep=" "):
    lines = [hierarchy_text(root, nl) + "MOTION", f"Frames: {frames}", f"Frame Time: {frame_time}"]
    for f in range(frames):
        lines.append(sep.join(f"{values[(j.name, c)][f]:.6f}" for j in joints for c in j.channels))
    with open(path, "w", newline="") as out:
        out.write(nl.join(lines) + nl)


def expected_rotation(j, values, f):
    """scipy's intrinsic sequence of the joint's rotation channels, in their order."""
    rot = [c for c in j.channels if c.endswith("rotation")]
    order = "".join(c[0] for c in rot)
    angles = [float(f"{values[(j.name, c)][f]:.6f}") for c in rot]
    return Rotation.from_euler(order, angles, degrees=True)


def check_read(path, joints, values, frames):
    status, out, err = run(["convert", path, "--to", "csv", "--rep", "quat"])
    if status != 0:
        fail(f"convert {path}: {err.strip()}")
        return
    rows = read_csv(out)
    by = {}
    for r in rows:
        by.setdefault(r["track"], []).append(r)
    if list(by) != [j.name for j in joints]:
        fail(f"{path}: tracks {list(by)}, expected {[j.name for j in joints]}")
        return
    worst, worst_pos = 0.0, 0.0
    for j in joints:
        got = by[j.name]
        if [int(r["frame"]) for r in got] != list(range(frames)):
            fail(f"{path}: {j.name}: frames not 0..{frames - 1}")
            return
        for f, r in enumerate(got):
            q = Rotation.from_quat([float(r["qx"]), float(r["qy"]), float(r["qz"]), float(r["qw"])])
            worst = max(worst, angle_deg(q, expected_rotation(j, values, f)))
            positions = [c for c in j.channels if c.endswith("position")]
            for c in positions:
                want = float(f"{values[(j.name, c)][f]:.6f}")
                worst_pos = max(worst_pos, abs(float(r["t" + c[0].lower()]) - want))
            if not positions and r.get("tx"):
                fail(f"{path}: {j.name} has a translation but no position channels")
                return
    if worst > 1e-9 or worst_pos > 0:
        fail(f"{path}: largest difference from scipy {worst:.3g} deg, {worst_pos:.3g} in position")
    else:
        ok(f"{path}: {len(joints)} joints x {frames} frames as scipy's from_euler, within {worst:.2g} deg")
    # Times: frame / 120 exactly, though the file says 0.0083333.
    _, text, _ = run(["resample", path, "--fps", "120", "--to", "csv", "--rep", "quat"])
    last = read_csv(text)[frames - 1]
    if float(last["time"]) != (frames - 1) / 120:
        fail(f"{path}: last frame at {last['time']} s, expected {(frames - 1) / 120}")
    else:
        ok(f"{path}: Frame Time 0.0083333 read as 120 fps (last frame at {last['time']} s)")


def motion_of(text):
    """The hierarchy text and the frame rows (lists of floats) of a BVH text."""
    head, _, rest = text.partition("MOTION")
    lines = [line for line in rest.replace("\r\n", "\n").split("\n") if line.strip()]
    return head, lines[1], [[float(x) for x in line.split()] for line in lines[2:]]


def joint_rotations(joints, row):
    """Per joint, the rotation its channel values in `row` give (scipy)."""
    out, i = [], 0
    for j in joints:
        vals = dict(zip(j.channels, row[i:i + len(j.channels)]))
        i += len(j.channels)
        rot = [c for c in j.channels if c.endswith("rotation")]
        out.append(Rotation.from_euler("".join(c[0] for c in rot), [vals[c] for c in rot], degrees=True))
    return out


def check_round_trip(path, joints, work):
    out = os.path.join(work, "round.bvh")
    status, _, err = run(["convert", path, "-o", out])
    if status != 0:
        fail(f"convert {path} -o {out}: {err.strip()}")
        return
    with open(path, newline="") as f:
        original = f.read()
    with open(out, newline="") as f:
        written = f.read()
    head_in, _, rows_in = motion_of(original)
    head_out, frame_time, rows_out = motion_of(written)
    if head_in != head_out:
        fail(f"{out}: the hierarchy was not kept byte for byte")
        return
    if ("\r\n" in original) != ("\r\n" in written):
        fail(f"{out}: line ends not kept")
    # Every value the number it was (written again in fewer digits: 4.000000 as 4)
    differ = sum(a != b for r0, r1 in zip(rows_in, rows_out) for a, b in zip(r0, r1))
    written_time = frame_time.split()[-1]
    if len(rows_in) != len(rows_out) or differ or written_time != "0.0083333":
        fail(f"{out}: {len(rows_out)} frames of {len(rows_in)}, {differ} values not as they were, '{frame_time}'")
    else:
        ok(f"{path} -> BVH at its own rate: hierarchy kept, every value as it was ({frame_time})")


def check_resample_24(path, joints, work):
    out = os.path.join(work, "take24.bvh")
    status, _, err = run(["resample", path, "--fps", "24", "-o", out])
    if status != 0:
        fail(f"resample {path} -o {out}: {err.strip()}")
        return
    with open(out, newline="") as f:
        _, frame_time, rows = motion_of(f.read())
    if frame_time.split()[-1] != repr(1 / 24):
        fail(f"{out}: '{frame_time}', expected Frame Time {1 / 24!r}")
    # Each 24 fps frame is a 120 Hz frame of the input, every value as it was there.
    with open(path, newline="") as f:
        _, _, rows_in = motion_of(f.read())
    differ = sum(a != b for f, row in enumerate(rows) for a, b in zip(row, rows_in[5 * f]))
    # The frames are keyrot's own 24 fps frames, read back.
    _, direct, _ = run(["resample", path, "--fps", "24", "--to", "csv", "--rep", "quat"])
    want = read_csv(direct)
    worst = 0.0
    for f, row in enumerate(rows):
        for j, r in zip(joints, joint_rotations(joints, row)):
            d = want[joints.index(j) * len(rows) + f]
            q = Rotation.from_quat([float(d["qx"]), float(d["qy"]), float(d["qz"]), float(d["qw"])])
            worst = max(worst, angle_deg(q, r))
    if differ or worst > 1e-9:
        fail(f"{out}: {differ} values not the input's at their frames, {worst:.3g} deg from the CSV frames")
    else:
        ok(f"{path} -> 24 fps BVH: {len(rows)} frames, each the input's own, within {worst:.2g} deg")
    # Resampling the BVH equals resampling its quaternion tracks: the same rows, times and
    # translations to the bit, quaternions to the last bit (read from CSV, they are normalised
    # once more).
    _, quats, _ = run(["convert", path, "--to", "csv", "--rep", "quat"])
    _, via_quats, err = run(["resample", "--from", "csv", "--fps", "24", "--rep", "quat"], quats.encode())
    a, b = read_csv(direct), read_csv(via_quats)
    q = ("qw", "qx", "qy", "qz")
    same = len(a) == len(b) and all({k: v for k, v in x.items() if k not in q} == {k: v for k, v in y.items() if k not in q}
                                    for x, y in zip(a, b))
    ulps = max(abs(float(x[c]) - float(y[c])) for x, y in zip(a, b) for c in q) / 2.0**-53
    if not same or ulps > 2:
        fail(f"{path}: resample differs from convert | resample ({ulps:.3g} ulp; {err.strip()})")
    else:
        ok(f"{path}: resample = convert to quaternions | resample (quaternions within {ulps:.2g} ulp)")


def check_continuous_csv(path, joints, values):
    _, canonical, _ = run(["convert", path, "--to", "csv", "--rep", "euler", "--out-euler", "ZXY"])
    status, continuous, err = run(["convert", path, "--to", "csv", "--rep", "euler", "--out-euler", "ZXY",
                                   "--euler-continuous"])
    if status != 0:
        fail(f"--euler-continuous: {err.strip()}")
        return
    a, b = read_csv(canonical), read_csv(continuous)
    worst, jump_before, jump_after, not_own = 0.0, 0.0, 0.0, 0
    frame = 0
    for i, (x, y) in enumerate(zip(a, b)):
        frame = frame + 1 if i and a[i - 1]["track"] == x["track"] else 0
        ex = [float(x[c]) for c in ("e1", "e2", "e3")]
        ey = [float(y[c]) for c in ("e1", "e2", "e3")]
        worst = max(worst, angle_deg(Rotation.from_euler("ZXY", ex, degrees=True),
                                     Rotation.from_euler("ZXY", ey, degrees=True)))
        joint = next(j for j in joints if j.name == x["track"])
        rotations = [c for c in joint.channels if c.endswith("rotation")]
        if "".join(c[0] for c in rotations) == "ZXY":
            # Keys in the output's own sequence: each the input's own angles, in both
            not_own += sum([float(f"{values[(joint.name, c)][frame]:.6f}") for c in rotations] != e for e in (ex, ey))
        elif frame:
            jump_before = max(jump_before, max(abs(p - float(a[i - 1][c])) for p, c in zip(ex, ("e1", "e2", "e3"))))
            jump_after = max(jump_after, max(abs(p - float(b[i - 1][c])) for p, c in zip(ey, ("e1", "e2", "e3"))))
    if not_own:
        fail(f"--rep euler --out-euler ZXY: {not_own} keys of ZXY joints not the input's own angles")
    if worst > 1e-9 or jump_after >= 90 or jump_before < 180:
        fail(f"--euler-continuous: {worst:.3g} deg apart; largest step {jump_before:.3g} canonical, {jump_after:.3g} continuous")
    else:
        ok(f"--euler-continuous: the same rotations; largest step {jump_before:.3g} deg canonical, {jump_after:.3g} continuous")


def check_gltf(path, root, joints, work):
    """BVH -> glTF: the skeleton as nodes (offsets as translations), the motion as one animation."""
    out = os.path.join(work, "take.gltf")
    status, _, err = run(["resample", path, "--fps", "30", "-o", out])
    if status != 0:
        fail(f"resample {path} -o {out}: {err.strip()}")
        return
    with open(out) as f:
        doc = json.load(f)
    nodes, want = doc["nodes"], []

    def walk(j, parent):
        want.append((j.name, parent, [float(np.float32(x)) for x in j.offset]))
        me = len(want) - 1
        for c in j.children:
            walk(c, me)
        if not j.children:
            want.append((j.name + "_End", me, [0.0, 1.0, 0.0]))

    walk(root, None)
    parents = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}
    got = [(n["name"], parents.get(i), n.get("translation", [0.0, 0.0, 0.0])) for i, n in enumerate(nodes)]
    targets = [(c["target"]["node"], c["target"]["path"]) for c in doc["animations"][0]["channels"]]
    animated = [(i, "rotation") for i, n in enumerate(nodes) if not n["name"].endswith("_End")]
    moved = {(i, "translation") for i, n in enumerate(nodes) if n["name"] in ("Hips", "Free Joint")}
    if got != want or set(targets) != set(animated) | moved or doc["scenes"][0]["nodes"] != [0]:
        fail(f"{out}: nodes {got[:3]}..., channels {targets[:4]}..., expected {want[:3]}...")
        return
    _, direct, _ = run(["resample", path, "--fps", "30", "--to", "csv", "--rep", "quat"])
    _, back, err = run(["convert", out, "--to", "csv", "--rep", "quat"])
    a, b = read_csv(direct), read_csv(back)
    rot = lambda r: Rotation.from_quat([float(r["qx"]), float(r["qy"]), float(r["qz"]), float(r["qw"])])
    worst = max((angle_deg(rot(x), rot(y)) for x, y in zip(a, b)), default=math.inf)
    if len(a) != len(b) or [x["track"] for x in a] != [y["track"] for y in b] or worst > 2e-5:
        fail(f"{out}: read back {len(b)} rows of {len(a)}, {worst:.3g} deg ({err.strip()})")
    else:
        ok(f"{path} -> glTF: the skeleton as {len(nodes)} nodes, the frames within {worst:.2g} deg (32-bit floats)")


def check_rates(work):
    """The rate a Frame Time as written stands for: a whole rate where exactly one rounds to it."""
    head = "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Zrotation\n}\nMOTION\nFrames: 2\nFrame Time: "
    rates = {"0.0083333": 120, "0.0333": 30, ".04": 25, "0.017": 1 / 0.017, "0.0333667": 1 / 0.0333667, "4e-2": 25}
    bad = []
    for written, rate in rates.items():
        _, out, err = run(["convert", "-", "--to", "json"], (head + written + "\n0\n1\n").encode())
        got = json.loads(out)["fps"] if out else None
        if got != rate:
            bad.append(f"{written}: {got}, expected {rate} ({err.strip()})")
    if bad:
        fail("Frame Time rates: " + "; ".join(bad))
    else:
        ok(f"Frame Time as written: {len(rates)} rates as the README says")


def check_bad(work):
    good = ("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation "
            "Yrotation\n  JOINT Leg\n  {\n    OFFSET 0 -1 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
            "    End Site\n    {\n      OFFSET 0 -1 0\n    }\n  }\n}\nMOTION\nFrames: 2\nFrame Time: 0.04\n"
            "0 0 0 0 0 0 0 0 0\n1 1 1 10 20 30 40 50 60\n")
    status, _, err = run(["info", "-"], good.encode())
    if status != 0:
        fail(f"the good file of the bad cases: {err.strip()}")
    cases = {
        "short line": (good.replace("1 1 1 10 20 30 40 50 60", "1 1 1 10 20 30 40 50"), ":20: expected 9 values"),
        "long line": (good.replace("1 1 1 10 20 30 40 50 60", "1 1 1 10 20 30 40 50 60 70"), ":20: expected 9 values"),
        "fewer frames": (good.replace("Frames: 2", "Frames: 3"), "'Frames: 3', but 2 frame lines"),
        "more frames": (good.replace("Frames: 2", "Frames: 1"), ":20: a frame line after the 1"),
        "no motion": (good.split("MOTION")[0], "no MOTION section"),
        "unknown channel": (good.replace("Zrotation Xrotation Yrotation\n    End", "Zrotation Xrotation Wrotation\n    End"),
                            ":9: channel 'Wrotation': expected"),
        "channel twice": (good.replace("Zrotation Xrotation Yrotation\n    End", "Zrotation Xrotation Zrotation\n    End"),
                          ":9: channel Zrotation listed twice"),
        "zero frame time": (good.replace("Frame Time: 0.04", "Frame Time: 0"), ":18: Frame Time 0: expected a positive"),
        "nan frame time": (good.replace("Frame Time: 0.04", "Frame Time: nan"), ":18: 'Frame Time: nan': expected"),
        "missing brace": (good.replace("    }\n  }\n}", "    }\n  }"), ":15: MOTION inside 'Hips'"),
        "extra brace": (good.replace("  }\n}\n", "  }\n}\n}\n"), ":16: '}' without a matching '{'"),
        "not a number": (good.replace("1 1 1 10", "1 1 1 ten"), ":20: value 4: 'ten': expected a number"),
        "channel count": (good.replace("CHANNELS 3 Z", "CHANNELS 2 Z"), ":9: CHANNELS 2: expected 2 channel names"),
        "no hierarchy": (good.replace("HIERARCHY\n", ""), "expected HIERARCHY"),
    }
    bad_ok = 0
    for name, (text, want) in cases.items():
        path = os.path.join(work, name.replace(" ", "_") + ".bvh")
        with open(path, "w") as f:
            f.write(text)
        out = path + ".out.bvh"
        status, _, err = run(["resample", path, "-o", out])
        # BVH to BVH on standard output streams too: after a pass that reads every frame.
        status_stdout, written, err_stdout = run(["resample", path])
        lines = err.strip().split("\n")
        if status != 2 or len(lines) != 1 or want not in lines[0] or not lines[0].startswith(f"keyrot: {path}") \
                or os.path.exists(out) or (status_stdout, written, err_stdout) != (2, "", err):
            fail(f"bad BVH '{name}': status {status}, stderr {err.strip()!r}, expected '{want}'; to standard "
                 f"output: status {status_stdout}, {len(written)} bytes, stderr {err_stdout.strip()!r}")
        else:
            bad_ok += 1
    status, _, err = run(["resample", os.path.join(os.path.dirname(KEYROT), "..", "data", "walk.csv"),
                          "--to", "bvh"])
    if status != 2 or "BVH output needs a BVH input" not in err:
        fail(f"BVH output from CSV: status {status}, {err.strip()}")
    else:
        bad_ok += 1
    if bad_ok == len(cases) + 1:
        ok(f"{bad_ok} bad inputs: one line naming file:line, exit 2, nothing written")


def check_memory(work):
    """BVH to BVH streams, to CSV or JSON keeps its columns in a temporary file, and to glTF its
    buffer: a take 10 times longer needs about the same memory. Both takes are long enough that
    their rows are formatted on threads (from 4,096 rows), whose batches are not the take's."""
    header = ("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation "
              "Xrotation Yrotation\n  JOINT Leg\n  {\n    OFFSET 0 -1 0\n    CHANNELS 3 Zrotation Xrotation "
              "Yrotation\n    End Site\n    {\n      OFFSET 0 -1 0\n    }\n  }\n}\nMOTION\n")
    peaks = []
    for frames in (30000, 300000):
        path = os.path.join(work, f"long{frames}.bvh")
        with open(path, "w") as f:
            f.write(header + f"Frames: {frames}\nFrame Time: 0.0083333\n")
            line = " ".join(["1.25", "-2.5", "3.75", "10.5", "-20.25", "30.125", "40.5", "-50.25", "60.125"]) + "\n"
            f.write(line * frames)
        for out in ("bvh", "csv", "json", "glb", "gltf"):
            for args in (["resample", path, "--fps", "24", "-o", f"{path}.24.{out}"],
                         ["resample", path, "--fps", "24", "--to", out]):
                status, kb = peak_kb(KEYROT, args)
                if status != 0:
                    fail(f"{' '.join(args)}: status {status}")
                peaks.append((frames, out, kb))
    def growth(out):
        short = max(kb for frames, o, kb in peaks if o == out and frames == 30000)
        return short, max(kb for frames, o, kb in peaks if o == out and frames == 300000)
    # What BVH to BVH, which holds a frame line at most, grows by in this build: the formatting
    # threads' batches, a bounded pool the longer take fills (about 3 MB in a release build, and
    # no more at 3,000,000 frames), and the allocator's own (more under AddressSanitizer).
    bvh_short, bvh_long = growth("bvh")
    allowance = 4000 + max(0, bvh_long - bvh_short)
    for out in ("bvh", "csv", "json", "glb", "gltf"):
        short, long_ = growth(out)
        # The 300,000 frames' values alone would take 21 MB held as numbers (glTF's 32-bit floats at
        # 24 fps, gathered as the previous writer did, 14 MB).
        if long_ > short + allowance:
            fail(f"BVH to {out} memory: {short} KB for 30,000 frames, {long_} KB for 300,000")
        else:
            ok(f"BVH to {out} memory: {short} KB for 30,000 frames, {long_} KB for 300,000 (file and standard output)")


def main():
    rng = np.random.default_rng(33)
    with tempfile.TemporaryDirectory() as work:
        root, joints = skeleton()
        frames = 600
        values = motion(joints, frames, rng)
        variants = [("take.bvh", "\n", " "), ("crlf_tabs.bvh", "\r\n", "\t")]
        for name, nl, sep in variants:
            path = os.path.join(work, name)
            write_bvh(path, root, joints, values, frames, nl=nl, sep=sep)
            check_read(path, joints, values, frames)
        path = os.path.join(work, "crlf_tabs.bvh")
        check_round_trip(path, joints, work)
        check_resample_24(os.path.join(work, "take.bvh"), joints, work)
        check_continuous_csv(os.path.join(work, "take.bvh"), joints, values)
        check_gltf(os.path.join(work, "take.bvh"), root, joints, work)
        check_rates(work)
        check_bad(work)
        check_memory(work)
    return summary("bvh_test")


if __name__ == "__main__":
    sys.exit(main())
