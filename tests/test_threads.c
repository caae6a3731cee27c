/* SPDX-License-Identifier: MIT */
/*
 * test_threads.c - the hosted thread pool (platform/hosted/threads.c) and
 * frames rendered through it: the pool runs every row of a job exactly
 * once whatever the thread count (more threads than rows included), a run
 * inside a run does not deadlock, bad thread counts are refused in the
 * limits' words; and every AOV of every built-in scene, one frame and
 * animated ones (reprojection, temporal accumulation, --gi-quarter), every
 * technique on a scene with a moving camera and object, has the same bits
 * with 1, 2, 3, 7 and more threads than rows as without a pool.
 *
 * `test_threads quick` runs a smaller set (tests/threads_tsan_test.sh runs
 * it under ThreadSanitizer).
 */
#include <pthread.h>
#include <stdlib.h>
#include "frame_fixture.h"
#include "hosted/threads.h"

static int quick;

/* ---- the pool alone ---- */

typedef struct visits {
    int rows;
    int *count;      /* per row: how many ranges covered it */
    int *bad_range;  /* per row: a range started here was empty or out of bounds */
} visits;

static void count_rows(void *job, int y0, int y1)
{
    visits *v = (visits *)job;
    int y;
    if (y0 < 0 || y1 > v->rows || y0 >= y1) {
        if (y0 >= 0 && y0 < v->rows) v->bad_range[y0] = 1;
        else v->bad_range[0] = 1;
        return;
    }
    for (y = y0; y < y1; y++) v->count[y]++;
}

/* 1 when run(count_rows) over `rows` covers every row once. */
static int covers_once(const tg_parallel *h, int rows)
{
    visits v;
    int y, good = 1;
    v.rows = rows;
    v.count = calloc((size_t)rows + 1, sizeof(int));
    v.bad_range = calloc((size_t)rows + 1, sizeof(int));
    h->run(h->user, count_rows, &v, rows);
    for (y = 0; y < rows; y++) good &= v.count[y] == 1 && !v.bad_range[y];
    free(v.count);
    free(v.bad_range);
    return good;
}

TEST(pool_runs_every_row_once)
{
    static const int threads[] = { 1, 2, 3, 7, 64 };
    static const int rows[] = { 1, 2, 3, 5, 17, 64, 65, 240, 1001 };
    size_t t, r;
    int round;
    for (t = 0; t < sizeof threads / sizeof threads[0]; t++) {
        tgp_pool *pool;
        tg_parallel h;
        char why[200];
        int made = tgp_pool_create(threads[t], &pool, why, sizeof why) == 0;
        CHECK(made, "a pool of %d threads: %s", threads[t], why);
        if (!made) continue;
        CHECK(tgp_pool_threads(pool) == threads[t], "%d threads", threads[t]);
        h = tgp_pool_parallel(pool);
        for (round = 0; round < 3; round++) /* the same threads, job after job */
            for (r = 0; r < sizeof rows / sizeof rows[0]; r++)
                CHECK(covers_once(&h, rows[r]), "%d threads, %d rows (round %d)", threads[t], rows[r], round);
        tgp_pool_destroy(pool);
    }
    tgp_pool_destroy(NULL);
}

TEST(pool_refuses_bad_thread_counts)
{
    static const int bad[] = { 0, -1, TG_MAX_THREADS + 1 };
    char why[200], want[200];
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        tgp_pool *pool = (tgp_pool *)&why; /* must be set to NULL */
        CHECK(tgp_pool_create(bad[i], &pool, why, sizeof why) == 1 && pool == NULL, "%d threads refused", bad[i]);
        snprintf(want, sizeof want, "threads must be 1..%d, got %d", TG_MAX_THREADS, bad[i]);
        CHECK(strcmp(why, want) == 0, "'%s' is not '%s'", why, want);
    }
    CHECK(tgp_cores() >= 1 && tgp_cores() <= TG_MAX_THREADS, "cores %d", tgp_cores());
}

/* A job whose ranges each run a whole job of their own through the pool. */
typedef struct nested {
    const tg_parallel *h;
    int rows, inner_rows;
    int *ok;         /* per outer row */
} nested;

static void run_inner(void *job, int y0, int y1)
{
    nested *n = (nested *)job;
    int y;
    for (y = y0; y < y1; y++) n->ok[y] = covers_once(n->h, n->inner_rows);
}

TEST(run_inside_run_finishes)
{
    tgp_pool *pool;
    tg_parallel h;
    nested n;
    char why[200];
    int y, all = 1;
    if (tgp_pool_create(3, &pool, why, sizeof why)) { CHECK(0, "pool: %s", why); return; }
    h = tgp_pool_parallel(pool);
    n.h = &h;
    n.rows = 40;
    n.inner_rows = 9;
    n.ok = calloc((size_t)n.rows, sizeof(int));
    h.run(h.user, run_inner, &n, n.rows);
    for (y = 0; y < n.rows; y++) all &= n.ok[y];
    CHECK(all, "every inner run covered its rows");
    free(n.ok);
    tgp_pool_destroy(pool);
}

TEST(set_parallel_checks_the_hook)
{
    rendered r;
    tg_request q = request(8, 6, AOVBIT(TG_AOV_COLOR));
    tg_parallel h;
    if (!setup(&r, tg_builtin_scene("plane"), &q)) { CHECK(0, "setup: %s", r.msg); return; }
    h.user = NULL;
    h.run = NULL;
    CHECK(tg_frame_set_parallel(r.frame, &h) == TG_ERR_INPUT, "a hook without run is refused");
    CHECK(tg_frame_set_parallel(r.frame, NULL) == TG_OK, "NULL: the calling thread");
    teardown(&r);
}

/* ---- frames through the pool ---- */

#define W 23
#define H 17
/* thread counts: 1 (a pool without workers), 2, 3, 7, more than rows */
static const int thread_counts[] = { 1, 2, 3, 7, H + 7 };
#define NPOOLS ((int)(sizeof thread_counts / sizeof thread_counts[0]))
static tgp_pool *pools[NPOOLS];

/* Every AOV's bits after q->frames frames, rendered through h (NULL: no hook). */
static unsigned char *render_with(const char *text, const tg_request *q, const tg_parallel *h, size_t *bytes)
{
    rendered r;
    tg_error err;
    unsigned char *all = NULL;
    int f, ok = 1;
    *bytes = 0;
    if (!setup(&r, text, q)) { teardown(&r); return NULL; }
    if (h && tg_frame_set_parallel(r.frame, h) != TG_OK) ok = 0;
    for (f = 0; f < q->frames && ok; f++) ok = tg_frame_render(r.frame, f, &err) == TG_OK;
    if (ok) all = raw_aovs(&r, bytes);
    teardown(&r);
    return all;
}

/* The frames of (text, q) through every pool equal those without one. */
static void same_with_every_pool(const char *what, const char *text, const tg_request *q)
{
    size_t n0, n;
    unsigned char *ref = render_with(text, q, NULL, &n0), *got;
    int p;
    CHECK(ref != NULL, "%s renders", what);
    if (!ref) return;
    for (p = 0; p < NPOOLS; p++) {
        tg_parallel h;
        if (quick && thread_counts[p] != 2 && thread_counts[p] != 7) continue;
        CHECK(pools[p] != NULL, "a pool of %d threads", thread_counts[p]);
        if (!pools[p]) continue;
        h = tgp_pool_parallel(pools[p]);
        got = render_with(text, q, &h, &n);
        CHECK(got && n == n0 && memcmp(ref, got, n0) == 0, "%s with %d threads differs", what, thread_counts[p]);
        free(got);
    }
    free(ref);
}

TEST(every_builtin_scene_every_aov_same_bits)
{
    int s, a, cfg;
    for (s = 0; tg_builtin_name(s); s++) {
        const char *name = tg_builtin_name(s), *text = tg_builtin_scene(name);
        char what[160];
        if (quick && s > 2) break;
        for (cfg = 0; cfg < 3; cfg++) { /* every AOV: 1 frame; 3 frames; 3 frames --gi-quarter */
            tg_request q = request(W, H, ALL_AOVS);
            q.frames = cfg == 0 ? 1 : 3;
            if (cfg == 2) q.gi_scale = 2;
            snprintf(what, sizeof what, "%s, %d frame(s)%s", name, q.frames, cfg == 2 ? ", quarter" : "");
            same_with_every_pool(what, text, &q);
        }
        for (a = 0; a < TG_AOV_COUNT && !quick; a++) { /* one AOV: the plan it alone needs */
            tg_request q = request(W, H, AOVBIT(a));
            q.frames = 2;
            snprintf(what, sizeof what, "%s, --aov %s, 2 frames", name, tg_aov_name((tg_aov)a));
            same_with_every_pool(what, text, &q);
        }
    }
}

/* A moving camera, a moving object, a shadowed spot light and an
 * environment: motion vectors, reprojection with disocclusions, the far
 * field, every technique. */
static const char *moving =
    "camera_key t 0 pos -0.3 1.2 -3 target 0 0.6 0\n"
    "camera_key t 1 pos 0.5 1.5 -2.8 target 0.1 0.5 0\n"
    "material floor albedo 0.6 0.6 0.6\n"
    "material red albedo 0.8 0.2 0.1 f0 0.1\n"
    "material glow albedo 0.3 0.3 0.3 emissive 1 2 4\n"
    "quad p0 -3 0 -3 p1 -3 0 3 p2 3 0 3 p3 3 0 -3 material floor\n"
    "box min -1.5 0 1 max 1.5 2 1.3 material floor\n"
    "sphere center 0 0.5 0 radius 0.5 material red name ball\n"
    "box min 0.8 0 -0.2 max 1.1 0.3 0.1 material glow\n"
    "object_key name ball t 0 translate -0.6 0 0\n"
    "object_key name ball t 1 translate 0.6 0.2 0\n"
    "light spot pos 0 2.8 -1 dir 0 -1 0.4 angle 60 color 1 0.9 0.8 intensity 8 shadows\n"
    "env sky 0.3 0.4 0.6 ground 0.15 0.1 0.1\n"
    "gi radius 1.5\n";

TEST(moving_scene_every_technique_same_bits)
{
    int t, cfg;
    char what[160];
    for (t = 0; t < TG_TECH_COUNT; t++) {
        tg_request q = request(W, H, ALL_AOVS);
        if (quick && t != TG_TECH_HBIL && t != TG_TECH_SSDO) continue;
        q.technique = (tg_technique)t;
        q.frames = 3;
        q.bounces = 2;
        if (t == TG_TECH_REFERENCE) { q.samples = 8; q.frames = 2; }
        snprintf(what, sizeof what, "moving scene, %s", tg_technique_name(q.technique));
        same_with_every_pool(what, moving, &q);
    }
    for (cfg = 0; cfg < 4; cfg++) { /* HBIL: quarter, full-resolution kernel, no temporal, three depth layers */
        tg_request q = request(W, H, ALL_AOVS);
        q.frames = 4;
        if (cfg == 0) q.gi_scale = 2;
        if (cfg == 1) q.interleave = 0;
        if (cfg == 2) { q.temporal = 0; q.gi_scale = 2; q.shadow_pcf = 0; }
        if (cfg == 3) q.depth_layers = TG_NO_TECHNIQUES ? 1 : 3;
        snprintf(what, sizeof what, "moving scene, hbil configuration %d", cfg);
        same_with_every_pool(what, moving, &q);
    }
}

/* Two application threads render at the same time through one pool: the
 * run that finds the pool busy does its rows itself, and both frames keep
 * their bits. */
typedef struct app_render {
    const tg_parallel *h;
    tg_request q;
    unsigned char *bits;
    size_t bytes;
} app_render;

static void *render_on_app_thread(void *arg)
{
    app_render *a = (app_render *)arg;
    a->bits = render_with(moving, &a->q, a->h, &a->bytes);
    return NULL;
}

TEST(two_frames_share_a_pool)
{
    app_render a[2];
    pthread_t t[2];
    tg_parallel h;
    size_t n0[2];
    unsigned char *ref[2];
    int i;
    if (!pools[2]) { CHECK(0, "a pool of %d threads", thread_counts[2]); return; }
    h = tgp_pool_parallel(pools[2]);
    for (i = 0; i < 2; i++) {
        a[i].h = &h;
        a[i].q = request(W + 8 * i, H, ALL_AOVS);
        a[i].q.frames = 3;
        a[i].q.gi_scale = 1 + i;
        ref[i] = render_with(moving, &a[i].q, NULL, &n0[i]);
    }
    for (i = 0; i < 2; i++) CHECK(pthread_create(&t[i], NULL, render_on_app_thread, &a[i]) == 0, "thread %d", i);
    for (i = 0; i < 2; i++) pthread_join(t[i], NULL);
    for (i = 0; i < 2; i++) {
        CHECK(ref[i] && a[i].bits && a[i].bytes == n0[i] && memcmp(ref[i], a[i].bits, n0[i]) == 0,
              "frame %d rendered beside another through one pool differs", i);
        free(ref[i]);
        free(a[i].bits);
    }
}

int main(int argc, char **argv)
{
    int p;
    quick = argc > 1 && strcmp(argv[1], "quick") == 0;
    RUN(pool_runs_every_row_once);
    RUN(pool_refuses_bad_thread_counts);
    RUN(run_inside_run_finishes);
    RUN(set_parallel_checks_the_hook);
    for (p = 0; p < NPOOLS; p++) {
        char why[200];
        if (tgp_pool_create(thread_counts[p], &pools[p], why, sizeof why))
            fprintf(stderr, "pool of %d threads: %s\n", thread_counts[p], why);
    }
    RUN(every_builtin_scene_every_aov_same_bits);
    RUN(moving_scene_every_technique_same_bits);
    RUN(two_frames_share_a_pool);
    for (p = 0; p < NPOOLS; p++) tgp_pool_destroy(pools[p]);
    return check_summary();
}
