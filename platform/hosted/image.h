/* SPDX-License-Identifier: MIT */
/*
 * image.h - PPM (P6), PFM (PF / Pf) and PNG images on the hosted platform:
 * writing (atomically, see file.h) and reading PPM/PFM (for tinygi diff and
 * the golden tests).
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
 *   PNG (written only): 8-bit RGB, not interlaced, filter type 0 (None) on
 *     every row, the zlib stream (RFC 1950) made of stored deflate blocks
 *     (RFC 1951 sec. 3.2.4), one per row in its own IDAT chunk, so rows
 *     stream out with no buffer; CRC-32 per chunk and Adler-32 at the end.
 *
 * LIMITS
 *   Each side 1..TG_MAX_IMAGE_SIDE and width * height <= TG_MAX_IMAGE_PIXELS
 *   (tinygi.h: the renderer's own limits, so diff reads any image tinygi
 *   writes); every size product is overflow-checked.
 */
#ifndef TG_HOSTED_IMAGE_H
#define TG_HOSTED_IMAGE_H

#include <stddef.h>
#include <stdint.h>
#include "file.h"

typedef enum tgp_img_format { TG_IMG_PPM, TG_IMG_PFM, TG_IMG_PNG } tgp_img_format;

typedef struct tgp_img {
    int width, height;
    int channels;          /* PPM: 3; PFM: 1 (Pf) or 3 (PF) */
    tgp_img_format format;
    int maxval;            /* PPM maxval (255 for 8-bit); 0 for PFM */
    float *pixels;         /* width*height*channels values, rows top to bottom;
                            * PPM samples as read (0..maxval), PFM linear */
} tgp_img;

/* The format a file name asks for by its extension (".ppm", ".pfm" or
 * ".png", any case): 0 and *format set, or 1 if it is none of them. */
int tgp_img_format_from_path(const char *path, tgp_img_format *format);

/* Check a size against the limits: 0 ok, else 1 with a reason in msg. */
int tgp_img_check_size(int width, int height, int channels, char *msg, size_t msgsize);

/* Headers, for streaming a file row by row through a tgp_outfile. */
void tgp_ppm_write_header(tgp_outfile *f, int width, int height);
void tgp_pfm_write_header(tgp_outfile *f, int width, int height, int channels);
/* One row of `count` floats, little-endian. */
void tgp_pfm_write_values(tgp_outfile *f, const float *values, size_t count);

/* PNG, streamed: the header, then `height` rows of width RGB triples (the
 * last row also ends the file). */
typedef struct tgp_png {
    int width, height, row;
    uint32_t adler;        /* Adler-32 of the scanlines so far (RFC 1950) */
} tgp_png;
void tgp_png_write_header(tgp_outfile *f, tgp_png *png, int width, int height);
void tgp_png_write_row(tgp_outfile *f, tgp_png *png, const uint8_t *rgb);
/* CRC-32 as PNG and zlib define it (ISO 3309), continued from crc (0 to start). */
uint32_t tgp_crc32(uint32_t crc, const void *data, size_t n);

/* Whole images.  rgb/values are rows top to bottom; the PFM writer stores
 * them bottom to top.  0 on success. */
int tgp_ppm_write(const char *path, int width, int height, const uint8_t *rgb,
                 char *msg, size_t msgsize);
int tgp_pfm_write(const char *path, int width, int height, int channels,
                 const float *values, char *msg, size_t msgsize);
int tgp_png_write(const char *path, int width, int height, const uint8_t *rgb,
                 char *msg, size_t msgsize);

/* Read a PPM (P6) or PFM (PF/Pf) by its magic number, not its name.  On
 * success img->pixels is malloc'd (free with tgp_img_free). */
int tgp_img_read(const char *path, tgp_img *img, char *msg, size_t msgsize);
int tgp_img_decode(const unsigned char *data, size_t size, tgp_img *img,
                  char *msg, size_t msgsize);
void tgp_img_free(tgp_img *img);

#endif
