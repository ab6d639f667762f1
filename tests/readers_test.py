#!/usr/bin/env python3
"""keyrot's default outputs, as the tools people pair it with read them.

Each command's output with no flags beyond the format (resample, convert,
slerp and reduce, in CSV and in NDJSON; compare's reports and grade table) goes to
pandas (read_csv, read_json(lines=True)), Python's csv module, Miller
(mlr --icsv), csvkit (csvjson), awk 'NR>1' and jq. Each reader must see the
header as its columns and one row per frame or key: the row counts are
known from the inputs (a 1 s track at 4 fps is 5 frames; a constant-speed
turn reduces to its two ends), not taken from keyrot.

Also: the course's worked example is the line after the header; a BVH take
with two joints of one name reads as two plain tracks in pandas; the
settings line appears exactly where keyrot would otherwise misread the
output, and the README's ways of reading such a file work.

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
checks, failures = 0, []


def check(condition, message):
    global checks
    checks += 1
    if condition:
        print("ok: " + message)
    else:
        failures.append(message)
        print("FAIL: " + message)


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
    # convert: head_turn's 5 keys, numbered by frame (at 24 fps, the default, which is not written)
    csv_readers("convert head_turn", keyrot("convert", head_turn, "--to", "csv"), ["frame", *aa], 5)
    ndjson_readers("convert head_turn ndjson", keyrot("convert", head_turn, "--to", "ndjson"), ["frame", "axis", "angle"], 5)
    csv_readers("convert head_turn euler", keyrot("convert", head_turn, "--to", "csv", "--rep", "euler"),
                ["frame", "e1", "e2", "e3"], 5)
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

    # The settings line is written where keyrot would misread the output
    # without it, and only then; the ways the README gives to read it.
    radians = keyrot("resample", homework, "--fps", "4", "--rep", "rotvec", "--radians", "--to", "csv")
    check(radians.startswith('# keyrot {"angles": "radians"}\nframe,time,rx,ry,rz\n'), "radians: one settings line")
    frame = pd.read_csv(io.StringIO(radians), skiprows=1)
    check(list(frame.columns) == ["frame", "time", "rx", "ry", "rz"] and len(frame) == 5, "radians: pandas skiprows=1")
    for args in (["--icsvlite", "--skip-comments"], ["--icsv", "--skip-comments", "--lazy-quotes"]):
        rc, out, err = tool(["mlr", *args, "--ojson", "cat"], radians)
        check(rc == 0 and len(json.loads(out)) == 5, f"radians: mlr {' '.join(args)}: status {rc} {err.strip()}")
    rc, out, _ = tool(["csvjson", "--skip-lines", "1"], radians)
    check(rc == 0 and len(json.loads(out)) == 5, "radians: csvjson --skip-lines 1")
    never = keyrot("resample", homework, "--fps", "4", "--rep", "rotvec", "--radians", "--to", "csv", "--settings-line", "never")
    check(never == radians.split("\n", 1)[1], "--settings-line never: the same rows without the line")
    stated = keyrot("convert", head_turn, "--to", "csv", "--key-fps", "30")
    check(stated.startswith('# keyrot {"fps": 30}\nframe,'), "frames at a stated rate other than 24: the rate is stated")
    xyzw = keyrot("convert", homework, "--to", "ndjson", "--rep", "quat", "--quat-order", "xyzw")
    check(xyzw.startswith('{"quat_order": "xyzw"}\n'), "NDJSON quaternions in xyzw order: the order is stated")
    for args in (["--rep", "quat", "--quat-order", "xyzw"], ["--rep", "euler", "--out-euler", "ZYX"], ["--fps", "30"],
                 ["--method", "squad"]):
        out = keyrot("resample", homework, "--to", "csv", *args)
        check(out.startswith("frame,time,"), f"resample {' '.join(args)}: plain")

    shutil.rmtree(work)
    print(f"{checks - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
