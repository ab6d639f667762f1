#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# CLI tests: run the built keyrot as a user would and check output and status.
# Usage: cli_test.sh KEYROT DATA_DIR
set -u
keyrot=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=tests/expect.sh
source "$(dirname "$0")/expect.sh"

# The textbook example (identity to 90 degrees about z, halfway 45), resampled from the homework file.
expect "textbook example" 0 "frame,time,qx,qy,qz,qw
0,0,0,0,0,1
1,0.5,0,0,0.3827,0.9239
2,1,0,0,0.7071,0.7071" -- \
    "$keyrot" resample "$data/homework.json" --fps 2 --rep quat --quat-order xyzw --precision 4 --to csv

# The turntable: 45 degrees a frame at 2 fps, the whole turn.
expect "turntable" 0 "frame,time,ax,ay,az,angle
0,0,1,0,0,0
1,0.5,0,0,1,45
2,1,0,0,1,90
3,1.5,0,0,1,135
4,2,0,0,1,180
5,2.5,0,0,-1,135
6,3,0,0,-1,90
7,3.5,0,0,-1,45
8,4,1,0,0,0" -- "$keyrot" resample "$data/turntable.csv" --fps 2 --precision 9

# The head turn keyed as Euler frames: keys come back exactly at their frames.
expect "head turn keys" 0 "0,0,0,0,0
12,0.5,35,-5,2
20,0.8333333333333334,60,-10,4
36,1.5,45,8,0
48,2,0,0,0" -- bash -c "'$keyrot' resample '$data/head_turn.json' --rep euler --to csv --precision 4 | grep -E '^(0|12|20|36|48),'"

# Tracks and translations survive resampling; the knee has no translation.
expect "walk tracks" 0 "track,frame,time,qw,qx,qy,qz,tx,ty,tz
hip,0,0,1,0,0,0,0,0.95,0
hip,1,0.5,0.9962,0,0.0872,0,0.4,0.97,0
hip,2,1,1,0,0,0,0.8,0.95,0
knee,0,0,0.9659,0.2588,0,0,,,
knee,1,0.5,0.9914,0.1305,0,0,,,
knee,2,1,0.9659,0.2588,0,0,,," -- "$keyrot" resample "$data/walk.csv" --fps 2 --rep quat --precision 4

# (The examples of the README and the user guide are run by docs_test.py.)

# stdin, sniffed as JSON; output in the input's format
expect "stdin json" 0 '{"fps": 1, "method": "slerp", "rep": "rotvec", "angles": "radians", "frames": [
{"frame": 0, "time": 0, "rotvec": [0, 0, 0]},
{"frame": 1, "time": 1, "rotvec": [0, 0, 1.5708]}]}' -- \
    bash -c "'$keyrot' resample --fps 1 --rep rotvec --radians --precision 4 < '$data/homework.json'"

# A track whose lone key is off the frame grid has no frame: the JSON
# document leaves it out as CSV does, and reads back (found by fuzz_formats)
printf 'track,time,qw,qx,qy,qz\na,0,1,0,0,0\na,1,0,1,0,0\nb,0.081,1,0,0,0\n' > "$work/lone.csv"
expect "lone key off the grid, json" 0 '{"fps": 2, "method": "slerp", "rep": "quat", "angles": "degrees", "quat_order": "wxyz", "tracks": {
"a": {"frames": [
{"frame": 0, "time": 0, "quat": [1, 0, 0, 0]},
{"frame": 1, "time": 0.5, "quat": [0.7071, 0.7071, 0, 0]},
{"frame": 2, "time": 1, "quat": [0, 1, 0, 0]}]}}}' -- \
    "$keyrot" resample "$work/lone.csv" --fps 2 --rep quat --precision 4 --to json
expect "lone key off the grid, json read back" 0 "track,frame,time,qw,qx,qy,qz
a,0,0,1,0,0,0
a,1,0.5,0.7071,0.7071,0,0
a,2,1,0,1,0,0" -- bash -c "'$keyrot' resample '$work/lone.csv' --fps 2 --rep quat --precision 4 --to json |
    '$keyrot' convert --from json --to csv --rep quat --precision 4"

# Errors: one line, status 2, nothing on stdout
printf 'time,qw,qx,qy,qz\n0,1,0,0,0\n0.5,abc,0,0,0\n' > "$work/bad.csv"
expect_error "bad number" "keyrot: $work/bad.csv:3: column 'qw': expected a finite number, got 'abc'" -- \
    "$keyrot" resample "$work/bad.csv"
expect_error "missing file" "keyrot: cannot read '$work/nope.csv': No such file or directory" -- \
    "$keyrot" resample "$work/nope.csv"
expect_error "bad fps" "keyrot: --fps: expected a positive frame rate, got 0" -- "$keyrot" resample --fps 0 "$data/turntable.csv"
# A rotation vector too long for the squares of its components (fuzz_csv's
# finding): 1e200 / 2 degrees is 64 past whole turns (Python's Fraction).
expect "huge rotation vector" 0 "time,qw,qx,qy,qz
0,0.438371146789,0,0,0.898794046299" -- \
    bash -c "printf 'time,rx,ry,rz\n0,0,0,1e200\n' | '$keyrot' convert --from csv --rep quat --precision 12"

# JSON tracks come out in the document's order (the spec's "in input order"),
# also when a track name with an escape sends the document to nlohmann-json.
for name in zeta 'z\u0065ta'; do
    expect "JSON tracks in input order ($name)" 0 "track,time,qw,qx,qy,qz
zeta,0,1,0,0,0
alpha,0,0,0,0,1" -- \
        bash -c "printf '%s' '{\"tracks\": {\"$name\": [{\"time\": 0, \"quat\": [1, 0, 0, 0]}], \"alpha\": [{\"time\": 0, \"quat\": [0, 0, 0, 1]}]}}' | '$keyrot' convert --from json --to csv --rep quat"
done

# --max-frames: 10 s at 24 fps is 241 frames.
printf 'time,qw,qx,qy,qz\n0,1,0,0,0\n10,0,0,0,1\n' > "$work/ten_seconds.csv"
expect_error "over --max-frames" "keyrot: $work/ten_seconds.csv:3: keys from 0 s to 10 s make 241 frames at 24 fps: \
expected at most 240 (--max-frames N raises the limit)" -- "$keyrot" resample --max-frames 240 "$work/ten_seconds.csv"
expect "at --max-frames" 0 "241" -- bash -c "'$keyrot' resample --max-frames 241 '$work/ten_seconds.csv' | grep -vc '^[#f]'"
expect_error "bad --max-frames" "keyrot: --max-frames: expected a number of frames, at least 1, got 0.5" -- \
    "$keyrot" resample --max-frames 0.5 "$work/ten_seconds.csv"
expect_error "euler without sequence" "keyrot: --method euler needs an Euler sequence: expected --euler SEQ" -- \
    "$keyrot" resample --method euler "$data/turntable.csv"
expect_error "several files" "keyrot: several input files need --output-dir DIR" -- \
    "$keyrot" convert "$data/turntable.csv" "$data/walk.csv"

# An error never replaces an existing output file.
echo precious > "$work/out.csv"
"$keyrot" resample "$work/bad.csv" -o "$work/out.csv" 2>/dev/null
expect "output untouched" 0 "precious" -- cat "$work/out.csv"

# Batch: the bad file is reported, the others are written, status 2.
cp "$data/turntable.csv" "$data/walk.csv" "$work/"
"$keyrot" convert "$work/turntable.csv" "$work/bad.csv" "$work/walk.csv" --output-dir "$work/out" --to json 2>"$work/batch.err"
expect "batch status" 2 "" -- bash -c "exit $?"
expect "batch files" 0 "turntable.json
walk.json" -- ls "$work/out"

# ---- slerp: textbook worked examples
expect "textbook slerp" 0 "t,qx,qy,qz,qw
0.5,0,0,0.3827,0.9239" -- \
    "$keyrot" slerp --quat-order xyzw 0,0,0,1 0,0,0.7071067811865476,0.7071067811865476 -t 0.5 --rep quat --precision 4
# The power form's route: axis-angle in, (q r^-1)^a r, axis-angle out. Halfway between
# 90 about x and 90 about y is 2 acos(sqrt(2/3)) = 70.52877936550931 about (1,1,0)/sqrt 2.
expect "power form route" 0 "t,ax,ay,az,angle
0.5,0.707106781187,0.707106781187,0,70.528779365509" -- \
    "$keyrot" slerp --from-rep axis-angle 1,0,0,90 0,1,0,90 -t 0.5 --precision 12
# -170 -> 160 degrees about z, the classic Euler-angle pitfall: the short way through 180, or the long way through 0
expect "short way" 0 "t,ax,ay,az,angle
0,0,0,-1,170
0.5,0,0,1,175
1,0,0,1,160" -- "$keyrot" slerp --from-rep axis-angle 0,0,1,-170 0,0,1,160 --steps 2 --precision 6
expect "long way" 0 "t,ax,ay,az,angle
0,0,0,-1,170
0.5,0,0,-1,5
1,0,0,1,160" -- "$keyrot" slerp --from-rep axis-angle 0,0,1,-170 0,0,1,160 --steps 2 --path direct --precision 6
# a quarter of the way to 180 degrees about z is 45
expect "slerp json" 0 '{"method": "slerp", "rep": "rotvec", "angles": "degrees", "frames": [
{"t": 0, "rotvec": [0, 0, 0]},
{"t": 0.25, "rotvec": [0, 0, 45]}]}' -- "$keyrot" slerp 1,0,0,0 0,0,0,1 -t 0 -t 0.25 --rep rotvec --to json --precision 9
expect_error "slerp needs t" "keyrot: slerp needs -t T or --steps N" -- "$keyrot" slerp 1,0,0,0 0,0,0,1
expect_error "slerp steps 0" "keyrot: --steps: expected at least 1, got 0" -- "$keyrot" slerp 1,0,0,0 0,0,0,1 --steps 0
expect_error "slerp operand" "keyrot: Q1: expected 4 comma-separated numbers (w,x,y,z, --from-rep quat), got '0,0,1'" -- \
    "$keyrot" slerp 1,0,0,0 0,0,1 -t 0.5
expect_error "slerp zero" "keyrot: Q0: quaternion is zero: expected a non-zero quaternion" -- \
    "$keyrot" slerp 0,0,0,0 0,0,0,1 -t 0.5

# ---- compare: a key at 4 fps and answers in other representations
"$keyrot" resample "$data/homework.json" --fps 4 --to csv -o "$work/key.csv"
"$keyrot" convert "$work/key.csv" --rep matrix -o "$work/matrix.csv"
"$keyrot" convert "$work/key.csv" --rep quat --to json -o "$work/quat.json"
sed -E 's/"quat": \[([^,]+), ([^,]+), ([^,]+), ([^]]+)\]/"quat": [-\1, -\2, -\3, -\4]/' "$work/quat.json" | sed 's/--//g' > "$work/negated.json"
"$keyrot" convert "$work/key.csv" --rep axis-angle --precision 17 | awk -F, -v OFS=, 'NR==4{$6=$6+0.5}{print}' > "$work/off.csv"
grep -v '^3,' "$work/key.csv" > "$work/missing.csv"
printf 'frame,time,qw,qx,qy,qz\n0,0,1,0,0,0\n1,0.25,x,0,0,0\n' > "$work/malformed.csv"
expect "compare exact in matrices" 0 "5 rows compared, 0 failed; largest difference 0 deg at frame 0 (0 s)" -- \
    "$keyrot" compare "$work/key.csv" "$work/matrix.csv"
expect "compare negated" 0 "5 rows compared, 0 failed; largest difference 0 deg at frame 0 (0 s)" -- \
    "$keyrot" compare "$work/key.csv" "$work/negated.json"
# a glTF file names the node of the key's unnamed track: still the same track
"$keyrot" convert "$work/key.csv" -o "$work/key.glb"
expect "compare with its glTF" 0 "5 rows compared, 0 failed" -- \
    bash -c "'$keyrot' compare '$work/key.csv' '$work/key.glb' | cut -d';' -f1"
# glb is binary: a terminal (script(1) gives the command one) gets one line
# and status 2 instead, as gzip refuses; a pipe, or -o /dev/stdout, gets it.
expect "glb not to a terminal" 2 "keyrot: glb is binary, and standard output is a terminal: expected -o FILE.glb, a pipe or > FILE (--to gltf writes text; -o /dev/stdout writes glb here all the same)" -- \
    bash -c "script -qec \"'$keyrot' convert '$work/key.csv' --to glb\" /dev/null | tr -d '\r'; exit \${PIPESTATUS[0]}"
expect "glb to a terminal named" 0 "glTF" -- \
    bash -c "script -qec \"'$keyrot' convert '$work/key.csv' --to glb -o /dev/stdout\" /dev/null | head -c 4"
expect "glb through a pipe" 0 "glTF" -- bash -c "'$keyrot' convert '$work/key.csv' --to glb | head -c 4"
expect "compare 0.5 off" 1 "5 rows compared, 1 failed; largest difference 0.5 deg at frame 2 (0.5 s)" -- \
    "$keyrot" compare "$work/key.csv" "$work/off.csv"
expect "compare 0.5 off reason" 1 "keyrot: $work/off.csv: frame 2 (0.5 s): rotation differs by 0.5 deg (tolerance 0.01)" -- \
    bash -c "'$keyrot' compare '$work/key.csv' '$work/off.csv' 2>&1 >/dev/null"
expect "compare tol 1" 0 "5 rows compared, 0 failed; largest difference 0.5 deg at frame 2 (0.5 s)" -- \
    "$keyrot" compare "$work/key.csv" "$work/off.csv" --tol 1
expect "compare missing row" 1 "5 rows compared, 1 failed; largest difference 0 deg at frame 0 (0 s)" -- \
    "$keyrot" compare "$work/key.csv" "$work/missing.csv"
expect_error "compare malformed" "keyrot: $work/malformed.csv:3: column 'qw': expected a finite number, got 'x'" -- \
    "$keyrot" compare "$work/key.csv" "$work/malformed.csv"
expect "compare json" 1 '{"rows": 5, "failed": 1, "max_difference": 0.5}' -- bash -c \
    "'$keyrot' compare '$work/key.csv' '$work/off.csv' --report json 2>/dev/null | /usr/bin/env python3 -c 'import json,sys; d=json.load(sys.stdin); print(json.dumps({\"rows\": d[\"rows\"], \"failed\": d[\"failed\"], \"max_difference\": round(d[\"max_difference\"], 9)})); sys.exit(1 if d[\"failed\"] else 0)'"
expect "grader loop" 0 "$work/matrix.csv ok
$work/negated.json ok" -- bash -c "for f in '$work/matrix.csv' '$work/negated.json' '$work/off.csv'; do '$keyrot' compare '$work/key.csv' \"\$f\" >/dev/null 2>&1 && echo \"\$f ok\"; done; true"

# ---- info
expect "info nlerp speed" 0 "  0-1      15.63        125.07
  3-4      23.69        189.56" -- bash -c \
    "'$keyrot' resample '$data/wide_turn.csv' --fps 8 --method nlerp | '$keyrot' info --segments --precision 2 | grep -E '^  (0-1|3-4) '"
expect "info flips" 0 "  0-1      90           180  (long way with --path direct)
  quaternion keys of the other sign than the one before: 1" -- bash -c \
    "printf 'time,qw,qx,qy,qz\n0,1,0,0,0\n0.5,-0.7071067811865476,0,0,-0.7071067811865476\n' | '$keyrot' info --segments | grep -E '0-1|sign'"
expect "info names the rate frame numbers count at" 0 "  frame numbers: at 24 fps, the default (--key-fps RATE for another)
track: 2 keys, 0 s to 0.4 s, given as quat
  frame numbers: at 30 fps, as stated" -- bash -c \
    "printf 'frame,qw,qx,qy,qz\n0,1,0,0,0\n12,0,0,0,1\n' > '$work/frames.csv'
     '$keyrot' info '$work/frames.csv' | grep 'frame numbers'; '$keyrot' info '$work/frames.csv' --key-fps 30 | sed -n 2,3p"
# The summary: 0, 10, 40 and 45 degrees about z at 0, 1, 2 and 2.5 s step
# by 10, 30 and 5 degrees; 24 keys of one rotation with every other sign
# flipped list the first ten flips of 23 (each key against the one before);
# one key given with the other sign lists it and the next; Euler angles
# past +-180 flip no sign the file gave (no line); slerp has no acceleration.
expect "info's summary" 0 "  spacing: 0.5 s to 1 s (1.2 keys/s on average)
  largest step: 30 deg, keys 1 to 2 (1 s to 2 s), 30 deg/s
  quaternion keys of the other sign than the one before: 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, ... (23 in all)
  quaternion keys of the other sign than the one before: 5, 6
0
0" -- bash -c \
    "{ printf 'time,ax,ay,az,angle\n0,0,0,1,0\n1,0,0,1,10\n2,0,0,1,40\n2.5,0,0,1,45\n' | '$keyrot' info | grep -E 'spacing|largest'
       awk 'BEGIN { print \"time,qw,qx,qy,qz\"; for (i = 0; i < 24; i++) print i \",\" (i % 2 ? -1 : 1) \",0,0,0\" }' |
           '$keyrot' info | grep sign
       awk 'BEGIN { print \"time,qw,qx,qy,qz\"; for (i = 0; i < 12; i++) print i \",\" (i == 5 ? -1 : 1) \",0,0,0\" }' |
           '$keyrot' info | grep sign
       '$keyrot' info '$data/capture.bvh' | grep -c sign
       '$keyrot' info '$data/capture.bvh' | grep -c acceleration; true; }"

expect "help" 0 "0" -- bash -c "'$keyrot' --help >/dev/null; echo \$?"
expect "version" 0 "keyrot 0.1.0" -- "$keyrot" --version

summary
