/* SPDX-License-Identifier: MIT */
/*
 * hbil.h - the Horizon-Based Indirect Lighting kernel (Mayaux 2018).
 *
 * One function serves the 4x4-interleaved quarter-resolution sub-images and
 * the full-resolution, non-interleaved image: it processes a G-buffer view
 * (raster/gview.h) whose pixel (x, y) is full-resolution pixel
 * (x * step + offset_x, y * step + offset_y), packed or strided, and it
 * marches in ITS OWN pixels (HBIL sec. 3.3: "the march steps in sub-image
 * pixels").
 *
 * Per pixel and per slice (HBIL sec. 1-2):
 *   local camera frame from the view vector (sec. 1.1), slice direction
 *   D(phi) (sec. 1.2), a march of `samples` steps along +D and -D within the
 *   projected radius, horizon cosines measured from the LOCAL view axis
 *   (sec. 1.3), horizons initialised from the normal (sec. 2.1),
 *   cosine-weighted AO (eq. 10-11), bent normal (eq. 4-6), cone aperture
 *   (eq. 12) and near-field irradiance gathered where the horizon rises
 *   (eq. 18), as irradiance: the receiver's 1 - F0 of eq. 19 is applied
 *   once, with the albedo, where Lo is composed (eq. 14), with the
 *   sender-normal rejection filter and running lerp of sec. 3.4.
 *
 * Slice angles: with S slices per pixel the slices of a pixel are
 * phi0 + s * pi / S.  Each of the 16 cells (i, j) of the 4x4 pattern gets
 * its own phi0 (tgi_hbil_slice_phi0), stratified over [0, pi / S), so a
 * 4x4 block covers 16 * S directions (32 with the default S = 2, pi / 32
 * apart).  Pixel (X, Y) of the image takes the cell tgi_hbil_pattern(X, Y):
 * (X & 3, (Y + t) & 3), t hashed from its block column X >> 2 and the
 * frame's rotation.  The kernel runs on the full-resolution image or on
 * its 16 sub-images (sub-image (i, j)'s pixel (x, y) is (4x + i, 4y + j)),
 * and both give a pixel the same cell, so the two results are comparable.  Not one cell
 * per sub-image (HBIL sec. 3.3 as printed): then every pixel of a
 * sub-image marches one slice direction at the same offsets, and where
 * the sub-image's step is one of its pixels (a 40x30 sub-image, 32
 * samples) their near fields err alike along the slice, diagonal bands
 * fixed to the screen that the temporal accumulation drags into streaks
 * when the camera moves; shifted by t, neighbours along a sub-image's row
 * march different slices.
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
 *  - E_near = (pi / S) sum over rises of L * dE (eq. 16-18).  With
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

#include "../tinygi.h"
#include "../raster/gview.h"

struct tgi_hbil_dirs;

typedef struct tgi_hbil_params {
    int slices, samples;      /* per pixel; defaults TG_DEFAULT_SLICES, TG_DEFAULT_SAMPLES; slices clamped to [1, TG_MAX_SLICES] */
    tg_real radius;           /* world units; projected to pixels, the march stops at the screen's edge */
    int pattern_scale;        /* each pixel's slice angles and march offset are its cell's
                               * (tgi_hbil_pattern) at its place in the kernel's image, read
                               * from the view (a sub-image's pixel (x, y) stands for the
                               * image's (4x + i, 4y + j)); the kernel's image's pixels are
                               * this many full-resolution pixels wide (2: --gi-quarter; 0 or
                               * 1: full resolution) */
    int rotation;             /* the frame rotation (tgi_hbil_slice_phi0, tgi_hbil_pattern) */
    tg_real rejection_a, rejection_b; /* sec. 3.4 t = smoothstep(a, b, -n'.w_i) */
    const tgi_gview *fine; /* interleaved: the image the 4x4 sub-image is taken from (its
                               * pixel (x, y) is fine's (4x + i, 4y + j)); the horizon on
                               * each side is refined there (hbil.c, refine_fine); NULL: none */
    const tgi_rgb *fine_radiance; /* the radiance indexed like fine; NULL: the refinement's
                               * bands take the radiance gathered before them */
    const struct tgi_hbil_dirs *dirs; /* tgi_hbil_dirs_init's table for these slices and
                               * rotation, shared by the calls of a pass; NULL (the
                               * default): each call computes its own */
} tgi_hbil_params;

/* The 4x4 pattern's per-cell constants for a count of slices and a
 * rotation: each cell's slice directions (cos, sin of tgi_hbil_slice_phi0
 * + s pi / slices) and march offset (tgi_hbil_step_jitter).  They cost
 * 16 x slices cosines and sines, which a call of tgi_hbil_rows computes
 * when params.dirs is NULL: a pass that makes many calls with one
 * slices and rotation (16 sub-images a row range, ranges a frame) computes
 * the table once and points params.dirs at it (same values, same bits). */
#define TGI_HBIL_PATTERN 16     /* the 4x4 pattern's cells (tgi_hbil_pattern) */
typedef struct tgi_hbil_dirs {
    tg_real cos_phi[TGI_HBIL_PATTERN][TG_MAX_SLICES], sin_phi[TGI_HBIL_PATTERN][TG_MAX_SLICES];
    tg_real jitter[TGI_HBIL_PATTERN];
} tgi_hbil_dirs;
/* The table for p's slices (clamped to [1, TG_MAX_SLICES] as the kernel
 * clamps them) and rotation */
void tgi_hbil_dirs_init(tgi_hbil_dirs *d, const tgi_hbil_params *p);

/* Defaults: 2 slices, 32 samples, radius 1, rotation 0, the
 * full-resolution pattern, rejection a = 0, b = 0.2. */
void tgi_hbil_defaults(tgi_hbil_params *p);

/* First slice angle of sub-image (i, j), i, j in 0..3, with `slices` per
 * pixel, in frame rotation `rot` (0..TG_HBIL_ROTATIONS - 1, the frame's
 * index modulo TG_HBIL_ROTATIONS): the 16 sub-images x S slices stratify
 * [0, pi) and each rotation takes its own eighth of every stratum, so the
 * frames of a still view gather from 8 x 32 directions. */
tg_real tgi_hbil_slice_phi0(int i, int j, int slices, int rot);

/* The march's start jitter of sub-image (i, j), a fraction of a step in
 * [0, 1): the 16 sub-images of a 4x4 block start their samples at the 16
 * offsets (k + 1/2) / 16 of a step, in an order unlike the slice angles',
 * so the 4x4 filter averages both (HBAO's per-pixel jitter, Bavoil 2008,
 * interleaved as HBIL sec. 3.3 interleaves the directions).  Without it
 * every pixel of a surface meets an occluder at a multiple of the step and
 * the near field shows bands the step's length apart.  Each frame
 * rotation `rot` takes its own eighth of every offset stratum. */
tg_real tgi_hbil_step_jitter(int i, int j, int rot);

/* The march's start offset of the pixel of 4x4 block (bx, by) whose
 * sub-image starts at `sub_image_jitter` (tgi_hbil_step_jitter): that
 * offset moved by a whole number of sixteenths, modulo 1: one hashed from
 * the block, plus 2 k for rotation `rot`, k = 0..7 in bit-reversed order.
 * A block's 16 pixels still take the 16 offset strata, but neighbouring
 * blocks take them in different sub-images: with one offset per
 * sub-image, the samples of every block in a row fall at the same
 * distances, and on a wall seen face-on rows of blocks see the same points
 * of a bright patch (stripes 4 pixels high that neither the 4x4 filter nor
 * the temporal accumulation removes; cornell at 160x120 over 60 frames,
 * colour RMSE against the path tracer 0.093 -> 0.083).  Over the 8
 * rotations each pixel's offset takes 8 strata 2 sixteenths apart, every
 * block alike, where a hash of the rotation too drew a block's 8 at random
 * (some twice): its error then differed from block to block and stayed
 * over the frames, a mosaic of 4x4 blocks in the near field (cornell
 * 320x240, the mean second difference of neighbouring blocks' near field
 * over their mean: 0.083 -> 0.076 over 16 frames, 0.081 -> 0.075 over 64;
 * 0.178 in one frame, the same bits as before). */
tg_real tgi_hbil_block_jitter(tg_real sub_image_jitter, int bx, int by, int rot);

/* The cell i + 4 j of the 4x4 pattern (tgi_hbil_slice_phi0,
 * tgi_hbil_step_jitter) pixel (x, y) of an image takes in rotation rot:
 * i = x & 3, j = (y + t) & 3, t in 0..3 hashed from x >> 2 and rot
 * (integers only: the same on every target).  Every aligned 4x4 block
 * and every 4 consecutive rows of a column x hold all 16, or all 4 cells
 * of column x & 3, so the 5x5 filter (gi/denoise.h) weighs the 16 alike. */
int tgi_hbil_pattern(int x, int y, int rot);


/* Run the kernel on rows [y0, y1) of the view `g` (its camera is the
 * full-resolution one).  radiance: last frame's diffuse radiance reprojected,
 * indexed like g; NULL or absent = no near field.  out: AO always, the
 * bent normal, cone and near-field irradiance when present (the near field
 * only with radiance). */
void tgi_hbil_rows(const tgi_hbil_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                   const tgi_gresult *out, int y0, int y1);

/* The interleaved kernel (HBIL sec. 3.3): rows [y0, y1) of the image `k`
 * (a view standing for the full-resolution image, or for its quarter-res
 * copy) whose 16 sub-images (gi/interleave.h) are packed in `split`, with
 * the radiance and results packed alike; each sub-image (i, j) gets its own
 * first slice angle.  Row Y of k is row Y / 4 of the sub-images (i, Y & 3). */
void tgi_hbil_interleaved_rows(const tgi_hbil_params *p, const tgi_gview *k, const tgi_gbuffer *split,
                               const tgi_rgb *radiance, const tgi_gresult *out, int y0, int y1);

/* Q(theta) = (theta - sin(theta) cos(theta)) / 2 from c = cos(theta), c in
 * [-1, 1] (clamped), theta = acos(c) in [0, pi]: the horizon's slice
 * integral (eq. 10-11) as the kernel evaluates it (one square root and a
 * polynomial; error in tests/test_hbil.c). */
tg_real tgi_hbil_slice_q(tg_real c);
/* Its square root, sqrt(x) for x in [0, 1]: Q16.16 gives tg_sqrt's value
 * (exactly rounded) without the call; float a two-step rsqrt times x and a
 * Newton step (tests/test_hbil.c hbil_unit_sqrt_exact). */
tg_real tgi_hbil_unit_sqrt(tg_real x);

#if !TG_WIDE_STORAGE && !TG_NO_COLOR
/* The near field's weight t = smoothstep(a, b, -n_s.w_i) (HBIL sec. 3.4) of
 * a sender whose normal is the octahedral direction n (raster/pack.h), seen
 * along the view-space unit vector dir from camera v, as the kernel
 * computes it (`tests` 1: with its tests that skip the normalisation where
 * t is 0 or 1; 0: always through the unit normal). */
tg_real tgi_hbil_rejection_weight(const tgi_view *v, tg_real a, tg_real b, tgi_oct_dir n, tg_vec3 dir, int tests);
#endif

#endif
