/* SPDX-License-Identifier: MIT */
/*
 * denoise.c - spatial 4x4-neighbourhood filter and temporal accumulation of
 * the HBIL outputs (HBIL sec. 3.3-3.4).  See denoise.h.
 */
#include <string.h>
#include "denoise.h"

#define DN_CH 7     /* ao, bent xyz, near rgb */
#define TM_CH 11    /* + depth, normal xyz */

void tgi_denoise_defaults(tgi_denoise_params *p)
{
    p->depth_tolerance = TG_R(0.1f);
    p->alpha = TG_R(0.2f);
    p->history_depth_tolerance = TG_R(0.05f);
    p->history_normal_cos = TG_R(0.9f);
}

static tg_real *channel(const tgi_denoise_io *io, int k)
{
    switch (k) {
    case 0: return io->ao;
    case 1: return io->bent_x;
    case 2: return io->bent_y;
    case 3: return io->bent_z;
    case 4: return io->near_r;
    case 5: return io->near_g;
    default: return io->near_b;
    }
}

size_t tgi_denoise_bytes(int w, int h) { return (size_t)w * (size_t)h * DN_CH * sizeof(tg_real); }

void tgi_denoise_begin(const tgi_denoise_io *io, void *scratch)
{
    size_t n = (size_t)io->width * io->height;
    int k;
    for (k = 0; k < DN_CH; k++) {
        tg_real *c = channel(io, k);
        if (c) memcpy((tg_real *)scratch + (size_t)k * n, c, n * sizeof(tg_real));
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

/* Per-call constants: the present channels (input plane, output) and the
 * 5x5 product weights. */
typedef struct dn_ctx {
    const tgi_denoise_params *p;
    const tgi_denoise_io *io;
    int nch;
    const tg_real *in[DN_CH];
    tg_real *out[DN_CH];
    tg_real tap2[5][5];
} dn_ctx;

static void dn_ctx_init(dn_ctx *c, const tgi_denoise_params *p, const tgi_denoise_io *io, const tg_real *scratch)
{
    size_t n = (size_t)io->width * io->height;
    int k, dx, dy;
    c->p = p;
    c->io = io;
    c->nch = 0;
    for (k = 0; k < DN_CH; k++) {
        tg_real *ch = channel(io, k);
        if (!ch) continue;
        c->in[c->nch] = scratch + (size_t)k * n;
        c->out[c->nch] = ch;
        c->nch++;
    }
    for (dy = 0; dy < 5; dy++)
        for (dx = 0; dx < 5; dx++) c->tap2[dy][dx] = tg_mul(tap_w[dx], tap_w[dy]);
}

/* The weights of the window's valid taps (depth and normal aware); returns
 * the count, fills tap index and weight. */
static int filter_taps(const dn_ctx *c, int x, int y, size_t *restrict tj, tg_real *restrict tw)
{
    const tgi_denoise_io *io = c->io;
    const tg_real *restrict depth = io->depth, *restrict nx = io->nx, *restrict ny = io->ny, *restrict nz = io->nz;
    const uint8_t *sky = io->sky;
    int w = io->width, h = io->height, xx, yy, nt = 0;
    int xa = x < 2 ? 0 : x - 2, xb = x + 2 >= w ? w - 1 : x + 2;
    int ya = y < 2 ? 0 : y - 2, yb = y + 2 >= h ? h - 1 : y + 2;
    size_t i = (size_t)y * w + x;
    tg_real zi = depth[i], nix = nx[i], niy = ny[i], niz = nz[i];
    tg_real ztol = tg_mul(c->p->depth_tolerance, zi);
    tg_real inv_ztol = tg_div(TG_ONE, ztol);
    for (yy = ya; yy <= yb; yy++) {
        const tg_real *tap_row = c->tap2[yy - y + 2];
        size_t row = (size_t)yy * w;
        for (xx = xa; xx <= xb; xx++) {
            size_t j = row + xx;
            tg_real wt, dz;
            if ((sky && sky[j]) || depth[j] <= 0) continue;
            dz = tg_abs(tg_sub(depth[j], zi));
            if (dz >= ztol) continue;
            wt = tg_mul(tap_row[xx - x + 2], tg_sub(TG_ONE, tg_mul(dz, inv_ztol)));
            wt = tg_mul(wt, normal_weight(tgi_v3_dot(tg_v3(nix, niy, niz), tg_v3(nx[j], ny[j], nz[j]))));
            if (wt <= 0) continue;
            tj[nt] = j;
            tw[nt] = wt;
            nt++;
        }
    }
    return nt;
}

static void filter_pixel(const dn_ctx *c, int x, int y)
{
    const tgi_denoise_io *io = c->io;
    size_t i = (size_t)y * io->width + x, tj[25];
    tg_real tw[25], wsum = 0;
    int nt = filter_taps(c, x, y, tj, tw), t, k;
    for (t = 0; t < nt; t++) wsum = tg_add(wsum, tw[t]);
    if (wsum <= 0) return;   /* the centre always weighs 1: cannot happen */
    for (k = 0; k < c->nch; k++) {
        const tg_real *restrict in = c->in[k];
        tg_real sum = 0;
        for (t = 0; t < nt; t++) sum = tg_add(sum, tg_mul(tw[t], in[tj[t]]));
        c->out[k][i] = tg_div(sum, wsum);
    }
    if (io->bent_x && io->bent_y && io->bent_z) {
        tg_vec3 b = tgi_v3_normalize_or(tg_v3(io->bent_x[i], io->bent_y[i], io->bent_z[i]),
                                       tg_v3(io->nx[i], io->ny[i], io->nz[i]));
        io->bent_x[i] = b.x; io->bent_y[i] = b.y; io->bent_z[i] = b.z;
    }
    io->ao[i] = tg_saturate(io->ao[i]);
    if (io->cone) io->cone[i] = tg_acos(tg_sub(TG_ONE, io->ao[i]));   /* HBIL eq. 12 */
}

void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_denoise_io *io, const void *scratch, int y0, int y1)
{
    dn_ctx c;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > io->height) y1 = io->height;
    dn_ctx_init(&c, p, io, (const tg_real *)scratch);
    for (y = y0; y < y1; y++)
        for (x = 0; x < io->width; x++) {
            size_t i = (size_t)y * io->width + x;
            if ((io->sky && io->sky[i]) || io->depth[i] <= 0) continue;
            filter_pixel(&c, x, y);
        }
}

/* ---- temporal ---- */
size_t tgi_temporal_bytes(int w, int h) { return 2 * (size_t)w * (size_t)h * TM_CH * sizeof(tg_real); }

void tgi_temporal_clear(void *state, int w, int h) { memset(state, 0, tgi_temporal_bytes(w, h)); }

static void temporal_pixel(const tgi_denoise_params *p, const tgi_denoise_io *io, const tg_real *prev, tg_real *next,
                           const tgi_view *prev_view, const tgi_view *view, int reset, int x, int y)
{
    int w = io->width, h = io->height, k;
    size_t n = (size_t)w * h, i = (size_t)y * w + x, s = 0;
    int ok = 0, sky = (io->sky && io->sky[i]) || io->depth[i] <= 0;
    if (!reset && !sky && prev_view) {
        tg_vec3 pv = tgi_view_unproject(view, tg_add(tg_from_int(x), TG_R(0.5f)), tg_add(tg_from_int(y), TG_R(0.5f)), io->depth[i]);
        tg_vec3 q = tgi_view_world_to_view(prev_view, tgi_view_view_to_world(view, pv));
        if (q.z > 0) {
            tg_real sx, sy;
            int px, py;
            tgi_view_project(prev_view, q, &sx, &sy);
            px = tg_to_int(sx); py = tg_to_int(sy);
            if (px >= 0 && py >= 0 && px < w && py < h) {
                tg_real hz;
                s = (size_t)py * w + px;
                hz = prev[7 * n + s];
                if (hz > 0 && tg_abs(tg_sub(hz, q.z)) <= tg_mul(p->history_depth_tolerance, hz)) {
                    tg_vec3 hn = tg_v3(prev[8 * n + s], prev[9 * n + s], prev[10 * n + s]);
                    ok = tgi_v3_dot(hn, tg_v3(io->nx[i], io->ny[i], io->nz[i])) >= p->history_normal_cos;
                }
            }
        }
    }
    for (k = 0; k < DN_CH; k++) {
        tg_real *c = channel(io, k);
        tg_real v = c ? c[i] : 0;
        if (c && ok) c[i] = v = tg_lerp(prev[(size_t)k * n + s], v, p->alpha);   /* exponential average */
        next[(size_t)k * n + i] = v;
    }
    if (ok && io->bent_x && io->bent_y && io->bent_z) {
        tg_vec3 b = tgi_v3_normalize_or(tg_v3(io->bent_x[i], io->bent_y[i], io->bent_z[i]), tg_v3(io->nx[i], io->ny[i], io->nz[i]));
        io->bent_x[i] = b.x; io->bent_y[i] = b.y; io->bent_z[i] = b.z;
    }
    if (ok && io->cone) io->cone[i] = tg_acos(tg_sub(TG_ONE, io->ao[i]));   /* HBIL eq. 12 */
    next[7 * n + i] = sky ? 0 : io->depth[i];
    next[8 * n + i] = io->nx[i]; next[9 * n + i] = io->ny[i]; next[10 * n + i] = io->nz[i];
}

void tgi_temporal_rows(const tgi_denoise_params *p, const tgi_denoise_io *io, void *state,
                      const tgi_view *prev_view, const tgi_view *view, int frame, int reset,
                      int y0, int y1)
{
    size_t half = (size_t)io->width * io->height * TM_CH;
    tg_real *a = (tg_real *)state, *b = a + half;
    const tg_real *prev = (frame & 1) ? b : a;
    tg_real *next = (frame & 1) ? a : b;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > io->height) y1 = io->height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < io->width; x++)
            temporal_pixel(p, io, prev, next, prev_view, view, reset, x, y);
}
