/* SPDX-License-Identifier: MIT */
/*
 * shadowmap.h - depth-only shadow maps for lights marked `shadows`,
 * rasterized by the G-buffer's rasterizer (tgi_raster_depth).
 *
 *   directional  one orthographic map fitted to the scene bounds (the light's
 *                view of the bounding box); stored depth = distance along the
 *                light direction from the front of the box (clip z).
 *   spot         one perspective map, half angle = the spot angle plus a
 *                border of PCF texels (the cone is clamped to 80 degrees).
 *   point        a cube of six perspective faces (+X -X +Y -Y +Z -Z).  Each
 *                face is rendered slightly wider than 90 degrees so that the
 *                PCF footprint of a lookup near a face edge stays inside the
 *                chosen face: no seams.
 * Perspective maps store clip w = the distance along the face axis.
 *
 * Lookup (tgi_shadow_visibility_err): PCF, a 3x3 tent (a 4x4 texel
 * footprint with bilinear weights) or, cheaper, a 2x2 bilinear comparison,
 * of the receiver against the stored depths.  1 = lit, 0 = shadowed.
 *   - receiver plane: the receiver's depth at each tap is extrapolated along
 *     its tangent plane to the tap's texel centre, so a plane is compared
 *     with itself at every incidence; a tap is never taken deeper than the
 *     lookup itself (past the plane's horizon, or round a concave corner,
 *     the plane's continuation is not there to be shadowed);
 *   - normal offset: that plane is first moved toward the light along the
 *     normal by the error bound of the receiver's position (the caller's
 *     `position_error`: a G-buffer position reconstructed from rasterized
 *     depth is off by up to ~1/20 pixel, tgi_shadow_gbuffer_error) plus
 *     the map's own (its rasterized depths likewise, ~1/20 texel), at most
 *     half way to the light.  An offset along the normal is 1/cos(theta)
 *     along the light's ray, so it holds at every grazing angle, where a
 *     depth bias does not: a surface facing the light with nothing between
 *     is lit at any image and map size;
 *   - plus a constant bias of half a texel (curved receivers).
 * Points outside a map, or where nothing was drawn, are lit.  An occluder
 * nearer the receiver's plane than the offset is lost (light leaks by
 * ~1/8 pixel or texel at contact).
 *
 * Memory: the caller gives tgi_shadow_map_bytes() bytes (tg_real aligned).
 */
#ifndef TG_SHADOWMAP_H
#define TG_SHADOWMAP_H

#include "../scene/scene.h"
#include "../raster/view.h"

#define TG_SHADOW_MAX_FACES 6

/* PCF filters (tgi_shadow_map.filter; setup picks the tent):
 *   TENT      16 taps, a 3x3 tent with bilinear weights: soft, ~1.5 texel radius
 *   BILINEAR  4 taps, bilinear comparison: a quarter of the cost, harder edges */
enum { TG_SHADOW_PCF_TENT = 0, TG_SHADOW_PCF_BILINEAR = 1 };

typedef struct tgi_shadow_map {
    int size;                    /* texels per side */
    int faces;                   /* 1, or 6 for a point light */
    int orthographic;            /* directional light */
    int filter;                  /* TG_SHADOW_PCF_*; may be changed after setup */
    tg_vec3 origin;              /* light position (perspective maps) */
    tg_vec3 right[TG_SHADOW_MAX_FACES], up[TG_SHADOW_MAX_FACES], forward[TG_SHADOW_MAX_FACES];
    tgi_mat4 world_to_clip[TG_SHADOW_MAX_FACES];
    tg_real focal;               /* perspective: NDC per unit of x/z (1 / tan half angle) */
    tg_real tan_half;            /* perspective: 1 / focal */
    tg_real texel_ndc;           /* 2 / size: one texel in NDC */
    tg_real ortho_scale;         /* orthographic: NDC per world unit */
    tg_real ortho_scale_inv;     /* orthographic: world units per NDC unit */
    tg_real ortho_center_x, ortho_center_y, ortho_near; /* in the light basis */
    tg_real texel_world;         /* ortho: world units per texel; persp: per texel at depth 1 */
    tg_real *depth;              /* faces * size * size, face-major, rows top to bottom */
} tgi_shadow_map;

/* Bytes of depth storage a map for light `l` at `size` texels needs; 0 for
 * a size outside TG_MIN_SHADOW_MAP..TG_MAX_SHADOW_MAP (or one whose bytes
 * would not fit in a size_t). */
size_t tgi_shadow_map_bytes(const tgi_light *l, int size);

/* Fit the map to the light and the scene bounds; `memory` holds
 * tgi_shadow_map_bytes(l, size) bytes.  A size that bytes refuses gives an
 * empty map: rendering writes nothing and every lookup is lit. */
void tgi_shadow_map_setup(tgi_shadow_map *sm, const tgi_light *l, int size,
                         tg_vec3 scene_min, tg_vec3 scene_max, void *memory);

/* Rasterize `tri_count` triangles (3 world positions each) into all faces. */
void tgi_shadow_map_render(tgi_shadow_map *sm, const tg_vec3 *pos, int tri_count);

/* The same for one face and texel rows [y0, y1) (for splitting across threads). */
void tgi_shadow_map_render_rows(tgi_shadow_map *sm, int face, const tg_vec3 *pos,
                               int tri_count, int y0, int y1);

/* Fraction of the light reaching `world_pos` (surface normal `world_normal`,
 * unit), in [0, 1].  `position_error` (>= 0, world units) bounds how far
 * world_pos may lie from the true surface along the normal. */
tg_real tgi_shadow_visibility_err(const tgi_shadow_map *sm, tg_vec3 world_pos, tg_vec3 world_normal,
                                  tg_real position_error);

/* The same for an exact receiver (a ray-traced point): position_error 0. */
tg_real tgi_shadow_visibility(const tgi_shadow_map *sm, tg_vec3 world_pos, tg_vec3 world_normal);

/* Error bound, per unit of view depth, of a world position reconstructed
 * from the G-buffer depth of `view` (the rasterizer's 1/16-pixel snapping,
 * and the arithmetic): position_error = depth * this. */
tg_real tgi_shadow_gbuffer_error(const tgi_view *view);

#endif
