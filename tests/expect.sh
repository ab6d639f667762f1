# SPDX-License-Identifier: MIT
# Shared by the shell tests: sourced, not run. Needs $work (a scratch
# directory). Counts into $passed and $failed; `summary` prints the closing
# line and returns the status.
passed=0
failed=0

fail() {
    failed=$((failed + 1))
    printf 'FAIL %s\n' "$*"
}

# expect NAME STATUS EXPECTED_STDOUT -- COMMAND...
expect() {
    local name=$1 status=$2 want=$3
    shift 4
    local got rc
    got=$("$@" 2>"$work/stderr")
    rc=$?
    if [[ $rc == "$status" && $got == "$want" ]]; then
        passed=$((passed + 1))
    else
        fail "$name: status $rc (want $status)
--- got
$got
--- want
$want
--- stderr
$(cat "$work/stderr")"
    fi
}

# expect_error NAME EXPECTED_STDERR_LINE -- COMMAND...: status 2, nothing on
# stdout, exactly that one line on stderr
expect_error() {
    local name=$1 want=$2
    shift 3
    local got rc
    got=$("$@" 2>"$work/stderr")
    rc=$?
    local err
    err=$(cat "$work/stderr")
    if [[ $rc == 2 && -z $got && $err == "$want" && $(wc -l <"$work/stderr") == 1 ]]; then
        passed=$((passed + 1))
    else
        fail "$name: status $rc, stdout [${got:0:80}], stderr [$err], want [$want]"
    fi
}

summary() {
    echo "$passed passed, $failed failed"
    [[ $failed == 0 ]]
}
