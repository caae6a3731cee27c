/* SPDX-License-Identifier: MIT */
/*
 * sampling.h - deterministic sample patterns shared by the AO techniques and
 * the ray-traced reference.  No rand(): every pattern is a closed-form
 * low-discrepancy set (Vogel / Fibonacci spirals) plus a 4x4 interleaved
 * per-pixel rotation and jitter (Keller-Heidrich interleaved sampling, as
 * used by Klehm sec. 4 and RTR sec. 11.3.6), identical in both number types
 * up to rounding.
 *
 * Local frames are z-up: (0, 0, 1) is the axis (the normal).
 */
#ifndef TG_AO_SAMPLING_H
#define TG_AO_SAMPLING_H

#include "../core/vec.h"

#define TG_AO_MAX_SAMPLES 64   /* per-pixel kernels of the screen-space passes */

/* A per-pixel count (samples, directions, slices) clamped to
 * 1..TG_AO_MAX_SAMPLES. */
static inline int tgi_ao_count(int n)
{
    return n < 1 ? 1 : n > TG_AO_MAX_SAMPLES ? TG_AO_MAX_SAMPLES : n;
}

/* n directions in the plane z = 0 at angles span k / n, k = 0..n-1 (HBAO's
 * directions over 2 pi, GTAO's slices over pi); tgi_ao_rotate_z turns one
 * by a pixel's rotation. */
void tgi_ao_circle(tg_real span, int n, tg_vec3 dirs[]);

/* Rotation (cos, sin) and a jitter in (0, 1) for one cell of the 4x4
 * interleaved pattern. */
typedef struct tgi_ao_rot { tg_real c, s, jitter; } tgi_ao_rot;

/* Fill the 16 cells: angles 2 pi (b + 1/2) / 16 by a 4x4 Bayer order b, so
 * neighbouring pixels get far-apart rotations. */
void tgi_ao_rotations(tgi_ao_rot rot[16]);
static inline const tgi_ao_rot *tgi_ao_rot_at(const tgi_ao_rot rot[16], int x, int y)
{
    return &rot[(x & 3) + ((y & 3) << 2)];
}

/* Fraction in [0, 1) of i times the golden ratio (the Fibonacci angle step). */
tg_real tgi_ao_golden_frac(int i);

/* Radical inverse of i in base 2 (van der Corput), in [0, 1), 16 bits. */
tg_real tgi_ao_radical2(int i);

/* i-th of n points of a Vogel spiral on the unit disk: radius
 * sqrt((i + 1/2) / n) (equal areas), angle 2 pi frac(i phi). */
void tgi_ao_disk(int i, int n, tg_real *x, tg_real *y);

/* i-th of n cosine-distributed hemisphere directions: the disk point lifted
 * to z = sqrt(1 - r^2) (Malley's method, RTR sec. 11.3.4). Unit. */
tg_vec3 tgi_ao_hemi_cosine(int i, int n);

/* i-th of n directions uniform in solid angle on the hemisphere
 * (z = (i + 1/2) / n, spiral angle). Unit. */
tg_vec3 tgi_ao_hemi_uniform(int i, int n);

/* Orthonormal basis (t, b) completing unit n (Duff et al. 2017, branchless
 * Frisvad). */
void tgi_ao_basis(tg_vec3 n, tg_vec3 *t, tg_vec3 *b);

/* Both helpers below take vectors of the unit ball (the kernels'
 * directions and offsets, a pixel's rotation, an orthonormal frame), every
 * component at most 2 in magnitude: their products are below 4 and their
 * sums below 12, so Q16.16 needs no saturation test (tgi_wide, real.h) and
 * gives the bits of the saturating tg_mul and tg_add, in fewer instructions
 * (about a third of a Q16.16 SSAO frame went to those tests); float is the
 * same expression in the same order. */
static inline tg_real tgi_ao_small_sum3(tg_real a0, tg_real b0, tg_real a1, tg_real b1, tg_real a2, tg_real b2)
{
    return (tg_real)(tgi_wide_mul(a0, b0) + tgi_wide_mul(a1, b1) + tgi_wide_mul(a2, b2));
}

/* Local (z-up) vector into the frame (t, b, n). */
static inline tg_vec3 tgi_ao_from_local(tg_vec3 l, tg_vec3 t, tg_vec3 b, tg_vec3 n)
{
    return tg_v3(tgi_ao_small_sum3(t.x, l.x, b.x, l.y, n.x, l.z), tgi_ao_small_sum3(t.y, l.x, b.y, l.y, n.y, l.z),
                 tgi_ao_small_sum3(t.z, l.x, b.z, l.y, n.z, l.z));
}

/* Rotate the local x, y of l by (c, s) about the z axis. */
static inline tg_vec3 tgi_ao_rotate_z(tg_vec3 l, tg_real c, tg_real s)
{
    return tg_v3((tg_real)(tgi_wide_mul(c, l.x) - tgi_wide_mul(s, l.y)), (tg_real)(tgi_wide_mul(s, l.x) + tgi_wide_mul(c, l.y)), l.z);
}

#endif
