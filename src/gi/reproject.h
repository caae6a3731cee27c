/* SPDX-License-Identifier: MIT */
/*
 * reproject.h - last frame's diffuse radiance in this frame's view (HBIL
 * sec. 3.2), the source of the near field (eq. 17: infinite bounces over
 * frames).
 *
 * A gather through the depth and the two cameras: each pixel of this frame
 * is unprojected with its depth, moved by its object's motion when objects
 * move, and projected into last frame's view; it takes last frame's
 * radiance at the pixel it lands in, unless last frame's depth there
 * disagrees with this surface seen from the previous camera (relative
 * tolerance, the paper's z-test) or it lands off screen or behind the
 * camera: then it is a hole (tgi_rgb_set_hole), for tgi_pushpull_fill.  The
 * paper scatters through a temporary z-buffer; gathering needs no scratch
 * and no ordering, so rows are independent (any split gives the same
 * image).  Sky pixels are holes too (the near field never gathers them).
 * Without history (prev absent: a camera cut) every pixel is a hole, and
 * push/pull makes the image 0.
 */
#ifndef TG_REPROJECT_H
#define TG_REPROJECT_H

#include "../raster/gview.h"

typedef struct tgi_reproject_io {
    const tgi_gview *g;                  /* this frame (full resolution, packed); its camera */
    const tgi_view *prev_view;
    const tgi_prev_geometry *prev_geometry; /* last frame's depth, packed like g */
    const tgi_rgb *prev;                 /* last frame's radiance, packed like g; absent: no history */
    const uint16_t *object;              /* this frame's object ids when objects move, else NULL */
    const tgi_mat4 *object_delta;        /* per object: current pose -> previous pose */
    tg_real depth_tolerance;             /* relative depth mismatch rejected (0: 0.05) */
    const tgi_rgb *out;                  /* this frame's radiance: a value or a hole */
} tgi_reproject_io;

/* ---- where a pixel's surface was: the per-pixel step of the gather here
 * and of temporal accumulation (temporal.c) ---- */
#include "../raster/motion.h"

/* The cameras (the caller's copies, as for tgi_motion_pair_start) and the
 * previous image's pixels accepted, [0, w) x [0, h). */
typedef struct tgi_reproject_cams {
    tgi_motion_pair pair;
    int w, h;
#if !TG_FIXED
    tg_real cur_cx, cur_cy, prev_cx, prev_cy;   /* the views' centres (tgi_view_unproject_inline's, project's) */
    tg_real wr, hr;                             /* w and h */
#else
    int64_t v_lim;   /* the pair's v_max, at most TG_REAL_MAX; -1: every pixel through the pair */
    int64_t d_lim;   /* a depth up to this has V <= v_lim at every pixel (below); -1: none */
    int64_t ex, ey, ez;   /* the current eye less the previous one */
#endif
} tgi_reproject_cams;

static inline void tgi_reproject_cams_start(tgi_reproject_cams *c, const tgi_view *cur, const tgi_view *prev, int w,
                                            int h)
{
    tgi_motion_pair_start(&c->pair, cur, prev);
    c->w = w;
    c->h = h;
#if !TG_FIXED
    c->cur_cx = tg_ldexp(tg_from_int(cur->width), -1);
    c->cur_cy = tg_ldexp(tg_from_int(cur->height), -1);
    c->prev_cx = tg_ldexp(tg_from_int(prev->width), -1);
    c->prev_cy = tg_ldexp(tg_from_int(prev->height), -1);
    c->wr = tg_from_int(w);
    c->hr = tg_from_int(h);
#else
    c->v_lim = c->pair.v_max < TG_REAL_MAX ? c->pair.v_max : TG_REAL_MAX;
    /* below: the sides within 2^13, so the centres (w 2^15) and the range
     * (w 2^16) are exact Q16.16 integers below TG_REAL_MAX */
    if (w < 0 || w > 8192 || h < 0 || h > 8192 || prev->width < 0 || prev->width > 8192 || prev->height < 0 ||
        prev->height > 8192 || prev->pixels_per_unit <= 0)
        c->v_lim = -1;
    /* V <= v_lim without summing it: with W x H the current view's sides
     * (tgi_reproject_prev_pixel's pixels lie within them), |vx| <=
     * |2x + 1 - W| 2^15 depth / ppu + 1/2 (the rounding) < W 2^15 depth /
     * ppu + 1, |vy| alike with H, so V < depth k + 2 for k =
     * floor((W + H) 2^15 / ppu) + 2 (more than (W + H) 2^15 / ppu + 1):
     * depth <= (v_lim - 2) / k is enough (ppu > 0 wherever v_lim >= 0) */
    c->d_lim = -1;
    if (c->v_lim >= 2) c->d_lim = (c->v_lim - 2) / ((((int64_t)cur->width + cur->height) << 15) / cur->pixels_per_unit + 2);
    c->ex = (int64_t)cur->eye.x - prev->eye.x;
    c->ey = (int64_t)cur->eye.y - prev->eye.y;
    c->ez = (int64_t)cur->eye.z - prev->eye.z;
#endif
}

/* The pixel (*px, *py) of the previous image where the surface at the
 * centre of pixel (x, y) of the current view, at view depth `depth`, moved
 * by delta (NULL: it does not move), was (*prev_z its previous view depth):
 * 1 when it lies within [0, w) x [0, h), 0 when not or when it was behind
 * the previous camera.  That is tgi_motion_prev_position_pair's position,
 * then tg_to_int and the range test: the same answers and pixels, in fewer
 * steps:
 *  - float: its operations in its order without its test that the
 *    position is finite, which the range test makes (NaN and the
 *    infinities fail it); within the range tg_to_int is floor (no NaN, no
 *    saturation; 0 <= m < w <= TG_MAX_IMAGE_SIDE, an integer exact in
 *    float, floor(m) >= 0 where m >= 0 and floor(m) < w where m < w) and
 *    floor is the truncation (int32_t)m for m >= 0;
 *  - Q16.16, without delta, for a pixel of the current view and V =
 *    |vx| + |vy| + depth <= v_lim (known from depth <= d_lim, else summed): the
 *    pair's sums (motion.h) with its roundings but none of the saturations
 *    (tgi_view_mul_div's, tg_add's, tg_sub's): v_lim <= TG_REAL_MAX, so
 *    vx and vy were in range and saturated to themselves, and the pair's
 *    test passes as here.  The projection's quotient q is left 64-bit, the
 *    position S = c + q (c the centre) too: with L = w 2^16 <= 2^29 the
 *    pair accepts where 0 <= sat(c + sat(q)) < L, which, sat being
 *    monotonic and the identity on [-MAX, MAX] (containing [0, L)), holds
 *    exactly where 0 <= S < L: for |q| <= MAX sat(q) = q; for q > MAX
 *    the pair's c + MAX and S both lie above L, for q < -MAX c - MAX and S
 *    both below 0 (0 <= c <= 2^28; y alike with c - q).  Its z above
 *    0.0001 (a raw 7) is the projection's max(z, 2^-16).  Other
 *    pixels go through the pair. */
#if defined(__GNUC__)
__attribute__((always_inline))   /* one copy in each row loop */
#endif
static inline int tgi_reproject_prev_pixel(const tgi_reproject_cams *c, const tgi_mat4 *delta, int x, int y,
                                           tg_real depth, int *px, int *py, tg_real *prev_z)
{
    tg_real mx, my;
#if TG_FIXED
    const tgi_view *cv = c->pair.cur, *pv = c->pair.prev;
    /* the pixel within the current view (W, H <= 8192 where v_lim >= 0) */
    if (!delta && (unsigned)x < (unsigned)cv->width && (unsigned)y < (unsigned)cv->height && depth >= 0) {
        const int64_t ppu = cv->pixels_per_unit, hu = ppu / 2;
        const int64_t ax = (int64_t)((2 * x + 1 - cv->width) * 32768) * depth;
        const int64_t ay = (int64_t)((cv->height - 2 * y - 1) * 32768) * depth;
        const int64_t vx = ax >= 0 ? (ax + hu) / ppu : -((-ax + hu) / ppu);   /* tgi_view_mul_div's rounding */
        const int64_t vy = ay >= 0 ? (ay + hu) / ppu : -((-ay + hu) / ppu);
        if (depth <= c->d_lim || (vx < 0 ? -vx : vx) + (vy < 0 ? -vy : vy) + depth <= c->v_lim) {
            const int64_t rx = (int64_t)cv->right.x * vx + (int64_t)cv->up.x * vy + (int64_t)cv->forward.x * depth;
            const int64_t ry = (int64_t)cv->right.y * vx + (int64_t)cv->up.y * vy + (int64_t)cv->forward.y * depth;
            const int64_t rz = (int64_t)cv->right.z * vx + (int64_t)cv->up.z * vy + (int64_t)cv->forward.z * depth;
            const int64_t dx = c->ex + tgi_shr_round(rx, 16);   /* world - prev eye */
            const int64_t dy = c->ey + tgi_shr_round(ry, 16);
            const int64_t dz = c->ez + tgi_shr_round(rz, 16);
            const int64_t qx = (int64_t)(tg_real)tgi_shr_round(dx * pv->right.x + dy * pv->right.y + dz * pv->right.z, 16);
            const int64_t qy = (int64_t)(tg_real)tgi_shr_round(dx * pv->up.x + dy * pv->up.y + dz * pv->up.z, 16);
            const tg_real z = (tg_real)tgi_shr_round(dx * pv->forward.x + dy * pv->forward.y + dz * pv->forward.z, 16);
            int64_t nx, ny, sx, sy;
            *prev_z = z;
            if (z <= TG_R(0.0001f)) return 0;
            nx = qx * pv->pixels_per_unit;
            ny = qy * pv->pixels_per_unit;
            sx = ((int64_t)pv->width << 15) + (nx >= 0 ? (nx + z / 2) / z : -((-nx + z / 2) / z));
            sy = ((int64_t)pv->height << 15) - (ny >= 0 ? (ny + z / 2) / z : -((-ny + z / 2) / z));
            if ((uint64_t)sx >= (uint64_t)c->w << 16 || (uint64_t)sy >= (uint64_t)c->h << 16) return 0;
            *px = (int)(sx >> 16);
            *py = (int)(sy >> 16);
            return 1;
        }
    }
    if (!tgi_motion_prev_position_pair(&c->pair, delta, x, y, depth, &mx, &my, prev_z)) return 0;
    *px = tg_to_int(mx);
    *py = tg_to_int(my);
    /* px < 0 || px >= w as one unsigned compare (w >= 0) */
    return (uint32_t)*px < (uint32_t)c->w && (uint32_t)*py < (uint32_t)c->h;
#else
    const tgi_view *cv = c->pair.cur, *pv = c->pair.prev;
    const tg_real sx = tg_add(tg_from_int(x), TG_R(0.5f)), sy = tg_add(tg_from_int(y), TG_R(0.5f));
    /* tgi_view_unproject_inline with the centres computed once */
    const tg_vec3 u = tg_v3(tgi_view_mul_div(tg_sub(sx, c->cur_cx), depth, cv->pixels_per_unit),
                            tgi_view_mul_div(tg_sub(c->cur_cy, sy), depth, cv->pixels_per_unit), depth);
    tg_vec3 p = tgi_view_view_to_world_inline(cv, u), v;
    if (delta) p = tgi_m4_point(delta, p);
    v = tgi_view_world_to_view_inline(pv, p);
    *prev_z = v.z;
    if (v.z <= TG_R(0.0001f)) return 0;
    {
        /* tgi_view_project_inline without tgi_view_mul_div's clamp to
         * [-MAX, MAX], which acts only on the infinities: c + inf and
         * c - inf fail the range test as c +- MAX do (c the centre, within
         * [0, 4096]), and NaN passes the clamp as it is */
        const tg_real z = tg_max(v.z, TGI_VIEW_MIN_DEPTH);
        mx = c->prev_cx + v.x * pv->pixels_per_unit / z;
        my = c->prev_cy - v.y * pv->pixels_per_unit / z;
    }
    if (!(mx >= 0 && mx < c->wr && my >= 0 && my < c->hr)) return 0;
    *px = (int32_t)mx;
    *py = (int32_t)my;
    return 1;
#endif
}

void tgi_reproject_gather_rows(const tgi_reproject_io *io, int y0, int y1);

#endif
