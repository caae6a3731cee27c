/* SPDX-License-Identifier: MIT */
/*
 * test_fbdev.c - the Linux framebuffer output (platform/fbdev) against
 * file-backed framebuffers: for every supported pixel format the bytes at
 * known pixels are the format's documented pixel values (written here by
 * hand, in the machine's byte order as fbdev stores them), padding beyond
 * the visible line is untouched, rows are line_length apart, the visible
 * offset is honoured, clipping holds, and unusable devices and formats are
 * clear errors: the reason alone, never the device's path (the caller names
 * the device), and tgp_fbdev_view says which errors are the device's.  Devices whose bytes are one of the core's pixel formats
 * show frames through tg_frame_write_pixels: the same bytes as the
 * conversion from the bitfields, screen by screen.
 */
#include <errno.h>
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
 * (565: round(c * 31 / 255) etc.; bits of no colour, X or alpha, all ones). */
static const struct {
    tgp_fb_format format;
    int bytes;
    uint32_t value[4];
} expected[] = {
    {TG_FB_XRGB8888, 4, {0xFFFF0000u, 0xFF0AC84Du, 0xFFFFFFFFu, 0xFF000000u}},
    {TG_FB_ARGB8888, 4, {0xFFFF0000u, 0xFF0AC84Du, 0xFFFFFFFFu, 0xFF000000u}},
    {TG_FB_XBGR8888, 4, {0xFF0000FFu, 0xFF4DC80Au, 0xFFFFFFFFu, 0xFF000000u}},
    {TG_FB_BGRX8888, 4, {0x0000FFFFu, 0x4DC80AFFu, 0xFFFFFFFFu, 0x000000FFu}},
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
    for (i = 0; i < 3; i++)
        CHECK(pixel_is(mem, line + 4u * (size_t)(1 + i), 0xFF000000u | (uint32_t)(i + 3) << 16, 4), "clipped left %d", i);
    CHECK(untouched(mem, line, 4), "left of the visible area");
    CHECK(pixel_is(mem, (size_t)H * line + 4u * (W - 1), 0xFF000000u | 1u << 16, 4), "clipped right 0");
    CHECK(pixel_is(mem, (size_t)H * line + 4u * W, 0xFF000000u | 2u << 16, 4), "clipped right 1");
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

/* fb->error is the reason alone: the system's strerror() text when the
 * file cannot be opened, and never the path (nor its last part). */
TEST(unusable_devices_are_errors)
{
    tgp_fb fb;
    tgp_fb_info info;
    char path[64];
    const char *base;
    CHECK(tgp_fb_open(&fb, "/nonexistent/fb9") != 0, "missing device opened");
    CHECK(strcmp(fb.error, strerror(ENOENT)) == 0, "reason: '%s', not '%s'", fb.error, strerror(ENOENT));
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0);
    CHECK(tgp_fb_open_file(&fb, "/nonexistent/fb9", &info) != 0, "missing file mapped");
    CHECK(strcmp(fb.error, strerror(ENOENT)) == 0, "reason: '%s', not '%s'", fb.error, strerror(ENOENT));
    if (make_file(path, 64) != 0) { CHECK(0, "temp file"); return; }
    base = strrchr(path, '/') + 1;
    CHECK(tgp_fb_open(&fb, path) != 0, "regular file taken for a framebuffer");
    CHECK(strncmp(fb.error, "not a framebuffer (", 19) == 0 && !strstr(fb.error, base), "reason: %s", fb.error);
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0); /* needs 192 bytes, the file has 64 */
    CHECK(tgp_fb_open_file(&fb, path, &info) != 0, "short file mapped");
    CHECK(strcmp(fb.error, "64 bytes of screen memory, 192 needed for 8x6") == 0, "reason: %s", fb.error);
    info.bits_per_pixel = 8;
    CHECK(tgp_fb_open_file(&fb, path, &info) != 0, "8 bpp file mapped");
    CHECK(strncmp(fb.error, "unsupported pixel format: ", 26) == 0 && !strstr(fb.error, base),
          "reason: %s", fb.error);
    unlink(path);
}

static void frame_rows_color(void *user, int y, uint8_t *rgb)
{
    tg_frame_aov_row8((tg_frame *)user, TG_AOV_COLOR, y, rgb);
}

/* A rendered w x h frame of the built-in cornell (its memory in *mem). */
static tg_frame *cornell_frame(int w, int h, void **mem)
{
    const char *text = tg_builtin_scene("cornell");
    static unsigned char scene_mem[1 << 20];
    tg_arena arena;
    tg_scene *scene = NULL;
    tg_request req;
    tg_plan plan;
    tg_frame *frame = NULL;
    tg_error err;
    *mem = NULL;
    memset(&err, 0, sizeof err);
    tg_arena_init(&arena, scene_mem, sizeof scene_mem);
    if (!text || tg_scene_parse(text, strlen(text), "cornell", NULL, &arena, &scene, &err) != TG_OK) return NULL;
    tg_request_defaults(&req);
    req.width = w;
    req.height = h;
    req.shadow_map_size = 16;
    if (tg_plan_make(&plan, scene, &req, &err) != TG_OK) return NULL;
    *mem = malloc(plan.total_bytes);
    if (!*mem || tg_frame_create(&plan, *mem, plan.total_bytes, &frame, &err) != TG_OK) return NULL;
    return tg_frame_render(frame, 0, &err) == TG_OK ? frame : NULL;
}

/* tgp_fb_view_frames renders a built-in scene and shows it centred: the
 * screen holds exactly the frame's 8-bit colour rows, converted. */
TEST(view_shows_rendered_frame)
{
    enum { FW = 16, FH = 12, SW = 20, SH = 16 };
    tgp_fb_info info;
    tgp_fb fb;
    void *frame_mem;
    tg_frame *frame = cornell_frame(FW, FH, &frame_mem);
    char path[64], msg[256];
    unsigned char *mem;
    uint8_t rgb[FW * 3];
    int x, y, x0 = (SW - FW) / 2, y0 = (SH - FH) / 2;
    size_t line = 4u * SW;
    if (!frame) { CHECK(0, "cornell frame"); free(frame_mem); return; }
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
            uint32_t v = 0xFF000000u | (uint32_t)rgb[3 * x] << 16 | (uint32_t)rgb[3 * x + 1] << 8 | rgb[3 * x + 2];
            CHECK(pixel_is(mem, (size_t)(y0 + y) * line + 4u * (size_t)(x0 + x), v, 4), "pixel (%d, %d)", x, y);
        }
    }
    CHECK(untouched(mem, (size_t)(y0 - 1) * line, (int)line), "line above the image");
    CHECK(untouched(mem, (size_t)y0 * line + 4u * (size_t)(x0 - 1), 4), "pixel left of the image");
    CHECK(untouched(mem, (size_t)(y0 + FH) * line, (int)line), "line below the image");
    free(mem);
    free(frame_mem);
}

/* tgp_fbdev_view tells the device's errors (TGP_FB_VIEW_DEVICE, `msg` the
 * reason alone) from the others (TGP_FB_VIEW_FAILED, a whole message), so
 * the caller need not look for the path in the message: a path longer than
 * tgp_fb.error, whose "PATH: REASON" was cut short before, is no different. */
TEST(view_device_errors_are_the_reason)
{
    void *frame_mem;
    tg_frame *frame = cornell_frame(16, 12, &frame_mem);
    char path[600], msg[256];
    size_t n;
    tgp_fb fb;
    tgp_fb_info info;
    if (!frame) { CHECK(0, "cornell frame"); free(frame_mem); return; }
    CHECK(tgp_fbdev_view("/nonexistent/fb9", frame, 16, 12, 1, msg, sizeof msg) == TGP_FB_VIEW_DEVICE,
          "missing device: not a device error");
    CHECK(strcmp(msg, strerror(ENOENT)) == 0, "reason: '%s', not '%s'", msg, strerror(ENOENT));
    strcpy(path, "/nonexistent");
    for (n = strlen(path); n + 101 < sizeof path; n += 101) /* 5 parts of 100 bytes */
        snprintf(path + n, sizeof path - n, "/%0100d", 7);
    CHECK(strlen(path) > sizeof fb.error, "path of %lu bytes", (unsigned long)strlen(path));
    CHECK(tgp_fbdev_view(path, frame, 16, 12, 1, msg, sizeof msg) == TGP_FB_VIEW_DEVICE,
          "long missing path: not a device error");
    CHECK(strcmp(msg, strerror(ENOENT)) == 0, "reason: '%s', not '%s'", msg, strerror(ENOENT));
    /* not the device's: a whole message, TGP_FB_VIEW_FAILED */
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0);
    if (make_file(path, (size_t)4 * W * H) != 0) { CHECK(0, "temp file"); free(frame_mem); return; }
    CHECK(tgp_fb_open_file(&fb, path, &info) == 0, "%s", fb.error);
    CHECK(tgp_fb_view_frames(&fb, frame, 0, 12, 1, msg, sizeof msg) == TGP_FB_VIEW_FAILED, "bad size shown");
    CHECK(strcmp(msg, "view: bad image size 0x12") == 0, "message: %s", msg);
    CHECK(tgp_fb_view_frames(&fb, frame, 16, 12, 1, msg, sizeof msg) == TGP_FB_VIEW_OK, "%s", msg);
    tgp_fb_close(&fb);
    unlink(path);
    free(frame_mem);
}

/* Which named layouts are one of the core's formats, in this machine's
 * byte order (fbdev stores pixel values in it). */
TEST(core_format_of_each_layout)
{
    int le = little_endian();
    const int want[TG_FB_FORMAT_COUNT] = {
        TG_PIXEL_XRGB8888, TG_PIXEL_XRGB8888,      /* XRGB8888, ARGB8888 */
        le ? TG_PIXEL_RGBA8888 : -1, -1,           /* XBGR8888 (bytes R, G, B, X when little-endian), BGRX8888 */
        le ? TG_PIXEL_BGR888 : TG_PIXEL_RGB888,    /* RGB888: red is the high byte of the value */
        le ? TG_PIXEL_RGB888 : TG_PIXEL_BGR888,    /* BGR888 */
        TG_PIXEL_RGB565, TG_PIXEL_BGR565,
    };
    tgp_fb_info info;
    int k;
    for (k = 0; k < TG_FB_FORMAT_COUNT; k++) {
        tgp_fb_info_format(&info, (tgp_fb_format)k, W, H, 0);
        CHECK(tgp_fb_core_format(&info) == want[k], "%s: %d, not %d", tgp_fb_format_name((tgp_fb_format)k),
              tgp_fb_core_format(&info), want[k]);
    }
    tgp_fb_info_format(&info, TG_FB_RGB565, W, H, 0); /* RGB555 */
    info.red.offset = 10; info.green.length = 5;
    CHECK(tgp_fb_core_format(&info) == -1, "RGB555 taken for a core format");
    tgp_fb_info_format(&info, TG_FB_XRGB8888, W, H, 0); /* 7-bit red */
    info.red.length = 7;
    CHECK(tgp_fb_core_format(&info) == -1, "XRGB7888 taken for a core format");
}

/* A frame shown through the core's writer is, byte for byte, the frame's
 * rows converted from the bitfields: every named layout, on a screen larger
 * than the frame, one shorter (rows clipped: the core writes the visible
 * ones) and one narrower (converted from the bitfields, clipped), lines
 * padded by 4 bytes, the visible area offset by a pixel and a line. */
TEST(view_core_path_same_bytes_as_bitfields)
{
    enum { FW = 16, FH = 12 };
    static const int screens[3][2] = {{20, 16}, {18, 9}, {13, 15}};
    void *frame_mem;
    tg_frame *frame = cornell_frame(FW, FH, &frame_mem);
    uint8_t rgb[FW * 3];
    int k, s;
    if (!frame) { CHECK(0, "cornell frame"); free(frame_mem); return; }
    for (k = 0; k < TG_FB_FORMAT_COUNT; k++)
        for (s = 0; s < 3; s++) {
            const char *name = tgp_fb_format_name((tgp_fb_format)k);
            tgp_fb_info info;
            tgp_fb shown, converted;
            char path_a[64], path_b[64], msg[256];
            unsigned char *a, *b;
            size_t size;
            int sw = screens[s][0], sh = screens[s][1];
            tgp_fb_info_format(&info, (tgp_fb_format)k, sw, sh, 0);
            info.line_length += 4;
            info.xoffset = 1; /* the visible area starts one pixel in and one line down */
            info.yoffset = 1;
            info.line_length += (size_t)(info.bits_per_pixel / 8);
            size = info.line_length * (size_t)(sh + 2); /* a line above and below the visible area */
            if (make_file(path_a, size) != 0 || make_file(path_b, size) != 0) { CHECK(0, "temp file"); continue; }
            CHECK(tgp_fb_open_file(&shown, path_a, &info) == 0 && tgp_fb_open_file(&converted, path_b, &info) == 0,
                  "%s: %s", name, shown.error);
            CHECK(tgp_fb_view_frames(&shown, frame, FW, FH, 1, msg, sizeof msg) == 0, "%s", msg);
            converted.pixel_format = -1; /* the frame just shown, from the bitfields */
            tgp_fb_draw(&converted, (sw - FW) / 2, (sh - FH) / 2, FW, FH, frame_rows_color, frame, rgb);
            tgp_fb_close(&shown);
            tgp_fb_close(&converted);
            a = read_file(path_a, size);
            b = read_file(path_b, size);
            unlink(path_a);
            unlink(path_b);
            CHECK(a && b && memcmp(a, b, size) == 0, "%s on %dx%d: the core's bytes differ from the bitfields'", name, sw, sh);
            CHECK(a && untouched(a, 0, (int)info.line_length) && untouched(a, size - info.line_length, (int)info.line_length),
                  "%s on %dx%d: lines outside the visible area written", name, sw, sh);
            CHECK(a && !untouched(a, (size_t)(1 + sh / 2) * info.line_length + (size_t)(sw / 2) * (size_t)(info.bits_per_pixel / 8),
                                  info.bits_per_pixel / 8),
                  "%s on %dx%d: nothing shown", name, sw, sh);
            free(a);
            free(b);
        }
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
    RUN(view_device_errors_are_the_reason);
    RUN(core_format_of_each_layout);
    RUN(view_core_path_same_bytes_as_bitfields);
    return check_summary();
}
