/* SPDX-License-Identifier: MIT */
/*
 * bvh.h - a bounding-volume hierarchy over the scene's triangles, for the
 * ray-traced AO reference (reference.c).  Built into caller memory (no
 * allocation), deterministic (median split on the longest centroid axis,
 * ties broken by triangle index), traversed iteratively with a fixed stack
 * (a median split is balanced, so the depth is at most log2(n) + 2 and the
 * 64-entry stack can never overflow for any int triangle count).
 *
 * Ray math is in tg_real with care for Q16.16: the triangle test works in
 * coordinates relative to the triangle, scaled by a power of two so every
 * product stays in range (see bvh.c).
 */
#ifndef TG_BVH_H
#define TG_BVH_H

#include "../core/vec.h"
#include "../scene/scene.h"

#define TG_BVH_LEAF_MAX 4      /* triangles per leaf */
#define TG_BVH_STACK 64

typedef struct tgi_bvh_node {
    tg_vec3 lo, hi;            /* bounds, slightly enlarged (conservative) */
    int32_t first;             /* leaf: first slot in tri_index; inner: left child (right = first + 1) */
    int32_t count;             /* leaf: triangles (> 0); inner: 0 */
} tgi_bvh_node;

/* A triangle prepared for the traversal's test (plane, then barycentrics
 * by dual edge vectors, Moller-Trumbore's values without its per-ray cross
 * products).  Edges are scaled by 2^k into [2, 4) before the duals are
 * formed, so Q16.16 keeps its precision for tiny and huge triangles alike. */
typedef struct tgi_bvh_tri {
    tg_vec3 v0;                /* vertex 0 */
    tg_vec3 n;                 /* unit plane normal; (0,0,0) for a degenerate triangle */
    tg_vec3 a, b;              /* duals of the scaled edges: u = a . h', v = b . h', h' = 2^k (h - v0) */
    int32_t k;                 /* the edge scale exponent */
} tgi_bvh_tri;

typedef struct tgi_bvh {
    int tri_count, node_count;
    const tg_vec3 *tri_pos;    /* 3 per triangle, the caller's (not copied) */
    tgi_bvh_node *nodes;        /* node 0 is the root */
    int32_t *tri_index;        /* leaf slots -> triangle index */
    tgi_bvh_tri *tris;          /* prepared triangles, in leaf-slot order */
} tgi_bvh;

typedef struct tgi_ray_hit {
    tg_real t;                 /* distance along the (unit) direction */
    tg_real u, v;              /* barycentrics of vertices 1 and 2 */
    int tri;                   /* triangle index, -1 when none */
} tgi_ray_hit;

/* Bytes tgi_bvh_build needs for tri_count triangles (0 when the count is
 * negative or the size overflows). */
size_t tgi_bvh_bytes(int tri_count);   /* SIZE_MAX when that does not fit */

/* Build over tri_pos[3 * tri_count] in `memory` (size >= tgi_bvh_bytes).
 * Returns 0, or -1 if the memory is too small or the count is negative. */
int tgi_bvh_build(tgi_bvh *bvh, const tg_vec3 *tri_pos, int tri_count, void *memory, size_t size);

/* Closest hit along o + t d with 0 < t < tmax (d unit).  Returns 1 on a hit. */
int tgi_bvh_closest(const tgi_bvh *bvh, tg_vec3 o, tg_vec3 d, tg_real tmax, tgi_ray_hit *hit);

/* Any hit with 0 < t < tmax: 1 if the segment is blocked. */
int tgi_bvh_occluded(const tgi_bvh *bvh, tg_vec3 o, tg_vec3 d, tg_real tmax);

/* Shadow ray for light l from receiver p (unit normal n facing the light,
 * position error bound err): 1 when nothing blocks the segment to the light
 * (a point or spot) or the ray toward it (directional), else 0 - hard
 * shadows.  The ray starts at p + n (err + e + 8 ulps), e = 2^-14 of the
 * scene's extent in Q16.16 and 2^-19 of |p|_1 in float (the plane tests'
 * precision), and stops
 * that much short of a point light.  `bvh` is a const tgi_bvh * (the shape
 * of tgi_shadow_ray_fn in light/shadowmap.h). */
tg_real tgi_bvh_light_visibility(const void *bvh, const tgi_light *l, tg_vec3 p, tg_vec3 n, tg_real err);

/* One ray against one prepared triangle: 1 on a hit with 0 < t < tmax,
 * filling t and the barycentrics u, w of vertices 1 and 2. */
int tgi_bvh_tri_hit(const tgi_bvh_tri *tr, tg_vec3 o, tg_vec3 d, tg_real tmax,
                   tg_real *t, tg_real *u, tg_real *w);

/* Prepare a triangle (v: its 3 vertices) for tgi_bvh_tri_hit. */
void tgi_bvh_tri_prepare(tgi_bvh_tri *tr, const tg_vec3 *v);

/* One ray against one triangle (v: its 3 vertices), Moller-Trumbore in
 * scaled relative coordinates; 1 on a hit with 0 < t < tmax, filling t, u,
 * v.  The independent check of tgi_bvh_tri_hit in the tests. */
int tgi_ray_triangle(const tg_vec3 *v, tg_vec3 o, tg_vec3 d, tg_real tmax,
                    tg_real *t, tg_real *u, tg_real *w);

#endif
