/* SPDX-License-Identifier: MIT */
/*
 * shadowmap.h - shadows for lights marked `shadows`: depth-only shadow maps
 * rasterized by the G-buffer's rasterizer (tgi_raster_depth16), or shadow
 * rays against the scene's BVH (a visibility function the caller gives).
 *
 *   directional  one orthographic map; across the light, the square that
 *                holds the receivers the camera sees (or, with no view, the
 *                whole scene bounds); along it, the whole bounds (every
 *                caster); stored depth = distance along the light direction
 *                from the front of the bounds (clip z).
 *   spot         one perspective map, half angle = the spot angle plus a
 *                border of PCF texels (the cone is clamped to 80 degrees).
 *   point        a cube of six perspective faces (+X -X +Y -Y +Z -Z), each
 *                with its own size; a face no visible receiver looks up is
 *                absent (size 0: no memory, not rendered).  Each face is
 *                rendered slightly wider than 90 degrees so that the PCF
 *                footprint of a lookup near a face edge stays inside the
 *                chosen face: no seams.
 * Perspective maps store clip w = the distance along the face axis.
 *
 * Storage: 16 bits a texel (TG_SHADOW_DEPTH16, the default, in both number
 * types) or a tg_real (TG_SHADOW_DEPTH32).  A 16-bit face stores its depth
 * range [lo, lo + range) - the distances along its axis from the light's
 * near plane to past the farthest corner of the scene bounds, or the
 * bounds' extent along a directional light - in 65536 steps; code 65535
 * (nothing drawn) reads back beyond every receiver, so it is lit.
 *
 * Lookup (tgi_shadow_visibility_err): PCF, a 2x2 bilinear comparison or a
 * 3x3 tent (a 4x4 texel footprint with bilinear weights), of the receiver
 * against the stored depths.  1 = lit, 0 = shadowed.
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
 *   - plus a constant bias of half a texel (curved receivers) and, in 16
 *     bits, one quantisation step (a stored depth reads back within half a
 *     step; the other half covers the arithmetic of the two conversions).
 * Points outside a map, in an absent face, or where nothing was drawn, are
 * lit.  An occluder nearer the receiver's plane than the offset is lost
 * (light leaks by ~1/8 pixel or texel at contact).
 *
 * Ray-cast shadows (tgi_shadow_rays_setup): the same lookup answers with
 * the caller's ray function (hard shadows: 1 or 0 per point, from the
 * receiver moved along its normal by position_error), no map memory.
 *
 * Memory: the caller gives tgi_shadow_need_bytes() bytes (2-byte aligned
 * for 16-bit maps, tg_real aligned for 32-bit ones).
 *
 * What the plan calls, per light with `shadows` (shadowview.h holds the
 * view-dependent functions):
 *   lo, hi = tgi_shadow_animation_bounds(scene, frames)  (the rest bounds
 *            when nothing moves)
 *   tgi_shadow_need_init(&nd, light);  nd.objects_move = (objects move);
 *   for every frame's camera view v (once for a still camera):
 *       tgi_shadow_map_size_rule(&nd, light, &v, lo, hi, tri_pos, tri_count);
 *   tgi_shadow_need_finish(&nd, request.shadow_map_size);  (0 = by the rule)
 *   map_bytes = tgi_shadow_need_bytes(&nd);
 *   tgi_shadow_choose(map_bytes, tgi_bvh_bytes(tri_count) (0 when a BVH
 *                     is built anyway), pixels, shadowed lights):
 *     TG_SHADOW_BY_MAP:  tgi_shadow_map_setup_need(&sm, light, &nd, lo, hi,
 *                        take(map_bytes)); sm.filter = the request's;
 *                        frame 0, and every frame whose objects moved
 *                        (after tgi_shadow_map_refit(&sm, posed lo, hi)):
 *                        tgi_shadow_map_render(&sm, posed triangles);
 *     TG_SHADOW_BY_RAYS: tgi_bvh_build over the triangles (again whenever
 *                        they move), tgi_shadow_rays_setup(&sm, light,
 *                        tgi_bvh_light_visibility, &bvh);
 *   tgi_direct_rows(..., shadow_maps = { &sm, ... }, ...) as before.
 * A technique that looks shadows up at points the camera does not see (the
 * reference's one-bounce source at its rays' hits) needs every face whole:
 * tgi_shadow_need_all(&nd) before finish (or shadow rays).
 */
#ifndef TG_SHADOWMAP_H
#define TG_SHADOWMAP_H

#include "../scene/scene.h"
#include "../raster/view.h"

#define TG_SHADOW_MAX_FACES 6

/* PCF filters (tgi_shadow_map.filter; setup picks the bilinear):
 *   BILINEAR  4 taps, bilinear comparison: the default.  At the size rule's
 *             texel per pixel its visibility is nearer hard shadow rays'
 *             than the tent's (mean error 0.0028-0.0035 against 0.0074-0.0080
 *             on cornell, columns and spheres at 320x240) for 55-60% of the
 *             tent's instructions (README "Shadows")
 *   TENT      16 taps, a 3x3 tent with bilinear weights: softer, ~1.5 texel radius */
enum { TG_SHADOW_PCF_TENT = 0, TG_SHADOW_PCF_BILINEAR = 1 };

/* Storage of a texel. */
enum { TG_SHADOW_DEPTH16 = 16, TG_SHADOW_DEPTH32 = 32 };

/* What a light's shadow map needs for the views a request renders
 * (tgi_shadow_map_size_rule fills it, view by view; tgi_shadow_need_finish
 * turns it into sizes).  The light plane of a face: tan coordinates
 * (x/z, y/z in the face's basis) for a perspective face, world units in
 * the light's basis for a directional map. */
typedef struct tgi_shadow_need {
    int faces;                             /* 1, or 6 for a point light */
    int seen[TG_SHADOW_MAX_FACES];         /* some view's receivers look this face up */
    tg_real density[TG_SHADOW_MAX_FACES];  /* texels per unit of the light plane the rule asks for */
    int window_set[TG_SHADOW_MAX_FACES];   /* 1: window[] holds the seen receivers */
    tg_real window[TG_SHADOW_MAX_FACES][4]; /* x0 y0 x1 y1 on the light plane (else the whole
                                              face, or the bounds for a directional map) */
    tg_real whole_side[TG_SHADOW_MAX_FACES]; /* the whole face's side on the light plane
                                              (the rule sets it; 0: unknown) */
    int size[TG_SHADOW_MAX_FACES];         /* after finish: texels per side, 0 = absent */
    int depth_bits;                        /* TG_SHADOW_DEPTH16 (default) or 32 */
    int objects_move;                      /* set by the caller: the triangles the rule is
                                              given are not where every frame has them */
} tgi_shadow_need;

/* One face of a map. */
typedef struct tgi_shadow_face {
    int size;                    /* texels per side; 0: absent (no memory, lookups lit) */
    size_t offset;               /* its first texel in the storage */
    tg_vec3 right, up, forward;
    tgi_mat4 world_to_clip;
    tg_real focal;               /* perspective: NDC per unit of x/z (1 / tan half angle) */
    tg_real tan_half;            /* perspective: 1 / focal */
    tg_real center_x, center_y;  /* perspective: the window's centre, in x/z and y/z */
    tg_real texel_ndc;           /* 2 / size: one texel in NDC */
    tg_real texel_world;         /* ortho: world units per texel; persp: per texel at depth 1 */
    tg_real depth_lo, depth_range; /* 16-bit: stored depth = lo + range q / 65536 */
    tg_real depth_step;          /* range / 65536 (float); 0 for 32-bit storage */
} tgi_shadow_face;

/* Ray-cast visibility of light l at p (unit normal n, facing the light),
 * position error bound err: 1 lit, 0 shadowed.  `tracer` is the caller's
 * (e.g. tgi_bvh_light_visibility with a tgi_bvh). */
typedef tg_real (*tgi_shadow_ray_fn)(const void *tracer, const tgi_light *l, tg_vec3 p, tg_vec3 n,
                                     tg_real err);

typedef struct tgi_shadow_map {
    int size;                    /* the largest face's texels per side */
    int faces;                   /* 1, or 6 for a point light; 0: empty (every lookup lit) */
    int orthographic;            /* directional light */
    int filter;                  /* TG_SHADOW_PCF_*; may be changed after setup */
    int depth_bits;              /* TG_SHADOW_DEPTH16 or 32 */
    tg_vec3 origin;              /* light position (perspective maps) */
    tgi_shadow_face face[TG_SHADOW_MAX_FACES];
    tg_real ortho_scale;         /* orthographic: NDC per world unit */
    tg_real ortho_scale_inv;     /* orthographic: world units per NDC unit */
    tg_real ortho_center_x, ortho_center_y, ortho_near; /* in the light basis */
    tg_real texel_world;         /* face 0's (or the largest face's) texel_world */
    tgi_shadow_need need;        /* what setup was given (refit keeps it) */
    void *depth;                 /* the storage: uint16_t or tg_real texels, face by face */
    tgi_shadow_ray_fn ray;       /* ray-cast shadows: non-NULL, no map */
    const void *tracer;
    const tgi_light *light;
} tgi_shadow_map;

/* ---- a need without a view: every face at one size (the --shadow-size
 * behaviour before the size rule) ---- */

#if TG_NO_SHADOW_MAPS
/* This build has no shadow maps (tinygi.h "FEATURE SWITCHES"): tg_plan_make
 * refuses the shadows effect, so no frame holds a map and every map pointer
 * the callers pass is NULL.  What they call reads as "no map": 0 bytes,
 * nothing to fit or render, every point lit.  Nothing of shadowmap.c is
 * linked. */
static inline size_t tgi_shadow_map_bytes(const tgi_light *l, int size) { (void)l; (void)size; return 0; }
static inline void tgi_shadow_map_setup(tgi_shadow_map *sm, const tgi_light *l, int size,
                                        tg_vec3 scene_min, tg_vec3 scene_max, void *memory)
{
    (void)l; (void)size; (void)scene_min; (void)scene_max; (void)memory;
    memset(sm, 0, sizeof *sm);
}
static inline void tgi_shadow_map_render(tgi_shadow_map *sm, const tg_vec3 *pos, int tri_count)
{
    (void)sm; (void)pos; (void)tri_count;
}
static inline tg_real tgi_shadow_visibility_err(const tgi_shadow_map *sm, tg_vec3 world_pos,
                                                tg_vec3 world_normal, tg_real position_error)
{
    (void)sm; (void)world_pos; (void)world_normal; (void)position_error;
    return TG_ONE;
}
static inline tg_real tgi_shadow_visibility(const tgi_shadow_map *sm, tg_vec3 world_pos, tg_vec3 world_normal)
{
    (void)sm; (void)world_pos; (void)world_normal;
    return TG_ONE;
}
static inline tg_real tgi_shadow_gbuffer_error(const tgi_view *view) { (void)view; return 0; }
static inline size_t tgi_shadow_need_bytes(const tgi_shadow_need *nd) { (void)nd; return 0; }
static inline void tgi_shadow_map_setup_need(tgi_shadow_map *sm, const tgi_light *l, const tgi_shadow_need *nd,
                                             tg_vec3 scene_min, tg_vec3 scene_max, void *memory)
{
    (void)l; (void)nd; (void)scene_min; (void)scene_max; (void)memory;
    memset(sm, 0, sizeof *sm);
}
static inline void tgi_shadow_map_refit(tgi_shadow_map *sm, tg_vec3 scene_min, tg_vec3 scene_max)
{
    (void)sm; (void)scene_min; (void)scene_max;
}
static inline void tgi_shadow_rays_setup(tgi_shadow_map *sm, const tgi_light *l, tgi_shadow_ray_fn ray,
                                         const void *tracer)
{
    (void)l; (void)ray; (void)tracer;
    memset(sm, 0, sizeof *sm);
}
#else
/* Bytes of a 16-bit map for light `l` with every face at `size` texels; 0
 * for a size outside TG_MIN_SHADOW_MAP..TG_MAX_SHADOW_MAP (or one whose
 * bytes would not fit in a size_t). */
size_t tgi_shadow_map_bytes(const tgi_light *l, int size);

/* Fit such a map to the light and the scene bounds; `memory` holds
 * tgi_shadow_map_bytes(l, size) bytes.  A size that bytes refuses gives an
 * empty map: rendering writes nothing and every lookup is lit. */
void tgi_shadow_map_setup(tgi_shadow_map *sm, const tgi_light *l, int size,
                         tg_vec3 scene_min, tg_vec3 scene_max, void *memory);

/* ---- the need ---- */

/* Start a need for light l: no face seen yet, 16-bit storage. */
void tgi_shadow_need_init(tgi_shadow_need *nd, const tgi_light *l);

/* Every face, whole (the whole nominal face; a directional map the whole
 * bounds): when no view is known, or when shadows are looked up where the
 * camera does not see. */
void tgi_shadow_need_all(tgi_shadow_need *nd);

/* Sizes from the densities: each seen face with a window gets
 * ceil(density x its window's side) texels plus the PCF border on each
 * side, clamped to TG_MIN_SHADOW_MAP..TG_MAX_SHADOW_MAP; a whole face
 * likewise across its whole side when the rule gave it a density and that
 * side, else the largest of the others (at least TG_MIN_SHADOW_MAP); an
 * unseen face 0.  A size_override > 0 (--shadow-size) makes every seen
 * face whole at that size (the same face whatever the views). */
void tgi_shadow_need_finish(tgi_shadow_need *nd, int size_override);

/* Bytes of the storage for a finished need; 0 when a size is out of range
 * or the sum does not fit in a size_t (and when no face is seen). */
size_t tgi_shadow_need_bytes(const tgi_shadow_need *nd);

/* Fit the map to the light, the need and the bounds; memory holds
 * tgi_shadow_need_bytes(nd) bytes.  A need whose bytes are 0 gives an
 * empty map. */
void tgi_shadow_map_setup_need(tgi_shadow_map *sm, const tgi_light *l, const tgi_shadow_need *nd,
                               tg_vec3 scene_min, tg_vec3 scene_max, void *memory);

/* Refit to new bounds (objects moved), keeping the light, need, filter and
 * memory; render again afterwards. */
void tgi_shadow_map_refit(tgi_shadow_map *sm, tg_vec3 scene_min, tg_vec3 scene_max);

/* Ray-cast shadows for light l: lookups call ray(tracer, l, p, n, err). */
void tgi_shadow_rays_setup(tgi_shadow_map *sm, const tgi_light *l, tgi_shadow_ray_fn ray,
                           const void *tracer);

/* Rasterize `tri_count` triangles (3 world positions each) into every
 * present face (nothing for ray-cast shadows). */
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

#if TG_FIXED
/* For tests: a perspective tap's depth test num >= tg_mul(a, den), as the
 * 64-bit compare of the Q16.16 lookups (wide) or as written. */
int tgi_shadow_lit_perspective_q16(tg_real num, tg_real a, tg_real den, int wide);
#endif

/* Error bound, per unit of view depth, of a world position reconstructed
 * from the G-buffer depth of `view` (the rasterizer's 1/16-pixel snapping,
 * and the arithmetic): position_error = depth * this. */
tg_real tgi_shadow_gbuffer_error(const tgi_view *view);

/* Cube face (0..5: +X -X +Y -Y +Z -Z) a point light's lookup uses for the
 * direction d from the light: the axis of d's largest component. */
int tgi_shadow_cube_face(tg_vec3 d);

/* The face's nominal half angle's tangent (before the PCF border): 1 for a
 * cube face, tan(angle) for a spot (clamped to 80 degrees); 0 otherwise. */
tg_real tgi_shadow_nominal_tan(const tgi_light *l);

/* The light's near distance and the unit axis of face f (perspective maps;
 * a directional light's direction). */
tg_real tgi_shadow_near(tg_vec3 origin, tg_vec3 scene_min, tg_vec3 scene_max);
tg_vec3 tgi_shadow_face_axis(const tgi_light *l, int face);

/* A face's right-handed basis: forward given, right = forward x helper, up = right x forward. */
void tgi_shadow_basis(tg_vec3 forward, tg_vec3 *right, tg_vec3 *up);

#endif /* !TG_NO_SHADOW_MAPS */

/* Texels of PCF border on each side of a face beyond its nominal extent. */
#define TG_SHADOW_BORDER 2

#endif
