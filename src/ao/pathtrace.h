/* SPDX-License-Identifier: MIT */
/*
 * pathtrace.h - the multi-bounce ground truth: unbiased diffuse path tracing
 * of the scene's triangles (a BVH, src/ao/bvh.h), for every technique's
 * colour to be measured against.
 *
 * Light transport (RTR ch. 11, the rendering equation for Lambertian
 * surfaces, HBIL eq. 13-14):
 *   Lo(x) = Le(x) + rho(x) / pi * E(x),  rho = albedo * (1 - F0)
 * (the diffuse reflectance tinygi's compose uses, so both render the same
 * materials), E estimated by
 *   - next-event estimation (shadow rays, no shadow maps) of every point,
 *     spot and directional light: tgi_direct_irradiance (direct.h, the same
 *     falloff and spot edge) times the BVH's visibility;
 *   - next-event estimation of emissive triangles: one emitter per vertex,
 *     picked with probability proportional to area * emitted luminance, a
 *     uniform point on it, L_e cos cos' / d^2 / pdf; emitters radiate from
 *     both faces;
 *   - one cosine-distributed continuation ray (Malley's method, RTR
 *     sec. 11.3.4; f cos / pdf = rho): escaping, it brings the environment
 *     (tgi_env_radiance); hitting a surface, that surface's reflected light.
 *     Its emission is NOT added there: it was counted by the emitter's
 *     next-event estimate, so every light path is counted exactly once
 *     (unbiased, no MIS weights needed).
 * Bounces: `bounces` = N indirect reflections, as in Cycles' "max bounces":
 * N = 0 is direct light (lights, emitters and the environment reaching the
 * surface); N reflections of it are added for N > 0.  Russian roulette from
 * vertex `rr_start` on (survival = the path's largest channel weight, at
 * least 1/16) keeps the estimate unbiased for paths of any length up to N.
 *
 * Primary hits come from the G-buffer (position reconstructed from depth
 * as direct.c does, normal, albedo, F0, emission), so the reference shades
 * exactly the pixels the rasterizer drew (no silhouette mismatch); rays
 * leave a G-buffer point lifted along its normal by its position error
 * bound (tgi_shadow_gbuffer_error).  Sky pixels get the environment.
 *
 * Samples: `samples` paths per pixel (default TG_DEFAULT_PATHTRACE_SAMPLES,
 * src/tinygi.h).
 * Random numbers: PCG32 (O'Neill 2014) seeded by (seed, pixel index, sample
 * index) only, so any split of the rows gives the same image.
 *
 * Number types: float is the reference.  Q16.16 runs the same code (tests
 * check it on the analytic cases at looser tolerances); its emitter pdf has
 * 16-bit steps, so emitters under ~2^-16 of the scene's emitted power are
 * sampled coarsely, and radiance saturates at TG_REAL_MAX.
 */
#ifndef TG_PATHTRACE_H
#define TG_PATHTRACE_H

#include "../scene/scene.h"
#include "../raster/gview.h"
#include "../raster/view.h"
#include "bvh.h"

/* One emissive triangle in the next-event table. */
typedef struct tgi_pt_emitter {
    int32_t tri;
    uint32_t start;             /* selection: u32 in [start, next start) picks it */
    tg_real area_over_pdf;      /* area / selection probability */
} tgi_pt_emitter;

typedef struct tgi_pathtrace_params {
    const tgi_bvh *bvh;                 /* over the scene's triangles (bvh->tri_pos) */
    const tg_vec3 *tri_nrm;             /* 3 unit vertex normals per triangle; NULL = face normals */
    const uint16_t *tri_material;       /* per triangle */
    const tgi_material *materials;
    const tgi_light *lights;
    int light_count;
    const tgi_env *env;                 /* NULL = black */
    const tgi_pt_emitter *emitters;     /* tgi_pathtrace_emitters; NULL when none */
    int emitter_count;
    int samples;                        /* paths per pixel, >= 1 */
    int bounces;                        /* N >= 0 (see above) */
    int rr_start;                       /* Russian roulette from this vertex on; > bounces = never */
    uint32_t seed;
} tgi_pathtrace_params;

typedef struct tgi_pathtrace_io {
    const tgi_gbuffer *gb;              /* primary hits */
    const tgi_view *view;
    tg_real *out_r, *out_g, *out_b;     /* Lo per pixel (emission included; sky: the environment) */
    tg_real *irr_r, *irr_g, *irr_b;     /* E per pixel (sky: 0), NULL when not wanted */
    const tgi_rgb *color, *irradiance;  /* instead of the planes when not NULL (a frame's
                                           storage): Lo and E; an absent one is not written */
} tgi_pathtrace_io;

/* Defaults: TG_DEFAULT_PATHTRACE_SAMPLES samples, 1 bounce, no roulette,
 * seed 1; the scene pointers NULL. */
void tgi_pathtrace_defaults(tgi_pathtrace_params *p);

/* Emissive triangles: how many (for the table's size). */
int tgi_pathtrace_emitter_count(const uint16_t *tri_material, const tgi_material *materials, int tri_count);

/* Bytes of a table of `count` emitters (0 for a negative count or an
 * overflow). */
size_t tgi_pathtrace_emitter_bytes(int count);

/* Fill `out` (tgi_pathtrace_emitter_count entries) for the triangles at
 * tri_pos.  Returns the count written. */
int tgi_pathtrace_emitters(tgi_pt_emitter *out, const tg_vec3 *tri_pos, const uint16_t *tri_material,
                           const tgi_material *materials, int tri_count);

/* Rows [y0, y1) of io. */
void tgi_pathtrace_rows(const tgi_pathtrace_params *p, const tgi_pathtrace_io *io, int y0, int y1);

#endif
