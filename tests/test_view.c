/* SPDX-License-Identifier: MIT */
/*
 * test_view.c - the camera (src/raster/view.c) for the number type of this
 * build: orthonormal basis with screen-right = forward x up, degenerate up
 * vectors (looking straight down/up) resolved deterministically, the
 * projection constants, the pixel-centre convention, and round trips
 * project(unproject(p)) and view_to_world(world_to_view(p)).
 */
#include "check.h"
#include "raster/view.h"


#define ULP CHECK_ULP

static unsigned rng_state = 7;
static double rnd(void) { return check_rnd(&rng_state); }
static tg_real rr(double lo, double hi) { return tg_from_float((float)(lo + (hi - lo) * rnd())); }
static tg_vec3 R3(double x, double y, double z) { return tg_v3(tg_from_float((float)x), tg_from_float((float)y), tg_from_float((float)z)); }
static double dot_d(tg_vec3 a, tg_vec3 b) { return check_exact(a.x) * check_exact(b.x) + check_exact(a.y) * check_exact(b.y) + check_exact(a.z) * check_exact(b.z); }

static void check_basis(const tgi_view *v, const char *what)
{
    tg_vec3 c = tgi_v3_cross(v->right, v->up);
    CHECK(fabs(dot_d(v->right, v->right) - 1) <= 4 * ULP && fabs(dot_d(v->up, v->up) - 1) <= 4 * ULP &&
          fabs(dot_d(v->forward, v->forward) - 1) <= 4 * ULP, "%s: basis not unit", what);
    CHECK(fabs(dot_d(v->right, v->up)) <= 6 * ULP && fabs(dot_d(v->right, v->forward)) <= 6 * ULP &&
          fabs(dot_d(v->up, v->forward)) <= 6 * ULP, "%s: basis not orthogonal (%.3g %.3g %.3g)", what,
          dot_d(v->right, v->up), dot_d(v->right, v->forward), dot_d(v->up, v->forward));
    /* view space x right, y up, z forward in a right-handed world: right x up = -forward */
    CHECK(fabs(check_exact(c.x) + check_exact(v->forward.x)) <= 8 * ULP && fabs(check_exact(c.y) + check_exact(v->forward.y)) <= 8 * ULP &&
          fabs(check_exact(c.z) + check_exact(v->forward.z)) <= 8 * ULP, "%s: right x up != -forward", what);
}

static int vec_is(tg_vec3 a, double x, double y, double z, double tol)
{
    return fabs(check_exact(a.x) - x) <= tol && fabs(check_exact(a.y) - y) <= tol && fabs(check_exact(a.z) - z) <= tol;
}

TEST(basis_conventions)
{
    tgi_view v;
    /* the classic camera: at +Z looking at the origin, up +Y */
    tgi_view_make(&v, R3(0, 0, 5), R3(0, 0, 0), R3(0, 1, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    check_basis(&v, "classic");
    CHECK(vec_is(v.right, 1, 0, 0, 0) && vec_is(v.up, 0, 1, 0, 0) && vec_is(v.forward, 0, 0, -1, 0),
          "classic camera basis: right +X, up +Y, forward -Z");
    /* a non-unit, tilted up vector is orthogonalised */
    tgi_view_make(&v, R3(1, 2, 3), R3(-2, 0.5, -1), R3(0.3, 4, 0.2), TG_R(0.8f), TG_R(0.1f), TG_R(100.0f), 64, 48);
    check_basis(&v, "tilted");
    CHECK(dot_d(v.up, R3(0.3, 4, 0.2)) > 0, "up keeps the side of the given up");
}

TEST(basis_random)
{
    int i;
    for (i = 0; i < 20000; i++) {
        tgi_view v;
        tg_vec3 eye = R3(rnd() * 200 - 100, rnd() * 200 - 100, rnd() * 200 - 100);
        tg_vec3 target = R3(rnd() * 200 - 100, rnd() * 200 - 100, rnd() * 200 - 100);
        tg_vec3 up = R3(rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1);
        if (i % 4 == 0) up = tgi_v3_sub(target, eye); /* degenerate on purpose */
        tgi_view_make(&v, eye, target, up, rr(0.2, 2.5), TG_R(0.1f), TG_R(500.0f), 320, 240);
        check_basis(&v, "random");
        {
            tg_vec3 d = tgi_v3_normalize(tgi_v3_sub(target, eye));
            CHECK(vec_is(v.forward, check_exact(d.x), check_exact(d.y), check_exact(d.z), 2 * ULP), "forward is the view direction");
        }
    }
}

TEST(degenerate_up)
{
    tgi_view v, w;
    /* straight down with up +Y: right +X, screen-up -Z (the limit of tilting down) */
    tgi_view_make(&v, R3(0, 5, 0), R3(0, 0, 0), R3(0, 1, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    check_basis(&v, "down");
    CHECK(vec_is(v.forward, 0, -1, 0, 0), "down: forward -Y");
    CHECK(vec_is(v.right, 1, 0, 0, 0), "down: right +X");
    CHECK(vec_is(v.up, 0, 0, -1, 0), "down: up -Z");
    /* up -Y gives the same frame (deterministic) */
    tgi_view_make(&w, R3(0, 5, 0), R3(0, 0, 0), R3(0, -1, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    CHECK(memcmp(&v.right, &w.right, sizeof v.right) == 0 && memcmp(&v.up, &w.up, sizeof v.up) == 0, "up -Y same frame");
    /* zero up is treated like a degenerate one */
    tgi_view_make(&w, R3(0, 5, 0), R3(0, 0, 0), R3(0, 0, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    CHECK(memcmp(&v.right, &w.right, sizeof v.right) == 0 && memcmp(&v.up, &w.up, sizeof v.up) == 0, "up 0 same frame");
    /* straight up: right +X, screen-up +Z */
    tgi_view_make(&v, R3(0, -5, 0), R3(0, 0, 0), R3(0, 1, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    check_basis(&v, "up");
    CHECK(vec_is(v.right, 1, 0, 0, 0) && vec_is(v.up, 0, 0, 1, 0), "up: right +X, up +Z");
    /* looking along +X with up +X: world +Y is used */
    tgi_view_make(&v, R3(0, 0, 0), R3(3, 0, 0), R3(1, 0, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    check_basis(&v, "along x");
    CHECK(vec_is(v.up, 0, 1, 0, 0) && vec_is(v.right, 0, 0, 1, 0), "along +X: up +Y, right +Z");
    /* eye == target: a valid frame, forward -Z */
    tgi_view_make(&v, R3(1, 1, 1), R3(1, 1, 1), R3(0, 1, 0), TG_R(1.0f), TG_R(0.1f), TG_R(100.0f), 320, 240);
    check_basis(&v, "eye == target");
}

TEST(projection_constants)
{
    tgi_view v;
    double fov = 60.0 * CHECK_PI / 180.0, f = 1.0 / tan(fov / 2);
    tgi_view_make(&v, R3(0, 0, 0), R3(0, 0, -1), R3(0, 1, 0), tg_from_float((float)fov), TG_R(0.1f), TG_R(100.0f), 320, 240);
    CHECK_NEAR(check_exact(v.tan_half_fov_y), tan(fov / 2), 2 * ULP);
    CHECK_NEAR(check_exact(v.aspect), 320.0 / 240.0, ULP);
    CHECK_NEAR(check_exact(v.focal_y), f, 4 * ULP * f);
    CHECK_NEAR(check_exact(v.focal_x), f * 240.0 / 320.0, 4 * ULP * f);
    CHECK_NEAR(check_exact(v.pixels_per_unit), 120.0 * f, 600 * ULP);
    CHECK(v.width == 320 && v.height == 240, "size");
    CHECK(v.znear == TG_R(0.1f) && v.zfar == TG_R(100.0f), "near/far kept");
}

TEST(pixel_convention)
{
    tgi_view v;
    tg_real sx, sy;
    double fov = 1.2, t = tan(fov / 2), aspect = 320.0 / 240.0;
    tg_vec3 p;
    tgi_view_make(&v, R3(0, 0, 0), R3(0, 0, -1), R3(0, 1, 0), tg_from_float((float)fov), TG_R(0.1f), TG_R(100.0f), 320, 240);
    /* the optical axis hits the centre of the screen, (w/2, h/2) */
    tgi_view_project(&v, tg_v3(0, 0, TG_R(3.0f)), &sx, &sy);
    CHECK(sx == TG_R(160.0f) && sy == TG_R(120.0f), "axis -> (160, 120), got (%.6f, %.6f)", check_exact(sx), check_exact(sy));
    /* the top-left corner (0,0) is the frustum corner (-tan*aspect, +tan) at depth 1 */
    p = tgi_view_unproject(&v, 0, 0, TG_ONE);
    CHECK(fabs(check_exact(p.x) + t * aspect) <= 1e-4 && fabs(check_exact(p.y) - t) <= 1e-4 && p.z == TG_ONE,
          "corner (0,0) -> (%.6f %.6f %.6f), want (%.6f %.6f 1)", check_exact(p.x), check_exact(p.y), check_exact(p.z), -t * aspect, t);
    /* bottom-right corner */
    p = tgi_view_unproject(&v, TG_R(320.0f), TG_R(240.0f), TG_R(2.0f));
    CHECK(fabs(check_exact(p.x) - 2 * t * aspect) <= 2e-4 && fabs(check_exact(p.y) + 2 * t) <= 2e-4, "corner (w,h)");
    /* pixel (0,0)'s centre is at (0.5, 0.5): left of and above the axis, inside the frustum */
    p = tgi_view_unproject(&v, TG_R(0.5f), TG_R(0.5f), TG_ONE);
    CHECK(check_exact(p.x) < 0 && check_exact(p.y) > 0 && check_exact(p.x) > -t * aspect && check_exact(p.y) < t, "pixel (0,0) centre top-left");
    /* a world point above the camera lands in the upper half (sy < h/2), right -> sx > w/2 */
    tgi_view_project(&v, tgi_view_world_to_view(&v, R3(1, 1, -5)), &sx, &sy);
    CHECK(check_exact(sx) > 160 && check_exact(sy) < 120, "(+x, +y) world -> right, up on screen");
    /* depth is view z: a point 5 in front */
    p = tgi_view_world_to_view(&v, R3(2, -1, -5));
    CHECK(p.z == TG_R(5.0f), "depth = view z = 5, got %.6f", check_exact(p.z));
    /* behind the camera: finite */
    tgi_view_project(&v, tg_v3(TG_ONE, TG_ONE, tg_neg(TG_ONE)), &sx, &sy);
    CHECK(tg_isfinite(sx) && tg_isfinite(sy), "behind the camera stays finite");
}

TEST(round_trips)
{
    int i;
    double worst_px = 0, worst_w = 0, worst_rel_px = 0;
    for (i = 0; i < 50000; i++) {
        tgi_view v;
        tg_real sx = rr(0, 320), sy = rr(0, 240), depth = rr(0.1, 100), sx2, sy2;
        tg_vec3 pv, pw, pv2, back;
        tgi_view_make(&v, R3(rnd() * 20 - 10, rnd() * 20 - 10, rnd() * 20 - 10),
                     R3(rnd() * 20 - 10, rnd() * 20 - 10, rnd() * 20 - 10), R3(0, 1, 0), rr(0.3, 2.0),
                     TG_R(0.1f), TG_R(200.0f), 320, 240);
        pv = tgi_view_unproject(&v, sx, sy, depth);
        CHECK(pv.z == depth, "unproject keeps depth");
        tgi_view_project(&v, pv, &sx2, &sy2);
        {
            double e = fmax(fabs(check_exact(sx2) - check_exact(sx)), fabs(check_exact(sy2) - check_exact(sy)));
            /* one ulp of the view-space point is ppu / depth pixels */
            double ulp_px = ULP * (check_exact(v.pixels_per_unit) / check_exact(depth) + 1);
            if (e > worst_px) worst_px = e;
            if (e / ulp_px > worst_rel_px) worst_rel_px = e / ulp_px;
        }
        /* view -> world -> view */
        pw = tgi_view_view_to_world(&v, pv);
        pv2 = tgi_view_world_to_view(&v, pw);
        {
            double e = fmax(fabs(check_exact(pv2.x) - check_exact(pv.x)), fmax(fabs(check_exact(pv2.y) - check_exact(pv.y)), fabs(check_exact(pv2.z) - check_exact(pv.z))));
            double m = 1 + fabs(check_exact(pv.z)) + fabs(check_exact(pv.x)) + fabs(check_exact(pv.y));
            if (e / m > worst_w) worst_w = e / m;
        }
        /* directions */
        back = tgi_view_dir_to_world(&v, tgi_view_dir_to_view(&v, v.forward));
        CHECK(vec_is(back, check_exact(v.forward.x), check_exact(v.forward.y), check_exact(v.forward.z), 8 * ULP), "dir round trip");
    }
#if TG_FIXED
    printf("measured view fixed: project(unproject) worst %.3g px (%.3g ulps of the view-space point); "
           "view->world->view worst %.3g (relative)\n", worst_px, worst_rel_px, worst_w);
#else
    printf("measured view float: project(unproject) worst %.3g px; view->world->view worst %.3g (relative)\n",
           worst_px, worst_w);
#endif
#if TG_FIXED
    CHECK(worst_rel_px <= 2.0, "project(unproject) off by %.4g point ulps", worst_rel_px);
    CHECK(worst_w <= 2e-4, "world round trip off by %.4g", worst_w);
#else
    CHECK(worst_px <= 2e-4, "project(unproject) off by %.4g px", worst_px);
    CHECK(worst_w <= 2e-6, "world round trip off by %.4g", worst_w);
#endif
}

int main(void)
{
    RUN(basis_conventions);
    RUN(basis_random);
    RUN(degenerate_up);
    RUN(projection_constants);
    RUN(pixel_convention);
    RUN(round_trips);
    return check_summary();
}
