/* SPDX-License-Identifier: MIT */
/*
 * compose.h - outgoing diffuse radiance from the irradiance terms, in linear
 * light (HBIL eq. 14 and 19):
 *
 *   E  = E_direct + E_far + E_near                    (HBIL sec. 2.3)
 *   Lo = albedo / pi * (1 - F0) * E + emissive        (HBIL eq. 14, 19)
 *
 * Sky pixels: Lo = the environment's radiance seen along the pixel's view
 * ray (tgi_env_radiance; 0 without an environment), E = 0.
 * Fixed point: every step saturates (an HDR value clamps at TG_REAL_MAX,
 * never wraps).
 */
#ifndef TG_COMPOSE_H
#define TG_COMPOSE_H

#include "../scene/scene.h"
#include "../raster/gview.h"

/* Rows [y0, y1) of a full-resolution view g.  terms: term_count irradiance
 * terms summed (e.g. [direct, far, near]), indexed like g; absent terms are
 * skipped.  out: Lo.  irr: the total E (AOV `irradiance`); NULL or absent
 * when not wanted.  g's camera and env give the sky (either may be NULL:
 * a black sky). */
void tgi_compose_rows(const tgi_gview *g, const tgi_env *env, const tgi_rgb *terms, int term_count,
                      const tgi_rgb *out, const tgi_rgb *irr, int y0, int y1);

/* The radiance of a sky pixel (x, y) of the camera's image: the
 * environment along its view ray (0 without an environment or camera). */
tg_vec3 tgi_compose_sky(const tgi_view *view, const tgi_env *env, int x, int y);

#endif
