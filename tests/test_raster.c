/* SPDX-License-Identifier: MIT */
/*
 * test_raster.c - the rasterizer: fill rule (every pixel exactly once),
 * near-plane and guard-band clipping, depth (constant and perspective-correct
 * on tilted planes, vs. analytic ray casts in double), normals, culling,
 * twosided, zero area, row ranges, and the depth-only mode (ortho and
 * perspective).  Both number types.
 */
#include <stdlib.h>
#include "check.h"
#include "storage_fixture.h"
#include "raster/raster.h"

/* ---------------------------------------------------------------------- */
/* helpers                                                                 */

static uint32_t rng_state = 12345u;
static uint32_t rng(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}
static double rnd(void) { return (rng() & 0xFFFFFF) / 16777216.0; }

static tg_real R(double d) { return tg_from_float((float)d); }
static tg_vec3 V(double x, double y, double z) { return tg_v3(R(x), R(y), R(z)); }

/* The G-buffer in the build's storage (storage_fixture.h), read back
 * through gview.h's accessors. */
typedef struct gbuf {
    tgi_gbuffer gb;
} gbuf;

static void gbuf_alloc(gbuf *g, int w, int h)
{
    sf_gbuffer_alloc(&g->gb, w, h, NULL, 0);
    g->gb.object = (uint16_t *)sf_calloc((size_t)w * (size_t)h, sizeof(uint16_t));
    tgi_gbuffer_clear_rows(&g->gb, 0, h);
}

static void gbuf_free(gbuf *g) { sf_gbuffer_free(&g->gb); }

static int gsky(const gbuf *g, int i) { tgi_gview v = sf_view(&g->gb, NULL); return tgi_gv_is_sky(&v, (size_t)i); }
static double gdepth(const gbuf *g, int i) { tgi_gview v = sf_view(&g->gb, NULL); return (double)tg_to_float(tgi_gv_depth(&v, (size_t)i)); }
static tg_vec3 gnormal(const gbuf *g, int i) { tgi_gview v = sf_view(&g->gb, NULL); return tgi_gv_normal(&v, (size_t)i); }
static int gmaterial(const gbuf *g, int i) { tgi_gview v = sf_view(&g->gb, NULL); return tgi_gv_material_index(&v, (size_t)i); }
/* The same stored bits at pixel i. */
static int gsame(const gbuf *a, const gbuf *b, int i)
{
#if TG_WIDE_STORAGE
    return a->gb.depth[i] == b->gb.depth[i] && a->gb.nx[i] == b->gb.nx[i] && a->gb.ny[i] == b->gb.ny[i] &&
           a->gb.nz[i] == b->gb.nz[i] && a->gb.material[i] == b->gb.material[i] && a->gb.object[i] == b->gb.object[i];
#else
    return a->gb.depth[i] == b->gb.depth[i] && (!a->gb.depth[i] || a->gb.nm[i] == b->gb.nm[i]) &&
           a->gb.object[i] == b->gb.object[i];
#endif
}

#define MAX_TRIS 20000
typedef struct mesh {
    tg_vec3 pos[3 * MAX_TRIS], nrm[3 * MAX_TRIS];
    uint16_t mat[MAX_TRIS], obj[MAX_TRIS];
    int n;
    tgi_material materials[4];
    tgi_raster_mesh rm;
} mesh;

static mesh *mesh_new(void)
{
    mesh *m = (mesh *)calloc(1, sizeof *m);
    int k;
    for (k = 0; k < 4; k++) {
        m->materials[k].albedo = V(0.25 * (k + 1), 0.5, 0.75);
        m->materials[k].f0 = R(0.04);
        m->materials[k].emissive = V(0, 0, 0.125 * k);
        tgi_material_finish(&m->materials[k]);
    }
    m->materials[1].twosided = 1;
    return m;
}

static tgi_raster_mesh *mesh_rm(mesh *m)
{
    m->rm.pos = m->pos; m->rm.nrm = m->nrm;
    m->rm.tri_material = m->mat; m->rm.tri_object = m->obj;
    m->rm.tri_count = m->n;
    m->rm.materials = m->materials;
    return &m->rm;
}

/* A camera at the origin looking along +z of the world; view space is then
 * reached through the view's own basis, so tests build geometry in view
 * coordinates (x right, y up, z forward) and map it to the world. */
static tgi_view view_make(int w, int h, double fov_deg, int aligned)
{
    tgi_view v;
    if (aligned)
        tgi_view_make(&v, V(0, 0, 0), V(0, 0, 1), V(0, 1, 0),
                     R(fov_deg * 3.14159265358979 / 180.0), R(0.05), R(1000), w, h);
    else
        tgi_view_make(&v, V(0.5, 1.0, -2.0), V(1.5, 1.25, 3.0), V(0, 1, 0),
                     R(fov_deg * 3.14159265358979 / 180.0), R(0.05), R(1000), w, h);
    return v;
}
static tgi_view view_at(int w, int h, double fov_deg) { return view_make(w, h, fov_deg, 0); }

static double D(tg_real r) { return check_d(r); }

/* A G-buffer of v's size with all of m rasterized from v. */
static void gbuf_draw(gbuf *g, const tgi_view *v, mesh *m)
{
    gbuf_alloc(g, v->width, v->height);
    tgi_raster_gbuffer(&g->gb, v, mesh_rm(m), 0, v->height);
}

static void drawn_free(gbuf *g, mesh *m)
{
    gbuf_free(g);
    free(m);
}

/* A view, the mesh built in it and the G-buffer it is drawn into: the
 * fixture of the tests that rasterize one mesh and read the pixels. */
typedef struct drawing {
    tgi_view v;
    mesh *m;
    gbuf g;
} drawing;

static drawing drawing_at(int w, int h, double fov_deg, int aligned)
{
    drawing d;
    memset(&d, 0, sizeof d);
    d.v = view_make(w, h, fov_deg, aligned);
    d.m = mesh_new();
    return d;
}

static void drawing_draw(drawing *d) { gbuf_draw(&d->g, &d->v, d->m); }
static void drawing_free(drawing *d) { drawn_free(&d->g, d->m); }

static tg_vec3 view_to_world(const tgi_view *v, double x, double y, double z)
{
    double p[3];
    int k;
    for (k = 0; k < 3; k++) {
        double r = k == 0 ? D(v->right.x) : k == 1 ? D(v->right.y) : D(v->right.z);
        double u = k == 0 ? D(v->up.x) : k == 1 ? D(v->up.y) : D(v->up.z);
        double f = k == 0 ? D(v->forward.x) : k == 1 ? D(v->forward.y) : D(v->forward.z);
        double e = k == 0 ? D(v->eye.x) : k == 1 ? D(v->eye.y) : D(v->eye.z);
        p[k] = e + r * x + u * y + f * z;
    }
    return V(p[0], p[1], p[2]);
}

static tg_vec3 dir_to_world(const tgi_view *v, double x, double y, double z)
{
    tg_vec3 o = view_to_world(v, 0, 0, 0), p = view_to_world(v, x, y, z);
    return tgi_v3_sub(p, o);
}

/* Add a triangle given in view space, with a flat normal (or vertex normals). */
static void add_tri_view(mesh *m, const tgi_view *v, const double (*p)[3], const double (*n)[3],
                         int material, int object)
{
    int k;
    double e1[3], e2[3], c[3], len;
    for (k = 0; k < 3; k++) { e1[k] = p[1][k] - p[0][k]; e2[k] = p[2][k] - p[0][k]; }
    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
    len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    if (len > 0) { c[0] /= len; c[1] /= len; c[2] /= len; }
    /* the view basis is left-handed (x right, y up, z forward): flip to world's sense */
    for (k = 0; k < 3; k++) {
        m->pos[3 * m->n + k] = view_to_world(v, p[k][0], p[k][1], p[k][2]);
        if (n) m->nrm[3 * m->n + k] = dir_to_world(v, n[k][0], n[k][1], n[k][2]);
        else m->nrm[3 * m->n + k] = dir_to_world(v, -c[0], -c[1], -c[2]);
    }
    m->mat[m->n] = (uint16_t)material;
    m->obj[m->n] = (uint16_t)object;
    m->n++;
}

/* Ray through the centre of pixel (px, py): view-space direction with z = 1. */
static void pixel_ray(const tgi_view *v, int px, int py, double *dx, double *dy)
{
    double ndc_x = (px + 0.5) / v->width * 2.0 - 1.0;
    double ndc_y = 1.0 - (py + 0.5) / v->height * 2.0;
    *dx = ndc_x / D(v->focal_x);
    *dy = ndc_y / D(v->focal_y);
}

/* Intersect the pixel ray with triangle p (view space): returns the hit's
 * view z (or -1) and the barycentrics. */
static double ray_tri(const tgi_view *v, int px, int py, const double (*p)[3], double *b)
{
    double d[3], e1[3], e2[3], s[3], h[3], q[3], a, f, u, w, t;
    int k;
    pixel_ray(v, px, py, &d[0], &d[1]);
    d[2] = 1.0;
    for (k = 0; k < 3; k++) { e1[k] = p[1][k] - p[0][k]; e2[k] = p[2][k] - p[0][k]; s[k] = -p[0][k]; }
    h[0] = d[1] * e2[2] - d[2] * e2[1]; h[1] = d[2] * e2[0] - d[0] * e2[2]; h[2] = d[0] * e2[1] - d[1] * e2[0];
    a = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabs(a) < 1e-15) return -1;
    f = 1.0 / a;
    u = f * (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]);
    q[0] = s[1] * e1[2] - s[2] * e1[1]; q[1] = s[2] * e1[0] - s[0] * e1[2]; q[2] = s[0] * e1[1] - s[1] * e1[0];
    w = f * (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]);
    t = f * (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]);
    b[0] = 1 - u - w; b[1] = u; b[2] = w;
    return t; /* d has z = 1, so t is the view z */
}

/* Depth tolerance: relative float/fixed precision plus the depth change over
 * the snapping error (1/32 pixel) on a slope. */
static double depth_tol(const tgi_view *v, int px, int py, const double (*p)[3], double z)
{
    double b[3], zx = ray_tri(v, px + 1, py, p, b), zy = ray_tri(v, px, py + 1, p, b);
    double slope = fabs(zx - z) > fabs(zy - z) ? fabs(zx - z) : fabs(zy - z), size = 0;
    int k, d;
    /* the vertices and the view basis are rounded to the number type: the
     * world -> view transform is off by about |p| times its precision */
    for (k = 0; k < 3; k++)
        for (d = 0; d < 3; d++) size = fabs(p[k][d]) > size ? fabs(p[k][d]) : size;
    return (TG_FIXED ? 2e-4 : 2e-5) * z + slope * 0.05 + (TG_FIXED ? 4.0 / 65536 + size * 4e-5 : size * 4e-7);
}

/* ---------------------------------------------------------------------- */
/* fill rule                                                               */

static int check_exactly_once(const uint16_t *count, int w, int h)
{
    int i, bad = 0;
    for (i = 0; i < w * h; i++) {
        if (count[i] != 1) {
            if (bad < 5) fprintf(stderr, "pixel (%d, %d) covered %d times\n", i % w, i / w, count[i]);
            bad++;
        }
    }
    return bad;
}

/* Jittered grid of quads over and past the screen, each quad either split
 * by a diagonal (either one) or fanned around a random interior point, with
 * random winding: every pixel centre exactly once. */
static void grid_tiling(int w, int h, int cell_px16, int y0, int y1)
{
    int nx = (w * 16 + 6 * 16) / cell_px16 + 2, ny = (h * 16 + 6 * 16) / cell_px16 + 2;
    int32_t *gx = (int32_t *)malloc(sizeof(int32_t) * (size_t)(nx + 1) * (size_t)(ny + 1));
    int32_t *gy = (int32_t *)malloc(sizeof(int32_t) * (size_t)(nx + 1) * (size_t)(ny + 1));
    int32_t *xy = (int32_t *)malloc(sizeof(int32_t) * 6 * 4 * (size_t)nx * (size_t)ny);
    uint16_t *count = (uint16_t *)calloc((size_t)w * (size_t)h, sizeof(uint16_t));
    int i, j, t = 0, row;
    for (j = 0; j <= ny; j++)
        for (i = 0; i <= nx; i++) {
            int jit = cell_px16 / 3;
            int32_t x = -48 + i * cell_px16, y = -48 + j * cell_px16;
            /* keep the outer ring straight so the tiling covers the screen */
            if (i > 0 && i < nx) x += (int32_t)(rng() % (uint32_t)(2 * jit + 1)) - jit;
            if (j > 0 && j < ny) y += (int32_t)(rng() % (uint32_t)(2 * jit + 1)) - jit;
            gx[j * (nx + 1) + i] = x;
            gy[j * (nx + 1) + i] = y;
        }
    for (j = 0; j < ny; j++)
        for (i = 0; i < nx; i++) {
            int c[4], k, style = (int)(rng() % 3);
            int32_t px[4], py[4];
            c[0] = j * (nx + 1) + i; c[1] = c[0] + 1; c[2] = c[1] + nx + 1; c[3] = c[0] + nx + 1;
            for (k = 0; k < 4; k++) { px[k] = gx[c[k]]; py[k] = gy[c[k]]; }
            if (style < 2) {
                int a = style, tri[2][3];
                tri[0][0] = a; tri[0][1] = a + 1; tri[0][2] = (a + 2) & 3;
                tri[1][0] = a; tri[1][1] = (a + 2) & 3; tri[1][2] = (a + 3) & 3;
                for (k = 0; k < 2; k++) {
                    int l, rev = (int)(rng() & 1);
                    for (l = 0; l < 3; l++) {
                        int vtx = tri[k][rev ? 2 - l : l];
                        xy[t * 6 + 2 * l] = px[vtx];
                        xy[t * 6 + 2 * l + 1] = py[vtx];
                    }
                    t++;
                }
            } else {
                /* fan around a point inside the (convex) jittered quad */
                int32_t cj = cell_px16 / 10;
                int32_t cx = (px[0] + px[1] + px[2] + px[3]) / 4 + (int32_t)(rng() % (uint32_t)(2 * cj + 1)) - cj;
                int32_t cy = (py[0] + py[1] + py[2] + py[3]) / 4 + (int32_t)(rng() % (uint32_t)(2 * cj + 1)) - cj;
                for (k = 0; k < 4; k++) {
                    int rev = (int)(rng() & 1);
                    xy[t * 6 + 0] = cx; xy[t * 6 + 1] = cy;
                    xy[t * 6 + 2] = px[rev ? (k + 1) & 3 : k]; xy[t * 6 + 3] = py[rev ? (k + 1) & 3 : k];
                    xy[t * 6 + 4] = px[rev ? k : (k + 1) & 3]; xy[t * 6 + 5] = py[rev ? k : (k + 1) & 3];
                    t++;
                }
            }
        }
    tgi_raster_coverage_count(count, w, h, xy, t, y0, y1);
    for (row = 0; row < h; row++) {
        int x, want = row >= y0 && row < y1;
        for (x = 0; x < w; x++) {
            if (count[row * w + x] != want) {
                CHECK(0, "cell %d: pixel (%d, %d) covered %d times, want %d", cell_px16, x, row,
                      count[row * w + x], want);
                goto done;
            }
        }
    }
done:
    free(gx); free(gy); free(xy); free(count);
}

TEST(fill_rule_grid_tiling)
{
    static const int cells[] = { 5, 16, 23, 37, 160, 333 };
    size_t k;
    for (k = 0; k < sizeof cells / sizeof cells[0]; k++) grid_tiling(61, 47, cells[k], 0, 47);
    grid_tiling(61, 47, 29, 10, 30); /* row range respected */
}

/* Fans of random triangles around shared vertices, all covering a big
 * polygon around the screen. */
TEST(fill_rule_random_fans)
{
    enum { W = 53, H = 41, SPOKES = 40 };
    int fan;
    for (fan = 0; fan < 20; fan++) {
        int32_t xy[SPOKES * 6];
        uint16_t count[W * H];
        int32_t cx = (int32_t)(rng() % (W * 16)), cy = (int32_t)(rng() % (H * 16));
        double a0 = rnd() * 6.283;
        int k;
        int32_t sx[SPOKES], sy[SPOKES];
        memset(count, 0, sizeof count);
        /* spoke ends at random angles (sorted by construction) on a circle
         * 2000 px out, each shared by two neighbouring triangles */
        for (k = 0; k < SPOKES; k++) {
            double a = a0 + 6.283185307179586 * (k + 0.8 * rnd()) / SPOKES, r = 2000 * 16;
            sx[k] = cx + (int32_t)(r * cos(a));
            sy[k] = cy + (int32_t)(r * sin(a));
        }
        for (k = 0; k < SPOKES; k++) {
            int rev = (int)(rng() & 1), next = (k + 1) % SPOKES;
            int32_t ax = sx[k], ay = sy[k], bx = sx[next], by = sy[next];
            xy[k * 6 + 0] = cx; xy[k * 6 + 1] = cy;
            xy[k * 6 + 2] = rev ? bx : ax; xy[k * 6 + 3] = rev ? by : ay;
            xy[k * 6 + 4] = rev ? ax : bx; xy[k * 6 + 5] = rev ? ay : by;
        }
        tgi_raster_coverage_count(count, W, H, xy, SPOKES, 0, H);
        CHECK(check_exactly_once(count, W, H) == 0, "fan %d around (%d, %d)/16", fan, cx, cy);
    }
}

/* Triangles with edges exactly through pixel centres, horizontal and
 * vertical edges included: the top-left rule decides alone. */
TEST(fill_rule_on_pixel_centres)
{
    enum { W = 16, H = 12 };
    uint16_t count[W * H];
    int32_t xy[2 * 6 * 4];
    int t = 0, k;
    /* a 2x2 split of the screen at a pixel-centre line, each quad in two triangles */
    int32_t X[3] = { -16, 7 * 16 + 8, W * 16 + 16 }, Y[3] = { -16, 5 * 16 + 8, H * 16 + 16 };
    int i, j;
    memset(count, 0, sizeof count);
    for (j = 0; j < 2; j++)
        for (i = 0; i < 2; i++) {
            int32_t q[4][2] = { { X[i], Y[j] }, { X[i + 1], Y[j] }, { X[i + 1], Y[j + 1] }, { X[i], Y[j + 1] } };
            int tri[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
            for (k = 0; k < 2; k++) {
                int l;
                for (l = 0; l < 3; l++) { xy[t * 6 + 2 * l] = q[tri[k][l]][0]; xy[t * 6 + 2 * l + 1] = q[tri[k][l]][1]; }
                t++;
            }
        }
    tgi_raster_coverage_count(count, W, H, xy, t, 0, H);
    CHECK(check_exactly_once(count, W, H) == 0, "pixel-centre edges");
    /* a lone 1x1-pixel square through centres covers exactly one pixel */
    {
        int32_t sq[12] = { 3 * 16 + 8, 2 * 16 + 8, 4 * 16 + 8, 2 * 16 + 8, 4 * 16 + 8, 3 * 16 + 8,
                           3 * 16 + 8, 2 * 16 + 8, 4 * 16 + 8, 3 * 16 + 8, 3 * 16 + 8, 3 * 16 + 8 };
        int n = 0;
        memset(count, 0, sizeof count);
        tgi_raster_coverage_count(count, W, H, sq, 2, 0, H);
        for (k = 0; k < W * H; k++) n += count[k];
        CHECK(n == 1 && count[2 * W + 3] == 1, "unit square covers %d pixels", n);
    }
}

/* The fill rule restated pixel by pixel, independently of the rasterizer's
 * row walks: pixel (x, y) is covered when its centre (16 x + 8, 16 y + 8)
 * is strictly inside every edge, or on an edge that is a top or a left one
 * (y down: an edge going up, or a horizontal one going right, once the
 * triangle is ordered with positive area). */
static int brute_covers(const int32_t *t, int64_t px, int64_t py)
{
    int64_t x[3], y[3], area;
    int i;
    for (i = 0; i < 3; i++) { x[i] = t[2 * i]; y[i] = t[2 * i + 1]; }
    area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    if (area == 0) return 0;
    if (area < 0) {
        int64_t s = x[1]; x[1] = x[2]; x[2] = s;
        s = y[1]; y[1] = y[2]; y[2] = s;
    }
    for (i = 0; i < 3; i++) {
        int64_t ax = x[(i + 1) % 3], ay = y[(i + 1) % 3], dx = x[(i + 2) % 3] - ax, dy = y[(i + 2) % 3] - ay;
        int64_t e = dx * (py - ay) - dy * (px - ax);
        if (e < 0 || (e == 0 && !(dy < 0 || (dy == 0 && dx > 0)))) return 0;
    }
    return 1;
}

/* One random vertex coordinate (28.4) of the kinds the row walks treat
 * apart: near the screen, on pixel centres (fill-rule ties), far off it
 * (up to the documented +-2^19). */
static int32_t brute_coord(int side16, int32_t near, int kind)
{
    switch (kind) {
    case 0: return (int32_t)(rng() % (uint32_t)(side16 + 128)) - 64;            /* anywhere near */
    case 1: return 16 * (int32_t)(rng() % (uint32_t)(side16 / 16 + 4)) - 24;    /* a pixel centre */
    case 2: return near + (int32_t)(rng() % 41) - 20;                           /* a small or thin one */
    case 3: return near + (int32_t)(rng() % 2001) - 1000;                       /* tens of pixels */
    default: return (int32_t)(rng() % (1u << 20)) - (1 << 19);                  /* huge */
    }
}

/* Random triangles, one at a time (tgi_raster_coverage_count), against
 * brute_covers at every pixel: the same pixels exactly, whatever the
 * triangle's size, shape, winding or row range. */
TEST(fill_rule_matches_brute_force)
{
    enum { W = 45, H = 37, TRIS = 12000 };
    static uint16_t count[W * H];
    int t, bad = 0;
    for (t = 0; t < TRIS && bad < 5; t++) {
        int32_t tri[6];
        int k, x, y, y0 = 0, y1 = H, kind = (int)(rng() % 5);
        for (k = 0; k < 3; k++) {
            int kk = k == 0 || kind >= 4 ? kind : (int)(rng() % 5);
            tri[2 * k] = brute_coord(W * 16, k ? tri[0] : W * 8, kk == 2 || kk == 3 ? kk : kind == 4 ? 4 : kk);
            tri[2 * k + 1] = brute_coord(H * 16, k ? tri[1] : H * 8, kk == 2 || kk == 3 ? kk : kind == 4 ? 4 : kk);
        }
        switch (rng() % 8) {   /* degenerate and axis-aligned ones */
        case 0: tri[4] = tri[0]; tri[5] = tri[1]; break;                          /* two vertices coincide */
        case 1: tri[4] = 2 * tri[2] - tri[0]; tri[5] = 2 * tri[3] - tri[1]; break; /* collinear */
        case 2: tri[3] = tri[1]; break;                                           /* a horizontal edge */
        case 3: tri[2] = tri[0]; break;                                           /* a vertical edge */
        case 4: tri[4] = tri[2] + (tri[2] - tri[0]) / 7 + 1; tri[5] = tri[3] + (tri[3] - tri[1]) / 7; break; /* a sliver */
        default: break;
        }
        for (k = 0; k < 6; k++) tri[k] = tri[k] < -(1 << 19) ? -(1 << 19) : tri[k] > (1 << 19) ? 1 << 19 : tri[k];
        if (rng() % 4 == 0) { y0 = (int)(rng() % H); y1 = y0 + (int)(rng() % (H - y0 + 1)); }
        memset(count, 0, sizeof count);
        tgi_raster_coverage_count(count, W, H, tri, 1, y0, y1);
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                int want = y >= y0 && y < y1 && brute_covers(tri, 16 * x + 8, 16 * y + 8);
                if (count[y * W + x] != want && bad++ < 5)
                    CHECK(0, "triangle %d (%d %d, %d %d, %d %d)/16, rows [%d, %d): pixel (%d, %d) covered %d, want %d",
                          t, tri[0], tri[1], tri[2], tri[3], tri[4], tri[5], y0, y1, x, y, count[y * W + x], want);
            }
    }
    CHECK(bad == 0, "%d pixels differ", bad);
}

/* ---------------------------------------------------------------------- */
/* the G-buffer path                                                       */

/* The NX by NZ cells of the grid of points P ((NZ + 1) rows of NX + 1
 * points, x y z each), two triangles a cell (corners 0 1 2 and 0 2 3 going
 * round it); each triangle's object is its index in m when IDS, else 0. */
static void add_grid(mesh *m, const tgi_view *v, const double *P, int nx, int nz, int ids)
{
    int i, j, k;
    for (j = 0; j < nz; j++)
        for (i = 0; i < nx; i++) {
            const double *c[4];
            double a[3][3], b[3][3];
            c[0] = P + 3 * (j * (nx + 1) + i);
            c[1] = c[0] + 3;
            c[2] = c[1] + 3 * (nx + 1);
            c[3] = c[0] + 3 * (nx + 1);
            for (k = 0; k < 3; k++) {
                a[0][k] = c[0][k]; a[1][k] = c[1][k]; a[2][k] = c[2][k];
                b[0][k] = c[0][k]; b[1][k] = c[2][k]; b[2][k] = c[3][k];
            }
            add_tri_view(m, v, (const double(*)[3])a, NULL, 0, ids ? m->n : 0);
            add_tri_view(m, v, (const double(*)[3])b, NULL, 0, ids ? m->n : 0);
        }
}

/* A jittered grid of quads on a tilted plane in front of the camera (past
 * the screen edges), distinct object ids: no pixel left as sky, and every
 * pixel clearly inside a triangle holds that triangle's id. */
/* A ground plane seen from above, once as a quad of +-900 and once of
 * +-20000 units, the far plane at 100: both show the same floor, pixel for
 * pixel.  In Q16.16 the big quad's clip coordinates (20000 fx sideways,
 * 19000 deep) and the clipper's differences and guard products saturated,
 * and it clipped to nothing: every pixel sky (raster.c
 * gbuffer_wide_triangle clips it in 64 bits now).  Also at a 5-degree
 * field of view, where +-3000 was already lost. */
static void floor_quad(mesh *m, double e)
{
    const double x[4] = { -e, -e, e, e }, z[4] = { -e, e, e, -e };
    static const int tri[6] = { 0, 1, 2, 0, 2, 3 };
    int k;
    for (k = 0; k < 6; k++) {
        m->pos[3 * m->n + k % 3 + (k / 3) * 3] = V(x[tri[k]], 0, z[tri[k]]);
        m->nrm[3 * m->n + k % 3 + (k / 3) * 3] = V(0, 1, 0);
    }
    m->mat[m->n] = m->mat[m->n + 1] = 0;
    m->n += 2;
}

TEST(far_ground_plane_in_fixed_point)
{
    static const double fovs[2] = { 60, 5 }, big[2] = { 20000, 3000 };
    int f;
    for (f = 0; f < 2; f++) {
        tgi_view v;
        mesh *small = mesh_new(), *large = mesh_new();
        gbuf a, b;
        int i, floor = 0, differ = 0, depth_off = 0;
        tgi_view_make(&v, V(0, 3, 12), V(0, 0, 0), V(0, 1, 0), R(fovs[f] * 3.14159265358979 / 180.0), R(0.05), R(100),
                      32, 24);
        floor_quad(small, 900);
        floor_quad(large, big[f]);
        gbuf_draw(&a, &v, small);
        gbuf_draw(&b, &v, large);
        for (i = 0; i < 32 * 24; i++) {
            if (gsky(&a, i) != gsky(&b, i)) { differ++; continue; }
            if (gsky(&a, i)) continue;
            floor++;
            if (fabs(gdepth(&a, i) - gdepth(&b, i)) > 1e-3 * gdepth(&a, i)) depth_off++;
        }
        CHECK(floor >= 200, "fov %g: %d floor pixels", fovs[f], floor);
        CHECK(differ == 0, "fov %g: %d pixels floor in one quad and sky in the other", fovs[f], differ);
        CHECK(depth_off == 0, "fov %g: %d depths apart by more than 0.1%%", fovs[f], depth_off);
        drawn_free(&a, small);
        drawn_free(&b, large);
    }
}

/* A ground plane that runs far past the screen, clipped by the guard band
 * and the near plane, seen from above at an angle: every floor pixel's
 * depth is the ray's hit on the plane y = 0 within 2e-4 of it (the
 * rounding of the view basis; and the slope across the pixel).  In Q16.16
 * a +-200 floor came out 1.4e-3 deep (the clipper's 16-bit fraction on its
 * 400-unit edges and the 32-bit view transform of its far vertices), enough
 * to sink the floor under itself by more than the shadow rays' offset: a
 * wedge of false shadow over a third of the image (PSNR 7.7 dB against
 * float).  Clipped triangles are now drawn from 64 bits, as the far ones. */
TEST(clipped_ground_plane_depth)
{
    static const double halves[3] = { 50, 200, 900 };
    int f;
    for (f = 0; f < 3; f++) {
        enum { W = 80, H = 60 };
        tgi_view v;
        mesh *m = mesh_new();
        gbuf g;
        int i, j, floor_px = 0, bad = 0;
        double worst = 0;
        tgi_view_make(&v, V(1.684, 4, 6.316), V(0, 0, 0), V(0, 1, 0), R(60 * 3.14159265358979 / 180.0), R(0.05), R(1000),
                      W, H);
        floor_quad(m, halves[f]);
        gbuf_draw(&g, &v, m);
        for (j = 0; j < H; j++)
            for (i = 0; i < W; i++) {
                double dx, dy, dir_y, z, err, slope;
                int k;
                if (gsky(&g, j * W + i)) continue;
                pixel_ray(&v, i, j, &dx, &dy);
                dir_y = D(v.forward.y) + dx * D(v.right.y) + dy * D(v.up.y);
                if (dir_y >= 0) continue;
                z = -D(v.eye.y) / dir_y;
                for (slope = 0, k = 0; k < 2; k++) {   /* the depth's change to the next pixel */
                    double ex, ey, zn;
                    pixel_ray(&v, i + (k == 0), j + (k == 1), &ex, &ey);
                    zn = -D(v.eye.y) / (D(v.forward.y) + ex * D(v.right.y) + ey * D(v.up.y));
                    if (zn > 0 && fabs(zn - z) > slope) slope = fabs(zn - z);
                }
                floor_px++;
                err = fabs(gdepth(&g, j * W + i) - z);
                if (err / z > worst) worst = err / z;
                if (err > 2e-4 * z + 0.05 * slope + 4.0 / 65536) bad++;
            }
        CHECK(floor_px > W * H / 2, "+-%g: %d floor pixels", halves[f], floor_px);
        CHECK(bad == 0, "+-%g: %d floor pixels off the plane's depth (worst rel %g)", halves[f], bad, worst);
        drawn_free(&g, m);
    }
}

TEST(gbuffer_tiling_ids)
{
    enum { W = 80, H = 60, N = 12 };
    tgi_view v = view_at(W, H, 60);
    mesh *m = mesh_new();
    gbuf g;
    double P[N + 1][N + 1][3];
    int i, j, k, sky = 0, wrong = 0, checked = 0;
    for (j = 0; j <= N; j++)
        for (i = 0; i <= N; i++) {
            double x = -6 + 12.0 * i / N + ((i > 0 && i < N) ? (rnd() - 0.5) * 0.4 : 0);
            double y = -5 + 10.0 * j / N + ((j > 0 && j < N) ? (rnd() - 0.5) * 0.4 : 0);
            P[j][i][0] = x; P[j][i][1] = y; P[j][i][2] = 4 + 0.3 * x + 0.2 * y;
        }
    add_grid(m, &v, &P[0][0][0], N, N, 1);
    gbuf_draw(&g, &v, m);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            int t, inside = -1;
            sky += gsky(&g, j * W + i);
            for (t = 0; t < m->n; t++) {
                double tri[3][3], bc[3];
                int q = t / 2, qi = q % N, qj = q / N;
                for (k = 0; k < 3; k++) {
                    if (t % 2 == 0) {
                        tri[0][k] = P[qj][qi][k]; tri[1][k] = P[qj][qi + 1][k]; tri[2][k] = P[qj + 1][qi + 1][k];
                    } else {
                        tri[0][k] = P[qj][qi][k]; tri[1][k] = P[qj + 1][qi + 1][k]; tri[2][k] = P[qj + 1][qi][k];
                    }
                }
                if (ray_tri(&v, i, j, (const double(*)[3])tri, bc) > 0 && bc[0] > 0.02 && bc[1] > 0.02 && bc[2] > 0.02)
                    inside = t;
            }
            if (inside >= 0) {
                checked++;
                if (g.gb.object[j * W + i] != inside) wrong++;
            }
        }
    CHECK(sky == 0, "%d sky pixels in a closed tiling", sky);
    CHECK(wrong == 0 && checked > W * H / 2, "%d of %d pixels hold the wrong object id", wrong, checked);
    drawn_free(&g, m);
}

/* Render one view-space triangle; check every pixel against the ray cast:
 * drawn where clearly inside (and in front of the near plane), not drawn
 * where clearly outside, depth and normal right. */
static void check_triangle(const double (*p)[3], int material, int expect_drawn, const char *what)
{
    enum { W = 64, H = 48 };
    tgi_view v = view_at(W, H, 70);
    mesh *m = mesh_new();
    gbuf g;
    int i, j, drawn = 0, miss = 0, extra = 0, bad_depth = 0, bad_normal = 0;
    double worst = 0;
    add_tri_view(m, &v, p, NULL, material, 7);
    gbuf_draw(&g, &v, m);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            double b[3], z = ray_tri(&v, i, j, p, b);
            int idx = j * W + i, is = !gsky(&g, idx);
            double margin = 0.01, zn = D(v.znear);
            int in = z > zn * 1.01 && b[0] > margin && b[1] > margin && b[2] > margin;
            int out = z < zn * 0.99 || b[0] < -margin || b[1] < -margin || b[2] < -margin;
            drawn += is;
            if (expect_drawn && in && !is) miss++;
            if ((!expect_drawn || out) && is) extra++;
            if (is && in) {
                double err = fabs(gdepth(&g, idx) - z), nlen;
                double nv[3], nw[3], dotv;
                if (err > depth_tol(&v, i, j, p, z)) bad_depth++;
                if (err > worst) worst = err;
                /* the normal faces the viewer: dot(n, eye - point) > 0 */
                nv[0] = D(gnormal(&g, idx).x); nv[1] = D(gnormal(&g, idx).y); nv[2] = D(gnormal(&g, idx).z);
                nlen = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
                {
                    tg_vec3 hit = view_to_world(&v, 0, 0, 0), pt;
                    double px, py;
                    pixel_ray(&v, i, j, &px, &py);
                    pt = view_to_world(&v, px * z, py * z, z);
                    nw[0] = D(hit.x) - D(pt.x); nw[1] = D(hit.y) - D(pt.y); nw[2] = D(hit.z) - D(pt.z);
                }
                dotv = nv[0] * nw[0] + nv[1] * nw[1] + nv[2] * nw[2];
                if (fabs(nlen - 1) > (TG_FIXED ? 2e-4 : 1e-5) || !(dotv > 0)) bad_normal++;
                CHECK(gmaterial(&g, idx) == material && g.gb.object[idx] == 7, "%s: surface attributes", what);
            }
        }
    CHECK(miss == 0, "%s: %d pixels inside not drawn", what, miss);
    CHECK(extra == 0, "%s: %d pixels drawn outside", what, extra);
    CHECK(bad_depth == 0, "%s: %d pixels with wrong depth (worst %g)", what, bad_depth, worst);
    CHECK(bad_normal == 0, "%s: %d pixels with a non-unit or back-facing normal", what, bad_normal);
    CHECK(!expect_drawn || drawn > 20, "%s: only %d pixels drawn", what, drawn);
    drawn_free(&g, m);
}

TEST(front_back_twosided)
{
    const double ccw[3][3] = { { -1, -1, 3 }, { 1, -0.8, 3.5 }, { 0, 1, 2.5 } };
    const double cw[3][3] = { { -1, -1, 3 }, { 0, 1, 2.5 }, { 1, -0.8, 3.5 } };
    check_triangle(ccw, 0, 1, "front face");
    check_triangle(cw, 0, 0, "back face culled");
    check_triangle(cw, 1, 1, "twosided back face");
    check_triangle(ccw, 1, 1, "twosided front face");
}

TEST(near_plane_clipping)
{
    /* a floor triangle with one vertex behind the camera */
    const double floor1[3][3] = { { -2, -1, 4 }, { 2, -1, 4 }, { 0.3, -1, -3 } };
    const double floor1r[3][3] = { { -2, -1, 4 }, { 0.3, -1, -3 }, { 2, -1, 4 } };
    /* two vertices behind, one in front */
    const double two_behind[3][3] = { { -3, -0.5, -2 }, { 0.5, 0.7, 6 }, { 3, -0.2, -1 } };
    const double two_behind_r[3][3] = { { -3, -0.5, -2 }, { 3, -0.2, -1 }, { 0.5, 0.7, 6 } };
    /* wholly behind: a naive projection would mirror it onto the screen */
    const double behind[3][3] = { { -1, -1, -3 }, { 1, -1, -3 }, { 0, 1, -3 } };
    const double behind_r[3][3] = { { -1, -1, -3 }, { 0, 1, -3 }, { 1, -1, -3 } };
    /* crossing w = 0 exactly at a vertex */
    const double at_eye[3][3] = { { 0.5, -2, 0 }, { 1, -1, 3 }, { -1, -1, 3 } };
    check_triangle(floor1[0][0] < 0 ? floor1 : floor1r, 1, 1, "one vertex behind (twosided)");
    check_triangle(floor1r, 1, 1, "one vertex behind, reversed");
    check_triangle(two_behind, 1, 1, "two vertices behind");
    check_triangle(two_behind_r, 1, 1, "two vertices behind, reversed");
    check_triangle(behind, 1, 0, "wholly behind");
    check_triangle(behind_r, 1, 0, "wholly behind, reversed");
    check_triangle(at_eye, 1, 1, "vertex at the eye");
}

TEST(big_triangle_past_edges)
{
    /* far past the screen on every side: fills it exactly, constant depth */
    const double big[3][3] = { { -900, -700, 5 }, { 900, -700, 5 }, { 0, 900, 5 } };
    const double tilted[3][3] = { { -300, -200, 30 }, { 300, -200, 5 }, { 0, 300, 12 } };
    enum { W = 64, H = 48 };
    tgi_view v = view_make(W, H, 70, 1);
    mesh *m = mesh_new();
    gbuf g;
    int i, sky = 0, bad = 0;
    add_tri_view(m, &v, big, NULL, 0, 1);
    gbuf_draw(&g, &v, m);
    for (i = 0; i < W * H; i++) {
        sky += gsky(&g, i);
        if (fabs(gdepth(&g, i) - 5.0) > (TG_FIXED ? 3.0 / 65536 : 5e-6)) bad++;
    }
    CHECK(sky == 0, "%d pixels left uncovered", sky);
    CHECK(bad == 0, "%d pixels not at depth 5 (e.g. %.9g)", bad, gdepth(&g, 0));
    drawn_free(&g, m);
    check_triangle(big, 0, 1, "big facing triangle");
    check_triangle(tilted, 0, 1, "big tilted triangle");
}

/* A screen-filling quad at a known depth, and a floor from near to far
 * (perspective-correct depth vs the analytic ray cast). */
TEST(depth_plane_and_floor)
{
    enum { W = 96, H = 72 };
    tgi_view v = view_make(W, H, 60, 1);
    mesh *m = mesh_new();
    gbuf g;
    const double q0[3][3] = { { -5, -5, 3 }, { 5, -5, 3 }, { 5, 5, 3 } };
    const double q1[3][3] = { { -5, -5, 3 }, { 5, 5, 3 }, { -5, 5, 3 } };
    const double f0[3][3] = { { -400, -1, 0.5 }, { 400, -1, 0.5 }, { 400, -1, 900 } };
    const double f1[3][3] = { { -400, -1, 0.5 }, { 400, -1, 900 }, { -400, -1, 900 } };
    int i, j, bad = 0, sky = 0, floor_px = 0;
    double worst = 0;
    add_tri_view(m, &v, q0, NULL, 0, 0);
    add_tri_view(m, &v, q1, NULL, 0, 0);
    gbuf_draw(&g, &v, m);
    for (i = 0; i < W * H; i++) {
        sky += gsky(&g, i);
        if (fabs(gdepth(&g, i) - 3.0) > (TG_FIXED ? 2.0 / 65536 : 3e-6)) bad++;
    }
    CHECK(sky == 0 && bad == 0, "plane at depth 3: %d sky, %d off", sky, bad);
    gbuf_free(&g);

    m->n = 0;
    add_tri_view(m, &v, f0, NULL, 0, 0);
    add_tri_view(m, &v, f1, NULL, 0, 0);
    gbuf_draw(&g, &v, m);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            double b[3], z0 = ray_tri(&v, i, j, f0, b), z1 = ray_tri(&v, i, j, f1, b), z = -1, err;
            int idx = j * W + i;
            if (z0 < 0) z0 = -1;
            if (z1 < 0) z1 = -1;
            (void)b;
            if (gsky(&g, idx)) continue;
            floor_px++;
            /* the plane y = -1 hit by this pixel's ray */
            {
                double dx, dy;
                pixel_ray(&v, i, j, &dx, &dy);
                if (dy < 0) z = -1.0 / dy;
            }
            if (z < 0 || z > 850) continue;
            err = fabs(gdepth(&g, idx) - z);
            if (err / z > worst) worst = err / z;
            if (err > depth_tol(&v, i, j, f0, z)) bad++;
        }
    CHECK(floor_px > W * H / 3, "floor drew %d pixels", floor_px);
    CHECK(bad == 0, "floor: %d pixels off the analytic depth (worst rel %g)", bad, worst);
    drawn_free(&g, m);
}

/* A floor grid crossing the near plane and running far past the screen
 * edges (near-plane and guard-band clipping of shared edges): no pixel
 * whose ray clearly hits the floor is left as sky, and depths match. */
TEST(clipped_tiling_watertight)
{
    enum { W = 96, H = 72, NX = 12, NZ = 12 };
    drawing d = drawing_at(W, H, 90, 1);
    static double P[NZ + 1][NX + 1][3];
    int i, j, holes = 0, bad = 0, checked = 0;
    for (j = 0; j <= NZ; j++)
        for (i = 0; i <= NX; i++) {
            /* uneven spacing so the near plane and screen edges cut cells anywhere */
            double x = -300 + 600.0 * i / NX + ((i > 0 && i < NX) ? (rnd() - 0.5) * 20 : 0);
            double z = -40 + 440.0 * (j * j) / (NZ * NZ) + ((j > 0 && j < NZ) ? (rnd() - 0.5) * 0.5 : 0);
            P[j][i][0] = x; P[j][i][1] = -1; P[j][i][2] = z;
        }
    add_grid(d.m, &d.v, &P[0][0][0], NX, NZ, 0);
    drawing_draw(&d);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            double dx, dy, z;
            pixel_ray(&d.v, i, j, &dx, &dy);
            if (dy >= 0) continue;
            z = -1.0 / dy;                         /* ray meets y = -1 at view z */
            if (z > 350 || fabs(dx * z) > 250) continue;
            checked++;
            if (gsky(&d.g, j * W + i)) { holes++; continue; }
            /* depth changes by 2 z^2 / (H focal_y) per pixel row here; snapping
             * moves vertices by up to 1/32 pixel */
            if (fabs(gdepth(&d.g, j * W + i) - z) > (TG_FIXED ? 3e-4 : 5e-5) * z + 0.05 * 2 * z * z / (H * D(d.v.focal_y))) {
                if (bad < 3) fprintf(stderr, "  (%d, %d): depth %.6g, want %.6g\n", i, j, gdepth(&d.g, j * W + i), z);
                bad++;
            }
        }
    CHECK(checked > W * H / 3, "checked only %d pixels", checked);
    CHECK(holes == 0, "%d holes in a clipped floor tiling", holes);
    CHECK(bad == 0, "%d floor pixels off the analytic depth", bad);
    drawing_free(&d);
}

/* Vertex normals interpolate perspective-correctly and come out unit. */
TEST(normal_interpolation)
{
    enum { W = 64, H = 48 };
    drawing d = drawing_at(W, H, 70, 0);
    const double p[3][3] = { { -3, -2, 2 }, { 3, -2, 9 }, { 0, 3, 4 } };
    double n[3][3] = { { -0.6, 0, -0.8 }, { 0.48, 0.6, -0.64 }, { 0, 0.8, -0.6 } };
    int i, j, k, bad = 0, count = 0;
    double worst = 0;
    add_tri_view(d.m, &d.v, p, (const double(*)[3])n, 0, 0);
    drawing_draw(&d);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            double b[3], z = ray_tri(&d.v, i, j, p, b), e[3], len = 0, err = 0;
            int idx = j * W + i;
            tg_vec3 ew;
            if (gsky(&d.g, idx) || z < 0 || b[0] < 0.01 || b[1] < 0.01 || b[2] < 0.01) continue;
            for (k = 0; k < 3; k++) e[k] = b[0] * n[0][k] + b[1] * n[1][k] + b[2] * n[2][k];
            len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            ew = dir_to_world(&d.v, e[0] / len, e[1] / len, e[2] / len);
            err = fabs(D(gnormal(&d.g, idx).x) - D(ew.x)) + fabs(D(gnormal(&d.g, idx).y) - D(ew.y)) + fabs(D(gnormal(&d.g, idx).z) - D(ew.z));
            if (err > worst) worst = err;
            if (err > 0.01) bad++;
            count++;
        }
    CHECK(count > 100 && bad == 0, "%d of %d normals off the perspective-correct value (worst %g)", bad, count, worst);
    drawing_free(&d);
}

TEST(zero_area_skipped)
{
    enum { W = 32, H = 24 };
    drawing d = drawing_at(W, H, 70, 0);
    const double line[3][3] = { { -1, -1, 3 }, { 0, 0, 3 }, { 1, 1, 3 } };
    const double point[3][3] = { { 0.1, 0.1, 3 }, { 0.1, 0.1, 3 }, { 0.1, 0.1, 3 } };
    const double dup[3][3] = { { -1, -1, 3 }, { -1, -1, 3 }, { 1, 0.5, 3 } };
    const double edge_on[3][3] = { { 0, -1, 2 }, { 0, 1, 3 }, { 0, -1, 5 } }; /* plane x = 0 through the eye */
    int i, drawn = 0;
    add_tri_view(d.m, &d.v, line, NULL, 1, 0);
    add_tri_view(d.m, &d.v, point, NULL, 1, 0);
    add_tri_view(d.m, &d.v, dup, NULL, 1, 0);
    add_tri_view(d.m, &d.v, edge_on, NULL, 1, 0);
    drawing_draw(&d);
    for (i = 0; i < W * H; i++) drawn += !gsky(&d.g, i);
    CHECK(drawn == 0, "zero-area triangles drew %d pixels", drawn);
    drawing_free(&d);
}

/* Garbage in (NaN, infinities, the largest values) draws nothing wrong:
 * no crash, every written depth finite and positive, normals unit. */
TEST(hostile_coordinates)
{
    enum { W = 40, H = 30 };
    drawing d = drawing_at(W, H, 70, 0);
    double big = TG_FIXED ? 32000.0 : 3e38;
    double vals[] = { 0, 1, -1, 5, 1e-30, -3, 0, 2 };
    int t, k, i, bad = 0;
    for (t = 0; t < 400; t++) {
        for (k = 0; k < 3; k++) {
            double c[3];
            int a;
            for (a = 0; a < 3; a++) {
                int pick = (int)(rng() % 12);
                c[a] = pick < 8 ? vals[pick] * (1 + rnd()) : pick == 8 ? big : pick == 9 ? -big
                     : pick == 10 ? (TG_FIXED ? big : (double)INFINITY) : (TG_FIXED ? -big : (double)NAN);
            }
            d.m->pos[3 * d.m->n + k] = V(c[0], c[1], c[2]);
            d.m->nrm[3 * d.m->n + k] = V(0, 0, -1);
        }
        d.m->mat[d.m->n] = (uint16_t)(t & 1);
        d.m->obj[d.m->n] = 0;
        d.m->n++;
    }
    drawing_draw(&d);
    for (i = 0; i < W * H; i++) {
        double z = gdepth(&d.g, i);
        if (gsky(&d.g, i)) continue;
        if (!(z > 0 && z < 1e30)) bad++;
    }
    CHECK(bad == 0, "%d pixels with a non-finite or non-positive depth", bad);
    drawing_free(&d);
}

/* A closed sphere: nearest wins, normals unit and facing the viewer, and
 * rendering in row bands gives the same bytes as one pass. */
static void add_sphere(mesh *m, const tgi_view *v, double cx, double cy, double cz, double r, int seg, int obj)
{
    int i, j, k;
    for (j = 0; j < seg; j++)
        for (i = 0; i < 2 * seg; i++) {
            double th[2] = { 3.14159265358979 * j / seg, 3.14159265358979 * (j + 1) / seg };
            double ph[2] = { 3.14159265358979 * i / seg, 3.14159265358979 * (i + 1) / seg };
            double P[4][3], N[4][3];
            int c;
            for (c = 0; c < 4; c++) {
                double t = th[c >> 1], f = ph[(c & 1) ^ (c >> 1)];
                N[c][0] = sin(t) * cos(f); N[c][1] = cos(t); N[c][2] = sin(t) * sin(f);
                P[c][0] = cx + r * N[c][0]; P[c][1] = cy + r * N[c][1]; P[c][2] = cz + r * N[c][2];
            }
            {
                int tris[2][3] = { { 0, 1, 2 }, { 0, 2, 3 } };
                for (k = 0; k < 2; k++) {
                    double tp[3][3], tn[3][3];
                    int l, d;
                    for (l = 0; l < 3; l++)
                        for (d = 0; d < 3; d++) { tp[l][d] = P[tris[k][l]][d]; tn[l][d] = N[tris[k][l]][d]; }
                    /* outward winding: swap when the face normal points inward */
                    {
                        double e1[3], e2[3], cr[3], dot;
                        for (d = 0; d < 3; d++) { e1[d] = tp[1][d] - tp[0][d]; e2[d] = tp[2][d] - tp[0][d]; }
                        cr[0] = e1[1] * e2[2] - e1[2] * e2[1];
                        cr[1] = e1[2] * e2[0] - e1[0] * e2[2];
                        cr[2] = e1[0] * e2[1] - e1[1] * e2[0];
                        dot = cr[0] * tn[0][0] + cr[1] * tn[0][1] + cr[2] * tn[0][2];
                        if (fabs(dot) < 1e-12) continue; /* pole degenerate */
                        /* view space is left-handed: a front face is clockwise in it */
                        if (dot > 0) {
                            for (d = 0; d < 3; d++) { double s = tp[1][d]; tp[1][d] = tp[2][d]; tp[2][d] = s; s = tn[1][d]; tn[1][d] = tn[2][d]; tn[2][d] = s; }
                        }
                    }
                    add_tri_view(m, v, (const double(*)[3])tp, (const double(*)[3])tn, 0, obj);
                }
            }
        }
}

TEST(sphere_nearest_and_rows)
{
    enum { W = 80, H = 60 };
    tgi_view v = view_at(W, H, 60);
    mesh *m = mesh_new();
    gbuf g, h;
    int i, j, bad_n = 0, bad_z = 0, drawn = 0, diff = 0;
    add_sphere(m, &v, 0.3, 0.1, 5, 1.5, 24, 1);
    add_sphere(m, &v, -0.8, -0.3, 7, 2.0, 16, 2); /* partly behind the first */
    gbuf_alloc(&g, W, H);
    gbuf_alloc(&h, W, H);
    tgi_raster_gbuffer(&g.gb, &v, mesh_rm(m), 0, H);
    for (i = 0; i < 5; i++) tgi_raster_gbuffer(&h.gb, &v, mesh_rm(m), i * H / 5, (i + 1) * H / 5);
    for (j = 0; j < H; j++)
        for (i = 0; i < W; i++) {
            int idx = j * W + i;
            double dx, dy, best = -1, nl;
            int s, grazing = 0;
            if (gsky(&g, idx)) continue;
            drawn++;
            nl = sqrt(D(gnormal(&g, idx).x) * D(gnormal(&g, idx).x) + D(gnormal(&g, idx).y) * D(gnormal(&g, idx).y) + D(gnormal(&g, idx).z) * D(gnormal(&g, idx).z));
            if (fabs(nl - 1) > (TG_FIXED ? 2e-4 : 1e-5)) bad_n++;
            /* analytic nearest sphere hit (the mesh is inscribed: within its sagitta) */
            pixel_ray(&v, i, j, &dx, &dy);
            for (s = 0; s < 2; s++) {
                double c[3] = { s ? -0.8 : 0.3, s ? -0.3 : 0.1, s ? 7 : 5 }, r = s ? 2.0 : 1.5;
                double a = dx * dx + dy * dy + 1, bb = -2 * (dx * c[0] + dy * c[1] + c[2]);
                double cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2] - r * r, disc = bb * bb - 4 * a * cc, t;
                if (disc < 0) continue;
                t = (-bb - sqrt(disc)) / (2 * a);
                if (best < 0 || t < best) {
                    /* cosine between the sphere normal and the ray: skip grazing hits,
                     * where the inscribed mesh and the sphere part ways */
                    double hp[3] = { dx * t - c[0], dy * t - c[1], t - c[2] };
                    best = t;
                    grazing = -(hp[0] * dx + hp[1] * dy + hp[2]) / (r * sqrt(a)) < 0.3;
                }
            }
            if (best > 0 && !grazing && fabs(gdepth(&g, idx) - best) > 0.06) bad_z++;
        }
    for (i = 0; i < W * H; i++)
        if (!gsame(&g, &h, i)) diff++;
    CHECK(drawn > 500, "sphere drew %d pixels", drawn);
    CHECK(bad_n == 0, "%d non-unit normals", bad_n);
    CHECK(bad_z == 0, "%d pixels not at the nearest sphere", bad_z);
    CHECK(diff == 0, "row bands differ from one pass at %d pixels", diff);
    /* rows outside the range are untouched */
    tgi_gbuffer_clear_rows(&h.gb, 0, H);
    tgi_raster_gbuffer(&h.gb, &v, mesh_rm(m), 20, 30);
    for (i = 0, diff = 0; i < W * H; i++)
        if ((i / W < 20 || i / W >= 30) && !gsky(&h, i)) diff++;
    CHECK(diff == 0, "%d pixels written outside rows [20, 30)", diff);
    gbuf_free(&g);
    gbuf_free(&h);
    free(m);
}

/* ---------------------------------------------------------------------- */
/* depth only                                                              */

static void set_row4(tgi_mat4 *m, int r, double a, double b, double c, double d)
{
    m->m[r * 4 + 0] = R(a); m->m[r * 4 + 1] = R(b); m->m[r * 4 + 2] = R(c); m->m[r * 4 + 3] = R(d);
}

/* Quad q (a planar convex loop, any order) facing outward along `out`
 * (view coordinates), as two triangles of `material`. */
static void add_quad_out(mesh *m, const tgi_view *v, double q[4][3], const double out[3], int material)
{
    double e1[3], e2[3], c[3], t[3][3], r[4][3];
    int k, j, rev;
    for (k = 0; k < 3; k++) { e1[k] = q[1][k] - q[0][k]; e2[k] = q[2][k] - q[0][k]; }
    c[0] = e1[1] * e2[2] - e1[2] * e2[1]; c[1] = e1[2] * e2[0] - e1[0] * e2[2]; c[2] = e1[0] * e2[1] - e1[1] * e2[0];
    /* the view basis is left-handed: a front face's e1 x e2 points away from the viewer */
    rev = c[0] * out[0] + c[1] * out[1] + c[2] * out[2] > 0;
    for (k = 0; k < 4; k++) for (j = 0; j < 3; j++) r[k][j] = q[rev ? 3 - k : k][j];
    for (j = 0; j < 3; j++) { t[0][j] = r[0][j]; t[1][j] = r[1][j]; t[2][j] = r[2][j]; }
    add_tri_view(m, v, (const double (*)[3])t, NULL, material, 0);
    for (j = 0; j < 3; j++) { t[1][j] = r[2][j]; t[2][j] = r[3][j]; }
    add_tri_view(m, v, (const double (*)[3])t, NULL, material, 0);
}

/* The layers the ray through pixel (px, py) meets in layers_scene: the box
 * [-1, 1] x [-1, 1] x [4, 6] (view coordinates) in front of the wall z = 9:
 * front depth, back-face depth (0: none) and the depth behind it (0: none). */
static void layers_exact(const tgi_view *v, double px, double py, double z[3])
{
    double d[3], tn = 0, tf = 1e30;
    const double lo[3] = { -1, -1, 4 }, hi[3] = { 1, 1, 6 };
    int k;
    d[0] = ((px + 0.5) / v->width * 2.0 - 1.0) / D(v->focal_x);
    d[1] = (1.0 - (py + 0.5) / v->height * 2.0) / D(v->focal_y);
    d[2] = 1.0;
    for (k = 0; k < 3; k++) {
        double t0 = lo[k] / d[k], t1 = hi[k] / d[k], a = t0 < t1 ? t0 : t1, b = t0 < t1 ? t1 : t0;
        if (a > tn) tn = a;
        if (b < tf) tf = b;
    }
    if (tn < tf) { z[0] = tn; z[1] = tf; z[2] = 9; }
    else { z[0] = 9; z[1] = 0; z[2] = 0; }
}

static void layers_scene(mesh *m, const tgi_view *v)
{
    const double lo[3] = { -1, -1, 4 }, hi[3] = { 1, 1, 6 };
    double q[4][3], out[3];
    int a, side, k;
    for (a = 0; a < 3; a++)           /* the box's six faces, outward */
        for (side = 0; side < 2; side++) {
            int u = (a + 1) % 3, w = (a + 2) % 3;
            for (k = 0; k < 4; k++) {
                q[k][a] = side ? hi[a] : lo[a];
                q[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
                q[k][w] = k >= 2 ? hi[w] : lo[w];
            }
            out[0] = out[1] = out[2] = 0;
            out[a] = side ? 1 : -1;
            add_quad_out(m, v, q, out, 0);
        }
    {   /* the wall, one-sided, facing the camera */
        double wall[4][3] = { { -40, -40, 9 }, { 40, -40, 9 }, { 40, 40, 9 }, { -40, 40, 9 } };
        const double toward[3] = { 0, 0, -1 };
        add_quad_out(m, v, wall, toward, 0);
    }
}

/* The G-buffer's second and third depth layers (request.depth_layers,
 * raster.h): a closed box in front of a wall, against the ray cast of
 * every pixel away from the box's outline: the back layer is the box's
 * far side (the exit of the ray: its back face or a side), the third the
 * wall behind it, and both are empty where the ray meets the wall alone
 * (a one-sided wall has no back face); a twosided sheet is its own back
 * face; the layers are the same drawn in two row ranges as in one. */
TEST(back_and_behind_layers)
{
    enum { W = 80, H = 60 };
    tgi_view v = view_make(W, H, 60, 1);
    mesh *m = mesh_new();
    gbuf g, split;
    int i, j, k, bad = 0, box_px = 0, wall_px = 0, diff = 0;
    double worst = 0;
    layers_scene(m, &v);
    gbuf_alloc(&g, W, H);
    gbuf_alloc(&split, W, H);
    g.gb.back_depth = sf_calloc((size_t)W * H, sizeof *g.gb.back_depth);
    g.gb.behind_depth = sf_calloc((size_t)W * H, sizeof *g.gb.behind_depth);
    split.gb.back_depth = sf_calloc((size_t)W * H, sizeof *split.gb.back_depth);
    split.gb.behind_depth = sf_calloc((size_t)W * H, sizeof *split.gb.behind_depth);
    tgi_raster_gbuffer(&g.gb, &v, mesh_rm(m), 0, H);
    tgi_raster_gbuffer(&split.gb, &v, mesh_rm(m), 0, H / 3);
    tgi_raster_gbuffer(&split.gb, &v, mesh_rm(m), H / 3, H);
    for (j = 1; j < H - 1; j++)
        for (i = 1; i < W - 1; i++) {
            tgi_gview gv = sf_view(&g.gb, NULL);
            double z[3], zn[4][3], got[3];
            size_t idx = (size_t)j * W + (size_t)i;
            int q, outline = 0;
            layers_exact(&v, i, j, z);
            layers_exact(&v, i + 1, j, zn[0]);
            layers_exact(&v, i, j + 1, zn[1]);
            layers_exact(&v, i - 1, j, zn[2]);
            layers_exact(&v, i, j - 1, zn[3]);
            for (q = 0; q < 4; q++) outline |= (zn[q][1] > 0) != (z[1] > 0);
            if (outline) continue;   /* away from the outline: the neighbours meet the same layers */
            got[0] = D(tgi_gv_depth(&gv, idx));
            got[1] = D(tgi_gv_back_depth(&gv, idx));
            got[2] = D(tgi_gv_behind_depth(&gv, idx));
            if (z[1] > 0) box_px++; else wall_px++;
            for (k = 0; k < 3; k++) {
                double slope = 0, tol, err = fabs(got[k] - z[k]);
                for (q = 0; q < 4; q++) if (fabs(zn[q][k] - z[k]) > slope) slope = fabs(zn[q][k] - z[k]);
                /* the number type's precision, and the depth change over the
                 * vertices' snapping (1/32 pixel) on a slope */
                tol = (TG_FIXED ? 2e-4 : 2e-5) * z[k] + 0.05 * slope + (TG_FIXED ? 2e-3 : 1e-5);
                /* the back face's 8-bit code: within half a step (1/32 to 1/64 of
                 * the thickness) of its depth behind the surface (pack.h) */
                if (k == 1 && !TG_WIDE_STORAGE) tol += fabs(z[1] - z[0]) / 32;
                if (z[k] == 0 ? got[k] != 0 : err > tol) {
                    if (bad < 4) fprintf(stderr, "pixel (%d, %d) layer %d: %.6g, exact %.6g\n", i, j, k, got[k], z[k]);
                    bad++;
                }
                if (z[k] > 0 && err > worst) worst = err;
            }
        }
    for (i = 0; i < W * H; i++) {
        tgi_gview a = sf_view(&g.gb, NULL), b = sf_view(&split.gb, NULL);
        if (tgi_gv_back_depth(&a, (size_t)i) != tgi_gv_back_depth(&b, (size_t)i) ||
            tgi_gv_behind_depth(&a, (size_t)i) != tgi_gv_behind_depth(&b, (size_t)i))
            diff++;
    }
    printf("# box in front of a wall, %dx%d: %d box and %d wall pixels, worst depth error %.2g\n", W, H, box_px,
           wall_px, worst);
    CHECK(box_px > 200 && wall_px > 1000, "pixels: %d on the box, %d on the wall alone", box_px, wall_px);
    CHECK(bad == 0, "%d layer depths off the ray cast", bad);
    CHECK(diff == 0, "%d pixels differ drawn in two row ranges", diff);
    free(g.gb.back_depth); free(g.gb.behind_depth); free(split.gb.back_depth); free(split.gb.behind_depth);
    gbuf_free(&g);
    gbuf_free(&split);

    /* a twosided sheet at depth 3 before the wall: its own back face */
    m->n = 0;
    {
        double sheet[4][3] = { { -30, -30, 3 }, { 30, -30, 3 }, { 30, 30, 3 }, { -30, 30, 3 } };
        const double away[3] = { 0, 0, 1 };
        add_quad_out(m, &v, sheet, away, 1);   /* material 1: twosided, seen from its back */
    }
    gbuf_alloc(&g, W, H);
    g.gb.back_depth = sf_calloc((size_t)W * H, sizeof *g.gb.back_depth);
    tgi_raster_gbuffer(&g.gb, &v, mesh_rm(m), 0, H);
    for (i = 0, bad = 0; i < W * H; i++) {
        tgi_gview gv = sf_view(&g.gb, NULL);
        if (tgi_gv_back_depth(&gv, (size_t)i) != tgi_gv_depth(&gv, (size_t)i) || tgi_gv_is_sky(&gv, (size_t)i)) bad++;
    }
    CHECK(bad == 0, "twosided sheet: %d pixels whose back layer is not the sheet", bad);
    free(g.gb.back_depth);
    drawn_free(&g, m);
}

TEST(depth_only_ortho)
{
    enum { S = 48 };
    tg_real *depth = (tg_real *)malloc(sizeof(tg_real) * S * S);
    tgi_mat4 m;
    /* light looks along -y; clip = (x / 4, z / 4, 10 - y, 1); a tilted plane
     * y = 2 + 0.25 x - 0.125 z spanning x, z in [-6, 6], both windings */
    const double pos[4][3] = { { -6, 0, -6 }, { 6, 0, -6 }, { 6, 0, 6 }, { -6, 0, 6 } };
    tg_vec3 tri[12];
    int i, j, k, bad = 0, drawn = 0;
    double worst = 0;
    int order[4][3] = { { 0, 1, 2 }, { 0, 3, 2 }, { 0, 1, 2 }, { 0, 2, 3 } };
    memset(&m, 0, sizeof m);
    set_row4(&m, 0, 0.25, 0, 0, 0);
    set_row4(&m, 1, 0, 0, 0.25, 0);
    set_row4(&m, 2, 0, -1, 0, 10);
    set_row4(&m, 3, 0, 0, 0, 1);
    for (k = 0; k < 2; k++) {
        int l;
        for (l = 0; l < 3; l++) {
            const double *p = pos[order[k + (k ? 2 : 0)][l]];
            tri[3 * k + l] = V(p[0], 2 + 0.25 * p[0] - 0.125 * p[2], p[2]);
        }
    }
    for (i = 0; i < S * S; i++) depth[i] = TG_REAL_MAX;
    tgi_raster_depth(depth, S, S, &m, 1, tri, 2, 0, S);
    for (j = 0; j < S; j++)
        for (i = 0; i < S; i++) {
            double x = ((i + 0.5) / S * 2 - 1) * 4, z = (1 - (j + 0.5) / S * 2) * 4;
            double want = 10 - (2 + 0.25 * x - 0.125 * z), got = D(depth[j * S + i]);
            drawn += depth[j * S + i] != TG_REAL_MAX;
            if (fabs(got - want) > worst) worst = fabs(got - want);
            if (fabs(got - want) > (TG_FIXED ? 2e-4 : 1e-5) + 0.05 * 0.25 * 4 / S * 2) bad++;
        }
    CHECK(drawn == S * S && bad == 0, "ortho depth: %d drawn, %d off (worst %g)", drawn, bad, worst);
    free(depth);
}

TEST(depth_only_perspective)
{
    enum { S = 64 };
    tg_real *depth = (tg_real *)malloc(sizeof(tg_real) * S * S);
    tgi_mat4 m;
    double n = 0.1, f = 50, a = (f + n) / (f - n), b = -2 * f * n / (f - n);
    /* light at the origin looking along +z, 90 degree frustum:
     * clip = (x, y, a z + b, z) */
    const double P[2][3][3] = { { { -10, -40, 2 }, { 20, -40, 17 }, { 20, 40, 17 } },
                                { { -10, -40, 2 }, { 20, 40, 17 }, { -10, 40, 2 } } };
    const double near_cross[3][3] = { { -1, 0.5, -1 }, { 1, 0.4, 3 }, { -0.5, 0.6, 3 } };
    tg_vec3 tri[9];
    int i, j, k, l, bad = 0, drawn = 0;
    double worst = 0;
    memset(&m, 0, sizeof m);
    set_row4(&m, 0, 1, 0, 0, 0);
    set_row4(&m, 1, 0, 1, 0, 0);
    set_row4(&m, 2, 0, 0, a, b);
    set_row4(&m, 3, 0, 0, 1, 0);
    for (k = 0; k < 2; k++)
        for (l = 0; l < 3; l++) tri[3 * k + l] = V(P[k][l][0], P[k][l][1], P[k][l][2]);
    for (i = 0; i < S * S; i++) depth[i] = TG_REAL_MAX;
    tgi_raster_depth(depth, S, S, &m, 0, tri, 2, 0, S);
    for (j = 0; j < S; j++)
        for (i = 0; i < S; i++) {
            /* plane z = 7 + 0.5 x: ray (u, v, 1) hits at z = 7 / (1 - 0.5 u) */
            double u = (i + 0.5) / S * 2 - 1, want = 7 / (1 - 0.5 * u), got = D(depth[j * S + i]);
            double slope = 7 / (1 - 0.5 * (u + 2.0 / S)) - want;
            drawn += depth[j * S + i] != TG_REAL_MAX;
            if (fabs(got - want) > worst) worst = fabs(got - want);
            if (fabs(got - want) > (TG_FIXED ? 2e-4 : 2e-5) * want + 0.05 * fabs(slope)) bad++;
        }
    CHECK(drawn == S * S && bad == 0, "perspective depth: %d drawn, %d off (worst %g)", drawn, bad, worst);
    /* a triangle crossing the light's near plane (and behind it) adds only
     * depths >= near, and nothing mirrored from behind */
    for (l = 0; l < 3; l++) tri[6 + l] = V(near_cross[l][0], near_cross[l][1], near_cross[l][2]);
    for (i = 0; i < S * S; i++) depth[i] = TG_REAL_MAX;
    tgi_raster_depth(depth, S, S, &m, 0, tri + 6, 1, 0, S);
    drawn = 0; bad = 0;
    for (i = 0; i < S * S; i++) {
        if (depth[i] == TG_REAL_MAX) continue;
        drawn++;
        if (D(depth[i]) < n * 0.99 || D(depth[i]) > 3.01) bad++;
        if ((i / S) > S / 2) bad++; /* y > 0 everywhere: only the top half */
    }
    CHECK(drawn > 10 && bad == 0, "near-crossing triangle: %d drawn, %d bad", drawn, bad);
    free(depth);
}

/* 16-bit depth codes are rounded (src/raster/raster.h: q = round((depth -
 * lo) 65536 / range)): a flat square at depth 4003 / 16384 (exact in both
 * number types) with lo = 0, range = 16 is 1000.75 codes deep, stored as
 * 1001 in every pixel it covers. */
TEST(depth16_codes_are_rounded)
{
    enum { S = 16 };
    uint16_t code[S * S];
    tgi_mat4 m;
    const double depth = 4003.0 / 16384.0, y = 10 - depth;
    tg_vec3 tri[6];
    int i, drawn = 0, bad = 0;
    memset(&m, 0, sizeof m);
    set_row4(&m, 0, 0.25, 0, 0, 0);   /* clip = (x / 4, z / 4, 10 - y, 1), as depth_only_ortho */
    set_row4(&m, 1, 0, 0, 0.25, 0);
    set_row4(&m, 2, 0, -1, 0, 10);
    set_row4(&m, 3, 0, 0, 0, 1);
    tri[0] = V(-6, y, -6); tri[1] = V(6, y, -6); tri[2] = V(6, y, 6);
    tri[3] = V(-6, y, -6); tri[4] = V(6, y, 6); tri[5] = V(-6, y, 6);
    for (i = 0; i < S * S; i++) code[i] = TG_RASTER_DEPTH16_EMPTY;
    tgi_raster_depth16(code, S, S, &m, 1, 0, R(16), tri, 2, 0, S);
    for (i = 0; i < S * S; i++) {
        drawn += code[i] != TG_RASTER_DEPTH16_EMPTY;
        bad += code[i] != 1001;
    }
    CHECK(drawn == S * S, "the square covers the map: %d of %d", drawn, S * S);
    CHECK(bad == 0, "%d of %d codes not round(1000.75) = 1001 (first %u)", bad, S * S, (unsigned)code[0]);
}

int main(void)
{
    RUN(fill_rule_grid_tiling);
    RUN(fill_rule_random_fans);
    RUN(fill_rule_on_pixel_centres);
    RUN(fill_rule_matches_brute_force);
    RUN(far_ground_plane_in_fixed_point);
    RUN(clipped_ground_plane_depth);
    RUN(gbuffer_tiling_ids);
    RUN(front_back_twosided);
    RUN(near_plane_clipping);
    RUN(big_triangle_past_edges);
    RUN(depth_plane_and_floor);
    RUN(clipped_tiling_watertight);
    RUN(normal_interpolation);
    RUN(zero_area_skipped);
    RUN(hostile_coordinates);
    RUN(sphere_nearest_and_rows);
    RUN(back_and_behind_layers);
    RUN(depth_only_ortho);
    RUN(depth_only_perspective);
    RUN(depth16_codes_are_rounded);
    return check_summary();
}
