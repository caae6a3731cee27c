/* SPDX-License-Identifier: MIT */
/*
 * test_light.c - direct light, shadow maps, composition and tonemapping
 * against analytic answers.  G-buffers are built by ray casting a tiny
 * analytic scene (a floor and axis-aligned boxes) in double precision, so
 * every expected value is independent of the code under test.
 */
#include <stdlib.h>
#include "check.h"
#include "light/direct.h"
#include "light/shadowmap.h"
#include "light/compose.h"
#include "light/tonemap.h"
#include "light/sh.h"
#include "storage_fixture.h"
#include "light_fixture.h"

#define W 64
#define H 48
#define DEG (3.14159265358979 / 180.0)
#define MAP_SIZE 512

/* ---- a tiny analytic scene: floor y = 0 over [-F, F]^2, plus boxes ---- */
typedef struct { double lo[3], hi[3]; } abox;
typedef struct { double floor_half; int box_count; abox box[4]; } ascene;

/* Ray o + t d against a box (slab test); t of entry (> 1e-9) or -1, face normal in n. */
static double ray_box(const double o[3], const double d[3], const abox *b, double n[3])
{
    double t0 = -1e30, t1 = 1e30;
    int axis = -1, a;
    double sign = 0;
    for (a = 0; a < 3; a++) {
        double lo, hi, s;
        if (fabs(d[a]) < 1e-15) {
            if (o[a] < b->lo[a] || o[a] > b->hi[a]) return -1;
            continue;
        }
        lo = (b->lo[a] - o[a]) / d[a];
        hi = (b->hi[a] - o[a]) / d[a];
        s = -1;
        if (lo > hi) { double tmp = lo; lo = hi; hi = tmp; s = 1; }
        if (lo > t0) { t0 = lo; axis = a; sign = d[a] > 0 ? -1 : 1; (void)s; }
        if (hi < t1) t1 = hi;
    }
    if (t0 > t1 || t1 < 1e-9 || t0 < 1e-9 || axis < 0) return -1;
    if (n) { n[0] = n[1] = n[2] = 0; n[axis] = sign; }
    return t0;
}

/* Nearest hit: t, normal; -1 when nothing. */
static double ray_scene(const ascene *s, const double o[3], const double d[3], double n[3])
{
    double best = -1, nn[3];
    int i;
    if (fabs(d[1]) > 1e-15) {
        double t = -o[1] / d[1];
        double x = o[0] + t * d[0], z = o[2] + t * d[2];
        if (t > 1e-9 && fabs(x) <= s->floor_half && fabs(z) <= s->floor_half) {
            best = t; n[0] = 0; n[1] = o[1] > 0 ? 1 : -1; n[2] = 0;
        }
    }
    for (i = 0; i < s->box_count; i++) {
        double t = ray_box(o, d, &s->box[i], nn);
        if (t > 0 && (best < 0 || t < best)) { best = t; n[0] = nn[0]; n[1] = nn[1]; n[2] = nn[2]; }
    }
    return best;
}

static ascene floor_only(double half)
{
    ascene s;
    memset(&s, 0, sizeof s);
    s.floor_half = half;
    return s;
}

static double dv(tg_real r) { return check_d(r); }
static tg_real rv(double x) { return tg_from_float((float)x); }
static tg_vec3 v3d(double x, double y, double z) { return tg_v3(rv(x), rv(y), rv(z)); }

/* World ray of pixel (x, y)'s centre, direction with view z = 1. */
static void pixel_ray(const tgi_view *v, int x, int y, double o[3], double d[3])
{
    double ndc_x = (x + 0.5) / v->width * 2 - 1, ndc_y = 1 - (y + 0.5) / v->height * 2;
    double vx = ndc_x / dv(v->focal_x), vy = ndc_y / dv(v->focal_y);
    o[0] = dv(v->eye.x); o[1] = dv(v->eye.y); o[2] = dv(v->eye.z);
    d[0] = vx * dv(v->right.x) + vy * dv(v->up.x) + dv(v->forward.x);
    d[1] = vx * dv(v->right.y) + vy * dv(v->up.y) + dv(v->forward.y);
    d[2] = vx * dv(v->right.z) + vy * dv(v->up.z) + dv(v->forward.z);
}

typedef struct {
    tgi_gbuffer gb;         /* the build's storage (storage_fixture.h) */
    uint8_t sky[W * H];
    double world[W * H][3]; /* exact hit point */
    int on_floor[W * H];
} gbuf;

/* The materials: 0 white (albedo 1 1 1, f0 0); 1..8 compose's test set. */
static tgi_material gbuf_materials[9];

static gbuf *gbuf_new(void)
{
    gbuf *g = (gbuf *)calloc(1, sizeof(gbuf));
    gbuf_materials[0].albedo = tg_v3(TG_ONE, TG_ONE, TG_ONE);
    tgi_material_finish(&gbuf_materials[0]);
    sf_gbuffer_alloc(&g->gb, W, H, gbuf_materials, 9);
    return g;
}

static void gbuf_free(gbuf *g)
{
    sf_gbuffer_free(&g->gb);
    free(g);
}

/* E_direct of the test G-buffer seen by camera v, into three planes
 * (through the build's colour storage). */
static void direct_rows(const tgi_gbuffer *gb, const tgi_view *v, const tgi_light *lights, int n,
                        const tgi_shadow_map *const *maps, tg_real *r, tg_real *g, tg_real *b, int y0, int y1)
{
    tgi_gview view;
    tgi_rgb e;
    sf_rgb_alloc(&e, W * H);
    tgi_gview_of(&view, gb, v);
    tgi_direct_rows(&view, lights, n, maps, &e, y0, y1);
    sf_rgb_read(&e, W * H, r, g, b);
    sf_rgb_free(&e);
}

/* Lo (and E when i_r is not NULL) of the test G-buffer seen by camera v,
 * from term planes (NULL: absent), through the build's colour storage. */
static void compose_rows(const tgi_gbuffer *gb, const tgi_view *v, const tgi_env *env, tg_real *const *term_planes,
                         int n, tg_real *o_r, tg_real *o_g, tg_real *o_b, tg_real *i_r, tg_real *i_g, tg_real *i_b)
{
    tgi_gview view;
    tgi_rgb out, irr = tgi_rgb_none(), terms[3];
    int k;
    for (k = 0; k < n; k++) {
        terms[k] = tgi_rgb_none();
        if (!term_planes[3 * k]) continue;
        sf_rgb_alloc(&terms[k], W * H);
        sf_rgb_fill(&terms[k], W * H, term_planes[3 * k], term_planes[3 * k + 1], term_planes[3 * k + 2]);
        sf_rgb_read(&terms[k], W * H, term_planes[3 * k], term_planes[3 * k + 1], term_planes[3 * k + 2]);
    }
    sf_rgb_alloc(&out, W * H);
    if (i_r) sf_rgb_alloc(&irr, W * H);
    tgi_gview_of(&view, gb, v);
    tgi_compose_rows(&view, env, terms, n, &out, &irr, 0, gb->height);
    sf_rgb_read(&out, W * H, o_r, o_g, o_b);
    if (i_r) { sf_rgb_read(&irr, W * H, i_r, i_g, i_b); sf_rgb_free(&irr); }
    sf_rgb_free(&out);
    for (k = 0; k < n; k++) if (tgi_rgb_present(&terms[k])) sf_rgb_free(&terms[k]);
}

/* Ray cast the analytic scene into a G-buffer (material 0: albedo 1 1 1, f0 0). */
static void gbuf_cast(gbuf *g, const tgi_view *v, const ascene *s)
{
    int x, y, k;
    tgi_gbuffer *gb = &g->gb;
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int i = y * W + x;
            double o[3], d[3], n[3] = { 0, 0, 0 }, t;
            pixel_ray(v, x, y, o, d);
            t = ray_scene(s, o, d, n);
            g->on_floor[i] = 0;
            if (t < 0) { g->sky[i] = 1; tgi_gb_set_sky(gb, (size_t)i); continue; }
            g->sky[i] = 0;
            tgi_gb_set(gb, (size_t)i, rv(t), tg_v3(rv(n[0]), rv(n[1]), rv(n[2])), 0);
            for (k = 0; k < 3; k++) g->world[i][k] = o[k] + t * d[k];
            g->on_floor[i] = fabs(g->world[i][1]) < 1e-6 && n[1] > 0.5;
        }
}

/* Triangles of the analytic scene for the shadow map (floor + boxes). */
static int scene_tris(const ascene *s, tg_vec3 *pos)
{
    double f = s->floor_half;
    int n = 0, i, face;
    tg_vec3 q[4];
    q[0] = v3d(-f, 0, -f); q[1] = v3d(f, 0, -f); q[2] = v3d(f, 0, f); q[3] = v3d(-f, 0, f);
    pos[n * 3 + 0] = q[0]; pos[n * 3 + 1] = q[2]; pos[n * 3 + 2] = q[1]; n++;
    pos[n * 3 + 0] = q[0]; pos[n * 3 + 1] = q[3]; pos[n * 3 + 2] = q[2]; n++;
    for (i = 0; i < s->box_count; i++) {
        const abox *b = &s->box[i];
        for (face = 0; face < 6; face++) {
            int a = face / 2, u = (a + 1) % 3, w = (a + 2) % 3, c;
            double p[4][3];
            for (c = 0; c < 4; c++) {
                p[c][a] = (face & 1) ? b->hi[a] : b->lo[a];
                p[c][u] = (c == 1 || c == 2) ? b->hi[u] : b->lo[u];
                p[c][w] = (c >= 2) ? b->hi[w] : b->lo[w];
            }
            for (c = 0; c < 4; c++) q[c] = v3d(p[c][0], p[c][1], p[c][2]);
            pos[n * 3 + 0] = q[0]; pos[n * 3 + 1] = q[1]; pos[n * 3 + 2] = q[2]; n++;
            pos[n * 3 + 0] = q[0]; pos[n * 3 + 1] = q[2]; pos[n * 3 + 2] = q[3]; n++;
        }
    }
    return n;
}

static tg_real e_r[W * H], e_g[W * H], e_b[W * H];

/* ---- direct light ---- */

TEST(directional_incidence)
{
    static const double thetas[] = { 0, 20, 45, 60, 75, 80, 85 };
    gbuf *g = gbuf_new();
    ascene s = floor_only(50);
    tgi_view v;
    size_t k;
    int i, seen = 0;
    tgi_view_make(&v, v3d(0, 5, -6), v3d(0, 0, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &s);
    for (k = 0; k < sizeof thetas / sizeof thetas[0]; k++) {
        double th = thetas[k] * DEG, I = 2.0;
        tgi_light l = make_light(TG_LIGHT_DIRECTIONAL, v3d(0, 0, 0), v3d(sin(th), -cos(th), 0.0), I, 0);
        direct_rows(&g->gb, &v, &l, 1, NULL, e_r, e_g, e_b, 0, H);
        for (i = 0; i < W * H; i++) {
            double want = I * cos(th);
            if (g->sky[i]) continue;
            seen++;
            CHECK(fabs(dv(e_r[i]) - want) <= 0.01 * want, "theta %g: E %g want %g", thetas[k], dv(e_r[i]), want);
            CHECK(fabs(dv(e_g[i]) - 0.5 * want) <= 0.01 * 0.5 * want, "theta %g: E_g %g", thetas[k], dv(e_g[i]));
            CHECK(fabs(dv(e_b[i]) - 0.25 * want) <= 0.01 * 0.25 * want + 2e-5, "theta %g: E_b %g", thetas[k], dv(e_b[i]));
        }
    }
    CHECK(seen > W * H, "the floor covers the image (%d)", seen);
    {   /* a second light from below the floor adds nothing (Lambert's cosine clamped at 0), it
         * does not take light away: E = I cos 20 of the first */
        tgi_light two[2];
        double want = 2.0 * cos(20 * DEG);
        two[0] = make_light(TG_LIGHT_DIRECTIONAL, v3d(0, 0, 0), v3d(sin(20 * DEG), -cos(20 * DEG), 0.0), 2.0, 0);
        two[1] = make_light(TG_LIGHT_DIRECTIONAL, v3d(0, 0, 0), v3d(0.3, 1, 0.2), 2.0, 0);
        direct_rows(&g->gb, &v, two, 2, NULL, e_r, e_g, e_b, 0, H);
        for (i = 0; i < W * H; i++)
            if (!g->sky[i]) CHECK(fabs(dv(e_r[i]) - want) <= 0.01 * want, "light from below: E %g want %g", dv(e_r[i]), want);
    }
    gbuf_free(g);
}

TEST(point_inverse_square_and_spot_edge)
{
    gbuf *g = gbuf_new();
    ascene s = floor_only(50);
    tgi_view v;
    double L[3] = { 1, 3, 0.5 }, I = 10, angle = 30 * DEG;
    tgi_light pt = make_light(TG_LIGHT_POINT, v3d(L[0], L[1], L[2]), v3d(0, -1, 0), I, 0);
    tgi_light sp = make_light(TG_LIGHT_SPOT, v3d(L[0], L[1], L[2]), v3d(0, -1, 0), I, angle);
    int i, inside = 0, outside = 0, between = 0;
    tgi_view_make(&v, v3d(0, 5, -6), v3d(0, 0, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &s);
    direct_rows(&g->gb, &v, &pt, 1, NULL, e_r, e_g, e_b, 0, H);
    for (i = 0; i < W * H; i++) {
        double *p = g->world[i], dx = L[0] - p[0], dy = L[1] - p[1], dz = L[2] - p[2];
        double d2 = dx * dx + dy * dy + dz * dz, want = I * (dy / sqrt(d2)) / d2;
        if (g->sky[i]) continue;
        CHECK(fabs(dv(e_r[i]) - want) <= 0.01 * want + 3e-5, "point: E %g want %g", dv(e_r[i]), want);
    }
    direct_rows(&g->gb, &v, &sp, 1, NULL, e_r, e_g, e_b, 0, H);
    for (i = 0; i < W * H; i++) {
        double *p = g->world[i], dx = L[0] - p[0], dy = L[1] - p[1], dz = L[2] - p[2];
        double d2 = dx * dx + dy * dy + dz * dz, full = I * (dy / sqrt(d2)) / d2;
        double off_axis = acos(dy / sqrt(d2));
        if (g->sky[i]) continue;
        if (off_axis < 0.84 * angle) {
            inside++;
            CHECK(fabs(dv(e_r[i]) - full) <= 0.01 * full + 3e-5, "spot inside: E %g want %g", dv(e_r[i]), full);
        } else if (off_axis > 1.01 * angle) {
            outside++;
            CHECK(e_r[i] == 0, "spot outside: E %g", dv(e_r[i]));
        } else {
            /* the smooth edge: full * smoothstep(cos outer, cos inner, cos off-axis) */
            double c0 = cos(angle), c1 = cos(angle * dv(TG_SPOT_INNER)), t = (cos(off_axis) - c0) / (c1 - c0);
            t = t < 0 ? 0 : t > 1 ? 1 : t;
            between++;
            CHECK(fabs(dv(e_r[i]) - full * t * t * (3 - 2 * t)) <= 0.02 * full + 1e-4, "spot edge: E %g of %g, want %g",
                  dv(e_r[i]), full, full * t * t * (3 - 2 * t));
        }
    }
    CHECK(inside > 20 && outside > 20 && between > 5, "coverage %d %d %d", inside, outside, between);
    gbuf_free(g);
}

/* ---- shadow maps ---- */

/* Analytic shadow test: does the segment from p towards the light hit box b grown by m? */
static int occluded(const double p[3], const tgi_light *l, const abox *b, double m)
{
    abox g = *b;
    double d[3], o[3], n[3], t, tmax = 1e30;
    int a;
    for (a = 0; a < 3; a++) { g.lo[a] -= m; g.hi[a] += m; o[a] = p[a]; }
    if (l->type == TG_LIGHT_DIRECTIONAL) {
        d[0] = -dv(l->dir.x); d[1] = -dv(l->dir.y); d[2] = -dv(l->dir.z);
    } else {
        d[0] = dv(l->pos.x) - p[0]; d[1] = dv(l->pos.y) - p[1]; d[2] = dv(l->pos.z) - p[2];
        tmax = 1;
    }
    t = ray_box(o, d, &g, n);
    return t > 0 && t < tmax;
}

typedef struct { int in_shadow, lit, edge; } shadow_counts;
static int shadow_filter = TG_SHADOW_PCF_TENT; /* the shadow tests run with each filter */

/* The shadow map of light l over scene s (its floor's extent, 2 high) with
 * shadow_filter; returns the map's memory (the caller frees it). */
static void *scene_shadow_map(tgi_shadow_map *sm, const ascene *s, const tgi_light *l)
{
    static tg_vec3 pos[3 * 64];
    void *mem = malloc(tgi_shadow_map_bytes(l, MAP_SIZE));
    int n = scene_tris(s, pos);
    tg_vec3 lo = v3d(-s->floor_half, 0, -s->floor_half), hi = v3d(s->floor_half, 2, s->floor_half);
    tgi_shadow_map_setup(sm, l, MAP_SIZE, lo, hi, mem);
    sm->filter = shadow_filter;
    tgi_shadow_map_render(sm, pos, n);
    return mem;
}

/* Render the map, light the G-buffer, and compare every floor pixel with the
 * analytic shadow: surely inside -> E <= 2% of unshadowed, surely outside -> >= 98%. */
static shadow_counts check_box_shadow(gbuf *g, const tgi_view *v, const ascene *s, const tgi_light *l,
                                      double margin)
{
    static tg_real unsh_r[W * H], dummy_g[W * H], dummy_b[W * H];
    shadow_counts c = { 0, 0, 0 };
    tgi_shadow_map sm;
    const tgi_shadow_map *maps[1];
    void *mem = scene_shadow_map(&sm, s, l);
    int i;
    maps[0] = &sm;
    direct_rows(&g->gb, v, l, 1, NULL, unsh_r, dummy_g, dummy_b, 0, H);
    direct_rows(&g->gb, v, l, 1, maps, e_r, e_g, e_b, 0, H);
    for (i = 0; i < W * H; i++) {
        double full = dv(unsh_r[i]), got = dv(e_r[i]);
        int k, inside = 0, outside = 1;
        if (!g->on_floor[i] || full < 1e-3) continue;
        for (k = 0; k < s->box_count; k++) {
            if (occluded(g->world[i], l, &s->box[k], -margin)) inside = 1;
            if (occluded(g->world[i], l, &s->box[k], margin)) outside = 0;
        }
        if (inside) {
            c.in_shadow++;
            CHECK(got <= 0.02 * full, "filter %d: in the shadow at (%.3f, %.3f): %g of %g", shadow_filter,
                  g->world[i][0], g->world[i][2], got, full);
        } else if (outside) {
            c.lit++;
            CHECK(got >= 0.98 * full, "filter %d: outside the shadow at (%.3f, %.3f): %g of %g", shadow_filter,
                  g->world[i][0], g->world[i][2], got, full);
        } else {
            c.edge++;
            CHECK(got >= 0 && got <= full * 1.0001 + 1e-4, "penumbra in range: %g of %g", got, full);
        }
    }
    free(mem);
    return c;
}

static void box_shadow_lands_where_geometry_says_with_filter(void)
{
    gbuf *g = gbuf_new();
    ascene s = { 4, 1, { { { -0.5, 0, -0.5 }, { 0.5, 1, 0.5 } } } };
    tgi_view v;
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3d(0, 0, 0), v3d(1.0, -0.8, 0.4), 1, 0);
    tgi_light sl = make_light(TG_LIGHT_SPOT, v3d(-2, 4, -1), v3d(2.5, -4, 1.2), 20, 50 * DEG);
    tgi_light pl = make_light(TG_LIGHT_POINT, v3d(-1.5, 3, 1), v3d(0, -1, 0), 20, 0);
    shadow_counts c;
    tgi_view_make(&v, v3d(0, 7, 0.01), v3d(0, 0, 0), v3d(0, 0, 1), rv(40 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &s);
    c = check_box_shadow(g, &v, &s, &dl, 0.08);
    CHECK(c.in_shadow > 80 && c.lit > 500, "directional: %d in shadow, %d lit, %d edge", c.in_shadow, c.lit, c.edge);
    c = check_box_shadow(g, &v, &s, &sl, 0.08);
    CHECK(c.in_shadow > 60 && c.lit > 200, "spot: %d in shadow, %d lit, %d edge", c.in_shadow, c.lit, c.edge);
    c = check_box_shadow(g, &v, &s, &pl, 0.08);
    CHECK(c.in_shadow > 60 && c.lit > 500, "point: %d in shadow, %d lit, %d edge", c.in_shadow, c.lit, c.edge);
    gbuf_free(g);
}

static void no_acne_at_80_degrees_with_filter(void)
{
    gbuf *g = gbuf_new();
    ascene s = floor_only(4);
    tgi_view v;
    double th = 80 * DEG;
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3d(0, 0, 0), v3d(sin(th), -cos(th), 0.3 * sin(th)), 1, 0);
    tgi_light sl = make_light(TG_LIGHT_SPOT, v3d(-8 * sin(th), 8 * cos(th), 0), v3d(sin(th), -cos(th), 0), 50, 20 * DEG);
    shadow_counts c;
    tgi_view_make(&v, v3d(0, 9, -3), v3d(0, 0, 0), v3d(0, 1, 0), rv(45 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &s);
    c = check_box_shadow(g, &v, &s, &dl, 0.0); /* no box: every floor pixel must be lit >= 98% */
    CHECK(c.lit > 1000 && c.in_shadow == 0, "directional: %d lit", c.lit);
    c = check_box_shadow(g, &v, &s, &sl, 0.0);
    CHECK(c.lit > 100 && c.in_shadow == 0, "spot: %d lit", c.lit);
    gbuf_free(g);
}

static void point_cube_faces_meet_without_seams_with_filter(void)
{
    gbuf *g = gbuf_new();
    /* a post whose shadow crosses the +X / -Y face boundary (x - 0.3 = 1.5 on the floor) */
    ascene s = { 4, 1, { { { 1.2, 0, -0.3 }, { 1.6, 0.6, 0.3 } } } };
    ascene open = floor_only(4);
    tgi_view v;
    tgi_light pl = make_light(TG_LIGHT_POINT, v3d(0.3, 1.5, -0.2), v3d(0, -1, 0), 20, 0);
    shadow_counts c;
    tgi_view_make(&v, v3d(0, 12, 0.01), v3d(0, 0, 0), v3d(0, 0, 1), rv(40 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &open);
    c = check_box_shadow(g, &v, &open, &pl, 0.0); /* an open floor is fully lit across all five faces */
    CHECK(c.lit > 1500 && c.in_shadow == 0, "open floor: %d lit", c.lit);
    {   /* and directly along the face edges, sampled finely */
        tgi_shadow_map sm;
        void *mem = scene_shadow_map(&sm, &open, &pl);
        int k, bad = 0;
        for (k = 0; k <= 2000; k++) {
            double z = -3.9 + 7.8 * k / 2000.0, off = ((k % 7) - 3) * 0.002;
            tg_vec3 p1 = v3d(0.3 + 1.5 + off, 0, z), p2 = v3d(0.3 - 1.5 + off, 0, z);
            tg_vec3 p3 = v3d(z, 0, -0.2 + 1.5 + off), up = tg_v3(0, TG_ONE, 0);
            if (tgi_shadow_visibility(&sm, p1, up) < TG_R(0.99f)) bad++;
            if (tgi_shadow_visibility(&sm, p2, up) < TG_R(0.99f)) bad++;
            if (tgi_shadow_visibility(&sm, p3, up) < TG_R(0.99f)) bad++;
        }
        CHECK(bad == 0, "%d points along the cube edges darkened", bad);
        free(mem);
    }
    {   /* the post's shadow crosses the +X / -Y face edge: dense samples across the edge */
        tgi_shadow_map sm;
        void *mem = scene_shadow_map(&sm, &s, &pl);
        int k, inside = 0;
        for (k = 0; k <= 4000; k++) {
            double z = -0.6 + 0.8 * (k / 40) / 100.0, x = 1.8 + ((k % 40) - 20) * 0.0005;
            double p[3] = { x, 0, z };
            tg_real vis = tgi_shadow_visibility(&sm, v3d(x, 0, z), tg_v3(0, TG_ONE, 0));
            if (!occluded(p, &pl, &s.box[0], -0.03)) continue;
            inside++;
            CHECK(vis <= TG_R(0.02f), "filter %d: at the face edge (%.4f, %.3f) in shadow: %g", shadow_filter, x, z, dv(vis));
        }
        CHECK(inside > 1000, "samples in the shadow at the edge: %d", inside);
        free(mem);
    }
    gbuf_cast(g, &v, &s);
    c = check_box_shadow(g, &v, &s, &pl, 0.06);
    CHECK(c.in_shadow > 8 && c.lit > 1000, "post: %d in shadow, %d lit, %d edge", c.in_shadow, c.lit, c.edge);
    gbuf_free(g);
}

TEST(degenerate_inputs_stay_finite_and_saturate)
{
    gbuf *g = gbuf_new();
    ascene s = floor_only(50);
    tgi_view v;
    tgi_light lights[4];
    tgi_shadow_map sm;
    static tg_vec3 pos[3 * 64];
    const tgi_shadow_map *maps[4] = { NULL, NULL, NULL, NULL };
    void *mem;
    int i, n;
    tgi_view_make(&v, v3d(0, 1, -2), v3d(0, 0, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &s);
    /* a huge point light almost touching the floor, a zero-angle spot, a zero direction */
    lights[0] = make_light(TG_LIGHT_POINT, v3d(0, 0.0001, 0), v3d(0, -1, 0), 30000, 0);
    lights[1] = make_light(TG_LIGHT_SPOT, v3d(0, 1, 0), v3d(0, -1, 0), 5, 0);
    lights[2] = make_light(TG_LIGHT_DIRECTIONAL, v3d(0, 0, 0), v3d(0, -1, 0), 1, 0);
    lights[2].dir = tg_v3(0, 0, 0);
    lights[3] = make_light(TG_LIGHT_POINT, v3d(0, 0, 0), v3d(0, -1, 0), 1, 0); /* on the surface */
#if TG_WIDE_STORAGE
    for (i = 0; i < 7; i++) { g->gb.nx[i] = g->gb.ny[i] = g->gb.nz[i] = 0; } /* zero normals */
#endif                                  /* (compact storage has none: octahedral) */
    tgi_gb_set_sky(&g->gb, 8);          /* zero depth is sky */
    n = scene_tris(&s, pos);
    mem = malloc(tgi_shadow_map_bytes(&lights[3], 64));
    tgi_shadow_map_setup(&sm, &lights[3], 64, v3d(-50, 0, -50), v3d(50, 1, 50), mem);
    tgi_shadow_map_render(&sm, pos, n);
    maps[3] = &sm;
    direct_rows(&g->gb, &v, lights, 4, maps, e_r, e_g, e_b, 0, H);
    for (i = 0; i < W * H; i++) {
        CHECK(tg_isfinite(e_r[i]) && e_r[i] >= 0 && e_g[i] >= 0 && e_b[i] >= 0, "pixel %d: E %g", i, dv(e_r[i]));
    }
    {   /* right under the huge light: saturates (fixed) or is huge (float), never negative */
        int best = 0;
        for (i = 0; i < W * H; i++) if (!g->sky[i] && e_r[i] > e_r[best]) best = i;
        CHECK(dv(e_r[best]) > 1000, "peak E %g", dv(e_r[best]));
    }
    CHECK(tgi_shadow_visibility(&sm, v3d(0, 0, 0), tg_v3(0, TG_ONE, 0)) >= 0, "lookup at the light");
    free(mem);
    gbuf_free(g);
}

/* A point light nearer a surface than TG_DIRECT_MIN_DISTANCE (0.01) is
 * taken at that distance: 0.005 above the surface along its normal, E =
 * I (0.005 / 0.01) / 0.01^2 = 5000 I (the cosine from the clamped distance
 * too), never above I / 0.01^2; a light exactly on the point gives 0, not
 * NaN. */
TEST(point_light_nearer_than_the_minimum_distance)
{
    tgi_light l = make_light(TG_LIGHT_POINT, v3d(0, 0.005, 0), v3d(0, -1, 0), 1, 0);
    tg_vec3 n = tg_v3(0, TG_ONE, 0), e = tgi_direct_irradiance(&l, tg_v3(0, 0, 0), n);
    double tol = TG_FIXED ? 0.25 : 0.01;   /* 0.01^2 is 7 ulps in Q16.16 */
    CHECK(fabs(dv(e.x) - 5000) <= tol * 5000 && dv(e.x) <= 10000 * (1 + tol), "E %g, want 5000", dv(e.x));
    l = make_light(TG_LIGHT_POINT, v3d(0, 0, 0), v3d(0, -1, 0), 1, 0);
    e = tgi_direct_irradiance(&l, tg_v3(0, 0, 0), n);
    CHECK(e.x == 0 && e.y == 0 && e.z == 0, "a light on the point: E %g", dv(e.x));
}

/* ---- composition ---- */

/* A sky pixel shows the environment along the ray through its centre: an
 * SH9 environment of bands 0 and 1 (radiance linear in the direction) to
 * 1e-4 (1e-3 in fixed point; a ray through the pixel's corner is 3e-3 off
 * or more here). */
TEST(sky_pixels_see_along_their_centre_ray)
{
    static const double L[4] = { 2.0, 0.5, 0.3, 0.8 };   /* L00, L1-1 (y), L10 (z), L11 (x) */
    tgi_env env;
    tgi_view v;
    double tol = TG_FIXED ? 1e-3 : 1e-4, worst = 0;
    int x, y, k;
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_SH9;
    for (k = 0; k < 4; k++) env.sh9[k] = v3d(L[k], L[k], L[k]);
    tgi_view_make(&v, v3d(0, 1, -6), v3d(0.5, 1.3, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            double o[3], d[3], l, want;
            tg_vec3 got = tgi_compose_sky(&v, &env, x, y);
            pixel_ray(&v, x, y, o, d);
            l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            want = 0.282094792 * L[0] + 0.488602512 * (d[1] * L[1] + d[2] * L[2] + d[0] * L[3]) / l;
            if (fabs(dv(got.x) - want) > worst) worst = fabs(dv(got.x) - want);
        }
    printf("# sky pixels: within %.2g of the environment along their centre ray\n", worst);
    CHECK(worst <= tol, "a sky pixel %.2g off its centre ray's radiance", worst);
}


TEST(compose_formula_sky_and_saturation)
{
    static tg_real d[3][W * H], f[3][W * H], nr[3][W * H], er[W * H], eg[W * H], eb[W * H];
    static tg_real o_r[W * H], o_g[W * H], o_b[W * H], i_r[W * H], i_g[W * H], i_b[W * H];
    gbuf *g = gbuf_new();
    ascene s = floor_only(4);
    tgi_env env;
    tgi_view v;
    tg_real *terms[9];
    int i, c, sky_seen = 0;
    tgi_view_make(&v, v3d(0, 1, -6), v3d(0, 1, 0), v3d(0, 1, 0), rv(60 * DEG), TG_R(0.05f), TG_R(1000.0f), W, H);
    gbuf_cast(g, &v, &s);
    /* per pixel: albedo 0.8 0.5 0.2, F0 0.04 (i % 4), emissive 0.75 on every third pixel:
     * material 1 + i % 4 + 4 (i % 3 == 0) */
    for (i = 0; i < 8; i++) {
        gbuf_materials[1 + i].albedo = tg_v3(rv(0.8), rv(0.5), rv(0.2));
        gbuf_materials[1 + i].f0 = rv(0.04 * (i % 4));
        gbuf_materials[1 + i].emissive = i >= 4 ? tg_v3(rv(0.75), rv(0.75), rv(0.75)) : tg_v3(0, 0, 0);
        tgi_material_finish(&gbuf_materials[1 + i]);
    }
    g->gb.has_emissive = 1;
    {
        tgi_gview gv = sf_view(&g->gb, &v);
        for (i = 0; i < W * H; i++) {
            for (c = 0; c < 3; c++) { d[c][i] = rv(0.5 + 0.1 * c); f[c][i] = rv(0.25 * (i % 5)); nr[c][i] = rv(0.125 * c); }
            if (!g->sky[i]) tgi_gb_set(&g->gb, (size_t)i, tgi_gv_depth(&gv, (size_t)i), tgi_gv_normal(&gv, (size_t)i),
                                       1 + i % 4 + (i % 3 == 0 ? 4 : 0));
        }
    }
    for (c = 0; c < 3; c++) { terms[c] = d[c]; terms[3 + c] = f[c]; terms[6 + c] = nr[c]; }
    memset(&env, 0, sizeof env);
    env.type = TG_ENV_SKY; env.sky = v3d(0.3, 0.5, 1.0); env.ground = v3d(0.2, 0.1, 0.05); env.up = v3d(0, 1, 0);
    compose_rows(&g->gb, &v, &env, terms, 3, o_r, o_g, o_b, i_r, i_g, i_b);
    for (i = 0; i < W * H; i++) {
        double alb[3] = { 0.8, 0.5, 0.2 }, out[3] = { dv(o_r[i]), dv(o_g[i]), dv(o_b[i]) };
        double irr[3] = { dv(i_r[i]), dv(i_g[i]), dv(i_b[i]) };
        if (g->sky[i]) {
            double o[3], dd[3];
            pixel_ray(&v, i % W, i / W, o, dd);
            sky_seen++;
            CHECK(fabs(out[2] - (dd[1] >= 0 ? 1.0 : 0.05)) < 1e-4 + sf_rgb_rounding(dd[1] >= 0 ? 1.0 : 0.2),
                  "sky radiance %g", out[2]);
            continue;
        }
        {
            /* the terms as stored (compose_rows read them back); the outputs within their storage's
             * rounding (RGB9E5: a step of the largest channel) */
            double E[3], want[3], f0 = 0.04 * (i % 4), em = i % 3 == 0 ? 0.75 : 0;
            for (c = 0; c < 3; c++) {
                E[c] = dv(d[c][i]) + dv(f[c][i]) + dv(nr[c][i]);
                want[c] = alb[c] / 3.14159265358979 * (1 - f0) * E[c] + em;
            }
            for (c = 0; c < 3; c++) {
                CHECK(fabs(irr[c] - E[c]) < 1e-4 + sf_rgb_rounding(fmax(E[0], fmax(E[1], E[2]))),
                      "irradiance %g want %g", irr[c], E[c]);
                CHECK(fabs(out[c] - want[c]) <= 1e-3 * want[c] + 1e-4 + sf_rgb_rounding(fmax(want[0], fmax(want[1], want[2]))),
                      "Lo %g want %g", out[c], want[c]);
            }
        }
    }
    CHECK(sky_seen > 100, "sky pixels %d", sky_seen);
    /* an absent term is skipped; huge irradiance saturates, never wraps */
    terms[3] = NULL;
    /* fixed point: the largest value, summed twice, must saturate; float: a huge finite value */
    for (i = 0; i < W * H; i++) { er[i] = TG_FIXED ? TG_REAL_MAX : TG_R(1e30f); eg[i] = rv(1e4); eb[i] = 0; }
    terms[0] = er; terms[1] = eg; terms[2] = eb;
    terms[6] = er; terms[7] = eg; terms[8] = eb;
    compose_rows(&g->gb, &v, NULL, terms, 3, o_r, o_g, o_b, NULL, NULL, NULL);
    for (i = 0; i < W * H; i++) {
        if (g->sky[i]) { CHECK(o_r[i] == 0 && o_b[i] == 0, "sky without env is black"); continue; }
        CHECK(tg_isfinite(o_r[i]) && dv(o_r[i]) > 1000, "HDR stays huge and positive: %g", dv(o_r[i]));
        CHECK(dv(o_g[i]) > 1000, "2e4 irradiance: %g", dv(o_g[i]));
        CHECK(dv(o_b[i]) >= 0 && dv(o_b[i]) <= 0.76, "no irradiance: emissive only %g", dv(o_b[i]));
    }
    gbuf_free(g);
}

/* ---- tonemap ---- */

static double srgb_exact(double c)
{
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1 / 2.4) - 0.055;
}

TEST(srgb_table_matches_formula)
{
    double worst = 0;
    int k, n = 200000;
    for (k = 0; k <= n; k++) {
        double x = (double)k / n;
        tg_real r = rv(x);
        double exact = 255 * srgb_exact(dv(r));
        double err = fabs(tgi_srgb8(r) - exact);
        if (err > worst) worst = err;
    }
    CHECK(worst <= 0.5 + 1e-4, "worst error %.6f LSB", worst);
    CHECK(tgi_srgb8(0) == 0 && tgi_srgb8(TG_ONE) == 255, "ends");
    CHECK(tgi_srgb8(TG_R(-1.0f)) == 0 && tgi_srgb8(TG_R(3.0f)) == 255, "clamps");
    printf("# sRGB table: worst error %.4f LSB\n", worst);
}

static double aces_exact(double x)
{
    double y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return y < 0 ? 0 : y > 1 ? 1 : y;
}

TEST(tonemap_monotone_zero_and_saturating)
{
    static const tg_real big[4] = { TG_REAL_MAX, TG_R(100.0f), TG_R(7.3f), TG_R(1000.0f) };
    tg_real prev = 0;
    uint8_t rgb[12], prev8 = 0;
    double worst = 0;
    int k, mono = 1, mono8 = 1;
    CHECK(tgi_tonemap_aces(0) == 0 && tgi_tonemap8(0) == 0, "0 -> 0");
    for (k = 0; k <= 80000; k++) {
        tg_real x = rv(k * 0.0001);
        tg_real y = tgi_tonemap_aces(x);
        uint8_t c = tgi_tonemap8(x);
        double ideal = 255 * srgb_exact(aces_exact(dv(x))), err = fabs(c - ideal);
        if (y < tg_sub(prev, TG_FIXED ? TG_EPS : 0)) mono = 0; /* Q16 rounding: within one ulp */
        if (c < prev8) mono8 = 0;
        if (err > worst) worst = err;
        CHECK(y >= 0 && y <= TG_ONE, "range %g", dv(y));
        CHECK(fabs(dv(y) - aces_exact(dv(x))) < (TG_FIXED ? 1e-4 : 1e-6), "ACES fit at %g: %g", dv(x), dv(y));
        prev = y; prev8 = c;
    }
    CHECK(mono && mono8, "monotone (linear %d, 8-bit %d)", mono, mono8);
    CHECK(worst <= 0.5 + 1e-3, "tonemap8 vs the exact curve: %.5f LSB", worst);
    printf("# tonemap8: worst error %.4f LSB against 255 srgb(aces(x))\n", worst);
    tgi_tonemap_row8(big, big, big, 4, TG_R(4.0f), rgb);
    for (k = 0; k < 12; k++) CHECK(rgb[k] == 255, "HDR saturates to white, got %d", rgb[k]);
    {
        tg_real zero[2] = { 0, 0 }, quarter[2] = { TG_R(0.25f), TG_R(0.125f) };
        tgi_tonemap_row8(zero, zero, zero, 2, TG_ONE, rgb);
        for (k = 0; k < 6; k++) CHECK(rgb[k] == 0, "black stays black");
        tgi_tonemap_row8(quarter, quarter + 1, quarter, 1, TG_R(2.0f), rgb);
        CHECK(rgb[0] == tgi_tonemap8(TG_R(0.5f)) && rgb[1] == tgi_tonemap8(TG_R(0.25f)) &&
              rgb[2] == tgi_tonemap8(TG_R(0.5f)), "exposure multiplies each channel before the curve");
    }
}

TEST(box_shadow_lands_where_geometry_says)
{
    for (shadow_filter = 0; shadow_filter < 2; shadow_filter++) box_shadow_lands_where_geometry_says_with_filter();
    shadow_filter = TG_SHADOW_PCF_TENT;
}

TEST(no_acne_at_80_degrees)
{
    for (shadow_filter = 0; shadow_filter < 2; shadow_filter++) no_acne_at_80_degrees_with_filter();
    shadow_filter = TG_SHADOW_PCF_TENT;
}

TEST(point_cube_faces_meet_without_seams)
{
    for (shadow_filter = 0; shadow_filter < 2; shadow_filter++) point_cube_faces_meet_without_seams_with_filter();
    shadow_filter = TG_SHADOW_PCF_TENT;
}

/* The bent cone's far field (sh.c) as its formula reads with tg_mul, tg_sub,
 * tgi_v3_dot and tg_add (HBIL sec. 2.2.4), to check the Q16.16 path that
 * skips the saturation tests where the weights are bounded. */
static tg_vec3 cone_formula(const tg_vec3 sh[9], tg_vec3 n, tg_real ao)
{
    tg_real t = tgi_cone_cos_from_ao(ao), omt2 = tg_saturate(ao), x = n.x, y = n.y, z = n.z, e[3];
    tg_real t2 = tg_sub(TG_ONE, omt2), t3 = tg_mul(t2, t), t4 = tg_mul(t2, t2);
    tg_real c0 = tg_mul(TG_R(0.886226925f), omt2), c1 = tg_mul(TG_R(1.023326708f), tg_sub(TG_ONE, t3));
    tg_real c2 = tg_mul(TG_R(0.247707956f), tg_sub(tg_mul(TG_R(3.0f), tg_sub(TG_ONE, t4)), tg_mul(TG_R(2.0f), omt2)));
    tg_real c2x = tg_mul(c2, TG_R(3.464101615f)), w[9];
    int c, k;
    w[0] = c0; w[1] = tg_mul(c1, y); w[2] = tg_mul(c1, z); w[3] = tg_mul(c1, x);
    w[4] = tg_mul(c2x, tg_mul(x, y)); w[5] = tg_mul(c2x, tg_mul(y, z));
    w[6] = tg_mul(c2, tg_sub(tg_mul(TG_R(3.0f), tg_mul(z, z)), TG_ONE)); w[7] = tg_mul(c2x, tg_mul(z, x));
    w[8] = tg_mul(tg_mul(c2, TG_R(1.732050808f)), tg_sub(tg_mul(x, x), tg_mul(y, y)));
    for (c = 0; c < 3; c++) {
        tg_real sum = 0;
        for (k = 0; k < 9; k += 3)
            sum = tg_add(sum, tgi_v3_dot(tg_v3(w[k], w[k + 1], w[k + 2]),
                                         tg_v3((&sh[k].x)[c], (&sh[k + 1].x)[c], (&sh[k + 2].x)[c])));
        e[c] = tg_max(sum, 0);
    }
    return tg_v3(e[0], e[1], e[2]);
}

/* tgi_sh9_irradiance_bent_cone gives its formula's bits: 3e6 random axes
 * (unit, and up to 512 long: the bounded path and the saturating one), AO
 * over [-0.5, 1.5] and SH9 coefficients from small to the range's ends. */
TEST(bent_cone_far_field_is_its_formula)
{
    uint64_t v = 0x853C49E6748FEA9Bull;
    tg_vec3 sh[9];
    long i, bad = 0;
    int k;
    for (i = 0; i < 3000000; i++) {
        tg_vec3 n, got, want;
        tg_real ao;
        uint32_t r[5];
        for (k = 0; k < 5; k++) { v ^= v << 13; v ^= v >> 7; v ^= v << 17; r[k] = (uint32_t)(v >> 32); }
        if (i % 1000 == 0)   /* a new environment: coefficients up to 2^(0..30) ulps, or the range's ends */
            for (k = 0; k < 27; k++) {
                uint64_t u;
                v ^= v << 13; v ^= v >> 7; v ^= v << 17; u = v;
                (&sh[k / 3].x)[k % 3] = (i / 1000) % 5 == 4 ? ((u & 1) ? TG_REAL_MAX : TG_REAL_MIN)
                                      : tg_from_float((float)((int32_t)(uint32_t)(u >> 32) >> (int)(u % 31)) / 65536.0f);
            }
        n = tg_v3(tg_from_float((float)(int32_t)r[0] / 2147483648.0f), tg_from_float((float)(int32_t)r[1] / 2147483648.0f),
                  tg_from_float((float)(int32_t)r[2] / 2147483648.0f));
        if (r[3] % 4) n = tgi_v3_normalize_or(n, tg_v3(0, TG_ONE, 0));
        else n = tgi_v3_scale(n, tg_from_int(r[3] % 8 == 0 ? 1 << (r[3] >> 4) % 10 : 1 + (int)(r[3] % 7)));   /* up to 512 */
        ao = tg_from_float(2.0f * (float)(r[4] & 0xFFFF) / 65536.0f - 0.5f);
        got = tgi_sh9_irradiance_bent_cone(sh, n, ao);
        want = cone_formula(sh, n, ao);
        bad += got.x != want.x || got.y != want.y || got.z != want.z;
    }
    CHECK(bad == 0, "%ld of 3e6 far-field irradiances differ from the formula", bad);
}

int main(void)
{
    RUN(directional_incidence);
    RUN(point_inverse_square_and_spot_edge);
    RUN(box_shadow_lands_where_geometry_says);
    RUN(no_acne_at_80_degrees);
    RUN(point_cube_faces_meet_without_seams);
    RUN(degenerate_inputs_stay_finite_and_saturate);
    RUN(point_light_nearer_than_the_minimum_distance);
    RUN(compose_formula_sky_and_saturation);
    RUN(sky_pixels_see_along_their_centre_ray);
    RUN(srgb_table_matches_formula);
    RUN(tonemap_monotone_zero_and_saturating);
    RUN(bent_cone_far_field_is_its_formula);
    return check_summary();
}
