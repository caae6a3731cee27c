/* SPDX-License-Identifier: MIT */
/*
 * real.h - tinygi's one number type, chosen once per build (like luaconf.h).
 *
 *   TG_FIXED undefined or 0 : tg_real is IEEE-754 float.
 *   TG_FIXED=1              : tg_real is Q16.16 fixed point in int32_t.
 *
 * Every kernel is written once against the scalar API below.  The rules:
 *  - arithmetic between tgi_reals goes through tg_add/tg_sub/tg_mul/tg_div
 *    (plain + and - are allowed in float-only code paths: there are none);
 *  - constants are written TG_R(0.5f) - a compile-time conversion;
 *  - fixed point multiplies in 64 bits and SATURATES to [-TG_REAL_MAX,
 *    TG_REAL_MAX]: it never wraps (a wrapped radiance is a black speck).
 *    -INT32_MAX, not INT32_MIN, is the floor so that negation is safe.
 *  - the transcendentals (tg_sqrt, tg_sin, ...) are the core's own, in
 *    real.c, each with a worst-case error documented there and measured
 *    against libm by tests/test_real.c.
 */
#ifndef TG_REAL_H
#define TG_REAL_H

#include <stdint.h>
#include <stddef.h>
#include <string.h>

#ifndef TG_FIXED
#define TG_FIXED 0
#endif

#if TG_FIXED

typedef int32_t tg_real;
#define TG_FRAC_BITS 16
#define TG_ONE ((tg_real)65536)
#define TG_REAL_MAX ((tg_real)INT32_MAX)
#define TG_REAL_MIN (-TG_REAL_MAX)
#define TG_EPS ((tg_real)1) /* one ulp, 2^-16 */
/* Compile-time conversion of a float constant (rounds to nearest). */
#define TG_R(x) ((tg_real)((x) >= 0 ? (x) * 65536.0f + 0.5f : (x) * 65536.0f - 0.5f))
#define TG_NUMBER_NAME "fixed"

static inline tg_real tgi_sat64(int64_t v)
{
    if (v > (int64_t)TG_REAL_MAX) return TG_REAL_MAX;
    if (v < (int64_t)TG_REAL_MIN) return TG_REAL_MIN;
    return (tg_real)v;
}
static inline tg_real tg_add(tg_real a, tg_real b) { return tgi_sat64((int64_t)a + b); }
static inline tg_real tg_sub(tg_real a, tg_real b) { return tgi_sat64((int64_t)a - b); }
static inline tg_real tg_neg(tg_real a) { return -a; }
/* Round-half-away-from-zero shift; avoids right-shifting negative values. */
static inline int64_t tgi_shr_round(int64_t p, int s)
{
    int64_t half = (int64_t)1 << (s - 1);
    return p >= 0 ? (p + half) >> s : -((-p + half) >> s);
}
static inline tg_real tg_mul(tg_real a, tg_real b)
{
    return tgi_sat64(tgi_shr_round((int64_t)a * b, TG_FRAC_BITS));
}
/* Division saturates; x/0 gives +-TG_REAL_MAX by the sign of x, 0/0 gives 0. */
static inline tg_real tg_div(tg_real a, tg_real b)
{
    int64_t n;
    if (b == 0) return a > 0 ? TG_REAL_MAX : a < 0 ? TG_REAL_MIN : 0;
    n = (int64_t)a * 65536;
    if ((n >= 0) == (b > 0)) n += (b > 0 ? b : -(int64_t)b) / 2;
    else n -= (b > 0 ? b : -(int64_t)b) / 2;
    return tgi_sat64(n / b);
}
static inline tg_real tg_from_int(int32_t i) { return tgi_sat64((int64_t)i * 65536); }
/* Floor to integer. */
static inline int32_t tg_to_int(tg_real a) { return (int32_t)(a >= 0 ? a >> 16 : -((-(int64_t)a + 65535) >> 16)); }
/* Round to nearest integer. */
static inline int32_t tg_round_int(tg_real a) { return tg_to_int(a + (a < TG_REAL_MAX - 32768 ? 32768 : 0)); }
/* n/d as a tg_real, exactly rounded; d > 0. */
static inline tg_real tg_ratio(int32_t n, int32_t d) { return tgi_sat64(((int64_t)n * 65536 + (n >= 0 ? d / 2 : -(d / 2))) / d); }
/* Host-side conversions (used by platform code and tests, never by kernels). */
static inline float tg_to_float(tg_real a) { return (float)a * (1.0f / 65536.0f); }
static inline tg_real tg_from_float(float f)
{
    float s = f * 65536.0f;
    if (!(s == s)) return 0;
    if (s >= 2147483520.0f) return TG_REAL_MAX;
    if (s <= -2147483520.0f) return TG_REAL_MIN;
    return (tg_real)(s >= 0 ? s + 0.5f : s - 0.5f);
}
/* Multiply by a power of two (shift), saturating. */
static inline tg_real tg_ldexp(tg_real a, int e)
{
    if (e >= 0) return tgi_sat64((int64_t)a * ((int64_t)1 << (e > 31 ? 31 : e)));
    return (tg_real)tgi_shr_round(a, -e > 31 ? 31 : -e);
}
static inline int tg_isfinite(tg_real a) { (void)a; return 1; }

#else /* float */

typedef float tg_real;
#define TG_ONE 1.0f
#define TG_REAL_MAX 3.402823466e+38f
#define TG_REAL_MIN (-TG_REAL_MAX)
#define TG_EPS 1.1920929e-07f
#define TG_R(x) ((tg_real)(x))
#define TG_NUMBER_NAME "float"

static inline tg_real tg_add(tg_real a, tg_real b) { return a + b; }
static inline tg_real tg_sub(tg_real a, tg_real b) { return a - b; }
static inline tg_real tg_neg(tg_real a) { return -a; }
static inline tg_real tg_mul(tg_real a, tg_real b) { return a * b; }
static inline tg_real tg_div(tg_real a, tg_real b) { return a / b; }
static inline tg_real tg_from_int(int32_t i) { return (tg_real)i; }
/* Floor to integer (saturates at the int32 range; NaN gives 0). */
static inline int32_t tg_to_int(tg_real a)
{
    int32_t i;
    if (!(a == a)) return 0;
    if (a >= 2147483520.0f) return INT32_MAX;
    if (a <= -2147483520.0f) return -INT32_MAX;
    i = (int32_t)a;
    return (tg_real)i > a ? i - 1 : i;
}
static inline int32_t tg_round_int(tg_real a) { return tg_to_int(a + 0.5f); }
static inline tg_real tg_ratio(int32_t n, int32_t d) { return (tg_real)n / (tg_real)d; }
static inline float tg_to_float(tg_real a) { return a; }
static inline tg_real tg_from_float(float f) { return f; }
static inline tg_real tg_ldexp(tg_real a, int e)
{
    while (e > 0) { a *= 2.0f; e--; }
    while (e < 0) { a *= 0.5f; e++; }
    return a;
}
static inline int tg_isfinite(tg_real a) { return a == a && a <= TG_REAL_MAX && a >= TG_REAL_MIN; }

/* rsqrt and sqrt are inline in the float build: every normalisation in the
 * hot loops calls them (error bounds in real.c's table). */
static inline float tgi_f_from_bits(uint32_t b) { float f; memcpy(&f, &b, sizeof f); return f; }
static inline uint32_t tgi_f_bits(float f) { uint32_t b; memcpy(&b, &f, sizeof b); return b; }

/* Bit-trick seed (within 3.5%) and three Newton steps (quadratic); x <= 0 gives TG_REAL_MAX. */
static inline tg_real tg_rsqrt(tg_real x)
{
    float y, hx, scale = 1.0f;
    if (!(x > 0.0f)) return TG_REAL_MAX;
    if (x > TG_REAL_MAX) return 0.0f;
    if (x < 1.17549435e-38f) { x *= 18446744073709551616.0f; scale = 4294967296.0f; }
    y = tgi_f_from_bits(0x5f3759dfu - (tgi_f_bits(x) >> 1));
    hx = 0.5f * x;
    y = y * (1.5f - hx * y * y);
    y = y * (1.5f - hx * y * y);
    y = y * (1.5f - hx * y * y);
    return y * scale;
}

/* sqrt = x * rsqrt(x), plus one Newton correction on the residual; x <= 0 gives 0. */
static inline tg_real tg_sqrt(tg_real x)
{
    float r, s;
    if (!(x > 0.0f)) return 0.0f;
    if (x > TG_REAL_MAX) return x;
    r = tg_rsqrt(x);
    s = x * r;
    return s + 0.5f * r * (x - s * s);
}

#endif

/* ---- shared helpers, identical for both types ---- */
static inline tg_real tg_abs(tg_real a) { return a < 0 ? tg_neg(a) : a; }
static inline tg_real tg_min(tg_real a, tg_real b) { return a < b ? a : b; }
static inline tg_real tg_max(tg_real a, tg_real b) { return a > b ? a : b; }
static inline tg_real tg_clamp(tg_real a, tg_real lo, tg_real hi) { return a < lo ? lo : a > hi ? hi : a; }
static inline tg_real tg_saturate(tg_real a) { return tg_clamp(a, 0, TG_ONE); }
/* a + (b - a) * t */
static inline tg_real tg_lerp(tg_real a, tg_real b, tg_real t) { return tg_add(a, tg_mul(tg_sub(b, a), t)); }
static inline tg_real tg_sqr(tg_real a) { return tg_mul(a, a); }

/* ---- the core's own transcendentals (real.c; error bounds documented there) ---- */
#if TG_FIXED
tg_real tg_sqrt(tg_real x);           /* x <= 0 gives 0 */
tg_real tg_rsqrt(tg_real x);          /* x <= 0 gives TG_REAL_MAX */
#endif
tg_real tg_sin(tg_real x);            /* radians, any x */
tg_real tg_cos(tg_real x);
tg_real tg_acos(tg_real x);           /* x clamped to [-1, 1]; result in [0, pi] */
tg_real tg_asin(tg_real x);           /* x clamped to [-1, 1] */
tg_real tg_atan2(tg_real y, tg_real x); /* result in [-pi, pi]; (0,0) gives 0 */
tg_real tg_tan(tg_real x);            /* |x| < pi/2 */
tg_real tg_exp2(tg_real x);           /* saturates */
tg_real tg_log2(tg_real x);           /* x <= 0 gives TG_REAL_MIN */
tg_real tg_pow(tg_real x, tg_real y); /* x >= 0 */
tg_real tg_floor(tg_real x);
tg_real tg_smoothstep(tg_real a, tg_real b, tg_real x);
/* Number of significant bits of v (0 for 0). */
int tgi_bit_length64(uint64_t v);
/* sqrt of a 64-bit integer, floor; used by fixed-point vector lengths. */
uint32_t tgi_isqrt64(uint64_t v);
/* Parse a decimal number ("1", "-0.5", "2.5e-3") into a tg_real, rounding to
 * nearest.  Returns the count of characters used, 0 if none form a number.
 * *overflow is set when the value is outside the tg_real range (the result
 * then saturates). */
size_t tg_parse_real(const char *s, size_t len, tg_real *out, int *overflow);

#define TG_PI TG_R(3.14159265358979f)
#define TG_TWO_PI TG_R(6.28318530717959f)
#define TG_HALF_PI TG_R(1.57079632679490f)
#define TG_INV_PI TG_R(0.318309886183791f)
#define TG_DEG2RAD TG_R(0.0174532925199433f)

#endif
