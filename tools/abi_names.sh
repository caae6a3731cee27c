#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/abi_names.sh - write (or check) src/core/abi_names.h, the list that
# gives every external symbol of the core its number type: one line
# `#define tgi_NAME TG_ABI(tgi_NAME)` per global function or object the core
# defines, so libtinygi.a exports tgi_NAME_f32 and libtinygi-fixed.a
# tgi_NAME_q16, and one program can link both libraries (the public tg_
# names carry the type through tinygi.h's ABI block already).
#
#   sh tools/abi_names.sh            rewrite src/core/abi_names.h
#   sh tools/abi_names.sh --check    exit 1 (and print the difference) if it
#                                    is not what the sources define
#
# Run it after adding, removing or renaming a non-static function or object
# in src/ (tests/both_types_test.sh fails until then).  It compiles every
# core file at -O0 in both number types, with and without TG_OUTLINE_HELPERS
# (a build for size makes a few storage helpers external: src/raster/pack.h),
# and lists (a) every global symbol defined without the _f32/_q16 suffix and
# (b) every name the header lists whose suffixed symbol is still defined.
# Names the sources suffix themselves (tgi_div_q16) are not listed.  CC is
# the compiler (default cc).
set -eu
export LC_ALL=C   # one sort order everywhere
cd "$(dirname "$0")/.."
check=0
[ "${1:-}" = --check ] && check=1
hdr=src/core/abi_names.h
cc=${CC:-cc}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM

i=0
for f in src/*/*.c; do
    for v in -UTG_FIXED -DTG_FIXED=1 -DTG_OUTLINE_HELPERS=1 "-DTG_FIXED=1 -DTG_OUTLINE_HELPERS=1"; do
        i=$((i + 1))
        echo "$tmp/$i.o $f $v"
    done
done | xargs -P 2 -L 1 sh -c 'cc=$0 out=$1 f=$2; shift 2; "$cc" -std=c99 -O0 -ffreestanding -w "$@" -c "$f" -o "$out"' "$cc" ||
    { echo "abi_names.sh: a core file does not compile" >&2; exit 1; }
nm -g --defined-only "$tmp"/*.o | awk 'NF == 3 {print $3}' | sort -u >"$tmp/defined"
[ -s "$tmp/defined" ] || { echo "abi_names.sh: no symbols (nm failed?)" >&2; exit 1; }
sed -n 's/^#define \([A-Za-z_0-9]*\) TG_ABI(.*/\1/p' "$hdr" 2>/dev/null | sort -u >"$tmp/listed" || :
{
    grep -vE '_(f32|q16)$' "$tmp/defined" || :
    sed -nE 's/_(f32|q16)$//p' "$tmp/defined" | sort -u | comm -12 - "$tmp/listed"
} | sort -u >"$tmp/names"

{
    cat <<'HEAD'
/* SPDX-License-Identifier: MIT */
/*
 * abi_names.h - every external symbol of the core carries its number type,
 * as the public functions do (tinygi.h, "ABI"): tgi_NAME is the symbol
 * tgi_NAME_f32 in libtinygi.a and tgi_NAME_q16 in libtinygi-fixed.a, so a
 * program can link both libraries (README "Embedding").  Every internal
 * header reaches this one (core/real.h, arena.h, error.h, path.h,
 * frame/pixels.h, scene/lex.h include it) before it declares a tgi_ name.
 * Written by tools/abi_names.sh (run it after adding or removing a
 * non-static function or object; tests/both_types_test.sh checks it); the
 * lines are sorted.  Static functions need no line.
 */
#ifndef TG_ABI_NAMES_H
#define TG_ABI_NAMES_H

#include "../tinygi.h"

HEAD
    sed 's/.*/#define & TG_ABI(&)/' "$tmp/names"
    printf '\n#endif\n'
} >"$tmp/abi_names.h"

if [ $check = 1 ]; then
    if cmp -s "$tmp/abi_names.h" "$hdr"; then echo "abi_names.sh: $hdr is up to date ($(wc -l <"$tmp/names") names)"; exit 0; fi
    echo "abi_names.sh: $hdr is out of date (run sh tools/abi_names.sh):" >&2
    diff "$hdr" "$tmp/abi_names.h" >&2 || :
    exit 1
fi
cp "$tmp/abi_names.h" "$hdr"
echo "abi_names.sh: wrote $hdr ($(wc -l <"$tmp/names") names)"
