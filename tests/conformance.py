#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Conformance of keyrot against an independent implementation of the spec.

Random tracks are written in every input representation and format, run
through `keyrot resample` / `keyrot convert` with every method, path, output
representation and format, and each output frame's rotation matrix is
compared with a reference built from scipy's Rotation (and, for what scipy
lacks, the spec's formulas written out in numpy) to 1e-9 per entry.

Usage: conformance.py KEYROT [--cases N] [--seed S]
Exit 0 when every case matches, 1 otherwise; 77 (skip) without scipy.
"""
import argparse
import bisect
import csv
import io
import json
import math
import subprocess
import sys

try:
    import numpy as np
    from scipy.spatial.transform import Rotation, Slerp
except ImportError:  # pragma: no cover
    print("conformance: numpy/scipy not installed (apt-get install python3-scipy); skipped")
    sys.exit(77)

TOL = 1e-9
SEQS = ["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ"]
SEQS += [s.lower() for s in SEQS]
IN_REPS = ["quat", "axis-angle", "rotvec", "euler", "matrix", "matrix4"]
OUT_REPS = ["axis-angle", "quat", "rotvec", "euler", "matrix", "matrix4"]
METHODS = ["slerp", "nlerp", "squad", "step", "euler"]


# ---------------------------------------------------------------- reference
def quat_wxyz(r):
    x, y, z, w = r.as_quat()
    return np.array([w, x, y, z])


def xyzw(q):
    """The order scipy's from_quat takes, of a wxyz quaternion or array of them."""
    return np.asarray(q)[..., [1, 2, 3, 0]]


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array([w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
                     w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
                     w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                     w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2])


def qconj(q):
    return np.array([q[0], -q[1], -q[2], -q[3]])


def qlog(q):
    v = q[1:]
    s = np.linalg.norm(v)
    if s == 0:
        return np.array([math.atan2(0, q[0]), 0, 0]) if q[0] < 0 else np.zeros(3)
    return math.atan2(s, q[0]) * v / s


def qexp(v):
    a = np.linalg.norm(v)
    if a == 0:
        return np.array([1.0, 0, 0, 0])
    return np.concatenate([[math.cos(a)], math.sin(a) * v / a])


def slerp_power(a, b, h):
    """The power form a (a^-1 b)^h (Shoemake 1985), no sign flip. (The sine form
    loses half its digits through acos when the keys nearly coincide.)"""
    return qmul(a, qexp(h * qlog(qmul(qconj(a), b))))


def to_matrix_wxyz(q):
    w, x, y, z = q
    return Rotation.from_quat([x, y, z, w]).as_matrix()


def reference_frames(keys, method, path, fps, euler_seq):
    """keys: list of dicts with time, q (wxyz as keyrot reads it), euler (radians, or None), t (translation or None)."""
    times = [k["time"] for k in keys]
    qs = [k["q"] / np.linalg.norm(k["q"]) for k in keys]
    if path == "shortest":
        for i in range(1, len(qs)):
            if np.dot(qs[i - 1], qs[i]) < 0:
                qs[i] = -qs[i]
    first = math.ceil(times[0] * fps - 1e-9)
    last = math.floor(times[-1] * fps + 1e-9)
    s = list(qs)
    if method == "squad":
        for i in range(1, len(qs) - 1):
            inv = qconj(qs[i])
            s[i] = qmul(qs[i], qexp(-(qlog(qmul(inv, qs[i + 1])) + qlog(qmul(inv, qs[i - 1]))) / 4))
    eul = None
    if method == "euler":
        eul = [k["euler"] if k["euler"] is not None else
               Rotation.from_quat(xyzw(k["q"])).as_euler(euler_seq) for k in keys]
    scipy_slerp = Slerp(times, Rotation.from_quat(xyzw(qs))) if len(keys) > 1 else None
    tkeys = [(k["time"], np.array(k["t"])) for k in keys if k["t"] is not None]
    out = []
    for f in range(first, last + 1):
        t = f / fps
        i = bisect.bisect_right(times, t + 1e-9 / fps) - 1
        if abs(t - times[i]) <= 1e-9 / fps or i == len(times) - 1:
            m = to_matrix_wxyz(qs[i])
        else:
            h = (t - times[i]) / (times[i + 1] - times[i])
            if method == "slerp" and path == "shortest":
                m = scipy_slerp([t]).as_matrix()[0]
            elif method == "slerp":
                m = to_matrix_wxyz(slerp_power(qs[i], qs[i + 1], h))
            elif method == "nlerp":
                m = to_matrix_wxyz((1 - h) * qs[i] + h * qs[i + 1])
            elif method == "squad":
                a = slerp_power(qs[i], qs[i + 1], h)
                b = slerp_power(s[i], s[i + 1], h)
                m = to_matrix_wxyz(slerp_power(a, b, 2 * h * (1 - h)))
            elif method == "step":
                m = to_matrix_wxyz(qs[i])
            else:
                e = (1 - h) * np.array(eul[i]) + h * np.array(eul[i + 1])
                m = Rotation.from_euler(euler_seq, e).as_matrix()
        tr = None
        if tkeys:
            ts = [a for a, _ in tkeys]
            if t <= ts[0]:
                tr = tkeys[0][1]
            elif t >= ts[-1]:
                tr = tkeys[-1][1]
            else:
                j = bisect.bisect_right(ts, t) - 1
                if method == "step":
                    tr = tkeys[j][1]
                else:
                    h = (t - ts[j]) / (ts[j + 1] - ts[j])
                    tr = (1 - h) * tkeys[j][1] + h * tkeys[j + 1][1]
        out.append((f, t, m, tr))
    return out


# ---------------------------------------------------------------- inputs
def random_keys(rng, n, with_translation, spacing=(0.05, 0.6)):
    times = np.cumsum(rng.uniform(*spacing, n))
    times -= times[0] - rng.choice([0.0, 0.25, rng.uniform(0, 1)])
    keys = []
    for i, t in enumerate(times):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        edge = rng.random()
        if keys and edge < 0.1:  # nearly the previous key
            q = quat_wxyz(Rotation.from_quat(xyzw(keys[-1]["q"])) * Rotation.from_rotvec(rng.normal(size=3) * 1e-7))
        elif keys and edge < 0.2:  # nearly 180 degrees from the previous key
            axis = rng.normal(size=3)
            q = quat_wxyz(Rotation.from_quat(xyzw(keys[-1]["q"])) *
                          Rotation.from_rotvec(axis / np.linalg.norm(axis) * (math.pi - rng.choice([1e-3, 1e-6]))))
        keys.append({"time": float(t), "q": q, "t": list(rng.uniform(-2, 2, 3)) if with_translation and rng.random() < 0.7 else None})
    return keys


def encode(keys, rep, seq, degrees, rng):
    """Values of each key in representation `rep`; updates k['q'] / k['euler'] to what keyrot will read."""
    unit = (180 / math.pi) if degrees else 1.0
    rows = []
    for k in keys:
        r = Rotation.from_quat(xyzw(k["q"]))
        k["euler"] = None
        if rep == "quat":
            scale = rng.choice([1.0, 1.0, 1.0005])  # some within the normalisation tolerance
            vals = list(k["q"] * scale)
        elif rep == "axis-angle":
            rv = r.as_rotvec()
            ang = np.linalg.norm(rv)
            axis = rv / ang * rng.uniform(0.5, 3)
            vals = list(axis) + [ang * unit]
            k["q"] = quat_wxyz(Rotation.from_rotvec(rv))
        elif rep == "rotvec":
            rv = r.as_rotvec()
            vals = list(rv * unit)
            k["q"] = quat_wxyz(Rotation.from_rotvec(rv))
        elif rep == "euler":
            e = r.as_euler(seq)
            if rng.random() < 0.1:  # exactly at gimbal lock, as keyed by hand
                e[1] = (0.0 if rng.random() < 0.5 else math.pi) if seq[0].lower() == seq[2].lower() else math.copysign(math.pi / 2, e[1])
            if rng.random() < 0.3:
                e = e + rng.choice([-2, 2]) * math.pi * np.array([1, 0, 0])  # unwrapped angles, as F-curves have
            vals = list(e * unit)
            k["euler"] = e
            k["q"] = quat_wxyz(Rotation.from_euler(seq, e))
        else:
            m = r.as_matrix()
            if rep == "matrix":
                vals = list(m.flatten())
            else:
                t = k["t"] if k["t"] is not None else [0.0, 0.0, 0.0]
                k["t"] = t
                vals = list(np.hstack([m, np.array(t)[:, None]]).flatten()) + [0, 0, 0, 1]
            k["q"] = quat_wxyz(Rotation.from_matrix(m))
        rows.append([float(v) for v in vals])
    return rows


CSV_COLS = {"quat": ["qw", "qx", "qy", "qz"], "axis-angle": ["ax", "ay", "az", "angle"], "rotvec": ["rx", "ry", "rz"],
            "euler": ["e1", "e2", "e3"], "matrix": ["m%d%d" % (i, j) for i in range(3) for j in range(3)],
            "matrix4": ["m%d%d" % (i, j) for i in range(4) for j in range(4)]}


def json_rotation(rep, vals, order):
    if rep == "quat":
        return {"quat": vals if order == "wxyz" else vals[1:] + vals[:1]}
    if rep == "axis-angle":
        return {"axis": vals[:3], "angle": vals[3]}
    if rep == "rotvec":
        return {"rotvec": vals}
    if rep == "euler":
        return {"euler": vals}
    n = 3 if rep == "matrix" else 4
    return {"matrix": [vals[i * n:(i + 1) * n] for i in range(n)]}


def key_rows(tracks, interleave):
    """(name, key, values) of every key: track after track, or (interleave)
    key i of each track in turn, as some motion-capture exports write them.
    Either way the tracks first appear in their order."""
    per_track = [[(name, k, vals) for k, vals in zip(keys, rows)] for name, (keys, rows) in tracks.items()]
    if not interleave:
        return [row for rows in per_track for row in rows]
    return [rows[i] for i in range(max(map(len, per_track))) for rows in per_track if i < len(rows)]


def write_input(tracks, rep, fmt, seq, degrees, order, by_frame, key_fps, interleave):
    """tracks: {name: (keys, rows)}; returns text. `interleave`: CSV and
    NDJSON keys in turns of the tracks (see key_rows)."""
    named = len(tracks) > 1
    def when(k):
        return {"frame": round(k["time"] * key_fps)} if by_frame else {"time": k["time"]}
    if fmt == "csv":
        out = io.StringIO()
        cols = (["track"] if named else []) + ["frame" if by_frame else "time"] + CSV_COLS[rep]
        has_t = rep != "matrix4" and any(k["t"] is not None for keys, _ in tracks.values() for k in keys)
        cols += ["tx", "ty", "tz"] if has_t else []
        out.write(",".join(cols) + "\n")
        for name, k, vals in key_rows(tracks, interleave):
            cells = ([name] if named else []) + [repr(list(when(k).values())[0])] + [repr(v) for v in vals]
            if has_t:
                cells += [repr(v) for v in k["t"]] if k["t"] is not None else ["", "", ""]
            out.write(",".join(cells) + "\n")
        return out.getvalue()
    def key_obj(k, vals):
        o = dict(when(k))
        o.update(json_rotation(rep, vals, order))
        if k["t"] is not None and rep != "matrix4":
            o["translation"] = k["t"]
        return o
    if fmt == "ndjson":
        lines = []
        for name, k, vals in key_rows(tracks, interleave):
            o = key_obj(k, vals)
            if named:
                o["track"] = name
            lines.append(json.dumps(o))
        return "\n".join(lines) + "\n"
    doc = {"angles": "degrees" if degrees else "radians", "quat_order": order}
    if rep == "euler":
        doc["euler"] = seq
    if named:
        doc["tracks"] = {name: {"keys": [key_obj(k, v) for k, v in zip(keys, rows)]} for name, (keys, rows) in tracks.items()}
    else:
        (keys, rows), = tracks.values()
        doc["keys"] = [key_obj(k, v) for k, v in zip(keys, rows)]
    return json.dumps(doc)


# ---------------------------------------------------------------- outputs
def read_output(text, fmt, rep, seq, degrees, order, own_angles=False):
    """-> {track: [(frame or None, time, matrix, translation or None, Euler angles as written or None)]}.
    `own_angles`: Euler angles of Euler input in its own sequence, which may leave the canonical ranges."""
    scale = (math.pi / 180) if degrees else 1.0
    def rot(get, quat_order):
        if rep == "quat":
            q = get("quat")
            w, x, y, z = q if quat_order == "wxyz" else q[3:] + q[:3]
            assert abs(math.sqrt(w * w + x * x + y * y + z * z) - 1) < 1e-12, "quat output is not unit"
            return Rotation.from_quat([x, y, z, w]).as_matrix(), None
        if rep == "axis-angle":
            ax, ang = get("axis"), get("angle")
            assert 0 <= ang <= math.pi / scale + 1e-12, "angle outside [0, 180]"
            return Rotation.from_rotvec(np.array(ax) * ang * scale).as_matrix(), None
        if rep == "rotvec":
            return Rotation.from_rotvec(np.array(get("rotvec")) * scale).as_matrix(), None
        if rep == "euler":
            e = np.array(get("euler")) * scale
            if not own_angles:
                assert all(-math.pi - 1e-12 <= a <= math.pi + 1e-12 for a in e), "Euler angle outside [-180, 180]"
                lo, hi = (-math.pi / 2, math.pi / 2) if seq[0].lower() != seq[2].lower() else (0, math.pi)
                assert lo - 1e-12 <= e[1] <= hi + 1e-12, "middle Euler angle outside its canonical range"
            return Rotation.from_euler(seq, e).as_matrix(), None
        m = np.array(get("matrix"))
        if rep == "matrix4":
            assert list(m[3]) == [0, 0, 0, 1]
            return m[:3, :3], list(m[:3, 3])
        return m, None
    def check_settings(h):
        # A JSON document states all its settings as fields (SPEC).
        angles = "degrees" if degrees else "radians"
        assert h["rep"] == rep, "stated rep %r, written %r" % (h["rep"], rep)
        assert h["angles"] == angles, "stated angles %r" % h["angles"]
        if rep == "euler":
            assert h["euler"] == seq, "stated Euler sequence %r, written %r" % (h["euler"], seq)
        if rep == "quat":
            assert h["quat_order"] == order, "stated quat_order %r, written %r" % (h["quat_order"], order)
    # A CSV or NDJSON file begins with its first row (no line of settings),
    # and the names of its columns or members say the unit and order where
    # they are not the default: "angle_rad", "quat_xyzw".
    unit = "" if degrees else "_rad"
    result = {}
    if fmt == "csv":
        assert not text.startswith("#"), "a CSV output begins with a comment line"
        rows = list(csv.DictReader(io.StringIO(text)))
        for r in rows:
            def get(name, r=r):
                if name == "quat":
                    return [float(r[c]) for c in ("qw", "qx", "qy", "qz")]
                if name == "axis":
                    return [float(r[c]) for c in ("ax", "ay", "az")]
                if name == "angle":
                    return float(r["angle" + unit])
                if name == "rotvec":
                    return [float(r[c + unit]) for c in ("rx", "ry", "rz")]
                if name == "euler":
                    return [float(r[c + unit]) for c in ("e1", "e2", "e3")]
                n = 3 if rep == "matrix" else 4
                return [[float(r["m%d%d" % (i, j)]) for j in range(n)] for i in range(n)]
            m, t4 = rot(get, "wxyz")
            t = t4 if t4 is not None else ([float(r[c]) for c in ("tx", "ty", "tz")] if r.get("tx") else None)
            frame = float(r["frame"]) if r.get("frame") else None
            angles = get("euler") if rep == "euler" else None
            result.setdefault(r.get("track", ""), []).append((frame, float(r["time"]), m, t, angles))
        return result
    objs = []
    if fmt == "ndjson":
        lines = text.splitlines()
        for line in lines:
            o = json.loads(line)
            assert "time" in o, "an NDJSON line without a time: %r" % line
            objs.append((o.get("track", ""), o))
        names = {"quat": "quat" if order == "wxyz" else "quat_xyzw", "angle": "angle" + unit,
                 "rotvec": "rotvec" + unit, "euler": "euler" + unit}
        member_order = order  # (as the name says)
    else:
        doc = json.loads(text)
        check_settings(doc)
        names, member_order = {}, order
        if "tracks" in doc:
            for name, tr in doc["tracks"].items():
                objs += [(name, o) for o in tr.get("frames", tr.get("keys"))]
        else:
            objs = [("", o) for o in doc.get("frames", doc.get("keys"))]
    for name, o in objs:
        m, t4 = rot(lambda n, o=o: o[names.get(n, n)], member_order)
        t = t4 if t4 is not None else o.get("translation")
        angles = o[names.get("euler", "euler")] if rep == "euler" else None
        result.setdefault(name, []).append((o.get("frame"), o["time"], m, t, angles))
    return result


def close(a, b):
    return np.max(np.abs(np.array(a) - np.array(b))) <= TOL


def run_case(keyrot, rng, case):
    rep = rng.choice(IN_REPS)
    fmt = rng.choice(["csv", "json", "ndjson"])
    seq = rng.choice(SEQS)
    degrees = bool(rng.random() < 0.7)
    order = rng.choice(["wxyz", "xyzw"])
    method = rng.choice(METHODS)
    path = rng.choice(["shortest", "direct"])
    out_rep = rng.choice(OUT_REPS)
    out_fmt = rng.choice(["csv", "json", "ndjson"])
    out_seq = rng.choice(SEQS)
    if case % 4 == 0:  # (without drawing on rng) Euler output of Euler input in its own sequence
        out_seq = seq
    fps = float(rng.choice([24, 30, 12, 25, 7.5]))
    by_frame = bool(rng.random() < 0.3)
    key_fps = float(rng.choice([24, 30]))
    command = rng.choice(["resample", "resample", "resample", "convert"])
    n_tracks = int(rng.choice([1, 1, 2, 3]))

    # Every 50th case has long tracks of dense keys (about 120 a second, more
    # than the frames): keyrot then parses ahead on a second thread.
    dense = case % 50 == 49
    tracks = {}
    for t in range(n_tracks):
        n_keys = int(rng.integers(1100, 2500)) if dense else int(rng.integers(1 if command == "convert" else 2, 6))
        keys = random_keys(rng, n_keys, with_translation=rng.random() < 0.5,
                           spacing=(0.004, 0.012) if dense else (0.05, 0.6))
        if by_frame:  # keys on whole frames of key_fps, distinct
            frames = sorted(set(round(k["time"] * key_fps) for k in keys))
            keys = keys[:len(frames)]
            for k, f in zip(keys, frames):
                k["time"] = f / key_fps
        rows = encode(keys, rep, seq, degrees, rng)
        tracks["joint%d" % t] = (keys, rows)
    # Every other case's tracks interleave (without drawing on rng, so that
    # the cases stay those of the same seed): keyrot then reads them whole.
    text = write_input(tracks, rep, fmt, seq, degrees, order, by_frame, key_fps, interleave=case % 2 == 1)
    # The long way between nearly opposite quaternions (the same rotation
    # with the other sign) is a near-full turn about an axis that doubles pin
    # down only to about 1e-9: no double reference can check it to 1e-9.
    pairs = [(k1["q"], k2["q"]) for keys, _ in tracks.values() for k1, k2 in zip(keys, keys[1:])]
    if any(np.dot(a, b) < -0.99999 for a, b in pairs):
        path = "shortest"
    # Keys exactly 180 degrees apart (q . q' = 0 to rounding) are a tie: which
    # way "shortest" turns depends on the last bit of the dot product.
    if command == "resample" and any(abs(np.dot(a, b)) < 1e-9 for a, b in pairs):
        return "skip"

    args = [keyrot, command, "--from", fmt, "--to", out_fmt, "--rep", out_rep, "--quat-order", order]
    if rep == "euler" and (fmt != "json" or rng.random() < 0.5):
        args += ["--euler", seq]
    if method == "euler" and rep != "euler":
        args += ["--euler", seq]
    if out_rep == "euler":
        args += ["--out-euler", out_seq]
    if not degrees:
        args += ["--radians"]
    # Frame numbers count at 24 fps unless stated, whatever --fps is: every
    # third case at 24 leaves it to the default (without drawing on rng).
    if by_frame and not (key_fps == 24 and case % 3 == 0):
        args += ["--key-fps", repr(key_fps)]
    if command == "resample":
        args += ["--fps", repr(fps), "--method", method, "--path", path]
    proc = subprocess.run(args, input=text.encode(), capture_output=True)
    desc = f"case {case}: {' '.join(args[1:])}\n--- input ---\n{text[:2000]}"
    if proc.returncode != 0:
        return f"{desc}\nexit {proc.returncode}: {proc.stderr.decode()}"
    # Euler output of Euler input in its own sequence: each key's own angles at its time.
    own_angles = rep == "euler" and out_rep == "euler" and out_seq == seq
    out = read_output(proc.stdout.decode(), out_fmt, out_rep, out_seq, degrees, order, own_angles)
    names = list(tracks) if n_tracks > 1 else [""]
    if list(out) != names and not (command == "resample" and set(out) <= set(names)):
        return f"{desc}\ntracks {list(out)} != {names}"
    for name, (keys, rows) in zip(names, tracks.values()):
        got = out.get(name, [])
        if own_angles:
            at_key = {k["time"]: r for k, r in zip(keys, rows)}
            for _, time, _, _, angles in got:
                if time in at_key and angles != at_key[time]:
                    return f"{desc}\ntrack {name} time {time}: Euler angles {angles}, given as {at_key[time]}"
        if command == "convert":
            want = [(k["time"], to_matrix_wxyz(k["q"] / np.linalg.norm(k["q"])), k["t"]) for k in keys]
        else:
            reference = reference_frames(keys, method, path, fps, seq)
            if [row[0] for row in got] != [f for f, _, _, _ in reference]:
                return f"{desc}\ntrack {name}: frames differ"
            want = [(t, m, tr) for _, t, m, tr in reference]
        if len(got) != len(want):
            return f"{desc}\ntrack {name}: {len(got)} rows, expected {len(want)}"
        for row, (t, m, tr) in zip(got, want):
            frame, time, gm, gt, _ = row
            if abs(time - t) > 1e-12:
                return f"{desc}\ntrack {name}: time {time} != {t}"
            if not close(gm, m):
                return f"{desc}\ntrack {name} time {t}: matrix\n{gm}\n!= reference\n{m}"
            if out_rep == "matrix4" and tr is None:
                tr = [0.0, 0.0, 0.0]  # matrix4 always has a translation column
            if (tr is None) != (gt is None) or (tr is not None and not close(gt, tr)):
                return f"{desc}\ntrack {name} time {t}: translation {gt} != {tr}"
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("keyrot")
    ap.add_argument("--cases", type=int, default=600)
    ap.add_argument("--seed", type=int, default=20261122)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    failures = skipped = 0
    for case in range(a.cases):
        msg = run_case(a.keyrot, rng, case)
        if msg == "skip":
            skipped += 1
        elif msg:
            failures += 1
            if failures <= 3:
                print(msg, file=sys.stderr)
    print(f"{a.cases - failures - skipped} passed, {failures} failed, {skipped} skipped")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
