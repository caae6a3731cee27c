/* SPDX-License-Identifier: MIT */
/*
 * aov.c - reading a rendered frame out, one row at a time: linear values
 * (tg_frame_aov_row, for PFM) or 8-bit RGB for viewing (tg_frame_aov_row8,
 * for PPM and screens).  An AOV whose effect the plan left out reads as 0
 * (for ao: 1, open; for bent: the normal; for cone: pi/2).
 */
#include <string.h>
#include "frame_internal.h"
#include "../light/tonemap.h"

static tg_real at(const tg_real *buf, size_t i, tg_real fallback)
{
    return buf ? buf[i] : fallback;
}

static void row_rgb(const tgi_rgb c, size_t i0, int w, tg_real *out, tg_real fallback)
{
    int x;
    for (x = 0; x < w; x++) {
        out[3 * x + 0] = at(c.r, i0 + (size_t)x, fallback);
        out[3 * x + 1] = at(c.g, i0 + (size_t)x, fallback);
        out[3 * x + 2] = at(c.b, i0 + (size_t)x, fallback);
    }
}

static tgi_rgb gb_rgb(tg_real *r, tg_real *g, tg_real *b)
{
    tgi_rgb c;
    c.r = r; c.g = g; c.b = b;
    return c;
}

/* Pixels [x0, x0 + w) of row y. */
static void aov_span(const tg_frame *f, tg_aov aov, int y, int x0, int w, tg_real *out)
{
    const tgi_gbuffer *g = &f->gb;
    size_t i0 = (size_t)y * (size_t)f->width + (size_t)x0;
    int x;
    switch (aov) {
    case TG_AOV_COLOR: row_rgb(f->color, i0, w, out, 0); break;
    case TG_AOV_DEPTH: for (x = 0; x < w; x++) out[x] = g->depth[i0 + (size_t)x]; break;
    case TG_AOV_NORMAL: row_rgb(gb_rgb(g->nx, g->ny, g->nz), i0, w, out, 0); break;
    case TG_AOV_ALBEDO: row_rgb(gb_rgb(g->albedo_r, g->albedo_g, g->albedo_b), i0, w, out, 0); break;
    case TG_AOV_AO: for (x = 0; x < w; x++) out[x] = at(f->ao, i0 + (size_t)x, TG_ONE); break;
    case TG_AOV_BENT:
        if (f->bent.r) row_rgb(f->bent, i0, w, out, 0);
        else row_rgb(gb_rgb(g->nx, g->ny, g->nz), i0, w, out, 0);
        break;
    case TG_AOV_CONE: for (x = 0; x < w; x++) out[x] = at(f->cone, i0 + (size_t)x, TG_HALF_PI); break;
    case TG_AOV_NEAR: row_rgb(f->near, i0, w, out, 0); break;
    case TG_AOV_FAR: row_rgb(f->far, i0, w, out, 0); break;
    case TG_AOV_DIRECT: row_rgb(f->direct, i0, w, out, 0); break;
    case TG_AOV_IRRADIANCE: row_rgb(f->irradiance, i0, w, out, 0); break;
    case TG_AOV_MOTION:
        for (x = 0; x < w; x++) {
            size_t i = i0 + (size_t)x;
            tg_real px = tg_add(tg_from_int(x0 + x), TG_R(0.5f)), py = tg_add(tg_from_int(y), TG_R(0.5f));
            int valid = g->motion_x && g->motion_x[i] != TG_REAL_MIN;
            out[3 * x + 0] = valid ? tg_sub(g->motion_x[i], px) : 0;
            out[3 * x + 1] = valid ? tg_sub(g->motion_y[i], py) : 0;
            out[3 * x + 2] = valid ? TG_ONE : 0;
        }
        break;
    default: memset(out, 0, (size_t)w * sizeof(tg_real)); break;
    }
}

/* Rows outside [0, height) are refused: zeros, never a read outside. */
static int row_outside(const tg_frame *f, int y)
{
    return y < 0 || y >= f->height;
}

tg_status tg_frame_aov_row(const tg_frame *f, tg_aov aov, int y, tg_real *out)
{
    if (row_outside(f, y)) {
        memset(out, 0, (size_t)f->width * (size_t)tg_aov_channels(aov) * sizeof(tg_real));
        return TG_ERR_INPUT;
    }
    aov_span(f, aov, y, 0, f->width, out);
    return TG_OK;
}

static uint8_t unit_to_byte(tg_real v)
{
    return (uint8_t)tg_round_int(tg_mul(tg_saturate(v), TG_R(255.0f)));
}

#define SPAN 32

/* Pixels [x0, x0 + w) of row y as 8-bit RGB, w <= SPAN. */
static void span8(const tg_frame *f, tg_aov aov, int y, int x0, int w, uint8_t *rgb)
{
    tg_real row[3 * SPAN];
    int x, c;
    aov_span(f, aov, y, x0, w, row);
    switch (aov) {
    case TG_AOV_COLOR: case TG_AOV_NEAR: case TG_AOV_FAR: case TG_AOV_DIRECT: case TG_AOV_IRRADIANCE: {
        /* HDR: exposure, tonemapper, sRGB */
        tg_real r[SPAN], g[SPAN], b[SPAN];
        tg_real exposure = f->plan.request.exposure;
        for (x = 0; x < w; x++) { r[x] = row[3 * x]; g[x] = row[3 * x + 1]; b[x] = row[3 * x + 2]; }
        if (aov != TG_AOV_COLOR) exposure = tg_mul(exposure, TG_INV_PI); /* irradiance -> radiance of a white surface */
        tgi_tonemap_row8(r, g, b, w, exposure, rgb);
        return;
    }
    case TG_AOV_ALBEDO:
        for (x = 0; x < 3 * w; x++) rgb[x] = tgi_srgb8(row[x]);
        return;
    case TG_AOV_NORMAL: case TG_AOV_BENT: case TG_AOV_MOTION:
        /* 0.5 v + 0.5 (motion: 1/16 pixel per level around grey) */
        for (x = 0; x < 3 * w; x++) {
            tg_real v = aov == TG_AOV_MOTION ? tg_ldexp(row[x], -4) : row[x];
            rgb[x] = unit_to_byte(tg_add(tg_ldexp(v, -1), TG_R(0.5f)));
        }
        return;
    default:
        for (x = 0; x < w; x++) {
            tg_real v = row[x];
            if (aov == TG_AOV_DEPTH) v = f->depth_max > 0 ? tg_div(v, f->depth_max) : 0;
            if (aov == TG_AOV_CONE) v = tg_div(v, TG_HALF_PI);
            for (c = 0; c < 3; c++) rgb[3 * x + c] = unit_to_byte(v);
        }
        return;
    }
}

tg_status tg_frame_aov_row8(const tg_frame *f, tg_aov aov, int y, uint8_t *rgb)
{
    int x0;
    if (row_outside(f, y)) {
        memset(rgb, 0, (size_t)f->width * 3u);
        return TG_ERR_INPUT;
    }
    for (x0 = 0; x0 < f->width; x0 += SPAN) {
        int w = f->width - x0 < SPAN ? f->width - x0 : SPAN;
        span8(f, aov, y, x0, w, rgb + 3 * x0);
    }
    return TG_OK;
}
