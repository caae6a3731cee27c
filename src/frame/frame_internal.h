/* SPDX-License-Identifier: MIT */
/*
 * frame_internal.h - what a frame holds, and the pass table that says what
 * runs on it.
 *
 * A frame is a list of passes (passes.c): each row names the pass in the
 * papers' words, says when the plan needs it, which buffers it reads and
 * writes, and how it runs (over rows, or as one serial step).  plan.c walks
 * the table to decide the passes and buffers (layout.c sizes and carves
 * them), tg_plan_explain prints that same list, and tg_frame_render
 * (frame.c) runs it.  A NULL buffer is an effect the scene did not call for.
 */
#ifndef TG_FRAME_INTERNAL_H
#define TG_FRAME_INTERNAL_H

#include "../tinygi.h"
#include "../scene/scene.h"
#include "../raster/gview.h"
#include "../raster/raster.h"
#include "../light/shadowmap.h"
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

struct tg_frame {
    tg_request request;            /* the plan's, every default resolved */
    int pass_count;                /* the plan's passes: rows of the pass table */
    unsigned char pass_rows[TG_PLAN_MAX_PASSES];
    const tg_scene *scene;
    int width, height;
    size_t pixels;
    uint32_t effects, needs;
    int frames_rendered;
    int index;                     /* the frame being rendered */
    int bounce, bounces;           /* the kernel iteration running, of how many */
    int has_history;               /* the previous frame's radiance is valid */
    int band;                      /* rows per call of a row-parallel pass; 0: all at once */
    tg_parallel parallel;          /* the platform's row runner (run NULL: this thread) */

    tgi_view view, prev_view;
    tg_real time, prev_time;
    tgi_gbuffer gb;                /* what the rasterizer writes, full resolution */
    tgi_gview full;                /* the view every full-resolution pass reads */
    tgi_gview half_view;           /* the quarter-res copy's, with --gi-quarter */

    /* animation */
    tg_vec3 *posed_pos, *posed_nrm;
    tgi_mat4 *object_delta;        /* per object, current pose -> previous pose */

    /* the game loop (camera.c): what the program set, and the poses shown */
    struct tgi_drive {
        unsigned set;              /* TGI_SET_CAMERA, TGI_SET_TIME */
        int cut;                   /* tg_frame_cut: the next render drops the history */
        int reprojected;           /* tg_frame_reprojected of the last render */
        tg_vec3 pos, target, up;   /* the program's camera */
        tg_real fov, time;         /* its fov; the keys' time it set */
        tgi_mat4 *object_set;      /* per object, the program's pose (m[15] == 0: none) */
        tgi_mat4 *object_pose;     /* per object, the pose last rendered */
    } drive;
    uint64_t shadows_stale;        /* bit per light: fit and render its map again */

    /* light */
    tgi_shadow_map *shadow_maps;   /* one per light (unused entries zero) */
    const tgi_shadow_map **shadow_ptrs;
    int shadows_valid;
    tg_vec3 sh[9];

    /* Radiance planes.  Two slots alternate frame by frame (tgi_frame_begin):
     * with history, slot[t & 1] holds last frame's Lo until reprojection,
     * then push/pull's mips, then this frame's near field; slot[1 - (t & 1)]
     * holds last frame's accumulated near field until temporal accumulation,
     * then E_direct, then this frame's Lo, composed in place.  bounce_source holds
     * the reprojected radiance (or a bounce's Lo for the next bounce).  With
     * the kernel at quarter resolution its near field is there and Lo is
     * composed over the history itself.  A plane an AOV asks for is its own. */
    tgi_rgb slot[2], bounce_source;
    tgi_rgb direct, color;         /* this frame's roles (pointing into the slots) */
    tgi_rgb history;               /* last frame's Lo (reprojection reads it) */
    tgi_rgb source;                /* what the near field gathers on the first bounce */
    tgi_rgb far, irradiance;       /* own planes: their AOVs (or SSDO's, bent cones' far field) */
    int direct_own;                /* E_direct has its own plane (the direct AOV) */

    /* GI results at the kernel's resolution: this frame's (unfiltered, then
     * accumulated) and last frame's, alternating between two sets */
    tgi_gresult set[2], res, res_prev;
    /* with --gi-quarter: the same at half width and height, and the filtered ones */
    tgi_gbuffer half;              /* storage of the quarter-res copy */
    tgi_gresult half_set[2], half_res, half_prev, half_filtered;
    tgi_gresult near_horizon;      /* the full-res near horizons' AO (AO plane alone) the upsample caps with */
    tgi_rgb half_source;
    /* the filtered (or upsampled) results an AOV asks for, at full resolution */
    tgi_gresult out;

    /* last frame's geometry (reprojection, temporal accumulation) */
    tgi_prev_geometry prev_geometry;
    void *pushpull_mips;

    /* technique scratch (reference BVH; the path tracer's emissive triangles) */
    void *bvh_scratch;
    size_t bvh_scratch_bytes;
    tgi_bvh bvh;
    void *emitters;
    int emitter_count;

    tg_real depth_max;            /* for the 8-bit depth view */
};

/* ---- buffers: each group is carved once, by the first pass that uses it ---- */
enum tgi_buffer_group {
    TGI_BUF_POSE, TGI_BUF_GBUFFER, TGI_BUF_MOTION, TGI_BUF_SHADOW_MAPS, TGI_BUF_DIRECT,
    TGI_BUF_SOURCE, TGI_BUF_HISTORY, TGI_BUF_REPROJECT, TGI_BUF_RESULTS, TGI_BUF_HALF,
    TGI_BUF_FILTER, TGI_BUF_TEMPORAL, TGI_BUF_BVH, TGI_BUF_FAR,
    TGI_BUF_COLOR, TGI_BUF_IRRADIANCE,
    TGI_BUF_GROUPS
};
#define TGI_BUF(g) (1u << (g))
/* The AOVs of the AO kernel's results (no light). */
#define TGI_AO_AOVS ((1u << TG_AOV_AO) | (1u << TG_AOV_BENT) | (1u << TG_AOV_CONE))

/* ---- the pass table ---- */
enum tgi_pass_rows {
    TGI_SERIAL,         /* one whole-image step: run(f) */
    TGI_ROWS_IMAGE,     /* rows(f, y0, y1) over the image's rows */
    TGI_ROWS_KERNEL     /* rows(f, y0, y1) over the kernel image's rows (half with --gi-quarter) */
};
enum {
    TGI_ON_FIRST_FRAME = 1u << 0,  /* only on a frame without history (a cut, the first) */
    TGI_ON_HISTORY = 1u << 1,      /* only on a frame with last frame's radiance */
    TGI_BOUNCE = 1u << 2           /* in the bounce loop: run `bounces` times on a frame
                                      without history (the rows so marked are contiguous) */
};

/* A pass's function: over rows [y0, y1) (row-parallel: any split of the
 * rows gives the same output), or a whole-image step. */
typedef void tgi_pass_rows_fn(tg_frame *f, int y0, int y1);
typedef void tgi_pass_step_fn(tg_frame *f);

typedef struct tgi_pass {
    const char *name;                      /* what it computes, in the papers' words */
    int (*needed)(const tg_frame *f);      /* does the plan call for it (f->plan, effects, needs) */
    uint32_t buffers;                      /* TGI_BUF() of every group it reads or writes */
    uint32_t when;                         /* TGI_ON_* and TGI_BOUNCE flags */
    int rows;                              /* enum tgi_pass_rows */
    tgi_pass_rows_fn *run_rows;            /* TGI_ROWS_IMAGE, TGI_ROWS_KERNEL */
    tgi_pass_step_fn *run;                 /* TGI_SERIAL */
} tgi_pass;

/* The table (passes.c), in the order the passes run. */
extern const tgi_pass tgi_passes[];
extern const int tgi_pass_count;

/* Rows a pass runs over on this frame (0 for a serial step). */
int tgi_pass_row_count(const tg_frame *f, const tgi_pass *p);
/* fn(job, y0, y1) over [0, rows) through the platform's hook (frame.c): for
 * a serial pass with inner row loops (each loop one call; the calls run one
 * after the other).  Call it only from a serial pass, never from inside fn:
 * fn follows the contract of tg_parallel in tinygi.h. */
void tgi_frame_parallel_rows(tg_frame *f, tg_rows_fn fn, void *job, int rows);
/* Render frame `index` with each row-parallel pass in bands of `band` rows,
 * last band first (0: all rows in one call, as tg_frame_render does). */
tg_status tgi_frame_render_bands(tg_frame *f, int index, int band, tg_error *err);

/* Lay the frame's buffers out (layout.c): with arena == NULL only measure
 * (fill plan->passes, plan->buffers and plan->total_bytes, using *fp as
 * scratch); otherwise carve the frame itself and then its buffers from
 * arena and set *fp.  Returns 0, or 1 when the arena is too small. */
int tgi_frame_layout(tg_frame **fp, tg_plan *plan, tg_arena *arena);
/* request.c: 1 (and err set) when a field of r is past its limit; then
 * the unset GI settings from the scene or the defaults (1 when the
 * scene's are past a limit). */
int tgi_request_refused(const tg_request *r, tg_error *err);
int tgi_request_resolve(tg_request *r, const tg_scene *s, tg_error *err);
/* The game loop's copy of the scene (camera.c): the frame renders `own`, a
 * copy of its scene whose lights are `lights` (a copy of the scene's), so
 * the program may change lights and environment per frame. */
void tgi_frame_own_scene(tg_frame *f, tg_scene *own, tgi_light *lights);
/* The triangles as the rasterizer takes them: posed, or the scene's (rasterize.c). */
tgi_raster_mesh tgi_frame_mesh(const tg_frame *f);
/* TG_NEED_* of a plan (plan.c). */
uint32_t tgi_frame_needs(const tg_plan *plan);
/* The image the interleaved kernel splits, its results and source: the
 * full-resolution view, or with --gi-quarter the half-resolution copy
 * (layout.c). */
const tgi_gview *tgi_frame_kernel(const tg_frame *f, const tgi_gresult **res, const tgi_rgb **source);
/* The radiance the near field gathers on this bounce, at full resolution:
 * this frame's direct light and emission (the first bounce of a frame
 * without history), last frame's reprojected radiance, or the previous
 * bounce's Lo (layout.c). */
const tgi_rgb *tgi_frame_source(const tg_frame *f);
/* What the radiance slots and results sets hold this frame (frame_internal.h's
 * tg_frame); tg_frame_render calls it first (layout.c). */
void tgi_frame_begin(tg_frame *f);
/* request.ao_multibounce with the ao AOV asked: the AOV reads the fit, the
 * G-buffer keeps the material (plan.c). */
int tgi_frame_ao_multibounce(const tg_frame *f);
/* The technique of the plan is HBIL with the interleaved kernel, and at
 * quarter resolution (plan.c). */
int tgi_frame_interleaved(const tg_frame *f);
int tgi_frame_quarter(const tg_frame *f);
/* --gi-quarter with the full-resolution near horizon (TG_QUARTER_NEAR_REACH >= 1) */
int tgi_frame_near_horizon(const tg_frame *f);
/* HBIL's kernel on --gi-quarter's half-resolution image (the request's
 * technique, interleave and gi_scale) */
int tgi_request_quarter(const tg_request *r);

#endif
