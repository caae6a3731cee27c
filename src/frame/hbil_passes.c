/* SPDX-License-Identifier: MIT */
/*
 * hbil_passes.c - HBIL's passes in a frame (Mayaux 2018).
 *
 * Interleaved (the default): the kernel's image (the full-resolution view,
 * or with --gi-quarter its point-sampled half-resolution copy) and its
 * near-field source radiance are split into 4x4 = 16 sub-images (HBIL sec.
 * 3.3), the horizon kernel runs on each sub-image with that sub-image's
 * slice angles, the results are merged back, filtered over the 4x4
 * neighbourhood (sec. 3.4), brought up to full resolution (quarter) and,
 * across frames, accumulated.  With interleave off the kernel runs on the
 * full-resolution view with the same 32 directions per 4x4 block.  Over
 * further depth layers the kernel is the visibility bitmask on the
 * kernel's image (full resolution, or the half-resolution copy with its
 * layers) with the interleaved angles (tgi_pass_hbil_layers).
 */
#include "frame_internal.h"
#include "../gi/hbil.h"
#include "../gi/interleave.h"
#include "../gi/resample.h"
#include "../ao/ssilvb.h"

static void hbil_params(const tg_frame *f, tgi_hbil_params *p)
{
    tgi_hbil_defaults(p);
    p->slices = f->request.slices;
    p->samples = f->request.samples;
    p->radius = f->request.radius;
    /* with temporal accumulation each frame since the history began takes
     * its own eighth of the directions and march offsets (a first frame is
     * the same whatever its index); without it, every frame the first's */
    p->rotation = (f->needs & TG_NEED_TEMPORAL) ? f->frames_rendered % TG_HBIL_ROTATIONS : 0;
}

/* Results without the cone: the kernel and the filter leave it to the
 * cone pass (HBIL eq. 12 from the final AO). */
static tgi_gresult without_cone(const tgi_gresult *r)
{
    tgi_gresult c = *r;
    c.cone = NULL;
    return c;
}

#if !TG_NO_GI_QUARTER /* left out with TG_NO_GI_QUARTER=1 (tinygi.h "FEATURE SWITCHES") */
void tgi_pass_downsample(tg_frame *f, int y0, int y1)
{
    tgi_downsample_rows(&f->full, &f->half, tgi_frame_source(f), &f->half_source, y0, y1);
}
#endif

/* The kernel on each of the 16 sub-images (i, j) of the kernel's image
 * (HBIL sec. 3.3), each a strided view of the image (no copy): its pixel
 * (x, y) is the image's (4x + i, 4y + j); its results and source radiance
 * are read and written in place, indexed alike.  Each pixel takes the
 * slice angles of its cell of the 4x4 pattern (gi/hbil.h,
 * tgi_hbil_pattern) and the kernel marches in sub-image pixels.  Rows
 * [y0, y1) of the image: row Y is row Y / 4 of the sub-images (i, Y & 3),
 * so any split of the rows writes disjoint pixels. */
void tgi_pass_hbil_interleaved(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params p;
    const tgi_gresult *res;
    const tgi_rgb *source;
    const tgi_gview *k = tgi_frame_kernel(f, &res, &source);
    int i, j;
#if !TG_OUTLINE_HELPERS   /* not compiling for size: the 16 sub-images' calls share one table */
    tgi_hbil_dirs dirs;
#endif
    hbil_params(f, &p);
    p.pattern_scale = k->step;
#if !TG_OUTLINE_HELPERS
    tgi_hbil_dirs_init(&dirs, &p);
    p.dirs = &dirs;
#endif
#if !TG_NO_FINE_HORIZON
    p.fine = &f->full;          /* the horizons are refined on the full-resolution pixels (gi/hbil.c) */
    p.fine_radiance = tgi_frame_source(f);
#endif
    for (j = 0; j < 4; j++)
        for (i = 0; i < 4; i++) {
            tgi_gview sub;
            tgi_gresult out;
            tgi_rgb src;
            size_t o;
            tgi_gview_strided_sub(&sub, k, i, j);
            if (sub.width == 0 || sub.height == 0) continue;
            o = tgi_gv_index(k, i, j);
            out = without_cone(res);
            out = tgi_gresult_from(&out, o);
            src = tgi_rgb_from(source, o);
            tgi_hbil_rows(&p, &sub, &src, &out, (y0 - j + 3) / 4, (y1 - j + 3) / 4);
        }
}

#if TGI_DEPTH_LAYERS /* left out with TG_NO_TECHNIQUES=1 (the bitmask's file with it) */
/* HBIL over the G-buffer's further depth layers (request.depth_layers 2, 3):
 * the horizon of each slice side becomes the visibility bitmask of
 * Therrien et al. 2023 (ao/ssilvb.h), which takes a sample as solid from
 * its front to its back face and open behind it, where a horizon takes
 * everything under it as solid.  It runs on the kernel's image (the
 * full-resolution view, or with --gi-quarter the half-resolution copy,
 * whose layers are point-sampled down with its depth), each pixel (x, y)
 * of it with the slice angles and march offsets of the cell (x & 3, y & 3)
 * of the 4x4 pattern (HBIL sec. 3.3, tgi_hbil_slice_phi0,
 * tgi_hbil_step_jitter; it marches in the image's own pixels, so the
 * horizon kernel's shift by column, tgi_hbil_pattern, is not needed) for this frame's
 * rotation, so the 4x4 filter (at quarter resolution, then the upsample)
 * and the temporal accumulation that follow see the same 16 x slices
 * directions a block, turned every frame, as with the horizon kernel.
 * Writes AO, bent normal and near field at the kernel's resolution. */
void tgi_pass_hbil_layers(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params h;
    tgi_ssilvb_params p;
    tgi_ao_rot pattern[16];
    const tgi_gresult *kres;
    const tgi_rgb *source;
    const tgi_gview *g = tgi_frame_kernel(f, &kres, &source);
    tgi_gresult res = without_cone(kres);
    int k;
    hbil_params(f, &h);
    for (k = 0; k < 16; k++) {
        tg_real phi = tgi_hbil_slice_phi0(k & 3, k >> 2, h.slices, h.rotation);
        pattern[k].c = tg_cos(phi);
        pattern[k].s = tg_sin(phi);
        pattern[k].jitter = tgi_hbil_step_jitter(k & 3, k >> 2, h.rotation);
    }
    tgi_ssilvb_defaults(&p);
    p.slices = tgi_ao_count(h.slices);
    p.steps = tgi_ao_count(h.samples);
    p.radius = h.radius;
    p.thickness = f->request.thickness;
    p.pattern = pattern;
    p.to_edge = 1;
    tgi_ssilvb_rows(&p, g, source, &res, y0, y1);
}
#endif

void tgi_pass_hbil_full(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params p;
    tgi_gresult res = without_cone(&f->res);
    hbil_params(f, &p);
    tgi_hbil_rows(&p, &f->full, tgi_frame_source(f), &res, y0, y1);
}
