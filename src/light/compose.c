/* SPDX-License-Identifier: MIT */
/*
 * compose.c - Lo = albedo / pi * (1 - F0) * (E_direct + E_far + E_near) +
 * emissive per pixel, the environment on sky pixels.  See compose.h.
 */
#include "compose.h"
#include "sh.h"

/* World direction of the view ray through the centre of pixel (x, y). */
static tg_vec3 pixel_ray(const tgi_view *view, int x, int y)
{
    tg_vec3 pv = tgi_view_unproject(view, tg_add(tg_from_int(x), TG_R(0.5f)),
                                   tg_add(tg_from_int(y), TG_R(0.5f)), TG_ONE);
    return tgi_view_dir_to_world(view, tgi_v3_normalize_or(pv, tg_v3(0, 0, TG_ONE)));
}

void tgi_compose_rows(const tgi_gview *g, const tgi_env *env, const tgi_rgb *terms, int term_count,
                      const tgi_rgb *out, const tgi_rgb *irr, int y0, int y1)
{
    const tgi_view *view = g->camera;
    int has_env = env && env->type != TG_ENV_NONE && view;
    int has_emit = tgi_gv_has_emissive(g);
    int want_irr = tgi_rgb_present(irr);
    int x, y, k;
    for (y = y0; y < y1; y++) {
        size_t i = tgi_gv_index(g, 0, y);
        for (x = 0; x < g->width; x++, i += (size_t)g->pixel_stride) {
            tg_real er = 0, eg = 0, eb = 0, kd;
            tg_vec3 a, lo;
            if (tgi_gv_is_sky(g, i)) {
                tgi_rgb_set(out, i, has_env ? tgi_env_radiance(env, pixel_ray(view, x, y)) : tg_v3(0, 0, 0));
                if (want_irr) tgi_rgb_set(irr, i, tg_v3(0, 0, 0));
                continue;
            }
            for (k = 0; k < term_count; k++) {
                tg_vec3 e;
                if (!tgi_rgb_present(&terms[k])) continue;
                e = tgi_rgb_get(&terms[k], i);
                er = tg_add(er, e.x);  /* HBIL sec. 2.3: E = E_direct + E_far + E_near */
                eg = tg_add(eg, e.y);
                eb = tg_add(eb, e.z);
            }
            if (want_irr) tgi_rgb_set(irr, i, tg_v3(er, eg, eb));
            kd = tg_mul(tg_saturate(tg_sub(TG_ONE, tgi_gv_f0(g, i))), TG_INV_PI); /* HBIL eq. 19: (1 - F0), eq. 14: 1/pi */
            a = tgi_gv_albedo(g, i);
            lo = tg_v3(tg_mul(tg_mul(a.x, kd), er), tg_mul(tg_mul(a.y, kd), eg), tg_mul(tg_mul(a.z, kd), eb));
            if (has_emit) lo = tgi_v3_add(lo, tgi_gv_emissive(g, i));
            tgi_rgb_set(out, i, lo);
        }
    }
}
