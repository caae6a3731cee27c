/* SPDX-License-Identifier: MIT */
/*
 * imgdiff.h - compare two images (PPM or PFM, see image.h): the numbers
 * behind `tinygi diff` and the golden-image tests (both use this code).
 *
 * DEFINITIONS (over every channel value of every pixel)
 *   difference  |a - b| per channel value, in the images' own units:
 *               0..maxval (0..255) for PPM, linear values for PFM.  A
 *               non-finite value (NaN, +-inf) differs by infinity from
 *               anything, itself included: a renderer's output must be
 *               finite, so NaN against NaN is a difference, never a match.
 *   rmse        sqrt(mean of difference^2).
 *   psnr        20 log10(peak / rmse) in dB, peak = maxval (PPM) or 1.0
 *               (PFM: linear white); +inf when the images are equal.
 *   max_abs     the largest difference, at pixel (max_x, max_y), channel
 *               max_channel (0 r, 1 g, 2 b); the first such in row order.
 *   tolerance   the largest difference still accepted: images are "within
 *               tolerance" when max_abs <= tolerance (never with a
 *               non-finite value).  pixels_over counts pixels with some
 *               channel difference > tolerance.
 *   nan, inf    per image (0 = a, 1 = b): how many channel values are NaN
 *               and how many infinite, and the first pixel with one
 *               (first_x/first_y, -1 when there is none), in row order.
 * Images compare only when they have the same format, size, channel count
 * and (PPM) maxval.
 */
#ifndef TG_HOSTED_IMGDIFF_H
#define TG_HOSTED_IMGDIFF_H

#include <stddef.h>
#include <stdint.h>
#include "image.h"

typedef struct tgp_diff {
    double rmse, psnr, peak;
    double max_abs;
    int max_x, max_y, max_channel;
    double max_finite;        /* largest finite difference (scales the diff image) */
    double tolerance;
    size_t pixels, pixels_over;
    size_t nan[2], inf[2];    /* non-finite channel values in a ([0]) and b ([1]) */
    int first_x[2], first_y[2];
} tgp_diff;

/* 0 and *d filled, or 1 if the images cannot be compared (reason in msg). */
int tgp_diff_compare(const tgp_img *a, const tgp_img *b, double tolerance, tgp_diff *d,
                    char *msg, size_t msgsize);
/* 1 when max_abs <= tolerance. */
int tgp_diff_within(const tgp_diff *d);
/* A visual difference image, width*height RGB bytes (malloc'd; NULL when out
 * of memory): each channel's difference scaled so that max_finite is 255
 * (non-finite differences are 255); one-channel images are grey. */
uint8_t *tgp_diff_image(const tgp_img *a, const tgp_img *b, const tgp_diff *d);
/* One line: "rmse R, psnr P dB, max M at X,Y (channel C), N of T pixels
 * over tolerance TOL", then ", NaN/inf in a|b: ..." when there are any.
 * Returns the length snprintf would give. */
int tgp_diff_describe(const tgp_diff *d, char *buf, size_t size);

#endif
