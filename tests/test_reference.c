/* SPDX-License-Identifier: MIT */
/*
 * test_reference.c - the BVH and the ray-traced AO reference on exact cases.
 *
 * Scenes are built here from rectangles: an analytic per-pixel ray cast
 * (in double, hosted) makes the G-buffer, and the same rectangles split in
 * two triangles each feed the BVH, so nothing waits for the rasterizer or
 * view.c.  Exact answers:
 *   open plane            AO = 1, bent = normal
 *   floor + tall wall     AO = 1/2 near the crease on both surfaces
 *                         (unlimited distance: every direction towards the
 *                         other surface is blocked, the cosine-weighted half)
 *   inside a closed box   AO = 0
 *   near field            wall radiating L: E = pi L / 2 at the crease
 * The tolerance of the sampled estimates is 0.5 / sqrt(N): one standard
 * deviation of a random N-sample estimate of 1/2 (the stratified pattern does
 * better; measured errors are printed).
 */
#include "check.h"
#include "ao/ao.h"
#include "ao/bvh.h"
#include "ao/reference.h"
#include <stdlib.h>

#include "ao_fixture.h"
}

TEST(ray_triangle_basics)
{
    tg_vec3 v[3] = { tg_v3(0, 0, 0), tg_v3(TG_ONE, 0, 0), tg_v3(0, TG_ONE, 0) };
    tg_real t, u, w;
    /* straight down the -z axis onto the triangle at (0.25, 0.25) from z = 2 */
    CHECK(tgi_ray_triangle(v, tg_v3(TG_R(0.25f), TG_R(0.25f), TG_R(2.0f)), tg_v3(0, 0, TG_R(-1.0f)),
                          TG_R(10.0f), &t, &u, &w), "hit expected");
    CHECK_NEAR(check_d(t), 2.0, 1e-3);
    CHECK_NEAR(check_d(u), 0.25, 1e-3);
    CHECK_NEAR(check_d(w), 0.25, 1e-3);
    /* tmax shorter than the hit: no hit */
    CHECK(!tgi_ray_triangle(v, tg_v3(TG_R(0.25f), TG_R(0.25f), TG_R(2.0f)), tg_v3(0, 0, TG_R(-1.0f)),
                           TG_R(1.5f), &t, &u, &w), "tmax must cut");
    /* outside the triangle */
    CHECK(!tgi_ray_triangle(v, tg_v3(TG_R(0.75f), TG_R(0.75f), TG_R(2.0f)), tg_v3(0, 0, TG_R(-1.0f)),
                           TG_R(10.0f), &t, &u, &w), "miss expected");
    /* behind the origin */
    CHECK(!tgi_ray_triangle(v, tg_v3(TG_R(0.25f), TG_R(0.25f), TG_R(2.0f)), tg_v3(0, 0, TG_ONE),
                           TG_R(10.0f), &t, &u, &w), "behind");
    /* a huge triangle (edges 400 units) is handled in fixed point too */
    {
        tg_vec3 big[3] = { tg_v3(TG_R(-200.0f), 0, TG_R(-200.0f)), tg_v3(TG_R(200.0f), 0, TG_R(-200.0f)),
                           tg_v3(0, 0, TG_R(200.0f)) };
        CHECK(tgi_ray_triangle(big, tg_v3(TG_R(1.0f), TG_R(0.01f), TG_R(3.0f)), tg_v3(0, TG_R(-1.0f), 0),
                              TG_R(10.0f), &t, &u, &w), "big hit");
        CHECK_NEAR(check_d(t), 0.01, 2e-4);
    }
}

static unsigned rnd_seed = 12345u;
static double RND(void) { rnd_seed = rnd_seed * 1103515245u + 12345u; return ((rnd_seed >> 8) & 0xffff) / 65536.0; }

/* BVH closest hit equals the brute-force loop (over the same prepared
 * triangles) on a pile of random triangles, and the prepared-triangle test
 * agrees with the independent Moller-Trumbore test away from edges. */
TEST(bvh_matches_brute_force)
{
    enum { NT = 300, NR = 2000 };
    static tg_vec3 tri[3 * NT];
    int i, r, mism = 0, hits = 0, disagree = 0, compared = 0;
    size_t bytes = tgi_bvh_bytes(NT);
    unsigned char *mem = malloc(bytes);
    tgi_bvh b;
    for (i = 0; i < NT; i++) {
        double c[3];
        int j;
        c[0] = RND() * 8 - 4; c[1] = RND() * 8 - 4; c[2] = RND() * 8 - 4; /* one draw per statement: portable order */
        for (j = 0; j < 3; j++) {
            double px = c[0] + RND() - 0.5, py, pz;
            py = c[1] + RND() - 0.5;
            pz = c[2] + RND() - 0.5;
            tri[3 * i + j] = tg_v3(tg_from_float((float)px), tg_from_float((float)py), tg_from_float((float)pz));
        }
    }
    CHECK(tgi_bvh_build(&b, tri, NT, mem, bytes - 17) == -1, "too small memory must fail");
    CHECK(tgi_bvh_build(&b, tri, NT, mem, bytes) == 0, "build");
    CHECK(b.node_count <= 2 * NT, "node count %d", b.node_count);
    for (r = 0; r < NR; r++) {
        double d[3], ox, oy, oz;
        tg_vec3 o, dv;
        tgi_ray_hit h;
        tg_real best = TG_R(20.0f), t, u, w, t2, u2, w2;
        d[0] = RND() * 2 - 1; d[1] = RND() * 2 - 1; d[2] = RND() * 2 - 1;
        ox = RND() * 10 - 5; oy = RND() * 10 - 5; oz = RND() * 10 - 5;
        o = tg_v3(tg_from_float((float)ox), tg_from_float((float)oy), tg_from_float((float)oz));
        if (r % 2 == 1) { /* every other ray aims at a triangle's centroid, so many hit */
            const tg_vec3 *v = &tri[3 * (r % NT)];
            d[0] = ((double)tg_to_float(v[0].x) + (double)tg_to_float(v[1].x) + (double)tg_to_float(v[2].x)) / 3.0 - ox;
            d[1] = ((double)tg_to_float(v[0].y) + (double)tg_to_float(v[1].y) + (double)tg_to_float(v[2].y)) / 3.0 - oy;
            d[2] = ((double)tg_to_float(v[0].z) + (double)tg_to_float(v[1].z) + (double)tg_to_float(v[2].z)) / 3.0 - oz;
        }
        int bi = -1, got;
        if (r % 10 == 0) { d[0] = 0; d[1] = 0; } /* axis-parallel rays too */
        norm3(d);
        dv = tv(d);
        for (i = 0; i < NT; i++) {
            int slot = -1, k, a, m;
            for (k = 0; k < NT; k++) if (b.tri_index[k] == i) slot = k;
            a = tgi_bvh_tri_hit(&b.tris[slot], o, dv, TG_R(20.0f), &t, &u, &w);
            m = tgi_ray_triangle(tri + 3 * i, o, dv, TG_R(20.0f), &t2, &u2, &w2);
            if (a && t < best) { best = t; bi = i; }
            if (m && (check_d(u2) < 2e-3 || check_d(w2) < 2e-3 || check_d(u2) + check_d(w2) > 1 - 2e-3)) continue;
            compared++;
            if (a != m || (a && fabs(check_d(t) - check_d(t2)) > 1e-3 * (1 + check_d(t2)))) disagree++;
        }
        got = tgi_bvh_closest(&b, o, dv, TG_R(20.0f), &h);
        hits += got;
        if (got != (bi >= 0) || (got && (h.tri != bi || h.t != best))) mism++;
        if (tgi_bvh_occluded(&b, o, dv, TG_R(20.0f)) != (bi >= 0)) mism++;
    }
    CHECK(mism == 0, "%d BVH mismatches of %d rays", mism, NR);
    /* Q16.16: the two formulations round differently for rays within the
     * 2^-12 edge widening of a triangle; a few in a million may disagree */
    CHECK(disagree <= (TG_FIXED ? compared / 100000 : 0), "prepared vs Moller-Trumbore: %d disagreements of %d tests", disagree, compared);
    CHECK(hits > NR / 10, "too few hits to mean anything: %d", hits);
    free(mem);
}

/* Huge and tiny triangles keep their precision in both number types. */
TEST(prepared_triangle_scales)
{
    static const float scales[] = { 0.01f, 1.0f, 400.0f };
    int s;
    for (s = 0; s < 3; s++) {
        double k = (double)scales[s];
        tg_vec3 v[3] = { tg_v3(0, 0, 0), tg_v3(tg_from_float((float)k), 0, 0), tg_v3(0, tg_from_float((float)k), 0) };
        tgi_bvh_tri tr;
        tg_real t, u, w;
        tgi_bvh_tri_prepare(&tr, v);
        /* aim at barycentrics (0.2, 0.3) from 2k above */
        CHECK(tgi_bvh_tri_hit(&tr, tg_v3(tg_from_float((float)(0.2 * k)), tg_from_float((float)(0.3 * k)), tg_from_float((float)(2 * k))),
                             tg_v3(0, 0, TG_R(-1.0f)), TG_REAL_MAX, &t, &u, &w), "scale %g: hit", k);
        /* tolerance: 2e-4 plus the input's own quantisation (two Q16.16 ulps of the coordinates / k) */
        CHECK_NEAR(check_d(u), 0.2, 2e-4 + 3.1e-5 / k);
        CHECK_NEAR(check_d(w), 0.3, 2e-4 + 3.1e-5 / k);
        CHECK_NEAR(check_d(t), 2.0 * k, 2e-4 * k + 4e-5);
        /* just outside the hypotenuse: a miss */
        CHECK(!tgi_bvh_tri_hit(&tr, tg_v3(tg_from_float((float)(0.5 * k)), tg_from_float((float)(0.505 * k)), tg_from_float((float)k)),
                              tg_v3(0, 0, TG_R(-1.0f)), TG_REAL_MAX, &t, &u, &w), "scale %g: miss", k);
    }
}

TEST(open_plane)
{
    static scene s;
    static outputs o;
    static const double eye[3] = { 0.5, 2.0, 3.0 }, target[3] = { 0, 0, -1 };
    tgi_reference_params p;
    ao_pass io;
    int i, n = 0;
    double worst_ao = 0, worst_angle = 0;
    memset(&s, 0, sizeof s);
    add_rect(&s, -BIG, 0, BIG, 2 * BIG, 0, 0, 0, 0, -2 * BIG);
    raster(&s, eye, target, 60.0);
    build_bvh(&s);
    p = reference_params(&s, TG_AO_INFINITE);
    io_for(&io, &s, &o, 0);
    io_with_cone(&io);
    tgi_reference_rows(&p, &io.g, &io.rad, &io.out, 0, H);
    io_read(&io);
    for (i = 0; i < W * H; i++) {
        double c;
        if (s.sky[i]) continue;
        n++;
        CHECK_NEAR(check_d(o.cone[i]), 3.14159265358979 / 2, 2e-3);   /* HBIL eq. 12 at AO = 1 */
        worst_ao = fmax(worst_ao, fabs(check_d(o.ao[i]) - 1.0));
        c = check_d(o.bx[i]) * check_d(s.nx[i]) + check_d(o.by[i]) * check_d(s.ny[i]) + check_d(o.bz[i]) * check_d(s.nz[i]);
        worst_angle = fmax(worst_angle, acos(fmin(1.0, c)) * 180 / 3.14159265358979);
    }
    printf("# open plane: %d pixels, worst |AO - 1| %.4g, worst bent angle %.3g deg\n", n, worst_ao, worst_angle);
    CHECK(n > W * H / 4, "plane must cover the view");
    CHECK(worst_ao == 0, "AO must be exactly 1 on an open plane: %g", worst_ao);
    CHECK(worst_angle < 1.0, "bent normal off by %g degrees", worst_angle);
}

/* Pixels within `band` of the crease (x = 0, y = 0), on floor or wall. */
static int near_crease(const scene *s, int i, double band, int surface)
{
    return !s->sky[i] && s->wrect[i] == surface && s->wpos[i][0] + s->wpos[i][1] < band &&
           fabs(s->wpos[i][2]) < 10;
}

TEST(groove_half)
{
    static scene s;
    static outputs o;
    tgi_reference_params p;
    ao_pass io;
    int i, surf, n[2] = { 0, 0 };
    double worst[2] = { 0, 0 }, tol = 0.5 / sqrt(256.0);
    groove(&s);
    p = reference_params(&s, TG_AO_INFINITE);
    reference_run(&io, &p, &s, &o);
    for (surf = 0; surf < 2; surf++)
        for (i = 0; i < W * H; i++) {
            if (!near_crease(&s, i, 0.3, surf)) continue;
            n[surf]++;
            worst[surf] = fmax(worst[surf], fabs(check_d(o.ao[i]) - 0.5));
        }
    printf("# groove: floor %d px worst |AO - 1/2| %.4f, wall %d px worst %.4f (tolerance %.4f)\n",
           n[0], worst[0], n[1], worst[1], tol);
    CHECK(n[0] >= 3 && n[1] >= 3, "crease must be in view on both surfaces: %d %d", n[0], n[1]);
    CHECK(worst[0] <= tol, "floor %g", worst[0]);
    CHECK(worst[1] <= tol, "wall %g", worst[1]);
    /* bent normal on the floor at the crease leans away from the wall:
     * mean of the cosine-weighted half space x > 0 is (4/(3pi), ... ) -> the
     * normalised bent makes atan((4/3pi)/(1/2)... checked by sign only here */
    for (i = 0; i < W * H; i++)
        if (near_crease(&s, i, 0.3, 0)) CHECK(check_d(o.bx[i]) > 0.3, "floor bent x %g", check_d(o.bx[i]));
    for (i = 0; i < W * H; i++)
        if (near_crease(&s, i, 0.3, 1)) CHECK(check_d(o.by[i]) > 0.3, "wall bent y %g", check_d(o.by[i]));
}

/* The bent normal of a quarter space has a closed form: the cosine-weighted
 * mean of directions with x > 0 about n = +y is (2/3 * 2/pi... ) - computed
 * here numerically in double to avoid transcribing it: E[l] over the
 * cosine-weighted hemisphere restricted to l.x > 0. */
TEST(groove_bent_exact)
{
    static scene s;
    static outputs o;
    tgi_reference_params p;
    ao_pass io;
    int i, k, m = 0;
    double sx = 0, sy = 0, expect, worst = 0;
    /* cosine-weighted: l = (r cos a, sqrt(1 - r^2), r sin a) with r^2 uniform, a uniform */
    for (k = 0; k < 200000; k++) {
        double r = sqrt((k % 400 + 0.5) / 400.0), a = 2 * 3.14159265358979 * ((k / 400) + 0.5) / 500.0;
        double lx = r * cos(a), ly = sqrt(1 - r * r);
        if (lx <= 0) continue;
        sx += lx; sy += ly; m++;
    }
    expect = atan2(sx / m, sy / m);
    groove(&s);
    p = reference_params(&s, TG_AO_INFINITE);
    reference_run(&io, &p, &s, &o);
    for (i = 0; i < W * H; i++) {
        double ang;
        if (!near_crease(&s, i, 0.3, 0)) continue;
        ang = atan2(check_d(o.bx[i]), check_d(o.by[i]));
        worst = fmax(worst, fabs(ang - expect));
    }
    printf("# groove bent: expected tilt %.2f deg, worst error %.2f deg\n", expect * 180 / 3.14159265358979,
           worst * 180 / 3.14159265358979);
    CHECK(worst * 180 / 3.14159265358979 < 3.0, "bent tilt error %g deg", worst * 180 / 3.14159265358979);
}

/* With a finite radius the groove's occlusion fades with distance from the
 * crease: a floor point farther than the radius from the wall is open. */
TEST(groove_radius_cutoff)
{
    static scene s;
    static outputs o;
    tgi_reference_params p;
    ao_pass io;
    int i, far_n = 0, near_n = 0;
    groove(&s);
    p = reference_params(&s, TG_R(0.5f));
    reference_run(&io, &p, &s, &o);
    for (i = 0; i < W * H; i++) {
        if (s.sky[i] || s.wrect[i] != 0) continue;
        if (s.wpos[i][0] > 0.55) { far_n++; CHECK(o.ao[i] == TG_ONE, "open beyond the radius: %g at x %g", check_d(o.ao[i]), s.wpos[i][0]); }
        if (s.wpos[i][0] < 0.05) { near_n++; CHECK(check_d(o.ao[i]) < 0.6, "crease %g", check_d(o.ao[i])); }
    }
    CHECK(far_n > 10 && near_n > 0, "pixels %d %d", far_n, near_n);
}

TEST(closed_box)
{
    static scene s;
    static outputs o;
    static const double eye[3] = { 0.1, 0.6, 0.2 }, target[3] = { 0.5, -1, -0.4 };
    tgi_reference_params p;
    ao_pass io;
    int i, n = 0;
    double worst = 0;
    memset(&s, 0, sizeof s);
    /* the six faces of [-1, 1]^3, each as a rectangle */
    add_rect(&s, -1, -1, -1, 2, 0, 0, 0, 0, 2);  /* bottom */
    add_rect(&s, -1, 1, -1, 0, 0, 2, 2, 0, 0);   /* top */
    add_rect(&s, -1, -1, -1, 0, 2, 0, 2, 0, 0);  /* back z = -1 */
    add_rect(&s, -1, -1, 1, 2, 0, 0, 0, 2, 0);   /* front z = 1 */
    add_rect(&s, -1, -1, -1, 0, 0, 2, 0, 2, 0);  /* left x = -1 */
    add_rect(&s, 1, -1, -1, 0, 2, 0, 0, 0, 2);   /* right x = 1 */
    raster(&s, eye, target, 90.0);
    build_bvh(&s);
    p = reference_params(&s, TG_AO_INFINITE);
    reference_run(&io, &p, &s, &o);
    for (i = 0; i < W * H; i++) {
        if (s.sky[i]) continue;
        n++;
        worst = fmax(worst, check_d(o.ao[i]));
    }
    printf("# closed box: %d pixels, worst AO %.4g (exact: every ray must hit)\n", n, worst);
    CHECK(n == W * H, "the box must fill the view: %d", n);
    /* exactly 0: one ray slipping through a crack between two triangles
     * (fixed point, before the widened edge test) gave 1/256 */
    CHECK(worst == 0, "AO inside a closed box must be 0: %g", worst);
}

/* Near field: the wall radiates L, the floor nothing.  At the crease half of
 * the cosine-weighted hemisphere sees the wall: E = pi L / 2. */
static tg_vec3 wall_radiance(void *user, int tri, tg_vec3 pos, tg_vec3 nrm)
{
    (void)user; (void)pos; (void)nrm;
    return tri >= 2 ? tg_v3(TG_ONE, TG_R(0.5f), TG_R(0.25f)) : tg_v3(0, 0, 0);
}

TEST(near_field_half)
{
    static scene s;
    static outputs o;
    static tg_real rr[W * H], rg[W * H], rb[W * H];
    tgi_reference_params p;
    ao_pass io;
    int i, n = 0;
    double worst = 0, tol = 3.14159265358979 * 0.5 / sqrt(256.0), want = 3.14159265358979 / 2;
    groove(&s);
    p = reference_params(&s, TG_AO_INFINITE);
    p.radiance = wall_radiance;
    io_for(&io, &s, &o, 1);
    tgi_reference_rows(&p, &io.g, &io.rad, &io.out, 0, H);
    io_read(&io);
    for (i = 0; i < W * H; i++) {
        if (!near_crease(&s, i, 0.3, 0)) continue;
        n++;
        worst = fmax(worst, fabs(check_d(o.nr[i]) - want));
        /* the colour's ratios, within the storage's rounding of each channel */
        CHECK_NEAR(check_d(o.ng[i]), 0.5 * check_d(o.nr[i]), 1e-3 + 1.5 * sf_rgb_rounding(check_d(o.nr[i])));
        CHECK_NEAR(check_d(o.nb[i]), 0.25 * check_d(o.nr[i]), 1e-3 + 1.25 * sf_rgb_rounding(check_d(o.nr[i])));
    }
    printf("# near field: %d floor px, worst |E - pi/2| %.4f (tolerance %.4f)\n", n, worst, tol);
    CHECK(n >= 3, "pixels %d", n);
    CHECK(worst <= tol, "E error %g", worst);
    /* the view-buffer fallback sees only visible hits: a lower bound, finite */
    for (i = 0; i < W * H; i++) {
        rr[i] = s.wrect[i] == 1 ? TG_ONE : 0; rg[i] = rr[i]; rb[i] = rr[i];
    }
    {
        static outputs o2;
        p.radiance = 0;
        io_for(&io, &s, &o2, 1);
        io_radiance(&io, rr, rg, rb);
        tgi_reference_rows(&p, &io.g, &io.rad, &io.out, 0, H);
        io_read(&io);
        int seen = 0;
        for (i = 0; i < W * H; i++) {
            if (s.sky[i]) continue;
            CHECK(o2.ao[i] == o.ao[i], "ao differs between near modes");
            if (s.wrect[i] != 0) continue;   /* wall pixels may pick up crease pixels of the wall itself */
            seen += near_crease(&s, i, 0.3, 0) && o2.nr[i] > 0;
            CHECK(o2.nr[i] >= 0 && check_d(o2.nr[i]) <= check_d(o.nr[i]) + 1e-3, "fallback %g > %g",
                  check_d(o2.nr[i]), check_d(o.nr[i]));
        }
        CHECK(seen >= 3, "the visible wall must light the crease through the view buffer: %d", seen);
    }
}

TEST(deterministic)
{
    static scene s;
    static outputs a, b;
    tgi_reference_params p;
    ao_pass io;
    groove(&s);
    tgi_reference_defaults(&p);
    p.bvh = &bvh; p.tri_nrm = s.nrm; p.samples = 64;
    io_for(&io, &s, &a, 0);
    tgi_reference_rows(&p, &io.g, &io.rad, &io.out, 0, H);
    io_read(&io);
    io_for(&io, &s, &b, 0);
    tgi_reference_rows(&p, &io.g, &io.rad, &io.out, 0, H / 2);          /* two row ranges give the same image */
    io_read(&io);
    tgi_reference_rows(&p, &io.g, &io.rad, &io.out, H / 2, H);
    io_read(&io);
    CHECK(memcmp(a.ao, b.ao, sizeof a.ao) == 0, "ao differs");
    CHECK(memcmp(a.bx, b.bx, sizeof a.bx) == 0, "bent differs");
}

/* Rays from inside a closed box aimed exactly at the edges its triangles
 * share (the box's twelve edges and each face's diagonal) and at its
 * corners: every one must hit.  The box is turned and moved off the axes so
 * that rounding puts an aimed-at point a hair outside one or more of the
 * triangles that share it; the 2^-12 edge margin of the prepared triangle
 * test (src/ao/bvh.c) must catch it on each of the three edges. */
static void turned_rect(scene *s, double m[3][3], const double c[3], const double p[3], const double u[3],
                        const double v[3])
{
    double q[3][3];
    int i;
    for (i = 0; i < 3; i++) {
        q[0][i] = c[i] + m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2];
        q[1][i] = m[i][0] * u[0] + m[i][1] * u[1] + m[i][2] * u[2];
        q[2][i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    }
    add_rect(s, q[0][0], q[0][1], q[0][2], q[1][0], q[1][1], q[1][2], q[2][0], q[2][1], q[2][2]);
}

TEST(closed_box_edges_hit)
{
    static scene s;
    static const double face[6][3][3] = {  /* the same six faces as closed_box: p, u, v */
        { { -1, -1, -1 }, { 2, 0, 0 }, { 0, 0, 2 } }, { { -1, 1, -1 }, { 0, 0, 2 }, { 2, 0, 0 } },
        { { -1, -1, -1 }, { 0, 2, 0 }, { 2, 0, 0 } }, { { -1, -1, 1 }, { 2, 0, 0 }, { 0, 2, 0 } },
        { { -1, -1, -1 }, { 0, 0, 2 }, { 0, 2, 0 } }, { { 1, -1, -1 }, { 0, 2, 0 }, { 0, 0, 2 } } };
    static const double centre[3] = { 0.31, -0.17, 0.23 };
    double m[3][3], ax[3] = { 1, 2, 3 }, ang = 0.7, c = cos(ang), sn = sin(ang);
    int o, k, e, j, i, rays = 0, missed = 0;
    norm3(ax);
    for (i = 0; i < 3; i++)   /* Rodrigues: rotation by ang about ax */
        for (j = 0; j < 3; j++)
            m[i][j] = (i == j ? c : 0) + (1 - c) * ax[i] * ax[j] +
                      sn * (i == j ? 0 : ((j == (i + 1) % 3) ? -ax[3 - i - j] : ax[3 - i - j]));
    memset(&s, 0, sizeof s);
    for (k = 0; k < 6; k++) turned_rect(&s, m, centre, face[k][0], face[k][1], face[k][2]);
    build_bvh(&s);
    for (o = 0; o < 24; o++) {
        double org[3];
        org[0] = RND() * 1.6 - 0.8; org[1] = RND() * 1.6 - 0.8; org[2] = RND() * 1.6 - 0.8;
        for (i = 0; i < 3; i++) org[i] = centre[i] + m[i][0] * org[0] + m[i][1] * org[1] + m[i][2] * org[2];
        for (k = 0; k < s.nrect * 2; k++)
            for (e = 0; e < 3; e++)
                for (j = 0; j < 16; j++) {  /* j = 0: the corners */
                    const tg_vec3 *a = &s.tri[3 * k + e], *b = &s.tri[3 * k + (e + 1) % 3];
                    double f = j / 16.0, d[3];
                    d[0] = check_d(a->x) + f * (check_d(b->x) - check_d(a->x)) - org[0];
                    d[1] = check_d(a->y) + f * (check_d(b->y) - check_d(a->y)) - org[1];
                    d[2] = check_d(a->z) + f * (check_d(b->z) - check_d(a->z)) - org[2];
                    norm3(d);
                    rays++;
                    if (!tgi_bvh_occluded(&bvh, tv(org), tv(d), TG_R(10.0f))) missed++;
                }
    }
    printf("# closed box edges: %d of %d rays at shared edges and corners escaped\n", missed, rays);
    CHECK(missed == 0, "%d of %d rays escaped the closed box through an edge or corner", missed, rays);
}

int main(void)
{
    RUN(ray_triangle_basics);
    RUN(bvh_matches_brute_force);
    RUN(prepared_triangle_scales);
    RUN(open_plane);
    RUN(groove_half);
    RUN(groove_bent_exact);
    RUN(groove_radius_cutoff);
    RUN(closed_box);
    RUN(near_field_half);
    RUN(deterministic);
    RUN(closed_box_edges_hit);
    free(bvh_mem);
    return check_summary();
}
