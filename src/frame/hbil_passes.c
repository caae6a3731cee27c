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
 * full-resolution view with the same 32 directions per 4x4 block.
 */
#include "frame_internal.h"
#include "../gi/hbil.h"
#include "../gi/interleave.h"
#include "../gi/resample.h"

static void hbil_params(const tg_frame *f, tgi_hbil_params *p)
{
    tgi_hbil_defaults(p);
    p->slices = f->request.slices;
    p->samples = f->request.samples;
    p->radius = f->request.radius;
}

/* Results without the cone: the kernel and the filter leave it to the
 * cone pass (HBIL eq. 12 from the final AO). */
static tgi_gresult without_cone(const tgi_gresult *r)
{
    tgi_gresult c = *r;
    c.cone = NULL;
    return c;
}

void tgi_pass_downsample(tg_frame *f, int y0, int y1)
{
    tgi_downsample_rows(&f->full, &f->half, tgi_frame_source(f), &f->half_source, y0, y1);
}

/* Kernel-image rows [y0, y1) into the 16 packed sub-images. */
void tgi_pass_split(tg_frame *f, int y0, int y1)
{
    const tgi_rgb *source;
    const tgi_gview *k = tgi_frame_kernel(f, NULL, &source);
    int with_source = tgi_rgb_present(&f->split_source), x, y;
    size_t start[4];
    for (y = y0; y < y1; y++) {
        tgi_interleave_row(k->width, k->height, y, start);
        for (x = 0; x < k->width; x++) {
            size_t i = tgi_gv_index(k, x, y), s = start[x & 3] + (size_t)(x >> 2);
            tgi_gview_copy_pixel(&f->split, s, k, i);
            if (with_source) tgi_rgb_set(&f->split_source, s, tgi_rgb_get(source, i));
        }
    }
}

/* The kernel on each of the 16 sub-images, with its own slice angles,
 * marching in sub-image pixels (HBIL sec. 3.3). */
void tgi_pass_hbil_interleaved(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params p;
    hbil_params(f, &p);
    tgi_hbil_interleaved_rows(&p, tgi_frame_kernel(f, NULL, NULL), &f->split, &f->split_source, &f->split_res, y0, y1);
}

void tgi_pass_hbil_full(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params p;
    tgi_gresult res = without_cone(&f->res);
    hbil_params(f, &p);
    p.per_pixel_pattern = 1;
    tgi_hbil_rows(&p, &f->full, tgi_frame_source(f), &res, y0, y1);
}

/* Kernel-image rows [y0, y1) back from the 16 sub-images. */
void tgi_pass_merge(tg_frame *f, int y0, int y1)
{
    const tgi_gresult *res;
    const tgi_gview *k = tgi_frame_kernel(f, &res, NULL);
    int x, y;
    size_t start[4];
    for (y = y0; y < y1; y++) {
        tgi_interleave_row(k->width, k->height, y, start);
        for (x = 0; x < k->width; x++)
            tgi_gresult_copy_pixel(res, tgi_gv_index(k, x, y), &f->split_res,
                                   start[x & 3] + (size_t)(x >> 2));
    }
}
