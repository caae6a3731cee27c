/* SPDX-License-Identifier: MIT */
/*
 * bake_check.c - a scene baked into C data by tinygi-bake (tools/scene_bake.c)
 * renders the same images, bit for bit, as the scene parsed from its text.
 * tests/bake_test.sh bakes each scene and builds this with the baked file
 * (its function named bake_scene):
 *
 *   bake_check SCENE_FILE|builtin:NAME FRAMES
 *
 * Both scenes render FRAMES frames of every AOV a colour plan and an AO
 * plan give; each AOV row must match byte for byte, and the images must
 * not be all 0 (so that matching says something).
 */
#include <stdlib.h>
#include "check.h"
#include "hosted/file.h"

#define W 40
#define H 30

const tg_scene *bake_scene(void);

static const char *scene_path;
static int frames;
static tg_scene *parsed;

/* Render `s` and append every row of the AOVs in `aovs` to out (W*H*3
 * reals per AOV, each frame); 0 on success. */
static int render(const tg_scene *s, uint32_t aovs, tg_real *out)
{
    tg_request req;
    tg_plan plan;
    tg_frame *f = NULL;
    tg_error err;
    void *mem;
    int i, a, y, ok;
    tg_request_defaults(&req);
    req.width = W;
    req.height = H;
    req.frames = frames;
    req.aovs = aovs;
    if (tg_plan_make(&plan, s, &req, &err) != TG_OK) {
        fprintf(stderr, "plan: %s\n", err.message);
        return 1;
    }
    mem = malloc(plan.total_bytes);
    ok = mem && tg_frame_create(&plan, mem, plan.total_bytes, &f, &err) == TG_OK;
    for (i = 0; ok && i < frames; i++) {
        ok = tg_frame_render(f, i, &err) == TG_OK;
        for (a = 0; ok && a < TG_AOV_COUNT; a++) {
            if (!(aovs & (1u << a))) continue;
            for (y = 0; ok && y < H; y++, out += 3 * W) ok = tg_frame_aov_row(f, (tg_aov)a, y, out) == TG_OK;
        }
    }
    free(mem);
    return !ok;
}

static int popcount(uint32_t v)
{
    int n = 0;
    for (; v; v &= v - 1) n++;
    return n;
}

static void compare(const tg_scene *text_scene, uint32_t aovs, const char *what)
{
    size_t n = (size_t)frames * (size_t)popcount(aovs) * W * H * 3, i, diff = 0;
    tg_real *a = calloc(n, sizeof *a), *b = calloc(n, sizeof *b);
    size_t nonzero = 0;
    CHECK(a && b, "out of memory");
    if (!a || !b) goto done;
    CHECK(render(text_scene, aovs, a) == 0, "%s: the parsed scene does not render", what);
    CHECK(render(bake_scene(), aovs, b) == 0, "%s: the baked scene does not render", what);
    for (i = 0; i < n; i++) {
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0) diff++;
        if (check_d(a[i]) != 0) nonzero++;
    }
    CHECK(diff == 0, "%s: %zu of %zu values differ", what, diff, n);
    CHECK(nonzero > 0, "%s: all %zu values are 0", what, n);
done:
    free(a);
    free(b);
}

TEST(colour_matches)
{
    compare(parsed, (1u << TG_AOV_COLOR) | (1u << TG_AOV_DIRECT) | (1u << TG_AOV_NEAR) | (1u << TG_AOV_DEPTH) |
                    (1u << TG_AOV_NORMAL) | (1u << TG_AOV_ALBEDO), "colour");
}

TEST(ao_matches)
{
    compare(parsed, (1u << TG_AOV_AO) | (1u << TG_AOV_BENT), "ao");
}

int main(int argc, char **argv)
{
    static unsigned char arena_mem[16 << 20];
    tg_arena arena;
    tg_error err;
    tgp_host_io io;
    char *text = NULL, msg[256];
    size_t size;
    if (argc != 3) {
        fputs("usage: bake_check SCENE_FILE FRAMES\n", stderr);
        return 2;
    }
    scene_path = argv[1];
    frames = atoi(argv[2]);
    if (!strncmp(scene_path, "builtin:", 8)) {
        const char *b = tg_builtin_scene(scene_path + 8);
        size = b ? strlen(b) : 0;
        text = b ? malloc(size + 1) : NULL;
        if (!text) return 2;
        memcpy(text, b, size + 1);
    } else if (tgp_file_read(scene_path, &text, &size, msg, sizeof msg)) {
        fprintf(stderr, "%s: %s\n", scene_path, msg);
        return 2;
    }
    tg_arena_init(&arena, arena_mem, sizeof arena_mem);
    tgp_host_io_init(&io);
    if (tg_scene_parse(text, size, scene_path, &io.io, &arena, &parsed, &err) != TG_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 2;
    }
    tgp_host_io_free(&io);
    RUN(colour_matches);
    RUN(ao_matches);
    free(text);
    return check_summary();
}
