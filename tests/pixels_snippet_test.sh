#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/pixels_snippet_test.sh - the README's "Pixels for a display" example
# (between "<!-- begin pixels snippet -->" and "<!-- end pixels snippet -->")
# compiles inside a function against both built libraries and does what it
# says on a rendered 320x240 cornell: the screen holds dithered RGB565 within
# one level of the 8-bit colour, and every row sent to the "panel" is the
# screen's row high byte first.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh

awk '/^<!-- begin pixels snippet -->/ { on = 1; next } /^<!-- end pixels snippet -->/ { on = 0 }
     on && !/^```/' README.md >"$T/snippet.c"
expect "README has the pixels snippet" test -s "$T/snippet.c"

cat >"$T/main.c" <<'C'
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"

static uint16_t sent[240][320];
static const uint16_t *shown;

static void panel_write_row(int y, const uint16_t *row)
{
    memcpy(sent[y], row, sizeof sent[y]);
}

static int show(const tg_frame *frame)
{
#include "snippet.c"
    shown = &screen[0][0];
    return 0;
}

/* |level * 255 / top - c| < 255 / top: within one level of the byte */
static int near(unsigned level, unsigned top, unsigned c)
{
    long d = (long)(level * 255u) - (long)(c * top);
    return (d < 0 ? -d : d) < 255;
}

int main(void)
{
    static unsigned char scene_mem[1 << 18];
    const char *text = tg_builtin_scene("cornell");
    tg_arena arena;
    tg_scene *scene;
    tg_request req;
    tg_plan plan;
    tg_frame *frame;
    tg_error err;
    void *mem;
    uint8_t rgb[320 * 3];
    int x, y, bad = 0;
    tg_arena_init(&arena, scene_mem, sizeof scene_mem);
    tg_request_defaults(&req);
    req.width = 320;
    req.height = 240;
    if (tg_scene_parse(text, strlen(text), "cornell", NULL, &arena, &scene, &err) != TG_OK ||
        tg_plan_make(&plan, scene, &req, &err) != TG_OK || !(mem = malloc(plan.total_bytes)) ||
        tg_frame_create(&plan, mem, plan.total_bytes, &frame, &err) != TG_OK ||
        tg_frame_render(frame, 0, &err) != TG_OK) {
        fprintf(stderr, "render: %s\n", err.message);
        return 1;
    }
    if (show(frame) != 0) { fprintf(stderr, "the snippet failed\n"); return 1; }
    for (y = 0; y < 240; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, rgb);
        for (x = 0; x < 320; x++) {
            unsigned v = shown[y * 320 + x];
            const unsigned char *b = (const unsigned char *)&sent[y][x];
            bad += b[0] != v >> 8 || b[1] != (v & 255u) || !near(v >> 11, 31, rgb[3 * x]) ||
                   !near(v >> 5 & 63u, 63, rgb[3 * x + 1]) || !near(v & 31u, 31, rgb[3 * x + 2]);
        }
    }
    free(mem);
    if (bad) { fprintf(stderr, "%d pixels wrong\n", bad); return 1; }
    return 0;
}
C

for num in float fixed; do
    # shellcheck disable=SC2086 # flag lists are split into words on purpose
    if $CC $TG_CFLAGS $(numdef $num) -Isrc -I"$T" "$T/main.c" "$BUILD/libtinygi$(suffix $num).a" \
        -o "$T/pixels-$num" $TG_LDLIBS 2>"$T/cc.err"; then ok "README pixels snippet compiles ($num)"
    else fail "README pixels snippet compiles ($num)" "$(head -n 10 "$T/cc.err")"; continue; fi
    if "$T/pixels-$num" 2>"$T/run.err"; then ok "README pixels snippet fills screen and panel ($num)"
    else fail "README pixels snippet fills screen and panel ($num)" "$(head -c 300 "$T/run.err")"; fi
done
summary
