/* SPDX-License-Identifier: MIT */
/*
 * pixels.h - one row of 8-bit sRGB in a display's pixel format, the step
 * tg_frame_write_pixels (pixels.c) takes for each row; tests feed it rows of
 * their own.
 */
#ifndef TG_PIXELS_H
#define TG_PIXELS_H

#include "../tinygi.h"
#include "../core/abi_names.h"

/* Bytes per pixel of a format, 0 if unknown. */
int tgi_pixel_bytes(tg_pixel_format format);

/* n pixels of RGB bytes, row y of the frame starting at its column 0 (the
 * dither pattern's place), to `format` at `dst`.  `dst` and `rgb` are
 * different buffers, or the same for RGB888. */
void tgi_pixels_row(const uint8_t *rgb, int n, int y, tg_pixel_format format, int flags, uint8_t *dst);

#endif
