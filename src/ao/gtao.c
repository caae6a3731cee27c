/* SPDX-License-Identifier: MIT */
/*
 * gtao.c - cosine-weighted horizon-based AO and bent normal in view-vector
 * slices (RTR eq. 11.18, Jimenez et al. 2016).  See gtao.h.
 */
#include "gtao.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

static const tgi_gtao_params gtao_defaults = { .slices = 4, .steps = 8, .radius = TG_ONE };

void tgi_gtao_defaults(tgi_gtao_params *p)
{
    *p = gtao_defaults;
}

/* Largest cos(angle to the view vector) of the samples along screen
 * direction (sdx, sdy); -1 when none is within the radius. */
static tg_real horizon_cos(const tgi_gtao_params *p, const tgi_gview *g, const tgi_ao_slice_pixel *px,
                           tg_real sdx, tg_real sdy)
{
    tg_real best = TG_R(-1.0f), d2;
    tg_vec3 h;
    int s, j, got;
    tgi_ao_rays rays = TGI_AO_RAYS_NONE;
    for (s = 0; s < p->steps; s++) {
        got = tgi_ao_slice_sample(g, px, s, p->steps, sdx, sdy, &h, &d2, &j, &rays);
        if (got < 0) break;
        /* (h.v) / |h| by one rsqrt: a signed squared cosine would save it but
         * loses Q16.16 bits for the nearest samples (|h|^2 ~ 1e-4) */
        if (got) best = tg_max(best, tg_mul(tgi_v3_dot(h, px->vd), tg_rsqrt(d2)));
    }
    return best;
}

/* Antiderivatives of the slice bent-normal integrands (see gtao.h). */
static tg_real bent_fs(tg_real th, tg_real cos_g, tg_real sin_g)
{
    tg_real s = tg_sin(th), c = tg_cos(th);
    tg_real s3 = tg_mul(tg_sqr(s), s), c3 = tg_mul(tg_sqr(c), c);
    return tg_add(tg_mul(cos_g, tg_div(s3, TG_R(3.0f))), tg_mul(sin_g, tg_sub(tg_div(c3, TG_R(3.0f)), c)));
}
static tg_real bent_fc(tg_real th, tg_real cos_g, tg_real sin_g)
{
    tg_real s = tg_sin(th), c = tg_cos(th);
    tg_real s3 = tg_mul(tg_sqr(s), s), c3 = tg_mul(tg_sqr(c), c);
    return tg_div(tg_sub(tg_mul(sin_g, s3), tg_mul(cos_g, c3)), TG_R(3.0f));
}

/* One slice (a tgi_ao_slice_fn, ao.h): its two horizons, clamped to the
 * normal's hemisphere, and the inner integrals between them. */
static void gtao_slice(const void *tech, const tgi_gview *g, const tgi_ao_slice_pixel *px, const tgi_ao_slice *sl,
                       tg_real sdx, tg_real sdy, tgi_ao_slice_sum *sum)
{
    const tgi_gtao_params *p = (const tgi_gtao_params *)tech;
    tg_real gamma = sl->gamma, cos_g = sl->cos_g, sin_g = sl->sin_g, h0, h1;
    sum->vis = tgi_ao_slice_arc(sl, horizon_cos(p, g, px, sdx, sdy), horizon_cos(p, g, px, tg_neg(sdx), tg_neg(sdy)),
                                &h1, &h0);
    /* the same slice with open horizons (gamma -+ pi/2): cos g + g sin g */
    sum->open = tg_add(cos_g, tg_mul(gamma, sin_g));
    /* bent normal in the slice: F(h1) + F(h0) - 2 F(0), F_s(0) = -2/3 sin g, F_c(0) = -cos g / 3 */
    sum->bs = tg_add(tg_add(bent_fs(h1, cos_g, sin_g), bent_fs(h0, cos_g, sin_g)), tg_mul(sin_g, TG_R(1.333333333f)));
    sum->bc = tg_add(tg_add(bent_fc(h1, cos_g, sin_g), bent_fc(h0, cos_g, sin_g)), tg_mul(cos_g, TG_R(0.666666667f)));
}

void tgi_gtao_rows(const tgi_gtao_params *p, const tgi_gview *g, const tgi_gresult *out, int y0, int y1)
{
    const tgi_ao_slices t = { .slices = p->slices, .steps = p->steps, .radius = p->radius, .slice = gtao_slice, .tech = p };
    tgi_ao_slices_rows(&t, g, out, y0, y1);
}

#endif /* !TG_NO_TECHNIQUES */
