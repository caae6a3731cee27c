/* SPDX-License-Identifier: MIT */
/*
 * frame.c - a frame is created from its plan and rendered by running the
 * plan's passes in order: the rows of the pass table (passes.c) the plan
 * needs, as tg_plan_explain lists them.
 *
 * A row-parallel pass runs over its rows [0, n) through the platform's hook
 * (tg_frame_set_parallel: it may split them over threads or cores, any
 * split gives the same output), else in one call on this thread; a serial
 * pass runs once, on this thread.  On a frame without history the bounce
 * loop (the passes marked TGI_BOUNCE) runs `bounces` times, each iteration
 * gathering the radiance the previous one composed (with history, one per
 * frame: HBIL eq. 17).
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
    tg_plan copy;
    tgi_error_clear(err);
    if (frame) *frame = NULL;
    /* total_bytes 0 or no scene: tg_plan_make failed, or never made it */
    if (!plan || !frame || plan->total_bytes == 0 || !plan->scene) {
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0,
                      "tg_frame_create: needs a plan that tg_plan_make made and somewhere to put the frame");
        return TG_ERR_INPUT;
    }
    /* the API checks what tg_plan_make checked: a request changed in the
     * plan after it (bounces 1000000 ran for minutes, technique 99 was
     * taken) is refused as tg_plan_make would refuse it */
    if (tgi_request_refused(&plan->request, err)) return TG_ERR_INPUT;
    copy = *plan;
    tg_arena_init(&arena, memory, size);
    if (tgi_frame_layout(&f, &copy, &arena) != 0) {
        tgi_error_set(err, TG_ERR_MEMORY, NULL, 0, 0, "the frame arena is too small for the plan");
        if (err) err->bytes_needed = plan->total_bytes;
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

tg_status tg_frame_set_parallel(tg_frame *f, const tg_parallel *p)
{
    if (!f || (p && !p->run)) return TG_ERR_INPUT;
    if (p) f->parallel = *p;
    else memset(&f->parallel, 0, sizeof f->parallel);
    return TG_OK;
}

/* Through the hook; without one on this thread, in bands of f->band rows
 * (0: all at once), last band first. */
void tgi_frame_parallel_rows(tg_frame *f, tg_rows_fn fn, void *job, int rows)
{
    int band = f->band > 0 ? f->band : rows, y1;
    if (rows <= 0) return;
    if (f->parallel.run) {
        f->parallel.run(f->parallel.user, fn, job, rows);
        return;
    }
    for (y1 = rows; y1 > 0; y1 -= band) fn(job, y1 > band ? y1 - band : 0, y1);
}

/* A row-parallel pass as a job of the hook. */
typedef struct pass_job {
    tg_frame *f;
    void (*rows)(tg_frame *f, int y0, int y1);
} pass_job;

static void pass_job_rows(void *job, int y0, int y1)
{
    const pass_job *j = (const pass_job *)job;
    j->rows(j->f, y0, y1);
}

/* One pass: serial, or its rows through tgi_frame_parallel_rows. */
static void run_frame_pass(tg_frame *f, const tgi_pass *p)
{
    pass_job job;
    if (!runs_now(f, p)) return;
    if (p->rows == TGI_SERIAL) { p->run(f); return; }
    job.f = f;
    job.rows = p->run_rows;
    tgi_frame_parallel_rows(f, pass_job_rows, &job, tgi_pass_row_count(f, p));
}

tg_status tg_frame_render(tg_frame *f, int index, tg_error *err)
{
    int k = 0, end, j;
    tgi_error_clear(err);
    if (!f) {   /* a failed tg_frame_create leaves NULL */
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "tg_frame_render: the frame is NULL");
        return TG_ERR_INPUT;
    }
    if (index < 0) {
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "frame index must be >= 0");
        return TG_ERR_INPUT;
    }
    f->index = index;
    f->bounces = (f->effects & TG_EFFECT_NEAR) && !f->has_history ? f->request.bounces : 1;
    if (f->bounces < 1) f->bounces = 1;
    f->bounce = 0;
    /* the camera pass, always the table's first row, decides whether this
     * frame continues the last one (a cut drops the history); the buffers'
     * roles for this frame follow from that */
    run_frame_pass(f, &tgi_passes[f->pass_rows[k++]]);
    tgi_frame_begin(f);
    while (k < f->pass_count) {
        if (!(tgi_passes[f->pass_rows[k]].when & TGI_BOUNCE)) {
            run_frame_pass(f, &tgi_passes[f->pass_rows[k++]]);
            continue;
        }
        for (end = k; end < f->pass_count && (tgi_passes[f->pass_rows[end]].when & TGI_BOUNCE); end++) {}
        for (f->bounce = 0; f->bounce < f->bounces; f->bounce++)
            for (j = k; j < end; j++) run_frame_pass(f, &tgi_passes[f->pass_rows[j]]);
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
