/* SPDX-License-Identifier: MIT */
/*
 * anim.h - keyframe animation (camera_key, object_key): camera and object
 * poses at a time t, posed triangles, and the per-object deltas from which
 * raster/motion.h makes motion vectors.  The keys are one producer of a
 * frame's camera and poses, the program (the game loop) the other; the
 * frame's camera pass (frame/camera.c) chooses between them.
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
 *            An object without keys stays in its rest pose; one with a
 *            single key stands at it.
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
/* The rigid delta taking pose `cur` to pose `prev`: prev = D cur. */
void tgi_anim_delta(const tgi_mat4 *cur, const tgi_mat4 *prev, tgi_mat4 *d);
/* A key's transform p' = R(axis, angle) p + translate (axis unit). */
tgi_mat4 tgi_anim_key_matrix(tg_vec3 translate, tg_vec3 axis, tg_real angle);
/* 1 when anything moves between frames (two or more camera keys or object keys). */
int tgi_anim_has_motion(const tg_scene *s);
/* 1 when the object has two or more keys (it moves). */
int tgi_anim_object_moves(const tg_scene *s, int object);
/* 1 when some object has keys: its triangles are posed, not at rest. */
int tgi_anim_has_posed_objects(const tg_scene *s);
/* Posed copies of all triangles: 3 positions and 3 unit normals per triangle. */
void tgi_anim_pose(const tg_scene *s, tg_real t, tg_vec3 *pos, tg_vec3 *nrm);
/* Object `object`'s triangles moved by the rigid pose m into pos and nrm
 * (the arrays of all triangles; the others are left as they are). */
void tgi_anim_pose_object(const tg_scene *s, int object, const tgi_mat4 *m, tg_vec3 *pos, tg_vec3 *nrm);

/* Bounds of tri_count posed triangles (3 positions each), e.g. to refit a
 * shadow map (tgi_shadow_map_setup) when objects move outside the rest-pose
 * scene bounds.  No triangles: lo = hi = 0. */
void tgi_anim_bounds(const tg_vec3 *pos, int tri_count, tg_vec3 *lo, tg_vec3 *hi);

#endif
