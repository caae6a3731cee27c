/* SPDX-License-Identifier: MIT */
/*
 * imgdiff.c - image comparison for `tinygi diff` and the golden tests:
 * RMSE, PSNR, the largest difference and where it is, and a visual
 * difference image.  Definitions in imgdiff.h.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "file.h"
#include "imgdiff.h"


static const char *format_name(const tgp_img *img)
{
    if (img->format == TG_IMG_PPM) return "PPM";
    return img->channels == 1 ? "PFM (Pf)" : "PFM (PF)";
}

static int compatible(const tgp_img *a, const tgp_img *b, char *msg, size_t msgsize)
{
    if (a->format != b->format || a->channels != b->channels) {
        tgp_say(msg, msgsize, "cannot compare a %s image with a %s image", format_name(a),
            format_name(b));
        return 0;
    }
    if (a->width != b->width || a->height != b->height) {
        tgp_say(msg, msgsize, "image sizes differ: %dx%d and %dx%d", a->width, a->height,
            b->width, b->height);
        return 0;
    }
    if (a->format == TG_IMG_PPM && a->maxval != b->maxval) {
        tgp_say(msg, msgsize, "PPM maxvals differ: %d and %d", a->maxval, b->maxval);
        return 0;
    }
    return 1;
}

/* |a - b|; infinite when either is not finite (NaN against NaN included). */
static double value_difference(float a, float b)
{
    double d;
    if (!isfinite(a) || !isfinite(b)) return HUGE_VAL;
    d = (double)a - (double)b;
    return d < 0.0 ? -d : d;
}

/* Count a's NaN and infinite values into image k's tallies. */
static void count_nonfinite(tgp_diff *d, int k, float v, size_t pixel, int width)
{
    if (isfinite(v)) return;
    if (isnan(v)) d->nan[k]++;
    else d->inf[k]++;
    if (d->first_x[k] < 0) {
        d->first_x[k] = (int)(pixel % (size_t)width);
        d->first_y[k] = (int)(pixel / (size_t)width);
    }
}

int tgp_diff_compare(const tgp_img *a, const tgp_img *b, double tolerance, tgp_diff *d,
                    char *msg, size_t msgsize)
{
    size_t count, i, c, n = (size_t)a->channels;
    double sum = 0.0;
    memset(d, 0, sizeof *d);
    if (!compatible(a, b, msg, msgsize)) return 1;
    d->tolerance = tolerance;
    d->peak = a->format == TG_IMG_PPM ? (double)a->maxval : 1.0;
    d->pixels = (size_t)a->width * (size_t)a->height;
    d->first_x[0] = d->first_x[1] = d->first_y[0] = d->first_y[1] = -1;
    count = d->pixels;
    for (i = 0; i < count; i++) {
        int over = 0;
        for (c = 0; c < n; c++) {
            double diff = value_difference(a->pixels[i * n + c], b->pixels[i * n + c]);
            count_nonfinite(d, 0, a->pixels[i * n + c], i, a->width);
            count_nonfinite(d, 1, b->pixels[i * n + c], i, a->width);
            sum += diff * diff;
            if (diff > d->max_abs) {
                d->max_abs = diff;
                d->max_x = (int)(i % (size_t)a->width);
                d->max_y = (int)(i / (size_t)a->width);
                d->max_channel = (int)c;
            }
            if (isfinite(diff) && diff > d->max_finite) d->max_finite = diff;
            if (diff > tolerance) over = 1;
        }
        d->pixels_over += (size_t)over;
    }
    d->rmse = sqrt(sum / (double)(count * n));
    d->psnr = d->rmse > 0.0 ? 20.0 * log10(d->peak / d->rmse) : HUGE_VAL;
    return 0;
}

int tgp_diff_within(const tgp_diff *d)
{
    return d->max_abs <= d->tolerance && !d->nan[0] && !d->nan[1] && !d->inf[0] && !d->inf[1];
}

uint8_t *tgp_diff_image(const tgp_img *a, const tgp_img *b, const tgp_diff *d)
{
    size_t count = (size_t)a->width * (size_t)a->height, i, c, n = (size_t)a->channels;
    uint8_t *rgb = (uint8_t *)malloc(count * 3u);
    double scale = d->max_finite > 0.0 ? 255.0 / d->max_finite : 0.0;
    if (!rgb) return NULL;
    for (i = 0; i < count; i++) {
        for (c = 0; c < 3; c++) {
            size_t k = i * n + (n == 1 ? 0 : c);
            double diff = value_difference(a->pixels[k], b->pixels[k]);
            double v = isfinite(diff) ? diff * scale + 0.5 : 255.0;
            rgb[i * 3 + c] = (uint8_t)(v > 255.0 ? 255.0 : v);
        }
    }
    return rgb;
}

int tgp_diff_describe(const tgp_diff *d, char *buf, size_t size)
{
    static const char channel_name[3] = { 'r', 'g', 'b' };
    int n = snprintf(buf, size, "rmse %.6g, psnr %.2f dB, max %.6g at %d,%d (channel %c), "
                     "%lu of %lu pixels over tolerance %.6g",
                     d->rmse, d->psnr, d->max_abs, d->max_x, d->max_y,
                     channel_name[d->max_channel < 0 || d->max_channel > 2 ? 0 : d->max_channel],
                     (unsigned long)d->pixels_over, (unsigned long)d->pixels, d->tolerance);
    int k;
    for (k = 0; k < 2 && n >= 0; k++) {
        size_t at = (size_t)n < size ? (size_t)n : size;
        int m;
        if (!d->nan[k] && !d->inf[k]) continue;
        m = snprintf(buf + at, size - at, ", %s has %lu NaN and %lu inf values (first at %d,%d)",
                     k ? "b" : "a", (unsigned long)d->nan[k], (unsigned long)d->inf[k],
                     d->first_x[k], d->first_y[k]);
        n = m < 0 ? m : n + m;
    }
    return n;
}
