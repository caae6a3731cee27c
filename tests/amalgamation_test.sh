#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/amalgamation_test.sh - `make amalgamation` writes one tinygi.c with
# every core source and one tinygi.h that includes no other tinygi header;
# `make examples EXAMPLES_LIB=amalgamation` compiles examples/minimal.c from
# them with the build's warnings (errors under DEV=1), both number types; the
# README's one cc line builds it too; each renders what the CLI renders.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh
A=$BUILD/amalgamation

if sub_make amalgamation >"$T/log" 2>&1; then ok "make amalgamation"
else fail "make amalgamation" "$(tail -n 10 "$T/log")"; fi
missing=""
for f in src/*/*.c; do grep -qx "#line 1 \"$f\"" "$A/tinygi.c" || missing="$missing $f"; done
expect "tinygi.c holds every core source" test -z "$missing"
[ -z "$missing" ] || echo "  missing:$missing"
expect "tinygi.c includes only \"tinygi.h\"" test "$(grep -c '^[ \t]*#[ \t]*include[ \t]*"' "$A/tinygi.c")" -eq 1
expect "tinygi.h includes no other tinygi header" test -z "$(grep '^[ \t]*#[ \t]*include[ \t]*"' "$A/tinygi.h")"
expect "tinygi.h is src/tinygi.h's API" grep -q 'tg_frame_render' "$A/tinygi.h"

if sub_make -j2 examples EXAMPLES_LIB=amalgamation >"$T/log" 2>&1; then ok "make examples EXAMPLES_LIB=amalgamation"
else fail "make examples EXAMPLES_LIB=amalgamation" "$(grep -m 10 -E 'error|warning' "$T/log")"; fi
for num in float fixed; do
    same_as_cli "examples from the amalgamation render what the CLI renders ($num)" \
        "$BUILD/$num/examples-amalgamation/minimal" $num
done

# the README's line, as printed (cc -> $CC, build/ -> $BUILD/, output in $T)
# with -O0 appended: it compiles in a second, and -O0 must give the same bits
line=$(readme_line amalgamation/tinygi.c)
expect "README has the amalgamation line" test -n "$line"
if [ -n "$line" ]; then
    cmd=${line//build\//$BUILD/}; cmd=${cmd/#cc /\$CC }; cmd="${cmd/-o minimal/-o \$T/minimal} -O0"
    if eval "$cmd" 2>"$T/cc.err"; then ok "README amalgamation line compiles"
    else fail "README amalgamation line compiles" "$cmd: $(head -n 10 "$T/cc.err")"; fi
    same_as_cli "README amalgamation line renders what the CLI renders" "$T/minimal" float
fi
# without built-in scenes (TG_NO_BUILTIN_SCENES=1) both examples say so and
# exit 1 (they passed NULL to strlen: a segfault, an outside probe)
for ex in minimal orbit; do
    # shellcheck disable=SC2086
    if $CC $TG_CFLAGS -O0 -DTG_NO_BUILTIN_SCENES=1 -I"$A" examples/$ex.c "$A/tinygi.c" -o "$T/$ex-nobuiltin" $TG_LDLIBS 2>"$T/cc.err"; then
        (cd "$T" && "./$ex-nobuiltin" >"$T/out" 2>&1); rc=$?
        if [ $rc = 1 ] && grep -q "no built-in scenes" "$T/out"; then ok "$ex without built-in scenes: says so, exit 1"
        else fail "$ex without built-in scenes" "exit $rc: $(head -c 300 "$T/out")"; fi
    else fail "$ex without built-in scenes compiles" "$(head -n 10 "$T/cc.err")"; fi
done
summary
