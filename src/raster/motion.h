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
void tgi_motion_rows(tgi_gbuffer *gb, const tgi_view *cur, const tgi_view *prev,
                    const tgi_mat4 *cur_to_prev, int y0, int y1);

#endif
