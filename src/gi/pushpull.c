/* SPDX-License-Identifier: MIT */
/*
 * pushpull.c - push/pull hole filling (Kraus 2009; HBIL sec. 3.2).
 * Level 0 is the caller's image with weights 1 (valid) or 0 (hole); levels
 * 1.. live in the scratch as (r, g, b, w) quadruples.
 */
#include <string.h>
#include "../tinygi.h"
#include "pushpull.h"

static int half_up(int n) { return (n + 1) / 2; }

size_t tgi_pushpull_bytes(int w, int h)
{
    size_t total = 0, level;
    while (w > 1 || h > 1) {
        w = half_up(w);
        h = half_up(h);
        if (tg_size_mul((size_t)w, (size_t)h, &level) || tg_size_mul(level, 4 * sizeof(tg_real), &level)
            || tg_size_add(total, level, &total))
            return SIZE_MAX;
    }
    return total;
}

/* Push one level: a 2x2 box over the weighted texels of the finer level. */
static void push_level(const tg_real *fine, int fw, int fh, tg_real *coarse, int cw, int ch)
{
    int x, y, dx, dy, k;
    for (y = 0; y < ch; y++)
        for (x = 0; x < cw; x++) {
            tg_real s[4] = { 0, 0, 0, 0 };
            tg_real *o = coarse + ((size_t)y * cw + x) * 4;
            for (dy = 0; dy < 2; dy++)
                for (dx = 0; dx < 2; dx++) {
                    int fx = 2 * x + dx, fy = 2 * y + dy;
                    const tg_real *t;
                    if (fx >= fw || fy >= fh) continue;
                    t = fine + ((size_t)fy * fw + fx) * 4;
                    for (k = 0; k < 3; k++) s[k] = tg_add(s[k], tg_mul(t[k], t[3]));
                    s[3] = tg_add(s[3], t[3]);
                }
            if (s[3] > 0) {
                for (k = 0; k < 3; k++) o[k] = tg_div(s[k], s[3]);   /* weighted mean of valid texels */
                o[3] = tg_min(s[3], TG_ONE);                        /* Kraus: weights clamped to 1 */
            } else {
                o[0] = o[1] = o[2] = o[3] = 0;
            }
        }
}

/* Bilinear sample of a coarse level at the centre of fine texel (x, y). */
static void upsample(const tg_real *coarse, int cw, int ch, int x, int y, tg_real out[3])
{
    /* fine centre (x + 0.5) / 2 - 0.5 in coarse texel units */
    int cx = (x - 1) >> 1, cy = (y - 1) >> 1, k, i;
    tg_real fx = (x & 1) ? TG_R(0.25f) : TG_R(0.75f), fy = (y & 1) ? TG_R(0.25f) : TG_R(0.75f);
    int xs[2], ys[2];
    tg_real wx[2], wy[2];
    xs[0] = cx < 0 ? 0 : cx; xs[1] = cx + 1 >= cw ? cw - 1 : cx + 1;
    ys[0] = cy < 0 ? 0 : cy; ys[1] = cy + 1 >= ch ? ch - 1 : cy + 1;
    wx[0] = tg_sub(TG_ONE, fx); wx[1] = fx;
    wy[0] = tg_sub(TG_ONE, fy); wy[1] = fy;
    for (k = 0; k < 3; k++) out[k] = 0;
    for (i = 0; i < 4; i++) {
        const tg_real *t = coarse + ((size_t)ys[i >> 1] * cw + xs[i & 1]) * 4;
        tg_real wgt = tg_mul(wx[i & 1], wy[i >> 1]);
        for (k = 0; k < 3; k++) out[k] = tg_add(out[k], tg_mul(t[k], wgt));
    }
}

/* Pull one level: complete texels of weight < 1 from the coarser level. */
static void pull_level(tg_real *fine, int fw, int fh, const tg_real *coarse, int cw, int ch)
{
    int x, y, k;
    for (y = 0; y < fh; y++)
        for (x = 0; x < fw; x++) {
            tg_real *t = fine + ((size_t)y * fw + x) * 4, up[3];
            if (t[3] >= TG_ONE) continue;
            upsample(coarse, cw, ch, x, y, up);
            for (k = 0; k < 3; k++) t[k] = tg_lerp(up[k], t[k], t[3]);  /* w c + (1 - w) c_up */
            t[3] = TG_ONE;
        }
}

void tgi_pushpull_fill(int w, int h, tg_real *r, tg_real *g, tg_real *b,
                      const uint8_t *valid, void *scratch)
{
    tg_real *lv = (tg_real *)scratch, *l1;
    int lw = half_up(w), lh = half_up(h), x, y;
    size_t i, n = (size_t)w * h;
    if (w <= 0 || h <= 0) return;
    if (w == 1 && h == 1) { if (!valid[0]) r[0] = g[0] = b[0] = 0; return; }
    /* level 1 straight from the image (weights 0/1) */
    l1 = lv;
    for (y = 0; y < lh; y++)
        for (x = 0; x < lw; x++) {
            tg_real s[4] = { 0, 0, 0, 0 }, *o = l1 + ((size_t)y * lw + x) * 4;
            int dx, dy;
            for (dy = 0; dy < 2; dy++)
                for (dx = 0; dx < 2; dx++) {
                    int fx = 2 * x + dx, fy = 2 * y + dy;
                    size_t j;
                    if (fx >= w || fy >= h) continue;
                    j = (size_t)fy * w + fx;
                    if (!valid[j]) continue;
                    s[0] = tg_add(s[0], r[j]); s[1] = tg_add(s[1], g[j]); s[2] = tg_add(s[2], b[j]);
                    s[3] = tg_add(s[3], TG_ONE);
                }
            if (s[3] > 0) {
                o[0] = tg_div(s[0], s[3]); o[1] = tg_div(s[1], s[3]); o[2] = tg_div(s[2], s[3]);
                o[3] = TG_ONE;
            } else o[0] = o[1] = o[2] = o[3] = 0;
        }
    /* push down to 1x1, then pull back up */
    {
        tg_real *levels[32];
        int ws[32], hs[32], nl = 1, k;
        levels[0] = l1; ws[0] = lw; hs[0] = lh;
        while ((ws[nl - 1] > 1 || hs[nl - 1] > 1) && nl < 32) {
            levels[nl] = levels[nl - 1] + (size_t)ws[nl - 1] * hs[nl - 1] * 4;
            ws[nl] = half_up(ws[nl - 1]); hs[nl] = half_up(hs[nl - 1]);
            push_level(levels[nl - 1], ws[nl - 1], hs[nl - 1], levels[nl], ws[nl], hs[nl]);
            nl++;
        }
        if (levels[nl - 1][3] < TG_ONE) {
            tg_real *t = levels[nl - 1];
            t[0] = tg_mul(t[0], t[3]); t[1] = tg_mul(t[1], t[3]); t[2] = tg_mul(t[2], t[3]);
            t[3] = TG_ONE;
        }
        for (k = nl - 2; k >= 0; k--) pull_level(levels[k], ws[k], hs[k], levels[k + 1], ws[k + 1], hs[k + 1]);
        /* level 0: holes take the upsampled level 1 */
        for (i = 0; i < n; i++) {
            tg_real up[3];
            if (valid[i]) continue;
            upsample(l1, lw, lh, (int)(i % (size_t)w), (int)(i / (size_t)w), up);
            r[i] = up[0]; g[i] = up[1]; b[i] = up[2];
        }
    }
}
