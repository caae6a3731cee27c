/* SPDX-License-Identifier: MIT */
/*
 * hbao.h - horizon-based ambient occlusion (Bavoil et al. 2008; RTR eq.
 * 11.16-11.17): the depth buffer is a height field; along `directions`
 * screen directions the horizon angle h above the tangent angle t is found
 * by marching `steps` samples within the projected radius, and
 *     k_A = 1 - 1/(2 pi) int (sin h(phi) - sin t(phi)) W(phi) dphi   (eq. 11.17)
 * with the linear falloff W = 1 - r / radius on the distance r of the point
 * that defines the horizon (applied per rise of the horizon while marching,
 * as in Bavoil et al.), and no cosine term (the difference to GTAO).
 * Angles are elevations above the plane perpendicular to the view axis
 * (RTR fig. 11.17); the tangent is the tangent plane's line in the slice
 * through the eye and the screen direction, so an open plane gives h = t
 * and ao = 1 exactly; `angle_bias` (a sine) is added to t against
 * quantisation.  Per-pixel direction rotation and step jitter from the 4x4
 * interleaved pattern.  Outputs ao only (bent = normal).
 */
#ifndef TG_HBAO_H
#define TG_HBAO_H

#include "ao.h"

typedef struct tgi_hbao_params {
    int directions;      /* screen directions over 2 pi, 1..TG_AO_MAX_SAMPLES (default 8) */
    int steps;           /* samples per direction (default 6) */
    tg_real radius;      /* world units (default 1) */
    tg_real angle_bias;  /* sine of the bias angle added to the tangent (default 0.05) */
} tgi_hbao_params;

void tgi_hbao_defaults(tgi_hbao_params *p);
void tgi_hbao_rows(const tgi_hbao_params *p, const tgi_gview *g, const tgi_gresult *out,
                    int y0, int y1);

#endif
