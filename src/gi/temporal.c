/* SPDX-License-Identifier: MIT */
/*
 * temporal.c - exponential accumulation of the HBIL outputs over frames,
 * history rejected by depth and normal.  See temporal.h.
 */
#include "../tinygi.h"
#include "temporal.h"
#include "reproject.h"   /* tgi_reproject_prev_pixel */
#include "../core/unit.h"

void tgi_temporal_defaults(tgi_temporal_params *p)
{
    p->alpha = TG_R(0.2f);
    p->history_depth_tolerance = TG_R(0.05f);
    p->history_normal_cos = TG_R(0.9f);
}

/* Where last frame's results hold this pixel's surface (normal n, depth z
 * now, full-resolution pixel (fx, fy)): 1 and *s (indexed like g) when last
 * frame's depth and normal agree (the history is accepted).  The cameras of
 * cams are the caller's copies (locals: no store through the result planes
 * can change them, so their fields stay in registers along the row); unit:
 * g is the camera's whole image (step 1, no offset, its size, tgi_gv_index
 * y width + x). */
#if defined(__GNUC__)
__attribute__((always_inline))   /* one copy in the row loop, its tests against the row's registers */
#endif
static inline int history_at(const tgi_temporal_params *p, const tgi_gview *g, const tgi_prev_geometry *h,
                             const tgi_reproject_cams *cams, int unit, int fx, int fy, tg_real depth, tg_vec3 n,
                             size_t *s, tgi_normal_memo *pm)
{
    const tgi_view *view = cams->pair.cur;
    int px, py, sx, sy;
    tg_real z, hz;
    size_t full;
    if (!tgi_reproject_prev_pixel(cams, NULL, fx, fy, depth, &px, &py, &z)) return 0;
    if (unit) {
        /* step 1 at offset 0 over the whole image, stored row by row: the
         * pixel itself, at the same index in g */
        full = (size_t)py * (size_t)view->width + (size_t)px;
        *s = full;
    } else {
        sx = (px - g->offset_x) / g->step;    /* the pixel of g standing for the full-res pixel's block */
        sy = (py - g->offset_y) / g->step;
        if (px < g->offset_x || py < g->offset_y || sx >= g->width || sy >= g->height) return 0;
        *s = tgi_gv_index(g, sx, sy);
        full = (size_t)(sy * g->step + g->offset_y) * (size_t)view->width + (size_t)(sx * g->step + g->offset_x);
    }
    hz = tgi_prev_depth(h, full);
    /* hz - z without tg_sub's saturation: hz > 0 there and z > 0.0001 (an
     * accepted position), both at most TG_REAL_MAX; the normals are unit
     * vectors (tgi_v3_dot_bounded) */
    if (!(hz > 0 && tgi_abs_fast(hz - z) <= tg_mul(p->history_depth_tolerance, hz))) return 0;
    return tgi_v3_dot_bounded(tgi_prev_normal_memo(h, pm, full), n) >= p->history_normal_cos;
}

/* tg_lerp(a, b, t): in Q16.16 for t within [0, 1] and |b - a| within
 * range (tg_sub would not saturate) the product (b - a) t rounds to within
 * |b - a| (tg_mul, not saturating) and a plus it lies between a and b
 * (tg_add, not saturating): the same integers without the tests. */
static inline tg_real lerp_unit(tg_real a, tg_real b, tg_real t)
{
#if TG_FIXED
    const int64_t d = (int64_t)b - a;
    if ((uint32_t)t <= (uint32_t)TG_ONE && d >= TG_REAL_MIN && d <= TG_REAL_MAX)
        return (tg_real)(a + tgi_shr_round(d * t, 16));
#endif
    return tg_lerp(a, b, t);
}
static inline tg_vec3 lerp_unit3(tg_vec3 a, tg_vec3 b, tg_real t)
{
    return tg_v3(lerp_unit(a.x, b.x, t), lerp_unit(a.y, b.y, t), lerp_unit(a.z, b.z, t));
}

tg_real tgi_temporal_lerp(tg_real h, tg_real v, tg_real t) { return lerp_unit(h, v, t); }

/* What a row of tgi_temporal_rows reads: the caller's copies (locals: no
 * store into the results, bytes, which may alias anything, can change
 * them, so they stay in registers along the row). */
typedef struct temporal_rows_in {
    tgi_temporal_params p;
    tgi_gview g;
    tgi_gresult r, prev;
    tgi_prev_geometry h;
    tgi_reproject_cams cams;
    int unit, p_bent, r_ao, p_ao, r_near, p_near;   /* unit: history_at's; the rest whether each plane is there */
} temporal_rows_in;

/* Rows [y0, y1) of tgi_temporal_rows; has_bent whether r has a bent normal
 * (a constant where inlined: the loop without the bent normal's code). */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void accumulate_rows(const temporal_rows_in *t, int has_bent, int y0, int y1)
{
    const tgi_temporal_params *p = &t->p;
    const tgi_gview *g = &t->g;
    const tgi_gresult *r = &t->r, *prev = &t->prev;
    const tg_real alpha = p->alpha;
    const int p_bent = t->p_bent, r_ao = t->r_ao, p_ao = t->p_ao, r_near = t->r_near, p_near = t->p_near;
    int x, y;
#if TGI_REUSE_NORMAL
    uint32_t bm_h = UINT32_MAX, bm_v = UINT32_MAX;   /* the bent normals' memo: no pair of codes yet */
    tg_vec3 bm_out = tg_v3(0, 0, 0);
#endif
    tgi_normal_memo nm, pm;   /* the normal decoded last (raster/gview.h), and last frame's (history_at) */
    tgi_normal_memo_start(&nm);
    tgi_normal_memo_start(&pm);
    for (y = y0; y < y1; y++) {
        int fy = y * g->step + g->offset_y;
        for (x = 0; x < g->width; x++) {
            size_t i = tgi_gv_index(g, x, y), s;
            if (tgi_gv_is_sky(g, i)) continue;
            const tg_vec3 n = tgi_gv_normal_memo(g, &nm, i);
            if (!history_at(p, g, &t->h, &t->cams, t->unit, x * g->step + g->offset_x, fy, tgi_gv_depth(g, i), n, &s,
                            &pm))
                continue;
            /* exponential average of the channels r has (tgi_gr_get and
             * tgi_gr_put channel by channel, whether each plane is present
             * tested once before the rows: prev's absent ones read as ao 1,
             * bent and near 0); the bent normal only where r has one
             * (without it no renormalisation of a zero vector, cornell
             * 320x240 3 frames float 13M instructions) */
            if (r_ao) tgi_gr_set_ao(r, i, lerp_unit(p_ao ? tgi_gr_ao(prev, s) : TG_ONE, tgi_gr_ao(r, i), alpha));
            if (has_bent) {
#if TGI_REUSE_NORMAL
                /* the pair of stored codes met last (0x10000: prev has no
                 * bent normal, its zero vector) gives the bent normal made
                 * last: lerp_unit3 and tgi_v3_unit_or are functions of their
                 * inputs, and n, the one thing more, is unit_or's only for
                 * a zero vector, which the memo never takes (a component
                 * at least 1/4 in size) */
                const uint32_t hc = p_bent ? tgi_gr_bent_word(prev, s) : 0x10000u, vc = tgi_gr_bent_word(r, i);
                if (hc == bm_h && vc == bm_v) {
                    tgi_gr_set_bent(r, i, bm_out);
                } else
#endif
                {
                    const tg_vec3 hb = p_bent ? tgi_gr_bent(prev, s) : tg_v3(0, 0, 0);
                    const tg_vec3 l = lerp_unit3(hb, tgi_gr_bent(r, i), alpha), b = tgi_v3_unit_or(l, n);
#if TGI_REUSE_NORMAL
                    if (tgi_abs_fast(l.x) >= TG_R(0.25f) || tgi_abs_fast(l.y) >= TG_R(0.25f) ||
                        tgi_abs_fast(l.z) >= TG_R(0.25f)) {
                        bm_h = hc;
                        bm_v = vc;
                        bm_out = b;
                    }
#endif
                    tgi_gr_set_bent(r, i, b);
                }
            }
            if (r_near)
                tgi_gr_set_near(r, i, lerp_unit3(p_near ? tgi_gr_near(prev, s) : tg_v3(0, 0, 0), tgi_gr_near(r, i), alpha));
        }
    }
}

void tgi_temporal_rows(const tgi_temporal_params *params, const tgi_gview *view_in, const tgi_gresult *r_in,
                       const tgi_gresult *prev_in, const tgi_prev_geometry *prev_geometry, const tgi_view *prev_view,
                       int reset, int y0, int y1)
{
    temporal_rows_in t;
    tgi_view view, before;
    if (reset || !prev_view) return;
    t.p = *params; t.g = *view_in; t.r = *r_in; t.prev = *prev_in; t.h = *prev_geometry;
    t.p_bent = tgi_gr_has_bent(&t.prev);
    t.r_ao = t.r.ao != NULL;
    t.p_ao = t.prev.ao != NULL;
    t.r_near = tgi_gr_has_near(&t.r);
    t.p_near = tgi_gr_has_near(&t.prev);
    if (y0 < 0) y0 = 0;
    if (y1 > t.g.height) y1 = t.g.height;
    view = *t.g.camera;
    before = *prev_view;
    tgi_reproject_cams_start(&t.cams, &view, &before, view.width, view.height);
    t.unit = t.g.step == 1 && t.g.offset_x == 0 && t.g.offset_y == 0 && t.g.width == view.width &&
             t.g.height == view.height && t.g.pixel_stride == 1 && t.g.row_stride == view.width;
#if !TG_OUTLINE_HELPERS
    if (!tgi_gr_has_bent(&t.r)) {   /* a copy of the loop without the bent normal (not when compiling for size) */
        accumulate_rows(&t, 0, y0, y1);
        return;
    }
#endif
    accumulate_rows(&t, tgi_gr_has_bent(&t.r), y0, y1);
}
