/* SPDX-License-Identifier: MIT */
/*
 * passes.c - the pass table: every pass of a frame, one row each, in the
 * order they run.  A row says what the pass computes (in the papers'
 * words, as --explain prints it), when the plan needs it, the buffer groups
 * it reads or writes (carved by layout.c), on which frames it runs, and its
 * function: tgi_pass_<name>(f, y0, y1) over rows, or tgi_pass_<name>(f) for a
 * whole-image step.  The plan, its explanation, the arena's size and
 * tg_frame_render all walk this table.  Adding a pass: README "Adding a
 * pass".
 */
#include "frame_internal.h"

#define AOV(a) (1u << (a))
#define B(g) TGI_BUF(TGI_BUF_##g)

/* ---- the pass functions (one file per family: camera.c, rasterize.c,
 * lighting.c, reprojection.c, hbil_passes.c, resolve.c, compare.c) ---- */
tgi_pass_step_fn tgi_pass_animate, tgi_pass_depth_range, tgi_pass_shadow_maps, tgi_pass_push_pull,
    tgi_pass_reference_bvh, tgi_pass_pathtrace_setup;
tgi_pass_rows_fn tgi_pass_gbuffer, tgi_pass_motion, tgi_pass_direct, tgi_pass_reproject, tgi_pass_push_pull_down,
    tgi_pass_push_pull_fill,
    tgi_pass_downsample, tgi_pass_hbil_interleaved, tgi_pass_hbil_full, tgi_pass_hbil_layers, tgi_pass_temporal,
    tgi_pass_filter_quarter, tgi_pass_near_horizon, tgi_pass_ssao, tgi_pass_vo, tgi_pass_hbao, tgi_pass_gtao, tgi_pass_ssilvb, tgi_pass_ssdo,
    tgi_pass_bentcone, tgi_pass_reference, tgi_pass_pathtrace, tgi_pass_resolve, tgi_pass_keep_history;
/* A left-out feature (tinygi.h "FEATURE SWITCHES") has no rows below, so
 * nothing refers to its passes and the linker leaves them out. */

/* ---- when the plan needs them ---- */
static int always(const tg_frame *f) { (void)f; return 1; }
static int wants_depth_view(const tg_frame *f) { return (f->request.aovs & AOV(TG_AOV_DEPTH)) != 0; }
#if !TG_NO_TEMPORAL /* the rows that carry history across frames (tinygi.h "FEATURE SWITCHES") */
static int wants_motion(const tg_frame *f) { return (f->needs & TG_NEED_MOTION) != 0; }
static int reprojects(const tg_frame *f) { return (f->effects & TG_EFFECT_REPROJECTION) != 0; }
static int accumulates(const tg_frame *f) { return (f->needs & TG_NEED_TEMPORAL) != 0; }
static int keeps_geometry(const tg_frame *f) { return reprojects(f) || accumulates(f); }
#endif
#if !TG_NO_COLOR /* the colour passes' rows (tinygi.h "FEATURE SWITCHES") */
static int casts_shadows(const tg_frame *f) { return (f->effects & TG_EFFECT_SHADOWS) != 0; }
static int gathers_near(const tg_frame *f) { return (f->effects & TG_EFFECT_NEAR) != 0; }
/* E_direct: the direct light, or (near field, no light) the 0 the first source is lit with */
static int lights_directly(const tg_frame *f) { return (f->effects & TG_EFFECT_DIRECT) || gathers_near(f); }
#if !TG_NO_TEMPORAL
static int lights_after_history(const tg_frame *f) { return lights_directly(f) && reprojects(f); }
#endif
#endif
static int composes(const tg_frame *f) { return (f->needs & TG_NEED_COMPOSE) != 0; }

static int technique_runs(const tg_frame *f, tg_technique t)
{
    return (f->needs & TG_NEED_GI_PASS) && f->request.technique == t;
}
static int runs_hbil(const tg_frame *f) { return technique_runs(f, TG_TECH_HBIL); }
/* over further depth layers HBIL's kernel is the visibility bitmask, on the
 * kernel's image (full, or half resolution with --gi-quarter: hbil_passes.c) */
static int reads_layers(const tg_frame *f) { return TGI_DEPTH_LAYERS && f->request.depth_layers >= 2; }
static int runs_hbil_interleaved(const tg_frame *f)
{
    return runs_hbil(f) && tgi_frame_interleaved(f) && !reads_layers(f);
}
static int runs_hbil_full(const tg_frame *f) { return runs_hbil(f) && !tgi_frame_interleaved(f) && !reads_layers(f); }
#if TGI_DEPTH_LAYERS
static int runs_hbil_layers(const tg_frame *f) { return runs_hbil(f) && reads_layers(f); }
#endif
#if !TG_NO_GI_QUARTER
static int runs_hbil_quarter(const tg_frame *f) { return runs_hbil(f) && tgi_frame_quarter(f); }
static int runs_near_horizon(const tg_frame *f) { return runs_hbil(f) && tgi_frame_near_horizon(f); }
#endif
#if !TG_NO_TECHNIQUES
static int runs_ssao(const tg_frame *f) { return technique_runs(f, TG_TECH_SSAO); }
static int runs_vo(const tg_frame *f) { return technique_runs(f, TG_TECH_VO); }
static int runs_hbao(const tg_frame *f) { return technique_runs(f, TG_TECH_HBAO); }
static int runs_gtao(const tg_frame *f) { return technique_runs(f, TG_TECH_GTAO); }
static int runs_ssilvb(const tg_frame *f) { return technique_runs(f, TG_TECH_SSILVB); }
static int runs_ssdo(const tg_frame *f) { return technique_runs(f, TG_TECH_SSDO); }
static int runs_bentcone(const tg_frame *f) { return technique_runs(f, TG_TECH_BENTCONE); }
#endif
#if !TG_NO_REFERENCE
static int runs_reference(const tg_frame *f) { return technique_runs(f, TG_TECH_REFERENCE); }
/* the path tracer: its own colour and irradiance, no GI pass, no compose */
static int path_traces(const tg_frame *f)
{
    return f->request.technique == TG_TECH_PATHTRACE && (f->needs & TG_NEED_COMPOSE);
}
#endif
/* compose, or an AOV of the GI results or the far field (everything after the kernel) */
static int resolves(const tg_frame *f)
{
    uint32_t results = AOV(TG_AOV_AO) | AOV(TG_AOV_BENT) | AOV(TG_AOV_CONE) | AOV(TG_AOV_NEAR) | AOV(TG_AOV_FAR);
    if (f->request.technique == TG_TECH_PATHTRACE) return 0;
    return composes(f) || (runs_hbil(f) && (f->request.aovs & results)) ||
           ((f->effects & TG_EFFECT_FAR) && (f->request.aovs & AOV(TG_AOV_FAR)));
}

#define ROWS(fn) TGI_ROWS_IMAGE, fn, NULL
#define KERNEL_ROWS(fn) TGI_ROWS_KERNEL, fn, NULL
#define SERIAL(fn) TGI_SERIAL, NULL, fn

const tgi_pass tgi_passes[] = {
    { "camera (the program's or its keys'; posed triangles when objects move)", always,
      B(POSE), 0, SERIAL(tgi_pass_animate) },
    { "rasterize G-buffer (the planes under buffers)", always,
      B(GBUFFER), 0, ROWS(tgi_pass_gbuffer) },
#if !TG_NO_TEMPORAL
    { "motion vectors", wants_motion,
      B(GBUFFER) | B(MOTION) | B(POSE), 0, ROWS(tgi_pass_motion) },
#endif
    { "depth range (for the 8-bit depth view)", wants_depth_view,
      B(GBUFFER), 0, SERIAL(tgi_pass_depth_range) },
#if !TG_NO_COLOR
    { "shadow maps (depth-only raster per shadow light)", casts_shadows,
      B(SHADOW_MAPS) | B(POSE), 0, SERIAL(tgi_pass_shadow_maps) },
#if !TG_NO_TEMPORAL
    { "reproject last frame's radiance (gather through the depth, z-test)", reprojects,
      B(GBUFFER) | B(POSE) | B(SOURCE) | B(HISTORY), TGI_ON_HISTORY, ROWS(tgi_pass_reproject) },
    { "push/pull hole filling: level 1, the 2x2 means of the valid pixels", reprojects,
      B(SOURCE) | B(REPROJECT), TGI_ON_HISTORY, ROWS(tgi_pass_push_pull_down) },
    { "push/pull hole filling: the coarser levels pushed, then pulled back to level 1", reprojects,
      B(SOURCE) | B(REPROJECT), TGI_ON_HISTORY, SERIAL(tgi_pass_push_pull) },
    { "push/pull hole filling: the holes from level 1 (bilinear)", reprojects,
      B(SOURCE) | B(REPROJECT), TGI_ON_HISTORY, ROWS(tgi_pass_push_pull_fill) },
#endif
    { "direct light (Lambert, shadows, spot falloff): E_direct, the near field's first source", lights_directly,
      B(GBUFFER) | B(SHADOW_MAPS) | B(DIRECT) | B(SOURCE), TGI_ON_FIRST_FRAME, ROWS(tgi_pass_direct) },
#endif
#if !TG_NO_REFERENCE
    { "reference: BVH over the posed triangles", runs_reference,
      B(BVH) | B(POSE), 0, SERIAL(tgi_pass_reference_bvh) },
    { "path tracing: BVH over the posed triangles, table of emissive triangles", path_traces,
      B(BVH) | B(POSE), 0, SERIAL(tgi_pass_pathtrace_setup) },
    { "path tracing: Lo = albedo/pi (1-F0) E + emissive, E from lights, emitters and the environment "
      "by next-event estimation over `bounces` diffuse bounces", path_traces,
      B(GBUFFER) | B(BVH) | B(SOURCE) | B(IRRADIANCE), 0, ROWS(tgi_pass_pathtrace) },
#endif
    /* the kernel and what follows it: iterated on a frame without history
     * (gi bounces), each iteration gathering the previous one's radiance */
#if !TG_NO_GI_QUARTER
    { "downsample to quarter resolution (point samples)", runs_hbil_quarter,
      B(HALF) | B(SOURCE), TGI_BOUNCE, KERNEL_ROWS(tgi_pass_downsample) },
#endif
    { "HBIL horizon kernel (AO, bent normal, near field), per 4x4 sub-image (strided, in place)", runs_hbil_interleaved,
      B(HALF) | B(SOURCE) | B(RESULTS), TGI_BOUNCE, KERNEL_ROWS(tgi_pass_hbil_interleaved) },
    { "HBIL horizon kernel, full resolution", runs_hbil_full,
      B(RESULTS) | B(SOURCE), TGI_BOUNCE, ROWS(tgi_pass_hbil_full) },
#if TGI_DEPTH_LAYERS
    { "HBIL over the depth layers: visibility bitmask (32 sectors, a sample solid to its back face), "
      "at the kernel's resolution, the 4x4 sub-images' angles", runs_hbil_layers,
      B(HALF) | B(RESULTS) | B(SOURCE), TGI_BOUNCE, KERNEL_ROWS(tgi_pass_hbil_layers) },
#endif
#if !TG_NO_TEMPORAL
    { "temporal accumulation at the kernel's resolution (history rejected by depth and normal)", accumulates,
      B(HALF) | B(SOURCE) | B(RESULTS) | B(TEMPORAL) | B(HISTORY), TGI_BOUNCE, KERNEL_ROWS(tgi_pass_temporal) },
#endif
#if !TG_NO_TECHNIQUES
    { "SSAO (Crytek point samples, normal-oriented hemisphere)", runs_ssao,
      B(RESULTS), TGI_BOUNCE, ROWS(tgi_pass_ssao) },
    { "volumetric obscurance (line samples in the ball)", runs_vo,
      B(RESULTS), TGI_BOUNCE, ROWS(tgi_pass_vo) },
    { "HBAO (horizon angles in screen directions)", runs_hbao,
      B(RESULTS), TGI_BOUNCE, ROWS(tgi_pass_hbao) },
    { "GTAO (cosine-weighted horizons in view-vector slices)", runs_gtao,
      B(RESULTS), TGI_BOUNCE, ROWS(tgi_pass_gtao) },
    { "visibility bitmask (GTAO slices, 32 sectors, constant thickness): AO, bent normal, near field",
      runs_ssilvb, B(RESULTS) | B(SOURCE), TGI_BOUNCE, ROWS(tgi_pass_ssilvb) },
    { "SSDO (directional occlusion, one indirect bounce, far field)", runs_ssdo,
      B(RESULTS) | B(SOURCE) | B(FAR), TGI_BOUNCE, ROWS(tgi_pass_ssdo) },
    { "bent normals and cones (far field in the cone)", runs_bentcone,
      B(RESULTS) | B(FAR), TGI_BOUNCE, ROWS(tgi_pass_bentcone) },
#endif
#if !TG_NO_REFERENCE
    { "reference: ray-traced AO, bent normal and near field", runs_reference,
      B(RESULTS) | B(SOURCE) | B(BVH), TGI_BOUNCE, ROWS(tgi_pass_reference) },
#endif
#if !TG_NO_GI_QUARTER
    { "depth/normal-aware 4x4 filter at quarter resolution", runs_hbil_quarter,
      B(HALF) | B(RESULTS) | B(FILTER), TGI_BOUNCE, KERNEL_ROWS(tgi_pass_filter_quarter) },
    { "near horizon at full resolution (AO under 2 slices of nearby pixels) for the upsample's cap", runs_near_horizon,
      B(GBUFFER) | B(HALF) | B(FILTER), TGI_BOUNCE, ROWS(tgi_pass_near_horizon) },
#endif
#if !TG_NO_COLOR && !TG_NO_TEMPORAL
    { "direct light (Lambert, shadows, spot falloff): E_direct", lights_after_history,
      B(GBUFFER) | B(SHADOW_MAPS) | B(DIRECT) | B(SOURCE), TGI_BOUNCE | TGI_ON_HISTORY, ROWS(tgi_pass_direct) },
#endif
    { "4x4 filter (or joint bilateral upsample) of the GI results, far field in the bent cone, "
      "compose Lo = albedo/pi (1-F0) (E_direct + E_far + E_near) + emissive", resolves,
      B(GBUFFER) | B(DIRECT) | B(SOURCE) | B(RESULTS) | B(HALF) | B(FILTER) | B(FAR) | B(COLOR) | B(IRRADIANCE),
      TGI_BOUNCE, ROWS(tgi_pass_resolve) },
    /* after the bounces */
#if !TG_NO_TEMPORAL
    { "keep the depth and normal as next frame's history", keeps_geometry,
      B(GBUFFER) | B(HISTORY), 0, ROWS(tgi_pass_keep_history) },
#endif
};

const int tgi_pass_count = (int)(sizeof tgi_passes / sizeof tgi_passes[0]);
