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
#define GRAZING_MIN_COS TG_R(0.001f)    /* |n . l| floor: keeps the receiver plane's slope finite */
/* Error bounds of rasterized depth (tgi_raster_* snap vertices to 1/16 of a
 * pixel or texel: a vertex moves up to sqrt(2)/32 of one sideways, and the
 * plane through the moved vertices, taken at any point of the triangle, moves
 * along its normal by at most that much at the point's own depth), with a
 * margin of ~3; and of the arithmetic, in units of the number type. */
#define RECEIVER_SNAP TG_R(0.125f)
#define RECEIVER_ULPS 8

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
    size_t texels, bytes;
    if (size < TG_MIN_SHADOW_MAP || size > TG_MAX_SHADOW_MAP) return 0;
    if (tg_size_mul((size_t)size, (size_t)size, &texels) ||
        tg_size_mul(texels, (size_t)light_faces(l), &texels) ||
        tg_size_mul(texels, sizeof(tg_real), &bytes)) return 0;
    return bytes;
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
    if (tgi_shadow_map_bytes(l, size) == 0) return; /* empty: faces = 0 */
    sm->size = size;
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
    tg_real *depth;
    size_t i;
    if (face < 0 || face >= sm->faces) return;
    depth = sm->depth + (size_t)face * n * n;
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

tg_real tgi_shadow_gbuffer_error(const tgi_view *view)
{
    /* RECEIVER_SNAP pixels at depth 1, plus RECEIVER_ULPS of the number type */
    return tg_add(tg_div(RECEIVER_SNAP, view->pixels_per_unit), RECEIVER_ULPS * TG_EPS);
}

/* How far the map's own depths may lie in front of the true surface, along
 * its normal, at distance `lz` (perspective) or anywhere (orthographic). */
static tg_real map_error(const tgi_shadow_map *sm, tg_real lz)
{
    tg_real texel = sm->orthographic ? sm->texel_world : tg_mul(sm->texel_world, lz);
    return tg_add(tg_add(tg_mul(texel, RECEIVER_SNAP), tg_mul(lz, RECEIVER_ULPS * TG_EPS)),
                  RECEIVER_ULPS * TG_EPS);
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
    int face;
    tg_real ndc_x, ndc_y;
    tg_real slope_x, slope_y;   /* depth (ortho) or den (perspective) per NDC unit */
    tg_real base;               /* ortho: the receiver's depth at the lookup, biased */
    tg_real num, den_c, bias;   /* perspective */
} lookup;

/* 1 when prepared, 0 when the surface faces away from the light. */
static int prepare_ortho(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real err, lookup *q)
{
    tg_vec3 r = sm->right[0], u = sm->up[0], f = sm->forward[0];
    tg_real nl_z = tgi_v3_dot(n, f), depth, inv_nz;
    if (nl_z >= 0) return 0;
    nl_z = tg_min(nl_z, tg_neg(GRAZING_MIN_COS));
    depth = tg_sub(tgi_v3_dot(p, f), sm->ortho_near);
    err = tg_add(err, map_error(sm, tg_abs(depth)));
    q->face = 0;
    q->num = q->den_c = q->bias = 0;
    q->ndc_x = tg_mul(tg_sub(tgi_v3_dot(p, r), sm->ortho_center_x), sm->ortho_scale);
    q->ndc_y = tg_mul(tg_sub(tgi_v3_dot(p, u), sm->ortho_center_y), sm->ortho_scale);
    /* the receiver moved by err along n is err / |n . f| nearer the light */
    q->base = tg_sub(tg_sub(depth, tg_ldexp(sm->texel_world, -1)), tg_div(err, tg_neg(nl_z)));
    /* plane n.(dx, dy, dz) = 0 -> dz = -(nx dx + ny dy) / nz; world = ndc / scale */
    inv_nz = tg_div(tg_neg(sm->ortho_scale_inv), nl_z);
    q->slope_x = tg_mul(tgi_v3_dot(n, r), inv_nz);
    q->slope_y = tg_mul(tgi_v3_dot(n, u), inv_nz);
    return 1;
}

/* 1 when prepared, 0 when the surface faces away, -1 behind the light's map (lit). */
static int prepare_perspective(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real err, lookup *q)
{
    tg_vec3 d = tgi_v3_sub(p, sm->origin), r, u, f;
    tg_real lx, ly, lz, inv_lz;
    q->face = sm->faces == 6 ? cube_face(d) : 0;
    q->base = 0;
    r = sm->right[q->face]; u = sm->up[q->face]; f = sm->forward[q->face];
    lz = tgi_v3_dot(d, f); lx = tgi_v3_dot(d, r); ly = tgi_v3_dot(d, u);
    if (lz <= TG_R(0.001f)) return -1;
    q->num = tgi_v3_dot(n, d);          /* n . (p - light): < 0 when the surface faces it */
    if (q->num >= 0) return 0;
    inv_lz = tg_div(TG_ONE, lz);
    q->ndc_x = tg_mul(tg_mul(lx, sm->focal), inv_lz);
    q->ndc_y = tg_mul(tg_mul(ly, sm->focal), inv_lz);
    q->den_c = tg_mul(q->num, inv_lz);  /* n . r at the lookup */
    q->bias = tg_ldexp(tg_mul(sm->texel_world, lz), -1);
    /* the plane moved toward the light by err, at most half way to it */
    err = tg_add(err, map_error(sm, lz));
    q->num = tg_min(tg_add(q->num, err), tg_ldexp(q->num, -1));
    q->slope_x = tg_mul(tgi_v3_dot(n, r), sm->tan_half);
    q->slope_y = tg_mul(tgi_v3_dot(n, u), sm->tan_half);
    return 1;
}

/* Is the receiver lit at a tap whose offsets are dx + dy, against `stored`? */
static inline int tap_lit(const lookup *q, int perspective, tg_real off, tg_real stored)
{
    if (perspective)
        return q->num >= tg_mul(tg_add(stored, q->bias), tg_min(tg_add(q->den_c, off), q->den_c));
    return tg_add(q->base, tg_min(off, 0)) <= stored;
}

/* PCF over the prepared lookup: continuous texel position (rows top to
 * bottom), then the footprint:
 *   tent      taps i0-1 .. i0+2, weights 1-f, 1, 1, f (sum 3 per axis)
 *   bilinear  taps i0 .. i0+1, weights 1-f, f (sum 1 per axis)
 * Taps outside the map, and texels where nothing was drawn, are lit. */
static tg_real pcf(const tgi_shadow_map *sm, const lookup *q)
{
    tg_real half_size = tg_ldexp(tg_from_int(sm->size), -1);
    tg_real su, sv, fx, fy, norm, lit = 0, wx[4], wy[4], dx[4], dy[4];
    const tg_real *depth = sm->depth + (size_t)q->face * (size_t)sm->size * (size_t)sm->size;
    int i0, j0, i, j, perspective = !sm->orthographic;
    int taps = sm->filter == TG_SHADOW_PCF_BILINEAR ? 2 : 4;
    int inside;
    su = tg_sub(tg_mul(tg_add(q->ndc_x, TG_ONE), half_size), TG_R(0.5f));
    sv = tg_sub(tg_mul(tg_sub(TG_ONE, q->ndc_y), half_size), TG_R(0.5f));
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
        dx[i] = tg_mul(q->slope_x, tg_mul(tg_sub(tg_from_int(i), fx), sm->texel_ndc));
        dy[i] = tg_mul(q->slope_y, tg_neg(tg_mul(tg_sub(tg_from_int(i), fy), sm->texel_ndc)));
    }
    /* an empty texel holds TG_REAL_MAX, which every tap test passes */
    inside = i0 >= 0 && j0 >= 0 && i0 + taps <= sm->size && j0 + taps <= sm->size;
    for (j = 0; j < taps; j++) {
        int ty = j0 + j;
        const tg_real *row = depth + (size_t)(ty < 0 ? 0 : ty) * (size_t)sm->size;
        tg_real row_lit = 0;
        if (inside && perspective) {        /* the common cases, without per-tap checks */
            tg_real den_row = tg_add(q->den_c, dy[j]);
            for (i = 0; i < taps; i++) {
                tg_real den = tg_min(tg_add(den_row, dx[i]), q->den_c);
                if (q->num >= tg_mul(tg_add(row[i0 + i], q->bias), den)) row_lit = tg_add(row_lit, wx[i]);
            }
        } else if (inside) {                /* base + min(dx + dy, 0) <= stored, as two tests */
            tg_real base_row = tg_add(q->base, dy[j]);
            for (i = 0; i < taps; i++) {
                tg_real stored = row[i0 + i];
                if (tg_add(base_row, dx[i]) <= stored || q->base <= stored) row_lit = tg_add(row_lit, wx[i]);
            }
        } else {                            /* at the map's edge: taps outside are lit */
            for (i = 0; i < taps; i++) {
                int tx = i0 + i;
                if (tx < 0 || ty < 0 || tx >= sm->size || ty >= sm->size ||
                    tap_lit(q, perspective, tg_add(dx[i], dy[j]), row[tx]))
                    row_lit = tg_add(row_lit, wx[i]);
            }
        }
        lit = tg_add(lit, tg_mul(row_lit, wy[j]));
    }
    return tg_saturate(tg_mul(lit, norm));
}

tg_real tgi_shadow_visibility_err(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real position_error)
{
    lookup q;
    int state;
    if (sm->faces == 0) return TG_ONE;  /* no map (an impossible size) */
    position_error = tg_max(position_error, 0);
    state = sm->orthographic ? prepare_ortho(sm, p, n, position_error, &q)
                             : prepare_perspective(sm, p, n, position_error, &q);
    if (state <= 0) return state < 0 ? TG_ONE : 0;
    return pcf(sm, &q);
}

tg_real tgi_shadow_visibility(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n)
{
    return tgi_shadow_visibility_err(sm, p, n, 0);
}
