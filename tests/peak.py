"""Peak resident memory of a keyrot run, measured from outside (wait4)."""
import os
import subprocess
import sys

# A child's peak memory counts what it was forked from: keyrot is started
# from a bare Python, not from the test's own with numpy loaded.
PEAK = ("import os, sys\n"
        "pid = os.posix_spawn(sys.argv[1], sys.argv[1:], os.environ,\n"
        "                     file_actions=[(os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0)])\n"
        "_, status, usage = os.wait4(pid, 0)\n"
        "print(os.waitstatus_to_exitcode(status), usage.ru_maxrss)\n")


def peak_kb(keyrot, args, cwd=None):
    """Status and peak resident memory (KB) of `keyrot args` (standard output discarded)."""
    # (AddressSanitizer holds freed memory back to catch its reuse: not here.)
    asan = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"), "quarantine_size_mb=0"]))
    out = subprocess.run([sys.executable, "-S", "-c", PEAK, keyrot] + args, capture_output=True, check=True,
                         cwd=cwd, env=dict(os.environ, ASAN_OPTIONS=asan))
    status, kb = out.stdout.split()
    return int(status), int(kb)


if __name__ == "__main__":
    # peak.py KEYROT ARGS...: prints the status and the peak (KB) of one run.
    print(*peak_kb(sys.argv[1], sys.argv[2:]))
