#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The layers of docs/design.md hold in the code: each folder includes only
# what stands below it, the threads of io/fast are included by io/open.cpp
# alone, a format folder includes no other format but the JSON parser, the
# picture writer (io/svg) knows no rotation, no source file is over 500
# lines, and every one names its licence.
# Usage: layers_test.sh SOURCE_DIR
set -uo pipefail
cd "$1" || exit 2
failures=0

# The includes of files under FOLDER... that name a path matching PATTERN.
includes() {
    local pattern=$1
    shift
    grep -rnE "^#include \"($pattern)" "$@" 2>/dev/null
}
none() {  # NAME FOUND
    if [[ -n $2 ]]; then
        echo "FAIL $1"
        sed 's/^/    /' <<<"$2"
        failures=$((failures + 1))
    else
        echo "ok   $1"
    fi
}

none "ground includes only ground and the core's error" \
    "$(includes '(core|io|app)/|keyrot/[^e]|cli|suggest|formats_help' src/ground)"
none "the core includes no I/O and no command" \
    "$(includes '(io|app)/|cli|suggest|formats_help' include/keyrot src/core)"
none "the core says nothing in flags (the CLI words its option errors)" \
    "$(grep -rnE '"[^"]*--[a-z]' include/keyrot src/core)"
none "the installed API holds no I/O: raw keys, warnings and usage errors are private" \
    "$(grep -rnwE 'raw_key|key_settings|make_key|warnings|usage_error|print_error' include/keyrot | grep -v '^[^:]*:[0-9]*:\s*//')"
none "io includes no command" "$(includes 'app/|cli|suggest|formats_help' src/io)"
none "io/common includes no format, no thread pool, nothing above it" \
    "$(includes 'io/(csv|json|gltf|bvh|fast)/|io/(open|document)\.' src/io/common)"
none "io/fast includes no format and nothing above it" \
    "$(includes 'io/(csv|json|gltf|bvh)/|io/(open|document)\.' src/io/fast)"
none "only io/open.cpp includes io/fast" \
    "$(includes 'io/fast/' src --exclude-dir=fast | grep -v '^src/io/open\.cpp:')"
# csv (its settings line) and gltf (a glTF file is JSON) use the JSON parser.
for f in csv json gltf bvh; do
    case $f in csv | gltf) allowed="$f|json" ;; *) allowed=$f ;; esac
    others=$(tr ' ' '\n' <<<"csv json gltf bvh" | grep -vxE "$allowed" | paste -sd '|')
    none "io/$f includes no other format and nothing above it" \
        "$(includes "io/($others)/|io/(open|document)\\.|io/fast/" "src/io/$f")"
done

none "io/svg draws figures: it includes no format and nothing above it" \
    "$(includes 'io/(csv|json|gltf|bvh|fast)/|io/(open|document)\.|keyrot/' src/io/svg)"

long=$(find src include -name '*.cpp' -o -name '*.hpp' | xargs wc -l | awk '$2 != "total" && $1 > 500')
none "no source file over 500 lines" "$long"

# Every source file names its licence on its first line (after a #! line).
unlicensed=$(find src include tests examples .ci CMakeLists.txt -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.py' \
    -o -name '*.sh' -o -name '*.js' -o -name '*.cmake' -o -name '*.cmake.in' -o -name '*.bash' -o -name CMakeLists.txt -o -path '.ci/*' \) \
    -not -path 'tests/npm/node_modules/*' -not -path 'tests/fuzz/corpus/*' -not -path 'tests/bad/*' -not -path 'tests/good/*' |
    while read -r file; do
        head -2 "$file" | sed '/^#!/d' | head -1 | grep -q 'SPDX-License-Identifier: MIT$' || echo "$file"
    done)
none "every source file says its licence (SPDX-License-Identifier: MIT)" "$unlicensed"

echo "$failures failed"
((failures == 0))
