#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How many times keyrot reads each input, counted with strace.

The bytes read from every descriptor opened on the input, divided by its
size, is the number of passes over it. A pass reads the input from start
to end; a resample, convert or reduce into a file is one pass, and into a
stream (standard output, a pipe) two: every key is checked before the
first byte is written, except for a glTF or BVH output, which writes
nothing before its last row anyway (one pass). A glTF file (and the .bin beside it) is read once,
whatever the output: it is loaded by the first pass and read from memory
after, also by a glTF output that rewrites it. The inputs are large enough
(megabytes) that the first chunk one pass reads to learn the first key
does not count as a pass.

Usage: reads_test.py KEYROT. Exit 0 when all pass, 1 otherwise; 77 (skip)
where strace cannot trace.
"""
import os
import re
import subprocess
import sys
import tempfile

# A pass, give or take the first chunk (64 KiB) read to learn the first key.
SLACK = 0.1


def reads(path, command, cwd):
    """The passes `command` makes over `path` (and its exit status)."""
    # LeakSanitizer cannot work under ptrace: a sanitizer build traced checks no leaks.
    env = dict(os.environ, ASAN_OPTIONS=(os.environ.get("ASAN_OPTIONS", "") + ":detect_leaks=0").lstrip(":"))
    with tempfile.NamedTemporaryFile(suffix=".strace") as log:
        run = subprocess.run(["strace", "-f", "-qq", "-e", "trace=openat,read,pread64", "-o", log.name] + command,
                             cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        if run.returncode != 0:
            print(run.stderr.decode(errors="replace").strip()[-400:])
        target = os.path.realpath(os.path.join(cwd, path))
        descriptors, total = set(), 0
        with open(log.name) as lines:
            for line in lines:
                opened = re.search(r'openat\(AT_FDCWD, "([^"]*)".*= (\d+)$', line)
                if opened:
                    fd = int(opened.group(2))
                    if os.path.realpath(os.path.join(cwd, opened.group(1))) == target:
                        descriptors.add(fd)
                    else:
                        descriptors.discard(fd)  # the number reused for another file
                    continue
                read = re.search(r"\b(?:pread64|read)\((\d+),.*= (\d+)$", line)
                if read and int(read.group(1)) in descriptors:
                    total += int(read.group(2))
    return total / os.path.getsize(target), run.returncode


def main():
    keyrot = os.path.abspath(sys.argv[1])
    if subprocess.run(["strace", "-f", "-qq", "-o", os.devnull, "true"], capture_output=True).returncode != 0:
        print("strace cannot trace here: skipped")
        return 77
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "keys.csv"), "w") as f:  # 100,000 keys at 200 Hz, about 3 MB
            f.write("time,ax,ay,az,angle\n")
            for i in range(100000):
                f.write(f"{i / 200},0,0.6,0.8,{(i * 0.7) % 360:.4f}\n")
        with open(os.path.join(work, "take.bvh"), "w") as f:  # 50,000 frames of two joints, about 2.5 MB
            f.write("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation "
                    "Xrotation Yrotation\n  JOINT Leg\n  {\n    OFFSET 0 -1 0\n    CHANNELS 3 Zrotation Xrotation "
                    "Yrotation\n    End Site\n    {\n      OFFSET 0 -1 0\n    }\n  }\n}\nMOTION\nFrames: 50000\n"
                    "Frame Time: 0.008333\n")
            for i in range(50000):
                f.write(" ".join(f"{(i * 0.37 * (j + 1)) % 90:.4f}" for j in range(9)) + "\n")
        for made in (["convert", "keys.csv", "-o", "keys.glb"], ["convert", "keys.csv", "-o", "keys.gltf"]):
            subprocess.run([keyrot] + made, cwd=work, check=True)
        cases = [  # (input counted, command, passes)
            ("keys.csv", ["resample", "keys.csv", "-o", "out.csv"], 1),
            ("keys.csv", ["resample", "keys.csv"], 2),
            ("keys.csv", ["convert", "keys.csv", "--to", "ndjson"], 2),
            ("keys.csv", ["resample", "keys.csv", "-o", "out.glb"], 1),
            ("keys.csv", ["resample", "keys.csv", "--to", "glb"], 1),
            ("keys.csv", ["reduce", "keys.csv", "-o", "kept.csv"], 1),
            ("keys.glb", ["resample", "keys.glb", "-o", "out.glb"], 1),
            ("keys.glb", ["resample", "keys.glb", "--to", "glb"], 1),
            ("keys.glb", ["resample", "keys.glb", "-o", "out.csv"], 1),
            ("keys.glb", ["resample", "keys.glb", "--to", "csv"], 1),
            ("keys.glb", ["reduce", "keys.glb", "-o", "kept.glb"], 1),
            ("keys.gltf", ["resample", "keys.gltf", "-o", "out.gltf"], 1),
            ("keys.bin", ["resample", "keys.gltf", "-o", "out.gltf"], 1),
            ("keys.bin", ["convert", "keys.gltf", "--to", "csv"], 1),
            ("take.bvh", ["resample", "take.bvh", "-o", "out.bvh"], 1),
            ("take.bvh", ["resample", "take.bvh"], 1),
            ("take.bvh", ["resample", "take.bvh", "--to", "csv"], 2),
            ("take.bvh", ["resample", "take.bvh", "-o", "out.glb"], 1),
        ]
        failures = 0
        for path, command, passes in cases:
            got, status = reads(path, [keyrot] + command, work)
            line = f"keyrot {' '.join(command)}: {path} read {got:.3f} times, expected {passes}"
            if status != 0 or not passes - 0.001 <= got <= passes + SLACK:
                failures += 1
                print(f"FAIL {line}" + (f" (exit {status})" if status else ""))
            else:
                print(f"ok   {line}")
    print(f"{failures} read counts wrong" if failures else "all read counts as expected")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
