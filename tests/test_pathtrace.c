/* SPDX-License-Identifier: MIT */
/*
 * test_pathtrace.c - the path-traced reference against analytic answers, on
 * G-buffers from the real rasterizer:
 *   - a closed box whose walls all emit L_e, of reflectance rho: the
 *     geometric series Lo = L_e (1 - rho^(N+2)) / (1 - rho) after N
 *     bounces, L_e / (1 - rho) with Russian roulette;
 *   - the furnace: a convex object of reflectance rho under a uniform sky L
 *     reflects exactly rho L (it never sees itself, so no series), at every
 *     pixel and bounce count;
 *   - a point light over a plane: rho / pi * I cos / d^2, exactly; spot and
 *     directional lights as direct.c's formulas; shadow rays against a box;
 *   - a rectangular emitter over a floor: Lambert's polygon irradiance;
 *   - the environment under partial occlusion: E = pi L AO with the
 *     reference's cosine-weighted AO, the far field's new aperture;
 *   - determinism: any split of the rows, the same image; another seed,
 *     another image.
 */
#include "raster_fixture.h"
#include "ao/pathtrace.h"
#include "light/direct.h"
#include "light/sh.h"
#include "ao/reference.h"

#define PI 3.14159265358979
#define TOL_MEAN (TG_FIXED ? 0.03 : 0.015)

static tgi_material material(double albedo, double f0, double e0, double e1, double e2)
{
    tgi_material m;
    memset(&m, 0, sizeof m);
    m.albedo = v3(albedo, albedo, albedo); m.f0 = rv(f0); m.emissive = v3(e0, e1, e2); m.twosided = 1;
    tgi_material_finish(&m);
    return m;
}

static tgi_pt_emitter *emitter_table;

/* Parameters for g (BVH built), with its emitter table. */
static void params_for(tgi_pathtrace_params *p, const geo *g, const tgi_material *mats, const tgi_light *lights,
                       int light_count, const tgi_env *env, int samples, int bounces)
{
    int n = tgi_pathtrace_emitter_count(g->mat, mats, g->n);
    geo_bvh(g);
    free(emitter_table);
    emitter_table = (tgi_pt_emitter *)malloc(tgi_pathtrace_emitter_bytes(n) + 1);
    tgi_pathtrace_defaults(p);
    p->bvh = &bvh; p->tri_nrm = g->nrm; p->tri_material = g->mat; p->materials = mats;
    p->lights = lights; p->light_count = light_count; p->env = env;
    p->emitter_count = tgi_pathtrace_emitters(emitter_table, g->pos, g->mat, mats, g->n);
    p->emitters = p->emitter_count ? emitter_table : NULL;
    CHECK(p->emitter_count == n, "%d emitters of %d", p->emitter_count, n);
    p->samples = samples; p->bounces = bounces;
}

/* Lo into out[0..2], E into out[3..5]. */
static void trace(const tgi_pathtrace_params *p, image *im, int y0, int y1)
{
    tgi_pathtrace_io io;
    memset(&io, 0, sizeof io);
    io.gb = &im->gb; io.view = &im->view;
    io.out_r = im->out[0]; io.out_g = im->out[1]; io.out_b = im->out[2];
    io.irr_r = im->out[3]; io.irr_g = im->out[4]; io.irr_b = im->out[5];
    tgi_pathtrace_rows(p, &io, y0, y1);
}

/* Mean of plane k over the non-sky pixels. */
static double mean_plane(const image *im, int k)
{
    double s = 0;
    int i, n = 0;
    for (i = 0; i < im->w * im->h; i++)
        if (!im->sky[i]) { s += dv(im->out[k][i]); n++; }
    return n ? s / n : 0;
}

/* ---- the geometric series ---- */

TEST(closed_box_of_emitters_is_a_geometric_series)
{
    static const double lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
    static const double eye[3] = { 0.2, -0.1, -0.7 }, target[3] = { -0.3, 0.2, 1 };
    static const double le[3] = { 1.0, 0.8, 0.6 };
    static const int bounces[] = { 0, 1, 2, 4 };
    double albedo = 0.6, f0 = 0.1, rho = albedo * (1 - f0);
    tgi_material mats[1];
    tgi_pathtrace_params p;
    geo *g = geo_new();
    image im;
    size_t k;
    int c, i;
    mats[0] = material(albedo, f0, le[0], le[1], le[2]);
    box(g, lo, hi, -1);
    image_render(&im, g, mats, eye, target, 70, 32, 24);
    for (k = 0; k <= sizeof bounces / sizeof bounces[0]; k++) {
        int roulette = k == sizeof bounces / sizeof bounces[0];
        double series = roulette ? 1 / (1 - rho) : (1 - pow(rho, bounces[k] + 2)) / (1 - rho);
        params_for(&p, g, mats, NULL, 0, NULL, 48, roulette ? TG_MAX_BOUNCES : bounces[k]);
        if (roulette) p.rr_start = 1;
        trace(&p, &im, 0, im.h);
        for (c = 0; c < 3; c++) {
            double got = mean_plane(&im, c), want = le[c] * series;
            printf("# box, %s: channel %d mean Lo %.4f, series %.4f (%+.2f%%)\n",
                   roulette ? "roulette" : "fixed N", c, got, want, 100 * (got / want - 1));
            CHECK(fabs(got / want - 1) <= TOL_MEAN, "N %d%s channel %d: mean Lo %g, series %g",
                  roulette ? -1 : bounces[k], roulette ? " (roulette)" : "", c, got, want);
        }
        for (i = 0; i < im.w * im.h; i++)   /* every pixel: its emission plus a finite reflection */
            CHECK(!im.sky[i] && dv(im.out[0][i]) >= le[0] && dv(im.out[0][i]) < 20 * le[0] * series,
                  "pixel %d: Lo %g (emission %g, series %g)", i, dv(im.out[0][i]), le[0], le[0] * series);
    }
    image_free(&im);
    free(g);
}

/* ---- the furnace ---- */

/* A UV sphere with flat faces (a convex polyhedron). */
static void flat_sphere(geo *g, const double c[3], double r, int seg)
{
    int i, j, k;
    for (i = 0; i < seg; i++)
        for (j = 0; j < 2 * seg; j++) {
            double q[4][3];
            for (k = 0; k < 4; k++) {
                double th = PI * (i + (k == 2 || k == 3)) / seg, ph = 2 * PI * (j + (k == 1 || k == 2)) / (2 * seg);
                q[k][0] = c[0] + r * sin(th) * cos(ph);
                q[k][1] = c[1] + r * cos(th);
                q[k][2] = c[2] + r * sin(th) * sin(ph);
            }
            /* outward (counter-clockwise seen from outside); the pole rows are triangles */
            if (i > 0) tri(g, q[0], q[1], q[2], NULL, NULL, NULL);
            if (i < seg - 1) tri(g, q[0], q[2], q[3], NULL, NULL, NULL);
        }
}

/* One convex object at a time (two would see each other). */
static void furnace_check(geo *g, const char *name, int min_pixels)
{
    static const double eye[3] = { 0.4, 1.5, -4.5 }, target[3] = { 0, 0, 0 };
    static const int bounces[] = { 0, 3 };
    double L[3] = { 0.7, 1.0, 1.4 }, albedo = 0.8, f0 = 0.04, rho = albedo * (1 - f0), worst = 0;
    tgi_material mats[1];
    tgi_env env;
    tgi_pathtrace_params p;
    image im;
    size_t k;
    int i, ch, seen = 0;
    mats[0] = material(albedo, f0, 0, 0, 0);
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_UNIFORM; env.uniform = v3(L[0], L[1], L[2]);
    image_render(&im, g, mats, eye, target, 50, 48, 36);
    for (k = 0; k < sizeof bounces / sizeof bounces[0]; k++) {
        params_for(&p, g, mats, NULL, 0, &env, 8, bounces[k]);
        trace(&p, &im, 0, im.h);
        for (i = 0; i < im.w * im.h; i++)
            for (ch = 0; ch < 3; ch++) {
                double want = im.sky[i] ? L[ch] : rho * L[ch], got = dv(im.out[ch][i]), err = fabs(got - want);
                if (!im.sky[i] && ch == 0) seen++;
                if (err > worst) worst = err;
                CHECK(err <= (TG_FIXED ? 2e-3 : 2e-6) * (1 + want), "%s N %d pixel %d ch %d: Lo %g, want %g%s",
                      name, bounces[k], i, ch, got, want, im.sky[i] ? " (sky)" : "");
            }
    }
    printf("# furnace, %s: largest |Lo - rho L| %.2g\n", name, worst);
    CHECK(seen / 2 >= min_pixels, "%s: %d object pixels", name, seen / 2);
    image_free(&im);
}

TEST(furnace_convex_objects_reflect_albedo_times_sky)
{
    static const double lo[3] = { -0.8, -0.9, -0.6 }, hi[3] = { 0.6, 0.4, 0.7 }, c[3] = { 0.1, 0.1, 0.2 };
    geo *g = geo_new();
    box(g, lo, hi, -1);
    furnace_check(g, "box", 100);
    memset(g, 0, sizeof *g);
    flat_sphere(g, c, 1.1, 12);
    furnace_check(g, "faceted sphere", 150);
    free(g);
}

/* ---- analytic lights ---- */

/* Lo = rho / pi E at every pixel of a lone plane: exact (no randomness
 * reaches it: no emitter, no sky, nothing to bounce off). */
TEST(point_light_over_a_plane_is_inverse_square_and_cosine)
{
    static const double eye[3] = { 0, 3, -4 }, target[3] = { 0, 0, 0.5 };
    double Lp[3] = { 0.3, 1.2, 0.1 }, I = 3, albedo = 0.7, rho = albedo, worst = 0;
    tgi_material mats[1];
    tgi_light lights[3];
    tgi_pathtrace_params p;
    geo *g = geo_new();
    image im;
    int i, k, bounce;
    tg_real dr[64 * 48], db[64 * 48];
    mats[0] = material(albedo, 0, 0, 0, 0);
    rect(g, 1, 0, -6, 6, -6, 6);
    image_render(&im, g, mats, eye, target, 60, 64, 48);
    lights[0] = make_light(TG_LIGHT_POINT, v3(Lp[0], Lp[1], Lp[2]), v3(0, -1, 0), I, 0);
    lights[1] = make_light(TG_LIGHT_SPOT, v3(Lp[0], Lp[1], Lp[2]), v3(0.2, -1, 0.3), I, 35 * DEG);
    lights[2] = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0.5, -1, 0.2), 1.5, 0);
    for (bounce = 0; bounce <= 3; bounce += 3) {
        params_for(&p, g, mats, &lights[0], 1, NULL, 2, bounce);
        trace(&p, &im, 0, im.h);
        for (i = 0; i < im.w * im.h; i++) {
            double pos[3], n[3], d[3], d2, want, got;
            if (im.sky[i]) continue;
            pixel_pos(&im, i, pos, n);
            for (k = 0; k < 3; k++) d[k] = Lp[k] - pos[k];
            d2 = dot3(d, d);
            want = rho / PI * I * (d[1] / sqrt(d2)) / d2;
            got = dv(im.out[0][i]);
            if (fabs(got / want - 1) > worst) worst = fabs(got / want - 1);
            CHECK(fabs(got - want) <= (TG_FIXED ? 0.01 : 2e-5) * want + 1e-6, "N %d pixel %d: Lo %g, want %g",
                  bounce, i, got, want);
            CHECK(fabs(dv(im.out[3][i]) - I * d[1] / sqrt(d2) / d2) <= (TG_FIXED ? 0.01 : 2e-5) * want * PI / rho + 1e-6,
                  "E at pixel %d", i);
        }
    }
    printf("# point light over a plane: largest relative error %.2g\n", worst);
    for (k = 1; k < 3; k++) {   /* spot and directional: direct.c's formulas, unshadowed */
        params_for(&p, g, mats, &lights[k], 1, NULL, 2, 1);
        image_direct(&im, &lights[k], 1, NULL, 0);   /* direct.c's E, through the build's colour storage */
        for (i = 0; i < im.w * im.h; i++) {
            if (im.sky[i]) continue;
            dr[i] = im.out[0][i]; db[i] = im.out[2][i];
        }
        trace(&p, &im, 0, im.h);
        for (i = 0; i < im.w * im.h; i++) {
            double st = sf_rgb_rounding(dv(dr[i]));   /* red is the light's largest channel */
            if (im.sky[i]) continue;
            CHECK(fabs(dv(im.out[3][i]) - dv(dr[i])) <= (TG_FIXED ? 2e-3 : 1e-6) * (1 + dv(dr[i])) + st &&
                  fabs(dv(im.out[5][i]) - dv(db[i])) <= (TG_FIXED ? 2e-3 : 1e-6) * (1 + dv(db[i])) + st,
                  "light %d pixel %d: E %g, direct %g", k, i, dv(im.out[3][i]), dv(dr[i]));
        }
    }
    image_free(&im);
    free(g);
}

/* Does the segment p -> q pass through the box [lo - m, hi + m]? */
static int segment_hits_box(const double p[3], const double q[3], const double lo[3], const double hi[3], double m)
{
    double t0 = 0, t1 = 1;
    int a;
    for (a = 0; a < 3; a++) {
        double d = q[a] - p[a], l = lo[a] - m, h = hi[a] + m;
        if (fabs(d) < 1e-15) { if (p[a] < l || p[a] > h) return 0; continue; }
        {
            double ta = (l - p[a]) / d, tb = (h - p[a]) / d;
            if (ta > tb) { double x = ta; ta = tb; tb = x; }
            if (ta > t0) t0 = ta;
            if (tb < t1) t1 = tb;
        }
    }
    return t0 <= t1;
}

TEST(shadow_rays_see_occluders)
{
    static const double eye[3] = { 0.5, 6, -4 }, target[3] = { 0, 0, 0.5 };
    static const double blo[3] = { -0.5, 0, -0.5 }, bhi[3] = { 0.5, 1, 0.5 };
    double Lp[3] = { -1.5, 3, -1 };
    tgi_material mats[1];
    tgi_light l = make_light(TG_LIGHT_POINT, v3(Lp[0], Lp[1], Lp[2]), v3(0, -1, 0), 20, 0);
    tgi_pathtrace_params p;
    geo *g = geo_new();
    image im;
    int i, inside = 0, outside = 0;
    tg_real dr[80 * 60];
    mats[0] = material(0.5, 0, 0, 0, 0);
    rect(g, 1, 0, -6, 6, -6, 6);
    box(g, blo, bhi, -1);
    image_render(&im, g, mats, eye, target, 50, 80, 60);
    params_for(&p, g, mats, &l, 1, NULL, 1, 0);
    image_direct(&im, &l, 1, NULL, 0);   /* direct.c's unshadowed E */
    for (i = 0; i < im.w * im.h; i++) dr[i] = im.out[0][i];
    trace(&p, &im, 0, im.h);
    for (i = 0; i < im.w * im.h; i++) {
        double pos[3], n[3], e = dv(im.out[3][i]), u = dv(dr[i]);
        if (im.sky[i] || u <= 0) continue;
        pixel_pos(&im, i, pos, n);
        if (fabs(pos[1]) > 0.01) continue;   /* the floor */
        if (segment_hits_box(pos, Lp, blo, bhi, -0.02)) {
            inside++;
            CHECK(e == 0, "floor pixel %d in the box's shadow: E %g", i, e);
        } else if (!segment_hits_box(pos, Lp, blo, bhi, 0.02)) {
            outside++;
            CHECK(fabs(e - u) <= 1e-6 * (1 + u) + sf_rgb_rounding(u), "lit floor pixel %d: E %g, direct %g", i, e, u);
        }
    }
    CHECK(inside > 50 && outside > 1000, "%d in the shadow, %d lit", inside, outside);
    image_free(&im);
    free(g);
}

/* ---- emitters ---- */

/* Irradiance at x (normal n) from a uniform Lambertian polygon of radiance
 * 1 (Lambert's formula, as in Arvo 1995): E = 1/2 sum theta_i n . g_i. */
static double polygon_irradiance(const double x[3], const double n[3], double v[][3], int count)
{
    double e = 0;
    int i, k;
    for (i = 0; i < count; i++) {
        double a[3], b[3], c[3], la, lb, lc, th;
        for (k = 0; k < 3; k++) { a[k] = v[i][k] - x[k]; b[k] = v[(i + 1) % count][k] - x[k]; }
        la = sqrt(dot3(a, a)); lb = sqrt(dot3(b, b));
        th = acos(fmax(-1, fmin(1, dot3(a, b) / (la * lb))));
        c[0] = a[1] * b[2] - a[2] * b[1]; c[1] = a[2] * b[0] - a[0] * b[2]; c[2] = a[0] * b[1] - a[1] * b[0];
        lc = sqrt(dot3(c, c));
        if (lc > 0) e += th * dot3(n, c) / lc;
    }
    return fabs(e) / 2;
}

TEST(rectangular_emitter_gives_lamberts_polygon_irradiance)
{
    static const double eye[3] = { 0, 3.5, -3.5 }, target[3] = { 0, 0, 0.3 };
    double quad_v[4][3] = { { -0.5, 1.2, -0.25 }, { 0.5, 1.2, -0.25 }, { 0.5, 1.2, 0.25 }, { -0.5, 1.2, 0.25 } };
    double le[3] = { 3, 2, 1 }, albedo = 0.5, sum_got = 0, sum_want = 0, sq = 0;
    tgi_material mats[2];
    tgi_pathtrace_params p;
    geo *g = geo_new();
    image im;
    int i, n = 0;
    mats[0] = material(albedo, 0, 0, 0, 0);
    mats[1] = material(0.0, 0, le[0], le[1], le[2]);
    rect(g, 1, 0, -4, 4, -4, 4);
    g->material = 1;
    quad(g, quad_v);
    image_render(&im, g, mats, eye, target, 60, 48, 36);
    params_for(&p, g, mats, NULL, 0, NULL, 64, 0);
    trace(&p, &im, 0, im.h);
    for (i = 0; i < im.w * im.h; i++) {
        double pos[3], nn[3], want, got;
        if (im.sky[i]) continue;
        pixel_pos(&im, i, pos, nn);
        if (fabs(pos[1]) > 0.01) continue;   /* floor pixels (the emitter itself shows its emission) */
        want = le[0] * polygon_irradiance(pos, nn, quad_v, 4);
        got = dv(im.out[3][i]);
        sum_got += got; sum_want += want; sq += (got - want) * (got - want); n++;
        CHECK(fabs(dv(im.out[0][i]) - albedo / PI * got) <= 1e-5 * (1 + got), "Lo = rho / pi E at %d", i);
    }
    printf("# emitter over a floor: mean E %.4f, Lambert %.4f (%+.2f%%), rms %.4f\n", sum_got / n, sum_want / n,
           100 * (sum_got / sum_want - 1), sqrt(sq / n));
    CHECK(n > 1000 && fabs(sum_got / sum_want - 1) <= TOL_MEAN, "%d floor pixels: mean E %g, Lambert %g", n,
          sum_got / n, sum_want / n);
    CHECK(sqrt(sq / n) <= 0.08 * sum_want / n, "rms error %g of mean %g", sqrt(sq / n), sum_want / n);
    image_free(&im);
    free(g);
}

/* ---- the environment through partial occlusion ---- */

/* A floor meeting a wall under a uniform sky, no bounces: the path-traced E
 * is pi L times the cosine-weighted AO that the reference measures (both
 * stochastic: means compared), so the far field's aperture
 * cos(alpha) = sqrt(1 - AO) (sh.h) gives it; HBIL eq. 12's 1 - AO gives
 * (2 - AO) times it. */
TEST(uniform_sky_through_occlusion_is_pi_l_times_cosine_ao)
{
    static const double eye[3] = { 2.6, 1.8, 2.2 }, target[3] = { 0.35, 0.3, -0.8 };
    double L = 1.0, s_pt = 0, s_new = 0, s_old = 0, s_sh = 0;
    tgi_material mats[1];
    tgi_env env;
    tgi_pathtrace_params p;
    tgi_reference_params rp;
    tgi_gview io;
    tgi_gresult out;
    tg_vec3 sh[9];
    geo *g = geo_new();
    image im;
    int i, n = 0;
    static tg_real ao[48 * 36];
    mats[0] = material(0.5, 0, 0, 0, 0);
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_UNIFORM; env.uniform = v3(L, L, L);
    tgi_sh9_from_env(&env, sh);
    rect(g, 1, 0, 0, 40, -20, 20);    /* floor x >= 0 */
    rect(g, 0, 0, 0, 20, -20, 20);    /* wall x = 0 */
    image_render(&im, g, mats, eye, target, 60, 48, 36);
    params_for(&p, g, mats, NULL, 0, &env, 256, 0);
    trace(&p, &im, 0, im.h);
    tgi_reference_defaults(&rp);
    rp.bvh = &bvh; rp.tri_nrm = g->nrm; rp.samples = 256; rp.radius = TG_AO_INFINITE;
    sf_results_alloc(&out, (size_t)im.w * (size_t)im.h, 0, 0, 0);
    tgi_gview_of(&io, &im.gb, &im.view);
    tgi_reference_rows(&rp, &io, NULL, &out, 0, im.h);
    sf_results_read(&out, (size_t)im.w * (size_t)im.h, ao, NULL, NULL, NULL, NULL, NULL, NULL, NULL);
    sf_results_free(&out);
    for (i = 0; i < im.w * im.h; i++) {
        double a = dv(ao[i]);
        if (im.sky[i] || a > 0.97) continue;   /* pixels the wall occludes */
        s_pt += dv(im.out[3][i]);
        s_new += PI * L * a;
        s_old += PI * L * a * (2 - a);
        s_sh += dv(tgi_sh9_irradiance_bent_cone(sh, tg_v3(im.nx[i], im.ny[i], im.nz[i]), ao[i]).x);
        n++;
    }
    printf("# uniform sky, %d occluded pixels: path-traced mean E %.4f; pi L AO %.4f (%+.2f%%); "
           "the far field %.4f (%+.2f%%); HBIL eq. 12 %.4f (%+.1f%%)\n", n, s_pt / n, s_new / n,
           100 * (s_new / s_pt - 1), s_sh / n, 100 * (s_sh / s_pt - 1), s_old / n, 100 * (s_old / s_pt - 1));
    CHECK(n > 200, "%d occluded pixels", n);
    CHECK(fabs(s_new / s_pt - 1) <= TOL_MEAN && fabs(s_sh / s_pt - 1) <= TOL_MEAN,
          "pi L AO %g and the far field %g against the path tracer %g", s_new / n, s_sh / n, s_pt / n);
    CHECK(s_old / s_pt > 1.1, "eq. 12's aperture overshoots: %g vs %g", s_old / n, s_pt / n);
    image_free(&im);
    free(g);
}

/* ---- determinism ---- */

TEST(rows_split_and_seed)
{
    static const double eye[3] = { 0.2, -0.1, -0.7 }, target[3] = { -0.3, 0.2, 1 };
    static const double lo[3] = { -1, -1, -1 }, hi[3] = { 1, 1, 1 };
    static tg_real whole[3][24 * 18];
    tgi_material mats[2];
    tgi_light l = make_light(TG_LIGHT_POINT, v3(0.3, 0.6, 0.2), v3(0, -1, 0), 2, 0);
    tgi_env env;
    tgi_pathtrace_params p;
    geo *g = geo_new();
    image im;
    int i, c, differ = 0;
    mats[0] = material(0.7, 0.04, 0, 0, 0);
    mats[1] = material(0.5, 0, 2, 2, 2);
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_UNIFORM; env.uniform = v3(0.5, 0.5, 0.5);
    box(g, lo, hi, 4);                                  /* open toward -z: the sky gets in */
    g->material = 1;
    rect(g, 1, 0.99, -0.3, 0.3, -0.2, 0.4);             /* a lamp under the ceiling */
    image_render(&im, g, mats, eye, target, 70, 24, 18);
    params_for(&p, g, mats, &l, 1, &env, 4, 3);
    p.rr_start = 2;
    trace(&p, &im, 0, im.h);
    for (c = 0; c < 3; c++) memcpy(whole[c], im.out[c], sizeof whole[c]);
    trace(&p, &im, 0, 5); trace(&p, &im, 5, 6); trace(&p, &im, 6, im.h);
    for (i = 0; i < im.w * im.h; i++)
        for (c = 0; c < 3; c++) CHECK(im.out[c][i] == whole[c][i], "split rows: pixel %d ch %d", i, c);
    p.seed = 2;
    trace(&p, &im, 0, im.h);
    for (i = 0; i < im.w * im.h; i++) differ += im.out[0][i] != whole[0][i];
    CHECK(differ > im.w * im.h / 4, "another seed changes %d pixels", differ);
    for (i = 0; i < im.w * im.h; i++)
        for (c = 0; c < 3; c++)
            CHECK(dv(im.out[c][i]) >= 0 && dv(im.out[c][i]) < 1e4, "finite, non-negative: pixel %d %g", i, dv(im.out[c][i]));
    image_free(&im);
    free(g);
}

TEST(emitter_table_sizes)
{
    CHECK(tgi_pathtrace_emitter_bytes(-1) == 0, "negative count");
    CHECK(tgi_pathtrace_emitter_bytes(3) == 3 * sizeof(tgi_pt_emitter), "3 emitters");
    CHECK(tgi_pathtrace_emitter_bytes(0) == 0, "none");
}

int main(void)
{
    RUN(emitter_table_sizes);
    RUN(closed_box_of_emitters_is_a_geometric_series);
    RUN(furnace_convex_objects_reflect_albedo_times_sky);
    RUN(point_light_over_a_plane_is_inverse_square_and_cosine);
    RUN(shadow_rays_see_occluders);
    RUN(rectangular_emitter_gives_lamberts_polygon_irradiance);
    RUN(uniform_sky_through_occlusion_is_pi_l_times_cosine_ao);
    RUN(rows_split_and_seed);
    free(emitter_table);
    free(bvh_mem);
    return check_summary();
}
