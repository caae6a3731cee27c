#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# both_types_test.sh - one program can link both libraries: every external
# symbol of libtinygi.a ends in _f32 and every one of libtinygi-fixed.a in
# _q16 (the public functions through tinygi.h's ABI block, the internal tgi_
# ones through src/core/abi_names.h), so the two define no name in common;
# src/core/abi_names.h lists what the sources define (tools/abi_names.sh
# --check, which also sees a build for size's extra helpers); and a program
# with a float and a Q16.16 translation unit, linked against both
# libraries, renders builtin:cornell in each type and gets the same picture
# within rounding from both.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_host_build

fl=$BUILD/libtinygi.a fx=$BUILD/libtinygi-fixed.a
defined() { nm -g --defined-only "$1" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u; }
defined "$fl" >"$tmp/float.syms"; defined "$fx" >"$tmp/fixed.syms"
expect "both libraries list their symbols (nm)" test -s "$tmp/float.syms" -a -s "$tmp/fixed.syms"
common=$(comm -12 "$tmp/float.syms" "$tmp/fixed.syms" | tr '\n' ' ')
expect "libtinygi.a and libtinygi-fixed.a define no symbol in common" test -z "$common"
[ -z "$common" ] || echo "  in both ($(echo $common | wc -w)): $(echo $common | cut -c1-300)"
for lib in float:_f32 fixed:_q16; do
    bad=$(grep -v -- "${lib#*:}\$" "$tmp/${lib%:*}.syms" | tr '\n' ' ')
    expect "every symbol of the ${lib%:*} library ends in ${lib#*:} (sh tools/abi_names.sh)" test -z "$bad"
    [ -z "$bad" ] || echo "  without it: $(echo $bad | cut -c1-300)"
done
if out=$(CC=$CC sh tools/abi_names.sh --check 2>&1); then ok "src/core/abi_names.h is up to date (tools/abi_names.sh --check)"
else fail "src/core/abi_names.h is up to date (tools/abi_names.sh --check)" "$(echo "$out" | head -n 12)"; fi

# one translation unit per number type, each with its own tinygi.h
cat >"$tmp/render.c" <<'EOF'
#include <stdlib.h>
#include "tinygi.h"
#if TG_FIXED
#define RENDER render_q16
#else
#define RENDER render_f32
#endif
/* builtin:cornell at 32x24, colour (HBIL): the sum of the sRGB bytes and the
 * AO's sum in 1/1000, or -1 */
int RENDER(long *rgb_sum, long *ao_sum);
int RENDER(long *rgb_sum, long *ao_sum)
{
    static unsigned char scene_mem[256 * 1024];
    const char *text = tg_builtin_scene("cornell");
    tg_arena arena;
    tg_scene *scene;
    tg_request req;
    tg_plan plan;
    tg_frame *frame;
    tg_error err;
    uint8_t rgb[32 * 3];
    tg_real ao[32];
    void *mem;
    int x, y;
    tg_arena_init(&arena, scene_mem, sizeof scene_mem);
    if (!text || tg_scene_parse(text, strlen(text), "cornell", NULL, &arena, &scene, &err) != TG_OK) return -1;
    tg_request_defaults(&req);
    req.width = 32; req.height = 24;
    req.aovs = (1u << TG_AOV_COLOR) | (1u << TG_AOV_AO);
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK) return -1;
    mem = malloc(plan.total_bytes);
    if (!mem || tg_frame_create(&plan, mem, plan.total_bytes, &frame, &err) != TG_OK) return -1;
    if (tg_frame_render(frame, 0, &err) != TG_OK) { free(mem); return -1; }
    *rgb_sum = 0; *ao_sum = 0;
    for (y = 0; y < 24; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, rgb);
        tg_frame_aov_row(frame, TG_AOV_AO, y, ao);
        for (x = 0; x < 32 * 3; x++) *rgb_sum += rgb[x];
        for (x = 0; x < 32; x++) *ao_sum += (long)(tg_to_float(ao[x]) * 1000.0f + 0.5f);
    }
    free(mem);
    return 0;
}
EOF
cat >"$tmp/main.c" <<'EOF'
#include <stdio.h>
#include <stdlib.h>
int render_f32(long *rgb_sum, long *ao_sum);
int render_q16(long *rgb_sum, long *ao_sum);
int main(void)
{
    long rf, af, rq, aq, n = 32 * 24;
    if (render_f32(&rf, &af) != 0) { puts("float render failed"); return 1; }
    if (render_q16(&rq, &aq) != 0) { puts("Q16.16 render failed"); return 1; }
    printf("mean sRGB float %.2f Q16.16 %.2f, mean AO float %.4f Q16.16 %.4f\n",
           rf / (3.0 * n), rq / (3.0 * n), af / (1000.0 * n), aq / (1000.0 * n));
    /* a lit room, not black or white; AO in (0.3, 1]; the types agree to
     * 1 of 255 on average and 0.01 in AO */
    if (rf < 20 * 3 * n || rf > 235 * 3 * n || af < 300 * n || af > 1000 * n) return 2;
    if (labs(rf - rq) > 3 * n || labs(af - aq) > 10 * n) return 3;
    return 0;
}
EOF
if $CC $TG_CFLAGS -Isrc -c "$tmp/render.c" -o "$tmp/render_f32.o" 2>"$tmp/err" &&
   $CC $TG_CFLAGS -DTG_FIXED=1 -Isrc -c "$tmp/render.c" -o "$tmp/render_q16.o" 2>>"$tmp/err" &&
   $CC $TG_CFLAGS -c "$tmp/main.c" -o "$tmp/main.o" 2>>"$tmp/err"; then
    ok "a float and a Q16.16 translation unit compile"
    if $CC $TG_CFLAGS "$tmp/main.o" "$tmp/render_f32.o" "$tmp/render_q16.o" "$fl" "$fx" -o "$tmp/both" $TG_LDLIBS 2>"$tmp/err"; then
        ok "the program links against libtinygi.a and libtinygi-fixed.a"
        if "$tmp/both" >"$tmp/out" 2>&1; then ok "both types render cornell alike ($(cat "$tmp/out"))"
        else fail "both types render cornell alike" "exit $?: $(head -c 300 "$tmp/out")"; fi
    else fail "the program links against libtinygi.a and libtinygi-fixed.a" \
        "$(grep -c 'multiple definition' "$tmp/err") multiple definitions: $(head -c 400 "$tmp/err")"; fi
else fail "a float and a Q16.16 translation unit compile" "$(head -c 400 "$tmp/err")"; fi
summary
