/* SPDX-License-Identifier: MIT */
/*
 * reprojection.c - last frame's radiance as this frame's near-field source
 * (HBIL sec. 3.2): gathered into this view through the depth and the two
 * cameras, the holes filled by push/pull, and, at the end of every frame,
 * the geometry kept for the next frame's depth tests.
 */
#include "frame_internal.h"
#include "../gi/reproject.h"
#include "../gi/pushpull.h"

#if !TG_NO_COLOR && !TG_NO_TEMPORAL /* radiance reprojection is left out with TG_NO_COLOR=1 or
                                     * TG_NO_TEMPORAL=1 (tinygi.h "FEATURE SWITCHES") */

/* HBIL sec. 3.2: last frame's radiance where this frame's surfaces were,
 * with the paper's depth test. */
void tgi_pass_reproject(tg_frame *f, int y0, int y1)
{
    tgi_reproject_io io;
    io.g = &f->full;
    io.prev_view = &f->prev_view;
    io.prev_geometry = &f->prev_geometry;
    io.prev = &f->history;
    io.object = f->posed_pos ? f->gb.object : NULL;
    io.object_delta = f->object_delta;
    io.depth_tolerance = 0;
    io.out = &f->bounce_source;
    tgi_reproject_gather_rows(&io, y0, y1);
}

/* ...then fill the holes by push/pull (Kraus 2009): level 1 over rows, the
 * coarser levels as one step, the holes over rows (pushpull.h). */
void tgi_pass_push_pull_down(tg_frame *f, int y0, int y1)
{
    tgi_pushpull_push_rows(f->width, f->height, &f->bounce_source, f->pushpull_mips, y0, y1);
}

#if !TG_OUTLINE_HELPERS
static void push2_rows(void *job, int y0, int y1)
{
    const tg_frame *f = (const tg_frame *)job;
    tgi_pushpull_push2_rows(f->width, f->height, f->pushpull_mips, y0, y1);
}

static void pull1_rows(void *job, int y0, int y1)
{
    const tg_frame *f = (const tg_frame *)job;
    tgi_pushpull_pull1_rows(f->width, f->height, f->pushpull_mips, y0, y1);
}
#endif

/* The coarser levels: level 2's push and level 1's pull over rows through
 * the platform's hook (most of the step's work), the rest on this thread;
 * a build for size runs them all here. */
void tgi_pass_push_pull(tg_frame *f)
{
#if !TG_OUTLINE_HELPERS
    tgi_frame_parallel_rows(f, push2_rows, f, tgi_pushpull_level_rows(f->width, f->height, 2));
    tgi_pushpull_levels_coarse(f->width, f->height, f->pushpull_mips);
    tgi_frame_parallel_rows(f, pull1_rows, f, tgi_pushpull_level_rows(f->width, f->height, 1));
#else
    tgi_pushpull_levels(f->width, f->height, f->pushpull_mips);
#endif
}

void tgi_pass_push_pull_fill(tg_frame *f, int y0, int y1)
{
    tgi_pushpull_fill_rows(f->width, f->height, &f->bounce_source, f->pushpull_mips, y0, y1);
}

/* Last frame's geometry for the next frame's depth tests (its Lo stays
 * where compose wrote it, frame_internal.h). */
#endif /* !TG_NO_COLOR && !TG_NO_TEMPORAL */

#if !TG_NO_TEMPORAL
void tgi_pass_keep_history(tg_frame *f, int y0, int y1)
{
    /* locals: the stores into the history cannot change them, so they stay in registers */
    tgi_gview g = f->full;
    tgi_prev_geometry h = f->prev_geometry;
    int x, y, w = f->width;
#if TGI_REUSE_NORMAL
    /* tgi_prev_keep's word with its normal's code kept from the pixel
     * before whose stored normal code (tgi_gv_normal_word) is the same:
     * equal codes decode to equal normals, which pack to equal codes (the
     * same words; a plane's pixels share their normal; the memo starts with
     * no code); sky takes +z as tgi_prev_keep, unmemoised. */
    tgi_normal_memo m;   /* its code only: the packed code is what repeats */
    uint32_t oct_before = 0;
    const uint32_t sky = tgi_oct_pack(tg_v3(0, 0, TG_ONE), 8), sky_word = tgi_prev_word(0, sky);
    const size_t step = (size_t)g.pixel_stride;
    tgi_normal_memo_start(&m);
    for (y = y0; y < y1; y++) {
        size_t j = (size_t)y * (size_t)w, i = tgi_gv_index(&g, 0, y);   /* i: tgi_gv_index(&g, x, y) */
        for (x = 0; x < w; x++, j++, i += step) {
            const uint32_t d = g.store.depth[i];
            if (d == 0) {   /* sky (tgi_gv_is_sky): depth 0 */
                h.dn[j] = sky_word;
                continue;
            }
            if (!tgi_gv_normal_repeats(&g, &m, i)) oct_before = tgi_oct_pack(tgi_gv_normal(&g, i), 8);
            h.dn[j] = tgi_prev_word(d, oct_before);
        }
    }
#else
    for (y = y0; y < y1; y++) {
        size_t j = (size_t)y * (size_t)w;
        for (x = 0; x < w; x++, j++) tgi_prev_keep(&h, j, &g, tgi_gv_index(&g, x, y));
    }
#endif
}
#endif /* !TG_NO_TEMPORAL */
