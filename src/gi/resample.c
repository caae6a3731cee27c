/* SPDX-License-Identifier: MIT */
/*
 * resample.c - quarter resolution for the GI kernel.
 *
 * The horizon kernel runs on a quarter of the pixels (half width, half
 * height): the G-buffer is point-sampled down (half-res pixel (X, Y) is
 * full-res pixel (2X, 2Y), so depth and normals stay those of a real
 * surface, never an average across an edge), the 4x4 interleaved kernel runs
 * there, and its results come back up by a joint bilateral upsample: the
 * bilinear weights of the (up to) 2x2 half-res neighbours, each times a depth
 * weight 1 - |z_j - z| / (0.1 z) and a normal weight (n . n_j)^4, floored
 * at 1/64 so a pixel always gets a value.  The bent normal is carried as its
 * bend, bent - normal, added to this pixel's own normal and kept in its
 * hemisphere.  Sky pixels get AO 1, the normal
 * as bent normal (0 on sky) and no near field.
 */
#include "resample.h"

void tgi_half_size(int w, int h, int *hw, int *hh)
{
    *hw = (w + 1) / 2;
    *hh = (h + 1) / 2;
}

void tgi_downsample_rows(const tgi_gview *full, const tgi_gbuffer *half, const tgi_rgb *src,
                         const tgi_rgb *half_src, int y0, int y1)
{
    int hw, hh, x, y, with_src = tgi_rgb_present(src) && tgi_rgb_present(half_src);
    tgi_half_size(full->width, full->height, &hw, &hh);
    if (y1 > hh) y1 = hh;
    for (y = y0; y < y1; y++)
        for (x = 0; x < hw; x++) {
            size_t i = tgi_gv_index(full, 2 * x, 2 * y), j = (size_t)y * (size_t)hw + (size_t)x;
            tgi_gview_copy_pixel(half, j, full, i);
            if (with_src) tgi_rgb_set(half_src, j, tgi_rgb_get(src, i));
        }
}

/* (n . m)^4 for unit normals, 0 when they face apart. */
static tg_real upsample_normal_weight(tg_vec3 n, tg_vec3 m)
{
    tg_real d = tg_add(tg_add(tg_mul(n.x, m.x), tg_mul(n.y, m.y)), tg_mul(n.z, m.z));
    if (d <= 0) return 0;
    d = tg_mul(d, d);
    return tg_mul(d, d);
}

/* 1 - |z_j - z| / (0.1 z), clamped to [0, 1]. */
static tg_real upsample_depth_weight(tg_real z, tg_real zj)
{
    tg_real tol = tg_mul(z, TG_R(0.1f));
    tg_real dz = tg_abs(tg_sub(zj, z));
    if (tol <= 0 || dz >= tol) return 0;
    return tg_sub(TG_ONE, tg_div(dz, tol));
}

/* Sky, or only sky around: open (AO 1, the normal as bent normal, no near field). */
static tgi_gr_value upsample_open(const tgi_gview *full, size_t i)
{
    tgi_gr_value v;
    v.ao = TG_ONE;
    v.bent = tgi_gv_is_sky(full, i) ? tg_v3(0, 0, 0) : tgi_gv_normal(full, i);
    v.near = tg_v3(0, 0, 0);
    return v;
}

/* The (up to) 2x2 half-res neighbours of full-res (x, y) and their bilinear
 * weights: an even coordinate sits on a half-res sample, an odd one halfway. */
static void bilinear_taps(const tgi_gview *half, int x, int y, size_t tap[4], tg_real wt[4])
{
    int X0 = x >> 1, Y0 = y >> 1, X1 = X0 + (x & 1), Y1 = Y0 + (y & 1);
    tg_real h = TG_R(0.5f);
    if (X1 >= half->width) X1 = half->width - 1;
    if (Y1 >= half->height) Y1 = half->height - 1;
    tap[0] = tgi_gv_index(half, X0, Y0); tap[1] = tgi_gv_index(half, X1, Y0);
    tap[2] = tgi_gv_index(half, X0, Y1); tap[3] = tgi_gv_index(half, X1, Y1);
    wt[0] = tg_mul((x & 1) ? h : TG_ONE, (y & 1) ? h : TG_ONE);
    wt[1] = (x & 1) ? tg_mul(h, (y & 1) ? h : TG_ONE) : 0;
    wt[2] = (y & 1) ? tg_mul((x & 1) ? h : TG_ONE, h) : 0;
    wt[3] = ((x & 1) && (y & 1)) ? tg_mul(h, h) : 0;
}

tgi_gr_value tgi_upsample_pixel(const tgi_gview *full, const tgi_gview *half, const tgi_gresult *hr, int x, int y)
{
    size_t i = tgi_gv_index(full, x, y), tap[4];
    tg_real wt[4], sum = 0, ao = 0, floor_w = TG_R(0.015625f);
    tg_vec3 n, bend = tg_v3(0, 0, 0), near = tg_v3(0, 0, 0);
    int k, want_bent = tgi_gr_has_bent(hr), want_near = tgi_gr_has_near(hr);
    tgi_gr_value v;
    if (tgi_gv_is_sky(full, i)) return upsample_open(full, i);
    n = tgi_gv_normal(full, i);
    bilinear_taps(half, x, y, tap, wt);
    for (k = 0; k < 4; k++) {
        size_t j = tap[k];
        tg_real w;
        tg_vec3 nj;
        if (wt[k] == 0) continue;
        if (tgi_gv_is_sky(half, j)) continue;
        nj = tgi_gv_normal(half, j);
        w = tg_mul(wt[k], tg_max(floor_w, tg_mul(upsample_depth_weight(tgi_gv_depth(full, i), tgi_gv_depth(half, j)),
                                                  upsample_normal_weight(n, nj))));
        sum = tg_add(sum, w);
        ao = tg_add(ao, tg_mul(w, tgi_gr_ao(hr, j)));
        if (want_bent) {   /* the bend (bent - normal) is what carries over (Klehm sec. 3.4) */
            tg_vec3 b = tgi_gr_bent(hr, j);
            bend = tg_v3(tg_add(bend.x, tg_mul(w, tg_sub(b.x, nj.x))), tg_add(bend.y, tg_mul(w, tg_sub(b.y, nj.y))),
                         tg_add(bend.z, tg_mul(w, tg_sub(b.z, nj.z))));
        }
        if (want_near) {
            tg_vec3 e = tgi_gr_near(hr, j);
            near = tg_v3(tg_add(near.x, tg_mul(w, e.x)), tg_add(near.y, tg_mul(w, e.y)), tg_add(near.z, tg_mul(w, e.z)));
        }
    }
    if (sum <= 0) return upsample_open(full, i);   /* only sky around: treat as open */
    v.ao = tg_saturate(tg_div(ao, sum));
    v.bent = n;
    if (want_bent) {
        tg_vec3 b = tgi_v3_add(n, tg_v3(tg_div(bend.x, sum), tg_div(bend.y, sum), tg_div(bend.z, sum)));
        tg_real d = tgi_v3_dot(b, n);
        /* keep it in the normal's hemisphere: drop the part below the tangent plane */
        if (d < 0) b = tgi_v3_sub(b, tgi_v3_scale(n, d));
        v.bent = tgi_v3_normalize_or(b, n);
    }
    v.near = want_near ? tg_v3(tg_max(0, tg_div(near.x, sum)), tg_max(0, tg_div(near.y, sum)), tg_max(0, tg_div(near.z, sum)))
                       : tg_v3(0, 0, 0);
    return v;
}

void tgi_upsample_rows(const tgi_gview *full, const tgi_gview *half, const tgi_gresult *half_res,
                       const tgi_gresult *out, int y0, int y1)
{
    int x, y;
    if (y1 > full->height) y1 = full->height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < full->width; x++) {
            tgi_gr_value v = tgi_upsample_pixel(full, half, half_res, x, y);
            tgi_gr_put(out, tgi_gv_index(full, x, y), &v);
        }
}
