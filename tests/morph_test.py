#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""glTF morph target weights against the glTF 2.0 specification written out here.

Generated files: a weights-only file in the manner of Khronos' SimpleMorph
(a mesh of two morph targets, a LINEAR weights channel and nothing else); a
skinned character whose face node has four targets keyed STEP at other
times than the joints' rotations; a node with its own rotation and three
CUBICSPLINE weights; normalised-integer weights. For each:

- resample to CSV: the columns w0..wN-1 equal the specification's curve at
  every frame (LINEAR component-wise, STEP held, CUBICSPLINE Hermite with
  the key interval, clamped outside the keys), within 1e-9;
- resample glTF to glTF: the weights sampler is on the same grid as the
  node transforms' samplers, reads back as the CSV frames to float32, and
  the Khronos glTF Validator finds nothing;
- CSV, JSON and NDJSON carry the weights (w0.. columns, "weights": [...])
  and read back to the same values; a CSV of keys resamples its weights
  linearly (numpy.interp), or held with --method step;
- compare passes a file against itself, and fails on a weight moved by
  more than --tol-translation, naming the weights; info lists them;
- reduce keeps its guarantee on the weights.

Then bad input: one line naming the file and what was expected, exit 2,
nothing written.

Usage: morph_test.py KEYROT [VALIDATOR_JS]. Exit 0 when all pass, 1
otherwise; 77 (skip) without numpy.
"""
import bisect
import csv
import io
import json
import os
import subprocess
import sys
import tempfile

try:
    import numpy as np
except ImportError:  # pragma: no cover
    print("morph_test: numpy not installed (apt-get install python3-numpy); skipped")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gltf_files as G  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import fail, ok, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])
VALIDATOR = sys.argv[2] if len(sys.argv) > 2 else None
TOL = 1e-9
FLOAT32 = 1e-6  # weights of about 1 rounded to 32-bit floats


def run(args, stdin=None):
    p = subprocess.run([KEYROT] + args, input=stdin, capture_output=True)
    return p.returncode, p.stdout.decode(), p.stderr.decode()


def rows_of(text):
    return list(csv.DictReader(line for line in io.StringIO(text) if not line.startswith("#")))


def weights_of(row, n):
    return np.array([float(row[f"w{j}"]) for j in range(n)])


# ---------------------------------------------------------------- the specification
def weights_at(times, values, interp, t):
    """A weights sampler at time t (glTF 2.0, "Animations" and Appendix C): values are keys x n,
    or keys x 3 x n (in-tangent, value, out-tangent) for CUBICSPLINE; clamped outside the keys."""
    cubic = interp == "CUBICSPLINE"
    value = (lambda i: values[i][1]) if cubic else (lambda i: values[i])
    if t <= times[0]:
        return np.asarray(value(0))
    if t >= times[-1]:
        return np.asarray(value(len(times) - 1))
    k = bisect.bisect_right(times, t) - 1
    if interp == "STEP" or times[k] == t:
        return np.asarray(value(k))
    td = times[k + 1] - times[k]
    s = (t - times[k]) / td
    if cubic:
        return ((2 * s**3 - 3 * s**2 + 1) * values[k][1] + td * (s**3 - 2 * s**2 + s) * values[k][2]
                + (-2 * s**3 + 3 * s**2) * values[k + 1][1] + td * (s**3 - s**2) * values[k + 1][0])
    return (1 - s) * np.asarray(values[k]) + s * np.asarray(values[k + 1])


# ---------------------------------------------------------------- files
class Case:
    """A file, and per track the weights channel as a reader decodes it."""

    def __init__(self, name, track, times, values, interp, targets, component=G.FLOAT):
        self.name, self.track, self.interp, self.targets = name, track, interp, targets
        self.b = G.Builder()
        self.times = list(self.b.decoded_times(times))
        self.span = (self.times[0], self.times[-1])  # the node's track: all its channels' keys
        self.values = self.b.decoded(np.asarray(values, dtype=float), component)
        # (SCALAR: a weight per target per key, one after another)
        self.channel = {"path": "weights", "times": times, "values": np.asarray(values, dtype=float).reshape(-1, 1),
                        "interpolation": interp, "component": component}

    def curve(self, t, fps):
        """The weights at a frame's time t: a frame within a key's 32-bit rounding of it is at the key."""
        near = [k for k in self.times if abs(k - t) * fps <= max(1e-9, abs(k) * fps * 2.0**-24)]
        t = near[0] if near else t
        v = self.values.reshape(len(self.times), 3, self.targets) if self.interp == "CUBICSPLINE" else \
            self.values.reshape(len(self.times), self.targets)
        return weights_at(self.times, v, self.interp, t)


def make_cases(work):
    rng = np.random.default_rng(20261203)
    cases = []

    # SimpleMorph's shape: a node with a mesh of two targets, animated in weights alone.
    c = Case("simple_morph.glb", "morph", [0.0, 1.0, 2.0, 3.0, 4.0],
             [[0, 0], [1, 0], [0, 1], [1, 1], [0, 0]], "LINEAR", 2)
    mesh = c.b.morph_mesh(2, [0.5, 0.5])
    c.b.json["nodes"] = [{"name": "morph", "mesh": mesh}]
    c.channel["node"] = 0
    c.b.animation([c.channel])
    cases.append((c, "glb"))

    # A skinned character: joints' rotations, a face of four targets keyed STEP at other times.
    c = Case("face.gltf", "face", sorted(rng.uniform(0.05, 2.9, 9)), rng.uniform(0, 1, (9, 4)), "STEP", 4)
    c.b.skeleton(6)
    mesh = c.b.morph_mesh(4)
    c.b.json["nodes"].append({"name": "face", "mesh": mesh})
    c.b.json["scenes"][0]["nodes"].append(len(c.b.json["nodes"]) - 1)
    c.channel["node"] = len(c.b.json["nodes"]) - 1
    joint_times = np.linspace(0, 3, 13)
    channels = [{"node": j, "path": "rotation", "times": joint_times,
                 "values": [q / np.linalg.norm(q) for q in rng.normal(size=(13, 4)) + [0, 0, 0, 3]]} for j in range(6)]
    c.b.animation(channels[:3] + [c.channel] + channels[3:])
    cases.append((c, "bin"))

    # A node with its own rotation channel and three CUBICSPLINE weights, keyed from 0.3 s.
    times = [0.3, 0.8, 1.1, 1.9, 2.4]
    c = Case("cubic_face.gltf", "head", times, rng.uniform(-0.5, 1.5, (5, 3, 3)), "CUBICSPLINE", 3)
    mesh = c.b.morph_mesh(3)
    c.b.json["nodes"] = [{"name": "head", "mesh": mesh}]
    c.channel["node"] = 0
    rotation = {"node": 0, "path": "rotation", "times": [0.0, 1.0, 2.0],
                "values": [[0, 0, 0, 1], [0, 0.5**0.5, 0, 0.5**0.5], [0, 1, 0, 0]]}
    c.b.animation([rotation, c.channel])
    c.span = (0.0, c.times[-1])  # the weights are held before their first key
    cases.append((c, "datauri"))

    # Normalised UNSIGNED_BYTE weights, as an exporter may store them.
    c = Case("byte_morph.glb", "blink", [0.0, 0.25, 0.5], [[0, 1], [1, 0.5], [0.2, 0]], "LINEAR", 2,
             G.UNSIGNED_BYTE)
    mesh = c.b.morph_mesh(2)
    c.b.json["nodes"] = [{"name": "blink", "mesh": mesh}]
    c.channel["node"] = 0
    c.b.animation([c.channel])
    cases.append((c, "glb"))

    for c, how in cases:
        c.path = os.path.join(work, c.name)
        c.b.write(c.path, how)
    return [c for c, _ in cases]


# ---------------------------------------------------------------- checks
def check_resample(c, fps):
    status, out, err = run(["resample", c.path, "--fps", str(fps), "--to", "csv"])
    if status != 0:
        return fail(f"{c.name} at {fps} fps: status {status}: {err.strip()}")
    rows = [r for r in rows_of(out) if r.get("track", c.track) == c.track]
    if not rows or f"w{c.targets - 1}" not in rows[0] or f"w{c.targets}" in rows[0]:
        return fail(f"{c.name}: expected columns w0 to w{c.targets - 1}, got {list(rows[0]) if rows else 'no rows'}")
    worst = max(np.max(np.abs(weights_of(r, c.targets) - c.curve(float(r["time"]), fps))) for r in rows)
    if worst > TOL:
        return fail(f"{c.name} at {fps} fps: weights differ from the specification's by {worst:.3g}")
    ok(f"{c.name} at {fps} fps: {len(rows)} frames of {c.targets} weights, within {worst:.2g} of the specification")


def accessor_floats(doc, binary, i):
    a = doc["accessors"][i]
    v = doc["bufferViews"][a["bufferView"]]
    start = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[a["type"]]
    return np.frombuffer(binary, "<f4", a["count"] * width, start).astype(float)


def check_gltf_out(c, fps, ext, written):
    out = os.path.splitext(c.path)[0] + f"_{fps}.{ext}"
    status, _, err = run(["resample", c.path, "--fps", str(fps), "-o", out])
    if status != 0:
        return fail(f"{out}: status {status}: {err.strip()}")
    written.append(out)
    doc, binary = G.parts(out)
    anim = doc["animations"][0]
    inputs = {ch["target"]["path"]: anim["samplers"][ch["sampler"]]["input"]
              for ch in anim["channels"] if ch["target"]["node"] == c.channel["node"]}
    node_inputs = {anim["samplers"][ch["sampler"]]["input"] for ch in anim["channels"]
                   if ch["target"]["path"] != "weights"}
    times = accessor_floats(doc, binary, inputs["weights"])
    if any(not np.array_equal(accessor_floats(doc, binary, i), times) and len(accessor_floats(doc, binary, i)) > 1
           and accessor_floats(doc, binary, i)[0] <= times[-1] for i in node_inputs if c.name != "face.gltf"):
        return fail(f"{out}: the weights are not on the node transforms' grid")
    grid = np.arange(np.ceil(c.span[0] * fps - 1e-6), np.floor(c.span[1] * fps + 1e-6) + 1) / fps
    if len(times) != len(grid) or np.max(np.abs(times - grid)) > 1e-6:
        return fail(f"{out}: weights keyed at {times[:4]}..., expected the {fps} fps grid {grid[:4]}...")
    sampler = next(anim["samplers"][ch["sampler"]] for ch in anim["channels"] if ch["target"]["path"] == "weights")
    values = accessor_floats(doc, binary, sampler["output"]).reshape(len(times), c.targets)
    worst = max(np.max(np.abs(values[i] - c.curve(t, fps))) for i, t in enumerate(grid))
    if worst > FLOAT32 or sampler.get("interpolation", "LINEAR") != ("STEP" if c.interp == "STEP" else "LINEAR"):
        return fail(f"{out}: weights {worst:.3g} from the specification's, interpolation {sampler.get('interpolation')}")
    _, back, _ = run(["convert", out, "--to", "csv"])
    back_rows = [r for r in rows_of(back) if r.get("track", c.track) == c.track]
    if len(back_rows) != len(grid) or max(np.max(np.abs(weights_of(r, c.targets) - c.curve(float(r["time"]), fps)))
                                          for r in back_rows) > FLOAT32:
        return fail(f"{out}: read back, the weights differ")
    ok(f"{out}: {len(grid)} weights keys on the {fps} fps grid, within {worst:.2g} of the specification")


def check_text_formats(c, work):
    _, frames, _ = run(["resample", c.path, "--to", "csv"])
    base = os.path.join(work, os.path.splitext(c.name)[0] + "_frames")
    with open(base + ".csv", "w") as f:
        f.write(frames)
    status, js, err = run(["convert", base + ".csv", "--to", "json"])
    if status != 0:
        return fail(f"{c.name} CSV to JSON: {err.strip()}")
    doc = json.loads(js)
    tracks = doc["tracks"] if "tracks" in doc else {c.track: doc}
    keys = tracks[c.track]["frames"] if "frames" in tracks[c.track] else tracks[c.track]["keys"]
    if any(len(k["weights"]) != c.targets for k in keys):
        return fail(f"{c.name}: JSON keys without {c.targets} weights")
    with open(base + ".json", "w") as f:
        f.write(js)
    status, nd, err = run(["convert", base + ".json", "--to", "ndjson"])
    lines = [json.loads(line) for line in nd.splitlines() if '"weights"' in line]
    if status != 0 or len(lines) != len(keys):
        return fail(f"{c.name}: NDJSON: {err.strip()} ({len(lines)} lines with weights)")
    status, again, err = run(["convert", "-", "--from", "ndjson", "--to", "csv"], nd.encode())
    weights = [f"w{j}" for j in range(c.targets)]
    if status != 0 or [[r[w] for w in weights] for r in rows_of(again)] != [[r[w] for w in weights] for r in rows_of(frames)]:
        return fail(f"{c.name}: CSV -> JSON -> NDJSON -> CSV changed the weights: {err.strip()}")
    ok(f"{c.name}: CSV, JSON and NDJSON carry the {c.targets} weights, and read back the same")


def check_csv_input(work):
    """Keys in CSV: weights resample linearly (or held), with the rotation; a track without weights beside."""
    path = os.path.join(work, "keys.csv")
    times = [0.0, 0.5, 1.25, 2.0]
    w = np.array([[0, 1, 0.25], [1, 0, 0.5], [0.5, 0.5, -0.25], [0.25, 0.75, 1.0]])
    with open(path, "w") as f:
        f.write("track,time,qw,qx,qy,qz,w0,w1,w2\n")
        for t, row in zip(times, w):
            f.write(f"face,{t},1,0,0,0,{row[0]},{row[1]},{row[2]}\n")
        f.write("arm,0,1,0,0,0,,,\narm,1,0,1,0,0,,,\n")
    for method, expect in (("slerp", lambda t: [np.interp(t, times, w[:, j]) for j in range(3)]),
                           ("step", lambda t: w[bisect.bisect_right(times, t + 1e-12) - 1])):
        status, out, err = run(["resample", path, "--fps", "24", "--method", method])
        if status != 0:
            return fail(f"keys.csv --method {method}: {err.strip()}")
        rows = rows_of(out)
        face = [r for r in rows if r["track"] == "face"]
        worst = max(np.max(np.abs(weights_of(r, 3) - expect(float(r["time"])))) for r in face)
        arm_empty = all(r["w0"] == "" and r["w2"] == "" for r in rows if r["track"] == "arm")
        if worst > TOL or len(face) != 49 or not arm_empty:
            return fail(f"keys.csv --method {method}: weights {worst:.3g} off, {len(face)} frames, arm empty {arm_empty}")
    ok("keys.csv: weights resample linearly (slerp) and held (step); a track without them leaves the cells empty")
    return path


def check_compare_info(c, work):
    _, frames, _ = run(["resample", c.path, "--to", "csv"])
    good = os.path.join(work, "morph_good.csv")
    with open(good, "w") as f:
        f.write(frames)
    played = os.path.join(work, "morph_24.glb")  # the same frames as a glTF file stores them
    run(["resample", c.path, "-o", played])
    status, _, err = run(["compare", good, played])
    if status != 0:
        return fail(f"compare {good} {played}: status {status}: {err.strip()}")
    lines = frames.splitlines()
    cells = lines[3].split(",")
    header = lines[0].split(",")
    cells[header.index("w1")] = str(float(cells[header.index("w1")]) + 0.01)
    lines[3] = ",".join(cells)
    bad = os.path.join(work, "morph_bad.csv")
    with open(bad, "w") as f:
        f.write("\n".join(lines) + "\n")
    status, _, err = run(["compare", good, bad])
    if status != 1 or "weights differ by 0.01" not in err:
        return fail(f"compare with a weight moved by 0.01: status {status}: {err.strip()}")
    status, report, _ = run(["compare", good, bad, "--report", "csv"])
    report_rows = rows_of(report)
    moved = [r for r in report_rows if r["pass"] == "false"]
    if "weights_difference" not in report_rows[0] or len(moved) != 1 or abs(float(moved[0]["weights_difference"]) - 0.01) > 1e-9:
        return fail(f"compare --report csv: {report_rows[:1]} {moved}")
    status, _, _ = run(["compare", good, bad, "--tol-translation", "0.02"])
    if status != 0:
        return fail("compare --tol-translation 0.02 failed a weight moved by 0.01")
    status, text, err = run(["info", c.path])
    status_json, js, _ = run(["info", c.path, "--to", "json"])
    if status or status_json or f"morph weights: {c.targets} (w0 to w{c.targets - 1})" not in text or \
            "weights linear" not in text or json.loads(js)["tracks"][0]["weights"] != c.targets:
        return fail(f"info {c.name}: {text} {err}")
    ok("compare reports the weights (and their column), --tol-translation holds them; info lists them")


def check_reduce(work, csv_path):
    out = os.path.join(work, "reduced.csv")
    status, _, err = run(["reduce", csv_path, "--tol", "0.01", "--tol-translation", "0.001", "-o", out])
    if status != 0:
        return fail(f"reduce keys.csv: {err.strip()}")
    kept = rows_of(open(out).read())
    # Every key of the input, played back from the kept keys, within tolerance.
    status, back, err = run(["compare", csv_path, out, "--tol-translation", "0.001"])
    if status != 0:
        return fail(f"compare keys.csv with its reduction: {err.strip()}")
    face = [r for r in kept if r["track"] == "face"]
    if len(face) != 4:  # every face key changes the weights' course
        return fail(f"reduce kept {len(face)} face keys, expected 4")
    ok("reduce keeps the keys the weights need")


def bad_inputs(work):
    """(name, args, stdin, piece of the message)."""
    cases = []
    b = G.Builder()
    b.json["nodes"] = [{"name": "nomesh"}]
    b.animation([{"node": 0, "path": "weights", "times": [0.0, 1.0], "values": [[0.0], [1.0]]}])  # (SCALAR)
    p = os.path.join(work, "no_mesh.glb")
    b.write(p, "glb")
    cases.append(("a weights channel of a node without a mesh", ["resample", p, "--to", "csv"],
                  "no_mesh.glb: animations[0].channels[0].target.node: a weights channel of node 0, which has no mesh"))
    b = G.Builder()
    mesh = b.morph_mesh(2)
    b.json["nodes"] = [{"name": "m", "mesh": mesh}]
    b.animation([{"node": 0, "path": "weights", "times": [0.0, 1.0, 2.0], "values": [[0.0], [1.0], [0.5]]}])
    p = os.path.join(work, "short.glb")
    b.write(p, "glb")
    cases.append(("weights for too few targets", ["resample", p, "--to", "csv"],
                  "short.glb: animations[0].samplers[0].output: 3 weights for 3 key times of 2 morph targets: expected 6"))
    p = os.path.join(work, "gap.csv")
    with open(p, "w") as f:
        f.write("time,qw,qx,qy,qz,w0,w2\n0,1,0,0,0,0,1\n")
    cases.append(("a CSV with w2 but no w1", ["resample", p], "gap.csv:1: column 'w2' without 'w1'"))
    p = os.path.join(work, "ragged.csv")
    with open(p, "w") as f:
        f.write("time,qw,qx,qy,qz,w0,w1\n0,1,0,0,0,0,1\n1,1,0,0,0,0,\n")
    cases.append(("a key with fewer weights than the one before", ["resample", p],
                  "ragged.csv:3: 1 morph weights after a key with 2: expected as many on every key of a track"))
    p = os.path.join(work, "holes.csv")
    with open(p, "w") as f:
        f.write("time,qw,qx,qy,qz,w0,w1\n0,1,0,0,0,,1\n")
    cases.append(("an empty weight before a number", ["resample", p],
                  "holes.csv:2: column 'w1' after an empty 'w0': expected the weights as numbers from w0 on"))
    cases.append(("JSON weights that are not numbers", ["resample", "-", "--from", "ndjson"],
                  "<stdin>:1: 'weights[1]': expected a number, got string"))
    p = os.path.join(work, "keys_for_new.csv")
    with open(p, "w") as f:
        f.write("time,qw,qx,qy,qz,w0\n0,1,0,0,0,0\n1,1,0,0,0,1\n")
    cases.append(("weights into a new glTF file", ["resample", p, "-o", os.path.join(work, "new.glb")],
                  "track '' has morph weights, which a new glTF file cannot hold"))
    return cases


def check_bad(work):
    for name, args, piece in bad_inputs(work):
        stdin = b'{"time": 0, "quat": [1, 0, 0, 0], "weights": [0, "a"]}\n' if "-" in args else None
        before = set(os.listdir(work))
        status, out, err = run(args, stdin)
        lines = err.strip().splitlines()
        if status != 2 or out or len(lines) != 1 or piece not in lines[0] or set(os.listdir(work)) != before:
            fail(f"{name}: status {status}, {len(out)} bytes out, stderr {err.strip()!r}; expected {piece!r}")
        else:
            ok(f"{name}: {lines[0]}")


def validate(files):
    if not VALIDATOR:
        print(f"morph_test: the glTF Validator is not installed (.ci/deps test): {len(files)} outputs not validated")
        return
    bad = G.validator_problems(VALIDATOR, files)
    if bad:
        fail("glTF Validator: " + "; ".join(bad[:10]))
    else:
        ok(f"glTF Validator: {len(files)} outputs, no errors, no warnings")


def main():
    with tempfile.TemporaryDirectory() as work:
        cases = make_cases(work)
        validate([c.path for c in cases])
        written = []
        for c in cases:
            for fps in (24, 30):
                check_resample(c, fps)
            check_gltf_out(c, 30, "glb", written)
            check_gltf_out(c, 24, "gltf", written)
            check_text_formats(c, work)
        validate(written)
        csv_path = check_csv_input(work)
        check_compare_info(cases[0], work)
        if csv_path:
            check_reduce(work, csv_path)
        check_bad(work)
    return summary("morph_test")


if __name__ == "__main__":
    sys.exit(main())
