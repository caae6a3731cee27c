/* SPDX-License-Identifier: MIT */
/*
 * vo.h - volumetric obscurance (Loos and Sloan 2010; RTR eq. 11.15): the
 * unoccupied fraction of a ball of `radius` about P, integrated numerically
 * over a disk of samples and ANALYTICALLY along each sample's line in depth.
 *
 *   sec. 4.1  line samples: free length max(min(z_s, d_r) + z_s, 0) with
 *             z_s = sqrt(1 - x^2 - y^2), d_r the depth buffer in the unit
 *             ball's coordinates.  Lines follow the eye rays through the
 *             disk points (the depth buffer is measured along them).
 *   sec. 4.3  thickness model: behind the visible surface only `thickness`
 *             world units are solid (the integral is taken again with
 *             1 - visibility shifted back by the thickness, and summed).
 *   sec. 4.4  clamping by the normal: each line is cut at the tangent plane
 *             (evaluated along the same ray), so only the hemisphere counts;
 *             an open plane then gives exactly 1.  Without the normal an open
 *             plane gives 1/2 and ao = min(1, 2 VO) (as ssao's sphere).
 *   sec. 4.2  area samples (option `area`): each disk sample reads the mean
 *             and standard deviation of depth over its footprint (first two
 *             moments, computed on the fly over up to 7x7 taps instead of a
 *             mip-map), and integrates the linear visibility ramp from
 *             mu - sigma to mu + sigma (Loos and Sloan's V_c formulas).
 * VO is the ratio of free to total line length (samples weighted by their
 * extent, sec. 4.5 footnote).  Outputs ao only (bent = normal).
 */
#ifndef TG_VO_H
#define TG_VO_H

#include "ao.h"

typedef struct tgi_vo_params {
    int samples;        /* line (or area) samples on the disk, 1..TG_AO_MAX_SAMPLES (default 9) */
    tg_real radius;     /* world units (default 1) */
    tg_real thickness;  /* world units (sec. 4.3); 0 = twice the radius, the ball's diameter
                           (default: surfaces inside the ball are solid through it, a
                           surface wholly in front of the ball frees what is behind);
                           TG_AO_INFINITE = no thickness model (infinitely thick) */
    int use_normal;     /* sec. 4.4 (default 1) */
    int area;           /* sec. 4.2 area samples (default 0: line samples) */
} tgi_vo_params;

void tgi_vo_defaults(tgi_vo_params *p);
void tgi_vo_rows(const tgi_vo_params *p, const tgi_gview *g, const tgi_gresult *out,
                    int y0, int y1);

#endif
