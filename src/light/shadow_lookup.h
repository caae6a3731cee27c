/* SPDX-License-Identifier: MIT */
/*
 * shadow_lookup.h - the shadow-map lookup (shadowmap.c), as static
 * functions: shadowmap.c defines tgi_shadow_visibility_err with it, and
 * direct.c includes it to have the lookup inline in its rows (a call per
 * pixel and light cost about 45 instructions: the vectors passed, the
 * prologue and epilogue).  Internal: include after shadowmap.h, with
 * TG_NO_SHADOW_MAPS 0.
 */
#ifndef TGI_SHADOW_LOOKUP_H
#define TGI_SHADOW_LOOKUP_H

#include "shadowmap.h"
#include "../raster/pack.h"   /* tgi_abs_fast */

#if !TG_NO_SHADOW_MAPS /* included unconditionally: tools/amalgamate.sh inlines a header once */

#define GRAZING_MIN_COS TG_R(0.001f)    /* |n . l| floor: keeps the receiver plane's slope finite */
/* Error bounds of rasterized depth (tgi_raster_* snap vertices to 1/16 of a
 * pixel or texel: a vertex moves up to sqrt(2)/32 of one sideways, and the
 * plane through the moved vertices, taken at any point of the triangle, moves
 * along its normal by at most that much at the point's own depth), with a
 * margin of ~3; and of the arithmetic, in units of the number type. */
#define RECEIVER_SNAP TG_R(0.125f)
#define RECEIVER_ULPS 8

/* LOOKUP_INLINE: a lookup's helpers inline in it (the float build called
 * cube_face, both builds map_error); a build for size keeps the calls. */
#if !TG_OUTLINE_HELPERS && defined(__GNUC__)
#define LOOKUP_INLINE inline __attribute__((always_inline))
#else
#define LOOKUP_INLINE inline
#endif
/* LOOKUP_STATIC: the helpers gcc may keep out of line; unused where a build
 * for size (TG_OUTLINE_HELPERS) has direct.c call tgi_shadow_visibility_err */
#if defined(__GNUC__)
#define LOOKUP_STATIC static __attribute__((unused))
#else
#define LOOKUP_STATIC static
#endif
/* LOOKUP_COPIED: the lookup's steps inline in each caller: direct.c has
 * the lookup in three copies of its rows (DIRECT_KIND_COPIES), where gcc
 * -O2 kept pcf, prepare_ortho and prepare_perspective calls (cornell float:
 * the rows 16.85M instructions with them out of line, 16.21M inline); a
 * build for size keeps them as LOOKUP_STATIC. */
#if !TG_OUTLINE_HELPERS && defined(__GNUC__)
#define LOOKUP_COPIED static inline __attribute__((always_inline))
#else
#define LOOKUP_COPIED LOOKUP_STATIC
#endif

static LOOKUP_INLINE int cube_face(tg_vec3 d)
{
    tg_real ax = tgi_abs_fast(d.x), ay = tgi_abs_fast(d.y), az = tgi_abs_fast(d.z);
    if (ax >= ay && ax >= az) return d.x >= 0 ? 0 : 1;
    if (ay >= az) return d.y >= 0 ? 2 : 3;
    return d.z >= 0 ? 4 : 5;
}


/* How far the face's own depths may lie in front of the true surface: along
 * its normal at distance `lz` (perspective) or anywhere (orthographic).  The
 * products by constants within [0, 1] never saturate (|a b| <= |a|:
 * tgi_mul_in_range); the sums in plain + (tg_add's value, never
 * saturating, float's own operation): texel in [0, 2^15] (texel_world > 0
 * times lz > 0, saturated at most), so texel / 8 <= 2^12; |lz| <= 2^15 (a
 * tg_real), |lz 8 EPS| <= 4 in Q16.16 (in float the sums cannot overflow):
 * the whole sum within [-4, 2^12 + 5], well inside the range. */
static LOOKUP_INLINE tg_real map_error(const tgi_shadow_map *sm, const tgi_shadow_face *fc, tg_real lz)
{
    tg_real texel = sm->orthographic ? fc->texel_world : tg_mul(fc->texel_world, lz);
    return tgi_mul_in_range(texel, RECEIVER_SNAP) + tgi_mul_in_range(lz, RECEIVER_ULPS * TG_EPS) + RECEIVER_ULPS * TG_EPS;
}

/* The constant depth bias of a lookup at distance lz: half a texel, plus one
 * quantisation step of a 16-bit face.  texel in [0, 2^15] (map_error), its
 * half within 2^14 + 1/2 and depth_step <= 1/2 (range / 2^16, or TG_EPS, or
 * 0): the sum never saturates, tg_add's value as plain +. */
LOOKUP_STATIC tg_real depth_bias(const tgi_shadow_face *fc, tg_real texel)
{
    return tg_ldexp(texel, -1) + fc->depth_step;
}

/* One lookup, prepared: the texel position and the receiver plane (the
 * plane through the receiver, moved toward the light by its error bound).
 *   orthographic  tap depth = base + min(dx[i] + dy[j], 0)
 *   perspective   tap ray r = (ndc / focal, 1) meets the plane at depth
 *                 num / den, den = n . r = den_c + dx[i] + dy[j], clamped
 *                 to <= den_c; lit when num >= (stored + bias) den (den < 0)
 * Both clamps keep a tap no deeper than the lookup itself: a tap past the
 * plane's horizon or round a concave corner would otherwise compare the
 * plane's continuation with whatever lies there. */
typedef struct lookup {
    const tgi_shadow_face *fc;
    tg_real ndc_x, ndc_y;
    tg_real slope_x, slope_y;   /* depth (ortho) or den (perspective) per NDC unit */
    tg_real base;               /* ortho: the receiver's depth at the lookup, biased */
    tg_real num, den_c, bias;   /* perspective */
} lookup;

/* a . b for b a face's basis vector (right, up, forward: unit vectors and
 * their cross products, components within [-2, 2]), for a the receiver's
 * unit normal (tgi_shadow_visibility_err's n, the same bound) or a row of an
 * orthographic face's world_to_clip (those times its scale, 1 / half >= 0.01,
 * within 101: components within +-2^23 in Q16.16).  Each product is below
 * 2^31 2^23 and their sum below 2^56, never past the 2^62 tgi_v3_dot tests
 * for, so the sum rounded once and saturated (tgi_wide_dot, tgi_wide_real:
 * core/real.h) is tgi_v3_dot's result without that test. */
#define dot_basis tgi_v3_dot_bounded

/* The terms of an orthographic lookup that depend on the receiver's normal
 * alone (direct.c keeps them while the G-buffer's normal code repeats). */
typedef struct ortho_normal {
    tg_real nl_z;               /* n . forward, at most -GRAZING_MIN_COS */
    tg_real slope_x, slope_y;   /* depth per NDC unit */
} ortho_normal;

/* 1 with t set, 0 when the surface faces away from the light. */
static LOOKUP_INLINE int ortho_normal_terms(const tgi_shadow_map *sm, tg_vec3 n, ortho_normal *t)
{
    const tgi_shadow_face *fc = &sm->face[0];
    tg_real nl_z = dot_basis(n, fc->forward), inv_nz;
    if (nl_z >= 0) return 0;
    t->nl_z = nl_z = tg_min(nl_z, tg_neg(GRAZING_MIN_COS));
    /* plane n.(dx, dy, dz) = 0 -> dz = -(nx dx + ny dy) / nz; world = ndc / scale */
    inv_nz = tg_div(tg_neg(sm->ortho_scale_inv), nl_z);
    t->slope_x = tg_mul(dot_basis(n, fc->right), inv_nz);
    t->slope_y = tg_mul(dot_basis(n, fc->up), inv_nz);
    return 1;
}

/* The lookup at p given its normal's terms. */
static LOOKUP_INLINE void prepare_ortho_at(const tgi_shadow_map *sm, tg_vec3 p, const ortho_normal *t, tg_real err,
                                           lookup *q)
{
    const tgi_shadow_face *fc = &sm->face[0];
    const tg_real *m = fc->world_to_clip.m;
    tg_real depth = tg_sub(dot_basis(p, fc->forward), sm->ortho_near);
    err = tg_add(err, map_error(sm, fc, tg_abs(depth)));
    q->fc = fc;
    q->num = q->den_c = q->bias = 0;
    /* the texel as the depth raster placed it: world_to_clip's rows as
     * raster_depth_rows applies them (src/raster/raster.c), not (p.r - cx)
     * s, whose rounding differs from the rows' (r s and -cx s) by up to
     * |p| 2^-17 in NDC: at 1000 units from the origin a few texels, the
     * lookups then read their neighbours' depths and a lit floor came out
     * shadowed in Q16.16 (test_shadow_plan ortho_map_far_from_the_origin) */
    q->ndc_x = tg_add(dot_basis(p, tg_v3(m[0], m[1], m[2])), m[3]);
    q->ndc_y = tg_add(dot_basis(p, tg_v3(m[4], m[5], m[6])), m[7]);
    /* the receiver moved by err along n is err / |n . f| nearer the light */
    q->base = tg_sub(tg_sub(depth, depth_bias(fc, fc->texel_world)), tg_div(err, tg_neg(t->nl_z)));
    q->slope_x = t->slope_x;
    q->slope_y = t->slope_y;
}

/* 1 when prepared, 0 when the surface faces away from the light. */
LOOKUP_COPIED int prepare_ortho(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real err, lookup *q)
{
    ortho_normal t;
    if (!ortho_normal_terms(sm, n, &t)) return 0;
    prepare_ortho_at(sm, p, &t, err, q);
    return 1;
}

/* 1 when prepared, 0 when the surface faces away, -1 behind the light's map
 * or in an absent face (lit). */
LOOKUP_COPIED int prepare_perspective(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real err, lookup *q)
{
    tg_vec3 d = tgi_v3_sub_wide(p, sm->origin), r, u, f;
    const tgi_shadow_face *fc = &sm->face[sm->faces == 6 ? cube_face(d) : 0];
    tg_real lx, ly, lz, inv_lz;
    if (fc->size == 0) return -1;
    q->fc = fc;
    q->base = 0;
    r = fc->right; u = fc->up; f = fc->forward;
    lz = dot_basis(d, f); lx = dot_basis(d, r); ly = dot_basis(d, u);
    if (lz <= TG_R(0.001f)) return -1;
    q->num = dot_basis(n, d);           /* n . (p - light): < 0 when the surface faces it; n unit (dot_basis) */
    if (q->num >= 0) return 0;
    inv_lz = tgi_div_pos(TG_ONE, lz);   /* lz > 0.001: 1 / lz < 1000, tg_div's quotient (core/real.h) */
    q->ndc_x = tg_mul(tg_sub(tg_mul(lx, inv_lz), fc->center_x), fc->focal);
    q->ndc_y = tg_mul(tg_sub(tg_mul(ly, inv_lz), fc->center_y), fc->focal);
    q->den_c = tg_mul(q->num, inv_lz);  /* n . r at the lookup */
    q->bias = depth_bias(fc, tg_mul(fc->texel_world, lz));
    /* the plane moved toward the light by err, at most half way to it */
    err = tg_add(err, map_error(sm, fc, lz));
    /* num < 0 and err >= 0 (position_error clamped to >= 0, map_error's
     * terms >= 0 here): num + err within [TG_REAL_MIN, TG_REAL_MAX), tg_add's
     * value as plain + */
    q->num = tg_min(q->num + err, tg_ldexp(q->num, -1));
#if TGI_Q16_WIDE
    /* n . r and n . u (components within [-2, 2]) lie within 12, so the
     * dots need no saturation test (tgi_wide_dot's integer is dot_basis's)
     * and, for tan_half <= 128, their products lie within 1536: tg_mul's
     * values as tgi_mul_in_range's */
    if (fc->tan_half <= TG_R(128.0f)) {
        q->slope_x = tgi_mul_in_range((tg_real)tgi_wide_dot(n.x, n.y, n.z, r.x, r.y, r.z), fc->tan_half);
        q->slope_y = tgi_mul_in_range((tg_real)tgi_wide_dot(n.x, n.y, n.z, u.x, u.y, u.z), fc->tan_half);
        return 1;
    }
#endif
    q->slope_x = tg_mul(dot_basis(n, r), fc->tan_half);
    q->slope_y = tg_mul(dot_basis(n, u), fc->tan_half);
    return 1;
}

/* A 16-bit code read back as a depth plus c: c + range q / 65536 (c = the
 * face's depth_lo, or that plus a bias). */
static inline tg_real depth16_plus(const tgi_shadow_face *fc, uint16_t q, tg_real c)
{
#if TG_FIXED
    return tg_add(c, (tg_real)(((int64_t)fc->depth_range * q + 32768) >> 16));
#else
    return c + (float)q * fc->depth_step;
#endif
}

static inline tg_real depth16(const tgi_shadow_face *fc, uint16_t q) { return depth16_plus(fc, q, fc->depth_lo); }

#define PCF_MAX_TAPS 4

/* The stored depths under a taps x taps footprint whose top-left texel is
 * (i0, j0), row by row; TG_REAL_MAX outside the face (lit). */
LOOKUP_STATIC void fetch_taps(const tgi_shadow_map *sm, const tgi_shadow_face *fc, int i0, int j0, int taps,
                       tg_real st[PCF_MAX_TAPS][PCF_MAX_TAPS])
{
    int i, j, n = fc->size;
    int inside = i0 >= 0 && j0 >= 0 && i0 + taps <= n && j0 + taps <= n;
    for (j = 0; j < taps; j++) {
        int ty = j0 + j;
        size_t row = fc->offset + (size_t)(ty < 0 ? 0 : ty) * (size_t)n;
        if (sm->depth_bits == TG_SHADOW_DEPTH16) {
            const uint16_t *d = (const uint16_t *)sm->depth + row;
            if (inside) {
                for (i = 0; i < taps; i++) st[j][i] = depth16(fc, d[i0 + i]);
                continue;
            }
            for (i = 0; i < taps; i++) {
                int tx = i0 + i;
                st[j][i] = (tx < 0 || ty < 0 || tx >= n || ty >= n) ? TG_REAL_MAX : depth16(fc, d[tx]);
            }
        } else {
            const tg_real *d = (const tg_real *)sm->depth + row;
            for (i = 0; i < taps; i++) {
                int tx = i0 + i;
                st[j][i] = (!inside && (tx < 0 || ty < 0 || tx >= n || ty >= n)) ? TG_REAL_MAX : d[tx];
            }
        }
    }
}

/* A perspective tap's test num >= tg_mul(a, den) (num < 0, as
 * prepare_perspective leaves it).  In Q16.16 without the product's rounding
 * and saturation: for P = a den and an integer num, num >= tgi_shr_round(P,
 * 16) = floor((P + 2^15) / 2^16) exactly when P + 2^15 < (num + 1) 2^16,
 * that is P <= num 2^16 + 2^15 - 1 (perspective_bound), and saturation
 * changes neither side (a product above the range fails both, one below it
 * passes both).  tests/test_shadow.c checks the two forms agree
 * (tgi_shadow_lit_perspective_q16). */
static inline int lit_perspective_mul(tg_real num, tg_real a, tg_real den) { return num >= tg_mul(a, den); }
#if TG_FIXED
static inline int64_t perspective_bound(tg_real num) { return (int64_t)num * 65536 + 32767; }
static inline int lit_perspective_wide(tg_real num, tg_real a, tg_real den) { return (int64_t)a * den <= perspective_bound(num); }
#endif
static inline int lit_perspective(tg_real num, tg_real a, tg_real den)
{
#if TGI_Q16_WIDE
    return lit_perspective_wide(num, a, den);
#else
    return lit_perspective_mul(num, a, den);
#endif
}

/* PCF_COPIES: pcf16_inside and pcf_taps inline with a constant footprint
 * (2 or 4 taps a side) and kind of face, a copy for each: their loops then
 * have constant bounds, which the compiler writes out (cornell's bilinear
 * point light: a lookup's loops and their counters gone); a build for size
 * (TG_OUTLINE_HELPERS) keeps the one copy. */
#define PCF_COPIES (!TG_OUTLINE_HELPERS)
#if PCF_COPIES && defined(__GNUC__)
#define PCF_INLINE inline __attribute__((always_inline))
#else
#define PCF_INLINE inline
#endif

/* The common case of pcf(): a 16-bit face, the footprint inside it; the
 * codes compared as read back (the bias folded into the read-back).  In
 * Q16.16 without the saturating adds, giving the same tests: the sums in 64
 * bits, clamped only where tg_add's saturation could change the result (a
 * read-back depth above TG_REAL_MAX, a den below TG_REAL_MIN: a den above
 * TG_REAL_MAX gives den_c either way; an ortho depth below TG_REAL_MIN passes
 * either way); row_lit, at most 4 weights in [0, 1], never saturates. */
static PCF_INLINE tg_real pcf16_inside(const tgi_shadow_face *fc, const lookup *q, int i0, int j0, const int taps,
                            const uint16_t *depth, const tg_real *wx, const tg_real *wy,
                            const tg_real *dx, const tg_real *dy, int perspective)
{
    const uint16_t *row = depth + fc->offset + (size_t)j0 * (size_t)fc->size + (size_t)i0;
    /* depth_lo in [0, 0.05] (0 for an orthographic face, else the near
     * plane, tgi_shadow_near's clamp), bias in [0, 2^14 + 1] (depth_bias;
     * 0 orthographic): tg_add's value as plain + */
    tg_real lo_bias = fc->depth_lo + q->bias;
    tgi_wide lit = 0;   /* sum of row_lit wy[j]: row_lit in [0, 3] (wx's sum), wy's sum 3: within 9 */
#if TGI_Q16_WIDE
    int64_t lim = perspective_bound(q->num);   /* lit_perspective's */
#endif
    int i, j;
#if TGI_Q16_WIDE
    /* A perspective lookup with den_c >= -2^30 raw, both slopes within
     * 2^10 and lo_bias + depth_range <= TG_REAL_MAX (nearly every one):
     * the loop below without its clamps, which cannot act there.  den_c =
     * num / lz (num < 0, 1 / lz > 0) is <= 0; each dx, dy is a slope
     * times (i - f) texel_ndc within 6 (pcf_taps), rounded: within 6 2^26
     * + 1 raw.  So den_c + dy[j] lies within [-(2^30 + 3 2^27 + 1), 6 2^26
     * + 1] (tg_add's value) and den_row + dx[i] >= -(2^30 + 3 2^28 + 2) >
     * TG_REAL_MIN: the clamp at TG_REAL_MIN never acts.  A code read back
     * adds (range q + 2^15) >> 16 <= max(range, 0) (q <= 65535) to
     * lo_bias >= 0, so a <= TG_REAL_MAX: depth16_plus's tg_add value, the
     * clamp at TG_REAL_MAX never acts. */
    if (perspective && q->den_c >= -((tg_real)1 << 30)
        && (uint32_t)q->slope_x + ((uint32_t)1 << 26) <= ((uint32_t)1 << 27)
        && (uint32_t)q->slope_y + ((uint32_t)1 << 26) <= ((uint32_t)1 << 27)
        && (int64_t)lo_bias + fc->depth_range <= (int64_t)TG_REAL_MAX) {
        for (j = 0; j < taps; j++, row += fc->size) {
            tg_real row_lit = 0;
            const int64_t den_row = (int64_t)q->den_c + dy[j];
            for (i = 0; i < taps; i++) {
                int64_t den = den_row + dx[i];
                int64_t a = (int64_t)lo_bias + (((int64_t)fc->depth_range * row[i] + 32768) >> 16);
                den = den < q->den_c ? den : q->den_c;
                row_lit += a * den <= lim ? wx[i] : 0;
            }
            lit += tgi_wide_mul(row_lit, wy[j]);
        }
        return (tg_real)lit;
    }
#endif
    for (j = 0; j < taps; j++, row += fc->size) {
        tg_real row_lit = 0;
        if (perspective) {
            tg_real den_row = tg_add(q->den_c, dy[j]);
            for (i = 0; i < taps; i++) {
#if TGI_Q16_WIDE
                int64_t den = (int64_t)den_row + dx[i];
                int64_t a = (int64_t)lo_bias + (((int64_t)fc->depth_range * row[i] + 32768) >> 16);
                den = den < q->den_c ? den : q->den_c;
                den = den > TG_REAL_MIN ? den : TG_REAL_MIN;
                a = a < TG_REAL_MAX ? a : TG_REAL_MAX;   /* depth16_plus; never below lo_bias >= TG_REAL_MIN */
                row_lit += a * den <= lim ? wx[i] : 0;
#else
                tg_real den = tg_min(tg_add(den_row, dx[i]), q->den_c);
                if (lit_perspective(q->num, depth16_plus(fc, row[i], lo_bias), den)) row_lit = tg_add(row_lit, wx[i]);
#endif
            }
        } else {                            /* base + min(dx + dy, 0) <= stored, as two tests */
            tg_real base_row = tg_add(q->base, dy[j]);
            for (i = 0; i < taps; i++) {
#if TGI_Q16_WIDE
                int64_t stored = (int64_t)fc->depth_lo + (((int64_t)fc->depth_range * row[i] + 32768) >> 16);
                int64_t b = (int64_t)base_row + dx[i];
                stored = stored < TG_REAL_MAX ? stored : TG_REAL_MAX;
                b = b < TG_REAL_MAX ? b : TG_REAL_MAX;
                row_lit += b <= stored || q->base <= stored ? wx[i] : 0;
#else
                tg_real stored = depth16(fc, row[i]);
                if (tg_add(base_row, dx[i]) <= stored || q->base <= stored) row_lit = tg_add(row_lit, wx[i]);
#endif
            }
        }
        lit += tgi_wide_mul(row_lit, wy[j]);   /* tg_mul's and tg_add's: never saturating */
    }
    return (tg_real)lit;
}

/* PCF_FLOAT_FLOOR: float, not compiling for size: pcf_taps's texel range
 * tested on su and sv themselves, then a floor without tg_to_int's
 * saturation (callgrind 160x120, 2 frames, direct rows: cornell 15.89M ->
 * 15.63M, columns 11.18M -> 10.80M, spheres 10.44M -> 10.11M) */
#define PCF_FLOAT_FLOOR (!TG_FIXED && !TG_OUTLINE_HELPERS)
#if PCF_FLOAT_FLOOR
/* tg_to_int's floor for a float within (-2^31, 2^31) */
static inline int32_t floor_in_range(float a)
{
    const int32_t i = (int32_t)a;
    return (float)i > a ? i - 1 : i;
}
#endif

/* PCF over the prepared lookup: continuous texel position (rows top to
 * bottom), then the footprint:
 *   tent      taps i0-1 .. i0+2, weights 1-f, 1, 1, f (sum 3 per axis)
 *   bilinear  taps i0 .. i0+1, weights 1-f, f (sum 1 per axis)
 * Taps outside the map, and texels where nothing was drawn, are lit. */
static PCF_INLINE tg_real pcf_taps(const tgi_shadow_map *sm, const lookup *q, const int taps)
{
    const tgi_shadow_face *fc = q->fc;
    tg_real fx, fy, norm, lit = 0, wx[PCF_MAX_TAPS], wy[PCF_MAX_TAPS], dx[PCF_MAX_TAPS], dy[PCF_MAX_TAPS];
    tg_real st[PCF_MAX_TAPS][PCF_MAX_TAPS];
    int i0, j0, i, j;
#if TGI_Q16_WIDE
    /* su = (ndc_x + 1) size / 2 - 1/2 (sv alike) in 64 bits without the
     * three saturations, and the range test on the 64-bit floor: |ndc + 1| <
     * 2^32 and size / 2 <= 2^12 (2^28 in Q16.16), so the product < 2^60.
     * Where the floor passes the test (within [-2, size + 1], size <= 2^13)
     * the sum ndc + 1 is within 1/4 of that (size / 2 >= 4), the product
     * and su within range: tg_add's, tg_mul's and tg_sub's values.  Where
     * it fails, so does the saturating form's: a sum past TG_REAL_MAX (the
     * sum never falls below TG_REAL_MIN: ndc + 1 > TG_REAL_MIN) saturates
     * the product (size / 2 >= 1) and su at TG_REAL_MAX - 1/2, a product
     * past either end su at that end's side (TG_REAL_MAX - 1/2 or
     * TG_REAL_MIN), and an su beyond the test's bounds within the range
     * is the same su: TG_ONE (lit) either way. */
    {
        const int64_t half = (int64_t)fc->size << 15;
        const int64_t wu = tgi_wide_mul((int64_t)q->ndc_x + TG_ONE, half) - 32768;
        const int64_t wv = tgi_wide_mul(TG_ONE - (int64_t)q->ndc_y, half) - 32768;
        const int64_t iu = wu >> 16, iv = wv >> 16;   /* tg_to_int's floor */
        if ((uint64_t)(iu + 2) > (uint64_t)fc->size + 3 || (uint64_t)(iv + 2) > (uint64_t)fc->size + 3)
            return TG_ONE;   /* outside [-2, size + 1], in one unsigned compare */
        i0 = (int)iu; j0 = (int)iv;
        /* su - tg_from_int(i0) (sv's alike), su = wu: i0 within [-2, size
         * + 1] (size <= 2^13), so tg_from_int's i0 2^16 is exact and su
         * minus the floor's 2^16 multiple is su's low 16 bits */
        fx = (tg_real)(wu & 0xFFFF); fy = (tg_real)(wv & 0xFFFF);
    }
#else
    tg_real su, sv;
    {
        tg_real half_size = tg_ldexp(tg_from_int(fc->size), -1);
        su = tg_sub(tg_mul(tg_add(q->ndc_x, TG_ONE), half_size), TG_R(0.5f));
        sv = tg_sub(tg_mul(tg_sub(TG_ONE, q->ndc_y), half_size), TG_R(0.5f));
    }
#if PCF_FLOAT_FLOOR
    /* tg_to_int's floor outside [-2, size + 1] (lit) exactly where su lies
     * outside [-2, size + 2) (size + 2 <= 2^13 + 2, exact), its saturated
     * ends included; a NaN fails neither test, as tg_to_int's 0 passes the
     * range; within it the floor needs no saturation (sv alike) */
    if (su < -2.0f || su >= (float)(fc->size + 2) || sv < -2.0f || sv >= (float)(fc->size + 2)) return TG_ONE;
    i0 = su == su ? floor_in_range(su) : 0;
    j0 = sv == sv ? floor_in_range(sv) : 0;
#else
    i0 = tg_to_int(su); j0 = tg_to_int(sv);
    if ((unsigned)i0 + 2u > (unsigned)fc->size + 3u || (unsigned)j0 + 2u > (unsigned)fc->size + 3u)
        return TG_ONE;   /* outside [-2, size + 1], in one unsigned compare */
#endif
    fx = su - tg_from_int(i0);
    fy = sv - tg_from_int(j0);
#endif
    /* the floor's fractions, in [0, 1): these and the weights below never saturate */
    if (taps == 4) {
        wx[0] = TG_ONE - fx; wx[1] = wx[2] = TG_ONE; wx[3] = fx;
        wy[0] = TG_ONE - fy; wy[1] = wy[2] = TG_ONE; wy[3] = fy;
        i0 -= 1; j0 -= 1; fx += TG_ONE; fy += TG_ONE;
        norm = TG_R(1.0f / 9.0f);
    } else {
        wx[0] = TG_ONE - fx; wx[1] = fx;
        wy[0] = TG_ONE - fy; wy[1] = fy;
        norm = TG_ONE;
    }
#if TGI_Q16_WIDE
    /* fx, fy in [0, 2) (the floor's fraction, plus 1 for the tent) and
     * texel_ndc = 2 / size in (0, 2]: i - fx within [-2, 3] and its
     * product within [-6, 6], so tgi_wide (core/real.h) gives tg_sub's
     * and tg_mul's integers without their saturation tests; and where both
     * slopes lie within [-2^12, 2^12] (one unsigned compare each) their
     * products by those within [-6 2^12, 6 2^12], within 1/2 after
     * rounding: tg_mul's values without its saturation */
    if ((uint32_t)q->slope_x + ((uint32_t)1 << 28) <= ((uint32_t)1 << 29)
        && (uint32_t)q->slope_y + ((uint32_t)1 << 28) <= ((uint32_t)1 << 29)) {
        for (i = 0; i < taps; i++) {
            dx[i] = tgi_mul_in_range(q->slope_x, (tg_real)tgi_wide_mul((int64_t)i * TG_ONE - fx, fc->texel_ndc));
            dy[i] = tgi_mul_in_range(q->slope_y, tg_neg((tg_real)tgi_wide_mul((int64_t)i * TG_ONE - fy, fc->texel_ndc)));
        }
    } else
#endif
    for (i = 0; i < taps; i++) {
        /* tap i's texel centre (i0 + i) relative to the lookup, in NDC (y up) */
#if TGI_Q16_WIDE
        dx[i] = tg_mul(q->slope_x, (tg_real)tgi_wide_mul((int64_t)i * TG_ONE - fx, fc->texel_ndc));
        dy[i] = tg_mul(q->slope_y, tg_neg((tg_real)tgi_wide_mul((int64_t)i * TG_ONE - fy, fc->texel_ndc)));
#else
        dx[i] = tg_mul(q->slope_x, tg_mul(tg_sub(tg_from_int(i), fx), fc->texel_ndc));
        dy[i] = tg_mul(q->slope_y, tg_neg(tg_mul(tg_sub(tg_from_int(i), fy), fc->texel_ndc)));
#endif
    }
    /* the footprint inside the face, 0 <= i0, j0 <= size - taps, in one
     * unsigned compare each: size >= TG_MIN_SHADOW_MAP >= taps (a face
     * looked up is never empty: prepare_perspective's test, and a
     * directional map with a face has it, need_layout) */
    if (sm->depth_bits == TG_SHADOW_DEPTH16 && (unsigned)i0 <= (unsigned)(fc->size - taps)
        && (unsigned)j0 <= (unsigned)(fc->size - taps)) {
#if PCF_COPIES
        lit = sm->orthographic ? pcf16_inside(fc, q, i0, j0, taps, (const uint16_t *)sm->depth, wx, wy, dx, dy, 0)
                               : pcf16_inside(fc, q, i0, j0, taps, (const uint16_t *)sm->depth, wx, wy, dx, dy, 1);
#else
        lit = pcf16_inside(fc, q, i0, j0, taps, (const uint16_t *)sm->depth, wx, wy, dx, dy, !sm->orthographic);
#endif
        /* bilinear: norm = 1 and lit already within [0, 1], so tg_mul by 1
         * (exact) and tg_saturate give lit itself.  Each row_lit is a sum
         * of some of wx[0] + wx[1] and lit of row_lit wy[j], every term >= 0
         * and rounded monotonically, so lit <= wy[0] + wy[1] (row_lit <= 1
         * alike): in Q16.16 (1 - f) + f = 1 exactly; in float fl(1 - f) is
         * within 2^-25 of 1 - f (f in [0, 1)), so their sum rounds to at
         * most 1 */
        if (taps == 2) return lit;
        return tg_saturate((tg_real)tgi_wide_mul(lit, norm));   /* within 9 times norm <= 1: tg_mul's */
    }
    fetch_taps(sm, fc, i0, j0, taps, st);
    for (j = 0; j < taps; j++) {
        tg_real row_lit = 0;
        if (!sm->orthographic) {
            tg_real den_row = tg_add(q->den_c, dy[j]);
            for (i = 0; i < taps; i++) {
                tg_real den = tg_min(tg_add(den_row, dx[i]), q->den_c);
                if (lit_perspective(q->num, tg_add(st[j][i], q->bias), den)) row_lit = tg_add(row_lit, wx[i]);
            }
        } else {                            /* base + min(dx + dy, 0) <= stored, as two tests */
            tg_real base_row = tg_add(q->base, dy[j]);
            for (i = 0; i < taps; i++)
                if (tg_add(base_row, dx[i]) <= st[j][i] || q->base <= st[j][i]) row_lit = tg_add(row_lit, wx[i]);
        }
        lit = tg_add(lit, tg_mul(row_lit, wy[j]));
    }
    return tg_saturate(tg_mul(lit, norm));
}

/* pcf_taps with the map's footprint (PCF_COPIES: a copy for each). */
LOOKUP_COPIED tg_real pcf(const tgi_shadow_map *sm, const lookup *q)
{
#if PCF_COPIES
    return sm->filter == TG_SHADOW_PCF_BILINEAR ? pcf_taps(sm, q, 2) : pcf_taps(sm, q, 4);
#else
    return pcf_taps(sm, q, sm->filter == TG_SHADOW_PCF_BILINEAR ? 2 : 4);
#endif
}

/* Fraction of the light reaching p: tgi_shadow_visibility_err's body (a
 * build for size writes it there, shadowmap.c: -Os made it 20 bytes longer
 * inlined on Cortex-M4). */
static LOOKUP_INLINE tg_real shadow_lookup(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real position_error)
{
    lookup q;
    int state;
    position_error = tg_max(position_error, 0);
    if (sm->ray) return sm->ray(sm->tracer, sm->light, p, n, position_error);
    if (sm->faces == 0) return TG_ONE;  /* no map (an impossible size) */
    state = sm->orthographic ? prepare_ortho(sm, p, n, position_error, &q)
                             : prepare_perspective(sm, p, n, position_error, &q);
    if (state <= 0) return state < 0 ? TG_ONE : 0;
    return pcf(sm, &q);
}

/* shadow_lookup of a plain orthographic map (no ray, a face) for a surface
 * facing the light, its normal's terms t given. */
static LOOKUP_INLINE tg_real shadow_lookup_ortho(const tgi_shadow_map *sm, tg_vec3 p, const ortho_normal *t,
                                                 tg_real position_error)
{
    lookup q;
    prepare_ortho_at(sm, p, t, tg_max(position_error, 0), &q);
    return pcf(sm, &q);
}

#endif /* !TG_NO_SHADOW_MAPS */

#endif
