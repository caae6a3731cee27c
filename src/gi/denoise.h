/* SPDX-License-Identifier: MIT */
/*
 * denoise.h - after the 4x4 merge: the depth- and normal-aware spatial
 * filter over the 4x4 neighbourhood (HBIL sec. 3.3-3.4).
 *
 * A 5x5 window with 1-D weights (1/2, 1, 1, 1, 1/2), which gives each of
 * the 16 interleaved direction patterns the same total weight (the 32
 * directions are merged evenly, and the window is symmetric), times
 *   w_depth  = 1 - |z_j - z_i| / (tol z_i), clamped at 0
 *   w_normal = max(0, n_i . n_j)^8
 * Sky pixels are left as they are.  AO, bent normal and near-field
 * irradiance are filtered; the bent normal is renormalised and the cone is
 * recomputed as acos(1 - AO) (HBIL eq. 12) from the filtered AO.
 *   tgi_denoise_keep_rows(g, r, scratch, y0, y1)      first, every row: keeps
 *                                                     the unfiltered values
 *   tgi_denoise_rows(p, g, r, scratch, y0, y1)        then writes the filtered
 *                                                     values back
 * Both are row-parallel (any split of the rows gives the same result), the
 * second only after the first has run on every row.  The temporal
 * accumulation that follows is in temporal.h.
 */
#ifndef TG_DENOISE_H
#define TG_DENOISE_H

#include "../raster/gview.h"

typedef struct tgi_denoise_params {
    tg_real depth_tolerance;   /* relative; default 0.1 */
} tgi_denoise_params;

void tgi_denoise_defaults(tgi_denoise_params *p);

/* Scratch bytes for a w x h view (SIZE_MAX when that does not fit). */
size_t tgi_denoise_bytes(int w, int h);
void tgi_denoise_keep_rows(const tgi_gview *g, const tgi_gresult *r, void *scratch, int y0, int y1);
void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r,
                      const void *scratch, int y0, int y1);

#endif
