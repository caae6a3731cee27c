/* SPDX-License-Identifier: MIT */
/*
 * bench_raster.c - rasterizer throughput: a UV sphere of ~50k triangles
 * rendered into a full G-buffer (depth, normal, albedo, f0, emissive, sky,
 * object) at 320x240 and 1280x720, one core, thread CPU time.  Prints Mtri/s (triangles
 * submitted per second, back faces included, as the peers count them), the
 * median of RUNS runs of FRAMES frames each, for the number type this
 * program is built with.  The time is the rasterizer's alone; the G-buffer
 * clear (a memset per channel) is reported beside it.
 *
 *   cc -std=c99 -O2 -Isrc -Iplatform tools/bench_raster.c build/libtinygi.a -lm
 *   cc -std=c99 -O2 -DTG_FIXED=1 -Isrc -Iplatform tools/bench_raster.c build/libtinygi-fixed.a -lm
 *   ./a.out [frames] [runs]
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "tinygi.h"
#include "raster/raster.h"

#define RINGS 112
#define SLICES 224
#define PI 3.14159265358979323846

/* CPU time of this thread: on a shared, loaded machine it tracks the work
 * done far better than the wall clock (which counts time spent descheduled). */
static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static tg_vec3 V(double x, double y, double z)
{
    return tg_v3(tg_from_float((float)x), tg_from_float((float)y), tg_from_float((float)z));
}

/* Unit sphere at the origin, counter-clockwise seen from outside. */
static int build_sphere(tg_vec3 *pos, tg_vec3 *nrm)
{
    int r, s, n = 0;
    for (r = 0; r < RINGS; r++)
        for (s = 0; s < SLICES; s++) {
            double t0 = PI * r / RINGS, t1 = PI * (r + 1) / RINGS;
            double p0 = 2 * PI * s / SLICES, p1 = 2 * PI * (s + 1) / SLICES;
            double c[4][3];
            int q[2][3] = { { 0, 2, 1 }, { 1, 2, 3 } }, k, l;
            double th[4] = { t0, t0, t1, t1 }, ph[4] = { p0, p1, p0, p1 };
            for (k = 0; k < 4; k++) {
                c[k][0] = sin(th[k]) * cos(ph[k]);
                c[k][1] = cos(th[k]);
                c[k][2] = -sin(th[k]) * sin(ph[k]);
            }
            for (k = 0; k < 2; k++) {
                if ((r == 0 && k == 0) || (r == RINGS - 1 && k == 1)) continue; /* pole slivers */
                for (l = 0; l < 3; l++) {
                    const double *v = c[q[k][l]];
                    pos[3 * n + l] = V(v[0], v[1], v[2]);
                    nrm[3 * n + l] = V(v[0], v[1], v[2]);
                }
                n++;
            }
        }
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static void bench(const tgi_raster_mesh *mesh, int w, int h, int frames, int runs)
{
    size_t n = (size_t)w * (size_t)h;
    tg_real *mem = (tg_real *)calloc(n * 11, sizeof(tg_real));
    tgi_gbuffer gb;
    tgi_view view;
    double *t = (double *)malloc(sizeof(double) * (size_t)runs), med;
    double *tclear = (double *)malloc(sizeof(double) * (size_t)runs);
    long drawn = 0;
    int run, f;
    size_t i;
    memset(&gb, 0, sizeof gb);
    gb.width = w; gb.height = h;
    gb.depth = mem; gb.nx = mem + n; gb.ny = mem + 2 * n; gb.nz = mem + 3 * n;
    gb.albedo_r = mem + 4 * n; gb.albedo_g = mem + 5 * n; gb.albedo_b = mem + 6 * n;
    gb.f0 = mem + 7 * n; gb.emit_r = mem + 8 * n; gb.emit_g = mem + 9 * n; gb.emit_b = mem + 10 * n;
    gb.sky = (uint8_t *)malloc(n);
    gb.object = (uint16_t *)malloc(n * sizeof(uint16_t));
    /* the sphere fills ~90% of the image height */
    tgi_view_make(&view, V(0, 0, -3.4), V(0, 0, 0), V(0, 1, 0), tg_from_float(0.6f), tg_from_float(0.05f),
                 tg_from_float(1000.0f), w, h);
    /* raster time only; the clear (a memset of every channel) is timed apart */
    for (run = 0; run < runs; run++) {
        double tr = 0, tc = 0;
        for (f = 0; f < frames; f++) {
            double t0 = now_seconds(), t1;
            tgi_gbuffer_clear_rows(&gb, 0, h);
            t1 = now_seconds();
            tgi_raster_gbuffer(&gb, &view, mesh, 0, h);
            tr += now_seconds() - t1;
            tc += t1 - t0;
        }
        t[run] = tr;
        tclear[run] = tc;
    }
    for (i = 0; i < n; i++) drawn += !gb.sky[i];
    qsort(t, (size_t)runs, sizeof *t, cmp_double);
    qsort(tclear, (size_t)runs, sizeof *tclear, cmp_double);
    med = t[runs / 2];
    printf("%-5s %4dx%-4d %6d tris %7.2f Mtri/s  raster %6.3f ms/frame, clear %6.3f ms  (median of %d runs x %d frames; %ld px covered)\n",
           TG_NUMBER_NAME, w, h, mesh->tri_count, mesh->tri_count * (double)frames / med * 1e-6,
           med / frames * 1e3, tclear[runs / 2] / frames * 1e3, runs, frames, drawn);
    free(mem); free(gb.sky); free(gb.object); free(t); free(tclear);
}

int main(int argc, char **argv)
{
    int frames = argc > 1 ? atoi(argv[1]) : 20, runs = argc > 2 ? atoi(argv[2]) : 9;
    tg_vec3 *pos = (tg_vec3 *)malloc(sizeof(tg_vec3) * 3 * RINGS * SLICES * 2);
    tg_vec3 *nrm = (tg_vec3 *)malloc(sizeof(tg_vec3) * 3 * RINGS * SLICES * 2);
    uint16_t *mat = (uint16_t *)calloc(RINGS * SLICES * 2, sizeof(uint16_t));
    uint16_t *obj = (uint16_t *)calloc(RINGS * SLICES * 2, sizeof(uint16_t));
    tgi_material m;
    tgi_raster_mesh mesh;
    if (frames < 1) frames = 1;
    if (runs < 5) runs = 5;
    memset(&m, 0, sizeof m);
    m.albedo = V(0.8, 0.6, 0.4);
    m.f0 = tg_from_float(0.04f);
    mesh.pos = pos; mesh.nrm = nrm; mesh.tri_material = mat; mesh.tri_object = obj;
    mesh.materials = &m;
    mesh.tri_count = build_sphere(pos, nrm);
    bench(&mesh, 320, 240, frames, runs);
    bench(&mesh, 1280, 720, frames, runs);
    free(pos); free(nrm); free(mat); free(obj);
    return 0;
}
