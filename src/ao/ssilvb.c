/* SPDX-License-Identifier: MIT */
/*
 * ssilvb.c - horizon search with a visibility bitmask and a thickness
 * (Therrien et al. 2023), cosine-weighted AO, bent normal and near-field
 * irradiance in GTAO's view-vector slices.  See ssilvb.h.
 */
#include "ssilvb.h"

#if !TG_NO_TECHNIQUES /* the whole file is left out with TG_NO_TECHNIQUES=1 (tinygi.h "FEATURE SWITCHES") */

static const tgi_ssilvb_params ssilvb_defaults = { .slices = 4, .steps = 8, .radius = TG_ONE, .thickness = TG_R(0.5f) };

void tgi_ssilvb_defaults(tgi_ssilvb_params *p)
{
    *p = ssilvb_defaults;
}

int tgi_ssilvb_popcount(uint32_t b)
{
    b = b - ((b >> 1) & 0x55555555u);                     /* 2-bit counts */
    b = (b & 0x33333333u) + ((b >> 2) & 0x33333333u);     /* 4-bit counts */
    b = (b + (b >> 4)) & 0x0f0f0f0fu;                     /* 8-bit counts */
    return (int)((b * 0x01010101u) >> 24);
}

uint32_t tgi_ssilvb_sector_bits(tg_real lo, tg_real hi)
{
    tg_real n = tg_from_int(TG_SSILVB_SECTORS), x0, x1;
    int start, count;
    lo = tg_saturate(lo);
    hi = tg_saturate(hi);
    if (hi < lo) { tg_real t = lo; lo = hi; hi = t; }
    x0 = tg_mul(lo, n);
    x1 = tg_mul(hi, n);
    start = tg_to_int(x0);                                   /* floor(u_min N_b) */
    count = -tg_to_int(tg_neg(tg_sub(x1, x0)));              /* ceil((u_max - u_min) N_b) */
    if (start >= TG_SSILVB_SECTORS || count <= 0) return 0;
    if (count >= TG_SSILVB_SECTORS) return 0xffffffffu << start;
    return (((uint32_t)1 << count) - 1u) << start;           /* bits past 31 fall off */
}

/* What a slice of the visibility bitmask reads besides the pixel: the
 * parameters, the radiance the near field gathers (with `near`), and the
 * thickness scaled by the pixel's shift (tgi_ao_slice_pixel). */
typedef struct vb_tech {
    const tgi_ssilvb_params *p;
    const tgi_rgb *radiance;
    int near;
    tg_real thick, sector;            /* sector: pi / N_b */
    tg_real thick_max;                /* 64 radii (scaled): as good as infinite */
    int to_edge;                      /* tgi_ssilvb_params.to_edge */
} vb_tech;

/* One slice's frame (ao.h) and its sector boundaries. */
typedef struct vb_slice {
    tg_real gamma, cos_g, sin_g;
    tg_real theta0, step;             /* theta_k = theta0 + k step, step = pi / N_b */
    int kz;                           /* tgi_ssilvb_bounds' (-1: not yet) */
    tg_real bound[TG_SSILVB_SECTORS + 1];
} vb_slice;

static tg_real sector_angle(const vb_slice *sl, int k)
{
    return tg_add(sl->theta0, tg_mul(tg_from_int(k), sl->step));
}

/* cos(k pi / 32), k = 0..16: the sines and cosines of the sector
 * boundaries' angles from the slice's (sector_sc), no tg_sin or tg_cos. */
static const tg_real quarter_cos[17] = {
    TG_R(1.000000000f),
    TG_R(0.995184727f),
    TG_R(0.980785280f),
    TG_R(0.956940336f),
    TG_R(0.923879533f),
    TG_R(0.881921264f),
    TG_R(0.831469612f),
    TG_R(0.773010453f),
    TG_R(0.707106781f),
    TG_R(0.634393284f),
    TG_R(0.555570233f),
    TG_R(0.471396737f),
    TG_R(0.382683432f),
    TG_R(0.290284677f),
    TG_R(0.195090322f),
    TG_R(0.098017140f),
    TG_R(0.000000000f)
};

/* cos and sin of k pi / N_b, k = 0..N_b (N_b = 32), by symmetry from quarter_cos. */
static void sector_sc(int k, tg_real *ck, tg_real *sk)
{
    if (k <= 16) { *ck = quarter_cos[k]; *sk = quarter_cos[16 - k]; }
    else { *ck = tg_neg(quarter_cos[32 - k]); *sk = quarter_cos[k - 16]; }
}

void tgi_ssilvb_bounds(tg_real gamma, tg_real cos_g, tg_real sin_g, tg_real bound[TG_SSILVB_SECTORS + 1], int *kz)
{
    int k;
    for (k = 0; k <= 16; k++) {        /* cos theta_k = sin(g + k pi / N_b) = sin g cos(k pi / N_b) + cos g sin(k pi / N_b) */
        tg_real a = tg_mul(sin_g, quarter_cos[k]), b = tg_mul(cos_g, quarter_cos[16 - k]);
        bound[k] = tg_add(a, b);
        bound[TG_SSILVB_SECTORS - k] = tg_sub(b, a);
    }
    k = tg_to_int(tg_mul(tg_sub(TG_HALF_PI, gamma), TG_R(10.1859164f)));   /* (pi/2 - gamma) N_b / pi */
    *kz = k < 0 ? 0 : k > TG_SSILVB_SECTORS ? TG_SSILVB_SECTORS : k;
}

uint32_t tgi_ssilvb_horizon_bits(tg_real c, int side, const tg_real bound[TG_SSILVB_SECTORS + 1], int kz)
{
    int lo, hi, m;
    if (side > 0) {      /* past kz, theta_k in (0, pi): theta >= theta_k where c <= cos theta_k, falling with k */
        lo = kz; hi = TG_SSILVB_SECTORS + 1;
        while (hi - lo > 1) {
            m = (lo + hi) >> 1;
            if (c <= bound[m]) lo = m;
            else hi = m;
        }
        return lo >= TG_SSILVB_SECTORS ? 0 : 0xffffffffu << lo;   /* from floor(u N_b) up */
    }
    /* theta = -acos c: up to kz, theta_k in (-pi, 0]: theta >= theta_k where cos theta_k <= c, rising with k */
    lo = -1; hi = kz + 1;
    while (hi - lo > 1) {
        m = (lo + hi) >> 1;
        if (bound[m] <= c) lo = m;
        else hi = m;
    }
    return lo + 1 >= TG_SSILVB_SECTORS ? 0xffffffffu : ((uint32_t)1 << (lo + 1)) - 1u;   /* ceil(u N_b) from 0 */
}

/* The slice integrals from 0 to theta (either sign), ssilvb.h:
 *   a  = int cos(t - g) |sin t|           (the cosine-weighted visibility)
 *   bs = int sin t cos(t - g) |sin t|     (bent normal along the slice direction)
 *   bc = int cos t cos(t - g) |sin t|     (bent normal along the view vector)
 * the positive branch's antiderivatives (gtao.h: a(h), F_s, F_c) minus
 * their value at 0, times sign(theta), at the boundary theta_k = g - pi/2
 * + k pi / N_b of sector k: sin theta_k = -cos(g + k pi / N_b) and cos
 * theta_k = sin(g + k pi / N_b), from the slice's cos g, sin g and
 * sector_sc's. */
typedef struct slice_prim { tg_real a, bs, bc; } slice_prim;

static slice_prim prim(const vb_slice *sl, int k)
{
    tg_real th = sector_angle(sl, k), cos_g = sl->cos_g, sin_g = sl->sin_g, ck, sk, s, c, s2, c2, s3, c3, cos2;
    const tg_real third = TG_R(0.333333333f);
    slice_prim r;
    sector_sc(k, &ck, &sk);
    s = tg_sub(tg_mul(sin_g, sk), tg_mul(cos_g, ck));
    c = tg_add(tg_mul(sin_g, ck), tg_mul(cos_g, sk));
    s2 = tg_sqr(s); c2 = tg_sqr(c); s3 = tg_mul(s2, s); c3 = tg_mul(c2, c);
    /* cos(2 th - g) = (c^2 - s^2) cos g + 2 s c sin g */
    cos2 = tg_add(tg_mul(tg_sub(c2, s2), cos_g), tg_mul(tg_ldexp(tg_mul(s, c), 1), sin_g));
    r.a = tg_ldexp(tg_sub(tg_add(cos_g, tg_mul(tg_ldexp(th, 1), sin_g)), cos2), -2);
    /* F_s(th) - F_s(0) = cos g s^3/3 + sin g (c^3/3 - c + 2/3) */
    r.bs = tg_add(tg_mul(cos_g, tg_mul(s3, third)),
                  tg_mul(sin_g, tg_add(tg_sub(tg_mul(c3, third), c), TG_R(0.666666667f))));
    /* F_c(th) - F_c(0) = (sin g s^3 - cos g c^3)/3 + cos g / 3 */
    r.bc = tg_mul(tg_add(tg_sub(tg_mul(sin_g, s3), tg_mul(cos_g, c3)), cos_g), third);
    if (th < 0) { r.a = tg_neg(r.a); r.bs = tg_neg(r.bs); r.bc = tg_neg(r.bc); }
    return r;
}

/* Sum of prim over the runs of set bits of b: the cosine weight (and the
 * bent integrals when bent is not NULL). */
static tg_real mask_weight(const vb_slice *sl, uint32_t b, tg_real *bs, tg_real *bc)
{
    tg_real w = 0;
    int k = 0;
    while (k < TG_SSILVB_SECTORS) {
        int j;
        slice_prim p0, p1;
        if (!((b >> k) & 1u)) { k++; continue; }
        for (j = k; j < TG_SSILVB_SECTORS && ((b >> j) & 1u); j++) {}
        p0 = prim(sl, k);
        p1 = prim(sl, j);
        w = tg_add(w, tg_sub(p1.a, p0.a));
        if (bs) {
            *bs = tg_add(*bs, tg_sub(p1.bs, p0.bs));
            *bc = tg_add(*bc, tg_sub(p1.bc, p0.bc));
        }
        k = j;
    }
    return w;
}

tg_real tgi_ssilvb_half_circle_u(tg_real c, int side, tg_real gamma)
{
    /* acos |c| = sqrt(1 - |c|) (a0 + a1 |c| + a2 |c|^2 + a3 |c|^3) within
     * 6.7e-5 (Abramowitz and Stegun 4.4.45): 2e-5 of the half circle */
    tg_real a = tg_min(tg_abs(c), TG_ONE), th;
    th = tg_add(TG_R(0.0742610f), tg_mul(a, TG_R(-0.0187293f)));
    th = tg_add(TG_R(-0.2121144f), tg_mul(a, th));
    th = tg_add(TG_R(1.5707288f), tg_mul(a, th));
    th = tg_mul(tg_sqrt(tg_sub(TG_ONE, a)), th);
    if (c < 0) th = tg_sub(TG_PI, th);
    if (side < 0) th = tg_neg(th);
    return tg_add(tg_mul(tg_sub(th, gamma), TG_INV_PI), TG_R(0.5f));
}

/* The signed angle from the view vector (positive toward the slice direction
 * on side +1) of view offset h, |h|^2 = d2 > 0, mapped to u in [0, 1] over
 * the slice's half circle: u = (theta - gamma) / pi + 1/2
 * (tgi_ssilvb_half_circle_u). */
static tg_real half_circle_u(const tgi_ao_slice_pixel *px, const vb_slice *sl, tg_vec3 h, tg_real d2, int side)
{
    return tgi_ssilvb_half_circle_u(tg_mul(tgi_v3_dot(h, px->vd), tg_rsqrt(d2)), side, sl->gamma);
}

/* The new sectors of a sample (bits, some not in *mask: the callers skip
 * a sample with none, which adds nothing) into *mask; with e, its pixel
 * j's radiance L over the new ones gathered into *e when the sender, at
 * front offset hf, faces the receiver. */
static void take_sectors(const vb_tech *t, const tgi_gview *g, const vb_slice *sl, uint32_t bits, int j, tg_vec3 hf,
                         uint32_t *mask, tg_vec3 *e)
{
    uint32_t fresh = bits & ~*mask;
    *mask |= bits;
    if (fresh && e && tgi_v3_dot(tgi_ao_normal_view(g, j), hf) < 0) {  /* the sender faces the receiver */
        tg_vec3 l = tgi_rgb_get(t->radiance, j);
        *e = tgi_v3_add(*e, tgi_v3_scale(l, mask_weight(sl, fresh, NULL, NULL)));
    }
}

/* March one side of a slice: set the sectors of every sample's front/back
 * pair in *mask; with radiance, gather each sample's L over its new sectors
 * into *e (unnormalised: the caller divides by the open weight). */
static void march(const vb_tech *t, const tgi_gview *g, const tgi_ao_slice_pixel *px, const vb_slice *sl,
                  tg_real sdx, tg_real sdy, int side, uint32_t *mask, tg_vec3 *e)
{
    tg_real thick = t->thick, d2, db2, uf, ub;
    tg_vec3 hf, hb;
    int steps = t->p->steps, s, j, got;
    uint32_t bits;
    tgi_ao_rays rays = TGI_AO_RAYS_NONE;
    for (s = 0; s < steps; s++) {
        got = tgi_ao_slice_sample(g, px, s, steps, sdx, sdy, &hf, &d2, &j, &rays);
        if (got < 0) break;
        if (got == 0) continue;
        /* the back point: the front moved by the thickness away from the eye */
        hb = tgi_v3_sub(hf, tgi_v3_scale(px->vd, thick));
        db2 = tgi_v3_dot(hb, hb);
        uf = half_circle_u(px, sl, hf, d2, side);
        ub = db2 > 0 ? half_circle_u(px, sl, hb, db2, side) : (side > 0 ? TG_ONE : 0);
        bits = tgi_ssilvb_sector_bits(tg_min(uf, ub), tg_max(uf, ub));
        if (bits & ~*mask) take_sectors(t, g, sl, bits, j, hf, mask, e);
    }
}

/* Whether the ray from offset a along direction v (any length) has no
 * point within the radius above the tangent plane: outside the radius
 * (|a|^2 = d2) and not moving inward, or on or under the tangent plane
 * and not rising.  Every segment of a sample lies on its view ray beyond
 * its front point, and of a segment segment_sectors counts only such
 * points, so this decides as it would (up to the rounding at the
 * boundaries) for the cost of two or three dot products. */
static int ray_misses(const tgi_ao_slice_pixel *px, tg_vec3 a, tg_vec3 v, tg_real d2)
{
    if (d2 >= px->r2 && tgi_v3_dot(a, v) >= 0) return 1;
    return tgi_v3_dot(a, px->nv) <= px->above && tgi_v3_dot(v, px->nv) <= 0;
}

/* The sectors of the solid segment from offset a to offset b (scaled by
 * the pixel's shift, as the samples are) where it lies within the radius,
 * |p|^2 < r2: the segment p = a + u t, u = (b - a) / |b - a|, 0 <= t <= |b
 * - a|, meets the sphere where t^2 + 2 (a.u) t + |a|^2 - r2 = 0.  In units
 * of the radius (rs in [0.5, 1], tgi_ao_unit_shift), a segment longer
 * than 64 radii (t->thick_max) is cut there (as good as infinite), so one
 * that can reach the sphere has |a| < rs + |b - a| <= 65 and (a.u)^2 and
 * |a|^2 stay inside Q16.16.  0 when no part is within the radius above
 * the tangent plane.  A segment ray_misses rejects costs no root, one
 * with both ends within the radius is not clipped. */
static uint32_t segment_sectors(const vb_tech *t, const tgi_ao_slice_pixel *px, const vb_slice *sl, tg_vec3 a, tg_vec3 b,
                                int side)
{
    tg_vec3 ab = tgi_v3_sub(b, a), u;
    tg_real len2 = tgi_v3_dot(ab, ab), d2 = tgi_v3_dot(a, a), b2, inv_len, len, reach, au, disc, root, t0, t1, ua, ub;
    if (!(len2 > 0) || ray_misses(px, a, ab, d2)) return 0;
    if (!(d2 < px->r2 && (b2 = tgi_v3_dot(b, b)) < px->r2)) {        /* clip it to the sphere */
        inv_len = tg_rsqrt(len2);
        len = tg_min(tg_mul(len2, inv_len), t->thick_max);             /* |b - a|, one root for it and u */
        reach = tg_add(px->rs, len);
        if (d2 >= tg_sqr(reach)) return 0;                            /* cannot reach the sphere */
        u = tgi_v3_scale(ab, inv_len);
        au = tgi_v3_dot(a, u);
        disc = tg_sub(tg_sqr(au), tg_sub(d2, px->r2));
        if (!(disc > 0)) return 0;
        root = tg_sqrt(disc);
        t0 = tg_max(tg_sub(tg_neg(au), root), 0);
        t1 = tg_min(tg_add(tg_neg(au), root), len);
        if (!(t0 < t1)) return 0;
        a = tgi_v3_add(a, tgi_v3_scale(u, t0));
        b = tgi_v3_add(a, tgi_v3_scale(u, tg_sub(t1, t0)));
        d2 = tgi_v3_dot(a, a);
        b2 = tgi_v3_dot(b, b);
    }
    if (tgi_v3_dot(a, px->nv) <= px->above && tgi_v3_dot(b, px->nv) <= px->above) return 0;   /* under the tangent plane */
    if (!(d2 > 0) || !(b2 > 0)) return 0;
    ua = half_circle_u(px, sl, a, d2, side);
    ub = half_circle_u(px, sl, b, b2, side);
    return tgi_ssilvb_sector_bits(tg_min(ua, ub), tg_max(ua, ub));
}

/* The depth z at the sample's pixel as an offset from the pixel: its
 * front offset hf moved along the pixel's view ray (per unit of depth)
 * by z - zf, scaled by the shift; 0 (and *h unset) when z is not beyond
 * zf (none, a back face in front of the surface, or the surface's own:
 * a sheet) or more than 64 radii beyond. */
static int layer_point(const vb_tech *t, const tgi_ao_slice_pixel *px, tg_vec3 hf, tg_vec3 ray, tg_real zf, tg_real z,
                       tg_vec3 *h)
{
    tg_real dz = tg_ldexp(tg_sub(z, zf), px->shift);
    if (!(z > zf) || dz <= 0 || dz >= t->thick_max) return 0;
    *h = tgi_v3_add(hf, tgi_v3_scale(ray, dz));
    return 1;
}

/* The sectors of a sample with no back face behind it (a one-sided
 * boundary, like a room's wall; front offset hf, |hf|^2 = d2): within the
 * radius and above the tangent plane, from its angle down to the end of
 * its side, as a horizon closes them (the surface between it and the
 * tangent plane is there too: the depth buffer's, seen from the pixel);
 * otherwise its view ray's segment to 64 radii where it enters the
 * radius. */
static uint32_t boundary_sectors(const vb_tech *t, const tgi_ao_slice_pixel *px, vb_slice *sl, tg_vec3 hf,
                                 tg_vec3 ray, tg_real d2, int side)
{
    tg_real uf;
    if (!(d2 < px->r2 && d2 > 0 && tgi_v3_dot(hf, px->nv) > px->above))
        return segment_sectors(t, px, sl, hf, tgi_v3_add(hf, tgi_v3_scale(ray, t->thick_max)), side);
    if (sl->cos_g > 0) {                                              /* its sector among the boundaries' cosines */
        if (sl->kz < 0) tgi_ssilvb_bounds(sl->gamma, sl->cos_g, sl->sin_g, sl->bound, &sl->kz);
        return tgi_ssilvb_horizon_bits(tg_mul(tgi_v3_dot(hf, px->vd), tg_rsqrt(d2)), side, sl->bound, sl->kz);
    }
    uf = half_circle_u(px, sl, hf, d2, side);
    return side > 0 ? tgi_ssilvb_sector_bits(uf, TG_ONE) : tgi_ssilvb_sector_bits(0, uf);
}

/* a + b, in tgi_wide where the caller's bound keeps the sum inside
 * tg_real (the same value as tg_add's then), else saturating. */
#if TG_FIXED && TG_MAX_IMAGE_SIDE > 8192
#error "march_layers' on-screen bound (4 sqrt 2 TG_MAX_IMAGE_SIDE pixels within Q16.16) needs TG_MAX_IMAGE_SIDE <= 8192"
#endif
static inline tg_real march_add(tg_real a, tg_real b, int bounded)
{
    return bounded ? (tg_real)((tgi_wide)a + b) : tg_add(a, b);
}

/* march with the G-buffer's further depth layers (request.depth_layers >=
 * 2): a sample's surface is solid along the pixel's view ray from its
 * front, the depth buffer's, to the nearest back face behind it
 * (tgi_gv_back_depth: a closed object's true thickness); where there is
 * none (a one-sided surface: a boundary, like a room's wall) it closes its
 * side down to the tangent plane as a horizon does (boundary_sectors);
 * where the back face is the surface's own (a
 * twosided sheet, which has no thickness to find) for the constant
 * thickness, as without layers.  With a third layer it is solid again
 * from the surface behind that back face (tgi_gv_behind_depth) for the
 * constant thickness.  Each segment counts where it lies within the
 * radius (the ray-traced reference's cut-off), not where its front point
 * does.  The hidden surface occludes and gathers nothing (its radiance is
 * unknown).  Between two samples a surface thinner than their spacing
 * occludes only where sampled, as with the paper's constant thickness.
 * With t->to_edge the samples spread over the part of the radius on the
 * screen (tgi_ao_screen_reach).  What costs nothing: a sample whose view
 * ray misses the radius above the tangent plane (ray_misses: none of its
 * segments counts) or that falls in the pixel of the one before
 * (tgi_ao_rays: it would set the same sectors again) is skipped before
 * its layers are read. */
static void march_layers(const vb_tech *t, const tgi_gview *g, const tgi_ao_slice_pixel *px, vb_slice *sl,
                         tg_real sdx, tg_real sdy, int side, uint32_t *mask, tg_vec3 *e)
{
    tg_real zf, zb, d2;
    tg_vec3 hf, hb, h3, h3end, ray;
    int steps = t->p->steps, s, j, got;
    uint32_t bits;
    tgi_ao_rays rays = TGI_AO_RAYS_NONE;
    tg_real r_px = px->r_px, dt, t_px, fx, fy, dx, dy;
    /* on the screen (to_edge) the march's distance and position stay
     * within two reaches of the screen, at most 2 x 8192 sqrt 2 pixels
     * (TG_MAX_IMAGE_SIDE), and their steps within Q16.16: stepped in
     * tgi_wide they are tg_add's sums, which never saturate here (the
     * saturation's two tests were a fifth of a Q16.16 layered frame) */
    const int on_screen = t->to_edge;
    if (t->to_edge) r_px = tg_min(r_px, tgi_ao_screen_reach(g, px, sdx, sdy));
    dt = tg_div(r_px, tg_from_int(steps));                            /* the samples' spacing in pixels */
    t_px = tg_mul(px->jitter, dt);
    dx = tg_mul(sdx, dt);
    dy = tg_mul(sdy, dt);
    fx = tg_add(tg_add(tg_from_int(px->x), TG_R(0.5f)), tg_mul(sdx, t_px));   /* the sample on the screen */
    fy = tg_add(tg_add(tg_from_int(px->y), TG_R(0.5f)), tg_mul(sdy, t_px));
    for (s = 0; s < steps; s++, t_px = march_add(t_px, dt, on_screen), fx = march_add(fx, dx, on_screen),
                               fy = march_add(fy, dy, on_screen)) {
        if (t_px < TG_ONE) continue;                                  /* within the pixel */
        got = tgi_ao_slice_point_at(g, px, fx, fy, &hf, &j, &rays);
        if (got < 0) break;
        if (got == 0) continue;
        ray = rays.ray;
        d2 = tgi_v3_dot(hf, hf);
        if (ray_misses(px, hf, ray, d2)) continue;
        zf = tgi_gv_depth(g, (size_t)j);
        zb = tgi_gv_back_depth(g, (size_t)j);
        if (layer_point(t, px, hf, ray, zf, zb, &hb))                 /* solid to its back face */
            bits = segment_sectors(t, px, sl, hf, hb, side);
        else if (zb == zf)                                            /* a twosided sheet: the thickness */
            bits = segment_sectors(t, px, sl, hf, tgi_v3_add(hf, tgi_v3_scale(ray, t->thick)), side);
        else                                                          /* no back face: a boundary */
            bits = boundary_sectors(t, px, sl, hf, ray, d2, side);
        if (bits & ~*mask)                                            /* new sectors; a sender within the radius */
            take_sectors(t, g, sl, bits, j, hf, mask, d2 < px->r2 ? e : NULL);
        if (layer_point(t, px, hf, ray, zf, tgi_gv_behind_depth(g, (size_t)j), &h3)) {
            h3end = tgi_v3_add(h3, tgi_v3_scale(ray, t->thick));
            *mask |= segment_sectors(t, px, sl, h3, h3end, side);
        }
    }
}

/* One slice (a tgi_ao_slice_fn, ao.h): both sides' sectors into one mask,
 * the visible weight and bent integrals over its runs of clear bits. */
static void bitmask_slice(const void *tech, const tgi_gview *g, const tgi_ao_slice_pixel *px, const tgi_ao_slice *f,
                          tg_real sdx, tg_real sdy, tgi_ao_slice_sum *sum)
{
    const vb_tech *t = (const vb_tech *)tech;
    vb_slice sl;
    uint32_t mask = 0;
    sl.gamma = f->gamma; sl.cos_g = f->cos_g; sl.sin_g = f->sin_g;
    sl.theta0 = tg_sub(f->gamma, TG_HALF_PI);
    sl.step = t->sector;
    sl.kz = -1;                                                       /* no bounds yet */
    if (g->store.back_depth) {
        march_layers(t, g, px, &sl, sdx, sdy, 1, &mask, t->near ? &sum->near : NULL);
        march_layers(t, g, px, &sl, tg_neg(sdx), tg_neg(sdy), -1, &mask, t->near ? &sum->near : NULL);
    } else {
        march(t, g, px, &sl, sdx, sdy, 1, &mask, t->near ? &sum->near : NULL);
        march(t, g, px, &sl, tg_neg(sdx), tg_neg(sdy), -1, &mask, t->near ? &sum->near : NULL);
    }
    sum->vis = mask_weight(&sl, ~mask, &sum->bs, &sum->bc);
    sum->open = mask_weight(&sl, 0xffffffffu, NULL, NULL);
}

void tgi_ssilvb_rows(const tgi_ssilvb_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                     const tgi_gresult *out, int y0, int y1)
{
    int shift = tgi_ao_unit_shift(p->radius);
    int near = tgi_gr_has_near(out) && tgi_rgb_present(radiance);
    /* the thickness as tgi_ao_slice_pixel scales the radius (rs); 64 radii
     * behind is as good as infinite (the back angle is then within 1/64 rad
     * of pi) and keeps |h_b|^2 inside Q16.16 */
    tg_real thick_max = tg_mul(tg_ldexp(p->radius, shift), TG_R(64.0f));
    tg_real thick = tg_min(tg_ldexp(tg_max(p->thickness, 0), shift), thick_max);
    const vb_tech vb = { p, radiance, near, thick, tg_div(TG_PI, tg_from_int(TG_SSILVB_SECTORS)), thick_max,
                         p->to_edge };
    const tgi_ao_slices t = { .slices = p->slices, .steps = p->steps, .radius = p->radius, .near = near,
                              .slice = bitmask_slice, .tech = &vb, .pattern = p->pattern };
    tgi_ao_slices_rows(&t, g, out, y0, y1);
}

#endif /* !TG_NO_TECHNIQUES */
