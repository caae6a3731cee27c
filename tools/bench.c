/* SPDX-License-Identifier: MIT */
/*
 * bench.c - accuracy vs time.  Every technique and
 * setting is timed (median of N whole frames, hosted clock) and measured
 * against the ray-traced reference (cached per scene and radius):
 *
 *   bench run    [--size WxH] [--runs N] [--out DIR] [--ref-samples N] [--scenes a,b]
 *                [--pt-samples N] [--color-frames N] [--only ao|color|multibounce]
 *       sweep techniques x settings (samples, slices, radius) over the
 *       built-in scenes in this binary's number type; writes
 *       DIR/rows-<float|fixed>.csv, DIR/passes-<type>.md (HBIL pass
 *       breakdown, HBIL sec. 3.5), DIR/ref/ (.bin files) (reference cache) and, in
 *       the float build, DIR/contact.ppm/.png (every technique's AO beside
 *       the reference).
 *   bench report [--out DIR]
 *       read DIR/rows-*.csv, write DIR/bench.csv, DIR/bench.md (summary,
 *       frontier, the papers' claims with a verdict, full table) and
 *       DIR/bench.svg (AO RMSE against ms, one polyline per technique);
 *       with DIR/cost-*.csv (tools/bench_cost.py) also each point's
 *       instructions per pixel in bench.md and DIR/bench-cost.svg (AO RMSE
 *       against instructions per pixel).
 *   bench count  [--size WxH] [--scenes a,b]
 *       for callgrind (tools/bench_cost.py): each configuration on the
 *       curves set up as `bench run` times it, its line printed, then its
 *       timed frame rendered once in count_frame.
 *
 * Colour: every technique at its default setting (HBIL converged over
 * --color-frames frames, the others one frame; plus "reference", the
 * ray-traced AO and one-bounce near field composed like the others) against
 * the path-traced reference (technique pathtrace, --pt-samples paths per
 * pixel, default 1024, in frames of at most TG_MAX_SAMPLES paths, each
 * frame index drawing other paths; its default bounces; cached per scene):
 * colour RMSE over geometry
 * pixels with every channel clamped to [0, 1], and the energy ratio
 * sum Lo / sum Lo_ref (unclamped).  The reference is traced as two halves
 * with different seeds: their difference gives its own noise (RMSE of the
 * average), the floor under every technique's colour RMSE, and the report
 * also gives each RMSE with it removed (noise_removed).  Written to
 * DIR/color-<type>.csv; the report adds bench-color.csv, a section of
 * bench.md, bench-color.svg (colour RMSE against ms) and, from the float
 * run, contact-color.ppm/.png (every technique's colour beside the path
 * tracer's, tonemapped as the CLI's PPM).
 *
 * Multi-bounce AO: each scene under a uniform white sky alone; the path
 * tracer's E / (pi L) against the AO (ray-traced without a cut-off, and
 * GTAO's), GTAO's multi-bounce fit of it (Jimenez et al. 2016, eq. 10) and
 * RTR eq. 11.13; DIR/multibounce-<type>.csv, a section of bench.md.
 *
 * Errors are over pixels that are geometry in both the technique's frame and
 * the reference: AO RMSE and max |error|; the mean angle between bent normals
 * (degrees); near-field irradiance relative error sum|E - E_ref| / sum E_ref
 * over the three channels (techniques that gather: hbil, ssdo; and
 * "gtao+ir", GTAO's AO brightened by RTR eq. 11.12-11.13).
 *
 * Hosted tool: stdio, libm and double are fine here (not in src/).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <sys/stat.h>
#include <time.h>
#include "tinygi.h"
#include "hosted/clock.h"
#include "frame/frame_internal.h"
#include "ao/ao.h"
#include "light/tonemap.h"

#if TG_FIXED
#define NUMBER "fixed"
#else
#define NUMBER "float"
#endif

#define AOVBIT(a) (1u << (a))
#define MAX_RUNS 64
#define MAX_ROWS 4096
#define COLOR_HEADER "scene,technique,frames,number,cpu_ms,color_rmse,energy,ref_noise,ref_paths"

/* ------------------------------------------------------------------ */
/* options */

static int opt_w = 160, opt_h = 120, opt_runs = 5, opt_ref_samples = 256, opt_pt_samples = 1024, opt_color_frames = 60;
static const char *opt_out = "build/bench";
static char opt_scenes[256] = "";
static char opt_only[32] = "";     /* "": everything; "ao", "color" or "multibounce": that part alone */

static void die(const char *msg, const char *arg)
{
    fprintf(stderr, "bench: error: %s%s%s\n", msg, arg ? ": " : "", arg ? arg : "");
    exit(2);
}

static void mkdirs(const char *path)
{
    char buf[512];
    size_t i, n = strlen(path);
    if (n >= sizeof buf) die("path too long", path);
    memcpy(buf, path, n + 1);
    for (i = 1; i <= n; i++)
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            mkdir(buf, 0777);
            buf[i] = c;
        }
}

static FILE *open_out(const char *name, const char *mode)
{
    char path[600];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", opt_out, name);
    f = fopen(path, mode);
    if (!f) die("cannot write", path);
    return f;
}

/* CPU time of this process (s): on a busy shared machine the wall clock
 * also counts the time other processes held the core; the CPU clock does
 * not.  Both are reported. */
static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* ------------------------------------------------------------------ */
/* frames */

typedef struct frame_run {
    void *scene_mem, *frame_mem;
    tg_scene *scene;
    tg_plan plan;
    tg_frame *frame;
} frame_run;

static tg_scene *load_scene(const char *name, void **mem)
{
    tg_arena arena;
    tg_error err;
    tg_scene *s = NULL;
    size_t bytes = (size_t)1 << 24;
    const char *text = tg_builtin_scene(name);
    if (!text) die("no such built-in scene", name);
    *mem = malloc(bytes);
    tg_arena_init(&arena, *mem, bytes);
    if (tg_scene_parse(text, strlen(text), name, NULL, &arena, &s, &err) != TG_OK) die("scene does not parse", name);
    return s;
}

static int frame_open(frame_run *r, tg_scene *scene, const tg_request *q)
{
    tg_error err;
    memset(r, 0, sizeof *r);
    r->scene = scene;
    if (tg_plan_make(&r->plan, scene, q, &err) != TG_OK) {
        fprintf(stderr, "bench: plan: %s\n", err.message);
        return 0;
    }
    r->frame_mem = malloc(r->plan.total_bytes);
    if (!r->frame_mem || tg_frame_create(&r->plan, r->frame_mem, r->plan.total_bytes, &r->frame, &err) != TG_OK) {
        fprintf(stderr, "bench: frame: %s\n", err.message);
        return 0;
    }
    return 1;
}

static void frame_close(frame_run *r)
{
    free(r->frame_mem);
    r->frame_mem = NULL;
}

/* A whole AOV as floats (channels * w * h). */
static float *read_aov(const tg_frame *f, tg_aov aov, int w, int h)
{
    int c = tg_aov_channels(aov), y, i;
    float *out = malloc(sizeof(float) * (size_t)(w * h * c));
    tg_real *row = malloc(sizeof(tg_real) * (size_t)(w * c));
    for (y = 0; y < h; y++) {
        tg_frame_aov_row(f, aov, y, row);
        for (i = 0; i < w * c; i++) out[(size_t)y * (size_t)(w * c) + (size_t)i] = tg_to_float(row[i]);
    }
    free(row);
    return out;
}

/* What a technique's frame gives the error measures. */
typedef struct result {
    float *ao, *bent, *near;   /* near NULL when not produced */
    uint8_t *sky;
} result;

static void result_free(result *r)
{
    free(r->ao); free(r->bent); free(r->near); free(r->sky);
    memset(r, 0, sizeof *r);
}

static uint8_t *read_sky(const tg_frame *f, int n)
{
    uint8_t *s = malloc((size_t)n);
    int i;
    for (i = 0; i < n; i++) s[i] = (uint8_t)tgi_gv_is_sky(&f->full, (size_t)i);
    return s;
}

/* ------------------------------------------------------------------ */
/* the reference, cached on disk (float32 planes: ao, bent xyz, near rgb, sky) */

static tg_request base_request(tg_technique t, int slices, int samples, double radius, uint32_t aovs)
{
    tg_request q;
    tg_request_defaults(&q);
    q.width = opt_w;
    q.height = opt_h;
    q.frames = 1;
    q.technique = t;
    q.slices = slices;
    q.samples = samples;
    q.radius = radius < 0 ? TG_R(-1.0f) : tg_from_float((float)radius);
    q.aovs = aovs;
    return q;
}

static double scene_radius(tg_scene *s)
{
    tg_plan p;
    tg_error err;
    tg_request q = base_request(TG_TECH_HBIL, 0, 0, -1, AOVBIT(TG_AOV_AO));
    if (tg_plan_make(&p, s, &q, &err) != TG_OK) die("plan", err.message);
    return (double)tg_to_float(p.request.radius);
}

static int load_reference(const char *path, result *r, int n)
{
    FILE *f = fopen(path, "rb");
    float *sky;
    int i, ok;
    if (!f) return 0;
    r->ao = malloc(sizeof(float) * (size_t)n);
    r->bent = malloc(sizeof(float) * (size_t)n * 3);
    r->near = malloc(sizeof(float) * (size_t)n * 3);
    sky = malloc(sizeof(float) * (size_t)n);
    ok = fread(r->ao, sizeof(float), (size_t)n, f) == (size_t)n &&
         fread(r->bent, sizeof(float), (size_t)n * 3, f) == (size_t)n * 3 &&
         fread(r->near, sizeof(float), (size_t)n * 3, f) == (size_t)n * 3 &&
         fread(sky, sizeof(float), (size_t)n, f) == (size_t)n;
    fclose(f);
    r->sky = malloc((size_t)n);
    for (i = 0; i < n; i++) r->sky[i] = sky[i] != 0.0f;
    free(sky);
    if (!ok) result_free(r);
    return ok;
}

static void reference(tg_scene *s, const char *name, double radius, result *r)
{
    char path[700];
    int n = opt_w * opt_h, i;
    frame_run fr;
    tg_error err;
    tg_request q;
    FILE *f;
    double t0;
    snprintf(path, sizeof path, "%s/ref/%s-%dx%d-r%.4f-s%d.bin", opt_out, name, opt_w, opt_h, radius, opt_ref_samples);
    if (load_reference(path, r, n)) return;
    q = base_request(TG_TECH_REFERENCE, 0, opt_ref_samples, radius,
                     AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_BENT) | AOVBIT(TG_AOV_NEAR));
    if (!frame_open(&fr, s, &q)) die("reference frame", name);
    t0 = tgp_clock_seconds();
    tg_frame_render(fr.frame, 0, &err);
    printf("  reference %s radius %.3f: %.0f ms\n", name, radius, (tgp_clock_seconds() - t0) * 1e3);
    fflush(stdout);
    r->ao = read_aov(fr.frame, TG_AOV_AO, opt_w, opt_h);
    r->bent = read_aov(fr.frame, TG_AOV_BENT, opt_w, opt_h);
    if (tgi_gr_has_near(&fr.frame->out)) r->near = read_aov(fr.frame, TG_AOV_NEAR, opt_w, opt_h);
    else r->near = calloc((size_t)n * 3, sizeof(float));
    r->sky = read_sky(fr.frame, n);
    frame_close(&fr);
    mkdirs(opt_out);
    {
        char dir[620];
        snprintf(dir, sizeof dir, "%s/ref", opt_out);
        mkdirs(dir);
    }
    f = fopen(path, "wb");
    if (!f) die("cannot write", path);
    fwrite(r->ao, sizeof(float), (size_t)n, f);
    fwrite(r->bent, sizeof(float), (size_t)n * 3, f);
    fwrite(r->near, sizeof(float), (size_t)n * 3, f);
    for (i = 0; i < n; i++) {
        float v = (float)r->sky[i];
        fwrite(&v, sizeof v, 1, f);
    }
    fclose(f);
}

/* ------------------------------------------------------------------ */
/* errors against the reference */

typedef struct errors {
    double ao_rmse, ao_max, bent_deg, near_rel;   /* near_rel NAN: not produced */
} errors;

static errors measure(const result *t, const result *ref, int n)
{
    errors e;
    double se = 0, mx = 0, ang = 0, dn = 0, sn = 0;
    long count = 0;
    int i, c;
    for (i = 0; i < n; i++) {
        double d, dot, la, lb;
        if (t->sky[i] || ref->sky[i]) continue;
        d = (double)t->ao[i] - (double)ref->ao[i];
        se += d * d;
        if (fabs(d) > mx) mx = fabs(d);
        dot = 0; la = 0; lb = 0;
        for (c = 0; c < 3; c++) {
            dot += (double)t->bent[3 * i + c] * (double)ref->bent[3 * i + c];
            la += (double)t->bent[3 * i + c] * (double)t->bent[3 * i + c];
            lb += (double)ref->bent[3 * i + c] * (double)ref->bent[3 * i + c];
        }
        if (la > 0 && lb > 0) {
            dot /= sqrt(la * lb);
            if (dot > 1) dot = 1;
            if (dot < -1) dot = -1;
            ang += acos(dot) * 180.0 / 3.14159265358979;
        }
        if (t->near)
            for (c = 0; c < 3; c++) {
                dn += fabs((double)t->near[3 * i + c] - (double)ref->near[3 * i + c]);
                sn += fabs((double)ref->near[3 * i + c]);
            }
        count++;
    }
    e.ao_rmse = count ? sqrt(se / (double)count) : 0;
    e.ao_max = mx;
    e.bent_deg = count ? ang / (double)count : 0;
    e.near_rel = (t->near && sn > 0) ? dn / sn : (double)NAN;
    return e;
}

/* ------------------------------------------------------------------ */
/* the sweep */

typedef struct config {
    const char *label;       /* curve name in the table and plot */
    tg_technique tech;
    int slices, samples;
    double rscale;           /* radius = scene radius * rscale */
    int interleave, near;    /* near: ask for the near field (gathering techniques) */
    int gi_scale;            /* HBIL: 2 quarter resolution (--gi-quarter), 1 every pixel (default) */
    int is_default, on_curve;
} config;

/* The request's depth layers for a curve: "ssilvb-3l" is the visibility
 * bitmask with the G-buffer's back faces and the surfaces behind them,
 * "hbil-3l" HBIL over them (its kernel that bitmask, at full resolution);
 * "hbil-ao" HBIL's AO alone as a user gets it, the plan's layers (two in a
 * scene with an environment) and samples (0: its default); the others one. */
static int label_layers(const char *label)
{
    if (strcmp(label, "hbil-ao") == 0) return 0;
    return strcmp(label, "ssilvb-3l") == 0 || strcmp(label, "hbil-3l") == 0 ? 3 : 1;
}

#define MAXCFG 96
static config cfgs[MAXCFG];
static int ncfg;

static void add(const char *label, tg_technique t, int slices, int samples, double rscale, int near, int on_curve)
{
    config *c = &cfgs[ncfg++];
    c->label = label; c->tech = t; c->slices = slices; c->samples = samples; c->rscale = rscale;
    c->interleave = strcmp(label, "hbil-full") != 0;
    c->gi_scale = strcmp(label, "hbil") == 0 ? 2 : 1;
    c->near = near;
    c->is_default = slices == TG_DEFAULT_SLICES && (samples == TG_DEFAULT_SAMPLES || samples == 0) && rscale == 1.0;
    c->on_curve = on_curve;
}

static void build_sweep(void)
{
    static const int ss[][2] = { {1, 4}, {1, 8}, {2, 8}, {2, 16}, {2, 32}, {4, 32} };
    static const int ssao_n[] = { 4, 8, 12, 16, 32, 64 }, vo_n[] = { 3, 5, 7, 9, 16, 32 };
    static const int ssdo_n[] = { 4, 8, 16, 32, 64 }, bc_n[] = { 4, 8, 16, 32 };
    static const double rs[] = { 0.5, 2.0 };
    int i;
    ncfg = 0;
    for (i = 0; i < 6; i++) add("hbil", TG_TECH_HBIL, ss[i][0], ss[i][1], 1.0, 1, 1);
    add("hbil-1x", TG_TECH_HBIL, 1, 8, 1.0, 1, 1);
    add("hbil-1x", TG_TECH_HBIL, 2, 16, 1.0, 1, 1);
    add("hbil-1x", TG_TECH_HBIL, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, 1.0, 1, 1);
    add("hbil-full", TG_TECH_HBIL, 1, 8, 1.0, 1, 1);
    add("hbil-full", TG_TECH_HBIL, 2, 16, 1.0, 1, 1);
    add("hbil-full", TG_TECH_HBIL, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, 1.0, 1, 1);
    /* HBIL over three depth layers (request.depth_layers 3) */
    add("hbil-3l", TG_TECH_HBIL, 1, 8, 1.0, 1, 1);
    add("hbil-3l", TG_TECH_HBIL, 2, 16, 1.0, 1, 1);
    add("hbil-3l", TG_TECH_HBIL, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, 1.0, 1, 1);
    /* HBIL's AO alone as `--aov ao` plans it (no near field asked: the
     * plan's depth layers and samples) */
    add("hbil-ao", TG_TECH_HBIL, TG_DEFAULT_SLICES, 0, 1.0, 0, 1);
    for (i = 0; i < 6; i++) add("gtao", TG_TECH_GTAO, ss[i][0], ss[i][1], 1.0, 0, 1);
    for (i = 0; i < 6; i++) add("hbao", TG_TECH_HBAO, ss[i][0], ss[i][1], 1.0, 0, 1);
    for (i = 0; i < 6; i++) add("ssao", TG_TECH_SSAO, 2, ssao_n[i], 1.0, 0, 1);
    for (i = 0; i < 6; i++) add("vo", TG_TECH_VO, 2, vo_n[i], 1.0, 0, 1);
    for (i = 0; i < 5; i++) add("ssdo", TG_TECH_SSDO, 2, ssdo_n[i], 1.0, 1, 1);
    for (i = 0; i < 4; i++) add("bentcone", TG_TECH_BENTCONE, 2, bc_n[i], 1.0, 0, 1);
    /* the visibility bitmask (Therrien et al. 2023): GTAO's slices and samples, the default thickness */
    for (i = 0; i < 6; i++) add("ssilvb", TG_TECH_SSILVB, ss[i][0], ss[i][1], 1.0, 1, 1);
    /* ... with three depth layers (request.depth_layers 3) */
    for (i = 0; i < 6; i++) add("ssilvb-3l", TG_TECH_SSILVB, ss[i][0], ss[i][1], 1.0, 1, 1);
    /* Ritschel table 1: directional occlusion alone (no bounce) */
    add("ssdo-do", TG_TECH_SSDO, 2, 8, 1.0, 0, 0);
    add("ssdo-do", TG_TECH_SSDO, 2, 16, 1.0, 0, 0);
    /* RTR eq. 11.12-11.13 on GTAO's AO, as a near-field estimate */
    add("gtao+ir", TG_TECH_GTAO, 2, 16, 1.0, 0, 0);
    /* radius: half and double the scene's, at the default setting */
    for (i = 0; i < 2; i++) {
        add("hbil", TG_TECH_HBIL, 2, 16, rs[i], 1, 0);
        add("gtao", TG_TECH_GTAO, 2, 16, rs[i], 0, 0);
        add("hbao", TG_TECH_HBAO, 2, 16, rs[i], 0, 0);
        add("ssao", TG_TECH_SSAO, 2, 16, rs[i], 0, 0);
        add("vo", TG_TECH_VO, 2, 16, rs[i], 0, 0);
        add("ssdo", TG_TECH_SSDO, 2, 16, rs[i], 1, 0);
        add("bentcone", TG_TECH_BENTCONE, 2, 16, rs[i], 0, 0);
        add("ssilvb", TG_TECH_SSILVB, 2, 16, rs[i], 1, 0);
    }
}

/* RTR eq. 11.12-11.13 as a near-field irradiance: the blocked directions
 * (1 - k_A) see the point's own outgoing radiance, summed over bounces,
 * E_total = E_direct k'_A / k_A, so E_near = E_direct (k'_A / k_A - 1). */
static float *interreflection_near(const tg_frame *f, int w, int h)
{
    int n = w * h, i, c;
    float *ao = read_aov(f, TG_AOV_AO, w, h), *ed = read_aov(f, TG_AOV_DIRECT, w, h);
    float *alb = read_aov(f, TG_AOV_ALBEDO, w, h), *out = malloc(sizeof(float) * (size_t)n * 3);
    for (i = 0; i < n; i++)
        for (c = 0; c < 3; c++) {
            float k = ao[i] > 1e-3f ? ao[i] : 1e-3f;
            float kp = tg_to_float(tgi_ao_interreflection(tg_from_float(k), tg_from_float(alb[3 * i + c])));
            out[3 * i + c] = ed[3 * i + c] * (kp / k - 1.0f);
        }
    free(ao); free(ed); free(alb);
    return out;
}

/* The request of one configuration (the timed run and the count alike). */
static tg_request config_request(const config *c, double radius)
{
    uint32_t aovs = AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_BENT);
    tg_request q;
    if (c->near) aovs |= AOVBIT(TG_AOV_NEAR);
    if (strcmp(c->label, "gtao+ir") == 0) aovs |= AOVBIT(TG_AOV_DIRECT) | AOVBIT(TG_AOV_ALBEDO);
    q = base_request(c->tech, c->slices, c->samples, radius, aovs);
    q.interleave = c->interleave;
    q.gi_scale = c->gi_scale;
    q.depth_layers = label_layers(c->label);
    return q;
}

/* Time one configuration: warm up, read the outputs, then opt_runs frames. */
static double run_config(tg_scene *s, const config *c, double radius, result *out, double *cpu_ms)
{
    double u[MAX_RUNS];
    frame_run fr;
    tg_error err;
    double t[MAX_RUNS];
    int k, n = opt_w * opt_h, ir = strcmp(c->label, "gtao+ir") == 0;
    tg_request q = config_request(c, radius);
    if (!frame_open(&fr, s, &q)) die("frame", c->label);
    tg_frame_render(fr.frame, 0, &err);
    memset(out, 0, sizeof *out);
    out->ao = read_aov(fr.frame, TG_AOV_AO, opt_w, opt_h);
    out->bent = read_aov(fr.frame, TG_AOV_BENT, opt_w, opt_h);
    out->sky = read_sky(fr.frame, n);
    if (c->near && tgi_gr_has_near(&fr.frame->out)) out->near = read_aov(fr.frame, TG_AOV_NEAR, opt_w, opt_h);
    if (ir) out->near = interreflection_near(fr.frame, opt_w, opt_h);
    for (k = 0; k < opt_runs; k++) {
        double t0 = tgp_clock_seconds(), u0 = cpu_seconds();
        tg_frame_render(fr.frame, 0, &err);
        if (ir) free(interreflection_near(fr.frame, opt_w, opt_h));
        t[k] = (tgp_clock_seconds() - t0) * 1e3;
        u[k] = (cpu_seconds() - u0) * 1e3;
    }
    frame_close(&fr);
    *cpu_ms = median(u, opt_runs);
    return median(t, opt_runs);
}

/* ------------------------------------------------------------------ */
/* contact sheet: a tiny 3x5 font, PPM and an uncompressed ("stored") PNG */

static const char *glyph(char ch)
{
    switch (ch) {
    case 'a': return "010101111101101"; case 'b': return "110101110101110";
    case 'c': return "011100100100011"; case 'd': return "110101101101110";
    case 'e': return "111100110100111"; case 'f': return "111100110100100";
    case 'g': return "011100101101011"; case 'h': return "101101111101101";
    case 'i': return "111010010010111"; case 'l': return "100100100100111";
    case 'n': return "110101101101101"; case 'o': return "010101101101010";
    case 'p': return "110101110100100"; case 'r': return "110101110101101";
    case 's': return "011100010001110"; case 't': return "111010010010010";
    case 'u': return "101101101101111"; case 'v': return "101101101101010";
    case '1': return "010110010010111"; case '3': return "111001011001111";
    case 'x': return "000101010101000";
    case '-': return "000000111000000"; case '+': return "000010111010000";
    default: return "000000000000000";
    }
}

static void draw_text(uint8_t *img, int iw, int x0, int y0, const char *s, int scale)
{
    int k, gx, gy, sx, sy;
    for (k = 0; s[k]; k++) {
        const char *g = glyph(s[k]);
        for (gy = 0; gy < 5; gy++)
            for (gx = 0; gx < 3; gx++)
                if (g[gy * 3 + gx] == '1')
                    for (sy = 0; sy < scale; sy++)
                        for (sx = 0; sx < scale; sx++) {
                            size_t p = ((size_t)(y0 + gy * scale + sy) * (size_t)iw + (size_t)(x0 + (k * 4 + gx) * scale + sx)) * 3;
                            img[p] = 255; img[p + 1] = 255; img[p + 2] = 255;
                        }
    }
}

static uint32_t crc_table[256];
static uint32_t crc32_update(uint32_t c, const uint8_t *p, size_t n)
{
    size_t i;
    if (!crc_table[1]) {
        uint32_t k, v;
        int b;
        for (k = 0; k < 256; k++) {
            v = k;
            for (b = 0; b < 8; b++) v = (v & 1) ? 0xEDB88320u ^ (v >> 1) : v >> 1;
            crc_table[k] = v;
        }
    }
    for (i = 0; i < n; i++) c = crc_table[(c ^ p[i]) & 255] ^ (c >> 8);
    return c;
}

static void put32(uint8_t *p, uint32_t v) { p[0] = (uint8_t)(v >> 24); p[1] = (uint8_t)(v >> 16); p[2] = (uint8_t)(v >> 8); p[3] = (uint8_t)v; }

static void png_chunk(FILE *f, const char *type, const uint8_t *data, size_t n)
{
    uint8_t b[4];
    uint32_t crc;
    put32(b, (uint32_t)n); fwrite(b, 1, 4, f);
    fwrite(type, 1, 4, f);
    if (n) fwrite(data, 1, n, f);
    crc = crc32_update(0xFFFFFFFFu, (const uint8_t *)type, 4);
    crc = crc32_update(crc, data, n) ^ 0xFFFFFFFFu;
    put32(b, crc); fwrite(b, 1, 4, f);
}

/* PNG of an RGB image, 8-bit: greyscale (its red channel, for a grey
 * sheet) when channels is 1, RGB when 3; zlib stream of stored
 * (uncompressed) deflate blocks. */
static void write_png(FILE *f, const uint8_t *rgb, int w, int h, int channels)
{
    static const uint8_t sig[8] = { 137, 80, 78, 71, 13, 10, 26, 10 };
    size_t row = (size_t)(1 + channels * w), raw_n = (size_t)h * row, blocks = (raw_n + 65534) / 65535, zn, i, pos;
    uint8_t *raw = malloc(raw_n), *z, ihdr[13];
    uint32_t a = 1, b = 0;
    int y, x;
    for (y = 0; y < h; y++) {
        raw[(size_t)y * row] = 0;
        for (x = 0; x < w * channels; x++)
            raw[(size_t)y * row + 1 + (size_t)x] = rgb[((size_t)y * (size_t)w + (size_t)(x / channels)) * 3 + (size_t)(x % channels)];
    }
    zn = 2 + raw_n + 5 * blocks + 4;
    z = malloc(zn);
    z[0] = 0x78; z[1] = 0x01;
    pos = 2;
    for (i = 0; i < raw_n; i += 65535) {
        size_t len = raw_n - i < 65535 ? raw_n - i : 65535;
        z[pos++] = i + len == raw_n ? 1 : 0;
        z[pos++] = (uint8_t)(len & 255); z[pos++] = (uint8_t)(len >> 8);
        z[pos++] = (uint8_t)(~len & 255); z[pos++] = (uint8_t)((~len >> 8) & 255);
        memcpy(z + pos, raw + i, len);
        pos += len;
    }
    for (i = 0; i < raw_n; i++) { a = (a + raw[i]) % 65521u; b = (b + a) % 65521u; }
    put32(z + pos, (b << 16) | a);
    pos += 4;
    fwrite(sig, 1, 8, f);
    put32(ihdr, (uint32_t)w); put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8; ihdr[9] = channels == 3 ? 2 : 0; ihdr[10] = 0; ihdr[11] = 0; ihdr[12] = 0;
    png_chunk(f, "IHDR", ihdr, 13);
    png_chunk(f, "IDAT", z, pos);
    png_chunk(f, "IEND", NULL, 0);
    free(raw); free(z);
}

/* A contact sheet: tiles of opt_w x opt_h pixels in `cols` columns with
 * 2-pixel gaps, RGB, written as NAME.ppm and NAME.png (png_channels 1: the
 * grey AO sheet). */
typedef struct contact_sheet {
    const char *name;
    int cols, tiles, png_channels;
    uint8_t *px;
    int w, h;
} contact_sheet;

/* nine techniques at their default, then the reference */
static contact_sheet ao_sheet = { "contact", 5, 15, 1, NULL, 0, 0 };

/* The sheet's pixels, made on first use. */
static void sheet_make(contact_sheet *s)
{
    if (s->px) return;
    s->w = s->cols * opt_w + (s->cols + 1) * 2;
    s->h = (s->tiles / s->cols) * opt_h + (s->tiles / s->cols + 1) * 2;
    s->px = calloc((size_t)s->w * (size_t)s->h * 3, 1);
}

/* Byte offset of pixel (x, y) of tile k. */
static size_t sheet_at(const contact_sheet *s, int k, int x, int y)
{
    int x0 = 2 + (k % s->cols) * (opt_w + 2), y0 = 2 + (k / s->cols) * (opt_h + 2);
    return ((size_t)(y0 + y) * (size_t)s->w + (size_t)(x0 + x)) * 3;
}

/* Tile k's label, on black in its corner when it fits. */
static void sheet_label(const contact_sheet *s, int k, const char *label)
{
    int x, y;
    if (opt_h < 24 || (int)strlen(label) * 8 >= opt_w) return;
    for (y = 0; y < 14; y++)
        for (x = 0; x < (int)strlen(label) * 8 + 4; x++) {
            size_t p = sheet_at(s, k, x, y);
            s->px[p] = s->px[p + 1] = s->px[p + 2] = 0;
        }
    draw_text(s->px, s->w, 2 + (k % s->cols) * (opt_w + 2) + 2, 2 + (k / s->cols) * (opt_h + 2) + 2, label, 2);
}

static void sheet_write(const contact_sheet *s)
{
    char path[64];
    FILE *f;
    if (!s->px) return;
    sprintf(path, "%s.ppm", s->name);
    f = open_out(path, "wb");
    fprintf(f, "P6\n%d %d\n255\n", s->w, s->h);
    fwrite(s->px, 1, (size_t)s->w * (size_t)s->h * 3, f);
    fclose(f);
    sprintf(path, "%s.png", s->name);
    f = open_out(path, "wb");
    write_png(f, s->px, s->w, s->h, s->png_channels);
    fclose(f);
}

static void sheet_tile(int k, const float *ao, const char *label)
{
    int x, y;
    sheet_make(&ao_sheet);
    for (y = 0; y < opt_h; y++)
        for (x = 0; x < opt_w; x++) {
            float v = ao[y * opt_w + x];
            int g = (int)(255.0f * (v < 0 ? 0 : v > 1 ? 1 : v) + 0.5f);
            size_t p = sheet_at(&ao_sheet, k, x, y);
            ao_sheet.px[p] = ao_sheet.px[p + 1] = ao_sheet.px[p + 2] = (uint8_t)g;
        }
    sheet_label(&ao_sheet, k, label);
}

/* ------------------------------------------------------------------ */
/* colour against the path-traced reference */

typedef struct color_config {
    const char *label;
    tg_technique tech;
    int interleave, gi_scale, converge;   /* converge: HBIL, rendered over --color-frames frames */
} color_config;

#define COLOR_TECHS 13
static const color_config color_cfgs[COLOR_TECHS] = {
    { "hbil", TG_TECH_HBIL, 1, 2, 1 }, { "hbil-1x", TG_TECH_HBIL, 1, 1, 1 }, { "hbil-full", TG_TECH_HBIL, 0, 1, 1 },
    { "gtao", TG_TECH_GTAO, 1, 1, 0 }, { "hbao", TG_TECH_HBAO, 1, 1, 0 }, { "ssao", TG_TECH_SSAO, 1, 1, 0 },
    { "vo", TG_TECH_VO, 1, 1, 0 }, { "ssdo", TG_TECH_SSDO, 1, 1, 0 }, { "bentcone", TG_TECH_BENTCONE, 1, 1, 0 },
    { "reference", TG_TECH_REFERENCE, 1, 1, 0 }, { "ssilvb", TG_TECH_SSILVB, 1, 1, 0 },
    { "ssilvb-3l", TG_TECH_SSILVB, 1, 1, 0 }, { "hbil-3l", TG_TECH_HBIL, 1, 1, 1 }
};

typedef struct color_ref {
    float *rgb;          /* linear Lo, 3 a pixel */
    uint8_t *sky;
    double noise;        /* its own colour RMSE (clamped), from the two halves */
} color_ref;

static void color_ref_free(color_ref *r)
{
    free(r->rgb); free(r->sky);
    memset(r, 0, sizeof *r);
}

static double clamp01(double v) { return v < 0 ? 0 : v > 1 ? 1 : v; }

/* Colour RMSE with every channel clamped to [0, 1] and the energy ratio
 * sum a / sum b, over pixels that are geometry in both. */
static void color_errors(const float *a, const uint8_t *sky_a, const float *b, const uint8_t *sky_b, int n,
                         double *rmse, double *energy)
{
    double se = 0, ea = 0, eb = 0;
    long k = 0;
    int i, c;
    for (i = 0; i < n; i++) {
        if (sky_a[i] || sky_b[i]) continue;
        for (c = 0; c < 3; c++) {
            double d = clamp01((double)a[3 * i + c]) - clamp01((double)b[3 * i + c]);
            se += d * d;
            ea += (double)a[3 * i + c];
            eb += (double)b[3 * i + c];
            k++;
        }
    }
    *rmse = k ? sqrt(se / (double)k) : 0;
    *energy = eb > 0 ? ea / eb : 0;
}

static int load_color_ref(const char *path, color_ref *r, int n)
{
    FILE *f = fopen(path, "rb");
    int ok;
    if (!f) return 0;
    r->rgb = malloc(sizeof(float) * (size_t)n * 3);
    r->sky = malloc((size_t)n);
    ok = fread(r->rgb, sizeof(float), (size_t)n * 3, f) == (size_t)n * 3 && fread(r->sky, 1, (size_t)n, f) == (size_t)n &&
         fread(&r->noise, sizeof r->noise, 1, f) == 1;
    fclose(f);
    if (!ok) color_ref_free(r);
    return ok;
}

/* The mean colour of frames [f0, f0 + count) of an open path-tracing frame
 * (each frame index draws other paths), malloc'd. */
static float *path_traced_mean(frame_run *fr, int f0, int count)
{
    int n = opt_w * opt_h, i, k;
    tg_error err;
    float *sum = NULL;
    for (k = 0; k < count; k++) {
        float *c;
        tg_frame_render(fr->frame, f0 + k, &err);
        c = read_aov(fr->frame, TG_AOV_COLOR, opt_w, opt_h);
        if (!sum) { sum = c; continue; }
        for (i = 0; i < 3 * n; i++) sum[i] += c[i];
        free(c);
    }
    for (i = 0; i < 3 * n; i++) sum[i] /= (float)count;
    return sum;
}

/* The path tracer's colour for a scene, as two halves of --pt-samples paths
 * (each half frames of at most TG_MAX_SAMPLES paths, every frame index
 * drawing other paths), averaged; cached. */
static void color_reference(tg_scene *s, const char *name, color_ref *r)
{
    char path[700], dir[620];
    int n = opt_w * opt_h, i, half = opt_pt_samples / 2;
    int per_frame = half < TG_MAX_SAMPLES ? half : TG_MAX_SAMPLES, frames = half / per_frame;
    frame_run fr;
    tg_request q;
    float *a, *b;
    double t0, e;
    FILE *f;
    snprintf(path, sizeof path, "%s/ref/%s-%dx%d-pt%d.bin", opt_out, name, opt_w, opt_h, opt_pt_samples);
    if (load_color_ref(path, r, n)) return;
    q = base_request(TG_TECH_PATHTRACE, 0, per_frame, -1, AOVBIT(TG_AOV_COLOR));
    if (!frame_open(&fr, s, &q)) die("path-traced reference frame", name);
    t0 = cpu_seconds();
    a = path_traced_mean(&fr, 0, frames);
    b = path_traced_mean(&fr, frames, frames);
    r->sky = read_sky(fr.frame, n);
    printf("  path-traced reference %s (%d paths, %d bounces): %.0f ms CPU\n", name, 2 * half,
           fr.plan.request.bounces, (cpu_seconds() - t0) * 1e3);
    fflush(stdout);
    frame_close(&fr);
    color_errors(a, r->sky, b, r->sky, n, &r->noise, &e);
    r->noise *= 0.5;   /* the halves differ by twice the average's noise (in RMS) */
    r->rgb = a;
    for (i = 0; i < 3 * n; i++) a[i] = 0.5f * (a[i] + b[i]);
    free(b);
    snprintf(dir, sizeof dir, "%s/ref", opt_out);
    mkdirs(dir);
    f = fopen(path, "wb");
    if (!f) die("cannot write", path);
    fwrite(r->rgb, sizeof(float), (size_t)n * 3, f);
    fwrite(r->sky, 1, (size_t)n, f);
    fwrite(&r->noise, sizeof r->noise, 1, f);
    fclose(f);
}

/* The colour sheet: every technique's colour and the path tracer's,
 * tonemapped as the CLI's PPM (exposure 1). */
static contact_sheet color_sheet = { "contact-color", 5, 15, 3, NULL, 0, 0 };

static void color_tile(int k, const float *rgb, const char *label)
{
    int x, y, c;
    sheet_make(&color_sheet);
    for (y = 0; y < opt_h; y++)
        for (x = 0; x < opt_w; x++)
            for (c = 0; c < 3; c++) {
                size_t p = sheet_at(&color_sheet, k, x, y);
                color_sheet.px[p + (size_t)c] = tgi_tonemap8(tg_from_float(rgb[3 * (y * opt_w + x) + c]));
            }
    sheet_label(&color_sheet, k, label);
}

/* One technique's colour: converged (HBIL: --color-frames frames in
 * sequence), then opt_runs more frames timed.  Returns the colour.  The
 * radius is the one the plan gives the request, as a user gets it (over
 * further depth layers a scene without its own gets a longer one). */
static float *color_run(tg_scene *s, const color_config *c, double *cpu_ms)
{
    double u[MAX_RUNS];
    frame_run fr;
    tg_error err;
    tg_request q = base_request(c->tech, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, -1, AOVBIT(TG_AOV_COLOR));
    int k, frames = c->converge ? opt_color_frames : 1;
    float *rgb;
    q.frames = frames + opt_runs;
    q.interleave = c->interleave;
    q.gi_scale = c->gi_scale;
    q.depth_layers = label_layers(c->label);
    if (c->tech == TG_TECH_REFERENCE) q.samples = opt_ref_samples;
    if (!frame_open(&fr, s, &q)) die("colour frame", c->label);
    for (k = 0; k < frames; k++) tg_frame_render(fr.frame, k, &err);
    rgb = read_aov(fr.frame, TG_AOV_COLOR, opt_w, opt_h);
    for (k = 0; k < opt_runs; k++) {
        double u0 = cpu_seconds();
        tg_frame_render(fr.frame, frames + k, &err);
        u[k] = (cpu_seconds() - u0) * 1e3;
    }
    frame_close(&fr);
    *cpu_ms = median(u, opt_runs);
    return rgb;
}

/* Every technique's colour on one scene against the path tracer's. */
static void color_rows(tg_scene *s, const char *name, FILE *csv, int tiles)
{
    int k, n = opt_w * opt_h;
    color_ref ref;
    uint8_t *sky;
    color_reference(s, name, &ref);
    {   /* any technique's frame has the same sky */
        frame_run fr;
        tg_request q = base_request(TG_TECH_SSAO, 2, 4, -1, AOVBIT(TG_AOV_AO));
        tg_error err;
        if (!frame_open(&fr, s, &q)) die("frame", name);
        tg_frame_render(fr.frame, 0, &err);
        sky = read_sky(fr.frame, n);
        frame_close(&fr);
    }
    for (k = 0; k < COLOR_TECHS; k++) {
        const color_config *c = &color_cfgs[k];
        double cpu, rmse, energy;
        float *rgb = color_run(s, c, &cpu);
        color_errors(rgb, sky, ref.rgb, ref.sky, n, &rmse, &energy);
        fprintf(csv, "%s,%s,%d,%s,%.4f,%.6f,%.6f,%.6f,%d\n", name, c->label, c->converge ? opt_color_frames : 1, NUMBER, cpu,
                rmse, energy, ref.noise, 2 * (opt_pt_samples / 2));
        fflush(csv);
        printf("  colour %-9s %3d frame%s %8.2f ms (cpu)  RMSE %.4f  energy %.3f  (reference noise %.4f)\n", c->label,
               c->converge ? opt_color_frames : 1, c->converge && opt_color_frames > 1 ? "s" : " ", cpu, rmse, energy, ref.noise);
        fflush(stdout);
        if (tiles) color_tile(k, rgb, c->label);
        free(rgb);
    }
    if (tiles) color_tile(COLOR_TECHS, ref.rgb, "pathtrace");
    free(sky);
    color_ref_free(&ref);
}

/* ------------------------------------------------------------------ */
/* multi-bounce AO (GTAO eq. 10) against the path tracer under a white sky */

#define MB_HEADER "scene,ao,number,plain_rmse,multibounce_rmse,interreflection_rmse,plain_bias,multibounce_bias"

/* The scene lit by a uniform white sky alone: its lights, environment and
 * emission dropped (malloc'd). */
static char *white_sky_text(const char *text)
{
    size_t n = strlen(text);
    char *out = malloc(n + 32), *o = out, line[4096];
    const char *p = text;
    while (*p) {
        const char *e = strchr(p, '\n');
        size_t len = e ? (size_t)(e - p) + 1 : strlen(p);
        char *m;
        if (len >= sizeof line) die("scene line too long", NULL);
        memcpy(line, p, len);
        line[len] = '\0';
        p += len;
        if (!strncmp(line, "light", 5) || !strncmp(line, "env", 3)) continue;
        if ((m = strstr(line, "emissive")) != NULL) {   /* "emissive R G B": four words out */
            char *q = m;
            int w;
            for (w = 0; w < 4; w++) {
                while (*q == ' ') q++;
                while (*q && *q != ' ' && *q != '\n') q++;
            }
            memmove(m, q, strlen(q) + 1);
        }
        memcpy(o, line, strlen(line));
        o += strlen(line);
    }
    strcpy(o, "\nenv uniform 1 1 1\n");
    return out;
}

static tg_scene *parse_text(const char *text, const char *name, void **mem)
{
    tg_arena arena;
    tg_error err;
    tg_scene *s = NULL;
    size_t bytes = (size_t)1 << 24;
    *mem = malloc(bytes);
    tg_arena_init(&arena, *mem, bytes);
    if (tg_scene_parse(text, strlen(text), name, NULL, &arena, &s, &err) != TG_OK) die("scene does not parse", err.message);
    return s;
}

/* One frame's AOV (and the sky, the albedo when asked) of technique t. */
static float *render_aov(tg_scene *s, tg_technique t, int samples, double radius, tg_aov aov, uint8_t **sky, float **albedo)
{
    frame_run fr;
    tg_error err;
    tg_request q = base_request(t, 2, samples, radius, AOVBIT(aov) | AOVBIT(TG_AOV_ALBEDO));
    float *v;
    if (!frame_open(&fr, s, &q)) die("frame", tg_technique_name(t));
    tg_frame_render(fr.frame, 0, &err);
    v = read_aov(fr.frame, aov, opt_w, opt_h);
    if (sky) *sky = read_sky(fr.frame, opt_w * opt_h);
    if (albedo) *albedo = read_aov(fr.frame, TG_AOV_ALBEDO, opt_w, opt_h);
    frame_close(&fr);
    return v;
}

/* AO, the fit and RTR eq. 11.13 against E / (pi L) of the path tracer. */
static void multibounce_errors(const float *ao, const float *albedo, const float *kref, const uint8_t *sky, double out[5])
{
    double s[5] = { 0, 0, 0, 0, 0 };
    long k = 0;
    int i, c, n = opt_w * opt_h;
    for (i = 0; i < n; i++) {
        if (sky[i]) continue;
        for (c = 0; c < 3; c++) {
            tg_real a = tg_from_float(ao[i]), rho = tg_from_float(albedo[3 * i + c]);
            double want = (double)kref[3 * i + c], plain = (double)ao[i] - want;
            double mb = (double)tg_to_float(tgi_ao_multibounce(a, rho)) - want;
            double ir = (double)tg_to_float(tgi_ao_interreflection(a, rho)) - want;
            s[0] += plain * plain; s[1] += mb * mb; s[2] += ir * ir; s[3] += plain; s[4] += mb;
            k++;
        }
    }
    for (c = 0; c < 5; c++) out[c] = k ? s[c] / (double)k : 0;
    for (c = 0; c < 3; c++) out[c] = sqrt(out[c]);
}

static void multibounce_rows(const char *name, double radius, FILE *csv)
{
    void *mem;
    char *text = white_sky_text(tg_builtin_scene(name));
    tg_scene *s = parse_text(text, name, &mem);
    int i, n = opt_w * opt_h, src;
    uint8_t *sky;
    float *albedo, *e = render_aov(s, TG_TECH_PATHTRACE, opt_pt_samples < TG_MAX_SAMPLES ? opt_pt_samples : TG_MAX_SAMPLES,
                                   -1, TG_AOV_IRRADIANCE, &sky, &albedo);
    for (i = 0; i < 3 * n; i++) e[i] = (float)((double)e[i] / 3.14159265358979);   /* E / (pi L), L = 1 */
    for (src = 0; src < 2; src++) {
        /* the ray-traced AO without a cut-off (the fit's own error), GTAO as a frame gives it */
        float *ao = src ? render_aov(s, TG_TECH_GTAO, 16, radius, TG_AOV_AO, NULL, NULL)
                        : render_aov(s, TG_TECH_REFERENCE, opt_ref_samples, TG_MAX_RADIUS, TG_AOV_AO, NULL, NULL);
        double r[5];
        multibounce_errors(ao, albedo, e, sky, r);
        fprintf(csv, "%s,%s,%s,%.6f,%.6f,%.6f,%.6f,%.6f\n", name, src ? "gtao" : "reference", NUMBER, r[0], r[1], r[2], r[3], r[4]);
        printf("  white sky, %s AO: RMSE against E/(pi L): AO %.4f, GTAO multi-bounce %.4f, RTR 11.13 %.4f (bias %+.4f, %+.4f)\n",
               src ? "gtao" : "reference", r[0], r[1], r[2], r[3], r[4]);
        fflush(stdout);
        free(ao);
    }
    free(e); free(sky); free(albedo); free(text); free(mem);
}

/* ------------------------------------------------------------------ */
/* HBIL pass breakdown (HBIL sec. 3.5): the plan's own passes (the rows of
 * the pass table the frame runs), timed one by one on a frame with history */

#define MAX_TIMED 40

/* Median ms of one pass of the plan, run as the frame runs it. */
static double time_pass(tg_frame *f, const tgi_pass *p)
{
    double t[MAX_RUNS];
    int k;
    for (k = 0; k < opt_runs; k++) {
        double t0 = cpu_seconds();
        if (p->rows == TGI_SERIAL) p->run(f);
        else p->run_rows(f, 0, tgi_pass_row_count(f, p));
        t[k] = (cpu_seconds() - t0) * 1e3;
    }
    return median(t, opt_runs);
}

/* ms of the first pass whose name starts with `prefix` (0 when none). */
static double ms_of(const tg_plan *plan, const double *ms, const char *prefix)
{
    int i;
    for (i = 0; i < plan->pass_count; i++)
        if (strncmp(plan->passes[i], prefix, strlen(prefix)) == 0) return ms[i];
    return 0;
}

static void pass_breakdown(tg_scene *s, const char *name)
{
    frame_run fr;
    tg_error err;
    tg_request q = base_request(TG_TECH_HBIL, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, -1, AOVBIT(TG_AOV_COLOR));
    double ms[MAX_TIMED], frame_ms, core, t[MAX_RUNS];
    const char *paper[4] = { "reproject", "push/pull", "4x4 split", "HBIL horizon kernel" };
    const char *paper_ms[4] = { "0.16 ms (5%)", "0.32 ms (10%)", "0.78 ms (24%)", "1.97 ms (61%)" };
    FILE *f;
    char fname[64];
    int i, k;
    q.frames = 2;   /* a second frame: reprojection has a history */
    if (!frame_open(&fr, s, &q)) die("hbil frame", name);
    tg_frame_render(fr.frame, 0, &err);
    tg_frame_render(fr.frame, 1, &err);
    for (k = 0; k < opt_runs; k++) {
        double t0 = cpu_seconds();
        tg_frame_render(fr.frame, 1, &err);
        t[k] = (cpu_seconds() - t0) * 1e3;
    }
    frame_ms = median(t, opt_runs);
    for (i = 0; i < fr.plan.pass_count && i < MAX_TIMED; i++)
        ms[i] = time_pass(fr.frame, &tgi_passes[fr.plan.pass_rows[i]]);
    core = 0;
    for (k = 0; k < 4; k++) core += ms_of(&fr.plan, ms, paper[k]);
    snprintf(fname, sizeof fname, "passes-%s.md", NUMBER);
    f = open_out(fname, "w");
    fprintf(f, "HBIL pass breakdown, %s, scene %s, %dx%d, %d slices x %d samples, median of %d (CPU ms of every pass of the plan, in the order the frame runs them; the share of the four passes HBIL sec. 3.5 lists, and the paper's GTX 680 at 1280x720, in the last columns):\n\n",
            NUMBER, name, opt_w, opt_h, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, opt_runs);
    fprintf(f, "| pass | ms (%s) | share | paper |\n|---|---:|---:|---:|\n", NUMBER);
    for (i = 0; i < fr.plan.pass_count && i < MAX_TIMED; i++) {
        int p = -1;
        for (k = 0; k < 4; k++)
            if (strncmp(fr.plan.passes[i], paper[k], strlen(paper[k])) == 0) p = k;
        if (p >= 0) fprintf(f, "| %s | %.3f | %.0f%% | %s |\n", fr.plan.passes[i], ms[i], 100 * ms[i] / core, paper_ms[p]);
        else fprintf(f, "| %s | %.3f | | |\n", fr.plan.passes[i], ms[i]);
    }
    fprintf(f, "| whole frame (tg_frame_render) | %.3f | | 3.23 ms (GI only) |\n\n", frame_ms);
    fprintf(f, "Verdict (%s): %s the kernel is %.0f%% of reprojection + push/pull + split + kernel (paper 61%%); the split is %.0f%% (paper 24%%).\n\n",
            NUMBER, ms_of(&fr.plan, ms, paper[3]) / core > 0.5 ? "HOLDS, the kernel dominates:" : "DOES NOT HOLD, the kernel does not dominate:",
            100 * ms_of(&fr.plan, ms, paper[3]) / core, 100 * ms_of(&fr.plan, ms, paper[2]) / core);
    fclose(f);
    printf("  passes (%s):", NUMBER);
    for (i = 0; i < fr.plan.pass_count && i < MAX_TIMED; i++) printf(" %.3f", ms[i]);
    printf(" ms; frame %.3f ms\n", frame_ms);
    frame_close(&fr);
}

/* ------------------------------------------------------------------ */
/* bench run */

static int scene_wanted(const char *name)
{
    const char *p = opt_scenes;
    size_t n = strlen(name);
    if (!*p) return 1;
    while (*p) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && strncmp(p, name, n) == 0) return 1;
        p += len + (e ? 1 : 0);
    }
    return 0;
}

static int cmd_run(void)
{
    char fname[64];
    FILE *csv, *ccsv, *mcsv;
    int si, ci, n = opt_w * opt_h, sheet_k = 0;
    const char *name, *sheet_scene = scene_wanted("columns") ? "columns" : NULL;
    const char *color_scene = scene_wanted("cornell") ? "cornell" : NULL;
    build_sweep();
    mkdirs(opt_out);
    snprintf(fname, sizeof fname, "rows-%s.csv", NUMBER);
    csv = open_out(fname, "w");
    fprintf(csv, "scene,technique,slices,samples,radius,interleave,number,median_ms,cpu_ms,ao_rmse,ao_max,bent_deg,near_rel,default,curve\n");
    snprintf(fname, sizeof fname, "color-%s.csv", NUMBER);
    ccsv = open_out(fname, "w");
    fprintf(ccsv, COLOR_HEADER "\n");
    snprintf(fname, sizeof fname, "multibounce-%s.csv", NUMBER);
    mcsv = open_out(fname, "w");
    fprintf(mcsv, MB_HEADER "\n");
    for (si = 0; (name = tg_builtin_name(si)) != NULL; si++) {
        void *mem;
        tg_scene *s;
        double r0;
        if (!scene_wanted(name)) continue;
        if (!sheet_scene) sheet_scene = name;
        s = load_scene(name, &mem);
        r0 = scene_radius(s);
        printf("%s (%s, radius %.3f, %dx%d, %d runs)\n", name, NUMBER, r0, opt_w, opt_h, opt_runs);
        fflush(stdout);
        for (ci = 0; ci < ncfg && (!*opt_only || !strcmp(opt_only, "ao")); ci++) {
            const config *c = &cfgs[ci];
            double radius = r0 * c->rscale, ms, cpu;
            result ref, res;
            errors e;
            reference(s, name, radius, &ref);
            ms = run_config(s, c, radius, &res, &cpu);
            e = measure(&res, &ref, n);
            fprintf(csv, "%s,%s,%d,%d,%.4f,%d,%s,%.4f,%.4f,%.6f,%.6f,%.4f,", name, c->label, c->slices, c->samples,
                    radius, c->interleave, NUMBER, ms, cpu, e.ao_rmse, e.ao_max, e.bent_deg);
            if (isnan(e.near_rel)) fprintf(csv, ","); else fprintf(csv, "%.6f,", e.near_rel);
            fprintf(csv, "%d,%d\n", c->is_default, c->on_curve);
            fflush(csv);
            printf("  %-9s s%d n%-2d r%.2f %8.2f ms (cpu %.2f)  AO rmse %.4f max %.3f  bent %5.2f deg  near %s%.3f\n",
                   c->label, c->slices, c->samples, radius, ms, cpu, e.ao_rmse, e.ao_max, e.bent_deg,
                   isnan(e.near_rel) ? "-" : "", isnan(e.near_rel) ? 0.0 : e.near_rel);
            fflush(stdout);
            if (!strcmp(NUMBER, "float") && sheet_scene && strcmp(name, sheet_scene) == 0 && c->is_default && c->on_curve && sheet_k < ao_sheet.tiles - 1)
                sheet_tile(sheet_k++, res.ao, c->label);
            if (!strcmp(NUMBER, "float") && sheet_scene && strcmp(name, sheet_scene) == 0 && ci == ncfg - 1)
                sheet_tile(sheet_k, ref.ao, "reference");
            result_free(&res);
            result_free(&ref);
        }
        if ((!*opt_only || !strcmp(opt_only, "ao")) && (strcmp(name, "cornell") == 0 || (!scene_wanted("cornell") && strcmp(name, sheet_scene) == 0)))
            pass_breakdown(s, name);
        if (!color_scene) color_scene = name;
        if (strcmp(opt_only, "multibounce") && strcmp(opt_only, "ao"))
            color_rows(s, name, ccsv, !strcmp(NUMBER, "float") && strcmp(name, color_scene) == 0);
        if (strcmp(opt_only, "color") && strcmp(opt_only, "ao")) multibounce_rows(name, r0, mcsv);
        free(mem);
    }
    fclose(csv);
    fclose(ccsv);
    fclose(mcsv);
    sheet_write(&ao_sheet);
    sheet_write(&color_sheet);
    return 0;
}

/* ------------------------------------------------------------------ */
/* bench count: the frame each timed run times, once per configuration on
 * the curves, for callgrind (tools/bench_cost.py runs this under
 * `valgrind --tool=callgrind --collect-atstart=no --toggle-collect=count_frame
 * --dump-after=count_frame`: one profile per call, in the order of the
 * lines printed) */

#if defined(__GNUC__)
__attribute__((noinline))
#endif
void count_frame(tg_frame *f);
void count_frame(tg_frame *f)
{
    tg_error err;
    if (tg_frame_render(f, 0, &err) != TG_OK) die("render", err.message);
}

static int cmd_count(void)
{
    int si, ci;
    const char *name;
    build_sweep();
    for (si = 0; (name = tg_builtin_name(si)) != NULL; si++) {
        void *mem;
        tg_scene *s;
        double r0;
        if (!scene_wanted(name)) continue;
        s = load_scene(name, &mem);
        r0 = scene_radius(s);
        for (ci = 0; ci < ncfg; ci++) {
            const config *c = &cfgs[ci];
            tg_request q;
            frame_run fr;
            tg_error err;
            if (!c->on_curve) continue;
            q = config_request(c, r0 * c->rscale);
            if (!frame_open(&fr, s, &q)) die("frame", c->label);
            tg_frame_render(fr.frame, 0, &err);   /* as run_config: the timed frames follow a first */
            printf("count: %s,%s,%d,%d,%s,%d\n", name, c->label, c->slices, c->samples, NUMBER, opt_w * opt_h);
            fflush(stdout);
            count_frame(fr.frame);
            frame_close(&fr);
        }
        free(mem);
    }
    return 0;
}

/* ------------------------------------------------------------------ */
/* bench report */

typedef struct row {
    char scene[32], tech[32], number[8];
    int slices, samples, interleave, is_default, on_curve;
    double radius, ms, cpu, ao_rmse, ao_max, bent_deg, near_rel;
} row;

static row rows[MAX_ROWS];
static int nrows;

/* DIR/<kind>-<number>.csv, read past its header line; NULL when it is
 * missing or empty. */
static FILE *open_rows(const char *kind, const char *number)
{
    char path[600], line[512];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s-%s.csv", opt_out, kind, number);
    f = fopen(path, "r");
    if (f && !fgets(line, sizeof line, f)) {
        fclose(f);
        f = NULL;
    }
    return f;
}

/* The rows of DIR/<kind>-<number>.csv into a table of *count (at most
 * MAX_ROWS) rows: parse_row(line, i) fills row i, 1 when the line is one. */
static void read_csv(const char *kind, const char *number, int *count, int (*parse_row)(char *line, int i))
{
    char line[512];
    FILE *f = open_rows(kind, number);
    if (!f) return;
    while (*count < MAX_ROWS && fgets(line, sizeof line, f))
        if (parse_row(line, *count)) ++*count;
    fclose(f);
}

static int parse_row(char *line, int i)
{
    row *r = &rows[i];
    char *fld[16], *p = line;
    int k = 0;
    line[strcspn(line, "\r\n")] = '\0';
    while (k < 16) {
        fld[k++] = p;
        p = strchr(p, ',');
        if (!p) break;
        *p++ = '\0';
    }
    if (k != 15) return 0;
    snprintf(r->scene, sizeof r->scene, "%s", fld[0]);
    snprintf(r->tech, sizeof r->tech, "%s", fld[1]);
    r->slices = atoi(fld[2]); r->samples = atoi(fld[3]); r->radius = atof(fld[4]);
    r->interleave = atoi(fld[5]);
    snprintf(r->number, sizeof r->number, "%s", fld[6]);
    r->ms = atof(fld[7]); r->cpu = atof(fld[8]);
    r->ao_rmse = atof(fld[9]); r->ao_max = atof(fld[10]); r->bent_deg = atof(fld[11]);
    r->near_rel = fld[12][0] ? atof(fld[12]) : (double)NAN;
    r->is_default = atoi(fld[13]); r->on_curve = atoi(fld[14]);
    return 1;
}

/* Means over scenes of one (technique, setting, number, radius scale) group. */
typedef struct point {
    char tech[32], number[8];
    int slices, samples, is_default, on_curve, scenes, near_n;
    double ms, wall, ao_rmse, ao_max, bent_deg, near_rel, rscale;   /* ms: CPU ms, wall: hosted clock */
    double ipp;                      /* instructions per pixel (cost-*.csv, mean over its scenes); 0: not counted */
    int ipp_n;
} point;

static point pts[512];
static int npts;

/* The radius scale of a row: its radius over the scene's default row's. */
static double row_rscale(const row *r)
{
    int i;
    for (i = 0; i < nrows; i++)
        if (strcmp(rows[i].scene, r->scene) == 0 && rows[i].is_default && rows[i].radius > 0)
            return r->radius / rows[i].radius;
    return 1;
}

static void group_points(void)
{
    int i, j;
    npts = 0;
    for (i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        double rs = row_rscale(r);
        point *p = NULL;
        for (j = 0; j < npts; j++)
            if (strcmp(pts[j].tech, r->tech) == 0 && strcmp(pts[j].number, r->number) == 0 &&
                pts[j].slices == r->slices && pts[j].samples == r->samples && fabs(pts[j].rscale - rs) < 1e-3) { p = &pts[j]; break; }
        if (!p) {
            if (npts == 512) continue;
            p = &pts[npts++];
            memset(p, 0, sizeof *p);
            snprintf(p->tech, sizeof p->tech, "%s", r->tech);
            snprintf(p->number, sizeof p->number, "%s", r->number);
            p->slices = r->slices; p->samples = r->samples; p->rscale = rs;
            p->is_default = r->is_default; p->on_curve = r->on_curve;
        }
        p->scenes++;
        p->ms += r->cpu; p->wall += r->ms; p->ao_rmse += r->ao_rmse; p->bent_deg += r->bent_deg;
        if (r->ao_max > p->ao_max) p->ao_max = r->ao_max;
        if (!isnan(r->near_rel)) { p->near_rel += r->near_rel; p->near_n++; }
    }
    for (j = 0; j < npts; j++) {
        point *p = &pts[j];
        p->ms /= p->scenes; p->wall /= p->scenes; p->ao_rmse /= p->scenes; p->bent_deg /= p->scenes;
        p->near_rel = p->near_n ? p->near_rel / p->near_n : (double)NAN;
    }
}

/* DIR/cost-<number>.csv (tools/bench_cost.py): each curve point's frame in
 * instructions per pixel, the mean over the scenes counted. */
static point *curve_point(const char *tech, const char *number, int slices, int samples)
{
    int j;
    for (j = 0; j < npts; j++)
        if (pts[j].on_curve && strcmp(pts[j].tech, tech) == 0 && strcmp(pts[j].number, number) == 0 &&
            pts[j].slices == slices && pts[j].samples == samples && fabs(pts[j].rscale - 1) < 1e-3)
            return &pts[j];
    return NULL;
}

static int parse_cost_row(char *line, int i)
{
    char scene[32], tech[32], number[8];
    int slices, samples;
    double pixels, instructions;
    point *p;
    (void)i;
    if (sscanf(line, "%31[^,],%31[^,],%d,%d,%7[^,],%lf,%lf", scene, tech, &slices, &samples, number, &pixels,
               &instructions) != 7 || pixels <= 0)
        return 0;
    p = curve_point(tech, number, slices, samples);
    if (p) { p->ipp += instructions / pixels; p->ipp_n++; }
    return 1;
}

static int read_costs(void)
{
    int j, n = 0, ncost = 0;
    read_csv("cost", "float", &ncost, parse_cost_row);
    read_csv("cost", "fixed", &ncost, parse_cost_row);
    for (j = 0; j < npts; j++)
        if (pts[j].ipp_n) { pts[j].ipp /= pts[j].ipp_n; n++; }
    return n;
}

static void fmt_ipp(char *buf, size_t n, const point *p)
{
    if (p->ipp_n) snprintf(buf, n, "%.0f", p->ipp);
    else snprintf(buf, n, "-");
}

static const point *find_point(const char *tech, const char *number, int slices, int samples)
{
    int j;
    for (j = 0; j < npts; j++)
        if (strcmp(pts[j].tech, tech) == 0 && strcmp(pts[j].number, number) == 0 &&
            (slices < 0 || pts[j].slices == slices) && pts[j].samples == samples && fabs(pts[j].rscale - 1) < 1e-3)
            return &pts[j];
    return NULL;
}

static const char *setting(const point *p, char *buf, size_t n)
{
    const char *t = p->tech;
    if (p->samples == 0)   /* hbil-ao: the plan's samples (16 over two layers, 32 on one) */
        snprintf(buf, n, "%d slice%s x the plan's", p->slices, p->slices == 1 ? "" : "s");
    else if (!strncmp(t, "hbil", 4) || !strcmp(t, "gtao") || !strcmp(t, "hbao") || !strncmp(t, "ssilvb", 6))
        snprintf(buf, n, "%d slice%s x %d", p->slices, p->slices == 1 ? "" : "s", p->samples);
    else snprintf(buf, n, "%d samples", p->samples);
    if (fabs(p->rscale - 1) > 1e-3) {
        size_t l = strlen(buf);
        snprintf(buf + l, n - l, ", radius x%.1f", p->rscale);
    }
    return buf;
}

static void fmt_near(char *buf, size_t n, double v)
{
    if (isnan(v)) snprintf(buf, n, "-");
    else snprintf(buf, n, "%.3f", v);
}

/* Pareto frontier of the float curve points: nothing both faster and better. */
static int on_frontier(const point *p)
{
    int j;
    if (strcmp(p->number, "float") || !p->on_curve) return 0;
    for (j = 0; j < npts; j++) {
        const point *q = &pts[j];
        if (q == p || strcmp(q->number, "float") || !q->on_curve) continue;
        if (q->ms <= p->ms && q->ao_rmse <= p->ao_rmse && (q->ms < p->ms || q->ao_rmse < p->ao_rmse)) return 0;
    }
    return 1;
}

static int cmp_ms(const void *a, const void *b)
{
    const point *x = *(const point *const *)a, *y = *(const point *const *)b;
    return x->ms < y->ms ? -1 : x->ms > y->ms;
}

static const char *tech_names[] = { "hbil", "hbil-1x", "hbil-full", "gtao", "hbao", "ssao", "vo", "ssdo", "bentcone",
                                    "ssilvb", "ssilvb-3l", "hbil-3l", "hbil-ao" };
static const char *tech_colors[] = { "#d62728", "#e377c2", "#ff7f0e", "#1f77b4", "#17becf", "#7f7f7f", "#2ca02c", "#9467bd", "#8c564b",
                                     "#bcbd22", "#393b79", "#8b0000", "#ff1493" };
#define NTECH 13

/* An SVG plot W x H on white. */
static void svg_begin(FILE *f, int W, int H)
{
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" font-family=\"sans-serif\" font-size=\"12\">\n", W, H, W, H);
    fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", W, H);
}

/* A plot's vertical grid at 1, 2 and 5 x 10^e, labelled, over log10 x in
 * [lx0, lx1] drawn from L to W - R (margins L, R, T, B of a W x H plot). */
static void svg_log_x_grid(FILE *f, double lx0, double lx1, int W, int H, int L, int R, int T, int B)
{
    int e, k;
    for (e = (int)floor(lx0); e <= (int)ceil(lx1); e++) {
        static const int m[] = { 1, 2, 5 };
        for (k = 0; k < 3; k++) {
            double v = m[k] * pow(10, e), x;
            if (log10(v) < lx0 - 1e-9 || log10(v) > lx1 + 1e-9) continue;
            x = L + (log10(v) - lx0) / (lx1 - lx0) * (W - L - R);
            fprintf(f, "<line x1=\"%.1f\" y1=\"%d\" x2=\"%.1f\" y2=\"%d\" stroke=\"#ddd\"/>\n", x, T, x, H - B);
            fprintf(f, "<text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\">%g</text>\n", x, H - B + 16, v);
        }
    }
}

/* A point's x in the plot: CPU ms, or instructions per pixel (0: none). */
static double plot_x(const point *p, int by_instructions)
{
    return by_instructions ? (p->ipp_n ? p->ipp : 0) : p->ms;
}

static int cmp_ipp(const void *a, const void *b)
{
    const point *x = *(const point *const *)a, *y = *(const point *const *)b;
    return x->ipp < y->ipp ? -1 : x->ipp > y->ipp;
}

/* bench.svg: AO RMSE against CPU ms; by_instructions: bench-cost.svg,
 * against instructions per pixel (the points counted). */
static void write_svg(int by_instructions)
{
    const int W = 860, H = 540, L = 70, R = 150, T = 50, B = 60;
    double xmin = 1e30, xmax = 0, ymax = 0, lx0, lx1, ystep = 1;
    int j, k, yticks = 5;
    FILE *f = open_out(by_instructions ? "bench-cost.svg" : "bench.svg", "w");
    for (j = 0; j < npts; j++) {
        double x = plot_x(&pts[j], by_instructions);
        if (!pts[j].on_curve || x <= 0) continue;
        if (x < xmin) xmin = x;
        if (x > xmax) xmax = x;
        if (pts[j].ao_rmse > ymax) ymax = pts[j].ao_rmse;
    }
    if (xmax <= 0) xmax = 1;
    if (xmin >= xmax) xmin = xmax / 10;
    lx0 = floor(log10(xmin) * 4) / 4; lx1 = ceil(log10(xmax) * 4) / 4;
    if (lx1 <= lx0) lx1 = lx0 + 1;
    {   /* y axis: about 6 steps of a round size (1, 2, 2.5 or 5 x 10^k) */
        double top = ymax > 0 ? ymax * 1.05 : 1, raw = top / 6, mag = pow(10, floor(log10(raw)));
        ystep = raw <= mag ? mag : raw <= 2 * mag ? 2 * mag : raw <= 2.5 * mag ? 2.5 * mag : raw <= 5 * mag ? 5 * mag : 10 * mag;
        yticks = (int)ceil(top / ystep - 1e-9);
        ymax = yticks * ystep;
    }
#define PX(p) (L + (log10(plot_x(p, by_instructions)) - lx0) / (lx1 - lx0) * (W - L - R))
#define PY(v) (H - B - (v) / ymax * (H - T - B))
    svg_begin(f, W, H);
    fprintf(f, "<text x=\"%d\" y=\"22\" font-size=\"15\" font-weight=\"bold\">tinygi: AO error against %s (mean over %s scenes, %dx%d)</text>\n",
            L, by_instructions ? "instructions" : "time", "the built-in", opt_w, opt_h);
    fprintf(f, "<text x=\"%d\" y=\"40\" fill=\"#444\">lower left is better; solid = float, dashed = Q16.16 fixed; each line sweeps its technique's samples/slices%s</text>\n", L,
            by_instructions ? " (callgrind, tools/bench_cost.py)" : "; grey band = frontier");
    /* axes and grid */
    svg_log_x_grid(f, lx0, lx1, W, H, L, R, T, B);
    for (k = 0; k <= yticks; k++) {
        double v = ystep * k, y = PY(v);
        fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", L, y, W - R, y);
        fprintf(f, "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", L - 6, y + 4, v);
    }
    fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"black\"/>\n", L, T, W - L - R, H - T - B);
    fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">%s (log scale)</text>\n", (L + W - R) / 2, H - 18,
            by_instructions ? "instructions per pixel of a frame (x86-64, gcc)" : "median CPU ms per frame");
    fprintf(f, "<text x=\"16\" y=\"%d\" text-anchor=\"middle\" transform=\"rotate(-90 16 %d)\">AO RMSE vs ray-traced reference</text>\n", (T + H - B) / 2, (T + H - B) / 2);
    /* frontier */
    if (!by_instructions) {
        const point *fr[512];
        int nf = 0;
        for (j = 0; j < npts; j++) if (on_frontier(&pts[j])) fr[nf++] = &pts[j];
        qsort(fr, (size_t)nf, sizeof fr[0], cmp_ms);
        if (nf > 1) {
            fprintf(f, "<polyline fill=\"none\" stroke=\"#bbb\" stroke-width=\"9\" stroke-linejoin=\"round\" stroke-opacity=\"0.6\" points=\"");
            for (k = 0; k < nf; k++) fprintf(f, "%.1f,%.1f ", PX(fr[k]), PY(fr[k]->ao_rmse));
            fprintf(f, "\"/>\n");
        }
    }
    /* one polyline per technique and number type */
    for (k = 0; k < NTECH; k++) {
        int num;
        for (num = 0; num < 2; num++) {
            const char *number = num ? "fixed" : "float";
            const point *cp[64];
            int nc = 0, i;
            for (j = 0; j < npts && nc < 64; j++)
                if (pts[j].on_curve && !strcmp(pts[j].tech, tech_names[k]) && !strcmp(pts[j].number, number) &&
                    plot_x(&pts[j], by_instructions) > 0) cp[nc++] = &pts[j];
            if (!nc) continue;
            qsort(cp, (size_t)nc, sizeof cp[0], by_instructions ? cmp_ipp : cmp_ms);
            fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\"%s points=\"", tech_colors[k],
                    num ? " stroke-dasharray=\"6 4\"" : "");
            for (i = 0; i < nc; i++) fprintf(f, "%.1f,%.1f ", PX(cp[i]), PY(cp[i]->ao_rmse));
            fprintf(f, "\"/>\n");
            for (i = 0; i < nc; i++) {
                char buf[64];
                fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%d\" fill=\"%s\"><title>%s %s %s: %.2f ms, %.0f instructions a pixel, AO RMSE %.4f</title></circle>\n",
                        PX(cp[i]), PY(cp[i]->ao_rmse), cp[i]->is_default ? 5 : 3, num ? "white" : tech_colors[k],
                        tech_names[k], number, setting(cp[i], buf, sizeof buf), cp[i]->ms, cp[i]->ipp, cp[i]->ao_rmse);
                if (num) fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%d\" fill=\"none\" stroke=\"%s\"/>\n",
                                 PX(cp[i]), PY(cp[i]->ao_rmse), cp[i]->is_default ? 5 : 3, tech_colors[k]);
            }
        }
        fprintf(f, "<line x1=\"%d\" y1=\"%d\" x2=\"%d\" y2=\"%d\" stroke=\"%s\" stroke-width=\"3\"/>\n", W - R + 14, T + 10 + 18 * k,
                W - R + 36, T + 10 + 18 * k, tech_colors[k]);
        fprintf(f, "<text x=\"%d\" y=\"%d\">%s</text>\n", W - R + 42, T + 14 + 18 * k, tech_names[k]);
    }
    /* labels last, over every line: each float curve's name at its slowest setting */
    for (k = 0; k < NTECH; k++) {
        const point *last = NULL;
        char buf[64];
        for (j = 0; j < npts; j++)
            if (pts[j].on_curve && !strcmp(pts[j].tech, tech_names[k]) && !strcmp(pts[j].number, "float") &&
                plot_x(&pts[j], by_instructions) > 0 && (!last || plot_x(&pts[j], by_instructions) > plot_x(last, by_instructions)))
                last = &pts[j];
        if (last)
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" fill=\"%s\" font-size=\"11\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">%s %s</text>\n",
                    PX(last) + 6, PY(last->ao_rmse) - 5, tech_colors[k], tech_names[k], setting(last, buf, sizeof buf));
    }
    fprintf(f, "<text x=\"%d\" y=\"%d\" fill=\"#444\" font-size=\"11\">big dot: default</text>\n", W - R + 14, T + 14 + 18 * NTECH + 6);
    fprintf(f, "<text x=\"%d\" y=\"%d\" fill=\"#444\" font-size=\"11\">(%d slices x %d)</text>\n", W - R + 14, T + 14 + 18 * NTECH + 20, TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES);
    fprintf(f, "</svg>\n");
    fclose(f);
#undef PX
#undef PY
}

static void claim_lines(FILE *f, const char *number)
{
    const point *ssao12 = find_point("ssao", number, -1, 12), *ssao8 = find_point("ssao", number, -1, 8);
    const point *ssao16 = find_point("ssao", number, -1, 16);
    const point *bc8 = find_point("bentcone", number, -1, 8), *ssdo16 = find_point("ssdo", number, -1, 16);
    const point *ssdo8 = find_point("ssdo", number, -1, 8);
    const point *do8 = find_point("ssdo-do", number, -1, 8), *do16 = find_point("ssdo-do", number, -1, 16);
    static const int vn[] = { 5, 7, 9 };
    int k, better = 0, faster = 0;
    if (!ssao12) return;
    fprintf(f, "**Loos & Sloan table 1** (%s): VO with 5-9 line samples against Crytek SSAO with 12 point samples: ", number);
    fprintf(f, "SSAO 12 %.2f ms, AO RMSE %.4f; ", ssao12->ms, ssao12->ao_rmse);
    for (k = 0; k < 3; k++) {
        const point *v = find_point("vo", number, -1, vn[k]);
        if (!v) continue;
        fprintf(f, "VO %d %.2f ms, RMSE %.4f; ", vn[k], v->ms, v->ao_rmse);
        if (v->ao_rmse <= ssao12->ao_rmse * 1.05) better++;
        if (v->ms <= ssao12->ms) faster++;
        if (v->ao_rmse <= ssao12->ao_rmse * 1.05 && v->ms <= ssao12->ms) better += 10;
    }
    fprintf(f, "verdict: **%s**.\n\n", better >= 10 ? "HOLDS (VO matches or beats SSAO 12's error in no more time)" :
            better > 0 ? "PARTLY (VO's error is as low, but not in less time)" :
            faster > 0 ? "PARTLY (VO is faster, but its error is higher)" : "DOES NOT HOLD");
    if (bc8 && ssdo16) {
        int q = bc8->bent_deg <= ssdo16->bent_deg * 1.1, t = bc8->ms < ssdo16->ms;
        fprintf(f, "**Klehm fig. 8** (%s): bent cones with 8 samples against SSDO with 16: bent cones %.2f ms, AO RMSE %.4f, bent %.2f deg; SSDO %.2f ms, AO RMSE %.4f, bent %.2f deg (paper: 6.0 vs 12.5 ms); verdict: **%s**.\n\n",
                number, bc8->ms, bc8->ao_rmse, bc8->bent_deg, ssdo16->ms, ssdo16->ao_rmse, ssdo16->bent_deg,
                q && t ? "HOLDS (as accurate a bent normal in less time)" : t ? "PARTLY (faster, but a worse bent normal)" :
                q ? "PARTLY (as accurate, but not faster)" : "DOES NOT HOLD");
    }
    if (ssao8 && ssao16 && do8 && do16 && ssdo8 && ssdo16) {
        double d8 = 100 * (do8->ms / ssao8->ms - 1), d16 = 100 * (do16->ms / ssao16->ms - 1);
        double b8 = 100 * (ssdo8->ms / ssao8->ms - 1), b16 = 100 * (ssdo16->ms / ssao16->ms - 1);
        fprintf(f, "**Ritschel table 1** (%s): SSDO's overhead over SSAO: directional occlusion alone %+.0f%% (N=8), %+.0f%% (N=16) (paper +0.2..+8.9%%); with one bounce %+.0f%% (N=8), %+.0f%% (N=16) (paper +19..+46%%); verdict: **%s**.\n\n",
                number, d8, d16, b8, b16,
                d8 < 15 && d16 < 15 && b8 < 60 && b16 < 60 ? "HOLDS (a modest overhead)" :
                d8 < 15 && d16 < 15 ? "PARTLY (DO is cheap, the bounce costs more than the paper's)" : "DOES NOT HOLD (DO is not a small overhead here)");
    }
}

/* ---- colour rows: DIR/color-<type>.csv ---- */

typedef struct crow {
    char scene[32], tech[32], number[8];
    int frames, paths;
    double cpu, rmse, energy, noise;
} crow;

static crow crows[MAX_ROWS];
static int ncrows;

static int parse_color_row(char *line, int i)
{
    crow *r = &crows[i];
    return sscanf(line, "%31[^,],%31[^,],%d,%7[^,],%lf,%lf,%lf,%lf,%d", r->scene, r->tech, &r->frames, r->number, &r->cpu,
                  &r->rmse, &r->energy, &r->noise, &r->paths) == 9;
}

/* An RMSE against a noisy reference without the reference's own noise:
 * the two add in squares, so sqrt(rmse^2 - noise^2) estimates the RMSE
 * against the converged image (0 where the noise is the larger). */
static double noise_removed(double rmse, double noise)
{
    return rmse > noise ? sqrt(rmse * rmse - noise * noise) : 0;
}

/* Means over the scenes of one technique and number type (clean: of
 * noise_removed). */
typedef struct cpoint { double cpu, rmse, clean, energy, noise, emin, emax; int scenes, frames; } cpoint;

static int color_point(const char *tech, const char *number, cpoint *p)
{
    int i;
    memset(p, 0, sizeof *p);
    p->emin = 1e30;
    for (i = 0; i < ncrows; i++) {
        const crow *r = &crows[i];
        if (strcmp(r->tech, tech) || strcmp(r->number, number)) continue;
        p->cpu += r->cpu; p->rmse += r->rmse; p->energy += r->energy; p->noise += r->noise;
        p->clean += noise_removed(r->rmse, r->noise);
        if (r->energy < p->emin) p->emin = r->energy;
        if (r->energy > p->emax) p->emax = r->energy;
        p->frames = r->frames;
        p->scenes++;
    }
    if (!p->scenes) return 0;
    p->cpu /= p->scenes; p->rmse /= p->scenes; p->clean /= p->scenes; p->energy /= p->scenes; p->noise /= p->scenes;
    return 1;
}

static void color_report(FILE *md)
{
    FILE *f;
    int i, k, num, frames = 1;
    if (!ncrows) return;
    for (i = 0; i < ncrows; i++) if (crows[i].frames > frames) frames = crows[i].frames;
    f = open_out("bench-color.csv", "w");
    fprintf(f, COLOR_HEADER "\n");
    for (i = 0; i < ncrows; i++) {
        const crow *r = &crows[i];
        fprintf(f, "%s,%s,%d,%s,%.4f,%.6f,%.6f,%.6f,%d\n", r->scene, r->tech, r->frames, r->number, r->cpu, r->rmse, r->energy,
                r->noise, r->paths);
    }
    fclose(f);
    fprintf(md, "## Colour against the path-traced reference\n\n");
    fprintf(md, "Each technique at its default setting (%d slices x %d samples, the radius its plan gives it: the scene's, or sized to it, the diagonal / 6 for light where it has an environment; HBIL converged over %d frames, the others one frame; `reference`: the ray-traced AO and one-bounce near field, composed like the others) against `--technique pathtrace` (%d paths per pixel in two halves, its default bounces). Colour RMSE over geometry pixels with every channel clamped to [0, 1]; energy: sum Lo / sum Lo_ref (1 = the path tracer's light). The reference's own noise (from its two halves) is a floor under every RMSE; `noise removed` is sqrt(RMSE^2 - noise^2), the error's estimate against the converged image (0 where the noise is larger). CPU ms: median per frame (converged).\n\n",
            TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES, frames, crows[0].paths);
    fprintf(md, "| technique | number | CPU ms | colour RMSE | noise removed | energy (mean) | energy (range over scenes) |\n"
                "|---|---|---:|---:|---:|---:|---|\n");
    for (num = 0; num < 2; num++)
        for (k = 0; k < COLOR_TECHS; k++) {
            cpoint p;
            if (!color_point(color_cfgs[k].label, num ? "fixed" : "float", &p)) continue;
            fprintf(md, "| %s | %s | %.2f | %.4f | %.4f | %.3f | %.3f..%.3f |\n", color_cfgs[k].label, num ? "fixed" : "float",
                    p.cpu, p.rmse, p.clean, p.energy, p.emin, p.emax);
        }
    fprintf(md, "\n| scene | technique | number | frames | CPU ms | colour RMSE | noise removed | energy | reference noise |\n"
                "|---|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (i = 0; i < ncrows; i++) {
        const crow *r = &crows[i];
        fprintf(md, "| %s | %s | %s | %d | %.2f | %.4f | %.4f | %.3f | %.4f |\n", r->scene, r->tech, r->number, r->frames,
                r->cpu, r->rmse, noise_removed(r->rmse, r->noise), r->energy, r->noise);
    }
    fprintf(md, "\n");
}

/* bench-color.svg: colour RMSE against CPU ms, a dot per technique (float
 * filled, fixed hollow), labelled; the path tracer's noise as a dashed line. */
static void write_color_svg(void)
{
    const int W = 760, H = 460, L = 70, R = 30, T = 50, B = 60;
    double xmin = 1e30, xmax = 0, ymax = 0, noise = 0, lx0, lx1;
    int k, num;
    cpoint pt[2][COLOR_TECHS];
    int have[2][COLOR_TECHS];
    FILE *f;
    if (!ncrows) return;
    for (num = 0; num < 2; num++)
        for (k = 0; k < COLOR_TECHS; k++) {
            have[num][k] = color_point(color_cfgs[k].label, num ? "fixed" : "float", &pt[num][k]);
            if (!have[num][k]) continue;
            if (pt[num][k].cpu > 0 && pt[num][k].cpu < xmin) xmin = pt[num][k].cpu;
            if (pt[num][k].cpu > xmax) xmax = pt[num][k].cpu;
            if (pt[num][k].rmse > ymax) ymax = pt[num][k].rmse;
            noise = pt[num][k].noise;
        }
    if (xmax <= 0) xmax = 1;
    if (xmin >= xmax) xmin = xmax / 10;
    lx0 = floor(log10(xmin) * 2) / 2; lx1 = ceil(log10(xmax) * 2) / 2;
    if (lx1 <= lx0) lx1 = lx0 + 1;
    ymax = ymax > 0 ? ymax * 1.15 : 1;
#define CX(ms) (L + (log10(ms) - lx0) / (lx1 - lx0) * (W - L - R))
#define CY(v) (H - B - (v) / ymax * (H - T - B))
    f = open_out("bench-color.svg", "w");
    svg_begin(f, W, H);
    fprintf(f, "<text x=\"%d\" y=\"22\" font-size=\"15\" font-weight=\"bold\">tinygi: colour error against the path tracer (mean over scenes, %dx%d)</text>\n", L, opt_w, opt_h);
    fprintf(f, "<text x=\"%d\" y=\"40\" fill=\"#444\">filled = float, hollow = Q16.16; default settings, HBIL converged; dashed = the path tracer's own noise</text>\n", L);
    svg_log_x_grid(f, lx0, lx1, W, H, L, R, T, B);
    for (k = 0; k <= 5; k++) {
        double v = ymax * k / 5, y = CY(v);
        fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", L, y, W - R, y);
        fprintf(f, "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\">%.3f</text>\n", L - 6, y + 4, v);
    }
    fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"black\"/>\n", L, T, W - L - R, H - T - B);
    fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#888\" stroke-dasharray=\"6 4\"/>\n", L, CY(noise), W - R, CY(noise));
    fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">median CPU ms per frame (log scale)</text>\n", (L + W - R) / 2, H - 18);
    fprintf(f, "<text x=\"16\" y=\"%d\" text-anchor=\"middle\" transform=\"rotate(-90 16 %d)\">colour RMSE (clamped at 1)</text>\n", (T + H - B) / 2, (T + H - B) / 2);
    for (num = 1; num >= 0; num--)
        for (k = 0; k < COLOR_TECHS; k++) {
            const cpoint *p = &pt[num][k];
            if (!have[num][k] || p->cpu <= 0) continue;
            fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" fill=\"%s\" stroke=\"#d62728\"><title>%s %s: %.2f ms, colour RMSE %.4f, energy %.3f</title></circle>\n",
                    CX(p->cpu), CY(p->rmse), num ? "white" : "#d62728", color_cfgs[k].label, num ? "fixed" : "float", p->cpu, p->rmse, p->energy);
            if (!num)
                fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"11\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">%s (energy %.2f)</text>\n",
                        CX(p->cpu) + 7, CY(p->rmse) - 6 - 11 * (k % 2), color_cfgs[k].label, p->energy);
        }
    fprintf(f, "</svg>\n");
    fclose(f);
#undef CX
#undef CY
}

/* 1 when DIR/multibounce-float.csv or -fixed.csv has a row. */
static int multibounce_rows_exist(void)
{
    char line[512];
    int num, lines = 0;
    for (num = 0; num < 2; num++) {
        FILE *f = open_rows("multibounce", num ? "fixed" : "float");
        if (!f) continue;
        while (fgets(line, sizeof line, f)) lines++;
        fclose(f);
    }
    return lines > 0;
}

/* The multi-bounce rows (DIR/multibounce-<type>.csv) as a section of bench.md. */
static void multibounce_report(FILE *md)
{
    char line[512];
    int num, first = 1;
    for (num = 0; num < 2; num++) {
        FILE *f = open_rows("multibounce", num ? "fixed" : "float");
        if (!f) continue;
        while (fgets(line, sizeof line, f)) {
            char scene[32], ao[32], number[8];
            double v[5];
            if (sscanf(line, "%31[^,],%31[^,],%7[^,],%lf,%lf,%lf,%lf,%lf", scene, ao, number, &v[0], &v[1], &v[2], &v[3], &v[4]) != 8)
                continue;
            if (first) {
                fprintf(md, "## Multi-bounce AO (GTAO, Jimenez et al. 2016, eq. 10) against the path tracer\n\n");
                fprintf(md, "Each scene lit by a uniform white sky alone (its lights, environment and emission dropped): the path tracer's E / (pi L) (interreflections included, its default bounces) is what an AO-only output should show. Against it, per colour channel over geometry pixels: the AO itself, the GTAO multi-bounce fit of the AO and the albedo, and RTR eq. 11.13 (k_A / (1 - rho (1 - k_A))). `reference`: the ray-traced AO without a cut-off (the fit's own error); `gtao`: GTAO at the scene's radius, as a frame gives it. Bias: mean (estimate - path tracer).\n\n");
                fprintf(md, "| scene | AO | number | AO RMSE | multi-bounce RMSE | RTR 11.13 RMSE | AO bias | multi-bounce bias |\n|---|---|---|---:|---:|---:|---:|---:|\n");
                first = 0;
            }
            fprintf(md, "| %s | %s | %s | %.4f | %.4f | %.4f | %+.4f | %+.4f |\n", scene, ao, number, v[0], v[1], v[2], v[3], v[4]);
        }
        fclose(f);
    }
    if (!first) fprintf(md, "\n");
}

static int cmd_report(void)
{
    FILE *f, *md;
    int i, j, num, counted;
    char buf[64], nb[32], ib[32];
    nrows = 0;
    ncrows = 0;
    read_csv("rows", "float", &nrows, parse_row);
    read_csv("rows", "fixed", &nrows, parse_row);
    read_csv("color", "float", &ncrows, parse_color_row);
    read_csv("color", "fixed", &ncrows, parse_color_row);
    if (!nrows && !ncrows && !multibounce_rows_exist()) die("no rows: run `bench run` first", opt_out);
    group_points();
    counted = read_costs();
    f = open_out("bench.csv", "w");
    fprintf(f, "scene,technique,slices,samples,radius,interleave,number,median_ms,cpu_ms,ao_rmse,ao_max,bent_deg,near_rel,default,curve\n");
    for (i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        fprintf(f, "%s,%s,%d,%d,%.4f,%d,%s,%.4f,%.4f,%.6f,%.6f,%.4f,", r->scene, r->tech, r->slices, r->samples, r->radius,
                r->interleave, r->number, r->ms, r->cpu, r->ao_rmse, r->ao_max, r->bent_deg);
        if (isnan(r->near_rel)) fprintf(f, ","); else fprintf(f, "%.6f,", r->near_rel);
        fprintf(f, "%d,%d\n", r->is_default, r->on_curve);
    }
    fclose(f);
    write_svg(0);
    if (counted) write_svg(1);
    write_color_svg();
    md = open_out("bench.md", "w");
    fprintf(md, "# tinygi accuracy vs time\n\n");
    fprintf(md, "Errors against the ray-traced reference (same radius as an obscurance cut-off); each value is the mean over the built-in scenes (max AO error: the worst pixel of any scene); CPU ms: median process CPU time per whole frame (robust on a busy machine: the plot, the frontier and the claims use it); wall ms: median by the hosted clock.\n\n");
    fprintf(md, "## Default setting (%d slices x %d samples, the scene's radius)\n\n", TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES);
    fprintf(md, "| technique | number | CPU ms | instr/px | wall ms | AO RMSE | AO max | bent deg | near rel. err |\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (num = 0; num < 2; num++)
        for (j = 0; j < npts; j++) {
            const point *p = &pts[j];
            if (strcmp(p->number, num ? "fixed" : "float") || !(p->is_default || !strcmp(p->tech, "gtao+ir")) || fabs(p->rscale - 1) > 1e-3) continue;
            if (!p->is_default && !(p->slices == TG_DEFAULT_SLICES && p->samples == TG_DEFAULT_SAMPLES)) continue;
            fmt_near(nb, sizeof nb, p->near_rel);
            fmt_ipp(ib, sizeof ib, p);
            fprintf(md, "| %s | %s | %.2f | %s | %.2f | %.4f | %.3f | %.2f | %s |\n", p->tech, p->number, p->ms, ib, p->wall, p->ao_rmse, p->ao_max, p->bent_deg, nb);
        }
    fprintf(md, "\ninstr/px: the frame's instructions per pixel (callgrind, `make bench-cost`, tools/bench_cost.py; the mean over the scenes counted; - where not counted).\n\n");
    if (counted) {
        /* every step of every curve: what its accuracy costs in ms and in instructions */
        fprintf(md, "## Every setting on the curves: AO error, CPU ms and instructions per pixel\n\n");
        fprintf(md, "| technique | setting | float ms | float instr/px | Q16.16 ms | Q16.16 instr/px | AO RMSE (float) |\n|---|---|---:|---:|---:|---:|---:|\n");
        for (i = 0; i < NTECH; i++)
            for (j = 0; j < npts; j++) {
                const point *p = &pts[j], *q;
                char fb[32];
                if (!p->on_curve || strcmp(p->tech, tech_names[i]) || strcmp(p->number, "float")) continue;
                q = curve_point(p->tech, "fixed", p->slices, p->samples);
                fmt_ipp(fb, sizeof fb, p);
                if (q) fmt_ipp(ib, sizeof ib, q); else snprintf(ib, sizeof ib, "-");
                if (q) snprintf(nb, sizeof nb, "%.2f", q->ms); else snprintf(nb, sizeof nb, "-");
                fprintf(md, "| %s | %s | %.2f | %s | %s | %s | %.4f |\n", p->tech, setting(p, buf, sizeof buf), p->ms, fb, nb, ib, p->ao_rmse);
            }
        fprintf(md, "\n");
    }
    color_report(md);
    multibounce_report(md);
    fprintf(md, "## Frontier (float): no other setting is both faster and more accurate\n\n");
    {
        const point *fr[512];
        int nf = 0;
        for (j = 0; j < npts; j++) if (on_frontier(&pts[j])) fr[nf++] = &pts[j];
        qsort(fr, (size_t)nf, sizeof fr[0], cmp_ms);
        fprintf(md, "| technique | setting | ms | instr/px | AO RMSE | step cost |\n|---|---|---:|---:|---:|---|\n");
        for (i = 0; i < nf; i++) {
            char step[128] = "";
            if (i > 0) snprintf(step, sizeof step, "%+.2f ms (x%.2f) for %.4f less RMSE (-%.0f%%)", fr[i]->ms - fr[i - 1]->ms,
                                fr[i]->ms / fr[i - 1]->ms, fr[i - 1]->ao_rmse - fr[i]->ao_rmse,
                                100 * (1 - fr[i]->ao_rmse / fr[i - 1]->ao_rmse));
            fmt_ipp(ib, sizeof ib, fr[i]);
            fprintf(md, "| %s | %s | %.2f | %s | %.4f | %s |\n", fr[i]->tech, setting(fr[i], buf, sizeof buf), fr[i]->ms, ib, fr[i]->ao_rmse, step);
        }
    }
    fprintf(md, "\n## The papers' claims\n\n");
    claim_lines(md, "float");
    claim_lines(md, "fixed");
    for (num = 0; num < 2; num++) {
        char path[700], line[1024];
        FILE *p;
        snprintf(path, sizeof path, "%s/passes-%s.md", opt_out, num ? "fixed" : "float");
        p = fopen(path, "r");
        if (!p) continue;
        while (fgets(line, sizeof line, p)) fputs(line, md);
        fclose(p);
    }
    {
        const point *ir = find_point("gtao+ir", "float", 2, 16), *hb = find_point("hbil", "float", 2, 16);
        const point *sd = find_point("ssdo", "float", 2, 16);
        if (ir && hb) {
            fmt_near(nb, sizeof nb, ir->near_rel);
            fprintf(md, "**Interreflection (RTR eq. 11.12-11.13)** (float): GTAO's AO brightened, read as near-field irradiance E_direct (k'_A/k_A - 1): relative error %s against the reference's one-bounce irradiance, at %.2f ms; ",
                    nb, ir->ms);
            fmt_near(nb, sizeof nb, hb->near_rel);
            fprintf(md, "HBIL's gathered bounce: %s at %.2f ms", nb, hb->ms);
            if (sd) { fmt_near(nb, sizeof nb, sd->near_rel); fprintf(md, "; SSDO's bounce: %s at %.2f ms", nb, sd->ms); }
            fprintf(md, ". Verdict: **%s**.\n\n", !isnan(ir->near_rel) && !isnan(hb->near_rel) && hb->near_rel < ir->near_rel ?
                    "HBIL's gather is closer to the reference than the AO brightening" : "the AO brightening is as close as HBIL's gather here");
        }
    }
    fprintf(md, "## Every row\n\n| scene | technique | setting | number | CPU ms | wall ms | AO RMSE | AO max | bent deg | near rel. err |\n|---|---|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (i = 0; i < nrows; i++) {
        const row *r = &rows[i];
        point p;
        memset(&p, 0, sizeof p);
        snprintf(p.tech, sizeof p.tech, "%s", r->tech);
        p.slices = r->slices; p.samples = r->samples; p.rscale = row_rscale(r);
        fmt_near(nb, sizeof nb, r->near_rel);
        fprintf(md, "| %s | %s | %s | %s | %.2f | %.2f | %.4f | %.3f | %.2f | %s |\n", r->scene, r->tech, setting(&p, buf, sizeof buf),
                r->number, r->cpu, r->ms, r->ao_rmse, r->ao_max, r->bent_deg, nb);
    }
    fclose(md);
    /* the verdicts on stdout */
    claim_lines(stdout, "float");
    claim_lines(stdout, "fixed");
    printf("wrote %s/bench.md, bench.csv, bench.svg%s%s\n", opt_out, counted ? ", bench-cost.svg" : "",
           ncrows ? ", bench-color.csv, bench-color.svg" : "");
    return 0;
}

int main(int argc, char **argv)
{
    int i;
    if (argc < 2) die("usage: bench run|report|count [--size WxH] [--runs N] [--out DIR] [--ref-samples N] [--scenes a,b] [--pt-samples N] [--color-frames N] [--only ao|color|multibounce]", NULL);
    for (i = 2; i < argc; i += 2) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) die("option needs a value", a);
        if (!strcmp(a, "--size")) { if (sscanf(v, "%dx%d", &opt_w, &opt_h) != 2 || opt_w < 8 || opt_h < 8 || opt_w > 4096 || opt_h > 4096) die("bad size", v); }
        else if (!strcmp(a, "--runs")) { opt_runs = atoi(v); if (opt_runs < 1 || opt_runs > MAX_RUNS) die("runs must be 1..64", v); }
        else if (!strcmp(a, "--out")) opt_out = v;
        else if (!strcmp(a, "--ref-samples")) { opt_ref_samples = atoi(v); if (opt_ref_samples < 17 || opt_ref_samples > 256) die("ref-samples must be 17..256", v); }
        else if (!strcmp(a, "--scenes")) snprintf(opt_scenes, sizeof opt_scenes, "%s", v);
        else if (!strcmp(a, "--pt-samples")) {
            opt_pt_samples = atoi(v);
            if (opt_pt_samples < 2 || opt_pt_samples > 16 * TG_MAX_SAMPLES ||
                (opt_pt_samples > 2 * TG_MAX_SAMPLES && opt_pt_samples % (2 * TG_MAX_SAMPLES)))
                die("pt-samples must be 2..512, or a multiple of 512 up to 4096", v);
        }
        else if (!strcmp(a, "--only")) {
            if (strcmp(v, "ao") && strcmp(v, "color") && strcmp(v, "multibounce")) die("--only takes ao, color or multibounce", v);
            snprintf(opt_only, sizeof opt_only, "%s", v);
        }
        else if (!strcmp(a, "--color-frames")) { opt_color_frames = atoi(v); if (opt_color_frames < 1 || opt_color_frames > 1000) die("color-frames must be 1..1000", v); }
        else die("unknown option", a);
    }
    if (!strcmp(argv[1], "run")) return cmd_run();
    if (!strcmp(argv[1], "report")) return cmd_report();
    if (!strcmp(argv[1], "count")) return cmd_count();
    die("unknown command", argv[1]);
    return 2;
}
