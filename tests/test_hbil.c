/* SPDX-License-Identifier: MIT */
/*
 * test_hbil.c - the HBIL horizon kernel on analytic scenes.
 *
 * The G-buffers are built by ray-casting a few quads per pixel (no
 * rasterizer).  Checked: an open plane at 5/30/60/90 degrees elevation is
 * unoccluded with the bent normal on the normal; a 90-degree groove's AO
 * rises with distance from the crease, is the same on both faces and is
 * close to a ray-traced cosine-weighted AO with the same radius; cone =
 * acos(sqrt(1 - AO)) (src/light/sh.h, not eq. 12); the interleaved path approaches the full-resolution
 * kernel with the same 32 directions; near field: an enclosure of uniform
 * radiance L gives AO + E_near / (pi L) = 1; fixed and float agree; a
 * floor before a wall whose top (against the sky) is hundreds of pixels of
 * march away gets the ray-traced AO; at quarter resolution (half-res kernel,
 * joint bilateral upsample) the floor at a low wall's foot keeps its contact
 * shadow.
 */
#include <stdlib.h>
#include "check.h"
#include "storage_fixture.h"
#include "core/vec.h"
#include "raster/view.h"
#include "gi/hbil.h"
#include "gi/interleave.h"
#include "gi/resample.h"
#include "ao/ao.h"
#include "frame_fixture.h"

#define DEG (3.14159265358979 / 180.0)

/* ---- analytic G-buffers ---- */
typedef struct quad { double o[3], e1[3], e2[3]; double rad; } quad;
typedef struct scene { int n; quad q[4]; } scene;

typedef struct gbuf {
    int w, h;
    tgi_view view;
    tg_real *depth, *nx, *ny, *nz, *rad;
    uint8_t *sky;
    int *face;             /* quad index or -1 */
    double *px, *py, *pz;  /* world hit point */
} gbuf;

static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1]; c[1] = a[2] * b[0] - a[0] * b[2]; c[2] = a[0] * b[1] - a[1] * b[0];
}
static void norm3(double *a) { double l = sqrt(dot3(a, a)); if (l > 0) { a[0] /= l; a[1] /= l; a[2] /= l; } }

/* Nearest hit of a ray (origin e, direction d) with the quads; t along d. */
static int cast(const scene *s, const double *e, const double *d, double tmax, double *t_out, double *n_out)
{
    int k, best = -1;
    double tb = tmax;
    for (k = 0; k < s->n; k++) {
        const quad *q = &s->q[k];
        double nq[3], rel[3], p[3], den, t, a, b;
        cross3(q->e1, q->e2, nq);
        den = dot3(nq, d);
        if (fabs(den) < 1e-12) continue;
        rel[0] = q->o[0] - e[0]; rel[1] = q->o[1] - e[1]; rel[2] = q->o[2] - e[2];
        t = dot3(nq, rel) / den;
        if (t <= 1e-9 || t >= tb) continue;
        p[0] = e[0] + t * d[0] - q->o[0]; p[1] = e[1] + t * d[1] - q->o[1]; p[2] = e[2] + t * d[2] - q->o[2];
        a = dot3(p, q->e1) / dot3(q->e1, q->e1);
        b = dot3(p, q->e2) / dot3(q->e2, q->e2);
        if (a < 0 || a > 1 || b < 0 || b > 1) continue;
        tb = t; best = k;
        if (n_out) { n_out[0] = nq[0]; n_out[1] = nq[1]; n_out[2] = nq[2]; norm3(n_out); if (dot3(n_out, d) > 0) { n_out[0] = -n_out[0]; n_out[1] = -n_out[1]; n_out[2] = -n_out[2]; } }
    }
    if (t_out) *t_out = tb;
    return best;
}

static tg_vec3 tv(double x, double y, double z) { return tg_v3(tg_from_float((float)x), tg_from_float((float)y), tg_from_float((float)z)); }
static void vd(tg_vec3 v, double *o) { o[0] = check_d(v.x); o[1] = check_d(v.y); o[2] = check_d(v.z); }

static void gbuf_make(gbuf *g, const scene *s, int w, int h, const double *eye, const double *target, const double *up)
{
    int x, y;
    size_t n = (size_t)w * h;
    double r[3], u[3], f[3], ppu;
    memset(g, 0, sizeof *g);
    g->w = w; g->h = h;
    tgi_view_make(&g->view, tv(eye[0], eye[1], eye[2]), tv(target[0], target[1], target[2]), tv(up[0], up[1], up[2]),
                 tg_from_float((float)(60 * DEG)), TG_R(0.05f), TG_R(1000.0f), w, h);
    g->depth = calloc(n, sizeof(tg_real)); g->nx = calloc(n, sizeof(tg_real));
    g->ny = calloc(n, sizeof(tg_real)); g->nz = calloc(n, sizeof(tg_real));
    g->rad = calloc(n, sizeof(tg_real)); g->sky = calloc(n, 1); g->face = calloc(n, sizeof(int));
    g->px = calloc(n, sizeof(double)); g->py = calloc(n, sizeof(double)); g->pz = calloc(n, sizeof(double));
    vd(g->view.right, r); vd(g->view.up, u); vd(g->view.forward, f);
    ppu = check_d(g->view.pixels_per_unit);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * w + x;
            double X = (x + 0.5 - w / 2.0) / ppu, Y = (h / 2.0 - (y + 0.5)) / ppu, d[3], t, nn[3];
            int k;
            d[0] = r[0] * X + u[0] * Y + f[0]; d[1] = r[1] * X + u[1] * Y + f[1]; d[2] = r[2] * X + u[2] * Y + f[2];
            k = cast(s, eye, d, 1e30, &t, nn);
            g->face[i] = k;
            if (k < 0) { g->sky[i] = 1; continue; }
            g->depth[i] = tg_from_float((float)t);  /* d has unit forward component: t is view z */
            g->nx[i] = tg_from_float((float)nn[0]); g->ny[i] = tg_from_float((float)nn[1]); g->nz[i] = tg_from_float((float)nn[2]);
            g->rad[i] = tg_from_float((float)s->q[k].rad);
            g->px[i] = eye[0] + t * d[0]; g->py[i] = eye[1] + t * d[1]; g->pz[i] = eye[2] + t * d[2];
        }
}

static void gbuf_free(gbuf *g)
{
    free(g->depth); free(g->nx); free(g->ny); free(g->nz); free(g->rad); free(g->sky); free(g->face);
    free(g->px); free(g->py); free(g->pz);
}

typedef struct result { tg_real *ao, *bx, *by, *bz, *cone, *near; } result;

static void result_alloc(result *r, size_t n)
{
    r->ao = calloc(n, sizeof(tg_real)); r->bx = calloc(n, sizeof(tg_real)); r->by = calloc(n, sizeof(tg_real));
    r->bz = calloc(n, sizeof(tg_real)); r->cone = calloc(n, sizeof(tg_real)); r->near = calloc(n, sizeof(tg_real));
}
static void result_free(result *r) { free(r->ao); free(r->bx); free(r->by); free(r->bz); free(r->cone); free(r->near); }

static void params_for(tgi_hbil_params *p, double radius)
{
    tgi_hbil_defaults(p);
    p->radius = tg_from_float((float)radius);
}

/* The full-resolution view of g (its storage in *gb, storage_fixture.h:
 * free it with sf_gbuffer_free). */
static void view_of(const gbuf *g, tgi_gbuffer *gb, tgi_gview *v)
{
    sf_gbuffer_alloc(gb, g->w, g->h, NULL, 0);
    sf_gbuffer_fill(gb, g->depth, g->nx, g->ny, g->nz, g->sky, 0);
    tgi_gview_of(v, gb, &g->view);
}

/* Results in the build's storage for n pixels (read back by results_read). */
static tgi_gresult results_of(size_t n, int near)
{
    tgi_gresult o;
    sf_results_alloc(&o, n, 1, 1, near);
    return o;
}

/* The results as numbers (the near field's red channel: the radiance is grey), then freed. */
static void results_read(tgi_gresult *o, size_t n, result *r)
{
    tg_real *gb_unused = (tg_real *)malloc(2 * n * sizeof(tg_real));
    sf_results_read(o, n, r->ao, r->bx, r->by, r->bz, r->cone, r->near, gb_unused, gb_unused + n);
    free(gb_unused);
    sf_results_free(o);
}

/* Full resolution, per-pixel 4x4 pattern of the 32 directions; every
 * surface of material `mat` of `materials` (NULL: the fixture's). */
static int hbil_rejection = 1;   /* 0: run_full gathers from every sender (HBIL sec. 3.4's t = 1) */
static int hbil_samples = 0;     /* > 0: run_full's samples a side (else the default) */

static void run_full_with(const gbuf *g, double radius, int near, result *r, const tgi_material *materials,
                          int count, int mat)
{
    tgi_hbil_params p;
    tgi_gbuffer gb;
    tgi_gview v;
    size_t n = (size_t)g->w * g->h;
    tgi_gresult o = results_of(n, near);
    tgi_rgb rad = tgi_rgb_none();
    params_for(&p, radius);
    if (hbil_samples > 0) p.samples = hbil_samples;
    if (!hbil_rejection) { p.rejection_a = TG_R(-3.0f); p.rejection_b = TG_R(-2.0f); }  /* t = 1 for every sender */
    sf_gbuffer_alloc(&gb, g->w, g->h, materials, count);
    sf_gbuffer_fill(&gb, g->depth, g->nx, g->ny, g->nz, g->sky, mat);
    tgi_gview_of(&v, &gb, &g->view);
    if (near) { sf_rgb_alloc(&rad, n); sf_rgb_fill(&rad, n, g->rad, g->rad, g->rad); }
    tgi_hbil_rows(&p, &v, &rad, &o, 0, g->h);
    results_read(&o, n, r);
    if (near) sf_rgb_free(&rad);
    sf_gbuffer_free(&gb);
}
static void run_full(const gbuf *g, double radius, int near, result *r) { run_full_with(g, radius, near, r, NULL, 0, 0); }

/* 4x4 split, the kernel per sub-image, merge. */
static void run_interleaved(const gbuf *g, double radius, result *r)
{
    size_t n = (size_t)g->w * g->h;
    tg_real *b[9];
    uint8_t *sky = malloc(n);
    const tg_real *in[4] = { g->depth, g->nx, g->ny, g->nz };
    tg_real *out[5] = { r->ao, r->bx, r->by, r->bz, r->cone };
    tgi_gbuffer split, gb;
    tgi_gview full;
    tgi_gresult o;
    tgi_hbil_params p;
    result split_r;
    int k;
    for (k = 0; k < 9; k++) b[k] = malloc(n * sizeof(tg_real));
    for (k = 0; k < 4; k++) tgi_interleave_split(in[k], g->w, g->h, b[k]);
    tgi_interleave_split8(g->sky, g->w, g->h, sky);
    sf_gbuffer_alloc(&split, g->w, g->h, NULL, 0);   /* the sub-images, in the build's storage */
    sf_gbuffer_fill(&split, b[0], b[1], b[2], b[3], sky, 0);
    o = results_of(n, 0);
    params_for(&p, radius);
    view_of(g, &gb, &full);
    tgi_hbil_interleaved_rows(&p, &full, &split, NULL, &o, 0, g->h);
    split_r.ao = b[4]; split_r.bx = b[5]; split_r.by = b[6]; split_r.bz = b[7]; split_r.cone = b[8]; split_r.near = NULL;
    results_read(&o, n, &split_r);
    for (k = 0; k < 5; k++) tgi_interleave_merge(b[4 + k], g->w, g->h, out[k]);
    for (k = 0; k < 9; k++) free(b[k]);
    sf_gbuffer_free(&split);
    sf_gbuffer_free(&gb);
    free(sky);
}

/* The same 16 sub-images as strided views of the full-resolution buffers
 * (no copy), the results written in place. */
static void run_strided(const gbuf *g, double radius, result *r)
{
    tgi_gbuffer gb;
    tgi_gview full;
    tgi_gresult all = results_of((size_t)g->w * g->h, 0);
    int i, j;
    view_of(g, &gb, &full);
    for (j = 0; j < 4; j++)
        for (i = 0; i < 4; i++) {
            tgi_hbil_params p;
            tgi_gview sub;
            tgi_gresult o = tgi_gresult_from(&all, tgi_gv_index(&full, i, j));
            tgi_gview_strided_sub(&sub, &full, i, j);
            if (sub.width == 0 || sub.height == 0) continue;
            params_for(&p, radius);
            p.fine = &full;
            tgi_hbil_rows(&p, &sub, NULL, &o, 0, sub.height);
        }
    results_read(&all, (size_t)g->w * g->h, r);
    sf_gbuffer_free(&gb);
}

static double angle_deg(double ax, double ay, double az, double bx, double by, double bz)
{
    double la = sqrt(ax * ax + ay * ay + az * az), lb = sqrt(bx * bx + by * by + bz * bz), c;
    if (la == 0 || lb == 0) return 180;
    c = (ax * bx + ay * by + az * bz) / (la * lb);
    if (c > 1) c = 1;
    if (c < -1) c = -1;
    return acos(c) / DEG;
}

/* ---- open plane ---- */
static void open_plane_check(double elev_deg, int interleaved, double radius)
{
    scene s = { 1, { { { -20, 0, -20 }, { 40, 0, 0 }, { 0, 0, 40 }, 1 } } };
    double eye[3], target[3] = { 0, 0, 0 }, up[3] = { 0, 1, 0 }, worst_ao = 1, worst_bent = 0;
    gbuf g;
    result r;
    size_t i, n, count = 0;
    eye[0] = 0; eye[1] = 4 * sin(elev_deg * DEG); eye[2] = 4 * cos(elev_deg * DEG);
    if (elev_deg >= 89.9) { up[0] = 0; up[1] = 0; up[2] = -1; }
    gbuf_make(&g, &s, 96, 64, eye, target, up);
    n = (size_t)g.w * g.h;
    result_alloc(&r, n);
    if (interleaved) run_interleaved(&g, radius, &r); else run_full(&g, radius, 0, &r);
    for (i = 0; i < n; i++) {
        double a, b;
        if (g.sky[i]) { CHECK(r.ao[i] == TG_ONE, "sky AO must be 1"); continue; }
        count++;
        a = check_d(r.ao[i]);
        b = angle_deg(check_d(r.bx[i]), check_d(r.by[i]), check_d(r.bz[i]), 0, 1, 0);
        if (a < worst_ao) worst_ao = a;
        if (b > worst_bent) worst_bent = b;
    }
    CHECK(count > n / 4, "plane covers %zu of %zu pixels", count, n);
    CHECK(worst_ao >= 0.99, "elevation %g%s, radius %g: worst AO %.4f", elev_deg, interleaved ? " interleaved" : "", radius, worst_ao);
    CHECK(worst_bent <= 2.0, "elevation %g%s, radius %g: worst bent angle %.3f deg", elev_deg, interleaved ? " interleaved" : "",
          radius, worst_bent);
    printf("  open plane %2g deg%s, radius %g: min AO %.5f, max bent angle %.3f deg\n", elev_deg,
           interleaved ? " (interleaved)" : "", radius, worst_ao, worst_bent);
    result_free(&r);
    gbuf_free(&g);
}

TEST(open_plane_full_res) { open_plane_check(5, 0, 1); open_plane_check(30, 0, 1); open_plane_check(60, 0, 1); open_plane_check(90, 0, 1); }
TEST(open_plane_interleaved) { open_plane_check(5, 1, 1); open_plane_check(30, 1, 1); open_plane_check(60, 1, 1); open_plane_check(90, 1, 1); }
/* A radius that spans the image: the march steps m > 1 pixels, and a
 * pixel at the screen's edge whose side had no sample (the offset o put
 * the first past the edge) took a "last pixel" sample at its own position
 * (march_between: distance -o, then room - last = o pixels on): a zero
 * offset of arbitrary direction that closed its side (AO 0.86 on the
 * image's edge columns of a plane, 0.91 interleaved). */
TEST(open_plane_long_radius)
{
    int interleaved;
    for (interleaved = 0; interleaved <= 1; interleaved++) {
        open_plane_check(5, interleaved, 50); open_plane_check(30, interleaved, 50);
        open_plane_check(60, interleaved, 50); open_plane_check(90, interleaved, 50);
    }
}

/* A ground plane to its far edge at a grazing view: the camera 0.3 above
 * it, the plane 800 across, so the row where it ends against the sky
 * spans it from 12 units away to 400.  A sample there, between that row
 * and the sky, took the row's depth on a ray above it (or, moved to the
 * row's own ray, a point off the slice): far above the plane, it closed
 * the horizon (AO 0.88 along the row at radius 50; sample_depth_edge). */
TEST(open_plane_far_edge)
{
    scene s = { 1, { { { -400, 0, -400 }, { 800, 0, 0 }, { 0, 0, 800 }, 1 } } };
    double eye[3] = { 0, 0.3, -8 }, target[3] = { 0, 0, 0 }, up[3] = { 0, 1, 0 }, radii[3] = { 0.5, 50, 500 };
    int k, interleaved;
    for (k = 0; k < 3; k++)
        for (interleaved = 0; interleaved <= 1; interleaved++) {
            gbuf g;
            result r;
            double worst = 1;
            size_t i, n, count = 0;
            gbuf_make(&g, &s, 64, 48, eye, target, up);
            n = (size_t)g.w * g.h;
            result_alloc(&r, n);
            if (interleaved) run_interleaved(&g, radii[k], &r); else run_full(&g, radii[k], 0, &r);
            for (i = 0; i < n; i++) {
                if (g.sky[i]) continue;
                count++;
                worst = fmin(worst, check_d(r.ao[i]));
            }
            printf("  plane to its far edge, radius %g%s: min AO %.4f over %zu pixels\n", radii[k],
                   interleaved ? " (interleaved)" : "", worst, count);
            CHECK(count > n / 3, "the plane covers %zu of %zu pixels", count, n);
            CHECK(worst >= 0.99, "radius %g%s: worst AO %.4f", radii[k], interleaved ? " interleaved" : "", worst);
            result_free(&r);
            gbuf_free(&g);
        }
}

/* ---- the groove: faces y = x (x >= 0) and y = -x (x <= 0), crease along z ---- */
static void groove_scene(scene *s)
{
    quad a = { { 0, 0, -20 }, { 3, 3, 0 }, { 0, 0, 40 }, 1 };
    quad b = { { 0, 0, -20 }, { -3, 3, 0 }, { 0, 0, 40 }, 1 };
    s->n = 2; s->q[0] = a; s->q[1] = b;
}

static void groove_view(gbuf *g, const scene *s, int w, int h)
{
    double eye[3] = { 0, 4, 0.5 }, target[3] = { 0, 0, 0.5 }, up[3] = { 0, 0, -1 };
    gbuf_make(g, s, w, h, eye, target, up);
}

/* The mean of f(face hit or -1, hit point) over 4096 cosine-weighted
 * directions about n from p, rays cut at `radius`. */
static double cosine_mean(const scene *s, const double *p, const double *n, double radius,
                          double (*f)(int face, const double *hit))
{
    int k, N = 4096;
    double t1[3], t2[3], a[3] = { 1, 0, 0 }, sum = 0;
    if (fabs(n[0]) > 0.9) { a[0] = 0; a[1] = 1; }
    cross3(n, a, t1); norm3(t1); cross3(n, t1, t2);
    for (k = 0; k < N; k++) {
        double u1 = (k + 0.5) / N, u2 = fmod(k * 0.618033988749895, 1.0);
        double r = sqrt(u1), ph = 2 * 3.14159265358979 * u2, z = sqrt(1 - u1), d[3], o[3], t = 0, hit[3];
        int j, face;
        for (j = 0; j < 3; j++) {
            d[j] = r * cos(ph) * t1[j] + r * sin(ph) * t2[j] + z * n[j];
            o[j] = p[j] + 1e-6 * n[j];
        }
        face = cast(s, o, d, radius, &t, NULL);
        for (j = 0; j < 3; j++) hit[j] = o[j] + t * d[j];
        sum += f(face, hit);
    }
    return sum / N;
}

static double open_direction(int face, const double *hit) { (void)hit; return face < 0; }

/* Ray-traced cosine-weighted AO with maximum distance `radius`. */
static double reference_ao(const scene *s, const double *p, const double *n, double radius)
{
    return cosine_mean(s, p, n, radius, open_direction);
}

/* Mean AO per face over bands of 4 pixel columns from the crease (the crease
 * is between the two centre columns, so mirrored bands hold the same 4
 * column residues of the 4x4 direction pattern); pos = mean hit point. */
#define BANDS 8
static void groove_bands(const gbuf *g, const tg_real *ao, double mean[2][BANDS], double pos[2][BANDS][3])
{
    double sum[2][BANDS] = { { 0 } }, ps[2][BANDS][3] = { { { 0 } } };
    int cnt[2][BANDS] = { { 0 } }, f, b, k;
    size_t i, n = (size_t)g->w * g->h;
    for (i = 0; i < n; i++) {
        int x = (int)(i % g->w);
        if (g->face[i] < 0) continue;
        if (fabs(g->pz[i] - 0.5) > 0.6) continue;   /* central strip */
        f = x >= g->w / 2 ? 0 : 1;
        b = f == 0 ? (x - g->w / 2) / 4 : (g->w / 2 - 1 - x) / 4;
        if (b >= BANDS || g->face[i] != f) continue;
        sum[f][b] += check_d(ao[i]);
        ps[f][b][0] += g->px[i]; ps[f][b][1] += g->py[i]; ps[f][b][2] += g->pz[i];
        cnt[f][b]++;
    }
    for (f = 0; f < 2; f++)
        for (b = 0; b < BANDS; b++) {
            mean[f][b] = cnt[f][b] ? sum[f][b] / cnt[f][b] : -1;
            for (k = 0; k < 3; k++) pos[f][b][k] = cnt[f][b] ? ps[f][b][k] / cnt[f][b] : 0;
        }
}

TEST(groove)
{
    scene s;
    gbuf g;
    result r;
    double mean[2][BANDS], pos[2][BANDS][3], radius = 1.0;
    int f, b;
    groove_scene(&s);
    groove_view(&g, &s, 192, 144);
    result_alloc(&r, (size_t)g.w * g.h);
    run_full(&g, radius, 0, &r);
    groove_bands(&g, r.ao, mean, pos);
    for (b = 0; b < BANDS; b++) {
        double nrm[2][3] = { { -0.70710678118654752, 0.70710678118654752, 0 }, { 0.70710678118654752, 0.70710678118654752, 0 } };
        double ref = reference_ao(&s, pos[0][b], nrm[0], radius);
        printf("  groove band %d (dist %.3f): AO face A %.4f face B %.4f ray-traced %.4f\n", b, sqrt(2.0) * pos[0][b][0],
               mean[0][b], mean[1][b], ref);
        for (f = 0; f < 2; f++) {
            CHECK(mean[f][b] >= 0, "band %d face %d empty", b, f);
            if (b > 0) CHECK(mean[f][b] >= mean[f][b - 1] - 0.01, "face %d band %d: AO %.4f < %.4f (must rise from the crease)", f, b, mean[f][b], mean[f][b - 1]);
            CHECK_NEAR(mean[f][b], ref, 0.03);   /* measured <= 0.015 */
        }
        CHECK_NEAR(mean[0][b], mean[1][b], 0.02);
    }
    CHECK(mean[0][0] < 0.8 && mean[1][0] < 0.8, "the crease is occluded: %.3f %.3f", mean[0][0], mean[1][0]);
    CHECK(mean[0][BANDS - 1] > mean[0][0] + 0.15, "AO rises from the crease");
    result_free(&r);
    gbuf_free(&g);
}

/* The cone whose cosine-weighted AO is the AO: acos(sqrt(1 - AO)) (src/light/sh.h). */
static double cone_of(double a) { return acos(sqrt(1 - a)); }

TEST(cone_is_the_aperture_of_a_cosine_weighted_ao)
{
    scene s;
    gbuf g;
    result r;
    size_t i, n;
    double worst = 0;
    groove_scene(&s);
    groove_view(&g, &s, 64, 48);
    n = (size_t)g.w * g.h;
    result_alloc(&r, n);
    run_full(&g, 1.0, 0, &r);
    for (i = 0; i < n; i++) {
        double a = check_d(r.ao[i]), c = check_d(r.cone[i]), e = fabs(c - cone_of(a));
        CHECK(a >= 0 && a <= 1 && c >= 0 && c <= 1.5708 + 1e-3, "pixel %zu: AO %g cone %g", i, a, c);
#if !TG_WIDE_STORAGE
        {   /* as stored: AO and cone in 8 bits each; take off the rounding of both */
            double h = 0.5 / 255, lo = cone_of(fmin(1, a + h)), hi = cone_of(fmax(0, a - h));
            double round = fmax(fabs(lo - cone_of(a)), fabs(hi - cone_of(a))) + 0.5 / 255 * 1.5707963;
            e = fmax(0, e - round);
        }
#endif
        if (e > worst) worst = e;
    }
    CHECK(worst < 2e-3, "cone vs acos(sqrt(1 - AO)): worst %.5f rad", worst); /* fixed acos error bound */
    result_free(&r);
    gbuf_free(&g);
}

static double rmse(const tg_real *a, const tg_real *b, const uint8_t *sky, size_t n)
{
    double s = 0;
    size_t i, c = 0;
    for (i = 0; i < n; i++) {
        double d;
        if (sky && sky[i]) continue;
        d = check_d(a[i]) - check_d(b[i]);
        s += d * d; c++;
    }
    return c ? sqrt(s / c) : 0;
}

/* The interleaved result approaches the full-resolution kernel with the
 * same 32 directions.  They differ only in where the march samples (every
 * 4th pixel vs every pixel); the stated remaining error is the RMSE below. */
TEST(interleaved_matches_full_res)
{
    scene s;
    gbuf g;
    result full, il;
    size_t n;
    double e_raw, e_blk;
    tg_real *fb, *ib;
    groove_scene(&s);
    groove_view(&g, &s, 160, 120);
    n = (size_t)g.w * g.h;
    result_alloc(&full, n); result_alloc(&il, n);
    run_full(&g, 1.0, 0, &full);
    run_interleaved(&g, 1.0, &il);
    e_raw = rmse(full.ao, il.ao, g.sky, n);
    /* 4x4 box average of both (the 32 directions merged), compared */
    fb = calloc(n, sizeof(tg_real)); ib = calloc(n, sizeof(tg_real));
    {
        int x, y;
        for (y = 0; y + 4 <= g.h; y += 4)
            for (x = 0; x + 4 <= g.w; x += 4) {
                double sf = 0, si = 0;
                int dx, dy;
                for (dy = 0; dy < 4; dy++) for (dx = 0; dx < 4; dx++) {
                    size_t i = (size_t)(y + dy) * g.w + x + dx;
                    sf += check_d(full.ao[i]); si += check_d(il.ao[i]);
                }
                fb[(size_t)y * g.w + x] = tg_from_float((float)(sf / 16)); ib[(size_t)y * g.w + x] = tg_from_float((float)(si / 16));
            }
    }
    e_blk = rmse(fb, ib, NULL, n) * 4; /* 1 in 16 entries are set */
    printf("  interleaved vs full-res AO: RMSE per pixel %.4f, of 4x4 block means %.4f\n", e_raw, e_blk);
    CHECK(e_raw < 0.05, "per-pixel RMSE %.4f", e_raw);
    CHECK(e_blk < 0.02, "block-mean RMSE %.4f", e_blk);
    free(fb); free(ib);
    result_free(&full); result_free(&il);
    gbuf_free(&g);
}

/* A 4x4 sub-image read as a strided view of the full-resolution buffers
 * gives the same bits as the packed copy the split makes (odd sizes: some
 * sub-images are narrower than others). */
TEST(strided_sub_images_match_packed_copies)
{
    scene s;
    gbuf g;
    result packed, strided;
    size_t n, i, diff = 0;
    groove_scene(&s);
    groove_view(&g, &s, 53, 37);
    n = (size_t)g.w * g.h;
    result_alloc(&packed, n); result_alloc(&strided, n);
    run_interleaved(&g, 1.0, &packed);
    run_strided(&g, 1.0, &strided);
    for (i = 0; i < n; i++)
        diff += packed.ao[i] != strided.ao[i] || packed.bx[i] != strided.bx[i] || packed.by[i] != strided.by[i]
              || packed.bz[i] != strided.bz[i] || packed.cone[i] != strided.cone[i];
    CHECK(diff == 0, "%zu of %zu pixels differ", diff, n);
    result_free(&packed); result_free(&strided);
    gbuf_free(&g);
}

/* Near field: a box around the camera of uniform radiance L, so every
 * occluded direction sends L: AO + E_near / (pi L) = 1 (HBIL fig. 15)
 * exactly when every sender counts; the rejection of senders facing away
 * (sec. 3.4's t < 1, near a crease where the other face is seen edge-on)
 * can only take light away, never add it. */
TEST(near_field_complements_ao)
{
    scene s;
    gbuf g;
    result r;
    size_t i, n;
    double worst = 0, over = 0, L = 2.0, maxnear = 0;
    int rejection;
    groove_scene(&s);
    s.q[0].rad = L; s.q[1].rad = L;
    groove_view(&g, &s, 64, 48);
    n = (size_t)g.w * g.h;
    result_alloc(&r, n);
    for (rejection = 0; rejection <= 1; rejection++) {
        hbil_rejection = rejection;
        run_full(&g, 1.0, 1, &r);
        for (i = 0; i < n; i++) {
            double a = check_d(r.ao[i]), e = check_d(r.near[i]), d, slack;
            if (g.sky[i]) { CHECK(r.near[i] == 0, "sky near must be 0"); continue; }
            slack = 0.5 / 255 + sf_rgb_rounding(e) / (3.14159265358979 * L);   /* the storage's rounding */
            d = a + e / (3.14159265358979 * L) - 1;
            if (!rejection && fabs(d) - slack > worst) worst = fabs(d) - slack;
            if (rejection && d - slack > over) over = d - slack;
            if (e > maxnear) maxnear = e;
        }
    }
    hbil_rejection = 1;
    printf("  near field: max E_near %.4f, worst |AO + E/(pi L) - 1| %.5f every sender, %.5f over with rejection\n",
           maxnear, worst, over);
    CHECK(maxnear > 0.3, "the groove gathers light: %g", maxnear);
    CHECK(worst < 0.002, "complement error %g", worst);
    CHECK(over < 0.002, "rejection added light: %g", over);
    result_free(&r);
    gbuf_free(&g);
}

/* The near field of a sender whose radiance changes along it: face B of
 * the groove sends L = 0.5 + 2 s (s: the distance from the crease), face A
 * gathers it.  Ray-traced, E = int L(x(w)) cos dw over the directions
 * that meet face B within the radius.  Face B climbs face A's horizon
 * sample after sample (as a ceiling does over a wall), and eq. 18 gives
 * each rise's band the radiance of the sample that closed it, the band's
 * far end: where L grows outward the bands took too much, the more the
 * farther apart the samples (+5.9% over the bands with 8 samples a side,
 * +0.2% with 32, -1.4% with 128: the sum depended on the step).  A band
 * closed right after another rise takes the mean of the two samples'
 * radiance (the trapezoid rule along the surface): -4.3%, -3.5%, -3.1%. */
static double ramp_radiance(int face, const double *hit) { return face == 1 ? 0.5 + 2 * sqrt(2.0) * fabs(hit[0]) : 0; }

static double reference_near(const scene *s, const double *p, const double *n, double radius)
{
    return 3.14159265358979 * cosine_mean(s, p, n, radius, ramp_radiance);   /* cosine-weighted: E = pi mean(L) */
}

TEST(near_field_of_a_radiance_ramp)
{
    static const int samples[3] = { 8, 32, 128 };
    scene s;
    gbuf g;
    result r;
    double mean[2][BANDS], pos[2][BANDS][3], radius = 1.0, ratio[3];
    size_t i, n;
    int b, k;
    groove_scene(&s);
    s.q[0].rad = 0;
    groove_view(&g, &s, 384, 288);
    n = (size_t)g.w * g.h;
    for (i = 0; i < n; i++)
        if (g.face[i] == 1) g.rad[i] = tg_from_float((float)(0.5 + 2 * sqrt(2.0) * fabs(g.px[i])));
    result_alloc(&r, n);
    for (k = 0; k < 3; k++) {
        double worst = 0, sum_h = 0, sum_r = 0;
        hbil_samples = samples[k];
        run_full(&g, radius, 1, &r);
        groove_bands(&g, r.near, mean, pos);
        for (b = 0; b < BANDS; b++) {
            double nrm[3] = { -0.70710678118654752, 0.70710678118654752, 0 };
            double ref = reference_near(&s, pos[0][b], nrm, radius), e = mean[0][b];
            CHECK(e >= 0 && ref > 0, "band %d empty", b);
            worst = fmax(worst, fabs(e / ref - 1));
            sum_h += e; sum_r += ref;
        }
        ratio[k] = sum_h / sum_r;
        printf("  radiance ramp, %3d samples a side: bands' E_near %+.1f%% of the ray-traced, worst band %.1f%%\n",
               samples[k], 100 * (ratio[k] - 1), 100 * worst);
        CHECK(fabs(ratio[k] - 1) < 0.05, "%d samples: the near field is %+.1f%% off", samples[k], 100 * (ratio[k] - 1));
        CHECK(worst < 0.10, "%d samples: a band's near field is %.1f%% off", samples[k], 100 * worst);
    }
    hbil_samples = 0;
    CHECK(fabs(ratio[0] / ratio[2] - 1) < 0.02, "the near field depends on the step: %+.1f%% with 8 samples against 128",
          100 * (ratio[0] / ratio[2] - 1));
    result_free(&r);
    gbuf_free(&g);
}

/* E_near is irradiance (HBIL eq. 16-18): the receiver's 1 - F0 of eq. 19
 * weighs it once, with the albedo, where Lo is composed, so a receiver's
 * F0 does not change it (it did: the kernel applied 1 - F0 too, and the
 * composed near field came out (1 - F0)^2). */
TEST(near_field_is_irradiance)
{
    scene s;
    gbuf g;
    result r[2];
    tgi_material m[2];
    size_t i, n;
    double sum[2] = { 0, 0 }, worst = 0;
    int k;
    memset(m, 0, sizeof m);
    for (k = 0; k < 2; k++) m[k].albedo = tg_v3(TG_R(0.8f), TG_R(0.8f), TG_R(0.8f));
    m[1].f0 = TG_R(0.5f);
    for (k = 0; k < 2; k++) tgi_material_finish(&m[k]);
    groove_scene(&s);
    s.q[0].rad = 1.0; s.q[1].rad = 1.0;
    groove_view(&g, &s, 64, 48);
    n = (size_t)g.w * g.h;
    for (k = 0; k < 2; k++) {
        result_alloc(&r[k], n);
        run_full_with(&g, 1.0, 1, &r[k], m, 2, k);
    }
    for (i = 0; i < n; i++) {
        if (g.sky[i]) continue;
        sum[0] += check_d(r[0].near[i]);
        sum[1] += check_d(r[1].near[i]);
        worst = fmax(worst, fabs(check_d(r[0].near[i]) - check_d(r[1].near[i])));
    }
    printf("  near field, receiver F0 0 vs 0.5: sums %.4f vs %.4f, worst pixel difference %.5f\n", sum[0], sum[1], worst);
    CHECK(sum[0] > 1, "the groove gathers light: %g", sum[0]);
    CHECK(worst == 0, "E_near depends on the receiver's F0: worst difference %g", worst);
    for (k = 0; k < 2; k++) result_free(&r[k]);
    gbuf_free(&g);
}

/* A scene without a gi radius gets one sized to it: its bounds' diagonal
 * without an environment, the diagonal / TG_RADIUS_ENV_DIVISOR with one
 * for AO alone (TG_RADIUS_LIGHT_DIVISOR for colour: test_request.c);
 * the scene's gi line or the request still decides when they give one. */
TEST(gather_radius_sized_to_the_scene)
{
    static const char *base =
        "camera pos 1 2 -5 target 1 2 0\n"
        "material m albedo 0.5 0.5 0.5\n"
        "box min -1 0 0  max 2 4 12  material m\n"   /* diagonal 13 */
        "light point pos 1 2 -1 color 1 1 1\n";
    static const char *tails[4] = { "", "env uniform 1 1 1\n", "gi radius 2\n", "" };
    double want[4] = { 13.0, 13.0 / TG_RADIUS_ENV_DIVISOR, 2.0, 5.0 };
    static unsigned char mem[1 << 20];
    int k;
    for (k = 0; k < 4; k++) {
        char text[1024];
        tg_arena arena;
        tg_scene *sc = NULL;
        tg_error err;
        tg_request q;
        tg_plan plan;
        snprintf(text, sizeof text, "%s%s", base, tails[k]);
        tg_arena_init(&arena, mem, sizeof mem);
        CHECK(tg_scene_parse(text, strlen(text), "radius.scene", NULL, &arena, &sc, &err) == TG_OK, "scene %d parses", k);
        if (!sc) continue;
        tg_request_defaults(&q);
        q.width = 32; q.height = 24;
        q.aovs = 1u << TG_AOV_AO;   /* AO alone */
        if (k == 3) q.radius = TG_R(5.0f);
        CHECK(tg_plan_make(&plan, sc, &q, &err) == TG_OK, "case %d plans", k);
        printf("  gather radius, case %d: %.4f (want %.4f)\n", k, check_d(plan.request.radius), want[k]);
        CHECK(fabs(check_d(plan.request.radius) - want[k]) < 1e-3 * want[k] + 1e-4, "case %d: radius %g, want %g",
              k, check_d(plan.request.radius), want[k]);
    }
}

/* The kernel's slice integral Q(theta) = (theta - sin cos) / 2
 * (tgi_hbil_slice_q) against libm over c = cos(theta) in [-1, 1]: every
 * Q16.16 value in fixed, a 2e5-point grid in float.  Bounds: 1e-6 (float:
 * the fit's 6e-8 and a few float roundings of pi/2) and 4 ulps = 6.1e-5
 * (fixed: the coefficients and the Horner steps each round to 2^-17). */
TEST(hbil_slice_q_accuracy)
{
    double worst = 0, at = 0;
    long i, n = TG_FIXED ? 65536 : 100000;
    for (i = -n; i <= n; i++) {
        tg_real c = TG_FIXED ? (tg_real)i : tg_from_float((float)i / (float)n);
        double cd = check_d(c), q = (acos(cd) - cd * sqrt(1 - cd * cd)) / 2;
        double e = fabs(check_d(tgi_hbil_slice_q(c)) - q);
        if (e > worst) { worst = e; at = cd; }
    }
    printf("  measured hbil_slice_q max |error| %.3g at %.6f\n", worst, at);
    CHECK(worst <= (TG_FIXED ? 4.0 / 65536.0 : 1e-6), "Q error %g at %g", worst, at);
}

/* The slice integral's square root (gi/hbil.c unit_sqrt) over x in [0,
 * 1]: in Q16.16 every value gives tg_sqrt's, exactly rounded (the inline
 * line-table form must not change a bit); in float a 2e5-point grid within
 * 2 float ulps (2.4e-7 relative) of libm. */
TEST(hbil_unit_sqrt_exact)
{
    long i, n = TG_FIXED ? 65536 : 200000, bad = 0;
    double worst = 0;
    for (i = 0; i <= n; i++) {
        tg_real x = TG_FIXED ? (tg_real)i : tg_from_float((float)i / (float)n), s = tgi_hbil_unit_sqrt(x);
#if TG_FIXED
        if (s != tg_sqrt(x)) {
            if (bad < 5) printf("  unit_sqrt raw %ld: %ld, tg_sqrt %ld\n", i, (long)s, (long)tg_sqrt(x));
            bad++;
        }
#else
        double w = sqrt(check_d(x)), e = w > 0 ? fabs(check_d(s) - w) / w : fabs(check_d(s));
        if (e > worst) worst = e;
#endif
    }
    printf("  unit_sqrt: %ld of %ld differ from tg_sqrt, float max rel. error %.3g\n", bad, n + 1, worst);
    CHECK(bad == 0, "%ld values differ", bad);
    CHECK(worst <= 2.4e-7, "rel. error %g", worst);
}

#if !TG_WIDE_STORAGE && !TG_NO_COLOR
/* The near field's weight t = smoothstep(a, b, -n_s.w_i) (HBIL sec. 3.4):
 * the kernel's tests that answer t = 0 or 1 without normalising the
 * sender's stored normal (gi/hbil.c rejection_weight) give the weights of
 * the unit normal bit for bit.  The 8-bit and the 11-bit octahedral words
 * at a stride, seen from a tilted camera along directions whose
 * -n_s.w_i lies at the ramp's ends, 2^-20 .. 2^-9 (the tests' margin is
 * 2^-10) and 0.01 to either side of them, and at random; the paper's ramp
 * (0, 0.2) and one 2^-12 wide off zero, steep enough that a Q16.16 step
 * changes t.  Without the margin (HBIL_REJECT_MARGIN 0) the weights near
 * the ends differ in both builds. */
TEST(rejection_tests_keep_the_weights)
{
    static const double offsets[] = { 0, 1.0 / 1048576, 1.0 / 65536, 1.0 / 4096, 1.0 / 1024, 1.0 / 512, 0.01 };
    static const double ramps[2][2] = { { 0.0, 0.2 }, { 0.3, 0.3 + 1.0 / 4096 } };
    static const int widths[2] = { 8, 11 };
    tgi_view view;
    double r[3], u[3], f[3];
    unsigned seed = 12345u;
    long count = 0, bad = 0, at_ends = 0;
    int k, ramp;
    tgi_view_make(&view, tv(1.0, 2.0, 3.0), tv(-0.3, 0.1, -0.7), tv(0.1, 1.0, 0.2), tg_from_float((float)(60 * DEG)),
                  TG_R(0.05f), TG_R(1000.0f), 64, 48);
    vd(view.right, r); vd(view.up, u); vd(view.forward, f);
    for (ramp = 0; ramp < 2; ramp++) {
        const tg_real a = tg_from_float((float)ramps[ramp][0]), b = tg_from_float((float)ramps[ramp][1]);
        for (k = 0; k < 2; k++) {
            const int bits = widths[k];
            const uint32_t words = 1u << (2 * bits), stride = bits > 8 ? 509u : 3u;
            uint32_t w;
            for (w = 0; w < words; w += stride) {
                tgi_oct_dir n = tgi_oct_fold(w, bits);
                double ns[3] = { n.x, n.y, n.z }, e[3] = { 1, 0, 0 }, p[3], q[3];
                int end, o, sign;
                norm3(ns);
                if (fabs(ns[0]) > 0.5) { e[0] = 0; e[1] = 1; }
                cross3(ns, e, p); norm3(p);                       /* p, q: perpendicular to n_s */
                cross3(ns, p, q);
                for (end = 0; end < 3; end++)
                    for (o = 0; o < (int)(sizeof offsets / sizeof offsets[0]); o++)
                        for (sign = -1; sign <= 1; sign += 2) {
                            /* w_i with -n_s.w_i = tt, then dir = w_i in view space */
                            double tt = end < 2 ? ramps[ramp][end] + sign * offsets[o] : 2 * check_rnd(&seed) - 1;
                            double phi = 2 * CHECK_PI * check_rnd(&seed), s = sqrt(1 - tt * tt), wi[3];
                            tg_vec3 dir;
                            tg_real t1, t0;
                            int j;
                            for (j = 0; j < 3; j++) wi[j] = -tt * ns[j] + s * (cos(phi) * p[j] + sin(phi) * q[j]);
                            dir = tv(dot3(wi, r), dot3(wi, u), dot3(wi, f));
                            t1 = tgi_hbil_rejection_weight(&view, a, b, n, dir, 1);
                            t0 = tgi_hbil_rejection_weight(&view, a, b, n, dir, 0);
                            count++;
                            at_ends += end < 2 && offsets[o] < 0.001;
                            if (memcmp(&t1, &t0, sizeof t1) && bad++ < 5)
                                fprintf(stderr, "2x%d word 0x%x, -n.w %.9f: t %.9g with the tests, %.9g without\n", bits,
                                        (unsigned)w, tt, check_exact(t1), check_exact(t0));
                        }
            }
        }
    }
    printf("  rejection weights: %ld directions (%ld within 2^-10 of a ramp's end), %ld differ\n", count, at_ends, bad);
    CHECK(bad == 0 && count > 1000000, "%ld of %ld weights differ from the unit normal's", bad, count);
}
#endif

#if !TG_WIDE_STORAGE && !TG_NO_COLOR
/* The kernel's smoothstep of the ramp (gi/hbil.c ramp_smoothstep, Q16.16
 * without tg_smoothstep's tests, its divisor b - a set once a call) is
 * tg_smoothstep(a, b, t) bit for bit: a camera on the world axes and the
 * sender's normal (0, 0, q) make -n_s.w_i the product -n_s.z dir.z, every
 * t from 64 steps below a to 64 above b for the paper's ramp (0, 0.2), the
 * test above's (0.3, 0.3 + 2^-12) and a few within [-2, 2]; at 4099 points
 * for 300 random ramps within [-2, 2] and for ramps whose b - a does not fit
 * (tg_smoothstep's path), a = b and a > b. */
TEST(ramp_smoothstep_is_tg_smoothstep)
{
    static const float ramps[][2] = { { 0.0f, 0.2f }, { 0.3f, 0.3f + 1.0f / 4096 }, { -2.0f, 2.0f }, { -1.0f, 1.0f },
                                      { -0.5f, 0.0f }, { 1.9f, 2.0f }, { -2.0f, -1.999f }, { 0.0f, 1.0f / 65536 },
                                      { -1.0f, 32767.0f }, { -30000.0f, 30000.0f }, { -32768.0f, 32767.0f },
                                      { 0.1f, 0.1f }, { 0.2f, 0.0f } };
    const int nfixed = (int)(sizeof ramps / sizeof ramps[0]);
#if TG_FIXED
    const tg_real ulp = 1;                      /* one Q16.16 step */
#else
    const tg_real ulp = 1.0f / 65536;
#endif
    tgi_view view;
    unsigned seed = 777u;
    long count = 0, bad = 0;
    int k, bits;
    memset(&view, 0, sizeof view);
    view.right = tg_v3(TG_ONE, 0, 0);
    view.up = tg_v3(0, TG_ONE, 0);
    view.forward = tg_v3(0, 0, TG_ONE);
    for (bits = 8; bits <= 11; bits += 3) {
        const uint32_t h = (1u << (bits - 1)) - 1;     /* x = y = 0 */
        const tgi_oct_dir n = tgi_oct_fold(h | h << bits, bits);
        const tg_vec3 ns = tgi_oct_unit(n);
        CHECK(n.x == 0 && n.y == 0 && n.z > 0 && ns.x == 0 && ns.y == 0 && ns.z > 0, "normal (%d %d %d)", n.x, n.y, n.z);
        for (k = 0; k < nfixed + 300; k++) {
            tg_real a, b, lo, hi, x, stepx;
            if (k < nfixed) {
                a = tg_from_float(ramps[k][0]);
                b = tg_from_float(ramps[k][1]);
            } else {
                a = tg_from_float((float)(4 * check_rnd(&seed) - 2));
                b = tg_from_float((float)(4 * check_rnd(&seed) - 2));
                if (b < a) { tg_real s = a; a = b; b = s; }
                if (b == a) b = tg_add(a, ulp);
            }
            lo = tg_sub(a < b ? a : b, TG_R(64.0f / 65536)); hi = tg_add(a < b ? b : a, TG_R(64.0f / 65536));
            if (tg_sub(hi, lo) < TG_R(2.0f) && hi < TG_R(2.5f) && lo > TG_R(-2.5f) && k < nfixed)
                stepx = ulp;                             /* every t (Q16.16) */
            else
                stepx = tg_max(ulp, tg_div(tg_sub(hi, lo), TG_R(4096.0f)));
            for (x = lo;; x = tg_add(x, stepx)) {
                const tg_vec3 dir = tg_v3(0, 0, tg_neg(x));
                const tg_real t = tg_neg(tg_mul(ns.z, dir.z));
                const tg_real want = tg_smoothstep(a, b, t);
                const tg_real got = tgi_hbil_rejection_weight(&view, a, b, n, dir, 0);
                count++;
                if (memcmp(&want, &got, sizeof want) && bad++ < 5)
                    fprintf(stderr, "ramp (%.9g, %.9g), t %.9g: %.9g, tg_smoothstep %.9g\n", check_exact(a), check_exact(b),
                            check_exact(t), check_exact(got), check_exact(want));
                if (x >= hi || tg_add(x, stepx) == x) break;
            }
        }
    }
    printf("  ramp smoothstep: %ld weights, %ld differ from tg_smoothstep\n", count, bad);
    CHECK(bad == 0 && count > 500000, "%ld of %ld weights differ from tg_smoothstep", bad, count);
}
#endif

#if TG_FIXED
/* The near horizon's tangent-plane test in one 64-bit compare (resample.c
 * near_plane_start) gives the saturating expression's answer: random
 * pixels (plane terms from a few units to the whole range, where products
 * and sums saturate), samples and depths, and the compare's edges (z i at
 * T 2^16 + 2^15 - 1, where tg_mul's rounding puts it, and one either side
 * (the tie, past it, was under with ties rounded away from zero), for T of either sign,
 * near and at the range's ends, above = TG_REAL_MAX). */
static tg_real plane_term(unsigned *seed)
{
    double r = 2 * check_rnd(seed) - 1;
    switch ((int)(check_rnd(seed) * 4)) {
    case 0: return tg_from_float((float)(r * 4));
    case 1: return tg_from_float((float)(r * 0.01));
    case 2: return (tg_real)(r * 2147483647.0);
    default: return check_rnd(seed) < 0.5 ? TG_REAL_MAX : TG_REAL_MIN;
    }
}
TEST(near_plane_test_is_the_saturating_one)
{
    unsigned seed = 12345;
    long count = 0, fast = 0, edges = 0, bad = 0, i;
    static const tg_real ts[] = { 0, 1, -1, 2, -2, 65535, -65536, 1000000, -1000000, TG_REAL_MAX - 1, TG_REAL_MIN,
                                  TG_REAL_MIN + 1, TG_REAL_MAX - 2 };
    for (i = 0; i < 2000000; i++) {
        const int reach = check_rnd(&seed) < 0.5 ? 16 : 140;
        const tg_real nr = plane_term(&seed), nax = plane_term(&seed), nay = plane_term(&seed);
        const tg_real np = plane_term(&seed), above = check_rnd(&seed) < 0.01 ? TG_REAL_MAX : plane_term(&seed);
        const tg_real z = (tg_real)(check_rnd(&seed) * (check_rnd(&seed) < 0.5 ? 2147483647.0 : 65536.0 * 64));
        const int ox = (int)(check_rnd(&seed) * (2 * reach + 1)) - reach, oy = (int)(check_rnd(&seed) * (2 * reach + 1)) - reach;
        const int a = tgi_near_under_plane(nr, nax, nay, np, above, reach, z, ox, oy, 1);
        const int b = tgi_near_under_plane(nr, nax, nay, np, above, reach, z, ox, oy, 0);
        count++;
        fast += (int64_t)tg_abs(nr) + (int64_t)reach * ((int64_t)tg_abs(nax) + tg_abs(nay)) <= TG_REAL_MAX;
        if (a != b && bad++ < 5)
            fprintf(stderr, "nr %d nax %d nay %d np %d above %d z %d (%d, %d): %d fast, %d saturating\n", (int)nr, (int)nax,
                    (int)nay, (int)np, (int)above, (int)z, ox, oy, a, b);
    }
    /* i = nr = +-2^-16 (nax = nay = 0): z i = +-z; np = 0, so T = above */
    for (i = 0; i < (long)(sizeof ts / sizeof ts[0]); i++) {
        const int64_t t = ts[i], edge = t * 65536 + 32767;
        int sign, d;
        for (sign = -1; sign <= 1; sign += 2)
            for (d = -1; d <= 1; d++) {
                const int64_t zz = sign * (edge + d);
                int a, b;
                if (zz < 0 || zz > TG_REAL_MAX) continue;
                a = tgi_near_under_plane(sign, 0, 0, 0, (tg_real)t, 16, (tg_real)zz, 3, -2, 1);
                b = tgi_near_under_plane(sign, 0, 0, 0, (tg_real)t, 16, (tg_real)zz, 3, -2, 0);
                edges++;
                if (a != b && bad++ < 10)
                    fprintf(stderr, "edge: T %ld, z i %ld: %d fast, %d saturating\n", (long)t, (long)(sign * zz), a, b);
            }
    }
    printf("  tangent-plane tests: %ld random (%ld by the compare), %ld at its edges, %ld differ\n", count, fast, edges, bad);
    CHECK(bad == 0 && fast > count / 8 && fast < count && edges >= 15, "%ld of %ld tests differ (%ld by the compare)", bad,
          count + edges, fast);
}
#endif

/* Fixed and float agree: the float run writes its AO next to its binary, the
 * fixed run (tests/run.sh runs float first) reads and compares.  Run alone,
 * the fixed test finds no file: it then runs the float binary beside it
 * with --groove-ao (that test alone) to write it, as tests/run.sh's order
 * would have (tests/hbil_alone_test.sh). */
static const char *argv0 = "";
TEST(fixed_and_float_agree)
{
    scene s;
    gbuf g;
    result r;
    size_t n;
    char path[1024];
    const char *slash = strrchr(argv0, '/');
    int len = slash ? (int)(slash - argv0) : 0;
    groove_scene(&s);
    groove_view(&g, &s, 96, 72);
    n = (size_t)g.w * g.h;
    result_alloc(&r, n);
    run_interleaved(&g, 1.0, &r);
#if TG_FIXED
    snprintf(path, sizeof path, "%.*s/../../float/tests/hbil_groove_ao.f32", len, argv0);
    {
        FILE *fp = fopen(path, "rb");
        if (!fp && !strchr(argv0, '\'')) {   /* alone: the float binary writes it */
            char cmd[1100];
            snprintf(cmd, sizeof cmd, "'%.*s/../../float/tests/test_hbil' --groove-ao >/dev/null", len, argv0);
            if (system(cmd) == 0) fp = fopen(path, "rb");
        }
        float *ref = malloc(n * sizeof(float));
        size_t i, c = 0;
        double e = 0;
        CHECK(fp != NULL, "missing %s (run the float test first)", path);
        if (fp) {
            CHECK(fread(ref, sizeof(float), n, fp) == n, "short file %s", path);
            fclose(fp);
            for (i = 0; i < n; i++) if (!g.sky[i]) { double d = check_d(r.ao[i]) - (double)ref[i]; e += d * d; c++; }
            e = c ? sqrt(e / c) : 0;
            printf("  fixed vs float AO RMSE on the groove: %.5f\n", e);
            CHECK(e < 0.02, "RMSE %g", e);
        }
        free(ref);
    }
#else
    snprintf(path, sizeof path, "%.*s/hbil_groove_ao.f32", len, argv0);
    {
        FILE *fp = fopen(path, "wb");
        size_t i;
        CHECK(fp != NULL, "cannot write %s", path);
        if (fp) { for (i = 0; i < n; i++) { float v = tg_to_float(r.ao[i]); fwrite(&v, sizeof v, 1, fp); } fclose(fp); }
    }
#endif
    result_free(&r);
    gbuf_free(&g);
}

/* The 16 sub-images x TG_HBIL_ROTATIONS frames stratify the slice angles
 * of [0, pi / S) and the march's start offsets of [0, 1) evenly: sorted,
 * the k-th is the centre of the k-th of 16 R equal strata (R rotations), so
 * the frames a temporal accumulation blends see every direction and every
 * offset once (the bands a fixed offset leaves the step's length apart go);
 * within 5% of a stratum: Q16.16 rounds pi / (16 S) (without the rotations
 * the sorted angles stand up to 3.5 strata from their centres). */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

TEST(rotations_stratify_slice_angles_and_march_offsets)
{
    enum { N = 16 * TG_HBIL_ROTATIONS };
    double phi[N], off[N], worst_phi = 0, worst_off = 0;
    int slices, i, j, rot, k;
    for (slices = 1; slices <= 3; slices++) {
        double stratum = 3.14159265358979 / slices / N;
        k = 0;
        for (rot = 0; rot < TG_HBIL_ROTATIONS; rot++)
            for (j = 0; j < 4; j++)
                for (i = 0; i < 4; i++, k++) {
                    phi[k] = check_d(tgi_hbil_slice_phi0(i, j, slices, rot));
                    off[k] = check_d(tgi_hbil_step_jitter(i, j, rot));
                }
        qsort(phi, N, sizeof phi[0], cmp_double);
        qsort(off, N, sizeof off[0], cmp_double);
        for (k = 0; k < N; k++) {
            worst_phi = fmax(worst_phi, fabs(phi[k] - (k + 0.5) * stratum) / stratum);
            worst_off = fmax(worst_off, fabs(off[k] - (k + 0.5) / N) * N);
        }
    }
    printf("  rotations: worst distance from the stratum centre, angle %.4f, offset %.4f (of a stratum)\n",
           worst_phi, worst_off);
    CHECK(worst_phi < 0.05, "slice angles not stratified: %g of a stratum", worst_phi);
    CHECK(worst_off < 0.05, "march offsets not stratified: %g of a stratum", worst_off);
}

/* Neighbouring 4x4 blocks take the march offsets in different sub-images
 * (no stripes of blocks sampling at the same distances), and each block
 * still takes all 16 offset strata of its rotation. */
TEST(blocks_decorrelate_march_offsets)
{
    enum { B = 32 };
    int rot, bx, by, i, j, k, same = 0, pairs = 0, unstratified = 0, repeats = 0;
    for (rot = 0; rot < TG_HBIL_ROTATIONS; rot++)
        for (by = 0; by < B; by++)
            for (bx = 0; bx < B; bx++) {
                int seen[16] = { 0 };
                for (j = 0; j < 4; j++)
                    for (i = 0; i < 4; i++) {
                        double sub = check_d(tgi_hbil_step_jitter(i, j, rot));
                        double off = check_d(tgi_hbil_block_jitter(tgi_hbil_step_jitter(i, j, rot), bx, by, rot));
                        double right = check_d(tgi_hbil_block_jitter(tgi_hbil_step_jitter(i, j, rot), bx + 1, by, rot));
                        double below = check_d(tgi_hbil_block_jitter(tgi_hbil_step_jitter(i, j, rot), bx, by + 1, rot));
                        double shift = (off - sub) * 16;
                        CHECK(off >= 0 && off < 1, "block (%d, %d): offset %g outside [0, 1)", bx, by, off);
                        if (shift < 0) shift += 16;
                        CHECK(fabs(shift - floor(shift + 0.5)) < 1e-4, "block shift %g not whole sixteenths", shift);
                        k = (int)floor(off * 16);
                        if (k >= 0 && k < 16) seen[k]++;
                        same += fabs(off - right) < 1e-6;
                        same += fabs(off - below) < 1e-6;
                        pairs += 2;
                    }
                for (k = 0; k < 16; k++) unstratified += seen[k] != 1;
            }
    /* over the rotations every pixel's offset takes 8 different strata */
    for (by = 0; by < B; by++)
        for (bx = 0; bx < B; bx++)
            for (j = 0; j < 4; j++)
                for (i = 0; i < 4; i++) {
                    int seen[16] = { 0 };
                    for (rot = 0; rot < TG_HBIL_ROTATIONS; rot++) {
                        k = (int)floor(check_d(tgi_hbil_block_jitter(tgi_hbil_step_jitter(i, j, rot), bx, by, rot)) * 16);
                        if (k >= 0 && k < 16 && seen[k]++) repeats++;
                    }
                }
    printf("  blocks: %.3f of neighbouring blocks share a sub-image's offset (1/16 = 0.0625 by chance), "
           "%d unstratified blocks, %d strata repeated over the rotations\n", (double)same / pairs, unstratified, repeats);
    CHECK(unstratified == 0, "%d blocks do not take each of the 16 offset strata once", unstratified);
    CHECK(repeats == 0, "%d times a pixel's offset fell in a stratum it took in another rotation", repeats);
    CHECK((double)same / pairs < 0.1, "neighbouring blocks share offsets: %.3f", (double)same / pairs);
}

/* A floor in front of a wall 1.5 high whose top edge stands against the
 * sky, the radius (10) spanning the scene, at 320x240 through the 16
 * strided sub-images with the kernel's defaults, the AO averaged over the
 * TG_HBIL_ROTATIONS march offsets (as the temporal accumulation does):
 * the floor's AO within 3 of the wall against the ray-traced AO of the
 * same quads with the same radius.  Toward the wall the horizon is its
 * top edge, the last pixel before the sky; the march reaches it in steps
 * of several pixels.  Failed before the march took the pixels after the
 * sample that set the horizon one by one and stopped capping its reach at
 * 128 pixels: bias +0.021, rmse 0.029 (the AO too bright); measured
 * after: +0.009, 0.020, in both number types. */
/* The interleaved kernel as the frame runs it on the image k (the
 * full-resolution view or its half-resolution copy): each of the 16
 * sub-images a strided view with its own slice angles and march offsets in
 * frame rotation rot, the results into *all (indexed like k), no near field
 * and no cap on the march but the screen. */
/* The frame's interleaved pass on the image k (tgi_pass_hbil_interleaved):
 * its 16 strided sub-images; fine: the image the horizons are refined on
 * (gi/hbil.c refine_fine), NULL for none; samples a side (0: the
 * default). */
static void kernel_sub_images_on(const tgi_gview *k, const tgi_gview *fine, double radius, int samples, int rot,
                                 tgi_gresult *all)
{
    int ii, jj;
    for (jj = 0; jj < 4; jj++)
        for (ii = 0; ii < 4; ii++) {
            tgi_hbil_params p;
            tgi_gview sub;
            tgi_gresult o = tgi_gresult_from(all, tgi_gv_index(k, ii, jj));
            tgi_gview_strided_sub(&sub, k, ii, jj);
            if (sub.width == 0 || sub.height == 0) continue;
            params_for(&p, radius);
            if (samples > 0) p.samples = samples;
            p.rotation = rot;
            p.fine = fine;
            p.pattern_scale = k->step;   /* as tgi_pass_hbil_interleaved */
            tgi_hbil_rows(&p, &sub, NULL, &o, 0, sub.height);
        }
}

/* A floor before a wall 1.5 high whose top is a silhouette against the
 * sky, radius 10: the floor's horizon toward the wall is the wall's last
 * pixel.  The interleaved kernel's AO (the 8 frame rotations averaged as
 * the frame's accumulation does) on the floor pixels within 3 of the wall
 * against the ray-traced AO: RMSE, bias and the worst pixel.  refine: the
 * horizons refined on the full-resolution pixels (gi/hbil.c refine_fine). */
/* A floor (y = 0, x >= 0) before a wall `height` high standing at x = 0. */
static void floor_and_wall(scene *s, double height)
{
    static const quad floor_q = { { 0, 0, -20 }, { 20, 0, 0 }, { 0, 0, 40 }, 1 };
    quad wall_q = { { 0, 0, -20 }, { 0, 0, 0 }, { 0, 0, 40 }, 1 };
    wall_q.e1[1] = height;
    s->n = 2; s->q[0] = floor_q; s->q[1] = wall_q;
}

/* floor_and_wall with a top `depth` deep on the wall: a box's front face
 * and top (0: the wall alone). */
static void floor_and_box(scene *s, double height, double depth)
{
    quad top_q = { { 0, 0, -20 }, { 0, 0, 0 }, { 0, 0, 40 }, 1 };
    floor_and_wall(s, height);
    if (depth <= 0) return;
    top_q.o[1] = height;
    top_q.e1[0] = -depth;
    s->q[s->n++] = top_q;
}

/* AO ao[] (one value a pixel of g) against the ray-traced AO of scene s at
 * radius `radius`, over every `stride`-th pixel of face `face` (normal nrm)
 * whose coordinate `axis` of the hit point lies between x0 and x1 and
 * within 3 of the middle: RMSE, bias, worst pixel and the count. */
static void face_ao_error(const gbuf *g, const scene *s, const double *ao, double radius, int face, const double *nrm,
                          int axis, double x0, double x1, int stride, double *rmse_out, double *bias_out,
                          double *worst_out, int *cnt_out)
{
    double se = 0, bias = 0, worst = 0;
    size_t i, n = (size_t)g->w * g->h;
    int cnt = 0;
    for (i = 0; i < n; i += (size_t)stride) {
        double pos[3], d;
        pos[0] = g->px[i]; pos[1] = g->py[i]; pos[2] = g->pz[i];
        if (g->face[i] != face || pos[axis] < x0 || pos[axis] > x1 || fabs(g->pz[i]) > 3) continue;
        d = ao[i] - reference_ao(s, pos, nrm, radius);
        se += d * d; bias += d; cnt++;
        worst = fmax(worst, fabs(d));
    }
    *rmse_out = cnt ? sqrt(se / cnt) : 0;
    *bias_out = cnt ? bias / cnt : 0;
    *worst_out = worst;
    *cnt_out = cnt;
}

/* The floor's pixels (face 0) between x0 and x1 from the wall. */
static void floor_ao_error(const gbuf *g, const scene *s, const double *ao, double radius, double x0, double x1,
                           int stride, double *rmse_out, double *bias_out, double *worst_out, int *cnt_out)
{
    static const double up[3] = { 0, 1, 0 };
    face_ao_error(g, s, ao, radius, 0, up, 0, x0, x1, stride, rmse_out, bias_out, worst_out, cnt_out);
}

/* The interleaved kernel's AO of g at radius `radius` as the frame's pass
 * computes it (refine: the horizons refined on g's own pixels, gi/hbil.c
 * refine_fine; samples a side, 0: the default), the 8 frame rotations
 * averaged as the frame's accumulation does, one value a pixel into sum. */
static void interleaved_accumulated(const gbuf *g, double radius, int refine, int samples, double *sum)
{
    size_t i, n = (size_t)g->w * g->h;
    tgi_gbuffer gb;
    tgi_gview full;
    result r;
    int rot;
    result_alloc(&r, n);
    view_of(g, &gb, &full);
    memset(sum, 0, n * sizeof(double));
    for (rot = 0; rot < TG_HBIL_ROTATIONS; rot++) {
        tgi_gresult all = results_of(n, 0);
        kernel_sub_images_on(&full, refine ? &full : NULL, radius, samples, rot, &all);
        results_read(&all, n, &r);
        for (i = 0; i < n; i++) sum[i] += check_d(r.ao[i]) / TG_HBIL_ROTATIONS;
    }
    sf_gbuffer_free(&gb);
    result_free(&r);
}

/* A floor before a wall `height` high (floor_and_wall), radius 10, seen
 * from (6, 2.2, 0) at w x h: the interleaved kernel's accumulated AO
 * (interleaved_accumulated; samples a side, 0: the default) on the floor
 * pixels x0 to x1 from the wall against the ray-traced AO. */
static void floor_before_wall_error(int w, int h, double height, double depth, int refine, int samples, double x0,
                                    double x1, double *rmse_out, double *bias_out, double *worst_out, int *cnt_out)
{
    double eye[3] = { 6, 2.2, 0 }, target[3] = { 0, 0.5, 0 }, up[3] = { 0, 1, 0 }, *sum;
    const double radius = 10;
    scene s;
    gbuf g;
    floor_and_box(&s, height, depth);
    gbuf_make(&g, &s, w, h, eye, target, up);
    sum = malloc((size_t)g.w * g.h * sizeof(double));
    interleaved_accumulated(&g, radius, refine, samples, sum);
    floor_ao_error(&g, &s, sum, radius, x0, x1, w > 200 ? 7 : 1, rmse_out, bias_out, worst_out, cnt_out);
    gbuf_free(&g);
    free(sum);
}

static void wall_top_error(int w, int h, int refine, double *rmse_out, double *bias_out, double *worst_out, int *cnt_out)
{
    floor_before_wall_error(w, h, 1.5, 0, refine, 0, -1, 3, rmse_out, bias_out, worst_out, cnt_out);
}

TEST(wall_top_sets_the_horizon_at_any_radius)
{
    double rmse, bias, worst;
    int cnt;
    wall_top_error(320, 240, 1, &rmse, &bias, &worst, &cnt);
    printf("  floor before a wall 1.5 high, radius 10, %d pixels: rmse %.4f, bias %+.4f, worst %.3f against ray-traced\n",
           cnt, rmse, bias, worst);
    CHECK(cnt > 300, "floor pixels %d", cnt);
    CHECK(fabs(bias) < 0.014, "bias %+.4f (the AO too bright: horizons missed)", bias);
    CHECK(rmse < 0.025, "rmse %.4f", rmse);
}

/* A radius that spans more image pixels than the march's 3D test once held
 * (150: its square had to fit Q16.16): a floor before a wall 4 high,
 * radius 20, seen by the full-resolution kernel at 320x240, on the floor
 * pixels 3 to 6 from the wall, where the wall stands 300-700 pixels' worth
 * away in 3D at the pixel's depth.  With the old cap every sample past 150
 * was out of the radius: the wall was never seen and the AO there came out
 * +0.1 too bright (measured +0.104); the horizon must find it at any
 * distance the radius allows. */
TEST(full_resolution_radius_beyond_150_pixels)
{
    double eye[3] = { 10, 3, 0 }, target[3] = { 0, 1.5, 0 }, up[3] = { 0, 1, 0 }, *ao, rmse, bias, worst;
    const double radius = 20;
    scene s;
    gbuf g;
    result r;
    size_t i, n;
    int cnt;
    floor_and_wall(&s, 4);
    gbuf_make(&g, &s, 320, 240, eye, target, up);
    n = (size_t)g.w * g.h;
    result_alloc(&r, n);
    run_full(&g, radius, 0, &r);
    ao = malloc(n * sizeof(double));
    for (i = 0; i < n; i++) ao[i] = check_d(r.ao[i]);
    floor_ao_error(&g, &s, ao, radius, 3, 6, 3, &rmse, &bias, &worst, &cnt);
    printf("  floor 3-6 from a wall 4 high, radius 20, 320x240 full resolution, %d pixels: rmse %.4f, bias %+.4f\n",
           cnt, rmse, bias);
    CHECK(cnt > 300, "floor pixels %d", cnt);
    CHECK(fabs(bias) < 0.02, "bias %+.4f (the AO too bright: the wall beyond the march's cap)", bias);
    CHECK(rmse < 0.05, "rmse %.4f", rmse);
    free(ao);
    result_free(&r);
    gbuf_free(&g);
}

/* The same wall at 160x120, where the sub-images' pixels are 4 image
 * pixels apart and the wall's top is 1.5 of them past the last sample on
 * it on average: without the refinement the AO is too bright (measured
 * +0.02 and more); with it the bias is that of the full-resolution march. */
TEST(interleaved_horizon_finds_the_wall_top_pixel)
{
    double rmse[2], bias[2], worst[2];
    int cnt[2], k;
    for (k = 0; k < 2; k++) {
        wall_top_error(160, 120, k, &rmse[k], &bias[k], &worst[k], &cnt[k]);
        printf("  160x120, %s: %d pixels, rmse %.4f, bias %+.4f, worst %.3f against ray-traced\n",
               k ? "refined on the image's pixels" : "sub-image samples only", cnt[k], rmse[k], bias[k], worst[k]);
    }
    CHECK(cnt[1] > 300, "floor pixels %d", cnt[1]);
    CHECK(fabs(bias[1]) < 0.01, "bias %+.4f (the AO too bright: the wall's top missed)", bias[1]);
    CHECK(rmse[1] < 0.025, "rmse %.4f", rmse[1]);
}

/* floor_before_wall_error at 160x120 with the refinement, printed and
 * bounded: at least min_cnt floor pixels, |bias| < max_bias (the AO too
 * bright: `missed` missed), RMSE < max_rmse, the worst pixel < max_worst. */
static void floor_before_check(double height, double depth, int samples, double x0, double x1, int min_cnt,
                               double max_bias, double max_rmse, double max_worst, const char *missed)
{
    double rmse, bias, worst;
    int cnt;
    floor_before_wall_error(160, 120, height, depth, 1, samples, x0, x1, &rmse, &bias, &worst, &cnt);
    printf("  floor %.2f-%.2f before a wall %.2f high, top %.1f deep, radius 10, %d samples a side, 160x120, %d pixels: "
           "rmse %.4f, bias %+.4f, worst %.3f against ray-traced\n", x0, x1, height, depth,
           samples > 0 ? samples : TG_DEFAULT_SAMPLES, cnt, rmse, bias, worst);
    CHECK(cnt > min_cnt, "floor pixels %d", cnt);
    CHECK(fabs(bias) < max_bias, "bias %+.4f (the AO too bright: %s missed)", bias, missed);
    CHECK(rmse < max_rmse, "rmse %.4f", rmse);
    CHECK(worst < max_worst, "worst pixel %.3f", worst);
}

/* A floor before a low step (a wall 0.25 high at x = 0, nothing behind
 * it), radius 10 (a long reach, gi/hbil.c refine_fine), 4 samples a side
 * at 160x120: the march's step m is then several sub-image pixels, and
 * for the floor within 0.8 of the step its top, the horizon toward it,
 * lies between the pixel and the side's first sample, m - o sub-image
 * pixels away (o the start's offset).  The fine pixels before the first
 * sub-image pixel and the sub-image pixels after it up to that sample
 * (gi/hbil.c march_near) must find it: with the fine pixels alone the AO
 * there is too bright (measured bias +0.060, rmse 0.069); with march_near
 * +0.014, 0.024 in both number types, as with every fine pixel up to the
 * first sample (refine_fine before march_near: +0.014, 0.024). */
TEST(long_reach_finds_a_step_before_the_first_sample)
{
    floor_before_check(0.25, 0, 4, 0.05, 0.8, 100, 0.02, 0.04, 1, "the step's top before the first sample");
}

/* A floor before a box 0.5 high and 1 deep, radius 10 (a long reach),
 * seen from above its top at 160x120, on the floor pixels 0.05 to 3 from
 * it: toward the box the horizon rises up its front face to the top's
 * edge and falls along the top, so where the sample that set the horizon
 * lies on the top the edge lies before it, within the fine pixels back to
 * the sub-image pixel before (gi/hbil.c refine_fine, fine_climb's climb
 * down).  Measured: every fine pixel of that span (before fine_climb)
 * rmse 0.0108, bias +0.0036, worst 0.063 in float; climbing 0.0109,
 * +0.0036, 0.063 (Q16.16 alike); without the climb down 0.0208, +0.0094,
 * 0.167. */
TEST(box_top_edge_before_the_peak_sample)
{
    floor_before_check(0.5, 1, 0, 0.05, 3, 1000, 0.006, 0.015, 0.1, "the box's edge before the peak's sample");
}

/* A back wall's foot as builtin:columns sees it (14 from the wall, the eye
 * 3 high, 160x120, radius 1.5): the floor at the crease is seen at a
 * grazing angle, its depth changing by about 0.5 a pixel row, so that it
 * crosses the radius within one sub-image pixel of the wall's last rows:
 * their first sample below lies on the floor beyond the radius, and the
 * floor within it is in the fine pixels before that sample (gi/hbil.c
 * refine_fine, hbil_side.beyond).  The interleaved kernel's AO (refined,
 * the 8 rotations averaged) on the wall pixels up to 0.6 above the crease
 * against the ray-traced AO: without those pixels the crease's occlusion
 * was missed (measured bias +0.205, RMSE 0.276, worst 0.50); with them
 * bias +0.016, RMSE 0.086, worst 0.19. */
TEST(interleaved_horizon_finds_the_crease_within_the_radius)
{
    double eye[3] = { 14, 3, -9 }, target[3] = { 0, 1.5, 0 }, up[3] = { 0, 1, 0 }, *sum;
    const double radius = 1.5, wall_n[3] = { 1, 0, 0 };
    double rmse, bias, worst;
    int cnt;
    scene s;
    gbuf g;
    floor_and_wall(&s, 6);
    gbuf_make(&g, &s, 160, 120, eye, target, up);
    sum = malloc((size_t)g.w * g.h * sizeof(double));
    interleaved_accumulated(&g, radius, 1, 0, sum);
    face_ao_error(&g, &s, sum, radius, 1, wall_n, 1, 0, 0.6, 1, &rmse, &bias, &worst, &cnt);
    printf("  wall 0-0.6 above the crease, radius 1.5, 160x120 interleaved, %d pixels: rmse %.4f, bias %+.4f, worst %.3f\n",
           cnt, rmse, bias, worst);
    CHECK(cnt > 30, "wall pixels %d", cnt);
    CHECK(bias < 0.05, "bias %+.4f (the AO too bright: the floor within the radius missed)", bias);
    CHECK(rmse < 0.12, "rmse %.4f", rmse);
    gbuf_free(&g);
    free(sum);
}

/* --gi-quarter's contact shadow: a floor at the foot of a wall 0.4 high,
 * 160x120, the kernel on the half-resolution copy (its 16 sub-images, the 8
 * frame rotations averaged as the frame's accumulation does) and brought
 * up by tgi_upsample_pixel; the floor pixels within 0.6 of the wall, where
 * the half-res samples lie 8 full-res pixels apart and the wall fills a few
 * pixels of the horizon, against the ray-traced AO.  The upsampled AO alone
 * misses the wall there (too bright); the full-resolution near horizon
 * (TG_QUARTER_NEAR_REACH) finds it. */
/* The near horizon's lower bound (tgi_near_horizon_bound), by which the
 * upsample skips the near horizon's integrals where it cannot cap the
 * upsampled AO: over random normals facing the eye, slices and horizons,
 * never above the AO the integrals give (ao.h's slice frame and arcs, the
 * slices weighted by their projected normal's length, as resample.c's
 * near_horizon_ao), by less than a quarter of the margin resample.c keeps
 * (1/64); 1 with no horizon; and within 0.5 of it in most cases (random
 * horizons, most of them far higher than a surface's). */
TEST(near_horizon_bound_stays_below_the_integral)
{
    unsigned seed = 12345u;
    int t, held = 0, close = 0, trials = 20000;
    double worst = -2;
    for (t = 0; t < trials; t++) {
        double v[3], nrm[3], a, lv, ln, vis = 0, open = 0, exact, bound;
        tg_real c1[2], c0[2], sdx, sdy;
        tg_vec3 nv, vd;
        int k;
        for (k = 0; k < 3; k++) { seed = seed * 1103515245u + 12345u; v[k] = (seed >> 8) / 16777216.0 * 2 - 1; }
        v[2] = -0.5 - fabs(v[2]);                                /* toward the eye: the view looks along +z */
        for (k = 0; k < 3; k++) { seed = seed * 1103515245u + 12345u; nrm[k] = (seed >> 8) / 16777216.0 * 2 - 1; }
        lv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        ln = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        if (ln < 0.1) continue;
        if ((nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2]) / (ln * lv) < 0.05) {   /* face the eye */
            for (k = 0; k < 3; k++) nrm[k] = -nrm[k];
            if ((nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2]) / (ln * lv) < 0.05) continue;
        }
        vd = tg_v3(tg_from_float((float)(v[0] / lv)), tg_from_float((float)(v[1] / lv)), tg_from_float((float)(v[2] / lv)));
        nv = tg_v3(tg_from_float((float)(nrm[0] / ln)), tg_from_float((float)(nrm[1] / ln)), tg_from_float((float)(nrm[2] / ln)));
        seed = seed * 1103515245u + 12345u;
        a = (seed >> 8) / 16777216.0 * 3.14159265358979;
        sdx = tg_from_float((float)cos(a));
        sdy = tg_from_float((float)sin(a));
        for (k = 0; k < 4; k++) {
            tg_real *c = k < 2 ? &c1[k] : &c0[k - 2];
            seed = seed * 1103515245u + 12345u;
            *c = (seed >> 8) % 10 < 3 ? TG_R(-1.0f) : tg_from_float((float)(((seed >> 8) % 100000) / 50000.0 - 1));
        }
        for (k = 0; k < 2; k++) {
            tgi_ao_slice sl;
            tg_real h1, h0, o;
            if (!tgi_ao_slice_frame(nv, vd, k ? tg_neg(sdy) : sdx, k ? sdx : sdy, &sl)) continue;
            o = tg_mul(sl.len, tg_add(sl.cos_g, tg_mul(sl.gamma, sl.sin_g)));
            open += check_d(o);
            if (c1[k] > TG_R(-1.0f) || c0[k] > TG_R(-1.0f)) o = tg_mul(sl.len, tgi_ao_slice_arc(&sl, c1[k], c0[k], &h1, &h0));
            vis += check_d(o);
        }
        bound = check_d(tgi_near_horizon_bound(nv, vd, sdx, sdy, c1, c0));
        if (bound <= -1 || open <= 0) continue;
        exact = vis / open;
        held++;
        if (bound - exact > worst) worst = bound - exact;
        if (exact - bound < 0.5) close++;
    }
    CHECK(held > trials / 2, "the bound holds for %d of %d cases", held, trials);
    CHECK(worst <= 0.015625 / 4, "bound above the integral by %g", worst);
    CHECK(close > held / 2, "bound within 0.5 of the integral in only %d of %d cases", close, held);
    {
        tg_real none[2] = { TG_R(-1.0f), TG_R(-1.0f) };
        CHECK_NEAR(check_d(tgi_near_horizon_bound(tg_v3(0, 0, TG_R(-1.0f)), tg_v3(0, TG_R(0.6f), TG_R(-0.8f)), TG_ONE, 0,
                                                  none, none)), 1.0, 1e-6);
    }
}

/* --gi-quarter's AO of the scene seen in g, one value a pixel into sum:
 * the kernel on the half-resolution copy (its 16 sub-images, the 8 frame
 * rotations averaged as the frame's accumulation does; its horizons refined
 * on the full-resolution pixels as the frame's pass does, fine_full, or on
 * the half-resolution ones) brought up by tgi_upsample_pixel. */
static void quarter_ao(const gbuf *g, double radius, int fine_full, double *sum)
{
    tgi_gbuffer gb, hgb;
    tgi_gview full, half;
    size_t hn;
    int rot, hw, hh, x, y;
    view_of(g, &gb, &full);
    tgi_half_size(g->w, g->h, &hw, &hh);
    hn = (size_t)hw * hh;
    sf_gbuffer_alloc(&hgb, hw, hh, NULL, 0);
    tgi_downsample_rows(&full, &hgb, NULL, NULL, 0, hh);
    tgi_gview_packed(&half, &hgb, 0, hw, hh, 2, 0, 0, &g->view);
    memset(sum, 0, (size_t)g->w * g->h * sizeof *sum);
    for (rot = 0; rot < TG_HBIL_ROTATIONS; rot++) {
        tgi_gresult hres = results_of(hn, 0);
        kernel_sub_images_on(&half, fine_full ? &full : &half, radius, 0, rot, &hres);
        for (y = 0; y < g->h; y++)
            for (x = 0; x < g->w; x++) {
                tgi_gr_value v = tgi_upsample_pixel(&full, &half, &hres, tg_from_float((float)radius), x, y);
                sum[(size_t)y * g->w + x] += check_d(v.ao) / TG_HBIL_ROTATIONS;
            }
        sf_results_free(&hres);
    }
    sf_gbuffer_free(&hgb);
    sf_gbuffer_free(&gb);
}

/* The upsample reads the full view through its strides: the same values
 * from a view whose rows lie 2600 pixels apart in a wider store as from
 * the packed one.  The near horizon's march inside the image reads each
 * sample's index offset from the plan (resample.h TGI_NEAR_DELTAS), kept in
 * 16 bits: the packed rows take it, the wide ones (13 rows of 2600 pixels
 * do not fit) compute each index; both the same samples, so the same bits. */
TEST(quarter_upsample_same_for_any_row_stride)
{
    static const quad floor_q = { { 0, 0, -20 }, { 20, 0, 0 }, { 0, 0, 40 }, 1 };
    static const quad wall_q = { { 0, 0, -20 }, { 0, 0.4, 0 }, { 0, 0, 40 }, 1 };
    double eye[3] = { 6, 2.2, 0 }, target[3] = { 0, 0.3, 0 }, up[3] = { 0, 1, 0 };
    const int wide_w = 2600;
    const double radius = 2;
    scene s;
    gbuf g;
    tgi_gbuffer gb, hgb, wgb;
    tgi_gview full, half, wide;
    tgi_gresult hres;
    int hw, hh, x, y, differ = 0, lower = 0;
    s.n = 2; s.q[0] = floor_q; s.q[1] = wall_q;
    gbuf_make(&g, &s, 160, 120, eye, target, up);
    view_of(&g, &gb, &full);
    tgi_half_size(g.w, g.h, &hw, &hh);
    sf_gbuffer_alloc(&hgb, hw, hh, NULL, 0);
    tgi_downsample_rows(&full, &hgb, NULL, NULL, 0, hh);
    tgi_gview_packed(&half, &hgb, 0, hw, hh, 2, 0, 0, &g.view);
    hres = results_of((size_t)hw * hh, 0);
    kernel_sub_images_on(&half, &half, radius, 0, 0, &hres);
    sf_gbuffer_alloc(&wgb, wide_w, g.h, NULL, 0);
    for (y = 0; y < g.h; y++)
        for (x = 0; x < g.w; x++) tgi_gview_copy_pixel(&wgb, (size_t)y * wide_w + x, &full, tgi_gv_index(&full, x, y));
    tgi_gview_packed(&wide, &wgb, 0, wide_w, g.h, 1, 0, 0, &g.view);
    wide.width = g.w;   /* the image's 160 columns, rows 2600 apart */
    for (y = 0; y < g.h; y++)
        for (x = 0; x < g.w; x++) {
            tgi_gr_value a = tgi_upsample_pixel(&full, &half, &hres, tg_from_float((float)radius), x, y);
            tgi_gr_value b = tgi_upsample_pixel(&wide, &half, &hres, tg_from_float((float)radius), x, y);
            differ += memcmp(&a.ao, &b.ao, sizeof a.ao) != 0 || memcmp(&a.bent, &b.bent, sizeof a.bent) != 0;
            lower += a.ao < TG_ONE;
        }
    printf("  upsample through rows 160 and %d apart: %d of %d pixels differ (%d with AO below 1)\n", wide_w, differ,
           g.w * g.h, lower);
    CHECK(differ == 0, "%d pixels differ", differ);
    CHECK(lower > 1000, "only %d pixels with AO below 1: nothing tested", lower);
    sf_results_free(&hres);
    sf_gbuffer_free(&wgb);
    sf_gbuffer_free(&hgb);
    sf_gbuffer_free(&gb);
    gbuf_free(&g);
}

TEST(quarter_resolution_keeps_the_contact_shadow)
{
    static const quad floor_q = { { 0, 0, -20 }, { 20, 0, 0 }, { 0, 0, 40 }, 1 };
    static const quad wall_q = { { 0, 0, -20 }, { 0, 0.4, 0 }, { 0, 0, 40 }, 1 };
    static const quad top_q = { { -1, 0.4, -20 }, { 1, 0, 0 }, { 0, 0, 40 }, 1 };
    double eye[3] = { 6, 2.2, 0 }, target[3] = { 0, 0.3, 0 }, up[3] = { 0, 1, 0 };
    double nrm[3] = { 0, 1, 0 }, se = 0, bias = 0, rmse, *sum;
    const double radius = 2;
    scene s;
    gbuf g;
    size_t i, n;
    int cnt = 0;
    s.n = 3; s.q[0] = floor_q; s.q[1] = wall_q; s.q[2] = top_q;
    gbuf_make(&g, &s, 160, 120, eye, target, up);
    n = (size_t)g.w * g.h;
    sum = calloc(n, sizeof(double));
    quarter_ao(&g, radius, 0, sum);
    for (i = 0; i < n; i++) {
        double pos[3], d;
        if (g.face[i] != 0 || g.px[i] > 0.6 || fabs(g.pz[i]) > 2) continue;
        pos[0] = g.px[i]; pos[1] = g.py[i]; pos[2] = g.pz[i];
        d = sum[i] - reference_ao(&s, pos, nrm, radius);
        se += d * d; bias += d; cnt++;
    }
    gbuf_free(&g);
    free(sum);
    rmse = sqrt(se / cnt);
    bias /= cnt;
    printf("  floor within 0.6 of a wall 0.4 high, quarter resolution, %d pixels: rmse %.4f, bias %+.4f against ray-traced\n",
           cnt, rmse, bias);
    CHECK(cnt > 100 && fabs(bias) < 0.015 && rmse < 0.04,
          "%d pixels, bias %+.4f, rmse %.4f (bounds 0.015, 0.04: the contact shadow missed, too bright)", cnt, bias, rmse);
}

#if !TG_NO_GI_QUARTER && !TG_NO_BUILTIN_SCENES
/* --gi-quarter where the march is room-wide: builtin:cornell (no gi
 * radius: the radius is its diagonal) at 160x120, 8 frames, against
 * --technique reference, AO RMSE and mean difference over the geometry's
 * pixels (issue 14's goal for --gi-quarter: RMSE <= 0.06, |bias| <= 0.01).
 * The half-res sub-images' samples lie 8 full-resolution pixels apart over
 * the whole screen: a wall that rises within the first of them (where a
 * wall seen nearly edge-on meets the floor at the screen's corners, the
 * back wall beside the tall block) and a horizon that peaks between two
 * samples were missed, the AO too bright: +0.0159 (Q16.16 +0.0155) before
 * gi/hbil.c refine_fine's long reach, +0.0091 (+0.0087) with it. */
TEST(quarter_resolution_in_a_room)
{
    double *ao[2], *depth = NULL, se = 0, bias = 0, rmse;
    const int w = 160, h = 120;
    int k, f, i, cnt = 0;
    for (k = 0; k < 2; k++) {
        rendered r;
        tg_request q = request(w, h, AOVBIT(TG_AOV_AO) | AOVBIT(TG_AOV_DEPTH));
        if (k) q.gi_scale = 2;
        else q.technique = TG_TECH_REFERENCE;
        if (!setup_checked(&r, tg_builtin_scene("cornell"), &q, k ? "cornell, quarter" : "cornell, reference")) {
            if (k) free(ao[0]);
            free(depth);
            return;
        }
        for (f = 0; f < (k ? 8 : 1); f++) CHECK(tg_frame_render(r.frame, f, NULL) == TG_OK, "frame %d renders", f);
        ao[k] = read_aov(&r, TG_AOV_AO);
        if (!k) depth = read_aov(&r, TG_AOV_DEPTH);
        teardown(&r);
    }
    for (i = 0; i < w * h; i++) {
        double d = ao[1][i] - ao[0][i];
        if (depth[i] <= 0) continue;
        se += d * d; bias += d; cnt++;
    }
    rmse = sqrt(se / cnt);
    bias /= cnt;
    printf("  builtin:cornell 160x120, --gi-quarter 8 frames against the reference, %d pixels: rmse %.4f, bias %+.4f\n",
           cnt, rmse, bias);
    CHECK(cnt > 10000, "geometry pixels %d", cnt);
    CHECK(fabs(bias) <= 0.01, "bias %+.4f (the AO too bright: horizons near the pixel or between samples missed)", bias);
    CHECK(rmse <= 0.06, "rmse %.4f", rmse);
    free(ao[0]); free(ao[1]); free(depth);
}
#endif

#if !TG_NO_BUILTIN_SCENES
/* The interleaved kernel's near field against the full-resolution
 * kernel's, builtin:cornell at 160x120, 8 frames each (the temporal
 * accumulation on): both estimate the same integral with the same 16
 * slice directions a 4x4 block, so after the 4x4 filter they differ by
 * noise.  Failed before each pixel of a sub-image took a cell of its own
 * (tgi_hbil_pattern): one cell a sub-image marched its 40x30 pixels along
 * one slice at the same offsets (a step of one of its pixels leaves the
 * march's jitter nothing to shift), and its near field erred alike along
 * the slice: diagonal bands fixed to the screen, RMSE 0.149 of the full-
 * resolution kernel's (both number types); 0.099 after. */
TEST(interleaved_near_field_has_no_bands)
{
    double *near[2], se = 0, rmse;
    const int w = 160, h = 120;
    int k, f, i, n = 3 * w * h;
    for (k = 0; k < 2; k++) {
        rendered r;
        tg_request q = request(w, h, AOVBIT(TG_AOV_NEAR));
        q.interleave = k == 0;
        q.frames = 8;
        if (!setup_checked(&r, tg_builtin_scene("cornell"), &q, k ? "cornell, full resolution" : "cornell")) {
            if (k) free(near[0]);
            return;
        }
        for (f = 0; f < 8; f++) CHECK(tg_frame_render(r.frame, f, NULL) == TG_OK, "frame %d renders", f);
        near[k] = read_aov(&r, TG_AOV_NEAR);
        teardown(&r);
    }
    for (i = 0; i < n; i++) {
        double d = near[0][i] - near[1][i];
        se += d * d;
    }
    rmse = sqrt(se / n);
    printf("  builtin:cornell 160x120, 8 frames: near field interleaved against full resolution, rmse %.4f\n", rmse);
    CHECK(rmse < 0.125, "rmse %.4f (bands along the sub-images' slices)", rmse);
    free(near[0]); free(near[1]);
}
#endif

int main(int argc, char **argv)
{
    argv0 = argv[0];
    if (argc > 1 && strcmp(argv[1], "--groove-ao") == 0) {   /* fixed_and_float_agree's file alone */
        RUN(fixed_and_float_agree);
        return check_summary();
    }
    RUN(open_plane_full_res);
    RUN(open_plane_interleaved);
    RUN(open_plane_long_radius);
    RUN(open_plane_far_edge);
    RUN(groove);
    RUN(cone_is_the_aperture_of_a_cosine_weighted_ao);
    RUN(interleaved_matches_full_res);
    RUN(strided_sub_images_match_packed_copies);
#if !TG_NO_BUILTIN_SCENES
    RUN(interleaved_near_field_has_no_bands);
#endif
    RUN(near_field_complements_ao);
    RUN(near_field_is_irradiance);
    RUN(near_field_of_a_radiance_ramp);
    RUN(gather_radius_sized_to_the_scene);
    RUN(fixed_and_float_agree);
    RUN(hbil_slice_q_accuracy);
    RUN(hbil_unit_sqrt_exact);
#if !TG_WIDE_STORAGE && !TG_NO_COLOR
    RUN(rejection_tests_keep_the_weights);
    RUN(ramp_smoothstep_is_tg_smoothstep);
#endif
    RUN(rotations_stratify_slice_angles_and_march_offsets);
    RUN(blocks_decorrelate_march_offsets);
    RUN(wall_top_sets_the_horizon_at_any_radius);
    RUN(full_resolution_radius_beyond_150_pixels);
    RUN(interleaved_horizon_finds_the_wall_top_pixel);
    RUN(box_top_edge_before_the_peak_sample);
    RUN(long_reach_finds_a_step_before_the_first_sample);
    RUN(interleaved_horizon_finds_the_crease_within_the_radius);
    RUN(near_horizon_bound_stays_below_the_integral);
#if TG_FIXED
    RUN(near_plane_test_is_the_saturating_one);
#endif
    RUN(quarter_upsample_same_for_any_row_stride);
    RUN(quarter_resolution_keeps_the_contact_shadow);
#if !TG_NO_GI_QUARTER && !TG_NO_BUILTIN_SCENES
    RUN(quarter_resolution_in_a_room);
#endif
    return check_summary();
}
