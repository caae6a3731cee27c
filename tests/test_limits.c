/* SPDX-License-Identifier: MIT */
/*
 * test_limits.c - every limit the scene parser enforces (the block at the
 * top of src/tinygi.h, cited in src/scene/format.md), walked: accepted AT
 * the bound, refused ONE STEP past it at FILE:LINE:COL with the words every
 * refusal uses, "NAME must be LO..HI, got V".
 *
 * "Accepted" is TG_OK, or TG_ERR_MEMORY from a small arena for the scenes
 * too big to build here (4,000,000 triangles): the parser's first pass has
 * then validated every line, limits included, before asking for memory.
 * The scene file's size is walked at its bound with 1 GiB of /dev/zero
 * mapped, not read: the parser stops at the first byte (a NUL), so it got
 * past the size check.
 */
#include "check.h"
#include <stdarg.h>
#include <stdlib.h>
#include <fcntl.h>
#include <unistd.h>
#include <sys/mman.h>

#define CAM "camera pos 0 1 5 target 0 0 0\n"
#define MAT "material m albedo 0.5 0.5 0.5\n"

static unsigned char arena_mem[1 << 23];

/* ---- a growing text buffer ---- */
typedef struct text { char *s; size_t n, cap; } text;

static void put(text *t, const char *fmt, ...)
{
    va_list ap;
    int k;
    for (;;) {
        size_t room = t->cap - t->n;
        va_start(ap, fmt);
        k = vsnprintf(t->s ? t->s + t->n : NULL, t->s ? room : 0, fmt, ap);
        va_end(ap);
        if (t->s && (size_t)k < room) { t->n += (size_t)k; return; }
        t->cap = (t->cap + (size_t)k + 1) * 2;
        t->s = (char *)realloc(t->s, t->cap);
        if (!t->s) abort();
    }
}

static void put_repeat(text *t, char c, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) put(t, "%c", c);
}

/* ---- files for meshes: any path ending in .mtl is an MTL, else an OBJ ---- */
typedef struct files {
    const char *obj, *mtl;
    size_t obj_n, mtl_n;        /* 0: strlen */
} files;

static int files_read(void *user, const char *path, const char **data, size_t *size,
                      const char **reason)
{
    const files *f = (const files *)user;
    size_t n = strlen(path);
    (void)reason;
    if (n >= 4 && strcmp(path + n - 4, ".mtl") == 0) {
        *data = f->mtl; *size = f->mtl_n ? f->mtl_n : strlen(f->mtl);
    } else {
        *data = f->obj; *size = f->obj_n ? f->obj_n : strlen(f->obj);
    }
    return 0;
}

static const char tri_obj[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
static const char red_mtl[] = "newmtl red\nKd 1 0 0\n";

static tg_status parse_with(const char *s, size_t n, const files *fs, size_t arena_size, tg_error *err)
{
    tg_arena a;
    tg_scene *scene;
    tg_io io;
    io.user = (void *)fs;
    io.read_file = files_read;
    tg_arena_init(&a, arena_mem, arena_size);
    return tg_scene_parse(s, n, "t.scene", fs ? &io : NULL, &a, &scene, err);
}

/* The text at the bound is accepted; past it, refused at line:col with `msg`. */
static void walk(const char *what, const text *at, const text *past, const files *fs,
                 int line, int col, const char *msg)
{
    tg_error err;
    char shown[600];
    tg_status st = parse_with(at->s, at->n, fs, sizeof arena_mem, &err);
    tg_error_format(&err, shown, sizeof shown);
    CHECK(st == TG_OK || st == TG_ERR_MEMORY, "%s at the bound: status %d: %s", what, (int)st, shown);
    st = parse_with(past->s, past->n, fs, sizeof arena_mem, &err);
    tg_error_format(&err, shown, sizeof shown);
    CHECK(st == TG_ERR_INPUT, "%s past the bound: status %d", what, (int)st);
    CHECK(strcmp(err.file, "t.scene") == 0 || strstr(err.file, ".obj") != NULL,
          "%s past the bound: in file '%s'", what, err.file);
    CHECK(err.line == line && (col == 0 || err.col == col), "%s past the bound: at %d:%d, expected %d:%d (%s)",
          what, err.line, err.col, line, col, shown);
    CHECK(strstr(err.message, msg) != NULL, "%s past the bound: '%s' lacks '%s'", what, err.message, msg);
}

static void reset(text *t) { t->n = 0; if (t->s) t->s[0] = '\0'; }

/* Two scenes that differ in one value of one line. */
static void walk_value(const char *what, const char *prefix, const char *ok, const char *bad,
                       const char *suffix, const char *msg)
{
    text a = {0}, b = {0};
    put(&a, CAM MAT "%s%s%s\n", prefix, ok, suffix);
    put(&b, CAM MAT "%s%s%s\n", prefix, bad, suffix);
    walk(what, &a, &b, NULL, 3, (int)strlen(prefix) + 1, msg);
    free(a.s); free(b.s);
}

TEST(gi_settings)
{
    walk_value("gi radius (high)", "gi radius ", "10000", "10000.01", "", "gi radius must be 0..10000, got 10000.01");
    walk_value("gi radius (low)", "gi radius ", "0", "-0.01", "", "gi radius must be 0..10000, got -0.01");
    walk_value("gi slices (high)", "gi slices ", "8", "9", "", "gi slices must be 1..8, got 9");
    walk_value("gi slices (low)", "gi slices ", "1", "0", "", "gi slices must be 1..8, got 0");
    walk_value("gi samples (high)", "gi samples ", "256", "257", "", "gi samples must be 1..256, got 257");
    walk_value("gi samples (low)", "gi samples ", "1", "0", "", "gi samples must be 1..256, got 0");
    walk_value("gi bounces (high)", "gi bounces ", "100", "101", "", "gi bounces must be 0..100, got 101");
    walk_value("gi bounces (low)", "gi bounces ", "0", "-1", "", "gi bounces must be 0..100, got -1");
    CHECK(TG_MAX_SLICES == 8 && TG_MAX_SAMPLES == 256 && TG_MAX_BOUNCES == 100 && TG_MAX_RADIUS == 10000,
          "the messages above spell tinygi.h's limits");
}

TEST(sphere_segments)
{
    walk_value("sphere segments (high)", "sphere center 0 0 0 radius 1 material m segments ", "256", "257", "",
               "sphere segments must be 4..256, got 257");
    walk_value("sphere segments (low)", "sphere center 0 0 0 radius 1 material m segments ", "4", "3", "",
               "sphere segments must be 4..256, got 3");
    CHECK(TG_MIN_SPHERE_SEGMENTS == 4 && TG_MAX_SPHERE_SEGMENTS == 256, "limits as spelt");
}

TEST(name_length)
{
    char ok[TG_MAX_NAME + 1], bad[TG_MAX_NAME + 2];
    memset(ok, 'n', TG_MAX_NAME); ok[TG_MAX_NAME] = '\0';
    memset(bad, 'n', TG_MAX_NAME + 1); bad[TG_MAX_NAME + 1] = '\0';
    walk_value("material name", "material ", ok, bad, " albedo 1 1 1", "name length in bytes must be 1..31, got 32");
    walk_value("object name", "box min 0 0 0 max 1 1 1 material m name ", ok, bad, "",
               "name length in bytes must be 1..31, got 32");
}

TEST(line_length)
{
    text a = {0}, b = {0};
    put(&a, CAM MAT "#"); put_repeat(&a, 'x', TG_MAX_LINE - 1); put(&a, "\n");
    put(&b, CAM MAT "#"); put_repeat(&b, 'x', TG_MAX_LINE); put(&b, "\n");
    walk("line length", &a, &b, NULL, 3, TG_MAX_LINE + 1, "line length in bytes must be 0..4096, got 4097");
    /* the line end is not counted, whichever it is */
    reset(&a); put(&a, CAM MAT "#"); put_repeat(&a, 'x', TG_MAX_LINE - 1); put(&a, "\r\n");
    reset(&b); put(&b, CAM MAT "#"); put_repeat(&b, 'x', TG_MAX_LINE); put(&b, "\r\n");
    walk("line length (CRLF)", &a, &b, NULL, 3, TG_MAX_LINE + 1, "line length in bytes must be 0..4096, got 4097");
    reset(&a); put(&a, "camera pos 0 1 5 target 0 0 0\r" MAT "#"); put_repeat(&a, 'x', TG_MAX_LINE - 1); put(&a, "\r");
    reset(&b); put(&b, "camera pos 0 1 5 target 0 0 0\r" MAT "#"); put_repeat(&b, 'x', TG_MAX_LINE); put(&b, "\r");
    walk("line length (CR)", &a, &b, NULL, 3, TG_MAX_LINE + 1, "line length in bytes must be 0..4096, got 4097");
    free(a.s); free(b.s);
}

/* `count` lines made by `line(i)`, then one more. */
static void walk_count(const char *what, const char *head, int count, void (*line)(text *, int),
                       int head_lines, int col, const char *msg)
{
    text a = {0}, b = {0};
    int i;
    put(&a, "%s", head);
    for (i = 0; i < count; i++) line(&a, i);
    put(&b, "%s", a.s);
    line(&b, count);
    walk(what, &a, &b, NULL, head_lines + count + 1, col, msg);
    free(a.s); free(b.s);
}

static void light_line(text *t, int i) { put(t, "light point pos 0 %d 0 color 1 1 1\n", i); }
static void material_line(text *t, int i) { put(t, "material m%d albedo 1 1 1\n", i); }
static void camera_key_line(text *t, int i) { put(t, "camera_key t %d pos 0 1 5 target 0 0 0\n", i); }
static void object_key_line(text *t, int i) { put(t, "object_key name b t %d\n", i); }
static void box_line(text *t, int i) { (void)i; put(t, "box min 0 0 0 max 1 1 1 material m\n"); }

TEST(counts)
{
    walk_count("lights", CAM, TG_MAX_LIGHTS, light_line, 1, 1, "light count must be 0..64, got 65");
    walk_count("materials", CAM, TG_MAX_MATERIALS, material_line, 1, 10, "material count must be 0..1024, got 1025");
    walk_count("camera keys", CAM, TG_MAX_KEYS, camera_key_line, 1, 1, "camera_key count must be 0..4096, got 4097");
    walk_count("object keys", CAM MAT "box min 0 0 0 max 1 1 1 material m name b\n", TG_MAX_KEYS, object_key_line, 3, 1,
               "object_key count must be 0..4096, got 4097");
    walk_count("objects", CAM MAT, TG_MAX_OBJECTS, box_line, 2, 1, "object count must be 0..65535, got 65536");
    CHECK(TG_MAX_LIGHTS == 64 && TG_MAX_MATERIALS == 1024 && TG_MAX_KEYS == 4096 && TG_MAX_OBJECTS == 65535,
          "limits as spelt");
}

TEST(triangles)
{
    /* 61 spheres of 256 segments (65024 triangles each), 2794 boxes (12
     * each) and 4 quads: 4,000,000 triangles exactly; then one OBJ triangle */
    text a = {0}, b = {0};
    files fs = {tri_obj, red_mtl, 0, 0};
    int i;
    put(&a, CAM MAT);
    for (i = 0; i < 61; i++) put(&a, "sphere center 0 0 0 radius 1 material m segments 256\n");
    for (i = 0; i < 2794; i++) put(&a, "box min 0 0 0 max 1 1 1 material m\n");
    for (i = 0; i < 4; i++) put(&a, "quad p0 0 0 0 p1 1 0 0 p2 1 1 0 p3 0 1 0 material m\n");
    CHECK(61L * 2 * 256 * 127 + 2794L * 12 + 4L * 2 == TG_MAX_TRIANGLES, "the arithmetic");
    put(&b, "%s", a.s);
    put(&b, "mesh file tri.obj material m\n");
    walk("triangles", &a, &b, &fs, 4, 7, "triangle count must be 0..4000000, got 4000001"); /* tri.obj:4:7 */
    free(a.s); free(b.s);
}

static void walk_obj(const char *what, const text *obj_at, const text *obj_past, const char *mtl,
                     int line, int col, const char *msg)
{
    text scene = {0};
    files at = {0}, past = {0};
    at.obj = obj_at->s; at.obj_n = obj_at->n; at.mtl = mtl;
    past.obj = obj_past->s; past.obj_n = obj_past->n; past.mtl = mtl;
    put(&scene, CAM MAT "mesh file o.obj material m\n");
    {
        tg_error err;
        char shown[600];
        tg_status st = parse_with(scene.s, scene.n, &at, sizeof arena_mem, &err);
        tg_error_format(&err, shown, sizeof shown);
        CHECK(st == TG_OK || st == TG_ERR_MEMORY, "%s at the bound: status %d: %s", what, (int)st, shown);
        st = parse_with(scene.s, scene.n, &past, sizeof arena_mem, &err);
        tg_error_format(&err, shown, sizeof shown);
        CHECK(st == TG_ERR_INPUT && strcmp(err.file, "o.obj") == 0 && err.line == line && err.col == col,
              "%s past the bound: status %d at %s:%d:%d, expected o.obj:%d:%d (%s)", what, (int)st,
              err.file, err.line, err.col, line, col, shown);
        CHECK(strstr(err.message, msg) != NULL, "%s: '%s' lacks '%s'", what, err.message, msg);
    }
    free(scene.s);
}

TEST(obj_vertices)
{
    text a = {0}, b = {0};
    long i;
    /* zeros: the float build parses "0" at once (other numbers exactly, slowly) */
    for (i = 0; i < TG_MAX_OBJ_VERTICES; i++) put(&a, "v 0 0 0\n");
    put(&a, "f 1 2 3\n");
    put(&b, "v 0 0 0\n%s", a.s);
    walk_obj("v lines", &a, &b, red_mtl, TG_MAX_OBJ_VERTICES + 1, 1, "v count per OBJ file must be 0..4000000, got 4000001");
    reset(&a); reset(&b);
    put(&a, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for (i = 0; i < TG_MAX_OBJ_VERTICES; i++) put(&a, "vn 0 0 0\n");
    put(&a, "f 1//1 2//2 3//3\n");
    put(&b, "vn 0 1 0\n%s", a.s);
    walk_obj("vn lines", &a, &b, red_mtl, TG_MAX_OBJ_VERTICES + 4, 1, "vn count per OBJ file must be 0..4000000, got 4000001");
    free(a.s); free(b.s);
}

TEST(mtllibs)
{
    text a = {0}, b = {0};
    int i;
    put(&b, "mtllib");
    for (i = 0; i < TG_MAX_MTLLIBS; i++) put(&b, " m%d.mtl", i);
    put(&a, "%s\nusemtl red\n%s", b.s, tri_obj);
    put(&b, " m%d.mtl\nusemtl red\n%s", TG_MAX_MTLLIBS, tri_obj);
    walk_obj("mtllib files", &a, &b, red_mtl, 1, 8 + 7 * TG_MAX_MTLLIBS, "mtllib count per OBJ file must be 0..8, got 9");
    free(a.s); free(b.s);
}

TEST(path_length)
{
    text a = {0}, b = {0};
    files fs = {tri_obj, red_mtl, 0, 0};
    char name[TG_MAX_PATH + 1];
    memset(name, 'p', sizeof name);
    memcpy(name + TG_MAX_PATH - 5, ".obj", 5); /* 255 bytes */
    put(&a, CAM MAT "mesh file %s material m\n", name);
    memcpy(name + TG_MAX_PATH - 4, ".obj", 5); /* 256 bytes */
    put(&b, CAM MAT "mesh file %s material m\n", name);
    walk("mesh path", &a, &b, &fs, 3, 11, "mesh path length in bytes must be 1..255, got 256");
    /* an MTL path joins the OBJ's directory: "d/" + 253 bytes is the bound */
    {
        text oa = {0}, ob = {0};
        files at = {0}, past = {0};
        tg_error err;
        tg_status st;
        memset(name, 'm', sizeof name);
        memcpy(name + TG_MAX_PATH - 7, ".mtl", 5); /* 253 bytes */
        put(&oa, "mtllib %s\n%s", name, tri_obj);
        memcpy(name + TG_MAX_PATH - 6, ".mtl", 5); /* 254 bytes */
        put(&ob, "mtllib %s\n%s", name, tri_obj);
        reset(&a); put(&a, CAM MAT "mesh file d/o.obj material m\n");
        at.obj = oa.s; at.mtl = red_mtl; past.obj = ob.s; past.mtl = red_mtl;
        st = parse_with(a.s, a.n, &at, sizeof arena_mem, &err);
        CHECK(st == TG_OK, "MTL path of 255 bytes: %d %s", (int)st, err.message);
        st = parse_with(a.s, a.n, &past, sizeof arena_mem, &err);
        CHECK(st == TG_ERR_INPUT && strcmp(err.file, "d/o.obj") == 0 && err.line == 1 && err.col == 8 &&
              strstr(err.message, "MTL path length in bytes must be 1..255, got 256"),
              "MTL path of 256 bytes: %s:%d:%d %s", err.file, err.line, err.col, err.message);
        free(oa.s); free(ob.s);
    }
    free(a.s); free(b.s);
}

/* 1 GiB + extra of zero bytes, mapped (not read); NULL where it cannot be. */
static const char *map_zeros(size_t n)
{
    int fd = open("/dev/zero", O_RDONLY);
    void *p;
    if (fd < 0) return NULL;
    p = mmap(NULL, n, PROT_READ, MAP_PRIVATE, fd, 0);
    close(fd);
    return p == MAP_FAILED ? NULL : (const char *)p;
}

TEST(file_sizes)
{
    size_t big = (size_t)TG_MAX_FILE_BYTES;
    const char *zeros = sizeof(size_t) > 4 ? map_zeros(big + 4096) : NULL;
    const char *scene = CAM MAT "mesh file o.obj material m\n";
    files fs = {tri_obj, red_mtl, 0, 0};
    tg_error err;
    tg_status st;
    char want[96];
    snprintf(want, sizeof want, "scene size in bytes must be 0..1073741824, got %lu", (unsigned long)big + 1);
    /* past the bound: refused before a byte is read (the text is short) */
    st = parse_with(CAM, big + 1, NULL, sizeof arena_mem, &err);
    CHECK(st == TG_ERR_INPUT && strcmp(err.file, "t.scene") == 0 && strstr(err.message, want),
          "scene of 1 GiB + 1: %d %s", (int)st, err.message);
    fs.obj_n = big + 1;
    st = parse_with(scene, strlen(scene), &fs, sizeof arena_mem, &err);
    snprintf(want, sizeof want, "mesh file size in bytes must be 0..1073741824, got %lu", (unsigned long)big + 1);
    CHECK(st == TG_ERR_INPUT && err.line == 3 && err.col == 11 && strstr(err.message, want),
          "mesh of 1 GiB + 1: %d %d:%d %s", (int)st, err.line, err.col, err.message);
    fs.obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    fs.obj_n = 0;
    fs.mtl_n = big + 1;
    st = parse_with(scene, strlen(scene), &fs, sizeof arena_mem, &err);
    snprintf(want, sizeof want, "MTL file size in bytes must be 0..1073741824, got %lu", (unsigned long)big + 1);
    CHECK(st == TG_ERR_INPUT && strcmp(err.file, "o.obj") == 0 && err.line == 1 && err.col == 8 &&
          strstr(err.message, want), "MTL of 1 GiB + 1: %d %s:%d:%d %s", (int)st, err.file, err.line, err.col,
          err.message);
    if (!zeros) { printf("# file_sizes: cannot map 1 GiB here; the bound itself not walked\n"); return; }
    /* at the bound: past the size check, stopped by the first (NUL) byte */
    st = parse_with(zeros, big, NULL, sizeof arena_mem, &err);
    CHECK(st == TG_ERR_INPUT && err.line == 1 && err.col == 1 && strstr(err.message, "NUL byte"),
          "scene of 1 GiB: %d %s", (int)st, err.message);
    fs.obj = zeros; fs.obj_n = big; fs.mtl_n = 0;
    st = parse_with(scene, strlen(scene), &fs, sizeof arena_mem, &err);
    CHECK(st == TG_ERR_INPUT && strcmp(err.file, "o.obj") == 0 && strstr(err.message, "NUL byte"),
          "mesh of 1 GiB: %d %s %s", (int)st, err.file, err.message);
    munmap((void *)(uintptr_t)zeros, big + 4096);
}

int main(void)
{
    RUN(gi_settings);
    RUN(sphere_segments);
    RUN(name_length);
    RUN(line_length);
    RUN(counts);
    RUN(triangles);
    RUN(obj_vertices);
    RUN(mtllibs);
    RUN(path_length);
    RUN(file_sizes);
    return check_summary();
}
