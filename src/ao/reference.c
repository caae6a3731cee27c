/* SPDX-License-Identifier: MIT */
/*
 * reference.c - ray-traced AO, bent normal and one-bounce near-field
 * irradiance from G-buffer positions (see reference.h).  Slow on purpose and
 * exact up to its sample count.
 */
#include "reference.h"
#include "sampling.h"
#include "../light/sh.h"
#include "../light/shadowmap.h"

#if !TG_NO_REFERENCE /* the whole file is left out with TG_NO_REFERENCE=1 (tinygi.h "FEATURE SWITCHES") */

void tgi_reference_defaults(tgi_reference_params *p)
{
    p->bvh = 0;
    p->tri_nrm = 0;
    p->samples = 256;
    p->radius = TG_ONE;
    p->radiance = 0;
    p->user = 0;
}

/* Unit normal at a hit, facing back along the ray. */
static tg_vec3 hit_normal(const tgi_reference_params *p, const tgi_ray_hit *h, tg_vec3 d)
{
    const tg_vec3 *v = p->bvh->tri_pos + 3 * (size_t)h->tri;
    tg_vec3 n;
    if (p->tri_nrm) {
        const tg_vec3 *vn = p->tri_nrm + 3 * (size_t)h->tri;
        tg_real w0 = tg_sub(tg_sub(TG_ONE, h->u), h->v);
        n = tgi_v3_add(tgi_v3_add(tgi_v3_scale(vn[0], w0), tgi_v3_scale(vn[1], h->u)), tgi_v3_scale(vn[2], h->v));
    } else {
        tg_vec3 e1 = tgi_v3_sub(v[1], v[0]), e2 = tgi_v3_sub(v[2], v[0]);
        tg_real m = tg_max(tg_max(tg_abs(e1.x), tg_abs(e1.y)), tg_abs(e1.z));
        m = tg_max(m, tg_max(tg_max(tg_abs(e2.x), tg_abs(e2.y)), tg_abs(e2.z)));
        if (m > 0) { /* scale edges to ~unit so the cross product cannot saturate */
            e1 = tgi_v3_scale(e1, tg_div(TG_ONE, m));
            e2 = tgi_v3_scale(e2, tg_div(TG_ONE, m));
        }
        n = tgi_v3_cross(e1, e2);
    }
    n = tgi_v3_normalize_or(n, tgi_v3_neg(d));
    return tgi_v3_dot(n, d) > 0 ? tgi_v3_neg(n) : n;
}

/* L_o at a hit seen in the current view's radiance buffer, 0 when hidden. */
static tg_vec3 radiance_from_view(const tgi_gview *g, const tgi_rgb *radiance, tg_vec3 pw)
{
    const tgi_view *v = g->camera;
    tg_vec3 pv = tgi_ao_dir_to_view(v, tgi_v3_sub(pw, v->eye));
    int j = tgi_ao_project_index(v, pv);
    tg_real tol;
    if (j < 0 || tgi_gv_is_sky(g, j) || !tgi_rgb_present(radiance)) return tg_v3(0, 0, 0);
    tol = tg_add(tg_mul(pv.z, TG_R(0.01f)), TG_R(0.00390625f));
    if (tg_abs(tg_sub(tgi_gv_depth(g, j), pv.z)) > tol) return tg_v3(0, 0, 0);
    return tgi_rgb_get(radiance, j);
}

static void reference_pixel(const tgi_reference_params *p, const tgi_gview *g, const tgi_rgb *radiance, const tgi_gresult *out, const tgi_ao_rot *rot,
                            int x, int y)
{
    int i = (int)tgi_gv_index(g, x, y), s, n = p->samples > 0 ? p->samples : 1, open = 0;
    int want_near = tgi_gr_has_near(out);
    const tgi_view *v = g->camera;
    tg_vec3 nrm = tgi_gv_normal(g, i), t, b, o, pv;
    tg_vec3 bent = tg_v3(0, 0, 0), near = tg_v3(0, 0, 0);
    tg_real eps, tmax = p->radius > 0 ? p->radius : 0;
    pv = tgi_ao_unproject(v, x, y, tgi_gv_depth(g, i));
    /* offset along the normal: the reconstructed position's error bound
     * (tgi_shadow_gbuffer_error: about 1/20 pixel, large in a small image)
     * plus 2^-10 of the depth + 2^-10 */
    eps = tg_add(tg_mul(tgi_gv_depth(g, i), tgi_shadow_gbuffer_error(v)),
                 tg_add(tg_ldexp(tgi_gv_depth(g, i), -10), TG_R(0.0009765625f)));
    o = tgi_v3_add(tgi_v3_add(v->eye, tgi_ao_dir_to_world(v, pv)), tgi_v3_scale(nrm, eps));
    tgi_ao_basis(nrm, &t, &b);
    for (s = 0; s < n; s++) {
        tg_vec3 l = tgi_ao_rotate_z(tgi_ao_hemi_cosine(s, n), rot->c, rot->s);
        tg_vec3 d = tgi_ao_from_local(l, t, b, nrm);     /* unit: a unit vector in an orthonormal frame */
        if (want_near) {
            tgi_ray_hit h;
            if (!tgi_bvh_closest(p->bvh, o, d, tmax, &h)) { open++; bent = tgi_v3_add(bent, d); continue; }
            {
                tg_vec3 hp = tgi_v3_add(o, tgi_v3_scale(d, h.t)), lo;
                lo = p->radiance ? p->radiance(p->user, h.tri, hp, hit_normal(p, &h, d))
                                 : radiance_from_view(g, radiance, hp);
                near = tgi_v3_add(near, lo);
            }
        } else if (!tgi_bvh_occluded(p->bvh, o, d, tmax)) {
            open++;
            bent = tgi_v3_add(bent, d);
        }
    }
    tgi_gr_set_ao(out, i, tg_ratio(open, n));          /* RTR eq. 11.8 / 11.14, cosine-importance sampled */
    if (tgi_gr_has_cone(out))                           /* the cone of a cosine-weighted AO (sh.h) */
        tgi_gr_set_cone(out, i, tgi_cone_angle_from_ao(tgi_gr_ao(out, i)));
    if (tgi_gr_has_bent(out)) {                         /* RTR eq. 11.10 */
        tg_vec3 bn = tgi_v3_normalize_or(bent, nrm);
        tgi_gr_set_bent(out, i, bn);
    }
    if (want_near) {                                    /* E = pi / N sum L_o (pdf cos / pi) */
        tg_real k = tg_div(TG_PI, tg_from_int(n));
        tgi_gr_set_near(out, i, tg_v3(tg_mul(near.x, k), tg_mul(near.y, k), tg_mul(near.z, k)));
    }
}

void tgi_reference_rows(const tgi_reference_params *p, const tgi_gview *g, const tgi_rgb *radiance, const tgi_gresult *out, int y0, int y1)
{
    tgi_ao_rot rot[16];
    int x, y;
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            if (tgi_gv_is_sky(g, i) || !p->bvh) { tgi_ao_write_open(g, out, i); continue; }
            reference_pixel(p, g, radiance, out, tgi_ao_rot_at(rot, x, y), x, y);
        }
}

#endif /* !TG_NO_REFERENCE */
