/* SPDX-License-Identifier: MIT */
/*
 * test_shadow.c - shadow maps against ray-traced visibility, on G-buffers
 * from the real rasterizer (the positions the direct pass reconstructs
 * carry the rasterizer's sub-pixel snapping, which is what used to put
 * grazing surfaces in their own shadow):
 *   - a surface facing an unoccluded light is lit, and its irradiance is the
 *     analytic one, at every image size from 40x30 to 640x480 and every map
 *     size, at grazing incidence (a ceiling 1% of the room's height above a
 *     point light; a wall lit at 85 degrees), with both PCF filters;
 *   - occluders still shadow: a box on a floor under point, spot and
 *     directional lights; receivers at 87-89 degrees; geometry crossing the
 *     light's near plane and lying behind the light;
 *   - the map's byte count is overflow-checked.
 * Visibility is decided by BVH shadow rays from the reconstructed position:
 * "surely lit" when the light is visible from the position and from points
 * around it on its tangent plane (farther than the PCF footprint and the
 * position error), "surely shadowed" when it is blocked from all of them.
 */
#include "raster_fixture.h"
#include "light/direct.h"
#include "light/shadowmap.h"

/* Outputs: E with shadows (0-2), E without (3-5). */
#define E_R(im) ((im)->out[0])
#define U_R(im) ((im)->out[3])

#define RAYS 0   /* image_light's size for ray-cast shadows (tgi_bvh_light_visibility) */

/* E with the light's shadow map (size, filter) or shadow rays (size RAYS),
 * and E without shadows. */
static void image_light(image *im, const geo *g, const tgi_light *l, int size, int filter)
{
    tgi_shadow_map sm;
    const tgi_shadow_map *maps[1];
    size_t bytes = size == RAYS ? 1 : tgi_shadow_map_bytes(l, size);
    void *mem = malloc(bytes);
    if (!mem) { fprintf(stderr, "out of memory\n"); exit(2); }
    if (size == RAYS) {
        tgi_shadow_rays_setup(&sm, l, tgi_bvh_light_visibility, &bvh);
    } else {
        tgi_shadow_map_setup(&sm, l, size, v3(g->lo[0], g->lo[1], g->lo[2]), v3(g->hi[0], g->hi[1], g->hi[2]), mem);
        sm.filter = filter;
        tgi_shadow_map_render(&sm, g->pos, g->n);
    }
    im->texel_world = dv(sm.texel_world);
    maps[0] = &sm;
    image_direct(im, l, 1, maps, 0);
    image_direct(im, l, 1, NULL, 3);
    free(mem);
}

static const char *method_name(int size, int filter)
{
    return size == RAYS ? "rays" : filter ? "bilinear" : "tent";
}

/* Unit vector from p toward the light, its distance (1e6 for a directional light). */
static double to_light(const tgi_light *l, const double p[3], double d[3])
{
    double len;
    if (l->type == TG_LIGHT_DIRECTIONAL) {
        d[0] = -dv(l->dir.x); d[1] = -dv(l->dir.y); d[2] = -dv(l->dir.z);
        len = sqrt(dot3(d, d));
        d[0] /= len; d[1] /= len; d[2] /= len;
        return 1e6;
    }
    d[0] = dv(l->pos.x) - p[0]; d[1] = dv(l->pos.y) - p[1]; d[2] = dv(l->pos.z) - p[2];
    len = sqrt(dot3(d, d));
    d[0] /= len; d[1] /= len; d[2] /= len;
    return len;
}

static int ray_blocked(const tgi_light *l, const double q[3])
{
    double d[3], dist = to_light(l, q, d);
    if (dist > 1e5) dist = 1e3;
    return tgi_bvh_occluded(&bvh, v3(q[0], q[1], q[2]), v3(d[0], d[1], d[2]), rv(dist * (1 - 1e-4)));
}

enum { SURELY_LIT, SURELY_SHADOWED, PENUMBRA };

/* BVH visibility of the light from p and from a 5x5 grid of points around
 * it on its tangent plane, +-`along` the light's direction projected on the
 * plane (where a texel is stretched by 1 / cos), +-`across` perpendicular. */
static int classify(const tgi_light *l, const double p[3], const double n[3], double lift,
                    double along, double across)
{
    double d[3], u[3], w[3], len;
    int k, blocked = 0;
    to_light(l, p, d);
    for (k = 0; k < 3; k++) u[k] = d[k] - n[k] * dot3(n, d);
    len = sqrt(dot3(u, u));
    if (len < 1e-9) { u[0] = n[1]; u[1] = n[2]; u[2] = n[0]; len = 1; } /* any tangent */
    for (k = 0; k < 3; k++) u[k] /= len;
    w[0] = n[1] * u[2] - n[2] * u[1]; w[1] = n[2] * u[0] - n[0] * u[2]; w[2] = n[0] * u[1] - n[1] * u[0];
    for (k = 0; k < 25; k++) {
        double a = (k % 5 - 2) * 0.5 * along, b = (k / 5 - 2) * 0.5 * across, q[3];
        int c;
        for (c = 0; c < 3; c++) q[c] = p[c] + n[c] * lift + u[c] * a + w[c] * b;
        blocked += ray_blocked(l, q);
        if (blocked && blocked <= k) return PENUMBRA;
    }
    return blocked == 0 ? SURELY_LIT : SURELY_SHADOWED;
}

typedef struct tally { int lit, shadowed, penumbra, zero; double worst_lit, worst_shadowed; } tally;

/* Compare every pixel that faces the light with the BVH: surely lit ->
 * E >= 98% of unshadowed, surely shadowed -> E <= 2%; always 0 <= E <= unshadowed. */
static tally check_visibility(const image *im, const tgi_light *l, const char *what, int occluders)
{
    tally t = { 0, 0, 0, 0, 1, 0 };
    /* about 5000 pixels at most: every pixel of the small images, a
     * stride coprime with the width on the large ones */
    int i, stride = im->w * im->h / 5000 + 1;
    while (stride > 1 && im->w % stride == 0) stride++;
    for (i = 0; i < im->w * im->h; i += stride) {
        double p[3], n[3], d[3], dist, cosl, footprint, texel, along, across, lift, e, u;
        int c;
        if (im->sky[i]) continue;
        pixel_pos(im, i, p, n);
        dist = to_light(l, p, d);
        cosl = dot3(n, d);
        u = dv(U_R(im)[i]); e = dv(E_R(im)[i]);
        CHECK(e >= 0 && e <= u * (1 + 1e-4) + 1e-6, "%s: E %g outside [0, unshadowed %g]", what, e, u);
        if (cosl < 0.01 || u <= 0) continue;
        footprint = dv(im->depth[i]) / dv(im->view.pixels_per_unit);
        texel = l->type == TG_LIGHT_DIRECTIONAL ? im->texel_world : im->texel_world * dist;
        lift = 0.1 * footprint + 1e-3;
        across = 2.5 * texel + 2 * footprint + 0.005;
        along = (2.5 * texel + lift) / (cosl > 0.01 ? cosl : 0.01) + 2 * footprint + 0.005;
        c = classify(l, p, n, lift, along, across);
        if (c == SURELY_SHADOWED && !occluders) c = PENUMBRA; /* a room's corner: its walls block the offsets */
        if (c == SURELY_LIT) {
            t.lit++;
            if (e == 0) t.zero++;
            if (e / u < t.worst_lit) t.worst_lit = e / u;
            CHECK(e >= 0.98 * u, "%s: surely lit pixel %d,%d at (%.3f %.3f %.3f) gets %.3f of its light",
                  what, i % im->w, i / im->w, p[0], p[1], p[2], e / u);
        } else if (c == SURELY_SHADOWED) {
            t.shadowed++;
            if (e / u > t.worst_shadowed) t.worst_shadowed = e / u;
            CHECK(e <= 0.02 * u, "%s: surely shadowed pixel %d,%d at (%.3f %.3f %.3f) gets %.3f of its light",
                  what, i % im->w, i / im->w, p[0], p[1], p[2], e / u);
        } else {
            t.penumbra++;
        }
    }
    return t;
}

static const int sizes[][2] = { { 40, 30 }, { 80, 60 }, { 160, 120 }, { 320, 240 }, { 640, 480 } };
#define SIZE_COUNT ((int)(sizeof sizes / sizeof sizes[0]))
static const int map_sizes[] = { TG_MIN_SHADOW_MAP, 64, 149, 512, 2048 };
#define MAP_COUNT ((int)(sizeof map_sizes / sizeof map_sizes[0]))

/* ---- a surface facing the light with nothing between is lit ---- */

/* The room x, z in [-2.5, 2.5] x [0, 5], y in [0, 2.5], open toward -z,
 * empty: every surface faces the light and nothing is between. */
static void empty_room(geo *g)
{
    static const double lo[3] = { -2.5, 0, 0 }, hi[3] = { 2.5, 2.5, 5 };
    memset(g, 0, sizeof *g);
    box(g, lo, hi, 4); /* no wall at z = 0 */
}

/* Analytic irradiance of a point light at the exact surface point the pixel
 * ray meets in the room (the ceiling y = 2.5, walls, floor), and the distance
 * from that point to the reconstructed one. */
static double room_exact_irradiance(const image *im, const tgi_light *l, int i, const double prec[3],
                                    const double nrec[3], double *err)
{
    double o[3] = { dv(im->view.eye.x), dv(im->view.eye.y), dv(im->view.eye.z) }, d[3], t = 1e30, p[3], n[3] = { 0, 0, 0 };
    static const double lo[3] = { -2.5, 0, 0 }, hi[3] = { 2.5, 2.5, 5 };
    double kx = (i % im->w + 0.5 - im->w / 2.0) / dv(im->view.pixels_per_unit);
    double ky = (im->h / 2.0 - (i / im->w + 0.5)) / dv(im->view.pixels_per_unit), L[3], r2, cosine;
    int a, best = -1;
    d[0] = dv(im->view.forward.x) + ky * dv(im->view.up.x) + kx * dv(im->view.right.x);
    d[1] = dv(im->view.forward.y) + ky * dv(im->view.up.y) + kx * dv(im->view.right.y);
    d[2] = dv(im->view.forward.z) + ky * dv(im->view.up.z) + kx * dv(im->view.right.z);
    for (a = 0; a < 3; a++) {   /* from inside (or in front of the open side): the exit face */
        double bound = d[a] > 0 ? hi[a] : lo[a], ta;
        if (fabs(d[a]) < 1e-12 || (a == 2 && d[a] < 0)) continue;
        ta = (bound - o[a]) / d[a];
        if (ta > 0 && ta < t) { t = ta; best = a; }
    }
    if (best < 0) return -1;
    n[best] = d[best] > 0 ? -1 : 1;
    if (dot3(n, nrec) < 0.99) return -1;   /* an edge pixel the raster gave the other face */
    for (a = 0; a < 3; a++) p[a] = o[a] + t * d[a];
    *err = sqrt((p[0] - prec[0]) * (p[0] - prec[0]) + (p[1] - prec[1]) * (p[1] - prec[1]) + (p[2] - prec[2]) * (p[2] - prec[2]));
    L[0] = dv(l->pos.x) - p[0]; L[1] = dv(l->pos.y) - p[1]; L[2] = dv(l->pos.z) - p[2];
    r2 = dot3(L, L);
    cosine = dot3(n, L) / sqrt(r2);
    return cosine > 0 ? dv(l->intensity) * cosine / r2 : 0;
}

/* Every pixel that faces the light and sees it (a BVH shadow ray) gets
 * E > 0; the surely lit ones (farther from the room's edges than the PCF
 * footprint) get >= 98% of the unshadowed E, and E matches the analytic
 * irradiance at the exact point within what the reconstructed position's
 * error allows. */
static void lit_check(const image *im, const tgi_light *l, const char *what, int analytic, int min_lit)
{
    tally t = check_visibility(im, l, what, 0);
    int i, visible = 0, facing = 0;
    CHECK(t.shadowed == 0, "%s: %d pixels surely shadowed", what, t.shadowed);
    CHECK(t.lit >= min_lit, "%s: %d pixels surely lit", what, t.lit);
    for (i = 0; i < im->w * im->h; i++) {
        double p[3], n[3], d[3], q[3], lift, e = dv(E_R(im)[i]);
        int c;
        if (im->sky[i]) continue;
        pixel_pos(im, i, p, n);
        to_light(l, p, d);
        if (dot3(n, d) < 0.01) continue;
        facing++;
        lift = 0.1 * dv(im->depth[i]) / dv(im->view.pixels_per_unit) + 1e-3;
        for (c = 0; c < 3; c++) q[c] = p[c] + n[c] * lift;
        if (ray_blocked(l, q)) continue;
        visible++;
        CHECK(e > 0, "%s: pixel %d,%d at (%.3f %.3f %.3f) faces the light, sees it, and gets no light",
              what, i % im->w, i / im->w, p[0], p[1], p[2]);
    }
    CHECK(visible >= facing - facing / 1000 && facing > 0, "%s: the BVH sees the light from %d of %d pixels",
          what, visible, facing);
    if (!analytic) return;
    for (i = 0; i < im->w * im->h; i++) {
        double p[3], n[3], err, want, e, L[3], dist, cosine, tol;
        if (im->sky[i]) continue;
        pixel_pos(im, i, p, n);
        want = room_exact_irradiance(im, l, i, p, n, &err);
        if (want <= 0) continue;
        e = dv(U_R(im)[i]);
        /* E = I cos / d^2 moves by up to 2 err / d (distance) and
         * err / (d cos) (angle) relative, for a position error err */
        L[0] = dv(l->pos.x) - p[0]; L[1] = dv(l->pos.y) - p[1]; L[2] = dv(l->pos.z) - p[2];
        dist = sqrt(dot3(L, L)); cosine = dot3(n, L) / dist;
        tol = 0.01 + 3 * err / dist + 1.5 * err / (dist * (cosine > 1e-6 ? cosine : 1e-6));
        if (TG_FIXED) tol += 2 * 1.53e-5 / (dist * dist); /* d^2 in Q16.16: one unit in the last place */
        CHECK(fabs(e - want) <= tol * want, "%s: pixel %d,%d at (%.3f %.3f %.3f) n (%.2f %.2f %.2f) unshadowed E %g, analytic %g (tolerance %.3f)",
              what, i % im->w, i / im->w, p[0], p[1], p[2], n[0], n[1], n[2], e, want, tol);
    }
}

/* Each image size, map size and filter. */
static void room_check(const geo *g, const tgi_light *l, const double eye[3], const double target[3],
                       double fov, const char *name, int analytic)
{
    int s, m, filter;
    char what[96];
    for (s = 0; s < SIZE_COUNT; s++) {
        image im;
        image_render(&im, g, NULL, eye, target, fov, sizes[s][0], sizes[s][1]);
        for (m = 0; m < MAP_COUNT; m++)
            for (filter = 0; filter < 2; filter++) {
                /* the largest map only at the smallest size, the bilinear
                 * filter only with the default map (time) */
                if ((map_sizes[m] > 512 && s > 0) || (filter && (map_sizes[m] != 512 || s != 2))) continue;
                snprintf(what, sizeof what, "%s %dx%d map %d %s", name, im.w, im.h, map_sizes[m],
                         method_name(map_sizes[m], filter));
                image_light(&im, g, l, map_sizes[m], filter ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT);
                lit_check(&im, l, what, analytic && m == 0, map_sizes[m] >= 512 ? im.w * im.h / 20 / ((im.w * im.h) / 5000 + 1) : 0);
            }
        if (s + 1 < SIZE_COUNT) {   /* shadow rays: the same checks (time: not at the largest size) */
            snprintf(what, sizeof what, "%s %dx%d rays", name, im.w, im.h);
            image_light(&im, g, l, RAYS, 0);
            lit_check(&im, l, what, 0, im.w * im.h / 20 / ((im.w * im.h) / 5000 + 1));
        }
        image_free(&im);
    }
}

TEST(ceiling_over_a_point_light_is_lit_at_every_size)
{
    static const double eye[3] = { 0, 1.25, -3.5 }, target[3] = { 0, 1.6, 2.5 };
    static const double eye2[3] = { 0.8, 0.6, 0.7 }, target2[3] = { -0.6, 2.5, 4.0 };
    geo *g = geo_new();
    tgi_light l;
    empty_room(g);
    geo_bvh(g);
    /* 1% of the room's height below the ceiling */
    l = make_light(TG_LIGHT_POINT, v3(0.4, 2.5 - 0.025, 2.3), v3(0, -1, 0), 2, 0);
    room_check(g, &l, eye, target, 60, "ceiling (front view)", 1);
    room_check(g, &l, eye2, target2, 70, "ceiling (from below)", 1);
    free(g);
}

/* A wall x = 0 (and a floor) lit at 85 degrees from the wall's normal at its
 * centre by a point, a spot and a directional light. */
TEST(wall_at_85_degrees_is_lit_at_every_size)
{
    static const double eye[3] = { 3.5, 1.6, -1.2 }, target[3] = { 0, 1.4, 0.6 };
    double th = 85 * DEG, c[3] = { 0, 1.5, 0 }, dist = 2.5;
    double lp[3] = { c[0] + dist * cos(th), c[1], c[2] - dist * sin(th) };
    geo *g = geo_new();
    tgi_light pt, sp, dl;
    memset(g, 0, sizeof *g);
    rect(g, 0, 0, 0, 3, -3, 3);        /* the wall, normal +x */
    rect(g, 1, 0, 0, 4, -3, 3);        /* a floor in front of it */
    geo_bvh(g);
    pt = make_light(TG_LIGHT_POINT, v3(lp[0], lp[1], lp[2]), v3(0, -1, 0), 8, 0);
    sp = make_light(TG_LIGHT_SPOT, v3(lp[0], lp[1], lp[2]), v3(c[0] - lp[0], c[1] - lp[1], c[2] - lp[2]), 8, 70 * DEG);
    dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(-cos(th), -0.05, sin(th)), 1, 0);
    room_check(g, &pt, eye, target, 60, "wall 85 point", 0);
    room_check(g, &sp, eye, target, 60, "wall 85 spot", 0);
    room_check(g, &dl, eye, target, 60, "wall 85 directional", 0);
    free(g);
}

/* ---- occluders still shadow ---- */

static void floor_and_box(geo *g, double half, const double lo[3], const double hi[3])
{
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -half, half, -half, half);
    box(g, lo, hi, -1);
    geo_bvh(g);
}

/* Shadow maps (the tent at every size, the bilinear filter at 160x120) and
 * shadow rays (up to 320x240) against the BVH's surely lit and surely
 * shadowed pixels; at 320x240 the map and the rays also agree (visibility
 * within 0.5) on all but `max_disagree` percent of the pixels facing the light. */
static void shadow_check(const geo *g, const tgi_light *l, const double eye[3], const double target[3],
                         double fov, int size, const char *name, int min_shadowed, double max_disagree)
{
    static const int method_size[3] = { -1, -1, RAYS }, method_filter[3] = { 0, 1, 0 };
    int s, k;
    char what[96];
    for (s = 0; s < SIZE_COUNT; s++) {
        image im;
        tg_real *map_vis = NULL;
        image_render(&im, g, NULL, eye, target, fov, sizes[s][0], sizes[s][1]);
        for (k = 0; k < 3; k++) {
            int msize = method_size[k] < 0 ? size : method_size[k], i, facing = 0, disagree = 0;
            tally t;
            if ((k == 1 && s != 2) || (k == 2 && s > 3)) continue;  /* time */
            snprintf(what, sizeof what, "%s %dx%d map %d %s", name, im.w, im.h, size, method_name(msize, method_filter[k]));
            image_light(&im, g, l, msize, method_filter[k] ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT);
            t = check_visibility(&im, l, what, 1);
            if (getenv("SHADOW_COUNTS")) printf("# %s: %d shadowed %d lit %d penumbra\n", what, t.shadowed, t.lit, t.penumbra);
            /* the shadow is there (from 320x240 on: below, the margins of
             * "surely" can cover it), and so is the open floor */
            CHECK((s < 3 || t.shadowed >= min_shadowed) && t.lit >= 100,
                  "%s: %d surely shadowed, %d surely lit", what, t.shadowed, t.lit);
            if (s != 3) continue;
            if (k == 0) {   /* keep the map's visibility for the rays to compare with */
                map_vis = (tg_real *)malloc((size_t)im.w * (size_t)im.h * sizeof(tg_real));
                if (!map_vis) { fprintf(stderr, "out of memory\n"); exit(2); }
                for (i = 0; i < im.w * im.h; i++)
                    map_vis[i] = U_R(&im)[i] > 0 ? rv(dv(E_R(&im)[i]) / dv(U_R(&im)[i])) : 0;
                continue;
            }
            if (k != 2 || !map_vis) continue;
            for (i = 0; i < im.w * im.h; i++) {
                double u = dv(U_R(&im)[i]);
                if (im.sky[i] || u <= 0) continue;
                facing++;
                disagree += fabs(dv(E_R(&im)[i]) / u - dv(map_vis[i])) > 0.5;
            }
            if (getenv("SHADOW_COUNTS")) printf("# %s: rays and map disagree on %d of %d\n", what, disagree, facing);
            CHECK(facing > 0 && disagree <= max_disagree / 100 * facing, "%s: rays and the map disagree on %d of %d pixels",
                  what, disagree, facing);
        }
        free(map_vis);
        image_free(&im);
    }
}

TEST(box_on_a_floor_casts_its_shadow)
{
    static const double lo[3] = { -0.5, 0, -0.5 }, hi[3] = { 0.5, 1, 0.5 };
    static const double eye[3] = { 0.5, 6, -4 }, target[3] = { 0, 0, 0.5 };
    geo *g = geo_new();
    tgi_light pl = make_light(TG_LIGHT_POINT, v3(-1.5, 3, -1), v3(0, -1, 0), 20, 0);
    tgi_light sl = make_light(TG_LIGHT_SPOT, v3(-2, 4, -1), v3(2.5, -4, 1.2), 20, 50 * DEG);
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0.8, -1, 0.5), 1, 0);
    floor_and_box(g, 6, lo, hi);
    shadow_check(g, &pl, eye, target, 50, 512, "box point", 30, 0.5);
    shadow_check(g, &sl, eye, target, 50, 512, "box spot", 20, 0.5);
    shadow_check(g, &dl, eye, target, 50, 512, "box directional", 15, 0.5);
    shadow_check(g, &pl, eye, target, 50, 64, "box point", 5, 0.5);
    free(g);
}

/* Light 1-3 degrees above the floor's plane: the box's shadow is 20-60 times
 * its height; inside it stays dark, the open floor stays lit. */
TEST(receivers_at_87_to_89_degrees_are_shadowed_and_lit)
{
    static const double lo[3] = { -0.5, 0, -0.5 }, hi[3] = { 0.5, 1.5, 0.5 };
    static const double eye[3] = { 0, 14, -6 }, target[3] = { 0, 0, 6 };
    static const double angles[] = { 87, 88, 89 };
    geo *g = geo_new();
    size_t k;
    char name[64];
    floor_and_box(g, 20, lo, hi);
    for (k = 0; k < sizeof angles / sizeof angles[0]; k++) {
        double th = angles[k] * DEG;
        tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0.1 * sin(th), -cos(th), sin(th)), 1, 0);
        /* a point light 15 m away at the same elevation */
        tgi_light pl = make_light(TG_LIGHT_POINT, v3(0, 15 * cos(th), -15 * sin(th)), v3(0, -1, 0), 400, 0);
        snprintf(name, sizeof name, "%g deg directional", angles[k]);
        shadow_check(g, &dl, eye, target, 60, 1024, name, 8, 0.5);
        if (angles[k] > 88) continue; /* the point light would sit below the box's top */
        snprintf(name, sizeof name, "%g deg point", angles[k]);
        shadow_check(g, &pl, eye, target, 60, 1024, name, 20, 0.5);
    }
    free(g);
}

/* Geometry crossing the light's near plane and lying behind the light: a
 * vertical fin 1 cm beside a point light (it crosses w = 0 in four faces of
 * the cube) shadows the floor beyond it and nothing else; a plane through a
 * spot light's own position (half of it behind the map) shadows only where
 * it is in front; a plate 2 cm under a point light (4 near distances)
 * shadows a wide disc. */
TEST(geometry_at_and_behind_the_light_near_plane)
{
    static const double eye[3] = { 0, 7, -5 }, target[3] = { 0, 0, 0.5 };
    geo *g = geo_new();
    tgi_light pl = make_light(TG_LIGHT_POINT, v3(0, 2, 0), v3(0, -1, 0), 10, 0);
    tgi_light sl = make_light(TG_LIGHT_SPOT, v3(0, 2, 0), v3(0, -1, 0), 10, 70 * DEG);
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -5, 5, -5, 5);
    rect(g, 2, 0.01, -1, 1, 1.5, 2.5);          /* fin: z = 0.01, x in [-1, 1], y in [1.5, 2.5] */
    geo_bvh(g);
    shadow_check(g, &pl, eye, target, 60, 512, "fin beside a point light", 300, 0.5);
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -5, 5, -5, 5);
    rect(g, 0, 1, 1.5, 2.5, -1, 1);              /* a wall x = 1 from above to below the spot */
    geo_bvh(g);
    shadow_check(g, &sl, eye, target, 60, 512, "wall through a spot light's plane", 40, 0.5);
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -5, 5, -5, 5);
    rect(g, 1, 1.98, -0.012, 0.012, -0.012, 0.012); /* plate 2 cm under the light, 2.4 cm wide */
    geo_bvh(g);
    shadow_check(g, &pl, eye, target, 60, 512, "plate 2 cm under a point light", 50, 0.5);
    free(g);
}

/* ---- the lookup itself, at exact points ---- */

static void exact_map(tgi_shadow_map *sm, void **mem, const geo *g, const tgi_light *l, int size)
{
    *mem = malloc(tgi_shadow_map_bytes(l, size));
    if (!*mem) { fprintf(stderr, "out of memory\n"); exit(2); }
    tgi_shadow_map_setup(sm, l, size, v3(g->lo[0], g->lo[1], g->lo[2]), v3(g->hi[0], g->hi[1], g->hi[2]), *mem);
    tgi_shadow_map_render(sm, g->pos, g->n);
}

/* A plate over a floor, both square and level about the y axis: the floor
 * at y = 0 and |x|, |z| <= floor_half, the plate at y = height and |x|,
 * |z| <= plate_half, with light l's exact map of them (exact_map), `size`
 * texels a side.  plate_scene_free releases it. */
typedef struct plate_scene {
    geo *g;
    tgi_shadow_map sm;
    void *mem;
} plate_scene;

static void plate_scene_map(plate_scene *ps, const tgi_light *l, double floor_half, double height,
                            double plate_half, int size)
{
    ps->g = geo_new();
    rect(ps->g, 1, 0, -floor_half, floor_half, -floor_half, floor_half);
    rect(ps->g, 1, height, -plate_half, plate_half, -plate_half, plate_half);
    exact_map(&ps->sm, &ps->mem, ps->g, l, size);
}

static void plate_scene_free(plate_scene *ps)
{
    free(ps->mem);
    free(ps->g);
}

/* A floor meeting a wall (x = 0), lit at 80 degrees toward the wall: floor
 * points within the PCF footprint of the corner see the wall in their
 * deeper taps, where the floor's plane continues behind it; a tap is never
 * taken deeper than the lookup, so they stay lit (the wall is shallower
 * than the lookup only for points within ~2 cos^2 texels of the corner). */
TEST(concave_corner_is_not_darkened)
{
    double th = 80 * DEG, ct = cos(th);
    geo *g = geo_new();
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(-sin(th), -cos(th), 0.1), 1, 0);
    tgi_light pl = make_light(TG_LIGHT_POINT, v3(6 * sin(th), 6 * cos(th), 0.3), v3(0, -1, 0), 1, 0);
    const tgi_light *lights[2] = { &dl, &pl };
    int k, j, seen = 0;
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, 0, 8, -4, 4);   /* floor x >= 0 */
    rect(g, 0, 0, 0, 4, -4, 4);   /* wall x = 0, facing +x */
    for (k = 0; k < 2; k++) {
        tgi_shadow_map sm;
        void *mem;
        exact_map(&sm, &mem, g, lights[k], 512);
        for (j = 0; j < 400; j++) {
            /* the lateral texel in world units at the receiver */
            double z = -1 + (j % 20) * 0.1, x0, tw = dv(sm.texel_world), lateral;
            if (lights[k]->type != TG_LIGHT_DIRECTIONAL) tw *= 6;
            lateral = (0.3 + 1.7 * (j / 20) / 19.0) * tw;   /* 0.3 .. 2 texels from the corner in the map */
            x0 = lateral / ct;
            {
                tg_real vis = tgi_shadow_visibility(&sm, v3(x0, 0, z), v3(0, 1, 0));
                seen++;
                CHECK(vis >= TG_R(0.98f), "%s: floor %.4f from the corner (%.2f texels) lit %.3f",
                      k ? "point" : "directional", x0, lateral / tw, dv(vis));
            }
        }
        free(mem);
    }
    CHECK(seen == 800, "%d points", seen);
    free(g);
}

/* The receiver's offset toward the light stops half way to it: a light 2 cm
 * over a floor, a plate 1.5 cm over it, a receiver whose position may be
 * off by 5 cm - the plate still shadows it (without the stop, the moved
 * plane would pass the light and everything would be lit). */
TEST(offset_stops_half_way_to_the_light)
{
    tgi_light pl = make_light(TG_LIGHT_POINT, v3(0, 0.02, 0), v3(0, -1, 0), 1, 0);
    plate_scene ps;
    tg_real under, beyond;
    plate_scene_map(&ps, &pl, 2, 0.015, 0.2, 512);
    under = tgi_shadow_visibility_err(&ps.sm, v3(0.05, 0, 0.03), v3(0, 1, 0), TG_R(0.05f));
    beyond = tgi_shadow_visibility_err(&ps.sm, v3(1.5, 0, 0.3), v3(0, 1, 0), TG_R(0.05f));
    CHECK(under <= TG_R(0.02f), "under the plate, position error 5 cm: %g", dv(under));
    CHECK(beyond >= TG_R(0.98f), "beyond the plate's shadow: %g", dv(beyond));
    plate_scene_free(&ps);
}

/* ---- sizes ---- */

TEST(map_bytes_are_checked)
{
    tgi_light pt = make_light(TG_LIGHT_POINT, v3(0, 1, 0), v3(0, -1, 0), 1, 0);
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0, -1, 0), 1, 0);
    tgi_shadow_map sm;
    static const int bad[] = { -1, 0, 1, TG_MIN_SHADOW_MAP - 1, TG_MAX_SHADOW_MAP + 1, 13378, 65536, 1518500250, INT32_MAX };
    size_t k;
    CHECK(tgi_shadow_map_bytes(&pt, 512) == 6u * 512 * 512 * 2, "point 512 (16 bits a texel): %zu", tgi_shadow_map_bytes(&pt, 512));
    CHECK(tgi_shadow_map_bytes(&dl, 512) == 512u * 512 * 2, "directional 512");
    CHECK(tgi_shadow_map_bytes(&pt, TG_MIN_SHADOW_MAP) > 0 && tgi_shadow_map_bytes(&pt, TG_MAX_SHADOW_MAP) > 0,
          "the limits themselves are allowed");
    /* the largest map fits a 32-bit size_t: 6 * 8192^2 * 2 < 2^32 */
    CHECK((double)tgi_shadow_map_bytes(&pt, TG_MAX_SHADOW_MAP) < 4294967296.0, "largest map %zu bytes",
          tgi_shadow_map_bytes(&pt, TG_MAX_SHADOW_MAP));
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        CHECK(tgi_shadow_map_bytes(&pt, bad[k]) == 0, "point map of %d texels: %zu bytes", bad[k], tgi_shadow_map_bytes(&pt, bad[k]));
        CHECK(tgi_shadow_map_bytes(&dl, bad[k]) == 0, "directional map of %d texels", bad[k]);
        /* set up anyway (a caller that ignored the 0): an empty map, rendering
         * writes nothing, every lookup is lit */
        tgi_shadow_map_setup(&sm, &pt, bad[k], v3(-1, 0, -1), v3(1, 1, 1), NULL);
        CHECK(sm.faces == 0 && sm.size == 0, "size %d: %d faces of %d", bad[k], sm.faces, sm.size);
        tgi_shadow_map_render(&sm, NULL, 0);
        CHECK(tgi_shadow_visibility(&sm, v3(0, 0, 0), v3(0, 1, 0)) == TG_ONE, "empty map is lit");
    }
}

/* A plate at the very top of the scene's bounds, under a light straight
 * overhead: the map's near side lies outside the bounds (by its margin), so
 * the plate is in the map and shadows the floor under it; the open floor is
 * lit.  Both filters, two map sizes. */
TEST(occluder_at_the_bounds_near_side_casts_its_shadow)
{
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0, -1, 0), 1, 0);
    static const int map_sides[2] = { 64, 512 };
    int k, filter;
    for (k = 0; k < 2; k++)
        for (filter = 0; filter < 2; filter++) {
            plate_scene ps;
            double x, z;
            int dark = 0, lit = 0, under = 0, open = 0;
            plate_scene_map(&ps, &dl, 3, 1, 0.8, map_sides[k]);
            ps.sm.filter = filter;           /* the lookup's: the map itself is the same */
            for (x = -2.5; x <= 2.5; x += 0.25)
                for (z = -2.5; z <= 2.5; z += 0.25) {
                    double v = dv(tgi_shadow_visibility(&ps.sm, v3(x, 0, z), v3(0, 1, 0)));
                    if (fabs(x) < 0.5 && fabs(z) < 0.5) { under++; dark += v < 0.01; }
                    if (fabs(x) > 1.2 || fabs(z) > 1.2) { open++; lit += v > 0.99; }
                }
            CHECK(dark == under, "size %d filter %d: %d of %d floor points under the plate in shadow", map_sides[k], filter, dark, under);
            CHECK(lit == open, "size %d filter %d: %d of %d open floor points lit", map_sides[k], filter, lit, open);
            plate_scene_free(&ps);
        }
}

/* Equal depths in the depth test: the first triangle drawn keeps the pixel,
 * in the G-buffer raster of both number types ("nearer", not "nearer or
 * equal"), so float and Q16.16 agree where coplanar surfaces meet. */
/* Two quads on the same plane with the same vertices (so every depth is
 * bit for bit the same), red drawn first, blue second, seen from one side
 * and from a grazing angle: every covered pixel is red. */
static void ties_from(const double eye[3], const char *what)
{
    static const tgi_material mats[2] = {
        { "red", { TG_ONE, 0, 0 }, 0, { 0, 0, 0 }, 1, { TG_INV_PI, 0, 0 } },   /* diffuse: tgi_material_finish's */
        { "blue", { 0, 0, TG_ONE }, 0, { 0, 0, 0 }, 1, { 0, 0, TG_INV_PI } },
    };
    static const double target[3] = { 0, 0, 0 };
    double q[4][3] = { { -1, 0, -1 }, { 1, 0, -1 }, { 1, 0, 1 }, { -1, 0, 1 } };
    geo *g = geo_new();
    image im;
    tgi_gview v;
    int i, covered = 0, blue = 0;
    g->material = 0;
    quad(g, q);
    g->material = 1;
    quad(g, q);
    image_render(&im, g, mats, eye, target, 60, 48, 36);
    v = sf_view(&im.gb, &im.view);
    for (i = 0; i < im.w * im.h; i++) {
        tg_vec3 a;
        if (im.sky[i]) continue;
        covered++;
        a = tgi_gv_albedo(&v, (size_t)i);
        if (a.z > 0 || a.x < TG_ONE) blue++;
    }
    CHECK(covered > 100, "%s: the plane covers %d pixels", what, covered);
    CHECK(blue == 0, "%s: %d of %d pixels took the second of two equal depths", what, blue, covered);
    image_free(&im);
    free(g);
}

TEST(coplanar_ties_keep_the_first_drawn)
{
    static const double above[3] = { 0.3, 2.5, -1.7 }, grazing[3] = { 0.2, 0.25, -1.4 };
    ties_from(above, "from above");
    ties_from(grazing, "grazing");
}

/* Receivers beyond 89.94 degrees (|n . l| below GRAZING_MIN_COS = 0.001 in
 * src/light/shadowmap.c) facing a light straight above, under a plate 6-16
 * m over them: a wall point 0.2 m over the floor, its normal 0.0005 to
 * 0.00005 from horizontal.  The lookup moves the receiver toward the light
 * by its position error / |n . l| (here ~4 mm / |n . l|) and the floor on
 * |n . l| keeps that under 4 m: the receiver's own tap and the taps deeper
 * than it see the plate, only the column of taps on the side where its
 * plane rises toward the light passes it (a third of the tent), so it is
 * mostly dark.  Without the floor the receiver is moved past the plate and
 * lit through it. */
TEST(receiver_beyond_89_94_degrees_under_a_plate_is_dark)
{
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0, -1, 0), 1, 0);
    static const double cosines[] = { 0.0005, 0.0002, 0.0001, 0.00005 };
    static const double heights[] = { 6, 10, 16 };
    size_t k, j;
    for (j = 0; j < sizeof heights / sizeof heights[0]; j++) {
        plate_scene ps;
        plate_scene_map(&ps, &dl, 8, heights[j], 1, 512);
        for (k = 0; k < sizeof cosines / sizeof cosines[0]; k++) {
            double c = cosines[k];
            tg_real vis = tgi_shadow_visibility(&ps.sm, v3(0.1, 0.2, 0.05), v3(sqrt(1 - c * c), c, 0));
            CHECK(vis <= TG_R(0.5f), "plate %g m above, |n . l| = %g: visibility %g", heights[j], c, dv(vis));
        }
        plate_scene_free(&ps);
    }
}

/* The tent PCF across a straight shadow edge: a plate over half the floor,
 * lit from straight above, its edge exactly on a texel boundary of the map.
 * The tent's weights (1 - f, 1, 1, f per axis, normalised by their sum 9)
 * make a linear ramp of the edge, odd about it: floor points at the same
 * distance either side of the edge have visibilities adding up to 1. */
TEST(tent_pcf_is_odd_about_a_shadow_edge)
{
    tgi_light dl = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0, -1, 0), 1, 0);
    plate_scene ps;
    tgi_shadow_map sm;
    void *mem;
    geo *g = geo_new();
    double r[3], tb, texel, worst = 0;
    int a, k, ax = 0, n;
    plate_scene_map(&ps, &dl, 8, 1, 8, 256);   /* the plate's final bounds: only its extent along r changes */
    r[0] = dv(ps.sm.face[0].right.x); r[1] = dv(ps.sm.face[0].right.y); r[2] = dv(ps.sm.face[0].right.z);
    for (a = 0; a < 3; a++) if (fabs(r[a]) > fabs(r[ax])) ax = a;
    n = ps.sm.face[0].size;
    texel = 2.0 / n / dv(ps.sm.ortho_scale);
    tb = dv(ps.sm.ortho_center_x) + (2.0 * (n / 2 + 3) / n - 1) / dv(ps.sm.ortho_scale);  /* p . r on a texel boundary */
    plate_scene_free(&ps);
    CHECK(ax != 1 && fabs(fabs(r[ax]) - 1) < 1e-6, "the light's right axis (%g, %g, %g) should be a floor axis", r[0], r[1], r[2]);
    rect(g, 1, 0, -8, 8, -8, 8);
    {   /* the plate over p . r >= tb */
        double lo = r[ax] > 0 ? tb : -8, hi = r[ax] > 0 ? 8 : -tb;
        if (ax == 0) rect(g, 1, 1, lo, hi, -8, 8);
        else rect(g, 1, 1, -8, 8, lo, hi);
    }
    exact_map(&sm, &mem, g, &dl, 256);
    sm.filter = TG_SHADOW_PCF_TENT;
    for (k = 1; k <= 48; k++) {
        double d = 2.5 * texel * k / 48, pa[3] = { 0.3, 0, 0.3 }, pb[3] = { 0.3, 0, 0.3 }, va, vb;
        pa[ax] = (tb + d) / r[ax];
        pb[ax] = (tb - d) / r[ax];
        va = dv(tgi_shadow_visibility(&sm, v3(pa[0], pa[1], pa[2]), v3(0, 1, 0)));
        vb = dv(tgi_shadow_visibility(&sm, v3(pb[0], pb[1], pb[2]), v3(0, 1, 0)));
        worst = fmax(worst, fabs(va + vb - 1));
        CHECK(fabs(va + vb - 1) <= 2e-3, "%.2f texels either side of the edge: %g + %g", d / texel, va, vb);
    }
    printf("# tent PCF across a shadow edge: worst |v(+d) + v(-d) - 1| %.2g\n", worst);
    free(mem);
    free(g);
}

/* Geometry nearer the light than its map's near plane: a plate 0.8 cm wide
 * 3 mm under a point light (the near plane: tgi_shadow_near, 5 mm here)
 * casts a shadow cone of half angle atan(4 / 3): the floor 2 m below is
 * dark out to 2.67 m from the foot of the light and lit beyond. */
TEST(plate_nearer_than_the_near_plane_shadows)
{
    static const double dark[][2] = { { 0, 0 }, { 0.5, 0.3 }, { -1.2, 1.0 }, { 2.0, -1.2 } };
    static const double lit[][2] = { { 3.5, 0 }, { -3.0, 2.5 }, { 0.5, 4.0 } };
    tgi_light pl = make_light(TG_LIGHT_POINT, v3(0, 2, 0), v3(0, -1, 0), 1, 0);
    plate_scene ps;
    const geo *g;
    size_t k;
    plate_scene_map(&ps, &pl, 5, 1.997, 0.004, 512);
    g = ps.g;
    printf("# near plane %.4f, plate 0.003 under the light\n", dv(tgi_shadow_near(pl.pos, v3(g->lo[0], g->lo[1], g->lo[2]),
           v3(g->hi[0], g->hi[1], g->hi[2]))));
    for (k = 0; k < sizeof dark / sizeof dark[0]; k++) {
        tg_real vis = tgi_shadow_visibility(&ps.sm, v3(dark[k][0], 0, dark[k][1]), v3(0, 1, 0));
        CHECK(vis <= TG_R(0.02f), "floor (%g, %g) under the plate: visibility %g", dark[k][0], dark[k][1], dv(vis));
    }
    for (k = 0; k < sizeof lit / sizeof lit[0]; k++) {
        tg_real vis = tgi_shadow_visibility(&ps.sm, v3(lit[k][0], 0, lit[k][1]), v3(0, 1, 0));
        CHECK(vis >= TG_R(0.98f), "floor (%g, %g) beyond the plate's shadow: visibility %g", lit[k][0], lit[k][1], dv(vis));
    }
    plate_scene_free(&ps);
}

#if TG_FIXED
/* The Q16.16 lookups' perspective depth test, one 64-bit compare, agrees
 * with num >= tg_mul(a, den) as written: random operands over the range
 * (where the product saturates too) and every product at a rounding tie,
 * a den = (2 num + 1 + 2 k) 2^15 over a = 1, and one either side: the
 * compare's bound is where tg_mul's rounding puts it (ties toward
 * +infinity since this round's eighteenth session: the bound moved from
 * num 2^16 + 2^15 to num 2^16 + 2^15 - 1, and this test failed at the ties
 * with the old one). */
TEST(perspective_test_in_64_bits_is_tg_mul_s)
{
    unsigned seed = 4242;
    long count = 0, ties = 0, bad = 0, i;
    for (i = 0; i < 2000000; i++) {
        const tg_real num = -(tg_real)(check_rnd(&seed) * (check_rnd(&seed) < 0.5 ? 70000.0 : 2147483647.0)) - 1;
        const tg_real a = (tg_real)((2 * check_rnd(&seed) - 1) * (check_rnd(&seed) < 0.5 ? 2147483647.0 : 65536.0 * 16));
        const tg_real den = (tg_real)((2 * check_rnd(&seed) - 1) * (check_rnd(&seed) < 0.5 ? 2147483647.0 : 65536.0 * 16));
        count++;
        if (tgi_shadow_lit_perspective_q16(num, a, den, 1) != tgi_shadow_lit_perspective_q16(num, a, den, 0) && bad++ < 5)
            fprintf(stderr, "num %d a %d den %d: %d in 64 bits, %d by tg_mul\n", (int)num, (int)a, (int)den,
                    tgi_shadow_lit_perspective_q16(num, a, den, 1), tgi_shadow_lit_perspective_q16(num, a, den, 0));
    }
    for (i = 1; i <= 60000; i += 7) {
        const int64_t num = -i;
        int k, d;
        for (k = -2; k <= 2; k++)
            for (d = -1; d <= 1; d++) {
                const int64_t den = (2 * num + 1 + 2 * k) * 32768 + d;   /* a den = P, a = 1: ties at d = 0 */
                if (den < -(int64_t)TG_REAL_MAX || den > TG_REAL_MAX) continue;
                ties += d == 0;
                if (tgi_shadow_lit_perspective_q16((tg_real)num, 1, (tg_real)den, 1)
                        != tgi_shadow_lit_perspective_q16((tg_real)num, 1, (tg_real)den, 0) && bad++ < 10)
                    fprintf(stderr, "num %ld den %ld: differ\n", (long)num, (long)den);
            }
    }
    printf("  perspective depth tests: %ld random, %ld at rounding ties (and either side), %ld differ\n", count, ties, bad);
    CHECK(bad == 0 && ties > 20000, "%ld of the tests differ (%ld ties)", bad, ties);
}
#endif

int main(void)
{
    RUN(occluder_at_the_bounds_near_side_casts_its_shadow);
    RUN(coplanar_ties_keep_the_first_drawn);
    RUN(map_bytes_are_checked);
    RUN(ceiling_over_a_point_light_is_lit_at_every_size);
    RUN(wall_at_85_degrees_is_lit_at_every_size);
    RUN(box_on_a_floor_casts_its_shadow);
    RUN(receivers_at_87_to_89_degrees_are_shadowed_and_lit);
    RUN(geometry_at_and_behind_the_light_near_plane);
    RUN(concave_corner_is_not_darkened);
    RUN(offset_stops_half_way_to_the_light);
    RUN(receiver_beyond_89_94_degrees_under_a_plate_is_dark);
    RUN(tent_pcf_is_odd_about_a_shadow_edge);
    RUN(plate_nearer_than_the_near_plane_shadows);
#if TG_FIXED
    RUN(perspective_test_in_64_bits_is_tg_mul_s);
#endif
    free(bvh_mem);
    return check_summary();
}
