/* SPDX-License-Identifier: MIT */
/*
 * pushpull.h - push/pull hole filling (Kraus 2009, "The Pull-Push
 * Algorithm Revisited"; HBIL sec. 3.2): the holes of a reprojected radiance
 * image take a smooth value from the valid pixels around them.
 *
 * Push: level 1 is the 2x2 mean of each block's valid pixels (weight 1 when
 * any is valid, else 0); each coarser level the weighted 2x2 mean of the
 * finer one, weights summed and clamped to 1.  Pull: from the coarsest level
 * up, a texel of weight w < 1 becomes w c + (1 - w) bilinear(coarser); the
 * holes of the image take the bilinear sample of level 1.  Valid pixels are
 * never changed; the result has no hole and is finite.  The mip chain
 * (levels 1..) lives in the scratch: a colour plane and a weight per texel
 * (RGB9E5 and 8 bits, or tg_real with TG_WIDE_STORAGE): about a third of
 * the image's pixels.
 */
#ifndef TG_PUSHPULL_H
#define TG_PUSHPULL_H

#include "../raster/gview.h"

size_t tgi_pushpull_bytes(int w, int h);   /* SIZE_MAX when that does not fit */

/* Fill the holes (tgi_rgb_is_hole) of the w x h packed image c: the three
 * steps below over all rows. */
void tgi_pushpull_fill(int w, int h, const tgi_rgb *c, void *scratch);

/* The same in three steps, the first and last row-parallel (any split of
 * the rows gives the same bits):
 *   push_rows  level 1 from image rows [y0, y1): each level-1 row y with
 *              y0 <= 2y < y1 (it reads image rows 2y and 2y + 1);
 *   levels     the coarser levels pushed, then pulled back to level 1
 *              (a whole-image step, under a third of the work: README "Performance");
 *   fill_rows  the holes of image rows [y0, y1) from level 1. */
void tgi_pushpull_push_rows(int w, int h, const tgi_rgb *c, void *scratch, int y0, int y1);
void tgi_pushpull_levels(int w, int h, void *scratch);
void tgi_pushpull_fill_rows(int w, int h, const tgi_rgb *c, void *scratch, int y0, int y1);

#if !TG_OUTLINE_HELPERS /* (builds for size keep levels one step) */
/* levels in three steps, the first and last row-parallel (the same bits
 * for any split): the larger two levels' share of the work over rows
 * (cornell 320x240, float: 2.3M instructions of the 3.1M a frame):
 *   push2_rows     level 2's rows [y0, y1) pushed from level 1;
 *   levels_coarse  levels 3.. pushed, then pulled back to level 2;
 *   pull1_rows     level 1's rows [y0, y1) pulled from level 2.
 * tgi_pushpull_level_rows: the rows of level 1 or 2 (0 when the chain
 * has no such level: then its steps do nothing). */
int tgi_pushpull_level_rows(int w, int h, int level);
void tgi_pushpull_push2_rows(int w, int h, void *scratch, int y0, int y1);
void tgi_pushpull_levels_coarse(int w, int h, void *scratch);
void tgi_pushpull_pull1_rows(int w, int h, void *scratch, int y0, int y1);
#endif

#endif
