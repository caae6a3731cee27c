/* SPDX-License-Identifier: MIT */
/*
 * frame_fixture.h - a scene text through the public API into a frame, for
 * the tests that render whole frames (test_frame.c, test_hardcases.c,
 * test_request.c): parse, plan and create in malloc'd memory, then read
 * the AOVs back.  Hosted test code.
 */
#ifndef TG_FRAME_FIXTURE_H
#define TG_FRAME_FIXTURE_H

#include <stdlib.h>
#include "check.h"

#define AOVBIT(a) (1u << (a))
#define ALL_AOVS ((1u << TG_AOV_COUNT) - 1u)

typedef struct rendered {
    tg_scene *scene;
    tg_plan plan;
    tg_frame *frame;
    void *scene_mem, *frame_mem;
    int ok;
    tg_status status;  /* of the step that failed */
    char msg[600];     /* its message, formatted */
} rendered;

/* The text every mesh path of the scene reads (NULL: no file). */
static const char *fixture_mesh_text;

static inline int fixture_read(void *user, const char *path, const char **data, size_t *size,
                               const char **reason)
{
    (void)user; (void)path; (void)reason;
    if (!fixture_mesh_text) return 1;
    *data = fixture_mesh_text;
    *size = strlen(fixture_mesh_text);
    return 0;
}

/* Parse, plan and create; 1 when the frame is ready, else 0 with status and msg. */
static inline int setup(rendered *r, const char *text, const tg_request *req)
{
    tg_arena arena;
    tg_error err;
    tg_io io;
    size_t scene_bytes = 1u << 22;
    tg_status s;
    memset(r, 0, sizeof *r);
    memset(&err, 0, sizeof err);
    io.user = NULL;
    io.read_file = fixture_read;
    r->scene_mem = malloc(scene_bytes);
    tg_arena_init(&arena, r->scene_mem, scene_bytes);
    s = tg_scene_parse(text, strlen(text), "test.scene", &io, &arena, &r->scene, &err);
    if (s == TG_OK) s = tg_plan_make(&r->plan, r->scene, req, &err);
    if (s == TG_OK) {
        r->frame_mem = malloc(r->plan.total_bytes);
        s = r->frame_mem ? tg_frame_create(&r->plan, r->frame_mem, r->plan.total_bytes, &r->frame, &err)
                         : TG_ERR_MEMORY;
    }
    if (s != TG_OK) {
        r->status = s;
        tg_error_format(&err, r->msg, sizeof r->msg);
        return 0;
    }
    r->ok = 1;
    return 1;
}

static inline void teardown(rendered *r)
{
    free(r->scene_mem);
    free(r->frame_mem);
    r->scene_mem = r->frame_mem = NULL;
    r->ok = 0;
}

/* setup as a check ("WHAT sets up"); r is torn down when it fails. */
static inline int setup_checked(rendered *r, const char *text, const tg_request *req, const char *what)
{
    CHECK(setup(r, text, req), "%s sets up", what);
    if (!r->ok) teardown(r);
    return r->ok;
}

static inline tg_request request(int w, int h, uint32_t aovs)
{
    tg_request q;
    tg_request_defaults(&q);
    q.width = w;
    q.height = h;
    q.aovs = aovs;
    return q;
}

/* A whole AOV (channels * w * h doubles, malloc'd). */
static inline double *read_aov(const rendered *r, tg_aov aov)
{
    int w = r->plan.request.width, h = r->plan.request.height, c = tg_aov_channels(aov), y, i;
    double *out = malloc(sizeof(double) * (size_t)w * (size_t)h * (size_t)c);
    tg_real *row = malloc(sizeof(tg_real) * (size_t)w * (size_t)c);
    for (y = 0; y < h; y++) {
        tg_frame_aov_row(r->frame, aov, y, row);
        for (i = 0; i < w * c; i++) out[(size_t)y * (size_t)(w * c) + (size_t)i] = check_d(row[i]);
    }
    free(row);
    return out;
}

/* Raw bits of every AOV of the current frame, concatenated (malloc'd). */
static inline unsigned char *raw_aovs(const rendered *r, size_t *bytes)
{
    int w = r->plan.request.width, h = r->plan.request.height, a, y;
    size_t n = 0, cap = 0;
    unsigned char *buf;
    for (a = 0; a < TG_AOV_COUNT; a++) cap += (size_t)w * (size_t)h * (size_t)tg_aov_channels((tg_aov)a) * sizeof(tg_real);
    buf = malloc(cap);
    for (a = 0; a < TG_AOV_COUNT; a++) {
        size_t row = (size_t)w * (size_t)tg_aov_channels((tg_aov)a) * sizeof(tg_real);
        for (y = 0; y < h; y++) {
            tg_frame_aov_row(r->frame, (tg_aov)a, y, (tg_real *)(void *)(buf + n));
            n += row;
        }
    }
    *bytes = n;
    return buf;
}

#endif
