/* SPDX-License-Identifier: MIT */
/*
 * view.h - the camera of one frame: world <-> view <-> screen.
 *
 * View space: x right, y up, z forward (into the screen); visible points have
 * z > 0 and "depth" is that z.  The projection keeps w = z, so clip space is
 *   clip = (x * focal_x, y * focal_y, -, z)
 * with focal_y = 1 / tan(fov_y / 2) and focal_x = focal_y / aspect; NDC is
 * clip / w in [-1, 1]; screen pixel coordinates are
 *   sx = (ndc_x + 1) / 2 * width,  sy = (1 - ndc_y) / 2 * height
 * so (0,0) is the top-left corner and pixel centres sit at +0.5.
 */
#ifndef TG_VIEW_H
#define TG_VIEW_H

#include "../core/vec.h"

typedef struct tgi_view {
    int width, height;
    tg_vec3 eye;
    tg_vec3 right, up, forward;  /* world-space unit basis of view space */
    tg_real fov_y;               /* radians */
    tg_real tan_half_fov_y;
    tg_real aspect;              /* width / height */
    tg_real focal_x, focal_y;    /* NDC per unit of x/z, y/z */
    tg_real pixels_per_unit;     /* height / 2 * focal_y: screen pixels per world unit at depth 1 */
    tg_real znear, zfar;
} tgi_view;

/* Build a view; a degenerate `up` (parallel to the view direction) is replaced
 * by a perpendicular axis so a camera looking along +/-Y still works. */
void tgi_view_make(tgi_view *v, tg_vec3 eye, tg_vec3 target, tg_vec3 up,
                  tg_real fov_y, tg_real znear, tg_real zfar, int width, int height);
tg_vec3 tgi_view_world_to_view(const tgi_view *v, tg_vec3 p);   /* point */
tg_vec3 tgi_view_dir_to_view(const tgi_view *v, tg_vec3 d);     /* direction */
tg_vec3 tgi_view_dir_to_world(const tgi_view *v, tg_vec3 d);    /* direction */
tg_vec3 tgi_view_view_to_world(const tgi_view *v, tg_vec3 p);   /* point */
/* Screen position (sx, sy in pixels, continuous) and depth to a view-space point. */
tg_vec3 tgi_view_unproject(const tgi_view *v, tg_real sx, tg_real sy, tg_real depth);
/* View-space point (z > 0) to continuous screen position. */
void tgi_view_project(const tgi_view *v, tg_vec3 pv, tg_real *sx, tg_real *sy);

/* The same maps inline, for the per-pixel loops that reproject (motion.h):
 * the functions above are these, so both give the same bits. */
#define TGI_VIEW_MIN_DEPTH TG_R(0.0000152587890625f)   /* smallest depth project() divides by */
/* a * b / c with one rounding (c > 0); fixed point: the product in 64 bits. */
static inline tg_real tgi_view_mul_div(tg_real a, tg_real b, tg_real c)
{
#if TG_FIXED
    int64_t p = (int64_t)a * b, h = c / 2;
    return tgi_sat64(p >= 0 ? (p + h) / c : -((-p + h) / c));
#else
    return tg_clamp(a * b / c, TG_REAL_MIN, TG_REAL_MAX);
#endif
}
static inline tg_vec3 tgi_view_dir_to_view_inline(const tgi_view *v, tg_vec3 d)
{
    return tg_v3(tgi_v3_dot(d, v->right), tgi_v3_dot(d, v->up), tgi_v3_dot(d, v->forward));
}
static inline tg_vec3 tgi_view_world_to_view_inline(const tgi_view *v, tg_vec3 p)
{
    return tgi_view_dir_to_view_inline(v, tgi_v3_sub(p, v->eye));
}
static inline tg_vec3 tgi_view_dir_to_world_inline(const tgi_view *v, tg_vec3 d)
{
    tg_vec3 r;
    r.x = tgi_v3_dot(tg_v3(v->right.x, v->up.x, v->forward.x), d);
    r.y = tgi_v3_dot(tg_v3(v->right.y, v->up.y, v->forward.y), d);
    r.z = tgi_v3_dot(tg_v3(v->right.z, v->up.z, v->forward.z), d);
    return r;
}
static inline tg_vec3 tgi_view_view_to_world_inline(const tgi_view *v, tg_vec3 p)
{
    return tgi_v3_add(v->eye, tgi_view_dir_to_world_inline(v, p));
}
static inline tg_vec3 tgi_view_unproject_inline(const tgi_view *v, tg_real sx, tg_real sy, tg_real depth)
{
    tg_real cx = tg_ldexp(tg_from_int(v->width), -1), cy = tg_ldexp(tg_from_int(v->height), -1);
    return tg_v3(tgi_view_mul_div(tg_sub(sx, cx), depth, v->pixels_per_unit),
                 tgi_view_mul_div(tg_sub(cy, sy), depth, v->pixels_per_unit), depth);
}
static inline void tgi_view_project_inline(const tgi_view *v, tg_vec3 pv, tg_real *sx, tg_real *sy)
{
    tg_real z = tg_max(pv.z, TGI_VIEW_MIN_DEPTH);
    tg_real cx = tg_ldexp(tg_from_int(v->width), -1), cy = tg_ldexp(tg_from_int(v->height), -1);
    *sx = tg_add(cx, tgi_view_mul_div(pv.x, v->pixels_per_unit, z));
    *sy = tg_sub(cy, tgi_view_mul_div(pv.y, v->pixels_per_unit, z));
}

#endif
