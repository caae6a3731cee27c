/* SPDX-License-Identifier: MIT */
/*
 * ssilvb.h - screen-space indirect lighting with a visibility bitmask
 * (Therrien, Levesque and Gilet 2023, "Screen Space Indirect Lighting with
 * Visibility Bitmask", arXiv 2301.11376): GTAO's slices (gtao.h) with the
 * two horizon angles of a slice replaced by a bit field of N_b = 32 sectors
 * uniformly distributed over the slice's half circle about the normal,
 * [gamma - pi/2, gamma + pi/2] (gamma: the projected normal's angle from the
 * view vector, as in gtao.h), bit k for the angles
 *     gamma - pi/2 + [k, k + 1) pi / N_b.
 * Every depth sample is a surface of constant `thickness`: its front point
 * (the depth buffer's) and its back point (the front moved by the thickness
 * away from the eye, along the shading point's view vector) subtend the
 * angles theta_f and theta_b, and the sectors between them are set (with
 * the paper's rounding: from floor(u_min N_b), ceil((u_max - u_min) N_b)
 * sectors, u the angle mapped to [0, 1] over the half circle).
 * Light passes behind a thin object; with an infinite thickness the mask is
 * GTAO's (every sector above the highest horizon set).
 *
 * Further depth layers (request.depth_layers 2, 3; the G-buffer's
 * tgi_gv_back_depth, tgi_gv_behind_depth, raster.h): the back point is
 * where the sample's own view ray leaves the surface, at the nearest back
 * face behind it (P_b = P_f z_b / z_f), infinitely far where there is no
 * back face (a one-sided boundary), the constant thickness where the back
 * face is the surface's own (a twosided sheet); with a third layer the
 * surface behind that back face is solid again for the constant
 * thickness.  Each solid segment sets its sectors where it lies within
 * the radius (the reference's cut-off), clipped to the sphere, not where
 * its front point does (ssilvb.c, march_layers).
 *
 * Weighting: tinygi's AO is cosine-weighted (RTR eq. 11.8, the reference in
 * reference.h), so a sector is weighted by GTAO's inner integral over its
 * angles, w_k = A(theta_{k+1}) - A(theta_k) with
 *     A(theta) = int_0^theta cos(t - gamma) |sin t| dt
 *              = sign(theta) (cos gamma + 2 theta sin gamma - cos(2 theta - gamma)) / 4
 * (gtao.h's a(h) with its sign), instead of the paper's uniform
 * 1 - popcount(b) / N_b; ao is, as in gtao.h, the ratio of the slices'
 * visible weight (times |projected normal|) to their open weight: exactly 1
 * where no bit is set.  The weight of a mask is summed over its runs of set
 * bits (two A per run), so no per-sector table is needed.
 *
 * Indirect light (the paper's indirect diffuse): each sample's radiance is gathered
 * over the sectors it occludes that no nearer sample had occluded
 * (b_sample & ~b), times the same cosine weights: the near-field irradiance
 *     E = pi sum_slices len sum_samples L_s w(b_s & ~b) / sum_slices len w(open),
 * exactly pi L under a uniform L that fills the half circles.  A sample seen
 * from behind (its normal facing away from the shading point) occludes but
 * sends nothing (its back's radiance is not in the image).  The bent normal
 * is GTAO's analytic slice integral over the visible runs.
 */
#ifndef TG_SSILVB_H
#define TG_SSILVB_H

#include "ao.h"

#define TG_SSILVB_SECTORS 32   /* N_b: the bits of a uint32_t */

typedef struct tgi_ssilvb_params {
    int slices;        /* slice directions over pi, 1..TG_AO_MAX_SAMPLES (default 4) */
    int steps;         /* samples per side of each slice (default 8) */
    tg_real radius;    /* world units (default 1): samples farther are ignored */
    tg_real thickness; /* world units (default 0.5): each sample's surface behind its depth */
    const tgi_ao_rot *pattern; /* the 4x4 cells' slice rotations and march offsets (tgi_ao_slices);
                                * NULL (default): tgi_ao_rotations', the same every frame.  HBIL
                                * over depth layers passes its interleaved angles, turned every
                                * frame (hbil_passes.c) */
    int to_edge;       /* 1: a side's samples spread over the part of the radius on the screen
                        * (HBIL's march, none wasted past the edge); 0 (default): over the radius */
} tgi_ssilvb_params;

void tgi_ssilvb_defaults(tgi_ssilvb_params *p);
/* ao, bent normal, and (when `out` has a near plane and `radiance` is
 * present) the near-field irradiance from radiance, indexed like g. */
void tgi_ssilvb_rows(const tgi_ssilvb_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                     const tgi_gresult *out, int y0, int y1);

/* Sectors [floor(lo N_b), that + ceil((hi - lo) N_b)) of N_b = 32, lo and
 * hi clamped to [0, 1] (the paper's bit range of a front/back pair). */
uint32_t tgi_ssilvb_sector_bits(tg_real lo, tg_real hi);
/* u = (theta - gamma) / pi + 1/2 of the angle theta = side acos(c) from
 * the view vector in a slice of normal angle gamma: where it lies over the
 * half circle [gamma - pi/2, gamma + pi/2] (0 and 1 at its ends), the
 * acos a polynomial within 6.7e-5 (no tg_acos): 2e-5 of the half circle,
 * 1/1500 of a sector. */
tg_real tgi_ssilvb_half_circle_u(tg_real c, int side, tg_real gamma);
/* A slice's sector boundaries theta_k = gamma - pi/2 + k pi / N_b for
 * gamma in (-pi/2, pi/2) (cos_g > 0: the normal toward the eye): their
 * cosines bound[k], k = 0..N_b, and kz, how many of k = 1..N_b have
 * theta_k <= 0. */
void tgi_ssilvb_bounds(tg_real gamma, tg_real cos_g, tg_real sin_g, tg_real bound[TG_SSILVB_SECTORS + 1], int *kz);
/* The sectors a horizon at theta = side acos(c) closes, from it to the end
 * of its side: tgi_ssilvb_sector_bits(u, 1) on side +1, (0, u) on side -1,
 * u = tgi_ssilvb_half_circle_u's, without the angle: c placed among the
 * slice's bounds by a binary search (the same sectors but where theta is
 * within rounding of a boundary). */
uint32_t tgi_ssilvb_horizon_bits(tg_real c, int side, const tg_real bound[TG_SSILVB_SECTORS + 1], int kz);
/* Set bits of a 32-bit mask (portable, no builtin). */
int tgi_ssilvb_popcount(uint32_t b);

#endif
