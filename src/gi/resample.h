/* SPDX-License-Identifier: MIT */
/*
 * resample.h - quarter resolution for the GI kernel: point-sampled
 * downsampling of the G-buffer to half width and height, and the joint
 * bilateral (depth- and normal-aware) upsampling of the kernel's results.
 */
#ifndef TG_RESAMPLE_H
#define TG_RESAMPLE_H

#include "../core/vec.h"

/* Half-resolution size of a w x h image: ceil(w / 2) x ceil(h / 2). */
void tgi_half_size(int w, int h, int *hw, int *hh);

/* Half-res rows [y0, y1): pixel (X, Y) = full-res pixel (2X, 2Y). */
void tgi_downsample_rows(const tg_real *src, int w, int h, tg_real *dst, int y0, int y1);
void tgi_downsample8_rows(const uint8_t *src, int w, int h, uint8_t *dst, int y0, int y1);

typedef struct tgi_upsample_io {
    int width, height;                          /* full resolution */
    const tg_real *depth, *nx, *ny, *nz;        /* full-res guides (world normals) */
    const uint8_t *sky;                         /* full-res sky, may be NULL */
    const tg_real *half_depth, *half_nx, *half_ny, *half_nz;
    const uint8_t *half_sky;                    /* may be NULL */
    const tg_real *half_ao, *half_bent_x, *half_bent_y, *half_bent_z;
    const tg_real *half_near_r, *half_near_g, *half_near_b;
    tg_real *ao;                                /* outputs, full res */
    tg_real *bent_x, *bent_y, *bent_z;          /* NULL: not wanted */
    tg_real *near_r, *near_g, *near_b;          /* NULL: not wanted */
} tgi_upsample_io;

/* Full-res rows [y0, y1). */
void tgi_upsample_rows(const tgi_upsample_io *io, int y0, int y1);

#endif
