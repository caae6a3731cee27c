/* SPDX-License-Identifier: MIT */
/*
 * shadowmap.c - shadow maps for directional (orthographic, fitted to the
 * receivers' square and the scene bounds), spot (perspective) and point
 * lights (a seamless cube of up to six wide faces, each sized on its own),
 * rasterized depth-only in 16 bits (tgi_raster_depth16) or 32, and the
 * lookup: receiver-plane depth bias + 2x2 bilinear or 3x3 tent PCF, or the
 * caller's ray function.  See shadowmap.h.
 */
#include <string.h>
#include "shadowmap.h"
#include "../raster/raster.h"
#include "../raster/pack.h"


#if !TG_NO_SHADOW_MAPS /* the whole file is left out with TG_NO_SHADOW_MAPS=1 (tinygi.h "FEATURE SWITCHES") */

#define SPOT_MAX_ANGLE TG_R(1.3962634f) /* 80 degrees */

void tgi_shadow_basis(tg_vec3 forward, tg_vec3 *right, tg_vec3 *up)
{
    tg_vec3 helper = tg_abs(forward.y) < TG_R(0.99f) ? tg_v3(0, TG_ONE, 0) : tg_v3(TG_ONE, 0, 0);
    *right = tgi_v3_normalize_or(tgi_v3_cross(forward, helper), tg_v3(TG_ONE, 0, 0));
    *up = tgi_v3_cross(*right, forward);
}

static int light_faces(const tgi_light *l) { return l->type == TG_LIGHT_POINT ? 6 : 1; }

static size_t texel_bytes(int depth_bits)
{
    return depth_bits == TG_SHADOW_DEPTH32 ? sizeof(tg_real) : sizeof(uint16_t);
}

/* Storage of the faces of a finished need, each face's first texel in
 * offset[] (may be NULL); 0 when a present face's size is out of range,
 * the sum overflows, or no face is present. */
static size_t need_layout(const tgi_shadow_need *nd, size_t *offset)
{
    size_t total = 0, texels = 0, bytes;
    int f;
    for (f = 0; f < nd->faces; f++) {
        int n = nd->size[f];
        if (offset) offset[f] = texels;
        if (n == 0) continue;
        if (n < TG_MIN_SHADOW_MAP || n > TG_MAX_SHADOW_MAP) return 0;
        if (tg_size_mul((size_t)n, (size_t)n, &bytes) || tg_size_add(texels, bytes, &texels)) return 0;
    }
    if (tg_size_mul(texels, texel_bytes(nd->depth_bits), &total)) return 0;
    return total;
}

void tgi_shadow_need_init(tgi_shadow_need *nd, const tgi_light *l)
{
    memset(nd, 0, sizeof *nd);
    nd->faces = light_faces(l);
    nd->depth_bits = TG_SHADOW_DEPTH16;
}

void tgi_shadow_need_all(tgi_shadow_need *nd)
{
    int f;
    for (f = 0; f < nd->faces; f++) nd->seen[f] = 1, nd->window_set[f] = 0;
}

/* ceil(density) + the border on each side, within the limits (density may
 * be anything a rule gives, including a saturated one). */
static int face_size(tg_real density)
{
    int32_t n;
    if (!(density > 0)) return TG_MIN_SHADOW_MAP;
    if (density >= tg_from_int(TG_MAX_SHADOW_MAP)) return TG_MAX_SHADOW_MAP;
    n = tg_to_int(density);
    if (tg_from_int(n) < density) n++;
    n += 2 * TG_SHADOW_BORDER;
    return n < TG_MIN_SHADOW_MAP ? TG_MIN_SHADOW_MAP : n > TG_MAX_SHADOW_MAP ? TG_MAX_SHADOW_MAP : (int)n;
}

/* Face f's size by its density: across its window, or across the whole
 * face when that side is known; 0 when neither. */
static int density_size(const tgi_shadow_need *nd, int f)
{
    const tg_real *w = nd->window[f];
    if (nd->window_set[f]) return face_size(tg_mul(nd->density[f], tg_max(tg_sub(w[2], w[0]), tg_sub(w[3], w[1]))));
    if (nd->density[f] > 0 && nd->whole_side[f] > 0) return face_size(tg_mul(nd->density[f], nd->whole_side[f]));
    return 0;
}

void tgi_shadow_need_finish(tgi_shadow_need *nd, int size_override)
{
    int f, largest = TG_MIN_SHADOW_MAP;
    for (f = 0; f < nd->faces; f++) {
        nd->size[f] = 0;
        if (!nd->seen[f]) continue;
        if (size_override > 0) {   /* whole, so that every plan's face is the same */
            nd->size[f] = size_override;
            nd->window_set[f] = 0;
            continue;
        }
        nd->size[f] = density_size(nd, f);   /* texels per unit, across the face */
        if (nd->size[f] > largest) largest = nd->size[f];
    }
    for (f = 0; f < nd->faces; f++)     /* whole faces without a size: the largest the rule gave */
        if (nd->seen[f] && nd->size[f] == 0) nd->size[f] = largest;
}

size_t tgi_shadow_need_bytes(const tgi_shadow_need *nd)
{
    return need_layout(nd, NULL);
}

/* The need of a map with every face at `size`, 16-bit. */
static void uniform_need(tgi_shadow_need *nd, const tgi_light *l, int size)
{
    tgi_shadow_need_init(nd, l);
    tgi_shadow_need_all(nd);
    tgi_shadow_need_finish(nd, size);
}

size_t tgi_shadow_map_bytes(const tgi_light *l, int size)
{
    tgi_shadow_need nd;
    if (size < TG_MIN_SHADOW_MAP || size > TG_MAX_SHADOW_MAP) return 0;
    uniform_need(&nd, l, size);
    return tgi_shadow_need_bytes(&nd);
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

/* size / (size - 2 border): a face is widened so a PCF border lies outside its nominal extent. */
static tg_real widening(int size)
{
    return tg_ratio(size, size > 2 * TG_SHADOW_BORDER + 1 ? size - 2 * TG_SHADOW_BORDER : 1);
}

/* The 16-bit depth range [lo, lo + range) of a face: range > 0 (the raster
 * draws nothing otherwise), one step = range / 65536. */
static void set_depth_range(tgi_shadow_face *fc, int depth_bits, tg_real lo, tg_real hi)
{
    fc->depth_lo = lo;
    fc->depth_range = tg_max(tg_sub(hi, lo), TG_R(0.001f));
    fc->depth_step = depth_bits == TG_SHADOW_DEPTH16 ? tg_ldexp(fc->depth_range, -16) : 0;
    if (depth_bits == TG_SHADOW_DEPTH16 && fc->depth_step < TG_EPS) fc->depth_step = TG_EPS;
}

static void setup_ortho(tgi_shadow_map *sm, tg_vec3 dir, tg_vec3 lo, tg_vec3 hi)
{
    tgi_shadow_face *fc = &sm->face[0];
    tg_vec3 f = tgi_v3_normalize_or(dir, tg_v3(0, tg_neg(TG_ONE), 0)), r, u;
    tg_real minx = TG_REAL_MAX, maxx = TG_REAL_MIN, miny = TG_REAL_MAX, maxy = TG_REAL_MIN;
    tg_real minz = TG_REAL_MAX, maxz = TG_REAL_MIN, half, scale, margin;
    int k;
    tgi_shadow_basis(f, &r, &u);
    for (k = 0; k < 8; k++) {
        tg_vec3 c = box_corner(lo, hi, k);
        tg_real x = tgi_v3_dot(c, r), y = tgi_v3_dot(c, u), z = tgi_v3_dot(c, f);
        minx = tg_min(minx, x); maxx = tg_max(maxx, x);
        miny = tg_min(miny, y); maxy = tg_max(maxy, y);
        minz = tg_min(minz, z); maxz = tg_max(maxz, z);
    }
    if (sm->need.window_set[0]) {  /* across the light: the receivers' window only */
        minx = sm->need.window[0][0]; miny = sm->need.window[0][1];
        maxx = sm->need.window[0][2]; maxy = sm->need.window[0][3];
    }
    half = tg_mul(tg_max(tg_sub(maxx, minx), tg_sub(maxy, miny)), TG_R(0.5f));
    half = tg_max(half, TG_R(0.01f));
    /* widen so the square plus a PCF border of texels fits */
    half = tg_mul(half, widening(fc->size));
    margin = tg_max(tg_mul(half, TG_R(0.01f)), TG_R(0.01f));
    scale = tg_div(TG_ONE, half);
    fc->right = r; fc->up = u; fc->forward = f;
    /* the window's centre; the sum in tgi_wide (core/real.h: tg_mul and
     * tg_add's result where they do not saturate): in Q16.16 a window past
     * 16384 units from the origin saturated the sum (a +-10 ground at x =
     * 30000 got its map centred at 16384) */
    sm->ortho_center_x = (tg_real)tgi_wide_mul((tgi_wide)minx + maxx, TG_R(0.5f));
    sm->ortho_center_y = (tg_real)tgi_wide_mul((tgi_wide)miny + maxy, TG_R(0.5f));
    sm->ortho_near = tg_sub(minz, margin);
    sm->ortho_scale = scale;
    sm->ortho_scale_inv = half;
    fc->texel_ndc = tg_div(TG_R(2.0f), tg_from_int(fc->size));
    fc->texel_world = tg_div(tg_mul(half, TG_R(2.0f)), tg_from_int(fc->size));
    /* stored depth = clip z, from 0 at the near side to past the far side */
    set_depth_range(fc, sm->depth_bits, 0, tg_add(tg_sub(maxz, sm->ortho_near), tg_ldexp(margin, 1)));
    fc->world_to_clip = tgi_m4_identity();
    /* clip = ((p.r - cx) s, (p.u - cy) s, p.f - near, 1) */
    set_row(&fc->world_to_clip, 0, tgi_v3_scale(r, scale), tg_neg(tg_mul(sm->ortho_center_x, scale)));
    set_row(&fc->world_to_clip, 1, tgi_v3_scale(u, scale), tg_neg(tg_mul(sm->ortho_center_y, scale)));
    set_row(&fc->world_to_clip, 2, f, tg_neg(sm->ortho_near));
    set_row(&fc->world_to_clip, 3, tg_v3(0, 0, 0), TG_ONE);
}

/* Perspective face: clip = ((x - cx z) f, (y - cy z) f, a z + b, z) in the
 * light's view space, f = 1 / the window's half side, widened by the
 * face's border; the window (centre cx, cy, half side h in x/z, y/z) is the
 * need's, or the whole nominal face. */
static void setup_face(tgi_shadow_map *sm, int face, tg_vec3 forward, tg_real tan_nominal,
                       tg_real znear, tg_real zfar)
{
    tgi_shadow_face *fc = &sm->face[face];
    const tgi_shadow_need *nd = &sm->need;
    tg_vec3 r, u, o = sm->origin;
    tgi_mat4 *m = &fc->world_to_clip;
    tg_real depth_range = tg_max(tg_sub(zfar, znear), TG_R(0.001f));
    tg_real a = tg_div(tg_add(zfar, znear), depth_range);
    tg_real b = tg_neg(tg_div(tg_mul(tg_mul(TG_R(2.0f), zfar), znear), depth_range));
    tg_real h = tan_nominal;
    tg_vec3 rx, uy;
    fc->center_x = fc->center_y = 0;
    if (nd->window_set[face]) {
        const tg_real *w = nd->window[face];
        fc->center_x = tg_ldexp(tg_add(w[0], w[2]), -1);
        fc->center_y = tg_ldexp(tg_add(w[1], w[3]), -1);
        h = tg_max(tg_ldexp(tg_max(tg_sub(w[2], w[0]), tg_sub(w[3], w[1])), -1), TG_R(0.001f));
    }
    tgi_shadow_basis(forward, &r, &u);
    fc->right = r; fc->up = u; fc->forward = forward;
    fc->tan_half = tg_mul(h, widening(fc->size));
    fc->focal = tg_div(TG_ONE, fc->tan_half);
    fc->texel_ndc = tg_div(TG_R(2.0f), tg_from_int(fc->size));
    fc->texel_world = tg_div(tg_mul(fc->tan_half, TG_R(2.0f)), tg_from_int(fc->size));
    set_depth_range(fc, sm->depth_bits, znear, zfar);
    rx = tgi_v3_scale(tgi_v3_sub(r, tgi_v3_scale(forward, fc->center_x)), fc->focal);
    uy = tgi_v3_scale(tgi_v3_sub(u, tgi_v3_scale(forward, fc->center_y)), fc->focal);
    set_row(m, 0, rx, tg_neg(tgi_v3_dot(rx, o)));
    set_row(m, 1, uy, tg_neg(tgi_v3_dot(uy, o)));
    set_row(m, 2, tgi_v3_scale(forward, a), tg_add(tg_neg(tg_mul(tgi_v3_dot(forward, o), a)), b));
    set_row(m, 3, forward, tg_neg(tgi_v3_dot(forward, o)));
}

/* Farthest distance from o to the bounds along `axis` (or in any direction,
 * axis = 0), plus a margin: 1% and 0.1. */
static tg_real far_along(tg_vec3 o, tg_vec3 axis, tg_vec3 lo, tg_vec3 hi)
{
    tg_real d = 0;
    int k, any = axis.x == 0 && axis.y == 0 && axis.z == 0;
    for (k = 0; k < 8; k++) {
        tg_vec3 v = tgi_v3_sub(box_corner(lo, hi, k), o);
        d = tg_max(d, any ? tgi_v3_length(v) : tgi_v3_dot(v, axis));
    }
    return tg_add(tg_mul(d, TG_R(1.01f)), TG_R(0.1f));
}

tg_real tgi_shadow_near(tg_vec3 origin, tg_vec3 scene_min, tg_vec3 scene_max)
{
    tg_real zfar = far_along(origin, tg_v3(0, 0, 0), scene_min, scene_max);
    return tg_clamp(tg_mul(zfar, TG_R(0.0005f)), TG_R(0.005f), TG_R(0.05f));
}

tg_vec3 tgi_shadow_face_axis(const tgi_light *l, int face)
{
    static const tg_real axes[6][3] = {
        { TG_ONE, 0, 0 }, { -TG_ONE, 0, 0 }, { 0, TG_ONE, 0 },
        { 0, -TG_ONE, 0 }, { 0, 0, TG_ONE }, { 0, 0, -TG_ONE } };
    if (l->type == TG_LIGHT_POINT && face >= 0 && face < 6)
        return tg_v3(axes[face][0], axes[face][1], axes[face][2]);
    return tgi_v3_normalize_or(l->dir, tg_v3(0, tg_neg(TG_ONE), 0));
}

tg_real tgi_shadow_nominal_tan(const tgi_light *l)
{
    tg_real angle;
    if (l->type == TG_LIGHT_POINT) return TG_ONE;  /* 90 degree cube face */
    if (l->type != TG_LIGHT_SPOT) return 0;
    angle = tg_clamp(l->angle, TG_R(0.001f), SPOT_MAX_ANGLE);
    return tg_div(tg_sin(angle), tg_max(tg_cos(angle), TG_R(0.01f)));
}

/* Place every face (the need and the memory are set). */
static void fit(tgi_shadow_map *sm, const tgi_light *l, tg_vec3 lo, tg_vec3 hi)
{
    tg_real znear;
    int f;
    if (l->type == TG_LIGHT_DIRECTIONAL) {
        sm->orthographic = 1;
        setup_ortho(sm, l->dir, lo, hi);
        sm->texel_world = sm->face[0].texel_world;
        return;
    }
    sm->origin = l->pos;
    znear = tgi_shadow_near(sm->origin, lo, hi);
    for (f = 0; f < sm->faces; f++) {
        tg_vec3 axis = tgi_shadow_face_axis(l, f);
        if (sm->face[f].size == 0) continue;
        setup_face(sm, f, axis, tgi_shadow_nominal_tan(l), znear,
                   tg_max(far_along(sm->origin, axis, lo, hi), tg_ldexp(znear, 1)));
        if (sm->face[f].size == sm->size) sm->texel_world = sm->face[f].texel_world;
    }
}

void tgi_shadow_map_setup_need(tgi_shadow_map *sm, const tgi_light *l, const tgi_shadow_need *nd,
                               tg_vec3 scene_min, tg_vec3 scene_max, void *memory)
{
    size_t offset[TG_SHADOW_MAX_FACES];
    int f;
    memset(sm, 0, sizeof *sm);
    sm->filter = TG_SHADOW_PCF_BILINEAR;
    sm->light = l;
    if (need_layout(nd, offset) == 0) return;  /* empty: faces = 0 */
    sm->need = *nd;
    sm->faces = nd->faces;
    sm->depth_bits = nd->depth_bits == TG_SHADOW_DEPTH32 ? TG_SHADOW_DEPTH32 : TG_SHADOW_DEPTH16;
    sm->depth = memory;
    for (f = 0; f < sm->faces; f++) {
        sm->face[f].size = nd->size[f];
        sm->face[f].offset = offset[f];
        if (nd->size[f] > sm->size) sm->size = nd->size[f];
    }
    fit(sm, l, scene_min, scene_max);
}

void tgi_shadow_map_setup(tgi_shadow_map *sm, const tgi_light *l, int size,
                         tg_vec3 scene_min, tg_vec3 scene_max, void *memory)
{
    tgi_shadow_need nd;
    if (size < TG_MIN_SHADOW_MAP || size > TG_MAX_SHADOW_MAP) {
        memset(sm, 0, sizeof *sm);
        return;
    }
    uniform_need(&nd, l, size);
    tgi_shadow_map_setup_need(sm, l, &nd, scene_min, scene_max, memory);
}

void tgi_shadow_map_refit(tgi_shadow_map *sm, tg_vec3 scene_min, tg_vec3 scene_max)
{
    if (sm->faces == 0 || sm->ray || !sm->light) return;
    fit(sm, sm->light, scene_min, scene_max);
}

void tgi_shadow_rays_setup(tgi_shadow_map *sm, const tgi_light *l, tgi_shadow_ray_fn ray,
                           const void *tracer)
{
    memset(sm, 0, sizeof *sm);
    sm->light = l;
    sm->ray = ray;
    sm->tracer = tracer;
}

/* the 16-bit faces' clear is a memset of 0xFF bytes */
typedef char tgi_depth16_empty_bytes[TG_RASTER_DEPTH16_EMPTY == 0xFFFF ? 1 : -1];

void tgi_shadow_map_render_rows(tgi_shadow_map *sm, int face, const tg_vec3 *pos,
                               int tri_count, int y0, int y1)
{
    const tgi_shadow_face *fc;
    size_t n, i;
    if (face < 0 || face >= sm->faces || sm->face[face].size == 0) return;
    fc = &sm->face[face];
    n = (size_t)fc->size;
    if (y0 < 0) y0 = 0;
    if (y1 > fc->size) y1 = fc->size;
    if (y0 >= y1) return;
    if (sm->depth_bits == TG_SHADOW_DEPTH16) {
        uint16_t *depth = (uint16_t *)sm->depth + fc->offset;
        /* every code TG_RASTER_DEPTH16_EMPTY (0xFFFF: tgi_depth16_empty_bytes) */
        memset(depth + (size_t)y0 * n, 0xFF, (size_t)(y1 - y0) * n * sizeof *depth);
        tgi_raster_depth16(depth, fc->size, fc->size, &fc->world_to_clip, sm->orthographic,
                           fc->depth_lo, fc->depth_range, pos, tri_count, y0, y1);
    } else {
        tg_real *depth = (tg_real *)sm->depth + fc->offset;
        for (i = (size_t)y0 * n; i < (size_t)y1 * n; i++) depth[i] = TG_REAL_MAX;
        tgi_raster_depth(depth, fc->size, fc->size, &fc->world_to_clip, sm->orthographic,
                         pos, tri_count, y0, y1);
    }
}

void tgi_shadow_map_render(tgi_shadow_map *sm, const tg_vec3 *pos, int tri_count)
{
    int f;
    for (f = 0; f < sm->faces; f++) tgi_shadow_map_render_rows(sm, f, pos, tri_count, 0, sm->face[f].size);
}

#include "shadow_lookup.h"   /* the lookup; GRAZING_MIN_COS, RECEIVER_* */

int tgi_shadow_cube_face(tg_vec3 d) { return cube_face(d); }

tg_real tgi_shadow_gbuffer_error(const tgi_view *view)
{
    /* RECEIVER_SNAP pixels at depth 1, plus RECEIVER_ULPS of the number type */
    return tg_add(tg_div(RECEIVER_SNAP, view->pixels_per_unit), RECEIVER_ULPS * TG_EPS);
}

#if TG_FIXED
int tgi_shadow_lit_perspective_q16(tg_real num, tg_real a, tg_real den, int wide)
{
    return wide ? lit_perspective_wide(num, a, den) : lit_perspective_mul(num, a, den);
}
#endif

tg_real tgi_shadow_visibility_err(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real position_error)
{
#if TG_OUTLINE_HELPERS
    /* shadow_lookup's body (shadow_lookup.h), as written before it */
    lookup q;
    int state;
    position_error = tg_max(position_error, 0);
    if (sm->ray) return sm->ray(sm->tracer, sm->light, p, n, position_error);
    if (sm->faces == 0) return TG_ONE;
    state = sm->orthographic ? prepare_ortho(sm, p, n, position_error, &q)
                             : prepare_perspective(sm, p, n, position_error, &q);
    if (state <= 0) return state < 0 ? TG_ONE : 0;
    return pcf(sm, &q);
#else
    return shadow_lookup(sm, p, n, position_error);
#endif
}

tg_real tgi_shadow_visibility(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n)
{
    return tgi_shadow_visibility_err(sm, p, n, 0);
}

#endif /* !TG_NO_SHADOW_MAPS */
