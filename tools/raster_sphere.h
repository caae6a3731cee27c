/* SPDX-License-Identifier: MIT */
/*
 * raster_sphere.h - the rasterizer bench's scene and clocks, shared by
 * tools/bench_raster.c and the peer programs (tools/peers/): a unit UV
 * sphere of 49,728 triangles (112 rings x 224 slices, the pole slivers
 * dropped, counter-clockwise seen from outside; the unit normal is the
 * position), seen from 3.4 units on -z with a 0.6 rad vertical field of
 * view; thread CPU time and wall time; the programs' command line.
 */
#ifndef TG_RASTER_SPHERE_H
#define TG_RASTER_SPHERE_H
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define SPHERE_RINGS 112
#define SPHERE_SLICES 224
#define SPHERE_MAX_TRIS (SPHERE_RINGS * SPHERE_SLICES * 2)
#define SPHERE_CAM_DIST 3.4
#define SPHERE_CAM_FOV 0.6
#define SPHERE_CAM_NEAR 0.05
#define SPHERE_CAM_FAR 1000.0

/* The triangles' corners, 9 floats a triangle (x, y, z of 3 corners) into
 * pos (SPHERE_MAX_TRIS triangles' room); the triangle count. */
static int sphere_corners(float *pos)
{
    const double pi = 3.14159265358979323846;
    int r, s, n = 0;
    for (r = 0; r < SPHERE_RINGS; r++)
        for (s = 0; s < SPHERE_SLICES; s++) {
            double t0 = pi * r / SPHERE_RINGS, t1 = pi * (r + 1) / SPHERE_RINGS;
            double p0 = 2 * pi * s / SPHERE_SLICES, p1 = 2 * pi * (s + 1) / SPHERE_SLICES;
            double c[4][3];
            int q[2][3] = { { 0, 2, 1 }, { 1, 2, 3 } }, k, l;
            double th[4] = { t0, t0, t1, t1 }, ph[4] = { p0, p1, p0, p1 };
            for (k = 0; k < 4; k++) {
                c[k][0] = sin(th[k]) * cos(ph[k]);
                c[k][1] = cos(th[k]);
                c[k][2] = -sin(th[k]) * sin(ph[k]);
            }
            for (k = 0; k < 2; k++) {
                if ((r == 0 && k == 0) || (r == SPHERE_RINGS - 1 && k == 1)) continue; /* pole slivers */
                for (l = 0; l < 3; l++) {
                    pos[9 * n + 3 * l] = (float)c[q[k][l]][0];
                    pos[9 * n + 3 * l + 1] = (float)c[q[k][l]][1];
                    pos[9 * n + 3 * l + 2] = (float)c[q[k][l]][2];
                }
                n++;
            }
        }
    return n;
}

/* CPU time of this thread: on a shared, loaded machine it tracks the work
 * done far better than the wall clock (which counts time spent
 * descheduled); both are reported. */
static double cpu_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* "WxH", each side 1..8192 */
static int parse_size(const char *s, int *w, int *h)
{
    char x;
    return sscanf(s, "%d%c%d", w, &x, h) == 3 && x == 'x' && *w >= 1 && *h >= 1 && *w <= 8192 && *h <= 8192;
}

/* The bench programs' command line, `NAME [WxH ...] [--frames N]`: up to 8
 * sizes (default 320x240 and 1280x720) and the frames a run (default 20);
 * 0, or 2 after a message on stderr. */
static int sphere_bench_args(int argc, char **argv, const char *name, int *frames, int sizes[8][2], int *nsizes)
{
    int a;
    *frames = 20;
    *nsizes = 0;
    for (a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--frames") && a + 1 < argc) {
            *frames = atoi(argv[++a]);
            if (*frames < 1 || *frames > 100000) {
                fprintf(stderr, "%s: --frames must be 1..100000, got '%s'\n", name, argv[a]);
                return 2;
            }
        } else if (*nsizes < 8 && parse_size(argv[a], &sizes[*nsizes][0], &sizes[*nsizes][1])) {
            (*nsizes)++;
        } else {
            fprintf(stderr, "usage: %s [WxH ...] [--frames N]   (got '%s')\n", name, argv[a]);
            return 2;
        }
    }
    if (*nsizes == 0) {
        sizes[0][0] = 320; sizes[0][1] = 240;
        sizes[1][0] = 1280; sizes[1][1] = 720;
        *nsizes = 2;
    }
    return 0;
}

#endif
