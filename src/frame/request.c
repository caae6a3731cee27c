/* SPDX-License-Identifier: MIT */
/*
 * request.c - what a caller asks for: the request's defaults, and the check
 * of every field against the limits block of tinygi.h (the same limits the
 * CLI and the scene parser use), before anything is planned or allocated.
 * A value past a limit is refused with TG_ERR_INPUT and a message naming
 * the field: "slices must be 1..8, got 20".
 */
#include <string.h>
#include "frame_internal.h"
#include "../core/error.h"

#define UNSET_RADIUS TG_R(-1.0f)   /* tg_request.radius and thickness: the scene's or the default */

void tg_request_defaults(tg_request *r)
{
    if (!r) return;   /* a NULL handle: nothing to fill */
    memset(r, 0, sizeof *r);
    r->width = TG_DEFAULT_WIDTH;
    r->height = TG_DEFAULT_HEIGHT;
    r->frames = 1;
    r->aovs = 1u << TG_AOV_COLOR;
    r->technique = TG_TECH_HBIL;
    r->slices = 0;
    r->samples = 0;
    r->radius = UNSET_RADIUS;
    r->bounces = -1;
    r->interleave = 1;
    r->gi_scale = 1;
    r->temporal = 1;
    r->exposure = TG_ONE;
    r->shadow_map_size = TG_DEFAULT_SHADOW_MAP;
    r->thickness = UNSET_RADIUS;
    r->shadow_pcf = 1;   /* bilinear: nearer hard shadows than the tent at the size rule's density */
}

/* 1 (and the message) when v is outside lo..hi. */
static int int_outside(tg_error *err, const char *name, long v, long lo, long hi)
{
    if (v >= lo && v <= hi) return 0;
    tgi_error_range(err, name, lo, hi);
    tgi_error_append_int(err, v);
    return 1;
}

/* Reals: NaN and the infinities are outside every range. */
static int real_outside(tg_error *err, const char *name, tg_real v, long lo, long hi)
{
    if (tg_isfinite(v) && v >= tg_from_int((int32_t)lo) && v <= tg_from_int((int32_t)hi)) return 0;
    tgi_error_range(err, name, lo, hi);
    tgi_error_append_real(err, v);
    return 1;
}

static int size_outside(const tg_request *r, tg_error *err)
{
    if (int_outside(err, "width", r->width, 1, TG_MAX_IMAGE_SIDE)) return 1;
    if (int_outside(err, "height", r->height, 1, TG_MAX_IMAGE_SIDE)) return 1;
    return int_outside(err, "pixels (width x height)", (long)r->width * r->height, 1, TG_MAX_IMAGE_PIXELS);
}

static int aovs_outside(const tg_request *r, tg_error *err)
{
    uint32_t all = (1u << TG_AOV_COUNT) - 1u;
    if (!(r->aovs & ~all)) return 0;
    tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "aovs must be 0..");
    tgi_error_append_int(err, (long)all);
    tgi_error_append(err, " (one bit per TG_AOV_*), got bit ");
    tgi_error_append_int(err, (long)tgi_bit_length64(r->aovs) - 1);
    return 1;
}

/* The GI settings; <= 0 slices or samples, -1 radius and < 0 bounces are
 * unset (the scene's gi line or the default decide). */
static int gi_outside(const tg_request *r, tg_error *err)
{
    if (r->slices > 0 && int_outside(err, "slices", r->slices, 1, TG_MAX_SLICES)) return 1;
    if (r->samples > 0 && int_outside(err, "samples", r->samples, 1, TG_MAX_SAMPLES)) return 1;
    if (r->radius != UNSET_RADIUS && real_outside(err, "radius", r->radius, 0, TG_MAX_RADIUS)) return 1;
    if (r->bounces >= 0 && int_outside(err, "bounces", r->bounces, 0, TG_MAX_BOUNCES)) return 1;
    if (r->thickness != UNSET_RADIUS && real_outside(err, "thickness", r->thickness, 0, TG_MAX_THICKNESS)) return 1;
    return 0;
}

/* More than one depth layer for a technique that does not read them: the
 * visibility bitmask (ssilvb) and HBIL's kernel over them (at full
 * resolution, or with --gi-quarter on the half-resolution image, whose
 * layers are point-sampled down as its depth is). */
static int depth_layers_unread(const tg_request *r, tg_error *err)
{
#if TG_NO_TECHNIQUES
    (void)r; (void)err;   /* one layer at most (int_switches) */
    return 0;
#else
    if (r->depth_layers < 2 || r->technique == TG_TECH_SSILVB || r->technique == TG_TECH_HBIL) return 0;
    tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "depth_layers must be 0..1 for technique ");
    tgi_error_append(err, tg_technique_name(r->technique));
    tgi_error_append(err, " (further layers are read by techniques hbil and ssilvb), got ");
    tgi_error_append_int(err, r->depth_layers);
    return 1;
#endif
}

/* The int switches, each with exactly the values documented in tinygi.h
 * (a table: one loop is smaller than a call each in the smallest builds). */
typedef struct int_switch {
    const char *name;
    unsigned short offset;        /* of the int field in tg_request */
    signed char lo, hi;
} int_switch;
#define SWITCH(f, lo, hi) { #f, (unsigned short)offsetof(tg_request, f), lo, hi }
static const int_switch int_switches[] = {
    SWITCH(interleave, 0, 1), SWITCH(gi_scale, 1, 2), SWITCH(temporal, 0, 1), SWITCH(far_mode, 0, 1),
    SWITCH(shadow_pcf, 0, 1),
    /* shadow rays trace the reference's BVH (left out by TG_NO_REFERENCE) */
    SWITCH(shadow_method, TG_SHADOWS_AUTO, TG_NO_REFERENCE ? TG_SHADOWS_MAPS : TG_SHADOWS_RAYS),
    SWITCH(game_loop, 0, 1), SWITCH(ao_multibounce, 0, 1),
    /* further layers are read by the visibility bitmask (left out by TG_NO_TECHNIQUES) */
    SWITCH(depth_layers, 0, TG_NO_TECHNIQUES ? 1 : TG_MAX_DEPTH_LAYERS)
};
#undef SWITCH

static int switch_outside(const tg_request *r, tg_error *err)
{
    size_t k;
    if (int_outside(err, "technique", (long)r->technique, 0, TG_TECH_COUNT - 1)) return 1;
    for (k = 0; k < sizeof int_switches / sizeof int_switches[0]; k++) {
        const int_switch *w = &int_switches[k];
        if (int_outside(err, w->name, *(const int *)(const void *)((const char *)r + w->offset), w->lo, w->hi))
            return 1;
    }
    return depth_layers_unread(r, err);
}

int tgi_request_refused(const tg_request *r, tg_error *err)
{
    return size_outside(r, err)
        || int_outside(err, "frames", r->frames, 1, TG_MAX_FRAMES)
        || aovs_outside(r, err)
        || switch_outside(r, err)
        || gi_outside(r, err)
        || real_outside(err, "exposure", r->exposure, 0, TG_MAX_EXPOSURE)
        || (r->shadow_map_size > 0
            && int_outside(err, "shadow_map_size", r->shadow_map_size, TG_MIN_SHADOW_MAP, TG_MAX_SHADOW_MAP));
}

/* The gather radius of a scene that gives none.  Without an environment
 * the far field is zero and the near field is all the indirect light
 * (HBIL eq. 15-17): a radius shorter than the scene drops the light of
 * every surface beyond it, so it spans the scene (its bounds' diagonal;
 * the screen bounds the march).  With an environment, directions with
 * nothing within the radius see the sky instead, and the environment's
 * ground where the scene's own lit floor is what a path would meet.  For
 * AO alone a local radius (diagonal / TG_RADIUS_ENV_DIVISOR), on one depth
 * layer or more (what AO means, the ray-traced reference's cut-off, does
 * not change with the layers a frame reads): on one it keeps a foreground
 * object from occluding, in the depth buffer, what lies far behind it.
 * Light reaches further (diagonal / TG_RADIUS_LIGHT_DIVISOR): where a
 * foreground object is taken as solid the direction sends that object's
 * own light in place of the sky's, an error far smaller than an AO of 0
 * for 1, while a local radius takes the environment's ground for every lit
 * surface beyond it (builtin:groove's wall, lit by the floor in front of
 * it: colour RMSE 0.080 -> 0.056 against the path tracer; spheres 0.043 ->
 * 0.055, both sizes alike; README "Colour against the path tracer").  A
 * scene without extent gets TG_DEFAULT_RADIUS. */
#define LIGHT_AOVS ((1u << TG_AOV_COLOR) | (1u << TG_AOV_IRRADIANCE) | (1u << TG_AOV_NEAR) | (1u << TG_AOV_FAR))
static tg_real scene_gather_radius(const tg_scene *s, const tg_request *r)
{
    tg_real d = tgi_v3_length(tgi_v3_sub(s->bounds_max, s->bounds_min));
    int halved = 0;
#if TG_FIXED
    if (d >= TG_REAL_MAX) {
        /* the diagonal beyond Q16.16's range (a scene across more than
         * 32767 units, each coordinate within it): the extent halved until
         * each axis is within half the range, the radius doubled back
         * after the division (it saturated: +-20000 with an env gave 5461
         * against float's 9428; test_request gather_radius_of_a_scene_past_the_range) */
        int64_t ex = (int64_t)s->bounds_max.x - s->bounds_min.x, ey = (int64_t)s->bounds_max.y - s->bounds_min.y;
        int64_t ez = (int64_t)s->bounds_max.z - s->bounds_min.z;
        while (ex > TG_REAL_MAX / 2 || ey > TG_REAL_MAX / 2 || ez > TG_REAL_MAX / 2) ex >>= 1, ey >>= 1, ez >>= 1, halved++;
        d = tgi_v3_length(tg_v3((tg_real)ex, (tg_real)ey, (tg_real)ez));
    }
#endif
    if (d <= 0) return tg_from_int(TG_DEFAULT_RADIUS);
    if (s->env.type != TG_ENV_NONE)
        d = tg_div(d, tg_from_int(r->aovs & LIGHT_AOVS ? TG_RADIUS_LIGHT_DIVISOR : TG_RADIUS_ENV_DIVISOR));
    return tg_min(tg_ldexp(d, halved), tg_from_int(TG_MAX_RADIUS));
}

#if TGI_DEPTH_LAYERS
/* AO alone (ao, bent, cone; no light) from HBIL at every pixel. */
static int hbil_ao_alone(const tg_request *r)
{
    return (r->aovs & TGI_AO_AOVS) && !(r->aovs & LIGHT_AOVS) && r->technique == TG_TECH_HBIL && r->gi_scale == 1;
}
#endif

/* The depth layers of a request that leaves them to the plan (0): two for
 * HBIL's AO alone at every pixel in a scene with an environment, where AO
 * decides how much sky a surface sees and one layer takes the ground
 * hidden behind every closed object as solid (builtin:spheres at 160x120,
 * AO RMSE against the ray-traced reference 0.047 -> 0.026, columns 0.052
 * -> 0.033; README "AO alone takes two layers in the open"), at no memory (the second
 * layer's 8-bit codes hold the filtered AO once the kernel has read them:
 * layout.c group_color) for about twice the instructions; one otherwise:
 * light meets its goals on one layer at a third of the cost, in a closed
 * room the layers add nothing (builtin:cornell 0.028 -> 0.029),
 * --gi-quarter is the cheap setting, and a build without the layers
 * (TG_NO_TECHNIQUES) has one. */
#if TGI_DEPTH_LAYERS
static int planned_depth_layers(const tg_request *r, const tg_scene *s)
{
    int ao_wanted = s->effects_auto || (s->effects & TG_EFFECT_AO);
    return hbil_ao_alone(r) && ao_wanted && s->env.type != TG_ENV_NONE ? 2 : 1;
}
#endif

/* Unset GI settings from the scene's gi line, else the defaults (the
 * radius: sized to the scene); then the scene's values are checked like
 * the request's. */
int tgi_request_resolve(tg_request *r, const tg_scene *s, tg_error *err)
{
    if (r->technique == TG_TECH_PATHTRACE) {   /* the scene's gi line is the screen-space kernel's */
        if (r->samples <= 0) r->samples = TG_DEFAULT_PATHTRACE_SAMPLES;
        if (r->bounces < 0) r->bounces = TG_DEFAULT_PATHTRACE_BOUNCES;
    }
    if (r->slices <= 0) r->slices = s->gi.slices > 0 ? s->gi.slices : TG_DEFAULT_SLICES;
    if (r->aovs == 0) r->aovs = 1u << TG_AOV_COLOR;
#if TGI_DEPTH_LAYERS   /* else one layer (0 and 1 alike) */
    if (r->depth_layers == 0) r->depth_layers = planned_depth_layers(r, s);
    if (r->samples <= 0 && s->gi.samples <= 0 && hbil_ao_alone(r) && r->depth_layers >= 2)
        r->samples = TG_DEFAULT_LAYERED_AO_SAMPLES;   /* the bitmask counts a sample's whole segment */
#endif
    if (r->samples <= 0) r->samples = s->gi.samples > 0 ? s->gi.samples : TG_DEFAULT_SAMPLES;
    if (r->radius == UNSET_RADIUS) r->radius = s->gi.radius >= 0 ? s->gi.radius : scene_gather_radius(s, r);
    if (r->bounces < 0) r->bounces = s->gi.bounces >= 0 ? s->gi.bounces : TG_DEFAULT_BOUNCES;
    if (r->thickness == UNSET_RADIUS) r->thickness = tg_div(r->radius, tg_from_int(TG_THICKNESS_RADIUS_DIVISOR));
    if (r->shadow_map_size <= 0) r->shadow_map_size = TG_DEFAULT_SHADOW_MAP;   /* 0: the size rule */
    if (!gi_outside(r, err)) return 0;
    tgi_error_append(err, " (the scene's gi line)");
    return 1;
}
