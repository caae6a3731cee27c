/* SPDX-License-Identifier: MIT */
/*
 * pushpull.c - push/pull hole filling (Kraus 2009; HBIL sec. 3.2).
 * Level 0 is the caller's image with weights 1 (a value) or 0 (a hole);
 * levels 1.. live in the scratch.  See pushpull.h.
 */
#include "../tinygi.h"
#include "pushpull.h"

#if !TG_NO_COLOR /* the whole file is left out with TG_NO_COLOR=1 (tinygi.h "FEATURE SWITCHES") */

#define MAX_LEVELS 32

#if TG_WIDE_STORAGE
typedef tg_real pp_weight;
static tg_real weight_get(const pp_weight *w, size_t i) { return w[i]; }
static void weight_set(pp_weight *w, size_t i, tg_real v) { w[i] = v; }
#else
typedef uint8_t pp_weight;
static tg_real weight_get(const pp_weight *w, size_t i) { return tgi_unorm8_unpack(w[i]); }
static void weight_set(pp_weight *w, size_t i, tg_real v) { w[i] = tgi_unorm8_pack(v); }
#endif

typedef struct pp_level {
    int w, h;
    tgi_rgb c;          /* mean colour of the valid texels below */
    pp_weight *wt;      /* their weight, clamped to 1 */
} pp_level;

static int half_up(int n) { return (n + 1) / 2; }

/* Bytes of one level of n texels (16-byte aligned parts, as level_carve
 * lays them); *overflow set on overflow. */
static size_t level_bytes(size_t n, int *overflow)
{
    size_t c, w;
    if (tg_size_mul(n, TGI_RGB_PIXEL_BYTES, &c) || tg_size_mul(n, sizeof(pp_weight), &w) ||
        tg_size_add(c, 15, &c) || tg_size_add(w, 15, &w) || tg_size_add(c & ~(size_t)15, w & ~(size_t)15, &c)) {
        *overflow = 1;
        return 0;
    }
    return c;
}

/* Point level l's planes at `base` (n texels). */
static void level_carve(pp_level *l, unsigned char *base, size_t n)
{
    l->wt = (pp_weight *)(void *)(base + tgi_rgb_carve(&l->c, n, base));
}

/* The chain of a w x h image: levels 1.. (count returned), carved from
 * scratch when given; *bytes their size. */
static int levels_layout(int w, int h, unsigned char *scratch, pp_level *lv, size_t *bytes)
{
    size_t total = 0;
    int n = 0, overflow = 0;
    while ((w > 1 || h > 1) && n < MAX_LEVELS) {
        size_t texels, b;
        w = half_up(w);
        h = half_up(h);
        texels = (size_t)w * (size_t)h;
        b = level_bytes(texels, &overflow);
        if (lv) {
            lv[n].w = w;
            lv[n].h = h;
            if (scratch) level_carve(&lv[n], scratch + total, texels);
        }
        if (overflow || tg_size_add(total, b, &total)) { *bytes = SIZE_MAX; return 0; }
        n++;
    }
    *bytes = total;
    return n;
}

size_t tgi_pushpull_bytes(int w, int h)
{
    size_t bytes;
    if (w < 0 || h < 0) return SIZE_MAX;
    levels_layout(w, h, NULL, NULL, &bytes);
    return bytes;
}

/* Texel t of a colour plane as tgi_rgb_get reads it; the levels are never
 * lit (tgi_rgb_carve), so the common case is the stored word decoded inline. */
static inline tg_vec3 texel(const tgi_rgb *c, size_t t)
{
    return c->lit ? tgi_rgb_get(c, t) : tgi_rgb_stored(c, t);
}
/* Texel t of a level (1..): never lit (tgi_rgb_carve gives no light), the
 * stored word decoded. */
static inline tg_vec3 level_texel(const tgi_rgb *c, size_t t) { return tgi_rgb_stored(c, t); }

/* A running sum's next term w v for a weight w within [0, 1] and a value
 * v >= 0: tgi_wide_add_weighted (core/real.h) without its test that they
 * are (stored colour planes, RGB9E5, decode to values >= 0; each use says
 * why its weights lie in [0, 1]); with tg_real planes (TG_WIDE_STORAGE)
 * and in float tgi_wide_add_weighted itself. */
#if TG_FIXED && !TG_WIDE_STORAGE
static inline tgi_wide add_weighted_nonneg(tgi_wide acc, tg_real w, tg_real v)
{
    return acc + (((int64_t)w * v + 32768) >> 16);
}
#else
#define add_weighted_nonneg tgi_wide_add_weighted
#endif
/* push_tap_wide's sums: float (the same additions, in tgi_wide: float) and
 * Q16.16 over RGB9E5 planes (texels >= 0); not when compiling for size. */
#define PP_BOX_WIDE ((!TG_FIXED || !TG_WIDE_STORAGE) && !TG_OUTLINE_HELPERS)

/* One tap of the 2x2 box: the finer texel t added to *s with its weight
 * (level 0, wt NULL: 1 for a value, skipped for a hole). */
#if defined(__GNUC__)
__attribute__((always_inline))   /* all four taps inline in push_level (gcc inlined some) */
#endif
static inline void push_tap(const tgi_rgb *c, const pp_weight *wt, size_t t, tg_vec3 *s, tg_real *sw)
{
    tg_real wf = TG_ONE;
    if (wt) {
        wf = weight_get(wt, t);
        *s = tgi_v3_add(*s, tgi_v3_scale(texel(c, t), wf));
    } else if (tgi_rgb_is_hole(c, t)) {
        return;
    } else {
        *s = tgi_v3_add(*s, texel(c, t));
    }
    *sw = tg_add(*sw, wf);
}

#if PP_BOX_WIDE
/* push_tap over an unlit plane, its stored words decoded inline.  Float:
 * the same additions and products in the same order.  Q16.16: the texels
 * (RGB9E5) are >= 0 and the weights (unorm8) within [0, 1], so each term
 * tg_add adds is >= 0 (tg_mul's product of such a pair lies within [0, v],
 * unsaturated) and the sums only grow: saturating at each step gives
 * min(MAX, the exact sum), what one saturation of the unsaturated sum
 * gives (push_level's tgi_wide_real).  The weights' sum is at most 4. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void push_tap_wide(const tgi_rgb *c, const pp_weight *wt, size_t t, tgi_wide s[3], tg_real *sw)
{
    tg_vec3 v;
    if (wt) {
        const tg_real wf = weight_get(wt, t);
        v = tgi_rgb_stored(c, t);
        s[0] = add_weighted_nonneg(s[0], wf, v.x);
        s[1] = add_weighted_nonneg(s[1], wf, v.y);
        s[2] = add_weighted_nonneg(s[2], wf, v.z);
        *sw += wf;
    } else if (!tgi_rgb_is_hole(c, t)) {
        v = tgi_rgb_stored(c, t);
        s[0] += v.x;
        s[1] += v.y;
        s[2] += v.z;
        *sw += TG_ONE;
    }
}
#endif

/* tg_div(TG_ONE, sw) for the box's weight sum sw > 0.  Stored 8-bit
 * weights (tgi_unorm8_unpack: at least 257 raw in Q16.16 where not 0) and
 * level 0's 1s make sw at least 257 raw, so 2^32 / sw fits: tgi_div_pos,
 * tg_div's rounding without its tests; tg_real weights (TG_WIDE_STORAGE)
 * may be smaller: tg_div. */
static inline tg_real inv_weight(tg_real sw)
{
#if TG_WIDE_STORAGE
    return tg_div(TG_ONE, sw);
#else
    return tgi_div_pos(TG_ONE, sw);
#endif
}

/* Push one level: a 2x2 box over the weighted texels of the finer w x h
 * level, its values c and weights wt.  Level 0, the image, has no weights
 * (wt NULL): a value weighs 1, a hole 0, and the value enters unscaled.
 * The taps in the order (0,0) (1,0) (0,1) (1,1); those past the finer
 * level's last row or column are left out.  Coarse rows [cy0, cy1). */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
__attribute__((always_inline))   /* a copy for level 0 (wt NULL) and one for the weighted levels */
#endif
static inline void push_level_of(const tgi_rgb *c, const pp_weight *wt, int w, int h, const pp_level *coarse, int cy0,
                                 int cy1)
{
    int x, y;
#if PP_BOX_WIDE && TG_FIXED
    const tg_real inv_n[5] = { 0, tg_div(TG_ONE, TG_ONE), tg_div(TG_ONE, 2 * TG_ONE), tg_div(TG_ONE, 3 * TG_ONE),
                               tg_div(TG_ONE, 4 * TG_ONE) };   /* tg_div(TG_ONE, sw) for sw = n TG_ONE */
#endif
    for (y = cy0; y < cy1; y++) {
        size_t r0 = (size_t)(2 * y) * (size_t)w, r1 = r0 + (size_t)w, o = (size_t)y * (size_t)coarse->w;
        int second_row = 2 * y + 1 < h;
        for (x = 0; x < coarse->w; x++, o++) {
            tg_vec3 s = tg_v3(0, 0, 0);
            tg_real sw = 0;
            size_t fx = (size_t)(2 * x);
            int second_column = 2 * x + 1 < w;
#if PP_BOX_WIDE
            if (!c->lit) {
                tgi_wide sum[3] = { 0, 0, 0 };
                push_tap_wide(c, wt, r0 + fx, sum, &sw);
                if (second_column) push_tap_wide(c, wt, r0 + fx + 1, sum, &sw);
                if (second_row) {
                    push_tap_wide(c, wt, r1 + fx, sum, &sw);
                    if (second_column) push_tap_wide(c, wt, r1 + fx + 1, sum, &sw);
                }
                s = tg_v3(tgi_wide_real(sum[0]), tgi_wide_real(sum[1]), tgi_wide_real(sum[2]));
#if TG_FIXED
                if (!wt && sw > 0) {
                    /* level 0 in Q16.16 (float's division and products
                     * test nothing): sw = n TG_ONE for the n values among
                     * the taps, so the mean's 1 / sw is inv_n[n] and its
                     * weight min(sw, 1) is 1; s >= 0 and 1 / n <= 1, so
                     * each product lies within [0, s] (tgi_mul_in_range) */
                    const tg_real inv = inv_n[sw >> 16];
                    tgi_rgb_set(&coarse->c, o, tg_v3(tgi_mul_in_range(s.x, inv), tgi_mul_in_range(s.y, inv),
                                                     tgi_mul_in_range(s.z, inv)));
                    weight_set(coarse->wt, o, TG_ONE);
                    continue;
                }
#endif
            } else
#endif
            {
                push_tap(c, wt, r0 + fx, &s, &sw);
                if (second_column) push_tap(c, wt, r0 + fx + 1, &s, &sw);
                if (second_row) {
                    push_tap(c, wt, r1 + fx, &s, &sw);
                    if (second_column) push_tap(c, wt, r1 + fx + 1, &s, &sw);
                }
            }
            if (sw > 0) {
                tgi_rgb_set(&coarse->c, o, tgi_v3_scale(s, inv_weight(sw)));   /* weighted mean */
                weight_set(coarse->wt, o, tg_min(sw, TG_ONE));                     /* Kraus: clamped to 1 */
            } else {
                tgi_rgb_set(&coarse->c, o, tg_v3(0, 0, 0));
                weight_set(coarse->wt, o, 0);
            }
        }
    }
}

static void push_level(const tgi_rgb *c, const pp_weight *wt, int w, int h, const pp_level *coarse, int cy0, int cy1)
{
    push_level_of(c, wt, w, h, coarse, cy0, cy1);
}
#if !TG_OUTLINE_HELPERS
static void push_level0(const tgi_rgb *c, int w, int h, const pp_level *coarse, int cy0, int cy1)
{
    push_level_of(c, NULL, w, h, coarse, cy0, cy1);
}
#else
#define push_level0(c, w, h, coarse, cy0, cy1) push_level(c, NULL, w, h, coarse, cy0, cy1)
#endif

/* Bilinear samples of a coarse level at the centres of one row y of the
 * finer level: fine centre (x + 0.5) / 2 - 0.5 in coarse texel units, so
 * the taps are coarse columns (x - 1) >> 1 and the one after (clamped to
 * the level), weights 0.75 / 0.25 by parity.  Fine texels 2k + 1 and
 * 2k + 2 read the same four coarse texels: they are decoded once. */
typedef struct pp_row_sampler {
    const pp_level *coarse;
    size_t r0, r1;            /* the two coarse rows' first texels */
    tg_real wxy[2][2][2];     /* [x parity][x tap][y tap]: wx * wy */
    int cx;                   /* the column whose texels q holds; -2: none */
    tg_vec3 q[4];             /* (x0,y0) (x1,y0) (x0,y1) (x1,y1) */
} pp_row_sampler;

static void row_sampler_start(pp_row_sampler *rs, const pp_level *coarse, int y)
{
    int cy = (y - 1) >> 1, p, k;
    int y0 = cy < 0 ? 0 : cy, y1 = cy + 1 >= coarse->h ? coarse->h - 1 : cy + 1;
    tg_real fy = (y & 1) ? TG_R(0.25f) : TG_R(0.75f), wy[2];
    wy[0] = tg_sub(TG_ONE, fy); wy[1] = fy;
    rs->coarse = coarse;
    rs->r0 = (size_t)y0 * (size_t)coarse->w;
    rs->r1 = (size_t)y1 * (size_t)coarse->w;
    for (p = 0; p < 2; p++) {
        tg_real fx = p ? TG_R(0.25f) : TG_R(0.75f), wx[2];
        wx[0] = tg_sub(TG_ONE, fx); wx[1] = fx;
        for (k = 0; k < 4; k++) rs->wxy[p][k & 1][k >> 1] = tg_mul(wx[k & 1], wy[k >> 1]);
    }
    rs->cx = -2;
}

/* One channel's bilinear sum of the four taps (x0,y0) (x1,y0) (x0,y1)
 * (x1,y1), in that order, with their weights w0..w3 (written out: a loop
 * over the taps cost cornell's fill 20% more). */
static inline tgi_wide taps4(tg_real w0, tg_real w1, tg_real w2, tg_real w3, tg_real v0, tg_real v1, tg_real v2,
                             tg_real v3)
{
    tgi_wide acc = add_weighted_nonneg(0, w0, v0);
    acc = add_weighted_nonneg(acc, w1, v1);
    acc = add_weighted_nonneg(acc, w2, v2);
    return add_weighted_nonneg(acc, w3, v3);
}

#if defined(__GNUC__)
__attribute__((always_inline))   /* inline in the fill and pull loops, as before its sums grew */
#endif
static inline tg_vec3 row_sample(pp_row_sampler *rs, int x)
{
    int cx = (x - 1) >> 1, p = x & 1;
    const tg_real w0 = rs->wxy[p][0][0], w1 = rs->wxy[p][1][0], w2 = rs->wxy[p][0][1], w3 = rs->wxy[p][1][1];
    tgi_wide ox, oy, oz;
    if (cx != rs->cx) {
        const tgi_rgb *c = &rs->coarse->c;
        size_t x0 = (size_t)(cx < 0 ? 0 : cx), x1 = (size_t)(cx + 1 >= rs->coarse->w ? rs->coarse->w - 1 : cx + 1);
        rs->q[0] = level_texel(c, rs->r0 + x0);
        rs->q[1] = level_texel(c, rs->r0 + x1);
        rs->q[2] = level_texel(c, rs->r1 + x0);
        rs->q[3] = level_texel(c, rs->r1 + x1);
        rs->cx = cx;
    }
    /* the bilinear weights within [0, 1] (products of 0.25 and 0.75 or
     * their complements), the levels' texels unlit: running sums of
     * add_weighted_nonneg */
    ox = taps4(w0, w1, w2, w3, rs->q[0].x, rs->q[1].x, rs->q[2].x, rs->q[3].x);
    oy = taps4(w0, w1, w2, w3, rs->q[0].y, rs->q[1].y, rs->q[2].y, rs->q[3].y);
    oz = taps4(w0, w1, w2, w3, rs->q[0].z, rs->q[1].z, rs->q[2].z, rs->q[3].z);
    return tg_v3(tgi_wide_real(ox), tgi_wide_real(oy), tgi_wide_real(oz));
}

/* tg_lerp(a, b, t) for a, b within [0, TG_REAL_MAX] and t within [0, 1]:
 * in Q16.16 over RGB9E5 levels (texels >= 0, row_sample's sums too) b - a
 * is within range, the product (b - a) t rounds to within |b - a| and a
 * plus it lies between a and b, so none of tg_sub's, tg_mul's and tg_add's
 * saturations acts: the same integers without their tests. */
static inline tg_real lerp_level(tg_real a, tg_real b, tg_real t)
{
#if TG_FIXED && !TG_WIDE_STORAGE
    return (tg_real)(a + tgi_shr_round(((int64_t)b - a) * t, 16));
#else
    return tg_lerp(a, b, t);
#endif
}

/* Pull one level, its rows [y0, y1): complete texels of weight < 1 from
 * the coarser level. */
static void pull_level(const pp_level *fine, const pp_level *coarse, int y0, int y1)
{
    int x, y;
    pp_row_sampler rs;
    for (y = y0; y < y1; y++) {
        size_t t = (size_t)y * (size_t)fine->w;
        row_sampler_start(&rs, coarse, y);
        for (x = 0; x < fine->w; x++, t++) {
            tg_real wt = weight_get(fine->wt, t);
            tg_vec3 c, up;
            if (wt >= TG_ONE) continue;
            c = level_texel(&fine->c, t);
            up = row_sample(&rs, x);
            c = tg_v3(lerp_level(up.x, c.x, wt), lerp_level(up.y, c.y, wt), lerp_level(up.z, c.z, wt));  /* w c + (1 - w) c_up */
            tgi_rgb_set(&fine->c, t, c);
            weight_set(fine->wt, t, TG_ONE);
        }
    }
}

/* The chain of the w x h image carved from scratch (levels 1.. in lv[0..]);
 * their count, 0 for an empty or 1 x 1 image. */
static int levels_of(int w, int h, void *scratch, pp_level *lv)
{
    size_t bytes;
    if (w <= 0 || h <= 0 || (w == 1 && h == 1)) return 0;
    return levels_layout(w, h, (unsigned char *)scratch, lv, &bytes);
}

void tgi_pushpull_push_rows(int w, int h, const tgi_rgb *c, void *scratch, int y0, int y1)
{
    pp_level lv[MAX_LEVELS];
    if (!levels_of(w, h, scratch, lv)) return;
    if (y0 < 0) y0 = 0;
    if (y1 > h) y1 = h;
    if (y0 >= y1) return;
    push_level0(c, w, h, &lv[0], (y0 + 1) >> 1, (y1 + 1) >> 1);   /* the level-1 rows y with y0 <= 2y < y1 */
}

/* Levels first.. pushed from the level before, the coarsest texel set,
 * and pulled back down to level last (lv[k] is level k + 1). */
static void levels_between(pp_level *lv, int nl, int first, int last)
{
    int k;
    for (k = first - 1; k < nl; k++) push_level(&lv[k - 1].c, lv[k - 1].wt, lv[k - 1].w, lv[k - 1].h, &lv[k], 0, lv[k].h);
    /* the coarsest texel: what weight it has, over black */
    if (weight_get(lv[nl - 1].wt, 0) < TG_ONE) {
        tgi_rgb_set(&lv[nl - 1].c, 0, tgi_v3_scale(tgi_rgb_get(&lv[nl - 1].c, 0), weight_get(lv[nl - 1].wt, 0)));
        weight_set(lv[nl - 1].wt, 0, TG_ONE);
    }
    for (k = nl - 2; k >= last - 1; k--) pull_level(&lv[k], &lv[k + 1], 0, lv[k].h);
}

void tgi_pushpull_levels(int w, int h, void *scratch)
{
    pp_level lv[MAX_LEVELS];
    int nl = levels_of(w, h, scratch, lv);
    if (nl) levels_between(lv, nl, 2, 1);
}

#if !TG_OUTLINE_HELPERS
int tgi_pushpull_level_rows(int w, int h, int level)
{
    pp_level lv[MAX_LEVELS];
    size_t bytes;
    int nl = w <= 0 || h <= 0 || (w == 1 && h == 1) ? 0 : levels_layout(w, h, NULL, lv, &bytes);
    return level >= 1 && level <= nl ? lv[level - 1].h : 0;
}

void tgi_pushpull_push2_rows(int w, int h, void *scratch, int y0, int y1)
{
    pp_level lv[MAX_LEVELS];
    if (levels_of(w, h, scratch, lv) < 2) return;
    if (y0 < 0) y0 = 0;
    if (y1 > lv[1].h) y1 = lv[1].h;
    if (y0 < y1) push_level(&lv[0].c, lv[0].wt, lv[0].w, lv[0].h, &lv[1], y0, y1);
}

void tgi_pushpull_levels_coarse(int w, int h, void *scratch)
{
    pp_level lv[MAX_LEVELS];
    int nl = levels_of(w, h, scratch, lv);
    if (nl == 1) levels_between(lv, nl, 2, 1);   /* level 1 is the coarsest: its texel alone */
    else if (nl) levels_between(lv, nl, 3, 2);
}

void tgi_pushpull_pull1_rows(int w, int h, void *scratch, int y0, int y1)
{
    pp_level lv[MAX_LEVELS];
    if (levels_of(w, h, scratch, lv) < 2) return;
    if (y0 < 0) y0 = 0;
    if (y1 > lv[0].h) y1 = lv[0].h;
    if (y0 < y1) pull_level(&lv[0], &lv[1], y0, y1);
}
#endif

void tgi_pushpull_fill_rows(int w, int h, const tgi_rgb *c, void *scratch, int y0, int y1)
{
    pp_level lv[MAX_LEVELS];
    size_t i;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > h) y1 = h;
    if (w <= 0 || y0 >= y1) return;
    if (w == 1 && h == 1) {
        if (tgi_rgb_is_hole(c, 0)) tgi_rgb_set(c, 0, tg_v3(0, 0, 0));
        return;
    }
    levels_of(w, h, scratch, lv);
    /* the holes take the upsampled level 1 */
    for (y = y0, i = (size_t)y0 * (size_t)w; y < y1; y++) {
        pp_row_sampler rs;
        row_sampler_start(&rs, &lv[0], y);
        for (x = 0; x < w; x++, i++)
            if (tgi_rgb_is_hole(c, i)) tgi_rgb_set(c, i, row_sample(&rs, x));
    }
}

void tgi_pushpull_fill(int w, int h, const tgi_rgb *c, void *scratch)
{
    tgi_pushpull_push_rows(w, h, c, scratch, 0, h);
    tgi_pushpull_levels(w, h, scratch);
    tgi_pushpull_fill_rows(w, h, c, scratch, 0, h);
}

#endif /* !TG_NO_COLOR */
