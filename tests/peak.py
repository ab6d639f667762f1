# SPDX-License-Identifier: MIT
"""Peak resident memory of a keyrot run, measured from outside by GNU time."""
import os
import re
import subprocess
import sys
import tempfile

# Linux counts into a child's peak the memory of the process it was started
# from (a Python started it with 8 MB or more, which hid any smaller peak):
# GNU time, 1 MB, starts keyrot and writes its status and peak to a file.
TIME = "/usr/bin/time"


def peak_kb(keyrot, args, cwd=None):
    """Status and peak resident memory (KB) of `keyrot args` (standard output discarded)."""
    # (AddressSanitizer holds freed memory back to catch its reuse: not here.)
    asan = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"), "quarantine_size_mb=0"]))
    with tempfile.NamedTemporaryFile("r") as report:
        subprocess.run([TIME, "-f", "%x %M", "-o", report.name, keyrot] + args, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, cwd=cwd, env=dict(os.environ, ASAN_OPTIONS=asan))
        text = report.read()
    # The last line is ours; before it, "Command exited with non-zero status N" or
    # "Command terminated by signal N", where %x gives 0.
    status, kb = text.split()[-2:]
    signal = re.search(r"terminated by signal (\d+)", text)
    return -int(signal.group(1)) if signal else int(status), int(kb)


if __name__ == "__main__":
    # peak.py KEYROT ARGS...: prints the status and the peak (KB) of one run.
    print(*peak_kb(sys.argv[1], sys.argv[2:]))
