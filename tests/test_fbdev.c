/* SPDX-License-Identifier: MIT */
/*
 * test_fbdev.c - the Linux framebuffer output (platform/fbdev) against
 * file-backed framebuffers: for every supported pixel format the bytes at
 * known pixels are the format's documented pixel values (written here by
 * hand, in the machine's byte order as fbdev stores them), padding beyond
 * the visible line is untouched, rows are line_length apart, the visible
 * offset is honoured, clipping holds, and unusable devices and formats are
 * clear errors.
 */
#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

#include "check.h"
#include "fbdev/fbdev.h"

#define FILL 0xEE
#define W 8
#define H 6

static const uint8_t colours[4][3] = {{255, 0, 0}, {10, 200, 77}, {255, 255, 255}, {0, 0, 0}};

/* Pixel values for the colours above, from the formats' definitions
 * (565: round(c * 31 / 255) etc.; alpha opaque). */
static const struct {
    tgp_fb_format format;
    int bytes;
    uint32_t value[4];
} expected[] = {
    {TG_FB_XRGB8888, 4, {0x00FF0000u, 0x000AC84Du, 0x00FFFFFFu, 0x00000000u}},
    {TG_FB_ARGB8888, 4, {0xFFFF0000u, 0xFF0AC84Du, 0xFFFFFFFFu, 0xFF000000u}},
    {TG_FB_XBGR8888, 4, {0x000000FFu, 0x004DC80Au, 0x00FFFFFFu, 0x00000000u}},
    {TG_FB_BGRX8888, 4, {0x0000FF00u, 0x4DC80A00u, 0xFFFFFF00u, 0x00000000u}},
    {TG_FB_RGB888, 3, {0xFF0000u, 0x0AC84Du, 0xFFFFFFu, 0x000000u}},
    {TG_FB_BGR888, 3, {0x0000FFu, 0x4DC80Au, 0xFFFFFFu, 0x000000u}},
    {TG_FB_RGB565, 2, {0xF800u, 0x0E29u, 0xFFFFu, 0x0000u}},
    {TG_FB_BGR565, 2, {0x001Fu, 0x4E21u, 0xFFFFu, 0x0000u}},
};

static int little_endian(void)
{
    const uint16_t one = 1;
    return *(const unsigned char *)&one == 1;
}

/* The pixel value as fbdev stores it: the machine's byte order. */
static void native_bytes(uint32_t v, int n, unsigned char *out)
{
    int i;
    for (i = 0; i < n; i++) {
        int shift = little_endian() ? 8 * i : 8 * (n - 1 - i);
        out[i] = (unsigned char)(v >> shift);
    }
}

/* A file of `size` FILL bytes; returns its path in `path`. */
static int make_file(char *path, size_t size)
{
    unsigned char *buf = malloc(size);
    int fd, ok;
    strcpy(path, "/tmp/tinygi-fbXXXXXX");
    fd = mkstemp(path);
    if (fd < 0 || !buf) { free(buf); return -1; }
    memset(buf, FILL, size);
    ok = write(fd, buf, size) == (ssize_t)size;
    close(fd);
    free(buf);
    return ok ? 0 : -1;
}

static unsigned char *read_file(const char *path, size_t size)
{
    unsigned char *buf = malloc(size);
    FILE *f = fopen(path, "rb");
    if (f && buf && fread(buf, 1, size, f) != size) { free(buf); buf = NULL; }
    if (f) fclose(f);
    return buf;
}

static int pixel_is(const unsigned char *mem, size_t at, uint32_t value, int bytes)
{
    unsigned char want[4];
    native_bytes(value, bytes, want);
    return memcmp(mem + at, want, (size_t)bytes) == 0;
}

static int untouched(const unsigned char *mem, size_t at, int bytes)
{
    int i;
    for (i = 0; i < bytes; i++)
        if (mem[at + (size_t)i] != FILL) return 0;
    return 1;
}

/* Every format: a row of the four colours at (2, 3), padded lines. */
TEST(formats_bytes_at_known_pixels)
{
    size_t k;
    for (k = 0; k < sizeof expected / sizeof expected[0]; k++) {
        tgp_fb_info info;
        tgp_fb fb;
        char path[64];
        int b = expected[k].bytes, i;
        size_t line = (size_t)W * (size_t)b + 12, size = line * H;
        uint8_t row[12];
        unsigned char *mem;
        const char *name = tgp_fb_format_name(expected[k].format);
        for (i = 0; i < 4; i++) memcpy(row + 3 * i, colours[i], 3);
        CHECK(tgp_fb_info_format(&info, expected[k].format, W, H, line) == 0, "%s", name);
        CHECK(info.bits_per_pixel == 8 * b, "%s: %d bpp", name, info.bits_per_pixel);
        if (make_file(path, size) != 0) { CHECK(0, "temp file"); return; }
        CHECK(tgp_fb_open_file(&fb, path, &info) == 0, "%s: %s", name, fb.error);
        tgp_fb_put_row(&fb, 2, 3, row, 4);
        tgp_fb_close(&fb);
        mem = read_file(path, size);
        unlink(path);
        if (!mem) { CHECK(0, "read back"); return; }
        for (i = 0; i < 4; i++)
            CHECK(pixel_is(mem, 3 * line + (size_t)(2 + i) * (size_t)b, expected[k].value[i], b),
                  "%s: colour %d at (%d, 3)", name, i, 2 + i);
        CHECK(untouched(mem, 3 * line + (size_t)b, b), "%s: pixel left of the row", name);
        CHECK(untouched(mem, 3 * line + 6u * (size_t)b, b), "%s: pixel right of the row", name);
        CHECK(untouched(mem, 2 * line + 2u * (size_t)b, b), "%s: row above", name);
        CHECK(untouched(mem, (size_t)W * (size_t)b, 12), "%s: line padding", name);
        free(mem);
    }
}

/* Clipping at all four edges, and the visible-area offset. */
TEST(clipping_and_offset)
{
    tgp_fb_info info;
    tgp_fb fb;
    char path[64];
    size_t line = 4u * (W + 2), size = line * (H + 1);
    uint8_t row[5 * 3];
    unsigned char *mem;
    int i;
    for (i = 0; i < 5; i++) { row[3 * i] = (uint8_t)(i + 1); row[3 * i + 1] = 0; row[3 * i + 2] = 0; }
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, line);
    info.xoffset = 1; /* the visible area starts one pixel in and one line down */
    info.yoffset = 1;
    if (make_file(path, size) != 0) { CHECK(0, "temp file"); return; }
    CHECK(tgp_fb_open_file(&fb, path, &info) == 0, "%s", fb.error);
    tgp_fb_put_row(&fb, -2, 0, row, 5);     /* pixels 3, 4, 5 land at x = 0..2 */
    tgp_fb_put_row(&fb, W - 2, H - 1, row, 5); /* pixels 1, 2 at x = W-2, W-1 */
    tgp_fb_put_row(&fb, 0, H, row, 5);      /* below the screen: nothing */
    tgp_fb_put_row(&fb, 0, -1, row, 5);     /* above: nothing */
    tgp_fb_put_row(&fb, W, 2, row, 5);      /* right of it: nothing */
    tgp_fb_close(&fb);
    mem = read_file(path, size);
    unlink(path);
    if (!mem) { CHECK(0, "read back"); return; }
    for (i = 0; i < 3; i++) CHECK(pixel_is(mem, line + 4u * (size_t)(1 + i), (uint32_t)(i + 3) << 16, 4), "clipped left %d", i);
    CHECK(untouched(mem, line, 4), "left of the visible area");
    CHECK(pixel_is(mem, (size_t)H * line + 4u * (W - 1), 1u << 16, 4), "clipped right 0");
    CHECK(pixel_is(mem, (size_t)H * line + 4u * W, 2u << 16, 4), "clipped right 1");
    CHECK(untouched(mem, (size_t)H * line + 4u * (W + 1), 4), "past the right edge");
    CHECK(untouched(mem, 0, (int)line), "line 0 (above the visible area)");
    CHECK(untouched(mem, 3 * line + 4u * (W + 1), 4), "right of the screen");
    free(mem);
}

static void gradient_row(void *user, int y, uint8_t *rgb)
{
    int x, w = *(const int *)user;
    for (x = 0; x < w; x++) {
        rgb[3 * x] = (uint8_t)(40 * x);
        rgb[3 * x + 1] = (uint8_t)(50 * y);
        rgb[3 * x + 2] = 7;
    }
}

/* tgp_fb_draw puts an image's rows where they belong, RGB565. */
TEST(draw_image_rows)
{
    tgp_fb_info info;
    tgp_fb fb;
    char path[64];
    size_t line = 2u * W, size = line * H;
    uint8_t scratch[4 * 3];
    unsigned char *mem;
    int w = 4, x, y;
    tgp_fb_info_format(&info, TG_FB_RGB565, W, H, 0);
    CHECK(info.line_length == line, "packed line %lu", (unsigned long)info.line_length);
    if (make_file(path, size) != 0) { CHECK(0, "temp file"); return; }
    CHECK(tgp_fb_open_file(&fb, path, &info) == 0, "%s", fb.error);
    tgp_fb_draw(&fb, 3, 2, w, 3, gradient_row, &w, scratch);
    tgp_fb_close(&fb);
    mem = read_file(path, size);
    unlink(path);
    if (!mem) { CHECK(0, "read back"); return; }
    for (y = 0; y < 3; y++)
        for (x = 0; x < w; x++) {
            uint32_t r5 = (uint32_t)((40 * x * 31 + 127) / 255), g6 = (uint32_t)((50 * y * 63 + 127) / 255);
            uint32_t b5 = (7 * 31 + 127) / 255;
            CHECK(pixel_is(mem, (size_t)(2 + y) * line + 2u * (size_t)(3 + x), r5 << 11 | g6 << 5 | b5, 2),
                  "pixel (%d, %d)", x, y);
        }
    CHECK(untouched(mem, 2 * line + 4, 2), "left of the image");
    CHECK(untouched(mem, 5 * line + 6, 2), "below the image");
    free(mem);
}

TEST(unsupported_formats_are_errors)
{
    tgp_fb_info info;
    char msg[256];
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0);
    CHECK(tgp_fb_info_check(&info, msg, sizeof msg) == 0, "%s", msg);
    info.bits_per_pixel = 8;
    CHECK(tgp_fb_info_check(&info, msg, sizeof msg) != 0, "8 bpp accepted");
    CHECK(strstr(msg, "8 bits per pixel") != NULL, "message: %s", msg);
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0);
    info.red.length = 10;
    CHECK(tgp_fb_info_check(&info, msg, sizeof msg) != 0, "10-bit red accepted");
    tgp_fb_info_format(&info, TG_FB_RGB565, W, H, 0);
    info.green.offset = 4; /* bits 4-9 overlap blue (0-4) */
    CHECK(tgp_fb_info_check(&info, msg, sizeof msg) != 0, "overlapping channels accepted");
    tgp_fb_info_format(&info, TG_FB_RGB565, W, H, 0);
    info.blue.offset = 12; /* 12 + 5 > 16 */
    CHECK(tgp_fb_info_check(&info, msg, sizeof msg) != 0, "channel past the pixel accepted");
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 4u * W - 1);
    CHECK(tgp_fb_info_check(&info, msg, sizeof msg) != 0, "short line accepted");
    CHECK(tgp_fb_info_format(&info, TG_FB_FORMAT_COUNT, W, H, 0) != 0, "unknown format");
}

TEST(unusable_devices_are_errors)
{
    tgp_fb fb;
    tgp_fb_info info;
    char path[64];
    CHECK(tgp_fb_open(&fb, "/nonexistent/fb9") != 0, "missing device opened");
    CHECK(strstr(fb.error, "/nonexistent/fb9") != NULL && strstr(fb.error, "No such file") != NULL,
          "message: %s", fb.error);
    if (make_file(path, 64) != 0) { CHECK(0, "temp file"); return; }
    CHECK(tgp_fb_open(&fb, path) != 0, "regular file taken for a framebuffer");
    CHECK(strstr(fb.error, "not a framebuffer") != NULL, "message: %s", fb.error);
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0); /* needs 192 bytes, the file has 64 */
    CHECK(tgp_fb_open_file(&fb, path, &info) != 0, "short file mapped");
    CHECK(strstr(fb.error, "needed") != NULL, "message: %s", fb.error);
    unlink(path);
}

/* tgp_fb_view_frames renders a built-in scene and shows it centred: the
 * screen holds exactly the frame's 8-bit colour rows, converted. */
TEST(view_shows_rendered_frame)
{
    enum { FW = 16, FH = 12, SW = 20, SH = 16 };
    const char *text = tg_builtin_scene("cornell");
    static unsigned char scene_mem[1 << 20];
    tg_arena arena;
    tg_scene *scene = NULL;
    tg_request req;
    tg_plan plan;
    tg_frame *frame = NULL;
    tg_error err;
    tgp_fb_info info;
    tgp_fb fb;
    void *frame_mem;
    char path[64], msg[256];
    unsigned char *mem;
    uint8_t rgb[FW * 3];
    int x, y, x0 = (SW - FW) / 2, y0 = (SH - FH) / 2;
    size_t line = 4u * SW;
    memset(&err, 0, sizeof err);
    CHECK(text != NULL, "no built-in cornell");
    if (!text) return;
    tg_arena_init(&arena, scene_mem, sizeof scene_mem);
    CHECK(tg_scene_parse(text, strlen(text), "cornell", NULL, &arena, &scene, &err) == TG_OK, "%s", err.message);
    tg_request_defaults(&req);
    req.width = FW;
    req.height = FH;
    req.shadow_map_size = 16;
    if (!scene || tg_plan_make(&plan, scene, &req, &err) != TG_OK) { CHECK(0, "plan: %s", err.message); return; }
    frame_mem = malloc(plan.total_bytes);
    if (!frame_mem || tg_frame_create(&plan, frame_mem, plan.total_bytes, &frame, &err) != TG_OK) {
        CHECK(0, "frame: %s", err.message);
        free(frame_mem);
        return;
    }
    tgp_fb_info_format(&info, TG_FB_XRGB8888, SW, SH, 0);
    if (make_file(path, line * SH) != 0) { CHECK(0, "temp file"); free(frame_mem); return; }
    CHECK(tgp_fb_open_file(&fb, path, &info) == 0, "%s", fb.error);
    CHECK(tgp_fb_view_frames(&fb, frame, FW, FH, 2, msg, sizeof msg) == 0, "%s", msg);
    tgp_fb_close(&fb);
    mem = read_file(path, line * SH);
    unlink(path);
    if (!mem) { CHECK(0, "read back"); free(frame_mem); return; }
    for (y = 0; y < FH; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, rgb); /* the last frame shown */
        for (x = 0; x < FW; x++) {
            uint32_t v = (uint32_t)rgb[3 * x] << 16 | (uint32_t)rgb[3 * x + 1] << 8 | rgb[3 * x + 2];
            CHECK(pixel_is(mem, (size_t)(y0 + y) * line + 4u * (size_t)(x0 + x), v, 4), "pixel (%d, %d)", x, y);
        }
    }
    CHECK(untouched(mem, (size_t)(y0 - 1) * line, (int)line), "line above the image");
    CHECK(untouched(mem, (size_t)y0 * line + 4u * (size_t)(x0 - 1), 4), "pixel left of the image");
    CHECK(untouched(mem, (size_t)(y0 + FH) * line, (int)line), "line below the image");
    free(mem);
    free(frame_mem);
}

int main(void)
{
    RUN(formats_bytes_at_known_pixels);
    RUN(clipping_and_offset);
    RUN(draw_image_rows);
    RUN(unsupported_formats_are_errors);
    RUN(unusable_devices_are_errors);
    RUN(view_shows_rendered_frame);
    return check_summary();
}
