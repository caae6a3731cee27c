/* SPDX-License-Identifier: MIT */
/*
 * reference.h - the ray-traced ground truth every screen-space technique is
 * measured against.  From each G-buffer position it casts deterministic
 * stratified cosine-weighted rays (Malley's method, RTR sec. 11.3.4) into a
 * BVH of the real scene triangles and writes
 *   ao    RTR eq. 11.8, with the visibility cut off at `radius` (obscurance
 *         with a step distance mapping, RTR sec. 11.3.2 / eq. 11.11): a ray
 *         is blocked only by a hit closer than the radius; TG_AO_INFINITE
 *         gives true ambient occlusion;
 *   bent  RTR eq. 11.10, the mean unoccluded direction (cosine-weighted by
 *         the sampling itself), normalised; the normal when all are blocked;
 *   near  one-bounce near-field irradiance E = int L_o(hit) cos dw over the
 *         blocked directions (estimator pi / N * sum L_o), L_o being the
 *         direct-light outgoing diffuse radiance at the hit point.
 * L_o at a hit comes from, in order of preference:
 *   1. the `radiance` callback (exact: the frame evaluates direct light at
 *      any point; the reference is slow on purpose, so a call per hit is
 *      acceptable here and nowhere else);
 *   2. else the `radiance` planes, looked up by projecting the hit into the
 *      current view, when the hit is the surface the camera sees there
 *      (depth within 1% + 2^-8); hidden hits then give 0, so this is the
 *      screen-visible part of the bounce - exactly what a screen-space
 *      gatherer can know, and a lower bound of the true value;
 *   3. no near output when the results have no near field.
 * cone  alpha = acos(sqrt(1 - ao)), the cone whose cosine-weighted AO is
 *       ao (tgi_cone_angle_from_ao, src/light/sh.h; not HBIL eq. 12's
 *       acos(1 - ao), see the deviation there), as every technique's cone
 *       AOV reads it, so the bench compares like with like.
 */
#ifndef TG_REFERENCE_H
#define TG_REFERENCE_H

#include "ao.h"
#include "bvh.h"

/* Outgoing diffuse radiance leaving triangle `tri` at world point `pos`
 * with unit normal `nrm` (facing the ray's origin). */
typedef tg_vec3 (*tgi_reference_radiance_fn)(void *user, int tri, tg_vec3 pos, tg_vec3 nrm);

typedef struct tgi_reference_params {
    const tgi_bvh *bvh;             /* over the scene's tri_pos */
    const tg_vec3 *tri_nrm;        /* 3 unit vertex normals per triangle; NULL = face normals */
    int samples;                   /* rays per pixel (default 256) */
    tg_real radius;                /* cut-off distance, world units; TG_AO_INFINITE = none (default 1) */
    tgi_reference_radiance_fn radiance; /* NULL: look up `radiance` (see above) */
    void *user;
} tgi_reference_params;

void tgi_reference_defaults(tgi_reference_params *p);

/* Rows [y0, y1) of the view g (ao; bent, cone and near when out has them). */
void tgi_reference_rows(const tgi_reference_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                    const tgi_gresult *out, int y0, int y1);

#endif
