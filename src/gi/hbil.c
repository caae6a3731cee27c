/* SPDX-License-Identifier: MIT */
/*
 * hbil.c - the HBIL horizon kernel (Mayaux 2018, sec. 1-2 and 3.3-3.4).
 *
 * For every pixel of an image (a 4x4 sub-image or the full-resolution
 * image, see hbil.h) and every slice: build the local camera frame, march
 * the depth buffer along +D and -D, keep the highest horizon on each side,
 * gather the near-field radiance each time a horizon rises, then integrate
 * AO, the bent normal and the cone aperture analytically in slice space.
 *
 * Units inside the march: the vector from the pixel to a sample is kept in
 * view space scaled by pixels_per_unit / (depth * step), i.e. in image
 * pixels at the pixel's depth.  Samples are then >= 1 unit away, squares stay
 * small for Q16.16 and nothing depends on the scene's scale.
 */
#include <string.h>
#include "hbil.h"
#include "interleave.h"
#include "../light/sh.h"
#include "../core/unit.h"

#define HBIL_PATTERN TGI_HBIL_PATTERN
/* Smallest n.w_o allowed: normals facing away from the camera are bent
 * toward it (an invalid G-buffer normal; the horizon frame needs n.w_o > 0). */
#define HBIL_MIN_NDOTV TG_R(0.0078125f)
/* Tie tolerance on cos|cos| of the horizon: a sample lying on the tangent
 * plane must not raise the horizon through rounding. */
#define HBIL_TIE TG_R(0.00024414f)
/* Depth is interpolated across the minor axis only between pixels whose
 * depths differ by less than this fraction of the nearer one: |za - zb| <
 * 3 min(za, zb), i.e. (both > 0) za < 4 zb and zb < 4 za, tested so. */
#define HBIL_LERP_MAX_RATIO TG_R(4.0f)
/* The 3D radius test works on lengths in the march's units (the view's
 * pixels at the pixel's depth), squared in tgi_wide (core/real.h): capped
 * at 2^14, twice the largest image side (TG_MAX_IMAGE_SIDE), so that a
 * sample anywhere on the screen is within it whenever the world radius
 * says so, and |d|^2 <= 3 2^28 fits tgi_wide's 64 bits in Q16.16.  (It was
 * 150, so that the square fitted tg_real: a radius wider than 150 of the
 * march's pixels was cut to 150, and the room-wide radius of
 * builtin:cornell lost its far walls at 1280x960, or at 320x240 without
 * the interleave: AO +0.14 too bright; test
 * full_resolution_radius_beyond_150_pixels.) */
#define HBIL_MAX_RADIUS_UNITS TG_R(16384.0f)
/* A march whose extent is longer than the image's smaller side over this
 * (a quarter: a room-wide radius, not an object's) refines its horizon on
 * more of the fine image's pixels (refine_fine). */
#define HBIL_LONG_REACH 4

/* Where refine_fine follows a surface from the pixel to the radius
 * (hbil_side.beyond), two neighbouring pixels of the fine image are taken
 * for one surface while their depths differ by at most this times z / ppu
 * (z the nearer's depth, ppu the image's pixels per unit at depth 1) a
 * pixel: a surface seen more than 6 degrees off edge-on (1 / tan 6 deg =
 * 9.5; the floor of builtin:columns seen at 7 degrees at the back wall's
 * foot is 8).  A larger step is a silhouette over what lies behind it
 * (the floor beside a sphere on builtin:spheres: 11.6 and more), which
 * one depth layer would take as infinitely thick: 6 to 14 give the same
 * AO within 0.001 on the four built-in scenes, 20 and more darken the
 * floor beside the spheres. */
#define HBIL_EDGE_SLOPE TG_R(9.5f)

/* A fine image at least this many times finer than the sub-image (the
 * full-resolution image under --gi-quarter's half-resolution sub-images)
 * takes every other pixel of refine_fine's span before the first sub-image
 * pixel, then the two beside the highest of them (refine_fine_sparse). */
#define HBIL_SPARSE_RATIO 8

/* The rare paths stay out of the march loop (register pressure).  The
 * gather is not rare (a third of the samples raise the horizon in a
 * corner): inlined (gather_rise), never cold (gcc would compile it for
 * size, its Q16.16 arithmetic as calls). */
#if defined(__GNUC__)
#define HBIL_COLD __attribute__((noinline, cold))
#define HBIL_NOINLINE __attribute__((noinline))
#define HBIL_INLINE inline __attribute__((always_inline))
#else
#define HBIL_COLD
#define HBIL_NOINLINE
#define HBIL_INLINE inline
#endif

/* Whether the kernel writes bent normals and cone apertures: never in a
 * build with TG_NO_BENT_NORMALS (tinygi.h "FEATURE SWITCHES"; the plan
 * refuses what reads them), whose code is then left out. */
#define HAS_BENT(out) (!TG_NO_BENT_NORMALS && tgi_gr_has_bent(out))
#define HAS_CONE(out) (!TG_NO_BENT_NORMALS && tgi_gr_has_cone(out))

/* Whether the kernel gathers the near field (ctx_init): never in a build
 * with TG_NO_COLOR (tinygi.h "FEATURE SWITCHES"; the plan refuses the near
 * effect there), whose gather is then left out. */
#if TG_NO_COLOR
#define NEAR_FIELD(c) 0
#else
#define NEAR_FIELD(c) ((c)->near_field)
#endif

static const uint8_t slice_rank4[4][4] = {
    { 0, 8, 2, 10 }, { 12, 4, 14, 6 }, { 3, 11, 1, 9 }, { 15, 7, 13, 5 }
};

/* The rotations' order: 0..7 bit-reversed, so any run of consecutive
 * frames spreads out (rotation_offset, tgi_hbil_block_jitter). */
static const uint8_t rotation_rank[8] = { 0, 4, 2, 6, 1, 5, 3, 7 };

/* Where in its stratum rotation r samples, in [0, 1): the eighths in
 * rotation_rank's order; the march offsets use the order shifted by half,
 * apart from the angles'. */
static tg_real rotation_offset(int r)
{
    return tg_ratio(2 * rotation_rank[r & 7] + 1, 2 * TG_HBIL_ROTATIONS);
}

tg_real tgi_hbil_slice_phi0(int i, int j, int slices, int rot)
{
    tg_real rank = tg_add(tg_from_int(slice_rank4[j & 3][i & 3]), rotation_offset(rot));
    if (slices < 1) slices = 1;
    /* stratified over [0, pi / S): the 16 sub-images x S slices cover [0, pi) */
    return tg_mul(tg_div(TG_PI, tg_from_int(slices * 16)), rank);
}

tg_real tgi_hbil_step_jitter(int i, int j, int rot)
{
    /* the slice angles' ranks transposed: no sub-image pairs its slice rank with the same jitter rank */
    tg_real rank = tg_add(tg_from_int(slice_rank4[i & 3][j & 3]), rotation_offset(rot + TG_HBIL_ROTATIONS / 2));
    return tg_mul(rank, TG_R(1.0f / 16.0f));
}

int tgi_hbil_pattern(int x, int y, int rot)
{
    /* t: the top 2 bits of frac((x >> 2) / golden ratio + rot / 8), a
     * Weyl sequence: neighbouring block columns' shifts spread evenly
     * (hashed shifts measured worse), and over the 8 rotations each column
     * takes each shift twice */
    uint32_t h = (uint32_t)(x >> 2) * 0x9E3779B1u + ((uint32_t)rot << 29);
    return (int)(((uint32_t)y + (h >> 30)) & 3u) * 4 + (x & 3);
}

void tgi_hbil_defaults(tgi_hbil_params *p)
{
    memset(p, 0, sizeof *p);
    p->slices = TG_DEFAULT_SLICES;
    p->samples = TG_DEFAULT_SAMPLES;
    p->radius = TG_ONE;
    p->rejection_a = 0;
    p->rejection_b = TG_R(0.2f);
}

/* Q16.16 tests wide_far only past a bound on q (march_q_near); compiling
 * for size (TG_OUTLINE_HELPERS) keeps the one test, and not the bound. */
#define HBIL_Q_NEAR TGI_Q16_WIDE

/* The call's last normalised sender normal kept (rejection_ramp_oct), not
 * compiling for size */
#define HBIL_UNIT_MEMO (!TG_OUTLINE_HELPERS)
#if HBIL_UNIT_MEMO
/* An octahedral direction and its unit vector (rejection_ramp_oct) */
typedef struct hbil_unit_memo {
    tgi_oct_dir d;
    tg_vec3 n;
} hbil_unit_memo;
/* A memo that holds no direction yet (an octahedral component is below 2^15 in size). */
static inline void unit_memo_start(hbil_unit_memo *m) { m->d.x = INT32_MIN; }
#endif

/* rejection_weight_memo: gather_rise's rejection weight with the last
 * sender normal's products kept; not compiling for size.  (Float took it
 * at first with the ramp's normalisation inlined: cornell 160x120, 2
 * frames, 520.18M -> 516.92M but columns 214.29M -> 214.79M; with that out
 * of line, rejection_ramp_unit then, rejection_ramp_oct now, it pays in
 * both.) */
#define HBIL_REJECT_MEMO (!TG_OUTLINE_HELPERS && !TG_WIDE_STORAGE && !TG_NO_COLOR)
/* A sender normal by its stored code (key: reject_memo_key), its
 * octahedral direction d, |d|^2 and d's dot products with the camera's
 * right, up and forward axes (rejection_weight_m's tests) */
typedef struct hbil_reject_memo {
    uint32_t key;
    tgi_oct_dir d;
#if TG_FIXED
    /* n2 last: after d, gcc 12 stored d and n2 at a fill as one vector (SSE2:
     * ~4 instructions more than four scalar stores; cornell 160x120 Q16.16
     * 644.27M -> 643.67M) */
    int64_t nr, nu, nf;
    int32_t n2;
#else
    float n2, nr, nu, nf;
#endif
} hbil_reject_memo;
#if HBIL_REJECT_MEMO
/* A memo that holds no normal yet (no key is all ones: reject_memo_key) */
static inline void reject_memo_start(hbil_reject_memo *m) { m->key = UINT32_MAX; }
/* The key of sender si of image g: its stored code (tgi_gv_normal_word),
 * below 2^22 (TGI_NORMAL_MASK) with materials, and 2^22 plus the 16-bit
 * code without (tgi_gb_has_material: the 8-bit octahedral pair), so equal
 * keys are equal codes of one storage form, which tgi_gv_normal_dir
 * decodes alike in any image.  (Keyed by the image and the code, the
 * memo missed at every change between the sub-image's senders and the
 * fine image's, refine_fine's gather and the march's after it.) */
static inline uint32_t reject_memo_key(const tgi_gview *g, size_t si)
{
    return tgi_gv_normal_word(g, si) | (uint32_t)!tgi_gb_has_material(&g->store) << TGI_MATERIAL_SHIFT;
}
#endif

/* ---- per-call constants ---- */
typedef struct hbil_ctx {
    const tgi_hbil_params *p;
    const tgi_gview *g;         /* what the kernel reads */
    const tgi_view *v;          /* the full-resolution camera */
    const tgi_rgb *rad;         /* the near field's source radiance */
    const tgi_gresult *out;
    int slices, samples, step, full_w, full_h;
    tg_real ppu, inv_ppu, inv_step, pi_over_s;
    tg_real p0z;                /* ppu / step: the z of P0 in the march's units (march_side) */
    const tgi_hbil_dirs *dirs;  /* per pattern cell: slice directions, step_jitter (p->dirs, or tgi_hbil_rows' local) */
    tg_real rejection_a, rejection_b;
#if !TG_OUTLINE_HELPERS
    tg_real ramp_d;             /* b - a where a < b and it fits (ramp_init), else 0 */
#endif
    int reject_fast;            /* rejection_weight's tests without the normalisation apply */
#if HBIL_UNIT_MEMO
    hbil_unit_memo *memo;       /* the call's last normalised sender normal (rejection_ramp_oct; tgi_hbil_rows' local) */
#endif
#if HBIL_REJECT_MEMO
    hbil_reject_memo *reject_memo;  /* the call's last sender normals in rejection_weight_memo, one a slice's side (2 TG_MAX_SLICES: tgi_hbil_rows' local) */
#endif
    tgi_wide reject_lo2, reject_hi2;  /* x|x| of the ramp's ends moved out by HBIL_REJECT_MARGIN */
    int near_field;
    const tgi_gview *fine;      /* tgi_hbil_params.fine; the sub-image is (fine_i, fine_j) in it */
    const tgi_rgb *fine_rad;    /* its radiance, or NULL */
    int fine_i, fine_j;         /* pixel (x, y) is fine's (x fine_ratio + fine_i, y fine_ratio + fine_j) */
    int fine_ratio;             /* 4, or 8 for a sub-image of --gi-quarter's half-res image */
#if !TG_NO_GI_QUARTER
    int pattern_shift;          /* the image the pattern tiles has pixels of 2^pattern_shift full-resolution ones */
#define PATTERN_SHIFT(c) ((c)->pattern_shift)
#else
#define PATTERN_SHIFT(c) 0
#endif
    tg_real inv_fine_ratio;
    tg_real long_reach;         /* HBIL_LONG_REACH in the march's units (refine_fine) */
    tg_real fine_edge;          /* HBIL_EDGE_SLOPE / ppu times the fine image's step (refine_fine) */
#if HBIL_Q_NEAR
    tg_real q_near;             /* |q| <= q_near: no offset component beyond HBIL_FAR (march_q_near) */
#endif
} hbil_ctx;

/* The side's gathered sums (hbil_side.er, eg, eb).  Q16.16 with packed
 * storage, not compiling for size (HBIL_WIDE_SUMS): int64, unsaturated,
 * the sums of gather_rise's rounded products l de >= 0 (each below 5
 * 2^31 raw, l <= TG_REAL_MAX and de < 5: near_sum_pos), fewer than 2^16
 * a side (a rise is a sample: the march's, its runs' and refine_fine's,
 * each a pixel of an image side below 2^14, or one a call), so below
 * 2^51.  Saturated once, in slice_run: for terms >= 0, min(min(x, M) +
 * y, M) = min(x + y, M) (either x >= M, both M, or the same sum), so
 * saturating the whole sum gives the running saturated sums' value
 * (near_sum_pos a rise, near_sum3_pos a slice) without a test a channel
 * a rise. */
#define HBIL_WIDE_SUMS (TGI_Q16_WIDE && !TG_WIDE_STORAGE)
#if HBIL_WIDE_SUMS
typedef int64_t hbil_esum;
#else
typedef tg_real hbil_esum;
#endif

/* One side of one slice: the horizon and the radiance gathered under it. */
typedef struct hbil_side {
    tg_real h, hs;          /* horizon cosine from w_o and h|h| */
    tg_real p_old;          /* P(theta) at the current horizon (near field) */
    int peak_a;             /* major coordinate of the sample that set the horizon; -1: none */
    int beyond;             /* the march's first sample lay beyond the 3D radius (refine_fine) */
    tg_real q;              /* Q(theta) at the current horizon (near field: kept by gather_rise) */
#if HBIL_REJECT_MEMO
    hbil_reject_memo *reject_memo;  /* the last sender normal gathered on this side of this slice, any pixel (slice_run) */
#endif
#if HBIL_WIDE_SUMS
    /* each sum apart from the next: adjacent, gcc 12 vectorised two of
     * gather_rise's three updates (SSE2: moves into and out of the vector
     * registers, ~4 instructions more a rise than three scalar adds;
     * cornell 160x120 Q16.16 646.22M -> 644.27M) */
    hbil_esum er; tg_real lr;   /* er, eg, eb: gathered sum of L * dE (eq. 18); lr, lg, lb: running radiance (sec. 3.4) */
    hbil_esum eg; tg_real lg;
    hbil_esum eb; tg_real lb;
#else
    tg_real lr, lg, lb;     /* running radiance of sec. 3.4 */
    hbil_esum er, eg, eb;   /* gathered sum of L * dE (eq. 18; HBIL_WIDE_SUMS) */
#endif
} hbil_side;

/* The pixel: its frame and normal in view space. */
typedef struct hbil_pixel {
    int x, y;
    tg_real X, Y;           /* full-res screen position from the centre, pixels, y up */
    tg_real z, inv_z;
    tg_vec3 wo, wx, wy;     /* local camera frame, sec. 1.1 */
    tg_vec3 n;              /* view-space normal with n.w_o >= HBIL_MIN_NDOTV */
    tg_vec3 nw;             /* the G-buffer's normal (world space), decoded once (pixel_run's bent normal; not compiling for size) */
#if TGI_REUSE_NORMAL
    tgi_normal_memo nm;     /* the stored normal code decoded last (nw its normal), nm.n its view-space n before pixel_setup bends it */
#endif
#if TGI_Q16_WIDE
    tg_real kx, ky;         /* X / ppu, Y / ppu (slice_screen_dir; Q16.16 not compiling for size) */
#endif
#if !TG_OUTLINE_HELPERS
    int k_small;            /* |X / ppu|, |Y / ppu| < 32 (pixel_setup, slice_screen_dir) */
#endif
    tg_real ndv;            /* n.w_o (every slice's n'_y) */
    tgi_wide radius_units2; /* (3D radius in image pixels at depth z)^2 */
    tg_real reach;          /* march extent, image pixels */
    tg_real jitter;         /* the samples start this fraction of a step nearer */
} hbil_pixel;

/* Slice-space normal n' = (n.D, n.w_o) (eq. 2) and the integrals. */
typedef struct hbil_slice {
    tg_vec3 d;              /* D(phi) in view space */
    tg_real nx, ny;         /* n' */
} hbil_slice;

/* n / 2 for an n below 2^15 in magnitude, tg_ratio(n, 2): in Q16.16 n
 * 2^15 exactly (tg_ratio adds +-1 to the even n 2^16 and halves it
 * truncating: the same), without its division and saturation test; the
 * builds for size and float call tg_ratio as before. */
static inline tg_real half_small(int n)
{
#if TGI_Q16_WIDE
    return (tg_real)n * 32768;
#else
    return tg_ratio(n, 2);
#endif
}

/* Full-res screen position (pixels from the centre, y up) of pixel x or
 * row y of the view g (the kernel's image or the fine one; x, y within it
 * or one pixel before it, sample_depth_edge's b0): the doubled position is
 * below 2 TG_MAX_IMAGE_SIDE + 1 = 2^14 + 1 in magnitude (half_small). */
static tg_real view_x(const hbil_ctx *c, const tgi_gview *g, int x)
{
    int X2 = 2 * (x * g->step + g->offset_x) + 1 - c->full_w;
    return half_small(X2);
}
static tg_real view_y(const hbil_ctx *c, const tgi_gview *g, int y)
{
    int Y2 = c->full_h - 2 * (y * g->step + g->offset_y) - 1;
    return half_small(Y2);
}
static tg_real full_x(const hbil_ctx *c, int x) { return view_x(c, c->g, x); }
static tg_real full_y(const hbil_ctx *c, int y) { return view_y(c, c->g, y); }

/* Q(theta) = (theta - sin(theta) cos(theta)) / 2 for the front side, from
 * c = cos(theta): with a = |c|, Q = sqrt(1 - a) g(a), g analytic on [0, 1]
 * (acos(a) = sqrt(1 - a) p(a) and a sin = sqrt(1 - a) a sqrt(1 + a)), so
 * one square root and a degree-6 polynomial (Chebyshev fit of g, |error|
 * <= 6e-8 on [0, 1]) give theta and its sine term together where acos and
 * sin each took a square root; Q(-a) = pi/2 - Q(a).  The error against
 * libm is measured by tests/test_hbil.c (hbil_slice_q_accuracy). */
static const tg_real slice_q_fit[7] = {
    TG_R(0.7853982160f), TG_R(-0.6073061101f), TG_R(-0.2053898813f), TG_R(0.0365542198f),
    TG_R(-0.0126462398f), TG_R(0.0041426349f), TG_R(-0.0007528721f)
};
/* Products and sums whose results are bounded (each use says why) without
 * the saturation test (tgi_wide, core/real.h): tg_mul, tg_add and tg_sub
 * would not saturate there, so these give their results.  In the slice
 * integrals every operand is a cosine, a sine, an angle in [-pi, pi], a fit
 * coefficient or a partial sum of the fit (all below 4 in magnitude). */
static tg_real small_mul(tg_real a, tg_real b) { return (tg_real)tgi_wide_mul(a, b); }
static tg_real small_add(tg_real a, tg_real b) { return (tg_real)((tgi_wide)a + b); }
static tg_real small_sub(tg_real a, tg_real b) { return (tg_real)((tgi_wide)a - b); }
/* an integer below 2^15 in magnitude (an image coordinate or offset) */
static tg_real small_from_int(int i)
{
#if TG_FIXED
    return (tg_real)((tgi_wide)i * TG_ONE);
#else
    return (tg_real)i;
#endif
}
/* small_mul(a, small_from_int(i)) where the product a i is small (each use
 * says why): in Q16.16 the raw product a i 2^16 is a multiple of 2^16, so
 * its rounding shift is exact and the result is the integer product a i,
 * without the rounding; float multiplies by (float)i as before. */
/* tgi_v3_scale, tgi_v3_add and tgi_v3_dot of small vectors (each use says
 * why): the same products, sums and one rounding of the dot's exact sum,
 * without the saturation tests (and the dot's test past 2^62).  Float
 * keeps the calls it had (macros, the same source: the same code). */
#if TG_FIXED
static inline tg_real small_mul_int(tg_real a, int i) { return (tg_real)((tgi_wide)a * i); }
static inline tg_vec3 small_v3_scale(tg_vec3 a, tg_real s) { return tg_v3(small_mul(a.x, s), small_mul(a.y, s), small_mul(a.z, s)); }
static inline tg_vec3 small_v3_add(tg_vec3 a, tg_vec3 b) { return tg_v3(small_add(a.x, b.x), small_add(a.y, b.y), small_add(a.z, b.z)); }
static inline tg_real small_dot(tg_vec3 a, tg_vec3 b) { return (tg_real)tgi_wide_dot(a.x, a.y, a.z, b.x, b.y, b.z); }
#else
#define small_mul_int(a, i) small_mul(a, small_from_int(i))
#define small_v3_scale tgi_v3_scale
#define small_v3_add tgi_v3_add
#define small_dot tgi_v3_dot
#endif
/* small_dot off the march's common path (sample_depth_edge,
 * rejection_ramp); compiling for size the library's tgi_v3_dot, whose
 * calls are shorter (24 bytes in the AO-only program) */
#if TG_OUTLINE_HELPERS
#define small_dot_rare tgi_v3_dot
#else
#define small_dot_rare small_dot
#endif

/* sqrt(x) for x in [0, 1] (the fit's sqrt(1 - a)): in float the two-step
 * reciprocal square root (core/real.h, rel. error < 5e-6) times x and one
 * Newton step on the residual (as tg_sqrt ends), without tg_sqrt's third
 * step and range tests; Q16.16 gives tg_sqrt's result, exactly rounded,
 * from a line table of its own (below), tg_sqrt itself compiling for
 * size.  gcc keeps it a function of 26 instructions; forced inline into
 * the march it had cost +6.5M instructions in a Q16.16 cornell 320x240
 * frame pair, and since horizon_cos's rounding with one shift it saves
 * 4.1M there (3490.8M -> 3486.6M; 160x120: -0.12%): inline in Q16.16
 * (HBIL_SQRT_INLINE), a call in float (inline +0.05% of its frame). */
#if TGI_Q16_WIDE
/* 256 sqrt(u) in Q14 for u in [2^15, 2^17), on 192 intervals of 2^9: the
 * line { value at the interval's start, slope } through the chord moved up
 * by half its largest distance from the curve (minimax), rounded to
 * integers; within 0.19 of 256 sqrt(u) 2^-k at every u 4^k below (the
 * values unit_sqrt takes, every one tried: tests/test_hbil.c
 * hbil_unit_sqrt_exact). */
static const uint32_t unit_sqrt_line[192][2] = {
    { 759252977u, 11540u }, { 765161562u, 11452u }, { 771024871u, 11366u }, { 776843928u, 11281u },
    { 782619721u, 11198u }, { 788353200u, 11118u }, { 794045283u, 11038u }, { 799696852u, 10961u },
    { 805308761u, 10885u }, { 810881833u, 10811u }, { 816416864u, 10738u }, { 821914622u, 10667u },
    { 827375850u, 10597u }, { 832801266u, 10528u }, { 838191567u, 10461u }, { 843547424u, 10395u },
    { 848869491u, 10330u }, { 854158398u, 10266u }, { 859414759u, 10204u }, { 864639165u, 10143u },
    { 869832194u, 10083u }, { 874994404u, 10023u }, { 880126336u, 9965u }, { 885228519u, 9908u },
    { 890301462u, 9852u }, { 895345664u, 9797u }, { 900361607u, 9743u }, { 905349760u, 9689u },
    { 910310581u, 9637u }, { 915244515u, 9585u }, { 920151992u, 9534u }, { 925033436u, 9484u },
    { 929889255u, 9435u }, { 934719849u, 9386u }, { 939525607u, 9339u }, { 944306908u, 9292u },
    { 949064122u, 9245u }, { 953797610u, 9200u }, { 958507722u, 9155u }, { 963194802u, 9110u },
    { 967859184u, 9067u }, { 972501194u, 9023u }, { 977121153u, 8981u }, { 981719370u, 8939u },
    { 986296151u, 8898u }, { 990851792u, 8857u }, { 995386583u, 8817u }, { 999900808u, 8777u },
    { 1004394745u, 8738u }, { 1008868664u, 8700u }, { 1013322830u, 8662u }, { 1017757504u, 8624u },
    { 1022172938u, 8587u }, { 1026569381u, 8550u }, { 1030947076u, 8514u }, { 1035306260u, 8478u },
    { 1039647167u, 8443u }, { 1043970025u, 8408u }, { 1048275056u, 8374u }, { 1052562480u, 8340u },
    { 1056832510u, 8306u }, { 1061085358u, 8273u }, { 1065321228u, 8240u }, { 1069540322u, 8208u },
    { 1073742838u, 8176u }, { 1077928970u, 8144u }, { 1082098908u, 8113u }, { 1086252839u, 8082u },
    { 1090390945u, 8052u }, { 1094513407u, 8022u }, { 1098620399u, 7992u }, { 1102712095u, 7962u },
    { 1106788665u, 7933u }, { 1110850275u, 7904u }, { 1114897088u, 7875u }, { 1118929266u, 7847u },
    { 1122946966u, 7819u }, { 1126950342u, 7791u }, { 1130939547u, 7764u }, { 1134914730u, 7737u },
    { 1138876038u, 7710u }, { 1142823615u, 7684u }, { 1146757604u, 7657u }, { 1150678143u, 7631u },
    { 1154585369u, 7606u }, { 1158479418u, 7580u }, { 1162360421u, 7555u }, { 1166228509u, 7530u },
    { 1170083810u, 7505u }, { 1173926450u, 7481u }, { 1177756553u, 7456u }, { 1181574240u, 7432u },
    { 1185379632u, 7409u }, { 1189172847u, 7385u }, { 1192954001u, 7362u }, { 1196723208u, 7339u },
    { 1200480581u, 7316u }, { 1204226230u, 7293u }, { 1207960265u, 7271u }, { 1211682793u, 7248u },
    { 1215393920u, 7226u }, { 1219093749u, 7204u }, { 1222782384u, 7183u }, { 1226459925u, 7161u },
    { 1230126472u, 7140u }, { 1233782122u, 7119u }, { 1237426974u, 7098u }, { 1241061121u, 7077u },
    { 1244684657u, 7057u }, { 1248297675u, 7036u }, { 1251900266u, 7016u }, { 1255492519u, 6996u },
    { 1259074523u, 6976u }, { 1262646366u, 6957u }, { 1266208133u, 6937u }, { 1269759909u, 6918u },
    { 1273301778u, 6899u }, { 1276833822u, 6880u }, { 1280356122u, 6861u }, { 1283868759u, 6842u },
    { 1287371811u, 6823u }, { 1290865358u, 6805u }, { 1294349475u, 6787u }, { 1297824238u, 6769u },
    { 1301289724u, 6751u }, { 1304746005u, 6733u }, { 1308193154u, 6715u }, { 1311631244u, 6697u },
    { 1315060345u, 6680u }, { 1318480528u, 6663u }, { 1321891862u, 6646u }, { 1325294415u, 6629u },
    { 1328688255u, 6612u }, { 1332073448u, 6595u }, { 1335450060u, 6578u }, { 1338818156u, 6562u },
    { 1342177800u, 6545u }, { 1345529056u, 6529u }, { 1348871985u, 6513u }, { 1352206650u, 6497u },
    { 1355533112u, 6481u }, { 1358851430u, 6465u }, { 1362161665u, 6450u }, { 1365463876u, 6434u },
    { 1368758119u, 6419u }, { 1372044453u, 6403u }, { 1375322934u, 6388u }, { 1378593619u, 6373u },
    { 1381856563u, 6358u }, { 1385111820u, 6343u }, { 1388359444u, 6328u }, { 1391599490u, 6314u },
    { 1394832009u, 6299u }, { 1398057054u, 6284u }, { 1401274677u, 6270u }, { 1404484928u, 6256u },
    { 1407687858u, 6242u }, { 1410883517u, 6227u }, { 1414071955u, 6213u }, { 1417253219u, 6200u },
    { 1420427358u, 6186u }, { 1423594421u, 6172u }, { 1426754453u, 6158u }, { 1429907501u, 6145u },
    { 1433053612u, 6131u }, { 1436192832u, 6118u }, { 1439325204u, 6105u }, { 1442450775u, 6091u },
    { 1445569587u, 6078u }, { 1448681685u, 6065u }, { 1451787112u, 6052u }, { 1454885911u, 6039u },
    { 1457978123u, 6027u }, { 1461063791u, 6014u }, { 1464142956u, 6001u }, { 1467215659u, 5989u },
    { 1470281941u, 5976u }, { 1473341841u, 5964u }, { 1476395399u, 5952u }, { 1479442655u, 5939u },
    { 1482483647u, 5927u }, { 1485518414u, 5915u }, { 1488546994u, 5903u }, { 1491569424u, 5891u },
    { 1494585743u, 5879u }, { 1497595986u, 5868u }, { 1500600191u, 5856u }, { 1503598393u, 5844u },
    { 1506590628u, 5833u }, { 1509576933u, 5821u }, { 1512557341u, 5810u }, { 1515531889u, 5798u }
};
#endif
#if TGI_Q16_WIDE
#define HBIL_SQRT_INLINE HBIL_INLINE
#else
#define HBIL_SQRT_INLINE
#endif
static HBIL_SQRT_INLINE tg_real unit_sqrt(tg_real x)
{
#if TGI_Q16_WIDE
    /* x = u 2^-16, u in [0, 2^16]: sqrt(x) raw is R, the nearest integer
     * to sqrt(v), v = u 2^16 (tg_sqrt's).  u 4^k in [2^15, 2^17) takes
     * the line's a = 256 sqrt(u 4^k) 2^-k within 0.19 (< 1/2) of sqrt(v),
     * so r = floor(a) is R or R - 1: R = r + 1 exactly when sqrt(v) >= r
     * + 1/2, v > r^2 + r (integers).  32-bit integers but the last test. */
    const uint32_t u = (uint32_t)x;
    uint32_t uk, a;
    int k;
    const uint32_t *c;
    if (x <= 0) return 0;
    k = (tgi_clz32_nz(u) - 15) >> 1;                /* 0..8: 17 - bit length, u > 0 */
    uk = u << 2 * k;                                 /* [2^15, 2^17) */
    c = unit_sqrt_line[(uk >> 9) - 64];
    a = c[0] + c[1] * (uk & 511u);                   /* 256 sqrt(uk) in Q14, < 2^31 */
    a >>= 14 + k;                                    /* floor(a): R or R - 1 */
    return (tg_real)(a + ((uint64_t)a * a + a < (uint64_t)u << 16));
#elif TG_FIXED
    return tg_sqrt(x);
#else
    float r, s;
    if (!(x > 0.0f)) return 0.0f;
    r = tgi_rsqrt_fast(x);
    s = x * r;
    return s + 0.5f * r * (x - s * s);
#endif
}

static inline tg_real slice_q_eval(tg_real c)
{
    const tg_real *k = slice_q_fit;
    /* |c| as tgi_abs_fast (raster/pack.h; float: +0 at c = -0, whose
     * products k a are zeros added to the nonzero k[5] .. k[0], and 1 - a
     * = 1 either way; a NaN fails a < 1 either way: a = 1) */
    tg_real a = tg_min(tgi_abs_fast(c), TG_ONE), p, t;
#if TGI_Q16_WIDE
    /* Horner as below, each step small_add(small_mul(p, a), k) with the
     * constant in the rounding's offset: floor((p a + 2^15) / 2^16) + k =
     * floor((p a + 2^15 + k 2^16) / 2^16), the same integer (|p| < 0.8,
     * a in [0, 1]: every partial sum fits tg_real, so small_add's and the
     * casts' truncations changed nothing); p stays in 64 bits (two
     * instructions fewer a step: Q16.16 cornell 160x120, 3 frames, -0.54%).
     * The first product in 32 bits, |k[6] a| <= 49 2^16 < 2^31 (k[6] raw
     * -49, a <= 2^16), the same integer: gcc 12 takes it as one imul where
     * it built the 64-bit one of shifts and subtractions (5 instructions;
     * cornell 160x120, 2 frames, Q16.16 642.19M -> 640.03M) */
    int64_t pw = ((int64_t)(k[6] * a) + ((int64_t)k[5] * 65536 + 32768)) >> 16;
    pw = (pw * a + ((int64_t)k[4] * 65536 + 32768)) >> 16;
    pw = (pw * a + ((int64_t)k[3] * 65536 + 32768)) >> 16;
    pw = (pw * a + ((int64_t)k[2] * 65536 + 32768)) >> 16;
    pw = (pw * a + ((int64_t)k[1] * 65536 + 32768)) >> 16;
    pw = (pw * a + ((int64_t)k[0] * 65536 + 32768)) >> 16;
    p = (tg_real)pw;
#else
    /* Horner, written out (gcc keeps a loop as a loop); |p| < 0.8 */
    p = small_add(small_mul(k[6], a), k[5]);
    p = small_add(small_mul(p, a), k[4]);
    p = small_add(small_mul(p, a), k[3]);
    p = small_add(small_mul(p, a), k[2]);
    p = small_add(small_mul(p, a), k[1]);
    p = small_add(small_mul(p, a), k[0]);
#endif
    t = small_mul(unit_sqrt(small_sub(TG_ONE, a)), p);
    return c < 0 ? small_sub(TG_HALF_PI, t) : t;
}
tg_real tgi_hbil_slice_q(tg_real c) { return slice_q_eval(c); }
tg_real tgi_hbil_unit_sqrt(tg_real x) { return unit_sqrt(x); }

/* sin(theta)^2 / 2 and (theta - sin cos) / 2 from cos(theta) and the side
 * (|c| <= 1, so the operands are small: see small_mul); on the back side
 * theta and sin change sign, and Q with them. */
static tg_real slice_R(tg_real c)
{
    return small_mul(TG_R(0.5f), small_sub(TG_ONE, small_mul(c, c)));
}
static tg_real slice_Q(tg_real c, int side)
{
#if TG_OUTLINE_HELPERS
    tg_real q = tgi_hbil_slice_q(c);   /* one copy when compiling for size */
#else
    tg_real q = slice_q_eval(c);
#endif
#if TGI_Q16_WIDE
    /* side is +1 or -1 and |q| < 2 (raw below 2^17): q side is -q or q
     * exactly, one multiply for the march's side, a variable there (the
     * test and the select took 4 instructions a rise: cornell 160x120
     * Q16.16 643.20M -> 642.19M) */
    return q * side;
#else
    return side < 0 ? tg_neg(q) : q;
#endif
}
/* tg_rsqrt(x) for x known positive, normal and finite (each use says
 * why): in float tg_rsqrt's seed and three Newton steps, the same
 * operations, without its range tests (x > 0, x <= TG_REAL_MAX, x below
 * the smallest normal) and its scale (1 for a normal x: a product that
 * changes no bit); cornell 160x120, 2 frames, float 529.04M -> 528.46M.
 * Q16.16 not compiling for size: tgi_rsqrt_pos, tg_rsqrt's steps inline
 * for x > 0 (real.h), at every call of the kernel's (x >= 1 in
 * pixel_setup, x >= 0.0001 in slice_screen_dir, x > 2^-15 in slice_run);
 * compiling for size tg_rsqrt itself. */
#if TGI_Q16_WIDE
#define rsqrt_in_range tgi_rsqrt_pos
#elif TG_FIXED || TG_OUTLINE_HELPERS
#define rsqrt_in_range tg_rsqrt
#else
#define rsqrt_in_range tgi_rsqrt_normal   /* tinygi.h */
#endif

static int pixel_setup(const hbil_ctx *c, hbil_pixel *px, int i)
{
    const tgi_gview *g = c->g;
    const tgi_view *v = c->v;
    tg_vec3 nw, k;   /* nw: px->nw */
    tg_real ndv, r_px;
    if (tgi_gv_is_sky(g, i) || tgi_gv_depth(g, i) <= 0) return 0;
    px->z = tgi_gv_depth(g, i);
    px->inv_z = tg_div(TG_ONE, px->z);
    px->X = full_x(c, px->x);
    px->Y = full_y(c, px->y);
    /* w_o: unit vector from the surface toward the eye (sec. 1.1) */
    k = tg_v3(tg_mul(px->X, c->inv_ppu), tg_mul(px->Y, c->inv_ppu), TG_ONE);
#if TGI_Q16_WIDE
    px->kx = k.x;
    px->ky = k.y;
#endif
#if TGI_Q16_WIDE
    /* k_x, k_y in (-32, 32): offset by 32 below 64 as unsigned (a negative one wraps high) */
    px->k_small = (uint32_t)k.x + (32u << TG_FRAC_BITS) < (64u << TG_FRAC_BITS)
               && (uint32_t)k.y + (32u << TG_FRAC_BITS) < (64u << TG_FRAC_BITS);
#elif !TG_OUTLINE_HELPERS
    px->k_small = tg_abs(k.x) < TG_R(32.0f) && tg_abs(k.y) < TG_R(32.0f);   /* not a NaN */
#endif
    /* in float, where |k_x|, |k_y| < 32, |k|^2 in [1, 2049] and 1 + k_x^2
     * in [1, 1025]: positive, normal and finite (rsqrt_in_range) */
#if !TG_FIXED && !TG_OUTLINE_HELPERS
#define HBIL_RSQRT_K(x) (px->k_small ? rsqrt_in_range(x) : tg_rsqrt(x))
#elif TGI_Q16_WIDE
#define HBIL_RSQRT_K(x) rsqrt_in_range(x)   /* x >= 1 (|k|^2 with k_z = 1, 1 + k_x^2) */
#else
#define HBIL_RSQRT_K(x) tg_rsqrt(x)
#endif
#if TGI_Q16_WIDE
    /* the scales are tg_rsqrt of values >= 1, at most 1 (65536 raw; every
     * x >= 65536 tried): |k_i r| <= |k_i| <= TG_REAL_MAX rounds inside the
     * range, so tg_mul never saturates there: small_v3_scale, its values */
#define HBIL_UNIT_SCALE small_v3_scale
#else
#define HBIL_UNIT_SCALE tgi_v3_scale
#endif
    px->wo = HBIL_UNIT_SCALE(k, tg_neg(HBIL_RSQRT_K(tgi_v3_dot(k, k))));          /* |k| >= 1 */
    /* w_x = Y x w_o / |..| = (-1, 0, k_x) / sqrt(1 + k_x^2), w_y = w_o x w_x (sec. 1.1) */
    px->wx = HBIL_UNIT_SCALE(tg_v3(tg_neg(TG_ONE), 0, k.x), HBIL_RSQRT_K(tg_add(TG_ONE, tg_mul(k.x, k.x))));
#undef HBIL_UNIT_SCALE
#undef HBIL_RSQRT_K
#if TGI_Q16_WIDE
    /* w_o and w_x unit (|component| <= 1 and a rounding): products below
     * 2, differences below 4, so tg_mul and tg_sub would not saturate:
     * tgi_v3_cross's operations in its order, small */
    px->wy = tg_v3(small_sub(small_mul(px->wo.y, px->wx.z), small_mul(px->wo.z, px->wx.y)),
                   small_sub(small_mul(px->wo.z, px->wx.x), small_mul(px->wo.x, px->wx.z)),
                   small_sub(small_mul(px->wo.x, px->wx.y), small_mul(px->wo.y, px->wx.x)));
#else
    px->wy = tgi_v3_cross(px->wo, px->wx);
#endif
#if TGI_REUSE_NORMAL
    /* a pixel whose stored normal code is the last decoded one's (a flat
     * surface's pixels share theirs) has its normal (tgi_gv_normal is a
     * function of the code) and so its n before the bend below, the same
     * products of the same normal and the call's camera: px->nw and
     * px->nm.n as that pixel left them (pixel_setup alone sets them) */
    if (tgi_gv_normal_repeats(g, &px->nm, (size_t)i)) {
        px->n = px->nm.n;
    } else
#endif
    {
        nw = tgi_gv_normal(g, i);
#if !TG_OUTLINE_HELPERS   /* compiling for size, pixel_run reads it again */
        px->nw = nw;
#endif
        /* unit vectors (the normal, the camera's axes, w_o: |component| <= 1
         * and a rounding), n's components from their dots: small_dot */
        px->n = tg_v3(small_dot_rare(nw, v->right), small_dot_rare(nw, v->up), small_dot_rare(nw, v->forward));
#if TGI_REUSE_NORMAL
        px->nm.n = px->n;
#endif
    }
    ndv = small_dot_rare(px->n, px->wo);
    if (ndv < HBIL_MIN_NDOTV) {
        px->n = tgi_v3_normalize_or(tgi_v3_add(px->n, tgi_v3_scale(px->wo, tg_sub(HBIL_MIN_NDOTV, ndv))), px->wo);
        ndv = tgi_v3_dot(px->n, px->wo);
    }
    px->ndv = ndv;
    /* the world radius projected to image pixels; the 3D test is unclamped */
    r_px = tg_div(tg_mul(c->p->radius, c->ppu), px->z);
    /* no other cap in pixels: the march ends at the screen's edge
     * (march_side) or where the 3D test would reject every sample */
    px->reach = tg_min(tg_mul(r_px, c->inv_step), HBIL_MAX_RADIUS_UNITS);
    px->radius_units2 = tgi_wide_mul(px->reach, px->reach);
    return 1;
}

/* Screen direction of D (image pixels, y down): d/de project(p + e D). */
static void slice_screen_dir(const hbil_ctx *c, const hbil_pixel *px, tg_vec3 d, tg_real *ux, tg_real *uy)
{
#if !TG_FIXED || TG_OUTLINE_HELPERS   /* float (its frame took +0.1% kept) and compiling for size (shorter): computed again */
    tg_real kx = tg_mul(px->X, c->inv_ppu), ky = tg_mul(px->Y, c->inv_ppu);
#else
    tg_real kx = px->kx, ky = px->ky;   /* pixel_setup's, the same products */
    (void)c;
#endif
    tg_vec3 u;
    tg_real len2, inv;
#if TGI_Q16_WIDE
    if (px->k_small) {
        /* |k_x|, |k_y| < 32 (every field of view below 170 degrees at an
         * aspect ratio up to 2) and D's components below 2 (slice_run): |k d_z| < 64,
         * |u_x|, |u_y| < 66, |u|^2 < 2^14; 1/|u| < 2^7 for |u|^2 >= 0.0001
         * (below), so |u_i| / |u| < 66 2^7 < 2^13: tg_mul, tg_sub and
         * tg_add would not saturate (small_*) */
        const tg_real sx = small_sub(d.x, small_mul(kx, d.z)), sy = tg_neg(small_sub(d.y, small_mul(ky, d.z)));
        len2 = small_add(small_mul(sx, sx), small_mul(sy, sy));
        if (len2 < TG_R(0.0001f)) { *ux = TG_ONE; *uy = 0; return; }
        inv = rsqrt_in_range(len2);
        *ux = small_mul(sx, inv);
        *uy = small_mul(sy, inv);
        return;
    }
#endif
    u = tg_v3(tg_sub(d.x, tg_mul(kx, d.z)), tg_neg(tg_sub(d.y, tg_mul(ky, d.z))), 0);
    len2 = tg_add(tg_mul(u.x, u.x), tg_mul(u.y, u.y));
    if (len2 < TG_R(0.0001f)) { *ux = TG_ONE; *uy = 0; return; }  /* D is never along the ray */
#if !TG_FIXED && !TG_OUTLINE_HELPERS
    /* float: |k_x|, |k_y| < 32 and D's components below 2 (as Q16.16's
     * above) put |u|^2 in [0.0001, 2^14): positive, normal and finite */
    inv = px->k_small ? rsqrt_in_range(len2) : tg_rsqrt(len2);
#elif TGI_Q16_WIDE
    inv = rsqrt_in_range(len2);   /* len2 >= 0.0001 */
#else
    inv = tg_rsqrt(len2);
#endif
    *ux = tg_mul(u.x, inv);
    *uy = tg_mul(u.y, inv);
}

/* Out of the march loop, cold in float; Q16.16 compiles it for speed: cold
 * (for size) its products and divisions were calls to tg_mul and tg_div
 * out of line (cornell 160x120, 2 frames: -22M instructions, 2.2% of the
 * Q16.16 frame; float +2M when not cold). */
#if TG_FIXED
#define HBIL_EDGE HBIL_NOINLINE
#else
#define HBIL_EDGE HBIL_COLD
#endif
/* Depth at the continuous minor-axis position b0 + f, so that the sample
 * lies on the slice plane.  Between two surface pixels: 1/z interpolated
 * linearly (exact on a plane, however grazing; inlined in march_side).  At
 * a depth discontinuity, next to the sky or the image edge (here): the
 * nearest pixel's tangent plane is extended to the ray through the
 * continuous position; 0 (skip the sample) when that ray misses the plane
 * or lands far from the nearest pixel, or when the nearest pixel's plane
 * is seen edge-on: it has no depth along any ray but its own, and its own
 * is off the slice.  (It took the nearest's depth on the continuous ray:
 * at a ground plane's far edge against the sky, where a pixel spans the
 * plane from metres away to its end, that point lay far above the plane,
 * or, moved to the pixel's own ray, far off the slice, and closed the
 * horizon: AO 0.88 along the row; test_hbil open_plane_far_edge.) */
HBIL_EDGE static tg_real sample_depth_edge(const hbil_ctx *c, const tgi_gview *g, int major_x, int a, int b0,
                                           tg_real f, int sa, int sn)
{
    const tgi_view *v = c->v;
    tg_real zn = tgi_gv_depth(g, sn), gn, gc, X, Y, Xn, Yn, ratio;
    int bn;
    tg_vec3 nw, n;
    /* tangent plane of the nearest pixel: z = zn (n.ray_n) / (n.ray_c), ray = (X/ppu, Y/ppu, 1) */
    nw = tgi_gv_normal(g, sn);
    /* unit vectors (|component| <= 1 and a rounding): small_dot */
    n = tg_v3(small_dot_rare(nw, v->right), small_dot_rare(nw, v->up), small_dot_rare(nw, v->forward));
    bn = sn == sa ? b0 : b0 + 1;
    if (major_x) {
        X = view_x(c, g, a);
        Yn = view_y(c, g, bn);
        Y = small_sub(view_y(c, g, b0), small_mul_int(f, g->step));   /* see below */
        Xn = X;
    } else {
        Y = view_y(c, g, a);
        Xn = view_x(c, g, bn);
        X = small_add(view_x(c, g, b0), small_mul_int(f, g->step));
        Yn = Y;
    }
    /* f in [0, 1) times the step (< 2^13: the view lies in the full image)
     * is exact, and the sum with a position below 2^13 small: small_add,
     * small_sub and small_mul_int give tg_add, tg_sub and tg_mul's values */
#if TGI_Q16_WIDE
    /* With ppu >= 1 (inv_ppu <= 1: every camera but a tiny image with an
     * extreme field of view) nothing below saturates: |X|, |Y|, |Xn|, |Yn|
     * <= 2^13 + 1/2 (view_x), so each product with inv_ppu is at most 2^13
     * + 1 in magnitude after its rounding; n's components are dots of unit
     * vectors (tgi_oct_unpack's and the camera's basis, each within 2^-10
     * of unit length) rounded once, below 1.003 in magnitude, so each
     * product with one below 8218 and the sums below 16438 < 2^15: tg_mul and
     * tg_add's values without their saturation tests, and the sums exact
     * (integer adds), so gn and gc share their term of the major axis, whose
     * position is the same (Xn = X or Yn = Y).  Cornell 160x120, 2 frames:
     * Q16.16 sample_depth_edge 7.76M -> 6.60M. */
    if (c->inv_ppu <= TG_ONE) {
        const tg_real tx = small_mul(n.x, small_mul(X, c->inv_ppu)), ty = small_mul(n.y, small_mul(Y, c->inv_ppu));
        gc = tx + ty + n.z;
        gn = major_x ? tx + small_mul(n.y, small_mul(Yn, c->inv_ppu)) + n.z : small_mul(n.x, small_mul(Xn, c->inv_ppu)) + ty + n.z;
    } else
#endif
    {
        gn = tg_add(tg_add(tg_mul(n.x, tg_mul(Xn, c->inv_ppu)), tg_mul(n.y, tg_mul(Yn, c->inv_ppu))), n.z);
        gc = tg_add(tg_add(tg_mul(n.x, tg_mul(X, c->inv_ppu)), tg_mul(n.y, tg_mul(Y, c->inv_ppu))), n.z);
    }
    if (gn > TG_R(-0.01f) || gc > TG_R(-0.005f)) return 0; /* the nearest seen edge-on, or the ray misses its plane */
    ratio = tg_div(gn, gc);
    if (ratio < TG_R(0.5f) || ratio > TG_R(2.0f)) return 0; /* too far from the nearest: skip */
    return tg_mul(zn, ratio);
}

/* The margin of rejection_weight's tests (below). */
#define HBIL_REJECT_MARGIN TG_R(0.000244140625f)   /* 2^-12 */

#if !TG_OUTLINE_HELPERS
/* tg_smoothstep(a, b, x) inside the ramp, a < x < b, with d = b - a
 * fitting tg_real (ramp_init): tg_smoothstep's operations without its
 * tests and the call (float: ~19 instructions a ramp, cornell 160x120, 2
 * frames, 496.96M -> 496.17M).  Q16.16: tg_sub(x, a) = x - a in (0, d)
 * and tg_sub(b, a) = d do not saturate; tg_div of u = x - a > 0 by d > 0
 * is (u 2^16 + d/2) / d, which tgi_div_nonneg gives, at most 2^16 (u <
 * d), so tg_saturate keeps it; then q^2 <= 2^32 rounds to at most 2^16,
 * and 3 - 2q lies in [1, 3]: tg_mul's products (below 2^34) neither
 * saturate, tgi_wide_mul's roundings.  Float: the same operations on the
 * same d = b - a, finite and > 0; for a finite x in (a, b), x - a lies in
 * (0, d] as rounded (rounding is monotone), so the quotient lies in (0, 1]
 * and tg_saturate would keep it (kept, it took cornell 160x120, 2 frames,
 * 492.28M -> 492.81M).  The same bits as tg_smoothstep (tests/test_hbil.c,
 * ramp_smoothstep_is_tg_smoothstep).  (Float had its own inline copy of
 * these operations beside this one until the thirty-fourth session's
 * review.) */
static inline tg_real ramp_smoothstep(tg_real a, tg_real d, tg_real x)
{
#if TG_FIXED
    const tg_real q = tgi_div_nonneg(x - a, d);
    return (tg_real)tgi_wide_mul(tgi_wide_mul(q, q), 3 * TG_ONE - 2 * q);
#else
    const tg_real q = (x - a) / d;
    return q * q * (3.0f - (q + q));
#endif
}

/* ramp_d: b - a for a < b where the difference fits tg_real, else 0 (the
 * kernel then calls tg_smoothstep) */
static void ramp_init(hbil_ctx *c)
{
#if TG_FIXED
    const int64_t d = (int64_t)c->rejection_b - c->rejection_a;
    c->ramp_d = d > 0 && d <= TG_REAL_MAX ? (tg_real)d : 0;
#else
    const tg_real d = c->rejection_b - c->rejection_a;   /* NaN ends: 0 */
    c->ramp_d = c->rejection_b > c->rejection_a && d <= TG_REAL_MAX ? d : 0;
#endif
}
#endif

/* HBIL sec. 3.4's weight t = smoothstep(a, b, -n_s.w_i) of a sender with
 * the unit normal n_s seen along dir (view space; w_i is dir in world space). */
static tg_real rejection_ramp(const hbil_ctx *c, tg_vec3 ns, tg_vec3 dir)
{
    const tgi_view *v = c->v;
    tg_real t;
    /* unit vectors: the camera's axes and dir (|.| <= 1, small_mul) */
#if TGI_Q16_WIDE
    /* the same sums in tgi_wide, not narrowed to tg_real and widened again
     * for the dot (each below 4 in magnitude: the same integers) */
    const tgi_wide wx = tgi_wide_mul(v->right.x, dir.x) + tgi_wide_mul(v->up.x, dir.y) + tgi_wide_mul(v->forward.x, dir.z);
    const tgi_wide wy = tgi_wide_mul(v->right.y, dir.x) + tgi_wide_mul(v->up.y, dir.y) + tgi_wide_mul(v->forward.y, dir.z);
    const tgi_wide wz = tgi_wide_mul(v->right.z, dir.x) + tgi_wide_mul(v->up.z, dir.y) + tgi_wide_mul(v->forward.z, dir.z);
    t = tg_neg((tg_real)tgi_wide_dot(ns.x, ns.y, ns.z, wx, wy, wz));
#else
    tg_vec3 wi = tg_v3(small_add(small_add(small_mul(v->right.x, dir.x), small_mul(v->up.x, dir.y)), small_mul(v->forward.x, dir.z)),
                       small_add(small_add(small_mul(v->right.y, dir.x), small_mul(v->up.y, dir.y)), small_mul(v->forward.y, dir.z)),
                       small_add(small_add(small_mul(v->right.z, dir.x), small_mul(v->up.z, dir.y)), small_mul(v->forward.z, dir.z)));
    t = tg_neg(small_dot_rare(ns, wi));   /* n_s unit, |w_i|'s components below 2: small */
#endif
    /* outside the ramp without the call (tg_smoothstep gives 0 and 1 there) */
#if !TG_OUTLINE_HELPERS
    if (c->ramp_d)
        return t <= c->rejection_a ? 0 : t >= c->rejection_b ? TG_ONE : ramp_smoothstep(c->rejection_a, c->ramp_d, t);
#endif
    if (c->rejection_b > c->rejection_a)
        return t <= c->rejection_a ? 0 : t >= c->rejection_b ? TG_ONE : tg_smoothstep(c->rejection_a, c->rejection_b, t);
    return tg_smoothstep(c->rejection_a, c->rejection_b, t);
}

#if !TG_WIDE_STORAGE
#if !TG_NO_COLOR
/* The ramp's ends for rejection_weight's tests (ctx_init); ends within
 * [-2, 2]: x|x| |n|^2 stays below 2^56 in Q16.16. */
static void rejection_init(hbil_ctx *c, tg_real a, tg_real b)
{
    const tg_real lo = tg_sub(a, HBIL_REJECT_MARGIN), hi = tg_add(b, HBIL_REJECT_MARGIN);
    c->rejection_a = a;
    c->rejection_b = b;
#if !TG_OUTLINE_HELPERS
    ramp_init(c);
#endif
    c->reject_fast = b > a && lo >= TG_R(-2.0f) && hi <= TG_R(2.0f);
    c->reject_lo2 = (tgi_wide)lo * (lo < 0 ? -(tgi_wide)lo : lo);
    c->reject_hi2 = (tgi_wide)hi * (hi < 0 ? -(tgi_wide)hi : hi);
}
#endif

#if HBIL_UNIT_MEMO
/* rejection_ramp of the stored normal, the normalisation out of line too:
 * off the march's registers, where gather_rise is inlined.  The call's
 * last normalised direction and its unit vector are kept (c->memo, a
 * local of tgi_hbil_rows: one a thread): tgi_oct_unit is a function of
 * the direction alone (the integers x, y, z; equal ones from either
 * image, the sub-image's or the fine one), so a sender with the direction
 * of the last (a flat surface's, the common case) takes the same unit
 * vector without the integer rsqrt, ~70 instructions (cornell 160x120,
 * 2 frames: Q16.16 746.43M -> 740.80M; with the memo in hbil_side, set
 * at each side_init, 745.35M, and columns +0.2M); float's, without the
 * conversions and the rsqrt, ~35 (499.87M -> 498.22M; it was
 * rejection_ramp_unit, which decoded at every call).  The direction n and
 * dir as six scalars: as two 12-byte structs gcc packed them into
 * registers at every rise, before the tests that make the call rare
 * (cornell 160x120, 2 frames, Q16.16 710.04M -> 707.72M, columns 314.49M
 * -> 314.45M; dir's alone 707.93M but columns 314.56M, dir by address
 * 710.10M; float 520.18M -> 518.99M, columns 214.29M -> 213.72M). */
/* The memo takes direction (nx, ny, nz).  Q16.16: out of line, its integer
 * rsqrt off the ramp's registers (rejection_ramp_oct pushed six callee-saved
 * registers at every call for it: cornell 160x120, 2 frames, Q16.16
 * 688.09M -> 687.26M); float's inline (out of line: +0.07M). */
#if TGI_Q16_WIDE
static HBIL_COLD void unit_memo_fill(hbil_unit_memo *m, int32_t nx, int32_t ny, int32_t nz)
#else
static HBIL_INLINE void unit_memo_fill(hbil_unit_memo *m, int32_t nx, int32_t ny, int32_t nz)
#endif
{
    m->d.x = nx; m->d.y = ny; m->d.z = nz;
    m->n = tgi_oct_unit(m->d);
}
static HBIL_NOINLINE tg_real rejection_ramp_oct(const hbil_ctx *c, int32_t nx, int32_t ny, int32_t nz, tg_real dx, tg_real dy, tg_real dz)
{
    hbil_unit_memo *const m = c->memo;
    if (nx != m->d.x || ny != m->d.y || nz != m->d.z) unit_memo_fill(m, nx, ny, nz);
    return rejection_ramp(c, m->n, tg_v3(dx, dy, dz));
}
#endif

/* rejection_ramp's t for a sender whose normal is stored as the octahedral
 * direction n (tgi_gv_normal_dir), n_s = n / |n|.  Outside the ramp, where t
 * is 0 or 1, the sign of f - x |n| tells, for f = -n.w_i and x the ramp's
 * end, without the normalisation: f|f| against x|x| |n|^2 (reject_lo2,
 * reject_hi2; |n|^2 < 2^22 is exact in both types).  The ends are moved out
 * by HBIL_REJECT_MARGIN, 2^-12 = 2.44e-4, above the error of the t
 * computed with n_s, so the tests answer only where that t is beyond the
 * end too: the weights are rejection_ramp's (tests/test_hbil.c,
 * rejection_tests_keep_the_weights).  The error, Q16.16: both start from
 * the same dir (|dir| <= 1 + 2^-9: sample_dir's 1/|d| >= 2^-7 rounded to
 * 2^-17, and its own roundings), M dir exact here (M the camera's axes,
 * |M dir|_j <= |dir|); against g = -(n / |n|).(M dir): n_s's components
 * within 3.2e-6 relative (the Q30 rsqrt) plus 2^-16 (truncated) of n / |n|
 * (sum over j below 3.2e-6 sqrt 3 + 3 2^-16 = 5.1e-5, times |w_i,j| <
 * 1.01), w_i's within 3 2^-17 of M dir (three roundings; times sum |n_j| /
 * |n| <= sqrt 3: 4.0e-5), the dot's rounding 2^-17: |t - g| < 1.0e-4; f
 * here is g |n| 2^16 floored (within 1 / (|n| 2^16) < 1.1e-7 of g, |n|
 * >= q / sqrt 3 > 146); so f at or past an end moved out by 2.44e-4 puts t
 * 1.4e-4 past the end.  Float: 1e-5.  (The margin was 2^-10: cornell
 * 160x120, 2 frames, Q16.16 737.69M -> 736.02M, float 526.76M -> 525.78M;
 * 2^-11 took 737.39M and 526.60M.) */
/* The memo m takes direction n (its key set by the caller): M^T n =
 * (n.right, n.up, n.forward) for M the camera's axes, and |n|^2 */
static HBIL_INLINE void reject_memo_fill(const hbil_ctx *c, hbil_reject_memo *m, tgi_oct_dir n)
{
    const tgi_view *v = c->v;
    m->d = n;
#if TG_FIXED
    m->n2 = n.x * n.x + n.y * n.y + n.z * n.z;      /* |n|^2 <= q^2 < 2^22 */
    m->nr = (int64_t)n.x * v->right.x + (int64_t)n.y * v->right.y + (int64_t)n.z * v->right.z;
    m->nu = (int64_t)n.x * v->up.x + (int64_t)n.y * v->up.y + (int64_t)n.z * v->up.z;
    m->nf = (int64_t)n.x * v->forward.x + (int64_t)n.y * v->forward.y + (int64_t)n.z * v->forward.z;
#else
    {   /* |n|^2 < 2^22 exact in float, as the integer */
        const float x = (float)n.x, y = (float)n.y, z = (float)n.z;
        m->n2 = x * x + y * y + z * z;
        m->nr = x * v->right.x + y * v->right.y + z * v->right.z;
        m->nu = x * v->up.x + y * v->up.y + z * v->up.z;
        m->nf = x * v->forward.x + y * v->forward.y + z * v->forward.z;
    }
#endif
}
/* The weight of m's direction n for a sample's direction dir, the tests
 * above written with M^T n: n.w_i = n.(M dir) = (M^T n).dir (w_i = M dir).
 * Q16.16: an exact integer sum in int64 (|n.axis| <= (|n_x| + |n_y| +
 * |n_z|) 2^16 < 2^27 for a camera axis unit and |n|_1 = q < 2^11, times
 * |dir_i| < 2^17: below 2^46 a term), to Q16.16 floored by the shift
 * (tgi_shift_floors: within a unit of 2^-16 as a truncation, which the
 * margin's bound takes); dir's components below 2 (a sample's direction,
 * sample_dir: at most 1 + 2^-9; the test entry below takes no other), so
 * |f| < 2^28.8 and f|f| < 2^58 without a test of f; x|x| |n|^2 < 2^34
 * 2^22.  Float: its rounding a few 2^-24 of |n| |w_i| (|n|^2 exact below
 * 2^22), inside the margin's bound (1e-5 in float).  (Summed as n.(M dir)
 * the integers were the same; float's sum in that order took the same
 * answers: tests/test_hbil.c rejection_tests_keep_the_weights.) */
static HBIL_INLINE tg_real rejection_weight_m(const hbil_ctx *c, const hbil_reject_memo *m, tg_vec3 dir)
{
    if (c->reject_fast) {
#if TG_FIXED
        const int64_t f = -((m->nr * dir.x + m->nu * dir.y + m->nf * dir.z) >> 16);
        const int64_t ff = f < 0 ? -f * f : f * f;
#else
        const float f = -(m->nr * dir.x + m->nu * dir.y + m->nf * dir.z);
        const float ff = f * tgi_abs_fast(f);   /* f|f| (raster/pack.h: a sign bit cleared; at f = -0 a zero of the other sign, equal in both tests) */
#endif
        if (ff >= c->reject_hi2 * m->n2) return TG_ONE;          /* the common case first */
        if (ff <= c->reject_lo2 * m->n2) return 0;
    }
#if HBIL_UNIT_MEMO
    return rejection_ramp_oct(c, m->d.x, m->d.y, m->d.z, dir.x, dir.y, dir.z);
#else
    return rejection_ramp(c, tgi_oct_unit(m->d), dir);   /* tgi_gv_normal's n_s, the word decoded once */
#endif
}
#if HBIL_REJECT_MEMO
/* rejection_weight_m of sender si of image g, M^T n and |n|^2 kept for the
 * sender's stored code (reject_memo_key; equal codes of one storage form,
 * equal normals): a flat surface's senders repeat it, and then a rise
 * takes three products for f, not the octahedral fold and twelve
 * (cornell 160x120, 2 frames: Q16.16 723.31M -> 713.04M, columns 314.99M
 * -> 314.64M; float 518.99M -> 506.62M, columns 213.72M -> 213.12M).
 * The memo m is the side's (hbil_side.reject_memo), one for each side of
 * each slice of the call: the two sides of a slice look at two
 * surfaces (a floor and a wall), as do the slices, and the pixels in a
 * row share them, where one memo for the call missed at nearly half the
 * rises on builtin:cornell, the sides taking turns (cornell 160x120, 2
 * frames, Q16.16 617.82M -> 616.10M, columns 270.51M -> 270.90M; float
 * 462.10M -> 460.12M, columns 199.98M -> 199.79M; one memo a side of the
 * slice, whatever the slice: 617.45M and 461.32M) */
static HBIL_INLINE tg_real rejection_weight_memo(const hbil_ctx *c, hbil_reject_memo *m, const tgi_gview *g, size_t si, tg_vec3 dir)
{
    const uint32_t key = reject_memo_key(g, si);
    if (key != m->key) {
        m->key = key;
        reject_memo_fill(c, m, tgi_gv_normal_dir(g, si));
    }
    return rejection_weight_m(c, m, dir);
}
#else
/* rejection_weight_m of one sender's direction n, no memo (the builds for
 * size; and TG_NO_COLOR's, which never gather) */
static tg_real rejection_weight(const hbil_ctx *c, tgi_oct_dir n, tg_vec3 dir)
{
    hbil_reject_memo m;
    reject_memo_fill(c, &m, n);
    return rejection_weight_m(c, &m, dir);
}
#endif

#if !TG_NO_COLOR
tg_real tgi_hbil_rejection_weight(const tgi_view *v, tg_real a, tg_real b, tgi_oct_dir n, tg_vec3 dir, int tests)
{
    hbil_ctx c;
#if HBIL_UNIT_MEMO
    hbil_unit_memo m;
#endif
    memset(&c, 0, sizeof c);
#if HBIL_UNIT_MEMO
    unit_memo_start(&m);
    c.memo = &m;
#endif
    c.v = v;
    rejection_init(&c, a, b);
    /* the tests for a dir as the kernel's (rejection_weight: components below 2) */
    if (!tests || !(dir.x < TG_R(2.0f) && dir.x > TG_R(-2.0f) && dir.y < TG_R(2.0f) && dir.y > TG_R(-2.0f)
                    && dir.z < TG_R(2.0f) && dir.z > TG_R(-2.0f)))
        c.reject_fast = 0;
#if HBIL_REJECT_MEMO   /* the kernel's: the tests through the memo's products */
    {
        hbil_reject_memo rm;
        reject_memo_fill(&c, &rm, n);
        return rejection_weight_m(&c, &rm, dir);
    }
#else
    return rejection_weight(&c, n, dir);
#endif
}
#endif
#endif /* !TG_WIDE_STORAGE */

/* L_old + (L - L_old) t, as tg_lerp, for t in [0, 1] (rejection_weight):
 * the product is at most |L - L_old|, so it does not saturate (small_mul),
 * and at t = 1 it is L - L_old itself. */
static HBIL_INLINE tg_real radiance_lerp(tg_real a, tg_real b, tg_real t)
{
    const tg_real d = tg_sub(b, a);
    return tg_add(a, t == TG_ONE ? d : small_mul(d, t));
}

/* The same with a and b in [0, TG_REAL_MAX] (radiance: radiance_nonneg):
 * in Q16.16 b - a fits and a + (b - a) t lies between a and b, so neither
 * tg_sub nor tg_add would saturate; in float the same operations. */
static HBIL_INLINE tg_real radiance_lerp_pos(tg_real a, tg_real b, tg_real t)
{
    const tg_real d = small_sub(b, a);
#if TG_FIXED   /* integers: a + (b - a) is b (float rounds the two) */
    return t == TG_ONE ? b : small_add(a, small_mul(d, t));
#else
    return small_add(a, t == TG_ONE ? d : small_mul(d, t));
#endif
}

/* 1 when gather_rise's running radiance, the band's and the sums are in
 * [0, TG_REAL_MAX], as radiance_lerp_pos and near_sum_pos need (in Q16.16
 * a negative one could wrap b - a, or a sum below TG_REAL_MIN, and then
 * not give tg_add's saturated value; in float the arithmetic of the two
 * branches is the same).  With packed storage it always is,
 * without a test: every radiance read (tgi_rgb_read, raster/gview.h) is an
 * RGB9E5 word's decode (tgi_rgb9e5_chan, raster/pack.h: unsigned, saturated
 * at TG_REAL_MAX; a hole decodes to 0), or tgi_gb_lit of one: diffuse e +
 * emissive, where diffuse = albedo (1 - F0)/pi >= 0 (tgi_material_finish,
 * core/material.h, from an albedo in [0, 1] and F0 in [0, 1]) and emissive
 * >= 0, as the parser (scene/parse.c st_material) and the MTL reader
 * (scene/obj.c mtl_color) check them and tinygi-bake copies them; no setter
 * changes a material.  The running radiance starts at 0 (side_init) and is
 * a lerp of such values with t in [0, 1]; the band is one of them or the
 * mean of two; the sums start at 0 and add products of them with de >= 0.
 * Wide storage keeps any tg_real a pass writes (a hole is TG_REAL_MIN until
 * push/pull fills it): there the test stays. */
static inline int radiance_nonneg(tg_real a, tg_real b, tg_real c, tg_real d, tg_real e, tg_real f)
{
#if TG_FIXED && TG_WIDE_STORAGE
    return (a | b | c | d | e | f) >= 0;
#else
    (void)a; (void)b; (void)c; (void)d; (void)e; (void)f;
    return TG_FIXED;   /* float: 0, the general branch, the same code as before */
#endif
}

/* s + l de, as tg_add(s, tg_mul(l, de)), for s, l in [0, TG_REAL_MAX] and
 * de in [0, 5) (the band's dE, |P| < 2.5): the product is l de rounded
 * (>= 0, below 2^51 as an integer) and both tg_mul and tg_add saturate
 * only at TG_REAL_MAX, so one saturation of the sum gives the same (a
 * saturated product saturates the sum too).  With HBIL_WIDE_SUMS its
 * term alone, in gather_rise. */
#if !HBIL_WIDE_SUMS
static HBIL_INLINE tg_real near_sum_pos(tg_real s, tg_real l, tg_real de)
{
#if TG_FIXED
    const int64_t v = (int64_t)s + (((int64_t)l * de + 32768) >> 16);
    return v > (int64_t)TG_REAL_MAX ? TG_REAL_MAX : (tg_real)v;
#else
    return s + l * de;
#endif
}
#endif

/* tg_mul(tg_add(a, b), TG_R(0.5f)) for a, b in [0, TG_REAL_MAX]
 * (radiance_nonneg).  Q16.16: the sum x = min(a + b, 2^31 - 1) times 2^15
 * rounded is (x 2^15 + 2^15) >> 16 = (x + 1) >> 1, i.e. min((a + b + 1)
 * >> 1, 2^30) (a sum past TG_REAL_MAX gives 2^30 and more unsaturated);
 * a + b + 1 < 2^32 in 32 unsigned bits, without the two saturation tests.
 * Float, and compiling for size (4 bytes shorter): as before. */
static HBIL_INLINE tg_real radiance_mean_pos(tg_real a, tg_real b)
{
#if TGI_Q16_WIDE
    const uint32_t m = ((uint32_t)a + (uint32_t)b + 1u) >> 1;
    return m > 0x40000000u ? (tg_real)0x40000000 : (tg_real)m;
#else
    return tg_mul(tg_add(a, b), TG_R(0.5f));
#endif
}

/* tg_add(a, tg_add(b, c)) for a, b, c in [0, TG_REAL_MAX]
 * (radiance_nonneg): min(a + b + c, TG_REAL_MAX) in 64 bits, one
 * saturation test (an inner sum saturated at TG_REAL_MAX saturates the
 * outer one too).  Float: as before. */
#if !TG_OUTLINE_HELPERS   /* its one use is not compiled for size (slice_run) */
static inline tg_real near_sum3_pos(tg_real a, hbil_esum b, hbil_esum c)
{
#if TG_FIXED
    const int64_t v = (int64_t)a + b + c;
    return v > (int64_t)TG_REAL_MAX ? TG_REAL_MAX : (tg_real)v;
#else
    return tg_add(a, tg_add(b, c));
#endif
}
#endif

/* A raised horizon: gather L(x') over the band it closes (eq. 18-19, sec.
 * 3.4).  The sender is pixel si of g, its radiance pixel si of rad; a
 * sample of the fine image without its radiance (refine_fine) passes rad
 * NULL: the band then takes the running radiance L_old (t = 0).  Inlined
 * where a rise is found (a call cost ~40 instructions a rise in float,
 * saving and restoring the march's registers: cornell 320x240 -1.5% of
 * the frame, .text +5.5 KB float, +9 KB Q16.16); one copy out of line
 * when compiling for size. */
#if TG_OUTLINE_HELPERS
#define HBIL_GATHER_INLINE HBIL_NOINLINE
#else
#define HBIL_GATHER_INLINE HBIL_INLINE
#endif
/* rad_set: 1 where rad is known not NULL, without the test (the march's
 * c->rad, which NEAR_FIELD's tgi_rgb_present checked), 0 where it may be
 * (refine_fine's fine radiance); compiling for size the test alone. */
#if TG_OUTLINE_HELPERS
#define GATHER_RISE(c, sl, sd, side, cos_new, dir, g, rad, si, trapezoid, rad_set) \
    gather_rise(c, sl, sd, side, cos_new, dir, g, rad, si, trapezoid)
static HBIL_GATHER_INLINE void gather_rise(const hbil_ctx *c, const hbil_slice *sl, hbil_side *sd, int side,
                        tg_real cos_new, tg_vec3 dir, const tgi_gview *g, const tgi_rgb *rad, int si, int trapezoid)
#else
#define GATHER_RISE gather_rise
static HBIL_GATHER_INLINE void gather_rise(const hbil_ctx *c, const hbil_slice *sl, hbil_side *sd, int side,
                        tg_real cos_new, tg_vec3 dir, const tgi_gview *g, const tgi_rgb *rad, int si, int trapezoid,
                        const int rad_set)
#endif
{
    const tg_real lr_old = sd->lr, lg_old = sd->lg, lb_old = sd->lb;   /* the running radiance before this rise */
    tg_real br, bg, bb;                                                    /* the band's */
    tg_real q_new = slice_Q(cos_new, side);
    /* P(theta) = int_0^theta (n'.w_i') |sin| : the antiderivative of eq. 10
     * (|n'| <= 1, |Q| < 2, R <= 1/2, |P| < 2.5: small_mul) */
    tg_real p_new = small_add(small_mul(sl->nx, q_new), small_mul(sl->ny, slice_R(cos_new)));
    tg_real de = tg_max(0, small_sub(sd->p_old, p_new));      /* HBIL eq. 18 */
    sd->p_old = p_new;
    sd->q = q_new;
#if TG_OUTLINE_HELPERS
    if (rad) {
#else
    if (rad_set || rad) {
#endif
#if TG_WIDE_STORAGE
        tg_real t = rejection_ramp(c, tgi_gv_normal(g, si), dir);
#elif HBIL_REJECT_MEMO
        tg_real t = rejection_weight_memo(c, sd->reject_memo, g, (size_t)si, dir);
#else
        tg_real t = rejection_weight(c, tgi_gv_normal_dir(g, si), dir);
#endif
        if (t != 0) {   /* lerp(L_old, L(x'), 0) is L_old: the sender's radiance is not read */
            tg_vec3 l = tgi_rgb_read(rad, si);
            if (radiance_nonneg(sd->lr, sd->lg, sd->lb, l.x, l.y, l.z)) {
                sd->lr = radiance_lerp_pos(sd->lr, l.x, t);
                sd->lg = radiance_lerp_pos(sd->lg, l.y, t);
                sd->lb = radiance_lerp_pos(sd->lb, l.z, t);
            } else {
                sd->lr = radiance_lerp(sd->lr, l.x, t);              /* L_new = lerp(L_old, L(x'), t) */
                sd->lg = radiance_lerp(sd->lg, l.y, t);
                sd->lb = radiance_lerp(sd->lb, l.z, t);
            }
        }
    }
    if (trapezoid) {   /* right after another rise: the mean of the band's two ends */
        if (radiance_nonneg(lr_old, lg_old, lb_old, sd->lr, sd->lg, sd->lb)) {
            br = radiance_mean_pos(lr_old, sd->lr);
            bg = radiance_mean_pos(lg_old, sd->lg);
            bb = radiance_mean_pos(lb_old, sd->lb);
        } else {
            br = tg_mul(tg_add(lr_old, sd->lr), TG_R(0.5f));
            bg = tg_mul(tg_add(lg_old, sd->lg), TG_R(0.5f));
            bb = tg_mul(tg_add(lb_old, sd->lb), TG_R(0.5f));
        }
    } else {           /* eq. 18: the far end's */
        br = sd->lr; bg = sd->lg; bb = sd->lb;
    }
#if HBIL_WIDE_SUMS   /* near_sum_pos's terms (radiance_nonneg: the band >= 0, de >= 0), unsaturated */
    /* each l de + 2^15 >= 0, so its shift is the same unsigned (gcc
     * vectorised two of the sums, and x86-64's SSE2 has no 64-bit
     * arithmetic shift: 19 instructions a rise for one; cornell 160x120,
     * 2 frames, Q16.16 713.04M -> 710.04M) */
    sd->er += (int64_t)((uint64_t)((int64_t)br * de + 32768) >> 16);
    sd->eg += (int64_t)((uint64_t)((int64_t)bg * de + 32768) >> 16);
    sd->eb += (int64_t)((uint64_t)((int64_t)bb * de + 32768) >> 16);
#else
    if (radiance_nonneg(sd->er, sd->eg, sd->eb, br, bg, bb)) {   /* de >= 0 too */
        sd->er = near_sum_pos(sd->er, br, de);
        sd->eg = near_sum_pos(sd->eg, bg, de);
        sd->eb = near_sum_pos(sd->eb, bb, de);
    } else {
        sd->er = tg_add(sd->er, tg_mul(br, de));
        sd->eg = tg_add(sd->eg, tg_mul(bg, de));
        sd->eb = tg_add(sd->eb, tg_mul(bb, de));
    }
#endif
}

/* Floor of a finite value well inside the int range (the march's minor
 * coordinate): tg_to_int without its NaN and saturation tests; in Q16.16
 * the integer part of the raw value offset by 2^31 into the unsigned
 * range, the same integer as tg_to_int's shift (written as the shift, gcc
 * compiled the march 0.15% longer: cornell 320x240, callgrind). */
/* Its users: the fine refinement (refine_fine, and fine_run through
 * floor_frac_small), EXTENT_TO_INT in float not compiling for size, and
 * the march's floor_frac_small in Q16.16 compiling for size; without the
 * fine horizon, float for size and Q16.16's wide march have none */
#if !TG_NO_FINE_HORIZON || (TG_FIXED ? TG_OUTLINE_HELPERS : !TG_OUTLINE_HELPERS)
static inline int floor_small(tg_real a)
{
#if TG_FIXED
    return (int)(((uint32_t)a + 0x80000000u) >> 16) - 32768;
#else
    int i = (int)a;
    return (tg_real)i > a ? i - 1 : i;
#endif
}
#endif

/* tg_to_int of a value known finite and within [0, 2^14 + 2] (each use
 * says why): in float floor_small, without tg_to_int's NaN and range
 * tests (three a slice and one a march_pixels: cornell 160x120, 2 frames,
 * float 530.02M -> 529.04M); Q16.16's tg_to_int
 * is its shift alone, and compiling for size tg_to_int as before. */
#if TG_FIXED || TG_OUTLINE_HELPERS
#define EXTENT_TO_INT tg_to_int
#else
#define EXTENT_TO_INT floor_small
#endif

/* Whole-pixel steps along the major axis: `samples` steps of m pixels
 * reach the extent; returns m and sets *n, the count of steps.  The
 * divisors are counts >= 1: the quotients fit (tgi_div_pos).  The extent
 * is in [0, 2^14] (the reach, at most HBIL_MAX_RADIUS_UNITS, times |u| <=
 * 1), samples <= TG_MAX_SAMPLES: the rounded quotient's floor m has m
 * samples <= extent + samples 2^-17 < 2^14 + 1, and m <= 2^14 + 1 after
 * the increment, so small_from_int gives tg_from_int's values (it would
 * not saturate) without its tests (compiling for size tg_from_int as
 * before: 12 bytes shorter in the AO-only program). */
#if TG_OUTLINE_HELPERS
#define STEPS_FROM_INT tg_from_int
#else
#define STEPS_FROM_INT small_from_int
#endif
static int march_steps(const hbil_ctx *c, tg_real extent, int *n)
{
    int m = EXTENT_TO_INT(tgi_div_pos(extent, STEPS_FROM_INT(c->samples)));
    if (STEPS_FROM_INT(m * c->samples) < extent) m++;
    if (m < 1) m = 1;
    *n = EXTENT_TO_INT(tgi_div_pos(extent, STEPS_FROM_INT(m)));
    if (*n > c->samples) *n = c->samples;
    return m;
}
#undef STEPS_FROM_INT


/* Branches gcc is told the march takes mostly (HBIL_LIKELY) or seldom:
 * its register choices (the march has more live values than registers)
 * then favour the common path; the same operations.  Each measured on
 * cornell 160x120, 2 frames, one at a time, and kept in the type it
 * lowered (the other's code as written):
 *   both: the interpolated depth (both neighbours inside, surface and
 *     close), float 480.77M -> 480.03M, Q16.16 655.70M -> 655.06M;
 *   Q16.16: the sample not above the horizon 656.79M -> 655.70M (float
 *     +0.65M), sample_cos's q within q_near 655.06M -> 654.73M, a sample
 *     beyond the radius seldom 654.74M -> 653.78M (float +0.20M);
 *   float: floor_frac_small's negative correction seldom 480.03M ->
 *     479.78M, the horizon test failing 479.50M -> 479.04M (Q16.16
 *     +0.58M), the cosine at or under h seldom 479.78M -> 479.50M (Q16.16
 *     +1.0M).
 * Measured and not kept: Q16.16 len2 <= r2 (655.75M against 654.73M) and
 * len2 < 2^30 (656.18M); float len2 <= r2 (481.65M against 480.03M); the
 * slice leaving the image seldom (float 479.53M, Q16.16 653.84M).  Not in
 * the builds for size. */
#if defined(__GNUC__) && !TG_OUTLINE_HELPERS
#define HBIL_LIKELY(x) __builtin_expect(!!(x), 1)
#define HBIL_UNLIKELY(x) __builtin_expect(!!(x), 0)
#else
#define HBIL_LIKELY(x) (x)
#define HBIL_UNLIKELY(x) (x)
#endif
#if TGI_Q16_WIDE
#define HBIL_Q16_LIKELY(x) HBIL_LIKELY(x)
#define HBIL_Q16_UNLIKELY(x) HBIL_UNLIKELY(x)
#else
#define HBIL_Q16_LIKELY(x) (x)
#define HBIL_Q16_UNLIKELY(x) (x)
#endif
#if TG_FIXED
#define HBIL_F_LIKELY(x) (x)
#define HBIL_F_UNLIKELY(x) (x)
#else
#define HBIL_F_LIKELY(x) HBIL_LIKELY(x)
#define HBIL_F_UNLIKELY(x) HBIL_UNLIKELY(x)
#endif

/* b0 = floor_small(a), returned, and *f = a - b0 in [0, 1): the raw
 * value's fraction bits in Q16.16.  In float the truncation's conversion
 * back, (float)i, serves the floor's compare and the fraction, less one
 * where the floor is i - 1: (float)(i - 1) is (float)i - 1 exactly (|i| <
 * 2^24), so the fraction is a - (float)b0 as it was, the same bits (it
 * had been a - (float)b0 after floor_small, whose conversion fine_run made
 * again: cornell 160x120 float 530.83M -> 530.31M, Q16.16 754.48M ->
 * 752.06M, its fine_run computing f before the image test; --gi-quarter
 * 320x240 float 1000.22M -> 997.59M, Q16.16's kernel the same). */
#if !TGI_Q16_WIDE || !TG_NO_FINE_HORIZON   /* Q16.16's march takes its own form (march_samples): fine_run's alone */
static inline int floor_frac_small(tg_real a, tg_real *f)
{
#if TG_FIXED
    *f = a & 0xFFFF;
    return floor_small(a);
#else
    int i = (int)a;
    tg_real fi = (tg_real)i;
    if (HBIL_UNLIKELY(fi > a)) {
        i--;
        fi = fi - 1.0f;
    }
    *f = a - fi;
    return i;
#endif
}
#endif

/* The sample's offset from the pixel, its squared length and its dot with
 * w_o (march_samples) in tgi_wide (core/real.h), which does not saturate.  The bounds that
 * make this exact, in image pixels: the image is at most
 * TG_MAX_IMAGE_SIDE = 2^13 pixels a side, so |P0 + s| < 2^14 and, with
 * |q| <= TG_REAL_MAX (tg_mul saturates it), |(P0 + s) q| < 2^45: every
 * product below fits 64 bits.  A component beyond HBIL_FAR (> the largest
 * 3D radius, HBIL_MAX_RADIUS_UNITS) is rejected before it is squared: the
 * saturating sum would have exceeded the radius too.  Below the radius
 * |d| <= 2^14, so d.d <= 3 2^28 and dot |dot|, h|h| |d|^2 < 2^30 (2^46 as
 * Q16.16 integers): every product fits 64 bits. */
#if TG_FIXED
#define HBIL_FAR (((int64_t)16384 + 1) << 16)
/* 1 when a component of d is beyond HBIL_FAR (fixed only: float squares
 * do not overflow).  First one test for the three: offset by 2^30 (16384)
 * they are all below 2^31 as unsigned (a negative one wraps high) unless
 * one is outside [-16384, 16384); only then the exact test per component */
static inline int wide_far(tgi_wide dx, tgi_wide dy, tgi_wide dz)
{
#if !TG_OUTLINE_HELPERS   /* compiling for size: the exact test alone */
    const tgi_wide near = (tgi_wide)1 << 30;
    if ((((uint64_t)(dx + near) | (uint64_t)(dy + near) | (uint64_t)(dz + near)) >> 31) == 0) return 0;
#endif
    return (uint64_t)(dx + HBIL_FAR) > (uint64_t)(2 * HBIL_FAR) || (uint64_t)(dy + HBIL_FAR) > (uint64_t)(2 * HBIL_FAR)
        || (uint64_t)(dz + HBIL_FAR) > (uint64_t)(2 * HBIL_FAR);
}

/* A bound on q = (z1 - z) / z (Q16.16) within which wide_far is 0 for
 * every sample of a frame w x h whose kernel image has the given step and
 * p0z = ppu / step: a sample lies in the image, so its screen position
 * P0 + s (march units from the centre) has |.| <= wh = (max(w, h) / 2 + 2)
 * / step + 2 and |s| <= 2 wh; then |d_x|, |d_y| <= 2 wh + wh |q| + 1 ulp
 * and |d_z| <= p0z |q| + 1 ulp, each at most 2^14 = 16384 units (below
 * HBIL_FAR) for |q| <= the returned bound (0 where none is). */
#if HBIL_Q_NEAR
static tg_real march_q_near(int w, int h, int step, tg_real p0z)
{
    const int64_t lim = (int64_t)1 << 30;   /* 16384 units */
    const int64_t wh = ((int64_t)((w > h ? w : h) / 2 + 2) << 16) / (step > 0 ? step : 1) + ((int64_t)2 << 16);
    int64_t qa = lim - 2 * wh - 2, qb;
    qa = qa > 0 ? (qa << 16) / wh : 0;                                  /* (lim - 2 wh - 2) / wh */
    qb = p0z > 0 ? ((lim - 1) << 16) / p0z : qa;                        /* (lim - 1) / p0z */
    qa = qa < qb ? qa : qb;
    return (tg_real)(qa < (int64_t)TG_REAL_MAX / 2 ? qa : (int64_t)TG_REAL_MAX / 2);
}
#endif
#else
static inline int wide_far(tgi_wide dx, tgi_wide dy, tgi_wide dz) { (void)dx; (void)dy; (void)dz; return 0; }
#endif

/* |d| of a tgi_wide: in float an and in the float registers (tgi_abs_bits,
 * raster/pack.h) where the conditional negation takes a compare and three
 * mask operations. */
static inline tgi_wide wide_abs(tgi_wide d)
{
#if TG_FIXED
    return d < 0 ? -d : d;
#else
    return tgi_abs_bits(d);
#endif
}

/* |d|^2 = tgi_wide_dot(d, d): in Q16.16 the exact sum of squares is >= 0
 * and below 3.0001 2^60 (each |d_i| <= HBIL_FAR, just over 2^30, after
 * wide_far): it fits int64 and tgi_shr_round. */
#define wide_len2(dx, dy, dz) tgi_wide_dot(dx, dy, dz, dx, dy, dz)

/* tgi_wide_mul(a, b) <= tgi_wide_mul(c, d) (the horizon test).  In Q16.16
 * the rounding (tgi_shr_round) does not decrease: a b <= c d exactly
 * implies the rounded products compare so too, and only a b > c d needs
 * them rounded (equal when both round to one value).  The products stay
 * below 2^62 (sample_cos's bounds: dot |dot|, h|h| |d|^2 < 2^46 as
 * integers times 2^16). */
#if TG_FIXED
static inline int wide_products_le(tgi_wide a, tgi_wide b, tgi_wide c, tgi_wide d)
{
    /* past p <= q, p > q and the rounded p >= the rounded q (the shift
     * is monotone): <= is ==, the bits above 2^16 of p + 2^15 and q + 2^15
     * equal, their xor below 2^16 (one compare for the two shifts) */
    const int64_t p = a * b, q = c * d;
    const int64_t half = (int64_t)1 << (TG_FRAC_BITS - 1);
    return p <= q || (uint64_t)((p + half) ^ (q + half)) < ((uint64_t)1 << TG_FRAC_BITS);
}
#else
#define wide_products_le(a, b, c, d) (tgi_wide_mul(a, b) <= tgi_wide_mul(c, d))
#endif

/* The cosine dot / |d| of a sample that passed the horizon test, clamped
 * to [-1, 1], and 1 / |d| (in Q16.16 |d| < 128 here: d, dot and len2 = |d|^2 fit
 * tg_real).  Float: one reciprocal square root, the two-step one of
 * core/real.h and a third Newton step (tg_sqrt and two divisions before).
 * Q16.16: the same reciprocal square root in integers, Q30 with its
 * exponent (1/|d| > 1/128 in Q16.16 holds too few bits for the cosine as
 * a product, the Q30 one 22 or more), rel. error 3.2e-6 (core/real.h):
 * the cosine within 0.71 of a unit of 2^-16 of dot / |d| (tg_sqrt and two
 * divisions before, whose rounded |d| erred up to 2^-9 relative at the
 * shortest). */
#if TGI_Q16_WIDE
typedef tgi_wide hbil_cos_arg;   /* Q16.16: dot and len2 unnarrowed (sample_cos) */
#else
typedef tg_real hbil_cos_arg;
#endif
#if !TG_FIXED
/* Float: the cosine's clamp to [-1, 1] at its top only.  horizon_cos is
 * called only past sample_cos's horizon test, dot|dot| > hs_tie |d|^2 with
 * hs_tie = h|h| + HBIL_TIE >= -1 + HBIL_TIE (every horizon h is a clamped
 * cosine or side_init's, |h| <= 1, so h|h| >= -1), so a negative dot has
 * dot^2 < (1 - 2^-12)(1 + 2^-22) |d|^2 (the products' and the sum's
 * roundings) and dot / |d| > -0.99988; r's three Newton steps err far
 * below 1e-4, so dot r > -1 and the bottom never acts (a NaN passes as it
 * did: NaN > 1 is false).  Cornell 160x120 2 frames: float 481.66M ->
 * 481.12M.  Q16.16 keeps tg_clamp: the same proof holds (the test's exact
 * integers; halved past |d| >= 128 their ratio moves by < 3.1e-5, and the
 * cosine lies within 0.71 units of 2^-16 of dot / |d| < 65530 units), but
 * the top alone took 656.78M -> 657.34M (gcc 12's registers in the march) */
static inline tg_real cos_top(tg_real x) { return x > TG_ONE ? TG_ONE : x; }
#endif
#if defined(__GNUC__) && TG_FIXED   /* float: gcc's own choice, 0.16% fewer (cornell 160x120) */
__attribute__((always_inline))
#endif
static inline tg_real horizon_cos(hbil_cos_arg dot, hbil_cos_arg len2, tg_real *inv_len)
{
#if TG_FIXED
    /* len2 = L 2^-16 with 0 < L < 2^31 (a sample with d = 0 has dot = 0
     * and fails the horizon test; sample_cos halves a longer d): L 2^e = X 2^30, X in [1, 4), e even
     * in [0, 30], so 1/|d| = rsqrt(X) 2^(e/2 - 7) = y 2^(e/2 - 37) for y
     * = rsqrt(X) in Q30 (<= 2^30); |dot| < 2^24, dot y < 2^54.  The two
     * roundings tgi_shr_round(y, s + 1) and tgi_shr_round(dot y, s + 17),
     * s = 20 - e/2 in [5, 20], with the one variable shift s first: the
     * offsets 2^s and 2^(s + 16) are multiples of 2^s, so floor((x + 2^(s
     * + k)) 2^-(s + k + 1)) = floor((floor(x 2^-s) + 2^k) 2^-(k + 1)) (the
     * shift floors), the same integers (not the three shift counts and two
     * offsets computed per rise; compiling for size the two calls of
     * tgi_shr_round, 24 bytes shorter in the AO-only program) */
    const int e = tgi_clz32_nz((uint32_t)len2) & ~1;
    const int64_t y = (int64_t)tgi_rsqrt_q30_fast((uint64_t)(uint32_t)len2 << e);
#if TGI_Q16_WIDE
    const int s = 20 - e / 2;
    *inv_len = (tg_real)(((y >> s) + 1) >> 1);                        /* <= 256: 2^24 */
    return tg_clamp((tg_real)(((dot * y >> s) + 65536) >> 17), TG_R(-1.0f), TG_ONE);
#else
    *inv_len = (tg_real)tgi_shr_round(y, 21 - e / 2);
    return tg_clamp((tg_real)tgi_shr_round(dot * y, 37 - e / 2), TG_R(-1.0f), TG_ONE);
#endif
#else
    float r = tgi_rsqrt_fast(len2);
    r = r * (1.5f - 0.5f * len2 * r * r);
    *inv_len = r;
    return cos_top(dot * r);
#endif
}

/* Whether the depths za > 0 and zb of two neighbours across the minor
 * axis are close enough to interpolate between (HBIL_LERP_MAX_RATIO; zb
 * > 0 follows), compared in tgi_wide, so a 4 z beyond TG_REAL_MAX (where
 * tg_mul saturated) gives the same answer. */
static inline int depths_close(tg_real za, tg_real zb)
{
#if TG_FIXED
    /* tgi_wide_mul(TG_R(4), z) = (4 2^16 z) 2^-16 rounded = 4 z exactly;
     * for integers 4 zb > za is zb > floor(za / 4) = za >> 2 (tinygi.h
     * tgi_shift_floors), the same answer in 32 bits: a 32-bit core takes
     * that form (no 64-bit products; Cortex-M3 cornell 160x120: -1.9% of
     * the Q16.16 frame), x86-64 the 64-bit one (the 32-bit form: +0.4%,
     * gcc 12's register choices in the march), za's test first (zb's
     * first, gcc 12 laid the lerp out of line after it, a jump more a
     * sample: cornell 160x120 Q16.16 647.79M -> 646.22M) */
#if TGI_CORE64
    return (tgi_wide)za * 4 > zb && (tgi_wide)zb * 4 > za;
#else
    return zb > (za >> 2) && za > (zb >> 2);
#endif
#else
    /* one test, of the smaller: with za > 0, 4 zb > za holds where zb >=
     * za and 4 za > zb where za > zb, so the test that can fail is the
     * smaller's times 4 against the larger; the same answer for every zb
     * (a NaN: both forms false; zb <= 0: min zb, false; infinities: 4 inf
     * > inf false in both; 4 min rounds to infinity only at min >= 2^126,
     * where both hold).  Cornell 160x120 float 501.96M -> 499.89M (the
     * fine runs' copies too) */
    return tgi_wide_mul(HBIL_LERP_MAX_RATIO, tg_min(za, zb)) > tg_max(za, zb);
#endif
}

/* Whether lerp_inverse_depth gives za at once for equal depths, and the
 * march tests them first (below): in both number types, not compiling for
 * size.  On 32-bit cores too (Q16.16's other form below: zd = 0, fzd =
 * small_mul(f, 0) = 0, tgi_div_nonneg(za, za) = 2^16 exactly, z = za):
 * make cross-count, cornell 160x120 second frame, Cortex-M3 Q16.16 541.7M
 * -> 507.9M, RV32IMAC Q16.16 708.8M -> 652.0M (a 64-bit division in
 * software skipped) */
#define HBIL_EQUAL_DEPTHS (!TG_OUTLINE_HELPERS)

/* The depth at fraction f in [0, 1) from za to zb, 1/z linear:
 * z = za + f (zb - za) za / (zb - f (zb - za)).  0 < za, zb <=
 * TG_REAL_MAX, close (depths_close): zb - za fits, f zd fits, zb - f zd
 * lies between them (> 0), so za / (zb - f zd) < 4 (tgi_div_pos) and its
 * product with f zd stays below 2^50 in tgi_wide: the same depth as
 * tg_mul and tg_add wherever they would not have saturated.  The sum is
 * za zb / (zb - f zd) > 0 within its roundings, a few ulps and the
 * quotient's 2^-17 times |f zd| < 2^15 (2^14 ulps in all), far above
 * TG_REAL_MIN: in Q16.16 only its top is tested (tgi_wide_real's other
 * test never acts). */
static inline tg_real lerp_inverse_depth(tg_real za, tg_real zb, tg_real f)
{
#if TGI_Q16_WIDE && TGI_CORE64
    /* the same integers in int64 throughout (no narrowing and widening
     * between the steps): zd, f zd fit tg_real, zb - f zd lies in (0,
     * TG_REAL_MAX] (tgi_div_nonneg's unsigned 64-bit division), the
     * quotient below 4 (2^18); cornell 160x120 Q16.16 768.64M -> 761.52M
     * (gcc 12: fewer conversions, and the march's registers).  z lies
     * between za and zb, roundings included, so it is not saturated: f in
     * [0, 2^16 - 1] raw and the shifts floor (tgi_shr_round).  zb >= za:
     * fzd = (f zd + 2^15) >> 16 <= zd (zd - zd/2^16 + 1/2 < zd + 1), so
     * den >= za and ratio <= floor(2^16 + 1/2) = 2^16 (1.0), fzd ratio in
     * [0, fzd 2^16], and its rounding <= fzd: z <= za + zd = zb.  zb < za:
     * fzd in [zd, 0], den in [zb, za], ratio >= 0, fzd ratio <= 0 rounds
     * to <= 0: z <= za.  (Without the test z > TG_REAL_MAX: cornell 160x120 Q16.16
     * 694.86M -> 690.48M) */
    const int64_t zd = (int64_t)zb - za, fzd = tgi_wide_mul(f, zd);
    uint64_t den;
    int64_t ratio;
    /* Equal depths (a plane seen along a row or a column: a floor's rows,
     * a wall's columns, a wall facing the camera) give za without the
     * division: fzd = (f 0 + 2^15) >> 16 = 0, den = zb = za, ratio =
     * floor((za 2^16 + floor(za / 2)) / za) = 2^16 (floor(za / 2) < za),
     * z = za + (0 + 2^15 >> 16) = za.  The march tests za == zb before
     * depths_close too (its call), which gcc 12 joins to this one.
     * Cornell 160x120, 2 frames, Q16.16 637.38M -> 621.13M, --gi-quarter
     * 312.08M -> 308.08M; columns, with fewer such pairs, 270.13M ->
     * 270.44M (the test a sample; here alone, without the march's,
     * cornell 626.85M, columns 270.71M). */
    if (zd == 0) return za;
    den = (uint64_t)((int64_t)zb - fzd);
    ratio = (int64_t)((((uint64_t)za << 16) + (den >> 1)) / den);
    return (tg_real)((int64_t)za + tgi_wide_mul(fzd, ratio));
#else
    tg_real zd = (tg_real)((tgi_wide)zb - za), fzd = small_mul(f, zd), ratio;
    tgi_wide z;
#if HBIL_EQUAL_DEPTHS
    /* equal depths (as Q16.16's above): zd = +0, fzd = f 0 = +0 (f >= 0
     * finite), za / (zb - 0) = 1 exactly, z = za + 0 1 = za, finite (za
     * <= TG_REAL_MAX), so tgi_wide_real gives za.  Cornell 160x120, 2
     * frames, float 471.57M -> 464.52M, --gi-quarter 227.25M -> 225.41M;
     * columns 198.10M -> 199.81M, --gi-quarter 156.27M -> 156.63M (the
     * test a sample: march_side, refine_fine, fine_follow); in sum over
     * the four the least of the forms measured: zd == 0 as the test took
     * cornell 469.96M, the test at the march's call alone 466.70M and
     * columns 199.49M (sum +2.9M), without the march's test before
     * depths_close 467.73M and 199.33M (sum +3.7M) */
    if (za == zb) return za;
#endif
    ratio = tgi_div_nonneg(za, small_sub(zb, fzd));   /* za > 0 */
    z = (tgi_wide)za + tgi_wide_mul(fzd, ratio);
#if TG_FIXED
    return z > TG_REAL_MAX ? TG_REAL_MAX : (tg_real)z;
#else
    return tgi_wide_real(z);
#endif
#endif
}

/* The depth of pixel j of g beside pixel i whose depth za is: in Q16.16
 * equal stored words give za without decoding the second (76% of cornell's
 * interpolated samples: a plane along a row or a column); different words
 * are decoded (they may still round to za) */
#if HBIL_EQUAL_DEPTHS && TG_FIXED
#define DEPTH_BESIDE(g, i, j, za) ((g)->store.depth[j] == (g)->store.depth[i] ? (za) : tgi_gv_depth(g, j))
#else
#define DEPTH_BESIDE(g, i, j, za) tgi_gv_depth(g, j)
#endif

/* The march's depths_close(za, zb = z) for za > 0 (and fine_run's):
 * equal depths first (close: za < 4 za), which lerp_inverse_depth then
 * gives at once (HBIL_EQUAL_DEPTHS; gcc 12 joins the two tests; in
 * fine_run too, cornell 160x120, 2 frames, Q16.16 621.13M -> 617.82M,
 * float 464.52M -> 462.10M, columns +0.06M and +0.17M).  A macro: as an
 * inline function gcc 12 laid the march out otherwise (cornell 160x120,
 * 2 frames, Q16.16 621.13M -> 622.16M, float 464.52M -> 463.63M) */
#if HBIL_EQUAL_DEPTHS
#define DEPTHS_EQUAL_OR_CLOSE(za, zb, z) (((zb) = (z)) == (za) || depths_close(za, zb))
#else
#define DEPTHS_EQUAL_OR_CLOSE(za, zb, z) depths_close(za, (zb) = (z))
#endif

/* refine_fine's per-slice values in hbil_march (march_axis): float not
 * compiling for size (march_side sets the march per side there).  Cornell
 * 160x120, 2 frames: float 481.66M -> 480.58M; Q16.16, whose floor of the
 * extent is a product and a shift, took 654.42M -> 655.45M (tgi_hbil_rows
 * +3.05M, refine_fine -1.1M), so computes them per side as before */
#define HBIL_FINE_SLICE (!TG_FIXED && !TG_OUTLINE_HELPERS && !TG_NO_FINE_HORIZON)

/* A run of samples along a side: march_side's, or march_between's
 * (march_run), which march_samples reads in place of copies of the whole
 * hbil_march. */
/* The fields' order: the minor coordinates and the integers alternate;
 * minor, dminor, ox, a in a row were stored by gcc 12 as one SSE2 vector
 * put together from four registers (~4 instructions more a side than four
 * scalar stores: cornell 160x120, 2 frames, Q16.16 643.67M -> 643.20M,
 * float 472.94M -> 472.84M). */
typedef struct hbil_run {
    tg_real minor;
    int a;
    tg_real dminor;
    int da;
    tg_real ox;                    /* ox: the minor offset before the first sample */
    int n;
    int back;                      /* o dir: sample k stands k da - back from the pixel */
} hbil_run;
/* The march's per-side constants (march_side).  In Q16.16 the ones
 * sample_cos takes into tgi_wide products and sums are stored widened
 * (hbil_mreal: the same values), so the march reads them as they are used,
 * not as tg_real widened at each sample (cornell 160x120, 2 frames:
 * Q16.16 677.39M -> 675.26M, march_side 316.38M -> 314.97M; float the
 * same code). */
#if TGI_Q16_WIDE
typedef tgi_wide hbil_mreal;
#else
typedef tg_real hbil_mreal;
#endif
typedef struct hbil_march {
    hbil_mreal p0x, p0y, p0z;
    tg_real z;
    hbil_mreal inv_z, wox, woy, woz;
#if HBIL_Q_NEAR
    hbil_mreal q_near;             /* hbil_ctx's */
    hbil_mreal q_span;             /* 2 q_near (< 2^31), sample_cos's one compare of qw + q_near */
#endif
    tgi_wide r2;                   /* the 3D radius squared, march units */
    tg_real slope, extent;         /* minor per major pixel; the march's extent, major pixels */
    int smaj, smin, bmax;
    hbil_run run;                  /* the side's own samples */
#if HBIL_FINE_SLICE
    /* refine_fine's values of the slice, set once a slice (march_axis,
     * with a fine image), not a side: the pixel in the fine image (fa0
     * along the major axis, fb0 the minor), the fine and the sub-image
     * pixels to the screen's edge against and along the major axis
     * (froom, fsub: [0] toward -a, [1] toward +a), floor(extent r) (fext),
     * the first sample's fine pixel r (m - o) (ffirst), the long reach */
    int fa0, fb0, froom[2], fsub[2], fext, ffirst, flong;
#endif
} hbil_march;

/* The sample at screen offset (sx, sy) from the pixel (image pixels, y
 * up) and depth z1 (> 0), for the side whose horizon is h with h|h| +
 * HBIL_TIE = hs_tie: its cosine from w_o when it lies within the 3D radius
 * and above the horizon, else HBIL_NOT_ABOVE; d, inv_len: its view-space
 * offset d = s + q (P0 + s), q = (z1 - z) / z, in tgi_wide (see above;
 * in Q16.16 halved until |d| < 128 when longer), and 1 / |d|: d inv_len is
 * the unit vector toward the sample.  One copy for the march and the fine samples when compiling for
 * size (TG_OUTLINE_HELPERS), inlined into each otherwise (and into the
 * march alone without the fine samples, TG_NO_FINE_HORIZON). */

#define HBIL_NOT_ABOVE TG_R(-2.0f)
#define HBIL_BEYOND TG_R(-3.0f)    /* not above either: beyond the 3D radius */
#if TG_OUTLINE_HELPERS && !TG_NO_FINE_HORIZON
#define HBIL_SAMPLE_INLINE HBIL_NOINLINE
#elif defined(__GNUC__)
#define HBIL_SAMPLE_INLINE inline __attribute__((always_inline))
#else
#define HBIL_SAMPLE_INLINE inline
#endif
static HBIL_SAMPLE_INLINE tg_real sample_cos(const hbil_march *mr, tg_real z1, tg_real sx, tg_real sy, tg_real h, tg_real hs_tie,
                          tgi_wide d[3], tg_real *inv_len)
{
#if HBIL_Q_NEAR
    /* tg_mul's product, rounded, tested against q_near before it is
     * saturated: |qw| <= q_near (<= TG_REAL_MAX / 2, march_q_near) leaves
     * tgi_sat64 nothing to do, and tgi_sat64(qw) lies within q_near exactly
     * when qw does, so the test is the one on the saturated q (its range
     * test only past q_near: cornell 160x120 -0.50% of the Q16.16 frame) */
    const int64_t qw = tgi_shr_round((int64_t)small_sub(z1, mr->z) * mr->inv_z, TG_FRAC_BITS);
    tgi_wide q;
#else
    const tg_real q = tg_mul(small_sub(z1, mr->z), mr->inv_z);   /* z1, z in (0, TG_REAL_MAX] */
#endif
    tgi_wide dx, dy, dz, len2, dot;
    tg_real cn;
#define HBIL_SAMPLE_D() \
    (dx = (tgi_wide)sx + tgi_wide_mul((tgi_wide)mr->p0x + sx, q), \
     dy = (tgi_wide)sy + tgi_wide_mul((tgi_wide)mr->p0y + sy, q), \
     dz = tgi_wide_mul(mr->p0z, q))
#if HBIL_Q_NEAR
    /* within q_near no component is beyond HBIL_FAR (march_q_near): wide_far's tests only past it.
     * One branch for the saturation and the test, d computed in each arm
     * (as a conditional q and a second test of q_far, gcc 12 tested it
     * twice: cornell 160x120 Q16.16 770.99M -> 768.64M) */
    if (!HBIL_Q16_LIKELY((uint64_t)qw + (uint64_t)mr->q_near <= (uint64_t)mr->q_span)) {
        q = tgi_sat64(qw);
        HBIL_SAMPLE_D();
        if (wide_far(dx, dy, dz)) return HBIL_BEYOND;
    } else {
        q = qw;   /* kept in int64 (no narrowing to widen again): 761.52M -> 759.90M */
        HBIL_SAMPLE_D();
    }
#else
    HBIL_SAMPLE_D();
    if (wide_far(dx, dy, dz)) return HBIL_BEYOND;                             /* beyond the 3D radius */
#endif
#undef HBIL_SAMPLE_D
    len2 = wide_len2(dx, dy, dz);
    if (len2 > mr->r2) return HBIL_BEYOND;                                    /* beyond the 3D radius */
    dot = tgi_wide_dot(dx, dy, dz, mr->wox, mr->woy, mr->woz);
    /* cos(theta) > horizon, without a division: dot|dot| > h|h| |d|^2 */
    if (HBIL_F_LIKELY(wide_products_le(dot, wide_abs(dot), hs_tie, len2))) return HBIL_NOT_ABOVE;
#if TG_FIXED
    if (len2 >= ((tgi_wide)1 << 30)) {   /* |d| >= 128: |d|^2 beyond tg_real; the cosine and the direction are scale-free */
        int k = 1;
        while ((len2 >> 2 * k) >= ((tgi_wide)1 << 30)) k++;
        dx = tgi_shr_round(dx, k); dy = tgi_shr_round(dy, k); dz = tgi_shr_round(dz, k);
        dot = tgi_shr_round(dot, k);
        len2 = tgi_shr_round(len2, 2 * k);
    }
#endif
    /* HBIL sec. 1.3; d, dot, len2 fit tg_real here: Q16.16 passes them
     * unnarrowed (cornell 160x120 -0.07%), a build for size as tg_real
     * (tgi_wide there: the AO-only program 8 bytes longer) */
    cn = horizon_cos((hbil_cos_arg)dot, (hbil_cos_arg)len2, inv_len);
    if (HBIL_F_UNLIKELY(cn <= h)) return HBIL_NOT_ABOVE;
    d[0] = dx; d[1] = dy; d[2] = dz;
    return cn;
}


/* The unit direction d / |d| of a sample that raised the horizon, and
 * h|h| + HBIL_TIE of its cosine h: |d_i| <= |d| (< 128 in Q16.16, as
 * sample_cos leaves it) and 1/|d| <= 256 give products of at most 1 (plus
 * rounding), |h| <= 1: small_mul and small_add (tg_mul and tg_add would
 * not saturate). */
static inline tg_vec3 sample_dir(const tgi_wide d[3], tg_real inv_len)
{
#if TGI_Q16_WIDE
    /* d's components fit tg_real (|d_i| < 128 units: the same integers
     * unnarrowed), their products small_mul's without the narrowing and
     * widening again (a sign extension a component a rise) */
    return tg_v3((tg_real)tgi_wide_mul(d[0], inv_len), (tg_real)tgi_wide_mul(d[1], inv_len), (tg_real)tgi_wide_mul(d[2], inv_len));
#else
    return tg_v3(small_mul((tg_real)d[0], inv_len), small_mul((tg_real)d[1], inv_len), small_mul((tg_real)d[2], inv_len));
#endif
}
/* h|h|, |h| as tgi_abs_fast (raster/pack.h: in float by the sign bit,
 * one and, where tg_abs is a compare and a select): at h = -0 the product
 * is a zero of the other sign, and hs is read only as horizon_tie's
 * hs + HBIL_TIE, HBIL_TIE for either zero; h is never a NaN (the clamped
 * tangent-plane cosine, or horizon_cos's of a finite d with |d| > 0) */
static inline tg_real horizon_sq(tg_real h) { return small_mul(h, tgi_abs_fast(h)); }
static inline tg_real horizon_tie(tg_real hs) { return small_add(hs, HBIL_TIE); }

/* The samples of one side; major_x is a constant in each of the two
 * copies (MARCH_SAMPLES), so the axis choice costs nothing per sample.
 * Compiling for size (TG_OUTLINE_HELPERS, tinygi.h) there is one copy, out
 * of line, that tests major_x at each use: the same arithmetic, the same
 * samples and horizons. */
#if TG_OUTLINE_HELPERS
HBIL_NOINLINE static void march_samples(
#else
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void march_samples(
#endif
                                 const hbil_ctx *c, const hbil_slice *sl, int side, hbil_side *sd,
                                 const hbil_march *mr, const hbil_run *run, const int major_x)
{
    const tgi_gview *const g = c->g;
    const tgi_rgb *const rad = c->rad;
    const int smaj = mr->smaj, bmax = mr->bmax, da = run->da, n = run->n;
    /* the pixel indices in ptrdiff_t (< 2^26: TG_MAX_IMAGE_SIDE squared),
     * not int widened at each of the two depth reads: cornell 160x120
     * Q16.16 759.35M -> 757.97M, float 536.31M -> 535.98M (a 32-bit
     * core's ptrdiff_t is its int) */
    const ptrdiff_t smin = mr->smin;
    const tg_real dminor = run->dminor;
    const int back = run->back;
    /* the horizon in a local (stored back at each rise): sd's fields are
     * stored through a pointer the compiler cannot tell from g's, so it
     * reloaded sd->h at every sample */
    tg_real minor = run->minor, ox = run->ox, h = sd->h, hs_tie = horizon_tie(sd->hs);
#if TGI_Q16_WIDE
    /* Q16.16: the rise's horizon, its square and its position in locals
     * too, stored to sd once after the samples (nothing in the loop reads
     * them from sd: gather_rise reads the band's fields, sample_cos takes
     * h and hs_tie).  Cornell 160x120 -0.11% of the Q16.16 frame; in float
     * the same cost 0.3% more (the march's registers), so there as before. */
    tg_real hs = sd->hs;
    int peak_a = sd->peak_a;
#endif
    /* the major offset k da - back of sample k, stepped (whole pixels < 2^14: exact).
     * Q16.16 (not for size): where a sample uses it, as a - a_origin (a = run->a + k
     * da), one register fewer stepped in the loop (cornell 160x120: Q16.16
     * 772.15M -> 771.52M); float computed so took 0.1% more (the integer's
     * conversion), there it is stepped. */
#if TGI_Q16_WIDE
    /* ox = minor - mo, not stepped: in Q16.16 both are integers stepped
     * by the same dminor without rounding or saturation (|minor|, |ox| <
     * 2^14 px), so their difference stays mo, the pixel's own minor
     * coordinate (march_side's run, and march_run's: minor - ox kept),
     * below 2^13 px (cornell 160x120 Q16.16 688.84M -> 688.24M) */
    const tg_real mo = minor - ox;
    const int a_origin = run->a + back;
#define HBIL_SMAJOR() small_from_int(a - a_origin)
#else
    tg_real smajor = small_from_int(-back);
    const tg_real dmajor = small_from_int(da);
#define HBIL_SMAJOR() smajor
#endif
    /* k_rose: the last rise's k (-1 before the first: none); sample k
     * comes right after a rise when k - 1 == k_rose, tested at a rise only
     * (a flag, rose, cleared at every sample and kept in memory: cornell
     * 160x120, 2 frames, float 528.46M -> 527.40M, Q16.16 751.54M ->
     * 750.58M; k == k_after, k_after = k + 1 at a rise, took Q16.16 to
     * 753.49M, the march's registers).  Not compiling for size, the
     * samples are counted by a itself, up to a_end = run->a + n da (|n da|
     * <= extent + m < 2^15: no overflow), without k: the first sample is a
     * == run->a + da, and a_rose, the last rise's a (run->a - da before the
     * first, which no sample's a - da is: da != 0), stands for k_rose
     * (cornell 160x120, 2 frames, Q16.16 695.60M -> 694.86M; float, after
     * depths_close's one test, 499.89M -> 499.62M, before it 0.07% more).
     * Float keeps a_next = a_rose + da instead (run->a before the first
     * rise, which no sample's a is), the test a == a_next: gcc 12 no
     * longer keeps a copy of the last a at every sample (cornell 160x120,
     * 2 frames, float 481.12M -> 480.77M; Q16.16 so took 656.79M ->
     * 658.09M). */
#if !TG_OUTLINE_HELPERS
#if TG_FIXED
    int a = run->a, a_rose = run->a - da;
#else
    int a = run->a, a_next = run->a;
#endif
    const int a_end = run->a + n * da;   /* n >= 0: march_steps' (extent >= 0, samples >= 1) cut at kmax >= 0, or march_run's k > 0 */
#define HBIL_FIRST() (a == run->a + da)
#if TG_FIXED
#define HBIL_AFTER_RISE() (a - da == a_rose)
#define HBIL_ROSE() (a_rose = a)
#else
#define HBIL_AFTER_RISE() (a == a_next)
#define HBIL_ROSE() (a_next = a + da)
#endif
#else
    int k, a = run->a, k_rose = -1;
#define HBIL_FIRST() (k == 1)
#define HBIL_AFTER_RISE() (k - 1 == k_rose)
#define HBIL_ROSE() (k_rose = k)
#endif
    ptrdiff_t sa_major = (ptrdiff_t)a * smaj;
#if !TG_OUTLINE_HELPERS
    while (a != a_end) {
#else
    for (k = 1; k <= n; k++) {
#endif
        int b0;
        ptrdiff_t sa;
        tg_real f, z1, sx, sy, za, zb, cn, inv_len;
        tgi_wide d[3];
        minor = (tg_real)((tgi_wide)minor + dminor);           /* |minor|, |ox| < 2^14 px: no saturation */
#if TGI_Q16_WIDE
        ox = minor - mo;
#else
        ox = (tg_real)((tgi_wide)ox + dminor);
#endif
#if !TGI_Q16_WIDE
        smajor = (tg_real)((tgi_wide)smajor + dmajor);
#endif
        a += da;
        sa_major += (ptrdiff_t)da * smaj;
#if TGI_Q16_WIDE
        {   /* floor_frac_small's integer as an arithmetic shift of the
             * 64-bit value (tinygi.h tgi_shift_floors), index arithmetic
             * in 64 bits without a sign extension (cornell 160x120 Q16.16
             * 690.48M -> 688.84M) */
            const ptrdiff_t b0w = (ptrdiff_t)((int64_t)minor >> TG_FRAC_BITS);
            f = minor & 0xFFFF;
            b0 = (int)b0w;
            sa = sa_major + b0w * smin;
        }
#else
        b0 = floor_frac_small(minor, &f);
        sa = sa_major + b0 * smin;
#endif
        /* both neighbours surface (depth > 0 is not sky) and close: 1/z
         * interpolated linearly, 1/z = (1-f)/za + f/zb  <=>
         * z = za + f (zb - za) za / (zb - f (zb - za)) */
        if (HBIL_LIKELY((unsigned)b0 < (unsigned)(bmax - 1)                 /* b0 and b0 + 1 inside */
            && (za = tgi_gv_depth(g, sa)) > 0 && DEPTHS_EQUAL_OR_CLOSE(za, zb, DEPTH_BESIDE(g, sa, sa + smin, za)))) {
            z1 = lerp_inverse_depth(za, zb, f);
        } else {
            int bn = f < TG_R(0.5f) ? b0 : b0 + 1, sn;
            if (bn < 0 || bn >= bmax) break;                    /* the slice leaves the image */
            sn = (int)(bn == b0 ? sa : sa + smin);
            if (tgi_gv_is_sky(g, sn) || tgi_gv_depth(g, sn) <= 0) continue;  /* sky never occludes */
            z1 = sample_depth_edge(c, g, major_x, a, b0, f, (int)sa, sn);
            if (z1 <= 0) continue;
        }
        sx = major_x ? HBIL_SMAJOR() : ox;
        sy = major_x ? tg_neg(ox) : tg_neg(HBIL_SMAJOR());
#if TG_OUTLINE_HELPERS   /* compiling for size: read where used (8 bytes fewer) */
        cn = sample_cos(mr, z1, sx, sy, sd->h, hs_tie, d, &inv_len);
        (void)h;
#else
        cn = sample_cos(mr, z1, sx, sy, h, hs_tie, d, &inv_len);
#endif
        if (HBIL_Q16_LIKELY(cn <= HBIL_NOT_ABOVE)) {
#if !TG_NO_FINE_HORIZON
            /* the side's first sample (refine_fine); beyond is 0 from
             * side_init and set nowhere else, so only a sample beyond the
             * radius tests k (a): the horizon test's failures (most samples)
             * go on without it */
            if (HBIL_Q16_UNLIKELY(cn == HBIL_BEYOND) && HBIL_FIRST() && run == &mr->run) sd->beyond = 1;
#endif
            continue;
        }
        h = cn;
#if TGI_Q16_WIDE
        peak_a = a;
        hs = horizon_sq(cn);
        hs_tie = horizon_tie(hs);
#else
        sd->h = cn;
        sd->peak_a = a;
        sd->hs = horizon_sq(cn);
        hs_tie = horizon_tie(sd->hs);
#endif
        if (NEAR_FIELD(c))
            GATHER_RISE(c, sl, sd, side, cn, sample_dir(d, inv_len),
                        g, rad, f < TG_R(0.5f) ? sa : sa + smin, HBIL_AFTER_RISE(), 1);   /* the nearest pixel; right after a rise */
        HBIL_ROSE();
    }
#if TGI_Q16_WIDE
    sd->h = h;
    sd->peak_a = peak_a;
    sd->hs = hs;
#endif
#undef HBIL_SMAJOR
#undef HBIL_FIRST
#undef HBIL_AFTER_RISE
#undef HBIL_ROSE
}

/* march_samples along the major axis major_x: a copy per axis, or the one copy */
#if TG_OUTLINE_HELPERS
#define MARCH_SAMPLES(c, sl, side, sd, mr, run, major_x) march_samples(c, sl, side, sd, mr, run, major_x)
#else
#define MARCH_SAMPLES(c, sl, side, sd, mr, run, major_x) \
    do { \
        if (major_x) march_samples(c, sl, side, sd, mr, run, 1); \
        else march_samples(c, sl, side, sd, mr, run, 0); \
    } while (0)
#endif

/* Samples at p0 + k step pixels from the pixel, k = 1..n, along the
 * march *mr that march_side set up. */
#if TG_OUTLINE_HELPERS
static void march_run(
#else
static HBIL_INLINE void march_run(   /* into march_between and march_near: the call and its set-up cost ~25 instructions a run */
#endif
                      const hbil_ctx *c, const hbil_slice *sl, int side, hbil_side *sd, const hbil_march *mr,
                      int major_x, int p0, int step, int n)
{
    hbil_run r;
    const int dir = mr->run.da < 0 ? -1 : 1;
    r.n = n;
    r.da = step * dir;
    r.back = -p0 * dir;
    r.a = mr->run.a + mr->run.back - r.back;
    r.ox = small_mul_int(mr->slope, p0);                 /* as in march_side */
    r.minor = small_add(small_sub(mr->run.minor, mr->run.ox), r.ox);
    r.dminor = small_mul_int(mr->slope, step);
    MARCH_SAMPLES(c, sl, side, sd, mr, &r, major_x);
}

/* More samples on a side marched in steps of m > 1 pixels (*mr as
 * march_side left it).  Between two samples lies what they skip: the
 * horizon of a wall or a floor that ends (its silhouette against the sky
 * or a farther surface, or the screen's edge) is at its last pixel, on
 * average m / 2 pixels past the last sample on it, and the maximum over a
 * subset of the pixels is at or under the maximum over them all: the AO
 * comes out too bright (by 0.03 on average on builtin:cornell).  So the
 * screen's last pixel within the extent is a sample, and the m - 1 pixels
 * after the sample that set the horizon are marched one by one. */
#if !TG_NO_FINE_HORIZON
/* Whether the march *mr (with a fine image) has refine_fine's long reach:
 * past HBIL_LONG_REACH. */
static inline int march_long_reach(const hbil_ctx *c, const hbil_march *mr) { return mr->extent > c->long_reach; }
#endif

/* Pixels from the side's pixel to the screen's edge along its march (*mr
 * as march_side set it up). */
static inline int march_room(const hbil_ctx *c, const hbil_march *mr, int major_x)
{
    const int a0 = mr->run.a + mr->run.back;
    return mr->run.da > 0 ? (major_x ? c->g->width : c->g->height) - 1 - a0 : a0;
}

/* The side's pixels p + 1 .. p + k one by one (march_run), k cut at the
 * screen's edge (room, march_room) and at the march's extent.  Inlined
 * into march_between and march_near (gcc kept it out of line: a call and
 * a six-register prologue a run; cornell 160x120 -0.5% of the frame in
 * float, -0.3% in Q16.16, .text +6.4 KB, +6.7 KB; the size builds keep
 * march_run out of line). */
static HBIL_INLINE void march_pixels(const hbil_ctx *c, const hbil_slice *sl, int side, hbil_side *sd, const hbil_march *mr,
                                int major_x, int room, int p, int k)
{
    if (k > room - p) k = room - p;
    /* p + k <= room < 2^13 (the image's side): small_from_int, without
     * Q16.16's saturation test */
    if (small_from_int(p + k) > mr->extent) k = EXTENT_TO_INT(mr->extent) - p;   /* the extent in [0, 2^14] (march_steps) */
    if (k > 0) march_run(c, sl, side, sd, mr, major_x, p, 1, k);
}

HBIL_NOINLINE static void march_between(const hbil_ctx *c, const hbil_slice *sl, int side, hbil_side *sd,
                                        const hbil_march *mr, int major_x)
{
    const int dir = mr->run.da < 0 ? -1 : 1, m = mr->run.da * dir, a0 = mr->run.a + mr->run.back;
    const int room = march_room(c, mr, major_x);
    const int last = mr->run.n * m - mr->run.back * dir;                 /* the last sample's distance */
    /* room > 0: a side with no sample (n = 0, the offset put the first
     * past the edge) has last = -o, and a pixel on the edge would sample
     * itself (test open_plane_long_radius) */
    if (room > 0 && last < room && small_from_int(room) <= mr->extent)   /* room < 2^13: small_from_int */
        march_run(c, sl, side, sd, mr, major_x, last, room - last, 1);
    if (sd->peak_a >= 0) march_pixels(c, sl, side, sd, mr, major_x, room, (sd->peak_a - a0) * dir, m - 1);
}

#if !TG_NO_FINE_HORIZON /* left out with TG_NO_FINE_HORIZON=1 (tinygi.h "FEATURE SWITCHES") */
/* With a long reach (refine_fine), the k sub-image pixels between the
 * pixel and the side's first sample, one by one, before the march's own
 * samples (so the rises come in order along the side): there a wall seen
 * nearly edge-on rises beside the pixel.  refine_fine took every fine
 * pixel of that span, r (m - o) - 1 of them (r fine pixels a sub-image
 * pixel, m the step, o the start's offset), a cost that grew with the
 * step; now it takes the r - 1 before the first sub-image pixel, and
 * these k = m - o - 1 are sub-image samples, refined around the peak as
 * the march's are.  AO against the ray-traced reference unchanged within
 * 0.0002 (RMSE and bias, the four built-ins at 160x120 and 320x240, with
 * and without --gi-quarter); cornell 320x240 -2.0% of the frame's
 * instructions in float, -3.3% in Q16.16 (README "Performance"). */
HBIL_NOINLINE static void march_near(const hbil_ctx *c, const hbil_slice *sl, int side, hbil_side *sd,
                                     const hbil_march *mr, int major_x, int k)
{
    march_pixels(c, sl, side, sd, mr, major_x, march_room(c, mr, major_x), 0, k);
}

/* The highest of refine_fine's samples. */
typedef struct hbil_fine_best {
    tg_real h, hs;          /* the highest horizon the fine samples found, h|h| */
    tgi_wide d[3];          /* its offset (march units) */
    tg_real inv_len;        /* 1 / |d| */
    int si;                 /* its pixel in the fine image; -1: none above the side's */
    int t;                  /* its distance in fine pixels (kept by a run with a stride) */
} hbil_fine_best;

/* The samples of the fine image t = los[k] .. his[k] - 1 (k < runs, runs
 * not empty, in order) fine pixels from the pixel along the major axis
 * (toward dir), on the slice's line: 1/z
 * interpolated across the minor axis between two close surface pixels,
 * else the nearest pixel's tangent plane, as in march_samples; each kept
 * in *best when it is above best's horizon.  A fine pixel is 1 /
 * fine_ratio of the march's unit (the sub-image's pixel); (fa0, fb0) is
 * the pixel in the fine image.  The major index is stepped, the minor
 * offset taken anew at each t (slope t, as one product), so every sample
 * is the one a sample taken alone would be.  mode (a constant at each
 * call): HBIL_FINE_EVERY takes every pixel of the runs; HBIL_FINE_FOLLOW
 * follows the pixel's surface from t = 1 (refine_fine), interpolating only
 * between neighbours on one surface and ending at a silhouette
 * (HBIL_EDGE_SLOPE); HBIL_FINE_CLIMB ends a run at its first pixel that
 * does not raise the horizon (fine_climb).  stride (a constant at each
 * call): every stride-th pixel of the runs, t = lo, lo + stride, ... up to
 * hi, not included (a negative stride runs down).  Inlined into
 * refine_fine's calls (its set-up, once for all the runs, costs as much as
 * a sample), one copy when compiling for size. */
enum { HBIL_FINE_EVERY, HBIL_FINE_FOLLOW, HBIL_FINE_CLIMB };
#if TG_OUTLINE_HELPERS
#define HBIL_FINE_INLINE HBIL_NOINLINE
#elif defined(__GNUC__)
#define HBIL_FINE_INLINE inline __attribute__((always_inline))
#else
#define HBIL_FINE_INLINE inline
#endif
static HBIL_FINE_INLINE void fine_run(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr, int major_x,
                                      int fa0, int fb0, const int *los, const int *his, int runs, int dir, int mode,
                                      int stride)
{
    const int follow = mode == HBIL_FINE_FOLLOW, climb = mode == HBIL_FINE_CLIMB;
    const tgi_gview *fg = c->fine;
    const int bmax = major_x ? fg->height : fg->width;
    const size_t smaj = (size_t)(major_x ? fg->pixel_stride : fg->row_stride);
    const size_t smin = (size_t)(major_x ? fg->row_stride : fg->pixel_stride);
    const size_t dmaj = (dir > 0 ? smaj : (size_t)0 - smaj) * (size_t)stride;   /* modulo 2^N: the sums are the indices */
    const tg_real slope = mr->slope, inv_r = c->inv_fine_ratio;
    /* t dir / r, the major offset in the march's units, stepped: multiples
     * of 1/4 or 1/8 below 2^14, exact in both types; small_mul_int, in
     * Q16.16 the integer product small_mul(small_from_int(i), 1/r) gave
     * (it rounded a multiple of 2^16), float's code the same */
#if TGI_Q16_WIDE
    /* the screen's y runs down, the march's up: with minor x (major y) the
     * offset's y is -t dir / r, stepped as such (ys = -1), and with major x
     * its y the minor's -minor / r, as minor times -1/r: the same integers
     * as negating tm and minor (-(a b) = a (-b), -(a + b) = (-a) + (-b)),
     * two negations a sample fewer (float's the same values, but its frame
     * took +0.1%, and compiling for size the one copy's tests of major_x:
     * kept as they were) */
    const int ys = major_x ? 1 : -1;
    const tg_real inv_r_minor = major_x ? tg_neg(inv_r) : inv_r;
#else
    const int ys = 1;
#endif
    const tg_real dtm = small_mul_int(inv_r, dir * stride * ys);
    tg_real h = best->h, hs_tie = horizon_tie(best->hs);
    int run;
    for (run = 0; run < runs; run++) {
        const int lo = los[run], hi = his[run];
        int t, fa = fa0 + lo * dir;
        size_t ia = (size_t)fa * smaj;
        tg_real tm = small_mul_int(inv_r, lo * dir * ys);   /* t dir / r, times ys */
        tg_real zc = mr->z;   /* follow: the depth of the last sample on the pixel's surface */
        for (t = lo; stride > 0 ? t < hi : t > hi; t += stride, fa += dir * stride, ia += dmaj, tm = small_add(tm, dtm)) {
            /* |slope| <= 1, t and the fine pixels below 2^14, times 1/4 or 1/8: small_mul */
            const tg_real minor = small_mul_int(slope, t);
            tg_real f, z1, za, zb, sx, sy, inv_len, cn;
            const int b0 = floor_frac_small(minor, &f), fb = fb0 + b0;
            size_t si;
            tgi_wide d[3];
            if ((unsigned)fb >= (unsigned)bmax) {                           /* the slice leaves the image */
                if (climb) break;
                continue;
            }
            si = ia + (size_t)fb * smin;
            za = tgi_gv_depth(fg, si);
            if (fb + 1 < bmax && za > 0 && DEPTHS_EQUAL_OR_CLOSE(za, zb, DEPTH_BESIDE(fg, si, si + smin, za))   /* as in march_samples */
                && (!follow || tg_abs(tg_sub(za, zb)) <= tg_mul(za, c->fine_edge))) {   /* not across a silhouette */
                z1 = lerp_inverse_depth(za, zb, f);
            } else {                                                        /* as in march_samples */
                /* sky (a zero word) reads as depth 0 in both types
                 * (pack.h), so march_samples' test, sky or depth <= 0, is
                 * depth <= 0: the nearest's depth, za already read when it
                 * is si (cornell 160x120, 2 frames: float 520.18M ->
                 * 518.20M, Q16.16 723.31M -> 721.02M; fewer loads and,
                 * in Q16.16, conversions) */
                const int nb = f >= TG_R(0.5f);
                size_t sn = nb ? si + smin : si;
                if ((nb && fb + 1 >= bmax)                                  /* outside the image */
                    || (nb ? tgi_gv_depth(fg, sn) : za) <= 0                /* sky never occludes */
                    || (z1 = sample_depth_edge(c, fg, major_x, fa, fb, f, (int)si, (int)sn)) <= 0) {
                    if (climb) break;
                    continue;
                }
                si = sn;
            }
            if (follow) {   /* a silhouette ends the surface */
                if (tg_abs(tg_sub(z1, zc)) > tg_mul(zc, c->fine_edge)) break;
                zc = z1;
            }
            /* fine pixels to the march's units: times 1/4 or 1/8, exact */
#if TGI_Q16_WIDE
            sx = major_x ? tm : small_mul(minor, inv_r_minor);
            sy = major_x ? small_mul(minor, inv_r_minor) : tm;
#else
            sx = major_x ? tm : small_mul(minor, inv_r);
            sy = major_x ? small_mul(tg_neg(minor), inv_r) : tg_neg(tm);
#endif
            cn = sample_cos(mr, z1, sx, sy, h, hs_tie, d, &inv_len);
            if (cn <= HBIL_NOT_ABOVE) {
                if (climb) break;
                continue;
            }
            h = cn;
            best->h = cn;
            best->hs = horizon_sq(cn);
            hs_tie = horizon_tie(best->hs);
            best->d[0] = d[0]; best->d[1] = d[1]; best->d[2] = d[2];
            best->inv_len = inv_len;
            best->si = (int)si;
            if (stride > 1) best->t = t;   /* refine_fine_sparse's: what lies beside it */
        }
    }
}

/* The span t = lo .. hi - 1 (lo odd) of a fine image HBIL_SPARSE_RATIO or
 * more times finer than the sub-image: its odd pixels, then, when one of
 * them raised best's horizon, the two beside the highest (within the
 * span).  With --gi-quarter on builtin:cornell, the 7 fine pixels between
 * the pixel and its first sub-image pixel became 4 and at most 2 more: AO
 * against the ray-traced reference unchanged to 0.0001 (RMSE and bias, the
 * four built-ins at 160x120 and 320x240; without the two beside, cornell
 * 160x120 0.0316 / +0.0096 -> 0.0321 / +0.0099), the quarter run 1.4%
 * cheaper in float, 2.5% in Q16.16.  Out of line (once a side at most). */
HBIL_NOINLINE static void refine_fine_sparse(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr,
                                             int major_x, int fa0, int fb0, int lo, int hi, int dir)
{
    const tg_real h = best->h;
    int los[2], his[2], n = 0;
    if (lo >= hi) return;
    fine_run(c, best, mr, major_x, fa0, fb0, &lo, &hi, 1, dir, HBIL_FINE_EVERY, 2);
    if (best->h == h) return;
    if (best->t - 1 >= lo) { los[n] = best->t - 1; his[n++] = best->t; }
    if (best->t + 1 < hi) { los[n] = best->t + 1; his[n++] = best->t + 2; }
    if (n > 0) fine_run(c, best, mr, major_x, fa0, fb0, los, his, n, dir, HBIL_FINE_EVERY, 1);
}

/* fine_run's one run t = lo .. hi - 1 following the pixel's surface: out
 * of line (rare: refine_fine's register use stays that of before). */
HBIL_NOINLINE static void fine_follow(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr, int major_x,
                                      int fa0, int fb0, int lo, int hi, int dir)
{
    fine_run(c, best, mr, major_x, fa0, fb0, &lo, &hi, 1, dir, HBIL_FINE_FOLLOW, 1);
}

/* The fine pixels around the peak's sample t0, lo <= t < hi, climbing: up
 * from t0 + 1 while each raises the horizon, then down from t0 - 1 alike.
 * Near the peak the horizon along the fine pixels rises to an edge and
 * falls past it, so the climb ends past the highest, where taking every
 * pixel of the span (the r - 1 after t0 and, on a long reach, the r - 1
 * before it: 3 each with the 4x4 interleave) finds none higher: AO against
 * the ray-traced reference unchanged to 0.0001 (RMSE and bias, the four
 * built-ins at 160x120 and 320x240, both number types); cornell 320x240
 * -1.4% of the frame's instructions in float, -2.2% in Q16.16.  Not for
 * --gi-quarter's 8-times finer image, where climbing cut spans short
 * (cornell 160x120 bias +0.0096 -> +0.0108). */
#if TG_OUTLINE_HELPERS
HBIL_NOINLINE static void fine_climb(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr, int major_x,
                                     int fa0, int fb0, int t0, int lo, int hi, int dir)
#else   /* into fine_climb_x and fine_climb_y, below */
static HBIL_INLINE void fine_climb(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr, int major_x,
                                   int fa0, int fb0, int t0, int lo, int hi, int dir)
#endif
{
    int from = t0 + 1, to = hi;
    if (from < to) fine_run(c, best, mr, major_x, fa0, fb0, &from, &to, 1, dir, HBIL_FINE_CLIMB, 1);
    from = t0 - 1;
    to = lo - 1;
    if (from > to) fine_run(c, best, mr, major_x, fa0, fb0, &from, &to, 1, dir, HBIL_FINE_CLIMB, -1);
}
#if !TG_OUTLINE_HELPERS
/* Out of line, a copy per axis as MARCH_SAMPLES (the one copy tested
 * major_x at each sample: cornell 160x120 -0.34% of the frame in both
 * types, .text +2 KB float, +4 KB Q16.16). */
HBIL_NOINLINE static void fine_climb_x(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr,
                                       int fa0, int fb0, int t0, int lo, int hi, int dir)
{
    fine_climb(c, best, mr, 1, fa0, fb0, t0, lo, hi, dir);
}
HBIL_NOINLINE static void fine_climb_y(const hbil_ctx *c, hbil_fine_best *best, const hbil_march *mr,
                                       int fa0, int fb0, int t0, int lo, int hi, int dir)
{
    fine_climb(c, best, mr, 0, fa0, fb0, t0, lo, hi, dir);
}
#endif

/* The interleaved kernel marches a 4x4 sub-image, whose pixels are 4
 * pixels of the image it is taken from apart (8 full-resolution pixels
 * with --gi-quarter; the fine image is the full-resolution one): the
 * fine pixels between its samples are never looked at.  Where the
 * horizon is highest that matters: the last pixel of a wall or a ceiling
 * that ends against the sky or a farther surface is on average 1.5 fine
 * pixels past the last sample on it, and one that runs off the screen is
 * highest at the screen's last pixel, up to 3 fine pixels past the
 * sub-image's.  A maximum over a subset of the pixels is at or under the
 * maximum over them all, so the AO came out too bright everywhere the
 * horizon is such an edge (builtin:cornell at 160x120, AO against the
 * ray-traced reference: +0.030 on average; without interleaving +0.008).
 * So the fine pixels after the sample that set the horizon (up to the
 * next sub-image pixel) and the fine image's last pixel within the
 * march's extent are samples too.
 *
 * A long reach (a march past a quarter of the image's smaller side,
 * HBIL_LONG_REACH: a room-wide radius, as builtin:cornell's, whose
 * horizons are walls running across the screen) also takes the fine
 * pixels before the first sub-image pixel (march_near marches the
 * sub-image pixels up to the first sample), where a wall seen nearly
 * edge-on rises beside the pixel (a room's corners at the screen's edges;
 * the back wall beside a block), and those after the sub-image pixel before the
 * peak's sample, where a horizon that peaks between two samples (an
 * edge) lies when the later sample set it: cornell's AO against the
 * ray-traced reference at 160x120, --gi-quarter +0.016 -> +0.009, every
 * pixel +0.012 -> +0.008.  A short reach (an object's radius) does not:
 * there the upsample's near horizon (gi/resample.c) stands for the first
 * pixels, and more of them deepen what one depth layer overstates (a
 * silhouette taken as infinitely thick): the pixels before the first
 * sample at every reach took --gi-quarter on builtin:spheres at 320x240
 * from -0.010 to -0.015, columns at 160x120 from +0.001 to -0.015.
 *
 * Except where the side's first sample lies beyond the 3D radius
 * (hbil_side.beyond): the horizon is the highest of the slice's samples
 * within the radius (HBIL sec. 1, figure 3; the radius is the gather's),
 * and on a surface that runs from the pixel out past the radius it is its
 * last pixel within it, here before the first sample.  A floor seen at a
 * grazing angle crosses the radius within a sub-image pixel: on
 * builtin:columns at 160x120 the back wall's pixels 1 to 3 above its
 * crease with the floor see their first samples on the floor 1.8 away at
 * radius 1.5, and the floor within it went unseen (AO too bright by up to
 * 0.26 on a pixel: RMSE 0.064 against the ray-traced AO, 0.051 without
 * the interleave; now 0.052).  So then the fine pixels before the first sample are taken
 * while they continue the pixel's surface (HBIL_EDGE_SLOPE): not past a
 * silhouette, nor interpolated across one, which one depth layer would
 * take as infinitely thick (the floor beside builtin:spheres' spheres). */
HBIL_NOINLINE static void refine_fine(const hbil_ctx *c, const hbil_pixel *px, const hbil_slice *sl, int side,
                                      hbil_side *sd, const hbil_march *mr, int major_x)
{
    const tgi_gview *fg = c->fine;
    const int dir = mr->run.da < 0 ? -1 : 1, a0 = mr->run.a + mr->run.back, r = c->fine_ratio;
#if HBIL_FINE_SLICE   /* march_axis's, the same values (why float only: at HBIL_FINE_SLICE) */
    const int fa0 = mr->fa0, fb0 = mr->fb0;
    const int room = mr->froom[dir > 0], sub_room = mr->fsub[dir > 0];
    const int tmax = mr->fext < room ? mr->fext : room;
    const int long_reach = mr->flong, first = mr->ffirst;
    (void)px;
#else
    const int fa0 = r * a0 + (major_x ? c->fine_i : c->fine_j);
    const int fb0 = r * (major_x ? px->y : px->x) + (major_x ? c->fine_j : c->fine_i);
    const int room = dir > 0 ? (major_x ? fg->width : fg->height) - 1 - fa0 : fa0;       /* fine pixels to the edge */
    const int sub_room = dir > 0 ? (major_x ? c->g->width : c->g->height) - 1 - a0 : a0;
#if TGI_Q16_WIDE
    /* tg_mul(extent, tg_from_int(r)) saturated, floored: below */
    const int64_t ext_floor = ((int64_t)mr->extent * r) >> 16;                          /* fine pixels */
#elif TG_FIXED
    /* tg_mul(extent, tg_from_int(r)): the raw product e r 2^16 is a
     * multiple of 2^16, its rounding shift exact: e r, saturated */
    const tg_real ext = tgi_sat64((int64_t)mr->extent * r);                              /* fine pixels */
#else
    const tg_real ext = tg_mul(mr->extent, tg_from_int(r));                            /* fine pixels */
#endif
    const int long_reach = march_long_reach(c, mr);
    const int first = r * (mr->run.da - mr->run.back) * dir;   /* the first sample's fine pixel */
    /* the screen's edge (room) and the extent (small_from_int(t) <= ext:
     * t <= floor(ext), ext >= 0) end every run; in float floor(ext) is
     * tg_to_int's without its NaN and saturation tests (floor_small): the
     * extent is the reach (at most HBIL_MAX_RADIUS_UNITS = 2^14, tg_min's
     * bound, which a NaN takes too) times |u| <= 1, so 0 <= ext <= 2^14 r
     * here (cornell 160x120: -0.2% of the float frame; Q16.16's
     * tg_to_int is the floor alone) */
#if TGI_Q16_WIDE
    /* Q16.16 (not for size): ext's floor from the unsaturated product,
     * without the test of ext < 0: e r >= 0 (0 <= ext, above; and a
     * negative floor would end every run as -1 does: each starts at 1 or
     * more), and where tgi_sat64 would cut e r (raw at or past 2^31) the
     * floor, 2^15 - 1 or more either way, is cut to room < 2^14 */
    const int tmax = ext_floor < room ? (int)ext_floor : room;
#elif TG_FIXED
    const int tmax = ext < 0 ? -1 : tg_to_int(ext) < room ? tg_to_int(ext) : room;
#else
    const int tmax = floor_small(ext) < room ? floor_small(ext) : room;   /* 0 <= ext: no test of ext < 0, as Q16.16's */
#endif
#endif /* HBIL_FINE_SLICE */
    const int climb = sd->peak_a >= 0 && r < HBIL_SPARSE_RATIO;   /* the peak's span by fine_climb */
    hbil_fine_best best;
    int t0 = -1, span[2][2] = { { 0, 0 }, { 0, 0 } };   /* fine pixels [span[k][0], span[k][1]) */
    /* Nothing to take (most sides of a short reach: 68% on builtin:columns
     * 320x240): without a peak, a long reach or a first sample beyond the
     * radius every span below is empty (no climb, no sparse run, no
     * follow) but the screen's last pixel, {room} when room > r sub_room,
     * cut at tmax: not empty exactly when room <= tmax too.  (Tested in
     * march_side before the call, or in a small function of its own
     * calling this one, it cost more on builtin:cornell than it saved:
     * march_side's registers, a second call.) */
#if !TG_OUTLINE_HELPERS   /* compiling for size: no test (36 bytes) */
    if (sd->peak_a < 0 && !long_reach && !sd->beyond && !(room > r * sub_room && room <= tmax)) return;
#endif
    best.h = sd->h;
    best.hs = sd->hs;
    best.si = -1;
    best.d[0] = best.d[1] = best.d[2] = 0;   /* read only with si >= 0, but gcc cannot tell */
    best.inv_len = 0;
    if (sd->peak_a >= 0) {
        /* the fine pixels after the peak's sample t0 up to the next
         * sub-image pixel, t0 + r, and with a long reach those after the
         * sub-image pixel before it too, from t0 - r (or the first) on */
        t0 = r * (sd->peak_a - a0) * dir;
        span[1][0] = !long_reach ? t0 + 1 : t0 - r + 1 > 1 ? t0 - r + 1 : 1;
        span[1][1] = t0 + r;
    }
    if (long_reach) {   /* and those before the first sample the peak's span does not take */
        span[0][0] = 1;
        span[0][1] = t0 >= 0 && span[1][0] < first ? span[1][0] : first;
        if (span[0][1] > r) span[0][1] = r;   /* up to the first sub-image pixel: march_near takes the rest */
    }
    if (climb) {   /* the peak's span, climbing */
        const int end = span[1][1] <= tmax ? span[1][1] : tmax + 1;
#if TG_OUTLINE_HELPERS
        fine_climb(c, &best, mr, major_x, fa0, fb0, t0, span[1][0], end, dir);
#else
        if (major_x) fine_climb_x(c, &best, mr, fa0, fb0, t0, span[1][0], end, dir);
        else fine_climb_y(c, &best, mr, fa0, fb0, t0, span[1][0], end, dir);
#endif
    }
    {
        /* the runs in the order of before: the peak's span without t0
         * (unless climbed), the span before the first sample, the screen's
         * last pixel */
        int lo[4], hi[4], n = 0;
#if TG_OUTLINE_HELPERS   /* compiling for size: the four runs' bounds, then a loop keeping the runs that are not empty */
        int k;
        lo[0] = span[1][0]; hi[0] = climb ? lo[0] : t0 >= 0 && t0 < span[1][1] ? t0 : span[1][1];
        lo[1] = t0 >= 0 && t0 + 1 > span[1][0] ? t0 + 1 : span[1][0]; hi[1] = climb ? lo[1] : span[1][1];
        lo[2] = span[0][0]; hi[2] = r >= HBIL_SPARSE_RATIO ? span[0][0] : span[0][1];   /* empty: refine_fine_sparse's */
        lo[3] = room; hi[3] = room > r * sub_room ? room + 1 : room;
        for (k = 0; k < 4; k++) {   /* the runs that are not empty, in order */
            const int end = hi[k] <= tmax ? hi[k] : tmax + 1;
            if (lo[k] >= end) continue;
            lo[n] = lo[k];
            hi[n++] = end;
        }
#else
        /* the same runs without the loop and its arrays' reloads
         * (cornell 160x120: -1.2% of the frame in float, -0.75% in Q16.16): the first two are empty
         * when climbed (hi = lo) and without a peak (t0 < 0: span[1] is
         * { 0, 0 }, lo = 0 = hi), the third one at HBIL_SPARSE_RATIO and
         * without a long reach (span[0] is { 0, 0 }) */
#define FINE_RUN_ADD(l, h) do { const int l_ = (l), e_ = (h) <= tmax ? (h) : tmax + 1; \
                                if (l_ < e_) { lo[n] = l_; hi[n++] = e_; } } while (0)
        if (!climb && t0 >= 0) {
            FINE_RUN_ADD(span[1][0], t0 < span[1][1] ? t0 : span[1][1]);
            FINE_RUN_ADD(t0 + 1 > span[1][0] ? t0 + 1 : span[1][0], span[1][1]);
        }
        if (r < HBIL_SPARSE_RATIO && long_reach) FINE_RUN_ADD(span[0][0], span[0][1]);
        if (room > r * sub_room) FINE_RUN_ADD(room, room + 1);
#undef FINE_RUN_ADD
#endif
        if (n > 0) {
#if TG_OUTLINE_HELPERS
            fine_run(c, &best, mr, major_x, fa0, fb0, lo, hi, n, dir, HBIL_FINE_EVERY, 1);
#else       /* a copy per axis, as MARCH_SAMPLES */
            if (major_x) fine_run(c, &best, mr, 1, fa0, fb0, lo, hi, n, dir, HBIL_FINE_EVERY, 1);
            else fine_run(c, &best, mr, 0, fa0, fb0, lo, hi, n, dir, HBIL_FINE_EVERY, 1);
#endif
        }
    }
    if (r >= HBIL_SPARSE_RATIO && span[0][0] < span[0][1])
        refine_fine_sparse(c, &best, mr, major_x, fa0, fb0, span[0][0], span[0][1] <= tmax ? span[0][1] : tmax + 1, dir);
    if (!long_reach && sd->beyond) {   /* the pixels before a first sample beyond the radius, on the pixel's surface */
        int lo = 1, hi = first <= tmax ? first : tmax + 1;
        if (lo < hi) fine_follow(c, &best, mr, major_x, fa0, fb0, lo, hi, dir);
    }
    if (best.si < 0) return;
    /* one raise to the highest: the band it closes lies within a few
     * pixels of the sub-image's samples, gathered from that pixel */
    sd->h = best.h;
    sd->hs = best.hs;
    if (NEAR_FIELD(c))
        GATHER_RISE(c, sl, sd, side, best.h,
                    sample_dir(best.d, best.inv_len),
                    fg, c->fine_rad, best.si, 0, 0);
}

#endif /* !TG_NO_FINE_HORIZON */

/* March one side (+1 along D, -1 against) and raise its horizon.  Indices
 * run along the major axis a (stride smaj) and the minor axis b (smin);
 * the sample's screen offset s (image pixels, y up) gives the view-space
 * offset d = s + q (P0 + s), q = (z1 - z) / z, P0 = the pixel's position
 * (X, Y, ppu) / step (see top). */
#if !TG_OUTLINE_HELPERS   /* compiling for size, march_side sets them per side (shorter) */
/* What a slice's two sides share, set once a slice (march_axis): the
 * major axis, the slope (minor per major pixel, side +1's), the march's
 * step m, count n and start offset o, the major direction of side +1, the
 * image's side along the major axis (amax) and the pixel's minor
 * coordinate b (set in march_side per side, they cost ~50 instructions a
 * side: two divisions, three tg_to_int); and in the pixel's hbil_march
 * (mt) the slice's fields: the strides, bmax and the extent.  The march
 * itself is mt: each side sets its own fields in it (the slope and the
 * run), not a copy (cornell 160x120, 2 frames: a copy of the struct a side
 * took float +0.9M, Q16.16 +0.2M; the fields set a side, +3.4M and +3.2M) */
typedef struct hbil_axis {
    int major_x, m, n, o, dir, amax;
    tg_real slope, b;
    hbil_march *mt;         /* the pixel's march (march_template), the slice's fields set */
} hbil_axis;

static void march_axis(const hbil_ctx *c, const hbil_pixel *px, tg_real ux, tg_real uy, hbil_axis *ax, hbil_march *mt)
{
    const tgi_gview *g = c->g;
    const int major_x = tg_abs(ux) >= tg_abs(uy);
    const tg_real umaj = major_x ? tg_abs(ux) : tg_abs(uy);
    int o;
    ax->major_x = major_x;
    ax->amax = major_x ? g->width : g->height;
    ax->b = small_from_int(major_x ? px->y : px->x);
    ax->mt = mt;
    mt->smaj = major_x ? g->pixel_stride : g->row_stride;
    mt->smin = major_x ? g->row_stride : g->pixel_stride;
    mt->bmax = major_x ? g->height : g->width;
    /* |minor| <= umaj: |slope| <= 1 (tgi_div_pos, umaj > 0 or 1) */
    ax->slope = tgi_div_pos(major_x ? uy : ux, umaj == 0 ? TG_ONE : umaj);
    ax->dir = (major_x ? ux : uy) < 0 ? -1 : 1;
    /* the reach in [0, 2^14] (radius >= 0, HBIL_MAX_RADIUS_UNITS) times
     * |u| <= 1: small_mul */
    mt->extent = small_mul(px->reach, umaj);
    ax->m = march_steps(c, mt->extent, &ax->n);
    o = EXTENT_TO_INT(small_mul(px->jitter, small_from_int(ax->m)));     /* sample k at k m - o pixels; jitter in [0, 1) */
    ax->o = o < 0 || o >= ax->m ? 0 : o;
#if HBIL_FINE_SLICE
    if (c->fine) {   /* refine_fine's values of the slice: its operations of before, once a slice */
        const tgi_gview *fg = c->fine;
        const int r = c->fine_ratio, a0 = major_x ? px->x : px->y;
        mt->fa0 = r * a0 + (major_x ? c->fine_i : c->fine_j);
        mt->fb0 = r * (major_x ? px->y : px->x) + (major_x ? c->fine_j : c->fine_i);
        mt->froom[0] = mt->fa0;                                                    /* fine pixels to the edge */
        mt->froom[1] = (major_x ? fg->width : fg->height) - 1 - mt->fa0;
        mt->fsub[0] = a0;
        mt->fsub[1] = ax->amax - 1 - a0;
        mt->fext = floor_small(tg_mul(mt->extent, tg_from_int(r)));   /* 0 <= ext <= 2^14 r (refine_fine) */
        mt->ffirst = r * (ax->m - ax->o);   /* r (da - back) dir = r (m dir - o dir) dir */
        mt->flong = march_long_reach(c, mt);
    }
#endif
}

/* The march's fields every side of the pixel shares, set once a pixel
 * (pixel_run; march_side set them per side, 4 sides a pixel with the
 * default 2 slices).  The products are small (small_mul): screen
 * positions < 2^13 times 1 / step <= 1. */
static void march_template(const hbil_ctx *c, const hbil_pixel *px, hbil_march *mt)
{
    mt->p0x = small_mul(px->X, c->inv_step);
    mt->p0y = small_mul(px->Y, c->inv_step);
    mt->p0z = c->p0z;
#if HBIL_Q_NEAR
    mt->q_near = c->q_near;
    mt->q_span = 2 * (hbil_mreal)c->q_near;   /* its doubling once a pixel, not at each sample (two instructions fewer) */
#endif
    mt->z = px->z;
    mt->inv_z = px->inv_z;
    mt->r2 = px->radius_units2;
    mt->wox = px->wo.x; mt->woy = px->wo.y; mt->woz = px->wo.z;
}
#endif

#if TG_OUTLINE_HELPERS
static void march_side(const hbil_ctx *c, const hbil_pixel *px, const hbil_slice *sl,
                       tg_real ux, tg_real uy, int side, hbil_side *sd)
#else
static void march_side(const hbil_ctx *c, const hbil_pixel *px, const hbil_slice *sl,
                       const hbil_axis *ax, int side, hbil_side *sd)
#endif
{
#if TG_OUTLINE_HELPERS
    const tgi_gview *g = c->g;
    const int w = g->width, h = g->height, rs = g->row_stride, ps = g->pixel_stride;
    const int major_x = tg_abs(ux) >= tg_abs(uy);
    const int amax = major_x ? w : h;
    const tg_real umaj = major_x ? tg_abs(ux) : tg_abs(uy);
    /* |minor| <= umaj: |slope| <= 1 (tgi_div_pos, umaj > 0 or 1) */
    tg_real slope = tgi_div_pos(major_x ? uy : ux, umaj == 0 ? TG_ONE : umaj);
    int dir = ((major_x ? ux : uy) < 0 ? -1 : 1) * side;
    int m, kmax, o;
    hbil_march mr_, *const mr = &mr_;
    mr->smaj = major_x ? ps : rs;
    mr->smin = major_x ? rs : ps;
    mr->bmax = major_x ? h : w;
    /* the per-side products and sums below are small (small_mul): screen
     * positions < 2^13 and ppu times 1/step <= 1, the reach in [0, 2^14]
     * (radius >= 0, HBIL_MAX_RADIUS_UNITS) times |u| <= 1, offsets below
     * 2^14 times |slope| <= 1 */
    mr->p0x = small_mul(px->X, c->inv_step);
    mr->p0y = small_mul(px->Y, c->inv_step);
    mr->p0z = c->p0z;
    mr->z = px->z;
    mr->inv_z = px->inv_z;
    mr->r2 = px->radius_units2;
    mr->wox = px->wo.x; mr->woy = px->wo.y; mr->woz = px->wo.z;
    if (side < 0) slope = tg_neg(slope);
    mr->slope = slope;
    mr->extent = small_mul(px->reach, umaj);
    m = march_steps(c, mr->extent, &mr->run.n);
    o = tg_to_int(small_mul(px->jitter, small_from_int(m)));     /* sample k at k m - o pixels */
    if (o < 0 || o >= m) o = 0;
#else
    const int major_x = ax->major_x;
    const int amax = ax->amax;
    const int dir = ax->dir * side, m = ax->m, o = ax->o;
    const tg_real slope = side < 0 ? tg_neg(ax->slope) : ax->slope;
    int kmax;
    hbil_march *const mr = ax->mt;   /* the pixel's and the slice's fields set: the side's below (offsets below 2^14 times |slope| <= 1: small) */
    mr->slope = slope;
    mr->run.n = ax->n;
#endif
    mr->run.da = m * dir;
    mr->run.a = major_x ? px->x : px->y;
    kmax = ((mr->run.da > 0 ? amax - 1 - mr->run.a : mr->run.a) + o) / m;   /* never past the screen edge */
    if (mr->run.n > kmax) mr->run.n = kmax;
    mr->run.back = o * dir;
    mr->run.a -= mr->run.back;
    mr->run.ox = small_mul_int(slope, -o);
#if TG_OUTLINE_HELPERS
    mr->run.minor = small_add(small_from_int(major_x ? px->y : px->x), mr->run.ox);
#else
    mr->run.minor = small_add(ax->b, mr->run.ox);
#endif
    mr->run.dminor = small_mul_int(slope, m);
#if !TG_NO_FINE_HORIZON
    if (c->fine && march_long_reach(c, mr) && m - o > 1) march_near(c, sl, side, sd, mr, major_x, m - o - 1);
#endif
    MARCH_SAMPLES(c, sl, side, sd, mr, &mr->run, major_x);
    if (m > 1) march_between(c, sl, side, sd, mr, major_x);
#if !TG_NO_FINE_HORIZON
    if (c->fine) refine_fine(c, px, sl, side, sd, mr, major_x);
#endif
}

static void side_init(hbil_side *sd, tg_real h, tg_real q_open, tg_real p_open)
{
#if TG_OUTLINE_HELPERS   /* compiling for size: the call is shorter */
    memset(sd, 0, sizeof *sd);
#else   /* every field set (a memset of the struct was a call to the C library's, 4 a pixel) */
    sd->beyond = 0;
    sd->lr = sd->lg = sd->lb = 0;
    sd->er = sd->eg = sd->eb = 0;
#endif
    sd->peak_a = -1;
    sd->h = h;
    sd->hs = horizon_sq(h);     /* |h| <= 1 */
    sd->q = q_open;
    sd->p_old = p_open;
}

typedef struct hbil_sums {
    tg_real occlusion;      /* sum_i AO_i(open) - AO_i */
    tg_vec3 bent_delta;     /* sum_i B_i - B_i(open), view space */
    tg_real er, eg, eb;     /* sum of L dE */
} hbil_sums;

#if TG_OUTLINE_HELPERS
static void slice_run(const hbil_ctx *c, const hbil_pixel *px, tg_real cphi, tg_real sphi, hbil_sums *acc)
#else
static void slice_run(const hbil_ctx *c, const hbil_pixel *px, hbil_march *mt, int s, tg_real cphi, tg_real sphi, hbil_sums *acc)
#endif
{
    hbil_slice sl;
#if !TG_OUTLINE_HELPERS
    hbil_axis ax;
#endif
    hbil_side front, back;
    tg_real inv_len_n, h1i, h0i, ux, uy, q1, q0, q1i, q0i, r1, r0, r1i, r0i, p1i, p0i, pf1, pf0;
    /* the frame's vectors w_x, w_y, w_o and n are unit (|component| <= 1
     * and a rounding), cos and sin at most 1: D's components below 2, n'
     * below 4, their products and sums small (small_mul, small_dot) */
    sl.d = small_v3_add(small_v3_scale(px->wx, cphi), small_v3_scale(px->wy, sphi)); /* HBIL sec. 1.2 D(phi) */
    sl.nx = small_dot(px->n, sl.d);                            /* HBIL eq. 2 */
    sl.ny = px->ndv;
    /* |n'|^2 >= ny^2 > 2^-15 (ny = n.w_o is at least HBIL_MIN_NDOTV =
     * 2^-7 over sqrt(1 + 2^-14) and a rounding, pixel_setup's bent n), and
     * below 32 (n''s components below 4): rsqrt_in_range */
    inv_len_n = rsqrt_in_range(tg_max(small_add(small_mul(sl.nx, sl.nx), small_mul(sl.ny, sl.ny)), small_mul(sl.ny, sl.ny)));
    /* horizons initialised on the tangent plane (sec. 2.1): cos = -/+
     * n_x/|n'| (|n_x| < 4 times 1/|n'| < 2^8: small_mul) */
    h1i = tg_clamp(small_mul(tg_neg(sl.nx), inv_len_n), TG_R(-1.0f), TG_ONE);
    h0i = tg_neg(h1i);
    /* Q(-c, -1) = Q(c, 1) - pi/2 and R(-c) = R(c): one fit for both sides */
    /* |Q| < 2, R <= 1/2, |n'| < 4: small */
    q1i = slice_Q(h1i, 1); q0i = small_sub(q1i, TG_HALF_PI);
    r1i = slice_R(h1i); r0i = r1i;
    p1i = small_add(small_mul(sl.nx, q1i), small_mul(sl.ny, r1i));
    p0i = small_add(small_mul(sl.nx, q0i), small_mul(sl.ny, r0i));
    side_init(&front, h1i, q1i, p1i);
    side_init(&back, h0i, q0i, p0i);
#if HBIL_REJECT_MEMO
    front.reject_memo = c->reject_memo + 2 * s;
    back.reject_memo = c->reject_memo + 2 * s + 1;
#elif !TG_OUTLINE_HELPERS
    (void)s;
#endif
    slice_screen_dir(c, px, sl.d, &ux, &uy);
#if TG_OUTLINE_HELPERS
    march_side(c, px, &sl, ux, uy, 1, &front);
    march_side(c, px, &sl, ux, uy, -1, &back);
#else
    march_axis(c, px, ux, uy, &ax, mt);   /* what the two sides share, once */
    march_side(c, px, &sl, &ax, 1, &front);
    march_side(c, px, &sl, &ax, -1, &back);
#endif
    /* Q and P at the found horizons: the near field's gather kept them
     * (gather_rise's q_new and p_new of the rise to h, P's sum the one
     * below; every rise of h gathers there, the march's and refine_fine's),
     * side_init's q_open and p_open at an unraised horizon (h1i: q1i and
     * p1i, whose r1i = slice_R(h1i); h0i: q0i and p0i, r0i = slice_R(h1i)
     * = slice_R(-h1i), c c = (-c)(-c) exactly) */
    r1 = slice_R(front.h); r0 = slice_R(back.h);
    if (NEAR_FIELD(c) || front.h == h1i) {
        q1 = front.q; pf1 = front.p_old;
    } else {
        q1 = slice_Q(front.h, 1); pf1 = small_add(small_mul(sl.nx, q1), small_mul(sl.ny, r1));
    }
    if (NEAR_FIELD(c) || back.h == h0i) {
        q0 = back.q; pf0 = back.p_old;
    } else {
        q0 = slice_Q(back.h, -1); pf0 = small_add(small_mul(sl.nx, q0), small_mul(sl.ny, r0));
    }
    /* AO_i = P(theta1) + P(theta0) (eq. 10-11 with |sin|); open minus found
     * (the slice's terms small as above: |P| < 4 2 + 4 / 2 = 10, a term
     * below 40, and the sum over at most TG_MAX_SLICES = 8 slices below
     * 320: small_add gives tg_add's value) */
    acc->occlusion = small_add(acc->occlusion, small_add(small_sub(p1i, pf1), small_sub(p0i, pf0)));
    /* eq. 5-6: n~x = Q1 + Q0, n~y = R1 + R0; B = D n~x + w_o n~y.  Small
     * (as above): |Q| < 2 and R in [0, 1/2] make the two factors below 8
     * and 2, D's components below 2 and w_o's 1, a slice's term below 18
     * and the sum over at most TG_MAX_SLICES = 8 slices below 2^8: tg_mul
     * and tg_add would not saturate (their bits, 15M fewer instructions in
     * a Q16.16 cornell 320x240 frame pair).  Only where the results take
     * a bent normal (pixel_run reads the sum under HAS_BENT alone; the
     * default colour frame writes none: its sums were wasted work) */
    if (HAS_BENT(c->out)) acc->bent_delta = small_v3_add(acc->bent_delta, small_v3_add(
        small_v3_scale(sl.d, small_sub(small_add(q1, q0), small_add(q1i, q0i))),
        small_v3_scale(px->wo, small_sub(small_add(r1, r0), small_add(r1i, r0i)))));
#if HBIL_WIDE_SUMS   /* the sides' sums unsaturated (hbil_esum), acc's in [0, TG_REAL_MAX] */
    acc->er = near_sum3_pos(acc->er, front.er, back.er);
    acc->eg = near_sum3_pos(acc->eg, front.eg, back.eg);
    acc->eb = near_sum3_pos(acc->eb, front.eb, back.eb);
#else
#if !TG_OUTLINE_HELPERS   /* compiling for size: the saturating sums alone (8 bytes shorter) */
    if (radiance_nonneg(acc->er, acc->eg, acc->eb, front.er, front.eg, front.eb)
        && radiance_nonneg(back.er, back.eg, back.eb, 0, 0, 0)) {   /* sums of gather_rise's sums */
        acc->er = near_sum3_pos(acc->er, front.er, back.er);
        acc->eg = near_sum3_pos(acc->eg, front.eg, back.eg);
        acc->eb = near_sum3_pos(acc->eb, front.eb, back.eb);
    } else
#endif
    {
        acc->er = tg_add(acc->er, tg_add(front.er, back.er));
        acc->eg = tg_add(acc->eg, tg_add(front.eg, back.eg));
        acc->eb = tg_add(acc->eb, tg_add(front.eb, back.eb));
    }
#endif
}

static void write_open(const hbil_ctx *c, int i)
{
    const tgi_gresult *out = c->out;
    tgi_gr_set_ao(out, i, TG_ONE);
    if (HAS_BENT(out)) tgi_gr_set_bent(out, i, tgi_gv_normal(c->g, i));
    if (HAS_CONE(out)) tgi_gr_set_cone(out, i, TG_HALF_PI);
    if (NEAR_FIELD(c)) tgi_gr_set_near(out, i, tg_v3(0, 0, 0));
}

tg_real tgi_hbil_block_jitter(tg_real sub_image_jitter, int bx, int by, int rot)
{
    uint32_t hsh = (uint32_t)bx * 0x8DA6B343u ^ (uint32_t)by * 0xD8163841u;
    tg_real j;
    hsh ^= hsh >> 15; hsh *= 0x2C1B3C6Du; hsh ^= hsh >> 12;
    /* the rotations' shifts: 0, 8, 4, 12, 2, 10, 6, 14 sixteenths, in rotation_rank's order */
    j = tg_add(sub_image_jitter, tg_ratio((int)(((hsh >> 28) + 2u * rotation_rank[rot & 7]) & 15u), 16));
    return j >= TG_ONE ? tg_sub(j, TG_ONE) : j;
}

static void pixel_run(const hbil_ctx *c, hbil_pixel *px, int i)
{
    const tgi_gresult *out = c->out;
    const tgi_view *v = c->v;
    hbil_sums acc;
#if !TG_OUTLINE_HELPERS
    hbil_march mt;
#endif
    int s, pat;
    tg_real ao;
    int X = px->x * c->step + c->g->offset_x, Y = px->y * c->step + c->g->offset_y;
#if TG_OUTLINE_HELPERS   /* compiling for size: the call is shorter */
    memset(&acc, 0, sizeof acc);
#else   /* every field set, as side_init (the memset was a call to the C library's a pixel) */
    acc.occlusion = 0;
    acc.bent_delta = tg_v3(0, 0, 0);
    acc.er = acc.eg = acc.eb = 0;
#endif
    pat = tgi_hbil_pattern(X >> PATTERN_SHIFT(c), Y >> PATTERN_SHIFT(c), c->p->rotation);
    px->jitter = tgi_hbil_block_jitter(c->dirs->jitter[pat], X >> 2, Y >> 2, c->p->rotation);
#if TG_OUTLINE_HELPERS
    for (s = 0; s < c->slices; s++)
        slice_run(c, px, c->dirs->cos_phi[pat][s], c->dirs->sin_phi[pat][s], &acc);
#else
    march_template(c, px, &mt);
    for (s = 0; s < c->slices; s++)
        slice_run(c, px, &mt, s, c->dirs->cos_phi[pat][s], c->dirs->sin_phi[pat][s], &acc);
#endif
    ao = tg_saturate(tg_sub(TG_ONE, tg_div(acc.occlusion, tg_from_int(c->slices))));
    tgi_gr_set_ao(out, i, ao);
    if (HAS_CONE(out)) tgi_gr_set_cone(out, i, tgi_cone_angle_from_ao(ao));   /* not eq. 12: sh.h */
    if (HAS_BENT(out)) {
        /* eq. 6: summed unnormalised over slices, normalised once (in world space) */
#if TG_OUTLINE_HELPERS   /* compiling for size: read again (shorter) */
        const tg_vec3 nw = tgi_gv_normal(c->g, i);
#else
        const tg_vec3 nw = px->nw;   /* tgi_gv_normal(c->g, i), as pixel_setup read it */
#endif
        tg_vec3 dw = tgi_v3_add(tgi_v3_add(tgi_v3_scale(v->right, acc.bent_delta.x),
                                         tgi_v3_scale(v->up, acc.bent_delta.y)),
                               tgi_v3_scale(v->forward, acc.bent_delta.z));
        tgi_gr_set_bent(out, i, tgi_v3_unit_or(tgi_v3_add(tgi_v3_scale(nw, tg_from_int(c->slices)), dw), nw));
    }
    if (NEAR_FIELD(c))   /* eq. 16-18; the receiver's (1 - F0) of eq. 19 is applied where Lo is composed */
        tgi_gr_set_near(out, i, tg_v3(tg_mul(acc.er, c->pi_over_s), tg_mul(acc.eg, c->pi_over_s),
                                      tg_mul(acc.eb, c->pi_over_s)));
}

static int clamp_slices(int slices)
{
    return slices < 1 ? 1 : slices > TG_MAX_SLICES ? TG_MAX_SLICES : slices;
}

void tgi_hbil_dirs_init(tgi_hbil_dirs *d, const tgi_hbil_params *p)
{
    const int slices = clamp_slices(p->slices);
    const tg_real pi_over_s = tg_div(TG_PI, tg_from_int(slices));
    int pat, s;
    for (pat = 0; pat < HBIL_PATTERN; pat++) {
        tg_real phi0 = tgi_hbil_slice_phi0(pat & 3, pat >> 2, slices, p->rotation);
        d->jitter[pat] = tgi_hbil_step_jitter(pat & 3, pat >> 2, p->rotation);
        for (s = 0; s < slices; s++) {
            tg_real phi = tg_add(phi0, tg_mul(pi_over_s, tg_from_int(s)));
            d->cos_phi[pat][s] = tg_cos(phi);
            d->sin_phi[pat][s] = tg_sin(phi);
        }
    }
}

/* own: the table's room when p->dirs is NULL */
static void ctx_init(hbil_ctx *c, const tgi_hbil_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                     const tgi_gresult *out, tgi_hbil_dirs *own)
{
    c->p = p;
    c->g = g;
    c->v = g->camera;
    c->rad = radiance;
    c->out = out;
    c->slices = clamp_slices(p->slices);
    c->samples = p->samples < 1 ? 1 : p->samples;
    c->step = g->step < 1 ? 1 : g->step;
    c->full_w = c->v->width;
    c->full_h = c->v->height;
    c->ppu = c->v->pixels_per_unit;
    c->inv_ppu = tg_div(TG_ONE, c->ppu);
    c->inv_step = tg_ratio(1, c->step);
    c->p0z = small_mul(c->ppu, c->inv_step);
#if HBIL_Q_NEAR
    c->q_near = march_q_near(c->full_w, c->full_h, c->step, c->p0z);
#endif
    c->pi_over_s = tg_div(TG_PI, tg_from_int(c->slices));
    c->near_field = tgi_rgb_present(radiance) && tgi_gr_has_near(out);
#if !TG_WIDE_STORAGE && !TG_NO_COLOR
    rejection_init(c, p->rejection_a, p->rejection_b);
#else
    c->rejection_a = p->rejection_a;
    c->rejection_b = p->rejection_b;
#if !TG_OUTLINE_HELPERS
    ramp_init(c);
#endif
    c->reject_fast = 0;
#endif
    c->fine = 0;
#if !TG_NO_FINE_HORIZON
    c->fine_rad = 0;
    if (p->fine && p->fine->step > 0 && g->step % p->fine->step == 0 && g->step / p->fine->step >= 4) {
        c->fine = p->fine;
        c->fine_ratio = g->step / p->fine->step;
        c->inv_fine_ratio = tg_ratio(1, c->fine_ratio);
        c->long_reach = tg_ratio(c->full_w < c->full_h ? c->full_w : c->full_h, HBIL_LONG_REACH * c->step);
        c->fine_edge = tg_div(tg_mul(HBIL_EDGE_SLOPE, tg_from_int(p->fine->step)), c->ppu);
        c->fine_i = (g->offset_x - p->fine->offset_x) / p->fine->step;
        c->fine_j = (g->offset_y - p->fine->offset_y) / p->fine->step;
        if (c->near_field && p->fine_radiance && tgi_rgb_present(p->fine_radiance)) c->fine_rad = p->fine_radiance;
    }
#endif
#if !TG_NO_GI_QUARTER
    c->pattern_shift = p->pattern_scale > 1;   /* --gi-quarter's half-resolution image */
#endif
    if (!p->dirs) tgi_hbil_dirs_init(own, p);
    c->dirs = p->dirs ? p->dirs : own;
}

void tgi_hbil_rows(const tgi_hbil_params *p, const tgi_gview *g, const tgi_rgb *radiance,
                   const tgi_gresult *out, int y0, int y1)
{
    hbil_ctx c;
    tgi_hbil_dirs own;
    hbil_pixel px;
    int x, y;
#if HBIL_UNIT_MEMO
    hbil_unit_memo memo;
#endif
#if HBIL_REJECT_MEMO
    hbil_reject_memo reject_memo[2 * TG_MAX_SLICES];
#endif
#if HBIL_UNIT_MEMO
    unit_memo_start(&memo);
    c.memo = &memo;
#endif
#if HBIL_REJECT_MEMO
    for (x = 0; x < 2 * TG_MAX_SLICES; x++) reject_memo_start(&reject_memo[x]);
    c.reject_memo = reject_memo;
#endif
    if (y0 < 0) y0 = 0;
    if (y1 > g->height) y1 = g->height;
    ctx_init(&c, p, g, radiance, out, &own);
#if TGI_REUSE_NORMAL
    tgi_normal_memo_start(&px.nm);
#endif
    for (y = y0; y < y1; y++) {
        for (x = 0; x < g->width; x++) {
            int i = (int)tgi_gv_index(g, x, y);
            px.x = x;
            px.y = y;
            if (!pixel_setup(&c, &px, i)) { write_open(&c, i); continue; }
            pixel_run(&c, &px, i);
        }
    }
}

void tgi_hbil_interleaved_rows(const tgi_hbil_params *p, const tgi_gview *k, const tgi_gbuffer *split,
                               const tgi_rgb *radiance, const tgi_gresult *out, int y0, int y1)
{
    int i, j;
#if !TG_OUTLINE_HELPERS   /* not compiling for size: the 16 calls share one table */
    tgi_hbil_dirs dirs;
    tgi_hbil_params q = *p;
    if (!q.dirs) {
        tgi_hbil_dirs_init(&dirs, p);
        q.dirs = &dirs;
    }
    p = &q;
#endif
    for (j = 0; j < 4; j++)
        for (i = 0; i < 4; i++) {
            tgi_hbil_params ps = *p;
            tgi_gview sub;
            tgi_gresult res;
            tgi_rgb src = tgi_rgb_none();
            int sw, sh;
            size_t o;
            tgi_interleave_sub_rect(k->width, k->height, i, j, &sw, &sh, &o);
            if (sw == 0 || sh == 0) continue;
            tgi_gview_packed(&sub, split, o, sw, sh, 4 * k->step, k->offset_x + i * k->step,
                             k->offset_y + j * k->step, k->camera);
            res = tgi_gresult_from(out, o);
            if (radiance) src = tgi_rgb_from(radiance, o);
            ps.pattern_scale = k->step;
            ps.fine = k;                 /* k's radiance is packed like split: not at hand */
            ps.fine_radiance = 0;
            tgi_hbil_rows(&ps, &sub, &src, &res, (y0 - j + 3) / 4, (y1 - j + 3) / 4);
        }
}
