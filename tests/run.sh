#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/run.sh - run every test program (both number types) and every script
# test, then print the one closing line "N passed, N failed".
set -u
BUILD=${BUILD:-build}
cd "$(dirname "$0")/.."
passed=0; failed=0
log=$(mktemp); trap 'rm -f "$log"' EXIT

tally() { # reads a program's output on $log
    local p f
    p=$(awk '/^TESTS passed/ {s += $3} END {print s + 0}' "$log")
    f=$(awk '/^TESTS passed/ {s += $5} END {print s + 0}' "$log")
    passed=$((passed + p)); failed=$((failed + f))
    grep -E '^(FAIL|ok)' "$log" | grep '^FAIL' || true
}

for num in float fixed; do
    for t in "$BUILD"/$num/tests/test_*; do
        [ -x "$t" ] || continue
        if ! "$t" >"$log" 2>&1; then
            if ! grep -q '^TESTS passed' "$log"; then
                echo "FAIL $num/$(basename "$t"): crashed or exited early"; tail -n 20 "$log"
                failed=$((failed + 1)); continue
            fi
            grep -v '^ok ' "$log" | head -n 40
        fi
        tally
    done
done

for s in tests/*_test.sh; do
    [ -f "$s" ] || continue
    if ! BUILD="$BUILD" bash "$s" >"$log" 2>&1; then
        grep -q '^TESTS passed' "$log" || { echo "FAIL $(basename "$s"): exited early"; tail -n 20 "$log"; failed=$((failed + 1)); continue; }
        grep -v '^ok ' "$log" | head -n 40
    fi
    tally
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
