#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/hbil_alone_test.sh - the Q16.16 test_hbil run on its own, with no
# float run before it (so no float AO beside the float binary), still
# compares against float: it runs the float binary for that file itself
# (it failed "missing ... (run the float test first)" before).
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
BUILD=${BUILD:-build}
fixed="$BUILD/fixed/tests/test_hbil" float="$BUILD/float/tests/test_hbil"
file="$BUILD/float/tests/hbil_groove_ao.f32"
if [ -x "$fixed" ] && [ -x "$float" ]; then
    saved=$(mktemp); trap 'rm -f "$saved"' EXIT
    had=0; [ -f "$file" ] && { cp "$file" "$saved"; had=1; }
    rm -f "$file"
    out=$("$fixed" 2>&1); rc=$?
    if [ $rc -eq 0 ] && [ -f "$file" ] && printf '%s\n' "$out" | grep -q '^ok .*/fixed_and_float_agree$' \
        && printf '%s\n' "$out" | grep -q 'fixed vs float AO RMSE'; then
        ok fixed_test_hbil_alone_compares_against_float
    else
        fail fixed_test_hbil_alone_compares_against_float "exit $rc"
        printf '%s\n' "$out" | grep -v '^ok ' | head -n 20
    fi
    [ $had -eq 1 ] && cp "$saved" "$file"
else
    fail fixed_test_hbil_alone_compares_against_float "$fixed or $float not built"
fi
summary
