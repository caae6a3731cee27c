/* SPDX-License-Identifier: MIT */
/*
 * ssdo.c - screen-space directional occlusion with one indirect bounce
 * (Ritschel et al. 2009 sec. 3).  See ssdo.h.
 */
#include "ssdo.h"
#include "sampling.h"
#include "../light/sh.h"
#include "../light/direct.h"
#include <string.h>

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

/* (far and light left out: all zero, absent planes as tgi_rgb_none) */
static const tgi_ssdo_params ssdo_defaults = { .samples = 16, .radius = TG_ONE, .bias = TG_AO_DEFAULT_BIAS, .bounce = TG_ONE,
    .env_sh9 = NULL, .lights = NULL, .light_count = 0, .light_steps = 4 };

void tgi_ssdo_defaults(tgi_ssdo_params *p)
{
    *p = ssdo_defaults;
}

/* Lights with directional occlusion: each light is one more sample
 * direction, towards it, marched in screen space (see ssdo.h). */
static tg_vec3 lights_do(const tgi_ssdo_params *p, const tgi_gview *g, tg_vec3 pv, tg_vec3 pw, tg_vec3 nw,
                         tg_real eps, tg_real jitter)
{
    tg_vec3 e = tg_v3(0, 0, 0);
    int l, m, steps = p->light_steps < 1 ? 1 : p->light_steps;
    for (l = 0; l < p->light_count; l++) {
        const tgi_light *li = &p->lights[l];
        tg_vec3 el = tgi_direct_irradiance(li, pw, nw), to_light, lv;
        int blocked = 0;
        if (el.x <= 0 && el.y <= 0 && el.z <= 0) continue;
        to_light = li->type == TG_LIGHT_DIRECTIONAL ? tgi_v3_neg(li->dir) : tgi_v3_sub(li->pos, pw);
        lv = tgi_ao_dir_to_view(g->camera, tgi_v3_normalize_or(to_light, nw));
        for (m = 0; m < steps && !blocked; m++) {
            tg_real lambda = tg_div(tg_mul(p->radius, tg_add(tg_from_int(m), jitter)), tg_from_int(steps));
            blocked = tgi_ao_sample_blocked(g, pv, tgi_v3_add(pv, tgi_v3_scale(lv, lambda)), eps, tg_ldexp(p->radius, 1));
        }
        if (!blocked) e = tgi_v3_add(e, el);                 /* E_l V_ss(l) */
    }
    return e;
}

typedef struct ssdo_sums {
    tg_real vis_cos, all_cos;
    tg_vec3 bent, far, near;
} ssdo_sums;

/* Ritschel sec. 3, indirect: the occluder's pixel j as a sender patch. */
static tg_vec3 sender(const tgi_gview *g, const tgi_rgb *radiance, tg_vec3 pv, tg_vec3 nv, int qx, int qy, tg_real area)
{
    int j = (int)tgi_gv_index(g, qx, qy);
    tg_vec3 q = tgi_ao_unproject(g->camera, qx, qy, tgi_gv_depth(g, j)), d = tgi_v3_sub(q, pv), ns, l;
    tg_real d2 = tgi_v3_dot(d, d), inv_d, cos_s, cos_r, k;
    if (d2 <= 0) return tg_v3(0, 0, 0);
    inv_d = tg_rsqrt(d2);
    ns = tgi_ao_normal_view(g, j);
    cos_s = tg_neg(tg_mul(tgi_v3_dot(ns, d), inv_d));       /* sender faces the receiver */
    cos_r = tg_mul(tgi_v3_dot(nv, d), inv_d);               /* sender above the receiver's plane */
    if (cos_s <= 0 || cos_r <= 0) return tg_v3(0, 0, 0);
    d2 = tg_max(d2, tg_mul(area, TG_INV_PI));               /* d clamped (Ritschel sec. 3) */
    k = tg_div(tg_mul(tg_mul(area, cos_s), cos_r), d2);    /* A_s cos(theta_s) cos(theta_r) / d^2 */
    l = tgi_rgb_get(radiance, j);
    return tg_v3(tg_mul(l.x, k), tg_mul(l.y, k), tg_mul(l.z, k));
}

static void ssdo_pixel(const tgi_ssdo_params *p, const tgi_gview *g, const tgi_rgb *radiance, const tgi_gresult *out, const tg_vec3 *dirs,
                       const tg_real *steps, int n, const tgi_ao_rot *rot, int x, int y)
{
    int i = (int)tgi_gv_index(g, x, y), k;
    const tgi_view *v = g->camera;
    tg_vec3 pv = tgi_ao_unproject(v, x, y, tgi_gv_depth(g, i)), nv = tgi_ao_normal_view(g, i), t, b;
    tg_real bias = tg_mul(p->bias, p->radius);
    tg_real area = tg_div(tg_mul(tg_mul(TG_PI, tg_sqr(p->radius)), p->bounce), tg_from_int(n)); /* A_s = pi r^2 / N */
    tg_real dw = tg_div(TG_TWO_PI, tg_from_int(n));                                           /* Delta w = 2 pi / N */
    int want_far = p->env_sh9 && tgi_rgb_present(&p->far), want_near = tgi_gr_has_near(out) && tgi_rgb_present(radiance);
    ssdo_sums sum;
    memset(&sum, 0, sizeof sum);
    tgi_ao_basis(nv, &t, &b);
    for (k = 0; k < n; k++) {
        tg_vec3 l = tgi_ao_rotate_z(dirs[k], rot->c, rot->s), w = tgi_ao_from_local(l, t, b, nv);
        tg_real lambda = tg_mul(p->radius, tg_add(steps[k], tg_ldexp(rot->jitter, -5)));
        tg_vec3 s = tgi_v3_add(pv, tgi_v3_scale(w, lambda));
        int qx, qy, blocked = tgi_ao_sample_blocked_at(g, pv, s, bias, tg_ldexp(p->radius, 1), &qx, &qy); /* below the surface */
        sum.all_cos = tg_add(sum.all_cos, l.z);
        if (!blocked) {
            sum.vis_cos = tg_add(sum.vis_cos, l.z);
            sum.bent = tgi_v3_add(sum.bent, tgi_v3_scale(w, l.z));
            if (want_far)                                   /* L_in(w) V(w) cos(theta) */
                sum.far = tgi_v3_add(sum.far, tgi_v3_scale(tgi_sh9_radiance(p->env_sh9, tgi_ao_dir_to_world(v, w)), l.z));
        } else if (want_near) {
            sum.near = tgi_v3_add(sum.near, sender(g, radiance, pv, nv, qx, qy, area));
        }
    }
    tgi_gr_set_ao(out, i, sum.all_cos > 0 ? tg_saturate(tg_div(sum.vis_cos, sum.all_cos)) : TG_ONE);
    tgi_ao_write_bent_view(g, out, i, sum.bent);
    if (want_far) {
        tgi_rgb_set(&p->far, i, tg_v3(tg_mul(sum.far.x, dw), tg_mul(sum.far.y, dw), tg_mul(sum.far.z, dw)));
    }
    if (want_near) tgi_gr_set_near(out, i, sum.near);
    if (tgi_rgb_present(&p->light) && p->lights && p->light_count > 0) {
        tg_vec3 nw = tgi_gv_normal(g, i);
        tg_vec3 pw = tgi_v3_add(v->eye, tgi_ao_dir_to_world(v, pv));
        tg_vec3 e = lights_do(p, g, pv, pw, nw, bias, rot->jitter);
        tgi_rgb_set(&p->light, i, e);
    }
}

void tgi_ssdo_rows(const tgi_ssdo_params *p, const tgi_gview *g, const tgi_rgb *radiance, const tgi_gresult *out, int y0, int y1)
{
    tg_vec3 dirs[TG_AO_MAX_SAMPLES];
    tg_real steps[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int n = tgi_ao_count(p->samples), k, x, y;
    for (k = 0; k < n; k++) {
        dirs[k] = tgi_ao_hemi_uniform(k, n);               /* uniform over the hemisphere (Ritschel sec. 3) */
        /* lambda in (0, 1]: van der Corput, decorrelated from the spiral; +1/32 jitter per pixel */
        steps[k] = tg_add(tg_mul(tgi_ao_radical2(k), TG_R(0.9375f)), TG_R(0.03125f));
    }
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            tgi_ao_write_open_far(g, out, i, &p->far, p->env_sh9);
            if (tgi_rgb_present(&p->light)) { tgi_rgb_set(&p->light, i, tg_v3(0, 0, 0)); }
            if (tgi_gv_is_sky(g, i)) continue;
            if (p->radius <= 0) {                               /* nothing occludes */
                if (tgi_rgb_present(&p->light) && p->lights && p->light_count > 0) {
                    tg_vec3 pv = tgi_ao_unproject(g->camera, x, y, tgi_gv_depth(g, i)), nw = tgi_gv_normal(g, i);
                    tg_vec3 e = lights_do(p, g, pv, tgi_v3_add(g->camera->eye, tgi_ao_dir_to_world(g->camera, pv)), nw, 0, 0);
                    tgi_rgb_set(&p->light, i, e);
                }
                continue;
            }
            ssdo_pixel(p, g, radiance, out, dirs, steps, n, tgi_ao_rot_at(rot, x, y), x, y);
        }
}

#endif /* !TG_NO_TECHNIQUES */
