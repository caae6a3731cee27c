/* SPDX-License-Identifier: MIT */
/*
 * motion.c - motion vectors: where each pixel's surface was on the screen
 * of the previous frame (motion.h).
 */
#include "motion.h"

void tgi_motion_rows(tgi_gbuffer *gb, const tgi_view *cur, const tgi_view *prev,
                    const tgi_mat4 *cur_to_prev, int y0, int y1)
{
    int use_objects = cur_to_prev && gb->object;
    int x, y, w = gb->width;
    for (y = y0; y < y1; y++) {
        int i = y * w;
        tg_real sy = tg_add(tg_from_int(y), TG_R(0.5f));
        for (x = 0; x < w; x++, i++) {
            tg_real sx = tg_add(tg_from_int(x), TG_R(0.5f)), px, py;
            tg_vec3 pv;
            if (gb->sky[i]) {
                /* a direction: rotate the view ray into the previous camera */
                tg_vec3 d = tgi_view_dir_to_world(cur, tgi_view_unproject(cur, sx, sy, TG_ONE));
                pv = tgi_view_dir_to_view(prev, d);
            } else {
                tg_vec3 p = tgi_view_view_to_world(cur, tgi_view_unproject(cur, sx, sy, gb->depth[i]));
                if (use_objects) p = tgi_m4_point(&cur_to_prev[gb->object[i]], p);
                pv = tgi_view_world_to_view(prev, p);
            }
            if (pv.z <= TG_R(0.0001f)) {
                gb->motion_x[i] = gb->motion_y[i] = TG_MOTION_INVALID;
                continue;
            }
            tgi_view_project(prev, pv, &px, &py);
            gb->motion_x[i] = px; gb->motion_y[i] = py;
        }
    }
}
