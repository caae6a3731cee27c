/* SPDX-License-Identifier: MIT */
/*
 * raster_fixture.h - test scenes built from rectangles and boxes in double
 * precision, rasterized by the real rasterizer into a G-buffer (so the
 * positions a pass reconstructs carry the rasterizer's snapping), with a
 * BVH over the same triangles.  Shared by test_shadow.c and
 * test_pathtrace.c.
 */
#ifndef TG_RASTER_FIXTURE_H
#define TG_RASTER_FIXTURE_H

#include <stdlib.h>
#include <stdint.h>
#include "check.h"
#include "raster/raster.h"
#include "scene/scene.h"
#include "ao/bvh.h"
#include "storage_fixture.h"
#include "light_fixture.h"

#define DEG (3.14159265358979 / 180.0)
#define MAXTRI 4096

static double dv(tg_real r) { return check_d(r); }
static tg_real rv(double x) { return tg_from_float((float)x); }
static tg_vec3 v3(double x, double y, double z) { return tg_v3(rv(x), rv(y), rv(z)); }
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* ---- geometry: quads as triangle pairs; `material` is the index the next
 * triangles get (into the materials image_render is given) ---- */

typedef struct geo {
    int n, material;
    tg_vec3 pos[3 * MAXTRI], nrm[3 * MAXTRI];
    uint16_t mat[MAXTRI];
    double lo[3], hi[3];
} geo;

static geo *geo_new(void)
{
    geo *g = (geo *)calloc(1, sizeof(geo));
    if (!g) { fprintf(stderr, "out of memory\n"); exit(2); }
    return g;
}

static void geo_point(geo *g, const double *p)
{
    int k;
    for (k = 0; k < 3; k++) {
        if (g->n == 0 && k == 0) { g->lo[0] = g->hi[0] = p[0]; g->lo[1] = g->hi[1] = p[1]; g->lo[2] = g->hi[2] = p[2]; }
        if (p[k] < g->lo[k]) g->lo[k] = p[k];
        if (p[k] > g->hi[k]) g->hi[k] = p[k];
    }
}

/* Triangle a b c with vertex normals na nb nc (NULL: the face normal). */
static void tri(geo *g, const double *a, const double *b, const double *c,
                const double *na, const double *nb, const double *nc)
{
    const double *v[3] = { a, b, c }, *vn[3] = { na, nb, nc };
    double e1[3], e2[3], n[3], l;
    int k, j;
    if (g->n >= MAXTRI) { fprintf(stderr, "too many triangles\n"); exit(2); }
    for (k = 0; k < 3; k++) { e1[k] = b[k] - a[k]; e2[k] = c[k] - a[k]; }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1]; n[1] = e1[2] * e2[0] - e1[0] * e2[2]; n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    l = sqrt(dot3(n, n));
    for (j = 0; j < 3; j++) {
        geo_point(g, v[j]);
        g->pos[3 * g->n + j] = v3(v[j][0], v[j][1], v[j][2]);
        g->nrm[3 * g->n + j] = vn[j] ? v3(vn[j][0], vn[j][1], vn[j][2]) : v3(n[0] / l, n[1] / l, n[2] / l);
    }
    g->mat[g->n] = (uint16_t)g->material;
    g->n++;
}

/* Quad p0 p1 p2 p3 (a planar convex loop; front = counter-clockwise). */
static void quad(geo *g, double q[4][3])
{
    tri(g, q[0], q[1], q[2], NULL, NULL, NULL);
    tri(g, q[0], q[2], q[3], NULL, NULL, NULL);
}

/* Axis-aligned rectangle on plane `axis` = c, spanning [a0, a1] x [b0, b1]
 * in the two other axes (in x, y, z order). */
static void rect(geo *g, int axis, double c, double a0, double a1, double b0, double b1)
{
    double q[4][3];
    int u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2, k;
    for (k = 0; k < 4; k++) {
        q[k][axis] = c;
        q[k][u] = (k == 1 || k == 2) ? a1 : a0;
        q[k][w] = (k >= 2) ? b1 : b0;
    }
    quad(g, q);
}

/* The six faces of a box (skip_face 2 axis + side, or -1 for none). */
static void box(geo *g, const double lo[3], const double hi[3], int skip_face)
{
    int a, s;
    for (a = 0; a < 3; a++)
        for (s = 0; s < 2; s++) {
            int u = a == 0 ? 1 : 0, w = a == 2 ? 1 : 2;
            if (2 * a + s == skip_face) continue;
            rect(g, a, s ? hi[a] : lo[a], lo[u], hi[u], lo[w], hi[w]);
        }
}

static tgi_bvh bvh;
static void *bvh_mem;

static void geo_bvh(const geo *g)
{
    size_t bytes = tgi_bvh_bytes(g->n);
    free(bvh_mem);
    bvh_mem = malloc(bytes);
    if (!bvh_mem || tgi_bvh_build(&bvh, g->pos, g->n, bvh_mem, bytes) != 0) { fprintf(stderr, "bvh\n"); exit(2); }
}

/* ---- an image: the rasterized G-buffer and per-pixel outputs ---- */

#define IMAGE_OUTPUTS 6
typedef struct image {
    int w, h;
    tgi_view view;
    tgi_gbuffer gb;                  /* in the build's storage (storage_fixture.h) */
    tg_real *planes;
    tg_real *depth, *nx, *ny, *nz;   /* the G-buffer read back as numbers */
    uint8_t *sky;
    tg_real *out[IMAGE_OUTPUTS];     /* planes for the test's results */
    double texel_world;              /* test_shadow: of the last map */
} image;

static void image_free(image *im)
{
    free(im->planes); free(im->sky);
    sf_gbuffer_free(&im->gb);
    memset(im, 0, sizeof *im);
}

/* The G-buffer as numbers: depth, normal, sky. */
static void image_read_back(image *im)
{
    tgi_gview v = sf_view(&im->gb, &im->view);
    size_t i, n = (size_t)im->w * (size_t)im->h;
    for (i = 0; i < n; i++) {
        tg_vec3 nn = tgi_gv_is_sky(&v, i) ? tg_v3(0, 0, 0) : tgi_gv_normal(&v, i);
        im->sky[i] = (uint8_t)tgi_gv_is_sky(&v, i);
        im->depth[i] = tgi_gv_depth(&v, i);
        im->nx[i] = nn.x; im->ny[i] = nn.y; im->nz[i] = nn.z;
    }
}

/* Rasterize g seen from eye toward target (fov in degrees) at w x h;
 * `materials` NULL = one two-sided white material. */
static void image_render(image *im, const geo *g, const tgi_material *materials, const double eye[3],
                         const double target[3], double fov_deg, int w, int h)
{
    static const tgi_material white = { "white", { TG_ONE, TG_ONE, TG_ONE }, 0, { 0, 0, 0 }, 1,
                                        { TG_INV_PI, TG_INV_PI, TG_INV_PI } };   /* diffuse: tgi_material_finish's */
    tgi_raster_mesh mesh;
    size_t n = (size_t)w * (size_t)h;
    int k, used;
    tg_real *p;
    memset(im, 0, sizeof *im);
    im->w = w; im->h = h;
    im->planes = (tg_real *)calloc(n * (4 + IMAGE_OUTPUTS), sizeof(tg_real));
    im->sky = (uint8_t *)calloc(n, 1);
    if (!im->planes || !im->sky) { fprintf(stderr, "out of memory\n"); exit(2); }
    p = im->planes;
    im->depth = p; im->nx = p + n; im->ny = p + 2 * n; im->nz = p + 3 * n;
    for (k = 0; k < IMAGE_OUTPUTS; k++) im->out[k] = p + (4 + (size_t)k) * n;
    for (k = 0, used = 1; k < g->n; k++) if (g->mat[k] + 1 > used) used = g->mat[k] + 1;
    sf_gbuffer_alloc(&im->gb, w, h, materials ? materials : &white, materials ? used : 1);
    tgi_view_make(&im->view, v3(eye[0], eye[1], eye[2]), v3(target[0], target[1], target[2]), v3(0, 1, 0),
                  rv(fov_deg * DEG), TG_R(0.05f), TG_R(1000.0f), w, h);
    mesh.pos = g->pos; mesh.nrm = g->nrm; mesh.tri_material = g->mat; mesh.tri_object = NULL;
    mesh.tri_count = g->n; mesh.materials = materials ? materials : &white;
    tgi_gbuffer_clear_rows(&im->gb, 0, h);
    tgi_raster_gbuffer(&im->gb, &im->view, &mesh, 0, h);
    image_read_back(im);
    for (k = 0; k < w * h; k++) if (!im->sky[k]) break;
    CHECK(k < w * h, "the camera sees the scene");
}

/* Direct irradiance (light/direct.h) of the image's G-buffer into outputs
 * first .. first + 2, through the build's colour storage. */
static void image_direct(image *im, const tgi_light *lights, int count, const tgi_shadow_map *const *maps, int first)
{
    tgi_gview v = sf_view(&im->gb, &im->view);
    tgi_rgb e;
    sf_rgb_alloc(&e, (size_t)im->w * (size_t)im->h);
    tgi_direct_rows(&v, lights, count, maps, &e, 0, im->h);
    sf_rgb_read(&e, (size_t)im->w * (size_t)im->h, im->out[first], im->out[first + 1], im->out[first + 2]);
    sf_rgb_free(&e);
}

/* World position of pixel i as the passes reconstruct it (view.h), and its normal. */
static void pixel_pos(const image *im, int i, double p[3], double n[3])
{
    const tgi_view *v = &im->view;
    double kx = (i % im->w + 0.5 - im->w / 2.0) / dv(v->pixels_per_unit);
    double ky = (im->h / 2.0 - (i / im->w + 0.5)) / dv(v->pixels_per_unit), z = dv(im->depth[i]);
    p[0] = dv(v->eye.x) + z * (dv(v->forward.x) + ky * dv(v->up.x) + kx * dv(v->right.x));
    p[1] = dv(v->eye.y) + z * (dv(v->forward.y) + ky * dv(v->up.y) + kx * dv(v->right.y));
    p[2] = dv(v->eye.z) + z * (dv(v->forward.z) + ky * dv(v->up.z) + kx * dv(v->right.z));
    n[0] = dv(im->nx[i]); n[1] = dv(im->ny[i]); n[2] = dv(im->nz[i]);
}

#endif
