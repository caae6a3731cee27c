/* SPDX-License-Identifier: MIT */
/*
 * peer_common.h - the peer programs' (tools/peers/) main: the sphere of
 * tools/raster_sphere.h (as tools/bench_raster.c draws it), the command
 * line (`PROGRAM [WxH ...] [--frames N]`) and the result line
 * tools/bench_time.py reads.  Each peer program defines peer_name,
 * peer_setup, bench_clear, bench_draw, peer_covered and peer_done.
 */
#ifndef TG_PEER_COMMON_H
#define TG_PEER_COMMON_H
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "../raster_sphere.h"

/* What each peer program provides. */
static const char *peer_name(void);
static int peer_setup(int w, int h, const float *pos, int tris);   /* 0: cannot draw at w x h */
static void bench_clear(void);
static void bench_draw(void);
static long peer_covered(void);   /* pixels the last draw covered */
static void peer_done(void);

/* Two untimed frames, then `frames` timed ones; one result line. */
static int peer_main(int argc, char **argv)
{
    int frames, sizes[8][2], nsizes, k, tris;
    float *pos = (float *)malloc(sizeof(float) * 9 * SPHERE_MAX_TRIS);
    if (sphere_bench_args(argc, argv, peer_name(), &frames, sizes, &nsizes)) return 2;
    if (!pos) return 1;
    tris = sphere_corners(pos);
    for (k = 0; k < nsizes; k++) {
        const int w = sizes[k][0], h = sizes[k][1];
        double draw_cpu = 0, draw_wall = 0, clear_cpu = 0, clear_wall = 0;
        int f;
        if (!peer_setup(w, h, pos, tris)) {
            fprintf(stderr, "%s: cannot draw at %dx%d\n", peer_name(), w, h);
            return 2;
        }
        for (f = -2; f < frames; f++) {
            double c0 = cpu_seconds(), w0 = wall_seconds(), c1, w1;
            bench_clear();
            c1 = cpu_seconds(); w1 = wall_seconds();
            bench_draw();
            if (f < 0) continue;
            clear_cpu += c1 - c0; clear_wall += w1 - w0;
            draw_cpu += cpu_seconds() - c1; draw_wall += wall_seconds() - w1;
        }
        printf("%s %dx%d tris=%d frames=%d draw_cpu_ms=%.4f draw_wall_ms=%.4f clear_cpu_ms=%.4f "
               "clear_wall_ms=%.4f covered=%ld\n",
               peer_name(), w, h, tris, frames, draw_cpu / frames * 1e3, draw_wall / frames * 1e3,
               clear_cpu / frames * 1e3, clear_wall / frames * 1e3, peer_covered());
        fflush(stdout);
        peer_done();
    }
    free(pos);
    return 0;
}

#endif
