/* SPDX-License-Identifier: MIT */
/*
 * sh.c - environment to SH9, and the far-field irradiance read from it:
 * unoccluded (Ramamoorthi-Hanrahan), restricted to the bent cone (HBIL
 * sec. 2.2.4) or scaled by the AO factor F0 (HBIL sec. 2.2.3), both for a
 * cosine-weighted AO (the deviation is documented in sh.h).
 * See sh.h for the basis, the coefficient order and the modes.
 */
#include "sh.h"

#if !TG_NO_ENVIRONMENT /* the whole file is left out with TG_NO_ENVIRONMENT=1 (tinygi.h "FEATURE SWITCHES") */

/* SH basis normalisation constants (Ramamoorthi-Hanrahan eq. 3) */
#define SH_Y00 TG_R(0.282094792f)
#define SH_Y1  TG_R(0.488602512f)
#define SH_Y2A TG_R(1.092548431f) /* xy, yz, xz */
#define SH_Y20 TG_R(0.315391565f) /* (3z^2 - 1) */
#define SH_Y22 TG_R(0.546274215f) /* (x^2 - y^2) */

#define SQRT_PI     TG_R(1.772453851f)
#define SQRT_3PI    TG_R(3.069980124f)
#define SQRT3       TG_R(1.732050808f)
#define TWO_SQRT3   TG_R(3.464101615f)
/* HBIL sec. 2.2.4 constants: c0 = sqrt(pi)/2, c1 = sqrt(3 pi)/3, c2 = sqrt(5 pi)/16 at t = 0 */
#define CONE_C0 TG_R(0.886226925f)
#define CONE_C1 TG_R(1.023326708f)
#define CONE_C2 TG_R(0.247707956f)

void tgi_sh9_from_env(const tgi_env *env, tg_vec3 sh[9])
{
    int i;
    for (i = 0; i < 9; i++) sh[i] = tg_v3(0, 0, 0);
    if (!env) return;
    switch (env->type) {
    case TG_ENV_UNIFORM:
        /* RTR eq. 10.40 for a constant: integral of Y00 over the sphere = 2 sqrt(pi) */
        sh[0] = tgi_v3_scale(env->uniform, tg_mul(TG_R(2.0f), SQRT_PI));
        break;
    case TG_ENV_SKY: {
        /* L = (s+g)/2 + (s-g)/2 sign(u.w): band 0 from the mean, band 1 from the step
         * (integral of sign(u.w) Y10 = sqrt(3 pi)); band 2 is exactly 0. */
        tg_vec3 mean = tgi_v3_add(env->sky, env->ground);        /* (s+g) sqrt(pi) = L00 */
        tg_vec3 half_diff = tgi_v3_scale(tgi_v3_sub(env->sky, env->ground), TG_R(0.5f));
        tg_vec3 b1 = tgi_v3_scale(half_diff, SQRT_3PI);
        tg_vec3 u = env->up;
        sh[0] = tgi_v3_scale(mean, SQRT_PI);
        sh[1] = tgi_v3_scale(b1, u.y);  /* L1-1 ~ y */
        sh[2] = tgi_v3_scale(b1, u.z);  /* L10  ~ z */
        sh[3] = tgi_v3_scale(b1, u.x);  /* L11  ~ x */
        break;
    }
    case TG_ENV_SH9:
        for (i = 0; i < 9; i++) sh[i] = env->sh9[i];
        break;
    default:
        break;
    }
}


#if TGI_Q16_WIDE
/* a b and a - b where the caller bounds the result within the range: tg_mul
 * and tg_sub's integers (tgi_wide_mul rounds as tg_mul rounds) */
typedef tgi_wide sh_weight;   /* in range: the integers in 64 bits (no sign extension before each product) */
static inline sh_weight mul_in(sh_weight a, sh_weight b, int in_range)
{
    return in_range ? tgi_wide_mul(a, b) : tg_mul((tg_real)a, (tg_real)b);
}
static inline sh_weight sub_in(sh_weight a, sh_weight b, int in_range)
{
    return in_range ? a - b : tg_sub((tg_real)a, (tg_real)b);
}
#if defined(__GNUC__)
#define SH_INLINE inline __attribute__((always_inline))   /* in_range a constant in each copy */
#else
#define SH_INLINE inline
#endif
#else
typedef tg_real sh_weight;
#define mul_in(a, b, in_range) tg_mul(a, b)
#define sub_in(a, b, in_range) tg_sub(a, b)
#define SH_INLINE inline
#endif

/* w0 . l0 + w1 . l1 + w2 . l2, each dot rounded once, summed with tg_add.
 * in_range (Q16.16): the weights within 64 (2^22 as integers) against any
 * coefficients (below 2^31) give products below 2^53 and sums below 2^55,
 * so tgi_v3_dot's 2^62 test cannot act and each dot is tgi_wide_dot's
 * integer saturated; when all three lie in [-2^29, 2^29) neither that
 * saturation nor tg_add's can act (partial sums within 2^30, the whole
 * within 3 2^29 < 2^31), so one test of the three stands for five. */
static SH_INLINE tg_real sum3_in(const sh_weight w[9], tg_vec3 l0, tg_vec3 l1, tg_vec3 l2, int in_range)
{
#if TGI_Q16_WIDE
    if (in_range) {
        tgi_wide d0 = tgi_wide_dot(w[0], w[1], w[2], l0.x, l0.y, l0.z);
        tgi_wide d1 = tgi_wide_dot(w[3], w[4], w[5], l1.x, l1.y, l1.z);
        tgi_wide d2 = tgi_wide_dot(w[6], w[7], w[8], l2.x, l2.y, l2.z);
        const tgi_wide half = (tgi_wide)1 << 29;
        if ((((uint64_t)(d0 + half) | (uint64_t)(d1 + half) | (uint64_t)(d2 + half)) >> 30) == 0)
            return (tg_real)(d0 + d1 + d2);
        return tg_add(tg_add(tgi_wide_real(d0), tgi_wide_real(d1)), tgi_wide_real(d2));
    }
#endif
    (void)in_range;
    return tg_add(tg_add(tgi_v3_dot(tg_v3((tg_real)w[0], (tg_real)w[1], (tg_real)w[2]), l0),
                         tgi_v3_dot(tg_v3((tg_real)w[3], (tg_real)w[4], (tg_real)w[5]), l1)),
                  tgi_v3_dot(tg_v3((tg_real)w[6], (tg_real)w[7], (tg_real)w[8]), l2));
}

/* HBIL sec. 2.2.4 evaluation: the per-coefficient weights for normal n and
 * band weights c0, c1, c2 (computed once, shared by the three channels):
 *   E = c0 L00 + c1 (y L1-1 + z L10 + x L11) + c2 L20 (3z^2 - 1)
 *     + c2 sqrt(3) L22 (x^2 - y^2) + 2 sqrt(3) c2 (xy L2-2 + yz L2-1 + zx L21)
 * in_range: |x|, |y|, |z| <= 2 and |c0|, |c1|, |c2| <= 4, so that every
 * weight and its factors stay within 64 (c2x z x: 2 sqrt(3) 4 2 2), no
 * product or difference saturates (a constant where inlined). */
static SH_INLINE tg_vec3 sh_eval_in(const tg_vec3 sh[9], tg_vec3 n, tg_real c0, tg_real c1, tg_real c2, int in_range)
{
    const sh_weight x = n.x, y = n.y, z = n.z, c2x = mul_in(c2, TWO_SQRT3, in_range);
    /* the nine weights (in_range: each the value tg_real would hold, in 64
     * bits); each channel is then three dot products (64-bit accumulation
     * in fixed point, one rounding each) */
    const sh_weight w[9] = {
        c0, mul_in(c1, y, in_range), mul_in(c1, z, in_range),
        mul_in(c1, x, in_range), mul_in(c2x, mul_in(x, y, in_range), in_range), mul_in(c2x, mul_in(y, z, in_range), in_range),
        mul_in(c2, sub_in(mul_in(TG_R(3.0f), mul_in(z, z, in_range), in_range), TG_ONE, in_range), in_range),
        mul_in(c2x, mul_in(z, x, in_range), in_range),
        mul_in(mul_in(c2, SQRT3, in_range), sub_in(mul_in(x, x, in_range), mul_in(y, y, in_range), in_range), in_range)
    };
    tg_real er = sum3_in(w, tg_v3(sh[0].x, sh[1].x, sh[2].x), tg_v3(sh[3].x, sh[4].x, sh[5].x),
                         tg_v3(sh[6].x, sh[7].x, sh[8].x), in_range);
    tg_real eg = sum3_in(w, tg_v3(sh[0].y, sh[1].y, sh[2].y), tg_v3(sh[3].y, sh[4].y, sh[5].y),
                         tg_v3(sh[6].y, sh[7].y, sh[8].y), in_range);
    tg_real eb = sum3_in(w, tg_v3(sh[0].z, sh[1].z, sh[2].z), tg_v3(sh[3].z, sh[4].z, sh[5].z),
                         tg_v3(sh[6].z, sh[7].z, sh[8].z), in_range);
    (void)in_range;   /* unused by the generic code */
    return tg_v3(tg_max(er, 0), tg_max(eg, 0), tg_max(eb, 0));
}

#if TGI_Q16_WIDE && defined(__GNUC__)
/* the saturating copy out of line: inlined beside the in_range copy, gcc
 * computes the products both share before the range test and spills the
 * coefficients (some 30 instructions more a pixel in the common case) */
__attribute__((noinline))
static tg_vec3 sh_eval_saturating(const tg_vec3 sh[9], tg_vec3 n, tg_real c0, tg_real c1, tg_real c2)
{
    return sh_eval_in(sh, n, c0, c1, c2, 0);
}
#else
#define sh_eval_saturating(sh, n, c0, c1, c2) sh_eval_in(sh, n, c0, c1, c2, 0)
#endif

/* c0, c1, c2 within [-2, 3] from both callers (Ramamoorthi-Hanrahan's
 * constants 0.886, 1.023, 0.248; irradiance_in_cone's, shown there), so in
 * Q16.16 only the normal's range is tested for sh_eval_in's in_range. */
static tg_vec3 sh_eval_rgb(const tg_vec3 sh[9], tg_vec3 n, tg_real c0, tg_real c1, tg_real c2)
{
#if TGI_Q16_WIDE
    if ((uint32_t)(n.x + 2 * TG_ONE) <= 4u * TG_ONE && (uint32_t)(n.y + 2 * TG_ONE) <= 4u * TG_ONE &&
        (uint32_t)(n.z + 2 * TG_ONE) <= 4u * TG_ONE)
        return sh_eval_in(sh, n, c0, c1, c2, 1);
#endif
    return sh_eval_saturating(sh, n, c0, c1, c2);
}

tg_vec3 tgi_sh9_irradiance(const tg_vec3 sh[9], tg_vec3 n)
{
    /* Ramamoorthi-Hanrahan eq. 13 = HBIL sec. 2.2.4 with t = cos(pi/2) = 0 */
    return sh_eval_rgb(sh, n, CONE_C0, CONE_C1, CONE_C2);
}

/* HBIL sec. 2.2.4 for t = cos(theta_max), given 1 - t^2 (exact when the
 * caller has it, e.g. AO itself). */
static tg_vec3 irradiance_in_cone(const tg_vec3 sh[9], tg_vec3 axis, tg_real t, tg_real one_minus_t2)
{
    /* t and 1 - t^2 within [0, 1] (both callers): every product and
     * difference below within [-2, 3], none saturates */
    tg_real t2 = sub_in(TG_ONE, one_minus_t2, 1), t3 = mul_in(t2, t, 1), t4 = mul_in(t2, t2, 1);
    tg_real c0 = mul_in(CONE_C0, one_minus_t2, 1);                        /* HBIL 2.2.4 c0 */
    tg_real c1 = mul_in(CONE_C1, sub_in(TG_ONE, t3, 1), 1);              /* HBIL 2.2.4 c1 */
    tg_real c2 = mul_in(CONE_C2, sub_in(mul_in(TG_R(3.0f), sub_in(TG_ONE, t4, 1), 1),
                                        mul_in(TG_R(2.0f), one_minus_t2, 1), 1), 1); /* HBIL 2.2.4 c2 */
    return sh_eval_rgb(sh, axis, c0, c1, c2);
}

tg_vec3 tgi_sh9_irradiance_in_cone(const tg_vec3 sh[9], tg_vec3 axis, tg_real cos_alpha)
{
    tg_real t = tg_saturate(cos_alpha);
    return irradiance_in_cone(sh, axis, t, tg_sub(TG_ONE, tg_mul(t, t)));
}

tg_vec3 tgi_sh9_irradiance_bent_cone(const tg_vec3 sh[9], tg_vec3 bent, tg_real ao)
{
    /* 1 - cos^2(alpha) = AO exactly, so a uniform sky gives pi L AO to the last bit */
    return irradiance_in_cone(sh, bent, tgi_cone_cos_from_ao(ao), tg_saturate(ao));
}

tg_vec3 tgi_sh9_irradiance_f0(const tg_vec3 sh[9], tg_vec3 bent, tg_real ao)
{
    return tgi_v3_scale(tgi_sh9_irradiance(sh, bent), tg_saturate(ao)); /* HBIL sec. 2.2.3, F0(AO) = AO */
}

static tg_real sh_radiance1(const tg_real L[9], tg_vec3 d)
{
    tg_real x = d.x, y = d.y, z = d.z, v;
    v = tg_mul(SH_Y00, L[0]);
    v = tg_add(v, tg_mul(SH_Y1, tg_add(tg_add(tg_mul(y, L[1]), tg_mul(z, L[2])), tg_mul(x, L[3]))));
    v = tg_add(v, tg_mul(SH_Y2A, tg_add(tg_add(tg_mul(tg_mul(x, y), L[4]), tg_mul(tg_mul(y, z), L[5])),
                                        tg_mul(tg_mul(x, z), L[7]))));
    v = tg_add(v, tg_mul(SH_Y20, tg_mul(L[6], tg_sub(tg_mul(TG_R(3.0f), tg_mul(z, z)), TG_ONE))));
    v = tg_add(v, tg_mul(SH_Y22, tg_mul(L[8], tg_sub(tg_mul(x, x), tg_mul(y, y)))));
    return v > 0 ? v : 0;
}

tg_vec3 tgi_sh9_radiance(const tg_vec3 sh[9], tg_vec3 dir)
{
    tg_real r[9], g[9], b[9];
    int i;
    for (i = 0; i < 9; i++) { r[i] = sh[i].x; g[i] = sh[i].y; b[i] = sh[i].z; }
    return tg_v3(sh_radiance1(r, dir), sh_radiance1(g, dir), sh_radiance1(b, dir));
}

tg_vec3 tgi_env_radiance(const tgi_env *env, tg_vec3 dir)
{
    if (!env) return tg_v3(0, 0, 0);
    switch (env->type) {
    case TG_ENV_UNIFORM: return env->uniform;
    case TG_ENV_SKY:
        return tgi_v3_dot(dir, env->up) >= 0 ? env->sky : env->ground;
    case TG_ENV_SH9: return tgi_sh9_radiance(env->sh9, dir);
    default: return tg_v3(0, 0, 0);
    }
}

tg_vec3 tgi_far_irradiance(const tg_vec3 sh[9], tg_vec3 n, int has_ao, tg_real ao, int has_bent, tg_vec3 bent,
                           int mode)
{
    if (has_bent && mode != TG_FAR_OPEN) n = bent;
    if (!has_ao) ao = TG_ONE;
    if (mode == TG_FAR_CUBE_F0) return tgi_sh9_irradiance_f0(sh, n, ao);
    if (mode == TG_FAR_OPEN || !has_ao) return tgi_sh9_irradiance(sh, n);
    return tgi_sh9_irradiance_bent_cone(sh, n, ao);
}

void tgi_far_rows(const tgi_gview *g, const tg_vec3 sh[9], const tgi_gresult *res, int mode,
                  const tgi_rgb *out, int y0, int y1)
{
    int has_ao = res && res->ao, has_bent = has_ao && tgi_gr_has_bent(res);
    int x, y;
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            size_t i = tgi_gv_index(g, x, y);
            if (tgi_gv_is_sky(g, i)) { tgi_rgb_set(out, i, tg_v3(0, 0, 0)); continue; }
            tgi_rgb_set(out, i, tgi_far_irradiance(sh, tgi_gv_normal(g, i), has_ao, has_ao ? tgi_gr_ao(res, i) : TG_ONE,
                                                   has_bent, has_bent ? tgi_gr_bent(res, i) : tg_v3(0, 0, 0), mode));
        }
}

#endif /* !TG_NO_ENVIRONMENT */
