/* SPDX-License-Identifier: MIT */
/*
 * image.c - PPM (P6) and PFM (PF/Pf) writing and reading for the hosted
 * platform.  Byte order is handled here, where bytes are written and read:
 * PFM floats go out little-endian whatever the host is.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"

static void say(char *msg, size_t msgsize, const char *fmt, ...)
{
    va_list ap;
    if (!msg || msgsize == 0) return;
    va_start(ap, fmt);
    vsnprintf(msg, msgsize, fmt, ap);
    va_end(ap);
}

int tgp_img_format_from_path(const char *path, tgp_img_format *format)
{
    size_t n = strlen(path);
    const char *ext;
    char e[4];
    int i;
    if (n < 4) return 1;
    ext = path + n - 4;
    if (ext[0] != '.') return 1;
    for (i = 0; i < 3; i++) e[i] = (char)tolower((unsigned char)ext[i + 1]);
    e[3] = '\0';
    if (strcmp(e, "ppm") == 0) { *format = TG_IMG_PPM; return 0; }
    if (strcmp(e, "pfm") == 0) { *format = TG_IMG_PFM; return 0; }
    return 1;
}

int tgp_img_check_size(int width, int height, int channels, char *msg, size_t msgsize)
{
    size_t pixels, values, bytes;
    if (width < 1 || height < 1 || width > TG_IMG_MAX_SIDE || height > TG_IMG_MAX_SIDE) {
        say(msg, msgsize, "image size %dx%d: each side must be in 1..%d", width, height,
            TG_IMG_MAX_SIDE);
        return 1;
    }
    if (channels != 1 && channels != 3) {
        say(msg, msgsize, "image with %d channels: expected 1 or 3", channels);
        return 1;
    }
    if (tg_size_mul((size_t)width, (size_t)height, &pixels) || pixels > TG_IMG_MAX_PIXELS ||
        tg_size_mul(pixels, (size_t)channels, &values) ||
        tg_size_mul(values, sizeof(float), &bytes)) {
        say(msg, msgsize, "image size %dx%d: more than %lu pixels", width, height,
            (unsigned long)TG_IMG_MAX_PIXELS);
        return 1;
    }
    return 0;
}

/* ---- writing ---- */

void tgp_ppm_write_header(tgp_outfile *f, int width, int height)
{
    char head[64];
    int n = snprintf(head, sizeof head, "P6\n%d %d\n255\n", width, height);
    tgp_outfile_write(f, head, (size_t)n);
}

void tgp_pfm_write_header(tgp_outfile *f, int width, int height, int channels)
{
    char head[64];
    int n = snprintf(head, sizeof head, "%s\n%d %d\n-1.0\n", channels == 1 ? "Pf" : "PF",
                     width, height);
    tgp_outfile_write(f, head, (size_t)n);
}

void tgp_pfm_write_values(tgp_outfile *f, const float *values, size_t count)
{
    unsigned char le[1024];
    size_t i, k = 0;
    for (i = 0; i < count; i++) {
        uint32_t bits;
        memcpy(&bits, &values[i], 4);
        le[k++] = (unsigned char)(bits & 0xffu);
        le[k++] = (unsigned char)((bits >> 8) & 0xffu);
        le[k++] = (unsigned char)((bits >> 16) & 0xffu);
        le[k++] = (unsigned char)(bits >> 24);
        if (k == sizeof le) {
            tgp_outfile_write(f, le, k);
            k = 0;
        }
    }
    if (k) tgp_outfile_write(f, le, k);
}

int tgp_ppm_write(const char *path, int width, int height, const uint8_t *rgb,
                 char *msg, size_t msgsize)
{
    tgp_outfile *f;
    if (tgp_img_check_size(width, height, 3, msg, msgsize)) return 1;
    f = tgp_outfile_create(path, msg, msgsize);
    if (!f) return 1;
    tgp_ppm_write_header(f, width, height);
    tgp_outfile_write(f, rgb, (size_t)width * (size_t)height * 3u);
    return tgp_outfile_finish(f, msg, msgsize);
}

int tgp_pfm_write(const char *path, int width, int height, int channels,
                 const float *values, char *msg, size_t msgsize)
{
    tgp_outfile *f;
    size_t row = (size_t)width * (size_t)channels;
    int y;
    if (tgp_img_check_size(width, height, channels, msg, msgsize)) return 1;
    f = tgp_outfile_create(path, msg, msgsize);
    if (!f) return 1;
    tgp_pfm_write_header(f, width, height, channels);
    for (y = height - 1; y >= 0; y--) /* PFM rows go bottom to top */
        tgp_pfm_write_values(f, values + (size_t)y * row, row);
    return tgp_outfile_finish(f, msg, msgsize);
}

/* ---- reading ---- */

typedef struct reader {
    const unsigned char *p, *end;
} reader;

static int is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/* Skip whitespace and '#' comments (to end of line). */
static void skip_blank(reader *r)
{
    while (r->p < r->end) {
        if (is_space(*r->p)) r->p++;
        else if (*r->p == '#') {
            while (r->p < r->end && *r->p != '\n') r->p++;
        } else break;
    }
}

/* A decimal integer in 0..limit; returns -1 if missing or malformed, -2 if
 * larger than limit. */
static long read_uint(reader *r, long limit)
{
    long v = 0;
    int digits = 0, big = 0;
    skip_blank(r);
    while (r->p < r->end && *r->p >= '0' && *r->p <= '9') {
        if (v > limit) big = 1;
        else v = v * 10 + (*r->p - '0');
        r->p++;
        digits++;
    }
    if (!digits || (r->p < r->end && !is_space(*r->p) && *r->p != '#')) return -1;
    if (big || v > limit) return -2;
    return v;
}

/* The PFM scale: a decimal number token. */
static int read_scale(reader *r, float *scale)
{
    char tok[64];
    size_t n = 0;
    char *endp;
    skip_blank(r);
    while (r->p < r->end && !is_space(*r->p) && n < sizeof tok - 1) tok[n++] = (char)*r->p++;
    tok[n] = '\0';
    if (n == 0 || (r->p < r->end && !is_space(*r->p))) return 1;
    *scale = strtof(tok, &endp);
    return *endp != '\0' || !(*scale == *scale) || *scale == 0.0f;
}

static int read_dims(reader *r, int *w, int *h, char *msg, size_t msgsize)
{
    long lw = read_uint(r, TG_IMG_MAX_SIDE), lh;
    if (lw < 0) {
        say(msg, msgsize, lw == -2 ? "width larger than %d" : "bad width (expected a number)",
            TG_IMG_MAX_SIDE);
        return 1;
    }
    lh = read_uint(r, TG_IMG_MAX_SIDE);
    if (lh < 0) {
        say(msg, msgsize, lh == -2 ? "height larger than %d" : "bad height (expected a number)",
            TG_IMG_MAX_SIDE);
        return 1;
    }
    *w = (int)lw;
    *h = (int)lh;
    return 0;
}

/* After the last header field comes exactly one whitespace byte. */
static int end_header(reader *r)
{
    if (r->p >= r->end || !is_space(*r->p)) return 1;
    r->p++;
    return 0;
}

static int alloc_pixels(tgp_img *img, char *msg, size_t msgsize)
{
    size_t count = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
    if (tgp_img_check_size(img->width, img->height, img->channels, msg, msgsize)) return 1;
    img->pixels = (float *)malloc(count * sizeof(float));
    if (!img->pixels) {
        say(msg, msgsize, "out of memory for a %dx%d image", img->width, img->height);
        return 1;
    }
    return 0;
}

static int decode_ppm(reader *r, tgp_img *img, char *msg, size_t msgsize)
{
    long maxval;
    size_t count, bytes_per, need, i;
    if (read_dims(r, &img->width, &img->height, msg, msgsize)) return 1;
    maxval = read_uint(r, 65535);
    if (maxval < 1) {
        say(msg, msgsize, "bad PPM maxval (expected 1..65535)");
        return 1;
    }
    if (end_header(r)) {
        say(msg, msgsize, "PPM header ends without the pixel data");
        return 1;
    }
    img->channels = 3;
    img->format = TG_IMG_PPM;
    img->maxval = (int)maxval;
    if (tgp_img_check_size(img->width, img->height, 3, msg, msgsize)) return 1;
    count = (size_t)img->width * (size_t)img->height * 3u;
    bytes_per = maxval > 255 ? 2u : 1u;
    need = count * bytes_per;
    if ((size_t)(r->end - r->p) < need) {
        say(msg, msgsize, "PPM data truncated: %lu of %lu bytes",
            (unsigned long)(r->end - r->p), (unsigned long)need);
        return 1;
    }
    if (alloc_pixels(img, msg, msgsize)) return 1;
    for (i = 0; i < count; i++) {
        unsigned v = bytes_per == 2 ? ((unsigned)r->p[2 * i] << 8) | r->p[2 * i + 1] : r->p[i];
        if (v > (unsigned)maxval) {
            say(msg, msgsize, "PPM sample %u exceeds maxval %ld", v, maxval);
            free(img->pixels);
            img->pixels = NULL;
            return 1;
        }
        img->pixels[i] = (float)v;
    }
    return 0;
}

static int decode_pfm(reader *r, tgp_img *img, char *msg, size_t msgsize)
{
    float scale;
    size_t row, need, i;
    int y, little;
    if (read_dims(r, &img->width, &img->height, msg, msgsize)) return 1;
    if (read_scale(r, &scale)) {
        say(msg, msgsize, "bad PFM scale (expected a non-zero number, negative for little-endian)");
        return 1;
    }
    if (end_header(r)) {
        say(msg, msgsize, "PFM header ends without the pixel data");
        return 1;
    }
    little = scale < 0.0f;
    img->format = TG_IMG_PFM;
    img->maxval = 0;
    if (tgp_img_check_size(img->width, img->height, img->channels, msg, msgsize)) return 1;
    row = (size_t)img->width * (size_t)img->channels;
    need = row * (size_t)img->height * 4u;
    if ((size_t)(r->end - r->p) < need) {
        say(msg, msgsize, "PFM data truncated: %lu of %lu bytes",
            (unsigned long)(r->end - r->p), (unsigned long)need);
        return 1;
    }
    if (alloc_pixels(img, msg, msgsize)) return 1;
    for (y = img->height - 1; y >= 0; y--) { /* file rows go bottom to top */
        float *out = img->pixels + (size_t)y * row;
        for (i = 0; i < row; i++, r->p += 4) {
            uint32_t bits = little
                ? (uint32_t)r->p[0] | (uint32_t)r->p[1] << 8 | (uint32_t)r->p[2] << 16 | (uint32_t)r->p[3] << 24
                : (uint32_t)r->p[3] | (uint32_t)r->p[2] << 8 | (uint32_t)r->p[1] << 16 | (uint32_t)r->p[0] << 24;
            memcpy(&out[i], &bits, 4);
        }
    }
    return 0;
}

int tgp_img_decode(const unsigned char *data, size_t size, tgp_img *img, char *msg, size_t msgsize)
{
    reader r;
    memset(img, 0, sizeof *img);
    r.p = data;
    r.end = data + size;
    if (size >= 2 && data[0] == 'P' && data[1] == '6') {
        r.p += 2;
        return decode_ppm(&r, img, msg, msgsize);
    }
    if (size >= 2 && data[0] == 'P' && (data[1] == 'F' || data[1] == 'f')) {
        img->channels = data[1] == 'F' ? 3 : 1;
        r.p += 2;
        return decode_pfm(&r, img, msg, msgsize);
    }
    say(msg, msgsize, "not a PPM (P6) or PFM (PF/Pf) image");
    return 1;
}

int tgp_img_read(const char *path, tgp_img *img, char *msg, size_t msgsize)
{
    char *data;
    size_t size;
    int r;
    memset(img, 0, sizeof *img);
    if (tgp_file_read(path, &data, &size, msg, msgsize)) return 1;
    r = tgp_img_decode((const unsigned char *)data, size, img, msg, msgsize);
    free(data);
    return r;
}

void tgp_img_free(tgp_img *img)
{
    free(img->pixels);
    img->pixels = NULL;
}
