/* SPDX-License-Identifier: MIT */
/*
 * gtao.c - cosine-weighted horizon-based AO and bent normal in view-vector
 * slices (RTR eq. 11.18, Jimenez et al. 2016).  See gtao.h.
 */
#include "gtao.h"
#include "sampling.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

static const tgi_gtao_params gtao_defaults = { .slices = 4, .steps = 8, .radius = TG_ONE };

void tgi_gtao_defaults(tgi_gtao_params *p)
{
    *p = gtao_defaults;
}

typedef tgi_ao_slice_pixel gtao_pixel;   /* ao.h: view position, normal, eye vector, radius in pixels */

/* Largest cos(angle to the view vector) of the samples along screen
 * direction (sdx, sdy); -1 when none is within the radius. */
static tg_real horizon_cos(const tgi_gtao_params *p, const tgi_gview *g, const gtao_pixel *px,
                           tg_real sdx, tg_real sdy)
{
    tg_real rs = tg_ldexp(p->radius, px->shift), best = TG_R(-1.0f), r2 = tg_sqr(rs);
    tg_real above = tg_add(tg_ldexp(px->pv.z, px->shift - 10), tg_mul(rs, TG_R(0.005f)));
    tg_vec3 h;
    int s;
    for (s = 0; s < p->steps; s++) {
        int j, got = tgi_ao_slice_sample(g, px, s, p->steps, sdx, sdy, &h, &j);
        tg_real d2;
        if (got < 0) break;
        if (got == 0) continue;
        d2 = tgi_v3_dot(h, h);
        if (d2 >= r2 || d2 <= 0) continue;
        if (tgi_v3_dot(h, px->nv) <= above) continue;      /* under the tangent plane: clamped anyway */
        /* (h.v) / |h| by one rsqrt: a signed squared cosine would save it but
         * loses Q16.16 bits for the nearest samples (|h|^2 ~ 1e-4) */
        best = tg_max(best, tg_mul(tgi_v3_dot(h, px->vd), tg_rsqrt(d2)));
    }
    return best;
}

/* a(h): the inner integral of eq. 11.18 from 0 to h (either sign of h). */
static tg_real inner_arc(tg_real h, tg_real gamma, tg_real cos_g, tg_real sin_g)
{
    tg_real t = tg_sub(tg_add(cos_g, tg_mul(tg_ldexp(h, 1), sin_g)), tg_cos(tg_sub(tg_ldexp(h, 1), gamma)));
    return tg_ldexp(t, -2);
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

/* One slice: adds its visibility to *vis and its bent vector to *bent. */
static void slice(const tgi_gtao_params *p, const tgi_gview *g, const gtao_pixel *px, tg_real sdx,
                  tg_real sdy, tg_real *vis, tg_real *open, tg_vec3 *bent)
{
    tgi_ao_slice sl;
    tg_vec3 dir;
    tg_real len, gamma, cos_g, sin_g, h0, h1, bs, bc;
    if (!tgi_ao_slice_frame(px->nv, px->vd, sdx, sdy, &sl)) return;
    dir = sl.dir; len = sl.len; gamma = sl.gamma; cos_g = sl.cos_g; sin_g = sl.sin_g;
    h1 = tg_acos(horizon_cos(p, g, px, sdx, sdy));
    h0 = tg_neg(tg_acos(horizon_cos(p, g, px, tg_neg(sdx), tg_neg(sdy))));
    h1 = tg_add(gamma, tg_min(tg_sub(h1, gamma), TG_HALF_PI));            /* clamp to the normal's hemisphere */
    h0 = tg_add(gamma, tg_max(tg_sub(h0, gamma), tg_neg(TG_HALF_PI)));
    /* RTR eq. 11.18, inner integral on both sides, weighted by |projected normal| */
    *vis = tg_add(*vis, tg_mul(len, tg_add(inner_arc(h0, gamma, cos_g, sin_g), inner_arc(h1, gamma, cos_g, sin_g))));
    /* the same slice with open horizons (gamma -+ pi/2): len (cos g + g sin g) */
    *open = tg_add(*open, tg_mul(len, tg_add(cos_g, tg_mul(gamma, sin_g))));
    /* bent normal in the slice: F(h1) + F(h0) - 2 F(0), F_s(0) = -2/3 sin g, F_c(0) = -cos g / 3 */
    bs = tg_add(tg_add(bent_fs(h1, cos_g, sin_g), bent_fs(h0, cos_g, sin_g)), tg_mul(sin_g, TG_R(1.333333333f)));
    bc = tg_add(tg_add(bent_fc(h1, cos_g, sin_g), bent_fc(h0, cos_g, sin_g)), tg_mul(cos_g, TG_R(0.666666667f)));
    *bent = tgi_v3_add(*bent, tgi_v3_scale(tgi_v3_add(tgi_v3_scale(dir, bs), tgi_v3_scale(px->vd, bc)), len));
}

void tgi_gtao_rows(const tgi_gtao_params *p, const tgi_gview *g, const tgi_gresult *out, int y0, int y1)
{
    tg_vec3 dirs[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int ns = tgi_ao_count(p->slices), k, x, y;
    int shift = tgi_ao_unit_shift(p->radius);
    tgi_ao_circle(TG_PI, ns, dirs);              /* slice angles over pi */
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            const tgi_ao_rot *r = tgi_ao_rot_at(rot, x, y);
            gtao_pixel px;
            tg_real vis = 0, open = 0;
            tg_vec3 bent = tg_v3(0, 0, 0);
            if (!tgi_ao_slice_pixel_at(g, out, x, y, i, p->radius, p->steps, r->jitter, shift, &px)) continue;
            for (k = 0; k < ns; k++) {
                tg_vec3 sd = tgi_ao_rotate_z(dirs[k], r->c, r->s);
                slice(p, g, &px, sd.x, sd.y, &vis, &open, &bent);
            }
            /* outer integral: the slice quadrature as a ratio to the same
             * quadrature of the open hemisphere (exact 1 on any plane) */
            tgi_gr_set_ao(out, i, open > 0 ? tg_saturate(tg_div(vis, open)) : TG_ONE);
            tgi_ao_write_bent_view(g, out, i, bent);
        }
}

#endif /* !TG_NO_TECHNIQUES */
