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
 * are read and written in place, indexed alike.  Each sub-image gets its
 * own first slice angle and the kernel marches in sub-image pixels.  Rows
 * [y0, y1) of the image: row Y is row Y / 4 of the sub-images (i, Y & 3),
 * so any split of the rows writes disjoint pixels. */
void tgi_pass_hbil_interleaved(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params p;
    const tgi_gresult *res;
    const tgi_rgb *source;
    const tgi_gview *k = tgi_frame_kernel(f, &res, &source);
    int i, j;
    hbil_params(f, &p);
#if !TG_NO_FINE_HORIZON
    p.fine = &f->full;          /* the horizons are refined on the full-resolution pixels (gi/hbil.c) */
    p.fine_radiance = tgi_frame_source(f);
#endif
    for (j = 0; j < 4; j++)
        for (i = 0; i < 4; i++) {
            tgi_hbil_params ps = p;
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
            tgi_hbil_for_sub_image(&ps, i, j);
            tgi_hbil_rows(&ps, &sub, &src, &out, (y0 - j + 3) / 4, (y1 - j + 3) / 4);
        }
}

void tgi_pass_hbil_full(tg_frame *f, int y0, int y1)
{
    tgi_hbil_params p;
    tgi_gresult res = without_cone(&f->res);
    hbil_params(f, &p);
    p.per_pixel_pattern = 1;
    tgi_hbil_rows(&p, &f->full, tgi_frame_source(f), &res, y0, y1);
}
