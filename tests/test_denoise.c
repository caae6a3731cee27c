/* SPDX-License-Identifier: MIT */
/*
 * test_denoise.c - the 4x4-neighbourhood filter's walk (gi/denoise.h): its
 * bands of rows, and that every order of calls and every split of the rows
 * gives the same filtered values (tests/test_reproject.c checks them
 * against the filter's formula, in rows, columns and backwards).
 *
 * Inputs: random G-buffers (depth steps across the depth tolerance, sky
 * pixels, normals facing every way, planes whose pixels share a normal)
 * and random results in every channel.
 */
#include "check.h"
#include "storage_fixture.h"
#include "raster/view.h"
#include "gi/denoise.h"

#define W 41
#define H 29
#define N (W * H)

static uint32_t rng_state = 12345u;
static uint32_t rng(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return rng_state >> 8;
}
static float frand(void) { return (float)(rng() & 0xFFFF) / 65536.0f; }   /* [0, 1) */

/* The bands: aligned to the walk's first row, TGI_DENOISE_BAND rows each,
 * cut at the caller's end; before the first pixel a band starts at the row
 * asked for. */
TEST(bands_are_aligned_to_the_first_row)
{
    tgi_denoise_walk k;
    int y, bad = 0;
    tgi_denoise_walk_start(&k);
    CHECK(tgi_denoise_band(&k, 7, 100) == 7 + TGI_DENOISE_BAND, "a first band starts where asked: ends %d",
          tgi_denoise_band(&k, 7, 100));
    CHECK(tgi_denoise_band(&k, 7, 8) == 8, "a band ends at the caller's end");
    k.base = 5;   /* as the first pixel, at row 5, leaves it */
    for (y = 0; y < 60; y++) {
        int end = tgi_denoise_band(&k, y, 1000), first = tgi_denoise_band_of(5, y);
        if (first > y || y - first >= TGI_DENOISE_BAND || (first - 5) % TGI_DENOISE_BAND != 0 ||
            end != first + TGI_DENOISE_BAND)
            bad++;
    }
    CHECK(bad == 0, "%d rows in the wrong band", bad);
}

static void random_inputs(tgi_gbuffer *gb, tgi_gresult *r)
{
    tg_vec3 planes[3];
    int i;
    planes[0] = tg_v3(0, TG_ONE, 0);
    planes[1] = tgi_v3_normalize(tg_v3(TG_R(0.3f), TG_ONE, TG_R(-0.2f)));
    planes[2] = tgi_v3_normalize(tg_v3(TG_R(-0.6f), TG_R(0.5f), TG_R(0.4f)));
    for (i = 0; i < N; i++) {
        int x = i % W, y = i / W, sky = rng() % 13 == 0;
        /* piecewise depths: steps of 0-20% between blocks, a slope within */
        float z = 1.5f + 0.3f * (float)((x / 3 + y / 4) % 4) + 0.01f * (float)(x % 3) + 0.05f * frand();
        tg_vec3 n = tgi_v3_normalize(tg_v3(tg_from_float(2 * frand() - 1), tg_from_float(2 * frand() - 1),
                                           tg_from_float(2 * frand() - 1)));
        if (rng() % 3) n = tgi_v3_normalize(tg_v3(tg_from_float(0.2f * frand()), TG_ONE, tg_from_float(0.2f * frand())));
        if ((x / 4 + y / 3) % 3 == 0) n = planes[(x / 8 + y / 6) % 3];   /* planes: neighbours share the normal */
        sf_gbuffer_set(gb, (size_t)i, sky ? 0 : tg_from_float(z), n, 0);
        tgi_gr_set_ao(r, (size_t)i, tg_from_float(frand()));
        tgi_gr_set_bent(r, (size_t)i, tgi_v3_normalize(tg_v3(tg_from_float(2 * frand() - 1), tg_from_float(frand()),
                                                                tg_from_float(2 * frand() - 1))));
        tgi_gr_set_near(r, (size_t)i, tg_v3(tg_from_float(4 * frand()), tg_from_float(frand()),
                                            tg_from_float(0.01f * frand())));
    }
}

static int same_value(tgi_gr_value a, tgi_gr_value b)
{
    return a.ao == b.ao && a.bent.x == b.bent.x && a.bent.y == b.bent.y && a.bent.z == b.bent.z &&
           a.near.x == b.near.x && a.near.y == b.near.y && a.near.z == b.near.z;
}

/* One walk along the rows (the order of before the bands), against: the
 * bands' order (tgi_denoise_rows, as the resolve walks), the rows split
 * into random ranges (threads), columns top to bottom, and random pixels. */
TEST(every_order_and_split_gives_the_same_values)
{
    static tgi_gbuffer gb;
    static tgi_gr_value want[N];
    tgi_view v;
    tgi_gview g;
    tgi_gresult r, out;
    tgi_denoise_params p;
    tgi_denoise_walk k;
    int scene, i, x, y, bad_rows = 0, bad_split = 0, bad_cols = 0, bad_random = 0, filtered = 0;
    tgi_view_make(&v, tg_v3(0, TG_ONE, 0), tg_v3(0, 0, tg_neg(TG_ONE)), tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f),
                  TG_R(100.0f), W, H);
    sf_gbuffer_alloc(&gb, W, H, NULL, 0);
    sf_results_alloc(&r, N, 1, 0, 1);
    sf_results_alloc(&out, N, 1, 0, 1);
    g = sf_view(&gb, &v);
    tgi_denoise_defaults(&p);
    for (scene = 0; scene < 40; scene++) {
        random_inputs(&gb, &r);
        tgi_denoise_walk_start(&k);
        for (y = 0; y < H; y++)
            for (x = 0; x < W; x++) {
                want[y * W + x] = tgi_denoise_pixel(&p, &g, &r, &k, x, y);
                if (!same_value(want[y * W + x], tgi_gr_get_kept(&r, tgi_gv_index(&g, x, y)))) filtered++;
            }
        tgi_denoise_rows(&p, &g, &r, &out, 0, H);
        {   /* the rows in 1-4 random ranges, each its own walk */
            tgi_gresult split;
            int y0 = 0;
            sf_results_alloc(&split, N, 1, 0, 1);
            while (y0 < H) {
                int y1 = y0 + 1 + (int)(rng() % 11);
                if (y1 > H) y1 = H;
                tgi_denoise_rows(&p, &g, &r, &split, y0, y1);
                y0 = y1;
            }
            for (i = 0; i < N; i++) {
                tgi_gr_value a = tgi_gr_get_kept(&out, (size_t)i), b = tgi_gr_get_kept(&split, (size_t)i);
                tgi_gr_value c;
                if (!same_value(a, b)) bad_split++;
                tgi_gr_put_kept(&split, (size_t)i, &want[i]);   /* the rows' values through the same storage */
                c = tgi_gr_get_kept(&split, (size_t)i);
                if (!same_value(a, c)) bad_rows++;
            }
            sf_results_free(&split);
        }
        tgi_denoise_walk_start(&k);
        for (x = 0; x < W; x++)
            for (y = 0; y < H; y++) bad_cols += !same_value(tgi_denoise_pixel(&p, &g, &r, &k, x, y), want[y * W + x]);
        tgi_denoise_walk_start(&k);
        for (i = 0; i < 4 * N; i++) {
            x = (int)(rng() % W); y = (int)(rng() % H);
            bad_random += !same_value(tgi_denoise_pixel(&p, &g, &r, &k, x, y), want[y * W + x]);
        }
    }
    CHECK(bad_rows == 0, "%d pixels of the bands' order differ from the rows'", bad_rows);
    CHECK(bad_split == 0, "%d pixels of split rows differ", bad_split);
    CHECK(bad_cols == 0, "%d pixels differ walked down the columns", bad_cols);
    CHECK(bad_random == 0, "%d pixels differ in a random order", bad_random);
    CHECK(filtered > 40 * N / 2, "the filter changed only %d of %d pixels", filtered, 40 * N);
    sf_results_free(&r);
    sf_results_free(&out);
    sf_gbuffer_free(&gb);
}

/* A tap whose depth weight 1 - dz / (tol z) rounds to 0 or below adds
 * nothing (the filter's sums take every tap of the window without a test:
 * tap_weights clamps the weights at 0).  A flat 5x5 patch far away (depth
 * 200, so that in Q16.16 the rounded dz / ztol can pass 1 while dz < ztol)
 * with near field 1 and one neighbour with near field 100 at depths from
 * just inside the tolerance to just outside: the centre's filtered near
 * field, a weighted average, never falls below 1 (a negative weight would
 * take it there), nor rises far above it where the neighbour weighs
 * (nearly) nothing. */
TEST(a_tap_at_the_depth_tolerance_adds_nothing_below_zero)
{
    static tgi_gbuffer gb;
    tgi_view v;
    tgi_gview g;
    tgi_gresult r;
    tgi_denoise_params p;
    const float zi = 200.0f, ztol = 0.1f * zi;
    int s, i, below = 0, tried = 0;
    double lowest = 2;
    tgi_view_make(&v, tg_v3(0, TG_ONE, 0), tg_v3(0, 0, tg_neg(TG_ONE)), tg_v3(0, TG_ONE, 0), TG_R(1.0f), TG_R(0.05f),
                  TG_R(1000.0f), 5, 5);
    sf_gbuffer_alloc(&gb, 5, 5, NULL, 0);
    sf_results_alloc(&r, 25, 1, 0, 1);
    g = sf_view(&gb, &v);
    tgi_denoise_defaults(&p);
    for (s = -64; s <= 64; s++) {
        tgi_denoise_walk k;
        tgi_gr_value out;
        float zj = zi + ztol * (1.0f + (float)s / 65536.0f);
        for (i = 0; i < 25; i++) {
            sf_gbuffer_set(&gb, (size_t)i, tg_from_float(i == 11 ? zj : zi), tg_v3(0, TG_ONE, 0), 0);
            tgi_gr_set_ao(&r, (size_t)i, TG_ONE);
            tgi_gr_set_near(&r, (size_t)i, i == 11 ? tg_v3(TG_R(100.0f), TG_R(100.0f), TG_R(100.0f))
                                                  : tg_v3(TG_ONE, TG_ONE, TG_ONE));
        }
        tgi_denoise_walk_start(&k);
        out = tgi_denoise_pixel(&p, &g, &r, &k, 2, 2);
        tried++;
        if (out.near.x < TG_ONE) below++;
        if (check_d(out.near.x) < lowest) lowest = check_d(out.near.x);
        CHECK(check_d(out.near.x) < 1.01, "near field %g at neighbour depth %.6f (tolerance %g): it weighs",
              check_d(out.near.x), (double)zj, (double)ztol);
    }
    printf("  a tap at %.0f +- 2^-10 of the depth tolerance, %d depths: lowest filtered near field %.9g\n", (double)ztol, tried,
           lowest);
    CHECK(below == 0, "%d of %d depths give a near field below every input's (lowest %.9g): a negative weight", below,
          tried, lowest);
    sf_results_free(&r);
    sf_gbuffer_free(&gb);
}

int main(void)
{
    RUN(bands_are_aligned_to_the_first_row);
    RUN(every_order_and_split_gives_the_same_values);
    RUN(a_tap_at_the_depth_tolerance_adds_nothing_below_zero);
    return check_summary();
}
