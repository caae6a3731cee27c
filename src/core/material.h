/* SPDX-License-Identifier: MIT */
/*
 * material.h - a surface material as the scene parser stores it and the
 * rasterizer writes it into the G-buffer (core, so that neither of the two
 * includes the other).
 */
#ifndef TG_MATERIAL_H
#define TG_MATERIAL_H

#include "vec.h"

typedef struct tgi_material {
    char name[TG_MAX_NAME + 1];
    tg_vec3 albedo;             /* linear RGB reflectance, each in [0, 1] */
    tg_real f0;                 /* Fresnel reflectance at normal incidence, [0, 1] */
    tg_vec3 emissive;           /* linear RGB radiance, >= 0 */
    int twosided;               /* not back-face culled; normal flips to face the viewer */
} tgi_material;

#endif
