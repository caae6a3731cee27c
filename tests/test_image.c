/* SPDX-License-Identifier: MIT */
/*
 * test_image.c - the hosted platform's image files and diff: PPM and PFM
 * bytes on disk (headers, byte order, PFM's bottom-to-top rows), round
 * trips, refusal of malformed files, the diff numbers against hand-computed
 * values, and atomic writes (a failed write never leaves a partial file or
 * touches an existing one).
 */
#include <dirent.h>
#include <signal.h>
#include <sys/resource.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>
#include "check.h"
#include "hosted/file.h"
#include "hosted/image.h"
#include "hosted/imgdiff.h"
#include "hosted/clock.h"

static char tmpdir[256];

static const char *tmp_path(const char *name)
{
    static char buf[4][512];
    static int next;
    char *p = buf[next++ & 3];
    snprintf(p, 512, "%s/%s", tmpdir, name);
    return p;
}

static int write_raw(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    size_t w;
    if (!f) return 1;
    w = fwrite(data, 1, n, f);
    return fclose(f) != 0 || w != n;
}

static int read_raw(const char *path, unsigned char **data, size_t *n)
{
    char *d;
    if (tgp_file_read(path, &d, n, NULL, 0)) return 1;
    *data = (unsigned char *)d;
    return 0;
}

/* Entries in tmpdir whose name contains ".tmp-" (left-over temporaries). */
static int count_temporaries(void)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    int n = 0;
    if (!d) return -1;
    while ((e = readdir(d)) != NULL)
        if (strstr(e->d_name, ".tmp-")) n++;
    closedir(d);
    return n;
}

TEST(ppm_bytes_on_disk)
{
    const uint8_t rgb[2 * 3 * 2] = { 1, 2, 3, 4, 5, 6, 250, 251, 252, 0, 128, 255 };
    const char *path = tmp_path("a.ppm");
    unsigned char *data;
    size_t n;
    CHECK(tgp_ppm_write(path, 2, 2, rgb, NULL, 0) == 0, "write");
    CHECK(read_raw(path, &data, &n) == 0, "read back");
    CHECK(n == 11 + 12, "size %zu", n);
    CHECK(memcmp(data, "P6\n2 2\n255\n", 11) == 0, "header");
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
    size_t n, h = strlen("Pf\n2 2\n-1.0\n");
    CHECK(tgp_pfm_write(path, 2, 2, 1, v, NULL, 0) == 0, "write");
    CHECK(read_raw(path, &data, &n) == 0, "read back");
    CHECK(n == h + 16, "size %zu", n);
    CHECK(memcmp(data, "Pf\n2 2\n-1.0\n", h) == 0, "header");
    /* the file's first row is the image's BOTTOM row, little-endian */
    CHECK(memcmp(data + h, three_le, 4) == 0, "first stored value is 3.0f LE");
    CHECK(memcmp(data + h + 8, one_le, 4) == 0, "third stored value is 1.0f LE");
    free(data);
}

TEST(pfm_rgb_header_and_size)
{
    enum { W = 5, H = 3 };
    float v[W * H * 3];
    unsigned char *data;
    size_t n, h = strlen("PF\n5 3\n-1.0\n");
    int i;
    for (i = 0; i < W * H * 3; i++) v[i] = (float)i;
    CHECK(tgp_pfm_write(tmp_path("rgb.pfm"), W, H, 3, v, NULL, 0) == 0, "write");
    CHECK(read_raw(tmp_path("rgb.pfm"), &data, &n) == 0, "read back");
    CHECK(n == h + (size_t)W * H * 3 * 4, "size %zu", n);
    CHECK(memcmp(data, "PF\n5 3\n-1.0\n", h) == 0, "header");
    free(data);
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
        { "P6\n16385 1\n255\n", 15, "width" },
        { "P6\n16384 16384\n255\n", 19, "pixels" },
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
    CHECK(tgp_img_check_size(TG_IMG_MAX_SIDE, 4096, 3, msg, sizeof msg) == 0, "16384x4096");
    CHECK(tgp_img_check_size(TG_IMG_MAX_SIDE, TG_IMG_MAX_SIDE, 3, msg, sizeof msg) != 0, "pixel cap");
    CHECK(tgp_img_check_size(TG_IMG_MAX_SIDE + 1, 1, 3, msg, sizeof msg) != 0, "side cap");
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
    CHECK(tgp_img_format_from_path("out.png", &f) != 0, "png");
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
    CHECK(tgp_diff_compare(&a, &a, 0.0, &d, NULL, 0) == 0 && d.max_abs == 0.0, "NaN equals NaN bits");
    CHECK(tgp_diff_compare(&a, &b, 1e30, &d, NULL, 0) == 0, "compare");
    CHECK(isinf(d.max_abs) && d.max_x == 1 && !tgp_diff_within(&d), "inf vs 1 is infinite");
    CHECK(tgp_diff_compare(&a, &c, 1e30, &d, NULL, 0) == 0, "compare");
    CHECK(isinf(d.max_abs) && d.max_x == 0, "NaN vs 1 is infinite");
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

TEST(atomic_write_replaces_whole_file)
{
    const char *path = tmp_path("atomic.bin");
    char *data;
    size_t n;
    struct stat st;
    mode_t old = umask(022);
    CHECK(write_raw(path, "old contents", 12) == 0, "setup");
    CHECK(tgp_file_write_atomic(path, "new", 3, NULL, 0) == 0, "write");
    CHECK(tgp_file_read(path, &data, &n, NULL, 0) == 0 && n == 3 && memcmp(data, "new", 3) == 0,
          "replaced whole");
    free(data);
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644, "mode %o (0666 minus umask 022)",
          (unsigned)(st.st_mode & 0777));
    CHECK(count_temporaries() == 0, "no temporaries left");
    umask(old);
}

TEST(atomic_write_abort_leaves_existing_file)
{
    const char *path = tmp_path("keep.ppm");
    tgp_outfile *f = (tgp_outfile *)malloc(sizeof *f);
    char *data;
    size_t n;
    CHECK(write_raw(path, "precious", 8) == 0, "setup");
    CHECK(tgp_outfile_open(f, path, NULL, 0) == 0, "open");
    tgp_ppm_write_header(f, 100, 100);
    tgp_outfile_write(f, "partial", 7);
    CHECK(count_temporaries() == 1, "one temporary while writing");
    tgp_outfile_abort(f);
    CHECK(tgp_file_read(path, &data, &n, NULL, 0) == 0 && n == 8 && memcmp(data, "precious", 8) == 0,
          "existing file untouched");
    free(data);
    CHECK(count_temporaries() == 0, "temporary removed");
    free(f);
}

TEST(atomic_write_failure_leaves_nothing)
{
    char msg[256] = "";
    const char *dirpath = tmp_path("adir");
    const char *missing = tmp_path("no/such/dir/x.ppm");
    uint8_t rgb[3] = { 1, 2, 3 };
    struct stat st;
    /* destination is a directory: rename fails, the directory stays, no temporary */
    CHECK(mkdir(dirpath, 0755) == 0, "setup");
    CHECK(tgp_ppm_write(dirpath, 1, 1, rgb, msg, sizeof msg) != 0, "write over a directory refused");
    CHECK(strstr(msg, "cannot write") != NULL, "message '%s'", msg);
    CHECK(stat(dirpath, &st) == 0 && S_ISDIR(st.st_mode), "directory untouched");
    CHECK(count_temporaries() == 0, "temporary removed");
    CHECK(tgp_file_dir_writable(dirpath, msg, sizeof msg) != 0, "dir_writable says no: %s", msg);
    rmdir(dirpath);
    /* missing directory */
    CHECK(tgp_ppm_write(missing, 1, 1, rgb, msg, sizeof msg) != 0, "missing dir refused");
    CHECK(stat(missing, &st) != 0, "nothing created");
    CHECK(tgp_file_dir_writable(missing, msg, sizeof msg) != 0, "dir_writable says no");
    CHECK(tgp_file_dir_writable(tmp_path("fine.ppm"), msg, sizeof msg) == 0, "%s", msg);
    /* a size outside the limits is refused before any file is made */
    CHECK(tgp_ppm_write(tmp_path("zero.ppm"), 0, 5, rgb, msg, sizeof msg) != 0, "0x5 refused");
    CHECK(stat(tmp_path("zero.ppm"), &st) != 0, "nothing created");
}

TEST(write_error_midway_leaves_existing_file)
{
    /* A file-size limit makes write() fail part way (EFBIG), even as root. */
    static char big[200000];
    const char *path = tmp_path("full.ppm");
    struct rlimit old, lim;
    char msg[256] = "", *data;
    size_t n;
    CHECK(write_raw(path, "precious", 8) == 0, "setup");
    CHECK(getrlimit(RLIMIT_FSIZE, &old) == 0, "getrlimit");
    lim = old;
    lim.rlim_cur = 1000;
    signal(SIGXFSZ, SIG_IGN);
    CHECK(setrlimit(RLIMIT_FSIZE, &lim) == 0, "setrlimit");
    CHECK(tgp_file_write_atomic(path, big, sizeof big, msg, sizeof msg) != 0, "write past the limit fails");
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, SIG_DFL);
    CHECK(strstr(msg, "cannot write") != NULL, "message '%s'", msg);
    CHECK(tgp_file_read(path, &data, &n, NULL, 0) == 0 && n == 8 && memcmp(data, "precious", 8) == 0,
          "existing file untouched");
    free(data);
    CHECK(count_temporaries() == 0, "no partial temporary left");
}

TEST(file_read_errors)
{
    char *data;
    size_t n;
    char msg[256];
    CHECK(tgp_file_read(tmp_path("nope"), &data, &n, msg, sizeof msg) != 0 &&
          strstr(msg, "cannot open"), "%s", msg);
    CHECK(tgp_file_read(tmpdir, &data, &n, msg, sizeof msg) != 0 && strstr(msg, "directory"), "%s", msg);
    CHECK(write_raw(tmp_path("empty"), "", 0) == 0, "setup");
    CHECK(tgp_file_read(tmp_path("empty"), &data, &n, msg, sizeof msg) == 0 && n == 0 && data[0] == 0,
          "empty file reads as empty, NUL-terminated");
    free(data);
}

TEST(host_io_reads_and_frees)
{
    tgp_host_io h;
    const char *d1, *d2, *why = NULL;
    size_t n1, n2;
    CHECK(write_raw(tmp_path("m.obj"), "v 0 0 0\n", 8) == 0, "setup");
    tgp_host_io_init(&h);
    CHECK(h.io.read_file(h.io.user, tmp_path("m.obj"), &d1, &n1, &why) == 0 && n1 == 8, "read");
    CHECK(h.io.read_file(h.io.user, tmp_path("m.obj"), &d2, &n2, &why) == 0 && d1 != d2, "second buffer");
    CHECK(memcmp(d1, "v 0 0 0\n", 8) == 0, "both buffers stay valid");
    CHECK(h.io.read_file(h.io.user, tmp_path("none.obj"), &d2, &n2, &why) != 0, "missing");
    CHECK(strstr(h.last_error, "cannot open") != NULL, "%s", h.last_error);
    tgp_host_io_free(&h);
    CHECK(h.files == NULL, "freed");
}

TEST(clock_monotonic)
{
    double a = tgp_clock_seconds(), b = tgp_clock_seconds();
    CHECK(a > 0.0 && b >= a, "%f then %f", a, b);
}

static void remove_tree(void)
{
    DIR *d = opendir(tmpdir);
    struct dirent *e;
    char p[600];
    if (!d) return;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.' && (!e->d_name[1] || (e->d_name[1] == '.' && !e->d_name[2]))) continue;
        snprintf(p, sizeof p, "%s/%s", tmpdir, e->d_name);
        if (unlink(p) != 0) rmdir(p);
    }
    closedir(d);
    rmdir(tmpdir);
}

int main(void)
{
    const char *base = getenv("TMPDIR");
    snprintf(tmpdir, sizeof tmpdir, "%s/tgi_image_XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(tmpdir)) {
        perror("mkdtemp");
        return 1;
    }
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
    RUN(diff_image_scaled);
    RUN(atomic_write_replaces_whole_file);
    RUN(atomic_write_abort_leaves_existing_file);
    RUN(atomic_write_failure_leaves_nothing);
    RUN(write_error_midway_leaves_existing_file);
    RUN(file_read_errors);
    RUN(host_io_reads_and_frees);
    RUN(clock_monotonic);
    remove_tree();
    return check_summary();
}
