#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What a user installs: `cmake --install` puts the program, its man page,
# its bash completion and the library with its CMake package where they
# belong; a program of one's own (examples/slerp_between) builds against
# the installed package and nothing of keyrot's own compile flags reaches
# it; `cpack -G DEB` gives keyrot and libkeyrot-dev packages whose fields
# and files are right, which lintian passes, and which install into a
# scratch root and work.
# Usage: install_test.sh BUILD_DIR SOURCE_DIR
set -uo pipefail
build=$(realpath "$1")
source_dir=$(realpath "$2")
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
ok() { echo "ok   $*"; }
version=$("$build/keyrot" --version | cut -d' ' -f2)

# 1. cmake --install
prefix=$scratch/prefix
cmake --install "$build" --prefix "$prefix" >"$scratch/install.log" || fail "cmake --install: $(tail -3 "$scratch/install.log")"
for file in bin/keyrot share/man/man1/keyrot.1.gz share/bash-completion/completions/keyrot lib/libkeyrot_core.a \
    include/keyrot/quat.hpp include/keyrot/interpolate.hpp include/keyrot/convert.hpp \
    lib/cmake/keyrot/keyrot-config.cmake lib/cmake/keyrot/keyrot-config-version.cmake \
    share/doc/keyrot/copyright share/doc/keyrot/changelog.gz share/doc/libkeyrot-dev/copyright; do
    [[ -f $prefix/$file ]] && ok "installed $file" || fail "not installed: $file"
done
# The copyright files hold the MIT licence, as LICENSE words it.
licence=$(sed -n '/^Permission/,$p' "$source_dir/LICENSE" | tr -s ' \n' ' ')
for package in keyrot libkeyrot-dev; do
    copyright=$prefix/share/doc/$package/copyright
    grep -q '^License: MIT$' "$copyright" && [[ $(sed -n '/^ Permission/,$p' "$copyright" | sed 's/^ \.$//' |
        tr -s ' \n' ' ') == " $licence" ]] && ok "$package's copyright holds the MIT licence" ||
        fail "$package's copyright: not the MIT licence of LICENSE"
done
# The installed headers are the public ones, and they include nothing that is not installed.
for header in "$prefix"/include/keyrot/*.hpp; do
    grep -ho '#include "[^"]*"' "$header" | cut -d'"' -f2 | while read -r included; do
        [[ -f $prefix/include/$included ]] || echo "FAIL $(basename "$header") includes $included, not installed"
    done
done | grep FAIL && failures=$((failures + 1))
[[ $("$prefix/bin/keyrot" slerp 1,0,0,0 0,0,0,1 -t 0.5 --rep quat --precision 4 | tail -1) == "0.5,0.7071,0,0,0.7071" ]] &&
    ok "the installed keyrot runs" || fail "the installed keyrot: $("$prefix/bin/keyrot" slerp 1,0,0,0 0,0,0,1 -t 0.5 --rep quat 2>&1)"

# 2. The man page: a section per command with every flag its help lists as
# a tagged paragraph (.TP) of its own, the formats, the examples.
manpage=$prefix/share/man/man1/keyrot.1.gz
page=$(MANWIDTH=200 man -l "$manpage" 2>"$scratch/man.err")
[[ -s $scratch/man.err ]] && fail "man -l: $(cat "$scratch/man.err")"
zcat "$manpage" | groff -man -Tutf8 -ww -z 2>"$scratch/groff.err" && [[ ! -s $scratch/groff.err ]] ||
    fail "groff warnings: $(head -3 "$scratch/groff.err")"
for section in NAME SYNOPSIS DESCRIPTION COMMANDS FORMATS EXAMPLES; do
    grep -qx "$section" <<<"$page" || fail "man page: no section $section"
done
# The tags of the .TP entries, as a reader sees them: "-o, --output TEXT".
tags=$(zcat "$manpage" | awk '/^\.TP$/ { getline; print }' | sed -e 's/\\f[BIR]//g' -e 's/\\-/-/g')
for command in resample convert slerp compare info reduce; do
    grep -qx "   $command" <<<"$page" || fail "man page: no section for $command"
    "$build/keyrot" "$command" --help | grep -E '^  -' | awk '{ print $1 }' | tr ',' '\n' | while read -r flag; do
        grep -qE -- "(^|, )$flag( |,|$)" <<<"$tags" || echo "FAIL man page: $command's $flag is no .TP entry"
    done | grep FAIL && failures=$((failures + 1))
    "$build/keyrot" "$command" --help | sed -n 's/^  \(keyrot .*\)/\1/p' | while read -r example; do
        [[ $(grep -cF -- "$example" <<<"$page") -ge 2 ]] || echo "FAIL man page: example '$example' not in $command's section and EXAMPLES"
    done | grep FAIL && failures=$((failures + 1))
done
grep -qF "$(keyrot_columns=$("$build/keyrot" help formats | grep '^  matrix4'); echo "$keyrot_columns")" <<<"$page" &&
    ok "man page: formats" || fail "man page: the formats are not keyrot help formats'"
grep -q "keyrot $version" <<<"$page" && ok "man page: version $version" || fail "man page: no version $version"
[[ $(grep -c . <<<"$tags") -ge 100 ]] && ok "man page: $(grep -c . <<<"$tags") flags as .TP entries" ||
    fail "man page: only $(grep -c . <<<"$tags") .TP entries"

# 3. A program of one's own against the installed package, without keyrot's flags.
targets=$prefix/lib/cmake/keyrot/keyrot-targets.cmake
grep -E -- '-ffp-contract|-W|FMT_USE|KEYROT_|flto|fsanitize' "$targets" && fail "keyrot's own flags leak into keyrot::core"
expected=$(for h in 0.00 0.25 0.50 0.75 1.00; do  # slerp from the identity to 90 degrees about z: 90 h degrees
    awk -v h=$h 'BEGIN { printf "h=%s axis=(%s) angle=%s deg\n", h, h == 0 ? "1, 0, 0" : "0, 0, 1", 90 * h }'
done)
compilers=(c++)
command -v clang++ >/dev/null && compilers+=(clang++)
for compiler in "${compilers[@]}"; do
    consumer=$scratch/consumer-$compiler
    if cmake -S "$source_dir/examples/slerp_between" -B "$consumer" -DCMAKE_PREFIX_PATH="$prefix" \
        -DCMAKE_CXX_COMPILER="$compiler" >"$scratch/consumer.log" 2>&1 && cmake --build "$consumer" >>"$scratch/consumer.log" 2>&1; then
        flags=$(cat "$consumer"/CMakeFiles/slerp_between.dir/flags.make)
        grep -E -- '-ffp-contract|-W|FMT_USE|KEYROT_|flto' <<<"$flags" && fail "$compiler: keyrot's flags reached the consumer"
        [[ $("$consumer/slerp_between") == "$expected" ]] && ok "examples/slerp_between built with $compiler against the installed package" ||
            fail "examples/slerp_between ($compiler) printed: $("$consumer/slerp_between")"
    else
        fail "examples/slerp_between with $compiler: $(tail -5 "$scratch/consumer.log")"
    fi
done

# 4. The Debian packages.
(cd "$build" && cpack -G DEB -B "$scratch/packages" >"$scratch/cpack.log" 2>&1) || fail "cpack: $(tail -3 "$scratch/cpack.log")"
arch=$(dpkg --print-architecture)
tool=$scratch/packages/keyrot_${version}_$arch.deb
dev=$scratch/packages/libkeyrot-dev_${version}_$arch.deb
for deb in "$tool" "$dev"; do [[ -f $deb ]] || fail "no package $(basename "$deb")"; done
field() { dpkg-deb -f "$1" "$2"; }
[[ $(field "$tool" Package) == keyrot && $(field "$tool" Version) == "$version" && $(field "$tool" Architecture) == "$arch" ]] &&
    ok "keyrot: Package, Version, Architecture" || fail "keyrot's control: $(dpkg-deb -f "$tool")"
# Depends: the package of every shared library the binary loads (none for the static build).
depends=$(field "$tool" Depends)
libraries=$(ldd "$build/keyrot" 2>/dev/null | awk '$3 ~ /^\// { print $3 }')
for library in $libraries; do
    package=$(dpkg -S "$(realpath "$library")" 2>/dev/null | head -1 | cut -d: -f1)
    [[ -n $package && $depends == *"$package"* ]] || fail "keyrot Depends '$depends' lacks $package ($library)"
done
[[ -n $libraries || -z $depends ]] && ok "keyrot Depends: '${depends}' for a binary that loads: ${libraries:-nothing}" ||
    fail "a static keyrot depends on '$depends'"
[[ $(field "$dev" Depends) == libfmt-dev* ]] && ok "libkeyrot-dev Depends: $(field "$dev" Depends)" || fail "libkeyrot-dev Depends: $(field "$dev" Depends)"
contents() { dpkg-deb -c "$1" | awk '{ print $6 }'; }
# (each list read whole before it is searched: under pipefail a grep -q that
# stops at its first match can fail the pipe of the writer it leaves)
tool_files=$(contents "$tool") dev_files=$(contents "$dev")
for file in ./usr/bin/keyrot ./usr/share/man/man1/keyrot.1.gz ./usr/share/bash-completion/completions/keyrot \
    ./usr/share/doc/keyrot/copyright ./usr/share/doc/keyrot/changelog.gz; do
    grep -qx -- "$file" <<<"$tool_files" || fail "keyrot lacks $file"
done
for file in ./usr/include/keyrot/interpolate.hpp ./usr/lib/libkeyrot_core.a ./usr/lib/cmake/keyrot/keyrot-config.cmake \
    ./usr/share/doc/libkeyrot-dev/copyright ./usr/share/doc/libkeyrot-dev/changelog.gz; do
    grep -qx -- "$file" <<<"$dev_files" || fail "libkeyrot-dev lacks $file"
done

# What a Debian maintainer runs first: no lintian error or warning (the
# static binary's error overridden, with the reason, by the package).
for deb in "$tool" "$dev"; do
    if lintian --fail-on error,warning "$deb" >"$scratch/lintian.log" 2>&1; then
        ok "lintian $(basename "$deb"): no errors or warnings"
    else
        fail "lintian $(basename "$deb"): $(grep -E '^[EW]:' "$scratch/lintian.log" | head -5)"
    fi
done

# Installed into a scratch root by dpkg itself (no network, no system change).
root=$scratch/root
mkdir -p "$root/var/lib/dpkg/updates" "$root/var/lib/dpkg/info" && touch "$root/var/lib/dpkg/status"
if dpkg --root="$root" --force-not-root --force-bad-path --force-script-chrootless --log=/dev/null -i "$tool" \
    >"$scratch/dpkg.log" 2>&1; then
    [[ $(dpkg --root="$root" -s keyrot 2>/dev/null | grep '^Status') == "Status: install ok installed" ]] &&
        ok "dpkg installs keyrot into a scratch root" || fail "dpkg status: $(dpkg --root="$root" -s keyrot 2>&1)"
    "$root/usr/bin/keyrot" resample "$source_dir/data/homework.json" --fps 4 --rep quat >/dev/null &&
        ok "the packaged keyrot resamples" || fail "the packaged keyrot does not run"
    [[ $(MANWIDTH=80 man -l "$root/usr/share/man/man1/keyrot.1.gz") == *"keyframe rotation interpolator"* ]] &&
        ok "the packaged man page reads" || fail "the packaged man page"
else
    fail "dpkg -i into a scratch root: $(tail -3 "$scratch/dpkg.log")"
fi
dpkg-deb -x "$dev" "$scratch/dev-root"
consumer=$scratch/consumer-deb
cmake -S "$source_dir/examples/slerp_between" -B "$consumer" -DCMAKE_PREFIX_PATH="$scratch/dev-root/usr" >/dev/null 2>&1 &&
    cmake --build "$consumer" >/dev/null 2>&1 && [[ $("$consumer/slerp_between") == "$expected" ]] &&
    ok "examples/slerp_between against libkeyrot-dev's files" || fail "examples/slerp_between against libkeyrot-dev"

((failures == 0)) || { echo "$failures install checks failed"; exit 1; }
echo "all install checks passed"
