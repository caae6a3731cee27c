/* SPDX-License-Identifier: MIT */
/*
 * frame.c - a frame is created from its plan and rendered by running the
 * plan's passes in order: the rows of the pass table (passes.c) the plan
 * needs, as tg_plan_explain lists them.
 *
 * A row-parallel pass runs over its rows [0, n) in one call here (a hosted
 * platform may split them: any split gives the same output); a serial pass
 * runs once.  On a frame without history the bounce loop (the passes marked
 * TGI_BOUNCE) runs `bounces` times, each iteration gathering the radiance
 * the previous one composed (with history, one per frame: HBIL eq. 17).
 */
#include <string.h>
#include "frame_internal.h"
#include "../core/error.h"
#include "../light/sh.h"

tg_status tg_frame_create(const tg_plan *plan, void *memory, size_t size,
                          tg_frame **frame, tg_error *err)
{
    tg_arena arena;
    tg_frame *f = NULL;
    tg_plan copy = *plan;
    tgi_error_clear(err);
    *frame = NULL;
    tg_arena_init(&arena, memory, size);
    if (tgi_frame_layout(&f, &copy, &arena) != 0) {
        tgi_error_set(err, TG_ERR_MEMORY, NULL, 0, 0, "the frame arena is too small for the plan");
        err->bytes_needed = plan->total_bytes;
        return TG_ERR_MEMORY;
    }
    if (f->effects & TG_EFFECT_FAR) tgi_sh9_from_env(&f->scene->env, f->sh);
    *frame = f;
    return TG_OK;
}

int tgi_pass_row_count(const tg_frame *f, const tgi_pass *p)
{
    switch (p->rows) {
    case TGI_ROWS_IMAGE: return f->height;
    case TGI_ROWS_KERNEL: return tgi_frame_kernel(f, NULL, NULL)->height;
    default: return 0;
    }
}

/* Whether pass p runs on this frame (history or not). */
static int runs_now(const tg_frame *f, const tgi_pass *p)
{
    if ((p->when & TGI_ON_FIRST_FRAME) && f->has_history) return 0;
    if ((p->when & TGI_ON_HISTORY) && !f->has_history) return 0;
    return 1;
}

/* One pass: serial, or its rows in bands of `band` (0: all), last band first. */
static void run_frame_pass(tg_frame *f, const tgi_pass *p, int band)
{
    int n = tgi_pass_row_count(f, p), y1;
    if (!runs_now(f, p)) return;
    if (p->rows == TGI_SERIAL) { p->run(f); return; }
    if (band <= 0) band = n;
    for (y1 = n; y1 > 0; y1 -= band) p->run_rows(f, y1 > band ? y1 - band : 0, y1);
}

tg_status tg_frame_render(tg_frame *f, int index, tg_error *err)
{
    int k = 0, end, j;
    tgi_error_clear(err);
    if (index < 0) {
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "frame index must be >= 0");
        return TG_ERR_INPUT;
    }
    f->index = index;
    f->bounces = (f->effects & TG_EFFECT_NEAR) && !f->has_history ? f->request.bounces : 1;
    if (f->bounces < 1) f->bounces = 1;
    f->bounce = 0;
    tgi_frame_begin(f);
    while (k < f->pass_count) {
        if (!(tgi_passes[f->pass_rows[k]].when & TGI_BOUNCE)) {
            run_frame_pass(f, &tgi_passes[f->pass_rows[k++]], f->band);
            continue;
        }
        for (end = k; end < f->pass_count && (tgi_passes[f->pass_rows[end]].when & TGI_BOUNCE); end++) {}
        for (f->bounce = 0; f->bounce < f->bounces; f->bounce++)
            for (j = k; j < end; j++) run_frame_pass(f, &tgi_passes[f->pass_rows[j]], f->band);
        k = end;
    }
    if (tgi_rgb_present(&f->history)) f->has_history = 1;
    f->frames_rendered++;
    return TG_OK;
}

tg_status tgi_frame_render_bands(tg_frame *f, int index, int band, tg_error *err)
{
    tg_status s;
    f->band = band;
    s = tg_frame_render(f, index, err);
    f->band = 0;
    return s;
}
