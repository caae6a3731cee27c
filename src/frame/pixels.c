/* SPDX-License-Identifier: MIT */
/*
 * pixels.c - a frame's rows in the pixel format a display wants, written
 * straight into the caller's buffer (tg_frame_write_pixels; the formats and
 * their bytes are defined in tinygi.h).  Built on tg_frame_aov_row8: every
 * format is a function of the 8-bit sRGB bytes, so both number types give
 * the same bytes; of the frame it reads nothing but its size.
 *
 * 5- and 6-bit channels: the level nearest below c * top / 255 + t, with the
 * threshold t = 1/2 (rounding to nearest) or, dithered, t = (M + 0.5) / 16
 * for M the index of the 4x4 Bayer matrix (Bayer 1973) at the pixel's frame
 * coordinates.  Over the 16 thresholds of a 4x4 block the levels average to
 * c * top / 255 rounded to 1/16.  With c * top an integer this is
 * floor((c * top + floor(255 t)) / 255), and x / 255 for x < 65535 is
 * (x + 1 + (x >> 8)) >> 8: no division per pixel, a 16-byte table.
 *
 * Grey is the luma Y' of Rec. 709 on the sRGB-encoded bytes (as Rec. 709
 * and sRGB define luma), not luminance from linear values: the grey byte is
 * shown sRGB-encoded anyway, a grey AOV (ao, depth, cone) keeps its exact
 * byte, and it needs no decoding table.  The weights in 2^-20 with the bias
 * below give exactly round(0.2126 R + 0.7152 G + 0.0722 B) with halves up
 * for all 2^24 inputs (tests/test_pixels.c checks every one).
 */
#include <string.h>
#include "frame_internal.h"
#include "pixels.h"

/* Bayer's 4x4 ordered-dither index matrix, row by row. */
static const uint8_t bayer_index[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};

#define LUMA_R 222927u
#define LUMA_G 749942u
#define LUMA_B 75707u   /* LUMA_R + LUMA_G + LUMA_B = 2^20 */
#define LUMA_BIAS 524390u /* 2^19 + 102: halves round up */

int tgi_pixel_bytes(tg_pixel_format format)
{
    switch (format) {
    case TG_PIXEL_RGB565: case TG_PIXEL_BGR565: case TG_PIXEL_RGB565_BE: return 2;
    case TG_PIXEL_RGB888: case TG_PIXEL_BGR888: return 3;
    case TG_PIXEL_XRGB8888: case TG_PIXEL_RGBA8888: return 4;
    case TG_PIXEL_GREY8: return 1;
    default: return 0;
    }
}

static int little_endian(void)
{
    const uint16_t one = 1;
    return *(const uint8_t *)&one == 1;
}

/* floor(x / 255) for 0 <= x < 65535. */
static unsigned div255(unsigned x)
{
    return (x + 1u + (x >> 8)) >> 8;
}

static void row_565(const uint8_t *rgb, int n, int y, tg_pixel_format format, int dither, uint8_t *dst)
{
    unsigned t[4]; /* floor(255 t) of the row's thresholds, by column mod 4 */
    int x, hi = format != TG_PIXEL_RGB565_BE && little_endian(); /* where the high byte goes */
    int top = format == TG_PIXEL_BGR565 ? 2 : 0;                   /* the channel in bits 15-11 */
    for (x = 0; x < 4; x++) t[x] = dither ? ((2u * bayer_index[(y & 3) * 4 + x] + 1u) * 255u) >> 5 : 127u;
    for (x = 0; x < n; x++, rgb += 3, dst += 2) {
        unsigned high = div255(rgb[top] * 31u + t[x & 3]), g = div255(rgb[1] * 63u + t[x & 3]);
        unsigned low = div255(rgb[2 - top] * 31u + t[x & 3]);
        unsigned v = high << 11 | g << 5 | low;
        dst[hi] = (uint8_t)(v >> 8);
        dst[hi ^ 1] = (uint8_t)v;
    }
}

/* Each pixel's red, green and blue bytes to at[0..2] and, with 4 bytes, 255 to at[3]. */
static void row_bytes(const uint8_t *rgb, int n, int bytes, const uint8_t *at, uint8_t *dst)
{
    int x;
    for (x = 0; x < n; x++, rgb += 3, dst += bytes) {
        dst[at[0]] = rgb[0];
        dst[at[1]] = rgb[1];
        dst[at[2]] = rgb[2];
        if (bytes == 4) dst[at[3]] = 255;
    }
}

static void row_grey(const uint8_t *rgb, int n, uint8_t *dst)
{
    int x;
    for (x = 0; x < n; x++, rgb += 3)
        dst[x] = (uint8_t)((LUMA_R * rgb[0] + LUMA_G * rgb[1] + LUMA_B * rgb[2] + LUMA_BIAS) >> 20);
}

void tgi_pixels_row(const uint8_t *rgb, int n, int y, tg_pixel_format format, int flags, uint8_t *dst)
{
    static const uint8_t bgr[3] = {2, 1, 0}, rgba[4] = {0, 1, 2, 3};
    static const uint8_t xrgb_le[4] = {2, 1, 0, 3}, xrgb_be[4] = {1, 2, 3, 0}; /* 0xXXRRGGBB stored */
    switch (format) {
    case TG_PIXEL_RGB565: case TG_PIXEL_BGR565: case TG_PIXEL_RGB565_BE:
        row_565(rgb, n, y, format, flags & TG_PIXELS_DITHER, dst);
        break;
    case TG_PIXEL_RGB888: if (dst != rgb) memcpy(dst, rgb, 3 * (size_t)n); break;
    case TG_PIXEL_BGR888: row_bytes(rgb, n, 3, bgr, dst); break;
    case TG_PIXEL_XRGB8888: row_bytes(rgb, n, 4, little_endian() ? xrgb_le : xrgb_be, dst); break;
    case TG_PIXEL_RGBA8888: row_bytes(rgb, n, 4, rgba, dst); break;
    case TG_PIXEL_GREY8: row_grey(rgb, n, dst); break;
    default: break;
    }
}

/* Rows [y0, y1) through a scratch row of 3 * width bytes on the stack. */
static void write_converted(const tg_frame *f, tg_aov aov, int y0, int y1, tg_pixel_format format,
                            int flags, uint8_t *dst, size_t stride)
{
    uint8_t rgb[3 * (size_t)f->width];
    int y;
    for (y = y0; y < y1; y++, dst += stride) {
        (void)tg_frame_aov_row8(f, aov, y, rgb);
        tgi_pixels_row(rgb, f->width, y, format, flags, dst);
    }
}

tg_status tg_frame_write_pixels(const tg_frame *f, tg_aov aov, int y0, int y1,
                                tg_pixel_format format, int flags, void *dst, size_t stride)
{
    int bytes = tgi_pixel_bytes(format), y;
    uint8_t *out = (uint8_t *)dst;
    if (!f || !dst || (unsigned)aov >= TG_AOV_COUNT || bytes == 0 || (flags & ~TG_PIXELS_DITHER) != 0 ||
        y0 < 0 || y0 > y1 || y1 > f->height || stride / (size_t)bytes < (size_t)f->width)
        return TG_ERR_INPUT;
    if (format != TG_PIXEL_RGB888) {
        if (y0 < y1) write_converted(f, aov, y0, y1, format, flags, out, stride);
        return TG_OK;
    }
    for (y = y0; y < y1; y++, out += stride) (void)tg_frame_aov_row8(f, aov, y, out); /* already RGB888 */
    return TG_OK;
}
