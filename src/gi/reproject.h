/* SPDX-License-Identifier: MIT */
/*
 * reproject.h - last frame's diffuse radiance in this frame's view (HBIL
 * sec. 3.2), the source of the near field (eq. 17: infinite bounces over
 * frames).
 *
 * Scatter (the paper's way): every previous pixel is unprojected with last
 * frame's depth and view and splatted to the pixel it lands on in the
 * current view; a temporary z-buffer keeps the nearest (ties: the lowest
 * source index, so the result does not depend on order).  Pixels nothing
 * landed on are holes (valid = 0), to be filled by tgi_pushpull_fill.
 *   tgi_reproject_clear(scratch)          whole image, first
 *   tgi_reproject_scatter_rows(y0, y1)    SOURCE rows; writes anywhere in the
 *                                         scratch: run the ranges one after
 *                                         another, not in parallel
 *   tgi_reproject_resolve_rows(y0, y1)    destination rows; parallel-safe
 * Gather (the alternative): each current pixel reads last frame's radiance
 * at its motion vector (gbuffer motion_x/y = previous screen position),
 * rejected (a hole) when last frame's depth there disagrees with this
 * surface seen from the previous camera.
 * No history (prev radiance NULL: a camera cut) gives 0 radiance and no
 * valid pixel; after push/pull the image is 0 everywhere, finite and
 * hole-free.
 */
#ifndef TG_REPROJECT_H
#define TG_REPROJECT_H

#include "../raster/view.h"

typedef struct tgi_reproject_io {
    int width, height;                    /* both frames have this size */
    const tgi_view *prev_view, *view;
    const tg_real *prev_depth;            /* last frame's view depth; <= 0 or sky: nothing */
    const uint8_t *prev_sky;              /* may be NULL */
    const tg_real *prev_r, *prev_g, *prev_b; /* last frame's diffuse radiance; NULL = no history */
    /* gather only: this frame's depth and motion vectors */
    const tg_real *depth, *motion_x, *motion_y;
    const uint8_t *sky;                   /* may be NULL */
    tg_real depth_tolerance;              /* gather: relative depth mismatch rejected (0: 0.05) */
    tg_real *out_r, *out_g, *out_b;       /* radiance in the current view */
    uint8_t *valid;                       /* 1 where a value landed, 0 = hole */
} tgi_reproject_io;

/* Scratch of the scatter: a z-buffer and the winning source index. */
size_t tgi_reproject_bytes(int w, int h);   /* SIZE_MAX when that does not fit */

void tgi_reproject_clear(const tgi_reproject_io *io, void *scratch);
void tgi_reproject_scatter_rows(const tgi_reproject_io *io, void *scratch, int y0, int y1);
void tgi_reproject_resolve_rows(const tgi_reproject_io *io, const void *scratch, int y0, int y1);
/* All three in order (one thread). */
void tgi_reproject_scatter(const tgi_reproject_io *io, void *scratch);

/* Gather through the motion vectors, destination rows [y0, y1). */
void tgi_reproject_gather_rows(const tgi_reproject_io *io, int y0, int y1);

#endif
