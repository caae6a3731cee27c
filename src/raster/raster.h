/* SPDX-License-Identifier: MIT */
/*
 * raster.h - the triangle rasterizer: world-space triangles into the G-buffer
 * (tgi_raster_gbuffer) or into a depth-only map for shadows (tgi_raster_depth).
 *
 * Pipeline per triangle: world -> clip (view.h conventions), outcodes,
 * homogeneous clipping (near, far, and a guard band for the screen edges)
 * only when a vertex needs it, snap to 28.4 fixed-point screen coordinates
 * (the same integers in the float and the Q16.16 build), back-face culling,
 * bounding box, incremental integer edge functions (64-bit) with the
 * top-left fill rule, perspective-correct interpolation of 1/w and the
 * normal, depth test on linear depth (nearest wins).
 *
 * Guarantees:
 *  - triangles sharing an edge cover each pixel centre exactly once
 *    (top-left rule on exact integer edge functions);
 *  - a triangle crossing the near plane is clipped, never dropped, and
 *    nothing behind the camera (w <= znear) is drawn;
 *  - screen coordinates stay within +-(GUARD + 1) screen sizes, so the
 *    28.4 integers never overflow; width and height must be at most
 *    TG_MAX_IMAGE_SIDE (tinygi.h), shadow maps included.
 *  - only rows [y0, y1) are written: several threads may split the rows
 *    of one image between them (every thread walks all triangles).
 */
#ifndef TG_RASTER_H
#define TG_RASTER_H

#include "../core/vec.h"
#include "../core/material.h"
#include "gbuffer.h"
#include "view.h"

#define TG_RASTER_SUBPIXEL_BITS 4   /* 28.4 screen coordinates */

typedef struct tgi_raster_mesh {
    const tg_vec3 *pos;   /* 3 per triangle, world space */
    const tg_vec3 *nrm;   /* 3 per triangle, unit world-space vertex normals */
    const uint16_t *tri_material, *tri_object; /* per triangle; tri_object may be NULL (object 0) */
    int tri_count;
    const tgi_material *materials;
} tgi_raster_mesh;

/* Sky everywhere in rows [y0, y1): sky = 1, depth = 0, normal = 0, albedo = 0,
 * f0 = 0, emissive = 0 (if present), object = 0xFFFF (if present). */
void tgi_gbuffer_clear_rows(tgi_gbuffer *gb, int y0, int y1);

/* Rasterize every triangle into G-buffer rows [y0, y1).  Writes depth (view
 * z), the perspective-correct interpolated vertex normal renormalized per
 * pixel (flipped for the back face of a twosided material), albedo, f0,
 * emissive (if gb->emit_r), sky = 0 and object (if gb->object).  Back faces
 * (clockwise on screen as the viewer sees them) of one-sided materials are
 * culled.  The G-buffer must be cleared first (tgi_gbuffer_clear_rows). */
void tgi_raster_gbuffer(tgi_gbuffer *gb, const tgi_view *view, const tgi_raster_mesh *mesh, int y0, int y1);

/* Depth only (shadow maps): clip = world_to_clip * p, NDC = clip / w,
 * texel x = (ndc_x + 1) / 2 * width, y = (1 - ndc_y) / 2 * height.
 *   Perspective (orthographic == 0): clip volume -w <= z <= w (the OpenGL
 *     convention: near and far come from the matrix's z row); stored depth =
 *     clip w (the light's view z), interpolated perspective-correctly.
 *   Orthographic (clip w == 1): clip volume z >= 0 (no far plane); stored
 *     depth = clip z, interpolated linearly.
 * No culling (both faces).  depth[] (width * height) must be cleared by the
 * caller to TG_REAL_MAX; the nearest value is kept.  Rows [y0, y1) only. */
void tgi_raster_depth(tg_real *depth, int width, int height, const tgi_mat4 *world_to_clip,
                     int orthographic, const tg_vec3 *pos, int tri_count, int y0, int y1);

/* The same into 16-bit codes (shadow maps at half the memory): a depth d
 * is stored as q = round((d - depth_lo) 65536 / depth_range), clamped to
 * [0, TG_RASTER_DEPTH16_EMPTY - 1], and reads back as
 * depth_lo + q depth_range / 65536, within half a step (depth_range / 2^17)
 * plus the number type's rounding.  depth[] must be cleared by the caller to
 * TG_RASTER_DEPTH16_EMPTY; the smallest code is kept.  depth_range > 0
 * (nothing is drawn otherwise). */
#define TG_RASTER_DEPTH16_EMPTY 0xFFFF
void tgi_raster_depth16(uint16_t *depth, int width, int height, const tgi_mat4 *world_to_clip,
                       int orthographic, tg_real depth_lo, tg_real depth_range,
                       const tg_vec3 *pos, int tri_count, int y0, int y1);

/* Test hook for the fill rule: add 1 to count[y * width + x] for every pixel
 * whose centre each triangle covers, using the rasterizer's own edge setup
 * and top-left rule, both faces, no depth test.  xy holds 6 integers per
 * triangle: screen x, y of three vertices in 28.4 fixed point (pixel units
 * * 16), each within +-2^19.  Zero-area triangles cover nothing. */
void tgi_raster_coverage_count(uint16_t *count, int width, int height,
                              const int32_t *xy, int tri_count, int y0, int y1);

#endif
