/* SPDX-License-Identifier: MIT */
/*
 * pack.h - the storage formats of the frame's buffers: the same bits in both
 * number types (a float frame's buffers and a Q16.16 frame's buffers hold
 * the same format; each build converts with its own arithmetic, integer only
 * in Q16.16).
 *
 *   depth      32-bit IEEE-754 binary32 bits of the view depth (0: sky).
 *              Positive floats order like their bits, so a depth test can
 *              compare the words.  Q16.16 values below 256 round-trip
 *              exactly; above, to 2^-24 relative.
 *   unit vector  octahedral (Cigolle et al. 2014, "A Survey of Efficient
 *              Representations for Independent Unit Vectors", sec. 3.1):
 *              the unit sphere onto the octahedron |x|+|y|+|z| = 1, the
 *              lower half folded over the upper, two coordinates in
 *              [-1, 1] quantized to `bits` each (2x11 for G-buffer normals,
 *              2x8 for bent normals) on 2^bits - 2 steps, so that 0 and +-1
 *              (the axes: floors and walls) are exact.
 *   RGB9E5     three 9-bit mantissas sharing a 5-bit exponent (the
 *              EXT_texture_shared_exponent format): non-negative linear
 *              RGB up to 65408, relative step 2^-9 of the largest channel.
 *              Negative, NaN and -0 store 0; larger values saturate (Q16.16's
 *              largest, 32768, fits).  RGB9E5_INVALID marks a pixel without
 *              a value (reads as 0; the encoder never produces it).
 *   unorm8     [0, 1] in 8 bits (ambient occlusion).
 */
#ifndef TG_PACK_H
#define TG_PACK_H

#include "../core/real.h"
#include "../core/vec.h"

/* ---- depth: binary32 bits ---- */
#if TG_FIXED
/* The word of a depth z >= 1 raw, in 32 bits without a branch: b = bit
 * length of v = z in 1..31, n = v 2^(32 - b) (its leading 1 at bit 31),
 * x = n >> 7 = floor(v 2^(25 - b)) and m = round(v 2^(24 - b)) ties up =
 * (x + 1) >> 1 (floor((y + 1) / 2) = floor((floor(y) + 1) / 2) for real
 * y; for b <= 24 x is even, and m the exact v << (24 - b)), in [2^23,
 * 2^24]; the word is ((b + 109) << 23) + m: for m < 2^24 the exponent field
 * floor(log2(z)) + 127 = b + 110 over m's 23 bits (m - 2^23), for m = 2^24
 * (the rounding carried) the next exponent over a zero significand.  It
 * had been two branches (b <= 24, the carry) and, above 24 bits, v + 2^(s -
 * 1) >> s, s = b - 24: the same words (tests/test_pack.c
 * depth_pack_matches_branchy_form: every word below 2^25, around each
 * power of two, 2,000,000 random). */
static inline uint32_t tgi_depth_pack_pos(tg_real z)
{
    const uint32_t v = (uint32_t)z;
    const int c = tgi_clz32_nz(v);    /* 32 - b */
    return ((uint32_t)(141 - c) << 23) + ((((v << c) >> 7) + 1u) >> 1);
}
static inline uint32_t tgi_depth_pack(tg_real z)
{
    return z > 0 ? tgi_depth_pack_pos(z) : 0;
}
/* The depth of a word, in two forms of the same function of every 32-bit
 * word (tests/test_pack.c depth_unpack_forms_agree): z = m 2^(e - 150), e
 * the biased exponent field, m the 24-bit significand, so Q16.16 raw
 * r = m 2^(e - 134) rounded to nearest, ties up; the sign ignored; 0 below
 * e = 110 (< 2^-17, and 0: sky), TG_REAL_MAX from e = 142 (>= 2^15: beyond
 * Q16.16).
 * 64 bits: m 2^(e - 110) (e in [110, 142): below 2^55) rounded at bit 24,
 * e taken as (bits << 1) >> 24, the bits 23..30 as (bits >> 23) & 0xFF
 * took them, in one lea and a shift on x86-64 (it had been a copy,
 * a shift and a zero extension: callgrind --frames 2 --threads 1 Q16.16,
 * cornell 160x120 806.9M -> 803.7M, 320x240 --gi-quarter 1575.7M ->
 * 1567.2M). */
static inline tg_real tgi_depth_unpack64(uint32_t bits)
{
    uint32_t e = (bits << 1) >> 24, m = (bits & 0x7FFFFFu) | 0x800000u;
    if (e - 110u >= 32u) return e >= 142u ? TG_REAL_MAX : 0;
    return (tg_real)((((uint64_t)m << (e - 110u)) + (1u << 23)) >> 24);
}
/* 32 bits: M = m 2^8 (bits << 8 drops the sign and the exponent but its
 * lowest bit, which the or overwrites with m's leading 1; M < 2^32, its low
 * 8 bits 0), k = 141 - e in [0, 31]: r = round(M 2^-(k + 1)) = floor((M
 * 2^-k + 1) / 2) = ((M >> k) + 1) >> 1 (floor((x + 1) / 2) = floor((floor(x)
 * + 1) / 2) for real x), and the 64-bit form's floor((m 2^(e - 110) +
 * 2^23) 2^-24) is the same floor with numerator and denominator scaled by
 * 2^(k - 24).  (M >> k) + 1 < 2^32 (M's low bits 0 at k = 0), r < 2^31.
 * On a 32-bit core two 32-bit shifts in place of a 64-bit one (Cortex-M3,
 * gcc 12 -O2: 9 instructions against 16, the range test included); x86-64
 * measured it the other way (callgrind cornell 160x120 --frames 2
 * --threads 1: Q16.16 806.9M -> 817.4M, gcc no longer seeing r > 0): a
 * 64-bit host keeps the 64-bit form, as depths_close (gi/hbil.c) does. */
static inline tg_real tgi_depth_unpack32(uint32_t bits)
{
    uint32_t e = (bits >> 23) & 0xFF, k = 141u - e;
    if (k >= 32u) return e >= 142u ? TG_REAL_MAX : 0;
    return (tg_real)(((((bits << 8) | 0x80000000u) >> k) + 1u) >> 1);
}
static inline tg_real tgi_depth_unpack(uint32_t bits)
{
#if TGI_CORE64
    return tgi_depth_unpack64(bits);
#else
    return tgi_depth_unpack32(bits);
#endif
}
#else
typedef union tgi_f32_bits { float f; uint32_t u; } tgi_f32_bits;
static inline uint32_t tgi_depth_pack(tg_real z)
{
    tgi_f32_bits b;
    if (!(z > 0.0f)) return 0;        /* sky, negative and NaN */
    b.f = z;
    return b.u;
}
static inline tg_real tgi_depth_unpack(uint32_t bits)
{
    tgi_f32_bits b;
    b.u = bits;
    return b.f;
}
static inline float tgi_abs_bits(float v)
{
#if defined(__GNUC__)
    return __builtin_fabsf(v);        /* an and in the float registers, no libm */
#else
    tgi_f32_bits b;
    b.f = v;
    b.u &= 0x7FFFFFFFu;
    return b.f;
#endif
}
#endif
/* |v| in either number type where -0's sign changes nothing (a
 * comparison, or a use that says why): float by the sign bit
 * (tgi_abs_bits, +0 at -0), Q16.16 tg_abs. */
static inline tg_real tgi_abs_fast(tg_real v)
{
#if TG_FIXED
    return tg_abs(v);
#else
    return tgi_abs_bits(v);
#endif
}

/* ---- the second depth layer: the back face's depth against the pixel's ---- */
/* The nearest back face behind a pixel's surface, z_b >= z_f > 0 (the
 * G-buffer's second depth layer, request.depth_layers >= 2), in 8 bits:
 * the relative depth t = z_b / z_f - 1 on a log scale, code 2 + 16 o + m
 * for t = 2^(o - 10) (1 + m / 16), o and m in 0..15, rounded to the
 * nearest m (a step is 1/16 to 1/32 of t: a thickness at most 3.2% off);
 * 1 a sheet (z_b = z_f, a twosided surface's own back face), 0 none.  A
 * layer thinner than 2^-10 z_f takes the smallest code, one thicker than
 * 58 z_f (code 255) the largest (the bitmask takes 64 radii behind as
 * infinite).  The codes order as the depths for one z_f (the nearest back
 * face is the smallest code); float and Q16.16 may round a t at a step's
 * middle apart, as their depths do. */
#define TGI_BACK_NONE 0u
#define TGI_BACK_SHEET 1u
#define TGI_BACK_LAST 255u
static inline uint8_t tgi_back_code(tg_real zf, tg_real zb)
{
    int o, m;
    if (!(zf > 0) || !(zb >= zf)) return TGI_BACK_NONE;
    if (zb == zf) return TGI_BACK_SHEET;
#if TG_FIXED
    {
        const uint32_t v = (uint32_t)tg_div(tg_sub(zb, zf), zf);   /* t, saturated */
        int top;
        if (v < 64u) return 2;                                      /* t < 2^-10 */
        top = tgi_bit_length64(v) - 1;                              /* 6..30 */
        o = top - 6;
        m = (int)(((((uint64_t)v - ((uint64_t)1 << top)) << 4) + ((uint64_t)1 << (top - 1))) >> top);
    }
#else
    {
        tgi_f32_bits b;
        int e;
        b.f = (zb - zf) / zf;
        e = (int)((b.u >> 23) & 0xFFu) - 127;
        if (e < -10) return 2;
        o = e + 10;
        m = (int)(((b.u & 0x7FFFFFu) + (1u << 18)) >> 19);
    }
#endif
    if (m == 16) { m = 0; o++; }
    if (o > 15 || (o == 15 && m > 13)) return TGI_BACK_LAST;
    return (uint8_t)(2 + 16 * o + m);
}
/* z_b of code c at a pixel of depth zf > 0 (0: none). */
static inline tg_real tgi_back_decode(uint8_t c, tg_real zf)
{
    int k, o, m;
    if (c == TGI_BACK_NONE) return 0;
    if (c == TGI_BACK_SHEET) return zf;
    k = c - 2;
    o = k >> 4;
    m = k & 15;
#if TG_FIXED
    return tg_add(zf, tg_mul(zf, (tg_real)((int32_t)(16 + m) << (o + 2))));   /* t = (16 + m) 2^(o - 14) */
#else
    {
        tgi_f32_bits t;
        t.u = ((uint32_t)(o - 10 + 127) << 23) | ((uint32_t)m << 19);       /* exactly 2^(o - 10) (1 + m/16) */
        return zf + zf * t.f;
    }
#endif
}

/* ---- octahedral unit vectors ---- */

/* Quantize one octahedral coordinate p in [-1, 1] (as num / den, |num| <= den)
 * to 0 .. 2^bits - 2, rounded to nearest. */
#if TG_FIXED
static inline uint32_t tgi_oct_quant(int64_t num, int64_t den, int bits)
{
    int64_t q = (int64_t)((1u << bits) - 2);
    return (uint32_t)(((num + den) * q + den) / (2 * den));
}
#else
/* (p + 1) 0.5 q + 1/2, q = 2^bits - 2: in one product by q / 2 (odd,
 * exact): p + 1 is 0 or at least 2^-24 in magnitude, so halving it is
 * exact and the product rounds once either way */
static inline float tgi_oct_quant_u(float p, int bits)
{
    return (p + 1.0f) * (float)((1u << (bits - 1)) - 1) + 0.5f;
}
static inline uint32_t tgi_oct_quant(float p, int bits)
{
    float q = (float)((1u << bits) - 2), u = tgi_oct_quant_u(p, bits);
    if (!(u > 0.0f)) return 0;
    if (u >= q) return (uint32_t)q;
    return (uint32_t)u;
}
/* tgi_oct_quant for the coordinates tgi_oct_pack_l1 makes, where its
 * clamps never act (u within (0, q + 1): truncated, 0 .. q, as clamped). */
static inline uint32_t tgi_oct_quant_unit(float p, int bits) { return (uint32_t)tgi_oct_quant_u(p, bits); }
#endif

#if TG_FIXED
/* Vector (x, y, z), integers with |.| < 2^31, to two `bits`-bit
 * coordinates, u in the low bits, v above it (the zero vector packs as +z). */
static inline uint32_t tgi_oct_pack64(int64_t x, int64_t y, int64_t z, int bits)
{
    int64_t ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, l1 = ax + ay + (z < 0 ? -z : z);
    if (l1 == 0) { x = 0; y = 0; z = 1; l1 = 1; }
    if (z < 0) {                      /* fold the lower half: p' = (1 - |p.yx|) sign(p) */
        int64_t fx = (l1 - ay) * (x < 0 ? -1 : 1), fy = (l1 - ax) * (y < 0 ? -1 : 1);
        x = fx; y = fy;
    }
    return tgi_oct_quant(x, l1, bits) | (tgi_oct_quant(y, l1, bits) << bits);
}
#endif

#if TG_FIXED
/* tgi_oct_pack64 of a vector (x, y, z) given as its magnitudes ax, ay
 * (|x|, |y|), l1 = |x| + |y| + |z| > 0 and whether x, y, z < 0: the
 * quantization's num + den is, along x, Np = x + l1 = l1 + ax (x >= 0) or
 * Nn = l1 - ax (x < 0) unfolded, and (l1 - ay) sign(x) + l1 = 2 l1 - ay or
 * ay folded (z < 0): in both Np = 2 l1 - Nn; likewise along y with ax.
 * All non-negative, so the quotient is the same unsigned
 * (tests/test_pack.c octahedral_pack_abs_matches). */
static inline uint32_t tgi_oct_pack_abs(uint64_t ax, uint64_t ay, uint64_t l1, int xneg, int yneg, int zneg,
                                        int bits)
{
    const uint64_t q = (1u << bits) - 2, l2 = 2 * l1;
    uint64_t nx = zneg ? ay : l1 - ax, ny = zneg ? ax : l1 - ay;
    if (!xneg) nx = l2 - nx;
    if (!yneg) ny = l2 - ny;
    return (uint32_t)((nx * q + l1) / l2) | ((uint32_t)((ny * q + l1) / l2) << bits);
}
#endif

#if !TG_FIXED
/* m projected on the octahedron |x|+|y|+|z| = 1: its plane coordinates
 * *x, *y, the lower half folded over ((1 - |p.yx|) sign(p), the sign by
 * negation, as exact as a product by -1); ax, ay are |m.x|, |m.y| and l1 =
 * ax + ay + |m.z| as tgi_oct_pack sums them. */
static inline void tgi_oct_project(tg_vec3 m, float ax, float ay, float l1, float *x, float *y)
{
    const float r = 1.0f / l1;
    *x = m.x * r;
    *y = m.y * r;
    if (m.z < 0.0f) {
        const float fx = 1.0f - ay * r, fy = 1.0f - ax * r;
        *x = m.x < 0.0f ? -fx : fx;
        *y = m.y < 0.0f ? -fy : fy;
    }
}

/* tgi_oct_pack of m for l1 in [2^-127, TG_REAL_MAX] (ax, ay, l1 as there),
 * without the quantization's clamps: r = 1 / l1 is finite (1 / l1 <=
 * 2^127) and l1 r <= 1 + 2^-22 (r within 2^-24 relative, or 2^-150 where
 * it is subnormal, l1 < 2^128); l1 >= ax (sums of non-negative terms round
 * no lower than a term), so |m.x| r and its rounded product (ay r in the
 * fold) are at most 1 + 2^-22, and 1 - ay r >= -2^-22: p + 1 rounds into
 * [-2^-22, 2 + 2^-22], u into (0.49, q + 0.5 + 2^-8) for bits <= 15
 * (tests/test_pack.c octahedral_pack_matches_clamped_form). */
static inline uint32_t tgi_oct_pack_l1(tg_vec3 m, float ax, float ay, float l1, int bits)
{
    float x, y;
    tgi_oct_project(m, ax, ay, l1, &x, &y);
    return tgi_oct_quant_unit(x, bits) | (tgi_oct_quant_unit(y, bits) << bits);
}
#define TGI_OCT_L1_MIN 5.87747175e-39f    /* 2^-127 */
#endif

/* Vector m (any length > 0; the zero vector packs as +z) to two `bits`-bit
 * coordinates, u in the low bits, v above it. */
static inline uint32_t tgi_oct_pack(tg_vec3 m, int bits)
{
#if TG_FIXED
    return tgi_oct_pack64(m.x, m.y, m.z, bits);
#else
    /* |.| by the sign bit (three ands): unlike v < 0 ? -v : v it makes -0
     * into +0, which changes no bit below (l1, 1 - ax r) */
    float ax = tgi_abs_bits(m.x), ay = tgi_abs_bits(m.y), l1 = ax + ay + tgi_abs_bits(m.z);
    float x, y;
    if (l1 >= TGI_OCT_L1_MIN && l1 <= TG_REAL_MAX) return tgi_oct_pack_l1(m, ax, ay, l1, bits);
    if (!(l1 > 0.0f) || l1 > TG_REAL_MAX) return tgi_oct_pack(tg_v3(0, 0, TG_ONE), bits);
    /* below 2^-127: 1 / l1 may overflow, the clamps act on infinite or NaN coordinates */
    tgi_oct_project(m, ax, ay, l1, &x, &y);
    return tgi_oct_quant(x, bits) | (tgi_oct_quant(y, bits) << bits);
#endif
}

#if TG_FIXED
/* sign(c) m for a magnitude m < 2^31: c's sign on |c| / |.| */
static inline tg_real tgi_oct_signed(uint64_t m, int32_t c) { return c < 0 ? -(tg_real)m : (tg_real)m; }
#endif

/* The direction of two `bits`-bit octahedral coordinates before its
 * normalisation: integers (the same in both builds) with |x| + |y| + |z| =
 * q = 2^bits - 2, so q^2 / 3 <= |.|^2 <= q^2. */
typedef struct tgi_oct_dir { int32_t x, y, z; } tgi_oct_dir;
/* (the two parts of tgi_oct_unpack_inline always inline: its callers
 * compile as they did when it was one function) */
#if defined(__GNUC__)
#define TGI_OCT_INLINE inline __attribute__((always_inline))
#else
#define TGI_OCT_INLINE inline
#endif
static TGI_OCT_INLINE tgi_oct_dir tgi_oct_fold(uint32_t w, int bits)
{
    int32_t q = (int32_t)((1u << bits) - 2), mask = (int32_t)((1u << bits) - 1);
    int32_t x = 2 * (int32_t)(w & (uint32_t)mask) - q, y = 2 * (int32_t)((w >> bits) & (uint32_t)mask) - q;
    int32_t ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, z = q - ax - ay;
    tgi_oct_dir d;
    if (z < 0) {                      /* the folded lower half */
        int32_t fx = (q - ay) * (x < 0 ? -1 : 1), fy = (q - ax) * (y < 0 ? -1 : 1);
        x = fx; y = fy;
    }
    d.x = x; d.y = y; d.z = z;
    return d;
}

/* The unit vector of an octahedral direction (tgi_oct_fold): the lengths
 * are integers; only the final normalisation is in the number type. */
static TGI_OCT_INLINE tg_vec3 tgi_oct_unit_inline(tgi_oct_dir d)
{
    int32_t x = d.x, y = d.y, z = d.z;
    tg_vec3 n;
#if TG_FIXED
    {
        /* 1/|(x, y, z)| by the integer rsqrt: |x| + |y| + |z| = q, so
         * q^2 / 3 <= |.|^2 <= q^2 < 2^32 (below 3 2^30 with the coordinate
         * 2^bits - 1 the encoder never writes, bits <= 15); x30 in [2^30, 2^32) */
        uint32_t mx = (uint32_t)(x < 0 ? -x : x), my = (uint32_t)(y < 0 ? -y : y), mz = (uint32_t)(z < 0 ? -z : z);
        uint32_t len2 = mx * mx + my * my + mz * mz;
        int k = tgi_clz32_nz(len2) >> 1, shift = 29 - k;   /* (32 - bit length) / 2, len2 > 0 */
        uint64_t r = tgi_rsqrt_q30_fast((uint64_t)len2 << (2 * k));
        /* component c / |.| in Q16.16: |c| r 2^-shift, truncated toward 0 (odd in c) */
        n.x = tgi_oct_signed((mx * r) >> shift, x);
        n.y = tgi_oct_signed((my * r) >> shift, y);
        n.z = tgi_oct_signed((mz * r) >> shift, z);
    }
#else
    {
        float fx = (float)x, fy = (float)y, fz = (float)z;
        float r = tgi_rsqrt_fast(fx * fx + fy * fy + fz * fz);
        n.x = fx * r; n.y = fy * r; n.z = fz * r;
    }
#endif
    return n;
}

/* Unit vector of two `bits`-bit octahedral coordinates. */
static inline tg_vec3 tgi_oct_unpack_inline(uint32_t w, int bits) { return tgi_oct_unit_inline(tgi_oct_fold(w, bits)); }

/* ---- RGB9E5: shared-exponent radiance ---- */
#define TGI_RGB9E5_INVALID 0xF8000000u    /* exponent 31, mantissas 0: "no value" */

#if TG_FIXED
/* TGI_RGB9E5_CARRY_BITS: the pack's exponent from a bit length on a
 * 64-bit core not compiling for size (callgrind 160x120, 2 frames: cornell
 * 634.64M -> 634.37M, columns 269.86M -> 269.69M); elsewhere the trial
 * mantissa and its test (a 32-bit core's 64-bit shifts cost it code). */
#define TGI_RGB9E5_CARRY_BITS (TGI_Q16_WIDE && TGI_CORE64)
/* c / 2^(e - 8) raw rounded half up, for e in [0, 31].  On a 64-bit core
 * in one form without branches: (q 2^8 + 2^(e - 1)) >> e in 64 bits
 * (2^(e - 1) taken as 0 for e = 0), each case's value: for e >= 9 (q +
 * 2^(e - 9)) >> (e - 8), the same floor of the same quotient; for e = 8 q
 * (128 / 256 floors away); for e < 8 q << (8 - e) (2^(e - 1) / 2^e floors
 * away).  A 32-bit core keeps the cases (64-bit shifts by a variable cost
 * it code). */
static inline uint32_t tgi_rgb9e5_mant(tg_real c, int e)
{
#if TGI_CORE64
    uint64_t q = c > 0 ? (uint32_t)c : 0;      /* raw Q16.16; a mantissa is c / 2^(e - 8) raw */
    return (uint32_t)(((q << 8) + (((uint64_t)1 << e) >> 1)) >> e);
#else
    uint32_t q = c > 0 ? (uint32_t)c : 0;
    if (e >= 8) return e - 8 >= 1 ? (q + (1u << (e - 9))) >> (e - 8) : q;
    return q << (8 - e);
#endif
}
static inline uint32_t tgi_rgb9e5_pack_inline(tg_vec3 c)
{
    tg_real mx = tg_max(tg_max(c.x, c.y), c.z);
    int e;
    if (mx <= 0) return 0;
    e = tgi_bit_length64((uint32_t)mx) - 1;     /* exponent field: floor(log2) + 16 */
#if TGI_RGB9E5_CARRY_BITS
    /* raised where the largest mantissa rounds to 512: that mantissa is S
     * >> e for S = mx 2^8 + 2^(e - 1) (2^(e - 1) as 0 for e = 0), and S
     * lies within [2^(e + 8), 2^(e + 10)) (mx < 2^(e + 1)), so S >> e >=
     * 512, S >= 2^(e + 9), exactly when S's bit length is e + 10, not e +
     * 9: the exponent is that length - 9, without the test (a sweep of
     * every mx against the test: the same exponent) */
    e = 55 - tgi_clz64_nz(((uint64_t)(uint32_t)mx << 8) + (((uint64_t)1 << e) >> 1));
#else
    if (tgi_rgb9e5_mant(mx, e) >= 512) e++;
#endif
    return tgi_rgb9e5_mant(c.x, e) | (tgi_rgb9e5_mant(c.y, e) << 9) | (tgi_rgb9e5_mant(c.z, e) << 18)
           | ((uint32_t)e << 27);
}
/* Q16.16 raw m 2^(e - 8), rounded to nearest: m 2^e (< 2^40) rounded at bit 8, saturated */
static inline tg_real tgi_rgb9e5_chan(uint32_t m, int e)
{
    uint64_t v = (((uint64_t)m << e) + 128u) >> 8;
    return v > (uint64_t)TG_REAL_MAX ? TG_REAL_MAX : (tg_real)v;
}
#else
static inline float tgi_pow2f(int k) { tgi_f32_bits b; b.u = (uint32_t)(k + 127) << 23; return b.f; }
/* c / 2^(e - 24) + 1/2, truncated: c at least +0 and no NaN (the clamp
 * below; +0 gives (uint32_t)0.5 = 0, the former test's 0), inv_step =
 * 2^(24 - e) */
static inline uint32_t tgi_rgb9e5_mant(float c, float inv_step) { return (uint32_t)(c * inv_step + 0.5f); }
/* A channel's binary32 bits clamped to [0, (511 / 512) 2^16]: a negative
 * (sign set) or a NaN to +0, and +inf to the top.  Non-negative floats
 * order as their bits, so the clamps and the channels' largest are integer
 * compares (gcc kept the float clamps' branches). */
#define TGI_RGB9E5_TOP_BITS 0x477F8000u       /* 65408 = (511 / 512) 2^16 */
static inline uint32_t tgi_rgb9e5_clamp_bits(float c)
{
    tgi_f32_bits b;
    b.f = c;
    if (b.u > TGI_RGB9E5_TOP_BITS) b.u = b.u > 0x7F800000u ? 0 : TGI_RGB9E5_TOP_BITS;
    return b.u;
}
/* The shared exponent e = floor(log2 max) + 16 from the float's exponent
 * field, plus 1 where the largest mantissa would round to 512: with max =
 * 2^(e - 16) (1 + f), max / 2^(e - 24) = 256 (1 + f) is exact and below
 * 512, so v + 0.5 is exact below 512 (a multiple of v's step 2^-15) and
 * rounds to 512 or more iff v >= 511.5, that is f >= 1 - 2^-9, the 23-bit
 * fraction at least 0x7FC000: the carry of fraction + 0x4000 into the
 * exponent field.  Where e is raised from below 0 to 0 (max < 2^-16), max
 * / 2^-24 < 256 never rounds to 512 and the carried exponent is still at
 * most 0.  The top's fraction, 0x7F8000, carries nothing: e <= 31.  (A
 * sweep of every binary32 channel value, alone and beside others, against
 * the former float clamps and mantissa-and-test: the same words.) */
static inline uint32_t tgi_rgb9e5_pack_inline(tg_vec3 c)
{
    uint32_t r = tgi_rgb9e5_clamp_bits(c.x), g = tgi_rgb9e5_clamp_bits(c.y), b = tgi_rgb9e5_clamp_bits(c.z);
    uint32_t mx = r > g ? r : g;
    tgi_f32_bits f;
    float inv_step;
    int e;
    mx = mx > b ? mx : b;
    if (mx < 0x33800000u) return 0;            /* below half the smallest step, 2^-24 */
    e = (int)((mx + 0x4000u) >> 23) - 127 + 16;   /* floor(log2) + 16 + the rounding's carry, >= -8 */
    if (e < 0) e = 0;
    inv_step = tgi_pow2f(24 - e);
    f.u = r;
    r = tgi_rgb9e5_mant(f.f, inv_step);
    f.u = g;
    g = tgi_rgb9e5_mant(f.f, inv_step);
    f.u = b;
    b = tgi_rgb9e5_mant(f.f, inv_step);
    return r | (g << 9) | (b << 18) | ((uint32_t)e << 27);
}
static inline tg_real tgi_rgb9e5_chan(uint32_t m, int e) { return (float)m * tgi_pow2f(e - 24); }
#endif

/* Linear RGB of a packed word (TGI_RGB9E5_INVALID reads as 0). */
static inline tg_vec3 tgi_rgb9e5_unpack_inline(uint32_t w)
{
    int e = (int)(w >> 27);
    tg_vec3 c;
#if TGI_Q16_WIDE
    /* e in [8, 30] (radiance from 2^-8 up: nearly every word the kernel
     * gathers): m 2^e is a multiple of 2^8, so tgi_rgb9e5_chan's (m 2^e +
     * 128) >> 8 is m 2^(e - 8) exactly, at most 511 2^22 < TG_REAL_MAX
     * (no saturation), in 32 bits: three shifts without the 64-bit
     * rounding and the clamps (the HBIL gather's reads on x86-64: 28
     * instructions -> 17) */
    if ((unsigned)(e - 8) <= 22u) {
        const int s = e - 8;
        c.x = (tg_real)((w & 511u) << s);
        c.y = (tg_real)(((w >> 9) & 511u) << s);
        c.z = (tg_real)(((w >> 18) & 511u) << s);
        return c;
    }
#endif
    c.x = tgi_rgb9e5_chan(w & 511u, e);
    c.y = tgi_rgb9e5_chan((w >> 9) & 511u, e);
    c.z = tgi_rgb9e5_chan((w >> 18) & 511u, e);
    return c;
}

/* The helpers every pass calls, inline, or with TG_OUTLINE_HELPERS (tinygi.h;
 * on at -Os) one copy in pack.c instead of one in each file that calls
 * them: the same code, the same bits. */
#if TG_OUTLINE_HELPERS
tg_vec3 tgi_oct_unit(tgi_oct_dir d);
tg_vec3 tgi_oct_unpack(uint32_t w, int bits);
uint32_t tgi_rgb9e5_pack(tg_vec3 c);
tg_vec3 tgi_rgb9e5_unpack(uint32_t w);
#else
static inline tg_vec3 tgi_oct_unit(tgi_oct_dir d) { return tgi_oct_unit_inline(d); }
static inline tg_vec3 tgi_oct_unpack(uint32_t w, int bits) { return tgi_oct_unpack_inline(w, bits); }
static inline uint32_t tgi_rgb9e5_pack(tg_vec3 c) { return tgi_rgb9e5_pack_inline(c); }
static inline tg_vec3 tgi_rgb9e5_unpack(uint32_t w) { return tgi_rgb9e5_unpack_inline(w); }
#endif

/* ---- unorm8: [0, 1] in a byte ---- */
static inline uint8_t tgi_unorm8_pack(tg_real a)
{
    return (uint8_t)tg_round_int(tg_mul(tg_saturate(a), TG_R(255.0f)));
}
static inline tg_real tgi_unorm8_unpack(uint8_t q)
{
#if TG_FIXED
    return (tg_real)((uint32_t)q * 257u + ((uint32_t)q >> 7));   /* q 65536 / 255, rounded */
#else
    return (float)q * (1.0f / 255.0f);
#endif
}

#endif
