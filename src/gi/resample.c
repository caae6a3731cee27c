/* SPDX-License-Identifier: MIT */
/*
 * resample.c - quarter resolution for the GI kernel.
 *
 * The horizon kernel runs on a quarter of the pixels (half width, half
 * height): the G-buffer is point-sampled down (half-res pixel (X, Y) is
 * full-res pixel (2X, 2Y), so depth and normals stay those of a real
 * surface, never an average across an edge), the 4x4 interleaved kernel runs
 * there, and its results come back up by a joint bilateral upsample: the
 * bilinear weights of the (up to) 2x2 half-res neighbours, each times a depth
 * weight 1 - |z_j - z| / (0.1 z) and a normal weight (n . n_j)^4, floored
 * at 1/64 so a pixel always gets a value.  The bent normal is carried as its
 * bend, bent - normal, added to this pixel's own normal and kept in its
 * hemisphere.  Sky pixels get AO 1, the normal
 * as bent normal (0 on sky) and no near field.
 *
 * The near horizon: the half-res kernel's samples lie 8 full-res pixels
 * apart (4x4 sub-images of the half-res image), so an occluder a few
 * pixels wide (a sphere's or a column's foot, a room's corner) gets one or
 * two samples a side and its horizon is missed: the upsampled AO is too
 * bright there.  Each full-res pixel also marches its own two slices a few
 * pixels (TG_QUARTER_NEAR_REACH) and the AO under those near horizons,
 * an upper bound of the true AO as the upsampled one is, caps it: AO =
 * min(upsampled, near).  The bent normal and the near field stay the
 * upsampled ones.  Over further depth layers (the kernel the visibility
 * bitmask, which leaves open what lies behind a closed object's back
 * face) a horizon is such a bound only where what it takes as solid is:
 * the near horizon takes a sample only where it is solid down to the
 * tangent plane (near_solid_below), else it would close the floor under
 * a sphere that the layers see open (spheres 160x120, --gi-quarter over
 * three layers: RMSE 0.112 with every sample, 0.043 so, 0.045 without
 * the near horizon).
 */
#include "resample.h"
#include "../ao/ao.h"

void tgi_half_size(int w, int h, int *hw, int *hh)
{
    *hw = (w + 1) / 2;
    *hh = (h + 1) / 2;
}

void tgi_downsample_rows(const tgi_gview *full, const tgi_gbuffer *half, const tgi_rgb *src,
                         const tgi_rgb *half_src, int y0, int y1)
{
    int hw, hh, x, y, with_src = tgi_rgb_present(src) && tgi_rgb_present(half_src);
    tgi_half_size(full->width, full->height, &hw, &hh);
    if (y1 > hh) y1 = hh;
    for (y = y0; y < y1; y++)
        for (x = 0; x < hw; x++) {
            size_t i = tgi_gv_index(full, 2 * x, 2 * y), j = (size_t)y * (size_t)hw + (size_t)x;
            tgi_gview_copy_pixel(half, j, full, i);
            if (with_src) tgi_rgb_set(half_src, j, tgi_rgb_get(src, i));
        }
}

/* (n . m)^4 for unit normals, 0 when they face apart.  The packed
 * G-buffer's normals (tgi_gv_normal: tgi_oct_unit, raster/pack.h, each
 * component |c| / |.| times a reciprocal square root within 3.2e-6) have
 * components within 1 + 2^-16: each product, the dot (within 4), its
 * square and its square's square (within 256) stay far below the range, so
 * tgi_wide (core/real.h) gives tg_mul's and tg_add's results without their
 * saturation tests; with TG_WIDE_STORAGE (normals as stored) Q16.16 keeps
 * the saturating form. */
static tg_real upsample_normal_weight(tg_vec3 n, tg_vec3 m)
{
#if TG_FIXED && TG_WIDE_STORAGE
    tg_real d = tg_add(tg_add(tg_mul(n.x, m.x), tg_mul(n.y, m.y)), tg_mul(n.z, m.z));
    if (d <= 0) return 0;
    d = tg_mul(d, d);
    return tg_mul(d, d);
#else
    tgi_wide d = tgi_wide_mul(n.x, m.x) + tgi_wide_mul(n.y, m.y) + tgi_wide_mul(n.z, m.z);
    if (d <= 0) return 0;
    d = tgi_wide_mul(d, d);
    return (tg_real)tgi_wide_mul(d, d);
#endif
}

/* 1 - |z_j - z| / (0.1 z), clamped to [0, 1]: |0.1 z| < |z| (tg_mul's
 * product, never saturating), the quotient of 0 <= |z_j - z| < 0.1 z
 * within [0, 1) (tgi_div_pos). */
static tg_real upsample_depth_tol(tg_real z) { return (tg_real)tgi_wide_mul(z, TG_R(0.1f)); }
static tg_real upsample_depth_weight(tg_real z, tg_real zj)
{
    tg_real tol = upsample_depth_tol(z);
    /* depths are never negative (tgi_gv_depth): their difference never
     * saturates, tg_sub's test left out (Q16.16 160x120 2 frames
     * --gi-quarter: cornell 315.60M -> 315.14M, columns 224.63M ->
     * 224.25M; float's the same subtraction) */
    tg_real dz = tg_abs(zj - z);
    if (tol <= 0 || dz >= tol) return 0;
    return (tg_real)((tgi_wide)TG_ONE - tgi_div_pos(dz, tol));
}

/* Sky, or only sky around: open (AO 1, the normal as bent normal, no near field). */
static tgi_gr_value upsample_open(const tgi_gview *full, size_t i)
{
    tgi_gr_value v;
    v.ao = TG_ONE;
    v.bent = tgi_gv_is_sky(full, i) ? tg_v3(0, 0, 0) : tgi_gv_normal(full, i);
    v.near = tg_v3(0, 0, 0);
    return v;
}

/* The (up to) 2x2 half-res neighbours of full-res (x, y) of bilinear
 * weight above 0 (an even coordinate sits on a half-res sample, an odd one
 * halfway): (X0, Y0) always, (X1, Y0) where x is odd, (X0, Y1) where y
 * is, (X1, Y1) where both are, in this order; each of the same weight, 1
 * or 1/2 times 1 or 1/2 (exact, tgi_wide), returned; their count in *n.
 * slot[k]: the parity of tap k's coordinates (before the clamp at the
 * edge), a slot of the walk (tgi_upsample_at). */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
__attribute__((always_inline))   /* into its two callers: out of line it cost Q16.16's --gi-quarter 0.7% */
#endif
static inline tg_real bilinear_taps(const tgi_gview *half, int x, int y, size_t tap[4], int slot[4], int *n)
{
    int X0 = x >> 1, Y0 = y >> 1, X1 = X0 + (x & 1), Y1 = Y0 + (y & 1), k = 1;
    int s0 = (X0 & 1) + ((Y0 & 1) << 1), sx = (x & 1), sy = (y & 1) << 1;   /* the parities of X1, Y1 flip X0's, Y0's */
    tg_real h = TG_R(0.5f);
    if (X1 >= half->width) X1 = half->width - 1;
    if (Y1 >= half->height) Y1 = half->height - 1;
    tap[0] = tgi_gv_index(half, X0, Y0); slot[0] = s0;
    if (x & 1) { tap[k] = tgi_gv_index(half, X1, Y0); slot[k++] = s0 ^ sx; }
    if (y & 1) { tap[k] = tgi_gv_index(half, X0, Y1); slot[k++] = s0 ^ sy; }
    if (x & y & 1) { tap[k] = tgi_gv_index(half, X1, Y1); slot[k++] = s0 ^ sx ^ sy; }
    *n = k;
    return (tg_real)tgi_wide_mul((x & 1) ? h : TG_ONE, (y & 1) ? h : TG_ONE);
}

/* The near horizon's slice directions: cell (x & 3, y & 3) of a 4x4 block
 * takes the screen direction (cos a, sin a), a = (b + 1/2) pi / 32 with b
 * the cell's rank in the 4x4 Bayer order (src/ao/sampling.c), and the one
 * at right angles to it: a block's 16 cells x 2 slices cover [0, pi) every
 * pi / 32, neighbours far apart. */
static const tg_real near_dir[16][2] = {
    { TG_R(0.9987955f), TG_R(0.0490677f) }, { TG_R(0.6715590f), TG_R(0.7409511f) },
    { TG_R(0.9700313f), TG_R(0.2429802f) }, { TG_R(0.5141027f), TG_R(0.8577286f) },
    { TG_R(0.3368899f), TG_R(0.9415441f) }, { TG_R(0.9039893f), TG_R(0.4275551f) },
    { TG_R(0.1467305f), TG_R(0.9891765f) }, { TG_R(0.8032075f), TG_R(0.5956993f) },
    { TG_R(0.9415441f), TG_R(0.3368899f) }, { TG_R(0.4275551f), TG_R(0.9039893f) },
    { TG_R(0.9891765f), TG_R(0.1467305f) }, { TG_R(0.5956993f), TG_R(0.8032075f) },
    { TG_R(0.0490677f), TG_R(0.9987955f) }, { TG_R(0.7409511f), TG_R(0.6715590f) },
    { TG_R(0.2429802f), TG_R(0.9700313f) }, { TG_R(0.8577286f), TG_R(0.5141027f) }
};

/* The near horizon's sample distances along a side, in pixels (resample.h's
 * TGI_NEAR_STEPS of them). */
static const int near_t[16] = { 1, 2, 3, 4, 6, 9, 13, 19, 28, 42, 63, 94, 141, 211, 316, 474 };

/* NEAR_OFF_CONST: the march offsets of tgi_upsample_start's off[][][][]
 * as constants.  Offset n of side e of a cell's slice k is
 * floor((128 + t s) / 256) for t = near_t[n] on either axis of the
 * rounded direction (ux, uy) = round(256 near_dir[c]) of slice 0, those
 * of slice 1 (-uy, ux) (round(-v) = -round(v)), side 1 the other way: the
 * pixel of the sample t pixels along it, stepping in 1/256 pixel from the
 * pixel's centre; integers alike in both number types (no 256
 * near_dir[c][k] lies within 0.001 of a half, so float's and Q16.16's
 * roundings agree: tgi_upsample_start's computation of them from
 * near_dir, before these, gave every one in both types for each
 * TG_QUARTER_NEAR_REACH from 1 to 18, and its farthest offset was the
 * last t).  NEAR_OI
 * keeps the shift to non-negative numbers (t s >= -256 t).  Up to 7 steps
 * (TG_QUARTER_NEAR_REACH <= 18); 896 bytes of constants, where
 * tgi_upsample_start computed them at each call (36K instructions a call,
 * once a row range of two passes); none in a build for size.
 *
 * NEAR_OFF_PAIRS (float, with the index offsets): the same offsets as
 * pairs of floats, which the march inside the image reads with one load an
 * offset (near_off_real's is a sign extension and a load) and multiplies
 * from memory (cornell 320x240 --gi-quarter 2 frames: float 1000.22M ->
 * 992.56M); 3584 bytes more (TG_QUARTER_NEAR_REACH <= 16, as
 * NEAR_OFF_TABLE). */
#define NEAR_OFF_CONST (!TG_OUTLINE_HELPERS && TG_QUARTER_NEAR_REACH >= 1 && TGI_NEAR_STEPS <= 7)
#define NEAR_OFF_PAIRS (!TG_FIXED && NEAR_OFF_CONST && TG_QUARTER_NEAR_REACH <= 16 && TGI_NEAR_DELTAS)
#if NEAR_OFF_CONST
#define NEAR_OI(s, t) ((((128 + (t) * (s) + 256 * ((t) + 1)) >> 8) - ((t) + 1)))
#define NEAR_OP(T, sx, sy, t) { (T)NEAR_OI(sx, t), (T)NEAR_OI(sy, t) }
#define NEAR_OS(T, sx, sy) \
    { NEAR_OP(T, sx, sy, 1), NEAR_OP(T, sx, sy, 2), NEAR_OP(T, sx, sy, 3), NEAR_OP(T, sx, sy, 4), \
      NEAR_OP(T, sx, sy, 6), NEAR_OP(T, sx, sy, 9), NEAR_OP(T, sx, sy, 13) }
#define NEAR_OC(T, ux, uy) { NEAR_OS(T, ux, uy), NEAR_OS(T, -(ux), -(uy)), NEAR_OS(T, -(uy), ux), NEAR_OS(T, uy, -(ux)) }
#define NEAR_CELLS(T) \
    NEAR_OC(T, 256, 13), NEAR_OC(T, 172, 190), NEAR_OC(T, 248, 62),  NEAR_OC(T, 132, 220), \
    NEAR_OC(T, 86, 241), NEAR_OC(T, 231, 109), NEAR_OC(T, 38, 253),  NEAR_OC(T, 206, 152), \
    NEAR_OC(T, 241, 86), NEAR_OC(T, 109, 231), NEAR_OC(T, 253, 38),  NEAR_OC(T, 152, 206), \
    NEAR_OC(T, 13, 256), NEAR_OC(T, 190, 172), NEAR_OC(T, 62, 248),  NEAR_OC(T, 220, 132)
static const signed char near_off_const[16][4][7][2] = { NEAR_CELLS(signed char) };
#if NEAR_OFF_PAIRS
static const float near_off_pairs[16][4][7][2] = { NEAR_CELLS(float) };
#endif
#undef NEAR_CELLS
#undef NEAR_OC
#undef NEAR_OS
#undef NEAR_OP
#undef NEAR_OI
#endif

/* tg_rsqrt(x) for 0 < x <= TG_REAL_MAX (each use says why): in Q16.16 not
 * compiling for size tgi_rsqrt_pos (core/real.h), tg_rsqrt's steps inline,
 * the same bits for every x > 0, without the call and the test of x <= 0
 * (Q16.16 160x120 2 frames --gi-quarter: cornell 318.04M -> 317.08M,
 * columns 226.26M -> 225.96M); else tg_rsqrt itself. */
#if TGI_Q16_WIDE
#define near_rsqrt tgi_rsqrt_pos
#else
#define near_rsqrt tg_rsqrt
#endif

#if TGI_NEAR_DELTAS || TGI_Q16_WIDE
static int64_t abs64(int64_t v) { return v < 0 ? -v : v; }
#endif

/* The offsets (dx, dy) and the index offset of sample n of cell c's side k
 * in the plan (TGI_NEAR_STEP_PAIRS: side by side, or apart). */
#if TGI_NEAR_STEP_PAIRS
#define NEAR_OFF(u, c, k, n) ((u)->step[c][k][n].off)
#define NEAR_DELTA(u, c, k, n) ((u)->step[c][k][n].delta)
#else
#define NEAR_OFF(u, c, k, n) ((u)->off[c][k][n])
#define NEAR_DELTA(u, c, k, n) ((u)->delta[c][k][n])
#endif

void tgi_upsample_start(tgi_upsample_plan *u, const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res,
                        tg_real radius, const tgi_gresult *near)
{
    const tgi_view *v = full->camera;
    int c, k, n, e;
    u->full = full; u->half = half; u->res = half_res; u->near = near;
    u->steps = 0;
#if TGI_DEPTH_LAYERS
    u->layers = full->store.back_depth != NULL;
#endif
    u->reach = 0;
#if TGI_NEAR_DELTAS
    u->deltas = 0;
#endif
    if (TG_QUARTER_NEAR_REACH < 1 || radius <= 0) return;
    u->steps = TGI_NEAR_STEPS;
    u->wfx = tg_mul(tg_from_int(v->width), v->focal_x);
    u->hfy = tg_mul(tg_from_int(v->height), v->focal_y);
    u->ax = tg_div(TG_R(2.0f), u->wfx);
    u->ay = tg_div(TG_R(2.0f), u->hfy);
    u->shift = tgi_ao_unit_shift(radius);
    u->r2 = tg_sqr(tg_ldexp(radius, u->shift));
    u->above_r = tg_mul(radius, TG_R(0.005f));
#if NEAR_OFF_CONST
    /* the constants; the farthest any lies on either axis: the last t (cell
     * 0's side 0, ux = 256, lies t away on x; |ux|, |uy| <= 256 keep every
     * offset within [-t, t], near_off_real's note) */
    u->reach = (short)near_t[TGI_NEAR_STEPS - 1];
    for (c = 0; c < 16; c++)
        for (k = 0; k < 4; k++)
            for (n = 0; n < TGI_NEAR_STEPS; n++) {
                NEAR_OFF(u, c, k, n)[0] = near_off_const[c][k][n][0];
                NEAR_OFF(u, c, k, n)[1] = near_off_const[c][k][n][1];
            }
    (void)e;
#else
    /* sample t of side e (k's direction, then against it) of a cell's slice k
     * along the screen direction (ux, uy) / 256 (y down), stepping in 1/256
     * pixel from the pixel's centre (integers alike in both number types):
     * the pixel floor((128 + t u) / 256) away, the shift kept to non-negative
     * numbers (NEAR_OFF_CONST's formula) */
    for (c = 0; c < 16; c++)
        for (k = 0; k < 2; k++) {
            const tg_real *d = near_dir[c];
            int ux = tg_round_int(tg_ldexp(k ? tg_neg(d[1]) : d[0], 8)), uy = tg_round_int(tg_ldexp(k ? d[0] : d[1], 8));
            for (e = 0; e < 2; e++)
                for (n = 0; n < u->steps; n++) {
                    signed char *o = NEAR_OFF(u, c, 2 * k + e, n);
                    int t = near_t[n], far = 256 * (t + 1), sx = e ? -ux : ux, sy = e ? -uy : uy;
                    int dx = ((128 + t * sx + far) >> 8) - (t + 1), dy = ((128 + t * sy + far) >> 8) - (t + 1);
                    o[0] = (signed char)dx;
                    o[1] = (signed char)dy;
                    if (dx > u->reach || -dx > u->reach) u->reach = dx > 0 ? dx : -dx;
                    if (dy > u->reach || -dy > u->reach) u->reach = dy > 0 ? dy : -dy;
                }
        }
#endif
#if TGI_Q16_WIDE
    /* Where near_horizon_cos may take a sample's offset from pixel q, h =
     * (z (kx + ox ax) - p.x, z (ky - oy ay) - p.y, z - p.z) scaled by
     * 2^shift, and its squared length in 64 bits without the saturation
     * tests: wherever each component lies within [-2^hk, 2^hk) before the
     * scale (tested there, else the generic code) and the pixel's |kx| <=
     * kx_room, |ky| <= ky_room, |p.x|, |p.y| <= p_room (near_horizon_ao),
     * each is the same integer as tg_mul's, tg_add's, tg_sub's and
     * tg_ldexp's.  With |kx| + reach |ax| <= TG_REAL_MAX,
     * tg_mul(tg_from_int(ox), ax) is ox ax exactly (|ox| <= reach: ox 2^16
     * ax rounded at 2^16) and its sum with kx does not saturate (y alike);
     * z times it (below 2^62) rounded is tg_mul's product where that does not
     * saturate, which |h.x| < 2^hk and |p.x| <= TG_REAL_MAX - 2^hk ensure
     * (its difference with p.x then fits too); z - p.z (both depths, within
     * [0, TG_REAL_MAX]) never saturates.  hk = 30 - max(shift, 0) keeps each
     * component times 2^shift within 2^30 (tg_ldexp unsaturated; a negative
     * shift is its rounding), so the squares sum below 2^62 (tgi_v3_dot
     * without its test; its rounding, then saturated: d2 >= r2 (r2 <=
     * TG_REAL_MAX) and d2 <= 0 as for the unsaturated sum).  A room below
     * 0 fails every pixel's test. */
    u->hk = 30 - (u->shift > 0 ? u->shift : 0);
    u->kx_room = (int64_t)TG_REAL_MAX - (int64_t)u->reach * abs64(u->ax);
    u->ky_room = (int64_t)TG_REAL_MAX - (int64_t)u->reach * abs64(u->ay);
    u->p_room = (int64_t)TG_REAL_MAX - ((int64_t)1 << u->hk);
    if (u->kx_room < 0 || u->ky_room < 0) u->hk = 0;
#endif
#if TGI_NEAR_DELTAS
    /* the index offsets, when every one fits 16 bits (|dx|, |dy| <= reach) */
    u->deltas = (int64_t)u->reach * (abs64(full->row_stride) + abs64(full->pixel_stride)) <= INT16_MAX;
    if (u->deltas) {
        const int rs = (int)full->row_stride, ps = (int)full->pixel_stride;   /* each within INT16_MAX (reach >= 1) */
        for (c = 0; c < 16; c++)
            for (k = 0; k < 4; k++)
                for (n = 0; n < TGI_NEAR_STEPS; n++)
                    NEAR_DELTA(u, c, k, n) = (int16_t)(NEAR_OFF(u, c, k, n)[1] * rs + NEAR_OFF(u, c, k, n)[0] * ps);
    }
#endif
}

/* A pixel's near horizon: its view position p, normal n and unit vector
 * to the eye, n . p, its view ray (kx, ky, 1), n . (kx, ky, 1), the change
 * of n . ray per pixel (n.x ax, n.y ay), and the height over the tangent
 * plane below which a sample counts for nothing (as tgi_ao_slice_pixel's). */
typedef struct near_plane {
    tg_real np, nax, nay, nr, above;
#if TG_FIXED
    int wide;             /* near_plane_start: the tangent-plane test in one 64-bit compare */
    int64_t lim;
#endif
} near_plane;
typedef struct near_pixel {
    int x, y, has_vd;
    size_t i;             /* tgi_gv_index(full, x, y) */
    tg_vec3 pv, nv, vd;
    tg_real kx, ky;
    near_plane pl;
#if TGI_Q16_WIDE
    int hk;               /* near_hk_set; -1: not yet */
#endif
} near_pixel;

/* The unit vector to the eye, normalised the first time a sample needs it
 * (most pixels have none above their tangent plane: near_horizon_ao).
 * tgi_v3_unit_or: tgi_v3_normalize_or's bits, in Q16.16 inline (core/unit.h;
 * flatten: gcc else made it a function of its own, the upsample's bent
 * normal then calling it too; Q16.16 160x120 2 frames --gi-quarter:
 * cornell 320.39M -> 318.04M, columns 226.96M -> 226.26M). */
#if defined(__GNUC__) && TGI_Q16_WIDE
__attribute__((noinline, flatten))   /* once a pixel: the march's registers stay its own on the other samples */
#elif defined(__GNUC__)
__attribute__((noinline))
#endif
static void near_vd_set(near_pixel *q)
{
#if TGI_Q16_WIDE
    q->vd = tgi_v3_unit_or(tgi_v3_neg(q->pv), tg_v3(0, 0, TG_R(-1.0f)));
#else   /* float, and a build for size: the call, one copy */
    q->vd = tgi_v3_normalize_or(tgi_v3_neg(q->pv), tg_v3(0, 0, TG_R(-1.0f)));
#endif
    q->has_vd = 1;
}
static inline tg_vec3 near_vd(near_pixel *q)
{
    if (!q->has_vd) near_vd_set(q);
    return q->vd;
}

#if TGI_Q16_WIDE
/* near_horizon_cos's offsets in 64 bits for pixel q: the plan's hk where q
 * passes its tests (tgi_upsample_start's note on hk), else 0. */
#if defined(__GNUC__)
__attribute__((noinline))   /* once a pixel, as near_vd_set */
#endif
static void near_hk_set(const tgi_upsample_plan *u, near_pixel *q)
{
    q->hk = (uint64_t)((int64_t)q->kx + u->kx_room) <= 2 * (uint64_t)u->kx_room
            && (uint64_t)((int64_t)q->ky + u->ky_room) <= 2 * (uint64_t)u->ky_room
            && (uint64_t)((int64_t)q->pv.x + u->p_room) <= 2 * (uint64_t)u->p_room
            && (uint64_t)((int64_t)q->pv.y + u->p_room) <= 2 * (uint64_t)u->p_room ? u->hk : 0;
}
#endif

#if TG_FIXED
/* The tangent-plane test of near_under_plane without its saturation tests,
 * for offsets up to `reach` pixels on either axis.  The saturating form is
 * D = sat(sat(P) - np) <= above with P = z i rounded (tg_mul) and i = nr +
 * (ox nax - oy nay).  When |nr| + reach (|nax| + |nay|) <= TG_REAL_MAX no
 * part of i saturates (wide): i is the exact sum, z i < 2^62 fits
 * 64 bits.  sat is monotone, so for above < TG_REAL_MAX, D <= above iff
 * sat(P) <= T = above + np (exact, 64 bits), which holds always when T >=
 * TG_REAL_MAX, never when T < TG_REAL_MIN (sat(P) >= TG_REAL_MIN), else iff
 * P <= T; and P = floor((z i + 2^15) / 2^16) (tgi_shr_round) is <= T iff
 * z i + 2^15 < (T + 1) 2^16, that is z i <= T 2^16 + 2^15 - 1.  above =
 * TG_REAL_MAX: every sample is under (D <= TG_REAL_MAX). */
static void near_plane_start(near_plane *pl, int reach)
{
    const int64_t t = (int64_t)pl->above + pl->np;
    pl->wide = (int64_t)tg_abs(pl->nr) + (int64_t)reach * ((int64_t)tg_abs(pl->nax) + tg_abs(pl->nay)) <= TG_REAL_MAX;
    if (pl->above >= TG_REAL_MAX || t >= TG_REAL_MAX) pl->lim = INT64_MAX;
    else if (t < TG_REAL_MIN) pl->lim = INT64_MIN;
    else pl->lim = t * 65536 + 32767;
}
#endif

/* Whether the sample at depth z, (ox, oy) pixels from pixel q, lies on or
 * under q's tangent plane, as high as q->above over it at most: its height
 * z (n . r) - n . p (near_horizon_cos).  Q16.16 with `wide` (a constant in
 * each copy of the march: pl->wide, NEAR_WIDE): near_plane_start's
 * compare, the same answer. */
static inline int near_under_plane_r(const near_plane *pl, tg_real z, tg_real fox, tg_real foy)
{
    return tg_sub(tg_mul(z, tg_add(pl->nr, tg_sub(tg_mul(fox, pl->nax), tg_mul(foy, pl->nay)))), pl->np) <= pl->above;
}
static inline int near_under_plane(const near_plane *pl, tg_real z, int ox, int oy, const int wide)
{
#if TG_FIXED
    if (wide) return (int64_t)z * ((int64_t)pl->nr + (int64_t)ox * pl->nax - (int64_t)oy * pl->nay) <= pl->lim;
#else
    (void)wide;
#endif
    return near_under_plane_r(pl, z, tg_from_int(ox), tg_from_int(oy));
}

/* A march offset o (tgi_upsample_start's off[][][][]) as a tg_real:
 * tg_from_int(o), in float read from a table (a load, not a sign
 * extension's conversion with its register clear), the same value: each
 * integer up to 16 is exactly a float.  |o| <= TG_QUARTER_NEAR_REACH: o =
 * floor((128 + t s) / 256) with |s| <= 256 is within [-t, t] (floor(t +
 * 1/2) = t, floor(1/2 - t) = -t), t = near_t[n] <= TG_QUARTER_NEAR_REACH
 * (TGI_NEAR_STEPS_OF). */
#define NEAR_OFF_TABLE (!TG_FIXED && !TG_OUTLINE_HELPERS && TG_QUARTER_NEAR_REACH <= 16)
#if NEAR_OFF_TABLE
static const float near_off_float[33] = { -16, -15, -14, -13, -12, -11, -10, -9, -8, -7, -6, -5, -4, -3, -2, -1, 0,
                                          1,   2,   3,   4,   5,   6,   7,   8,  9,  10, 11, 12, 13, 14, 15, 16 };
#endif
static inline tg_real near_off_real(int o)
{
#if NEAR_OFF_TABLE
    return (near_off_float + 16)[o];
#else
    return tg_from_int(o);
#endif
}
/* near_under_plane of a march offset off (near_off_real). */
static inline int near_under_off(const near_plane *pl, tg_real z, const signed char off[2], const int wide)
{
#if TG_FIXED
    if (wide) return near_under_plane(pl, z, off[0], off[1], 1);
#else
    (void)wide;
#endif
    return near_under_plane_r(pl, z, near_off_real(off[0]), near_off_real(off[1]));
}
#if TG_FIXED
#define NEAR_WIDE(q) ((q)->pl.wide)
#else
#define NEAR_WIDE(q) 0
#endif

/* NEAR_SLOPES: the march's tangent-plane test reads each sample's part of
 * n . r that its offset adds, ox nax - oy nay (near_under_plane_r's
 * difference of products, in Q16.16 with `wide` near_under_plane's exact
 * one), from a memo, a pixel's cell's 4 sides x TGI_NEAR_STEPS values,
 * made for its (nax, nay) and kept while the next pixels of that cell have
 * the same (a plane's pixels share their normal, so their nax and nay):
 * per sample a load where two offsets' loads, two products and a
 * difference were.  The same values, so the same answers: in float the
 * same products and difference of the same operands (fox nax - foy nay,
 * near_off_real's values); in Q16.16 made only for a pixel with `wide`,
 * whose |nr| + reach (|nax| + |nay|) <= TG_REAL_MAX bounds |ox nax - oy
 * nay| (|ox|, |oy| <= reach, near_off_real's note) within TG_REAL_MAX: the
 * exact 64-bit integer fits a tg_real, and so for every later pixel of the
 * same (nax, nay); (int64_t)nr + it is near_under_plane's sum.  Q16.16
 * without `wide` keeps the offsets' saturating form.  Keys compared by
 * their bits (float's +0 and -0 apart).  A sample 21 -> 15 instructions in
 * float, 32 -> 27 in Q16.16; 16% of cornell's pixels make their cell's
 * values anew (160x120 2 frames --gi-quarter: float cornell 227.25M ->
 * 225.73M, columns 156.27M -> 154.46M; Q16.16 312.32M -> 310.35M, 218.08M
 * -> 216.21M).  The memo takes 1.8 KB of stack in float, 3.6 KB in
 * Q16.16 (tgi_near_horizon_rows'), so only on 64-bit hosts, whose stacks
 * are large (as TGI_DENOISE_BAND's 16 rows, gi/denoise.h): 32-bit cores
 * keep the offsets' form within their stack (README "Porting"); none in a
 * build for size. */
#define NEAR_SLOPES (!TG_OUTLINE_HELPERS && TG_QUARTER_NEAR_REACH >= 1 && UINTPTR_MAX > 0xFFFFFFFFu)
#define NEAR_SLOPE_DELTAS (NEAR_SLOPES && TG_FIXED && TGI_NEAR_DELTAS)   /* (near_slope) */
#define NEAR_RAYS (NEAR_SLOPES && TG_FIXED ? 1024 : 0)   /* (near_ray_x) */
#if NEAR_SLOPES
/* a sample's value, in Q16.16 beside its index offset (NEAR_DELTA, where
 * the plan has them; else unset and unread): the march's loop then reads one table, its
 * pointer and counter a register each, where gcc else read three values
 * back from the stack a sample (Q16.16 160x120 2 frames --gi-quarter:
 * cornell 311.74M -> 311.61M, columns 217.50M -> 217.17M; float took
 * 0.9M more, so keeps the plan's offsets) */
typedef struct near_slope {
    tg_real t;
#if NEAR_SLOPE_DELTAS
    int32_t delta;
#endif
} near_slope;
typedef struct near_slopes {
    uint32_t key[16][2];   /* the bits of the (nax, nay) each cell's values were made for */
    unsigned char set[16];
    near_slope t[16][4][TGI_NEAR_STEPS];
#if NEAR_RAYS
    const tg_real *ray_x;   /* near_ray_x of columns [0, rays), tgi_near_horizon_rows' (NEAR_RAYS) */
    int rays;
#endif
} near_slopes;
static void near_slopes_start(near_slopes *s)
{
    memset(s->set, 0, sizeof s->set);
#if NEAR_RAYS
    s->rays = 0;
#endif
}
static inline uint32_t near_bits(tg_real v)
{
#if TG_FIXED
    return (uint32_t)v;
#else
    tgi_f32_bits b;   /* (raster/pack.h; memcpy is a call in a freestanding build) */
    b.f = v;
    return b.u;
#endif
}
/* cell's values for the plane pl (in Q16.16 a plane with `wide`) */
static const near_slope *near_slopes_of(near_slopes *s, const tgi_upsample_plan *u, int cell, const near_plane *pl)
{
    const uint32_t ka = near_bits(pl->nax), kb = near_bits(pl->nay);
    int k, n;
    if (s->set[cell] && s->key[cell][0] == ka && s->key[cell][1] == kb) return s->t[cell][0];
#if NEAR_SLOPE_DELTAS
    /* the index offsets, the plan's, the first time the cell is made (only
     * the inside copy reads them, which runs only where the plan has them) */
    if (!s->set[cell] && u->deltas)
        for (k = 0; k < 4; k++)
            for (n = 0; n < TGI_NEAR_STEPS; n++) s->t[cell][k][n].delta = NEAR_DELTA(u, cell, k, n);
#endif
    for (k = 0; k < 4; k++)
        for (n = 0; n < TGI_NEAR_STEPS; n++) {
            const signed char *o = NEAR_OFF(u, cell, k, n);
#if TG_FIXED
            s->t[cell][k][n].t = (tg_real)((int64_t)o[0] * pl->nax - (int64_t)o[1] * pl->nay);
#else
            s->t[cell][k][n].t = tg_sub(tg_mul(near_off_real(o[0]), pl->nax), tg_mul(near_off_real(o[1]), pl->nay));
#endif
        }
    s->set[cell] = 1;
    s->key[cell][0] = ka;
    s->key[cell][1] = kb;
    return s->t[cell][0];
}
/* near_under_plane of a sample whose offset adds t (near_slopes_of) */
static inline int near_under_slope(const near_plane *pl, tg_real z, tg_real t)
{
#if TG_FIXED
    return (int64_t)z * ((int64_t)pl->nr + t) <= pl->lim;
#else
    return tg_sub(tg_mul(z, tg_add(pl->nr, t)), pl->np) <= pl->above;
#endif
}
#else
typedef struct near_slope { tg_real t; } near_slope;
typedef struct near_slopes { int unused; } near_slopes;
#define near_slopes_start(s) ((void)(s))
#endif

int tgi_near_under_plane(tg_real nr, tg_real nax, tg_real nay, tg_real np, tg_real above, int reach, tg_real z, int ox,
                         int oy, int fast)
{
    near_plane pl;
    pl.nr = nr; pl.nax = nax; pl.nay = nay; pl.np = np; pl.above = above;
#if TG_FIXED
    near_plane_start(&pl, reach);
    if (fast && pl.wide) return near_under_plane(&pl, z, ox, oy, 1);
#else
    (void)reach; (void)fast;
#endif
    return near_under_plane(&pl, z, ox, oy, 0);
}

#if TGI_DEPTH_LAYERS
/* Over further depth layers, whether a sample above a pixel's tangent
 * plane pl, at depth z with its nearest back face at zb (0: none), is solid
 * down to that plane, so that its horizon bounds the occlusion from below
 * as on one layer: a one-sided boundary (no back face behind it, as
 * ssilvb.c's boundary_sectors) is; a closed object is where its back face,
 * on the sample's view ray, lies on or under the plane (the segment from
 * front to back then crosses every angle from the front's down to the
 * plane); a twosided sheet (zb = z) of unknown thickness is not. */
static inline int near_solid_below(const near_plane *pl, tg_real zb, tg_real z, const signed char off[2], const int wide)
{
    return !(zb >= z) || near_under_off(pl, zb, off, wide);
}
#endif

/* The largest cos(angle to the view vector) of the samples off[0..steps)
 * (pixel offsets) of pixel q that lie above the tangent plane and within
 * the radius; -1 when none; the march ends at the screen's edge (`inside`:
 * no sample can reach it).  A sample's view position is its depth z times
 * its ray r, so its height over the tangent plane is z (n . r) - n . p,
 * n . r changing by n.x ax and -n.y ay a pixel. */
#if defined(__GNUC__)
__attribute__((always_inline))   /* a copy for each `inside` and `wide`, their tests gone from the loop */
#endif
static inline tg_real near_horizon_cos(const tgi_upsample_plan *u, near_pixel *q, int cell, int side,
                                       const tgi_gview *g, const near_plane *ppl, const near_slope *slope,
                                       const int inside, const int wide)
{
#if TGI_NEAR_STEP_PAIRS
    const struct tgi_near_step *st = u->step[cell][side];
#define STEP_OFF(n) (st[n].off)
#define STEP_DELTA(n) (st[n].delta)
#else
    const signed char (*off)[2] = u->off[cell][side];
#if TGI_NEAR_DELTAS
    const int16_t *delta = u->delta[cell][side];
#endif
#define STEP_OFF(n) (off[n])
#define STEP_DELTA(n) (delta[n])
#endif
#if NEAR_OFF_PAIRS
    const float (*pair)[2] = near_off_pairs[cell][side];   /* off's, inside (u->deltas) */
#endif
    const near_plane pl = *ppl;
    const int x = q->x, y = q->y;
    const size_t i0 = q->i;
    tg_real best = TG_R(-1.0f);
#if TG_FIXED
    /* u->steps is 0 or TGI_NEAR_STEPS (tgi_upsample_start) and the march
     * runs only when it is not 0 (near_horizon_ao): the constant, one
     * register fewer in Q16.16's loops (cornell 320x240 --gi-quarter 2
     * frames 1483.37M -> 1480.88M; float, which unrolls them then,
     * 1000.22M -> 1002.17M, keeps u->steps) */
    const int steps = TGI_NEAR_STEPS;
#else
    const int steps = u->steps;
#endif
    int n = 0;
    for (;;) {
        size_t j = 0;
        tg_real z, d2, fdx, fdy;
        tg_vec3 h;
        /* the next sample above the tangent plane, in a loop of its own (the
         * compiler keeps its few values in registers) */
        for (; n < steps; n++) {
            int sx = x + STEP_OFF(n)[0], sy = y + STEP_OFF(n)[1];
            if (!inside && ((unsigned)sx >= (unsigned)g->width || (unsigned)sy >= (unsigned)g->height)) {
                n = steps;   /* the march ends at the screen's edge */
                break;
            }
            /* inside: the index of (sx, sy) as the pixel's plus the offset's
             * (the same size_t, both taken modulo 2^N; the memo's copy of the
             * offset, where the march reads it, NEAR_SLOPES) */
#if NEAR_SLOPE_DELTAS
            if (inside && wide) j = i0 + (size_t)(ptrdiff_t)slope[n].delta;
            else
#endif
#if TGI_NEAR_DELTAS
            j = inside ? i0 + (size_t)(ptrdiff_t)STEP_DELTA(n) : tgi_gv_index(g, sx, sy);
#else
            j = inside ? i0 + (size_t)((ptrdiff_t)STEP_OFF(n)[1] * g->row_stride
                                       + (ptrdiff_t)STEP_OFF(n)[0] * g->pixel_stride)
                       : tgi_gv_index(g, sx, sy);
#endif
#if NEAR_SLOPES
            if (!TG_FIXED || wide) {   /* the side's memo (near_slopes_of) */
                if (!tgi_gv_is_sky(g, j) && !near_under_slope(&pl, tgi_gv_depth(g, j), slope[n].t)) break;
                continue;
            }
#else
            (void)slope;
#endif
            if (!tgi_gv_is_sky(g, j) && !near_under_off(&pl, tgi_gv_depth(g, j), STEP_OFF(n), wide)) break;
        }
        if (n >= steps) break;
        z = tgi_gv_depth(g, j);
#if TGI_DEPTH_LAYERS
        if (u->layers && !near_solid_below(&pl, tgi_gv_back_depth(g, j), z, STEP_OFF(n), wide)) {
            n++;
            continue;
        }
#endif
#if NEAR_OFF_PAIRS
        fdx = inside ? pair[n][0] : near_off_real(STEP_OFF(n)[0]);
        fdy = inside ? pair[n][1] : near_off_real(STEP_OFF(n)[1]);
#else
        fdx = near_off_real(STEP_OFF(n)[0]);
        fdy = near_off_real(STEP_OFF(n)[1]);
#endif
#if TGI_Q16_WIDE
        if (q->hk < 0) near_hk_set(u, q);
        if (q->hk) {   /* tgi_upsample_start's note on hk */
            const int64_t lh = (int64_t)1 << q->hk;
            const int64_t bx = (int64_t)q->kx + (int64_t)STEP_OFF(n)[0] * u->ax;
            const int64_t by = (int64_t)q->ky - (int64_t)STEP_OFF(n)[1] * u->ay;
            int64_t hx = tgi_shr_round((int64_t)z * bx, TG_FRAC_BITS) - q->pv.x;
            int64_t hy = tgi_shr_round((int64_t)z * by, TG_FRAC_BITS) - q->pv.y, hz = (int64_t)z - q->pv.z;
            if (((uint64_t)(hx + lh) | (uint64_t)(hy + lh) | (uint64_t)(hz + lh)) < 2 * (uint64_t)lh) {
                tgi_wide d2w;
                n++;
                if (u->shift > 0) {
                    const int64_t m = (int64_t)1 << u->shift;
                    hx *= m; hy *= m; hz *= m;
                } else if (u->shift < 0) {
                    hx = tgi_shr_round(hx, -u->shift); hy = tgi_shr_round(hy, -u->shift); hz = tgi_shr_round(hz, -u->shift);
                }
                d2w = tgi_wide_dot(hx, hy, hz, hx, hy, hz);
                if (d2w >= u->r2 || d2w <= 0) continue;                      /* beyond the gather radius */
                /* d2 < r2 <= TG_REAL_MAX keeps each component below 2^24
                 * (its square below 2^47), times near_vd's unit vector
                 * (within 1 + 2^-16, below 2^17) the products' sum far
                 * below 2^62: tgi_v3_dot's value without its test */
                h = tg_v3((tg_real)hx, (tg_real)hy, (tg_real)hz);
                best = tg_max(best, tg_mul(tgi_v3_dot_bounded(h, near_vd(q)), near_rsqrt((tg_real)d2w)));   /* 0 < d2w < r2 */
                continue;
            }
        }
#endif
        n++;
        h = tg_v3(tg_sub(tg_mul(z, tg_add(q->kx, tg_mul(fdx, u->ax))), q->pv.x),
                  tg_sub(tg_mul(z, tg_sub(q->ky, tg_mul(fdy, u->ay))), q->pv.y), tg_sub(z, q->pv.z));
        if (u->shift) h = tg_v3(tg_ldexp(h.x, u->shift), tg_ldexp(h.y, u->shift), tg_ldexp(h.z, u->shift));
        d2 = tgi_v3_dot(h, h);
        if (d2 >= u->r2 || d2 <= 0) continue;                      /* beyond the gather radius */
        best = tg_max(best, tg_mul(tgi_v3_dot(h, near_vd(q)), near_rsqrt(d2)));   /* 0 < d2 < r2 */
    }
    return best;
#undef STEP_OFF
#undef STEP_DELTA
}

/* Whether every sample of side `side` of pixel q's cell lies inside the
 * image, so that its march may take near_horizon_cos's inside copy (the
 * same samples, indices and answer: that copy only leaves out the test of
 * the screen's edge, which no sample then meets).  Each offset is
 * floor((128 + t s) / 256) (tgi_upsample_start), non-decreasing in t for
 * s >= 0 and non-increasing for s < 0, with near_t increasing from t = 1
 * and floor(128 / 256) = 0 at t = 0: every offset of the side lies between
 * 0 and its last one on either axis, so the pixel and its last sample
 * inside put all of them inside.  A side at a time rather than the whole
 * reach around the pixel: a pixel near the image's edge marches its sides
 * that point away from it in the inside copy (cornell 160x120
 * --gi-quarter: 41% of the pixels lie within the reach of an edge, 22%
 * at 320x240). */
static inline int near_side_inside(const tgi_upsample_plan *u, const tgi_gview *g, const near_pixel *q, int cell,
                                   int side)
{
    const signed char *o = NEAR_OFF(u, cell, side, u->steps - 1);
    return (unsigned)(q->x + o[0]) < (unsigned)g->width && (unsigned)(q->y + o[1]) < (unsigned)g->height;
}

/* near_horizon_cos of the four sides of pixel q's slices into c1[k], c0[k]:
 * `inside` 1, each in the inside copy (the pixel's whole reach inside the
 * image), else each side in the copy near_side_inside allows. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void near_sides_with(const tgi_upsample_plan *u, near_pixel *q, int cell, const near_slope *slopes,
                                   tg_real c1[2], tg_real c0[2], const int inside, const int wide)
{
    /* the view and the plane as locals, kept in registers through the
     * marches (near_vd, which writes *q, would else have them read again
     * at every sample) */
    const tgi_gview gv = *u->full;
    const near_plane pl = q->pl;
#if TGI_NEAR_DELTAS
    const int deltas = u->deltas;   /* the inside copy reads the index offsets */
#else
    const int deltas = 1;
#endif
    int k;
    for (k = 0; k < 2; k++) {
        if (inside || (deltas && near_side_inside(u, &gv, q, cell, 2 * k)))
            c1[k] = near_horizon_cos(u, q, cell, 2 * k, &gv, &pl, slopes + 2 * k * TGI_NEAR_STEPS, 1, wide);
        else
            c1[k] = near_horizon_cos(u, q, cell, 2 * k, &gv, &pl, slopes + 2 * k * TGI_NEAR_STEPS, 0, wide);
        if (inside || (deltas && near_side_inside(u, &gv, q, cell, 2 * k + 1)))
            c0[k] = near_horizon_cos(u, q, cell, 2 * k + 1, &gv, &pl, slopes + (2 * k + 1) * TGI_NEAR_STEPS, 1, wide);
        else
            c0[k] = near_horizon_cos(u, q, cell, 2 * k + 1, &gv, &pl, slopes + (2 * k + 1) * TGI_NEAR_STEPS, 0, wide);
    }
}
static void near_horizon_sides(const tgi_upsample_plan *u, near_slopes *s, near_pixel *q, int cell,
                               tg_real c1[2], tg_real c0[2])
{
    const tgi_gview *g = u->full;
    const int inside = q->x >= u->reach && q->y >= u->reach && q->x + u->reach < g->width
                       && q->y + u->reach < g->height
#if TGI_NEAR_DELTAS
                       && u->deltas   /* the inside copy reads the index offsets */
#endif
        ;
    const near_slope *slopes = NULL;   /* Q16.16 without `wide`: none, the offsets' form */
#if NEAR_SLOPES
    if (!TG_FIXED || NEAR_WIDE(q)) slopes = near_slopes_of(s, u, cell, &q->pl);
#else
    (void)s;
#endif
    if (NEAR_WIDE(q)) {   /* Q16.16 only */
        if (inside) near_sides_with(u, q, cell, slopes, c1, c0, 1, 1);
        else near_sides_with(u, q, cell, slopes, c1, c0, 0, 1);
    } else if (inside) {
        near_sides_with(u, q, cell, slopes, c1, c0, 1, 0);
    } else {
        near_sides_with(u, q, cell, slopes, c1, c0, 0, 0);
    }
}

/* How much a lower bound of the near horizon's AO must stay above the
 * upsampled AO for its integrals to be skipped (near_horizon_ao): more than
 * the rounding of either number type in the integrals and the bound. */
#define NEAR_BOUND_MARGIN TG_R(0.015625f)

#if TGI_Q16_WIDE
/* Whether a Q16.16 value lies within [-2, 2 - 2^-16]: a + 2^17 (modulo 2^32) within
 * [0, 2^18 - 1], so the or of several such sums is below 2^18 iff each is. */
#define NEAR_SMALL(a) ((uint32_t)(a) + 0x20000u)

/* tgi_near_horizon_bound in Q16.16 without the saturation tests that
 * cannot fire, where every input lies within [-2, 2] (NEAR_SMALL: unit
 * vectors and cosines, up to their roundings) and each slice's n . s
 * within [-2, 2] (tested; 0: the caller takes the generic code, which
 * gives the same value).  Bounds (values, not raw): n . v, d . v, d . d
 * within 12, 8, 8, so the sums of products of the dots (tgi_wide_dot,
 * below 2^37) rounded once are tgi_v3_dot's, unsaturated; dv^2 <= 64,
 * perp within 72; perp > 0.01, so tg_rsqrt(perp) <= 10.1; n . d - (n . v)
 * dv within 104, times that within 1051: tg_mul's products unsaturated;
 * len^2 = (n . v)^2 + (n . s)^2 <= 148 (each square rounded, never
 * negative, so tg_add's sum, saturated or not, is the same); c^2 <= 4, 1 -
 * c^2 within [-3, 1], its root (of max(0, .)) <= 1 (+ rounding), times
 * n . v <= 12.2, c n . s <= 4, each l within 12.2 + 16.2 (len <= 12.2),
 * lost <= 4 of those; (n . s)^2 / len with len > 0.01 (raw >= 656) and
 * (n . s)^2 in [0, 4]: a quotient in [0, 400], tg_div's rounding
 * (tgi_div_nonneg: b > 0, a >= 0) unsaturated; open within 2 (12 + 400).
 * The last quotient, lost / open (open may be tiny), keeps tg_div. */
static int near_bound_wide(tg_vec3 nv, tg_vec3 vd, tg_real sdx, tg_real sdy, const tg_real c1[2], const tg_real c0[2],
                           tg_real *out)
{
    tg_real nv_v, lost = 0, open = 0;
    int k;
    if ((NEAR_SMALL(nv.x) | NEAR_SMALL(nv.y) | NEAR_SMALL(nv.z) | NEAR_SMALL(vd.x) | NEAR_SMALL(vd.y) | NEAR_SMALL(vd.z)
         | NEAR_SMALL(sdx) | NEAR_SMALL(sdy) | NEAR_SMALL(c1[0]) | NEAR_SMALL(c1[1]) | NEAR_SMALL(c0[0])
         | NEAR_SMALL(c0[1])) >= 0x40000u)
        return 0;
    nv_v = (tg_real)tgi_wide_dot(nv.x, nv.y, nv.z, vd.x, vd.y, vd.z);
    if (nv_v <= 0) { *out = TG_R(-1.0f); return 1; }
    for (k = 0; k < 2; k++) {
        const tg_real dx = k ? -sdy : sdx, dy = k ? -sdx : -sdy;   /* the slice's (x, -y, 0) */
        tg_real dv = (tg_real)tgi_wide_dot(dx, dy, 0, vd.x, vd.y, vd.z), perp, nv_s, len, l;
        perp = (tg_real)(tgi_wide_dot(dx, dy, 0, dx, dy, 0) - tgi_wide_mul(dv, dv));
        if (perp <= TG_R(0.01f)) { *out = TG_R(-1.0f); return 1; }
        nv_s = (tg_real)tgi_wide_mul(tgi_wide_dot(nv.x, nv.y, nv.z, dx, dy, 0) - tgi_wide_mul(nv_v, dv), near_rsqrt(perp));   /* perp in (0.01, 72] */
        if (NEAR_SMALL(nv_s) >= 0x40000u) return 0;
        len = tg_sqrt((tg_real)(tgi_wide_mul(nv_v, nv_v) + tgi_wide_mul(nv_s, nv_s)));
        if (len <= TG_R(0.01f)) { *out = TG_R(-1.0f); return 1; }
        if (c1[k] > TG_R(-1.0f)) {   /* len (1 - sin(t - g)) */
            tgi_wide r = tgi_wide_mul(tg_sqrt(tg_max(0, (tg_real)(TG_ONE - tgi_wide_mul(c1[k], c1[k])))), nv_v);
            l = (tg_real)(len - (r - tgi_wide_mul(c1[k], nv_s)));
            lost += tg_max(0, l);
        }
        if (c0[k] > TG_R(-1.0f)) {   /* len (1 - sin(t + g)) */
            tgi_wide r = tgi_wide_mul(tg_sqrt(tg_max(0, (tg_real)(TG_ONE - tgi_wide_mul(c0[k], c0[k])))), nv_v);
            l = (tg_real)(len - (r + tgi_wide_mul(c0[k], nv_s)));
            lost += tg_max(0, l);
        }
        open += nv_v + tgi_div_nonneg((tg_real)tgi_wide_mul(nv_s, nv_s), len);   /* len (cos g + sin^2 g) */
    }
    *out = tg_sub(TG_ONE, tg_div(lost, open));
    return 1;
}
#undef NEAR_SMALL
#endif

tg_real tgi_near_horizon_bound(tg_vec3 nv, tg_vec3 vd, tg_real sdx, tg_real sdy, const tg_real c1[2],
                                const tg_real c0[2])
{
    tg_real nv_v, lost = 0, open = 0;
    int k;
#if TGI_Q16_WIDE
    if (near_bound_wide(nv, vd, sdx, sdy, c1, c0, &lost)) return lost;
    lost = 0;
#endif
    nv_v = tgi_v3_dot(nv, vd);
    if (nv_v <= 0) return TG_R(-1.0f);
    for (k = 0; k < 2; k++) {
        tg_vec3 d3 = k ? tg_v3(tg_neg(sdy), tg_neg(sdx), 0) : tg_v3(sdx, tg_neg(sdy), 0);   /* the slice's (x, -y, 0) */
        tg_real dv = tgi_v3_dot(d3, vd), perp = tg_sub(tgi_v3_dot(d3, d3), tg_sqr(dv)), nv_s, len, l;
        if (perp <= TG_R(0.01f)) return TG_R(-1.0f);
        nv_s = tg_mul(tg_sub(tgi_v3_dot(nv, d3), tg_mul(nv_v, dv)), tg_rsqrt(perp));   /* n . s_k */
        len = tg_sqrt(tg_add(tg_sqr(nv_v), tg_sqr(nv_s)));
        if (len <= TG_R(0.01f)) return TG_R(-1.0f);
        if (c1[k] > TG_R(-1.0f)) {   /* len (1 - sin(t - g)) */
            l = tg_sub(len, tg_sub(tg_mul(tg_sqrt(tg_max(0, tg_sub(TG_ONE, tg_sqr(c1[k])))), nv_v), tg_mul(c1[k], nv_s)));
            lost = tg_add(lost, tg_max(0, l));
        }
        if (c0[k] > TG_R(-1.0f)) {   /* len (1 - sin(t + g)) */
            l = tg_sub(len, tg_add(tg_mul(tg_sqrt(tg_max(0, tg_sub(TG_ONE, tg_sqr(c0[k])))), nv_v), tg_mul(c0[k], nv_s)));
            lost = tg_add(lost, tg_max(0, l));
        }
        open = tg_add(open, tg_add(nv_v, tg_div(tg_sqr(nv_s), len)));   /* len (cos g + sin^2 g) */
    }
    return tg_sub(TG_ONE, tg_div(lost, open));
}

/* tg_ldexp(z, -10), the depth's part of the height over the tangent plane
 * below which a sample counts for nothing: in float one product by 2^-10
 * where z 2^-10 is a normal number (z >= 2^-116; NaN fails the test),
 * where each of tg_ldexp's ten halvings is exact too: the same value. */
static tg_real near_depth_part(tg_real z)
{
#if !TG_FIXED && !TG_OUTLINE_HELPERS
    if (z >= TG_R(0x1p-116f)) return z * TG_R(0x1p-10f);
#endif
    return tg_ldexp(z, -10);
}

/* The near horizon of surface pixel (x, y), index i (tgi_gv_index), normal nv in view space: the
 * AO (cosine-weighted, RTR eq. 11.18, the slices weighted as GTAO's,
 * src/ao/ao.h) under the horizons of full-resolution pixels up to
 * TG_QUARTER_NEAR_REACH away along its two slices, both sides, within the
 * gather radius (ky: the row's near_ray_y).  It sees only occluders the whole horizon sees too, so it
 * is an upper bound of the AO, as the upsampled one is.  1 (without the
 * integrals) when no sample rises above the tangent plane, or when its lower
 * bound (tgi_near_horizon_bound) is above `ao`, the upsampled AO it caps, by
 * more than NEAR_BOUND_MARGIN: either way no lower than `ao`. */
/* The view ray's y of row y (tgi_ao_unproject's), which near_horizon_ao
 * takes from its caller, once a row, not once a pixel (the same quotient;
 * Q16.16 cornell 320x240 --gi-quarter 2 frames 1455.71M -> 1452.50M, float
 * unchanged); only where the plan has a near horizon (u->steps > 0: hfy
 * set). */
static tg_real near_ray_y(const tgi_upsample_plan *u, int y)
{
    return tg_div(tg_from_int(u->full->camera->height - 2 * y - 1), u->hfy);
}
/* The view ray's x of column x (tgi_ao_unproject's), which
 * tgi_near_horizon_rows in Q16.16 computes once a call for its first
 * NEAR_RAYS columns, near_horizon_ao reading them from its memo (the same
 * quotient, not once a pixel: 160x120 2 frames --gi-quarter cornell
 * 310.18M -> 309.52M, columns 216.03M -> 215.39M; float's quotient, a
 * division, cost less than the table, 225.73M -> 225.76M, 154.46M ->
 * 154.48M, so it keeps it); 4 KB of stack, so only on 64-bit hosts (as
 * NEAR_SLOPES); u->steps > 0 (wfx set). */
static tg_real near_ray_x(const tgi_upsample_plan *u, int x)
{
    return tg_div(tg_from_int(2 * x + 1 - u->full->camera->width), u->wfx);
}

static tg_real near_horizon_ao(const tgi_upsample_plan *u, near_slopes *s, int x, int y, size_t i, tg_real ky, tg_vec3 nv,
                               tg_real ao)
{
    const tgi_gview *full = u->full;
    int cell = (x & 3) + ((y & 3) << 2);
    const tg_real *d = near_dir[cell];
    tg_real c1[2], c0[2], vis = 0, open = 0, h1, h0, z;
    near_pixel q;
    tgi_ao_slice sl;
    int k, found = 0;
    if (u->steps < 1) return TG_ONE;
    q.x = x; q.y = y; q.i = i;
#if NEAR_RAYS
    q.kx = x < s->rays ? s->ray_x[x] : near_ray_x(u, x);   /* tgi_ao_unproject's ray */
#else
    q.kx = near_ray_x(u, x);   /* tgi_ao_unproject's ray */
#endif
    q.ky = ky;   /* near_ray_y(u, y) */
    z = tgi_gv_depth(full, i);                                   /* tgi_ao_view_at's view of the pixel */
    q.pv = tg_v3(tg_mul(q.kx, z), tg_mul(q.ky, z), z);
    q.nv = nv;
    q.has_vd = 0;
    q.pl.nax = tg_mul(q.nv.x, u->ax);
    q.pl.nay = tg_mul(q.nv.y, u->ay);
    q.pl.nr = tg_add(tg_add(tg_mul(q.nv.x, q.kx), tg_mul(q.nv.y, q.ky)), q.nv.z);
    q.pl.np = tgi_v3_dot(q.nv, q.pv);
    q.pl.above = tg_add(near_depth_part(q.pv.z), u->above_r);
#if TG_FIXED
    near_plane_start(&q.pl, u->reach);
#endif
#if TGI_Q16_WIDE
    q.hk = -1;   /* near_hk_set, at the first sample above the tangent plane */
#endif
    near_horizon_sides(u, s, &q, cell, c1, c0);   /* the cell's direction and the one at right angles */
    for (k = 0; k < 2; k++) found |= c1[k] > TG_R(-1.0f) || c0[k] > TG_R(-1.0f);
    if (!found) return TG_ONE;
    near_vd(&q);
    if (tg_sub(tgi_near_horizon_bound(q.nv, q.vd, d[0], d[1], c1, c0), NEAR_BOUND_MARGIN) >= ao) return TG_ONE;
    for (k = 0; k < 2; k++) {
        tg_real o;
        if (!tgi_ao_slice_frame(q.nv, q.vd, k ? tg_neg(d[1]) : d[0], k ? d[0] : d[1], &sl)) continue;
        o = tg_mul(sl.len, tg_add(sl.cos_g, tg_mul(sl.gamma, sl.sin_g)));
        open = tg_add(open, o);
        /* a slice without a horizon sees its open arc */
        if (c1[k] > TG_R(-1.0f) || c0[k] > TG_R(-1.0f)) o = tg_mul(sl.len, tgi_ao_slice_arc(&sl, c1[k], c0[k], &h1, &h0));
        vis = tg_add(vis, o);
    }
    return open > 0 ? tg_saturate(tg_div(vis, open)) : TG_ONE;
}

/* A pixel's normal in view space (tgi_ao_dir_to_view of tgi_gv_normal),
 * m's where the stored code repeats (tgi_gv_normal_repeats). */
static tg_vec3 near_view_normal(const tgi_gview *g, tgi_normal_memo *m, size_t i)
{
    if (!tgi_gv_normal_repeats(g, m, i)) m->n = tgi_ao_dir_to_view(g->camera, tgi_gv_normal(g, i));
    return m->n;
}

/* The near horizon of surface pixel (x, y), index i, as the plane of
 * tgi_near_horizon_rows keeps it (the results' AO storage, the same value
 * read back), skipping its integrals (near_horizon_ao) where it cannot go
 * below the highest filtered AO of the half-res pixels its upsample
 * weighs (bilinear_taps), so not below its upsampled AO, a weighted mean
 * of theirs; m keeps the last pixel's normal (near_view_normal). */
static tg_real near_horizon_stored(const tgi_upsample_plan *u, tgi_normal_memo *m, near_slopes *s, int x, int y, size_t i,
                                   tg_real ky)
{
    const tgi_gview *half = u->half;
    size_t tap[4];
    tg_real top = 0, ao;
    int k, n, slot[4];
    (void)bilinear_taps(half, x, y, tap, slot, &n);   /* those of weight above 0 */
    for (k = 0; k < n; k++)
        if (!tgi_gv_is_sky(half, tap[k])) top = tg_max(top, tgi_gr_ao(u->res, tap[k]));
    ao = near_horizon_ao(u, s, x, y, i, ky, near_view_normal(u->full, m, i), top);
#if TG_WIDE_STORAGE
    return ao;
#else
    return tgi_unorm8_unpack(tgi_unorm8_pack(ao));
#endif
}

/* near_horizon_stored with its row's ray (out of line: the upsample's
 * registers stay its own) */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static tg_real near_horizon_stored_at(const tgi_upsample_plan *u, tgi_normal_memo *m, int x, int y, size_t i)
{
    near_slopes s;   /* a pixel's own (this path is not the near horizon pass's) */
    near_slopes_start(&s);
    return near_horizon_stored(u, m, &s, x, y, i, near_ray_y(u, y));
}

/* The upsampled AO ao of full-res pixel (x, y) at depth z capped by the
 * mean near horizon of the pixel and of its 3x3 neighbours at its depth (within a tenth of it, where the upsample's depth
 * weight reaches): a pixel's own is 2 slices (its 4x4 cell's, near_dir),
 * a noisy estimate whose low side the cap min(upsampled, near) would take
 * (dark single pixels beside a sphere's foot, AO biased low); the mean
 * sees 18 directions.  AO RMSE against the ray-traced reference, 8 frames
 * of `--gi-quarter`, spheres 160x120 0.071 -> 0.051, columns 0.060 ->
 * 0.052 (README, "Quarter resolution and the near horizon").  Over further
 * depth layers the pixel's own: there the near horizon takes only what is
 * solid below it and the cap stays a bound (the mean: spheres 0.043 ->
 * 0.044, columns 0.037 -> 0.040). */
/* near_horizon_mean's term of neighbour j with the near horizons stored (u->near). */
static inline void near_mean_term(const tgi_upsample_plan *u, size_t j, tg_real z, tg_real tol, tgi_wide *sum, int *n)
{
    if (!(tg_abs(tg_sub(tgi_gv_depth(u->full, j), z)) < tol)) return;   /* sky too (near_horizon_mean's note) */
    *sum += tgi_gr_ao(u->near, j);
    (*n)++;
}

/* A sky neighbour (depth 0) is never within tol of z, so it has no test
 * of its own: z >= 0 (a surface's depth, tgi_gv_depth), so |0 - z| = z
 * (tg_sub exact) and tol = 0.1 z rounded is at most z (float: z times
 * 0.1f rounded, monotone; Q16.16: floor((6554 z + 2^15) / 2^16) <= z, raw
 * values), so z < tol fails; NaN fails it too. */
/* The least of the stored near horizons of the 3x3 neighbourhood rows j0,
 * j1, j2 (each three pixels px apart): m.  Their mean over any of them
 * (near_horizon_mean, whatever its depth tests take; none: TG_ONE) is at
 * least m: in Q16.16 exactly (n values >= m sum to s >= n m, exact
 * integers, and tgi_div_nonneg gives floor(s / n + 1/2) >= m, m an
 * integer), in float but for the roundings (n <= 9 values >= m > 0, all
 * normal: each of the n - 1 sums of non-negative terms and the quotient
 * lose at most a factor 1 - 2^-24, so the mean is > m (1 - 9 2^-24)).  So
 * the cap min(ao, mean) is ao where ao <= m (Q16.16), where ao < m (1 -
 * 2^-20) rounded (float: that product is at most m (1 - 2^-20) (1 +
 * 2^-24) < m (1 - 9 2^-24); m = 0 passes no ao >= 0), and where m is 1
 * (every stored near horizon lies in [0, 1]: near_horizon_ao gives
 * TG_ONE or a tg_saturate; so all nine are 1, as byte 255, which
 * tgi_unorm8_unpack makes TG_ONE exactly: Q16.16 255 * 257 + 1 = 65536,
 * float 255 times 1/255 rounded rounds to 1; n ones sum to n exactly,
 * n / n = 1, and ao <= 1, a tg_saturate).  Most pixels have no sample
 * above their tangent plane (near_horizon_ao: 1) or a near horizon above
 * the upsampled AO: the nine values' minimum skips their depth tests and
 * their sum for most (cornell 320x240 --gi-quarter 2 frames, float 992.60M
 * -> 977.82M, Q16.16 1480.88M -> 1449.32M with the other changes between;
 * the and of the nine bytes against 255 alone took 978.20M, 1450.76M).
 * The minimum of the bytes, unpacked (tgi_unorm8_unpack is
 * non-decreasing).  A build for size tests nothing and sums. */
#if !TG_OUTLINE_HELPERS
#define NEAR_LESS(a, b) ((b) < (a) ? (b) : (a))
static inline tg_real near_least(const tgi_gresult *r, size_t j0, size_t j1, size_t j2, size_t px)
{
#if TG_WIDE_STORAGE
    tg_real m;
#else
    uint8_t m;
#endif
    m = NEAR_LESS(r->ao[j0], r->ao[j0 + px]); m = NEAR_LESS(m, r->ao[j0 + 2 * px]);
    m = NEAR_LESS(m, r->ao[j1]); m = NEAR_LESS(m, r->ao[j1 + px]); m = NEAR_LESS(m, r->ao[j1 + 2 * px]);
    m = NEAR_LESS(m, r->ao[j2]); m = NEAR_LESS(m, r->ao[j2 + px]); m = NEAR_LESS(m, r->ao[j2 + 2 * px]);
#if TG_WIDE_STORAGE
    return m;
#else
    return tgi_unorm8_unpack(m);
#endif
}
#undef NEAR_LESS
/* whether near_least's m leaves the upsampled AO ao uncapped */
static inline int near_below_least(tg_real ao, tg_real m)
{
#if TG_FIXED
    return ao <= m;
#else
    return m >= TG_ONE || ao < m * (1.0f - 0x1p-20f);
#endif
}
#endif

static tg_real near_horizon_mean(const tgi_upsample_plan *u, int x, int y, tg_real z, tg_real ao)
{
    const tgi_gview *full = u->full;
    const tg_real tol = upsample_depth_tol(z);   /* where upsample_depth_weight is above 0 */
    tgi_wide sum = 0;   /* at most 9 AO values in [0, 1]: tg_add's sums without its saturation tests */
    int n = 0, xx, yy, r = 1, xa, xb, ya, yb;
    tgi_normal_memo m;
    tgi_normal_memo_start(&m);
#if TGI_DEPTH_LAYERS
    if (u->layers) r = 0;
#endif
    /* the neighbourhood's part inside the image, rows then columns */
    xa = x - r < 0 ? 0 : x - r; xb = x + r >= full->width ? full->width - 1 : x + r;
    ya = y - r < 0 ? 0 : y - r; yb = y + r >= full->height ? full->height - 1 : y + r;
    if (u->near && xb - xa == 2 && yb - ya == 2) {   /* all 3x3 inside the image, the stored near horizons */
        const size_t px = (size_t)full->pixel_stride, row = (size_t)full->row_stride;
        const size_t j0 = tgi_gv_index(full, xa, ya), j1 = j0 + row, j2 = j1 + row;   /* modulo 2^N, as the loop's */
#if !TG_OUTLINE_HELPERS
        if (near_below_least(ao, near_least(u->near, j0, j1, j2, px))) return ao;
#endif
        /* the loop's terms in its order (rows, then columns) */
        near_mean_term(u, j0, z, tol, &sum, &n); near_mean_term(u, j0 + px, z, tol, &sum, &n);
        near_mean_term(u, j0 + 2 * px, z, tol, &sum, &n);
        near_mean_term(u, j1, z, tol, &sum, &n); near_mean_term(u, j1 + px, z, tol, &sum, &n);
        near_mean_term(u, j1 + 2 * px, z, tol, &sum, &n);
        near_mean_term(u, j2, z, tol, &sum, &n); near_mean_term(u, j2 + px, z, tol, &sum, &n);
        near_mean_term(u, j2 + 2 * px, z, tol, &sum, &n);
        return tg_min(ao, n > 0 ? tgi_div_nonneg(tgi_wide_real(sum), tg_from_int(n)) : TG_ONE);
    }
    for (yy = ya; yy <= yb; yy++) {
        size_t j = tgi_gv_index(full, xa, yy);
        for (xx = xa; xx <= xb; xx++, j += (size_t)full->pixel_stride) {   /* j: (xx, yy), modulo 2^N */
            if (!(tg_abs(tg_sub(tgi_gv_depth(full, j), z)) < tol)) continue;   /* sky too (near_horizon_mean's note) */
            sum += u->near ? tgi_gr_ao(u->near, j) : near_horizon_stored_at(u, &m, xx, yy, j);
            n++;
        }
    }
    return tg_min(ao, n > 0 ? tgi_div_nonneg(tgi_wide_real(sum), tg_from_int(n)) : TG_ONE);
}

void tgi_near_horizon_rows(const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res, tg_real radius,
                           const tgi_gresult *near, int y0, int y1)
{
    tgi_upsample_plan u;
    tgi_normal_memo m;
    near_slopes sl;   /* along the rows: a plane's pixels share a cell's values */
    int x, y;
#if NEAR_RAYS
    tg_real ray_x[NEAR_RAYS];   /* near_ray_x of columns [0, sl.rays) */
#endif
    if (y1 > full->height) y1 = full->height;
    tgi_upsample_start(&u, full, half, half_res, radius, near);
    tgi_normal_memo_start(&m);
    near_slopes_start(&sl);
#if NEAR_RAYS
    sl.ray_x = ray_x;
    if (u.steps > 0 && y0 < y1)
        for (sl.rays = full->width < NEAR_RAYS ? full->width : NEAR_RAYS, x = 0; x < sl.rays; x++) ray_x[x] = near_ray_x(&u, x);
#endif
    for (y = y0; y < y1; y++) {
        const tg_real ky = u.steps > 0 ? near_ray_y(&u, y) : 0;
        for (x = 0; x < full->width; x++) {
            size_t i = tgi_gv_index(full, x, y);
            tgi_gr_set_ao(near, i, tgi_gv_is_sky(full, i) ? TG_ONE : near_horizon_stored(&u, &m, &sl, x, y, i, ky));
        }
    }
}

/* Half-res pixel j decoded into slot t of the walk (once per pixel while
 * the row's pixels share it): sky, depth, normal, AO, bend (bent -
 * normal) and near field where the results carry them. */
static const tgi_upsample_tap *upsample_tap(const tgi_upsample_plan *u, tgi_upsample_walk *w, int t, size_t j)
{
    tgi_upsample_tap *c = &w->tap[t];
    if (c->index == j) return c;
    c->index = j;
    c->sky = tgi_gv_is_sky(u->half, j);
    if (c->sky) return c;
    c->z = tgi_gv_depth(u->half, j);
    c->n = tgi_gv_normal(u->half, j);
    c->ao = tgi_gr_ao(u->res, j);
    if (tgi_gr_has_bent(u->res)) {   /* the bend (bent - normal) is what carries over (Klehm sec. 3.4) */
        tg_vec3 b = tgi_gr_bent(u->res, j);
#if !TG_WIDE_STORAGE
        /* octahedral unit vectors (within 1 + 2^-16): tg_sub's differences
         * never saturate */
        c->bend = tg_v3(b.x - c->n.x, b.y - c->n.y, b.z - c->n.z);
#else
        c->bend = tg_v3(tg_sub(b.x, c->n.x), tg_sub(b.y, c->n.y), tg_sub(b.z, c->n.z));
#endif
    }
    if (tgi_gr_has_near(u->res)) c->near = tgi_gr_near(u->res, j);
    return c;
}

#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
/* tg_max(0, tg_div(a, b)) for a >= 0 and b > 0 (tgi_upsample_at's near
 * field: sums of the weights w > 0 times rgb9e5's values >= 0, in either
 * form of tgi_wide_add_weighted never below 0, saturated to at most
 * TG_REAL_MAX; their weights' sum > 0, at most TG_REAL_MAX): tg_div's
 * quotient (a 2^16 + floor(b / 2)) / b, truncated, >= 0, saturated at
 * TG_REAL_MAX only (tgi_sat64), without its tests of b = 0 and of the
 * signs; the maximum with 0 changes nothing (Q16.16 160x120 2 frames
 * --gi-quarter: cornell 317.08M -> 316.73M, columns 225.96M -> 225.65M;
 * checked against tg_div on 2e8 random pairs, 0 differ). */
static inline tg_real near_quotient(tg_real a, tg_real b)
{
    const uint64_t q = (((uint64_t)(uint32_t)a << 16) + ((uint32_t)b >> 1)) / (uint32_t)b;
    return q > (uint64_t)TG_REAL_MAX ? TG_REAL_MAX : (tg_real)q;
}
#endif

void tgi_upsample_walk_start(tgi_upsample_walk *w)
{
    int t;
    for (t = 0; t < 4; t++) w->tap[t].index = (size_t)-1;
    tgi_normal_memo_start(&w->normal);
}

tgi_gr_value tgi_upsample_at(const tgi_upsample_plan *u, tgi_upsample_walk *walk, int x, int y)
{
    const tgi_gview *full = u->full, *half = u->half;
    const tgi_gresult *hr = u->res;
    size_t i = tgi_gv_index(full, x, y), tap[4];
    tg_real wt, sum, ao, floor_w = TG_R(0.015625f), z;
    tgi_wide sum_w = 0, ao_w = 0, near_w[3] = { 0, 0, 0 };   /* running sums (tgi_wide_add_weighted) */
    tg_vec3 n, bend = tg_v3(0, 0, 0), near;
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
    tgi_wide bend_w[3] = { 0, 0, 0 };   /* bend's sums, unsaturated (below) */
#endif
    int k, taps, slot[4], want_bent = tgi_gr_has_bent(hr), want_near = tgi_gr_has_near(hr);
    tgi_gr_value v;
    if (tgi_gv_is_sky(full, i)) return upsample_open(full, i);
    n = tgi_gv_normal_memo(full, &walk->normal, i);   /* the walk's last where the code repeats */
    z = tgi_gv_depth(full, i);
    wt = bilinear_taps(half, x, y, tap, slot, &taps);
    for (k = 0; k < taps; k++) {
        const tgi_upsample_tap *c;
        tg_real w;
        /* tap k is half-res pixel (X0 or X1, Y0 or Y1): a slot per parity of
         * its coordinates, the two of a pixel's taps on an axis differ in it */
        c = upsample_tap(u, walk, slot[k], tap[k]);
        if (c->sky) continue;
        /* the depth weight within [0, 1] and the bilinear one within (0, 1]
         * keep each product within its other factor (tgi_wide) */
        w = (tg_real)tgi_wide_mul(wt, tg_max(floor_w, (tg_real)tgi_wide_mul(upsample_depth_weight(z, c->z),
                                                                               upsample_normal_weight(n, c->n))));
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
        /* tgi_wide_add_weighted of w and 1, of w and the AO, without its
         * range tests: w in (0, 256] (floor_w > 0; the normal weight within
         * 256, upsample_normal_weight; the other factors within 1), the AO
         * in [0, 1] (unorm8), so each product rounded (its fast form's and
         * tg_mul's rounding, w 1 = w exactly) is below 2^25 and the sums of
         * at most 4 stay far inside the range, where its saturating form
         * (w above 1) gives these integers too (Q16.16 cornell 320x240
         * --gi-quarter 2 frames 1449.32M -> 1447.65M) */
        sum_w += w;
        ao_w += tgi_wide_mul(w, c->ao);
#else
        sum_w = tgi_wide_add_weighted(sum_w, w, TG_ONE);
        ao_w = tgi_wide_add_weighted(ao_w, w, c->ao);
#endif
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
        /* the bend's tg_mul and tg_add without their saturation tests: each
         * component is the difference of two octahedral unit vectors'
         * (tgi_oct_unpack: within 1 + 2^-16, upsample_normal_weight's note),
         * within 2 + 2^-15, times w in (0, 256]: products within 513, their
         * sum over at most 4 taps within 2052, far inside the range, so the
         * same integers */
        if (want_bent) {
            bend_w[0] += tgi_wide_mul(w, c->bend.x);
            bend_w[1] += tgi_wide_mul(w, c->bend.y);
            bend_w[2] += tgi_wide_mul(w, c->bend.z);
        }
#else
        if (want_bent)
            bend = tg_v3(tg_add(bend.x, tg_mul(w, c->bend.x)), tg_add(bend.y, tg_mul(w, c->bend.y)),
                         tg_add(bend.z, tg_mul(w, c->bend.z)));
#endif
        if (want_near) {
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
            /* tgi_wide_add_weighted's fast form for every w, w above 1
             * too (the normal weight of two equal normals rounds a little
             * above 1, so its slow form ran at a third of the taps): each
             * term p = w v rounded is >= 0 (w in (0, 256], v >= 0: rgb9e5
             * unpacked is never negative), where tg_mul rounds it alike.
             * Over terms >= 0 both forms end at min(S, TG_REAL_MAX), S the
             * terms' exact sum: the slow form's step sat(sat(acc) +
             * sat(p)) is min(acc + p, TG_REAL_MAX) for acc, p >= 0 (either
             * above the range puts the sum there), so by induction the
             * running sum is S while S is within the range, and at least
             * TG_REAL_MAX once S is above it, and tgi_wide_real
             * saturates it at the end; here the sum is S itself (p below
             * 2^55, four of them below 2^57) (Q16.16 160x120 2 frames
             * --gi-quarter: cornell 310.35M -> 310.18M, columns 216.21M ->
             * 216.04M) */
            near_w[0] += ((int64_t)w * c->near.x + 32768) >> 16;
            near_w[1] += ((int64_t)w * c->near.y + 32768) >> 16;
            near_w[2] += ((int64_t)w * c->near.z + 32768) >> 16;
#else
            near_w[0] = tgi_wide_add_weighted(near_w[0], w, c->near.x);
            near_w[1] = tgi_wide_add_weighted(near_w[1], w, c->near.y);
            near_w[2] = tgi_wide_add_weighted(near_w[2], w, c->near.z);
#endif
        }
    }
    sum = tgi_wide_real(sum_w);
    ao = tgi_wide_real(ao_w);
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
    bend = tg_v3((tg_real)bend_w[0], (tg_real)bend_w[1], (tg_real)bend_w[2]);
#endif
    near = tg_v3(tgi_wide_real(near_w[0]), tgi_wide_real(near_w[1]), tgi_wide_real(near_w[2]));
    if (sum <= 0) return upsample_open(full, i);   /* only sky around: treat as open */
    /* the upsampled AO misses what lies between the half-res samples (a
     * contact shadow a few pixels wide): the near horizon's is the lower */
#if !TG_WIDE_STORAGE
    /* tg_div's quotients where they fit (tgi_div_nonneg, tgi_div_pos: the
     * same roundings, sum > 0): the AO's sum is at least 0 and at most the
     * weights' (each product w a rounded, a within [0, 1] (unorm8), is
     * within [0, w]), so its quotient lies in [0, 1]; each bend's sum is
     * that of w b rounded, |b| within 2 + 2^-15 (above), so its quotient is
     * within 2.001 */
    v.ao = tg_saturate(tgi_div_nonneg(ao, sum));
#else
    v.ao = tg_saturate(tg_div(ao, sum));
#endif
    if (u->steps > 0) v.ao = near_horizon_mean(u, x, y, z, v.ao);
    v.bent = n;
    if (want_bent) {
#if !TG_WIDE_STORAGE
        /* n within 1 + 2^-16, the quotients within 2.001: b within 3.01,
         * tg_add's sums and the dot (tgi_v3_dot_bounded) unsaturated */
        tg_vec3 b = tg_v3(n.x + tgi_div_pos(bend.x, sum), n.y + tgi_div_pos(bend.y, sum), n.z + tgi_div_pos(bend.z, sum));
        tg_real d = tgi_v3_dot_bounded(b, n);
#else
        tg_vec3 b = tgi_v3_add(n, tg_v3(tg_div(bend.x, sum), tg_div(bend.y, sum), tg_div(bend.z, sum)));
        tg_real d = tgi_v3_dot(b, n);
#endif
        /* keep it in the normal's hemisphere: drop the part below the tangent plane */
        if (d < 0) b = tgi_v3_sub(b, tgi_v3_scale(n, d));
        v.bent = tgi_v3_unit_or(b, n);
    }
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
    v.near = want_near ? tg_v3(near_quotient(near.x, sum), near_quotient(near.y, sum), near_quotient(near.z, sum))
                       : tg_v3(0, 0, 0);
#else
    v.near = want_near ? tg_v3(tg_max(0, tg_div(near.x, sum)), tg_max(0, tg_div(near.y, sum)), tg_max(0, tg_div(near.z, sum)))
                       : tg_v3(0, 0, 0);
#endif
    return v;
}

tgi_gr_value tgi_upsample_pixel(const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res,
                                tg_real radius, int x, int y)
{
    tgi_upsample_plan u;
    tgi_upsample_walk w;
    tgi_upsample_start(&u, full, half, half_res, radius, NULL);
    tgi_upsample_walk_start(&w);
    return tgi_upsample_at(&u, &w, x, y);
}
