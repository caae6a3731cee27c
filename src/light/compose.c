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

void tgi_compose_rows(const tgi_gbuffer *gb, const tgi_view *view, const tgi_env *env,
                     const tgi_rgb_planes *terms, int term_count,
                     tg_real *out_r, tg_real *out_g, tg_real *out_b,
                     tg_real *irr_r, tg_real *irr_g, tg_real *irr_b, int y0, int y1)
{
    int has_env = env && env->type != TG_ENV_NONE && view;
    int has_emit = gb->emit_r && gb->emit_g && gb->emit_b;
    int want_irr = irr_r && irr_g && irr_b;
    int x, y, k, w = gb->width;
    for (y = y0; y < y1; y++) {
        int i = y * w;
        for (x = 0; x < w; x++, i++) {
            tg_real er = 0, eg = 0, eb = 0, kd;
            if (gb->sky[i]) {
                tg_vec3 sky = has_env ? tgi_env_radiance(env, pixel_ray(view, x, y)) : tg_v3(0, 0, 0);
                out_r[i] = sky.x; out_g[i] = sky.y; out_b[i] = sky.z;
                if (want_irr) irr_r[i] = irr_g[i] = irr_b[i] = 0;
                continue;
            }
            for (k = 0; k < term_count; k++) {
                if (!terms[k].r) continue;
                er = tg_add(er, terms[k].r[i]);  /* HBIL sec. 2.3: E = E_direct + E_far + E_near */
                eg = tg_add(eg, terms[k].g[i]);
                eb = tg_add(eb, terms[k].b[i]);
            }
            if (want_irr) { irr_r[i] = er; irr_g[i] = eg; irr_b[i] = eb; }
            kd = tg_mul(tg_saturate(tg_sub(TG_ONE, gb->f0[i])), TG_INV_PI); /* HBIL eq. 19: (1 - F0), eq. 14: 1/pi */
            out_r[i] = tg_mul(tg_mul(gb->albedo_r[i], kd), er);
            out_g[i] = tg_mul(tg_mul(gb->albedo_g[i], kd), eg);
            out_b[i] = tg_mul(tg_mul(gb->albedo_b[i], kd), eb);
            if (has_emit) {
                out_r[i] = tg_add(out_r[i], gb->emit_r[i]);
                out_g[i] = tg_add(out_g[i], gb->emit_g[i]);
                out_b[i] = tg_add(out_b[i], gb->emit_b[i]);
            }
        }
    }
}
