/* SPDX-License-Identifier: MIT */
/*
 * test_scene.c - the scene format v1 parser, OBJ/MTL meshes and the built-in
 * scenes (src/scene/parse.c, obj.c, builtin.c; format in src/scene/format.md).
 *
 * Checks exact geometry where there is an exact answer (quad and box
 * normals, positions, counts), unit outward sphere normals within a stated
 * tolerance, that every triangle's winding agrees with its normals, every
 * built-in scene, every class of bad input (TG_ERR_INPUT at the right
 * FILE:LINE:COL with a message saying what was expected), the arena
 * protocol (TG_ERR_MEMORY with bytes_needed, then success with exactly
 * that), and OBJ meshes read from memory and from tests/scenes/.
 */
#include "check.h"
#include "scene/scene.h"
#include "scene/lex.h"
#include "hosted/file.h"
#include <stdlib.h>

#define PI_D 3.14159265358979323846

#if TG_FIXED
#define NTOL 2e-3 /* unit-length tolerance: Q16.16 trig and sqrt */
#define PTOL 2e-3
#else
#define NTOL 1e-5
#define PTOL 1e-5
#endif

static unsigned char arena_mem[1 << 23];

static tg_status parse_io(const char *text, size_t n, const char *file, const tg_io *io,
                          tg_scene **s, tg_error *err)
{
    tg_arena a;
    tg_arena_init(&a, arena_mem, sizeof arena_mem);
    return tg_scene_parse(text, n, file, io, &a, s, err);
}

static tg_status parse(const char *text, tg_scene **s, tg_error *err)
{
    return parse_io(text, strlen(text), "t.scene", NULL, s, err);
}

static double D(tg_real r) { return check_d(r); }
typedef struct { double x, y, z; } dv;
static dv V(tg_vec3 v) { dv r; r.x = D(v.x); r.y = D(v.y); r.z = D(v.z); return r; }
static dv dsub(dv a, dv b) { dv r; r.x = a.x - b.x; r.y = a.y - b.y; r.z = a.z - b.z; return r; }
static double ddot(dv a, dv b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static dv dcross(dv a, dv b)
{
    dv r;
    r.x = a.y * b.z - a.z * b.y; r.y = a.z * b.x - a.x * b.z; r.z = a.x * b.y - a.y * b.x;
    return r;
}
static double dlen(dv a) { return sqrt(ddot(a, a)); }

static void print_error(const tg_error *err)
{
    char buf[600];
    tg_error_format(err, buf, sizeof buf);
    fprintf(stderr, "  %s\n", buf);
}

/* Invariants every parsed scene keeps; returns the number of problems. */
static int check_invariants(const tg_scene *s, const char *what)
{
    int bad = 0, t, i, o, sum = 0, m;
    /* every material's diffuse factor, formed once by the parser: albedo / pi (1 - F0) */
    for (m = 0; m < s->material_count; m++) {
        const tgi_material *mt = &s->materials[m];
        const double kd = (1 - D(mt->f0)) / 3.14159265358979, tol = TG_FIXED ? 3e-5 : 1e-6;
        CHECK(fabs(D(mt->diffuse.x) - D(mt->albedo.x) * kd) <= tol && fabs(D(mt->diffuse.y) - D(mt->albedo.y) * kd) <= tol &&
                  fabs(D(mt->diffuse.z) - D(mt->albedo.z) * kd) <= tol,
              "%s: material %s's diffuse %g %g %g, albedo %g %g %g, f0 %g", what, mt->name, D(mt->diffuse.x),
              D(mt->diffuse.y), D(mt->diffuse.z), D(mt->albedo.x), D(mt->albedo.y), D(mt->albedo.z), D(mt->f0));
    }
    for (o = 0; o < s->object_count; o++) {
        if (s->objects[o].first_tri != sum) bad++;
        sum += s->objects[o].tri_count;
        if (s->objects[o].key_count && s->objects[o].first_key + s->objects[o].key_count > s->object_key_count) bad++;
    }
    CHECK(sum == s->tri_count, "%s: object ranges cover %d of %d triangles", what, sum, s->tri_count);
    CHECK(bad == 0, "%s: %d objects with bad ranges", what, bad);
    bad = 0;
    for (t = 0; t < s->tri_count; t++) {
        dv p[3], n[3], fn;
        double area;
        if (s->tri_material[t] >= s->material_count) bad++;
        if (s->tri_object[t] >= s->object_count) bad++;
        if (t < s->objects[s->tri_object[t]].first_tri ||
            t >= s->objects[s->tri_object[t]].first_tri + s->objects[s->tri_object[t]].tri_count) bad++;
        for (i = 0; i < 3; i++) {
            p[i] = V(s->tri_pos[3 * t + i]);
            n[i] = V(s->tri_nrm[3 * t + i]);
            if (!isfinite(p[i].x) || !isfinite(p[i].y) || !isfinite(p[i].z)) bad++;
            if (fabs(dlen(n[i]) - 1.0) > NTOL) bad++;
            if (p[i].x < D(s->bounds_min.x) || p[i].y < D(s->bounds_min.y) || p[i].z < D(s->bounds_min.z) ||
                p[i].x > D(s->bounds_max.x) || p[i].y > D(s->bounds_max.y) || p[i].z > D(s->bounds_max.z)) bad++;
        }
        fn = dcross(dsub(p[1], p[0]), dsub(p[2], p[0]));
        area = dlen(fn);
        if (area > 1e-6) /* front face counter-clockwise: winding agrees with normals */
            for (i = 0; i < 3; i++)
                if (ddot(fn, n[i]) <= 0) { bad++; if (bad < 4) fprintf(stderr, "  %s: triangle %d winding disagrees with its normal\n", what, t); }
    }
    CHECK(bad == 0, "%s: %d bad triangle facts", what, bad);
    for (i = 1; i < s->camera_key_count; i++)
        CHECK(s->camera_keys[i - 1].t < s->camera_keys[i].t, "%s: camera keys not sorted", what);
    return bad;
}

/* ---- built-in scenes ---- */

/* Is world point c inside the camera's view at 4:3? */
static int in_view(const tg_scene *s, dv c)
{
    dv pos = V(s->camera.pos), f = dsub(V(s->camera.target), pos), up = V(s->camera.up), r, u, d;
    double lf = dlen(f), z, th = tan(D(s->camera.fov) / 2);
    f.x /= lf; f.y /= lf; f.z /= lf;
    r = dcross(f, up);
    u = dcross(r, f);
    d = dsub(c, pos);
    z = ddot(d, f);
    return z > 0 && fabs(ddot(d, r) / dlen(r)) < z * th * 4.0 / 3.0 && fabs(ddot(d, u) / dlen(u)) < z * th;
}

static int find_mat(const tg_scene *s, const char *name)
{
    int i;
    for (i = 0; i < s->material_count; i++)
        if (strcmp(s->materials[i].name, name) == 0) return i;
    return -1;
}

static int find_obj(const tg_scene *s, const char *name)
{
    int i;
    for (i = 0; i < s->object_count; i++)
        if (strcmp(s->objects[i].name, name) == 0) return i;
    return -1;
}

/* Lowest y of an object's vertices. */
static double object_min_y(const tg_scene *s, int o)
{
    double m = 1e30;
    int t, i;
    for (t = s->objects[o].first_tri; t < s->objects[o].first_tri + s->objects[o].tri_count; t++)
        for (i = 0; i < 3; i++) m = fmin(m, D(s->tri_pos[3 * t + i].y));
    return m;
}

TEST(builtins_parse)
{
    int i, n = 0;
    const char *name;
    for (i = 0; (name = tg_builtin_name(i)) != NULL; i++) {
        tg_scene *s = NULL;
        tg_error err;
        tg_status st;
        dv c;
        char file[64];
        snprintf(file, sizeof file, "builtin:%s", name);
        st = parse_io(tg_builtin_scene(name), strlen(tg_builtin_scene(name)), file, NULL, &s, &err);
        CHECK(st == TG_OK, "%s does not parse", name);
        if (st) { print_error(&err); continue; }
        n++;
        CHECK(s->tri_count > 0 && s->tri_count < 5000, "%s: %d triangles", name, s->tri_count);
        check_invariants(s, name);
        c.x = (D(s->bounds_min.x) + D(s->bounds_max.x)) / 2;
        c.y = (D(s->bounds_min.y) + D(s->bounds_max.y)) / 2;
        c.z = (D(s->bounds_min.z) + D(s->bounds_max.z)) / 2;
        CHECK(in_view(s, c), "%s: the scene's centre is outside the camera's view", name);
        CHECK(s->light_count >= 1, "%s: no light", name);
        CHECK(tg_builtin_scene(file) == tg_builtin_scene(name), "%s: builtin: prefix", name);
        for (st = 0; (int)st < s->material_count; st++)
            CHECK(D(s->materials[st].f0) > 0.01 && D(s->materials[st].f0) < 0.1, "%s: f0", name);
    }
    CHECK(n == 5, "5 built-in scenes, got %d", n);
    CHECK(tg_builtin_scene("nope") == NULL, "unknown builtin");
    CHECK(tg_builtin_name(-1) == NULL && tg_builtin_name(5) == NULL, "names past the end");
}

TEST(builtin_cornell)
{
    tg_scene *s;
    tg_error err;
    int red, green, lamp, o, t, i;
    const char *text = tg_builtin_scene("cornell");
    CHECK(parse(text, &s, &err) == TG_OK, "parse");
    red = find_mat(s, "red");
    green = find_mat(s, "green");
    lamp = find_mat(s, "lamp");
    CHECK(red >= 0 && green >= 0 && lamp >= 0, "materials");
    if (red < 0 || green < 0 || lamp < 0) return;
    CHECK(D(s->materials[red].albedo.x) > 2 * D(s->materials[red].albedo.y), "red is red");
    CHECK(D(s->materials[green].albedo.y) > 2 * D(s->materials[green].albedo.x), "green is green");
    CHECK(D(s->materials[lamp].emissive.x) > 0, "the ceiling patch emits");
    CHECK(s->env.type == TG_ENV_NONE, "closed box: no env");
    CHECK(s->lights[0].type == TG_LIGHT_POINT && s->lights[0].shadows, "point light with shadows");
    CHECK(D(s->lights[0].pos.y) < D(s->bounds_max.y) && D(s->lights[0].pos.y) > D(s->bounds_max.y) - 0.5,
          "light just below the ceiling");
    /* red wall on the camera's left: right = forward x up */
    {
        dv f = dsub(V(s->camera.target), V(s->camera.pos)), r = dcross(f, V(s->camera.up));
        o = find_obj(s, "left_wall");
        CHECK(o >= 0 && s->tri_material[s->objects[o].first_tri] == red, "left wall is red");
        if (o >= 0) {
            dv p = V(s->tri_pos[3 * s->objects[o].first_tri]);
            dv toward = dsub(p, V(s->camera.target));
            CHECK(ddot(toward, r) < 0, "the red wall is on the left of the image");
        }
    }
    /* both blocks stand on the floor, the tall one taller */
    o = find_obj(s, "tall_block");
    t = find_obj(s, "short_block");
    CHECK(o >= 0 && t >= 0, "blocks");
    if (o >= 0 && t >= 0)
        CHECK(D(s->tri_pos[3 * s->objects[o].first_tri].y) > D(s->tri_pos[3 * s->objects[t].first_tri].y),
              "tall block is taller");
    /* the front (toward the camera) is open: no triangle faces the camera from z < 0 */
    for (t = 0; t < s->tri_count; t++)
        for (i = 0; i < 3; i++) CHECK(D(s->tri_pos[3 * t + i].z) >= 0, "geometry in front of the box");
}

TEST(builtin_spheres_rest_on_floor)
{
    tg_scene *s;
    tg_error err;
    int o, spheres = 0;
    CHECK(parse(tg_builtin_scene("spheres"), &s, &err) == TG_OK, "parse");
    for (o = 0; o < s->object_count; o++)
        if (strncmp(s->objects[o].name, "sphere_", 7) == 0) {
            spheres++;
            CHECK_NEAR(object_min_y(s, o), 0.0, 1e-3);
        }
    CHECK(spheres >= 3, "%d named spheres", spheres);
    CHECK(s->env.type == TG_ENV_SKY, "sky");
    CHECK(s->lights[0].type == TG_LIGHT_DIRECTIONAL && s->lights[0].shadows, "sun with shadows");
    CHECK(parse(tg_builtin_scene("columns"), &s, &err) == TG_OK, "columns");
    CHECK(s->env.type == TG_ENV_SKY && s->lights[0].shadows, "columns: sky and shadowed sun");
    CHECK(find_obj(s, "column7") >= 0, "8 columns");
    CHECK(parse(tg_builtin_scene("groove"), &s, &err) == TG_OK, "groove");
    CHECK(s->tri_count == 4, "groove: two quads");
    CHECK(fabs(ddot(V(s->tri_nrm[0]), V(s->tri_nrm[6]))) < 1e-6, "groove: planes at 90 degrees");
}

/* ---- geometry ---- */

#define CAM "camera pos 0 1 5 target 0 0 0\n"
#define MAT "material m albedo 0.5 0.5 0.5\n"

static int veq(tg_vec3 a, double x, double y, double z)
{
    return D(a.x) == x && D(a.y) == y && D(a.z) == z;
}

TEST(quad_exact)
{
    tg_scene *s;
    tg_error err;
    int i;
    tg_status st = parse(CAM MAT "quad p0 0 0 0 p1 0 0 1 p2 1 0 1 p3 1 0 0 material m name floor\n"
                         "quad p0 0 2 0 p1 1 2 0 p2 1 2 1 p3 0 2 1 material m\n", &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(s->tri_count == 4 && s->object_count == 2, "%d tris %d objects", s->tri_count, s->object_count);
    for (i = 0; i < 6; i++) CHECK(veq(s->tri_nrm[i], 0, 1, 0), "up-facing quad normal %d", i);
    for (i = 6; i < 12; i++) CHECK(veq(s->tri_nrm[i], 0, -1, 0), "down-facing quad normal %d", i);
    CHECK(veq(s->tri_pos[0], 0, 0, 0) && veq(s->tri_pos[1], 0, 0, 1) && veq(s->tri_pos[2], 1, 0, 1),
          "triangle (p0 p1 p2)");
    CHECK(veq(s->tri_pos[3], 0, 0, 0) && veq(s->tri_pos[4], 1, 0, 1) && veq(s->tri_pos[5], 1, 0, 0),
          "triangle (p0 p2 p3)");
    CHECK(strcmp(s->objects[0].name, "floor") == 0 && s->objects[1].name[0] == '\0', "object names");
    CHECK(s->objects[1].first_tri == 2 && s->objects[1].tri_count == 2, "second object range");
    CHECK(veq(s->bounds_min, 0, 0, 0) && veq(s->bounds_max, 1, 2, 1), "bounds");
    CHECK(s->tri_material[0] == 0 && s->tri_object[3] == 1, "per-triangle indices");
    check_invariants(s, "quads");
}

static void check_box(int inward)
{
    tg_scene *s;
    tg_error err;
    int t, i, dirs[6] = {0, 0, 0, 0, 0, 0};
    dv center = {0, 1, 0};
    tg_status st = parse(inward ? CAM MAT "box min -1 0 -2 max 1 2 2 material m inward\n"
                                : CAM MAT "box min -1 0 -2 max 1 2 2 material m\n", &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(s->tri_count == 12, "%d triangles", s->tri_count);
    for (t = 0; t < s->tri_count; t++) {
        dv n = V(s->tri_nrm[3 * t]), c = {0, 0, 0};
        int axis = n.x != 0 ? 0 : n.y != 0 ? 1 : 2;
        for (i = 0; i < 3; i++) {
            dv p = V(s->tri_pos[3 * t + i]);
            c.x += p.x / 3; c.y += p.y / 3; c.z += p.z / 3;
            CHECK(ddot(V(s->tri_nrm[3 * t + i]), n) == 1.0, "flat exact normals");
        }
        CHECK(fabs(n.x) + fabs(n.y) + fabs(n.z) == 1.0, "axis-aligned unit normal");
        CHECK((ddot(n, dsub(c, center)) > 0) == !inward, "triangle %d faces %s", t, inward ? "in" : "out");
        dirs[2 * axis + ((axis == 0 ? n.x : axis == 1 ? n.y : n.z) > 0)]++;
    }
    for (i = 0; i < 6; i++) CHECK(dirs[i] == 2, "two triangles per face direction %d", i);
    CHECK(veq(s->bounds_min, -1, 0, -2) && veq(s->bounds_max, 1, 2, 2), "bounds");
    check_invariants(s, "box");
}

TEST(box_outward) { check_box(0); }
TEST(box_inward) { check_box(1); }

TEST(sphere_normals)
{
    tg_scene *s;
    tg_error err;
    int t, i;
    double maxerr = 0;
    tg_status st = parse(CAM MAT "sphere center 1 2 3 radius 2 material m\n"
                         "sphere center 0 0 0 radius 1 material m segments 8 name small\n", &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(s->objects[0].tri_count == 2 * 24 * 11, "24 segments: %d triangles", s->objects[0].tri_count);
    CHECK(s->objects[1].tri_count == 2 * 8 * 3, "8 segments: %d triangles", s->objects[1].tri_count);
    for (t = 0; t < s->objects[0].tri_count; t++)
        for (i = 0; i < 3; i++) {
            dv p = V(s->tri_pos[3 * t + i]), n = V(s->tri_nrm[3 * t + i]), c = {1, 2, 3}, d = dsub(p, c);
            double e = fabs(d.x / 2 - n.x) + fabs(d.y / 2 - n.y) + fabs(d.z / 2 - n.z);
            maxerr = fmax(maxerr, e);
            CHECK(ddot(n, d) > 0, "outward");
            CHECK_NEAR(dlen(d), 2.0, 4 * PTOL);
        }
    CHECK(maxerr < 6 * PTOL, "normal = (p - c) / r within %g, got %g", 6 * PTOL, maxerr);
    CHECK(D(s->bounds_max.y) == 4.0 && D(s->bounds_min.y) == -1.0, "poles exact: y in [%g, %g]",
          D(s->bounds_min.y), D(s->bounds_max.y));
    CHECK(D(s->bounds_max.x) <= 3.0 + PTOL && D(s->bounds_max.x) >= 2.9, "x extent");
    check_invariants(s, "spheres");
}

/* ---- values, defaults, units ---- */

TEST(defaults)
{
    tg_scene *s;
    tg_error err;
    tg_status st = parse(CAM MAT "light point pos 0 5 0 color 1 1 1\n", &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(veq(s->camera.up, 0, 1, 0), "up +Y");
    CHECK_NEAR(D(s->camera.fov), PI_D / 3, 2e-4);
    CHECK_NEAR(D(s->camera.znear), 0.05, 1e-4);
    CHECK_NEAR(D(s->camera.zfar), 1000, 1e-3);
    CHECK_NEAR(D(s->materials[0].f0), 0.04, 1e-4);
    CHECK(veq(s->materials[0].emissive, 0, 0, 0) && !s->materials[0].twosided, "material defaults");
    CHECK(D(s->lights[0].intensity) == 1.0 && !s->lights[0].shadows, "light defaults");
    CHECK(s->env.type == TG_ENV_NONE, "no env");
    CHECK(D(s->gi.radius) == -1.0 && s->gi.slices == 0 && s->gi.samples == 0 && s->gi.bounces == -1,
          "gi unset");
    CHECK(s->effects_auto == 1 && s->effects == 0, "effects auto");
    CHECK(s->tri_count == 0 && s->object_count == 0 && s->camera_key_count == 0, "empty");
}

TEST(values_and_units)
{
    tg_scene *s;
    tg_error err;
    int i;
    tg_status st = parse(
        "camera pos 0 1 5 target 0 0 0 up 0 2 0 fov 90 near 0.1 far 50\n"
        MAT "material g albedo 0 1 0.25 f0 0.5 emissive 2 3 4 twosided\n"
        "light directional dir 0 -2 0 color 1 1 1 intensity 3 shadows\n"
        "light spot pos 0 5 0 dir 3 0 4 angle 30 color 1 0.5 0.25\n"
        "env sky 0.1 0.2 0.3 ground 0.3 0.2 0.1 up 0 0 5\n"
        "gi radius 2 slices 3 samples 8 bounces 0\n"
        "effects direct shadows ao\n", &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK_NEAR(D(s->camera.fov), PI_D / 2, 2e-4);
    CHECK(veq(s->camera.up, 0, 1, 0), "up normalized");
    CHECK_NEAR(D(s->camera.znear), 0.1, 1e-4);
    CHECK_NEAR(D(s->camera.zfar), 50, 1e-4);
    CHECK(s->material_count == 2 && strcmp(s->materials[1].name, "g") == 0, "materials");
    CHECK(veq(s->materials[1].albedo, 0, 1, 0.25) && D(s->materials[1].f0) == 0.5, "albedo f0");
    CHECK(veq(s->materials[1].emissive, 2, 3, 4) && s->materials[1].twosided, "emissive twosided");
    CHECK(s->light_count == 2, "lights");
    CHECK(s->lights[0].type == TG_LIGHT_DIRECTIONAL && veq(s->lights[0].dir, 0, -1, 0), "dir normalized");
    CHECK(D(s->lights[0].intensity) == 3.0 && s->lights[0].shadows, "intensity shadows");
    CHECK(s->lights[1].type == TG_LIGHT_SPOT && veq(s->lights[1].pos, 0, 5, 0), "spot");
    CHECK_NEAR(D(s->lights[1].dir.x), 0.6, 1e-4);
    CHECK_NEAR(D(s->lights[1].dir.z), 0.8, 1e-4);
    CHECK_NEAR(D(s->lights[1].angle), PI_D / 6, 2e-4);
    CHECK(s->env.type == TG_ENV_SKY && veq(s->env.up, 0, 0, 1), "sky up normalized");
    CHECK_NEAR(D(s->env.sky.z), 0.3, 1e-4);
    CHECK_NEAR(D(s->env.ground.x), 0.3, 1e-4);
    CHECK(D(s->gi.radius) == 2 && s->gi.slices == 3 && s->gi.samples == 8 && s->gi.bounces == 0, "gi");
    CHECK(!s->effects_auto && s->effects == (TG_EFFECT_DIRECT | TG_EFFECT_SHADOWS | TG_EFFECT_AO), "effects");
    st = parse(CAM "env sh9 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 -27\n"
               "effects far near reprojection\n", &s, &err);
    CHECK(st == TG_OK, "sh9");
    if (st) { print_error(&err); return; }
    CHECK(s->env.type == TG_ENV_SH9, "sh9 type");
    for (i = 0; i < 9; i++)
        CHECK(D(s->env.sh9[i].x) == 3 * i + 1 && D(s->env.sh9[i].y) == 3 * i + 2 &&
              fabs(D(s->env.sh9[i].z)) == 3 * i + 3, "sh9 coefficient %d in order", i);
    CHECK(D(s->env.sh9[8].z) == -27, "negative sh9 allowed");
    CHECK(s->effects == (TG_EFFECT_FAR | TG_EFFECT_NEAR | TG_EFFECT_REPROJECTION), "effects 2");
    st = parse("camera pos 0 10 0 target 0 0 0\n", &s, &err);
    CHECK(st == TG_OK && veq(s->camera.up, 0, 1, 0), "a camera looking straight down parses (up kept as +Y)");
    st = parse(CAM "env uniform 0.5 0.25 0\neffects auto\n", &s, &err);
    CHECK(st == TG_OK && s->env.type == TG_ENV_UNIFORM && veq(s->env.uniform, 0.5, 0.25, 0), "uniform");
    CHECK(s->effects_auto, "effects auto");
}

TEST(keys_sorted)
{
    tg_scene *s;
    tg_error err;
    int a, b;
    tg_status st = parse(
        "camera_key t 2 pos 0 0 2 target 0 0 0\n"
        "camera_key t 0 pos 0 0 5 target 0 1 0\n"
        "camera_key t 1 pos 0 0 3 target 0 0 0\n"
        MAT "box min 0 0 0 max 1 1 1 material m name a\n"
        "box min 2 0 0 max 3 1 1 material m name b\n"
        "object_key name b t 1 translate 1 0 0\n"
        "object_key name a t 5 rotate 0 0 2 180\n"
        "object_key name b t 0\n"
        "object_key name a t -1 translate 0 1 0\n", &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(s->camera_key_count == 3, "3 camera keys");
    CHECK(D(s->camera_keys[0].t) == 0 && D(s->camera_keys[1].t) == 1 && D(s->camera_keys[2].t) == 2, "sorted");
    CHECK(veq(s->camera.pos, 0, 0, 5) && veq(s->camera.target, 0, 1, 0), "camera from the first key");
    a = find_obj(s, "a");
    b = find_obj(s, "b");
    CHECK(s->object_key_count == 4 && s->objects[a].key_count == 2 && s->objects[b].key_count == 2, "key counts");
    CHECK(D(s->object_keys[s->objects[a].first_key].t) == -1 && D(s->object_keys[s->objects[a].first_key + 1].t) == 5,
          "a's keys sorted");
    CHECK(D(s->object_keys[s->objects[b].first_key].t) == 0 && D(s->object_keys[s->objects[b].first_key + 1].t) == 1,
          "b's keys sorted");
    CHECK(veq(s->object_keys[s->objects[a].first_key + 1].axis, 0, 0, 1), "axis normalized");
    CHECK_NEAR(D(s->object_keys[s->objects[a].first_key + 1].angle), PI_D, 5e-4);
    CHECK(veq(s->object_keys[s->objects[b].first_key + 1].translate, 1, 0, 0), "translate");
    CHECK(veq(s->object_keys[s->objects[b].first_key].axis, 0, 1, 0) &&
          D(s->object_keys[s->objects[b].first_key].angle) == 0, "no rotation by default");
    check_invariants(s, "keys");
}

TEST(lexing)
{
    tg_scene *s;
    tg_error err;
    char line[TG_MAX_LINE + 64];
    tg_status st;
    /* BOM, CRLF, tabs, comments, blank lines, a line of exactly the limit */
    st = parse("\xEF\xBB\xBF# comment\r\n\r\n\tcamera\tpos 0 1 5 target 0 0 0 # trailing\r\n" MAT, &s, &err);
    CHECK(st == TG_OK, "BOM, CRLF, tabs");
    if (st) print_error(&err);
    memset(line, ' ', sizeof line);
    memcpy(line, CAM, strlen(CAM));
    line[strlen(CAM) + TG_MAX_LINE - 1] = '#';
    line[strlen(CAM) + TG_MAX_LINE] = '\n';
    line[strlen(CAM) + TG_MAX_LINE + 1] = '\0';
    st = parse(line, &s, &err);
    CHECK(st == TG_OK, "a line of exactly %d bytes", TG_MAX_LINE);
    line[strlen(CAM) + TG_MAX_LINE] = ' ';
    line[strlen(CAM) + TG_MAX_LINE + 1] = '\n';
    line[strlen(CAM) + TG_MAX_LINE + 2] = '\0';
    st = parse(line, &s, &err);
    CHECK(st == TG_ERR_INPUT && err.line == 2 && err.col == TG_MAX_LINE + 1 && strstr(err.message, "line length in bytes must be 0..4096, got 4097"),
          "a line of %d bytes: %d:%d %s", TG_MAX_LINE + 1, err.line, err.col, err.message);
    /* CR-only line ends (old Mac text) end lines too; lines are counted */
    st = parse("camera pos 0 1 5 target 0 0 0\rmaterial m albedo 1 1 1\r\rmaterial n albedo 1 1 1\r", &s, &err);
    CHECK(st == TG_OK && s->material_count == 2, "CR-only lines: %s", err.message);
    st = parse("camera pos 0 1 5 target 0 0 0\r\n\rmaterial m albedo 1 1 1\rbogus\r", &s, &err);
    CHECK(st == TG_ERR_INPUT && err.line == 4 && err.col == 1 && strstr(err.message, "unknown keyword 'bogus'"),
          "CR, CRLF and CR lines counted: %d:%d %s", err.line, err.col, err.message);
    {
        static const char nul[] = "camera pos 0 1 5\0 target 0 0 0\n";
        st = parse_io(nul, sizeof nul - 1, "n.scene", NULL, &s, &err);
        CHECK(st == TG_ERR_INPUT && err.line == 1 && err.col == 17 && strstr(err.message, "NUL byte"),
              "NUL: %d:%d %s", err.line, err.col, err.message);
    }
}

/* A value that rounds to 0 in the number type says so; one past the range
 * says what the range is. */
TEST(number_notes)
{
#if TG_FIXED
    static const char tiny[] = "0.000001", huge[] = "40000";
#else
    static const char tiny[] = "1e-50", huge[] = "1e39";
#endif
    char text[256];
    tg_scene *s;
    tg_error err;
    snprintf(text, sizeof text, CAM MAT "sphere center 0 0 0 radius %s material m\n", tiny);
    CHECK(parse(text, &s, &err) == TG_ERR_INPUT && err.line == 3 && err.col == 28 &&
          strstr(err.message, "'radius' must be greater than 0") && strstr(err.message, TGI_ZERO_NOTE),
          "radius %s: %d:%d %s", tiny, err.line, err.col, err.message);
    snprintf(text, sizeof text, CAM MAT "mesh file a.obj material m scale %s\n", tiny);
    CHECK(parse(text, &s, &err) == TG_ERR_INPUT && strstr(err.message, TGI_ZERO_NOTE), "scale %s: %s", tiny, err.message);
    snprintf(text, sizeof text, "camera pos 0 1 5 target 0 0 0 up 0 %s 0\n", tiny);
    CHECK(parse(text, &s, &err) == TG_ERR_INPUT && strstr(err.message, "non-zero length") &&
          strstr(err.message, TGI_ZERO_NOTE), "up 0 %s 0: %s", tiny, err.message);
    snprintf(text, sizeof text, "camera pos 0 1 5 target 0 0 0 up 0 0 0\n");
    CHECK(parse(text, &s, &err) == TG_ERR_INPUT && !strstr(err.message, "rounds to 0"), "a true zero: %s", err.message);
    snprintf(text, sizeof text, "camera pos 0 %s 5 target 0 0 0\n", huge);
    CHECK(parse(text, &s, &err) == TG_ERR_INPUT && err.col == 14 && strstr(err.message, "number out of range") &&
          strstr(err.message, TGI_RANGE_NOTE), "pos 0 %s 5: %s", huge, err.message);
    CHECK(strstr(TG_FIXED ? TGI_ZERO_NOTE : "Q16.16", "Q16.16") != NULL, "the fixed-point note names Q16.16");
}

/* ---- bad input: every class of error ---- */

typedef struct bad_case {
    const char *text;
    int line, col;
    const char *fragment;
} bad_case;

static const bad_case bad_cases[] = {
    {"camra pos 0 0 0 target 1 1 1\n", 1, 1, "unknown keyword 'camra'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 1 1 1 shiny 3\n", 2, 25, "unknown key 'shiny'"},
    {"camera pos 0 1 5 target 0 0 0\nbox min 0 0 0 max 1 1 1 material m outward\n", 2, 36, "unknown key 'outward'"},
    {"camera pos 0 1 5\n", 1, 1, "missing the required key 'target'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nsphere center 0 0 0 material m\n", 3, 1, "missing the required key 'radius'"},
    {"camera pos 0 1 target 0 0 0\n", 1, 16, "'pos' expects 3 numbers, got 2"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 1 1\n", 2, 22, "'albedo' expects 3 numbers, got 2"},
    {"camera pos 0 1 5 7 target 0 0 0\n", 1, 18, "too many numbers for 'pos' (expects 3)"},
    {"camera pos 0 x 5 target 0 0 0\n", 1, 14, "expected a number for 'pos', got 'x'"},
    {"camera pos 0 nan 5 target 0 0 0\n", 1, 14, "expected a number for 'pos'"},
    {"camera pos 0 inf 5 target 0 0 0\n", 1, 14, "expected a number for 'pos'"},
    {"camera pos 0 1e999 5 target 0 0 0\n", 1, 14, "number out of range for 'pos'"},
    {"camera pos 0 1 5 target 0 0 0 fov 1.5.2\n", 1, 35, "expected a number for 'fov'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 -0.1 0.5\n", 2, 23, "'albedo' must be in [0, 1]"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 1.5\n", 2, 27, "'albedo' must be in [0, 1]"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5 f0 2\n", 2, 34, "'f0' must be in [0, 1]"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5 emissive 1 -1 1\n", 2, 42, "'emissive' must be 0 or more"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nsphere center 0 0 0 radius -1 material m\n", 3, 28, "'radius' must be greater than 0"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nsphere center 0 0 0 radius 0 material m\n", 3, 28, "'radius' must be greater than 0"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nsphere center 0 0 0 radius 1 material m segments 2\n", 3, 50, "sphere segments must be 4..256, got 2"},
    {"camera pos 0 1 5 target 0 0 0 fov 0\n", 1, 35, "'fov' must be between 0 and 180"},
    {"camera pos 0 1 5 target 0 0 0 fov 180\n", 1, 35, "'fov' must be between 0 and 180"},
    {"camera pos 0 1 5 target 0 0 0 near 0\n", 1, 36, "'near' must be greater than 0"},
    {"camera pos 0 1 5 target 0 0 0 near 2 far 1\n", 1, 42, "'far' must be greater than 'near'"},
    {"camera pos 1 2 3 target 1 2 3\n", 1, 25, "'target' must differ from 'pos'"},
    {"camera pos 0 1 5 target 0 0 0 up 0 0 0\n", 1, 34, "'up' must be a direction of non-zero length"},
    {"camera pos 0 1 5 pos 1 1 1 target 0 0 0\n", 1, 18, "duplicate key 'pos'"},
    {"camera pos 0 1 5 target 0 0 0\nlight directional dir 0 0 0 color 1 1 1\n", 2, 23, "'dir' must be a direction of non-zero length"},
    {"camera pos 0 1 5 target 0 0 0\nlight spot pos 0 5 0 dir 0 -1 0 angle 95 color 1 1 1\n", 2, 39, "'angle' must be in (0, 90]"},
    {"camera pos 0 1 5 target 0 0 0\nlight spot pos 0 5 0 dir 0 -1 0 angle 0 color 1 1 1\n", 2, 39, "'angle' must be in (0, 90]"},
    {"camera pos 0 1 5 target 0 0 0\nlight point pos 0 5 0 color 1 1 1 intensity -2\n", 2, 45, "'intensity' must be 0 or more"},
    {"camera pos 0 1 5 target 0 0 0\nlight point pos 0 5 0 color 1 -1 1\n", 2, 31, "'color' must be 0 or more"},
    {"camera pos 0 1 5 target 0 0 0\nlight area pos 0 0 0 color 1 1 1\n", 2, 7, "unknown light type 'area'"},
    {"camera pos 0 1 5 target 0 0 0\nlight spot pos 0 5 0 dir 0 -1 0 color 1 1 1\n", 2, 1, "missing the required key 'angle'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nmaterial m albedo 1 1 1\n", 3, 10, "duplicate material 'm'"},
    {"camera pos 0 1 5 target 0 0 0\nquad p0 0 0 0 p1 1 0 0 p2 1 1 0 p3 0 1 0 material nope\n", 2, 51, "undefined material 'nope'"},
    {"camera pos 0 1 5 target 0 0 0\nquad p0 0 0 0 p1 1 0 0 p2 1 1 0 p3 0 1 0 material m\nmaterial m albedo 0.5 0.5 0.5\n", 2, 51, "undefined material 'm'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial albedo 1 1 1\n", 2, 10, "'material' expects a name first"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa albedo 1 1 1\n", 2, 10, "name length in bytes must be 1..31, got 32"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nbox min 0 0 0 max 1 1 1 material m name a\nbox min 2 0 0 max 3 1 1 material m name a\n", 4, 41, "duplicate object name 'a'"},
    {"camera pos 0 1 5 target 0 0 0\nobject_key name ghost t 0\n", 2, 17, "undefined object 'ghost'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nbox min 0 0 0 max 1 1 1 material m name a\nobject_key name a t 0 rotate 0 0 0 90\n", 4, 30, "'rotate' must be a direction of non-zero length"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nbox min 0 0 0 max 1 1 1 material m name a\nobject_key name a t 1\nobject_key name a t 1\n", 5, 21, "duplicate object_key time"},
    {"camera pos 0 1 5 target 0 0 0\ncamera_key t 0 pos 0 0 0 target 0 0 1\ncamera_key t 0 pos 1 0 0 target 0 0 1\n", 3, 14, "duplicate camera_key time"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nbox min 0 0 0 max 1 0 1 material m\n", 3, 21, "box 'max' must be greater than 'min'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nquad p0 0 0 0 p1 1 0 0 p2 2 0 0 p3 3 0 0 material m\n", 3, 9, "quad has zero area"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nmesh file a.obj material m scale 0\n", 3, 34, "'scale' must be greater than 0"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nmesh file missing.obj material m\n", 3, 11, "cannot read mesh file 'scenes/missing.obj'"},
    {"camera pos 0 1 5 target 0 0 0\nenv hdr 1 1 1\n", 2, 5, "unknown env type 'hdr'"},
    {"camera pos 0 1 5 target 0 0 0\nenv uniform 1 1\n", 2, 16, "'uniform' expects 3 numbers, got 2"},
    {"camera pos 0 1 5 target 0 0 0\nenv uniform 1 1 1 1\n", 2, 19, "too many numbers for 'uniform' (expects 3)"},
    {"camera pos 0 1 5 target 0 0 0\nenv uniform 1 -1 1\n", 2, 15, "'uniform' must be 0 or more"},
    {"camera pos 0 1 5 target 0 0 0\nenv sh9 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1 0.1\n", 2, 112, "'sh9' expects 27 numbers, got 26"},
    {"camera pos 0 1 5 target 0 0 0\nenv sky 1 1 1 ground 1 1 1\nenv uniform 1 1 1\n", 3, 1, "duplicate 'env'"},
    {"camera pos 0 1 5 target 0 0 0\nenv sky 1 1 1\n", 2, 1, "missing the required key 'ground'"},
    {"camera pos 0 1 5 target 0 0 0\ngi slices 0\n", 2, 11, "gi slices must be 1..8, got 0"},
    {"camera pos 0 1 5 target 0 0 0\ngi samples 2.5\n", 2, 12, "expected an integer for 'samples'"},
    {"camera pos 0 1 5 target 0 0 0\ngi radius -1\n", 2, 11, "gi radius must be 0..10000, got -1"},
    {"camera pos 0 1 5 target 0 0 0\ngi bounces 101\n", 2, 12, "gi bounces must be 0..100, got 101"},
    {"camera pos 0 1 5 target 0 0 0\neffects direct glow\n", 2, 16, "unknown effect 'glow'"},
    {"camera pos 0 1 5 target 0 0 0\neffects auto ao\n", 2, 14, "'auto' cannot be mixed"},
    {"camera pos 0 1 5 target 0 0 0\neffects\n", 2, 8, "'effects' expects a value"},
    {"camera pos 0 1 5 target 0 0 0\ncamera pos 0 1 5 target 0 0 0\n", 2, 1, "duplicate 'camera'"},
    {"material m albedo 0.5 0.5 0.5\n", 1, 1, "the scene has no 'camera' statement"},
    {"  camera pos 0 1 5 target 0 0 0 # fine\n\tbogus 1 # comment\n", 2, 2, "unknown keyword 'bogus'"},
    {"camera pos 0 1 5 target 0 0 0\nmaterial m albedo 1 1 1 twosided 1\n", 2, 34, "unknown key '1'"},
};

/* One bad case: refused with no scene, at its file, line and column, with
 * its fragment in the message; `table` names the table in a failure. */
static void check_bad_case(const bad_case *c, const char *table, int i)
{
    tg_scene *s = (tg_scene *)1;
    tg_error err;
    char msg[600];
    tg_status st = parse_io(c->text, strlen(c->text), "scenes/t.scene", NULL, &s, &err);
    tg_error_format(&err, msg, sizeof msg);
    CHECK(st == TG_ERR_INPUT, "%s case %d: status %d (%s)", table, i, (int)st, msg);
    CHECK(s == NULL, "%s case %d: no scene on error", table, i);
    CHECK(strcmp(err.file, "scenes/t.scene") == 0, "%s case %d: file '%s'", table, i, err.file);
    CHECK(err.line == c->line && err.col == c->col, "%s case %d: at %d:%d, expected %d:%d (%s)", table, i,
          err.line, err.col, c->line, c->col, msg);
    CHECK(strstr(err.message, c->fragment) != NULL, "%s case %d: message '%s' lacks '%s'", table, i,
          err.message, c->fragment);
}

TEST(bad_input_table)
{
    size_t i, n = sizeof bad_cases / sizeof bad_cases[0];
    CHECK(n >= 30, "%d cases", (int)n);
    for (i = 0; i < n; i++) check_bad_case(&bad_cases[i], "bad-input", (int)i);
}

/* ---- a line with two errors reports the first in the text ----
 * Each pair of lines holds the same two mistakes in both orders; the error
 * is the one further left, whichever check the parser would run first. */

#define CAM_LINE "camera pos 0 1 5 target 0 0 0\n"
#define MAT_LINE "material m albedo 0.5 0.5 0.5\n"

static const bad_case first_error_cases[] = {
    /* two values out of range */
    {"camera pos 0 1 5 target 0 0 0 near -1 fov 500\n", 1, 36, "'near' must be greater than 0"},
    {"camera pos 0 1 5 target 0 0 0 fov 500 near -1\n", 1, 35, "'fov' must be between 0 and 180"},
    {CAM_LINE "material q f0 2 albedo 2 0 0\n", 2, 15, "'f0' must be in [0, 1]"},
    {CAM_LINE "material q albedo 2 0 0 f0 2\n", 2, 19, "'albedo' must be in [0, 1]"},
    {CAM_LINE MAT_LINE "sphere center 0 0 0 segments 2 radius -1 material m\n", 3, 30, "sphere segments must be 4..256, got 2"},
    {CAM_LINE MAT_LINE "sphere center 0 0 0 radius -1 segments 2 material m\n", 3, 28, "'radius' must be greater than 0"},
    {CAM_LINE "gi bounces 500 slices 20\n", 2, 12, "gi bounces must be 0..100, got 500"},
    {CAM_LINE "gi slices 20 bounces 500\n", 2, 11, "gi slices must be 1..8, got 20"},
    {CAM_LINE "light spot pos 0 0 0 angle 100 dir 0 0 0 color 1 1 1\n", 2, 28, "'angle' must be in (0, 90]"},
    {CAM_LINE "light spot pos 0 0 0 dir 0 0 0 angle 100 color 1 1 1\n", 2, 26, "'dir' must be a direction of non-zero length"},
    {CAM_LINE "light point pos 0 0 0 intensity -1 color -1 1 1\n", 2, 33, "'intensity' must be 0 or more"},
    {CAM_LINE "light point pos 0 0 0 color -1 1 1 intensity -1\n", 2, 29, "'color' must be 0 or more"},
    {CAM_LINE MAT_LINE "mesh file a.obj rotate 0 0 0 1 scale 0 material m\n", 3, 24, "'rotate' must be a direction of non-zero length"},
    {CAM_LINE MAT_LINE "mesh file a.obj scale 0 rotate 0 0 0 1 material m\n", 3, 23, "'scale' must be greater than 0"},
    {CAM_LINE "env sky -1 1 1 up 0 0 0 ground 1 1 1\n", 2, 9, "'sky' must be 0 or more"},
    {CAM_LINE "env sky 1 1 1 up 0 0 0 ground -1 1 1\n", 2, 18, "'up' must be a direction of non-zero length"},
    /* a value against two keys (checked after the single values) */
    {"camera pos 0 0 0 target 0 0 0 fov 500\n", 1, 25, "camera 'target' must differ from 'pos'"},
    {"camera fov 500 pos 0 0 0 target 0 0 0\n", 1, 12, "'fov' must be between 0 and 180"},
    {CAM_LINE MAT_LINE "quad p0 0 0 0 p1 1 0 0 p2 2 0 0 p3 3 0 0 material m name aaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaaa\n", 3, 9, "quad has zero area"},
    {CAM_LINE MAT_LINE "box min 0 0 0 max 1 0 1 material m segments 2\n", 3, 21, "box 'max' must be greater than 'min'"},
    /* a bad value, then a bad token (the line is read up to the token) */
    {CAM_LINE "material q albedo 2 0 0 f0 x\n", 2, 19, "'albedo' must be in [0, 1]"},
    {CAM_LINE "material q f0 x albedo 2 0 0\n", 2, 15, "expected a number for 'f0', got 'x'"},
    {"camera pos 0 1 5 target 0 0 0 fov 500 bogus 1\n", 1, 35, "'fov' must be between 0 and 180"},
    {"camera pos 0 1 5 target 0 0 0 bogus 1 fov 500\n", 1, 31, "unknown key 'bogus'"},
    {"camera pos 0 1 5 target 0 0 0 up 0 0 0 pos 1 1 1\n", 1, 34, "'up' must be a direction of non-zero length"},
    {CAM_LINE "gi slices 20 samples 2.5\n", 2, 11, "gi slices must be 1..8, got 20"},
    {CAM_LINE "material q emissive -1 0 0 albedo 0.5 0.5\n", 2, 21, "'emissive' must be 0 or more"},
    {CAM_LINE MAT_LINE "sphere radius -1 center 0 0 x material m\n", 3, 15, "'radius' must be greater than 0"},
    {CAM_LINE "env uniform -1 1 1 x\n", 2, 13, "'uniform' must be 0 or more"},
    {CAM_LINE "env uniform 1 x -1\n", 2, 15, "expected a number for 'uniform', got 'x'"},
    /* no error made up from the keys not read: far is after the bad token */
    {"camera pos 0 1 5 target 0 0 0 near 2000 bogus far 3000\n", 1, 41, "unknown key 'bogus'"},
    /* a missing key is reported at the keyword, left of every value */
    {CAM_LINE "sphere center 0 0 0 radius -1\n", 2, 1, "missing the required key 'material'"},
    /* names, resolved in pass 2 */
    {CAM_LINE MAT_LINE "box min 0 0 0 max 1 1 1 material m name a\nbox min 2 0 0 max 3 1 1 name a material nope\n", 4, 30, "duplicate object name 'a'"},
    {CAM_LINE MAT_LINE "box min 0 0 0 max 1 1 1 material m name a\nbox min 2 0 0 max 3 1 1 material nope name a\n", 4, 34, "undefined material 'nope'"},
};

TEST(first_error_in_text)
{
    size_t i, n = sizeof first_error_cases / sizeof first_error_cases[0];
    for (i = 0; i < n; i++) check_bad_case(&first_error_cases[i], "first-error", (int)i);
}

TEST(limits)
{
    tg_scene *s;
    tg_error err;
    char *big;
    size_t at = 0, cap = 1 << 20;
    int i;
    big = malloc(cap);
    at += (size_t)snprintf(big + at, cap - at, CAM);
    for (i = 0; i <= 64; i++)
        at += (size_t)snprintf(big + at, cap - at, "light point pos 0 %d 0 color 1 1 1\n", i);
    CHECK(parse(big, &s, &err) == TG_ERR_INPUT && err.line == 66 && strstr(err.message, "light count must be 0..64, got 65"),
          "65 lights: %d %s", err.line, err.message);
    at = (size_t)snprintf(big, cap, CAM);
    for (i = 0; i <= 1024; i++)
        at += (size_t)snprintf(big + at, cap - at, "material m%d albedo 1 1 1\n", i);
    CHECK(parse(big, &s, &err) == TG_ERR_INPUT && err.line == 1026 && strstr(err.message, "material count must be 0..1024, got 1025"),
          "1025 materials: %d %s", err.line, err.message);
    /* each limit itself is allowed: the largest slices, samples and bounces,
     * the fewest sphere segments, radius 0 */
    snprintf(big, cap, CAM MAT "sphere center 0 0 0 radius 1 material m segments %d\n"
             "gi radius 0 slices %d samples %d bounces %d\n", TG_MIN_SPHERE_SEGMENTS, TG_MAX_SLICES, TG_MAX_SAMPLES,
             TG_MAX_BOUNCES);
    CHECK(parse(big, &s, &err) == TG_OK, "the limits themselves: %s", err.message);
    /* an integer token past 1e9 is out of range as a number (a 32-bit long would wrap it) */
    CHECK(parse(CAM "gi slices 4294967297\n", &s, &err) == TG_ERR_INPUT && strstr(err.message, "number out of range"),
          "slices 2^32 + 1: %s", err.message);
    free(big);
}

/* A sky without `up` has up = +y (src/scene/format.md). */
TEST(sky_up_defaults_to_y)
{
    tg_scene *s;
    tg_error err;
    CHECK(parse(CAM "env sky 1 1 1 ground 0 0 0\n", &s, &err) == TG_OK, "parse: %s", err.message);
    CHECK(s->env.type == TG_ENV_SKY && veq(s->env.up, 0, 1, 0), "default up (%g %g %g)", D(s->env.up.x), D(s->env.up.y),
          D(s->env.up.z));
}

/* ---- the arena ---- */

TEST(arena_protocol)
{
    static unsigned char mem[1 << 20];
    const char *text = tg_builtin_scene("spheres");
    tg_arena a;
    tg_error err;
    tg_scene *s = NULL;
    size_t need;
    tg_status st;
    tg_arena_init(&a, mem, 64);
    st = tg_scene_parse(text, strlen(text), "spheres", NULL, &a, &s, &err);
    CHECK(st == TG_ERR_MEMORY && s == NULL && a.used == 0, "too small: %d", (int)st);
    need = err.bytes_needed;
    CHECK(need > 2000 * 3 * 2 * sizeof(tg_vec3) && need < sizeof mem, "bytes_needed %zu", need);
    tg_arena_init(&a, mem, need - 1);
    CHECK(tg_scene_parse(text, strlen(text), "spheres", NULL, &a, &s, &err) == TG_ERR_MEMORY &&
          err.bytes_needed == need, "one byte short");
    tg_arena_init(&a, mem, need);
    st = tg_scene_parse(text, strlen(text), "spheres", NULL, &a, &s, &err);
    CHECK(st == TG_OK && s != NULL && a.used <= need, "exactly bytes_needed: %d", (int)st);
    if (st == TG_OK) check_invariants(s, "spheres in a tight arena");
    /* an input error leaves the arena as it was */
    tg_arena_init(&a, mem, sizeof mem);
    st = tg_scene_parse(CAM "quad p0 0 0 0 p1 1 0 0 p2 1 1 0 p3 0 1 0 material nope\n", 70, "x", NULL, &a, &s, &err);
    CHECK(st == TG_ERR_INPUT && a.used == 0, "input error: arena untouched (used %zu)", a.used);
}

/* ---- OBJ meshes from memory ---- */

typedef struct memfile { const char *path, *data; } memfile;
typedef struct memfs {
    const memfile *files;
    char requested[8][256];
    int nreq;
} memfs;

static int mem_read(void *user, const char *path, const char **data, size_t *size,
                    const char **reason)
{
    (void)reason;
    memfs *fs = (memfs *)user;
    const memfile *f;
    if (fs->nreq < 8) snprintf(fs->requested[fs->nreq++], 256, "%s", path);
    for (f = fs->files; f->path; f++)
        if (strcmp(f->path, path) == 0) {
            *data = f->data;
            *size = strlen(f->data);
            return 0;
        }
    *reason = "no such file in the test's memfs";
    return 1;
}

/* A tg_io reading the memory files `files` through fs (which records the
 * paths asked for). */
static tg_io memfs_io(memfs *fs, const memfile *files)
{
    tg_io io;
    memset(fs, 0, sizeof *fs);
    fs->files = files;
    io.user = fs;
    io.read_file = mem_read;
    return io;
}

static const char obj_a[] =
    "# quad polygon, smooth triangle with negative indices, pentagon\n"
    "mtllib a.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\n"
    "f 1 4 3 2\n"
    "vn 1 1 0\n"
    "usemtl red\n"
    "f -4//-1 -1//-1 -2//-1\n"
    "v 2 0 0\nv 3 0 0\nv 3 0 1\nv 2.5 0 1.5\nv 2 0 1\n"
    "vt 0 0\n"
    "usemtl glow\n"
    "f 5/1 9/1 8/1 7/1 6/1\n"
    "usemtl red\n"
    "f -5 -1 -2\n";
static const char mtl_a[] =
    "newmtl red\nKa 0 0 0\nKd 0.8 0.1 0.1\nNs 10\n"
    "newmtl glow\nKd 0.5\nKe 2 3 4\n";

/* Two MTL materials whose "objname/mtlname" names are cut to one prefix
 * (an object name of 30 bytes leaves no room for the MTL name) stay two
 * materials, each face in its own; a second usemtl of one reuses it.
 * Before the fix every face took the first material (red). */
TEST(obj_cut_material_names_stay_distinct)
{
    static const memfile files[] = {
        {"m.obj", "mtllib m.mtl\nv -1 0 0\nv 0 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\n"
                  "usemtl red\nf 1 2 3\nusemtl blue\nf 2 4 5\nusemtl red\nf 1 3 2\n"},
        {"m.mtl", "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n"}, {NULL, NULL}};
    static const char scene[] = CAM "material m albedo 0.5 0.5 0.5\n"
                                    "mesh file m.obj material m name statue_in_the_main_hall_left_1\n";
    memfs fs;
    tg_io io;
    tg_scene *s;
    tg_error err;
    tg_status st;
    int a, b, c;
    io = memfs_io(&fs, files);
    st = parse_io(scene, strlen(scene), "s.scene", &io, &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(s->tri_count == 3, "%d triangles", s->tri_count);
    CHECK(s->material_count == 3, "base + red + blue: %d", s->material_count);
    if (s->tri_count != 3) return;
    a = s->tri_material[0]; b = s->tri_material[1]; c = s->tri_material[2];
    CHECK(a != b, "red and blue faces: two materials (%d, %d)", a, b);
    CHECK(a == c, "the second usemtl red reuses the first (%d, %d)", a, c);
    CHECK(veq(s->materials[a].albedo, 1, 0, 0), "the first face red");
    CHECK(veq(s->materials[b].albedo, 0, 0, 1), "the second face blue");
    check_invariants(s, "cut material names");
}

TEST(obj_from_memory)
{
    static const memfile files[] = {
        {"dir/meshes/a.obj", obj_a}, {"dir/meshes/a.mtl", mtl_a}, {NULL, NULL}};
    static const char scene[] = CAM "material base albedo 0.25 0.25 0.25 f0 0.3 twosided\n"
                                    "mesh file meshes/a.obj material base name a\n";
    memfs fs;
    tg_io io;
    tg_scene *s;
    tg_error err;
    tg_status st;
    int red, glow, t, i;
    io = memfs_io(&fs, files);
    st = parse_io(scene, strlen(scene), "dir/scene.scene", &io, &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    CHECK(strcmp(fs.requested[0], "dir/meshes/a.obj") == 0, "OBJ path relative to the scene: %s", fs.requested[0]);
    CHECK(strcmp(fs.requested[1], "dir/meshes/a.mtl") == 0, "MTL path relative to the OBJ: %s", fs.requested[1]);
    CHECK(s->tri_count == 2 + 1 + 3 + 1, "%d triangles", s->tri_count);
    CHECK(s->object_count == 1 && s->objects[0].tri_count == 7, "one object");
    CHECK(s->material_count == 3, "base + a/red + a/glow: %d", s->material_count);
    red = find_mat(s, "a/red");
    glow = find_mat(s, "a/glow");
    CHECK(red > 0 && glow > 0, "usemtl materials named objname/mtlname");
    if (red <= 0 || glow <= 0) return;
    CHECK_NEAR(D(s->materials[red].albedo.x), 0.8, 1e-4);
    CHECK_NEAR(D(s->materials[red].albedo.y), 0.1, 1e-4);
    CHECK(veq(s->materials[red].emissive, 0, 0, 0), "no Ke: the mesh material's emission");
    CHECK(veq(s->materials[glow].albedo, 0.5, 0.5, 0.5) && veq(s->materials[glow].emissive, 2, 3, 4), "Kd grey, Ke");
    CHECK(D(s->materials[glow].f0) == D(s->materials[0].f0) && s->materials[glow].twosided, "f0/twosided from the mesh material");
    check_invariants(s, "usemtl");
    CHECK(s->tri_material[0] == 0 && s->tri_material[1] == 0, "faces before usemtl: the mesh material");
    CHECK(s->tri_material[2] == red, "usemtl red");
    for (t = 3; t < 6; t++) CHECK(s->tri_material[t] == glow, "usemtl glow");
    CHECK(s->tri_material[6] == red, "red reused");
    /* quad polygon: face normals +Y */
    for (i = 0; i < 6; i++) CHECK(veq(s->tri_nrm[i], 0, 1, 0), "face normal %d", i);
    CHECK(veq(s->tri_pos[0], 0, 0, 0) && veq(s->tri_pos[1], 0, 0, 1) && veq(s->tri_pos[2], 1, 0, 1), "fan 1");
    CHECK(veq(s->tri_pos[3], 0, 0, 0) && veq(s->tri_pos[4], 1, 0, 1) && veq(s->tri_pos[5], 1, 0, 0), "fan 2");
    /* negative indices: -4 -1 -2 with 4 vertices = 1 4 3; vn normalized */
    CHECK(veq(s->tri_pos[6], 0, 0, 0) && veq(s->tri_pos[7], 0, 0, 1) && veq(s->tri_pos[8], 1, 0, 1), "negative");
    for (i = 6; i < 9; i++) {
        CHECK_NEAR(D(s->tri_nrm[i].x), sqrt(0.5), NTOL);
        CHECK_NEAR(D(s->tri_nrm[i].y), sqrt(0.5), NTOL);
    }
    /* the pentagon 5 9 8 7 6 fans as (5 9 8) (5 8 7) (5 7 6) */
    CHECK(veq(s->tri_pos[9], 2, 0, 0) && veq(s->tri_pos[10], 2, 0, 1) && veq(s->tri_pos[11], 2.5, 0, 1.5), "pent 1");
    CHECK(veq(s->tri_pos[14], 3, 0, 1) && veq(s->tri_pos[17], 3, 0, 0), "pent 3");
    CHECK(veq(s->tri_pos[18], 2, 0, 0) && veq(s->tri_pos[19], 2, 0, 1) && veq(s->tri_pos[20], 2.5, 0, 1.5), "-5 -1 -2");
    CHECK(veq(s->bounds_min, 0, 0, 0) && veq(s->bounds_max, 3, 0, 1.5), "bounds");
    check_invariants(s, "obj");
}

TEST(obj_transform)
{
    static const memfile files[] = {
        {"m.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1 1 0\nf 1//1 2//1 3//1\n"}, {NULL, NULL}};
    static const char scene[] = CAM MAT "mesh file m.obj material m translate 10 0 0 scale 2 rotate 0 3 0 90\n";
    memfs fs;
    tg_io io;
    tg_scene *s;
    tg_error err;
    tg_status st;
    io = memfs_io(&fs, files);
    st = parse_io(scene, strlen(scene), "s.scene", &io, &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st) { print_error(&err); return; }
    /* p' = R(90 deg about +Y) (2 p) + (10 0 0): x -> -z, z -> +x */
    CHECK_NEAR(D(s->tri_pos[0].x), 10, PTOL * 10);
    CHECK_NEAR(D(s->tri_pos[0].z), -2, PTOL * 10);
    CHECK_NEAR(D(s->tri_pos[1].y), 2, PTOL * 10);
    CHECK_NEAR(D(s->tri_pos[1].x), 10, PTOL * 10);
    CHECK_NEAR(D(s->tri_pos[2].x), 12, PTOL * 10);
    CHECK_NEAR(D(s->tri_pos[2].z), 0, PTOL * 10);
    /* normals rotated (not scaled), unit */
    CHECK_NEAR(D(s->tri_nrm[0].x), 0, NTOL * 4);
    CHECK_NEAR(D(s->tri_nrm[0].y), sqrt(0.5), NTOL * 4);
    CHECK_NEAR(D(s->tri_nrm[0].z), -sqrt(0.5), NTOL * 4);
    CHECK(strcmp(s->materials[0].name, "m") == 0 && s->material_count == 1, "no usemtl: the statement's material");
}

typedef struct obj_bad {
    const char *obj, *mtl;
    const char *file;
    int line, col;
    const char *fragment;
} obj_bad;

static const obj_bad obj_bad_cases[] = {
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", NULL, "s/m.obj", 4, 7, "OBJ vertex index 4 is out of range (3 defined so far)"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", NULL, "s/m.obj", 4, 7, "index 0 is invalid"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", NULL, "s/m.obj", 4, 3, "OBJ vertex index -4 is out of range"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", NULL, "s/m.obj", 4, 3, "OBJ normal index 1 is out of range (0 defined"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", NULL, "s/m.obj", 5, 7, "OBJ texture index 2 is out of range"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1/1/1 2 3\n", NULL, "s/m.obj", 4, 3, "bad face vertex '1/1/1/1'"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf a 2 3\n", NULL, "s/m.obj", 4, 3, "bad face vertex 'a'"},
    {"v 0 0 0\nv 1 0 0\nf 1 2\n", NULL, "s/m.obj", 3, 6, "a face needs at least 3 vertices, got 2"},
    {"v 0 0 0\nv 1 2\n", NULL, "s/m.obj", 2, 6, "'v' expects 3 numbers, got 2"},
    {"v 0 0 0\nv 1 x 2\n", NULL, "s/m.obj", 2, 5, "expected a number in 'v', got 'x'"},
    {"vn 0 1\n", NULL, "s/m.obj", 1, 7, "'vn' expects 3 numbers, got 2"},
    {"v 0 0 0\nvn 0 1 0 1\n", NULL, "s/m.obj", 2, 10, "too many numbers for 'vn'"},
    {"usemtl red\n", NULL, "s/m.obj", 1, 8, "no 'mtllib'"},
    {"mtllib m.mtl\nusemtl blue\n", "newmtl red\nKd 1 0 0\n", "s/m.obj", 2, 8, "material 'blue' is not defined"},
    {"mtllib none.mtl\nusemtl red\n", NULL, "s/m.obj", 1, 8, "cannot read MTL file 's/none.mtl'"},
    {"mtllib m.mtl\nusemtl red\n", "newmtl red\nKd 1.5 0 0\n", "s/m.mtl", 2, 4, "'Kd' must be in [0, 1]"},
    {"mtllib m.mtl\nusemtl red\n", "newmtl red\nKd 0.5 x 0.5\n", "s/m.mtl", 2, 8, "expected a number in 'Kd'"},
    {"mtllib m.mtl\nusemtl red\n", "newmtl red\nKe 1 -1 0\n", "s/m.mtl", 2, 6, "'Ke' must be 0 or more"},
    {"mtllib m.mtl\nusemtl red\n", "newmtl red\nKd 0.5 -0.1 0.5\n", "s/m.mtl", 2, 8, "'Kd' must be in [0, 1]"},   /* radiance >= 0: gi/hbil.c radiance_nonneg */
    {"mtllib m.mtl\nusemtl red\n", "newmtl red\nKd 1 1\n", "s/m.mtl", 2, 7, "'Kd' expects 3 numbers"},
    /* not an OBJ at all: an error, not an empty object */
    {"", NULL, "s/t.scene", 3, 11, "mesh file 's/m.obj' has no faces; expected an OBJ file with 'v' and 'f' lines"},
    {"v 0 0 0\nv 1 0 0\nv 0 1 0\n", NULL, "s/t.scene", 3, 11, "mesh file 's/m.obj' has no faces"},
    {"root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1:daemon:/usr/sbin:/usr/sbin/nologin\n", NULL, "s/t.scene", 3, 11,
     "mesh file 's/m.obj' has no faces"},
    /* an mtllib that cannot be read is an error even when no usemtl needs it */
    {"mtllib none.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", NULL, "s/m.obj", 1, 8,
     "cannot read MTL file 's/none.mtl': no such file in the test's memfs"},
    /* numbers past the number type's range say what the range is */
    {"v 0 0 1e39\n", NULL, "s/m.obj", 1, 7, "number out of range in 'v', got '1e39'" TGI_RANGE_NOTE},
};

TEST(obj_bad_input)
{
    size_t i, n = sizeof obj_bad_cases / sizeof obj_bad_cases[0];
    static const char scene[] = CAM MAT "mesh file m.obj material m\n";
    for (i = 0; i < n; i++) {
        memfile files[3];
        memfs fs;
        tg_io io;
        tg_scene *s;
        tg_error err;
        char msg[600];
        tg_status st;
        memset(files, 0, sizeof files);
        files[0].path = "s/m.obj";
        files[0].data = obj_bad_cases[i].obj;
        files[1].path = obj_bad_cases[i].mtl ? "s/m.mtl" : NULL;
        files[1].data = obj_bad_cases[i].mtl;
        io = memfs_io(&fs, files);
        st = parse_io(scene, strlen(scene), "s/t.scene", &io, &s, &err);
        tg_error_format(&err, msg, sizeof msg);
        CHECK(st == TG_ERR_INPUT, "obj case %d: status %d", (int)i, (int)st);
        CHECK(strcmp(err.file, obj_bad_cases[i].file) == 0 && err.line == obj_bad_cases[i].line &&
              err.col == obj_bad_cases[i].col, "obj case %d: %s, expected %s:%d:%d", (int)i, msg,
              obj_bad_cases[i].file, obj_bad_cases[i].line, obj_bad_cases[i].col);
        CHECK(strstr(err.message, obj_bad_cases[i].fragment) != NULL, "obj case %d: '%s' lacks '%s'", (int)i,
              err.message, obj_bad_cases[i].fragment);
    }
    {   /* no tg_io at all */
        tg_scene *s;
        tg_error err;
        CHECK(parse(scene, &s, &err) == TG_ERR_INPUT && err.line == 3 && err.col == 11 &&
              strstr(err.message, "cannot read mesh file 'm.obj': no tg_io to read files with"),
              "no io: %d:%d %s", err.line, err.col, err.message);
    }
    {   /* the reader's reason is in the message */
        static const memfile none[] = {{NULL, NULL}};
        memfs fs;
        tg_io io;
        tg_scene *s;
        tg_error err;
        io = memfs_io(&fs, none);
        CHECK(parse_io(scene, strlen(scene), "s/t.scene", &io, &s, &err) == TG_ERR_INPUT && err.line == 3 &&
              err.col == 11 && strcmp(err.message, "cannot read mesh file 's/m.obj': no such file in the test's memfs") == 0,
              "reason: %d:%d %s", err.line, err.col, err.message);
    }
}

TEST(obj_arena)
{
    static const memfile files[] = {{"a.obj", obj_a}, {"a.mtl", mtl_a}, {NULL, NULL}};
    static const char scene[] = CAM MAT "mesh file a.obj material m\nmesh file a.obj material m name b\n";
    static unsigned char mem[1 << 16];
    memfs fs;
    tg_io io;
    tg_arena a;
    tg_scene *s;
    tg_error err;
    size_t need;
    tg_status st;
    io = memfs_io(&fs, files);
    tg_arena_init(&a, mem, 100);
    CHECK(tg_scene_parse(scene, strlen(scene), "x.scene", &io, &a, &s, &err) == TG_ERR_MEMORY, "too small");
    need = err.bytes_needed;
    tg_arena_init(&a, mem, need);
    st = tg_scene_parse(scene, strlen(scene), "x.scene", &io, &a, &s, &err);
    CHECK(st == TG_OK, "bytes_needed is enough");
    if (st) { print_error(&err); return; }
    CHECK(a.used < need, "OBJ scratch released: used %zu of %zu", a.used, need);
    CHECK(s->tri_count == 14 && s->object_count == 2, "two meshes");
    CHECK(find_mat(s, "a/red") > 0 && find_mat(s, "b/glow") > 0, "names from file name and from 'name'");
    check_invariants(s, "two meshes");
}

/* ---- OBJ files on disk, through the hosted tg_io ---- */

TEST(obj_from_disk)
{
    tgp_host_io host;
    tg_scene *s;
    tg_error err;
    char *text, msg[256];
    size_t n;
    tg_status st;
    int o;
    if (tgp_file_read("tests/scenes/meshes.scene", &text, &n, msg, sizeof msg)) {
        CHECK(0, "cannot read tests/scenes/meshes.scene: %s", msg);
        return;
    }
    tgp_host_io_init(&host);
    st = parse_io(text, n, "tests/scenes/meshes.scene", &host.io, &s, &err);
    CHECK(st == TG_OK, "parse");
    if (st == TG_OK) {
        CHECK(s->tri_count == 24 && s->object_count == 2, "two cubes: %d triangles", s->tri_count);
        o = find_obj(s, "cube");
        CHECK(o == 0 && s->objects[0].tri_count == 12, "named cube");
        CHECK(D(s->bounds_min.y) == 0.25, "second cube's bottom at 0.5 - 0.25: %g", D(s->bounds_min.y));
        CHECK(D(s->bounds_max.y) == 1.5, "first cube top at 1.5");
        CHECK(find_mat(s, "cube/red") > 0 && find_mat(s, "cube/white") > 0, "MTL materials");
        CHECK_NEAR(D(s->materials[find_mat(s, "cube/white")].emissive.y), 0.25, 1e-4);
        check_invariants(s, "meshes.scene");
        {   /* the cube's normals point out of its centre (0 1 0) */
            int t, bad = 0;
            for (t = 0; t < 12; t++) {
                dv c = {0, 0, 0}, ctr = {0, 1, 0};
                int i;
                for (i = 0; i < 3; i++) {
                    dv p = V(s->tri_pos[3 * t + i]);
                    c.x += p.x / 3; c.y += p.y / 3; c.z += p.z / 3;
                }
                if (ddot(V(s->tri_nrm[3 * t]), dsub(c, ctr)) <= 0) bad++;
            }
            CHECK(bad == 0, "%d cube faces point inward", bad);
        }
    } else print_error(&err);
    tgp_host_io_free(&host);
    free(text);

    if (tgp_file_read("tests/scenes/bad_index.scene", &text, &n, msg, sizeof msg)) {
        CHECK(0, "cannot read tests/scenes/bad_index.scene: %s", msg);
        return;
    }
    tgp_host_io_init(&host);
    st = parse_io(text, n, "tests/scenes/bad_index.scene", &host.io, &s, &err);
    CHECK(st == TG_ERR_INPUT && strcmp(err.file, "tests/scenes/obj/bad_index.obj") == 0 && err.line == 5 &&
          err.col == 7, "bad index on disk: %s:%d:%d %s", err.file, err.line, err.col, err.message);
    tgp_host_io_free(&host);
    free(text);
}

/* ---- robustness: mutated scenes never crash and always explain ---- */

static unsigned lcg_state = 12345u;
static unsigned lcg(void) { lcg_state = lcg_state * 1664525u + 1013904223u; return lcg_state >> 8; }

TEST(mutations)
{
    static const char alphabet[] = "0123456789-+.eE #\n\t/xaz\0";
    static char buf[1 << 16];
    int i, k, ok = 0, input = 0, other = 0, unexplained = 0;
    const char *name;
    for (i = 0; (name = tg_builtin_name(i)) != NULL; i++) {
        const char *text = tg_builtin_scene(name);
        size_t n = strlen(text);
        for (k = 0; k < 400; k++) {
            tg_scene *s;
            tg_error err;
            tg_status st;
            size_t len = n, at, m = 1 + lcg() % 3, j;
            memcpy(buf, text, n);
            for (j = 0; j < m; j++) {
                at = lcg() % len;
                switch (lcg() % 3) {
                case 0: buf[at] = alphabet[lcg() % (sizeof alphabet - 1)]; break;
                case 1: memmove(buf + at, buf + at + 1, len - at - 1); len--; break;
                default:
                    if (len + 1 < sizeof buf) {
                        memmove(buf + at + 1, buf + at, len - at);
                        buf[at] = alphabet[lcg() % (sizeof alphabet - 1)];
                        len++;
                    }
                }
            }
            st = parse_io(buf, len, "m.scene", NULL, &s, &err);
            if (st == TG_OK) {
                ok++;
                if (check_invariants(s, "mutated") > 0) break;
            } else if (st == TG_ERR_INPUT) {
                input++;
                if (err.line < 1 || err.col < 1 || !err.message[0]) unexplained++;
            } else
                other++;
        }
    }
    CHECK(other == 0, "%d mutated scenes gave neither OK nor TG_ERR_INPUT", other);
    CHECK(unexplained == 0, "%d input errors without LINE:COL or message", unexplained);
    CHECK(ok > 50 && input > 200, "ok %d input %d: the mutations exercise both", ok, input);
}

/* A mesh file that changes between the two passes: a runtime error, no overrun. */
typedef struct changing_io { int reads; } changing_io;

static int changing_read(void *user, const char *path, const char **data, size_t *size,
                         const char **reason)
{
    (void)reason;
    changing_io *c = (changing_io *)user;
    static const char small[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    static const char big[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\nf 1 2 4\n";
    (void)path; (void)reason;
    *data = c->reads++ == 0 ? small : big;
    *size = strlen(*data);
    return 0;
}

TEST(mesh_changes_between_passes)
{
    changing_io c;
    tg_io io;
    tg_scene *s;
    tg_error err;
    static const char scene[] = CAM MAT "mesh file m.obj material m\n";
    c.reads = 0;
    io.user = &c;
    io.read_file = changing_read;
    CHECK(parse_io(scene, strlen(scene), "s.scene", &io, &s, &err) == TG_ERR_RUNTIME,
          "changed mesh: %s", err.message);
    CHECK(c.reads == 2, "read once per pass");
    /* and with no error struct at all */
    CHECK(parse_io(CAM "camra\n", 36, "s.scene", NULL, &s, NULL) == TG_ERR_INPUT, "NULL err");
    {
        tg_arena a;
        tg_arena_init(&a, arena_mem, 10);
        CHECK(tg_scene_parse(CAM, strlen(CAM), "s", NULL, &a, &s, NULL) == TG_ERR_MEMORY, "NULL err, memory");
    }
}

int main(void)
{
    RUN(builtins_parse);
    RUN(builtin_cornell);
    RUN(builtin_spheres_rest_on_floor);
    RUN(quad_exact);
    RUN(box_outward);
    RUN(box_inward);
    RUN(sphere_normals);
    RUN(defaults);
    RUN(values_and_units);
    RUN(keys_sorted);
    RUN(lexing);
    RUN(number_notes);
    RUN(bad_input_table);
    RUN(first_error_in_text);
    RUN(limits);
    RUN(sky_up_defaults_to_y);
    RUN(arena_protocol);
    RUN(obj_cut_material_names_stay_distinct);
    RUN(obj_from_memory);
    RUN(obj_transform);
    RUN(obj_bad_input);
    RUN(obj_arena);
    RUN(obj_from_disk);
    RUN(mutations);
    RUN(mesh_changes_between_passes);
    return check_summary();
}
