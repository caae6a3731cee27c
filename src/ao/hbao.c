/* SPDX-License-Identifier: MIT */
/*
 * hbao.c - horizon-based AO without the cosine, linear falloff (RTR eq.
 * 11.16-11.17).  See hbao.h.
 */
#include "hbao.h"
#include "sampling.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

static const tgi_hbao_params hbao_defaults = { .directions = 8, .steps = 6, .radius = TG_ONE, .angle_bias = TG_R(0.05f) };

void tgi_hbao_defaults(tgi_hbao_params *p)
{
    *p = hbao_defaults;
}

/* Occlusion (sin h - sin t) W of one screen direction (sdx, sdy). */
static tg_real direction_occlusion(const tgi_hbao_params *p, const tgi_gview *g, tg_vec3 pv, tg_vec3 nv,
                                   tg_vec3 view_dir, tg_real sdx, tg_real sdy, tg_real r_px,
                                   tg_real jitter, int x, int y)
{
    const tgi_view *v = g->camera;
    tg_vec3 d3 = tg_v3(sdx, tg_neg(sdy), 0);                /* screen y is down, view y up */
    tg_vec3 axis = tgi_v3_cross(d3, view_dir), tangent;
    tg_real sin_t, max_sin, occlusion = 0;
    tg_real above = tg_add(tg_ldexp(pv.z, -10), tg_mul(p->radius, TG_R(0.005f)));
    int s;
    tgi_ao_rays rays = TGI_AO_RAYS_NONE;
    /* tangent: the tangent plane's line in the slice (eye, screen direction) */
    tangent = tgi_v3_normalize_or(tgi_v3_cross(axis, nv), d3);
    if (tgi_v3_dot(tangent, d3) < 0) tangent = tgi_v3_neg(tangent);
    sin_t = tg_neg(tangent.z);                              /* elevation towards the viewer */
    max_sin = tg_add(sin_t, p->angle_bias);
    for (s = 0; s < p->steps; s++) {
        /* (s + jitter) r_px >= 0: tg_div's quotient without its tests */
        tg_real t_px = tgi_div_nonneg(tg_mul(tg_add(tg_from_int(s), jitter), r_px), tg_from_int(p->steps));
        int qx, qy, j;
        tg_vec3 h;
        tg_real z, dist2, dist, sin_h;
        if (t_px < TG_ONE) continue;
        qx = tg_to_int(tg_add(tg_add(tg_from_int(x), TG_R(0.5f)), tg_mul(sdx, t_px)));
        qy = tg_to_int(tg_add(tg_add(tg_from_int(y), TG_R(0.5f)), tg_mul(sdy, t_px)));
        if (qx < 0 || qy < 0 || qx >= g->width || qy >= g->height) break;
        j = (int)tgi_gv_index(g, qx, qy);
        if (tgi_gv_is_sky(g, j)) continue;
        z = tgi_gv_depth(g, j);
        tgi_ao_rays_at(v, &rays, qx, qy);
        h = tgi_v3_sub(tg_v3(tg_mul(rays.kx, z), tg_mul(rays.ky, z), z), pv);   /* tgi_ao_unproject's products */
        dist2 = tgi_v3_dot(h, h);
        if (dist2 >= tg_sqr(p->radius) || dist2 <= 0) continue;
        if (tgi_v3_dot(h, nv) <= above) continue;           /* on or under the tangent plane: no horizon */
        dist = tg_sqrt(dist2);
        sin_h = tg_div(tg_neg(h.z), dist);
        if (sin_h <= max_sin) continue;
        /* RTR eq. 11.17, W(r) = 1 - r / radius: each rise of the horizon is
         * weighted by the falloff of the point that raises it (Bavoil et al.'s
         * accumulation; the sum telescopes to (sin h - sin t) W when a single
         * point defines the horizon) */
        occlusion = tg_add(occlusion, tg_mul(tg_sub(sin_h, max_sin), tg_sub(TG_ONE, tg_div(dist, p->radius))));
        max_sin = sin_h;
    }
    return occlusion;
}

void tgi_hbao_rows(const tgi_hbao_params *p, const tgi_gview *g, const tgi_gresult *out, int y0, int y1)
{
    tg_vec3 dirs[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int nd = tgi_ao_count(p->directions), k, x, y;
    tgi_ao_circle(TG_TWO_PI, nd, dirs);
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            const tgi_ao_rot *r = tgi_ao_rot_at(rot, x, y);
            tg_vec3 pv, nv, vd;
            tg_real r_px, occ = 0;
            tgi_ao_write_open(g, out, i);
            if (tgi_gv_is_sky(g, i) || p->radius <= 0 || p->steps < 1) continue;
            r_px = tgi_ao_view_at(g, x, y, i, p->radius, &pv, &nv, &vd);
            if (r_px < TG_ONE) continue;                     /* the radius covers less than a pixel */
            for (k = 0; k < nd; k++) {
                tg_vec3 sd = tgi_ao_rotate_z(dirs[k], r->c, r->s);
                occ = tg_add(occ, direction_occlusion(p, g, pv, nv, vd, sd.x, sd.y, r_px, r->jitter, x, y));
            }
            tgi_gr_set_ao(out, i, tg_saturate(tg_sub(TG_ONE, tg_div(occ, tg_from_int(nd))))); /* RTR eq. 11.17 */
        }
}

#endif /* !TG_NO_TECHNIQUES */
