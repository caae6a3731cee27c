/* SPDX-License-Identifier: MIT */
/*
 * fuzz_api.c - libFuzzer target for the public API as a whole: from the
 * input's first bytes a tg_request (every field, out-of-range values
 * included) and a few frame indices; from the rest a scene, planned, laid
 * out and rendered in ONE small arena, so parsing, planning, layout and
 * rendering are fuzzed together.
 *
 * Input: the header read_case reads (25 bytes; a missing byte reads as 0), then
 *   mode 0: the scene text itself;
 *   mode 1: a built-in scene with the bytes appended (more objects, lights,
 *           keys, gi and effects lines);
 *   mode 2: a built-in scene with the bytes as edits (2 bytes position,
 *           1 byte value), numbers and keywords mutated in place.
 * Any path ending in ".obj" is a small mesh; any other file is empty.
 *
 * The arena is ARENA_BYTES at a fuzzed alignment: the scene takes its
 * front, the frame gets the rest, and the frame's memory ends at the end of
 * the allocation (AddressSanitizer reports a byte past it).  A request past
 * a documented limit must be refused by tg_plan_make (abort otherwise; see
 * plan_checks_fields).  A frame is rendered only when its work is small
 * (WORK_BUDGET), so each input runs in well under a second.  Every output
 * must be finite, colour and irradiances >= 0, AO in [0, 1], normals and
 * bent normals at most unit length, cone apertures in [0, pi/2]; the frame
 * is also written in a fuzzed display format (tg_frame_write_pixels, format
 * and flags out of range included) into a buffer of exactly its size.
 */
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define ARENA_BYTES (256u * 1024u)
#define MAX_RENDERS 3
#define WORK_BUDGET 3000000.0   /* pixels x slices x samples x (bounces + 1) x renders */

typedef struct reader {
    const uint8_t *p;
    size_t n;
} reader;

static unsigned byte_of(reader *r)
{
    if (!r->n) return 0;
    r->n--;
    return *r->p++;
}

/* Values just past (and at) the documented limits, and integer extremes. */
static const int int_extremes[16] = {
    0, -1, INT_MIN, INT_MAX, TG_MAX_SLICES + 1, TG_MAX_SAMPLES + 1, TG_MAX_BOUNCES + 1,
    TG_MIN_SHADOW_MAP - 1, TG_MAX_SHADOW_MAP + 1, TG_MAX_IMAGE_SIDE + 1, TG_MAX_FRAMES + 1,
    TG_TECH_COUNT, 2, 3, 1000000, 13378
};

/* Usually in [lo, hi]; one byte value in 16 an extreme. */
static int pick_int(reader *r, int lo, int hi)
{
    unsigned b = byte_of(r);
    if (b >= 240) return int_extremes[b - 240];
    return lo + (int)(b % (unsigned)(hi - lo + 1));
}

/* Usually lo + (hi - lo) b / 239; else NaN, the infinities, the tg_real
 * extremes, -1 (unset), values just past the limits. */
static tg_real pick_real(reader *r, float lo, float hi)
{
    float inf = 1e30f * 1e30f;
    unsigned b = byte_of(r);
    if (b < 240) return tg_from_float(lo + (hi - lo) * (float)b / 239.0f);
    switch (b - 240) {
    case 0: return tg_from_float(inf - inf);
    case 1: return tg_from_float(inf);
    case 2: return tg_from_float(-inf);
    case 3: return TG_REAL_MAX;
    case 4: return TG_REAL_MIN;
    case 5: return TG_R(-1.0f);
    case 6: return TG_R(-0.5f);
    case 7: return TG_EPS;
    case 8: return tg_add(tg_from_int(TG_MAX_RADIUS), TG_EPS);
    case 9: return tg_add(tg_from_int(TG_MAX_EXPOSURE), TG_EPS);
    case 10: return tg_from_int(TG_MAX_RADIUS);
    case 11: return tg_from_int(TG_MAX_EXPOSURE);
    default: return 0;
    }
}

typedef struct fuzz_case {
    tg_request q;
    int index[MAX_RENDERS];
    unsigned offset, mode, builtin;
    int format, flags;   /* tg_frame_write_pixels */
} fuzz_case;

static void read_case(reader *r, fuzz_case *c)
{
    tg_request *q = &c->q;
    int k;
    tg_request_defaults(q);
    c->mode = byte_of(r) % 3u;
    c->builtin = byte_of(r);
    c->offset = byte_of(r) & 15u;
    q->width = pick_int(r, 1, 64);
    q->height = pick_int(r, 1, 64);
    q->frames = pick_int(r, 1, 4);
    q->aovs = byte_of(r);
    q->aovs |= byte_of(r) << 8;                  /* bits past TG_AOV_COUNT included */
    q->technique = (tg_technique)pick_int(r, 0, TG_TECH_COUNT - 1);
    q->slices = pick_int(r, -1, TG_MAX_SLICES);
    q->samples = pick_int(r, -1, 24);
    q->radius = pick_real(r, -1.0f, 4.0f);
    q->bounces = pick_int(r, -1, 4);
    q->interleave = pick_int(r, 0, 1);
    q->gi_scale = pick_int(r, 1, 2);
    q->temporal = pick_int(r, 0, 1);
    q->far_mode = pick_int(r, 0, 1);
    q->exposure = pick_real(r, 0.0f, 4.0f);
    q->shadow_map_size = pick_int(r, TG_MIN_SHADOW_MAP - 1, 64);
    q->shadow_pcf = pick_int(r, 0, 1);
    for (k = 0; k < MAX_RENDERS; k++) c->index[k] = pick_int(r, 0, 5);
    c->format = pick_int(r, 0, TG_PIXEL_FORMAT_COUNT - 1);
    c->flags = pick_int(r, 0, TG_PIXELS_DITHER);
}

/* ---- the documented limits (tinygi.h, the tg_request comments) ---- */

static int real_within(tg_real v, long lo, long hi)
{
    return tg_isfinite(v) && v >= tg_from_int((int32_t)lo) && v <= tg_from_int((int32_t)hi);
}

static int request_within_limits(const tg_request *q)
{
    if (q->width < 1 || q->width > TG_MAX_IMAGE_SIDE || q->height < 1 || q->height > TG_MAX_IMAGE_SIDE) return 0;
    if ((long)q->width * q->height > TG_MAX_IMAGE_PIXELS) return 0;
    if (q->frames < 1 || q->frames > TG_MAX_FRAMES) return 0;
    if (q->aovs & ~((1u << TG_AOV_COUNT) - 1u)) return 0;
    if ((unsigned)q->technique >= TG_TECH_COUNT) return 0;
    if (q->slices > TG_MAX_SLICES || q->samples > TG_MAX_SAMPLES || q->bounces > TG_MAX_BOUNCES) return 0;
    if (q->radius != TG_R(-1.0f) && !real_within(q->radius, 0, TG_MAX_RADIUS)) return 0;
    if (!real_within(q->exposure, 0, TG_MAX_EXPOSURE)) return 0;
    if (q->interleave < 0 || q->interleave > 1 || q->gi_scale < 1 || q->gi_scale > 2) return 0;
    if (q->temporal < 0 || q->temporal > 1 || q->far_mode < 0 || q->far_mode > 1) return 0;
    if (q->shadow_pcf < 0 || q->shadow_pcf > 1) return 0;
    if (q->shadow_map_size > 0 && (q->shadow_map_size < TG_MIN_SHADOW_MAP || q->shadow_map_size > TG_MAX_SHADOW_MAP))
        return 0;
    return 1;
}

/* Whether this library's tg_plan_make checks every request field (a plan
 * that does refuses bounces = TG_MAX_BOUNCES + 1).  When it does, a request
 * past a limit that it accepts is a finding (abort); when it does not, such
 * requests are planned but not rendered (tests/test_hostile.c marks that
 * gap expected-to-fail). */
static int plan_checks_fields(void)
{
    static int known = -1;
    if (known < 0) {
        static unsigned char mem[1u << 16];
        const char *text = tg_builtin_scene("plane");
        tg_arena a;
        tg_scene *s = NULL;
        tg_plan plan;
        tg_request q;
        tg_arena_init(&a, mem, sizeof mem);
        if (tg_scene_parse(text, strlen(text), "plane", NULL, &a, &s, NULL) != TG_OK) abort();
        tg_request_defaults(&q);
        q.bounces = TG_MAX_BOUNCES + 1;
        known = tg_plan_make(&plan, s, &q, NULL) == TG_ERR_INPUT;
    }
    return known;
}

/* ---- the scene ---- */

static const char mesh_obj[] = "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0 0.8 0\nv 0 0 0.5\nf 1 2 3\nf 2 4 3\nf 4 1 3\nf 1 4 2\n";

static int read_file(void *user, const char *path, const char **data, size_t *size, const char **reason)
{
    size_t n = strlen(path);
    (void)user;
    (void)reason;
    if (n >= 4 && memcmp(path + n - 4, ".obj", 4) == 0) { *data = mesh_obj; *size = sizeof mesh_obj - 1; }
    else { *data = ""; *size = 0; }
    return 0;
}

static int builtin_count(void)
{
    int n = 0;
    while (tg_builtin_name(n)) n++;
    return n;
}

/* The scene text of the case (malloc'd, exactly *n bytes, no NUL). */
static char *scene_text(const fuzz_case *c, reader *r, size_t *n)
{
    const char *base = tg_builtin_scene(tg_builtin_name((int)(c->builtin % (unsigned)builtin_count())));
    size_t bn = strlen(base);
    char *t;
    if (c->mode == 0) {
        *n = r->n;
        t = (char *)malloc(*n + 1);
        memcpy(t, r->p, *n);
        return t;
    }
    if (c->mode == 1) {
        *n = bn + r->n;
        t = (char *)malloc(*n + 1);
        memcpy(t, base, bn);
        memcpy(t + bn, r->p, r->n);
        return t;
    }
    *n = bn;
    t = (char *)malloc(bn + 1);
    memcpy(t, base, bn);
    while (r->n >= 3) {
        size_t at = (byte_of(r) | byte_of(r) << 8) % bn;
        t[at] = (char)byte_of(r);
    }
    return t;
}

/* ---- the outputs ---- */

static void fail(const char *what, int aov, int y, int i, float v)
{
    fprintf(stderr, "fuzz_api: %s: %s row %d value %d = %g\n", what, tg_aov_name((tg_aov)aov), y, i, (double)v);
    abort();
}

static void check_value(int aov, int y, int i, float v)
{
    if (!(v == v) || v > 3.402823466e+38f || v < -3.402823466e+38f) fail("not finite", aov, y, i, v);
    switch (aov) {
    case TG_AOV_COLOR: case TG_AOV_DIRECT: case TG_AOV_NEAR: case TG_AOV_IRRADIANCE: case TG_AOV_DEPTH:
        if (v < 0) fail("negative", aov, y, i, v);
        break;
    case TG_AOV_AO:
        if (v < 0 || v > 1) fail("outside [0, 1]", aov, y, i, v);
        break;
    case TG_AOV_CONE:
        if (v < 0 || v > 1.5708f + 1e-3f) fail("outside [0, pi/2]", aov, y, i, v);
        break;
    default:
        break;
    }
}

static void check_row(const tg_frame *frame, int aov, int y, int w, tg_real *row, uint8_t *row8)
{
    int c = tg_aov_channels((tg_aov)aov), x, i;
    tg_frame_aov_row(frame, (tg_aov)aov, y, row);
    tg_frame_aov_row8(frame, (tg_aov)aov, y, row8);
    for (i = 0; i < w * c; i++) check_value(aov, y, i, tg_to_float(row[i]));
    if (aov != TG_AOV_NORMAL && aov != TG_AOV_BENT) return;
    for (x = 0; x < w; x++) {
        float a = tg_to_float(row[3 * x]), b = tg_to_float(row[3 * x + 1]), d = tg_to_float(row[3 * x + 2]);
        if (a * a + b * b + d * d > 1.05f) fail("longer than unit", aov, y, x, a * a + b * b + d * d);
    }
}

static void check_outputs(const tg_frame *frame, const tg_plan *plan)
{
    int w = plan->request.width, a, y;
    tg_real *row = (tg_real *)malloc((size_t)w * 3u * sizeof(tg_real));
    uint8_t *row8 = (uint8_t *)malloc((size_t)w * 3u);
    for (a = 0; a < TG_AOV_COUNT; a++)
        if (plan->request.aovs & (1u << a))
            for (y = 0; y < plan->request.height; y++) check_row(frame, a, y, w, row, row8);
    free(row);
    free(row8);
}

/* ---- one input ---- */

/* The reference traces `samples` rays per pixel (256 when samples <= 16),
 * each costing about a hundred horizon samples. */
static double work(const tg_plan *plan, int renders)
{
    const tg_request *q = &plan->request;
    double per_pixel = (double)(q->slices > 0 ? q->slices : 1) * (q->samples > 0 ? q->samples : 1);
    if (q->technique == TG_TECH_REFERENCE) per_pixel = 100.0 * (q->samples > 16 ? q->samples : 256);
    return (double)q->width * q->height * per_pixel * (q->bounces + 1) * renders;
}

/* FUZZ_API_TRACE=1 in the environment: one line per input saying how far it got. */
static void trace(const char *what, const tg_plan *plan, const tg_error *err)
{
    static int on = -1;
    if (on < 0) on = getenv("FUZZ_API_TRACE") != NULL;
    if (!on) return;
    if (plan) fprintf(stderr, "fuzz_api: %s: %dx%d %s frames %d, %zu bytes\n", what, plan->request.width,
                      plan->request.height, tg_technique_name(plan->request.technique), plan->request.frames,
                      plan->total_bytes);
    else fprintf(stderr, "fuzz_api: %s: %s\n", what, err ? err->message : "");
}

/* The frame's colour in the case's display format, rows packed, into a
 * buffer of exactly their bytes; refused exactly when the format or the
 * flags are unknown. */
static void write_pixels(const fuzz_case *c, const tg_frame *frame, const tg_plan *plan)
{
    static const int bytes[TG_PIXEL_FORMAT_COUNT] = { 2, 2, 2, 3, 3, 4, 4, 1 };
    int known = c->format >= 0 && c->format < TG_PIXEL_FORMAT_COUNT && (c->flags & ~TG_PIXELS_DITHER) == 0;
    size_t row = (size_t)plan->request.width * (size_t)(known ? bytes[c->format] : 4);
    uint8_t *dst = (uint8_t *)malloc(row * (size_t)plan->request.height);
    tg_status st = tg_frame_write_pixels(frame, TG_AOV_COLOR, 0, plan->request.height, (tg_pixel_format)c->format,
                                         c->flags, dst, row);
    if (st != (known ? TG_OK : TG_ERR_INPUT)) abort();
    free(dst);
}

static void render(const fuzz_case *c, const tg_plan *plan, unsigned char *mem, size_t size)
{
    tg_frame *frame = NULL;
    tg_error err;
    int k;
    tg_status st = tg_frame_create(plan, mem, size, &frame, &err);
    if (st != TG_OK) {
        if (st != TG_ERR_MEMORY || frame || err.bytes_needed != plan->total_bytes || size >= plan->total_bytes) abort();
        trace("no room for the frame", plan, NULL);
        return;
    }
    trace("rendered", plan, NULL);
    if (!frame) abort();
    for (k = 0; k < MAX_RENDERS; k++) {
        st = tg_frame_render(frame, c->index[k], &err);
        if (st != (c->index[k] < 0 ? TG_ERR_INPUT : TG_OK)) abort();
        check_outputs(frame, plan);
    }
    write_pixels(c, frame, plan);
}

static void run(const fuzz_case *c, const char *text, size_t n)
{
    unsigned char *block = (unsigned char *)malloc(c->offset + ARENA_BYTES);
    unsigned char *base = block + c->offset;
    tg_arena arena;
    tg_scene *scene = NULL;
    tg_error err;
    tg_io io;
    tg_plan plan;
    char msg[64];
    tg_status st;
    io.user = NULL;
    io.read_file = read_file;
    tg_arena_init(&arena, base, ARENA_BYTES);
    st = tg_scene_parse(text, n, "fuzz/api.scene", &io, &arena, &scene, &err);
    if (st != TG_OK) {
        if (scene || arena.used != 0 || tg_error_format(&err, msg, sizeof msg) < strlen(msg)) abort();
        trace("scene refused", NULL, &err);
        free(block);
        return;
    }
    st = tg_plan_make(&plan, scene, &c->q, &err);
    if (st == TG_OK) {
        tg_plan_explain(&plan, msg, sizeof msg);
        if (!request_within_limits(&c->q)) {
            if (plan_checks_fields()) {
                fprintf(stderr, "fuzz_api: tg_plan_make accepted a request past a documented limit\n");
                abort();
            }
            trace("past a limit, planned only", &plan, NULL);
        } else if (work(&plan, MAX_RENDERS) <= WORK_BUDGET) {
            render(c, &plan, base + arena.used, ARENA_BYTES - arena.used);
        } else {
            trace("too much work, planned only", &plan, NULL);
        }
    } else if (st != TG_ERR_INPUT || !err.message[0]) {
        abort();
    } else {
        trace("request refused", NULL, &err);
    }
    free(block);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reader r;
    fuzz_case c;
    char *text;
    size_t n;
    r.p = data;
    r.n = size;
    read_case(&r, &c);
    text = scene_text(&c, &r, &n);
    run(&c, text, n);
    free(text);
    return 0;
}
