/* SPDX-License-Identifier: MIT */
/*
 * gbuffer.h - the geometry buffer the rasterizer writes and every later pass
 * reads.  Structure of arrays, one tg_real (or byte) per pixel per channel,
 * row-major, index = y * width + x.
 */
#ifndef TG_GBUFFER_H
#define TG_GBUFFER_H

#include "../core/vec.h"

typedef struct tgi_gbuffer {
    int width, height;
    tg_real *depth;              /* linear view depth (view-space z); 0 on sky */
    tg_real *nx, *ny, *nz;       /* world-space unit normal (faces the viewer) */
    tg_real *albedo_r, *albedo_g, *albedo_b;
    tg_real *f0;
    tg_real *emit_r, *emit_g, *emit_b; /* NULL when the scene has no emissive material */
    uint8_t *sky;                /* 1 where no triangle was drawn */
    uint16_t *object;            /* object index per pixel (motion vectors); NULL if unused */
    tg_real *motion_x, *motion_y;/* previous-frame screen position of this pixel's surface
                                    (continuous pixel coordinates); NULL unless planned */
} tgi_gbuffer;

static inline int tgi_gb_is_sky(const tgi_gbuffer *g, int i) { return g->sky[i] != 0; }

#endif
