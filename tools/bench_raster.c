/* SPDX-License-Identifier: MIT */
/*
 * bench_raster.c - rasterizer throughput: a UV sphere of 49,728 triangles
 * (112 rings x 224 slices, the pole slivers dropped) rendered into a full
 * G-buffer (depth, normal, albedo, f0, emissive, sky, object: 11 tg_real
 * planes and 3 bytes a pixel) on one core, for the number type this program
 * is built with.  For each size it prints one line of per-frame means over
 * FRAMES frames (after two untimed ones): the draw (tgi_raster_gbuffer) and
 * the clear (tgi_gbuffer_clear_rows) apart, in thread CPU time and wall time.
 * `make bench-raster` (tools/bench_time.py) runs it in interleaved rounds
 * and reports medians, Mtri/s (triangles submitted per second, back faces
 * included, as the peers count them) and callgrind's count per frame.
 *
 *   build/bench_raster [WxH ...] [--frames N]     default 320x240 1280x720, 20
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "tinygi.h"
#include "raster/raster.h"
#include "raster/gview.h"

#include "raster_sphere.h"

static tg_vec3 V(double x, double y, double z)
{
    return tg_v3(tg_from_float((float)x), tg_from_float((float)y), tg_from_float((float)z));
}

/* raster_sphere.h's sphere as tinygi's numbers (the normal is the position) */
static int build_sphere(tg_vec3 *pos, tg_vec3 *nrm)
{
    float *c = (float *)malloc(sizeof(float) * 9 * SPHERE_MAX_TRIS);
    int n, i;
    if (!c) return 0;
    n = sphere_corners(c);
    for (i = 0; i < 3 * n; i++)
        pos[i] = nrm[i] = tg_v3(tg_from_float(c[3 * i]), tg_from_float(c[3 * i + 1]), tg_from_float(c[3 * i + 2]));
    free(c);
    return n;
}

/* Kept out of line so that callgrind can count one frame's draw and clear
 * (bench_time.py reads the inclusive cost of these two names). */
static void __attribute__((noinline)) bench_clear(tgi_gbuffer *gb)
{
    tgi_gbuffer_clear_rows(gb, 0, gb->height);
}

static void __attribute__((noinline)) bench_draw(tgi_gbuffer *gb, const tgi_view *view,
                                                 const tgi_raster_mesh *mesh)
{
    tgi_raster_gbuffer(gb, view, mesh, 0, gb->height);
}

/* FNV-1a of what the draw wrote (depth, normal, material, object of every
 * covered pixel): a change to the rasterizer that should keep its output
 * bit for bit is checked by comparing this between builds. */
static void fnv_bytes(unsigned long *h, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    while (n--) *h = ((*h ^ *b++) * 16777619ul) & 0xFFFFFFFFul;
}

static unsigned long gbuffer_hash(const tgi_gbuffer *gb)
{
    unsigned long h = 2166136261ul;
    size_t i, n = (size_t)gb->width * (size_t)gb->height;
    for (i = 0; i < n; i++) {
        fnv_bytes(&h, &gb->depth[i], sizeof gb->depth[i]);
        if (!gb->depth[i]) continue;
#if TG_WIDE_STORAGE
        fnv_bytes(&h, &gb->nx[i], sizeof gb->nx[i]);
        fnv_bytes(&h, &gb->ny[i], sizeof gb->ny[i]);
        fnv_bytes(&h, &gb->nz[i], sizeof gb->nz[i]);
        fnv_bytes(&h, &gb->material[i], sizeof gb->material[i]);
#else
        fnv_bytes(&h, &gb->nm[i], sizeof gb->nm[i]);
#endif
        fnv_bytes(&h, &gb->object[i], sizeof gb->object[i]);
    }
    return h;
}

/* Two untimed frames (page faults, caches), then FRAMES timed ones; one
 * line, the per-frame means of this run: the driver (tools/bench_time.py)
 * interleaves runs of every configuration and takes medians. */
static void bench(const tgi_raster_mesh *mesh, int w, int h, int frames)
{
    size_t n = (size_t)w * (size_t)h;
    tgi_gbuffer gb;
    void *mem = calloc(tgi_gbuffer_carve(&gb, w, h, NULL), 1);
    tgi_view view;
    double draw_cpu = 0, draw_wall = 0, clear_cpu = 0, clear_wall = 0;
    long drawn = 0;
    int f;
    size_t i;
    tgi_gbuffer_carve(&gb, w, h, mem);   /* the build's storage (raster/gview.h) */
    gb.materials = mesh->materials;
    gb.object = (uint16_t *)malloc(n * sizeof(uint16_t));
    if (!mem || !gb.object) {
        fprintf(stderr, "bench_raster: out of memory at %dx%d\n", w, h);
        exit(1);
    }
    /* the sphere fills ~90% of the image height */
    tgi_view_make(&view, V(0, 0, -SPHERE_CAM_DIST), V(0, 0, 0), V(0, 1, 0), tg_from_float((float)SPHERE_CAM_FOV),
                 tg_from_float((float)SPHERE_CAM_NEAR), tg_from_float((float)SPHERE_CAM_FAR), w, h);
    for (f = -2; f < frames; f++) {
        double c0 = cpu_seconds(), w0 = wall_seconds(), c1, w1;
        bench_clear(&gb);
        c1 = cpu_seconds(); w1 = wall_seconds();
        bench_draw(&gb, &view, mesh);
        if (f < 0) continue;
        clear_cpu += c1 - c0; clear_wall += w1 - w0;
        draw_cpu += cpu_seconds() - c1; draw_wall += wall_seconds() - w1;
    }
    for (i = 0; i < n; i++) drawn += gb.depth[i] != 0;
    printf("tinygi-%s %dx%d tris=%d frames=%d draw_cpu_ms=%.4f draw_wall_ms=%.4f clear_cpu_ms=%.4f "
           "clear_wall_ms=%.4f covered=%ld gbuffer_fnv=0x%08lx\n",
           TG_NUMBER_NAME, w, h, mesh->tri_count, frames, draw_cpu / frames * 1e3, draw_wall / frames * 1e3,
           clear_cpu / frames * 1e3, clear_wall / frames * 1e3, drawn, gbuffer_hash(&gb));
    fflush(stdout);
    free(mem); free(gb.object);
}

int main(int argc, char **argv)
{
    int frames, sizes[8][2], nsizes, k;
    tg_vec3 *pos = (tg_vec3 *)malloc(sizeof(tg_vec3) * 3 * SPHERE_MAX_TRIS);
    tg_vec3 *nrm = (tg_vec3 *)malloc(sizeof(tg_vec3) * 3 * SPHERE_MAX_TRIS);
    uint16_t *mat = (uint16_t *)calloc(SPHERE_MAX_TRIS, sizeof(uint16_t));
    uint16_t *obj = (uint16_t *)calloc(SPHERE_MAX_TRIS, sizeof(uint16_t));
    tgi_material m;
    tgi_raster_mesh mesh;
    if (sphere_bench_args(argc, argv, "bench_raster", &frames, sizes, &nsizes)) return 2;
    if (!pos || !nrm || !mat || !obj) return 1;
    memset(&m, 0, sizeof m);
    m.albedo = V(0.8, 0.6, 0.4);
    m.f0 = tg_from_float(0.04f);
    tgi_material_finish(&m);
    mesh.pos = pos; mesh.nrm = nrm; mesh.tri_material = mat; mesh.tri_object = obj;
    mesh.materials = &m;
    mesh.tri_count = build_sphere(pos, nrm);
    for (k = 0; k < nsizes; k++) bench(&mesh, sizes[k][0], sizes[k][1], frames);
    free(pos); free(nrm); free(mat); free(obj);
    return 0;
}
