/* SPDX-License-Identifier: MIT */
/*
 * denoise.c - the spatial 4x4-neighbourhood filter of the HBIL outputs
 * (HBIL sec. 3.3-3.4).  See denoise.h.
 */
#include "../tinygi.h"
#include "denoise.h"
#include "../core/unit.h"

/* FLOAT_UNROLLED: the float sums of a whole window written out per column
 * phase (window_sums); a build for size keeps the loop over window_order. */
#define FLOAT_UNROLLED (!TG_FIXED && !TG_OUTLINE_HELPERS)

#if defined(__GNUC__)
#define DENOISE_INLINE inline __attribute__((always_inline))   /* a constant (whole, phase) in each copy */
/* the rare side of a test, laid out after the common one (which then
 * falls through, no jump back) */
#define DENOISE_RARE(c) __builtin_expect((c) != 0, 0)
#else
#define DENOISE_INLINE inline
#define DENOISE_RARE(c) (c)
#endif

void tgi_denoise_defaults(tgi_denoise_params *p)
{
    p->depth_tolerance = TG_R(0.1f);
}

/* The 2-D tap weights, the products of the 1-D ones (1/2, 1, 1, 1, 1/2):
 * 1/4, 1/2 or 1, exact in both number types.  In the walk's layout
 * (denoise.h: tap (xx, yy) at (yy - y + 2) * 5 + xx % 5), for a centre in
 * column x with x % 5 = phase: slot s holds window column (s - phase + 2)
 * mod 5, whose 1-D weight is 1/2 in the first and last column.  PHASE lists
 * a middle row's five slots, then the outer rows' (half those). */
#define W_H TG_R(0.5f)
#define W_Q TG_R(0.25f)
#define W_1 TG_ONE
#define PHASE(a, b, c, d, e, ha, hb, hc, hd, he) \
    { ha, hb, hc, hd, he, a, b, c, d, e, a, b, c, d, e, a, b, c, d, e, ha, hb, hc, hd, he, 0, 0, 0 }
#define PIXEL_TAPS 28   /* a pixel's 25 entries of the walk and the 3 after them (denoise.h) */
#if !TGI_Q16_WIDE
static const tg_real spatial_w[5][PIXEL_TAPS] = {
    PHASE(W_1, W_1, W_H, W_H, W_1, W_H, W_H, W_Q, W_Q, W_H),   /* x % 5 = 0: window columns 3 4 0 1 2 in slots 0..4 */
    PHASE(W_1, W_1, W_1, W_H, W_H, W_H, W_H, W_H, W_Q, W_Q),   /* 1: columns 2 3 4 0 1 */
    PHASE(W_H, W_1, W_1, W_1, W_H, W_Q, W_H, W_H, W_H, W_Q),   /* 2: columns 0 1 2 3 4 */
    PHASE(W_H, W_H, W_1, W_1, W_1, W_Q, W_Q, W_H, W_H, W_H),   /* 3: columns 4 0 1 2 3 */
    PHASE(W_1, W_H, W_H, W_1, W_1, W_H, W_Q, W_Q, W_H, W_H),   /* 4: columns 1 2 3 4 0 */
};
#endif
#if TGI_Q16_WIDE
/* The same weights for weigh_entry: a pair (c, w) a tap such that the
 * factor mul_pos(sp, 1 - q), q = mul_pos(dz, inv_ztol) (dz / ztol
 * rounded), is (c - w p) >> 18 from the product p = dz inv_ztol itself,
 * the same integer without q's rounding.  With sp = 2^(16 - s), s = 0, 1,
 * 2 (1, 1/2, 1/4): mul_pos(sp, 2^16 - q) = (2^(16 - s) (2^16 - q) + 2^15)
 * >> 16 = floor((2^16 + s - q) / 2^s); with q = floor((p + 2^15) / 2^16),
 * 2^16 + s - q = floor((K - p) / 2^16), K = (2^16 + s) 2^16 + 2^15 - 1
 * (-floor(x / n) = floor((n - 1 - x) / n) for integers), and floor(floor(y
 * / 2^16) / 2^s) = floor(y / 2^(16 + s)) for y = K - p >= 0 (>= 2^16 where
 * a tap is kept: 1 - q > 0); times 2^(2 - s) above and below, one shift
 * for every tap: c = 2^(2 - s) K, w = 2^(2 - s) = sp >> 14 (c = w = 0 for
 * the 3 entries after the window, weight 0 as before).  Where a tap is
 * kept p + 2^15 < 2^32 (dz_lim), so w p < 2^34 and c < 2^35: no overflow.
 * Both operands 64-bit, one read from the table by the multiply; two
 * instructions a tap fewer than q's rounding (Q16.16 cornell 160x120 2
 * frames 693.80M -> 692.40M).  The table holds -w (nw), and the factor is
 * (c + nw p) >> 18, the same integer: the add reads c from the table
 * itself, where c - w p took a move of c and a subtraction (one
 * instruction a tap; Q16.16 cornell 160x120 2 frames 656.78M -> 656.06M). */
typedef struct spatial_pair { int64_t c, nw; } spatial_pair;
#define SP_SHIFT(w) ((w) == W_1 ? 0 : (w) == W_H ? 1 : 2)
#define SP_PAIR(w) { (w) ? ((((((int64_t)1 << 16) + SP_SHIFT(w)) << 16) + 32767) * ((w) >> 14)) : 0, -((w) >> 14) }
#undef PHASE
#define PHASE(a, b, c, d, e, ha, hb, hc, hd, he) \
    { SP_PAIR(ha), SP_PAIR(hb), SP_PAIR(hc), SP_PAIR(hd), SP_PAIR(he), \
      SP_PAIR(a), SP_PAIR(b), SP_PAIR(c), SP_PAIR(d), SP_PAIR(e), SP_PAIR(a), SP_PAIR(b), SP_PAIR(c), SP_PAIR(d), SP_PAIR(e), \
      SP_PAIR(a), SP_PAIR(b), SP_PAIR(c), SP_PAIR(d), SP_PAIR(e), \
      SP_PAIR(ha), SP_PAIR(hb), SP_PAIR(hc), SP_PAIR(hd), SP_PAIR(he), SP_PAIR(0), SP_PAIR(0), SP_PAIR(0) }
static const spatial_pair spatial_pairs[5][PIXEL_TAPS] = {
    PHASE(W_1, W_1, W_H, W_H, W_1, W_H, W_H, W_Q, W_Q, W_H),   /* as spatial_w */
    PHASE(W_1, W_1, W_1, W_H, W_H, W_H, W_H, W_H, W_Q, W_Q),
    PHASE(W_H, W_1, W_1, W_1, W_H, W_Q, W_H, W_H, W_H, W_Q),
    PHASE(W_H, W_H, W_1, W_1, W_1, W_Q, W_Q, W_H, W_H, W_H),
    PHASE(W_1, W_H, W_H, W_1, W_1, W_H, W_Q, W_Q, W_H, W_H),
};
#undef SP_PAIR
#undef SP_SHIFT
#endif
#undef PHASE

#if !TGI_Q16_WIDE && !FLOAT_UNROLLED
/* The entries of a whole window in the order of the sums (rows, then
 * columns), for a centre in column x with x % 5 = phase: row r's columns
 * x - 2 .. x + 2 are slots (phase + 3 .. phase + 7) % 5. */
#define ROW(r, a, b, c, d, e) 5 * r + a, 5 * r + b, 5 * r + c, 5 * r + d, 5 * r + e
#define ORDER(a, b, c, d, e) { ROW(0, a, b, c, d, e), ROW(1, a, b, c, d, e), ROW(2, a, b, c, d, e), \
                               ROW(3, a, b, c, d, e), ROW(4, a, b, c, d, e) }
static const unsigned char window_order[5][25] = {
    ORDER(3, 4, 0, 1, 2), ORDER(4, 0, 1, 2, 3), ORDER(0, 1, 2, 3, 4), ORDER(1, 2, 3, 4, 0), ORDER(2, 3, 4, 0, 1),
};
#undef ORDER
#undef ROW
#endif

#if TGI_Q16_WIDE
/* Q16.16 products without tg_mul's sign test and saturation, giving its
 * integers where the bounds stated at each use hold: a b >= 0 and below
 * 2^63 - 2^15, rounded as tgi_shr_round rounds a non-negative product. */
static inline uint64_t mul_pos(uint64_t a, uint64_t b) { return (a * b + 32768u) >> 16; }
#else
/* |.| as tgi_abs_fast (raster/pack.h: in float by the sign bit, one and,
 * not tg_abs's compare and select).  The two differ only at -0 (+0 here, -0
 * there), which changes no weight: a depth step of -0 gives min(dz, ztol)
 * = +-0 (or ztol itself, when ztol is 0) and 1 - (+-0) inv_ztol the same
 * value (+-0 times a finite inv_ztol, or NaN times an infinite one, which
 * is rejected: ztol = 0 keeps no tap); in normal_weight a dot of -0 gives
 * (-0 + -0) / 2 = -0 there, +0 here, whose square is +0 either way. */
/* The weights' factors are in [0, 1] (up to a rounding): their products
 * never saturate, so tgi_wide_mul (core/real.h) gives tg_mul's result. */
static tg_real weight_mul(tg_real a, tg_real b) { return (tg_real)tgi_wide_mul(a, b); }

/* max(0, n_i . n_j)^8; the clamp as (d + |d|) / 2 (exact in both number
 * types: 2d or 0 halved) so that the loop over the taps has no branch.  In
 * Q16.16 the dot also clamped at 2 (unit normals never reach it), which
 * bounds the weights for the sums' products (tgi_denoise_pixel). */
static tg_real normal_weight(tg_real d)
{
    d = (d + tgi_abs_fast(d)) / 2;
#if TG_FIXED
    d = tg_min(d, 2 * TG_ONE);
#endif
    d = weight_mul(d, d); d = weight_mul(d, d); d = weight_mul(d, d);   /* (n_i . n_j)^8 */
    return d;
}
#endif

#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
/* A tap's key: its normal's stored code (tgi_gv_normal_word; UINT64_MAX on
 * sky, which no code is).  Equal codes decode to equal normals, whose
 * weight is the centre's own (weigh_and_sum); unequal codes take
 * normal_d8 of the decoded normals, which gives that same weight where
 * they decode alike: the same weights as keys that compare the decoded
 * normals (normal_key below, kept where normals are stored as tg_real),
 * without building one at each decode. */
#define NORMAL_WORDS 1
typedef uint32_t normal_code;   /* the walk's nkey: compared in 32 bits, not widened at each entry */
#else
#define NORMAL_WORDS 0
typedef uint64_t normal_code;
#endif

#if TGI_Q16_WIDE && !NORMAL_WORDS
/* A normal as one word, equal for two normals exactly when they are equal:
 * its components in 21 bits each when all are within [-2^20, 2^20) (unit
 * normals are within [-2^16, 2^16]), else `other` (UINT64_MAX for a tap,
 * UINT64_MAX - 1 for a centre: the two never match, nor match a normal in
 * range, whose word is below 2^63). */
static inline uint64_t normal_key(tg_vec3 n, uint64_t other)
{
    uint64_t x = (uint64_t)((int64_t)n.x + (1 << 20)), y = (uint64_t)((int64_t)n.y + (1 << 20)),
             z = (uint64_t)((int64_t)n.z + (1 << 20));
    return (x | y | z) >> 21 ? other : x << 42 | y << 21 | z;
}
#endif

/* TGI_REUSE_NORMAL (raster/gview.h): a column's taps are loaded top to
 * bottom; a tap whose normal's stored code is the one just above it takes
 * that tap's decoded normal; so does the bent normal (its octahedral code,
 * tgi_gr_bent_word). */

/* The codes of the tap loaded just before, (xx, yy - 1) in entry j - 5:
 * UINT64_MAX and UINT32_MAX for none (the column's first tap, or sky),
 * which no code is. */
typedef struct tap_above { uint64_t normal; uint32_t bent; } tap_above;

/* Value c of entry j of the walk (denoise.h: planes in Q16.16 on 64-bit
 * cores, else an entry's values together). */
#if TGI_DENOISE_LANES
/* an entry's lanes (denoise.h): the value plus 2^31, unsigned */
#define SET_VAL(k, j, c, x) ((k)->v[j][c] = (uint32_t)(x) ^ 0x80000000u)
#define GET_VAL(k, j, c) ((tg_real)(int32_t)((k)->v[j][c] ^ 0x80000000u))
#elif TGI_Q16_WIDE
#define VAL(k, j, c) ((k)->v[c][j])
#else
#define VAL(k, j, c) ((k)->v[j][c])
#endif
#ifndef SET_VAL
#define SET_VAL(k, j, c, x) (VAL(k, j, c) = (x))
#define GET_VAL(k, j, c) VAL(k, j, c)
#endif

/* Pixel (xx, yy) of g decoded into entry j of the walk; has_bent, has_near:
 * what tgi_gr_get_kept reads of r.  above: the codes of the tap above it,
 * set to this tap's for the tap below (TGI_REUSE_NORMAL). */
static void tap_load(tgi_denoise_walk *k, int j, const tgi_gview *g, const tgi_gresult *r, int has_bent, int has_near,
                     int xx, int yy, tap_above *above)
{
    size_t i = tgi_gv_index(g, xx, yy);
    tg_vec3 n, b, e;
#if TGI_REUSE_NORMAL
    uint32_t code;
#endif
    if (tgi_gv_is_sky(g, i)) {
        above->normal = UINT64_MAX; above->bent = UINT32_MAX;
        k->z[j] = k->nx[j] = k->ny[j] = k->nz[j] = 0;
#if TGI_DENOISE_LANES
        SET_VAL(k, j, 0, 0); SET_VAL(k, j, 1, 0); SET_VAL(k, j, 2, 0); SET_VAL(k, j, 3, 0);
        SET_VAL(k, j, 4, 0); SET_VAL(k, j, 5, 0); SET_VAL(k, j, 6, 0);
#else
        VAL(k, j, 0) = VAL(k, j, 1) = VAL(k, j, 2) = VAL(k, j, 3) = VAL(k, j, 4) = VAL(k, j, 5) = VAL(k, j, 6) = 0;
#endif
#if !TGI_Q16_WIDE
        VAL(k, j, 7) = TG_FIXED ? 0 : TG_ONE;
#endif
#if NORMAL_WORDS
        k->nkey[j] = UINT32_MAX;
#elif TGI_Q16_WIDE
        k->nkey[j] = normal_key(tg_v3(0, 0, 0), UINT64_MAX);
#endif
        return;
    }
#if TGI_REUSE_NORMAL
    code = tgi_gv_normal_word(g, i);
    n = above->normal == code ? tg_v3(k->nx[j - 5], k->ny[j - 5], k->nz[j - 5]) : tgi_gv_normal(g, i);
    above->normal = code;
#else
    (void)above;
    n = tgi_gv_normal(g, i);
#endif
#if NORMAL_WORDS
    k->nkey[j] = code;
#elif TGI_Q16_WIDE
    k->nkey[j] = normal_key(n, UINT64_MAX);
#endif
#if TGI_Q16_WIDE
    k->z[j] = tgi_gv_depth(g, i);
    k->nx[j] = n.x; k->ny[j] = n.y; k->nz[j] = n.z;
    SET_VAL(k, j, 0, r->ao ? tgi_gr_ao(r, i) : TG_ONE);
    /* a channel the results lack is not stored (3 stores a tap each): its
     * planes keep what they held (0 from tgi_denoise_walk_start, or values
     * decoded before: integers within the range, whose products and sums
     * stay within tgi_denoise_pixel's bounds), which no filtered value
     * reads (weigh_and_sum adds them only to sums tgi_denoise_pixel then
     * leaves unused); each channel's loads and stores under the one test */
    if (has_bent) {
#if TGI_REUSE_NORMAL
        uint32_t bent = tgi_gr_bent_word(r, i);
        b = above->bent == bent ? tg_v3(GET_VAL(k, j - 5, 1), GET_VAL(k, j - 5, 2), GET_VAL(k, j - 5, 3)) : tgi_gr_bent(r, i);
        above->bent = bent;
#else
        b = tgi_gr_bent(r, i);
#endif
        SET_VAL(k, j, 1, b.x); SET_VAL(k, j, 2, b.y); SET_VAL(k, j, 3, b.z);
    }
    if (has_near) { e = tgi_gr_near(r, i); SET_VAL(k, j, 4, e.x); SET_VAL(k, j, 5, e.y); SET_VAL(k, j, 6, e.z); }
#else
#if TGI_REUSE_NORMAL
    b = tg_v3(0, 0, 0);
    if (has_bent) {
        uint32_t bent = tgi_gr_bent_word(r, i);
        b = above->bent == bent ? tg_v3(VAL(k, j - 5, 1), VAL(k, j - 5, 2), VAL(k, j - 5, 3)) : tgi_gr_bent(r, i);
        above->bent = bent;
    }
#else
    b = has_bent ? tgi_gr_bent(r, i) : tg_v3(0, 0, 0);
#endif
    e = has_near ? tgi_gr_near(r, i) : tg_v3(0, 0, 0);
    k->z[j] = tgi_gv_depth(g, i);
    k->nx[j] = n.x; k->ny[j] = n.y; k->nz[j] = n.z;
    VAL(k, j, 0) = r->ao ? tgi_gr_ao(r, i) : TG_ONE;
    VAL(k, j, 1) = b.x; VAL(k, j, 2) = b.y; VAL(k, j, 3) = b.z;
    VAL(k, j, 4) = e.x; VAL(k, j, 5) = e.y; VAL(k, j, 6) = e.z;
    VAL(k, j, 7) = TG_FIXED ? 0 : TG_ONE;
#endif
}

#if TGI_Q16_WIDE
/* The weights of tap_weights below (the float build's) in Q16.16 and the
 * sums of tgi_denoise_pixel in one pass over the window's entries, the set
 * bits of `window` (bit j: entry j).  The same integers for every weight
 * that is positive; an entry whose weight is <= 0 adds nothing, so the
 * tests below leave it out as soon as one of its factors is 0 (whole: all
 * 25 entries, window unused).  Where the
 * weight is kept, dz < ztol, so ztol > 0, inv_ztol > 0 and dz / ztol in
 * [0, 1 + a rounding]; 1 - dz / ztol is kept only when positive.  Every
 * factor is then non-negative: the spatial weight <= 1 and the dot clamped
 * at 2 (normal_weight), so the weight <= 2^8 (2^24 in Q16.16).  The dot's
 * rounding: tgi_shr_round of a sum s <= 0 is <= 0 (the normal weight 0),
 * of s > 0 it is mul_pos's; the normals' components are within [-1, 1], so
 * |s| < 2^34.  The sums are exact integers (tgi_denoise_pixel bounds them
 * below 2^60), so the order of the entries, here the walk's and not the
 * window's rows and columns, gives the same sums. */
/* max(0, a . b)^8 (normal_weight's) */
static inline uint64_t normal_d8(tg_vec3 a, tg_vec3 b)
{
    int64_t s = (int64_t)a.x * b.x + (int64_t)a.y * b.y + (int64_t)a.z * b.z;
    uint64_t d;
    if (s <= 0) return 0;
    d = ((uint64_t)s + 32768u) >> 16;
    d = d < 2 * TG_ONE ? d : 2 * TG_ONE;
    d = mul_pos(d, d); d = mul_pos(d, d);
    return mul_pos(d, d);
}

#if TGI_DENOISE_LANES
/* The sums of the lanes (denoise.h): 64-bit, two a vector, each the
 * products of a lane's values by the weights (SSE2's pmuludq: the even
 * 32-bit lanes of two vectors, unsigned, multiplied into two 64-bit
 * ones).  Lanes 0-3 (AO, bent x y z) in a, 4-7 (near r g b, 1) in b; their
 * even lanes (0 and 2) and odd ones (1 and 3, moved down by a shuffle)
 * apart.  A lane's value is below 2^32 and a weight at most 2^24
 * (normal_weight), a product below 2^56 and 25 of them below 2^61: the
 * sums exact.  A sum less 2^31 times the weights' sum (the lanes' bias),
 * modulo 2^64, is the sum of the values times the weights, whose size is
 * below 2^60 (tgi_denoise_pixel): exactly the int64_t it is, the same
 * sums as a product a value.  A tap's 7 products, 21 instructions (load,
 * multiply, add), take 12 here and the weight's broadcast 2; the 8 sums
 * in 4 vector registers leave the centre's constants in general ones
 * (Q16.16 160x120 2 frames: columns 282.43M -> 277.46M, cornell, whose
 * results have no bent normal, 649.46M -> 648.57M; --gi-quarter 228.00M
 * -> 226.96M, 320.66M -> 320.39M). */
typedef int lanes_i32 __attribute__((vector_size(16)));
typedef unsigned long long lanes_u64 __attribute__((vector_size(16)));
typedef struct entry_sums { lanes_u64 a_even, a_odd, b_even, b_odd; } entry_sums;
static inline lanes_u64 lanes_mul_even(lanes_i32 a, lanes_i32 w) { return (lanes_u64)__builtin_ia32_pmuludq128(a, w); }
typedef const uint32_t (*lane_row)[TGI_DENOISE_VALUES + 1];   /* a pixel's first entry's lanes, k->v + o */
#else
typedef int64_t entry_sums;   /* s[0..7], s[7] the weights' */
typedef const void *lane_row;  /* unused */
#endif

/* One entry e (spatial weight sp) of weigh_and_sum into the sums s[0..7]
 * (s[7] the weights'). */
static DENOISE_INLINE void weigh_entry(const tgi_denoise_walk *k, int e, const spatial_pair *sp, int64_t zi, tg_vec3 ni,
                                       int64_t dz_lim, tg_real inv_ztol, uint64_t inv_wide, normal_code key, uint64_t same,
                                       const int bent, const int near, const int wide, const lane_row lanes, int j, entry_sums *s)
{
    /* in 64 bits (the depth's load widens it; no widening of dz for the
     * product); depths are never negative: no overflow in 32 bits either */
    int64_t dz = (int64_t)k->z[e] - zi, wj;
    uint64_t d, t;
    dz = dz < 0 ? -dz : dz;
    if (dz >= dz_lim) return;   /* dz >= ztol, or 1 - dz / ztol <= 0 (dz_lim) */
    /* mul_pos(sp, 1 - dz / ztol) (spatial_pairs), 1 - dz / ztol > 0 */
    t = (uint64_t)(sp->c + sp->nw * (int64_t)((uint64_t)dz * (wide ? inv_wide : (uint64_t)inv_ztol))) >> 18;
    /* the normal weight: the centre's own for a normal equal to it (the
     * common case: a plane's pixels share their normal); a weight 0
     * (normals apart) adds 0 */
    d = same;
    if (DENOISE_RARE(k->nkey[e] != key)) d = normal_d8(ni, tg_v3(k->nx[e], k->ny[e], k->nz[e]));
    wj = (int64_t)mul_pos(t, d);
#if TGI_DENOISE_LANES
    {
        /* wj <= 2^24 (normal_d8 <= 2^24, t <= 2^16): a 32-bit lane */
        const lanes_i32 w = { (int)wj, (int)wj, (int)wj, (int)wj };
        const lanes_i32 a = *(const lanes_i32 *)lanes[j], b = *(const lanes_i32 *)(lanes[j] + 4);
        s->a_even += lanes_mul_even(a, w);                                        /* AO, bent y */
        if (bent) s->a_odd += lanes_mul_even(__builtin_shufflevector(a, a, 1, 1, 3, 3), w);       /* bent x, z */
        if (near) s->b_even += lanes_mul_even(b, w);                              /* near r, b */
        s->b_odd += lanes_mul_even(__builtin_shufflevector(b, b, 1, 1, 3, 3), w);                 /* near g, the weights' */
    }
#else
    (void)lanes; (void)j;
    s[0] += VAL(k, e, 0) * wj; s[7] += wj;   /* the weights' sum */
    if (bent) { s[1] += VAL(k, e, 1) * wj; s[2] += VAL(k, e, 2) * wj; s[3] += VAL(k, e, 3) * wj; }
    if (near) { s[4] += VAL(k, e, 4) * wj; s[5] += VAL(k, e, 5) * wj; s[6] += VAL(k, e, 6) * wj; }
#endif
}

/* bent, near (constants in each copy): 0 when the results have no bent
 * normal, no near field; tap_load's values are 0 there, so are their sums,
 * which are then not added (tgi_denoise_pixel does not read them).  A
 * whole window's entries a row of five written out (the loop's counters
 * and tests a row, not an entry). */
static DENOISE_INLINE void weigh_and_sum(const tgi_denoise_walk *k, int o, const spatial_pair *spatial, tg_real zi,
                                         tg_vec3 ni, int ce, uint64_t same, int64_t dz_lim, tg_real inv_ztol, uint64_t inv_wide,
                                         uint32_t window, int whole, const int bent, const int near, int64_t *sum)
{
    /* whole_fewer's and whole_all's copies (whole) take the inverse
     * inv_wide, widened once by the caller (the same value,
     * (uint64_t)inv_ztol): from a tg_real, gcc sign-extended it again at
     * each of their 25 entries (Q16.16 cornell 160x120 2 frames 694.46M ->
     * 693.80M); the copy inlined in tgi_denoise_pixel (part of a window)
     * keeps the tg_real (widened there, columns took 73K more) */
#if TGI_DENOISE_LANES
    entry_sums ls = { { 0, 0 }, { 0, 0 }, { 0, 0 }, { 0, 0 } }, *s = &ls;
    const lane_row lanes = k->v + o;
    uint64_t bias;
#else
    int64_t s[TGI_DENOISE_VALUES + 1] = { 0, 0, 0, 0, 0, 0, 0, 0 };
    const lane_row lanes = NULL;
#endif
#if NORMAL_WORDS
    normal_code key = k->nkey[ce];   /* the centre's code */
#else
    normal_code key = normal_key(ni, UINT64_MAX - 1);
    (void)ce;
#endif
    int j, c;
#define ENTRY(j_) weigh_entry(k, o + (j_), &spatial[j_], zi, ni, dz_lim, inv_ztol, inv_wide, key, same, bent, near, whole, lanes, j_, s)
#define ROW5(j) ENTRY(j); ENTRY(j + 1); ENTRY(j + 2); ENTRY(j + 3); ENTRY(j + 4)
    /* whole_fewer's and whole_all's copies (out of line, registers to
     * spare) all 25 written out: no counters, nor the end read back from
     * the stack (5 instructions a row; Q16.16 cornell 160x120 2 frames
     * 695.61M -> 695.01M); the copy inlined in tgi_denoise_pixel takes
     * part of a window only */
    if (whole) {
        ROW5(0); ROW5(5); ROW5(10); ROW5(15); ROW5(20);
    } else {
        for (j = 0; window != 0; j++, window >>= 1)
            if (window & 1) ENTRY(j);
    }
#undef ROW5
#undef ENTRY
    /* the sums out, those of a channel left out (bent, near: 0, s[c] never
     * added to) as the constant 0 they are: gcc then keeps every sum in a
     * register without a flag of whether any entry was added (a register
     * and an instruction an entry; Q16.16 cornell 160x120 2 frames 754.48M
     * -> 752.74M) */
#if TGI_DENOISE_LANES
    (void)c;
    bias = ls.b_odd[1] << 31;   /* the weights' sum times the lanes' bias */
    sum[0] = (int64_t)(ls.a_even[0] - bias); sum[7] = (int64_t)ls.b_odd[1];
    sum[1] = bent ? (int64_t)(ls.a_odd[0] - bias) : 0;
    sum[2] = bent ? (int64_t)(ls.a_even[1] - bias) : 0;
    sum[3] = bent ? (int64_t)(ls.a_odd[1] - bias) : 0;
    sum[4] = near ? (int64_t)(ls.b_even[0] - bias) : 0;
    sum[5] = near ? (int64_t)(ls.b_odd[0] - bias) : 0;
    sum[6] = near ? (int64_t)(ls.b_even[1] - bias) : 0;
#else
    sum[0] = s[0]; sum[7] = s[7];
    for (c = 1; c < 4; c++) sum[c] = bent ? s[c] : 0;
    for (c = 4; c < 7; c++) sum[c] = near ? s[c] : 0;
#endif
}
/* weigh_and_sum over a whole window without the bent normal, the near
 * field or both (cornell 320x240 3 frames, no bent normals: 3 products a
 * tap fewer, tgi_denoise_pixel 374.5M -> 341.8M with this).  Out of line:
 * inlined too, tgi_denoise_pixel's registers spilled more in the common
 * copy (every channel; columns 405.7M -> 410.5M, cornell 333.1M). */
/* weigh_and_sum over a whole window with every channel, out of line too:
 * inlined in tgi_denoise_pixel, whose own values (the pixel's, the
 * results' and the view's) hold registers across it, its 8 sums and the
 * pixel's constants spilled (the inverse and the normal weight read back
 * from the stack into a register at each entry, a sum added in memory);
 * here a call a pixel (Q16.16 columns 160x120 2 frames 286.41M -> 285.62M;
 * cornell, whose results have no bent normal, 656.06M -> 656.08M: the
 * test of the two channels before the calls).  Its own function, not a
 * copy in whole_fewer: there, the copies' registers shared, cornell's
 * took 0.66M more. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void whole_all(const tgi_denoise_walk *k, int o, const spatial_pair *spatial, tg_real zi, tg_vec3 ni, int ce, uint64_t same,
                      int64_t dz_lim, uint64_t inv_ztol, int64_t *sum)
{
    weigh_and_sum(k, o, spatial, zi, ni, ce, same, dz_lim, 0, inv_ztol, 0, 1, 1, 1, sum);
}
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void whole_fewer(const tgi_denoise_walk *k, int o, const spatial_pair *spatial, tg_real zi, tg_vec3 ni, int ce, uint64_t same,
                        int64_t dz_lim, uint64_t inv_ztol, int bent, int near, int64_t *sum)
{
    if (near) weigh_and_sum(k, o, spatial, zi, ni, ce, same, dz_lim, 0, inv_ztol, 0, 1, 0, 1, sum);
    else if (bent) weigh_and_sum(k, o, spatial, zi, ni, ce, same, dz_lim, 0, inv_ztol, 0, 1, 1, 0, sum);
    else weigh_and_sum(k, o, spatial, zi, ni, ce, same, dz_lim, 0, inv_ztol, 0, 1, 0, 0, sum);
}
#else
/* The weight of every entry of the walk for the centre (depth zi, normal
 * ni): the 2-D tap weight times depth and normal awareness; 0 for a depth
 * step of tol zi or more, so for sky (depth 0).  No branch, so that the loop
 * runs over contiguous values (vector operations): every entry's weight is
 * computed (from finite values: the walk starts zeroed), the window's and
 * the others alike, then multiplied by 1 or 0 (the plain product is w or 0
 * in either number type). */
static void tap_weights(const tgi_denoise_walk *k, int o, const tg_real *spatial, tg_real zi, tg_vec3 ni,
                        tg_real ztol, tg_real inv_ztol, tg_real *wt)
{
    int j;
    for (j = 0; j < PIXEL_TAPS; j++) {
        /* depths are never negative: their difference never saturates */
        tg_real dz = tgi_abs_fast(k->z[o + j] - zi), w;
        tg_real dzc = tg_min(dz, ztol);   /* = dz where the weight is kept: dz / ztol in [0, 1] */
        tg_real kept = dz < ztol ? 1 : 0;
        w = weight_mul(spatial[j], TG_ONE - weight_mul(dzc, inv_ztol));   /* in [0, 1]: never saturates */
        w = weight_mul(w, normal_weight(tgi_v3_dot(ni, tg_v3(k->nx[o + j], k->ny[o + j], k->nz[o + j]))));
        /* kept or 0, and never below 0 (a weight 1 - dz / ztol rounded
         * below 0 adds nothing, as a rejected one); in the same loop (the
         * weights not stored and read back) */
        wt[j] = tg_max(w * kept, 0);
    }
}

#endif

#if FLOAT_UNROLLED
/* The float sums of a whole window (tgi_denoise_pixel's loop over
 * window_order[phase]) written out for a constant phase: the same taps in
 * the same order (rows, then columns x - 2 .. x + 2, slots (phase + 3 ..
 * phase + 7) % 5), so the same sums, without the table's index and the
 * address arithmetic a tap (about 16 -> 9 instructions a tap; cornell
 * 320x240 3 frames tgi_denoise_pixel 227.2M -> 195.8M).  A copy per phase
 * (tgi_denoise_pixel's switch); the five taps of a row written out, the
 * rows a loop (the whole window written out took 20M more: gcc spilled). */
#define WINDOW_TAP(c) do { \
        const int j_ = (phase + 3 + (c)) % 5; \
        const tg_real *tv_ = row[j_], wj_ = w[j_]; \
        for (ch = 0; ch <= TGI_DENOISE_VALUES; ch++) s[ch] += tv_[ch] * wj_; \
    } while (0)
static DENOISE_INLINE void window_sums(const tgi_denoise_walk *k, int o, const tg_real *wt, const int phase,
                                       tgi_wide *sum)
{
    tg_real s[TGI_DENOISE_VALUES + 1] = { 0, 0, 0, 0, 0, 0, 0, 0 };
    const tg_real (*row)[TGI_DENOISE_VALUES + 1] = k->v + o;
    const tg_real *w = wt;
    int r, ch;
    for (r = 0; r < 5; r++, row += 5, w += 5) {
        WINDOW_TAP(0); WINDOW_TAP(1); WINDOW_TAP(2); WINDOW_TAP(3); WINDOW_TAP(4);
    }
    for (ch = 0; ch <= TGI_DENOISE_VALUES; ch++) sum[ch] = s[ch];
}
#undef WINDOW_TAP
#endif

/* A value's filtered result: its sum over the weights' sum ws > 0 (see
 * tgi_denoise_pixel); in Q16.16 the sum is Q32, rounded half away from zero
 * as tg_div rounds.  A weighted average (weights >= 0) of values within
 * [TG_REAL_MIN, TG_REAL_MAX], integers, lies within them, and so does its
 * rounding to an integer: tgi_sat64 would change nothing (and is kept in a
 * build for size, where it costs nothing). */
static tg_real average(tgi_wide sum, tgi_wide ws)
{
#if TGI_Q16_WIDE
    return (tg_real)tgi_div_round(sum, ws);
#elif TG_FIXED
    return tgi_sat64(tgi_div_round(sum, ws));
#else
    return tg_div(sum, ws);
#endif
}
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
/* average of a channel whose values are never negative: the AO (unorm8
 * unpacked, within [0, 1], or 1 without the plane) and the near field
 * (rgb9e5 unpacked: never negative), weights >= 0, so sum >= 0 and
 * tgi_div_round's test of its sign is known; the AO's average, its values
 * within [0, 1], is within [0, 1] too (sum <= ws: (sum + ws / 2) / ws <=
 * 1.5 rounds down to at most 1), so tg_saturate changes nothing there */
static tg_real average_pos(tgi_wide sum, tgi_wide ws) { return (tg_real)(((uint64_t)sum + (uint64_t)ws / 2) / (uint64_t)ws); }
#define AO_AVERAGE(s, ws) average_pos(s, ws)
#else
#define average_pos average
#define AO_AVERAGE(s, ws) tg_saturate(average(s, ws))
#endif

/* The filtered bent normal made unit again (out of line: inlined, its
 * registers cost the filter's loop more than the call). */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static tg_vec3 bent_unit(tg_vec3 b, tg_vec3 fallback) { return tgi_v3_unit_or(b, fallback); }

void tgi_denoise_walk_start(tgi_denoise_walk *k)
{
    memset(k, 0, sizeof *k);
    k->base = -1;                       /* set by the first pixel */
#if TGI_DENOISE_LANES
    {
        int j;
        for (j = 0; j < TGI_DENOISE_TAPS; j++) k->v[j][TGI_DENOISE_VALUES] = 1;   /* the weights' lane */
    }
#endif
    k->band = -2 * TGI_DENOISE_BAND;    /* none: a band starts at row -(TGI_DENOISE_BAND - 1) or later */
#if NORMAL_WORDS
    k->same_key = UINT32_MAX;           /* none: no centre is sky */
#endif
    k->lo = k->next = 0;
}

tgi_gr_value tgi_denoise_pixel(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r,
                               tgi_denoise_walk *k, int x, int y)
{
    size_t i = tgi_gv_index(g, x, y);
    int w = g->width, h = g->height, xx, yy, band, o, has_bent = !TG_NO_BENT_NORMALS && tgi_gr_has_bent(r), has_near = !TG_NO_COLOR && tgi_gr_has_near(r);
    int xa = x < 2 ? 0 : x - 2, xb = x + 2 >= w ? w - 1 : x + 2;
    int ya = y < 2 ? 0 : y - 2, yb = y + 2 >= h ? h - 1 : y + 2;
    tg_real zi, ztol, inv_ztol;
#if TGI_Q16_WIDE
    int64_t dz_lim;
    uint64_t same;
    int ce;
#endif
#if !TGI_Q16_WIDE
    tg_real wt[PIXEL_TAPS];
    const unsigned char *order;
    unsigned char part[25];
    int c, t, taps = 0;
#endif
    /* The sums in tgi_wide (core/real.h), in the order of the taps (rows,
     * then columns), each of the walk's values its own sum, then the
     * weights' (sum[7]); the filtered value is a sum over the weights' sum
     * (average).  In float the products tgi_wide_mul's; in Q16.16 exact,
     * Q32, with one rounding in the division: |value| < 2^31 and 0 < weight
     * <= 2^24 (normal_weight), so a product < 2^55 and 25 of them < 2^60,
     * and the weighted average of values in the range stays in it.  A build
     * with TG_NO_COLOR (tinygi.h "FEATURE SWITCHES") has no near field, one
     * with TG_NO_BENT_NORMALS no bent normal: their values are 0 and their
     * sums not used. */
    tgi_wide sum[TGI_DENOISE_VALUES + 1], ws;
    tg_vec3 ni;
    tgi_gr_value v;
    if (tgi_gv_is_sky(g, i)) return tgi_gr_get_kept(r, i);
    /* the band's columns decoded once: those of the last pixels are kept */
    if (k->base < 0) k->base = y;
    band = tgi_denoise_band_of(k->base, y);
    if (k->band != band || xa < k->lo) { k->band = band; k->lo = k->next = xa; }
    if (k->next <= xb) {
        int ra = band < 2 ? 0 : band - 2, rb = band + TGI_DENOISE_BAND + 1 >= h ? h - 1 : band + TGI_DENOISE_BAND + 1;
        for (; k->next <= xb; k->next++) {
            tap_above above = { UINT64_MAX, UINT32_MAX };   /* none: the column's first tap decodes */
            for (yy = ra; yy <= rb; yy++)
                tap_load(k, (yy - band + 2) * 5 + k->next % 5, g, r, has_bent, has_near, k->next, yy, &above);
        }
    }
    if (k->next - k->lo > 5) k->lo = k->next - 5;
    o = (y - band) * 5;   /* the pixel's entries: tap (xx, yy) at o + (yy - y + 2) * 5 + xx % 5 */
    zi = k->z[o + 2 * 5 + x % 5];
    ni = tg_v3(k->nx[o + 2 * 5 + x % 5], k->ny[o + 2 * 5 + x % 5], k->nz[o + 2 * 5 + x % 5]);
    ztol = tg_mul(p->depth_tolerance, zi);
#if TGI_Q16_WIDE
    /* tg_div(1, ztol) (tgi_div_inline: 2^32 plus half of ztol > 0, over
     * ztol, saturated) without its tests of the signs where ztol > 0, the
     * common case (zi > 0, the tolerance's default 0.1) */
    inv_ztol = ztol > 0 ? tgi_sat64((((int64_t)1 << 32) + ztol / 2) / ztol) : tg_div(TG_ONE, ztol);
#else
    inv_ztol = tg_div(TG_ONE, ztol);
#endif
#if TGI_Q16_WIDE
    /* dz_lim: the entries kept are those with dz < ztol and 1 - dz / ztol
     * > 0, that is mul_pos(dz, inv_ztol) < 1 (2^16), dz inv_ztol + 2^15 <
     * 2^32, dz < ceil((2^32 - 2^15) / inv_ztol): one bound, the smaller,
     * for both tests, set once a pixel (ztol >= 0: zi >= 0 and the
     * tolerance's default 0.1; inv_ztol > 0 except for a negative one,
     * when ztol < 0 rejects every entry as before) */
    dz_lim = ztol;
    if (inv_ztol > 0) {
        const int64_t t = (int64_t)(((((uint64_t)1 << 32) - 32768u) + (uint64_t)inv_ztol - 1) / (uint64_t)inv_ztol);
        dz_lim = t < dz_lim ? t : dz_lim;
    }
    ce = o + 2 * 5 + x % 5;   /* the centre's entry */
    /* the centre's own normal weight, normal_d8(ni, ni): kept in the walk
     * for the next centres with the same code (a plane's pixels share it),
     * which decode to the same normal (same_key: none at the start;
     * Q16.16 cornell 160x120 2 frames 692.40M -> 691.93M) */
#if NORMAL_WORDS
    if (k->nkey[ce] != k->same_key) { k->same_key = k->nkey[ce]; k->same = (uint32_t)normal_d8(ni, ni); }
    same = k->same;
#else
    same = normal_d8(ni, ni);
#endif
    if (xb - xa == 4 && yb - ya == 4) {   /* the whole window: every entry; a copy per set of channels */
        const spatial_pair *sp = spatial_pairs[x % 5];
        if (has_bent && has_near) whole_all(k, o, sp, zi, ni, ce, same, dz_lim, (uint64_t)inv_ztol, sum);
        else whole_fewer(k, o, sp, zi, ni, ce, same, dz_lim, (uint64_t)inv_ztol, has_bent, has_near, sum);
    } else {   /* the window's entries inside the image: its rows' slots of its columns */
        uint32_t slots = 0, window = 0;
        for (xx = xa; xx <= xb; xx++) slots |= 1u << (xx % 5);
        for (yy = ya; yy <= yb; yy++) window |= slots << ((yy - y + 2) * 5);
        weigh_and_sum(k, o, spatial_pairs[x % 5], zi, ni, ce, same, dz_lim, inv_ztol, 0, window, 0, 1, 1, sum);
    }
#else
    tap_weights(k, o, spatial_w[x % 5], zi, ni, ztol, inv_ztol, wt);
    if (xb - xa == 4 && yb - ya == 4) {
#if FLOAT_UNROLLED
        switch (x % 5) {   /* the whole window: a copy of the sums per phase */
        case 0: window_sums(k, o, wt, 0, sum); break;
        case 1: window_sums(k, o, wt, 1, sum); break;
        case 2: window_sums(k, o, wt, 2, sum); break;
        case 3: window_sums(k, o, wt, 3, sum); break;
        default: window_sums(k, o, wt, 4, sum); break;
        }
        order = NULL;                  /* summed */
#else
        order = window_order[x % 5];   /* the whole window */
        taps = 25;
#endif
    } else {                           /* the window's part inside the image */
        for (yy = ya; yy <= yb; yy++)
            for (xx = xa; xx <= xb; xx++) part[taps++] = (unsigned char)((yy - y + 2) * 5 + xx % 5);
        order = part;
    }
    if (order != NULL)
        for (c = 0; c <= TGI_DENOISE_VALUES; c++) sum[c] = 0;
    for (t = 0; t < taps; t++) {
        int j = order[t];
        const tg_real *tv = k->v[o + j];
        tg_real wj = wt[j];
        /* no test for a weight 0 (tap_weights: >= 0): the products of the
         * finite values and +0 are zeros, and a sum plus a zero is the sum
         * (a sum from +0 is never -0: x + -x is +0), as without the tap.
         * Written out: straight-line code the compiler keeps in registers
         * (Q16.16) or turns into vector operations (float) */
#if TG_FIXED
        sum[0] += (int64_t)tv[0] * wj; sum[1] += (int64_t)tv[1] * wj;
        sum[2] += (int64_t)tv[2] * wj; sum[3] += (int64_t)tv[3] * wj;
        sum[4] += (int64_t)tv[4] * wj; sum[5] += (int64_t)tv[5] * wj;
        sum[6] += (int64_t)tv[6] * wj; sum[7] += wj;   /* the weights' sum */
#else
        for (c = 0; c <= TGI_DENOISE_VALUES; c++) sum[c] += tv[c] * wj;   /* sum[7]: 1 wj, the weights' sum */
#endif
    }
#endif
    ws = sum[TGI_DENOISE_VALUES];
    if (ws <= 0) return tgi_gr_get_kept(r, i);   /* the centre always weighs 1: cannot happen */
    v.ao = AO_AVERAGE(sum[0], ws);
    v.bent = has_bent ? bent_unit(tg_v3(average(sum[1], ws), average(sum[2], ws), average(sum[3], ws)), ni)
                      : tg_v3(0, 0, 0);
    v.near = has_near ? tg_v3(average_pos(sum[4], ws), average_pos(sum[5], ws), average_pos(sum[6], ws)) : tg_v3(0, 0, 0);
    return v;
}

void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r, const tgi_gresult *out,
                      int y0, int y1)
{
    tgi_denoise_walk k;
    int x, y, yy, end;
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    tgi_denoise_walk_start(&k);
    for (y = y0; y < y1; y = end) {     /* band by band, column by column */
        end = tgi_denoise_band(&k, y, y1);
        for (x = 0; x < g->width; x++)
            for (yy = y; yy < end; yy++) {
                tgi_gr_value v = tgi_denoise_pixel(p, g, r, &k, x, yy);
                tgi_gr_put_kept(out, tgi_gv_index(g, x, yy), &v);
            }
    }
}
