/* SPDX-License-Identifier: MIT */
/*
 * storage_fixture.h - G-buffers, GI results and colour planes for tests that
 * call a pass directly: storage for either build (compact, or
 * TG_WIDE_STORAGE), malloc'd, written and read as tg_real planes through
 * gview.h's accessors, so a test states its inputs and checks its outputs
 * as numbers whatever the storage.  Hosted test code.
 */
#ifndef TG_STORAGE_FIXTURE_H
#define TG_STORAGE_FIXTURE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "raster/gview.h"

/* One material for G-buffers that need none in particular (albedo 0.8, F0 0). */
static tgi_material sf_material_table[1];

static inline void *sf_calloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size ? size : 1);
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

/* A w x h G-buffer (all sky) reading its materials from `materials`
 * (NULL: sf_material_table); motion and object planes are left to the test
 * (sf_gbuffer_free frees them too). */
static inline void sf_gbuffer_alloc(tgi_gbuffer *g, int w, int h, const tgi_material *materials, int material_count)
{
    int k;
    tgi_gbuffer_carve(g, w, h, sf_calloc(tgi_gbuffer_carve(g, w, h, NULL), 1));
    if (!materials) {
        sf_material_table[0].albedo = tg_v3(TG_R(0.8f), TG_R(0.8f), TG_R(0.8f));
        tgi_material_finish(&sf_material_table[0]);
        materials = sf_material_table;
        material_count = 1;
    }
    g->materials = materials;
    for (k = 0; k < material_count; k++)
        if (materials[k].emissive.x > 0 || materials[k].emissive.y > 0 || materials[k].emissive.z > 0) g->has_emissive = 1;
}

static inline void sf_gbuffer_free(tgi_gbuffer *g)
{
    free(g->depth);   /* the block's first part */
    free(g->object); free(g->motion_x); free(g->motion_y);
    memset(g, 0, sizeof *g);
}

/* Pixel i: a surface (depth > 0) or sky (depth <= 0). */
static inline void sf_gbuffer_set(const tgi_gbuffer *g, size_t i, tg_real depth, tg_vec3 n, int material)
{
    if (depth > 0) tgi_gb_set(g, i, depth, n, material);
    else tgi_gb_set_sky(g, i);
}

/* Every pixel from planes (sky where sky[i] or depth <= 0; sky may be NULL). */
static inline void sf_gbuffer_fill(const tgi_gbuffer *g, const tg_real *depth, const tg_real *nx, const tg_real *ny,
                            const tg_real *nz, const uint8_t *sky, int material)
{
    size_t i, n = (size_t)g->width * (size_t)g->height;
    for (i = 0; i < n; i++)
        sf_gbuffer_set(g, i, sky && sky[i] ? 0 : depth[i], tg_v3(nx[i], ny[i], nz[i]), material);
}

/* The view of the whole G-buffer with camera `v`. */
static inline tgi_gview sf_view(const tgi_gbuffer *g, const tgi_view *v)
{
    tgi_gview view;
    tgi_gview_of(&view, g, v);
    return view;
}

/* The first plane of a carved block, the one its allocation starts (the
 * wide and the compact storage name it differently). */
#if TG_WIDE_STORAGE
#define SF_RGB_BLOCK(c) ((c)->r)
#define SF_PREV_BLOCK(h) ((h)->depth)
#else
#define SF_RGB_BLOCK(c) ((c)->p)
#define SF_PREV_BLOCK(h) ((h)->dn)
#endif

/* ---- colour planes ---- */
static inline void sf_rgb_alloc(tgi_rgb *c, size_t n)
{
    tgi_rgb_carve(c, n, sf_calloc(tgi_rgb_carve(c, n, NULL), 1));
}
static inline void sf_rgb_free(tgi_rgb *c)
{
    free(SF_RGB_BLOCK(c));
    *c = tgi_rgb_none();
}
static inline void sf_rgb_fill(const tgi_rgb *c, size_t n, const tg_real *r, const tg_real *g, const tg_real *b)
{
    size_t i;
    for (i = 0; i < n; i++) tgi_rgb_set(c, i, tg_v3(r[i], g[i], b[i]));
}
static inline void sf_rgb_read(const tgi_rgb *c, size_t n, tg_real *r, tg_real *g, tg_real *b)
{
    size_t i;
    for (i = 0; i < n; i++) {
        tg_vec3 v = tgi_rgb_get(c, i);
        r[i] = v.x; g[i] = v.y; b[i] = v.z;
    }
}

/* The storage's rounding of a colour whose largest channel is v: half a
 * step of RGB9E5's 9-bit mantissa (0 for the wide planes). */
static inline double sf_rgb_rounding(double v)
{
#if TG_WIDE_STORAGE
    (void)v;
    return 0;
#else
    return v > 0 ? ldexp(1.0, (int)floor(log2(v)) - 9) : 0;
#endif
}

/* ---- last frame's geometry ---- */
static inline void sf_prev_alloc(tgi_prev_geometry *h, size_t n)
{
    tgi_prev_carve(h, n, sf_calloc(tgi_prev_carve(h, n, NULL), 1));
}
static inline void sf_prev_free(tgi_prev_geometry *h)
{
    free(SF_PREV_BLOCK(h));
    memset(h, 0, sizeof *h);
}

/* ---- GI results ---- */
static inline void sf_results_alloc(tgi_gresult *r, size_t n, int bent, int cone, int near)
{
    tgi_gresult_carve(r, n, bent, cone, near, sf_calloc(tgi_gresult_carve(r, n, bent, cone, near, NULL), 1));
}
static inline void sf_results_free(tgi_gresult *r)
{
    free(r->ao);      /* the block's first part */
    memset(r, 0, sizeof *r);
}
/* Decode n pixels of r into planes (any may be NULL; what r lacks is left alone). */
static inline void sf_results_read(const tgi_gresult *r, size_t n, tg_real *ao, tg_real *bx, tg_real *by, tg_real *bz,
                            tg_real *cone, tg_real *nr, tg_real *ng, tg_real *nb)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (ao) ao[i] = tgi_gr_ao(r, i);
        if (bx && tgi_gr_has_bent(r)) {
            tg_vec3 b = tgi_gr_bent(r, i);
            bx[i] = b.x; by[i] = b.y; bz[i] = b.z;
        }
        if (cone && r->cone) cone[i] = tgi_gr_cone(r, i);
        if (nr && tgi_gr_has_near(r)) {
            tg_vec3 e = tgi_gr_near(r, i);
            nr[i] = e.x; ng[i] = e.y; nb[i] = e.z;
        }
    }
}

#endif
