/* SPDX-License-Identifier: MIT */
/*
 * test_request.c - the API is as safe as the CLI: every tg_request field
 * swept to its extremes (each is refused with TG_ERR_INPUT and a message
 * naming the field, or it plans a sane arena and renders finite AOVs), the
 * scene's gi values checked like the request's, and AOV rows outside the
 * image refused without reading outside the frame.  Sizes are computed in
 * double here so the test means the same on a 32-bit build (where a wrapped
 * size_t would show as a plan far smaller than its buffers).
 */
#include <float.h>
#include <limits.h>
#include "frame_fixture.h"
#include "gi/resample.h"

/* Every effect and both kinds of shadow map: a point light (six faces) and
 * a spot, an environment, an emissive material. */
static const char *scene_text =
    "camera pos 0 1.2 -3 target 0 0.8 0 fov 60\n"
    "material wall albedo 0.7 0.6 0.5 f0 0.04\n"
    "material lamp albedo 0.5 0.5 0.5 emissive 2 2 2\n"
    "quad p0 -3 0 -3  p1 3 0 -3  p2 3 0 3  p3 -3 0 3 material wall\n"
    "box min -0.5 0 -0.5 max 0.5 1 0.5 material wall\n"
    "box min 0.8 0 0.8 max 1.2 0.4 1.2 material lamp\n"
    "light point pos 0 2.5 -1 color 1 1 1 intensity 6 shadows\n"
    "light spot pos 1 2 -1 dir -0.3 -1 0.3 angle 40 color 1 1 1 intensity 4 shadows\n"
    "env sky 0.4 0.5 0.7 ground 0.2 0.2 0.2\n";

#define RENDER_CAP (48.0 * 1024 * 1024)   /* arena bytes this test renders at most */

enum { ACCEPT, REFUSE };

typedef struct sweep_case {
    const char *field;      /* the word the refusal must contain */
    int expect;
    tg_request q;
    char value[48];
} sweep_case;

static tg_scene *sweep_scene;
static void *sweep_scene_mem;

static tg_request small_request(void)
{
    tg_request q = request(12, 9, ALL_AOVS);
    q.frames = 2;
    return q;
}

static int all_finite(const rendered *r)
{
    int a, bad = 0;
    size_t n = (size_t)r->plan.request.width * (size_t)r->plan.request.height, i;
    for (a = 0; a < TG_AOV_COUNT; a++) {
        double *v = read_aov(r, (tg_aov)a);
        for (i = 0; i < n * (size_t)tg_aov_channels((tg_aov)a); i++) bad += !isfinite(v[i]);
        free(v);
    }
    return bad == 0;
}

/* Two frames (or one), every AOV finite. */
static void render_case(const sweep_case *c, const tg_plan *plan)
{
    rendered r;
    tg_error err;
    int f;
    memset(&r, 0, sizeof r);
    r.plan = *plan;
    r.frame_mem = malloc(plan->total_bytes);
    CHECK(r.frame_mem && tg_frame_create(plan, r.frame_mem, plan->total_bytes, &r.frame, &err) == TG_OK,
          "%s = %s: frame create", c->field, c->value);
    if (!r.frame) { free(r.frame_mem); return; }
    for (f = 0; f < (plan->request.frames < 2 ? plan->request.frames : 2); f++) {
        CHECK(tg_frame_render(r.frame, f, &err) == TG_OK, "%s = %s: render", c->field, c->value);
        CHECK(all_finite(&r), "%s = %s: frame %d has a non-finite AOV", c->field, c->value, f);
    }
    free(r.frame_mem);
}

/* The arena holds at least the G-buffer depth and a shadow-map face the
 * view needs (16 bits a texel): a size that wrapped around would be
 * smaller. */
static double least_bytes(const tg_plan *p)
{
    double n = (double)p->request.shadow_map_size;
    return (double)p->request.width * p->request.height * sizeof(tg_real) + n * n * 2.0;
}

static void run_case(const sweep_case *c)
{
    tg_plan plan;
    tg_error err;
    char msg[600];
    tg_status s;
    memset(&err, 0, sizeof err);
    s = tg_plan_make(&plan, sweep_scene, &c->q, &err);
    tg_error_format(&err, msg, sizeof msg);
    if (c->expect == REFUSE) {
        CHECK(s == TG_ERR_INPUT, "%s = %s: accepted (status %d), expected a refusal", c->field, c->value, (int)s);
        CHECK(s != TG_ERR_INPUT || (strstr(msg, c->field) && strstr(msg, "must be")),
              "%s = %s: message does not name the field: %s", c->field, c->value, msg);
        return;
    }
    /* within every limit: planned, or refused only for the address space */
    CHECK(s == TG_OK || (s == TG_ERR_INPUT && strstr(msg, "address space")),
          "%s = %s: refused: %s", c->field, c->value, msg);
    if (s != TG_OK) return;
    CHECK((double)plan.total_bytes >= least_bytes(&plan), "%s = %s: plan of %.0f bytes, less than its buffers (%.0f)",
          c->field, c->value, (double)plan.total_bytes, least_bytes(&plan));
    if ((double)plan.total_bytes <= RENDER_CAP) render_case(c, &plan);
}

/* A case on the small request, its field still to be set. */
static sweep_case new_case(const char *field, int expect)
{
    sweep_case c;
    memset(&c, 0, sizeof c);
    c.q = small_request();
    c.field = field;
    c.expect = expect;
    return c;
}

static sweep_case int_case(const char *field, int *slot_of_q, tg_request *q, long v, int expect)
{
    sweep_case c = new_case(field, expect);
    *slot_of_q = (int)v;
    c.q = *q;
    snprintf(c.value, sizeof c.value, "%ld", v);
    return c;
}

/* An int field: each value with its expectation, on an otherwise small request. */
#define SWEEP_INT(FIELD, NAME, ...) do {                                       \
        static const long v_[][2] = { __VA_ARGS__ };                           \
        size_t k_;                                                             \
        for (k_ = 0; k_ < sizeof v_ / sizeof v_[0]; k_++) {                    \
            tg_request q_ = small_request();                                   \
            sweep_case c_ = int_case(NAME, (int *)(void *)&q_.FIELD, &q_, v_[k_][0], (int)v_[k_][1]); \
            run_case(&c_);                                                     \
        }                                                                      \
    } while (0)

TEST(every_int_field_at_its_extremes)
{
    SWEEP_INT(width, "width", { INT_MIN, REFUSE }, { -1, REFUSE }, { 0, REFUSE }, { 1, ACCEPT },
              { TG_MAX_IMAGE_SIDE, ACCEPT }, { TG_MAX_IMAGE_SIDE + 1, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(height, "height", { INT_MIN, REFUSE }, { 0, REFUSE }, { 1, ACCEPT },
              { TG_MAX_IMAGE_SIDE, ACCEPT }, { TG_MAX_IMAGE_SIDE + 1, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(frames, "frames", { INT_MIN, REFUSE }, { -1, REFUSE }, { 0, REFUSE }, { 1, ACCEPT },
              { TG_MAX_FRAMES, ACCEPT }, { TG_MAX_FRAMES + 1L, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(technique, "technique", { INT_MIN, REFUSE }, { -1, REFUSE }, { TG_TECH_COUNT, REFUSE },
              { INT_MAX, REFUSE }, { TG_TECH_HBIL, ACCEPT }, { TG_TECH_SSDO, ACCEPT }, { TG_TECH_BENTCONE, ACCEPT });
    SWEEP_INT(slices, "slices", { INT_MIN, ACCEPT }, { 0, ACCEPT }, { 1, ACCEPT }, { TG_MAX_SLICES, ACCEPT },
              { TG_MAX_SLICES + 1, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(samples, "samples", { INT_MIN, ACCEPT }, { 0, ACCEPT }, { 1, ACCEPT }, { TG_MAX_SAMPLES, ACCEPT },
              { TG_MAX_SAMPLES + 1, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(bounces, "bounces", { INT_MIN, ACCEPT }, { -1, ACCEPT }, { 0, ACCEPT }, { TG_MAX_BOUNCES, ACCEPT },
              { TG_MAX_BOUNCES + 1, REFUSE }, { 1000000, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(interleave, "interleave", { INT_MIN, REFUSE }, { -1, REFUSE }, { 0, ACCEPT }, { 1, ACCEPT },
              { 2, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(gi_scale, "gi_scale", { INT_MIN, REFUSE }, { 0, REFUSE }, { 1, ACCEPT }, { 2, ACCEPT },
              { 3, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(temporal, "temporal", { -1, REFUSE }, { 0, ACCEPT }, { 1, ACCEPT }, { 2, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(far_mode, "far_mode", { -1, REFUSE }, { 0, ACCEPT }, { 1, ACCEPT }, { 2, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(shadow_pcf, "shadow_pcf", { -1, REFUSE }, { 0, ACCEPT }, { 1, ACCEPT }, { 2, REFUSE }, { INT_MAX, REFUSE });
    SWEEP_INT(depth_layers, "depth_layers", { INT_MIN, REFUSE }, { -1, REFUSE }, { 0, ACCEPT }, { 1, ACCEPT },
              { 2, ACCEPT }, { TG_MAX_DEPTH_LAYERS, ACCEPT }, { TG_MAX_DEPTH_LAYERS + 1, REFUSE },
              { INT_MAX, REFUSE });   /* technique hbil, read at full resolution */
    SWEEP_INT(shadow_map_size, "shadow_map_size", { INT_MIN, ACCEPT }, { 0, ACCEPT }, { 1, REFUSE },
              { TG_MIN_SHADOW_MAP - 1, REFUSE }, { TG_MIN_SHADOW_MAP, ACCEPT }, { TG_MAX_SHADOW_MAP, ACCEPT },
              { TG_MAX_SHADOW_MAP + 1, REFUSE }, { 13378, REFUSE }, { 1518500250, REFUSE }, { INT_MAX, REFUSE });
}

TEST(image_pixels_at_the_limit)
{
    static const long sizes[][3] = {   /* width, height, expectation */
        { TG_MAX_IMAGE_SIDE, TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE, ACCEPT },
        { TG_MAX_IMAGE_SIDE, TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE + 1, REFUSE },
        { TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE + 1, TG_MAX_IMAGE_SIDE, REFUSE },
        { TG_MAX_IMAGE_SIDE, TG_MAX_IMAGE_SIDE, TG_MAX_IMAGE_PIXELS >= (long)TG_MAX_IMAGE_SIDE * TG_MAX_IMAGE_SIDE ? ACCEPT : REFUSE },
        { 1, TG_MAX_IMAGE_SIDE, ACCEPT } };
    size_t k;
    for (k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        sweep_case c = new_case("pixels", (int)sizes[k][2]);
        c.q.width = (int)sizes[k][0];
        c.q.height = (int)sizes[k][1];
        snprintf(c.value, sizeof c.value, "%ldx%ld", sizes[k][0], sizes[k][1]);
        run_case(&c);
    }
}

TEST(aovs_bits_outside_the_list)
{
    static const uint32_t bits[][2] = { { 0, ACCEPT }, { 1, ACCEPT }, { ALL_AOVS, ACCEPT },
        { ALL_AOVS + 1u, REFUSE }, { 0x80000000u, REFUSE }, { 0xffffffffu, REFUSE } };
    size_t k;
    for (k = 0; k < sizeof bits / sizeof bits[0]; k++) {
        sweep_case c = new_case("aovs", (int)bits[k][1]);
        c.q.aovs = bits[k][0];
        snprintf(c.value, sizeof c.value, "0x%lx", (unsigned long)bits[k][0]);
        run_case(&c);
    }
}

/* which: 0 exposure, 1 radius, 2 thickness (rendered by the technique that reads it) */
static void real_case(const char *field, int which, tg_real v, const char *shown, int expect)
{
    sweep_case c = new_case(field, expect);
    if (which == 1) c.q.radius = v;
    else if (which == 2) { c.q.thickness = v; c.q.technique = TG_TECH_SSILVB; }
    else c.q.exposure = v;
    snprintf(c.value, sizeof c.value, "%s", shown);
    run_case(&c);
}

TEST(radius_and_exposure_at_their_extremes)
{
    static const long max[3] = { TG_MAX_EXPOSURE, TG_MAX_RADIUS, TG_MAX_THICKNESS };
    int k;
    for (k = 0; k < 3; k++) {
        const char *f = k == 2 ? "thickness" : k ? "radius" : "exposure";
        real_case(f, k, TG_REAL_MIN, "most negative", REFUSE);
        real_case(f, k, TG_R(-2.0f), "-2", REFUSE);
        real_case(f, k, TG_R(-0.5f), "-0.5", REFUSE);
        real_case(f, k, 0, "0", ACCEPT);
        real_case(f, k, TG_EPS, "smallest", ACCEPT);
        real_case(f, k, tg_from_int((int32_t)max[k]), "max", ACCEPT);
        real_case(f, k, tg_add(tg_from_int((int32_t)max[k]), TG_ONE), "max + 1", REFUSE);
        real_case(f, k, TG_REAL_MAX, "largest", REFUSE);
#if !TG_FIXED
        real_case(f, k, -HUGE_VALF, "-inf", REFUSE);
        real_case(f, k, HUGE_VALF, "inf", REFUSE);
        real_case(f, k, nanf(""), "nan", REFUSE);
#endif
    }
    real_case("radius", 1, TG_R(-1.0f), "-1 (unset)", ACCEPT);
    real_case("thickness", 2, TG_R(-1.0f), "-1 (unset)", ACCEPT);
    real_case("exposure", 0, TG_R(-1.0f), "-1", REFUSE);
}

TEST(refusal_names_the_field_and_the_value)
{
    tg_request q = small_request();
    tg_plan plan;
    tg_error err;
    char msg[600];
    q.slices = 20;
    CHECK(tg_plan_make(&plan, sweep_scene, &q, &err) == TG_ERR_INPUT, "slices 20 refused");
    tg_error_format(&err, msg, sizeof msg);
    CHECK(strcmp(msg, "error: slices must be 1..8, got 20") == 0, "message: %s", msg);
    q = small_request();
    q.exposure = TG_R(-2.5f);
    CHECK(tg_plan_make(&plan, sweep_scene, &q, &err) == TG_ERR_INPUT, "exposure -2.5 refused");
    tg_error_format(&err, msg, sizeof msg);
    CHECK(strcmp(msg, "error: exposure must be 0..1000, got -2.5") == 0, "message: %s", msg);
}

/* An unset thickness (technique ssilvb) is the resolved radius / TG_THICKNESS_RADIUS_DIVISOR, the
 * request's or the scene's; a set one is kept. */
TEST(thickness_unset_follows_the_radius)
{
    static const float radii[] = { -1.0f, 0.5f, 3.0f };
    int k;
    for (k = 0; k < 3; k++) {
        rendered r;
        tg_request q = small_request();
        q.technique = TG_TECH_SSILVB;
        q.radius = TG_R(radii[k]);
        if (!setup(&r, scene_text, &q)) { CHECK(0, "sets up: %s", r.msg); continue; }
        CHECK(fabs(check_d(r.plan.request.thickness) - check_d(r.plan.request.radius) / TG_THICKNESS_RADIUS_DIVISOR) < 1e-4,
              "radius %g: thickness %g", check_d(r.plan.request.radius), check_d(r.plan.request.thickness));
        CHECK(r.plan.request.radius > 0, "a radius");
        teardown(&r);
    }
    {
        rendered r;
        tg_request q = small_request();
        q.technique = TG_TECH_SSILVB;
        q.thickness = TG_R(0.25f);
        if (setup(&r, scene_text, &q)) {
            CHECK(r.plan.request.thickness == TG_R(0.25f), "kept: %g", check_d(r.plan.request.thickness));
            teardown(&r);
        } else CHECK(0, "sets up: %s", r.msg);
    }
}

/* Further depth layers (techniques ssilvb and hbil, and hbil at quarter
 * resolution): accepted up to TG_MAX_DEPTH_LAYERS, and each a plane of 4
 * bytes a pixel in the plan only when asked (at quarter resolution also
 * one of the half-resolution image's pixels), rendered finite; HBIL's
 * kernel over them is the bitmask's pass, not the horizon kernel's. */
static void layers_planned(tg_technique technique, int gi_scale)
{
    size_t bytes[TG_MAX_DEPTH_LAYERS + 1];
    int layers, b;
    for (layers = 1; layers <= TG_MAX_DEPTH_LAYERS + 1; layers++) {
        rendered r;
        tg_request q = small_request();
        int back = 0, behind = 0, half_back = 0, half_behind = 0, horizon = 0, bitmask = 0, hw, hh;
        q.technique = technique;
        q.depth_layers = layers;
        q.gi_scale = gi_scale;
        tgi_half_size(q.width, q.height, &hw, &hh);
        if (layers > TG_MAX_DEPTH_LAYERS) {
            CHECK(!setup(&r, scene_text, &q) && strstr(r.msg, "depth_layers must be"), "%d layers: %s", layers, r.msg);
            teardown(&r);
            continue;
        }
        if (!setup(&r, scene_text, &q)) { CHECK(0, "%d layers, gi_scale %d: %s", layers, gi_scale, r.msg); continue; }
        for (b = 0; b < r.plan.buffer_count; b++) {
            int half = strstr(r.plan.buffers[b].name, "quarter-res") != NULL;
            back += !half && strstr(r.plan.buffers[b].name, "back-face depth") != NULL;
            behind += !half && strstr(r.plan.buffers[b].name, "behind the back face") != NULL;
            half_back += half && strstr(r.plan.buffers[b].name, "back-face depth") != NULL;
            half_behind += half && strstr(r.plan.buffers[b].name, "behind the back face") != NULL;
        }
        for (b = 0; b < r.plan.pass_count; b++) {
            horizon += strstr(r.plan.passes[b], "HBIL horizon kernel") != NULL;
            bitmask += strstr(r.plan.passes[b], "HBIL over the depth layers") != NULL;
        }
        if (technique == TG_TECH_HBIL)
            CHECK(horizon == (layers < 2) && bitmask == (layers >= 2), "%d layers: horizon kernel %d, bitmask %d",
                  layers, horizon, bitmask);
        bytes[layers] = r.plan.total_bytes;
        CHECK(back == (layers >= 2) && behind == (layers >= 3), "%d layers: back-face plane %d, behind %d", layers,
              back, behind);
        CHECK(half_back == (gi_scale == 2 && layers >= 2) && half_behind == (gi_scale == 2 && layers >= 3),
              "%d layers, gi_scale %d: quarter-res back-face plane %d, behind %d", layers, gi_scale, half_back,
              half_behind);
        if (layers > 1) {
            size_t px = (size_t)q.width * (size_t)q.height + (gi_scale == 2 ? (size_t)hw * (size_t)hh : 0);
            /* the second layer an 8-bit code a pixel, the third a 32-bit depth (wide: tg_real each) */
            size_t per2 = TG_WIDE_STORAGE ? sizeof(tg_real) : 1, per3 = TG_WIDE_STORAGE ? sizeof(tg_real) : 4;
            size_t want = bytes[1] + per2 * px + (layers >= 3 ? per3 * px : 0);
            CHECK(bytes[layers] >= want && bytes[layers] <= want + 128 * (size_t)layers,
                  "%d layers: %.0f bytes, one layer %.0f", layers, (double)bytes[layers], (double)bytes[1]);
        }
        {
            tg_error err;
            CHECK(tg_frame_render(r.frame, 0, &err) == TG_OK && all_finite(&r), "%d layers: rendered finite", layers);
        }
        teardown(&r);
    }
}

TEST(depth_layers_are_planned_only_when_asked)
{
    static const tg_technique unread[] = { TG_TECH_GTAO, TG_TECH_SSAO, TG_TECH_REFERENCE, TG_TECH_PATHTRACE };
    size_t k;
    layers_planned(TG_TECH_SSILVB, 1);
    layers_planned(TG_TECH_HBIL, 1);
    layers_planned(TG_TECH_HBIL, 2);   /* --gi-quarter: the half-resolution image's layers too */
    /* refused where nothing reads them: the other techniques */
    for (k = 0; k < sizeof unread / sizeof unread[0]; k++) {
        rendered r;
        tg_request q = small_request();
        q.depth_layers = 2;
        q.technique = unread[k];
        CHECK(!setup(&r, scene_text, &q) && strstr(r.msg, "depth_layers must be 0..1 for technique "),
              "%s: %s", tg_technique_name(q.technique), r.msg);
        teardown(&r);
    }
}

/* tg_plan_reads_thickness says what the frames do: for every technique
 * and number of depth layers it accepts (hbil also at quarter resolution),
 * the AO of a thin and of a thick thickness differ where it says 1 and are
 * the same bits where it says 0 (the CLI's "--thickness is unread"
 * warning asks it).  The scene: a twosided plank in front of a wall, both
 * sheets (over depth layers the thickness is a twosided sheet's alone), the
 * wall beside the plank seeing behind it only when it is thin. */
static const char *sheet_text =
    "camera pos 0 0 3 target 0 0 0 fov 60\n"
    "material sheet albedo 0.7 0.7 0.7 twosided\n"
    "quad p0 -3 -3 -1  p1 3 -3 -1  p2 3 3 -1  p3 -3 3 -1 material sheet\n"
    "quad p0 -0.15 -2 -0.2  p1 0.15 -2 -0.2  p2 0.15 2 -0.2  p3 -0.15 2 -0.2 material sheet\n";

TEST(plan_reads_thickness_as_rendered)
{
    int t, layers, gi_scale, k;
    for (t = 0; t < TG_TECH_COUNT; t++)
        for (layers = 1; layers <= TG_MAX_DEPTH_LAYERS; layers++)
            for (gi_scale = 1; gi_scale <= (t == TG_TECH_HBIL ? 2 : 1); gi_scale++) {
                double *ao[2] = { NULL, NULL };
                int reads = -1, differ = 0, planned = 1;
                size_t n = 0, i;
                for (k = 0; k < 2; k++) {
                    rendered r;
                    tg_error err;
                    tg_request q = small_request();
                    q.technique = (tg_technique)t;
                    q.depth_layers = layers;
                    q.gi_scale = gi_scale;
                    q.aovs = 1u << TG_AOV_AO;
                    q.slices = 2;
                    q.samples = t == TG_TECH_PATHTRACE || t == TG_TECH_REFERENCE ? 4 : 8;
                    q.width = 32;
                    q.height = 24;
                    q.radius = TG_ONE;
                    q.thickness = k ? TG_R(4.0f) : TG_R(0.01f);
                    if (!setup(&r, sheet_text, &q)) {   /* refused only for layers the technique does not read */
                        CHECK(layers > 1 && strstr(r.msg, "depth_layers must be"), "%s, %d layers: %s",
                              tg_technique_name(q.technique), layers, r.msg);
                        planned = 0;
                        teardown(&r);
                        break;
                    }
                    if (k == 0) reads = tg_plan_reads_thickness(&r.plan);
                    else CHECK(tg_plan_reads_thickness(&r.plan) == reads, "%s: the answer changed with the thickness",
                               tg_technique_name(q.technique));
                    CHECK(tg_frame_render(r.frame, 0, &err) == TG_OK, "%s, %d layers: render", tg_technique_name(q.technique), layers);
                    n = (size_t)q.width * (size_t)q.height;
                    ao[k] = read_aov(&r, TG_AOV_AO);
                    teardown(&r);
                }
                if (planned) {
                    for (i = 0; i < n; i++) differ += ao[0][i] != ao[1][i];
                    CHECK(reads == (differ > 0), "%s, %d layers, gi_scale %d: tg_plan_reads_thickness %d, "
                          "%d of %d AO pixels differ between thickness 0.01 and 4",
                          tg_technique_name((tg_technique)t), layers, gi_scale, reads, differ, (int)n);
                }
                free(ao[0]);
                free(ao[1]);
            }
}

/* A scene with an environment and no gi radius: for light (colour, near,
 * far, irradiance) its radius is the bounds' diagonal /
 * TG_RADIUS_LIGHT_DIVISOR (6), for AO alone / TG_RADIUS_ENV_DIVISOR (30),
 * over one depth layer or more (what AO means does not change with the
 * layers), for both techniques that read layers and for HBIL at quarter
 * resolution; a radius the scene or the request gives is kept. */
TEST(gather_radius_reaches_further_for_light)
{
    static const char *text =
        "camera pos 1 2 -5 target 1 2 0\n"
        "material m albedo 0.5 0.5 0.5\n"
        "box min -1 0 0  max 2 4 12  material m\n"   /* diagonal 13 */
        "env uniform 1 1 1\n";
    static const tg_technique reads[] = { TG_TECH_HBIL, TG_TECH_SSILVB, TG_TECH_HBIL };   /* the last at gi_scale 2 */
    static const uint32_t outputs[] = { AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_BENT) | AOVBIT(TG_AOV_CONE) | AOVBIT(TG_AOV_DEPTH),
                                        AOVBIT(TG_AOV_COLOR), AOVBIT(TG_AOV_NEAR), AOVBIT(TG_AOV_FAR),
                                        AOVBIT(TG_AOV_IRRADIANCE) | AOVBIT(TG_AOV_AO), 0 /* colour */ };
    int k, layers, o;
    for (o = 0; o < (int)(sizeof outputs / sizeof outputs[0]); o++)
        for (k = 0; k < 3; k++)
            for (layers = 1; layers <= TG_MAX_DEPTH_LAYERS; layers++) {
                rendered r;
                tg_request q = small_request();
                int light = o > 0 && !TG_NO_COLOR;
                double want = 13.0 / (light ? TG_RADIUS_LIGHT_DIVISOR : TG_RADIUS_ENV_DIVISOR);
                if (o > 0 && TG_NO_COLOR) continue;
                q.aovs = outputs[o];
                q.technique = reads[k];
                q.gi_scale = k == 2 ? 2 : 1;
                q.depth_layers = TG_NO_TECHNIQUES ? 1 : layers;
                if (!setup_checked(&r, text, &q, "the scene")) continue;
                CHECK(fabs(check_d(r.plan.request.radius) - want) < 1e-3 * want, "%s%s, %d layers, outputs %#x: radius %g, want %g",
                      tg_technique_name(reads[k]), k == 2 ? " quarter" : "", layers, (unsigned)outputs[o],
                      check_d(r.plan.request.radius), want);
                teardown(&r);
                q.radius = TG_R(0.75f);
                if (!setup_checked(&r, text, &q, "the scene, a radius asked")) continue;
                CHECK(r.plan.request.radius == TG_R(0.75f), "%s, %d layers: the request's radius kept",
                      tg_technique_name(reads[k]), layers);
                teardown(&r);
            }
}

/* A scene across more than Q16.16's range (each coordinate within it): its
 * diagonal, 56569 for +-20000 in x and z, no longer fits tg_real; the radius
 * it gives (diagonal / 6 for light, / 30 for AO alone, with an env) is the
 * same in both number types (Q16.16 gave 5461 and 1092, the saturated
 * diagonal's), and so is a scene's across 60000 with no env, capped at
 * TG_MAX_RADIUS. */
TEST(gather_radius_of_a_scene_past_the_range)
{
    static const char *texts[2] = {
        "camera pos 0 3 8 target 0 0 0\n"
        "material m albedo 0.5 0.5 0.5\n"
        "quad p0 -20000 0 -20000 p1 -20000 0 20000 p2 20000 0 20000 p3 20000 0 -20000 material m\n"
        "env uniform 1 1 1\n",
        "camera pos 0 3 8 target 0 0 0\n"
        "material m albedo 0.5 0.5 0.5\n"
        "quad p0 -30000 0 -1 p1 -30000 0 1 p2 30000 0 1 p3 30000 0 -1 material m\n" };
    const double diagonal = sqrt(2.0) * 40000;
    int t, o;
    for (t = 0; t < 2; t++)
        for (o = 0; o < 2; o++) {
            rendered r;
            tg_request q = small_request();
            const int light = o == 1 && !TG_NO_COLOR;
            const double want = t == 1 ? TG_MAX_RADIUS
                              : diagonal / (light ? TG_RADIUS_LIGHT_DIVISOR : TG_RADIUS_ENV_DIVISOR);
            q.aovs = light ? AOVBIT(TG_AOV_COLOR) : AOVBIT(TG_AOV_AO);
            if (!setup_checked(&r, texts[t], &q, "a scene past the range")) continue;
            CHECK(fabs(check_d(r.plan.request.radius) - want) < 1e-3 * want, "scene %d, %s: radius %g, want %g", t,
                  light ? "light" : "AO", check_d(r.plan.request.radius), want);
            teardown(&r);
        }
}

/* The scene's gi values are held to the same limits (by the parser, or
 * else by the plan), with the same words. */
TEST(scene_gi_values_have_the_same_limits)
{
    static const char *lines[] = { "gi slices 20\n", "gi samples 300\n", "gi bounces 101\n" };
    static const char *field[] = { "slices", "samples", "bounces" };
    int k;
    for (k = 0; k < 3; k++) {
        char text[1024];
        rendered r;
        tg_request q = small_request();
        snprintf(text, sizeof text, "%s%s", scene_text, lines[k]);
        CHECK(!setup(&r, text, &q), "%s accepted", lines[k]);
        CHECK(r.status == TG_ERR_INPUT && strstr(r.msg, field[k]) && strstr(r.msg, "must be"),
              "%s: %s", lines[k], r.msg);
        teardown(&r);
    }
}

/* Rows outside [0, height): refused, the row zeroed, nothing past it written. */
TEST(aov_rows_outside_the_image_are_refused)
{
    static const int rows[] = { 6, 7, -1, INT_MAX, INT_MIN };
    rendered r;
    tg_request q = request(8, 6, ALL_AOVS);
    tg_error err;
    size_t k;
    int a, i;
    CHECK(setup(&r, scene_text, &q) && tg_frame_render(r.frame, 0, &err) == TG_OK, "renders");
    if (!r.ok) { teardown(&r); return; }
    for (a = 0; a < TG_AOV_COUNT; a++)
        for (k = 0; k < sizeof rows / sizeof rows[0]; k++) {
            tg_real out[3 * 8 + 1];
            uint8_t rgb[3 * 8 + 1];
            int n = 8 * tg_aov_channels((tg_aov)a), bad = 0;
            memset(out, 0x5a, sizeof out);
            memset(rgb, 0x5a, sizeof rgb);
            CHECK(tg_frame_aov_row(r.frame, (tg_aov)a, rows[k], out) == TG_ERR_INPUT, "aov %d row %d", a, rows[k]);
            CHECK(tg_frame_aov_row8(r.frame, (tg_aov)a, rows[k], rgb) == TG_ERR_INPUT, "aov8 %d row %d", a, rows[k]);
            for (i = 0; i < n; i++) bad += out[i] != 0;
            for (i = 0; i < 24; i++) bad += rgb[i] != 0;
            CHECK(bad == 0, "aov %d row %d: %d values not zero", a, rows[k], bad);
            CHECK(rgb[24] == 0x5a, "aov8 %d row %d wrote past the row", a, rows[k]);
        }
    for (a = 0; a < TG_AOV_COUNT; a++) {
        tg_real out[3 * 8];
        CHECK(tg_frame_aov_row(r.frame, (tg_aov)a, 0, out) == TG_OK, "row 0 of aov %d", a);
        CHECK(tg_frame_aov_row(r.frame, (tg_aov)a, 5, out) == TG_OK, "row 5 of aov %d", a);
    }
    teardown(&r);
}

int main(void)
{
    tg_arena arena;
    tg_error err;
    size_t bytes = 1u << 22;
    sweep_scene_mem = malloc(bytes);
    tg_arena_init(&arena, sweep_scene_mem, bytes);
    if (tg_scene_parse(scene_text, strlen(scene_text), "sweep.scene", NULL, &arena, &sweep_scene, &err) != TG_OK) {
        fprintf(stderr, "the sweep scene does not parse\n");
        return 2;
    }
    RUN(every_int_field_at_its_extremes);
    RUN(image_pixels_at_the_limit);
    RUN(aovs_bits_outside_the_list);
    RUN(radius_and_exposure_at_their_extremes);
    RUN(thickness_unset_follows_the_radius);
    RUN(depth_layers_are_planned_only_when_asked);
    RUN(plan_reads_thickness_as_rendered);
    RUN(gather_radius_reaches_further_for_light);
    RUN(gather_radius_of_a_scene_past_the_range);
    RUN(refusal_names_the_field_and_the_value);
    RUN(scene_gi_values_have_the_same_limits);
    RUN(aov_rows_outside_the_image_are_refused);
    free(sweep_scene_mem);
    return check_summary();
}
