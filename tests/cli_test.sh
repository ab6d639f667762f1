#!/usr/bin/env bash
# CLI tests: run the built keyrot as a user would and check output and status.
# Usage: cli_test.sh KEYROT DATA_DIR
set -u
keyrot=$1
data=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failed=0

# expect NAME STATUS EXPECTED_STDOUT -- COMMAND...
expect() {
    local name=$1 status=$2 want=$3
    shift 4
    local got rc
    got=$("$@" 2>"$work/stderr")
    rc=$?
    if [[ $rc == "$status" && $got == "$want" ]]; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        printf 'FAIL %s: status %s (want %s)\n--- got\n%s\n--- want\n%s\n--- stderr\n%s\n' \
            "$name" "$rc" "$status" "$got" "$want" "$(cat "$work/stderr")"
    fi
}

# expect_error NAME EXPECTED_STDERR_LINE -- COMMAND...: status 2, nothing on stdout, one line on stderr
expect_error() {
    local name=$1 want=$2
    shift 3
    local got rc
    got=$("$@" 2>"$work/stderr")
    rc=$?
    local err
    err=$(cat "$work/stderr")
    if [[ $rc == 2 && -z $got && $err == "$want" ]]; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        printf 'FAIL %s: status %s, stdout [%s]\n--- stderr\n%s\n--- want\n%s\n' "$name" "$rc" "$got" "$err" "$want"
    fi
}

# Seed 000's worked example, resampled from the homework file.
expect "seed 000 example" 0 "frame,time,qx,qy,qz,qw
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
20,0.8333,60,-10,4
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

# stdin, sniffed as JSON; output in the input's format
expect "stdin json" 0 '{"fps": 1, "method": "slerp", "rep": "rotvec", "angles": "radians", "frames": [
{"frame": 0, "time": 0, "rotvec": [0, 0, 0]},
{"frame": 1, "time": 1, "rotvec": [0, 0, 1.5708]}]}' -- \
    bash -c "'$keyrot' resample --fps 1 --rep rotvec --radians --precision 4 < '$data/homework.json'"

# Errors: one line, status 2, nothing on stdout
printf 'time,qw,qx,qy,qz\n0,1,0,0,0\n0.5,abc,0,0,0\n' > "$work/bad.csv"
expect_error "bad number" "keyrot: $work/bad.csv:3: column 'qw': expected a finite number, got 'abc'" -- \
    "$keyrot" resample "$work/bad.csv"
expect_error "missing file" "keyrot: cannot read '$work/nope.csv': No such file or directory" -- \
    "$keyrot" resample "$work/nope.csv"
expect_error "bad fps" "keyrot: --fps: expected a positive frame rate, got 0" -- "$keyrot" resample --fps 0 "$data/turntable.csv"
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

expect "help" 0 "0" -- bash -c "'$keyrot' --help >/dev/null; echo \$?"
expect "version" 0 "keyrot 0.1.0" -- "$keyrot" --version

echo "$passed passed, $failed failed"
[[ $failed == 0 ]]
