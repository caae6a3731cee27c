/* SPDX-License-Identifier: MIT */
/*
 * motion.h - per-pixel motion vectors for reprojection.
 *
 * motion_x/y (gbuffer.h) = the continuous screen position in the PREVIOUS
 * frame of the surface seen at this pixel's centre now: the pixel is
 * unprojected with the current view (view.h), moved by its object's rigid
 * delta (scene/anim.h makes those from the keys) and projected with the
 * previous view.
 */
#ifndef TG_MOTION_H
#define TG_MOTION_H

#include "gbuffer.h"
#include "view.h"

/* Screen position written for a surface that was behind the previous camera. */
#define TG_MOTION_INVALID TG_REAL_MIN

/* Motion vectors for rows [y0, y1) into gb->motion_x/y.  cur_to_prev: one
 * world-space rigid delta per object (indexed by gb->object), or NULL when
 * nothing but the camera moves.  Sky pixels reproject their view direction
 * (a point at infinity).  A surface behind the previous camera gets
 * TG_MOTION_INVALID in both. */
/* Where the surface at the centre of pixel (x, y) of `cur`, at view depth
 * `depth`, was on the screen of `prev` (*px, *py, continuous pixels; its
 * previous view depth *prev_z), moved by its object's delta (NULL: it does
 * not move).  0 when it was behind the previous camera. */
int tgi_motion_prev_position(const tgi_view *cur, const tgi_view *prev, const tgi_mat4 *delta,
                             int x, int y, tg_real depth, tg_real *px, tg_real *py, tg_real *prev_z);

/* The same inline, for the per-pixel loops of reprojection and temporal
 * accumulation (src/gi/reproject.c, src/gi/temporal.c): the same bits. */
static inline int tgi_motion_prev_position_inline(const tgi_view *cur, const tgi_view *prev, const tgi_mat4 *delta,
                                                  int x, int y, tg_real depth, tg_real *px, tg_real *py,
                                                  tg_real *prev_z)
{
    tg_real sx = tg_add(tg_from_int(x), TG_R(0.5f)), sy = tg_add(tg_from_int(y), TG_R(0.5f));
    tg_vec3 p = tgi_view_view_to_world_inline(cur, tgi_view_unproject_inline(cur, sx, sy, depth)), pv;
    if (delta) p = tgi_m4_point(delta, p);
    pv = tgi_view_world_to_view_inline(prev, p);
    *prev_z = pv.z;
    if (pv.z <= TG_R(0.0001f)) return 0;
    tgi_view_project_inline(prev, pv, px, py);
    return 1;
}

void tgi_motion_rows(tgi_gbuffer *gb, const tgi_view *cur, const tgi_view *prev,
                    const tgi_mat4 *cur_to_prev, int y0, int y1);

#endif
