/* SPDX-License-Identifier: MIT */
/*
 * switches_check.c - one build of the core under the feature switches it is
 * compiled with (tinygi.h "FEATURE SWITCHES"; tests/switches_test.sh builds
 * it under each).  Every build renders what it keeps (colour HBIL with
 * direct light and reprojection, and AO), and for each switch either uses
 * the feature (switch 0: it works) or asks for it and must be refused with
 * TG_ERR_INPUT and a message naming the switch (switch 1).
 *
 * With TG_NO_SCENE_TEXT=1 the scenes below are not parsed: the script bakes
 * them on the host (tinygi-bake; this file built with SWITCHES_PRINT=1
 * prints them) and links them in as switches_plain() and the like.
 */
#include <stdlib.h>
#include "check.h"
#include "../tools/room_scene.h"

#define W 24
#define H 18

/* No shadows, no environment, no mesh: what every build can render. */
static const char scene_plain[] =
    TG_ROOM_SCENE
    "light point pos 0 2.8 -1  color 1 0.9 0.8  intensity 10\n";
/* The same lit by a shadowed light under a sky. */
static const char scene_rich[] =
    "camera pos 0 1.5 -4  target 0 1 0  fov 50\n"
    "material white albedo 0.73 0.73 0.73\n"
    "quad p0 -2 0 -2  p1 -2 0 2  p2 2 0 2  p3 2 0 -2  material white name floor\n"
    "box min -0.5 0 -0.5  max 0.5 1 0.5  material white name block\n"
    "light point pos 0 2.8 -1  color 1 0.9 0.8  intensity 10  shadows\n"
    "env sky 0.45 0.6 0.9  ground 0.25 0.22 0.2\n";
/* A sky behind colour, with the far field left out by `effects`. */
static const char scene_sky_no_far[] =
    "camera pos 0 1.5 -4  target 0 1 0  fov 50\n"
    "material white albedo 0.73 0.73 0.73\n"
    "quad p0 -2 0 -2  p1 -2 0 2  p2 2 0 2  p3 2 0 -2  material white name floor\n"
    "light point pos 0 2.8 -1  color 1 0.9 0.8  intensity 10\n"
    "env uniform 0.3 0.4 0.5\n"
    "effects direct near ao\n";
/* The plain scene with its box turning and the camera moving (keys). */
static const char scene_keyed[] =
    TG_ROOM_SCENE
    "light point pos 0 2.8 -1  color 1 0.9 0.8  intensity 10\n"
    "camera_key t 0  pos 0 1.5 -4  target 0 1 0\n"
    "camera_key t 1  pos 0.5 1.5 -4  target 0 1 0\n";
/* A mesh from an OBJ file (the io below holds it). */
static const char scene_mesh[] =
    "camera pos 0 1 -3  target 0 0 0  fov 50\n"
    "material white albedo 0.7 0.7 0.7\n"
    "mesh file tri.obj material white\n";
static const char obj_tri[] = "v -1 0 -1\nv 1 0 -1\nv 0 0 1\nf 1 3 2\n";

static int read_mem(void *user, const char *path, const char **data, size_t *size, const char **reason)
{
    (void)user; (void)reason;
    if (strcmp(path, "tri.obj") != 0) return 1;
    *data = obj_tri;
    *size = sizeof obj_tri - 1;
    return 0;
}

#if SWITCHES_PRINT
/* the scenes' text, for baking: switches_check plain|rich|sky_no_far|keyed */
int main(int argc, char **argv)
{
    const char *text = argc < 2 ? NULL : !strcmp(argv[1], "plain") ? scene_plain
                       : !strcmp(argv[1], "rich") ? scene_rich : !strcmp(argv[1], "sky_no_far") ? scene_sky_no_far
                       : !strcmp(argv[1], "keyed") ? scene_keyed : NULL;
    (void)read_mem; (void)scene_mesh;
    (void)check_current_name; (void)check_current_failures; (void)check_tests_passed; (void)check_tests_failed;
    return text ? fputs(text, stdout) < 0 : 2;
}
#else

static unsigned char scene_memory[1 << 20];
static tg_arena arena;

#if TG_NO_SCENE_TEXT
const tg_scene *switches_plain(void);
const tg_scene *switches_rich(void);
const tg_scene *switches_sky_no_far(void);
const tg_scene *switches_keyed(void);
#endif

static const tg_scene *parse(const char *text, tg_status *st, tg_error *err)
{
    tg_io io = { NULL, read_mem };
    tg_scene *s = NULL;
    tg_arena_init(&arena, scene_memory, sizeof scene_memory);
    *st = tg_scene_parse(text, strlen(text), "switches.scene", &io, &arena, &s, err);
#if TG_NO_SCENE_TEXT
    /* refused (TEST(scene_text) checks how): the same scene, baked */
    if (*st == TG_ERR_INPUT && s == NULL) {
        const tg_scene *baked = text == scene_plain ? switches_plain() : text == scene_rich ? switches_rich()
                                : text == scene_sky_no_far ? switches_sky_no_far()
                                : text == scene_keyed ? switches_keyed() : NULL;
        if (baked) *st = TG_OK;
        return baked;
    }
#endif
    return s;
}

/* The request's settings beyond the defaults: gi_scale 2, temporal 0. */
enum { QUARTER = 1, NO_TEMPORAL = 2 };

static tg_status plan_with(const char *text, tg_technique t, uint32_t aovs, int frames, int settings, tg_plan *plan,
                           tg_error *err)
{
    tg_status st;
    tg_request req;
    const tg_scene *s = parse(text, &st, err);
    if (st != TG_OK) return st;
    tg_request_defaults(&req);
    req.width = W;
    req.height = H;
    req.frames = frames;
    req.technique = t;
    req.aovs = aovs;
    if (settings & QUARTER) req.gi_scale = 2;
    if (settings & NO_TEMPORAL) req.temporal = 0;
    return tg_plan_make(plan, s, &req, err);
}

static tg_status plan_for(const char *text, tg_technique t, uint32_t aovs, int frames, tg_plan *plan, tg_error *err)
{
    return plan_with(text, t, aovs, frames, 0, plan, err);
}

/* Frames in one request where the build keeps history (TG_NO_TEMPORAL
 * refuses more than one with temporal accumulation). */
#define FRAMES(n) (TG_NO_TEMPORAL ? 1 : (n))

/* Render the plan's frames; 1 when every value of `aov` is finite and
 * within [lo, hi]. */
static int renders_within(const tg_plan *plan, tg_aov aov, double lo, double hi)
{
    tg_frame *f = NULL;
    tg_error err;
    tg_real row[3 * W];
    void *mem = malloc(plan->total_bytes);
    int i, y, ok = mem != NULL;
    if (ok) ok = tg_frame_create(plan, mem, plan->total_bytes, &f, &err) == TG_OK;
    for (i = 0; ok && i < plan->request.frames; i++) ok = tg_frame_render(f, i, &err) == TG_OK;
    for (y = 0; ok && y < H; y++) {
        ok = tg_frame_aov_row(f, aov, y, row) == TG_OK;
        for (i = 0; ok && i < W * tg_aov_channels(aov); i++) {
            double v = check_d(row[i]);
            ok = tg_isfinite(row[i]) && v >= lo && v <= hi;
        }
    }
    free(mem);
    return ok;
}

/* Refused as input with a message naming the switch. */
static int refused(tg_status st, const tg_error *err, const char *sw)
{
    char want[64];
    snprintf(want, sizeof want, "(%s=1)", sw);
    if (st != TG_ERR_INPUT) return 0;
    if (!strstr(err->message, want)) {
        fprintf(stderr, "message without %s: %s\n", want, err->message);
        return 0;
    }
    return 1;
}

/* text planned for technique t and one AOV, aov: with the switch sw
 * compiled out (off) refused with a message naming it, and so is light
 * (direct, far, colour) without colour (TG_NO_COLOR), and the far field
 * without bent normals (TG_NO_BENT_NORMALS); else planned, with
 * `effect` among the plan's effects (0: none asked), rendering aov within
 * [lo, hi].  The status, plan and error are the caller's to check further. */
static tg_status check_switch(int off, const char *sw, const char *text, tg_technique t, tg_aov aov,
                              unsigned effect, double lo, double hi, const char *what, tg_plan *plan, tg_error *err)
{
    tg_status st = plan_for(text, t, 1u << aov, 1, plan, err);
    if (off) {
        CHECK(refused(st, err, sw), "%s: status %d", what, (int)st);
    } else if (TG_NO_COLOR && (aov == TG_AOV_DIRECT || aov == TG_AOV_FAR || aov == TG_AOV_COLOR)) {
        CHECK(refused(st, err, "TG_NO_COLOR"), "%s: status %d", what, (int)st);
    } else if (TG_NO_BENT_NORMALS && aov == TG_AOV_FAR) {   /* lit in the bent cone */
        CHECK(refused(st, err, "TG_NO_BENT_NORMALS"), "%s: status %d", what, (int)st);
    } else {
        CHECK(st == TG_OK, "%s: %s", what, err->message);
        if (effect) CHECK(plan->effects & effect, "%s: effects %u", what, (unsigned)plan->effects);
        CHECK(renders_within(plan, aov, lo, hi), "%s: %s outside [%g, %g] or not finite", what, tg_aov_name(aov), lo, hi);
    }
    return st;
}

TEST(renders_colour_and_ao)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_COLOR, 3, &plan, &err);
    if (TG_NO_COLOR) {
        CHECK(refused(st, &err, "TG_NO_COLOR"), "status %d", (int)st);
    } else if (TG_NO_TEMPORAL) {
        CHECK(refused(st, &err, "TG_NO_TEMPORAL"), "status %d", (int)st);
        CHECK(plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_COLOR, 1, &plan, &err) == TG_OK, "%s", err.message);
        CHECK(!(plan.effects & TG_EFFECT_REPROJECTION), "effects %u", (unsigned)plan.effects);
        CHECK(renders_within(&plan, TG_AOV_COLOR, 0, 1e6), "colour not finite or negative");
    } else {
        CHECK(st == TG_OK, "%s", err.message);
        CHECK(plan.effects & TG_EFFECT_REPROJECTION, "effects %u", (unsigned)plan.effects);
        CHECK(renders_within(&plan, TG_AOV_COLOR, 0, 1e6), "colour not finite or negative");
    }
    CHECK(plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, &plan, &err) == TG_OK, "%s", err.message);
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
}

TEST(techniques)
{
    static const tg_technique some[] = { TG_TECH_GTAO, TG_TECH_SSAO, TG_TECH_BENTCONE, TG_TECH_SSILVB };
    tg_plan plan;
    tg_error err;
    int i;
    for (i = 0; i < (int)(sizeof some / sizeof some[0]); i++) {
        const char *name = tg_technique_name(some[i]);
        check_switch(TG_NO_TECHNIQUES, "TG_NO_TECHNIQUES", scene_plain, some[i], TG_AOV_AO, 0, 0, 1, name, &plan, &err);
        if (TG_NO_TECHNIQUES) CHECK(strstr(err.message, name) != NULL, "%s", err.message);
    }
}

TEST(reference)
{
    tg_plan plan;
    tg_error err;
    check_switch(TG_NO_REFERENCE, "TG_NO_REFERENCE", scene_plain, TG_TECH_REFERENCE, TG_AOV_AO, 0, 0, 1, "reference",
                 &plan, &err);
    if (TG_NO_REFERENCE) CHECK(plan.total_bytes == 0, "a refused plan has total_bytes %zu", plan.total_bytes);
}

TEST(shadow_maps)
{
    tg_plan plan;
    tg_error err;
    check_switch(TG_NO_SHADOW_MAPS, "TG_NO_SHADOW_MAPS", scene_rich, TG_TECH_HBIL, TG_AOV_DIRECT, TG_EFFECT_SHADOWS,
                 0, 1e6, "direct light", &plan, &err);
    /* AO of the same scene needs no shadow map (nor the environment) */
    CHECK(plan_for(scene_rich, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, &plan, &err) == TG_OK, "%s", err.message);
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
}

TEST(environment)
{
    tg_plan plan;
    tg_error err;
    check_switch(TG_NO_ENVIRONMENT, "TG_NO_ENVIRONMENT", scene_rich, TG_TECH_HBIL, TG_AOV_FAR, TG_EFFECT_FAR,
                 0, 1e6, "far", &plan, &err);
    /* colour over the sky reads the env even with `effects` leaving far out */
    check_switch(TG_NO_ENVIRONMENT, "TG_NO_ENVIRONMENT", scene_sky_no_far, TG_TECH_HBIL, TG_AOV_COLOR, 0,
                 0, 1e6, "sky", &plan, &err);
    if (!TG_NO_ENVIRONMENT && !TG_NO_COLOR) CHECK(!(plan.effects & TG_EFFECT_FAR), "sky: effects %u", (unsigned)plan.effects);
    /* a scene without env renders colour in every build with colour */
    {
        tg_status st = plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_COLOR, 1, &plan, &err);
        CHECK(TG_NO_COLOR ? refused(st, &err, "TG_NO_COLOR") : st == TG_OK, "%s", err.message);
    }
}

TEST(obj_meshes)
{
    tg_status st;
    tg_error err;
    const tg_scene *s = parse(scene_mesh, &st, &err);
    if (TG_NO_SCENE_TEXT) {
        CHECK(refused(st, &err, "TG_NO_SCENE_TEXT") && s == NULL, "status %d", (int)st);
    } else if (TG_NO_OBJ) {
        CHECK(refused(st, &err, "TG_NO_OBJ") && s == NULL, "status %d", (int)st);
        CHECK(err.line == 3 && err.col == 1, "at %d:%d", err.line, err.col);
    } else {
        CHECK(st == TG_OK && s != NULL, "%s", err.message);
    }
}

TEST(builtin_scenes)
{
    if (TG_NO_BUILTIN_SCENES) {
        CHECK(tg_builtin_scene("cornell") == NULL && tg_builtin_name(0) == NULL, "a built-in scene is left");
    } else {
        CHECK(tg_builtin_scene("cornell") != NULL && tg_builtin_name(0) != NULL, "no built-in scene");
    }
}

TEST(scene_text)
{
    tg_scene *s = NULL;
    tg_error err;
    tg_status st;
    tg_arena_init(&arena, scene_memory, sizeof scene_memory);
    st = tg_scene_parse(scene_plain, strlen(scene_plain), "switches.scene", NULL, &arena, &s, &err);
    if (TG_NO_SCENE_TEXT) {
        CHECK(refused(st, &err, "TG_NO_SCENE_TEXT") && s == NULL, "status %d", (int)st);
        CHECK(!strcmp(err.file, "switches.scene"), "error file %s", err.file);
        CHECK(arena.used == 0, "a refused parse took %zu bytes", arena.used);
    } else {
        CHECK(st == TG_OK && s != NULL, "%s", err.message);
    }
}

/* Colour and every light AOV are refused with TG_NO_COLOR=1; AO, bent
 * normals (unless TG_NO_BENT_NORMALS) and the geometry AOVs (here of the
 * lit scene) render. */
TEST(color)
{
    static const tg_aov light[] = { TG_AOV_COLOR, TG_AOV_IRRADIANCE, TG_AOV_DIRECT, TG_AOV_NEAR };
    tg_plan plan;
    tg_error err;
    tg_status st;
    int i;
    for (i = 0; i < 4; i++) {
        st = plan_for(scene_plain, TG_TECH_HBIL, 1u << light[i], FRAMES(2), &plan, &err);
        if (TG_NO_COLOR) CHECK(refused(st, &err, "TG_NO_COLOR"), "%s: status %d", tg_aov_name(light[i]), (int)st);
        else CHECK(st == TG_OK, "%s: %s", tg_aov_name(light[i]), err.message);
    }
    st = plan_for(scene_plain, TG_TECH_HBIL, (1u << TG_AOV_AO) | (TG_NO_BENT_NORMALS ? 0 : 1u << TG_AOV_BENT) |
                  (1u << TG_AOV_DEPTH) | (1u << TG_AOV_ALBEDO), FRAMES(2), &plan, &err);
    CHECK(st == TG_OK, "%s", err.message);
    CHECK(!(plan.effects & (TG_EFFECT_DIRECT | TG_EFFECT_NEAR)), "effects %u", (unsigned)plan.effects);
    if (!TG_NO_BENT_NORMALS) CHECK(renders_within(&plan, TG_AOV_BENT, -1, 1), "bent normal outside [-1, 1]");
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
    /* the radiance AOVs of an AO plan read 0 (without colour: their planes are never there) */
    CHECK(renders_within(&plan, TG_AOV_COLOR, 0, 0), "colour of an AO plan is not 0");
    CHECK(renders_within(&plan, TG_AOV_NEAR, 0, 0), "near field of an AO plan is not 0");
}

/* The bent and cone AOVs, and the far field lit in the bent cone, are
 * refused with TG_NO_BENT_NORMALS=1; AO renders (the same bits in every
 * build: ao_digest below). */
TEST(bent_normals)
{
    static const tg_aov bent[] = { TG_AOV_BENT, TG_AOV_CONE };
    tg_plan plan;
    tg_error err;
    tg_status st;
    int i;
    for (i = 0; i < 2; i++) {
        st = plan_for(scene_plain, TG_TECH_HBIL, 1u << bent[i], 1, &plan, &err);
        if (TG_NO_BENT_NORMALS) {
            CHECK(refused(st, &err, "TG_NO_BENT_NORMALS"), "%s: status %d", tg_aov_name(bent[i]), (int)st);
        } else {
            CHECK(st == TG_OK, "%s: %s", tg_aov_name(bent[i]), err.message);
            CHECK(renders_within(&plan, bent[i], bent[i] == TG_AOV_CONE ? 0 : -1, bent[i] == TG_AOV_CONE ? 1.571 : 1),
                  "%s out of range", tg_aov_name(bent[i]));
        }
    }
    if (!TG_NO_ENVIRONMENT && !TG_NO_COLOR)   /* else refused first for the env or the light */
        check_switch(TG_NO_BENT_NORMALS, "TG_NO_BENT_NORMALS", scene_rich, TG_TECH_HBIL, TG_AOV_FAR, TG_EFFECT_FAR,
                     0, 1e6, "far", &plan, &err);
    CHECK(plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, &plan, &err) == TG_OK, "%s", err.message);
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
}

/* gi_scale 2 (the kernel at quarter resolution) is refused with
 * TG_NO_GI_QUARTER=1; full resolution renders in every build. */
TEST(gi_quarter)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_with(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, QUARTER, &plan, &err);
    if (TG_NO_GI_QUARTER) {
        CHECK(refused(st, &err, "TG_NO_GI_QUARTER"), "status %d", (int)st);
    } else {
        CHECK(st == TG_OK, "%s", err.message);
        CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
    }
}

/* With TG_NO_TEMPORAL=1 every plan that carries history is refused:
 * temporal accumulation, motion vectors over frames, the near field's
 * reprojection; frames without history (temporal 0, AO) still render. */
TEST(temporal)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 3, &plan, &err);
    if (TG_NO_TEMPORAL) CHECK(refused(st, &err, "TG_NO_TEMPORAL"), "temporal accumulation: status %d", (int)st);
    else CHECK(st == TG_OK && renders_within(&plan, TG_AOV_AO, 0, 1), "temporal accumulation: %s", err.message);
    st = plan_with(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_MOTION, 2, NO_TEMPORAL, &plan, &err);
    if (TG_NO_TEMPORAL) CHECK(refused(st, &err, "TG_NO_TEMPORAL"), "motion: status %d", (int)st);
    else CHECK(st == TG_OK && renders_within(&plan, TG_AOV_MOTION, -1e6, 1e6), "motion: %s", err.message);
    st = plan_with(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 3, NO_TEMPORAL, &plan, &err);
    CHECK(st == TG_OK, "AO over frames without temporal accumulation: %s", err.message);
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
}

/* A scene with keys is refused with TG_NO_ANIMATION=1 (the camera and
 * objects can still come from the program); else its frames render. */
TEST(animation)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_for(scene_keyed, TG_TECH_HBIL, 1u << TG_AOV_AO, FRAMES(2), &plan, &err);
    if (TG_NO_ANIMATION) {
        CHECK(refused(st, &err, "TG_NO_ANIMATION"), "status %d", (int)st);
    } else {
        CHECK(st == TG_OK, "%s", err.message);
        CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
    }
}

/* FNV-1a of the AO AOV's values of scene_plain (HBIL, one frame), printed
 * as "ao-digest HEX": tests/switches_test.sh checks that every build of a
 * number type prints the same, so no switch changes what it keeps. */
static void ao_digest(void)
{
    tg_plan plan;
    tg_error err;
    tg_frame *f = NULL;
    tg_real row[W];
    uint32_t h = 2166136261u;
    void *mem;
    int x, y, ok;
    ok = plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, &plan, &err) == TG_OK;
    mem = ok ? malloc(plan.total_bytes) : NULL;
    ok = mem && tg_frame_create(&plan, mem, plan.total_bytes, &f, &err) == TG_OK && tg_frame_render(f, 0, &err) == TG_OK;
    for (y = 0; ok && y < H; y++) {
        ok = tg_frame_aov_row(f, TG_AOV_AO, y, row) == TG_OK;
        for (x = 0; x < W; x++) {
            unsigned char b[sizeof(tg_real)];
            size_t k;
            memcpy(b, &row[x], sizeof b);
            for (k = 0; k < sizeof b; k++) h = (h ^ b[k]) * 16777619u;
        }
    }
    free(mem);
    if (ok) printf("ao-digest %08lx\n", (unsigned long)h);
    else printf("ao-digest none: %s\n", err.message);
}

int main(void)
{
    ao_digest();
    RUN(renders_colour_and_ao);
    RUN(techniques);
    RUN(reference);
    RUN(shadow_maps);
    RUN(environment);
    RUN(obj_meshes);
    RUN(builtin_scenes);
    RUN(scene_text);
    RUN(color);
    RUN(gi_quarter);
    RUN(temporal);
    RUN(animation);
    RUN(bent_normals);
    return check_summary();
}
#endif /* !SWITCHES_PRINT */
