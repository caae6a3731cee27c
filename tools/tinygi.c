/* SPDX-License-Identifier: MIT */
/*
 * tinygi.c - the command line: render a scene to PPM/PFM files, compare two
 * images, list what is built in.
 *
 *   tinygi render SCENE [options]     SCENE is a file or builtin:NAME
 *   tinygi view SCENE [options] [--fbdev PATH]   show frames on a framebuffer
 *   tinygi diff A B [--tolerance T] [-o DIFF.ppm]
 *   tinygi list
 *
 * Exit status: 0 success (diff: within tolerance); 1 runtime failure (cannot
 * write, out of memory; diff: outside tolerance); 2 bad usage or bad input
 * (diff: unreadable or mismatched images).  On status 2 nothing is written:
 * everything is validated before the first byte goes out, and every file is
 * written through a temporary and renamed (platform/hosted/file.h).
 *
 * The memory story: the scene is parsed into one malloc'd arena (grown and
 * retried on TG_ERR_MEMORY), the frame plan says how many bytes a frame
 * needs, and one malloc of that size is all the core gets.
 */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "tinygi.h"
#include "hosted/clock.h"
#include "hosted/file.h"
#include "hosted/image.h"
#include "hosted/imgdiff.h"
#include "fbdev/fbdev.h"

/* Limits of the command line (also in --help and the README). */
#define CLI_MAX_SIDE TG_IMG_MAX_SIDE        /* 16384 pixels per side */
#define CLI_MAX_PIXELS ((long)1 << 24)      /* 16,777,216 pixels per frame */
#define CLI_MAX_FRAMES 100000
#define CLI_MAX_PATH 4096
#define CLI_MAX_SCENE_ARENA ((size_t)1 << 31) /* 2 GiB for a parsed scene */

#define EXIT_RUNTIME 1
#define EXIT_INPUT 2

#if TG_FIXED
#define NUMBER_DESCRIPTION "Q16.16 fixed point"
#else
#define NUMBER_DESCRIPTION "float"
#endif

/* ---- messages ---- */

static void usage_error(const char *fmt, ...)
{
    va_list ap;
    fputs("tinygi: error: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

static void file_error(const char *path, const char *what)
{
    fprintf(stderr, "%s: error: %s\n", path, what);
}

static void core_error(const tg_error *err)
{
    char line[1024];
    tg_error_format(err, line, sizeof line);
    fprintf(stderr, "%s%s\n", err->file[0] ? "" : "tinygi: ", line);
}

static int exit_for(tg_status s)
{
    return s == TG_ERR_INPUT ? EXIT_INPUT : EXIT_RUNTIME;
}

static void print_help(FILE *out)
{
    fprintf(out,
        "usage: tinygi render SCENE [options]  render SCENE (a file or builtin:NAME) to files\n"
        "       tinygi view SCENE [options]    show the frames on a Linux framebuffer\n"
        "       tinygi diff A B [--tolerance T] [-o DIFF.ppm]   compare two images\n"
        "       tinygi list                    built-in scenes, AOVs, techniques\n"
        "       tinygi --help | --version\n"
        "\n"
        "render and view options:\n"
        "  -o PATH           render: output file (default out.ppm); .ppm is 8 bits per\n"
        "                    channel for viewing (colour exposed, tonemapped, sRGB),\n"
        "                    .pfm linear floats (Pf for 1-channel AOVs, PF for RGB);\n"
        "                    %%d or %%04d in PATH numbers frames from 0 (%%%% is a '%%');\n"
        "                    without it only the last frame is written\n"
        "  --size WxH        image size (default 320x240; sides 1..%d, at most %ld pixels)\n"
        "  --frames N        frames to render, 1..%d (default 1)\n"
        "  --aov NAME        output: color depth normal albedo ao bent cone near far\n"
        "                    direct irradiance motion (default color)\n"
        "  --technique NAME  hbil gtao hbao ssao vo ssdo bentcone reference (default hbil)\n"
        "  --slices N        horizon slices per pixel, 1..8\n"
        "  --samples N       samples per slice, 1..256\n"
        "  --radius R        gather radius in world units, 0..10000\n"
        "  --bounces N       light bounces, 0..100\n"
        "  --exposure E      linear exposure before the tonemapper, 0..1000 (default 1)\n"
        "  --shadow-size N   shadow map texels per side, 8..8192 (default 512)\n"
        "  --no-interleave   full-resolution GI kernel instead of 4x4 interleaved\n"
        "  --no-temporal     no temporal accumulation\n"
        "  --pcf-bilinear    4-tap shadow-map filtering instead of the 16-tap tent\n"
        "  --gi-quarter      GI kernel on a quarter of the pixels (half width and height,\n"
        "                    then a joint bilateral upsample): about 3x faster\n"
        "  --far-f0          far field as E0(bent) F0(AO) (HBIL sec. 2.2.3) instead of\n"
        "                    the SH9 cosine lobe restricted to the bent cone (sec. 2.2.4)\n"
        "  --explain         print the frame plan and exit without rendering\n"
        "  --quiet           no progress and no summary on stderr\n"
        "  --fbdev PATH      view: the framebuffer device (default /dev/fb0)\n"
        "  (GI settings not given come from the scene's gi line, then the defaults)\n"
        "\n"
        "diff: compares two PPM or two PFM images of the same size; prints RMSE,\n"
        "  PSNR (peak 255 for PPM, 1.0 for PFM) and the largest per-channel\n"
        "  difference and where it is.  T (default 0) is the largest per-channel\n"
        "  difference accepted, in the images' units: 0..255 for PPM, linear for\n"
        "  PFM.  -o writes the absolute difference scaled so the largest is white.\n"
        "\n"
        "exit status: 0 success (diff: within tolerance); 1 runtime failure\n"
        "  (diff: outside tolerance); 2 bad usage or bad input, nothing written\n"
        "  (diff: unreadable or mismatched images, or DIFF.ppm not written)\n",
        CLI_MAX_SIDE, CLI_MAX_PIXELS, CLI_MAX_FRAMES);
}

/* ---- option values ---- */

static int parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    long v;
    if (!*s || !((*s >= '0' && *s <= '9') || *s == '-')) return 1;
    errno = 0;
    v = strtol(s, &end, 10);
    if (errno || *end || v < lo || v > hi) return 1;
    *out = v;
    return 0;
}

static int parse_number(const char *s, double lo, double hi, double *out)
{
    char *end;
    double v;
    if (!*s || !((*s >= '0' && *s <= '9') || *s == '-' || *s == '+' || *s == '.')) return 1;
    errno = 0;
    v = strtod(s, &end);
    if (errno || *end || !(v >= lo && v <= hi)) return 1; /* also refuses NaN */
    *out = v;
    return 0;
}

static int parse_size(const char *s, int *w, int *h)
{
    char buf[64];
    const char *x = strchr(s, 'x');
    long lw, lh;
    size_t n;
    if (!x) x = strchr(s, 'X');
    if (!x || (n = (size_t)(x - s)) >= sizeof buf) return 1;
    memcpy(buf, s, n);
    buf[n] = '\0';
    if (parse_long(buf, 1, CLI_MAX_SIDE, &lw) || parse_long(x + 1, 1, CLI_MAX_SIDE, &lh)) return 1;
    if (lw * lh > CLI_MAX_PIXELS) return 1; /* both <= 16384: the product fits a long */
    *w = (int)lw;
    *h = (int)lh;
    return 0;
}

/* ---- output paths: "%d" / "%04d" number the frames ---- */

typedef struct out_pattern {
    char prefix[CLI_MAX_PATH], suffix[CLI_MAX_PATH];
    int numbered, width, zero;
} out_pattern;

static int copy_piece(char *dst, const char *s, size_t n)
{
    size_t i, k = 0;
    for (i = 0; i < n; i++) {
        if (s[i] == '%') i++; /* "%%": the checker made sure it is one */
        if (k + 1 >= CLI_MAX_PATH) return 1;
        dst[k++] = s[i];
    }
    dst[k] = '\0';
    return 0;
}

/* Split PATH at its one frame-number spec; 0 ok, else 1 with *why set. */
static int parse_pattern(const char *path, out_pattern *p, const char **why)
{
    const char *s = path, *spec = NULL, *spec_end = NULL;
    memset(p, 0, sizeof *p);
    if (strlen(path) >= CLI_MAX_PATH) { *why = "path too long"; return 1; }
    while (*s) {
        const char *q;
        if (*s != '%') { s++; continue; }
        if (s[1] == '%') { s += 2; continue; }
        q = s + 1;
        if (*q == '0') { p->zero = 1; q++; }
        if (*q >= '1' && *q <= '9') p->width = *q++ - '0';
        if (*q != 'd' || (p->zero && !p->width)) {
            *why = "a '%' must start %d, %0Nd (N 1..9) or %%";
            return 1;
        }
        if (spec) { *why = "more than one frame number (%d)"; return 1; }
        spec = s;
        spec_end = q + 1;
        s = spec_end;
    }
    if (!spec) return copy_piece(p->prefix, path, strlen(path)) ? (*why = "path too long", 1) : 0;
    p->numbered = 1;
    if (copy_piece(p->prefix, path, (size_t)(spec - path)) ||
        copy_piece(p->suffix, spec_end, strlen(spec_end))) {
        *why = "path too long";
        return 1;
    }
    return 0;
}

/* The file name of one frame; prefix + suffix < CLI_MAX_PATH (parse_pattern),
 * so out needs CLI_MAX_PATH + 16 bytes. */
static void pattern_path(const out_pattern *p, int frame, char *out)
{
    char number[16] = "";
    size_t a = strlen(p->prefix), b, c = strlen(p->suffix);
    if (p->numbered) snprintf(number, sizeof number, p->zero ? "%0*d" : "%*d", p->width, frame);
    b = strlen(number);
    memcpy(out, p->prefix, a);
    memcpy(out + a, number, b);
    memcpy(out + a + b, p->suffix, c + 1);
}

/* ---- render ---- */

typedef struct render_opts {
    int view;               /* tinygi view: to a framebuffer, no files */
    const char *fbdev;      /* view: device path (NULL: /dev/fb0) */
    const char *scene;
    const char *output;
    int width, height, frames, aov, technique;
    long slices, samples, bounces, shadow_size;
    double radius, exposure;
    int have_radius, have_exposure;
    int interleave, temporal, far_f0, gi_quarter, pcf_bilinear, explain, quiet;
} render_opts;

/* "--name=value" or "--name value": the value, or NULL (and the index moved). */
static const char *option_value(int argc, char **argv, int *i, const char *name, int *matched)
{
    const char *a = argv[*i];
    size_t n = strlen(name);
    *matched = 0;
    if (strncmp(a, name, n) != 0) return NULL;
    if (a[n] == '=') { *matched = 1; return a + n + 1; }
    if (a[n] != '\0') return NULL;
    *matched = 1;
    if (*i + 1 >= argc) return NULL;
    return argv[++*i];
}

static void list_names(FILE *out, const char *(*name_of)(int), int count, const char *sep)
{
    int i;
    for (i = 0; i < count; i++) {
        const char *n = name_of(i);
        if (!n) break;
        fprintf(out, "%s%s", i ? sep : "", n);
    }
}

/* The names joined by ", " into buf (for one-line messages). */
static const char *join_names(char *buf, size_t size, const char *(*name_of)(int), int count)
{
    size_t at = 0;
    int i;
    buf[0] = '\0';
    for (i = 0; i < count && at < size; i++) {
        const char *n = name_of(i);
        int w;
        if (!n) break;
        w = snprintf(buf + at, size - at, "%s%s", i ? ", " : "", n);
        if (w < 0) break;
        at += (size_t)w;
    }
    return buf;
}

static const char *aov_name_i(int i) { return tg_aov_name((tg_aov)i); }
static const char *technique_name_i(int i) { return tg_technique_name((tg_technique)i); }
static const char *builtin_name_i(int i) { return tg_builtin_name(i); }

/* Parse one render option at argv[*i]; 0 ok, 1 usage error (reported). */
static int render_option(int argc, char **argv, int *i, render_opts *o)
{
    static const char *const names[] = {
        "-o", "--size", "--frames", "--aov", "--technique", "--slices", "--samples",
        "--radius", "--bounces", "--exposure", "--shadow-size", "--fbdev"
    };
    const char *a = argv[*i], *v = NULL, *name = NULL;
    char list[512];
    long l;
    size_t k;
    int matched = 0;

    if (!strcmp(a, "--no-interleave")) { o->interleave = 0; return 0; }
    if (!strcmp(a, "--no-temporal")) { o->temporal = 0; return 0; }
    if (!strcmp(a, "--far-f0")) { o->far_f0 = 1; return 0; }
    if (!strcmp(a, "--gi-quarter")) { o->gi_quarter = 1; return 0; }
    if (!strcmp(a, "--pcf-bilinear")) { o->pcf_bilinear = 1; return 0; }
    if (!strcmp(a, "--explain")) { o->explain = 1; return 0; }
    if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) { o->quiet = 1; return 0; }
    for (k = 0; k < sizeof names / sizeof names[0] && !matched; k++) {
        v = option_value(argc, argv, i, names[k], &matched);
        name = names[k];
    }
    if (!matched) {
        usage_error("unknown option '%s' (see tinygi --help)", a);
        return 1;
    }
    if (!v) {
        usage_error("option %s: missing value", name);
        return 1;
    }
    if ((!strcmp(name, "-o") && o->view) || (!strcmp(name, "--fbdev") && !o->view)) {
        usage_error("option %s: not used by tinygi %s", name, o->view ? "view" : "render");
        return 1;
    }
    if (!strcmp(name, "-o")) {
        o->output = v;
    } else if (!strcmp(name, "--fbdev")) {
        o->fbdev = v;
    } else if (!strcmp(name, "--size")) {
        if (parse_size(v, &o->width, &o->height)) {
            usage_error("option --size: expected WxH with W,H in 1..%d and W*H <= %ld, got '%s'",
                        CLI_MAX_SIDE, CLI_MAX_PIXELS, v);
            return 1;
        }
    } else if (!strcmp(name, "--frames")) {
        if (parse_long(v, 1, CLI_MAX_FRAMES, &l)) {
            usage_error("option --frames: expected an integer in 1..%d, got '%s'", CLI_MAX_FRAMES, v);
            return 1;
        }
        o->frames = (int)l;
    } else if (!strcmp(name, "--aov")) {
        o->aov = tg_aov_from_name(v);
        if (o->aov < 0) {
            usage_error("option --aov: expected one of %s; got '%s'",
                        join_names(list, sizeof list, aov_name_i, TG_AOV_COUNT), v);
            return 1;
        }
    } else if (!strcmp(name, "--technique")) {
        o->technique = tg_technique_from_name(v);
        if (o->technique < 0) {
            usage_error("option --technique: expected one of %s; got '%s'",
                        join_names(list, sizeof list, technique_name_i, TG_TECH_COUNT), v);
            return 1;
        }
    } else if (!strcmp(name, "--slices")) {
        if (parse_long(v, 1, 8, &o->slices)) {
            usage_error("option --slices: expected an integer in 1..8, got '%s'", v);
            return 1;
        }
    } else if (!strcmp(name, "--samples")) {
        if (parse_long(v, 1, 256, &o->samples)) {
            usage_error("option --samples: expected an integer in 1..256, got '%s'", v);
            return 1;
        }
    } else if (!strcmp(name, "--bounces")) {
        if (parse_long(v, 0, 100, &o->bounces)) {
            usage_error("option --bounces: expected an integer in 0..100, got '%s'", v);
            return 1;
        }
    } else if (!strcmp(name, "--shadow-size")) {
        if (parse_long(v, 8, 8192, &o->shadow_size)) {
            usage_error("option --shadow-size: expected an integer in 8..8192, got '%s'", v);
            return 1;
        }
    } else if (!strcmp(name, "--radius")) {
        if (parse_number(v, 0.0, 10000.0, &o->radius)) {
            usage_error("option --radius: expected a number in 0..10000 (world units), got '%s'", v);
            return 1;
        }
        o->have_radius = 1;
    } else if (!strcmp(name, "--exposure")) {
        if (parse_number(v, 0.0, 1000.0, &o->exposure)) {
            usage_error("option --exposure: expected a number in 0..1000, got '%s'", v);
            return 1;
        }
        o->have_exposure = 1;
    }
    return 0;
}

static int parse_render_args(int argc, char **argv, render_opts *o)
{
    int i;
    memset(o, 0, sizeof *o);
    o->view = !strcmp(argv[1], "view");
    o->output = "out.ppm";
    o->width = 320;
    o->height = 240;
    o->frames = 1;
    o->aov = TG_AOV_COLOR;
    o->technique = -1;
    o->slices = o->samples = -1;
    o->bounces = o->shadow_size = -1;
    o->interleave = o->temporal = 1;
    for (i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] == '-' && a[1] != '\0') {
            if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
                print_help(stdout);
                exit(0);
            }
            if (render_option(argc, argv, &i, o)) return 1;
        } else if (!o->scene) {
            o->scene = a;
        } else {
            usage_error("%s: unexpected argument '%s' (one SCENE only)", argv[1], a);
            return 1;
        }
    }
    if (!o->scene) {
        usage_error("%s: missing SCENE (a scene file or builtin:NAME)", argv[1]);
        return 1;
    }
    return 0;
}

/* Scene text: a file or builtin:NAME.  0 ok; else exit status. */
static int load_scene_text(const char *scene, char **owned, const char **text, size_t *size)
{
    char why[512];
    *owned = NULL;
    if (!strncmp(scene, "builtin:", 8)) {
        *text = tg_builtin_scene(scene + 8);
        if (!*text) {
            char list[512];
            usage_error("unknown built-in scene '%s' (expected builtin: and one of %s)",
                        scene + 8, join_names(list, sizeof list, builtin_name_i, 1000));
            return EXIT_INPUT;
        }
        *size = strlen(*text);
        return 0;
    }
    if (tgp_file_read(scene, owned, size, why, sizeof why)) {
        file_error(scene, why);
        return EXIT_INPUT;
    }
    *text = *owned;
    return 0;
}

/* Parse into a malloc'd arena, growing it on TG_ERR_MEMORY.  0 ok, else exit status. */
static int parse_scene(const char *name, const char *text, size_t size, tgp_host_io *io,
                       void **arena_mem, tg_scene **scene)
{
    size_t cap;
    tg_error err;
    tg_status s = TG_ERR_MEMORY;
    if (tg_size_mul(size, 8, &cap) || tg_size_add(cap, (size_t)1 << 20, &cap)) cap = CLI_MAX_SCENE_ARENA;
    *arena_mem = NULL;
    while (s == TG_ERR_MEMORY) {
        tg_arena arena;
        if (cap > CLI_MAX_SCENE_ARENA) {
            fprintf(stderr, "tinygi: error: out of memory: the scene needs more than %lu bytes\n",
                    (unsigned long)CLI_MAX_SCENE_ARENA);
            return EXIT_RUNTIME;
        }
        free(*arena_mem);
        *arena_mem = malloc(cap);
        if (!*arena_mem) {
            fprintf(stderr, "tinygi: error: out of memory: the scene needs %lu bytes\n",
                    (unsigned long)cap);
            return EXIT_RUNTIME;
        }
        tg_arena_init(&arena, *arena_mem, cap);
        memset(&err, 0, sizeof err);
        tgp_host_io_free(io);
        s = tg_scene_parse(text, size, name, &io->io, &arena, scene, &err);
        if (s == TG_ERR_MEMORY) {
            size_t next = err.bytes_needed > cap ? err.bytes_needed : 0;
            if (!next && tg_size_mul(cap, 2, &next)) next = (size_t)-1;
            cap = next;
        }
    }
    if (s != TG_OK) {
        core_error(&err);
        return exit_for(s);
    }
    return 0;
}

static void make_request(const render_opts *o, tg_request *r)
{
    tg_request_defaults(r);
    r->width = o->width;
    r->height = o->height;
    r->frames = o->frames;
    r->aovs = 1u << o->aov;
    if (o->technique >= 0) r->technique = (tg_technique)o->technique;
    if (o->slices > 0) r->slices = (int)o->slices;
    if (o->samples > 0) r->samples = (int)o->samples;
    if (o->bounces >= 0) r->bounces = (int)o->bounces;
    if (o->shadow_size > 0) r->shadow_map_size = (int)o->shadow_size;
    if (o->have_radius) r->radius = tg_from_float((float)o->radius);
    if (o->have_exposure) r->exposure = tg_from_float((float)o->exposure);
    r->interleave = o->interleave;
    r->far_mode = o->far_f0;
    if (o->gi_quarter) r->gi_scale = 2;
    r->shadow_pcf = o->pcf_bilinear;
    r->temporal = o->temporal;
}

static int print_explain(const tg_plan *plan)
{
    size_t size = 65536, n;
    char *buf = (char *)malloc(size);
    if (!buf) return EXIT_RUNTIME;
    n = tg_plan_explain(plan, buf, size);
    if (n >= size) { /* did not fit: ask again with room */
        char *bigger = (char *)realloc(buf, n + 1);
        if (!bigger) { free(buf); return EXIT_RUNTIME; }
        buf = bigger;
        size = n + 1;
        n = tg_plan_explain(plan, buf, size);
        if (n >= size) n = size - 1;
    }
    fwrite(buf, 1, n, stdout);
    if (n == 0 || buf[n - 1] != '\n') fputc('\n', stdout);
    free(buf);
    return fflush(stdout) == 0 ? 0 : EXIT_RUNTIME;
}

typedef struct row_buffers {
    uint8_t *rgb8;
    tg_real *reals;
    float *floats;
} row_buffers;

/* Write one frame's AOV to path (atomically).  0 ok, else 1 (reported). */
static int write_frame(const tg_frame *frame, tg_aov aov, tgp_img_format format, int w, int h,
                       const char *path, row_buffers *rb)
{
    char why[512];
    tgp_outfile *f = tgp_outfile_create(path, why, sizeof why);
    int y, channels = tg_aov_channels(aov);
    size_t x, count = (size_t)w * (size_t)channels;
    if (!f) {
        file_error(path, why);
        return 1;
    }
    if (format == TG_IMG_PPM) {
        tgp_ppm_write_header(f, w, h);
        for (y = 0; y < h; y++) {
            tg_frame_aov_row8(frame, aov, y, rb->rgb8);
            tgp_outfile_write(f, rb->rgb8, (size_t)w * 3u);
        }
    } else {
        tgp_pfm_write_header(f, w, h, channels);
        for (y = h - 1; y >= 0; y--) { /* PFM rows go bottom to top */
            tg_frame_aov_row(frame, aov, y, rb->reals);
            for (x = 0; x < count; x++) rb->floats[x] = tg_to_float(rb->reals[x]);
            tgp_pfm_write_values(f, rb->floats, count);
        }
    }
    if (tgp_outfile_finish(f, why, sizeof why)) {
        file_error(path, why);
        return 1;
    }
    return 0;
}

static void show_progress(int done, int total, double start)
{
    double elapsed = tgp_clock_seconds() - start;
    double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    fprintf(stderr, "\rframe %d/%d, elapsed %.1f s, ETA %.1f s   ", done, total, elapsed, eta);
    fflush(stderr);
}

/* Render every frame and write the requested ones.  0 ok, else exit status. */
static int render_frames(const render_opts *o, const out_pattern *pat, tgp_img_format format,
                         tg_frame *frame)
{
    row_buffers rb;
    char path[CLI_MAX_PATH + 16];
    int i, progress = o->frames > 1 && !o->quiet && isatty(2), status = 0;
    double start = tgp_clock_seconds();
    tg_error err;
    rb.rgb8 = (uint8_t *)malloc((size_t)o->width * 3u);
    rb.reals = (tg_real *)malloc((size_t)o->width * 3u * sizeof(tg_real));
    rb.floats = (float *)malloc((size_t)o->width * 3u * sizeof(float));
    if (!rb.rgb8 || !rb.reals || !rb.floats) {
        fprintf(stderr, "tinygi: error: out of memory\n");
        status = EXIT_RUNTIME;
    }
    for (i = 0; i < o->frames && !status; i++) {
        memset(&err, 0, sizeof err);
        if (progress) show_progress(i, o->frames, start);
        if (tg_frame_render(frame, i, &err) != TG_OK) {
            if (progress) fputc('\n', stderr);
            core_error(&err);
            status = EXIT_RUNTIME; /* the input was validated by the plan */
            break;
        }
        if (pat->numbered || i == o->frames - 1) {
            pattern_path(pat, i, path);
            if (write_frame(frame, (tg_aov)o->aov, format, o->width, o->height, path, &rb))
                status = EXIT_RUNTIME;
        }
    }
    if (progress) {
        show_progress(i, o->frames, start);
        fputc('\n', stderr);
    }
    if (!status && !o->quiet) {
        double ms = (tgp_clock_seconds() - start) * 1000.0 / o->frames;
        pattern_path(pat, pat->numbered ? 0 : o->frames - 1, path);
        fprintf(stderr, "tinygi: wrote %s%s (%dx%d %s, %d frame%s, %.1f ms/frame)\n", path,
                pat->numbered && o->frames > 1 ? " ..." : "", o->width, o->height,
                tg_aov_name((tg_aov)o->aov), o->frames, o->frames > 1 ? "s" : "", ms);
    }
    free(rb.rgb8);
    free(rb.reals);
    free(rb.floats);
    return status;
}

static int cmd_render(int argc, char **argv)
{
    render_opts o;
    out_pattern pat;
    tgp_img_format format;
    tgp_host_io io;
    tg_request req;
    tg_plan plan;
    tg_error err;
    tg_scene *scene = NULL;
    tg_frame *frame = NULL;
    void *scene_mem = NULL, *frame_mem = NULL;
    char *owned = NULL, why[512], first[CLI_MAX_PATH + 16];
    const char *text, *bad;
    size_t size;
    int status;

    if (parse_render_args(argc, argv, &o)) return EXIT_INPUT;
    if (parse_pattern(o.output, &pat, &bad)) {
        usage_error("option -o: %s in '%s'", bad, o.output);
        return EXIT_INPUT;
    }
    if (tgp_img_format_from_path(o.output, &format)) {
        usage_error("option -o: expected a file name ending in .ppm or .pfm, got '%s'", o.output);
        return EXIT_INPUT;
    }
    tgp_host_io_init(&io);
    status = load_scene_text(o.scene, &owned, &text, &size);
    if (!status) status = parse_scene(o.scene, text, size, &io, &scene_mem, &scene);
    if (!status) {
        make_request(&o, &req);
        memset(&err, 0, sizeof err);
        tg_status s = tg_plan_make(&plan, scene, &req, &err);
        if (s != TG_OK) {
            core_error(&err);
            status = exit_for(s);
        }
    }
    if (!status && o.explain) {
        status = print_explain(&plan);
        goto done;
    }
    if (o.view) goto create;
    /* Fail before a long render if the output cannot be written. */
    pattern_path(&pat, pat.numbered ? 0 : o.frames - 1, first);
    if (!status && tgp_file_dir_writable(first, why, sizeof why)) {
        file_error(first, why);
        status = EXIT_RUNTIME;
    }
create:
    if (!status) {
        frame_mem = malloc(plan.total_bytes ? plan.total_bytes : 1);
        if (!frame_mem) {
            fprintf(stderr, "tinygi: error: out of memory: the frame needs %lu bytes\n",
                    (unsigned long)plan.total_bytes);
            status = EXIT_RUNTIME;
        }
    }
    if (!status) {
        tg_status s;
        memset(&err, 0, sizeof err);
        s = tg_frame_create(&plan, frame_mem, plan.total_bytes, &frame, &err);
        if (s != TG_OK) {
            core_error(&err);
            status = exit_for(s);
        }
    }
    if (!status && o.view) {
        if (tgp_fbdev_view(o.fbdev, frame, o.width, o.height, o.frames, why, sizeof why)) {
            usage_error("%s", why);
            status = EXIT_RUNTIME;
        }
    } else if (!status) {
        tgp_outfile_remove_on_signals();
        status = render_frames(&o, &pat, format, frame);
    }
done:
    free(frame_mem);
    free(scene_mem);
    free(owned);
    tgp_host_io_free(&io);
    return status;
}

/* ---- diff ---- */

static int cmd_diff(int argc, char **argv)
{
    const char *a_path = NULL, *b_path = NULL, *out = NULL;
    double tolerance = 0.0;
    tgp_img a, b;
    tgp_diff d;
    char why[512];
    int i, status;

    for (i = 2; i < argc; i++) {
        const char *v;
        int matched;
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            print_help(stdout);
            return 0;
        }
        v = option_value(argc, argv, &i, "--tolerance", &matched);
        if (matched) {
            if (!v || parse_number(v, 0.0, 1e30, &tolerance)) {
                usage_error("option --tolerance: expected a number >= 0 (largest per-channel "
                            "difference: 0..255 for PPM, linear for PFM), got '%s'", v ? v : "");
                return EXIT_INPUT;
            }
            continue;
        }
        v = option_value(argc, argv, &i, "-o", &matched);
        if (matched) {
            tgp_img_format f;
            if (!v || tgp_img_format_from_path(v, &f) || f != TG_IMG_PPM) {
                usage_error("option -o: expected a file name ending in .ppm, got '%s'", v ? v : "");
                return EXIT_INPUT;
            }
            out = v;
            continue;
        }
        if (argv[i][0] == '-' && argv[i][1]) {
            usage_error("unknown option '%s' (see tinygi --help)", argv[i]);
            return EXIT_INPUT;
        }
        if (!a_path) a_path = argv[i];
        else if (!b_path) b_path = argv[i];
        else {
            usage_error("diff: unexpected argument '%s' (two images only)", argv[i]);
            return EXIT_INPUT;
        }
    }
    if (!b_path) {
        usage_error("diff: expected two images: tinygi diff A B [--tolerance T] [-o DIFF.ppm]");
        return EXIT_INPUT;
    }
    if (tgp_img_read(a_path, &a, why, sizeof why)) {
        file_error(a_path, why);
        return EXIT_INPUT;
    }
    if (tgp_img_read(b_path, &b, why, sizeof why)) {
        file_error(b_path, why);
        tgp_img_free(&a);
        return EXIT_INPUT;
    }
    if (tgp_diff_compare(&a, &b, tolerance, &d, why, sizeof why)) {
        usage_error("cannot compare '%s' and '%s': %s", a_path, b_path, why);
        tgp_img_free(&a);
        tgp_img_free(&b);
        return EXIT_INPUT;
    }
    status = tgp_diff_within(&d) ? 0 : 1;
    printf("size %dx%d %s\n", a.width, a.height, a.format == TG_IMG_PPM ? "PPM" : "PFM");
    printf("rmse %.6g\n", d.rmse);
    printf("psnr %.2f dB\n", d.psnr);
    printf("max %.6g at %d,%d channel %c\n", d.max_abs, d.max_x, d.max_y,
           a.channels == 1 ? 'v' : "rgb"[d.max_channel]);
    printf("over %lu of %lu pixels (tolerance %.6g)\n", (unsigned long)d.pixels_over,
           (unsigned long)d.pixels, d.tolerance);
    printf("%s\n", status ? "outside tolerance" : "within tolerance");
    if (out) {
        uint8_t *rgb = tgp_diff_image(&a, &b, &d);
        if (!rgb || tgp_ppm_write(out, a.width, a.height, rgb, why, sizeof why)) {
            file_error(out, rgb ? why : "cannot write: out of memory");
            status = EXIT_INPUT;
        }
        free(rgb);
    }
    tgp_img_free(&a);
    tgp_img_free(&b);
    return status;
}

/* ---- list ---- */

static int cmd_list(void)
{
    int i;
    printf("built-in scenes:");
    for (i = 0; tg_builtin_name(i); i++) printf(" builtin:%s", tg_builtin_name(i));
    printf("\naovs: ");
    list_names(stdout, aov_name_i, TG_AOV_COUNT, " ");
    printf("\ntechniques: ");
    list_names(stdout, technique_name_i, TG_TECH_COUNT, " ");
    printf("\n");
    return fflush(stdout) == 0 ? 0 : EXIT_RUNTIME;
}

int main(int argc, char **argv)
{
    const char *cmd = argc > 1 ? argv[1] : NULL;
    if (!cmd) {
        print_help(stderr);
        return EXIT_INPUT;
    }
    if (!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help")) {
        print_help(stdout);
        return 0;
    }
    if (!strcmp(cmd, "--version")) {
        printf("tinygi %s (%s)\n", TG_VERSION, NUMBER_DESCRIPTION);
        return 0;
    }
    if (!strcmp(cmd, "render") || !strcmp(cmd, "view")) return cmd_render(argc, argv);
    if (!strcmp(cmd, "diff")) return cmd_diff(argc, argv);
    if (!strcmp(cmd, "list")) return cmd_list();
    usage_error("unknown command '%s' (expected render, view, diff or list; see tinygi --help)", cmd);
    return EXIT_INPUT;
}
