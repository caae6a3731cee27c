/* SPDX-License-Identifier: MIT */
/*
 * temporal.c - exponential accumulation of the HBIL outputs over frames,
 * history rejected by depth and normal.  See temporal.h.
 */
#include "../tinygi.h"
#include "temporal.h"
#include "../raster/motion.h"

void tgi_temporal_defaults(tgi_temporal_params *p)
{
    p->alpha = TG_R(0.2f);
    p->history_depth_tolerance = TG_R(0.05f);
    p->history_normal_cos = TG_R(0.9f);
}

/* Where last frame's results hold this pixel's surface: 1 and *s (indexed
 * like g) when last frame's depth and normal agree (the history is accepted). */
static int history_at(const tgi_temporal_params *p, const tgi_gview *g, const tgi_prev_geometry *h,
                      const tgi_view *prev_view, int x, int y, size_t i, size_t *s)
{
    const tgi_view *view = g->camera;
    int fx = x * g->step + g->offset_x, fy = y * g->step + g->offset_y, px, py, sx, sy;
    tg_real mx, my, z, hz;
    size_t full;
    if (!tgi_motion_prev_position(view, prev_view, NULL, fx, fy, tgi_gv_depth(g, i), &mx, &my, &z)) return 0;
    px = tg_to_int(mx); py = tg_to_int(my);
    if (px < 0 || py < 0 || px >= view->width || py >= view->height) return 0;
    sx = (px - g->offset_x) / g->step;    /* the pixel of g standing for the full-res pixel's block */
    sy = (py - g->offset_y) / g->step;
    if (px < g->offset_x || py < g->offset_y || sx >= g->width || sy >= g->height) return 0;
    *s = tgi_gv_index(g, sx, sy);
    full = (size_t)(sy * g->step + g->offset_y) * (size_t)view->width + (size_t)(sx * g->step + g->offset_x);
    hz = tgi_prev_depth(h, full);
    if (!(hz > 0 && tg_abs(tg_sub(hz, z)) <= tg_mul(p->history_depth_tolerance, hz))) return 0;
    return tgi_v3_dot(tgi_prev_normal(h, full), tgi_gv_normal(g, i)) >= p->history_normal_cos;
}

static tg_vec3 lerp3(tg_vec3 a, tg_vec3 b, tg_real t)
{
    return tg_v3(tg_lerp(a.x, b.x, t), tg_lerp(a.y, b.y, t), tg_lerp(a.z, b.z, t));
}

void tgi_temporal_rows(const tgi_temporal_params *p, const tgi_gview *g, const tgi_gresult *r, const tgi_gresult *prev,
                       const tgi_prev_geometry *prev_geometry, const tgi_view *prev_view, int reset, int y0, int y1)
{
    int x, y;
    if (reset || !prev_view) return;
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            size_t i = tgi_gv_index(g, x, y), s;
            tgi_gr_value v, h;
            if (tgi_gv_is_sky(g, i) || !history_at(p, g, prev_geometry, prev_view, x, y, i, &s)) continue;
            v = tgi_gr_get(r, i);
            h = tgi_gr_get(prev, s);
            v.ao = tg_lerp(h.ao, v.ao, p->alpha);                       /* exponential average */
            v.bent = tgi_v3_normalize_or(lerp3(h.bent, v.bent, p->alpha), tgi_gv_normal(g, i));
            v.near = lerp3(h.near, v.near, p->alpha);
            tgi_gr_put(r, i, &v);
        }
}
