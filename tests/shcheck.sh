# SPDX-License-Identifier: MIT
# tests/shcheck.sh - sourced by the script tests: ok/fail counting that
# matches check.h ("ok NAME" / "FAIL NAME", then "TESTS passed N failed M").
sh_passed=0; sh_failed=0
ok()   { echo "ok $1"; sh_passed=$((sh_passed + 1)); }
fail() { echo "FAIL $1${2:+: $2}"; sh_failed=$((sh_failed + 1)); }
# expect NAME COND-EXIT-STATUS...: run "$@" after the name; pass when it succeeds
expect() { local name=$1; shift; if "$@"; then ok "$name"; else fail "$name"; fi; }
summary() { echo "TESTS passed $sh_passed failed $sh_failed"; [ "$sh_failed" -eq 0 ]; }
