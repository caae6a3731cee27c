/* SPDX-License-Identifier: MIT */
/*
 * bentcone.h - screen-space bent normals and bent cones (Klehm, Ritschel,
 * Eisemann and Seidel 2011, sec. 3.1-3.4).
 *
 *   sec. 3.1  N_ss(i) = (sum_j d(Delta_ij))^-1 sum_j Delta_ij/|Delta_ij| d(Delta_ij):
 *             the mean of the unoccluded sample directions.  Directions are
 *             uniform over the hemisphere (the definition of AO and N in
 *             Klehm eq. 1-2 has no cosine), each tested by `steps` ray-march
 *             points (Klehm sec. 5 uses 3) with the d_xn depth test.
 *             ao = unoccluded fraction (Klehm eq. 3).
 *   sec. 3.2  cone half angle C(i) = (1 - max(0, 2 |N_ss(i)| - 1)) pi / 2:
 *             an open point (|N_ss| = 1/2 for uniform directions) gets the
 *             whole hemisphere.
 *   sec. 3.3  the environment pre-convolved inside the cone about the bent
 *             normal, L_c = t / pi int L (w_o . w_i) V(cone) dw_i, evaluated
 *             analytically from SH9 (light/sh.h, HBIL sec. 2.2.4 cone
 *             coefficients).  Klehm writes t = (1 - cos a)^-1 and asks for
 *             "equal results L_c independent of a if L is constant"; the
 *             cosine-weighted cone integral of a constant is pi sin^2 a, so
 *             we use t = 1 / sin^2 a, which is what that sentence requires.
 *   sec. 3.4  the geometric term heuristic (w . n) ~ (w . N)(N . n): the
 *             cone irradiance is multiplied by max(0, N . n), and by ao
 *             ("we still rely on AO to estimate the average visibility").
 * Output far: E_far = pi L_c(N, C) ao (N . n), into far.
 */
#ifndef TG_BENTCONE_H
#define TG_BENTCONE_H

#include "ao.h"

typedef struct tgi_bentcone_params {
    int samples;                 /* directions per pixel, 1..TG_AO_MAX_SAMPLES (default 8) */
    int steps;                   /* ray-march points per direction (default 3) */
    tg_real radius;              /* world units (default 1) */
    tg_real bias;                /* depth below the occluder's tangent plane that counts, fraction of the radius (default 0.03) */
    const tg_vec3 *env_sh9;      /* environment radiance SH9; NULL = no far output */
    tgi_rgb far;                 /* out: cone-restricted environment irradiance; absent = not wanted */
} tgi_bentcone_params;

void tgi_bentcone_defaults(tgi_bentcone_params *p);
void tgi_bentcone_rows(const tgi_bentcone_params *p, const tgi_gview *g, const tgi_gresult *out,
                    int y0, int y1);

/* Klehm sec. 3.2: cone half angle from the length of the mean unoccluded
 * direction (uniform hemisphere sampling), radians in [0, pi/2]. */
tg_real tgi_bentcone_aperture(tg_real mean_length);

/* Klehm sec. 3.3-3.4: E_far = pi L_c(bent, cone) * ao * max(0, bent . n). */
tg_vec3 tgi_bentcone_far(const tg_vec3 sh[9], tg_vec3 bent, tg_real cone, tg_real ao, tg_vec3 n);

#endif
