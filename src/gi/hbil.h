/* SPDX-License-Identifier: MIT */
/*
 * hbil.h - the Horizon-Based Indirect Lighting kernel (Mayaux 2018).
 *
 * One function serves the 4x4-interleaved quarter-resolution sub-images and
 * the full-resolution, non-interleaved image: it processes an image of
 * (width, height) pixels whose pixel (x, y) is full-resolution pixel
 * (x * step + offset_x, y * step + offset_y), and it marches in ITS OWN
 * pixels (HBIL sec. 3.3: "the march steps in sub-image pixels").
 *
 * Per pixel and per slice (HBIL sec. 1-2):
 *   local camera frame from the view vector (sec. 1.1), slice direction
 *   D(phi) (sec. 1.2), a march of `samples` steps along +D and -D within the
 *   projected radius, horizon cosines measured from the LOCAL view axis
 *   (sec. 1.3), horizons initialised from the normal (sec. 2.1),
 *   cosine-weighted AO (eq. 10-11), bent normal (eq. 4-6), cone aperture
 *   (eq. 12) and near-field irradiance gathered where the horizon rises
 *   (eq. 18) weighted by 1 - F0 (eq. 19) with the sender-normal rejection
 *   filter and running lerp of sec. 3.4.
 *
 * Slice angles: with S slices per pixel the slices of a pixel are
 * phi0 + s * pi / S.  Each of the 16 sub-images (i, j) gets its own phi0
 * (tgi_hbil_slice_phi0), stratified over [0, pi / S), so a 4x4 block covers
 * 16 * S directions (32 with the default S = 2, pi / 32 apart).  For the
 * full-resolution image set per_pixel_pattern: full-res pixel (X, Y) then
 * uses tgi_hbil_slice_phi0(X & 3, Y & 3, S), the same directions the
 * interleaved path gives that pixel, so the two results are comparable.
 *
 * Estimators (documented deviations, both consistent with the paper's
 * integrals and exact for unoccluded surfaces):
 *  - AO = 1 - (1/S) sum_i (AO_i(open horizons) - AO_i(found horizons)).
 *    The paper's (1/S) sum_i AO_i converges to the same value but with two
 *    slices per pixel swings between ~0.8 and ~1.1 on an open plane seen at
 *    grazing angles (the per-slice weight |n'|(cos g + g sin g) is not
 *    constant in phi); subtracting the exact open value (a control variate,
 *    whose integral over phi is exactly 1) removes that noise.
 *  - bent = normalize(S n + sum_i (B_i - B_i(open))), B_i from eq. 5-6; the
 *    open integral of eq. 3 is exactly pi n (S n in slice-sum units).
 *  - eq. 6 and eq. 11 as printed integrate n_x sin(theta) without the
 *    |sin(theta)| of eq. 10 on the back side; we integrate eq. 10 exactly
 *    (this matches GTAO, RTR eq. 11.18), which gives ~n_x = 0 for
 *    symmetric horizons as it must.
 *  - E_near = (pi / S) (1 - F0) sum over rises of L * dE (eq. 16-19).  With
 *    uniform radiance L in every occluded direction, AO + E_near / (pi L)
 *    = 1 exactly (fig. 15: the near field is the complement of the far).
 *
 * Sampling: the march steps along the major screen axis in whole pixels
 * and interpolates depth linearly across the minor axis, so a sample lies
 * on the slice plane (a snapped sample off the slice would make an open
 * plane occlude itself).  Samples farther than `radius` (3D, world units)
 * from the pixel, sky samples and samples outside the image are ignored.
 */
#ifndef TG_HBIL_H
#define TG_HBIL_H

#include "../raster/view.h"

#define TG_HBIL_MAX_SLICES 8
#define TG_HBIL_DEFAULT_SLICES 2
#define TG_HBIL_DEFAULT_SAMPLES 16

typedef struct tgi_hbil_params {
    const tgi_view *view;      /* full-resolution camera */
    int slices, samples;      /* per pixel; defaults 2 and 16; slices clamped to [1, TG_HBIL_MAX_SLICES] */
    tg_real radius;           /* world units; projected to pixels, clamped to max_radius_px and the screen */
    tg_real max_radius_px;    /* in full-res pixels */
    int step, offset_x, offset_y;   /* image pixel (x, y) -> full-res pixel (x*step+ox, y*step+oy) */
    tg_real slice_phi0;       /* first slice angle of this image (interleaved), radians */
    int per_pixel_pattern;    /* full-res: slice angle from (X & 3, Y & 3), slice_phi0 ignored */
    tg_real rejection_a, rejection_b; /* sec. 3.4 t = smoothstep(a, b, -n'.w_i) */
} tgi_hbil_params;

typedef struct tgi_hbil_io {
    int width, height;
    const tg_real *depth, *nx, *ny, *nz;      /* view depth; world normals */
    const tg_real *f0;                         /* may be NULL: 0 */
    const uint8_t *sky;                        /* may be NULL: no sky */
    const tg_real *rad_r, *rad_g, *rad_b;      /* last frame's diffuse radiance reprojected; NULL = no near field */
    const tg_real *snx, *sny, *snz;            /* sender normals for the rejection filter; may alias nx..; NULL = nx.. */
    tg_real *ao, *bent_x, *bent_y, *bent_z, *cone; /* outputs; bent world space unit; any may be NULL except ao */
    tg_real *near_r, *near_g, *near_b;         /* near-field irradiance; written only with rad_r and near_r */
} tgi_hbil_io;

/* Defaults: 2 slices, 16 samples, radius 1, max radius 128 px, step 1, no
 * offset, phi0 of sub-image (0,0), no pattern, rejection a = 0, b = 0.2. */
void tgi_hbil_defaults(tgi_hbil_params *p, const tgi_view *view);

/* First slice angle of sub-image (i, j), i, j in 0..3, with `slices` per pixel. */
tg_real tgi_hbil_slice_phi0(int i, int j, int slices);

/* Run the kernel on image rows [y0, y1). */
void tgi_hbil_rows(const tgi_hbil_params *p, const tgi_hbil_io *io, int y0, int y1);

#endif
