/* SPDX-License-Identifier: MIT */
/*
 * temporal.h - exponential accumulation of the GI results over frames, with
 * the history rejected by depth and normal.
 *
 * r = lerp(history, r, alpha) in place, where the history is last frame's
 * accumulated results `prev` at the pixel this pixel's surface lands in when
 * reprojected into the previous view, accepted only when last frame's depth
 * there matches within history_depth_tolerance and its normal within
 * history_normal_cos (last frame's full-resolution geometry, gview.h's
 * tgi_prev_geometry); otherwise r keeps this frame's values.  It runs at
 * the kernel's resolution, on the unfiltered results (the spatial filter
 * reads the accumulated ones, denoise.h), so r and prev alternate between
 * two buffers frame by frame and nothing else is kept.  `reset` (a camera
 * cut, the first frame) ignores the history.  Row-parallel: a row reads any
 * pixel of prev and writes only its own.
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

/* Rows [y0, y1) of the view g (full resolution, or the packed quarter-res
 * copy; its camera is this frame's) and its results r, accumulated in place
 * from prev (indexed like g); prev_geometry is packed at full resolution. */
void tgi_temporal_rows(const tgi_temporal_params *p, const tgi_gview *g, const tgi_gresult *r, const tgi_gresult *prev,
                       const tgi_prev_geometry *prev_geometry, const tgi_view *prev_view, int reset, int y0, int y1);

/* The exponential average's blend h + (v - h) t as tgi_temporal_rows
 * computes it (temporal.c lerp_unit: tg_lerp's integers, in Q16.16
 * without its saturation tests where they cannot act); for
 * tests/test_reproject.c, which compares it with tg_lerp. */
tg_real tgi_temporal_lerp(tg_real h, tg_real v, tg_real t);

#endif
