#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Two keyrot binaries give the same bytes: standard output, standard error,
# files written with -o, and exit status, on data/, tests/good, tests/bad
# (with their command lines), glTF files of every kind of channel
# (gltf_variety.py), a spread of flags, and the conformance cases.
# Run by hand around a change that must not change behaviour:
#   tests/bench/same_output.sh OLD_KEYROT NEW_KEYROT
# With --outputs first, only what is written (standard output and files) is
# compared, where both binaries succeed, and not the conformance cases, whose
# checks follow the new binary's contract: for an older build whose messages
# or formats have changed since, the data its defaults wrote.
set -u
outputs_only=false
if [[ ${1:-} == --outputs ]]; then
    outputs_only=true
    shift
fi
old=$(realpath "$1")
new=$(realpath "$2")
root=$(cd "$(dirname "$0")/../.." && pwd)
python=/usr/bin/python3
[[ -x $python ]] || python=python3  # Debian's, with python3-scipy
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
runs=0 differ=0

# One command line, run by both binaries in a directory of their own.
both() {
    runs=$((runs + 1))
    for side in old new; do
        mkdir -p "$work/$side" && rm -rf "${work:?}/$side"/*
        local binary=${!side}
        (cd "$work/$side" && "$binary" "$@" >stdout 2>stderr </dev/null; echo $? >status)
    done
    if $outputs_only; then
        [[ $(cat "$work/old/status") == 0 && $(cat "$work/new/status") == 0 ]] || return
        rm -f "$work"/{old,new}/{stderr,status}
    fi
    if ! diff -r "$work/old" "$work/new" >/dev/null; then
        differ=$((differ + 1))
        echo "differs: keyrot $*" >&2
        diff -r "$work/old" "$work/new" | head -n 5 >&2
    fi
}

inputs=("$root"/data/* "$root"/tests/good/* "$root"/tests/bad/*.csv "$root"/tests/bad/*.json "$root"/tests/bad/*.ndjson)
for f in "${inputs[@]}"; do
    [[ -f $f ]] || continue
    both resample "$f"
    both resample "$f" -o out.csv
    both resample "$f" --fps 30 --method squad --rep quat --to json
    both resample "$f" --method nlerp --path longest --rep euler --out-euler zyx --to ndjson --precision 6
    both resample "$f" --method step --rep rotvec --out-radians -o out.json
    both resample "$f" --method euler --euler ZXY --rep matrix --to csv
    both convert "$f" --rep quat --quat-order xyzw
    both convert "$f" --rep matrix4 --to json -o out.ndjson
    both info "$f"
    both compare "$f" "$root/data/walk.csv" --report json
done
cd "$root/tests/bad" || exit 1
for args in *.args; do
    # shellcheck disable=SC2046
    both $(cat "$args")
done
both slerp 1,0,0,0 0,0,0,1 --steps 4
both slerp 0,0,1,90 0,1,0,90 --from axis-angle --rep euler --out-euler XYZ -t 0.25 -t 0.5
both convert "$root/data/walk.csv" "$root/data/turntable.csv" --output-dir out --to json
# Outputs large enough for the formatting threads.
both slerp 1,0,0,0 0,0,0.6,0.8 --steps 30000 --rep euler --out-euler ZYX
both slerp 1,0,0,0 0,0,0.6,0.8 --steps 30000 -o out.json
# The reports: info and reduce as JSON, compare's rows and grade tables
# against answers that fail (made once, by the old binary).
mkdir -p "$work/answers"
for f in "$root"/data/*; do
    key=$work/answers/key_$(basename "$f").csv answer=$work/answers/$(basename "$f").csv
    "$old" resample "$f" -o "$key" 2>/dev/null
    "$old" resample "$f" --method nlerp -o "$answer" 2>/dev/null
    both info "$f" --to json --segments
    both reduce "$f" --tol 0.5 --report json -o out.json
    both compare "$key" "$answer" --report json
    both compare "$key" "$answer" "$root/data/walk.csv" "$key" --report json
    both compare "$key" "$answer" "$root/data/walk.csv" --report csv
done
# glTF: channels merged on one track's key times, splines, weights; glTF out.
if "$python" "$root/tests/bench/gltf_variety.py" "$work/gltf"; then
    for f in "$work"/gltf/*; do
        both resample "$f" --fps 24
        both resample "$f" --fps 7 --rep euler --out-euler zyx --to ndjson
        both resample "$f" --fps 24 --method squad --to json
        both resample "$f" --fps 30 -o out.glb
        both resample "$f" --fps 30 --method nlerp -o out.glb
        both resample "$f" --fps 60 --compact -o out.glb
        both convert "$f" --rep quat
        both reduce "$f" --tol 0.5 -o out.glb
        both reduce "$f" --tol 0.01 --report json --to csv
        both info "$f" --segments
    done
else
    echo "gltf_variety.py did not run" >&2
    differ=$((differ + 1))
fi
for f in "$root"/data/*; do
    both resample "$f" --fps 5000
    both resample "$f" --fps 3000 --rep matrix4 -o out.ndjson
    both resample "$f" --fps 3000 --rep quat --to json
done

if $outputs_only; then
    echo "$runs command lines, $differ with different output"
    [[ $differ == 0 ]]
    exit
fi

# The conformance cases: a keyrot that runs both and logs any difference.
cat >"$work/keyrot-both" <<EOF
#!/usr/bin/env bash
cat > "$work/stdin"
"$old" "\$@" < "$work/stdin" > "$work/out.old" 2> "$work/err.old"; s_old=\$?
"$new" "\$@" < "$work/stdin" > "$work/out.new" 2> "$work/err.new"; s_new=\$?
if [[ \$s_old != \$s_new ]] || ! cmp -s "$work/out.old" "$work/out.new" || ! cmp -s "$work/err.old" "$work/err.new"; then
    echo "differs: keyrot \$*" >> "$work/conformance.log"
fi
cat "$work/out.old"; cat "$work/err.old" >&2; exit \$s_old
EOF
chmod +x "$work/keyrot-both"
if "$python" "$root/tests/conformance.py" "$work/keyrot-both" --cases 1500 >/dev/null; then
    runs=$((runs + 1500))
    if [[ -s $work/conformance.log ]]; then
        differ=$((differ + $(wc -l <"$work/conformance.log")))
        head -n 5 "$work/conformance.log" >&2
    fi
else
    echo "conformance.py did not run" >&2
    differ=$((differ + 1))
fi

echo "$runs command lines, $differ with different output"
[[ $differ == 0 ]]
