/* SPDX-License-Identifier: MIT */
/*
 * fuzz_common.h - shared by the libFuzzer targets (hosted, built by
 * platform/sanitize.mk with clang -fsanitize=fuzzer,address,undefined).
 *
 * An input is up to three parts split by the line "~~~":
 *   fuzz_scene:  SCENE [~~~ OBJ [~~~ MTL]]
 *   fuzz_obj:    OBJ [~~~ MTL]  (under a fixed scene that loads it as a mesh)
 * The tg_io serves the OBJ part for any path ending in ".obj" and the MTL
 * part (or an empty file when there is none) for anything else.  A scene
 * that parses is planned and rendered at a tiny size, and every output must
 * be finite (abort otherwise), so the fuzzer hunts NaNs and wraps as well as
 * memory errors.
 */
#ifndef TG_FUZZ_COMMON_H
#define TG_FUZZ_COMMON_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>
#include "tinygi.h"

#define FUZZ_SEP "\n~~~\n"

typedef struct fuzz_files {
    const char *obj, *mtl;
    size_t obj_n, mtl_n;
} fuzz_files;

static int fuzz_read(void *user, const char *path, const char **data, size_t *size,
                     const char **reason)
{
    (void)reason;
    const fuzz_files *f = (const fuzz_files *)user;
    (void)reason;
    size_t n = strlen(path);
    if (n >= 4 && memcmp(path + n - 4, ".obj", 4) == 0) {
        if (!f->obj) return 1;
        *data = f->obj; *size = f->obj_n;
    } else { /* no MTL part: an empty MTL, so an mtllib line does not end the input */
        *data = f->mtl ? f->mtl : ""; *size = f->mtl ? f->mtl_n : 0;
    }
    return 0;
}

/* Split [p, p+n) at the first FUZZ_SEP: returns the length of the head and
 * sets *rest / *rest_n (NULL when there is no separator). */
static size_t fuzz_split(const char *p, size_t n, const char **rest, size_t *rest_n)
{
    size_t k = sizeof FUZZ_SEP - 1, i;
    for (i = 0; i + k <= n; i++) {
        if (memcmp(p + i, FUZZ_SEP, k) == 0) {
            *rest = p + i + k;
            *rest_n = n - i - k;
            return i;
        }
    }
    *rest = NULL;
    *rest_n = 0;
    return n;
}

static unsigned char fuzz_scene_mem[1u << 23];

static void fuzz_check_finite(const tg_frame *frame, const tg_plan *plan)
{
    static tg_real row[3 * 64];
    int a, y, i;
    for (a = 0; a < TG_AOV_COUNT; a++) {
        int c = tg_aov_channels((tg_aov)a);
        if (!(plan->request.aovs & (1u << a))) continue;
        for (y = 0; y < plan->request.height; y++) {
            tg_frame_aov_row(frame, (tg_aov)a, y, row);
            for (i = 0; i < plan->request.width * c; i++) {
                float v = tg_to_float(row[i]);
                if (!(v == v) || v > 3.0e38f || v < -3.0e38f) {
                    fprintf(stderr, "non-finite %s at row %d index %d\n", tg_aov_name((tg_aov)a), y, i);
                    abort();
                }
            }
        }
    }
}

/* Parse; on success plan and render two frames at 12x9 (HBIL, then the
 * technique chosen by the input's length) and check every AOV is finite. */
static void fuzz_run(const char *scene, size_t scene_n, const fuzz_files *files)
{
    tg_arena arena;
    tg_scene *sc = NULL;
    tg_error err;
    tg_io io;
    tg_plan plan;
    tg_request q;
    tg_frame *frame;
    void *mem;
    char msg[600];
    int f;
    io.user = (void *)files;
    io.read_file = fuzz_read;
    tg_arena_init(&arena, fuzz_scene_mem, sizeof fuzz_scene_mem);
    if (tg_scene_parse(scene, scene_n, "fuzz/in.scene", &io, &arena, &sc, &err) != TG_OK) {
        tg_error_format(&err, msg, sizeof msg);   /* the message must format */
        if (strlen(msg) >= sizeof msg) abort();
        return;
    }
    tg_request_defaults(&q);
    q.width = 12;
    q.height = 9;
    q.frames = 2;
    q.shadow_map_size = 16;
    q.aovs = (1u << TG_AOV_COUNT) - 1u;
    q.technique = (tg_technique)(scene_n % TG_TECH_REFERENCE); /* the reference is too slow to fuzz */
    if (q.samples > 8 || q.samples <= 0) q.samples = 8;
    if (tg_plan_make(&plan, sc, &q, &err) != TG_OK) return;
    if (plan.total_bytes > (64u << 20)) return;
    mem = malloc(plan.total_bytes);
    if (!mem) return;
    if (tg_frame_create(&plan, mem, plan.total_bytes, &frame, &err) == TG_OK) {
        for (f = 0; f < 2; f++) {
            if (tg_frame_render(frame, f, &err) != TG_OK) break;
            fuzz_check_finite(frame, &plan);
        }
    }
    free(mem);
}

#endif
