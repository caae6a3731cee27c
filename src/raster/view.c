/* SPDX-License-Identifier: MIT */
/*
 * view.c - the camera of one frame: its orthonormal basis, projection and
 * the maps world <-> view <-> screen (conventions in view.h: view x right,
 * y up, z forward; depth = view z; screen (0,0) top-left, pixel centres at
 * +0.5, square pixels).
 *
 * With square pixels both screen axes share one scale,
 *   pixels_per_unit = height / 2 * focal_y = height / (2 tan(fov_y / 2)),
 * so   sx = width / 2 + ppu x / z,   sy = height / 2 - ppu y / z
 * and unproject is the exact inverse.  In fixed point the products x * ppu
 * and (sx - w/2) * z are formed in 64 bits before the one division.
 */
#include "view.h"

/* Below this sine of the angle between `up` and the view direction the up
 * vector is treated as degenerate. */
#define VIEW_DEGENERATE_UP TG_R(0.0009765625f)
/* The up vector actually used: `up` unless (nearly) parallel to `forward`,
 * then world +Y, and when forward itself is (nearly) vertical the limit of
 * tilting a level camera: -Z looking down, +Z looking up.  This choice
 * gives screen-right = world +X for a camera looking straight down or up. */
static tg_vec3 choose_up(tg_vec3 forward, tg_vec3 up)
{
    tg_vec3 u = tgi_v3_normalize(up);
    if (tgi_v3_length(tgi_v3_cross(forward, u)) > VIEW_DEGENERATE_UP) return u;
    u = tg_v3(0, TG_ONE, 0);
    if (tgi_v3_length(tgi_v3_cross(forward, u)) > VIEW_DEGENERATE_UP) return u;
    return tg_v3(0, 0, forward.y < 0 ? tg_neg(TG_ONE) : TG_ONE);
}

/* normalize(a x b).  Fixed point forms the cross product exactly in 64
 * bits first: for nearly parallel a, b the Q16.16 cross product would
 * keep only a few significant bits. */
static tg_vec3 cross_dir(tg_vec3 a, tg_vec3 b)
{
#if TG_FIXED
    int64_t c[3], m = 0;
    int i, s = 0;
    c[0] = (int64_t)a.y * b.z - (int64_t)a.z * b.y; /* |a|, |b| <= 1: no overflow */
    c[1] = (int64_t)a.z * b.x - (int64_t)a.x * b.z;
    c[2] = (int64_t)a.x * b.y - (int64_t)a.y * b.x;
    for (i = 0; i < 3; i++) if ((c[i] < 0 ? -c[i] : c[i]) > m) m = c[i] < 0 ? -c[i] : c[i];
    while ((m >> s) >= ((int64_t)1 << 30)) s++;
    if (s > 0) for (i = 0; i < 3; i++) c[i] = tgi_shr_round(c[i], s);
    return tgi_v3_normalize(tg_v3((tg_real)c[0], (tg_real)c[1], (tg_real)c[2]));
#else
    return tgi_v3_normalize(tgi_v3_cross(a, b));
#endif
}

void tgi_view_make(tgi_view *v, tg_vec3 eye, tg_vec3 target, tg_vec3 up,
                  tg_real fov_y, tg_real znear, tg_real zfar, int width, int height)
{
    tg_vec3 f = tgi_v3_normalize_or(tgi_v3_sub(target, eye), tg_v3(0, 0, tg_neg(TG_ONE)));
    tg_vec3 r = cross_dir(f, choose_up(f, up));
    /* re-orthogonalise with well-conditioned products of near-perpendicular
     * unit vectors: up from (right, forward), then right from (forward, up) */
    tg_vec3 u = tgi_v3_normalize(tgi_v3_cross(r, f));
    r = tgi_v3_normalize(tgi_v3_cross(f, u));
    if (width < 1) width = 1;
    if (height < 1) height = 1;
    v->width = width;
    v->height = height;
    v->eye = eye;
    v->forward = f;
    v->right = r;
    v->up = u;
    v->fov_y = tg_clamp(fov_y, TG_R(0.001f), TG_R(3.1f));
    v->tan_half_fov_y = tg_tan(tg_ldexp(v->fov_y, -1));
    v->aspect = tg_ratio(width, height);
    v->focal_y = tg_div(TG_ONE, v->tan_half_fov_y);
    v->focal_x = tg_div(v->focal_y, v->aspect);
    v->pixels_per_unit = tg_mul(tg_ldexp(tg_from_int(height), -1), v->focal_y);
    v->znear = znear;
    v->zfar = zfar;
}

tg_vec3 tgi_view_dir_to_view(const tgi_view *v, tg_vec3 d) { return tgi_view_dir_to_view_inline(v, d); }

tg_vec3 tgi_view_world_to_view(const tgi_view *v, tg_vec3 p) { return tgi_view_world_to_view_inline(v, p); }

tg_vec3 tgi_view_dir_to_world(const tgi_view *v, tg_vec3 d) { return tgi_view_dir_to_world_inline(v, d); }
tg_vec3 tgi_view_view_to_world(const tgi_view *v, tg_vec3 p) { return tgi_view_view_to_world_inline(v, p); }

tg_vec3 tgi_view_unproject(const tgi_view *v, tg_real sx, tg_real sy, tg_real depth)
{
    return tgi_view_unproject_inline(v, sx, sy, depth);
}

void tgi_view_project(const tgi_view *v, tg_vec3 pv, tg_real *sx, tg_real *sy) { tgi_view_project_inline(v, pv, sx, sy); }
