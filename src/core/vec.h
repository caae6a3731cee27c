/* SPDX-License-Identifier: MIT */
/*
 * vec.h - 3-vectors, quaternions and 4x4 matrices over tg_real.
 *
 * Matrices are row-major, m[row * 4 + col], and act on column vectors:
 * p' = M p.  Dot products in fixed point accumulate in 64 bits before the
 * single saturating shift, so a dot of unit vectors keeps full precision.
 */
#ifndef TG_VEC_H
#define TG_VEC_H

#include "real.h"

typedef struct tg_vec3 { tg_real x, y, z; } tg_vec3;
typedef struct tgi_vec4 { tg_real x, y, z, w; } tgi_vec4;
typedef struct tgi_quat { tg_real x, y, z, w; } tgi_quat;
typedef struct tgi_mat4 { tg_real m[16]; } tgi_mat4;

static inline tg_vec3 tg_v3(tg_real x, tg_real y, tg_real z) { tg_vec3 v; v.x = x; v.y = y; v.z = z; return v; }
static inline tg_vec3 tgi_v3_add(tg_vec3 a, tg_vec3 b) { return tg_v3(tg_add(a.x, b.x), tg_add(a.y, b.y), tg_add(a.z, b.z)); }
static inline tg_vec3 tgi_v3_sub(tg_vec3 a, tg_vec3 b) { return tg_v3(tg_sub(a.x, b.x), tg_sub(a.y, b.y), tg_sub(a.z, b.z)); }
static inline tg_vec3 tgi_v3_scale(tg_vec3 a, tg_real s) { return tg_v3(tg_mul(a.x, s), tg_mul(a.y, s), tg_mul(a.z, s)); }
static inline tg_vec3 tgi_v3_mul(tg_vec3 a, tg_vec3 b) { return tg_v3(tg_mul(a.x, b.x), tg_mul(a.y, b.y), tg_mul(a.z, b.z)); }
static inline tg_vec3 tgi_v3_neg(tg_vec3 a) { return tg_v3(tg_neg(a.x), tg_neg(a.y), tg_neg(a.z)); }
/* The largest |component|. */
static inline tg_real tgi_v3_max_abs(tg_vec3 v) { return tg_max(tg_abs(v.x), tg_max(tg_abs(v.y), tg_abs(v.z))); }
static inline tg_vec3 tgi_v3_lerp(tg_vec3 a, tg_vec3 b, tg_real t) { return tg_v3(tg_lerp(a.x, b.x, t), tg_lerp(a.y, b.y, t), tg_lerp(a.z, b.z, t)); }

#if TG_FIXED
/* The three products summed in 64 bits and rounded once.  A product of two
 * values in [-TG_REAL_MAX, TG_REAL_MAX] is under 2^62, so the first two sum
 * to s without overflow (|s| < 2^63 - 2^33), but the third, r, can take the
 * sum past 2^63 (saturated weights against coefficients at the range's
 * ends).  That needs |s| > 2^62 and r of s's sign, when the whole sum is
 * past 2^62 as s is, and either rounds to far past tg_real's range: s
 * alone is then rounded (and saturates).  Wherever the sum fits, the same
 * bits as the plain sum (tests/test_vec.c dot_product_at_the_range_ends). */
static inline tg_real tgi_v3_dot(tg_vec3 a, tg_vec3 b)
{
    const int64_t big = (int64_t)1 << 62;
    int64_t s = (int64_t)a.x * b.x + (int64_t)a.y * b.y, r = (int64_t)a.z * b.z;
    if ((s > big || s < -big) && (s < 0) == (r < 0)) r = 0;   /* s alone is past 2^62 too */
    return tgi_sat64(tgi_shr_round(s + r, TG_FRAC_BITS));
}
#else
static inline tg_real tgi_v3_dot(tg_vec3 a, tg_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
#endif

/* a . b where the sum of the products cannot pass 2^62 (each caller says
 * why: a unit vector against one within 2^23 or so): in Q16.16 the sum
 * rounded once and saturated (tgi_wide_dot, tgi_wide_real), tgi_v3_dot's
 * result without its test; float, and a build for size (one copy),
 * tgi_v3_dot itself. */
#if TGI_Q16_WIDE
static inline tg_real tgi_v3_dot_bounded(tg_vec3 a, tg_vec3 b)
{
    return tgi_wide_real(tgi_wide_dot(a.x, a.y, a.z, b.x, b.y, b.z));
}
#else
#define tgi_v3_dot_bounded tgi_v3_dot
#endif

/* tgi_v3_sub(a, b) with one range test (Q16.16 on 64-bit cores, not
 * compiling for size; direct light's vector to a point light, the
 * perspective shadow lookup's): the differences in 64 bits, each within
 * [TG_REAL_MIN, TG_REAL_MAX] exactly when it plus 2^31 lies in [0, 2^32)
 * (a negative sum has its high bits set as uint64_t), and there tg_sub's
 * value; else tgi_v3_sub's saturation.  Elsewhere tgi_v3_sub itself. */
#if TGI_Q16_WIDE
static inline tg_vec3 tgi_v3_sub_wide(tg_vec3 a, tg_vec3 b)
{
    const int64_t x = (int64_t)a.x - b.x, y = (int64_t)a.y - b.y, z = (int64_t)a.z - b.z;
    const uint64_t h = (uint64_t)1 << 31;
    if ((((uint64_t)x + h) | ((uint64_t)y + h) | ((uint64_t)z + h)) >> 32) return tgi_v3_sub(a, b);
    return tg_v3((tg_real)x, (tg_real)y, (tg_real)z);
}
#else
#define tgi_v3_sub_wide tgi_v3_sub
#endif

static inline tg_vec3 tgi_v3_cross(tg_vec3 a, tg_vec3 b)
{
    return tg_v3(tg_sub(tg_mul(a.y, b.z), tg_mul(a.z, b.y)),
                 tg_sub(tg_mul(a.z, b.x), tg_mul(a.x, b.z)),
                 tg_sub(tg_mul(a.x, b.y), tg_mul(a.y, b.x)));
}

/* vec.c */
tg_real tgi_v3_length(tg_vec3 a);           /* exact in 64 bits for fixed point */
tg_vec3 tgi_v3_normalize(tg_vec3 a);        /* zero vector gives (0,0,0) */
/* Normalize; a zero (or tiny) vector gives `fallback`. */
tg_vec3 tgi_v3_normalize_or(tg_vec3 a, tg_vec3 fallback);

tgi_mat4 tgi_m4_identity(void);
tgi_mat4 tgi_m4_mul(const tgi_mat4 *a, const tgi_mat4 *b);
tgi_vec4 tgi_m4_apply(const tgi_mat4 *m, tgi_vec4 v);
tg_vec3 tgi_m4_point(const tgi_mat4 *m, tg_vec3 p);   /* w = 1, no divide */
tg_vec3 tgi_m4_dir(const tgi_mat4 *m, tg_vec3 d);     /* w = 0 */
tgi_mat4 tgi_m4_translate(tg_vec3 t);
tgi_mat4 tgi_m4_scale(tg_real s);
tgi_mat4 tgi_m4_rotate(tg_vec3 axis, tg_real angle_rad); /* Rodrigues; axis need not be unit */

tgi_quat tgi_q_axis_angle(tg_vec3 axis, tg_real angle_rad);
tgi_quat tgi_q_slerp(tgi_quat a, tgi_quat b, tg_real t); /* shortest arc, exact at t = 0 and 1 */
tgi_mat4 tgi_q_to_m4(tgi_quat q);

/* Unit vector, exact for axis-aligned ones; zero when too short. */
tg_vec3 tgi_unit(tg_vec3 v);
/* Degrees to radians, precise in Q16.16 too. */
tg_real tgi_deg_to_rad(tg_real deg);
/* Unit face normal of triangle (a, b, c), counter-clockwise front, robust in
 * fixed point (edges scaled to [-1, 1] first); returns 0 if degenerate. */
int tgi_face_normal(tg_vec3 a, tg_vec3 b, tg_vec3 c, tg_vec3 *n);

#endif
