/* SPDX-License-Identifier: MIT */
/*
 * fbdev.h - show tinygi frames on a Linux framebuffer (/dev/fbN).
 *
 * tgp_fb_open() reads the device's variable and fixed screen info
 * (FBIOGET_VSCREENINFO / FBIOGET_FSCREENINFO), checks the pixel format and
 * maps the screen.  Rows of 8-bit RGB are converted to the device's pixel
 * format from its bitfield offsets and lengths - 16, 24 or 32 bits per
 * pixel, each of red/green/blue 1..8 bits, bits that hold no colour (alpha,
 * padding) written as ones, i.e. opaque - which covers XRGB8888, ARGB8888,
 * RGB565, BGR888, BGRX8888 and the other orders.  When the device's bytes
 * are those of one of the core's pixel formats (RGB565, BGR565, RGB888,
 * BGR888, XRGB8888, RGBA8888: tgp_fb_core_format), frames are written by
 * tg_frame_write_pixels straight into the screen, with the same bytes.  Rows
 * are line_length bytes apart and the visible area starts at (xoffset,
 * yoffset).
 *
 * ioctls do not work on regular files, so tests use tgp_fb_open_file() with
 * screen info the caller supplies (tgp_fb_info_format fills one in).
 *
 * Errors come back as a reason in fb->error (or the caller's buffer), fit
 * to show a person, without the device's path: the caller has the path and
 * names it, e.g. "/dev/fb0: error: No such file or directory" from the path
 * it passed (TGP_FB_DEFAULT_PATH for NULL) and fb->error.
 */
#ifndef TG_FBDEV_H
#define TG_FBDEV_H

#include <stddef.h>
#include <stdint.h>

#include "tinygi.h"

/* The device tgp_fb_open() and tgp_fbdev_view() use when given NULL. */
#define TGP_FB_DEFAULT_PATH "/dev/fb0"

typedef struct tgp_fb_channel {
    int offset, length; /* bit position from the least significant bit; 0 length: absent */
} tgp_fb_channel;

typedef struct tgp_fb_info {
    int xres, yres;          /* visible size in pixels */
    int xoffset, yoffset;    /* visible area's origin in the virtual screen */
    int bits_per_pixel;      /* 16, 24 or 32 */
    size_t line_length;      /* bytes from one line to the next */
    tgp_fb_channel red, green, blue, transp;
} tgp_fb_info;

/* Named layouts, written from the most significant bit of the pixel value
 * down (like DRM fourcc names): XRGB8888 is x:24-31 r:16-23 g:8-15 b:0-7.
 * Pixel values are stored in the machine's byte order, as fbdev does. */
typedef enum tgp_fb_format {
    TG_FB_XRGB8888, TG_FB_ARGB8888, TG_FB_XBGR8888, TG_FB_BGRX8888,
    TG_FB_RGB888, TG_FB_BGR888, TG_FB_RGB565, TG_FB_BGR565,
    TG_FB_FORMAT_COUNT
} tgp_fb_format;

typedef struct tgp_fb {
    tgp_fb_info info;
    unsigned char *screen;   /* first byte of the visible area */
    unsigned char *map;      /* the whole mapping */
    size_t map_size;
    int fd;
    int bytes_per_pixel;
    uint32_t lut[3][256];    /* 8-bit channel value -> its bits in the pixel */
    uint32_t opaque;         /* the bits of no colour channel, all ones */
    int pixel_format;        /* tgp_fb_core_format's, or -1: from the bitfields */
    char error[256];         /* why opening failed; never holds the path */
} tgp_fb;

/* The name of a format ("XRGB8888"), and screen info for it; line_length 0
 * means packed (xres * bytes per pixel).  Returns 0, or -1 if unknown. */
const char *tgp_fb_format_name(tgp_fb_format format);
int tgp_fb_info_format(tgp_fb_info *info, tgp_fb_format format, int xres, int yres, size_t line_length);

/* The core's tg_pixel_format that writes exactly the bytes this format
 * holds (the 5/6-bit channels rounded to nearest, the bits of no colour set),
 * or -1.  In the machine's byte order: on a little-endian machine RGB888
 * (red in bits 16-23) is the core's BGR888 and XBGR8888 its RGBA8888. */
int tgp_fb_core_format(const tgp_fb_info *info);

/* Check that tinygi can draw this format; 0, or -1 with a message. */
int tgp_fb_info_check(const tgp_fb_info *info, char *msg, size_t size);

/* Open and map the framebuffer device at `path` (NULL: TGP_FB_DEFAULT_PATH)
 * with ioctls; 0, or -1 with the reason in fb->error (the system's
 * strerror() text when opening the file fails; the path is not in it). */
int tgp_fb_open(tgp_fb *fb, const char *path);
/* Map a regular file as a framebuffer described by `info` (for tests): the
 * file must already hold (yoffset + yres) * line_length bytes.  0, or -1
 * with the reason in fb->error, as for tgp_fb_open(). */
int tgp_fb_open_file(tgp_fb *fb, const char *path, const tgp_fb_info *info);
void tgp_fb_close(tgp_fb *fb);

/* Convert n pixels of 8-bit RGB to the device format into `dst`. */
void tgp_fb_convert_row(const tgp_fb *fb, const uint8_t *rgb, int n, unsigned char *dst);
/* Draw n RGB pixels at (x, y) of the visible area, clipped to it. */
void tgp_fb_put_row(tgp_fb *fb, int x, int y, const uint8_t *rgb, int n);

/* Produces row y of an image as 8-bit RGB. */
typedef void (*tgp_fb_row_fn)(void *user, int y, uint8_t *rgb);
/* Draw a width x height image with its top-left at (x0, y0), clipped.
 * `rgb_row` is scratch for one row (width * 3 bytes). */
void tgp_fb_draw(tgp_fb *fb, int x0, int y0, int width, int height,
                tgp_fb_row_fn row, void *user, uint8_t *rgb_row);

/* What tgp_fbdev_view() and tgp_fb_view_frames() return. */
enum {
    TGP_FB_VIEW_OK = 0,
    TGP_FB_VIEW_FAILED = 1, /* `msg` is a whole message ("view: out of memory",
                               a render error) */
    TGP_FB_VIEW_DEVICE = 2  /* the device cannot be used: `msg` is the reason
                               only, as in tgp_fb.error; the caller adds the path */
};

/* Render `frames` frames of `frame` (tg_frame_render with index 0, 1, ...)
 * and show each, centred, on the framebuffer at `path` (NULL:
 * TGP_FB_DEFAULT_PATH) as soon as it is rendered.  Returns TGP_FB_VIEW_OK;
 * TGP_FB_VIEW_DEVICE with the reason in `msg` when the device cannot be used
 * (missing, not a framebuffer, unsupported format); or TGP_FB_VIEW_FAILED
 * with a message in `msg` when memory runs out or a frame fails to render. */
int tgp_fbdev_view(const char *path, tg_frame *frame, int width, int height,
                  int frames, char *msg, size_t size);
/* The same on an open framebuffer (tests use a file-backed one): returns
 * TGP_FB_VIEW_OK or TGP_FB_VIEW_FAILED. */
int tgp_fb_view_frames(tgp_fb *fb, tg_frame *frame, int width, int height,
                      int frames, char *msg, size_t size);

#endif
