/* SPDX-License-Identifier: MIT */
/*
 * plan.c - the frame is a plan (design.md "The frame is a plan").
 *
 * Before any pixel is touched, the scene and the request decide which
 * effects a frame simulates, which passes run in which order, and which
 * buffers exist, with their sizes.  What the scene does not call for is
 * neither computed nor allocated:
 *   no light                      -> no direct pass
 *   no light marked `shadows`     -> no shadow maps
 *   no environment                -> no far-field pass
 *   nothing lit or emissive, zero albedo everywhere, or bounces 0
 *                                 -> no near-field gathering, no radiance history
 *   one frame                     -> no reprojection, no temporal state
 *   only ao / bent / cone asked   -> nothing after the kernel
 * `effects LIST` in the scene forces (or, by omission, forbids) effects.
 *
 * The same layout function measures (arena NULL) and allocates, so the plan's
 * byte count is exactly what tg_frame_create carves.
 */
#include <string.h>
#include "frame_internal.h"
#include "../core/error.h"
#include "../core/text.h"
#include "../gi/hbil.h"
#include "../gi/pushpull.h"
#include "../gi/reproject.h"
#include "../gi/denoise.h"
#include "../ao/bvh.h"
#include "../scene/anim.h"

#define AOV(a) (1u << (a))

static int positive(tg_vec3 c) { return c.x > 0 || c.y > 0 || c.z > 0; }

static int scene_has_emissive(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->material_count; i++)
        if (positive(s->materials[i].emissive)) return 1;
    return 0;
}

static int scene_has_albedo(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->material_count; i++)
        if (positive(s->materials[i].albedo)) return 1;
    return 0;
}

static int scene_has_shadow_light(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->light_count; i++)
        if (s->lights[i].shadows) return 1;
    return 0;
}

static int technique_gathers_near(tg_technique t)
{
    return t == TG_TECH_HBIL || t == TG_TECH_SSDO || t == TG_TECH_REFERENCE;
}

/* Effects the scene makes possible at all. */
static uint32_t possible_effects(const tg_scene *s, const tg_request *r)
{
    uint32_t e = TG_EFFECT_AO;
    if (s->light_count > 0) e |= TG_EFFECT_DIRECT;
    if (s->light_count > 0 && scene_has_shadow_light(s)) e |= TG_EFFECT_SHADOWS;
    if (s->env.type != TG_ENV_NONE) e |= TG_EFFECT_FAR;
    if (r->bounces != 0 && technique_gathers_near(r->technique) && scene_has_albedo(s) &&
        (s->light_count > 0 || scene_has_emissive(s)))
        e |= TG_EFFECT_NEAR;
    if (r->frames > 1 && r->technique == TG_TECH_HBIL) e |= TG_EFFECT_REPROJECTION;
    return e;
}

/* Effects the request calls for, given what is possible. */
static uint32_t wanted_effects(uint32_t possible, uint32_t aovs)
{
    int color = (aovs & (AOV(TG_AOV_COLOR) | AOV(TG_AOV_IRRADIANCE))) != 0;
    int want_near = color || (aovs & AOV(TG_AOV_NEAR));
    int want_far = color || (aovs & AOV(TG_AOV_FAR));
    int want_ao = (aovs & (AOV(TG_AOV_AO) | AOV(TG_AOV_BENT) | AOV(TG_AOV_CONE))) != 0;
    uint32_t e = 0;
    if (want_near && (possible & TG_EFFECT_NEAR)) e |= TG_EFFECT_NEAR;
    if (want_far && (possible & TG_EFFECT_FAR)) e |= TG_EFFECT_FAR;
    if ((color || (aovs & AOV(TG_AOV_DIRECT)) || (e & TG_EFFECT_NEAR)) && (possible & TG_EFFECT_DIRECT))
        e |= TG_EFFECT_DIRECT;
    if ((e & TG_EFFECT_DIRECT) && (possible & TG_EFFECT_SHADOWS)) e |= TG_EFFECT_SHADOWS;
    if (want_ao || (e & (TG_EFFECT_NEAR | TG_EFFECT_FAR))) e |= TG_EFFECT_AO;
    if ((e & TG_EFFECT_NEAR) && (possible & TG_EFFECT_REPROJECTION)) e |= TG_EFFECT_REPROJECTION;
    return e;
}

uint32_t tgi_frame_needs(const tg_plan *p)
{
    const tg_scene *s = p->scene;
    const tg_request *r = &p->request;
    uint32_t n = 0, e = p->effects;
    if (e & (TG_EFFECT_AO | TG_EFFECT_NEAR)) n |= TG_NEED_GI_PASS;
    if (r->aovs & (AOV(TG_AOV_COLOR) | AOV(TG_AOV_IRRADIANCE))) n |= TG_NEED_COMPOSE;
    /* next frame's near field gathers this frame's outgoing radiance */
    if (e & TG_EFFECT_REPROJECTION) n |= TG_NEED_COMPOSE;
    if (r->frames > 1 && tgi_anim_has_motion(s)) {
        int i;
        for (i = 0; i < s->object_count; i++)
            if (tgi_anim_object_moves(s, i)) n |= TG_NEED_POSE;
    }
    if ((r->aovs & AOV(TG_AOV_MOTION)) && r->frames > 1) n |= TG_NEED_MOTION;
    if (r->frames > 1 && r->temporal && r->technique == TG_TECH_HBIL && (e & TG_EFFECT_AO))
        n |= TG_NEED_TEMPORAL | TG_NEED_MOTION;
    if ((e & TG_EFFECT_REPROJECTION) && (n & TG_NEED_POSE)) n |= TG_NEED_MOTION;
    if ((e & TG_EFFECT_FAR) || (r->aovs & AOV(TG_AOV_BENT))) n |= TG_NEED_BENT;
    if (r->aovs & AOV(TG_AOV_CONE)) n |= TG_NEED_CONE;
    return n;
}

tg_status tg_plan_make(tg_plan *plan, const tg_scene *scene, const tg_request *req, tg_error *err)
{
    tg_frame probe, *pp = &probe;
    uint32_t possible;
    tgi_error_clear(err);
    memset(plan, 0, sizeof *plan);
    plan->request = *req;
    plan->scene = scene;
    if (tgi_request_refused(req, err) || tgi_request_resolve(&plan->request, scene, err))
        return TG_ERR_INPUT;
    possible = possible_effects(scene, &plan->request);
    if (scene->effects_auto) plan->effects = wanted_effects(possible, plan->request.aovs);
    else plan->effects = scene->effects & possible;
    if (plan->effects & TG_EFFECT_NEAR) plan->effects |= TG_EFFECT_AO;
    if (!(plan->effects & TG_EFFECT_DIRECT)) plan->effects &= ~(uint32_t)TG_EFFECT_SHADOWS;
    if (!(plan->effects & TG_EFFECT_NEAR)) plan->effects &= ~(uint32_t)TG_EFFECT_REPROJECTION;
    memset(&probe, 0, sizeof probe);
    if (tgi_frame_layout(&pp, plan, NULL) != 0) {
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "frame size overflows the address space");
        return TG_ERR_INPUT;
    }
    return TG_OK;
}

/* ---- layout: measure or allocate ---- */

typedef struct layout {
    tg_plan *plan;
    tg_arena *arena;   /* NULL: measure */
    size_t total;
    int overflow;
} layout;

static void *take(layout *l, const char *name, size_t count, size_t elem)
{
    size_t bytes, padded;
    if (l->overflow || count == 0) return NULL;
    if (tg_size_mul(count, elem, &bytes) || tg_size_add(bytes, 15, &padded)) { l->overflow = 1; return NULL; }
    padded &= ~(size_t)15;
    if (tg_size_add(l->total, padded, &l->total)) { l->overflow = 1; return NULL; }
    if (!l->arena) {
        tg_plan *p = l->plan;
        if (p->buffer_count > 0 && strcmp(p->buffers[p->buffer_count - 1].name, name) == 0) {
            p->buffers[p->buffer_count - 1].bytes += padded;
        } else if (p->buffer_count < TG_PLAN_MAX_BUFFERS) {
            p->buffers[p->buffer_count].name = name;
            p->buffers[p->buffer_count].bytes = padded;
            p->buffer_count++;
        }
        return NULL;
    }
    {
        void *m = tg_arena_alloc(l->arena, bytes);
        if (!m) l->overflow = 1;
        return m;
    }
}

static tg_real *take_real(layout *l, const char *name, size_t n)
{
    return (tg_real *)take(l, name, n, sizeof(tg_real));
}

static void take_rgb(layout *l, const char *name, size_t n, tgi_rgb *c)
{
    c->r = take_real(l, name, n);
    c->g = take_real(l, name, n);
    c->b = take_real(l, name, n);
}

static void add_pass(tg_plan *p, const char *name)
{
    if (p->pass_count < TG_PLAN_MAX_PASSES) p->passes[p->pass_count++] = name;
}

static void layout_gbuffer(layout *l, tg_frame *f, size_t n)
{
    tgi_gbuffer *g = &f->gb;
    int emissive = scene_has_emissive(l->plan->scene);
    g->width = l->plan->request.width;
    g->height = l->plan->request.height;
    g->depth = take_real(l, "G-buffer depth (view z)", n);
    g->nx = take_real(l, "G-buffer normal (world)", n);
    g->ny = take_real(l, "G-buffer normal (world)", n);
    g->nz = take_real(l, "G-buffer normal (world)", n);
    g->albedo_r = take_real(l, "G-buffer albedo", n);
    g->albedo_g = take_real(l, "G-buffer albedo", n);
    g->albedo_b = take_real(l, "G-buffer albedo", n);
    g->f0 = take_real(l, "G-buffer F0", n);
    if (emissive) {
        g->emit_r = take_real(l, "G-buffer emissive", n);
        g->emit_g = take_real(l, "G-buffer emissive", n);
        g->emit_b = take_real(l, "G-buffer emissive", n);
    }
    g->sky = (uint8_t *)take(l, "G-buffer sky marker", n, 1);
    if (f->needs & (TG_NEED_MOTION | TG_NEED_POSE))
        g->object = (uint16_t *)take(l, "G-buffer object id", n, 2);
    if (f->needs & TG_NEED_MOTION) {
        g->motion_x = take_real(l, "motion vectors", n);
        g->motion_y = take_real(l, "motion vectors", n);
    }
}

static void layout_light(layout *l, tg_frame *f, size_t n)
{
    tg_plan *p = l->plan;
    const tg_scene *s = p->scene;
    uint32_t e = p->effects;
    int i;
    if (e & TG_EFFECT_SHADOWS) {
        f->shadow_maps = (tgi_shadow_map *)take(l, "shadow map descriptors", (size_t)s->light_count, sizeof(tgi_shadow_map));
        f->shadow_ptrs = (const tgi_shadow_map **)take(l, "shadow map descriptors", (size_t)s->light_count, sizeof(void *));
        for (i = 0; i < s->light_count; i++) {
            if (!s->lights[i].shadows) continue;
            {
                int size = p->request.shadow_map_size;
                void *depth = take(l, "shadow maps (depth)", tgi_shadow_map_bytes(&s->lights[i], size), 1);
                if (!l->arena || !depth) continue;
                tgi_shadow_map_setup(&f->shadow_maps[i], &s->lights[i], size, s->bounds_min, s->bounds_max, depth);
                f->shadow_maps[i].filter = p->request.shadow_pcf ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT;
                f->shadow_ptrs[i] = &f->shadow_maps[i];
            }
        }
        add_pass(p, "shadow maps (depth-only raster per shadow light)");
    }
    if (e & TG_EFFECT_DIRECT) {
        take_rgb(l, "direct irradiance E_direct", n, &f->direct);
        add_pass(p, "direct light (Lambert, shadows, spot falloff)");
    }
    (void)n;
}

static void layout_gi(layout *l, tg_frame *f, size_t n)
{
    tg_plan *p = l->plan;
    uint32_t e = p->effects;
    int hbil = p->request.technique == TG_TECH_HBIL;
    int interleaved = hbil && p->request.interleave;
    int quarter = interleaved && p->request.gi_scale == 2;
    int kw = p->request.width, kh = p->request.height;   /* the kernel's image */
    if (e & TG_EFFECT_NEAR) {
        take_rgb(l, "near-field source radiance", n, &f->source);
        if (e & TG_EFFECT_REPROJECTION) {
            take_rgb(l, "radiance history (last frame)", n, &f->history);
            f->history_depth = take_real(l, "radiance history depth", n);
            if (f->needs & TG_NEED_POSE)
                f->history_object = (uint16_t *)take(l, "radiance history object id", n, 2);
            f->reproject_scratch_bytes = tgi_reproject_bytes(p->request.width, p->request.height)
                                       + tgi_pushpull_bytes(p->request.width, p->request.height) + n + 32;
            f->reproject_scratch = take(l, "reprojection z-buffer + push/pull mips", f->reproject_scratch_bytes, 1);
            add_pass(p, "reproject last frame's radiance (scatter + z-test)");
            add_pass(p, "push/pull hole filling");
        }
    }
    if (!(f->needs & TG_NEED_GI_PASS)) return;
    f->ao = take_real(l, "ambient occlusion", n);
    if (f->needs & TG_NEED_BENT || hbil) take_rgb(l, "bent normal (world)", n, &f->bent);
    if (f->needs & TG_NEED_CONE) f->cone = take_real(l, "cone aperture", n);
    if (e & TG_EFFECT_NEAR) take_rgb(l, "near-field irradiance E_near", n, &f->near);
    if (quarter) {
        kw = (p->request.width + 1) / 2;
        kh = (p->request.height + 1) / 2;
    }
    if (interleaved) {
        size_t nk = (size_t)kw * (size_t)kh;   /* pixels the kernel sees */
        if (quarter) {
            f->half_depth = take_real(l, "quarter-res G-buffer (depth, normal, sky)", nk);
            take_rgb(l, "quarter-res G-buffer (depth, normal, sky)", nk, &f->half_normal);
            f->half_sky = (uint8_t *)take(l, "quarter-res G-buffer (depth, normal, sky)", nk, 1);
            f->half_ao = take_real(l, "quarter-res kernel output", nk);
            take_rgb(l, "quarter-res kernel output", nk, &f->half_bent);
            if (e & TG_EFFECT_NEAR) {
                f->half_f0 = take_real(l, "quarter-res F0 and source radiance", nk);
                take_rgb(l, "quarter-res F0 and source radiance", nk, &f->half_source);
                take_rgb(l, "quarter-res kernel output", nk, &f->half_near);
            }
            add_pass(p, "downsample to quarter resolution (point samples)");
        }
        f->q_depth = take_real(l, "4x4 split: depth", nk);
        take_rgb(l, "4x4 split: normal", nk, &f->q_normal);
        f->q_sky = (uint8_t *)take(l, "4x4 split: sky", nk, 1);
        f->q_ao = take_real(l, "4x4 split: kernel output", nk);
        take_rgb(l, "4x4 split: kernel output", nk, &f->q_bent);
        if (e & TG_EFFECT_NEAR) {
            f->q_f0 = take_real(l, "4x4 split: F0", nk);
            take_rgb(l, "4x4 split: source radiance", nk, &f->q_source);
            take_rgb(l, "4x4 split: kernel output", nk, &f->q_near);
        }
        add_pass(p, "4x4 split (depth, normal, radiance into 16 sub-images)");
        add_pass(p, "HBIL horizon kernel (AO, bent normal, near field), per sub-image");
        add_pass(p, "4x4 merge");
    } else {
        add_pass(p, hbil ? "HBIL horizon kernel, full resolution" : tg_technique_name(p->request.technique));
    }
    if (hbil) {
        f->denoise_scratch_bytes = tgi_denoise_bytes(kw, kh);
        f->denoise_scratch = take(l, "spatial filter scratch", f->denoise_scratch_bytes, 1);
        add_pass(p, quarter ? "depth/normal-aware 4x4 filter (quarter res)" : "depth/normal-aware 4x4 filter");
        if (quarter) add_pass(p, "joint bilateral upsample to full resolution");
        if (f->needs & TG_NEED_TEMPORAL) {
            f->temporal_state_bytes = tgi_temporal_bytes(p->request.width, p->request.height);
            f->temporal_state = take(l, "temporal accumulation history", f->temporal_state_bytes, 1);
            add_pass(p, "temporal accumulation (history rejected by depth and normal)");
        }
    }
    if (p->request.technique == TG_TECH_REFERENCE) {
        f->technique_scratch_bytes = tgi_bvh_bytes(p->scene->tri_count);
        f->technique_scratch = take(l, "reference BVH", f->technique_scratch_bytes, 1);
    }
}

int tgi_frame_layout(tg_frame **fp, tg_plan *plan, tg_arena *arena)
{
    layout l;
    size_t n;
    const tg_scene *s = plan->scene;
    uint32_t e = plan->effects;
    tg_frame *f;
    memset(&l, 0, sizeof l);
    l.plan = plan;
    l.arena = arena;
    if (!arena) { plan->pass_count = 0; plan->buffer_count = 0; }
    if (tg_size_mul((size_t)plan->request.width, (size_t)plan->request.height, &n)) return 1;
    f = (tg_frame *)take(&l, "frame state", 1, sizeof(tg_frame));
    if (arena && !f) return 1;
    if (!arena) f = *fp;
    *fp = f;
    f->plan = *plan;
    f->scene = s;
    f->width = plan->request.width;
    f->height = plan->request.height;
    f->pixels = n;
    f->effects = e;
    f->needs = tgi_frame_needs(plan);
    if (!arena) add_pass(plan, (f->needs & TG_NEED_POSE) ? "animate (camera and object keys, posed triangles)"
                               : s->camera_key_count > 0 ? "animate (camera keys)" : "camera");
    if (f->needs & TG_NEED_POSE) {
        f->posed_pos = (tg_vec3 *)take(&l, "posed triangles", (size_t)s->tri_count * 3, sizeof(tg_vec3));
        f->posed_nrm = (tg_vec3 *)take(&l, "posed triangles", (size_t)s->tri_count * 3, sizeof(tg_vec3));
        f->object_delta = (tgi_mat4 *)take(&l, "object motion", (size_t)s->object_count, sizeof(tgi_mat4));
    }
    layout_gbuffer(&l, f, n);
    add_pass(plan, "rasterize G-buffer (depth, normal, albedo, F0, emissive)");
    if (f->needs & TG_NEED_MOTION) add_pass(plan, "motion vectors");
    layout_light(&l, f, n);
    layout_gi(&l, f, n);
    if (e & TG_EFFECT_FAR) {
        take_rgb(&l, "far-field irradiance E_far", n, &f->far);
        add_pass(plan, "far field: SH9 environment in the bent cone");
    }
    if (f->needs & TG_NEED_COMPOSE) {
        take_rgb(&l, "outgoing radiance Lo (colour)", n, &f->color);
        if (plan->request.aovs & AOV(TG_AOV_IRRADIANCE)) take_rgb(&l, "total irradiance", n, &f->irradiance);
        add_pass(plan, "compose Lo = albedo/pi (1-F0) (E_direct + E_far + E_near) + emissive");
        add_pass(plan, "tonemap + sRGB (on output)");
    }
    if (l.overflow) return 1;
    if (!arena) plan->total_bytes = l.total + 16;
    return 0;
}

/* ---- explain ---- */

static void put_effects(tgi_text *t, uint32_t e)
{
    static const char *const names[6] = { "direct", "shadows", "far", "near", "ao", "reprojection" };
    int i, any = 0;
    for (i = 0; i < 6; i++) {
        if (!(e & (1u << i))) continue;
        if (any) tgi_text_put(t, " ");
        tgi_text_put(t, names[i]);
        any = 1;
    }
    if (!any) tgi_text_put(t, "(none)");
}

size_t tg_plan_explain(const tg_plan *plan, char *buf, size_t size)
{
    tgi_text t;
    int i;
    size_t pixels = (size_t)plan->request.width * (size_t)plan->request.height;
    tgi_text_init(&t, buf, size);
    tgi_text_put(&t, "plan: "); tgi_text_put_uint(&t, (size_t)plan->request.width); tgi_text_put(&t, "x");
    tgi_text_put_uint(&t, (size_t)plan->request.height); tgi_text_put(&t, ", technique ");
    tgi_text_put(&t, tg_technique_name(plan->request.technique)); tgi_text_put(&t, ", number type ");
    tgi_text_put(&t, TG_NUMBER_NAME); tgi_text_put(&t, ", frames "); tgi_text_put_uint(&t, (size_t)plan->request.frames);
    tgi_text_put(&t, "\neffects: "); put_effects(&t, plan->effects);
    tgi_text_put(&t, "\nskipped: "); put_effects(&t, (~plan->effects) & 63u);
    tgi_text_put(&t, "\npasses:\n");
    for (i = 0; i < plan->pass_count; i++) {
        tgi_text_put(&t, "  "); tgi_text_put_uint(&t, (size_t)(i + 1)); tgi_text_put(&t, ". "); tgi_text_put(&t, plan->passes[i]); tgi_text_put(&t, "\n");
    }
    tgi_text_put(&t, "buffers:\n");
    for (i = 0; i < plan->buffer_count; i++) {
        tgi_text_put(&t, "  "); tgi_text_put(&t, plan->buffers[i].name); tgi_text_put(&t, ": ");
        tgi_text_put_uint(&t, plan->buffers[i].bytes); tgi_text_put(&t, " bytes\n");
    }
    tgi_text_put(&t, "total: "); tgi_text_put_uint(&t, plan->total_bytes); tgi_text_put(&t, " bytes, ");
    tgi_text_put_uint(&t, pixels ? plan->total_bytes / pixels : 0); tgi_text_put(&t, " bytes per pixel\n");
    return t.at;
}
