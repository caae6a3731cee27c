/* SPDX-License-Identifier: MIT */
/*
 * reprojection.c - last frame's radiance as this frame's near-field source
 * (HBIL sec. 3.2): scattered into this view through a z-buffer, the holes
 * filled by push/pull, and, at the end of every frame, the radiance kept as
 * the next frame's history.
 */
#include <string.h>
#include "frame_internal.h"
#include "../gi/reproject.h"
#include "../gi/pushpull.h"

/* HBIL sec. 3.2: scatter last frame's radiance into this view through a
 * temporary z-buffer (nearest wins). */
void tgi_pass_reproject(tg_frame *f)
{
    tgi_reproject_io io;
    memset(&io, 0, sizeof io);
    io.width = f->width;
    io.height = f->height;
    io.prev_view = &f->prev_view;
    io.view = &f->view;
    io.prev_depth = f->history_depth;
    io.prev_r = f->history.r; io.prev_g = f->history.g; io.prev_b = f->history.b;
    io.out_r = f->source.r; io.out_g = f->source.g; io.out_b = f->source.b;
    io.valid = f->reproject_valid;
    tgi_reproject_scatter(&io, f->reproject_zbuffer);
}

/* ...then fill the holes by push/pull (Kraus 2009). */
void tgi_pass_push_pull(tg_frame *f)
{
    tgi_pushpull_fill(f->width, f->height, f->source.r, f->source.g, f->source.b, f->reproject_valid,
                      f->pushpull_mips);
}

/* The radiance the next frame's near field gathers: this frame's Lo (or,
 * without colour, its source), with the depth and object ids it was seen at. */
void tgi_pass_keep_history(tg_frame *f, int y0, int y1)
{
    const tgi_rgb *lo = f->color.r ? &f->color : &f->source;
    int x, y;
    for (y = y0; y < y1; y++)
        for (x = 0; x < f->width; x++) {
            size_t i = (size_t)y * (size_t)f->width + (size_t)x, j = tgi_gv_index(&f->full, x, y);
            tgi_rgb_set(&f->history, i, tgi_rgb_get(lo, j));
            f->history_depth[i] = tgi_gv_depth(&f->full, j);
            if (f->history_object && f->gb.object) f->history_object[i] = f->gb.object[i];
        }
}
