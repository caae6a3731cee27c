/* SPDX-License-Identifier: MIT */
/*
 * shadowview.h - what a light's shadow needs for the views a request
 * renders: which faces, how large, over which window (the size rule), how
 * many bytes; the bounds an animation's poses stay in; and whether shadow
 * rays against the BVH are the cheaper choice.
 *
 * The size rule (tgi_shadow_map_size_rule), per face of the light's map
 * (a point light's six cube faces, a spot's one, a directional light's
 * orthographic one) and per view:
 *   1. where:  the region a visible receiver can be in is the scene bounds
 *      (grown by the G-buffer position's error bound) cut by the camera's
 *      frustum and by the face's pyramid.  A face whose region is empty is
 *      not seen: no visible receiver's lookup can choose it (the lookup
 *      picks the face of the largest axis of the direction from the light,
 *      and every receiver lies in its region), so it gets no memory.  The
 *      region is exact (the boundary of the intersection of three convex
 *      hexahedra, each one's faces clipped by the others' planes), with a
 *      margin: conservative.  The face's window is the region's extent on
 *      the light plane (x/z, y/z of the face, or the light basis of a
 *      directional map): the map covers only it, its depth still every
 *      caster between the light and the bounds.
 *   2. how fine:  one texel for about one image pixel on the receivers the
 *      camera sees.  Over the scene's triangles facing both the camera and
 *      the light (at most TG_SHADOW_RULE_TRIANGLES of them, evenly
 *      sampled), cut to the frustum and the face: A_cam, the fraction of the
 *      image they cover, and A_light, the area they cover on the light
 *      plane; the face's density is sqrt(A_cam W H / A_light) texels per
 *      unit of the light plane, so that density^2 A_light texels ~ A_cam W H
 *      pixels.  Its size is that density times the window's side, plus the
 *      PCF border (tgi_shadow_need_finish), clamped to
 *      TG_MIN_SHADOW_MAP..TG_MAX_SHADOW_MAP.  Occluded triangles count in
 *      both areas (an estimate, not a bound); without triangles the
 *      region's own projected areas stand in.
 * Over several views (a moving camera) the faces seen, the windows and
 * the densities are the union / the largest: the plan calls the rule for
 * every frame's view before it allocates, so one allocation holds every
 * frame.  Objects that move: bounds holding every pose
 * (tgi_shadow_animation_bounds); the densities use the rest pose.
 */
#ifndef TG_SHADOWVIEW_H
#define TG_SHADOWVIEW_H

#include "shadowmap.h"

#define TG_SHADOW_RULE_TRIANGLES 4096   /* triangles the size rule samples per view */

/* Add one view's needs to nd (started by tgi_shadow_need_init): the faces
 * its receivers can look up, their windows and densities (see above).
 * lo, hi: the scene bounds; tri_pos: 3 positions per triangle (NULL: the
 * bounds alone). */
void tgi_shadow_map_size_rule(tgi_shadow_need *nd, const tgi_light *l, const tgi_view *view,
                              tg_vec3 lo, tg_vec3 hi, const tg_vec3 *tri_pos, int tri_count);

/* Bytes light l's map needs for one view by the rule (size_override > 0:
 * every seen face that size instead): init, rule, finish, bytes. */
size_t tgi_shadow_map_bytes_for_view(const tgi_light *l, const tgi_view *view, tg_vec3 lo, tg_vec3 hi,
                                     const tg_vec3 *tri_pos, int tri_count, int size_override);

/* Bounds holding every triangle at every frame 0..frames-1: the rest-pose
 * bounds, grown by each moving object's rest bounds carried by its pose
 * at each frame (the box of the eight transformed corners). */
void tgi_shadow_animation_bounds(const tg_scene *s, int frames, tg_vec3 *lo, tg_vec3 *hi);

/* How a light's shadows are computed. */
enum { TG_SHADOW_BY_MAP = 0, TG_SHADOW_BY_RAYS = 1 };

/* Image pixels' worth of shadow-map bytes the plan accepts before it
 * considers shadow rays (16-bit maps by the rule take 1.8-7 bytes a pixel
 * on the built-in scenes): the maps of all the lights that cast shadows
 * together, each light's share 1 / (their count) of it
 * (tgi_shadow_light_budget). */
#define TG_SHADOW_MAP_BYTES_PER_PIXEL 8

/* One shadowed light's share of the maps' budget for an image of `pixels`
 * pixels and `lights` shadowed lights (<= 1: the whole budget);
 * (size_t)-1 when the budget is past size_t. */
size_t tgi_shadow_light_budget(size_t pixels, int lights);

/* The choice for one light, measured (README "Shadows"): a shadow ray
 * against the BVH costs 1.3-6 times the instructions of a PCF lookup per
 * pixel and frame (900 on 4 triangles, 1800 on 32, 2500-2900 on 300-2300;
 * the 4-tap lookup 250-400), while a static scene's maps are rendered
 * once; so maps, unless they take more than the light's share of the
 * budget (tgi_shadow_light_budget: 64 point lights' maps took 35 MB at
 * 320x240 when each light had the whole budget) and the BVH (shared by
 * every light that uses rays) takes fewer bytes than they do.  map_bytes
 * from tgi_shadow_need_bytes, bvh_bytes from tgi_bvh_bytes(triangles),
 * lights the count of shadowed lights. */
int tgi_shadow_choose(size_t map_bytes, size_t bvh_bytes, size_t pixels, int lights);

/* A map serves a receiver coarsely where one of its texels spans more
 * than TG_SHADOW_COARSE x TG_SHADOW_COARSE image pixels of it; when more
 * than 1 / TG_SHADOW_COARSE_SHARE of the receivers' image area is served
 * so (a ground plane far past the objects under one map: README
 * "Shadows"), the plan's auto choice takes shadow rays instead, if the BVH
 * is the smaller. */
#define TG_SHADOW_COARSE 4
#define TG_SHADOW_COARSE_SHARE 4

/* 1 when the finished need nd's maps serve the receivers view sees (the
 * rule's: lit, seen, tri_pos[0 .. 3 tri_count)) coarsely on more than 1 /
 * TG_SHADOW_COARSE_SHARE of their image area on some face, each measured
 * in the view's depth slabs of ratio 2. */
int tgi_shadow_map_coarse(const tgi_shadow_need *nd, const tgi_light *l, const tgi_view *view,
                          tg_vec3 lo, tg_vec3 hi, const tg_vec3 *tri_pos, int tri_count);

/* ---- the plan ---- */

/* Views the plan gives the rule: every frame's camera up to this many;
 * beyond, this many spread over the frames and every face whole. */
#define TG_SHADOW_PLAN_VIEWS 16

/* The plan raises the rule's densities by up to this factor while the maps
 * stay within their light's share of the budget (tgi_shadow_light_budget). */
#define TG_SHADOW_RULE_GAIN 2

/* Light `light`'s shadows for request r (defaults resolved): how
 * (TG_SHADOW_BY_MAP or BY_RAYS: r->shadow_method, else tgi_shadow_choose
 * with bvh_bytes, 0 when a BVH is paid for anyway), and for maps the
 * finished need and the bounds to set the map up with.  The rule sees
 * every frame's camera by the keys; the program's cameras (game loop), a
 * technique that looks shadows up where the camera does not see (the
 * reference) or more than TG_SHADOW_PLAN_VIEWS views make every face whole
 * (tgi_shadow_need_all) at the rule's density. */
#if TG_NO_SHADOW_MAPS
/* (no shadow maps in this build: tg_plan_make refuses the shadows effect) */
static inline int tgi_shadow_plan(const tg_scene *s, const tg_request *r, int light, size_t bvh_bytes,
                                  tgi_shadow_need *nd, tg_vec3 *lo, tg_vec3 *hi)
{
    (void)r; (void)light; (void)bvh_bytes;
    memset(nd, 0, sizeof *nd);
    *lo = s->bounds_min; *hi = s->bounds_max;
    return TG_SHADOW_BY_MAP;
}
#else
int tgi_shadow_plan(const tg_scene *s, const tg_request *r, int light, size_t bvh_bytes,
                    tgi_shadow_need *nd, tg_vec3 *lo, tg_vec3 *hi);
#endif

/* The plan's shadows for tg_plan_explain: per shadowed light, rays or
 * each face's size ("absent" for a culled face) and the bytes (bvh_bytes
 * as tgi_shadow_plan's). */
struct tgi_text;
#if TG_NO_SHADOW_MAPS
static inline void tgi_shadow_explain(struct tgi_text *t, const tg_scene *s, const tg_request *r, size_t bvh_bytes)
{
    (void)t; (void)s; (void)r; (void)bvh_bytes;
}
#else
void tgi_shadow_explain(struct tgi_text *t, const tg_scene *s, const tg_request *r, size_t bvh_bytes);
#endif

#endif
