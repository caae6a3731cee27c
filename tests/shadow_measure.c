/* SPDX-License-Identifier: MIT */
/*
 * shadow_measure.c - direct light of a built-in scene with each shadow
 * method, against hard BVH shadow rays: memory, accuracy and (under
 * callgrind) instructions.  Not a test; built and run by hand:
 *
 *   make build/libtinygi.a
 *   cc -O2 -std=c99 -Isrc -Itests tests/shadow_measure.c build/libtinygi.a -lm -o build/shadow_measure
 *   build/shadow_measure cornell 320x240             every method, one table row each
 *   build/shadow_measure cornell 320x240 rule16-tent only one method (for callgrind:
 *       valgrind --tool=callgrind build/shadow_measure cornell 320x240 rule16-tent, then
 *       callgrind_annotate --inclusive=yes: tgi_direct_rows / pixels, and the set-up)
 *   (TG_FIXED=1 and build/libtinygi-fixed.a for Q16.16)
 *
 * The reference is rays, or the method SHADOW_MEASURE_REF names (e.g.
 * SHADOW_MEASURE_REF=map32-512-tent: 16 against 32 bits).  SHADOW_MEASURE_PGM=DIR
 * writes each method's visibility error and the reference's visibility as
 * DIR/METHOD.pgm.
 * Methods: none (no shadows), rays (tgi_bvh_light_visibility: the
 * reference), map32-N / map16-N (every face N texels, 32 or 16 bits),
 * rule16 (16 bits, sizes and faces by tgi_shadow_map_size_rule), plan
 * (the frame's default maps: tgi_shadow_plan, the rule raised within the
 * budget), each with -tent or -bilinear PCF.  Per row: the map's faces and bytes (the
 * BVH's for rays), bytes per image pixel, and against the rays over the
 * pixels a shadowed light faces: wrong = |visibility - rays'| > 0.5 (lit
 * taken for shadowed or the reverse), mean |visibility - rays'|,
 * mean |E - E_rays| / mean E_rays (E_direct, every light), and the largest
 * |visibility - rays'|.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include "tinygi.h"
#include "scene/scene.h"
#include "raster/raster.h"
#include "light/direct.h"
#include "light/shadowmap.h"
#include "light/shadowview.h"
#include "ao/bvh.h"
#include "storage_fixture.h"

typedef struct method { const char *name; int kind, bits, size, filter; double scale; } method;
enum { NONE, RAYS, MAP, RULE, PLAN };

static int parse_method(const char *s, method *m)
{
    const char *dash = strrchr(s, '-');
    memset(m, 0, sizeof *m);
    m->name = s;
    m->filter = dash && !strcmp(dash, "-bilinear") ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT;
    if (!strcmp(s, "none")) { m->kind = NONE; return 1; }
    if (!strcmp(s, "rays")) { m->kind = RAYS; return 1; }
    if (!strncmp(s, "plan", 4)) { m->kind = PLAN; m->bits = 16; return 1; }
    if (!strncmp(s, "rule16", 6)) {   /* rule16xK: the rule's densities times K */
        m->kind = RULE; m->bits = 16; m->scale = 1;
        if (s[6] == 'x') m->scale = atof(s + 7);
        return m->scale > 0;
    }
    if (sscanf(s, "map%d-%d", &m->bits, &m->size) == 2 && (m->bits == 16 || m->bits == 32)) {
        m->kind = MAP;
        return 1;
    }
    return 0;
}

typedef struct frame_in {
    tg_scene *scene;
    tgi_view view;
    tgi_gbuffer gb;
    tgi_bvh bvh;
    size_t bvh_bytes;
    int w, h;
} frame_in;

static void *xmalloc(size_t n)
{
    void *p = calloc(1, n ? n : 1);
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

static void frame_make(frame_in *fi, const char *name, int w, int h)
{
    static tg_arena arena;
    size_t n = (size_t)w * (size_t)h, arena_size = (size_t)256 << 20;
    const char *text = tg_builtin_scene(name);
    tg_error err;
    tgi_raster_mesh mesh;
    const tgi_scene_camera *c;
    memset(fi, 0, sizeof *fi);
    if (!text) { fprintf(stderr, "no built-in scene '%s'\n", name); exit(2); }
    tg_arena_init(&arena, xmalloc(arena_size), arena_size);
    if (tg_scene_parse(text, strlen(text), name, NULL, &arena, &fi->scene, &err) != TG_OK) {
        fprintf(stderr, "%s: %s\n", name, err.message);
        exit(2);
    }
    c = &fi->scene->camera;
    fi->w = w; fi->h = h;
    tgi_view_make(&fi->view, c->pos, c->target, c->up, c->fov, c->znear, c->zfar, w, h);
    (void)n;
    sf_gbuffer_alloc(&fi->gb, w, h, fi->scene->materials, fi->scene->material_count);
    mesh.pos = fi->scene->tri_pos; mesh.nrm = fi->scene->tri_nrm;
    mesh.tri_material = fi->scene->tri_material; mesh.tri_object = fi->scene->tri_object;
    mesh.tri_count = fi->scene->tri_count; mesh.materials = fi->scene->materials;
    tgi_gbuffer_clear_rows(&fi->gb, 0, h);
    tgi_raster_gbuffer(&fi->gb, &fi->view, &mesh, 0, h);
}

static void bvh_make(frame_in *fi)
{
    fi->bvh_bytes = tgi_bvh_bytes(fi->scene->tri_count);
    if (tgi_bvh_build(&fi->bvh, fi->scene->tri_pos, fi->scene->tri_count, xmalloc(fi->bvh_bytes), fi->bvh_bytes)) {
        fprintf(stderr, "bvh\n");
        exit(2);
    }
}

/* The shadows of every shadowed light by method m; returns their bytes. */
static size_t shadows_make(const frame_in *fi, const method *m, tgi_shadow_map *sm, const tgi_shadow_map **ptr,
                           char *faces, size_t faces_size)
{
    const tg_scene *s = fi->scene;
    size_t total = 0;
    int i, f;
    faces[0] = 0;
    for (i = 0; i < s->light_count; i++) {
        const tgi_light *l = &s->lights[i];
        tgi_shadow_need nd;
        size_t bytes;
        ptr[i] = NULL;
        if (!l->shadows || m->kind == NONE) continue;
        ptr[i] = &sm[i];
        if (m->kind == RAYS) {
            tgi_shadow_rays_setup(&sm[i], l, tgi_bvh_light_visibility, &fi->bvh);
            total += fi->bvh_bytes;
            snprintf(faces + strlen(faces), faces_size - strlen(faces), "%d tris ", s->tri_count);
            continue;
        }
        tgi_shadow_need_init(&nd, l);
        nd.depth_bits = m->bits;
        if (m->kind == PLAN) {   /* the frame's: tgi_shadow_plan, maps forced */
            tg_request q;
            tg_vec3 lo, hi;
            tg_request_defaults(&q);
            q.width = fi->w; q.height = fi->h;
            q.shadow_method = TG_SHADOWS_MAPS;
            tgi_shadow_plan(s, &q, i, 0, &nd, &lo, &hi);
        } else if (m->kind == RULE) {
            tgi_shadow_map_size_rule(&nd, l, &fi->view, s->bounds_min, s->bounds_max, s->tri_pos, s->tri_count);
            for (f = 0; f < nd.faces; f++) nd.density[f] = tg_mul(nd.density[f], tg_from_float((float)m->scale));
            tgi_shadow_need_finish(&nd, 0);
        } else {
            tgi_shadow_need_all(&nd);
            tgi_shadow_need_finish(&nd, m->size);
        }
        bytes = tgi_shadow_need_bytes(&nd);
        tgi_shadow_map_setup_need(&sm[i], l, &nd, s->bounds_min, s->bounds_max, xmalloc(bytes));
        sm[i].filter = m->filter;
        tgi_shadow_map_render(&sm[i], s->tri_pos, s->tri_count);
        total += bytes;
        for (f = 0; f < nd.faces; f++)
            snprintf(faces + strlen(faces), faces_size - strlen(faces), "%d%s", nd.size[f], f + 1 < nd.faces ? "," : " ");
    }
    return total;
}

/* E_direct (3 planes) for the frame with these shadows. */
static tg_real *direct(const frame_in *fi, const tgi_shadow_map *const *ptr)
{
    size_t n = (size_t)fi->w * (size_t)fi->h;
    tg_real *e = (tg_real *)xmalloc(3 * n * sizeof(tg_real));
    tgi_gview gv = sf_view(&fi->gb, &fi->view);
    tgi_rgb er;
    sf_rgb_alloc(&er, n);
    tgi_direct_rows(&gv, fi->scene->lights, fi->scene->light_count, ptr, &er, 0, fi->h);
    sf_rgb_read(&er, n, e, e + n, e + 2 * n);
    sf_rgb_free(&er);
    return e;
}

static double lum(const tg_real *e, size_t n, size_t i)
{
    return tg_to_float(e[i]) + tg_to_float(e[n + i]) + tg_to_float(e[2 * n + i]);
}

static void row(const frame_in *fi, const method *m, const tg_real *e_none, const tg_real *e_rays, int print)
{
    tgi_shadow_map *sm = (tgi_shadow_map *)xmalloc(sizeof(tgi_shadow_map) * (size_t)fi->scene->light_count);
    const tgi_shadow_map **ptr = (const tgi_shadow_map **)xmalloc(sizeof(void *) * (size_t)fi->scene->light_count);
    size_t n = (size_t)fi->w * (size_t)fi->h, i, facing = 0, wrong = 0;
    char faces[128];
    size_t bytes = shadows_make(fi, m, sm, ptr, faces, sizeof faces);
    tg_real *e = direct(fi, ptr);
    double dvis = 0, de = 0, eref = 0, dmax = 0;
    if (getenv("SHADOW_MEASURE_PGM") && e_rays) {   /* visibility and its error as images */
        char path[256];
        FILE *fp;
        snprintf(path, sizeof path, "%s/%s.pgm", getenv("SHADOW_MEASURE_PGM"), m->name);
        fp = fopen(path, "wb");
        if (fp) {   /* left: error 0.5 + (vis - rays' vis) / 2; right: rays' visibility */
            size_t y, x, j;
            fprintf(fp, "P5 %d %d 255\n", fi->w * 2, fi->h);
            for (y = 0; y < (size_t)fi->h; y++)
                for (j = 0; j < 2; j++)
                    for (x = 0; x < (size_t)fi->w; x++) {
                        size_t k = y * (size_t)fi->w + x;
                        double u = lum(e_none, n, k), v = 0;
                        if (u > 0) v = j ? lum(e_rays, n, k) / u : 0.5 + 0.5 * (lum(e, n, k) - lum(e_rays, n, k)) / u;
                        fputc((int)(255 * (v < 0 ? 0 : v > 1 ? 1 : v)), fp);
                    }
            fclose(fp);
        }
    }
    if (!print || !e_rays) { free(e); return; }
    for (i = 0; i < n; i++) {
        double u = lum(e_none, n, i), r = lum(e_rays, n, i), x = lum(e, n, i);
        if (fi->gb.depth[i] == 0 || u <= 0) continue;
        facing++;
        if (fabs(x / u - r / u) > 0.5) wrong++;
        dvis += fabs(x / u - r / u);
        if (fabs(x / u - r / u) > dmax) dmax = fabs(x / u - r / u);
        de += fabs(x - r);
        eref += r;
    }
    printf("| %-18s | %-26s | %9zu | %6.2f | %6.3f%% | %.2e | %.2e | %.3f |\n", m->name, faces, bytes,
           (double)bytes / (double)n, 100.0 * (double)wrong / (double)(facing ? facing : 1),
           dvis / (double)(facing ? facing : 1), de / (eref > 0 ? eref : 1), dmax);
    free(e);
}

int main(int argc, char **argv)
{
    static const char *const all_default[] = { "none", "rays", "map32-512-tent", "map16-512-tent", "map32-512-bilinear",
                                       "rule16-tent", "rule16-bilinear", "plan-tent", "plan-bilinear", "map16-64-tent", NULL };
    const char *const *all = all_default;
    const char *list[64];
    frame_in fi;
    method m;
    int w = 320, h = 240, k;
    tg_real *e_none, *e_rays;
    if (argc < 2) { fprintf(stderr, "usage: %s SCENE [WxH] [METHOD]\n", argv[0]); return 2; }
    if (argc > 2 && sscanf(argv[2], "%dx%d", &w, &h) != 2) { fprintf(stderr, "size WxH\n"); return 2; }
    frame_make(&fi, argv[1], w, h);
    if (argc > 4) {   /* a list of methods, all measured */
        for (k = 3; k < argc && k - 3 < 62; k++) list[k - 3] = argv[k];
        list[k - 3] = NULL;
        all = list;
    } else if (argc > 3) {   /* one method alone (callgrind) */
        if (!parse_method(argv[3], &m)) { fprintf(stderr, "unknown method %s\n", argv[3]); return 2; }
        if (m.kind == RAYS) bvh_make(&fi);
        row(&fi, &m, NULL, NULL, 0);
        return 0;
    }
    bvh_make(&fi);
    parse_method("none", &m);
    e_none = direct(&fi, NULL);
    {
        tgi_shadow_map *sm = (tgi_shadow_map *)xmalloc(sizeof(tgi_shadow_map) * (size_t)fi.scene->light_count);
        const tgi_shadow_map **ptr = (const tgi_shadow_map **)xmalloc(sizeof(void *) * (size_t)fi.scene->light_count);
        char faces[128];
        /* the reference: rays, or SHADOW_MEASURE_REF (e.g. map32-512-tent against map16-512-tent) */
        if (!getenv("SHADOW_MEASURE_REF") || !parse_method(getenv("SHADOW_MEASURE_REF"), &m)) parse_method("rays", &m);
        shadows_make(&fi, &m, sm, ptr, faces, sizeof faces);
        e_rays = direct(&fi, ptr);
    }
    printf("%s %dx%d %s, %d triangles, against %s\n\n", argv[1], w, h, TG_NUMBER_NAME, fi.scene->tri_count, m.name);
    printf("| method | faces (texels per side) | bytes | B/px | wrong | mean dvis | mean dE/E | max dvis |\n");
    printf("| --- | --- | --- | --- | --- | --- | --- | --- |\n");
    for (k = 0; all[k]; k++) {
        parse_method(all[k], &m);
        row(&fi, &m, e_none, e_rays, 1);
    }
    return 0;
}
