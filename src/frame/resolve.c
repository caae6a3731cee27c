/* SPDX-License-Identifier: MIT */
/*
 * resolve.c - the GI results after the kernel: temporal accumulation at the
 * kernel's resolution, the filter at quarter resolution, and the resolve
 * pass, which per pixel filters the results over their 4x4 neighbourhood
 * (HBIL sec. 3.3-3.4; or upsamples the filtered quarter-res ones), lights
 * the far field in the bent cone (HBIL sec. 2.2.4) and composes Lo (HBIL
 * sec. 2.3), writing the filtered results only where an AOV asks for them.
 * The filter reads the kernel's results in their plane and writes nowhere
 * else, so no full-size copy of them is kept and any split of the rows gives
 * the same frame.
 */
#include "frame_internal.h"
#include "../gi/denoise.h"
#include "../gi/temporal.h"
#include "../gi/resample.h"
#include "../light/sh.h"
#include "../light/compose.h"

#if !TG_NO_TEMPORAL /* left out with TG_NO_TEMPORAL=1 (tinygi.h "FEATURE SWITCHES") */
/* Exponential accumulation over frames, in place, at the kernel's resolution. */
void tgi_pass_temporal(tg_frame *f, int y0, int y1)
{
    tgi_temporal_params p;
    const tgi_gresult *res;
    const tgi_gview *k = tgi_frame_kernel(f, &res, NULL);
    tgi_temporal_defaults(&p);
    tgi_temporal_rows(&p, k, res, tgi_frame_quarter(f) ? &f->half_prev : &f->res_prev, &f->prev_geometry,
                      &f->prev_view, f->frames_rendered == 0, y0, y1);
}
#endif

#if !TG_NO_GI_QUARTER /* left out with TG_NO_GI_QUARTER=1 (tinygi.h "FEATURE SWITCHES") */
/* HBIL sec. 3.3-3.4 at quarter resolution: the filtered results the
 * upsample reads. */
void tgi_pass_filter_quarter(tg_frame *f, int y0, int y1)
{
    tgi_denoise_params p;
    tgi_denoise_defaults(&p);
    tgi_denoise_rows(&p, &f->half_view, &f->half_res, &f->half_filtered, y0, y1);
}

/* Each full-res pixel's near horizon, which the upsample (the resolve) caps
 * its AO with over the pixel's 3x3 neighbourhood. */
void tgi_pass_near_horizon(tg_frame *f, int y0, int y1)
{
    tgi_near_horizon_rows(&f->full, &f->half_view, &f->half_filtered, f->request.radius, &f->near_horizon, y0, y1);
}
#endif

/* What a row of the resolve needs, fixed per call. */
typedef struct resolve_ctx {
    tgi_denoise_params filter;
    union {                       /* one or the other, sharing the stack: */
        tgi_denoise_walk walk;    /* the filter's decoded window along the row */
#if !TG_NO_GI_QUARTER
        struct {
            tgi_upsample_plan plan;   /* or the upsample's plan, fixed per frame, */
            tgi_upsample_walk walk;   /* and the half-res pixels it decoded */
        } up;
#endif
    } r;
    int gi, hbil, quarter, far_mode, far_inline;
    const tgi_rgb *lo;            /* where Lo goes: this frame's colour, or the next bounce's source */
    const tgi_rgb *far_own;       /* E_far's plane, written here (its AOV) */
} resolve_ctx;

static void resolve_ctx_init(resolve_ctx *c, const tg_frame *f)
{
    int technique_far = f->request.technique == TG_TECH_SSDO || f->request.technique == TG_TECH_BENTCONE;
    tgi_denoise_defaults(&c->filter);
    c->gi = (f->needs & TG_NEED_GI_PASS) != 0;
    c->hbil = c->gi && f->request.technique == TG_TECH_HBIL;
    c->quarter = tgi_frame_quarter(f);
#if !TG_NO_GI_QUARTER
    if (c->hbil && c->quarter) {
        tgi_upsample_start(&c->r.up.plan, &f->full, &f->half_view, &f->half_filtered, f->request.radius,
                           tgi_frame_near_horizon(f) ? &f->near_horizon : NULL);
        tgi_upsample_walk_start(&c->r.up.walk);
    } else
#endif
        tgi_denoise_walk_start(&c->r.walk);
    c->far_mode = f->request.far_mode ? TG_FAR_CUBE_F0 : TG_FAR_CONE_SH;
    c->far_inline = (f->effects & TG_EFFECT_FAR) && !technique_far;
    c->far_own = c->far_inline && tgi_rgb_present(&f->far) ? &f->far : NULL;
    c->lo = f->bounce + 1 < f->bounces ? &f->bounce_source : &f->color;
}

/* The GI results of full-resolution pixel (x, y) as compose and the AOVs use
 * them: HBIL's filtered (or upsampled), another technique's as they are. */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
#define RESOLVE_INLINE inline __attribute__((always_inline))   /* a copy per mode (below) */
#elif TG_OUTLINE_HELPERS
#define RESOLVE_INLINE   /* a build for size: the compiler's choice, one copy */
#else
#define RESOLVE_INLINE inline
#endif

/* mode, a constant in each copy of the pixel's code (tgi_pass_resolve):
 * RESOLVE_FILTER where c->gi and c->hbil are set and c->quarter is not (the
 * full-res filter runs), RESOLVE_UPSAMPLE where all three are (the
 * upsample runs); else 0, the flags read. */
#define RESOLVE_FILTER 1
#define RESOLVE_UPSAMPLE 2
static RESOLVE_INLINE tgi_gr_value results_at(resolve_ctx *c, const tg_frame *f, int x, int y, size_t i,
                                              const int mode)
{
    if (mode == RESOLVE_FILTER) return tgi_denoise_pixel(&c->filter, &f->full, &f->res, &c->r.walk, x, y);
#if !TG_NO_GI_QUARTER
    if (mode == RESOLVE_UPSAMPLE) return tgi_upsample_at(&c->r.up.plan, &c->r.up.walk, x, y);
#endif
    if (!c->hbil) return tgi_gr_get_kept(&f->res, i);
#if !TG_NO_GI_QUARTER
    if (c->quarter) return tgi_upsample_at(&c->r.up.plan, &c->r.up.walk, x, y);
#endif
    return tgi_denoise_pixel(&c->filter, &f->full, &f->res, &c->r.walk, x, y);
}

#if !TG_NO_COLOR /* a build with TG_NO_COLOR (tinygi.h "FEATURE SWITCHES") composes nothing */
/* The G-buffer normal of surface pixel (x, y, index i): the filter's walk
 * holds it when the filter ran for the pixel (results_at), decoded there
 * by the same tgi_gv_normal (columns 320x240: one decode a pixel fewer). */
static RESOLVE_INLINE tg_vec3 normal_at(const resolve_ctx *c, const tg_frame *f, int x, int y, size_t i, const int mode)
{
#if !TG_OUTLINE_HELPERS
    if (mode == RESOLVE_FILTER || (mode == 0 && c->hbil && !c->quarter)) return tgi_denoise_centre_normal(&c->r.walk, x, y);
#else
    (void)c; (void)x; (void)y; (void)mode;
#endif
    return tgi_gv_normal(&f->full, i);
}

/* E = E_direct + E_far + E_near (HBIL sec. 2.3) of a surface pixel. */
static RESOLVE_INLINE tg_vec3 irradiance_at(const resolve_ctx *c, const tg_frame *f, int x, int y, size_t i,
                                            const tgi_gr_value *v, const int mode)
{
    tg_vec3 e = tg_v3(0, 0, 0), far;
    int has_bent = mode == RESOLVE_UPSAMPLE || (mode == 0 && c->hbil && c->quarter) ? tgi_gr_has_bent(&f->half_filtered)
                                                                                     : tgi_gr_has_bent(&f->res);
    if (tgi_rgb_present(&f->direct)) e = tgi_rgb_get(&f->direct, i);
    if (c->far_inline) {
        far = tgi_far_irradiance(f->sh, normal_at(c, f, x, y, i, mode), mode || c->gi, v->ao, has_bent, v->bent,
                                 c->far_mode);
        if (c->far_own) tgi_rgb_set(c->far_own, i, far);
        e = tgi_v3_add(e, far);
    } else if (tgi_rgb_present(&f->far)) {
        e = tgi_v3_add(e, tgi_rgb_get(&f->far, i));   /* SSDO's or bent cones' own */
    }
    if ((mode || c->gi) && (f->effects & TG_EFFECT_NEAR)) e = tgi_v3_add(e, v->near);
    return e;
}
#endif

/* Pixel (x, y): its GI results, their AOV, E and Lo. */
static RESOLVE_INLINE void resolve_pixel(resolve_ctx *c, tg_frame *f, int compose, int x, int y, const int mode)
{
    size_t i = tgi_gv_index(&f->full, x, y);
    tgi_gr_value v;
#if !TG_NO_COLOR
    tg_vec3 e;
#else
    (void)compose;
#endif
    v.ao = TG_ONE; v.bent = v.near = tg_v3(0, 0, 0);
    if (mode || c->gi) v = results_at(c, f, x, y, i, mode);
    if (mode || c->hbil) tgi_gr_put_kept(&f->out, i, &v);   /* the filtered results an AOV asks for */
#if !TG_NO_COLOR /* without colour (the plan refuses the far field and composition) nothing else */
    if (tgi_gv_is_sky(&f->full, i)) {
        if (c->far_own) tgi_rgb_set(c->far_own, i, tg_v3(0, 0, 0));
        if (!compose) return;
        tgi_rgb_set(c->lo, i, tgi_compose_sky(&f->view, &f->scene->env, x, y));
        if (tgi_rgb_present(&f->irradiance)) tgi_rgb_set(&f->irradiance, i, tg_v3(0, 0, 0));
        return;
    }
    e = irradiance_at(c, f, x, y, i, &v, mode);
    if (!compose) return;
    if (tgi_rgb_present(&f->irradiance)) tgi_rgb_set(&f->irradiance, i, e);
    tgi_rgb_set(c->lo, i, tgi_gv_lit(&f->full, i, e));   /* HBIL eq. 14, 19 */
#endif
}

void tgi_pass_resolve(tg_frame *f, int y0, int y1)
{
    resolve_ctx c;
    int x, y, yy, end, compose = (f->needs & TG_NEED_COMPOSE) != 0;
    resolve_ctx_init(&c, f);
    /* the filter's order: band by band, column by column (denoise.h); else row by row */
#if !TG_OUTLINE_HELPERS   /* (a build for size keeps one copy) */
    /* HBIL's two ways: a copy of the pixel's code each, without the flags'
     * tests (cornell 160x120 2 frames float 526.76M -> 526.14M, Q16.16
     * 743.17M -> 742.44M; 320x240 --gi-quarter float 969.85M -> 964.35M,
     * Q16.16 1433.16M -> 1433.02M) */
    if (c.gi && c.hbil && !c.quarter) {
        for (y = y0; y < y1; y = end) {
            end = tgi_denoise_band(&c.r.walk, y, y1);
            for (x = 0; x < f->width; x++)
                for (yy = y; yy < end; yy++) resolve_pixel(&c, f, compose, x, yy, RESOLVE_FILTER);
        }
        return;
    }
    if (c.gi && c.hbil) {
        for (y = y0; y < y1; y++)
            for (x = 0; x < f->width; x++) resolve_pixel(&c, f, compose, x, y, RESOLVE_UPSAMPLE);
        return;
    }
#endif
    for (y = y0; y < y1; y = end) {
        end = c.hbil && !c.quarter ? tgi_denoise_band(&c.r.walk, y, y1) : y + 1;
        for (x = 0; x < f->width; x++)
            for (yy = y; yy < end; yy++) resolve_pixel(&c, f, compose, x, yy, 0);
    }
}
