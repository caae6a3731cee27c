/* SPDX-License-Identifier: MIT */
/*
 * ssao.c - Crytek point-sample SSAO in a sphere, in the normal-oriented
 * hemisphere, and Crytek2D in a screen disk (see ssao.h).
 */
#include "ssao.h"
#include "sampling.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

static const tgi_ssao_params ssao_defaults = { .samples = 16, .radius = TG_ONE, .variant = TG_SSAO_HEMISPHERE, .bias = TG_AO_DEFAULT_BIAS };

void tgi_ssao_defaults(tgi_ssao_params *p)
{
    *p = ssao_defaults;
}


/* Kernel of unit-ball offsets (local frame) and their unit directions. */
static int make_kernel(int variant, int n, tg_vec3 *off, tg_vec3 *dir)
{
    int k;
    if (variant == TG_SSAO_SPHERE) {          /* antipodal pairs, sphere Fibonacci directions */
        int half = n / 2 > 0 ? n / 2 : 1;
        for (k = 0; k < half; k++) {
            tg_real z = tg_sub(TG_ONE, tg_ratio(2 * k + 1, half));
            tg_real r = tg_sqrt(tg_sub(TG_ONE, tg_sqr(z)));
            tg_real a = tg_mul(TG_TWO_PI, tgi_ao_golden_frac(k));
            tg_real len = tg_pow(tg_ratio(2 * k + 1, 2 * half), TG_R(0.333333333f)); /* volume-uniform */
            dir[2 * k] = tg_v3(tg_mul(r, tg_cos(a)), tg_mul(r, tg_sin(a)), z);
            dir[2 * k + 1] = tgi_v3_neg(dir[2 * k]);
            off[2 * k] = tgi_v3_scale(dir[2 * k], len);
            off[2 * k + 1] = tgi_v3_neg(off[2 * k]);
        }
        return 2 * half;
    }
    if (variant == TG_SSAO_HEMISPHERE) {
        for (k = 0; k < n; k++) {
            tg_real u = tg_add(tgi_ao_radical2(k), tg_ratio(1, 2 * n));
            dir[k] = tgi_ao_hemi_cosine(k, n);
            off[k] = tgi_v3_scale(dir[k], tg_pow(u, TG_R(0.333333333f)));
        }
        return n;
    }
    for (k = 0; k < n; k++) {                 /* disk: Vogel spiral */
        tg_real x, y;
        tgi_ao_disk(k, n, &x, &y);
        off[k] = tg_v3(x, y, 0);
        dir[k] = off[k];
    }
    return n;
}

static void ssao_3d(const tgi_ssao_params *p, const tgi_gview *g, const tgi_gresult *out, const tg_vec3 *off, const tg_vec3 *dir,
                    int n, const tgi_ao_rot *rot, int x, int y)
{
    int i = (int)tgi_gv_index(g, x, y), k, open = 0;
    tg_vec3 pv = tgi_ao_unproject(g->camera, x, y, tgi_gv_depth(g, i)), nv = tgi_ao_normal_view(g, i);
    tg_vec3 t = tg_v3(TG_ONE, 0, 0), b = tg_v3(0, TG_ONE, 0), axis = tg_v3(0, 0, TG_ONE);
    tg_vec3 bent = tg_v3(0, 0, 0);
    tg_real bias = tg_mul(p->bias, p->radius);
    if (p->variant == TG_SSAO_HEMISPHERE) { axis = nv; tgi_ao_basis(nv, &t, &b); }
    for (k = 0; k < n; k++) {
        tg_vec3 o = tgi_ao_from_local(tgi_ao_rotate_z(off[k], rot->c, rot->s), t, b, axis);
        tg_vec3 s = tgi_v3_add(pv, tgi_v3_scale(o, p->radius));
        if (tgi_ao_sample_blocked(g, pv, s, bias, tg_ldexp(p->radius, 1))) continue; /* Klehm eq. 3, d_x with range check */
        open++;
        bent = tgi_v3_add(bent, tgi_ao_from_local(tgi_ao_rotate_z(dir[k], rot->c, rot->s), t, b, axis));
    }
    if (p->variant == TG_SSAO_SPHERE)
        tgi_gr_set_ao(out, i, tg_min(TG_ONE, tg_ratio(2 * open, n)));      /* half the ball is under any surface */
    else
        tgi_gr_set_ao(out, i, tg_ratio(open, n));                          /* Klehm eq. 3 */
    tgi_ao_write_bent_view(g, out, i, bent);                         /* Klehm sec. 3.1 */
}

static void ssao_2d(const tgi_ssao_params *p, const tgi_gview *g, const tgi_gresult *out, const tg_vec3 *off, int n,
                    const tgi_ao_rot *rot, int x, int y)
{
    int i = (int)tgi_gv_index(g, x, y), k, blocked = 0;
    const tgi_view *v = g->camera;
    tg_vec3 pv = tgi_ao_unproject(v, x, y, tgi_gv_depth(g, i)), nv = tgi_ao_normal_view(g, i);
    tg_real r_px = tg_div(tg_mul(p->radius, v->pixels_per_unit), tgi_gv_depth(g, i));
    tg_real r2 = tg_sqr(p->radius);
    for (k = 0; k < n; k++) {
        tg_vec3 o = tgi_ao_rotate_z(off[k], rot->c, rot->s), d;
        int qx = tg_to_int(tg_add(tg_add(tg_from_int(x), TG_R(0.5f)), tg_mul(o.x, r_px)));
        int qy = tg_to_int(tg_add(tg_add(tg_from_int(y), TG_R(0.5f)), tg_mul(o.y, r_px)));
        int j = (int)tgi_gv_index(g, qx, qy);
        tg_real dn, dd;
        if (qx < 0 || qy < 0 || qx >= g->width || qy >= g->height || j == i || tgi_gv_is_sky(g, j)) continue;
        d = tgi_v3_sub(tgi_ao_unproject(v, qx, qy, tgi_gv_depth(g, j)), pv);
        dd = tgi_v3_dot(d, d);
        dn = tgi_v3_dot(d, nv);
        /* Klehm d_xn: above the tangent plane (with a bias angle of ~3 deg) and in range */
        if (dn > 0 && tg_sqr(dn) > tg_mul(dd, TG_R(0.0025f)) && dd < r2) blocked++;
    }
    tgi_gr_set_ao(out, i, tg_sub(TG_ONE, tg_ratio(blocked, n)));            /* Klehm eq. 3 */
    if (tgi_gr_has_bent(out)) tgi_gr_set_bent(out, i, tgi_gv_normal(g, i));
}

void tgi_ssao_rows(const tgi_ssao_params *p, const tgi_gview *g, const tgi_gresult *out, int y0, int y1)
{
    tg_vec3 off[TG_AO_MAX_SAMPLES], dir[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int n = make_kernel(p->variant, tgi_ao_count(p->samples), off, dir), x, y;
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            if (tgi_gv_is_sky(g, i) || p->radius <= 0) { tgi_ao_write_open(g, out, i); continue; }
            if (tgi_gr_has_cone(out)) tgi_gr_set_cone(out, i, TG_HALF_PI);
            if (tgi_gr_has_near(out)) tgi_gr_set_near(out, i, tg_v3(0, 0, 0));
            if (p->variant == TG_SSAO_DISK2D) ssao_2d(p, g, out, off, n, tgi_ao_rot_at(rot, x, y), x, y);
            else ssao_3d(p, g, out, off, dir, n, tgi_ao_rot_at(rot, x, y), x, y);
        }
}

#endif /* !TG_NO_TECHNIQUES */
