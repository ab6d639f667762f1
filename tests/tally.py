# SPDX-License-Identifier: MIT
"""A test script's checks: each printed as it is made, the failures kept for the summary."""
checks, failures = 0, []


def check(condition, message):
    global checks
    checks += 1
    if condition:
        print("ok: " + message)
    else:
        failures.append(message)
        print("FAIL: " + message)


def summary(name):
    """Prints how many checks passed; the script's exit status."""
    print(f"{name}: {checks - len(failures)} of {checks} checks passed")
    return 1 if failures else 0
