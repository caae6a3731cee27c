/* SPDX-License-Identifier: MIT */
/*
 * reproject.h - last frame's diffuse radiance in this frame's view (HBIL
 * sec. 3.2), the source of the near field (eq. 17: infinite bounces over
 * frames).
 *
 * A gather through the depth and the two cameras: each pixel of this frame
 * is unprojected with its depth, moved by its object's motion when objects
 * move, and projected into last frame's view; it takes last frame's
 * radiance at the pixel it lands in, unless last frame's depth there
 * disagrees with this surface seen from the previous camera (relative
 * tolerance, the paper's z-test) or it lands off screen or behind the
 * camera: then it is a hole (tgi_rgb_set_hole), for tgi_pushpull_fill.  The
 * paper scatters through a temporary z-buffer; gathering needs no scratch
 * and no ordering, so rows are independent (any split gives the same
 * image).  Sky pixels are holes too (the near field never gathers them).
 * Without history (prev absent: a camera cut) every pixel is a hole, and
 * push/pull makes the image 0.
 */
#ifndef TG_REPROJECT_H
#define TG_REPROJECT_H

#include "../raster/gview.h"

typedef struct tgi_reproject_io {
    const tgi_gview *g;                  /* this frame (full resolution, packed); its camera */
    const tgi_view *prev_view;
    const tgi_prev_geometry *prev_geometry; /* last frame's depth, packed like g */
    const tgi_rgb *prev;                 /* last frame's radiance, packed like g; absent: no history */
    const uint16_t *object;              /* this frame's object ids when objects move, else NULL */
    const tgi_mat4 *object_delta;        /* per object: current pose -> previous pose */
    tg_real depth_tolerance;             /* relative depth mismatch rejected (0: 0.05) */
    const tgi_rgb *out;                  /* this frame's radiance: a value or a hole */
} tgi_reproject_io;

void tgi_reproject_gather_rows(const tgi_reproject_io *io, int y0, int y1);

#endif
