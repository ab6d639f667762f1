#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The bad-input corpus (tests/bad: NAME, or NAME.args alone for a command
# line, with NAME.err the one line keyrot must print) and the good corpus
# (tests/good: variants keyrot must accept quietly), plus inputs too large to
# check in and the output-safety cases.
# Usage: corpus_test.sh KEYROT TESTS_DIR
set -u
keyrot=$(realpath "$1")
tests=$(realpath "$2")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=tests/expect.sh
source "$(dirname "$0")/expect.sh"

cd "$tests/bad" || exit 1
for expected in *.err; do
    name=${expected%.err}
    if [[ -e $name ]]; then
        expect_error "$name" "$(cat "$expected")" -- "$keyrot" resample "$name"
    else
        # shellcheck disable=SC2046
        expect_error "$name" "$(cat "$expected")" -- "$keyrot" $(cat "$name.args")
    fi
done

# Into -o FILE, which resample writes in one pass (falling back to the two
# passes on any error): the same one line, and no file.
for expected in *.err; do
    name=${expected%.err}
    [[ -e $name ]] || continue
    expect_error "$name -o" "$(cat "$expected")" -- "$keyrot" resample "$name" -o "$work/bad_out.csv"
    if [[ -e $work/bad_out.csv || -n $(find "$work" -name '*.keyrot-*') ]]; then
        fail "$name -o: output file left behind"
        rm -f "$work/bad_out.csv"
    fi
done

# The same inputs on standard input name <stdin>, read in place from a file
# or else kept in a temporary file in $TMPDIR, which no way of ending may
# leave behind: an error, empty input, success, a closed pipe.
mkdir "$work/tmp"
export TMPDIR=$work/tmp
expect_error "stdin" "keyrot: <stdin>:3: column 'qw': expected a finite number, got 'one'" -- \
    bash -c "'$keyrot' resample < not_a_number.csv"
expect_error "stdin pipe" "keyrot: <stdin>:3: column 'qw': expected a finite number, got 'one'" -- \
    bash -c "cat not_a_number.csv | '$keyrot' resample"
expect_error "empty stdin" "keyrot: <stdin>: empty input: expected a CSV header and keys" -- \
    bash -c "'$keyrot' resample < /dev/null"
cat "$tests/../data/turntable.csv" | "$keyrot" resample >/dev/null
cat "$tests/../data/turntable.csv" | "$keyrot" resample --fps 100000 | head -n 1 >/dev/null
if [[ -z $(ls -A "$work/tmp") ]]; then
    passed=$((passed + 1))
else
    fail "standard input left in $TMPDIR: $(ls -A "$work/tmp")"
fi
unset TMPDIR

# A file on standard input is read in place, from where its offset stands
# (here after a line the shell's read took): no temporary file, so an
# unusable $TMPDIR does not matter; a pipe needs one, and says so.
{ echo "not a header"; cat "$tests/../data/walk.csv"; } > "$work/after_a_line.csv"
expect "stdin file in place" 0 "$("$keyrot" resample "$tests/../data/walk.csv")" -- \
    bash -c "{ IFS= read -r line; TMPDIR=/nonexistent '$keyrot' resample; } < '$work/after_a_line.csv'"
expect "stdin file in place, -o" 0 "$("$keyrot" resample "$tests/../data/walk.csv" --rep euler --euler XYZ)" -- \
    bash -c "{ IFS= read -r line; TMPDIR=/nonexistent '$keyrot' resample -o '$work/in_place.csv' --rep euler \
        --euler XYZ && cat '$work/in_place.csv'; } < '$work/after_a_line.csv'"
expect_error "stdin a directory" "keyrot: cannot read '<stdin>': it is a directory" -- \
    bash -c "'$keyrot' resample < '$work'"
expect_error "stdin closed" "keyrot: cannot read '<stdin>': it is closed" -- bash -c "'$keyrot' resample <&-"
expect_error "stdin pipe, no temporary directory" \
    "keyrot: cannot store standard input in a temporary file: \$TMPDIR '/nonexistent': No such file or directory" -- \
    bash -c "cat '$tests/../data/walk.csv' | TMPDIR=/nonexistent '$keyrot' resample"

# Accepted quietly: every variant resamples to the textbook example.
want="frame,time,qw,qx,qy,qz
0,0,1,0,0,0
1,0.5,0.92388,0,0,0.382683
2,1,0.707107,0,0,0.707107"
cd "$tests/good" || exit 1
for f in *; do
    out=$("$keyrot" resample "$f" --fps 2 --rep quat --precision 6 --to csv 2>"$work/err")
    rc=$?
    if [[ $rc == 0 && $out == "$want" && ! -s $work/err ]]; then
        passed=$((passed + 1))
    else
        fail "good $f: status $rc, stderr [$(cat "$work/err")], stdout [$out]"
    fi
done

# resample and convert -o FILE guess the header from the first key (track
# names, translation, convert's time columns) to stream in one pass; where
# the guess is wrong the output and the messages must still be those of the
# two passes on standard output.
cd "$work" || exit 1
printf 'time,qw,qx,qy,qz,tx,ty,tz\n0,1,0,0,0,,,\n1,0,0,0,1,1,2,3\n2,1,0,0,0,2,2,2\n' > late_translation.csv
printf 'track,time,qw,qx,qy,qz,tx,ty,tz\na,0,1,0,0,0,,,\na,1,0,1,0,0,,,\nb,0,1,0,0,0,1,1,1\nb,1,0,0,1,0,2,2,2\n' \
    > second_track_translation.csv
printf 'track,time,qw,qx,qy,qz\na,0,1,0,0,0\nb,0,1,0,0,0\na,1,0,1,0,0\nb,1,0,0,1,0\n' > interleaved.csv
printf 'time,qw,qx,qy,qz,extra\n0,2,0,0,0,x\n1,0,0,0,1,y\n' > warnings.csv
# Dense keys (120 a second, more keys than frames at 4 or 80 fps) are
# parsed on a second thread after the first 1024; an error there must still
# come out after the keys before it: a bad cell on line 2500, and on line
# 2000 a zero quaternion, which the reading thread finds. Key i turns 2 h(i)
# about z, h(i) = i/200 + (i/1000)^2: slerp turns evenly between keys, so
# frame k at 80 fps turns 2 h linearly interpolated at i = 1.5 k. A lost key
# would move the frames within a key of it (one at least) by 1e-7 or more.
awk 'function h(i) { return i / 200 + (i / 1000) ^ 2 }
     BEGIN { print "time,qw,qx,qy,qz"
             for (i = 0; i < 3000; i++) printf "%.17g,%.17g,0,0,%.17g\n", i / 120, cos(h(i)), sin(h(i)) }' > dense.csv
for out in "" "-o dense_out.csv"; do
    # shellcheck disable=SC2086
    "$keyrot" resample dense.csv --fps 80 $out >dense_stdout.csv
    [[ -n $out ]] && mv dense_out.csv dense_stdout.csv
    if awk -F, 'function h(i) { return i / 200 + (i / 1000) ^ 2 }
                NR > 1 { a = $5 * $6 * 3.14159265358979324 / 180; x = 1.5 * $1; j = int(x)
                         want = 2 * (h(j) + (x - j) * (h(j + 1) - h(j)))
                         if (($6 != 0 && ($3 != 0 || $4 != 0)) || (cos(a) - cos(want)) ^ 2 + (sin(a) - sin(want)) ^ 2 > 1e-24)
                             bad = 1 }
                END { exit bad || NR != 2001 }' dense_stdout.csv; then
        passed=$((passed + 1))
    else
        fail "dense.csv at 80 fps $out: frames off the keys' turn about z"
    fi
done
awk -F, -v OFS=, 'NR == 2500 { $5 = "x" } 1' dense.csv > dense_bad_cell.csv
awk -F, -v OFS=, 'NR == 2000 { $2 = $3 = $4 = $5 = 0 } 1' dense_bad_cell.csv > dense_zero_key.csv
awk -F, 'NR > 1 { printf "{\"time\": %s, \"quat\": [%s, %s, %s, %s]}\n", $1, $2, $3, $4, NR == 2500 ? "\"x\"" : $5 }' \
    dense.csv > dense_bad_cell.ndjson
for f in dense_bad_cell.csv dense_zero_key.csv dense_bad_cell.ndjson; do
    for out in "" "-o bad_out.csv"; do
        case $f in
            *.csv) line=2500 message="column 'qz': expected a finite number, got 'x'" ;;
            *) line=2499 message="'quat[3]': expected a number, got string \"x\"" ;;
        esac
        [[ $f == dense_zero_key.csv ]] && line=2000 message="quaternion is zero: expected a non-zero quaternion"
        # shellcheck disable=SC2086
        expect_error "$f $out" "keyrot: $f:$line: $message" -- "$keyrot" resample "$f" --fps 4 $out
    done
done
# Into standard output redirected to a file, written in one pass, an error
# a long way in (hundreds of thousands of rows) cuts the file back to where
# keyrot began: what it held before stays, and nothing of keyrot's. Where
# standard error shares the file (2>&1), or it is appended to (>>), the two
# passes write it, warnings first.
for f in dense_bad_cell.csv dense_zero_key.ndjson; do
    [[ -e $f ]] || awk -F, 'NR > 1 { printf "{\"time\": %s, \"quat\": [%s, %s, %s, %s]}\n", $1, NR == 2000 ? 0 : $2, $3, $4,
                                         NR == 2000 ? 0 : $5 }' dense.csv >"$f"
    { printf 'kept\n'; "$keyrot" resample "$f" --fps 20000 2>redirected.err; } >redirected.out
    rc=$?
    if [[ $rc == 2 && $(cat redirected.out) == kept && $(wc -l <redirected.err) == 1 ]]; then
        passed=$((passed + 1))
    else
        fail "$f into a redirected standard output: status $rc, $(wc -c <redirected.out) bytes, stderr [$(cat redirected.err)]"
    fi
done
"$keyrot" resample warnings.csv --fps 20000 2>&1 | cat >piped.out
"$keyrot" resample warnings.csv --fps 20000 >shared.out 2>&1
printf 'kept\n' >appended.out
"$keyrot" resample warnings.csv --fps 20000 >>appended.out 2>/dev/null
if [[ $(head -c 7 shared.out) == keyrot: ]] && cmp -s shared.out piped.out &&
    cmp -s appended.out <(printf 'kept\n'; grep -v '^keyrot:' piped.out); then
    passed=$((passed + 1))
else
    fail "warnings.csv into standard output shared with standard error, or appended to: not the two passes' output"
fi
printf '{"frame": 0, "quat": [1, 0, 0, 0]}\n{"time": 1, "quat": [0, 1, 0, 0]}\n' > frame_then_time.ndjson
printf '{"time": 0, "quat": [1, 0, 0, 0]}\n{"frame": 24, "quat": [0, 1, 0, 0]}\n' > time_then_frame.ndjson
for f in late_translation.csv second_track_translation.csv interleaved.csv warnings.csv dense.csv \
    frame_then_time.ndjson time_then_frame.ndjson \
    "$tests"/../data/* "$tests"/good/*; do
    # 20000 fps: tens of thousands of rows, formatted on several threads.
    # Two passes into a pipe; one into -o FILE, and into standard output
    # redirected to a file (after a wrong guess, cut back and written again).
    for command in "resample --fps 4" "resample --fps 20000" convert; do
        # shellcheck disable=SC2086
        "$keyrot" $command "$f" --to csv 2>two.err | cat >two.out
        rc_two=${PIPESTATUS[0]}
        # shellcheck disable=SC2086
        "$keyrot" $command "$f" -o one.csv 2>one.err
        rc_one=$?
        # shellcheck disable=SC2086
        { printf 'kept\n'; "$keyrot" $command "$f" --to csv 2>redirected.err; } >redirected.out
        rc_redirected=$?
        if [[ $rc_one == "$rc_two" && $rc_redirected == "$rc_two" ]] && cmp -s one.csv two.out &&
            cmp -s one.err two.err && cmp -s redirected.err two.err &&
            cmp -s redirected.out <(printf 'kept\n'; cat two.out); then
            passed=$((passed + 1))
        else
            fail "one pass $(basename "$f"), $command: status $rc_one, redirected $rc_redirected (two passes: $rc_two), stderr [$(cat one.err)]"
        fi
        rm -f one.csv two.out redirected.out
    done
done

# Tracks that interleave (key by key, joint by joint) are read whole, their
# keys parsed ahead on other threads after the first 1024 as streamed input
# is: the output must be that of the same tracks one after another, which
# streams. 3 tracks of 1500 keys, each turning about its own axis, in CSV
# and in NDJSON.
awk 'BEGIN { print "track,time,qw,qx,qy,qz"
             for (i = 0; i < 1500; i++) for (j = 0; j < 3; j++)
                 printf "j%d,%.17g,%.17g,%.17g,%.17g,%.17g\n", j, i / 30, cos(i / 7 + j),
                     (j == 0) * sin(i / 7 + j), (j == 1) * sin(i / 7 + j), (j == 2) * sin(i / 7 + j) }' \
    > interleaved_long.csv
{ head -n 1 interleaved_long.csv; for j in 0 1 2; do grep "^j$j," interleaved_long.csv; done; } > one_after_another.csv
awk -F, 'NR > 1 { printf "{\"track\": \"%s\", \"time\": %s, \"quat\": [%s, %s, %s, %s]}\n", $1, $2, $3, $4, $5, $6 }' \
    interleaved_long.csv > interleaved_long.ndjson
for from in csv ndjson; do
    for out in csv ndjson; do
        "$keyrot" resample interleaved_long.$from --to $out >interleaved.out 2>&1
        "$keyrot" resample one_after_another.csv --to $out >one_after_another.out 2>&1
        if [[ $(wc -l <interleaved.out) -gt 3000 ]] && cmp -s interleaved.out one_after_another.out; then
            passed=$((passed + 1))
        else
            fail "interleaved tracks from $from to $out: not the output of the same tracks one after another"
        fi
    done
done

# A JSON document whose settings come before its keys is streamed; with one
# after them it is read whole (here "quat_order"). Both must give the same
# output and messages: by name, on standard input, with -o, resampled and
# converted. Two tracks of 1500 keys, the second with translations and one
# key not of unit norm, which the warning names.
awk 'BEGIN { printf "{\"rep\": \"quat\", \"quat_order\": \"xyzw\", \"tracks\": {"
             for (j = 0; j < 2; j++) {
                 printf "%s\"j%d\": {\"keys\": [\n", j ? "]}, " : "", j
                 for (i = 0; i < 1500; i++) {
                     n = i == 700 && j ? 2 : 1
                     printf "%s{\"time\": %.17g, \"quat\": [%.17g, %.17g, 0, %.17g]%s}", i ? ",\n" : "", i / 24,
                         n * cos(i / 7 + j) * cos(i / 11), n * cos(i / 7 + j) * sin(i / 11), n * sin(i / 7 + j),
                         j ? sprintf(", \"translation\": [%d, 0, 1]", i) : ""
                 }
             }
             print "]}}}" }' > track.json
mkdir streamed read_whole
mv track.json streamed
sed 's/"quat_order": "xyzw", //; s/}}}$/}}, "quat_order": "xyzw"}/' streamed/track.json > read_whole/track.json
for command in "resample --fps 50" "convert --rep axis-angle"; do
    for way in name stdin -o; do
        for dir in streamed read_whole; do
            # shellcheck disable=SC2086
            case $way in
                name) (cd $dir && "$keyrot" $command track.json --to csv >out 2>err) ;;
                stdin) (cd $dir && "$keyrot" $command --to ndjson <track.json >out 2>err) ;;
                -o) (cd $dir && "$keyrot" $command track.json -o out.csv 2>err && mv out.csv out) ;;
            esac
        done
        if [[ $(wc -l <streamed/out) -ge 3000 && $(cat streamed/err) == *"tracks.j1.keys[700]"* ]] &&
            cmp -s streamed/out read_whole/out && cmp -s streamed/err read_whole/err; then
            passed=$((passed + 1))
        else
            fail "JSON $command, $way: streamed and read whole differ [$(cat streamed/err)]"
        fi
    done
done
# info and compare too, by name and on standard input; and a document of
# Euler keys at frames, whose settings (the document's "fps", "angles" and
# "euler", a track's own "euler") make its keys, over the flags': read
# whole, its "fps" comes last. The second track's 1000th key is 2 degrees
# off in compare.
awk 'BEGIN { printf "{\"euler\": \"ZYX\", \"angles\": \"degrees\", \"fps\": 30, \"tracks\": {"
             for (j = 0; j < 2; j++) {
                 printf "%s\"e%d\": {%s\"keys\": [\n", j ? "]}, " : "", j, j ? "\"euler\": \"xyz\", " : ""
                 for (i = 0; i < 1500; i++)
                     printf "%s{\"frame\": %d, \"euler\": [%.17g, %.17g, %.17g]}", i ? ",\n" : "", 5 * i,
                         170 * sin(i / 9), 80 * cos(i / 13 + j), 120 * sin(i / 5)
             }
             print "]}}}" }' > streamed/euler.json
sed 's/"fps": 30, //; s/}}}$/}}, "fps": 30}/' streamed/euler.json > read_whole/euler.json
for dir in streamed read_whole; do  # line 2501: e1's 1000th key
    awk 'NR == 2501 { i = index($0, "["); rest = substr($0, i + 1)
                      $0 = substr($0, 1, i) sprintf("%.17g", rest + 2) substr(rest, index(rest, ",")) }
         { print }' $dir/euler.json > $dir/euler_off.json
done
for way in info info_stdin info_json compare compare_stdin euler_info euler_compare euler_resample; do
    for dir in streamed read_whole; do
        case $way in
            info) (cd $dir && "$keyrot" info track.json >out 2>err) ;;
            info_stdin) (cd $dir && "$keyrot" info --from json <track.json >out 2>err) ;;
            info_json) (cd $dir && "$keyrot" info track.json --to json -o out 2>err) ;;
            compare) (cd $dir && "$keyrot" compare track.json track.json >out 2>err) ;;
            compare_stdin) (cd $dir && "$keyrot" compare track.json - <track.json >out 2>err) ;;
            euler_info) (cd $dir && "$keyrot" info euler.json --euler zxy --key-fps 24 --radians >out 2>err) ;;
            euler_compare) (cd $dir && "$keyrot" compare euler.json euler_off.json --euler zxy >out 2>err) ;;
            euler_resample) (cd $dir && "$keyrot" resample euler.json --rep euler --to csv >out 2>err) ;;
        esac
    done
    case $way in
        euler_compare) [[ $(cat streamed/out) == *"3000 rows compared, 1 failed; largest difference 2 deg"* ]] && said=yes || said="" ;;
        euler_*) said=yes ;;
        *) [[ $(cat streamed/err) == *"tracks.j1.keys[700]"* ]] && said=yes || said="" ;;
    esac
    if [[ -s streamed/out && -n $said ]] && cmp -s streamed/out read_whole/out && cmp -s streamed/err read_whole/err; then
        passed=$((passed + 1))
    else
        fail "JSON $way: streamed and read whole differ [$(cat streamed/err)]"
    fi
done

# Formatted on several threads, batches must come out whole and in order:
# each track's frames 0..20000 once each, in order, and a key exact.
"$keyrot" resample "$tests/../data/walk.csv" --fps 20000 --rep quat -o threaded.csv
"$keyrot" resample "$tests/../data/walk.csv" --fps 20000 --rep quat --to csv >threaded_stdout.csv
"$keyrot" resample "$tests/../data/walk.csv" --fps 20000 --rep quat --to ndjson |
    sed 's/^{"track": "\([a-z]*\)", "frame": \([0-9]*\), "time": [^,]*, "quat": \[\([^,]*\),.*/\1,\2,-,\3/' \
        >threaded_ndjson.csv
for f in threaded.csv threaded_stdout.csv threaded_ndjson.csv; do
    if awk -F, '$1 == "track" || /^[#{]/ { next }
        $1 != track { if (track != "" && next_frame != 20001) bad = 1; track = $1; tracks = tracks $1 " "; next_frame = 0 }
        $2 != next_frame { bad = 1 }
        { next_frame++ }
        $1 == "hip" && $2 == 10000 && $4 != "0.9961946980917455" { bad = 1 }
        END { exit bad || next_frame != 20001 || tracks != "hip knee " }' "$f"; then
        passed=$((passed + 1))
    else
        fail "$f: frames missing, repeated or out of order"
    fi
done

# Slerp and squad frames of a track with nothing but rotations are worked
# out on the formatting threads where the output is the same for q and -q;
# with --velocity they are worked out as they are made. The rotations must
# be the same digits either way: two tracks of uneven keys, 33,554 rows
# (past the first 4,096, formatted before the threads start), every such
# representation, CSV and NDJSON (its rates dropped, both sides through jq).
awk 'BEGIN { print "track,time,qw,qx,qy,qz"
    for (j = 0; j < 2; j++) for (i = 0; i < 700; i++) {
        w = cos(i * 0.7 + j); x = sin(i * 1.3); y = cos(i * 0.4 + 2 * j); z = sin(i * 0.9 + 1); n = sqrt(w * w + x * x + y * y + z * z)
        printf "j%d,%.17g,%.17g,%.17g,%.17g,%.17g\n", j, i * 0.05 + i % 3 * 0.01, w / n, x / n, y / n, z / n } }' > arc_keys.csv
for how in slerp squad; do
    for rep in axis-angle:4 rotvec:3 matrix:9 matrix4:16; do
        columns=$((3 + ${rep#*:}))
        "$keyrot" resample arc_keys.csv --fps 480 --method $how --rep "${rep%:*}" -o arc_later.csv
        "$keyrot" resample arc_keys.csv --fps 480 --method $how --rep "${rep%:*}" --velocity -o arc_here.csv
        if [[ $(wc -l < arc_later.csv) == 33555 ]] && cmp -s arc_later.csv <(cut -d, -f1-$columns arc_here.csv); then
            passed=$((passed + 1))
        else
            fail "$how, --rep ${rep%:*}: the frames worked out on the formatting threads differ from the ones made in order"
        fi
    done
    "$keyrot" resample arc_keys.csv --fps 480 --method $how --rep matrix --to ndjson | jq -c . > arc_later.ndjson
    "$keyrot" resample arc_keys.csv --fps 480 --method $how --rep matrix --to ndjson --velocity |
        jq -c 'del(.angular_velocity)' > arc_here.ndjson
    if [[ $(wc -l < arc_later.ndjson) == 33554 ]] && cmp -s arc_later.ndjson arc_here.ndjson; then
        passed=$((passed + 1))
    else
        fail "$how, NDJSON: the frames worked out on the formatting threads differ from the ones made in order"
    fi
done

# A single 100 MB line (generated, not checked in), in CSV and in JSON.
{ printf 'time,qw,qx,qy,qz\n0,'; head -c 100000000 /dev/zero | tr '\0' '1'; printf ',0,0,0\n'; } > long_line.csv
expect_error "100 MB CSV line, by default" "keyrot: long_line.csv:2: line longer than 1048576 bytes: expected the lines of a keyframe table (--max-bytes N raises the limit)" -- \
    "$keyrot" resample long_line.csv
expect_error "100 MB CSV line, --max-bytes 200000000" "keyrot: long_line.csv:2: column 'qw': expected a finite number, got '1111111111111111111111111111111111111111'" -- \
    "$keyrot" resample long_line.csv --max-bytes 200000000
{ printf '{"rep": "'; head -c 100000000 /dev/zero | tr '\0' 'x'; printf '", "keys": [{"time": 0, "quat": [1, 0, 0, 0]}, {"time": 1, "quat": [1, 0, 0]}]}'; } > long_line.json
expect_error "100 MB JSON line" "keyrot: long_line.json: keys[1]: 'quat': expected an array of 4 numbers, got 3 elements" -- \
    "$keyrot" resample long_line.json

# Out of memory (a JSON document is held whole, a CSV line too) is one clean
# error naming the file; the target stays as it was, and in a batch the other
# files are still written. Not under AddressSanitizer, which cannot start in
# 200 MB of address space.
if (ulimit -v 200000 && "$keyrot" --version) >/dev/null 2>&1; then
    echo precious >"$work/kept.csv"
    expect_error "out of memory" "keyrot: long_line.json: out of memory" -- \
        bash -c 'ulimit -v 200000 && exec "$@"' _ "$keyrot" resample long_line.json -o "$work/kept.csv"
    expect "out of memory, batch: the file, and the count" 0 "keyrot: long_line.json: out of memory
keyrot: 1 of 2 files failed
2" -- bash -c 'ulimit -v 200000 && "$@" 2>&1 >/dev/null; echo $?' _ "$keyrot" resample long_line.json "$tests/../data/turntable.csv" --output-dir "$work/batch" --jobs 1
    expect_error "out of memory, CSV line" "keyrot: long_line.csv: out of memory" -- \
        bash -c 'ulimit -v 200000 && exec "$@"' _ "$keyrot" resample long_line.csv --max-bytes 300000000
    expect_error "out of memory, info" "keyrot: long_line.json: out of memory" -- \
        bash -c 'ulimit -v 200000 && exec "$@"' _ "$keyrot" info long_line.json
    # slerp writes its rows as it makes them: five million in 200 MB.
    expect "slerp --steps streamed" 0 "5000001" -- \
        bash -c 'ulimit -v 200000 && "$@" | wc -l' _ "$keyrot" slerp 1,0,0,0 0,0,0,1 --steps 4999999
    if [[ $(cat "$work/kept.csv") == precious && -s $work/batch/turntable.csv && ! -e $work/batch/long_line.json ]] &&
        [[ -z $(find "$work" -name '*.keyrot-*') ]]; then
        passed=$((passed + 1))
    else
        fail "out of memory: target changed, or the batch's other file missing: $(ls -A "$work" "$work/batch")"
    fi

    # keyrot's threads only make it faster. Where the address space runs
    # short, the system refuses some of them (each takes 8 MB for its
    # stack) or their memory: keyrot goes on without them, or says it is out
    # of memory, and never aborts. From 10 to 100 MB, on two tracks one after
    # another (streamed: formatting threads, keys parsed ahead) and
    # interleaved (read whole): the whole output, or the one line. What went
    # to standard output stays, as when a disk fills; with -o, nothing does.
    awk 'BEGIN { print "track,time,qw,qx,qy,qz"
                 for (i = 0; i < 6000; i++) for (j = 0; j < 2; j++)
                     printf "j%d,%.17g,%.17g,0,0,%.17g\n", j, i / 10, cos(i / 7 + j), sin(i / 7 + j) }' > threads_interleaved.csv
    { head -n 1 threads_interleaved.csv; grep '^j0,' threads_interleaved.csv; grep '^j1,' threads_interleaved.csv; } \
        > threads_streamed.csv
    for f in threads_streamed.csv threads_interleaved.csv; do
        "$keyrot" resample "$f" >threads_whole.csv
        for limit in $(seq 10000 5000 100000); do
            rm -f threads_o.csv
            (ulimit -v "$limit" && exec "$keyrot" resample "$f" >threads_stdout.csv 2>threads_stdout.err)
            rc_stdout=$?
            (ulimit -v "$limit" && exec "$keyrot" resample "$f" -o threads_o.csv 2>threads_o.err)
            rc_o=$?
            if { [[ $rc_stdout == 0 && ! -s threads_stdout.err ]] && cmp -s threads_stdout.csv threads_whole.csv ||
                 [[ $rc_stdout == 2 && $(cat threads_stdout.err) == "keyrot: $f: out of memory" ]]; } &&
               { [[ $rc_o == 0 && ! -s threads_o.err ]] && cmp -s threads_o.csv threads_whole.csv ||
                 [[ $rc_o == 2 && $(cat threads_o.err) == "keyrot: $f: out of memory" && ! -e threads_o.csv ]]; } &&
               [[ -z $(find . -name '.threads_o.csv.keyrot-*') ]]; then
                passed=$((passed + 1))
            else
                fail "$f in $limit KB: status $rc_stdout [$(head -c 200 threads_stdout.err)], with -o $rc_o [$(head -c 200 threads_o.err)] $(find . -name '.threads_o.csv.keyrot-*')"
                rm -f .threads_o.csv.keyrot-*
            fi
        done
    done
    # A streamed JSON document needs a few keys' memory: 200,000 keys (17
    # MB, which read whole take 130 MB) in 60 MB of address space.
    awk 'BEGIN { printf "{\"keys\": [\n"
                 for (i = 0; i < 200000; i++) printf "%s{\"time\": %.17g, \"quat\": [%.17g, 0, 0, %.17g]}", i ? ",\n" : "", i / 24, cos(i / 7), sin(i / 7)
                 print "]}" }' > long_track.json
    "$keyrot" resample long_track.json --to csv >long_track.csv
    for out in "--to csv" "-o long_track_o.csv"; do
        # shellcheck disable=SC2086
        (ulimit -v 60000 && exec "$keyrot" resample long_track.json $out >long_track_limited.csv 2>long_track.err)
        rc=$?
        [[ -e long_track_o.csv ]] && mv long_track_o.csv long_track_limited.csv
        if [[ $rc == 0 && ! -s long_track.err && $(wc -l <long_track.csv) == 200001 ]] && cmp -s long_track.csv long_track_limited.csv; then
            passed=$((passed + 1))
        else
            fail "long_track.json $out in 60 MB: status $rc [$(head -c 200 long_track.err)]"
        fi
    done
    rm -f long_track.json long_track.csv long_track_limited.csv
    # And a batch on two jobs: each file written whole, or its line.
    "$keyrot" resample threads_streamed.csv threads_interleaved.csv --output-dir threads_whole
    for limit in $(seq 10000 5000 100000); do
        rm -rf threads_batch
        (ulimit -v "$limit" && exec "$keyrot" resample threads_streamed.csv threads_interleaved.csv \
            --output-dir threads_batch --jobs 2 2>threads_batch.err)
        rc=$?
        batch_ok=$([[ $rc == 0 || $rc == 2 ]] && echo yes)
        for f in threads_streamed.csv threads_interleaved.csv; do
            if [[ -e threads_batch/$f ]]; then
                cmp -s "threads_batch/$f" "threads_whole/$f" || batch_ok=
            elif ! grep -qxF "keyrot: $f: out of memory" threads_batch.err; then
                batch_ok=
            fi
        done
        if [[ -n $batch_ok ]] &&
            ! grep -vqE '^keyrot: (threads_(streamed|interleaved).csv: out of memory|[12] of 2 files failed)$' threads_batch.err; then
            passed=$((passed + 1))
        else
            fail "batch in $limit KB: status $rc [$(head -c 200 threads_batch.err)]"
        fi
    done
fi
rm -f long_line.csv long_line.json

# Output safety: a directory as the target is one clean error and leaves no temporary file.
mkdir -p "$work/target.csv"
expect_error "directory target" "keyrot: cannot write '$work/target.csv': Is a directory" -- \
    "$keyrot" resample "$tests/../data/turntable.csv" -o "$work/target.csv"
if [[ -z $(ls -A "$work/target.csv") && -z $(find "$work" -name '*.keyrot-*') ]]; then
    passed=$((passed + 1))
else
    fail "temporary file left behind: $(ls -A "$work")"
fi

# -o into a pipe or a device writes into it, after the input is known good
# (nothing can be taken back there), and leaves it what it was; through a
# symbolic link, the file it names is replaced, keeping its mode, and the
# link stays.
mkfifo "$work/fifo"
"$keyrot" resample "$tests/../data/turntable.csv" --to csv >"$work/want.csv"
for input in "$tests/../data/turntable.csv" "$tests/bad/not_a_number.csv"; do
    timeout 20 cat "$work/fifo" >"$work/from_fifo.csv" &  # timeout: were the FIFO replaced, no writer would come
    reader=$!
    "$keyrot" resample "$input" -o "$work/fifo" 2>/dev/null
    rc=$?
    # never opened: let the reader end (timeout: unless it has, having read something)
    [[ $rc == 2 ]] && timeout 5 bash -c ': >"$1"' _ "$work/fifo"
    wait $reader
    if [[ $input == *turntable* ]]; then expected=$work/want.csv; else expected=/dev/null; fi
    if [[ -p $work/fifo ]] && cmp -s "$work/from_fifo.csv" "$expected"; then
        passed=$((passed + 1))
    else
        fail "-o FIFO, $(basename "$input"): status $rc, $(wc -c <"$work/from_fifo.csv") bytes read, $(stat -c %F "$work/fifo")"
    fi
done
expect_error "device target" "keyrot: cannot write '/dev/full': No space left on device" -- \
    "$keyrot" resample "$tests/../data/turntable.csv" -o /dev/full
if [[ -c /dev/full ]]; then passed=$((passed + 1)); else fail "/dev/full is no longer a device"; fi
echo precious >"$work/real.csv"
chmod 640 "$work/real.csv"
ln -s real.csv "$work/link.csv"
"$keyrot" resample "$tests/../data/turntable.csv" -o "$work/link.csv"
if [[ -L $work/link.csv && $(stat -c %a "$work/real.csv") == 640 ]] && cmp -s "$work/real.csv" "$work/want.csv"; then
    passed=$((passed + 1))
else
    fail "-o symbolic link: $(ls -l "$work/link.csv" "$work/real.csv")"
fi

# A read error is one clean error, not a short input: reading
# /proc/self/mem from offset 0 (never mapped) fails with EIO.
expect_error "read error" "keyrot: cannot read '/proc/self/mem': Input/output error" -- \
    "$keyrot" resample /proc/self/mem

# A closed pipe ends keyrot quietly.
"$keyrot" resample "$tests/../data/turntable.csv" --fps 100000 2>"$work/pipe.err" | head -n 1 >/dev/null
if [[ ! -s $work/pipe.err ]]; then
    passed=$((passed + 1))
else
    fail "closed pipe: stderr [$(cat "$work/pipe.err")]"
fi

summary
