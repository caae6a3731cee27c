/* SPDX-License-Identifier: MIT */
/*
 * interleave.h - 4x4 split and merge of full-resolution buffers into 16
 * quarter-resolution sub-images (HBIL sec. 3.3; Bavoil 2014, deinterleaved
 * texturing).
 *
 * Sub-image (i, j), i, j in 0..3, holds the full-resolution pixels
 * (4x + i, 4y + j).  Its size is sw = ceil((w - i) / 4), sh = ceil((h - j) / 4)
 * (0 when w <= i or h <= j: such a sub-image is empty).  The 16 sub-images
 * are stored one after the other in the order k = j * 4 + i, each row-major
 * with its own width sw; `offset` is where sub-image (i, j) starts.  The
 * total size is exactly w * h, so split and merge are exact inverses for
 * every size down to 1x1.
 */
#ifndef TG_INTERLEAVE_H
#define TG_INTERLEAVE_H

#include "../core/real.h"

/* Size and start of sub-image (i, j) of a w x h image. */
void tgi_interleave_sub_rect(int w, int h, int i, int j, int *sw, int *sh, size_t *offset);

/* Where full-resolution row y lands: pixel (x, y) of a w x h image is at
 * start[x & 3] + (x >> 2) of the sub-image layout. */
void tgi_interleave_row(int w, int h, int y, size_t start[4]);

/* Full-resolution src (w x h) -> 16 concatenated sub-images in dst (w * h).
 * The row range [y0, y1) is in FULL-resolution rows. */
void tgi_interleave_split_rows(const tg_real *src, int w, int h, tg_real *dst, int y0, int y1);
void tgi_interleave_merge_rows(const tg_real *src, int w, int h, tg_real *dst, int y0, int y1);
void tgi_interleave_split8_rows(const uint8_t *src, int w, int h, uint8_t *dst, int y0, int y1);
void tgi_interleave_merge8_rows(const uint8_t *src, int w, int h, uint8_t *dst, int y0, int y1);

/* Whole images. */
void tgi_interleave_split(const tg_real *src, int w, int h, tg_real *dst);
void tgi_interleave_merge(const tg_real *src, int w, int h, tg_real *dst);
void tgi_interleave_split8(const uint8_t *src, int w, int h, uint8_t *dst);
void tgi_interleave_merge8(const uint8_t *src, int w, int h, uint8_t *dst);

#endif
