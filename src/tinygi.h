/* SPDX-License-Identifier: MIT */
/*
 * tinygi.h - the public API of tinygi, a dependency-free C99 software
 * renderer with screen-space global illumination (Horizon-Based Indirect
 * Lighting, HBIL) for small machines.  This one header is all a program
 * needs: it includes nothing but <stddef.h>, <stdint.h> and <string.h>, and
 * compiles as C99 or C++ (extern "C").
 *
 * CONFIGURATION (one macro, set for the whole build, like luaconf.h)
 *   TG_FIXED=1   tg_real is Q16.16 fixed point (int32_t); default is float.
 *   The program and the library must agree: every public function's symbol
 *   carries the number type (tg_plan_make is tg_plan_make_f32 or
 *   tg_plan_make_q16, by the macros in "ABI" below), so a program built with
 *   the other type's header fails to LINK instead of reading garbage.
 * Feature switches TG_NO_TECHNIQUES, TG_NO_REFERENCE, TG_NO_OBJ,
 * TG_NO_BUILTIN_SCENES, TG_NO_SHADOW_MAPS, TG_NO_ENVIRONMENT,
 * TG_NO_SCENE_TEXT, TG_NO_COLOR, TG_NO_GI_QUARTER, TG_NO_TEMPORAL,
 * TG_NO_ANIMATION, TG_NO_BENT_NORMALS, TG_NO_FINE_HORIZON, TG_NO_WIDE_CLIP (0 or 1, for
 * the LIBRARY's build) leave code out of it to save flash: see "FEATURE
 * SWITCHES" below.
 *
 * MEMORY
 *   The core never allocates.  The caller hands it one arena (tg_arena) and
 *   asks how many bytes a frame plan needs (tg_plan.total_bytes) beforehand.
 *
 * CONVENTIONS (decided once, used everywhere)
 *   - Right-handed world space, +Y up by default.  The camera looks along
 *     its forward vector; view space is x right, y up, z FORWARD (positive
 *     into the screen), so a visible point has z > 0.
 *   - "depth" is linear view depth: the view-space z of the surface (the
 *     distance along the view axis, not along the ray), in world units.
 *     Sky pixels have depth 0 and the sky marker set.
 *   - The gi radius is in world units.
 *   - Normals and bent normals in AOVs are world space, unit length.
 *   - Cone apertures are in radians (half angle), in [0, pi/2].
 *   - Colour is linear RGB until the tonemapper; sRGB 8-bit only at the end.
 *   - Image rows are top to bottom, pixel (0,0) is the top-left corner and
 *     pixel centres are at (x + 0.5, y + 0.5).
 *   - Front faces are counter-clockwise seen from the front.
 *
 * ERRORS
 *   Functions return TG_OK (0) or a tg_status; a tg_error then holds a
 *   message fit to show a person, with FILE:LINE:COL when it is about input.
 *
 * ARGUMENTS: what the core checks, what the caller guarantees
 *   - Handles are checked: a NULL scene, request, plan or frame, a plan
 *     whose tg_plan_make failed (total_bytes 0) and a NULL row buffer are
 *     refused with TG_ERR_INPUT (tests/test_hostile.c).  Other pointers
 *     are not: each must point to memory of the size its comment gives,
 *     unless the comment allows NULL.  `err` may be NULL in every function
 *     (the status alone then tells).
 *   - Sizes, indices and names are checked as each function's comment says;
 *     past its range a value is refused with a status or gets the stated
 *     fallback, and nothing outside the memory given is read or written.
 *   - A handle is used only after the call that made it returned TG_OK: the
 *     scene of tg_scene_parse, the plan of tg_plan_make, the frame of
 *     tg_frame_create.  What a failed call leaves (a NULL scene or frame, a
 *     plan with total_bytes 0) is refused when passed on, as above.
 *   - Memory the core points into stays valid and untouched by the caller
 *     while it is in use: a scene's arena while the scene, its plans or its
 *     frames are used; a frame's memory while the frame is.  The core
 *     allocates nothing after tg_frame_create and keeps no pointer into
 *     text, files, requests, plans or errors after a call returns.
 *   - Memory may have any alignment: the arena aligns each block to a
 *     16-byte address.
 */
#ifndef TINYGI_H
#define TINYGI_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TG_VERSION "0.2.0"

/* ==== THE NUMBER TYPE =====================================================
 * tinygi's one number type, chosen once per build.
 *
 *   TG_FIXED undefined or 0 : tg_real is IEEE-754 float.
 *   TG_FIXED=1              : tg_real is Q16.16 fixed point in int32_t.
 *
 * Every kernel is written once against the scalar API below.  The rules:
 *  - arithmetic between tg_reals goes through tg_add/tg_sub/tg_mul/tg_div;
 *  - constants are written TG_R(0.5f) - a compile-time conversion;
 *  - fixed point multiplies in 64 bits and SATURATES to [-TG_REAL_MAX,
 *    TG_REAL_MAX]: it never wraps (a wrapped radiance is a black speck).
 *    -INT32_MAX, not INT32_MIN, is the floor so that negation is safe.
 *  - the transcendentals (tg_sqrt, tg_sin, ...) are the core's own, in
 *    src/core/real.c, each with a worst-case error documented there and
 *    measured against libm by tests/test_real.c.
 * Names with the tgi_ prefix below are static inline helpers of this
 * section, not API.
 */
#ifndef TG_FIXED
#define TG_FIXED 0
#endif
/* TG_OUTLINE_HELPERS: see "FEATURE SWITCHES" below; on at -Os. */
#ifndef TG_OUTLINE_HELPERS
#ifdef __OPTIMIZE_SIZE__
#define TG_OUTLINE_HELPERS 1
#else
#define TG_OUTLINE_HELPERS 0
#endif
#endif

#if TG_FIXED

typedef int32_t tg_real;
#define TG_FRAC_BITS 16
#define TG_ONE ((tg_real)65536)
#define TG_REAL_MAX ((tg_real)INT32_MAX)
#define TG_REAL_MIN (-TG_REAL_MAX)
#define TG_EPS ((tg_real)1) /* one ulp, 2^-16 */
/* Compile-time conversion of a float constant (rounds to nearest). */
#define TG_R(x) ((tg_real)((x) >= 0 ? (x) * 65536.0f + 0.5f : (x) * 65536.0f - 0.5f))
#define TG_NUMBER_NAME "fixed"

/* v clamped to [TG_REAL_MIN, TG_REAL_MAX], under every saturating
 * operation.  A 64-bit host tests the range in one unsigned compare (v +
 * MAX, wrapping below 0, is at most 2 MAX exactly in range): 20% fewer
 * instructions in a Q16.16 SSAO frame, 1% in HBIL's.  On 32-bit cores the
 * two signed compares measured fewer (make cross-count: the one compare
 * took Cortex-M3 749.5M -> 751.9M, Cortex-M0 4211.0M -> 4248.2M).  The same
 * values (tests/test_real.c sat64_is_the_clamp). */
/* Internal: 1 on a core with 64-bit registers (pointers past 32 bits), 0
 * on a 32-bit one; the Q16.16 helpers that measured faster in 32-bit
 * operations on 32-bit cores choose their form by it. */
#define TGI_CORE64 (UINTPTR_MAX > 0xFFFFFFFFu)
static inline tg_real tgi_sat64(int64_t v)
{
#if TGI_CORE64
    if ((uint64_t)v + (uint64_t)TG_REAL_MAX > 2u * (uint64_t)TG_REAL_MAX) return v > 0 ? TG_REAL_MAX : TG_REAL_MIN;
#else
    if (v > (int64_t)TG_REAL_MAX) return TG_REAL_MAX;
    if (v < (int64_t)TG_REAL_MIN) return TG_REAL_MIN;
#endif
    return (tg_real)v;
}
static inline tg_real tg_add(tg_real a, tg_real b) { return tgi_sat64((int64_t)a + b); }
static inline tg_real tg_sub(tg_real a, tg_real b) { return tgi_sat64((int64_t)a - b); }
static inline tg_real tg_neg(tg_real a) { return -a; }
/* p 2^-s rounded to nearest, ties toward +infinity: (p + 2^(s-1)) >> s,
 * as ARM's rounding shift instructions (VRSHR) round.  The shift of a
 * negative p floors: C99 leaves that to the implementation (6.5.7), so
 * tgi_shift_floors stops the build on one that does not.  Every product
 * and rounding shift of Q16.16 rounds so; ties were rounded away from zero
 * before (a sign test and, for a negative p, two negations more: 6% of a
 * Q16.16 frame's instructions).  Magnitudes never exceed the old
 * rounding's (a negative tie rounds up, toward 0).
 * tgi_shr_round_q16 and tgi_div_q16 (src/core/real.c, always in the Q16.16
 * library) are the same code out of line: compiling for size
 * (TG_OUTLINE_HELPERS) every file calls that one copy instead of keeping
 * its own. */
typedef char tgi_shift_floors[((int64_t)-3 >> 1) == -2 ? 1 : -1];
int64_t tgi_shr_round_q16(int64_t p, int s);
int32_t tgi_div_q16(int32_t a, int32_t b);
static inline int64_t tgi_shr_round_inline(int64_t p, int s)
{
    return (p + ((int64_t)1 << (s - 1))) >> s;
}
#if TG_OUTLINE_HELPERS
#define TGI_Q16_HELPER(name) tgi_##name##_q16     /* the library's one copy */
#else
#define TGI_Q16_HELPER(name) tgi_##name##_inline  /* inline, in each caller */
#endif
static inline int64_t tgi_shr_round(int64_t p, int s) { return TGI_Q16_HELPER(shr_round)(p, s); }
static inline tg_real tg_mul(tg_real a, tg_real b)
{
    return tgi_sat64(tgi_shr_round((int64_t)a * b, TG_FRAC_BITS));
}
/* n / d for d > 0, rounded to nearest, halves away from zero (half d
 * moves n away from zero, then C's division truncates toward it): the
 * rounding of every Q16.16 division (core/real.h tgi_div_pos,
 * gi/denoise.c's averages; tg_div below the same for either sign). */
static inline int64_t tgi_div_round(int64_t n, int64_t d) { return (n >= 0 ? n + d / 2 : n - d / 2) / d; }
/* Division rounds to nearest, halves away from zero, for every sign of a
 * and b (a / b = -a / -b); it saturates; x/0 gives +-TG_REAL_MAX by the
 * sign of x, 0/0 gives 0. */
static inline tg_real tgi_div_inline(tg_real a, tg_real b)
{
    int64_t n, half;
    if (b == 0) return a > 0 ? TG_REAL_MAX : a < 0 ? TG_REAL_MIN : 0;
    n = (int64_t)a * 65536;
    half = (b > 0 ? b : -(int64_t)b) / 2;   /* tgi_div_round for either sign of b, in one division */
    n += n >= 0 ? half : -half;
    return tgi_sat64(n / b);
}
static inline tg_real tg_div(tg_real a, tg_real b) { return TGI_Q16_HELPER(div)(a, b); }
static inline tg_real tg_from_int(int32_t i) { return tgi_sat64((int64_t)i * 65536); }
/* Floor to integer: the shift floors (tgi_shift_floors). */
static inline int32_t tg_to_int(tg_real a) { return (int32_t)(a >> 16); }
/* Round to nearest integer. */
static inline int32_t tg_round_int(tg_real a) { return tg_to_int(a + (a < TG_REAL_MAX - 32768 ? 32768 : 0)); }
/* n/d as a tg_real, exactly rounded; d > 0. */
static inline tg_real tg_ratio(int32_t n, int32_t d) { return tgi_sat64(((int64_t)n * 65536 + (n >= 0 ? d / 2 : -(d / 2))) / d); }
/* Host-side conversions (used by platform code and tests, never by kernels). */
static inline float tg_to_float(tg_real a) { return (float)a * (1.0f / 65536.0f); }
static inline tg_real tg_from_float(float f)
{
    float s = f * 65536.0f;
    if (!(s == s)) return 0;
    if (s >= 2147483520.0f) return TG_REAL_MAX;
    if (s <= -2147483520.0f) return TG_REAL_MIN;
    return (tg_real)(s >= 0 ? s + 0.5f : s - 0.5f);
}
/* Multiply by a power of two (shift), saturating. */
static inline tg_real tg_ldexp(tg_real a, int e)
{
    if (e >= 0) return tgi_sat64((int64_t)a * ((int64_t)1 << (e > 31 ? 31 : e)));
    return (tg_real)tgi_shr_round(a, -e > 31 ? 31 : -e);
}
static inline int tg_isfinite(tg_real a) { (void)a; return 1; }

#else /* float */

typedef float tg_real;
#define TG_ONE 1.0f
#define TG_REAL_MAX 3.402823466e+38f
#define TG_REAL_MIN (-TG_REAL_MAX)
#define TG_EPS 1.1920929e-07f
#define TG_R(x) ((tg_real)(x))
#define TG_NUMBER_NAME "float"

static inline tg_real tg_add(tg_real a, tg_real b) { return a + b; }
static inline tg_real tg_sub(tg_real a, tg_real b) { return a - b; }
static inline tg_real tg_neg(tg_real a) { return -a; }
static inline tg_real tg_mul(tg_real a, tg_real b) { return a * b; }
static inline tg_real tg_div(tg_real a, tg_real b) { return a / b; }
static inline tg_real tg_from_int(int32_t i) { return (tg_real)i; }
/* Floor to integer (saturates at the int32 range; NaN gives 0). */
static inline int32_t tg_to_int(tg_real a)
{
    int32_t i;
    if (!(a == a)) return 0;
    if (a >= 2147483520.0f) return INT32_MAX;
    if (a <= -2147483520.0f) return -INT32_MAX;
    i = (int32_t)a;
    return (tg_real)i > a ? i - 1 : i;
}
static inline int32_t tg_round_int(tg_real a) { return tg_to_int(a + 0.5f); }
static inline tg_real tg_ratio(int32_t n, int32_t d) { return (tg_real)n / (tg_real)d; }
static inline float tg_to_float(tg_real a) { return a; }
static inline tg_real tg_from_float(float f) { return f; }
static inline tg_real tg_ldexp(tg_real a, int e)
{
    while (e > 0) { a *= 2.0f; e--; }
    while (e < 0) { a *= 0.5f; e++; }
    return a;
}
static inline int tg_isfinite(tg_real a) { return a == a && a <= TG_REAL_MAX && a >= TG_REAL_MIN; }

/* rsqrt and sqrt are inline in the float build: every normalisation in the
 * hot loops calls them (error bounds in real.c's table). */
/* The bits of a float and back.  -ffreestanding (the core's build) turns
 * off the compiler's own memcpy, so a 4-byte type pun would be a library
 * call per use; gcc and clang take __builtin_memcpy as one move. */
#if defined(__GNUC__)
#define TGI_PUN_COPY __builtin_memcpy
#else
#define TGI_PUN_COPY memcpy
#endif
static inline float tgi_f_from_bits(uint32_t b) { float f; TGI_PUN_COPY(&f, &b, sizeof f); return f; }
static inline uint32_t tgi_f_bits(float f) { uint32_t b; TGI_PUN_COPY(&b, &f, sizeof b); return b; }

/* tg_rsqrt's steps for a normal x in (0, TG_REAL_MAX]: the bit-trick seed
 * (within 3.5%) and three Newton steps (quadratic), without the range
 * tests; for callers that have settled the range (the HBIL kernel, direct
 * light's 1/d), the same bits as tg_rsqrt there. */
static inline float tgi_rsqrt_normal(float x)
{
    float y = tgi_f_from_bits(0x5f3759dfu - (tgi_f_bits(x) >> 1));
    const float hx = 0.5f * x;
    y = y * (1.5f - hx * y * y);
    y = y * (1.5f - hx * y * y);
    y = y * (1.5f - hx * y * y);
    return y;
}

/* Bit-trick seed (within 3.5%) and three Newton steps (quadratic); x <= 0 gives TG_REAL_MAX. */
static inline tg_real tg_rsqrt(tg_real x)
{
    float scale = 1.0f;
    if (!(x > 0.0f)) return TG_REAL_MAX;
    if (x > TG_REAL_MAX) return 0.0f;
    if (x < 1.17549435e-38f) { x *= 18446744073709551616.0f; scale = 4294967296.0f; }
    return tgi_rsqrt_normal(x) * scale;
}

/* sqrt = x * rsqrt(x), plus one Newton correction on the residual; x <= 0 gives 0. */
static inline tg_real tg_sqrt(tg_real x)
{
    float r, s;
    if (!(x > 0.0f)) return 0.0f;
    if (x > TG_REAL_MAX) return x;
    r = tg_rsqrt(x);
    s = x * r;
    return s + 0.5f * r * (x - s * s);
}

#endif

/* ---- shared helpers, identical for both types ---- */
static inline tg_real tg_abs(tg_real a) { return a < 0 ? tg_neg(a) : a; }
static inline tg_real tg_min(tg_real a, tg_real b) { return a < b ? a : b; }
static inline tg_real tg_max(tg_real a, tg_real b) { return a > b ? a : b; }
static inline tg_real tg_clamp(tg_real a, tg_real lo, tg_real hi) { return a < lo ? lo : a > hi ? hi : a; }
static inline tg_real tg_saturate(tg_real a) { return tg_clamp(a, 0, TG_ONE); }
/* a + (b - a) * t */
static inline tg_real tg_lerp(tg_real a, tg_real b, tg_real t) { return tg_add(a, tg_mul(tg_sub(b, a), t)); }
static inline tg_real tg_sqr(tg_real a) { return tg_mul(a, a); }

/* ==== ABI: symbols carry the number type ===================================
 * Each public function is a macro for its symbol, NAME_f32 (float) or
 * NAME_q16 (Q16.16): programs write tg_plan_make, the library exports
 * tg_plan_make_q16, and a header/library mismatch fails at link time.
 * A new public function gets its line here (tests/purity_test.sh checks
 * that the libraries export nothing else).
 */
#if TG_FIXED
#define TG_ABI(name) name##_q16
#else
#define TG_ABI(name) name##_f32
#endif
#if TG_FIXED
#define tg_sqrt TG_ABI(tg_sqrt)
#define tg_rsqrt TG_ABI(tg_rsqrt)
#endif
#define tg_sin TG_ABI(tg_sin)
#define tg_cos TG_ABI(tg_cos)
#define tg_acos TG_ABI(tg_acos)
#define tg_asin TG_ABI(tg_asin)
#define tg_atan2 TG_ABI(tg_atan2)
#define tg_tan TG_ABI(tg_tan)
#define tg_exp2 TG_ABI(tg_exp2)
#define tg_log2 TG_ABI(tg_log2)
#define tg_pow TG_ABI(tg_pow)
#define tg_floor TG_ABI(tg_floor)
#define tg_smoothstep TG_ABI(tg_smoothstep)
#define tg_parse_real TG_ABI(tg_parse_real)
#define tg_error_format TG_ABI(tg_error_format)
#define tg_arena_init TG_ABI(tg_arena_init)
#define tg_arena_alloc TG_ABI(tg_arena_alloc)
#define tg_size_mul TG_ABI(tg_size_mul)
#define tg_size_add TG_ABI(tg_size_add)
#define tg_scene_parse TG_ABI(tg_scene_parse)
#define tg_builtin_scene TG_ABI(tg_builtin_scene)
#define tg_builtin_name TG_ABI(tg_builtin_name)
#define tg_aov_name TG_ABI(tg_aov_name)
#define tg_aov_from_name TG_ABI(tg_aov_from_name)
#define tg_aov_channels TG_ABI(tg_aov_channels)
#define tg_technique_name TG_ABI(tg_technique_name)
#define tg_technique_from_name TG_ABI(tg_technique_from_name)
#define tg_request_defaults TG_ABI(tg_request_defaults)
#define tg_plan_make TG_ABI(tg_plan_make)
#define tg_plan_explain TG_ABI(tg_plan_explain)
#define tg_plan_reads_thickness TG_ABI(tg_plan_reads_thickness)
#define tg_frame_create TG_ABI(tg_frame_create)
#define tg_frame_render TG_ABI(tg_frame_render)
#define tg_frame_aov_row TG_ABI(tg_frame_aov_row)
#define tg_frame_aov_row8 TG_ABI(tg_frame_aov_row8)
#define tg_frame_write_pixels TG_ABI(tg_frame_write_pixels)
#define tg_frame_set_parallel TG_ABI(tg_frame_set_parallel)
#define tg_scene_find_object TG_ABI(tg_scene_find_object)
#define tg_scene_light_count TG_ABI(tg_scene_light_count)
#define tg_frame_set_camera TG_ABI(tg_frame_set_camera)
#define tg_frame_set_object TG_ABI(tg_frame_set_object)
#define tg_frame_set_time TG_ABI(tg_frame_set_time)
#define tg_frame_set_light TG_ABI(tg_frame_set_light)
#define tg_frame_move_light TG_ABI(tg_frame_move_light)
#define tg_frame_set_env_uniform TG_ABI(tg_frame_set_env_uniform)
#define tg_frame_set_env_sky TG_ABI(tg_frame_set_env_sky)
#define tg_frame_set_env_sh9 TG_ABI(tg_frame_set_env_sh9)
#define tg_frame_cut TG_ABI(tg_frame_cut)
#define tg_frame_reprojected TG_ABI(tg_frame_reprojected)

/* ---- the core's own transcendentals (real.c; error bounds documented there) ---- */
#if TG_FIXED
tg_real tg_sqrt(tg_real x);           /* x <= 0 gives 0 */
tg_real tg_rsqrt(tg_real x);          /* x <= 0 gives TG_REAL_MAX */
#endif
tg_real tg_sin(tg_real x);            /* radians, any x */
tg_real tg_cos(tg_real x);
tg_real tg_acos(tg_real x);           /* x clamped to [-1, 1]; result in [0, pi] */
tg_real tg_asin(tg_real x);           /* x clamped to [-1, 1] */
tg_real tg_atan2(tg_real y, tg_real x); /* result in [-pi, pi]; (0,0) gives 0 */
tg_real tg_tan(tg_real x);            /* |x| < pi/2 */
tg_real tg_exp2(tg_real x);           /* saturates */
tg_real tg_log2(tg_real x);           /* x <= 0 gives TG_REAL_MIN */
tg_real tg_pow(tg_real x, tg_real y); /* x >= 0 */
tg_real tg_floor(tg_real x);
tg_real tg_smoothstep(tg_real a, tg_real b, tg_real x);
/* Parse a decimal number ("1", "-0.5", "2.5e-3") into a tg_real, rounding to
 * nearest.  Returns the count of characters used, 0 if none form a number.
 * *overflow is set when the value is outside the tg_real range (the result
 * then saturates). */
size_t tg_parse_real(const char *s, size_t len, tg_real *out, int *overflow);

#define TG_PI TG_R(3.14159265358979f)
#define TG_TWO_PI TG_R(6.28318530717959f)
#define TG_HALF_PI TG_R(1.57079632679490f)
#define TG_INV_PI TG_R(0.318309886183791f)
#define TG_DEG2RAD TG_R(0.0174532925199433f)
/* ======================================================================= */

/* ==== FEATURE SWITCHES ===================================================
 * Each is 0 (default: the feature is in) or 1 (left out of the library:
 * its files compile to nothing and no pass-table row refers to it, so the
 * linker has nothing of it to pull in).  Set them for the library's build
 * (-DTG_NO_OBJ=1 ...); the API stays the same, and a program built without
 * them links to such a library.  What needs a left-out feature is refused
 * with TG_ERR_INPUT and a message naming the switch, e.g. "technique gtao is
 * left out of this build (TG_NO_TECHNIQUES=1)":
 *   TG_NO_TECHNIQUES      GTAO, HBAO, SSAO, VO, SSDO, bent cones, the visibility
 *                         bitmask (src/ao):
 *                         tg_plan_make refuses those techniques.
 *   TG_NO_REFERENCE       the ray-traced reference, its BVH and the path
 *                         tracer: tg_plan_make refuses technique reference.
 *   TG_NO_OBJ             the OBJ/MTL loader: tg_scene_parse refuses a
 *                         `mesh` line.
 *   TG_NO_BUILTIN_SCENES  the built-in scenes' text: tg_builtin_scene and
 *                         tg_builtin_name give NULL for every name/index.
 *   TG_NO_SHADOW_MAPS     shadow maps: tg_plan_make refuses a plan with the
 *                         shadows effect (a light marked `shadows` lighting
 *                         the frame); leave `shadows` off the lights.
 *   TG_NO_ENVIRONMENT     the environment (SH9 projection, far field, sky):
 *                         tg_plan_make refuses a plan that would read the
 *                         scene's `env` (the far effect, or colour over a
 *                         sky); AO-only plans of such a scene still work.
 *   TG_NO_SCENE_TEXT      the scene-text parser, its lexer and the OBJ
 *                         loader: tg_scene_parse refuses every text; the
 *                         program renders a scene baked into C data on the
 *                         host (tinygi-bake, tools/scene_bake.c).
 *   TG_NO_COLOR           everything after AO that makes colour: direct
 *                         light, shadow maps, reprojection of radiance and
 *                         push/pull, composition, the kernel's near-field
 *                         gather, the radiance AOVs' readout (they read
 *                         0) and planes: tg_plan_make refuses a
 *                         plan with the direct, near, far or reprojection
 *                         effect or a radiance AOV (colour, irradiance,
 *                         direct, near, far); AO, bent normals, cones and
 *                         the geometry AOVs still render.
 *   TG_NO_GI_QUARTER      the kernel at quarter resolution (gi_scale 2): its
 *                         downsample, filter and joint bilateral upsample:
 *                         tg_plan_make refuses gi_scale 2.
 *   TG_NO_TEMPORAL        everything that carries a frame's results into
 *                         the next: temporal accumulation, reprojection of
 *                         radiance and push/pull, motion vectors, the kept
 *                         history: tg_plan_make refuses a plan that needs
 *                         them (frames > 1 with temporal accumulation or
 *                         the near field, the motion AOV over frames > 1);
 *                         every frame renders alone, as a first frame does.
 *   TG_NO_ANIMATION       the scene's keys (interpolated camera and object
 *                         poses): tg_plan_make refuses a scene with camera
 *                         or object keys; the program still sets the camera
 *                         and the objects' transforms (the game loop).
 *   TG_NO_BENT_NORMALS    the kernel's bent normals and cone apertures:
 *                         their sums, filtering, storage and readout:
 *                         tg_plan_make refuses the bent and cone AOVs and
 *                         the far field (lit in the bent cone); AO renders.
 *   TG_NO_FINE_HORIZON    the interleaved kernel's horizons refined on the
 *                         full-resolution pixels (src/gi/hbil.c,
 *                         refine_fine; about 1 KB): nothing is refused, but
 *                         the AO and light differ, the horizons set by the
 *                         sub-images' samples alone (README "Flash size").
 *   TG_NO_WIDE_CLIP       Q16.16 only: the rasterizer's 64-bit clipper for
 *                         G-buffer triangles that need clipping or whose
 *                         clip coordinates pass 2048 units
 *                         (src/raster/raster.c, gbuffer_wide_triangle;
 *                         about 1.6 KB): nothing is refused, but such a
 *                         far triangle (a ground plane of +-20000, or
 *                         +-3000 at a 5-degree fov) may be lost, and a
 *                         clipped one is clipped with a 16-bit fraction
 *                         (a +-200 floor's depth up to 0.9% off); a scene
 *                         whose triangles stay within the screen's guard
 *                         band and the depth range renders the same.
 * README "Flash size" has the .text each configuration takes on a Cortex-M4
 * (`make size-table`).
 */
#ifndef TG_NO_TECHNIQUES
#define TG_NO_TECHNIQUES 0
#endif
#ifndef TG_NO_REFERENCE
#define TG_NO_REFERENCE 0
#endif
#ifndef TG_NO_OBJ
#define TG_NO_OBJ 0
#endif
#ifndef TG_NO_BUILTIN_SCENES
#define TG_NO_BUILTIN_SCENES 0
#endif
#ifndef TG_NO_SHADOW_MAPS
#define TG_NO_SHADOW_MAPS 0
#endif
#ifndef TG_NO_ENVIRONMENT
#define TG_NO_ENVIRONMENT 0
#endif
#ifndef TG_NO_SCENE_TEXT
#define TG_NO_SCENE_TEXT 0
#endif
#ifndef TG_NO_COLOR
#define TG_NO_COLOR 0
#endif
#ifndef TG_NO_GI_QUARTER
#define TG_NO_GI_QUARTER 0
#endif
#ifndef TG_NO_TEMPORAL
#define TG_NO_TEMPORAL 0
#endif
#ifndef TG_NO_ANIMATION
#define TG_NO_ANIMATION 0
#endif
#ifndef TG_NO_BENT_NORMALS
#define TG_NO_BENT_NORMALS 0
#endif
#ifndef TG_NO_FINE_HORIZON
#define TG_NO_FINE_HORIZON 0
#endif
#ifndef TG_NO_WIDE_CLIP
#define TG_NO_WIDE_CLIP 0
#endif
/* TG_OUTLINE_HELPERS: 1 makes the larger storage helpers every pass calls
 * (src/raster/pack.h: octahedral normals, RGB9E5) one out-of-line copy
 * instead of one per file, the rasterizer's per-pixel weights loops, and
 * the HBIL horizon march (src/gi/hbil.c) one out-of-line copy for both
 * major axes instead of one inlined copy per axis and caller, and Q16.16's
 * rounding shift and division (tgi_shr_round, tg_div) calls to one copy in
 * the library instead of a static copy in each file; the default
 * is on when compiling for size (-Os, __OPTIMIZE_SIZE__), where the
 * compiler keeps a static copy in each file; the same bits either way. */
/* (its default is set before the number type, which uses it) */
/* ======================================================================= */

/* ==== LIMITS AND DEFAULTS ================================================
 * Every limit tinygi enforces, in one place (in the manner of luaconf.h),
 * each with its unit and its reason.  The scene parser, the plan
 * (tg_plan_make), the CLI and its --help, the README and
 * src/scene/format.md all use these; a value past a limit is refused with a
 * message that names it (FILE:LINE:COL in a scene file).  A build may LOWER
 * a limit marked [policy] by defining it first; the others follow from the
 * number formats and are fixed.
 */
/* -- image -- */
#define TG_MAX_IMAGE_SIDE 8192          /* pixels per side: the rasterizer's 28.4
                                           screen coordinates with a guard band of
                                           GUARD screens stay within 2^20 */
#if !defined(TG_MAX_IMAGE_PIXELS)
#define TG_MAX_IMAGE_PIXELS 16777216L   /* [policy] pixels per frame (2^24: 4096x4096) */
#endif
#if !defined(TG_MAX_FRAMES)
#define TG_MAX_FRAMES 100000            /* [policy] frames in one request */
#endif
/* -- GI settings (request fields and the scene's `gi` line) -- */
#define TG_MAX_SLICES 8                 /* slices per pixel: the kernel's per-slice table */
#define TG_MAX_SAMPLES 256              /* horizon samples per slice side */
#define TG_MAX_BOUNCES 100              /* kernel iterations on a frame without history */
#define TG_MAX_RADIUS 10000             /* gather radius, world units (0 is allowed) */
#define TG_MAX_THICKNESS 10000          /* technique ssilvb: surface thickness behind the depth
                                           buffer, world units (0 allowed: every sample a sheet) */
#define TG_MAX_DEPTH_LAYERS 3           /* technique ssilvb: the depth buffer, the nearest back
                                           face behind it and the nearest surface behind that
                                           (request.depth_layers) */
#define TG_THICKNESS_RADIUS_DIVISOR 2   /* ... unset (neither request nor scene): the gather
                                           radius / this (Therrien et al. 2023's constant
                                           thickness, sized to the scene as the radius is) */
#define TG_MAX_EXPOSURE 1000            /* linear multiplier before the tonemapper (0 allowed) */
#define TG_MIN_SHADOW_MAP 8             /* shadow-map texels per side: the PCF footprint */
#define TG_SHADOW_CLIP_DIVISOR 64       /* a point or spot light's map clips geometry at its near plane
                                        * / this (not at the near plane: what lies between is drawn at
                                        * the nearest depth code and shadows, instead of leaking light) */
#define TG_MAX_SHADOW_MAP 8192          /* ... and the rasterizer's largest side */
#define TG_DEFAULT_SLICES 2             /* HBIL sec. 3.3: 2 slices per pixel */
#define TG_HBIL_ROTATIONS 8             /* frames before HBIL's slice angles and march offsets repeat:
                                        * each frame takes the next eighth of every stratum, so the
                                        * temporal accumulation (weight 0.2) sees 8 x 32 directions */
#define TG_DEFAULT_SAMPLES 32            /* horizon samples per slice side: at most this many, one
                                        * step apart; a gather that reaches fewer sub-image pixels
                                        * takes each (cornell at 160x120 over 60 frames: colour RMSE
                                        * against the path tracer 0.083 with 16, 0.063 with 32) */
#define TG_DEFAULT_LAYERED_AO_SAMPLES 16 /* ... for HBIL's AO alone over further depth layers at
                                        * every pixel (the visibility bitmask counts a sample's
                                        * whole segment to its back face, not its front point):
                                        * AO RMSE against the reference within 0.001 of 32's on
                                        * the built-in scenes at 160x120 and 320x240, at about
                                        * half the instructions */
#if !defined(TG_QUARTER_NEAR_REACH)
#define TG_QUARTER_NEAR_REACH 16        /* [policy] --gi-quarter: full-resolution horizon samples per
                                        * slice side 1, 2, 3, 4, 6, 9, 13 pixels away (from 4 on, 1.5
                                        * times the last) up to this many, that the upsampled AO may
                                        * not be brighter than (src/gi/resample.c); 0: none, the
                                        * upsample alone; at most 140 (the offsets are bytes) */
#endif
#define TG_DEFAULT_BOUNCES 1
#define TG_DEFAULT_RADIUS 1             /* world units, for a scene without extent (neither request
                                           nor scene giving one: see TG_RADIUS_ENV_DIVISOR) */
#define TG_RADIUS_ENV_DIVISOR 30        /* a scene without a gi radius gets its bounds' diagonal
                                           without an environment, diagonal / this with one for AO
                                           alone (no colour, near, far, irradiance) */
#define TG_RADIUS_LIGHT_DIVISOR 6       /* ... and diagonal / this with one for light (colour, near,
                                           far, irradiance: a surface taken as solid sends its own
                                           light) */
#define TG_DEFAULT_SHADOW_MAP 0         /* texels per side; 0: each face by the size rule,
                                           about one texel per image pixel (README "Shadows") */
/* the path-traced reference (technique pathtrace: samples = paths per pixel,
 * bounces = most indirect bounces; the scene's gi line is not read) */
#define TG_DEFAULT_PATHTRACE_SAMPLES 64 /* paths per pixel */
#define TG_DEFAULT_PATHTRACE_BOUNCES 8  /* as a path tracer's "max bounces" */
#define TG_DEFAULT_PATHTRACE_ROULETTE 3 /* Russian roulette from this path vertex on */
#define TG_DEFAULT_WIDTH 320
#define TG_DEFAULT_HEIGHT 240
/* -- threads (the hosted platform's pool; the core never creates one) -- */
#if !defined(TG_MAX_THREADS)
#define TG_MAX_THREADS 64               /* [policy] threads of a hosted pool (tinygi --threads) */
#endif
/* -- scene text and OBJ files -- */
#define TG_MAX_LINE 4096                /* bytes in a scene or OBJ line, not counting the line end */
#define TG_MAX_NAME 31                  /* bytes in a material or object name */
#if !defined(TG_MAX_TRIANGLES)
#define TG_MAX_TRIANGLES 4000000L       /* [policy] triangles in a scene (meshes included) */
#endif
#define TG_MAX_MATERIALS 1024           /* materials in a scene */
#define TG_MAX_OBJECTS 65535            /* objects: a 16-bit object id per triangle */
#define TG_MAX_LIGHTS 64
#define TG_MAX_KEYS 4096                /* camera keys; object keys likewise */
#define TG_MIN_SPHERE_SEGMENTS 4
#define TG_MAX_SPHERE_SEGMENTS 256
#define TG_DEFAULT_SPHERE_SEGMENTS 24   /* segments around a sphere (12 rings) */
#define TG_DEFAULT_FOV 60               /* camera: vertical field of view, degrees */
#define TG_DEFAULT_NEAR 0.05f           /* camera: near plane, world units */
#define TG_DEFAULT_FAR 1000             /* camera: far plane, world units */
#if !defined(TG_CUT_DISTANCE)
#define TG_CUT_DISTANCE 0.5f            /* [policy] a camera cut: a move of more than this
                                           fraction of the scene's size (its bounding box's
                                           diagonal) from one frame to the next, or a turn
                                           by more than the vertical fov, drops the history */
#endif
#define TG_DEFAULT_F0 0.04f             /* material: Fresnel F0 of a dielectric */
#define TG_MAX_PATH 256                 /* a resolved mesh or MTL path, bytes with the NUL */
#if !defined(TG_MAX_OBJ_VERTICES)
#define TG_MAX_OBJ_VERTICES 4000000L    /* [policy] v, vn and vt lines each, per OBJ */
#endif
#define TG_MAX_MTLLIBS 8                /* mtllib files named by one OBJ */
#if !defined(TG_MAX_FILE_BYTES)
#define TG_MAX_FILE_BYTES (1L << 30)    /* [policy] a scene, OBJ or MTL file (1 GiB) */
#endif
/* ======================================================================= */

typedef enum tg_status {
    TG_OK = 0,
    TG_ERR_RUNTIME = 1, /* anything not the input's fault */
    TG_ERR_INPUT = 2,   /* bad scene, bad OBJ, bad request */
    TG_ERR_MEMORY = 3   /* the arena is too small: see tg_error.bytes_needed */
} tg_status;

typedef struct tg_error {
    char file[256];      /* "" when the error is not about a file */
    int line, col;       /* 1-based; 0 when unknown */
    char message[256];
    size_t bytes_needed; /* with TG_ERR_MEMORY */
} tg_error;

/* Write the error as "FILE:LINE:COL: error: MESSAGE" (or "error: MESSAGE";
 * no ":LINE:COL" when line <= 0) into buf, cut to size - 1 bytes and always
 * NUL-terminated when size > 0; buf may be NULL when size is 0.  Returns the
 * length of the whole text, as snprintf does (>= size: it was cut).  `err`
 * is one a tinygi function filled, or all zero; NULL formats as all zero
 * ("error: "). */
size_t tg_error_format(const tg_error *err, char *buf, size_t size);

/* ---- the arena: one block of caller memory, carved front to back ---- */
typedef struct tg_arena {
    unsigned char *base;
    size_t size, used;
    size_t failed_request; /* largest request that did not fit, 0 if none */
} tg_arena;

/* `size` bytes at `memory` (any alignment), none used yet; NULL memory gives
 * an empty arena whatever the size.  `size` must not exceed the memory. */
void tg_arena_init(tg_arena *a, void *memory, size_t size);
/* `bytes` zeroed bytes at the next 16-byte aligned ADDRESS (whatever the
 * alignment of the memory given to tg_arena_init: up to 15 bytes of it may
 * go to padding); NULL when they do not fit (a->used unchanged,
 * a->failed_request updated), and from an arena without memory.  0 bytes
 * gives a pointer not to be dereferenced. */
void *tg_arena_alloc(tg_arena *a, size_t bytes);
/* a * b with overflow check: returns 0 and sets *out, or returns 1 on
 * overflow (*out unchanged).  tg_size_add likewise for a + b. */
int tg_size_mul(size_t a, size_t b, size_t *out);
int tg_size_add(size_t a, size_t b, size_t *out);

/* ---- files the scene refers to (OBJ meshes): supplied by the platform ---- */
typedef struct tg_io {
    void *user;
    /* Give the whole file (at most TG_MAX_FILE_BYTES); the buffer must stay
     * valid while parsing.  Return 0 on success, non-zero if the file cannot
     * be read, and then may set *reason (NULL on entry) to a short phrase
     * saying why, e.g. "permission denied", "is a directory", "not a regular
     * file", "larger than the 1 GiB limit": the parser reports
     * "cannot read mesh file 'PATH': REASON". */
    int (*read_file)(void *user, const char *path, const char **data, size_t *size,
                     const char **reason);
} tg_io;

/* ---- scenes ---- */
typedef struct tg_scene tg_scene;

/* Parse scene-format v1 text (see README "Scene format"): `size` bytes at
 * `text`, no NUL needed (text may be NULL when size is 0); a size over
 * TG_MAX_FILE_BYTES is TG_ERR_INPUT before a byte is read.  `filename` is
 * used in messages and to resolve mesh paths (NULL: "<scene>").  `io` may
 * be NULL (then a mesh line is TG_ERR_INPUT).  The scene lives in `arena`
 * (its blocks from arena->used on); a NULL arena or scene is
 * TG_ERR_RUNTIME.  TG_ERR_MEMORY when the arena is too small, with
 * err->bytes_needed the arena size that would do (its used bytes included).
 * On failure *scene is NULL and arena->used is unchanged. */
tg_status tg_scene_parse(const char *text, size_t size, const char *filename,
                         const tg_io *io, tg_arena *arena, tg_scene **scene,
                         tg_error *err);
/* Built-in scenes: their text, by name ("cornell" or "builtin:cornell"), or
 * NULL for an unknown name or NULL. */
const char *tg_builtin_scene(const char *name);
/* The i-th built-in scene name, NULL for i outside 0..count-1. */
const char *tg_builtin_name(int i);

/* ---- what to render ---- */
typedef enum tg_aov {
    TG_AOV_COLOR, TG_AOV_DEPTH, TG_AOV_NORMAL, TG_AOV_ALBEDO,
    TG_AOV_AO, TG_AOV_BENT, TG_AOV_CONE, TG_AOV_NEAR, TG_AOV_FAR,
    TG_AOV_DIRECT, TG_AOV_IRRADIANCE, TG_AOV_MOTION,
    TG_AOV_COUNT
} tg_aov;
const char *tg_aov_name(tg_aov aov);    /* "?" for a value outside the enum */
int tg_aov_from_name(const char *name); /* exact lower-case name; -1 if unknown (name not NULL) */
int tg_aov_channels(tg_aov aov);        /* 1 or 3 (motion: 3, z = validity); 3 if unknown */

typedef enum tg_technique {
    TG_TECH_HBIL, TG_TECH_GTAO, TG_TECH_HBAO, TG_TECH_SSAO, TG_TECH_VO,
    TG_TECH_SSDO, TG_TECH_BENTCONE, TG_TECH_REFERENCE,
    TG_TECH_PATHTRACE,  /* the multi-bounce ground truth: unbiased diffuse path
                           tracing of the scene's triangles (src/ao/pathtrace.h);
                           colour and irradiance only (AO reads 1), no
                           screen-space effect (the plan's effects are 0),
                           each frame traced anew with the seed frame index + 1 */
    TG_TECH_SSILVB,     /* screen-space indirect lighting with a visibility bitmask
                           (Therrien et al. 2023, src/ao/ssilvb.h): GTAO's slices
                           with 32 sectors and surfaces of a constant thickness
                           (request.thickness), so light passes behind thin objects;
                           with request.depth_layers 2 or 3 a surface ends at the
                           nearest back face behind it instead (see depth_layers);
                           AO, bent normal and near field */
    TG_TECH_COUNT
} tg_technique;
const char *tg_technique_name(tg_technique t);    /* "?" for a value outside the enum */
int tg_technique_from_name(const char *name); /* -1 if unknown (name not NULL) */

/* Effects a frame can simulate; a plan holds the subset the scene calls for. */
enum {
    TG_EFFECT_DIRECT = 1u << 0,
    TG_EFFECT_SHADOWS = 1u << 1,
    TG_EFFECT_FAR = 1u << 2,          /* environment light (SH9) */
    TG_EFFECT_NEAR = 1u << 3,         /* gathered bounce light */
    TG_EFFECT_AO = 1u << 4,
    TG_EFFECT_REPROJECTION = 1u << 5
};

/* tg_request.shadow_method */
enum { TG_SHADOWS_AUTO = 0, TG_SHADOWS_MAPS = 1, TG_SHADOWS_RAYS = 2 };

/* What to render.  tg_plan_make checks every field against the limits block
 * above and refuses a value past its limit (TG_ERR_INPUT, a message naming
 * the field: "slices must be 1..8, got 20"); "unset" values take the
 * scene's gi line, else the TG_DEFAULT_* value. */
typedef struct tg_request {
    int width, height;     /* 1..TG_MAX_IMAGE_SIDE each, at most TG_MAX_IMAGE_PIXELS in all */
    int frames;            /* frames to render, 1..TG_MAX_FRAMES (1: no reprojection) */
    uint32_t aovs;         /* bit (1u << TG_AOV_x) per output wanted; 0: colour */
    tg_technique technique;/* 0..TG_TECH_COUNT - 1 */
    int slices;            /* 1..TG_MAX_SLICES; <= 0: unset */
    int samples;           /* 1..TG_MAX_SAMPLES; <= 0: unset (TG_DEFAULT_SAMPLES; HBIL's
                              AO alone over depth layers at gi_scale 1:
                              TG_DEFAULT_LAYERED_AO_SAMPLES; pathtrace: paths per pixel,
                              TG_DEFAULT_PATHTRACE_SAMPLES) */
    tg_real radius;        /* world units, 0..TG_MAX_RADIUS (0 is allowed); -1: unset;
                              NaN, the infinities and other negatives are refused */
    int bounces;           /* 0..TG_MAX_BOUNCES; < 0: unset (pathtrace: most
                              bounces, unset: TG_DEFAULT_PATHTRACE_BOUNCES) */
    int interleave;        /* 1: 4x4 interleaved kernel (default); 0: one full-res image */
    int gi_scale;          /* interleaved kernel on 1 pixel in gi_scale^2: 1 = every
                              pixel (default, the paper's), 2 = a quarter of them (half
                              width and height: about 3x faster, AO slightly brighter) */
    int temporal;          /* 1: temporal accumulation of the GI result (default); 0: none */
    int far_mode;          /* 0: SH9 cosine lobe in the bent cone (HBIL sec. 2.2.4, default);
                              1: E0(bent) F0(AO) (HBIL sec. 2.2.3) */
    tg_real exposure;      /* linear multiplier before the tonemapper, 0..TG_MAX_EXPOSURE
                              (default 1; NaN and the infinities are refused) */
    int shadow_map_size;   /* texels per side of every face the views need, each whole,
                              TG_MIN_SHADOW_MAP..TG_MAX_SHADOW_MAP; <= 0: unset (the size rule,
                              README "Shadows") */
    int shadow_pcf;        /* 1: 4-tap bilinear PCF (tg_request_defaults'); 0: 16-tap tent,
                              softer, 1.6x the cost, and darker bands along concave corners */
    int shadow_method;     /* TG_SHADOWS_AUTO (0, default): the plan chooses per light between
                              shadow maps and shadow rays against a BVH (README "Shadows");
                              TG_SHADOWS_MAPS or TG_SHADOWS_RAYS force one */
    int game_loop;         /* 0 (default): the camera and objects follow the scene's keys;
                              1: the program may also set the camera, objects, lights and
                              environment per frame ("the game loop" below): the frame keeps
                              a copy of the lights and environment, posed copies of the
                              triangles (72 bytes a triangle), each object's motion and a
                              2-byte-a-pixel object id; the shadow plan makes every map face
                              whole (it cannot know the cameras), which may choose shadow
                              rays instead (README "A game loop") */
    tg_real thickness;     /* technique ssilvb: world units, 0..TG_MAX_THICKNESS; -1: unset
                              (radius / TG_THICKNESS_RADIUS_DIVISOR); NaN, the infinities and
                              other negatives are refused */
    int ao_multibounce;    /* 0 (default) or 1: the ao AOV reads GTAO's multi-bounce fit
                              (Jimenez et al. 2016, eq. 10; src/ao/ao.h) of the AO with the
                              pixel's albedo, its Rec. 709 luminance (the AOV has one channel):
                              what the AO means with the bounces a path tracer adds, for
                              AO-only output.  The G-buffer then keeps the material index
                              (+2 bytes a pixel); nothing else changes (colour is composed
                              from the AO as computed) */
    int depth_layers;      /* 0 (default): the plan's choice, `--explain` prints it: 2 for
                              AO alone (ao, bent, cone without colour, irradiance, near or
                              far) from technique hbil at every pixel (gi_scale 1) in a
                              scene with an environment, where one layer takes the ground
                              hidden behind every closed object as solid; else 1;
                              1: one depth layer, the depth buffer;
                              2 (techniques ssilvb and hbil): the rasterizer also keeps the view
                              depth of the nearest back face at or behind each pixel's surface
                              (+1 byte a pixel: an 8-bit code against the pixel's depth,
                              within 3.2% of the thickness; with AO alone, the filtered AO
                              then reuses those bytes),
                              and the visibility bitmask takes a surface as solid from the
                              depth buffer to that back face (a closed object's true
                              thickness), to infinity where there is none (a one-sided
                              boundary), for request.thickness where it is the surface's own
                              (a twosided sheet); 3 (TG_MAX_DEPTH_LAYERS): also the nearest
                              surface behind that back face (+4 bytes a pixel), solid again
                              from there for request.thickness.  With technique hbil the
                              kernel is then that visibility bitmask (a one-sided boundary's
                              sample closing its side down to the tangent plane, as a horizon
                              does), on the kernel's image (full resolution, or at gi_scale 2
                              the half-resolution one, its layers point-sampled down with its
                              depth: +1 and +4 bytes a half-resolution pixel) with the 4x4
                              sub-images' slice angles and march offsets turned every frame, the
                              samples spread over the part of the radius on the screen; HBIL's
                              filter, upsample and temporal accumulation follow as usual
                              (src/frame/hbil_passes.c).  Other values are refused, and 2 or 3
                              with any other technique */
} tg_request;

/* Every field at its default: 320x240, one frame, colour, HBIL, GI settings
 * unset.  NULL: nothing is done. */
void tg_request_defaults(tg_request *r);

/* ---- the frame plan ---- */
#define TG_PLAN_MAX_PASSES 40
#define TG_PLAN_MAX_BUFFERS 64

typedef struct tg_plan_buffer {
    const char *name;   /* what it holds, in the papers' words */
    size_t bytes;
} tg_plan_buffer;

typedef struct tg_plan {
    tg_request request;        /* the request with every default resolved */
    uint32_t effects;          /* TG_EFFECT_* the frame simulates */
    int pass_count;
    const char *passes[TG_PLAN_MAX_PASSES];   /* what a frame runs, in order */
    unsigned char pass_rows[TG_PLAN_MAX_PASSES]; /* (internal) their rows in the pass table */
    int buffer_count;
    tg_plan_buffer buffers[TG_PLAN_MAX_BUFFERS];
    size_t total_bytes;        /* arena bytes tg_frame_create needs */
    const tg_scene *scene;
} tg_plan;

/* Decide what a frame of `scene` computes for `req` and how many arena
 * bytes it needs.  TG_ERR_INPUT when a request field (or the scene's gi
 * value it falls back on) is past its limit, or when the frame's size does
 * not fit the address space. */
tg_status tg_plan_make(tg_plan *plan, const tg_scene *scene,
                       const tg_request *req, tg_error *err);
/* Human-readable plan (the CLI's --explain) into buf, cut and NUL-terminated
 * as by tg_error_format (buf may be NULL when size is 0); returns the length
 * of the whole text. */
size_t tg_plan_explain(const tg_plan *plan, char *buf, size_t size);
/* Whether the plan's frames read request.thickness (the visibility
 * bitmask's surface thickness: technique ssilvb, and hbil over depth
 * layers, depth_layers >= 2); 0 when the thickness changes nothing. */
int tg_plan_reads_thickness(const tg_plan *plan);

/* ---- frames ---- */
typedef struct tg_frame tg_frame;

/* Carve a frame out of `size` bytes at `memory`, at any alignment:
 * plan->total_bytes is enough at every address.  Too little (or NULL
 * memory) is TG_ERR_MEMORY, err->bytes_needed = plan->total_bytes.  On
 * failure *frame is NULL.  The frame uses only those bytes; it copies what
 * it needs of the plan, and points into the plan's scene.  A plan whose
 * request was changed after tg_plan_make is checked again as tg_plan_make
 * checks a request: a field past its limit is TG_ERR_INPUT. */
tg_status tg_frame_create(const tg_plan *plan, void *memory, size_t size,
                          tg_frame **frame, tg_error *err);
/* Render frame `index` (0-based; the keys' time comes from it unless
 * tg_frame_set_time set one: 0 the first key, request.frames - 1 the last,
 * later indices hold the last).  Frames follow one another: frame index > 0
 * reprojects the frame rendered before it (see "the game loop"); index 0
 * starts afresh, with no history.  The temporal filter alternates two
 * buffers by the parity of index, so a sequence counts up by one.  A
 * negative index is TG_ERR_INPUT; rendering allocates nothing. */
tg_status tg_frame_render(tg_frame *frame, int index, tg_error *err);

/* ---- threads: the platform runs row ranges, the core creates no thread ----
 * Most passes of a frame are row-parallel: rows [y0, y1) of the pass's
 * image are computed from what earlier passes wrote, and no two rows write
 * the same byte.  tg_frame_render hands each such pass (and each inner row
 * loop of a pass) to `run`, which must call fn(job, y0, y1) over disjoint
 * ranges that together cover [0, rows) exactly once, in any order and split,
 * possibly at the same time on several threads or cores, and return only
 * when every call has returned (the next pass reads what they wrote, so
 * `run` must also make their writes visible to the calling thread: a mutex,
 * a join or a core's FIFO and barrier do).  Serial steps (the camera,
 * shadow maps, the reprojection scatter, push/pull's coarser levels, the
 * reference's BVH) run on the thread that called tg_frame_render.
 *  - Any split gives the same bits as one call over [0, rows).
 *  - fn touches only the frame's arena and the scene (read only): nothing
 *    global, no allocation, no I/O; each thread that runs it needs the stack
 *    a frame needs on the calling thread (see README "Porting").
 *  - `run` is called from the thread that called tg_frame_render, never
 *    from inside fn; with rows >= 1.  The simplest correct `run` is
 *    fn(job, 0, rows).
 * Do not render two frames that share a hook's threads at the same time
 * unless `run` allows it. */
typedef void (*tg_rows_fn)(void *job, int y0, int y1);
typedef struct tg_parallel {
    void *user;
    void (*run)(void *user, tg_rows_fn fn, void *job, int rows);
} tg_parallel;
/* Run the frame's row-parallel passes through p (copied; NULL: every pass on
 * the calling thread, the default).  TG_ERR_INPUT when p->run is NULL. */
tg_status tg_frame_set_parallel(tg_frame *frame, const tg_parallel *p);
/* Row y of an AOV as linear values: `out` holds width * tg_aov_channels(aov)
 * values.  y must be in [0, height): another row is refused (TG_ERR_INPUT,
 * `out` all zeros), nothing outside the frame is read.  An AOV the plan did
 * not compute reads as 0 (ao 1, cone pi/2, bent the normal); a value
 * outside the enum reads as `width` zeros. */
tg_status tg_frame_aov_row(const tg_frame *frame, tg_aov aov, int y, tg_real *out);
/* Row y of an AOV as 8-bit RGB for viewing (`rgb` holds 3 * width bytes):
 * colour is exposed, tonemapped and sRGB-encoded; normals are 0.5n + 0.5;
 * scalar AOVs are grey.  y as for tg_frame_aov_row (zeros when refused). */
tg_status tg_frame_aov_row8(const tg_frame *frame, tg_aov aov, int y, uint8_t *rgb);

/* ---- pixels for a display ----
 * tg_frame_write_pixels writes rows [y0, y1) of an AOV, as tg_frame_aov_row8
 * gives them (8-bit sRGB), into `dst` in a display's pixel format: row y0 at
 * dst, each next row `stride` bytes further (stride >= width * bytes per
 * pixel; bytes past a row's pixels are not touched).  Each format by its
 * bytes in memory:
 *   TG_PIXEL_RGB565    2: one uint16_t in the MACHINE's byte order, red in
 *                      bits 15-11, green 10-5, blue 4-0 (the Linux
 *                      framebuffer's, LTDC's, SDL's RGB565)
 *   TG_PIXEL_BGR565    2: the same with blue in 15-11 and red in 4-0
 *   TG_PIXEL_RGB565_BE 2: the RGB565 value high byte first on any machine
 *                      (what SPI panels such as the ILI9341 and ST7789 read)
 *   TG_PIXEL_RGB888    3: R, G, B (as PPM)
 *   TG_PIXEL_BGR888    3: B, G, R
 *   TG_PIXEL_XRGB8888  4: one uint32_t in the machine's byte order,
 *                      0xXXRRGGBB with X = 255, so it is opaque ARGB8888 too
 *                      (bytes B, G, R, 255 on a little-endian machine)
 *   TG_PIXEL_RGBA8888  4: R, G, B, 255 (as OpenGL's GL_RGBA bytes and PNG)
 *   TG_PIXEL_GREY8     1: the Rec. 709 luma of the sRGB bytes,
 *                      round(0.2126 R + 0.7152 G + 0.0722 B), halves up
 * 5- and 6-bit channels are rounded to nearest, round(c * 31 / 255).  With
 * TG_PIXELS_DITHER they are dithered instead (ordered, 4x4 Bayer):
 * floor(c * 31 / 255 + (M + 0.5) / 16), M the Bayer index at (x mod 4,
 * y mod 4) of the pixel's place in the FRAME, so the pattern stays still from
 * frame to frame and does not depend on how rows are split over calls; any
 * 4x4 block of one colour averages to c * 31 / 255 within 1/32.  The flag
 * changes nothing in the 8-bit formats.  Without division, identical in both
 * number types.  Uses 3 * width bytes of stack (RGB888: none).  TG_ERR_INPUT,
 * with nothing written, for a NULL frame or dst, an unknown aov, format or
 * flag, rows not 0 <= y0 <= y1 <= height, or a stride below a row. */
typedef enum tg_pixel_format {
    TG_PIXEL_RGB565, TG_PIXEL_BGR565, TG_PIXEL_RGB565_BE,
    TG_PIXEL_RGB888, TG_PIXEL_BGR888, TG_PIXEL_XRGB8888, TG_PIXEL_RGBA8888,
    TG_PIXEL_GREY8,
    TG_PIXEL_FORMAT_COUNT
} tg_pixel_format;
enum { TG_PIXELS_DITHER = 1 };
tg_status tg_frame_write_pixels(const tg_frame *frame, tg_aov aov, int y0, int y1,
                                tg_pixel_format format, int flags, void *dst, size_t stride);
/* ---- the game loop: driving frames from a program ----
 * A frame renders the scene as it is NOW: its camera, object poses, lights
 * and environment are per-frame state held by the frame, never written
 * into the parsed scene, so one scene can drive several frames.  Two
 * producers fill that state before each render: the scene's keys
 * (camera_key, object_key at the keys' time) and the program, through the
 * calls below, made between renders (never during one).  Precedence, per
 * quantity:
 *   camera      the program's from the first tg_frame_set_camera on (the
 *               last one set holds while no new one comes); before that,
 *               the camera keys (or the fixed camera).
 *   object      likewise per object: tg_frame_set_object takes that object
 *               from its keys for good; the others follow their keys.
 *   keys' time  tg_frame_set_time's t from its first call on; before that,
 *               the frame index (src/scene/format.md, camera_key: t runs
 *               from the first key to the last over request.frames frames).
 *   light, env  the program's values replace the scene's from the next
 *               render on (the scene has no keys for them).
 * A frame made anew (tg_frame_create) starts from the scene again.
 * The next tg_frame_render then reprojects what the previous frame showed,
 * with motion vectors from the old camera and poses to the new: the one
 * code path of the keys (src/frame/camera.c).
 *
 * A camera cut drops the history (the frame renders as a first frame: no
 * reprojection, the temporal filter restarts, the full `gi bounces`, zero
 * motion): declared by tg_frame_cut, or detected when the camera moved
 * further than TG_CUT_DISTANCE times the scene's size (its bounding box's
 * diagonal) or turned by more than the vertical fov since the last frame,
 * whoever moved it.  tg_frame_reprojected says whether it happened.
 *
 * The setters (camera, object, light, environment) need a plan made with
 * request.game_loop = 1, which keeps what they change; on another frame
 * they return TG_ERR_INPUT.  tg_frame_set_time and tg_frame_cut work on any
 * frame.  Every call checks its arguments and returns TG_ERR_INPUT, with a
 * message in err (which may be NULL), on a NULL pointer, an index out of
 * range or a value outside its domain (NaN and the infinities are outside
 * every domain); nothing is changed then.  Vectors are 3 tg_reals (x, y,
 * z) in world space; angles are radians.
 *
 * What changes cost: a moved object or light (tg_frame_move_light) fits and
 * renders its shadow map again on the next render; a light's colour or
 * intensity and the environment change no shadow map (the environment's
 * SH9 projection is recomputed at once, 9 coefficients).  A static scene
 * renders its shadow maps once. */

/* The index of the object named `name` (the scene's `name ID`), or -1 when
 * no object has that name or either argument is NULL. */
int tg_scene_find_object(const tg_scene *scene, const char *name);
/* Lights have no names: they are numbered 0..count-1 in the order of the
 * scene's `light` lines.  0 for a NULL scene. */
int tg_scene_light_count(const tg_scene *scene);

/* The camera from the next render on: at `pos`, looking at `target` (which
 * must differ from pos), `up` any non-zero vector (normalized; one
 * parallel to the view gets a perpendicular one, as in the scene), and
 * `fov` the vertical field of view in radians, in (0, pi).  near and far
 * stay the scene's camera's. */
tg_status tg_frame_set_camera(tg_frame *frame, const tg_real pos[3], const tg_real target[3],
                              const tg_real up[3], tg_real fov, tg_error *err);
/* Object `object`'s pose from the next render on, as the scene's
 * object_key gives it: the rest-pose triangles rotated by `angle` radians
 * (any finite value) about the unit `axis` (non-zero, normalized) through
 * the world origin, then moved by `translate`.  Axis-angle and not a
 * quaternion or matrix because it is the keys' own form: the program and
 * the keys build the pose by the same code, so the same pose gives the
 * same bits, and a pose cannot be other than rigid.  From a unit
 * quaternion (x, y, z, w): axis (x, y, z), angle 2 atan2(|(x, y, z)|, w). */
tg_status tg_frame_set_object(tg_frame *frame, int object, const tg_real translate[3],
                              const tg_real axis[3], tg_real angle, tg_error *err);
/* Sample the keys at time t (the scene's key units, any finite value) from
 * the next render on, instead of at the time the frame index gives. */
tg_status tg_frame_set_time(tg_frame *frame, tg_real t, tg_error *err);
/* Light `light`'s colour (linear RGB, each >= 0) and intensity (>= 0) from
 * the next render on.  No shadow map is rendered again for it. */
tg_status tg_frame_set_light(tg_frame *frame, int light, const tg_real color[3],
                             tg_real intensity, tg_error *err);
/* Move light `light` from the next render on: `pos` for a point or spot
 * light, `dir` (the direction light travels, non-zero, normalized) for a
 * directional or spot light; NULL keeps the current one (both NULL is
 * refused, and so is a `pos` for a directional or a `dir` for a point
 * light).  Its shadow map is fitted and rendered again. */
tg_status tg_frame_move_light(tg_frame *frame, int light, const tg_real pos[3],
                              const tg_real dir[3], tg_error *err);
/* The environment from the next render on, as the scene's `env` lines
 * give it (each colour >= 0; `up` non-zero, normalized; SH9: 27 numbers,
 * RGB of L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22, any sign).  The
 * scene must have an `env` line (without one the plan has no far field). */
tg_status tg_frame_set_env_uniform(tg_frame *frame, const tg_real radiance[3], tg_error *err);
tg_status tg_frame_set_env_sky(tg_frame *frame, const tg_real sky[3], const tg_real ground[3],
                               const tg_real up[3], tg_error *err);
tg_status tg_frame_set_env_sh9(tg_frame *frame, const tg_real coeffs[27], tg_error *err);
/* Declare a camera cut: the next render drops the history.  TG_ERR_INPUT
 * for a NULL frame. */
tg_status tg_frame_cut(tg_frame *frame);
/* 1 when the frame last rendered continued from the one before (its
 * radiance and temporal history reprojected, motion from the previous
 * camera and poses); 0 on a first frame, after a cut (declared or
 * detected), when the plan keeps no history (one frame) and for NULL. */
int tg_frame_reprojected(const tg_frame *frame);

#ifdef __cplusplus
}
#endif

#endif
