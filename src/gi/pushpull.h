/* SPDX-License-Identifier: MIT */
/*
 * pushpull.h - push/pull hole filling (Kraus 2009, "The Pull-Push Algorithm
 * Revisited"; HBIL sec. 3.2).
 *
 * Push: mips are built from the valid pixels only, each texel carrying the
 * weight of the valid pixels under it (clamped to 1).  Pull: from the
 * coarsest level up, every texel with weight < 1 is completed by the
 * bilinearly upsampled coarser level.  Every output is a convex combination
 * of valid inputs, so it is finite and within their range; no valid input
 * at all (a camera cut) gives 0 everywhere.  Valid pixels are unchanged.
 *
 * Whole-image pass (the mip chain is small: 1/3 of the image).
 */
#ifndef TG_PUSHPULL_H
#define TG_PUSHPULL_H

#include "../core/real.h"

/* Scratch bytes for a w x h image (the mip chain: r, g, b, weight). */
size_t tgi_pushpull_bytes(int w, int h);   /* SIZE_MAX when that does not fit */

/* Fill the holes (valid[i] == 0) of r, g, b in place.  `scratch` holds at
 * least tgi_pushpull_bytes(w, h) bytes, aligned for tg_real. */
void tgi_pushpull_fill(int w, int h, tg_real *r, tg_real *g, tg_real *b,
                      const uint8_t *valid, void *scratch);

#endif
