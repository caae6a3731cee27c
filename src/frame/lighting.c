/* SPDX-License-Identifier: MIT */
/*
 * lighting.c - the frame's light passes: shadow maps, the direct light, the
 * near field's first source (this frame's direct light and emission, on a
 * frame without history), the far field in the bent cone, the composed
 * outgoing radiance, and the radiance the next bounce gathers.
 */
#include <string.h>
#include "frame_internal.h"
#include "../scene/anim.h"
#include "../light/direct.h"
#include "../light/sh.h"
#include "../light/compose.h"

/* A static scene's shadow maps are rendered once and kept; when objects
 * move they are refitted to where the geometry is now. */
void tgi_pass_shadow_maps(tg_frame *f)
{
    const tg_scene *s = f->scene;
    tgi_raster_mesh mesh = tgi_frame_mesh(f);
    int i;
    if (f->shadows_valid && !f->posed_pos) return;
    if (f->posed_pos) {
        tg_vec3 lo, hi;
        tgi_anim_bounds(mesh.pos, mesh.tri_count, &lo, &hi);
        for (i = 0; i < s->light_count; i++)
            if (f->shadow_ptrs[i]) {
                int filter = f->shadow_maps[i].filter;
                tgi_shadow_map_setup(&f->shadow_maps[i], &s->lights[i], f->shadow_maps[i].size, lo, hi,
                                    f->shadow_maps[i].depth);
                f->shadow_maps[i].filter = filter;
            }
    }
    for (i = 0; i < s->light_count; i++)
        if (f->shadow_ptrs[i]) tgi_shadow_map_render(&f->shadow_maps[i], mesh.pos, mesh.tri_count);
    f->shadows_valid = 1;
}

void tgi_pass_direct(tg_frame *f, int y0, int y1)
{
    const tg_scene *s = f->scene;
    tgi_direct_rows(&f->full, s->lights, s->light_count,
                    (f->effects & TG_EFFECT_SHADOWS) ? f->shadow_ptrs : NULL, &f->direct, y0, y1);
}

/* On a cut (the first frame, no history) the near field gathers this
 * frame's direct light and emission: Lo of the direct term alone. */
void tgi_pass_source_direct(tg_frame *f, int y0, int y1)
{
    tgi_compose_rows(&f->full, &f->scene->env, &f->direct, 1, &f->source, NULL, y0, y1);
}

void tgi_pass_far(tg_frame *f, int y0, int y1)
{
    tgi_far_rows(&f->full, f->sh, &f->res, f->request.far_mode ? TG_FAR_CUBE_F0 : TG_FAR_CONE_SH, &f->far, y0, y1);
}

/* Lo from every irradiance term the plan has (HBIL sec. 2.3). */
void tgi_pass_compose(tg_frame *f, int y0, int y1)
{
    tgi_rgb terms[3];
    terms[0] = f->direct;
    terms[1] = f->far;
    terms[2] = f->res.near;
    tgi_compose_rows(&f->full, &f->scene->env, terms, 3, &f->color, &f->irradiance, y0, y1);
}

/* Bounces on one view: the next iteration of the kernel gathers the
 * radiance this one composed (not after the last). */
void tgi_pass_next_bounce(tg_frame *f, int y0, int y1)
{
    int x, y;
    if (f->bounce + 1 >= f->bounces) return;
    for (y = y0; y < y1; y++)
        for (x = 0; x < f->width; x++) {
            size_t i = tgi_gv_index(&f->full, x, y);
            tgi_rgb_set(&f->source, i, tgi_rgb_get(&f->color, i));
        }
}
