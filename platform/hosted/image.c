/* SPDX-License-Identifier: MIT */
/*
 * image.c - PPM (P6) and PFM (PF/Pf) writing and reading, and PNG writing,
 * for the hosted platform.  Byte order is handled here, where bytes are
 * written and read: PFM floats go out little-endian and PNG integers
 * big-endian whatever the host is.
 */
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image.h"


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
    if (strcmp(e, "png") == 0) { *format = TG_IMG_PNG; return 0; }
    return 1;
}

int tgp_img_check_size(int width, int height, int channels, char *msg, size_t msgsize)
{
    size_t pixels, values, bytes;
    if (width < 1 || height < 1 || width > TG_MAX_IMAGE_SIDE || height > TG_MAX_IMAGE_SIDE) {
        tgp_say(msg, msgsize, "image size %dx%d: each side must be 1..%d", width, height,
            TG_MAX_IMAGE_SIDE);
        return 1;
    }
    if (channels != 1 && channels != 3) {
        tgp_say(msg, msgsize, "image with %d channels: expected 1 or 3", channels);
        return 1;
    }
    if (tg_size_mul((size_t)width, (size_t)height, &pixels) ||
        pixels > (size_t)TG_MAX_IMAGE_PIXELS || tg_size_mul(pixels, (size_t)channels, &values) ||
        tg_size_mul(values, sizeof(float), &bytes)) {
        tgp_say(msg, msgsize, "image size %dx%d: pixels must be 1..%ld", width, height,
            (long)TG_MAX_IMAGE_PIXELS);
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

/* ---- PNG ---- */

/* A stored deflate block holds at most 65535 bytes: a scanline (filter
 * byte + 3 bytes per pixel) must fit one. */
typedef char png_row_fits_a_stored_block[1 + 3 * TG_MAX_IMAGE_SIDE <= 65535 ? 1 : -1];

uint32_t tgp_crc32(uint32_t crc, const void *data, size_t n)
{
    static uint32_t table[256];
    const unsigned char *p = (const unsigned char *)data;
    size_t i;
    if (!table[1]) {
        uint32_t k, v;
        int b;
        for (k = 0; k < 256; k++) {
            for (v = k, b = 0; b < 8; b++) v = (v & 1u) ? 0xEDB88320u ^ (v >> 1) : v >> 1;
            table[k] = v;
        }
    }
    crc = ~crc;
    for (i = 0; i < n; i++) crc = table[(crc ^ p[i]) & 255u] ^ (crc >> 8);
    return ~crc;
}

/* RFC 1950 sec. 8.2: s1 = 1 + sum of bytes, s2 = sum of the s1s, both mod 65521 */
static uint32_t adler32(uint32_t adler, const unsigned char *p, size_t n)
{
    uint32_t a = adler & 0xffffu, b = adler >> 16;
    while (n > 0) {
        size_t run = n < 5552 ? n : 5552; /* the most bytes before b can overflow */
        n -= run;
        while (run--) {
            a += *p++;
            b += a;
        }
        a %= 65521u;
        b %= 65521u;
    }
    return b << 16 | a;
}

static void put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* One chunk: length, type, the pieces of its data, CRC over type and data. */
static void png_chunk(tgp_outfile *f, const char *type, const unsigned char *const *piece,
                      const size_t *len, int pieces)
{
    unsigned char be[4];
    uint32_t crc = tgp_crc32(0, type, 4), total = 0;
    int i;
    for (i = 0; i < pieces; i++) total += (uint32_t)len[i];
    put_be32(be, total);
    tgp_outfile_write(f, be, 4);
    tgp_outfile_write(f, type, 4);
    for (i = 0; i < pieces; i++) {
        tgp_outfile_write(f, piece[i], len[i]);
        crc = tgp_crc32(crc, piece[i], len[i]);
    }
    put_be32(be, crc);
    tgp_outfile_write(f, be, 4);
}

void tgp_png_write_header(tgp_outfile *f, tgp_png *png, int width, int height)
{
    static const unsigned char signature[8] = { 137, 'P', 'N', 'G', '\r', '\n', 26, '\n' };
    unsigned char ihdr[13];
    const unsigned char *piece[1];
    size_t len[1];
    png->width = width;
    png->height = height;
    png->row = 0;
    png->adler = 1;
    put_be32(ihdr, (uint32_t)width);
    put_be32(ihdr + 4, (uint32_t)height);
    ihdr[8] = 8;   /* bits per sample */
    ihdr[9] = 2;   /* colour type: RGB */
    ihdr[10] = ihdr[11] = ihdr[12] = 0; /* deflate, adaptive filtering, no interlace */
    tgp_outfile_write(f, signature, sizeof signature);
    piece[0] = ihdr;
    len[0] = sizeof ihdr;
    png_chunk(f, "IHDR", piece, len, 1);
}

void tgp_png_write_row(tgp_outfile *f, tgp_png *png, const uint8_t *rgb)
{
    static const unsigned char zlib_header[2] = { 0x78, 0x01 }; /* deflate, 32K window, check bits */
    static const unsigned char filter_none = 0;
    unsigned char block[5], adler[4];
    const unsigned char *piece[5];
    size_t len[5], n = 1 + (size_t)png->width * 3u;
    int k = 0, last = png->row == png->height - 1;
    if (png->row >= png->height) return;
    if (png->row == 0) piece[k] = zlib_header, len[k++] = 2;
    block[0] = (unsigned char)last; /* BFINAL, BTYPE 00: stored */
    block[1] = (unsigned char)(n & 0xffu);
    block[2] = (unsigned char)(n >> 8);
    block[3] = (unsigned char)(~n & 0xffu); /* NLEN: one's complement of LEN */
    block[4] = (unsigned char)((~n >> 8) & 0xffu);
    piece[k] = block, len[k++] = 5;
    piece[k] = &filter_none, len[k++] = 1;
    piece[k] = rgb, len[k++] = n - 1;
    png->adler = adler32(png->adler, &filter_none, 1);
    png->adler = adler32(png->adler, rgb, n - 1);
    if (last) {
        put_be32(adler, png->adler);
        piece[k] = adler, len[k++] = 4;
    }
    png_chunk(f, "IDAT", piece, len, k);
    if (last) png_chunk(f, "IEND", piece, len, 0);
    png->row++;
}

int tgp_png_write(const char *path, int width, int height, const uint8_t *rgb,
                 char *msg, size_t msgsize)
{
    tgp_outfile *f;
    tgp_png png;
    int y;
    if (tgp_img_check_size(width, height, 3, msg, msgsize)) return 1;
    f = tgp_outfile_create(path, msg, msgsize);
    if (!f) return 1;
    tgp_png_write_header(f, &png, width, height);
    for (y = 0; y < height; y++) tgp_png_write_row(f, &png, rgb + (size_t)y * (size_t)width * 3u);
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
    long lw = read_uint(r, TG_MAX_IMAGE_SIDE), lh;
    if (lw < 0) {
        tgp_say(msg, msgsize, lw == -2 ? "width must be 1..%d" : "bad width (expected a number)",
            TG_MAX_IMAGE_SIDE);
        return 1;
    }
    lh = read_uint(r, TG_MAX_IMAGE_SIDE);
    if (lh < 0) {
        tgp_say(msg, msgsize, lh == -2 ? "height must be 1..%d" : "bad height (expected a number)",
            TG_MAX_IMAGE_SIDE);
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
        tgp_say(msg, msgsize, "out of memory for a %dx%d image", img->width, img->height);
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
        tgp_say(msg, msgsize, "bad PPM maxval (expected 1..65535)");
        return 1;
    }
    if (end_header(r)) {
        tgp_say(msg, msgsize, "PPM header ends without the pixel data");
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
        tgp_say(msg, msgsize, "PPM data truncated: %lu of %lu bytes",
            (unsigned long)(r->end - r->p), (unsigned long)need);
        return 1;
    }
    if (alloc_pixels(img, msg, msgsize)) return 1;
    for (i = 0; i < count; i++) {
        unsigned v = bytes_per == 2 ? ((unsigned)r->p[2 * i] << 8) | r->p[2 * i + 1] : r->p[i];
        if (v > (unsigned)maxval) {
            tgp_say(msg, msgsize, "PPM sample %u exceeds maxval %ld", v, maxval);
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
        tgp_say(msg, msgsize, "bad PFM scale (expected a non-zero number, negative for little-endian)");
        return 1;
    }
    if (end_header(r)) {
        tgp_say(msg, msgsize, "PFM header ends without the pixel data");
        return 1;
    }
    little = scale < 0.0f;
    img->format = TG_IMG_PFM;
    img->maxval = 0;
    if (tgp_img_check_size(img->width, img->height, img->channels, msg, msgsize)) return 1;
    row = (size_t)img->width * (size_t)img->channels;
    need = row * (size_t)img->height * 4u;
    if ((size_t)(r->end - r->p) < need) {
        tgp_say(msg, msgsize, "PFM data truncated: %lu of %lu bytes",
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
    tgp_say(msg, msgsize, "not a PPM (P6) or PFM (PF/Pf) image");
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
