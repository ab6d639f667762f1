#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The coverage each fuzz target reaches on its checked-in corpus, checked.

For each target of tests/fuzz/floors: libFuzzer's coverage points ("cov")
on the corpus run once (-runs=0), printed with the floor recorded there.
It fails when:
- the coverage is more than 3% below the floor (a target that stopped
  reaching the code: raise the floor when a change reaches more);
- the corpus in another order (shuffled, two seeds) reaches more than 1%
  more or less (a run that leaves state behind for the next: the threads'
  timing moves a few points);
- some seed run alone reaches more than the whole corpus does (the seeds
  written by hand, and of the fuzzers' seeds enough, evenly spread, to run
  SAMPLE in all);
- a target (tests/fuzz/fuzz_*.cpp) has no floor.

Usage: coverage.py BUILD_DIR [TARGET...]. Exit 0 when all pass, 1 otherwise.
"""
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
SLACK_BELOW_FLOOR = 0.03
SLACK_BETWEEN_ORDERS = 0.01
SAMPLE = 200  # seeds run alone: a process each


def floors():
    out = {}
    with open(os.path.join(HERE, "floors")) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                out[line[0]] = int(line[1])
    return out


def coverage(binary, corpus, *flags):
    """libFuzzer's coverage points after running `corpus` once."""
    p = subprocess.run([binary, "-runs=0", "-rss_limit_mb=2048", *flags, corpus],
                       capture_output=True, text=True, cwd=tempfile.gettempdir())
    found = re.search(r"INITED cov: (\d+)", p.stderr)
    if p.returncode != 0 or not found:
        raise SystemExit(f"{os.path.basename(binary)} {corpus}: status {p.returncode}\n{p.stderr[-2000:]}")
    return int(found.group(1))


def alone(binary, corpus, seeds):
    """The coverage of each seed run by itself."""
    with tempfile.TemporaryDirectory() as scratch:
        def one(i_seed):
            i, seed = i_seed
            d = os.path.join(scratch, str(i))
            os.mkdir(d)
            os.symlink(os.path.join(corpus, seed), os.path.join(d, "seed"))
            return coverage(binary, d)
        with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
            return list(pool.map(one, enumerate(seeds)))


def sampled(seeds):
    """The seeds to run alone: every one written by hand (named, not a
    fuzzer's hash), and the fuzzers' evenly spread, SAMPLE in all."""
    named = [s for s in seeds if not re.fullmatch(r"[0-9a-f]{40}", s)]
    found = [s for s in seeds if s not in named]
    room = max(0, SAMPLE - len(named))
    if len(found) > room:
        found = [found[i * len(found) // room] for i in range(room)]
    return named + found


def main():
    build = os.path.abspath(sys.argv[1])
    wanted = floors()
    targets = sys.argv[2:] or list(wanted)
    sources = sorted(f[len("fuzz_"):-len(".cpp")] for f in os.listdir(HERE) if re.fullmatch(r"fuzz_\w+\.cpp", f))
    failed = sorted(wanted) != sources
    if failed:
        print(f"FAIL: the targets {', '.join(sources)} and the floors of {', '.join(wanted)} differ")
    for target in targets:
        binary = os.path.join(build, f"fuzz_{target}")
        corpus = os.path.join(HERE, "corpus", target)
        seeds = sorted(os.listdir(corpus))
        whole = coverage(binary, corpus)
        orders = [coverage(binary, corpus, "-prefer_small=0", f"-seed={s}") for s in (1, 2)]
        sample = sampled(seeds)
        each = alone(binary, corpus, sample)
        best = max(range(len(sample)), key=lambda i: each[i])
        floor = wanted[target]
        print(f"fuzz_{target}: {whole} points on its {len(seeds)} seeds (floor {floor}); "
              f"in other orders {', '.join(map(str, orders))}; one seed alone at most {each[best]} ({sample[best]}, of {len(sample)})")
        problems = []
        if whole < floor * (1 - SLACK_BELOW_FLOOR):
            problems.append(f"{whole} points is {100 * (1 - whole / floor):.1f}% below the floor of {floor}")
        spread = max(orders + [whole]) - min(orders + [whole])
        if spread > whole * SLACK_BETWEEN_ORDERS:
            problems.append(f"the seeds in another order reach {spread} points more or less: a run leaves state behind")
        if each[best] > whole:
            problems.append(f"{sample[best]} alone reaches {each[best]} points, more than the whole corpus")
        for p in problems:
            print(f"  FAIL fuzz_{target}: {p}")
        failed = failed or bool(problems)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
