/* SPDX-License-Identifier: MIT */
/*
 * soak.c - a long run (`make soak`): LAPS x LAP + 1 frames (default 8 x 256
 * + 1 = 2049) of an animated scene with reprojection, temporal
 * accumulation, shadows, an emitter and an environment, at 32x24, through
 * the public API.
 *
 * The animation repeats every LAP frames (camera keys with a cut in each
 * lap, an object moving back and forth), so frame i and frame i + LAP see
 * the same poses: the animation time is the frame index, exact in both
 * number types because frames - 1 is a power of two.  Asserted:
 *   - every frame, every output finite and bounded: colour in
 *     [0, COLOR_BOUND], irradiances and depth >= 0, AO in [0, 1], cone in
 *     [0, pi/2], normals and bent normals of surface pixels unit length;
 *   - no drift: from the third lap to the last whole one, each frame's
 *     colour repeats the frame LAP before (mean absolute difference below
 *     DRIFT_TOL, mean colour within ENERGY_TOL), so nothing accumulates
 *     over thousands of frames of reprojection;
 *   - fixed memory: the frame gets exactly the plan's total_bytes, at an
 *     address 1 past a multiple of 16 (the worst alignment: the plan's
 *     16 bytes of slack go to padding, so the frame ends within a byte of
 *     its memory's end), with guard bytes before and after it, checked every
 *     100 frames (and poisoned under AddressSanitizer, which then reports
 *     the first byte written to them); re-planning gives the same
 *     total_bytes; the scene's memory is not written (checksum).
 * Prints one line per number type, exits 1 on the first failure.
 *
 *   usage: soak [LAPS]   (a power of two, 2..64)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/asan_interface.h>
#define POISON(p, n) ASAN_POISON_MEMORY_REGION(p, n)
#define UNPOISON(p, n) ASAN_UNPOISON_MEMORY_REGION(p, n)
#else
#define POISON(p, n) ((void)(p), (void)(n))
#define UNPOISON(p, n) ((void)(p), (void)(n))
#endif

#define W 32
#define H 24
#define LAP 256
#define COLOR_BOUND 64.0f   /* linear radiance; the brightest surface here is ~6 */
#define DRIFT_TOL 1e-3      /* mean |colour(i) - colour(i - LAP)| from the third lap on */
#define ENERGY_TOL 2e-4     /* |mean colour(i) - mean colour(i - LAP)| likewise: the radiance
                               history is RGB9E5 (9-bit mantissas, 1 part in 512), and the
                               largest lap-to-lap change, 1.2e-4, is at the third lap's start and
                               smaller after it (the wide tg_real history kept it under 1e-4) */
#define GUARD 4097           /* after malloc's 16-byte aligned block: the frame at 16k + 1 */
#define PATTERN 0x5A

static int failures;

#define FAIL(...) do { fprintf(stderr, "soak %s: ", TG_NUMBER_NAME); fprintf(stderr, __VA_ARGS__); \
                       fputc('\n', stderr); failures++; } while (0)

/* The scene: a room with a moving box, keys repeating every LAP frames, up
 * to frame `frames` - 1 = a whole number of laps (the animation time is the
 * frame index). */
static char *scene_text(int frames)
{
    static const char *head =
        "material wall albedo 0.7 0.7 0.7\n"
        "material red albedo 0.8 0.2 0.2 f0 0.1\n"
        "material hot albedo 0.5 0.5 0.5 emissive 3 2 1\n"
        "quad p0 -3 0 -4  p1 -3 0 3  p2 3 0 3  p3 3 0 -4 material wall\n"
        "quad p0 -3 0 3  p1 -3 3 3  p2 3 3 3  p3 3 0 3 material wall\n"
        "quad p0 -3 0 -4  p1 -3 3 -4  p2 -3 3 3  p3 -3 0 3 material red\n"
        "box min -0.4 0 -0.4 max 0.4 0.8 0.4 material red name mover\n"
        "sphere center 1.2 0.4 0.5 radius 0.4 material hot segments 8\n"
        "light point pos 0 2.5 -1 color 1 1 1 intensity 3 shadows\n"
        "light directional dir -0.5 -1 0.3 color 0.6 0.6 0.7 shadows\n"
        "env sky 0.4 0.5 0.8 ground 0.2 0.2 0.2\n"
        "gi radius 1\n";
    /* per lap: frame offset, camera position, target */
    static const struct { int t; const char *cam; } lap[] = {
        { 0, "pos 0 1.4 -3.6 target 0 0.8 0" },
        { 64, "pos 1.5 1.8 -3 target 0 0.6 0" },
        { 128, "pos 0.5 1.6 -3.4 target 0 0.7 0" },
        { 129, "pos -2 2.4 -1 target 0.5 0.3 1" },   /* a cut */
        { 192, "pos -1 1.5 -3.3 target 0 0.8 0" },
    };
    size_t cap = 1 << 20, at;
    char *t = (char *)malloc(cap);
    int base, k;
    at = (size_t)snprintf(t, cap, "%s", head);
    for (base = 0; base < frames - 1; base += LAP)
        for (k = 0; k < 5; k++)
            at += (size_t)snprintf(t + at, cap - at, "camera_key t %d %s\n", base + lap[k].t, lap[k].cam);
    at += (size_t)snprintf(t + at, cap - at, "camera_key t %d %s\n", frames - 1, lap[0].cam);
    for (base = 0; base < frames - 1; base += LAP) {
        at += (size_t)snprintf(t + at, cap - at, "object_key name mover t %d translate -0.8 0 0\n", base);
        at += (size_t)snprintf(t + at, cap - at, "object_key name mover t %d translate 0.8 0 0.5 rotate 0 1 0 40\n",
                               base + LAP / 2);
    }
    snprintf(t + at, cap - at, "object_key name mover t %d translate -0.8 0 0\n", frames - 1);
    return t;
}

static int finite(float v) { return v == v && v <= 3.402823466e+38f && v >= -3.402823466e+38f; }

static void fill(unsigned char *p, size_t n) { memset(p, PATTERN, n); }

static int intact(const unsigned char *p, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) if (p[i] != PATTERN) return 0;
    return 1;
}

static uint32_t checksum(const unsigned char *p, size_t n)
{
    uint32_t h = 2166136261u;
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ p[i]) * 16777619u;
    return h;
}

typedef struct stats {
    float max_color;
    double drift_max, energy_max;
    int drift_frame, energy_frame;
} stats;

/* Every output of the frame in bounds; the colour into `color`. */
static void check_frame(const tg_frame *frame, int index, float *color)
{
    tg_real row[3 * W], depth[W];
    int a, x, y, i, c;
    for (y = 0; y < H; y++) {
        tg_frame_aov_row(frame, TG_AOV_DEPTH, y, depth);
        for (a = 0; a < TG_AOV_COUNT; a++) {
            c = tg_aov_channels((tg_aov)a);
            tg_frame_aov_row(frame, (tg_aov)a, y, row);
            for (i = 0; i < W * c; i++) {
                float v = tg_to_float(row[i]);
                int nonneg = a == TG_AOV_COLOR || a == TG_AOV_DIRECT || a == TG_AOV_NEAR || a == TG_AOV_FAR ||
                             a == TG_AOV_IRRADIANCE || a == TG_AOV_DEPTH || a == TG_AOV_AO || a == TG_AOV_CONE;
                if (!finite(v) || (nonneg && v < 0) || (a == TG_AOV_AO && v > 1.0f) ||
                    (a == TG_AOV_CONE && v > tg_to_float(TG_HALF_PI) + 1e-4f) || (a == TG_AOV_COLOR && v > COLOR_BOUND)) {
                    FAIL("frame %d: %s at (%d, %d) channel %d = %g", index, tg_aov_name((tg_aov)a), i / c, y, i % c, (double)v);
                    return;
                }
                if (a == TG_AOV_COLOR) color[(y * W) * 3 + i] = v;
            }
            if (a != TG_AOV_NORMAL && a != TG_AOV_BENT) continue;
            for (x = 0; x < W; x++) {
                float nx = tg_to_float(row[3 * x]), ny = tg_to_float(row[3 * x + 1]), nz = tg_to_float(row[3 * x + 2]);
                float len2 = nx * nx + ny * ny + nz * nz;
                if (depth[x] > 0 && (len2 < 0.96f || len2 > 1.04f)) {
                    FAIL("frame %d: %s at (%d, %d) has length^2 %g", index, tg_aov_name((tg_aov)a), x, y, (double)len2);
                    return;
                }
            }
        }
    }
}

/* Mean |a - b| and |mean a - mean b| of two colour images. */
static void compare(const float *a, const float *b, double *abs_diff, double *energy)
{
    double s = 0, e = 0;
    int i;
    for (i = 0; i < W * H * 3; i++) {
        s += (double)(a[i] > b[i] ? a[i] - b[i] : b[i] - a[i]);
        e += (double)(a[i] - b[i]);
    }
    *abs_diff = s / (W * H * 3);
    *energy = (e < 0 ? -e : e) / (W * H * 3);
}

static int soak(int frames)
{
    char *text = scene_text(frames);
    size_t scene_bytes;
    unsigned char *scene_mem, *frame_block;
    tg_arena arena;
    tg_scene *scene = NULL;
    tg_request q;
    tg_plan plan, again;
    tg_frame *frame = NULL;
    tg_error err;
    uint32_t scene_sum;
    float *laps = (float *)calloc((size_t)LAP * W * H * 3, sizeof(float)), color[W * H * 3];
    stats st;
    int i;
    memset(&st, 0, sizeof st);
    memset(color, 0, sizeof color);
    tg_arena_init(&arena, NULL, 0);
    tg_scene_parse(text, strlen(text), "soak.scene", NULL, &arena, &scene, &err);
    scene_bytes = err.bytes_needed;
    scene_mem = (unsigned char *)malloc(scene_bytes);
    tg_arena_init(&arena, scene_mem, scene_bytes);
    if (tg_scene_parse(text, strlen(text), "soak.scene", NULL, &arena, &scene, &err) != TG_OK) {
        FAIL("scene: %s:%d:%d: %s", err.file, err.line, err.col, err.message);
        return 1;
    }
    tg_request_defaults(&q);
    q.width = W;
    q.height = H;
    q.frames = frames;
    q.aovs = (1u << TG_AOV_COUNT) - 1u;
    q.shadow_map_size = 64;
    if (tg_plan_make(&plan, scene, &q, &err) != TG_OK) { FAIL("plan: %s", err.message); return 1; }
    if (!(plan.effects & TG_EFFECT_REPROJECTION)) { FAIL("the plan has no reprojection"); return 1; }
    frame_block = (unsigned char *)malloc(plan.total_bytes + 2 * GUARD);
    fill(frame_block, plan.total_bytes + 2 * GUARD);
    if (tg_frame_create(&plan, frame_block + GUARD, plan.total_bytes, &frame, &err) != TG_OK) {
        FAIL("create: %s", err.message);
        return 1;
    }
    scene_sum = checksum(scene_mem, scene_bytes);
    POISON(frame_block, GUARD);
    POISON(frame_block + GUARD + plan.total_bytes, GUARD);
    for (i = 0; i < frames && !failures; i++) {
        float *prev = laps + (size_t)(i % LAP) * W * H * 3;
        if (tg_frame_render(frame, i, &err) != TG_OK) { FAIL("render %d: %s", i, err.message); break; }
        check_frame(frame, i, color);
        for (int k = 0; k < W * H * 3; k++) if (color[k] > st.max_color) st.max_color = color[k];
        if (i >= 2 * LAP) {
            double d, e;
            compare(color, prev, &d, &e);
            if (d > st.drift_max) { st.drift_max = d; st.drift_frame = i; }
            if (e > st.energy_max) { st.energy_max = e; st.energy_frame = i; }
        }
        memcpy(prev, color, sizeof color);
        if (i % 100 == 99 || i == frames - 1) {
            UNPOISON(frame_block, GUARD);
            UNPOISON(frame_block + GUARD + plan.total_bytes, GUARD);
            if (!intact(frame_block, GUARD) || !intact(frame_block + GUARD + plan.total_bytes, GUARD))
                FAIL("frame %d: the frame wrote outside its %zu bytes", i, plan.total_bytes);
            POISON(frame_block, GUARD);
            POISON(frame_block + GUARD + plan.total_bytes, GUARD);
            if (checksum(scene_mem, scene_bytes) != scene_sum) FAIL("frame %d: the scene's memory changed", i);
            if (tg_plan_make(&again, scene, &q, &err) != TG_OK || again.total_bytes != plan.total_bytes)
                FAIL("frame %d: re-planning gives %zu bytes, not %zu", i, again.total_bytes, plan.total_bytes);
        }
    }
    if (st.drift_max > DRIFT_TOL)
        FAIL("lap-to-lap difference %.4g at frame %d (tolerance %g)", st.drift_max, st.drift_frame, DRIFT_TOL);
    if (st.energy_max > ENERGY_TOL)
        FAIL("lap-to-lap mean colour change %.4g at frame %d (tolerance %g)", st.energy_max, st.energy_frame, ENERGY_TOL);
    printf("soak %s: %d frames %dx%d, %zu frame bytes, colour max %.3g (bound %g), lap to lap: mean |difference| "
           "%.2g (tolerance %g), mean colour change %.2g (tolerance %g): %s\n", TG_NUMBER_NAME, i, W, H,
           plan.total_bytes, (double)st.max_color, (double)COLOR_BOUND, st.drift_max, DRIFT_TOL, st.energy_max,
           ENERGY_TOL, failures ? "FAILED" : "ok");
    free(text);
    free(scene_mem);
    UNPOISON(frame_block, plan.total_bytes + 2 * GUARD);
    free(frame_block);
    free(laps);
    return failures ? 1 : 0;
}

int main(int argc, char **argv)
{
    int laps = argc > 1 ? atoi(argv[1]) : 8;
    if (laps < 2 || laps > 64 || (laps & (laps - 1))) {
        fprintf(stderr, "usage: soak [LAPS]  (a power of two, 2..64; %d frames each)\n", LAP);
        return 2;
    }
    return soak(laps * LAP + 1);
}
