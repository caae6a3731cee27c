/* SPDX-License-Identifier: MIT */
/*
 * test_hostile.c - every public function of tinygi.h called as a careless or
 * hostile caller would: NULL where the header does not allow it, zero and
 * maximum sizes (INT_MAX, SIZE_MAX), negative and past-the-end indices,
 * unknown enum values, NaN and infinities in tg_real fields, arenas at
 * base + 1..15 and one byte too small, calls out of order (plan before
 * parse, render before create, a plan whose tg_plan_make failed).  Each
 * call must return the status the header documents and touch nothing
 * outside the memory it was given: buffers are allocated to their exact
 * size under AddressSanitizer (`make sanitize` runs this test) and carry
 * guard bytes, checked after each call, otherwise.
 *
 * Every case runs in a child process with a time limit, so a crash, a
 * sanitizer report or a hang fails that case alone and names it.  A case
 * marked expected-to-fail (XFAIL_*) documents a bug that is fixed outside
 * this test's files: it passes while it still fails, and FAILS as soon as
 * it passes ("XPASS"), so the mark is removed when the fix lands.
 */
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <signal.h>
#include <fcntl.h>
#include <unistd.h>
#include <sys/types.h>
#include <sys/wait.h>
#include "check.h"

/* ---- expected failures ----------------------------------------------------
 * A case marked with a string (the bug, where it is fixed) expects a failure;
 * NULL expects the case to pass.  None is marked now: the last marks
 * (a NULL or failed handle, a NULL err in src/frame) were fixed in the
 * twenty-first session. */

#if defined(__SANITIZE_ADDRESS__)
#define HOSTILE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HOSTILE_ASAN 1
#endif
#endif
#ifndef HOSTILE_ASAN
#define HOSTILE_ASAN 0
#endif

/* ---- guarded memory ---------------------------------------------------------
 * `size` bytes at an address with the given remainder mod 16.  Under ASan
 * the block ends exactly at the end of the allocation (any access past it
 * is reported); otherwise GUARD bytes of a pattern follow it.  The bytes
 * before it (the alignment offset) hold the pattern in both. */
#define GUARD 64
#define PATTERN 0xA5

typedef struct guarded {
    unsigned char *block, *p;
    size_t size, before, after;
} guarded;

static guarded guard_alloc(size_t size, unsigned offset)
{
    guarded g;
    g.before = offset & 15u;
    g.after = HOSTILE_ASAN ? 0 : GUARD;
    g.size = size;
    g.block = (unsigned char *)malloc(g.before + size + g.after ? g.before + size + g.after : 1);
    if (!g.block) { fprintf(stderr, "out of memory\n"); exit(3); }
    memset(g.block, PATTERN, g.before + size + g.after);
    g.p = g.block + g.before;
    return g;
}

/* 1 when the bytes around the block still hold the pattern. */
static int guard_intact(const guarded *g)
{
    size_t i;
    for (i = 0; i < g->before; i++) if (g->block[i] != PATTERN) return 0;
    for (i = 0; i < g->after; i++) if (g->p[g->size + i] != PATTERN) return 0;
    return 1;
}

static void guard_free(guarded *g) { free(g->block); g->block = g->p = NULL; }

/* ---- cases in child processes ---------------------------------------------- */

static int hostile_case_failed(const char *name, int status, const char *xfail, unsigned seconds)
{
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        if (!xfail) return 0;
        printf("FAIL %s/%s/%s XPASS: passes now; remove its mark (%s)\n", TG_NUMBER_NAME,
               check_file_name(__FILE__), name, xfail);
        return 1;
    }
    if (xfail) {
        printf("ok %s/%s/%s (expected to fail: %s)\n", TG_NUMBER_NAME, check_file_name(__FILE__), name, xfail);
        return 0;
    }
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
        printf("FAIL %s/%s/%s: no answer after %u s\n", TG_NUMBER_NAME, check_file_name(__FILE__), name, seconds);
    else if (WIFSIGNALED(status))
        printf("FAIL %s/%s/%s: killed by signal %d\n", TG_NUMBER_NAME, check_file_name(__FILE__), name, WTERMSIG(status));
    else
        printf("FAIL %s/%s/%s: exit status %d\n", TG_NUMBER_NAME, check_file_name(__FILE__), name, WEXITSTATUS(status));
    return 1;
}

/* Run one case in a child with an alarm; an expected failure's output is
 * discarded (it is known) unless HOSTILE_SHOW_XFAIL is set in the
 * environment. */
static void run_case(const char *name, void (*fn)(void), const char *xfail, unsigned seconds)
{
    pid_t pid;
    int status = 0;
    fflush(stdout);
    fflush(stderr);
    pid = fork();
    if (pid < 0) { perror("fork"); exit(3); }
    if (pid == 0) {
        if (xfail && !getenv("HOSTILE_SHOW_XFAIL")) {
            int fd = open("/dev/null", O_WRONLY);
            if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); }
        }
        alarm(seconds);
        check_current_name = name;
        check_current_failures = 0;
        fn();
        fflush(stderr);
        _exit(check_current_failures ? 1 : 0);
    }
    while (waitpid(pid, &status, 0) < 0) {}
    if (hostile_case_failed(name, status, xfail, seconds)) check_tests_failed++;
    else {
        check_tests_passed++;
        if (!xfail) printf("ok %s/%s/%s\n", TG_NUMBER_NAME, check_file_name(__FILE__), name);
    }
    fflush(stdout);
}

#define CASE(name, xfail) run_case(#name, name, xfail, 120)

/* ---- scenes ----------------------------------------------------------------- */

/* Every effect at once: keyed camera and object, the three light types with
 * shadows, an emitter, an environment. */
static const char *everything =
    "camera_key t 0 pos 0 1.4 -3.6 target 0 0.8 0\n"
    "camera_key t 1 pos 0.8 1.7 -3.2 target 0 0.6 0\n"
    "material wall albedo 0.7 0.7 0.7\n"
    "material red albedo 0.8 0.2 0.2 f0 0.1\n"
    "material hot albedo 0.5 0.5 0.5 emissive 3 2 1\n"
    "quad p0 -3 0 -4  p1 -3 0 3  p2 3 0 3  p3 3 0 -4 material wall name floor\n"
    "quad p0 -3 0 3  p1 -3 3 3  p2 3 3 3  p3 3 0 3 material wall name back\n"
    "box min -0.4 0 -0.4 max 0.4 0.8 0.4 material red name mover\n"
    "sphere center 1.2 0.4 0.5 radius 0.4 material hot segments 8\n"
    "object_key name mover t 0 translate -0.8 0 0\n"
    "object_key name mover t 1 translate 0.8 0 0 rotate 0 1 0 30\n"
    "light point pos 0 2.5 -1 color 1 1 1 intensity 3 shadows\n"
    "light spot pos 1 2.5 -2 dir -0.3 -1 0.5 angle 40 color 1 0.9 0.8 shadows\n"
    "light directional dir -0.5 -1 0.3 color 0.6 0.6 0.7 shadows\n"
    "env sky 0.4 0.5 0.8 ground 0.2 0.2 0.2\n"
    "gi radius 1\n";

typedef struct loaded {
    void *mem;
    tg_scene *scene;
} loaded;

/* Parse `text` into an arena of exactly the bytes it needs. */
static loaded load(const char *text)
{
    loaded l;
    tg_arena a;
    tg_error err;
    size_t n = strlen(text);
    memset(&l, 0, sizeof l);
    tg_arena_init(&a, NULL, 0);
    if (tg_scene_parse(text, n, "hostile.scene", NULL, &a, &l.scene, &err) != TG_ERR_MEMORY) {
        fprintf(stderr, "scene: %s\n", err.message);
        exit(3);
    }
    l.mem = malloc(err.bytes_needed);
    tg_arena_init(&a, l.mem, err.bytes_needed);
    if (tg_scene_parse(text, n, "hostile.scene", NULL, &a, &l.scene, &err) != TG_OK) {
        fprintf(stderr, "scene: %s\n", err.message);
        exit(3);
    }
    return l;
}

static tg_request small_request(int w, int h, int frames)
{
    tg_request q;
    tg_request_defaults(&q);
    q.width = w;
    q.height = h;
    q.frames = frames;
    q.shadow_map_size = TG_MIN_SHADOW_MAP * 2;
    q.samples = 4;
    q.aovs = (1u << TG_AOV_COUNT) - 1u;
    return q;
}

static int finite_real(tg_real v)
{
    float f = tg_to_float(v);
    return f == f && f <= 3.402823466e+38f && f >= -3.402823466e+38f;
}

/* Every requested AOV of the frame, row by row into exact-size buffers:
 * finite, colour and irradiance >= 0, AO in [0, 1]; returns the count of
 * bad values. */
static long check_outputs(const tg_frame *frame, const tg_plan *plan)
{
    int w = plan->request.width, h = plan->request.height, a, y, i;
    long bad = 0;
    for (a = 0; a < TG_AOV_COUNT; a++) {
        int c = tg_aov_channels((tg_aov)a);
        guarded row = guard_alloc((size_t)w * (size_t)c * sizeof(tg_real), 0);
        guarded row8 = guard_alloc((size_t)w * 3u, 0);
        if (!(plan->request.aovs & (1u << a))) { guard_free(&row); guard_free(&row8); continue; }
        for (y = 0; y < h; y++) {
            const tg_real *v = (const tg_real *)row.p;
            if (tg_frame_aov_row(frame, (tg_aov)a, y, (tg_real *)row.p) != TG_OK ||
                tg_frame_aov_row8(frame, (tg_aov)a, y, row8.p) != TG_OK) bad++;
            for (i = 0; i < w * c; i++) {
                int nonneg = a == TG_AOV_COLOR || a == TG_AOV_IRRADIANCE || a == TG_AOV_DIRECT ||
                             a == TG_AOV_NEAR || a == TG_AOV_AO || a == TG_AOV_DEPTH;
                if (!finite_real(v[i]) || (nonneg && v[i] < 0) || (a == TG_AOV_AO && v[i] > TG_ONE)) {
                    if (bad < 5) fprintf(stderr, "  %s row %d value %d: %g\n", tg_aov_name((tg_aov)a), y, i, check_d(v[i]));
                    bad++;
                }
            }
        }
        if (!guard_intact(&row) || !guard_intact(&row8)) {
            fprintf(stderr, "  %s: a row wrote outside its buffer\n", tg_aov_name((tg_aov)a));
            bad++;
        }
        guard_free(&row);
        guard_free(&row8);
    }
    return bad;
}

/* Plan, create in guarded memory at `offset`, render frames 0..n-1 and
 * check every output and the guard; returns the plan's status. */
static tg_status render_checked(const tg_scene *scene, const tg_request *q, int n, unsigned offset)
{
    tg_plan plan;
    tg_error err;
    tg_frame *frame = NULL;
    guarded mem;
    tg_status st;
    int i;
    if ((st = tg_plan_make(&plan, scene, q, &err)) != TG_OK) return st;
    mem = guard_alloc(plan.total_bytes, offset);
    st = tg_frame_create(&plan, mem.p, mem.size, &frame, &err);
    CHECK(st == TG_OK && frame, "create %zu bytes at +%u: %s", plan.total_bytes, offset, err.message);
    for (i = 0; st == TG_OK && i < n; i++) {
        st = tg_frame_render(frame, i, &err);
        CHECK(st == TG_OK, "render %d: %s", i, err.message);
        CHECK(check_outputs(frame, &plan) == 0, "%dx%d %s frame %d: outputs out of bounds",
              q->width, q->height, tg_technique_name(q->technique), i);
    }
    CHECK(guard_intact(&mem), "the frame wrote outside its %zu bytes at +%u", mem.size, offset);
    guard_free(&mem);
    return TG_OK;
}

/* ==== the number type ========================================================= */

/* Inputs no caller should send, and some they will. */
static tg_real extremes[24];
static int extreme_count;

static void make_extremes(void)
{
    static const float finite[] = { 0.0f, 1e-6f, -1e-6f, 0.5f, -1.0f, 1.0f, 1.5707963f, -3.1415926f,
                                     100.0f, -1000.0f, 30000.0f, -32767.0f };
    size_t i;
    extreme_count = 0;
    for (i = 0; i < sizeof finite / sizeof finite[0]; i++) extremes[extreme_count++] = tg_from_float(finite[i]);
    extremes[extreme_count++] = TG_REAL_MAX;
    extremes[extreme_count++] = TG_REAL_MIN;
    extremes[extreme_count++] = TG_EPS;
    extremes[extreme_count++] = tg_neg(TG_EPS);
#if !TG_FIXED
    extremes[extreme_count++] = 1e-40f;                 /* subnormal */
    extremes[extreme_count++] = 1e30f;
    extremes[extreme_count++] = -1e30f;
#endif
}

/* The functions documented for any x give finite results in their ranges. */
TEST(real_functions_at_extremes)
{
    int i, j;
    make_extremes();
    for (i = 0; i < extreme_count; i++) {
        tg_real x = extremes[i], r;
        double d = check_d(x);
        r = tg_sin(x); CHECK(finite_real(r) && tg_abs(r) <= TG_ONE, "sin(%g) = %g", d, check_d(r));
        r = tg_cos(x); CHECK(finite_real(r) && tg_abs(r) <= TG_ONE, "cos(%g) = %g", d, check_d(r));
        r = tg_acos(x); CHECK(finite_real(r) && r >= 0 && r <= TG_PI, "acos(%g) = %g", d, check_d(r));
        r = tg_asin(x); CHECK(finite_real(r) && tg_abs(r) <= TG_HALF_PI, "asin(%g) = %g", d, check_d(r));
        r = tg_exp2(x); CHECK(finite_real(r) && r >= 0, "exp2(%g) = %g", d, check_d(r));
        r = tg_log2(x); CHECK(finite_real(r) && (x > 0 || r == TG_REAL_MIN), "log2(%g) = %g", d, check_d(r));
        r = tg_floor(x); CHECK(finite_real(r) && r <= x, "floor(%g) = %g", d, check_d(r));
        r = tg_sqrt(x); CHECK(finite_real(r) && r >= 0 && (x > 0 || r == 0), "sqrt(%g) = %g", d, check_d(r));
        r = tg_rsqrt(x); CHECK(r >= 0 && (x > 0 || r == TG_REAL_MAX), "rsqrt(%g) = %g", d, check_d(r));
        if (x >= 0) { r = tg_pow(x, TG_R(2.5f)); CHECK(finite_real(r) && r >= 0, "pow(%g, 2.5) = %g", d, check_d(r)); }
        for (j = 0; j < extreme_count; j++) {
            tg_real y = extremes[j];
            r = tg_atan2(x, y);
            CHECK(finite_real(r) && tg_abs(r) <= TG_PI, "atan2(%g, %g) = %g", d, check_d(y), check_d(r));
            r = tg_smoothstep(x, y, TG_R(0.25f));
            CHECK(finite_real(r) && r >= 0 && r <= TG_ONE, "smoothstep(%g, %g, 0.25) = %g", d, check_d(y), check_d(r));
            if (x >= 0) {
                r = tg_pow(x, y);
                CHECK(finite_real(r) && r >= 0, "pow(%g, %g) = %g", d, check_d(y), check_d(r));
            }
        }
    }
}

#if !TG_FIXED
/* NaN and the infinities (float only): the functions that clamp their
 * argument or document "any x" answer finitely; none hangs. */
TEST(real_functions_nan_and_inf)
{
    float bad[3];
    int i;
    bad[0] = tg_from_float(1e30f) * 1e30f;   /* inf */
    bad[1] = -bad[0];
    bad[2] = bad[0] - bad[0];                /* NaN */
    for (i = 0; i < 3; i++) {
        tg_real x = bad[i], r;
        r = tg_sin(x); CHECK(finite_real(r), "sin(%g) = %g", (double)x, (double)r);
        r = tg_cos(x); CHECK(finite_real(r), "cos(%g) = %g", (double)x, (double)r);
        r = tg_acos(x); CHECK(finite_real(r) && r >= 0 && r <= TG_PI, "acos(%g) = %g", (double)x, (double)r);
        r = tg_asin(x); CHECK(finite_real(r), "asin(%g) = %g", (double)x, (double)r);
        r = tg_atan2(x, 1.0f); CHECK(tg_abs(r) <= TG_PI || r != r, "atan2(%g, 1) = %g", (double)x, (double)r);
        r = tg_atan2(1.0f, x); CHECK(tg_abs(r) <= TG_PI || r != r, "atan2(1, %g) = %g", (double)x, (double)r);
        (void)tg_exp2(x); (void)tg_log2(x); (void)tg_floor(x); (void)tg_sqrt(x); (void)tg_rsqrt(x);
        (void)tg_pow(1.0f, x); (void)tg_tan(x); (void)tg_smoothstep(0.0f, 1.0f, x);
    }
}
#endif

/* tg_parse_real: never reads past `len`, returns at most `len`, NULL out
 * and overflow allowed, saturates with *overflow set. */
static size_t parse_exact(const char *s, size_t len, tg_real *out, int *ovf)
{
    guarded g = guard_alloc(len, 0);
    size_t used;
    memcpy(g.p, s, len);
    used = tg_parse_real((const char *)g.p, len, out, ovf);
    CHECK(guard_intact(&g), "wrote around the text");
    guard_free(&g);
    CHECK(used <= len, "used %zu of %zu bytes", used, len);
    return used;
}

TEST(parse_real_hostile)
{
    static const char *const junk[] = { "", "-", "+", ".", "-.", "e5", ".e1", "+-1", "--1", "nan", "inf", "x1" };
    tg_real v;
    int ovf, i;
    char *big;
    size_t n;
    for (i = 0; i < (int)(sizeof junk / sizeof junk[0]); i++)
        CHECK(parse_exact(junk[i], strlen(junk[i]), &v, &ovf) == 0, "'%s' is no number", junk[i]);
    CHECK(tg_parse_real("7", 0, &v, &ovf) == 0, "len 0 reads nothing");
    CHECK(parse_exact("0x10", 4, &v, &ovf) == 1 && v == 0, "hex is a 0 and junk");
    CHECK(parse_exact("1.5e3x", 6, &v, &ovf) == 5 && check_d(v) == 1500.0 && !ovf, "prefix number: %g", check_d(v));
    CHECK(parse_exact("1e", 2, &v, &ovf) == 1 && v == TG_ONE, "exponent without digits");
    CHECK(parse_exact("25", 1, &v, &ovf) == 1 && v == tg_from_int(2), "stops at len");
    CHECK(parse_exact("2", 1, NULL, NULL) == 1, "out and overflow may be NULL");
    CHECK(parse_exact("1e99999999999999999999", 22, &v, &ovf) == 22 && ovf && v == TG_REAL_MAX, "huge exponent: %g", check_d(v));
    CHECK(parse_exact("-1e99999999999999999999", 23, &v, &ovf) == 23 && ovf && v == TG_REAL_MIN, "huge negative");
    CHECK(parse_exact("1e-99999999999999999999", 23, &v, &ovf) == 23 && !ovf && v == 0, "tiny: %g", check_d(v));
    n = 100000;                                   /* 1 and 99999 zeros, then 0.000...1 */
    big = (char *)malloc(n);
    memset(big, '0', n);
    big[0] = '1';
    CHECK(parse_exact(big, n, &v, &ovf) == n && ovf && v == TG_REAL_MAX, "10^99999 saturates");
    big[0] = '0'; big[1] = '.'; big[n - 1] = '1';
    CHECK(parse_exact(big, n, &v, &ovf) == n && !ovf && v == 0, "10^-99998 is 0: %g", check_d(v));
    free(big);
}

/* ==== errors, the arena, sizes ================================================ */

TEST(error_format_any_size)
{
    tg_error err;
    char full[700];
    size_t len, size, i;
    memset(&err, 0, sizeof err);
    memset(err.file, 'f', sizeof err.file - 1);
    memset(err.message, 'm', sizeof err.message - 1);
    err.line = INT_MAX;
    err.col = INT_MIN;
    len = tg_error_format(&err, full, sizeof full);
    CHECK(len == strlen(full) && len > 2 * 255, "full length %zu", len);
    CHECK(tg_error_format(&err, NULL, 0) == len, "NULL buffer with size 0 counts the length");
    for (size = 1; size <= len + 1; size += (size < 40 || size > len - 4) ? 1 : 37) {
        guarded g = guard_alloc(size, 3);
        CHECK(tg_error_format(&err, (char *)g.p, size) == len, "size %zu: returns the full length", size);
        CHECK(memchr(g.p, 0, size) != NULL, "size %zu: NUL-terminated", size);
        CHECK(memcmp(g.p, full, strlen((char *)g.p)) == 0 && strlen((char *)g.p) == (size - 1 < len ? size - 1 : len),
              "size %zu: a prefix of the message", size);
        CHECK(guard_intact(&g), "size %zu: wrote outside", size);
        guard_free(&g);
    }
    memset(&err, 0, sizeof err);                 /* a zeroed error formats */
    err.line = -5;
    CHECK(tg_error_format(&err, full, sizeof full) == strlen("error: ") && strcmp(full, "error: ") == 0, "zeroed: '%s'", full);
    for (i = 0; i < 2; i++) {                   /* negative line/col: no garbage numbers */
        memset(&err, 0, sizeof err);
        strcpy(err.file, "a.scene");
        err.line = i ? 3 : -3;
        err.col = -7;
        tg_error_format(&err, full, sizeof full);
        CHECK(strstr(full, "-") == NULL, "negative line or column printed: '%s'", full);
    }
}

TEST(arena_hostile)
{
    tg_arena a;
    unsigned off;
    size_t s, out = 12345;
    unsigned char *p;
    tg_arena_init(&a, NULL, SIZE_MAX);
    CHECK(a.size == 0 && tg_arena_alloc(&a, 0) == NULL, "NULL memory is an empty arena");
    CHECK(tg_arena_alloc(&a, 1) == NULL && a.failed_request == 1, "nothing fits in no memory");
    for (off = 0; off < 16; off++) {
        for (s = 0; s <= 48; s++) {
            guarded g = guard_alloc(s, off);
            size_t k;
            tg_arena_init(&a, g.p, s);
            for (k = 0; k < 6; k++) {
                p = (unsigned char *)tg_arena_alloc(&a, k * 5);
                if (!p) continue;
                CHECK(((uintptr_t)p & 15u) == 0, "+%u size %zu: misaligned block", off, s);
                CHECK(p >= g.p && p + k * 5 <= g.p + s, "+%u size %zu: block outside", off, s);
                if (k) memset(p, 0x11, k * 5);
            }
            CHECK(a.used <= s, "+%u size %zu: used %zu", off, s, a.used);
            CHECK(tg_arena_alloc(&a, SIZE_MAX) == NULL && tg_arena_alloc(&a, SIZE_MAX - 15) == NULL &&
                  tg_arena_alloc(&a, s + 1) == NULL, "+%u size %zu: impossible sizes refused", off, s);
            CHECK(a.failed_request == SIZE_MAX, "failed_request keeps the largest");
            CHECK(guard_intact(&g), "+%u size %zu: wrote outside", off, s);
            guard_free(&g);
        }
    }
    CHECK(tg_size_mul(SIZE_MAX, 2, &out) == 1 && out == 12345, "SIZE_MAX * 2 overflows, *out untouched");
    CHECK(tg_size_mul(SIZE_MAX / 2 + 1, 2, &out) == 1, "2^63 * 2 overflows");
    CHECK(tg_size_mul(0, SIZE_MAX, &out) == 0 && out == 0, "0 * SIZE_MAX");
    CHECK(tg_size_mul(SIZE_MAX, 1, &out) == 0 && out == SIZE_MAX, "SIZE_MAX * 1");
    CHECK(tg_size_add(SIZE_MAX, 1, &out) == 1 && out == SIZE_MAX, "SIZE_MAX + 1 overflows");
    CHECK(tg_size_add(SIZE_MAX, 0, &out) == 0 && out == SIZE_MAX, "SIZE_MAX + 0");
}

/* ==== names ==================================================================== */

TEST(names_hostile)
{
    static const int bad[] = { -1, INT_MIN, INT_MAX, 1000 };
    int i;
    for (i = 0; i < 4; i++) {
        const char *a = tg_aov_name((tg_aov)bad[i]), *t = tg_technique_name((tg_technique)bad[i]);
        int c = tg_aov_channels((tg_aov)bad[i]);
        CHECK(a && strcmp(a, "?") == 0, "aov %d: '%s'", bad[i], a ? a : "(null)");
        CHECK(t && strcmp(t, "?") == 0, "technique %d: '%s'", bad[i], t ? t : "(null)");
        CHECK(c == 1 || c == 3, "channels of aov %d: %d", bad[i], c);
        CHECK(tg_builtin_name(bad[i]) == NULL, "builtin %d", bad[i]);
    }
    CHECK(strcmp(tg_aov_name(TG_AOV_COUNT), "?") == 0 && strcmp(tg_technique_name(TG_TECH_COUNT), "?") == 0, "COUNT");
    CHECK(tg_aov_from_name("") == -1 && tg_aov_from_name("COLOR") == -1 && tg_aov_from_name("color ") == -1, "aov names are exact");
    CHECK(tg_technique_from_name("") == -1 && tg_technique_from_name("hbil2") == -1, "technique names are exact");
    CHECK(tg_builtin_scene(NULL) == NULL && tg_builtin_scene("") == NULL && tg_builtin_scene("builtin:") == NULL,
          "no builtin scene for NULL or ''");
    CHECK(tg_builtin_scene("builtin:cornell") == tg_builtin_scene("cornell") && tg_builtin_scene("cornell"), "builtin: prefix");
    for (i = 0; tg_builtin_name(i); i++)
        CHECK(tg_builtin_scene(tg_builtin_name(i)) != NULL, "builtin %d has text", i);
    CHECK(i >= 1, "there are builtins");
    for (i = 0; i < TG_AOV_COUNT; i++)
        CHECK(tg_aov_from_name(tg_aov_name((tg_aov)i)) == i, "aov %d round trip", i);
    for (i = 0; i < TG_TECH_COUNT; i++)
        CHECK(tg_technique_from_name(tg_technique_name((tg_technique)i)) == i, "technique %d round trip", i);
}

/* Defaults over garbage give a request every builtin plans. */
TEST(request_defaults_over_garbage)
{
    tg_request q;
    int i;
    memset(&q, 0xFF, sizeof q);
    tg_request_defaults(&q);
    for (i = 0; tg_builtin_name(i); i++) {
        loaded l = load(tg_builtin_scene(tg_builtin_name(i)));
        tg_plan plan;
        tg_error err;
        CHECK(tg_plan_make(&plan, l.scene, &q, &err) == TG_OK && plan.total_bytes > 0, "%s: %s", tg_builtin_name(i), err.message);
        free(l.mem);
    }
}

/* ==== tg_scene_parse ============================================================ */

static unsigned char scene_mem[1u << 20];

/* Parse into scene_mem; a failed parse leaves the arena's use unchanged. */
static tg_status parse_in(const char *text, size_t size, const tg_io *io, tg_scene **s, tg_error *err)
{
    tg_arena a;
    tg_status st;
    tg_arena_init(&a, scene_mem, sizeof scene_mem);
    a.used = 48;
    st = tg_scene_parse(text, size, "h.scene", io, &a, s, err);
    CHECK(st == TG_OK || (a.used == 48 && *s == NULL), "a failed parse (status %d) used the arena: %zu", st, a.used);
    return st;
}

/* A message quotes the input (a name, a file name): its control bytes come
 * out as \xNN, so an escape sequence in a scene (ESC [ 2 J: clear the
 * screen) never reaches a terminal through an error.  Before, the bytes
 * were copied as they were. */
TEST(error_messages_escape_control_bytes)
{
    static const char text[] = "camera pos 0 1 -3 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\n"
                               "quad p0 0 0 0 p1 1 0 0 p2 1 1 0 p3 0 1 0 material nope\033[2J\a\n";
    tg_arena a;
    tg_scene *sc = NULL;
    tg_error err;
    char shown[600];
    size_t i, n;
    int raw = 0;
    tg_arena_init(&a, scene_mem, sizeof scene_mem);
    CHECK(tg_scene_parse(text, sizeof text - 1, "bad\033]0;title\a.scene", NULL, &a, &sc, &err) == TG_ERR_INPUT,
          "an undefined material refused");
    n = tg_error_format(&err, shown, sizeof shown);
    for (i = 0; i < n && i < sizeof shown - 1; i++) raw += (unsigned char)shown[i] < 0x20 || shown[i] == 0x7f;
    CHECK(raw == 0, "%d control bytes in '%s'", raw, shown);
    CHECK(strstr(shown, "nope\\x1b[2J\\x07") != NULL, "the name escaped: '%s'", shown);
    CHECK(strstr(shown, "bad\\x1b]0;title\\x07.scene:") == shown, "the file name escaped: '%s'", shown);
}

TEST(scene_parse_missing_arguments)
{
    const char *text = tg_builtin_scene("plane");
    tg_arena a;
    tg_scene *s = (tg_scene *)&a;
    tg_error err;
    tg_status st;
    tg_arena_init(&a, scene_mem, sizeof scene_mem);
    st = tg_scene_parse(text, strlen(text), "h.scene", NULL, NULL, &s, &err);
    CHECK(st == TG_ERR_RUNTIME && s == NULL && err.message[0], "NULL arena: %d '%s'", st, err.message);
    st = tg_scene_parse(text, strlen(text), "h.scene", NULL, &a, NULL, &err);
    CHECK(st == TG_ERR_RUNTIME && a.used == 0, "NULL scene: %d", st);
    st = tg_scene_parse(NULL, 10, "h.scene", NULL, &a, &s, &err);
    CHECK(st == TG_ERR_RUNTIME && s == NULL && a.used == 0, "NULL text with a size: %d", st);
    st = tg_scene_parse(NULL, 0, "h.scene", NULL, &a, &s, &err);
    CHECK(st == TG_ERR_INPUT && s == NULL && a.used == 0, "NULL text, size 0 (an empty scene): %d '%s'", st, err.message);
    st = tg_scene_parse(text, strlen(text), NULL, NULL, &a, &s, NULL);
    CHECK(st == TG_OK && s != NULL, "NULL filename and err: %d", st);
    st = tg_scene_parse("camera pos 0 0 0\n", 17, NULL, NULL, &a, &s, NULL);
    CHECK(st == TG_ERR_INPUT && s == NULL, "a bad scene with NULL err: %d", st);
    st = tg_scene_parse("junk\n", 5, NULL, NULL, &a, &s, &err);
    CHECK(st == TG_ERR_INPUT && strncmp(err.file, "<scene>", 7) == 0, "NULL filename in messages: '%s'", err.file);
}

/* Sizes past the file limit are refused before a byte is read: the text
 * here is 8 bytes long, its size claims more. */
TEST(scene_parse_sizes)
{
    guarded g = guard_alloc(8, 0);
    tg_scene *s;
    tg_error err;
    size_t sizes[3];
    int i;
    memcpy(g.p, "camera\n\n", 8);
    sizes[0] = (size_t)TG_MAX_FILE_BYTES + 1;
    sizes[1] = SIZE_MAX;
    sizes[2] = SIZE_MAX / 2 + 1;
    for (i = 0; i < 3; i++) {
        tg_status st = parse_in((const char *)g.p, sizes[i], NULL, &s, &err);
        CHECK(st == TG_ERR_INPUT && strstr(err.message, "must be") && s == NULL, "size %zu: %d '%s'", sizes[i], st, err.message);
    }
    guard_free(&g);
}

/* Texts without a terminating NUL, cut anywhere: parsed or refused with a
 * position inside the text, never read past it. */
TEST(scene_text_cut_anywhere)
{
    const char *text = tg_builtin_scene("cornell");
    size_t n = strlen(text), k;
    int ok = 0;
    for (k = 0; k <= n; k += (k < 200 || k + 40 > n) ? 1 : 7) {
        guarded g = guard_alloc(k, 0);
        tg_scene *s;
        tg_error err;
        tg_status st;
        memcpy(g.p, text, k);
        st = parse_in((const char *)g.p, k, NULL, &s, &err);
        CHECK(st == TG_OK || (st == TG_ERR_INPUT && err.line >= 0 && s == NULL), "cut at %zu: %d", k, st);
        ok += st == TG_OK;
        guard_free(&g);
    }
    CHECK(ok >= 1, "the whole text parses");
}

/* Bytes no text editor writes. */
TEST(scene_text_hostile_bytes)
{
    static const char *const texts[] = {
        "\xEF\xBB\xBF", "\xFF\xFE\x00\x01", "camera\rpos 0 1 -3\r\rtarget 0 0 0\r",
        "camera pos 0 1 -3 target 0 0 0 fov 1e39\n", "camera pos nan 1 -3 target 0 0 0\n",
        "camera pos 0 1 -3 target 0 1 -3\n", "gi radius -0\n", "effects\n", "light\n",
        "camera pos 0 1 -3 target 0 0 0\nmaterial m albedo 1 1 1\nsphere center 0 0 0 radius 1e-30 material m\n",
        "camera pos 0 1 -3 target 0 0 0\nmaterial m albedo 1 1 1\nbox min 1 1 1 max 1 1 1 material m\n",
        "camera pos 0 1 -3 target 0 0 0\nenv sh9 1 2 3\n",
        "camera pos 0 1 -3 target 0 0 0\nobject_key name x t 0\n",
    };
    size_t i, n;
    char *line;
    for (i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        size_t len = strlen(texts[i]) + (i == 1 ? 3 : 0);
        guarded g = guard_alloc(len, 0);
        tg_scene *s;
        tg_error err;
        tg_status st;
        char msg[600];
        memcpy(g.p, texts[i], len);
        st = parse_in((const char *)g.p, len, NULL, &s, &err);
        CHECK(st == TG_OK || st == TG_ERR_INPUT, "text %zu: status %d", i, st);
        if (st != TG_OK) CHECK(tg_error_format(&err, msg, sizeof msg) < sizeof msg && err.message[0], "text %zu: a message", i);
        guard_free(&g);
    }
    for (n = (size_t)TG_MAX_LINE; n <= (size_t)TG_MAX_LINE + 1; n++) {   /* the longest line, and one byte more */
        tg_scene *s;
        tg_error err;
        line = (char *)malloc(n);
        memset(line, ' ', n);
        CHECK(parse_in(line, n, NULL, &s, &err) == TG_ERR_INPUT, "a blank scene is refused");
        if (n > TG_MAX_LINE) CHECK(err.col == TG_MAX_LINE + 1 && strstr(err.message, "line length"), "long line: col %d", err.col);
        else CHECK(!strstr(err.message, "line length"), "%zu bytes is not too long: %s", n, err.message);
        free(line);
    }
}

/* The arena one byte short at every base alignment: TG_ERR_MEMORY naming
 * the same need; the exact need parses; nothing outside is written. */
TEST(scene_arena_short_by_one)
{
    int i;
    unsigned off;
    for (i = 0; tg_builtin_name(i); i++) {
        const char *text = tg_builtin_scene(tg_builtin_name(i));
        for (off = 0; off < 16; off++) {
            guarded g = guard_alloc(0, off);
            tg_arena a;
            tg_scene *s;
            tg_error err;
            size_t need;
            tg_arena_init(&a, g.p, 0);
            CHECK(tg_scene_parse(text, strlen(text), "b", NULL, &a, &s, &err) == TG_ERR_MEMORY, "empty arena");
            need = err.bytes_needed;
            guard_free(&g);
            g = guard_alloc(need - 1, off);
            tg_arena_init(&a, g.p, need - 1);
            CHECK(tg_scene_parse(text, strlen(text), "b", NULL, &a, &s, &err) == TG_ERR_MEMORY && err.bytes_needed == need && !s,
                  "%s +%u: %zu - 1 bytes", tg_builtin_name(i), off, need);
            CHECK(guard_intact(&g), "%s +%u: short arena written outside", tg_builtin_name(i), off);
            guard_free(&g);
            g = guard_alloc(need, off);
            tg_arena_init(&a, g.p, need);
            CHECK(tg_scene_parse(text, strlen(text), "b", NULL, &a, &s, &err) == TG_OK && s && a.used <= need,
                  "%s +%u: %zu bytes: %s", tg_builtin_name(i), off, need, err.message);
            CHECK(guard_intact(&g), "%s +%u: written outside", tg_builtin_name(i), off);
            guard_free(&g);
        }
    }
}

/* ---- a platform's tg_io that misbehaves ---- */
typedef struct bad_io {
    int mode, calls;
    const char *reason;
} bad_io;

static const char cube_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\n";
static const char other_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\nf 1 2 3\nf 1 2 3\nf 3 2 1\n";

static int bad_read(void *user, const char *path, const char **data, size_t *size, const char **reason)
{
    bad_io *b = (bad_io *)user;
    (void)path;
    b->calls++;
    switch (b->mode) {
    case 0: *reason = b->reason; return 1;                        /* fails with (or without) a reason */
    case 1: *data = NULL; *size = 5; return 0;                    /* "success" with no data */
    case 2: *data = cube_obj; *size = (size_t)TG_MAX_FILE_BYTES + 1; return 0; /* too large */
    case 3: *data = NULL; *size = 0; return 0;                    /* empty */
    case 4: if (b->calls & 1) { *data = cube_obj; *size = sizeof cube_obj - 1; }  /* changes between reads */
            else { *data = other_obj; *size = sizeof other_obj - 1; }
            return 0;
    default: *data = "\x7f" "ELF\x02\x01\x01"; *size = 7; return 0; /* not OBJ text */
    }
}

TEST(scene_io_misbehaves)
{
    static const char text[] = "camera pos 0 1 -3 target 0 0 0\nmaterial m albedo 1 1 1\n"
                               "mesh file a.obj material m\nmesh file b.obj material m\n";
    int mode;
    tg_io io;
    tg_scene *s;
    tg_error err;
    tg_status st;
    bad_io b;
    io.user = &b;
    io.read_file = NULL;
    st = parse_in(text, sizeof text - 1, &io, &s, &err);
    CHECK(st == TG_ERR_INPUT && strstr(err.message, "cannot read"), "read_file NULL: %d '%s'", st, err.message);
    io.read_file = bad_read;
    for (mode = 0; mode <= 5; mode++) {
        memset(&b, 0, sizeof b);
        b.mode = mode;
        b.reason = "permission denied";
        st = parse_in(text, sizeof text - 1, &io, &s, &err);
        CHECK(st == TG_OK || st == TG_ERR_INPUT || st == TG_ERR_RUNTIME, "mode %d: status %d", mode, st);
        CHECK(st == TG_OK || err.message[0], "mode %d: no message", mode);
        if (mode == 0) CHECK(st == TG_ERR_INPUT && strstr(err.message, "permission denied"), "the reason: '%s'", err.message);
        if (mode == 1 || mode == 2) CHECK(st == TG_ERR_INPUT, "mode %d refused: %d", mode, st);
    }
    memset(&b, 0, sizeof b);                     /* a failure with no reason */
    st = parse_in(text, sizeof text - 1, &io, &s, &err);
    CHECK(st == TG_ERR_INPUT && strstr(err.message, "a.obj"), "no reason: '%s'", err.message);
}

/* ==== tg_plan_make: every request field past its limits ========================== */

static loaded all_effects;

static const tg_scene *scene_everything(void)
{
    if (!all_effects.scene) all_effects = load(everything);
    return all_effects.scene;
}

/* TG_ERR_INPUT and "FIELD must be LO..HI, got V". */
static void expect_refused(const tg_request *q, const char *field, const char *what)
{
    tg_plan plan;
    tg_error err;
    tg_status st = tg_plan_make(&plan, scene_everything(), q, &err);
    CHECK(st == TG_ERR_INPUT, "%s: status %d, not refused", what, st);
    CHECK(strncmp(err.message, field, strlen(field)) == 0 && strstr(err.message, " must be ") &&
          strstr(err.message, ", got "), "%s: message '%s' does not say '%s must be LO..HI, got V'",
          what, err.message, field);
    CHECK(tg_plan_make(&plan, scene_everything(), q, NULL) == TG_ERR_INPUT, "%s: refused with NULL err too", what);
}

/* Accepted and (when `n`) rendered n frames, every output in bounds. */
static void expect_accepted(const tg_request *q, int n, const char *what)
{
    tg_plan plan;
    tg_error err;
    tg_status st = tg_plan_make(&plan, scene_everything(), q, &err);
    CHECK(st == TG_OK, "%s: refused: %s", what, err.message);
    if (st == TG_OK && n > 0) render_checked(scene_everything(), q, n, 0);
}

#define FIELD_REFUSED(field, v) do { \
        tg_request fq = small_request(8, 6, 2); fq.field = (v); \
        expect_refused(&fq, #field, #field " = " #v); } while (0)
#define FIELD_ACCEPTED(field, v, n) do { \
        tg_request fq = small_request(8, 6, 2); fq.field = (v); \
        expect_accepted(&fq, n, #field " = " #v); } while (0)

TEST(request_size_refused)
{
    FIELD_REFUSED(width, 0);
    FIELD_REFUSED(width, -1);
    FIELD_REFUSED(width, INT_MIN);
    FIELD_REFUSED(width, TG_MAX_IMAGE_SIDE + 1);
    FIELD_REFUSED(width, INT_MAX);
    FIELD_REFUSED(height, 0);
    FIELD_REFUSED(height, INT_MIN);
    FIELD_REFUSED(height, INT_MAX);
    {
        tg_request q = small_request(TG_MAX_IMAGE_SIDE, (int)(TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE) + 1, 1);
        expect_refused(&q, "pixels", "more than TG_MAX_IMAGE_PIXELS");
    }
}

TEST(request_size_extremes_render)
{
    tg_request q = small_request(1, 1, 2);
    expect_accepted(&q, 2, "1x1");
    q = small_request(TG_MAX_IMAGE_SIDE, 1, 1);
    q.aovs = 1u << TG_AOV_COLOR;
    expect_accepted(&q, 1, "widest");
    q = small_request(1, 97, 1);
    expect_accepted(&q, 1, "1x97");
    q = small_request(TG_MAX_IMAGE_SIDE, (int)(TG_MAX_IMAGE_PIXELS / TG_MAX_IMAGE_SIDE), 1);
    expect_accepted(&q, 0, "TG_MAX_IMAGE_PIXELS (planned only)");
}

TEST(request_frames_and_aovs_refused)
{
    tg_request q = small_request(8, 6, 2);
    FIELD_REFUSED(frames, 0);
    FIELD_REFUSED(frames, -1);
    FIELD_REFUSED(frames, INT_MIN);
    FIELD_REFUSED(frames, TG_MAX_FRAMES + 1);
    FIELD_REFUSED(frames, INT_MAX);
    q.aovs = 1u << TG_AOV_COUNT;
    expect_refused(&q, "aovs", "aovs = 1 << TG_AOV_COUNT");
    q.aovs = 0xFFFFFFFFu;
    expect_refused(&q, "aovs", "aovs = all bits");
    FIELD_REFUSED(technique, (tg_technique)-1);
    FIELD_REFUSED(technique, TG_TECH_COUNT);
    FIELD_REFUSED(technique, (tg_technique)INT_MAX);
}

TEST(request_gi_settings_refused)
{
    FIELD_REFUSED(slices, TG_MAX_SLICES + 1);
    FIELD_REFUSED(slices, INT_MAX);
    FIELD_REFUSED(samples, TG_MAX_SAMPLES + 1);
    FIELD_REFUSED(samples, INT_MAX);
    FIELD_REFUSED(bounces, TG_MAX_BOUNCES + 1);
    FIELD_REFUSED(bounces, 1000000);
    FIELD_REFUSED(bounces, INT_MAX);
    FIELD_REFUSED(radius, TG_R(-0.5f));
    FIELD_REFUSED(radius, TG_REAL_MIN);
    FIELD_REFUSED(radius, tg_add(tg_from_int(TG_MAX_RADIUS), TG_ONE));
    FIELD_REFUSED(exposure, TG_R(-1.0f));
    FIELD_REFUSED(exposure, TG_REAL_MIN);
    FIELD_REFUSED(exposure, tg_add(tg_from_int(TG_MAX_EXPOSURE), TG_ONE));
#if TG_FIXED
    FIELD_REFUSED(radius, TG_REAL_MAX);
    FIELD_REFUSED(exposure, TG_REAL_MAX);
#else
    {
        float inf = tg_from_float(1e30f) * 1e30f, nan = inf - inf;
        FIELD_REFUSED(radius, nan);
        FIELD_REFUSED(radius, inf);
        FIELD_REFUSED(radius, -inf);
        FIELD_REFUSED(exposure, nan);
        FIELD_REFUSED(exposure, inf);
        FIELD_REFUSED(exposure, -inf);
    }
#endif
}

TEST(request_switches_and_shadow_map_refused)
{
    FIELD_REFUSED(interleave, 2);
    FIELD_REFUSED(interleave, -1);
    FIELD_REFUSED(gi_scale, 0);
    FIELD_REFUSED(gi_scale, 3);
    FIELD_REFUSED(gi_scale, INT_MIN);
    FIELD_REFUSED(temporal, 2);
    FIELD_REFUSED(temporal, -1);
    FIELD_REFUSED(far_mode, 2);
    FIELD_REFUSED(far_mode, -1);
    FIELD_REFUSED(shadow_pcf, 2);
    FIELD_REFUSED(shadow_pcf, INT_MAX);
    FIELD_REFUSED(shadow_map_size, 1);
    FIELD_REFUSED(shadow_map_size, TG_MIN_SHADOW_MAP - 1);
    FIELD_REFUSED(shadow_map_size, TG_MAX_SHADOW_MAP + 1);
    FIELD_REFUSED(shadow_map_size, 13378);        /* overflowed a 32-bit shadow-map size */
    FIELD_REFUSED(shadow_map_size, 1518500250);   /* ... and a 64-bit one (heap overflow) */
    FIELD_REFUSED(shadow_map_size, INT_MAX);
}

/* The values at the limits, and "unset" ones, plan and render finitely. */
TEST(request_limits_render)
{
    tg_request q;
    FIELD_ACCEPTED(slices, TG_MAX_SLICES, 1);
    FIELD_ACCEPTED(slices, -5, 0);                     /* unset */
    FIELD_ACCEPTED(samples, TG_MAX_SAMPLES, 1);
    FIELD_ACCEPTED(samples, INT_MIN, 0);                /* unset */
    FIELD_ACCEPTED(bounces, TG_MAX_BOUNCES, 1);
    FIELD_ACCEPTED(bounces, 0, 1);
    FIELD_ACCEPTED(bounces, -1, 0);                     /* unset */
    FIELD_ACCEPTED(radius, 0, 1);
    FIELD_ACCEPTED(radius, tg_from_int(TG_MAX_RADIUS), 1);
    FIELD_ACCEPTED(radius, TG_R(-1.0f), 0);             /* unset */
    FIELD_ACCEPTED(exposure, 0, 1);
    FIELD_ACCEPTED(exposure, tg_from_int(TG_MAX_EXPOSURE), 1);
    FIELD_ACCEPTED(shadow_map_size, TG_MIN_SHADOW_MAP, 2);
    FIELD_ACCEPTED(shadow_map_size, 0, 0);              /* unset */
    FIELD_ACCEPTED(frames, TG_MAX_FRAMES, 0);
    FIELD_ACCEPTED(aovs, 0, 1);                         /* colour */
    FIELD_ACCEPTED(gi_scale, 2, 2);
    FIELD_ACCEPTED(interleave, 0, 1);
    FIELD_ACCEPTED(temporal, 0, 2);
    FIELD_ACCEPTED(far_mode, 1, 1);
    FIELD_ACCEPTED(shadow_pcf, 1, 1);
    q = small_request(8, 6, 2);
    q.shadow_map_size = TG_MAX_SHADOW_MAP;
    expect_accepted(&q, 0, "largest shadow map (planned only)");
}

/* Every technique at sizes a 4x4 interleave and a quarter-res kernel do
 * not divide. */
TEST(techniques_at_odd_sizes)
{
    static const int sizes[][2] = { { 1, 1 }, { 3, 2 }, { 5, 7 }, { 17, 1 } };
    int t, k, scale;
    for (t = 0; t < TG_TECH_COUNT; t++)
        for (k = 0; k < 4; k++)
            for (scale = 1; scale <= 2; scale++) {
                tg_request q = small_request(sizes[k][0], sizes[k][1], 2);
                q.technique = (tg_technique)t;
                q.gi_scale = scale;
                expect_accepted(&q, 2, tg_technique_name((tg_technique)t));
            }
}

TEST(plan_explain_any_size)
{
    tg_request q = small_request(8, 6, 2);
    tg_plan plan;
    tg_error err;
    size_t len, size;
    char *full;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    len = tg_plan_explain(&plan, NULL, 0);
    full = (char *)malloc(len + 1);
    CHECK(tg_plan_explain(&plan, full, len + 1) == len && strlen(full) == len, "length %zu", len);
    for (size = 1; size <= len + 1; size += size < 64 || size + 64 > len ? 1 : 61) {
        guarded g = guard_alloc(size, 5);
        CHECK(tg_plan_explain(&plan, (char *)g.p, size) == len, "size %zu: returns the full length", size);
        CHECK(memchr(g.p, 0, size) && strncmp((char *)g.p, full, size - 1) == 0, "size %zu: a prefix", size);
        CHECK(guard_intact(&g), "size %zu: wrote outside", size);
        guard_free(&g);
    }
    free(full);
}

/* ==== frames ======================================================================= */

/* The frame's memory at every base alignment: plan.total_bytes is enough
 * at each, 32 bytes fewer never is (TG_ERR_MEMORY naming total_bytes), no
 * memory at all is refused, and nothing outside the memory is touched. */
TEST(frame_memory_any_base_and_short)
{
    tg_request q = small_request(9, 7, 3);
    tg_plan plan;
    tg_error err;
    unsigned off;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    for (off = 0; off < 16; off++) {
        guarded g = guard_alloc(plan.total_bytes - 32, off);
        tg_frame *frame = (tg_frame *)&g;
        tg_status st = tg_frame_create(&plan, g.p, g.size, &frame, &err);
        CHECK(st == TG_ERR_MEMORY && frame == NULL && err.bytes_needed == plan.total_bytes,
              "+%u: %zu bytes of %zu: status %d, needed %zu", off, g.size, plan.total_bytes, st, err.bytes_needed);
        CHECK(guard_intact(&g), "+%u: a refused frame wrote outside", off);
        guard_free(&g);
        render_checked(scene_everything(), &q, 3, off);
    }
    {
        tg_frame *frame;
        unsigned char byte;
        CHECK(tg_frame_create(&plan, NULL, plan.total_bytes, &frame, &err) == TG_ERR_MEMORY && !frame, "NULL memory");
        CHECK(tg_frame_create(&plan, &byte, 0, &frame, &err) == TG_ERR_MEMORY && !frame, "0 bytes");
    }
}

/* The frame's memory at every size short of plan.total_bytes, for plans
 * whose layout carves different groups (shadow maps, shadow rays and their
 * BVH, the game loop's scene state, the reference, quarter resolution):
 * each is TG_ERR_MEMORY naming total_bytes, with no frame, whichever buffer
 * the memory runs out at (within the 16 bytes of alignment slack a frame
 * may fit, and then renders in what it was given).  (Layout carved on past the buffer that did not
 * fit: a light's shadow descriptor was set up through a null pointer, found
 * by fuzz_api-fixed.) */
TEST(frame_memory_every_short_size)
{
    static const struct { int method, game_loop, technique, gi_scale; } cases[] = {
        { TG_SHADOWS_MAPS, 0, TG_TECH_HBIL, 1 }, { TG_SHADOWS_RAYS, 0, TG_TECH_HBIL, 1 },
        { TG_SHADOWS_RAYS, 1, TG_TECH_HBIL, 2 }, { TG_SHADOWS_AUTO, 1, TG_TECH_REFERENCE, 1 },
    };
    size_t c;
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        tg_request q = small_request(5, 4, 2);
        tg_plan plan;
        tg_error err;
        size_t size, bad = 0;
        q.shadow_method = cases[c].method;
        q.game_loop = cases[c].game_loop;
        q.technique = (tg_technique)cases[c].technique;
        q.gi_scale = cases[c].gi_scale;
        CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "case %zu: %s", c, err.message);
        for (size = 0; size < plan.total_bytes; size++) {
            unsigned char *m = (unsigned char *)malloc(size ? size : 1);
            tg_frame *frame = (tg_frame *)m;
            tg_status st;
            if (!m) { fprintf(stderr, "out of memory\n"); exit(3); }
            st = tg_frame_create(&plan, m, size, &frame, &err);
            if (st == TG_OK && size + 16 >= plan.total_bytes) {   /* the alignment slack, unused at this base */
                CHECK(tg_frame_render(frame, 0, &err) == TG_OK, "case %zu: %zu bytes: %s", c, size, err.message);
            } else if (st != TG_ERR_MEMORY || frame || err.bytes_needed != plan.total_bytes) {
                if (!bad) CHECK(0, "case %zu: %zu bytes of %zu: status %d", c, size, plan.total_bytes, st);
                bad++;
            }
            free(m);
        }
        CHECK(bad == 0, "case %zu: %zu sizes not refused", c, bad);
    }
}

/* Frames rendered in any order, past the last and at INT_MAX; negative
 * indices refused; outputs in bounds after each. */
TEST(render_indices_out_of_order)
{
    static const int order[] = { 5, 2, 0, 2, INT_MAX, 1, 3, 3 };
    tg_request q = small_request(8, 6, 4);
    tg_plan plan;
    tg_error err;
    tg_frame *frame;
    guarded g;
    size_t i;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    g = guard_alloc(plan.total_bytes, 0);
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_OK, "%s", err.message);
    CHECK(check_outputs(frame, &plan) == 0, "outputs read before any render are in bounds");
    CHECK(tg_frame_render(frame, -1, &err) == TG_ERR_INPUT && strstr(err.message, "index"), "index -1: '%s'", err.message);
    CHECK(tg_frame_render(frame, INT_MIN, NULL) == TG_ERR_INPUT, "index INT_MIN, NULL err");
    for (i = 0; i < sizeof order / sizeof order[0]; i++) {
        CHECK(tg_frame_render(frame, order[i], NULL) == TG_OK, "index %d", order[i]);
        CHECK(check_outputs(frame, &plan) == 0, "after index %d", order[i]);
    }
    CHECK(guard_intact(&g), "wrote outside the frame");
    guard_free(&g);
}

/* AOVs the request did not ask for, and unknown ones, read as the
 * documented values (zeros; ao 1, cone pi/2) into exactly their row. */
TEST(aov_not_requested_or_unknown)
{
    static const int unknown[] = { -1, TG_AOV_COUNT, INT_MAX };
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame;
    guarded g, row;
    int i, a, w = 8;
    q.aovs = 1u << TG_AOV_DEPTH;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    g = guard_alloc(plan.total_bytes, 0);
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_OK, "%s", err.message);
    CHECK(tg_frame_render(frame, 0, &err) == TG_OK, "%s", err.message);
    for (a = 0; a < TG_AOV_COUNT; a++) {
        const tg_real *v;
        row = guard_alloc((size_t)w * (size_t)tg_aov_channels((tg_aov)a) * sizeof(tg_real), 0);
        v = (const tg_real *)row.p;
        tg_frame_aov_row(frame, (tg_aov)a, 3, (tg_real *)row.p);
        for (i = 0; i < w * tg_aov_channels((tg_aov)a); i++) {
            if (a == TG_AOV_NEAR || a == TG_AOV_FAR || a == TG_AOV_IRRADIANCE || a == TG_AOV_COLOR)
                CHECK(v[i] == 0, "%s not computed reads %g", tg_aov_name((tg_aov)a), check_d(v[i]));
            if (a == TG_AOV_AO) CHECK(v[i] == TG_ONE, "ao not computed reads %g", check_d(v[i]));
            if (a == TG_AOV_CONE) CHECK(v[i] == TG_HALF_PI, "cone not computed reads %g", check_d(v[i]));
            CHECK(finite_real(v[i]), "%s: finite", tg_aov_name((tg_aov)a));
        }
        CHECK(guard_intact(&row), "%s wrote outside its row", tg_aov_name((tg_aov)a));
        guard_free(&row);
    }
    for (i = 0; i < 3; i++) {
        size_t k;
        int c = tg_aov_channels((tg_aov)unknown[i]);
        guarded row8 = guard_alloc((size_t)w * 3u, 0);
        row = guard_alloc((size_t)w * (size_t)c * sizeof(tg_real), 0);
        tg_frame_aov_row(frame, (tg_aov)unknown[i], 2, (tg_real *)row.p);
        tg_frame_aov_row8(frame, (tg_aov)unknown[i], 2, row8.p);
        for (k = 0; k < (size_t)w; k++) CHECK(((tg_real *)row.p)[k] == 0, "aov %d: zeros", unknown[i]);
        for (k = 0; k < (size_t)w * 3u; k++) CHECK(row8.p[k] == 0, "aov %d: black", unknown[i]);
        CHECK(guard_intact(&row) && guard_intact(&row8), "aov %d wrote outside its row", unknown[i]);
        guard_free(&row);
        guard_free(&row8);
    }
    guard_free(&g);
}

/* Rows outside [0, height): refused, the row all zeros, nothing outside
 * the frame read (the frame sits at the end of its allocation). */
TEST(aov_rows_outside_refused)
{
    static const int rows[] = { -1, 6, 7, INT_MAX, INT_MIN };
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame;
    guarded g;
    int i, a, k;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    g = guard_alloc(plan.total_bytes, 0);
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_OK, "%s", err.message);
    CHECK(tg_frame_render(frame, 0, &err) == TG_OK, "%s", err.message);
    for (a = 0; a < TG_AOV_COUNT; a++)
        for (i = 0; i < 5; i++) {
            int c = tg_aov_channels((tg_aov)a);
            guarded row = guard_alloc((size_t)8 * (size_t)c * sizeof(tg_real), 0);
            guarded row8 = guard_alloc(24, 0);
            memset(row.p, 0x7F, row.size);
            memset(row8.p, 0x7F, row8.size);
            CHECK(tg_frame_aov_row(frame, (tg_aov)a, rows[i], (tg_real *)row.p) == TG_ERR_INPUT &&
                  tg_frame_aov_row8(frame, (tg_aov)a, rows[i], row8.p) == TG_ERR_INPUT,
                  "%s row %d: refused", tg_aov_name((tg_aov)a), rows[i]);
            for (k = 0; k < 8 * c; k++) CHECK(((tg_real *)row.p)[k] == 0, "%s row %d: zeros", tg_aov_name((tg_aov)a), rows[i]);
            for (k = 0; k < 24; k++) CHECK(row8.p[k] == 0, "%s row8 %d: zeros", tg_aov_name((tg_aov)a), rows[i]);
            CHECK(guard_intact(&row) && guard_intact(&row8), "wrote outside the row");
            guard_free(&row);
            guard_free(&row8);
        }
    CHECK(guard_intact(&g), "wrote outside the frame");
    guard_free(&g);
}

/* ---- tg_frame_write_pixels ---- */

static int pixel_bytes(int format)
{
    static const int bytes[TG_PIXEL_FORMAT_COUNT] = { 2, 2, 2, 3, 3, 4, 4, 1 };
    return bytes[format];
}

/* One call into a guarded buffer of `size` bytes: its status, and whether
 * it wrote only inside the rows' pixels (1) or nothing at all when refused. */
static tg_status write_pixels_guarded(const tg_frame *frame, int aov, int y0, int y1, int format, int flags,
                                      size_t stride, size_t size, int *clean)
{
    guarded g = guard_alloc(size, 0);
    tg_status st;
    size_t i, k;
    memset(g.p, PATTERN, size);
    st = tg_frame_write_pixels(frame, (tg_aov)aov, y0, y1, (tg_pixel_format)format, flags, g.p, stride);
    *clean = guard_intact(&g);
    if (st != TG_OK)
        for (i = 0; i < size; i++) *clean &= g.p[i] == PATTERN;
    else if ((unsigned)format < TG_PIXEL_FORMAT_COUNT && stride > (size_t)8 * (size_t)pixel_bytes(format))
        for (i = 0; y0 + (int)i < y1; i++)                   /* bytes past each row's pixels untouched */
            for (k = (size_t)8 * (size_t)pixel_bytes(format); k < stride && i * stride + k < size; k++)
                *clean &= g.p[i * stride + k] == PATTERN;
    guard_free(&g);
    return st;
}

/* Every argument of tg_frame_write_pixels past its range is refused with
 * nothing written; in range, exactly the rows' pixels are written, into a
 * buffer of exactly (rows - 1) * stride + a row's bytes. */
TEST(write_pixels_hostile)
{
    static const int bad_rows[][2] = { { -1, 1 }, { 0, 7 }, { 3, 2 }, { INT_MIN, 0 }, { 0, INT_MAX }, { 7, 7 } };
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame;
    guarded g;
    int f, i, clean;
    uint8_t byte;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    g = guard_alloc(plan.total_bytes, 0);
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_OK, "%s", err.message);
    CHECK(tg_frame_render(frame, 0, &err) == TG_OK, "%s", err.message);
    for (f = 0; f < TG_PIXEL_FORMAT_COUNT; f++) {
        size_t row = (size_t)8 * (size_t)pixel_bytes(f);
        for (i = 0; i < 6; i++)
            CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, bad_rows[i][0], bad_rows[i][1], f, 0, row, 6 * row, &clean)
                  == TG_ERR_INPUT && clean, "format %d rows [%d, %d): refused, nothing written", f, bad_rows[i][0], bad_rows[i][1]);
        CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 0, 6, f, 0, row - 1, 6 * row, &clean) == TG_ERR_INPUT && clean,
              "format %d: a stride one byte short of a row refused", f);
        CHECK(write_pixels_guarded(frame, -1, 0, 6, f, 0, row, 6 * row, &clean) == TG_ERR_INPUT && clean, "aov -1");
        CHECK(write_pixels_guarded(frame, TG_AOV_COUNT, 0, 6, f, 0, row, 6 * row, &clean) == TG_ERR_INPUT && clean, "aov COUNT");
        CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 0, 6, f, 2, row, 6 * row, &clean) == TG_ERR_INPUT && clean, "flag 2");
        CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 0, 6, f, -1, row, 6 * row, &clean) == TG_ERR_INPUT && clean, "flags -1");
        CHECK(write_pixels_guarded(NULL, TG_AOV_COLOR, 0, 6, f, 0, row, 6 * row, &clean) == TG_ERR_INPUT && clean, "NULL frame");
        CHECK(tg_frame_write_pixels(frame, TG_AOV_COLOR, 0, 6, (tg_pixel_format)f, 0, NULL, row) == TG_ERR_INPUT, "NULL dst");
        CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 0, 6, f, 0, row, 6 * row, &clean) == TG_OK && clean,
              "format %d: the whole frame, rows packed", f);
        CHECK(write_pixels_guarded(frame, TG_AOV_NORMAL, 1, 5, f, TG_PIXELS_DITHER, row + 13, 3 * (row + 13) + row, &clean)
              == TG_OK && clean, "format %d: rows [1, 5) with 13 bytes between rows", f);
        CHECK(write_pixels_guarded(frame, TG_AOV_DEPTH, 5, 6, f, 0, row, row, &clean) == TG_OK && clean, "format %d: the last row", f);
        CHECK(tg_frame_write_pixels(frame, TG_AOV_AO, 6, 6, (tg_pixel_format)f, 0, &byte, row) == TG_OK, "no rows");
    }
    CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 0, 6, -1, 0, 64, 6 * 64, &clean) == TG_ERR_INPUT && clean, "format -1");
    CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 0, 6, TG_PIXEL_FORMAT_COUNT, 0, 64, 6 * 64, &clean) == TG_ERR_INPUT && clean,
          "format COUNT");
    CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 2, 3, TG_PIXEL_RGB888, 0, SIZE_MAX, 24, &clean) == TG_OK && clean,
          "one row with the largest stride");
    CHECK(write_pixels_guarded(frame, TG_AOV_COLOR, 2, 3, TG_PIXEL_RGB565, 0, SIZE_MAX, 16, &clean) == TG_OK && clean,
          "one row with the largest stride (RGB565)");
    CHECK(guard_intact(&g), "wrote outside the frame");
    guard_free(&g);
}

/* What tinygi.h says the core keeps no pointer into (text, files, file
 * names, requests, plans, errors) is freed right after each call; the frame
 * renders on, and gives the same image as a frame whose inputs stayed
 * alive (under ASan a kept pointer is a use-after-free). */
static char *mesh_copies[8];
static int mesh_copy_count;

static int heap_read(void *user, const char *path, const char **data, size_t *size, const char **reason)
{
    char *copy;
    (void)user;
    (void)path;
    (void)reason;
    if (mesh_copy_count == 8) return 1;
    copy = (char *)malloc(sizeof cube_obj);
    memcpy(copy, cube_obj, sizeof cube_obj);
    mesh_copies[mesh_copy_count++] = copy;
    *data = copy;
    *size = sizeof cube_obj - 1;
    return 0;
}

static void render_color(tg_frame *frame, float *out)
{
    tg_real row[8 * 3];
    int y, i;
    CHECK(tg_frame_render(frame, 0, NULL) == TG_OK && tg_frame_render(frame, 1, NULL) == TG_OK, "render");
    for (y = 0; y < 6; y++) {
        tg_frame_aov_row(frame, TG_AOV_COLOR, y, row);
        for (i = 0; i < 8 * 3; i++) out[y * 24 + i] = tg_to_float(row[i]);
    }
}

TEST(no_pointers_kept)
{
    static const char mesh_line[] = "mesh file m.obj material red name thing\n";
    size_t n = strlen(everything) + sizeof mesh_line - 1;
    char *text = (char *)malloc(n), *name = (char *)malloc(16);
    tg_request *q = (tg_request *)malloc(sizeof *q);
    tg_plan *plan = (tg_plan *)malloc(sizeof *plan);
    tg_error *err = (tg_error *)malloc(sizeof *err);
    tg_io io;
    tg_arena a;
    tg_scene *s = NULL;
    tg_frame *frame = NULL, *kept = NULL;
    void *mem, *mem2;
    float first[6 * 24], second[6 * 24];
    memcpy(text, everything, strlen(everything));
    memcpy(text + strlen(everything), mesh_line, sizeof mesh_line - 1);
    strcpy(name, "dir/h.scene");
    io.user = NULL;
    io.read_file = heap_read;
    tg_arena_init(&a, scene_mem, sizeof scene_mem);
    CHECK(tg_scene_parse(text, n, name, &io, &a, &s, err) == TG_OK, "parse: %s", err->message);
    free(text);
    free(name);
    while (mesh_copy_count > 0) free(mesh_copies[--mesh_copy_count]);   /* the mesh data */
    *q = small_request(8, 6, 2);
    CHECK(tg_plan_make(plan, s, q, err) == TG_OK, "plan: %s", err->message);
    mem = malloc(plan->total_bytes);
    mem2 = malloc(plan->total_bytes);
    CHECK(tg_frame_create(plan, mem2, plan->total_bytes, &kept, err) == TG_OK, "create");
    CHECK(tg_frame_create(plan, mem, plan->total_bytes, &frame, err) == TG_OK, "create");
    render_color(kept, first);
    free(q);
    free(plan);
    free(err);
    render_color(frame, second);
    CHECK(memcmp(first, second, sizeof first) == 0, "the frame whose inputs were freed renders differently");
    free(mem);
    free(mem2);
}

/* ---- out of order: handles that an earlier, failed call left ---- */

/* A NULL scene (tg_scene_parse failed): refused (it crashed until the
 * twenty-first session). */
TEST(plan_before_parse)
{
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    CHECK(tg_plan_make(&plan, NULL, &q, &err) == TG_ERR_INPUT && err.message[0], "NULL scene");
}

/* A plan whose tg_plan_make failed (total_bytes 0) makes no frame. */
TEST(create_from_failed_plan)
{
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame = NULL;
    guarded g = guard_alloc(1u << 20, 0);
    q.slices = 1000;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_ERR_INPUT, "slices 1000 refused");
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_ERR_INPUT && frame == NULL,
          "a frame from a refused plan");
    guard_free(&g);
}

/* tg_frame_create with err NULL and too little memory. */
TEST(create_short_with_null_err)
{
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame;
    unsigned char small[64];
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    CHECK(tg_frame_create(&plan, small, sizeof small, &frame, NULL) == TG_ERR_MEMORY && !frame, "short, NULL err");
}

/* Render and read before create, or after it failed (frame NULL). */
TEST(render_before_create)
{
    tg_error err;
    tg_real row[8 * 3];
    uint8_t row8[8 * 3];
    memset(row, 0x7F, sizeof row);
    memset(row8, 0x7F, sizeof row8);
    CHECK(tg_frame_render(NULL, 0, &err) == TG_ERR_INPUT && err.message[0], "render a NULL frame");
    CHECK(tg_frame_aov_row(NULL, TG_AOV_COLOR, 0, row) == TG_ERR_INPUT, "read a NULL frame");
    CHECK(tg_frame_aov_row8(NULL, TG_AOV_COLOR, 0, row8) == TG_ERR_INPUT, "read a NULL frame, 8 bits");
}

/* Every other NULL handle or output the API takes: refused with
 * TG_ERR_INPUT (each crashed before the twenty-first session), err NULL
 * too; nothing is written. */
TEST(null_handles_refused)
{
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame = NULL;
    tg_parallel par;
    guarded g;
    char text[16];
    CHECK(tg_plan_make(NULL, scene_everything(), &q, &err) == TG_ERR_INPUT && err.message[0], "NULL plan");
    CHECK(tg_plan_make(&plan, scene_everything(), NULL, &err) == TG_ERR_INPUT && err.message[0], "NULL request");
    CHECK(tg_plan_make(&plan, NULL, &q, NULL) == TG_ERR_INPUT, "NULL scene, NULL err");
    memset(text, 'x', sizeof text);
    CHECK(tg_plan_explain(NULL, text, sizeof text) == 0 && text[0] == '\0', "explain a NULL plan: ''");
    CHECK(tg_frame_create(NULL, NULL, 0, &frame, &err) == TG_ERR_INPUT && frame == NULL, "create from a NULL plan");
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    g = guard_alloc(plan.total_bytes, 0);
    CHECK(tg_frame_create(&plan, g.p, g.size, NULL, &err) == TG_ERR_INPUT, "create into a NULL handle");
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, NULL) == TG_OK && frame, "create with err NULL");
    CHECK(tg_frame_set_parallel(NULL, NULL) == TG_ERR_INPUT, "parallel hook on a NULL frame");
    memset(&par, 0, sizeof par);
    CHECK(tg_frame_set_parallel(frame, &par) == TG_ERR_INPUT, "a hook without run");
    CHECK(tg_frame_render(frame, 0, NULL) == TG_OK, "render with err NULL");
    CHECK(tg_frame_aov_row(frame, TG_AOV_COLOR, 0, NULL) == TG_ERR_INPUT, "read into NULL");
    CHECK(tg_frame_aov_row8(frame, TG_AOV_COLOR, 0, NULL) == TG_ERR_INPUT, "read into NULL, 8 bits");
    guard_free(&g);
}

/* A plan made, then tg_plan_make failing on it (a NULL scene: a re-parse
 * that failed): the plan is left with total_bytes 0 and no scene, and
 * makes no frame (it kept the old plan's bytes and scene, and a frame was
 * made from it: an outside probe, the twenty-third session). */
TEST(failed_plan_over_a_good_one)
{
    tg_request q = small_request(8, 6, 1);
    tg_plan plan;
    tg_error err;
    tg_frame *frame = NULL;
    guarded g = guard_alloc(1u << 20, 0);
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK && plan.total_bytes > 0, "%s", err.message);
    CHECK(tg_plan_make(&plan, NULL, &q, &err) == TG_ERR_INPUT, "NULL scene refused");
    CHECK(plan.total_bytes == 0 && plan.scene == NULL, "the failed plan: total_bytes %zu, scene %p", plan.total_bytes,
          (const void *)plan.scene);
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_ERR_INPUT && frame == NULL, "a frame from it");
    CHECK(tg_plan_make(&plan, scene_everything(), NULL, &err) == TG_ERR_INPUT && plan.total_bytes == 0, "NULL request");
    guard_free(&g);
}

/* A request changed in the plan after tg_plan_make is checked again by
 * tg_frame_create as tg_plan_make checks one (bounces 1000000 rendered for
 * minutes, technique 99 and slices 50 were taken: an outside probe). */
TEST(plan_request_changed_after_make)
{
    tg_request q = small_request(8, 6, 1);
    tg_plan plan, bad;
    tg_error err;
    tg_frame *frame = NULL;
    guarded g;
    int k;
    CHECK(tg_plan_make(&plan, scene_everything(), &q, &err) == TG_OK, "%s", err.message);
    g = guard_alloc(plan.total_bytes, 0);
    for (k = 0; k < 5; k++) {
        bad = plan;
        switch (k) {
        case 0: bad.request.bounces = 1000000; break;
        case 1: bad.request.technique = (tg_technique)99; break;
        case 2: bad.request.slices = 50; break;
        case 3: bad.request.gi_scale = 7; break;
        default: bad.request.frames = 0; break;
        }
        frame = NULL;
        CHECK(tg_frame_create(&bad, g.p, g.size, &frame, &err) == TG_ERR_INPUT && frame == NULL && err.message[0],
              "change %d taken", k);
    }
    CHECK(tg_frame_create(&plan, g.p, g.size, &frame, &err) == TG_OK && frame, "the plan as made: %s", err.message);
    guard_free(&g);
}

/* tg_request_defaults(NULL) does nothing; tg_error_format(NULL) formats a
 * zeroed error (both dereferenced NULL). */
TEST(defaults_and_format_of_null)
{
    char buf[32];
    tg_request_defaults(NULL);
    CHECK(tg_error_format(NULL, buf, sizeof buf) == strlen("error: ") && !strcmp(buf, "error: "), "'%s'", buf);
    CHECK(tg_error_format(NULL, NULL, 0) == strlen("error: "), "NULL error, NULL buffer");
}

int main(void)
{
    CASE(real_functions_at_extremes, NULL);
#if !TG_FIXED
    CASE(real_functions_nan_and_inf, NULL);
#endif
    CASE(parse_real_hostile, NULL);
    CASE(error_format_any_size, NULL);
    CASE(arena_hostile, NULL);
    CASE(names_hostile, NULL);
    CASE(request_defaults_over_garbage, NULL);
    CASE(scene_parse_missing_arguments, NULL);
    CASE(scene_parse_sizes, NULL);
    CASE(scene_text_cut_anywhere, NULL);
    CASE(scene_text_hostile_bytes, NULL);
    CASE(scene_arena_short_by_one, NULL);
    CASE(scene_io_misbehaves, NULL);
    CASE(request_size_refused, NULL);
    CASE(request_size_extremes_render, NULL);
    CASE(request_frames_and_aovs_refused, NULL);
    CASE(request_gi_settings_refused, NULL);
    CASE(request_switches_and_shadow_map_refused, NULL);
    CASE(request_limits_render, NULL);
    CASE(techniques_at_odd_sizes, NULL);
    CASE(plan_explain_any_size, NULL);
    CASE(frame_memory_any_base_and_short, NULL);
    CASE(frame_memory_every_short_size, NULL);
    CASE(render_indices_out_of_order, NULL);
    CASE(aov_not_requested_or_unknown, NULL);
    CASE(aov_rows_outside_refused, NULL);
    CASE(write_pixels_hostile, NULL);
    CASE(no_pointers_kept, NULL);
    CASE(error_messages_escape_control_bytes, NULL);
    CASE(plan_before_parse, NULL);
    CASE(create_from_failed_plan, NULL);
    CASE(create_short_with_null_err, NULL);
    CASE(render_before_create, NULL);
    CASE(null_handles_refused, NULL);
    CASE(failed_plan_over_a_good_one, NULL);
    CASE(plan_request_changed_after_make, NULL);
    CASE(defaults_and_format_of_null, NULL);
    return check_summary();
}
