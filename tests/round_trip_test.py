#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Round trips give back the user's own numbers.

BVH takes in the styles of the files people have (CMU's: a root of six
channels and joints in ZYX at 120 Hz; Bandai Namco's research takes: joints
in ZYX at 30 fps; Truebones': six channels on every joint in ZXY, CRLF and
tabs), each with angles crossing +-180 degrees as captures write them, and
variants with a joint flipped 180 degrees for one frame (a glitch), values
to 4 decimals, and values past +-180 degrees. For each:
- convert to BVH, and resample at the take's own rate: every channel value
  of every frame the number it was, the hierarchy and the Frame Time as
  written;
- resample at half the rate: each frame the input's frame at its time;
- resample at twice the rate: the input's frames among them, and between
  them angles that go on from the frame before, on its branch, so that a
  glitch disturbs only the frames around it (no channel more than 45
  degrees from the key before), with the rotations of keyrot's own frames;
- Euler output (CSV, JSON, NDJSON) in the joints' own sequence: every key
  its own angles; keyrot's picture of a glitched joint stays within the
  take's angles.
And keys of every other representation (CSV, JSON) written back in their
own representation with the numbers they were given: no floating-point
noise on 45 or 30.5. And glTF times: a CSV made at a rate goes to .glb and
back with the same time column; times on no rate come back as the shortest
decimals of their 32-bit floats, which make the same file again.

Usage: round_trip_test.py KEYROT. Exit 0 when all pass, 1 otherwise, 77
without scipy.
"""
import csv
import io
import json
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import check, summary  # noqa: E402

try:
    import numpy as np
    from scipy.spatial.transform import Rotation
except ImportError:  # pragma: no cover
    print("round_trip_test: numpy/scipy not installed (apt-get install python3-scipy); skipped")
    sys.exit(77)

KEYROT = os.path.abspath(sys.argv[1])


def run(*args, stdin=None):
    p = subprocess.run([KEYROT, *args], input=stdin, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"keyrot {' '.join(args)}: status {p.returncode}: {p.stderr}")
    return p.stdout


# ---------------------------------------------------------------- takes
# (name, rotation channels of the root and of a joint, six channels on every joint, rate, Frame Time as written)
STYLES = {
    "cmu": ("ZYX", "ZYX", False, 120, "0.008333"),
    "bandai_namco": ("ZYX", "ZYX", False, 30, "0.033333"),
    "truebones": ("ZXY", "ZXY", True, 30, "0.0333333"),
}
JOINTS = ["Hips", "Spine", "Neck", "LeftUpLeg", "LeftLeg", "RightUpLeg"]


def channels_of(style, joint):
    root_order, joint_order, six, _, _ = STYLES[style]
    order = root_order if joint == "Hips" else joint_order
    rotations = [f"{a}rotation" for a in order]
    return ["Xposition", "Yposition", "Zposition"] + rotations if joint == "Hips" or six else rotations


def hierarchy(style, nl, tab):
    lines = ["HIERARCHY"]
    parents = {"Spine": "Hips", "Neck": "Spine", "LeftUpLeg": "Hips", "LeftLeg": "LeftUpLeg", "RightUpLeg": "Hips"}

    def emit(joint, depth):
        pad = tab * depth
        lines.append(f"{pad}{'ROOT' if joint == 'Hips' else 'JOINT'} {joint}")
        lines.append(f"{pad}{{")
        lines.append(f"{pad}{tab}OFFSET 0.000000 {1.5 * depth:.6f} 0.000000")
        chans = channels_of(style, joint)
        lines.append(f"{pad}{tab}CHANNELS {len(chans)} {' '.join(chans)}")
        children = [j for j in JOINTS if parents.get(j) == joint]
        for c in children:
            emit(c, depth + 1)
        if not children:
            lines.extend([f"{pad}{tab}End Site", f"{pad}{tab}{{", f"{pad}{tab}{tab}OFFSET 0.000000 1.000000 0.000000",
                          f"{pad}{tab}}}"])
        lines.append(f"{pad}}}")

    emit("Hips", 0)
    return nl.join(lines) + nl


def take(style, rng, frames, decimals=6, glitch=None, unwrapped=False):
    """{(joint, channel): values}: angles sweeping through +-180 (written wrapped into [-180, 180],
    as captures write them, or as they run with `unwrapped`), positions drifting. `glitch`: (joint,
    frame) where the joint is flipped 180 degrees about its first axis for one frame."""
    t = np.arange(frames) / STYLES[style][3]
    values = {}
    for joint in JOINTS:
        for c in channels_of(style, joint):
            if c.endswith("rotation"):
                v = rng.uniform(-180, 180) + rng.uniform(-150, 150) * t + 15 * np.sin(5 * t + rng.uniform(0, 6))
                if c == channels_of(style, joint)[-3]:  # the first axis: through +-180 on the way
                    v = 170 + 40 * t / t[-1]
                if not unwrapped:
                    v = (v + 180) % 360 - 180
            else:
                v = rng.normal() * 10 + 3 * t
            values[(joint, c)] = np.round(v, decimals)
    if glitch:
        joint, frame = glitch
        first = channels_of(style, joint)[-3]
        v = values[(joint, first)]
        v[frame] = np.round((v[frame] + 360) % 360 - 180, decimals)  # half a turn about it, wrapped
    return values


def bvh_text(style, values, frames, decimals=6, nl="\n", tab="\t"):
    lines = [hierarchy(style, nl, tab) + "MOTION", f"Frames: {frames}", f"Frame Time: {STYLES[style][4]}"]
    sep = "\t" if tab == "\t" and nl == "\r\n" else " "
    for f in range(frames):
        lines.append(sep.join(f"{values[(j, c)][f]:.{decimals}f}" for j in JOINTS for c in channels_of(style, j)))
    return nl.join(lines) + nl


def motion_rows(text):
    head, _, rest = text.partition("MOTION")
    lines = [line for line in rest.replace("\r\n", "\n").split("\n") if line.strip()]
    return head, lines[1].split(":", 1)[1].strip(), [[float(x) for x in line.split()] for line in lines[2:]]


def rotation_columns(style):
    """The indices of the rotation channels in a frame line."""
    out, i = [], 0
    for j in JOINTS:
        for c in channels_of(style, j):
            if c.endswith("rotation"):
                out.append(i)
            i += 1
    return out


def check_take(name, style, text, work, glitch=None):
    path = os.path.join(work, name + ".bvh")
    with open(path, "w", newline="") as f:
        f.write(text)
    head, frame_time, rows = motion_rows(text)
    rate = STYLES[style][3]

    for command in (["convert", path], ["resample", path, "--fps", str(rate)]):
        out = os.path.join(work, "out.bvh")
        run(*command, "-o", out)
        with open(out, newline="") as f:
            written = f.read()
        head2, time2, rows2 = motion_rows(written)
        differ = sum(a != b for r0, r1 in zip(rows, rows2) for a, b in zip(r0, r1))
        check(head2 == head and time2 == frame_time and len(rows2) == len(rows) and differ == 0
              and ("\r\n" in written) == ("\r\n" in text),
              f"{name}: {command[0]} to BVH{' at its rate' if len(command) > 2 else ''}: every value as it was "
              f"({differ} not), hierarchy and Frame Time {time2} kept")

    _, _, half = motion_rows(run("resample", path, "--fps", str(rate // 2), "--to", "bvh"))
    differ = sum(a != b for f, row in enumerate(half) for a, b in zip(row, rows[2 * f]))
    check(len(half) == (len(rows) + 1) // 2 and differ == 0,
          f"{name}: at half the rate, each frame the input's at its time ({differ} values not)")

    _, _, double = motion_rows(run("resample", path, "--fps", str(2 * rate), "--to", "bvh"))
    differ = sum(a != b for f, row in enumerate(double[::2]) for a, b in zip(row, rows[f]))
    angles = rotation_columns(style)
    far = []
    for f in range(1, len(double), 2):
        key = f // 2
        if glitch and key in (glitch - 1, glitch):
            continue  # the segments into and out of the flipped frame
        far += [(f, i) for i in angles if abs(double[f][i] - rows[key][i]) > 45]
    # The rotations are keyrot's own frames (CSV quaternions) at the same times.
    quats = list(csv.DictReader(io.StringIO(run("resample", path, "--fps", str(2 * rate), "--to", "csv", "--rep",
                                                "quat"))))
    n = len(double)
    worst = 0.0
    for j_index, joint in enumerate(JOINTS):
        chans = channels_of(style, joint)
        rot = [k for k, c in enumerate(chans) if c.endswith("rotation")]
        start = sum(len(channels_of(style, j)) for j in JOINTS[:j_index])
        order = "".join(chans[k][0] for k in rot)
        for f in range(n):
            r = Rotation.from_euler(order, [double[f][start + k] for k in rot], degrees=True)
            q = quats[j_index * n + f]
            ref = Rotation.from_quat([float(q[c]) for c in ("qx", "qy", "qz", "qw")])
            worst = max(worst, float(np.degrees((r.inv() * ref).magnitude())))
    check(differ == 0 and not far and worst < 1e-9,
          f"{name}: at twice the rate, the input's frames as they were ({differ} values not), between them "
          f"within 45 deg of the frame before ({len(far)} not: {far[:3]}), rotations within {worst:.2g} deg")

    order = STYLES[style][1]
    if STYLES[style][0] == order:  # every joint in one sequence: Euler tables of the take
        for fmt in ("csv", "json", "ndjson"):
            out = run("convert", path, "--rep", "euler", "--out-euler", order, "--to", fmt)
            got = []
            if fmt == "csv":
                got = [[float(r[c]) for c in ("e1", "e2", "e3")] for r in csv.DictReader(io.StringIO(out))]
            elif fmt == "ndjson":
                got = [json.loads(line)["euler"] for line in out.splitlines()]
            else:
                got = [k["euler"] for t in json.loads(out)["tracks"].values() for k in t["keys"]]
            want = []
            for joint in JOINTS:
                rot = [i for i, c in enumerate(channels_of(style, joint)) if c.endswith("rotation")]
                start = sum(len(channels_of(style, j)) for j in JOINTS[:JOINTS.index(joint)])
                want += [[row[start + i] for i in rot] for row in rows]
            check(got == want, f"{name}: convert --rep euler --out-euler {order} --to {fmt}: every key's own angles "
                               f"({sum(a != b for a, b in zip(got, want))} not)")

    if glitch:
        # The picture of the glitched joint: after the segments out of the flip, its curves are back on
        # the take's angles, which are within +-180 (going on past it for less than a frame; not a
        # turn off, as a curve continuous through the flip would be).
        after = [v for t, v in curve_points(run("plot", path, "--track", JOINTS[1], "-o", "-")) if t >= (glitch + 2) / rate]
        check(after and max(abs(v) for v in after) <= 190,
              f"{name}: the picture of the glitched joint is back on the take's angles after the flip "
              f"(largest {max(abs(v) for v in after) if after else None:.4g} deg)")


def curve_points(svg):
    """(time, value) of each point of an SVG picture's curves (one panel), by its axes' tick labels."""
    # (the labels' text stands a little below its grid line: the lines place the values)
    labels = [float(v) for v in re.findall(r'text-anchor="end">(-?[0-9.]+)</text>', svg)]
    lines = [float(y) for y in re.findall(r"M[0-9.]+ ([0-9.]+)H", re.search(r'class="grid" d="([^"]*)"', svg).group(1))]
    ticks_y = list(zip(lines, labels))
    ticks_x = [(float(x), float(t)) for x, t in re.findall(r'<text x="([0-9.]+)" y="[0-9.]+" text-anchor="middle">(-?[0-9.]+)</text>', svg)]
    (y0, v0), (y1, v1) = ticks_y[0], ticks_y[-1]
    (x0, t0), (x1, t1) = ticks_x[0], ticks_x[-1]
    points = []
    for d in re.findall(r'<path d="(M[^"]*)" fill="none" class="c[0-9]" stroke="#[0-9A-F]+" stroke-width="1.75"', svg):
        numbers = [float(n) for n in re.findall(r"-?[0-9.]+", d)]
        if "h" in d:  # the legend's line
            continue
        for x, y in zip(numbers[::2], numbers[1::2]):
            points.append((t0 + (x - x0) * (t1 - t0) / (x1 - x0), v0 + (y - y0) * (v1 - v0) / (y1 - y0)))
    return points


def check_other_representations():
    """Keys of every representation written back in it with the numbers they were given."""
    tables = {
        "quat": "time,qw,qx,qy,qz\n0,0.5,0.5,0.5,0.5\n1,0.9238795325112867,0,0,0.3826834323650898\n2,1,0,0,0\n",
        "axis-angle": "time,ax,ay,az,angle\n0,0,0,1,45\n1,0,0,1,30.5\n2,0.6,0.8,0,17.3\n3,0,1,0,180\n",
        "rotvec": "time,rx,ry,rz\n0,0,0,45\n1,10,20,30\n2,-0.1,0.25,3.5\n",
        "euler": "time,e1,e2,e3\n0,10,20,30\n1,179.669,3.5,-0.1\n2,-180.331,4,0.2\n3,725,-89,0\n",
    }
    for rep, table in tables.items():
        flags = ["--euler", "ZYX"] if rep == "euler" else []
        out = run("convert", "-", "--from", "csv", "--rep", rep, *flags, "--to", "csv", stdin=table)
        check(out == table, f"{rep} keys written back as given: {out!r}")
        for fmt in ("json", "ndjson"):
            chained = run("convert", "-", "--from", fmt, "--rep", rep, *flags, "--to", "csv",
                          stdin=run("convert", "-", "--from", "csv", "--rep", rep, *flags, "--to", fmt, stdin=table))
            check(chained == table, f"{rep} keys through {fmt} and back: as given")
    # radians stay radians, and what is not canonical is not written as given (a 2-long axis, a negative angle)
    out = run("convert", "-", "--from", "csv", "--rep", "euler", "--euler", "xyz", "--radians", "--to", "csv",
              stdin="time,e1,e2,e3\n0,0.1,0.2,4\n")
    check(out == "time,e1_rad,e2_rad,e3_rad\n0,0.1,0.2,4\n", f"radians written back as given: {out!r}")
    out = run("convert", "-", "--from", "csv", "--rep", "axis-angle", "--to", "csv",
              stdin="time,ax,ay,az,angle\n0,0,0,2,45\n1,0,0,1,-30\n")
    check(out == "time,ax,ay,az,angle\n0,0,0,1,45\n1,0,0,-1,30\n", f"axis-angle made canonical where it was not: {out!r}")
    # resample at the keys' times: the keys as given, and between them the method's rotation
    out = run("resample", "-", "--from", "csv", "--rep", "euler", "--euler", "ZYX", "--fps", "2", "--method", "euler",
              "--to", "csv", stdin="time,e1,e2,e3\n0,170,0,0\n1,190,10,0\n")
    check(out == "frame,time,e1,e2,e3\n0,0,170,0,0\n1,0.5,180,5,0\n2,1,190,10,0\n",
          f"--method euler: its own angles, linear in the keys' numbers: {out!r}")


def check_gltf_times(work):
    """glTF stores times as 32-bit floats: frames made at a rate read back at their times to the digit,
    and other times as the shortest decimals of their floats, which go back to the same floats."""
    walk = os.path.join(os.path.dirname(KEYROT), "..", "data", "walk.csv")
    for fps in ("24", "25", "30", "48", "50", "60", "120", "90", "29.97002997002997"):
        table = run("resample", walk, "--fps", fps, "--rep", "quat")
        glb = os.path.join(work, "walk.glb")
        run("convert", "-", "--from", "csv", "-o", glb, stdin=table)
        back = run("convert", glb, "--to", "csv", "--rep", "quat")
        times = [line.split(",")[2] for line in table.splitlines()[1:]]
        times_back = [line.split(",")[1] for line in back.splitlines()[1:]]
        check(times == times_back, f"CSV at {fps} fps -> .glb -> CSV: the same time column "
                                   f"({sum(a != b for a, b in zip(times, times_back))} of {len(times)} differ)")
    # times on no rate: the shortest decimal of each float, which reads back as that float
    keys = "time,qw,qx,qy,qz\n0.12582215666770935,1,0,0,0\n0.3700000047683716,0,0,0,1\n1.0000001,1,0,0,0\n"
    glb = os.path.join(work, "odd.glb")
    run("convert", "-", "--from", "csv", "-o", glb, stdin=keys)
    back = run("convert", glb, "--to", "csv", "--rep", "quat")
    times = [line.split(",")[1] for line in back.splitlines()[1:]]  # (after the node's name, "track")
    floats = [np.float32(float(t)) for t in times]
    check(times == ["0.12582216", "0.37", "1.0000001"] and floats == [np.float32(t) for t in (0.12582215666770935,
                                                                                             0.3700000047683716, 1.0000001)],
          f"times on no rate: the shortest decimals of their floats: {times}")
    again = os.path.join(work, "again.glb")
    run("convert", "-", "--from", "csv", "-o", again, stdin=back)
    check(open(glb, "rb").read() == open(again, "rb").read(), "... which make the same .glb again, to the byte")


def main():
    rng = np.random.default_rng(86)
    with tempfile.TemporaryDirectory() as work:
        for style in STYLES:
            frames = 241 if STYLES[style][3] == 120 else 61
            values = take(style, rng, frames)
            check_take(style, style, bvh_text(style, values, frames), work)
            glitched = take(style, rng, frames, glitch=(JOINTS[1], frames // 2))
            check_take(style + "_glitch", style, bvh_text(style, glitched, frames), work, glitch=frames // 2)
            coarse = take(style, rng, frames, decimals=4)
            check_take(style + "_4_decimals_crlf", style, bvh_text(style, coarse, frames, 4, "\r\n", "\t"), work)
            past = take(style, rng, frames, unwrapped=True)
            check_take(style + "_past_180", style, bvh_text(style, past, frames), work)
        check_other_representations()
        check_gltf_times(work)
    return summary("round_trip_test")


if __name__ == "__main__":
    sys.exit(main())
