#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Smooth motion: --method cubic against scipy, and every method's
angular velocity and acceleration against finite differences of its frames.

- cubic against scipy's RotationSpline (set to converge to 1e-13, as keyrot
  does, not its default 1e-9 in ten rounds) on non-uniform keys, near-180
  degree steps, a long track and the joints of data/capture.bvh: the
  rotations within 1e-6 degrees, the velocities (order 1) and accelerations
  (order 2) within 1e-7 relative;
- for every method (slerp, nlerp, squad, step, euler, cubic, and a glTF
  CUBICSPLINE track), in the body and the world frame: each frame's velocity
  equals the central difference of the rotations either side, and its
  acceleration the central difference of the velocities, away from keys;
- continuity, from the frames alone: the one-sided differences at each key
  agree for cubic (velocity and acceleration), and show the jumps slerp
  (velocity) and squad on uneven keys (acceleration) have;
- the columns read back (CSV wx.., JSON angular_velocity), through convert
  unchanged; compare passes a file with them against one without; pandas
  reads them;
- bad input: one line, exit 2, nothing written.

Usage: motion_test.py KEYROT DATA_DIR. Exit 0 when all pass, 1 otherwise; 77
(skip) without numpy and scipy.
"""
import csv
import io
import json
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
    from scipy.spatial.transform import Rotation as R, RotationSpline
except ImportError:  # pragma: no cover
    print("motion_test: numpy or scipy not installed (apt-get install python3-scipy); skipped")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_files as G  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import check, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])
DATA = os.path.abspath(sys.argv[2])


def run(*args, stdin=None):
    return subprocess.run([KEYROT, *args], input=stdin, capture_output=True, text=True)


def csv_text(times, quats, track=None):
    """A CSV of quaternion keys (w, x, y, z), written with repr: the exact doubles."""
    lines = ["time,qw,qx,qy,qz" if track is None else "track,time,qw,qx,qy,qz"]
    for t, q in zip(times, quats):
        row = ",".join(repr(float(v)) for v in (t, *q))
        lines.append(row if track is None else f"{track},{row}")
    return "\n".join(lines) + "\n"


def table(text):
    """keyrot's CSV output as a header (its names without a "_rad" unit) and a float array."""
    rows = text.splitlines()
    if rows[0].startswith("track,"):  # (one track here: its name dropped)
        rows = [r.split(",", 1)[1] for r in rows]
    header = [name.removesuffix("_rad") for name in rows[0].split(",")]
    return header, np.array([[float(c) for c in r.split(",")] for r in rows[1:]])


def resample(text, *flags):
    """Frames with quaternions, radians: (times, xyzw quats, velocities, accelerations)."""
    r = run("resample", "-", "--from", "csv", "--rep", "quat", "--out-radians", "--velocity", "--acceleration", *flags,
            stdin=text)
    if r.returncode != 0:
        raise RuntimeError(r.stderr)
    header, a = table(r.stdout)
    col = {name: i for i, name in enumerate(header)}
    q = a[:, [col["qx"], col["qy"], col["qz"], col["qw"]]]
    w = a[:, [col["wx"], col["wy"], col["wz"]]]
    dw = a[:, [col["dwx"], col["dwy"], col["dwz"]]]
    return a[:, col["time"]], q, w, dw


def random_rotations(rng, n, step_deg):
    """n rotations, each a random turn of up to step_deg from the one before."""
    out = [R.random(random_state=rng)]
    for _ in range(n - 1):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        out.append(out[-1] * R.from_rotvec(axis * np.radians(rng.uniform(0.3, 1) * step_deg)))
    return R.concatenate(out)


def wxyz(rotations):
    q = rotations.as_quat()
    return q[:, [3, 0, 1, 2]]


# --- cubic against scipy ---------------------------------------------------------------

class AsShipped(RotationSpline):  # scipy's own stopping rule
    MAX_ITER = 10
    TOL = 1e-9


RotationSpline.MAX_ITER = 500  # converged as tightly as keyrot's
RotationSpline.TOL = 1e-13


def against_scipy(name, times, rotations, fps):
    t, q, w, dw = resample(csv_text(times, wxyz(rotations)), "--method", "cubic", "--fps", str(fps))
    spline = RotationSpline(times, rotations)
    angle = np.degrees((R.from_quat(q).inv() * spline(t)).magnitude()).max()
    check(angle <= 1e-9, f"{name}: cubic is {angle:.3g} deg from scipy's RotationSpline")
    # As shipped, scipy stops after ten rounds: on large steps short of its own bound, and as far
    # from the converged curve as from keyrot's.
    as_shipped = AsShipped(times, rotations)(t)
    shipped = np.degrees((R.from_quat(q).inv() * as_shipped).magnitude()).max()
    unconverged = np.degrees((spline(t).inv() * as_shipped).magnitude()).max()
    check(shipped <= 1e-6 + unconverged, f"{name}: cubic is {shipped:.3g} deg from scipy's RotationSpline as shipped")
    errors = []
    for order, mine in ((1, w), (2, dw)):
        ref = spline(t, order)
        scale = np.maximum(1, np.linalg.norm(ref, axis=1))
        errors.append((np.linalg.norm(mine - ref, axis=1) / scale).max())
        check(errors[-1] <= 1e-7, f"{name}: cubic's derivative {order} is {errors[-1]:.3g} (relative) from scipy's")
    print(f"{name}: {angle:.2g} deg ({shipped:.2g} from scipy as shipped, itself {unconverged:.2g} from converged), velocity {errors[0]:.2g}, acceleration {errors[1]:.2g} from scipy")


rng = np.random.default_rng(46)
times = np.cumsum(rng.uniform(0.05, 0.5, 25))
against_scipy("uneven keys", times, random_rotations(rng, 25, 120), 30)
times = np.cumsum(rng.uniform(0.1, 0.3, 12))
against_scipy("near-180-degree steps", times, random_rotations(rng, 12, 179), 60)
# longer than a stretch keyrot solves at once (4,096 keys and 256 of look-ahead): the stretches' joins
times = np.arange(12000) / 120 + rng.uniform(0, 1e-3, 12000)
against_scipy("a long track (three stretches)", times, random_rotations(rng, 12000, 8), 24)
times = np.cumsum(rng.uniform(0.01, 0.5, 9000))
against_scipy("a long track of large uneven steps", times, random_rotations(rng, 9000, 60), 2)
# the joints of a captured take
bvh = run("convert", os.path.join(DATA, "capture.bvh"), "--rep", "quat", "--to", "csv")
check(bvh.returncode == 0, f"convert capture.bvh: {bvh.stderr}")
rows = [r.split(",") for r in bvh.stdout.splitlines()]
check(rows[0][:7] == ["track", "frame", "time", "qw", "qx", "qy", "qz"], f"capture.bvh as CSV: header {rows[0]}")
by_track = {}
for cells in rows[1:]:
    by_track.setdefault(cells[0], []).append([float(c) for c in cells[1:7]])
for track, keys in list(by_track.items())[:8]:
    keys = np.array(keys)
    check(np.array_equal(keys[:, 1], keys[:, 0] / 120), f"capture.bvh joint {track}: frames at 120 fps and their times")
    against_scipy(f"capture.bvh joint {track}", keys[:, 1], R.from_quat(keys[:, [3, 4, 5, 2]]), 25)

# glTF and BVH in and out: cubic's frames, LINEAR samplers of them (to float32), BVH's Euler frames
with tempfile.TemporaryDirectory() as tmp:
    for name, out in (("arm_wave.gltf", "out.glb"), ("capture.bvh", "out.bvh")):
        path = os.path.join(tmp, out)
        r = run("resample", os.path.join(DATA, name), "--method", "cubic", "--fps", "30", "-o", path)
        check(r.returncode == 0, f"resample {name} --method cubic -o {out}: {r.stderr}")
        direct = run("resample", os.path.join(DATA, name), "--method", "cubic", "--fps", "30", "--rep", "quat", "--to", "csv")
        back = run("convert", path, "--rep", "quat", "--to", "csv")
        quats = []
        for text_ in (direct.stdout, back.stdout):
            lines = [line.split(",") for line in text_.splitlines()]
            at = [lines[0].index(c) for c in ("qx", "qy", "qz", "qw")]
            quats.append(np.array([[float(row[i]) for i in at] for row in lines[1:]]))
        qd, qb = quats
        angle = np.degrees((R.from_quat(qd).inv() * R.from_quat(qb)).magnitude()).max() if len(qd) == len(qb) else 1e9
        check(angle < 1e-3, f"{name} by cubic into {out} and back: {angle:.3g} deg from the CSV frames")

# two keys: the constant-rate slerp
t, q, w, dw = resample(csv_text([0, 2], [[1, 0, 0, 0], [np.cos(0.5), 0, 0, np.sin(0.5)]]), "--method", "cubic", "--fps", "4")
check(np.allclose(w, [[0, 0, 0.5]] * len(t), atol=1e-15) and np.allclose(dw, 0, atol=1e-15),
      f"two keys: cubic is not slerp's constant 0.5 rad/s about z: {w[:2]} {dw[:2]}")


# --- every method's derivatives against finite differences of its frames ---------------

FPS = 4000
DELTA = 1 / FPS


def body_rate(qa, qb, seconds):
    """The body-frame rotation vector per second from qa to qb."""
    return (R.from_quat(qa).inv() * R.from_quat(qb)).as_rotvec() / seconds


def derivative_checks(name, text, key_times, flags):
    for frame in ("body", "world"):
        t, q, w, dw = resample(text, "--fps", str(FPS), "--velocity-frame", frame, *flags)
        away = np.array([np.min(np.abs(key_times - x)) > 2.5 * DELTA for x in t])
        inner = np.where(away[1:-1])[0] + 1
        rot = R.from_quat(q)
        if frame == "body":
            fd = (rot[inner - 1].inv() * rot[inner + 1]).as_rotvec() / (2 * DELTA)
        else:
            fd = (rot[inner + 1] * rot[inner - 1].inv()).as_rotvec() / (2 * DELTA)
        scale = 1 + np.abs(w[inner]).max()
        err = np.abs(fd - w[inner]).max() / scale
        check(err < 1e-5, f"{name} ({frame} frame): velocity is {err:.3g} from the frames' differences")
        fd2 = (w[inner + 1] - w[inner - 1]) / (2 * DELTA)
        scale2 = 1 + np.abs(dw[inner]).max()
        err2 = np.abs(fd2 - dw[inner]).max() / scale2
        check(err2 < 1e-5, f"{name} ({frame} frame): acceleration is {err2:.3g} from the velocities' differences")


rng = np.random.default_rng(7)
key_times = np.round(np.cumsum(rng.uniform(0.1, 0.4, 7)) * FPS) / FPS  # on the grid
rotations = random_rotations(rng, 7, 100)
text = csv_text(key_times, wxyz(rotations))
for method in ("slerp", "nlerp", "squad", "step", "cubic"):
    derivative_checks(method, text, key_times, ["--method", method])
euler = np.degrees(rotations.as_euler("ZYX"))
euler_text = "time,e1,e2,e3\n" + "".join(f"{t!r},{a!r},{b!r},{c!r}\n" for t, (a, b, c) in zip(key_times, euler))
derivative_checks("euler ZYX", euler_text, key_times, ["--method", "euler", "--euler", "ZYX"])
euler_x = np.degrees(rotations.as_euler("xyz"))
euler_text = "time,e1,e2,e3\n" + "".join(f"{t!r},{a!r},{b!r},{c!r}\n" for t, (a, b, c) in zip(key_times, euler_x))
derivative_checks("euler xyz", euler_text, key_times, ["--method", "euler", "--euler", "xyz"])

# a glTF CUBICSPLINE rotation track
with tempfile.TemporaryDirectory() as tmp:
    b = G.Builder()
    b.json["nodes"].append({"name": "spun"})
    b.json["scenes"][0]["nodes"].append(0)
    values = np.zeros((len(key_times), 3, 4))
    values[:, 1] = rotations.as_quat()
    values[:, 0] = rng.normal(scale=0.5, size=(len(key_times), 4))
    values[:, 2] = rng.normal(scale=0.5, size=(len(key_times), 4))
    b.animation([{"node": 0, "path": "rotation", "times": key_times, "values": values, "interpolation": "CUBICSPLINE"}])
    path = os.path.join(tmp, "spline.gltf")
    b.write(path, "datauri")
    for frame in ("body", "world"):
        r = run("resample", path, "--fps", str(FPS), "--rep", "quat", "--out-radians", "--velocity", "--acceleration",
                "--velocity-frame", frame, "--to", "csv")
        check(r.returncode == 0, f"CUBICSPLINE glTF --velocity: {r.stderr}")
        header, a = table(r.stdout)
        col = {n: i for i, n in enumerate(header)}
        stored = np.array(G.Builder().decoded(key_times))
        t = a[:, col["time"]]
        q = a[:, [col["qx"], col["qy"], col["qz"], col["qw"]]]
        w = a[:, [col["wx"], col["wy"], col["wz"]]]
        away = np.array([np.min(np.abs(stored - x)) > 2.5 * DELTA for x in t])
        inner = np.where(away[1:-1])[0] + 1
        rot = R.from_quat(q)
        fd = ((rot[inner - 1].inv() * rot[inner + 1]) if frame == "body" else (rot[inner + 1] * rot[inner - 1].inv())).as_rotvec() / (2 * DELTA)
        err = np.abs(fd - w[inner]).max() / (1 + np.abs(w[inner]).max())
        check(err < 1e-5, f"CUBICSPLINE ({frame} frame): velocity is {err:.3g} from the frames' differences")


# --- continuity at the keys, from the frames alone ----------------------------------------

def one_sided_jumps(method, key_times_, text_):
    """At each inner key: the largest change of velocity (from the rotations) and of
    acceleration (from the velocities) across it, one-sided differences either side
    (1.5 frames from the key, so a smooth velocity changes by 3 frames' acceleration)."""
    t, q, w, dw = resample(text_, "--method", method, "--fps", str(FPS))
    rot = R.from_quat(q)
    jumps_w, jumps_a = [], []
    for key in key_times_[1:-1]:
        k = int(np.argmin(np.abs(t - key)))
        left = (rot[k - 2].inv() * rot[k - 1]).as_rotvec() / DELTA
        right = (rot[k + 1].inv() * rot[k + 2]).as_rotvec() / DELTA
        jumps_w.append(np.linalg.norm(right - left - 3 * DELTA * dw[k]))
        jumps_a.append(np.linalg.norm((w[k + 2] - w[k + 1]) / DELTA - (w[k - 1] - w[k - 2]) / DELTA))
    return max(jumps_w), max(jumps_a)


jw, ja = one_sided_jumps("cubic", key_times, text)
check(jw < 2e-3, f"cubic: the velocity jumps by {jw:.3g} rad/s at a key")
jw_slerp, _ = one_sided_jumps("slerp", key_times, text)
check(jw_slerp > 1000 * jw, f"slerp's velocity jump {jw_slerp:.3g} is not far above cubic's {jw:.3g}: the check sees nothing")
_, ja_squad = one_sided_jumps("squad", key_times, text)
print(f"continuity at the keys: velocity jumps {jw:.3g} (slerp {jw_slerp:.3g}), acceleration {ja:.3g} (squad {ja_squad:.3g})")
check(ja < ja_squad / 20, f"cubic: the acceleration jumps by {ja:.3g} at a key (squad's: {ja_squad:.3g})")


# --- the columns read back ----------------------------------------------------------------

with tempfile.TemporaryDirectory() as tmp:
    src = os.path.join(tmp, "keys.csv")
    with open(src, "w") as f:
        f.write(text)
    made = {}
    for ext in ("csv", "json", "ndjson"):
        out = os.path.join(tmp, f"rates.{ext}")
        r = run("resample", src, "--method", "cubic", "--velocity", "--acceleration", "-o", out)
        check(r.returncode == 0 and r.stderr == "", f"resample --velocity -o {ext}: {r.stderr}")
        made[ext] = out
        back = run("convert", out, "--rep", "quat", "--to", "csv")
        check(back.returncode == 0 and back.stderr == "", f"convert of the {ext} with velocities: {back.stderr}")
        header, a = table(back.stdout)
        check(header[-6:] == ["wx", "wy", "wz", "dwx", "dwy", "dwz"], f"{ext} read back: columns {header}")
        made[ext + "_back"] = a[:, -6:]
    check(np.array_equal(made["csv_back"], made["json_back"]) and np.array_equal(made["csv_back"], made["ndjson_back"]),
          "the velocities read back differ between CSV, JSON and NDJSON")
    import pandas  # noqa: E402  (Debian's python3-pandas, as readers_test)
    frame = pandas.read_csv(made["csv"])
    check(list(frame.columns[-6:]) == ["wx", "wy", "wz", "dwx", "dwy", "dwz"] and len(frame) > 10,
          f"pandas reads the velocity columns: {list(frame.columns)}")
    first = json.loads(open(made["ndjson"]).readline())
    check(len(first["angular_velocity"]) == 3 and len(first["angular_acceleration"]) == 3,
          f"NDJSON row without its velocity: {first}")
    # degrees per second by default, radians with --out-radians (and stated, so it reads back)
    rad = run("resample", src, "--method", "cubic", "--velocity", "--rep", "quat", "--out-radians")
    deg = run("resample", src, "--method", "cubic", "--velocity", "--rep", "quat")
    _, a_rad = table(rad.stdout)
    _, a_deg = table(deg.stdout)
    check(np.allclose(np.degrees(a_rad[:, -3:]), a_deg[:, -3:], rtol=1e-14, atol=1e-12), "velocity: radians are not degrees")
    check(rad.stdout.splitlines()[0].endswith(",wx_rad,wy_rad,wz_rad"), f"radians not in the names: {rad.stdout[:60]!r}")
    back = run("convert", "-", "--from", "csv", "--rep", "quat", stdin=rad.stdout)
    _, a_back = table(back.stdout)
    check(np.allclose(a_back[:, -3:], a_deg[:, -3:], rtol=1e-14, atol=1e-12), "radians read back are not the degrees")
    # compare ignores them
    plain = os.path.join(tmp, "plain.csv")
    run("resample", src, "--method", "cubic", "-o", plain)
    r = run("compare", plain, made["csv"])
    check(r.returncode == 0, f"compare of frames with and without velocities: {r.stdout} {r.stderr}")
    # ... unless asked: the velocities then count, and their differences are reported
    r = run("compare", made["csv"], made["json"], "--tol-velocity", "1e-9", "--tol-acceleration", "1e-9")
    check(r.returncode == 0, f"compare --tol-velocity of the same frames: {r.stdout} {r.stderr}")
    other = os.path.join(tmp, "nlerp.csv")
    run("resample", src, "--method", "nlerp", "--velocity", "--acceleration", "-o", other)
    r = run("compare", made["csv"], other, "--tol", "360", "--tol-velocity", "0.5", "--report", "csv")
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    check(r.returncode == 1 and "velocity_difference" in rows[0] and "acceleration_difference" not in rows[0]
          and any("angular velocity differs by" in row["reason"] for row in rows),
          f"compare --tol-velocity of cubic against nlerp: {r.stdout[:300]} {r.stderr}")
    largest = max(float(row["velocity_difference"]) for row in rows)
    _, a_cubic = table(run("convert", made["csv"], "--rep", "quat", "--to", "csv").stdout)
    _, a_nlerp = table(run("convert", other, "--rep", "quat", "--to", "csv").stdout)
    expected_largest = np.linalg.norm(a_cubic[:, -6:-3] - a_nlerp[:, -6:-3], axis=1).max()
    check(abs(largest - expected_largest) <= 1e-9 * expected_largest,
          f"velocity_difference {largest} against numpy's {expected_largest}")
    r = run("compare", made["csv"], plain, "--tol-velocity", "1")
    check(r.returncode == 1 and "angular velocity missing from the answer" in r.stderr,
          f"compare --tol-velocity against frames without: {r.stderr}")
    # resample of frames with velocities says it does not keep them
    r = run("resample", made["csv"], "--fps", "10")
    check(r.returncode == 0 and "ignoring the angular velocity" in r.stderr and "wx" not in r.stdout.splitlines()[0],
          f"resample of a file with velocities: {r.stderr}")


# --- info: the speed, and the spikes a captured take's glitches make ---------------------------

def info_json(text_, *flags):
    r = run("info", "-", "--from", "csv", "--to", "json", *flags, stdin=text_)
    check(r.returncode == 0, f"info {flags}: {r.stderr}")
    return json.loads(r.stdout)["tracks"][0]["speed"], r.stderr


# a take at 120 Hz turning at 90 deg/s about z, with one frame flipped 180 degrees about x
frames = np.arange(600)
steady = R.from_rotvec(np.outer(np.radians(90) * frames / 120, [0, 0, 1]))
take = "frame,qw,qx,qy,qz\n" + "".join(f"{f},{q[0]!r},{q[1]!r},{q[2]!r},{q[3]!r}\n" for f, q in zip(frames, wxyz(steady)))
speed, err = info_json(take, "--key-fps", "120")
check(abs(speed["fastest"]["value"] - 90) < 1e-9 and abs(speed["mean"] - 90) < 1e-9 and speed["spikes"]["count"] == 0
      and err == "", f"info of a steady 90 deg/s turn: {speed} {err}")
glitched = R.concatenate([steady[:300], steady[300] * R.from_euler("x", 180, degrees=True), steady[301:]])
take = "frame,qw,qx,qy,qz\n" + "".join(f"{f},{q[0]!r},{q[1]!r},{q[2]!r},{q[3]!r}\n" for f, q in zip(frames, wxyz(glitched)))
speed, err = info_json(take, "--key-fps", "120")
spikes = speed["spikes"]
check(spikes["count"] == 2 and [(p["frame"], p["frame_to"]) for p in spikes["first"]] == [(299, 300), (300, 301)],
      f"info of a take with a flipped frame: spikes {spikes}")
warned = err.strip().splitlines()
check(len(warned) == 2 and all("frames 299 to 300" in warned[0] and "a flip" in w for w in warned[:1])
      and "frames 300 to 301" in warned[1], f"info's spike warnings: {err}")
text_out = run("info", "-", "--from", "csv", "--key-fps", "120", stdin=take).stdout
check("speed spikes (over 10 times the speed around, turning over 1 deg): 2.491667 s (frames 299 to 300)" in text_out,
      f"info's text: {text_out}")
# under cubic: the largest speed of scipy's spline at the five points of each segment info looks at
rng = np.random.default_rng(3)
key_t = np.cumsum(rng.uniform(0.1, 0.5, 30))
rot = random_rotations(rng, 30, 90)
speed, err = info_json(csv_text(key_t, wxyz(rot)), "--method", "cubic")
points = np.concatenate([key_t[i] + np.array([0, 0.25, 0.5, 0.75, 1]) * (key_t[i + 1] - key_t[i]) for i in range(29)])
spline = RotationSpline(key_t, rot)
fastest = np.degrees(np.linalg.norm(spline(points, 1), axis=1)).max()
accel = np.degrees(np.linalg.norm(spline(points, 2), axis=1)).max()
check(abs(speed["fastest"]["value"] - fastest) < 1e-9 * fastest and speed["method"] == "cubic",
      f"info --method cubic: fastest {speed['fastest']['value']} against scipy's {fastest}")
check(abs(speed["most_accelerated"]["value"] - accel) < 1e-7 * accel,
      f"info --method cubic: acceleration {speed['most_accelerated']['value']} against scipy's {accel}")


# --- bad input ------------------------------------------------------------------------------

def bad(args, stdin, expect, target=None):
    r = run(*args, stdin=stdin)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and expect in r.stderr and r.stdout == "",
          f"{' '.join(args)}: status {r.returncode}, {r.stderr!r}")
    if target:
        check(not os.path.exists(target), f"{' '.join(args)} wrote {target}")


with tempfile.TemporaryDirectory() as tmp:
    one = "time,qw,qx,qy,qz\n0,1,0,0,0\n"
    bad(["resample", "-", "--from", "csv", "--method", "cubic"], one, "one key: --method cubic needs two keys")
    bad(["resample", "-", "--from", "csv", "--method", "cubic"], "track,time,qw,qx,qy,qz\nhip,0,1,0,0,0\nhip,1,0,1,0,0\nknee,0,1,0,0,0\n",
        "track 'knee' has one key")
    bad(["convert", "-", "--from", "csv", "--velocity"], text, "--velocity")
    out = os.path.join(tmp, "x.glb")
    bad(["resample", "-", "--from", "csv", "--velocity", "-o", out], text, "glTF has no place", out)
    bad(["resample", "-", "--from", "csv", "--velocity", "--to", "bvh"], text, "BVH has no place")
    bad(["resample", "-", "--from", "csv", "--method", "cubic", "--path", "direct"], text, "expected --path shortest")
    bad(["resample", "-", "--from", "csv", "--velocity-frame", "space"], text, "--velocity-frame")
    bad(["reduce", "-", "--from", "csv", "--method", "cubic", "--tol", "1"], text, "cubic")
    # Steps of 150 to 180 degrees, keys 2 ms to 7 s apart: the spline's equations do not settle
    # (nor do scipy's); after a good track, to standard output and to a file.
    unsettled = "track,time,qw,qx,qy,qz\ngood,0,1,0,0,0\ngood,1,0,1,0,0\n" + "".join("bad," + row + "\n" for row in """
0.0,-0.03725680385049308,-0.016142823473472567,-0.7670069026502585,0.640352833291153
0.1696819007223831,-0.3915886974804691,0.748163716147109,-0.4654255067662194,-0.2651196776889747
0.2687527324945638,0.139336768274835,0.31624828641619196,0.45671216572640816,-0.8197476953447572
0.3186244515636646,-0.5367273188013024,0.7411075418488718,-0.393762299405335,-0.08737647414556692
0.5194507767251229,0.7058727194787591,0.6731640891036009,-0.21627221390171758,-0.0426631284721366
7.875583925852533,-0.4557751201400748,0.4372730766541493,-0.6857814760188038,-0.36161452327607885
7.943554077980701,-0.9488208139055722,-0.17886686066620583,0.2584402940175832,-0.03089212979204932
10.181686029190212,-0.13959046382299897,-0.8007841782936335,-0.1696784864555375,0.5571969251875214
10.183358998061308,0.8393502199129528,-0.01903165994643263,-0.4677959729509751,0.27621718256222155
10.218220735599996,0.535293951965064,0.25812262248467505,0.7992983447836031,-0.08919222374988857
10.39279723249915,-0.05242941128239948,-0.6259209249278482,0.5693236865538349,0.5304193553206735
10.695685340661164,0.8425985981524549,0.142913026408512,0.519233134336867,-0.000649215673490605
10.705687029974,-0.18942752171972768,0.2160129522369807,0.4775265459222694,-0.8303156125356989
10.74523862970376,-0.9273621427889011,0.3087768694054056,-0.194798451437994,0.0819137617225245
16.883207407232696,-0.3027350585134129,-0.38089919688934276,0.7617403107538675,0.4278071821843757
17.277122858297332,0.4448565475272554,0.22715184991431844,0.7471999441982641,-0.43840270595965175
17.495831021714228,0.11026960200038378,0.8041399814884648,-0.384667829017964,-0.4395795336057119
17.49765573587355,0.5393510449618131,-0.30260813916082346,-0.7808769671430702,-0.08809044555264975
17.49927271729697,0.3894708190760304,-0.7870718382231581,0.36623563840027734,-0.3077366727086755
17.50628071242646,-0.3408363121580112,-0.5237826430557112,-0.7335784702796887,-0.26710480918585544
17.509839410173598,-0.3255204101724397,-0.8161077150859574,0.39547973091830657,0.2675825898131799
""".split())
    bad(["resample", "-", "--from", "csv", "--method", "cubic"], unsettled, "<stdin>:4: track 'bad': the cubic spline's equations do not settle")
    out = os.path.join(tmp, "x.csv")
    bad(["resample", "-", "--from", "csv", "--method", "cubic", "-o", out], unsettled, "do not settle", out)

sys.exit(summary("motion_test"))
