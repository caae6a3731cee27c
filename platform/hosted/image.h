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
 *     memory a tg_img is always top to bottom.  Reading accepts either byte
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

typedef enum tg_img_format { TG_IMG_PPM, TG_IMG_PFM } tg_img_format;

typedef struct tg_img {
    int width, height;
    int channels;          /* PPM: 3; PFM: 1 (Pf) or 3 (PF) */
    tg_img_format format;
    int maxval;            /* PPM maxval (255 for 8-bit); 0 for PFM */
    float *pixels;         /* width*height*channels values, rows top to bottom;
                            * PPM samples as read (0..maxval), PFM linear */
} tg_img;

/* The format a file name asks for by its extension (".ppm" / ".pfm", any
 * case): 0 and *format set, or 1 if it is neither. */
int tg_img_format_from_path(const char *path, tg_img_format *format);

/* Check a size against the limits: 0 ok, else 1 with a reason in msg. */
int tg_img_check_size(int width, int height, int channels, char *msg, size_t msgsize);

/* Headers, for streaming a file row by row through a tg_outfile. */
void tg_ppm_write_header(tg_outfile *f, int width, int height);
void tg_pfm_write_header(tg_outfile *f, int width, int height, int channels);
/* One row of `count` floats, little-endian. */
void tg_pfm_write_values(tg_outfile *f, const float *values, size_t count);

/* Whole images.  rgb/values are rows top to bottom; the PFM writer stores
 * them bottom to top.  0 on success. */
int tg_ppm_write(const char *path, int width, int height, const uint8_t *rgb,
                 char *msg, size_t msgsize);
int tg_pfm_write(const char *path, int width, int height, int channels,
                 const float *values, char *msg, size_t msgsize);

/* Read a PPM (P6) or PFM (PF/Pf) by its magic number, not its name.  On
 * success img->pixels is malloc'd (free with tg_img_free). */
int tg_img_read(const char *path, tg_img *img, char *msg, size_t msgsize);
int tg_img_decode(const unsigned char *data, size_t size, tg_img *img,
                  char *msg, size_t msgsize);
void tg_img_free(tg_img *img);

#endif
