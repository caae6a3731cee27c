/* SPDX-License-Identifier: MIT */
/*
 * gtao.h - ground-truth ambient occlusion (Jimenez et al. 2016; RTR eq.
 * 11.18): horizon-based like HBAO but with the cosine term and no ad hoc
 * attenuation, in slices about the view vector:
 *     k_A = 1/pi int_0^pi int_{h1(phi)}^{h2(phi)} cos(theta - gamma)^+ |sin theta| dtheta dphi
 * The inner integral is analytic per slice,
 *     a(h) = (cos gamma + 2 h sin gamma - cos(2 h - gamma)) / 4   for each side,
 * times the length of the normal projected into the slice; the outer one is
 * a quadrature over `slices` slice angles.  Horizons are clamped to the
 * normal's hemisphere (h within gamma +- pi/2).  With few slices the
 * quadrature of the open hemisphere itself is off (0.86 for 2 slices on a
 * plane seen at 80 degrees), so ao is the ratio of the slice sum to the
 * same sum with open horizons, len (cos gamma + gamma sin gamma) per slice:
 * exactly 1 on any plane, and the same weights on both sides of the ratio.  Samples farther than `radius` are ignored (the same
 * cut-off distance as the reference).  Full resolution, no interleaved
 * quarter-res rendering; the 4x4 pattern only rotates the slices and
 * jitters the steps per pixel.
 *
 * Bent normal (RTR eq. 11.10 in the slice): the cosine-weighted mean
 * direction over [h1, h2] is analytic too,
 *     int sin(theta) cos(theta - gamma) |sin theta| dtheta along the slice direction,
 *     int cos(theta) cos(theta - gamma) |sin theta| dtheta along the view vector,
 * with antiderivatives F_s = cos g sin^3/3 + sin g (cos^3/3 - cos) and
 * F_c = sin g sin^3/3 - cos g cos^3/3 (derived here, see gtao.c).
 */
#ifndef TG_GTAO_H
#define TG_GTAO_H

#include "ao.h"

typedef struct tgi_gtao_params {
    int slices;        /* slice directions over pi, 1..TG_AO_MAX_SAMPLES (default 4) */
    int steps;         /* samples per side of each slice (default 8) */
    tg_real radius;    /* world units (default 1) */
} tgi_gtao_params;

void tgi_gtao_defaults(tgi_gtao_params *p);
void tgi_gtao_rows(const tgi_gtao_params *p, const tgi_gview *g, const tgi_gresult *out,
                    int y0, int y1);

#endif
