/* SPDX-License-Identifier: MIT */
/*
 * test_shadow_rule.c - shadow maps that fit: 16-bit depth (read back within
 * half a step, the step in the bias), the size rule's values on views
 * where the answer is known, face culling and windows never dropping a
 * receiver the camera sees (random rooms, lights and cameras), the byte
 * counts, the animation's bounds and the choice between maps and rays.
 */
#include "raster_fixture.h"
#include "light/shadowmap.h"
#include "light/shadowview.h"
#include "light/direct.h"
#include "scene/anim.h"

/* ---- 16-bit depth ---- */

static void map_with(tgi_shadow_map *sm, void **mem, const geo *g, const tgi_light *l, int size, int bits)
{
    tgi_shadow_need nd;
    tgi_shadow_need_init(&nd, l);
    nd.depth_bits = bits;
    tgi_shadow_need_all(&nd);
    tgi_shadow_need_finish(&nd, size);
    *mem = malloc(tgi_shadow_need_bytes(&nd));
    if (!*mem) { fprintf(stderr, "out of memory\n"); exit(2); }
    tgi_shadow_map_setup_need(sm, l, &nd, v3(g->lo[0], g->lo[1], g->lo[2]), v3(g->hi[0], g->hi[1], g->hi[2]), *mem);
    tgi_shadow_map_render(sm, g->pos, g->n);
}

/* A floor, boxes, and triangles crossing the light's near plane. */
static void clutter(geo *g)
{
    static const double lo1[3] = { -1, 0, -1 }, hi1[3] = { -0.2, 0.8, 0.5 };
    static const double lo2[3] = { 0.5, 0, 0.3 }, hi2[3] = { 1.5, 2.5, 1.1 };
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -4, 4, -4, 4);
    box(g, lo1, hi1, -1);
    box(g, lo2, hi2, -1);
    rect(g, 2, 0.02, -1, 1, 2.5, 3.5);  /* a fin 2 cm from the light */
}

TEST(depth16_reads_back_within_half_a_step)
{
    geo *g = geo_new();
    tgi_light lights[3];
    int k, f, checked = 0;
    clutter(g);
    lights[0] = make_light(TG_LIGHT_POINT, v3(0, 3, 0), v3(0, -1, 0), 1, 0);
    lights[1] = make_light(TG_LIGHT_SPOT, v3(-2, 4, -1), v3(1, -2, 0.5), 1, 50 * DEG);
    lights[2] = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0.4, -1, 0.3), 1, 0);
    for (k = 0; k < 3; k++) {
        tgi_shadow_map m16, m32;
        void *mem16, *mem32;
        map_with(&m16, &mem16, g, &lights[k], 96, TG_SHADOW_DEPTH16);
        map_with(&m32, &mem32, g, &lights[k], 96, TG_SHADOW_DEPTH32);
        CHECK(m16.depth_bits == 16 && m32.depth_bits == 32, "formats %d %d", m16.depth_bits, m32.depth_bits);
        for (f = 0; f < m16.faces; f++) {
            const tgi_shadow_face *fc = &m16.face[f];
            const uint16_t *q = (const uint16_t *)m16.depth + fc->offset;
            const tg_real *d = (const tg_real *)m32.depth + m32.face[f].offset;
            double lo = dv(fc->depth_lo), range = dv(fc->depth_range), step = range / 65536;
            int i, drawn = 0;
            CHECK(m32.face[f].offset == fc->offset && m32.face[f].size == fc->size, "same layout");
            CHECK(range > 0 && step > 0, "light %d face %d: range %g", k, f, range);
            for (i = 0; i < fc->size * fc->size; i++) {
                double back, want;
                if (d[i] == TG_REAL_MAX) {
                    CHECK(q[i] == TG_RASTER_DEPTH16_EMPTY, "light %d face %d texel %d: nothing drawn, code %u", k, f, i, q[i]);
                    continue;
                }
                drawn++;
                CHECK(q[i] < TG_RASTER_DEPTH16_EMPTY, "light %d face %d texel %d: drawn, code %u", k, f, i, q[i]);
                back = lo + range * q[i] / 65536.0;
                want = dv(d[i]);
                /* half a step, and the number type's rounding of depth and range */
                CHECK(fabs(back - want) <= 0.5 * step + 4 * dv(TG_EPS) * (1 + fabs(want)) + 1e-6 * range,
                      "light %d face %d texel %d: 16 bits %.6f, 32 bits %.6f (step %.2e)", k, f, i, back, want, step);
                /* the code past the bounds reads back beyond every drawn depth */
                CHECK(lo + range * 65535.0 / 65536.0 > want, "light %d face %d: empty code nearer than %g", k, f, want);
            }
            checked += drawn;
        }
        free(mem16); free(mem32);
    }
    CHECK(checked > 10000, "%d texels compared", checked);
    free(g);
}

/* A floor under a light straight above, in bounds that reach 1000 units up
 * (a speck): one 16-bit step (1000 / 65536 = 1.5 cm) is several times the
 * half-texel bias, so without the step in the bias half of the floor would
 * shadow itself.  Every floor point is lit, for each light type and filter. */
TEST(quantisation_step_is_in_the_bias)
{
    geo *g = geo_new();
    tgi_light lights[2];
    int k, j, filter;
    double tri_a[3] = { 0.3, 1000, 0.3 }, tri_b[3] = { 0.31, 1000, 0.3 }, tri_c[3] = { 0.3, 1000, 0.31 };
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -1, 1, -1, 1);
    tri(g, tri_a, tri_b, tri_c, NULL, NULL, NULL);
    lights[0] = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0, -1, 0), 1, 0);
    lights[1] = make_light(TG_LIGHT_SPOT, v3(0, 990, 0), v3(0, -1, 0), 1, 0.03 * DEG);
    for (k = 0; k < 2; k++)
        for (filter = 0; filter < 2; filter++) {
            tgi_shadow_map sm;
            void *mem;
            int lit = 0;
            double texel;
            map_with(&sm, &mem, g, &lights[k], 512, TG_SHADOW_DEPTH16);
            sm.filter = filter ? TG_SHADOW_PCF_BILINEAR : TG_SHADOW_PCF_TENT;
            texel = dv(sm.face[0].texel_world) * (k ? 990 : 1);
            CHECK(dv(sm.face[0].depth_step) > 2 * texel, "light %d: the step %g is not over twice the texel %g", k,
                  dv(sm.face[0].depth_step), texel);
            for (j = 0; j < 400; j++) {
                double x = -0.9 + 1.8 * (j % 20) / 19.0, z = -0.9 + 1.8 * (j / 20) / 19.0;
                tg_real vis;
                if (k == 1) { x *= 0.5; z *= 0.5; }   /* inside the spot's cone */
                vis = tgi_shadow_visibility(&sm, v3(x, 0, z), v3(0, 1, 0));
                lit += vis >= TG_R(0.98f);
            }
            CHECK(lit == 400, "light %d %s: %d of 400 floor points lit", k, filter ? "bilinear" : "tent", lit);
            free(mem);
        }
    free(g);
}

/* ---- the size rule on views with a known answer ---- */

/* The rule's need for one view of g. */
static void rule_need(tgi_shadow_need *nd, const tgi_light *l, const geo *g, const tgi_view *view, int override)
{
    tgi_shadow_need_init(nd, l);
    tgi_shadow_map_size_rule(nd, l, view, v3(g->lo[0], g->lo[1], g->lo[2]), v3(g->hi[0], g->hi[1], g->hi[2]),
                             g->pos, g->n);
    tgi_shadow_need_finish(nd, override);
}

/* A floor y = 0 over [-half, half]^2 alone. */
static geo *floor_geo(double half)
{
    geo *g = geo_new();
    memset(g, 0, sizeof *g);
    rect(g, 1, 0, -half, half, -half, half);
    return g;
}

/* A square w x w camera at eye looking at target (up +Z, fov in radians),
 * and the rule's need for light l over g there; what names it. */
typedef struct square_need {
    tgi_view view;
    tgi_shadow_need nd;
    char what[32];
} square_need;

static void need_looking_down(square_need *q, const char *light_name, const tgi_light *l, const geo *g,
                              tg_vec3 eye, tg_vec3 target, double fov_rad, int w)
{
    snprintf(q->what, sizeof q->what, "%s, W %d", light_name, w);
    tgi_view_make(&q->view, eye, target, v3(0, 0, 1), rv(fov_rad), TG_R(0.05f), TG_R(100.0f), w, w);
    rule_need(&q->nd, l, g, &q->view, 0);
}

/* Face f of a finished need: a window of side within [side_lo, side_hi],
 * `texels` texels across side_lo (within 2%), and the size that density
 * times the window's side and the PCF border make. */
static void check_face(const tgi_shadow_need *nd, int f, double side_lo, double side_hi, double texels, const char *what)
{
    double side = fmax(dv(nd->window[f][2]) - dv(nd->window[f][0]), dv(nd->window[f][3]) - dv(nd->window[f][1]));
    double density = dv(nd->density[f]);
    CHECK(nd->seen[f] && nd->window_set[f], "%s: face %d seen", what, f);
    CHECK(side >= side_lo && side <= side_hi, "%s: window side %g, want %g..%g", what, side, side_lo, side_hi);
    CHECK(fabs(density * side_lo - texels) <= 0.02 * texels, "%s: %g texels across, want %g", what, density * side_lo, texels);
    CHECK(nd->size[f] == (int)ceil(density * side - 1e-3) + 2 * TG_SHADOW_BORDER ||
          nd->size[f] == (int)ceil(density * side + 1e-3) + 2 * TG_SHADOW_BORDER,
          "%s: size %d, density %g x side %g + the border", what, nd->size[f], density, side);
}

/* A camera straight above a 2 x 2 floor that it frames exactly (square
 * image W x W), the sun straight above: the floor fills the image (A_cam =
 * 1) and covers 4 square units of the light plane, so the density is W / 2
 * texels per unit, the window the floor (side 2 and the margin), the size
 * W + the PCF border of 2 x 2 texels, plus the margin's texel or two. */
TEST(rule_gives_a_texel_per_pixel_under_the_sun)
{
    static const int widths[] = { 16, 64, 128, 320 };
    geo *g = floor_geo(1);
    tgi_light sun = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(0, -1, 0), 1, 0);
    size_t k;
    for (k = 0; k < sizeof widths / sizeof widths[0]; k++) {
        int w = widths[k];
        square_need q;
        need_looking_down(&q, "sun", &sun, g, v3(0, 4, 0), v3(0, 0, 0), 2 * atan(0.25), w);
        /* the window: the floor, and the position error's margin (at most 5%) */
        check_face(&q.nd, 0, 2, 2.1, w, q.what);
        CHECK(tgi_shadow_need_bytes(&q.nd) == (size_t)q.nd.size[0] * (size_t)q.nd.size[0] * 2, "W %d: bytes", w);
    }
    free(g);
}

/* A point light at the camera, both looking down at a floor that fills the
 * view (fov 80 degrees, square W x W): only the -Y face is seen, its window
 * is the view (tan 40 degrees each side) and the floor's pixels match its
 * texels one to one: size W + the border. */
TEST(rule_gives_a_texel_per_pixel_from_the_light)
{
    static const int widths[] = { 32, 100, 240 };
    geo *g = floor_geo(10);
    tgi_light pt = make_light(TG_LIGHT_POINT, v3(0.3, 2, -0.2), v3(0, -1, 0), 1, 0);
    double t = tan(40 * DEG);
    size_t k;
    int f;
    for (k = 0; k < sizeof widths / sizeof widths[0]; k++) {
        int w = widths[k];
        square_need q;
        need_looking_down(&q, "point", &pt, g, v3(0.3, 2, -0.2), v3(0.3, 0, -0.2), 80 * DEG, w);
        for (f = 0; f < 6; f++)
            CHECK((f == 3) == (q.nd.size[f] > 0), "W %d: face %d size %d (only -Y is seen)", w, f, q.nd.size[f]);
        /* the window: the view, and the position error's margin (at most 5%) */
        check_face(&q.nd, 3, 2 * t, 2 * t * 1.05, w, q.what);
        CHECK(tgi_shadow_map_bytes_for_view(&pt, &q.view, v3(-10, 0, -10), v3(10, 0, 10), g->pos, g->n, 0) ==
              (size_t)q.nd.size[3] * (size_t)q.nd.size[3] * 2, "bytes for the view: one face of %d", q.nd.size[3]);
        /* --shadow-size overrides the size of every seen face, and only theirs */
        tgi_shadow_need_finish(&q.nd, 77);
        for (f = 0; f < 6; f++) CHECK(q.nd.size[f] == (f == 3 ? 77 : 0), "override: face %d size %d", f, q.nd.size[f]);
        CHECK(tgi_shadow_map_bytes_for_view(&pt, &q.view, v3(-10, 0, -10), v3(10, 0, 10), g->pos, g->n, 77) == 77u * 77 * 2,
              "bytes for the view at --shadow-size 77");
    }
    free(g);
}

/* ---- faces and windows never drop a receiver the camera sees ---- */

static uint32_t rng_state = 12345u;
static double rnd(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (double)(rng_state >> 8) / 16777216.0;
}
static double rnd_in(double a, double b) { return a + (b - a) * rnd(); }

/* A room 6 x 3 x 5 with two blocks and a table, open toward -z. */
static void room(geo *g)
{
    static const double lo[3] = { 0, 0, 0 }, hi[3] = { 6, 3, 5 };
    static const double b1lo[3] = { 1, 0, 1 }, b1hi[3] = { 2, 1.5, 2 };
    static const double b2lo[3] = { 3.5, 0, 3 }, b2hi[3] = { 4.5, 0.8, 4.2 };
    memset(g, 0, sizeof *g);
    box(g, lo, hi, 4);
    box(g, b1lo, b1hi, -1);
    box(g, b2lo, b2hi, -1);
    rect(g, 1, 1.1, 3, 5, 0.5, 1.5);
}

/* The world position direct.c reconstructs at pixel i (tg_real). */
static tg_vec3 pixel_world(const image *im, int i)
{
    const tgi_view *v = &im->view;
    int x = i % im->w, y = i / im->w;
    tg_real half_w = tg_ldexp(tg_from_int(v->width), -1), half_h = tg_ldexp(tg_from_int(v->height), -1);
    tg_real ky = tg_div(tg_sub(half_h, tg_add(tg_from_int(y), TG_R(0.5f))), v->pixels_per_unit);
    tg_real kx = tg_div(tg_sub(tg_add(tg_from_int(x), TG_R(0.5f)), half_w), v->pixels_per_unit);
    tg_vec3 d = tgi_v3_add(tgi_v3_add(v->forward, tgi_v3_scale(v->up, ky)), tgi_v3_scale(v->right, kx));
    return tgi_v3_add(v->eye, tgi_v3_scale(d, im->depth[i]));
}

/* Every pixel whose lookup the direct pass makes (facing the light, inside
 * a spot's cone): its face is present and its light-plane point lies in
 * the face's window.  Returns the lookups checked. */
static int check_lookups(const image *im, const tgi_light *l, const tgi_shadow_need *nd, const char *what)
{
    int i, n = 0, bad = 0;
    for (i = 0; i < im->w * im->h; i++) {
        tg_vec3 p, nrm, d, r, u, axis;
        tg_real inv;
        double x, y;
        int f = 0;
        if (im->sky[i]) continue;
        p = pixel_world(im, i);
        {   /* the same point as the fixture's double-precision one */
            double pd[3], nd3[3], tol = 1e-3 * (1 + dv(im->depth[i])) + (TG_FIXED ? 2e-3 : 0);
            pixel_pos(im, i, pd, nd3);
            CHECK(fabs(pd[0] - dv(p.x)) + fabs(pd[1] - dv(p.y)) + fabs(pd[2] - dv(p.z)) <= tol, "%s: pixel %d reconstructed", what, i);
        }
        nrm = tg_v3(im->nx[i], im->ny[i], im->nz[i]);
        if (tgi_v3_dot(tgi_direct_irradiance(l, p, nrm), tg_v3(TG_ONE, TG_ONE, TG_ONE)) <= 0) continue;
        n++;
        if (l->type == TG_LIGHT_DIRECTIONAL) {
            axis = tgi_shadow_face_axis(l, 0);
            tgi_shadow_basis(axis, &r, &u);
            x = dv(tgi_v3_dot(p, r)); y = dv(tgi_v3_dot(p, u));
        } else {
            d = tgi_v3_sub(p, l->pos);
            if (l->type == TG_LIGHT_POINT) f = tgi_shadow_cube_face(d);
            axis = tgi_shadow_face_axis(l, f);
            tgi_shadow_basis(axis, &r, &u);
            if (tgi_v3_dot(d, axis) <= TG_R(0.001f)) continue;   /* at the light: lit without a lookup */
            inv = tg_div(TG_ONE, tgi_v3_dot(d, axis));
            x = dv(tg_mul(tgi_v3_dot(d, r), inv)); y = dv(tg_mul(tgi_v3_dot(d, u), inv));
        }
        if (nd->size[f] == 0) {
            if (bad++ < 5) CHECK(0, "%s: pixel %d,%d looks up face %d, which is absent", what, i % im->w, i / im->w, f);
            continue;
        }
        if (!nd->window_set[f]) continue;
        if (x < dv(nd->window[f][0]) - 1e-4 || x > dv(nd->window[f][2]) + 1e-4 ||
            y < dv(nd->window[f][1]) - 1e-4 || y > dv(nd->window[f][3]) + 1e-4) {
            if (getenv("SHADOW_DEBUG"))
                printf("p %.4f %.4f %.4f depth %.4f eye %.3f %.3f %.3f\n", dv(p.x), dv(p.y), dv(p.z), dv(im->depth[i]),
                       dv(im->view.eye.x), dv(im->view.eye.y), dv(im->view.eye.z));
            if (bad++ < 5)
                CHECK(0, "%s: pixel %d,%d at (%.4f %.4f) outside face %d's window %.4f %.4f %.4f %.4f", what, i % im->w,
                      i / im->w, x, y, f, dv(nd->window[f][0]), dv(nd->window[f][1]), dv(nd->window[f][2]), dv(nd->window[f][3]));
        }
    }
    CHECK(bad == 0, "%s: %d lookups outside the map", what, bad);
    return n;
}

/* Random rooms, lights and cameras (inside and outside the room, a moving
 * camera's three views sharing one need): every lookup finds its face and
 * its window; and faces do get culled (else the test would prove nothing). */
TEST(faces_and_windows_hold_every_visible_receiver)
{
    geo *g = geo_new();
    int trial, culled = 0, lookups = 0, cropped = 0;
    room(g);
    for (trial = 0; trial < 120; trial++) {
        tgi_light l;
        tgi_shadow_need nd;
        image im[3];
        int v, type = trial % 3, f, views = trial % 4 == 0 ? 3 : 1;
        char what[96];
        if (type == 0)
            l = make_light(TG_LIGHT_POINT, v3(rnd_in(0.2, 5.8), rnd_in(0.3, 2.95), rnd_in(0.2, 4.8)), v3(0, -1, 0), 1, 0);
        else if (type == 1)
            l = make_light(TG_LIGHT_SPOT, v3(rnd_in(0.2, 5.8), rnd_in(1, 2.95), rnd_in(0.2, 4.8)),
                           v3(rnd_in(-1, 1), rnd_in(-1, -0.2), rnd_in(-1, 1)), 1, rnd_in(15, 75) * DEG);
        else
            l = make_light(TG_LIGHT_DIRECTIONAL, v3(0, 0, 0), v3(rnd_in(-1, 1), rnd_in(-1, -0.1), rnd_in(-1, 1)), 1, 0);
        tgi_shadow_need_init(&nd, &l);
        for (v = 0; v < views; v++) {
            double eye[3], target[3];
            int outside = rnd() < 0.3;
            eye[0] = rnd_in(0.3, 5.7); eye[1] = rnd_in(0.3, 2.7); eye[2] = outside ? rnd_in(-6, -1) : rnd_in(0.3, 4.7);
            target[0] = rnd_in(0, 6); target[1] = rnd_in(0, 3); target[2] = rnd_in(0, 5);
            image_render(&im[v], g, NULL, eye, target, rnd_in(25, 100), 48, 36);
            tgi_shadow_map_size_rule(&nd, &l, &im[v].view, v3(g->lo[0], g->lo[1], g->lo[2]),
                                     v3(g->hi[0], g->hi[1], g->hi[2]), g->pos, g->n);
        }
        tgi_shadow_need_finish(&nd, 0);
        for (f = 0; f < nd.faces; f++) culled += nd.size[f] == 0;
        for (f = 0; f < nd.faces; f++)
            cropped += nd.window_set[f] && (l.type == TG_LIGHT_DIRECTIONAL ||
                                             dv(nd.window[f][2]) - dv(nd.window[f][0]) < 1.9 * dv(tgi_shadow_nominal_tan(&l)));
        for (v = 0; v < views; v++) {
            snprintf(what, sizeof what, "trial %d (%s light), view %d of %d", trial,
                     type == 0 ? "point" : type == 1 ? "spot" : "directional", v + 1, views);
            lookups += check_lookups(&im[v], &l, &nd, what);
            image_free(&im[v]);
        }
    }
    CHECK(lookups > 20000, "%d lookups checked", lookups);
    CHECK(culled >= 20, "%d faces culled in 40 point lights", culled);
    CHECK(cropped >= 20, "%d windows smaller than their face", cropped);
    free(g);
}

/* A culled, cropped map at the rule's sizes lights the room's pixels as a
 * full 512-texel cube does, but for shadow edges (within 2% of the pixels
 * facing the light), with a face culled. */
TEST(culled_map_lights_like_a_full_one)
{
    static const double eye[3] = { 3, 1.6, 0.3 }, target[3] = { 3.5, 1, 5 };
    geo *g = geo_new();
    tgi_light l = make_light(TG_LIGHT_POINT, v3(2.8, 2.5, 2.5), v3(0, -1, 0), 4, 0);
    tgi_shadow_need nd;
    tgi_shadow_map culled, full;
    const tgi_shadow_map *maps[1];
    void *mem_c, *mem_f;
    image im;
    int i, f, n = 0, differ = 0, present = 0;
    room(g);
    geo_bvh(g);
    image_render(&im, g, NULL, eye, target, 50, 160, 120);
    rule_need(&nd, &l, g, &im.view, 0);
    for (f = 0; f < 6; f++) present += nd.size[f] > 0;
    CHECK(present < 6, "the face toward the camera is culled (%d present)", present);
    mem_c = malloc(tgi_shadow_need_bytes(&nd));
    tgi_shadow_map_setup_need(&culled, &l, &nd, v3(g->lo[0], g->lo[1], g->lo[2]), v3(g->hi[0], g->hi[1], g->hi[2]), mem_c);
    tgi_shadow_map_render(&culled, g->pos, g->n);
    map_with(&full, &mem_f, g, &l, 512, TG_SHADOW_DEPTH16);
    maps[0] = &culled;
    image_direct(&im, &l, 1, maps, 0);
    maps[0] = &full;
    image_direct(&im, &l, 1, maps, 3);
    for (i = 0; i < im.w * im.h; i++) {
        double a = dv(im.out[0][i]), b = dv(im.out[3][i]);
        if (im.sky[i] || b <= 0) continue;
        n++;
        differ += fabs(a - b) > 0.5 * b;
    }
    CHECK(n > 1000 && differ <= n / 50, "%d of %d pixels differ by more than half", differ, n);
    free(mem_c); free(mem_f);
    image_free(&im);
    free(g);
}

/* ---- bytes, the animation's bounds, the choice ---- */

TEST(need_bytes_are_checked)
{
    tgi_light pt = make_light(TG_LIGHT_POINT, v3(0, 1, 0), v3(0, -1, 0), 1, 0);
    tgi_shadow_need nd;
    tgi_shadow_map sm;
    tgi_shadow_need_init(&nd, &pt);
    CHECK(nd.faces == 6 && nd.depth_bits == TG_SHADOW_DEPTH16, "a point light's need: %d faces, %d bits", nd.faces, nd.depth_bits);
    tgi_shadow_need_finish(&nd, 0);
    CHECK(tgi_shadow_need_bytes(&nd) == 0, "nothing seen, no bytes");
    tgi_shadow_map_setup_need(&sm, &pt, &nd, v3(-1, 0, -1), v3(1, 1, 1), NULL);
    CHECK(sm.faces == 0 && tgi_shadow_visibility(&sm, v3(0, 0, 0), v3(0, 1, 0)) == TG_ONE, "an empty map is lit");
    nd.seen[1] = nd.seen[4] = 1;
    tgi_shadow_need_finish(&nd, 100);
    CHECK(tgi_shadow_need_bytes(&nd) == 2u * 100 * 100 * 2, "two faces of 100: %zu", tgi_shadow_need_bytes(&nd));
    nd.depth_bits = TG_SHADOW_DEPTH32;
    CHECK(tgi_shadow_need_bytes(&nd) == 2u * 100 * 100 * sizeof(tg_real), "32 bits: %zu", tgi_shadow_need_bytes(&nd));
    nd.size[4] = TG_MIN_SHADOW_MAP - 1;
    CHECK(tgi_shadow_need_bytes(&nd) == 0, "a size below the limit");
    nd.size[4] = TG_MAX_SHADOW_MAP + 1;
    CHECK(tgi_shadow_need_bytes(&nd) == 0, "a size above the limit");
    /* the rule's densities (texels per unit across windows of side 1) are clamped to the limits */
    nd.size[4] = 0;
    nd.density[1] = TG_REAL_MAX; nd.density[4] = 0;
    nd.window_set[1] = nd.window_set[4] = 1;
    nd.window[1][0] = nd.window[1][1] = nd.window[4][0] = nd.window[4][1] = 0;
    nd.window[1][2] = nd.window[1][3] = nd.window[4][2] = nd.window[4][3] = TG_ONE;
    tgi_shadow_need_finish(&nd, 0);
    CHECK(nd.size[1] == TG_MAX_SHADOW_MAP && nd.size[4] == TG_MIN_SHADOW_MAP, "clamped: %d %d", nd.size[1], nd.size[4]);
    CHECK(tgi_shadow_need_bytes(&nd) > 0, "the largest face's bytes fit");
    /* whole faces (need_all after the rule) take the largest size the rule gave */
    nd.density[1] = TG_R(50.0f);
    nd.window_set[1] = 1;
    nd.window[1][0] = nd.window[1][1] = TG_R(-0.5f); nd.window[1][2] = nd.window[1][3] = TG_R(0.5f);
    tgi_shadow_need_all(&nd);
    nd.window_set[1] = 1;
    tgi_shadow_need_finish(&nd, 0);
    CHECK(nd.size[1] == 50 + 2 * TG_SHADOW_BORDER, "a windowed face: %d", nd.size[1]);
    CHECK(nd.size[0] == nd.size[1] && nd.size[5] == nd.size[1], "whole faces as large: %d %d", nd.size[0], nd.size[5]);
}

TEST(animation_bounds_hold_every_pose)
{
    static const char text[] =
        "camera pos 0 2 -6  target 0 1 0\n"
        "material m albedo 0.5 0.5 0.5\n"
        "quad p0 -3 0 -3  p1 -3 0 3  p2 3 0 3  p3 3 0 -3  material m\n"
        "box min -0.5 0 -0.5  max 0.5 1 0.5  material m  name mover\n"
        "object_key name mover t 0\n"
        "object_key name mover t 1 translate 4 2 0  rotate 0 0 1 90\n"
        "object_key name mover t 2 translate -2 5 1  rotate 1 0 0 45\n";
    static unsigned char arena_mem[1 << 20];
    tg_arena arena;
    tg_scene *s;
    tg_error err;
    tg_vec3 lo, hi, *pos, *nrm;
    int frames = 9, frame, i, outside = 0, beyond_rest = 0;
    tg_arena_init(&arena, arena_mem, sizeof arena_mem);
    CHECK(tg_scene_parse(text, sizeof text - 1, "anim", NULL, &arena, &s, &err) == TG_OK, "parse: %s", err.message);
    tgi_shadow_animation_bounds(s, frames, &lo, &hi);
    pos = (tg_vec3 *)malloc(3 * (size_t)s->tri_count * sizeof(tg_vec3));
    nrm = (tg_vec3 *)malloc(3 * (size_t)s->tri_count * sizeof(tg_vec3));
    for (frame = 0; frame < frames; frame++) {
        tgi_anim_pose(s, tgi_anim_time(s, frame, frames), pos, nrm);
        for (i = 0; i < 3 * s->tri_count; i++) {
            tg_vec3 p = pos[i];
            outside += p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x > hi.x || p.y > hi.y || p.z > hi.z;
            beyond_rest += p.x > s->bounds_max.x || p.y > s->bounds_max.y;
        }
    }
    CHECK(outside == 0, "%d posed vertices outside the animation's bounds", outside);
    CHECK(beyond_rest > 0, "the object leaves its rest bounds (else the test proves nothing)");
    free(pos); free(nrm);
}

TEST(choice_between_maps_and_rays)
{
    size_t pixels = 320 * 240, budget = pixels * TG_SHADOW_MAP_BYTES_PER_PIXEL;
    CHECK(tgi_shadow_choose(budget, 1000, pixels, 1) == TG_SHADOW_BY_MAP, "maps within the budget");
    CHECK(tgi_shadow_choose(budget + 1, 1000, pixels, 1) == TG_SHADOW_BY_RAYS, "maps over it, a smaller BVH: rays");
    CHECK(tgi_shadow_choose(budget + 1, budget + 2, pixels, 1) == TG_SHADOW_BY_MAP, "a larger BVH: maps");
    CHECK(tgi_shadow_choose(0, 0, 0, 1) == TG_SHADOW_BY_MAP, "no map bytes: maps");
    CHECK(tgi_shadow_choose(1, 0, (size_t)-1, 1) == TG_SHADOW_BY_MAP, "a budget past size_t: maps");
    /* four shadowed lights share it: a quarter each (0 or 1 light: the whole) */
    CHECK(tgi_shadow_light_budget(pixels, 4) == budget / 4 && tgi_shadow_light_budget(pixels, 0) == budget
          && tgi_shadow_light_budget(pixels, 1) == budget, "the lights' shares");
    CHECK(tgi_shadow_choose(budget / 4, 1000, pixels, 4) == TG_SHADOW_BY_MAP, "four lights: maps within a share");
    CHECK(tgi_shadow_choose(budget / 4 + 1, 1000, pixels, 4) == TG_SHADOW_BY_RAYS, "four lights: over a share, rays");
    CHECK(tgi_shadow_choose(budget / 4 + 1, budget, pixels, 4) == TG_SHADOW_BY_MAP, "four lights: a larger BVH, maps");
}

int main(void)
{
    RUN(depth16_reads_back_within_half_a_step);
    RUN(quantisation_step_is_in_the_bias);
    RUN(rule_gives_a_texel_per_pixel_under_the_sun);
    RUN(rule_gives_a_texel_per_pixel_from_the_light);
    RUN(faces_and_windows_hold_every_visible_receiver);
    RUN(culled_map_lights_like_a_full_one);
    RUN(need_bytes_are_checked);
    RUN(animation_bounds_hold_every_pose);
    RUN(choice_between_maps_and_rays);
    free(bvh_mem);
    return check_summary();
}
