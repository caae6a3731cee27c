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
 * storage: the formats (pack.h, gbuffer.h) live here and in the rasterizer's
 * writer, not in the passes.
 *   G-buffer   binary32 depth with sky as 0; octahedral normal 2x11 bits and
 *              a material index in 32 bits (albedo, F0 and emissive read
 *              from the scene's material table); in a frame that reads no
 *              material (AO only) the octahedral normal 2x8 alone
 *   results    AO in 8 bits; bent normal octahedral 2x8; the cone is not
 *              stored (acos sqrt(1 - AO) when read, src/light/sh.h); near-field
 *              irradiance as a colour plane
 *   colour     RGB9E5 (shared exponent, saturating, never negative)
 * With TG_WIDE_STORAGE=1 every one of them is tg_real planes.
 *
 * A results view (tgi_gresult: AO, bent normal, near-field irradiance) and
 * colour planes (tgi_rgb: radiance or irradiance) are indexed like the
 * G-buffer view they are used with.
 */
#ifndef TG_GVIEW_H
#define TG_GVIEW_H

#include "gbuffer.h"
#include "view.h"
#include "pack.h"

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

/* ---- the G-buffer: reading ---- */

/* 1 where no triangle was drawn (depth 0). */
static inline int tgi_gv_is_sky(const tgi_gview *v, size_t i) { return v->store.depth[i] == 0; }
/* A pass that meets the normal's stored code it decoded last
 * (tgi_gv_normal_word: a plane's pixels share theirs) takes that normal
 * instead of decoding it again (denoise.c, direct.c, temporal.c); not with normals
 * stored as tg_real (nothing to decode) nor in a build for size. */
#define TGI_REUSE_NORMAL (!TG_WIDE_STORAGE && !TG_OUTLINE_HELPERS)
#if TG_WIDE_STORAGE
/* Linear view depth (view-space z), 0 on sky. */
static inline tg_real tgi_gv_depth(const tgi_gview *v, size_t i) { return v->store.depth[i]; }
/* World-space unit normal, facing the viewer (undefined on sky). */
static inline tg_vec3 tgi_gv_normal(const tgi_gview *v, size_t i)
{
    return tg_v3(v->store.nx[i], v->store.ny[i], v->store.nz[i]);
}
static inline int tgi_gv_material_index(const tgi_gview *v, size_t i) { return v->store.material[i]; }
#else
static inline tg_real tgi_gv_depth(const tgi_gview *v, size_t i) { return tgi_depth_unpack(v->store.depth[i]); }
static inline tg_vec3 tgi_gv_normal(const tgi_gview *v, size_t i)
{
    if (!v->store.nm) return tgi_oct_unpack(v->store.n8[i], 8);
    return tgi_oct_unpack(v->store.nm[i] & TGI_NORMAL_MASK, TGI_NORMAL_BITS);
}
/* The normal's stored code (its octahedral direction's bits): equal codes
 * give equal normals (tgi_gv_normal). */
static inline uint32_t tgi_gv_normal_word(const tgi_gview *v, size_t i)
{
    return v->store.nm ? v->store.nm[i] & TGI_NORMAL_MASK : v->store.n8[i];
}
/* The normal as its octahedral direction before the normalisation
 * (tgi_oct_fold): tgi_gv_normal is this over its length. */
static inline tgi_oct_dir tgi_gv_normal_dir(const tgi_gview *v, size_t i)
{
    if (!v->store.nm) return tgi_oct_fold(v->store.n8[i], 8);
    return tgi_oct_fold(v->store.nm[i] & TGI_NORMAL_MASK, TGI_NORMAL_BITS);
}
static inline int tgi_gv_material_index(const tgi_gview *v, size_t i)
{
    return v->store.nm ? (int)(v->store.nm[i] >> TGI_MATERIAL_SHIFT) : 0;
}
#endif
/* The normal a pass decoded last and its stored code (TGI_REUSE_NORMAL;
 * UINT64_MAX: none yet, no code is), or what the pass derived from that
 * normal (resample.c keeps it in view space). */
typedef struct tgi_normal_memo {
    uint64_t code;
    tg_vec3 n;
} tgi_normal_memo;
static inline void tgi_normal_memo_start(tgi_normal_memo *m)
{
    m->code = UINT64_MAX;
    m->n = tg_v3(0, 0, 0);
}
/* 1 when pixel i's stored normal code is m's (m->n then stands for its
 * normal); else m takes the code and 0 (the caller sets m->n).  Always 0
 * without TGI_REUSE_NORMAL. */
static inline int tgi_gv_normal_repeats(const tgi_gview *v, tgi_normal_memo *m, size_t i)
{
#if TGI_REUSE_NORMAL
    const uint32_t code = tgi_gv_normal_word(v, i);
    if (code == m->code) return 1;
    m->code = code;
#else
    (void)v; (void)m; (void)i;
#endif
    return 0;
}
/* Pixel i's normal (tgi_gv_normal), the one m holds where the code repeats. */
static inline tg_vec3 tgi_gv_normal_memo(const tgi_gview *v, tgi_normal_memo *m, size_t i)
{
    if (!tgi_gv_normal_repeats(v, m, i)) m->n = tgi_gv_normal(v, i);
    return m->n;
}
/* The second depth layer (request.depth_layers 2): the view depth of the
 * nearest back face at or behind the pixel's surface (a one-sided triangle
 * facing away, or either face of a twosided one: then the surface's own
 * depth), where a closed object the depth buffer sees ends; 0 where no back
 * face was drawn or the frame has no second layer. */
#if !TGI_DEPTH_LAYERS
#define TGI_LAYER_DEPTH(v, plane, i) ((void)(v), (void)(i), (tg_real)0)   /* left out (gbuffer.h) */
#elif TG_WIDE_STORAGE
#define TGI_LAYER_DEPTH(v, plane, i) ((v)->store.plane ? (v)->store.plane[i] : 0)
#else
#define TGI_LAYER_DEPTH(v, plane, i) ((v)->store.plane ? tgi_depth_unpack((v)->store.plane[i]) : 0)
#endif
#if TGI_DEPTH_LAYERS && !TG_WIDE_STORAGE   /* an 8-bit code against the pixel's depth (pack.h) */
static inline tg_real tgi_gv_back_depth(const tgi_gview *v, size_t i)
{
    return v->store.back_depth ? tgi_back_decode(v->store.back_depth[i], tgi_gv_depth(v, i)) : 0;
}
#else
static inline tg_real tgi_gv_back_depth(const tgi_gview *v, size_t i) { return TGI_LAYER_DEPTH(v, back_depth, i); }
#endif
/* The third (request.depth_layers 3): the view depth of the nearest
 * surface (either facing) behind that back face, where the space a closed
 * object's back leaves open ends (the floor under a sphere); 0 where none. */
static inline tg_real tgi_gv_behind_depth(const tgi_gview *v, size_t i) { return TGI_LAYER_DEPTH(v, behind_depth, i); }

/* 1 when the storage holds a material per pixel (not so in an AO-only frame). */
static inline int tgi_gb_has_material(const tgi_gbuffer *g)
{
#if TG_WIDE_STORAGE
    return g->material != NULL;
#else
    return g->nm != NULL;
#endif
}
/* The surface's material (NULL on sky, or without materials). */
static inline const tgi_material *tgi_gv_material(const tgi_gview *v, size_t i)
{
    if (tgi_gv_is_sky(v, i) || !tgi_gb_has_material(&v->store)) return NULL;
    return &v->store.materials[tgi_gv_material_index(v, i)];
}
/* Albedo, F0 and emissive of the material; 0 on sky. */
static inline tg_vec3 tgi_gv_albedo(const tgi_gview *v, size_t i)
{
    const tgi_material *m = tgi_gv_material(v, i);
    return m ? m->albedo : tg_v3(0, 0, 0);
}
static inline tg_real tgi_gv_f0(const tgi_gview *v, size_t i)
{
    const tgi_material *m = tgi_gv_material(v, i);
    return m ? m->f0 : 0;
}
/* 1 when some material of the scene emits (else tgi_gv_emissive is 0). */
static inline int tgi_gv_has_emissive(const tgi_gview *v) { return v->store.has_emissive; }
static inline tg_vec3 tgi_gv_emissive(const tgi_gview *v, size_t i)
{
    const tgi_material *m = tgi_gv_material(v, i);
    return m ? m->emissive : tg_v3(0, 0, 0);
}

/* ---- the G-buffer: writing (the rasterizer, copies, tests) ---- */

/* Pixel i of storage g: a surface at view depth z > 0 with world normal n
 * (any length > 0) of material `material`. */
static inline void tgi_gb_set(const tgi_gbuffer *g, size_t i, tg_real z, tg_vec3 n, int material)
{
#if TG_WIDE_STORAGE
    n = tgi_v3_normalize_or(n, tg_v3(0, 0, TG_ONE));
    g->depth[i] = z > 0 ? z : 0;
    g->nx[i] = n.x; g->ny[i] = n.y; g->nz[i] = n.z;
    g->material[i] = (uint16_t)material;
#else
    g->depth[i] = tgi_depth_pack(z);
    if (g->nm) g->nm[i] = tgi_oct_pack(n, TGI_NORMAL_BITS) | ((uint32_t)material << TGI_MATERIAL_SHIFT);
    else g->n8[i] = (uint16_t)tgi_oct_pack(n, 8);
#endif
}
/* Pixel i of storage g: sky. */
static inline void tgi_gb_set_sky(const tgi_gbuffer *g, size_t i) { g->depth[i] = 0; }

/* Storage g seen from index `start` on (absent planes stay absent). */
static inline tgi_gbuffer tgi_gbuffer_from(const tgi_gbuffer *g, size_t start)
{
    tgi_gbuffer s = *g;
#define TGI_FROM(p) s.p = g->p ? g->p + start : NULL
#if TG_WIDE_STORAGE
    TGI_FROM(depth); TGI_FROM(nx); TGI_FROM(ny); TGI_FROM(nz); TGI_FROM(material);
#else
    TGI_FROM(depth); TGI_FROM(nm); TGI_FROM(n8);
#endif
    TGI_FROM(object); TGI_FROM(motion_x); TGI_FROM(motion_y);
#if TGI_DEPTH_LAYERS
    TGI_FROM(back_depth); TGI_FROM(behind_depth);
#endif
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
/* Copy pixel i of src into pixel j of the packed storage dst: depth, normal
 * and material, as stored (no conversion). */
static inline void tgi_gview_copy_pixel(const tgi_gbuffer *dst, size_t j, const tgi_gview *src, size_t i)
{
    dst->depth[j] = src->store.depth[i];
#if TG_WIDE_STORAGE
    dst->nx[j] = src->store.nx[i];
    dst->ny[j] = src->store.ny[i];
    dst->nz[j] = src->store.nz[i];
    dst->material[j] = src->store.material[i];
#else
    if (dst->nm) dst->nm[j] = src->store.nm[i];   /* dst has src's planes */
    else dst->n8[j] = src->store.n8[i];
#endif
#if TGI_DEPTH_LAYERS   /* the further depth layers where dst has them (src has them then) */
    if (dst->back_depth) dst->back_depth[j] = src->store.back_depth[i];
    if (dst->behind_depth) dst->behind_depth[j] = src->store.behind_depth[i];
#endif
}

/* ---- the light a diffuse surface sends ---- */

/* Lo of pixel i of storage g under irradiance e: albedo / pi (1 - F0) e +
 * emissive (HBIL sec. 2.3: eq. 14's 1/pi, eq. 19's 1 - F0; the material's
 * diffuse); 0 on sky. */
static inline tg_vec3 tgi_gb_lit(const tgi_gbuffer *g, size_t i, tg_vec3 e)
{
    const tgi_material *m;
    tg_vec3 lo;
    if (g->depth[i] == 0 || !tgi_gb_has_material(g)) return tg_v3(0, 0, 0);
#if TG_WIDE_STORAGE
    m = &g->materials[g->material[i]];
#else
    m = &g->materials[g->nm[i] >> TGI_MATERIAL_SHIFT];
#endif
    /* diffuse <= 1/pi: each product is smaller than its e, never saturates (tgi_wide_mul: tg_mul's rounding) */
    lo = tg_v3((tg_real)tgi_wide_mul(m->diffuse.x, e.x), (tg_real)tgi_wide_mul(m->diffuse.y, e.y),
               (tg_real)tgi_wide_mul(m->diffuse.z, e.z));
#if TG_FIXED
    /* a material that emits nothing adds nothing: lo itself, without three
     * saturating adds of 0 (in a scene with a light panel, most reads) */
    if (!g->has_emissive || (m->emissive.x | m->emissive.y | m->emissive.z) == 0) return lo;
    return tgi_v3_add(lo, m->emissive);
#else
    return g->has_emissive ? tgi_v3_add(lo, m->emissive) : lo;
#endif
}
static inline tg_vec3 tgi_gv_lit(const tgi_gview *v, size_t i, tg_vec3 e) { return tgi_gb_lit(&v->store, i, e); }

/* ---- colour planes: radiance or irradiance, linear RGB ----
 * A plane may be read as lit: it holds irradiance, and its reads give the
 * radiance its surfaces send (tgi_gb_lit), so the direct light's plane is
 * also the near field's first source without a plane of its own. */
typedef struct tgi_rgb {
#if TG_WIDE_STORAGE
    tg_real *r, *g, *b;            /* r NULL: absent */
#else
    uint32_t *p;                   /* RGB9E5 words; NULL: absent */
#endif
    const tgi_gbuffer *lit;        /* non-NULL: reads are tgi_gb_lit of these surfaces */
    size_t lit_at;                 /* pixel i of the plane is pixel lit_at + i of lit */
} tgi_rgb;

#if TG_WIDE_STORAGE
static inline int tgi_rgb_present(const tgi_rgb *c) { return c && c->r != NULL; }
static inline tg_vec3 tgi_rgb_stored(const tgi_rgb *c, size_t i) { return tg_v3(c->r[i], c->g[i], c->b[i]); }
static inline void tgi_rgb_set(const tgi_rgb *c, size_t i, tg_vec3 v) { c->r[i] = v.x; c->g[i] = v.y; c->b[i] = v.z; }
#else
static inline int tgi_rgb_present(const tgi_rgb *c) { return c && c->p != NULL; }
static inline tg_vec3 tgi_rgb_stored(const tgi_rgb *c, size_t i) { return tgi_rgb9e5_unpack(c->p[i]); }
static inline void tgi_rgb_set(const tgi_rgb *c, size_t i, tg_vec3 v) { c->p[i] = tgi_rgb9e5_pack(v); }
#endif
/* The read, inline wherever it is called: the kernel's gather calls it
 * (gcc left tgi_rgb_get a call there in Q16.16, its tg_vec3 returned
 * through the stack: -0.6% of cornell's Q16.16 frame), the other passes
 * tgi_rgb_get, which the compiler places (forced into every reader it cost
 * push/pull 32 instructions a pixel).  Compiling for size
 * (TG_OUTLINE_HELPERS) leaves both to the compiler. */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
#define TGI_RGB_GET_INLINE inline __attribute__((always_inline))
#else
#define TGI_RGB_GET_INLINE inline
#endif
static TGI_RGB_GET_INLINE tg_vec3 tgi_rgb_read(const tgi_rgb *c, size_t i)
{
    tg_vec3 v = tgi_rgb_stored(c, i);
    if (!c->lit) return v;
    return tgi_gb_lit(c->lit, c->lit_at + i, v);
}
static inline tg_vec3 tgi_rgb_get(const tgi_rgb *c, size_t i) { return tgi_rgb_read(c, i); }
#if TG_WIDE_STORAGE
/* A vector stored wide, three tg_real planes, moved on to index `start`
 * (absent planes stay absent). */
static inline void tgi_real3_from(tg_real **x, tg_real **y, tg_real **z, size_t start)
{
    *x = *x ? *x + start : NULL;
    *y = *y ? *y + start : NULL;
    *z = *z ? *z + start : NULL;
}
#endif
/* The plane seen from index `start` on (absent stays absent). */
static inline tgi_rgb tgi_rgb_from(const tgi_rgb *c, size_t start)
{
    tgi_rgb s = *c;
#if TG_WIDE_STORAGE
    tgi_real3_from(&s.r, &s.g, &s.b, start);
#else
    s.p = c->p ? c->p + start : NULL;
#endif
    s.lit_at = c->lit_at + start;
    return s;
}
/* The same plane read as lit by the surfaces of g (pixel i of the plane is pixel i of g). */
static inline tgi_rgb tgi_rgb_lit_by(const tgi_rgb *c, const tgi_gbuffer *g)
{
    tgi_rgb s = *c;
    s.lit = g;
    s.lit_at = 0;
    return s;
}
/* An absent colour plane. */
static inline tgi_rgb tgi_rgb_none(void)
{
    tgi_rgb c;
    memset(&c, 0, sizeof c);
    return c;
}
/* Bytes a pixel of a colour plane. */
#define TGI_RGB_PIXEL_BYTES (TG_WIDE_STORAGE ? 3 * sizeof(tg_real) : sizeof(uint32_t))
/* Pixel j of dst = pixel i of src, as stored (src not lit). */
#if TG_WIDE_STORAGE
static inline void tgi_rgb_copy(const tgi_rgb *dst, size_t j, const tgi_rgb *src, size_t i)
{
    dst->r[j] = src->r[i]; dst->g[j] = src->g[i]; dst->b[j] = src->b[i];
}
#else
static inline void tgi_rgb_copy(const tgi_rgb *dst, size_t j, const tgi_rgb *src, size_t i) { dst->p[j] = src->p[i]; }
#endif
/* A pixel without a value (a reprojection hole): reads as 0, marked apart. */
#if TG_WIDE_STORAGE
static inline void tgi_rgb_set_hole(const tgi_rgb *c, size_t i) { c->r[i] = TG_REAL_MIN; c->g[i] = c->b[i] = 0; }
static inline int tgi_rgb_is_hole(const tgi_rgb *c, size_t i) { return c->r[i] == TG_REAL_MIN; }
#else
static inline void tgi_rgb_set_hole(const tgi_rgb *c, size_t i) { c->p[i] = TGI_RGB9E5_INVALID; }
static inline int tgi_rgb_is_hole(const tgi_rgb *c, size_t i) { return c->p[i] == TGI_RGB9E5_INVALID; }
#endif

/* ---- last frame's geometry: what reprojection and temporal accumulation
 * test a pixel's history against.  Compact: one word a pixel, the view
 * depth's binary32 bits rounded to their top 16 (8-bit exponent, 7-bit
 * mantissa: 0.4%, against a 5% depth tolerance) and the normal octahedral
 * 2x8. ---- */
typedef struct tgi_prev_geometry {
#if TG_WIDE_STORAGE
    tg_real *depth, *nx, *ny, *nz;
#else
    uint32_t *dn;                 /* depth bits >> 16 above, octahedral normal below */
#endif
} tgi_prev_geometry;

#if !TG_WIDE_STORAGE
/* The word of a pixel of stored depth bits d (0: sky) and octahedral 2x8
 * normal code oct. */
static inline uint32_t tgi_prev_word(uint32_t d, uint32_t oct)
{
    const uint32_t top = d ? (d + 0x8000u) >> 16 : 0;
    return (top << 16) | oct;
}
#endif
/* Keep pixel i of view g as pixel j of last frame's geometry h. */
static inline void tgi_prev_keep(const tgi_prev_geometry *h, size_t j, const tgi_gview *g, size_t i)
{
    tg_vec3 n = tgi_gv_is_sky(g, i) ? tg_v3(0, 0, TG_ONE) : tgi_gv_normal(g, i);
#if TG_WIDE_STORAGE
    h->depth[j] = tgi_gv_depth(g, i);
    h->nx[j] = n.x; h->ny[j] = n.y; h->nz[j] = n.z;
#else
    h->dn[j] = tgi_prev_word(g->store.depth[i], tgi_oct_pack(n, 8));
#endif
}
#if TG_WIDE_STORAGE
static inline tg_real tgi_prev_depth(const tgi_prev_geometry *h, size_t j) { return h->depth[j]; }
static inline tg_vec3 tgi_prev_normal(const tgi_prev_geometry *h, size_t j)
{
    return tg_v3(h->nx[j], h->ny[j], h->nz[j]);
}
#else
static inline tg_real tgi_prev_depth(const tgi_prev_geometry *h, size_t j)
{
    return tgi_depth_unpack(h->dn[j] & 0xFFFF0000u);
}
static inline tg_vec3 tgi_prev_normal(const tgi_prev_geometry *h, size_t j) { return tgi_oct_unpack(h->dn[j] & 0xFFFFu, 8); }
#endif
/* Last frame's normal of pixel j (tgi_prev_normal), the one m holds where
 * its octahedral code (the word's low 16 bits) repeats. */
static inline tg_vec3 tgi_prev_normal_memo(const tgi_prev_geometry *h, tgi_normal_memo *m, size_t j)
{
#if TGI_REUSE_NORMAL
    const uint32_t code = h->dn[j] & 0xFFFFu;
    if (code != m->code) {
        m->code = code;
        m->n = tgi_prev_normal(h, j);
    }
    return m->n;
#else
    (void)m;
    return tgi_prev_normal(h, j);
#endif
}

/* ---- the GI results of a pass ---- */
typedef struct tgi_gresult {
#if TG_WIDE_STORAGE
    tg_real *ao;                         /* [0, 1], 1 = open; always present */
    tg_real *bent_x, *bent_y, *bent_z;   /* world unit bent normal; NULL: not wanted */
    tg_real *cone;                       /* a technique's own cone half angle; NULL: from the AO */
#else
    uint8_t *ao;                         /* unorm8 */
    uint16_t *bent;                      /* octahedral 2x8 */
    uint8_t *cone;                       /* unorm8 of the angle / (pi / 2); NULL: from the AO */
#endif
    tgi_rgb near;                        /* near-field irradiance; absent: not gathered */
} tgi_gresult;

#if TG_WIDE_STORAGE
static inline tg_real tgi_gr_ao(const tgi_gresult *r, size_t i) { return r->ao[i]; }
static inline void tgi_gr_set_ao(const tgi_gresult *r, size_t i, tg_real v) { r->ao[i] = v; }
static inline int tgi_gr_has_bent(const tgi_gresult *r) { return r->bent_x != NULL; }
static inline tg_vec3 tgi_gr_bent(const tgi_gresult *r, size_t i) { return tg_v3(r->bent_x[i], r->bent_y[i], r->bent_z[i]); }
static inline void tgi_gr_set_bent(const tgi_gresult *r, size_t i, tg_vec3 b)
{
    r->bent_x[i] = b.x; r->bent_y[i] = b.y; r->bent_z[i] = b.z;
}
#else
static inline tg_real tgi_gr_ao(const tgi_gresult *r, size_t i) { return tgi_unorm8_unpack(r->ao[i]); }
static inline void tgi_gr_set_ao(const tgi_gresult *r, size_t i, tg_real v) { r->ao[i] = tgi_unorm8_pack(v); }
static inline int tgi_gr_has_bent(const tgi_gresult *r) { return r->bent != NULL; }
static inline tg_vec3 tgi_gr_bent(const tgi_gresult *r, size_t i) { return tgi_oct_unpack(r->bent[i], 8); }
/* The bent normal's stored code: equal codes give equal bent normals (tgi_gr_bent). */
static inline uint32_t tgi_gr_bent_word(const tgi_gresult *r, size_t i) { return r->bent[i]; }
static inline void tgi_gr_set_bent(const tgi_gresult *r, size_t i, tg_vec3 b) { r->bent[i] = (uint16_t)tgi_oct_pack(b, 8); }
#endif
/* The bent cone's half angle: from the AO when read, unless a
 * results view carries a cone plane of its own (a technique's estimate, for
 * its tests: the frame carves none).  Writes without a plane go nowhere. */
static inline int tgi_gr_has_cone(const tgi_gresult *r) { return r->cone != NULL; }
#if TG_WIDE_STORAGE
static inline void tgi_gr_set_cone(const tgi_gresult *r, size_t i, tg_real c) { if (r->cone) r->cone[i] = c; }
static inline tg_real tgi_gr_stored_cone(const tgi_gresult *r, size_t i) { return r->cone[i]; }
#else
static inline void tgi_gr_set_cone(const tgi_gresult *r, size_t i, tg_real c)
{
    if (r->cone) r->cone[i] = tgi_unorm8_pack(tg_div(c, TG_HALF_PI));
}
static inline tg_real tgi_gr_stored_cone(const tgi_gresult *r, size_t i)
{
    return tg_mul(tgi_unorm8_unpack(r->cone[i]), TG_HALF_PI);
}
#endif
static inline tg_real tgi_gr_cone(const tgi_gresult *r, size_t i)
{
    if (r->cone) return tgi_gr_stored_cone(r, i);
    /* cos(alpha) = sqrt(1 - AO), a cosine-weighted AO's cone (tgi_cone_cos_from_ao, src/light/sh.h) */
    return tg_acos(tg_sqrt(tg_sub(TG_ONE, tg_saturate(tgi_gr_ao(r, i)))));
}
static inline int tgi_gr_has_near(const tgi_gresult *r) { return tgi_rgb_present(&r->near); }
static inline tg_vec3 tgi_gr_near(const tgi_gresult *r, size_t i) { return tgi_rgb_stored(&r->near, i); }   /* results are never lit */
static inline void tgi_gr_set_near(const tgi_gresult *r, size_t i, tg_vec3 e) { tgi_rgb_set(&r->near, i, e); }

/* Every channel of pixel i at once (those r lacks read as ao 1, bent 0, near 0). */
typedef struct tgi_gr_value { tg_real ao; tg_vec3 bent, near; } tgi_gr_value;
static inline tgi_gr_value tgi_gr_get(const tgi_gresult *r, size_t i)
{
    tgi_gr_value v;
    v.ao = r->ao ? tgi_gr_ao(r, i) : TG_ONE;
    v.bent = tgi_gr_has_bent(r) ? tgi_gr_bent(r, i) : tg_v3(0, 0, 0);
    v.near = tgi_gr_has_near(r) ? tgi_gr_near(r, i) : tg_v3(0, 0, 0);
    return v;
}
/* Write the channels r has. */
static inline void tgi_gr_put(const tgi_gresult *r, size_t i, const tgi_gr_value *v)
{
    if (r->ao) tgi_gr_set_ao(r, i, v->ao);
    if (tgi_gr_has_bent(r)) tgi_gr_set_bent(r, i, v->bent);
    if (tgi_gr_has_near(r)) tgi_gr_set_near(r, i, v->near);
}

/* The results seen from index `start` on (a sub-image of a larger image). */
static inline tgi_gresult tgi_gresult_from(const tgi_gresult *r, size_t start)
{
    tgi_gresult s = *r;
    s.ao = r->ao ? r->ao + start : NULL;
#if TG_WIDE_STORAGE
    tgi_real3_from(&s.bent_x, &s.bent_y, &s.bent_z, start);
#else
    s.bent = r->bent ? r->bent + start : NULL;
#endif
    s.cone = r->cone ? r->cone + start : NULL;
    s.near = tgi_rgb_from(&r->near, start);
    return s;
}

/* Copy pixel i of src into pixel j of dst: the channels both have. */
static inline void tgi_gresult_copy_pixel(const tgi_gresult *dst, size_t j, const tgi_gresult *src, size_t i)
{
#if TG_WIDE_STORAGE
    tgi_gr_set_ao(dst, j, tgi_gr_ao(src, i));
    if (tgi_gr_has_bent(dst) && tgi_gr_has_bent(src)) tgi_gr_set_bent(dst, j, tgi_gr_bent(src, i));
    if (dst->cone && src->cone) dst->cone[j] = src->cone[i];
    if (tgi_gr_has_near(dst) && tgi_gr_has_near(src)) tgi_gr_set_near(dst, j, tgi_gr_near(src, i));
#else
    dst->ao[j] = src->ao[i];                       /* the same formats: the words */
    if (dst->bent && src->bent) dst->bent[j] = src->bent[i];
    if (dst->cone && src->cone) dst->cone[j] = src->cone[i];
    if (dst->near.p && src->near.p) dst->near.p[j] = src->near.p[i];
#endif
}

/* ---- storage from one block of memory (gstore.c): each function points
 * its planes into mem (16-byte aligned parts; NULL: measure only) and
 * returns the bytes.  G-buffer planes only (materials, object and motion
 * are the caller's); results with the bent normal, a cone plane and the
 * near field when asked. ---- */
size_t tgi_gbuffer_carve(tgi_gbuffer *g, int w, int h, void *mem);
/* The same without the material: depth and normal only (compact: the
 * normal octahedral 2x8; wide: as tgi_gbuffer_carve). */
size_t tgi_gbuffer_carve_geometry(tgi_gbuffer *g, int w, int h, void *mem);
size_t tgi_gresult_carve(tgi_gresult *r, size_t n, int bent, int cone, int near, void *mem);
size_t tgi_rgb_carve(tgi_rgb *c, size_t n, void *mem);
size_t tgi_prev_carve(tgi_prev_geometry *h, size_t n, void *mem);

#endif
