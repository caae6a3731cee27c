/* SPDX-License-Identifier: MIT */
/*
 * layout.c - the frame's buffers, measured (no arena) or carved from the
 * arena by the same code, so the plan's byte count is exactly what
 * tg_frame_create carves.
 *
 * Buffers come in groups (enum tgi_buffer_group); each row of the pass table
 * lists the groups its pass uses, and the layout walks the table: a group
 * is carved once, when the first pass the plan needs that uses it is laid
 * out, with the sizes the plan implies (a group whose effect the plan left
 * out carves nothing).  Every size goes through tg_size_mul / tg_size_add.
 */
#include <string.h>
#include "frame_internal.h"
#include "../gi/pushpull.h"
#include "../gi/resample.h"
#include "../light/shadowview.h"
#include "../ao/pathtrace.h"

#define AOV(a) (1u << (a))

typedef struct layout {
    tg_plan *plan;
    tg_arena *arena;   /* NULL: measure */
    size_t total;
    int overflow;
    uint32_t carved;   /* TGI_BUF() of the groups done */
} layout;

static void note_buffer(tg_plan *p, const char *name, size_t bytes)
{
    if (p->buffer_count > 0 && strcmp(p->buffers[p->buffer_count - 1].name, name) == 0) {
        p->buffers[p->buffer_count - 1].bytes += bytes;
    } else if (p->buffer_count < TG_PLAN_MAX_BUFFERS) {
        p->buffers[p->buffer_count].name = name;
        p->buffers[p->buffer_count].bytes = bytes;
        p->buffer_count++;
    }
}

/* count * elem bytes, 16-byte aligned: measured (NULL) or carved (zeroed). */
static void *take(layout *l, const char *name, size_t count, size_t elem)
{
    size_t bytes, padded;
    void *m;
    if (l->overflow || count == 0) return NULL;
    if (tg_size_mul(count, elem, &bytes) || tg_size_add(bytes, 15, &padded)) { l->overflow = 1; return NULL; }
    padded &= ~(size_t)15;
    if (tg_size_add(l->total, padded, &l->total)) { l->overflow = 1; return NULL; }
    if (!l->arena) {
        note_buffer(l->plan, name, padded);
        return NULL;
    }
    m = tg_arena_alloc(l->arena, bytes);
    if (!m) l->overflow = 1;
    return m;
}

/* Storage formats, as --explain prints them beside each buffer. */
#if TG_WIDE_STORAGE
#define FMT_G "tg_real depth (0: sky) and normal, 16-bit material index"
#define FMT_G_GEOMETRY FMT_G " (the material unread)"
#define FMT_RGB "3 x tg_real"
#define FMT_AO "tg_real"
#define FMT_BENT "3 x tg_real"
#define FMT_PREV "tg_real depth and normal"
#define FMT_BACK "tg_real"
#define FMT_BEHIND "tg_real"
#else
#define FMT_G "32-bit float depth (0: sky); octahedral 2x11 normal + 10-bit material index"
#define FMT_G_GEOMETRY "32-bit float depth (0: sky); octahedral 2x8 normal"
#define FMT_RGB "RGB9E5, 32 bits"
#define FMT_AO "8 bits"
#define FMT_BENT "octahedral 2x8"
#define FMT_PREV "16-bit float depth + octahedral 2x8 normal"
#define FMT_BACK "8-bit log code of the depth behind the surface's, 0: none"
#define FMT_BEHIND "32-bit float, 0: none"
#endif

static tg_real *take_real(layout *l, const char *name, size_t n)
{
    return (tg_real *)take(l, name, n, sizeof(tg_real));
}

static void take_rgb(layout *l, const char *name, size_t n, tgi_rgb *c)
{
    tgi_rgb_carve(c, n, take(l, name, tgi_rgb_carve(c, n, NULL), 1));
    if (!tgi_rgb_present(c)) *c = tgi_rgb_none();
}

/* A G-buffer's storage of n = w x h pixels, its materials from the scene
 * (with `material` 0, depth and normal only). */
static void take_gbuffer_planes(layout *l, tgi_gbuffer *g, const tg_scene *s, int w, int h, int material,
                                const char *name)
{
    int i;
    if (material) tgi_gbuffer_carve(g, w, h, take(l, name, tgi_gbuffer_carve(g, w, h, NULL), 1));
    else tgi_gbuffer_carve_geometry(g, w, h, take(l, name, tgi_gbuffer_carve_geometry(g, w, h, NULL), 1));
    g->materials = s->materials;
    for (i = 0; i < s->material_count; i++) {
        tg_vec3 e = s->materials[i].emissive;
        if (e.x > 0 || e.y > 0 || e.z > 0) g->has_emissive = 1;
    }
}

/* Results of n pixels: AO, the bent normal and the near field when asked. */
static void take_results(layout *l, tgi_gresult *r, size_t n, int bent, int near, const char *name)
{
    void *m = take(l, name, tgi_gresult_carve(r, n, bent, 0, near, NULL), 1);
    tgi_gresult_carve(r, n, bent, 0, near, m);
    if (!m) memset(r, 0, sizeof *r);
}

/* The kernel's image: full size, or half width and height (quarter res). */
static void kernel_size(const tg_frame *f, int *w, int *h, size_t *n)
{
    *w = f->width;
    *h = f->height;
    if (tgi_frame_quarter(f)) tgi_half_size(f->width, f->height, w, h);
    *n = (size_t)*w * (size_t)*h;
}

/* What the plan computes, as the groups size it. */
static int near_field(const tg_frame *f) { return (f->effects & TG_EFFECT_NEAR) != 0; }
static int reprojects(const tg_frame *f) { return (f->effects & TG_EFFECT_REPROJECTION) != 0; }
/* The kernel's near field lives in the radiance slots (the kernel at full resolution). */
static int near_in_slots(const tg_frame *f) { return near_field(f) && !tgi_frame_quarter(f); }
static int wants_aov(const tg_frame *f, tg_aov a) { return (f->request.aovs & AOV(a)) != 0; }
static int direct_own(const tg_frame *f) { return (f->effects & TG_EFFECT_DIRECT) && wants_aov(f, TG_AOV_DIRECT); }
static int bent_needed(const tg_frame *f) { return !TG_NO_BENT_NORMALS && (f->needs & TG_NEED_BENT) != 0; }
/* Some pass or output reads a surface's material (albedo, F0, emissive):
 * light, compose, the techniques that light, any output but those of the
 * geometry and the occlusion.  Else the G-buffer keeps no material. */
static int reads_material(const tg_frame *f)
{
    uint32_t geometric = AOV(TG_AOV_AO) | AOV(TG_AOV_BENT) | AOV(TG_AOV_CONE) | AOV(TG_AOV_DEPTH) |
                         AOV(TG_AOV_NORMAL) | AOV(TG_AOV_MOTION);
    tg_technique t = f->request.technique;
    return (f->needs & TG_NEED_COMPOSE) || (f->effects & (TG_EFFECT_DIRECT | TG_EFFECT_NEAR | TG_EFFECT_FAR)) ||
           f->request.aovs == 0 || (f->request.aovs & ~geometric) || t == TG_TECH_SSDO || t == TG_TECH_REFERENCE ||
           tgi_frame_ao_multibounce(f);
}
/* The resolved results an AOV reads have planes of their own (HBIL filters or upsamples). */
static int resolves_into_planes(const tg_frame *f)
{
    return (f->needs & TG_NEED_GI_PASS) && f->request.technique == TG_TECH_HBIL;
}

/* ---- the groups ----
 * A group whose effect a feature switch leaves out (tinygi.h "FEATURE
 * SWITCHES"; the plan refuses what would need it) returns first, so its
 * body is not compiled into that build. */

static void group_pose(layout *l, tg_frame *f)
{
    const tg_scene *s = f->scene;
    if (f->request.game_loop) {
        const char *name = "the program's scene state (game loop)";
        tg_scene *own = (tg_scene *)take(l, name, 1, sizeof(tg_scene));
        tgi_light *lights = (tgi_light *)take(l, name, (size_t)s->light_count, sizeof(tgi_light));
        f->drive.object_set = (tgi_mat4 *)take(l, name, (size_t)s->object_count, sizeof(tgi_mat4));
        if (own) tgi_frame_own_scene(f, own, lights);
    }
    if (!(f->needs & TG_NEED_POSE)) return;
    f->posed_pos = (tg_vec3 *)take(l, "posed triangles", (size_t)s->tri_count * 3, sizeof(tg_vec3));
    f->posed_nrm = (tg_vec3 *)take(l, "posed triangles", (size_t)s->tri_count * 3, sizeof(tg_vec3));
    f->object_delta = (tgi_mat4 *)take(l, "object motion", (size_t)s->object_count, sizeof(tgi_mat4));
    f->drive.object_pose = (tgi_mat4 *)take(l, "object motion", (size_t)s->object_count, sizeof(tgi_mat4));
}

static void group_gbuffer(layout *l, tg_frame *f)
{
    if (reads_material(f))
        take_gbuffer_planes(l, &f->gb, f->scene, f->width, f->height, 1, "G-buffer [" FMT_G "]");
    else
        take_gbuffer_planes(l, &f->gb, f->scene, f->width, f->height, 0, "G-buffer, no material [" FMT_G_GEOMETRY "]");
    if (f->needs & TG_NEED_POSE) f->gb.object = (uint16_t *)take(l, "G-buffer object id [16 bits]", f->pixels, 2);
#if TGI_DEPTH_LAYERS
    /* the further depth layers: the visibility bitmask's surfaces, technique
     * ssilvb's or HBIL's kernel over them (request.c refuses depth_layers 2
     * and 3 for every other technique; with --gi-quarter group_half adds
     * the half-resolution image's) */
    if (!(f->needs & TG_NEED_GI_PASS)) return;
    if (f->request.depth_layers >= 2)
        f->gb.back_depth = (void *)take(l, "G-buffer back-face depth, the second layer [" FMT_BACK "]", f->pixels,
                                        sizeof *f->gb.back_depth);
    if (f->request.depth_layers >= 3)
        f->gb.behind_depth = (void *)take(l, "G-buffer depth behind the back face, the third layer [" FMT_BEHIND "]",
                                          f->pixels, sizeof *f->gb.behind_depth);
#endif
}

static void group_motion(layout *l, tg_frame *f)
{
    if (TG_NO_TEMPORAL || !(f->needs & TG_NEED_MOTION)) return;
    f->gb.motion_x = take_real(l, "motion vectors [2 x tg_real]", f->pixels);
    f->gb.motion_y = take_real(l, "motion vectors [2 x tg_real]", f->pixels);
}

/* Shadow rays against the frame's BVH (a local function, so that taking
 * its address needs no GOT in position-independent code). */
static tg_real bvh_shadow_ray(const void *bvh, const tgi_light *l, tg_vec3 p, tg_vec3 n, tg_real err)
{
#if TG_NO_REFERENCE   /* no BVH in this build: the plan never chooses rays */
    (void)bvh; (void)l; (void)p; (void)n; (void)err;
    return TG_ONE;
#else
    return tgi_bvh_light_visibility(bvh, l, p, n, err);
#endif
}

/* Per shadowed light, maps sized and culled by the plan (tgi_shadow_plan:
 * absent faces take no bytes) or shadow rays, and the BVH they trace (the
 * reference's own when it runs). */
static void group_shadow_maps(layout *l, tg_frame *f)
{
    const tg_scene *s = f->scene;
    int i, rays = 0, reference = f->request.technique == TG_TECH_REFERENCE;
    if (TG_NO_SHADOW_MAPS || !(f->effects & TG_EFFECT_SHADOWS)) return;
    f->shadow_maps = (tgi_shadow_map *)take(l, "shadow map descriptors", (size_t)s->light_count, sizeof(tgi_shadow_map));
    f->shadow_ptrs = (const tgi_shadow_map **)take(l, "shadow map descriptors", (size_t)s->light_count, sizeof(void *));
    for (i = 0; i < s->light_count; i++) {
        tgi_shadow_need nd;
        tg_vec3 lo, hi;
        void *depth = NULL;
        int by;
        if (!s->lights[i].shadows) continue;
        by = tgi_shadow_plan(s, &f->request, i, TG_NO_REFERENCE ? SIZE_MAX : reference ? 0 : tgi_bvh_bytes(s->tri_count),
                             &nd, &lo, &hi);
        rays |= by == TG_SHADOW_BY_RAYS;
        if (by == TG_SHADOW_BY_MAP) depth = take(l, "shadow maps (depth) [16 bits]", tgi_shadow_need_bytes(&nd), 1);
        if (!l->arena || l->overflow) continue;   /* measuring, or the memory ran out (shadow_maps or shadow_ptrs may be NULL) */
        if (by == TG_SHADOW_BY_RAYS) tgi_shadow_rays_setup(&f->shadow_maps[i], &s->lights[i], bvh_shadow_ray, &f->bvh);
        else tgi_shadow_map_setup_need(&f->shadow_maps[i], &s->lights[i], &nd, lo, hi, depth);
        f->shadow_maps[i].filter = f->request.shadow_pcf ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT;
        f->shadow_ptrs[i] = &f->shadow_maps[i];
    }
    if (!TG_NO_REFERENCE && rays && !reference) {
        f->bvh_scratch_bytes = tgi_bvh_bytes(s->tri_count);
        f->bvh_scratch = take(l, "shadow rays: BVH", f->bvh_scratch_bytes, 1);
    }
}

/* E_direct's own plane: only when its AOV is asked (else it lives in a slot). */
static void group_direct(layout *l, tg_frame *f)
{
    if (!TG_NO_COLOR && direct_own(f)) take_rgb(l, "direct irradiance E_direct [" FMT_RGB "]", f->pixels, &f->direct);
}

/* The radiance slots (frame_internal.h): the lit slot (E_direct and Lo, or
 * last frame's Lo), the near-field slot when the kernel gathers at full
 * resolution, and the bounce slot for reprojected radiance. */
static void group_source(layout *l, tg_frame *f)
{
    int composes = (f->needs & TG_NEED_COMPOSE) != 0, lit = composes || near_field(f);
    size_t n = f->pixels, mips = !TG_NO_COLOR && !TG_NO_TEMPORAL && reprojects(f) ? tgi_pushpull_bytes(f->width, f->height) : 0;
    if (TG_NO_COLOR) return;
    if (lit) {
        size_t b = tgi_rgb_carve(&f->slot[0], n, NULL);
        tgi_rgb_carve(&f->slot[0], n, take(l, near_in_slots(f) ? "radiance slot A: E_direct, Lo; last frame's Lo or near field,"
                                             " push/pull mips [" FMT_RGB "]"
                                           : "radiance slot A: E_direct, Lo; last frame's Lo, push/pull mips [" FMT_RGB "]",
                                           b > mips ? b : mips, 1));
    }
    if (near_in_slots(f)) {
        size_t b = tgi_rgb_carve(&f->slot[1], n, NULL);
        tgi_rgb_carve(&f->slot[1], n, take(l, "radiance slot B: the near field; alternates with A [" FMT_RGB "]",
                                           b > mips ? b : mips, 1));
    }
    if (reprojects(f) || (near_field(f) && f->request.bounces > 1))
        take_rgb(l, "near-field source: reprojected radiance, or a bounce's Lo [" FMT_RGB "]", n, &f->bounce_source);
}

/* Last frame's geometry: reprojection's and temporal accumulation's depth test. */
static void group_history(layout *l, tg_frame *f)
{
    if (TG_NO_TEMPORAL || (!reprojects(f) && !(f->needs & TG_NEED_TEMPORAL))) return;
    tgi_prev_carve(&f->prev_geometry, f->pixels,
                   take(l, "last frame's depth and normal [" FMT_PREV "]", tgi_prev_carve(&f->prev_geometry, f->pixels, NULL), 1));
}

/* Push/pull's mips live in the slot last frame's Lo leaves (tgi_frame_begin). */
static void group_reproject(layout *l, tg_frame *f)
{
    (void)l; (void)f;
}

/* Result set k (0 this frame's, 1 last frame's) at the kernel's
 * resolution: at quarter resolution with its near field, at full
 * resolution without (the near field is in a radiance slot there). */
static void take_result_set(layout *l, tg_frame *f, int k, const char *quarter_what, const char *full_what)
{
    int w, h;
    size_t n;
    kernel_size(f, &w, &h, &n);
    if (tgi_frame_quarter(f))
        take_results(l, &f->half_set[k], n, bent_needed(f), near_field(f), quarter_what);
    else
        take_results(l, &f->set[k], n, bent_needed(f), 0, full_what);
}

/* This frame's results at the kernel's resolution. */
static void group_results(layout *l, tg_frame *f)
{
    if (!(f->needs & TG_NEED_GI_PASS)) return;
    take_result_set(l, f, 0, "quarter-res kernel results: AO [" FMT_AO "], bent [" FMT_BENT "], near [" FMT_RGB "]",
                    bent_needed(f) ? "kernel results: AO [" FMT_AO "], bent normal [" FMT_BENT "]"
                                   : "kernel results: AO [" FMT_AO "]");
}

static void group_half(layout *l, tg_frame *f)
{
    int w, h;
    size_t n;
    if (TG_NO_GI_QUARTER || !tgi_frame_quarter(f)) return;
    kernel_size(f, &w, &h, &n);
    if (reads_material(f))
        take_gbuffer_planes(l, &f->half, f->scene, w, h, 1, "quarter-res G-buffer [" FMT_G "]");
    else
        take_gbuffer_planes(l, &f->half, f->scene, w, h, 0, "quarter-res G-buffer, no material [" FMT_G_GEOMETRY "]");
    if (near_field(f)) take_rgb(l, "quarter-res source radiance [" FMT_RGB "]", n, &f->half_source);
#if TGI_DEPTH_LAYERS
    /* HBIL's kernel over the further depth layers reads them at its resolution */
    if (f->request.depth_layers >= 2)
        f->half.back_depth = (void *)take(l, "quarter-res back-face depth, the second layer [" FMT_BACK "]", n,
                                          sizeof *f->half.back_depth);
    if (f->request.depth_layers >= 3)
        f->half.behind_depth = (void *)take(l, "quarter-res depth behind the back face, the third layer [" FMT_BEHIND "]",
                                            n, sizeof *f->half.behind_depth);
#endif
}

/* The filtered quarter-res results the upsample reads. */
static void group_filter(layout *l, tg_frame *f)
{
    int w, h;
    size_t n;
    if (TG_NO_GI_QUARTER || !tgi_frame_quarter(f)) return;
    kernel_size(f, &w, &h, &n);
    take_results(l, &f->half_filtered, n, bent_needed(f), near_field(f),
                 "quarter-res filtered results: AO, bent, near [" FMT_AO ", " FMT_BENT ", " FMT_RGB "]");
    if (tgi_frame_near_horizon(f))
        take_results(l, &f->near_horizon, f->pixels, 0, 0, "near horizons at full resolution, the upsample's cap [" FMT_AO "]");
}

/* Last frame's accumulated results: the second set (its near field, at full
 * resolution, in the other radiance slot). */
static void group_temporal(layout *l, tg_frame *f)
{
    if (TG_NO_TEMPORAL || !(f->needs & TG_NEED_TEMPORAL)) return;
    take_result_set(l, f, 1, "quarter-res results of last frame (temporal accumulation)",
                    "kernel results of last frame (temporal accumulation)");
}

static void group_bvh(layout *l, tg_frame *f)
{
    const tg_scene *s = f->scene;
    int traces = f->request.technique == TG_TECH_PATHTRACE, n;
    if (TG_NO_REFERENCE) return;
    if (f->request.technique != TG_TECH_REFERENCE && !traces) return;
    f->bvh_scratch_bytes = tgi_bvh_bytes(s->tri_count);
    f->bvh_scratch = take(l, traces ? "BVH of the triangles (path tracer)" : "reference BVH", f->bvh_scratch_bytes, 1);
    n = traces ? tgi_pathtrace_emitter_count(s->tri_material, s->materials, s->tri_count) : 0;
    if (n > 0) f->emitters = take(l, "emissive triangles (path tracer's next-event table)", tgi_pathtrace_emitter_bytes(n), 1);
}

/* E_far's own plane: its AOV, or a technique that writes it (SSDO, bent
 * cones); else compose computes it per pixel. */
static void group_far(layout *l, tg_frame *f)
{
    int technique_far = f->request.technique == TG_TECH_SSDO || f->request.technique == TG_TECH_BENTCONE;
    if (!TG_NO_COLOR && (f->effects & TG_EFFECT_FAR) && (technique_far || wants_aov(f, TG_AOV_FAR)))
        take_rgb(l, "far-field irradiance E_far [" FMT_RGB "]", f->pixels, &f->far);
}

/* The filtered full-resolution results the AOVs ask for (other techniques
 * read their results as they are). */
static void group_color(layout *l, tg_frame *f)
{
    int ao = wants_aov(f, TG_AOV_AO) || wants_aov(f, TG_AOV_CONE), bent = !TG_NO_BENT_NORMALS && wants_aov(f, TG_AOV_BENT);
    int near = wants_aov(f, TG_AOV_NEAR) && near_field(f);
    if (!resolves_into_planes(f) || !(ao || bent || near)) return;
#if TGI_DEPTH_LAYERS && !TG_WIDE_STORAGE
    /* AO alone over further depth layers at every pixel: the filtered AO
     * (8 bits a pixel) in the second layer's bytes (8-bit codes), which
     * only the kernel reads, a pass before the resolve writes them (the
     * next frame's rasterizer draws the layer anew): AO-only frames take
     * the second layer for 1 byte a pixel */
    if (!bent && !near && f->request.depth_layers >= 2 && f->request.gi_scale == 1) {
        note_buffer(l->plan, "filtered AO, in the second layer's bytes once the kernel has read them [" FMT_AO "]", 0);
        if (l->arena) tgi_gresult_carve(&f->out, f->pixels, 0, 0, 0, f->gb.back_depth);   /* group_gbuffer took it */
        return;
    }
#endif
    take_results(l, &f->out, f->pixels, bent, near, "filtered results for the AOVs asked [" FMT_AO ", " FMT_BENT ", " FMT_RGB "]");
    if (!ao) f->out.ao = NULL;
}

static void group_irradiance(layout *l, tg_frame *f)
{
    if (!TG_NO_COLOR && (f->needs & TG_NEED_COMPOSE) && wants_aov(f, TG_AOV_IRRADIANCE))
        take_rgb(l, "total irradiance [" FMT_RGB "]", f->pixels, &f->irradiance);
}

static void (*const group_layout[TGI_BUF_GROUPS])(layout *l, tg_frame *f) = {
    group_pose, group_gbuffer, group_motion, group_shadow_maps, group_direct,
    group_source, group_history, group_reproject, group_results, group_half,
    group_filter, group_temporal, group_bvh, group_far,
    group_color, group_irradiance
};

/* ---- the walk ---- */

static void frame_init(tg_frame *f, const tg_plan *plan, size_t pixels)
{
    f->request = plan->request;
    f->pass_count = plan->pass_count;
    memcpy(f->pass_rows, plan->pass_rows, sizeof f->pass_rows);
    f->scene = plan->scene;
    f->width = plan->request.width;
    f->height = plan->request.height;
    f->pixels = pixels;
    f->effects = plan->effects;
    f->needs = tgi_frame_needs(plan);
}

/* The views the passes read: the full-resolution G-buffer, and the image
 * the interleaved kernel splits (the full view or the quarter-res copy). */
static void frame_views(tg_frame *f)
{
    tgi_gview_of(&f->full, &f->gb, &f->view);
    if (tgi_frame_quarter(f))
        tgi_gview_packed(&f->half_view, &f->half, 0, f->half.width, f->half.height, 2, 0, 0, &f->view);
    tgi_frame_begin(f);
}

const tgi_rgb *tgi_frame_source(const tg_frame *f)
{
    return f->bounce > 0 ? &f->bounce_source : &f->source;
}

const tgi_gview *tgi_frame_kernel(const tg_frame *f, const tgi_gresult **res, const tgi_rgb **source)
{
    int quarter = tgi_frame_quarter(f);
    if (res) *res = quarter ? &f->half_res : &f->res;
    if (source) *source = quarter ? &f->half_source : tgi_frame_source(f);
    return quarter ? &f->half_view : &f->full;
}

#if !TG_NO_COLOR
/* The plane under a colour plane's first pointer (push/pull's scratch). */
static void *plane_memory(const tgi_rgb *c)
{
#if TG_WIDE_STORAGE
    return c->r;
#else
    return c->p;
#endif
}
#endif

/* This frame's results: set t of two (temporal accumulation), else the one. */
static void results_roles(const tgi_gresult *set, int t, tgi_gresult *res, tgi_gresult *prev)
{
    int two = set[1].ao != NULL;
    *res = set[two ? t : 0];
    *prev = set[two ? 1 - t : 0];
}

void tgi_frame_begin(tg_frame *f)
{
    int t = f->frames_rendered & 1;
#if !TG_NO_COLOR /* without colour (tinygi.h "FEATURE SWITCHES") the radiance planes stay none, as carved */
    int two = tgi_rgb_present(&f->slot[1]);
    const tgi_rgb *lo = two ? &f->slot[1 - t] : &f->slot[0], *hist = two ? &f->slot[t] : &f->slot[0];
#endif
    results_roles(f->set, t, &f->res, &f->res_prev);
    results_roles(f->half_set, t, &f->half_res, &f->half_prev);
#if !TG_NO_COLOR
    if (two) { f->res.near = f->slot[t]; f->res_prev.near = f->slot[1 - t]; }
    f->color = (f->needs & TG_NEED_COMPOSE) ? *lo : tgi_rgb_none();
    if (!direct_own(f)) f->direct = (f->effects & (TG_EFFECT_DIRECT | TG_EFFECT_NEAR)) ? *lo : tgi_rgb_none();
    f->history = reprojects(f) ? *hist : tgi_rgb_none();
    f->pushpull_mips = reprojects(f) ? plane_memory(hist) : NULL;
    f->source = tgi_rgb_none();
    if (near_field(f)) f->source = f->has_history ? f->bounce_source : tgi_rgb_lit_by(&f->direct, &f->gb);
#endif
    if (!resolves_into_planes(f)) f->out = f->res;
}

/* 1 when the plan has no room for another pass (TG_PLAN_MAX_PASSES). */
static int add_pass(tg_plan *p, int row)
{
    if (p->pass_count >= TG_PLAN_MAX_PASSES || row > 255) return 1;
    p->passes[p->pass_count] = tgi_passes[row].name;
    p->pass_rows[p->pass_count] = (unsigned char)row;
    p->pass_count++;
    return 0;
}

int tgi_frame_layout(tg_frame **fp, tg_plan *plan, tg_arena *arena)
{
    layout l;
    size_t n;
    tg_frame *f;
    int k, g;
    memset(&l, 0, sizeof l);
    l.plan = plan;
    l.arena = arena;
    if (!arena) { plan->pass_count = 0; plan->buffer_count = 0; }
    if (tg_size_mul((size_t)plan->request.width, (size_t)plan->request.height, &n)) return 1;
    f = (tg_frame *)take(&l, "frame state", 1, sizeof(tg_frame));
    if (arena && !f) return 1;
    if (!arena) f = *fp;
    *fp = f;
    frame_init(f, plan, n);
    for (k = 0; k < tgi_pass_count; k++) {
        const tgi_pass *p = &tgi_passes[k];
        if (!p->needed(f)) continue;
        if (!arena && add_pass(plan, k)) return 1;
        for (g = 0; g < TGI_BUF_GROUPS && !l.overflow; g++)   /* the memory ran out: no group carves on */
            if ((p->buffers & TGI_BUF(g)) && !(l.carved & TGI_BUF(g))) {
                l.carved |= TGI_BUF(g);
                group_layout[g](&l, f);
            }
    }
    if (l.overflow) return 1;
    if (arena) frame_views(f);
    else plan->total_bytes = l.total + 16;
    return 0;
}
