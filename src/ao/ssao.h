/* SPDX-License-Identifier: MIT */
/*
 * ssao.h - Crytek-style screen-space ambient occlusion by point samples
 * (RTR sec. 11.3.6; Klehm et al. 2011 sec. 2 and 4), three variants:
 *
 *   TG_SSAO_SPHERE      Crytek3D in a sphere (Mittring 2007): view-space
 *                       points in a ball of `radius` about P, tested against
 *                       the depth buffer.  Half the ball lies under any
 *                       surface, so an open plane gives an unblocked fraction
 *                       f = 1/2 by construction; the kernel is antipodally
 *                       symmetric so this holds exactly, and ao = min(1, 2 f)
 *                       (our normalisation; RTR notes raw Crytek darkens
 *                       flat surfaces).  Open plane: ao = 1 up to the bias.
 *   TG_SSAO_HEMISPHERE  the normal-oriented hemisphere (RTR 11.3.6, Klehm's
 *                       Crytek3D on the unit hemisphere): points along
 *                       cosine-distributed directions (so the unblocked
 *                       fraction estimates the cosine-weighted eq. 11.8) at
 *                       distances of a volume-uniform ball.  ao = f.
 *   TG_SSAO_DISK2D      Klehm's Crytek2D: a screen-space disk of the
 *                       projected radius; neighbour positions x_j occlude
 *                       when above the tangent plane (Delta . n > 0, Klehm's
 *                       d_xn) and nearer than `radius` in 3D.  ao = 1 -
 *                       blocked fraction.  No bent normal (the unblocked
 *                       Delta lie in the tangent plane).
 * The bent normal (sphere, hemisphere) is Klehm sec. 3.1: the mean of the
 * unblocked sample directions.  Per-pixel kernel rotation from the 4x4
 * interleaved pattern.  No near-field output.
 */
#ifndef TG_SSAO_H
#define TG_SSAO_H

#include "ao.h"

typedef enum tgi_ssao_variant { TG_SSAO_SPHERE = 0, TG_SSAO_HEMISPHERE = 1, TG_SSAO_DISK2D = 2 } tgi_ssao_variant;

typedef struct tgi_ssao_params {
    int samples;       /* points per pixel, 1..TG_AO_MAX_SAMPLES (default 16) */
    tg_real radius;    /* world units (default 1) */
    int variant;       /* tgi_ssao_variant (default TG_SSAO_HEMISPHERE) */
    tg_real bias;      /* depth below the occluder's tangent plane that counts, fraction of the radius (default 0.03) */
} tgi_ssao_params;

void tgi_ssao_defaults(tgi_ssao_params *p);
void tgi_ssao_rows(const tgi_ssao_params *p, const tgi_gview *g, const tgi_gresult *out,
                    int y0, int y1);

#endif
