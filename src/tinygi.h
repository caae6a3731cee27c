/* SPDX-License-Identifier: MIT */
/*
 * tinygi.h - the public API of tinygi, a dependency-free C99 software
 * renderer with screen-space global illumination (Horizon-Based Indirect
 * Lighting, HBIL) for small machines.
 *
 * CONFIGURATION (one macro, set for the whole build, like luaconf.h)
 *   TG_FIXED=1   tg_real is Q16.16 fixed point (int32_t); default is float.
 *
 * MEMORY
 *   The core never allocates.  The caller hands it one arena (tg_arena) and
 *   asks how many bytes a frame plan needs (tgi_plan_bytes) beforehand.
 *
 * CONVENTIONS (decided once, used everywhere)
 *   - Right-handed world space, +Y up by default.  The camera looks along
 *     its forward vector; view space is x right, y up, z FORWARD (positive
 *     into the screen), so a visible point has z > 0.
 *   - "depth" is linear view depth: the view-space z of the surface (the
 *     distance along the view axis, not along the ray), in world units.
 *     Sky pixels have depth 0 and the sky marker set.
 *   - The gi radius is in world units.
 *   - Normals and bent normals in AOVs are world space, unit length.
 *   - Cone apertures are in radians (half angle), in [0, pi/2].
 *   - Colour is linear RGB until the tonemapper; sRGB 8-bit only at the end.
 *   - Image rows are top to bottom, pixel (0,0) is the top-left corner and
 *     pixel centres are at (x + 0.5, y + 0.5).
 *   - Front faces are counter-clockwise seen from the front.
 *
 * ERRORS
 *   Functions return TG_OK (0) or a tg_status; a tg_error then holds a
 *   message fit to show a person, with FILE:LINE:COL when it is about input.
 */
#ifndef TINYGI_H
#define TINYGI_H

#include <stddef.h>
#include <stdint.h>
#include "core/real.h"

#define TG_VERSION "0.2.0"

/* ==== LIMITS AND DEFAULTS ================================================
 * Every limit tinygi enforces, in one place (in the manner of luaconf.h),
 * each with its unit and its reason.  The scene parser, the plan
 * (tg_plan_make), the CLI and its --help, the README and
 * src/scene/format.md all use these; a value past a limit is refused with a
 * message that names it (FILE:LINE:COL in a scene file).  A build may LOWER
 * a limit marked [policy] by defining it first; the others follow from the
 * number formats and are fixed.
 */
/* -- image -- */
#define TG_MAX_IMAGE_SIDE 8192          /* pixels per side: the rasterizer's 28.4
                                           screen coordinates with a guard band of
                                           GUARD screens stay within 2^20 */
#if !defined(TG_MAX_IMAGE_PIXELS)
#define TG_MAX_IMAGE_PIXELS 16777216L   /* [policy] pixels per frame (2^24: 4096x4096) */
#endif
#if !defined(TG_MAX_FRAMES)
#define TG_MAX_FRAMES 100000            /* [policy] frames in one request */
#endif
/* -- GI settings (request fields and the scene's `gi` line) -- */
#define TG_MAX_SLICES 8                 /* slices per pixel: the kernel's per-slice table */
#define TG_MAX_SAMPLES 256              /* horizon samples per slice side */
#define TG_MAX_BOUNCES 100              /* kernel iterations on a frame without history */
#define TG_MAX_RADIUS 10000             /* gather radius, world units (0 is allowed) */
#define TG_MAX_EXPOSURE 1000            /* linear multiplier before the tonemapper (0 allowed) */
#define TG_MIN_SHADOW_MAP 8             /* shadow-map texels per side: the PCF footprint */
#define TG_MAX_SHADOW_MAP 8192          /* ... and the rasterizer's largest side */
#define TG_DEFAULT_SLICES 2             /* HBIL sec. 3.3: 2 slices per pixel */
#define TG_DEFAULT_SAMPLES 16
#define TG_DEFAULT_BOUNCES 1
#define TG_DEFAULT_RADIUS 1             /* world units, when neither request nor scene gives one */
#define TG_DEFAULT_SHADOW_MAP 512       /* texels per side */
#define TG_DEFAULT_WIDTH 320
#define TG_DEFAULT_HEIGHT 240
/* -- scene text and OBJ files -- */
#define TG_MAX_LINE 4096                /* bytes in a scene or OBJ line, not counting the line end */
#define TG_MAX_NAME 31                  /* bytes in a material or object name */
#if !defined(TG_MAX_TRIANGLES)
#define TG_MAX_TRIANGLES 4000000L       /* [policy] triangles in a scene (meshes included) */
#endif
#define TG_MAX_MATERIALS 1024           /* materials in a scene */
#define TG_MAX_OBJECTS 65535            /* objects: a 16-bit object id per triangle */
#define TG_MAX_LIGHTS 64
#define TG_MAX_KEYS 4096                /* camera keys; object keys likewise */
#define TG_MIN_SPHERE_SEGMENTS 4
#define TG_MAX_SPHERE_SEGMENTS 256
#define TG_MAX_PATH 256                 /* a resolved mesh or MTL path, bytes with the NUL */
#if !defined(TG_MAX_OBJ_VERTICES)
#define TG_MAX_OBJ_VERTICES 4000000L    /* [policy] v, vn and vt lines each, per OBJ */
#endif
#define TG_MAX_MTLLIBS 8                /* mtllib files named by one OBJ */
#if !defined(TG_MAX_FILE_BYTES)
#define TG_MAX_FILE_BYTES (1L << 30)    /* [policy] a scene, OBJ or MTL file (1 GiB) */
#endif
/* ======================================================================= */

typedef enum tg_status {
    TG_OK = 0,
    TG_ERR_RUNTIME = 1, /* anything not the input's fault */
    TG_ERR_INPUT = 2,   /* bad scene, bad OBJ, bad request */
    TG_ERR_MEMORY = 3   /* the arena is too small: see tg_error.bytes_needed */
} tg_status;

typedef struct tg_error {
    char file[256];      /* "" when the error is not about a file */
    int line, col;       /* 1-based; 0 when unknown */
    char message[256];
    size_t bytes_needed; /* with TG_ERR_MEMORY */
} tg_error;

/* Write the error as "FILE:LINE:COL: error: MESSAGE" (or "error: MESSAGE"). */
size_t tg_error_format(const tg_error *err, char *buf, size_t size);

/* ---- the arena: one block of caller memory, carved front to back ---- */
typedef struct tg_arena {
    unsigned char *base;
    size_t size, used;
    size_t failed_request; /* largest request that did not fit, 0 if none */
} tg_arena;

void tg_arena_init(tg_arena *a, void *memory, size_t size);
void *tg_arena_alloc(tg_arena *a, size_t bytes); /* 16-byte aligned, zeroed; NULL when full */
/* a * b with overflow check: returns 0 and sets *out, or returns 1 on overflow. */
int tg_size_mul(size_t a, size_t b, size_t *out);
int tg_size_add(size_t a, size_t b, size_t *out);

/* ---- files the scene refers to (OBJ meshes): supplied by the platform ---- */
typedef struct tg_io {
    void *user;
    /* Give the whole file; the buffer must stay valid while parsing.
     * Return 0 on success, non-zero if the file cannot be read; then set
     * *reason to a short phrase ("permission denied", "is a directory",
     * "not a regular file", "larger than the 1 GiB limit") or leave it NULL. */
    int (*read_file)(void *user, const char *path, const char **data, size_t *size,
                     const char **reason);
} tg_io;

/* ---- scenes ---- */
typedef struct tg_scene tg_scene;

/* Parse scene-format v1 text (see README "Scene format").  `filename` is used
 * in messages and to resolve mesh paths.  `io` may be NULL (no meshes).  The
 * scene lives in `arena`. */
tg_status tg_scene_parse(const char *text, size_t size, const char *filename,
                         const tg_io *io, tg_arena *arena, tg_scene **scene,
                         tg_error *err);
/* Built-in scenes: their text, by name ("cornell"), or NULL. */
const char *tg_builtin_scene(const char *name);
/* The i-th built-in scene name, NULL past the end. */
const char *tg_builtin_name(int i);

/* ---- what to render ---- */
typedef enum tg_aov {
    TG_AOV_COLOR, TG_AOV_DEPTH, TG_AOV_NORMAL, TG_AOV_ALBEDO,
    TG_AOV_AO, TG_AOV_BENT, TG_AOV_CONE, TG_AOV_NEAR, TG_AOV_FAR,
    TG_AOV_DIRECT, TG_AOV_IRRADIANCE, TG_AOV_MOTION,
    TG_AOV_COUNT
} tg_aov;
const char *tg_aov_name(tg_aov aov);
int tg_aov_from_name(const char *name); /* -1 if unknown */
int tg_aov_channels(tg_aov aov);        /* 1 or 3 (motion: 3, z = validity) */

typedef enum tg_technique {
    TG_TECH_HBIL, TG_TECH_GTAO, TG_TECH_HBAO, TG_TECH_SSAO, TG_TECH_VO,
    TG_TECH_SSDO, TG_TECH_BENTCONE, TG_TECH_REFERENCE,
    TG_TECH_COUNT
} tg_technique;
const char *tg_technique_name(tg_technique t);
int tg_technique_from_name(const char *name); /* -1 if unknown */

/* Effects a frame can simulate; a plan holds the subset the scene calls for. */
enum {
    TG_EFFECT_DIRECT = 1u << 0,
    TG_EFFECT_SHADOWS = 1u << 1,
    TG_EFFECT_FAR = 1u << 2,          /* environment light (SH9) */
    TG_EFFECT_NEAR = 1u << 3,         /* gathered bounce light */
    TG_EFFECT_AO = 1u << 4,
    TG_EFFECT_REPROJECTION = 1u << 5
};

typedef struct tg_request {
    int width, height;     /* default 320x240 */
    int frames;            /* frames to render (1: no reprojection) */
    uint32_t aovs;         /* bit (1u << TG_AOV_x) per output wanted; default colour */
    tg_technique technique;
    int slices;            /* <= 0: the scene's gi line or the default (2) */
    int samples;           /* <= 0: the scene's or the default (16) */
    tg_real radius;        /* < 0: the scene's or the default (1.0); 0 is allowed */
    int bounces;           /* < 0: the scene's or the default (1) */
    int interleave;        /* 1: 4x4 interleaved kernel (default); 0: one full-res image */
    int gi_scale;          /* interleaved kernel on 1 pixel in gi_scale^2: 1 = every
                              pixel (default, the paper's), 2 = a quarter of them (half
                              width and height: about 3x faster, AO slightly brighter) */
    int temporal;          /* 1: temporal accumulation of the GI result (default 1) */
    int far_mode;          /* 0: SH9 cosine lobe in the bent cone (HBIL sec. 2.2.4, default);
                              1: E0(bent) F0(AO) (HBIL sec. 2.2.3) */
    tg_real exposure;      /* linear multiplier before the tonemapper, default 1 */
    int shadow_map_size;   /* texels per side, default 512 */
    int shadow_pcf;        /* 0: 16-tap tent PCF (default, soft); 1: 4-tap bilinear (a quarter of the cost) */
} tg_request;

void tg_request_defaults(tg_request *r);

/* ---- the frame plan ---- */
#define TG_PLAN_MAX_PASSES 40
#define TG_PLAN_MAX_BUFFERS 64

typedef struct tg_plan_buffer {
    const char *name;   /* what it holds, in the papers' words */
    size_t bytes;
} tg_plan_buffer;

typedef struct tg_plan {
    tg_request request;        /* the request with every default resolved */
    uint32_t effects;          /* TG_EFFECT_* the frame simulates */
    int pass_count;
    const char *passes[TG_PLAN_MAX_PASSES];
    int buffer_count;
    tg_plan_buffer buffers[TG_PLAN_MAX_BUFFERS];
    size_t total_bytes;        /* arena bytes tg_frame_create needs */
    const tg_scene *scene;
} tg_plan;

tg_status tg_plan_make(tg_plan *plan, const tg_scene *scene,
                       const tg_request *req, tg_error *err);
/* Human-readable plan (the CLI's --explain); returns the length written. */
size_t tg_plan_explain(const tg_plan *plan, char *buf, size_t size);

/* ---- frames ---- */
typedef struct tg_frame tg_frame;

/* Carve a frame out of `memory` (at least plan->total_bytes). */
tg_status tg_frame_create(const tg_plan *plan, void *memory, size_t size,
                          tg_frame **frame, tg_error *err);
/* Render frame `index` (0-based; the animation time comes from it). */
tg_status tg_frame_render(tg_frame *frame, int index, tg_error *err);
/* One row of an AOV as linear values (channels per pixel from tg_aov_channels). */
void tg_frame_aov_row(const tg_frame *frame, tg_aov aov, int y, tg_real *out);
/* One row of an AOV as 8-bit RGB for viewing: colour is exposed, tonemapped
 * and sRGB-encoded; normals are 0.5n + 0.5; scalar AOVs are grey. */
void tg_frame_aov_row8(const tg_frame *frame, tg_aov aov, int y, uint8_t *rgb);

#endif
