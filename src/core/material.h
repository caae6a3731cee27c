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
    tg_vec3 diffuse;            /* albedo / pi (1 - F0): tgi_material_finish's */
} tgi_material;

/* Sets m's diffuse: the radiance a diffuse surface of m sends per unit of
 * irradiance, albedo / pi (1 - F0) (HBIL sec. 2.3: eq. 14's 1 / pi, eq.
 * 19's 1 - F0), which every lit read multiplies by (tgi_gb_lit): formed once
 * a material, not once a read.  Call it after setting albedo or f0. */
static inline void tgi_material_finish(tgi_material *m)
{
    const tg_real kd = tg_mul(tg_saturate(tg_sub(TG_ONE, m->f0)), TG_INV_PI);
    m->diffuse = tg_v3(tg_mul(m->albedo.x, kd), tg_mul(m->albedo.y, kd), tg_mul(m->albedo.z, kd));
}

#endif
