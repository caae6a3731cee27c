/* SPDX-License-Identifier: MIT */
/*
 * ao.h - what every ambient-occlusion / directional-occlusion technique of
 * tinygi shares: view-space helpers written straight from the tgi_view
 * fields (no call into view.c per sample), read through the G-buffer view
 * (raster/gview.h), and the interreflection brightening of AO (RTR eq.
 * 11.12-11.13).
 *
 * Every technique is a pass of the same shape
 *     void tgi_<tech>_rows(const tgi_<tech>_params *p, const tgi_gview *g,
 *                          const tgi_gresult *out, int y0, int y1);
 * over rows [y0, y1) of a full-resolution view (SSDO and the reference also
 * read the direct-light radiance, indexed like g), so the frame can treat
 * them alike and rows can be split across threads.  Conventions of the
 * results:
 *   ao      in [0, 1], 1 = open (unoccluded);
 *   bent    world-space unit bent normal (RTR eq. 11.10); NULL = not wanted;
 *   cone    bent-cone half angle in radians, [0, pi/2]; NULL = not wanted;
 *   near    one-bounce near-field IRRADIANCE (W/m^2-like, not multiplied by
 *           the receiver's albedo); NULL when the technique does not gather.
 * Sky pixels get ao 1, bent = the G-buffer normal there, cone pi/2, near 0.
 */
#ifndef TG_AO_H
#define TG_AO_H

#include "../core/vec.h"
#include "../core/unit.h"
#include "../raster/gview.h"
#include "../light/sh.h"
#include "sampling.h"

/* A radius this large means "unlimited" (ambient occlusion rather than
 * obscurance, RTR sec. 11.3.2). */
#define TG_AO_INFINITE TG_REAL_MAX

/* The default `bias` of the techniques that test samples against the
 * occluder's tangent plane (SSAO, SSDO, bent cones): the depth below it that
 * counts, as a fraction of the radius. */
#define TG_AO_DEFAULT_BIAS TG_R(0.03f)

/* ---- interreflection (RTR eq. 11.12-11.13) ----
 * k'_A = k_A / (1 - rho_ss (1 - k_A)): AO brightened as if the blocked
 * directions saw the shaded point's own outgoing radiance (Stewart-Langer).
 * Usable on any technique's ao, per colour channel (albedo = rho_ss). */
static inline tg_real tgi_ao_interreflection(tg_real ao, tg_real albedo)
{
    tg_real k = tg_saturate(ao);
    tg_real den = tg_sub(TG_ONE, tg_mul(tg_saturate(albedo), tg_sub(TG_ONE, k))); /* RTR eq. 11.13 */
    if (den <= 0) return TG_ONE;            /* albedo 1 and k 0: the limit is 1 */
    return tg_saturate(tg_div(k, den));
}

/* ---- multi-bounce AO (Jimenez et al. 2016, GTAO, eq. 10) ----
 * A cubic fit, per colour channel, of path-traced occlusion under a uniform
 * white sky with the interreflections of surfaces of albedo rho around the
 * point (the albedo taken as locally constant), from the AO k:
 *   k' = max(k, ((a k + b) k + c) k),  a = 2.0404 rho - 0.3324,
 *   b = -4.7951 rho + 0.6417,  c = 2.7552 rho + 0.6903.
 * k' = 0 at k = 0, about 1 at k = 1 (a + b + c = 0.9996 + 0.0005 rho, so
 * the result is clamped to [k, 1]), and grows with rho.  For AO-only
 * output: what the AO means with the bounces a path tracer adds. */
static inline tg_real tgi_ao_multibounce(tg_real ao, tg_real albedo)
{
    tg_real k = tg_saturate(ao), rho = tg_saturate(albedo);
    tg_real a = tg_sub(tg_mul(TG_R(2.0404f), rho), TG_R(0.3324f));    /* GTAO eq. 10 */
    tg_real b = tg_add(tg_mul(TG_R(-4.7951f), rho), TG_R(0.6417f));
    tg_real c = tg_add(tg_mul(TG_R(2.7552f), rho), TG_R(0.6903f));
    tg_real v = tg_mul(tg_add(tg_mul(tg_add(tg_mul(a, k), b), k), c), k);
    return tg_clamp(v, k, TG_ONE);
}

/* ---- view-space helpers (view.h conventions: x right, y up, z forward) ---- */

/* View-space position of the centre of pixel (x, y) at view depth z:
 * (kx z, ky z, z) with kx, ky its ray per unit of depth (the two below). */
static inline tg_real tgi_ao_ray_x(const tgi_view *v, int x)
{
    /* x_v = ndc_x z / focal_x with ndc_x = (2x + 1 - W) / W: one division per
     * axis, of numbers near 1, so Q16.16 keeps its precision */
    return tg_div(tg_from_int(2 * x + 1 - v->width), tg_mul(tg_from_int(v->width), v->focal_x));
}
static inline tg_real tgi_ao_ray_y(const tgi_view *v, int y)
{
    return tg_div(tg_from_int(v->height - 2 * y - 1), tg_mul(tg_from_int(v->height), v->focal_y));
}
static inline tg_vec3 tgi_ao_unproject(const tgi_view *v, int x, int y, tg_real z)
{
    return tg_v3(tg_mul(tgi_ao_ray_x(v, x), z), tg_mul(tgi_ao_ray_y(v, y), z), z);
}

/* Pixel (px, py) of a view-space point: 1, or 0 when it is behind the
 * camera or off screen.  Nearest pixel (whose square holds the projection). */
static inline int tgi_ao_project_pixel(const tgi_view *v, tg_vec3 p, int *px, int *py)
{
    tg_real ndc_x, ndc_y;
    int32_t x, y;
    if (p.z <= TG_R(0.001f)) return 0;
    ndc_x = tg_div(tg_mul(p.x, v->focal_x), p.z);
    ndc_y = tg_div(tg_mul(p.y, v->focal_y), p.z);
    if (ndc_x <= TG_R(-1.0f) || ndc_x >= TG_ONE || ndc_y <= TG_R(-1.0f) || ndc_y >= TG_ONE) return 0;
    x = tg_to_int(tg_ldexp(tg_mul(tg_add(ndc_x, TG_ONE), tg_from_int(v->width)), -1));
    y = tg_to_int(tg_ldexp(tg_mul(tg_sub(TG_ONE, ndc_y), tg_from_int(v->height)), -1));
    if (x < 0 || y < 0 || x >= v->width || y >= v->height) return 0;
    *px = (int)x; *py = (int)y;
    return 1;
}

/* Pixel index of a view-space point, or -1 (see tgi_ao_project_pixel). */
static inline int tgi_ao_project_index(const tgi_view *v, tg_vec3 p)
{
    int x, y;
    return tgi_ao_project_pixel(v, p, &x, &y) ? y * v->width + x : -1;
}

/* World direction -> view direction and back (the view basis is orthonormal). */
static inline tg_vec3 tgi_ao_dir_to_view(const tgi_view *v, tg_vec3 d)
{
    return tg_v3(tgi_v3_dot(d, v->right), tgi_v3_dot(d, v->up), tgi_v3_dot(d, v->forward));
}
static inline tg_vec3 tgi_ao_dir_to_world(const tgi_view *v, tg_vec3 d)
{
    return tgi_v3_add(tgi_v3_add(tgi_v3_scale(v->right, d.x), tgi_v3_scale(v->up, d.y)),
                     tgi_v3_scale(v->forward, d.z));
}

/* G-buffer normal of pixel i in view space. */
static inline tg_vec3 tgi_ao_normal_view(const tgi_gview *g, size_t i)
{
    return tgi_ao_dir_to_view(g->camera, tgi_gv_normal(g, i));
}

/* Depth bias of a screen-space test at view position pv with view normal
 * nv: `base` plus the depth change of the surface across one pixel
 * (slope-scaled, as for shadow maps): (z / pixels_per_unit) tan(theta),
 * theta between the normal and the view ray, tan clamped to 16.  At grazing
 * angles the nearest-pixel depth of a plane differs from the plane at the
 * sample by about this much, so smaller gaps are not evidence of occlusion. */
static inline tg_real tgi_ao_depth_bias(const tgi_gview *g, tg_vec3 pv, tg_vec3 nv, tg_real base)
{
    tg_vec3 ray = tgi_v3_normalize_or(pv, tg_v3(0, 0, TG_ONE));
    tg_real c = tg_abs(tgi_v3_dot(nv, ray));
    tg_real s = tg_sqrt(tg_sub(TG_ONE, tg_min(tg_sqr(c), TG_ONE)));
    tg_real tan_t = tg_div(s, tg_max(c, TG_R(0.0625f)));
    tg_real pixel = tg_div(pv.z, g->camera->pixels_per_unit);
    return tg_add(base, tg_mul(pixel, tan_t));
}

/* Screen-space occlusion test of a sample point s (view space) of the
 * shading point p, after Klehm sec. 2 (d_xn) and Ritschel sec. 3: s is an
 * occluder position when it lies behind the surface the camera sees at its
 * pixel j, i.e. more than `eps` below that surface's tangent plane (through
 * the pixel's position q_j, with its normal), and q_j is within `range` of p
 * (the range check: a foreground object far in front does not occlude what
 * is behind it).  The tangent-plane test makes a plane exact at any viewing
 * angle: the nearest-pixel depth of a grazing plane differs from the plane
 * at the sample by up to a pixel's slope, which a plain depth comparison
 * would read as occlusion.  Off-screen and sky count as open.  *qx, *qy get
 * the pixel (when on screen). */
static inline int tgi_ao_sample_blocked_at(const tgi_gview *g, tg_vec3 p, tg_vec3 s, tg_real eps,
                                          tg_real range, int *qx, int *qy)
{
    size_t j;
    tg_vec3 q, pq;
    if (!tgi_ao_project_pixel(g->camera, s, qx, qy)) return 0;
    j = tgi_gv_index(g, *qx, *qy);
    if (tgi_gv_is_sky(g, j) || tgi_gv_depth(g, j) >= s.z) return 0;
    q = tgi_ao_unproject(g->camera, *qx, *qy, tgi_gv_depth(g, j));
    pq = tgi_v3_sub(q, p);
    if (tgi_v3_dot(pq, pq) >= tg_sqr(range)) return 0;
    return tgi_v3_dot(tgi_ao_normal_view(g, j), tgi_v3_sub(s, q)) < tg_neg(eps);
}
static inline int tgi_ao_sample_blocked(const tgi_gview *g, tg_vec3 p, tg_vec3 s, tg_real eps, tg_real range)
{
    int qx, qy;
    return tgi_ao_sample_blocked_at(g, p, s, eps, range, &qx, &qy);
}

/* Write the "nothing computed" result for pixel i (sky, or no data). */
static inline void tgi_ao_write_open(const tgi_gview *g, const tgi_gresult *out, size_t i)
{
    tgi_gr_set_ao(out, i, TG_ONE);
    if (tgi_gr_has_bent(out)) tgi_gr_set_bent(out, i, tgi_gv_normal(g, i));
    if (tgi_gr_has_cone(out)) tgi_gr_set_cone(out, i, TG_HALF_PI);
    if (tgi_gr_has_near(out)) tgi_gr_set_near(out, i, tg_v3(0, 0, 0));
}

/* tgi_ao_write_open, and the far field pixel i starts from in the
 * techniques that compute their own environment term (SSDO, bent cones):
 * E0 of its normal, 0 on the sky or with no environment (env_sh9 NULL);
 * nothing when far is absent. */
static inline void tgi_ao_write_open_far(const tgi_gview *g, const tgi_gresult *out, size_t i,
                                         const tgi_rgb *far, const tg_vec3 *env_sh9)
{
    tgi_ao_write_open(g, out, i);
    if (tgi_rgb_present(far)) {
        tg_vec3 e = tg_v3(0, 0, 0);
        if (!tgi_gv_is_sky(g, i) && env_sh9) e = tgi_sh9_irradiance(env_sh9, tgi_gv_normal(g, i));
        tgi_rgb_set(far, i, e);
    }
}

/* The horizon techniques' view of pixel (x, y) (index i): view position
 * *pv, view normal *nv, unit vector to the eye *vd (at the full-resolution
 * pixel it stands for: gview.h's step and offset); returns the world
 * radius in the view's pixels at its depth. */
static inline tg_real tgi_ao_view_at(const tgi_gview *g, int x, int y, size_t i, tg_real radius,
                                     tg_vec3 *pv, tg_vec3 *nv, tg_vec3 *vd)
{
    tg_real r_px = tg_div(tg_mul(radius, g->camera->pixels_per_unit), tgi_gv_depth(g, i));
    *pv = tgi_ao_unproject(g->camera, x * g->step + g->offset_x, y * g->step + g->offset_y, tgi_gv_depth(g, i));
    *nv = tgi_ao_normal_view(g, i);
    *vd = tgi_v3_normalize_or(tgi_v3_neg(*pv), tg_v3(0, 0, TG_R(-1.0f)));
    return g->step > 1 ? tg_div(r_px, tg_from_int(g->step)) : r_px;   /* in the view's pixels */
}

/* Store a bent normal given in view space (any length) as a world unit
 * vector; a zero vector falls back to the normal. */
static inline void tgi_ao_write_bent_view(const tgi_gview *g, const tgi_gresult *out, size_t i, tg_vec3 bent_view)
{
    if (!tgi_gr_has_bent(out)) return;
    tgi_gr_set_bent(out, i, tgi_v3_unit_or(tgi_ao_dir_to_world(g->camera, bent_view), tgi_gv_normal(g, i)));
}

/* ---- view-vector slices (GTAO, gtao.c; the visibility bitmask, ssilvb.c) ---- */

/* Q16.16: the power of two 2^e that brings the radius into [0.5, 1], so the
 * squared sample distances neither underflow (a room 1 mm across) nor
 * saturate (1 km across).  Float needs none (0). */
static inline int tgi_ao_unit_shift(tg_real radius)
{
    int e = 0;
#if TG_FIXED
    while (radius > 0 && radius < TG_R(0.5f) && e < 16) { radius = tg_ldexp(radius, 1); e++; }
    while (radius > TG_ONE && e > -15) { radius = tg_ldexp(radius, -1); e--; }
#else
    (void)radius;
#endif
    return e;
}

/* A pixel marching its slices: (x, y), view position, normal, unit vector
 * to the eye, the radius in pixels at its depth, its jitter, the shift its
 * sample offsets are scaled by (tgi_ao_unit_shift), and, scaled by it, the
 * radius, its square and the height over the tangent plane below which a
 * sample counts for nothing. */
typedef struct tgi_ao_slice_pixel {
    int x, y;
    tg_vec3 pv, nv, vd;
    tg_real r_px, jitter;
    int shift;
    tg_real rs, r2, above;
} tgi_ao_slice_pixel;

/* Pixel (x, y) of g, index i, starts open (tgi_ao_write_open); 1 with *px
 * set up to march its slices of world radius `radius` (its jitter, the
 * radius's shift), 0 for sky or a technique that gathers nothing
 * (radius <= 0, steps < 1). */
static inline int tgi_ao_slice_pixel_at(const tgi_gview *g, const tgi_gresult *out, int x, int y, int i,
                                        tg_real radius, int steps, tg_real jitter, int shift,
                                        tgi_ao_slice_pixel *px)
{
    tgi_ao_write_open(g, out, (size_t)i);
    if (tgi_gv_is_sky(g, (size_t)i) || radius <= 0 || steps < 1) return 0;
    px->x = x; px->y = y;
    px->r_px = tgi_ao_view_at(g, x, y, (size_t)i, radius, &px->pv, &px->nv, &px->vd);
    px->jitter = jitter;
    px->shift = shift;
    px->rs = tg_ldexp(radius, shift);
    px->r2 = tg_sqr(px->rs);
    px->above = tg_add(tg_ldexp(px->pv.z, shift - 10), tg_mul(px->rs, TG_R(0.005f)));
    return 1;
}

/* The view rays per unit of depth of a march (tgi_ao_slice_point): the
 * last column's and row's (the samples of a slice side share them, a
 * division each saved), and the sample's; the last sample's pixel index,
 * which a march reading them skips when the next sample falls in it
 * again (it would add nothing).  Starts with qx = qy = j = -1. */
typedef struct tgi_ao_rays { int qx, qy, j; tg_real kx, ky; tg_vec3 ray; } tgi_ao_rays;
#define TGI_AO_RAYS_NONE { -1, -1, -1, 0, 0, { 0, 0, 0 } }

/* The rays of full-resolution column qx and row qy in rays->kx, ky: their
 * divisions once a column and once a row of a march.  The view position
 * at depth z is then (kx z, ky z, z), tgi_ao_unproject's products (the
 * same bits). */
static inline void tgi_ao_rays_at(const tgi_view *v, tgi_ao_rays *rays, int qx, int qy)
{
    if (qx != rays->qx) { rays->qx = qx; rays->kx = tgi_ao_ray_x(v, qx); }
    if (qy != rays->qy) { rays->qy = qy; rays->ky = tgi_ao_ray_y(v, qy); }
}

/* The pixel of sample s of `steps` along screen direction (sdx, sdy) at
 * distance (s + jitter) r_px / steps (the view's pixels): 1 with *h the
 * view offset of its surface from pv (times 2^shift; at the full-resolution
 * pixel it stands for), *j its index and rays->ray its view ray per unit
 * of depth (tgi_ao_unproject at depth 1); 0 to skip it (within a pixel,
 * sky, or the last sample's pixel: the march's rays, starting
 * TGI_AO_RAYS_NONE); -1 past the screen's edge (the march ends). */
#if defined(__GNUC__)
__attribute__((always_inline))   /* in each march's loop: its results in registers, not stored through pointers */
#endif
static inline int tgi_ao_slice_point_at(const tgi_gview *g, const tgi_ao_slice_pixel *px, tg_real fx, tg_real fy,
                                        tg_vec3 *h, int *j, tgi_ao_rays *rays);
static inline int tgi_ao_slice_point(const tgi_gview *g, const tgi_ao_slice_pixel *px, int s, int steps,
                                     tg_real sdx, tg_real sdy, tg_vec3 *h, int *j, tgi_ao_rays *rays)
{
    /* (s + jitter) r_px >= 0 (jitter in [0, 1), r_px > 0), steps >= 1: a
     * quotient no larger than the product, tg_div's without its tests */
    tg_real t_px = tgi_div_nonneg(tg_mul(tg_add(tg_from_int(s), px->jitter), px->r_px), tg_from_int(steps));
    if (t_px < TG_ONE) return 0;
    return tgi_ao_slice_point_at(g, px, tg_add(tg_add(tg_from_int(px->x), TG_R(0.5f)), tg_mul(sdx, t_px)),
                                 tg_add(tg_add(tg_from_int(px->y), TG_R(0.5f)), tg_mul(sdy, t_px)), h, j, rays);
}
/* The pixel floor(a) of position a along a side of n pixels, -1 outside
 * (and for NaN).  In float, inside, a truncation, without tg_to_int's
 * tests for NaN, the int range and the sign (12% of a layered AO frame's
 * instructions). */
static inline int tgi_ao_pixel_of(tg_real a, int n)
{
#if TG_FIXED
    int q = tg_to_int(a);   /* a shift and a sign test in Q16.16 */
    return q >= 0 && q < n ? q : -1;
#else
    return a >= 0.0f && a < (float)n ? (int)a : -1;
#endif
}
/* The same for the sample at screen position (fx, fy) (the view's pixels),
 * a pixel or more from px's centre. */
static inline int tgi_ao_slice_point_at(const tgi_gview *g, const tgi_ao_slice_pixel *px, tg_real fx, tg_real fy,
                                        tg_vec3 *h, int *j, tgi_ao_rays *rays)
{
    int qx = tgi_ao_pixel_of(fx, g->width), qy = tgi_ao_pixel_of(fy, g->height);
    tg_real z;
    if (qx < 0 || qy < 0) return -1;
    *j = (int)tgi_gv_index(g, qx, qy);
    if (tgi_gv_is_sky(g, *j)) return 0;
    qx = qx * g->step + g->offset_x;   /* the full-resolution pixel it stands for */
    qy = qy * g->step + g->offset_y;
    z = tgi_gv_depth(g, *j);
    if (*j == rays->j) return 0;
    rays->j = *j;
    tgi_ao_rays_at(g->camera, rays, qx, qy);
    rays->ray = tg_v3(rays->kx, rays->ky, TG_ONE);
    *h = tgi_v3_sub(tg_v3(tg_mul(rays->kx, z), tg_mul(rays->ky, z), z), px->pv);
    if (px->shift) *h = tg_v3(tg_ldexp(h->x, px->shift), tg_ldexp(h->y, px->shift), tg_ldexp(h->z, px->shift));
    return 1;
}

/* The distance in pixels from pixel px's centre along screen direction
 * (sdx, sdy) (a unit vector) to the image's edge: where a march along it
 * leaves the screen. */
static inline tg_real tgi_ao_screen_reach(const tgi_gview *g, const tgi_ao_slice_pixel *px, tg_real sdx, tg_real sdy)
{
    tg_real cx = tg_add(tg_from_int(px->x), TG_R(0.5f)), cy = tg_add(tg_from_int(px->y), TG_R(0.5f));
    tg_real rx = TG_REAL_MAX, ry = TG_REAL_MAX;
    if (sdx > 0) rx = tg_div(tg_sub(tg_from_int(g->width), cx), sdx);
    else if (sdx < 0) rx = tg_div(cx, tg_neg(sdx));
    if (sdy > 0) ry = tg_div(tg_sub(tg_from_int(g->height), cy), sdy);
    else if (sdy < 0) ry = tg_div(cy, tg_neg(sdy));
    return tg_min(rx, ry);
}

/* Sample s as tgi_ao_slice_point gives it with the march's rays (so 0
 * too for a sample in the last one's pixel: marches whose samples only
 * raise a maximum or set bits lose nothing by it), also with *d2 = |h|^2,
 * and 0 when not within the radius or on or under the tangent plane (where
 * a horizon is clamped anyway). */
static inline int tgi_ao_slice_sample(const tgi_gview *g, const tgi_ao_slice_pixel *px, int s, int steps,
                                      tg_real sdx, tg_real sdy, tg_vec3 *h, tg_real *d2, int *j, tgi_ao_rays *rays)
{
    int got = tgi_ao_slice_point(g, px, s, steps, sdx, sdy, h, j, rays);
    if (got <= 0) return got;
    *d2 = tgi_v3_dot(*h, *h);
    if (*d2 >= px->r2 || *d2 <= 0) return 0;
    return tgi_v3_dot(*h, px->nv) > px->above;
}

/* The slice of screen direction (sdx, sdy) about the view vector vd
 * (Jimenez et al. 2016): its unit direction in view space, the length of
 * the normal nv projected into it, and that projection's angle gamma from
 * vd (positive toward dir), with its cosine and sine.  0 when the
 * projected normal is too short to have a direction. */
typedef struct tgi_ao_slice { tg_vec3 dir; tg_real len, gamma, cos_g, sin_g; } tgi_ao_slice;
static inline int tgi_ao_slice_frame(tg_vec3 nv, tg_vec3 vd, tg_real sdx, tg_real sdy, tgi_ao_slice *sl)
{
    tg_vec3 d3 = tg_v3(sdx, tg_neg(sdy), 0), axis, pn;
    tg_real cos_n;
    sl->dir = tgi_v3_normalize_or(tgi_v3_sub(d3, tgi_v3_scale(vd, tgi_v3_dot(d3, vd))), d3);
    axis = tgi_v3_cross(sl->dir, vd);
    pn = tgi_v3_sub(nv, tgi_v3_scale(axis, tgi_v3_dot(nv, axis)));   /* normal projected into the slice */
    sl->len = tgi_v3_length(pn);
    if (sl->len <= TG_R(0.0001f)) return 0;
    cos_n = tg_clamp(tg_div(tgi_v3_dot(pn, vd), sl->len), TG_R(-1.0f), TG_ONE);
    sl->gamma = tg_acos(cos_n);
    if (tgi_v3_dot(pn, sl->dir) < 0) sl->gamma = tg_neg(sl->gamma);
    sl->cos_g = tg_cos(sl->gamma);
    sl->sin_g = tg_sin(sl->gamma);
    return 1;
}

/* a(h): the inner integral of RTR eq. 11.18 from 0 to h (either sign of h),
 * for the slice's normal angle gamma. */
static inline tg_real tgi_ao_inner_arc(tg_real h, tg_real gamma, tg_real cos_g, tg_real sin_g)
{
    tg_real t = tg_sub(tg_add(cos_g, tg_mul(tg_ldexp(h, 1), sin_g)), tg_cos(tg_sub(tg_ldexp(h, 1), gamma)));
    return tg_ldexp(t, -2);
}

/* The cosine-weighted visible arc of slice sl (RTR eq. 11.18, inner
 * integral on both sides) under the horizons of cosines c1 (along the
 * slice's direction) and c0 (against it), -1 for none; *h1, *h0 get the
 * horizon angles from the view vector, clamped to the normal's hemisphere.
 * With no horizon the arc is the open one, cos g + g sin g. */
static inline tg_real tgi_ao_slice_arc(const tgi_ao_slice *sl, tg_real c1, tg_real c0, tg_real *h1, tg_real *h0)
{
    tg_real gamma = sl->gamma;
    *h1 = tg_add(gamma, tg_min(tg_sub(tg_acos(c1), gamma), TG_HALF_PI));            /* clamp to the normal's hemisphere */
    *h0 = tg_add(gamma, tg_max(tg_sub(tg_neg(tg_acos(c0)), gamma), tg_neg(TG_HALF_PI)));
    return tg_add(tgi_ao_inner_arc(*h0, gamma, sl->cos_g, sl->sin_g), tgi_ao_inner_arc(*h1, gamma, sl->cos_g, sl->sin_g));
}

/* What one slice adds before its weight (the length of the normal
 * projected into it, tgi_ao_slice's len): the cosine-weighted visible arc
 * and the same arc with open horizons, the bent-normal integrals along the
 * slice direction and along the view vector, and the near-field irradiance
 * gathered (unnormalised). */
typedef struct tgi_ao_slice_sum { tg_real vis, open, bs, bc; tg_vec3 near; } tgi_ao_slice_sum;

/* A technique's slice: march pixel px's slice sl of screen direction
 * (sdx, sdy) both ways and fill *sum (which starts at zero); `tech` is the
 * technique's own data (tgi_ao_slices). */
typedef void (*tgi_ao_slice_fn)(const void *tech, const tgi_gview *g, const tgi_ao_slice_pixel *px,
                                const tgi_ao_slice *sl, tg_real sdx, tg_real sdy, tgi_ao_slice_sum *sum);

/* A technique of view-vector slices: slices per pixel (tgi_ao_count), samples
 * per side, world radius, whether it writes the near field, its slice with
 * its data, and the 4x4 pattern of rotations and march offsets its pixels
 * take (pixel (x, y) the cell (x & 3) + 4 (y & 3); NULL: tgi_ao_rotations'). */
typedef struct tgi_ao_slices {
    int slices, steps;
    tg_real radius;
    int near;
    tgi_ao_slice_fn slice;
    const void *tech;
    const tgi_ao_rot *pattern;
} tgi_ao_slices;

/* Rows [y0, y1) of a technique of view-vector slices (Jimenez et al. 2016):
 * each pixel's slices at angles over pi turned by its 4x4 rotation, each
 * weighted by its projected normal's length; the outer integral as the
 * ratio of the visible to the open sums (exact 1 where nothing occludes:
 * GTAO on any plane, the bitmask with no bit set), the bent normal, and
 * with `near` the near field (pi / open times its sum).
 * Inline, so each technique's slice is called directly. */
static inline void tgi_ao_slices_rows(const tgi_ao_slices *t, const tgi_gview *g, const tgi_gresult *out,
                                      int y0, int y1)
{
    tg_vec3 dirs[TG_AO_MAX_SAMPLES];
    tgi_ao_rot own[16];
    const tgi_ao_rot *rot = t->pattern;
    int ns = tgi_ao_count(t->slices), k, x, y;
    int shift = tgi_ao_unit_shift(t->radius);
    tgi_ao_circle(TG_PI, ns, dirs);              /* slice angles over pi */
    if (!rot) {
        tgi_ao_rotations(own);
        rot = own;
    }
    for (y = y0; y < y1; y++)
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            const tgi_ao_rot *r = tgi_ao_rot_at(rot, x, y);
            tgi_ao_slice_pixel px;
            tg_real vis = 0, open = 0;
            tg_vec3 bent = tg_v3(0, 0, 0), e = tg_v3(0, 0, 0);
            if (!tgi_ao_slice_pixel_at(g, out, x, y, i, t->radius, t->steps, r->jitter, shift, &px)) continue;
            for (k = 0; k < ns; k++) {
                tg_vec3 sd = tgi_ao_rotate_z(dirs[k], r->c, r->s);
                tgi_ao_slice sl;
                tgi_ao_slice_sum sum = { 0, 0, 0, 0, { 0, 0, 0 } };
                if (!tgi_ao_slice_frame(px.nv, px.vd, sd.x, sd.y, &sl)) continue;
                t->slice(t->tech, g, &px, &sl, sd.x, sd.y, &sum);
                vis = tg_add(vis, tg_mul(sl.len, sum.vis));
                open = tg_add(open, tg_mul(sl.len, sum.open));
                bent = tgi_v3_add(bent, tgi_v3_scale(tgi_v3_add(tgi_v3_scale(sl.dir, sum.bs), tgi_v3_scale(px.vd, sum.bc)), sl.len));
                if (t->near) e = tgi_v3_add(e, tgi_v3_scale(sum.near, sl.len));
            }
            tgi_gr_set_ao(out, i, open > 0 ? tg_saturate(tg_div(vis, open)) : TG_ONE);
            tgi_ao_write_bent_view(g, out, i, bent);
            if (t->near && open > 0) {
                tg_real k_e = tg_div(TG_PI, open);
                tgi_gr_set_near(out, i, tg_v3(tg_mul(e.x, k_e), tg_mul(e.y, k_e), tg_mul(e.z, k_e)));
            }
        }
}

#endif
