/*
 * technique.c - the frame's GI step.
 *
 * HBIL (default): the G-buffer and the near-field source radiance are split
 * into 4x4 = 16 quarter-resolution sub-images (HBIL sec. 3.3), the horizon
 * kernel runs once per sub-image with that sub-image's slice angles, the
 * results are merged back, then filtered over the 4x4 neighbourhood (sec.
 * 3.4) and, across frames, accumulated.  With interleave off the kernel runs
 * at full resolution with the same 32 directions per 4x4 block.
 *
 * The comparison techniques (issue 5) write the same outputs at full
 * resolution from the G-buffer; the reference ray traces the scene.
 */
#include <string.h>
#include "technique.h"
#include "../gi/hbil.h"
#include "../gi/interleave.h"
#include "../gi/resample.h"
#include "../ao/ao.h"
#include "../ao/reference.h"
#include "../light/direct.h"
#include "../gi/reproject.h"
#include "../gi/pushpull.h"
#include "../gi/denoise.h"

/* HBIL eq. 12: the bent cone's half angle from the AO, cos(alpha) = 1 - AO. */
static void cone_from_ao(tg_frame *f)
{
    size_t i;
    if (!f->cone) return;
    for (i = 0; i < f->pixels; i++) f->cone[i] = tg_acos(tg_sub(TG_ONE, tg_saturate(f->ao[i])));
}

static void hbil_params(const tg_frame *f, tg_hbil_params *p)
{
    tg_hbil_defaults(p, &f->view);
    p->slices = f->plan.request.slices;
    p->samples = f->plan.request.samples;
    p->radius = f->plan.request.radius;
}

/* The kernel's image: full resolution, or the quarter-res copy. */
typedef struct kernel_image {
    int w, h, scale;
    const tg_real *depth, *nx, *ny, *nz, *f0, *src_r, *src_g, *src_b;
    const uint8_t *sky;
    tg_real *ao, *bent_x, *bent_y, *bent_z, *near_r, *near_g, *near_b;
} kernel_image;

static void downsample(const tg_frame *f, const tg_real *src, tg_real *dst)
{
    tg_downsample_rows(src, f->width, f->height, dst, 0, f->height);
}

/* Quarter resolution: point-sample the G-buffer (and the near-field
 * source) to half width and height; the kernel writes half-res results. */
static kernel_image quarter_image(tg_frame *f, int near)
{
    const tg_gbuffer *g = &f->gb;
    kernel_image k;
    tg_half_size(f->width, f->height, &k.w, &k.h);
    k.scale = 2;
    downsample(f, g->depth, f->half_depth);
    downsample(f, g->nx, f->half_normal.r);
    downsample(f, g->ny, f->half_normal.g);
    downsample(f, g->nz, f->half_normal.b);
    tg_downsample8_rows(g->sky, f->width, f->height, f->half_sky, 0, f->height);
    k.depth = f->half_depth; k.nx = f->half_normal.r; k.ny = f->half_normal.g; k.nz = f->half_normal.b;
    k.sky = f->half_sky;
    k.ao = f->half_ao; k.bent_x = f->half_bent.r; k.bent_y = f->half_bent.g; k.bent_z = f->half_bent.b;
    k.f0 = k.src_r = k.src_g = k.src_b = NULL;
    k.near_r = k.near_g = k.near_b = NULL;
    if (near) {
        downsample(f, g->f0, f->half_f0);
        downsample(f, f->source.r, f->half_source.r);
        downsample(f, f->source.g, f->half_source.g);
        downsample(f, f->source.b, f->half_source.b);
        k.f0 = f->half_f0;
        k.src_r = f->half_source.r; k.src_g = f->half_source.g; k.src_b = f->half_source.b;
        k.near_r = f->half_near.r; k.near_g = f->half_near.g; k.near_b = f->half_near.b;
    }
    return k;
}

static kernel_image full_image(tg_frame *f, int near)
{
    const tg_gbuffer *g = &f->gb;
    kernel_image k;
    k.w = f->width; k.h = f->height; k.scale = 1;
    k.depth = g->depth; k.nx = g->nx; k.ny = g->ny; k.nz = g->nz; k.sky = g->sky;
    k.ao = f->ao; k.bent_x = f->bent.r; k.bent_y = f->bent.g; k.bent_z = f->bent.b;
    k.f0 = near ? g->f0 : NULL;
    k.src_r = near ? f->source.r : NULL; k.src_g = near ? f->source.g : NULL; k.src_b = near ? f->source.b : NULL;
    k.near_r = near ? f->near.r : NULL; k.near_g = near ? f->near.g : NULL; k.near_b = near ? f->near.b : NULL;
    return k;
}

/* Joint bilateral upsample of the quarter-res results (resample.c). */
static void upsample(tg_frame *f, int near)
{
    const tg_gbuffer *g = &f->gb;
    tg_upsample_io io;
    memset(&io, 0, sizeof io);
    io.width = f->width; io.height = f->height;
    io.depth = g->depth; io.nx = g->nx; io.ny = g->ny; io.nz = g->nz; io.sky = g->sky;
    io.half_depth = f->half_depth;
    io.half_nx = f->half_normal.r; io.half_ny = f->half_normal.g; io.half_nz = f->half_normal.b;
    io.half_sky = f->half_sky;
    io.half_ao = f->half_ao;
    io.half_bent_x = f->half_bent.r; io.half_bent_y = f->half_bent.g; io.half_bent_z = f->half_bent.b;
    io.ao = f->ao;
    io.bent_x = f->bent.r; io.bent_y = f->bent.g; io.bent_z = f->bent.b;
    if (near) {
        io.half_near_r = f->half_near.r; io.half_near_g = f->half_near.g; io.half_near_b = f->half_near.b;
        io.near_r = f->near.r; io.near_g = f->near.g; io.near_b = f->near.b;
    }
    tg_upsample_rows(&io, 0, f->height);
}

/* HBIL sec. 3.3: split into 16 sub-images, the kernel on each with its own
 * slice angles (marching in sub-image pixels), merge back. */
static void hbil_interleaved(tg_frame *f)
{
    int near = (f->effects & TG_EFFECT_NEAR) != 0, i, j;
    kernel_image k = f->half_depth ? quarter_image(f, near) : full_image(f, near);
    tg_interleave_split(k.depth, k.w, k.h, f->q_depth);
    tg_interleave_split(k.nx, k.w, k.h, f->q_normal.r);
    tg_interleave_split(k.ny, k.w, k.h, f->q_normal.g);
    tg_interleave_split(k.nz, k.w, k.h, f->q_normal.b);
    tg_interleave_split8(k.sky, k.w, k.h, f->q_sky);
    if (near) {
        tg_interleave_split(k.f0, k.w, k.h, f->q_f0);
        tg_interleave_split(k.src_r, k.w, k.h, f->q_source.r);
        tg_interleave_split(k.src_g, k.w, k.h, f->q_source.g);
        tg_interleave_split(k.src_b, k.w, k.h, f->q_source.b);
    }
    for (j = 0; j < 4; j++) {
        for (i = 0; i < 4; i++) {
            tg_hbil_params p;
            tg_hbil_io io;
            int sw, sh;
            size_t o;
            tg_interleave_sub_rect(k.w, k.h, i, j, &sw, &sh, &o);
            if (sw == 0 || sh == 0) continue;
            hbil_params(f, &p);
            p.step = 4 * k.scale;
            p.offset_x = i * k.scale;
            p.offset_y = j * k.scale;
            p.slice_phi0 = tg_hbil_slice_phi0(i, j, p.slices);
            memset(&io, 0, sizeof io);
            io.width = sw;
            io.height = sh;
            io.depth = f->q_depth + o;
            io.nx = f->q_normal.r + o; io.ny = f->q_normal.g + o; io.nz = f->q_normal.b + o;
            io.sky = f->q_sky + o;
            io.ao = f->q_ao + o;
            io.bent_x = f->q_bent.r + o; io.bent_y = f->q_bent.g + o; io.bent_z = f->q_bent.b + o;
            if (near) {
                io.f0 = f->q_f0 + o;
                io.rad_r = f->q_source.r + o; io.rad_g = f->q_source.g + o; io.rad_b = f->q_source.b + o;
                io.near_r = f->q_near.r + o; io.near_g = f->q_near.g + o; io.near_b = f->q_near.b + o;
            }
            tg_hbil_rows(&p, &io, 0, sh);
        }
    }
    tg_interleave_merge(f->q_ao, k.w, k.h, k.ao);
    tg_interleave_merge(f->q_bent.r, k.w, k.h, k.bent_x);
    tg_interleave_merge(f->q_bent.g, k.w, k.h, k.bent_y);
    tg_interleave_merge(f->q_bent.b, k.w, k.h, k.bent_z);
    if (near) {
        tg_interleave_merge(f->q_near.r, k.w, k.h, k.near_r);
        tg_interleave_merge(f->q_near.g, k.w, k.h, k.near_g);
        tg_interleave_merge(f->q_near.b, k.w, k.h, k.near_b);
    }
}

static void hbil_full(tg_frame *f)
{
    const tg_gbuffer *g = &f->gb;
    tg_hbil_params p;
    tg_hbil_io io;
    hbil_params(f, &p);
    p.per_pixel_pattern = 1;
    memset(&io, 0, sizeof io);
    io.width = f->width;
    io.height = f->height;
    io.depth = g->depth; io.nx = g->nx; io.ny = g->ny; io.nz = g->nz;
    io.sky = g->sky;
    io.ao = f->ao;
    io.bent_x = f->bent.r; io.bent_y = f->bent.g; io.bent_z = f->bent.b;
    if (f->effects & TG_EFFECT_NEAR) {
        io.f0 = g->f0;
        io.rad_r = f->source.r; io.rad_g = f->source.g; io.rad_b = f->source.b;
        io.near_r = f->near.r; io.near_g = f->near.g; io.near_b = f->near.b;
    }
    tg_hbil_rows(&p, &io, 0, f->height);
}

static tg_ao_io ao_io(tg_frame *f)
{
    tg_ao_io io;
    const tg_gbuffer *g = &f->gb;
    memset(&io, 0, sizeof io);
    io.width = f->width;
    io.height = f->height;
    io.view = &f->view;
    io.depth = g->depth; io.nx = g->nx; io.ny = g->ny; io.nz = g->nz;
    io.sky = g->sky;
    if (f->effects & TG_EFFECT_NEAR) {
        io.rad_r = f->source.r; io.rad_g = f->source.g; io.rad_b = f->source.b;
        io.near_r = f->near.r; io.near_g = f->near.g; io.near_b = f->near.b;
    }
    io.ao = f->ao;
    io.bent_x = f->bent.r; io.bent_y = f->bent.g; io.bent_z = f->bent.b;
    io.cone = f->cone;
    return io;
}

/* Outgoing diffuse radiance leaving a scene point under the direct lights:
 * the reference's exact one-bounce source (same lights, same shadow maps). */
static tg_vec3 direct_radiance_at(void *user, int tri, tg_vec3 pos, tg_vec3 nrm)
{
    const tg_frame *f = (const tg_frame *)user;
    const tg_scene *s = f->scene;
    const tg_material *m = &s->materials[s->tri_material[tri]];
    tg_vec3 e = tg_v3(0, 0, 0), lo;
    tg_real k;
    int l;
    if (f->effects & TG_EFFECT_DIRECT) {
        for (l = 0; l < s->light_count; l++) {
            tg_vec3 el = tg_direct_irradiance(&s->lights[l], pos, nrm);
            if (f->shadow_ptrs && f->shadow_ptrs[l])
                el = tg_v3_scale(el, tg_shadow_visibility(f->shadow_ptrs[l], pos, nrm));
            e = tg_v3_add(e, el);
        }
    }
    k = tg_mul(TG_INV_PI, tg_sub(TG_ONE, m->f0));   /* compose: albedo / pi * (1 - F0) */
    lo = tg_v3_scale(tg_v3_mul(m->albedo, e), k);
    return tg_v3_add(lo, m->emissive);
}

static void reference(tg_frame *f)
{
    tg_reference_params p;
    tg_ao_io io = ao_io(f);
    const tg_vec3 *pos = f->posed_pos ? f->posed_pos : f->scene->tri_pos;
    tg_reference_defaults(&p);
    tg_bvh_build(&f->bvh, pos, f->scene->tri_count, f->technique_scratch, f->technique_scratch_bytes);
    p.bvh = &f->bvh;
    p.tri_nrm = f->posed_nrm ? f->posed_nrm : f->scene->tri_nrm;
    p.samples = f->plan.request.samples > 16 ? f->plan.request.samples : 256;
    p.radius = f->plan.request.radius;
    p.radiance = direct_radiance_at;
    p.user = f;
    tg_reference_rows(&p, &io, 0, f->height);
}

/* HBIL sec. 3.3-3.4: the depth/normal-aware filter over the 4x4
 * neighbourhood (at the kernel's resolution, where the 4x4 pattern lives),
 * then the upsample from quarter resolution, then (across frames) temporal
 * accumulation at full resolution. */
static void hbil_filter(tg_frame *f, int index)
{
    tg_denoise_params p;
    tg_denoise_io io;
    const tg_gbuffer *g = &f->gb;
    int near = (f->effects & TG_EFFECT_NEAR) != 0;
    tg_denoise_defaults(&p);
    memset(&io, 0, sizeof io);
    if (f->half_depth) {
        tg_half_size(f->width, f->height, &io.width, &io.height);
        io.depth = f->half_depth;
        io.nx = f->half_normal.r; io.ny = f->half_normal.g; io.nz = f->half_normal.b;
        io.sky = f->half_sky;
        io.ao = f->half_ao;
        io.bent_x = f->half_bent.r; io.bent_y = f->half_bent.g; io.bent_z = f->half_bent.b;
        io.near_r = f->half_near.r; io.near_g = f->half_near.g; io.near_b = f->half_near.b;
        tg_denoise_begin(&io, f->denoise_scratch);
        tg_denoise_rows(&p, &io, f->denoise_scratch, 0, io.height);
        upsample(f, near);
    }
    io.width = f->width;
    io.height = f->height;
    io.depth = g->depth; io.nx = g->nx; io.ny = g->ny; io.nz = g->nz;
    io.sky = g->sky;
    io.ao = f->ao;
    io.bent_x = f->bent.r; io.bent_y = f->bent.g; io.bent_z = f->bent.b;
    io.cone = f->cone;
    io.near_r = f->near.r; io.near_g = f->near.g; io.near_b = f->near.b;
    if (!f->half_depth) {
        tg_denoise_begin(&io, f->denoise_scratch);
        tg_denoise_rows(&p, &io, f->denoise_scratch, 0, f->height);
    }
    if (f->temporal_state)
        tg_temporal_rows(&p, &io, f->temporal_state, &f->prev_view, &f->view, index,
                         f->frames_rendered == 0, 0, f->height);
}

int tg_frame_technique(tg_frame *f, int index)
{
    int far_done = 0;
    switch (f->plan.request.technique) {
    case TG_TECH_HBIL:
        if (f->plan.request.interleave) hbil_interleaved(f);
        else hbil_full(f);
        hbil_filter(f, index);
        break;
    case TG_TECH_REFERENCE:
        reference(f);
        break;
    default:
        far_done = tg_frame_technique_other(f, ao_io(f));
        break;
    }
    cone_from_ao(f);
    return far_done;
}

/* HBIL sec. 3.2: scatter last frame's radiance into this view through a
 * temporary z-buffer (nearest wins), then fill the holes by push/pull. */
int tg_frame_reproject(tg_frame *f)
{
    tg_reproject_io io;
    unsigned char *scratch = (unsigned char *)f->reproject_scratch;
    size_t zbytes = (tg_reproject_bytes(f->width, f->height) + 15u) & ~(size_t)15u;
    size_t pbytes = (tg_pushpull_bytes(f->width, f->height) + 15u) & ~(size_t)15u;
    uint8_t *valid = scratch + zbytes + pbytes;
    if (!f->history.r || !scratch) return 0;
    memset(&io, 0, sizeof io);
    io.width = f->width;
    io.height = f->height;
    io.prev_view = &f->prev_view;
    io.view = &f->view;
    io.prev_depth = f->history_depth;
    io.prev_r = f->history.r; io.prev_g = f->history.g; io.prev_b = f->history.b;
    io.out_r = f->source.r; io.out_g = f->source.g; io.out_b = f->source.b;
    io.valid = valid;
    tg_reproject_scatter(&io, scratch);
    tg_pushpull_fill(f->width, f->height, f->source.r, f->source.g, f->source.b, valid, scratch + zbytes);
    return 1;
}
