#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The help teaches what is true: every example in a command's help runs on
# the files of data/, the columns and fields `keyrot help formats` lists are
# the ones keyrot writes and reads, and a bad topic is one line, status 2.
# Usage: help_test.sh KEYROT DATA_DIR
set -uo pipefail
keyrot=$(realpath "$1")
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cp -r "$2"/. "$scratch"
cd "$scratch" || exit 1
# The examples say "keyrot": this one.
mkdir bin && ln -s "$keyrot" bin/keyrot
export PATH="$scratch/bin:$PATH"
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }

for command in resample convert slerp compare info reduce; do
    help=$(keyrot "$command" --help)
    examples=$(echo "$help" | sed -n '/^Examples:/,$p' | sed -n 's/^  \(keyrot .*\)/\1/p')
    (($(echo "$examples" | wc -l) >= 2)) || fail "$command --help: expected two or more examples"
    grep -q '(default' <<<"$help" || fail "$command --help shows no defaults"
    while read -r example; do  # (and without a warning)
        if out=$(bash -c "$example" 2>&1 >/dev/null) && ! grep -q warning <<<"$out"; then
            echo "ok   $example"
        else
            fail "$example: $out"
        fi
    done <<<"$examples"
    # Every flag the help names (outside its examples, which may run other
    # commands) is one the command takes.
    taken=$(echo "$help" | grep -E '^ +-' | grep -oE -- '--[a-z][a-z0-9-]*' | sort -u)
    for flag in $(echo "$help" | grep -v '^  keyrot ' | grep -oE -- '--[a-z][a-z0-9-]*' | sort -u); do
        grep -qx -- "$flag" <<<"$taken" || fail "$command --help names $flag, which $command does not take"
    done
done
# (Help is read whole before it is searched: under pipefail, a grep -q that
# stops at its first match can leave the writer a closed pipe, which fails
# the pipe whatever it found.)
resample_help=$(keyrot resample --help)
for flag in --rep --method --path --quat-order; do  # (the text may be on the line under the flag)
    [[ $(grep -A1 -E -- "^  $flag " <<<"$resample_help") == *"(default: "* ]] || fail "resample --help: $flag has no default"
done
for group in Input Output Interpolation; do
    grep -qx "$group:" <<<"$resample_help" || fail "resample --help: no group $group"
done

# `help formats`: each representation's CSV columns are the header keyrot writes,
# and its JSON fields are in the document keyrot writes.
formats=$(keyrot help formats)
for rep in axis-angle quat rotvec euler matrix matrix4; do
    columns=$(echo "$formats" | sed -n '/^CSV/,/^JSON/p' | awk -v r="$rep" '$1 == r { print $2 }')
    header=$(keyrot convert homework.json --rep "$rep" --euler ZYX --to csv | sed -n 1p)
    [[ $header == "time,$columns" ]] && echo "ok   CSV columns of $rep: $columns" || fail "CSV $rep: help says '$columns', keyrot writes '$header'"
    fields=$(echo "$formats" | sed -n '/^JSON/,/^NDJSON/p' | awk -v r="$rep" '$1 == r' | sed 's/ or .*//' | grep -oE '"[a-z]+":' | sort -u)
    written=$(keyrot convert homework.json --rep "$rep" --euler ZYX --to json)
    [[ -n $fields ]] || fail "JSON $rep: no fields in help formats"
    for field in $fields; do
        grep -q "$field" <<<"$written" || fail "JSON $rep: help names $field, keyrot writes $written"
    done
done
xyzw=$(echo "$formats" | grep -oE 'xyzw: [a-z,]+' | cut -d' ' -f2)
[[ $(keyrot convert homework.json --rep quat --quat-order xyzw --to csv | sed -n 1p) == "time,$xyzw" ]] ||
    fail "CSV quat in xyzw order: help says $xyzw"
# Files laid out as the help says read back.
echo '{"keys": [{"time": 0, "quat": {"w": 1, "x": 0, "y": 0, "z": 0}}]}' >object.json
keyrot convert object.json >/dev/null || fail "a quaternion as an object, as help formats says"
printf 'frame,track,e1,e2,e3,tx,ty,tz\n0,hip,10,20,30,1,2,3\n' >layout.csv
keyrot convert layout.csv --euler ZYX --rep quat >/dev/null || fail "a CSV file laid out as help formats says"

# Bad topics: one line, status 2.
for args in "help nonsense" "help formats extra" "hlep"; do
    err=$(keyrot $args 2>&1 >/dev/null)
    status=$?
    [[ $status == 2 && $(echo "$err" | wc -l) == 1 && $err == keyrot:* ]] && echo "ok   keyrot $args: $err" ||
        fail "keyrot $args: status $status, '$err'"
done
[[ $(keyrot help FORMTS 2>&1) == *"(did you mean 'formats'?)" ]] || fail "keyrot help FORMTS: $(keyrot help FORMTS 2>&1)"
[[ $(keyrot help) == "$(keyrot --help)" ]] || fail "keyrot help differs from keyrot --help"
[[ $(keyrot help convert) == "$(keyrot convert --help)" ]] || fail "keyrot help convert differs from keyrot convert --help"

((failures == 0)) || { echo "$failures help checks failed"; exit 1; }
echo "all help checks passed"
