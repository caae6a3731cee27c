/* SPDX-License-Identifier: MIT */
/*
 * test_reproject.c - scatter/gather reprojection (HBIL sec. 3.2) and
 * push/pull hole filling (Kraus 2009), plus the spatial/temporal filter.
 *
 * Scene: a tilted analytic plane z = depth(x, y) seen by a camera; checks
 * identity for a static view, finite hole-free output after a camera cut
 * and after a teleport, holes filled within the range of valid inputs.
 */
#include <stdlib.h>
#include "check.h"
#include "raster/view.h"
#include "gi/reproject.h"
#include "gi/pushpull.h"
#include "gi/denoise.h"
#include "gi/temporal.h"

#define W 37
#define H 23
#define N (W * H)

static tgi_view make_view(float ex, float ey, float ez)
{
    tgi_view v;
    tgi_view_make(&v, tg_v3(tg_from_float(ex), tg_from_float(ey), tg_from_float(ez)), tg_v3(0, 0, 0),
                 tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f), TG_R(100.0f), W, H);
    return v;
}

/* Depth of the plane y = -1 (a floor) plus a wall z = -3, ray-cast per pixel. */
static void scene_depth(const tgi_view *v, tg_real *depth, uint8_t *sky)
{
    int x, y;
    double ppu = check_d(v->pixels_per_unit);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            double X = (x + 0.5 - W / 2.0) / ppu, Y = (H / 2.0 - (y + 0.5)) / ppu, d[3], e[3], t = 1e30, tt;
            int i = y * W + x;
            d[0] = check_d(v->right.x) * X + check_d(v->up.x) * Y + check_d(v->forward.x);
            d[1] = check_d(v->right.y) * X + check_d(v->up.y) * Y + check_d(v->forward.y);
            d[2] = check_d(v->right.z) * X + check_d(v->up.z) * Y + check_d(v->forward.z);
            e[0] = check_d(v->eye.x); e[1] = check_d(v->eye.y); e[2] = check_d(v->eye.z);
            if (d[1] < -1e-9) { tt = (-1 - e[1]) / d[1]; if (tt > 0 && tt < t) t = tt; }
            if (d[2] < -1e-9) { tt = (-3 - e[2]) / d[2]; if (tt > 0 && tt < t) t = tt; }
            sky[i] = t > 1e29;
            depth[i] = sky[i] ? 0 : tg_from_float((float)t);
        }
}

static tg_real depth0[N], depth1[N], rr[N], rg[N], rb[N], orr[N], org[N], orb[N];
static uint8_t sky0[N], sky1[N], valid[N];

static void fill_radiance(void)
{
    int i;
    for (i = 0; i < N; i++) {
        rr[i] = tg_from_float(0.1f + (float)(i % 7) * 0.2f);
        rg[i] = tg_from_float(0.5f + (float)(i % 5) * 0.1f);
        rb[i] = tg_from_float((float)(i % 3));
    }
}

static void io_for(tgi_reproject_io *io, const tgi_view *pv, const tgi_view *v)
{
    memset(io, 0, sizeof *io);
    io->width = W; io->height = H; io->prev_view = pv; io->view = v;
    io->prev_depth = depth0; io->prev_sky = sky0;
    io->prev_r = rr; io->prev_g = rg; io->prev_b = rb;
    io->out_r = orr; io->out_g = org; io->out_b = orb; io->valid = valid;
}

static void *scratch_for(void) { return malloc(tgi_reproject_bytes(W, H) + tgi_pushpull_bytes(W, H)); }

TEST(static_view_is_identity)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_reproject_io io;
    void *s = scratch_for();
    int i, bad = 0;
    scene_depth(&v, depth0, sky0);
    fill_radiance();
    io_for(&io, &v, &v);
    tgi_reproject_scatter(&io, s);
    for (i = 0; i < N; i++) {
        if (sky0[i]) { bad += valid[i] != 0; continue; }
        bad += !valid[i] || orr[i] != rr[i] || org[i] != rg[i] || orb[i] != rb[i];
    }
    CHECK(bad == 0, "scatter: %d pixels differ from the source", bad);
    /* gather with identity motion vectors */
    {
        tg_real mx[N], my[N];
        int x, y;
        for (y = 0; y < H; y++) for (x = 0; x < W; x++) {
            mx[y * W + x] = tg_add(tg_from_int(x), TG_R(0.5f)); my[y * W + x] = tg_add(tg_from_int(y), TG_R(0.5f));
        }
        io.depth = depth0; io.sky = sky0; io.motion_x = mx; io.motion_y = my;
        tgi_reproject_gather_rows(&io, 0, H);
        bad = 0;
        for (i = 0; i < N; i++) bad += sky0[i] ? valid[i] != 0 : (!valid[i] || orr[i] != rr[i] || orb[i] != rb[i]);
        CHECK(bad == 0, "gather: %d pixels differ", bad);
    }
    free(s);
}

static void check_filled(const char *what, tg_real lo, tg_real hi)
{
    int i, bad = 0;
    for (i = 0; i < N; i++) {
        double a = check_d(orr[i]);
        if (!(a == a) || orr[i] < lo || orr[i] > hi || org[i] < 0 || orb[i] < 0) bad++;
    }
    CHECK(bad == 0, "%s: %d pixels outside [%g, %g] or not finite", what, bad, check_d(lo), check_d(hi));
}

TEST(camera_cut_gives_zero)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    tgi_reproject_io io;
    void *s = scratch_for();
    int i, nz = 0;
    scene_depth(&v, depth0, sky0);
    fill_radiance();
    io_for(&io, &v, &v);
    io.prev_r = io.prev_g = io.prev_b = NULL;    /* no history */
    tgi_reproject_scatter(&io, s);
    tgi_pushpull_fill(W, H, orr, org, orb, valid, (unsigned char *)s + tgi_reproject_bytes(W, H));
    for (i = 0; i < N; i++) nz += valid[i] || orr[i] != 0 || org[i] != 0 || orb[i] != 0;
    CHECK(nz == 0, "camera cut: %d pixels not zero", nz);
    free(s);
}

TEST(teleport_is_finite_and_hole_free)
{
    tgi_view v0 = make_view(0.3f, 0.5f, 2.0f), v1 = make_view(-1.5f, 0.2f, 1.0f);
    tgi_reproject_io io;
    void *s = scratch_for();
    int i, holes = 0;
    scene_depth(&v0, depth0, sky0);
    scene_depth(&v1, depth1, sky1);
    fill_radiance();
    io_for(&io, &v0, &v1);
    tgi_reproject_scatter(&io, s);
    for (i = 0; i < N; i++) holes += !valid[i];
    CHECK(holes > 0 && holes < N, "a teleport leaves some holes (%d)", holes);
    tgi_pushpull_fill(W, H, orr, org, orb, valid, (unsigned char *)s + tgi_reproject_bytes(W, H));
    check_filled("teleport", TG_R(0.0999f), TG_R(1.3001f)); /* the source range */
    free(s);
}

TEST(pushpull_fills_within_range)
{
    int i, k;
    void *s = malloc(tgi_pushpull_bytes(W, H));
    for (k = 0; k < 3; k++) {
        for (i = 0; i < N; i++) {
            valid[i] = k == 0 ? (i % 3 == 0) : k == 1 ? (i == 17) : (i < N / 2);
            orr[i] = valid[i] ? tg_from_float(2.0f + (float)(i % 11) * 0.25f) : TG_REAL_MAX;  /* holes hold garbage */
            org[i] = valid[i] ? TG_ONE : TG_REAL_MAX;
            orb[i] = valid[i] ? 0 : TG_REAL_MAX;
        }
        tgi_pushpull_fill(W, H, orr, org, orb, valid, s);
        check_filled("push/pull", TG_R(2.0f), TG_R(4.5f));
        for (i = 0; i < N; i++) CHECK_NEAR(check_d(org[i]), 1.0, 1e-3);
        for (i = 0; i < N; i++) if (valid[i]) CHECK(orr[i] == tg_from_float(2.0f + (float)(i % 11) * 0.25f), "valid pixel %d changed", i);
    }
    /* odd and tiny sizes */
    {
        tg_real a = TG_ONE, b = TG_ONE, c = TG_ONE;
        uint8_t v = 0;
        tgi_pushpull_fill(1, 1, &a, &b, &c, &v, s);
        CHECK(a == 0 && b == 0 && c == 0, "1x1 hole without data gives 0");
    }
    free(s);
}

/* The spatial filter leaves a constant field constant and keeps cone = acos(1 - AO);
 * the temporal pass with a static view converges to a constant input. */
TEST(filters_preserve_constants)
{
    tgi_view v = make_view(0.3f, 0.5f, 2.0f);
    static tg_real ao[N], bx[N], by[N], bz[N], cone[N], nx[N], ny[N], nz[N];
    tgi_gbuffer gb;
    tgi_gview g;
    tgi_gresult r;
    tgi_denoise_params p;
    tgi_temporal_params tp;
    void *scratch = malloc(tgi_denoise_bytes(W, H)), *state = malloc(tgi_temporal_bytes(W, H));
    int i, f, bad = 0;
    scene_depth(&v, depth0, sky0);
    for (i = 0; i < N; i++) {
        ao[i] = tg_from_float(0.25f + (float)(i % 4) * 0.25f); /* varies inside every 4x4 block */
        nx[i] = 0; ny[i] = TG_ONE; nz[i] = 0;
        bx[i] = 0; by[i] = TG_ONE; bz[i] = 0;
    }
    memset(&gb, 0, sizeof gb);
    gb.width = W; gb.height = H; gb.depth = depth0; gb.nx = nx; gb.ny = ny; gb.nz = nz; gb.sky = sky0;
    tgi_gview_of(&g, &gb, &v);
    memset(&r, 0, sizeof r);
    r.ao = ao; r.bent_x = bx; r.bent_y = by; r.bent_z = bz; r.cone = cone;
    tgi_denoise_defaults(&p);
    tgi_denoise_keep_rows(&g, &r, scratch, 0, H);
    tgi_denoise_rows(&p, &g, &r, scratch, 0, H);
    for (i = 0; i < N; i++) {
        double a = check_d(ao[i]);
        if (sky0[i]) continue;
        if (!(a >= 0.25 && a <= 1.0)) bad++;
        if (fabs(check_d(cone[i]) - acos(1 - a)) > 2e-3) bad++;
    }
    CHECK(bad == 0, "filtered AO out of range or cone != acos(1 - AO): %d", bad);
    tgi_temporal_defaults(&tp);
    tgi_temporal_clear(state, W, H);
    for (f = 0; f < 40; f++) {
        for (i = 0; i < N; i++) ao[i] = TG_R(0.5f);
        tgi_temporal_rows(&tp, &g, &r, state, &v, f, f == 0, 0, H);
    }
    for (i = 0; i < N; i++) if (!sky0[i]) CHECK_NEAR(check_d(ao[i]), 0.5, 1e-3);
    free(scratch); free(state);
}

int main(void)
{
    RUN(static_view_is_identity);
    RUN(camera_cut_gives_zero);
    RUN(teleport_is_finite_and_hole_free);
    RUN(pushpull_fills_within_range);
    RUN(filters_preserve_constants);
    return check_summary();
}
