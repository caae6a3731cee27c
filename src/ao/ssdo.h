/* SPDX-License-Identifier: MIT */
/*
 * ssdo.h - screen-space directional occlusion (Ritschel, Grosch and Seidel
 * 2009, sec. 3).  Per pixel, N directions w_i uniform over the normal's
 * hemisphere (each Delta w = 2 pi / N) and a step lambda_i in [0, radius]
 * give sample points P + lambda_i w_i; a point is an occluder when the
 * surface seen at its pixel is in front of it (and nearer than the radius:
 * the usual range check).  Then
 *   direct / far   E_do = sum_i L_env(w_i) V(w_i) cos(theta_i) Delta w
 *                  (Ritschel's L_dir without the BRDF rho/pi, which the
 *                  compose pass applies): the environment is occluded per
 *                  direction, not by one AO factor.  Written to far.
 *   indirect       E_near = sum_i L_pixel (1 - V(w_i)) A_s cos(theta_s) cos(theta_r) / d_i^2
 *                  for each occluder, the pixel it projects to sends its
 *                  direct-light radiance (`radiance`) from a patch of area
 *                  A_s = bounce * pi radius^2 / N oriented by that pixel's
 *                  normal; back-facing senders (cos theta_s <= 0) and
 *                  senders below the receiver's tangent plane give nothing
 *                  (the sender-normal check).  d^2 is clamped below by
 *                  A_s / pi (Ritschel clamps d to 1; ours is scale-free).
 *   ao / bent      the cosine-weighted visible fraction and mean visible
 *                  direction of the same samples (RTR eq. 11.8, 11.10).
 *   lights         a delta light is never hit by a random hemisphere
 *                  direction, so, as Ritschel does for "known important
 *                  light sources", each light gets its own additional sample
 *                  direction (towards it); its visibility is the same
 *                  screen-space test marched at `light_steps` points along
 *                  that direction within the radius (Ritschel uses shadow
 *                  maps there; the frame can use either):
 *                  E_lights = sum_l E_l(P, n) V_ss(l), E_l from
 *                  light/direct.h (falloff, spot cone, cosine), into
 *                  light.  light_count 0 (default) skips it.
 */
#ifndef TG_SSDO_H
#define TG_SSDO_H

#include "ao.h"

typedef struct tgi_ssdo_params {
    int samples;                 /* directions per pixel, 1..TG_AO_MAX_SAMPLES (default 16) */
    tg_real radius;              /* r_max, world units (default 1) */
    tg_real bias;                /* depth below the occluder's tangent plane that counts, fraction of the radius (default 0.03) */
    tg_real bounce;              /* sender patch area factor (default 1) */
    const tg_vec3 *env_sh9;      /* environment radiance SH9 (light/sh.h order); NULL = none */
    tgi_rgb far;                 /* out: E_do from the environment; absent = not wanted */
    const struct tgi_light *lights;  /* scene lights (scene.h); NULL or light_count 0 = none */
    int light_count;
    int light_steps;             /* screen-space march points per light (default 4) */
    tgi_rgb light;               /* out: direct irradiance with screen-space DO; absent = not wanted */
} tgi_ssdo_params;

void tgi_ssdo_defaults(tgi_ssdo_params *p);
void tgi_ssdo_rows(const tgi_ssdo_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                    const tgi_gresult *out, int y0, int y1);

#endif
