#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# purity_test.sh - the core is pure: it includes nothing but <stdint.h>,
# <stddef.h>, <string.h>; says no `double`; the compiled libraries (built
# with -ffreestanding) need nothing from outside but string.h functions and
# compiler helpers, and export nothing but the public API of src/tinygi.h
# (with its number-type suffix) and internal tgi_ names.
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

tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
tmp_api=$tmp

allowed='^(memcpy|memset|memmove|memcmp|strlen|strcmp|strncmp|strchr|strrchr|__.*)$'
for lib in "$BUILD/libtinygi.a" "$BUILD/libtinygi-fixed.a"; do
    defined=$(nm -g --defined-only "$lib" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u)
    undefined=$(nm -u "$lib" 2>/dev/null | awk 'NF >= 2 {print $2}' | sort -u)
    outside=$(comm -23 <(echo "$undefined") <(echo "$defined") | grep -vE "$allowed" | tr '\n' ' ')
    expect "$(basename "$lib") needs only string.h and compiler helpers" test -z "$outside"
    [ -z "$outside" ] || echo "  outside symbols: $outside"
done

# the libraries export only the public API (the functions src/tinygi.h
# declares, each carrying its number type: _f32 or _q16) and tgi_ names
echo '#include "tinygi.h"' >"$tmp_api/api.c"
for num in float fixed; do
    lib=$BUILD/libtinygi.a; def=; sfx=_f32
    [ $num = fixed ] && { lib=$BUILD/libtinygi-fixed.a; def=-DTG_FIXED=1; sfx=_q16; }
    # gcc's -aux-info lists every prototype with its file, after the macros
    rm -f "$tmp_api/aux.txt"
    if ! command -v gcc >/dev/null; then echo "# no gcc: the exported names are not checked"; break; fi
    gcc -std=c99 -Isrc $def -aux-info "$tmp_api/aux.txt" -c "$tmp_api/api.c" -o "$tmp_api/api.o" 2>/dev/null ||
        { fail "$num: list tinygi.h's functions (gcc -aux-info)"; continue; }
    declared=$(grep -E '^/\* src/tinygi.h:' "$tmp_api/aux.txt" | grep -v ' \*/ static ' |
               sed -E 's/^\/\* [^*]*\*\/ //; s/ \(.*//; s/.*[ *]//' | sort -u)
    exported=$(nm -g --defined-only "$lib" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u)
    unsuffixed=$(echo "$declared" | grep -v -- "$sfx\$" | tr '\n' ' ')
    expect "$num: every function tinygi.h declares carries $sfx (add '#define tg_NAME TG_ABI(tg_NAME)' to its ABI block)" \
        test -z "$unsuffixed"
    [ -z "$unsuffixed" ] || echo "  without the suffix: $unsuffixed"
    extra=$(comm -23 <(echo "$exported") <(echo "$declared") | grep -vE '^(tgi_|__)' | tr '\n' ' ')
    expect "$(basename "$lib") exports only tinygi.h's functions and tgi_ names" test -z "$extra"
    [ -z "$extra" ] || echo "  exported but not public API (make them static or tgi_): $extra"
    missing=$(comm -13 <(echo "$exported") <(echo "$declared") | tr '\n' ' ')
    expect "$(basename "$lib") defines every function tinygi.h declares" test -z "$missing"
    [ -z "$missing" ] || echo "  declared, not defined: $missing"
done

# the whole core compiles freestanding with no libc headers but the compiler's own
ok_build=1
excess=-fexcess-precision=fast   # gcc's; clang does not know it
echo 'int x;' >"$tmp/probe.c"
${CC:-cc} $excess -Werror -c "$tmp/probe.c" -o "$tmp/probe.o" 2>/dev/null || excess=
for f in src/*/*.c; do
    ${CC:-cc} -std=c99 -ffreestanding -fno-builtin -nostdlib -Wall -Wextra -Wpedantic -Werror \
        ${REPRO--ffp-contract=off $excess} -DTG_FIXED=1 -c "$f" -o "$tmp/x.o" 2>"$tmp/err" || { ok_build=0; head -5 "$tmp/err"; }
done
expect "core compiles with -ffreestanding -nostdlib (fixed point)" test "$ok_build" = 1
summary
