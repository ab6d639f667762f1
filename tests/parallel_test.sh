#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The README's recipe for many files on many machines, run on this one
# (-S :): GNU parallel with keyrot as the per-file worker. Every output is
# the one keyrot writes by itself, the job log holds each file's exit
# status (2 for a bad file, which stops nothing else), and --resume-failed
# reruns only the failed file once it is fixed.
# Usage: parallel_test.sh KEYROT
set -uo pipefail
keyrot=$(realpath "$1")
command -v parallel >/dev/null || { echo "GNU parallel is not installed (.ci/deps test installs it)"; exit 1; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cd "$scratch" || exit 1
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

# 200 tracks, each a turn of its own, and one that is not a track.
mkdir tracks
for i in $(seq 1 200); do
    awk -v i="$i" 'BEGIN { print "time,ax,ay,az,angle"; for (k = 0; k <= 4; k++) printf "%g,0,0,1,%g\n", k * 0.5, k * i % 360 }' \
        >"tracks/take$i.csv"
done
printf 'time,ax,ay,az\n0,0,0,1\n' >tracks/broken.csv

run() {
    parallel -S : --trc {.}.json --joblog jobs.log "$@" "$keyrot" resample {} --fps 30 -o {.}.json ::: tracks/*.csv \
        2>parallel.err
}
run
status=$?
[[ $status == 1 ]] || fail "parallel: status $status, expected 1 (one job failed): $(cat parallel.err)"
grep -q "broken.csv:.*angle" parallel.err || fail "the bad file's message: $(cat parallel.err)"

# The job log: a line per file, exit 0, and 2 for the bad one.
[[ $(tail -n +2 jobs.log | wc -l) == 201 ]] || fail "job log: $(tail -n +2 jobs.log | wc -l) jobs, expected 201"
bad=$(awk -F'\t' 'NR > 1 && $7 != 0 { print $7, $NF }' jobs.log)
[[ $bad == "2 $keyrot resample tracks/broken.csv --fps 30 -o tracks/broken.json" ]] || fail "failed jobs: $bad"

# Every output is what keyrot writes alone (one batch run), byte for byte; none for the bad file.
"$keyrot" resample tracks/take*.csv --fps 30 --to json --output-dir alone || fail "keyrot resample --output-dir"
same=0
for i in $(seq 1 200); do
    cmp -s "tracks/take$i.json" "alone/take$i.json" && same=$((same + 1))
done
[[ $same == 200 ]] || fail "$((200 - same)) outputs differ from keyrot's own"
[[ -e tracks/broken.json ]] && fail "an output for the bad file"

# Fixed, the failed file alone runs again.
printf 'time,ax,ay,az,angle\n0,0,0,1,0\n1,0,0,1,90\n' >tracks/broken.csv
run --resume-failed
status=$?
[[ $status == 0 ]] || fail "--resume-failed: status $status: $(cat parallel.err)"
[[ $(tail -n +2 jobs.log | wc -l) == 202 ]] || fail "--resume-failed ran $(($(tail -n +2 jobs.log | wc -l) - 201)) jobs, expected 1"
[[ $(tail -1 jobs.log | awk -F'\t' '{ print $7, $NF }') == "0 $keyrot resample tracks/broken.csv --fps 30 -o tracks/broken.json" ]] ||
    fail "the rerun: $(tail -1 jobs.log)"
"$keyrot" info tracks/broken.json | grep -q "31 keys, 0 s to 1 s" || fail "the fixed file resampled: $("$keyrot" info tracks/broken.json 2>&1)"

((failures == 0)) || { echo "$failures parallel checks failed"; exit 1; }
echo "all parallel checks passed: 200 outputs as keyrot's own, the job log, --resume-failed"
