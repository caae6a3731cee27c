/* SPDX-License-Identifier: MIT */
/*
 * test_techniques.c - every technique through the public API, on exact
 * cases:
 *   - the far field is consistent with the AO it uses: under a uniform sky
 *     L, with no light and no emitter, every pixel's colour is
 *     Lo = albedo / pi (1 - F0) pi L AO exactly (the AO AOV's own value,
 *     within its 8-bit and RGB9E5 storage), for any AO, in both far-field
 *     modes, for every technique whose far field is read from its AO;
 *   - the cone AOV is the cone whose cosine-weighted AO is the AO:
 *     cos(cone) = sqrt(1 - AO) (src/light/sh.h), not HBIL eq. 12's 1 - AO;
 *   - the ray-traced reference's AO does not depend on the image size (its
 *     rays start off the reconstructed position by that position's error
 *     bound, which grows with the pixels);
 *   - HBIL over three depth layers (its kernel the visibility bitmask)
 *     meets AO RMSE 0.04 against the reference on `spheres`, where one
 *     layer does not;
 *   - GTAO's multi-bounce fit (Jimenez et al. 2016, eq. 10): the cubic as
 *     published, in [AO, 1], 0 at AO 0, 1 at AO 1, growing with albedo and
 *     AO (its accuracy against the path tracer is measured by the bench);
 *   - request.ao_multibounce: the ao AOV is the published cubic of the AO
 *     computed without it, with the albedo's Rec. 709 luminance; the colour
 *     is the same bits; the G-buffer keeps the material only then (the
 *     default AO plan stays at its bytes); a value past 1 is refused;
 *   - technique pathtrace: a convex object under a uniform sky L (the
 *     furnace) reflects rho L and receives E = pi L at every pixel; its plan
 *     has no screen-space effect; a frame is deterministic and the next
 *     frame index draws other paths.  (src/ao/pathtrace.c's own analytic
 *     cases are in tests/test_pathtrace.c.)
 */
#include <math.h>
#include "frame_fixture.h"
#include "ao/ao.h"

#define PI 3.14159265358979

/* A floor, a wall and a box on the floor: AO from 0 to 1.  No light, no
 * emitter: the sky is the only light. */
static const char *groove_under_uniform_sky =
    "camera pos 3 2.5 5  target 0 0.6 0  fov 60\n"
    "material m albedo 0.6 0.5 0.4 f0 0.04\n"
    "quad p0 -6 0 -1  p1 -6 0 6  p2 6 0 6  p3 6 0 -1  material m\n"
    "quad p0 -6 0 -1  p1 6 0 -1  p2 6 5 -1  p3 -6 5 -1  material m\n"
    "box min -0.5 0 0 max 0.5 0.8 1 material m\n"
    "env uniform 0.8 1.0 1.3\n"
    "gi radius 2\n";

/* The far field reads these techniques' AO (SSDO and bent cones integrate
 * their own). */
static const tg_technique far_from_ao[] = {
    TG_TECH_HBIL, TG_TECH_GTAO, TG_TECH_HBAO, TG_TECH_SSAO, TG_TECH_VO, TG_TECH_REFERENCE, TG_TECH_SSILVB
};

static void uniform_sky_case(tg_technique t, int far_mode, int quarter)
{
    static const double L[3] = { 0.8, 1.0, 1.3 }, albedo[3] = { 0.6, 0.5, 0.4 }, f0 = 0.04;
    tg_request q = request(48, 36, AOVBIT(TG_AOV_COLOR) | AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_CONE) | AOVBIT(TG_AOV_DEPTH));
    rendered r;
    double *color, *ao, *cone, *depth, worst = 0, worst_cone = 0, ao_min = 1;
    int i, c, n = 48 * 36, bad = 0;
    q.technique = t;
    q.far_mode = far_mode;
    q.gi_scale = quarter ? 2 : 1;
    q.samples = 8;
    if (!setup(&r, groove_under_uniform_sky, &q)) {
        CHECK(0, "%s sets up: %s", tg_technique_name(t), r.msg);
        return;
    }
    CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "renders");
    color = read_aov(&r, TG_AOV_COLOR);
    ao = read_aov(&r, TG_AOV_AO);
    cone = read_aov(&r, TG_AOV_CONE);
    depth = read_aov(&r, TG_AOV_DEPTH);
    for (i = 0; i < n; i++) {
        double A = ao[i], dc = fabs(cone[i] - acos(sqrt(1 - A)));
        if (depth[i] == 0) continue;   /* sky: the environment itself */
        if (A < ao_min) ao_min = A;
        if (dc > worst_cone) worst_cone = dc;
        for (c = 0; c < 3; c++) {
            /* the AOV's AO is 8 bits of the value compose used (1/510), colour is RGB9E5 (2^-9) */
            double want = albedo[c] * (1 - f0) * L[c] * A, got = color[3 * i + c];
            double tol = albedo[c] * (1 - f0) * L[c] / 500 + want / 256 + (TG_FIXED ? 2e-3 : 1e-5);
            if (fabs(got - want) > worst) worst = fabs(got - want);
            if (fabs(got - want) > tol && bad++ < 3)
                CHECK(0, "%s far mode %d pixel %d ch %d: Lo %g, albedo (1 - F0) L AO = %g (AO %g)",
                      tg_technique_name(t), far_mode, i, c, got, want, A);
        }
    }
    printf("# %s%s, far mode %d: AO down to %.2f, largest |Lo - a (1-F0) L AO| %.2g, |cone - acos sqrt(1-AO)| %.2g\n",
           tg_technique_name(t), quarter ? " (quarter)" : "", far_mode, ao_min, worst, worst_cone);
    CHECK(bad == 0, "%s far mode %d: %d channels off", tg_technique_name(t), far_mode, bad);
    CHECK(ao_min < 0.7, "%s: the scene has occluded pixels (AO down to %g)", tg_technique_name(t), ao_min);
    CHECK(worst_cone < (TG_FIXED ? 2e-3 : 1e-4), "%s: cone = acos(sqrt(1 - AO)) within %g", tg_technique_name(t),
          worst_cone);
    free(color); free(ao); free(cone); free(depth);
    teardown(&r);
}

TEST(uniform_sky_gives_albedo_times_ao_for_every_technique)
{
    size_t k;
    for (k = 0; k < sizeof far_from_ao / sizeof far_from_ao[0]; k++) {
        uniform_sky_case(far_from_ao[k], 0, 0);
        uniform_sky_case(far_from_ao[k], 1, 0);
    }
    uniform_sky_case(TG_TECH_HBIL, 0, 1);
}

/* The groove (builtin) at 8x6 to 160x120: the mean AO of its surfaces is
 * the same at every size (an offset too small for large pixels made the
 * surfaces occlude themselves: mean 0.66 at 32x24 against 0.98). */
TEST(reference_ao_does_not_depend_on_the_image_size)
{
    static const int sizes[][2] = { { 160, 120 }, { 8, 6 }, { 16, 12 }, { 32, 24 }, { 64, 48 } };
    double mean_big = 0;
    int k, i;
    for (k = 0; k < 5; k++) {
        int w = sizes[k][0], h = sizes[k][1], n = 0;
        tg_request q = request(w, h, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
        rendered r;
        double *ao, *depth, sum = 0;
        q.technique = TG_TECH_REFERENCE;
        q.samples = 64;
        if (!setup(&r, tg_builtin_scene("groove"), &q)) { CHECK(0, "sets up: %s", r.msg); return; }
        CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "renders");
        ao = read_aov(&r, TG_AOV_AO); depth = read_aov(&r, TG_AOV_DEPTH);
        for (i = 0; i < w * h; i++)
            if (depth[i] > 0) { n++; sum += ao[i]; }
        if (k == 0) mean_big = sum / n;
        printf("# reference on the groove at %dx%d: mean AO %.4f over %d pixels\n", w, h, sum / n, n);
        CHECK(n > 0 && fabs(sum / n - mean_big) < 0.03, "%dx%d: mean AO %g, at 160x120 %g", w, h, sum / n, mean_big);
        free(ao); free(depth);
        teardown(&r);
    }
}

/* AO RMSE and bias over the geometry pixels of q's render against ref. */
static void ao_against(const char *scene, tg_request q, const double *ref, double *rmse, double *bias)
{
    rendered r;
    double *ao, *depth, se = 0, sum = 0;
    int i, f, n = 0, px = q.width * q.height;
    *rmse = *bias = 1;
    if (!setup_checked(&r, scene, &q, tg_technique_name(q.technique))) return;
    for (f = 0; f < q.frames; f++) CHECK(tg_frame_render(r.frame, f, NULL) == TG_OK, "frame %d renders", f);
    ao = read_aov(&r, TG_AOV_AO);
    depth = read_aov(&r, TG_AOV_DEPTH);
    for (i = 0; i < px; i++) {
        if (depth[i] <= 0) continue;
        se += (ao[i] - ref[i]) * (ao[i] - ref[i]);
        sum += ao[i] - ref[i];
        n++;
    }
    CHECK(n > px / 2, "geometry covers the image: %d of %d pixels", n, px);
    if (n) { *rmse = sqrt(se / n); *bias = sum / n; }
    free(ao); free(depth);
    teardown(&r);
}

/* HBIL on `spheres` at 80x60 (at gi_scale `scale`), 8 frames, one layer
 * and three against the reference, all at the scene's radius for AO: RMSE and
 * bias r[0], b[0] on one layer, r[1], b[1] on three. */
static void spheres_layers_against_the_reference(int scale, double r[2], double b[2])
{
    const char *scene = tg_builtin_scene("spheres");
    tg_request q = request(80, 60, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
    rendered rr;
    double *ref;
    tg_real radius;
    r[0] = r[1] = b[0] = b[1] = 1;
    q.technique = TG_TECH_REFERENCE;
    q.samples = 128;
    if (!setup_checked(&rr, scene, &q, "reference")) return;
    CHECK(tg_frame_render(rr.frame, 0, NULL) == TG_OK, "the reference renders");
    ref = read_aov(&rr, TG_AOV_AO);
    radius = rr.plan.request.radius;
    teardown(&rr);
    q = request(80, 60, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
    q.frames = 8;
    q.radius = radius;
    q.gi_scale = scale;
    q.depth_layers = 1;   /* not the plan's choice (two for AO alone in the open) */
    ao_against(scene, q, ref, &r[0], &b[0]);
    q.depth_layers = 3;
    ao_against(scene, q, ref, &r[1], &b[1]);
    printf("# hbil%s on spheres 80x60, 8 frames, AO against the reference: one layer %.4f / %+.4f, three layers "
           "%.4f / %+.4f\n", scale == 2 ? " --gi-quarter" : "", r[0], b[0], r[1], b[1]);
    free(ref);
}

/* HBIL over further depth layers (request.depth_layers 3: its kernel the
 * visibility bitmask, hbil_passes.c) against the ray-traced reference on
 * `spheres`, where one layer cannot see the floor under and behind the
 * spheres: 8 frames, AO RMSE and bias over the geometry pixels, all at
 * the scene's one-layer radius.  Measured
 * at 80x60: one layer 0.075 / +0.018, three layers 0.029 / +0.002 (both
 * number types).  The bound is the 0.04, and three layers must take
 * at least 40% off one layer's error. */
TEST(hbil_over_depth_layers_against_the_reference)
{
    double r[2], b[2];
    spheres_layers_against_the_reference(1, r, b);
    CHECK(r[1] < 0.04 && fabs(b[1]) < 0.01, "three layers: RMSE %g, bias %g", r[1], b[1]);
    CHECK(r[1] < 0.6 * r[0], "three layers %g against one layer %g", r[1], r[0]);
}

/* --gi-quarter over three depth layers (the bitmask's kernel on the
 * half-resolution image, its layers point-sampled down as its depth is;
 * the upsample's near horizon taking only samples solid down to the
 * tangent plane, src/gi/resample.c) against the same reference, at the
 * same radius: measured at 80x60, one layer 0.088 / +0.005, three layers
 * 0.057 / +0.006 (both number types; with the near horizon taking every
 * sample three layers were 0.066 / -0.014).  Since one layer's cap is the
 * near horizon's mean over 3x3 pixels (this round's twelfth session) one
 * layer is 0.057 / +0.011 too, so three layers must no longer take a
 * quarter off it, only be no worse; within the 0.06 at sizes of
 * 160x120 and more (here 0.065: a 40x30 half image) and its 0.01 bias. */
TEST(quarter_over_depth_layers_against_the_reference)
{
    double r[2], b[2];
    spheres_layers_against_the_reference(2, r, b);
    CHECK(r[1] < 0.065 && fabs(b[1]) < 0.01, "three layers: RMSE %g, bias %g", r[1], b[1]);
    CHECK(r[1] <= r[0], "three layers %g against one layer %g", r[1], r[0]);
}

/* AO alone from HBIL in a scene with an environment: the plan takes the
 * second depth layer (request.depth_layers 0 -> 2, with
 * TG_DEFAULT_LAYERED_AO_SAMPLES a side) at the radius AO has on one layer,
 * in the memory of one layer (the layer is a byte a pixel, and the
 * filtered AO lives in those bytes once the kernel has read them,
 * layout.c), and meets issue 14's AO goal on
 * builtin:spheres at 160x120 where one layer does not: measured against
 * 4096 directions 0.026 / +0.003, one layer 0.047 / -0.003 (both number
 * types); here against 256 directions, whose noise adds to both.  Light,
 * a closed room, quarter resolution and an asked layer count keep theirs. */
TEST(ao_alone_takes_a_second_layer_in_the_open)
{
    const char *spheres = tg_builtin_scene("spheres"), *cornell = tg_builtin_scene("cornell");
    tg_request q = request(160, 120, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH)), one;
    rendered r;
    double *ref, *aliased, *kept, r2, b2, r1, b1;
    size_t bytes_two, bytes_one;
    tg_real radius_two, radius_one;
    int i, differ = 0;
    if (!setup_checked(&r, spheres, &q, "AO alone")) return;
    CHECK(r.plan.request.depth_layers == (TGI_DEPTH_LAYERS ? 2 : 1), "spheres, AO alone: %d layers",
          r.plan.request.depth_layers);
    if (!TGI_DEPTH_LAYERS) { teardown(&r); return; }
    CHECK(r.plan.request.samples == TG_DEFAULT_LAYERED_AO_SAMPLES, "samples %d", r.plan.request.samples);
    bytes_two = r.plan.total_bytes;
    radius_two = r.plan.request.radius;
    teardown(&r);
    one = q;
    one.depth_layers = 1;
    if (!setup_checked(&r, spheres, &one, "AO alone, one layer")) return;
    bytes_one = r.plan.total_bytes;
    radius_one = r.plan.request.radius;
    teardown(&r);
    CHECK(radius_two == radius_one, "the radius AO has on one layer: %g, %g", check_d(radius_two), check_d(radius_one));
    CHECK(bytes_two == bytes_one, "no more memory than one layer (the layer's byte a pixel is the filtered "
          "AO's): %.0f against %.0f", (double)bytes_two, (double)bytes_one);
    {   /* what keeps one layer */
        static const struct { const char *what; int scene_cornell, color, quarter, layers; } keep[] = {
            { "with colour", 0, 1, 0, 0 }, { "a closed room", 1, 0, 0, 0 }, { "quarter resolution", 0, 0, 1, 0 },
            { "one layer asked", 0, 0, 0, 1 } };
        size_t k;
        for (k = 0; k < sizeof keep / sizeof keep[0]; k++) {
            tg_request c = q;
            if (keep[k].color) c.aovs |= AOVBIT(TG_AOV_COLOR);
            if (keep[k].quarter) c.gi_scale = 2;
            c.depth_layers = keep[k].layers;
            if (!setup_checked(&r, keep[k].scene_cornell ? cornell : spheres, &c, keep[k].what)) continue;
            CHECK(r.plan.request.depth_layers == 1, "%s: %d layers", keep[k].what, r.plan.request.depth_layers);
            teardown(&r);
        }
    }
    /* the filtered AO in the layer's bytes is the AO kept apart (with the
     * bent normal asked the results take their own plane) */
    q.frames = 3;
    {
        tg_request bent = q;
        bent.aovs |= AOVBIT(TG_AOV_BENT);
        bent.depth_layers = 2;
        bent.samples = TG_DEFAULT_LAYERED_AO_SAMPLES;
        aliased = NULL;
        if (setup_checked(&r, spheres, &q, "AO alone, 3 frames")) {
            for (i = 0; i < 3; i++) tg_frame_render(r.frame, i, NULL);
            aliased = read_aov(&r, TG_AOV_AO);
            teardown(&r);
        }
        if (aliased && setup_checked(&r, spheres, &bent, "AO and bent, 3 frames")) {
            for (i = 0; i < 3; i++) tg_frame_render(r.frame, i, NULL);
            kept = read_aov(&r, TG_AOV_AO);
            for (i = 0; i < 160 * 120; i++) differ += aliased[i] != kept[i];
            CHECK(differ == 0, "%d AO pixels differ from the results kept in their own plane", differ);
            free(kept);
            teardown(&r);
        }
        free(aliased);
    }
    /* against the reference */
    q.frames = 8;
    {
        tg_request rq = request(160, 120, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
        rq.technique = TG_TECH_REFERENCE;
        rq.samples = 256;
        rq.radius = radius_one;
        if (!setup_checked(&r, spheres, &rq, "reference")) return;
        CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "the reference renders");
        ref = read_aov(&r, TG_AOV_AO);
        teardown(&r);
    }
    ao_against(spheres, q, ref, &r2, &b2);
    one.frames = 8;
    ao_against(spheres, one, ref, &r1, &b1);
    printf("# hbil on spheres 160x120, AO alone, 8 frames, against the reference (256 directions): the plan's two "
           "layers %.4f / %+.4f, one layer %.4f / %+.4f\n", r2, b2, r1, b1);
    CHECK(r2 <= 0.04 && fabs(b2) <= 0.01, "two layers: RMSE %g, bias %g", r2, b2);
    CHECK(r2 < 0.75 * r1, "two layers %g against one layer %g", r2, r1);
    free(ref);
}

TEST(gtao_multibounce_fit)
{
    int i, j;
    double worst = 0;
    for (j = 0; j <= 10; j++) {
        double rho = j / 10.0, prev_k = -1;
        double a = 2.0404 * rho - 0.3324, b = -4.7951 * rho + 0.6417, c = 2.7552 * rho + 0.6903;
        CHECK(check_d(tgi_ao_multibounce(0, TG_R((float)rho))) == 0, "AO 0 stays 0 (albedo %g)", rho);
        CHECK(tgi_ao_multibounce(TG_ONE, TG_R((float)rho)) == TG_ONE, "AO 1 stays 1 (albedo %g)", rho);
        for (i = 0; i <= 40; i++) {
            double k = check_d(TG_R((float)(i / 40.0))), want = fmin(1, fmax(k, ((a * k + b) * k + c) * k));
            double got = check_d(tgi_ao_multibounce(TG_R((float)k), TG_R((float)rho)));
            double lower = j > 0 ? check_d(tgi_ao_multibounce(TG_R((float)k), TG_R((float)(rho - 0.1)))) : 0;
            if (fabs(got - want) > worst) worst = fabs(got - want);
            CHECK(got >= k - 1e-6 && got <= 1, "in [AO, 1]: AO %g albedo %g gives %g", k, rho, got);
            CHECK(got >= lower - 1e-6, "grows with albedo at AO %g", k);
            CHECK(got >= prev_k - 1e-6, "grows with AO at albedo %g", rho);
            prev_k = got;
        }
    }
    printf("# GTAO multi-bounce fit: largest difference from the published cubic %.2g\n", worst);
    CHECK(worst < (TG_FIXED ? 3e-4 : 1e-6), "the published cubic within %g", worst);
    CHECK(fabs(check_d(tgi_ao_multibounce(TG_R(0.5f), TG_R(0.8f))) - 0.811125) < 2e-4, "AO 0.5, albedo 0.8: %g",
          check_d(tgi_ao_multibounce(TG_R(0.5f), TG_R(0.8f))));
}

/* The cubic of GTAO eq. 10 in double. */
static double published_multibounce(double k, double rho)
{
    double a = 2.0404 * rho - 0.3324, b = -4.7951 * rho + 0.6417, c = 2.7552 * rho + 0.6903;
    return fmin(1, fmax(k, ((a * k + b) * k + c) * k));
}

TEST(ao_multibounce_option_applies_the_fit_to_the_ao_output)
{
    const double rho = 0.2126 * 0.6 + 0.7152 * 0.5 + 0.0722 * 0.4;   /* the groove's albedo, luminance */
    const int w = 48, h = 36, n = 48 * 36;
    tg_request q = request(w, h, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
    rendered plain, fit;
    double *ao0, *ao1, *depth, worst = 0, gain = 0;
    unsigned char *c0, *c1;
    size_t n0, n1;
    int i, bad = 0, k;
    q.technique = TG_TECH_GTAO;
    if (!setup(&plain, groove_under_uniform_sky, &q)) { CHECK(0, "sets up: %s", plain.msg); return; }
    q.ao_multibounce = 1;
    if (!setup(&fit, groove_under_uniform_sky, &q)) { CHECK(0, "sets up: %s", fit.msg); teardown(&plain); return; }
    /* the option carves the material index (2 bytes a pixel) and nothing else */
    CHECK(fit.plan.total_bytes > plain.plan.total_bytes && fit.plan.total_bytes - plain.plan.total_bytes <= (size_t)(2 * n + 64),
          "bytes %zu, without the option %zu", fit.plan.total_bytes, plain.plan.total_bytes);
    for (k = 0; k < fit.plan.buffer_count; k++)
        if (strstr(fit.plan.buffers[k].name, "G-buffer"))
            CHECK(strstr(fit.plan.buffers[k].name, "material") && !strstr(fit.plan.buffers[k].name, "no material"),
                  "the G-buffer keeps the material: %s", fit.plan.buffers[k].name);
    for (k = 0; k < plain.plan.buffer_count; k++)
        if (strstr(plain.plan.buffers[k].name, "G-buffer"))
            CHECK(strstr(plain.plan.buffers[k].name, "no material"), "the default AO plan has none: %s", plain.plan.buffers[k].name);
    CHECK(tg_frame_render(plain.frame, 0, NULL) == TG_OK && tg_frame_render(fit.frame, 0, NULL) == TG_OK, "renders");
    ao0 = read_aov(&plain, TG_AOV_AO); ao1 = read_aov(&fit, TG_AOV_AO); depth = read_aov(&fit, TG_AOV_DEPTH);
    for (i = 0; i < n; i++) {
        double want = depth[i] == 0 ? ao0[i] : published_multibounce(ao0[i], rho), d = fabs(ao1[i] - want);
        if (d > worst) worst = d;
        gain = fmax(gain, ao1[i] - ao0[i]);
        if (d > (TG_FIXED ? 4e-4 : 1e-5) && bad++ < 3)
            CHECK(0, "pixel %d: AO %g, fit %g, want %g (albedo luminance %g)", i, ao0[i], ao1[i], want, rho);
    }
    printf("# ao multi-bounce on the groove (albedo luminance %.4f): largest |AO' - cubic(AO)| %.2g, brightest gain %.3f\n",
           rho, worst, gain);
    CHECK(bad == 0, "%d pixels off the published cubic", bad);
    CHECK(gain > 0.05, "the fit brightens the occluded pixels (by up to %g)", gain);
    free(ao0); free(ao1); free(depth);
    teardown(&plain); teardown(&fit);
    /* colour is composed from the AO as computed: the same bits with the option */
    q = request(24, 18, AOVBIT(TG_AOV_COLOR) | AOVBIT(TG_AOV_AO));
    q.technique = TG_TECH_GTAO;
    if (!setup(&plain, groove_under_uniform_sky, &q)) { CHECK(0, "colour sets up: %s", plain.msg); return; }
    q.ao_multibounce = 1;
    if (!setup(&fit, groove_under_uniform_sky, &q)) { CHECK(0, "colour sets up: %s", fit.msg); teardown(&plain); return; }
    CHECK(tg_frame_render(plain.frame, 0, NULL) == TG_OK && tg_frame_render(fit.frame, 0, NULL) == TG_OK, "renders");
    {
        double *a = read_aov(&plain, TG_AOV_COLOR), *b = read_aov(&fit, TG_AOV_COLOR);
        CHECK(memcmp(a, b, sizeof(double) * 3 * 24 * 18) == 0, "colour unchanged by the option");
        free(a); free(b);
    }
    c0 = raw_aovs(&plain, &n0); c1 = raw_aovs(&fit, &n1);
    CHECK(n0 == n1 && memcmp(c0, c1, n0) != 0, "the ao AOV differs");
    free(c0); free(c1);
    teardown(&plain); teardown(&fit);
    /* refusals */
    q = request(8, 6, AOVBIT(TG_AOV_AO));
    q.ao_multibounce = 2;
    CHECK(!setup(&plain, groove_under_uniform_sky, &q) && plain.status == TG_ERR_INPUT && strstr(plain.msg, "ao_multibounce"),
          "ao_multibounce 2 refused: %s", plain.msg);
    teardown(&plain);
    q.ao_multibounce = -1;
    CHECK(!setup(&plain, groove_under_uniform_sky, &q) && plain.status == TG_ERR_INPUT, "ao_multibounce -1 refused");
    teardown(&plain);
}

static const char *furnace_sphere =
    "camera pos 0 0 4  target 0 0 0  fov 40\n"
    "material m albedo 0.8 0.6 0.4 f0 0\n"
    "sphere center 0 0 0 radius 1 material m segments 48\n"
    "env uniform 0.5 0.5 0.5\n"
    "gi radius 0.3 bounces 1\n";

TEST(pathtrace_furnace_through_the_frame)
{
    static const double albedo[3] = { 0.8, 0.6, 0.4 }, L = 0.5;
    tg_request q = request(40, 30, AOVBIT(TG_AOV_COLOR) | AOVBIT(TG_AOV_IRRADIANCE) | AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
    rendered r;
    double *color, *irr, *ao, *depth, sum[3] = { 0, 0, 0 }, worst_e = 0;
    unsigned char *bits0, *bits0b, *bits1;
    size_t n0, n0b, n1;
    int i, c, n = 0, k;
    q.technique = TG_TECH_PATHTRACE;
    q.samples = 16;
    if (!setup(&r, furnace_sphere, &q)) { CHECK(0, "sets up: %s", r.msg); return; }
    CHECK(r.plan.effects == 0, "no screen-space effect (effects %u)", (unsigned)r.plan.effects);
    CHECK(r.plan.request.samples == 16 && r.plan.request.bounces == TG_DEFAULT_PATHTRACE_BOUNCES,
          "samples as asked, bounces the path tracer's default (the scene's gi line is not read): %d, %d",
          r.plan.request.samples, r.plan.request.bounces);
    for (k = 0; k < r.plan.pass_count; k++)
        CHECK(!strstr(r.plan.passes[k], "compose") && !strstr(r.plan.passes[k], "direct light"), "pass %s", r.plan.passes[k]);
    CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "renders");
    color = read_aov(&r, TG_AOV_COLOR); irr = read_aov(&r, TG_AOV_IRRADIANCE);
    ao = read_aov(&r, TG_AOV_AO); depth = read_aov(&r, TG_AOV_DEPTH);
    for (i = 0; i < 40 * 30; i++) {
        CHECK(ao[i] == 1, "AO reads 1");
        if (depth[i] == 0) {
            CHECK(fabs(color[3 * i] - L) < 2e-3 && irr[3 * i] == 0, "sky: L, E 0");
            continue;
        }
        for (c = 0; c < 3; c++) sum[c] += color[3 * i + c];
        if (fabs(irr[3 * i] - PI * L) > worst_e) worst_e = fabs(irr[3 * i] - PI * L);
        n++;
    }
    printf("# pathtrace furnace, %d pixels: mean Lo %.4f %.4f %.4f (rho L %.2f %.2f %.2f), worst |E - pi L| %.3g\n", n,
           sum[0] / n, sum[1] / n, sum[2] / n, albedo[0] * L, albedo[1] * L, albedo[2] * L, worst_e);
    CHECK(n > 300, "the sphere covers %d pixels", n);
    for (c = 0; c < 3; c++)
        CHECK(fabs(sum[c] / n / (albedo[c] * L) - 1) < (TG_FIXED ? 0.03 : 0.01), "channel %d: mean Lo %g, rho L %g", c,
              sum[c] / n, albedo[c] * L);
    free(color); free(irr); free(ao); free(depth);
    teardown(&r);
    /* the furnace has no noise (every path escapes); the groove has */
    q = request(24, 18, AOVBIT(TG_AOV_COLOR));
    q.technique = TG_TECH_PATHTRACE;
    q.samples = 4;
    if (!setup(&r, groove_under_uniform_sky, &q)) { CHECK(0, "groove sets up: %s", r.msg); return; }
    CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "renders");
    bits0 = raw_aovs(&r, &n0);
    CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "renders again");
    bits0b = raw_aovs(&r, &n0b);
    CHECK(n0 == n0b && memcmp(bits0, bits0b, n0) == 0, "the same frame index gives the same bits");
    CHECK(tg_frame_render(r.frame, 1, NULL) == TG_OK, "renders frame 1");
    bits1 = raw_aovs(&r, &n1);
    CHECK(n1 == n0 && memcmp(bits0, bits1, n0) != 0, "frame 1 draws other paths");
    free(bits0); free(bits0b); free(bits1);
    teardown(&r);
}

int main(void)
{
    RUN(uniform_sky_gives_albedo_times_ao_for_every_technique);
    RUN(reference_ao_does_not_depend_on_the_image_size);
    RUN(hbil_over_depth_layers_against_the_reference);
    RUN(quarter_over_depth_layers_against_the_reference);
    RUN(ao_alone_takes_a_second_layer_in_the_open);
    RUN(gtao_multibounce_fit);
    RUN(ao_multibounce_option_applies_the_fit_to_the_ao_output);
    RUN(pathtrace_furnace_through_the_frame);
    return check_summary();
}
