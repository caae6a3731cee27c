/* SPDX-License-Identifier: MIT */
/*
 * test_ssilvb.c - the visibility-bitmask technique (src/ao/ssilvb.h,
 * Therrien et al. 2023) on the ray-cast G-buffers of tests/ao_fixture.h,
 * in both number types:
 *   - the bit range of a front/back pair (the paper's floor/ceil rounding)
 *     and the portable popcount, exactly;
 *   - an open plane: ao exactly 1 at every pixel, the bent normal GTAO's;
 *   - the groove (floor meeting a tall wall): the floor's ao against the
 *     exact cosine-weighted occlusion of an infinite wall within the radius,
 *     per pixel, with the bound the 32 sectors allow;
 *   - a thin plank standing in front of a wall, with a gap behind it larger
 *     than the thickness: the wall's pixels beside it see light behind the
 *     plank as the reference does, where GTAO (an infinitely thick depth
 *     buffer) darkens them;
 *   - the near field under a uniform radiance L on every sender that faces
 *     the receiver: E = pi L (1 - ao), the gathered sectors being exactly the
 *     occluded ones;
 *   - further depth layers (the nearest back face, the surface behind
 *     it): a box floating over a floor in front of a wall, the floor's ao
 *     nearer the ray-cast reference with each layer;
 *   - hard cases (grazing views, depth discontinuities, zero and huge
 *     thickness, radius 0, one and three layers): finite, ao in [0, 1], E
 *     in [0, pi L];
 *   - deterministic under any row split.
 */
#include "check.h"
#include "ao/ao.h"
#include "ao/bvh.h"
#include "ao/reference.h"
#include "ao/gtao.h"
#include "ao/ssilvb.h"
#include <stdlib.h>

#include "ao_fixture.h"
}

#define PI 3.14159265358979

static void open_plane(scene *s, const double eye[3], const double target[3])
{
    memset(s, 0, sizeof *s);
    add_rect(s, -BIG, 0, BIG, 2 * BIG, 0, 0, 0, 0, -2 * BIG);
    raster(s, eye, target, 60.0);
}

static tgi_ssilvb_params vb_params(double radius, double thickness)
{
    tgi_ssilvb_params p;
    tgi_ssilvb_defaults(&p);
    p.radius = tg_from_float((float)radius);
    p.thickness = tg_from_float((float)thickness);
    return p;
}

static void run_vb(ao_pass *io, const tgi_ssilvb_params *p, int y0, int y1)
{
    tgi_ssilvb_rows(p, &io->g, &io->rad, &io->out, y0, y1);
}

/* ssilvb over the whole image of s into o (no near field), read back. */
static void vb_image(ao_pass *io, scene *s, outputs *o, const tgi_ssilvb_params *p)
{
    io_for(io, s, o, 0);
    run_vb(io, p, 0, H);
    io_read(io);
}

TEST(sector_bits_and_popcount)
{
    uint32_t b = 1u;
    int k, naive;
    CHECK(tgi_ssilvb_sector_bits(0, 0) == 0, "an empty range sets nothing");
    CHECK(tgi_ssilvb_sector_bits(TG_ONE, TG_ONE) == 0, "the end of the half circle sets nothing (no shift by 32)");
    CHECK(tgi_ssilvb_sector_bits(0, TG_ONE) == 0xffffffffu, "the whole half circle");
    CHECK(tgi_ssilvb_sector_bits(TG_R(0.5f), TG_ONE) == 0xffff0000u, "the upper half: %08x",
          (unsigned)tgi_ssilvb_sector_bits(TG_R(0.5f), TG_ONE));
    CHECK(tgi_ssilvb_sector_bits(TG_R(-3.0f), TG_R(0.25f)) == 0x000000ffu, "clamped to [0, 1]");
    CHECK(tgi_ssilvb_sector_bits(TG_R(0.25f), TG_R(0.2578125f)) == 0x100u, "a range of 1/4 sector sets one: %08x",
          (unsigned)tgi_ssilvb_sector_bits(TG_R(0.25f), TG_R(0.2578125f)));
    /* the paper's rounding: start floor(8.5) = 8, ceil(9.75 - 8.5) = 2 sectors */
    CHECK(tgi_ssilvb_sector_bits(TG_R(0.265625f), TG_R(0.3046875f)) == 0x300u, "%08x",
          (unsigned)tgi_ssilvb_sector_bits(TG_R(0.265625f), TG_R(0.3046875f)));
    CHECK(tgi_ssilvb_sector_bits(TG_R(0.3046875f), TG_R(0.265625f)) == 0x300u, "either order");
    CHECK(tgi_ssilvb_popcount(0) == 0 && tgi_ssilvb_popcount(0xffffffffu) == 32, "popcount ends");
    for (k = 0; k < 2000; k++) {
        uint32_t v = b;
        naive = 0;
        while (v) { naive += (int)(v & 1u); v >>= 1; }
        CHECK(tgi_ssilvb_popcount(b) == naive, "popcount %08x: %d, want %d", (unsigned)b, tgi_ssilvb_popcount(b), naive);
        b = b * 1664525u + 1013904223u;
    }
}

TEST(open_plane_is_exactly_open)
{
    static const double eyes[3][3] = { { 0.5, 2.0, 3.0 }, { 0.0, 0.3, 4.0 }, { 3.0, 0.08, 0.0 } };
    static const double target[3] = { 0, 0, -1 };
    static scene s;
    static outputs o, g;
    ao_pass io;
    tgi_gtao_params gp;
    int e, i;
    for (e = 0; e < 3; e++) {   /* from above, low, grazing */
        tgi_ssilvb_params p = vb_params(1, 0.5);
        int n = 0, not_one = 0;
        double worst_bent = 0, worst_gtao = 0;
        open_plane(&s, eyes[e], target);
        io_for(&io, &s, &g, 0);
        tgi_gtao_defaults(&gp);
        tgi_gtao_rows(&gp, &io.g, &io.out, 0, H);
        io_read(&io);
        vb_image(&io, &s, &o, &p);
        for (i = 0; i < W * H; i++) {
            double c, cg;
            if (s.sky[i]) continue;
            n++;
            if (o.ao[i] != TG_ONE) not_one++;
            c = check_d(o.bx[i]) * check_d(g.bx[i]) + check_d(o.by[i]) * check_d(g.by[i]) + check_d(o.bz[i]) * check_d(g.bz[i]);
            cg = check_d(g.bx[i]) * check_d(s.nx[i]) + check_d(g.by[i]) * check_d(s.ny[i]) + check_d(g.bz[i]) * check_d(s.nz[i]);
            worst_bent = fmax(worst_bent, acos(fmin(1.0, c)) * 180 / PI);
            worst_gtao = fmax(worst_gtao, acos(fmin(1.0, cg)) * 180 / PI);
        }
        printf("# open plane, eye %d: %d pixels, %d with ao != 1; bent normal off GTAO's by up to %.2f deg (GTAO's off "
               "the normal by %.2f: the slice quadrature)\n", e, n, not_one, worst_bent, worst_gtao);
        CHECK(n > 100, "the plane is seen (%d pixels)", n);
        CHECK(not_one == 0, "eye %d: %d pixels not exactly 1", e, not_one);
        /* open half circles: the same integrals as GTAO's, up to the 2x8-bit storage */
        CHECK(worst_bent < 1.0, "eye %d: bent normal %g deg off GTAO's", e, worst_bent);
    }
}

/* Exact cosine-weighted AO of a floor point at distance d from an infinite
 * wall x = 0 (floor y = 0, x >= 0), rays cut off at r: 1 - (1/pi) int over
 * the directions that reach the wall within r of cos(theta) d omega.  A
 * direction (sin t cos f, cos t, sin t sin f), f from the wall's normal
 * direction -x, reaches it after d / (sin t cos f). */
static double wall_ao(double d, double r)
{
    int it, ip, nt = 400, np = 400;
    double blocked = 0;
    if (d >= r) return 1;
    for (it = 0; it < nt; it++) {
        double t = (it + 0.5) * (PI / 2) / nt, st = sin(t);
        for (ip = 0; ip < np; ip++) {
            double f = -PI / 2 + (ip + 0.5) * PI / np;
            if (st * cos(f) * r > d) blocked += cos(t) * st;
        }
    }
    return 1 - blocked * (PI / 2 / nt) * (PI / np) / PI;
}

TEST(groove_against_the_exact_wall)
{
    static scene s;
    static outputs o;
    ao_pass io;
    tgi_ssilvb_params p = vb_params(1, 1000);   /* a wall: thicker than anything within reach */
    int i, n = 0;
    double se = 0, bias = 0, worst = 0;
    groove(&s);
    vb_image(&io, &s, &o, &p);
    for (i = 0; i < W * H; i++) {
        double want, d;
        if (s.sky[i] || s.wrect[i] != 0 || fabs(s.wpos[i][2]) > 10 || s.wpos[i][0] > 1.5) continue;
        want = wall_ao(s.wpos[i][0], 1.0);
        d = check_d(o.ao[i]) - want;
        se += d * d; bias += d; n++;
        worst = fmax(worst, fabs(d));
    }
    printf("# groove floor within 1.5 of the wall, %d pixels: rmse %.4f, bias %+.4f, worst %.3f against the exact wall\n",
           n, sqrt(se / n), bias / n, worst);
    CHECK(n > 100, "floor pixels %d", n);
    /* 4 slices of 8 steps (gtao's own quadrature error on this groove is
     * ~0.04) and the paper's rounding, up to one sector (pi/32 of the half
     * circle) too dark at a horizon */
    CHECK(sqrt(se / n) < 0.08, "rmse %g", sqrt(se / n));
    CHECK(fabs(bias / n) < 0.05, "bias %g", bias / n);
}

/* A wall z = -1 facing the camera, a plank (0.3 wide, tall, no thickness)
 * standing 0.8 in front of it: light reaches the wall behind the plank. */
static void plank(scene *s)
{
    static const double eye[3] = { 0.0, 0.0, 2.5 }, target[3] = { 0, 0, -1 };
    memset(s, 0, sizeof *s);
    add_rect(s, -BIG, -BIG, -1, 2 * BIG, 0, 0, 0, 2 * BIG, 0);   /* the wall, normal +z */
    add_rect(s, -0.15, -BIG, -0.2, 0.3, 0, 0, 0, 2 * BIG, 0);    /* the plank */
    raster(s, eye, target, 60.0);
    build_bvh(s);
}

TEST(thin_plank_lets_light_through_behind_it)
{
    static scene s;
    static outputs ref, vb, gt;
    ao_pass io;
    tgi_reference_params rp;
    tgi_gtao_params gp;
    tgi_ssilvb_params p = vb_params(1.5, 0.1);
    double m_ref = 0, m_vb = 0, m_gt = 0;
    int i, n = 0;
    plank(&s);
    tgi_reference_defaults(&rp);
    rp.bvh = &bvh; rp.tri_nrm = s.nrm; rp.radius = TG_R(1.5f);
    io_for(&io, &s, &ref, 0);
    tgi_reference_rows(&rp, &io.g, &io.rad, &io.out, 0, H);
    io_read(&io);
    vb_image(&io, &s, &vb, &p);
    tgi_gtao_defaults(&gp);
    gp.radius = TG_R(1.5f);
    io_for(&io, &s, &gt, 0);
    tgi_gtao_rows(&gp, &io.g, &io.out, 0, H);
    io_read(&io);
    for (i = 0; i < W * H; i++) {   /* the wall's pixels beside the plank */
        double x = fabs(s.wpos[i][0]);
        if (s.sky[i] || s.wrect[i] != 0 || x < 0.2 || x > 0.6 || fabs(s.wpos[i][1]) > 0.8) continue;
        m_ref += check_d(ref.ao[i]); m_vb += check_d(vb.ao[i]); m_gt += check_d(gt.ao[i]); n++;
    }
    m_ref /= n; m_vb /= n; m_gt /= n;
    printf("# plank 0.3 wide, 0.8 in front of the wall, thickness 0.1, %d wall pixels beside it: mean ao "
           "reference %.3f, ssilvb %.3f, gtao %.3f\n", n, m_ref, m_vb, m_gt);
    CHECK(n > 30, "wall pixels beside the plank: %d", n);
    CHECK(fabs(m_vb - m_ref) < 0.06, "ssilvb %g against the reference %g", m_vb, m_ref);
    CHECK(m_gt < m_ref - 0.15, "gtao darkens behind the plank: %g against the reference %g", m_gt, m_ref);
    CHECK(m_vb > m_gt + 0.15, "the bitmask lets light through where gtao does not: %g vs %g", m_vb, m_gt);
}

TEST(near_field_gathers_the_occluded_sectors)
{
    static scene s;
    static outputs o;
    static tg_real lr[W * H], lg[W * H], lb[W * H];
    ao_pass io;
    tgi_ssilvb_params p = vb_params(1, 0.3);
    int i, n = 0, occluded = 0;
    double worst = 0;
    groove(&s);
    for (i = 0; i < W * H; i++) { lr[i] = TG_R(0.5f); lg[i] = TG_R(1.0f); lb[i] = TG_R(2.0f); }
    io_for(&io, &s, &o, 1);
    io_radiance(&io, lr, lg, lb);
    run_vb(&io, &p, 0, H);
    io_read(&io);
    for (i = 0; i < W * H; i++) {
        double a = check_d(o.ao[i]), want = PI * (1 - a), d;
        if (s.sky[i]) continue;
        n++;
        if (a < 0.9) occluded++;
        /* the AO is stored in 8 bits (1/510), the irradiance as RGB9E5 (2^-9 relative) */
        d = fabs(check_d(o.ng[i]) - want);
        worst = fmax(worst, d);
        CHECK(d < PI / 500 + want / 256 + (TG_FIXED ? 3e-3 : 1e-5), "pixel %d: E %g, pi L (1 - ao) %g", i,
              check_d(o.ng[i]), want);
        CHECK(fabs(check_d(o.nr[i]) * 2 - check_d(o.ng[i])) < 1e-2 + check_d(o.ng[i]) / 128 &&
              fabs(check_d(o.nb[i]) - 2 * check_d(o.ng[i])) < 2e-2 + check_d(o.ng[i]) / 128,
              "pixel %d: E proportional to L per channel", i);
    }
    printf("# groove, uniform L on every sender: |E - pi L (1 - ao)| up to %.2g over %d pixels (%d with ao < 0.9)\n",
           worst, n, occluded);
    CHECK(occluded > 50, "the groove has occluded pixels: %d", occluded);
}

/* ---- further depth layers (request.depth_layers, raster.h) ---- */

/* The box [lo, hi] as six rectangles facing outward (normal u x v). */
static void add_box(scene *s, const double lo[3], const double hi[3])
{
    int a, side, k;
    for (a = 0; a < 3; a++)
        for (side = 0; side < 2; side++) {
            int u = (a + 1) % 3, w = (a + 2) % 3;
            double p[3], eu[3] = { 0, 0, 0 }, ev[3] = { 0, 0, 0 }, n[3];
            for (k = 0; k < 3; k++) p[k] = lo[k];
            p[a] = side ? hi[a] : lo[a];
            eu[u] = hi[u] - lo[u];
            ev[w] = hi[w] - lo[w];
            cross3(eu, ev, n);
            if ((n[a] > 0) != (side == 1)) {   /* swap to face outward */
                double t[3];
                memcpy(t, eu, sizeof t); memcpy(eu, ev, sizeof t); memcpy(ev, t, sizeof t);
            }
            add_rect(s, p[0], p[1], p[2], eu[0], eu[1], eu[2], ev[0], ev[1], ev[2]);
        }
}

/* A box floating over a floor, 0.3 in front of a wall, seen from above
 * and in front. */
static void floating_box(scene *s)
{
    static const double eye[3] = { 0.3, 1.7, 2.4 }, target[3] = { 0, 0.2, -1.2 };
    static const double lo[3] = { -0.5, 0.35, -1.6 }, hi[3] = { 0.5, 1.05, -0.6 };
    memset(s, 0, sizeof *s);
    add_rect(s, -BIG, 0, BIG, 2 * BIG, 0, 0, 0, 0, -2 * BIG);   /* floor, normal +y */
    add_rect(s, -BIG, 0, -1.9, 2 * BIG, 0, 0, 0, BIG, 0);       /* wall, normal +z */
    add_box(s, lo, hi);
    raster(s, eye, target, 60.0);
    build_bvh(s);
}

/* The ray-cast G-buffer's further layers (scene.back, .behind) in the
 * build's storage, planes the view io->g then reads. */
static void io_with_layers(ao_pass *io, const scene *s, int layers)
{
#if TG_WIDE_STORAGE
    static tg_real back[W * H], behind[W * H];
#else
    static uint8_t back[W * H];   /* codes against the pixel's depth, as the rasterizer keeps them */
    static uint32_t behind[W * H];
#endif
    int i;
    for (i = 0; i < W * H; i++) {
        tg_real b = tg_from_float((float)s->back[i]), c = tg_from_float((float)s->behind[i]);
#if TG_WIDE_STORAGE
        back[i] = b; behind[i] = c;
#else
        back[i] = s->back[i] > 0 ? tgi_back_code(tgi_gv_depth(&io->g, (size_t)i), b) : TGI_BACK_NONE;
        behind[i] = s->behind[i] > 0 ? tgi_depth_pack(c) : 0;
#endif
    }
    io->g.store.back_depth = back;
    io->g.store.behind_depth = layers >= 3 ? behind : NULL;
}

/* A box floating over the floor in front of a wall, the floor's ao
 * against the ray-cast reference: the depth buffer alone takes the box as
 * solid from its front to infinity (the floor beside and under it too
 * dark); with its back faces (two layers) the box ends where it ends, but
 * the wall hidden behind it is gone (too bright); with the surface behind
 * the back faces (three) the wall is there again.  Each layer brings the
 * floor nearer the reference, and three are within the bound. */
TEST(depth_layers_against_the_reference)
{
    static scene s;
    static outputs ref, o[3];
    ao_pass io;
    tgi_reference_params rp;
    tgi_ssilvb_params p = vb_params(1.2, 1e4);
    double err[3] = { 0, 0, 0 }, bias[3] = { 0, 0, 0 };
    int i, k, n = 0;
    floating_box(&s);
    p.slices = 8;
    p.steps = 32;
    rp = reference_params(&s, TG_R(1.2f));
    rp.samples = 1024;
    reference_run(&io, &rp, &s, &ref);
    for (k = 0; k < 3; k++) {
        io_for(&io, &s, &o[k], 0);
        if (k > 0) io_with_layers(&io, &s, k + 1);
        run_vb(&io, &p, 0, H);
        io_read(&io);
    }
    for (i = 0; i < W * H; i++) {   /* the floor near the box */
        if (s.sky[i] || s.wrect[i] != 0 || fabs(s.wpos[i][0]) > 1.6 || s.wpos[i][2] > 0.6) continue;
        for (k = 0; k < 3; k++) {
            double e = check_d(o[k].ao[i]) - check_d(ref.ao[i]);
            err[k] += e * e;
            bias[k] += e;
        }
        n++;
    }
    for (k = 0; k < 3; k++) { err[k] = sqrt(err[k] / n); bias[k] /= n; }
    printf("# a box floating over the floor, %d floor pixels near it, ao against the reference, rmse / bias: "
           "one layer %.3f / %+.3f, two %.3f / %+.3f, three %.3f / %+.3f\n", n, err[0], bias[0], err[1], bias[1],
           err[2], bias[2]);
    CHECK(n > 300, "floor pixels near the box: %d", n);
    CHECK(err[1] < 0.8 * err[0] && err[2] < 0.8 * err[1], "each layer closer: %g, %g, %g", err[0], err[1], err[2]);
    CHECK(err[2] < 0.05 && fabs(bias[2]) < 0.02, "three layers: rmse %g, bias %g", err[2], bias[2]);
}

/* The groove's floor within 1.5 of the wall with the scene's further
 * layers (s->back, s->behind) against the exact wall (radius 1): the
 * pixels counted, *rmse and *bias. */
static int groove_floor_with_layers(scene *s, const tgi_ssilvb_params *p, int layers, double *rmse,
                                    double *bias)
{
    static outputs o;
    ao_pass io;
    int i, n = 0;
    double se = 0, sum = 0;
    io_for(&io, s, &o, 0);
    io_with_layers(&io, s, layers);
    run_vb(&io, p, 0, H);
    io_read(&io);
    for (i = 0; i < W * H; i++) {
        double d;
        if (s->sky[i] || s->wrect[i] != 0 || fabs(s->wpos[i][2]) > 10 || s->wpos[i][0] > 1.5) continue;
        d = check_d(o.ao[i]) - wall_ao(s->wpos[i][0], 1.0);
        se += d * d; sum += d; n++;
    }
    *rmse = n ? sqrt(se / n) : 1;
    *bias = n ? sum / n : 1;
    return n;
}

/* Every surface a twosided sheet (its back face at its own depth, as the
 * rasterizer's back layer holds one): the constant thickness stands in,
 * as without layers, and the groove's floor sees the wall as the exact
 * one-layer test above does (a sheet taken as no thickness would occlude
 * nothing: ao 1 everywhere). */
TEST(twosided_sheets_keep_the_constant_thickness)
{
    static scene s;
    tgi_ssilvb_params p = vb_params(1, 1000);
    int i, n;
    double rmse, bias;
    groove(&s);
    for (i = 0; i < W * H; i++) { s.back[i] = s.sky[i] ? 0 : check_d(s.depth[i]); s.behind[i] = 0; }
    n = groove_floor_with_layers(&s, &p, 2, &rmse, &bias);
    printf("# groove of twosided sheets, %d floor pixels: rmse %.4f against the exact wall\n", n, rmse);
    CHECK(n > 100 && rmse < 0.08, "%d pixels, rmse %g", n, rmse);
}

/* The groove again with further layers, its surfaces one-sided (no back
 * face behind them: tgi_gv_back_depth 0): a sample of a boundary, like a
 * room's wall, closes its side of the slice from its angle down to the
 * tangent plane, as a horizon does (ssilvb.c, march_layers): the wall
 * between it and the corner is there too.  Taken instead as solid along
 * the sample's view ray and cut at the radius, the directions below that
 * segment stayed open near the corner, too bright: measured rmse 0.0475 /
 * bias +0.0169 before, 0.0463 / +0.0111 after (the one-layer test above,
 * the horizon's: 0.0479 / +0.0123), both number types. */
TEST(one_sided_boundaries_close_like_a_horizon)
{
    static scene s;
    tgi_ssilvb_params p = vb_params(1, 0.1);   /* a thin constant thickness: the layers decide */
    int i, n;
    double rmse, bias;
    groove(&s);
    for (i = 0; i < W * H; i++) { s.back[i] = 0; s.behind[i] = 0; }
    n = groove_floor_with_layers(&s, &p, 3, &rmse, &bias);
    printf("# groove of one-sided boundaries, three layers, %d floor pixels: rmse %.4f, bias %+.4f against the exact "
           "wall\n", n, rmse, bias);
    CHECK(n > 100 && rmse < 0.06 && fabs(bias) < 0.014, "%d pixels, rmse %g, bias %g", n, rmse, bias);
}

/* tgi_ssilvb_params.to_edge (HBIL over the layers, hbil_passes.c): with a
 * radius far past the screen (a room's diagonal) a side's samples spread
 * over the part of the slice on the screen, not over the radius, where most
 * would fall past the edge.  The groove's floor with a radius of 10 (some
 * 120 to 200 pixels, the image 48 wide), 8 samples a side, against the
 * same bitmask marched densely (TG_AO_MAX_SAMPLES samples over the radius):
 * measured rmse 0.016 with it, 0.067 without, both number types. */
TEST(samples_spread_over_the_screen_with_to_edge)
{
    static scene s;
    static outputs o, dense;
    ao_pass io;
    double err[2];
    int i, n = 0, edge;
    tgi_ssilvb_params p = vb_params(10, 0.1);
    groove(&s);
    for (i = 0; i < W * H; i++) { s.back[i] = 0; s.behind[i] = 0; }
    p.steps = TG_AO_MAX_SAMPLES;
    io_for(&io, &s, &dense, 0);
    io_with_layers(&io, &s, 3);
    run_vb(&io, &p, 0, H);
    io_read(&io);
    for (edge = 0; edge < 2; edge++) {
        double se = 0;
        p.to_edge = edge;
        p.steps = 8;
        io_for(&io, &s, &o, 0);
        io_with_layers(&io, &s, 3);
        run_vb(&io, &p, 0, H);
        io_read(&io);
        n = 0;
        for (i = 0; i < W * H; i++) {
            double d;
            if (s.sky[i]) continue;
            d = check_d(o.ao[i]) - check_d(dense.ao[i]);
            se += d * d; n++;
        }
        err[edge] = sqrt(se / n);
    }
    printf("# groove, radius 10, 8 samples a side, %d pixels: rmse %.4f with to_edge, %.4f without, against "
           "%d samples\n", n, err[1], err[0], TG_AO_MAX_SAMPLES);
    CHECK(n > 100 && err[1] < 0.5 * err[0], "rmse %g with to_edge, %g without", err[1], err[0]);
}

TEST(hard_cases_stay_finite)
{
    static const double eye_graze[3] = { 3.0, 0.06, 0.4 }, target_graze[3] = { -2, 0.0, -1 };
    static scene s;
    static outputs o;
    static tg_real lr[W * H];
    static const double thick[] = { 0, 0.05, 1e4 };
    static const double radii[] = { 0, 0.3, 1000 };
    ao_pass io;
    int sc, a, b, i, layers, bad = 0;
    for (i = 0; i < W * H; i++) lr[i] = TG_ONE;
    for (sc = 0; sc < 3; sc++) {
        if (sc == 0) groove(&s);
        else if (sc == 1) plank(&s);   /* depth discontinuities at the plank's edges */
        else {
            memset(&s, 0, sizeof s);
            add_rect(&s, 0, 0, BIG, BIG, 0, 0, 0, 0, -2 * BIG);
            add_rect(&s, 0, 0, -BIG, 0, BIG, 0, 0, 0, 2 * BIG);
            raster(&s, eye_graze, target_graze, 60.0);   /* the floor at a grazing angle */
        }
        for (a = 0; a < 6; a++)   /* one depth layer, then three */
            for (b = 0; b < 3; b++) {
                tgi_ssilvb_params p = vb_params(radii[b], thick[a % 3]);
                layers = a < 3 ? 1 : 3;
                io_for(&io, &s, &o, 1);
                if (layers > 1) io_with_layers(&io, &s, layers);
                io_radiance(&io, lr, lr, lr);
                run_vb(&io, &p, 0, H);
                io_read(&io);
                for (i = 0; i < W * H; i++) {
                    double ao = check_d(o.ao[i]), e = check_d(o.nr[i]);
                    double bl = sqrt(check_d(o.bx[i]) * check_d(o.bx[i]) + check_d(o.by[i]) * check_d(o.by[i]) +
                                     check_d(o.bz[i]) * check_d(o.bz[i]));
                    if (!(ao >= 0 && ao <= 1) || !(e >= 0 && e <= PI * 1.01) || !(fabs(bl - 1) < 2e-3)) {
                        if (bad++ < 5)
                            CHECK(0, "scene %d, %d layers, thickness %g radius %g pixel %d: ao %g, E %g, |bent| %g", sc,
                                  layers, thick[a % 3], radii[b], i, ao, e, bl);
                    }
                    if (b == 0 && ao != 1) bad++;   /* radius 0: nothing is within reach */
                }
            }
    }
    CHECK(bad == 0, "%d bad values", bad);
}

TEST(deterministic_under_row_splits)
{
    static scene s;
    static outputs a, b;
    static tg_real lr[W * H];
    ao_pass io;
    tgi_ssilvb_params p = vb_params(1, 0.3);
    int i;
    groove(&s);
    for (i = 0; i < W * H; i++) lr[i] = TG_R(0.7f);
    io_for(&io, &s, &a, 1);
    io_radiance(&io, lr, lr, lr);
    run_vb(&io, &p, 0, H);
    io_read(&io);
    io_for(&io, &s, &b, 1);
    io_radiance(&io, lr, lr, lr);
    run_vb(&io, &p, 0, 7);
    run_vb(&io, &p, 7, H);
    io_read(&io);
    CHECK(memcmp(a.ao, b.ao, sizeof a.ao) == 0 && memcmp(a.bx, b.bx, sizeof a.bx) == 0 &&
          memcmp(a.nr, b.nr, sizeof a.nr) == 0, "the same bits under a row split");
}

/* tgi_ssilvb_half_circle_u (a polynomial acos) against the exact u =
 * (side acos c - gamma) / pi + 1/2 over 201 x 2 x 41 directions and
 * normal angles: within 5e-5 (float) or 1e-4 (Q16.16, its inputs rounded
 * to 2^-16 and acos' slope near |c| = 1), and the sector it falls in
 * (floor(32 u), the bit tgi_ssilvb_sector_bits starts at) the exact one
 * but where the exact u is that close to a sector's boundary, then one
 * off at most. */
TEST(half_circle_u_without_acos)
{
    int i, side, k, n = 0, off = 0, far = 0;
    double worst = 0, tol = TG_FIXED ? 1e-4 : 5e-5;
    for (k = 0; k <= 40; k++) {
        double gamma = -1.5 + 3.0 * k / 40;
        tg_real g = tg_from_float((float)gamma);
        for (side = -1; side <= 1; side += 2)
            for (i = 0; i <= 200; i++) {
                tg_real c = tg_from_float((float)(-1.0 + 2.0 * i / 200 + (i % 7) * 1e-4 * (i < 200)));
                double cd = check_d(c), want = (side * acos(fmin(1, fmax(-1, cd))) - check_d(g)) / PI + 0.5;
                double got = check_d(tgi_ssilvb_half_circle_u(c, side, g)), d = fabs(got - want);
                int sw = (int)floor(32 * want), sg = (int)floor(32 * got);
                n++;
                worst = fmax(worst, d);
                if (d > tol) far++;
                if (sg != sw) {
                    double edge = fabs(32 * want - floor(32 * want + 0.5)) / 32;
                    if (edge > tol || abs(sg - sw) > 1) far++;
                    else off++;
                }
            }
    }
    printf("# half circle u without acos: %d directions, worst %.2g of the half circle, %d one sector off at a "
           "boundary\n", n, worst, off);
    CHECK(far == 0, "%d directions off by more than %g or in the wrong sector away from a boundary (worst %g)", far,
          tol, worst);
}

/* tgi_ssilvb_horizon_bits (the sector of a horizon among the slice's
 * boundaries' cosines, no angle) against tgi_ssilvb_sector_bits at the
 * exact u = (side acos c - gamma) / pi + 1/2 (from u to the end of its
 * side) over 401 x 2 x 61 directions and normal angles in (-pi/2, pi/2):
 * the same bits, or where the exact u is within 1e-4 of a sector boundary
 * (the rounding of c and of the bounds; in Q16.16 4e-3, acos(1 - 2^-16)
 * being 0.0055) the bits of u on one side of it. */
TEST(horizon_bits_without_the_angle)
{
    int i, side, k, n = 0, edge = 0, bad = 0;
    double tol = TG_FIXED ? 4e-3 : 1e-4;
    for (k = 0; k <= 60; k++) {
        double gamma = -1.55 + 3.1 * k / 60;
        tg_real g = tg_from_float((float)gamma), bound[TG_SSILVB_SECTORS + 1];
        int kz;
        tgi_ssilvb_bounds(g, tg_from_float((float)cos(gamma)), tg_from_float((float)sin(gamma)), bound, &kz);
        for (side = -1; side <= 1; side += 2)
            for (i = 0; i <= 400; i++) {
                tg_real c = tg_from_float((float)(-1.0 + 2.0 * i / 400 + (i % 5) * 3e-4 * (i < 400)));
                double u = (side * acos(fmin(1, fmax(-1, check_d(c)))) - gamma) / PI + 0.5;
                uint32_t got = tgi_ssilvb_horizon_bits(c, side, bound, kz), want, lo, hi;
#define VB_BITS(x) (side > 0 ? tgi_ssilvb_sector_bits(tg_from_float((float)(x)), TG_ONE) \
                             : tgi_ssilvb_sector_bits(0, tg_from_float((float)(x))))
                want = VB_BITS(u);
                lo = VB_BITS(u - tol);
                hi = VB_BITS(u + tol);
#undef VB_BITS
                n++;
                if (got == want) continue;
                if (got == lo || got == hi) edge++;
                else bad++;
            }
    }
    printf("# horizon bits without the angle: %d directions, %d at a sector boundary one off, %d wrong\n", n, edge,
           bad);
    CHECK(bad == 0 && edge < n / 100, "%d directions in the wrong sectors, %d at a boundary", bad, edge);
}

/* The slice point as written before the march kept its rays: the sample's
 * distance with tg_div's tests, its pixel unprojected with its own two
 * divisions (tgi_ao_unproject), no pixel skipped. */
static int plain_slice_point(const tgi_gview *g, const tgi_ao_slice_pixel *px, int s, int steps, tg_real sdx,
                             tg_real sdy, tg_vec3 *h, int *j)
{
    tg_real t_px = tg_div(tg_mul(tg_add(tg_from_int(s), px->jitter), px->r_px), tg_from_int(steps)), fx, fy;
    int qx, qy;
    if (t_px < TG_ONE) return 0;
    fx = tg_add(tg_add(tg_from_int(px->x), TG_R(0.5f)), tg_mul(sdx, t_px));
    fy = tg_add(tg_add(tg_from_int(px->y), TG_R(0.5f)), tg_mul(sdy, t_px));
    qx = tgi_ao_pixel_of(fx, g->width);
    qy = tgi_ao_pixel_of(fy, g->height);
    if (qx < 0 || qy < 0) return -1;
    *j = (int)tgi_gv_index(g, qx, qy);
    if (tgi_gv_is_sky(g, *j)) return 0;
    *h = tgi_v3_sub(tgi_ao_unproject(g->camera, qx * g->step + g->offset_x, qy * g->step + g->offset_y,
                                     tgi_gv_depth(g, *j)), px->pv);
    if (px->shift) *h = tg_v3(tg_ldexp(h->x, px->shift), tg_ldexp(h->y, px->shift), tg_ldexp(h->z, px->shift));
    return 1;
}

/* tgi_ao_slice_point with a march's rays (every slice march: the last
 * column's and row's ray kept, a division each saved, and a sample in the
 * pixel of the one before skipped, as it adds nothing) against the plain
 * one (plain_slice_point), over every pixel of the groove, 8 directions,
 * 16 steps and two radii (shifted in Q16.16): the same result, offset and
 * index bits, the ray tgi_ao_unproject's at depth 1, or 0 exactly where
 * the sample's pixel is the last one read. */
TEST(slice_point_rays_keep_the_bits)
{
    static scene s;
    static outputs o;
    static const float radii[2] = { 0.3f, 3.0f };
    ao_pass io;
    tg_vec3 dirs[8];
    int x, y, k, r, st, n = 0, skipped = 0, bad = 0;
    groove(&s);
    io_for(&io, &s, &o, 0);
    tgi_ao_circle(TG_R(6.2831853f), 8, dirs);
    for (r = 0; r < 2; r++) {
        tg_real radius = TG_R(radii[r]);
        int shift = tgi_ao_unit_shift(radius), steps = 16;
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                int i = (int)tgi_gv_index(&io.g, x, y);
                tgi_ao_slice_pixel px;
                if (!tgi_ao_slice_pixel_at(&io.g, &io.out, x, y, i, radius, steps, TG_R(0.37f), shift, &px)) continue;
                for (k = 0; k < 8; k++) {
                    tgi_ao_rays rays = TGI_AO_RAYS_NONE;
                    int last = -1;
                    for (st = 0; st < steps; st++) {
                        tg_vec3 h0, h1;
                        int j0 = -1, j1 = -1;
                        int g0 = plain_slice_point(&io.g, &px, st, steps, dirs[k].x, dirs[k].y, &h0, &j0);
                        int g1 = tgi_ao_slice_point(&io.g, &px, st, steps, dirs[k].x, dirs[k].y, &h1, &j1, &rays);
                        if (g0 < 0) { bad += g1 != g0; break; }
                        if (g0 == 0) { bad += g1 != 0; continue; }
                        n++;
                        if (j0 == last) { skipped++; bad += g1 != 0; continue; }
                        last = j0;
                        if (g1 != 1 || j1 != j0 || memcmp(&h0, &h1, sizeof h0) != 0) { bad++; continue; }
                        {
                            int qx = (j0 % io.g.row_stride) / io.g.pixel_stride, qy = j0 / io.g.row_stride;
                            tg_vec3 want = tgi_ao_unproject(io.g.camera, qx, qy, TG_ONE);
                            bad += memcmp(&want, &rays.ray, sizeof want) != 0;
                        }
                    }
                }
            }
    }
    printf("# slice points with the march's rays: %d samples, %d in the pixel before (skipped), %d differ\n", n,
           skipped, bad);
    CHECK(n > 10000 && skipped > 100, "the march covers the groove (%d samples, %d skipped)", n, skipped);
    CHECK(bad == 0, "%d samples differ from the plain slice point", bad);
}

int main(void)
{
    RUN(sector_bits_and_popcount);
    RUN(open_plane_is_exactly_open);
    RUN(groove_against_the_exact_wall);
    RUN(thin_plank_lets_light_through_behind_it);
    RUN(depth_layers_against_the_reference);
    RUN(twosided_sheets_keep_the_constant_thickness);
    RUN(one_sided_boundaries_close_like_a_horizon);
    RUN(samples_spread_over_the_screen_with_to_edge);
    RUN(near_field_gathers_the_occluded_sectors);
    RUN(hard_cases_stay_finite);
    RUN(deterministic_under_row_splits);
    RUN(slice_point_rays_keep_the_bits);
    RUN(half_circle_u_without_acos);
    RUN(horizon_bits_without_the_angle);
    return check_summary();
}
