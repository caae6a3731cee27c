/* SPDX-License-Identifier: MIT */
/*
 * test_real.c - the scalar API against libm, over each function's whole
 * domain, for the number type of this build; saturation at the range ends;
 * the decimal parser (rounding, overflow, garbage).
 *
 * Every sweep prints "measured FUNCTION: ..." with the worst error found and
 * where, and asserts the bound documented at the top of src/core/real.c.
 *
 * Error measures:
 *   fixed : |f - ref| in ulps (2^-16), divided by max(1, |ref|): absolute
 *           for results up to 1, relative (in units of 2^-16) above;
 *   float : relative |f - ref| / |ref|; for sin/cos within 1e-2 of a zero
 *           other than x = 0 (where relative error is meaningless) the
 *           absolute error is measured and bounded instead.
 */
#include "check.h"
#include "core/real.h"
#include "core/text.h"
#include "core/unit.h"
#include <stdlib.h>
#include <stdint.h>
#include <float.h>

#define BIG_ERR 1e300

typedef struct stat {
    const char *name;
    double worst, at_x, at_y;
    double worst_abs, abs_x; /* float: absolute error near zeros */
    long n, n_abs;
} stat;

static void stat_init(stat *s, const char *name)
{
    memset(s, 0, sizeof *s);
    s->name = name;
}

static void stat_add(stat *s, double e, double x, double y)
{
    if (!(e <= s->worst)) { s->worst = e == e ? e : BIG_ERR; s->at_x = x; s->at_y = y; }
    s->n++;
}

#if !TG_FIXED
static void stat_add_abs(stat *s, double e, double x)
{
    if (!(e <= s->worst_abs)) { s->worst_abs = e == e ? e : BIG_ERR; s->abs_x = x; }
    s->n_abs++;
}
#endif

static void stat_print(const stat *s)
{
#if TG_FIXED
    printf("measured %-10s fixed: worst %.4f ulp (x %.9g, y %.9g), %ld points\n", s->name,
           s->worst, s->at_x, s->at_y, s->n);
#else
    printf("measured %-10s float: worst rel %.3g (x %.9g, y %.9g), %ld points", s->name, s->worst,
           s->at_x, s->at_y, s->n);
    if (s->n_abs) printf("; near zeros abs %.3g (x %.9g), %ld points", s->worst_abs, s->abs_x, s->n_abs);
    printf("\n");
#endif
    fflush(stdout);
}


#if !TG_FIXED
static float from_bits(uint32_t b) { float f; memcpy(&f, &b, sizeof f); return f; }
#endif

/* Record one result against its reference. */
static void measure(stat *s, tg_real got, double ref, double x, double y, int zero_is_abs)
{
    double g = check_exact(got);
#if TG_FIXED
    double m = fabs(ref) > 1.0 ? fabs(ref) : 1.0;
    (void)zero_is_abs;
    stat_add(s, fabs(g - ref) * 65536.0 / m, x, y);
#else
    if ((zero_is_abs && fabs(ref) < 1e-2) || fabs(ref) < (double)FLT_MIN) stat_add_abs(s, fabs(g - ref), x);
    else if (ref == 0.0) stat_add(s, g == 0.0 ? 0.0 : BIG_ERR, x, y);
    else stat_add(s, fabs(g - ref) / fabs(ref), x, y);
#endif
}

/* bound check: fixed bound in ulps, float relative and absolute bounds */
static void check_stat(const stat *s, double fixed_ulps, double float_rel, double float_abs)
{
    stat_print(s);
#if TG_FIXED
    (void)float_rel; (void)float_abs;
    CHECK(s->worst <= fixed_ulps, "%s: worst %.4f ulp > %.4f at x=%.9g y=%.9g", s->name, s->worst,
          fixed_ulps, s->at_x, s->at_y);
#else
    (void)fixed_ulps;
    CHECK(s->worst <= float_rel, "%s: worst rel %.3g > %.3g at x=%.9g y=%.9g", s->name, s->worst,
          float_rel, s->at_x, s->at_y);
    if (float_abs < (double)FLT_MIN) float_abs = (double)FLT_MIN; /* results below FLT_MIN: absolute */
    CHECK(s->worst_abs <= float_abs, "%s: worst abs %.3g > %.3g at x=%.9g", s->name, s->worst_abs,
          float_abs, s->abs_x);
#endif
    CHECK(s->n > 1000, "%s: only %ld points", s->name, s->n);
}

/* ---- sweeps over a 1-argument function ---- */
typedef tg_real (*fn1)(tg_real);
typedef double (*ref1)(double);

#if TG_FIXED
/* every raw value in [lo, hi] with the given step */
static void sweep_raw(stat *s, fn1 f, ref1 r, int64_t lo, int64_t hi, int64_t step, int zero_abs)
{
    int64_t i;
    for (i = lo; i <= hi; i += step) {
        tg_real x = (tg_real)i;
        measure(s, f(x), r(check_exact(x)), check_exact(x), 0, zero_abs);
    }
}
#else
/* n points uniform in [lo, hi] */
static void sweep_uniform(stat *s, fn1 f, ref1 r, double lo, double hi, long n, int zero_abs)
{
    long i;
    for (i = 0; i <= n; i++) {
        float x = (float)(lo + (hi - lo) * (double)i / (double)n);
        measure(s, f(x), r((double)x), (double)x, 0, zero_abs);
    }
}
/* every `step`-th float bit pattern with magnitude in [lo, hi], both signs
 * when `neg` */
static void sweep_bits(stat *s, fn1 f, ref1 r, float lo, float hi, uint32_t step, int neg, int zero_abs)
{
    uint32_t b, blo, bhi;
    memcpy(&blo, &lo, 4);
    memcpy(&bhi, &hi, 4);
    for (b = blo; b <= bhi && b >= blo; b += step) {
        float x = from_bits(b);
        measure(s, f(x), r((double)x), (double)x, 0, zero_abs);
        if (neg) measure(s, f(-x), r(-(double)x), -(double)x, 0, zero_abs);
    }
}
#endif

/* ---- sqrt, rsqrt ---- */

static double ref_rsqrt(double x) { return 1.0 / sqrt(x); }

TEST(sqrt_whole_domain)
{
    stat s;
    stat_init(&s, "tg_sqrt");
#if TG_FIXED
    {
        /* exact rounding: (2r - 1)^2 <= 4 v <= (2r + 1)^2, v = x_raw 2^16 */
        int64_t i;
        long bad = 0;
        for (i = 0; i <= INT32_MAX; i += (i < (1 << 22) ? 1 : 509)) {
            uint64_t v = (uint64_t)i << 16, r = (uint64_t)tg_sqrt((tg_real)i);
            if (i > 0 && !((2 * r - 1) * (2 * r - 1) <= 4 * v && 4 * v <= (2 * r + 1) * (2 * r + 1))) {
                if (bad++ < 5) fprintf(stderr, "sqrt raw %lld -> %llu\n", (long long)i, (unsigned long long)r);
            }
            /* the size build's tg_sqrt (TG_OUTLINE_HELPERS, real.c) gives the same */
            if (tgi_isqrt_round64(v) != r && bad++ < 5)
                fprintf(stderr, "size-build sqrt raw %lld -> %llu, not %llu\n", (long long)i,
                        (unsigned long long)tgi_isqrt_round64(v), (unsigned long long)r);
            measure(&s, (tg_real)r, sqrt(check_exact((tg_real)i)), check_exact((tg_real)i), 0, 0);
        }
        /* and the top end exactly */
        measure(&s, tg_sqrt(TG_REAL_MAX), sqrt(check_exact(TG_REAL_MAX)), check_exact(TG_REAL_MAX), 0, 0);
        CHECK(bad == 0, "%ld sqrt results not correctly rounded", bad);
    }
    check_stat(&s, 0.5 + 1e-9, 0, 0);
#else
    sweep_bits(&s, tg_sqrt, sqrt, from_bits(1), FLT_MAX, 1021, 0, 0);
    sweep_uniform(&s, tg_sqrt, sqrt, 0.0, 4.0, 400000, 0);
    check_stat(&s, 0, 2.5e-7, 0);
#endif
    CHECK(tg_sqrt(0) == 0, "sqrt(0)");
    CHECK(tg_sqrt(tg_neg(TG_ONE)) == 0, "sqrt(-1) must give 0");
    CHECK(tg_sqrt(TG_R(4.0f)) == TG_R(2.0f), "sqrt(4) exact");
}

#if TG_FIXED
/* The rounding boundaries of the Q16.16 sqrt: sqrt(v), v = x_raw 2^16, is
 * R + 1/2 between the neighbouring x_raw floor((R + 1/2)^2 2^-16) and the
 * next, for every R the range holds, so those two must give R and R + 1
 * (tg_sqrt's quadratic estimate is furthest off at the top of the range,
 * where one step of the final correction has to do it). */
TEST(sqrt_rounding_boundaries)
{
    uint64_t r;
    long bad = 0;
    for (r = 256; (r + 1) * (r + 1) <= ((uint64_t)INT32_MAX << 16); r++) {
        uint64_t b = r * r + r;                        /* floor((r + 1/2)^2) */
        int64_t lo = (int64_t)(b >> 16), k;            /* lo 2^16 <= b < (r + 1/2)^2 <= (lo + 1) 2^16 */
        for (k = lo; k <= lo + 1 && k <= INT32_MAX; k++) {
            uint64_t v = (uint64_t)k << 16, q = (uint64_t)tg_sqrt((tg_real)k);
            if (!((2 * q - 1) * (2 * q - 1) <= 4 * v && 4 * v <= (2 * q + 1) * (2 * q + 1)) && bad++ < 5)
                fprintf(stderr, "sqrt near (%llu + 1/2)^2: raw %lld -> %llu\n", (unsigned long long)r,
                        (long long)k, (unsigned long long)q);
        }
    }
    CHECK(bad == 0, "%ld sqrt results near rounding boundaries not correctly rounded", bad);
    CHECK(r > 11800000, "boundaries up to the top of the range (%llu)", (unsigned long long)r);
}
#endif

/* floor(sqrt(v)) for 64-bit v: r^2 <= v < (r+1)^2 */
static int isqrt_ok(uint64_t v, uint32_t r)
{
    uint64_t r1 = (uint64_t)r + 1;
    if ((uint64_t)r * r > v) return 0;
    return r1 == ((uint64_t)1 << 32) || r1 * r1 > v;
}

#if TG_FIXED
/* Q16.16's rounding shift (every product's rounding, tinygi.h
 * tgi_shr_round): p 2^-s to the nearest integer, a tie toward +infinity,
 * for either sign of p: |p - r 2^s| <= 2^(s-1), and r 2^s > p at a tie.
 * Random p (|p| < 2^61, as every caller's) and shifts, each p's ties and
 * their neighbours, and tg_mul's ties: +-1.5 ulp and +-0.5 ulp. */
TEST(rounding_shift_ties_toward_plus_infinity)
{
    uint64_t v = 0x2545f4914f6cdd1dull;
    long bad = 0, ties = 0, i;
    for (i = 0; i < 4000000; i++) {
        int64_t p, r, e, half;
        int sh;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        p = (int64_t)v >> (3 + (int)((v >> 33) & 31));
        sh = 1 + (int)((v >> 20) % 48);
        half = (int64_t)1 << (sh - 1);
        if (i & 1) p = (p / (2 * half)) * (2 * half) + ((p < 0) ? -half : half);   /* a tie */
        r = tgi_shr_round(p, sh);
        e = p - r * (2 * half);                    /* the rounding's error, times 2^sh */
        ties += e == half || e == -half;
        if ((e > half || e < -half || e == half) && bad++ < 5)
            fprintf(stderr, "p %lld >> %d: %lld (error %lld of %lld)\n", (long long)p, sh, (long long)r, (long long)e,
                    (long long)half);
    }
    CHECK(bad == 0 && ties > 1000000, "%ld rounding shifts not to nearest, ties up (%ld ties)", bad, ties);
    CHECK(tg_mul(3, 32768) == 2 && tg_mul(-3, 32768) == -1 && tg_mul(1, 32768) == 1 && tg_mul(-1, 32768) == 0,
          "tg_mul's ties: 1.5 ulp -> %d, -1.5 -> %d, 0.5 -> %d, -0.5 -> %d", (int)tg_mul(3, 32768),
          (int)tg_mul(-3, 32768), (int)tg_mul(1, 32768), (int)tg_mul(-1, 32768));
}
#endif

#if TG_FIXED
/* The size build's out-of-line rounding shift and division (tinygi.h,
 * TG_OUTLINE_HELPERS) against the inline ones every other build uses:
 * edges (0, +-1, the extremes, division by 0) and random operands. */
TEST(outline_div_and_shift_match_inline)
{
    static const int32_t edge[] = { 0, 1, -1, 2, -2, 32767, 32768, -32768, 65535, 65536, -65536,
                                    INT32_MAX, -INT32_MAX, INT32_MIN, INT32_MAX - 1, 123456789 };
    uint64_t v = 0x9e3779b97f4a7c15ull;
    long bad = 0;
    int i, j, n = (int)(sizeof edge / sizeof edge[0]);
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++)
            if (tgi_div_q16(edge[i], edge[j]) != tg_div(edge[i], edge[j])) bad++;
    for (i = 0; i < 4000000; i++) {
        int32_t a, b;
        int64_t p;
        int sh;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        a = (int32_t)(uint32_t)v >> (int)(v >> 59);        /* all magnitudes */
        b = (int32_t)(uint32_t)(v >> 32) >> (int)((v >> 40) & 31);
        p = (int64_t)v >> (2 + (int)((v >> 33) & 31));     /* |p| < 2^61, as every caller's is */
        sh = 1 + (int)((v >> 20) % 61);                    /* p + 2^(sh-1) stays below 2^62 */
        if (tgi_div_q16(a, b) != tg_div(a, b)) bad++;
        if (tgi_shr_round_q16(p, sh) != tgi_shr_round(p, sh)) bad++;
    }
    CHECK(bad == 0, "%ld out-of-line results differ from the inline ones", bad);
}

/* tg_div rounds to nearest, halves away from zero, whatever the signs: in
 * Q16.16 a/b is the integer nearest a 2^16 / b, and the four sign cases are
 * the same magnitude.  It added half the divisor toward the wrong side
 * when b < 0: tg_div(-1, -2) gave 0.5 - 2^-16 and tg_div(3, -2) gave
 * -1.5 + 2^-16, one unit off on exact quotients (found by the
 * fixedmarch12 work; sample_depth_edge divides two negatives). */
TEST(div_rounds_alike_for_every_sign)
{
#if TG_FIXED
    unsigned seed = 2024u;
    long bad = 0, n = 0;
    int i;
    CHECK(tg_div(tg_neg(TG_ONE), TG_R(-2.0f)) == TG_R(0.5f), "-1 / -2 = %d / 65536", tg_div(tg_neg(TG_ONE), TG_R(-2.0f)));
    CHECK(tg_div(TG_R(3.0f), TG_R(-2.0f)) == TG_R(-1.5f), "3 / -2 = %d / 65536", tg_div(TG_R(3.0f), TG_R(-2.0f)));
    CHECK(tg_div(3, -2) == -98304, "3 ulp / -2 ulp = %d (1.5 = 98304)", tg_div(3, -2));
    for (i = 0; i < 2000000; i++) {
        int32_t a, b;
        int64_t num, q, want;
        seed = seed * 1103515245u + 12345u; a = (int32_t)(seed >> 1) >> (seed % 20);
        seed = seed * 1103515245u + 12345u; b = (int32_t)(seed >> 1) >> (seed % 28);
        if (seed & 1) a = -a;
        if (seed & 2) b = -b;
        if (b == 0) continue;
        num = (int64_t)a * 65536;
        q = (num < 0 ? -num : num) / (b < 0 ? -(int64_t)b : b);                  /* |a 2^16 / b|, floor */
        if (2 * ((num < 0 ? -num : num) - q * (b < 0 ? -(int64_t)b : b)) >= (b < 0 ? -(int64_t)b : b)) q++;  /* half away */
        want = ((num < 0) != (b < 0)) ? -q : q;
        if (want > TG_REAL_MAX) want = TG_REAL_MAX;
        if (want < TG_REAL_MIN) want = TG_REAL_MIN;
        n++;
        if (tg_div(a, b) != (tg_real)want || tgi_div_q16(a, b) != (tg_real)want) bad++;
    }
    CHECK(n > 1000000 && bad == 0, "%ld of %ld quotients not rounded to nearest", bad, n);
#endif
}

/* tgi_div_pos (core/real.h) is tg_div for b > 0 wherever the quotient
 * fits tg_real (tg_div does not saturate), including the halves that round
 * away from zero. */
TEST(div_pos_matches_div)
{
    uint64_t v = 0x2545f4914f6cdd1dull;
    long bad = 0, n = 0;
    int i;
    for (i = 0; i < 4000000; i++) {
        int64_t a, q;
        int32_t b;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        a = (int64_t)(int32_t)(uint32_t)v >> (int)(v >> 59);
        b = (int32_t)((uint32_t)(v >> 32) >> (1 + (int)((v >> 40) % 31)));   /* 0 .. 2^31 - 1 */
        if (b <= 0) continue;
        if (i & 1) a = (a / 65536) * b + ((v >> 20) & 1 ? b / 2 : -(b / 2));   /* a tie: a 2^16 / b = k + 1/2 */
        q = ((a < 0 ? -a : a) * 65536 + b / 2) / b;
        if (q > INT32_MAX || a > INT32_MAX || a < -INT32_MAX) continue;
        n++;
        if (tgi_div_pos((tg_real)a, b) != tg_div((tg_real)a, b)) bad++;
    }
    CHECK(n > 1000000 && bad == 0, "%ld of %ld quotients differ from tg_div", bad, n);
}
#endif

#if TG_FIXED
/* tgi_div_nonneg32 (core/real.h, the 32-bit cores' tgi_div_nonneg) is the
 * 64-bit form's quotient floor((a 2^16 + floor(b / 2)) / b) mod 2^32 for
 * every a >= 0, b > 0: divisors at and around each power of two (both
 * branches and their edges, the correction steps' worst cases near 2^k D
 * - b = 2^k), numerators at 0, 2^31 - 1 and random, quotients past 2^32
 * included (truncated alike). */
TEST(div_nonneg32_matches)
{
    uint64_t v = 0x9e3779b97f4a7c15ull;
    long bad = 0, n = 0;
    int i, e, j;
    for (i = 0; i < 3000000; i++) {
        uint32_t a, b;
        uint64_t want;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        a = (uint32_t)(v >> 33) >> (int)((v >> 8) % 32);                      /* 0 .. 2^31 - 1 */
        b = ((uint32_t)v >> 1) >> (int)((v >> 16) % 31);                      /* 0 .. 2^31 - 1 */
        if (i % 4 == 1) b = ((uint32_t)1 << ((v >> 24) % 31)) + (uint32_t)((v >> 40) % 5) - 2;   /* near 2^k */
        if (i % 4 == 2) b |= 0xFFFFu >> ((v >> 28) % 16);                    /* low bits set: 2^k D - b near 2^k */
        if (i % 8 == 3) a = (v >> 50) & 1 ? 0x7FFFFFFFu : 0;
        if (b == 0 || b > 0x7FFFFFFFu) continue;
        want = ((((uint64_t)a << 16) + (b >> 1)) / b) & 0xFFFFFFFFu;
        n++;
        if ((uint32_t)tgi_div_nonneg32((tg_real)a, (tg_real)b) != (uint32_t)want) bad++;
    }
    for (e = 0; e < 31; e++)                                                  /* every divisor's bit length, both ends */
        for (j = 0; j < 2; j++) {
            const uint32_t b = j ? (e == 30 ? 0x7FFFFFFFu : ((uint32_t)2 << e) - 1) : (uint32_t)1 << e;
            uint64_t a;
            for (a = 0; a <= 0x7FFFFFFFu; a = a < 0x7FFFFFFFu && a * 3 + 0xFFFFu > 0x7FFFFFFFu ? 0x7FFFFFFFu : a * 3 + 0xFFFFu) {
                uint64_t want = (((a << 16) + (b >> 1)) / b) & 0xFFFFFFFFu;
                n++;
                if ((uint32_t)tgi_div_nonneg32((tg_real)a, (tg_real)b) != (uint32_t)want) bad++;
            }
        }
    CHECK(n > 2000000 && bad == 0, "%ld of %ld quotients differ from the 64-bit division", bad, n);
}
#endif

TEST(isqrt64_exact)
{
    uint64_t k, v = 88172645463325252ull;
    long i, bad = 0;
    CHECK(tgi_isqrt64(0) == 0 && tgi_isqrt64(1) == 1 && tgi_isqrt64(3) == 1 && tgi_isqrt64(4) == 2, "small");
    CHECK(tgi_isqrt64(UINT64_MAX) == 0xffffffffu, "isqrt(2^64-1) = 2^32-1");
    k = 0xffffffffu;
    CHECK(tgi_isqrt64(k * k) == k && tgi_isqrt64(k * k - 1) == k - 1 && tgi_isqrt64(k * k + 1) == k, "near 2^64");
    CHECK(tgi_isqrt64((uint64_t)1 << 62) == (uint32_t)1 << 31 && tgi_isqrt64(((uint64_t)1 << 62) - 1) == ((uint32_t)1 << 31) - 1,
          "2^62");
    for (k = 1; k < ((uint64_t)1 << 32); k = k * 3 + 1) {
        if (tgi_isqrt64(k * k) != k || (k > 1 && tgi_isqrt64(k * k - 1) != k - 1)) bad++;
    }
    for (i = 0; i < 2000000; i++) { /* xorshift64 over the whole range, and shifted down */
        uint64_t w;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        w = v >> (i % 64);
        if (!isqrt_ok(w, tgi_isqrt64(w))) bad++;
    }
    for (k = 0; k < 2000000; k++) if (!isqrt_ok(k, tgi_isqrt64(k))) bad++;
    CHECK(bad == 0, "%ld wrong integer square roots", bad);
}

#if TG_FIXED
/* unit.h's square root against tgi_isqrt64 over its whole domain [2^60,
 * 3 2^62]: its ends, every square k^2 and its neighbours there (a step of
 * 1/2^20 of the range), and 4e6 random values. */
TEST(isqrt64_upper_matches)
{
    uint64_t lo = (uint64_t)1 << 60, hi = 3 * ((uint64_t)1 << 62), k, v = 0x9E3779B97F4A7C15ull;
    long i, n = 0, bad = 0;
    for (k = 1u << 30; k * k <= hi; k += 1 + (k >> 20)) {   /* squares and their neighbours */
        uint64_t sq = k * k, w;
        for (w = sq - 1; w <= sq + 1; w++)
            if (w >= lo && w <= hi) { n++; bad += tgi_isqrt64_upper(w) != tgi_isqrt64(w); }
    }
    bad += tgi_isqrt64_upper(lo) != tgi_isqrt64(lo);
    bad += tgi_isqrt64_upper(hi) != tgi_isqrt64(hi);
    for (i = 0; i < 4000000; i++) {
        uint64_t w;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        w = lo + v % (hi - lo + 1);
        n++;
        bad += tgi_isqrt64_upper(w) != tgi_isqrt64(w);
    }
    CHECK(n > 5000000 && bad == 0, "%ld of %ld roots differ from tgi_isqrt64", bad, n);
}
#endif

/* tgi_v3_unit_or gives tgi_v3_normalize_or's bits: 6e6 random vectors
 * with components of random magnitude (from a few ulps to the range's
 * ends, each component its own), axis-aligned ones, the zero vector (the
 * fallback) and the range's corners. */
TEST(unit_or_matches_normalize_or)
{
    uint64_t v = 0x2545F4914F6CDD1Dull;
    long i, bad = 0;
    tg_vec3 fb = tg_v3(TG_R(0.25f), 0, TG_R(-0.5f)), a, u, w;
    static const tg_real ends[] = { TG_REAL_MAX, TG_REAL_MIN, 0, 1, -1, TG_ONE, TG_R(-0.5f) };
    int x, y, z;
    for (x = 0; x < 7; x++)
        for (y = 0; y < 7; y++)
            for (z = 0; z < 7; z++) {
                a = tg_v3(ends[x], ends[y], ends[z]);
                u = tgi_v3_unit_or(a, fb); w = tgi_v3_normalize_or(a, fb);
                bad += u.x != w.x || u.y != w.y || u.z != w.z;
            }
    for (i = 0; i < 6000000; i++) {
        tg_real c[3];
        int j;
        for (j = 0; j < 3; j++) {
            uint32_t r;
            v ^= v << 13; v ^= v >> 7; v ^= v << 17;
            r = (uint32_t)(v >> 32);
#if TG_FIXED
            c[j] = (tg_real)((int32_t)r >> (int)(v % 32));       /* every magnitude */
#else
            c[j] = (float)(int32_t)r * tg_ldexp(1.0f, (int)(v % 80) - 70);
#endif
            if ((v >> 8) % 7 == 0) c[j] = 0;                      /* axis-aligned and zero vectors */
        }
        a = tg_v3(c[0], c[1], c[2]);
        u = tgi_v3_unit_or(a, fb); w = tgi_v3_normalize_or(a, fb);
        bad += u.x != w.x || u.y != w.y || u.z != w.z;
    }
    CHECK(bad == 0, "%ld vectors normalised differently", bad);
}

TEST(rsqrt_whole_domain)
{
    stat s;
    stat_init(&s, "tg_rsqrt");
#if TG_FIXED
    /* every x below 16, then a stride: 1/sqrt(2^-16) = 256 still fits */
    sweep_raw(&s, tg_rsqrt, ref_rsqrt, 1, 1 << 20, 1, 0);
    sweep_raw(&s, tg_rsqrt, ref_rsqrt, 1 << 20, INT32_MAX, 2039, 0);
    check_stat(&s, 0.501, 0, 0);
    CHECK(tg_rsqrt(1) == (tg_real)(1 << 24), "rsqrt(2^-16) = 256 exactly");
    {   /* at most 1 from 1 on (hbil.c pixel_setup's unsaturated scales; every x was tried) */
        int64_t x;
        long over = 0;
        for (x = TG_ONE; x <= INT32_MAX; x += x < 2 * TG_ONE ? 1 : 4093)
            if (tg_rsqrt((tg_real)x) > TG_ONE) over++;
        CHECK(tg_rsqrt(TG_ONE) == TG_ONE && tg_rsqrt(TG_REAL_MAX) <= TG_ONE && over == 0,
              "rsqrt above 1 for %ld x >= 1", over);
    }
#else
    sweep_bits(&s, tg_rsqrt, ref_rsqrt, from_bits(1), FLT_MAX, 1021, 0, 0);
    check_stat(&s, 0, 2.5e-7, 0);
#endif
    CHECK(tg_rsqrt(0) == TG_REAL_MAX, "rsqrt(0) saturates");
    CHECK(tg_rsqrt(tg_neg(TG_ONE)) == TG_REAL_MAX, "rsqrt(-1) saturates");
}

/* ---- trig ---- */

TEST(sin_cos_whole_domain)
{
    stat s, c;
    stat_init(&s, "tg_sin");
    stat_init(&c, "tg_cos");
#if TG_FIXED
    /* every value in [-16, 16], then the whole range with a prime stride */
    sweep_raw(&s, tg_sin, sin, -16 * 65536, 16 * 65536, 1, 0);
    sweep_raw(&s, tg_sin, sin, -(int64_t)INT32_MAX, INT32_MAX, 4093, 0);
    sweep_raw(&c, tg_cos, cos, -16 * 65536, 16 * 65536, 1, 0);
    sweep_raw(&c, tg_cos, cos, -(int64_t)INT32_MAX, INT32_MAX, 4093, 0);
    check_stat(&s, 0.501, 0, 0);
    check_stat(&c, 0.501, 0, 0);
#else
    /* near 0 (relative), a dense uniform grid, and magnitudes up to 2^22 */
    sweep_bits(&s, tg_sin, sin, 1e-30f, 4194303.0f, 1021, 1, 0);
    sweep_uniform(&s, tg_sin, sin, -20.0, 20.0, 1000000, 0);
    /* sin's zeros other than x = 0 */
    {
        stat z;
        stat_init(&z, "tg_sin@kpi");
        sweep_bits(&z, tg_sin, sin, 0.5f, 4194303.0f, 1021, 1, 1);
        sweep_uniform(&z, tg_sin, sin, 0.5, 20.0, 1000000, 1);
        check_stat(&z, 0, 2.5e-7, 1.5e-7);
    }
    sweep_bits(&c, tg_cos, cos, 1e-30f, 4194303.0f, 1021, 1, 1);
    sweep_uniform(&c, tg_cos, cos, -20.0, 20.0, 1000000, 1);
    check_stat(&s, 0, 2.5e-7, 0);
    check_stat(&c, 0, 2.5e-7, 1.5e-7);
#endif
    CHECK(tg_sin(0) == 0 && tg_cos(0) == TG_ONE, "sin(0) = 0, cos(0) = 1 exactly");
}

TEST(tan_domain)
{
    stat s;
    stat_init(&s, "tg_tan");
#if TG_FIXED
    /* every value with |x| < pi/2 - 2^-10 */
    sweep_raw(&s, tg_tan, tan, -(102944 - 64), 102944 - 64, 1, 0);
    check_stat(&s, 0.501, 0, 0);
#else
    sweep_uniform(&s, tg_tan, tan, -1.5698, 1.5698, 1000000, 0);
    sweep_bits(&s, tg_tan, tan, 1e-30f, 1.5698f, 1021, 1, 0);
    check_stat(&s, 0, 3e-7, 0);
#endif
}

TEST(asin_acos_whole_domain)
{
    stat s, c;
    stat_init(&s, "tg_asin");
    stat_init(&c, "tg_acos");
#if TG_FIXED
    /* every representable value in [-1, 1] */
    sweep_raw(&s, tg_asin, asin, -65536, 65536, 1, 0);
    sweep_raw(&c, tg_acos, acos, -65536, 65536, 1, 0);
    check_stat(&s, 0.501, 0, 0);
    check_stat(&c, 0.501, 0, 0);
#else
    sweep_uniform(&s, tg_asin, asin, -1.0, 1.0, 1000000, 0);
    sweep_bits(&s, tg_asin, asin, 1e-38f, 1.0f, 257, 1, 0);
    sweep_uniform(&c, tg_acos, acos, -1.0, 1.0, 1000000, 0);
    sweep_bits(&c, tg_acos, acos, 1e-38f, 1.0f, 257, 1, 0);
    check_stat(&s, 0, 4.5e-7, 0);
    check_stat(&c, 0, 2.5e-7, 0);
#endif
    /* clamping outside [-1, 1] */
    CHECK(tg_acos(TG_R(2.0f)) == 0, "acos(2) clamps to acos(1) = 0");
    CHECK_NEAR(check_exact(tg_acos(TG_R(-2.0f))), CHECK_PI, 2e-5);
    CHECK_NEAR(check_exact(tg_asin(TG_R(3.0f))), CHECK_PI / 2, 2e-5);
    CHECK(tg_acos(TG_ONE) == 0, "acos(1) = 0 exactly");
}

/* magnitudes for atan2 sweeps: 0 and log-spaced values, both signs */
static int atan2_values(tg_real *v, int max)
{
    int n = 0, i;
    v[n++] = 0;
#if TG_FIXED
    for (i = 0; i < 700 && n + 2 <= max; i++) {
        double m = pow(2.0, 31.0 * i / 699.0);
        int64_t r = (int64_t)m;
        if (r > INT32_MAX) r = INT32_MAX;
        r += i % 7; /* avoid only powers of two */
        if (r > INT32_MAX) r = INT32_MAX;
        v[n++] = (tg_real)r;
        v[n++] = (tg_real)-r;
    }
#else
    for (i = 0; i < 700 && n + 2 <= max; i++) {
        float m = (float)pow(10.0, -30.0 + 60.0 * i / 699.0) * (1.0f + 0.013f * (float)(i % 7));
        v[n++] = m;
        v[n++] = -m;
    }
#endif
    return n;
}

TEST(atan2_whole_domain)
{
    static tg_real v[1500];
    int n = atan2_values(v, 1500), i, j;
    stat s;
    stat_init(&s, "tg_atan2");
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            if (v[i] == 0 && v[j] == 0) continue;
            measure(&s, tg_atan2(v[i], v[j]), atan2(check_exact(v[i]), check_exact(v[j])), check_exact(v[i]),
                    check_exact(v[j]), 0);
        }
    /* and the unit circle, densely */
    for (i = 0; i < 1000000; i++) {
        double a = -CHECK_PI + 2 * CHECK_PI * i / 1000000.0;
        tg_real y = tg_from_float((float)sin(a)), x = tg_from_float((float)cos(a));
        measure(&s, tg_atan2(y, x), atan2(check_exact(y), check_exact(x)), check_exact(y), check_exact(x), 0);
    }
    check_stat(&s, 0.501, 3e-7, 0);
    CHECK(tg_atan2(0, 0) == 0, "atan2(0,0) = 0");
    CHECK(tg_atan2(0, tg_neg(TG_ONE)) == TG_PI, "atan2(0,-1) = pi");
    CHECK(tg_atan2(TG_ONE, 0) == TG_HALF_PI, "atan2(1,0) = pi/2");
}

/* ---- exp2, log2, pow ---- */

TEST(exp2_log2_whole_domain)
{
    stat e, l;
    stat_init(&e, "tg_exp2");
    stat_init(&l, "tg_log2");
#if TG_FIXED
    /* every value with a representable result: [-17, 15) */
    sweep_raw(&e, tg_exp2, exp2, -17 * 65536, 15 * 65536 - 1, 1, 0);
    sweep_raw(&l, tg_log2, log2, 1, 1 << 21, 1, 0);
    sweep_raw(&l, tg_log2, log2, 1 << 21, INT32_MAX, 1021, 0);
    check_stat(&e, 0.501, 0, 0);
    check_stat(&l, 0.501, 0, 0);
    CHECK(tg_exp2(TG_R(15.0f)) == TG_REAL_MAX, "exp2(15) saturates");
    CHECK(tg_exp2(TG_R(-20.0f)) == 0, "exp2(-20) underflows to 0");
#else
    sweep_uniform(&e, tg_exp2, exp2, -126.0, 127.99, 1000000, 0);
    sweep_bits(&e, tg_exp2, exp2, 1e-30f, 1.0f, 257, 1, 0);
    sweep_bits(&l, tg_log2, log2, from_bits(1), FLT_MAX, 1021, 0, 0);
    sweep_uniform(&l, tg_log2, log2, 0.5, 2.0, 1000000, 0);
    check_stat(&e, 0, 2.5e-7, 0);
    check_stat(&l, 0, 3.5e-7, 0);
    CHECK(tg_exp2(1000.0f) == TG_REAL_MAX, "exp2(1000) saturates");
    CHECK(tg_exp2(-1000.0f) == 0.0f, "exp2(-1000) = 0");
#endif
    CHECK(tg_exp2(0) == TG_ONE, "exp2(0) = 1");
    CHECK(tg_exp2(TG_R(3.0f)) == TG_R(8.0f), "exp2(3) = 8 exactly");
    CHECK(tg_log2(TG_R(8.0f)) == TG_R(3.0f), "log2(8) = 3 exactly");
    CHECK(tg_log2(0) == TG_REAL_MIN, "log2(0) = MIN");
    CHECK(tg_log2(tg_neg(TG_ONE)) == TG_REAL_MIN, "log2(-1) = MIN");
}

TEST(pow_domain)
{
    stat s;
    int i, j;
    stat_init(&s, "tg_pow");
    for (i = 0; i < 1000; i++)
        for (j = 0; j < 400; j++) {
#if TG_FIXED
            tg_real x = (tg_real)(1 + (int64_t)(pow(2.0, 31.0 * i / 999.0)) % INT32_MAX);
            double lim = 14.9;
#else
            tg_real x = (float)pow(2.0, -120.0 + 240.0 * i / 999.0) * (1.0f + 0.01f * (float)(i % 5));
            double lim = 64.0;
#endif
            tg_real y = tg_from_float((float)(-8.0 + 16.0 * j / 399.0));
            double ref = pow(check_exact(x), check_exact(y));
            if (fabs(check_exact(y) * log2(check_exact(x))) >= lim) continue;
            measure(&s, tg_pow(x, y), ref, check_exact(x), check_exact(y), 0);
        }
    check_stat(&s, 0.501, 5e-6, 0);
    CHECK(tg_pow(TG_R(2.0f), TG_R(10.0f)) == TG_R(1024.0f), "2^10 exact");
    CHECK(tg_pow(0, TG_R(2.0f)) == 0, "0^2 = 0");
    CHECK(tg_pow(0, 0) == TG_ONE, "0^0 = 1");
    CHECK(tg_pow(0, tg_neg(TG_ONE)) == TG_REAL_MAX, "0^-1 saturates");
}

/* ---- floor, smoothstep ---- */

TEST(floor_exact)
{
    long bad = 0;
#if TG_FIXED
    int64_t i;
    for (i = -(int64_t)INT32_MAX; i <= INT32_MAX; i += 977) {
        double f = floor(check_exact((tg_real)i));
        double g = check_exact(tg_floor((tg_real)i));
        if (f >= -32767.0 && g != f) bad++;
    }
    CHECK(tg_floor(TG_REAL_MIN) == TG_REAL_MIN, "floor(MIN) saturates");
#else
    int i;
    for (i = 0; i < 1000000; i++) {
        float x = (float)(-3e4 + 6e4 * i / 1000000.0);
        if (tg_floor(x) != (float)floor((double)x)) bad++;
    }
    CHECK(tg_floor(1e30f) == 1e30f, "large floats are integral");
#endif
    CHECK(bad == 0, "%ld floor mismatches", bad);
    CHECK(tg_floor(TG_R(-0.5f)) == tg_neg(TG_ONE), "floor(-0.5) = -1");
    CHECK(tg_floor(TG_R(2.0f)) == TG_R(2.0f), "floor(2) = 2");
}

TEST(smoothstep_values)
{
    int i;
    tg_real prev = 0;
    CHECK(tg_smoothstep(TG_ONE, TG_R(3.0f), 0) == 0, "below a");
    CHECK(tg_smoothstep(TG_ONE, TG_R(3.0f), TG_R(5.0f)) == TG_ONE, "above b");
    CHECK(tg_smoothstep(TG_ONE, TG_R(3.0f), TG_R(2.0f)) == TG_R(0.5f), "midpoint 1/2");
    CHECK(tg_smoothstep(TG_ONE, TG_ONE, TG_R(2.0f)) == TG_ONE, "a == b is a step");
    CHECK(tg_smoothstep(TG_ONE, TG_ONE, 0) == 0, "a == b is a step");
    for (i = 0; i <= 1000; i++) {
        tg_real x = tg_ratio(i, 1000), r = tg_smoothstep(0, TG_ONE, x);
        double t = check_exact(x);
        CHECK_NEAR(check_exact(r), t * t * (3 - 2 * t), 4.0 / 65536);
        CHECK(r >= prev, "monotonic at %d", i);
        prev = r;
    }
}

/* ---- saturation at the range ends ---- */

TEST(saturation)
{
#if TG_FIXED
    CHECK(tg_mul(TG_REAL_MAX, TG_REAL_MAX) == TG_REAL_MAX, "MAX*MAX");
    CHECK(tg_mul(TG_REAL_MAX, TG_REAL_MIN) == TG_REAL_MIN, "MAX*MIN");
    CHECK(tg_mul(TG_R(200.0f), TG_R(200.0f)) == TG_REAL_MAX, "200*200 saturates, not wraps");
    CHECK(tg_mul(TG_R(-200.0f), TG_R(200.0f)) == TG_REAL_MIN, "-200*200");
    CHECK(tg_add(TG_REAL_MAX, TG_ONE) == TG_REAL_MAX, "MAX+1");
    CHECK(tg_add(TG_REAL_MIN, tg_neg(TG_ONE)) == TG_REAL_MIN, "MIN-1");
    CHECK(tg_sub(TG_REAL_MIN, TG_REAL_MAX) == TG_REAL_MIN, "MIN-MAX");
    CHECK(tg_sub(TG_REAL_MAX, TG_REAL_MIN) == TG_REAL_MAX, "MAX-MIN");
    CHECK(tg_div(TG_ONE, 0) == TG_REAL_MAX, "1/0");
    CHECK(tg_div(tg_neg(TG_ONE), 0) == TG_REAL_MIN, "-1/0");
    CHECK(tg_div(0, 0) == 0, "0/0");
    CHECK(tg_div(TG_R(1000.0f), TG_EPS) == TG_REAL_MAX, "1000/eps");
    CHECK(tg_from_int(40000) == TG_REAL_MAX, "from_int(40000)");
    CHECK(tg_neg(TG_REAL_MIN) == TG_REAL_MAX, "-MIN");
    CHECK(tg_ldexp(TG_R(3.0f), 20) == TG_REAL_MAX, "ldexp saturates");
    /* results of the transcendentals stay in range */
    CHECK(tg_tan(TG_R(1.5707f)) > TG_R(1000.0f), "tan near pi/2 large and positive");
    CHECK(tg_pow(TG_R(100.0f), TG_R(100.0f)) == TG_REAL_MAX, "100^100 saturates");
#else
    CHECK(tg_mul(TG_REAL_MAX, TG_REAL_MAX) > 0, "MAX*MAX overflows to +inf, not wraps");
    CHECK(tg_isfinite(tg_pow(100.0f, 100.0f)) && tg_pow(100.0f, 100.0f) == TG_REAL_MAX, "pow saturates");
    CHECK(tg_exp2(200.0f) == TG_REAL_MAX, "exp2 saturates");
    CHECK(tg_isfinite(tg_rsqrt(0.0f)), "rsqrt(0) finite");
    CHECK(tg_sin(INFINITY) == 0.0f && tg_cos(NAN) == TG_ONE, "outside the domain: finite");
    CHECK(tg_atan2(NAN, 1.0f) == 0.0f, "atan2 NaN: 0");
    CHECK(tg_isfinite(tg_tan(1.57079637f)), "tan at float(pi/2) finite");
#endif
    CHECK(tg_isfinite(tg_log2(0)), "log2(0) finite");
    CHECK(tg_isfinite(tg_acos(TG_REAL_MAX)), "acos(MAX) finite");
}

#if TG_FIXED
/* tgi_sat64, under every tg_add, tg_mul and tg_div: one unsigned compare on
 * a 64-bit host, two signed ones on a 32-bit core (tinygi.h); either must
 * be the clamp to [TG_REAL_MIN, TG_REAL_MAX] = [-(2^31 - 1), 2^31 - 1].
 * The edges (-2^31 is below the range: TG_REAL_MIN is symmetric), the
 * int64 extremes and random values of every magnitude. */
static tg_real clamp_by_definition(int64_t v)
{
    return v > TG_REAL_MAX ? TG_REAL_MAX : v < TG_REAL_MIN ? TG_REAL_MIN : (tg_real)v;
}
TEST(sat64_is_the_clamp)
{
    static const int64_t edges[] = { INT64_MIN, INT64_MIN + 1, -((int64_t)1 << 32), -((int64_t)1 << 31) - 1,
                                     -((int64_t)1 << 31), -((int64_t)1 << 31) + 1, -1, 0, 1,
                                     ((int64_t)1 << 31) - 2, ((int64_t)1 << 31) - 1, (int64_t)1 << 31,
                                     ((int64_t)1 << 32) - 2, ((int64_t)1 << 32) - 1, (int64_t)1 << 32, INT64_MAX - 1,
                                     INT64_MAX };
    uint64_t v = 0x9e3779b97f4a7c15ull;
    long bad = 0, i;
    for (i = 0; i < (long)(sizeof edges / sizeof edges[0]); i++)
        if (tgi_sat64(edges[i]) != clamp_by_definition(edges[i]) && bad++ < 5)
            fprintf(stderr, "tgi_sat64(%lld) = %d\n", (long long)edges[i], (int)tgi_sat64(edges[i]));
    for (i = 0; i < 1000000; i++) {
        int64_t x;
        v ^= v << 13; v ^= v >> 7; v ^= v << 17;
        x = (int64_t)v >> (int)((v >> 58) & 63);   /* every magnitude from 2^0 to 2^63 */
        if (tgi_sat64(x) != clamp_by_definition(x) && bad++ < 5)
            fprintf(stderr, "tgi_sat64(%lld) = %d\n", (long long)x, (int)tgi_sat64(x));
    }
    CHECK(bad == 0, "%ld values where tgi_sat64 is not the clamp to [TG_REAL_MIN, TG_REAL_MAX]", bad);
    CHECK(tg_add(TG_REAL_MIN, -1) == TG_REAL_MIN && tg_sub(-TG_ONE, TG_REAL_MAX) == TG_REAL_MIN,
          "a sum of -2^31 saturates to TG_REAL_MIN = -(2^31 - 1)");
}
#endif

/* ---- the decimal parser ---- */

static tg_real parse(const char *s, size_t *used, int *ovf)
{
    tg_real r = TG_ONE;
    *used = tg_parse_real(s, strlen(s), &r, ovf);
    return r;
}

#define ALL ((size_t)-1)
/* expected: consumed count and value (checked bit-exact) */
static void parse_case(const char *s, size_t want_used, tg_real want, int want_ovf)
{
    size_t used;
    int ovf = -1;
    tg_real r = parse(s, &used, &ovf);
    if (want_used == ALL) want_used = strlen(s);
    CHECK(used == want_used, "\"%s\": used %zu, want %zu", s, used, want_used);
    CHECK(r == want, "\"%s\": got %.9g (raw %.9g), want %.9g", s, check_exact(r), (double)r, check_exact(want));
    CHECK(ovf == want_ovf, "\"%s\": overflow %d want %d", s, ovf, want_ovf);
}

TEST(parse_grammar)
{
    int ovf;
    char buf[400];
    parse_case("1", 1, TG_ONE, 0);
    parse_case("-0.5", 4, TG_R(-0.5f), 0);
    parse_case("+2.5", 4, TG_R(2.5f), 0);
    parse_case(".5", 2, TG_R(0.5f), 0);
    parse_case("5.", 2, TG_R(5.0f), 0);
    parse_case("-.25e1", 6, TG_R(-2.5f), 0);
    parse_case("2.5E+2", 6, TG_R(250.0f), 0);
    parse_case("1e", 1, TG_ONE, 0);
    parse_case("1e+", 1, TG_ONE, 0);
#if TG_FIXED
    parse_case("1e5x", 3, TG_REAL_MAX, 1);
    parse_case("1e4x", 3, TG_R(10000.0f), 0);
#else
    parse_case("1e5x", 3, 100000.0f, 0);
#endif
    /* garbage */
    parse_case("inf", 0, 0, 0);
    parse_case("nan", 0, 0, 0);
    parse_case("-", 0, 0, 0);
    parse_case(".", 0, 0, 0);
    parse_case("+.", 0, 0, 0);
    parse_case("", 0, 0, 0);
    parse_case("abc", 0, 0, 0);
    parse_case("--1", 0, 0, 0);
    parse_case(" 1", 0, 0, 0);
    parse_case("0x10", 1, 0, 0); /* only "0": the caller sees "x10" left */
    parse_case("1.5.3", 3, TG_R(1.5f), 0);
    /* the length is respected */
    CHECK(tg_parse_real("123", 2, &(tg_real){0}, &ovf) == 2, "len 2 of \"123\"");
    {
        tg_real r;
        tg_parse_real("123", 2, &r, &ovf);
        CHECK(r == TG_R(12.0f), "\"12\" of \"123\"");
    }
    /* long strings: 200 leading zeros, 200 trailing digits */
    memset(buf, '0', 200);
    strcpy(buf + 200, "1.5");
    parse_case(buf, 203, TG_R(1.5f), 0);
    strcpy(buf, "0.");
    memset(buf + 2, '0', 300);
    strcpy(buf + 302, "1e301");
    parse_case(buf, strlen(buf), TG_ONE, 0);
    /* huge exponents */
    parse_case("1e999999999999999", 17, TG_REAL_MAX, 1);
    parse_case("1e-999999999999999", 18, 0, 0);
    parse_case("0e999999999", 11, 0, 0);
    parse_case("-1e99", 5, TG_REAL_MIN, 1);
}

/* `tie` (a decimal exactly halfway between two numbers) followed by 150
 * zeros then a 1 parses to `above`; with the 1 a 0, to `at` (the sticky
 * digit decides). */
static void parse_sticky(const char *tie, tg_real above, tg_real at)
{
    char buf[400];
    size_t n = strlen(tie);
    strcpy(buf, tie);
    memset(buf + n, '0', 150);
    strcpy(buf + n + 150, "1");
    parse_case(buf, n + 151, above, 0);
    buf[n + 150] = '0';
    parse_case(buf, n + 151, at, 0);
}

/* ties, sticky digits beyond the kept ones, range ends */
TEST(parse_rounding)
{
#if TG_FIXED
    parse_case("0.00000762939453125", 19, 0, 0);          /* 2^-17: tie, to even (0) */
    parse_case("0.00002288818359375", 19, 2, 0);          /* 3 2^-17: tie, to even (2) */
    parse_case("0.000007629394531250000000000000000000000000001", ALL, 1, 0); /* just above */
    parse_case("0.00000762939453124999999999999999", ALL, 0, 0);
    parse_case("-0.00002288818359375", 20, -2, 0);
    parse_case("0.0000152587890625", 18, 1, 0);          /* 2^-16 exactly */
    parse_case("32767.99998474121", 17, TG_REAL_MAX, 0);  /* rounds to MAX */
    parse_case("32767.9999923706055", 19, TG_REAL_MAX, 1); /* rounds past MAX */
    parse_case("32768", 5, TG_REAL_MAX, 1);
    parse_case("-32768", 6, TG_REAL_MIN, 1);
    parse_case("1e-6", 4, 0, 0);
    parse_case("0.1", 3, 6554, 0);                        /* 6553.6 -> 6554 */
    parse_case("3.14159265358979", 16, 205887, 0);        /* 205887.416 */
    parse_sticky("0.00000762939453125", 1, 0);
#else
    parse_case("16777217", 8, 16777216.0f, 0);            /* tie, to even */
    parse_case("16777219", 8, 16777220.0f, 0);            /* tie, to even */
    parse_case("16777217.00000000000000000000000000000000001", 44, 16777218.0f, 0);
    parse_case("3.4028235e38", 12, FLT_MAX, 0);
    parse_case("3.40282357e38", 13, TG_REAL_MAX, 1);      /* past FLT_MAX + ulp/2 */
    parse_case("1e39", 4, TG_REAL_MAX, 1);
    parse_case("1e-50", 5, 0.0f, 0);
    parse_case("1.4e-45", 7, from_bits(1), 0);            /* smallest subnormal */
    parse_case("7.0064923216240853e-46", 22, 0.0f, 0);    /* < half of it */
    parse_case("7.00649232162408535461864791644958065640130970938257885878534141944895541342930300743319094181060791015625e-46", ALL, 0.0f, 0); /* exactly half: to even */
    parse_case("7.0064923216240854e-46", 22, from_bits(1), 0);
    parse_case("1.1754942e-38", 13, from_bits(0x7fffff), 0);
    parse_case("0.1", 3, 0.1f, 0);
    parse_sticky("16777217.", 16777218.0f, 16777216.0f);
#endif
}

/* random decimal strings against the C library (strtof is correctly
 * rounded in glibc; fixed point against strtod away from ties) */
TEST(parse_random)
{
    unsigned seed = 12345;
    long i, bad = 0, n = 0;
    char s[128];
    for (i = 0; i < 300000; i++) {
        int k = 0, nd, j, e, dot;
        size_t used;
        int ovf;
        tg_real r;
        seed = seed * 1103515245u + 12345u;
        if (seed & 0x100) s[k++] = '-';
        nd = 1 + (int)((seed >> 16) % 40);
        dot = (int)((seed >> 8) % (unsigned)(nd + 2)) - 1; /* -1: ".5", nd: no point */
        if (dot == -1) s[k++] = '.';
        for (j = 0; j < nd; j++) {
            seed = seed * 1103515245u + 12345u;
            s[k++] = (char)('0' + (seed >> 16) % 10);
            if (j == dot) s[k++] = '.';
        }
        seed = seed * 1103515245u + 12345u;
#if TG_FIXED
        e = (int)((seed >> 16) % 30) - 20;
#else
        e = (int)((seed >> 16) % 100) - 60;
#endif
        k += sprintf(s + k, "e%d", e);
        used = tg_parse_real(s, (size_t)k, &r, &ovf);
        n++;
        if (used != (size_t)k) { bad++; continue; }
#if TG_FIXED
        {
            double v = strtod(s, NULL) * 65536.0, fl = floor(v);
            if (fabs(v) >= 2147483647.0) { if (!ovf) bad++; continue; }
            if (fabs(v - fl - 0.5) < 1e-6) continue; /* too close to a tie for the reference */
            if ((double)r != (fabs(v - fl) < 0.5 ? fl : fl + 1)) {
                if (bad++ < 5) fprintf(stderr, "parse %s -> raw %d, ref %.3f\n", s, r, v);
            }
        }
#else
        {
            float ref = strtof(s, NULL);
            if (isinf(ref)) { if (!ovf || r != (ref > 0 ? TG_REAL_MAX : TG_REAL_MIN)) bad++; continue; }
            if (memcmp(&ref, &r, 4) != 0) {
                if (bad++ < 5) fprintf(stderr, "parse %s -> %.9g, strtof %.9g\n", s, (double)r, (double)ref);
            }
        }
#endif
    }
    printf("measured tg_parse_real %s: %ld random strings, %ld mismatches\n", TG_NUMBER_NAME, n, bad);
    CHECK(bad == 0, "%ld of %ld random strings parsed wrong", bad, n);
}

/* The integer helpers of core/real.h: bit length, rounded isqrt, and the
 * rasterizer's per-pixel reciprocal square root (bounds stated there). */
TEST(integer_helpers)
{
    int k, bad = 0;
    double worst = 0;
    CHECK(tgi_bit_length64(0) == 0 && tgi_bit_length64(1) == 1 && tgi_bit_length64(UINT64_MAX) == 64, "ends");
    for (k = 1; k < 64; k++) {
        uint64_t p = (uint64_t)1 << k;
        if (tgi_bit_length64(p) != k + 1 || tgi_bit_length64(p - 1) != k || tgi_bit_length64(p | 1) != k + 1) bad++;
    }
    CHECK(bad == 0, "%d wrong bit lengths", bad);
    for (k = 0; k < 32; k++) {   /* tgi_clz32_nz: 32 - the bit length, at both ends of each length */
        uint32_t p = (uint32_t)1 << k, q = p | (p - 1);
        if (tgi_clz32_nz(p) != 31 - k || tgi_clz32_nz(q) != 31 - k || tgi_clz32_nz(p | 1) != 31 - k) bad++;
    }
    CHECK(bad == 0, "%d wrong leading-zero counts", bad);
    CHECK(tgi_isqrt_round64(0) == 0 && tgi_isqrt_round64(2) == 1 && tgi_isqrt_round64(3) == 2 &&
          tgi_isqrt_round64(12) == 3 && tgi_isqrt_round64(13) == 4, "rounded isqrt");
#if TG_FIXED
    {   /* 1/sqrt(X) in Q30 over X in [1, 4), every 1024th input */
        uint64_t x;
        for (x = (uint64_t)1 << 30; x < (uint64_t)1 << 32; x += 1024) {
            double X = (double)x / 1073741824.0, ref = 1.0 / sqrt(X);
            double e = fabs((double)tgi_rsqrt_q30_fast(x) / 1073741824.0 - ref) / ref;
            if (e > worst) worst = e;
        }
        printf("measured tgi_rsqrt_q30_fast: rel. error %.3g over [1, 4)\n", worst);
        CHECK(worst < 3.2e-6, "rel. error %.3g", worst);
    }
#else
    {   /* 1/sqrt(x) over the normal floats, 64 points per octave */
        double x;
        for (x = 1.2e-38; x < 3e38; x *= 1.0108892860517005) {
            double ref = 1.0 / sqrt((double)(float)x);
            double e = fabs((double)tgi_rsqrt_fast((float)x) - ref) / ref;
            if (e > worst) worst = e;
        }
        printf("measured tgi_rsqrt_fast: rel. error %.3g over the normal floats\n", worst);
        CHECK(worst < 5e-6, "rel. error %.3g", worst);
    }
#endif
}

/* tgi_text_put_real (error messages, the plan's explanation) as the float
 * code formats tg_to_float(r): "-", the integer part, up to three decimals
 * rounded (src/core/text.c).  Q16.16 formats in integers (no soft float in
 * a small program): every r with |r| < 2^21, every r within 4096 of each
 * power of two from 2^21 up (where the conversion to float starts to
 * round, ties included), and 2^20 pseudo-random ones. */
static void ref_put_real(char *out, tg_real r)
{
    float v = tg_to_float(r);
    uint32_t whole, frac;
    int e = 0;
    if (v != v) { strcpy(out, "nan"); return; }
    if (v < 0) { *out++ = '-'; v = -v; }
    if (v > 3.402823466e+38f) { strcpy(out, "inf"); return; }
    while (v >= 1e9f) { v /= 10.0f; e++; }
    if (e > 0) while (v >= 10.0f) { v /= 10.0f; e++; }
    whole = (uint32_t)v;
    frac = (uint32_t)((v - (float)whole) * 1000.0f + 0.5f);
    if (frac >= 1000u) { whole++; frac -= 1000u; }
    out += sprintf(out, "%lu", (unsigned long)whole);
    if (frac) {
        out += sprintf(out, ".%03lu", (unsigned long)frac);
        while (out[-1] == '0') *--out = '\0';
    }
    if (e > 0) sprintf(out, "e+%d", e);
}

static int put_real_differs(tg_real r)
{
    char got[64], want[64];
    tgi_text t;
    tgi_text_init(&t, got, sizeof got);
    tgi_text_put_real(&t, r);
    ref_put_real(want, r);
    if (strcmp(got, want) == 0) return 0;
    CHECK(0, "tgi_text_put_real(%.9g) gave '%s', the float code '%s'", (double)tg_to_float(r), got, want);
    return 1;
}

TEST(text_put_real_as_float)
{
    long n = 0;
    int k, bad = 0;
    uint32_t lcg = 12345u;
#if TG_FIXED
    int32_t i;
    for (i = -(1 << 21); i <= (1 << 21) && !bad; i++, n++) bad = put_real_differs(i);
    for (k = 21; k <= 31 && !bad; k++) {
        int64_t d;
        for (d = -4096; d <= 4096 && !bad; d++) {
            int64_t v = ((int64_t)1 << k) + d;
            if (v > INT32_MAX) break;
            bad = put_real_differs((tg_real)v) || put_real_differs((tg_real)-v);
            n += 2;
        }
    }
    bad = bad || put_real_differs(INT32_MIN) || put_real_differs(INT32_MAX);
    for (k = 0; k < (1 << 20) && !bad; k++, n++) {
        lcg = lcg * 1664525u + 1013904223u;
        bad = put_real_differs((tg_real)(int32_t)lcg);
    }
#else
    static const float edge[] = { 0.0f, -0.0f, 0.0005f, 0.9995f, 1e9f, 123456789e3f, 3.4e38f, 1e-30f };
    for (k = 0; k < (int)(sizeof edge / sizeof edge[0]) && !bad; k++, n++) bad = put_real_differs(edge[k]);
    for (k = 0; k < (1 << 20) && !bad; k++, n++) {
        uint32_t b;
        float f;
        lcg = lcg * 1664525u + 1013904223u;
        b = lcg & 0xff7fffffu;   /* finite */
        memcpy(&f, &b, sizeof f);
        bad = put_real_differs(f);
    }
#endif
    printf("measured tgi_text_put_real: %ld values as the float code formats them\n", n);
}

int main(void)
{
    RUN(isqrt64_exact);
#if TG_FIXED
    RUN(isqrt64_upper_matches);
#endif
    RUN(unit_or_matches_normalize_or);
#if TG_FIXED
    RUN(rounding_shift_ties_toward_plus_infinity);
    RUN(outline_div_and_shift_match_inline);
    RUN(div_rounds_alike_for_every_sign);
    RUN(div_pos_matches_div);
    RUN(div_nonneg32_matches);
#endif
    RUN(text_put_real_as_float);
    RUN(integer_helpers);
    RUN(sqrt_whole_domain);
#if TG_FIXED
    RUN(sqrt_rounding_boundaries);
#endif
    RUN(rsqrt_whole_domain);
    RUN(sin_cos_whole_domain);
    RUN(tan_domain);
    RUN(asin_acos_whole_domain);
    RUN(atan2_whole_domain);
    RUN(exp2_log2_whole_domain);
    RUN(pow_domain);
    RUN(floor_exact);
    RUN(smoothstep_values);
    RUN(saturation);
#if TG_FIXED
    RUN(sat64_is_the_clamp);
#endif
    RUN(parse_grammar);
    RUN(parse_rounding);
    RUN(parse_random);
    return check_summary();
}
