/* SPDX-License-Identifier: MIT */
/*
 * render.c - tinygi's portable render driver: renders built-in scenes at a
 * small size and writes, per scene, one little-endian PFM per AOV
 * (SCENE.color.pfm, SCENE.depth.pfm, ...) and, when colour is among them,
 * SCENE.ppm (8-bit sRGB).
 * It is the same C99 file on every target - Linux on x86-64, i686, s390x
 * and powerpc (port_stdio.c), Cortex-M3/M4F with newlib, Cortex-M0 with
 * no C library at all and 32-bit RISC-V with picolibc (port_semihost.c) -
 * so `make cross` can compare the outputs of every target byte for byte.
 *
 *   usage: render [out=DIR] [size=WxH] [frames=N] [aovs=A+B+...]
 *                 [shadow=N] [technique=NAME] [SCENE...]
 *     out        where the files go (default ".")
 *     size       image size (default 64x48)
 *     frames     frames rendered; the last one is written (default 1)
 *     aovs       AOV names split by '+' or ',' (default color+depth+normal+ao;
 *                '+' because QEMU's -semihosting-config takes the commas);
 *                an AOV the core cannot plan for a scene is skipped, said so
 *     shadow     shadow map texels per side (default: the core's)
 *     technique  hbil, gtao, ... (default: the core's)
 *     SCENE      built-in scene names (default: all of them)
 *   exit status: 0 all written, 1 runtime/output error, 2 bad arguments or
 *   scene, 3 arena too small (TG_BM_ARENA_BYTES).
 *
 * Memory: one static arena of TG_BM_ARENA_BYTES holds the parsed scene,
 * the frame (tg_plan.total_bytes) and one row buffer; nothing else.
 * Cost: where port_insn_count() counts (counter.c), each frame's
 * instructions are printed ("cornell 64x48 fixed frame 2/2: N
 * instructions, P per pixel").
 */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "tinygi.h"
#include "port.h"

#ifndef TG_BM_ARENA_BYTES
#define TG_BM_ARENA_BYTES (2u * 1024u * 1024u)
#endif

static unsigned char arena_memory[TG_BM_ARENA_BYTES] __attribute__((aligned(16)));

/* Helpers that need big buffers stay out of render_scene's stack frame,
 * which is live during the whole render (the deepest stack use). */
#define NOINLINE __attribute__((noinline))

/* ---- tiny string helpers (no libc on the smallest targets) ---- */
static size_t str_len(const char *s)
{
    size_t n = 0;
    while (s[n]) n++;
    return n;
}

static int str_eq(const char *a, const char *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (a[i] != b[i]) return 0;
    return b[n] == 0;
}

/* The first n characters of a are those of b. */
static int str_eq_prefix(const char *a, const char *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (a[i] != b[i]) return 0;
    return 1;
}

/* Append s to buf (of size cap) at *at; always NUL-terminated. */
static void cat_str(char *buf, size_t cap, size_t *at, const char *s)
{
    while (*s && *at + 1 < cap) buf[(*at)++] = *s++;
    buf[*at] = 0;
}

static void cat_uint(char *buf, size_t cap, size_t *at, uint64_t v)
{
    char digits[24];
    int n = 0;
    do {
        digits[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v);
    while (n > 0 && *at + 1 < cap) buf[(*at)++] = digits[--n];
    buf[*at] = 0;
}

/* Parse a decimal integer at *s, advancing it; -1 if none. */
static long parse_ulong(const char **s)
{
    long v = 0;
    if (**s < '0' || **s > '9') return -1;
    while (**s >= '0' && **s <= '9' && v < 1000000L) v = v * 10 + (*(*s)++ - '0');
    return v;
}

/* ---- output ---- */
static int write_all(int h, const void *data, size_t n, int *bad)
{
    if (!*bad && port_write(h, data, n) != 0) *bad = 1;
    return *bad;
}

/* PFM is little-endian (negative scale); bytes are built from the float's
 * bits so that big-endian targets write the same file. */
static void put_f32le(unsigned char *p, float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    p[0] = (unsigned char)(u & 0xffu);
    p[1] = (unsigned char)((u >> 8) & 0xffu);
    p[2] = (unsigned char)((u >> 16) & 0xffu);
    p[3] = (unsigned char)(u >> 24);
}

static int open_output(const char *dir, const char *scene, const char *suffix, char *path, size_t cap)
{
    size_t at = 0;
    path[0] = 0;
    cat_str(path, cap, &at, dir);
    cat_str(path, cap, &at, "/");
    cat_str(path, cap, &at, scene);
    cat_str(path, cap, &at, suffix);
    return port_open(path);
}

static void header(char *buf, size_t cap, const char *magic, int w, int h, const char *tail)
{
    size_t at = 0;
    buf[0] = 0;
    cat_str(buf, cap, &at, magic);
    cat_uint(buf, cap, &at, (uint64_t)w);
    cat_str(buf, cap, &at, " ");
    cat_uint(buf, cap, &at, (uint64_t)h);
    cat_str(buf, cap, &at, tail);
}

NOINLINE static int write_ppm(const tg_frame *frame, int w, int h, const char *dir, const char *scene, uint8_t *row8)
{
    char path[160], head[48];
    int y, bad = 0, f = open_output(dir, scene, ".ppm", path, sizeof path);
    if (f < 0) return -1;
    header(head, sizeof head, "P6\n", w, h, "\n255\n");
    write_all(f, head, str_len(head), &bad);
    for (y = 0; y < h; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, row8);
        write_all(f, row8, (size_t)w * 3u, &bad);
    }
    if (port_close(f) != 0) bad = 1;
    return bad ? -1 : 0;
}

NOINLINE static int write_pfm(const tg_frame *frame, tg_aov aov, int w, int h, const char *dir,
                     const char *scene, tg_real *row)
{
    unsigned char *bytes = (unsigned char *)row; /* converted in place: value i's 4 bytes replace it */
    char path[160], head[48], suffix[24];
    size_t at = 0, i, n;
    int y, bad = 0, f, channels = tg_aov_channels(aov);
    cat_str(suffix, sizeof suffix, &at, ".");
    cat_str(suffix, sizeof suffix, &at, tg_aov_name(aov));
    cat_str(suffix, sizeof suffix, &at, ".pfm");
    f = open_output(dir, scene, suffix, path, sizeof path);
    if (f < 0) return -1;
    header(head, sizeof head, channels == 3 ? "PF\n" : "Pf\n", w, h, "\n-1.0\n");
    write_all(f, head, str_len(head), &bad);
    n = (size_t)w * (size_t)channels;
    for (y = h - 1; y >= 0; y--) { /* PFM rows run bottom to top */
        tg_frame_aov_row(frame, aov, y, row);
        for (i = 0; i < n; i++) put_f32le(bytes + 4u * i, tg_to_float(row[i]));
        write_all(f, bytes, 4u * n, &bad);
    }
    if (port_close(f) != 0) bad = 1;
    return bad ? -1 : 0;
}

/* ---- rendering ---- */
typedef struct settings {
    const char *outdir;
    int width, height, frames, shadow, technique;
    uint32_t aovs;
} settings;

NOINLINE static void log_error(const char *what, const tg_error *err)
{
    char msg[400];
    size_t at = 0;
    cat_str(msg, sizeof msg, &at, "render: ");
    cat_str(msg, sizeof msg, &at, what);
    cat_str(msg, sizeof msg, &at, ": ");
    at += tg_error_format(err, msg + at, sizeof msg - at);
    port_log(msg);
}

static int status_exit(tg_status s) { return s == TG_ERR_MEMORY ? 3 : s == TG_ERR_INPUT ? 2 : 1; }

/* "render: NAME: skipping aov AOV" */
NOINLINE static void log_skipped(const char *name, tg_aov a)
{
    char msg[96];
    size_t at = 0;
    cat_str(msg, sizeof msg, &at, "render: ");
    cat_str(msg, sizeof msg, &at, name);
    cat_str(msg, sizeof msg, &at, ": skipping aov ");
    cat_str(msg, sizeof msg, &at, tg_aov_name(a));
    port_log(msg);
}

/* Plan with the AOVs the core accepts for this scene: when the whole set
 * cannot be planned, drop one AOV at a time (and say so). */
NOINLINE static tg_status plan_scene(tg_plan *plan, const tg_scene *scene, const settings *st,
                            const char *name, tg_error *err)
{
    tg_request req;
    int a;
    tg_request_defaults(&req);
    req.width = st->width;
    req.height = st->height;
    req.frames = st->frames;
    req.aovs = st->aovs;
    if (st->shadow > 0) req.shadow_map_size = st->shadow;
    if (st->technique >= 0) req.technique = (tg_technique)st->technique;
    if (tg_plan_make(plan, scene, &req, err) == TG_OK) return TG_OK;
    for (a = 0; a < TG_AOV_COUNT; a++) {
        uint32_t bit = 1u << a;
        if (!(req.aovs & bit) || req.aovs == bit) continue;
        req.aovs &= ~bit;
        if (tg_plan_make(plan, scene, &req, err) == TG_OK) {
            log_skipped(name, (tg_aov)a);
            return TG_OK;
        }
        req.aovs |= bit;
    }
    return tg_plan_make(plan, scene, &req, err);
}

/* "render: NAME: arena too small: about N bytes needed, M available" */
NOINLINE static void log_arena_short(const char *name, size_t used, size_t more)
{
    char msg[160];
    size_t at = 0;
    cat_str(msg, sizeof msg, &at, "render: ");
    cat_str(msg, sizeof msg, &at, name);
    cat_str(msg, sizeof msg, &at, ": arena too small: about ");
    cat_uint(msg, sizeof msg, &at, (uint64_t)(used + more));
    cat_str(msg, sizeof msg, &at, " bytes needed, ");
    cat_uint(msg, sizeof msg, &at, (uint64_t)TG_BM_ARENA_BYTES);
    cat_str(msg, sizeof msg, &at, " available (TG_BM_ARENA_BYTES)");
    port_log(msg);
}

/* "NAME WxH NUMBER" */
static void cat_scene(char *msg, size_t cap, size_t *at, const char *name, const settings *st)
{
    cat_str(msg, cap, at, name);
    cat_str(msg, cap, at, " ");
    cat_uint(msg, cap, at, (uint64_t)st->width);
    cat_str(msg, cap, at, "x");
    cat_uint(msg, cap, at, (uint64_t)st->height);
    cat_str(msg, cap, at, " " TG_NUMBER_NAME);
}

/* "NAME WxH NUMBER: frame B bytes, arena used A bytes, N frame(s) in C
 * instructions" (or "in T ms" where nothing counts instructions). */
NOINLINE static void log_scene(const char *name, const settings *st, const tg_plan *plan, size_t arena_used,
                               uint64_t insns, long cs)
{
    char msg[200];
    size_t at = 0;
    cat_scene(msg, sizeof msg, &at, name, st);
    cat_str(msg, sizeof msg, &at, ": frame ");
    cat_uint(msg, sizeof msg, &at, (uint64_t)plan->total_bytes);
    cat_str(msg, sizeof msg, &at, " bytes, arena used ");
    cat_uint(msg, sizeof msg, &at, (uint64_t)arena_used);
    cat_str(msg, sizeof msg, &at, " bytes, ");
    cat_uint(msg, sizeof msg, &at, (uint64_t)st->frames);
    cat_str(msg, sizeof msg, &at, " frame(s) in ");
    cat_uint(msg, sizeof msg, &at, insns > 0 ? insns : (uint64_t)(cs > 0 ? cs * 10 : 0));
    cat_str(msg, sizeof msg, &at, insns > 0 ? " instructions" : " ms");
    port_log(msg);
}

/* "NAME WxH NUMBER frame I/N: C instructions, P per pixel" (counter.c) */
NOINLINE static void log_frame_count(const char *name, const settings *st, int i, uint64_t insns)
{
    char msg[160];
    size_t at = 0;
    cat_scene(msg, sizeof msg, &at, name, st);
    cat_str(msg, sizeof msg, &at, " frame ");
    cat_uint(msg, sizeof msg, &at, (uint64_t)i + 1u);
    cat_str(msg, sizeof msg, &at, "/");
    cat_uint(msg, sizeof msg, &at, (uint64_t)st->frames);
    cat_str(msg, sizeof msg, &at, ": ");
    cat_uint(msg, sizeof msg, &at, insns);
    cat_str(msg, sizeof msg, &at, " instructions, ");
    cat_uint(msg, sizeof msg, &at, insns / ((uint64_t)st->width * (uint64_t)st->height));
    cat_str(msg, sizeof msg, &at, " per pixel");
    port_log(msg);
}

static int render_scene(const char *name, const settings *st)
{
    static tg_plan plan; /* static: 1.3 KB less stack, counted by the linker */
    static tg_error err;
    tg_arena arena;
    tg_scene *scene = 0;
    tg_frame *frame = 0;
    tg_status s;
    void *frame_memory;
    tg_real *row; /* a row of any AOV, as tg_real, PFM bytes or 8-bit RGB */
    const char *text = tg_builtin_scene(name);
    /* Where instructions are counted the host clock is not read, so that
     * a run's log is the same every time. */
    uint64_t insn0 = port_insn_count();
    long t0 = insn0 > 0 ? 0 : port_clock_cs();
    int i, a, bad = 0;

    memset(&err, 0, sizeof err);
    if (!text) {
        port_log("render: unknown built-in scene");
        port_log(name);
        return 2;
    }
    tg_arena_init(&arena, arena_memory, sizeof arena_memory);
    s = tg_scene_parse(text, str_len(text), name, 0, &arena, &scene, &err);
    if (s != TG_OK) { log_error(name, &err); return status_exit(s); }
    s = plan_scene(&plan, scene, st, name, &err);
    if (s != TG_OK) { log_error(name, &err); return status_exit(s); }
    frame_memory = tg_arena_alloc(&arena, plan.total_bytes);
    row = tg_arena_alloc(&arena, (size_t)st->width * 3u * sizeof(tg_real));
    if (!frame_memory || !row) {
        log_arena_short(name, arena.used, plan.total_bytes + (size_t)st->width * 3u * sizeof(tg_real) + 32u);
        return 3;
    }
    s = tg_frame_create(&plan, frame_memory, plan.total_bytes, &frame, &err);
    for (i = 0; s == TG_OK && i < st->frames; i++) {
        uint64_t insns = port_insn_count();
        s = tg_frame_render(frame, i, &err);
        insns = port_insn_count() - insns;
        if (s == TG_OK && insns > 0) log_frame_count(name, st, i, insns);
    }
    if (s != TG_OK) { log_error(name, &err); return status_exit(s); }
    if (insn0 > 0) log_scene(name, st, &plan, arena.used, port_insn_count() - insn0, 0);
    else log_scene(name, st, &plan, arena.used, 0, port_clock_cs() - t0);

    if ((plan.request.aovs & (1u << TG_AOV_COLOR)) &&
        write_ppm(frame, st->width, st->height, st->outdir, name, (uint8_t *)row) != 0)
        bad = 1;
    for (a = 0; a < TG_AOV_COUNT; a++)
        if ((plan.request.aovs >> a) & 1u)
            if (write_pfm(frame, (tg_aov)a, st->width, st->height, st->outdir, name, row) != 0) bad = 1;
    if (bad) port_log("render: could not write an output file");
    return bad;
}

static int parse_aovs(const char *list, uint32_t *aovs)
{
    *aovs = 0;
    while (*list) {
        size_t n = 0;
        int a, found = -1;
        while (list[n] && list[n] != ',' && list[n] != '+') n++;
        for (a = 0; a < TG_AOV_COUNT; a++)
            if (str_eq(list, tg_aov_name((tg_aov)a), n)) found = a;
        if (found < 0) return -1;
        *aovs |= 1u << found;
        list += n;
        if (*list == ',' || *list == '+') list++;
    }
    return 0;
}

static int parse_size(const char *s, int *w, int *h)
{
    long x = parse_ulong(&s), y;
    if (x <= 0 || *s++ != 'x') return -1;
    y = parse_ulong(&s);
    if (y <= 0 || *s) return -1;
    *w = (int)x;
    *h = (int)y;
    return 0;
}

static int parse_count(const char *s, int *out)
{
    long n = parse_ulong(&s);
    if (n <= 0 || *s) return -1;
    *out = (int)n;
    return 0;
}

/* "key=value" when arg starts with key and '='; value in *v. */
static int is_key(const char *arg, const char *key, const char **v)
{
    size_t n = str_len(key);
    if (!str_eq_prefix(arg, key, n) || arg[n] != '=') return 0;
    *v = arg + n + 1;
    return 1;
}

static int parse_args(int argc, char **argv, settings *st, int *first_scene)
{
    int i;
    for (i = 1; i < argc; i++) {
        const char *v, *a = argv[i];
        int bad = 0;
        if (is_key(a, "out", &v)) st->outdir = v;
        else if (is_key(a, "size", &v)) bad = parse_size(v, &st->width, &st->height);
        else if (is_key(a, "frames", &v)) bad = parse_count(v, &st->frames);
        else if (is_key(a, "aovs", &v)) bad = parse_aovs(v, &st->aovs);
        else if (is_key(a, "shadow", &v)) bad = parse_count(v, &st->shadow);
        else if (is_key(a, "technique", &v)) bad = (st->technique = tg_technique_from_name(v)) < 0;
        else break;
        if (bad) return -1;
    }
    *first_scene = i;
    return 0;
}

int main(int argc, char **argv)
{
    settings st;
    int i, first, worst = 0;
    st.outdir = ".";
    st.width = 64;
    st.height = 48;
    st.frames = 1;
    st.shadow = 0;
    st.technique = -1;
    st.aovs = (1u << TG_AOV_COLOR) | (1u << TG_AOV_DEPTH) | (1u << TG_AOV_NORMAL) | (1u << TG_AOV_AO);
    if (parse_args(argc, argv, &st, &first) != 0) {
        port_log("usage: render [out=DIR] [size=WxH] [frames=N] [aovs=A+B] [shadow=N] [technique=T] [SCENE...]");
        return 2;
    }
    if (first < argc) {
        for (i = first; i < argc; i++) {
            int r = render_scene(argv[i], &st);
            if (r > worst) worst = r;
        }
    } else {
        const char *name;
        for (i = 0; (name = tg_builtin_name(i)) != 0; i++) {
            int r = render_scene(name, &st);
            if (r > worst) worst = r;
        }
    }
    return worst;
}
