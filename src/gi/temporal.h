/* SPDX-License-Identifier: MIT */
/*
 * temporal.h - exponential accumulation of the GI results over frames,
 * with the history rejected by depth and normal (after the spatial filter
 * of denoise.h).
 *
 * out = lerp(history, current, alpha) where the history (two state halves,
 * ping-ponged by `frame & 1`) is fetched by reprojecting this pixel's
 * surface into the previous view and accepted only when last frame's depth
 * there matches within history_depth_tolerance and the stored normal
 * within history_normal_cos; otherwise out = current.  `reset` (a camera
 * cut, the first frame) ignores the history.  Row-parallel: a row reads
 * any pixel of last frame's half and writes only its own pixels.
 */
#ifndef TG_TEMPORAL_H
#define TG_TEMPORAL_H

#include "../raster/gview.h"

typedef struct tgi_temporal_params {
    tg_real alpha;                   /* weight of the current frame; default 0.2 */
    tg_real history_depth_tolerance; /* relative; default 0.05 */
    tg_real history_normal_cos;      /* default 0.9 */
} tgi_temporal_params;

void tgi_temporal_defaults(tgi_temporal_params *p);

/* State: two halves of (ao, bent xyz, near rgb, depth, normal xyz) for a
 * w x h image (SIZE_MAX when that does not fit). */
size_t tgi_temporal_bytes(int w, int h);
/* Clear the state (no history). */
void tgi_temporal_clear(void *state, int w, int h);
/* Rows [y0, y1) of a full-resolution view g (its camera is this frame's)
 * and its results r, accumulated in place. */
void tgi_temporal_rows(const tgi_temporal_params *p, const tgi_gview *g, const tgi_gresult *r, void *state,
                       const tgi_view *prev_view, int frame, int reset, int y0, int y1);

#endif
