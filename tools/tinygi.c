/* SPDX-License-Identifier: MIT */
/*
 * tinygi.c - the command line: render a scene to PPM/PFM/PNG files, compare
 * two images, list what is built in.
 *
 *   tinygi render SCENE [options]     SCENE is a file or builtin:NAME
 *   tinygi view SCENE [options] [--fbdev PATH]   show frames on a framebuffer
 *   tinygi diff A B [--tolerance T] [-o DIFF.ppm]
 *   tinygi list
 *
 * Exit status: 0 success (diff: within tolerance); 1 runtime failure (cannot
 * write, out of memory; diff: outside tolerance); 2 bad usage or bad input
 * (diff: unreadable or mismatched images).  On status 2 nothing is written:
 * everything is validated before the first byte goes out (options against
 * the limits block of tinygi.h, the output names, no output naming an
 * input), and every file is written through a temporary and renamed
 * (platform/hosted/file.h).
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
#include "hosted/threads.h"
#include "fbdev/fbdev.h"

/* The limits of options are the core's (tinygi.h); these two are the CLI's own. */
#define CLI_MAX_PATH 4096                     /* an output path or pattern, bytes */
#define CLI_MAX_SCENE_ARENA ((size_t)1 << 31) /* 2 GiB for a parsed scene */

#define EXIT_RUNTIME 1
#define EXIT_INPUT 2

#if TG_FIXED
#define NUMBER_DESCRIPTION "Q16.16 fixed point"
#else
#define NUMBER_DESCRIPTION "float"
#endif

/* ---- messages ---- */

/* One line on stderr: the message formatted, each control byte in it
 * (below 0x20, and 0x7f) written as \xNN, as the core writes its messages
 * (src/core/error.c): a file name or an option's value holding ESC [ 2 J
 * reached the terminal as an escape sequence, and a newline split the
 * line. */
static void say(const char *fmt, ...)
{
    char line[4096];
    const unsigned char *c;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    for (c = (const unsigned char *)line; *c; c++) {
        if (*c < 0x20 || *c == 0x7f) fprintf(stderr, "\\x%02x", *c);
        else fputc(*c, stderr);
    }
    fputc('\n', stderr);
}

static void usage_error(const char *fmt, ...)
{
    char what[3072];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    say("tinygi: error: %s", what);
}

static void file_error(const char *path, const char *what)
{
    say("%s: error: %s", path, what);
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
        "                    .png the same pixels as PNG, .pfm linear floats (Pf for\n"
        "                    1-channel AOVs, PF for RGB); %%d or %%04d in PATH numbers\n"
        "                    frames from 0 (%%%% is a '%%'); without it only the last\n"
        "                    frame is written.  Never an input file; a symbolic link is\n"
        "                    written through; an existing read-only file is refused\n");
    fprintf(out,
        "  --size WxH        image size (default %dx%d; sides 1..%d, at most %ld pixels)\n"
        "  --frames N        frames to render, 1..%d (default 1)\n"
        "  --aov NAME        output: color depth normal albedo ao bent cone near far\n"
        "                    direct irradiance motion (default color)\n"
        "  --technique NAME  hbil gtao hbao ssao vo ssdo bentcone reference pathtrace\n"
        "                    ssilvb (default hbil; pathtrace: the path-traced ground\n"
        "                    truth; ssilvb: GTAO's slices with a visibility bitmask)\n"
        "  --slices N        horizon slices per pixel, 1..%d (default %d)\n"
        "  --samples N       samples per slice side, 1..%d (default %d; %d for hbil's AO\n"
        "                    alone over depth layers at every pixel; pathtrace:\n"
        "                    paths per pixel, default %d)\n"
        "  --radius R        gather radius in world units, 0..%d (default: the scene's\n"
        "                    gi radius, else its diagonal without an env, diagonal / %d\n"
        "                    with one for light, / %d for AO alone; %d without extent;\n"
        "                    --explain prints it)\n"
        "  --thickness T     ssilvb, and hbil with --depth-layers: surface thickness\n"
        "                    behind the depth buffer, world units, 0..%d (default:\n"
        "                    the radius / %d)\n"
        "  --depth-layers N  ssilvb and hbil, 1..%d: 2 also keeps the nearest back\n"
        "                    face's depth, where a closed object ends, 3 also the\n"
        "                    surface behind it; 1 the depth buffer alone (default:\n"
        "                    2 for --aov ao, bent or cone alone from hbil in a scene\n"
        "                    with an env, else 1; --explain prints it);\n"
        "                    hbil's kernel then is the visibility bitmask (with\n"
        "                    --gi-quarter on the half-resolution image)\n"
        "  --bounces N       light bounces, 0..%d (default %d; pathtrace: the most\n"
        "                    bounces, default %d)\n"
        "  --exposure E      linear exposure before the tonemapper, 0..%d (default 1)\n"
        "  --shadow-size N   shadow map texels per side of every face the view needs,\n"
        "                    %d..%d (default: each face by the size rule, about a texel\n"
        "                    per image pixel)\n"
        "  --shadows HOW     auto maps rays: shadow maps, or shadow rays against a BVH\n"
        "                    (default auto: the plan chooses per light, see --explain)\n"
        "  --threads N       threads that share each pass's rows, 1..%d (default: the\n"
        "                    processors, here %d); the image is the same for every N\n",
        TG_DEFAULT_WIDTH, TG_DEFAULT_HEIGHT, TG_MAX_IMAGE_SIDE, (long)TG_MAX_IMAGE_PIXELS,
        TG_MAX_FRAMES, TG_MAX_SLICES, TG_DEFAULT_SLICES, TG_MAX_SAMPLES, TG_DEFAULT_SAMPLES, TG_DEFAULT_LAYERED_AO_SAMPLES,
        TG_DEFAULT_PATHTRACE_SAMPLES,
        TG_MAX_RADIUS, TG_RADIUS_LIGHT_DIVISOR, TG_RADIUS_ENV_DIVISOR, TG_DEFAULT_RADIUS, TG_MAX_THICKNESS, TG_THICKNESS_RADIUS_DIVISOR, TG_MAX_DEPTH_LAYERS, TG_MAX_BOUNCES, TG_DEFAULT_BOUNCES, TG_DEFAULT_PATHTRACE_BOUNCES, TG_MAX_EXPOSURE,
        TG_MIN_SHADOW_MAP, TG_MAX_SHADOW_MAP, TG_MAX_THREADS, tgp_cores());
    fprintf(out,
        "  --no-interleave   full-resolution GI kernel instead of 4x4 interleaved\n"
        "  --no-temporal     no temporal accumulation\n"
        "  --pcf-tent        16-tap tent shadow-map filtering instead of the 4-tap bilinear\n"
        "  --pcf-bilinear    4-tap bilinear shadow-map filtering (the default)\n"
        "  --gi-quarter      GI kernel on a quarter of the pixels (half width and height,\n"
        "                    then a joint bilateral upsample): 1.5-2.2x fewer\n"
        "                    instructions a frame\n"
        "  --ao-multibounce  the ao output through GTAO's multi-bounce fit (Jimenez et al.\n"
        "                    2016, eq. 10) with each pixel's albedo (its luminance)\n"
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
        "  PFM.  A NaN or infinity in either image is always a difference, and is\n"
        "  reported.  -o writes the absolute difference (.ppm or .png) scaled so\n"
        "  the largest is white.\n"
        "\n"
        "input files (scenes, meshes, images) must be regular files of at most %ld\n"
        "  bytes.\n"
        "\n"
        "exit status: 0 success (diff: within tolerance); 1 runtime failure such\n"
        "  as out of memory or an output the file system refuses (diff: outside\n"
        "  tolerance); 2 bad usage or bad input, nothing written (diff: any failure)\n",
        (long)TG_MAX_FILE_BYTES);
}

/* ---- option values ---- */

/* An integer: 0 ok, 1 not an integer, 2 outside lo..hi. */
static int parse_long(const char *s, long lo, long hi, long *out)
{
    char *end;
    long v;
    if (!*s || !((*s >= '0' && *s <= '9') || *s == '-' || *s == '+')) return 1;
    errno = 0;
    v = strtol(s, &end, 10);
    if (*end) return 1;
    if (errno || v < lo || v > hi) return 2;
    *out = v;
    return 0;
}

/* A decimal number, as the scene format writes one (no hex, inf or nan:
 * strtod reads those, the scene parser does not): 0 ok, 1 not a number, 2
 * outside lo..hi. */
static int parse_number(const char *s, double lo, double hi, double *out)
{
    char *end;
    double v;
    const char *c;
    if (!*s || !((*s >= '0' && *s <= '9') || *s == '-' || *s == '+' || *s == '.')) return 1;
    for (c = s; *c; c++)
        if (!((*c >= '0' && *c <= '9') || *c == '-' || *c == '+' || *c == '.' || *c == 'e' || *c == 'E')) return 1;
    errno = 0;
    v = strtod(s, &end);
    if (*end) return 1;
    if (errno || !(v >= lo && v <= hi)) return 2; /* also refuses NaN */
    *out = v;
    return 0;
}

/* The value as the user gave it, for "got V" ('' when empty). */
static const char *shown(const char *v)
{
    return *v ? v : "''";
}

/* "option NAME: must be LO..HI, got V" unless v is an integer in lo..hi. */
static int int_option(const char *name, const char *v, long lo, long hi, long *out)
{
    if (!parse_long(v, lo, hi, out)) return 0;
    usage_error("option %s: must be %ld..%ld, got %s", name, lo, hi, shown(v));
    return 1;
}

static int real_option(const char *name, const char *v, double hi, double *out)
{
    if (!parse_number(v, 0.0, hi, out)) return 0;
    usage_error("option %s: must be 0..%g, got %s", name, hi, shown(v));
    return 1;
}

/* --size WxH: 0 ok, else 1 (reported). */
static int size_option(const char *s, int *w, int *h)
{
    char buf[64];
    const char *x = strchr(s, 'x');
    long side[2];
    size_t n;
    int k;
    if (!x) x = strchr(s, 'X');
    if (!x || (n = (size_t)(x - s)) >= sizeof buf) {
        usage_error("option --size: expected WxH (e.g. %dx%d), got '%s'", TG_DEFAULT_WIDTH,
                    TG_DEFAULT_HEIGHT, s);
        return 1;
    }
    memcpy(buf, s, n);
    buf[n] = '\0';
    for (k = 0; k < 2; k++) {
        const char *v = k ? x + 1 : buf;
        int r = parse_long(v, 1, TG_MAX_IMAGE_SIDE, &side[k]);
        if (r == 1) {
            usage_error("option --size: expected WxH (e.g. %dx%d), got '%s'", TG_DEFAULT_WIDTH,
                        TG_DEFAULT_HEIGHT, s);
            return 1;
        }
        if (r) {
            usage_error("option --size: %s must be 1..%d, got %s", k ? "height" : "width",
                        TG_MAX_IMAGE_SIDE, v);
            return 1;
        }
    }
    if (side[0] * side[1] > (long)TG_MAX_IMAGE_PIXELS) { /* sides <= TG_MAX_IMAGE_SIDE: fits */
        usage_error("option --size: pixels (width*height) must be 1..%ld, got %ld",
                    (long)TG_MAX_IMAGE_PIXELS, side[0] * side[1]);
        return 1;
    }
    *w = (int)side[0];
    *h = (int)side[1];
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
    long slices, samples, bounces, shadow_size, threads, depth_layers;
    int shadows;            /* TG_SHADOWS_* */
    double radius, exposure, thickness;
    int have_radius, have_exposure, have_thickness;
    int interleave, temporal, far_f0, gi_quarter, pcf_tent, explain, quiet, ao_multibounce;
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

/* Option `name`'s value v, one of count names (from_name its index, name_of
 * the names): *out its index, or a usage error listing them. */
static int name_option(const char *name, const char *v, int (*from_name)(const char *),
                       const char *(*name_of)(int), int count, int *out)
{
    char list[512];
    *out = from_name(v);
    if (*out >= 0) return 0;
    usage_error("option %s: expected one of %s; got '%s'", name, join_names(list, sizeof list, name_of, count), v);
    return 1;
}

static const char *builtin_name_i(int i) { return tg_builtin_name(i); }

/* Parse one render option at argv[*i]; 0 ok, 1 usage error (reported). */
static int render_option(int argc, char **argv, int *i, render_opts *o)
{
    static const char *const names[] = {
        "-o", "--size", "--frames", "--aov", "--technique", "--slices", "--samples",
        "--radius", "--bounces", "--exposure", "--shadow-size", "--fbdev", "--threads",
        "--shadows", "--thickness", "--depth-layers"
    };
    const char *a = argv[*i], *v = NULL, *name = NULL;
    long l;
    size_t k;
    int matched = 0;

    if (!strcmp(a, "--no-interleave")) { o->interleave = 0; return 0; }
    if (!strcmp(a, "--no-temporal")) { o->temporal = 0; return 0; }
    if (!strcmp(a, "--far-f0")) { o->far_f0 = 1; return 0; }
    if (!strcmp(a, "--ao-multibounce")) { o->ao_multibounce = 1; return 0; }
    if (!strcmp(a, "--gi-quarter")) { o->gi_quarter = 1; return 0; }
    if (!strcmp(a, "--pcf-bilinear")) { o->pcf_tent = 0; return 0; }   /* the default (kept for scripts) */
    if (!strcmp(a, "--pcf-tent")) { o->pcf_tent = 1; return 0; }
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
        if (size_option(v, &o->width, &o->height)) return 1;
    } else if (!strcmp(name, "--frames")) {
        if (int_option(name, v, 1, TG_MAX_FRAMES, &l)) return 1;
        o->frames = (int)l;
    } else if (!strcmp(name, "--aov")) {
        return name_option(name, v, tg_aov_from_name, aov_name_i, TG_AOV_COUNT, &o->aov);
    } else if (!strcmp(name, "--technique")) {
        return name_option(name, v, tg_technique_from_name, technique_name_i, TG_TECH_COUNT, &o->technique);
    } else if (!strcmp(name, "--slices")) {
        return int_option(name, v, 1, TG_MAX_SLICES, &o->slices);
    } else if (!strcmp(name, "--samples")) {
        return int_option(name, v, 1, TG_MAX_SAMPLES, &o->samples);
    } else if (!strcmp(name, "--bounces")) {
        return int_option(name, v, 0, TG_MAX_BOUNCES, &o->bounces);
    } else if (!strcmp(name, "--shadow-size")) {
        return int_option(name, v, TG_MIN_SHADOW_MAP, TG_MAX_SHADOW_MAP, &o->shadow_size);
    } else if (!strcmp(name, "--shadows")) {
        static const char *const how[3] = { "auto", "maps", "rays" };
        for (k = 0; k < 3 && strcmp(v, how[k]); k++) continue;
        if (k == 3) {
            usage_error("option --shadows: expected one of auto maps rays; got '%s'", v);
            return 1;
        }
        o->shadows = (int)k;   /* TG_SHADOWS_AUTO, _MAPS, _RAYS */
    } else if (!strcmp(name, "--depth-layers")) {
        return int_option(name, v, 1, TG_MAX_DEPTH_LAYERS, &o->depth_layers);
    } else if (!strcmp(name, "--threads")) {
        return int_option(name, v, 1, TG_MAX_THREADS, &o->threads);
    } else if (!strcmp(name, "--radius")) {
        if (real_option(name, v, TG_MAX_RADIUS, &o->radius)) return 1;
        o->have_radius = 1;
    } else if (!strcmp(name, "--thickness")) {
        if (real_option(name, v, TG_MAX_THICKNESS, &o->thickness)) return 1;
        o->have_thickness = 1;
    } else if (!strcmp(name, "--exposure")) {
        if (real_option(name, v, TG_MAX_EXPOSURE, &o->exposure)) return 1;
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
    o->width = TG_DEFAULT_WIDTH;
    o->height = TG_DEFAULT_HEIGHT;
    o->frames = 1;
    o->aov = TG_AOV_COLOR;
    o->technique = -1;
    o->slices = o->samples = -1;
    o->bounces = o->shadow_size = -1;
    o->threads = tgp_cores();
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
    /* the API refuses it too (request.c), naming the request's field */
    if (o->depth_layers > 1 && o->technique >= 0 && o->technique != TG_TECH_HBIL && o->technique != TG_TECH_SSILVB) {
        usage_error("option --depth-layers: must be 1 for technique %s (further layers are read by "
                    "techniques hbil and ssilvb), got %ld", tg_technique_name((tg_technique)o->technique),
                    o->depth_layers);
        return 1;
    }
    return 0;
}

/* Scene text: a file or builtin:NAME (then *is_file is 0).  0 ok; else exit status. */
static int load_scene_text(const char *scene, char **owned, const char **text, size_t *size,
                           tgp_file_id *id, int *is_file)
{
    char why[512];
    int r;
    *owned = NULL;
    *is_file = 0;
    if (!strncmp(scene, "builtin:", 8)) {
        *text = tg_builtin_scene(scene + 8);
        if (!*text) {
            char list[512];
            if (!tg_builtin_name(0))
                usage_error("built-in scenes are left out of this build (TG_NO_BUILTIN_SCENES=1)");
            else
                usage_error("unknown built-in scene '%s' (expected builtin: and one of %s)",
                            scene + 8, join_names(list, sizeof list, builtin_name_i, 1000));
            return EXIT_INPUT;
        }
        *size = strlen(*text);
        return 0;
    }
    r = tgp_file_read_limited(scene, (size_t)TG_MAX_FILE_BYTES, owned, size, id, why, sizeof why);
    if (r) {
        say("%s: error: cannot read: %s", scene, why);
        return exit_for((tg_status)r);
    }
    *is_file = 1;
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
        /* a mesh that could not be read for want of memory is not bad input */
        return io->last_status == TG_ERR_RUNTIME ? EXIT_RUNTIME : exit_for(s);
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
    if (o->have_thickness) r->thickness = tg_from_float((float)o->thickness);
    if (o->depth_layers > 0) r->depth_layers = (int)o->depth_layers;
    r->interleave = o->interleave;
    r->far_mode = o->far_f0;
    if (o->gi_quarter) r->gi_scale = 2;
    r->shadow_pcf = !o->pcf_tent;
    r->shadow_method = o->shadows;
    r->temporal = o->temporal;
    r->ao_multibounce = o->ao_multibounce;
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
    } else if (format == TG_IMG_PNG) {
        tgp_png png;
        tgp_png_write_header(f, &png, w, h);
        for (y = 0; y < h; y++) {
            tg_frame_aov_row8(frame, aov, y, rb->rgb8);
            tgp_png_write_row(f, &png, rb->rgb8);
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
        say("tinygi: wrote %s%s (%dx%d %s, %d frame%s, %.1f ms/frame)", path,
                pat->numbered && o->frames > 1 ? " ..." : "", o->width, o->height,
                tg_aov_name((tg_aov)o->aov), o->frames, o->frames > 1 ? "s" : "", ms);
    }
    free(rb.rgb8);
    free(rb.reals);
    free(rb.floats);
    return status;
}

/* 0 if every file the render will write can be written (names, directories,
 * no read-only file in the way): checked before any work; else exit status. */
static int check_outputs(const render_opts *o, const out_pattern *pat)
{
    char path[CLI_MAX_PATH + 16], why[512];
    int i = pat->numbered ? 0 : o->frames - 1;
    for (; i < o->frames; i++) {
        int r;
        pattern_path(pat, i, path);
        r = tgp_outfile_check(path, why, sizeof why);
        if (r) {
            file_error(path, why);
            return r == TG_ERR_INPUT ? EXIT_INPUT : EXIT_RUNTIME;
        }
    }
    return 0;
}

/* Inputs are never overwritten: 0 if no output is the same file (device and
 * inode, whatever links lead there) as the scene or a mesh/MTL it read. */
static int refuse_inputs(const render_opts *o, const out_pattern *pat,
                         const tgp_file_id *scene_id, const tgp_host_io *io)
{
    char path[CLI_MAX_PATH + 16];
    int i = pat->numbered ? 0 : o->frames - 1;
    for (; i < o->frames; i++) {
        const tgp_host_io_file *in;
        const char *input = NULL;
        tgp_file_id out;
        pattern_path(pat, i, path);
        if (tgp_file_identify(path, &out)) continue; /* does not exist yet */
        if (scene_id && out.dev == scene_id->dev && out.ino == scene_id->ino) input = o->scene;
        for (in = io->files; in && !input; in = in->next)
            if (out.dev == in->id.dev && out.ino == in->id.ino) input = in->path;
        if (input) {
            say("%s: error: the output is the input file '%s'; refusing to overwrite it", path, input);
            return EXIT_INPUT;
        }
    }
    return 0;
}

/* --aov near / far on a frame that computes no such light: say why it is black. */
static void warn_black_aov(const render_opts *o, const tg_plan *plan, const tg_scene *scene)
{
    if (o->aov == TG_AOV_NEAR && !(plan->effects & TG_EFFECT_NEAR)) {
        tg_request probe_req = plan->request;
        tg_plan probe;
        tg_error err;
        const char *why = "the scene has no light to bounce (no lights or emissive surfaces "
                          "with albedo) or its effects line leaves near out";
        probe_req.technique = TG_TECH_HBIL;
        if (plan->request.bounces == 0) why = "bounces are 0";
        else if (plan->request.technique != TG_TECH_HBIL &&
                 tg_plan_make(&probe, scene, &probe_req, &err) == TG_OK &&
                 (probe.effects & TG_EFFECT_NEAR))
            why = "this technique computes no near field (bounce light); hbil does";
        fprintf(stderr, "tinygi: warning: --aov near (technique %s) is black: %s\n",
                tg_technique_name(plan->request.technique), why);
    }
    if (o->aov == TG_AOV_FAR && !(plan->effects & TG_EFFECT_FAR))
        fprintf(stderr, "tinygi: warning: --aov far is black: the scene has no environment "
                "light (an env line) or its effects line leaves far out\n");
    if ((o->aov == TG_AOV_AO || o->aov == TG_AOV_BENT || o->aov == TG_AOV_CONE) && !(plan->effects & TG_EFFECT_AO))
        fprintf(stderr, "tinygi: warning: --aov %s holds no occlusion (AO 1): %s\n", tg_aov_name((tg_aov)o->aov),
                plan->request.technique == TG_TECH_PATHTRACE
                    ? "technique pathtrace traces all light itself and computes no AO (technique reference does)"
                    : "the scene's effects line leaves ao out");
}

/* An option this frame reads nowhere: say so rather than ignore it (both
 * were silent: an outside probe).  The thickness is the visibility
 * bitmask's, which ssilvb runs and hbil over depth layers (plan.c prints it
 * under the same condition); the multi-bounce fit changes the ao output only. */
static void warn_unread_options(const render_opts *o, const tg_plan *plan)
{
    const tg_request *r = &plan->request;
    if (o->have_thickness && !tg_plan_reads_thickness(plan))
        fprintf(stderr, "tinygi: warning: --thickness is unread: %s\n",
                r->technique == TG_TECH_HBIL ? "hbil reads it only over depth layers (--depth-layers 2 or 3)"
                                             : "only ssilvb, and hbil over depth layers, read it");
    if (o->ao_multibounce && o->aov != TG_AOV_AO)
        fprintf(stderr, "tinygi: warning: --ao-multibounce is unread: it changes the ao output "
                "(--aov ao) only, and this render writes %s\n", tg_aov_name((tg_aov)o->aov));
}

/* The scene and its plan: 0 or exit status. */
static int plan_scene(const render_opts *o, const out_pattern *pat, tgp_host_io *io,
                      char **owned, void **scene_mem, tg_plan *plan)
{
    tg_request req;
    tg_error err;
    tg_scene *scene = NULL;
    tgp_file_id scene_id;
    const char *text;
    size_t size;
    int is_file, status;
    tg_status s;
    status = load_scene_text(o->scene, owned, &text, &size, &scene_id, &is_file);
    if (!status) status = parse_scene(o->scene, text, size, io, scene_mem, &scene);
    if (!status && !o->view && !o->explain)
        status = refuse_inputs(o, pat, is_file ? &scene_id : NULL, io);
    if (status) return status;
    make_request(o, &req);
    memset(&err, 0, sizeof err);
    s = tg_plan_make(plan, scene, &req, &err);
    if (s != TG_OK) {
        core_error(&err);
        return exit_for(s);
    }
    warn_black_aov(o, plan, scene);
    warn_unread_options(o, plan);
    return 0;
}

static int cmd_render(int argc, char **argv)
{
    render_opts o;
    out_pattern pat;
    tgp_img_format format;
    tgp_host_io io;
    tg_plan plan;
    tg_error err;
    tg_frame *frame = NULL;
    tgp_pool *pool = NULL;
    void *scene_mem = NULL, *frame_mem = NULL;
    char *owned = NULL, why[512];
    const char *bad;
    int status = 0;

    if (parse_render_args(argc, argv, &o)) return EXIT_INPUT;
    if (parse_pattern(o.output, &pat, &bad)) {
        usage_error("option -o: %s in '%s'", bad, o.output);
        return EXIT_INPUT;
    }
    if (tgp_img_format_from_path(o.output, &format)) {
        usage_error("option -o: expected a file name ending in .ppm, .png or .pfm, got '%s'",
                    o.output);
        return EXIT_INPUT;
    }
    /* Fail before a long render if an output cannot be written. */
    if (!o.view && !o.explain) status = check_outputs(&o, &pat);
    tgp_host_io_init(&io);
    if (!status) status = plan_scene(&o, &pat, &io, &owned, &scene_mem, &plan);
    if (!status && o.explain) {
        status = print_explain(&plan);
        goto done;
    }
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
    if (!status && o.threads > 1) { /* every pass's rows shared by the pool */
        tg_parallel hook;
        if (tgp_pool_create((int)o.threads, &pool, why, sizeof why)) {
            fprintf(stderr, "tinygi: error: --threads %ld: %s\n", o.threads, why);
            status = EXIT_RUNTIME;
        } else {
            hook = tgp_pool_parallel(pool);
            tg_frame_set_parallel(frame, &hook);
        }
    }
    if (!status && o.view) {
        int r = tgp_fbdev_view(o.fbdev, frame, o.width, o.height, o.frames, why, sizeof why);
        /* the device's errors are a reason: PATH: error: REASON, as for files */
        if (r == TGP_FB_VIEW_DEVICE) file_error(o.fbdev ? o.fbdev : TGP_FB_DEFAULT_PATH, why);
        else if (r != TGP_FB_VIEW_OK) usage_error("%s", why);
        if (r != TGP_FB_VIEW_OK) status = EXIT_RUNTIME;
    } else if (!status) {
        tgp_outfile_remove_on_signals();
        status = render_frames(&o, &pat, format, frame);
    }
done:
    tgp_pool_destroy(pool);
    free(frame_mem);
    free(scene_mem);
    free(owned);
    tgp_host_io_free(&io);
    return status;
}

/* ---- diff ---- */

/* diff -o: writable, and neither image (checked before they are read). */
static int diff_output_refused(const char *out, const char *a_path, const char *b_path)
{
    char why[512];
    tgp_file_id id;
    if (tgp_outfile_check(out, why, sizeof why)) {
        file_error(out, why);
        return 1;
    }
    if (!tgp_file_identify(out, &id) && (tgp_file_is(a_path, &id) || tgp_file_is(b_path, &id))) {
        say("%s: error: the output is the input file '%s'; refusing to overwrite it",
            out, tgp_file_is(a_path, &id) ? a_path : b_path);
        return 1;
    }
    return 0;
}

static int cmd_diff(int argc, char **argv)
{
    const char *a_path = NULL, *b_path = NULL, *out = NULL;
    tgp_img_format out_format = TG_IMG_PPM;
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
            if (!v || tgp_img_format_from_path(v, &out_format) || out_format == TG_IMG_PFM) {
                usage_error("option -o: expected a file name ending in .ppm or .png, got '%s'",
                            v ? v : "");
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
    if (out && diff_output_refused(out, a_path, b_path)) return EXIT_INPUT;
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
    for (i = 0; i < 2; i++)
        if (d.nan[i] || d.inf[i])
            printf("not finite in %s: %lu NaN, %lu inf values, first at %d,%d\n", i ? "B" : "A",
                   (unsigned long)d.nan[i], (unsigned long)d.inf[i], d.first_x[i], d.first_y[i]);
    printf("%s\n", status ? "outside tolerance" : "within tolerance");
    if (out) {
        uint8_t *rgb = tgp_diff_image(&a, &b, &d);
        if (!rgb || (out_format == TG_IMG_PNG
                         ? tgp_png_write(out, a.width, a.height, rgb, why, sizeof why)
                         : tgp_ppm_write(out, a.width, a.height, rgb, why, sizeof why))) {
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
    if ((!strcmp(cmd, "--help") || !strcmp(cmd, "-h") || !strcmp(cmd, "help") || !strcmp(cmd, "--version")
         || !strcmp(cmd, "list")) && argc > 2) {   /* they take no arguments */
        usage_error("%s: unexpected argument '%s'", cmd, argv[2]);
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
