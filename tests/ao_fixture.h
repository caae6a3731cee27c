/* SPDX-License-Identifier: MIT */
/*
 * ao_fixture.h - the analytic test scenes shared by test_ao.c and
 * test_reference.c: rectangles ray-cast per pixel into a G-buffer (no
 * rasterizer involved), the same rectangles as triangles for the BVH, and
 * the open plane / groove / closed box they are built into.
 */
#ifndef TG_AO_FIXTURE_H
#define TG_AO_FIXTURE_H

#include <stdlib.h>
#include "ao/ao.h"
#include "ao/bvh.h"
#include "ao/reference.h"
#include "storage_fixture.h"

#define W 48
#define H 36
#define MAXRECT 8

typedef struct rect { double p[3], u[3], v[3]; } rect; /* p + s u + t v, s, t in [0, 1] */

typedef struct scene {
    int nrect;
    rect r[MAXRECT];
    tg_vec3 tri[MAXRECT * 6], nrm[MAXRECT * 6];
    tgi_view view;
    tg_real depth[W * H], nx[W * H], ny[W * H], nz[W * H];
    uint8_t sky[W * H];
    double wpos[W * H][3];   /* world position per pixel (hosted, for picking pixels) */
    int wrect[W * H];        /* which rectangle, -1 sky */
    double back[W * H];      /* the nearest back face's depth (the rectangle's normal u x v
                                pointing away from the eye), 0: none */
    double behind[W * H];    /* the nearest surface beyond it, 0: none (raster.h's layers) */
} scene;

static void cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1]; c[1] = a[2] * b[0] - a[0] * b[2]; c[2] = a[0] * b[1] - a[1] * b[0];
}
static double dot3(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void norm3(double *a) { double l = sqrt(dot3(a, a)); a[0] /= l; a[1] /= l; a[2] /= l; }
static tg_vec3 tv(const double *a) { return tg_v3(tg_from_float((float)a[0]), tg_from_float((float)a[1]), tg_from_float((float)a[2])); }

static void add_rect(scene *s, double px, double py, double pz, double ux, double uy, double uz,
                     double vx, double vy, double vz)
{
    rect *r = &s->r[s->nrect];
    double c[3][3], n[3];
    int k = s->nrect * 2, j;
    r->p[0] = px; r->p[1] = py; r->p[2] = pz;
    r->u[0] = ux; r->u[1] = uy; r->u[2] = uz;
    r->v[0] = vx; r->v[1] = vy; r->v[2] = vz;
    cross3(r->u, r->v, n); norm3(n);
    for (j = 0; j < 3; j++) { c[0][j] = r->p[j] + r->u[j]; c[1][j] = c[0][j] + r->v[j]; c[2][j] = r->p[j] + r->v[j]; }
    s->tri[3 * k + 0] = tv(r->p); s->tri[3 * k + 1] = tv(c[0]); s->tri[3 * k + 2] = tv(c[1]);
    s->tri[3 * k + 3] = tv(r->p); s->tri[3 * k + 4] = tv(c[1]); s->tri[3 * k + 5] = tv(c[2]);
    for (j = 0; j < 6; j++) s->nrm[3 * k + j] = tv(n);
    s->nrect++;
}

static void make_view(tgi_view *v, const double eye[3], const double target[3], double fov_deg)
{
    double f[3] = { target[0] - eye[0], target[1] - eye[1], target[2] - eye[2] }, up[3] = { 0, 1, 0 }, r[3], u[3];
    double fy = 1.0 / tan(fov_deg * 3.14159265358979 / 360.0);
    norm3(f); cross3(f, up, r); norm3(r); cross3(r, f, u);
    memset(v, 0, sizeof *v);
    v->width = W; v->height = H;
    v->eye = tv(eye); v->right = tv(r); v->up = tv(u); v->forward = tv(f);
    v->fov_y = tg_from_float((float)(fov_deg * 3.14159265358979 / 180.0));
    v->aspect = tg_from_float((float)W / H);
    v->focal_y = tg_from_float((float)fy);
    v->focal_x = tg_from_float((float)(fy * H / W));
    v->tan_half_fov_y = tg_from_float((float)(1.0 / fy));
    v->pixels_per_unit = tg_from_float((float)(H / 2.0 * fy));
    v->znear = tg_from_float(0.05f); v->zfar = tg_from_float(1000.0f);
}

/* Ray-cast every pixel centre against the rectangles (double precision). */
static void raster(scene *s, const double eye[3], const double target[3], double fov_deg)
{
    int x, y, k, j;
    double f[3], r[3], u[3], up[3] = { 0, 1, 0 };
    double fy = 1.0 / tan(fov_deg * 3.14159265358979 / 360.0), fx = fy * H / W;
    make_view(&s->view, eye, target, fov_deg);
    for (j = 0; j < 3; j++) f[j] = target[j] - eye[j];
    norm3(f); cross3(f, up, r); norm3(r); cross3(r, f, u);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            int i = y * W + x, best = -1, nhit = 0, h;
            double ndx = (2.0 * x + 1 - W) / W, ndy = (H - 2.0 * y - 1) / H, d[3], bt = 1e30, bn[3] = { 0, 0, 0 };
            double hit_t[MAXRECT];
            int hit_back[MAXRECT];
            for (j = 0; j < 3; j++) d[j] = f[j] + r[j] * ndx / fx + u[j] * ndy / fy; /* view z of d is 1 */
            for (k = 0; k < s->nrect; k++) {
                const rect *q = &s->r[k];
                double n[3], w[3], t, a, b, uu = dot3(q->u, q->u), vv = dot3(q->v, q->v), hp[3];
                cross3(q->u, q->v, n); norm3(n);
                if (fabs(dot3(n, d)) < 1e-12) continue;
                for (j = 0; j < 3; j++) w[j] = q->p[j] - eye[j];
                t = dot3(n, w) / dot3(n, d);
                if (t <= 1e-6) continue;
                for (j = 0; j < 3; j++) hp[j] = eye[j] + t * d[j] - q->p[j];
                a = dot3(hp, q->u) / uu; b = dot3(hp, q->v) / vv;
                if (a < 0 || a > 1 || b < 0 || b > 1) continue;
                hit_t[nhit] = t; hit_back[nhit++] = dot3(n, d) > 0;
                if (t >= bt) continue;
                bt = t; best = k;
                if (dot3(n, d) > 0) { n[0] = -n[0]; n[1] = -n[1]; n[2] = -n[2]; }
                bn[0] = n[0]; bn[1] = n[1]; bn[2] = n[2];
            }
            s->back[i] = s->behind[i] = 0;
            for (h = 0; h < nhit; h++)
                if (hit_back[h] && (s->back[i] == 0 || hit_t[h] < s->back[i])) s->back[i] = hit_t[h];
            for (h = 0; h < nhit; h++)
                if (s->back[i] > 0 && hit_t[h] > s->back[i] && (s->behind[i] == 0 || hit_t[h] < s->behind[i]))
                    s->behind[i] = hit_t[h];
            s->wrect[i] = best;
            s->sky[i] = best < 0;
            s->depth[i] = best < 0 ? 0 : tg_from_float((float)bt);
            s->nx[i] = tg_from_float((float)bn[0]); s->ny[i] = tg_from_float((float)bn[1]); s->nz[i] = tg_from_float((float)bn[2]);
            for (j = 0; j < 3; j++) s->wpos[i][j] = best < 0 ? 0 : eye[j] + bt * d[j];
        }
}

typedef struct outputs {
    tg_real ao[W * H], bx[W * H], by[W * H], bz[W * H], cone[W * H], nr[W * H], ng[W * H], nb[W * H];
} outputs;

/* What a technique reads and writes: the view of the ray-cast G-buffer (in
 * the build's storage), the results (read back into `outputs` by io_read)
 * and the radiance planes (absent unless a test sets them). */
typedef struct ao_pass {
    tgi_gview g;
    tgi_gresult out;
    tgi_rgb rad;
    outputs *o;
} ao_pass;

static tgi_gbuffer ao_gb;
static tgi_gresult ao_res, ao_res_near, ao_res_cone, ao_res_near_cone;
static tgi_rgb ao_rad;

static inline void io_for(ao_pass *io, scene *s, outputs *o, int want_near)
{
    if (!ao_gb.depth) {
        sf_gbuffer_alloc(&ao_gb, W, H, NULL, 0);
        sf_results_alloc(&ao_res, W * H, 1, 0, 0);
        sf_results_alloc(&ao_res_near, W * H, 1, 0, 1);
        sf_results_alloc(&ao_res_cone, W * H, 1, 1, 0);
        sf_results_alloc(&ao_res_near_cone, W * H, 1, 1, 1);
        sf_rgb_alloc(&ao_rad, W * H);
    }
    memset(io, 0, sizeof *io);
    sf_gbuffer_fill(&ao_gb, s->depth, s->nx, s->ny, s->nz, s->sky, 0);
    io->g = sf_view(&ao_gb, &s->view);
    io->out = want_near ? ao_res_near : ao_res;
    io->o = o;
}

/* The technique's own cone as well (io_read fills o->cone). */
static inline void io_with_cone(ao_pass *io)
{
    io->out = tgi_gr_has_near(&io->out) ? ao_res_near_cone : ao_res_cone;
}

/* Radiance planes the technique gathers. */
static inline void io_radiance(ao_pass *io, const tg_real *r, const tg_real *g, const tg_real *b)
{
    sf_rgb_fill(&ao_rad, W * H, r, g, b);
    io->rad = ao_rad;
}

/* The results as numbers, into the outputs io_for was given. */
static inline void io_read(const ao_pass *io)
{
    outputs *o = io->o;
    sf_results_read(&io->out, W * H, o->ao, o->bx, o->by, o->bz, o->cone, o->nr, o->ng, o->nb);
}

static tgi_bvh bvh;
static unsigned char *bvh_mem;

static void build_bvh(scene *s)
{
    size_t bytes = tgi_bvh_bytes(s->nrect * 2);
    free(bvh_mem);
    bvh_mem = malloc(bytes);
    if (tgi_bvh_build(&bvh, s->tri, s->nrect * 2, bvh_mem, bytes) != 0) { fprintf(stderr, "bvh build failed\n"); exit(2); }
}

/* The reference's parameters for s (the BVH build_bvh made, s's triangle
 * normals) at radius. */
static inline tgi_reference_params reference_params(const scene *s, tg_real radius)
{
    tgi_reference_params p;
    tgi_reference_defaults(&p);
    p.bvh = &bvh; p.tri_nrm = s->nrm; p.radius = radius;
    return p;
}

/* The reference with p over s into o (no near field, no cone). */
static inline void reference_run(ao_pass *io, const tgi_reference_params *p, scene *s, outputs *o)
{
    io_for(io, s, o, 0);
    tgi_reference_rows(p, &io->g, &io->rad, &io->out, 0, H);
    io_read(io);
}

/* ---- the groove: floor y = 0 (x >= 0) meeting a wall x = 0 (y >= 0) ---- */
#define BIG 50.0
static void groove(scene *s)
{
    static const double eye[3] = { 2.6, 1.8, 2.2 }, target[3] = { 0.35, 0.3, -0.8 };
    memset(s, 0, sizeof *s);
    add_rect(s, 0, 0, BIG, BIG, 0, 0, 0, 0, -2 * BIG);        /* floor, normal +y */
    add_rect(s, 0, 0, -BIG, 0, BIG, 0, 0, 0, 2 * BIG);        /* wall, normal +x */
    raster(s, eye, target, 60.0);
    build_bvh(s);

#endif
