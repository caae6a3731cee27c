/* SPDX-License-Identifier: MIT */
/*
 * test_sh.c - the SH9 environment and the far field: white furnace, sky
 * hemisphere against RTR eq. 10.42, the cosine-lobe convolution and the
 * bent-cone restriction (HBIL sec. 2.2.4) against numerical integration of
 * the environment's radiance, the cone aperture of a cosine-weighted AO,
 * the F0 alternative (HBIL sec. 2.2.3), and both under a uniform sky:
 * Lo = albedo / pi (1 - F0) pi L AO exactly.
 */
#include <stdlib.h>
#include "check.h"
#include "storage_fixture.h"
#include "light/sh.h"
#include "light/compose.h"

#define PI 3.14159265358979
#define N 16 /* G-buffer side */

static double dv(tg_real r) { return check_d(r); }
static tg_real rv(double x) { return tg_from_float((float)x); }
static tg_vec3 v3d(double x, double y, double z) { return tg_v3(rv(x), rv(y), rv(z)); }
static double tol_rel(void) { return TG_FIXED ? 0.02 : 0.01; }

/* The real SH basis in double, same order as sh.h. */
static void basis(const double d[3], double y[9])
{
    double x = d[0], yy = d[1], z = d[2];
    y[0] = 0.282094792;
    y[1] = 0.488602512 * yy; y[2] = 0.488602512 * z; y[3] = 0.488602512 * x;
    y[4] = 1.092548431 * x * yy; y[5] = 1.092548431 * yy * z;
    y[6] = 0.315391565 * (3 * z * z - 1);
    y[7] = 1.092548431 * x * z; y[8] = 0.546274215 * (x * x - yy * yy);
}

/* Radiance of channel c of the SH9 env in double. */
static double sh_radiance_d(const tg_vec3 sh[9], int c, const double d[3])
{
    double y[9], s = 0;
    int j;
    basis(d, y);
    for (j = 0; j < 9; j++) s += y[j] * dv(c == 0 ? sh[j].x : c == 1 ? sh[j].y : sh[j].z);
    return s;
}

/* Orthonormal frame around unit n. */
static void frame(const double n[3], double t[3], double b[3])
{
    double a[3] = { 1, 0, 0 }, l;
    if (fabs(n[0]) > 0.9) { a[0] = 0; a[1] = 1; }
    t[0] = n[1] * a[2] - n[2] * a[1]; t[1] = n[2] * a[0] - n[0] * a[2]; t[2] = n[0] * a[1] - n[1] * a[0];
    l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    t[0] /= l; t[1] /= l; t[2] /= l;
    b[0] = n[1] * t[2] - n[2] * t[1]; b[1] = n[2] * t[0] - n[0] * t[2]; b[2] = n[0] * t[1] - n[1] * t[0];
}

/* Integral of L(w) (n.w) over the cone of half angle theta_max about n (midpoint rule). */
typedef double (*radiance_fn)(const void *ctx, const double d[3]);
static double cone_irradiance(radiance_fn L, const void *ctx, const double n[3], double theta_max)
{
    double t[3], b[3], sum = 0;
    int i, j, nt = 300, np = 600;
    frame(n, t, b);
    for (i = 0; i < nt; i++) {
        double th = (i + 0.5) * theta_max / nt, st = sin(th), ct = cos(th);
        for (j = 0; j < np; j++) {
            double ph = (j + 0.5) * 2 * PI / np, d[3];
            int k;
            for (k = 0; k < 3; k++) d[k] = ct * n[k] + st * (cos(ph) * t[k] + sin(ph) * b[k]);
            sum += L(ctx, d) * ct * st;
        }
    }
    return sum * (theta_max / nt) * (2 * PI / np);
}

typedef struct { const tg_vec3 *sh; int c; } sh_ctx;
static double L_sh(const void *ctx, const double d[3])
{
    const sh_ctx *s = (const sh_ctx *)ctx;
    return sh_radiance_d(s->sh, s->c, d);
}
typedef struct { double sky, ground, up[3]; } sky_ctx;
static double L_sky(const void *ctx, const double d[3])
{
    const sky_ctx *s = (const sky_ctx *)ctx;
    return d[0] * s->up[0] + d[1] * s->up[1] + d[2] * s->up[2] >= 0 ? s->sky : s->ground;
}

static void unit(double d[3])
{
    double l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    d[0] /= l; d[1] /= l; d[2] /= l;
}

/* A positive, band-limited test environment (L00 dominant). */
static void test_env(tg_vec3 sh[9])
{
    static const double c[9][3] = {
        { 2.0, 1.6, 1.2 }, { 0.5, 0.3, -0.2 }, { -0.3, 0.2, 0.4 }, { 0.25, -0.35, 0.1 },
        { 0.15, 0.1, -0.1 }, { -0.12, 0.08, 0.05 }, { 0.2, -0.1, 0.15 }, { 0.1, 0.12, -0.08 }, { -0.15, 0.05, 0.1 } };
    int j;
    for (j = 0; j < 9; j++) sh[j] = v3d(c[j][0], c[j][1], c[j][2]);
}

static const double normals[][3] = {
    { 0, 1, 0 }, { 0, -1, 0 }, { 1, 0, 0 }, { 0, 0, -1 }, { 0.3, 0.8, -0.5 }, { -0.7, -0.2, 0.6 }, { 0.5, -0.5, 0.7 } };
#define NORMAL_COUNT ((int)(sizeof normals / sizeof normals[0]))

typedef struct {
    tgi_gbuffer gb;                /* the build's storage (storage_fixture.h) */
    tgi_material material;         /* every pixel's */
    tg_real nx[N * N], ny[N * N], nz[N * N];   /* the normals as stored */
} small_gb;

/* An N x N G-buffer of non-sky pixels with varied unit normals. */
static small_gb *make_gb(double albedo)
{
    small_gb *g = (small_gb *)calloc(1, sizeof *g);
    tgi_gview v;
    int i;
    g->material.albedo = v3d(albedo, albedo, albedo);
    tgi_material_finish(&g->material);
    sf_gbuffer_alloc(&g->gb, N, N, &g->material, 1);
    v = sf_view(&g->gb, NULL);
    for (i = 0; i < N * N; i++) {
        double a = i * 2.399963, zc = 1 - 2 * (i + 0.5) / (N * N), r = sqrt(1 - zc * zc);
        tg_vec3 n;
        tgi_gb_set(&g->gb, (size_t)i, TG_ONE, v3d(r * cos(a), zc, r * sin(a)), 0);
        n = tgi_gv_normal(&v, (size_t)i);
        g->nx[i] = n.x; g->ny[i] = n.y; g->nz[i] = n.z;
    }
    return g;
}

static void free_gb(small_gb *g)
{
    sf_gbuffer_free(&g->gb);
    free(g);
}

static tg_real e[3][N * N], o[3][N * N];

/* A colour as the build stores it (RGB9E5, or itself when wide). */
static tg_vec3 stored(tg_vec3 c)
{
    tgi_rgb p;
    sf_rgb_alloc(&p, 1);
    tgi_rgb_set(&p, 0, c);
    c = tgi_rgb_get(&p, 0);
    sf_rgb_free(&p);
    return c;
}

/* E_far of the small G-buffer into e: results from ao and bent planes (the
 * planes then hold them as stored); ao NULL: no results. */
static void far_rows(const small_gb *g, const tg_vec3 sh[9], tg_real *ao, tg_real *bx, tg_real *by, tg_real *bz, int mode)
{
    tgi_gview v = sf_view(&g->gb, NULL);
    tgi_gresult res;
    tgi_rgb out;
    size_t i;
    sf_rgb_alloc(&out, N * N);
    if (ao) {
        sf_results_alloc(&res, N * N, bx != NULL, 0, 0);
        for (i = 0; i < N * N; i++) {
            tgi_gr_set_ao(&res, i, ao[i]);
            if (bx) tgi_gr_set_bent(&res, i, tg_v3(bx[i], by[i], bz[i]));
        }
        sf_results_read(&res, N * N, ao, bx, by, bz, NULL, NULL, NULL, NULL);
    }
    tgi_far_rows(&v, sh, ao ? &res : NULL, mode, &out, 0, N);
    sf_rgb_read(&out, N * N, e[0], e[1], e[2]);
    sf_rgb_free(&out);
    if (ao) sf_results_free(&res);
}

/* Lo of the small G-buffer (no camera: a black sky) lit by E_far in e, into o. */
static void compose_far(const small_gb *g, const tgi_env *env)
{
    tgi_gview view;
    tgi_rgb far, out;
    sf_rgb_alloc(&far, N * N);
    sf_rgb_alloc(&out, N * N);
    sf_rgb_fill(&far, N * N, e[0], e[1], e[2]);
    tgi_gview_of(&view, &g->gb, NULL);
    tgi_compose_rows(&view, env, &far, 1, &out, NULL, 0, N);
    sf_rgb_read(&out, N * N, o[0], o[1], o[2]);
    sf_rgb_free(&far);
    sf_rgb_free(&out);
}

TEST(white_furnace)
{
    small_gb *g = make_gb(0.5);
    tgi_env env;
    tg_vec3 sh[9];
    int i, c;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_UNIFORM; env.uniform = v3d(1, 1, 1);
    tgi_sh9_from_env(&env, sh);
    far_rows(g, sh, NULL, NULL, NULL, NULL, TG_FAR_CONE_SH);
    compose_far(g, &env);
    for (i = 0; i < N * N; i++)
        for (c = 0; c < 3; c++) {
            CHECK(fabs(dv(e[c][i]) - PI) <= tol_rel() * PI, "E %g want pi", dv(e[c][i]));
            CHECK(fabs(dv(o[c][i]) - 0.5) <= tol_rel() * 0.5, "Lo %g want 0.5", dv(o[c][i]));
        }
    free_gb(g);
}

TEST(sky_hemisphere_matches_rtr_10_42)
{
    double s = 1.2, gr = 0.3;
    tgi_env env;
    tg_vec3 sh[9];
    sky_ctx ctx;
    int k;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_SKY; env.sky = v3d(s, 0.5, 0); env.ground = v3d(gr, 0.5, 0.8); env.up = v3d(0, 1, 0);
    tgi_sh9_from_env(&env, sh);
    {   /* RTR eq. 10.42 at theta = 0, 90, 180 degrees */
        static const double n[3][3] = { { 0, 1, 0 }, { 1, 0, 0 }, { 0, -1, 0 } };
        double want[3] = { PI * s, PI * (0.5 * s + 0.5 * gr), PI * gr };
        for (k = 0; k < 3; k++) {
            tg_vec3 E = tgi_sh9_irradiance(sh, v3d(n[k][0], n[k][1], n[k][2]));
            CHECK(fabs(dv(E.x) - want[k]) <= 0.02 * want[k], "facing %d: E %g want %g", k, dv(E.x), want[k]);
            CHECK(fabs(dv(E.y) - PI * 0.5) <= 0.02 * PI * 0.5, "grey channel %g", dv(E.y));
            CHECK(fabs(dv(E.z) - PI * 0.8 * (k == 0 ? 0 : k == 1 ? 0.5 : 1)) <= 0.02 * PI * 0.8 + 1e-4,
                  "black sky channel %g", dv(E.z));
        }
    }
    /* at any tilt the SH9 irradiance equals the integral of the actual step (band 3+ of
     * the step do not survive the cosine lobe), which is RTR eq. 10.43 */
    ctx.sky = s; ctx.ground = gr; ctx.up[0] = 0; ctx.up[1] = 1; ctx.up[2] = 0;
    for (k = 0; k < NORMAL_COUNT; k++) {
        double n[3] = { normals[k][0], normals[k][1], normals[k][2] }, ref, ct;
        tg_vec3 E;
        unit(n);
        ref = cone_irradiance(L_sky, &ctx, n, PI / 2);
        ct = n[1];
        E = tgi_sh9_irradiance(sh, v3d(n[0], n[1], n[2]));
        CHECK(fabs(dv(E.x) - ref) <= 0.02 * ref, "tilt %d: E %g, integral %g", k, dv(E.x), ref);
        CHECK(fabs(ref - PI * ((1 + ct) / 2 * s + (1 - ct) / 2 * gr)) <= 1e-3 * ref, "eq. 10.43 %g", ref);
    }
    /* the environment itself, for sky pixels */
    CHECK(dv(tgi_env_radiance(&env, v3d(0.1, 0.5, 0)).x) == dv(env.sky.x), "sky above");
    CHECK(dv(tgi_env_radiance(&env, v3d(0.1, -0.5, 0)).x) == dv(env.ground.x), "ground below");
}

TEST(sh9_irradiance_is_the_cosine_convolution)
{
    tg_vec3 sh[9];
    int k, c;
    test_env(sh);
    for (k = 0; k < NORMAL_COUNT; k++) {
        double n[3] = { normals[k][0], normals[k][1], normals[k][2] };
        tg_vec3 E;
        unit(n);
        E = tgi_sh9_irradiance(sh, v3d(n[0], n[1], n[2]));
        for (c = 0; c < 3; c++) {
            sh_ctx ctx;
            double ref, got = dv(c == 0 ? E.x : c == 1 ? E.y : E.z);
            ctx.sh = sh; ctx.c = c;
            ref = cone_irradiance(L_sh, &ctx, n, PI / 2);
            CHECK(fabs(got - ref) <= tol_rel() * ref, "normal %d channel %d: %g vs integral %g", k, c, got, ref);
        }
    }
}

TEST(sh9_radiance_round_trip)
{
    /* project tgi_sh9_radiance back onto the basis (RTR eq. 10.40) and recover the coefficients */
    tg_vec3 sh[9];
    double acc[9][3] = { { 0 } };
    int i, j, nt = 120, np = 240;
    test_env(sh);
    for (i = 0; i < nt; i++) {
        double th = (i + 0.5) * PI / nt;
        for (j = 0; j < np; j++) {
            double ph = (j + 0.5) * 2 * PI / np, d[3] = { sin(th) * cos(ph), cos(th), sin(th) * sin(ph) };
            double y[9], dw = sin(th) * (PI / nt) * (2 * PI / np);
            tg_vec3 L = tgi_sh9_radiance(sh, v3d(d[0], d[1], d[2]));
            int m;
            basis(d, y);
            for (m = 0; m < 9; m++) {
                acc[m][0] += y[m] * dv(L.x) * dw; acc[m][1] += y[m] * dv(L.y) * dw; acc[m][2] += y[m] * dv(L.z) * dw;
            }
        }
    }
    for (j = 0; j < 9; j++) {
        CHECK(fabs(acc[j][0] - dv(sh[j].x)) < 0.01, "L%d r: %g vs %g", j, acc[j][0], dv(sh[j].x));
        CHECK(fabs(acc[j][2] - dv(sh[j].z)) < 0.01, "L%d b: %g vs %g", j, acc[j][2], dv(sh[j].z));
    }
}

TEST(cone_restricted_far_field)
{
    tg_vec3 sh[9];
    int k, a, c;
    test_env(sh);
    for (k = 0; k < NORMAL_COUNT; k++) {
        double n[3] = { normals[k][0], normals[k][1], normals[k][2] };
        tg_vec3 bent, open, full, prev;
        unit(n);
        bent = v3d(n[0], n[1], n[2]);
        open = tgi_sh9_irradiance(sh, bent);
        full = tgi_sh9_irradiance_bent_cone(sh, bent, TG_ONE);
        /* AO = 1: the whole hemisphere, equal to the unoccluded irradiance */
        CHECK(fabs(dv(full.x) - dv(open.x)) <= (TG_FIXED ? 4e-4 : 1e-6) * (1 + dv(open.x)), "AO 1: %g vs %g", dv(full.x), dv(open.x));
        CHECK(fabs(dv(full.z) - dv(open.z)) <= (TG_FIXED ? 4e-4 : 1e-6) * (1 + dv(open.z)), "AO 1 blue");
        prev = full;
        for (a = 19; a >= 0; a--) {
            tg_real ao = rv(a / 20.0);
            tg_vec3 E = tgi_sh9_irradiance_bent_cone(sh, bent, ao);
            CHECK(E.x <= prev.x && E.y <= prev.y && E.z <= prev.z, "decreases as AO drops (AO %g: %g after %g)",
                  a / 20.0, dv(E.x), dv(prev.x));
            if (a == 0) CHECK(E.x == 0 && E.y == 0 && E.z == 0, "AO 0 gives 0");
            if (a == 15 || a == 9 || a == 3) {  /* HBIL sec. 2.2.4 = the integral over the cone asin(sqrt(AO)) */
                double th = asin(sqrt(dv(ao)));
                for (c = 0; c < 3; c++) {
                    sh_ctx ctx;
                    double ref, got = dv(c == 0 ? E.x : c == 1 ? E.y : E.z);
                    ctx.sh = sh; ctx.c = c;
                    ref = cone_irradiance(L_sh, &ctx, n, th);
                    CHECK(fabs(got - ref) <= tol_rel() * ref + 2e-4, "cone AO %g ch %d: %g vs %g", dv(ao), c, got, ref);
                }
            }
            prev = E;
        }
    }
}

/* cos(alpha) = sqrt(1 - AO): the cone whose own cosine-weighted AO
 * (1/pi int_cone cos dw, integrated numerically) is AO. */
TEST(cone_aperture_of_a_cosine_weighted_ao)
{
    int i;
    CHECK(tgi_cone_cos_from_ao(TG_ONE) == 0 && tgi_cone_cos_from_ao(0) == TG_ONE, "AO 1 -> 0, AO 0 -> 1");
    CHECK(tgi_cone_cos_from_ao(rv(1.5)) == 0 && tgi_cone_cos_from_ao(rv(-0.5)) == TG_ONE, "clamped");
    CHECK(fabs(dv(tgi_cone_cos_from_ao(rv(0.75))) - 0.5) < 1e-4, "AO 3/4 -> 60 degrees");
    CHECK(fabs(dv(tgi_cone_angle_from_ao(TG_ONE)) - PI / 2) < 1e-4 && tgi_cone_angle_from_ao(0) == 0,
          "angles: AO 1 -> pi/2, AO 0 -> 0");
    for (i = 1; i < 20; i++) {
        double ao = i / 20.0, c = dv(tgi_cone_cos_from_ao(rv(ao))), alpha = acos(c), sum = 0;
        int k, steps = 2000;
        for (k = 0; k < steps; k++) {   /* 1/pi int_0^alpha 2 pi cos sin dtheta, midpoint rule */
            double th = (k + 0.5) * alpha / steps;
            sum += 2 * cos(th) * sin(th) * alpha / steps;
        }
        CHECK(fabs(sum - ao) < (TG_FIXED ? 2e-4 : 2e-6), "AO %g: the cone %g rad has AO %g", ao, alpha, sum);
        CHECK(fabs(dv(tgi_cone_angle_from_ao(rv(ao))) - alpha) < (TG_FIXED ? 2e-4 : 2e-6), "angle of AO %g", ao);
        /* HBIL eq. 12's aperture acos(1 - AO) is wider: its cone lets through
         * (2 - AO) times the light the AO says */
        {
            double t12 = 1 - ao, e12 = 1 - t12 * t12;
            CHECK(fabs(e12 / ao - (2 - ao)) < 1e-12 && e12 > ao, "eq. 12 at AO %g", ao);
        }
    }
}

/* A uniform sky L over surfaces of albedo a and Fresnel F0 with AO A:
 * Lo = a / pi (1 - F0) pi L A, exactly, in both far-field modes, for any
 * bent normal (a uniform sky does not care where the cone points). */
TEST(uniform_sky_gives_albedo_times_ao_in_both_modes)
{
    small_gb *g = make_gb(0.6);
    static tg_real ao[N * N], bx[N * N], by[N * N], bz[N * N];
    tgi_env env;
    tg_vec3 sh[9];
    double L[3] = { 0.8, 1.0, 1.3 }, albedo = 0.6, f0 = 0.04;
    int i, c, mode;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_UNIFORM; env.uniform = v3d(L[0], L[1], L[2]);
    tgi_sh9_from_env(&env, sh);
    g->material.f0 = rv(f0);
    tgi_material_finish(&g->material);
    for (mode = TG_FAR_CONE_SH; mode <= TG_FAR_CUBE_F0; mode++) {
        double worst = 0;
        for (i = 0; i < N * N; i++) {
            ao[i] = rv((i % 21) / 20.0);
            bx[i] = g->ny[i]; by[i] = g->nz[i]; bz[i] = g->nx[i];
        }
        far_rows(g, sh, ao, bx, by, bz, mode);
        compose_far(g, &env);
        for (i = 0; i < N * N; i++)
            for (c = 0; c < 3; c++) {
                /* A as stored; E and Lo within their storage's rounding (the largest channel, L[2]) */
                double A = dv(ao[i]), want_e = PI * L[c] * A, want = albedo * (1 - f0) * L[c] * A;
                double err = fabs(dv(o[c][i]) - want);
                if (err > worst) worst = err;
                CHECK(fabs(dv(e[c][i]) - want_e) <= (TG_FIXED ? 3e-4 : 2e-6) * (1 + want_e) + sf_rgb_rounding(PI * L[2] * A),
                      "mode %d AO %g: E %g want pi L AO = %g", mode, A, dv(e[c][i]), want_e);
                CHECK(err <= (TG_FIXED ? 2e-4 : 1e-6) * (1 + want) + 2 * sf_rgb_rounding(albedo * L[2] * A),
                      "mode %d AO %g: Lo %g want %g", mode, A, dv(o[c][i]), want);
            }
        printf("# uniform sky, far mode %d: largest |Lo - a/pi (1 - F0) pi L AO| = %.2g\n", mode, worst);
    }
    free_gb(g);
}

TEST(f0_alternative_and_far_rows_inputs)
{
    small_gb *g = make_gb(1.0);
    static tg_real ao[N * N], bx[N * N], by[N * N], bz[N * N];
    tg_vec3 sh[9];
    int i, mode;
    test_env(sh);
    tgi_gb_set_sky(&g->gb, 5);
    for (mode = 0; mode < 3; mode++) {
        for (i = 0; i < N * N; i++) {
            ao[i] = rv((i % 11) / 10.0);
            bx[i] = g->ny[i]; by[i] = g->nz[i]; bz[i] = g->nx[i]; /* another unit vector */
        }
        far_rows(g, sh, ao, bx, by, bz, mode);   /* ao and bent now as stored */
        for (i = 0; i < N * N; i++) {
            tg_vec3 bent = tg_v3(bx[i], by[i], bz[i]), n = tg_v3(g->nx[i], g->ny[i], g->nz[i]), want;
            if (i == 5) { CHECK(e[0][i] == 0 && e[2][i] == 0, "sky pixel gets no far field"); continue; }
            want = stored(mode == TG_FAR_CONE_SH ? tgi_sh9_irradiance_bent_cone(sh, bent, ao[i])
                        : mode == TG_FAR_CUBE_F0 ? tgi_v3_scale(tgi_sh9_irradiance(sh, bent), ao[i])
                        : tgi_sh9_irradiance(sh, n));
            CHECK(e[0][i] == want.x && e[1][i] == want.y && e[2][i] == want.z, "mode %d pixel %d", mode, i);
        }
    }
    /* no AO and no bent normal: the unoccluded irradiance along the normal */
    far_rows(g, sh, NULL, NULL, NULL, NULL, TG_FAR_CONE_SH);
    for (i = 0; i < N * N; i++) {
        tg_vec3 want = stored(tgi_sh9_irradiance(sh, tg_v3(g->nx[i], g->ny[i], g->nz[i])));
        if (i != 5) CHECK(e[0][i] == want.x, "unoccluded pixel %d", i);
    }
    free_gb(g);
}

/* Each basis function alone (over L00 = 1, keeping the radiance positive):
 * the radiance is Y00 + 0.5 Y_j(d) and the irradiance pi Y00 + 0.5 A_l Y_j(n)
 * with A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (Ramamoorthi-Hanrahan eq. 8
 * and 12), against the basis in double to 1e-5 (1e-4 in fixed point; a
 * basis constant wrong in its third digit is 5e-4 off or more). */
TEST(sh9_basis_functions_exact)
{
    static const double A[9] = { PI, 2 * PI / 3, 2 * PI / 3, 2 * PI / 3, PI / 4, PI / 4, PI / 4, PI / 4, PI / 4 };
    double tol = TG_FIXED ? 1e-4 : 1e-5, worst_l = 0, worst_e = 0;
    int i, j, count = 400;
    for (j = 0; j < 9; j++) {
        tg_vec3 sh[9];
        int k;
        for (k = 0; k < 9; k++) sh[k] = tg_v3(0, 0, 0);
        sh[0] = tg_v3(TG_ONE, TG_ONE, TG_ONE);
        sh[j] = tgi_v3_add(sh[j], tg_v3(TG_R(0.5f), TG_R(0.5f), TG_R(0.5f)));
        for (i = 0; i < count; i++) {   /* a Fibonacci sphere */
            double z = 1 - (2 * i + 1.0) / count, r = sqrt(1 - z * z), ph = i * 2.399963229728653;
            double d[3] = { r * cos(ph), r * sin(ph), z }, y[9], want_l, want_e;
            tg_vec3 dd = v3d(d[0], d[1], d[2]), L, E;
            basis(d, y);
            want_l = y[0] * (j == 0 ? 1.5 : 1.0) + (j ? 0.5 * y[j] : 0);
            want_e = PI * y[0] * (j == 0 ? 1.5 : 1.0) + (j ? 0.5 * A[j] * y[j] : 0);
            L = tgi_sh9_radiance(sh, dd);
            E = tgi_sh9_irradiance(sh, dd);
            if (fabs(dv(L.x) - want_l) > worst_l) worst_l = fabs(dv(L.x) - want_l);
            if (fabs(dv(E.z) - want_e) > worst_e) worst_e = fabs(dv(E.z) - want_e);
            CHECK(fabs(dv(L.x) - want_l) <= tol, "Y%d at (%.3f %.3f %.3f): radiance %.6f, want %.6f", j, d[0], d[1],
                  d[2], dv(L.x), want_l);
            CHECK(fabs(dv(E.z) - want_e) <= 2 * tol, "Y%d at (%.3f %.3f %.3f): irradiance %.6f, want %.6f", j, d[0],
                  d[1], d[2], dv(E.z), want_e);
        }
    }
    printf("# SH9 basis: radiance within %.2g, irradiance within %.2g of the basis in double\n", worst_l, worst_e);
}

/* The F0 alternative (HBIL sec. 2.2.3) scales by AO clamped to [0, 1]. */
TEST(f0_alternative_clamps_ao)
{
    tg_vec3 sh[9], n = v3d(0.3, 0.8, -0.52), open, a, b;
    test_env(sh);
    open = tgi_sh9_irradiance(sh, n);
    a = tgi_sh9_irradiance_f0(sh, n, TG_R(1.5f));
    b = tgi_sh9_irradiance_f0(sh, n, TG_R(-0.5f));
    CHECK(a.x == open.x && a.y == open.y && a.z == open.z, "AO 1.5 gives the open irradiance");
    CHECK(b.x == 0 && b.y == 0 && b.z == 0, "AO -0.5 gives 0");
}

/* A sky whose up is tilted off every axis: the SH9 irradiance is RTR eq.
 * 10.43 exactly, E = pi ((1 + cos) / 2 sky + (1 - cos) / 2 ground) with cos
 * the angle to up (the step's band 2 is 0 and its bands 3+ do not survive
 * the cosine lobe), to 1e-3 (2e-3 in fixed point); a direction on the
 * horizon (exactly perpendicular to up) sees the sky. */
TEST(tilted_sky_is_rtr_10_43_exactly)
{
    double s = 1.2, gr = 0.3, up[3] = { 0.36, 0.48, 0.8 }, tol = TG_FIXED ? 2e-3 : 1e-3;   /* unit */
    tgi_env env;
    tg_vec3 sh[9];
    int k;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_SKY; env.sky = v3d(s, s, s); env.ground = v3d(gr, gr, gr); env.up = v3d(up[0], up[1], up[2]);
    tgi_sh9_from_env(&env, sh);
    for (k = 0; k < NORMAL_COUNT + 2; k++) {
        double n[3], ct, want;
        tg_vec3 E;
        if (k < NORMAL_COUNT) { n[0] = normals[k][0]; n[1] = normals[k][1]; n[2] = normals[k][2]; unit(n); }
        else { int sgn = k == NORMAL_COUNT ? 1 : -1; n[0] = sgn * up[0]; n[1] = sgn * up[1]; n[2] = sgn * up[2]; }
        ct = n[0] * up[0] + n[1] * up[1] + n[2] * up[2];
        want = PI * ((1 + ct) / 2 * s + (1 - ct) / 2 * gr);
        E = tgi_sh9_irradiance(sh, v3d(n[0], n[1], n[2]));
        CHECK(fabs(dv(E.x) - want) <= tol * want, "normal %d (cos %.3f to up): E %g want %g", k, ct, dv(E.x), want);
    }
    /* (1, 0.8, -0.6) . (0, 0.6, 0.8) = 0: the same two products, exactly cancelling */
    env.up = tg_v3(0, TG_R(0.6f), TG_R(0.8f));
    CHECK(dv(tgi_env_radiance(&env, tg_v3(TG_ONE, TG_R(0.8f), TG_R(-0.6f))).x) == dv(env.sky.x), "the horizon is sky");
    CHECK(dv(tgi_env_radiance(&env, tg_v3(TG_ONE, TG_R(0.8f), TG_R(-0.61f))).x) == dv(env.ground.x), "just below it ground");
}

int main(void)
{
    RUN(white_furnace);
    RUN(sky_hemisphere_matches_rtr_10_42);
    RUN(sh9_irradiance_is_the_cosine_convolution);
    RUN(sh9_radiance_round_trip);
    RUN(cone_restricted_far_field);
    RUN(cone_aperture_of_a_cosine_weighted_ao);
    RUN(uniform_sky_gives_albedo_times_ao_in_both_modes);
    RUN(f0_alternative_and_far_rows_inputs);
    RUN(sh9_basis_functions_exact);
    RUN(f0_alternative_clamps_ao);
    RUN(tilted_sky_is_rtr_10_43_exactly);
    return check_summary();
}
