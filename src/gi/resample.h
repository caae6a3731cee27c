/* SPDX-License-Identifier: MIT */
/*
 * resample.h - quarter resolution for the GI kernel: point-sampled
 * downsampling of the G-buffer view to half width and height, and the joint
 * bilateral (depth- and normal-aware) upsampling of the kernel's results.
 * Both are row-parallel.
 */
#ifndef TG_RESAMPLE_H
#define TG_RESAMPLE_H

#include "../raster/gview.h"

/* Half-resolution size of a w x h image: ceil(w / 2) x ceil(h / 2). */
void tgi_half_size(int w, int h, int *hw, int *hh);

/* Half-res rows [y0, y1): half-res pixel (X, Y) = full's pixel (2X, 2Y):
 * its G-buffer pixel into the packed storage half (of the half size), and
 * the radiance src into half_src when present. */
void tgi_downsample_rows(const tgi_gview *full, const tgi_gbuffer *half, const tgi_rgb *src,
                         const tgi_rgb *half_src, int y0, int y1);

/* Samples a side of the near horizon: those of 1, 2, 3, 4, 6, 9, 13, 19,
 * 28, 42, 63, 94, 141, 211, 316, 474 pixels away (from 4 on, each 1.5 times
 * the last) up to TG_QUARTER_NEAR_REACH (src/gi/resample.c); at least 1 to
 * size the plan's tables. */
#define TGI_NEAR_STEPS_OF(r) ((r) >= 1) + ((r) >= 2) + ((r) >= 3) + ((r) >= 4) + ((r) >= 6) + ((r) >= 9) + \
    ((r) >= 13) + ((r) >= 19) + ((r) >= 28) + ((r) >= 42) + ((r) >= 63) + ((r) >= 94) + ((r) >= 141) + \
    ((r) >= 211) + ((r) >= 316) + ((r) >= 474)
#define TGI_NEAR_STEPS (TG_QUARTER_NEAR_REACH >= 1 ? (TGI_NEAR_STEPS_OF(TG_QUARTER_NEAR_REACH)) : 1)
#if TG_QUARTER_NEAR_REACH >= 141
#error "TG_QUARTER_NEAR_REACH: the near horizon's offsets are kept in a byte (at most 140, samples up to 94 pixels away)"
#endif

/* TGI_NEAR_DELTAS: the plan also keeps each sample's index offset
 * (dy row_stride + dx pixel_stride of the full view, in 16 bits) for the
 * march inside the image: 896 bytes more with the default reach, which
 * keeps the plan within the 4x4 filter's window it shares the stack with
 * (float 2080 bytes); a build for size (TG_OUTLINE_HELPERS) or a longer
 * reach computes the index at each sample instead. */
#ifndef TGI_NEAR_DELTAS
#define TGI_NEAR_DELTAS (!TG_OUTLINE_HELPERS && TGI_NEAR_STEPS <= 7)
#endif
/* TGI_NEAR_STEP_PAIRS: the index offsets kept beside the offsets (the
 * plan's step below), in Q16.16; the same bytes. */
#define TGI_NEAR_STEP_PAIRS (TGI_NEAR_DELTAS && TG_FIXED)

/* What the upsample of a frame keeps fixed: the views and the half-res
 * results, the camera's per-pixel ray steps, the radius's shift
 * (tgi_ao_unit_shift) and, scaled by it, its square, the height over a
 * tangent plane that a sample must pass besides the depth's (as a part of
 * the radius), and the near horizon's samples a side (0: none) as pixel
 * offsets (dx, dy), for each cell of a 4x4 block and each of its two
 * slices' two sides, with the farthest any of them lies on either axis
 * (896 bytes with the default reach: the plan shares the resolve's stack
 * with the 4x4 filter's window, src/frame/resolve.c). */
typedef struct tgi_upsample_plan {
    const tgi_gview *full, *half;
    const tgi_gresult *res;
    const tgi_gresult *near;   /* the full-res near horizons' AO (tgi_near_horizon_rows); NULL: taken on the spot */
    tg_real wfx, hfy, ax, ay, r2, above_r;
    int shift;
    short steps, reach;   /* (short: the plan within the window, TGI_NEAR_DELTAS) */
#if TGI_DEPTH_LAYERS
    int layers;           /* full has further depth layers: the near horizon takes only what is solid below it */
#endif
#if TGI_NEAR_STEP_PAIRS
    /* a sample's offsets beside its index offset: Q16.16's march reads
     * both through one base register, which keeps one more of its
     * tangent plane's values in a register (cornell 320x240 --gi-quarter 2
     * frames near_horizon_sides 146.15M -> 144.56M; float, whose loop
     * then steps a pointer more, 111.37M -> 113.73M, keeps them apart) */
    struct tgi_near_step { int16_t delta; signed char off[2]; } step[16][4][TGI_NEAR_STEPS];
#else
    signed char off[16][4][TGI_NEAR_STEPS][2];
#endif
#if TGI_Q16_WIDE
    int hk;               /* the near horizon's offsets in 64 bits within 2^hk (0: never), */
    int64_t kx_room, ky_room, p_room;   /* for pixels within these (resample.c) */
#endif
#if TGI_NEAR_DELTAS
    int deltas;           /* every offset's index offset fits (else no pixel takes the march's inside copy) */
#if !TGI_NEAR_STEP_PAIRS
    int16_t delta[16][4][TGI_NEAR_STEPS];
#endif
#endif
} tgi_upsample_plan;

/* The plan of upsampling half_res (indexed like the view half) to full with
 * gather radius `radius` (world units), reading the near horizons' AO from
 * near (full's size, written by tgi_near_horizon_rows; NULL: each pixel
 * takes its neighbours' on the spot, the same values). */
void tgi_upsample_start(tgi_upsample_plan *u, const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res,
                        tg_real radius, const tgi_gresult *near);

/* A half-res pixel as the upsample reads it (resample.c), and the last four
 * a walk along the full-res rows read (index (size_t)-1: none), and the
 * last full-res pixel's normal. */
typedef struct tgi_upsample_tap {
    size_t index;
    int sky;
    tg_real z, ao;
    tg_vec3 n, bend, near;
} tgi_upsample_tap;
typedef struct tgi_upsample_walk {
    tgi_upsample_tap tap[4];
    tgi_normal_memo normal;   /* the last full-res pixel's (raster/gview.h) */
} tgi_upsample_walk;
void tgi_upsample_walk_start(tgi_upsample_walk *w);

/* tgi_upsample_pixel under plan u, reusing what walk w (started with
 * tgi_upsample_walk_start, any pixel order) has decoded. */
tgi_gr_value tgi_upsample_at(const tgi_upsample_plan *u, tgi_upsample_walk *w, int x, int y);

/* A lower bound of the near horizon's AO (resample.c) at a pixel of view
 * normal nv and unit vector to the eye vd, with no angle taken: its slices
 * of screen directions (sdx, sdy) and (-sdy, sdx) (y down) see horizons of
 * cosines c1[k] along and c0[k] against their direction (-1: none), the
 * AO the cosine-weighted arcs (RTR eq. 11.18, the slices weighted as
 * GTAO's, src/ao/ao.h) leave.  In slice k (unit direction s in view space,
 * at right angles to vd) the normal projects to length len = |(n.s, n.v)|
 * at angle g from v, cos g = n.v / len, sin g = n.s / len.  With u = h - g,
 * the arc a horizon at angle t = acos c from v takes from its side, the
 * integral of |sin h| cos u over u from t - g to pi/2 (the inner integral),
 * is at most 1 - sin(t - g) (against the direction 1 - sin(t + g)); the
 * open arc cos g + g sin g is at least cos g + sin^2 g; so the AO,
 * 1 - sum len lost / sum len open, is at least
 * 1 - sum len (lost's bound) / sum len (open's bound).  -1 where that does
 * not hold: a normal facing away from the eye (n.v <= 0) or nearly at right
 * angles to a slice (len <= 0.01). */
tg_real tgi_near_horizon_bound(tg_vec3 nv, tg_vec3 vd, tg_real sdx, tg_real sdy, const tg_real c1[2],
                               const tg_real c0[2]);

/* The near horizon's test whether a sample at depth z, (ox, oy) pixels
 * from a pixel (|ox|, |oy| <= reach), lies on or under its tangent plane
 * (resample.c near_under_plane: z (nr + ox nax - oy nay) - np <= above),
 * with `fast` the Q16.16 compare of near_plane_start where it applies,
 * else the saturating expression: for tests/test_hbil.c, which has both
 * give the same answers. */
int tgi_near_under_plane(tg_real nr, tg_real nax, tg_real nay, tg_real np, tg_real above, int reach, tg_real z, int ox,
                         int oy, int fast);

/* The near horizon of every full-res pixel of rows [y0, y1): the AO under
 * its two slices' horizons within TG_QUARTER_NEAR_REACH full-res pixels
 * (resample.c near_horizon_ao; 1 where it cannot cap the upsampled AO)
 * into near's AO plane (full's size), which the upsample reads over each
 * pixel's 3x3 neighbourhood. */
void tgi_near_horizon_rows(const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res, tg_real radius,
                           const tgi_gresult *near, int y0, int y1);

/* The upsampled results at full-res pixel (x, y) from the half-res results
 * half_res (indexed like the view half), guided by both views' depth and
 * normals, the AO no more than the mean near horizon of the pixel and its
 * neighbours at its depth (3x3, within TG_QUARTER_NEAR_REACH full-res pixels,
 * gather radius `radius`, world units). */
tgi_gr_value tgi_upsample_pixel(const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res,
                                tg_real radius, int x, int y);

#endif
