/* SPDX-License-Identifier: MIT */
/*
 * frame.c - one frame, pass by pass, in the order of design.md:
 *
 *   animate -> rasterize G-buffer -> motion vectors -> shadow maps ->
 *   direct light -> near-field source (reprojected history, or this frame's
 *   direct light on a cut) -> technique (HBIL: 4x4 split, kernel per
 *   sub-image, merge, filter, temporal) -> far field in the bent cone ->
 *   compose -> keep the radiance as next frame's history.
 *
 * Each pass is a plain function over rows; here every pass runs over all
 * rows [0, height) in one call.  Buffers that are NULL belong to effects the
 * plan left out, and their passes are skipped.
 */
#include <string.h>
#include "frame_internal.h"
#include "technique.h"
#include "../core/error.h"
#include "../raster/raster.h"
#include "../light/direct.h"
#include "../light/sh.h"
#include "../light/compose.h"
#include "../scene/anim.h"
#include "../raster/motion.h"

tg_status tg_frame_create(const tg_plan *plan, void *memory, size_t size,
                          tg_frame **frame, tg_error *err)
{
    tg_arena arena;
    tg_frame *f = NULL;
    tg_plan copy = *plan;
    tgi_error_clear(err);
    *frame = NULL;
    tg_arena_init(&arena, memory, size);
    if (tgi_frame_layout(&f, &copy, &arena) != 0) goto no_memory;
    if (f->effects & TG_EFFECT_FAR) tgi_sh9_from_env(&f->scene->env, f->sh);
    *frame = f;
    return TG_OK;
no_memory:
    tgi_error_set(err, TG_ERR_MEMORY, NULL, 0, 0, "the frame arena is too small for the plan");
    err->bytes_needed = plan->total_bytes;
    return TG_ERR_MEMORY;
}

/* ---- passes ---- */

static void pass_animate(tg_frame *f, int index)
{
    const tg_scene *s = f->scene;
    tg_vec3 pos = s->camera.pos, target = s->camera.target;
    int o;
    f->prev_view = f->view;
    f->prev_time = f->time;
    f->time = tgi_anim_time(s, index, f->plan.request.frames);
    if (s->camera_key_count > 0) tgi_anim_camera(s, f->time, &pos, &target);
    tgi_view_make(&f->view, pos, target, s->camera.up, s->camera.fov, s->camera.znear,
                 s->camera.zfar, f->width, f->height);
    if (f->posed_pos) {
        tgi_anim_pose(s, f->time, f->posed_pos, f->posed_nrm);
        for (o = 0; o < s->object_count; o++)
            tgi_anim_object_delta(s, o, f->time, index > 0 ? f->prev_time : f->time, &f->object_delta[o]);
    }
}

static tgi_raster_mesh frame_mesh(const tg_frame *f)
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

static void pass_gbuffer(tg_frame *f, int index)
{
    tgi_raster_mesh mesh = frame_mesh(f);
    size_t i;
    tgi_gbuffer_clear_rows(&f->gb, 0, f->height);
    tgi_raster_gbuffer(&f->gb, &f->view, &mesh, 0, f->height);
    if (f->gb.motion_x)
        tgi_motion_rows(&f->gb, &f->view, index > 0 ? &f->prev_view : &f->view,
                       f->posed_pos ? f->object_delta : NULL, 0, f->height);
    f->depth_max = 0;   /* scales the 8-bit depth view; only needed for it */
    if (f->plan.request.aovs & (1u << TG_AOV_DEPTH))
        for (i = 0; i < f->pixels; i++)
            if (f->gb.depth[i] > f->depth_max) f->depth_max = f->gb.depth[i];
}

static void pass_shadows(tg_frame *f)
{
    const tg_scene *s = f->scene;
    tgi_raster_mesh mesh = frame_mesh(f);
    int i;
    /* a static scene's shadow maps are rendered once and kept */
    if (f->shadows_valid && !f->posed_pos) return;
    if (f->posed_pos) {
        /* objects move: refit the maps to where the geometry is now */
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

static void pass_direct(tg_frame *f)
{
    const tg_scene *s = f->scene;
    tgi_direct_rows(&f->gb, &f->view, s->lights, s->light_count,
                   (f->effects & TG_EFFECT_SHADOWS) ? f->shadow_ptrs : NULL,
                   f->direct.r, f->direct.g, f->direct.b, 0, f->height);
}

static tgi_rgb_planes planes(tgi_rgb c)
{
    tgi_rgb_planes p;
    p.r = c.r; p.g = c.g; p.b = c.b;
    return p;
}

/* Lo from the irradiance terms the plan has. */
static void compose_into(tg_frame *f, tgi_rgb out, tgi_rgb irr, int with_far, int with_near)
{
    tgi_rgb_planes terms[3];
    int n = 0;
    if (f->direct.r) terms[n++] = planes(f->direct);
    if (with_far && f->far.r) terms[n++] = planes(f->far);
    if (with_near && f->near.r) terms[n++] = planes(f->near);
    tgi_compose_rows(&f->gb, &f->view, &f->scene->env, terms, n, out.r, out.g, out.b,
                    irr.r, irr.g, irr.b, 0, f->height);
}

/* The radiance the near field gathers: last frame's, reprojected, or on a
 * cut (first frame, no history) this frame's direct light and emission. */
static void pass_source(tg_frame *f)
{
    tgi_rgb none = { NULL, NULL, NULL };
    if (f->has_history && tgi_frame_reproject(f)) return;
    compose_into(f, f->source, none, 0, 0);
}

static void pass_far(tg_frame *f)
{
    if (!(f->effects & TG_EFFECT_FAR)) return;
    tgi_far_rows(&f->gb, f->sh, f->ao, f->bent.r, f->bent.g, f->bent.b,
                f->plan.request.far_mode ? TG_FAR_CUBE_F0 : TG_FAR_CONE_SH,
                f->far.r, f->far.g, f->far.b, 0, f->height);
}

static void keep_history(tg_frame *f)
{
    size_t bytes = f->pixels * sizeof(tg_real);
    if (!f->history.r) return;
    memcpy(f->history.r, f->color.r ? f->color.r : f->source.r, bytes);
    memcpy(f->history.g, f->color.g ? f->color.g : f->source.g, bytes);
    memcpy(f->history.b, f->color.b ? f->color.b : f->source.b, bytes);
    memcpy(f->history_depth, f->gb.depth, bytes);
    if (f->history_object && f->gb.object)
        memcpy(f->history_object, f->gb.object, f->pixels * sizeof(uint16_t));
    f->has_history = 1;
}

tg_status tg_frame_render(tg_frame *f, int index, tg_error *err)
{
    int bounce, bounces;
    tgi_error_clear(err);
    if (index < 0) {
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "frame index must be >= 0");
        return TG_ERR_INPUT;
    }
    pass_animate(f, index);
    pass_gbuffer(f, index);
    if (f->effects & TG_EFFECT_SHADOWS) pass_shadows(f);
    if (f->effects & TG_EFFECT_DIRECT) pass_direct(f);
    if (f->effects & TG_EFFECT_NEAR) pass_source(f);
    /* bounces on one view: iterate the kernel, each pass gathering the
     * previous one's radiance; with history, one pass per frame (eq. 17) */
    bounces = (f->effects & TG_EFFECT_NEAR) && !f->has_history ? f->plan.request.bounces : 1;
    if (bounces < 1) bounces = 1;
    for (bounce = 0; bounce < bounces; bounce++) {
        int far_done = 0;
        if (f->needs & TG_NEED_GI_PASS) far_done = tgi_frame_technique(f, index);
        if (!far_done) pass_far(f);
        if (f->color.r) compose_into(f, f->color, f->irradiance, 1, 1);
        if (bounce + 1 < bounces && f->color.r) {
            size_t bytes = f->pixels * sizeof(tg_real);
            memcpy(f->source.r, f->color.r, bytes);
            memcpy(f->source.g, f->color.g, bytes);
            memcpy(f->source.b, f->color.b, bytes);
        }
    }
    keep_history(f);
    f->frames_rendered++;
    return TG_OK;
}
