/* SPDX-License-Identifier: MIT */
/*
 * sampling.c - deterministic low-discrepancy sample patterns for the AO
 * techniques and the reference (see sampling.h).
 */
#include "sampling.h"

#if !(TG_NO_TECHNIQUES && TG_NO_REFERENCE) /* used by the techniques and the reference only (tinygi.h "FEATURE SWITCHES") */

/* 4x4 Bayer (ordered-dither) matrix: consecutive values are far apart. */
static const uint8_t bayer4[16] = { 0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5 };

void tgi_ao_rotations(tgi_ao_rot rot[16])
{
    int k;
    for (k = 0; k < 16; k++) {
        tg_real a = tg_mul(TG_TWO_PI, tg_ratio(2 * bayer4[k] + 1, 32));
        rot[k].c = tg_cos(a);
        rot[k].s = tg_sin(a);
        /* a second, decorrelated order for the jitter */
        rot[k].jitter = tg_ratio(2 * ((bayer4[k] * 7 + 5) & 15) + 1, 32);
    }
}

void tgi_ao_circle(tg_real span, int n, tg_vec3 dirs[])
{
    int k;
    for (k = 0; k < n; k++) {
        tg_real a = tg_mul(span, tg_ratio(k, n));
        dirs[k] = tg_v3(tg_cos(a), tg_sin(a), 0);
    }
}

tg_real tgi_ao_golden_frac(int i)
{
    /* i * 2^32 / phi, wrapped: the fractional part of i / phi in 32 bits
     * (Knuth's multiplicative hash constant 2654435769 = 2^32 / phi). */
    uint32_t u = (uint32_t)i * 2654435769u;
    return tg_ratio((int32_t)(u >> 16), 65536);
}

tg_real tgi_ao_radical2(int i)
{
    uint32_t u = (uint32_t)i, r = 0;
    int b;
    for (b = 0; b < 16; b++) { r = (r << 1) | (u & 1u); u >>= 1; }
    return tg_ratio((int32_t)r, 65536);
}

void tgi_ao_disk(int i, int n, tg_real *x, tg_real *y)
{
    tg_real r = tg_sqrt(tg_ratio(2 * i + 1, 2 * n));
    tg_real a = tg_mul(TG_TWO_PI, tgi_ao_golden_frac(i));
    *x = tg_mul(r, tg_cos(a));
    *y = tg_mul(r, tg_sin(a));
}

tg_vec3 tgi_ao_hemi_cosine(int i, int n)
{
    tg_real x, y, r2;
    tgi_ao_disk(i, n, &x, &y);
    r2 = tg_add(tg_sqr(x), tg_sqr(y));
    return tg_v3(x, y, tg_sqrt(tg_sub(TG_ONE, tg_min(r2, TG_ONE)))); /* Malley, RTR sec. 11.3.4 */
}

tg_vec3 tgi_ao_hemi_uniform(int i, int n)
{
    tg_real z = tg_ratio(2 * i + 1, 2 * n);
    tg_real r = tg_sqrt(tg_sub(TG_ONE, tg_sqr(z)));
    tg_real a = tg_mul(TG_TWO_PI, tgi_ao_golden_frac(i));
    return tg_v3(tg_mul(r, tg_cos(a)), tg_mul(r, tg_sin(a)), z);
}

void tgi_ao_basis(tg_vec3 n, tg_vec3 *t, tg_vec3 *b)
{
    tg_real sign = n.z >= 0 ? TG_ONE : TG_R(-1.0f);
    tg_real a = tg_div(TG_R(-1.0f), tg_add(sign, n.z)); /* |sign + n.z| >= 1 */
    tg_real bb = tg_mul(tg_mul(n.x, n.y), a);
    *t = tg_v3(tg_add(TG_ONE, tg_mul(tg_mul(sign, tg_sqr(n.x)), a)), tg_mul(sign, bb), tg_neg(tg_mul(sign, n.x)));
    *b = tg_v3(bb, tg_add(sign, tg_mul(tg_sqr(n.y), a)), tg_neg(n.y));
}

#endif /* !(TG_NO_TECHNIQUES && TG_NO_REFERENCE) */
