/* SPDX-License-Identifier: MIT */
/*
 * denoise.h - after the 4x4 merge: the depth- and normal-aware spatial
 * filter over the 4x4 neighbourhood (HBIL sec. 3.3-3.4) and the temporal
 * exponential accumulation with history rejected by depth and normal.
 *
 * Spatial: a 5x5 window with 1-D weights (1/2, 1, 1, 1, 1/2), which gives
 * each of the 16 interleaved direction patterns the same total weight (the
 * 32 directions are merged evenly, and the window is symmetric), times
 *   w_depth  = 1 - |z_j - z_i| / (tol z_i), clamped at 0
 *   w_normal = max(0, n_i . n_j)^8
 * Sky pixels are left as they are.  AO, bent normal and near-field
 * irradiance are filtered; the bent normal is renormalised and the cone is
 * recomputed as acos(1 - AO) (HBIL eq. 12) from the filtered AO.
 *   tgi_denoise_begin(io, scratch)   whole image first: copies the inputs
 *   tgi_denoise_rows(io, scratch, y0, y1)   writes the filtered values back
 *
 * Temporal: out = lerp(history, current, alpha) where the history (two
 * state halves, ping-ponged by `frame & 1`) is fetched by reprojecting
 * this pixel's surface into the previous view and accepted only when last
 * frame's depth there matches within depth_tolerance and the stored normal
 * within normal_cos; otherwise out = current.  `reset` (a camera cut, the
 * first frame) ignores the history.
 */
#ifndef TG_DENOISE_H
#define TG_DENOISE_H

#include "../raster/view.h"

typedef struct tgi_denoise_io {
    int width, height;
    const tg_real *depth, *nx, *ny, *nz;   /* full-res guides (world normals) */
    const uint8_t *sky;                    /* may be NULL */
    tg_real *ao;                           /* in-out; the others may be NULL */
    tg_real *bent_x, *bent_y, *bent_z, *cone;
    tg_real *near_r, *near_g, *near_b;
} tgi_denoise_io;

typedef struct tgi_denoise_params {
    tg_real depth_tolerance;   /* relative; default 0.1 */
    /* temporal */
    tg_real alpha;             /* weight of the current frame; default 0.2 */
    tg_real history_depth_tolerance; /* relative; default 0.05 */
    tg_real history_normal_cos;      /* default 0.9 */
} tgi_denoise_params;

void tgi_denoise_defaults(tgi_denoise_params *p);

size_t tgi_denoise_bytes(int w, int h);
void tgi_denoise_begin(const tgi_denoise_io *io, void *scratch);
void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_denoise_io *io, const void *scratch, int y0, int y1);

/* Temporal state: two halves of (ao, bent xyz, near rgb, depth, normal xyz). */
size_t tgi_temporal_bytes(int w, int h);
/* Clear the state (no history). */
void tgi_temporal_clear(void *state, int w, int h);
void tgi_temporal_rows(const tgi_denoise_params *p, const tgi_denoise_io *io, void *state,
                      const tgi_view *prev_view, const tgi_view *view, int frame, int reset,
                      int y0, int y1);

#endif
