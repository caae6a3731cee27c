#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# abi_test.sh - the public header stands alone and the ABI says its number
# type: src/tinygi.h compiles by itself (no other file of src/ on the include
# path) as C99 and as C++, a C++ program links against both libraries
# (extern "C") and renders, and a program built with one number type's header
# fails to LINK against the other type's library (the symbols carry _f32 or
# _q16) instead of reading Q16.16 numbers as floats.  A program compiled at
# -Os (the header's TG_OUTLINE_HELPERS) links against the library as built.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
BUILD=${BUILD:-build}
CC=${CC:-cc}
CXX=${CXX:-g++}
ldflags="${EXTRA_LDFLAGS:-} ${LDFLAGS:-}"   # make sanitize: the libraries need the sanitizer runtimes
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/inc"
cp src/tinygi.h "$tmp/inc/"

# a program that uses the whole public API path: scene, plan, frame, rows
cat >"$tmp/prog.c" <<'PROG'
#include "tinygi.h"
#include <stdio.h>
#include <stdlib.h>
int main(void)
{
    static unsigned char scene_mem[1 << 20];
    const char *text = tg_builtin_scene("plane");
    tg_arena arena;
    tg_scene *scene = NULL;
    tg_error err;
    tg_request req;
    tg_plan plan;
    tg_frame *frame = NULL;
    void *mem;
    tg_real row[8];
    tg_arena_init(&arena, scene_mem, sizeof scene_mem);
    if (!text || tg_scene_parse(text, strlen(text), "plane", NULL, &arena, &scene, &err) != TG_OK) return 3;
    tg_request_defaults(&req);
    req.width = 8; req.height = 6;
    req.aovs = 1u << TG_AOV_AO;
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK) return 4;
    mem = malloc(plan.total_bytes);
    if (!mem || tg_frame_create(&plan, mem, plan.total_bytes, &frame, &err) != TG_OK) return 5;
    if (tg_frame_render(frame, 0, &err) != TG_OK) return 6;
    tg_frame_aov_row(frame, TG_AOV_AO, 3, row);
    /* through tg_div and tg_mul: at -Os out-of-line calls into the library */
    printf("ao %.3f %s\n", (double)tg_to_float(tg_mul(tg_div(row[4], tg_from_int(3)), tg_from_int(3))), TG_NUMBER_NAME);
    free(mem);
    return tg_to_float(row[4]) > 0.5f && tg_to_float(row[4]) <= 1.0f ? 0 : 7;
}
PROG
cp "$tmp/prog.c" "$tmp/prog.cpp"

for num in float fixed; do
    def=; lib=$BUILD/libtinygi.a; other=$BUILD/libtinygi-fixed.a; sym=_f32
    [ $num = fixed ] && { def=-DTG_FIXED=1; lib=$BUILD/libtinygi-fixed.a; other=$BUILD/libtinygi.a; sym=_q16; }
    echo '#include "tinygi.h"' >"$tmp/alone.c"
    expect "$num: tinygi.h compiles alone (C99, -Wpedantic -Werror, freestanding)" \
        $CC -std=c99 -Wall -Wextra -Wpedantic -Wshadow -Werror -ffreestanding $def -I"$tmp/inc" -c "$tmp/alone.c" -o "$tmp/alone.o"
    expect "$num: tinygi.h compiles alone as C++" \
        $CXX -std=c++11 -Wall -Wextra -Wpedantic -Werror $def -I"$tmp/inc" -x c++ -c "$tmp/alone.c" -o "$tmp/alone.o"
    if $CC -std=c99 -Wall -Werror $def -I"$tmp/inc" "$tmp/prog.c" "$lib" -o "$tmp/prog-$num" $ldflags 2>"$tmp/err" \
        && "$tmp/prog-$num" >"$tmp/out"; then ok "$num: C program links and renders ($(cat "$tmp/out"))"
    else fail "$num: C program links and renders" "$(head -c 300 "$tmp/err")"; fi
    if $CXX -std=c++11 -Wall -Wextra -Werror $def -I"$tmp/inc" "$tmp/prog.cpp" "$lib" -o "$tmp/progxx-$num" $ldflags 2>"$tmp/err" \
        && "$tmp/progxx-$num" >"$tmp/out"; then ok "$num: C++ program links (extern \"C\") and renders ($(cat "$tmp/out"))"
    else fail "$num: C++ program links (extern \"C\") and renders" "$(head -c 300 "$tmp/err")"; fi
    # compiled for size, the header calls the library's one copy of Q16.16's
    # shift and division (TG_OUTLINE_HELPERS): a library built at any level has it
    if $CC -std=c99 -Os -Wall -Werror $def -I"$tmp/inc" "$tmp/prog.c" "$lib" -o "$tmp/prog-os-$num" $ldflags 2>"$tmp/err" \
        && "$tmp/prog-os-$num" >"$tmp/out-os" && cmp -s "$tmp/out" "$tmp/out-os"; then
        ok "$num: the program compiled at -Os links and prints the same ($(cat "$tmp/out-os"))"
    else fail "$num: the program compiled at -Os links and prints the same" "$(head -c 300 "$tmp/err")"; fi
    # the mismatch: this type's header, the other type's library
    if $CC -std=c99 $def -I"$tmp/inc" "$tmp/prog.c" "$other" -o "$tmp/mix" $ldflags 2>"$tmp/err"; then
        fail "$num header with $(basename "$other"): the link must fail"
    else
        expect "$num header with $(basename "$other"): link fails on a ${sym} symbol" grep -q "tg_[a-z_0-9]*${sym}" "$tmp/err"
    fi
done
summary
