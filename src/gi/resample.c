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
 * as bent normal and no near field.
 */
#include "resample.h"

void tgi_half_size(int w, int h, int *hw, int *hh)
{
    *hw = (w + 1) / 2;
    *hh = (h + 1) / 2;
}

void tgi_downsample_rows(const tg_real *src, int w, int h, tg_real *dst, int y0, int y1)
{
    int hw, hh, x, y;
    tgi_half_size(w, h, &hw, &hh);
    if (y1 > hh) y1 = hh;
    for (y = y0; y < y1; y++) {
        const tg_real *row = src + (size_t)(2 * y) * (size_t)w;
        tg_real *out = dst + (size_t)y * (size_t)hw;
        for (x = 0; x < hw; x++) out[x] = row[2 * x];
    }
}

void tgi_downsample8_rows(const uint8_t *src, int w, int h, uint8_t *dst, int y0, int y1)
{
    int hw, hh, x, y;
    tgi_half_size(w, h, &hw, &hh);
    if (y1 > hh) y1 = hh;
    for (y = y0; y < y1; y++) {
        const uint8_t *row = src + (size_t)(2 * y) * (size_t)w;
        uint8_t *out = dst + (size_t)y * (size_t)hw;
        for (x = 0; x < hw; x++) out[x] = row[2 * x];
    }
}

/* (n . m)^4 for unit normals, 0 when they face apart. */
static tg_real normal_weight(const tgi_upsample_io *io, size_t i, size_t j)
{
    tg_real d = tg_add(tg_add(tg_mul(io->nx[i], io->half_nx[j]), tg_mul(io->ny[i], io->half_ny[j])),
                       tg_mul(io->nz[i], io->half_nz[j]));
    if (d <= 0) return 0;
    d = tg_mul(d, d);
    return tg_mul(d, d);
}

/* 1 - |z_j - z| / (0.1 z), clamped to [0, 1]. */
static tg_real depth_weight(tg_real z, tg_real zj)
{
    tg_real tol = tg_mul(z, TG_R(0.1f));
    tg_real dz = tg_abs(tg_sub(zj, z));
    if (tol <= 0 || dz >= tol) return 0;
    return tg_sub(TG_ONE, tg_div(dz, tol));
}

static void write_open(const tgi_upsample_io *io, size_t i)
{
    io->ao[i] = TG_ONE;
    if (io->bent_x) { io->bent_x[i] = io->nx[i]; io->bent_y[i] = io->ny[i]; io->bent_z[i] = io->nz[i]; }
    if (io->near_r) { io->near_r[i] = 0; io->near_g[i] = 0; io->near_b[i] = 0; }
}

static void upsample_pixel(const tgi_upsample_io *io, int hw, int hh, int x, int y)
{
    size_t i = (size_t)y * (size_t)io->width + (size_t)x, tap[4];
    tg_real wt[4], sum = 0, ao = 0, bx = 0, by = 0, bz = 0, nr = 0, ng = 0, nb = 0;
    int X0 = x >> 1, Y0 = y >> 1, X1 = X0 + (x & 1), Y1 = Y0 + (y & 1), k;
    tg_real half = TG_R(0.5f), floor_w = TG_R(0.015625f);
    if (io->sky && io->sky[i]) { write_open(io, i); return; }
    if (X1 >= hw) X1 = hw - 1;
    if (Y1 >= hh) Y1 = hh - 1;
    tap[0] = (size_t)Y0 * (size_t)hw + (size_t)X0; tap[1] = (size_t)Y0 * (size_t)hw + (size_t)X1;
    tap[2] = (size_t)Y1 * (size_t)hw + (size_t)X0; tap[3] = (size_t)Y1 * (size_t)hw + (size_t)X1;
    /* bilinear: an even coordinate sits on a half-res sample, an odd one halfway */
    wt[0] = tg_mul((x & 1) ? half : TG_ONE, (y & 1) ? half : TG_ONE);
    wt[1] = (x & 1) ? tg_mul(half, (y & 1) ? half : TG_ONE) : 0;
    wt[2] = (y & 1) ? tg_mul((x & 1) ? half : TG_ONE, half) : 0;
    wt[3] = ((x & 1) && (y & 1)) ? tg_mul(half, half) : 0;
    for (k = 0; k < 4; k++) {
        size_t j = tap[k];
        tg_real w;
        if (wt[k] == 0) continue;
        if (io->half_sky && io->half_sky[j]) continue;
        w = tg_mul(wt[k], tg_max(floor_w, tg_mul(depth_weight(io->depth[i], io->half_depth[j]),
                                                  normal_weight(io, i, j))));
        sum = tg_add(sum, w);
        ao = tg_add(ao, tg_mul(w, io->half_ao[j]));
        if (io->bent_x) {   /* the bend (bent - normal) is what carries over (Klehm sec. 3.4) */
            bx = tg_add(bx, tg_mul(w, tg_sub(io->half_bent_x[j], io->half_nx[j])));
            by = tg_add(by, tg_mul(w, tg_sub(io->half_bent_y[j], io->half_ny[j])));
            bz = tg_add(bz, tg_mul(w, tg_sub(io->half_bent_z[j], io->half_nz[j])));
        }
        if (io->near_r) {
            nr = tg_add(nr, tg_mul(w, io->half_near_r[j]));
            ng = tg_add(ng, tg_mul(w, io->half_near_g[j]));
            nb = tg_add(nb, tg_mul(w, io->half_near_b[j]));
        }
    }
    if (sum <= 0) { write_open(io, i); return; }   /* only sky around: treat as open */
    io->ao[i] = tg_saturate(tg_div(ao, sum));
    if (io->bent_x) {
        tg_vec3 n = tg_v3(io->nx[i], io->ny[i], io->nz[i]);
        tg_vec3 b = tgi_v3_add(n, tg_v3(tg_div(bx, sum), tg_div(by, sum), tg_div(bz, sum)));
        tg_real d = tgi_v3_dot(b, n);
        /* keep it in the normal's hemisphere: drop the part below the tangent plane */
        if (d < 0) b = tgi_v3_sub(b, tgi_v3_scale(n, d));
        b = tgi_v3_normalize_or(b, n);
        io->bent_x[i] = b.x; io->bent_y[i] = b.y; io->bent_z[i] = b.z;
    }
    if (io->near_r) {
        io->near_r[i] = tg_max(0, tg_div(nr, sum));
        io->near_g[i] = tg_max(0, tg_div(ng, sum));
        io->near_b[i] = tg_max(0, tg_div(nb, sum));
    }
}

void tgi_upsample_rows(const tgi_upsample_io *io, int y0, int y1)
{
    int hw, hh, x, y;
    tgi_half_size(io->width, io->height, &hw, &hh);
    if (y1 > io->height) y1 = io->height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < io->width; x++) upsample_pixel(io, hw, hh, x, y);
}
