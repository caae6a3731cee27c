/* SPDX-License-Identifier: MIT */
/*
 * gbuffer.h - the geometry buffer the rasterizer writes and every later pass
 * reads (through the accessors of gview.h, never these fields).  Row-major,
 * index = y * width + x.
 *
 * Storage (pack.h has the formats), the same in both number types:
 *   depth  32 bits: binary32 bits of the view depth; 0 = sky (no triangle)
 *   nm     32 bits: octahedral world normal, 2 x 11 bits, and the material
 *          index above them (10 bits: albedo, F0 and emissive come from the
 *          scene's material table, `materials`)
 * 8 bytes a pixel.  A frame that reads no material (AO only) has n8, the
 * octahedral normal in 2 x 8 bits, instead of nm: 6 bytes a pixel.  Built with TG_WIDE_STORAGE=1 the G-buffer (and the GI
 * results and colour planes of gview.h) are tg_real planes instead, 18
 * bytes a pixel here: the reference the compact formats are measured
 * against (tests/storage_test.sh, the bench's wide rows).
 */
#ifndef TG_GBUFFER_H
#define TG_GBUFFER_H

#include "../core/vec.h"
#include "../core/material.h"

#ifndef TG_WIDE_STORAGE
#define TG_WIDE_STORAGE 0
#endif

/* The further depth layers (request.depth_layers, back_depth and
 * behind_depth below) are read by the visibility bitmask alone: left out
 * with the techniques (tinygi.h "FEATURE SWITCHES"). */
#define TGI_DEPTH_LAYERS (!TG_NO_TECHNIQUES)

#define TGI_NORMAL_BITS 11                 /* per octahedral coordinate */
#define TGI_MATERIAL_SHIFT (2 * TGI_NORMAL_BITS)
#define TGI_NORMAL_MASK ((1u << TGI_MATERIAL_SHIFT) - 1u)
#if TG_MAX_MATERIALS > (1 << (32 - TGI_MATERIAL_SHIFT))
#error "TG_MAX_MATERIALS does not fit the G-buffer's material index bits"
#endif

typedef struct tgi_gbuffer {
    int width, height;
#if TG_WIDE_STORAGE
    tg_real *depth;               /* linear view depth (view-space z); 0 on sky */
    tg_real *nx, *ny, *nz;        /* world-space unit normal (faces the viewer) */
    uint16_t *material;           /* index into materials */
#else
    uint32_t *depth;              /* binary32 bits of the view depth; 0 on sky */
    uint32_t *nm;                 /* octahedral normal | material index << TGI_MATERIAL_SHIFT */
    uint16_t *n8;                 /* instead of nm when no pass reads a material (AO
                                     only): octahedral normal 2 x 8 bits */
#endif
    const tgi_material *materials;/* the scene's material table */
    int has_emissive;             /* some material of the table emits */
    uint16_t *object;             /* object index per pixel (objects move); NULL if unused */
#if TGI_DEPTH_LAYERS && TG_WIDE_STORAGE
    tg_real *back_depth, *behind_depth;
#elif TGI_DEPTH_LAYERS
    uint8_t *back_depth;          /* the second depth layer: view depth of the nearest back
                                     face at or behind the pixel's surface, as an 8-bit code
                                     against its depth (tgi_back_code, pack.h); 0 where none;
                                     NULL unless planned (request.depth_layers >= 2) */
    uint32_t *behind_depth;       /* the third: the nearest surface behind that back face
                                     (request.depth_layers 3); 0 where none */
#endif
    tg_real *motion_x, *motion_y; /* previous-frame screen position of this pixel's surface
                                     (continuous pixel coordinates); NULL unless planned */
} tgi_gbuffer;

/* Bytes a pixel of the G-buffer's depth, normal and material. */
#if TG_WIDE_STORAGE
#define TGI_GBUFFER_PIXEL_BYTES (4 * sizeof(tg_real) + sizeof(uint16_t))
#else
#define TGI_GBUFFER_PIXEL_BYTES (2 * sizeof(uint32_t))
#endif

#endif
