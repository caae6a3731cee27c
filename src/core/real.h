/* SPDX-License-Identifier: MIT */
/*
 * real.h - the number type (tg_real, TG_R, the inline arithmetic and the
 * transcendentals) is public API and lives in src/tinygi.h, section "THE
 * NUMBER TYPE"; this header adds the core's internal integer helpers from
 * real.c that the kernels share.
 */
#ifndef TG_REAL_H
#define TG_REAL_H

#include "../tinygi.h"
#include "abi_names.h"

/* Number of significant bits of v (0 for 0). */
static inline int tgi_bit_length64(uint64_t v)
{
#if defined(__GNUC__)
    return v ? 64 - __builtin_clzll(v) : 0;
#else
    int n = 0;
    if (v >> 32) { v >>= 32; n += 32; }
    if (v >> 16) { v >>= 16; n += 16; }
    if (v >> 8) { v >>= 8; n += 8; }
    if (v >> 4) { v >>= 4; n += 4; }
    if (v >> 2) { v >>= 2; n += 2; }
    if (v >> 1) { v >>= 1; n += 1; }
    return n + (int)v;
#endif
}

/* 32 - tgi_bit_length64(v) for v != 0 (the leading zeros of 32 bits),
 * without the test for 0 that gcc keeps in tgi_bit_length64.
 * __builtin_clz counts in an unsigned int: only where that has 32 bits
 * (a 16-bit int would truncate v; a 64-bit one would count 32 more). */
static inline int tgi_clz32_nz(uint32_t v)
{
#if defined(__GNUC__) && defined(__SIZEOF_INT__) && __SIZEOF_INT__ == 4
    return __builtin_clz(v);
#else
    return 32 - tgi_bit_length64(v);
#endif
}
/* 64 - tgi_bit_length64(v) for v != 0, the same way (__builtin_clzll counts
 * in an unsigned long long: only where that has 64 bits). */
static inline int tgi_clz64_nz(uint64_t v)
{
#if defined(__GNUC__) && defined(__SIZEOF_LONG_LONG__) && __SIZEOF_LONG_LONG__ == 8
    return __builtin_clzll(v);
#else
    return 64 - tgi_bit_length64(v);
#endif
}

/* sqrt of a 64-bit integer, floor; used by fixed-point vector lengths. */
uint32_t tgi_isqrt64(uint64_t v);
/* sqrt of a 64-bit integer, rounded to nearest. */
static inline uint64_t tgi_isqrt_round64(uint64_t v)
{
    uint64_t r = tgi_isqrt64(v);
    return v - r * r > r ? r + 1 : r;
}

/* ---- unsaturated sums and products ----
 * Where a kernel's values are provably bounded (each use states the bound
 * next to the code), it may compute in tgi_wide: Q16.16 in 64 bits with
 * products rounded exactly as tg_mul rounds them but never saturated, and
 * a dot product summed exactly and rounded once as tgi_v3_dot; in the float
 * build the same operations in float.  The results equal tg_mul, tg_add and
 * tgi_v3_dot's whenever those would not have saturated (and no product may
 * reach 2^62). */
/* TGI_Q16_WIDE: a Q16.16 build whose kernels take those unsaturated
 * paths (each with its bounds at the code), giving the same integers as
 * the generic code; a build for size (TG_OUTLINE_HELPERS, tinygi.h) and
 * the float build keep the generic code (smaller; float has no saturation
 * to skip).  The one place the kernels ask. */
#define TGI_Q16_WIDE (TG_FIXED && !TG_OUTLINE_HELPERS)
#if TG_FIXED
typedef int64_t tgi_wide;
static inline tgi_wide tgi_wide_mul(tgi_wide a, tgi_wide b) { return tgi_shr_round(a * b, TG_FRAC_BITS); }
static inline tgi_wide tgi_wide_dot(tgi_wide ax, tgi_wide ay, tgi_wide az, tgi_wide bx, tgi_wide by, tgi_wide bz)
{
    return tgi_shr_round(ax * bx + ay * by + az * bz, TG_FRAC_BITS);
}
/* back to tg_real, saturating */
static inline tg_real tgi_wide_real(tgi_wide a) { return tgi_sat64(a); }
/* a / b rounded as tg_div rounds it (half away from zero), for b > 0
 * where the quotient fits tg_real (each use states why): tg_div without
 * its zero, sign and saturation tests; compiling for size
 * (TG_OUTLINE_HELPERS) the library's one tg_div, the same quotient. */
static inline tg_real tgi_div_pos(tg_real a, tg_real b)
{
#if TG_OUTLINE_HELPERS
    return tgi_div_q16(a, b);
#else
    return (tg_real)tgi_div_round((int64_t)a * 65536, b);
#endif
}
/* tgi_div_nonneg's quotient floor((a 2^16 + floor(b / 2)) / b) mod 2^32
 * (a >= 0, b > 0) in 32-bit divisions, for a 32-bit core that divides in
 * hardware but calls the library for a 64-bit division (TGI_DIV32: the
 * Cortex-M3's kernel spent ~12% of a Q16.16 frame in __aeabi_uldivmod).
 * Long division in base 2^16: N = a 2^16 + h, h = floor(b / 2), is
 * nh 2^16 + nl with nh = a + floor(h / 2^16) < 2^32, nl = h mod 2^16;
 * q1 = floor(nh / b), r1 = nh - q1 b, and the quotient is q1 2^16 + q2,
 * q2 = floor(n2 / b) < 2^16 for n2 = r1 2^16 + nl < b 2^16.  For b < 2^16,
 * n2 < 2^32: one more division.  Else, with k = bit length of b - 16 (1 ..
 * 15) and D = floor(b / 2^k) + 1 (2^15 < D <= 2^16, b < 2^k D <= b + 2^k),
 * q = floor(floor(n2 / 2^k) / D) (floor(n2 / 2^k) < 2^32) is at most q2
 * and short of it by less than n2 (2^k D - b) / (b 2^k D) + 1 / D + 1 <
 * 2^16 / D + 1.0001 < 3.0001: at most three steps up (tests/test_real.c
 * div_nonneg32_matches). */
static inline tg_real tgi_div_nonneg32(tg_real a, tg_real b)
{
    const uint32_t d = (uint32_t)b, h = d >> 1, nh = (uint32_t)a + (h >> 16), nl = h & 0xFFFFu;
    const uint32_t q1 = nh / d, r1 = nh - q1 * d;
    uint32_t q2;
    if (d < 0x10000u) {
        q2 = ((r1 << 16) | nl) / d;
    } else {
        const int k = tgi_bit_length64(d) - 16;
        const uint64_t n2 = ((uint64_t)r1 << 16) | nl;
        uint64_t rem;
        q2 = (uint32_t)(n2 >> k) / ((d >> k) + 1u);
        rem = n2 - (uint64_t)q2 * d;
        while (rem >= d) { q2++; rem -= d; }
    }
    return (tg_real)((q1 << 16) + q2);
}
#if !TGI_CORE64 && (defined(__ARM_FEATURE_IDIV) || defined(__riscv_div))
#define TGI_DIV32 1
#else
#define TGI_DIV32 0
#endif
/* tgi_div_pos for a >= 0 too: the rounding's half divisor a shift and the
 * division unsigned, the same quotient (a non-negative one truncates alike);
 * in 32-bit divisions where a 64-bit one is a library call (TGI_DIV32) */
static inline tg_real tgi_div_nonneg(tg_real a, tg_real b)
{
#if TG_OUTLINE_HELPERS
    return tgi_div_pos(a, b);
#elif TGI_DIV32
    return tgi_div_nonneg32(a, b);
#else
    const uint64_t den = (uint64_t)(uint32_t)b;
    return (tg_real)((((uint64_t)(uint32_t)a << 16) + (den >> 1)) / den);
#endif
}
#else
typedef float tgi_wide;
static inline tgi_wide tgi_wide_mul(tgi_wide a, tgi_wide b) { return a * b; }
static inline tgi_wide tgi_wide_dot(tgi_wide ax, tgi_wide ay, tgi_wide az, tgi_wide bx, tgi_wide by, tgi_wide bz)
{
    return ax * bx + ay * by + az * bz;
}
static inline tg_real tgi_wide_real(tgi_wide a) { return a; }
static inline tg_real tgi_div_pos(tg_real a, tg_real b) { return a / b; }
static inline tg_real tgi_div_nonneg(tg_real a, tg_real b) { return a / b; }
#endif

/* tg_mul(a, b) for a product provably within the range (each use says
 * why): in a TGI_Q16_WIDE build tg_mul's integer without its saturation
 * test, elsewhere tg_mul itself (a build for size keeps its one function;
 * float has nothing to skip). */
#if TGI_Q16_WIDE
static inline tg_real tgi_mul_in_range(tg_real a, tg_real b) { return (tg_real)tgi_wide_mul(a, b); }
#else
#define tgi_mul_in_range tg_mul
#endif

/* acc + w v, a running weighted sum in tgi_wide (tgi_wide_real gives its
 * value), for weights w within [0, 1].  Q16.16: tg_add's running sum of
 * tg_mul's products saturates at each step; for 0 <= w <= 1 and v >= 0 the
 * product is within [0, v] (tg_mul's rounding, never saturating) and the
 * sum only grows, so its saturation can wait to the end (acc never goes
 * below TG_REAL_MIN: a saturated step puts it back in range, a product of
 * this kind adds to it); any other term saturates the sum so far and adds
 * its product saturating, as tg_add and tg_mul do.  Float: acc + w v. */
#if TG_FIXED
static inline tgi_wide tgi_wide_add_weighted(tgi_wide acc, tg_real w, tg_real v)
{
    if ((uint32_t)w <= (uint32_t)TG_ONE && v >= 0) return acc + (((int64_t)w * v + 32768) >> 16);
    return tg_add(tgi_sat64(acc), tg_mul(w, v));
}
#else
static inline tgi_wide tgi_wide_add_weighted(tgi_wide acc, tg_real w, tg_real v) { return acc + w * v; }
#endif

/* ---- the exact reciprocal square root ----
 * tg_rsqrt's steps (real.c), inline for the kernels' calls of positive x
 * (the HBIL kernel's six a pixel in Q16.16: one call and two returns, its
 * test of x <= 0 and the call into rsqrt_q30 fewer; the same operations,
 * so the same bits for every x > 0: checked against the previous
 * out-of-line tg_rsqrt at every x in (0, 2^31), 0 differ, by a program
 * linking 93f6823's libtinygi-fixed.a, session 36). */
/* 1/sqrt(M) in Q30 at the middle of [i/64, (i+1)/64), i = 16..63 (real.c). */
extern const uint32_t tgi_rsqrt_seed_q30_64[48];

/* 1/sqrt(M) in Q30 for M in [1/4, 1) given in Q32 (relative error about
 * 2^-29): table seed (1.5%), then three Newton steps
 * y <- y (3 - M y^2) / 2 in integers. */
static inline uint64_t tgi_rsqrt_step_q30(uint64_t m, uint64_t y)
{
    const uint64_t my2 = (m * ((y * y) >> 30)) >> 32; /* M y^2, Q30 */
    return (y * (3 * ((uint64_t)1 << 30) - my2)) >> 31;
}
static inline uint64_t tgi_rsqrt_q30(uint64_t m)
{
    uint64_t y = tgi_rsqrt_seed_q30_64[(m >> 26) - 16];
#if TG_OUTLINE_HELPERS   /* compiling for size: the loop */
    int i;
    for (i = 0; i < 3; i++) y = tgi_rsqrt_step_q30(m, y);
#else   /* the three steps written out: gcc -O2 kept the loop (its counter, 2 instructions a step) */
    y = tgi_rsqrt_step_q30(m, y);
    y = tgi_rsqrt_step_q30(m, y);
    y = tgi_rsqrt_step_q30(m, y);
#endif
    return y;
}

#if TG_FIXED
/* tg_rsqrt(x) for x > 0 (not compiling for size: real.c's form).
 * mantissa_even without its branch: 0 < x < 2^31 has bl = 32 - c bits
 * (c = clz32(x) >= 1); for s = c & ~1, M = x << s in Q32 (bl even: s = c,
 * x 2^(32 - bl); bl odd: s = c - 1, x 2^(32 - bl) / 2 exactly) and e =
 * 32 - s (bl rounded up to even): mantissa_even's M and e.  Then the
 * rounding (y + 2^(k - 1)) >> k, k = 6 + e/2 = 22 - s/2, as ((y >> (k -
 * 1)) + 1) >> 1 (the offset a multiple of 2^(k - 1): the same floor);
 * y <= 2^31, so the result < 2^26 needs no saturation test */
static inline tg_real tgi_rsqrt_pos(tg_real x)
{
    const int s = tgi_clz32_nz((uint32_t)x) & ~1;
    const uint64_t y = tgi_rsqrt_q30((uint64_t)(uint32_t)x << s);
    return (tg_real)(((y >> (21 - s / 2)) + 1) >> 1);
}
#endif

/* ---- the per-pixel reciprocal square root ----
 * Cheaper than tg_rsqrt (two Newton steps instead of three, and no range
 * handling), for the rasterizer's per-pixel normals, whose error stays below
 * the number type's step; error bounds measured by tests/test_real.c. */
#if TG_FIXED
/* rsqrt at the midpoints of [1, 4) split in 24 steps of 1/8, Q30 (real.c). */
extern const uint32_t tgi_rsqrt_seed_q30[24];

/* 1/sqrt(X) in Q30 for X = x30 / 2^30 in [1, 4): table seed within 3.2%,
 * then two Newton steps y (3 - X y^2) / 2 in integers (rel. error 3e-6). */
static inline uint64_t tgi_rsqrt_q30_fast(uint64_t x30)
{
    uint64_t y = tgi_rsqrt_seed_q30[(x30 >> 27) - 8], t;
    t = (((y * y) >> 30) * x30) >> 30;            /* X y^2, Q30 */
    y = (y * ((3u << 30) - t)) >> 31;
    t = (((y * y) >> 30) * x30) >> 30;
    return (y * ((3u << 30) - t)) >> 31;
}
#else
/* 1/sqrt(x) for a normal float x > 0: bit-trick seed (within 0.18% after
 * the first step) and two Newton steps, rel. error < 5e-6. */
static inline float tgi_rsqrt_fast(float x)
{
    float y = tgi_f_from_bits(0x5f375a86u - (tgi_f_bits(x) >> 1));
    y = y * (1.5f - 0.5f * x * y * y);
    return y * (1.5f - 0.5f * x * y * y);
}
#endif

#endif
