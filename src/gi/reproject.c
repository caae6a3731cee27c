/* SPDX-License-Identifier: MIT */
/*
 * reproject.c - gather reprojection of last frame's radiance (HBIL sec.
 * 3.2).  See reproject.h.
 */
#include "../tinygi.h"
#include "reproject.h"

#if !TG_NO_COLOR /* the whole file is left out with TG_NO_COLOR=1 (tinygi.h "FEATURE SWITCHES") */

/* Last frame's pixel holding this surface: 1 and *s when its depth agrees.
 * The cameras of cams are the caller's copies (locals: the stores into
 * `out` cannot change them, so their fields stay in registers along the
 * row); the pixels it accepts are g's. */
#if defined(__GNUC__)
__attribute__((always_inline))   /* one copy in the row loop */
#endif
static inline int history_pixel(const tgi_reproject_io *io, const tgi_reproject_cams *cams, const tgi_mat4 *delta,
                                int x, int y, tg_real depth, tg_real tol, size_t *s)
{
    const tgi_gview *g = io->g;
    tg_real z, hz;
    int sx, sy;
    if (!tgi_reproject_prev_pixel(cams, delta, x, y, depth, &sx, &sy, &z)) return 0;
    *s = (size_t)sy * (size_t)g->width + (size_t)sx;
    hz = tgi_prev_depth(io->prev_geometry, *s);
    return hz > 0 && tgi_abs_fast(tg_sub(z, hz)) <= tg_mul(tol, hz);   /* the z-test of HBIL sec. 3.2 */
}

void tgi_reproject_gather_rows(const tgi_reproject_io *io_in, int y0, int y1)
{
    /* locals: the stores into `out` cannot change them, so they stay in registers along the row */
    tgi_reproject_io iol = *io_in;
    tgi_gview gl = *io_in->g;
    tgi_prev_geometry hl;
    tgi_rgb outl = *io_in->out, prevl;
    const tgi_reproject_io *io = &iol;
    const tgi_gview *g = &gl;
    tg_real tol = io->depth_tolerance > 0 ? io->depth_tolerance : TG_R(0.05f);
    tgi_view view, before;
    tgi_reproject_cams cams;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    if (!tgi_rgb_present(io->prev)) {     /* no history: every pixel a hole */
        for (y = y0; y < y1; y++)
            for (x = 0; x < g->width; x++) tgi_rgb_set_hole(io->out, tgi_gv_index(g, x, y));
        return;
    }
    prevl = *io_in->prev;
    hl = *io_in->prev_geometry;
    iol.g = &gl; iol.prev_geometry = &hl; iol.out = &outl; iol.prev = &prevl;
    view = *g->camera;
    before = *io->prev_view;
    tgi_reproject_cams_start(&cams, &view, &before, g->width, g->height);
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            size_t i = tgi_gv_index(g, x, y), s;
            const tgi_mat4 *delta = io->object && io->object[i] != 0xFFFF ? &io->object_delta[io->object[i]] : NULL;
            if (!tgi_gv_is_sky(g, i) && history_pixel(io, &cams, delta, x, y, tgi_gv_depth(g, i), tol, &s))
                tgi_rgb_copy(io->out, i, io->prev, s);
            else
                tgi_rgb_set_hole(io->out, i);
        }
}

#endif /* !TG_NO_COLOR */
