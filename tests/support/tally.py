# SPDX-License-Identifier: MIT
"""The checks of a Python test script (tests/*.py), shared by them all: each
printed as it is made, the failures kept for the summary, which gives the
script's exit status.

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
    from tally import check, fail, ok, summary  # noqa: E402
"""
checks, failures = 0, []


def ok(message):
    """A check that passed."""
    global checks
    checks += 1
    print("ok: " + message)


def fail(message):
    """A check that failed."""
    global checks
    checks += 1
    failures.append(message)
    print("FAIL: " + message)


def check(condition, message):
    (ok if condition else fail)(message)


def passed():
    """A check that passed without a word of its own (one of many alike)."""
    global checks
    checks += 1


def summary(name):
    """Prints how many checks passed; the script's exit status."""
    print(f"{name}: {checks - len(failures)} of {checks} checks passed")
    return 1 if failures else 0
