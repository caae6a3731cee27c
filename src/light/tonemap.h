/* SPDX-License-Identifier: MIT */
/*
 * tonemap.h - the last step of a frame: exposure, a tonemapper, sRGB 8-bit.
 *
 * Tonemapper: Narkowicz's 2015 fit of the ACES filmic curve,
 *   f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1].
 * Why this one: f(0) = 0; it is strictly increasing for x >= 0 (the
 * derivative's numerator is 1.408 x^2 + 0.703 x + 0.0042 > 0); it has a soft
 * toe and a filmic shoulder, so bright GI bounces and light sources roll off
 * instead of clipping per channel as a plain clamp would; and it reaches 1 at
 * x = 7.24, so every x >= TG_ACES_WHITE maps to exactly 1 - in Q16.16 the
 * rational is then only evaluated on [0, 7.25] where nothing can overflow.
 * (Reinhard x / (1 + x) never reaches white and flattens contrast.)
 *
 * sRGB encoding is by table (no pow at run time): correctly rounded to 8 bits.
 * The 8-bit output is monotone in both builds; tgi_tonemap_aces on its own in
 * Q16.16 is monotone up to one ulp of rounding.
 */
#ifndef TG_TONEMAP_H
#define TG_TONEMAP_H

#include "../core/real.h"

#define TG_ACES_WHITE TG_R(7.25f)

/* The ACES fit on one linear value; result in [0, 1]. */
tg_real tgi_tonemap_aces(tg_real x);

/* Linear [0, 1] to the 8-bit sRGB code, correctly rounded; clamps outside. */
uint8_t tgi_srgb8(tg_real linear);

/* The 8-bit sRGB code of tgi_tonemap_aces(x), correctly rounded against the
 * exact curve (within 0.5 LSB), from a table of thresholds on x: no division. */
uint8_t tgi_tonemap8(tg_real x);

/* n pixels of linear RGB planes -> exposure -> ACES -> sRGB, interleaved RGB
 * bytes (tgi_tonemap8 per channel). */
void tgi_tonemap_row8(const tg_real *r, const tg_real *g, const tg_real *b, int n,
                     tg_real exposure, uint8_t *rgb);

#endif
