/* SPDX-License-Identifier: MIT */
/*
 * frame_internal.h - what a frame holds.  plan.c decides which of these
 * exist (and sizes them); frame.c runs the passes over them; aov.c reads
 * them out.  A NULL buffer is an effect the scene did not call for.
 */
#ifndef TG_FRAME_INTERNAL_H
#define TG_FRAME_INTERNAL_H

#include "../tinygi.h"
#include "../scene/scene.h"
#include "../raster/gbuffer.h"
#include "../raster/view.h"
#include "../light/shadowmap.h"
#include "../ao/ao.h"
#include "../ao/bvh.h"

/* What the frame computes beyond the effects (internal). */
enum {
    TG_NEED_GI_PASS = 1u << 0,   /* a technique pass (AO and friends) runs */
    TG_NEED_COMPOSE = 1u << 1,   /* outgoing radiance Lo (colour) */
    TG_NEED_MOTION = 1u << 2,    /* motion vectors in the G-buffer */
    TG_NEED_POSE = 1u << 3,      /* objects move: posed triangle copies */
    TG_NEED_TEMPORAL = 1u << 4,  /* temporal accumulation of the GI result */
    TG_NEED_BENT = 1u << 5,      /* bent normals are used */
    TG_NEED_CONE = 1u << 6       /* cone apertures are used */
};

typedef struct tgi_rgb { tg_real *r, *g, *b; } tgi_rgb;

struct tg_frame {
    tg_plan plan;
    const tg_scene *scene;
    int width, height;
    size_t pixels;
    uint32_t effects, needs;
    int frames_rendered;

    tgi_gbuffer gb;
    tgi_view view, prev_view;
    tg_real time, prev_time;
    int has_history;              /* the previous frame's radiance is valid */

    /* animation */
    tg_vec3 *posed_pos, *posed_nrm;
    tgi_mat4 *object_delta;        /* per object, current pose -> previous pose */

    /* light */
    tgi_shadow_map *shadow_maps;   /* one per light (unused entries zero) */
    const tgi_shadow_map **shadow_ptrs;
    int shadows_valid;
    tg_vec3 sh[9];
    tgi_rgb direct, far, near, color, irradiance;

    /* GI / AO results, full resolution */
    tg_real *ao, *cone;
    tgi_rgb bent;
    tgi_rgb source;                /* radiance the near field gathers from */

    /* HBIL at quarter resolution: the G-buffer point-sampled to half width
     * and height, and the kernel's results there before upsampling */
    tg_real *half_depth, *half_f0, *half_ao;
    tgi_rgb half_normal, half_source, half_bent, half_near;
    uint8_t *half_sky;

    /* HBIL: 4x4 interleaved sub-images */
    tg_real *q_depth, *q_f0;
    tgi_rgb q_normal, q_source, q_bent, q_near;
    tg_real *q_ao, *q_cone;
    uint8_t *q_sky;

    /* radiance history for reprojection (previous frame) */
    tgi_rgb history;
    tg_real *history_depth;
    uint16_t *history_object;
    void *reproject_scratch;
    size_t reproject_scratch_bytes;

    /* spatial / temporal filter */
    void *denoise_scratch;
    size_t denoise_scratch_bytes;
    void *temporal_state;
    size_t temporal_state_bytes;

    /* technique scratch (reference BVH) */
    void *technique_scratch;
    size_t technique_scratch_bytes;
    tgi_bvh bvh;

    tg_real depth_max;            /* for the 8-bit depth view */
};

/* Lay the frame's buffers out: with arena == NULL only measure (fill
 * plan->buffers and plan->total_bytes, using *fp as scratch); otherwise carve
 * the frame itself and then its buffers from arena and set *fp.  Returns 0,
 * or 1 when the arena is too small. */
int tgi_frame_layout(tg_frame **fp, tg_plan *plan, tg_arena *arena);
/* request.c: 1 (and err set) when a field of r is past its limit; then
 * the unset GI settings from the scene or the defaults (1 when the
 * scene's are past a limit). */
int tgi_request_refused(const tg_request *r, tg_error *err);
int tgi_request_resolve(tg_request *r, const tg_scene *s, tg_error *err);
/* TG_NEED_* of a plan (plan.c). */
uint32_t tgi_frame_needs(const tg_plan *plan);

#endif
