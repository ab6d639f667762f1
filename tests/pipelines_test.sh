#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Pipelines: keyrot's outputs read back into keyrot with the same meaning
# and no flags, through real pipes, FIFOs, process substitution and batches.
# Usage: pipelines_test.sh KEYROT DATA_DIR
set -u
keyrot=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=tests/expect.sh
source "$(dirname "$0")/expect.sh"
cd "$work" || exit 1

# expect_pass NAME ROWS -- COMMAND...: a compare that matched ROWS rows, all within tolerance
expect_pass() {
    local name=$1 rows=$2
    shift 3
    local got rc
    got=$("$@" 2>"$work/stderr")
    rc=$?
    if [[ $rc == 0 && $got == "$rows rows compared, 0 failed;"* ]]; then
        passed=$((passed + 1))
    else
        fail "$name: status $rc, [$got], stderr [$(cat "$work/stderr")]"
    fi
}

# ---- every output, read back with no flags: each format, representation and unit
printf 'track,time,qw,qx,qy,qz,tx,ty,tz,sx,sy,sz\nhip,0,1,0,0,0,0,1,0,,,\nhip,0.5,0.5,0.5,0.5,0.5,1,1,0,1,2,3
hip,1,0,0.6,0,0.8,2,1,0,1,1,1\nknee,0,0.9,0.1,0.3,0.3,,,,0.5,0.5,0.5\nknee,1,0.5,-0.5,0.5,0.5,,,,,,\n' > walk.csv
"$keyrot" resample walk.csv --fps 10 --rep quat > direct.csv
# (Euler angles in CSV and NDJSON do not carry their sequence, which has no
# default: read back without --euler they are refused, naming it.)
for to in csv json ndjson; do
    for rep in quat axis-angle rotvec euler matrix matrix4; do
        sequence=""
        [[ $rep == euler && $to != json ]] && sequence="--euler xyz"
        for unit in "" --radians; do
            # shellcheck disable=SC2086
            expect_pass "read back: $to $rep $unit" 22 -- bash -c \
                "'$keyrot' resample walk.csv --fps 10 --to $to --rep $rep --out-euler xyz --quat-order xyzw $unit |
                 '$keyrot' compare direct.csv - --tol 1e-9 $sequence"
        done
    done
done
for to in csv ndjson; do
    expect_error "Euler $to read back without --euler" "keyrot: <stdin>:$([[ $to == csv ]] && echo 2 || echo 1): Euler angles need a sequence: expected --euler SEQ or an \"euler\" field" -- \
        bash -c "'$keyrot' resample walk.csv --fps 10 --to $to --rep euler --out-euler xyz 2>/dev/null | '$keyrot' convert"
done
# and through convert, with no flags on the second command but the sequence
for to in csv json ndjson; do
    sequence="--euler xyz"
    [[ $to == json ]] && sequence=""
    expect_pass "convert chain: $to euler xyz radians" 22 -- bash -c \
        "'$keyrot' resample walk.csv --fps 10 --rep euler --out-euler xyz --radians --to $to | '$keyrot' convert $sequence |
         '$keyrot' compare direct.csv - --tol 1e-9"
done

# two NDJSON outputs one after the other read as one document; with other settings, an error that says so
printf 'track,time,qw,qx,qy,qz\nhip,0,1,0,0,0\nhip,1,0,0,0,1\n' > hip.csv
printf 'track,time,qw,qx,qy,qz\nknee,0,1,0,0,0\nknee,1,0,1,0,0\n' > knee.csv
expect "cat of two NDJSON outputs" 0 "hip 3
knee 3" -- bash -c "cat <('$keyrot' resample hip.csv --fps 2 --to ndjson) <('$keyrot' resample knee.csv --fps 2 --to ndjson) |
    '$keyrot' info --to json | /usr/bin/env python3 -c 'import json,sys; [print(t[\"name\"], t[\"keys\"]) for t in json.load(sys.stdin)[\"tracks\"]]'"
expect "cat of NDJSON outputs at two rates" 0 "hip 3
knee 4" -- bash -c "cat <('$keyrot' resample hip.csv --fps 2 --to ndjson) <('$keyrot' resample knee.csv --fps 3 --to ndjson) |
    '$keyrot' info --to json | /usr/bin/env python3 -c 'import json,sys; [print(t[\"name\"], t[\"keys\"]) for t in json.load(sys.stdin)[\"tracks\"]]'"
expect_error "cat of NDJSON outputs stating two rates" "keyrot: <stdin>:5: a header line with other settings than the first: expected the lines of one document (keyrot outputs made with other settings cannot be joined)" -- \
    bash -c "cat <('$keyrot' resample hip.csv --fps 2 --to ndjson --settings-line always) <('$keyrot' resample knee.csv --fps 3 --to ndjson --settings-line always) | '$keyrot' info"

# ---- the key rate travels with frame-numbered keys
printf 'frame,qw,qx,qy,qz\n0,1,0,0,0\n15,0.9238795325112867,0,0,0.3826834323650898\n30,0.7071067811865476,0,0,0.7071067811865476\n' > anim.csv
"$keyrot" resample anim.csv --key-fps 30 > anim_direct.csv
for to in csv json ndjson; do
    # A 1 s clip stays 1 s: 25 frames at 24 fps, the last at 1 s and 90 degrees.
    expect "key rate through convert --to $to" 0 "24,1,0,0,1,90" -- bash -c \
        "'$keyrot' convert anim.csv --key-fps 30 --to $to | '$keyrot' resample - --to csv | tail -n 1"
    expect_pass "key rate chain --to $to" 25 -- bash -c \
        "'$keyrot' convert anim.csv --key-fps 30 --to $to | '$keyrot' resample - | '$keyrot' compare anim_direct.csv -"
done
expect "a conflicting flag is named" 0 "keyrot: warning: <stdin>: frame 15 is 0.625 s at --key-fps 24, where the file says 0.5 s: frames are timed at --key-fps (<stdin>:3)" -- bash -c \
    "'$keyrot' convert anim.csv --key-fps 30 | '$keyrot' resample - --key-fps 24 2>&1 >/dev/null"
expect "a file's own rate is named against a flag" 0 "keyrot: warning: <stdin>: the file's 'fps' is used, not --key-fps 24" -- bash -c \
    "'$keyrot' convert anim.csv --key-fps 30 --to json | '$keyrot' resample - --key-fps 24 2>&1 >/dev/null"
expect "convert of frames at two rates: each key with its time" 0 "track,frame,time,qw,qx,qy,qz
a,30,1,1,0,0,0
b,24,1,1,0,0,0" -- bash -c \
    "printf '%s' '{\"tracks\": {\"a\": {\"fps\": 30, \"keys\": [{\"frame\": 30, \"quat\": [1,0,0,0]}]}, \"b\": {\"fps\": 24, \"keys\": [{\"frame\": 24, \"quat\": [1,0,0,0]}]}}}' |
     '$keyrot' convert --from json --to csv --rep quat"

# ---- frame numbers count at 24 fps unless stated, whatever --fps is: resampling keeps times
head_turn=$data/head_turn.json  # frames 0 to 48: 0 s to 2 s
rate_warning="keyrot: warning: $head_turn: frame numbers count at 24 fps (the default, whatever --fps is): --key-fps RATE reads them at another"
for fps in 30 120 5; do
    expect "head_turn at --fps $fps ends at 2 s" 0 "$((2 * fps)),2" -- bash -c \
        "'$keyrot' resample '$head_turn' --fps $fps --to csv | tail -n 1 | cut -d, -f1,2"
    expect "head_turn at --fps $fps: one warning naming --key-fps" 0 "$rate_warning" -- bash -c \
        "'$keyrot' resample '$head_turn' --fps $fps 2>&1 >/dev/null"
done
expect "no warning at --fps 24, with --key-fps, or for times" 0 "" -- bash -c \
    "{ '$keyrot' resample '$head_turn' && '$keyrot' resample '$head_turn' --fps 30 --key-fps 24 &&
       '$keyrot' resample '$data/walk.csv' --fps 30 && '$keyrot' convert '$head_turn'; } 2>&1 >/dev/null"
mkdir -p batch_in && cp "$head_turn" "$data/walk.csv" batch_in/
expect "a batch keeps head_turn's 2 s" 0 "keyrot: warning: batch_in/head_turn.json: frame numbers count at 24 fps (the default, whatever --fps is): --key-fps RATE reads them at another
[60,2]" -- bash -c "'$keyrot' resample batch_in/* --fps 30 --output-dir out30 2>&1 &&
    jq -c '.frames[-1] | [.frame, .time]' out30/head_turn.json"
# every command reads frame 48 as 2 s
expect "info reads frame 48 as 2 s" 0 "track: 5 keys, 0 s to 2 s, given as euler" -- bash -c \
    "'$keyrot' info '$head_turn' | sed -n 2p"
expect "convert keeps frame 48 with its time, and states no rate it assumed" 0 '{"frame": 48, "time": 2, "axis": [1, 0, 0], "angle": 0}]}
0' -- bash -c \
    "'$keyrot' convert '$head_turn' --to json | tail -n 1 && '$keyrot' convert '$head_turn' --to json | grep -c fps; true"
expect "reduce keeps frame 48" 0 "48" -- bash -c "'$keyrot' reduce '$head_turn' --to csv 2>/dev/null | tail -n 1 | cut -d, -f1"
printf 'time,e1,e2,e3\n0,0,0,0\n0.5,35,-5,2\n0.8333333333333334,60,-10,4\n1.5,45,8,0\n2,0,0,0\n' > head_turn_times.csv
expect_pass "compare: the frames at the times 24 fps gives them" 5 -- \
    "$keyrot" compare "$head_turn" head_turn_times.csv --euler ZYX --tol 1e-9
# a rate assumed upstream never overrides one typed downstream: the frames
# are timed at it, and the times written from the assumption get a warning
printf 'frame,qw,qx,qy,qz\n0,1,0,0,0\n30,0.7071067811865476,0,0,0.7071067811865476\n' > frames30.csv
for to in csv json ndjson; do
    expect "convert --to $to | resample --key-fps 30: 1 s" 0 "1
24,1,0,0,1,90" -- bash -c \
        "'$keyrot' convert frames30.csv --to $to | '$keyrot' resample - --key-fps 30 --to csv 2>&1 | grep -c 'timed at --key-fps' &&
         '$keyrot' convert frames30.csv --to $to | '$keyrot' resample - --key-fps 30 --to csv 2>/dev/null | tail -n 1"
done

# ---- slerp's table reads back
expect_pass "slerp into compare" 5 -- bash -c \
    "'$keyrot' slerp 1,0,0,0 0.7071067811865476,0,0,0.7071067811865476 --steps 4 > key.csv &&
     '$keyrot' compare key.csv <('$keyrot' slerp 0,0,0,1 0,0,0.7071067811865476,0.7071067811865476 --quat-order xyzw --steps 4 --to json)"
expect "slerp into convert" 0 "0.5,0,0,1,45" -- bash -c \
    "'$keyrot' slerp 1,0,0,0 0.7071067811865476,0,0,0.7071067811865476 --steps 2 | '$keyrot' convert --precision 9 | sed -n 3p"

# ---- compare at two frame rates: by time
printf '{"keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "axis": [0, 0, 1], "angle": 90}]}' > homework.json
"$keyrot" resample homework.json --fps 4 --to csv > key4.csv
"$keyrot" resample homework.json --fps 8 --to csv > answer8.csv
expect "4 fps key, 8 fps answer: only the extra rows fail" 1 "9 rows compared, 4 failed; largest difference 0 deg at frame 0 (0 s)" -- \
    "$keyrot" compare key4.csv answer8.csv
expect "4 fps key, 8 fps answer: rates named, no difference claimed" 0 "keyrot: key4.csv counts frames at 4 fps, answer8.csv at 8 fps: rows are matched by time
keyrot: answer8.csv: frame 1 (0.125 s): only in the answer" -- bash -c \
    "'$keyrot' compare key4.csv answer8.csv 2>&1 >/dev/null | head -n 2"
expect "no word of rates where one file has no frames" 0 "" -- bash -c \
    "'$keyrot' compare <('$keyrot' slerp 1,0,0,0 0.7071067811865476,0,0,0.7071067811865476 --steps 4) key4.csv 2>&1 >/dev/null"
expect "a misnamed track, said once" 0 "keyrot: b.json: track 'Hip' missing from the answer
keyrot: b.json: track 'Hips' only in the answer" -- bash -c \
    "printf '{\"tracks\": {\"Hip\": [{\"time\": 0, \"quat\": [1,0,0,0]}, {\"time\": 1, \"quat\": [1,0,0,0]}]}}' > a.json &&
     printf '{\"tracks\": {\"Hips\": [{\"time\": 0, \"quat\": [1,0,0,0]}, {\"time\": 1, \"quat\": [1,0,0,0]}]}}' > b.json &&
     '$keyrot' compare a.json b.json 2>&1 >/dev/null; true"

# ---- --precision rounds values, not times; at a key's time, the key
expect "precision keeps times" 0 "3,0.375,0.9569,0,0,0.2903" -- bash -c \
    "'$keyrot' resample homework.json --fps 8 --to csv --rep quat --precision 4 | sed -n 5p"
printf 'time,ax,ay,az,angle\n0,0,0,1,0\n1,0,0,1,0\n1.000000000001,0,0,1,90\n2,0,0,1,90\n' > close.csv
expect "keys 1e-12 s apart: frame 1 is the key at 1 s" 0 "1,1,1,0,0,0" -- bash -c \
    "'$keyrot' resample close.csv --fps 1 | sed -n 3p"
printf 'time,ax,ay,az,angle\n0,0,0,1,0\n1e-12,0,0,1,90\n' > close_start.csv
expect "keys at 0 and 1e-12 s: frame 0 is the key at 0" 0 "0,0,1,0,0,0" -- bash -c \
    "'$keyrot' resample close_start.csv --fps 1 | sed -n 2p"
printf 'time,qw,qx,qy,qz,tx,ty,tz\n0,1,0,0,0,0,0,0\n0.999999999999,1,0,0,0,5,5,5\n1,1,0,0,0,1,1,1\n' > close_translation.csv
expect "translation at a key's exact time" 0 "1,1,1,0,0,0,1,1,1" -- bash -c \
    "'$keyrot' resample close_translation.csv --fps 1 | sed -n 3p"

# ---- inputs that cannot be read twice are read as standard input is
"$keyrot" resample walk.csv --fps 10 > walk10.csv
expect_pass "process substitution" 22 -- bash -c "'$keyrot' compare walk10.csv <('$keyrot' resample walk.csv --fps 10 --to ndjson)"
expect_pass "/dev/stdin" 22 -- bash -c "'$keyrot' resample walk.csv --fps 10 | '$keyrot' compare walk10.csv /dev/stdin"
mkfifo fifo.csv
expect_pass "a named pipe" 22 -- timeout 60 bash -c "('$keyrot' resample walk.csv --fps 10 > fifo.csv &) ; '$keyrot' compare walk10.csv fifo.csv"

# ---- batches never lose a file or replace an input
mkdir -p a b out
cp walk.csv a/track.csv
"$keyrot" convert walk.csv --to json > b/track.json
expect_error "two inputs, one output name" "keyrot: --output-dir out: 'a/track.csv' and 'b/track.json' would both be written to 'out/track.csv': expected inputs with distinct names" -- \
    "$keyrot" convert a/track.csv b/track.json --output-dir out --to csv
expect "nothing written before the error" 0 "" -- ls out
expect_error "an output would replace its input" "keyrot: --output-dir .: the output of 'self.csv' would replace the input 'self.csv'" -- \
    bash -c "cp walk.csv self.csv && '$keyrot' convert self.csv --output-dir ."
expect "the input kept" 0 "" -- cmp self.csv walk.csv
expect "distinct formats, distinct names" 0 "track.csv
track.json" -- bash -c "'$keyrot' convert a/track.csv b/track.json --output-dir out && ls out"

# ---- JSON: duplicate names are errors, unknown fields are named
expect_error "duplicate track" "keyrot: <stdin>:1: tracks: 'a' appears twice: expected each name once in an object" -- bash -c \
    "printf '{\"tracks\": {\"a\": [{\"time\": 0, \"quat\": [1,0,0,0]}], \"a\": [{\"time\": 1, \"quat\": [1,0,0,0]}]}}' | '$keyrot' convert"
printf '{"keys": [{"time": 0, "quat": [1,0,0,0], "translaton": [1,2,3]}]}' > typo.json
expect "a misspelt field warns" 0 "keyrot: warning: typo.json: ignoring unknown field 'translaton' (typo.json: keys[0])" -- bash -c \
    "'$keyrot' convert typo.json 2>&1 >/dev/null"
expect_error "a misspelt field, --strict" "keyrot: typo.json: keys[0]: unknown field 'translaton': expected only fields keyrot reads (--strict)" -- \
    "$keyrot" convert typo.json --strict
expect "a misspelt document field warns" 0 "keyrot: warning: <stdin>: ignoring unknown field 'quatorder' (<stdin>: document)" -- bash -c \
    "printf '{\"quatorder\": \"xyzw\", \"keys\": [{\"time\": 0, \"quat\": [0,0,0,1]}]}' | '$keyrot' convert 2>&1 >/dev/null"
expect "a misspelt NDJSON field warns" 0 "keyrot: warning: <stdin>: ignoring unknown field 'angle_unit' (<stdin>:1)" -- bash -c \
    "printf '{\"time\": 0, \"rotvec\": [0,0,1], \"angle_unit\": \"radians\"}\n' | '$keyrot' convert 2>&1 >/dev/null"

# ---- one rule for numbers in CSV and JSON: too small is 0, too large an error
expect "1e-400 in CSV and JSON alike" 0 "0,1,0,0,0
0,1,0,0,0" -- bash -c "printf 'time,qw,qx,qy,qz\n0,1,1e-400,0,0\n' | '$keyrot' convert --rep quat | tail -n 1 &&
    printf '{\"keys\": [{\"time\": 0, \"quat\": [1, 1e-400, 0, 0]}]}' | '$keyrot' convert --rep quat --to csv | tail -n 1"

# ---- every flag a command lists does what it says
# Warnings in one order whatever the target: the input's (a quaternion of
# norm 2 at line 6), then the output's (gimbal lock at 0.5 s, written
# before line 6 is read when the output streams into a file).
{ printf 'time,qw,qx,qy,qz\n0,1,0,0,0\n0.5,0.7071067811865476,0,0.7071067811865476,0\n1,1,0,0,0\n1.5,1,0,0,0\n2,2,0,0,0\n'
  for i in $(seq 3 3000); do echo "$i,1,0,0,0"; done; } > order.csv
for to in csv json ndjson; do
    expect "warnings in one order, $to" 0 "same
keyrot: warning: order.csv: quaternion norm 2 differs from 1 by more than 0.001 (order.csv:6); such keys are normalised
keyrot: warning: order.csv: gimbal lock in Euler sequence ZYX: the third angle is set to 0" -- bash -c \
        "'$keyrot' resample order.csv --rep euler --out-euler ZYX --to $to 2> e_stdout.txt > /dev/null
         '$keyrot' resample order.csv --rep euler --out-euler ZYX -o order_out.$to 2> e_file.txt
         rm -rf order_dir; '$keyrot' resample order.csv --rep euler --out-euler ZYX --to $to --output-dir order_dir 2> e_dir.txt
         cmp -s e_stdout.txt e_file.txt && cmp -s e_file.txt e_dir.txt && echo same; cat e_file.txt"
done
expect "info -o info.json writes JSON" 0 "walk.csv 2" -- bash -c \
    "'$keyrot' info walk.csv -o info.json && /usr/bin/env python3 -c 'import json; d = json.load(open(\"info.json\")); print(d[\"source\"], len(d[\"tracks\"]))'"
# (arm_wave's samplers: shoulder's rotation and translation LINEAR, the wrist's rotation STEP)
expect "info names each channel as played" 0 "  interpolation: rotation slerp, translation linear
  interpolation: rotation step" -- bash -c "'$keyrot' info '$data/arm_wave.gltf' | grep -E '^  interpolation: (rotation slerp, translation|rotation step)'"
expect_error "info --to csv" "keyrot: info: --to: csv not in {json} (see keyrot info --help)" -- "$keyrot" info walk.csv --to csv
expect_error "compare --rep" "keyrot: compare: The following argument was not expected: --rep (--rep is a flag of keyrot resample, convert, slerp, reduce and plot) (see keyrot compare --help)" -- \
    "$keyrot" compare walk.csv walk.csv --rep quat
# the same choice, spelled otherwise by another command: compare's report and info's format
expect_error "compare --to" "keyrot: compare: The following argument was not expected: --to (--to is a flag of keyrot resample, convert, slerp, info and reduce; did you mean '--report'?) (see keyrot compare --help)" -- \
    "$keyrot" compare walk.csv walk.csv --to json
expect_error "info --report" "keyrot: info: The following argument was not expected: --report=json (--report is a flag of keyrot compare and reduce; did you mean '--to'?) (see keyrot info --help)" -- \
    "$keyrot" info walk.csv --report=json
expect "compare -o" 0 "22 rows compared, 0 failed" -- bash -c "'$keyrot' compare walk10.csv walk10.csv -o summary.txt && cut -d';' -f1 summary.txt"

# ---- messages in the user's words
expect_error "ANSWER missing" "keyrot: compare: ANSWER is missing: expected the key, then one answer or more (see keyrot compare --help)" -- \
    "$keyrot" compare key.csv
expect_error "unknown command" "keyrot: unknown command 'interp': expected resample, convert, slerp, compare, info, reduce or plot (did you mean 'slerp'?)" -- \
    "$keyrot" interp x
expect_error "slerp -t nan" "keyrot: -t: expected a finite number, got nan" -- "$keyrot" slerp 1,0,0,0 0,0,0,1 -t nan
expect_error "JSON named .csv" "keyrot: out.csv:1: expected a CSV header, got what looks like JSON ('{'): --from json or --from ndjson reads it as such" -- \
    bash -c "'$keyrot' resample homework.json --to json > out.csv && '$keyrot' info out.csv"
# a stray comma at byte 50,002 of one long line
/usr/bin/env python3 -c '
import json
d = json.dumps({"keys": [{"time": i, "quat": [1, 0, 0, 0]} for i in range(3000)]})
open("long.json", "w").write(d[:50001] + "," + d[50001:])'
expect "a long JSON line: the column" 0 "keyrot: long.json:1:50002: invalid JSON" -- bash -c "'$keyrot' info long.json 2>&1 | cut -d: -f1-5"
expect "info on matrices: no sign lines" 0 "0" -- bash -c \
    "'$keyrot' convert walk.csv --rep matrix | '$keyrot' info | grep -c -e flipped -e 'long way' || true"

summary
