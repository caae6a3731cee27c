/* SPDX-License-Identifier: MIT */
/*
 * motion.c - motion vectors: where each pixel's surface was on the screen
 * of the previous frame (motion.h).
 */
#include "motion.h"
#include "gview.h"

int tgi_motion_prev_position(const tgi_view *cur, const tgi_view *prev, const tgi_mat4 *delta,
                             int x, int y, tg_real depth, tg_real *px, tg_real *py, tg_real *prev_z)
{
    return tgi_motion_prev_position_inline(cur, prev, delta, x, y, depth, px, py, prev_z);
}

void tgi_motion_rows(tgi_gbuffer *gb, const tgi_view *cur, const tgi_view *prev,
                    const tgi_mat4 *cur_to_prev, int y0, int y1)
{
    int use_objects = cur_to_prev && gb->object;
    int x, y, w = gb->width;
    tgi_gview g;
    tgi_gview_of(&g, gb, cur);
    for (y = y0; y < y1; y++) {
        size_t i = (size_t)y * (size_t)w;
        for (x = 0; x < w; x++, i++) {
            tg_real px, py, z;
            int front;
            if (tgi_gv_is_sky(&g, i)) {
                /* a direction: rotate the view ray into the previous camera */
                tg_real sx = tg_add(tg_from_int(x), TG_R(0.5f)), sy = tg_add(tg_from_int(y), TG_R(0.5f));
                tg_vec3 d = tgi_view_dir_to_world(cur, tgi_view_unproject(cur, sx, sy, TG_ONE));
                tg_vec3 pv = tgi_view_dir_to_view(prev, d);
                front = pv.z > TG_R(0.0001f);
                if (front) tgi_view_project(prev, pv, &px, &py);
            } else {
                front = tgi_motion_prev_position(cur, prev, use_objects ? &cur_to_prev[gb->object[i]] : NULL, x, y,
                                                 tgi_gv_depth(&g, i), &px, &py, &z);
            }
            if (!front) {
                gb->motion_x[i] = gb->motion_y[i] = TG_MOTION_INVALID;
                continue;
            }
            gb->motion_x[i] = px; gb->motion_y[i] = py;
        }
    }
}
