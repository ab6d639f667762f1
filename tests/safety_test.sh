#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Output safety under faults: nothing written where it does not belong,
# nothing lost, failures never reported as success.
# Usage: safety_test.sh KEYROT DATA_DIR
set -u
keyrot=$1
data=$2
tests=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
chmod 755 "$work"
trap 'rm -rf "$work"' EXIT
# shellcheck source=tests/expect.sh
source "$(dirname "$0")/expect.sh"
cd "$work" || exit 1
# As root, the keyrot under test runs from a directory of mode 700, as a
# checkout in root's home does: what a second user runs is copied out.
if [[ $(id -u) == 0 ]]; then
    mkdir -m 700 home && cp "$keyrot" home/keyrot && keyrot=$work/home/keyrot
fi
cp "$data/walk.csv" walk.csv
"$keyrot" resample walk.csv --fps 1 > walk1.csv

# ---- -o naming a standard stream writes into it, where the shell pointed it
echo log > log.csv
"$keyrot" resample walk.csv --fps 1 -o /dev/stdout >> log.csv
expect "-o /dev/stdout >> log keeps the log" 0 "log
$(cat walk1.csv)" -- cat log.csv
{ echo header; "$keyrot" resample walk.csv --fps 1 -o /dev/stdout; echo footer; } > framed.csv
expect "-o /dev/stdout between other writes" 0 "header
$(cat walk1.csv)
footer" -- cat framed.csv
echo earlier > err.log
"$keyrot" resample walk.csv --fps 1 -o /dev/stderr 2>> err.log
expect "-o /dev/stderr 2>> err.log" 0 "earlier
$(cat walk1.csv)" -- cat err.log

# ---- links
ln -s nowhere.csv dangling.csv
expect "-o onto a dangling link: the file it names, the link kept" 0 "dangling.csv -> nowhere.csv
$(cat walk1.csv)" -- bash -c "'$keyrot' resample walk.csv --fps 1 -o dangling.csv && echo \"dangling.csv -> \$(readlink dangling.csv)\" && cat nowhere.csv"
ln -s loop_a loop_b && ln -s loop_b loop_a
expect_error "-o onto a link loop" "keyrot: cannot write 'loop_a': Too many levels of symbolic links" -- \
    "$keyrot" resample walk.csv -o loop_a

# ---- another user's link, a read-only file, a set-user-ID file (root can make a second user)
other=keyrot-test-other
if [[ $(id -u) == 0 ]] && { id "$other" >/dev/null 2>&1 || useradd -M -s /usr/sbin/nologin "$other" 2>/dev/null; }; then
    # What the second user runs is where that user can reach it: the build
    # may be in a directory of mode 700 (root's home, where root clones).
    mkdir -m 755 reach && cp "$keyrot" reach/keyrot
    su -s /bin/sh "$other" -c "reach/keyrot --version" >/dev/null 2>&1 ||
        fail "the second user cannot run a copy of keyrot in $work/reach"
    mkdir -m 1777 shared
    echo precious > victim.txt
    su -s /bin/sh "$other" -c "ln -s '$work/victim.txt' shared/walk.csv && ln -s '$work/victim.txt' shared/result.csv"
    expect "--output-dir: another user's link is replaced, not written through" 0 "precious
regular file
$(cat walk1.csv)" -- bash -c "'$keyrot' resample walk.csv --fps 1 --output-dir shared && cat victim.txt && stat -c %F shared/walk.csv && cat shared/walk.csv"
    # A directory the other user made, with a link to root's file planted in it.
    su -s /bin/sh "$other" -c "mkdir shared/out && ln -s ../../victim.txt shared/out/walk.csv"
    expect "--output-dir of another user's: its link is replaced" 0 "precious
regular file" -- bash -c "'$keyrot' resample walk.csv --output-dir shared/out && cat victim.txt && stat -c %F shared/out/walk.csv"
    # Root replacing another user's file keeps its owner, group and mode.
    cp walk.csv theirs.csv && chown "$other:$other" theirs.csv && chmod 640 theirs.csv
    expect "root replacing another user's file keeps its owner" 0 "$other $other 640" -- \
        bash -c "'$keyrot' resample walk.csv -o theirs.csv && stat -c '%U %G %a' theirs.csv"
    expect "... into --output-dir too" 0 "$other $other 640" -- \
        bash -c "cp -p theirs.csv shared/theirs.csv && '$keyrot' resample theirs.csv --output-dir shared && stat -c '%U %G %a' shared/theirs.csv"
    expect_error "-o: another user's link" "keyrot: cannot write 'shared/result.csv': 'shared/result.csv' is a symbolic link of another user (uid $(id -u "$other")): expected a file, or a link of yours or of the directory's owner" -- \
        "$keyrot" resample walk.csv -o shared/result.csv
    su -s /bin/sh "$other" -c "ln -s /dev/null shared/device.csv"
    expect_error "-o: another user's link to a device" "keyrot: cannot write 'shared/device.csv': 'shared/device.csv' is a symbolic link of another user (uid $(id -u "$other")): expected a file, or a link of yours or of the directory's owner" -- \
        "$keyrot" resample walk.csv -o shared/device.csv
    expect "the victim untouched, no temporary beside it" 0 "precious
0" -- bash -c "cat victim.txt; ls -a | grep -c keyrot- || true"
    mkdir -m 777 open && cp walk.csv open/readonly.csv && chmod 444 open/readonly.csv && chown "$other" open
    expect "a 0444 file is refused, as > refuses it" 0 "keyrot: cannot write 'open/readonly.csv': Permission denied
2
$(cat walk.csv)" -- bash -c "su -s /bin/sh $other -c \"reach/keyrot resample walk.csv -o open/readonly.csv; echo \\\$?\" 2>&1; cat open/readonly.csv"
    touch setuid.csv && chmod 4755 setuid.csv
    expect "the set-user-ID bit is not passed on" 0 "755" -- bash -c "'$keyrot' resample walk.csv -o setuid.csv && stat -c %a setuid.csv"
else
    echo "skipped: other users' links and read-only files need root to make a second user"
fi

# ---- failures to write are failures
for args in "info walk.csv" "slerp 1,0,0,0 0,0,0,1 --steps 4" "compare walk1.csv walk1.csv" \
    "compare walk1.csv walk1.csv --report json" "--help" "--version" "resample walk.csv"; do
    # shellcheck disable=SC2086
    expect_error "$args > /dev/full" "keyrot: cannot write to standard output: No space left on device" -- \
        bash -c "'$keyrot' $args > /dev/full"
    # shellcheck disable=SC2086
    expect_error "$args, standard output closed" "keyrot: cannot write to standard output: it is closed" -- \
        bash -c "'$keyrot' $args >&-"
done
# 100,001 rows: past the first few thousand, they are formatted and written on other threads
printf 'time,qw,qx,qy,qz\n0,1,0,0,0\n100,0,0,0,1\n' > long.csv
for rep in axis-angle quat; do
    expect_error "$rep rows from other threads > /dev/full" "keyrot: cannot write to standard output: No space left on device" -- \
        bash -c "'$keyrot' resample long.csv --fps 1000 --rep $rep > /dev/full"
done
expect "standard output closed, -o FILE" 0 "$(cat walk1.csv)" -- bash -c "'$keyrot' resample walk.csv --fps 1 -o closed_out.csv >&- && cat closed_out.csv"
# a warning with standard error closed goes nowhere, not into the spooled input
printf 'time,qw,qx,qy,qz\n0,2,0,0,0\n1,2,0,0,0\n' > norm.csv
expect "standard error closed" 0 "$("$keyrot" resample norm.csv --fps 1 2>/dev/null)" -- bash -c "cat norm.csv | '$keyrot' resample --fps 1 2>&-"
if [[ $(id -u) == 0 ]] && mkdir small && mount -t tmpfs -o size=8k tmpfs small 2>/dev/null; then
    expect_error "slerp into a full filesystem" "keyrot: cannot write to standard output: No space left on device" -- \
        bash -c "'$keyrot' slerp 1,0,0,0 0,0,0,1 --steps 400 > small/table.csv"
    expect_error "-o into a full filesystem" "keyrot: cannot write 'small/table.csv': No space left on device" -- \
        bash -c "rm -f small/table.csv; '$keyrot' slerp 1,0,0,0 0,0,0,1 --steps 400 -o small/table.csv"
    expect "nothing left in it" 0 "" -- ls -A small
    expect_error "-o into a full filesystem, rows from other threads" "keyrot: cannot write 'small/long.csv': No space left on device" -- \
        "$keyrot" resample long.csv --fps 1000 --rep axis-angle -o small/long.csv
    expect "nothing left in it either" 0 "" -- ls -A small
    umount small
else
    echo "skipped: a full filesystem needs root and a tmpfs"
fi

# ---- a catchable signal leaves no temporary file, and the target as it was
awk 'BEGIN { print "time,qw,qx,qy,qz"; for (i = 0; i < 100000; i++) printf "%d,%.17g,0,0,%.17g\n", i, cos(i / 7), sin(i / 7) }' > long.csv
expect "SIGINT, SIGTERM, SIGHUP mid-write" 0 "clean" -- /usr/bin/env python3 -c '
import glob, os, signal, subprocess, sys, time
keyrot = sys.argv[1]
open("target.csv", "w").write("precious\n")
for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP) * 3:
    p = subprocess.Popen([keyrot, "resample", "long.csv", "--fps", "100", "-o", "target.csv"])
    for _ in range(2000):  # until the temporary file is there
        if glob.glob(".target.csv.keyrot-*") or p.poll() is not None:
            break
        time.sleep(0.001)
    p.send_signal(sig)
    p.wait()
    left = glob.glob(".target.csv.keyrot-*")
    if left or (p.returncode == -sig and open("target.csv").read() != "precious\n"):
        sys.exit("left %s after signal %d (status %d)" % (left, sig, p.returncode))
    open("target.csv", "w").write("precious\n")
print("clean")' "$keyrot"

# ---- input changed while keyrot reads it: the checked rows or an error, never a mix
awk 'BEGIN { print "time,qw,qx,qy,qz"; for (i = 0; i < 200000; i++) printf "%d,%.17g,0,0,%.17g\n", i, cos(i / 7), sin(i / 7) }' > growing.csv
"$keyrot" resample growing.csv --fps 1 > growing_before.csv
{ cat growing.csv; echo '300000,1,0,0,0'; } > grown.csv
"$keyrot" resample grown.csv --fps 1 > growing_after.csv
# status 0 with the rows of the file before or after the append (it came
# before keyrot opened it), or status 2 and nothing on standard output
expect "appended while read" 0 "consistent" -- bash -c "
    for i in 1 2 3 4 5 6; do
        cp growing.csv changing.csv
        (sleep 0.0\$i; echo '300000,1,0,0,0' >> changing.csv) &
        '$keyrot' resample changing.csv --fps 1 > out.csv 2>err.txt
        rc=\$?
        wait
        if [[ \$rc == 0 ]]; then
            cmp -s out.csv growing_before.csv || cmp -s out.csv growing_after.csv || { echo \"run \$i: status 0, other rows\"; exit; }
        elif [[ \$rc != 2 || -s out.csv || \$(cat err.txt) != \"keyrot: 'changing.csv' changed while keyrot was reading it: expected it to stay as it was until keyrot is done\" ]]; then
            echo \"run \$i: status \$rc, \$(wc -c <out.csv) bytes, \$(cat err.txt)\"; exit
        fi
    done
    echo consistent"

# ---- endless or random input ends in one error, within --max-bytes
for from in csv ndjson; do
    expect_error "/dev/zero as $from" "keyrot: /dev/zero:1: line longer than 1000000 bytes: expected the lines of a keyframe table (--max-bytes N raises the limit)" -- \
        timeout 60 "$keyrot" resample /dev/zero --from "$from" --max-bytes 1000000
done
expect_error "/dev/zero as JSON" "keyrot: /dev/zero:1:1: invalid JSON: syntax error while parsing value - unexpected end of input; expected '[', '{', or a literal" -- \
    timeout 60 "$keyrot" resample /dev/zero --from json
expect_error "a JSON document past --max-bytes" "keyrot: <stdin>: JSON document longer than 1000000 bytes (--max-bytes N raises the limit)" -- \
    timeout 60 bash -c "{ echo '{\"keys\": ['; cat /dev/zero | tr '\\0' ' '; } | '$keyrot' resample --from json --max-bytes 1000000"
for from in csv json ndjson; do
    expect "random bytes as $from" 0 "2 1" -- timeout 60 bash -c \
        "head -c 10000000 /dev/urandom | '$keyrot' resample --from $from > random.out 2> random.err; echo \$? \$(wc -l < random.err)"
done
# By default a line may take 1 MiB (a JSON document or a glTF file 256 MiB),
# and input that cannot begin a glTF file is not read on: endless junk in
# any format ends in one line and a small peak (measured from outside).
expect_error "/dev/zero as CSV, by default" "keyrot: /dev/zero:1: line longer than 1048576 bytes: expected the lines of a keyframe table (--max-bytes N raises the limit)" -- \
    timeout 60 "$keyrot" resample /dev/zero
# A JSON document broken in its first block is said to be at once, not after
# reading on to the limit (random bytes that happen to begin with '{').
{ printf '{'; head -c 70000000 /dev/urandom; } > brace_junk.json
expect "'{' and 70 MB of random bytes as JSON: one error, peak under 64 MB" 0 "2 small" -- timeout 60 bash -c \
    "read status kb < <(python3 '$tests/peak.py' '$keyrot' resample brace_junk.json 2>/dev/null)
     echo \$status \$( ((kb < 65536)) && echo small || echo \$kb KB)"
expect "'{' and 70 MB of random bytes piped as glTF: one error, peak under 64 MB" 0 "2 small" -- timeout 60 bash -c \
    "read status kb < <(python3 '$tests/peak.py' '$keyrot' resample --from gltf < <(cat brace_junk.json) 2>/dev/null)
     echo \$status \$( ((kb < 65536)) && echo small || echo \$kb KB)"
rm -f brace_junk.json
# The same for a GLB's magic with a version other than 2 (glTF 1.0's binary
# extension wrote 1), followed by random bytes.
{ printf 'glTF\001\000\000\000'; head -c 70000000 /dev/urandom; } > magic_junk.glb
expect "'glTF', version 1 and 70 MB of random bytes piped as glb: one error, peak under 64 MB" 0 "2 small" -- timeout 60 bash -c \
    "read status kb < <(python3 '$tests/peak.py' '$keyrot' resample --from glb < <(cat magic_junk.glb) 2>/dev/null)
     echo \$status \$( ((kb < 65536)) && echo small || echo \$kb KB)"
# And for one whose header states a length past the limit (4 GiB here).
{ printf 'glTF\002\000\000\000\377\377\377\377'; head -c 70000000 /dev/urandom; } > long_junk.glb
expect "a .glb header stating 4 GiB, piped: one error, peak under 64 MB" 0 "2 small" -- timeout 60 bash -c \
    "read status kb < <(python3 '$tests/peak.py' '$keyrot' resample --from glb < <(cat long_junk.glb) 2>/dev/null)
     echo \$status \$( ((kb < 65536)) && echo small || echo \$kb KB)"
expect_error "a .glb header stating 4 GiB, piped: the message" "keyrot: <stdin>: GLB header states 4294967295 bytes, more than 268435456: expected a smaller file (--max-bytes N raises the limit)" -- \
    bash -c "cat long_junk.glb | '$keyrot' resample --from glb"
rm -f magic_junk.glb long_junk.glb
for source in /dev/zero /dev/urandom; do
    for from in csv ndjson json gltf glb bvh; do
        expect "$source as $from: one error, peak under 64 MB" 0 "2 small" -- timeout 60 bash -c \
            "read status kb < <(python3 '$tests/peak.py' '$keyrot' resample $source --from $from 2>/dev/null)
             echo \$status \$( ((kb < 65536)) && echo small || echo \$kb KB)"
    done
done

# ---- what a message quotes stays readable; control bytes never reach a terminal raw
{ printf 'time,qw,qx,qy,qz\n0,'; head -c 50000000 /dev/zero | tr '\0' '1'; printf ',0,0,0\n'; } > long_value.csv
expect "a 50 MB value is cut in the message" 0 "1" -- bash -c "'$keyrot' resample long_value.csv 2>&1 | wc -l"
expect_error "--fps 1e-320" "keyrot: --fps: expected a positive frame rate, got 1e-320" -- "$keyrot" resample walk.csv --fps 1e-320
escape=$(printf 'x\033]0;title\007.csv')
cp walk.csv "$escape"
expect "info escapes a file name's control bytes" 0 'x\x1b]0;title\x07.csv: 2 tracks, csv' -- bash -c "'$keyrot' info '$escape' | head -n 1"

# ---- track names that need quoting survive a CSV round trip
printf 'track,time,qw,qx,qy,qz\n"#hash",0,1,0,0,0\n" lead",0,1,0,0,0\n"a,b",0,1,0,0,0\n' > names.csv
expect "track names through CSV twice" 0 '{"track": "#hash", "time": 0, "quat": [1, 0, 0, 0]}
{"track": " lead", "time": 0, "quat": [1, 0, 0, 0]}
{"track": "a,b", "time": 0, "quat": [1, 0, 0, 0]}' -- bash -c \
    "'$keyrot' convert names.csv | '$keyrot' convert | '$keyrot' convert --to ndjson --rep quat"

# ---- durability: renamed into place without waiting for the disk by default;
# --fsync waits (file, then directory), and a batch waits once, not once a file
mkdir -p many_in && for i in $(seq 1 20); do cp walk.csv "many_in/w$i.csv"; done
if command -v strace >/dev/null && strace -f -qq -o /dev/null true 2>/dev/null; then
    # syncs COMMAND...: the sync calls it made, as "fsync=N syncfs=N sync_file_range=N"
    syncs() {
        strace -f -qq -e trace=fsync,fdatasync,syncfs,sync_file_range -o trace.txt "$@" >/dev/null 2>&1
        local call counts=()
        for call in fsync syncfs sync_file_range; do
            counts+=("$call=$(grep -cE "^[0-9]+ +$call\(" trace.txt)")
        done
        echo "${counts[*]}"
    }
    expect "-o: no sync by default" 0 "fsync=0 syncfs=0 sync_file_range=0" -- syncs "$keyrot" resample walk.csv -o plain.csv
    expect "a batch: no sync by default" 0 "fsync=0 syncfs=0 sync_file_range=0" -- \
        syncs "$keyrot" resample many_in/*.csv --output-dir many_plain
    expect "-o --fsync: the file and its directory" 0 "fsync=2 syncfs=0 sync_file_range=1" -- \
        syncs "$keyrot" resample walk.csv -o durable.csv --fsync
    expect "info and compare -o --fsync" 0 "fsync=2 syncfs=0 sync_file_range=1
fsync=2 syncfs=0 sync_file_range=1" -- bash -c \
        "$(declare -f syncs); syncs '$keyrot' info walk.csv -o info.txt --fsync && syncs '$keyrot' compare walk.csv walk.csv -o c.txt --fsync"
    expect "a batch of 20 with --fsync: one syncfs, one directory" 0 "fsync=1 syncfs=1 sync_file_range=20" -- \
        syncs "$keyrot" resample many_in/*.csv --output-dir many_durable --fsync --jobs 2
else
    echo "strace cannot trace here: the sync calls are not counted"
fi
"$keyrot" resample many_in/*.csv --output-dir many_plain
"$keyrot" resample many_in/*.csv --output-dir many_durable --fsync
expect "--fsync writes the same files, and leaves no temporary file" 0 "" -- bash -c \
    "diff -r many_plain many_durable && find many_durable -name '.*keyrot-*'"
cp walk.csv many_in/bad.csv && echo 'x,1,0,0,0' >> many_in/bad.csv
expect "a batch with --fsync and a bad file: the others put in place, status 2" 0 "2 20 0" -- bash -c \
    "'$keyrot' resample many_in/*.csv --output-dir many_mixed --fsync 2>/dev/null; echo \$? \$(ls many_mixed | wc -l) \$(find many_mixed -name '.*keyrot-*' | wc -l)"

summary
