/* SPDX-License-Identifier: MIT */
/*
 * image.h - PPM (P6) and PFM (PF / Pf) images on the hosted platform:
 * writing (atomically, see file.h) and reading (for tinygi diff and the
 * golden tests).
 *
 * FORMATS
 *   PPM P6: header "P6\nW H\n255\n", then W*H RGB byte triples, rows top to
 *     bottom.  Reading also accepts comments, any whitespace and maxval
 *     1..65535 (16-bit samples are big-endian, as Netpbm says).
 *   PFM: header "PF\nW H\n-1.0\n" (RGB) or "Pf\nW H\n-1.0\n" (one channel),
 *     then 32-bit IEEE floats; a negative scale means little-endian, which is
 *     what we write.  Rows are stored BOTTOM TO TOP (the format's rule); in
 *     memory a tgp_img is always top to bottom.  Reading accepts either byte
 *     order (positive scale: big-endian).
 *
 * LIMITS
 *   Each side 1..TG_IMG_MAX_SIDE, and width * height <= TG_IMG_MAX_PIXELS;
 *   every size product is overflow-checked.
 */
#ifndef TG_HOSTED_IMAGE_H
#define TG_HOSTED_IMAGE_H

#include <stddef.h>
#include <stdint.h>
#include "file.h"

#define TG_IMG_MAX_SIDE 16384
#define TG_IMG_MAX_PIXELS ((size_t)1 << 26) /* 67,108,864: e.g. 8192 x 8192 */

typedef enum tgp_img_format { TG_IMG_PPM, TG_IMG_PFM } tgp_img_format;

typedef struct tgp_img {
    int width, height;
    int channels;          /* PPM: 3; PFM: 1 (Pf) or 3 (PF) */
    tgp_img_format format;
    int maxval;            /* PPM maxval (255 for 8-bit); 0 for PFM */
    float *pixels;         /* width*height*channels values, rows top to bottom;
                            * PPM samples as read (0..maxval), PFM linear */
} tgp_img;

/* The format a file name asks for by its extension (".ppm" / ".pfm", any
 * case): 0 and *format set, or 1 if it is neither. */
int tgp_img_format_from_path(const char *path, tgp_img_format *format);

/* Check a size against the limits: 0 ok, else 1 with a reason in msg. */
int tgp_img_check_size(int width, int height, int channels, char *msg, size_t msgsize);

/* Headers, for streaming a file row by row through a tgp_outfile. */
void tgp_ppm_write_header(tgp_outfile *f, int width, int height);
void tgp_pfm_write_header(tgp_outfile *f, int width, int height, int channels);
/* One row of `count` floats, little-endian. */
void tgp_pfm_write_values(tgp_outfile *f, const float *values, size_t count);

/* Whole images.  rgb/values are rows top to bottom; the PFM writer stores
 * them bottom to top.  0 on success. */
int tgp_ppm_write(const char *path, int width, int height, const uint8_t *rgb,
                 char *msg, size_t msgsize);
int tgp_pfm_write(const char *path, int width, int height, int channels,
                 const float *values, char *msg, size_t msgsize);

/* Read a PPM (P6) or PFM (PF/Pf) by its magic number, not its name.  On
 * success img->pixels is malloc'd (free with tgp_img_free). */
int tgp_img_read(const char *path, tgp_img *img, char *msg, size_t msgsize);
int tgp_img_decode(const unsigned char *data, size_t size, tgp_img *img,
                  char *msg, size_t msgsize);
void tgp_img_free(tgp_img *img);

#endif
