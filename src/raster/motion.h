/* SPDX-License-Identifier: MIT */
/*
 * motion.h - per-pixel motion vectors for reprojection.
 *
 * motion_x/y (gbuffer.h) = the continuous screen position in the PREVIOUS
 * frame of the surface seen at this pixel's centre now: the pixel is
 * unprojected with the current view (view.h), moved by its object's rigid
 * delta (scene/anim.h makes those from the keys) and projected with the
 * previous view.
 */
#ifndef TG_MOTION_H
#define TG_MOTION_H

#include "gbuffer.h"
#include "view.h"

/* Screen position written for a surface that was behind the previous camera. */
#define TG_MOTION_INVALID TG_REAL_MIN

/* Motion vectors for rows [y0, y1) into gb->motion_x/y.  cur_to_prev: one
 * world-space rigid delta per object (indexed by gb->object), or NULL when
 * nothing but the camera moves.  Sky pixels reproject their view direction
 * (a point at infinity).  A surface behind the previous camera gets
 * TG_MOTION_INVALID in both. */
/* Where the surface at the centre of pixel (x, y) of `cur`, at view depth
 * `depth`, was on the screen of `prev` (*px, *py, continuous pixels; its
 * previous view depth *prev_z), moved by its object's delta (NULL: it does
 * not move).  0 when it was behind the previous camera. */
int tgi_motion_prev_position(const tgi_view *cur, const tgi_view *prev, const tgi_mat4 *delta,
                             int x, int y, tg_real depth, tg_real *px, tg_real *py, tg_real *prev_z);

/* The same inline, for the per-pixel loops of reprojection and temporal
 * accumulation (src/gi/reproject.c, src/gi/temporal.c): the same bits. */
static inline int tgi_motion_prev_position_inline(const tgi_view *cur, const tgi_view *prev, const tgi_mat4 *delta,
                                                  int x, int y, tg_real depth, tg_real *px, tg_real *py,
                                                  tg_real *prev_z)
{
    tg_real sx = tg_add(tg_from_int(x), TG_R(0.5f)), sy = tg_add(tg_from_int(y), TG_R(0.5f));
    tg_vec3 p = tgi_view_view_to_world_inline(cur, tgi_view_unproject_inline(cur, sx, sy, depth)), pv;
    if (delta) p = tgi_m4_point(delta, p);
    pv = tgi_view_world_to_view_inline(prev, p);
    *prev_z = pv.z;
    if (pv.z <= TG_R(0.0001f)) return 0;
#if !TG_FIXED
    /* a world near float's range (coordinates of 1e38): eye + ray overflows
     * to inf and inf - inf is NaN, or the projection overflows: no previous
     * position (the motion AOV was NaN there; test_hardcases.c
     * world_near_float_range).  v - v is 0 for every finite v, NaN for the
     * infinities and NaN: one subtraction and compare a coordinate. */
    tgi_view_project_inline(prev, pv, px, py);
    return *px - *px == 0.0f && *py - *py == 0.0f;
#else
    tgi_view_project_inline(prev, pv, px, py);
    return 1;
#endif
}

/* A camera pair for tgi_motion_prev_position_pair: in Q16.16 with the
 * bound that lets the map from the current view to the previous one skip
 * its saturation tests (tgi_motion_pair_start).  cur and prev are the
 * caller's (its locals, in src/gi/temporal.c and reproject.c). */
typedef struct tgi_motion_pair {
    const tgi_view *cur, *prev;
#if TG_FIXED
    int64_t v_max;   /* |v.x| + |v.y| + |v.z| of the unprojected point at most this: no step saturates; -1: none */
#endif
} tgi_motion_pair;

/* Q16.16: the unprojected point v = (vx, vy, depth) of the current view
 * goes to the world r + eye (r_i = sum_j b_ij v_j, b the camera's axes),
 * then d = that - prev eye and pv_i = sum_j b'_ij d_j (tgi_v3_dot: one
 * rounding each, then the saturation).  With B the largest |axis
 * component| of both cameras (1, 2^16, for unit axes), E their eyes'
 * largest components summed and V = |v.x| + |v.y| + |v.z|: |r_i| <= B V
 * 2^-16 + 1, |world_i|, |d_i| <= D = E + B V 2^-16 + 1, |pv_i| <= 3 B D
 * 2^-16 + 1, all in Q16.16 integers.  v_max keeps D <= D_max = (MAX - 1)
 * 2^16 / (3 B) and D_max <= TG_REAL_MAX, so for V <= v_max no step leaves
 * the range and the 64-bit sums below are tg_add's and tgi_v3_dot's. */
static inline void tgi_motion_pair_start(tgi_motion_pair *m, const tgi_view *cur, const tgi_view *prev)
{
#if TG_FIXED
    const tg_real ax[18] = { cur->right.x, cur->right.y, cur->right.z, cur->up.x, cur->up.y, cur->up.z,
                             cur->forward.x, cur->forward.y, cur->forward.z, prev->right.x, prev->right.y,
                             prev->right.z, prev->up.x, prev->up.y, prev->up.z, prev->forward.x, prev->forward.y,
                             prev->forward.z };
    int64_t b = 1, e1 = 0, e2 = 0, d_max;
    int k;
    for (k = 0; k < 18; k++) b = tg_abs(ax[k]) > b ? tg_abs(ax[k]) : b;
    e1 = tg_max(tg_max(tg_abs(cur->eye.x), tg_abs(cur->eye.y)), tg_abs(cur->eye.z));
    e2 = tg_max(tg_max(tg_abs(prev->eye.x), tg_abs(prev->eye.y)), tg_abs(prev->eye.z));
    d_max = (((int64_t)TG_REAL_MAX - 1) << 16) / (3 * b);
    if (d_max > TG_REAL_MAX) d_max = TG_REAL_MAX;
    m->v_max = d_max - e1 - e2 - 1 < 0 ? -1 : ((d_max - e1 - e2 - 1) << 16) / b;
    /* the pixel's offset from the centre is exact for images up to 2^13 a side */
    if (cur->width < 1 || cur->width > 8192 || cur->height < 1 || cur->height > 8192 || cur->pixels_per_unit <= 0)
        m->v_max = -1;
#endif
    m->cur = cur;
    m->prev = prev;
}

/* tgi_motion_prev_position_inline of the pair's cameras: the same bits.
 * Q16.16 without a delta, for pixels within 2^13 of the origin and V <=
 * v_max: tgi_motion_pair_start's sums without saturation tests (the centre
 * offset (2x + 1 - width) / 2 is sx - cx exactly, as is its y). */
static inline int tgi_motion_prev_position_pair(const tgi_motion_pair *m, const tgi_mat4 *delta, int x, int y,
                                                tg_real depth, tg_real *px, tg_real *py, tg_real *prev_z)
{
#if TG_FIXED
    if (!delta && (unsigned)x < 8192u && (unsigned)y < 8192u && depth >= 0) {
        const tgi_view *c = m->cur, *p = m->prev;
        const tg_real vx = tgi_view_mul_div((tg_real)((2 * x + 1 - c->width) * 32768), depth, c->pixels_per_unit);
        const tg_real vy = tgi_view_mul_div((tg_real)((c->height - 2 * y - 1) * 32768), depth, c->pixels_per_unit);
        if ((int64_t)tg_abs(vx) + tg_abs(vy) + depth <= m->v_max) {
            const int64_t rx = (int64_t)c->right.x * vx + (int64_t)c->up.x * vy + (int64_t)c->forward.x * depth;
            const int64_t ry = (int64_t)c->right.y * vx + (int64_t)c->up.y * vy + (int64_t)c->forward.y * depth;
            const int64_t rz = (int64_t)c->right.z * vx + (int64_t)c->up.z * vy + (int64_t)c->forward.z * depth;
            const int64_t dx = c->eye.x - (int64_t)p->eye.x + tgi_shr_round(rx, 16);   /* world - prev eye */
            const int64_t dy = c->eye.y - (int64_t)p->eye.y + tgi_shr_round(ry, 16);
            const int64_t dz = c->eye.z - (int64_t)p->eye.z + tgi_shr_round(rz, 16);
            tg_vec3 pv;
            pv.x = (tg_real)tgi_shr_round(dx * p->right.x + dy * p->right.y + dz * p->right.z, 16);
            pv.y = (tg_real)tgi_shr_round(dx * p->up.x + dy * p->up.y + dz * p->up.z, 16);
            pv.z = (tg_real)tgi_shr_round(dx * p->forward.x + dy * p->forward.y + dz * p->forward.z, 16);
            *prev_z = pv.z;
            if (pv.z <= TG_R(0.0001f)) return 0;
            tgi_view_project_inline(p, pv, px, py);
            return 1;
        }
    }
#endif
    return tgi_motion_prev_position_inline(m->cur, m->prev, delta, x, y, depth, px, py, prev_z);
}

void tgi_motion_rows(tgi_gbuffer *gb, const tgi_view *cur, const tgi_view *prev,
                    const tgi_mat4 *cur_to_prev, int y0, int y1);

#endif
