/* SPDX-License-Identifier: MIT */
/*
 * vec.c - vector lengths and normalization, 4x4 matrices, Rodrigues
 * rotation and quaternions over tg_real (declarations and conventions in
 * vec.h: row-major matrices acting on column vectors).
 *
 * Fixed point: lengths and normalization work on the exact 64-bit sum of
 * squares and the integer sqrt (tgi_isqrt64), after shifting the vector so
 * its largest component has 30 significant bits - a huge vector does not
 * overflow, a tiny one (a few ulps) still gets full precision.  Matrix rows
 * accumulate their four products in 64 bits before one rounding.
 * Float: the vector is scaled by a power of two (exact) before squaring, so
 * nothing overflows or underflows.
 * At the end: exact axis-aligned units, robust face normals and degrees to
 * radians, which the scene parser and the OBJ loader build geometry with.
 */
#include <string.h>
#include "vec.h"

#define VEC_MAX_N 4

/* normalize_n is inlined into its callers, each of which passes n as a
 * constant, so its loops unroll (out of line a 3-vector's normalisation
 * cost about 80 instructions in float, and a pixel's bent normal comes
 * through tgi_v3_normalize_or two or three times: the kernel, the filter,
 * temporal accumulation); one copy when compiling for size. */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
#define VEC_NORMALIZE_INLINE inline __attribute__((always_inline))
#else
#define VEC_NORMALIZE_INLINE
#endif

#if TG_FIXED

/* Normalize v[0..n) in place; returns 0 (v untouched) for the zero vector. */
static VEC_NORMALIZE_INLINE int normalize_n(tg_real *v, int n)
{
    int64_t w[VEC_MAX_N], m = 0, inv;
    uint64_t sum = 0, len2;
    int i, s;
    for (i = 0; i < n; i++) {
        int64_t a = v[i] < 0 ? -(int64_t)v[i] : v[i];
        if (a > m) m = a;
    }
    if (m == 0) return 0;
    s = 30 - tgi_bit_length64((uint64_t)m); /* largest |w| in [2^29, 2^30) */
    for (i = 0; i < n; i++) {
        w[i] = s >= 0 ? (int64_t)v[i] * ((int64_t)1 << s) : tgi_shr_round(v[i], -s);
        sum += (uint64_t)(w[i] * w[i]);
    }
    len2 = tgi_isqrt_round64(sum << 2); /* 2 |w|, in [2^30, 2^32] */
    inv = (int64_t)((((uint64_t)1 << 62) + len2 / 2) / len2); /* 2^62 / (2 |w|), one division */
    for (i = 0; i < n; i++) v[i] = tgi_sat64(tgi_shr_round(w[i] * inv, 45)); /* w 2^16 / |w| */
    return 1;
}

tg_real tgi_v3_length(tg_vec3 a)
{
    uint64_t sum = (uint64_t)((int64_t)a.x * a.x) + (uint64_t)((int64_t)a.y * a.y)
                 + (uint64_t)((int64_t)a.z * a.z);
    uint64_t r = tgi_isqrt_round64(sum); /* sum = |a|^2 2^32 exactly */
    return r > (uint64_t)TG_REAL_MAX ? TG_REAL_MAX : (tg_real)r;
}

/* r . v over four terms: 64-bit products, one rounding (pairs halved only
 * when the sum could leave 64 bits). */
static tg_real dot4(const tg_real *r, tg_real a, tg_real b, tg_real c, tg_real d)
{
    int64_t s1 = (int64_t)r[0] * a + (int64_t)r[1] * b;
    int64_t s2 = (int64_t)r[2] * c + (int64_t)r[3] * d;
    const int64_t lim = (int64_t)1 << 62;
    if (s1 < lim && s1 > -lim && s2 < lim && s2 > -lim)
        return tgi_sat64(tgi_shr_round(s1 + s2, TG_FRAC_BITS));
    return tgi_sat64(tgi_shr_round(tgi_shr_round(s1, 1) + tgi_shr_round(s2, 1), TG_FRAC_BITS - 1));
}

#else

/* Multiply v[0..n) by 2^(64 k), one exact step at a time. */
static void scale_pow2_64(tg_real *v, int n, int k)
{
    int i;
    for (; k > 0; k--) for (i = 0; i < n; i++) v[i] *= 18446744073709551616.0f;
    for (; k < 0; k++) for (i = 0; i < n; i++) v[i] *= 5.42101086e-20f;
}

/* k such that 2^(64 k) brings max |v| into [2^-32, 2^32]. */
static int prescale(const tg_real *v, int n)
{
    float m = 0.0f;
    int i, k = 0;
    for (i = 0; i < n; i++) {
        float a = v[i] < 0.0f ? -v[i] : v[i];
        if (a > m) m = a;
    }
    while (m < 2.3283064e-10f && m > 0.0f) { m *= 18446744073709551616.0f; k++; }
    while (m > 4294967296.0f) { m *= 5.42101086e-20f; k--; }
    return k;
}

static int finite_n(const tg_real *v, int n)
{
    int i;
    for (i = 0; i < n; i++) if (!tg_isfinite(v[i])) return 0;
    return 1;
}

static VEC_NORMALIZE_INLINE int normalize_n(tg_real *v, int n)
{
    float w[VEC_MAX_N], sum = 0.0f, r;
    int i;
    for (i = 0; i < n; i++) sum += v[i] * v[i];
    if (sum > 1e-30f && sum < 1e30f) { /* the common case: no scaling needed */
        r = tg_sqrt(sum);
        for (i = 0; i < n; i++) v[i] = v[i] / r;
        return 1;
    }
    sum = 0.0f;
    if (!finite_n(v, n)) return 0;
    for (i = 0; i < n; i++) w[i] = v[i];
    scale_pow2_64(w, n, prescale(v, n));
    for (i = 0; i < n; i++) sum += w[i] * w[i];
    if (!(sum > 0.0f)) return 0;
    r = tg_sqrt(sum); /* divide: axis-aligned vectors come out exact */
    for (i = 0; i < n; i++) v[i] = w[i] / r;
    return 1;
}

tg_real tgi_v3_length(tg_vec3 a)
{
    tg_real v[3], l[1];
    float sum = a.x * a.x + a.y * a.y + a.z * a.z;
    int k;
    if (sum > 1e-30f && sum < 1e30f) return tg_sqrt(sum);
    v[0] = a.x; v[1] = a.y; v[2] = a.z;
    if (!finite_n(v, 3)) return TG_REAL_MAX;
    k = prescale(v, 3);
    scale_pow2_64(v, 3, k);
    l[0] = tg_sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    scale_pow2_64(l, 1, -k);
    return l[0];
}

static tg_real dot4(const tg_real *r, tg_real a, tg_real b, tg_real c, tg_real d)
{
    return r[0] * a + r[1] * b + r[2] * c + r[3] * d;
}

#endif

tg_vec3 tgi_v3_normalize_or(tg_vec3 a, tg_vec3 fallback)
{
    tg_real v[3];
    v[0] = a.x; v[1] = a.y; v[2] = a.z;
    if (!normalize_n(v, 3)) return fallback;
    return tg_v3(v[0], v[1], v[2]);
}

tg_vec3 tgi_v3_normalize(tg_vec3 a) { return tgi_v3_normalize_or(a, tg_v3(0, 0, 0)); }

/* ---- matrices ---- */

tgi_mat4 tgi_m4_identity(void)
{
    tgi_mat4 m;
    memset(&m, 0, sizeof m);
    m.m[0] = m.m[5] = m.m[10] = m.m[15] = TG_ONE;
    return m;
}

tgi_mat4 tgi_m4_mul(const tgi_mat4 *a, const tgi_mat4 *b)
{
    tgi_mat4 r;
    int i, j;
    memset(&r, 0, sizeof r);
    for (i = 0; i < 4; i++)
        for (j = 0; j < 4; j++)
            r.m[i * 4 + j] = dot4(&a->m[i * 4], b->m[j], b->m[4 + j], b->m[8 + j], b->m[12 + j]);
    return r;
}

tgi_vec4 tgi_m4_apply(const tgi_mat4 *m, tgi_vec4 v)
{
    tgi_vec4 r;
    r.x = dot4(&m->m[0], v.x, v.y, v.z, v.w);
    r.y = dot4(&m->m[4], v.x, v.y, v.z, v.w);
    r.z = dot4(&m->m[8], v.x, v.y, v.z, v.w);
    r.w = dot4(&m->m[12], v.x, v.y, v.z, v.w);
    return r;
}

tg_vec3 tgi_m4_point(const tgi_mat4 *m, tg_vec3 p)
{
    return tg_v3(dot4(&m->m[0], p.x, p.y, p.z, TG_ONE), dot4(&m->m[4], p.x, p.y, p.z, TG_ONE),
                 dot4(&m->m[8], p.x, p.y, p.z, TG_ONE));
}

tg_vec3 tgi_m4_dir(const tgi_mat4 *m, tg_vec3 d)
{
    return tg_v3(dot4(&m->m[0], d.x, d.y, d.z, 0), dot4(&m->m[4], d.x, d.y, d.z, 0),
                 dot4(&m->m[8], d.x, d.y, d.z, 0));
}

tgi_mat4 tgi_m4_translate(tg_vec3 t)
{
    tgi_mat4 m = tgi_m4_identity();
    m.m[3] = t.x;
    m.m[7] = t.y;
    m.m[11] = t.z;
    return m;
}

tgi_mat4 tgi_m4_scale(tg_real s)
{
    tgi_mat4 m = tgi_m4_identity();
    m.m[0] = s;
    m.m[5] = s;
    m.m[10] = s;
    return m;
}

/* Rodrigues' rotation formula, R = c I + s [k]x + (1 - c) k k^T, for a unit
 * axis k; counter-clockwise looking down the axis (right-handed). */
tgi_mat4 tgi_m4_rotate(tg_vec3 axis, tg_real angle_rad)
{
    tgi_mat4 m = tgi_m4_identity();
    tg_vec3 k = axis;
    tg_real c, s, t;
    tg_real v[3];
    v[0] = k.x; v[1] = k.y; v[2] = k.z;
    if (!normalize_n(v, 3)) return m;
    k = tg_v3(v[0], v[1], v[2]);
    c = tg_cos(angle_rad);
    s = tg_sin(angle_rad);
    t = tg_sub(TG_ONE, c);
    m.m[0] = tg_add(tg_mul(t, tg_mul(k.x, k.x)), c);
    m.m[1] = tg_sub(tg_mul(t, tg_mul(k.x, k.y)), tg_mul(s, k.z));
    m.m[2] = tg_add(tg_mul(t, tg_mul(k.x, k.z)), tg_mul(s, k.y));
    m.m[4] = tg_add(tg_mul(t, tg_mul(k.x, k.y)), tg_mul(s, k.z));
    m.m[5] = tg_add(tg_mul(t, tg_mul(k.y, k.y)), c);
    m.m[6] = tg_sub(tg_mul(t, tg_mul(k.y, k.z)), tg_mul(s, k.x));
    m.m[8] = tg_sub(tg_mul(t, tg_mul(k.x, k.z)), tg_mul(s, k.y));
    m.m[9] = tg_add(tg_mul(t, tg_mul(k.y, k.z)), tg_mul(s, k.x));
    m.m[10] = tg_add(tg_mul(t, tg_mul(k.z, k.z)), c);
    return m;
}

/* ---- quaternions (x, y, z vector part, w scalar) ---- */

static tgi_quat quat(tg_real x, tg_real y, tg_real z, tg_real w)
{
    tgi_quat q;
    q.x = x; q.y = y; q.z = z; q.w = w;
    return q;
}

static tgi_quat quat_normalize(tgi_quat q)
{
    tg_real v[4];
    v[0] = q.x; v[1] = q.y; v[2] = q.z; v[3] = q.w;
    if (!normalize_n(v, 4)) return quat(0, 0, 0, TG_ONE);
    return quat(v[0], v[1], v[2], v[3]);
}

static tg_real quat_dot(tgi_quat a, tgi_quat b)
{
    tg_real r[4];
    r[0] = a.x; r[1] = a.y; r[2] = a.z; r[3] = a.w;
    return dot4(r, b.x, b.y, b.z, b.w);
}

/* q = (k sin(angle/2), cos(angle/2)) */
tgi_quat tgi_q_axis_angle(tg_vec3 axis, tg_real angle_rad)
{
    tg_real v[3], half = tg_ldexp(angle_rad, -1), s;
    v[0] = axis.x; v[1] = axis.y; v[2] = axis.z;
    if (!normalize_n(v, 3)) return quat(0, 0, 0, TG_ONE);
    s = tg_sin(half);
    return quat(tg_mul(v[0], s), tg_mul(v[1], s), tg_mul(v[2], s), tg_cos(half));
}

/* Shoemake's slerp: sin((1-t) theta)/sin(theta) a + sin(t theta)/sin(theta) b,
 * b negated when a.b < 0 (shortest arc); nlerp when nearly parallel. */
tgi_quat tgi_q_slerp(tgi_quat a, tgi_quat b, tg_real t)
{
    tg_real d, wa, wb;
    if (t <= 0) return a;
    if (t >= TG_ONE) return b;
    d = quat_dot(a, b);
    if (d < 0) { b = quat(tg_neg(b.x), tg_neg(b.y), tg_neg(b.z), tg_neg(b.w)); d = tg_neg(d); }
    if (d > TG_R(0.9995f)) {
        wa = tg_sub(TG_ONE, t);
        wb = t;
    } else {
        tg_real theta = tg_acos(d), inv_s = tg_div(TG_ONE, tg_sin(theta));
        wa = tg_mul(tg_sin(tg_mul(tg_sub(TG_ONE, t), theta)), inv_s);
        wb = tg_mul(tg_sin(tg_mul(t, theta)), inv_s);
    }
    return quat_normalize(quat(tg_add(tg_mul(a.x, wa), tg_mul(b.x, wb)),
                               tg_add(tg_mul(a.y, wa), tg_mul(b.y, wb)),
                               tg_add(tg_mul(a.z, wa), tg_mul(b.z, wb)),
                               tg_add(tg_mul(a.w, wa), tg_mul(b.w, wb))));
}

/* Rotation matrix of q (scaled by 2/|q|^2 so a non-unit q still rotates). */
tgi_mat4 tgi_q_to_m4(tgi_quat q)
{
    tgi_mat4 m = tgi_m4_identity();
    tg_real n2 = quat_dot(q, q), s, xs, ys, zs;
    tg_real wx, wy, wz, xx, xy, xz, yy, yz, zz;
    if (!(n2 > 0)) return m;
    s = tg_div(TG_R(2.0f), n2);
    xs = tg_mul(q.x, s); ys = tg_mul(q.y, s); zs = tg_mul(q.z, s);
    wx = tg_mul(q.w, xs); wy = tg_mul(q.w, ys); wz = tg_mul(q.w, zs);
    xx = tg_mul(q.x, xs); xy = tg_mul(q.x, ys); xz = tg_mul(q.x, zs);
    yy = tg_mul(q.y, ys); yz = tg_mul(q.y, zs); zz = tg_mul(q.z, zs);
    m.m[0] = tg_sub(TG_ONE, tg_add(yy, zz));
    m.m[1] = tg_sub(xy, wz);
    m.m[2] = tg_add(xz, wy);
    m.m[4] = tg_add(xy, wz);
    m.m[5] = tg_sub(TG_ONE, tg_add(xx, zz));
    m.m[6] = tg_sub(yz, wx);
    m.m[8] = tg_sub(xz, wy);
    m.m[9] = tg_add(yz, wx);
    m.m[10] = tg_sub(TG_ONE, tg_add(xx, yy));
    return m;
}

/* ---------------------------------------------------------------------- */
/* geometry helpers of the scene (parser and meshes)                      */

tg_vec3 tgi_unit(tg_vec3 v)
{
    tg_vec3 u = tgi_v3_normalize_or(v, tg_v3(0, 0, 0));
    /* an axis-aligned vector's unit is exact: keep it so */
    if (u.y == 0 && u.z == 0 && u.x != 0) u.x = u.x > 0 ? TG_ONE : tg_neg(TG_ONE);
    if (u.x == 0 && u.z == 0 && u.y != 0) u.y = u.y > 0 ? TG_ONE : tg_neg(TG_ONE);
    if (u.x == 0 && u.y == 0 && u.z != 0) u.z = u.z > 0 ? TG_ONE : tg_neg(TG_ONE);
    return u;
}

tg_real tgi_deg_to_rad(tg_real deg)
{
    /* multiply by pi first (keeps Q16.16 precision) unless that would saturate */
    if (tg_abs(deg) <= TG_R(10000.0f)) return tg_div(tg_mul(deg, TG_PI), TG_R(180.0f));
    return tg_mul(tg_div(deg, TG_R(180.0f)), TG_PI);
}

int tgi_face_normal(tg_vec3 a, tg_vec3 b, tg_vec3 c, tg_vec3 *n)
{
    tg_vec3 e1 = tgi_v3_sub(b, a), e2 = tgi_v3_sub(c, a), x;
    tg_real m1 = tgi_v3_max_abs(e1), m2 = tgi_v3_max_abs(e2);
    if (m1 == 0 || m2 == 0) return 0;
    /* scale both edges into [-1, 1] first so the fixed-point cross product
     * neither saturates nor loses its small components */
    e1 = tg_v3(tg_div(e1.x, m1), tg_div(e1.y, m1), tg_div(e1.z, m1));
    e2 = tg_v3(tg_div(e2.x, m2), tg_div(e2.y, m2), tg_div(e2.z, m2));
    x = tgi_v3_cross(e1, e2);
    if (tgi_v3_max_abs(x) <= TG_R(2e-5f)) return 0;
    *n = tgi_unit(x);
    return 1;
}
