/* SPDX-License-Identifier: MIT */
/*
 * test_pixels.c - tg_frame_write_pixels and its row step (src/frame/pixels.c)
 * against a plain reference written here from the formats' definitions in
 * tinygi.h: the levels by integer division, the bytes by the machine's byte
 * order found at run time.  Every format on rendered frames (1x1, 7x3,
 * 16x12; colour, normals, depth, AO) with strides longer than a row; row
 * ranges and splits; the dither pattern's exact levels and its mean; every
 * input of the grey and 5/6-bit conversions; refused arguments that write
 * nothing (buffers are exactly the size the call may use, so `make
 * sanitize` catches a write outside).  The conversions are integer
 * functions of the 8-bit bytes and both number types are checked against
 * the same integer reference, so they write identical bytes for identical
 * rows.
 */
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "frame/pixels.h"

#define FILL 0xA5
#define AOVBIT(a) (1u << (a))

static const int bayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};

static const tg_pixel_format formats[] = {
    TG_PIXEL_RGB565, TG_PIXEL_BGR565, TG_PIXEL_RGB565_BE, TG_PIXEL_RGB888, TG_PIXEL_BGR888,
    TG_PIXEL_XRGB8888, TG_PIXEL_RGBA8888, TG_PIXEL_GREY8,
};
#define NFORMATS (int)(sizeof formats / sizeof formats[0])
static const int format_bytes[] = {2, 2, 2, 3, 3, 4, 4, 1}; /* in the order above */

static int little_endian(void)
{
    const uint16_t one = 1;
    return *(const unsigned char *)&one == 1;
}

/* ---- the reference ---- */

/* Level of an 8-bit channel with `top` = 31 or 63: round(c top / 255) with
 * halves up, or dithered with Bayer index m: floor(c top / 255 + (m + 0.5) / 16). */
static unsigned ref_level(unsigned c, unsigned top, int m)
{
    if (m < 0) return (2u * c * top + 255u) / 510u;
    return (c * top * 32u + (2u * (unsigned)m + 1u) * 255u) / (255u * 32u);
}

/* Rec. 709 luma of sRGB bytes, round(0.2126 R + 0.7152 G + 0.0722 B), halves up. */
static unsigned ref_grey(unsigned r, unsigned g, unsigned b)
{
    return (2126u * r + 7152u * g + 722u * b + 5000u) / 10000u;
}

/* `v` as n bytes in the machine's order. */
static void native(uint32_t v, int n, uint8_t *out)
{
    int i;
    for (i = 0; i < n; i++) out[i] = (uint8_t)(v >> (little_endian() ? 8 * i : 8 * (n - 1 - i)));
}

/* The bytes of pixel (x, y) of the frame, RGB bytes p; returns their count. */
static int ref_pixel(const uint8_t *p, int x, int y, tg_pixel_format fmt, int flags, uint8_t *out)
{
    int m = (flags & TG_PIXELS_DITHER) ? bayer[y & 3][x & 3] : -1;
    uint32_t r5 = ref_level(p[0], 31, m), g6 = ref_level(p[1], 63, m), b5 = ref_level(p[2], 31, m);
    switch (fmt) {
    case TG_PIXEL_RGB565: native(r5 << 11 | g6 << 5 | b5, 2, out); return 2;
    case TG_PIXEL_BGR565: native(b5 << 11 | g6 << 5 | r5, 2, out); return 2;
    case TG_PIXEL_RGB565_BE: out[0] = (uint8_t)(r5 << 3 | g6 >> 3); out[1] = (uint8_t)((g6 & 7) << 5 | b5); return 2;
    case TG_PIXEL_RGB888: out[0] = p[0]; out[1] = p[1]; out[2] = p[2]; return 3;
    case TG_PIXEL_BGR888: out[0] = p[2]; out[1] = p[1]; out[2] = p[0]; return 3;
    case TG_PIXEL_XRGB8888: native(0xFF000000u | (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2], 4, out); return 4;
    case TG_PIXEL_RGBA8888: out[0] = p[0]; out[1] = p[1]; out[2] = p[2]; out[3] = 255; return 4;
    case TG_PIXEL_GREY8: out[0] = (uint8_t)ref_grey(p[0], p[1], p[2]); return 1;
    default: return 0;
    }
}

/* ---- rendered frames ---- */
typedef struct rendered {
    tg_frame *frame;
    void *scene_mem, *frame_mem;
    int w, h;
} rendered;

static int render(rendered *r, int w, int h)
{
    const char *text = tg_builtin_scene("cornell");
    size_t scene_bytes = 1u << 20;
    tg_arena arena;
    tg_scene *scene = NULL;
    tg_request req;
    tg_plan plan;
    tg_error err;
    memset(r, 0, sizeof *r);
    r->w = w;
    r->h = h;
    r->scene_mem = malloc(scene_bytes);
    tg_arena_init(&arena, r->scene_mem, scene_bytes);
    if (!text || tg_scene_parse(text, strlen(text), "cornell", NULL, &arena, &scene, &err) != TG_OK) return 0;
    tg_request_defaults(&req);
    req.width = w;
    req.height = h;
    req.shadow_map_size = 16;
    req.aovs = AOVBIT(TG_AOV_COLOR) | AOVBIT(TG_AOV_DEPTH) | AOVBIT(TG_AOV_NORMAL) | AOVBIT(TG_AOV_AO);
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK) return 0;
    r->frame_mem = malloc(plan.total_bytes);
    if (!r->frame_mem || tg_frame_create(&plan, r->frame_mem, plan.total_bytes, &r->frame, &err) != TG_OK) return 0;
    return tg_frame_render(r->frame, 0, &err) == TG_OK;
}

static void release(rendered *r)
{
    free(r->scene_mem);
    free(r->frame_mem);
}

/* A buffer of exactly the bytes rows [0, n) at `stride` may use, FILL. */
static uint8_t *buffer(int n, size_t stride, size_t row, size_t *size)
{
    uint8_t *b;
    *size = n > 0 ? (size_t)(n - 1) * stride + row : 1;
    b = malloc(*size);
    if (b) memset(b, FILL, *size);
    return b;
}

static int all_fill(const uint8_t *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (b[i] != FILL) return 0;
    return 1;
}

/* Rows [y0, y1) of `dst` (stride apart) are the reference's for the frame's
 * 8-bit rows, and the bytes between rows are untouched. */
static void check_rows(const rendered *r, tg_aov aov, int y0, int y1, tg_pixel_format fmt, int flags,
                       const uint8_t *dst, size_t stride, int bpp)
{
    uint8_t *rgb = malloc(3u * (size_t)r->w), want[4];
    int x, y;
    for (y = y0; y < y1; y++) {
        const uint8_t *row = dst + (size_t)(y - y0) * stride;
        tg_frame_aov_row8(r->frame, aov, y, rgb);
        for (x = 0; x < r->w; x++) {
            int n = ref_pixel(rgb + 3 * x, x, y, fmt, flags, want);
            CHECK(n == bpp && memcmp(row + (size_t)x * (size_t)bpp, want, (size_t)bpp) == 0,
                  "%dx%d aov %s format %d flags %d: pixel (%d, %d)", r->w, r->h, tg_aov_name(aov), fmt, flags, x, y);
        }
        if (y + 1 < y1)
            CHECK(all_fill(row + (size_t)r->w * (size_t)bpp, stride - (size_t)r->w * (size_t)bpp),
                  "format %d: bytes after row %d touched", fmt, y);
    }
    free(rgb);
}

/* Every format and flag, on whole frames of three sizes and four AOVs, rows
 * padded by an odd number of bytes. */
TEST(every_format_matches_reference)
{
    static const int sizes[3][2] = {{1, 1}, {7, 3}, {16, 12}};
    static const tg_aov aovs[] = {TG_AOV_COLOR, TG_AOV_NORMAL, TG_AOV_DEPTH, TG_AOV_AO};
    int s, a, k, flags;
    for (s = 0; s < 3; s++) {
        rendered r;
        if (!render(&r, sizes[s][0], sizes[s][1])) { CHECK(0, "render %dx%d", sizes[s][0], sizes[s][1]); release(&r); continue; }
        for (a = 0; a < 4; a++)
            for (k = 0; k < NFORMATS; k++)
                for (flags = 0; flags <= TG_PIXELS_DITHER; flags++) {
                    size_t row = (size_t)r.w * (size_t)format_bytes[k], stride = row + 3, size;
                    uint8_t *dst = buffer(r.h, stride, row, &size);
                    CHECK(tg_frame_write_pixels(r.frame, aovs[a], 0, r.h, formats[k], flags, dst, stride) == TG_OK,
                          "format %d", formats[k]);
                    check_rows(&r, aovs[a], 0, r.h, formats[k], flags, dst, stride, format_bytes[k]);
                    free(dst);
                }
        release(&r);
    }
}

/* A row range lands at dst with the frame's own rows (and dither rows); a
 * frame written one row per call equals it written at once; an empty range
 * writes nothing. */
TEST(row_ranges_and_splits)
{
    rendered r;
    int k, y;
    if (!render(&r, 16, 12)) { CHECK(0, "render"); release(&r); return; }
    for (k = 0; k < NFORMATS; k++) {
        size_t row = 16u * (size_t)format_bytes[k], size, part_size;
        uint8_t *whole = buffer(12, row, row, &size), *split = buffer(12, row, row, &size);
        uint8_t *part = buffer(5, row + 8, row, &part_size);
        CHECK(tg_frame_write_pixels(r.frame, TG_AOV_COLOR, 0, 12, formats[k], TG_PIXELS_DITHER, whole, row) == TG_OK, "whole");
        for (y = 0; y < 12; y++)
            CHECK(tg_frame_write_pixels(r.frame, TG_AOV_COLOR, y, y + 1, formats[k], TG_PIXELS_DITHER,
                                        split + (size_t)y * row, row) == TG_OK, "row %d", y);
        CHECK(memcmp(whole, split, size) == 0, "format %d: rows one by one differ from the whole frame", formats[k]);
        CHECK(tg_frame_write_pixels(r.frame, TG_AOV_COLOR, 3, 8, formats[k], TG_PIXELS_DITHER, part, row + 8) == TG_OK, "part");
        check_rows(&r, TG_AOV_COLOR, 3, 8, formats[k], TG_PIXELS_DITHER, part, row + 8, format_bytes[k]);
        for (y = 0; y < 5; y++)
            CHECK(memcmp(part + (size_t)y * (row + 8), whole + (size_t)(3 + y) * row, row) == 0, "rows 3..7: row %d", 3 + y);
        free(part);
        part = buffer(1, row, row, &part_size);
        CHECK(tg_frame_write_pixels(r.frame, TG_AOV_COLOR, 12, 12, formats[k], 0, part, row) == TG_OK, "empty range at the end");
        CHECK(tg_frame_write_pixels(r.frame, TG_AOV_COLOR, 5, 5, formats[k], 0, part, row) == TG_OK, "empty range");
        CHECK(all_fill(part, part_size), "an empty range wrote");
        free(whole); free(split); free(part);
    }
    release(&r);
}

/* The red (5-bit) and green (6-bit) levels of grey 128, dithered, in the
 * 4x4 block at frame rows 4..7: 128 * 31 / 255 = 15.56 goes up to 16 where
 * (M + 0.5) / 16 >= 0.44, i.e. Bayer index M >= 7; 128 * 63 / 255 = 31.62
 * goes up to 32 where M >= 6.  The pattern repeats every 4 columns. */
TEST(dither_pattern_exact)
{
    static const unsigned red[4][4] = {{15, 16, 15, 16}, {16, 15, 16, 15}, {15, 16, 15, 16}, {16, 16, 16, 15}};
    static const unsigned green[4][4] = {{31, 32, 31, 32}, {32, 31, 32, 32}, {31, 32, 31, 32}, {32, 32, 32, 31}};
    uint8_t rgb[8 * 3], out[8 * 2];
    int x, y;
    memset(rgb, 128, sizeof rgb);
    for (y = 4; y < 8; y++) {
        tgi_pixels_row(rgb, 8, y, TG_PIXEL_RGB565_BE, TG_PIXELS_DITHER, out);
        for (x = 0; x < 8; x++) {
            unsigned v = (unsigned)out[2 * x] << 8 | out[2 * x + 1];
            CHECK(v >> 11 == red[y & 3][x & 3] && (v >> 5 & 63) == green[y & 3][x & 3] && (v & 31) == v >> 11,
                  "(%d, %d): r %u g %u b %u", x, y, v >> 11, v >> 5 & 63, v & 31);
        }
        tgi_pixels_row(rgb, 8, y, TG_PIXEL_RGB565_BE, 0, out);
        for (x = 0; x < 8; x++) /* not dithered: nearest, 16 and 32 */
            CHECK(out[2 * x] == (16 << 3 | 32 >> 3) && out[2 * x + 1] == 16, "undithered (%d, %d)", x, y);
    }
}

/* On a gradient holding every byte value at all 16 places of the Bayer
 * matrix (value x / 4 at column x, rows 0..3), every format's bytes are the
 * reference's, dithered or not. */
TEST(gradient_every_value_every_place)
{
    enum { N = 1024 };
    static uint8_t rgb[N * 3], out[N * 4];
    uint8_t want[4];
    int x, y, k, flags;
    for (x = 0; x < N; x++) {
        rgb[3 * x] = (uint8_t)(x / 4);
        rgb[3 * x + 1] = (uint8_t)(255 - x / 4);
        rgb[3 * x + 2] = (uint8_t)(x / 4 * 7);
    }
    for (k = 0; k < NFORMATS; k++)
        for (flags = 0; flags <= TG_PIXELS_DITHER; flags++)
            for (y = 0; y < 4; y++) {
                int bad = 0;
                tgi_pixels_row(rgb, N, y, formats[k], flags, out);
                for (x = 0; x < N; x++) {
                    int n = ref_pixel(rgb + 3 * x, x, y, formats[k], flags, want);
                    bad += n != format_bytes[k] || memcmp(out + x * n, want, (size_t)n) != 0;
                }
                CHECK(bad == 0, "format %d flags %d row %d: %d pixels differ", formats[k], flags, y, bad);
            }
}

/* Dithering keeps a colour's mean: over a 4x4 block of one byte value c the
 * levels average to c * top / 255 within 1/32 of a level (the 16 thresholds
 * round it to 1/16), well within half a level. */
TEST(dither_keeps_the_mean)
{
    uint8_t rgb[4 * 3], out[4 * 2];
    unsigned c;
    double worst = 0;
    for (c = 0; c < 256; c++) {
        double sum_r = 0, sum_g = 0, er, eg;
        int x, y;
        memset(rgb, (int)c, sizeof rgb);
        for (y = 0; y < 4; y++) {
            tgi_pixels_row(rgb, 4, y, TG_PIXEL_RGB565_BE, TG_PIXELS_DITHER, out);
            for (x = 0; x < 4; x++) {
                unsigned v = (unsigned)out[2 * x] << 8 | out[2 * x + 1];
                sum_r += v >> 11;
                sum_g += v >> 5 & 63;
            }
        }
        er = fabs(sum_r / 16 - c * 31.0 / 255);
        eg = fabs(sum_g / 16 - c * 63.0 / 255);
        CHECK(er <= 1.0 / 32 + 1e-12 && eg <= 1.0 / 32 + 1e-12, "c %u: mean off by %g (5 bits), %g (6 bits)", c, er, eg);
        if (er > worst) worst = er;
        if (eg > worst) worst = eg;
    }
    CHECK(worst > 0.03, "worst error %g: the bound above is not tight", worst); /* rounding to 1/16 does show */
}

/* Grey: every one of the 2^24 inputs against round(0.2126 R + 0.7152 G +
 * 0.0722 B); a grey byte stays itself. */
TEST(grey_every_input)
{
    static uint8_t rgb[256 * 3], out[256];
    int r, g, b, bad = 0;
    for (r = 0; r < 256; r++)
        for (g = 0; g < 256; g++) {
            for (b = 0; b < 256; b++) { rgb[3 * b] = (uint8_t)r; rgb[3 * b + 1] = (uint8_t)g; rgb[3 * b + 2] = (uint8_t)b; }
            tgi_pixels_row(rgb, 256, 0, TG_PIXEL_GREY8, 0, out);
            for (b = 0; b < 256; b++) bad += out[b] != ref_grey((unsigned)r, (unsigned)g, (unsigned)b);
        }
    CHECK(bad == 0, "%d inputs differ", bad);
    for (r = 0; r < 256; r++) memset(rgb + 3 * r, r, 3);
    tgi_pixels_row(rgb, 256, 0, TG_PIXEL_GREY8, 0, out);
    for (r = 0; r < 256; r++) CHECK(out[r] == r, "grey %d -> %d", r, out[r]);
}

/* Refused: NULL frame or buffer, unknown aov, format or flag, rows outside
 * the frame or reversed, a stride below a row.  Each is TG_ERR_INPUT and the
 * buffer (exactly one call's worth) is untouched; the same buffer with a
 * stride of exactly a row is written whole. */
TEST(bad_arguments_write_nothing)
{
    rendered r;
    size_t row = 7u * 2u, size;
    uint8_t *dst;
    tg_frame *f;
    if (!render(&r, 7, 3)) { CHECK(0, "render"); release(&r); return; }
    f = r.frame;
    dst = buffer(3, row, row, &size);
#define REFUSED(call) do { \
        CHECK((call) == TG_ERR_INPUT, "accepted: %s", #call); \
        CHECK(all_fill(dst, size), "wrote: %s", #call); } while (0)
    REFUSED(tg_frame_write_pixels(NULL, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, 0, NULL, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COUNT, 0, 3, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, (tg_aov)-1, 0, 3, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_FORMAT_COUNT, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, (tg_pixel_format)-1, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, 2, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, -1, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, -1, 2, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 1, 4, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 2, 1, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 4, 4, TG_PIXEL_RGB565, 0, dst, row));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, 0, dst, row - 1));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_XRGB8888, 0, dst, 7u * 4u - 1u));
    REFUSED(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 1, TG_PIXEL_GREY8, 0, dst, 0));
#undef REFUSED
    CHECK(tg_frame_write_pixels(f, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, TG_PIXELS_DITHER, dst, row) == TG_OK, "exact stride");
    check_rows(&r, TG_AOV_COLOR, 0, 3, TG_PIXEL_RGB565, TG_PIXELS_DITHER, dst, row, 2);
    free(dst);
    release(&r);
}

int main(void)
{
    RUN(every_format_matches_reference);
    RUN(row_ranges_and_splits);
    RUN(dither_pattern_exact);
    RUN(gradient_every_value_every_place);
    RUN(dither_keeps_the_mean);
    RUN(grey_every_input);
    RUN(bad_arguments_write_nothing);
    return check_summary();
}
