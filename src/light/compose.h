/* SPDX-License-Identifier: MIT */
/*
 * compose.h - outgoing diffuse radiance from the irradiance terms, in linear
 * light (HBIL eq. 14 and 19, design.md "compose"):
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
#include "../raster/gbuffer.h"
#include "../raster/view.h"

/* One irradiance term as three planes (gbuffer layout); r == NULL = absent. */
typedef struct tgi_rgb_planes {
    const tg_real *r, *g, *b;
} tgi_rgb_planes;

/* Rows [y0, y1).  terms: term_count irradiance terms summed (e.g. [direct,
 * far, near]); absent terms are skipped.  out_*: Lo.  irr_*: the total E
 * (AOV `irradiance`), NULL when not wanted.  view and env give the sky
 * (env may be NULL). */
void tgi_compose_rows(const tgi_gbuffer *gb, const tgi_view *view, const tgi_env *env,
                     const tgi_rgb_planes *terms, int term_count,
                     tg_real *out_r, tg_real *out_g, tg_real *out_b,
                     tg_real *irr_r, tg_real *irr_g, tg_real *irr_b, int y0, int y1);

#endif
