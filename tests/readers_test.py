#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""keyrot's default outputs, as the tools people pair it with read them.

Each command's output with no flags beyond the format (resample, convert,
slerp and reduce, in CSV and in NDJSON; compare's reports and grade table) goes to
pandas (read_csv, read_json(lines=True)), Python's csv module, Miller
(mlr --icsv), csvkit (csvjson), awk 'NR>1' and jq. Each reader must see the
header as its columns and one row per frame or key: the row counts are
known from the inputs (a 1 s track at 4 fps is 5 frames; a constant-speed
turn reduces to its two ends), not taken from keyrot.

Also: the course's worked example is the line after the header; a BVH take
with two joints of one name reads as two plain tracks in pandas; and every
flag that changes a column (radians, the quaternion order, frames at any
key rate, reduce of a BVH and of a glTF file, matrices, velocities) still
gives a plain table that each of those readers takes, whose names say the
unit and order, and that keyrot reads back with no flags to the same
rotations (compare against the same command without the flag passes). No
output begins with a line of settings unless asked (--settings-line always).

Usage: readers_test.py KEYROT DATA_DIR. Exit 0 when all pass, 1 otherwise,
77 when pandas, Miller, csvkit or jq is missing.
"""
import csv
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import check, summary  # noqa: E402

try:
    import pandas as pd
except ImportError:  # pragma: no cover
    print("readers_test: pandas not installed (apt-get install python3-pandas); skipped")
    sys.exit(77)
for tool in ("mlr", "csvjson", "jq", "awk"):
    if not shutil.which(tool):
        print(f"readers_test: {tool} not installed (apt-get install miller csvkit jq); skipped")
        sys.exit(77)

KEYROT = os.path.abspath(sys.argv[1])
DATA = os.path.abspath(sys.argv[2])


def keyrot(*args, stdin=None):
    p = subprocess.run([KEYROT, *args], capture_output=True, text=True, input=stdin)
    if p.returncode != 0:
        raise SystemExit(f"keyrot {' '.join(args)}: exit {p.returncode}: {p.stderr}")
    return p.stdout


def tool(args, text):
    p = subprocess.run(args, capture_output=True, text=True, input=text)
    return p.returncode, p.stdout, p.stderr


def csv_readers(name, text, columns, rows):
    """Every CSV reader sees `columns` as the header and `rows` rows."""
    frame = pd.read_csv(io.StringIO(text))
    check(list(frame.columns) == columns and len(frame) == rows and not frame.isna().all(axis=1).any(),
          f"{name}: pandas.read_csv: columns {list(frame.columns)}, {len(frame)} rows")
    reader = csv.DictReader(io.StringIO(text))
    records = list(reader)
    check(reader.fieldnames == columns and len(records) == rows,
          f"{name}: csv.DictReader: fields {reader.fieldnames}, {len(records)} rows")
    rc, out, err = tool(["mlr", "--icsv", "--ojson", "cat"], text)
    records = json.loads(out) if rc == 0 else []
    check(rc == 0 and len(records) == rows and all(list(r) == columns for r in records),
          f"{name}: mlr --icsv: status {rc}, {len(records)} records {err.strip()}")
    rc, out, err = tool(["csvjson", "--no-inference"], text)
    records = json.loads(out) if rc == 0 else []
    check(rc == 0 and len(records) == rows and all(list(r) == columns for r in records),
          f"{name}: csvkit csvjson: status {rc}, {len(records)} records {err.strip()}")
    rc, out, _ = tool(["csvlook", "--no-inference"], text)
    check(rc == 0 and out.splitlines()[0].split("|")[1].strip() == columns[0],
          f"{name}: csvkit csvlook: status {rc}")
    rc, out, _ = tool(["awk", "-F,", "NR>1"], text)
    lines = out.splitlines()
    check(rc == 0 and len(lines) == rows and all(len(line.split(",")) >= len(columns) for line in lines)
          and not any(line.startswith(columns[0] + ",") for line in lines),
          f"{name}: awk 'NR>1': {len(lines)} data lines")


def ndjson_readers(name, text, fields, rows):
    """pandas and jq see `rows` objects, each with `fields`, and no header object."""
    frame = pd.read_json(io.StringIO(text), lines=True)
    # (a field some rows have and others not, a track's translation, is NaN in the others)
    check(len(frame) == rows and list(frame.columns) == fields and not frame[fields[:2]].isna().any(axis=None),
          f"{name}: pandas.read_json(lines=True): columns {list(frame.columns)}, {len(frame)} rows")
    time = "t" if "t" in fields else "time" if "time" in fields else "frame"
    rc, out, _ = tool(["jq", "-r", "." + time], text)
    values = out.split()
    check(rc == 0 and len(values) == rows and "null" not in values, f"{name}: jq -r .{time}: {values[:3]}...")
    rc, out, _ = tool(["mlr", "--ijsonl", "--ojson", "cat"], text)
    records = json.loads(out) if rc == 0 else []
    check(rc == 0 and len(records) == rows, f"{name}: mlr --ijsonl: status {rc}, {len(records)} records")


def read_back_equal(name, plain, flagged, fmt, *flags):
    """keyrot reads `flagged` (of format `fmt`) back with no flags (but the Euler sequence, which has
    no default) to the same rotations at the same times as `plain` (CSV): compare of the two passes,
    every row matched (with --ignore-extra among `flags`: every row of `flagged`, graded as the key;
    otherwise `plain` is the key, whose tracks without a translation a 4x4 matrix's zero one matches)."""
    with open("plain.csv", "w") as f:
        f.write(plain)
    with open("flagged." + fmt, "w") as f:
        f.write(flagged)
    files = ["flagged." + fmt, "plain.csv"] if "--ignore-extra" in flags else ["plain.csv", "flagged." + fmt]
    p = subprocess.run([KEYROT, "compare", *files, *flags, "--tol", "1e-9", "--report", "json"], capture_output=True,
                       text=True)
    report = json.loads(p.stdout) if p.stdout.startswith("{") else {}
    check(p.returncode == 0 and report.get("failed") == 0 and report.get("missing") == 0 and
          ("--ignore-extra" in flags or report.get("extra") == 0),
          f"{name}: read back with no flags, the same rotations: status {p.returncode} {p.stderr.strip()}")


def flagged_outputs(homework, head_turn, walk):
    """Each flag that changes a column: a plain table every reader takes, read back by keyrot with no flags."""
    bvh = os.path.join(DATA, "capture.bvh")
    gltf = os.path.join(DATA, "arm_wave.gltf")
    aa = ["ax", "ay", "az", "angle"]
    cases = [
        # (name, command, flags, CSV columns, NDJSON members, rows, flags keyrot reads the outputs with)
        ("axis-angle in radians", ["resample", homework, "--fps", "4"], ["--out-radians"],
         ["frame", "time", "ax", "ay", "az", "angle_rad"], ["frame", "time", "axis", "angle_rad"], 5, []),
        ("rotation vectors in radians", ["resample", homework, "--fps", "4", "--rep", "rotvec"], ["--radians"],
         ["frame", "time", "rx_rad", "ry_rad", "rz_rad"], ["frame", "time", "rotvec_rad"], 5, []),
        ("Euler angles in radians", ["resample", head_turn, "--fps", "4", "--rep", "euler"], ["--out-radians"],
         ["frame", "time", "e1_rad", "e2_rad", "e3_rad"], ["frame", "time", "euler_rad"], 9, ["--euler", "ZYX"]),
        ("quaternions in xyzw order", ["resample", homework, "--fps", "4", "--rep", "quat"], ["--quat-order", "xyzw"],
         ["frame", "time", "qx", "qy", "qz", "qw"], ["frame", "time", "quat_xyzw"], 5, []),
        # (the keys at 30 fps: the frames resample makes at 30 fps from them, five of which they are)
        ("frames at 30 fps", ["convert", head_turn, "--rep", "quat"], ["--key-fps", "30"],
         ["frame", "time", "qw", "qx", "qy", "qz"], ["frame", "time", "quat"], 5, ["--ignore-extra"]),
        ("reduce of a 120 Hz BVH take", ["reduce", bvh, "--tol", "0.5"], ["--rep", "axis-angle"],
         ["track", "frame", "time", *aa, "tx", "ty", "tz"], ["track", "frame", "time", "axis", "angle", "translation"],
         None, []),
        ("reduce of a glTF file", ["reduce", gltf, "--tol", "0.5"], ["--rep", "rotvec"],
         ["track", "time", "rx", "ry", "rz", "tx", "ty", "tz"], ["track", "time", "rotvec", "translation"], None, []),
        ("matrices", ["resample", walk, "--fps", "2"], ["--rep", "matrix"],
         ["track", "frame", "time", "m00", "m01", "m02", "m10", "m11", "m12", "m20", "m21", "m22", "tx", "ty", "tz"],
         ["track", "frame", "time", "matrix", "translation"], 6, []),
        ("4x4 matrices", ["resample", walk, "--fps", "2"], ["--rep", "matrix4"],
         ["track", "frame", "time", *[f"m{i}{j}" for i in range(4) for j in range(4)]], ["track", "frame", "time", "matrix"],
         6, []),
        ("angular velocity in radians", ["resample", walk, "--fps", "2", "--velocity", "--acceleration"],
         ["--out-radians"],
         ["track", "frame", "time", "ax", "ay", "az", "angle_rad", "tx", "ty", "tz", "wx_rad", "wy_rad", "wz_rad",
          "dwx_rad", "dwy_rad", "dwz_rad"],
         ["track", "frame", "time", "axis", "angle_rad", "translation", "angular_velocity_rad",
          "angular_acceleration_rad"], 6, []),
    ]
    for name, command, flags, columns, members, rows, key_flags in cases:
        plain = keyrot(*command, "--to", "csv", *(["--rep", "quat"] if command[0] == "reduce" else []))
        if "--ignore-extra" in key_flags:
            plain = keyrot("resample", head_turn, "--key-fps", "30", "--fps", "30", "--to", "csv")
        for fmt, readers, names in (("csv", csv_readers, columns), ("ndjson", ndjson_readers, members)):
            out = keyrot(*command, *flags, "--to", fmt)
            count = rows if rows is not None else len(plain.splitlines()) - 1
            check(not out.startswith("#") and (fmt == "csv" or "time" in json.loads(out.splitlines()[0])),
                  f"{name} {fmt}: its first row first, with a time")
            readers(f"{name} {fmt}", out, names, count)
            read_back_equal(f"{name} {fmt}", plain, out, fmt, *key_flags)
    # The settings line only when asked for, and keyrot reads it
    stated = keyrot("resample", homework, "--fps", "4", "--rep", "rotvec", "--radians", "--to", "csv", "--settings-line",
                    "always")
    check(stated.startswith('# keyrot {"fps": 4, "method": "slerp", "rep": "rotvec", "angles": "radians"}\n'),
          f"--settings-line always: {stated[:80]!r}")
    read_back_equal("--settings-line always", keyrot("resample", homework, "--fps", "4", "--to", "csv"), stated, "csv")
    check(keyrot("resample", homework, "--fps", "4", "--to", "ndjson", "--settings-line", "always").startswith(
        '{"fps": 4, "method": "slerp", "rep": "axis-angle", "angles": "degrees"}\n'), "--settings-line always: NDJSON")
    for args in (["--rep", "quat", "--quat-order", "xyzw"], ["--rep", "euler", "--out-euler", "ZYX"], ["--fps", "30"],
                 ["--method", "squad"], ["--radians", "--rep", "euler", "--out-euler", "xyz"]):
        out = keyrot("resample", homework, "--to", "csv", *args)
        check(out.startswith("frame,time,"), f"resample {' '.join(args)}: plain")


def records_read_back(walk, head_turn):
    """A table's rows as JSON records, as Miller and pandas write them, read as the CSV they came from."""
    tables = {
        "walk": keyrot("resample", walk, "--fps", "8", "--rep", "quat"),  # two tracks, a translation on one
        "head turn": keyrot("convert", head_turn, "--rep", "euler", "--to", "csv"),  # frames with times
        "radians": keyrot("resample", walk, "--fps", "4", "--rep", "rotvec", "--radians", "--velocity"),
    }
    for name, table in tables.items():
        flags = ["--euler", "ZYX"] if name == "head turn" else []
        with open("table.csv", "w") as f:
            f.write(table)
        frame = pd.read_csv("table.csv")
        made = {
            "Miller NDJSON": tool(["mlr", "--icsv", "--ojsonl", "cat"], table)[1],
            "Miller JSON": tool(["mlr", "--icsv", "--ojson", "cat"], table)[1],
            "pandas records": frame.to_json(orient="records"),
            "pandas records, lines": frame.to_json(orient="records", lines=True),
        }
        for how, text in made.items():
            fmt = "ndjson" if "NDJSON" in how or "lines" in how else "json"
            with open("records." + fmt, "w") as f:
                f.write(text)
            # (pandas writes 10 significant digits: within 1e-6 degrees)
            p = subprocess.run([KEYROT, "compare", "table.csv", "records." + fmt, *flags, "--tol", "1e-6",
                                "--tol-translation", "1e-9", "--report", "json"], capture_output=True, text=True)
            report = json.loads(p.stdout) if p.stdout.startswith("{") else {}
            rows = len(table.splitlines()) - 1
            check(p.returncode == 0 and report.get("rows") == rows and report.get("failed") == 0,
                  f"{name} as {how}: read as the CSV: status {p.returncode}, {report.get('rows')} rows of {rows} "
                  f"{p.stderr.strip()}")


def main():
    work = tempfile.mkdtemp()
    os.chdir(work)
    homework = os.path.join(DATA, "homework.json")
    head_turn = os.path.join(DATA, "head_turn.json")
    walk = os.path.join(DATA, "walk.csv")
    # A constant-speed quarter turn in 9 keys: reduce keeps its two ends.
    with open("turn.csv", "w") as f:
        f.write(keyrot("slerp", "1,0,0,0", "0.7071067811865476,0,0,0.7071067811865476", "--steps", "8", "--rep", "quat"))

    # resample: homework is 0 s to 1 s, 5 frames at 4 fps; walk's two tracks 0 s to 1 s, 3 frames each at 2 fps
    aa = ["ax", "ay", "az", "angle"]
    csv_readers("resample homework --fps 4", keyrot("resample", homework, "--fps", "4", "--to", "csv"),
                ["frame", "time", *aa], 5)
    csv_readers("resample walk --fps 2", keyrot("resample", walk, "--fps", "2"),
                ["track", "frame", "time", *aa, "tx", "ty", "tz"], 6)
    ndjson_readers("resample homework --fps 4 ndjson", keyrot("resample", homework, "--fps", "4", "--to", "ndjson"),
                   ["frame", "time", "axis", "angle"], 5)
    ndjson_readers("resample walk --fps 2 ndjson", keyrot("resample", walk, "--fps", "2", "--to", "ndjson"),
                   ["track", "frame", "time", "axis", "angle", "translation"], 6)
    # convert: head_turn's 5 keys, numbered by frame, with their times beside
    csv_readers("convert head_turn", keyrot("convert", head_turn, "--to", "csv"), ["frame", "time", *aa], 5)
    ndjson_readers("convert head_turn ndjson", keyrot("convert", head_turn, "--to", "ndjson"),
                   ["frame", "time", "axis", "angle"], 5)
    csv_readers("convert head_turn euler", keyrot("convert", head_turn, "--to", "csv", "--rep", "euler"),
                ["frame", "time", "e1", "e2", "e3"], 5)
    # slerp: the course's worked example is the line after the header
    example = keyrot("slerp", "0,0,0,1", "0,0,0.7071067811865476,0.7071067811865476", "--quat-order", "xyzw", "--rep",
                     "quat", "--precision", "4", "-t", "0.5")
    csv_readers("slerp worked example", example, ["t", "qx", "qy", "qz", "qw"], 1)
    rc, out, _ = tool(["awk", "NR==2"], example)
    check(out == "0.5,0,0,0.3827,0.9239\n", f"slerp worked example on the second line: {out!r}")
    csv_readers("slerp --steps 4", keyrot("slerp", "1,0,0,0", "0,0,0,1", "--steps", "4"), ["t", *aa], 5)
    ndjson_readers("slerp --steps 4 ndjson", keyrot("slerp", "1,0,0,0", "0,0,0,1", "--steps", "4", "--to", "ndjson"),
                   ["t", "axis", "angle"], 5)
    # reduce
    csv_readers("reduce turn", keyrot("reduce", "turn.csv"), ["time", "qw", "qx", "qy", "qz"], 2)
    ndjson_readers("reduce turn ndjson", keyrot("reduce", "turn.csv", "--to", "ndjson"), ["time", "quat"], 2)
    # compare's report
    keyrot("resample", homework, "--fps", "4", "--to", "csv", "-o", "key.csv")
    keyrot("convert", "key.csv", "--rep", "matrix", "-o", "answer.csv")
    report = subprocess.run([KEYROT, "compare", "key.csv", "answer.csv", "--report", "json"], capture_output=True,
                            text=True).stdout
    rc, out, _ = tool(["jq", "-r", ".rows, (.entries | length), ([.entries[].pass] | all)"], report)
    check(rc == 0 and out.split() == ["5", "5", "true"], f"compare --report json through jq: {out.split()}")
    report = subprocess.run([KEYROT, "compare", "key.csv", "answer.csv", "--report", "csv"], capture_output=True,
                            text=True).stdout
    csv_readers("compare --report csv", report, ["track", "frame", "time", "difference", "translation_difference",
                                                 "scale_difference", "extra", "pass", "reason"], 5)
    # the grade table of two answers
    table = subprocess.run([KEYROT, "compare", "key.csv", "answer.csv", "key.csv", "--report", "csv"],
                           capture_output=True, text=True).stdout
    csv_readers("compare grade table", table, ["answer", "grade", "rows", "failed", "missing", "extra",
                                               "max_difference", "track", "time", "reason"], 2)

    # Track names stay plain: a second joint of one name is '<name>.2', which
    # pandas reads as it is (a '#' would have been taken for a comment by
    # read_csv(comment='#') and turned the track into empty rows).
    with open(os.path.join(DATA, "capture.bvh")) as f:
        bvh = f.read().replace("JOINT LeftUpLeg", "JOINT Spine")
    with open("twins.bvh", "w") as f:
        f.write(bvh)
    names = pd.read_csv(io.StringIO(keyrot("resample", "twins.bvh", "--to", "csv")))["track"]
    check(list(dict.fromkeys(names)) == ["Hips", "Spine", "Head", "Spine.2"] and not names.isna().any(),
          f"duplicate BVH joint names: {list(dict.fromkeys(names))}")

    flagged_outputs(homework, head_turn, walk)
    records_read_back(walk, head_turn)

    shutil.rmtree(work)
    return summary("readers_test")


if __name__ == "__main__":
    sys.exit(main())
