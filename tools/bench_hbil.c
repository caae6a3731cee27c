/* SPDX-License-Identifier: MIT */
/*
 * bench_hbil.c - time the GI chain on a 320x240 analytic groove G-buffer:
 * 4x4 split, the HBIL kernel on the 16 sub-images (2 slices, 16 samples),
 * merge, and the spatial filter; prints the median of 15 runs in ms.
 * `bench_hbil 1` runs once (for callgrind); `bench_hbil 15 out.bin` also
 * writes ao, bent xyz and cone as 5 x W x H raw floats for before/after diffs.
 *
 *   make BUILD=build-hbil
 *   cc -std=c99 -O2 -D_POSIX_C_SOURCE=200809L -Isrc tools/bench_hbil.c build-hbil/libtinygi.a -lm -o build-hbil/bench_hbil
 *   cc -std=c99 -O2 -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc tools/bench_hbil.c build-hbil/libtinygi-fixed.a -lm -o build-hbil/bench_hbil-fixed
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "core/vec.h"
#include "raster/view.h"
#include "gi/hbil.h"
#include "gi/interleave.h"
#include "gi/denoise.h"

#define W 320
#define H 240
#define N (W * H)
#define MAX_RUNS 15

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static tg_real depth[N], nx[N], ny[N], nz[N], ao[N], bx[N], by[N], bz[N], cone[N];
static uint8_t sky[N];

/* The groove: faces y = |x|, seen from (0, 4, 0.5) looking down. */
static void groove(tgi_view *v)
{
    int x, y;
    double ppu;
    tgi_view_make(v, tg_v3(0, TG_R(4.0f), TG_R(0.5f)), tg_v3(0, 0, TG_R(0.5f)), tg_v3(0, 0, -TG_ONE),
                 TG_R(1.0471976f), TG_R(0.05f), TG_R(100.0f), W, H);
    ppu = tg_to_float(v->pixels_per_unit);
    for (y = 0; y < H; y++)
        for (x = 0; x < W; x++) {
            /* view: right = (1,0,0)?  use the view basis to build the ray */
            double X = (x + 0.5 - W / 2.0) / ppu, Y = (H / 2.0 - (y + 0.5)) / ppu, d[3], t, s;
            int i = y * W + x;
            d[0] = tg_to_float(v->right.x) * X + tg_to_float(v->up.x) * Y + tg_to_float(v->forward.x);
            d[1] = tg_to_float(v->right.y) * X + tg_to_float(v->up.y) * Y + tg_to_float(v->forward.y);
            s = d[0] >= 0 ? 1 : -1;              /* face y = s x */
            t = 4.0 / (s * d[0] - d[1]);         /* 4 + t d1 = s t d0 */
            depth[i] = tg_from_float((float)t);
            nx[i] = tg_from_float((float)(-s * 0.70710678)); ny[i] = tg_from_float(0.70710678f); nz[i] = 0;
            sky[i] = 0;
        }
}

/* Write ao, bent xyz, cone (floats, N each) for before/after comparisons. */
static void dump(const char *path)
{
    FILE *f = fopen(path, "wb");
    const tg_real *ch[5] = { ao, bx, by, bz, cone };
    int k, i;
    if (!f) { perror(path); exit(1); }
    for (k = 0; k < 5; k++)
        for (i = 0; i < N; i++) {
            float v = tg_to_float(ch[k][i]);
            fwrite(&v, sizeof v, 1, f);
        }
    fclose(f);
}

/* usage: bench_hbil [RUNS [DUMP_FILE]]  (RUNS default 15; 1 for callgrind) */
int main(int argc, char **argv)
{
    static const tgi_material white = { "white", { TG_ONE, TG_ONE, TG_ONE }, 0, { 0, 0, 0 }, 0,
                                        { TG_INV_PI, TG_INV_PI, TG_INV_PI } };   /* diffuse: tgi_material_finish's */
    tgi_view v;
    tgi_denoise_params dp;
    tgi_hbil_params hp;
    tgi_gbuffer gb, split;
    tgi_gview full;
    tgi_gresult res, split_res;
    void *scratch = malloc(tgi_denoise_bytes(W, H));
    /* the build's storage (raster/gview.h): G-buffer, its 4x4 split and the results of both */
    void *gmem = calloc(tgi_gbuffer_carve(&gb, W, H, NULL), 1), *smem = calloc(tgi_gbuffer_carve(&split, W, H, NULL), 1);
    void *rmem = calloc(tgi_gresult_carve(&res, N, 1, 1, 0, NULL), 1);
    void *srmem = calloc(tgi_gresult_carve(&split_res, N, 1, 1, 0, NULL), 1);
    double t[MAX_RUNS], sum_ao = 0;
    int r, i, x, y, RUNS = argc > 1 ? atoi(argv[1]) : MAX_RUNS;
    size_t start[4];
    if (RUNS < 1 || RUNS > MAX_RUNS) RUNS = MAX_RUNS;
    groove(&v);
    tgi_denoise_defaults(&dp);
    tgi_hbil_defaults(&hp);
    tgi_gbuffer_carve(&gb, W, H, gmem);
    tgi_gbuffer_carve(&split, W, H, smem);
    tgi_gresult_carve(&res, N, 1, 1, 0, rmem);
    tgi_gresult_carve(&split_res, N, 1, 1, 0, srmem);
    gb.materials = split.materials = &white;
    for (i = 0; i < N; i++) tgi_gb_set(&gb, (size_t)i, depth[i], tg_v3(nx[i], ny[i], nz[i]), 0);
    tgi_gview_of(&full, &gb, &v);
    for (r = 0; r < RUNS; r++) {
        double t0 = now_ms();
        for (y = 0; y < H; y++) {          /* split, as the frame's split pass */
            tgi_interleave_row(W, H, y, start);
            for (x = 0; x < W; x++)
                tgi_gview_copy_pixel(&split, start[x & 3] + (size_t)(x >> 2), &full, tgi_gv_index(&full, x, y));
        }
        tgi_hbil_interleaved_rows(&hp, &full, &split, NULL, &split_res, 0, H);
        for (y = 0; y < H; y++) {          /* merge */
            tgi_interleave_row(W, H, y, start);
            for (x = 0; x < W; x++)
                tgi_gresult_copy_pixel(&res, tgi_gv_index(&full, x, y), &split_res, start[x & 3] + (size_t)(x >> 2));
        }
        tgi_denoise_keep_rows(&full, &res, scratch, 0, H);
        tgi_denoise_rows(&dp, &full, &res, scratch, 0, H);
        t[r] = now_ms() - t0;
    }
    for (i = 0; i < N; i++) {
        tg_vec3 b = tgi_gr_bent(&res, (size_t)i);
        ao[i] = tgi_gr_ao(&res, (size_t)i);
        bx[i] = b.x; by[i] = b.y; bz[i] = b.z;
        cone[i] = tgi_gr_cone(&res, (size_t)i);
        sum_ao += tg_to_float(ao[i]);
    }
    qsort(t, RUNS, sizeof t[0], cmp);
    printf("bench_hbil %s %dx%d: split+kernel+merge+filter median %.2f ms (min %.2f, max %.2f), mean AO %.4f\n",
           TG_NUMBER_NAME, W, H, t[RUNS / 2], t[0], t[RUNS - 1], sum_ao / N);
    if (argc > 2) dump(argv[2]);
    free(scratch); free(gmem); free(smem); free(rmem); free(srmem);
    return 0;
}
