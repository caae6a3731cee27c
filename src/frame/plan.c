/* SPDX-License-Identifier: MIT */
/*
 * plan.c - the frame is a plan.
 *
 * Before any pixel is touched, the scene and the request decide which
 * effects a frame simulates; the pass table (passes.c) then gives the passes
 * the plan needs, in order, and the buffers they use (layout.c), with their
 * sizes.  What the scene does not call for is neither computed nor
 * allocated:
 *   no light                      -> no direct pass
 *   no light marked `shadows`     -> no shadow maps
 *   no environment                -> no far-field pass
 *   nothing lit or emissive, zero albedo everywhere, or bounces 0
 *                                 -> no near-field gathering, no radiance history
 *   one frame                     -> no reprojection, no temporal state
 *   only ao / bent / cone asked   -> nothing after the kernel
 * `effects LIST` in the scene forces (or, by omission, forbids) effects.
 * tg_plan_explain prints the plan: the same list of passes the frame runs.
 */
#include <string.h>
#include "frame_internal.h"
#include "../core/error.h"
#include "../core/text.h"
#include "../scene/anim.h"
#include "../light/shadowview.h"

#define AOV(a) (1u << (a))
#define RADIANCE_AOVS (AOV(TG_AOV_COLOR) | AOV(TG_AOV_IRRADIANCE) | AOV(TG_AOV_DIRECT) | AOV(TG_AOV_NEAR) | AOV(TG_AOV_FAR))

static int positive(tg_vec3 c) { return c.x > 0 || c.y > 0 || c.z > 0; }

static int scene_has_emissive(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->material_count; i++)
        if (positive(s->materials[i].emissive)) return 1;
    return 0;
}

static int scene_has_albedo(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->material_count; i++)
        if (positive(s->materials[i].albedo)) return 1;
    return 0;
}

static int scene_has_shadow_light(const tg_scene *s)
{
    int i;
    for (i = 0; i < s->light_count; i++)
        if (s->lights[i].shadows) return 1;
    return 0;
}

static int technique_gathers_near(tg_technique t)
{
    return t == TG_TECH_HBIL || t == TG_TECH_SSDO || t == TG_TECH_REFERENCE || t == TG_TECH_SSILVB;
}

/* Effects the scene makes possible at all. */
static uint32_t possible_effects(const tg_scene *s, const tg_request *r)
{
    uint32_t e = TG_EFFECT_AO;
    if (s->light_count > 0) e |= TG_EFFECT_DIRECT;
    if (s->light_count > 0 && scene_has_shadow_light(s)) e |= TG_EFFECT_SHADOWS;
    if (s->env.type != TG_ENV_NONE) e |= TG_EFFECT_FAR;
    if (r->bounces != 0 && technique_gathers_near(r->technique) && scene_has_albedo(s) &&
        (s->light_count > 0 || scene_has_emissive(s)))
        e |= TG_EFFECT_NEAR;
    if (r->frames > 1 && r->technique == TG_TECH_HBIL) e |= TG_EFFECT_REPROJECTION;
    return e;
}

/* Effects the request calls for, given what is possible. */
static uint32_t wanted_effects(uint32_t possible, uint32_t aovs)
{
    int color = (aovs & (AOV(TG_AOV_COLOR) | AOV(TG_AOV_IRRADIANCE))) != 0;
    int want_near = color || (aovs & AOV(TG_AOV_NEAR));
    int want_far = color || (aovs & AOV(TG_AOV_FAR));
    int want_ao = (aovs & TGI_AO_AOVS) != 0;
    uint32_t e = 0;
    if (want_near && (possible & TG_EFFECT_NEAR)) e |= TG_EFFECT_NEAR;
    if (want_far && (possible & TG_EFFECT_FAR)) e |= TG_EFFECT_FAR;
    if ((color || (aovs & AOV(TG_AOV_DIRECT)) || (e & TG_EFFECT_NEAR)) && (possible & TG_EFFECT_DIRECT))
        e |= TG_EFFECT_DIRECT;
    if ((e & TG_EFFECT_DIRECT) && (possible & TG_EFFECT_SHADOWS)) e |= TG_EFFECT_SHADOWS;
    if (want_ao || (e & (TG_EFFECT_NEAR | TG_EFFECT_FAR))) e |= TG_EFFECT_AO;
    if ((e & TG_EFFECT_NEAR) && (possible & TG_EFFECT_REPROJECTION)) e |= TG_EFFECT_REPROJECTION;
    return e;
}

/* "HEAD[NAME] left out of this build (SWITCH=1)[WHY]": a feature the
 * plan needs is not in this build (tinygi.h "FEATURE SWITCHES"). */
static int refuse_left_out(tg_error *err, const char *head, const char *name, const char *sw, const char *why)
{
    tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, head);
    if (name) {
        tgi_error_append(err, name);
        tgi_error_append(err, " is");
    }
    tgi_error_append(err, " left out of this build (");
    tgi_error_append(err, sw);
    tgi_error_append(err, "=1)");
    if (why) tgi_error_append(err, why);
    return 1;
}

/* The scene has keys (camera or objects). */
static int scene_has_keys(const tg_scene *s)
{
    int i;
    if (s->camera_key_count > 0) return 1;
    for (i = 0; i < s->object_count; i++)
        if (s->objects[i].key_count > 0) return 1;
    return 0;
}

/* 1 (and the message) when the plan needs a feature this build leaves out. */
static int left_out(const tg_plan *p, tg_error *err)
{
    tg_technique t = p->request.technique;
    int reads_env = p->scene->env.type != TG_ENV_NONE &&
                    ((p->effects & TG_EFFECT_FAR) || (tgi_frame_needs(p) & TG_NEED_COMPOSE));
    if (TG_NO_TECHNIQUES && t != TG_TECH_HBIL && t != TG_TECH_REFERENCE)
        return refuse_left_out(err, "technique ", tg_technique_name(t), "TG_NO_TECHNIQUES", NULL);
    if (TG_NO_REFERENCE && t == TG_TECH_REFERENCE)
        return refuse_left_out(err, "technique ", tg_technique_name(t), "TG_NO_REFERENCE", NULL);
    if (TG_NO_SHADOW_MAPS && (p->effects & TG_EFFECT_SHADOWS))
        return refuse_left_out(err, "shadow maps are", NULL, "TG_NO_SHADOW_MAPS",
                               ": a light the plan uses is marked `shadows`");
    if (TG_NO_ENVIRONMENT && reads_env)
        return refuse_left_out(err, "the environment is", NULL, "TG_NO_ENVIRONMENT",
                               ": the plan reads the scene's env (the far field, or the sky behind colour)");
    if (TG_NO_COLOR && ((p->effects & (TG_EFFECT_DIRECT | TG_EFFECT_NEAR | TG_EFFECT_FAR | TG_EFFECT_REPROJECTION)) ||
                        (p->request.aovs & RADIANCE_AOVS)))
        return refuse_left_out(err, "colour is", NULL, "TG_NO_COLOR",
                               ": the plan asks for light (colour, irradiance, direct, near or far); "
                               "AO, bent normals, cones and the geometry AOVs render");
    if (TG_NO_BENT_NORMALS && (tgi_frame_needs(p) & (TG_NEED_BENT | TG_NEED_CONE)))
        return refuse_left_out(err, "bent normals are", NULL, "TG_NO_BENT_NORMALS",
                               ": the plan asks for the bent or cone AOV, or the far field (lit in the bent "
                               "cone); ask for ao");
    if (TG_NO_ANIMATION && scene_has_keys(p->scene))
        return refuse_left_out(err, "scene keys are", NULL, "TG_NO_ANIMATION",
                               ": the scene has camera or object keys; set the camera and objects from the "
                               "program (tg_frame_set_camera, tg_frame_set_object)");
    if (TG_NO_GI_QUARTER && t == TG_TECH_HBIL && p->request.interleave && p->request.gi_scale == 2)
        return refuse_left_out(err, "quarter-resolution GI is", NULL, "TG_NO_GI_QUARTER", ": ask for gi_scale 1");
    if (TG_NO_TEMPORAL && ((p->effects & TG_EFFECT_REPROJECTION) ||
                           (tgi_frame_needs(p) & (TG_NEED_TEMPORAL | TG_NEED_MOTION))))
        return refuse_left_out(err, "history across frames is", NULL, "TG_NO_TEMPORAL",
                               ": the plan needs temporal accumulation, reprojection of radiance or motion "
                               "vectors; ask for one frame, or temporal 0 without the near field");
    return 0;
}

uint32_t tgi_frame_needs(const tg_plan *p)
{
    const tg_scene *s = p->scene;
    const tg_request *r = &p->request;
    uint32_t n = 0, e = p->effects;
    if (e & (TG_EFFECT_AO | TG_EFFECT_NEAR)) n |= TG_NEED_GI_PASS;
    if (r->aovs & (AOV(TG_AOV_COLOR) | AOV(TG_AOV_IRRADIANCE))) n |= TG_NEED_COMPOSE;
    /* next frame's near field gathers this frame's outgoing radiance */
    if (e & TG_EFFECT_REPROJECTION) n |= TG_NEED_COMPOSE;
    if (tgi_anim_has_posed_objects(s) || (r->game_loop && s->object_count > 0)) n |= TG_NEED_POSE;
    /* reprojection and temporal accumulation find last frame's pixel
     * through the depth and the cameras (and the posed objects' motion):
     * motion vectors are for their AOV alone */
    if ((r->aovs & AOV(TG_AOV_MOTION)) && r->frames > 1) n |= TG_NEED_MOTION;
    if (r->frames > 1 && r->temporal && r->technique == TG_TECH_HBIL && (e & TG_EFFECT_AO))
        n |= TG_NEED_TEMPORAL;
    if ((e & TG_EFFECT_FAR) || (r->aovs & AOV(TG_AOV_BENT))) n |= TG_NEED_BENT;
    if (r->aovs & AOV(TG_AOV_CONE)) n |= TG_NEED_CONE;
    return n;
}

tg_status tg_plan_make(tg_plan *plan, const tg_scene *scene, const tg_request *req, tg_error *err)
{
    tg_frame probe, *pp = &probe;
    uint32_t possible;
    tgi_error_clear(err);
    if (plan) memset(plan, 0, sizeof *plan);   /* a failed call leaves total_bytes 0, whatever fails */
    if (!plan || !scene || !req) {   /* a failed tg_scene_parse leaves a NULL scene */
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "tg_plan_make: plan, scene and request must not be NULL");
        return TG_ERR_INPUT;
    }
    memset(plan, 0, sizeof *plan);
    plan->request = *req;
    plan->scene = scene;
    if (tgi_request_refused(req, err) || tgi_request_resolve(&plan->request, scene, err))
        return TG_ERR_INPUT;
    possible = possible_effects(scene, &plan->request);
    if (scene->effects_auto) plan->effects = wanted_effects(possible, plan->request.aovs);
    else plan->effects = scene->effects & possible;
    if (plan->request.technique == TG_TECH_PATHTRACE) plan->effects = 0;   /* it traces all light itself */
    if (plan->effects & TG_EFFECT_NEAR) plan->effects |= TG_EFFECT_AO;
    if (!(plan->effects & TG_EFFECT_DIRECT)) plan->effects &= ~(uint32_t)TG_EFFECT_SHADOWS;
    if (!(plan->effects & TG_EFFECT_NEAR)) plan->effects &= ~(uint32_t)TG_EFFECT_REPROJECTION;
    if (left_out(plan, err)) return TG_ERR_INPUT;
    memset(&probe, 0, sizeof probe);
    if (tgi_frame_layout(&pp, plan, NULL) != 0) {
        tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, "frame size overflows the address space");
        return TG_ERR_INPUT;
    }
    return TG_OK;
}

/* ---- explain ---- */

static void put_effects(tgi_text *t, uint32_t e)
{
    static const char *const names[6] = { "direct", "shadows", "far", "near", "ao", "reprojection" };
    int i, any = 0;
    for (i = 0; i < 6; i++) {
        if (!(e & (1u << i))) continue;
        if (any) tgi_text_put(t, " ");
        tgi_text_put(t, names[i]);
        any = 1;
    }
    if (!any) tgi_text_put(t, "(none)");
}

static void put_number_line(tgi_text *t, const char *a, size_t v, const char *b)
{
    tgi_text_put(t, a);
    tgi_text_put_uint(t, v);
    tgi_text_put(t, b);
}

/* "  N. NAME [on which frames] (serial)": the passes as the frame runs them,
 * the bounce loop announced before its first pass. */
static void put_passes(tgi_text *t, const tg_plan *plan)
{
    int i, in_loop = 0, bounces = (plan->effects & TG_EFFECT_NEAR) ? plan->request.bounces : 1;
    for (i = 0; i < plan->pass_count; i++) {
        const tgi_pass *p = &tgi_passes[plan->pass_rows[i]];
        int loop = (p->when & TGI_BOUNCE) && bounces > 1;
        if (loop && !in_loop)
            put_number_line(t, "  (on a frame without history the next passes run ", (size_t)bounces,
                            " times: gi bounces)\n");
        if (!loop && in_loop) tgi_text_put(t, "  (end of the bounces)\n");
        in_loop = loop;
        put_number_line(t, "  ", (size_t)(i + 1), ". ");
        tgi_text_put(t, p->name);
        if (p->when & TGI_ON_FIRST_FRAME) tgi_text_put(t, " [frames without history]");
        if (p->when & TGI_ON_HISTORY) tgi_text_put(t, " [frames with history]");
        if (p->rows == TGI_SERIAL) tgi_text_put(t, " (serial)");
        tgi_text_put(t, "\n");
    }
}

/* The visibility bitmask reads the thickness (Therrien et al. 2023: a
 * sample occludes the sectors between its front and its front plus the
 * thickness, src/ao/ssilvb.c): ssilvb always, hbil when its kernel is the bitmask over depth
 * layers (hbil_passes.c, tgi_pass_hbil_layers). */
int tg_plan_reads_thickness(const tg_plan *plan)
{
    return plan->request.technique == TG_TECH_SSILVB ||
           (plan->request.technique == TG_TECH_HBIL && plan->request.depth_layers >= 2);
}

size_t tg_plan_explain(const tg_plan *plan, char *buf, size_t size)
{
    tgi_text t;
    int i;
    size_t pixels;
    tgi_text_init(&t, buf, size);
    if (!plan) return 0;   /* nothing to explain: "" */
    pixels = (size_t)plan->request.width * (size_t)plan->request.height;
    put_number_line(&t, "plan: ", (size_t)plan->request.width, "x");
    put_number_line(&t, "", (size_t)plan->request.height, ", technique ");
    tgi_text_put(&t, tg_technique_name(plan->request.technique));
    tgi_text_put(&t, ", number type " TG_NUMBER_NAME);
    put_number_line(&t, ", frames ", (size_t)plan->request.frames, "\neffects: ");
    if (plan->request.technique == TG_TECH_PATHTRACE)
        put_number_line(&t, "(none: path traced, lights, emitters and environment over ", (size_t)plan->request.bounces,
                        " bounces)");
    else put_effects(&t, plan->effects);
    tgi_text_put(&t, "\nskipped: ");
    put_effects(&t, (~plan->effects) & 63u);
    if (plan->request.technique != TG_TECH_PATHTRACE) {   /* the radius a scene without one gets is sized to it */
        tgi_text_put(&t, "\ngather radius ");
        tgi_text_put_real(&t, plan->request.radius);
        put_number_line(&t, " (world units), slices ", (size_t)plan->request.slices, ", samples ");
        put_number_line(&t, "", (size_t)plan->request.samples, "");
    }
    if (tg_plan_reads_thickness(plan)) {   /* the bitmask's surfaces */
        tgi_text_put(&t, "\nvisibility bitmask: radius ");
        tgi_text_put_real(&t, plan->request.radius);
        tgi_text_put(&t, ", thickness ");
        tgi_text_put_real(&t, plan->request.thickness);
        tgi_text_put(&t, " (world units)");
#if !TG_NO_TECHNIQUES
        if (plan->request.depth_layers >= 2)
            put_number_line(&t, "; depth layers ", (size_t)plan->request.depth_layers,
                            plan->request.depth_layers >= 3 ? ": a surface ends at its back face; the thickness is a "
                                                              "twosided sheet's and that of the surface behind"
                                                            : ": a surface ends at its back face; the thickness is a "
                                                              "twosided sheet's");
#endif
    }
    tgi_text_put(&t, "\npasses:\n");
    put_passes(&t, plan);
    if (plan->request.aovs & (AOV(TG_AOV_COLOR) | AOV(TG_AOV_NEAR) | AOV(TG_AOV_FAR) | AOV(TG_AOV_DIRECT) | AOV(TG_AOV_IRRADIANCE)))
        tgi_text_put(&t, "on output: exposure, tonemap + sRGB (8-bit views)\n");
    if (plan->request.ao_multibounce && (plan->request.aovs & AOV(TG_AOV_AO)))
        tgi_text_put(&t, "on output: ao through GTAO's multi-bounce fit (Jimenez et al. 2016, eq. 10) "
                         "with the albedo's luminance (the G-buffer keeps the material)\n");
    tgi_text_put(&t, "buffers:\n");
    for (i = 0; i < plan->buffer_count; i++) {
        tgi_text_put(&t, "  ");
        tgi_text_put(&t, plan->buffers[i].name);
        put_number_line(&t, ": ", plan->buffers[i].bytes, " bytes\n");
    }
    put_number_line(&t, "total: ", plan->total_bytes, " bytes, ");
    put_number_line(&t, "", pixels ? plan->total_bytes / pixels : 0, " bytes per pixel\n");
    if (plan->effects & TG_EFFECT_SHADOWS)
        tgi_shadow_explain(&t, plan->scene, &plan->request,
                           TG_NO_REFERENCE ? SIZE_MAX
                           : plan->request.technique == TG_TECH_REFERENCE ? 0 : tgi_bvh_bytes(plan->scene->tri_count));
    return t.at;
}

int tgi_frame_ao_multibounce(const tg_frame *f)
{
    return f->request.ao_multibounce && (f->request.aovs & AOV(TG_AOV_AO)) != 0;
}

int tgi_frame_interleaved(const tg_frame *f)
{
    return f->request.technique == TG_TECH_HBIL && f->request.interleave;
}

int tgi_request_quarter(const tg_request *r)
{
    return r->technique == TG_TECH_HBIL && r->interleave && r->gi_scale == 2;
}

int tgi_frame_quarter(const tg_frame *f)
{
    return tgi_request_quarter(&f->request);
}

int tgi_frame_near_horizon(const tg_frame *f)
{
    return TG_QUARTER_NEAR_REACH >= 1 && tgi_frame_quarter(f);
}
