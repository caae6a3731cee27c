/* SPDX-License-Identifier: MIT */
/*
 * gview.h - where a pass reads the G-buffer (tgi_gview) and where it reads
 * and writes its results (tgi_gresult, tgi_rgb).
 *
 * One view type serves the full-resolution G-buffer, its half-resolution
 * copy (the quarter-res GI kernel) and each 4x4 sub-image, whether the
 * sub-image is a packed copy or a strided view of a larger image.  A view
 * is width x height pixels; its pixel (x, y)
 *   - is at index  i = y * row_stride + x * pixel_stride  of its storage
 *     (tgi_gv_index; the storage pointers start at the view's pixel (0, 0)),
 *   - stands for the full-resolution pixel
 *     (x * step + offset_x, y * step + offset_y)  of the camera's image.
 *
 * Passes read and write ONLY through the accessors below, never through the
 * storage, so that a narrower storage (octahedral normals, one material
 * index per pixel, sky folded into depth 0, 8-bit AO, shared-exponent RGB)
 * changes this file and the rasterizer's writer, not the passes.
 *
 * A results view (tgi_gresult: AO, bent normal, cone, near-field
 * irradiance) and colour planes (tgi_rgb: radiance or irradiance) are
 * indexed like the G-buffer view they are used with.
 */
#ifndef TG_GVIEW_H
#define TG_GVIEW_H

#include "gbuffer.h"
#include "view.h"

typedef struct tgi_gview {
    int width, height;             /* pixels of this view */
    int row_stride, pixel_stride;  /* index of pixel (x, y): y * row_stride + x * pixel_stride */
    int step, offset_x, offset_y;  /* pixel (x, y) stands for full-res (x * step + offset_x, ...) */
    const tgi_view *camera;        /* the full-resolution camera; NULL: none */
    tgi_gbuffer store;             /* the storage at pixel (0, 0): through the accessors only */
} tgi_gview;

static inline size_t tgi_gv_index(const tgi_gview *v, int x, int y)
{
    return (size_t)y * (size_t)v->row_stride + (size_t)x * (size_t)v->pixel_stride;
}
/* Linear view depth (view-space z), 0 on sky. */
static inline tg_real tgi_gv_depth(const tgi_gview *v, size_t i) { return v->store.depth[i]; }
/* World-space unit normal, facing the viewer. */
static inline tg_vec3 tgi_gv_normal(const tgi_gview *v, size_t i)
{
    return tg_v3(v->store.nx[i], v->store.ny[i], v->store.nz[i]);
}
/* 1 where no triangle was drawn. */
static inline int tgi_gv_is_sky(const tgi_gview *v, size_t i) { return v->store.sky[i] != 0; }
static inline tg_vec3 tgi_gv_albedo(const tgi_gview *v, size_t i)
{
    return tg_v3(v->store.albedo_r[i], v->store.albedo_g[i], v->store.albedo_b[i]);
}
/* Specular reflectance at normal incidence; 0 when the view carries none. */
static inline tg_real tgi_gv_f0(const tgi_gview *v, size_t i) { return v->store.f0 ? v->store.f0[i] : 0; }
/* 1 when some material of the scene emits (else tgi_gv_emissive is 0). */
static inline int tgi_gv_has_emissive(const tgi_gview *v) { return v->store.emit_r != NULL; }
static inline tg_vec3 tgi_gv_emissive(const tgi_gview *v, size_t i)
{
    return tg_v3(v->store.emit_r[i], v->store.emit_g[i], v->store.emit_b[i]);
}

/* Storage g seen from index `start` on (absent planes stay absent). */
static inline tgi_gbuffer tgi_gbuffer_from(const tgi_gbuffer *g, size_t start)
{
    tgi_gbuffer s = *g;
#define TGI_FROM(p) s.p = g->p ? g->p + start : NULL
    TGI_FROM(depth); TGI_FROM(nx); TGI_FROM(ny); TGI_FROM(nz);
    TGI_FROM(albedo_r); TGI_FROM(albedo_g); TGI_FROM(albedo_b); TGI_FROM(f0);
    TGI_FROM(emit_r); TGI_FROM(emit_g); TGI_FROM(emit_b);
    TGI_FROM(sky); TGI_FROM(object); TGI_FROM(motion_x); TGI_FROM(motion_y);
#undef TGI_FROM
    return s;
}

/* The packed view of `w` x `h` pixels of storage g from index `start` on,
 * standing for full-res (x * step + ox, y * step + oy). */
static inline void tgi_gview_packed(tgi_gview *v, const tgi_gbuffer *g, size_t start, int w, int h,
                                    int step, int ox, int oy, const tgi_view *camera)
{
    v->width = w;
    v->height = h;
    v->row_stride = w;
    v->pixel_stride = 1;
    v->step = step;
    v->offset_x = ox;
    v->offset_y = oy;
    v->camera = camera;
    v->store = tgi_gbuffer_from(g, start);
    v->store.width = w;
    v->store.height = h;
}

/* The packed view of a whole G-buffer (full resolution: step 1, no offset). */
static inline void tgi_gview_of(tgi_gview *v, const tgi_gbuffer *g, const tgi_view *camera)
{
    tgi_gview_packed(v, g, 0, g->width, g->height, 1, 0, 0, camera);
}

/* Sub-image (i, j), i, j in 0..3, of `full` as a strided view of the same
 * storage (no copy): its pixel (x, y) is full's pixel (4x + i, 4y + j).
 * Empty (0 x 0) when full is narrower than i + 1 or lower than j + 1. */
static inline void tgi_gview_strided_sub(tgi_gview *sub, const tgi_gview *full, int i, int j)
{
    int w = full->width > i ? (full->width - i + 3) / 4 : 0, h = full->height > j ? (full->height - j + 3) / 4 : 0;
    *sub = *full;
    sub->width = w;
    sub->height = h;
    sub->row_stride = 4 * full->row_stride;
    sub->pixel_stride = 4 * full->pixel_stride;
    sub->step = 4 * full->step;
    sub->offset_x = full->offset_x + i * full->step;
    sub->offset_y = full->offset_y + j * full->step;
    if (w && h) sub->store = tgi_gbuffer_from(&full->store, tgi_gv_index(full, i, j));
}
/* Copy pixel i of src into pixel j of the packed storage dst: the depth,
 * normal, sky and (when dst has it) F0. */
static inline void tgi_gview_copy_pixel(const tgi_gbuffer *dst, size_t j, const tgi_gview *src, size_t i)
{
    dst->depth[j] = src->store.depth[i];
    dst->nx[j] = src->store.nx[i];
    dst->ny[j] = src->store.ny[i];
    dst->nz[j] = src->store.nz[i];
    dst->sky[j] = src->store.sky[i];
    if (dst->f0) dst->f0[j] = src->store.f0[i];
}

/* ---- colour planes: radiance or irradiance, linear RGB ---- */
typedef struct tgi_rgb { tg_real *r, *g, *b; } tgi_rgb;   /* r NULL: absent */

static inline int tgi_rgb_present(const tgi_rgb *c) { return c && c->r != NULL; }
static inline tg_vec3 tgi_rgb_get(const tgi_rgb *c, size_t i) { return tg_v3(c->r[i], c->g[i], c->b[i]); }
static inline void tgi_rgb_set(const tgi_rgb *c, size_t i, tg_vec3 v) { c->r[i] = v.x; c->g[i] = v.y; c->b[i] = v.z; }
/* The planes seen from index `start` on (absent stays absent). */
static inline tgi_rgb tgi_rgb_from(const tgi_rgb *c, size_t start)
{
    tgi_rgb s;
    s.r = c->r ? c->r + start : NULL;
    s.g = c->g ? c->g + start : NULL;
    s.b = c->b ? c->b + start : NULL;
    return s;
}

/* ---- the GI results of a pass ---- */
typedef struct tgi_gresult {
    tg_real *ao;                         /* [0, 1], 1 = open; always present */
    tg_real *bent_x, *bent_y, *bent_z;   /* world unit bent normal; NULL: not wanted */
    tg_real *cone;                       /* bent-cone half angle, radians; NULL: not wanted */
    tgi_rgb near;                        /* near-field irradiance; r NULL: not gathered */
} tgi_gresult;

static inline tg_real tgi_gr_ao(const tgi_gresult *r, size_t i) { return r->ao[i]; }
static inline void tgi_gr_set_ao(const tgi_gresult *r, size_t i, tg_real v) { r->ao[i] = v; }
static inline int tgi_gr_has_bent(const tgi_gresult *r) { return r->bent_x != NULL; }
static inline tg_vec3 tgi_gr_bent(const tgi_gresult *r, size_t i) { return tg_v3(r->bent_x[i], r->bent_y[i], r->bent_z[i]); }
static inline void tgi_gr_set_bent(const tgi_gresult *r, size_t i, tg_vec3 b)
{
    r->bent_x[i] = b.x; r->bent_y[i] = b.y; r->bent_z[i] = b.z;
}
static inline int tgi_gr_has_cone(const tgi_gresult *r) { return r->cone != NULL; }
static inline tg_real tgi_gr_cone(const tgi_gresult *r, size_t i) { return r->cone[i]; }
static inline void tgi_gr_set_cone(const tgi_gresult *r, size_t i, tg_real c) { r->cone[i] = c; }
static inline int tgi_gr_has_near(const tgi_gresult *r) { return r->near.r != NULL; }
static inline tg_vec3 tgi_gr_near(const tgi_gresult *r, size_t i) { return tgi_rgb_get(&r->near, i); }
static inline void tgi_gr_set_near(const tgi_gresult *r, size_t i, tg_vec3 e) { tgi_rgb_set(&r->near, i, e); }

/* The results seen from index `start` on (a sub-image of a larger image). */
static inline tgi_gresult tgi_gresult_from(const tgi_gresult *r, size_t start)
{
    tgi_gresult s;
    s.ao = r->ao ? r->ao + start : NULL;
    s.bent_x = r->bent_x ? r->bent_x + start : NULL;
    s.bent_y = r->bent_y ? r->bent_y + start : NULL;
    s.bent_z = r->bent_z ? r->bent_z + start : NULL;
    s.cone = r->cone ? r->cone + start : NULL;
    s.near = tgi_rgb_from(&r->near, start);
    return s;
}

/* Copy pixel i of src into pixel j of dst: the channels both have. */
static inline void tgi_gresult_copy_pixel(const tgi_gresult *dst, size_t j, const tgi_gresult *src, size_t i)
{
    tgi_gr_set_ao(dst, j, tgi_gr_ao(src, i));
    if (tgi_gr_has_bent(dst) && tgi_gr_has_bent(src)) tgi_gr_set_bent(dst, j, tgi_gr_bent(src, i));
    if (tgi_gr_has_cone(dst) && tgi_gr_has_cone(src)) tgi_gr_set_cone(dst, j, tgi_gr_cone(src, i));
    if (tgi_gr_has_near(dst) && tgi_gr_has_near(src)) tgi_gr_set_near(dst, j, tgi_gr_near(src, i));
}

#endif
