/* SPDX-License-Identifier: MIT */
/*
 * denoise.c - the spatial 4x4-neighbourhood filter of the HBIL outputs
 * (HBIL sec. 3.3-3.4).  See denoise.h.
 */
#include <string.h>
#include "../tinygi.h"
#include "denoise.h"

#define DN_CH 7     /* ao, bent xyz, near rgb: planes of the scratch */

void tgi_denoise_defaults(tgi_denoise_params *p)
{
    p->depth_tolerance = TG_R(0.1f);
}

size_t tgi_denoise_bytes(int w, int h)
{
    size_t n;
    if (w < 0 || h < 0 || tg_size_mul((size_t)w, (size_t)h, &n) || tg_size_mul(n, DN_CH * sizeof(tg_real), &n))
        return SIZE_MAX;
    return n;
}

/* The channels of pixel i: ao, bent, near (what r does not have reads 0). */
static void channels_get(const tgi_gresult *r, size_t i, tg_real v[DN_CH])
{
    tg_vec3 b = tgi_gr_has_bent(r) ? tgi_gr_bent(r, i) : tg_v3(0, 0, 0);
    tg_vec3 e = tgi_gr_has_near(r) ? tgi_gr_near(r, i) : tg_v3(0, 0, 0);
    v[0] = tgi_gr_ao(r, i);
    v[1] = b.x; v[2] = b.y; v[3] = b.z;
    v[4] = e.x; v[5] = e.y; v[6] = e.z;
}

void tgi_denoise_keep_rows(const tgi_gview *g, const tgi_gresult *r, void *scratch, int y0, int y1)
{
    size_t n = (size_t)g->width * (size_t)g->height;
    tg_real *keep = (tg_real *)scratch, v[DN_CH];
    int x, y, k;
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            size_t j = (size_t)y * (size_t)g->width + (size_t)x;
            channels_get(r, tgi_gv_index(g, x, y), v);
            for (k = 0; k < DN_CH; k++) keep[(size_t)k * n + j] = v[k];
        }
}

/* 1-D tap weights (1/2, 1, 1, 1, 1/2); the 2-D weight is their product. */
static const tg_real tap_w[5] = { TG_R(0.5f), TG_ONE, TG_ONE, TG_ONE, TG_R(0.5f) };

static tg_real normal_weight(tg_real d)
{
    d = tg_max(d, 0);
    d = tg_mul(d, d); d = tg_mul(d, d); d = tg_mul(d, d);   /* (n_i . n_j)^8 */
    return d;
}

/* Per-call constants: the channels present (their scratch planes) and the
 * 5x5 product weights. */
typedef struct dn_ctx {
    const tgi_denoise_params *p;
    const tgi_gview *g;
    const tgi_gresult *r;
    int nch, ch[DN_CH];          /* channel numbers present, in order */
    const tg_real *keep;         /* the scratch: DN_CH planes, packed */
    size_t n;
    tg_real tap2[5][5];
} dn_ctx;

static void dn_ctx_init(dn_ctx *c, const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r,
                        const tg_real *scratch)
{
    int k, dx, dy;
    c->p = p;
    c->g = g;
    c->r = r;
    c->keep = scratch;
    c->n = (size_t)g->width * (size_t)g->height;
    c->nch = 0;
    for (k = 0; k < DN_CH; k++) {
        int present = k == 0 || (k < 4 ? tgi_gr_has_bent(r) : tgi_gr_has_near(r));
        if (present) c->ch[c->nch++] = k;
    }
    for (dy = 0; dy < 5; dy++)
        for (dx = 0; dx < 5; dx++) c->tap2[dy][dx] = tg_mul(tap_w[dx], tap_w[dy]);
}

/* The weights of the window's valid taps (depth and normal aware); returns
 * the count, fills each tap's packed index and weight. */
static int filter_taps(const dn_ctx *c, int x, int y, size_t *restrict tj, tg_real *restrict tw)
{
    const tgi_gview *g = c->g;
    int w = g->width, h = g->height, xx, yy, nt = 0;
    int xa = x < 2 ? 0 : x - 2, xb = x + 2 >= w ? w - 1 : x + 2;
    int ya = y < 2 ? 0 : y - 2, yb = y + 2 >= h ? h - 1 : y + 2;
    size_t i = tgi_gv_index(g, x, y);
    tg_real zi = tgi_gv_depth(g, i);
    tg_vec3 ni = tgi_gv_normal(g, i);
    tg_real ztol = tg_mul(c->p->depth_tolerance, zi);
    tg_real inv_ztol = tg_div(TG_ONE, ztol);
    for (yy = ya; yy <= yb; yy++) {
        const tg_real *tap_row = c->tap2[yy - y + 2];
        size_t j = tgi_gv_index(g, xa, yy), packed = (size_t)yy * (size_t)w + (size_t)xa;
        for (xx = xa; xx <= xb; xx++, j += (size_t)g->pixel_stride, packed++) {
            tg_real wt, dz;
            if (tgi_gv_is_sky(g, j) || tgi_gv_depth(g, j) <= 0) continue;
            dz = tg_abs(tg_sub(tgi_gv_depth(g, j), zi));
            if (dz >= ztol) continue;
            wt = tg_mul(tap_row[xx - x + 2], tg_sub(TG_ONE, tg_mul(dz, inv_ztol)));
            wt = tg_mul(wt, normal_weight(tgi_v3_dot(ni, tgi_gv_normal(g, j))));
            if (wt <= 0) continue;
            tj[nt] = packed;
            tw[nt] = wt;
            nt++;
        }
    }
    return nt;
}

static void filter_pixel(const dn_ctx *c, int x, int y)
{
    const tgi_gresult *r = c->r;
    size_t i = tgi_gv_index(c->g, x, y), tj[25];
    tg_real tw[25], wsum = 0, v[DN_CH], ao;
    int nt = filter_taps(c, x, y, tj, tw), t, k;
    for (t = 0; t < nt; t++) wsum = tg_add(wsum, tw[t]);
    if (wsum <= 0) return;   /* the centre always weighs 1: cannot happen */
    for (k = 0; k < c->nch; k++) {
        const tg_real *restrict in = c->keep + (size_t)c->ch[k] * c->n;
        tg_real sum = 0;
        for (t = 0; t < nt; t++) sum = tg_add(sum, tg_mul(tw[t], in[tj[t]]));
        v[c->ch[k]] = tg_div(sum, wsum);
    }
    ao = tg_saturate(v[0]);
    tgi_gr_set_ao(r, i, ao);
    if (tgi_gr_has_bent(r))
        tgi_gr_set_bent(r, i, tgi_v3_normalize_or(tg_v3(v[1], v[2], v[3]), tgi_gv_normal(c->g, i)));
    if (tgi_gr_has_near(r)) tgi_gr_set_near(r, i, tg_v3(v[4], v[5], v[6]));
    if (tgi_gr_has_cone(r)) tgi_gr_set_cone(r, i, tg_acos(tg_sub(TG_ONE, ao)));   /* HBIL eq. 12 */
}

void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r,
                      const void *scratch, int y0, int y1)
{
    dn_ctx c;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    dn_ctx_init(&c, p, g, r, (const tg_real *)scratch);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            size_t i = tgi_gv_index(g, x, y);
            if (tgi_gv_is_sky(g, i) || tgi_gv_depth(g, i) <= 0) continue;
            filter_pixel(&c, x, y);
        }
}
