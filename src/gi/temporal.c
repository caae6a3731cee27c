/* SPDX-License-Identifier: MIT */
/*
 * temporal.c - exponential accumulation of the HBIL outputs over frames,
 * history rejected by depth and normal.  See temporal.h.
 */
#include <string.h>
#include "../tinygi.h"
#include "temporal.h"

#define TM_CH 11    /* ao, bent xyz, near rgb, depth, normal xyz */
#define TM_GI 7     /* the first seven are accumulated */

void tgi_temporal_defaults(tgi_temporal_params *p)
{
    p->alpha = TG_R(0.2f);
    p->history_depth_tolerance = TG_R(0.05f);
    p->history_normal_cos = TG_R(0.9f);
}

size_t tgi_temporal_bytes(int w, int h)
{
    size_t n;
    if (w < 0 || h < 0 || tg_size_mul((size_t)w, (size_t)h, &n) || tg_size_mul(n, 2 * TM_CH * sizeof(tg_real), &n))
        return SIZE_MAX;
    return n;
}

void tgi_temporal_clear(void *state, int w, int h) { memset(state, 0, tgi_temporal_bytes(w, h)); }

/* Where last frame's half holds this pixel's surface: 1 and *s when its
 * depth and normal agree (the history is accepted). */
static int history_at(const tgi_temporal_params *p, const tgi_gview *g, const tg_real *prev, const tgi_view *prev_view,
                      int x, int y, size_t i, size_t *s)
{
    const tgi_view *view = g->camera;
    int w = g->width, h = g->height, px, py;
    size_t n = (size_t)w * (size_t)h;
    tg_real sx, sy, hz;
    tg_vec3 pv = tgi_view_unproject(view, tg_add(tg_from_int(x), TG_R(0.5f)), tg_add(tg_from_int(y), TG_R(0.5f)),
                                    tgi_gv_depth(g, i));
    tg_vec3 q = tgi_view_world_to_view(prev_view, tgi_view_view_to_world(view, pv));
    if (!(q.z > 0)) return 0;
    tgi_view_project(prev_view, q, &sx, &sy);
    px = tg_to_int(sx); py = tg_to_int(sy);
    if (px < 0 || py < 0 || px >= w || py >= h) return 0;
    *s = (size_t)py * (size_t)w + (size_t)px;
    hz = prev[7 * n + *s];
    if (!(hz > 0 && tg_abs(tg_sub(hz, q.z)) <= tg_mul(p->history_depth_tolerance, hz))) return 0;
    return tgi_v3_dot(tg_v3(prev[8 * n + *s], prev[9 * n + *s], prev[10 * n + *s]), tgi_gv_normal(g, i))
           >= p->history_normal_cos;
}

static void temporal_pixel(const tgi_temporal_params *p, const tgi_gview *g, const tgi_gresult *r,
                           const tg_real *prev, tg_real *next, const tgi_view *prev_view, int reset, int x, int y)
{
    size_t n = (size_t)g->width * (size_t)g->height, j = (size_t)y * (size_t)g->width + (size_t)x, s = 0;
    size_t i = tgi_gv_index(g, x, y);
    int has_bent = tgi_gr_has_bent(r), has_near = tgi_gr_has_near(r), k;
    int sky = tgi_gv_is_sky(g, i) || tgi_gv_depth(g, i) <= 0;
    int ok = !reset && !sky && prev_view && history_at(p, g, prev, prev_view, x, y, i, &s);
    tg_vec3 b = has_bent ? tgi_gr_bent(r, i) : tg_v3(0, 0, 0), e = has_near ? tgi_gr_near(r, i) : tg_v3(0, 0, 0);
    tg_vec3 nrm = tgi_gv_normal(g, i);
    tg_real v[TM_GI];
    v[0] = tgi_gr_ao(r, i);
    v[1] = b.x; v[2] = b.y; v[3] = b.z;
    v[4] = e.x; v[5] = e.y; v[6] = e.z;
    for (k = 0; k < TM_GI; k++) {
        int present = k == 0 || (k < 4 ? has_bent : has_near);
        if (present && ok) v[k] = tg_lerp(prev[(size_t)k * n + s], v[k], p->alpha);   /* exponential average */
        next[(size_t)k * n + j] = v[k];
    }
    if (ok) {
        tgi_gr_set_ao(r, i, v[0]);
        if (has_bent) tgi_gr_set_bent(r, i, tgi_v3_normalize_or(tg_v3(v[1], v[2], v[3]), nrm));
        if (has_near) tgi_gr_set_near(r, i, tg_v3(v[4], v[5], v[6]));
        if (tgi_gr_has_cone(r)) tgi_gr_set_cone(r, i, tg_acos(tg_sub(TG_ONE, v[0])));   /* HBIL eq. 12 */
    }
    next[7 * n + j] = sky ? 0 : tgi_gv_depth(g, i);
    next[8 * n + j] = nrm.x; next[9 * n + j] = nrm.y; next[10 * n + j] = nrm.z;
}

void tgi_temporal_rows(const tgi_temporal_params *p, const tgi_gview *g, const tgi_gresult *r, void *state,
                       const tgi_view *prev_view, int frame, int reset, int y0, int y1)
{
    size_t half = (size_t)g->width * (size_t)g->height * TM_CH;
    tg_real *a = (tg_real *)state, *b = a + half;
    const tg_real *prev = (frame & 1) ? b : a;
    tg_real *next = (frame & 1) ? a : b;
    int x, y;
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++)
            temporal_pixel(p, g, r, prev, next, prev_view, reset, x, y);
}
