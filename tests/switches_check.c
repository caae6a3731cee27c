/* SPDX-License-Identifier: MIT */
/*
 * switches_check.c - one build of the core under the feature switches it is
 * compiled with (tinygi.h "FEATURE SWITCHES"; tests/switches_test.sh builds
 * it under each).  Every build renders what it keeps (colour HBIL with
 * direct light and reprojection, and AO), and for each switch either uses
 * the feature (switch 0: it works) or asks for it and must be refused with
 * TG_ERR_INPUT and a message naming the switch (switch 1).
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

static unsigned char scene_memory[1 << 20];
static tg_arena arena;

static tg_scene *parse(const char *text, tg_status *st, tg_error *err)
{
    tg_io io = { NULL, read_mem };
    tg_scene *s = NULL;
    tg_arena_init(&arena, scene_memory, sizeof scene_memory);
    *st = tg_scene_parse(text, strlen(text), "switches.scene", &io, &arena, &s, err);
    return s;
}

static tg_status plan_for(const char *text, tg_technique t, uint32_t aovs, int frames, tg_plan *plan, tg_error *err)
{
    tg_status st;
    tg_request req;
    tg_scene *s = parse(text, &st, err);
    if (st != TG_OK) return st;
    tg_request_defaults(&req);
    req.width = W;
    req.height = H;
    req.frames = frames;
    req.technique = t;
    req.aovs = aovs;
    return tg_plan_make(plan, s, &req, err);
}

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

TEST(renders_colour_and_ao)
{
    tg_plan plan;
    tg_error err;
    CHECK(plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_COLOR, 3, &plan, &err) == TG_OK, "%s", err.message);
    CHECK(plan.effects & TG_EFFECT_REPROJECTION, "effects %u", (unsigned)plan.effects);
    CHECK(renders_within(&plan, TG_AOV_COLOR, 0, 1e6), "colour not finite or negative");
    CHECK(plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, &plan, &err) == TG_OK, "%s", err.message);
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
}

TEST(techniques)
{
    static const tg_technique some[] = { TG_TECH_GTAO, TG_TECH_SSAO, TG_TECH_BENTCONE, TG_TECH_SSILVB };
    tg_plan plan;
    tg_error err;
    tg_status st;
    int i;
    for (i = 0; i < (int)(sizeof some / sizeof some[0]); i++) {
        st = plan_for(scene_plain, some[i], 1u << TG_AOV_AO, 1, &plan, &err);
        if (TG_NO_TECHNIQUES) {
            CHECK(refused(st, &err, "TG_NO_TECHNIQUES"), "%s: status %d", tg_technique_name(some[i]), (int)st);
            CHECK(strstr(err.message, tg_technique_name(some[i])) != NULL, "%s", err.message);
        } else {
            CHECK(st == TG_OK, "%s", err.message);
            CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "%s: AO outside [0, 1]", tg_technique_name(some[i]));
        }
    }
}

TEST(reference)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_for(scene_plain, TG_TECH_REFERENCE, 1u << TG_AOV_AO, 1, &plan, &err);
    if (TG_NO_REFERENCE) {
        CHECK(refused(st, &err, "TG_NO_REFERENCE"), "status %d", (int)st);
        CHECK(plan.total_bytes == 0, "a refused plan has total_bytes %zu", plan.total_bytes);
    } else {
        CHECK(st == TG_OK, "%s", err.message);
        CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "reference AO outside [0, 1]");
    }
}

TEST(shadow_maps)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_for(scene_rich, TG_TECH_HBIL, 1u << TG_AOV_DIRECT, 1, &plan, &err);
    if (TG_NO_SHADOW_MAPS) {
        CHECK(refused(st, &err, "TG_NO_SHADOW_MAPS"), "status %d", (int)st);
    } else {
        CHECK(st == TG_OK, "%s", err.message);
        CHECK(plan.effects & TG_EFFECT_SHADOWS, "effects %u", (unsigned)plan.effects);
        CHECK(renders_within(&plan, TG_AOV_DIRECT, 0, 1e6), "direct light not finite");
    }
    /* AO of the same scene needs no shadow map (nor the environment) */
    CHECK(plan_for(scene_rich, TG_TECH_HBIL, 1u << TG_AOV_AO, 1, &plan, &err) == TG_OK, "%s", err.message);
    CHECK(renders_within(&plan, TG_AOV_AO, 0, 1), "AO outside [0, 1]");
}

TEST(environment)
{
    tg_plan plan;
    tg_error err;
    tg_status st = plan_for(scene_rich, TG_TECH_HBIL, 1u << TG_AOV_FAR, 1, &plan, &err);
    if (TG_NO_ENVIRONMENT) {
        CHECK(refused(st, &err, "TG_NO_ENVIRONMENT"), "far: status %d", (int)st);
    } else {
        CHECK(st == TG_OK, "%s", err.message);
        CHECK(plan.effects & TG_EFFECT_FAR, "effects %u", (unsigned)plan.effects);
        CHECK(renders_within(&plan, TG_AOV_FAR, 0, 1e6), "far field not finite");
    }
    /* colour over the sky reads the env even with `effects` leaving far out */
    st = plan_for(scene_sky_no_far, TG_TECH_HBIL, 1u << TG_AOV_COLOR, 1, &plan, &err);
    if (TG_NO_ENVIRONMENT) {
        CHECK(refused(st, &err, "TG_NO_ENVIRONMENT"), "sky: status %d", (int)st);
    } else {
        CHECK(st == TG_OK && !(plan.effects & TG_EFFECT_FAR), "%s", err.message);
        CHECK(renders_within(&plan, TG_AOV_COLOR, 0, 1e6), "colour not finite");
    }
    /* a scene without env renders colour in every build */
    CHECK(plan_for(scene_plain, TG_TECH_HBIL, 1u << TG_AOV_COLOR, 1, &plan, &err) == TG_OK, "%s", err.message);
}

TEST(obj_meshes)
{
    tg_status st;
    tg_error err;
    tg_scene *s = parse(scene_mesh, &st, &err);
    if (TG_NO_OBJ) {
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

int main(void)
{
    RUN(renders_colour_and_ao);
    RUN(techniques);
    RUN(reference);
    RUN(shadow_maps);
    RUN(environment);
    RUN(obj_meshes);
    RUN(builtin_scenes);
    return check_summary();
}
