/* SPDX-License-Identifier: MIT */
/*
 * unit.h - tgi_v3_normalize_or (vec.c) for the per-pixel loops, inline and
 * in fewer instructions, with the same bits.
 *
 * Q16.16: vec.c's normalize_n for three components (the vector shifted so
 * its largest component has 30 significant bits, the exact sum of squares
 * S, 2|w| = sqrt(4 S) rounded, one division for 2^62 / (2|w|), each
 * component w 2^62 / (2|w|) rounded at bit 45) with the integer square root
 * taken from tgi_rsqrt_q30_fast (real.h) and one Newton step instead of
 * tgi_isqrt64's general one: both are then made exact by the same integer
 * tests, so the root, and everything after it, is the same.  Float: vec.c's
 * own (the call).  tests/test_real.c compares the two over millions of
 * vectors and the square root over millions of values.
 */
#ifndef TG_UNIT_H
#define TG_UNIT_H

#include "vec.h"

#if TG_FIXED
/* floor(sqrt(v)) for v in [2^60, 2^64 - 2^62] (tgi_isqrt64's result there):
 * X = v >> t in [2^30, 2^32) for an even t, sqrt(v) ~ X y 2^(t/2 - 45)
 * with y = 2^30 / sqrt(X / 2^30) from tgi_rsqrt_q30_fast (relative error
 * below 1e-5: within 2^15 of the root, which is below 2^32); one Newton
 * step r = (r + v / r) / 2 then leaves it within 1 (the error squared over
 * 2 r, below 1/2, plus the step's truncation), and the tests make it
 * exact (each loop at most a step or two; (r + 1)^2 < 2^64 throughout). */
static inline uint64_t tgi_isqrt64_upper(uint64_t v)
{
    int b = tgi_bit_length64(v), t = (b - 31) & ~1;
    uint64_t x = v >> t, r = (x * tgi_rsqrt_q30_fast(x)) >> (45 - t / 2);
    r = (r + v / r) >> 1;
    while (r * r > v) r--;
    while ((r + 1) * (r + 1) <= v) r++;
    return r;
}
#endif

/* tgi_v3_normalize_or(a, fallback): a / |a|, fallback for the zero vector. */
static inline tg_vec3 tgi_v3_unit_or(tg_vec3 a, tg_vec3 fallback)
{
#if TG_FIXED
    int64_t ax = a.x < 0 ? -(int64_t)a.x : a.x, ay = a.y < 0 ? -(int64_t)a.y : a.y, az = a.z < 0 ? -(int64_t)a.z : a.z;
    int64_t m = ax > ay ? ax : ay, wx, wy, wz, inv;
    uint64_t v, r;
    int s;
    m = m > az ? m : az;
    if (m == 0) return fallback;
    s = 30 - tgi_bit_length64((uint64_t)m);   /* largest |w| in [2^29, 2^30) */
    if (s >= 0) {
        wx = (int64_t)a.x * ((int64_t)1 << s); wy = (int64_t)a.y * ((int64_t)1 << s); wz = (int64_t)a.z * ((int64_t)1 << s);
    } else {
        wx = tgi_shr_round(a.x, -s); wy = tgi_shr_round(a.y, -s); wz = tgi_shr_round(a.z, -s);
    }
    /* 4 S in [2^60, 3 2^62): the largest |w| >= 2^29 (a rounding down to
     * 2^29 at most), each below 2^30 + 1 */
    v = ((uint64_t)(wx * wx) + (uint64_t)(wy * wy) + (uint64_t)(wz * wz)) << 2;
    r = tgi_isqrt64_upper(v);
    r += v - r * r > r;                       /* tgi_isqrt_round64: 2 |w|, in [2^30, 2^32] */
    inv = (int64_t)((((uint64_t)1 << 62) + r / 2) / r);
    return tg_v3(tgi_sat64(tgi_shr_round(wx * inv, 45)), tgi_sat64(tgi_shr_round(wy * inv, 45)),
                 tgi_sat64(tgi_shr_round(wz * inv, 45)));
#else
    return tgi_v3_normalize_or(a, fallback);
#endif
}

#endif
