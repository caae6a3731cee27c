/* SPDX-License-Identifier: MIT */
/*
 * test_shadow_plan.c - the plan's shadows: each face's size is the size
 * rule's and the plan carves exactly those bytes (absent faces none);
 * --shadow-size still forces every face the view needs; the plan's choice
 * between maps and shadow rays (rays where one map is too coarse: a box on
 * a far-reaching ground plane, its shadow checked against the geometry);
 * rays against maps at a fine size; and no
 * pixel of cornell's ceiling round the lamp (facing the light, nothing
 * between) left without direct light at 40x30, 160x120 or 320x240.
 */
#include "frame_fixture.h"
#include "frame/frame_internal.h"
#include "light/shadowview.h"

static const char *method_names[3] = { "auto", "maps", "rays" };

/* Bytes of the plan's buffers whose names start with `prefix`. */
static size_t buffer_bytes(const tg_plan *p, const char *prefix)
{
    size_t total = 0;
    int i;
    for (i = 0; i < p->buffer_count; i++)
        if (!strncmp(p->buffers[i].name, prefix, strlen(prefix))) total += p->buffers[i].bytes;
    return total;
}

static size_t round16(size_t n) { return (n + 15) & ~(size_t)15; }

/* A frame of `text` for q with shadow maps forced; 0 (reported) when it fails. */
static int set_up_maps(rendered *r, const char *text, tg_request q)
{
    q.shadow_method = TG_SHADOWS_MAPS;
    if (setup(r, text, &q)) return 1;
    CHECK(0, "%s", r->msg);
    return 0;
}

/* The rule's need for light i at the scene's own camera, computed here
 * step by step (the plan's own path is tgi_shadow_plan). */
static void rule_at_the_camera(const tg_scene *s, int i, int w, int h, int size, tgi_shadow_need *nd)
{
    const tgi_scene_camera *c = &s->camera;
    tgi_view v;
    tgi_view_make(&v, c->pos, c->target, c->up, c->fov, c->znear, c->zfar, w, h);
    tgi_shadow_need_init(nd, &s->lights[i]);
    tgi_shadow_map_size_rule(nd, &s->lights[i], &v, s->bounds_min, s->bounds_max, s->tri_pos, s->tri_count);
    tgi_shadow_need_finish(nd, size);
}

/* The plan's need: the rule's, its densities then raised by the largest
 * k = 1 + j/16 <= TG_SHADOW_RULE_GAIN whose maps fit in
 * TG_SHADOW_MAP_BYTES_PER_PIXEL bytes per image pixel (--shadow-size: none). */
static void plan_need(const tg_scene *s, int i, int w, int h, int size, tgi_shadow_need *nd)
{
    tgi_shadow_need rule;
    int j, f, lights = 0;
    size_t budget;
    for (j = 0; j < s->light_count; j++) lights += s->lights[j].shadows != 0;
    budget = tgi_shadow_light_budget((size_t)w * (size_t)h, lights);   /* the light's share */
    rule_at_the_camera(s, i, w, h, size, &rule);
    *nd = rule;
    if (size > 0 || tgi_shadow_need_bytes(&rule) >= budget) return;
    for (j = 16 * (TG_SHADOW_RULE_GAIN - 1); j > 0; j--) {
        for (f = 0; f < nd->faces; f++) nd->density[f] = tg_mul(rule.density[f], tg_ratio(16 + j, 16));
        tgi_shadow_need_finish(nd, 0);
        if (tgi_shadow_need_bytes(nd) <= budget) return;
    }
    *nd = rule;
}

/* The frame's maps have the rule's faces and the plan carved their bytes. */
static void check_rule_sizes(const char *scene, int w, int h, int size)
{
    rendered r;
    tg_request q = request(w, h, AOVBIT(TG_AOV_COLOR));
    size_t want = 0;
    int i, f;
    q.shadow_map_size = size;
    if (!set_up_maps(&r, tg_builtin_scene(scene), q)) return;
    for (i = 0; i < r.scene->light_count; i++) {
        tgi_shadow_need nd;
        size_t texels = 0;
        if (!r.scene->lights[i].shadows) continue;
        plan_need(r.scene, i, w, h, size, &nd);
        for (f = 0; f < nd.faces; f++) {
            texels += (size_t)nd.size[f] * (size_t)nd.size[f];
            CHECK(r.frame->shadow_maps[i].face[f].size == nd.size[f], "%s %dx%d size %d: light %d face %d: %d, the rule %d",
                  scene, w, h, size, i, f, r.frame->shadow_maps[i].face[f].size, nd.size[f]);
            if (size > 0) CHECK(nd.size[f] == 0 || nd.size[f] == size, "%s: --shadow-size %d, face %d %d", scene, size, f, nd.size[f]);
        }
        want += round16(texels * 2);
    }
    CHECK(buffer_bytes(&r.plan, "shadow maps (depth)") == want, "%s %dx%d size %d: the plan carves %zu bytes, the faces %zu",
          scene, w, h, size, buffer_bytes(&r.plan, "shadow maps (depth)"), want);
    teardown(&r);
}

TEST(plan_sizes_are_the_rule)
{
    static const char *scenes[] = { "cornell", "columns", "spheres" };
    static const int sizes[][2] = { { 40, 30 }, { 160, 120 }, { 320, 240 } };
    size_t a, b;
    for (a = 0; a < 3; a++)
        for (b = 0; b < 3; b++) {
            check_rule_sizes(scenes[a], sizes[b][0], sizes[b][1], 0);
            check_rule_sizes(scenes[a], sizes[b][0], sizes[b][1], 64);   /* --shadow-size forces */
        }
}

/* The goal: shadow maps at the default rule take at most
 * TG_SHADOW_MAP_BYTES_PER_PIXEL bytes per image pixel on cornell and
 * columns at 320x240 (512-texel faces took 41 and 6.8 in 16 bits). */
TEST(default_maps_fit_in_eight_bytes_a_pixel)
{
    static const char *scenes[] = { "cornell", "columns" };
    size_t a;
    for (a = 0; a < 2; a++) {
        rendered r;
        size_t bytes;
        if (!set_up_maps(&r, tg_builtin_scene(scenes[a]), request(320, 240, AOVBIT(TG_AOV_COLOR)))) continue;
        bytes = buffer_bytes(&r.plan, "shadow maps (depth)");
        CHECK(bytes > 0 && bytes <= 320u * 240u * TG_SHADOW_MAP_BYTES_PER_PIXEL, "%s: %zu bytes", scenes[a], bytes);
        teardown(&r);
    }
}

/* Eight shadowed point lights in cornell share the maps' budget: their
 * maps together within TG_SHADOW_MAP_BYTES_PER_PIXEL bytes a pixel, the
 * lights over their share on shadow rays (the BVH of 32 triangles is the
 * smaller).  Each light had the whole budget: 9 maps took 1299280 bytes at
 * 160x120, 8.5 times the budget (a hard-case probe: 64 lights took 35 MB
 * at 320x240).  Forced maps still take what the rule says. */
TEST(lights_share_the_maps_budget)
{
    const int w = 160, h = 120, n = 8;
    char text[8192];
    size_t len, budget = (size_t)w * h * TG_SHADOW_MAP_BYTES_PER_PIXEL;
    int i, m;
    len = (size_t)snprintf(text, sizeof text, "%s", tg_builtin_scene("cornell"));
    for (i = 0; i < n && len < sizeof text; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "light point pos %.2f 4.5 %.2f color 1 1 1 intensity 2 shadows\n",
                                1.0 + 0.5 * i, 1.5 + 0.3 * i);
    for (m = TG_SHADOWS_AUTO; m <= TG_SHADOWS_MAPS; m++) {
        rendered r;
        tg_request q = request(w, h, AOVBIT(TG_AOV_COLOR));
        size_t bytes;
        int rays = 0, maps = 0, x;
        q.shadow_method = m;
        if (!setup_checked(&r, text, &q, "cornell with 8 more lights") || tg_frame_render(r.frame, 0, NULL) != TG_OK) {
            CHECK(0, "%s", r.msg);
            continue;
        }
        bytes = buffer_bytes(&r.plan, "shadow maps (depth)");
        for (i = 0; i < r.scene->light_count; i++)
            if (r.scene->lights[i].shadows) {
                if (r.frame->shadow_maps[i].ray) rays++;
                else maps++;
            }
        CHECK(rays + maps == n + 1, "%d shadowed lights, want %d", rays + maps, n + 1);
        if (m == TG_SHADOWS_MAPS) {
            CHECK(rays == 0 && bytes > budget, "forced maps: %d on rays, %zu bytes (over %zu: else the test proves nothing)",
                  rays, bytes, budget);
        } else {
            CHECK(bytes <= budget, "auto: the maps take %zu bytes, over the budget %zu", bytes, budget);
            CHECK(rays > 0 && buffer_bytes(&r.plan, "shadow rays: BVH") > 0, "auto: %d lights on rays", rays);
        }
        {   /* a finite, lit frame either way */
            tg_real row[3 * 160];
            int y, lit = 0, bad = 0;
            for (y = 0; y < h; y++) {
                CHECK(tg_frame_aov_row(r.frame, TG_AOV_COLOR, y, row) == TG_OK, "row %d", y);
                for (x = 0; x < 3 * w; x++) {
                    const double v = check_d(row[x]);
                    bad += !(v >= 0 && v <= 1e6);
                    lit += v > 0.01;
                }
            }
            CHECK(bad == 0 && lit > w * h, "%s: %d values not finite, %d lit", method_names[m], bad, lit);
        }
        teardown(&r);
    }
}

/* A point light over a floor, the camera beside it looking straight down:
 * no receiver it sees can look up any face but -Y, so the others are
 * absent (no bytes, size 0), with the rule and with --shadow-size; the
 * map still shadows (a post between the light and the floor). */
TEST(culled_faces_take_no_memory)
{
    static const char text[] =
        "camera pos 0.2 2.5 0  target 0.2 0 0.01  fov 40\n"
        "material white albedo 0.8 0.8 0.8\n"
        "quad p0 -20 0 -20  p1 -20 0 20  p2 20 0 20  p3 20 0 -20  material white\n"
        "box min -0.1 0 -0.1  max 0.1 1 0.1  material white\n"
        "light point pos 0 2 0  color 1 1 1  intensity 10  shadows\n";
    static const int sizes[] = { 0, 64 };
    size_t k;
    int f;
    for (k = 0; k < 2; k++) {
        rendered r;
        tg_request q = request(64, 48, AOVBIT(TG_AOV_DIRECT));
        double *e;
        int x, y, dark = 0;
        q.shadow_map_size = sizes[k];
        if (!set_up_maps(&r, text, q)) continue;
        for (f = 0; f < 6; f++)
            CHECK((r.frame->shadow_maps[0].face[f].size > 0) == (f == 3), "size %d: face %d size %d", sizes[k], f,
                  r.frame->shadow_maps[0].face[f].size);
        CHECK(buffer_bytes(&r.plan, "shadow maps (depth)") ==
              round16((size_t)r.frame->shadow_maps[0].face[3].size * (size_t)r.frame->shadow_maps[0].face[3].size * 2),
              "size %d: one face's bytes, got %zu", sizes[k], buffer_bytes(&r.plan, "shadow maps (depth)"));
        CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "render");
        e = read_aov(&r, TG_AOV_DIRECT);
        for (y = 0; y < 48; y++)
            for (x = 0; x < 64; x++) dark += e[3 * (y * 64 + x)] <= 0;
        CHECK(dark > 0 && dark < 64 * 48 / 4, "size %d: %d pixels in the post's shadow", sizes[k], dark);
        free(e);
        teardown(&r);
    }
}

/* The plan's choice: tgi_shadow_choose on the rule's bytes, the BVH's
 * bytes and the scene, then rays where one map is too coarse and the BVH
 * smaller (tgi_shadow_map_coarse; README "Shadows"), as --explain reports it; rays
 * carve the BVH and no map, forced either way. */
TEST(plan_chooses_as_the_rule_says)
{
    static const char *scenes[] = { "cornell", "columns", "spheres" };
    static const int sizes[][2] = { { 40, 30 }, { 320, 240 } };
    size_t a, b;
    int m;
    for (a = 0; a < 3; a++)
        for (b = 0; b < 2; b++)
            for (m = TG_SHADOWS_AUTO; m <= TG_SHADOWS_RAYS; m++) {
                rendered r;
                tg_request q = request(sizes[b][0], sizes[b][1], AOVBIT(TG_AOV_COLOR));
                tgi_shadow_need nd;
                int want;
                char text[4096];
                q.shadow_method = m;
                if (!setup(&r, tg_builtin_scene(scenes[a]), &q)) { CHECK(0, "%s", r.msg); continue; }
                plan_need(r.scene, 0, sizes[b][0], sizes[b][1], 0, &nd);
                want = m == TG_SHADOWS_MAPS ? TG_SHADOW_BY_MAP : m == TG_SHADOWS_RAYS ? TG_SHADOW_BY_RAYS
                     : tgi_shadow_choose(tgi_shadow_need_bytes(&nd), tgi_bvh_bytes(r.scene->tri_count),
                                         (size_t)sizes[b][0] * (size_t)sizes[b][1], 1);
                if (m == TG_SHADOWS_AUTO && want == TG_SHADOW_BY_MAP
                    && tgi_bvh_bytes(r.scene->tri_count) < tgi_shadow_need_bytes(&nd)) {   /* one map too coarse */
                    const tgi_scene_camera *c = &r.scene->camera;
                    tgi_view v;
                    tgi_view_make(&v, c->pos, c->target, c->up, c->fov, c->znear, c->zfar, sizes[b][0], sizes[b][1]);
                    if (tgi_shadow_map_coarse(&nd, &r.scene->lights[0], &v, r.scene->bounds_min, r.scene->bounds_max,
                                              r.scene->tri_pos, r.scene->tri_count))
                        want = TG_SHADOW_BY_RAYS;
                }
                CHECK((r.frame->shadow_maps[0].ray != NULL) == (want == TG_SHADOW_BY_RAYS), "%s %dx%d %s: rays %d, want %d",
                      scenes[a], sizes[b][0], sizes[b][1], method_names[m], r.frame->shadow_maps[0].ray != NULL, want);
                CHECK((buffer_bytes(&r.plan, "shadow rays: BVH") == round16(tgi_bvh_bytes(r.scene->tri_count))) ==
                      (want == TG_SHADOW_BY_RAYS), "%s: the BVH's bytes", scenes[a]);
                CHECK((buffer_bytes(&r.plan, "shadow maps (depth)") == 0) == (want == TG_SHADOW_BY_RAYS), "%s: the maps' bytes",
                      scenes[a]);
                tg_plan_explain(&r.plan, text, sizeof text);
                CHECK((strstr(text, "shadow rays against the BVH") != NULL) == (want == TG_SHADOW_BY_RAYS),
                      "%s: --explain says how", scenes[a]);
                teardown(&r);
            }
}

/* E_direct's luminance per pixel for cornell with shadows `method` (maps
 * at `size`, 0 = the rule; filter `pcf`). */
static double *cornell_direct(int w, int h, int method, int size, int pcf, rendered *r, double **depth, double **normal)
{
    tg_request q = request(w, h, AOVBIT(TG_AOV_DIRECT) | AOVBIT(TG_AOV_DEPTH) | AOVBIT(TG_AOV_NORMAL));
    double *e;
    q.shadow_method = method;
    q.shadow_map_size = size;
    q.shadow_pcf = pcf;
    if (!setup(r, tg_builtin_scene("cornell"), &q) || tg_frame_render(r->frame, 0, NULL) != TG_OK) {
        CHECK(0, "cornell %dx%d: %s", w, h, r->msg);
        return NULL;
    }
    e = read_aov(r, TG_AOV_DIRECT);
    if (depth) *depth = read_aov(r, TG_AOV_DEPTH);
    if (normal) *normal = read_aov(r, TG_AOV_NORMAL);
    return e;
}

/* Cornell's lamp quad (y 5.478, x 2.13..3.43, z 2.27..3.32) hangs between
 * the point light (2.78, 5.3, 2.795) and the ceiling (y 5.488): a ceiling
 * point is in its shadow iff the ray to the light crosses the quad, i.e.
 * within the quad scaled about the light by (5.488 - 5.3) / (5.478 - 5.3).
 * Seen from below, the ceiling shows outside the quad and the quad's lit
 * underside within it.  1: every point within mx, mz of (x, z) is lit. */
static int lit_round_the_lamp(double x, double z, double mx, double mz)
{
    double s = (5.488 - 5.3) / (5.478 - 5.3);
    double x0 = 2.78 + s * (2.13 - 2.78), x1 = 2.78 + s * (3.43 - 2.78);
    double z0 = 2.795 + s * (2.27 - 2.795), z1 = 2.795 + s * (3.32 - 2.795);
    int on_lamp = x > 2.13 + mx && x < 3.43 - mx && z > 2.27 + mz && z < 3.32 - mz;
    int out_of_shadow = x < x0 - mx || x > x1 + mx || z < z0 - mz || z > z1 + mz;
    return on_lamp || out_of_shadow;
}

/* Every pixel of the ceiling or of the lamp's underside within 2.5 of the
 * light (the walls are farther) (facing it; lit at grazing incidence round the lamp) whose whole
 * footprint sees the light gets at least half its unshadowed irradiance
 * (none may be 0); returns how many there were. */
static int check_ceiling(int w, int h, int method, int pcf, const char *what)
{
    rendered r;
    double *depth = NULL, *normal = NULL, *e = cornell_direct(w, h, method, 0, pcf, &r, &depth, &normal);
    const tgi_scene_camera *c;
    tgi_view v;
    int x, y, j, count = 0, dark = 0;
    if (!e) return 0;
    c = &r.scene->camera;
    tgi_view_make(&v, c->pos, c->target, c->up, c->fov, c->znear, c->zfar, w, h);
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            double ppu = check_d(v.pixels_per_unit), ky = (h / 2.0 - (y + 0.5)) / ppu, kx = (x + 0.5 - w / 2.0) / ppu;
            double d = depth[i], p[3], l[3], dist, eye_dist = 0, foot, want, got;
            if (d <= 0 || normal[3 * i + 1] > -0.99) continue;   /* sky, or not facing down */
            for (j = 0; j < 3; j++) {
                double dir = check_d((&v.forward.x)[j]) + ky * check_d((&v.up.x)[j]) + kx * check_d((&v.right.x)[j]);
                p[j] = check_d((&v.eye.x)[j]) + dir * d;
                eye_dist += dir * d * dir * d;
            }
            eye_dist = sqrt(eye_dist);
            if (p[1] < 5.4) continue;                              /* the short block's top */
            l[0] = 2.78 - p[0]; l[1] = 5.3 - p[1]; l[2] = 2.795 - p[2];
            dist = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
            if (dist > 2.5) continue;
            /* the pixel's footprint (the lookup's filter spans about as much):
             * a pixel across, stretched by the grazing view in depth */
            foot = eye_dist / ppu;
            if (!lit_round_the_lamp(p[0], p[2], foot, foot * eye_dist / fabs(p[1] - check_d(v.eye.y)))) continue;
            want = 18 * (1 + 0.85 + 0.65) * (fabs(l[1]) / dist) / (dist * dist);   /* Lambert, n = (0, -1, 0) */
            got = e[3 * i] + e[3 * i + 1] + e[3 * i + 2];
            count++;
            if (got < 0.5 * want) {
                if (dark < 5)
                    fprintf(stderr, "  %s %dx%d: pixel (%d, %d) at (%.3f, %.3f, %.3f): E %.4g, unshadowed %.4g\n", what, w, h,
                            x, y, p[0], p[1], p[2], got, want);
                dark++;
            }
        }
    if (getenv("SHADOW_PLAN_VERBOSE")) fprintf(stderr, "%s %dx%d: %d ceiling pixels, %d dark\n", what, w, h, count, dark);
    CHECK(dark == 0, "%s %dx%d: %d of %d ceiling pixels round the lamp lit less than half", what, w, h, dark, count);
    free(e); free(depth); free(normal);
    teardown(&r);
    return count;
}

/* A 2-unit box on a ground plane of half side `half`, both moved by
 * (offset, 0, offset), under a directional light (README "Shadows": where
 * one map is not enough). */
static const char *box_on_ground_at(int half, int ox, int oz, char *text, size_t size)
{
    snprintf(text, size,
             "camera pos %d 3 %d  target %d 0.5 %d\n"
             "material base albedo 0.5 0.5 0.5\n"
             "material red albedo 0.8 0.2 0.2\n"
             "quad p0 %d 0 %d p1 %d 0 %d p2 %d 0 %d p3 %d 0 %d material base\n"
             "box min %d 0 %d max %d 2 %d material red\n"
             "light directional dir -0.3 -1 -0.2 color 1 1 1 intensity 3 shadows\n"
             "env uniform 0.1 0.1 0.1\n",
             ox, oz + 8, ox, oz, ox - half, oz - half, ox - half, oz + half, ox + half, oz + half, ox + half, oz - half,
             ox - 1, oz - 1, ox + 1, oz + 1);
    return text;
}
static const char *box_on_ground(int half, int offset, char *text, size_t size)
{
    return box_on_ground_at(half, offset, offset, text, size);
}

/* Whether the ray from (x, 0, z) toward the light (-dir) meets the box
 * [-1, 1] x [0, 2] x [-1, 1] (slabs; x, z relative to the box's centre). */
static int in_box_shadow(double x, double z)
{
    const double o[3] = { x, 0, z }, d[3] = { 0.3, 1, 0.2 }, lo[3] = { -1, 0, -1 }, hi[3] = { 1, 2, 1 };
    double t0 = 0, t1 = 1e9;
    int k;
    for (k = 0; k < 3; k++) {
        double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
        if (a > b) { double c = a; a = b; b = c; }
        if (a > t0) t0 = a;
        if (b < t1) t1 = b;
    }
    return t0 <= t1;
}

/* The rendered frame r of box_on_ground(.., offset): the box's shadow on
 * the floor is where the geometry puts it: every floor pixel whose
 * footprint (0.1 about it) lies wholly in the shadow gets under a tenth of
 * the lit floor's direct light, every one wholly outside over nine tenths. */
static void check_box_shadow_at(const rendered *r, int ox, int oz, const char *what)
{
    const int w = r->plan.request.width, h = r->plan.request.height;
    const tgi_scene_camera *c = &r->scene->camera;
    double *e = read_aov(r, TG_AOV_DIRECT), *depth = read_aov(r, TG_AOV_DEPTH), *normal = read_aov(r, TG_AOV_NORMAL);
    double lit = 0;
    tgi_view v;
    int x, y, j, shadowed = 0, open = 0, bad = 0;
    tgi_view_make(&v, c->pos, c->target, c->up, c->fov, c->znear, c->zfar, w, h);
    for (j = 0; j < w * h; j++)
        if (depth[j] > 0 && normal[3 * j + 1] > 0.99 && e[3 * j] > lit) lit = e[3 * j];
    for (y = 0; y < h; y++)
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            double ppu = check_d(v.pixels_per_unit), ky = (h / 2.0 - (y + 0.5)) / ppu, kx = (x + 0.5 - w / 2.0) / ppu;
            double p[3], px, pz;
            int all_in, any_in;
            if (depth[i] <= 0 || normal[3 * i + 1] < 0.99) continue;   /* sky, or not the floor */
            for (j = 0; j < 3; j++)
                p[j] = check_d((&v.eye.x)[j]) +
                       (check_d((&v.forward.x)[j]) + ky * check_d((&v.up.x)[j]) + kx * check_d((&v.right.x)[j])) * depth[i];
            if (fabs(p[1]) > 0.01) continue;                             /* the box's top */
            px = p[0] - ox;
            pz = p[2] - oz;
            all_in = in_box_shadow(px - 0.1, pz - 0.1) && in_box_shadow(px + 0.1, pz - 0.1) &&
                     in_box_shadow(px - 0.1, pz + 0.1) && in_box_shadow(px + 0.1, pz + 0.1);
            any_in = in_box_shadow(px - 0.1, pz - 0.1) || in_box_shadow(px + 0.1, pz - 0.1) ||
                     in_box_shadow(px - 0.1, pz + 0.1) || in_box_shadow(px + 0.1, pz + 0.1);
            if (all_in) shadowed++, bad += e[3 * i] >= 0.1 * lit;
            else if (!any_in) open++, bad += e[3 * i] <= 0.9 * lit;
        }
    CHECK(lit > 0 && shadowed >= 20 && open >= 1000, "%s: %d pixels in the shadow, %d outside", what, shadowed, open);
    CHECK(bad == 0, "%s: %d floor pixels lit against the geometry", what, bad);
    free(e); free(depth); free(normal);
}
static void check_box_shadow(const rendered *r, int offset, const char *what) { check_box_shadow_at(r, offset, offset, what); }

/* One map for a ground plane that runs far past the box spends its texels
 * on the distant floor: the auto choice takes shadow rays there
 * (tgi_shadow_map_coarse), and the box's shadow is where the geometry puts
 * it (check_box_shadow).  With one map (the choice before) the +-200
 * plane's shadow was blotchy and partly missing (PSNR 35 dB against rays).
 * A +-5 plane keeps its map (not coarse). */
TEST(one_map_too_coarse_takes_rays)
{
    static const int halves[2] = { 5, 200 };
    char text[1024], what[64];
    int k;
    for (k = 0; k < 2; k++) {
        const int w = 160, h = 120;
        rendered r, maps;
        tg_request q = request(w, h, AOVBIT(TG_AOV_DIRECT) | AOVBIT(TG_AOV_DEPTH) | AOVBIT(TG_AOV_NORMAL));
        const tgi_scene_camera *c;
        tgi_shadow_need nd;
        tgi_view v;
        int coarse;
        box_on_ground(halves[k], 0, text, sizeof text);
        if (!set_up_maps(&maps, text, q)) continue;
        c = &maps.scene->camera;
        tgi_view_make(&v, c->pos, c->target, c->up, c->fov, c->znear, c->zfar, w, h);
        plan_need(maps.scene, 0, w, h, 0, &nd);
        coarse = tgi_shadow_map_coarse(&nd, &maps.scene->lights[0], &v, maps.scene->bounds_min, maps.scene->bounds_max,
                                       maps.scene->tri_pos, maps.scene->tri_count);
        CHECK(coarse == (halves[k] == 200), "+-%d plane: one map coarse %d", halves[k], coarse);
        teardown(&maps);
        if (!setup_checked(&r, text, &q, "box on the ground") || tg_frame_render(r.frame, 0, NULL) != TG_OK) {
            CHECK(0, "%s", r.msg);
            continue;
        }
        CHECK((r.frame->shadow_maps[0].ray != NULL) == (halves[k] == 200), "+-%d plane: rays %d", halves[k],
              r.frame->shadow_maps[0].ray != NULL);
        snprintf(what, sizeof what, "+-%d plane", halves[k]);
        check_box_shadow(&r, 0, what);
        teardown(&r);
    }
}

/* The same +-10 scene 0 to 2000 units from the origin, with a shadow map:
 * the box's shadow where the geometry puts it.  A lookup placed its texel
 * as (p.r - cx) s and the depth raster as the rows r s and -cx s, whose
 * roundings differ by |p| 2^-17 in NDC: a few texels at 1000 units, and in
 * Q16.16 the lit floor came out shadowed from about 400 on (a hard-case
 * probe: 54112 of 54176 pixels at 1000). */
TEST(ortho_map_far_from_the_origin)
{
    static const int offsets[3] = { 0, 1000, 2000 };
    char text[1024], what[64];
    int k;
    for (k = 0; k < 3; k++) {
        rendered r;
        tg_request q = request(160, 120, AOVBIT(TG_AOV_DIRECT) | AOVBIT(TG_AOV_DEPTH) | AOVBIT(TG_AOV_NORMAL));
        box_on_ground(10, offsets[k], text, sizeof text);
        if (!set_up_maps(&r, text, q)) continue;
        if (tg_frame_render(r.frame, 0, NULL) != TG_OK) {
            CHECK(0, "%s", r.msg);
            teardown(&r);
            continue;
        }
        CHECK(r.frame->shadow_maps[0].ray == NULL, "offset %d: a map", offsets[k]);
        snprintf(what, sizeof what, "+-10 plane at %d, map", offsets[k]);
        check_box_shadow(&r, offsets[k], what);
        teardown(&r);
    }
}

/* The same +-10 scene with the default shadows, up to 30000 units from the
 * origin on one axis and 20000 on two: the box's shadow where the geometry
 * puts it in both number types.  In Q16.16 the size rule's sums lo + hi and
 * a triangle's three corners saturated past 16384 (10922) units (the
 * ground measured about x = 16384, its light-plane area 0: an 8-texel map,
 * its shadow anywhere), and so did the map's window centre (minx + maxx);
 * on two axes at 20000 a map's light-plane coordinates (up to |p|_1)
 * are past Q16.16's range and the plan takes rays. */
TEST(default_shadows_far_out)
{
    static const int at[][2] = { { 30000, 0 }, { 0, 30000 }, { -30000, 0 }, { 15000, 15000 }, { 20000, 20000 } };
    char text[1024], what[64];
    size_t k;
    for (k = 0; k < sizeof at / sizeof at[0]; k++) {
        rendered r;
        tg_request q = request(160, 120, AOVBIT(TG_AOV_DIRECT) | AOVBIT(TG_AOV_DEPTH) | AOVBIT(TG_AOV_NORMAL));
        box_on_ground_at(10, at[k][0], at[k][1], text, sizeof text);
        if (!setup_checked(&r, text, &q, "box on the ground, far out") || tg_frame_render(r.frame, 0, NULL) != TG_OK) {
            CHECK(0, "%s", r.msg);
            continue;
        }
        if (at[k][0] == 0 || at[k][1] == 0)   /* one axis: a map, of the size it has at the origin */
            CHECK(r.frame->shadow_maps[0].ray == NULL && r.frame->shadow_maps[0].face[0].size > 128,
                  "(%d, %d): rays %d, a map of %d texels", at[k][0], at[k][1], r.frame->shadow_maps[0].ray != NULL,
                  r.frame->shadow_maps[0].face[0].size);
        snprintf(what, sizeof what, "+-10 plane at (%d, %d), default shadows", at[k][0], at[k][1]);
        check_box_shadow_at(&r, at[k][0], at[k][1], what);
        teardown(&r);
    }
}

/* Shadow rays on the same +-10 scene far from the origin: the ray starts
 * off the surface by 2^-14 of the scene's extent in Q16.16 (its unit
 * normals' 16 bits, its coordinates' fixed step) and 2^-19 of the point's
 * coordinates in float, so both keep the box's shadow at 20000 (2^-14 of
 * the coordinates put the start 2.4 units up, over the 2-unit box: no
 * shadow, PSNR 19.4 dB against the map). */
TEST(rays_far_from_the_origin)
{
    static const int offsets[4] = { 0, 1000, 2000, 20000 };
    char text[1024], what[64];
    int k;
    for (k = 0; k < 4; k++) {
        rendered r;
        tg_request q = request(160, 120, AOVBIT(TG_AOV_DIRECT) | AOVBIT(TG_AOV_DEPTH) | AOVBIT(TG_AOV_NORMAL));
        q.shadow_method = TG_SHADOWS_RAYS;
        box_on_ground(10, offsets[k], text, sizeof text);
        if (!setup_checked(&r, text, &q, "box on the ground, rays") || tg_frame_render(r.frame, 0, NULL) != TG_OK) {
            CHECK(0, "%s", r.msg);
            continue;
        }
        snprintf(what, sizeof what, "+-10 plane at %d, rays", offsets[k]);
        check_box_shadow(&r, offsets[k], what);
        teardown(&r);
    }
}

TEST(ceiling_round_the_lamp_is_lit)
{
    static const int sizes[][2] = { { 40, 30 }, { 160, 120 }, { 320, 240 } };
    size_t k;
    for (k = 0; k < 3; k++) {
        int w = sizes[k][0], h = sizes[k][1];
        CHECK(check_ceiling(w, h, TG_SHADOWS_AUTO, 0, "default") > 0, "%dx%d: ceiling pixels found", w, h);
        check_ceiling(w, h, TG_SHADOWS_MAPS, 0, "maps, tent");
        check_ceiling(w, h, TG_SHADOWS_MAPS, 1, "maps, bilinear");
        check_ceiling(w, h, TG_SHADOWS_RAYS, 0, "rays");
    }
}

/* Shadow rays and 2048-texel maps give the same direct light but for the
 * pixels along shadow edges: at 160x120 fewer than 1% of the lit pixels
 * differ by more than half, and the mean |dE| is under 1% of the mean E. */
TEST(rays_match_fine_maps)
{
    rendered ra, rm;
    double *a = cornell_direct(160, 120, TG_SHADOWS_RAYS, 0, 0, &ra, NULL, NULL);
    double *b = cornell_direct(160, 120, TG_SHADOWS_MAPS, 2048, 0, &rm, NULL, NULL);
    double de = 0, sum = 0;
    int i, off = 0, lit = 0;
    if (a && b) {
        for (i = 0; i < 160 * 120; i++) {
            double ea = a[3 * i] + a[3 * i + 1] + a[3 * i + 2], eb = b[3 * i] + b[3 * i + 1] + b[3 * i + 2];
            de += fabs(ea - eb);
            sum += ea;
            lit += ea > 0 || eb > 0;
            off += fabs(ea - eb) > 0.5 * fmax(ea, eb);
        }
        CHECK(off <= lit / 100, "%d of %d lit pixels differ by more than half", off, lit);
        CHECK(de <= 0.01 * sum, "mean |dE| / mean E = %.4f", de / sum);
    }
    free(a); free(b);
    if (a) teardown(&ra);
    if (b) teardown(&rm);
}

/* Views the plan cannot know (the game loop's cameras) or lookups off
 * screen (the reference) need every face, whole. */
TEST(unknown_views_need_every_face)
{
    int k;
    for (k = 0; k < 2; k++) {
        rendered r;
        tg_request q = request(64, 48, AOVBIT(TG_AOV_COLOR));
        int f;
        if (k == 0) q.game_loop = 1;
        else q.technique = TG_TECH_REFERENCE;
        if (!set_up_maps(&r, tg_builtin_scene("cornell"), q)) continue;
        for (f = 0; f < 6; f++) {
            CHECK(r.frame->shadow_maps[0].face[f].size > 0, "%s: face %d absent", k ? "reference" : "game loop", f);
            CHECK(!r.frame->shadow_maps[0].need.window_set[f], "%s: face %d windowed", k ? "reference" : "game loop", f);
        }
        teardown(&r);
    }
}

/* The reference pays for a BVH anyway: when the maps (every face whole,
 * the sun's over the whole bounds) would not fit, its shadows are rays
 * against that BVH, carved once. */
TEST(reference_traces_its_own_bvh)
{
    rendered r;
    tg_request q = request(80, 60, AOVBIT(TG_AOV_COLOR));
    q.technique = TG_TECH_REFERENCE;
    if (!setup(&r, tg_builtin_scene("spheres"), &q)) { CHECK(0, "%s", r.msg); return; }
    CHECK(r.frame->shadow_maps[0].ray != NULL, "rays");
    CHECK(buffer_bytes(&r.plan, "shadow maps (depth)") == 0 && buffer_bytes(&r.plan, "shadow rays: BVH") == 0,
          "no map, no second BVH");
    CHECK(buffer_bytes(&r.plan, "reference BVH") > 0, "the reference's BVH");
    CHECK(tg_frame_render(r.frame, 0, NULL) == TG_OK, "render");
    teardown(&r);
}

int main(void)
{
    RUN(plan_sizes_are_the_rule);
    RUN(default_maps_fit_in_eight_bytes_a_pixel);
    RUN(lights_share_the_maps_budget);
    RUN(culled_faces_take_no_memory);
    RUN(plan_chooses_as_the_rule_says);
    RUN(one_map_too_coarse_takes_rays);
    RUN(ortho_map_far_from_the_origin);
    RUN(rays_far_from_the_origin);
    RUN(default_shadows_far_out);
    RUN(ceiling_round_the_lamp_is_lit);
    RUN(rays_match_fine_maps);
    RUN(unknown_views_need_every_face);
    RUN(reference_traces_its_own_bvh);
    return check_summary();
}
