/* SPDX-License-Identifier: MIT */
/*
 * anim.h - keyframe animation (camera_key, object_key): camera and object
 * poses at a time t, posed triangles, and the per-object deltas from which
 * raster/motion.h makes motion vectors.
 *
 * Time: frame i of N samples t linearly from the first key to the last
 * (over camera and object keys together); frame 0 is the first key, frame
 * N - 1 the last.  Before the first key / after the last, values hold.
 * Interpolation is exact AT the keys (a key's own values are returned).
 *   camera   pos and target linear.
 *   object   key transform p' = R p + T (rotation about the world origin,
 *            then translation).  T linear; R: when both keys rotate about
 *            the same axis the angle is interpolated linearly (so a turn of
 *            more than 180 degrees between two keys is kept), otherwise
 *            quaternion slerp along the shortest arc (tgi_q_slerp).
 *            An object without keys stays in its rest pose.
 */
#ifndef TG_ANIM_H
#define TG_ANIM_H

#include "scene.h"

tg_real tgi_anim_time(const tg_scene *s, int frame, int frames);
void tgi_anim_camera(const tg_scene *s, tg_real t, tg_vec3 *pos, tg_vec3 *target);
/* Key transform of `object` at t (identity without keys). */
void tgi_anim_object_matrix(const tg_scene *s, int object, tg_real t, tgi_mat4 *m);
/* World-space rigid delta taking the object's pose at t_cur to its pose at
 * t_prev: prev = D cur. */
void tgi_anim_object_delta(const tg_scene *s, int object, tg_real t_cur, tg_real t_prev, tgi_mat4 *d);
/* 1 when anything moves between frames (two or more camera keys or object keys). */
int tgi_anim_has_motion(const tg_scene *s);
/* 1 when the object has two or more keys (it moves). */
int tgi_anim_object_moves(const tg_scene *s, int object);
/* Posed copies of all triangles: 3 positions and 3 unit normals per triangle. */
void tgi_anim_pose(const tg_scene *s, tg_real t, tg_vec3 *pos, tg_vec3 *nrm);

/* Bounds of tri_count posed triangles (3 positions each), e.g. to refit a
 * shadow map (tgi_shadow_map_setup) when objects move outside the rest-pose
 * scene bounds.  No triangles: lo = hi = 0. */
void tgi_anim_bounds(const tg_vec3 *pos, int tri_count, tg_vec3 *lo, tg_vec3 *hi);

#endif
