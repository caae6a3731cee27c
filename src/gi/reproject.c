/* SPDX-License-Identifier: MIT */
/*
 * reproject.c - scatter (z-buffered) and gather reprojection of last
 * frame's radiance (HBIL sec. 3.2).  See reproject.h.
 */
#include <string.h>
#include "../tinygi.h"
#include "reproject.h"

#define NO_SOURCE (-1)

typedef struct scatter_buf { tg_real *z; int32_t *src; } scatter_buf;

static scatter_buf buf_of(const tgi_reproject_io *io, void *scratch)
{
    scatter_buf b;
    size_t n = (size_t)io->width * io->height;
    b.z = (tg_real *)scratch;
    b.src = (int32_t *)(void *)((unsigned char *)scratch + ((n * sizeof(tg_real) + 15) & ~(size_t)15));
    return b;
}

size_t tgi_reproject_bytes(int w, int h)
{
    size_t n, z, idx;
    if (w < 0 || h < 0 || tg_size_mul((size_t)w, (size_t)h, &n) || tg_size_mul(n, sizeof(tg_real), &z)
        || tg_size_add(z, 15, &z) || tg_size_mul(n, sizeof(int32_t), &idx) || tg_size_add(z & ~(size_t)15, idx, &z))
        return SIZE_MAX;
    return z;
}

void tgi_reproject_clear(const tgi_reproject_io *io, void *scratch)
{
    scatter_buf b = buf_of(io, scratch);
    size_t i, n = (size_t)io->width * io->height;
    for (i = 0; i < n; i++) { b.z[i] = TG_REAL_MAX; b.src[i] = NO_SOURCE; }
}

void tgi_reproject_scatter_rows(const tgi_reproject_io *io, void *scratch, int y0, int y1)
{
    scatter_buf b = buf_of(io, scratch);
    int x, y, w = io->width, h = io->height;
    if (!io->prev_r || !io->prev_g || !io->prev_b || !io->prev_depth) return;   /* camera cut */
    if (y0 < 0) y0 = 0;
    if (y1 > h) y1 = h;
    for (y = y0; y < y1; y++)
        for (x = 0; x < w; x++) {
            int32_t i = y * w + x;
            tg_real sx, sy;
            tg_vec3 pv, pw, cv;
            int dx, dy;
            size_t d;
            if ((io->prev_sky && io->prev_sky[i]) || io->prev_depth[i] <= 0) continue;
            pv = tgi_view_unproject(io->prev_view, tg_add(tg_from_int(x), TG_R(0.5f)),
                                   tg_add(tg_from_int(y), TG_R(0.5f)), io->prev_depth[i]);
            pw = tgi_view_view_to_world(io->prev_view, pv);
            cv = tgi_view_world_to_view(io->view, pw);
            if (cv.z <= io->view->znear || cv.z <= 0) continue;     /* behind the new camera */
            tgi_view_project(io->view, cv, &sx, &sy);
            dx = tg_to_int(sx);
            dy = tg_to_int(sy);
            if (dx < 0 || dy < 0 || dx >= w || dy >= h) continue;
            d = (size_t)dy * w + dx;
            /* temporary z-buffer keeps the nearest (HBIL sec. 3.2); ties: lowest source */
            if (cv.z < b.z[d] || (cv.z == b.z[d] && i < b.src[d])) { b.z[d] = cv.z; b.src[d] = i; }
        }
}

void tgi_reproject_resolve_rows(const tgi_reproject_io *io, const void *scratch, int y0, int y1)
{
    scatter_buf b = buf_of(io, (void *)(uintptr_t)scratch);
    int x, y, w = io->width;
    if (y0 < 0) y0 = 0;
    if (y1 > io->height) y1 = io->height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < w; x++) {
            size_t d = (size_t)y * w + x;
            int32_t s = io->prev_r ? b.src[d] : NO_SOURCE;
            if (s == NO_SOURCE) {
                io->out_r[d] = io->out_g[d] = io->out_b[d] = 0;
                io->valid[d] = 0;
            } else {
                io->out_r[d] = io->prev_r[s]; io->out_g[d] = io->prev_g[s]; io->out_b[d] = io->prev_b[s];
                io->valid[d] = 1;
            }
        }
}

void tgi_reproject_scatter(const tgi_reproject_io *io, void *scratch)
{
    tgi_reproject_clear(io, scratch);
    tgi_reproject_scatter_rows(io, scratch, 0, io->height);
    tgi_reproject_resolve_rows(io, scratch, 0, io->height);
}

void tgi_reproject_gather_rows(const tgi_reproject_io *io, int y0, int y1)
{
    int x, y, w = io->width, h = io->height;
    tg_real tol = io->depth_tolerance > 0 ? io->depth_tolerance : TG_R(0.05f);
    if (y0 < 0) y0 = 0;
    if (y1 > h) y1 = h;
    for (y = y0; y < y1; y++)
        for (x = 0; x < w; x++) {
            size_t d = (size_t)y * w + x, s;
            int px, py, ok = 0;
            io->out_r[d] = io->out_g[d] = io->out_b[d] = 0;
            if (io->prev_r && io->prev_g && io->prev_b && io->prev_depth && io->motion_x && io->motion_y &&
                !(io->sky && io->sky[d]) && io->depth[d] > 0) {
                px = tg_to_int(io->motion_x[d]);
                py = tg_to_int(io->motion_y[d]);
                if (px >= 0 && py >= 0 && px < w && py < h) {
                    tg_vec3 pv, pw, q;
                    s = (size_t)py * w + px;
                    /* this surface seen from the previous camera must match last frame's depth */
                    pv = tgi_view_unproject(io->view, tg_add(tg_from_int(x), TG_R(0.5f)),
                                           tg_add(tg_from_int(y), TG_R(0.5f)), io->depth[d]);
                    pw = tgi_view_view_to_world(io->view, pv);
                    q = tgi_view_world_to_view(io->prev_view, pw);
                    if (!(io->prev_sky && io->prev_sky[s]) && io->prev_depth[s] > 0 &&
                        tg_abs(tg_sub(q.z, io->prev_depth[s])) <= tg_mul(tol, io->prev_depth[s])) {
                        io->out_r[d] = io->prev_r[s]; io->out_g[d] = io->prev_g[s]; io->out_b[d] = io->prev_b[s];
                        ok = 1;
                    }
                }
            }
            io->valid[d] = (uint8_t)ok;
        }
}
