/* SPDX-License-Identifier: MIT */
/*
 * scene.h - the parsed scene, as every pass sees it.
 *
 * Geometry is flattened to triangles at parse time (quads, boxes, spheres and
 * OBJ meshes alike): three world-space positions and three unit vertex
 * normals per triangle, and the object and material each triangle belongs
 * to.  Objects own a contiguous range of triangles; an object with keys
 * (object_key) is moved rigidly per frame by its key transform, applied to
 * its rest-pose triangles.
 */
#ifndef TG_SCENE_H
#define TG_SCENE_H

#include "../tinygi.h"
#include "../core/vec.h"
#include "../core/material.h"

/* The C layout of the scene's tables as tinygi-bake writes them: a baked
 * file stops with #error where it differs (tools/scene_bake.c).  Raised
 * when a baked struct changes: 2, tgi_material.diffuse. */
#define TGI_SCENE_LAYOUT 2

typedef struct tgi_key {         /* object_key: rigid transform at time t */
    tg_real t;
    tg_vec3 translate;
    tg_vec3 axis;               /* unit rotation axis */
    tg_real angle;              /* radians */
} tgi_key;

typedef struct tgi_object {
    char name[TG_MAX_NAME + 1]; /* "" when unnamed */
    int first_tri, tri_count;
    int first_key, key_count;   /* into scene->object_keys, sorted by t */
} tgi_object;

typedef struct tgi_camera_key {
    tg_real t;
    tg_vec3 pos, target;
} tgi_camera_key;

typedef enum tgi_light_type { TG_LIGHT_DIRECTIONAL, TG_LIGHT_POINT, TG_LIGHT_SPOT } tgi_light_type;

typedef struct tgi_light {
    tgi_light_type type;
    tg_vec3 pos;                /* point, spot */
    tg_vec3 dir;                /* unit direction the light travels (directional, spot) */
    tg_vec3 color;              /* linear RGB */
    tg_real intensity;          /* default 1 */
    tg_real angle;              /* spot: half angle of the cone, radians */
    int shadows;
} tgi_light;

typedef enum tgi_env_type { TG_ENV_NONE, TG_ENV_UNIFORM, TG_ENV_SKY, TG_ENV_SH9 } tgi_env_type;

typedef struct tgi_env {
    tgi_env_type type;
    tg_vec3 uniform;            /* TG_ENV_UNIFORM radiance */
    tg_vec3 sky, ground, up;    /* TG_ENV_SKY (up is unit) */
    tg_vec3 sh9[9];             /* TG_ENV_SH9: radiance coefficients L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22 */
} tgi_env;

typedef struct tgi_scene_camera {
    tg_vec3 pos, target, up;    /* up defaults to +Y */
    tg_real fov;                /* vertical field of view, radians (default 60 deg) */
    tg_real znear, zfar;        /* defaults 0.05 and 1000 */
} tgi_scene_camera;

/* gi line; a field < 0 (or 0 for the ints) means "not given" */
typedef struct tgi_gi_settings {
    tg_real radius;
    int slices, samples, bounces;
} tgi_gi_settings;

struct tg_scene {
    tgi_scene_camera camera;
    int camera_key_count;
    tgi_camera_key *camera_keys; /* sorted by t */

    int material_count;
    tgi_material *materials;

    int object_count;
    tgi_object *objects;
    int object_key_count;
    tgi_key *object_keys;

    int tri_count;
    tg_vec3 *tri_pos;           /* 3 per triangle, world space rest pose */
    tg_vec3 *tri_nrm;           /* 3 per triangle, unit */
    uint16_t *tri_material;     /* per triangle */
    uint16_t *tri_object;       /* per triangle */

    int light_count;
    tgi_light *lights;
    tgi_env env;
    tgi_gi_settings gi;
    int effects_auto;           /* 1 unless an `effects LIST` line was given */
    uint32_t effects;           /* TG_EFFECT_* listed, when !effects_auto */

    tg_vec3 bounds_min, bounds_max; /* of all rest-pose triangles */
};

#endif
