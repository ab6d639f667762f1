#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The bash completion (src/dist/keyrot.bash) offers exactly the commands,
# flags and flag values that keyrot's own help lists, and files where a
# file goes: the two cannot drift apart.
# Usage: completion_test.sh KEYROT COMPLETION_SCRIPT
set -uo pipefail
keyrot=$1
# shellcheck source=../src/dist/keyrot.bash
source "$2"
failures=0

# What the completion offers for the command line "$@", the last word being typed.
offers() {
    COMP_WORDS=("$@")
    COMP_CWORD=$(($# - 1))
    COMPREPLY=()
    _keyrot
    ((${#COMPREPLY[@]})) && printf '%s\n' "${COMPREPLY[@]}" | sort -u
}
same() {  # NAME EXPECTED ACTUAL (newline-separated sets)
    if [[ $2 != "$3" ]]; then
        echo "FAIL $1"
        diff <(echo "$2") <(echo "$3") | sed 's/^/    /'
        failures=$((failures + 1))
    else
        echo "ok   $1"
    fi
}
sorted() { tr ' ' '\n' | sed '/^$/d' | sort -u; }

commands=$("$keyrot" --help | sed -n '/^Subcommands:/,/^$/p' | awk 'NR > 1 && NF { print $1 }')
[[ -n $commands ]] || { echo "FAIL no commands in keyrot --help"; exit 1; }
same "commands" "$(echo "$commands" | sorted)" "$(offers keyrot '')"
same "top-level flags" "$("$keyrot" --help | sed -n '/^Options:/,/^$/p' | grep -oE -- '--?[a-z][a-z-]*' | sorted)" \
    "$(offers keyrot -)"

for command in $commands; do
    [[ $command == help ]] && continue
    help=$("$keyrot" "$command" --help)
    # Flag lines: "  -o,--output TEXT ...", "  --rep TEXT:{axis-angle,quat,...}".
    flags=$(echo "$help" | grep -E '^  -' | awk '{ print $1 }' | tr ',' '\n' | sorted)
    same "$command: flags" "$flags" "$(offers keyrot "$command" -)"
    while read -r flag values; do
        same "$command $flag: values" "$(echo "$values" | tr ',' ' ' | sorted)" "$(offers keyrot "$command" "$flag" '')"
    done < <(echo "$help" | sed -nE 's/^  (-[a-z],)?(--[a-z-]+) TEXT:\{([^}]*)\}.*/\2 \3/p')
done

topics=$(echo "$commands" | grep -vx help; echo formats)
same "help topics" "$(echo "$topics" | sorted)" "$(offers keyrot help '')"
for topic in $topics; do
    "$keyrot" help "$topic" >/dev/null || { echo "FAIL keyrot help $topic"; failures=$((failures + 1)); }
done

# Every Euler sequence offered is one keyrot takes, intrinsic and extrinsic.
sequences=$(offers keyrot convert --euler '')
same "Euler sequences: 12 intrinsic, 12 extrinsic" "24" "$(echo "$sequences" | wc -l)"
same "--out-euler offers the same" "$sequences" "$(offers keyrot resample --out-euler '')"
for seq in $sequences; do
    "$keyrot" slerp 10,20,30 40,50,60 --from-rep euler --euler "$seq" -t 0.5 >/dev/null ||
        { echo "FAIL --euler $seq"; failures=$((failures + 1)); }
done

# --flag=value, which bash splits at '='.
same "--rep=" "$(offers keyrot resample --rep '')" "$(offers keyrot resample --rep =)"
same "--rep=q" "quat" "$(offers keyrot resample --rep = q)"
same "--euler=Z" "$(printf 'ZXY\nZXZ\nZYX\nZYZ')" "$(offers keyrot convert --euler = Z)"

# Files where an input or -o goes, directories for --output-dir, nothing for numbers.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cd "$scratch" && mkdir out && touch walk.csv walk.json
same "input files" "$(printf 'walk.csv\nwalk.json')" "$(offers keyrot resample wa)"
same "-o file" "$(printf 'walk.csv\nwalk.json')" "$(offers keyrot convert walk.csv -o w)"
same "--output-dir directory" "out" "$(offers keyrot convert walk.csv --output-dir '')"
same "--fps: a number, nothing offered" "" "$(offers keyrot resample --fps '')"
same "slerp operands: numbers, nothing offered" "" "$(offers keyrot slerp '')"

((failures == 0)) || { echo "$failures completion checks failed"; exit 1; }
echo "all completion checks passed"
