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
 *                    cone of half angle alpha along the bent normal,
 *                    cos(alpha) = tgi_cone_cos_from_ao(AO).
 *   TG_FAR_CUBE_F0   HBIL sec. 2.2.3: E0(bent) * F0(AO), the unoccluded
 *                    irradiance times the AO factor; F0(AO) = AO here.
 *   TG_FAR_OPEN      E0(n): unoccluded, AO and bent normal ignored.
 * With AO = 1 the first two equal the unoccluded irradiance exactly; under a
 * uniform environment L both give pi L AO exactly, the irradiance a
 * cosine-weighted AO means (AO = 1/pi int V cos dw, HBIL eq. 9).
 *
 * Deviation from HBIL (the cone aperture).  HBIL eq. 12 takes
 * cos(alpha) = 1 - AO, the aperture of a cone whose SOLID ANGLE is 2 pi AO:
 * the AO of eq. 8, uniform over solid angle.  tinygi's AO is cosine-weighted
 * (eq. 9, as HBIL itself computes it, eq. 11); an unoccluded cone of half
 * angle alpha about the normal has that AO = 1/pi int_0^alpha 2 pi cos sin
 * = sin^2(alpha), so cos(alpha) = sqrt(1 - AO).  With eq. 12 the cone's
 * lobe integral under a uniform sky is pi L (1 - (1 - AO)^2) =
 * pi L AO (2 - AO): (2 - AO) times what the occlusion lets through (+50% at
 * AO 0.5), which a path tracer confirms (tests/test_pathtrace.c).  Likewise
 * HBIL's F0(a) = a (1 + (1 - a)^0.75 / 2) (sec. 2.2.3) lifts eq. 8's
 * uniform AO toward a cosine-weighted visibility; applied to a
 * cosine-weighted AO it overshoots by the same kind of factor, so F0 is the
 * identity here.
 */
#ifndef TG_SH_H
#define TG_SH_H

#include "../scene/scene.h"
#include "../raster/gview.h"
#include "../raster/view.h"

typedef enum tgi_far_mode { TG_FAR_CONE_SH = 0, TG_FAR_CUBE_F0 = 1, TG_FAR_OPEN = 2 } tgi_far_mode;

/* The bent cone's aperture from a cosine-weighted AO (clamped to [0, 1]):
 * cos(alpha) = sqrt(1 - AO), the one place this formula lives (see the
 * deviation above).  AO 1 -> 0 (the hemisphere), AO 0 -> 1 (a closed cone). */
static inline tg_real tgi_cone_cos_from_ao(tg_real ao)
{
    /* a cosine-weighted AO of an open cone is sin^2(alpha) */
    return tg_sqrt(tg_sub(TG_ONE, tg_saturate(ao)));
}

/* The same as a half angle in radians, in [0, pi/2] (the `cone` AOV). */
static inline tg_real tgi_cone_angle_from_ao(tg_real ao)
{
    return tg_acos(tgi_cone_cos_from_ao(ao));
}

#if TG_NO_ENVIRONMENT
/* This build has no environment (tinygi.h "FEATURE SWITCHES"): tg_plan_make
 * refuses every plan that would read the scene's env (the far effect,
 * colour over a sky), so the frame's SH9 stays zero and the callers below
 * are reached only with no environment, whose SH9, radiance and far field
 * are 0.  Nothing of sh.c is linked. */
static inline void tgi_sh9_from_env(const tgi_env *env, tg_vec3 sh[9]) { (void)env; memset(sh, 0, 9 * sizeof *sh); }
static inline tg_vec3 tgi_sh9_irradiance(const tg_vec3 sh[9], tg_vec3 n) { (void)sh; (void)n; return tg_v3(0, 0, 0); }
static inline tg_vec3 tgi_sh9_irradiance_in_cone(const tg_vec3 sh[9], tg_vec3 axis, tg_real cos_alpha)
{
    (void)sh; (void)axis; (void)cos_alpha;
    return tg_v3(0, 0, 0);
}
static inline tg_vec3 tgi_sh9_radiance(const tg_vec3 sh[9], tg_vec3 dir) { (void)sh; (void)dir; return tg_v3(0, 0, 0); }
static inline tg_vec3 tgi_env_radiance(const tgi_env *env, tg_vec3 dir) { (void)env; (void)dir; return tg_v3(0, 0, 0); }
static inline tg_vec3 tgi_far_irradiance(const tg_vec3 sh[9], tg_vec3 n, int has_ao, tg_real ao, int has_bent,
                                         tg_vec3 bent, int mode)
{
    (void)sh; (void)n; (void)has_ao; (void)ao; (void)has_bent; (void)bent; (void)mode;
    return tg_v3(0, 0, 0);
}
#else

/* Radiance SH9 of an environment (RTR eq. 10.40-10.41, done analytically):
 * uniform L -> L00 = 2 sqrt(pi) L; sky/ground hemisphere -> bands 0 and 1
 * only (the step's band-2 projection is exactly zero), whose irradiance is
 * RTR eq. 10.43 and agrees with eq. 10.42 facing up, sideways and down;
 * sh9 -> copied; none -> zeros. */
void tgi_sh9_from_env(const tgi_env *env, tg_vec3 sh[9]);

/* Unoccluded irradiance E0(n), n unit world normal (Ramamoorthi-Hanrahan
 * cosine-lobe convolution). Negative ringing is clamped to 0. */
tg_vec3 tgi_sh9_irradiance(const tg_vec3 sh[9], tg_vec3 n);


/* Irradiance from the cone of half angle alpha about `axis`, given
 * cos_alpha in [0, 1] (clamped) (HBIL sec. 2.2.4); cos_alpha = 0 gives the
 * hemisphere. */
tg_vec3 tgi_sh9_irradiance_in_cone(const tg_vec3 sh[9], tg_vec3 axis, tg_real cos_alpha);

/* The bent cone of a cosine-weighted AO: tgi_sh9_irradiance_in_cone with
 * cos_alpha = tgi_cone_cos_from_ao(ao), its band-0 weight exact in AO. */
tg_vec3 tgi_sh9_irradiance_bent_cone(const tg_vec3 sh[9], tg_vec3 bent, tg_real ao);

/* E0(bent) * F0(ao) (HBIL sec. 2.2.3) with F0(AO) = AO (see above). */
tg_vec3 tgi_sh9_irradiance_f0(const tg_vec3 sh[9], tg_vec3 bent, tg_real ao);

/* Radiance of the SH9 environment seen in world direction `dir` (unit),
 * sum of L_lm Y_lm(dir), clamped to >= 0. */
tg_vec3 tgi_sh9_radiance(const tg_vec3 sh[9], tg_vec3 dir);

/* Radiance of the environment itself in direction `dir` (unit): the exact
 * step for env sky, the constant for uniform, tgi_sh9_radiance for sh9, 0 for
 * none or a NULL env.  Used for sky pixels. */
tg_vec3 tgi_env_radiance(const tgi_env *env, tg_vec3 dir);

/* E_far of one surface: normal n, AO `ao` and bent normal `bent` of the GI
 * results (has_ao 0: unoccluded; has_bent 0: the normal), in `mode` (a
 * tgi_far_mode). */
tg_vec3 tgi_far_irradiance(const tg_vec3 sh[9], tg_vec3 n, int has_ao, tg_real ao, int has_bent, tg_vec3 bent,
                           int mode);

/* Far-field pass over rows [y0, y1) of the view g: E_far per pixel into
 * `out`, from the results `res` (NULL: unoccluded, the G-buffer normal).
 * Sky pixels get 0. */
void tgi_far_rows(const tgi_gview *g, const tg_vec3 sh[9], const tgi_gresult *res, int mode,
                  const tgi_rgb *out, int y0, int y1);

#endif /* !TG_NO_ENVIRONMENT */

#endif
