/* SPDX-License-Identifier: MIT */
/*
 * shadowmap.c - shadow maps for directional (orthographic, fitted to the
 * scene bounds), spot (perspective) and point lights (a seamless cube of six
 * wide faces), rasterized depth-only by tgi_raster_depth, and the lookup:
 * receiver-plane depth bias + 3x3 tent PCF.  See shadowmap.h.
 */
#include <string.h>
#include "shadowmap.h"
#include "../raster/raster.h"

#define SHADOW_BORDER 2                 /* texels kept for the PCF footprint at a face edge */
#define SPOT_MAX_ANGLE TG_R(1.3962634f) /* 80 degrees */
#define GRAZING_COS TG_R(0.1f)          /* slope of the receiver plane clamped at ~84 degrees */

/* A right-handed light basis: forward given, right = forward x helper, up = right x forward. */
static void light_basis(tg_vec3 forward, tg_vec3 *right, tg_vec3 *up)
{
    tg_vec3 helper = tg_abs(forward.y) < TG_R(0.99f) ? tg_v3(0, TG_ONE, 0) : tg_v3(TG_ONE, 0, 0);
    *right = tgi_v3_normalize_or(tgi_v3_cross(forward, helper), tg_v3(TG_ONE, 0, 0));
    *up = tgi_v3_cross(*right, forward);
}

static int light_faces(const tgi_light *l) { return l->type == TG_LIGHT_POINT ? 6 : 1; }

size_t tgi_shadow_map_bytes(const tgi_light *l, int size)
{
    size_t n = (size_t)(size > 0 ? size : 0);
    return (size_t)light_faces(l) * n * n * sizeof(tg_real);
}

static void set_row(tgi_mat4 *m, int row, tg_vec3 a, tg_real d)
{
    m->m[row * 4 + 0] = a.x; m->m[row * 4 + 1] = a.y; m->m[row * 4 + 2] = a.z; m->m[row * 4 + 3] = d;
}

/* Corner k (0..7) of the box [lo, hi]. */
static tg_vec3 box_corner(tg_vec3 lo, tg_vec3 hi, int k)
{
    return tg_v3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
}

static void setup_ortho(tgi_shadow_map *sm, tg_vec3 dir, tg_vec3 lo, tg_vec3 hi)
{
    tg_vec3 f = tgi_v3_normalize_or(dir, tg_v3(0, tg_neg(TG_ONE), 0)), r, u;
    tg_real minx = TG_REAL_MAX, maxx = TG_REAL_MIN, miny = TG_REAL_MAX, maxy = TG_REAL_MIN;
    tg_real minz = TG_REAL_MAX, half, scale, margin;
    int k;
    light_basis(f, &r, &u);
    for (k = 0; k < 8; k++) {
        tg_vec3 c = box_corner(lo, hi, k);
        tg_real x = tgi_v3_dot(c, r), y = tgi_v3_dot(c, u), z = tgi_v3_dot(c, f);
        minx = tg_min(minx, x); maxx = tg_max(maxx, x);
        miny = tg_min(miny, y); maxy = tg_max(maxy, y);
        minz = tg_min(minz, z);
    }
    half = tg_mul(tg_max(tg_sub(maxx, minx), tg_sub(maxy, miny)), TG_R(0.5f));
    half = tg_max(half, TG_R(0.01f));
    /* widen so the box plus a PCF border of texels fits */
    half = tg_div(tg_mul(half, tg_from_int(sm->size)), tg_from_int(sm->size > 2 * SHADOW_BORDER + 1 ? sm->size - 2 * SHADOW_BORDER : 1));
    margin = tg_max(tg_mul(half, TG_R(0.01f)), TG_R(0.01f));
    scale = tg_div(TG_ONE, half);
    sm->right[0] = r; sm->up[0] = u; sm->forward[0] = f;
    sm->ortho_center_x = tg_mul(tg_add(minx, maxx), TG_R(0.5f));
    sm->ortho_center_y = tg_mul(tg_add(miny, maxy), TG_R(0.5f));
    sm->ortho_near = tg_sub(minz, margin);
    sm->ortho_scale = scale;
    sm->ortho_scale_inv = half;
    sm->texel_world = tg_div(tg_mul(half, TG_R(2.0f)), tg_from_int(sm->size));
    sm->world_to_clip[0] = tgi_m4_identity();
    /* clip = ((p.r - cx) s, (p.u - cy) s, p.f - near, 1) */
    set_row(&sm->world_to_clip[0], 0, tgi_v3_scale(r, scale), tg_neg(tg_mul(sm->ortho_center_x, scale)));
    set_row(&sm->world_to_clip[0], 1, tgi_v3_scale(u, scale), tg_neg(tg_mul(sm->ortho_center_y, scale)));
    set_row(&sm->world_to_clip[0], 2, f, tg_neg(sm->ortho_near));
    set_row(&sm->world_to_clip[0], 3, tg_v3(0, 0, 0), TG_ONE);
}

/* Perspective face: clip = (x f, y f, a z + b, z) in the light's view space. */
static void setup_face(tgi_shadow_map *sm, int face, tg_vec3 forward, tg_real znear, tg_real zfar)
{
    tg_vec3 r, u, o = sm->origin;
    tgi_mat4 *m = &sm->world_to_clip[face];
    tg_real depth_range = tg_max(tg_sub(zfar, znear), TG_R(0.001f));
    tg_real a = tg_div(tg_add(zfar, znear), depth_range);
    tg_real b = tg_neg(tg_div(tg_mul(tg_mul(TG_R(2.0f), zfar), znear), depth_range));
    light_basis(forward, &r, &u);
    sm->right[face] = r; sm->up[face] = u; sm->forward[face] = forward;
    set_row(m, 0, tgi_v3_scale(r, sm->focal), tg_neg(tg_mul(tgi_v3_dot(r, o), sm->focal)));
    set_row(m, 1, tgi_v3_scale(u, sm->focal), tg_neg(tg_mul(tgi_v3_dot(u, o), sm->focal)));
    set_row(m, 2, tgi_v3_scale(forward, a), tg_add(tg_neg(tg_mul(tgi_v3_dot(forward, o), a)), b));
    set_row(m, 3, forward, tg_neg(tgi_v3_dot(forward, o)));
}

/* Farthest distance from the light to the bounds, plus a margin. */
static tg_real far_distance(tg_vec3 o, tg_vec3 lo, tg_vec3 hi)
{
    tg_real d = 0;
    int k;
    for (k = 0; k < 8; k++) d = tg_max(d, tgi_v3_length(tgi_v3_sub(box_corner(lo, hi, k), o)));
    return tg_add(tg_mul(d, TG_R(1.01f)), TG_R(0.1f));
}

void tgi_shadow_map_setup(tgi_shadow_map *sm, const tgi_light *l, int size,
                         tg_vec3 scene_min, tg_vec3 scene_max, void *memory)
{
    static const tg_real axes[6][3] = {
        { TG_ONE, 0, 0 }, { -TG_ONE, 0, 0 }, { 0, TG_ONE, 0 },
        { 0, -TG_ONE, 0 }, { 0, 0, TG_ONE }, { 0, 0, -TG_ONE } };
    tg_real tan_half, zfar, znear, widen;
    int f;
    memset(sm, 0, sizeof *sm);
    sm->size = size > 0 ? size : 1;
    sm->faces = light_faces(l);
    sm->depth = (tg_real *)memory;
    sm->texel_ndc = tg_div(TG_R(2.0f), tg_from_int(sm->size));
    sm->filter = TG_SHADOW_PCF_TENT;
    if (l->type == TG_LIGHT_DIRECTIONAL) {
        sm->orthographic = 1;
        setup_ortho(sm, l->dir, scene_min, scene_max);
        return;
    }
    sm->origin = l->pos;
    /* size / (size - 2 border): the face is widened so a PCF border lies outside its nominal cone */
    widen = tg_ratio(sm->size, sm->size > 2 * SHADOW_BORDER + 1 ? sm->size - 2 * SHADOW_BORDER : 1);
    if (l->type == TG_LIGHT_SPOT) {
        tg_real angle = tg_clamp(l->angle, TG_R(0.001f), SPOT_MAX_ANGLE);
        tan_half = tg_div(tg_sin(angle), tg_max(tg_cos(angle), TG_R(0.01f)));
    } else {
        tan_half = TG_ONE; /* 90 degree cube face */
    }
    tan_half = tg_mul(tan_half, widen);
    sm->focal = tg_div(TG_ONE, tan_half);
    sm->tan_half = tan_half;
    sm->texel_world = tg_div(tg_mul(tan_half, TG_R(2.0f)), tg_from_int(sm->size));
    zfar = far_distance(sm->origin, scene_min, scene_max);
    znear = tg_clamp(tg_mul(zfar, TG_R(0.0005f)), TG_R(0.005f), TG_R(0.05f));
    if (l->type == TG_LIGHT_SPOT) {
        setup_face(sm, 0, tgi_v3_normalize_or(l->dir, tg_v3(0, tg_neg(TG_ONE), 0)), znear, zfar);
        return;
    }
    for (f = 0; f < 6; f++)
        setup_face(sm, f, tg_v3(axes[f][0], axes[f][1], axes[f][2]), znear, zfar);
}

void tgi_shadow_map_render_rows(tgi_shadow_map *sm, int face, const tg_vec3 *pos,
                               int tri_count, int y0, int y1)
{
    size_t n = (size_t)sm->size;
    tg_real *depth = sm->depth + (size_t)face * n * n;
    size_t i;
    for (i = (size_t)y0 * n; i < (size_t)y1 * n; i++) depth[i] = TG_REAL_MAX;
    tgi_raster_depth(depth, sm->size, sm->size, &sm->world_to_clip[face], sm->orthographic,
                    pos, tri_count, y0, y1);
}

void tgi_shadow_map_render(tgi_shadow_map *sm, const tg_vec3 *pos, int tri_count)
{
    int f;
    for (f = 0; f < sm->faces; f++) tgi_shadow_map_render_rows(sm, f, pos, tri_count, 0, sm->size);
}

/* Cube face whose axis dominates d: +X -X +Y -Y +Z -Z. */
static int cube_face(tg_vec3 d)
{
    tg_real ax = tg_abs(d.x), ay = tg_abs(d.y), az = tg_abs(d.z);
    if (ax >= ay && ax >= az) return d.x >= 0 ? 0 : 1;
    if (ay >= az) return d.y >= 0 ? 2 : 3;
    return d.z >= 0 ? 4 : 5;
}

/* Receiver-plane depth bias: the receiver's depth at each PCF tap is
 * extrapolated from its plane (normal n in the light basis).  Taps are
 * separable: tap (i, j) sits at NDC offset (ox[i], oy[j]) from the lookup.
 *   orthographic  depth(i, j) = depth + gx ox[i] + gy oy[j]
 *   perspective   the tap's ray r = (ndc / focal, 1) meets the plane at
 *                 depth num / den, den = n . r = den_c + dx[i] + dy[j]; the
 *                 test depth - bias <= stored is done as num >= (stored +
 *                 bias) den (den < 0), without a division per tap. */
tg_real tgi_shadow_visibility(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n)
{
    int face = sm->faces == 6 ? cube_face(tgi_v3_sub(p, sm->origin)) : 0;
    tg_vec3 r = sm->right[face], u = sm->up[face], f = sm->forward[face];
    tg_real nl_x = tgi_v3_dot(n, r), nl_y = tgi_v3_dot(n, u), nl_z = tgi_v3_dot(n, f);
    tg_real half_size = tg_ldexp(tg_from_int(sm->size), -1);
    tg_real ndc_x, ndc_y, tw, bias, su, sv, fx, fy, norm, lit = 0;
    tg_real wx[4], wy[4], tx_off[4], ty_off[4];
    tg_real base = 0, num = 0, den_c = 0, den_max = 0;
    const tg_real *depth = sm->depth + (size_t)face * (size_t)sm->size * (size_t)sm->size;
    int i0, j0, i, j, perspective = !sm->orthographic;
    int taps = sm->filter == TG_SHADOW_PCF_BILINEAR ? 2 : 4;

    if (!perspective) {
        tg_real inv_nz;
        if (nl_z >= 0) return 0; /* the surface faces away from the light */
        if (nl_z > tg_neg(GRAZING_COS)) nl_z = tg_neg(GRAZING_COS);
        ndc_x = tg_mul(tg_sub(tgi_v3_dot(p, r), sm->ortho_center_x), sm->ortho_scale);
        ndc_y = tg_mul(tg_sub(tgi_v3_dot(p, u), sm->ortho_center_y), sm->ortho_scale);
        tw = sm->texel_world;
        bias = tg_ldexp(tw, -1);
        base = tg_sub(tg_sub(tgi_v3_dot(p, f), sm->ortho_near), bias);
        /* plane n.(dx, dy, dz) = 0 -> dz = -(nx dx + ny dy) / nz; world = ndc / scale */
        inv_nz = tg_div(tg_neg(sm->ortho_scale_inv), nl_z);
        nl_x = tg_mul(nl_x, inv_nz);  /* now depth change per NDC unit along x */
        nl_y = tg_mul(nl_y, inv_nz);
    } else {
        tg_vec3 d = tgi_v3_sub(p, sm->origin);
        tg_real lz = tgi_v3_dot(d, f), lx = tgi_v3_dot(d, r), ly = tgi_v3_dot(d, u), inv_lz;
        if (lz <= TG_R(0.001f)) return TG_ONE; /* behind the light's map: unshadowed */
        num = tg_add(tg_add(tg_mul(nl_x, lx), tg_mul(nl_y, ly)), tg_mul(nl_z, lz));
        if (num >= 0) return 0; /* faces away from the light position */
        inv_lz = tg_div(TG_ONE, lz);
        ndc_x = tg_mul(tg_mul(lx, sm->focal), inv_lz);
        ndc_y = tg_mul(tg_mul(ly, sm->focal), inv_lz);
        tw = tg_mul(sm->texel_world, lz);
        bias = tg_ldexp(tw, -1);
        den_c = tg_mul(num, inv_lz);                 /* n . r at the lookup */
        den_max = tg_mul(den_c, GRAZING_COS);        /* a tap is at most 1/GRAZING_COS deeper */
        nl_x = tg_mul(nl_x, sm->tan_half);           /* d(n . r) per NDC unit */
        nl_y = tg_mul(nl_y, sm->tan_half);
    }
    /* continuous texel position (rows top to bottom), then the PCF footprint:
     * tent  taps i0-1 .. i0+2, weights 1-f, 1, 1, f (sum 3 per axis)
     * bilinear  taps i0 .. i0+1, weights 1-f, f (sum 1 per axis) */
    su = tg_sub(tg_mul(tg_add(ndc_x, TG_ONE), half_size), TG_R(0.5f));
    sv = tg_sub(tg_mul(tg_sub(TG_ONE, ndc_y), half_size), TG_R(0.5f));
    i0 = tg_to_int(su); j0 = tg_to_int(sv);
    if (i0 < -2 || j0 < -2 || i0 > sm->size + 1 || j0 > sm->size + 1) return TG_ONE;
    fx = tg_sub(su, tg_from_int(i0));
    fy = tg_sub(sv, tg_from_int(j0));
    if (taps == 4) {
        wx[0] = tg_sub(TG_ONE, fx); wx[1] = wx[2] = TG_ONE; wx[3] = fx;
        wy[0] = tg_sub(TG_ONE, fy); wy[1] = wy[2] = TG_ONE; wy[3] = fy;
        i0 -= 1; j0 -= 1; fx = tg_add(fx, TG_ONE); fy = tg_add(fy, TG_ONE);
        norm = TG_R(1.0f / 9.0f);
    } else {
        wx[0] = tg_sub(TG_ONE, fx); wx[1] = fx;
        wy[0] = tg_sub(TG_ONE, fy); wy[1] = fy;
        norm = TG_ONE;
    }
    for (i = 0; i < taps; i++) {
        /* tap i's texel centre (i0 + i) relative to the lookup, in NDC (y up) */
        tg_real ox = tg_mul(tg_sub(tg_from_int(i), fx), sm->texel_ndc);
        tg_real oy = tg_neg(tg_mul(tg_sub(tg_from_int(i), fy), sm->texel_ndc));
        tx_off[i] = tg_mul(nl_x, ox);
        ty_off[i] = tg_mul(nl_y, oy);
    }
    if (i0 >= 0 && j0 >= 0 && i0 + taps <= sm->size && j0 + taps <= sm->size) {
        /* fast path, the whole footprint inside the map (an empty texel holds
         * TG_REAL_MAX, which passes both tests without a special case) */
        for (j = 0; j < taps; j++) {
            const tg_real *row = depth + (size_t)(j0 + j) * (size_t)sm->size + i0;
            tg_real row_lit = 0;
            if (perspective) {
                tg_real den_row = tg_add(den_c, ty_off[j]);
                for (i = 0; i < taps; i++) {
                    tg_real den = tg_min(tg_add(den_row, tx_off[i]), den_max);
                    row_lit = tg_add(row_lit, num >= tg_mul(tg_add(row[i], bias), den) ? wx[i] : 0);
                }
            } else {
                tg_real base_row = tg_add(base, ty_off[j]);
                for (i = 0; i < taps; i++)
                    row_lit = tg_add(row_lit, tg_add(base_row, tx_off[i]) <= row[i] ? wx[i] : 0);
            }
            lit = tg_add(lit, tg_mul(row_lit, wy[j]));
        }
        return tg_saturate(tg_mul(lit, norm));
    }
    for (j = 0; j < taps; j++) {   /* at the map's edge: taps outside are lit */
        int ty = j0 + j;
        const tg_real *row = depth + (size_t)(ty < 0 ? 0 : ty) * (size_t)sm->size;
        tg_real row_lit = 0;
        for (i = 0; i < taps; i++) {
            int tx = i0 + i;
            tg_real stored;
            if (tx < 0 || ty < 0 || tx >= sm->size || ty >= sm->size) { row_lit = tg_add(row_lit, wx[i]); continue; }
            stored = row[tx];
            if (stored == TG_REAL_MAX) { row_lit = tg_add(row_lit, wx[i]); continue; }
            if (perspective) {
                tg_real den = tg_min(tg_add(tg_add(den_c, tx_off[i]), ty_off[j]), den_max);
                if (num >= tg_mul(tg_add(stored, bias), den)) row_lit = tg_add(row_lit, wx[i]);
            } else if (tg_add(tg_add(base, tx_off[i]), ty_off[j]) <= stored) {
                row_lit = tg_add(row_lit, wx[i]);
            }
        }
        lit = tg_add(lit, tg_mul(row_lit, wy[j]));
    }
    return tg_saturate(tg_mul(lit, norm));
}
