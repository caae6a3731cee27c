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
#include "../gi/denoise.h"
#include "../gi/temporal.h"
#include "../gi/resample.h"

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

static tg_real *take_real(layout *l, const char *name, size_t n)
{
    return (tg_real *)take(l, name, n, sizeof(tg_real));
}

static void take_rgb(layout *l, const char *name, size_t n, tgi_rgb *c)
{
#if TG_WIDE_STORAGE
    c->r = take_real(l, name, n);
    c->g = take_real(l, name, n);
    c->b = take_real(l, name, n);
#else
    c->p = (uint32_t *)take(l, name, n, sizeof(uint32_t));
#endif
}

/* Depth, normal and material index: the storage of a G-buffer of n pixels. */
static void take_gbuffer_planes(layout *l, tgi_gbuffer *g, const tg_scene *s, size_t n, int w, int h,
                                const char *depth, const char *normal)
{
    int i;
    g->width = w;
    g->height = h;
    g->materials = s->materials;
    g->has_emissive = 0;
    for (i = 0; i < s->material_count; i++) {
        tg_vec3 e = s->materials[i].emissive;
        if (e.x > 0 || e.y > 0 || e.z > 0) g->has_emissive = 1;
    }
#if TG_WIDE_STORAGE
    g->depth = take_real(l, depth, n);
    g->nx = take_real(l, normal, n);
    g->ny = take_real(l, normal, n);
    g->nz = take_real(l, normal, n);
    g->material = (uint16_t *)take(l, normal, n, sizeof(uint16_t));
#else
    g->depth = (uint32_t *)take(l, depth, n, sizeof(uint32_t));
    g->nm = (uint32_t *)take(l, normal, n, sizeof(uint32_t));
#endif
}

static void take_results(layout *l, tgi_gresult *r, size_t n, int bent, int near,
                         const char *ao_name, const char *bent_name, const char *near_name)
{
#if TG_WIDE_STORAGE
    r->ao = take_real(l, ao_name, n);
    if (bent) {
        r->bent_x = take_real(l, bent_name, n);
        r->bent_y = take_real(l, bent_name, n);
        r->bent_z = take_real(l, bent_name, n);
    }
#else
    r->ao = (uint8_t *)take(l, ao_name, n, 1);
    if (bent) r->bent = (uint16_t *)take(l, bent_name, n, sizeof(uint16_t));
#endif
    if (near) take_rgb(l, near_name, n, &r->near);
}

/* The kernel's results at its own resolution: AO, bent normal, near field. */
static void take_kernel_results(layout *l, tgi_gresult *r, size_t n, int near, const char *name)
{
    take_results(l, r, n, 1, near, name, name, name);
}

/* The kernel's image: full size, or half width and height (quarter res). */
static void kernel_size(const tg_frame *f, int *w, int *h, size_t *n)
{
    *w = f->width;
    *h = f->height;
    if (tgi_frame_quarter(f)) tgi_half_size(f->width, f->height, w, h);
    *n = (size_t)*w * (size_t)*h;
}

/* ---- the groups ---- */

static void group_pose(layout *l, tg_frame *f)
{
    const tg_scene *s = f->scene;
    if (!(f->needs & TG_NEED_POSE)) return;
    f->posed_pos = (tg_vec3 *)take(l, "posed triangles", (size_t)s->tri_count * 3, sizeof(tg_vec3));
    f->posed_nrm = (tg_vec3 *)take(l, "posed triangles", (size_t)s->tri_count * 3, sizeof(tg_vec3));
    f->object_delta = (tgi_mat4 *)take(l, "object motion", (size_t)s->object_count, sizeof(tgi_mat4));
}

static void group_gbuffer(layout *l, tg_frame *f)
{
    tgi_gbuffer *g = &f->gb;
    size_t n = f->pixels;
    take_gbuffer_planes(l, g, f->scene, n, f->width, f->height, "G-buffer depth (view z; 0: sky)",
                        "G-buffer normal and material index");
    if (f->needs & (TG_NEED_MOTION | TG_NEED_POSE))
        g->object = (uint16_t *)take(l, "G-buffer object id", n, 2);
}

static void group_motion(layout *l, tg_frame *f)
{
    if (!(f->needs & TG_NEED_MOTION)) return;
    f->gb.motion_x = take_real(l, "motion vectors", f->pixels);
    f->gb.motion_y = take_real(l, "motion vectors", f->pixels);
}

static void group_shadow_maps(layout *l, tg_frame *f)
{
    const tg_scene *s = f->scene;
    const tg_request *r = &f->request;
    int i;
    if (!(f->effects & TG_EFFECT_SHADOWS)) return;
    f->shadow_maps = (tgi_shadow_map *)take(l, "shadow map descriptors", (size_t)s->light_count, sizeof(tgi_shadow_map));
    f->shadow_ptrs = (const tgi_shadow_map **)take(l, "shadow map descriptors", (size_t)s->light_count, sizeof(void *));
    for (i = 0; i < s->light_count; i++) {
        void *depth;
        if (!s->lights[i].shadows) continue;
        depth = take(l, "shadow maps (depth)", tgi_shadow_map_bytes(&s->lights[i], r->shadow_map_size), 1);
        if (!l->arena || !depth) continue;
        tgi_shadow_map_setup(&f->shadow_maps[i], &s->lights[i], r->shadow_map_size, s->bounds_min, s->bounds_max, depth);
        f->shadow_maps[i].filter = r->shadow_pcf ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT;
        f->shadow_ptrs[i] = &f->shadow_maps[i];
    }
}

static void group_direct(layout *l, tg_frame *f)
{
    if (f->effects & TG_EFFECT_DIRECT) take_rgb(l, "direct irradiance E_direct", f->pixels, &f->direct);
}

static void group_source(layout *l, tg_frame *f)
{
    if (f->effects & TG_EFFECT_NEAR) take_rgb(l, "near-field source radiance", f->pixels, &f->source);
}

static void group_history(layout *l, tg_frame *f)
{
    if (!(f->effects & TG_EFFECT_REPROJECTION)) return;
    take_rgb(l, "radiance history (last frame)", f->pixels, &f->history);
#if TG_WIDE_STORAGE
    f->prev_geometry.depth = take_real(l, "last frame's depth and normal", f->pixels);
    f->prev_geometry.nx = take_real(l, "last frame's depth and normal", f->pixels);
    f->prev_geometry.ny = take_real(l, "last frame's depth and normal", f->pixels);
    f->prev_geometry.nz = take_real(l, "last frame's depth and normal", f->pixels);
#else
    f->prev_geometry.dn = (uint32_t *)take(l, "last frame's depth and normal", f->pixels, sizeof(uint32_t));
#endif
}

/* The push/pull mip chain. */
static void group_reproject(layout *l, tg_frame *f)
{
    if (!(f->effects & TG_EFFECT_REPROJECTION)) return;
    f->pushpull_mips = take(l, "push/pull mips", tgi_pushpull_bytes(f->width, f->height), 1);
}

static void group_results(layout *l, tg_frame *f)
{
    int hbil = f->request.technique == TG_TECH_HBIL;
    if (!(f->needs & TG_NEED_GI_PASS)) return;
    take_results(l, &f->res, f->pixels, (f->needs & TG_NEED_BENT) || hbil, (f->effects & TG_EFFECT_NEAR) != 0,
                 "ambient occlusion", "bent normal (world)", "near-field irradiance E_near");
}

static void group_half(layout *l, tg_frame *f)
{
    int near = (f->effects & TG_EFFECT_NEAR) != 0, w, h;
    size_t n;
    if (!tgi_frame_quarter(f)) return;
    kernel_size(f, &w, &h, &n);
    take_gbuffer_planes(l, &f->half, f->scene, n, w, h, "quarter-res G-buffer (depth, normal, material)",
                        "quarter-res G-buffer (depth, normal, material)");
    if (near) take_rgb(l, "quarter-res source radiance", n, &f->half_source);
    take_kernel_results(l, &f->half_res, n, near, "quarter-res kernel output");
}

static void group_split(layout *l, tg_frame *f)
{
    int near = (f->effects & TG_EFFECT_NEAR) != 0, w, h;
    size_t n;
    if (!tgi_frame_interleaved(f)) return;
    kernel_size(f, &w, &h, &n);
    take_gbuffer_planes(l, &f->split, f->scene, n, w, h, "4x4 split: depth", "4x4 split: normal and material");
    if (near) take_rgb(l, "4x4 split: source radiance", n, &f->split_source);
    take_kernel_results(l, &f->split_res, n, near, "4x4 split: kernel output");
}

static void group_filter(layout *l, tg_frame *f)
{
    int w, h;
    size_t n;
    if (f->request.technique != TG_TECH_HBIL) return;
    kernel_size(f, &w, &h, &n);
    f->denoise_scratch = take(l, "spatial filter input", tgi_denoise_bytes(w, h), 1);
}

static void group_temporal(layout *l, tg_frame *f)
{
    if (f->needs & TG_NEED_TEMPORAL)
        f->temporal_state = take(l, "temporal accumulation history", tgi_temporal_bytes(f->width, f->height), 1);
}

static void group_bvh(layout *l, tg_frame *f)
{
    if (f->request.technique != TG_TECH_REFERENCE) return;
    f->bvh_scratch_bytes = tgi_bvh_bytes(f->scene->tri_count);
    f->bvh_scratch = take(l, "reference BVH", f->bvh_scratch_bytes, 1);
}

static void group_far(layout *l, tg_frame *f)
{
    if (f->effects & TG_EFFECT_FAR) take_rgb(l, "far-field irradiance E_far", f->pixels, &f->far);
}

static void group_color(layout *l, tg_frame *f)
{
    if (f->needs & TG_NEED_COMPOSE) take_rgb(l, "outgoing radiance Lo (colour)", f->pixels, &f->color);
}

static void group_irradiance(layout *l, tg_frame *f)
{
    if ((f->needs & TG_NEED_COMPOSE) && (f->request.aovs & AOV(TG_AOV_IRRADIANCE)))
        take_rgb(l, "total irradiance", f->pixels, &f->irradiance);
}

static void (*const group_layout[TGI_BUF_GROUPS])(layout *l, tg_frame *f) = {
    group_pose, group_gbuffer, group_motion, group_shadow_maps, group_direct,
    group_source, group_history, group_reproject, group_results, group_half,
    group_split, group_filter, group_temporal, group_bvh, group_far,
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
}

const tgi_gview *tgi_frame_kernel(const tg_frame *f, const tgi_gresult **res, const tgi_rgb **source)
{
    int quarter = tgi_frame_quarter(f);
    if (res) *res = quarter ? &f->half_res : &f->res;
    if (source) *source = quarter ? &f->half_source : &f->source;
    return quarter ? &f->half_view : &f->full;
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
        for (g = 0; g < TGI_BUF_GROUPS; g++)
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
