/* SPDX-License-Identifier: MIT */
/*
 * compare.c - the papers' other screen-space techniques, run at full
 * resolution from the G-buffer view so the bench can set them beside HBIL
 * and the ray-traced reference.  The request's knobs map onto each:
 *   slices  -> GTAO slices, HBAO directions (2 per slice: a slice has two sides)
 *   samples -> GTAO/HBAO steps per direction, SSAO/VO/SSDO/bent-cone samples
 *   radius  -> every technique's world-space radius
 *   thickness -> the visibility bitmask's surface thickness (ssilvb)
 * Everything else is the technique's documented default.  SSDO and bent
 * cones compute their own environment term (the plan then runs no far-field
 * pass).  The reference ray traces the scene's triangles through a BVH.
 * The path tracer (pathtrace) takes samples as paths per pixel and bounces
 * as the most indirect bounces, and writes the colour and irradiance.
 */
#include "frame_internal.h"
#include "../ao/sampling.h"
#include "../ao/ssao.h"
#include "../ao/vo.h"
#include "../ao/hbao.h"
#include "../ao/gtao.h"
#include "../ao/ssilvb.h"
#include "../ao/ssdo.h"
#include "../ao/bentcone.h"
#include "../ao/reference.h"
#include "../ao/pathtrace.h"
#include "../light/direct.h"

#if !TG_NO_TECHNIQUES /* the techniques' passes (tinygi.h "FEATURE SWITCHES") */
/* The environment's SH9 when the plan has a far field, else NULL. */
static const tg_vec3 *far_sh(const tg_frame *f)
{
    return (f->effects & TG_EFFECT_FAR) ? f->sh : NULL;
}

/* A comparison technique's pass: its parameters from the technique's
 * defaults and the request's knobs (KNOBS, statements on p), then its rows
 * over the full-resolution view (ARGS, the rows function's arguments). */
#define TECHNIQUE_PASS(NAME, KNOBS, ARGS)                                   \
    void tgi_pass_##NAME(tg_frame *f, int y0, int y1)                      \
    {                                                                      \
        tgi_##NAME##_params p;                                             \
        tgi_##NAME##_defaults(&p);                                         \
        p.radius = f->request.radius;                                      \
        KNOBS                                                              \
        tgi_##NAME##_rows ARGS;                                            \
    }
#define SAMPLES p.samples = tgi_ao_count(f->request.samples);
#define SLICES_STEPS p.slices = tgi_ao_count(f->request.slices); p.steps = tgi_ao_count(f->request.samples);
#define FAR_FIELD p.env_sh9 = far_sh(f); if (p.env_sh9) p.far = f->far;
#define RESULTS (&p, &f->full, &f->res, y0, y1)
#define SOURCE_RESULTS (&p, &f->full, tgi_frame_source(f), &f->res, y0, y1)

TECHNIQUE_PASS(ssao, SAMPLES, RESULTS)
TECHNIQUE_PASS(vo, SAMPLES, RESULTS)
/* HBAO's directions are the slices' two sides */
TECHNIQUE_PASS(hbao, p.directions = tgi_ao_count(2 * f->request.slices); p.steps = tgi_ao_count(f->request.samples);,
               RESULTS)
TECHNIQUE_PASS(gtao, SLICES_STEPS, RESULTS)
TECHNIQUE_PASS(ssilvb, SLICES_STEPS p.thickness = f->request.thickness;, SOURCE_RESULTS)
TECHNIQUE_PASS(ssdo, SAMPLES FAR_FIELD, SOURCE_RESULTS)
TECHNIQUE_PASS(bentcone, SAMPLES FAR_FIELD, RESULTS)

#endif /* !TG_NO_TECHNIQUES */

#if !TG_NO_REFERENCE /* the reference's passes */
/* Outgoing diffuse radiance leaving a scene point under the direct lights:
 * the reference's exact one-bounce source (same lights, same shadow maps). */
static tg_vec3 direct_radiance_at(void *user, int tri, tg_vec3 pos, tg_vec3 nrm)
{
    const tg_frame *f = (const tg_frame *)user;
    const tg_scene *s = f->scene;
    const tgi_material *m = &s->materials[s->tri_material[tri]];
    tg_vec3 e = tg_v3(0, 0, 0);
    int l;
    if (f->effects & TG_EFFECT_DIRECT) {
        for (l = 0; l < s->light_count; l++) {
            tg_vec3 el = tgi_direct_irradiance(&s->lights[l], pos, nrm);
            if (f->shadow_ptrs && f->shadow_ptrs[l])
                el = tgi_v3_scale(el, tgi_shadow_visibility(f->shadow_ptrs[l], pos, nrm));
            e = tgi_v3_add(e, el);
        }
    }
    return tgi_v3_add(tgi_v3_mul(m->diffuse, e), m->emissive);   /* compose's: albedo / pi (1 - F0) E */
}

void tgi_pass_reference_bvh(tg_frame *f)
{
    const tg_vec3 *pos = f->posed_pos ? f->posed_pos : f->scene->tri_pos;
    tgi_bvh_build(&f->bvh, pos, f->scene->tri_count, f->bvh_scratch, f->bvh_scratch_bytes);
}

void tgi_pass_reference(tg_frame *f, int y0, int y1)
{
    tgi_reference_params p;
    tgi_reference_defaults(&p);
    p.bvh = &f->bvh;
    p.tri_nrm = f->posed_nrm ? f->posed_nrm : f->scene->tri_nrm;
    p.samples = f->request.samples > 16 ? f->request.samples : 256;
    p.radius = f->request.radius;
    p.radiance = direct_radiance_at;
    p.user = f;
    tgi_reference_rows(&p, &f->full, tgi_frame_source(f), &f->res, y0, y1);
}

/* The path tracer's BVH over the posed triangles and its table of emissive
 * triangles (both carved by layout.c's BVH group). */
void tgi_pass_pathtrace_setup(tg_frame *f)
{
    const tg_scene *s = f->scene;
    const tg_vec3 *pos = f->posed_pos ? f->posed_pos : s->tri_pos;
    tgi_bvh_build(&f->bvh, pos, s->tri_count, f->bvh_scratch, f->bvh_scratch_bytes);
    f->emitter_count = f->emitters ? tgi_pathtrace_emitters((tgi_pt_emitter *)f->emitters, pos, s->tri_material,
                                                            s->materials, s->tri_count) : 0;
}

void tgi_pass_pathtrace(tg_frame *f, int y0, int y1)
{
    const tg_scene *s = f->scene;
    tgi_pathtrace_params p;
    tgi_pathtrace_io io;
    tgi_pathtrace_defaults(&p);
    p.bvh = &f->bvh;
    p.tri_nrm = f->posed_nrm ? f->posed_nrm : s->tri_nrm;
    p.tri_material = s->tri_material;
    p.materials = s->materials;
    p.lights = s->lights;
    p.light_count = s->light_count;
    p.env = s->env.type != TG_ENV_NONE ? &s->env : NULL;
    p.emitters = f->emitter_count > 0 ? (const tgi_pt_emitter *)f->emitters : NULL;
    p.emitter_count = f->emitter_count;
    p.samples = f->request.samples;
    p.bounces = f->request.bounces;
    p.rr_start = TG_DEFAULT_PATHTRACE_ROULETTE;
    p.seed = (uint32_t)f->index + 1u;
    memset(&io, 0, sizeof io);
    io.gb = &f->gb;
    io.view = &f->view;
    io.color = &f->color;
    io.irradiance = &f->irradiance;
    tgi_pathtrace_rows(&p, &io, y0, y1);
}
#endif /* !TG_NO_REFERENCE */
