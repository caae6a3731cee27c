/* SPDX-License-Identifier: MIT */
/*
 * fbdev.c - the Linux framebuffer output of fbdev.h: screen info, mapping,
 * the device's pixel format (one of the core's, written by
 * tg_frame_write_pixels, or converted here from its bitfields), and the
 * `view` loop that shows frames as they are rendered.  On systems without
 * <linux/fb.h> the device functions fail with a message; conversion still
 * works.
 */
#include "fbdev.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef __linux__
#include <fcntl.h>
#include <linux/fb.h>
#include <sys/ioctl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

/* ---- formats ---- */
typedef struct fb_layout {
    const char *name;
    int bpp;
    int r_off, r_len, g_off, g_len, b_off, b_len, a_off, a_len;
} fb_layout;

static const fb_layout fb_layouts[TG_FB_FORMAT_COUNT] = {
    {"XRGB8888", 32, 16, 8, 8, 8, 0, 8, 0, 0},
    {"ARGB8888", 32, 16, 8, 8, 8, 0, 8, 24, 8},
    {"XBGR8888", 32, 0, 8, 8, 8, 16, 8, 0, 0},
    {"BGRX8888", 32, 8, 8, 16, 8, 24, 8, 0, 0},
    {"RGB888", 24, 16, 8, 8, 8, 0, 8, 0, 0},
    {"BGR888", 24, 0, 8, 8, 8, 16, 8, 0, 0},
    {"RGB565", 16, 11, 5, 5, 6, 0, 5, 0, 0},
    {"BGR565", 16, 0, 5, 5, 6, 11, 5, 0, 0},
};

const char *tgp_fb_format_name(tgp_fb_format format)
{
    return (unsigned)format < TG_FB_FORMAT_COUNT ? fb_layouts[format].name : NULL;
}

int tgp_fb_info_format(tgp_fb_info *info, tgp_fb_format format, int xres, int yres, size_t line_length)
{
    const fb_layout *l;
    if ((unsigned)format >= TG_FB_FORMAT_COUNT) return -1;
    l = &fb_layouts[format];
    memset(info, 0, sizeof *info);
    info->xres = xres;
    info->yres = yres;
    info->bits_per_pixel = l->bpp;
    info->line_length = line_length ? line_length : (size_t)xres * (size_t)(l->bpp / 8);
    info->red.offset = l->r_off;   info->red.length = l->r_len;
    info->green.offset = l->g_off; info->green.length = l->g_len;
    info->blue.offset = l->b_off;  info->blue.length = l->b_len;
    info->transp.offset = l->a_off; info->transp.length = l->a_len;
    return 0;
}

static int channel_ok(tgp_fb_channel c, int bpp, int optional)
{
    if (c.length == 0) return optional;
    return c.length >= 1 && c.length <= 8 && c.offset >= 0 && c.offset + c.length <= bpp;
}

static uint32_t channel_mask(tgp_fb_channel c)
{
    return c.length ? (((uint32_t)1 << c.length) - 1u) << c.offset : 0;
}

int tgp_fb_info_check(const tgp_fb_info *info, char *msg, size_t size)
{
    int bpp = info->bits_per_pixel;
    uint32_t r = channel_mask(info->red), g = channel_mask(info->green), b = channel_mask(info->blue);
    if (bpp != 16 && bpp != 24 && bpp != 32) {
        snprintf(msg, size, "unsupported pixel format: %d bits per pixel (tinygi draws 16, 24 or 32)", bpp);
        return -1;
    }
    if (!channel_ok(info->red, bpp, 0) || !channel_ok(info->green, bpp, 0) ||
        !channel_ok(info->blue, bpp, 0) || !channel_ok(info->transp, bpp, 1) ||
        (r & g) || (r & b) || (g & b) || ((r | g | b) & channel_mask(info->transp))) {
        snprintf(msg, size, "unsupported pixel format: %d bpp with red %d/%d green %d/%d blue %d/%d "
                 "alpha %d/%d (offset/length; each colour 1-8 bits, no overlap)", bpp,
                 info->red.offset, info->red.length, info->green.offset, info->green.length,
                 info->blue.offset, info->blue.length, info->transp.offset, info->transp.length);
        return -1;
    }
    if (info->xres <= 0 || info->yres <= 0 || info->xoffset < 0 || info->yoffset < 0 ||
        info->line_length < (size_t)(info->xoffset + info->xres) * (size_t)(bpp / 8)) {
        snprintf(msg, size, "unsupported screen: %dx%d at +%d+%d with %lu bytes per line",
                 info->xres, info->yres, info->xoffset, info->yoffset, (unsigned long)info->line_length);
        return -1;
    }
    return 0;
}

static int host_is_little_endian(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b == 1;
}

/* Byte of an 8-bit channel within a pixel of n bytes stored in the
 * machine's order; -1 if the channel is not a whole byte. */
static int channel_byte(tgp_fb_channel c, int n)
{
    if (c.length != 8 || c.offset % 8 != 0) return -1;
    return host_is_little_endian() ? c.offset / 8 : n - 1 - c.offset / 8;
}

static int channel_is(tgp_fb_channel c, int offset, int length)
{
    return c.offset == offset && c.length == length;
}

/* The core's pixel format (tinygi.h) whose bytes are this device's, with
 * every bit that holds no colour set; -1 if none is. */
int tgp_fb_core_format(const tgp_fb_info *info)
{
    static const struct { tg_pixel_format format; int bytes; signed char r, g, b; } bytewise[] = {
        {TG_PIXEL_RGB888, 3, 0, 1, 2}, {TG_PIXEL_BGR888, 3, 2, 1, 0}, {TG_PIXEL_RGBA8888, 4, 0, 1, 2},
    };
    tgp_fb_channel xrgb_r = {16, 8}, xrgb_g = {8, 8}, xrgb_b = {0, 8};
    int n = info->bits_per_pixel / 8, r = channel_byte(info->red, n), g = channel_byte(info->green, n);
    int b = channel_byte(info->blue, n);
    size_t k;
    if (n == 2 && channel_is(info->green, 5, 6) && info->transp.length == 0) {
        if (channel_is(info->red, 11, 5) && channel_is(info->blue, 0, 5)) return TG_PIXEL_RGB565;
        if (channel_is(info->red, 0, 5) && channel_is(info->blue, 11, 5)) return TG_PIXEL_BGR565;
    }
    if (r < 0 || g < 0 || b < 0) return -1;
    if (n == 4 && r == channel_byte(xrgb_r, 4) && g == channel_byte(xrgb_g, 4) && b == channel_byte(xrgb_b, 4))
        return TG_PIXEL_XRGB8888;
    for (k = 0; k < sizeof bytewise / sizeof bytewise[0]; k++)
        if (n == bytewise[k].bytes && r == bytewise[k].r && g == bytewise[k].g && b == bytewise[k].b)
            return bytewise[k].format;
    return -1;
}

/* Nearest value of an n-bit channel for an 8-bit one: round(c * (2^n - 1) / 255). */
static void build_lut(uint32_t *lut, tgp_fb_channel c)
{
    uint32_t top = ((uint32_t)1 << c.length) - 1u, v;
    for (v = 0; v < 256; v++) lut[v] = ((v * top + 127u) / 255u) << c.offset;
}

/* Check `info`, fill the lookup tables; the mapping is set by the caller. */
static int fb_setup(tgp_fb *fb, const tgp_fb_info *info)
{
    fb->info = *info;
    if (tgp_fb_info_check(info, fb->error, sizeof fb->error) != 0) return -1;
    fb->bytes_per_pixel = info->bits_per_pixel / 8;
    build_lut(fb->lut[0], info->red);
    build_lut(fb->lut[1], info->green);
    build_lut(fb->lut[2], info->blue);
    fb->opaque = (info->bits_per_pixel == 32 ? 0xFFFFFFFFu : ((uint32_t)1 << info->bits_per_pixel) - 1u) &
                 ~(channel_mask(info->red) | channel_mask(info->green) | channel_mask(info->blue));
    fb->pixel_format = tgp_fb_core_format(info);
    return 0;
}

void tgp_fb_convert_row(const tgp_fb *fb, const uint8_t *rgb, int n, unsigned char *dst)
{
    int i, le = host_is_little_endian();
    for (i = 0; i < n; i++, rgb += 3, dst += fb->bytes_per_pixel) {
        uint32_t px = fb->lut[0][rgb[0]] | fb->lut[1][rgb[1]] | fb->lut[2][rgb[2]] | fb->opaque;
        if (fb->bytes_per_pixel == 4) {
            memcpy(dst, &px, 4); /* native byte order, like the kernel's */
        } else if (fb->bytes_per_pixel == 2) {
            uint16_t p16 = (uint16_t)px;
            memcpy(dst, &p16, 2);
        } else if (le) {
            dst[0] = (unsigned char)px; dst[1] = (unsigned char)(px >> 8); dst[2] = (unsigned char)(px >> 16);
        } else {
            dst[0] = (unsigned char)(px >> 16); dst[1] = (unsigned char)(px >> 8); dst[2] = (unsigned char)px;
        }
    }
}

void tgp_fb_put_row(tgp_fb *fb, int x, int y, const uint8_t *rgb, int n)
{
    unsigned char *dst;
    if (!fb->screen || y < 0 || y >= fb->info.yres || x >= fb->info.xres) return;
    if (x < 0) {
        if (n <= -x) return;
        rgb += 3 * (size_t)(-x);
        n += x;
        x = 0;
    }
    if (n > fb->info.xres - x) n = fb->info.xres - x;
    if (n <= 0) return;
    dst = fb->screen + (size_t)y * fb->info.line_length + (size_t)x * (size_t)fb->bytes_per_pixel;
    tgp_fb_convert_row(fb, rgb, n, dst);
}

void tgp_fb_draw(tgp_fb *fb, int x0, int y0, int width, int height,
                tgp_fb_row_fn row, void *user, uint8_t *rgb_row)
{
    int y;
    for (y = 0; y < height; y++) {
        if (y0 + y < 0 || y0 + y >= fb->info.yres) continue;
        row(user, y, rgb_row);
        tgp_fb_put_row(fb, x0, y0 + y, rgb_row, width);
    }
}

/* ---- devices and files ---- */
static void fb_clear(tgp_fb *fb)
{
    memset(fb, 0, sizeof *fb);
    fb->fd = -1;
}

void tgp_fb_close(tgp_fb *fb)
{
#ifdef __linux__
    if (fb->map) munmap(fb->map, fb->map_size);
    if (fb->fd >= 0) close(fb->fd);
#endif
    fb->map = NULL;
    fb->screen = NULL;
    fb->fd = -1;
}

#ifdef __linux__
static int fb_map(tgp_fb *fb, size_t size)
{
    size_t need = (size_t)(fb->info.yoffset + fb->info.yres) * fb->info.line_length;
    void *m;
    if (size < need) {
        snprintf(fb->error, sizeof fb->error, "%lu bytes of screen memory, %lu needed for %dx%d",
                 (unsigned long)size, (unsigned long)need, fb->info.xres, fb->info.yres);
        return -1;
    }
    m = mmap(NULL, size, PROT_READ | PROT_WRITE, MAP_SHARED, fb->fd, 0);
    if (m == MAP_FAILED) {
        snprintf(fb->error, sizeof fb->error, "cannot map the screen: %s", strerror(errno));
        return -1;
    }
    fb->map = m;
    fb->map_size = size;
    fb->screen = fb->map + (size_t)fb->info.yoffset * fb->info.line_length +
                 (size_t)fb->info.xoffset * (size_t)fb->bytes_per_pixel;
    return 0;
}

static int fb_fail(tgp_fb *fb)
{
    char keep[sizeof fb->error];
    memcpy(keep, fb->error, sizeof keep);
    tgp_fb_close(fb);
    memcpy(fb->error, keep, sizeof keep);
    return -1;
}

static void fb_info_from_linux(tgp_fb_info *info, const struct fb_var_screeninfo *var,
                               const struct fb_fix_screeninfo *fix)
{
    memset(info, 0, sizeof *info);
    info->xres = (int)var->xres;
    info->yres = (int)var->yres;
    info->xoffset = (int)var->xoffset;
    info->yoffset = (int)var->yoffset;
    info->bits_per_pixel = (int)var->bits_per_pixel;
    info->line_length = fix->line_length;
    info->red.offset = (int)var->red.offset;       info->red.length = (int)var->red.length;
    info->green.offset = (int)var->green.offset;   info->green.length = (int)var->green.length;
    info->blue.offset = (int)var->blue.offset;     info->blue.length = (int)var->blue.length;
    info->transp.offset = (int)var->transp.offset; info->transp.length = (int)var->transp.length;
}

int tgp_fb_open(tgp_fb *fb, const char *path)
{
    struct fb_var_screeninfo var;
    struct fb_fix_screeninfo fix;
    tgp_fb_info info;
    fb_clear(fb);
    if (!path) path = TGP_FB_DEFAULT_PATH;
    fb->fd = open(path, O_RDWR);
    if (fb->fd < 0) {
        snprintf(fb->error, sizeof fb->error, "%s", strerror(errno));
        return -1;
    }
    if (ioctl(fb->fd, FBIOGET_VSCREENINFO, &var) != 0 || ioctl(fb->fd, FBIOGET_FSCREENINFO, &fix) != 0) {
        snprintf(fb->error, sizeof fb->error, "not a framebuffer (screen info ioctl failed: %s)",
                 strerror(errno));
        return fb_fail(fb);
    }
    if (fix.type != FB_TYPE_PACKED_PIXELS || fix.visual != FB_VISUAL_TRUECOLOR ||
        var.red.msb_right || var.green.msb_right || var.blue.msb_right) {
        snprintf(fb->error, sizeof fb->error, "unsupported framebuffer (type %u, visual %u; "
                 "tinygi draws packed true-colour pixels)", fix.type, fix.visual);
        return fb_fail(fb);
    }
    fb_info_from_linux(&info, &var, &fix);
    if (fb_setup(fb, &info) != 0) return fb_fail(fb);
    if (fb_map(fb, fix.smem_len ? (size_t)fix.smem_len
                                      : (size_t)var.yres_virtual * fix.line_length) != 0)
        return fb_fail(fb);
    return 0;
}

int tgp_fb_open_file(tgp_fb *fb, const char *path, const tgp_fb_info *info)
{
    struct stat st;
    fb_clear(fb);
    if (fb_setup(fb, info) != 0) return -1;
    fb->fd = open(path, O_RDWR);
    if (fb->fd < 0) {
        snprintf(fb->error, sizeof fb->error, "%s", strerror(errno));
        return -1;
    }
    if (fstat(fb->fd, &st) != 0 || st.st_size <= 0) {
        snprintf(fb->error, sizeof fb->error, "empty or unreadable file");
        return fb_fail(fb);
    }
    if (fb_map(fb, (size_t)st.st_size) != 0) return fb_fail(fb);
    return 0;
}
#else
int tgp_fb_open(tgp_fb *fb, const char *path)
{
    (void)path;
    fb_clear(fb);
    snprintf(fb->error, sizeof fb->error, "the Linux framebuffer is not available on this system");
    return -1;
}

int tgp_fb_open_file(tgp_fb *fb, const char *path, const tgp_fb_info *info)
{
    (void)info;
    return tgp_fb_open(fb, path);
}
#endif

/* ---- view: render and show ---- */
typedef struct frame_rows {
    tg_frame *frame;
} frame_rows;

static void frame_row8(void *user, int y, uint8_t *rgb)
{
    tg_frame_aov_row8(((frame_rows *)user)->frame, TG_AOV_COLOR, y, rgb);
}

/* The frame's colour, centred: written by the core straight into the screen
 * when the device's format is one of the core's and the rows fit across it
 * (the rows below or above the screen are left out), else a row at a time
 * through `rgb` (width * 3 bytes), converted from the bitfields and clipped. */
static int show_frame(tgp_fb *fb, tg_frame *frame, int width, int height, uint8_t *rgb)
{
    int x0 = (fb->info.xres - width) / 2, y0 = (fb->info.yres - height) / 2;
    frame_rows rows;
    if (fb->pixel_format >= 0 && width <= fb->info.xres) {
        int first = y0 < 0 ? -y0 : 0, end = fb->info.yres - y0 < height ? fb->info.yres - y0 : height;
        size_t line = fb->info.line_length;
        unsigned char *at = fb->screen + (size_t)(y0 + first) * line + (size_t)x0 * (size_t)fb->bytes_per_pixel;
        return tg_frame_write_pixels(frame, TG_AOV_COLOR, first, end, (tg_pixel_format)fb->pixel_format, 0,
                                     at, line) == TG_OK ? 0 : -1;
    }
    rows.frame = frame;
    tgp_fb_draw(fb, x0, y0, width, height, frame_row8, &rows, rgb);
    return 0;
}

int tgp_fb_view_frames(tgp_fb *fb, tg_frame *frame, int width, int height,
                      int frames, char *msg, size_t size)
{
    uint8_t *rgb;
    tg_error err;
    int i;
    if (width <= 0 || height <= 0) {
        snprintf(msg, size, "view: bad image size %dx%d", width, height);
        return TGP_FB_VIEW_FAILED;
    }
    rgb = malloc((size_t)width * 3u);
    if (!rgb) {
        snprintf(msg, size, "view: out of memory");
        return TGP_FB_VIEW_FAILED;
    }
    memset(&err, 0, sizeof err);
    for (i = 0; i < frames; i++) {
        tg_status s = tg_frame_render(frame, i, &err);
        if (s != TG_OK) {
            tg_error_format(&err, msg, size);
            free(rgb);
            return TGP_FB_VIEW_FAILED;
        }
        if (show_frame(fb, frame, width, height, rgb) != 0) {
            snprintf(msg, size, "view: a %dx%d frame's rows cannot be written to the screen", width, height);
            free(rgb);
            return TGP_FB_VIEW_FAILED;
        }
    }
    free(rgb);
    return TGP_FB_VIEW_OK;
}

int tgp_fbdev_view(const char *path, tg_frame *frame, int width, int height,
                  int frames, char *msg, size_t size)
{
    tgp_fb fb;
    int r;
    if (tgp_fb_open(&fb, path) != 0) {
        snprintf(msg, size, "%s", fb.error);
        return TGP_FB_VIEW_DEVICE;
    }
    r = tgp_fb_view_frames(&fb, frame, width, height, frames, msg, size);
    tgp_fb_close(&fb);
    return r;
}
