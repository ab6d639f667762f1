#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every example the README and the user guide show with its output, run and compared.

An example is a fenced block without a language whose lines begin with
"$ ": each such line is a command, and the lines after it, up to the next
command or the end of the block, are what it prints (standard output and
standard error together, in that order). A line "..." (or "  ...") in the
printed text stands for any lines, none included. The commands of a block
run one after another in one shell, in a scratch folder that holds a copy of
data/ (so "data/walk.csv" and "cd data" work as in a checkout), with the
keyrot under test first on the PATH (and as build/keyrot); files named by an
example that data/ lacks are made by the block's own earlier commands.

A block is not run where the line before its opening fence says so:
"<!-- not run: why -->" (a take the reader has, a terminal's bytes). Blocks
fenced as ```sh are shell snippets to copy (installing, building), never run.

Usage: docs_test.py KEYROT ROOT [FILE.md...] (default: README.md and
docs/guide.md under ROOT). Exit 0 when every example prints what it shows, 1
otherwise.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

KEYROT = os.path.abspath(sys.argv[1])
ROOT = os.path.abspath(sys.argv[2])
FILES = sys.argv[3:] or ["README.md", "docs/guide.md"]


def examples(path):
    """(line, commands) for each example of a Markdown file: commands as (command, expected lines)."""
    lines = open(path, encoding="utf-8").read().splitlines()
    out, i = [], 0
    while i < len(lines):
        fence = re.match(r"^(\s*)```(\S*)\s*$", lines[i])
        if not fence:
            i += 1
            continue
        indent, language, start = fence.group(1), fence.group(2), i
        skipped = start > 0 and lines[start - 1].strip().startswith("<!-- not run")
        i += 1
        body = []
        while i < len(lines) and lines[i].strip() != "```":
            body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i].lstrip())
            i += 1
        i += 1
        if language or skipped or not any(line.startswith("$ ") for line in body):
            continue
        commands = []
        for line in body:
            if line.startswith("$ "):
                commands.append((line[2:], []))
            elif commands:
                commands[-1][1].append(line)
        out.append((start + 1, commands))
    return out


def matches(got, want):
    """Whether the lines `got` are the lines `want`, each "..." any lines."""
    if not want:
        return not got
    if want[0].strip() == "...":
        return any(matches(got[k:], want[1:]) for k in range(len(got) + 1))
    return bool(got) and got[0] == want[0] and matches(got[1:], want[1:])


def run_block(commands, work):
    """What each command printed, run one after another in one shell in `work`."""
    marker = "@@keyrot-docs-test@@"
    script = ["set +e", "__status=0"]
    for command, _ in commands:
        # each command sees the status of the one before it ($?), as at a prompt
        script.append(f"(exit $__status); {{ {command}\n}} 2>&1; __status=$?; echo {marker}")
    env = dict(os.environ, PATH=os.path.dirname(os.path.join(work, "build", "keyrot")) + os.pathsep + os.environ["PATH"],
               LC_ALL="C.UTF-8")
    p = subprocess.run(["bash", "-c", "\n".join(script)], cwd=work, capture_output=True, text=True, env=env, timeout=120)
    printed = p.stdout.split(marker + "\n")
    return [part.splitlines() for part in printed[:len(commands)]] + [[]] * (len(commands) - len(printed[:len(commands)]))


def main():
    checked, failures = 0, []
    for name in FILES:
        path = os.path.join(ROOT, name)
        for line, commands in examples(path):
            work = tempfile.mkdtemp()
            shutil.copytree(os.path.join(ROOT, "data"), os.path.join(work, "data"))
            os.makedirs(os.path.join(work, "build"))
            os.symlink(KEYROT, os.path.join(work, "build", "keyrot"))
            printed = run_block(commands, work)
            for (command, want), got in zip(commands, printed):
                checked += 1
                if matches(got, want):
                    continue
                failures.append(f"{name}:{line}: $ {command}\n--- shown\n" + "\n".join(want) + "\n--- printed\n" +
                                "\n".join(got))
            shutil.rmtree(work)
    for f in failures:
        print("FAIL " + f + "\n")
    print(f"docs_test: {checked - len(failures)} of {checked} examples print what the docs show")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
