/* SPDX-License-Identifier: MIT */
/*
 * direct.c - direct diffuse irradiance from directional, point and spot
 * lights: Lambert cosine, inverse-square falloff, smooth spot edge, shadow
 * maps.  See direct.h.
 */
#include "direct.h"
/* the shadow lookup inline in the rows (shadow_lookup.h); a build for size
 * calls the one copy in shadowmap.c */
#include "shadow_lookup.h"
#if !TG_OUTLINE_HELPERS && !TG_NO_SHADOW_MAPS
#define SHADOW_LOOKUP shadow_lookup
#else
#define SHADOW_LOOKUP tgi_shadow_visibility_err
#endif

#define LIGHT_CHUNK 8   /* lights prepared at once (a frame rarely has more) */
/* Q16.16: the pixel rays' right kx depends on the column alone, so the rows
 * share it, computed for DIRECT_COLUMNS columns at a time (on the stack, 12
 * bytes each): the same operations, the same bits, without a division and
 * three saturating products a pixel.  Float computes it per pixel (its
 * division and products cost less than the chunks' loop). */
#if TGI_Q16_WIDE   /* Q16.16 but a build for size (one loop) */
#define DIRECT_COLUMNS 32
#else
#define DIRECT_COLUMNS 0
#endif
/* a . b for a unit vector a (components within [-2, 2]: a G-buffer normal,
 * a light's normalised direction): each product below 2^17 2^31, their sum
 * below 2^50, never past 2^62 (tgi_v3_dot_bounded, core/vec.h). */
#define dot_unit tgi_v3_dot_bounded
/* v . v rounded and saturated as tgi_v3_dot gives it, for every v.  Q16.16:
 * each square is below 2^62 (|v_i| <= TG_REAL_MAX = 2^31 - 1), so the three
 * sum below 2^64 in uint64_t, exactly and without tgi_v3_dot's test for a
 * sum past 2^63 or its signs; where that sum is at most 2^62 it is
 * tgi_v3_dot's (which drops its third product only past 2^62), rounded
 * alike and then clamped at TG_REAL_MAX (it is never negative); past 2^62
 * both give TG_REAL_MAX (tgi_v3_dot's sum then also exceeds 2^62 >
 * TG_REAL_MAX 2^16). */
#if TGI_Q16_WIDE
static inline tg_real length2(tg_vec3 v)
{
    uint64_t s = (uint64_t)((int64_t)v.x * v.x) + (uint64_t)((int64_t)v.y * v.y) + (uint64_t)((int64_t)v.z * v.z);
    s = (s + 32768) >> 16;
    return s < (uint64_t)TG_REAL_MAX ? (tg_real)s : TG_REAL_MAX;
}
#else
static inline tg_real length2(tg_vec3 v) { return tgi_v3_dot(v, v); }
#endif
/* light_factor inline in the rows' loop (gcc kept it a call: its prologue,
 * epilogue and the vectors passed cost more than the body's registers);
 * a build for size keeps the one copy */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
#define LIGHT_FACTOR_INLINE inline __attribute__((always_inline))
#else
#define LIGHT_FACTOR_INLINE
#endif

/* 1/sqrt(x) for light_factor's x: at least tg_mul(TG_DIRECT_MIN_DISTANCE,
 * TG_DIRECT_MIN_DISTANCE) (1e-4 in float) and below TG_REAL_MAX (the
 * branch's test; a NaN fails it).  Float not compiling for size: tg_rsqrt's
 * seed and three Newton steps without its range tests (x > 0, x <=
 * TG_REAL_MAX, x below the smallest normal, all settled) and its scale (1
 * for a normal x: a product that changes no bit).  Q16.16 not compiling
 * for size: tgi_rsqrt_pos (core/real.h), tg_rsqrt's operations for x > 0
 * inline, x being at least 655^2 2^-16 rounded = 7 raw. */
#if !TG_FIXED && !TG_OUTLINE_HELPERS
#define rsqrt_positive tgi_rsqrt_normal   /* tinygi.h */
#elif TGI_Q16_WIDE
#define rsqrt_positive tgi_rsqrt_pos
#else
#define rsqrt_positive tg_rsqrt
#endif


/* What a light needs per pixel, prepared once per row range. */
typedef struct prepared_light {
    tgi_light_type type;
    tg_vec3 radiant;        /* intensity * colour */
    tg_vec3 to_light;       /* directional: unit vector towards the light */
    tg_vec3 pos, dir;
    tg_real cos_outer, cos_inner;
    const tgi_shadow_map *shadow;
    int ortho_plain;        /* shadow is an orthographic map with a face, no ray (shadow_lookup_ortho) */
#if TGI_Q16_WIDE
    uint64_t inv2_limit;    /* light_irradiance_wide's bound on inv^2 (raw) */
#endif
} prepared_light;

static void prepare(prepared_light *p, const tgi_light *l, const tgi_shadow_map *sm)
{
    p->type = l->type;
    p->radiant = tgi_v3_scale(l->color, l->intensity);
    p->pos = l->pos;
    p->dir = tgi_v3_normalize_or(l->dir, tg_v3(0, tg_neg(TG_ONE), 0));
    p->to_light = tgi_v3_neg(p->dir);
    p->cos_outer = tg_cos(l->angle);
    p->cos_inner = tg_cos(tg_mul(l->angle, TG_SPOT_INNER));
    p->shadow = sm;
#if !TG_NO_SHADOW_MAPS && !TG_OUTLINE_HELPERS   /* read by the directional copy alone (DIRECT_KIND_COPIES) */
    p->ortho_plain = sm && !sm->ray && sm->faces != 0 && sm->orthographic;
#else
    p->ortho_plain = 0;
#endif
#if TGI_Q16_WIDE
    {   /* 2 R + 1 for R the largest |radiant| (raw): 0 when above TG_REAL_MAX (never unsaturated) */
        int64_t r = tg_max(tg_max(tg_abs(p->radiant.x), tg_abs(p->radiant.y)), tg_abs(p->radiant.z));
        int64_t r2 = 2 * r + 1;
        p->inv2_limit = r2 <= TG_REAL_MAX ? ((uint64_t)1 << 62) / (uint64_t)r2 : 0;
    }
#endif
}

/* The kinds of light a chunk of lights holds: light_factor and the rows'
 * loop take one as a constant, so a copy for directional lights alone or
 * for point and spot lights alone has no test of each light's type (and the
 * directional copy none of the distance's terms). */
enum { LIGHTS_ANY, LIGHTS_DIRECTIONAL, LIGHTS_POSITIONAL };

/* Unshadowed irradiance scale as cosine * spot edge (<= 1) and the inverse
 * distance (1 for directional lights): E = radiant * scale * inv * inv.  The
 * product is formed largest first so Q16.16 keeps its relative precision. */
static LIGHT_FACTOR_INLINE tg_real light_factor(const prepared_light *p, tg_vec3 pos, tg_vec3 n, tg_real *inv_dist,
                                                const int kind)
{
    tg_vec3 v;
    tg_real len2, inv, cosine;
    *inv_dist = TG_ONE;
    if (kind == LIGHTS_DIRECTIONAL || (kind == LIGHTS_ANY && p->type == TG_LIGHT_DIRECTIONAL))
        return tg_max(dot_unit(n, p->to_light), 0); /* Lambert */
    v = tgi_v3_sub_wide(p->pos, pos);
    len2 = length2(v);
    if (len2 < TG_REAL_MAX) {   /* 1/d from d^2 (the common case) */
        inv = rsqrt_positive(tg_max(len2, tg_mul(TG_DIRECT_MIN_DISTANCE, TG_DIRECT_MIN_DISTANCE)));
    } else {                    /* d^2 saturated (fixed point, d > 181): the exact length */
        inv = tg_div(TG_ONE, tg_max(tgi_v3_length(v), TG_DIRECT_MIN_DISTANCE));
    }
    /* n . v inv and -dir . v inv, n and dir unit: below 2 in magnitude, so
     * no product saturates (tgi_mul_in_range), nor the cosine times the spot's
     * smoothstep in [0, 1].  |n|, |dir| <= sqrt(3) (components within
     * [-1, 1]); inv <= 1.04 / |v| (1 + 2^-14) where it is 1 / sqrt(len2),
     * len2 >= 7 2^-16 being v . v within 2^-17; where len2 is raised to
     * 0.01^2 (7 2^-16), inv <= 97 and |v| < 0.0107; where len2 saturated,
     * inv <= 1 / |v|; the dot's rounding adds at most 2^-17 97 */
    cosine = tgi_mul_in_range(dot_unit(n, v), inv); /* Lambert */
    if (cosine <= 0) return 0;
    *inv_dist = inv;
    if (p->type == TG_LIGHT_SPOT) {
        tg_real along = tgi_mul_in_range(tg_neg(dot_unit(p->dir, v)), inv);
        cosine = tgi_mul_in_range(cosine, tg_smoothstep(p->cos_outer, p->cos_inner, along)); /* smooth spot edge */
    }
    return cosine;
}

/* radiant * scale / d^2 (inverse square), largest factor first. */
static tg_vec3 light_irradiance(tg_vec3 radiant, tg_real scale, tg_real inv)
{
    tg_vec3 e = tgi_v3_scale(radiant, scale);
    if (inv != TG_ONE) e = tgi_v3_scale(tgi_v3_scale(e, inv), inv);
    return e;
}

#if TGI_Q16_WIDE && !TG_NO_COLOR   /* used by the direct-light pass alone */
/* light_irradiance(p->radiant, scale, inv) for scale in (0, 2) (light_factor
 * times a visibility in [0, 1]) and inv > 0, without the nine products'
 * saturation where none can saturate: for R the largest |radiant| (raw),
 * each |radiant scale| < 2 R 2^16, so the first products are at most 2 R
 * after rounding, within range when 2 R + 1 <= TG_REAL_MAX; where inv < 1
 * the next two are no larger; else they are at most (2 R + 1) inv / 2^16
 * + 1/2 and (2 R + 1) inv^2 / 2^32 + inv / 2^17 + 1/2 (raw inv below 2^31),
 * so with (2 R + 1) inv^2 <= 2^62 (inv2_limit) below 2^30 + 2^14 + 1: no
 * product leaves the range, tg_mul's values as tgi_mul_in_range's. */
static inline tg_vec3 light_irradiance_wide(const prepared_light *p, tg_real scale, tg_real inv)
{
    if ((uint64_t)((int64_t)inv * inv) > p->inv2_limit) return light_irradiance(p->radiant, scale, inv);
    {
        tg_vec3 e = tg_v3(tgi_mul_in_range(p->radiant.x, scale), tgi_mul_in_range(p->radiant.y, scale),
                          tgi_mul_in_range(p->radiant.z, scale));
        if (inv != TG_ONE)
            e = tg_v3(tgi_mul_in_range(tgi_mul_in_range(e.x, inv), inv), tgi_mul_in_range(tgi_mul_in_range(e.y, inv), inv),
                      tgi_mul_in_range(tgi_mul_in_range(e.z, inv), inv));
        return e;
    }
}
#define LIGHT_IRRADIANCE(p, scale, inv) light_irradiance_wide(p, scale, inv)
#else
#define LIGHT_IRRADIANCE(p, scale, inv) light_irradiance((p)->radiant, scale, inv)
#endif

tg_vec3 tgi_direct_irradiance(const tgi_light *l, tg_vec3 p, tg_vec3 n)
{
    prepared_light pl;
    tg_real inv, f;
    prepare(&pl, l, NULL);
    f = light_factor(&pl, p, n, &inv, LIGHTS_ANY);
    return f > 0 ? light_irradiance(pl.radiant, f, inv) : tg_v3(0, 0, 0);
}

#if !TG_NO_COLOR /* the direct-light pass is left out with TG_NO_COLOR=1 (tinygi.h "FEATURE SWITCHES") */
/* kx of column x's pixel centre: (x + 1/2 - half_w) / pixels_per_unit */
static inline tg_real column_kx(const tgi_view *view, tg_real half_w, int x)
{
#if TGI_Q16_WIDE
    /* x + 1/2 - half_w: for x < 16383 (every row within
     * TG_MAX_IMAGE_SIDE) neither tg_from_int nor tg_add
     * saturates, and half_w lies in [-2^14, 2^14] (tg_from_int's
     * range halved), so the difference lies within (-2^14,
     * 2^15 - 1/2]: tg_sub's value in one integer expression
     * (wider rows keep the saturating form) */
    return tg_div(x < 16383 ? (tg_real)(x * 65536 + 32768 - half_w)
                            : tg_sub(tg_add(tg_from_int(x), TG_R(0.5f)), half_w),
                  view->pixels_per_unit);
#else
    return tg_div(tg_sub(tg_add(tg_from_int(x), TG_R(0.5f)), half_w), view->pixels_per_unit);
#endif
}

/* The rows' loop in copies by the kinds of light in a chunk (LIGHTS_*, a
 * constant in each): columns' and spheres' one directional light and
 * cornell's one point light have no per-light test of the type left
 * (callgrind, 160x120, 2 frames, the rows float / Q16.16: cornell 16.50M
 * -> 16.21M / 24.24M -> 24.03M; columns 13.02M -> 12.21M / 18.72M ->
 * 18.41M; spheres 11.69M -> 10.96M / 16.84M -> 16.53M; Q16.16 with the
 * copy for point and spot lights only since tgi_v3_sub_wide and tgi_rsqrt_pos made
 * it gain: without them gcc's registers there cost cornell 0.19M).  A
 * build for size keeps the one copy. */
#if !TG_OUTLINE_HELPERS && defined(__GNUC__)
#define DIRECT_KIND_COPIES 1
#define ROWS_INLINE inline __attribute__((always_inline))
#else
#define DIRECT_KIND_COPIES 0
#define ROWS_INLINE inline
#endif

/* A directional light's terms that depend on the normal alone, kept while
 * the G-buffer's normal code repeats (the normal memo, raster/gview.h): the
 * Lambert cosine and, for a plain orthographic shadow map, its lookup's
 * normal terms (shadow_lookup.h), which cost three dot products, a
 * division and two products a pixel.  In the LIGHTS_DIRECTIONAL copy alone
 * (callgrind 160x120, 2 frames, the rows float / Q16.16: columns 12.21M ->
 * 11.18M / 18.41M -> 15.38M, spheres 10.96M -> 10.44M / 16.53M -> 14.58M;
 * cornell, with no directional light, 16.21M -> 15.89M / 24.03M -> 24.12M
 * through gcc's registers). */
typedef struct directional_memo {
    tg_real lambert;            /* max(n . to_light, 0) */
#if !TG_NO_SHADOW_MAPS
    int faces_light;            /* ortho set; else the map's visibility is 0 */
    ortho_normal ortho;
#endif
} directional_memo;

static inline void directional_terms(const prepared_light *pl, int count, tg_vec3 n, directional_memo *dm)
{
    int k;
    for (k = 0; k < count; k++) {
        dm[k].lambert = tg_max(dot_unit(n, pl[k].to_light), 0); /* Lambert, light_factor's */
#if !TG_NO_SHADOW_MAPS
        if (pl[k].ortho_plain && dm[k].lambert > 0)
            dm[k].faces_light = ortho_normal_terms(pl[k].shadow, n, &dm[k].ortho);
#endif
    }
}

/* What the rows of one chunk of lights and columns share. */
typedef struct rows_frame {
    const tgi_gview *g;
    const prepared_light *pl;
    int count;                  /* lights in pl */
    const tgi_rgb *e_out;
    tg_real half_w, half_h, position_error;
    int zero_first;             /* the first chunk into a fresh plane: E starts at 0, unread */
    struct directional_memo *dm;   /* LIGHTS_DIRECTIONAL: per light, its terms of the memo's normal */
#if DIRECT_COLUMNS
    const tg_vec3 *right_kx;    /* right kx of the chunk's columns x0.. */
    tg_real rk_max;             /* the largest |right kx| component of the chunk */
    int eye_small;              /* |eye| components below 2^30 */
#endif
} rows_frame;

/* E_direct of rows [y0, y1), columns [x0, x1), the lights of kind `kind`. */
static ROWS_INLINE void direct_rows_kind(const rows_frame *fr, tgi_normal_memo *nm, int y0, int y1, int x0, int x1,
                                         const int kind)
{
    const tgi_gview *g = fr->g;
    const tgi_view *view = g->camera;
    const prepared_light *pl = fr->pl;
    const int count = fr->count;
    int k, x, y;
#if DIRECT_COLUMNS
    const tg_vec3 *right_kx = fr->right_kx;
    uint64_t z_limit;       /* depths below it: p without saturation (the rows' loop) */
#define RIGHT_KX(x) right_kx[(x) - x0]
#else
#define RIGHT_KX(x) tgi_v3_scale(view->right, column_kx(view, fr->half_w, x))
#endif
#if TGI_Q16_WIDE
    int zero;   /* e is still the 0 it started as */
#endif
    for (y = y0; y < y1; y++) {
        /* pixel centre ray with view z = 1: forward + right kx + up ky (view.h) */
        tg_real ky = tg_div(tg_sub(fr->half_h, tg_add(tg_from_int(y), TG_R(0.5f))), view->pixels_per_unit);
        tg_vec3 row_dir = tgi_v3_add(view->forward, tgi_v3_scale(view->up, ky));
#if DIRECT_COLUMNS
        /* p = eye + (row_dir + right kx) z without saturation where
         * none can happen: with D = the largest |row_dir| plus the
         * largest |right kx| (raw) at most TG_REAL_MAX, no sum
         * row_dir + right kx leaves the range; for 0 <= z < z_limit
         * = 2^46 / D each product is below 2^46 raw, at most 2^30
         * once rounded, and with |eye| < 2^30 (eye_small) the sums
         * stay within the range: tg_add's and tg_mul's values.
         * z_limit 0 (no pixel) where the bounds fail. */
        {
            int64_t d = (int64_t)tg_max(tg_max(tg_abs(row_dir.x), tg_abs(row_dir.y)), tg_abs(row_dir.z)) + fr->rk_max;
            z_limit = fr->eye_small && d <= TG_REAL_MAX ? ((uint64_t)1 << 46) / (uint64_t)(d + 1) : 0;
        }
#endif
        for (x = x0; x < x1; x++) {
            size_t i = tgi_gv_index(g, x, y);
            tg_vec3 p, e;
            tg_real z;
            if (tgi_gv_is_sky(g, i)) {
                if (fr->zero_first) tgi_rgb_set(fr->e_out, i, tg_v3(0, 0, 0));
                continue;
            }
            tg_vec3 n;
            if (kind == LIGHTS_DIRECTIONAL) {
                if (!tgi_gv_normal_repeats(g, nm, i)) {
                    nm->n = tgi_gv_normal(g, i);
                    directional_terms(pl, count, nm->n, fr->dm);
                }
                n = nm->n;
            } else
                n = tgi_gv_normal_memo(g, nm, i);
            z = tgi_gv_depth(g, i);   /* decoded once: the calls below would have it read again */
#if DIRECT_COLUMNS
            if ((uint64_t)(uint32_t)z < z_limit) {
                const tg_vec3 rk = right_kx[x - x0];
                p = tg_v3(view->eye.x + tgi_mul_in_range(row_dir.x + rk.x, z),
                          view->eye.y + tgi_mul_in_range(row_dir.y + rk.y, z),
                          view->eye.z + tgi_mul_in_range(row_dir.z + rk.z, z));
            } else
#endif
            p = tgi_v3_add(view->eye, tgi_v3_scale(tgi_v3_add(row_dir, RIGHT_KX(x)), z));
            e = fr->zero_first ? tg_v3(0, 0, 0) : tgi_rgb_get(fr->e_out, i);   /* the stored 0 reads back as 0 */
#if TGI_Q16_WIDE
            zero = fr->zero_first;
#endif
            for (k = 0; k < count; k++) {
                tg_real inv, f;
                if (kind == LIGHTS_DIRECTIONAL) {   /* light_factor's, kept */
                    f = fr->dm[k].lambert;
                    inv = TG_ONE;
                } else
                    f = light_factor(&pl[k], p, n, &inv, kind);
                if (f <= 0) continue;
                /* f below 2 (light_factor), the visibility in [0, 1]: tgi_mul_in_range */
#if !TG_NO_SHADOW_MAPS && DIRECT_KIND_COPIES
                if (kind == LIGHTS_DIRECTIONAL && pl[k].ortho_plain)   /* shadow_lookup's steps, the normal's kept */
                    f = fr->dm[k].faces_light ? tgi_mul_in_range(f, shadow_lookup_ortho(pl[k].shadow, p, &fr->dm[k].ortho,
                                                                                       tg_mul(z, fr->position_error)))
                                              : 0;
                else
#endif
                if (pl[k].shadow) f = tgi_mul_in_range(f, SHADOW_LOOKUP(pl[k].shadow, p, n,
                                                                       tg_mul(z, fr->position_error)));
#if TGI_Q16_WIDE
                /* tg_add(0, v) is v: the first light's irradiance as it is */
                if (zero) { e = LIGHT_IRRADIANCE(&pl[k], f, inv); zero = 0; continue; }
#endif
                e = tgi_v3_add(e, LIGHT_IRRADIANCE(&pl[k], f, inv));
            }
            tgi_rgb_set(fr->e_out, i, e);
        }
    }
#undef RIGHT_KX
}

void tgi_direct_rows(const tgi_gview *g, const tgi_light *lights, int light_count,
                    const tgi_shadow_map *const *shadow_maps, const tgi_rgb *e_out, int y0, int y1)
{
    const tgi_view *view = g->camera;
    prepared_light pl[LIGHT_CHUNK];
    directional_memo dm[LIGHT_CHUNK];
    rows_frame fr;
#if DIRECT_COLUMNS
    tg_vec3 right_kx[DIRECT_COLUMNS];   /* right kx of the chunk's columns */
#endif
    int first, k, x, x0, x1, y, w = g->width;
    /* E starts at 0: the first chunk of lights writes every pixel (a plane
     * read lit would add its surfaces' emission to what it reads: then the
     * zeros are written first and read back, as the later chunks read) */
    int fresh = !e_out->lit;
    fr.g = g;
    fr.pl = pl;
    fr.dm = dm;
    fr.e_out = e_out;
    fr.half_w = tg_ldexp(tg_from_int(view->width), -1);
    fr.half_h = tg_ldexp(tg_from_int(view->height), -1);
    fr.position_error = tgi_shadow_gbuffer_error(view); /* per unit depth */
#if DIRECT_COLUMNS
    fr.right_kx = right_kx;
    fr.eye_small = tg_max(tg_max(tg_abs(view->eye.x), tg_abs(view->eye.y)), tg_abs(view->eye.z)) < ((tg_real)1 << 30);
#endif
    if (!fresh || light_count == 0)
        for (y = y0; y < y1; y++)
            for (x = 0; x < w; x++) tgi_rgb_set(e_out, tgi_gv_index(g, x, y), tg_v3(0, 0, 0));
    for (first = 0; first < light_count; first += LIGHT_CHUNK) {
        int count = light_count - first < LIGHT_CHUNK ? light_count - first : LIGHT_CHUNK;
#if DIRECT_KIND_COPIES
        int directional = 0;  /* of the chunk's lights */
#endif
        tgi_normal_memo nm;   /* the normal decoded last (raster/gview.h) */
        tgi_normal_memo_start(&nm);
        for (k = 0; k < count; k++) {
            prepare(&pl[k], &lights[first + k], shadow_maps ? shadow_maps[first + k] : NULL);
#if DIRECT_KIND_COPIES
            directional += pl[k].type == TG_LIGHT_DIRECTIONAL;
#endif
        }
        fr.count = count;
        fr.zero_first = fresh && first == 0;
        for (x0 = 0; x0 < w; x0 = x1) {
#if DIRECT_COLUMNS
            x1 = w - x0 > DIRECT_COLUMNS ? x0 + DIRECT_COLUMNS : w;
            fr.rk_max = 0;
            for (x = x0; x < x1; x++) {
                tg_vec3 rk = tgi_v3_scale(view->right, column_kx(view, fr.half_w, x));
                right_kx[x - x0] = rk;
                fr.rk_max = tg_max(fr.rk_max, tg_max(tg_max(tg_abs(rk.x), tg_abs(rk.y)), tg_abs(rk.z)));
            }
#else
            x1 = w;
#endif
#if DIRECT_KIND_COPIES
            if (directional == count) direct_rows_kind(&fr, &nm, y0, y1, x0, x1, LIGHTS_DIRECTIONAL);
            else if (directional == 0) direct_rows_kind(&fr, &nm, y0, y1, x0, x1, LIGHTS_POSITIONAL);
            else
#endif
            direct_rows_kind(&fr, &nm, y0, y1, x0, x1, LIGHTS_ANY);
        }
    }
}
#endif /* !TG_NO_COLOR */
