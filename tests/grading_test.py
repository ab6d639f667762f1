#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Grading a class at once: `keyrot compare KEY ANSWER...`.

The key and every answer are written here, with Python's own math (a turn
about z, and answers off by known amounts), never by keyrot, so the grades
expected are known before keyrot runs:

- a class (right, slightly off, just over the tolerance, in radians graded
  as degrees, an Euler answer in another sequence, a JSON answer in xyzw
  order, extra rows, frame numbers of a 4 fps grid, unreadable, empty) is
  graded in one command, and the table checked as text, CSV and JSON, with
  its exit status and the hints it gives;
- the pass/fail boundary, for rotation and translation: answers 0.99 and
  1.01 times the tolerance off;
- one answer keeps its summary line; --report json of an unreadable answer
  is still a JSON document with an `error` member;
- compare and info of a million rows in the memory of a hundred thousand, and
  files of two layouts (track after track, rows interleaved) compared;
- --ignore-extra, float32 times, messages naming the right file, slerp -t
  outside [0, 1], --radians on degrees, UTF-16 files, and the flag messages.

Usage: grading_test.py KEYROT. Exit 0 when all pass, 1 otherwise.
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

from peak import peak_kb

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import check, summary  # noqa: E402

KEYROT = os.path.abspath(sys.argv[1])


def keyrot(*args, cwd):
    return subprocess.run([KEYROT, *args], cwd=cwd, capture_output=True, text=True)


def write(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


# The key: 90 degrees about z over 1 s, at 4 fps (angle 22.5 * i at t = i / 4).
TIMES = [i / 4 for i in range(5)]
ANGLES = [22.5 * i for i in range(5)]


def axis_angle_csv(angles, times=TIMES, translation=None):
    rows = ["time,ax,ay,az,angle" + (",tx,ty,tz" if translation else "")]
    for i, (t, a) in enumerate(zip(times, angles)):
        rows.append(f"{t!r},0,0,1,{a!r}" + (f",{translation[i]!r},0,0" if translation else ""))
    return "\n".join(rows) + "\n"


def quat_z(deg):
    h = math.radians(deg) / 2
    return [math.cos(h), 0.0, 0.0, math.sin(h)]  # w, x, y, z


with tempfile.TemporaryDirectory() as d:
    write(os.path.join(d, "key.csv"), axis_angle_csv(ANGLES))
    answers = {
        "right.csv": axis_angle_csv(ANGLES),
        "slightly_off.csv": axis_angle_csv([a + 0.005 for a in ANGLES]),
        "over.csv": axis_angle_csv([a + 0.0101 for a in ANGLES]),
        "radians.csv": axis_angle_csv([math.radians(a) for a in ANGLES]),
        # ZYX angles (z first) of a turn about z, read as XYZ: a turn about x.
        "euler.csv": "time,e1,e2,e3\n" + "".join(f"{t!r},{a!r},0,0\n" for t, a in zip(TIMES, ANGLES)),
        # Arrays in x, y, z, w order with nothing saying so.
        "xyzw.ndjson": "".join(json.dumps({"time": t, "quat": quat_z(a)[1:] + quat_z(a)[:1]}) + "\n"
                               for t, a in zip(TIMES, ANGLES)),
        "extra.csv": axis_angle_csv([11.25 * i for i in range(9)], [i / 8 for i in range(9)]),
        # Frames 0-4 of a 4 fps grid, no times: read at 24 fps, only frame 0 matches.
        "frames4.csv": "frame,ax,ay,az,angle\n" + "".join(f"{i},0,0,1,{a!r}\n" for i, a in enumerate(ANGLES)),
        # Columns named qw,qx,qy,qz over values in x, y, z, w order.
        "xyzw_columns.csv": "time,qw,qx,qy,qz\n" + "".join(f"{t!r},{','.join(repr(v) for v in quat_z(a)[1:] + quat_z(a)[:1])}\n"
                                                           for t, a in zip(TIMES, ANGLES)),
        "unreadable.csv": "when,ax,ay,az,angle\n0,0,0,1,0\n",
        "empty.csv": "",
    }
    for name, text in answers.items():
        write(os.path.join(d, name), text)
    expected = {"right.csv": "pass", "slightly_off.csv": "pass", "over.csv": "fail", "radians.csv": "fail",
                "euler.csv": "fail", "xyzw.ndjson": "fail", "extra.csv": "fail", "frames4.csv": "fail",
                "xyzw_columns.csv": "fail", "unreadable.csv": "unreadable", "empty.csv": "unreadable"}
    names = list(answers)
    flags = ["--euler", "XYZ"]

    r = keyrot("compare", "key.csv", *names, *flags, "--report", "csv", cwd=d)
    check(r.returncode == 1, f"a class with failures: exit 1 (got {r.returncode}: {r.stderr.strip()})")
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    got = {row["answer"]: row["grade"] for row in rows}
    check(got == expected, f"--report csv grades every answer as expected: {got}")
    by = {row["answer"]: row for row in rows}
    check(by.get("extra.csv", {}).get("extra") == "4", "extra.csv: 4 extra rows counted")
    check((by.get("frames4.csv", {}).get("missing"), by.get("frames4.csv", {}).get("extra")) == ("4", "4"),
          "frames4.csv: frames 1-4 at 24 fps are not the key's 0.25-1 s: 4 missing, 4 extra")
    check("--radians" in by.get("radians.csv", {}).get("reason", ""), "radians.csv: the hint names --radians")
    check("--euler ZYX" in by.get("euler.csv", {}).get("reason", ""), "euler.csv: the hint names --euler ZYX")
    check("--quat-order xyzw" in by.get("xyzw.ndjson", {}).get("reason", ""),
          "xyzw.ndjson: the hint names --quat-order xyzw")
    check("--key-fps" in by.get("frames4.csv", {}).get("reason", "") and
          "the answer counts its frames at 24 fps (the default; it states no rate)" in by["frames4.csv"]["reason"],
          f"frames4.csv: the hint names --key-fps and the rate the answer counts at: {by.get('frames4.csv')}")
    check("its header should read qx,qy,qz,qw" in by.get("xyzw_columns.csv", {}).get("reason", ""),
          f"xyzw_columns.csv: the hint says the columns hold x, y, z, w: {by.get('xyzw_columns.csv')}")
    check("no time column" in by.get("unreadable.csv", {}).get("reason", ""), "unreadable.csv: the reason is given")
    # A JSON document with its settings after its keys is read whole (not
    # streamed): its hint reads it again the other way too.
    keys = ", ".join(f'{{"time": {t!r}, "axis": [0, 0, 1], "angle": {math.radians(a)!r}}}' for t, a in zip(TIMES, ANGLES))
    write(os.path.join(d, "radians_late.json"), f'{{"keys": [{keys}], "fps": 24}}')
    late = keyrot("compare", "key.csv", "radians_late.json", cwd=d)
    check(late.returncode == 1 and "read as radians (--radians)" in late.stdout,
          f"a JSON document read whole: the hint names --radians: {late.stdout.strip()}")
    over = by.get("over.csv", {})
    check(abs(float(over.get("max_difference") or "nan") - 0.0101) < 1e-9, f"over.csv: max difference 0.0101: {over}")
    check("2 pass, 7 fail, 2 unreadable" in r.stderr,
          f"the count on stderr: {r.stderr.strip().splitlines()[-1:]}")

    r = keyrot("compare", "key.csv", *names, *flags, "--report", "json", cwd=d)
    table = json.loads(r.stdout)
    check({g["answer"]: g["grade"] for g in table["grades"]} == expected, "--report json grades as --report csv")
    check((table["pass"], table["fail"], table["unreadable"]) == (2, 7, 2), "--report json counts")
    check(all("error" in g for g in table["grades"] if g["grade"] == "unreadable"), "unreadable answers: an error member")

    r = keyrot("compare", "key.csv", *names, *flags, cwd=d)
    lines = r.stdout.splitlines()
    check(lines[0].split()[:3] == ["answer", "grade", "rows"] and len(lines) == 1 + len(names),
          "the text table: a header and a row per answer")
    check(all(line.split()[1] == expected[line.split()[0]] for line in lines[1:]), "the text table's grades")

    r = keyrot("compare", "key.csv", "right.csv", "slightly_off.csv", cwd=d)
    check(r.returncode == 0, "every answer passes: exit 0")
    r = keyrot("compare", "key.csv", "extra.csv", "right.csv", "--ignore-extra", "--report", "csv", cwd=d)
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    check(r.returncode == 0 and rows[0]["grade"] == "pass" and rows[0]["extra"] == "4",
          "--ignore-extra: extra rows counted, not failed")
    r = keyrot("compare", "key.csv", "frames4.csv", "--key-fps", "4", cwd=d)
    check(r.returncode == 0, "--key-fps 4 grades the frame-numbered answer right")

    # Messages, tables and reports speak of the answer and the key, never of EXPECTED or ACTUAL
    write(os.path.join(d, "two_tracks.csv"), "track,time,ax,ay,az,angle\n" + "".join(
        f"{n},{t!r},0,0,1,{a!r}\n" for n in ("hip", "knee") for t, a in zip(TIMES, ANGLES)))
    write(os.path.join(d, "knee_only.csv"), "track,time,ax,ay,az,angle\n" + "".join(
        f"Knee,{t!r},0,0,1,{a!r}\n" for t, a in zip(TIMES, ANGLES)) + "".join(
        f"elbow,{t!r},0,0,1,{a!r}\n" for t, a in zip(TIMES, ANGLES)))
    said = ""
    for report in ([], ["--report", "csv"], ["--report", "json"]):
        for files in (["two_tracks.csv", "knee_only.csv"], ["two_tracks.csv", "knee_only.csv", "right.csv"],
                      ["key.csv", "extra.csv"], ["key.csv", "frames4.csv"]):
            r = keyrot("compare", *files, *report, cwd=d)
            said += r.stdout + r.stderr
    check("ACTUAL" not in said and "EXPECTED" not in said and "only in the answer" in said and
          "missing from the answer" in said, "compare says 'answer' and 'key', never ACTUAL or EXPECTED")
    # Track names that differ only in case: one line and a hint, not a track missing and another extra
    r = keyrot("compare", "two_tracks.csv", "knee_only.csv", cwd=d)
    lines = r.stderr.splitlines()
    check(r.returncode == 1 and "knee_only.csv: track 'Knee' is the key's 'knee' in another case" in r.stderr and
          not any("'Knee' only in the answer" in line or "'knee' missing" in line for line in lines) and
          "track 'hip' missing from the answer" in r.stderr and "track 'elbow' only in the answer" in r.stderr and
          "the answer's track 'Knee' is the key's 'knee' in another case" in r.stdout,
          f"track names differing in case: a hint: {r.stdout.strip()} / {lines}")

    # The boundary: 0.99 and 1.01 of the tolerance, rotation and translation.
    write(os.path.join(d, "key_t.csv"), axis_angle_csv(ANGLES, translation=[0.5] * 5))
    for tol in (0.01, 0.5):
        for factor, grade in ((0.99, "pass"), (1.01, "fail")):
            write(os.path.join(d, "b.csv"), axis_angle_csv([a + tol * factor for a in ANGLES], translation=[0.5] * 5))
            r = keyrot("compare", "key_t.csv", "b.csv", "--tol", str(tol), cwd=d)
            check(r.returncode == (0 if grade == "pass" else 1), f"rotation {factor} x --tol {tol}: {grade}")
    for tol in (0.001, 0.25):
        for factor, grade in ((0.99, "pass"), (1.01, "fail")):
            write(os.path.join(d, "b.csv"), axis_angle_csv(ANGLES, translation=[0.5 + tol * factor] * 5))
            r = keyrot("compare", "key_t.csv", "b.csv", "--tol-translation", str(tol), cwd=d)
            check(r.returncode == (0 if grade == "pass" else 1), f"translation {factor} x --tol-translation {tol}: {grade}")
    r = keyrot("compare", "key.csv", "slightly_off.csv", "--tol", "0.004deg", cwd=d)
    check(r.returncode == 1, "--tol 0.004deg: 0.005 off fails")
    r = keyrot("compare", "key.csv", "slightly_off.csv", "--tol", "0.0001rad", cwd=d)
    check(r.returncode == 0, "--tol 0.0001rad (0.0057 deg): 0.005 off passes")

    # One answer: the summary line; an unreadable answer still gives JSON.
    r = keyrot("compare", "key.csv", "over.csv", cwd=d)
    check(r.returncode == 1 and r.stdout.startswith("5 rows compared, 5 failed"), f"one answer: the summary: {r.stdout!r}")
    r = keyrot("compare", "key.csv", "unreadable.csv", "--report", "json", cwd=d)
    doc = json.loads(r.stdout or "null")
    check(r.returncode == 2 and doc and "no time column" in doc.get("error", ""), "one unreadable answer: JSON with error")

    # Rows in one file only are named under that file, at its own frame numbers.
    write(os.path.join(d, "key4.csv"), "frame,time,ax,ay,az,angle\n" +
          "".join(f"{i},{t!r},0,0,1,{a!r}\n" for i, (t, a) in enumerate(zip(TIMES, ANGLES))))
    write(os.path.join(d, "a8.csv"), "frame,time,ax,ay,az,angle\n" +
          "".join(f"{i},{i / 8!r},0,0,1,{11.25 * i!r}\n" for i in range(9)))
    r = keyrot("compare", "a8.csv", "key4.csv", cwd=d)
    check("a8.csv: frame 1 (0.125 s): missing from the answer" in r.stderr,
          f"a row missing from the answer is named under the key's file: {r.stderr.strip().splitlines()[:2]}")

    # Times stored as 32-bit floats (a glTF file's, written out as decimals: the floats' own values, or
    # their shortest decimals, as keyrot writes them now) match their frames.
    times = [i / 30 for i in range(1, 6001)]
    f32 = [struct.unpack("f", struct.pack("f", t))[0] for t in times]

    def shortest(f):
        for digits in range(1, 10):
            if struct.unpack("f", struct.pack("f", float(f"{f:.{digits}g}")))[0] == f:
                return float(f"{f:.{digits}g}")
    write(os.path.join(d, "exact.csv"), axis_angle_csv([0.0] * len(times), times))
    write(os.path.join(d, "f32.csv"), axis_angle_csv([0.0] * len(times), f32))
    write(os.path.join(d, "f32_shortest.csv"), axis_angle_csv([0.0] * len(times), [shortest(f) for f in f32]))
    check(any(abs(a - b) > 1e-6 for a, b in zip(times, f32)), "(some float32 times are more than 1e-6 s off)")
    for name in ("f32.csv", "f32_shortest.csv"):
        r = keyrot("compare", "exact.csv", name, cwd=d)
        check(r.returncode == 0, f"float32 times ({name}) match their frames: {r.stdout.strip()}")

    # Hints outside compare.
    r = keyrot("slerp", "1,0,0,0", "0,0,0,1", "-t", "25", "-t", "50", cwd=d)
    check("outside [0, 1]" in r.stderr and "extrapolates" in r.stderr, "slerp -t 25: says it extrapolates")
    r = keyrot("slerp", "1,0,0,0", "0,0,0,1", "-t", "0.25,0.5,0.75", cwd=d)
    check(r.returncode == 0 and len(r.stdout.splitlines()) == 4, "slerp -t 0.25,0.5,0.75: three rows")
    write(os.path.join(d, "deg.csv"), axis_angle_csv([0, 90, 180, 270, 360]))
    r = keyrot("info", "deg.csv", "--radians", cwd=d)
    check("read as radians" in r.stderr, "--radians on degrees: a warning")
    r = keyrot("info", "deg.csv", cwd=d)
    check("radians" not in r.stderr, "degrees read as degrees: no warning")

    # A spreadsheet's "Unicode Text" (UTF-16, with or without a byte-order mark) is named as such.
    for name, text, encoding in (("u16.csv", "time\tqw\tqx\tqy\tqz\n0\t1\t0\t0\t0\n", "utf-16"),
                                 ("u16le.csv", "time,qw,qx,qy,qz\n0,1,0,0,0\n", "utf-16-le"),
                                 ("u16.json", '{"keys": [{"time": 0, "quat": [1, 0, 0, 0]}]}', "utf-16")):
        with open(os.path.join(d, name), "w", encoding=encoding) as f:
            f.write(text)
        r = keyrot("compare", "key.csv", name, cwd=d)
        check(r.returncode == 2 and "UTF-16" in r.stderr and "invalid UTF-8" not in r.stderr,
              f"{name} ({encoding}): named UTF-16: {r.stderr.strip()}")

    # Flag messages name the flag.
    r = keyrot("compare", "key.csv", "right.csv", "--tolerance", "0.1", cwd=d)
    check(r.returncode == 2 and "did you mean '--tol'" in r.stderr, f"--tolerance: did you mean --tol: {r.stderr.strip()}")
    r = keyrot("compare", "--fps", "4", "key.csv", "right.csv", cwd=d)
    check(r.returncode == 2 and "--fps" in r.stderr and "right.csv" not in r.stderr, f"compare --fps names the flag: {r.stderr.strip()}")
    r = keyrot("compare", "key.csv", "right.csv", "--tol", "0.1km", cwd=d)
    check(r.returncode == 2 and "0.1deg" in r.stderr, f"--tol 0.1km says how to write an angle: {r.stderr.strip()}")


def turn_rows(path, n, off_at=None):
    """n frames at 24 fps of a turn about z, 0.001 degrees a frame; frame `off_at` 0.5 degrees further."""
    with open(path, "w") as f:
        f.write("frame,time,ax,ay,az,angle\n")
        f.writelines(f"{i},{i / 24!r},0,0,1,{i * 0.001 + (0.5 if i == off_at else 0)!r}\n" for i in range(n))


# compare and info read a key at a time: a million rows take no more memory
# than a hundred thousand (by then the reading threads' queues are full),
# and at most 16 MB (unless a hundred thousand rows already take more: an
# AddressSanitizer build's floor).
with tempfile.TemporaryDirectory() as d:
    for n in (100000, 1000000):
        turn_rows(os.path.join(d, f"key{n}.csv"), n)
        turn_rows(os.path.join(d, f"answer{n}.csv"), n, off_at=n // 2)
    n = 1000000
    r = keyrot("compare", "key1000000.csv", "answer1000000.csv", cwd=d)
    check(r.returncode == 1 and r.stdout == "1000000 rows compared, 1 failed; largest difference 0.5 deg at frame "
          f"500000 ({500000 / 24!r} s)\n", f"compare of 1M rows: {r.stdout.strip()}")
    r = keyrot("info", "answer1000000.csv", cwd=d)
    check("  spacing: every 0.041667 s (24 keys/s)\n  largest step: 0.501 deg, keys 499999 to 500000 "
          "(20833.291667 s to 20833.333333 s), 12.024 deg/s\n" in r.stdout, f"info of 1M rows: {r.stdout.strip()}")
    runs = {"compare": ["compare", "key{}.csv", "answer{}.csv"],
            "compare --report csv": ["compare", "key{}.csv", "answer{}.csv", "--report", "csv"],
            "compare --report json": ["compare", "key{}.csv", "answer{}.csv", "--report", "json"],
            "info": ["info", "answer{}.csv"]}
    for what, args in runs.items():
        peaks = [peak_kb(KEYROT, [a.format(n) for a in args], cwd=d) for n in (100000, 1000000)]
        (_, small), (status, big) = peaks
        bounded = big <= small + 2048 and (small > 16384 or big <= 16384)
        check(status in (0, 1) and bounded, f"{what}: {small} KB for 100,000 rows, {big} KB for 1,000,000")

    # Files of two layouts: the key track after track, the answer's rows
    # interleaved (hip, knee, hip, ...), knee's frame 150 off by 0.5 degrees.
    def rows(track, f, off=0.0):
        return f"{track},{f},{f / 24!r},0,0,1,{f * 0.25 + off!r}\n"
    header = "track,frame,time,ax,ay,az,angle\n"
    write(os.path.join(d, "grouped.csv"), header + "".join(rows(t, f) for t in ("hip", "knee") for f in range(200)))
    write(os.path.join(d, "interleaved.csv"),
          header + "".join(rows(t, f, 0.5 if (t, f) == ("knee", 150) else 0) for f in range(200) for t in ("hip", "knee")))
    # A spreadsheet in a decimal-comma locale saves semicolons and decimal
    # commas: read as the same numbers (3,000 rows: parsed ahead on threads
    # as long files are); 0.5 degrees off at one frame fails there.
    for name, off_at in (("semicolons.csv", None), ("semicolons_off.csv", 1234)):
        turn_rows(os.path.join(d, "commas.csv"), 3000, off_at)
        with open(os.path.join(d, "commas.csv")) as f, open(os.path.join(d, name), "w") as g:
            g.writelines(line.replace(",", ";").replace(".", ",") for line in f)
    turn_rows(os.path.join(d, "key3000.csv"), 3000)
    r = keyrot("compare", "key3000.csv", "semicolons.csv", cwd=d)
    check(r.returncode == 0 and r.stdout.startswith("3000 rows compared, 0 failed"),
          f"a semicolon-separated answer with decimal commas: {r.stdout.strip()} {r.stderr.strip()}")
    r = keyrot("compare", "key3000.csv", "semicolons_off.csv", cwd=d)
    check(r.returncode == 1 and r.stdout.startswith("3000 rows compared, 1 failed; largest difference 0.5 deg at "
                                                     "frame 1234"), f"... and one 0.5 degrees off: {r.stdout.strip()}")
    for key, answer in (("grouped.csv", "interleaved.csv"), ("interleaved.csv", "grouped.csv")):
        r = keyrot("compare", key, answer, cwd=d)
        check(r.returncode == 1 and r.stdout.startswith("400 rows compared, 1 failed; largest difference 0.5 deg at "
                                                         "track knee frame 150"),
              f"compare {key} {answer}: {r.stdout.strip()}")

sys.exit(summary("grading_test"))
