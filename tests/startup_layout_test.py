#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The code a small run executes is laid out together at the front of the
program (src/dist/startup.ld; docs/design.md, "Start-up"), and the list
still names the code there is: checked in the link map of the build.
Skipped (77) for a program built by another toolchain than the list was
written for, whose functions and C library objects have other names.

    startup_layout_test.py BUILD/keyrot BUILD/keyrot.map SRC/dist/startup.ld
"""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
from tally import check, summary  # noqa: E402

SECTION = ".text.startup_path"
# Functions every run executes, which the layout must hold (CLI11's App,
# the CSV row and cell splitter: names link-time optimisation has changed
# before, leaving a list that still matched most of the program).
EVERY_RUN = ("main", "keyrot::parse_command_line(", "__libc_start_main", "keyrot::write_number(", "CLI::App::App(")
# The same for functions the map may name by their section alone (a local
# symbol of one link-time partition, as the partitions fall): the CSV
# writer's row and the CSV reader's cell splitter.
EVERY_RUN_SECTIONS = (".text._ZN6keyrot12_GLOBAL__N_110csv_writer3row",
                      ".text._ZN6keyrot12_GLOBAL__N_113cell_splitter5split")
# A list written for other code (functions renamed, cloned or gone) would
# leave more of it unmatched than this.
MOST_UNMATCHED = 0.1



def main():
    binary, map_path, script_path = sys.argv[1], sys.argv[2], sys.argv[3]
    sys.dont_write_bytecode = True  # (nothing written into the sources)
    sys.path.insert(0, os.path.dirname(os.path.abspath(script_path)))
    from startup_order import toolchain  # the list's own reading of it
    script = open(script_path, encoding="utf-8").read()
    written_for = re.search(r"Toolchain: (.*?) \*/", script)
    if not written_for or written_for.group(1) != toolchain(binary):
        print(f"{script_path} was written for {written_for.group(1) if written_for else 'another toolchain'}, "
              f"this keyrot built by {toolchain(binary)}: skipped")
        sys.exit(77)
    listed = [line.strip() for line in script.split("\n") if line.strip().startswith("*")]
    lines = open(map_path, encoding="utf-8", errors="replace").read().split("\n")
    start = next((i for i, line in enumerate(lines) if line.strip() == SECTION or line.startswith(SECTION + " ")),
                 None)
    if start is None:
        sys.exit(f"FAIL: no {SECTION} in {map_path}: was the program linked with {script_path}?")
    end = next(i for i in range(start + 1, len(lines)) if lines[i] and not lines[i][0].isspace())
    block = lines[start:end]
    size = int(re.search(r"0x[0-9a-f]+\s+(0x[0-9a-f]+)", "\n".join(block[:2])).group(1), 16)

    # Each pattern the linker echoes, and whether a section follows it before the next.
    patterns, matched = [], set()
    for line in block:
        if line.startswith(" *") and not line.startswith(" *fill*"):
            patterns.append(line.strip())
        elif line.startswith(" .text") and patterns:
            matched.add(patterns[-1])
    unmatched = [p for p in patterns if p not in matched]
    check(len(patterns) == len(listed), f"{len(listed)} patterns in {script_path}, {len(patterns)} in the map")
    check(len(unmatched) <= MOST_UNMATCHED * len(patterns),
          f"{len(unmatched)} of the {len(patterns)} sections listed are not in the program "
          f"(e.g. {unmatched[:3]}): run src/dist/startup_order.py")
    check(size > 64 * 1024, f"{SECTION} holds only {size} bytes")
    text = "\n".join(block)
    for name in EVERY_RUN:
        check(re.search(r"^\s+0x[0-9a-f]+\s+" + re.escape(name), text, re.M) is not None,
              f"{name} is not in {SECTION}")
    for name in EVERY_RUN_SECTIONS:
        check(re.search(r"^ " + re.escape(name), text, re.M) is not None, f"{name}* is not in {SECTION}")
    print(f"{len(patterns) - len(unmatched)} of {len(patterns)} sections listed laid out together, {size} bytes")
    sys.exit(summary("startup_layout_test"))


if __name__ == "__main__":
    main()
