/* SPDX-License-Identifier: MIT */
/*
 * aov.c - reading a rendered frame out, one row at a time: linear values
 * (tg_frame_aov_row, for PFM) or 8-bit RGB for viewing (tg_frame_aov_row8,
 * for PPM and screens), through the G-buffer view and the results' accessors.
 * An AOV whose effect the plan left out reads as 0 (for ao: 1, open; for
 * bent: the normal; for cone: pi/2).
 */
#include <string.h>
#include "frame_internal.h"
#include "../light/tonemap.h"
#include "../ao/ao.h"

#if !TG_NO_COLOR /* the radiance AOVs read 0 in a build without colour (aov_span) */
/* RGB planes (absent: `fallback`) at pixels [i0, i0 + w) of a packed row. */
static void row_rgb(const tgi_rgb *c, const tgi_gview *g, int x0, int y, int w, tg_real *out, tg_real fallback)
{
    int x;
    for (x = 0; x < w; x++) {
        tg_vec3 v = tgi_rgb_present(c) ? tgi_rgb_get(c, tgi_gv_index(g, x0 + x, y)) : tg_v3(fallback, fallback, fallback);
        out[3 * x + 0] = v.x; out[3 * x + 1] = v.y; out[3 * x + 2] = v.z;
    }
}
#endif

/* A G-buffer vector (normal or albedo) of pixels [x0, x0 + w) of row y; 0 on sky. */
static void row_vec(const tgi_gview *g, tg_vec3 (*get)(const tgi_gview *, size_t), int x0, int y, int w, tg_real *out)
{
    int x;
    for (x = 0; x < w; x++) {
        size_t i = tgi_gv_index(g, x0 + x, y);
        tg_vec3 v = tgi_gv_is_sky(g, i) ? tg_v3(0, 0, 0) : get(g, i);
        out[3 * x + 0] = v.x; out[3 * x + 1] = v.y; out[3 * x + 2] = v.z;
    }
}

static void row_bent(const tg_frame *f, int x0, int y, int w, tg_real *out)
{
    const tgi_gview *g = &f->full;
    int x;
    if (TG_NO_BENT_NORMALS || !tgi_gr_has_bent(&f->out)) { row_vec(g, tgi_gv_normal, x0, y, w, out); return; }
    for (x = 0; x < w; x++) {
        size_t i = tgi_gv_index(g, x0 + x, y);
        tg_vec3 v = tgi_gv_is_sky(g, i) ? tg_v3(0, 0, 0) : tgi_gr_bent(&f->out, i);
        out[3 * x + 0] = v.x; out[3 * x + 1] = v.y; out[3 * x + 2] = v.z;
    }
}

/* The AO as its AOV reads it: with request.ao_multibounce, GTAO's
 * multi-bounce fit (Jimenez et al. 2016, eq. 10) with the albedo's Rec. 709
 * luminance, the material's (the AOV has one channel). */
static tg_real ao_out(const tg_frame *f, size_t i)
{
    tg_real ao = tgi_gr_ao(&f->out, i);
    tg_vec3 a;
    if (!tgi_frame_ao_multibounce(f) || tgi_gv_is_sky(&f->full, i)) return ao;
    a = tgi_gv_albedo(&f->full, i);
    return tgi_ao_multibounce(ao, tg_add(tg_add(tg_mul(TG_R(0.2126f), a.x), tg_mul(TG_R(0.7152f), a.y)),
                                         tg_mul(TG_R(0.0722f), a.z)));
}

/* AO (1, open, without a GI pass) or cone (pi/2 without one). */
static void row_scalar(const tg_frame *f, tg_aov aov, int x0, int y, int w, tg_real *out)
{
    const tgi_gview *g = &f->full;
    int x;
    for (x = 0; x < w; x++) {
        size_t i = tgi_gv_index(g, x0 + x, y);
        if (aov == TG_AOV_DEPTH) out[x] = tgi_gv_depth(g, i);
        else if (aov == TG_AOV_AO) out[x] = f->out.ao ? ao_out(f, i) : TG_ONE;
        else out[x] = !TG_NO_BENT_NORMALS && f->out.ao ? tgi_gr_cone(&f->out, i) : TG_HALF_PI;
    }
}

#if !TG_NO_TEMPORAL /* no motion vectors with TG_NO_TEMPORAL: the AOV reads 0 (aov_span) */
/* Motion: the offset to last frame's position, z = validity. */
static void row_motion(const tg_frame *f, int x0, int y, int w, tg_real *out)
{
    const tgi_gbuffer *g = &f->gb;
    size_t i0 = (size_t)y * (size_t)f->width + (size_t)x0;
    int x;
    for (x = 0; x < w; x++) {
        size_t i = i0 + (size_t)x;
        tg_real px = tg_add(tg_from_int(x0 + x), TG_R(0.5f)), py = tg_add(tg_from_int(y), TG_R(0.5f));
        int valid = g->motion_x && g->motion_x[i] != TG_REAL_MIN;
        out[3 * x + 0] = valid ? tg_sub(g->motion_x[i], px) : 0;
        out[3 * x + 1] = valid ? tg_sub(g->motion_y[i], py) : 0;
        out[3 * x + 2] = valid ? TG_ONE : 0;
    }
}
#endif

#if !TG_NO_COLOR
/* E_direct as its AOV reads it: its own plane when asked (else it lives in a
 * radiance slot, composed over; frame_internal.h), NULL otherwise. */
static const tgi_rgb *direct_plane(const tg_frame *f)
{
    return (f->effects & TG_EFFECT_DIRECT) && (f->request.aovs & (1u << TG_AOV_DIRECT)) ? &f->direct : NULL;
}
#endif

/* Pixels [x0, x0 + w) of row y.  In a build with TG_NO_COLOR or
 * TG_NO_TEMPORAL (tinygi.h "FEATURE SWITCHES") the planes of the AOVs it
 * leaves out are never there: they read 0, as an absent plane reads. */
static void aov_span(const tg_frame *f, tg_aov aov, int y, int x0, int w, tg_real *out)
{
    const tgi_gview *g = &f->full;
    switch (aov) {
#if TG_NO_COLOR
    case TG_AOV_COLOR: case TG_AOV_NEAR: case TG_AOV_FAR: case TG_AOV_DIRECT: case TG_AOV_IRRADIANCE:
        memset(out, 0, 3 * (size_t)w * sizeof(tg_real));
        break;
#else
    case TG_AOV_COLOR: row_rgb(&f->color, g, x0, y, w, out, 0); break;
#endif
    case TG_AOV_DEPTH: case TG_AOV_AO: case TG_AOV_CONE: row_scalar(f, aov, x0, y, w, out); break;
    case TG_AOV_NORMAL: row_vec(g, tgi_gv_normal, x0, y, w, out); break;
    case TG_AOV_ALBEDO: row_vec(g, tgi_gv_albedo, x0, y, w, out); break;
    case TG_AOV_BENT: row_bent(f, x0, y, w, out); break;
#if !TG_NO_COLOR
    case TG_AOV_NEAR: row_rgb(&f->out.near, g, x0, y, w, out, 0); break;
    case TG_AOV_FAR: row_rgb(&f->far, g, x0, y, w, out, 0); break;
    case TG_AOV_DIRECT: row_rgb(direct_plane(f), g, x0, y, w, out, 0); break;
    case TG_AOV_IRRADIANCE: row_rgb(&f->irradiance, g, x0, y, w, out, 0); break;
#endif
#if TG_NO_TEMPORAL
    case TG_AOV_MOTION: memset(out, 0, 3 * (size_t)w * sizeof(tg_real)); break;
#else
    case TG_AOV_MOTION: row_motion(f, x0, y, w, out); break;
#endif
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
    if (!f || !out) return TG_ERR_INPUT;
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
#if !TG_NO_COLOR /* the plan refuses these AOVs with TG_NO_COLOR=1 (tinygi.h "FEATURE SWITCHES") */
    case TG_AOV_COLOR: case TG_AOV_NEAR: case TG_AOV_FAR: case TG_AOV_DIRECT: case TG_AOV_IRRADIANCE: {
        /* HDR: exposure, tonemapper, sRGB */
        tg_real r[SPAN], g[SPAN], b[SPAN];
        tg_real exposure = f->request.exposure;
        for (x = 0; x < w; x++) { r[x] = row[3 * x]; g[x] = row[3 * x + 1]; b[x] = row[3 * x + 2]; }
        if (aov != TG_AOV_COLOR) exposure = tg_mul(exposure, TG_INV_PI); /* irradiance -> radiance of a white surface */
        tgi_tonemap_row8(r, g, b, w, exposure, rgb);
        return;
    }
#endif
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
    if (!f || !rgb) return TG_ERR_INPUT;
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
