/* SPDX-License-Identifier: MIT */
/*
 * test_reproject.c - gather reprojection (HBIL sec. 3.2) and push/pull
 * hole filling (Kraus 2009), plus the spatial/temporal filter.
 *
 * Scene: a floor y = -1 and a wall z = -3 ray cast per pixel; checks
 * identity for a static view, that a moved camera fetches last frame's
 * radiance from where the same surface was, finite hole-free output after a
 * camera cut and after a teleport, holes filled within the range of valid
 * inputs.  Buffers are in the build's storage (storage_fixture.h).
 */
#include <stdlib.h>
#include "check.h"
#include "storage_fixture.h"
#include "raster/view.h"
#include "gi/reproject.h"
#include "gi/pushpull.h"
#include "gi/denoise.h"
#include "gi/temporal.h"
#include "raster/motion.h"

#define W 37
#define H 23
#define N (W * H)

static tgi_view make_view(float ex, float ey, float ez)
{
    tgi_view v;
    tgi_view_make(&v, tg_v3(tg_from_float(ex), tg_from_float(ey), tg_from_float(ez)), tg_v3(0, 0, 0),
                 tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f), TG_R(100.0f), W, H);
    return v;
}

/* World point of pixel i of v at view depth z (view.h conventions). */
static void world_of(const tgi_view *v, int i, double z, double p[3])
{
    double ppu = check_d(v->pixels_per_unit);
    double X = (i % W + 0.5 - W / 2.0) / ppu, Y = (H / 2.0 - (i / W + 0.5)) / ppu;
    p[0] = check_d(v->eye.x) + z * (check_d(v->right.x) * X + check_d(v->up.x) * Y + check_d(v->forward.x));
    p[1] = check_d(v->eye.y) + z * (check_d(v->right.y) * X + check_d(v->up.y) * Y + check_d(v->forward.y));
    p[2] = check_d(v->eye.z) + z * (check_d(v->right.z) * X + check_d(v->up.z) * Y + check_d(v->forward.z));
}

static int no_floor;   /* 1: the wall alone */

/* The floor y = -1 and the wall z = -3 ray cast per pixel into g (sky: 0). */
static void scene_cast(const tgi_view *v, tgi_gbuffer *g)
{
    int i;
    for (i = 0; i < N; i++) {
        double d[3], t = 1e30, tt, e1 = check_d(v->eye.y), e2 = check_d(v->eye.z), p[3];
        world_of(v, i, 1.0, p);
        d[1] = p[1] - e1; d[2] = p[2] - e2;
        if (d[1] < -1e-9 && !no_floor) { tt = (-1 - e1) / d[1]; if (tt > 0 && tt < t) t = tt; }
        if (d[2] < -1e-9) { tt = (-3 - e2) / d[2]; if (tt > 0 && tt < t) t = tt; }
        sf_gbuffer_set(g, (size_t)i, t > 1e29 ? 0 : tg_from_float((float)t), tg_v3(0, TG_ONE, 0), 0);
    }
}

static tgi_gbuffer g0, g1;
static tgi_prev_geometry prev;
static tgi_rgb history, out;

static void setup(const tgi_view *v0)
{
    size_t i;
    tgi_gview view;
    if (!g0.depth) {
        sf_gbuffer_alloc(&g0, W, H, NULL, 0);
        sf_gbuffer_alloc(&g1, W, H, NULL, 0);
        sf_prev_alloc(&prev, N + W);      /* a row past the image: what a larger buffer would hold */
        sf_rgb_alloc(&history, N + W);
        sf_rgb_alloc(&out, N);
    }
    scene_cast(v0, &g0);
    view = sf_view(&g0, v0);
    for (i = 0; i < N; i++) {
        tgi_prev_keep(&prev, i, &view, i);
        tgi_rgb_set(&history, i, tg_v3(tg_from_float(0.1f + (float)(i % 7) * 0.2f),
                                       tg_from_float(0.5f + (float)(i % 5) * 0.1f), tg_from_float((float)(i % 3))));
    }
}

static void gather(const tgi_view *v0, const tgi_view *v1, const tgi_gbuffer *g, const tgi_rgb *hist)
{
    tgi_reproject_io io;
    tgi_gview view = sf_view(g, v1);
    memset(&io, 0, sizeof io);
    io.g = &view;
    io.prev_view = v0;
    io.prev_geometry = &prev;
    io.prev = hist;
    io.out = &out;
    tgi_reproject_gather_rows(&io, 0, H);
}

static int holes(void)
{
    int i, n = 0;
    for (i = 0; i < N; i++) n += tgi_rgb_is_hole(&out, (size_t)i);
    return n;
}

TEST(static_view_is_identity)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_gview view;
    int i, bad = 0;
    setup(&v);
    gather(&v, &v, &g0, &history);
    view = sf_view(&g0, &v);
    for (i = 0; i < N; i++) {
        tg_vec3 a = tgi_rgb_get(&out, (size_t)i), b = tgi_rgb_get(&history, (size_t)i);
        if (tgi_gv_is_sky(&view, (size_t)i)) { bad += !tgi_rgb_is_hole(&out, (size_t)i); continue; }
        bad += tgi_rgb_is_hole(&out, (size_t)i) || a.x != b.x || a.y != b.y || a.z != b.z;
    }
    CHECK(bad == 0, "%d pixels differ from the source", bad);
}

/* Screen position (continuous pixels) of world point p in view v. */
static void project(const tgi_view *v, const double p[3], double *px, double *py)
{
    double d[3] = { p[0] - check_d(v->eye.x), p[1] - check_d(v->eye.y), p[2] - check_d(v->eye.z) };
    double x = d[0] * check_d(v->right.x) + d[1] * check_d(v->right.y) + d[2] * check_d(v->right.z);
    double y = d[0] * check_d(v->up.x) + d[1] * check_d(v->up.y) + d[2] * check_d(v->up.z);
    double z = d[0] * check_d(v->forward.x) + d[1] * check_d(v->forward.y) + d[2] * check_d(v->forward.z);
    double ppu = check_d(v->pixels_per_unit);
    *px = W / 2.0 + x / z * ppu;
    *py = H / 2.0 - y / z * ppu;
}

/* A moved camera fetches each surface's radiance from the pixel where last
 * frame saw it (the pixel its point projects into): the history holds each
 * pixel's own coordinates. */
TEST(moved_camera_fetches_the_same_surface)
{
    tgi_view v0 = make_view(0.3f, 0.5f, 2.0f), v1 = make_view(0.1f, 0.55f, 1.8f);
    tgi_gview view1;
    int i, fetched = 0, bad = 0;
    setup(&v0);
    for (i = 0; i < N; i++) tgi_rgb_set(&history, (size_t)i, tg_v3(tg_from_int(i % W + 1), tg_from_int(i / W + 1), 0));
    scene_cast(&v1, &g1);
    gather(&v0, &v1, &g1, &history);
    view1 = sf_view(&g1, &v1);
    for (i = 0; i < N; i++) {
        tg_vec3 c = tgi_rgb_get(&out, (size_t)i);
        double p[3], px, py;
        if (tgi_rgb_is_hole(&out, (size_t)i)) continue;
        fetched++;
        world_of(&v1, i, check_d(tgi_gv_depth(&view1, (size_t)i)), p);
        project(&v0, p, &px, &py);
        if (fabs(px - (check_d(c.x) - 0.5)) > 0.51 || fabs(py - (check_d(c.y) - 0.5)) > 0.51) bad++;
    }
    printf("# moved camera: %d of %d pixels fetched their history\n", fetched, N);
    CHECK(fetched > N / 2, "only %d pixels found their history", fetched);
    CHECK(bad == 0, "%d pixels fetched radiance from another pixel than the one their surface was in", bad);
}

static void check_filled(const char *what, double lo, double hi)
{
    int i, bad = 0;
    for (i = 0; i < N; i++) {
        tg_vec3 c = tgi_rgb_get(&out, (size_t)i);
        double a = check_d(c.x);
        if (tgi_rgb_is_hole(&out, (size_t)i) || !(a == a) || a < lo || a > hi || c.y < 0 || c.z < 0) bad++;
    }
    CHECK(bad == 0, "%s: %d pixels outside [%g, %g], not finite or holes", what, bad, lo, hi);
}

TEST(camera_cut_gives_zero)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_rgb none = tgi_rgb_none();
    void *s = malloc(tgi_pushpull_bytes(W, H));
    int i, nz = 0;
    setup(&v);
    gather(&v, &v, &g0, &none);    /* no history */
    CHECK(holes() == N, "a cut leaves every pixel a hole");
    tgi_pushpull_fill(W, H, &out, s);
    for (i = 0; i < N; i++) {
        tg_vec3 c = tgi_rgb_get(&out, (size_t)i);
        nz += tgi_rgb_is_hole(&out, (size_t)i) || c.x != 0 || c.y != 0 || c.z != 0;
    }
    CHECK(nz == 0, "camera cut: %d pixels not zero", nz);
    free(s);
}

TEST(teleport_is_finite_and_hole_free)
{
    tgi_view v0 = make_view(0.3f, 0.5f, 2.0f), v1 = make_view(-1.5f, 0.2f, 1.0f);
    void *s = malloc(tgi_pushpull_bytes(W, H));
    int n;
    setup(&v0);
    scene_cast(&v1, &g1);
    gather(&v0, &v1, &g1, &history);
    n = holes();
    CHECK(n > 0 && n < N, "a teleport leaves some holes (%d)", n);
    tgi_pushpull_fill(W, H, &out, s);
    check_filled("teleport", 0.0999 - sf_rgb_rounding(2.0), 1.3001 + sf_rgb_rounding(2.0)); /* the source range */
    free(s);
}

TEST(pushpull_fills_within_range)
{
    int i, k;
    void *s = malloc(tgi_pushpull_bytes(W, H));
    for (k = 0; k < 3; k++) {
        for (i = 0; i < N; i++) {
            int valid = k == 0 ? (i % 3 == 0) : k == 1 ? (i == 17) : (i < N / 2);
            if (valid) tgi_rgb_set(&out, (size_t)i, tg_v3(tg_from_float(2.0f + (float)(i % 11) * 0.25f), TG_ONE, 0));
            else tgi_rgb_set_hole(&out, (size_t)i);
        }
        tgi_pushpull_fill(W, H, &out, s);
        check_filled("push/pull", 2.0, 4.5);
        for (i = 0; i < N; i++) CHECK_NEAR(check_d(tgi_rgb_get(&out, (size_t)i).y), 1.0, 1e-3);
        for (i = 0; i < N; i++) {
            int valid = k == 0 ? (i % 3 == 0) : k == 1 ? (i == 17) : (i < N / 2);
            if (valid) CHECK(tgi_rgb_get(&out, (size_t)i).x == tg_from_float(2.0f + (float)(i % 11) * 0.25f),
                             "valid pixel %d changed", i);
        }
    }
    {   /* odd and tiny sizes */
        tgi_rgb one;
        tg_vec3 c;
        sf_rgb_alloc(&one, 1);
        tgi_rgb_set_hole(&one, 0);
        tgi_pushpull_fill(1, 1, &one, s);
        c = tgi_rgb_get(&one, 0);
        CHECK(!tgi_rgb_is_hole(&one, 0) && c.x == 0 && c.y == 0 && c.z == 0, "1x1 hole without data gives 0");
        sf_rgb_free(&one);
    }
    free(s);
}

/* The spatial filter keeps AO in the range of its inputs and leaves a
 * constant field constant. */
TEST(filter_preserves_range_and_constants)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    static tg_real ao[N];
    tgi_gview g;
    tgi_gresult r, filtered;
    tgi_denoise_params p;
    int i, k, bad = 0;
    setup(&v);
    g = sf_view(&g0, &v);
    sf_results_alloc(&r, N, 1, 0, 1);
    sf_results_alloc(&filtered, N, 1, 0, 1);
    tgi_denoise_defaults(&p);
    for (k = 0; k < 2; k++) {
        for (i = 0; i < N; i++) {
            /* varies inside every 4x4 block, or constant */
            tgi_gr_set_ao(&r, (size_t)i, k ? TG_R(0.5f) : tg_from_float(0.25f + (float)(i % 4) * 0.25f));
            tgi_gr_set_bent(&r, (size_t)i, tg_v3(0, TG_ONE, 0));
            tgi_gr_set_near(&r, (size_t)i, tg_v3(TG_ONE, TG_R(0.5f), 0));
        }
        tgi_denoise_rows(&p, &g, &r, &filtered, 0, H);
        sf_results_read(&filtered, N, ao, NULL, NULL, NULL, NULL, NULL, NULL, NULL);
        for (i = 0; i < N; i++) {
            double a = check_d(ao[i]);
            tg_vec3 e = tgi_gr_near(&filtered, (size_t)i), b = tgi_gr_bent(&filtered, (size_t)i);
            if (tgi_gv_is_sky(&g, (size_t)i)) continue;
            if (k == 0 && !(a >= 0.25 && a <= 1.0)) bad++;
            if (k == 1 && (fabs(a - 0.5) > 1.0 / 255 || fabs(check_d(e.x) - 1) > 1e-3 || fabs(check_d(e.y) - 0.5) > 1e-3 ||
                           check_d(b.y) < 0.9999)) bad++;
        }
    }
    CHECK(bad == 0, "filtered AO out of range, or a constant field changed: %d", bad);
    sf_results_free(&r);
    sf_results_free(&filtered);
}

/* The filter of a pixel, straight from its formula (denoise.h): every tap
 * of the 5x5 window in the image, not sky, with |z_j - z_i| < tol z_i,
 * weighs w_x w_y (1 - |z_j - z_i| / (tol z_i)) max(0, n_i . n_j)^8, the
 * products rounded as tg_mul rounds them and the sums in tgi_wide, in the
 * order of the taps (rows, then columns). */
/* The filter's weighted average: in float the sum of products over the
 * weights' sum; in Q16.16 the products exact (Q32) and one rounding, half
 * away from zero, in the division. */
#if TG_FIXED
static tgi_wide formula_product(tg_real v, tg_real w) { return (tgi_wide)v * w; }
static tg_real formula_average(tgi_wide s, tgi_wide ws)
{
    tgi_wide q = (s < 0 ? -s : s) * 2 / ws, r = (q + 1) / 2;   /* round(|s| / ws), halves up */
    return (tg_real)(s < 0 ? -r : r);
}
#else
static tgi_wide formula_product(tg_real v, tg_real w) { return tgi_wide_mul(v, w); }
static tg_real formula_average(tgi_wide s, tgi_wide ws) { return tg_div(s, ws); }
#endif

static tgi_gr_value filter_formula(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r, int x, int y)
{
    static const float tap_w[5] = { 0.5f, 1, 1, 1, 0.5f };
    size_t i = tgi_gv_index(g, x, y);
    tgi_wide ws = 0, ao = 0, b[3] = { 0, 0, 0 }, e[3] = { 0, 0, 0 };
    tg_real zi, ztol, inv;
    tg_vec3 ni;
    tgi_gr_value v;
    int xx, yy, c;
    if (tgi_gv_is_sky(g, i)) return tgi_gr_get_kept(r, i);
    zi = tgi_gv_depth(g, i);
    ni = tgi_gv_normal(g, i);
    ztol = tg_mul(p->depth_tolerance, zi);
    inv = tg_div(TG_ONE, ztol);
    for (yy = y - 2; yy <= y + 2; yy++)
        for (xx = x - 2; xx <= x + 2; xx++) {
            size_t j;
            tg_real dz, wt, d;
            tgi_gr_value t;
            if (xx < 0 || yy < 0 || xx >= g->width || yy >= g->height) continue;
            j = tgi_gv_index(g, xx, yy);
            if (tgi_gv_is_sky(g, j)) continue;
            dz = tg_abs(tg_sub(tgi_gv_depth(g, j), zi));
            if (dz >= ztol) continue;
            wt = tg_mul(tg_mul(tg_from_float(tap_w[xx - x + 2]), tg_from_float(tap_w[yy - y + 2])),
                        tg_sub(TG_ONE, tg_mul(dz, inv)));
            d = tg_max(tgi_v3_dot(ni, tgi_gv_normal(g, j)), 0);
#if TG_FIXED
            d = tg_min(d, 2 * TG_ONE);   /* never reached by unit normals */
#endif
            d = tg_mul(d, d); d = tg_mul(d, d); d = tg_mul(d, d);
            wt = tg_mul(wt, d);
            if (wt <= 0) continue;
            t = tgi_gr_get_kept(r, j);
            ws += wt;
            ao += formula_product(t.ao, wt);
            for (c = 0; c < 3; c++) b[c] += formula_product((&t.bent.x)[c], wt);
            for (c = 0; c < 3; c++) e[c] += formula_product((&t.near.x)[c], wt);
        }
    v.ao = tg_saturate(formula_average(ao, ws));
    v.bent = tgi_v3_normalize_or(tg_v3(formula_average(b[0], ws), formula_average(b[1], ws),
                                       formula_average(b[2], ws)), ni);
    v.near = tg_v3(formula_average(e[0], ws), formula_average(e[1], ws), formula_average(e[2], ws));
    return v;
}

static int same_value(tgi_gr_value a, tgi_gr_value b)
{
    return a.ao == b.ao && a.bent.x == b.bent.x && a.bent.y == b.bent.y && a.bent.z == b.bent.z &&
           a.near.x == b.near.x && a.near.y == b.near.y && a.near.z == b.near.z;
}

/* The filter gives its formula's values exactly (filter_formula), for any
 * order of calls on one walk: along rows, down columns, backwards.  The
 * G-buffer has depth steps, sky pixels and normals that vary per pixel; the
 * results vary per pixel in every channel. */
TEST(filter_is_its_formula_in_any_order)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    static tgi_gbuffer gf;
    tgi_gview g;
    tgi_gresult r;
    tgi_denoise_params p;
    tgi_denoise_walk k;
    int i, x, y, order, bad = 0, filtered = 0;
    if (!gf.depth) sf_gbuffer_alloc(&gf, W, H, NULL, 0);
    for (i = 0; i < N; i++) {
        int x0 = i % W, y0 = i / W, sky = (x0 * 7 + y0 * 3) % 29 == 0 || (x0 < 3 && y0 < 4);
        float z = 2.0f + 0.04f * (float)(x0 % 4) + 0.03f * (float)(y0 % 3) + (x0 > W / 2 ? 0.6f : 0.0f);
        tg_vec3 n = tgi_v3_normalize(tg_v3(tg_from_float(0.3f * (float)((x0 * 5 + y0) % 7 - 3)), TG_ONE,
                                           tg_from_float(0.2f * (float)((y0 * 3 + x0) % 5 - 2))));
        sf_gbuffer_set(&gf, (size_t)i, sky ? 0 : tg_from_float(z), n, 0);
    }
    g = sf_view(&gf, &v);
    sf_results_alloc(&r, N, 1, 0, 1);
    for (i = 0; i < N; i++) {
        tgi_gr_set_ao(&r, (size_t)i, tg_from_float((float)((i * 37) % 256) / 255.0f));
        tgi_gr_set_bent(&r, (size_t)i, tgi_v3_normalize(tg_v3(tg_from_float(0.1f * (float)(i % 9 - 4)), TG_ONE,
                                                                tg_from_float(0.1f * (float)(i % 5 - 2)))));
        tgi_gr_set_near(&r, (size_t)i, tg_v3(tg_from_float(0.05f * (float)(i % 11)), tg_from_float(0.3f),
                                             tg_from_float(0.02f * (float)(i % 13))));
    }
    tgi_denoise_defaults(&p);
    for (order = 0; order < 3; order++) {
        tgi_denoise_walk_start(&k);
        for (i = 0; i < N; i++) {
            tgi_gr_value got, want;
            x = order == 1 ? i / H : order == 2 ? W - 1 - i % W : i % W;
            y = order == 1 ? i % H : order == 2 ? H - 1 - i / W : i / W;
            got = tgi_denoise_pixel(&p, &g, &r, &k, x, y);
            want = filter_formula(&p, &g, &r, x, y);
            if (!same_value(got, want)) {
                if (bad < 5) printf("# order %d pixel (%d, %d): ao %g, formula %g\n", order, x, y, check_d(got.ao), check_d(want.ao));
                bad++;
            }
            if (order == 0 && !same_value(got, tgi_gr_get_kept(&r, tgi_gv_index(&g, x, y)))) filtered++;
        }
    }
    CHECK(bad == 0, "%d pixels differ from the filter's formula", bad);
    CHECK(filtered > N / 2, "the filter changed only %d of %d pixels", filtered, N);
    sf_results_free(&r);
}

/* Temporal accumulation with a static view: an input alternating between
 * 0.25 and 0.75 frame by frame settles at 0.5 +- 0.028 (alpha 0.2: the
 * fixed points (0.16 b + 0.2 a) / 0.36), the frames' results alternating
 * between two buffers; history whose depth does not match is rejected. */
TEST(temporal_accumulates_and_rejects)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_gview g;
    tgi_gresult set[2];
    tgi_temporal_params tp;
    int i, f, bad = 0, changed = 0;
    double worst = 0;
    setup(&v);
    g = sf_view(&g0, &v);
    sf_results_alloc(&set[0], N, 1, 0, 0);
    sf_results_alloc(&set[1], N, 1, 0, 0);
    tgi_temporal_defaults(&tp);
    for (f = 0; f < 40; f++) {
        const tgi_gresult *r = &set[f & 1], *last = &set[1 - (f & 1)];
        for (i = 0; i < N; i++) {
            tgi_gr_set_ao(r, (size_t)i, (f & 1) ? TG_R(0.75f) : TG_R(0.25f));
            tgi_gr_set_bent(r, (size_t)i, tg_v3(0, TG_ONE, 0));
        }
        tgi_temporal_rows(&tp, &g, r, last, &prev, &v, f == 0, 0, H);
    }
    for (i = 0; i < N; i++) {
        double a = check_d(tgi_gr_ao(&set[1], (size_t)i));   /* the last frame's (f = 39) */
        if (tgi_gv_is_sky(&g, (size_t)i)) continue;
        if (fabs(a - 0.5) > worst) worst = fabs(a - 0.5);
        if (fabs(a - 0.5278) > 0.01) bad++;
    }
    printf("# temporal: alternating 0.25 / 0.75 settles within %.4f of 0.5\n", worst);
    CHECK(bad == 0, "%d pixels did not settle at 0.528 (worst |AO - 0.5| %.4f)", bad, worst);
    /* last frame's depth twice as far: every history rejected, the input kept */
    {
        tgi_gbuffer far;
        tgi_gview fv;
        sf_gbuffer_alloc(&far, W, H, NULL, 0);
        for (i = 0; i < N; i++)
            sf_gbuffer_set(&far, (size_t)i, tg_mul(tgi_gv_depth(&g, (size_t)i), TG_R(2.0f)), tg_v3(0, TG_ONE, 0), 0);
        fv = sf_view(&far, &v);
        for (i = 0; i < N; i++) tgi_prev_keep(&prev, (size_t)i, &fv, (size_t)i);
        for (i = 0; i < N; i++) tgi_gr_set_ao(&set[0], (size_t)i, TG_R(0.25f));
        tgi_temporal_rows(&tp, &g, &set[0], &set[1], &prev, &v, 0, 0, H);
        for (i = 0; i < N; i++) changed += tgi_gr_ao(&set[0], (size_t)i) != tgi_unorm8_unpack(tgi_unorm8_pack(TG_R(0.25f)));
        CHECK(changed == 0, "%d pixels took a history whose depth does not match", changed);
        sf_gbuffer_free(&far);
    }
    sf_results_free(&set[0]);
    sf_results_free(&set[1]);
}

/* A camera at eye looking along -z (its right is +x, its up +y). */
static tgi_view make_view_ahead(double ex, double ey, double ez)
{
    tgi_view v;
    tg_vec3 e = tg_v3(tg_from_float((float)ex), tg_from_float((float)ey), tg_from_float((float)ez));
    tgi_view_make(&v, e, tgi_v3_add(e, tg_v3(0, 0, tg_neg(TG_ONE))), tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f),
                  TG_R(100.0f), W, H);
    return v;
}

/* HBIL sec. 3.2's z-test: with a static camera, a surface 3% farther than
 * last frame's takes last frame's radiance exactly, one 7% farther (past the
 * 5% tolerance: a disocclusion) is a hole. */
TEST(gather_depth_test_has_a_five_percent_tolerance)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_gview view0;
    int i, kept = 0, bad_near = 0, bad_far = 0;
    setup(&v);
    view0 = sf_view(&g0, &v);
    for (i = 0; i < N; i++) {
        tg_real z = tgi_gv_depth(&view0, (size_t)i);
        if (tgi_gv_is_sky(&view0, (size_t)i)) { sf_gbuffer_set(&g1, (size_t)i, 0, tg_v3(0, TG_ONE, 0), 0); continue; }
        sf_gbuffer_set(&g1, (size_t)i, tg_mul(z, (i % W) % 2 ? TG_R(1.07f) : TG_R(1.03f)), tg_v3(0, TG_ONE, 0), 0);
    }
    gather(&v, &v, &g1, &history);
    for (i = 0; i < N; i++) {
        tg_vec3 a = tgi_rgb_get(&out, (size_t)i), b = tgi_rgb_get(&history, (size_t)i);
        if (tgi_gv_is_sky(&view0, (size_t)i)) continue;
        if ((i % W) % 2) { bad_far += !tgi_rgb_is_hole(&out, (size_t)i); continue; }
        kept++;
        bad_near += tgi_rgb_is_hole(&out, (size_t)i) || a.x != b.x || a.y != b.y || a.z != b.z;
    }
    CHECK(kept > N / 4, "only %d pixels tested", kept);
    CHECK(bad_near == 0, "%d pixels 3%% farther did not take their own history", bad_near);
    CHECK(bad_far == 0, "%d pixels 7%% farther took a history across the disocclusion", bad_far);
}

/* A camera panned by one pixel (at the wall's depth, the wall alone) in
 * each direction: a surface that last frame was outside the image (past the
 * last column or row, left of the first column or above the first row) is
 * a hole, although the buffers go on past the image with the same surface;
 * every other pixel takes the radiance of the pixel its surface was in. */
TEST(gather_out_of_image_history_is_a_hole)
{
    static const int pan[4][2] = { { 1, 0 }, { -1, 0 }, { 0, 1 }, { 0, -1 } };
    tgi_view v0 = make_view_ahead(0, 0, 2), v1;
    tgi_gview view0, view1;
    double step;
    int k, i, outside = 0, inside = 0, bad_out = 0, bad_in = 0;
    no_floor = 1;
    setup(&v0);
    view0 = sf_view(&g0, &v0);
    for (i = 0; i < N + W; i++) {
        tgi_rgb_set(&history, (size_t)i, tg_v3(tg_from_int(i % W + 1), tg_from_int(i / W + 1), 0));
        if (i >= N) tgi_prev_keep(&prev, (size_t)i, &view0, (size_t)(i - W));   /* the wall goes on */
    }
    step = 5.0 / check_d(v0.pixels_per_unit);   /* one pixel at the wall z = -3, 5 from the eye */
    for (k = 0; k < 4; k++) {
        v1 = make_view_ahead(pan[k][0] * step, pan[k][1] * step, 2);
        scene_cast(&v1, &g1);
        gather(&v0, &v1, &g1, &history);
        view1 = sf_view(&g1, &v1);
        for (i = 0; i < N; i++) {
            double p[3], px, py;
            tg_vec3 c = tgi_rgb_get(&out, (size_t)i);
            if (tgi_gv_is_sky(&view1, (size_t)i)) continue;
            world_of(&v1, i, check_d(tgi_gv_depth(&view1, (size_t)i)), p);
            project(&v0, p, &px, &py);
            if (px < -0.05 || py < -0.05 || px > W + 0.05 || py > H + 0.05) {
                outside++;
                bad_out += !tgi_rgb_is_hole(&out, (size_t)i);
            } else if (fabs(px - floor(px) - 0.5) < 0.45 && fabs(py - floor(py) - 0.5) < 0.45 && px < W && py < H) {
                inside++;
                bad_in += tgi_rgb_is_hole(&out, (size_t)i) || check_d(c.x) != floor(px) + 1 || check_d(c.y) != floor(py) + 1;
            }
        }
    }
    no_floor = 0;
    printf("# out-of-image history: %d pixels outside, %d inside\n", outside, inside);
    CHECK(outside == 2 * (W + H), "%d pixels came from outside the image, not %d", outside, 2 * (W + H));
    CHECK(inside == 4 * N - outside, "only %d pixels came from inside the image", inside);
    CHECK(bad_out == 0, "%d pixels whose surface was outside the image took a history", bad_out);
    CHECK(bad_in == 0, "%d pixels did not take the history of the pixel their surface was in", bad_in);
}

/* A moving object: the wall (alone, camera static) of object 0 on even rows
 * moved one pixel right since last frame (its delta, current pose to last
 * frame's, is one pixel left), odd rows belong to no object (0xFFFF).  On
 * even rows pixel x takes the history of pixel x - 1 and the first column,
 * which was outside the image, is a hole; odd rows take their own. */
TEST(gather_follows_the_object_motion)
{
    tgi_view v = make_view_ahead(0, 0, 2);
    static uint16_t object[N];
    tgi_mat4 delta[1];
    tgi_reproject_io io;
    tgi_gview view;
    int i, bad = 0, moved = 0;
    no_floor = 1;
    setup(&v);
    no_floor = 0;
    for (i = 0; i < N; i++) {
        tgi_rgb_set(&history, (size_t)i, tg_v3(tg_from_int(i % W + 1), tg_from_int(i / W + 1), 0));
        object[i] = (i / W) % 2 ? 0xFFFF : 0;
    }
    delta[0] = tgi_m4_translate(tg_v3(tg_from_float((float)(-5.0 / check_d(v.pixels_per_unit))), 0, 0));
    view = sf_view(&g0, &v);
    memset(&io, 0, sizeof io);
    io.g = &view;
    io.prev_view = &v;
    io.prev_geometry = &prev;
    io.prev = &history;
    io.object = object;
    io.object_delta = delta;
    io.out = &out;
    tgi_reproject_gather_rows(&io, 0, H);
    for (i = 0; i < N; i++) {
        int x = i % W, from = object[i] == 0 ? x - 1 : x;
        tg_vec3 c = tgi_rgb_get(&out, (size_t)i);
        if (from < 0) { bad += !tgi_rgb_is_hole(&out, (size_t)i); continue; }
        moved += from != x;
        bad += tgi_rgb_is_hole(&out, (size_t)i) || check_d(c.x) != from + 1 || check_d(c.y) != i / W + 1;
    }
    CHECK(moved > N / 3, "only %d pixels moved", moved);
    CHECK(bad == 0, "%d pixels did not take the history of where their object was", bad);
}

/* Temporal accumulation (an exponential average, alpha 0.2 on the current
 * frame): history AO 1, near field (1, 0.5, 0.25), bent normal +y under a
 * current AO 0, near field 0 and bent normal +x give exactly AO 0.8, near
 * field (0.8, 0.4, 0.2) and bent normal normalize(0.2, 0.8, 0).  History is
 * accepted 3% farther and rejected 7% farther (the 5% depth tolerance), and
 * accepted with a normal 18 degrees off, rejected 32 degrees off (cos 0.9). */
TEST(temporal_blends_with_exact_weights)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_gview g, pv;
    tgi_gresult cur, last;
    tgi_temporal_params tp;
    tgi_gbuffer pg;
    const double bl = sqrt(0.2 * 0.2 + 0.8 * 0.8);
    int i, k, tested = 0, bad_blend = 0, bad_keep = 0;
    setup(&v);
    g = sf_view(&g0, &v);
    sf_results_alloc(&cur, N, 1, 0, 1);
    sf_results_alloc(&last, N, 1, 0, 1);
    sf_gbuffer_alloc(&pg, W, H, NULL, 0);
    tgi_temporal_defaults(&tp);
    /* last frame's geometry: pixel kind k = i % 5: 0 same, 1 3% farther,
     * 2 7% farther, 3 normal 18 degrees off, 4 normal 32 degrees off */
    for (i = 0; i < N; i++) {
        tg_real z = tgi_gv_depth(&g, (size_t)i);
        static const float scale[5] = { 1.0f, 1.03f, 1.07f, 1.0f, 1.0f };
        static const float tilt[5] = { 0, 0, 0, 0.3249f, 0.6249f };   /* tan 18, tan 32 degrees */
        k = i % 5;
        sf_gbuffer_set(&pg, (size_t)i, tgi_gv_is_sky(&g, (size_t)i) ? 0 : tg_mul(z, tg_from_float(scale[k])),
                       tg_v3(tg_from_float(tilt[k]), TG_ONE, 0), 0);
    }
    pv = sf_view(&pg, &v);
    for (i = 0; i < N; i++) tgi_prev_keep(&prev, (size_t)i, &pv, (size_t)i);
    for (i = 0; i < N; i++) {
        tgi_gr_set_ao(&last, (size_t)i, TG_ONE);
        tgi_gr_set_bent(&last, (size_t)i, tg_v3(0, TG_ONE, 0));
        tgi_gr_set_near(&last, (size_t)i, tg_v3(TG_ONE, TG_R(0.5f), TG_R(0.25f)));
        tgi_gr_set_ao(&cur, (size_t)i, 0);
        tgi_gr_set_bent(&cur, (size_t)i, tg_v3(TG_ONE, 0, 0));
        tgi_gr_set_near(&cur, (size_t)i, tg_v3(0, 0, 0));
    }
    tgi_temporal_rows(&tp, &g, &cur, &last, &prev, &v, 0, 0, H);
    for (i = 0; i < N; i++) {
        double a = check_d(tgi_gr_ao(&cur, (size_t)i)), tol = sf_rgb_rounding(1.0) + 1e-3;
        tg_vec3 e = tgi_gr_near(&cur, (size_t)i), b = tgi_gr_bent(&cur, (size_t)i);
        if (tgi_gv_is_sky(&g, (size_t)i)) continue;
        k = i % 5;
        tested++;
        if (k == 0 || k == 1 || k == 3)
            bad_blend += fabs(a - 0.8) > 1.0 / 255 + 1e-4 || fabs(check_d(e.x) - 0.8) > tol ||
                         fabs(check_d(e.y) - 0.4) > tol || fabs(check_d(e.z) - 0.2) > tol ||
                         fabs(check_d(b.x) - 0.2 / bl) > 0.02 || fabs(check_d(b.y) - 0.8 / bl) > 0.02;
        else
            bad_keep += a != 0 || e.x != 0 || e.y != 0 || e.z != 0 || fabs(check_d(b.x) - 1) > 0.02;
    }
    CHECK(tested > N / 2, "only %d pixels tested", tested);
    CHECK(bad_blend == 0, "%d pixels not blended 0.8 history + 0.2 current", bad_blend);
    CHECK(bad_keep == 0, "%d pixels took a history 7%% farther or 32 degrees off", bad_keep);
    sf_gbuffer_free(&pg);
    sf_results_free(&cur);
    sf_results_free(&last);
}

/* Temporal history on a 4x4 sub-image (the pixel (x, y) of sub-image (0, 0)
 * stands for full-res (4x, 4y)): a camera panned one pixel right, so the
 * surface of the last column (x = W - 1, in this sub-image as W = 37) was
 * at x = W last frame, outside the image: its value is kept, while the
 * columns inside take their history. */
TEST(temporal_out_of_image_history_on_a_sub_image)
{
    tgi_view v0 = make_view_ahead(0, 0, 2), v1;
    tgi_gview full, sub, pv;
    tgi_gresult cur, last;
    tgi_temporal_params tp;
    int x, y, edge = 0, inner = 0, bad_edge = 0;
    setup(&v0);
    v1 = make_view_ahead(5.0 / check_d(v0.pixels_per_unit), 0, 2);
    scene_cast(&v1, &g1);
    pv = sf_view(&g0, &v0);
    for (x = 0; x < N; x++) tgi_prev_keep(&prev, (size_t)x, &pv, (size_t)x);
    full = sf_view(&g1, &v1);
    tgi_gview_strided_sub(&sub, &full, 0, 0);
    sf_results_alloc(&cur, N, 0, 0, 0);
    sf_results_alloc(&last, N, 0, 0, 0);
    for (x = 0; x < N; x++) { tgi_gr_set_ao(&cur, (size_t)x, 0); tgi_gr_set_ao(&last, (size_t)x, TG_ONE); }
    tgi_temporal_defaults(&tp);
    tgi_temporal_rows(&tp, &sub, &cur, &last, &prev, &v0, 0, 0, sub.height);
    for (y = 0; y < sub.height; y++)
        for (x = 0; x < sub.width; x++) {
            size_t i = tgi_gv_index(&sub, x, y);
            if (tgi_gv_is_sky(&sub, i)) continue;
            if (4 * x == W - 1) { edge++; bad_edge += tgi_gr_ao(&cur, i) != 0; }
            else inner += tgi_gr_ao(&cur, i) != 0;
        }
    CHECK(W % 4 == 1 && edge > 0, "the sub-image holds the last column (%d pixels)", edge);
    CHECK(inner > sub.width * sub.height / 2, "only %d pixels took their history", inner);
    CHECK(bad_edge == 0, "%d pixels of the last column took a history from outside the image", bad_edge);
    sf_results_free(&cur);
    sf_results_free(&last);
}

/* Push/pull on a ramp: columns x even hold x, odd ones are holes (a 16x8
 * image, so every 2x2 block of level 1 holds one column: level 1's texel X
 * is 2X with weight 1).  A hole at x = 2X + 1 takes the bilinear sample of
 * level 1 at its centre, a quarter texel right of texel X: 0.75 * 2X +
 * 0.25 * (2X + 2) = x - 0.5; the last column (clamped at the border) x - 1.
 * The same down the rows for a ramp in y. */
TEST(pushpull_ramp_takes_the_bilinear_sample)
{
    enum { PW = 16, PH = 8 };
    tgi_rgb c;
    void *s = malloc(tgi_pushpull_bytes(PW, PH) + tgi_pushpull_bytes(PH, PW));
    int axis, i, bad = 0;
    sf_rgb_alloc(&c, PW * PH);
    for (axis = 0; axis < 2; axis++) {
        int w = axis ? PH : PW, h = axis ? PW : PH;
        for (i = 0; i < w * h; i++) {
            int t = axis ? i / w : i % w;
            if (t % 2) tgi_rgb_set_hole(&c, (size_t)i);
            else tgi_rgb_set(&c, (size_t)i, tg_v3(tg_from_int(t), TG_ONE, 0));
        }
        tgi_pushpull_fill(w, h, &c, s);
        for (i = 0; i < w * h; i++) {
            int t = axis ? i / w : i % w, last = axis ? h - 1 : w - 1;
            double want = t % 2 == 0 ? t : t == last ? t - 1 : t - 0.5;
            double got = check_d(tgi_rgb_get(&c, (size_t)i).x);
            if (fabs(got - want) > 2 * sf_rgb_rounding(16.0) + 1e-3) {
                if (bad < 5) printf("# ramp along %s: pixel %d: %g, want %g\n", axis ? "y" : "x", i, got, want);
                bad++;
            }
        }
    }
    CHECK(bad == 0, "%d pixels not at the bilinear sample of level 1", bad);
    sf_rgb_free(&c);
    free(s);
}

/* push/pull's row-parallel steps (pushpull.h) over any split of the rows,
 * in any order, give the whole-image fill's bits: level-1 rows owned by the
 * range holding their first image row, odd boundaries and one-row ranges
 * included, odd sizes (the last level-1 row from one image row). */
TEST(pushpull_rows_equal_the_whole_image_in_any_split)
{
    enum { SW = 13, SH = 11 };
    static const int cuts[][6] = { { 0, 11, 11, 11, 11, 11 }, { 0, 1, 2, 3, 7, 11 }, { 0, 5, 6, 9, 10, 11 },
                                   { 0, 4, 8, 11, 11, 11 } };
    tgi_rgb whole, part;
    void *s = malloc(tgi_pushpull_bytes(SW, SH));
    int c, k, i, differ = 0, holes_before = 0;
    sf_rgb_alloc(&whole, SW * SH);
    sf_rgb_alloc(&part, SW * SH);
    for (c = 0; c < (int)(sizeof cuts / sizeof cuts[0]); c++) {
        for (i = 0; i < SW * SH; i++) {
            int valid = (i * 7 + c) % 5 < 2 || i == SW * SH - 1;
            tg_vec3 v = tg_v3(tg_from_float(0.5f + (float)(i % 13) * 0.125f), tg_from_float((float)(i % 3)), TG_ONE);
            if (valid) { tgi_rgb_set(&whole, (size_t)i, v); tgi_rgb_set(&part, (size_t)i, v); }
            else { tgi_rgb_set_hole(&whole, (size_t)i); tgi_rgb_set_hole(&part, (size_t)i); holes_before++; }
        }
        tgi_pushpull_fill(SW, SH, &whole, s);
        memset(s, 0x5A, tgi_pushpull_bytes(SW, SH));   /* no level left over from the whole fill */
        for (k = 4; k >= 0; k--) tgi_pushpull_push_rows(SW, SH, &part, s, cuts[c][k], cuts[c][k + 1]);   /* last range first */
        tgi_pushpull_levels(SW, SH, s);
        for (k = 0; k < 5; k++) tgi_pushpull_fill_rows(SW, SH, &part, s, cuts[c][k], cuts[c][k + 1]);
#if TG_WIDE_STORAGE
        for (i = 0; i < SW * SH; i++)
            differ += whole.r[i] != part.r[i] || whole.g[i] != part.g[i] || whole.b[i] != part.b[i];
#else
        for (i = 0; i < SW * SH; i++) differ += whole.p[i] != part.p[i];   /* the stored words */
#endif
    }
    CHECK(holes_before > 0, "the images have holes");
    CHECK(differ == 0, "%d pixels differ between the row ranges and the whole image", differ);
    sf_rgb_free(&whole);
    sf_rgb_free(&part);
    free(s);
}

#if TG_FIXED
/* The map to the previous camera without saturation tests
 * (tgi_motion_prev_position_pair under tgi_motion_pair_start's bound, used
 * by temporal.c and reproject.c) gives the saturating map's bits
 * (tgi_motion_prev_position, motion.c): random camera pairs (eyes from the
 * origin to 30000 units away, small moves and cuts), image sizes up to
 * 8192 a side, pixels anywhere in them and depths from 2^-16 to the whole
 * range; both sides of the bound (the fast sums and the fallback) taken. */
TEST(motion_pair_gives_the_saturating_map)
{
    unsigned seed = 777;
    long count = 0, fast = 0, front = 0, bad = 0, i;
    for (i = 0; i < 400000; i++) {
        const double far = check_rnd(&seed) < 0.5 ? 10 : check_rnd(&seed) < 0.5 ? 3000 : 30000;
        const int w = check_rnd(&seed) < 0.5 ? 1 + (int)(check_rnd(&seed) * 400) : 1 + (int)(check_rnd(&seed) * 8192);
        const int h = 1 + (int)(check_rnd(&seed) * (check_rnd(&seed) < 0.5 ? 300 : 8192));
        const double ex = (2 * check_rnd(&seed) - 1) * far, ey = (2 * check_rnd(&seed) - 1) * far,
                     ez = (2 * check_rnd(&seed) - 1) * far, move = check_rnd(&seed) < 0.7 ? 0.3 : far;
        tgi_view cur, before;
        tgi_motion_pair m;
        tg_real px0, py0, z0, px1, py1, z1, depth;
        int x, y, r0, r1;
        tgi_view_make(&cur, tg_v3(tg_from_float((float)ex), tg_from_float((float)ey), tg_from_float((float)ez)),
                      tg_v3(tg_from_float((float)(ex + 2 * check_rnd(&seed) - 1)), tg_from_float((float)(ey + 2 * check_rnd(&seed) - 1)),
                            tg_from_float((float)(ez + 2 * check_rnd(&seed) - 1))),
                      tg_v3(0, TG_ONE, 0), tg_from_float((float)(0.2 + 2.5 * check_rnd(&seed))), TG_R(0.05f), TG_R(1000.0f), w, h);
        tgi_view_make(&before, tg_v3(tg_from_float((float)(ex + move * (2 * check_rnd(&seed) - 1))), tg_from_float((float)(ey + move * (2 * check_rnd(&seed) - 1))),
                                   tg_from_float((float)(ez + move * (2 * check_rnd(&seed) - 1)))),
                      tg_v3(tg_from_float((float)(ex + 2 * check_rnd(&seed) - 1)), tg_from_float((float)(ey + 2 * check_rnd(&seed) - 1)),
                            tg_from_float((float)(ez + 2 * check_rnd(&seed) - 1))),
                      tg_v3(0, TG_ONE, 0), tg_from_float((float)(0.2 + 2.5 * check_rnd(&seed))), TG_R(0.05f), TG_R(1000.0f), w, h);
        tgi_motion_pair_start(&m, &cur, &before);
        x = (int)(check_rnd(&seed) * w);
        y = (int)(check_rnd(&seed) * h);
        depth = check_rnd(&seed) < 0.3 ? (tg_real)(1 + check_rnd(&seed) * 65536)
              : check_rnd(&seed) < 0.5 ? tg_from_float((float)(check_rnd(&seed) * 100))
                                       : (tg_real)(check_rnd(&seed) * 2147483647.0);
        px0 = py0 = z0 = px1 = py1 = z1 = 12345;
        r0 = tgi_motion_prev_position(&cur, &before, NULL, x, y, depth, &px0, &py0, &z0);
        r1 = tgi_motion_prev_position_pair(&m, NULL, x, y, depth, &px1, &py1, &z1);
        {
            const tg_real vx = tgi_view_mul_div((tg_real)((2 * x + 1 - w) * 32768), depth, cur.pixels_per_unit);
            const tg_real vy = tgi_view_mul_div((tg_real)((h - 2 * y - 1) * 32768), depth, cur.pixels_per_unit);
            fast += (int64_t)tg_abs(vx) + tg_abs(vy) + depth <= m.v_max;
        }
        count++;
        front += r0;
        if ((r0 != r1 || z0 != z1 || (r0 && (px0 != px1 || py0 != py1))) && bad++ < 5)
            fprintf(stderr, "%dx%d (%d, %d) depth %d: %d (%d, %d, %d) saturating, %d (%d, %d, %d) pair\n", w, h, x, y,
                    (int)depth, r0, (int)px0, (int)py0, (int)z0, r1, (int)px1, (int)py1, (int)z1);
    }
    printf("  motion: %ld points (%ld in front of the previous camera, %ld by the sums without tests), %ld differ\n",
           count, front, fast, bad);
    CHECK(bad == 0 && fast > count / 4 && fast < count - count / 10 && front > count / 4, "%ld of %ld differ (%ld fast)",
          bad, count, fast);
}
#endif

#if TG_FIXED
/* The exponential average's blend (tgi_temporal_lerp) is tg_lerp's, to
 * the bit (float: it is tg_lerp): random history, current value and weight, from 2^-16 to the
 * whole range and past it for the weight (where the blend saturates). */
TEST(temporal_blend_is_tg_lerp)
{
    unsigned seed = 4242;
    long count = 0, bad = 0, i;
    for (i = 0; i < 3000000; i++) {
        const int kind = (int)(check_rnd(&seed) * 3);
        const double span = kind == 0 ? 2 : kind == 1 ? 300 : 32767;
        const tg_real h = tg_from_float((float)((2 * check_rnd(&seed) - 1) * span));
        const tg_real v = check_rnd(&seed) < 0.02 ? (check_rnd(&seed) < 0.5 ? TG_REAL_MAX : TG_REAL_MIN)
                                                  : tg_from_float((float)((2 * check_rnd(&seed) - 1) * span));
        const tg_real t = check_rnd(&seed) < 0.9 ? tg_from_float((float)check_rnd(&seed))
                                                 : tg_from_float((float)((2 * check_rnd(&seed) - 1) * 8));
        const tg_real a = tgi_temporal_lerp(h, v, t), b = tg_lerp(h, v, t);
        count++;
        if (memcmp(&a, &b, sizeof a) && bad++ < 5)
            fprintf(stderr, "h %.9g v %.9g t %.9g: %.9g blended, %.9g tg_lerp\n", check_d(h), check_d(v), check_d(t),
                    check_d(a), check_d(b));
    }
    printf("  temporal blends: %ld, %ld differ from tg_lerp\n", count, bad);
    CHECK(bad == 0, "%ld of %ld blends differ from tg_lerp", bad, count);
}
#endif

int main(void)
{
    RUN(static_view_is_identity);
    RUN(moved_camera_fetches_the_same_surface);
    RUN(camera_cut_gives_zero);
    RUN(teleport_is_finite_and_hole_free);
    RUN(pushpull_fills_within_range);
    RUN(filter_preserves_range_and_constants);
    RUN(filter_is_its_formula_in_any_order);
    RUN(temporal_accumulates_and_rejects);
    RUN(gather_depth_test_has_a_five_percent_tolerance);
    RUN(gather_out_of_image_history_is_a_hole);
    RUN(gather_follows_the_object_motion);
    RUN(temporal_blends_with_exact_weights);
    RUN(temporal_out_of_image_history_on_a_sub_image);
    RUN(pushpull_ramp_takes_the_bilinear_sample);
    RUN(pushpull_rows_equal_the_whole_image_in_any_split);
#if TG_FIXED
    RUN(temporal_blend_is_tg_lerp);
#endif
#if TG_FIXED
    RUN(motion_pair_gives_the_saturating_map);
#endif
    return check_summary();
}
