/* SPDX-License-Identifier: MIT */
/*
 * pushpull.c - push/pull hole filling (Kraus 2009; HBIL sec. 3.2).
 * Level 0 is the caller's image with weights 1 (a value) or 0 (a hole);
 * levels 1.. live in the scratch.  See pushpull.h.
 */
#include "../tinygi.h"
#include "pushpull.h"

#define MAX_LEVELS 32

#if TG_WIDE_STORAGE
typedef tg_real pp_weight;
static tg_real weight_get(const pp_weight *w, size_t i) { return w[i]; }
static void weight_set(pp_weight *w, size_t i, tg_real v) { w[i] = v; }
#else
typedef uint8_t pp_weight;
static tg_real weight_get(const pp_weight *w, size_t i) { return tgi_unorm8_unpack(w[i]); }
static void weight_set(pp_weight *w, size_t i, tg_real v) { w[i] = tgi_unorm8_pack(v); }
#endif

typedef struct pp_level {
    int w, h;
    tgi_rgb c;          /* mean colour of the valid texels below */
    pp_weight *wt;      /* their weight, clamped to 1 */
} pp_level;

static int half_up(int n) { return (n + 1) / 2; }

/* Bytes of one level of n texels (16-byte aligned parts, as level_carve
 * lays them); *overflow set on overflow. */
static size_t level_bytes(size_t n, int *overflow)
{
    size_t c, w;
    if (tg_size_mul(n, TGI_RGB_PIXEL_BYTES, &c) || tg_size_mul(n, sizeof(pp_weight), &w) ||
        tg_size_add(c, 15, &c) || tg_size_add(w, 15, &w) || tg_size_add(c & ~(size_t)15, w & ~(size_t)15, &c)) {
        *overflow = 1;
        return 0;
    }
    return c;
}

/* Point level l's planes at `base` (n texels). */
static void level_carve(pp_level *l, unsigned char *base, size_t n)
{
    l->wt = (pp_weight *)(void *)(base + tgi_rgb_carve(&l->c, n, base));
}

/* The chain of a w x h image: levels 1.. (count returned), carved from
 * scratch when given; *bytes their size. */
static int levels_layout(int w, int h, unsigned char *scratch, pp_level *lv, size_t *bytes)
{
    size_t total = 0;
    int n = 0, overflow = 0;
    while ((w > 1 || h > 1) && n < MAX_LEVELS) {
        size_t texels, b;
        w = half_up(w);
        h = half_up(h);
        texels = (size_t)w * (size_t)h;
        b = level_bytes(texels, &overflow);
        if (lv) {
            lv[n].w = w;
            lv[n].h = h;
            if (scratch) level_carve(&lv[n], scratch + total, texels);
        }
        if (overflow || tg_size_add(total, b, &total)) { *bytes = SIZE_MAX; return 0; }
        n++;
    }
    *bytes = total;
    return n;
}

size_t tgi_pushpull_bytes(int w, int h)
{
    size_t bytes;
    if (w < 0 || h < 0) return SIZE_MAX;
    levels_layout(w, h, NULL, NULL, &bytes);
    return bytes;
}

/* Push one level: a 2x2 box over the weighted texels of the finer w x h
 * level, its values c and weights wt.  Level 0, the image, has no weights
 * (wt NULL): a value weighs 1, a hole 0, and the value enters unscaled. */
static void push_level(const tgi_rgb *c, const pp_weight *wt, int w, int h, const pp_level *coarse)
{
    int x, y, dx, dy;
    for (y = 0; y < coarse->h; y++)
        for (x = 0; x < coarse->w; x++) {
            tg_vec3 s = tg_v3(0, 0, 0);
            tg_real sw = 0;
            size_t o = (size_t)y * (size_t)coarse->w + (size_t)x;
            for (dy = 0; dy < 2; dy++)
                for (dx = 0; dx < 2; dx++) {
                    int fx = 2 * x + dx, fy = 2 * y + dy;
                    size_t t;
                    tg_real wf = TG_ONE;
                    if (fx >= w || fy >= h) continue;
                    t = (size_t)fy * (size_t)w + (size_t)fx;
                    if (wt) {
                        wf = weight_get(wt, t);
                        s = tgi_v3_add(s, tgi_v3_scale(tgi_rgb_get(c, t), wf));
                    } else if (tgi_rgb_is_hole(c, t)) {
                        continue;
                    } else {
                        s = tgi_v3_add(s, tgi_rgb_get(c, t));
                    }
                    sw = tg_add(sw, wf);
                }
            if (sw > 0) {
                tgi_rgb_set(&coarse->c, o, tgi_v3_scale(s, tg_div(TG_ONE, sw)));   /* weighted mean */
                weight_set(coarse->wt, o, tg_min(sw, TG_ONE));                     /* Kraus: clamped to 1 */
            } else {
                tgi_rgb_set(&coarse->c, o, tg_v3(0, 0, 0));
                weight_set(coarse->wt, o, 0);
            }
        }
}

/* Bilinear sample of a coarse level at the centre of fine texel (x, y). */
static tg_vec3 upsample(const pp_level *coarse, int x, int y)
{
    /* fine centre (x + 0.5) / 2 - 0.5 in coarse texel units */
    int cx = (x - 1) >> 1, cy = (y - 1) >> 1, i;
    tg_real fx = (x & 1) ? TG_R(0.25f) : TG_R(0.75f), fy = (y & 1) ? TG_R(0.25f) : TG_R(0.75f);
    int xs[2], ys[2];
    tg_real wx[2], wy[2];
    tg_vec3 out = tg_v3(0, 0, 0);
    xs[0] = cx < 0 ? 0 : cx; xs[1] = cx + 1 >= coarse->w ? coarse->w - 1 : cx + 1;
    ys[0] = cy < 0 ? 0 : cy; ys[1] = cy + 1 >= coarse->h ? coarse->h - 1 : cy + 1;
    wx[0] = tg_sub(TG_ONE, fx); wx[1] = fx;
    wy[0] = tg_sub(TG_ONE, fy); wy[1] = fy;
    for (i = 0; i < 4; i++) {
        size_t t = (size_t)ys[i >> 1] * (size_t)coarse->w + (size_t)xs[i & 1];
        out = tgi_v3_add(out, tgi_v3_scale(tgi_rgb_get(&coarse->c, t), tg_mul(wx[i & 1], wy[i >> 1])));
    }
    return out;
}

/* Pull one level: complete texels of weight < 1 from the coarser level. */
static void pull_level(const pp_level *fine, const pp_level *coarse)
{
    int x, y;
    for (y = 0; y < fine->h; y++)
        for (x = 0; x < fine->w; x++) {
            size_t t = (size_t)y * (size_t)fine->w + (size_t)x;
            tg_real wt = weight_get(fine->wt, t);
            tg_vec3 c, up;
            if (wt >= TG_ONE) continue;
            c = tgi_rgb_get(&fine->c, t);
            up = upsample(coarse, x, y);
            c = tg_v3(tg_lerp(up.x, c.x, wt), tg_lerp(up.y, c.y, wt), tg_lerp(up.z, c.z, wt));  /* w c + (1 - w) c_up */
            tgi_rgb_set(&fine->c, t, c);
            weight_set(fine->wt, t, TG_ONE);
        }
}

void tgi_pushpull_fill(int w, int h, const tgi_rgb *c, void *scratch)
{
    pp_level lv[MAX_LEVELS];
    size_t bytes, i;
    int nl, k, x, y;
    if (w <= 0 || h <= 0) return;
    if (w == 1 && h == 1) {
        if (tgi_rgb_is_hole(c, 0)) tgi_rgb_set(c, 0, tg_v3(0, 0, 0));
        return;
    }
    nl = levels_layout(w, h, (unsigned char *)scratch, lv, &bytes);
    push_level(c, NULL, w, h, &lv[0]);
    for (k = 1; k < nl; k++) push_level(&lv[k - 1].c, lv[k - 1].wt, lv[k - 1].w, lv[k - 1].h, &lv[k]);
    /* the coarsest texel: what weight it has, over black */
    if (weight_get(lv[nl - 1].wt, 0) < TG_ONE) {
        tgi_rgb_set(&lv[nl - 1].c, 0, tgi_v3_scale(tgi_rgb_get(&lv[nl - 1].c, 0), weight_get(lv[nl - 1].wt, 0)));
        weight_set(lv[nl - 1].wt, 0, TG_ONE);
    }
    for (k = nl - 2; k >= 0; k--) pull_level(&lv[k], &lv[k + 1]);
    /* level 0: holes take the upsampled level 1 */
    for (i = 0, y = 0; y < h; y++)
        for (x = 0; x < w; x++, i++)
            if (tgi_rgb_is_hole(c, i)) tgi_rgb_set(c, i, upsample(&lv[0], x, y));
}
