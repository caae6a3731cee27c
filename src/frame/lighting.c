/* SPDX-License-Identifier: MIT */
/*
 * lighting.c - the frame's light passes: shadow maps and the direct light
 * (into its radiance slot, frame_internal.h; read as lit it is also the
 * near field's first source).  The far field and the composed outgoing
 * radiance are computed per pixel by the resolve pass (resolve.c).
 */
#include <string.h>
#include "frame_internal.h"
#include "../scene/anim.h"
#include "../light/direct.h"

#if !TG_NO_COLOR /* the whole file is left out with TG_NO_COLOR=1 (tinygi.h "FEATURE SWITCHES") */

/* A static scene's shadow maps (or the BVH shadow rays trace) are made
 * once and kept; when objects move (camera.c marks every light stale) or
 * a light moves (its own) the maps are refitted to where the geometry and
 * the light are now, keeping the plan's faces and sizes, and the BVH is
 * built again. */
void tgi_pass_shadow_maps(tg_frame *f)
{
    const tg_scene *s = f->scene;
    tgi_raster_mesh mesh = tgi_frame_mesh(f);
    tg_vec3 lo = s->bounds_min, hi = s->bounds_max;
    int i, rays = 0;
    if (f->shadows_valid && !f->shadows_stale) return;
    if (f->shadows_stale) tgi_anim_bounds(mesh.pos, mesh.tri_count, &lo, &hi);
    for (i = 0; i < s->light_count; i++) {
        tgi_shadow_map *sm = &f->shadow_maps[i];
        int stale = (int)(f->shadows_stale >> i) & 1;
        if (!f->shadow_ptrs[i] || (f->shadows_valid && !stale)) continue;
        if (sm->ray) { rays = 1; continue; }
        if (stale) tgi_shadow_map_refit(sm, lo, hi);
        tgi_shadow_map_render(sm, mesh.pos, mesh.tri_count);
    }
    if (!TG_NO_REFERENCE && rays) tgi_bvh_build(&f->bvh, mesh.pos, mesh.tri_count, f->bvh_scratch, f->bvh_scratch_bytes);
    f->shadows_valid = 1;
    f->shadows_stale = 0;
}

/* E_direct; 0 without the direct effect (the near field's first source is
 * then the emission alone). */
void tgi_pass_direct(tg_frame *f, int y0, int y1)
{
    const tg_scene *s = f->scene;
    tgi_direct_rows(&f->full, s->lights, (f->effects & TG_EFFECT_DIRECT) ? s->light_count : 0,
                    (f->effects & TG_EFFECT_SHADOWS) ? f->shadow_ptrs : NULL, &f->direct, y0, y1);
}

#endif /* !TG_NO_COLOR */
