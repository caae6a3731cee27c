/*
 * ao.h - what every ambient-occlusion / directional-occlusion technique of
 * tinygi shares: the pass input/output block (tg_ao_io), view-space helpers
 * written straight from the tg_view fields (no call into view.c per sample),
 * and the interreflection brightening of AO (RTR eq. 11.12-11.13).
 *
 * Every technique is a pass of the same shape
 *     void tg_<tech>_rows(const tg_<tech>_params *p, const tg_ao_io *io, int y0, int y1);
 * over rows [y0, y1), so the frame can treat them alike and a hosted
 * platform can split rows across threads.  Conventions of the outputs:
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
#include "../raster/view.h"

typedef struct tg_ao_io {
    int width, height;
    const tg_view *view;                       /* the camera that made the G-buffer */
    const tg_real *depth, *nx, *ny, *nz;       /* G-buffer: view z, world unit normal */
    const uint8_t *sky;                        /* 1 where no triangle was drawn */
    const tg_real *rad_r, *rad_g, *rad_b;      /* direct-light outgoing diffuse radiance; NULL if none */
    tg_real *ao, *bent_x, *bent_y, *bent_z;    /* ao in [0,1]; bent world unit, may be NULL */
    tg_real *cone;                             /* bent-cone half angle (radians), may be NULL */
    tg_real *near_r, *near_g, *near_b;         /* one-bounce irradiance, NULL when not computed */
} tg_ao_io;

/* A radius this large means "unlimited" (ambient occlusion rather than
 * obscurance, RTR sec. 11.3.2). */
#define TG_AO_INFINITE TG_REAL_MAX

/* ---- interreflection (RTR eq. 11.12-11.13) ----
 * k'_A = k_A / (1 - rho_ss (1 - k_A)): AO brightened as if the blocked
 * directions saw the shaded point's own outgoing radiance (Stewart-Langer).
 * Usable on any technique's ao, per colour channel (albedo = rho_ss). */
static inline tg_real tg_ao_interreflection(tg_real ao, tg_real albedo)
{
    tg_real k = tg_saturate(ao);
    tg_real den = tg_sub(TG_ONE, tg_mul(tg_saturate(albedo), tg_sub(TG_ONE, k))); /* RTR eq. 11.13 */
    if (den <= 0) return TG_ONE;            /* albedo 1 and k 0: the limit is 1 */
    return tg_saturate(tg_div(k, den));
}

/* ---- view-space helpers (view.h conventions: x right, y up, z forward) ---- */

/* View-space position of the centre of pixel (x, y) at view depth z. */
static inline tg_vec3 tg_ao_unproject(const tg_view *v, int x, int y, tg_real z)
{
    tg_real ndc_x = tg_ratio(2 * x + 1 - v->width, v->width);
    tg_real ndc_y = tg_ratio(v->height - 2 * y - 1, v->height);
    return tg_v3(tg_div(tg_mul(ndc_x, z), v->focal_x), tg_div(tg_mul(ndc_y, z), v->focal_y), z);
}

/* Pixel index of a view-space point, or -1 when it is behind the camera or
 * off screen.  Nearest pixel (the one whose square contains the projection). */
static inline int tg_ao_project_index(const tg_view *v, tg_vec3 p)
{
    tg_real ndc_x, ndc_y;
    int32_t px, py;
    if (p.z <= TG_R(0.001f)) return -1;
    ndc_x = tg_div(tg_mul(p.x, v->focal_x), p.z);
    ndc_y = tg_div(tg_mul(p.y, v->focal_y), p.z);
    if (ndc_x <= TG_R(-1.0f) || ndc_x >= TG_ONE || ndc_y <= TG_R(-1.0f) || ndc_y >= TG_ONE) return -1;
    px = tg_to_int(tg_ldexp(tg_mul(tg_add(ndc_x, TG_ONE), tg_from_int(v->width)), -1));
    py = tg_to_int(tg_ldexp(tg_mul(tg_sub(TG_ONE, ndc_y), tg_from_int(v->height)), -1));
    if (px < 0 || py < 0 || px >= v->width || py >= v->height) return -1;
    return (int)py * v->width + (int)px;
}

/* World direction -> view direction and back (the view basis is orthonormal). */
static inline tg_vec3 tg_ao_dir_to_view(const tg_view *v, tg_vec3 d)
{
    return tg_v3(tg_v3_dot(d, v->right), tg_v3_dot(d, v->up), tg_v3_dot(d, v->forward));
}
static inline tg_vec3 tg_ao_dir_to_world(const tg_view *v, tg_vec3 d)
{
    return tg_v3_add(tg_v3_add(tg_v3_scale(v->right, d.x), tg_v3_scale(v->up, d.y)),
                     tg_v3_scale(v->forward, d.z));
}

/* Write the "nothing computed" result for pixel i (sky, or no data). */
static inline void tg_ao_write_open(const tg_ao_io *io, int i)
{
    io->ao[i] = TG_ONE;
    if (io->bent_x) { io->bent_x[i] = io->nx[i]; io->bent_y[i] = io->ny[i]; io->bent_z[i] = io->nz[i]; }
    if (io->cone) io->cone[i] = TG_HALF_PI;
    if (io->near_r) { io->near_r[i] = 0; io->near_g[i] = 0; io->near_b[i] = 0; }
}

/* Store a bent normal given in view space (any length) as a world unit
 * vector; a zero vector falls back to the normal. */
static inline void tg_ao_write_bent_view(const tg_ao_io *io, int i, tg_vec3 bent_view)
{
    tg_vec3 n = tg_v3(io->nx[i], io->ny[i], io->nz[i]);
    tg_vec3 b;
    if (!io->bent_x) return;
    b = tg_v3_normalize_or(tg_ao_dir_to_world(io->view, bent_view), n);
    io->bent_x[i] = b.x; io->bent_y[i] = b.y; io->bent_z[i] = b.z;
}

#endif
