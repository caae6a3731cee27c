/* SPDX-License-Identifier: MIT */
/*
 * bentcone.c - screen-space bent normals, bent cones and the
 * cone-restricted environment lookup (Klehm et al. 2011 sec. 3).  See
 * bentcone.h.
 */
#include "bentcone.h"
#include "sampling.h"
#include "../light/sh.h"

void tgi_bentcone_defaults(tgi_bentcone_params *p)
{
    p->samples = 8;
    p->steps = 3;
    p->radius = TG_ONE;
    p->bias = TG_R(0.03f);
    p->env_sh9 = 0;
    p->far_r = p->far_g = p->far_b = 0;
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
        e = tgi_v3_scale(tgi_sh9_irradiance_cone(sh, bent, tg_sub(TG_ONE, tg_cos(cone))), tg_div(TG_ONE, s2));
    return tgi_v3_scale(e, tg_mul(ao, geo));                  /* sec. 3.4 geometric term, times AO */
}

static void bentcone_pixel(const tgi_bentcone_params *p, const tgi_ao_io *io, const tg_vec3 *dirs, int n,
                           const tgi_ao_rot *rot, int x, int y)
{
    int i = y * io->width + x, k, m, open = 0, steps = p->steps < 1 ? 1 : p->steps;
    const tgi_view *v = io->view;
    tg_vec3 pv = tgi_ao_unproject(v, x, y, io->depth[i]), nv = tgi_ao_normal_view(io, i), t, b;
    tg_vec3 sum = tg_v3(0, 0, 0), nw = tg_v3(io->nx[i], io->ny[i], io->nz[i]), bent_w;
    tg_real bias = tg_mul(p->bias, p->radius), mean_len, cone, ao;
    tgi_ao_basis(nv, &t, &b);
    for (k = 0; k < n; k++) {
        tg_vec3 w = tgi_ao_from_local(tgi_ao_rotate_z(dirs[k], rot->c, rot->s), t, b, nv);
        int blocked = 0;
        for (m = 0; m < steps && !blocked; m++) {           /* ray-march points along w */
            tg_real lambda = tg_div(tg_mul(p->radius, tg_add(tg_from_int(m), rot->jitter)), tg_from_int(steps));
            blocked = tgi_ao_sample_blocked(io, pv, tgi_v3_add(pv, tgi_v3_scale(w, lambda)), bias, tg_ldexp(p->radius, 1));
        }
        if (blocked) continue;
        open++;
        sum = tgi_v3_add(sum, w);
    }
    ao = tg_ratio(open, n);                                 /* Klehm eq. 3 */
    io->ao[i] = ao;
    if (open == 0) {
        bent_w = nw;
        cone = 0;
    } else {
        tg_vec3 mean = tgi_v3_scale(sum, tg_div(TG_ONE, tg_from_int(open))); /* N_ss, sec. 3.1 */
        mean_len = tgi_v3_length(mean);
        cone = tgi_bentcone_aperture(mean_len);
        bent_w = tgi_v3_normalize_or(tgi_ao_dir_to_world(v, mean), nw);
    }
    if (io->bent_x) { io->bent_x[i] = bent_w.x; io->bent_y[i] = bent_w.y; io->bent_z[i] = bent_w.z; }
    if (io->cone) io->cone[i] = cone;
    if (p->env_sh9 && p->far_r) {
        tg_vec3 e = tgi_bentcone_far(p->env_sh9, bent_w, cone, ao, nw);
        p->far_r[i] = e.x; p->far_g[i] = e.y; p->far_b[i] = e.z;
    }
}

void tgi_bentcone_rows(const tgi_bentcone_params *p, const tgi_ao_io *io, int y0, int y1)
{
    tg_vec3 dirs[TG_AO_MAX_SAMPLES];
    tgi_ao_rot rot[16];
    int n = p->samples < 1 ? 1 : p->samples > TG_AO_MAX_SAMPLES ? TG_AO_MAX_SAMPLES : p->samples, k, x, y;
    for (k = 0; k < n; k++) dirs[k] = tgi_ao_hemi_uniform(k, n);
    tgi_ao_rotations(rot);
    for (y = y0; y < y1; y++)
        for (x = 0; x < io->width; x++) {
            int i = y * io->width + x;
            tgi_ao_write_open(io, i);
            if (p->far_r) {
                tg_vec3 e = tg_v3(0, 0, 0);
                if (!io->sky[i] && p->env_sh9) e = tgi_sh9_irradiance(p->env_sh9, tg_v3(io->nx[i], io->ny[i], io->nz[i]));
                p->far_r[i] = e.x; p->far_g[i] = e.y; p->far_b[i] = e.z;
            }
            if (io->sky[i] || p->radius <= 0) continue;
            bentcone_pixel(p, io, dirs, n, tgi_ao_rot_at(rot, x, y), x, y);
        }
}
