/*
 * shadowmap.c - shadow maps for directional (orthographic, fitted to the
 * scene bounds), spot (perspective) and point lights (a seamless cube of six
 * wide faces), rasterized depth-only by tg_raster_depth, and the lookup:
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
    *right = tg_v3_normalize_or(tg_v3_cross(forward, helper), tg_v3(TG_ONE, 0, 0));
    *up = tg_v3_cross(*right, forward);
}

static int light_faces(const tg_light *l) { return l->type == TG_LIGHT_POINT ? 6 : 1; }

size_t tg_shadow_map_bytes(const tg_light *l, int size)
{
    size_t n = (size_t)(size > 0 ? size : 0);
    return (size_t)light_faces(l) * n * n * sizeof(tg_real);
}

static void set_row(tg_mat4 *m, int row, tg_vec3 a, tg_real d)
{
    m->m[row * 4 + 0] = a.x; m->m[row * 4 + 1] = a.y; m->m[row * 4 + 2] = a.z; m->m[row * 4 + 3] = d;
}

/* Corner k (0..7) of the box [lo, hi]. */
static tg_vec3 box_corner(tg_vec3 lo, tg_vec3 hi, int k)
{
    return tg_v3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
}

static void setup_ortho(tg_shadow_map *sm, tg_vec3 dir, tg_vec3 lo, tg_vec3 hi)
{
    tg_vec3 f = tg_v3_normalize_or(dir, tg_v3(0, tg_neg(TG_ONE), 0)), r, u;
    tg_real minx = TG_REAL_MAX, maxx = TG_REAL_MIN, miny = TG_REAL_MAX, maxy = TG_REAL_MIN;
    tg_real minz = TG_REAL_MAX, half, scale, margin;
    int k;
    light_basis(f, &r, &u);
    for (k = 0; k < 8; k++) {
        tg_vec3 c = box_corner(lo, hi, k);
        tg_real x = tg_v3_dot(c, r), y = tg_v3_dot(c, u), z = tg_v3_dot(c, f);
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
    sm->texel_world = tg_div(tg_mul(half, TG_R(2.0f)), tg_from_int(sm->size));
    sm->world_to_clip[0] = tg_m4_identity();
    /* clip = ((p.r - cx) s, (p.u - cy) s, p.f - near, 1) */
    set_row(&sm->world_to_clip[0], 0, tg_v3_scale(r, scale), tg_neg(tg_mul(sm->ortho_center_x, scale)));
    set_row(&sm->world_to_clip[0], 1, tg_v3_scale(u, scale), tg_neg(tg_mul(sm->ortho_center_y, scale)));
    set_row(&sm->world_to_clip[0], 2, f, tg_neg(sm->ortho_near));
    set_row(&sm->world_to_clip[0], 3, tg_v3(0, 0, 0), TG_ONE);
}

/* Perspective face: clip = (x f, y f, a z + b, z) in the light's view space. */
static void setup_face(tg_shadow_map *sm, int face, tg_vec3 forward, tg_real znear, tg_real zfar)
{
    tg_vec3 r, u, o = sm->origin;
    tg_mat4 *m = &sm->world_to_clip[face];
    tg_real depth_range = tg_max(tg_sub(zfar, znear), TG_R(0.001f));
    tg_real a = tg_div(tg_add(zfar, znear), depth_range);
    tg_real b = tg_neg(tg_div(tg_mul(tg_mul(TG_R(2.0f), zfar), znear), depth_range));
    light_basis(forward, &r, &u);
    sm->right[face] = r; sm->up[face] = u; sm->forward[face] = forward;
    set_row(m, 0, tg_v3_scale(r, sm->focal), tg_neg(tg_mul(tg_v3_dot(r, o), sm->focal)));
    set_row(m, 1, tg_v3_scale(u, sm->focal), tg_neg(tg_mul(tg_v3_dot(u, o), sm->focal)));
    set_row(m, 2, tg_v3_scale(forward, a), tg_add(tg_neg(tg_mul(tg_v3_dot(forward, o), a)), b));
    set_row(m, 3, forward, tg_neg(tg_v3_dot(forward, o)));
}

/* Farthest distance from the light to the bounds, plus a margin. */
static tg_real far_distance(tg_vec3 o, tg_vec3 lo, tg_vec3 hi)
{
    tg_real d = 0;
    int k;
    for (k = 0; k < 8; k++) d = tg_max(d, tg_v3_length(tg_v3_sub(box_corner(lo, hi, k), o)));
    return tg_add(tg_mul(d, TG_R(1.01f)), TG_R(0.1f));
}

void tg_shadow_map_setup(tg_shadow_map *sm, const tg_light *l, int size,
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
    sm->texel_world = tg_div(tg_mul(tan_half, TG_R(2.0f)), tg_from_int(sm->size));
    zfar = far_distance(sm->origin, scene_min, scene_max);
    znear = tg_clamp(tg_mul(zfar, TG_R(0.0005f)), TG_R(0.005f), TG_R(0.05f));
    if (l->type == TG_LIGHT_SPOT) {
        setup_face(sm, 0, tg_v3_normalize_or(l->dir, tg_v3(0, tg_neg(TG_ONE), 0)), znear, zfar);
        return;
    }
    for (f = 0; f < 6; f++)
        setup_face(sm, f, tg_v3(axes[f][0], axes[f][1], axes[f][2]), znear, zfar);
}

void tg_shadow_map_render_rows(tg_shadow_map *sm, int face, const tg_vec3 *pos,
                               int tri_count, int y0, int y1)
{
    size_t n = (size_t)sm->size;
    tg_real *depth = sm->depth + (size_t)face * n * n;
    size_t i;
    for (i = (size_t)y0 * n; i < (size_t)y1 * n; i++) depth[i] = TG_REAL_MAX;
    tg_raster_depth(depth, sm->size, sm->size, &sm->world_to_clip[face], sm->orthographic,
                    pos, tri_count, y0, y1);
}

void tg_shadow_map_render(tg_shadow_map *sm, const tg_vec3 *pos, int tri_count)
{
    int f;
    for (f = 0; f < sm->faces; f++) tg_shadow_map_render_rows(sm, f, pos, tri_count, 0, sm->size);
}

/* Cube face whose axis dominates d: +X -X +Y -Y +Z -Z. */
static int cube_face(tg_vec3 d)
{
    tg_real ax = tg_abs(d.x), ay = tg_abs(d.y), az = tg_abs(d.z);
    if (ax >= ay && ax >= az) return d.x >= 0 ? 0 : 1;
    if (ay >= az) return d.y >= 0 ? 2 : 3;
    return d.z >= 0 ? 4 : 5;
}

/* The tent PCF: taps i0-1 .. i0+2 with weights 1-f, 1, 1, f (sum 3). */
static void tent_weights(tg_real frac, tg_real w[4])
{
    w[0] = tg_sub(TG_ONE, frac); w[1] = TG_ONE; w[2] = TG_ONE; w[3] = frac;
}

/* Receiver-plane depth at the tap whose NDC offset from the lookup is (dx, dy)
 * (orthographic: world offsets).  See setup of `plane` in tg_shadow_visibility. */
typedef struct receiver_plane {
    int orthographic;
    tg_real depth;          /* receiver depth at the lookup point */
    tg_real gx, gy;         /* ortho: depth change per world unit along right / up */
    tg_real num;            /* persp: n . p (light view space), < 0 when lit side */
    tg_real nx_f, ny_f, nz; /* persp: n.x / focal, n.y / focal, n.z */
    tg_real den_max;        /* persp: grazing clamp of n . r (negative) */
} receiver_plane;

static tg_real plane_depth(const receiver_plane *pl, tg_real ax, tg_real ay)
{
    tg_real den;
    if (pl->orthographic) return tg_add(pl->depth, tg_add(tg_mul(pl->gx, ax), tg_mul(pl->gy, ay)));
    /* ray r = (ndc_x / focal, ndc_y / focal, 1): depth = (n.p) / (n.r), exact for the plane */
    den = tg_add(tg_add(tg_mul(pl->nx_f, ax), tg_mul(pl->ny_f, ay)), pl->nz);
    if (den > pl->den_max) den = pl->den_max;
    return tg_div(pl->num, den);
}

tg_real tg_shadow_visibility(const tg_shadow_map *sm, tg_vec3 p, tg_vec3 n)
{
    int face = sm->faces == 6 ? cube_face(tg_v3_sub(p, sm->origin)) : 0;
    tg_vec3 r = sm->right[face], u = sm->up[face], f = sm->forward[face];
    tg_real nl_x = tg_v3_dot(n, r), nl_y = tg_v3_dot(n, u), nl_z = tg_v3_dot(n, f);
    tg_real size = tg_from_int(sm->size), half_size = tg_mul(size, TG_R(0.5f));
    tg_real ndc_x, ndc_y, tw, bias, su, sv, wx[4], wy[4], lit = 0;
    const tg_real *depth = sm->depth + (size_t)face * (size_t)sm->size * (size_t)sm->size;
    receiver_plane pl;
    int i0, j0, i, j;

    memset(&pl, 0, sizeof pl);

    pl.orthographic = sm->orthographic;
    if (sm->orthographic) {
        if (nl_z >= 0) return 0; /* the surface faces away from the light */
        if (nl_z > tg_neg(GRAZING_COS)) nl_z = tg_neg(GRAZING_COS);
        tg_real lx = tg_sub(tg_v3_dot(p, r), sm->ortho_center_x);
        tg_real ly = tg_sub(tg_v3_dot(p, u), sm->ortho_center_y);
        ndc_x = tg_mul(lx, sm->ortho_scale);
        ndc_y = tg_mul(ly, sm->ortho_scale);
        pl.depth = tg_sub(tg_v3_dot(p, f), sm->ortho_near);
        /* plane n.(dx, dy, dz) = 0 -> dz = -(nx dx + ny dy) / nz, per NDC unit */
        pl.gx = tg_div(tg_neg(nl_x), tg_mul(nl_z, sm->ortho_scale));
        pl.gy = tg_div(tg_neg(nl_y), tg_mul(nl_z, sm->ortho_scale));
        tw = sm->texel_world;
    } else {
        tg_vec3 d = tg_v3_sub(p, sm->origin);
        tg_real lz = tg_v3_dot(d, f);
        if (lz <= TG_R(0.001f)) return TG_ONE; /* behind the light's map: unshadowed */
        ndc_x = tg_div(tg_mul(tg_v3_dot(d, r), sm->focal), lz);
        ndc_y = tg_div(tg_mul(tg_v3_dot(d, u), sm->focal), lz);
        pl.depth = lz;
        pl.num = tg_add(tg_add(tg_mul(nl_x, tg_v3_dot(d, r)), tg_mul(nl_y, tg_v3_dot(d, u))), tg_mul(nl_z, lz));
        if (pl.num >= 0) return 0; /* faces away from the light position */
        pl.nx_f = tg_div(nl_x, sm->focal);
        pl.ny_f = tg_div(nl_y, sm->focal);
        pl.nz = nl_z;
        /* grazing clamp: a tap's receiver depth is at most 1 / GRAZING_COS times the lookup's */
        pl.den_max = tg_mul(tg_div(pl.num, lz), GRAZING_COS);
        tw = tg_mul(sm->texel_world, lz);
    }
    bias = tg_mul(tw, TG_R(0.5f));
    /* continuous texel position (rows top to bottom), then the 4x4 tent footprint */
    su = tg_sub(tg_mul(tg_add(ndc_x, TG_ONE), half_size), TG_R(0.5f));
    sv = tg_sub(tg_mul(tg_sub(TG_ONE, ndc_y), half_size), TG_R(0.5f));
    i0 = tg_to_int(su); j0 = tg_to_int(sv);
    if (i0 < -2 || j0 < -2 || i0 > sm->size + 1 || j0 > sm->size + 1) return TG_ONE;
    tent_weights(tg_sub(su, tg_from_int(i0)), wx);
    tent_weights(tg_sub(sv, tg_from_int(j0)), wy);
    for (j = 0; j < 4; j++) {
        int ty = j0 - 1 + j;
        tg_real row_lit = 0;
        /* NDC of the tap's texel centre relative to the lookup */
        tg_real ay = tg_neg(tg_div(tg_sub(tg_from_int(ty), sv), half_size));
        for (i = 0; i < 4; i++) {
            int tx = i0 - 1 + i;
            tg_real ax, stored, receiver;
            if (tx < 0 || ty < 0 || tx >= sm->size || ty >= sm->size) { row_lit = tg_add(row_lit, wx[i]); continue; }
            stored = depth[(size_t)ty * (size_t)sm->size + (size_t)tx];
            if (stored == TG_REAL_MAX) { row_lit = tg_add(row_lit, wx[i]); continue; }
            ax = tg_div(tg_sub(tg_from_int(tx), su), half_size);
            receiver = plane_depth(&pl, sm->orthographic ? ax : tg_add(ndc_x, ax),
                                   sm->orthographic ? ay : tg_add(ndc_y, ay));
            if (tg_sub(receiver, bias) <= stored) row_lit = tg_add(row_lit, wx[i]);
        }
        lit = tg_add(lit, tg_mul(row_lit, wy[j]));
    }
    return tg_saturate(tg_mul(lit, TG_R(1.0f / 9.0f)));
}
