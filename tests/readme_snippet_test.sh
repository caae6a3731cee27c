#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/readme_snippet_test.sh - the README's embedding example cannot drift
# from the code: the C between the markers "<!-- begin examples/minimal.c -->"
# and "<!-- end examples/minimal.c -->" in README.md is examples/minimal.c
# (from its first #include on), and it compiles with the build's flags against
# both built libraries and renders the same image as the CLI; and the
# README's `--explain` example is what that command prints.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh

awk '/^<!-- begin examples\/minimal.c -->/ { on = 1; next } /^<!-- end examples\/minimal.c -->/ { on = 0 }
     on && !/^```/' README.md >"$T/snippet.c"
expect "README has the examples/minimal.c snippet" test -s "$T/snippet.c"
sed -n '/^#include/,$p' examples/minimal.c >"$T/minimal-body.c"
if diff -u "$T/minimal-body.c" "$T/snippet.c" >"$T/diff"; then ok "README snippet is examples/minimal.c"
else fail "README snippet is examples/minimal.c" "$(head -n 20 "$T/diff")"; fi

for num in float fixed; do
    # shellcheck disable=SC2086 # flag lists are split into words on purpose
    if $CC $TG_CFLAGS $(numdef $num) -Isrc "$T/snippet.c" "$BUILD/libtinygi$(suffix $num).a" \
        -o "$T/snippet-$num" $TG_LDLIBS 2>"$T/cc.err"; then ok "README snippet compiles ($num)"
    else fail "README snippet compiles ($num)" "$(head -n 10 "$T/cc.err")"; continue; fi
    same_as_cli "README snippet renders what the CLI renders ($num)" "$T/snippet-$num" $num
done
# The README's --explain example is that command's output today (the plan,
# its passes and every buffer's bytes): it cannot go stale.
awk '$0 == "$ build/tinygi render builtin:cornell --explain" { on = 1; next } on && /^```/ { exit } on' \
    README.md >"$T/explain-readme.txt"
expect "README has the --explain example" test -s "$T/explain-readme.txt"
if "$BUILD/tinygi" render builtin:cornell --explain >"$T/explain.txt" 2>&1 \
    && diff -u "$T/explain-readme.txt" "$T/explain.txt" >"$T/explain.diff"; then
    ok "README --explain example is the CLI's output"
else fail "README --explain example is the CLI's output" "$(head -n 20 "$T/explain.diff" 2>/dev/null)"; fi
summary
