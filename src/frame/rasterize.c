/* SPDX-License-Identifier: MIT */
/*
 * rasterize.c - the frame's geometry passes: the G-buffer of the triangles
 * as this frame poses them (camera.c), the motion vectors, and the depth
 * range the 8-bit depth view is scaled by.
 */
#include "frame_internal.h"
#include "../raster/motion.h"

tgi_raster_mesh tgi_frame_mesh(const tg_frame *f)
{
    const tg_scene *s = f->scene;
    tgi_raster_mesh m;
    m.pos = f->posed_pos ? f->posed_pos : s->tri_pos;
    m.nrm = f->posed_nrm ? f->posed_nrm : s->tri_nrm;
    m.tri_material = s->tri_material;
    m.tri_object = s->tri_object;
    m.tri_count = s->tri_count;
    m.materials = s->materials;
    return m;
}

void tgi_pass_gbuffer(tg_frame *f, int y0, int y1)
{
    tgi_raster_mesh mesh = tgi_frame_mesh(f);
    tgi_gbuffer_clear_rows(&f->gb, y0, y1);
    tgi_raster_gbuffer(&f->gb, &f->view, &mesh, y0, y1);
}

#if !TG_NO_TEMPORAL /* motion vectors are left out with TG_NO_TEMPORAL=1 (tinygi.h "FEATURE SWITCHES") */
void tgi_pass_motion(tg_frame *f, int y0, int y1)
{
    tgi_motion_rows(&f->gb, &f->view, f->index > 0 ? &f->prev_view : &f->view,
                    f->posed_pos ? f->object_delta : NULL, y0, y1);
}
#endif

/* The largest depth: scales the 8-bit depth view (needed only for it). */
void tgi_pass_depth_range(tg_frame *f)
{
    int x, y;
    f->depth_max = 0;
    for (y = 0; y < f->height; y++)
        for (x = 0; x < f->width; x++) {
            tg_real z = tgi_gv_depth(&f->full, tgi_gv_index(&f->full, x, y));
            if (z > f->depth_max) f->depth_max = z;
        }
}
