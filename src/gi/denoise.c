/* SPDX-License-Identifier: MIT */
/*
 * denoise.c - the spatial 4x4-neighbourhood filter of the HBIL outputs
 * (HBIL sec. 3.3-3.4).  See denoise.h.
 */
#include "../tinygi.h"
#include "denoise.h"

void tgi_denoise_defaults(tgi_denoise_params *p)
{
    p->depth_tolerance = TG_R(0.1f);
}

/* 1-D tap weights (1/2, 1, 1, 1, 1/2); the 2-D weight is their product. */
static const tg_real tap_w[5] = { TG_R(0.5f), TG_ONE, TG_ONE, TG_ONE, TG_R(0.5f) };

/* The weights' factors are in [0, 1] (up to a rounding): their products
 * never saturate, so tgi_wide_mul (core/real.h) gives tg_mul's result. */
static tg_real weight_mul(tg_real a, tg_real b) { return (tg_real)tgi_wide_mul(a, b); }

static tg_real normal_weight(tg_real d)
{
    d = tg_max(d, 0);
    d = weight_mul(d, d); d = weight_mul(d, d); d = weight_mul(d, d);   /* (n_i . n_j)^8 */
    return d;
}

/* Pixel (xx, yy) of g decoded into its tap slot. */
static void tap_load(tgi_denoise_tap *t, const tgi_gview *g, const tgi_gresult *r, int xx, int yy)
{
    size_t j = tgi_gv_index(g, xx, yy);
    t->sky = tgi_gv_is_sky(g, j);
    if (t->sky) return;
    t->z = tgi_gv_depth(g, j);
    t->n = tgi_gv_normal(g, j);
    t->v = tgi_gr_get_kept(r, j);
}

/* Weight of tap t for the centre (depth zi, normal ni): depth and normal
 * aware; 0 for sky and for a depth step of tol zi or more. */
static tg_real tap_weight(const tgi_denoise_tap *t, tg_real tap, tg_real zi, tg_vec3 ni, tg_real ztol, tg_real inv_ztol)
{
    tg_real dz, wt;
    if (t->sky) return 0;
    dz = tg_abs(tg_sub(t->z, zi));
    if (dz >= ztol) return 0;
    wt = weight_mul(tap, tg_sub(TG_ONE, weight_mul(dz, inv_ztol)));   /* dz < ztol: dz / ztol in [0, 1] */
    return weight_mul(wt, normal_weight(tgi_v3_dot(ni, t->n)));
}

void tgi_denoise_walk_start(tgi_denoise_walk *k)
{
    k->y = -1;
    k->lo = k->next = 0;
}

tgi_gr_value tgi_denoise_pixel(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r,
                               tgi_denoise_walk *k, int x, int y)
{
    size_t i = tgi_gv_index(g, x, y);
    int w = g->width, h = g->height, xx, yy, slot[5], has_bent = !TG_NO_BENT_NORMALS && tgi_gr_has_bent(r), has_near = !TG_NO_COLOR && tgi_gr_has_near(r);
    int xa = x < 2 ? 0 : x - 2, xb = x + 2 >= w ? w - 1 : x + 2;
    int ya = y < 2 ? 0 : y - 2, yb = y + 2 >= h ? h - 1 : y + 2;
    tg_real zi, ztol, inv_ztol;
    /* The sums in tgi_wide (core/real.h), unsaturated: every weight is in
     * (0, 1] and there are at most 25, so wsum <= 9, ao <= 9 and |bent| <= 9
     * never saturate; the near field is never negative (RGB9E5; the kernel's
     * gathered sums), so saturating after the last tap gives what a
     * saturating add after each tap gives.  A build with TG_NO_COLOR
     * (tinygi.h "FEATURE SWITCHES") has no near field, one with
     * TG_NO_BENT_NORMALS no bent normal: their sums are left out. */
    tgi_wide wsum = 0, ao = 0, bx = 0, by = 0, bz = 0, nr = 0, ng = 0, nb = 0;
    tg_vec3 ni, bent, near;
    const tgi_denoise_tap *ci;
    tgi_gr_value v;
    if (tgi_gv_is_sky(g, i)) return tgi_gr_get_kept(r, i);
    /* the window's columns decoded once: those of the last pixel are kept */
    if (k->y != y || xa < k->lo) { k->y = y; k->lo = k->next = xa; }
    for (; k->next <= xb; k->next++)
        for (yy = ya; yy <= yb; yy++)
            tap_load(&k->tap[k->next % 5][yy - y + 2], g, r, k->next, yy);
    if (k->next - k->lo > 5) k->lo = k->next - 5;
    ci = &k->tap[x % 5][2];
    zi = ci->z;
    ni = ci->n;
    ztol = tg_mul(p->depth_tolerance, zi);
    inv_ztol = tg_div(TG_ONE, ztol);
    for (xx = xa; xx <= xb; xx++) slot[xx - xa] = xx % 5;
    for (yy = ya; yy <= yb; yy++)
        for (xx = xa; xx <= xb; xx++) {
            const tgi_denoise_tap *t = &k->tap[slot[xx - xa]][yy - y + 2];
            tg_real wt = tap_weight(t, weight_mul(tap_w[xx - x + 2], tap_w[yy - y + 2]), zi, ni, ztol, inv_ztol);
            if (wt <= 0) continue;
            wsum += wt;
            ao += tgi_wide_mul(wt, t->v.ao);
            if (has_bent) {
                bx += tgi_wide_mul(t->v.bent.x, wt);
                by += tgi_wide_mul(t->v.bent.y, wt);
                bz += tgi_wide_mul(t->v.bent.z, wt);
            }
            if (has_near) {
                nr += tgi_wide_mul(t->v.near.x, wt);
                ng += tgi_wide_mul(t->v.near.y, wt);
                nb += tgi_wide_mul(t->v.near.z, wt);
            }
        }
    if (wsum <= 0) return tgi_gr_get_kept(r, i);   /* the centre always weighs 1: cannot happen */
    bent = tg_v3(tgi_wide_real(bx), tgi_wide_real(by), tgi_wide_real(bz));
    near = tg_v3(tgi_wide_real(nr), tgi_wide_real(ng), tgi_wide_real(nb));
    v.ao = tg_saturate(tg_div(tgi_wide_real(ao), tgi_wide_real(wsum)));
    {
        tg_real ws = tgi_wide_real(wsum);
        v.bent = has_bent ? tgi_v3_normalize_or(tg_v3(tg_div(bent.x, ws), tg_div(bent.y, ws), tg_div(bent.z, ws)), ni)
                          : tg_v3(0, 0, 0);
        v.near = has_near ? tg_v3(tg_div(near.x, ws), tg_div(near.y, ws), tg_div(near.z, ws)) : tg_v3(0, 0, 0);
    }
    return v;
}

void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r, const tgi_gresult *out,
                      int y0, int y1)
{
    tgi_denoise_walk k;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    tgi_denoise_walk_start(&k);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            tgi_gr_value v = tgi_denoise_pixel(p, g, r, &k, x, y);
            tgi_gr_put_kept(out, tgi_gv_index(g, x, y), &v);
        }
}
