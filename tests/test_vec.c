/* SPDX-License-Identifier: MIT */
/*
 * test_vec.c - vectors, matrices, Rodrigues rotation and quaternions for
 * the number type of this build: unit length after normalize (big and tiny
 * vectors too), exact lengths in fixed point, cross/dot identities,
 * orthonormal rotation matrices, slerp endpoints / midpoint / shortest arc,
 * overflow-safe matrix rows.
 */
#include "check.h"
#include "core/vec.h"
#include <stdlib.h>


/* one ulp of the build (fixed) or a float tolerance scaled by magnitude */
#define ULP CHECK_ULP
#if TG_FIXED
#define DIR_TOL (1.5 * ULP)  /* per component of a normalized vector */
#define ROT_TOL (8 * ULP)    /* per element of a rotation matrix product */
#else
#define DIR_TOL 4e-7
#define ROT_TOL 2.5e-6
#endif

static unsigned rng_state = 1;
static double rnd(void) { return check_rnd(&rng_state); } /* [0, 1) */
static tg_real rnd_real(double lo, double hi) { return tg_from_float((float)(lo + (hi - lo) * rnd())); }
/* One draw per statement: C leaves the order of arguments unspecified, and
 * the same inputs must be drawn on every target (s390x, powerpc). */
static tg_vec3 rnd_vec(double r)
{
    tg_real x = rnd_real(-r, r), y, z;
    y = rnd_real(-r, r);
    z = rnd_real(-r, r);
    return tg_v3(x, y, z);
}

static double len_d(tg_vec3 a) { return sqrt(check_exact(a.x) * check_exact(a.x) + check_exact(a.y) * check_exact(a.y) + check_exact(a.z) * check_exact(a.z)); }
static double dot_d(tg_vec3 a, tg_vec3 b) { return check_exact(a.x) * check_exact(b.x) + check_exact(a.y) * check_exact(b.y) + check_exact(a.z) * check_exact(b.z); }

TEST(length_exact)
{
    int i;
    CHECK(tgi_v3_length(tg_v3(TG_R(3.0f), TG_R(4.0f), 0)) == TG_R(5.0f), "|(3,4,0)| = 5");
    CHECK(tgi_v3_length(tg_v3(TG_R(2.0f), TG_R(3.0f), TG_R(6.0f))) == TG_R(7.0f), "|(2,3,6)| = 7");
    CHECK(tgi_v3_length(tg_v3(0, 0, 0)) == 0, "|0| = 0");
    for (i = 0; i < 200000; i++) {
        double mag = pow(10.0, -4.0 + 8.0 * rnd());
        tg_vec3 a = rnd_vec(mag > 18000.0 ? 18000.0 : mag);
#if TG_FIXED
        /* exactly round(sqrt(sum of raw squares)) */
        double sum = (double)a.x * a.x + (double)a.y * a.y + (double)a.z * a.z;
        double r = floor(sqrt(sum) + 0.5);
        if (r > 2147483647.0) r = 2147483647.0;
        CHECK(fabs((double)tgi_v3_length(a) - r) <= 0.0, "length raw %d vs %.0f", tgi_v3_length(a), r);
#else
        double ref = len_d(a);
        CHECK(fabs(check_exact(tgi_v3_length(a)) - ref) <= 3e-7 * ref, "length %.9g vs %.9g", check_exact(tgi_v3_length(a)), ref);
#endif
    }
#if TG_FIXED
    CHECK(tgi_v3_length(tg_v3(TG_REAL_MAX, TG_REAL_MAX, TG_REAL_MAX)) == TG_REAL_MAX, "saturates");
#else
    CHECK_NEAR(check_exact(tgi_v3_length(tg_v3(3e30f, 4e30f, 0))) / 5e30, 1.0, 1e-6);
    CHECK_NEAR(check_exact(tgi_v3_length(tg_v3(3e-40f, 4e-40f, 0))) / 5e-40, 1.0, 1e-4);
#endif
}

/* normalize: unit length, same direction */
static void check_unit(tg_vec3 a, const char *what)
{
    tg_vec3 n = tgi_v3_normalize(a);
    double l = len_d(a);
    CHECK(fabs(len_d(n) - 1.0) <= 3 * ULP, "%s: |n| = %.9g", what, len_d(n));
    CHECK(fabs(check_exact(n.x) - check_exact(a.x) / l) <= DIR_TOL && fabs(check_exact(n.y) - check_exact(a.y) / l) <= DIR_TOL &&
          fabs(check_exact(n.z) - check_exact(a.z) / l) <= DIR_TOL,
          "%s: direction (%.9g %.9g %.9g) of (%.9g %.9g %.9g)", what, check_exact(n.x), check_exact(n.y), check_exact(n.z),
          check_exact(a.x), check_exact(a.y), check_exact(a.z));
}

TEST(normalize_unit)
{
    int i;
    tg_vec3 fb = tg_v3(0, TG_ONE, 0);
    for (i = 0; i < 200000; i++) {
        double mag = pow(10.0, -4.0 + 8.5 * rnd());
        tg_vec3 a = rnd_vec(mag > 32000.0 ? 32000.0 : mag);
        if (a.x == 0 && a.y == 0 && a.z == 0) continue; /* rounded to zero in fixed */
        check_unit(a, "random");
    }
#if TG_FIXED
    /* huge: components at the range end, the sum of squares needs 64 bits */
    check_unit(tg_v3(TG_REAL_MAX, TG_REAL_MAX, TG_REAL_MAX), "max");
    check_unit(tg_v3(TG_REAL_MIN, TG_REAL_MAX, 0), "min/max");
    check_unit(tg_v3(TG_R(30000.0f), TG_R(-20000.0f), TG_R(100.0f)), "big");
    /* tiny: a few ulps */
    check_unit(tg_v3(1, 0, 0), "1 ulp");
    check_unit(tg_v3(1, 2, 2), "(1,2,2) ulps");
    check_unit(tg_v3(-3, 0, 4), "(-3,0,4) ulps");
    CHECK(tgi_v3_normalize(tg_v3(1, 2, 2)).x == tg_ratio(1, 3), "(1,2,2) ulps -> 1/3 exactly rounded");
    CHECK(tgi_v3_normalize(tg_v3(7, 0, 0)).x == TG_ONE, "(7,0,0) ulps -> (1,0,0)");
#else
    check_unit(tg_v3(3e38f, -3e38f, 3e38f), "huge");
    check_unit(tg_v3(1e-45f, 0.0f, 0.0f), "subnormal");
    check_unit(tg_v3(3e-42f, 4e-42f, 0.0f), "subnormal 3-4-5");
#endif
    {
        tg_vec3 z = tgi_v3_normalize(tg_v3(0, 0, 0)), f = tgi_v3_normalize_or(tg_v3(0, 0, 0), fb);
        CHECK(z.x == 0 && z.y == 0 && z.z == 0, "normalize(0) = 0");
        CHECK(f.x == 0 && f.y == TG_ONE && f.z == 0, "normalize_or(0) = fallback");
    }
}

TEST(cross_dot_identities)
{
    int i;
    tg_vec3 x = tg_v3(TG_ONE, 0, 0), y = tg_v3(0, TG_ONE, 0), z = tg_v3(0, 0, TG_ONE);
    tg_vec3 c = tgi_v3_cross(x, y);
    CHECK(c.x == 0 && c.y == 0 && c.z == TG_ONE, "x cross y = z (right-handed)");
    c = tgi_v3_cross(y, z);
    CHECK(c.x == TG_ONE && c.y == 0 && c.z == 0, "y cross z = x");
    for (i = 0; i < 100000; i++) {
        tg_vec3 a = tgi_v3_normalize(rnd_vec(1.0)), b = tgi_v3_normalize(rnd_vec(1.0));
        tg_vec3 axb = tgi_v3_cross(a, b), bxa = tgi_v3_cross(b, a);
        double d = check_exact(tgi_v3_dot(a, b)), l = len_d(axb);
        /* perpendicular to both factors */
        CHECK(fabs(dot_d(axb, a)) <= 4 * ULP && fabs(dot_d(axb, b)) <= 4 * ULP, "a x b not perpendicular");
        /* anti-commutative, exactly */
        CHECK(axb.x == tg_neg(bxa.x) && axb.y == tg_neg(bxa.y) && axb.z == tg_neg(bxa.z), "a x b = -(b x a)");
        /* Lagrange: |a x b|^2 + (a.b)^2 = |a|^2 |b|^2 = 1 */
        CHECK(fabs(l * l + d * d - 1.0) <= 12 * ULP, "Lagrange identity %.9g", l * l + d * d);
        /* dot is symmetric and matches the exact value */
        CHECK(tgi_v3_dot(a, b) == tgi_v3_dot(b, a), "dot symmetric");
        /* float: each product and sum rounds, so the bound scales with sum |a_i b_i| (cancellation) */
        CHECK(fabs(d - dot_d(a, b)) <= 0.5 * ULP + 2e-7 * (fabs(check_exact(a.x) * check_exact(b.x)) + fabs(check_exact(a.y) * check_exact(b.y)) + fabs(check_exact(a.z) * check_exact(b.z))),
              "dot rounding %.9g vs %.9g", d, dot_d(a, b));
    }
}

static double m4(const tgi_mat4 *m, int r, int c) { return check_exact(m->m[r * 4 + c]); }

/* R R^T = I, det R = +1, last row/column of an affine rotation */
static void check_rotation(const tgi_mat4 *r, double tol, const char *what)
{
    int i, j, k;
    double det;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double s = 0;
            for (k = 0; k < 3; k++) s += m4(r, i, k) * m4(r, j, k);
            CHECK(fabs(s - (i == j ? 1.0 : 0.0)) <= tol, "%s: (R R^T)[%d][%d] = %.9g", what, i, j, s);
        }
    det = m4(r, 0, 0) * (m4(r, 1, 1) * m4(r, 2, 2) - m4(r, 1, 2) * m4(r, 2, 1))
        - m4(r, 0, 1) * (m4(r, 1, 0) * m4(r, 2, 2) - m4(r, 1, 2) * m4(r, 2, 0))
        + m4(r, 0, 2) * (m4(r, 1, 0) * m4(r, 2, 1) - m4(r, 1, 1) * m4(r, 2, 0));
    CHECK(fabs(det - 1.0) <= 2 * tol, "%s: det %.9g", what, det);
    CHECK(r->m[3] == 0 && r->m[7] == 0 && r->m[11] == 0 && r->m[12] == 0 && r->m[13] == 0 &&
          r->m[14] == 0 && r->m[15] == TG_ONE, "%s: not affine", what);
}

TEST(rotation_orthonormal)
{
    int i;
    tgi_mat4 r = tgi_m4_rotate(tg_v3(0, 0, TG_R(5.0f)), TG_HALF_PI);
    tg_vec3 p = tgi_m4_dir(&r, tg_v3(TG_ONE, 0, 0));
    /* counter-clockwise about +Z: x -> y */
    CHECK_NEAR(check_exact(p.x), 0.0, 2 * ULP);
    CHECK_NEAR(check_exact(p.y), 1.0, 2 * ULP);
    CHECK_NEAR(check_exact(p.z), 0.0, 2 * ULP);
    r = tgi_m4_rotate(tg_v3(0, 0, 0), TG_ONE);
    check_rotation(&r, 0, "zero axis gives identity");
    for (i = 0; i < 20000; i++) {
        tg_vec3 axis = rnd_vec(10.0), k = tgi_v3_normalize(axis), ka;
        tg_real angle = rnd_real(-7.0, 7.0);
        double c = cos(check_exact(angle)), s = sin(check_exact(angle));
        tg_vec3 v = rnd_vec(1.0), rv;
        double kx = check_exact(k.x), ky = check_exact(k.y), kz = check_exact(k.z), vx = check_exact(v.x), vy = check_exact(v.y), vz = check_exact(v.z);
        double kv = kx * vx + ky * vy + kz * vz, ex, ey, ez;
        if (len_d(axis) < 1e-3) continue;
        r = tgi_m4_rotate(axis, angle);
        check_rotation(&r, ROT_TOL, "rotate");
        /* the axis is fixed */
        ka = tgi_m4_dir(&r, k);
        CHECK(fabs(check_exact(ka.x) - kx) <= 6 * ULP && fabs(check_exact(ka.y) - ky) <= 6 * ULP && fabs(check_exact(ka.z) - kz) <= 6 * ULP,
              "axis moved");
        /* Rodrigues in 64-bit arithmetic */
        ex = vx * c + (ky * vz - kz * vy) * s + kx * kv * (1 - c);
        ey = vy * c + (kz * vx - kx * vz) * s + ky * kv * (1 - c);
        ez = vz * c + (kx * vy - ky * vx) * s + kz * kv * (1 - c);
        rv = tgi_m4_dir(&r, v);
        CHECK(fabs(check_exact(rv.x) - ex) <= 8 * ULP && fabs(check_exact(rv.y) - ey) <= 8 * ULP && fabs(check_exact(rv.z) - ez) <= 8 * ULP,
              "rotated (%.9g %.9g %.9g) vs (%.9g %.9g %.9g)", check_exact(rv.x), check_exact(rv.y), check_exact(rv.z), ex, ey, ez);
    }
}

TEST(matrix_basics)
{
    tgi_mat4 id = tgi_m4_identity(), t = tgi_m4_translate(tg_v3(TG_ONE, TG_R(2.0f), TG_R(-3.0f)));
    tgi_mat4 s = tgi_m4_scale(TG_R(2.0f)), r = tgi_m4_rotate(tg_v3(0, TG_ONE, 0), TG_R(0.7f));
    tgi_mat4 ts = tgi_m4_mul(&t, &s), a, b, rt, r_t;
    tg_vec3 p = tg_v3(TG_R(0.5f), TG_R(-1.0f), TG_R(4.0f)), q;
    tgi_vec4 v4, w4;
    int i;
    a = tgi_m4_mul(&id, &t);
    b = tgi_m4_mul(&t, &id);
    CHECK(memcmp(&a, &t, sizeof a) == 0 && memcmp(&b, &t, sizeof b) == 0, "I T = T I = T");
    q = tgi_m4_point(&ts, p); /* T (S p) */
    CHECK(q.x == TG_R(2.0f) && q.y == 0 && q.z == TG_R(5.0f), "translate(scale(p))");
    q = tgi_m4_dir(&t, p);
    CHECK(q.x == p.x && q.y == p.y && q.z == p.z, "directions ignore translation");
    /* (R T) p = R (T p) */
    rt = tgi_m4_mul(&r, &t);
    q = tgi_m4_point(&rt, p);
    {
        tg_vec3 tp = tgi_m4_point(&t, p), rtp = tgi_m4_point(&r, tp);
        CHECK(fabs(check_exact(q.x) - check_exact(rtp.x)) <= 4 * ULP * 5 && fabs(check_exact(q.y) - check_exact(rtp.y)) <= 4 * ULP * 5 &&
              fabs(check_exact(q.z) - check_exact(rtp.z)) <= 4 * ULP * 5, "associativity");
    }
    v4.x = p.x; v4.y = p.y; v4.z = p.z; v4.w = TG_ONE;
    w4 = tgi_m4_apply(&rt, v4);
    CHECK(w4.x == q.x && w4.y == q.y && w4.z == q.z && w4.w == TG_ONE, "apply with w = 1 equals point");
    /* R^T R = I through tgi_m4_mul */
    for (i = 0; i < 16; i++) r_t.m[i] = r.m[(i % 4) * 4 + i / 4];
    a = tgi_m4_mul(&r_t, &r);
    for (i = 0; i < 16; i++) CHECK_NEAR(check_exact(a.m[i]), (i % 5 == 0) ? 1.0 : 0.0, 4 * ULP);
#if TG_FIXED
    /* rows whose products pass 2^63 in total still come out right */
    {
        tgi_mat4 big = tgi_m4_identity();
        tgi_vec4 u, o;
        for (i = 0; i < 4; i++) big.m[i] = TG_REAL_MAX;
        big.m[4] = TG_REAL_MAX; big.m[5] = TG_REAL_MIN; big.m[6] = TG_REAL_MAX; big.m[7] = TG_REAL_MIN;
        u.x = u.y = u.z = u.w = TG_REAL_MAX;
        o = tgi_m4_apply(&big, u);
        CHECK(o.x == TG_REAL_MAX, "huge row saturates (%d)", o.x);
        CHECK(o.y == 0, "huge cancelling row gives exactly 0 (%d)", o.y);
        u.x = TG_R(30000.0f); u.y = TG_R(-30000.0f); u.z = 0; u.w = 0;
        big.m[8] = TG_R(30000.0f); big.m[9] = TG_R(30000.0f); big.m[10] = 0; big.m[11] = 0;
        o = tgi_m4_apply(&big, u);
        CHECK(o.z == 0, "30000^2 - 30000^2 = 0 (%d)", o.z);
    }
#endif
}

static tgi_quat qneg(tgi_quat q) { q.x = tg_neg(q.x); q.y = tg_neg(q.y); q.z = tg_neg(q.z); q.w = tg_neg(q.w); return q; }
static double qdot_d(tgi_quat a, tgi_quat b) { return check_exact(a.x) * check_exact(b.x) + check_exact(a.y) * check_exact(b.y) + check_exact(a.z) * check_exact(b.z) + check_exact(a.w) * check_exact(b.w); }

TEST(quaternions)
{
    int i;
    for (i = 0; i < 20000; i++) {
        tg_vec3 axis = rnd_vec(1.0), axis2 = rnd_vec(1.0);
        tg_real angle = rnd_real(-3.1, 3.1), angle2 = rnd_real(-3.1, 3.1);
        tgi_quat q, qa, qb, h, m, m2;
        tgi_mat4 mq, mr;
        int j;
        if (len_d(axis) < 1e-2 || len_d(axis2) < 1e-2) continue;
        q = tgi_q_axis_angle(axis, angle);
        CHECK(fabs(qdot_d(q, q) - 1.0) <= 4 * ULP, "|q| = 1");
        /* q to matrix equals Rodrigues */
        mq = tgi_q_to_m4(q);
        mr = tgi_m4_rotate(axis, angle);
        check_rotation(&mq, ROT_TOL, "q_to_m4");
        for (j = 0; j < 16; j++) CHECK_NEAR(check_exact(mq.m[j]), check_exact(mr.m[j]), 8 * ULP);
        /* slerp endpoints exact */
        qa = tgi_q_axis_angle(axis2, angle2);
        qb = q;
        m = tgi_q_slerp(qa, qb, 0);
        CHECK(memcmp(&m, &qa, sizeof m) == 0, "slerp(t=0) = a exactly");
        m = tgi_q_slerp(qa, qb, TG_ONE);
        CHECK(memcmp(&m, &qb, sizeof m) == 0, "slerp(t=1) = b exactly");
        /* midpoint of identity -> q is the half rotation */
        h = tgi_q_axis_angle(axis, tg_ldexp(angle, -1));
        m = tgi_q_slerp(tgi_q_axis_angle(axis, 0), q, TG_R(0.5f));
        CHECK(fabs(fabs(qdot_d(m, h)) - 1.0) <= 8 * ULP, "midpoint: dot %.9g", qdot_d(m, h));
        /* shortest arc: -b is the same rotation, same path */
        m = tgi_q_slerp(qa, qb, TG_R(0.3f));
        m2 = tgi_q_slerp(qa, qneg(qb), TG_R(0.3f));
        CHECK(fabs(qdot_d(m, m2) - 1.0) <= 8 * ULP, "slerp(a, -b) = slerp(a, b)");
        CHECK(fabs(qdot_d(m, m) - 1.0) <= 4 * ULP, "slerp result unit");
    }
    /* a 300-degree rotation is reached the short way: the midpoint turns -30 degrees */
    {
        tg_vec3 zax = tg_v3(0, 0, TG_ONE);
        tgi_quat id = tgi_q_axis_angle(zax, 0), far = tgi_q_axis_angle(zax, TG_R((float)(300.0 * CHECK_PI / 180.0)));
        tgi_quat mid = tgi_q_slerp(id, far, TG_R(0.5f)), want = tgi_q_axis_angle(zax, TG_R((float)(-30.0 * CHECK_PI / 180.0)));
        CHECK(fabs(fabs(qdot_d(mid, want)) - 1.0) <= 8 * ULP, "shortest arc midpoint, dot %.9g", qdot_d(mid, want));
    }
    /* nearly equal quaternions (the nlerp branch) stay unit and between */
    {
        tg_vec3 yax = tg_v3(0, TG_ONE, 0);
        tgi_quat a = tgi_q_axis_angle(yax, TG_R(0.01f)), b = tgi_q_axis_angle(yax, TG_R(0.02f));
        tgi_quat m = tgi_q_slerp(a, b, TG_R(0.5f)), want = tgi_q_axis_angle(yax, TG_R(0.015f));
        CHECK(fabs(qdot_d(m, want) - 1.0) <= 8 * ULP, "nlerp branch dot %.9g", qdot_d(m, want));
    }
}

/* Slerp interpolates the angle: a 16-degree turn about y at t = 0.25 is
 * the 4-degree turn, q = (0, sin 2, 0, cos 2) degrees, to 1e-6 in float
 * (normalised lerp there is 4e-5 off; 1e-4 in fixed point). */
TEST(slerp_is_angle_linear_below_the_nlerp_switch)
{
    tg_vec3 yax = tg_v3(0, TG_ONE, 0);
    double tol = TG_FIXED ? 1e-4 : 1e-6, a;
    int k;
    for (k = 1; k < 4; k++) {
        tgi_quat m = tgi_q_slerp(tgi_q_axis_angle(yax, 0), tgi_q_axis_angle(yax, TG_R((float)(16.0 * CHECK_PI / 180.0))),
                                 tg_from_float(0.25f * (float)k));
        a = 4.0 * k * CHECK_PI / 180.0;
        CHECK(fabs(check_exact(m.y) - sin(a / 2)) <= tol && fabs(check_exact(m.w) - cos(a / 2)) <= tol,
              "t = %.2f: (%.7f, %.7f), want (%.7f, %.7f)", 0.25 * k, check_exact(m.y), check_exact(m.w), sin(a / 2), cos(a / 2));
    }
}

/* Float lengths of tiny vectors keep their precision (no subnormal sum of
 * squares): |(3, 4, 0) 1e-22| = 5e-22 to 1e-6. */
TEST(length_of_tiny_and_thin)
{
#if !TG_FIXED
    tg_real l = tgi_v3_length(tg_v3(3e-22f, 4e-22f, 0));
    CHECK(fabs(check_exact(l) / 5e-22 - 1) <= 1e-6, "length %g", check_exact(l));
#endif
    {   /* a triangle whose edges are 0.1 degree apart has a face normal; 0.0005 degree is degenerate */
        tg_vec3 n = tg_v3(0, 0, 0);
        double a = 0.1 * CHECK_PI / 180.0, b = 0.0005 * CHECK_PI / 180.0;
        CHECK(tgi_face_normal(tg_v3(0, 0, 0), tg_v3(TG_ONE, 0, 0), tg_v3(tg_from_float((float)cos(a)),
                              tg_from_float((float)sin(a)), 0), &n) == 1 && n.z == TG_ONE, "thin triangle: n.z %g", check_exact(n.z));
        CHECK(tgi_face_normal(tg_v3(0, 0, 0), tg_v3(TG_ONE, 0, 0), tg_v3(tg_from_float((float)cos(b)),
                              tg_from_float((float)sin(b)), 0), &n) == 0, "0.0005 degrees is degenerate");
    }
}

/* Q16.16: three products of values at the range's ends sum past 2^63; the
 * dot product saturates to the sign of the exact sum instead of wrapping
 * (which gave TG_REAL_MIN for three positive products of 2^62, and is
 * undefined in C), and is the plain sum's bits wherever that fits. */
TEST(dot_product_at_the_range_ends)
{
#if TG_FIXED
    const tg_real lo = TG_REAL_MIN, hi = TG_REAL_MAX;
    uint64_t v = 0x9E3779B97F4A7C15u;
    long differ = 0;
    int i;
    CHECK(tgi_v3_dot(tg_v3(lo, lo, lo), tg_v3(lo, lo, lo)) == hi, "three products of 2^62: %ld",
          (long)tgi_v3_dot(tg_v3(lo, lo, lo), tg_v3(lo, lo, lo)));
    CHECK(tgi_v3_dot(tg_v3(lo, lo, lo), tg_v3(hi, hi, hi)) == lo, "three products of -2^62: %ld",
          (long)tgi_v3_dot(tg_v3(lo, lo, lo), tg_v3(hi, hi, hi)));
    CHECK(tgi_v3_dot(tg_v3(lo, lo, hi), tg_v3(lo, lo, lo)) == hi, "2^62 + 2^62 - (2^62 - 2^31)");
    /* two products of 2^62 cancelling, and a small third: its own value */
    CHECK(tgi_v3_dot(tg_v3(hi, lo, 7), tg_v3(hi, hi, TG_ONE)) == tgi_v3_dot(tg_v3(0, 0, 7), tg_v3(0, 0, TG_ONE)) +
          tgi_v3_dot(tg_v3(hi, lo, 0), tg_v3(hi, hi, 0)), "cancelling products: %ld",
          (long)tgi_v3_dot(tg_v3(hi, lo, 7), tg_v3(hi, hi, TG_ONE)));
    /* the first two past 2^62, the third of the other sign: the exact sum, 1 */
    CHECK(tgi_v3_dot(tg_v3(hi, TG_ONE, hi), tg_v3(hi, TG_ONE, lo)) == TG_ONE, "past 2^62 and back: %ld",
          (long)tgi_v3_dot(tg_v3(hi, TG_ONE, hi), tg_v3(hi, TG_ONE, lo)));
    CHECK(tgi_v3_dot(tg_v3(lo, -TG_ONE, lo), tg_v3(hi, TG_ONE, lo)) == -TG_ONE, "past -2^62 and back: %ld",
          (long)tgi_v3_dot(tg_v3(lo, -TG_ONE, lo), tg_v3(hi, TG_ONE, lo)));
    for (i = 0; i < 1000000; i++) {   /* components within 2^30: the plain sum fits */
        int32_t c[6];
        int k;
        int64_t sum = 0;
        for (k = 0; k < 6; k++) {
            v ^= v << 13; v ^= v >> 7; v ^= v << 17;
            c[k] = (int32_t)(uint32_t)(v >> 32) / (1 << (int)(v % 3));
        }
        for (k = 0; k < 3; k++) sum += (int64_t)c[k] * c[k + 3];
        differ += tgi_v3_dot(tg_v3(c[0], c[1], c[2]), tg_v3(c[3], c[4], c[5])) != tgi_sat64(tgi_shr_round(sum, TG_FRAC_BITS));
    }
    CHECK(differ == 0, "%ld of 1e6 dot products differ from the plain sum", differ);
#endif
}

int main(void)
{
    RUN(length_exact);
    RUN(normalize_unit);
    RUN(cross_dot_identities);
    RUN(rotation_orthonormal);
    RUN(matrix_basics);
    RUN(quaternions);
    RUN(slerp_is_angle_linear_below_the_nlerp_switch);
    RUN(length_of_tiny_and_thin);
    RUN(dot_product_at_the_range_ends);
    return check_summary();
}
