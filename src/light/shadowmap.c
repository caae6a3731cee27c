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
#define GRAZING_MIN_COS TG_R(0.001f)    /* |n . l| floor: keeps the receiver plane's slope finite */
/* Error bounds of rasterized depth (tgi_raster_* snap vertices to 1/16 of a
 * pixel or texel: a vertex moves up to sqrt(2)/32 of one sideways, and the
 * plane through the moved vertices, taken at any point of the triangle, moves
 * along its normal by at most that much at the point's own depth), with a
 * margin of ~3; and of the arithmetic, in units of the number type. */
#define RECEIVER_SNAP TG_R(0.125f)
#define RECEIVER_ULPS 8

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
        for (i = (size_t)y0 * n; i < (size_t)y1 * n; i++) depth[i] = TG_RASTER_DEPTH16_EMPTY;
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

/* LOOKUP_INLINE: a lookup's helpers inline in it (the float build called
 * cube_face, both builds map_error); a build for size keeps the calls. */
#if !TG_OUTLINE_HELPERS && defined(__GNUC__)
#define LOOKUP_INLINE inline __attribute__((always_inline))
#else
#define LOOKUP_INLINE inline
#endif

static LOOKUP_INLINE int cube_face(tg_vec3 d)
{
    tg_real ax = tgi_abs_fast(d.x), ay = tgi_abs_fast(d.y), az = tgi_abs_fast(d.z);
    if (ax >= ay && ax >= az) return d.x >= 0 ? 0 : 1;
    if (ay >= az) return d.y >= 0 ? 2 : 3;
    return d.z >= 0 ? 4 : 5;
}

int tgi_shadow_cube_face(tg_vec3 d) { return cube_face(d); }

tg_real tgi_shadow_gbuffer_error(const tgi_view *view)
{
    /* RECEIVER_SNAP pixels at depth 1, plus RECEIVER_ULPS of the number type */
    return tg_add(tg_div(RECEIVER_SNAP, view->pixels_per_unit), RECEIVER_ULPS * TG_EPS);
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
static tg_real depth_bias(const tgi_shadow_face *fc, tg_real texel)
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

/* 1 when prepared, 0 when the surface faces away from the light. */
static int prepare_ortho(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real err, lookup *q)
{
    const tgi_shadow_face *fc = &sm->face[0];
    const tg_real *m = fc->world_to_clip.m;
    tg_vec3 r = fc->right, u = fc->up, f = fc->forward;
    tg_real nl_z = dot_basis(n, f), depth, inv_nz;
    if (nl_z >= 0) return 0;
    nl_z = tg_min(nl_z, tg_neg(GRAZING_MIN_COS));
    depth = tg_sub(dot_basis(p, f), sm->ortho_near);
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
    q->base = tg_sub(tg_sub(depth, depth_bias(fc, fc->texel_world)), tg_div(err, tg_neg(nl_z)));
    /* plane n.(dx, dy, dz) = 0 -> dz = -(nx dx + ny dy) / nz; world = ndc / scale */
    inv_nz = tg_div(tg_neg(sm->ortho_scale_inv), nl_z);
    q->slope_x = tg_mul(dot_basis(n, r), inv_nz);
    q->slope_y = tg_mul(dot_basis(n, u), inv_nz);
    return 1;
}

/* 1 when prepared, 0 when the surface faces away, -1 behind the light's map
 * or in an absent face (lit). */
static int prepare_perspective(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real err, lookup *q)
{
    tg_vec3 d = tgi_v3_sub(p, sm->origin), r, u, f;
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
static void fetch_taps(const tgi_shadow_map *sm, const tgi_shadow_face *fc, int i0, int j0, int taps,
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
int tgi_shadow_lit_perspective_q16(tg_real num, tg_real a, tg_real den, int wide)
{
    return wide ? lit_perspective_wide(num, a, den) : lit_perspective_mul(num, a, den);
}
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

/* PCF over the prepared lookup: continuous texel position (rows top to
 * bottom), then the footprint:
 *   tent      taps i0-1 .. i0+2, weights 1-f, 1, 1, f (sum 3 per axis)
 *   bilinear  taps i0 .. i0+1, weights 1-f, f (sum 1 per axis)
 * Taps outside the map, and texels where nothing was drawn, are lit. */
static PCF_INLINE tg_real pcf_taps(const tgi_shadow_map *sm, const lookup *q, const int taps)
{
    const tgi_shadow_face *fc = q->fc;
    tg_real su, sv, fx, fy, norm, lit = 0, wx[PCF_MAX_TAPS], wy[PCF_MAX_TAPS], dx[PCF_MAX_TAPS], dy[PCF_MAX_TAPS];
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
        su = (tg_real)wu; sv = (tg_real)wv; i0 = (int)iu; j0 = (int)iv;
    }
#else
    {
        tg_real half_size = tg_ldexp(tg_from_int(fc->size), -1);
        su = tg_sub(tg_mul(tg_add(q->ndc_x, TG_ONE), half_size), TG_R(0.5f));
        sv = tg_sub(tg_mul(tg_sub(TG_ONE, q->ndc_y), half_size), TG_R(0.5f));
    }
    i0 = tg_to_int(su); j0 = tg_to_int(sv);
    if ((unsigned)i0 + 2u > (unsigned)fc->size + 3u || (unsigned)j0 + 2u > (unsigned)fc->size + 3u)
        return TG_ONE;   /* outside [-2, size + 1], in one unsigned compare */
#endif
    /* the floor's fractions, in [0, 1): these and the weights below never saturate */
    fx = su - tg_from_int(i0);
    fy = sv - tg_from_int(j0);
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
    for (i = 0; i < taps; i++) {
        /* tap i's texel centre (i0 + i) relative to the lookup, in NDC (y up) */
#if TGI_Q16_WIDE
        /* fx, fy in [0, 2) (the floor's fraction, plus 1 for the tent) and
         * texel_ndc = 2 / size in (0, 2]: i - fx within [-2, 3] and its
         * product within [-6, 6], so tgi_wide (core/real.h) gives tg_sub's
         * and tg_mul's integers without their saturation tests */
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
static tg_real pcf(const tgi_shadow_map *sm, const lookup *q)
{
#if PCF_COPIES
    return sm->filter == TG_SHADOW_PCF_BILINEAR ? pcf_taps(sm, q, 2) : pcf_taps(sm, q, 4);
#else
    return pcf_taps(sm, q, sm->filter == TG_SHADOW_PCF_BILINEAR ? 2 : 4);
#endif
}

tg_real tgi_shadow_visibility_err(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n, tg_real position_error)
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

tg_real tgi_shadow_visibility(const tgi_shadow_map *sm, tg_vec3 p, tg_vec3 n)
{
    return tgi_shadow_visibility_err(sm, p, n, 0);
}

#endif /* !TG_NO_SHADOW_MAPS */
