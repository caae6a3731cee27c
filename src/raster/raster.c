/* SPDX-License-Identifier: MIT */
/*
 * raster.c - the triangle rasterizer behind the G-buffer and the shadow maps.
 *
 * Per triangle:
 *   1. world -> clip.  G-buffer: clip = (x fx, y fy, z, w = z) in view space
 *      (view.h), each vertex classified and snapped (3.) once and kept in a
 *      small cache keyed by its position's bits, since neighbouring
 *      triangles share vertices.  Depth-only: clip = world_to_clip * p.
 *   2. a triangle wholly outside one screen/near/far plane is dropped; one
 *      with a vertex outside the near/far planes or the guard band
 *      (|x|, |y| <= GUARD w) is clipped in homogeneous space
 *      (Sutherland-Hodgman, near/far first, each cut edge interpolated from
 *      its inside end so neighbours agree), so nothing behind the camera is
 *      ever projected and screen coordinates stay bounded.  Most triangles
 *      take the fast path and skip this.
 *   3. snap to 28.4 fixed point (4 sub-pixel bits), identical integers in
 *      both number types; the signed area decides facing (culling) and
 *      skips zero-area triangles.  Normals are read only after culling.
 *   4. bounding box (clamped to the image, then to rows [y0, y1)), exact
 *      64-bit integer edge functions with the top-left fill rule; each row's
 *      covered run is found by stepping them, so the pixel loop has no
 *      coverage test.
 *   5. per covered pixel: perspective-correct 1/w (depth = 1 / interpolated
 *      1/w) and normal (n/w interpolated), depth test on linear depth
 *      (nearest wins); where it passes, depth, packed normal with the
 *      material index, and object are written.
 *
 * Interpolation differs by number type only where the representation
 * forces it: float steps attribute planes per pixel; Q16.16 weights
 * per-vertex values by the exact integer edge functions (normalized to sum
 * ~2^30), with 1/w held in Q30 relative to the triangle's nearest vertex:
 * depth costs one division per pixel and its relative error stays below
 * ~2^-30 w / w_min (2e-5 for one triangle spanning near 0.05 to far 1000).
 */
#include <stddef.h>
#include <string.h>
#include "raster.h"
#include "gview.h"
#include "../core/real.h"

#define SUB 16                    /* sub-pixels per pixel (28.4) */
#ifndef SPAN_WALK_MAX
#define SPAN_WALK_MAX 4           /* span_row walks boxes this wide or narrower (SPAN_DIVIDE) */
#endif
#define HALF_SUB 8                /* pixel centre offset */
#define GUARD 8                   /* guard band, in NDC units */
#define COORD_LIMIT (1 << 20)     /* |28.4 coordinate| bound: GUARD + 1 half screens of
                                     TG_MAX_IMAGE_SIDE pixels, 16 sub-pixels each, fit */
#define DIV_OFFSET (1 << 22)      /* a multiple of 16 above COORD_LIMIT for floor division */
#define MAX_POLY 12               /* 3 vertices + one per clip plane, with room */
/* The depth-only raster (tgi_raster_depth, tgi_raster_depth16) is for shadow
 * maps alone: left out with them (tinygi.h "FEATURE SWITCHES"). */
#define TGI_RASTER_DEPTH (!TG_NO_SHADOW_MAPS && !TG_NO_COLOR)
/* The G-buffer's second depth layer (tgi_gbuffer.back_depth) is read by
 * the visibility bitmask alone: left out with the techniques. */
#define TGI_RASTER_BACK_LAYER TGI_DEPTH_LAYERS
/* Depth-only rows serve both. */
#define TGI_RASTER_DEPTH_ROWS (TGI_RASTER_DEPTH || TGI_RASTER_BACK_LAYER)

#if (GUARD + 1) * (TG_MAX_IMAGE_SIDE / 2) * SUB > COORD_LIMIT || TG_MAX_SHADOW_MAP > TG_MAX_IMAGE_SIDE
#error "TG_MAX_IMAGE_SIDE or TG_MAX_SHADOW_MAP is beyond the rasterizer's 28.4 coordinates"
#endif

/* A helper gcc would otherwise call from its two callers' loops. */
#if defined(__GNUC__)
#define RASTER_INLINE inline __attribute__((always_inline))
#define RASTER_NOINLINE __attribute__((noinline))
#else
#define RASTER_INLINE inline
#define RASTER_NOINLINE
#endif

/* span_row's runs by division (a 64-bit core divides 64-bit integers in
 * one instruction) in boxes wider than SPAN_WALK_MAX, always inline
 * (gcc would call it).  Float only: in Q16.16 gcc then inlines less of
 * the pixel walk and the vertex set-up around it (callgrind bench_raster
 * 320x240 39.98M -> 41.0M; 1280x720 109.0M -> 107.4M, or 115.0M with
 * pixel_walk_row always inline too). */
#define SPAN_DIVIDE (UINTPTR_MAX > 0xFFFFFFFFu && !TG_OUTLINE_HELPERS && !TG_FIXED)
/* Q16.16 (64-bit, outside size builds), where span_row walks every row:
 * the run's end by division (SPAN_RUN_DIVIDE, at span_row's walk).  It
 * measured callgrind bench_raster-fixed 1280x720 84.23M -> 81.65M a frame
 * but 320x240 32.70M -> 32.93M (runs of a pixel or two walk cheaper;
 * dividing only in boxes wider than 3, 5 or 8 pixels: 33.00M / 81.95M,
 * 33.11M / 82.03M, 33.11M / 82.49M; walking two pixels first 32.94M /
 * 82.37M). */
#ifndef SPAN_RUN_DIVIDE
#define SPAN_RUN_DIVIDE (UINTPTR_MAX > 0xFFFFFFFFu && !TG_OUTLINE_HELPERS && TG_FIXED)
#endif
#ifndef SPAN_LEFT_WALK_MAX
#define SPAN_LEFT_WALK_MAX 16     /* SPAN_RUN_DIVIDE's start by division in boxes wider */
#endif
#if SPAN_DIVIDE
#define SPAN_INLINE RASTER_INLINE
#else
#define SPAN_INLINE inline
#endif

/* ---------------------------------------------------------------------- */
/* small integer helpers                                                   */

/* floor(v / 16) and ceil(v / 16) for |v| < DIV_OFFSET, no negative shifts. */
static int floor_div_sub(int64_t v) { return (int)((v + DIV_OFFSET) >> 4) - (DIV_OFFSET >> 4); }
static int ceil_div_sub(int64_t v) { return floor_div_sub(v + SUB - 1); }

static int32_t clamp_coord(int64_t v)
{
    return (int32_t)(v > COORD_LIMIT ? COORD_LIMIT : v < -COORD_LIMIT ? -COORD_LIMIT : v);
}

/* ---------------------------------------------------------------------- */
/* edge functions and the fill rule                                        */

typedef struct tri_edges {
    int x0, x1, y0, y1;           /* pixel box [x0, x1) x [y0, y1) to draw */
    int oy;                       /* origin row: the box top clamped to the image only, so
                                     results do not depend on the row range */
    int64_t e[3];                 /* biased edge functions at the centre of pixel (x0, oy) */
    int64_t step_x[3], step_y[3]; /* change per pixel right / down */
    int64_t bias[3];              /* 0 on top-left edges, -1 elsewhere */
    int64_t area2;                /* twice the area, > 0, in sub-pixels^2 */
    int32_t cx, cy;               /* sub-pixel position of that pixel centre */
} tri_edges;

/* Edge i from a to b: E(p) = dx (p.y - a.y) - dy (p.x - a.x), >= 0 inside;
 * top-left: dy < 0 (a left edge) or dy == 0 and dx > 0 (a top edge). */
static inline void edge_setup(tri_edges *t, int i, int32_t ax, int32_t ay, int32_t bx, int32_t by)
{
    int32_t dx = bx - ax, dy = by - ay;           /* |d| < 2^21 */
    t->bias[i] = (dy < 0 || (dy == 0 && dx > 0)) ? 0 : -1;
    t->e[i] = (int64_t)dx * (t->cy - ay) - (int64_t)dy * (t->cx - ax) + t->bias[i];
    t->step_x[i] = -(int64_t)dy * SUB;
    t->step_y[i] = (int64_t)dx * SUB;
}

/* Set up the three edge functions of a triangle with area2 > 0 in 28.4
 * screen space (y down).  Edge i is opposite vertex i; E_i(p) >= 0 inside.
 * Returns 0 when the box holds no pixel centre.  Always inline outside
 * size builds (gcc called it from draw_snapped, the edges through memory:
 * callgrind bench_raster-fixed 320x240 33.14M -> 32.70M a frame, 1280x720
 * 84.81M -> 84.23M; bench_raster 26.13M -> 25.56M, 59.11M -> 59.01M). */
#if !TG_OUTLINE_HELPERS
#define EDGES_INLINE RASTER_INLINE
#else
#define EDGES_INLINE inline
#endif
static EDGES_INLINE int edges_setup(tri_edges *t, const int32_t *x, const int32_t *y, int64_t area2,
                       int width, int row0, int row1)
{
    int32_t minx = x[0], maxx = x[0], miny = y[0], maxy = y[0];
    if (x[1] < minx) minx = x[1];
    if (x[1] > maxx) maxx = x[1];
    if (x[2] < minx) minx = x[2];
    if (x[2] > maxx) maxx = x[2];
    if (y[1] < miny) miny = y[1];
    if (y[1] > maxy) maxy = y[1];
    if (y[2] < miny) miny = y[2];
    if (y[2] > maxy) maxy = y[2];
    /* pixel centres px*16+8 within [min, max] */
    t->x0 = ceil_div_sub((int64_t)minx - HALF_SUB);
    t->x1 = floor_div_sub((int64_t)maxx - HALF_SUB) + 1;
    t->y0 = ceil_div_sub((int64_t)miny - HALF_SUB);
    t->y1 = floor_div_sub((int64_t)maxy - HALF_SUB) + 1;
    if (t->x0 < 0) t->x0 = 0;
    if (t->x1 > width) t->x1 = width;
    if (t->y0 < 0) t->y0 = 0;
    t->oy = t->y0;
    if (t->y0 < row0) t->y0 = row0;
    if (t->y1 > row1) t->y1 = row1;
    if (t->x0 >= t->x1 || t->y0 >= t->y1) return 0;
    t->area2 = area2;
    t->cx = t->x0 * SUB + HALF_SUB;
    t->cy = t->oy * SUB + HALF_SUB;
    edge_setup(t, 0, x[1], y[1], x[2], y[2]);
    edge_setup(t, 1, x[2], y[2], x[0], y[0]);
    edge_setup(t, 2, x[0], y[0], x[1], y[1]);
    return 1;
}

static inline int64_t signed_area2(const int32_t *x, const int32_t *y)
{
    return ((int64_t)x[1] - x[0]) * ((int64_t)y[2] - y[0]) - ((int64_t)y[1] - y[0]) * ((int64_t)x[2] - x[0]);
}

/* The covered pixels of a row form one run (the triangle is convex): the
 * row's pixels are tested from the box's left side, all edges at once, and
 * the edge values step down a row at a time.  (Walking each edge's
 * boundary from the row above instead executes fewer instructions on wide
 * rows, but its many short loops mispredict more: measured slower.) */
typedef struct span_walk {
    int64_t e[3];                 /* E_i at the centre of pixel (x0, row) */
} span_walk;

/* Start at row te->y0. */
static inline void span_begin(span_walk *sw, const tri_edges *te)
{
    int64_t dy = te->y0 - te->oy;
#if TG_FIXED && !TG_OUTLINE_HELPERS
    /* dy = 0 unless the rows [row0, row1) cut the box's top (a thread
     * drawing the rows below another's): no products then.  Q16.16 only (callgrind
     * bench_raster-fixed bench_draw a frame: 1280x720 76.84M -> 76.69M,
     * 320x240 31.06M -> 30.99M; float 48.27M -> 48.94M, 21.36M -> 21.41M) */
    if (dy == 0) {
        sw->e[0] = te->e[0]; sw->e[1] = te->e[1]; sw->e[2] = te->e[2];
        return;
    }
#endif
    sw->e[0] = te->e[0] + dy * te->step_y[0];
    sw->e[1] = te->e[1] + dy * te->step_y[1];
    sw->e[2] = te->e[2] + dy * te->step_y[2];
}

#if SPAN_DIVIDE
/* span_row's bound of one edge e + j st >= 0 on the run [lo, hi] (lo >=
 * 0 and hi < n on entry).  A division only where it can move a bound: for
 * st > 0 and e >= 0 ceil(-e / st) <= 0 <= lo; for st < 0 and e < 0
 * floor(e / -st) <= -1, the row empty, as hi = -1 says (span_row then
 * sets hi = lo - 1 either way).  (Each division had been made:
 * callgrind bench_raster 320x240 24.26M -> 24.20M a frame, 1280x720
 * 55.78M -> 55.57M.) */
static RASTER_INLINE void span_bound(int64_t e, int64_t st, int64_t *lo, int64_t *hi)
{
    if (st > 0) {
        if (e < 0) {
            const int64_t j = (st - 1 - e) / st;   /* ceil(-e / st) */
            if (j > *lo) *lo = j;
        }
    } else if (e < 0) {
        *hi = -1;
    } else if (st < 0) {
        const int64_t j = e / -st;   /* floor(e / -st), e >= 0 */
        if (j < *hi) *hi = j;
    }
}
#endif

#if SPAN_RUN_DIVIDE
/* span_row's start of a run in a box n > SPAN_LEFT_WALK_MAX pixels wide
 * (a shadow map's walls) by one division an edge, not a walk: the run
 * starts at x0 + j, or is empty for j < 0.  Pixel x0 + j is inside edge i
 * when e_i + j s_i >= 0: an edge outside at x0 with s_i > 0 holds from j =
 * ceil(-e_i / s_i) on (C's quotient of positives), one with s_i <= 0
 * never does, and the row is empty; so is it when j is past the box, or
 * an edge is outside at j (one with s_i < 0: it only falls to the right).
 * The walk stops at the same pixel, or at x1 with nothing covered (its
 * e_i there are then not used).  Out of line: rare in meshes of small
 * triangles, and span_row stays small enough to be inlined. */
static RASTER_NOINLINE int64_t span_start(int64_t e0, int64_t e1, int64_t e2, int64_t s0, int64_t s1, int64_t s2,
                                          int64_t n)
{
    int64_t j = 0;
    if (e0 < 0) { if (s0 <= 0) return -1; j = (s0 - 1 - e0) / s0; }
    if (e1 < 0) { if (s1 <= 0) return -1; if ((s1 - 1 - e1) / s1 > j) j = (s1 - 1 - e1) / s1; }
    if (e2 < 0) { if (s2 <= 0) return -1; if ((s2 - 1 - e2) / s2 > j) j = (s2 - 1 - e2) / s2; }
    if (j >= n || ((e0 + j * s0) | (e1 + j * s1) | (e2 + j * s2)) < 0) return -1;
    return j;
}
#endif

/* The run [*xa, returned end) of this row (empty when end <= *xa); moves
 * on to the next row.  With ea, E_i at the centre of pixel (*xa, row) too
 * (the walk's values there: no products to find them again). */
static SPAN_INLINE int span_row(const tri_edges *te, span_walk *sw, int *xa, int64_t *ea, int wide)
{
#if SPAN_DIVIDE
    /* On a 64-bit core, in a wide box, each edge's bound by one division
     * instead of a walk: pixel x0 + j is inside edge i when e_i + j s_i >=
     * 0, i.e. j >= ceil(-e_i / s_i) for s_i > 0, j <= floor(e_i / -s_i) for
     * s_i < 0, and always or never for s_i = 0; the run is the
     * intersection with [0, n) (what the walk finds: the first j inside
     * all three, then the last). */
    const int64_t n = te->x1 - te->x0;
    int64_t lo = 0, hi = n - 1;
    if (n <= SPAN_WALK_MAX) goto walk;
    /* the three edges written out: gcc had kept the loop over them (its
     * counter, its loads through te and sw): callgrind bench_raster
     * 1280x720 61.09M -> 59.13M a frame, 320x240 26.135M -> 26.20M, or with
     * walks to 3 pixels 59.11M, 26.13M; with edges_setup inline too, walks
     * to 2, 3, 4, 5, 6 pixels: 59.05M / 25.68M, 59.01M / 25.56M, 59.00M /
     * 25.53M, 59.03M / 25.55M, 59.17M / 25.55M */
    span_bound(sw->e[0], te->step_x[0], &lo, &hi);
    span_bound(sw->e[1], te->step_x[1], &lo, &hi);
    span_bound(sw->e[2], te->step_x[2], &lo, &hi);
    if (lo > n) lo = n;
    if (hi < lo) hi = lo - 1;
    *xa = te->x0 + (int)lo;
    if (ea) {
        ea[0] = sw->e[0] + lo * te->step_x[0];
        ea[1] = sw->e[1] + lo * te->step_x[1];
        ea[2] = sw->e[2] + lo * te->step_x[2];
    }
    sw->e[0] += te->step_y[0];
    sw->e[1] += te->step_y[1];
    sw->e[2] += te->step_y[2];
    return te->x0 + (int)hi + 1;
walk:
#endif
    {
    int64_t e0 = sw->e[0], e1 = sw->e[1], e2 = sw->e[2];
    const int64_t s0 = te->step_x[0], s1 = te->step_x[1], s2 = te->step_x[2];
    int x = te->x0, x1 = te->x1;
    (void)wide;
#if SPAN_RUN_DIVIDE
    if (wide && x1 - x > SPAN_LEFT_WALK_MAX && (e0 | e1 | e2) < 0) {
        const int64_t j = span_start(e0, e1, e2, s0, s1, s2, x1 - x);
        if (j < 0) {
            x = x1;
        } else {
            e0 += j * s0; e1 += j * s1; e2 += j * s2;
            x += (int)j;
        }
        goto found;
    }
#endif
    while (x < x1 && (e0 | e1 | e2) < 0) { e0 += s0; e1 += s1; e2 += s2; x++; }
#if SPAN_RUN_DIVIDE
found:
#endif
    *xa = x;
    if (ea) { ea[0] = e0; ea[1] = e1; ea[2] = e2; }
#if SPAN_RUN_DIVIDE
    /* The run's end by one division an edge instead of the walk through
     * it: at x < x1 every e_i >= 0 (the walk above stopped there); an edge
     * with s_i >= 0 stays so to the right, one with s_i < 0 holds x + j for
     * j <= floor(e_i / -s_i) (e_i >= 0: C's quotient), so the walk would
     * have stopped at x + 1 + min(x1 - 1 - x, those). */
    if (x < x1) {
        int64_t hi = x1 - 1 - x;
        if (s0 < 0 && e0 / -s0 < hi) hi = e0 / -s0;
        if (s1 < 0 && e1 / -s1 < hi) hi = e1 / -s1;
        if (s2 < 0 && e2 / -s2 < hi) hi = e2 / -s2;
        x += (int)hi + 1;
    }
#else
    while (x < x1 && (e0 | e1 | e2) >= 0) { e0 += s0; e1 += s1; e2 += s2; x++; }
#endif
    sw->e[0] += te->step_y[0];
    sw->e[1] += te->step_y[1];
    sw->e[2] += te->step_y[2];
    return x;
    }
}

void tgi_raster_coverage_count(uint16_t *count, int width, int height,
                              const int32_t *xy, int tri_count, int y0, int y1)
{
    int t;
    if (y0 < 0) y0 = 0;
    if (y1 > height) y1 = height;
    for (t = 0; t < tri_count; t++) {
        int32_t x[3], y[3];
        int64_t area2;
        tri_edges te;
        span_walk sw;
        int row, col, k;
        for (k = 0; k < 3; k++) {
            x[k] = clamp_coord(xy[t * 6 + 2 * k]);
            y[k] = clamp_coord(xy[t * 6 + 2 * k + 1]);
        }
        area2 = signed_area2(x, y);
        if (area2 == 0) continue;
        if (area2 < 0) {
            int32_t s = x[1]; x[1] = x[2]; x[2] = s;
            s = y[1]; y[1] = y[2]; y[2] = s;
            area2 = -area2;
        }
        if (!edges_setup(&te, x, y, area2, width, y0, y1)) continue;
        span_begin(&sw, &te);
        for (row = te.y0; row < te.y1; row++) {
            int xa, xb = span_row(&te, &sw, &xa, NULL, 0);
            uint16_t *line = count + (size_t)row * (size_t)width;
            for (col = xa; col < xb; col++) line[col]++;
        }
    }
}

/* ---------------------------------------------------------------------- */
/* clipping in homogeneous space                                           */

typedef struct clip_vertex {
    tg_real x, y, z, w;
    tg_vec3 n;                    /* world normal (G-buffer mode) */
} clip_vertex;

enum { MODE_GBUFFER, MODE_PERSPECTIVE, MODE_ORTHO };
enum { PL_LEFT, PL_RIGHT, PL_BOTTOM, PL_TOP, PL_NEAR, PL_FAR, PL_COUNT };

typedef struct clip_ctx {
    int mode;
    tg_real znear, zfar;          /* G-buffer mode; perspective depth mode: znear the clip's w */
} clip_ctx;

#define GUARD_R TG_R(8.0f)

/* Signed distance of v to plane p (>= 0 inside). */
static inline tg_real plane_distance(const clip_ctx *c, const clip_vertex *v, int p)
{
    switch (p) {
    case PL_LEFT: return tg_add(v->x, tg_mul(GUARD_R, v->w));
    case PL_RIGHT: return tg_sub(tg_mul(GUARD_R, v->w), v->x);
    case PL_BOTTOM: return tg_add(v->y, tg_mul(GUARD_R, v->w));
    case PL_TOP: return tg_sub(tg_mul(GUARD_R, v->w), v->y);
    case PL_NEAR:
        if (c->mode == MODE_GBUFFER) return tg_sub(v->w, c->znear);
        if (c->mode == MODE_PERSPECTIVE) return tg_sub(v->w, c->znear);
        return v->z;
    default:
        if (c->mode == MODE_GBUFFER) return tg_sub(c->zfar, v->w);
        if (c->mode == MODE_PERSPECTIVE) return tg_sub(v->w, v->z);
        return TG_ONE;
    }
}

/* Put a new vertex exactly on plane p (the lerp rounds). */
static void snap_to_plane(const clip_ctx *c, clip_vertex *v, int p)
{
    switch (p) {
    case PL_LEFT: v->x = tg_neg(tg_mul(GUARD_R, v->w)); break;
    case PL_RIGHT: v->x = tg_mul(GUARD_R, v->w); break;
    case PL_BOTTOM: v->y = tg_neg(tg_mul(GUARD_R, v->w)); break;
    case PL_TOP: v->y = tg_mul(GUARD_R, v->w); break;
    case PL_NEAR:
        if (c->mode == MODE_GBUFFER) v->z = v->w = c->znear;
        else if (c->mode == MODE_PERSPECTIVE) v->w = c->znear;
        else v->z = 0;
        break;
    default:
        if (c->mode == MODE_GBUFFER) v->z = v->w = c->zfar;
        else if (c->mode == MODE_PERSPECTIVE) v->z = v->w;
        break;
    }
}

static clip_vertex clip_lerp(const clip_vertex *a, const clip_vertex *b, tg_real t)
{
    clip_vertex r;
    r.x = tg_lerp(a->x, b->x, t);
    r.y = tg_lerp(a->y, b->y, t);
    r.z = tg_lerp(a->z, b->z, t);
    r.w = tg_lerp(a->w, b->w, t);
    r.n = tgi_v3_lerp(a->n, b->n, t);
    return r;
}

/* Outcode bits: 0..5 outside the guard band / near / far planes (clip
 * needed); 8..13 outside the screen planes |x|, |y| <= w, near, far. */
#define OUT_GUARD_MASK 0x3Fu
#define OUT_SCREEN_SHIFT 8
static inline unsigned outcode(const clip_ctx *c, const clip_vertex *v)
{
    unsigned code = 0;
    tg_real gw = tg_mul(GUARD_R, v->w), nw = tg_neg(v->w), ngw = tg_neg(gw);
    if (v->x < ngw) code |= 1u << PL_LEFT;
    if (v->x > gw) code |= 1u << PL_RIGHT;
    if (v->y < ngw) code |= 1u << PL_BOTTOM;
    if (v->y > gw) code |= 1u << PL_TOP;
    if (plane_distance(c, v, PL_NEAR) < 0) code |= 1u << PL_NEAR;
    if (plane_distance(c, v, PL_FAR) < 0) code |= 1u << PL_FAR;
    if (v->x < nw) code |= 1u << (OUT_SCREEN_SHIFT + PL_LEFT);
    if (v->x > v->w) code |= 1u << (OUT_SCREEN_SHIFT + PL_RIGHT);
    if (v->y < nw) code |= 1u << (OUT_SCREEN_SHIFT + PL_BOTTOM);
    if (v->y > v->w) code |= 1u << (OUT_SCREEN_SHIFT + PL_TOP);
    code |= (code & ((1u << PL_NEAR) | (1u << PL_FAR))) << OUT_SCREEN_SHIFT;
    return code;
}

/* Sutherland-Hodgman against the planes in `planes`; returns the vertex
 * count of the clipped convex polygon (0 when nothing is left). */
static int clip_polygon(const clip_ctx *c, clip_vertex *poly, int n, unsigned planes)
{
    /* near and far first: the guard-band planes then cut vertices whose w
     * is already in range, and set x, y exactly on the band */
    static const int order[PL_COUNT] = { PL_NEAR, PL_FAR, PL_LEFT, PL_RIGHT, PL_BOTTOM, PL_TOP };
    clip_vertex tmp[MAX_POLY];
    int o;
    for (o = 0; o < PL_COUNT && n > 0; o++) {
        int i, m = 0, p = order[o];
        if (!(planes & (1u << p))) continue;
        for (i = 0; i < n; i++) {
            const clip_vertex *a = &poly[i], *b = &poly[i + 1 == n ? 0 : i + 1];
            tg_real da = plane_distance(c, a, p), db = plane_distance(c, b, p);
            if (da >= 0) tmp[m++] = *a;
            if ((da >= 0) != (db >= 0) && m < MAX_POLY) {
                /* from the inside vertex to the outside one, whatever the edge's
                 * direction, so triangles sharing the edge get the same point */
                const clip_vertex *in = da >= 0 ? a : b, *out = da >= 0 ? b : a;
                tg_real din = da >= 0 ? da : db, dout = da >= 0 ? db : da;
                tg_real t = tg_clamp(tg_div(din, tg_sub(din, dout)), 0, TG_ONE);
                tmp[m] = clip_lerp(in, out, t);
                snap_to_plane(c, &tmp[m], p);
                m++;
            }
        }
        n = m;
        memcpy(poly, tmp, (size_t)n * sizeof *poly);
    }
    return n;
}

/* ---------------------------------------------------------------------- */
/* snapping to 28.4                                                        */

/* 1/w, computed once per vertex and shared by snapping and interpolation. */
#if TG_FIXED
typedef int64_t inv_w;            /* 2^46 / w (raw Q16.16 w) */
static inline inv_w inverse_w(tg_real w) { return w > 0 ? ((int64_t)1 << 46) / w : 0; }

/* round(c / w * half16): NDC coordinate to sub-pixels from the image
 * centre.  |c| <= (GUARD + 1) w, so c * iw < 2^50. */
static inline int32_t snap_ndc(tg_real c, tg_real w, inv_w iw, int32_t half16)
{
    int64_t lim = (int64_t)(GUARD + 1) * w, ndc, v;
    if (c > lim) c = (tg_real)lim;               /* rounding in clipping: stay in the band */
    if (c < -lim) c = (tg_real)-lim;
    ndc = (int64_t)c * iw;                       /* NDC * 2^46 */
    ndc = ndc >= 0 ? ndc >> 20 : -((-ndc) >> 20);  /* NDC * 2^26 */
    v = ndc * half16;
    return clamp_coord(v >= 0 ? (v + (1 << 25)) >> 26 : -((-v + (1 << 25)) >> 26));
}
#else
typedef float inv_w;
static inline inv_w inverse_w(tg_real w) { return w > 0.0f ? 1.0f / w : 0.0f; }

static inline int32_t snap_ndc(tg_real c, tg_real w, inv_w iw, int32_t half16)
{
    float v = c * iw * (float)half16;
    (void)w;
    if (!(v <= (float)COORD_LIMIT)) v = (float)COORD_LIMIT;   /* also NaN */
    if (v < -(float)COORD_LIMIT) v = -(float)COORD_LIMIT;
    return (int32_t)(v >= 0.0f ? v + 0.5f : v - 0.5f);
}
#endif

/* ---------------------------------------------------------------------- */
/* per-pixel normalization                                                 */

#if TG_FIXED
static int64_t asr64(int64_t v, int s) { return v >= 0 ? v >> s : -((-v) >> s); }
#if !TG_WIDE_STORAGE && !TG_OUTLINE_HELPERS
/* |v| as unsigned (INT64_MIN too: 2^63), for gbuffer_rows' row loop: by
 * the sign's mask s (all ones for v < 0), (v ^ s) - s = ~v + 1 = -v modulo
 * 2^64, else v.  (As v < 0 ? -v : v, gcc stepped each sum's negation as
 * an induction variable of its own beside the sum, and spilled; callgrind
 * bench_raster-fixed 1280x720 86.07M -> 85.84M a frame.) */
static inline uint64_t mag64(int64_t v)
{
    const uint64_t s = 0u - ((uint64_t)v >> 63);
    return ((uint64_t)v ^ s) - s;
}
#endif

#if TG_WIDE_STORAGE

/* Unit vector (Q16.16) along m (|m_i| < 2^31): 1/sqrt by
 * tgi_rsqrt_q30_fast (rel. error 3e-6, below the Q16.16 ulp).  Returns 0
 * for the zero vector. */
static int unit_q16(int64_t mx, int64_t my, int64_t mz, tg_real *n)
{
    uint64_t len2 = (uint64_t)(mx * mx) + (uint64_t)(my * my) + (uint64_t)(mz * mz);
    uint64_t x30, y;
    int b = tgi_bit_length64(len2), shift;
    if (b == 0) return 0;
    if (b >= 31) {
        int k = (b - 31) >> 1;
        x30 = len2 >> (2 * k);
        shift = 29 + k;
    } else {
        int k = (32 - b) >> 1;
        x30 = len2 << (2 * k);
        shift = 29 - k;
    }
    /* x30 in [2^30, 2^32): X = x30 / 2^30 in [1, 4) */
    y = tgi_rsqrt_q30_fast(x30);
    n[0] = (tg_real)asr64(mx * (int64_t)y, shift);
    n[1] = (tg_real)asr64(my * (int64_t)y, shift);
    n[2] = (tg_real)asr64(mz * (int64_t)y, shift);
    return 1;
}
#endif
#endif

/* ---------------------------------------------------------------------- */
/* the G-buffer                                                            */

/* Only the depth is cleared (0: sky): every other channel of a pixel is
 * read only where the depth says a surface was drawn, and is written with it. */
void tgi_gbuffer_clear_rows(tgi_gbuffer *gb, int y0, int y1)
{
    size_t a, n;
    if (y0 < 0) y0 = 0;
    if (y1 > gb->height) y1 = gb->height;
    if (y0 >= y1) return;
    a = (size_t)y0 * (size_t)gb->width;
    n = (size_t)(y1 - y0) * (size_t)gb->width;
    memset(gb->depth + a, 0, n * sizeof *gb->depth);
    if (gb->object) memset(gb->object + a, 0xFF, n * sizeof(uint16_t));
#if TGI_RASTER_BACK_LAYER
    if (gb->back_depth) memset(gb->back_depth + a, 0, n * sizeof *gb->back_depth);
    if (gb->behind_depth) memset(gb->behind_depth + a, 0, n * sizeof *gb->behind_depth);
#endif
}

/* What every pixel of one triangle shares. */
typedef struct surface {
    uint32_t material;            /* compact: index << TGI_MATERIAL_SHIFT; wide: index */
    uint16_t object;
    tg_vec3 fallback_normal;      /* if the interpolated normal vanishes */
    int normal_bits;              /* compact: per octahedral coordinate (nm, or n8) */
} surface;

#if !TG_WIDE_STORAGE
/* Pixel i's packed normal and material: the nm word, or n8 without a
 * material; `bits` is the surface's normal_bits, TGI_NORMAL_BITS exactly
 * when the G-buffer has nm (draw_snapped): a constant in float's
 * gbuffer_rows. */
static void put_nm(const tgi_gbuffer *g, size_t i, uint32_t w, int bits)
{
#if TG_FIXED || TG_OUTLINE_HELPERS
    (void)bits;
    if (g->nm) g->nm[i] = w;
#else
    if (bits == TGI_NORMAL_BITS) g->nm[i] = w;
#endif
    else g->n8[i] = (uint16_t)w;
}
#endif

/* Depth-only output: 32-bit depths (tg_real), or 16-bit codes of the depth
 * range [lo, lo + range): q = round((depth - lo) 65536 / range), clamped to
 * [0, TG_RASTER_DEPTH16_EMPTY - 1]; or the G-buffer's back-face layer in
 * its depth's format (0: none); the nearest is kept. */
typedef struct depth_out {
    tg_real *d32;
    uint16_t *d16;
#if TGI_RASTER_BACK_LAYER && TG_WIDE_STORAGE
    tg_real *back, *behind;
    const tg_real *front;         /* the G-buffer's depth, final before the back faces are drawn */
#elif TGI_RASTER_BACK_LAYER
    uint8_t *back;                /* codes against front[i] (tgi_back_code) */
    uint32_t *behind;             /* kept only beyond back[i]'s code (the third layer) */
    const uint32_t *front;        /* the G-buffer's depth, final before the back faces are drawn */
#endif
    tg_real lo;
#if TG_FIXED
    int64_t range, recip;         /* raw Q16.16 range (>= 1); 2^48 / range */
#else
    float scale;                  /* 65536 / range */
#endif
} depth_out;
#if TGI_RASTER_BACK_LAYER
#define KEEPS_BACK(o) ((o)->back != NULL)
#else
#define KEEPS_BACK(o) 0
#endif

#if TGI_RASTER_DEPTH_ROWS   /* depth_rows' (neither kept with every switch set) */
static inline uint16_t depth_code(const depth_out *o, tg_real z)
{
#if TG_FIXED
    int64_t dz = (int64_t)z - o->lo, q;
    if (dz <= 0) return 0;
    if (dz > o->range) dz = o->range;
    q = (dz * o->recip + ((int64_t)1 << 31)) >> 32;   /* dz * recip <= 2^48 */
#else
    float f = (z - o->lo) * o->scale + 0.5f;
    int32_t q;
    if (!(f > 0.0f)) return 0;                        /* also NaN */
    if (f >= (float)TG_RASTER_DEPTH16_EMPTY) return TG_RASTER_DEPTH16_EMPTY - 1;
    q = (int32_t)f;
#endif
    return (uint16_t)(q < TG_RASTER_DEPTH16_EMPTY ? q : TG_RASTER_DEPTH16_EMPTY - 1);
}

/* Keep depth z (> 0 in the back layer) at texel i when nearer than what is there.
 * Always inline in Q16.16 outside size builds (callgrind build/tinygi-fixed
 * render builtin:cornell --size 160x120 --frames 2 673.93M -> 673.77M;
 * bench_raster-fixed bench_draw 32.55M -> 32.52M, 81.56M -> 81.15M a
 * frame); not in float (bench_raster 24.26M -> 24.54M, 55.78M -> 56.50M). */
#if TG_FIXED && !TG_OUTLINE_HELPERS
#define DEPTH_KEEP_INLINE RASTER_INLINE
#else
#define DEPTH_KEEP_INLINE inline
#endif
static DEPTH_KEEP_INLINE void depth_keep(const depth_out *o, size_t i, tg_real z)
{
    if (o->d16) {
        uint16_t q = depth_code(o, z);
        if (q < o->d16[i]) o->d16[i] = q;
#if TGI_RASTER_BACK_LAYER
    } else if (o->behind) {
#if TG_WIDE_STORAGE
        if (o->back[i] > 0 && z > o->back[i] && (!(o->behind[i] > 0) || z < o->behind[i])) o->behind[i] = z;
#else
        /* beyond the back face's code (not the back face itself, drawn again here) */
        uint32_t zb = tgi_depth_pack(z);   /* binary32 words order like the depths */
        if (o->back[i] && tgi_back_code(tgi_depth_unpack(o->front[i]), z) > o->back[i] &&
            (!o->behind[i] || zb < o->behind[i]))
            o->behind[i] = zb;
#endif
    } else if (o->back) {   /* the nearest back face at or behind the surface */
#if TG_WIDE_STORAGE
        if (o->front[i] > 0 && z >= o->front[i] && (!(o->back[i] > 0) || z < o->back[i])) o->back[i] = z;
#else
        uint8_t c = tgi_back_code(tgi_depth_unpack(o->front[i]), z);
        if (c != TGI_BACK_NONE && (o->back[i] == TGI_BACK_NONE || c < o->back[i])) o->back[i] = c;
#endif
#endif
    } else if (z < o->d32[i]) {
        o->d32[i] = z;
    }
}
#endif

/* One triangle ready to draw: screen vertices ordered so area2 > 0. */
typedef struct screen_tri {
    int32_t x[3], y[3];
    tg_real w[3], z[3];
    inv_w iw[3];
    tg_vec3 n[3];
} screen_tri;

#if TG_FIXED

/* Exact barycentrics: u_i = unbiased edge function scaled so their sum is
 * ~2^30.  Perspective-correct depth in one division:
 *   w = sum(u_i) / sum(u_i / w_i) = w_min sum(u_i) / sum(u_i q_i),  q_i = w_min / w_i. */
typedef struct bary_setup {
    int ls, rs, sm;               /* weight shifts left / right; normal shift */
    int64_t wmin;                 /* nearest vertex w, raw Q16.16 */
    int64_t q[3];                 /* w_min / w_i, Q30 */
    int64_t nq[3][3];             /* n_i q_i, Q30 */
    int64_t z[3];                 /* clip z (orthographic depth), Q16.16 */
} bary_setup;

static void bary_make(bary_setup *b, const screen_tri *st, const tri_edges *te)
{
    tg_real wmin = st->w[0];
    int i, bl;
    if (st->w[1] < wmin) wmin = st->w[1];
    if (st->w[2] < wmin) wmin = st->w[2];
    if (wmin < 1) wmin = 1;
    /* weights u_i = E_i 2^(ls - rs) with sum(u) = area2 2^(ls - rs) ~ 2^30 */
    b->rs = tgi_bit_length64((uint64_t)te->area2) - 30;
    b->ls = b->rs < 0 ? -b->rs : 0;
    if (b->rs < 0) b->rs = 0;
    bl = tgi_bit_length64(((uint64_t)te->area2 << b->ls) >> b->rs);
    b->sm = bl > 0 ? bl - 1 : 0;
    b->wmin = wmin;
    for (i = 0; i < 3; i++) {
        b->q[i] = ((int64_t)wmin * st->iw[i]) >> 16;  /* w_min / w_i <= 1, Q30 */
        if (b->q[i] > ((int64_t)1 << 30)) b->q[i] = (int64_t)1 << 30;
        b->nq[i][0] = asr64((int64_t)st->n[i].x * b->q[i], 16);
        b->nq[i][1] = asr64((int64_t)st->n[i].y * b->q[i], 16);
        b->nq[i][2] = asr64((int64_t)st->n[i].z * b->q[i], 16);
        b->z[i] = st->z[i];
    }
}

/* The pixels a triangle covers, row by row (span_row), left to right:
 * each one's index i in a W-wide image and the edge functions e[] there.
 *     pixel_walk_begin(&pw, te, W);
 *     while (pixel_walk_row(&pw, te, wide))
 *         for (; pw.col < pw.xb; pixel_walk_step(&pw, te)) ...  */
typedef struct pixel_walk {
    span_walk sw;
    int row, col, xb, W;
    size_t i;
    int64_t e[3];
} pixel_walk;

static inline void pixel_walk_begin(pixel_walk *pw, const tri_edges *te, int W)
{
    span_begin(&pw->sw, te);
    pw->row = te->y0 - 1;
    pw->W = W;
}

/* Step to the first pixel of the next row that covers any; 0 after the
 * last row.  wide (a constant): find the start of a run in a wide box by
 * division (span_start; depth_rows, whose shadow maps' boxes are wide; in
 * gbuffer_rows the test a row cost more than it saved in the meshes of
 * tools/bench_raster.c). */
static inline int pixel_walk_row(pixel_walk *pw, const tri_edges *te, int wide)
{
    while (++pw->row < te->y1) {
        int xa;
        pw->xb = span_row(te, &pw->sw, &xa, pw->e, wide);
        if (xa < pw->xb) {
            pw->col = xa;
            pw->i = (size_t)pw->row * (size_t)pw->W + (size_t)xa;
            return 1;
        }
    }
    return 0;
}

/* Step to the next pixel of the row. */
static inline void pixel_walk_step(pixel_walk *pw, const tri_edges *te)
{
    pw->col++;
    pw->i++;
#if TG_OUTLINE_HELPERS   /* a loop at -Os */
    {
        int k;
        for (k = 0; k < 3; k++) pw->e[k] += te->step_x[k];
    }
#else
    pw->e[0] += te->step_x[0]; pw->e[1] += te->step_x[1]; pw->e[2] += te->step_x[2];
#endif
}

/* The barycentric weights u[] of the pixel whose edge functions are e[]
 * (unbiased and scaled as bary_make set up); returns their sum. */
static inline int64_t bary_weights(const bary_setup *b, const tri_edges *te, const int64_t e[3], int64_t u[3])
{
#if TG_OUTLINE_HELPERS   /* a loop at -Os, the same integers */
    int k;
    int64_t sum = 0;
    for (k = 0; k < 3; k++) sum += u[k] = ((e[k] - te->bias[k]) << b->ls) >> b->rs;
    return sum;
#else
    u[0] = ((e[0] - te->bias[0]) << b->ls) >> b->rs;
    u[1] = ((e[1] - te->bias[1]) << b->ls) >> b->rs;
    u[2] = ((e[2] - te->bias[2]) << b->ls) >> b->rs;
    return u[0] + u[1] + u[2];
#endif
}

/* One pixel i from its weights' sum su, sum(u_i q_i) (su w_min / w in
 * Q30) and sum(u_i nq_i) per component; g and sf the callers' local
 * copies.  (Always inline: called from two loops, gcc would call it, with
 * its arguments through memory.) */
static RASTER_INLINE void gbuffer_pixel(const tgi_gbuffer *gp, const surface *sfp, const bary_setup *b, size_t i,
                                        int64_t su, int64_t sq30, const int64_t sn[3], int bits)
{
#define g (*gp)
#define sf (*sfp)
    int64_t sq = sq30 >> 30, mx, my, mz;
    tg_real z;
    if (su <= 0 || sq <= 0) return;
    z = tgi_sat64((b->wmin * su + sq / 2) / sq);
#if TG_OUTLINE_HELPERS   /* a loop at -Os, the same integers */
    {
        int64_t m[3];
        int c;
        for (c = 0; c < 3; c++) m[c] = asr64(sn[c], b->sm);
        mx = m[0]; my = m[1]; mz = m[2];
    }
#else
    mx = asr64(sn[0], b->sm);
    my = asr64(sn[1], b->sm);
    mz = asr64(sn[2], b->sm);
#endif
#if TG_WIDE_STORAGE
    {
        tg_real n[3];
        (void)bits;
        if (g.depth[i] > 0 && z >= g.depth[i]) return;
        if (!unit_q16(mx, my, mz, n)) {
            n[0] = sf.fallback_normal.x; n[1] = sf.fallback_normal.y; n[2] = sf.fallback_normal.z;
        }
        g.depth[i] = z;
        g.nx[i] = n[0]; g.ny[i] = n[1]; g.nz[i] = n[2];
        g.material[i] = (uint16_t)sf.material;
    }
#else
    {
        uint32_t zb = tgi_depth_pack(z);   /* binary32 words order like the depths */
        if (g.depth[i] && zb >= g.depth[i]) return;
        g.depth[i] = zb;
        put_nm(&g, i, ((mx | my | mz) ? tgi_oct_pack64(mx, my, mz, bits)
                                      : tgi_oct_pack(sf.fallback_normal, bits)) | sf.material, bits);
    }
#endif
    if (g.object) g.object[i] = sf.object;
#undef g
#undef sf
}

/* sum(u_i q_i) and sum(u_i nq_i) for weights u. */
static inline int64_t bary_sums(const bary_setup *b, const int64_t u[3], int64_t sn[3])
{
#if TG_OUTLINE_HELPERS   /* one loop for the three components at -Os, the same integers */
    int c;
    for (c = 0; c < 3; c++) sn[c] = u[0] * b->nq[0][c] + u[1] * b->nq[1][c] + u[2] * b->nq[2][c];
#else
    sn[0] = u[0] * b->nq[0][0] + u[1] * b->nq[1][0] + u[2] * b->nq[2][0];
    sn[1] = u[0] * b->nq[0][1] + u[1] * b->nq[1][1] + u[2] * b->nq[2][1];
    sn[2] = u[0] * b->nq[0][2] + u[1] * b->nq[1][2] + u[2] * b->nq[2][2];
#endif
    return u[0] * b->q[0] + u[1] * b->q[1] + u[2] * b->q[2];
}

#if !TG_OUTLINE_HELPERS
/* gbuffer_rows' pixels with shifted weights (rs > 0: a triangle of 2^21
 * pixels or more), rare: out of line, draw_snapped the smaller (callgrind
 * build/bench_raster-fixed 1280x720: 92.2M a frame inline, 91.1M not). */
static RASTER_NOINLINE void gbuffer_rows_shifted(const tgi_gbuffer *gbp, const surface *sfp, const bary_setup *bp,
                                                 const tri_edges *te, pixel_walk *pwp, int bits)
{
    const tgi_gbuffer g = *gbp;
    const surface sf = *sfp;
    const bary_setup b = *bp;
    pixel_walk pw = *pwp;
    while (pixel_walk_row(&pw, te, 0))
        for (; pw.col < pw.xb; pixel_walk_step(&pw, te)) {
            int64_t u[3], su = bary_weights(&b, te, pw.e, u), sn[3], sq = bary_sums(&b, u, sn);
            gbuffer_pixel(&g, &sf, &b, pw.i, su, sq, sn, bits);
        }
}
#endif

static void gbuffer_rows(const tgi_gbuffer *gbp, const tri_edges *te, const screen_tri *st, const surface *sfp)
{
    /* local copies: the stores may alias anything reached through a pointer */
    const tgi_gbuffer g = *gbp;
    const surface sf = *sfp;
#if TG_WIDE_STORAGE
    const int bits = 0;           /* (no packed normal) */
#else
    const int bits = sf.normal_bits;
#endif
    bary_setup b;
    pixel_walk pw;
    bary_make(&b, st, te);
    pixel_walk_begin(&pw, te, g.width);
#if !TG_OUTLINE_HELPERS
    if (b.rs == 0) {
        /* u_i = (E_i - bias_i) 2^ls (E_i the unbiased edge function):
         * linear in the pixel's column and row, and so are su (constant:
         * the steps of u sum to 0 both ways, as the edges' dy and dx do)
         * and the sums of products, which step by the sums of the steps'
         * products.  Found in uint64_t, exact modulo 2^64: at every covered
         * pixel the same 64 bits as bary_sums' there (within int64_t for
         * unit normals: 0 <= u_i <= su < 2^30, q_i, |nq_i| <= 2^30),
         * whatever the products (a sliver's E_i step times q_i, or u_i at
         * the box's corner, can exceed 64 bits).  The steps of u sum to 0,
         * so sum(du_k a_k) = du_1 (a_1 - a_0) + du_2 (a_2 - a_0): two
         * products an attribute.  A row's run starts from the sums at the
         * box's left side, stepped down a row at a time from its corner
         * (x0, y0), j pixels on: one product an attribute, where the
         * weights and bary_sums at the run's start took three (callgrind
         * bench_raster-fixed, bench_draw a frame: 1280x720 80.94M ->
         * 77.87M, 320x240 32.30M -> 32.09M). */
        const uint64_t du1 = (uint64_t)te->step_x[1] << b.ls, du2 = (uint64_t)te->step_x[2] << b.ls;
        const uint64_t dv1 = (uint64_t)te->step_y[1] << b.ls, dv2 = (uint64_t)te->step_y[2] << b.ls;
        const uint64_t u0 = (uint64_t)(pw.sw.e[0] - te->bias[0]) << b.ls,
                       u1 = (uint64_t)(pw.sw.e[1] - te->bias[1]) << b.ls,
                       u2 = (uint64_t)(pw.sw.e[2] - te->bias[2]) << b.ls;
        const int64_t su = (int64_t)(u0 + u1 + u2);
#define U_SUM(a0, a1, a2) (u0 * (uint64_t)(a0) + u1 * (uint64_t)(a1) + u2 * (uint64_t)(a2))
#define U_SUM_N(c) U_SUM(b.nq[0][c], b.nq[1][c], b.nq[2][c])
#define U_STEP(d1, d2, a0, a1, a2) ((d1) * (uint64_t)((a1) - (a0)) + (d2) * (uint64_t)((a2) - (a0)))
#define U_STEP_N(d1, d2, c) U_STEP(d1, d2, b.nq[0][c], b.nq[1][c], b.nq[2][c])
        const uint64_t dq = U_STEP(du1, du2, b.q[0], b.q[1], b.q[2]), dqy = U_STEP(dv1, dv2, b.q[0], b.q[1], b.q[2]);
        const uint64_t dn[3] = { U_STEP_N(du1, du2, 0), U_STEP_N(du1, du2, 1), U_STEP_N(du1, du2, 2) };
        const uint64_t dny[3] = { U_STEP_N(dv1, dv2, 0), U_STEP_N(dv1, dv2, 1), U_STEP_N(dv1, dv2, 2) };
        uint64_t rq = U_SUM(b.q[0], b.q[1], b.q[2]), r0 = U_SUM_N(0), r1 = U_SUM_N(1), r2 = U_SUM_N(2);
        int row;
#undef U_SUM
#undef U_SUM_N
#undef U_STEP
#undef U_STEP_N
        if (su <= 0) return;
        for (row = te->y0; row < te->y1; row++, rq += dqy, r0 += dny[0], r1 += dny[1], r2 += dny[2]) {
            int xa, xb = span_row(te, &pw.sw, &xa, NULL, 0);
            const uint64_t j = (uint64_t)(xa - te->x0);
            uint64_t sq = rq + j * dq, s0 = r0 + j * dn[0], s1 = r1 + j * dn[1], s2 = r2 + j * dn[2];
            size_t i = (size_t)row * (size_t)g.width + (size_t)xa, end = i + (size_t)(xb - xa);
            if (xb <= xa) continue;
#if TG_WIDE_STORAGE
            for (; i < end; i++, sq += dq, s0 += dn[0], s1 += dn[1], s2 += dn[2]) {
                int64_t n[3];
                n[0] = (int64_t)s0; n[1] = (int64_t)s1; n[2] = (int64_t)s2;
                gbuffer_pixel(&g, &sf, &b, i, su, (int64_t)sq, n, bits);
            }
#else
            /* gbuffer_pixel's integers, cheaper.  Depth: u_i >= 0 at a
             * covered pixel (e_i >= 0, u_i = (e_i - bias_i) 2^ls, bias_i
             * 0 or -1) and q_i <= 2^30, so sq <= su and z >= w_min >= 1:
             * tgi_sat64 only clamps above, tgi_depth_pack_pos applies.
             * Normal: |asr64(s, sm)| = |s| >> sm, and asr64(s, sm) < 0
             * exactly where s <= -2^sm (s > INT64_MIN: |s| < 2^61 for unit
             * normals, as above), which tgi_oct_pack_abs takes; its l1 is
             * 0 exactly for the zero vector. */
            {
                const int64_t wsu = b.wmin * su, neg = -((int64_t)1 << b.sm);
                for (; i < end; i++, sq += dq, s0 += dn[0], s1 += dn[1], s2 += dn[2]) {
                    const int64_t sqi = (int64_t)sq >> 30, x = (int64_t)s0, y = (int64_t)s1, zs = (int64_t)s2;
                    int64_t z;
                    uint64_t ax, ay, l1;
                    uint32_t zb, w;
                    if (sqi <= 0) continue;
                    z = (wsu + (sqi >> 1)) / sqi;
                    if (z > TG_REAL_MAX) z = TG_REAL_MAX;
                    zb = tgi_depth_pack_pos((tg_real)z);
                    if (g.depth[i] && zb >= g.depth[i]) continue;
                    g.depth[i] = zb;
                    ax = mag64(x) >> b.sm;
                    ay = mag64(y) >> b.sm;
                    l1 = ax + ay + (mag64(zs) >> b.sm);
                    w = l1 ? tgi_oct_pack_abs(ax, ay, l1, x <= neg, y <= neg, zs <= neg, bits)
                           : tgi_oct_pack(sf.fallback_normal, bits);
                    put_nm(&g, i, w | sf.material, bits);
                    if (g.object) g.object[i] = sf.object;
                }
            }
#endif
        }
        return;
    }
    gbuffer_rows_shifted(&g, &sf, &b, te, &pw, bits);
#else
    while (pixel_walk_row(&pw, te, 0))
        for (; pw.col < pw.xb; pixel_walk_step(&pw, te)) {
            int64_t u[3], su = bary_weights(&b, te, pw.e, u), sn[3], sq = bary_sums(&b, u, sn);
            gbuffer_pixel(&g, &sf, &b, pw.i, su, sq, sn, bits);
        }
#endif
}

#if TGI_RASTER_DEPTH_ROWS
static void depth_rows(const depth_out *o, int W, const tri_edges *te, const screen_tri *st, int ortho)
{
    bary_setup b;
    pixel_walk pw;
    bary_make(&b, st, te);
    pixel_walk_begin(&pw, te, W);
#if !TG_OUTLINE_HELPERS
    if (b.rs == 0) {
        /* As gbuffer_rows: the sum of products stepped along the row in
         * uint64_t, exact modulo 2^64, so at every covered pixel the same
         * 64 bits as the sum there (within int64_t: 0 <= u_i, sum(u) <
         * 2^30, 0 <= q_i <= 2^30 and |z_i| < 2^31); su is the same at
         * every pixel (the steps of u sum to 0); depth_keep is inline
         * here (DEPTH_KEEP_INLINE).  With span_start: callgrind
         * tinygi-fixed render builtin:cornell --size 160x120 --frames 2,
         * draw_snapped + depth_keep 11.73M -> 7.79M, the whole 677.39M ->
         * 673.93M. */
        const uint64_t du1 = (uint64_t)te->step_x[1] << b.ls, du2 = (uint64_t)te->step_x[2] << b.ls;
        const int64_t *a = ortho ? b.z : b.q;
        const uint64_t dv = du1 * (uint64_t)(a[1] - a[0]) + du2 * (uint64_t)(a[2] - a[0]);
        while (pixel_walk_row(&pw, te, 1)) {
            int64_t u[3], su = bary_weights(&b, te, pw.e, u);
            uint64_t v = (uint64_t)(u[0] * a[0] + u[1] * a[1] + u[2] * a[2]);
            size_t i = pw.i, end = pw.i + (size_t)(pw.xb - pw.col);
            pw.col = pw.xb;
            if (su <= 0) continue;
            for (; i < end; i++, v += dv) {
                int64_t z, vi = (int64_t)v;
                if (ortho) {
                    z = vi >= 0 ? (vi + su / 2) / su : -((-vi + su / 2) / su);
                } else {
                    vi >>= 30;
                    if (vi <= 0) continue;
                    z = (b.wmin * su + vi / 2) / vi;
                }
                depth_keep(o, i, tgi_sat64(z));
            }
        }
        return;
    }
#endif
    while (pixel_walk_row(&pw, te, 1))
        for (; pw.col < pw.xb; pixel_walk_step(&pw, te)) {
            int64_t u[3], su = bary_weights(&b, te, pw.e, u), v;
            if (su <= 0) continue;
            if (ortho) {
                v = u[0] * b.z[0] + u[1] * b.z[1] + u[2] * b.z[2];
                v = v >= 0 ? (v + su / 2) / su : -((-v + su / 2) / su);
                depth_keep(o, pw.i, tgi_sat64(v));
            } else {
                v = (u[0] * b.q[0] + u[1] * b.q[1] + u[2] * b.q[2]) >> 30;
                if (v <= 0) continue;
                v = (b.wmin * su + v / 2) / v;
                depth_keep(o, pw.i, tgi_sat64(v));
            }
        }
}
#endif

#else /* float */

/* An attribute plane: value at the centre of pixel (x0, y0) and its change
 * per pixel right and down. */
typedef struct plane { float v, dx, dy; } plane;

typedef struct plane_basis {
    float fy20, fy01, fx02, fx10, inv_area, ox, oy;
} plane_basis;

static inline void plane_basis_make(plane_basis *pb, const screen_tri *st, const tri_edges *te)
{
    pb->fy20 = (float)(st->y[2] - st->y[0]);
    pb->fy01 = (float)(st->y[0] - st->y[1]);
    pb->fx02 = (float)(st->x[0] - st->x[2]);
    pb->fx10 = (float)(st->x[1] - st->x[0]);
    pb->inv_area = 1.0f / (float)te->area2;
    pb->ox = (float)(te->cx - st->x[0]);
    pb->oy = (float)(te->cy - st->y[0]);
}

/* RASTER_OCT_LANES: the float G-buffer's normal in vector lanes (below,
 * at oct_pack_lanes), where GCC's or clang's vector extensions are and
 * the machine has IEEE single-precision vector registers (SSE2, AArch64's
 * NEON; not 32-bit ARM's NEON, which flushes subnormals): elsewhere the
 * compiler would emulate the lanes (no gain) and gcc warns that a vector
 * argument takes a non-standard ABI (-Wpsabi, 32-bit PowerPC) */
#if !TG_WIDE_STORAGE && defined(__GNUC__) && !defined(__OPTIMIZE_SIZE__) && !TG_OUTLINE_HELPERS && defined(__has_builtin) \
    && (defined(__SSE2__) || defined(__aarch64__))
#if __has_builtin(__builtin_shufflevector) && __has_builtin(__builtin_convertvector)
#define RASTER_OCT_LANES 1
#endif
#endif
#ifndef RASTER_OCT_LANES
#define RASTER_OCT_LANES 0
#endif

#if !RASTER_OCT_LANES || TGI_RASTER_DEPTH_ROWS   /* the lanes make the G-buffer's planes themselves */
/* a(p) = a0 + lambda1 (a1 - a0) + lambda2 (a2 - a0), lambda from the edge functions. */
static inline plane plane_make(const plane_basis *pb, float a0, float a1, float a2)
{
    plane p;
    float d1 = a1 - a0, d2 = a2 - a0;
    float gx = (d1 * pb->fy20 + d2 * pb->fy01) * pb->inv_area;
    float gy = (d1 * pb->fx02 + d2 * pb->fx10) * pb->inv_area;
    p.v = a0 + gx * pb->ox + gy * pb->oy;
    p.dx = gx * (float)SUB;
    p.dy = gy * (float)SUB;
    return p;
}
#endif

/* Whether the interpolated normal m is used (else the fallback):
 * |m|^2 > 1e-30, as computed.  Decided first by the l1 norm tgi_oct_pack
 * computes (the same sums, shared): l1 > 1e-14 puts a component above
 * 3.3e-15 (l1 rounds twice, by under 2^-22), whose square (1.1e-29, a
 * normal float) is at most |m|^2 (sums of non-negative terms round no
 * lower than their largest), so |m|^2 > 1e-30; l1 = inf makes |m|^2
 * inf too.  Otherwise (a small normal, or NaN) |m|^2 as before. */
static inline int normal_nonzero(float mx, float my, float mz)
{
    float l1 = tgi_abs_bits(mx) + tgi_abs_bits(my) + tgi_abs_bits(mz);
    return l1 > 1e-14f || mx * mx + my * my + mz * mz > 1e-30f;
}

#if !TG_WIDE_STORAGE
/* The packed normal of a pixel whose l1 is small, huge or NaN: out of
 * line (a call in the loop's rare branch; inline, its clamped quantization
 * took registers from the loop: bench_raster 1280x720 67.9M -> 78.9M). */
static RASTER_NOINLINE uint32_t oct_pack_rare(const surface *sf, float mx, float my, float mz, int bits)
{
    return tgi_oct_pack(normal_nonzero(mx, my, mz) ? tg_v3(mx, my, mz) : sf->fallback_normal, bits);
}
#endif

/* The normal's interpolants in vector lanes (GCC's and clang's vector
 * extensions): the planes of (mx, my, mz, qv) made at once, s = (mx, my,
 * mz, 0) found per row and stepped per pixel by one vector add, the
 * magnitudes by one and, l1 by two adds of the lanes into every lane
 * (ax + ay in lanes 0 and 1, az + 0 = 0 + az = az in lanes 2 and 3, then
 * each lane plus the one two away: (ax + ay) + az everywhere, IEEE
 * addition being commutative), r = 1 / l1 by one vector division (no
 * broadcast), and the octahedral x and y projected, folded and quantized
 * side by side in lanes 0 and 1, packed by one shift and or of the lanes.
 * Each lane is the scalar IEEE operation on the same operands
 * (-ffp-contract=off: no fused or reassociated step), so every word is
 * tgi_oct_pack_l1's: l1 = (ax + ay) + az as there, the fold's -fx the sign
 * bit flipped where m.x < 0 (as negation), the truncation cvttps2dq's
 * (uint32_t) of u in (0.49, q + 0.5).  The fold flips by s's own sign bit
 * (s & sign: two instructions fewer than the mask of s < 0): s is never
 * -0, the one word where the two differ, as the planes' value is taken as
 * v0 = pl.v + 0 (-0 + 0 = +0, every other word unchanged) and a sum of
 * two floats is -0 only when both are (an exact zero rounds to +0; with
 * gradual underflow no nonzero sum rounds to zero; SSE2 and AArch64 do not
 * flush by default), so neither row_start = (v0 + dy pl.dy) + dx pl.dx nor
 * s stepped from it is; it is not NaN either where the fold runs (l1 in
 * range).  That + 0 changes at most the sign of a zero, in pl.v and so in
 * s and qv, which changes no word (|s|, s < 0, s r + 1, qv > 0 are the
 * same; the rare path's tgi_oct_pack reads m through |m|, m < 0 and m r
 * + 1 too).  The unused lanes 2 and 3 hold mz r or 1 - az r (bounded as x and
 * y: u in (0.49, q + 0.5) too), and 0 or 1, so their conversion is
 * defined.  Not in the -Os size build.  Exact: tools/same_bits.sh 0 differ,
 * bench_raster's gbuffer_fnv unchanged; callgrind bench_raster a frame
 * 1280x720 54.93M -> 52.38M, 320x240 23.55M -> 22.60M (the flip by the
 * sign bit, l1 in every lane and the packing in lanes: 52.38M -> 50.51M,
 * 22.60M -> 22.44M).  The lane shuffles that read a vector kept for later
 * (a, t, s) are written on its integer view, the same bits moved: SSE2's
 * pshufd copies and shuffles in one instruction where shufps shuffles in
 * place after a copy (50.51M -> 49.20M, 22.44M -> 22.21M).  The + 0 once
 * a triangle, on pl.v, not once a row (48.98M -> 48.89M, 21.99M ->
 * 21.98M). */
#if RASTER_OCT_LANES
typedef float oct_v4f __attribute__((vector_size(16)));
typedef int32_t oct_v4i __attribute__((vector_size(16)));
typedef struct oct_lanes { oct_v4f one, half, scale, zero; oct_v4i sign; } oct_lanes;
/* s as above, a = |s|, l1 = (a0 + a1) + a2 in every lane */
static RASTER_INLINE uint32_t oct_pack_lanes(const oct_lanes *c, oct_v4f s, oct_v4f a, oct_v4f l1, int bits)
{
    const oct_v4f r = c->one / l1;
    oct_v4f p;
    oct_v4i k;
    if (((oct_v4f)__builtin_shufflevector((oct_v4i)s, (oct_v4i)s, 2, 2, 2, 2))[0] < 0.0f) {   /* (1 - |p.yx|) sign(p) */
        p = c->one - __builtin_shufflevector(a, a, 1, 0, 2, 3) * r;
        p = (oct_v4f)((oct_v4i)p ^ ((oct_v4i)s & c->sign));
    } else {
        p = s * r;
    }
    k = __builtin_convertvector((p + c->one) * c->scale + c->half, oct_v4i);
    k |= __builtin_shufflevector(k, k, 1, 1, 1, 1) << bits;
    return (uint32_t)k[0];
}
/* plane_make in each lane */
typedef struct plane_lanes { oct_v4f v, dx, dy; } plane_lanes;
static inline plane_lanes plane_make_lanes(const plane_basis *pb, oct_v4f a0, oct_v4f a1, oct_v4f a2)
{
    plane_lanes p;
    oct_v4f d1 = a1 - a0, d2 = a2 - a0;
    oct_v4f gx = (d1 * pb->fy20 + d2 * pb->fy01) * pb->inv_area;
    oct_v4f gy = (d1 * pb->fx02 + d2 * pb->fx10) * pb->inv_area;
    p.v = a0 + gx * pb->ox + gy * pb->oy;
    p.dx = gx * (float)SUB;
    p.dy = gy * (float)SUB;
    return p;
}
#endif

static RASTER_INLINE void gbuffer_rows_bits(const tgi_gbuffer *gbp, const tri_edges *te, const screen_tri *st,
                                          const surface *sfp, int bits)
{
    /* local copies: the stores may alias anything reached through a pointer */
    const tgi_gbuffer g = *gbp;
    const surface sf = *sfp;
    plane_basis pb;
#if !RASTER_OCT_LANES
    plane pq, pnx, pny, pnz;
#endif
    span_walk sw;
    float wmin = st->w[0], q[3];
    int row, col, k, W = g.width;
    if (st->w[1] < wmin) wmin = st->w[1];
    if (st->w[2] < wmin) wmin = st->w[2];
    for (k = 0; k < 3; k++) q[k] = wmin * st->iw[k];
    plane_basis_make(&pb, st, te);
#if !RASTER_OCT_LANES
    pq = plane_make(&pb, q[0], q[1], q[2]);
    pnx = plane_make(&pb, st->n[0].x * q[0], st->n[1].x * q[1], st->n[2].x * q[2]);
    pny = plane_make(&pb, st->n[0].y * q[0], st->n[1].y * q[1], st->n[2].y * q[2]);
    pnz = plane_make(&pb, st->n[0].z * q[0], st->n[1].z * q[1], st->n[2].z * q[2]);
#else
    const float scale = (float)((1u << (bits - 1)) - 1);   /* tgi_oct_quant_u's */
    const oct_lanes lanes = {{1.0f, 1.0f, 1.0f, 1.0f}, {0.5f, 0.5f, 0.5f, 0.5f}, {scale, scale, scale, scale},
                             {0.0f, 0.0f, 0.0f, 0.0f},
                             {INT32_MIN, INT32_MIN, 0, 0}};
    const oct_v4i magnitude = {INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX}, normal = {-1, -1, -1, 0};
    /* lane k: the products n.x q, n.y q, n.z q, 1 q = q as pnx, pny, pnz, pq take them */
    const plane_lanes pl = plane_make_lanes(&pb, (oct_v4f){st->n[0].x, st->n[0].y, st->n[0].z, 1.0f} * q[0],
                                            (oct_v4f){st->n[1].x, st->n[1].y, st->n[1].z, 1.0f} * q[1],
                                            (oct_v4f){st->n[2].x, st->n[2].y, st->n[2].z, 1.0f} * q[2]);
    const oct_v4f sdx = (oct_v4f)((oct_v4i)pl.dx & normal);
    const float qdx = pl.dx[3];
    const oct_v4f v0 = pl.v + lanes.zero;   /* never -0: oct_pack_lanes' s (above) */
#endif
    span_begin(&sw, te);
    for (row = te->y0; row < te->y1; row++) {
        int xa, xb = span_row(te, &sw, &xa, NULL, 0);
        float dy, dx, qv;
#if !RASTER_OCT_LANES
        float mx, my, mz;
#endif
        size_t i;
        if (xb <= xa) continue;
        dy = (float)(row - te->oy);
        dx = (float)(xa - te->x0);
        i = (size_t)row * (size_t)W + (size_t)xa;
#if RASTER_OCT_LANES
        {   /* the lanes of mx, my, mz, qv below, the same operations */
            const oct_v4f row_start = v0 + pl.dy * dy + pl.dx * dx;
            oct_v4f s = (oct_v4f)((oct_v4i)row_start & normal);
            for (col = xa, qv = row_start[3]; col < xb; col++, i++, qv += qdx, s += sdx) {
                tgi_f32_bits zb, lb, lo, hi;
                oct_v4f a, t;
                uint32_t dw;
                if (!(qv > 0.0f)) continue;
                dw = g.depth[i];
                zb.f = wmin / qv;   /* the depth test as below */
                if (dw != 0 && (((int32_t)dw > 0 && wmin >= qv * tgi_depth_unpack(dw)) || zb.u >= dw)) continue;
                g.depth[i] = zb.u;
                a = (oct_v4f)((oct_v4i)s & magnitude);
                t = a + (oct_v4f)__builtin_shufflevector((oct_v4i)a, (oct_v4i)a, 1, 0, 3, 2);
                t += (oct_v4f)__builtin_shufflevector((oct_v4i)t, (oct_v4i)t, 2, 3, 0, 1);
                lb.f = t[0];
                lo.f = 1e-14f;
                hi.f = TG_REAL_MAX;
                put_nm(&g, i, (lb.u - lo.u - 1u < hi.u - lo.u ? oct_pack_lanes(&lanes, s, a, t, bits)
                                                               : oct_pack_rare(&sf, s[0], s[1], s[2], bits))
                              | sf.material, bits);
                if (g.object) g.object[i] = sf.object;
            }
        }
        continue;   /* (no-op; gcc 12 orders the loop's blocks better with it: 1280x720 52.96M -> 52.38M) */
#else
        qv = pq.v + pq.dy * dy + pq.dx * dx;
        mx = pnx.v + pnx.dy * dy + pnx.dx * dx;
        my = pny.v + pny.dy * dy + pny.dx * dx;
        mz = pnz.v + pnz.dy * dy + pnz.dx * dx;
        for (col = xa; col < xb; col++, i++, qv += pq.dx, mx += pnx.dx, my += pny.dx, mz += pnz.dx) {
#if TG_WIDE_STORAGE
            float d;
#else
            uint32_t dw;
#endif
            if (!(qv > 0.0f)) continue;
#if TG_WIDE_STORAGE
            (void)bits;
            d = g.depth[i];
            if (d > 0.0f && wmin >= qv * d) continue;
            {
                float z = wmin / qv;
                if (d > 0.0f && z >= d) continue;   /* an equal depth: the first drawn keeps it */
                g.depth[i] = z;
            }
            if (normal_nonzero(mx, my, mz)) {
                float r = tgi_rsqrt_fast(mx * mx + my * my + mz * mz);
                g.nx[i] = mx * r; g.ny[i] = my * r; g.nz[i] = mz * r;
            } else {
                g.nx[i] = sf.fallback_normal.x; g.ny[i] = sf.fallback_normal.y; g.nz[i] = sf.fallback_normal.z;
            }
            g.material[i] = (uint16_t)sf.material;
#else
            dw = g.depth[i];
            {   /* The stored word dw: 0 is sky, drawn over without a test.  Else
                 * the two tests as before: d > 0 as (int32_t)dw > 0 (d's bits: a
                 * positive float or +inf exactly where the signed word is
                 * positive, but for a positive NaN, where wmin >= qv d fails as
                 * d > 0 did); then qv * d rounds, so an equal depth can pass
                 * that test, and the first surface drawn keeps it, as in Q16.16:
                 * zb >= dw.  wmin > 0 (every drawn vertex has w > 0: w >= znear
                 * > 0 unclipped, draw_polygon's test clipped) and qv > 0, both
                 * finite, so z = wmin / qv is +0, +inf or positive, never NaN
                 * or negative: its bits are tgi_depth_pack's word (+0's are 0).
                 * z is found before the first test (no side effect). */
                tgi_f32_bits zb;
                zb.f = wmin / qv;
                if (dw != 0 && (((int32_t)dw > 0 && wmin >= qv * tgi_depth_unpack(dw)) || zb.u >= dw)) continue;
                g.depth[i] = zb.u;
            }
            {   /* tgi_oct_pack(normal_nonzero(m) ? m : fallback): l1 > 1e-14 is nonzero, and
                 * above 2^-127, so the unclamped tgi_oct_pack_l1 packs it.  The test as
                 * one unsigned range test of l1's bits: non-negative floats order as
                 * their bits, and every other word (negative, -0, NaN of either sign,
                 * +inf) lies outside the range as it fails the comparisons (checked
                 * for all 2^32 words; 3 instructions a pixel fewer). */
                const float ax = tgi_abs_bits(mx), ay = tgi_abs_bits(my), l1 = ax + ay + tgi_abs_bits(mz);
                tgi_f32_bits lb, lo, hi;
                lb.f = l1;
                lo.f = 1e-14f;
                hi.f = TG_REAL_MAX;
                put_nm(&g, i, (lb.u - lo.u - 1u < hi.u - lo.u ? tgi_oct_pack_l1(tg_v3(mx, my, mz), ax, ay, l1, bits)
                                                               : oct_pack_rare(&sf, mx, my, mz, bits))
                              | sf.material, bits);
            }
#endif
            if (g.object) g.object[i] = sf.object;
        }
#endif
    }
}

#if TGI_RASTER_DEPTH_ROWS
static void depth_rows(const depth_out *o, int W, const tri_edges *te, const screen_tri *st, int ortho)
{
    plane_basis pb;
    plane pa;
    span_walk sw;
    float wmin = st->w[0];
    int row, col;
    if (st->w[1] < wmin) wmin = st->w[1];
    if (st->w[2] < wmin) wmin = st->w[2];
    plane_basis_make(&pb, st, te);
    if (ortho) pa = plane_make(&pb, st->z[0], st->z[1], st->z[2]);
    else pa = plane_make(&pb, wmin * st->iw[0], wmin * st->iw[1], wmin * st->iw[2]);
    span_begin(&sw, te);
    for (row = te->y0; row < te->y1; row++) {
        int xa, xb = span_row(te, &sw, &xa, NULL, 0);
        float a;
        size_t i;
        if (xb <= xa) continue;
        a = pa.v + pa.dy * (float)(row - te->oy) + pa.dx * (float)(xa - te->x0);
        i = (size_t)row * (size_t)W + (size_t)xa;
        for (col = xa; col < xb; col++, i++, a += pa.dx) {
            if (ortho) {
                depth_keep(o, i, a);
            } else if (a > 0.0f) {
                if (o->d16 || KEEPS_BACK(o)) depth_keep(o, i, wmin / a);
                else if (wmin < a * o->d32[i]) o->d32[i] = wmin / a;
            }
        }
    }
}
#endif

/* A triangle's pixels: with each normal format's constants (its
 * quantization, the nm or n8 store) where code size allows.  (Q16.16 does
 * not gain: its quantization divides anyway, and gcc then inlines less
 * elsewhere; callgrind bench_raster 1280x720 109.0M -> 117.7M.) */
static void gbuffer_rows(const tgi_gbuffer *gbp, const tri_edges *te, const screen_tri *st, const surface *sfp)
{
#if TG_WIDE_STORAGE
    gbuffer_rows_bits(gbp, te, st, sfp, 0);
#elif TG_OUTLINE_HELPERS
    gbuffer_rows_bits(gbp, te, st, sfp, sfp->normal_bits);
#else
    if (sfp->normal_bits == TGI_NORMAL_BITS) gbuffer_rows_bits(gbp, te, st, sfp, TGI_NORMAL_BITS);
    else gbuffer_rows_bits(gbp, te, st, sfp, 8);
#endif
}

#endif

/* ---------------------------------------------------------------------- */
/* triangles                                                               */

typedef struct raster_target {
    int width, height, row0, row1;
    int32_t half_w16, half_h16;   /* width * 8, height * 8 */
    clip_ctx clip;
    tgi_gbuffer *gb;               /* G-buffer mode */
    int material;                 /* of the current triangle: its index */
    uint16_t object;
    const tg_vec3 *tri_nrm;       /* its three vertex normals */
    int cull_back, flip_back;     /* G-buffer: one-sided / twosided */
#if TGI_RASTER_BACK_LAYER
    int back_layer;               /* G-buffer: drawing the back faces' layer (dout.back) */
#endif
    depth_out dout;               /* depth-only mode, and the G-buffer's back-face layer */
} raster_target;

/* Whether the G-buffer culls a triangle of facing `front`: a one-sided
 * back face, or a front face when drawing the back-face layer; and whether
 * it writes the surface (not in the back-face layer). */
#if TGI_RASTER_BACK_LAYER
#define FACE_CULLED(rt, front) ((rt)->gb && ((rt)->back_layer ? (front) : !(front)) && (rt)->cull_back)
#define SURFACE_OUT(rt) ((rt)->gb && !(rt)->back_layer)
#else
#define FACE_CULLED(rt, front) ((rt)->gb && !(front) && (rt)->cull_back)
#define SURFACE_OUT(rt) ((rt)->gb != NULL)
#endif

/* A clip-space vertex (inside the guard band, w > 0) to 28.4 screen
 * coordinates.  Every path snaps through here, so a vertex shared by two
 * triangles lands on the same integers whichever path draws them. */
static inline void snap_vertex(const raster_target *rt, const clip_vertex *v, int32_t *sx, int32_t *sy, inv_w *iw)
{
    *iw = inverse_w(v->w);
    *sx = rt->half_w16 + snap_ndc(v->x, v->w, *iw, rt->half_w16);
    *sy = rt->half_h16 - snap_ndc(v->y, v->w, *iw, rt->half_h16);
}

/* Rasterize one snapped triangle: vertex k of the ordered triangle is
 * v[idx[k]] (normals from nrm[idx[k]] when nrm is given). */
static void draw_snapped(const raster_target *rt, const clip_vertex *v, const tg_vec3 *nrm,
                         const int32_t *sx, const int32_t *sy, const inv_w *iw, const int *idx,
                         int64_t area2, int flip)
{
    screen_tri st;
    tri_edges te;
    int k;
    for (k = 0; k < 3; k++) { st.x[k] = sx[idx[k]]; st.y[k] = sy[idx[k]]; }
    if (!edges_setup(&te, st.x, st.y, area2, rt->width, rt->row0, rt->row1)) return;
    for (k = 0; k < 3; k++) {
        const clip_vertex *c = &v[idx[k]];
        st.w[k] = c->w;
        st.z[k] = c->z;
        st.iw[k] = iw[idx[k]];
#if TG_OUTLINE_HELPERS   /* the smaller code */
        if (SURFACE_OUT(rt)) {
            tg_vec3 n = nrm ? nrm[idx[k]] : c->n;
            st.n[k] = flip ? tgi_v3_neg(n) : n;
        }
#endif
    }
    if (SURFACE_OUT(rt)) {
        surface sf;
#if !TG_OUTLINE_HELPERS
        /* the normals, each test once a triangle (gcc had kept them in the
         * loop above: callgrind bench_raster 320x240 24.63M -> 24.26M a
         * frame, 1280x720 55.82M -> 55.78M; Q16.16 32.93M -> 32.63M,
         * 81.65M -> 81.64M) */
        if (nrm) {
            st.n[0] = nrm[idx[0]]; st.n[1] = nrm[idx[1]]; st.n[2] = nrm[idx[2]];
        } else {
            st.n[0] = v[idx[0]].n; st.n[1] = v[idx[1]].n; st.n[2] = v[idx[2]].n;
        }
        if (flip) {
            st.n[0] = tgi_v3_neg(st.n[0]); st.n[1] = tgi_v3_neg(st.n[1]); st.n[2] = tgi_v3_neg(st.n[2]);
        }
#endif
        sf.object = rt->object;
        sf.fallback_normal = flip ? tgi_v3_neg(rt->tri_nrm[0]) : rt->tri_nrm[0];
#if TG_WIDE_STORAGE
        sf.material = (uint32_t)rt->material;
#else
        sf.normal_bits = rt->gb->nm ? TGI_NORMAL_BITS : 8;
        sf.material = rt->gb->nm ? (uint32_t)rt->material << TGI_MATERIAL_SHIFT : 0;
#endif
        gbuffer_rows(rt->gb, &te, &st, &sf);
    }
#if TGI_RASTER_DEPTH_ROWS
    else depth_rows(&rt->dout, rt->width, &te, &st, rt->clip.mode == MODE_ORTHO);
#endif
}

/* The common case: a triangle needing no clipping.  Normals come from nrm
 * (loaded only once the triangle survives culling). */
static void draw_triangle(const raster_target *rt, const clip_vertex *v, const tg_vec3 *nrm)
{
    static const int order_front[3] = { 0, 2, 1 }, order_back[3] = { 0, 1, 2 };
    int32_t sx[3], sy[3];
    inv_w iw[3];
    int64_t area2;
    int k, front;
    for (k = 0; k < 3; k++) snap_vertex(rt, &v[k], &sx[k], &sy[k], &iw[k]);
    area2 = signed_area2(sx, sy);
    if (area2 == 0) return;                       /* zero area */
    front = area2 < 0;                            /* counter-clockwise as seen, y down */
    if (FACE_CULLED(rt, front)) return;
    draw_snapped(rt, v, nrm, sx, sy, iw, front ? order_front : order_back, front ? -area2 : area2,
                 rt->gb && !front && rt->flip_back);
}

/* A clipped convex polygon, drawn as a fan; facing is decided once from
 * its whole signed area. */
static void draw_polygon(const raster_target *rt, const clip_vertex *poly, int n)
{
    int32_t sx[MAX_POLY], sy[MAX_POLY];
    inv_w iw[MAX_POLY];
    int64_t total = 0;
    int i, front, flip;
    for (i = 0; i < n; i++) {
        if (!(poly[i].w > 0)) return;             /* a degenerate projection (or NaN): nothing in front */
        snap_vertex(rt, &poly[i], &sx[i], &sy[i], &iw[i]);
    }
    for (i = 0; i < n; i++) {
        int j = i + 1 == n ? 0 : i + 1;
        total += (int64_t)sx[i] * sy[j] - (int64_t)sx[j] * sy[i];
    }
    if (total == 0) return;
    front = total < 0;
    if (FACE_CULLED(rt, front)) return;
    flip = rt->gb && !front && rt->flip_back;
    for (i = 1; i + 1 < n; i++) {
        int idx[3];
        int32_t tx[3], ty[3];
        int64_t area2;
        idx[0] = 0;
        idx[1] = front ? i + 1 : i;               /* order so area2 > 0 */
        idx[2] = front ? i : i + 1;
        tx[0] = sx[idx[0]]; tx[1] = sx[idx[1]]; tx[2] = sx[idx[2]];
        ty[0] = sy[idx[0]]; ty[1] = sy[idx[1]]; ty[2] = sy[idx[2]];
        area2 = signed_area2(tx, ty);
        if (area2 <= 0) continue;                 /* sliver of the opposite facing */
        draw_snapped(rt, poly, NULL, sx, sy, iw, idx, area2, flip);
    }
}

/* One clip-space triangle: reject, clip if needed, draw.  When no clipping
 * is needed and nrm is given, the normals are read from it lazily. */
static void draw_clip_tri(const raster_target *rt, clip_vertex *v, const tg_vec3 *nrm)
{
    unsigned c0 = outcode(&rt->clip, &v[0]), c1 = outcode(&rt->clip, &v[1]), c2 = outcode(&rt->clip, &v[2]);
    clip_vertex poly[MAX_POLY];
    int n;
    if ((c0 & c1 & c2) >> OUT_SCREEN_SHIFT) return;   /* wholly outside one plane */
    if (!((c0 | c1 | c2) & OUT_GUARD_MASK)) {
        draw_triangle(rt, v, nrm);
        return;
    }
    poly[0] = v[0]; poly[1] = v[1]; poly[2] = v[2];
    if (nrm) { poly[0].n = nrm[0]; poly[1].n = nrm[1]; poly[2].n = nrm[2]; }
    n = clip_polygon(&rt->clip, poly, 3, (c0 | c1 | c2) & OUT_GUARD_MASK);
    if (n >= 3) draw_polygon(rt, poly, n);
}

static int target_rows(raster_target *rt, int width, int height, int y0, int y1)
{
    if (width <= 0 || height <= 0 || width > TG_MAX_IMAGE_SIDE || height > TG_MAX_IMAGE_SIDE) return 0;
    rt->width = width;
    rt->height = height;
    rt->row0 = y0 < 0 ? 0 : y0;
    rt->row1 = y1 > height ? height : y1;
    rt->half_w16 = (int32_t)width * (SUB / 2);
    rt->half_h16 = (int32_t)height * (SUB / 2);
    return rt->row0 < rt->row1;
}

/* ---------------------------------------------------------------------- */
/* G-buffer triangles through a small vertex cache                         */

/* A world vertex in view clip space (x fx, y fy, w = view z), classified:
 * V_INSIDE when inside the guard band and the depth range (no clipping
 * needed; sx, sy are then its 28.4 screen position), V_RIGHT.. when beyond
 * that screen side. */
/* In Q16.16 with the wide clipper a vertex whose clip coordinates pass
 * TGI_CLIP_SAFE has no flag at all (its saturated coordinates say
 * nothing), so a triangle with one is neither inside nor off a side: it is
 * clipped, in 64 bits (gbuffer_wide_triangle). */
enum { V_INSIDE = 1, V_RIGHT = 2, V_LEFT = 4, V_TOP = 8, V_BOTTOM = 16 };
#define V_OFF_SIDE (V_RIGHT | V_LEFT | V_TOP | V_BOTTOM)

/* The vertex cache's size (see vertex_cache below). */
#if UINTPTR_MAX > 0xFFFFFFFFu && !TG_OUTLINE_HELPERS
#define VCACHE_BIG 1
#if TG_FIXED
#define VCACHE_BITS 10
#else
#define VCACHE_BITS 11            /* float's 20-byte entries: 2048 in 64 KB */
#endif
#else
#define VCACHE_BIG 0
#define VCACHE_BITS 4
#endif

/* The float build's big cache keeps no x, y (clip space, for the clipper
 * alone): a triangle that needs clipping makes them again (tri_clip_xy),
 * and the entries shrink from 28 to 20 bytes, the cache from 40 to 32 KB
 * (callgrind bench_raster 320x240 25.27M -> 25.08M instructions a frame,
 * D1 misses 72.0K + 36.8K -> 68.1K + 30.1K; 1280x720 56.46M -> 56.27M,
 * 109.6K + 87.9K -> 106.9K + 81.8K).  Not in Q16.16, where the clipper
 * is the wide one from the positions and gcc drops the copies of x, y
 * anyway: its 40-byte entries down to 24 measured 32.93M -> 32.99M. */
#define VIEW_XY (!VCACHE_BIG || TG_FIXED)
typedef struct view_vertex {
#if VIEW_XY
    tg_real x, y;
#endif
    tg_real w;
    inv_w iw;
    int32_t sx, sy;
    int flags;
} view_vertex;

typedef struct view_frame {
    tg_vec3 eye, rx, ry, rz;      /* clip x = (p - eye) . rx, y = . ry, w = . rz */
    tg_real znear, zfar;
} view_frame;

#if TG_FIXED && !TG_NO_WIDE_CLIP
/* Whether a clip coordinate is past TGI_CLIP_SAFE (2048 units, 2^27 raw):
 * within it, the clipper's differences of two coordinates (< 2^28) and
 * guard-band products 8 w (< 2^30) fit tg_real, and clip_polygon is exact;
 * past it they saturate (a saturated coordinate too: 32767). */
#define TGI_CLIP_SAFE ((int32_t)1 << 27)
static inline int past_clip_safe(tg_real c) { return (uint32_t)c + TGI_CLIP_SAFE > 2u * TGI_CLIP_SAFE; }
#endif

/* Q16.16 (outside size builds): the vertex set-up always inline, down to
 * the triangle's three fetches in tgi_raster_gbuffer.  Left to gcc, some of
 * it went out of line with small changes anywhere in this file (its
 * max-inline-insns-single): view_vertex_make called at a cache miss, or
 * vertex_fetch, or triangle_fetch, each 0.3 to 3M a frame at 320x240
 * (build/bench_raster-fixed, callgrind). */
#if TG_FIXED && !TG_OUTLINE_HELPERS
#define VIEW_VERTEX_INLINE RASTER_INLINE
#else
#define VIEW_VERTEX_INLINE inline
#endif
static VIEW_VERTEX_INLINE view_vertex view_vertex_make(const raster_target *rt, const view_frame *vf, tg_vec3 p)
{
    view_vertex o;
    tg_vec3 d = tgi_v3_sub(p, vf->eye);
    tg_real x = tgi_v3_dot(d, vf->rx), y = tgi_v3_dot(d, vf->ry), w = tgi_v3_dot(d, vf->rz);
    tg_real gw = tg_mul(GUARD_R, w), ngw = tg_neg(gw), nw = tg_neg(w);
#if VIEW_XY
    o.x = x;
    o.y = y;
#endif
    o.w = w;
    o.iw = inverse_w(w);
    o.flags = x >= ngw && x <= gw && y >= ngw && y <= gw && w >= vf->znear && w <= vf->zfar ? V_INSIDE : 0;
    if (x > w) o.flags |= V_RIGHT;                /* each almost never: branches that predict well */
    if (x < nw) o.flags |= V_LEFT;
    if (y > w) o.flags |= V_TOP;
    if (y < nw) o.flags |= V_BOTTOM;
#if TG_FIXED && !TG_NO_WIDE_CLIP
    if (past_clip_safe(x) || past_clip_safe(y) || past_clip_safe(w)) o.flags = 0;
#endif
    o.sx = rt->half_w16 + snap_ndc(x, w, o.iw, rt->half_w16);
    o.sy = rt->half_h16 - snap_ndc(y, w, o.iw, rt->half_h16);
    return o;
}

#if TG_FIXED && !TG_NO_WIDE_CLIP
/* ---- G-buffer triangles clipped in Q16.16 ----
 * A vertex's clip coordinates x = d . right fx, y = d . up fy, w = d .
 * forward (d from the eye) leave Q16.16 (32767) for a vertex more than
 * 32767 / fx units to the side or 32767 deep, and the clipper's
 * differences and guard-band products 8 w leave it sooner: a ground plane
 * of +-20000 seen at 60 degrees, or of +-3000 at 5, clipped to nothing,
 * and the plane vanished.  Such a triangle (a coordinate past
 * TGI_CLIP_SAFE) is clipped here in 64 bits, as
 * clip_polygon clips (near, far, then the guard band; the screen's planes
 * when 8 zfar would not fit), from its world vertices: what is left lies
 * within the band and the depth range, so it fits tg_real again and is
 * drawn as any clipped polygon (tests/test_raster.c
 * far_ground_plane_in_fixed_point).  So is every other triangle that needs
 * clipping (not V_INSIDE): clip_polygon's 16-bit fraction on a +-200
 * floor's 400-unit edges, and the 32-bit view transform of its far
 * vertices, put its depth up to 0.9% off, and sank it under its own shadow
 * rays' start (clipped_ground_plane_depth). */
typedef struct wide_vertex {
    int64_t x, y, w;              /* Q16.16 in 64 bits; z = w (G-buffer mode) */
    tg_vec3 n;
} wide_vertex;

/* (a . b) for a = p - eye exact in 64 bits (|a_i| < 2^32 raw: scene
 * coordinates within +-32767) and a unit axis times a focal length (|b_i|
 * < 2^31): each product is below 2^63, a quarter of it below 2^61, so the
 * three quarters sum without overflow; below 2^48.6 in all. */
static int64_t wide_dot(const int64_t *a, tg_vec3 b)
{
    return tgi_shr_round((a[0] * b.x >> 2) + (a[1] * b.y >> 2) + (a[2] * b.z >> 2), TG_FRAC_BITS - 2);
}

/* The bound under which the clipping below cannot overflow: coordinates
 * below 2^46 raw (2^30 units) keep every difference below 2^47 and every
 * plane distance below 2^50.  Past it (a focal length over 2^14, a field of
 * view under 0.01 degrees, on geometry 30000 units away) the triangle is
 * not drawn. */
#define WIDE_CLIP_MAX ((int64_t)1 << 46)
static int wide_in_range(int64_t v) { return v < WIDE_CLIP_MAX && v > -WIDE_CLIP_MAX; }

static int64_t wide_plane_distance(const clip_ctx *c, const wide_vertex *v, int p, int64_t g)
{
    switch (p) {
    case PL_LEFT: return v->x + g * v->w;
    case PL_RIGHT: return g * v->w - v->x;
    case PL_BOTTOM: return v->y + g * v->w;
    case PL_TOP: return g * v->w - v->y;
    case PL_NEAR: return v->w - c->znear;
    default: return c->zfar - v->w;
    }
}

static void wide_snap_to_plane(const clip_ctx *c, wide_vertex *v, int p, int64_t g)
{
    switch (p) {
    case PL_LEFT: v->x = -g * v->w; break;
    case PL_RIGHT: v->x = g * v->w; break;
    case PL_BOTTOM: v->y = -g * v->w; break;
    case PL_TOP: v->y = g * v->w; break;
    case PL_NEAR: v->w = c->znear; break;
    default: v->w = c->zfar; break;
    }
}

/* a + (b - a) t for t = t31 2^-31 in [0, 1], |b - a| < 2^47: in two
 * products below 2^62 (the high and the low 16 bits of b - a), within a
 * unit of the exact value.  The fraction needs the 31 bits: an edge from
 * behind the eye to 20000 units ahead is 2^46 raw long, and a Q16.16 t
 * would put its clipped point half a unit off (depth 1.4% off). */
static int64_t wide_lerp(int64_t a, int64_t b, int64_t t31)
{
    const int64_t d = b - a, hi = d / 65536, lo = d - hi * 65536;
    return a + tgi_shr_round(hi * t31, 15) + tgi_shr_round(lo * t31, 31);
}

/* din / (din - dout) as t31, din >= 0 > dout (below 2^50 each): both
 * shifted until the divisor is below 2^31, then (din << 31) / divisor
 * rounded, at most 2^31 */
static int64_t wide_fraction(int64_t din, int64_t dout)
{
    int64_t den = din - dout;
    while (den >= ((int64_t)1 << 31)) { din >>= 1; den >>= 1; }
    return ((din << 31) + den / 2) / den;
}

static void gbuffer_wide_triangle(const raster_target *rt, const view_frame *vf, const tg_vec3 *pos, const tg_vec3 *nrm)
{
    static const int order[PL_COUNT] = { PL_NEAR, PL_FAR, PL_LEFT, PL_RIGHT, PL_BOTTOM, PL_TOP };
    /* the guard band where 8 zfar fits tg_real (the far plane within 4095:
     * every G-buffer's default), else the screen's planes (drawn polygons
     * whose vertices lie on the screen's edges come out up to 0.4% off in
     * depth: the guard band's are exact) */
    const int64_t g = rt->clip.zfar <= TG_REAL_MAX / 8 ? 8 : 1;
    wide_vertex a[MAX_POLY], b[MAX_POLY];
    clip_vertex poly[MAX_POLY];
    int k, o, n = 3;
    for (k = 0; k < 3; k++) {
        const int64_t d[3] = { (int64_t)pos[k].x - vf->eye.x, (int64_t)pos[k].y - vf->eye.y, (int64_t)pos[k].z - vf->eye.z };
        a[k].x = wide_dot(d, vf->rx);
        a[k].y = wide_dot(d, vf->ry);
        a[k].w = wide_dot(d, vf->rz);
        a[k].n = nrm ? nrm[k] : tg_v3(0, 0, 0);
        if (!wide_in_range(a[k].x) || !wide_in_range(a[k].y) || !wide_in_range(a[k].w)) return;
    }
    for (o = 0; o < PL_COUNT && n > 0; o++) {
        int i, m = 0, p = order[o];
        for (i = 0; i < n; i++) {
            const wide_vertex *va = &a[i], *vb = &a[i + 1 == n ? 0 : i + 1];
            int64_t da = wide_plane_distance(&rt->clip, va, p, g), db = wide_plane_distance(&rt->clip, vb, p, g);
            if (da >= 0) b[m++] = *va;
            if ((da >= 0) != (db >= 0) && m < MAX_POLY) {
                const wide_vertex *in = da >= 0 ? va : vb, *out = da >= 0 ? vb : va;
                const int64_t din = da >= 0 ? da : db, dout = da >= 0 ? db : da;
                const int64_t t31 = wide_fraction(din, dout);
                b[m].x = wide_lerp(in->x, out->x, t31);
                b[m].y = wide_lerp(in->y, out->y, t31);
                b[m].w = wide_lerp(in->w, out->w, t31);
                b[m].n = tgi_v3_lerp(in->n, out->n, (tg_real)((t31 + (1 << 14)) >> 15));
                wide_snap_to_plane(&rt->clip, &b[m], p, g);
                m++;
            }
        }
        n = m;
        memcpy(a, b, (size_t)n * sizeof *a);
    }
    for (k = 0; k < n; k++) {   /* within the band and the depth range: tg_real again */
        poly[k].x = tgi_sat64(a[k].x);
        poly[k].y = tgi_sat64(a[k].y);
        poly[k].z = poly[k].w = tgi_sat64(a[k].w);
        poly[k].n = a[k].n;
    }
    if (n >= 3) draw_polygon(rt, poly, n);
}
#endif

/* Neighbouring triangles of a mesh share vertices (a triangle strip reuses
 * two of every three): a direct-mapped cache keyed by the position's bits
 * gives back the same view_vertex without transforming it again.  A hit
 * is the entry view_vertex_make made from the same bits: the same vertex
 * whatever the cache's size or hash.
 * On a 64-bit host outside size builds (VCACHE_BIG) it has 2048 entries
 * in float (64 KB of stack), 1024 in Q16.16 (52 KB): a grid of quads, row
 * by row (a tessellated sphere's rings), meets each vertex again a row
 * later, after a row's worth of others, which 16 entries never keep
 * (bench_raster's sphere of 224 slices: 56,285 transforms a frame for
 * 25,203 vertices; 33,941 with 1024, 30,009 with 2048: callgrind
 * bench_raster 320x240 25.08M -> 24.63M a frame, 1280x720 56.27M ->
 * 55.82M; Q16.16's 2048 would take 104 KB, near musl's 128 KB thread
 * stacks, for 32.93M -> 32.17M and 81.65M -> 80.89M).  Its hash and keys are 64-bit,
 * x and y in one word (two multiplies and a compare fewer than three
 * 32-bit keys).  (The 32-bit hash sum(k_i c_i), c_i odd, put (x, y, z)
 * and (-x, y, -z), a ring's opposite points, on one entry: the two sign
 * flips each add 2^31; 49,842 transforms with 1024 entries.) */
#if VCACHE_BIG   /* vertex_fetch's key: x, y the first 8 bytes of a tg_vec3 */
typedef char vcache_key_xy_check[offsetof(tg_vec3, y) == sizeof(tg_real) && sizeof(tg_real) == 4 ? 1 : -1];
#endif
typedef struct vertex_cache {
#if VCACHE_BIG
    uint64_t key_xy[1 << VCACHE_BITS];
    uint32_t key_z[1 << VCACHE_BITS];
#else
    uint32_t key[1 << VCACHE_BITS][3];
#endif
    view_vertex v[1 << VCACHE_BITS];
} vertex_cache;

static inline uint32_t real_bits(tg_real r)
{
#if TG_FIXED
    return (uint32_t)r;
#else
    union { float f; uint32_t u; } b;
    b.f = r;
    return b.u;
#endif
}

/* Every entry starts as the origin, transformed: a hit is always right. */
static void vertex_cache_init(vertex_cache *c, const raster_target *rt, const view_frame *vf)
{
    view_vertex o = view_vertex_make(rt, vf, tg_v3(0, 0, 0));
    uint32_t z = real_bits(0);
    int i;
    for (i = 0; i < 1 << VCACHE_BITS; i++) {
#if VCACHE_BIG
        c->key_xy[i] = (uint64_t)z << 32 | z;
        c->key_z[i] = z;
        c->v[i] = o;
#else
        c->key[i][0] = c->key[i][1] = c->key[i][2] = z;
        c->v[i] = o;
#endif
    }
}

/* One triangle's vertices as the drawing code takes them. */
typedef struct tri_vertices {
    clip_vertex v[3];
    int32_t sx[3], sy[3];
    inv_w iw[3];
    int flags;                    /* V_* of all three: V_INSIDE if all are inside, V_RIGHT.. if all are beyond */
} tri_vertices;

/* The view_vertex of *pp, from the cache or made there: a copy (the next
 * look-up may take its entry).  The position by pointer, read again at a
 * miss: passed by value, gcc kept its words on the stack through every hit
 * for the miss's call (callgrind bench_draw a frame: float 1280x720 48.42M
 * -> 48.27M, 320x240 21.51M -> 21.36M; Q16.16 76.844M and 31.06M, within
 * 0.002M). */
static VIEW_VERTEX_INLINE view_vertex vertex_lookup(vertex_cache *c, const raster_target *rt, const view_frame *vf,
                                                   const tg_vec3 *pp)
{
    const tg_vec3 p = *pp;
#if VCACHE_BIG
    /* x and y's bits as one 64-bit word through a union (C99 reads the
     * bytes stored; vcache_key_xy_check: no padding between them): on a
     * little-endian host the word ky << 32 | kx it replaces, so the same
     * entries, without two 32-bit loads, a shift and an or a vertex
     * (callgrind bench_raster, bench_draw a frame: float 320x240 24.20M ->
     * 23.55M, 1280x720 55.57M -> 54.93M; Q16.16 32.52M -> 32.30M, 81.15M
     * -> 80.94M); on a big-endian one x, y swap halves, other entries, and
     * a hit is the same vertex whatever the hash.  (memcpy was a call at
     * -ffreestanding: 26.50M.) */
    union { tg_vec3 v; uint64_t xy; } key;
    uint64_t kxy;
    uint32_t kz, h;
    const view_vertex *o;
    key.v = p;
    kxy = key.xy;
    kz = real_bits(p.z);
    h = (uint32_t)((kxy * 0x9E3779B97F4A7C15u + kz * 0x85EBCA77C2B2AE63u) >> (64 - VCACHE_BITS));
    o = &c->v[h];
    if (c->key_xy[h] != kxy || c->key_z[h] != kz) {
        c->key_xy[h] = kxy; c->key_z[h] = kz;
        c->v[h] = view_vertex_make(rt, vf, *pp);
    }
#else
    uint32_t kx = real_bits(p.x), ky = real_bits(p.y), kz = real_bits(p.z);
    uint32_t h = (kx * 0x9E3779B1u + ky * 0x85EBCA77u + kz * 0xC2B2AE3Du) >> (32 - VCACHE_BITS);
    const view_vertex *o = &c->v[h];
    if (c->key[h][0] != kx || c->key[h][1] != ky || c->key[h][2] != kz) {
        c->key[h][0] = kx; c->key[h][1] = ky; c->key[h][2] = kz;
        c->v[h] = view_vertex_make(rt, vf, *pp);
    }
#endif
    return *o;
}

/* Vertex k of tv from its view_vertex o. */
static inline void tri_vertex_set(tri_vertices *tv, int k, const view_vertex *o)
{
#if VIEW_XY
    tv->v[k].x = o->x;
    tv->v[k].y = o->y;
#endif
    tv->v[k].z = tv->v[k].w = o->w;
    tv->sx[k] = o->sx;
    tv->sy[k] = o->sy;
    tv->iw[k] = o->iw;
}

#if TGI_RASTER_BACK_LAYER   /* (further_layer's; the G-buffer's loop keeps a triangle's vertices as values until it is drawn) */
/* Vertex k of tv: the view_vertex of p, from the cache or made there. */
static VIEW_VERTEX_INLINE void vertex_fetch(vertex_cache *c, const raster_target *rt, const view_frame *vf, tg_vec3 p,
                                tri_vertices *tv, int k)
{
    const view_vertex o = vertex_lookup(c, rt, vf, &p);
    tri_vertex_set(tv, k, &o);
    tv->flags &= o.flags;
}

/* Triangle t's three vertices, through the cache. */
static VIEW_VERTEX_INLINE void triangle_fetch(vertex_cache *c, const raster_target *rt, const view_frame *vf,
                                  const tgi_raster_mesh *mesh, int t, tri_vertices *tv)
{
    tv->flags = ~0;
    vertex_fetch(c, rt, vf, mesh->pos[3 * t], tv, 0);
    vertex_fetch(c, rt, vf, mesh->pos[3 * t + 1], tv, 1);
    vertex_fetch(c, rt, vf, mesh->pos[3 * t + 2], tv, 2);
}
#endif

/* The clip-space x, y of tv's vertices (at pos) for the clipper: as
 * view_vertex_make finds them, the same bits. */
static void tri_clip_xy(const view_frame *vf, const tg_vec3 *pos, tri_vertices *tv)
{
#if !VIEW_XY
    int k;
    for (k = 0; k < 3; k++) {
        tg_vec3 d = tgi_v3_sub(pos[k], vf->eye);
        tv->v[k].x = tgi_v3_dot(d, vf->rx);
        tv->v[k].y = tgi_v3_dot(d, vf->ry);
    }
#else
    (void)vf; (void)pos; (void)tv;
#endif
}

#if TGI_RASTER_BACK_LAYER
/* Triangle t into the back-face layer (rt->dout.back): a one-sided
 * triangle facing away, or either face of a twosided one (a sheet is its
 * own back); the nearest such depth is kept.  front, area2: its facing and
 * signed area when all its vertices are inside (tv->flags & V_INSIDE). */
static void back_triangle(raster_target *rt, const view_frame *vf, const tg_vec3 *pos, tri_vertices *tv, int front,
                          int64_t area2)
{
    static const int order_front[3] = { 0, 2, 1 }, order_back[3] = { 0, 1, 2 };
#if TG_FIXED && !TG_NO_WIDE_CLIP
    if (!(tv->flags & V_INSIDE)) {               /* as gbuffer_triangle */
        rt->back_layer = 1;
        gbuffer_wide_triangle(rt, vf, pos, NULL);
        rt->back_layer = 0;
        return;
    }
#endif
    if ((tv->flags & V_INSIDE) && area2 == 0) return;   /* zero area */
    rt->back_layer = 1;
    if (!(tv->flags & V_INSIDE)) {
        tv->v[0].n = tv->v[1].n = tv->v[2].n = tg_v3(0, 0, 0);   /* the clipper carries them along */
        tri_clip_xy(vf, pos, tv);
        draw_clip_tri(rt, tv->v, NULL);
    }
    else if (!front || !rt->cull_back)
        draw_snapped(rt, tv->v, NULL, tv->sx, tv->sy, tv->iw, front ? order_front : order_back,
                     front ? -area2 : area2, 0);
    rt->back_layer = 0;
}
#endif

/* Triangle t of tgi_raster_gbuffer, neither off a side nor culled:
 * twosided its material's, front its facing and area2 its signed area when
 * all its vertices are inside (tv->flags & V_INSIDE). */
static RASTER_INLINE void gbuffer_triangle_drawn(raster_target *rt, const view_frame *vf, tri_vertices *tv,
                                                 const tgi_raster_mesh *mesh, int t, int twosided, int front,
                                                 int64_t area2)
{
    static const int order_front[3] = { 0, 2, 1 }, order_back[3] = { 0, 1, 2 };
    rt->material = mesh->tri_material[t];
    rt->cull_back = !twosided;
    rt->flip_back = twosided;
    rt->object = mesh->tri_object ? mesh->tri_object[t] : 0;
    rt->tri_nrm = mesh->nrm + 3 * t;
#if TG_FIXED && !TG_NO_WIDE_CLIP
    if (!(tv->flags & V_INSIDE)) {               /* clipped: in 64 bits (gbuffer_wide_triangle) */
        gbuffer_wide_triangle(rt, vf, mesh->pos + 3 * t, rt->tri_nrm);
        return;
    }
#endif
    if (tv->flags & V_INSIDE)
        draw_snapped(rt, tv->v, rt->tri_nrm, tv->sx, tv->sy, tv->iw, front ? order_front : order_back,
                     front ? -area2 : area2, !front && twosided);
    else {
        tri_clip_xy(vf, mesh->pos + 3 * t, tv);
        draw_clip_tri(rt, tv->v, rt->tri_nrm);
    }
}

#if TGI_RASTER_BACK_LAYER
/* Every triangle into a further layer (rt->dout.back, or .behind), once
 * the layer before it is final: with cull, a one-sided triangle's back
 * face only (the second layer: where a closed object ends), else either
 * face (the third: any surface behind the back face); back_triangle skips
 * zero areas and culled faces. */
static void further_layer(raster_target *rt, vertex_cache *cache, const view_frame *vf, const tgi_raster_mesh *mesh,
                          int cull)
{
    int t;
    for (t = 0; t < mesh->tri_count; t++) {
        tri_vertices tv;
        int64_t area2;
        triangle_fetch(cache, rt, vf, mesh, t, &tv);
        if (tv.flags & V_OFF_SIDE) continue;
        rt->cull_back = cull && !mesh->materials[mesh->tri_material[t]].twosided;
        area2 = tv.flags & V_INSIDE ? signed_area2(tv.sx, tv.sy) : 0;
        back_triangle(rt, vf, mesh->pos + 3 * t, &tv, area2 < 0, area2);
    }
}
#endif

void tgi_raster_gbuffer(tgi_gbuffer *gb, const tgi_view *view, const tgi_raster_mesh *mesh, int y0, int y1)
{
    /* the mesh's fields read once (the loop's stores, to the G-buffer,
     * would otherwise have them read again every triangle) */
    const tg_vec3 *const mesh_pos = mesh->pos;
    const uint16_t *const tri_material = mesh->tri_material;
    const tgi_material *const materials = mesh->materials;
    const int tri_count = mesh->tri_count;
    raster_target rt;
    view_frame vf;
    vertex_cache cache;
    int t;
    memset(&rt, 0, sizeof rt);
    if (!target_rows(&rt, gb->width, gb->height, y0, y1)) return;
    rt.clip.mode = MODE_GBUFFER;
    rt.clip.znear = view->znear > 0 ? view->znear : TG_EPS;
    rt.clip.zfar = view->zfar > rt.clip.znear ? view->zfar : tg_add(rt.clip.znear, TG_ONE);
    rt.gb = gb;
    vf.eye = view->eye;
    vf.rx = tgi_v3_scale(view->right, view->focal_x);
    vf.ry = tgi_v3_scale(view->up, view->focal_y);
    vf.rz = view->forward;
    vf.znear = rt.clip.znear;
    vf.zfar = rt.clip.zfar;
    vertex_cache_init(&cache, &rt, &vf);
    for (t = 0; t < tri_count; t++) {
        /* Triangle t: reject, cull, draw (clipped if needed).  Its vertices
         * as values until it is drawn: a culled one (most back faces of a
         * closed mesh) writes nothing. */
        const tg_vec3 *pos = mesh_pos + 3 * t;
        const view_vertex a = vertex_lookup(&cache, &rt, &vf, &pos[0]), b = vertex_lookup(&cache, &rt, &vf, &pos[1]),
                          c = vertex_lookup(&cache, &rt, &vf, &pos[2]);
        tri_vertices tv;
        int twosided, front = 0;
        int64_t area2 = 0;
        tv.flags = a.flags & b.flags & c.flags;
        if (tv.flags & V_OFF_SIDE) continue;      /* wholly off one side of the screen */
        twosided = materials[tri_material[t]].twosided;
        if (tv.flags & V_INSIDE) {
            const int32_t sx[3] = { a.sx, b.sx, c.sx }, sy[3] = { a.sy, b.sy, c.sy };
            area2 = signed_area2(sx, sy);
            front = area2 < 0;                    /* counter-clockwise as seen, y down */
            if (area2 == 0 || (!front && !twosided)) continue;   /* zero area, culled */
        }
        tri_vertex_set(&tv, 0, &a);
        tri_vertex_set(&tv, 1, &b);
        tri_vertex_set(&tv, 2, &c);
        gbuffer_triangle_drawn(&rt, &vf, &tv, mesh, t, twosided, front, area2);
    }
#if TGI_RASTER_BACK_LAYER
    /* the second layer, once these rows' depth is final: the back faces at
     * or behind it */
    if (!gb->back_depth) return;
    rt.dout.back = gb->back_depth;
    rt.dout.front = gb->depth;
    further_layer(&rt, &cache, &vf, mesh, 1);
    /* the third layer, once these rows' back faces are all drawn: every
     * triangle, either facing, beyond the back face */
    if (!gb->behind_depth) return;
    rt.dout.behind = gb->behind_depth;
    further_layer(&rt, &cache, &vf, mesh, 0);
#endif
}

#if TGI_RASTER_DEPTH
/* Depth-only rows into rt (set up by the callers below). */
static void raster_depth_rows(raster_target *rt, const tgi_mat4 *world_to_clip, int orthographic,
                              const tg_vec3 *pos, int tri_count)
{
    const tg_real *m = world_to_clip->m;
    tg_vec3 r0 = tg_v3(m[0], m[1], m[2]), r1 = tg_v3(m[4], m[5], m[6]);
    tg_vec3 r2 = tg_v3(m[8], m[9], m[10]), r3 = tg_v3(m[12], m[13], m[14]);
    int t, k;
    rt->clip.mode = orthographic ? MODE_ORTHO : MODE_PERSPECTIVE;
    if (!orthographic) {
        /* a perspective map's z row is alpha w + beta: its near plane (z = -w)
         * at w = -beta / (alpha + 1); clipped a TG_SHADOW_CLIP_DIVISOR-th of
         * that from the light, what lies nearer than the near plane is drawn
         * at the nearest depth code and shadows (no light leaks past it) */
        tg_real alpha = tg_div(tgi_v3_dot(r2, r3), tg_max(tgi_v3_dot(r3, r3), TG_EPS));
        tg_real beta = tg_sub(m[11], tg_mul(alpha, m[15]));
        tg_real n = tg_div(tg_neg(beta), tg_max(tg_add(alpha, TG_ONE), TG_EPS));
        rt->clip.znear = tg_max(tg_div(n, tg_from_int(TG_SHADOW_CLIP_DIVISOR)), TG_EPS);
    }
    for (t = 0; t < tri_count; t++) {
        clip_vertex v[3];
        for (k = 0; k < 3; k++) {
            tg_vec3 p = pos[3 * t + k];
            v[k].x = tg_add(tgi_v3_dot(p, r0), m[3]);
            v[k].y = tg_add(tgi_v3_dot(p, r1), m[7]);
            v[k].z = tg_add(tgi_v3_dot(p, r2), m[11]);
            v[k].w = orthographic ? TG_ONE : tg_add(tgi_v3_dot(p, r3), m[15]);
            v[k].n = tg_v3(0, 0, 0);
        }
        draw_clip_tri(rt, v, NULL);
    }
}

void tgi_raster_depth(tg_real *depth, int width, int height, const tgi_mat4 *world_to_clip,
                     int orthographic, const tg_vec3 *pos, int tri_count, int y0, int y1)
{
    raster_target rt;
    memset(&rt, 0, sizeof rt);
    if (!target_rows(&rt, width, height, y0, y1)) return;
    rt.dout.d32 = depth;
    raster_depth_rows(&rt, world_to_clip, orthographic, pos, tri_count);
}

void tgi_raster_depth16(uint16_t *depth, int width, int height, const tgi_mat4 *world_to_clip,
                       int orthographic, tg_real depth_lo, tg_real depth_range,
                       const tg_vec3 *pos, int tri_count, int y0, int y1)
{
    raster_target rt;
    memset(&rt, 0, sizeof rt);
    if (!(depth_range > 0) || !target_rows(&rt, width, height, y0, y1)) return;
    rt.dout.d16 = depth;
    rt.dout.lo = depth_lo;
#if TG_FIXED
    rt.dout.range = depth_range;
    rt.dout.recip = (((int64_t)1 << 48) + depth_range / 2) / depth_range;
#else
    rt.dout.scale = 65536.0f / depth_range;
#endif
    raster_depth_rows(&rt, world_to_clip, orthographic, pos, tri_count);
}
#endif /* TGI_RASTER_DEPTH */
