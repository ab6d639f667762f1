#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes src/dist/startup.ld: the code a small run of keyrot executes, to be
laid out together at the front of the program (docs/design.md, "Start-up").

    python3 src/dist/startup_order.py BUILD_DIR

BUILD_DIR holds a static GCC build of keyrot and the link map it writes
(keyrot.map). Each command below runs once under Valgrind's lackey, which
lists every instruction executed; the input sections (functions, or a C
library object's code) holding them are listed in the order the commands
first reach them, so that code every command runs comes first and a format's
own code sits together. Valgrind's CPU is not the machine's: the C library's
string functions are listed in every variant the library has, whichever
one a CPU picks. A function is listed with every clone GCC makes of it
(name.lto_priv.0, name.isra.0: the suffixes come and go with changes
elsewhere in the program). Run it again after changes that rename or add
functions on the everyday path: a name the linker does not find is skipped,
so a stale list costs start-up time, never correctness.
"""
import bisect
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "data")
OUT = os.path.join(ROOT, "src", "dist", "startup.ld")

# Small runs of the everyday commands and formats, the most common first.
COMMANDS = [
    ["resample", "{data}/walk.csv", "-o", "{tmp}/out.csv"],
    ["resample", "{data}/walk.csv", "-o", "{tmp}/out.csv"],  # (replacing a file is another path)
    ["resample", "{data}/walk.csv"],
    ["convert", "{data}/walk.csv", "--rep", "euler", "--euler", "xyz", "-o", "{tmp}/euler.csv"],
    ["convert", "{data}/walk.csv", "--rep", "matrix"],
    ["info", "{data}/walk.csv"],
    ["reduce", "{data}/walk.csv", "-o", "{tmp}/reduced.csv"],
    ["compare", "{data}/walk.csv", "{tmp}/out.csv"],
    ["resample", "{data}/head_turn.json", "-o", "{tmp}/out.json"],
    ["convert", "{data}/head_turn.json", "-o", "{tmp}/out.ndjson"],
    ["resample", "{tmp}/out.ndjson", "--fps", "30"],
    ["resample", "{data}/arm_wave.gltf", "--fps", "30", "-o", "{tmp}/out.glb"],
    ["resample", "{data}/capture.bvh", "-o", "{tmp}/out.csv"],
]

# What Valgrind cannot show: the static C library looks up the kernel's
# vDSO (its clock_gettime) at start, and Valgrind gives the program none.
VDSO_SETUP = ("dl-object.o", "dl-setup_hash.o", "dl-lookup.o", "dl-misc.o")

# The suffixes of GCC's clones of a function (partitioning, dropped or
# constant arguments, a split-off part), chained as GCC chains them.
CLONE_SUFFIX = re.compile(r"(?:\.(?:lto_priv|isra|constprop|part)\.[0-9]+)+$")
SECTION = re.compile(r"^ (\.text\S*)(?:\s+(0x[0-9a-f]+)\s+(0x[0-9a-f]+)\s+(\S.*))?$")
PLACED = re.compile(r"^\s+(0x[0-9a-f]+)\s+(0x[0-9a-f]+)\s+(\S.*)$")


def code_sections(map_path):
    """(address, size, section name, input file) of each piece of code placed."""
    sections = []
    lines = open(map_path, encoding="utf-8", errors="replace").read().split("\n")
    for i, line in enumerate(lines):
        m = SECTION.match(line)
        if not m:
            continue
        name, where = m.group(1), m.groups()[1:]
        if where[0] is None:  # a long name: the address, size and file on the next line
            placed = PLACED.match(lines[i + 1]) if i + 1 < len(lines) else None
            if not placed:
                continue
            where = placed.groups()
        address, size = int(where[0], 16), int(where[1], 16)
        if address > 0 and size > 0:  # (discarded sections are listed at 0)
            sections.append((address, size, name, where[2].strip()))
    return sorted(sections)


def executed(binary, command, tmp):
    """The addresses of the instructions `binary command` executes."""
    log = os.path.join(tmp, "lackey.log")
    args = [a.format(data=DATA, tmp=tmp) for a in command]
    run = subprocess.run(["valgrind", "--tool=lackey", "--trace-mem=yes", f"--log-file={log}", binary, *args],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode not in (0, 1):  # (compare's 1: rotations apart)
        sys.exit(f"startup_order.py: keyrot {' '.join(args)} failed: {run.stderr.strip()}")
    addresses = set()
    with open(log, encoding="utf-8", errors="replace") as f:
        for line in f:
            if line.startswith("I"):
                addresses.add(int(line.split()[1].split(",")[0], 16))
    os.remove(log)
    return addresses


def toolchain(binary):
    """The compilers that built `binary`, as its .comment section names them
    (the list's names of functions and of the C library's objects are theirs)."""
    dump = subprocess.run(["readelf", "-p", ".comment", binary], capture_output=True, text=True).stdout
    return "; ".join(re.findall(r"^\s*\[\s*[0-9a-f]+\]\s+(.*\S)\s*$", dump, re.M))


def pattern(name, input_file):
    """A linker script input-section pattern for the section, or None."""
    archive = re.match(r"^(.*)\((.*)\)$", input_file)
    if archive:  # a library's member (a C library object's code is all named .text)
        return f"*{os.path.basename(archive.group(1))}:{archive.group(2)}({name})"
    if ".ltrans" in input_file:  # keyrot's own code, a section a function, with its clones
        if name == ".text":
            return None
        function = CLONE_SUFFIX.sub("", name)
        return f"*({function} {function}.*)"
    return f"*{os.path.basename(input_file)}({name})"  # the C run-time's start files


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    build = sys.argv[1]
    binary, map_path = os.path.join(build, "keyrot"), os.path.join(build, "keyrot.map")
    if not shutil.which("valgrind"):
        sys.exit("startup_order.py: needs valgrind (apt install valgrind)")
    sections = code_sections(map_path)
    starts = [s[0] for s in sections]
    order, seen = [], set()
    with tempfile.TemporaryDirectory() as tmp:
        for command in COMMANDS:
            hit = set()
            for a in executed(binary, command, tmp):
                i = bisect.bisect_right(starts, a) - 1
                if i >= 0 and a < sections[i][0] + sections[i][1] and i not in seen:
                    hit.add(i)
            seen |= hit
            order.extend(sorted(hit))
    # Every variant of the C library's string functions the runs reached
    # (but Intel's transactional ones), and its vDSO set-up.
    variants = re.compile(r"^(.*libc\.a)\(((?:str|mem|stp|wcs|wmem)[a-z]*)-[a-z0-9_-]+\.o\)$")
    families = {m.groups() for i in order if (m := variants.match(sections[i][3]))}
    vdso_setup = tuple(f"libc.a({member})" for member in VDSO_SETUP)
    for i, (_, _, _, input_file) in enumerate(sections):
        m = variants.match(input_file)
        wanted = (m and m.groups() in families and "-rtm" not in input_file) or input_file.endswith(vdso_setup)
        if wanted and i not in seen:
            seen.add(i)
            order.append(i)
    patterns = {}  # (ordered)
    for i in order:
        p = pattern(sections[i][2], sections[i][3])
        if p:
            patterns.setdefault(p, sections[i][1])
    with open(OUT, "w", encoding="utf-8") as f:
        f.write("/* Written by src/dist/startup_order.py (run it again rather than edit):\n"
                "   the code small runs of keyrot execute, laid out together.\n"
                f"   Toolchain: {toolchain(binary)} */\n")
        f.write("SECTIONS {\n  .text.startup_path : {\n")
        f.writelines(f"    {p}\n" for p in patterns)
        f.write("  }\n} INSERT BEFORE .text;\n")
    print(f"{OUT}: {len(patterns)} sections, {sum(patterns.values())} bytes")


if __name__ == "__main__":
    main()
