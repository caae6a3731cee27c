#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# purity_test.sh - the core is pure (issue 2 item 2): it includes nothing
# but <stdint.h>, <stddef.h>, <string.h>; says no `double`; and the compiled
# libraries (built with -ffreestanding) need nothing from outside but
# string.h functions and compiler helpers.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
BUILD=${BUILD:-build}

bad=$(grep -rhoE '#include *<[^>]+>' src | sort -u | grep -vE '<(stdint|stddef|string)\.h>')
expect "core includes only stdint.h, stddef.h, string.h" test -z "$bad"
[ -z "$bad" ] || echo "  found: $bad"

dbl=$(grep -rnwE 'double|long double' src --include='*.c' --include='*.h' | grep -vE '^\S+:[0-9]+:\s*(/\*|\*|//)')
expect "core has no double" test -z "$dbl"
[ -z "$dbl" ] || echo "$dbl" | head -5

allowed='^(memcpy|memset|memmove|memcmp|strlen|strcmp|strncmp|strchr|strrchr|__.*)$'
for lib in "$BUILD/libtinygi.a" "$BUILD/libtinygi-fixed.a"; do
    defined=$(nm -g --defined-only "$lib" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u)
    undefined=$(nm -u "$lib" 2>/dev/null | awk 'NF >= 2 {print $2}' | sort -u)
    outside=$(comm -23 <(echo "$undefined") <(echo "$defined") | grep -vE "$allowed" | tr '\n' ' ')
    expect "$(basename "$lib") needs only string.h and compiler helpers" test -z "$outside"
    [ -z "$outside" ] || echo "  outside symbols: $outside"
done

# the whole core compiles freestanding with no libc headers but the compiler's own
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
ok_build=1
for f in src/*/*.c; do
    ${CC:-cc} -std=c99 -ffreestanding -fno-builtin -nostdlib -Wall -Wextra -Wpedantic -Werror \
        ${REPRO--ffp-contract=off -fexcess-precision=fast} -DTG_FIXED=1 -c "$f" -o "$tmp/x.o" 2>"$tmp/err" || { ok_build=0; head -5 "$tmp/err"; }
done
expect "core compiles with -ffreestanding -nostdlib (fixed point)" test "$ok_build" = 1
summary
