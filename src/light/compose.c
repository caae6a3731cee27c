/* SPDX-License-Identifier: MIT */
/*
 * compose.c - Lo = albedo / pi * (1 - F0) * (E_direct + E_far + E_near) +
 * emissive per pixel, the environment on sky pixels.  See compose.h.
 */
#include "compose.h"
#include "sh.h"
#include "../core/unit.h"

#if !TG_NO_COLOR /* the whole file is left out with TG_NO_COLOR=1 (tinygi.h "FEATURE SWITCHES") */

/* World direction of the view ray through the centre of pixel (x, y). */
static tg_vec3 pixel_ray(const tgi_view *view, int x, int y)
{
    tg_vec3 pv = tgi_view_unproject(view, tg_add(tg_from_int(x), TG_R(0.5f)),
                                   tg_add(tg_from_int(y), TG_R(0.5f)), TG_ONE);
    return tgi_view_dir_to_world(view, tgi_v3_unit_or(pv, tg_v3(0, 0, TG_ONE)));
}

tg_vec3 tgi_compose_sky(const tgi_view *view, const tgi_env *env, int x, int y)
{
    if (!view || !env || env->type == TG_ENV_NONE) return tg_v3(0, 0, 0);
    return tgi_env_radiance(env, pixel_ray(view, x, y));
}

void tgi_compose_rows(const tgi_gview *g, const tgi_env *env, const tgi_rgb *terms, int term_count,
                      const tgi_rgb *out, const tgi_rgb *irr, int y0, int y1)
{
    const tgi_view *view = g->camera;
    int has_env = env && env->type != TG_ENV_NONE && view;
    int want_irr = tgi_rgb_present(irr);
    int x, y, k;
    for (y = y0; y < y1; y++) {
        size_t i = tgi_gv_index(g, 0, y);
        for (x = 0; x < g->width; x++, i += (size_t)g->pixel_stride) {
            tg_real er = 0, eg = 0, eb = 0;
            if (tgi_gv_is_sky(g, i)) {
                tgi_rgb_set(out, i, has_env ? tgi_compose_sky(view, env, x, y) : tg_v3(0, 0, 0));
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
            tgi_rgb_set(out, i, tgi_gv_lit(g, i, tg_v3(er, eg, eb)));   /* HBIL eq. 14, 19 */
        }
    }
}

#endif /* !TG_NO_COLOR */
