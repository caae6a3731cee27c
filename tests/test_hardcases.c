/* SPDX-License-Identifier: MIT */
/*
 * test_hardcases.c - the hard-case suite: named scenes and
 * requests that push the numerics (grazing planes, geometry through the
 * near plane and behind the camera, degenerate triangles, extreme fov,
 * near/far and scale, tiny and odd framebuffers, many frames, camera cuts,
 * fast motion), each rendered with every technique in this number type
 * (and HBIL and the bitmask over three depth layers).
 * For every frame and every technique:
 *   - every AOV value is finite; depth >= 0;
 *   - AO in [0, 1]; cone in [0, pi/2];
 *   - on geometry the bent normal is unit within 1e-3 and in the normal's
 *     hemisphere (dot >= -1e-3);
 *   - irradiance, near, far, direct and colour >= 0;
 *   - a second, independent run gives bit-identical AOVs.
 * Sizes are tiny and the reference uses 16 samples so the whole suite stays
 * well under a minute per number type.
 */
#include "frame_fixture.h"

#define CONE_MAX (1.5707963267948966 + (TG_FIXED ? 2e-5 : 1e-6))

/* The invariants of one rendered frame; returns the count of violations
 * and describes the first in `why`. */
static int frame_violations(const rendered *r, char *why, size_t why_n)
{
    int w = r->plan.request.width, h = r->plan.request.height, a, bad = 0;
    size_t n = (size_t)w * (size_t)h, i, k;
    double *v[TG_AOV_COUNT];
    for (a = 0; a < TG_AOV_COUNT; a++) v[a] = read_aov(r, (tg_aov)a);
#define BAD(...) do { if (bad++ == 0) snprintf(why, why_n, __VA_ARGS__); } while (0)
    for (a = 0; a < TG_AOV_COUNT; a++) {
        size_t m = n * (size_t)tg_aov_channels((tg_aov)a);
        for (k = 0; k < m; k++)
            if (!isfinite(v[a][k])) BAD("%s[%zu] = %g not finite", tg_aov_name((tg_aov)a), k, v[a][k]);
    }
    for (i = 0; i < n; i++) {
        const double *nb = v[TG_AOV_BENT] + 3 * i, *nn = v[TG_AOV_NORMAL] + 3 * i;
        double ao = v[TG_AOV_AO][i], cone = v[TG_AOV_CONE][i], depth = v[TG_AOV_DEPTH][i];
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
        if (!(ao >= 0 && ao <= 1)) BAD("AO %g at (%d,%d)", ao, x, y);
        if (!(cone >= 0 && cone <= CONE_MAX)) BAD("cone %.9g at (%d,%d)", cone, x, y);
        if (!(depth >= 0)) BAD("depth %g at (%d,%d)", depth, x, y);
        for (k = 0; k < 3; k++) {
            static const tg_aov nonneg[] = { TG_AOV_IRRADIANCE, TG_AOV_NEAR, TG_AOV_FAR, TG_AOV_DIRECT, TG_AOV_COLOR };
            size_t j;
            for (j = 0; j < sizeof nonneg / sizeof nonneg[0]; j++)
                if (!(v[nonneg[j]][3 * i + k] >= 0))
                    BAD("%s %g at (%d,%d)", tg_aov_name(nonneg[j]), v[nonneg[j]][3 * i + k], x, y);
        }
        if (depth > 0) { /* geometry: the bent normal is a unit vector in the normal's hemisphere */
            double len = sqrt(nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2]);
            double d = nb[0] * nn[0] + nb[1] * nn[1] + nb[2] * nn[2];
            if (!(fabs(len - 1) <= 1e-3)) BAD("|bent| = %.6f at (%d,%d)", len, x, y);
            if (!(d >= -1e-3)) BAD("bent . n = %.6f at (%d,%d)", d, x, y);
        }
    }
#undef BAD
    for (a = 0; a < TG_AOV_COUNT; a++) free(v[a]);
    return bad;
}

typedef struct hard_case {
    const char *test;     /* the TEST that runs it (the table below) */
    const char *name;
    const char *text;
    int width, height, frames;
    int samples, slices;  /* 0: default (the reference gets 16) */
    double radius;        /* < 0: the scene's */
    int may_refuse;       /* fixed point may refuse with a clear TG_ERR_INPUT */
    const char *mesh;     /* the OBJ text every mesh path reads (NULL: none) */
} hard_case;

/* Run a case with technique t over `layers` depth layers twice; check
 * every frame of the first run and the bits of both runs' last frames.
 * Returns 1 when it rendered. */
static int run_layers(const hard_case *c, int t, int layers)
{
    rendered a, b;
    tg_request q;
    tg_error err;
    int f, ok_a, ok_b, rendered_ok = 0;
    char why[256] = "", tname[64];
    snprintf(tname, sizeof tname, "%s%s", tg_technique_name((tg_technique)t), layers > 1 ? " over 3 layers" : "");
    tg_request_defaults(&q);
    q.width = c->width ? c->width : 16;
    q.height = c->height ? c->height : 12;
    q.frames = c->frames ? c->frames : 1;
    q.aovs = ALL_AOVS;
    q.technique = (tg_technique)t;
    q.depth_layers = layers;
    q.shadow_map_size = 32;
    q.samples = c->samples ? c->samples : (t == TG_TECH_REFERENCE ? 16 : 0);
    q.slices = c->slices;
    if (c->radius >= 0) q.radius = TG_R((float)c->radius);
    fixture_mesh_text = c->mesh;
    ok_a = setup(&a, c->text, &q);
    ok_b = setup(&b, c->text, &q);
    fixture_mesh_text = NULL;
    if (!ok_a || !ok_b) {
        int refused = TG_FIXED && c->may_refuse && a.status == TG_ERR_INPUT && strstr(a.msg, "error: ") && strlen(a.msg) > 20;
        CHECK(refused, "%s / %s: setup failed (%d): %s", c->name, tname, (int)a.status, a.msg);
        teardown(&a); teardown(&b);
        return 0;
    }
    for (f = 0; f < q.frames; f++) {
        tg_status sa = tg_frame_render(a.frame, f, &err), sb = tg_frame_render(b.frame, f, &err);
        int bad;
        CHECK(sa == TG_OK && sb == TG_OK, "%s / %s: frame %d render failed", c->name, tname, f);
        if (sa != TG_OK || sb != TG_OK) break;
        /* checking every frame of a long run costs more than rendering it */
        if (f < 8 || f == q.frames - 1 || f % 97 == 0) {
            bad = frame_violations(&a, why, sizeof why);
            CHECK(bad == 0, "%s / %s frame %d: %d violations, first: %s", c->name,
                  tname, f, bad, why);
            if (bad) break;
        }
        if (f == q.frames - 1) {
            size_t na, nb;
            unsigned char *ra = raw_aovs(&a, &na), *rb = raw_aovs(&b, &nb);
            CHECK(na == nb && memcmp(ra, rb, na) == 0, "%s / %s: two runs differ", c->name, tname);
            free(ra); free(rb);
            rendered_ok = 1;
        }
    }
    teardown(&a); teardown(&b);
    return rendered_ok;
}

static int run_technique(const hard_case *c, int t) { return run_layers(c, t, 1); }

/* Every technique, and the two that read further depth layers over three
 * (HBIL's kernel then the visibility bitmask). */
static void run_case(const hard_case *c)
{
    int t;
    for (t = 0; t < TG_TECH_COUNT; t++) run_technique(c, t);
#if !TG_NO_TECHNIQUES
    run_layers(c, TG_TECH_HBIL, 3);
    run_layers(c, TG_TECH_SSILVB, 3);
#endif
}

/* ---- scenes ---- */

#define ROOM                                                                  \
    "camera pos 0 1 -3.5 target 0 1 0 fov 60\n"                               \
    "material wall albedo 0.7 0.7 0.7 f0 0\n"                                 \
    "material lamp albedo 0.5 0.5 0.5 emissive 5 5 5\n"                       \
    "box min -2 0 -4 max 2 3 2 material wall inward\n"                        \
    "box min -0.5 0 -0.5 max 0.5 1 0.5 material wall\n"                       \
    "quad p0 -0.5 2.99 -0.5  p1 0.5 2.99 -0.5  p2 0.5 2.99 0.5  p3 -0.5 2.99 0.5 material lamp\n" \
    "light point pos 0 2.5 0 color 1 1 1 intensity 4 shadows\n"               \
    "env uniform 0.2 0.2 0.2\n"                                               \
    "gi radius 1.5\n"

/* The cases whose scene is a fixed text, each run by the TEST named in its
 * first field (in the table's order). */
static const hard_case named_cases[] = {
    /* A mesh whose vertex normals point away from the camera (and one at 89
     * degrees to its face): shading normals facing away. */
    { "interpolated_normals_facing_away", "normals facing away",
      "camera pos 0 1 -3 target 0 0.5 0\n"
      "material m albedo 0.6 0.6 0.6 twosided\n"
      "quad p0 -5 0 -5 p1 -5 0 5 p2 5 0 5 p3 5 0 -5 material m\n"
      "mesh file away.obj material m\n"
      "light point pos 0 2 -2 color 1 1 1 intensity 3 shadows\n"
      "env uniform 0.3 0.3 0.3\n",
      16, 12, 1, 0, 0, -1, 0,
      "v -1 0 0\nv 1 0 0\nv 1 2 0\nv -1 2 0\n"
      "vn 0 0 1\nvn 0.2 0 1\nvn 0 0.99 0.01\nvn -0.7 0 0.7\n"
      "f 1//1 2//2 3//3\nf 1//1 3//3 4//4\n"
      "f 2//4 1//2 4//1\n" },
    { "camera_inside_a_box", "inside an inward box",
      "camera pos 0 0 0 target 1 0.2 0.3 fov 90\n"
      "material m albedo 0.8 0.8 0.8\n"
      "box min -1 -1 -1 max 1 1 1 material m inward\n"
      "light point pos 0 0.5 0 color 1 1 1 intensity 2 shadows\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    { "camera_inside_a_box", "inside an outward two-sided box",
      "camera pos 0 0 0 target 1 0.2 0.3 fov 90\n"
      "material m albedo 0.8 0.8 0.8 twosided\n"
      "box min -1 -1 -1 max 1 1 1 material m\n"
      "light point pos 0 0.5 0 color 1 1 1 intensity 2\n"
      "env uniform 1 1 1\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    /* A wall through the camera (it crosses the near plane), a floor that
     * runs behind the camera, and a triangle with a vertex exactly in the
     * camera's plane (w = 0) and one behind it (w < 0). */
    { "near_plane_crossing_and_behind_camera", "geometry through the near plane and behind the camera",
      "camera pos 0 1 0 target 0 1 1 near 0.05\n"
      "material m albedo 0.6 0.6 0.6 twosided\n"
      "quad p0 -20 0 -20 p1 -20 0 20 p2 20 0 20 p3 20 0 -20 material m\n"
      "quad p0 0.3 0 -5 p1 0.3 0 5 p2 0.3 3 5 p3 0.3 3 -5 material m\n"
      "mesh file w.obj material m\n"
      "light point pos 0 2 2 color 1 1 1 intensity 3 shadows\n"
      "env uniform 0.2 0.2 0.2\n",
      16, 12, 1, 0, 0, -1, 0,
      "v -1 0.5 0\nv -0.5 2 3\nv -2 0.2 -1\nv -0.2 1.2 0.01\n"
      "f 1 2 3\nf 4 2 1\nf 3 2 4\n" },
    { "sky_beside_geometry", "a lone box in an empty sky",
      "camera pos 0 0.5 -3 target 0 0.5 0\n"
      "material m albedo 0.9 0.9 0.9\n"
      "box min -0.4 0 -0.4 max 0.4 1 0.4 material m\n"
      "light directional dir 0 -1 1 color 1 1 1\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    { "sky_beside_geometry", "a box against an environment",
      "camera pos 0 0.5 -3 target 0 0.5 0\n"
      "material m albedo 0.9 0.9 0.9\n"
      "box min -0.4 0 -0.4 max 0.4 1 0.4 material m\n"
      "env sky 1 1 1 ground 0.3 0.2 0.1\n"
      "gi radius 5\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    /* Pillars about a pixel wide (at 32 px across a 60 degree fov, 8 m away,
     * a pixel is ~0.29 m) in front of a far wall. */
    { "one_pixel_pillars", "one-pixel pillars before a far wall",
      "camera pos 0 1 -8 target 0 1 0\n"
      "material m albedo 0.7 0.7 0.7\n"
      "quad p0 -20 0 -20 p1 -20 0 20 p2 20 0 20 p3 20 0 -20 material m\n"
      "quad p0 -20 0 20 p1 20 0 20 p2 20 8 20 p3 -20 8 20 material m\n"
      "box min -2.1 0 0 max -1.85 3 0.25 material m\n"
      "box min -0.1 0 0 max 0.15 3 0.25 material m\n"
      "box min 1.9 0 0 max 2.02 3 0.12 material m\n"
      "light point pos 0 4 -4 color 1 1 1 intensity 10 shadows\n"
      "gi radius 2\n",
      32, 24, 1, 0, 0, -1, 0, NULL },
    { "near_tiny_far_huge", "near 1e-3, far 1e4",
      "camera pos 0 1 -3 target 0 1 0 near 0.001 far 10000\n"
      "material m albedo 0.7 0.7 0.7\n"
      "quad p0 -9000 0 -9000 p1 -9000 0 9000 p2 9000 0 9000 p3 9000 0 -9000 material m\n"
      "quad p0 -9000 0 9000 p1 9000 0 9000 p2 9000 5000 9000 p3 -9000 5000 9000 material m\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material m\n"
      "light point pos 0 3 -1 color 1 1 1 intensity 3 shadows\n"
      "env uniform 0.2 0.2 0.2\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    { "radius_zero_and_screen_covering", "radius 0", ROOM, 16, 12, 1, 0, 0, 0, 0, NULL },
    { "radius_zero_and_screen_covering", "radius covering the screen", ROOM, 16, 12, 1, 0, 0, 1000, 0, NULL },
    { "samples_and_slices_extremes", "samples 1", ROOM, 16, 12, 1, 1, 0, -1, 0, NULL },
    { "samples_and_slices_extremes", "samples 64", ROOM, 12, 8, 1, 64, 0, -1, 0, NULL },
    { "samples_and_slices_extremes", "slices 1", ROOM, 16, 12, 1, 0, 1, -1, 0, NULL },
    { "samples_and_slices_extremes", "slices 8", ROOM, 16, 12, 1, 0, 8, -1, 0, NULL },
    { "white_box_1000_frames_and_hot_emitter", "albedo 1 closed box, 1000 frames",
      "camera pos 0 1 -1.5 target 0 1 0\n"
      "material wall albedo 1 1 1 f0 0\n"
      "material lamp albedo 1 1 1 emissive 20 20 20\n"
      "box min -2 0 -2 max 2 3 2 material wall inward\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material lamp\n"
      "light point pos 0 2.5 0 color 1 1 1 intensity 20\n"
      "env uniform 1 1 1\n",
      4, 4, 1000, 0, 0, -1, 0, NULL },
    { "white_box_1000_frames_and_hot_emitter", "emissive 1e4",
      "camera pos 0 1 -3.5 target 0 1 0\n"
      "material wall albedo 1 1 1 f0 0\n"
      "material lamp albedo 1 1 1 emissive 10000 10000 10000\n"
      "box min -2 0 -4 max 2 3 2 material wall inward\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material lamp\n"
      "light point pos 0 2.5 0 color 1 1 1 intensity 10000 shadows\n",
      16, 12, 3, 0, 0, -1, 0, NULL },
    /* Zero-area, collinear and sliver triangles (the OBJ loader keeps them). */
    { "degenerate_triangles", "zero-area, collinear and sliver triangles",
      "camera pos 0 1 -3 target 0 0.5 0\n"
      "material m albedo 0.6 0.6 0.6 twosided\n"
      "quad p0 -5 0 -5 p1 -5 0 5 p2 5 0 5 p3 5 0 -5 material m\n"
      "mesh file bad.obj material m\n"
      "light point pos 0 2 -1 color 1 1 1 intensity 3 shadows\n"
      "env uniform 0.3 0.3 0.3\n",
      16, 12, 1, 0, 0, -1, 0,
      "v 0 0.5 0\nv 1 0.5 0\nv 2 0.5 0\nv 0 1.5 0\nv -1 0.2 0\nv 1 0.2001 0\nv -1 0.2 0.00001\n"
      "vn 0 0 -1\n"
      "f 1 1 1\nf 1 2 1\nf 1 2 3\nf 3 2 1\n"
      "f 5 6 7\nf 5 4 6\nf 1//1 2//1 3//1\nf 4 4 2\n" },
    { "fov_extremes_and_camera_straight_down", "fov 1",
      "camera pos 0 1 -3.5 target 0 0.5 0 fov 1\n"
      "material m albedo 0.7 0.7 0.7\n"
      "box min -2 0 -4 max 2 3 2 material m inward\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material m\n"
      "light point pos 0 2.5 0 color 1 1 1 intensity 4\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    { "fov_extremes_and_camera_straight_down", "fov 179",
      "camera pos 0 1 -3.5 target 0 1 0 fov 179\n"
      "material m albedo 0.7 0.7 0.7\n"
      "box min -2 0 -4 max 2 3 2 material m inward\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material m\n"
      "light point pos 0 2.5 0 color 1 1 1 intensity 4\n",
      16, 12, 1, 0, 0, -1, 0, NULL },
    { "fov_extremes_and_camera_straight_down", "camera straight down",
      "camera pos 0 4 0 target 0 0 0\n"
      "material m albedo 0.7 0.7 0.7\n"
      "quad p0 -5 0 -5 p1 -5 0 5 p2 5 0 5 p3 5 0 -5 material m\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material m\n"
      "light directional dir 0 -1 0 color 1 1 1 shadows\n"
      "env uniform 0.3 0.3 0.3\n",
      16, 12, 2, 0, 0, -1, 0, NULL },
    /* A square pit seen from straight above: at its centre the horizons are
     * the same on every side, the horizontal parts of the bent normal cancel. */
    { "symmetric_pit", "symmetric pit",
      "camera pos 0 3 0.0001 target 0 0 0 fov 40\n"
      "material m albedo 0.7 0.7 0.7\n"
      "quad p0 -1 -1 -1 p1 -1 -1 1 p2 1 -1 1 p3 1 -1 -1 material m\n"
      "quad p0 -1 -1 -1 p1 1 -1 -1 p2 1 0 -1 p3 -1 0 -1 material m\n"
      "quad p0 1 -1 1 p1 -1 -1 1 p2 -1 0 1 p3 1 0 1 material m\n"
      "quad p0 -1 -1 1 p1 -1 -1 -1 p2 -1 0 -1 p3 -1 0 1 material m\n"
      "quad p0 1 -1 -1 p1 1 -1 1 p2 1 0 1 p3 1 0 -1 material m\n"
      "env uniform 1 1 1\n"
      "gi radius 3\n",
      17, 17, 1, 0, 0, -1, 0, NULL },
    { "camera_cut_and_fast_object", "camera cut",
      "camera_key t 0 pos 0 1 -3.5 target 0 1 0\n"
      "camera_key t 1 pos 0 1 -3.5 target 0 1 0\n"
      "camera_key t 1.01 pos 1.5 2.5 1.5 target -1 0 -2\n"
      "camera_key t 3 pos 1.5 2.5 1.5 target -1 0 -2\n"
      "material wall albedo 0.7 0.7 0.7\n"
      "material lamp albedo 0.5 0.5 0.5 emissive 5 5 5\n"
      "box min -2 0 -4 max 2 3 2 material wall inward\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material wall\n"
      "quad p0 -0.5 2.99 -0.5  p1 0.5 2.99 -0.5  p2 0.5 2.99 0.5  p3 -0.5 2.99 0.5 material lamp\n"
      "light point pos 0 2.5 0 color 1 1 1 intensity 4 shadows\n",
      16, 12, 4, 0, 0, -1, 0, NULL },
    { "camera_cut_and_fast_object", "fast-moving object",
      "camera pos 0 1 -3.5 target 0 1 0\n"
      "camera_key t 0 pos 0 1 -3.5 target 0 1 0\n"
      "camera_key t 3 pos 0.1 1 -3.5 target 0 1 0\n"
      "material wall albedo 0.7 0.7 0.7\n"
      "box min -2 0 -4 max 2 3 2 material wall inward\n"
      "box min -0.5 0 -0.5 max 0.5 1 0.5 material wall name runner\n"
      "object_key name runner t 0 translate -1.4 0 0\n"
      "object_key name runner t 1 translate 1.4 0.5 -1 rotate 0 1 0 90\n"
      "object_key name runner t 2 translate -1.4 0 -2 rotate 1 0 0 180\n"
      "object_key name runner t 3 translate 1.4 1 0\n"
      "light point pos 0 2.5 0 color 1 1 1 intensity 4 shadows\n"
      "env uniform 0.2 0.2 0.2\n",
      16, 12, 4, 0, 0, -1, 0, NULL },
    /* A world near float's range (coordinates 3e38, the camera as far out):
     * eye + view ray overflowed to inf, and the motion AOV of a camera that
     * never moves was NaN (motion.h; inf - inf).  Q16.16 refuses the
     * numbers (beyond 32767). */
    { "world_near_float_range", "world near float's range",
      "camera pos 0 3e38 3e38 target 0 0 0 far 3.4e38\n"
      "material m albedo 0.5 0.5 0.5\n"
      "quad p0 -3e38 0 -3e38 p1 -3e38 0 3e38 p2 3e38 0 3e38 p3 3e38 0 -3e38 material m\n",
      7, 5, 2, 0, 0, -1, 1, NULL },
};

/* Run every case of named_cases the test `test` owns (it owns at least one). */
static void run_named(const char *test)
{
    size_t i;
    int owned = 0;
    for (i = 0; i < sizeof named_cases / sizeof named_cases[0]; i++)
        if (strcmp(named_cases[i].test, test) == 0) {
            run_case(&named_cases[i]);
            owned++;
        }
    CHECK(owned > 0, "no case in named_cases for %s", test);
}

#define NAMED_TEST(name) TEST(name) { run_named(#name); }

NAMED_TEST(interpolated_normals_facing_away)
NAMED_TEST(camera_inside_a_box)
NAMED_TEST(near_plane_crossing_and_behind_camera)
NAMED_TEST(sky_beside_geometry)
NAMED_TEST(one_pixel_pillars)
NAMED_TEST(near_tiny_far_huge)
NAMED_TEST(radius_zero_and_screen_covering)
NAMED_TEST(samples_and_slices_extremes)
NAMED_TEST(white_box_1000_frames_and_hot_emitter)
NAMED_TEST(degenerate_triangles)
NAMED_TEST(fov_extremes_and_camera_straight_down)
NAMED_TEST(symmetric_pit)
NAMED_TEST(camera_cut_and_fast_object)
NAMED_TEST(world_near_float_range)

/* A generated scene: its name and text. */
typedef struct scene_buf { char name[64], text[1024]; } scene_buf;

/* The case of the default size (16x12, one frame) that renders b->text;
 * b->name is name_fmt with value. */
static hard_case generated(scene_buf *b, const char *name_fmt, double value, int may_refuse)
{
    hard_case c = { 0, 0, 0, 16, 12, 1, 0, 0, -1, 0, NULL };
    snprintf(b->name, sizeof b->name, name_fmt, value);
    c.name = b->name;
    c.text = b->text;
    c.may_refuse = may_refuse;
    return c;
}

/* A plane (y = 0) seen at `deg` degrees between the view and the plane. */
static void plane_at(scene_buf *b, double deg)
{
    double a = deg * 3.14159265358979 / 180.0;
    snprintf(b->text, sizeof b->text,
             "camera pos 0 %.7f %.7f target 0 0 0 fov 50\n"
             "material m albedo 0.5 0.5 0.5\n"
             "quad p0 -300 0 -300 p1 -300 0 300 p2 300 0 300 p3 300 0 -300 material m\n"
             "box min -0.3 0 -0.3 max 0.3 0.4 0.3 material m\n"
             "light directional dir 0.3 -1 0.2 color 1 1 1 shadows\n"
             "env sky 0.4 0.5 0.7 ground 0.1 0.1 0.1\n",
             3 * sin(a), -3 * cos(a));
}

TEST(planes_at_grazing_and_steep_angles)
{
    static const double deg[] = { 0.1, 1, 80, 89.9 };
    int k;
    for (k = 0; k < 4; k++) {
        scene_buf b;
        hard_case c;
        plane_at(&b, deg[k]);
        c = generated(&b, "plane at %g deg", deg[k], 0);
        run_case(&c);
    }
}

/* The room scaled by s (geometry, camera, near/far, radius; lights scaled
 * so that the irradiance is the same). */
static void scaled_room(scene_buf *b, double s)
{
    snprintf(b->text, sizeof b->text,
             "camera pos 0 %.9g %.9g target 0 %.9g 0 fov 60 near %.9g far %.9g\n"
             "material wall albedo 0.7 0.7 0.7 f0 0\n"
             "box min %.9g 0 %.9g max %.9g %.9g %.9g material wall inward\n"
             "box min %.9g 0 %.9g max %.9g %.9g %.9g material wall\n"
             "light directional dir 0.2 -1 0.3 color 1 1 1\n"
             "env uniform 0.2 0.2 0.2\n"
             "gi radius %.9g\n",
             1 * s, -3.5 * s, 1 * s, 0.05 * s, 100 * s,
             -2 * s, -4 * s, 2 * s, 3 * s, 2 * s,
             -0.5 * s, -0.5 * s, 0.5 * s, 1 * s, 0.5 * s, 1.5 * s);
}

/* Techniques whose AO is checked to be the same at every scale.  Known
 * failures at scale 0.001 (left out until fixed):
 * the reference (float and fixed: a world-unit ray epsilon, AO off by
 * ~0.08), and in fixed point hbao (0.08) and vo (0.18), whose
 * squared distances underflow Q16.16. */
static int scale_invariant(int t)
{
    if (t == TG_TECH_REFERENCE) return 0;
    if (TG_FIXED && (t == TG_TECH_HBAO || t == TG_TECH_VO)) return 0;
    return 1;
}

/* Scale 1000 and 0.001: the invariants hold (or fixed point refuses with a
 * message), and AO - which is scale-invariant - matches the unit room. */
TEST(room_scaled_by_1000_and_0001)
{
    static const double scales[] = { 1000, 0.001 };
    scene_buf unit;
    int k, t;
    scaled_room(&unit, 1);
    for (k = 0; k < 2; k++) {
        scene_buf room;
        hard_case c;
        scaled_room(&room, scales[k]);
        c = generated(&room, "room scaled by %g", scales[k], 1);
        for (t = 0; t < TG_TECH_COUNT; t++) {
            if (run_technique(&c, t) && scale_invariant(t)) {
                rendered a, b;
                tg_request q;
                tg_error err;
                tg_request_defaults(&q);
                q.width = 32; q.height = 24; q.aovs = AOVBIT(TG_AOV_AO); q.technique = (tg_technique)t;
                if (t == TG_TECH_REFERENCE) q.samples = 16;
                if (setup(&a, unit.text, &q) && setup(&b, c.text, &q)) {
                    double *x, *y, diff = 0;
                    size_t i;
                    tg_frame_render(a.frame, 0, &err);
                    tg_frame_render(b.frame, 0, &err);
                    x = read_aov(&a, TG_AOV_AO);
                    y = read_aov(&b, TG_AOV_AO);
                    for (i = 0; i < 32 * 24; i++) diff += fabs(x[i] - y[i]);
                    diff /= 32 * 24;
                    CHECK(diff <= 0.02, "%s / %s: AO differs from the unit room by %.4f on average",
                          c.name, tg_technique_name((tg_technique)t), diff);
                    free(x); free(y);
                } else {
                    CHECK(TG_FIXED && b.status == TG_ERR_INPUT, "%s: %s", c.name, b.msg);
                }
                teardown(&a); teardown(&b);
            }
        }
    }
}

TEST(odd_framebuffers)
{
    static const int sizes[][2] = { { 1, 1 }, { 2, 2 }, { 3, 5 }, { 5, 3 }, { 4097, 3 } };
    int k;
    for (k = 0; k < 5; k++) {
        char name[64];
        hard_case c = { 0, 0, 0, 0, 0, 2, 0, 0, -1, 0, NULL };
        snprintf(name, sizeof name, "framebuffer %dx%d", sizes[k][0], sizes[k][1]);
        c.name = name;
        c.text = tg_builtin_scene("cornell");
        c.width = sizes[k][0];
        c.height = sizes[k][1];
        run_case(&c);
    }
}

TEST(acos_a_hair_outside_its_domain)
{
    static const float xs[] = { 1.0000001f, 1.00001f, 1.001f, 2.0f, -1.0000001f, -1.00001f, -1.001f, -2.0f, 1.0f, -1.0f };
    int k;
    for (k = 0; k < 10; k++) {
        tg_real x = TG_R(xs[k]);
        double a = check_d(tg_acos(x));
        double want = xs[k] > 0 ? 0 : 3.14159265358979;
        CHECK(isfinite(a) && a >= 0 && a <= 3.1416, "acos(%.9g) = %g", (double)xs[k], a);
        CHECK_NEAR(a, want, TG_FIXED ? 2e-3 : 1e-3);
    }
    /* one ulp outside in the build's own representation */
#if TG_FIXED
    CHECK_NEAR(check_d(tg_acos(TG_ONE + 1)), 0, 2e-3);
    CHECK_NEAR(check_d(tg_acos(-TG_ONE - 1)), 3.14159265358979, 2e-3);
    CHECK_NEAR(check_d(tg_acos(TG_REAL_MAX)), 0, 2e-3);
    CHECK_NEAR(check_d(tg_acos(TG_REAL_MIN)), 3.14159265358979, 2e-3);
#endif
    CHECK(check_d(tg_sqrt(TG_R(-1e-4f))) == 0, "sqrt of a tiny negative is 0");
}

int main(void)
{
    RUN(planes_at_grazing_and_steep_angles);
    RUN(interpolated_normals_facing_away);
    RUN(camera_inside_a_box);
    RUN(near_plane_crossing_and_behind_camera);
    RUN(sky_beside_geometry);
    RUN(one_pixel_pillars);
    RUN(near_tiny_far_huge);
    RUN(room_scaled_by_1000_and_0001);
    RUN(radius_zero_and_screen_covering);
    RUN(samples_and_slices_extremes);
    RUN(odd_framebuffers);
    RUN(white_box_1000_frames_and_hot_emitter);
    RUN(degenerate_triangles);
    RUN(fov_extremes_and_camera_straight_down);
    RUN(symmetric_pit);
    RUN(acos_a_hair_outside_its_domain);
    RUN(camera_cut_and_fast_object);
    RUN(world_near_float_range);
    return check_summary();
}
