/* SPDX-License-Identifier: MIT */
/*
 * test_image.c - the hosted platform's image files and diff: PPM and PFM
 * bytes on disk (headers, byte order, PFM's bottom-to-top rows), round
 * trips, refusal of malformed files, PNG's chunks, CRC-32, Adler-32 and
 * stored blocks (tests/png_test.sh decodes whole files with Python's zlib),
 * and the diff numbers against hand-computed values, non-finite values
 * included.  Files and atomic writes: test_file.c.
 */
#include <stdint.h>
#include <stdlib.h>
#include "check.h"
#include "tmpdir.h"
#include "hosted/file.h"
#include "hosted/image.h"
#include "hosted/imgdiff.h"
#include "hosted/clock.h"

static int read_raw(const char *path, unsigned char **data, size_t *n)
{
    char *d;
    if (tgp_file_read(path, &d, n, NULL, 0)) return 1;
    *data = (unsigned char *)d;
    return 0;
}

/* The bytes of the file at path (malloc'd), checked to be want_n of them
 * starting with header. */
static unsigned char *read_with_header(const char *path, size_t want_n, const char *header)
{
    unsigned char *data;
    size_t n;
    CHECK(read_raw(path, &data, &n) == 0, "read back");
    CHECK(n == want_n, "size %zu", n);
    CHECK(memcmp(data, header, strlen(header)) == 0, "header");
    return data;
}

TEST(ppm_bytes_on_disk)
{
    const uint8_t rgb[2 * 3 * 2] = { 1, 2, 3, 4, 5, 6, 250, 251, 252, 0, 128, 255 };
    const char *path = tmp_path("a.ppm");
    unsigned char *data;
    CHECK(tgp_ppm_write(path, 2, 2, rgb, NULL, 0) == 0, "write");
    data = read_with_header(path, 11 + 12, "P6\n2 2\n255\n");
    CHECK(memcmp(data + 11, rgb, 12) == 0, "pixels top to bottom, as given");
    free(data);
}

TEST(ppm_round_trip)
{
    enum { W = 7, H = 5 };
    uint8_t rgb[W * H * 3];
    tgp_img img;
    char msg[256];
    int i;
    for (i = 0; i < W * H * 3; i++) rgb[i] = (uint8_t)(i * 37 + 11);
    CHECK(tgp_ppm_write(tmp_path("rt.ppm"), W, H, rgb, msg, sizeof msg) == 0, "%s", msg);
    CHECK(tgp_img_read(tmp_path("rt.ppm"), &img, msg, sizeof msg) == 0, "%s", msg);
    CHECK(img.format == TG_IMG_PPM && img.width == W && img.height == H, "format/size");
    CHECK(img.channels == 3 && img.maxval == 255, "channels %d maxval %d", img.channels, img.maxval);
    for (i = 0; i < W * H * 3; i++)
        CHECK(img.pixels[i] == (float)rgb[i], "value %d: %g vs %d", i, (double)img.pixels[i], rgb[i]);
    tgp_img_free(&img);
}

TEST(pfm_bytes_on_disk)
{
    /* 2x2 one channel: rows top to bottom in memory {1, 2}, {3, -0.5} */
    const float v[4] = { 1.0f, 2.0f, 3.0f, -0.5f };
    const unsigned char one_le[4] = { 0x00, 0x00, 0x80, 0x3f };   /* 1.0f */
    const unsigned char three_le[4] = { 0x00, 0x00, 0x40, 0x40 }; /* 3.0f */
    const char *path = tmp_path("a.pfm");
    unsigned char *data;
    size_t h = strlen("Pf\n2 2\n-1.0\n");
    CHECK(tgp_pfm_write(path, 2, 2, 1, v, NULL, 0) == 0, "write");
    data = read_with_header(path, h + 16, "Pf\n2 2\n-1.0\n");
    /* the file's first row is the image's BOTTOM row, little-endian */
    CHECK(memcmp(data + h, three_le, 4) == 0, "first stored value is 3.0f LE");
    CHECK(memcmp(data + h + 8, one_le, 4) == 0, "third stored value is 1.0f LE");
    free(data);
}

TEST(pfm_rgb_header_and_size)
{
    enum { W = 5, H = 3 };
    float v[W * H * 3];
    size_t h = strlen("PF\n5 3\n-1.0\n");
    int i;
    for (i = 0; i < W * H * 3; i++) v[i] = (float)i;
    CHECK(tgp_pfm_write(tmp_path("rgb.pfm"), W, H, 3, v, NULL, 0) == 0, "write");
    free(read_with_header(tmp_path("rgb.pfm"), h + (size_t)W * H * 3 * 4, "PF\n5 3\n-1.0\n"));
}

TEST(pfm_round_trip)
{
    enum { W = 6, H = 4 };
    float v[W * H * 3];
    tgp_img img;
    char msg[256];
    int i, ch;
    for (ch = 1; ch <= 3; ch += 2) {
        for (i = 0; i < W * H * ch; i++) v[i] = (float)i * 0.37f - 3.0f + (i == 5 ? 1e30f : 0.0f);
        CHECK(tgp_pfm_write(tmp_path("rt.pfm"), W, H, ch, v, msg, sizeof msg) == 0, "%s", msg);
        CHECK(tgp_img_read(tmp_path("rt.pfm"), &img, msg, sizeof msg) == 0, "%s", msg);
        CHECK(img.format == TG_IMG_PFM && img.width == W && img.height == H, "format/size");
        CHECK(img.channels == ch, "channels %d vs %d", img.channels, ch);
        for (i = 0; i < W * H * ch; i++)
            CHECK(memcmp(&img.pixels[i], &v[i], 4) == 0, "value %d bit-exact", i);
        tgp_img_free(&img);
    }
}

TEST(pfm_big_endian_read)
{
    /* positive scale: big-endian; 1x2 Pf, file rows bottom to top: 2.0, then 1.0 */
    const unsigned char file[] = { 'P', 'f', '\n', '1', ' ', '2', '\n', '1', '.', '0', '\n',
                                   0x40, 0x00, 0x00, 0x00, 0x3f, 0x80, 0x00, 0x00 };
    tgp_img img;
    char msg[256];
    CHECK(tgp_img_decode(file, sizeof file, &img, msg, sizeof msg) == 0, "%s", msg);
    CHECK(img.width == 1 && img.height == 2 && img.channels == 1, "size");
    CHECK(img.pixels[0] == 1.0f && img.pixels[1] == 2.0f, "top %g bottom %g",
          (double)img.pixels[0], (double)img.pixels[1]);
    tgp_img_free(&img);
}

TEST(ppm_header_variants)
{
    /* comments, odd whitespace, maxval 15 and 16-bit samples */
    const unsigned char a[] = "P6 # comment\n1\t1 # more\n15\n\x01\x02\x0f";
    const unsigned char b[] = "P6\n1 1\n65535\n\x01\x00\x00\x02\xff\xff";
    tgp_img img;
    char msg[256];
    CHECK(tgp_img_decode(a, sizeof a - 1, &img, msg, sizeof msg) == 0, "%s", msg);
    CHECK(img.maxval == 15 && img.pixels[2] == 15.0f, "maxval %d", img.maxval);
    tgp_img_free(&img);
    CHECK(tgp_img_decode(b, sizeof b - 1, &img, msg, sizeof msg) == 0, "%s", msg);
    CHECK(img.maxval == 65535 && img.pixels[0] == 256.0f && img.pixels[1] == 2.0f &&
          img.pixels[2] == 65535.0f, "16-bit big-endian samples");
    tgp_img_free(&img);
}

TEST(malformed_images_refused)
{
    static const struct { const char *bytes; size_t n; const char *why; } bad[] = {
        { "", 0, "not a PPM" },
        { "P5\n1 1\n255\n\0", 12, "not a PPM" },
        { "P6\n2 2\n255\n\1\2\3", 14, "truncated" },
        { "P6\n0 2\n255\n", 11, "1.." },
        { "P6\n2 0\n255\n", 11, "1.." },
        { "P6\n99999999999999999999 1\n255\n", 30, "width" },
        { "P6\n8193 1\n255\n", 14, "width must be 1..8192" },
        { "P6\n1 8193\n255\n", 14, "height must be 1..8192" },
        { "P6\n8192 8192\n255\n", 17, "pixels must be 1..16777216" },
        { "P6\nx 1\n255\n", 11, "width" },
        { "P6\n1 1\n0\n\1\2\3", 12, "maxval" },
        { "P6\n1 1\n70000\n\1\2\3", 16, "maxval" },
        { "P6\n1 1\n255", 10, "header" },
        { "P6\n1 1\n10\n\1\2\13", 13, "exceeds" },
        { "PF\n1 1\n-1.0\n\0\0\0\0", 16, "truncated" },
        { "Pf\n1 1\n0\n\0\0\0\0", 13, "scale" },
        { "Pf\n1 1\nabc\n\0\0\0\0", 15, "scale" },
        { "Pf\n-1 1\n-1\n\0\0\0\0", 15, "width" },
    };
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        tgp_img img;
        char msg[256] = "";
        int r = tgp_img_decode((const unsigned char *)bad[i].bytes, bad[i].n, &img, msg, sizeof msg);
        CHECK(r != 0, "case %zu accepted", i);
        CHECK(strstr(msg, bad[i].why) != NULL, "case %zu: message '%s' lacks '%s'", i, msg, bad[i].why);
        if (r == 0) tgp_img_free(&img);
        else CHECK(img.pixels == NULL, "case %zu: pixels left allocated", i);
    }
}

TEST(size_limits_overflow_checked)
{
    char msg[256];
    CHECK(tgp_img_check_size(1, 1, 3, msg, sizeof msg) == 0, "1x1");
    CHECK(tgp_img_check_size(4097, 3, 3, msg, sizeof msg) == 0, "4097x3");
    /* the renderer's limits (tinygi.h): sides 1..8192, at most 2^24 pixels */
    CHECK(tgp_img_check_size(TG_MAX_IMAGE_SIDE, (int)(TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE), 3,
                             msg, sizeof msg) == 0, "8192x2048: %s", msg);
    CHECK(tgp_img_check_size(TG_MAX_IMAGE_SIDE, (int)(TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE) + 1,
                             3, msg, sizeof msg) != 0 && strstr(msg, "pixels must be 1..16777216"),
          "pixel cap: %s", msg);
    CHECK(tgp_img_check_size(TG_MAX_IMAGE_SIDE + 1, 1, 3, msg, sizeof msg) != 0 &&
          strstr(msg, "each side must be 1..8192"), "side cap: %s", msg);
    CHECK(tgp_img_check_size(1, TG_MAX_IMAGE_SIDE + 1, 3, msg, sizeof msg) != 0, "height cap");
    CHECK(tgp_img_check_size(0, 1, 3, msg, sizeof msg) != 0, "zero");
    CHECK(tgp_img_check_size(-5, 1, 3, msg, sizeof msg) != 0, "negative");
    CHECK(tgp_img_check_size(1, 1, 2, msg, sizeof msg) != 0, "2 channels");
}

TEST(format_from_path)
{
    tgp_img_format f;
    CHECK(tgp_img_format_from_path("a/out.ppm", &f) == 0 && f == TG_IMG_PPM, "ppm");
    CHECK(tgp_img_format_from_path("OUT.PFM", &f) == 0 && f == TG_IMG_PFM, "PFM");
    CHECK(tgp_img_format_from_path("f%04d.pfm", &f) == 0 && f == TG_IMG_PFM, "pattern");
    CHECK(tgp_img_format_from_path("out.png", &f) == 0 && f == TG_IMG_PNG, "png");
    CHECK(tgp_img_format_from_path("F%03d.PNG", &f) == 0 && f == TG_IMG_PNG, "PNG pattern");
    CHECK(tgp_img_format_from_path("out.jpg", &f) != 0, "jpg");
    CHECK(tgp_img_format_from_path("ppm", &f) != 0, "no dot");
    CHECK(tgp_img_format_from_path("out.ppmx", &f) != 0, "ppmx");
}

static tgp_img make_img(tgp_img_format format, int w, int h, int channels, float *px)
{
    tgp_img img;
    img.width = w;
    img.height = h;
    img.channels = channels;
    img.format = format;
    img.maxval = format == TG_IMG_PPM ? 255 : 0;
    img.pixels = px;
    return img;
}

TEST(diff_numbers)
{
    /* 2x2 RGB PPM; b differs by 3 at (1,0) green and by 4 at (0,1) blue:
     * sum of squares 9 + 16 = 25 over 12 values -> rmse = 5/sqrt(12). */
    float pa[12] = { 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120 };
    float pb[12] = { 10, 20, 30, 40, 53, 60, 70, 80, 94, 100, 110, 120 };
    tgp_img a = make_img(TG_IMG_PPM, 2, 2, 3, pa), b = make_img(TG_IMG_PPM, 2, 2, 3, pb);
    tgp_diff d;
    char msg[256];
    double rmse = 5.0 / sqrt(12.0);
    CHECK(tgp_diff_compare(&a, &b, 3.0, &d, msg, sizeof msg) == 0, "%s", msg);
    CHECK_NEAR(d.rmse, rmse, 1e-12);
    CHECK_NEAR(d.psnr, 20.0 * log10(255.0 / rmse), 1e-9);
    CHECK(d.max_abs == 4.0 && d.max_x == 0 && d.max_y == 1 && d.max_channel == 2,
          "max %g at %d,%d c%d", d.max_abs, d.max_x, d.max_y, d.max_channel);
    CHECK(d.pixels == 4 && d.pixels_over == 1, "over %zu of %zu", d.pixels_over, d.pixels);
    CHECK(!tgp_diff_within(&d), "4 > tolerance 3");
    CHECK(tgp_diff_compare(&a, &b, 4.0, &d, msg, sizeof msg) == 0 && tgp_diff_within(&d), "4 <= 4");
    CHECK(d.pixels_over == 0, "none over 4");
    CHECK(tgp_diff_describe(&d, msg, sizeof msg) > 0 && strstr(msg, "max 4 at 0,1 (channel b)"), "%s", msg);
}

TEST(diff_max_is_first_in_row_order)
{
    /* 3x2 one channel; equal largest differences at (2,0) and (1,1) */
    float pa[6] = { 0, 0, 0, 0, 0, 0 }, pb[6] = { 1, 0, 7, 0, 7, 7 };
    tgp_img a = make_img(TG_IMG_PFM, 3, 2, 1, pa), b = make_img(TG_IMG_PFM, 3, 2, 1, pb);
    tgp_diff d;
    CHECK(tgp_diff_compare(&a, &b, 0.0, &d, NULL, 0) == 0, "compare");
    CHECK(d.max_abs == 7.0 && d.max_x == 2 && d.max_y == 0, "max %g at %d,%d", d.max_abs, d.max_x, d.max_y);
    CHECK(d.pixels_over == 4, "over %zu", d.pixels_over);
}

TEST(diff_identical_and_symmetric)
{
    float pa[6] = { 0.5f, -1.0f, 2.0f, 0.25f, 1e-8f, 3.0f };
    float pb[6] = { 0.5f, -1.0f, 2.5f, 0.25f, 0.0f, 3.0f };
    tgp_img a = make_img(TG_IMG_PFM, 3, 2, 1, pa), b = make_img(TG_IMG_PFM, 3, 2, 1, pb);
    tgp_diff d, e;
    CHECK(tgp_diff_compare(&a, &a, 0.0, &d, NULL, 0) == 0, "compare");
    CHECK(d.rmse == 0.0 && d.max_abs == 0.0 && isinf(d.psnr) && d.psnr > 0, "identical");
    CHECK(tgp_diff_within(&d), "identical is within tolerance 0");
    CHECK(tgp_diff_compare(&a, &b, 0.0, &d, NULL, 0) == 0, "compare");
    CHECK(tgp_diff_compare(&b, &a, 0.0, &e, NULL, 0) == 0, "compare");
    CHECK(d.rmse == e.rmse && d.max_abs == e.max_abs && d.max_x == e.max_x, "symmetric");
    CHECK(d.max_abs == 0.5 && d.max_x == 2 && d.max_y == 0, "max %g at %d,%d", d.max_abs, d.max_x, d.max_y);
    CHECK_NEAR(d.psnr, 20.0 * log10(1.0 / d.rmse), 1e-9); /* PFM peak is 1 */
    CHECK(d.pixels_over == 2, "1e-8 and 0.5 over tolerance 0: %zu", d.pixels_over);
}

TEST(diff_non_finite)
{
    float pa[2] = { NAN, INFINITY }, pb[2] = { NAN, 1.0f }, pc[2] = { 1.0f, INFINITY };
    tgp_img a = make_img(TG_IMG_PFM, 2, 1, 1, pa), b = make_img(TG_IMG_PFM, 2, 1, 1, pb);
    tgp_img c = make_img(TG_IMG_PFM, 2, 1, 1, pc);
    tgp_diff d;
    char line[512];
    /* an image against itself: NaN vs NaN and inf vs inf are differences */
    CHECK(tgp_diff_compare(&a, &a, 1e30, &d, NULL, 0) == 0, "compare");
    CHECK(isinf(d.max_abs) && d.max_x == 0 && d.pixels_over == 2 && !tgp_diff_within(&d),
          "NaN vs NaN and inf vs inf: max %g at %d, %zu over", d.max_abs, d.max_x, d.pixels_over);
    CHECK(d.nan[0] == 1 && d.inf[0] == 1 && d.nan[1] == 1 && d.inf[1] == 1, "counted");
    CHECK(d.first_x[0] == 0 && d.first_y[0] == 0, "first at %d,%d", d.first_x[0], d.first_y[0]);
    CHECK(tgp_diff_compare(&a, &b, 1e30, &d, NULL, 0) == 0, "compare");
    CHECK(isinf(d.max_abs) && d.max_x == 0 && !tgp_diff_within(&d), "NaN vs NaN first");
    CHECK(d.nan[1] == 1 && d.inf[1] == 0, "b: one NaN");
    CHECK(tgp_diff_compare(&b, &c, 1e30, &d, NULL, 0) == 0, "compare");
    CHECK(isinf(d.max_abs) && d.max_x == 0 && d.pixels_over == 2, "NaN vs 1 and 1 vs inf");
    CHECK(tgp_diff_describe(&d, line, sizeof line) > 0 &&
          strstr(line, "a has 1 NaN and 0 inf values (first at 0,0)") &&
          strstr(line, "b has 0 NaN and 1 inf values (first at 1,0)"), "%s", line);
    /* a NaN where the other image has the same finite values elsewhere */
    pb[0] = 2.0f;
    CHECK(tgp_diff_compare(&b, &b, 0.0, &d, NULL, 0) == 0 && d.max_abs == 0.0 &&
          tgp_diff_within(&d) && d.first_x[0] == -1, "finite images equal to themselves");
}

/* ---- PNG ---- */

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

TEST(crc32_check_values)
{
    /* the CRC-32 check value (ISO 3309 / ITU-T V.42) and PNG's IEND chunk CRC */
    CHECK(tgp_crc32(0, "123456789", 9) == 0xCBF43926u, "%08x", (unsigned)tgp_crc32(0, "123456789", 9));
    CHECK(tgp_crc32(0, "IEND", 4) == 0xAE426082u, "IEND");
    CHECK(tgp_crc32(tgp_crc32(0, "1234", 4), "56789", 5) == 0xCBF43926u, "continued");
}

TEST(png_bytes_on_disk)
{
    /* 2x1: one scanline [0, 1 2 3, 250 251 252] in one stored block */
    const uint8_t rgb[6] = { 1, 2, 3, 250, 251, 252 };
    static const unsigned char sig[8] = { 137, 'P', 'N', 'G', 13, 10, 26, 10 };
    static const unsigned char ihdr[13] = { 0, 0, 0, 2, 0, 0, 0, 1, 8, 2, 0, 0, 0 };
    unsigned char *d;
    size_t n, idat = 8 + 12 + 13, len;
    uint32_t s1 = 1 + 0 + 1 + 2 + 3 + 250 + 251 + 252, s2 = 0, run = 1;
    int i;
    const int bytes[7] = { 0, 1, 2, 3, 250, 251, 252 };
    for (i = 0; i < 7; i++) { run += (uint32_t)bytes[i]; s2 += run; } /* RFC 1950 sec. 8.2 */
    CHECK(tgp_png_write(tmp_path("a.png"), 2, 1, rgb, NULL, 0) == 0, "write");
    CHECK(read_raw(tmp_path("a.png"), &d, &n) == 0, "read back");
    if (n < idat + 8) return;
    CHECK(memcmp(d, sig, 8) == 0, "signature");
    CHECK(be32(d + 8) == 13 && memcmp(d + 12, "IHDR", 4) == 0 && memcmp(d + 16, ihdr, 13) == 0,
          "IHDR: 2x1, 8 bits, RGB");
    CHECK(be32(d + 29) == tgp_crc32(0, d + 12, 17), "IHDR CRC");
    len = be32(d + idat);
    CHECK(len == 2 + 5 + 7 + 4 && memcmp(d + idat + 4, "IDAT", 4) == 0, "one IDAT of %zu", len);
    CHECK(d[idat + 8] == 0x78 && d[idat + 9] == 0x01 && (0x78 * 256 + 0x01) % 31 == 0, "zlib header");
    CHECK(d[idat + 10] == 1 && d[idat + 11] == 7 && d[idat + 12] == 0 && d[idat + 13] == 0xf8 &&
          d[idat + 14] == 0xff, "stored block: final, LEN 7, NLEN ~7");
    CHECK(d[idat + 15] == 0 && memcmp(d + idat + 16, rgb, 6) == 0, "filter None, then the pixels");
    CHECK(be32(d + idat + 22) == ((s2 % 65521u) << 16 | (s1 % 65521u)), "Adler-32 %08x",
          (unsigned)be32(d + idat + 22));
    CHECK(be32(d + idat + 8 + len) == tgp_crc32(0, d + idat + 4, 4 + len), "IDAT CRC");
    CHECK(n == idat + 12 + len + 12 && be32(d + n - 12) == 0 && memcmp(d + n - 8, "IEND", 4) == 0 &&
          be32(d + n - 4) == 0xAE426082u, "IEND last, %zu bytes", n);
    free(d);
}

TEST(png_one_block_per_row)
{
    /* 3 rows: three IDAT chunks, only the last block final and followed by Adler-32 */
    uint8_t rgb[4 * 3 * 3];
    unsigned char *d;
    size_t n, at = 8 + 25;
    int row;
    memset(rgb, 7, sizeof rgb);
    CHECK(tgp_png_write(tmp_path("b.png"), 4, 3, rgb, NULL, 0) == 0, "write");
    CHECK(read_raw(tmp_path("b.png"), &d, &n) == 0, "read back");
    for (row = 0; row < 3 && at + 12 <= n; row++) {
        size_t len = be32(d + at), head = row == 0 ? 2 : 0;
        CHECK(memcmp(d + at + 4, "IDAT", 4) == 0, "row %d IDAT", row);
        CHECK(len == head + 5 + 13 + (row == 2 ? 4 : 0), "row %d length %zu", row, len);
        CHECK(d[at + 8 + head] == (row == 2), "row %d BFINAL", row);
        CHECK(be32(d + at + 8 + len) == tgp_crc32(0, d + at + 4, 4 + len), "row %d CRC", row);
        at += 12 + len;
    }
    CHECK(at + 12 == n, "IEND follows the last row");
    free(d);
    CHECK(tgp_png_write(tmp_path("c.png"), 0, 3, rgb, NULL, 0) != 0, "0x3 refused");
}

TEST(png_adler32_past_the_modulus)
{
    /* 200x100 white: the sums pass 65521 many times; Adler-32 computed here
     * byte by byte, the slow way of RFC 1950 sec. 8.2 */
    enum { W = 200, H = 100 };
    static uint8_t rgb[W * H * 3];
    unsigned char *d;
    size_t n, i;
    uint32_t s1 = 1, s2 = 0;
    memset(rgb, 255, sizeof rgb);
    for (i = 0; i < (size_t)H * (1 + 3 * W); i++) {
        s1 = (s1 + (i % (1 + 3 * W) == 0 ? 0u : 255u)) % 65521u;
        s2 = (s2 + s1) % 65521u;
    }
    CHECK(tgp_png_write(tmp_path("w.png"), W, H, rgb, NULL, 0) == 0, "write");
    CHECK(read_raw(tmp_path("w.png"), &d, &n) == 0 && n > 24, "read back");
    if (n <= 24) return;
    /* the Adler-32 ends the last IDAT, just before its CRC and the 12-byte IEND */
    CHECK(be32(d + n - 12 - 8) == (s2 << 16 | s1), "Adler-32 %08x, expected %08x",
          (unsigned)be32(d + n - 20), (unsigned)(s2 << 16 | s1));
    free(d);
}

TEST(diff_refuses_mismatch)
{
    float p[12] = { 0 };
    tgp_img a = make_img(TG_IMG_PPM, 2, 2, 3, p), b = make_img(TG_IMG_PPM, 4, 1, 3, p);
    tgp_img c = make_img(TG_IMG_PFM, 2, 2, 3, p), e = make_img(TG_IMG_PFM, 2, 2, 1, p);
    tgp_img f = make_img(TG_IMG_PPM, 2, 2, 3, p);
    tgp_diff d;
    char msg[256];
    f.maxval = 65535;
    CHECK(tgp_diff_compare(&a, &b, 0.0, &d, msg, sizeof msg) != 0 && strstr(msg, "sizes"), "%s", msg);
    CHECK(tgp_diff_compare(&a, &c, 0.0, &d, msg, sizeof msg) != 0 && strstr(msg, "PFM"), "%s", msg);
    CHECK(tgp_diff_compare(&c, &e, 0.0, &d, msg, sizeof msg) != 0, "PF vs Pf");
    CHECK(tgp_diff_compare(&a, &f, 0.0, &d, msg, sizeof msg) != 0 && strstr(msg, "maxval"), "%s", msg);
}

TEST(diff_image_scaled)
{
    float pa[3] = { 0, 0, 0 }, pb[3] = { 2, 4, 1 };
    tgp_img a = make_img(TG_IMG_PFM, 3, 1, 1, pa), b = make_img(TG_IMG_PFM, 3, 1, 1, pb);
    tgp_diff d;
    uint8_t *rgb;
    CHECK(tgp_diff_compare(&a, &b, 0.0, &d, NULL, 0) == 0, "compare");
    rgb = tgp_diff_image(&a, &b, &d);
    CHECK(rgb != NULL, "image");
    if (!rgb) return;
    CHECK(rgb[3] == 255 && rgb[4] == 255 && rgb[5] == 255, "largest difference is white");
    CHECK(rgb[0] == 128 && rgb[1] == 128 && rgb[2] == 128, "half difference is mid grey: %d", rgb[0]);
    CHECK(rgb[6] == 64, "quarter: %d", rgb[6]);
    free(rgb);
}

TEST(clock_monotonic)
{
    double a = tgp_clock_seconds(), b = tgp_clock_seconds();
    CHECK(a > 0.0 && b >= a, "%f then %f", a, b);
}

int main(void)
{
    if (tmpdir_make("image")) return 1;
    RUN(ppm_bytes_on_disk);
    RUN(ppm_round_trip);
    RUN(pfm_bytes_on_disk);
    RUN(pfm_rgb_header_and_size);
    RUN(pfm_round_trip);
    RUN(pfm_big_endian_read);
    RUN(ppm_header_variants);
    RUN(malformed_images_refused);
    RUN(size_limits_overflow_checked);
    RUN(format_from_path);
    RUN(diff_numbers);
    RUN(diff_max_is_first_in_row_order);
    RUN(diff_identical_and_symmetric);
    RUN(diff_non_finite);
    RUN(diff_refuses_mismatch);
    RUN(crc32_check_values);
    RUN(png_bytes_on_disk);
    RUN(png_one_block_per_row);
    RUN(png_adler32_past_the_modulus);
    RUN(diff_image_scaled);
    RUN(clock_monotonic);
    tmpdir_remove();
    return check_summary();
}
