/* SPDX-License-Identifier: MIT */
/*
 * bentcone.c - screen-space bent normals, bent cones and the
 * cone-restricted environment lookup (Klehm et al. 2011 sec. 3).  See
 * bentcone.h.
 */
#include "bentcone.h"
#include "sampling.h"
#include "../light/sh.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

/* (far left out: all zero, an absent plane as tgi_rgb_none) */
static const tgi_bentcone_params bentcone_defaults = { .samples = 8, .steps = 3, .radius = TG_ONE, .bias = TG_AO_DEFAULT_BIAS,
    .env_sh9 = NULL };

void tgi_bentcone_defaults(tgi_bentcone_params *p)
{
    *p = bentcone_defaults;
}

tg_real tgi_bentcone_aperture(tg_real mean_length)
{
    tg_real k = tg_max(0, tg_sub(tg_ldexp(mean_length, 1), TG_ONE));
    return tg_mul(tg_saturate(tg_sub(TG_ONE, k)), TG_HALF_PI);     /* Klehm sec. 3.2, C(i) */
}

tg_vec3 tgi_bentcone_far(const tg_vec3 sh[9], tg_vec3 bent, tg_real cone, tg_real ao, tg_vec3 n)
{
    tg_real s = tg_sin(cone), s2 = tg_sqr(s), geo = tg_max(0, tgi_v3_dot(bent, n));
    tg_vec3 e;
    if (s2 < TG_R(0.001f))                                   /* the limit a -> 0: pi L(N) */
        e = tgi_v3_scale(tgi_sh9_radiance(sh, bent), TG_PI);
    else                                                     /* t int_cone L (w . N) dw, t = 1 / sin^2 a */
        e = tgi_v3_scale(tgi_sh9_irradiance_in_cone(sh, bent, tg_cos(cone)), tg_div(TG_ONE, s2));
    return tgi_v3_scale(e, tg_mul(ao, geo));                  /* sec. 3.4 geometric term, times AO */
}

static void bentcone_pixel(const tgi_bentcone_params *p, const tgi_gview *g, const tgi_gresult *out, const tg_vec3 *dirs, int n,
                           const tgi_ao_rot *rot, int x, int y)
{
    int i = (int)tgi_gv_index(g, x, y), k, m, open = 0, steps = p->steps < 1 ? 1 : p->steps;
    const tgi_view *v = g->camera;
    tg_vec3 pv = tgi_ao_unproject(v, x, y, tgi_gv_depth(g, i)), nv = tgi_ao_normal_view(g, i), t, b;
    tg_vec3 sum = tg_v3(0, 0, 0), nw = tgi_gv_normal(g, i), bent_w;
    tg_real bias = tg_mul(p->bias, p->radius), mean_len, cone, ao;
    tgi_ao_basis(nv, &t, &b);
    for (k = 0; k < n; k++) {
        tg_vec3 w = tgi_ao_from_local(tgi_ao_rotate_z(dirs[k], rot->c, rot->s), t, b, nv);
        int blocked = 0;
        for (m = 0; m < steps && !blocked; m++) {           /* ray-march points along w */
            tg_real lambda = tg_div(tg_mul(p->radius, tg_add(tg_from_int(m), rot->jitter)), tg_from_int(steps));
            blocked = tgi_ao_sample_blocked(g, pv, tgi_v3_add(pv, tgi_v3_scale(w, lambda)), bias, tg_ldexp(p->radius, 1));
        }
        if (blocked) continue;
        open++;
        sum = tgi_v3_add(sum, w);
    }
    ao = tg_ratio(open, n);                                 /* Klehm eq. 3 */
    tgi_gr_set_ao(out, i, ao);
    if (open == 0) {
        bent_w = nw;
        cone = 0;
    } else {
        tg_vec3 mean = tgi_v3_scale(sum, tg_div(TG_ONE, tg_from_int(open))); /* N_ss, sec. 3.1 */
        mean_len = tgi_v3_length(mean);
        cone = tgi_bentcone_aperture(mean_len);
        bent_w = tgi_v3_normalize_or(tgi_ao_dir_to_world(v, mean), nw);
    }
    if (tgi_gr_has_bent(out)) tgi_gr_set_bent(out, i, bent_w);
    if (tgi_gr_has_cone(out)) tgi_gr_set_cone(out, i, cone);
    if (p->env_sh9 && tgi_rgb_present(&p->far)) {
        tg_vec3 e = tgi_bentcone_far(p->env_sh9, bent_w, cone, ao, nw);
        tgi_rgb_set(&p->far, i, e);
    }
}

void tgi_bentcone_rows(const tgi_bentcone_params *p, const tgi_gview *g, const tgi_gresult *out, int y0, int y1)
{
    tg_vec3 dirs[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int n = tgi_ao_count(p->samples), k, x, y;
    for (k = 0; k < n; k++) dirs[k] = tgi_ao_hemi_uniform(k, n);
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            tgi_ao_write_open_far(g, out, i, &p->far, p->env_sh9);
            if (tgi_gv_is_sky(g, i) || p->radius <= 0) continue;
            bentcone_pixel(p, g, out, dirs, n, tgi_ao_rot_at(rot, x, y), x, y);
        }
}

#endif /* !TG_NO_TECHNIQUES */
