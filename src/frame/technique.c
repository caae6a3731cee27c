/* SPDX-License-Identifier: MIT */
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

static void hbil_params(const tg_frame *f, tgi_hbil_params *p)
{
    tgi_hbil_defaults(p, &f->view);
    p->slices = f->plan.request.slices;
    p->samples = f->plan.request.samples;
    p->radius = f->plan.request.radius;
}

/* The kernel's image: full resolution, or the quarter-res copy. */
typedef struct kernel_image {
    int w, h, scale, near;
    const tg_real *depth, *nx, *ny, *nz, *f0, *src_r, *src_g, *src_b;
    const uint8_t *sky;
    tg_real *ao, *bent_x, *bent_y, *bent_z, *near_r, *near_g, *near_b;
} kernel_image;

/* Which buffers the interleaved kernel reads and writes: the quarter-res
 * copies when the plan has them, the full-res G-buffer otherwise. */
static kernel_image kernel_of(tg_frame *f)
{
    const tgi_gbuffer *g = &f->gb;
    kernel_image k;
    int q = f->half_depth != NULL;
    memset(&k, 0, sizeof k);
    k.near = (f->effects & TG_EFFECT_NEAR) != 0;
    k.scale = q ? 2 : 1;
    if (q) tgi_half_size(f->width, f->height, &k.w, &k.h);
    else { k.w = f->width; k.h = f->height; }
    k.depth = q ? f->half_depth : g->depth;
    k.nx = q ? f->half_normal.r : g->nx;
    k.ny = q ? f->half_normal.g : g->ny;
    k.nz = q ? f->half_normal.b : g->nz;
    k.sky = q ? f->half_sky : g->sky;
    k.ao = q ? f->half_ao : f->ao;
    k.bent_x = q ? f->half_bent.r : f->bent.r;
    k.bent_y = q ? f->half_bent.g : f->bent.g;
    k.bent_z = q ? f->half_bent.b : f->bent.b;
    if (k.near) {
        k.f0 = q ? f->half_f0 : g->f0;
        k.src_r = q ? f->half_source.r : f->source.r;
        k.src_g = q ? f->half_source.g : f->source.g;
        k.src_b = q ? f->half_source.b : f->source.b;
        k.near_r = q ? f->half_near.r : f->near.r;
        k.near_g = q ? f->half_near.g : f->near.g;
        k.near_b = q ? f->half_near.b : f->near.b;
    }
    return k;
}

static void downsample(const tg_frame *f, const tg_real *src, tg_real *dst)
{
    tgi_downsample_rows(src, f->width, f->height, dst, 0, f->height);
}

void tgi_hbil_stage_downsample(tg_frame *f)
{
    const tgi_gbuffer *g = &f->gb;
    if (!f->half_depth) return;
    downsample(f, g->depth, f->half_depth);
    downsample(f, g->nx, f->half_normal.r);
    downsample(f, g->ny, f->half_normal.g);
    downsample(f, g->nz, f->half_normal.b);
    tgi_downsample8_rows(g->sky, f->width, f->height, f->half_sky, 0, f->height);
    if (f->effects & TG_EFFECT_NEAR) {
        downsample(f, g->f0, f->half_f0);
        downsample(f, f->source.r, f->half_source.r);
        downsample(f, f->source.g, f->half_source.g);
        downsample(f, f->source.b, f->half_source.b);
    }
}

void tgi_hbil_stage_split(tg_frame *f)
{
    kernel_image k = kernel_of(f);
    tgi_interleave_split(k.depth, k.w, k.h, f->q_depth);
    tgi_interleave_split(k.nx, k.w, k.h, f->q_normal.r);
    tgi_interleave_split(k.ny, k.w, k.h, f->q_normal.g);
    tgi_interleave_split(k.nz, k.w, k.h, f->q_normal.b);
    tgi_interleave_split8(k.sky, k.w, k.h, f->q_sky);
    if (k.near) {
        tgi_interleave_split(k.f0, k.w, k.h, f->q_f0);
        tgi_interleave_split(k.src_r, k.w, k.h, f->q_source.r);
        tgi_interleave_split(k.src_g, k.w, k.h, f->q_source.g);
        tgi_interleave_split(k.src_b, k.w, k.h, f->q_source.b);
    }
}

/* The kernel on each of the 16 sub-images, with its own slice angles,
 * marching in sub-image pixels (HBIL sec. 3.3). */
void tgi_hbil_stage_kernel(tg_frame *f)
{
    kernel_image k = kernel_of(f);
    int i, j;
    for (j = 0; j < 4; j++) {
        for (i = 0; i < 4; i++) {
            tgi_hbil_params p;
            tgi_hbil_io io;
            int sw, sh;
            size_t o;
            tgi_interleave_sub_rect(k.w, k.h, i, j, &sw, &sh, &o);
            if (sw == 0 || sh == 0) continue;
            hbil_params(f, &p);
            p.step = 4 * k.scale;
            p.offset_x = i * k.scale;
            p.offset_y = j * k.scale;
            p.slice_phi0 = tgi_hbil_slice_phi0(i, j, p.slices);
            memset(&io, 0, sizeof io);
            io.width = sw;
            io.height = sh;
            io.depth = f->q_depth + o;
            io.nx = f->q_normal.r + o; io.ny = f->q_normal.g + o; io.nz = f->q_normal.b + o;
            io.sky = f->q_sky + o;
            io.ao = f->q_ao + o;
            io.bent_x = f->q_bent.r + o; io.bent_y = f->q_bent.g + o; io.bent_z = f->q_bent.b + o;
            if (k.near) {
                io.f0 = f->q_f0 + o;
                io.rad_r = f->q_source.r + o; io.rad_g = f->q_source.g + o; io.rad_b = f->q_source.b + o;
                io.near_r = f->q_near.r + o; io.near_g = f->q_near.g + o; io.near_b = f->q_near.b + o;
            }
            tgi_hbil_rows(&p, &io, 0, sh);
        }
    }
}

void tgi_hbil_stage_merge(tg_frame *f)
{
    kernel_image k = kernel_of(f);
    tgi_interleave_merge(f->q_ao, k.w, k.h, k.ao);
    tgi_interleave_merge(f->q_bent.r, k.w, k.h, k.bent_x);
    tgi_interleave_merge(f->q_bent.g, k.w, k.h, k.bent_y);
    tgi_interleave_merge(f->q_bent.b, k.w, k.h, k.bent_z);
    if (k.near) {
        tgi_interleave_merge(f->q_near.r, k.w, k.h, k.near_r);
        tgi_interleave_merge(f->q_near.g, k.w, k.h, k.near_g);
        tgi_interleave_merge(f->q_near.b, k.w, k.h, k.near_b);
    }
}

/* HBIL sec. 3.3-3.4: the depth/normal-aware filter over the 4x4
 * neighbourhood, at the kernel's resolution (where the 4x4 pattern lives). */
void tgi_hbil_stage_filter(tg_frame *f)
{
    kernel_image k = kernel_of(f);
    tgi_denoise_params p;
    tgi_denoise_io io;
    tgi_denoise_defaults(&p);
    memset(&io, 0, sizeof io);
    io.width = k.w;
    io.height = k.h;
    io.depth = k.depth; io.nx = k.nx; io.ny = k.ny; io.nz = k.nz;
    io.sky = k.sky;
    io.ao = k.ao;
    io.bent_x = k.bent_x; io.bent_y = k.bent_y; io.bent_z = k.bent_z;
    io.near_r = k.near_r; io.near_g = k.near_g; io.near_b = k.near_b;
    tgi_denoise_begin(&io, f->denoise_scratch);
    tgi_denoise_rows(&p, &io, f->denoise_scratch, 0, io.height);
}

/* Joint bilateral upsample of the quarter-res results (resample.c). */
void tgi_hbil_stage_upsample(tg_frame *f)
{
    const tgi_gbuffer *g = &f->gb;
    tgi_upsample_io io;
    if (!f->half_depth) return;
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
    if (f->effects & TG_EFFECT_NEAR) {
        io.half_near_r = f->half_near.r; io.half_near_g = f->half_near.g; io.half_near_b = f->half_near.b;
        io.near_r = f->near.r; io.near_g = f->near.g; io.near_b = f->near.b;
    }
    tgi_upsample_rows(&io, 0, f->height);
}

/* Exponential accumulation over frames, history rejected by depth and normal. */
void tgi_hbil_stage_temporal(tg_frame *f, int index)
{
    const tgi_gbuffer *g = &f->gb;
    tgi_denoise_params p;
    tgi_denoise_io io;
    if (!f->temporal_state) return;
    tgi_denoise_defaults(&p);
    memset(&io, 0, sizeof io);
    io.width = f->width;
    io.height = f->height;
    io.depth = g->depth; io.nx = g->nx; io.ny = g->ny; io.nz = g->nz;
    io.sky = g->sky;
    io.ao = f->ao;
    io.bent_x = f->bent.r; io.bent_y = f->bent.g; io.bent_z = f->bent.b;
    io.cone = f->cone;
    io.near_r = f->near.r; io.near_g = f->near.g; io.near_b = f->near.b;
    tgi_temporal_rows(&p, &io, f->temporal_state, &f->prev_view, &f->view, index,
                     f->frames_rendered == 0, 0, f->height);
}

/* HBIL, interleaved (the default): every stage in order. */
static void hbil_interleaved(tg_frame *f, int index)
{
    tgi_hbil_stage_downsample(f);
    tgi_hbil_stage_split(f);
    tgi_hbil_stage_kernel(f);
    tgi_hbil_stage_merge(f);
    tgi_hbil_stage_filter(f);
    tgi_hbil_stage_upsample(f);
    tgi_hbil_stage_temporal(f, index);
}

static void hbil_full(tg_frame *f)
{
    const tgi_gbuffer *g = &f->gb;
    tgi_hbil_params p;
    tgi_hbil_io io;
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
    tgi_hbil_rows(&p, &io, 0, f->height);
}

static tgi_ao_io ao_io(tg_frame *f)
{
    tgi_ao_io io;
    const tgi_gbuffer *g = &f->gb;
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
    const tgi_material *m = &s->materials[s->tri_material[tri]];
    tg_vec3 e = tg_v3(0, 0, 0), lo;
    tg_real k;
    int l;
    if (f->effects & TG_EFFECT_DIRECT) {
        for (l = 0; l < s->light_count; l++) {
            tg_vec3 el = tgi_direct_irradiance(&s->lights[l], pos, nrm);
            if (f->shadow_ptrs && f->shadow_ptrs[l])
                el = tgi_v3_scale(el, tgi_shadow_visibility(f->shadow_ptrs[l], pos, nrm));
            e = tgi_v3_add(e, el);
        }
    }
    k = tg_mul(TG_INV_PI, tg_sub(TG_ONE, m->f0));   /* compose: albedo / pi * (1 - F0) */
    lo = tgi_v3_scale(tgi_v3_mul(m->albedo, e), k);
    return tgi_v3_add(lo, m->emissive);
}

static void reference(tg_frame *f)
{
    tgi_reference_params p;
    tgi_ao_io io = ao_io(f);
    const tg_vec3 *pos = f->posed_pos ? f->posed_pos : f->scene->tri_pos;
    tgi_reference_defaults(&p);
    tgi_bvh_build(&f->bvh, pos, f->scene->tri_count, f->technique_scratch, f->technique_scratch_bytes);
    p.bvh = &f->bvh;
    p.tri_nrm = f->posed_nrm ? f->posed_nrm : f->scene->tri_nrm;
    p.samples = f->plan.request.samples > 16 ? f->plan.request.samples : 256;
    p.radius = f->plan.request.radius;
    p.radiance = direct_radiance_at;
    p.user = f;
    tgi_reference_rows(&p, &io, 0, f->height);
}

int tgi_frame_technique(tg_frame *f, int index)
{
    int far_done = 0;
    switch (f->plan.request.technique) {
    case TG_TECH_HBIL:
        if (f->plan.request.interleave) {
            hbil_interleaved(f, index);
        } else {
            hbil_full(f);
            tgi_hbil_stage_filter(f);
            tgi_hbil_stage_temporal(f, index);
        }
        break;
    case TG_TECH_REFERENCE:
        reference(f);
        break;
    default:
        far_done = tgi_frame_technique_other(f, ao_io(f));
        break;
    }
    cone_from_ao(f);
    return far_done;
}

/* Where the reprojection's scratch lives: z-buffer, push/pull mips, valid mask. */
static void reproject_io(tg_frame *f, tgi_reproject_io *io, unsigned char **zbuf, unsigned char **mips)
{
    unsigned char *scratch = (unsigned char *)f->reproject_scratch;
    size_t zbytes = (tgi_reproject_bytes(f->width, f->height) + 15u) & ~(size_t)15u;
    size_t pbytes = (tgi_pushpull_bytes(f->width, f->height) + 15u) & ~(size_t)15u;
    memset(io, 0, sizeof *io);
    io->width = f->width;
    io->height = f->height;
    io->prev_view = &f->prev_view;
    io->view = &f->view;
    io->prev_depth = f->history_depth;
    io->prev_r = f->history.r; io->prev_g = f->history.g; io->prev_b = f->history.b;
    io->out_r = f->source.r; io->out_g = f->source.g; io->out_b = f->source.b;
    io->valid = scratch + zbytes + pbytes;
    *zbuf = scratch;
    *mips = scratch + zbytes;
}

/* HBIL sec. 3.2: scatter last frame's radiance into this view through a
 * temporary z-buffer (nearest wins)... */
void tgi_frame_reproject_scatter(tg_frame *f)
{
    tgi_reproject_io io;
    unsigned char *zbuf, *mips;
    reproject_io(f, &io, &zbuf, &mips);
    tgi_reproject_scatter(&io, zbuf);
}

/* ...then fill the holes by push/pull (Kraus 2009). */
void tgi_frame_reproject_fill(tg_frame *f)
{
    tgi_reproject_io io;
    unsigned char *zbuf, *mips;
    reproject_io(f, &io, &zbuf, &mips);
    tgi_pushpull_fill(f->width, f->height, f->source.r, f->source.g, f->source.b, io.valid, mips);
}

int tgi_frame_reproject(tg_frame *f)
{
    if (!f->history.r || !f->reproject_scratch) return 0;
    tgi_frame_reproject_scatter(f);
    tgi_frame_reproject_fill(f);
    return 1;
}
