/* SPDX-License-Identifier: MIT */
/*
 * direct.h - direct diffuse irradiance E_direct from the scene's analytic
 * lights (the AOV `direct`), per G-buffer pixel.
 *
 *   directional  E = I c max(0, n . -dir)
 *   point        E = I c max(0, n . l) / d^2           (inverse square)
 *   spot         point times smoothstep(cos(angle), cos(TG_SPOT_INNER angle), -l . dir):
 *                full inside 85% of the half angle, 0 outside it, smooth between.
 * I = intensity, c = colour (linear RGB), l = unit vector to the light, d its
 * distance (clamped below at TG_DIRECT_MIN_DISTANCE so nothing divides by 0).
 * Irradiance only: the (1 - F0) and albedo / pi weights are compose's.
 * Shadowed lights multiply by tgi_shadow_visibility.
 */
#ifndef TG_DIRECT_H
#define TG_DIRECT_H

#include "../scene/scene.h"
#include "../raster/gview.h"
#include "shadowmap.h"

#define TG_SPOT_INNER TG_R(0.85f)
#define TG_DIRECT_MIN_DISTANCE TG_R(0.01f)

/* E_direct for rows [y0, y1) of a full-resolution view g, into e (indexed
 * like g).  World position of a pixel = the G-buffer depth unprojected at
 * the pixel centre with g's camera (tgi_view_unproject + tgi_view_view_to_world).
 * shadow_maps: NULL, or one entry per light, a NULL entry = unshadowed.
 * Sky pixels get 0. */
void tgi_direct_rows(const tgi_gview *g, const tgi_light *lights, int light_count,
                    const tgi_shadow_map *const *shadow_maps, const tgi_rgb *e, int y0, int y1);

/* Irradiance from one light at a world point with unit normal n (no shadow). */
tg_vec3 tgi_direct_irradiance(const tgi_light *l, tg_vec3 p, tg_vec3 n);

#endif
