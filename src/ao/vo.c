/* SPDX-License-Identifier: MIT */
/*
 * vo.c - volumetric obscurance by line samples (Loos and Sloan sec. 4.1),
 * with the thickness model (4.3), normal clamping (4.4) and optional area
 * samples from depth moments (4.2).  See vo.h.
 */
#include "vo.h"
#include "sampling.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

static const tgi_vo_params vo_defaults = { .samples = 9, .radius = TG_ONE, .thickness = 0, .use_normal = 1, .area = 0 };

void tgi_vo_defaults(tgi_vo_params *p)
{
    *p = vo_defaults;
}

/* Integral over [lo, hi] of the visibility g: 1 for z <= z0, falling
 * linearly to 0 at z1, 0 beyond (a step when z0 == z1).  Loos and Sloan
 * sec. 4.1 (step) and 4.2: V_c(z_min, z_max) = z_max - z_min and
 * V_c(z_0, z_1, a, b) = a (z_1^2 - z_0^2) / 2 + b (z_1 - z_0). */
static tg_real visible_length(tg_real lo, tg_real hi, tg_real z0, tg_real z1)
{
    tg_real a0, a1, len;
    if (hi <= lo) return 0;
    a0 = tg_clamp(z0, lo, hi);
    len = tg_sub(a0, lo);                                   /* the constant part */
    a1 = tg_clamp(z1, lo, hi);
    if (a1 > a0 && z1 > z0)                                 /* the linear ramp, exact */
        len = tg_add(len, tg_div(tg_sub(tg_sqr(tg_sub(z1, a0)), tg_sqr(tg_sub(z1, a1))),
                                 tg_ldexp(tg_sub(z1, z0), 1)));
    return len;
}

/* Free length of one line [lo, hi] given the depth model [z0, z1] (unit
 * ball coordinates) and the thickness t (<= 0: infinitely thick). */
static tg_real free_length(tg_real lo, tg_real hi, tg_real z0, tg_real z1, tg_real t)
{
    tg_real f = visible_length(lo, hi, z0, z1);
    if (t > 0)                                              /* sec. 4.3: + (1 - visibility) shifted by t */
        f = tg_add(f, tg_sub(tg_sub(hi, lo), visible_length(lo, hi, tg_add(z0, t), tg_add(z1, t))));
    return tg_min(f, tg_sub(hi, lo));
}

/* Mean and standard deviation of (depth - zc) / r over a footprint of
 * half-size `half` taps spaced `stride` pixels around (cx, cy). 0 if empty. */
static int depth_moments(const tgi_gview *g, int cx, int cy, int half, int stride, tg_real zc,
                         tg_real inv_r, tg_real *mu, tg_real *sigma)
{
    tg_real m1 = 0, m2 = 0;
    int dx, dy, count = 0;
    for (dy = -half; dy <= half; dy++)
        for (dx = -half; dx <= half; dx++) {
            int x = cx + dx * stride, y = cy + dy * stride, j;
            tg_real d;
            if (x < 0 || y < 0 || x >= g->width || y >= g->height) continue;
            j = (int)tgi_gv_index(g, x, y);
            if (tgi_gv_is_sky(g, j)) continue;
            d = tg_clamp(tg_mul(tg_sub(tgi_gv_depth(g, j), zc), inv_r), TG_R(-64.0f), TG_R(64.0f));
            m1 = tg_add(m1, d);
            m2 = tg_add(m2, tg_sqr(d));
            count++;
        }
    if (count == 0) return 0;
    m1 = tg_div(m1, tg_from_int(count));                    /* M1 = E[z] */
    m2 = tg_div(m2, tg_from_int(count));                    /* M2 = E[z^2] */
    *mu = m1;
    *sigma = tg_sqrt(tg_max(tg_sub(m2, tg_sqr(m1)), 0));    /* sigma^2 = E[z^2] - E[z]^2, sec. 4.2 */
    return 1;
}

/* Depth of the surface seen at pixel (qx, qy), taken along the eye ray
 * through s: the pixel's tangent plane (its position and normal) cut by
 * that ray.  This is the depth buffer read at s's exact position, free of
 * nearest-pixel quantisation on planes; a plane not cut in front of the eye
 * falls back to the stored depth. */
static tg_real surface_depth(const tgi_gview *g, tg_vec3 s, int qx, int qy)
{
    int j = (int)tgi_gv_index(g, qx, qy);
    tg_vec3 q = tgi_ao_unproject(g->camera, qx, qy, tgi_gv_depth(g, j)), nj = tgi_ao_normal_view(g, j);
    tg_real n_dot_s = tgi_v3_dot(nj, s), n_dot_q = tgi_v3_dot(nj, q), z;
    if (n_dot_s >= TG_R(-0.0001f) || n_dot_q >= 0) return tgi_gv_depth(g, j);
    z = tg_div(tg_mul(s.z, n_dot_q), n_dot_s);
    return tg_clamp(z, tg_sub(tgi_gv_depth(g, j), TG_R(64.0f)), tg_add(tgi_gv_depth(g, j), TG_R(64.0f)));
}

static void vo_pixel(const tgi_vo_params *p, const tgi_gview *g, const tgi_gresult *out, const tg_real *dx, const tg_real *dy,
                     const tg_real *zs, int n, const tgi_ao_rot *rot, int x, int y)
{
    int i = (int)tgi_gv_index(g, x, y), k;
    const tgi_view *v = g->camera;
    tg_vec3 pv = tgi_ao_unproject(v, x, y, tgi_gv_depth(g, i)), nv = tgi_ao_normal_view(g, i);
    tg_real inv_r = tg_div(TG_ONE, p->radius), t_r = 0, sum_free = 0, sum_len = 0;
    tg_real n_dot_p = tgi_v3_dot(nv, pv), foot_px = 0;
    tg_real bias_r = tg_mul(tgi_ao_depth_bias(g, pv, nv, 0), inv_r);   /* area: the depth buffer's slope slack */
    /* thickness in unit-ball coordinates: 0 = the ball's diameter (2); infinite = no model */
    t_r = p->thickness <= 0 ? TG_R(2.0f) : p->thickness == TG_AO_INFINITE ? 0 : tg_max(tg_mul(p->thickness, inv_r), TG_EPS);
    if (p->area)   /* each sample's footprint: radius R_px / sqrt(n) */
        foot_px = tg_div(tg_div(tg_mul(p->radius, v->pixels_per_unit), tgi_gv_depth(g, i)), tg_sqrt(tg_from_int(n)));
    for (k = 0; k < n; k++) {
        tg_vec3 sd = tgi_ao_rotate_z(tg_v3(dx[k], dy[k], 0), rot->c, rot->s);   /* a disk point turned */
        tg_vec3 s = tg_v3(tg_add(pv.x, tg_mul(sd.x, p->radius)), tg_add(pv.y, tg_mul(sd.y, p->radius)), pv.z);
        tg_real lo = tg_neg(zs[k]), hi = zs[k], z0, z1;
        int qx, qy, j;
        if (p->use_normal) {  /* sec. 4.4: cut at the tangent plane, along the eye ray through s */
            tg_real n_dot_s = tgi_v3_dot(nv, s);
            if (n_dot_s < TG_R(-0.0001f)) {
                tg_real zp = tg_mul(tg_sub(tg_div(tg_mul(s.z, n_dot_p), n_dot_s), pv.z), inv_r);
                hi = tg_min(hi, zp);
            }
        }
        if (hi <= lo) continue;
        sum_len = tg_add(sum_len, tg_sub(hi, lo));
        if (!tgi_ao_project_pixel(v, s, &qx, &qy) || tgi_gv_is_sky(g, j = (int)tgi_gv_index(g, qx, qy))) {
            sum_free = tg_add(sum_free, tg_sub(hi, lo));
            continue;
        }
        z0 = z1 = tg_clamp(tg_mul(tg_sub(surface_depth(g, s, qx, qy), pv.z), inv_r), TG_R(-64.0f), TG_R(64.0f));
        if (p->area) {
            tg_real mu, sigma;
            int half = tg_to_int(foot_px), stride = 1;
            if (half > 3) { stride = (half + 2) / 3; half = 3; }
            if (depth_moments(g, qx, qy, half, stride, pv.z, inv_r, &mu, &sigma)) {
                z0 = tg_add(tg_sub(mu, sigma), bias_r);     /* box model of the depth distribution */
                z1 = tg_add(tg_add(mu, sigma), bias_r);
            }
        }
        sum_free = tg_add(sum_free, free_length(lo, hi, z0, z1, t_r)); /* sec. 4.1 line integral */
    }
    if (sum_len <= 0) { tgi_gr_set_ao(out, i, TG_ONE); return; }
    tgi_gr_set_ao(out, i, tg_saturate(tg_div(sum_free, sum_len)));
    if (!p->use_normal) tgi_gr_set_ao(out, i, tg_min(TG_ONE, tg_ldexp(tgi_gr_ao(out, i), 1)));
}

void tgi_vo_rows(const tgi_vo_params *p, const tgi_gview *g, const tgi_gresult *out, int y0, int y1)
{
    tg_real dx[TG_AO_MAX_SAMPLES], dy[TG_AO_MAX_SAMPLES], zs[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int n = tgi_ao_count(p->samples), k, x, y;
    /* centrally symmetric line pattern: the centre when n is odd, then
     * +- pairs of a Vogel spiral; a tilted plane's depth is linear in x, y,
     * so its errors cancel pairwise (Loos and Sloan sec. 4.5 note the best
     * sets are symmetric and include the centre for 5 and 9 samples) */
    for (k = 0; k < n; k++) {
        int half = n / 2, m = n & 1 ? k - 1 : k;
        if (n & 1 && k == 0) { dx[k] = 0; dy[k] = 0; }
        else {
            tgi_ao_disk(m / 2, half, &dx[k], &dy[k]);
            if (m & 1) { dx[k] = tg_neg(dx[k]); dy[k] = tg_neg(dy[k]); }
        }
        zs[k] = tg_sqrt(tg_max(tg_sub(TG_ONE, tg_add(tg_sqr(dx[k]), tg_sqr(dy[k]))), 0)); /* z_s, sec. 4.1 */
    }
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            tgi_ao_write_open(g, out, i);
            if (tgi_gv_is_sky(g, i) || p->radius <= 0) continue;
            vo_pixel(p, g, out, dx, dy, zs, n, tgi_ao_rot_at(rot, x, y), x, y);
        }
}

#endif /* !TG_NO_TECHNIQUES */
