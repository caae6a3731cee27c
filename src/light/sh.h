/* SPDX-License-Identifier: MIT */
/*
 * sh.h - the distant environment as nine RGB spherical-harmonic coefficients
 * (SH9, bands 0-2) and the far-field irradiance E_far read from them.
 *
 * Coefficient order (as scene.h's env sh9): L00, L1-1, L10, L11, L2-2, L2-1,
 * L20, L21, L22, the real SH basis of Ramamoorthi and Hanrahan evaluated on
 * WORLD-space (x, y, z) directions:
 *   Y00 = 0.282095            Y1-1 = 0.488603 y   Y10 = 0.488603 z
 *   Y11 = 0.488603 x          Y2-2 = 1.092548 xy  Y2-1 = 1.092548 yz
 *   Y20 = 0.315392 (3z^2 - 1) Y21 = 1.092548 xz   Y22 = 0.546274 (x^2 - y^2)
 * The coefficients are RADIANCE coefficients (RTR eq. 10.40, k_Lj); the
 * cosine-lobe convolution (RTR eq. 10.41 / Ramamoorthi-Hanrahan) is applied
 * when irradiance is read, so the same nine numbers serve the full
 * hemisphere and the bent cone (HBIL sec. 2.2.4).
 *
 * Far field, per pixel, in one of three modes (tgi_far_mode):
 *   TG_FAR_CONE_SH   HBIL sec. 2.2.4: the cosine lobe restricted to the bent
 *                    cone, t = cos(theta_max) = 1 - AO, along the bent normal.
 *   TG_FAR_CUBE_F0   HBIL sec. 2.2.3: E0(bent) * F0(AO), the unoccluded
 *                    irradiance times the energy-compensated AO factor.
 *   TG_FAR_OPEN      E0(n): unoccluded, AO and bent normal ignored.
 * With AO = 1 the first two equal the unoccluded irradiance exactly.
 */
#ifndef TG_SH_H
#define TG_SH_H

#include "../scene/scene.h"
#include "../raster/gbuffer.h"
#include "../raster/view.h"

typedef enum tgi_far_mode { TG_FAR_CONE_SH = 0, TG_FAR_CUBE_F0 = 1, TG_FAR_OPEN = 2 } tgi_far_mode;

/* Radiance SH9 of an environment (RTR eq. 10.40-10.41, done analytically):
 * uniform L -> L00 = 2 sqrt(pi) L; sky/ground hemisphere -> bands 0 and 1
 * only (the step's band-2 projection is exactly zero), whose irradiance is
 * RTR eq. 10.43 and agrees with eq. 10.42 facing up, sideways and down;
 * sh9 -> copied; none -> zeros. */
void tgi_sh9_from_env(const tgi_env *env, tg_vec3 sh[9]);

/* Unoccluded irradiance E0(n), n unit world normal (Ramamoorthi-Hanrahan
 * cosine-lobe convolution). Negative ringing is clamped to 0. */
tg_vec3 tgi_sh9_irradiance(const tg_vec3 sh[9], tg_vec3 n);

/* Irradiance from the cone of half angle acos(1 - ao) about `bent`
 * (HBIL sec. 2.2.4). ao in [0, 1] (clamped); ao = 1 gives the hemisphere. */
tg_vec3 tgi_sh9_irradiance_cone(const tg_vec3 sh[9], tg_vec3 bent, tg_real ao);

/* HBIL sec. 2.2.3: F0(a) = a (1 + (1 - a)^0.75 / 2), a clamped to [0, 1]. */
tg_real tgi_far_f0(tg_real ao);

/* E0(bent) * F0(ao) (HBIL sec. 2.2.3). */
tg_vec3 tgi_sh9_irradiance_f0(const tg_vec3 sh[9], tg_vec3 bent, tg_real ao);

/* Radiance of the SH9 environment seen in world direction `dir` (unit),
 * sum of L_lm Y_lm(dir), clamped to >= 0. */
tg_vec3 tgi_sh9_radiance(const tg_vec3 sh[9], tg_vec3 dir);

/* Radiance of the environment itself in direction `dir` (unit): the exact
 * step for env sky, the constant for uniform, tgi_sh9_radiance for sh9, 0 for
 * none or a NULL env.  Used for sky pixels. */
tg_vec3 tgi_env_radiance(const tgi_env *env, tg_vec3 dir);

/* Far-field pass over rows [y0, y1): E_far per pixel into e_r/e_g/e_b.
 *   ao       per-pixel AO in [0, 1], NULL = unoccluded (AO 1)
 *   bent_*   world-space unit bent normal, NULL = use the G-buffer normal
 *   mode     a tgi_far_mode
 * Sky pixels get 0. */
void tgi_far_rows(const tgi_gbuffer *gb, const tg_vec3 sh[9], const tg_real *ao,
                 const tg_real *bent_x, const tg_real *bent_y, const tg_real *bent_z,
                 int mode, tg_real *e_r, tg_real *e_g, tg_real *e_b, int y0, int y1);

#endif
