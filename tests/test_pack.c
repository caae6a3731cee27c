/* SPDX-License-Identifier: MIT */
/*
 * test_pack.c - the storage formats (raster/pack.h): the same bits in both
 * number types, round trips within the format's step, saturation instead of
 * wrapping, nothing non-finite; the G-buffer of a frame that reads no
 * material (gview.h): 6 bytes a pixel, the normal within 2x8's step.
 */
#include <math.h>
#include <stdlib.h>
#include "check.h"
#include "raster/gview.h"

static tg_real rv(double v) { return tg_from_float((float)v); }
static double dv(tg_real v) { return (double)tg_to_float(v); }

/* A deterministic pseudo-random number in [0, 1). */
static double rnd(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (double)(*s >> 8) / 16777216.0;
}

/* Both builds write the IEEE bits of the same value. */
TEST(depth_is_binary32_in_both_builds)
{
    CHECK(tgi_depth_pack(TG_ONE) == 0x3F800000u, "1.0 -> 0x%08x", (unsigned)tgi_depth_pack(TG_ONE));
    CHECK(tgi_depth_pack(TG_R(1.5f)) == 0x3FC00000u, "1.5 -> 0x%08x", (unsigned)tgi_depth_pack(TG_R(1.5f)));
    CHECK(tgi_depth_pack(TG_R(0.25f)) == 0x3E800000u, "0.25 -> 0x%08x", (unsigned)tgi_depth_pack(TG_R(0.25f)));
    CHECK(tgi_depth_pack(TG_R(1000.0f)) == 0x447A0000u, "1000 -> 0x%08x", (unsigned)tgi_depth_pack(TG_R(1000.0f)));
    CHECK(tgi_depth_pack(0) == 0 && tgi_depth_pack(TG_R(-2.0f)) == 0, "sky and negative depths pack as 0");
    CHECK(tgi_depth_unpack(0) == 0, "0 is sky");
}

/* Round trips: exact in float, exact below 256 in Q16.16 and within 2^-24
 * above; the packed words order like the depths (the raster's depth test). */
TEST(depth_round_trip_and_order)
{
    uint32_t s = 7, prev_bits = 0;
    int i, order_ok = 1, exact_ok = 1;
    double worst = 0;
    tg_real prev = 0;
    for (i = 0; i < 200000; i++) {
        double d = exp(-8.0 + 15.0 * rnd(&s));   /* 3e-4 .. 1.1e3 */
        tg_real z = rv(d), back;
        uint32_t b = tgi_depth_pack(z);
        if (z <= 0) continue;
        back = tgi_depth_unpack(b);
        if (z < TG_R(256.0f) && back != z) exact_ok = 0;
        if (fabs(dv(back) - dv(z)) / dv(z) > worst) worst = fabs(dv(back) - dv(z)) / dv(z);
        if ((z > prev) != (b > prev_bits) && z != prev) order_ok = 0;
        prev = z; prev_bits = b;
    }
    CHECK(exact_ok, "a depth below 256 does not round-trip exactly");
    CHECK(worst <= 6e-8, "worst relative round-trip error %.3g", worst);
    CHECK(order_ok, "packed depths do not order like the depths");
#if TG_FIXED
    CHECK(tgi_depth_unpack(tgi_depth_pack(TG_REAL_MAX)) == TG_REAL_MAX, "the largest Q16.16 depth saturates, never wraps");
    CHECK(tgi_depth_unpack(0x7F000000u) == TG_REAL_MAX, "a float depth beyond Q16.16 saturates");
#endif
}

#if TG_FIXED
/* Every binary32 word (a stride through all 2^32, and each exponent's
 * significands at the rounding points) reads back as z 2^16 rounded to
 * nearest, ties up, saturated: 0 below 2^-17, TG_REAL_MAX from 2^15
 * (infinities and NaN too), the sign ignored. */
static int64_t depth_word_q16(uint32_t b)
{
    int e = (int)((b >> 23) & 0xFF);
    double z = ldexp((double)((b & 0x7FFFFFu) | 0x800000u), e - 150), r = floor(z * 65536.0 + 0.5);
    if (e == 0 && (b & 0x7FFFFFFFu) == 0) return 0;
    return e >= 142 || r > (double)TG_REAL_MAX ? TG_REAL_MAX : (int64_t)r;
}

/* tgi_depth_unpack and both of pack.h's forms (32-bit shifts on 32-bit
 * cores, a 64-bit shift on 64-bit hosts: each tested wherever the tests
 * run) against depth_word_q16 */
#define DEPTH_WORD_CHECK(w) do { \
        const uint32_t w_ = (w); \
        const int64_t want_ = depth_word_q16(w_); \
        n++; \
        if ((tgi_depth_unpack(w_) != want_ || tgi_depth_unpack32(w_) != want_ || tgi_depth_unpack64(w_) != want_) \
            && bad++ < 5) \
            fprintf(stderr, "depth word 0x%08x -> %ld (32-bit form %ld, 64-bit form %ld), want %ld\n", (unsigned)w_, \
                    (long)tgi_depth_unpack(w_), (long)tgi_depth_unpack32(w_), (long)tgi_depth_unpack64(w_), (long)want_); \
    } while (0)

TEST(depth_unpack_every_word)
{
    uint64_t b;
    uint32_t e, k;
    long bad = 0, n = 0;
    for (b = 0; b <= 0xFFFFFFFFu; b += 97) DEPTH_WORD_CHECK((uint32_t)b);
    for (e = 0; e < 256; e++)
        for (k = 0; k < 24; k++) {
            uint32_t half = 1u << k, m[4] = { half - 1, half, half + 1, 0x7FFFFFu }, i;
            for (i = 0; i < 4; i++) DEPTH_WORD_CHECK((e << 23) | (m[i] & 0x7FFFFFu));
        }
    CHECK(bad == 0, "%ld of %ld depth words read back wrong", bad, n);
}

/* The two forms agree on every word: outside e = 110 .. 141 neither reads
 * the significand (0 or TG_REAL_MAX from the sign and e alone), so a few
 * significands there, at every exponent in both signs; inside, every
 * significand of each of the 32 exponents (the words that reach the
 * shifts) in both signs.  With depth_unpack_every_word (the values), both
 * are the rounded depth on every word. */
TEST(depth_unpack_forms_agree)
{
    uint32_t e, f, sign;
    long bad = 0, n = 0;
#define DEPTH_FORMS_AGREE(w) do { \
        n++; \
        if (tgi_depth_unpack32(w) != tgi_depth_unpack64(w) && bad++ < 5) \
            fprintf(stderr, "depth word 0x%08x: 32-bit %ld, 64-bit %ld\n", (unsigned)(w), \
                    (long)tgi_depth_unpack32(w), (long)tgi_depth_unpack64(w)); \
    } while (0)
    for (sign = 0; sign < 2; sign++)
        for (e = 110; e < 142; e++)
            for (f = 0; f <= 0x7FFFFFu; f++) DEPTH_FORMS_AGREE((sign << 31) | (e << 23) | f);
    for (sign = 0; sign < 2; sign++)
        for (e = 0; e < 256; e++) {
            const uint32_t fs[6] = { 0, 1, 0x3FFFFFu, 0x400000u, 0x7FFFFEu, 0x7FFFFFu };
            for (f = 0; f < 6; f++) DEPTH_FORMS_AGREE((sign << 31) | (e << 23) | fs[f]);
        }
#undef DEPTH_FORMS_AGREE
    CHECK(bad == 0, "%ld of %ld depth words unpack apart in the two forms", bad, n);
}
#undef DEPTH_WORD_CHECK
#endif

static double angle_deg(tg_vec3 a, double bx, double by, double bz)
{
    double d = (dv(a.x) * bx + dv(a.y) * by + dv(a.z) * bz) /
               sqrt(dv(a.x) * dv(a.x) + dv(a.y) * dv(a.y) + dv(a.z) * dv(a.z));
    if (d > 1) d = 1;
    return acos(d) * 180.0 / 3.14159265358979;
}

/* Octahedral unit vectors: every direction within the step's angle, unit
 * length, axis vectors exactly, the same words in both builds. */
static void oct_round_trip(int bits, double max_deg)
{
    uint32_t s = 11;
    double worst = 0, worst_len = 0;
    int i;
    for (i = 0; i < 100000; i++) {
        double z = 2 * rnd(&s) - 1, phi = 6.28318530718 * rnd(&s), r = sqrt(1 - z * z);
        double x = r * cos(phi), y = r * sin(phi);
        tg_vec3 n = tgi_oct_unpack(tgi_oct_pack(tg_v3(rv(x), rv(y), rv(z)), bits), bits);
        double a = angle_deg(n, x, y, z), len = sqrt(dv(n.x) * dv(n.x) + dv(n.y) * dv(n.y) + dv(n.z) * dv(n.z));
        if (a > worst) worst = a;
        if (fabs(len - 1) > worst_len) worst_len = fabs(len - 1);
    }
    CHECK(worst <= max_deg, "2x%d: worst angle %.4f deg (bound %.4f)", bits, worst, max_deg);
    CHECK(worst_len <= 1e-4, "2x%d: decoded length off by %.3g", bits, worst_len);
}

/* The second depth layer's 8-bit code (tgi_back_code): a back face behind
 * the pixel's depth z_f comes back within half a step of its thickness
 * (1/32 of t = z_b / z_f - 1, plus the number type's rounding), the codes
 * order as the depths, z_b = z_f is a sheet (returned exactly), a face in
 * front of the surface or a pixel of sky has none, and thicknesses past
 * the range take its ends; the same codes in both builds (away from a
 * step's middle). */
TEST(back_face_code)
{
    static const double zfs[] = { 0.05, 0.3, 1.0, 7.5, 120.0, 900.0 };
    size_t k;
    int i, worse = 0, disorder = 0;
    double worst = 0;
    for (k = 0; k < sizeof zfs / sizeof zfs[0]; k++) {
        tg_real zf = rv(zfs[k]);
        uint8_t last = TGI_BACK_SHEET;
        CHECK(tgi_back_code(zf, zf) == TGI_BACK_SHEET && tgi_back_decode(TGI_BACK_SHEET, zf) == zf,
              "z_f %g: a sheet is its own depth", zfs[k]);
        CHECK(tgi_back_code(zf, rv(zfs[k] * 0.9)) == TGI_BACK_NONE && tgi_back_code(0, zf) == TGI_BACK_NONE &&
              tgi_back_decode(TGI_BACK_NONE, zf) == 0, "z_f %g: in front of the surface or on sky, none", zfs[k]);
        for (i = 0; i <= 400; i++) {
            double t = pow(2.0, -9.0 + 14.5 * i / 400.0), zb = dv(zf) * (1 + t);   /* 2^-9 .. 2^5.5 */
            tg_real zbr = rv(zb);
            uint8_t c;
            double got, want, err, tol;
            if (TG_FIXED && zb > 30000) break;   /* Q16.16's range */
            c = tgi_back_code(zf, zbr);
            got = dv(tgi_back_decode(c, zf));
            want = dv(zbr);
            err = fabs(got - want) / (want - dv(zf));   /* relative to the thickness */
            tol = 1.0 / 32 + (TG_FIXED ? 4.0 / 65536 / (want - dv(zf)) + 1e-3 : 1e-5);
            if (err > tol) { if (worse < 4) printf("# z_f %g t %g: code %d gives %g for %g\n", zfs[k], t, c, got, want); worse++; }
            if (err > worst && zb - dv(zf) > 1e-2) worst = err;
            if (c < last) disorder++;
            last = c;
        }
    }
    CHECK(worse == 0, "%d decoded back faces off by more than half a step", worse);
    CHECK(disorder == 0, "%d codes out of order", disorder);
    CHECK(worst > 0.005 && worst < 1.0 / 32 + 1e-3, "worst relative thickness error %g", worst);
    /* past the range: the ends */
    CHECK(tgi_back_code(TG_ONE, rv(1.0 + 1e-4)) == 2, "thinner than 2^-10: the smallest code, got %d",
          tgi_back_code(TG_ONE, rv(1.0 + 1e-4)));
    CHECK(tgi_back_code(TG_ONE, rv(200.0)) == TGI_BACK_LAST, "thicker than 58 z_f: the largest code");
    CHECK(fabs(dv(tgi_back_decode(TGI_BACK_LAST, TG_ONE)) - 59.0) < 1e-3, "the largest code: t = 58, got z_b %g",
          dv(tgi_back_decode(TGI_BACK_LAST, TG_ONE)));
    /* the same code in both builds: t = 0.3 and 3 at z_f 2 (not at a step's middle) */
    CHECK(tgi_back_code(rv(2.0), rv(2.6)) == 2 + 16 * 8 + 3 && tgi_back_code(rv(2.0), rv(8.0)) == 2 + 16 * 11 + 8,
          "codes %d %d", tgi_back_code(rv(2.0), rv(2.6)), tgi_back_code(rv(2.0), rv(8.0)));
}

TEST(octahedral_normals)
{
    static const int axes[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
    int k;
    oct_round_trip(11, 0.125);
    oct_round_trip(8, 1.0);
    for (k = 0; k < 6; k++) {
        tg_vec3 a = tg_v3(tg_from_int(axes[k][0]), tg_from_int(axes[k][1]), tg_from_int(axes[k][2]));
        tg_vec3 b = tgi_oct_unpack(tgi_oct_pack(a, 11), 11);
        CHECK(angle_deg(b, axes[k][0], axes[k][1], axes[k][2]) == 0, "axis %d comes back at %.4f deg", k,
              angle_deg(b, axes[k][0], axes[k][1], axes[k][2]));
    }
    /* the same words in both builds: +x, a diagonal, below the horizon, and the zero vector (as +z) */
    CHECK(tgi_oct_pack(tg_v3(TG_ONE, 0, 0), 11) == (2046u | (1023u << 11)), "+x packs as 0x%x",
          (unsigned)tgi_oct_pack(tg_v3(TG_ONE, 0, 0), 11));
    CHECK(tgi_oct_pack(tg_v3(TG_ONE, TG_ONE, TG_ONE), 11) == (1364u | (1364u << 11)), "(1,1,1) packs as 0x%x",
          (unsigned)tgi_oct_pack(tg_v3(TG_ONE, TG_ONE, TG_ONE), 11));
    CHECK(tgi_oct_pack(tg_v3(TG_R(-0.5f), TG_R(0.25f), TG_R(-0.25f)), 8) == (32u | (191u << 8)),
          "(-0.5, 0.25, -0.25) packs as 0x%x", (unsigned)tgi_oct_pack(tg_v3(TG_R(-0.5f), TG_R(0.25f), TG_R(-0.25f)), 8));
    CHECK(tgi_oct_pack(tg_v3(0, 0, 0), 8) == tgi_oct_pack(tg_v3(0, 0, TG_ONE), 8), "the zero vector packs as +z");
}

/* src/raster/pack.h's unpack before the magnitudes were computed directly
 * (as of commit fb8a8d5): the oracle the faster one must equal bit for bit
 * on every word (the G-buffer's and the goldens' normals). */
#if TG_FIXED
static tg_real oracle_oct_scale(int32_t c, uint64_t r, int shift)
{
    uint64_t a = (uint64_t)(c < 0 ? -(int64_t)c : c) * r >> shift;
    return c < 0 ? -(tg_real)a : (tg_real)a;
}
#endif
static tg_vec3 oracle_oct_unpack(uint32_t w, int bits)
{
    int32_t q = (int32_t)((1u << bits) - 2), mask = (int32_t)((1u << bits) - 1);
    int32_t x = 2 * (int32_t)(w & (uint32_t)mask) - q, y = 2 * (int32_t)((w >> bits) & (uint32_t)mask) - q;
    int32_t ax = x < 0 ? -x : x, ay = y < 0 ? -y : y, z = q - ax - ay;
    tg_vec3 n;
    if (z < 0) {
        int32_t fx = (q - ay) * (x < 0 ? -1 : 1), fy = (q - ax) * (y < 0 ? -1 : 1);
        x = fx; y = fy;
    }
#if TG_FIXED
    {
        uint64_t len2 = (uint64_t)((int64_t)x * x + (int64_t)y * y + (int64_t)z * z), r;
        int b = tgi_bit_length64(len2), k = (32 - b) >> 1, shift = 29 - k;
        r = tgi_rsqrt_q30_fast(len2 << (2 * k));
        n.x = oracle_oct_scale(x, r, shift);
        n.y = oracle_oct_scale(y, r, shift);
        n.z = oracle_oct_scale(z, r, shift);
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

/* Every word of 2x4, 2x8 and 2x11 bits (2x15 at a stride) decodes to the
 * oracle's bits, with the coordinate 2^bits - 1 the encoder never writes. */
TEST(octahedral_unpack_matches_oracle)
{
    static const int widths[4] = { 4, 8, 11, 15 };
    int k;
    for (k = 0; k < 4; k++) {
        int bits = widths[k];
        uint64_t w, n = (uint64_t)1 << (2 * bits), step = bits > 12 ? 4099u : 1u;
        long bad = 0, count = 0;
        for (w = 0; w < n; w += step) {
            tg_vec3 a = tgi_oct_unpack((uint32_t)w, bits), b = oracle_oct_unpack((uint32_t)w, bits);
            count++;
            if (memcmp(&a.x, &b.x, sizeof a.x) || memcmp(&a.y, &b.y, sizeof a.y) || memcmp(&a.z, &b.z, sizeof a.z)) {
                if (bad++ < 5) fprintf(stderr, "2x%d word 0x%x: (%g %g %g), oracle (%g %g %g)\n", bits, (unsigned)w,
                                       dv(a.x), dv(a.y), dv(a.z), dv(b.x), dv(b.y), dv(b.z));
            }
        }
        CHECK(bad == 0 && count >= 256, "2x%d: %ld of %ld words differ from the oracle", bits, bad, count);
    }
}

/* RGB9E5: within half a step of the largest channel's exponent, the same
 * words in both builds, saturating, never negative or non-finite. */
TEST(shared_exponent_rgb)
{
    uint32_t s = 3;
    int i, ok = 1, ok_exp = 1;
    double worst = 0;
    for (i = 0; i < 100000; i++) {
        double m = exp(-10.0 + 20.0 * rnd(&s));   /* 4.5e-5 .. 2.2e4 */
        double c[3], step;
        uint32_t w;
        tg_vec3 v, back;
        int k;
        for (k = 0; k < 3; k++) c[k] = m * rnd(&s);
        v = tg_v3(rv(c[0]), rv(c[1]), rv(c[2]));
        w = tgi_rgb9e5_pack(v);
        back = tgi_rgb9e5_unpack(w);
        m = dv(tg_max(tg_max(v.x, v.y), v.z));
        if (m >= 1.0 / 65536) ok_exp &= w >> 27 == (uint32_t)floor(log2(m)) + 16u || w >> 27 == (uint32_t)floor(log2(m)) + 17u;
        step = pow(2.0, (double)(w >> 27) - 24);  /* 9-bit mantissas of the shared exponent */
        for (k = 0; k < 3; k++) {
            double in = k == 0 ? dv(v.x) : k == 1 ? dv(v.y) : dv(v.z);
            double out = k == 0 ? dv(back.x) : k == 1 ? dv(back.y) : dv(back.z);
            double e = fabs(out - in) / step;
            if (e > worst) worst = e;
            if (!(out >= 0)) ok = 0;
        }
    }
    CHECK(worst <= 0.5 + 1e-3, "worst error %.4f steps", worst);
    CHECK(ok_exp, "the shared exponent is not the largest channel's (or one more, when it rounds up)");
    CHECK(ok, "a channel came back negative or NaN");
    CHECK(tgi_rgb9e5_pack(tg_v3(TG_ONE, TG_R(0.5f), TG_R(0.25f))) == (256u | (128u << 9) | (64u << 18) | (16u << 27)),
          "(1, 0.5, 0.25) packs as 0x%08x", (unsigned)tgi_rgb9e5_pack(tg_v3(TG_ONE, TG_R(0.5f), TG_R(0.25f))));
    CHECK(tgi_rgb9e5_pack(tg_v3(TG_R(-1.0f), 0, 0)) == 0, "negative radiance stores 0");
    {
        tg_vec3 big = tgi_rgb9e5_unpack(tgi_rgb9e5_pack(tg_v3(TG_REAL_MAX, TG_REAL_MAX, 0)));
        CHECK(big.x > TG_R(30000.0f) && big.x == big.y && big.z == 0, "the largest value saturates: %g", dv(big.x));
        CHECK(tgi_rgb9e5_pack(tg_v3(TG_REAL_MAX, 0, 0)) != TGI_RGB9E5_INVALID, "saturation never gives the invalid mark");
    }
    {
        tg_vec3 inv = tgi_rgb9e5_unpack(TGI_RGB9E5_INVALID);
        CHECK(inv.x == 0 && inv.y == 0 && inv.z == 0, "the invalid mark reads as 0");
    }
#if !TG_FIXED
    {
        float nan = 0.0f / 0.0f;
        CHECK(tgi_rgb9e5_pack(tg_v3(nan, 1.0f / 0.0f, 1.0f)) == tgi_rgb9e5_pack(tg_v3(0, 65408.0f, 1.0f)),
              "NaN stores 0, infinity saturates");
    }
#endif
}

/* Every mantissa and exponent of a channel reads back as m 2^(e - 24):
 * exactly in float, rounded to nearest (ties up) and saturated in Q16.16. */
TEST(shared_exponent_every_channel)
{
    uint32_t m, e;
    long bad = 0;
    for (e = 0; e < 32; e++)
        for (m = 0; m < 512; m++) {
            tg_vec3 c = tgi_rgb9e5_unpack(m | ((511u - m) << 9) | (m << 18) | (e << 27));
            double want = ldexp((double)m, (int)e - 24), want2 = ldexp((double)(511u - m), (int)e - 24);
#if TG_FIXED
            want = floor(want * 65536.0 + 0.5); want2 = floor(want2 * 65536.0 + 0.5);
            if (want > (double)TG_REAL_MAX) want = (double)TG_REAL_MAX;
            if (want2 > (double)TG_REAL_MAX) want2 = (double)TG_REAL_MAX;
#endif
            if (((double)c.x != want || (double)c.y != want2 || (double)c.z != want) && bad++ < 5)
                fprintf(stderr, "rgb9e5 m %u e %u: %g %g %g\n", (unsigned)m, (unsigned)e, dv(c.x), dv(c.y), dv(c.z));
        }
    CHECK(bad == 0, "%ld channel values read back wrong", bad);
}

TEST(unorm8_ao)
{
    int q, ok = 1;
    for (q = 0; q < 256; q++) {
        tg_real a = tgi_unorm8_unpack((uint8_t)q);
        if (tgi_unorm8_pack(a) != q) ok = 0;
        if (fabs(dv(a) - q / 255.0) > 1e-5) ok = 0;
    }
    CHECK(ok, "a byte does not round-trip");
    CHECK(tgi_unorm8_unpack(255) == TG_ONE && tgi_unorm8_unpack(0) == 0, "0 and 1 are exact");
    CHECK(tgi_unorm8_pack(TG_R(2.0f)) == 255 && tgi_unorm8_pack(TG_R(-1.0f)) == 0, "AO saturates to [0, 1]");
    CHECK(tgi_unorm8_pack(TG_R(0.5f)) == 128, "0.5 packs as %d", tgi_unorm8_pack(TG_R(0.5f)));
}

/* A G-buffer without material (tgi_gbuffer_carve_geometry, an AO-only
 * frame's): depth as stored, the normal within the 2x8 step, no material
 * (albedo, F0, emissive and the light sent read 0), copies keep it. */
TEST(geometry_gbuffer_without_material)
{
    tgi_material mats[2];
    tgi_gbuffer g, h;
    tgi_gview v, w;
    size_t bytes = tgi_gbuffer_carve_geometry(&g, 4, 3, NULL), full = tgi_gbuffer_carve(&h, 4, 3, NULL);
    void *mem = calloc(bytes, 1), *mem2 = calloc(bytes, 1);
    tg_vec3 n = tg_v3(TG_R(0.48f), TG_R(-0.6f), TG_R(0.64f)), back;
    double a;
    memset(mats, 0, sizeof mats);
    mats[1].albedo = tg_v3(TG_R(0.5f), TG_R(0.5f), TG_R(0.5f));
    mats[1].f0 = TG_R(0.25f);
    tgi_material_finish(&mats[1]);
#if TG_WIDE_STORAGE
    CHECK(bytes == full, "wide storage keeps every plane (%lu vs %lu bytes)", (unsigned long)bytes, (unsigned long)full);
#else
    CHECK(bytes == 48 + 32 && full == 48 + 48, "12 pixels: %lu bytes (depth 48 + normal 24, each to 16), full %lu",
          (unsigned long)bytes, (unsigned long)full);
#endif
    tgi_gbuffer_carve_geometry(&g, 4, 3, mem);
    tgi_gbuffer_carve_geometry(&h, 4, 3, mem2);
    g.materials = h.materials = mats;
    tgi_gb_set(&g, 5, TG_R(2.5f), n, 1);
    tgi_gview_of(&v, &g, NULL);
    tgi_gview_of(&w, &h, NULL);
    tgi_gview_copy_pixel(&h, 5, &v, 5);
    back = tgi_gv_normal(&w, 5);
    a = angle_deg(back, 0.48, -0.6, 0.64);
    CHECK(tgi_gv_depth(&w, 5) == TG_R(2.5f) && !tgi_gv_is_sky(&w, 5) && tgi_gv_is_sky(&w, 4), "depth and sky as stored");
    CHECK(a <= 1.0, "the normal comes back %.3f deg off (2x8 bound 1 deg)", a);
#if !TG_WIDE_STORAGE
    CHECK(!tgi_gb_has_material(&g) && tgi_gv_material(&w, 5) == NULL, "no material plane, no material");
    CHECK(tgi_gv_f0(&w, 5) == 0 && tgi_gv_albedo(&w, 5).x == 0 && tgi_gv_lit(&w, 5, tg_v3(TG_ONE, TG_ONE, TG_ONE)).y == 0,
          "albedo, F0 and the light sent read 0");
#endif
    free(mem);
    free(mem2);
}

#if !TG_FIXED
/* The float octahedral packing as it was written before its clamps were
 * dropped and its fold negated (pack.h tgi_oct_quant_unit's proof): the
 * oracle the packing must match bit for bit. */
static uint32_t oct_quant_clamped(float p, int bits)
{
    float q = (float)((1u << bits) - 2);
    float u = (p + 1.0f) * 0.5f * q + 0.5f;
    if (!(u > 0.0f)) return 0;
    if (u >= q) return (uint32_t)q;
    return (uint32_t)u;
}
static uint32_t oct_pack_clamped(tg_vec3 m, int bits)
{
    float ax = fabsf(m.x), ay = fabsf(m.y), l1 = ax + ay + fabsf(m.z), x, y, r;
    if (!(l1 > 0.0f) || l1 > TG_REAL_MAX) return oct_pack_clamped(tg_v3(0, 0, TG_ONE), bits);
    r = 1.0f / l1;
    x = m.x * r; y = m.y * r;
    if (m.z < 0.0f) {
        float fx = (1.0f - ay * r) * (m.x < 0.0f ? -1.0f : 1.0f), fy = (1.0f - ax * r) * (m.y < 0.0f ? -1.0f : 1.0f);
        x = fx; y = fy;
    }
    return oct_quant_clamped(x, bits) | (oct_quant_clamped(y, bits) << bits);
}

/* Random components over 2^-141 .. 2^126.6 (sums past FLT_MAX too) with
 * either sign, zeros (+0 and -0) and equal magnitudes among them, 8 and 11
 * bits. */
TEST(octahedral_pack_matches_clamped_form)
{
    uint32_t s = 12345;
    int i, bad = 0;
    for (i = 0; i < 400000; i++) {
        float c[3];
        int k, bits = (i & 1) ? 11 : 8;
        for (k = 0; k < 3; k++) {
            double r = rnd(&s), e = rnd(&s);
            int kind = (int)(rnd(&s) * 8.0);
            c[k] = (float)(ldexp(0.5 + r, (int)(e * 267.0) - 140) * (rnd(&s) < 0.5 ? -1.0 : 1.0));
            if (kind == 0) c[k] = 0.0f;
            else if (kind == 1) c[k] = -0.0f;
            else if (kind == 2 && k > 0) c[k] = c[k - 1];
            else if (kind == 3) c[k] = (float)(r * 2.0 - 1.0);
        }
        if (tgi_oct_pack(tg_v3(c[0], c[1], c[2]), bits) != oct_pack_clamped(tg_v3(c[0], c[1], c[2]), bits)) {
            if (bad++ < 5)
                CHECK(0, "(%g, %g, %g) at %d bits packs as 0x%x, the clamped form 0x%x", (double)c[0], (double)c[1],
                      (double)c[2], bits, (unsigned)tgi_oct_pack(tg_v3(c[0], c[1], c[2]), bits),
                      (unsigned)oct_pack_clamped(tg_v3(c[0], c[1], c[2]), bits));
        }
    }
    CHECK(bad == 0, "%d of 400000 vectors differ", bad);
}
#endif

#if TG_FIXED
/* tgi_depth_pack as it was written with its branches (b <= 24, the
 * rounding's carry). */
static uint32_t depth_pack_branchy(tg_real z)
{
    uint32_t v = (uint32_t)z, m;
    int b, e;
    if (z <= 0) return 0;
    b = tgi_bit_length64(v);
    e = b - 1 - 16;
    if (b <= 24) {
        m = v << (24 - b);
    } else {
        int s = b - 24;
        m = (v + (1u << (s - 1))) >> s;
        if (m >> 24) { m >>= 1; e++; }
    }
    return ((uint32_t)(e + 127) << 23) | (m & 0x7FFFFFu);
}

/* tgi_depth_pack (and tgi_depth_pack_pos, the rasterizer's for z >= 1
 * raw) give the branchy form's words: every word below 2^25 (the exact
 * shifts, and the first roundings), each power of two's neighbourhood (the
 * carries), 2,000,000 random ones, and 0 for z <= 0. */
TEST(depth_pack_matches_branchy_form)
{
    uint32_t s = 777, v;
    int b, d, bad = 0;
    for (v = 1; v < (1u << 25); v++)
        bad += tgi_depth_pack((tg_real)v) != depth_pack_branchy((tg_real)v) ||
               tgi_depth_pack_pos((tg_real)v) != depth_pack_branchy((tg_real)v);
    for (b = 25; b <= 31; b++)
        for (d = -300; d <= 300; d++) {
            v = (uint32_t)((int64_t)1 << b) + (uint32_t)d;
            if (v >= 1u && v <= 0x7FFFFFFFu)
                bad += tgi_depth_pack((tg_real)v) != depth_pack_branchy((tg_real)v) ||
                       tgi_depth_pack_pos((tg_real)v) != depth_pack_branchy((tg_real)v);
        }
    for (d = 0; d < 2000000; d++) {
        s = s * 1664525u + 1013904223u;
        v = (s >> 1) >> (s & 7);
        bad += tgi_depth_pack((tg_real)v) != depth_pack_branchy((tg_real)v);
        bad += tgi_depth_pack(-(tg_real)v) != 0u;
    }
    bad += tgi_depth_pack(TG_REAL_MIN) != 0u || tgi_depth_pack(TG_REAL_MAX) != depth_pack_branchy(TG_REAL_MAX);
    CHECK(bad == 0, "%d depths pack apart", bad);
}

static int64_t asr_zero(int64_t v, int sh) { return v >= 0 ? v >> sh : -((-v) >> sh); }

/* The rasterizer's packing of a normal sum s >> sm (rounded toward zero)
 * by magnitudes and s <= -2^sm (tgi_oct_pack_abs) is tgi_oct_pack64 of the
 * shifted components: random sums below 2^(sm + 31), with zeros, sums
 * near -2^sm, +-(2^sm - 1) (shifting to 0) and equal magnitudes, 8 and 11
 * bits, shifts 0 .. 30. */
TEST(octahedral_pack_abs_matches)
{
    uint32_t s = 4242;
    int i, bad = 0;
    for (i = 0; i < 400000; i++) {
        int64_t c[3], m[3];
        uint64_t a[3];
        int k, bits = (i & 1) ? 11 : 8, sm = (int)(rnd(&s) * 31.0);
        const int64_t neg = -((int64_t)1 << sm);
        uint32_t want, got;
        for (k = 0; k < 3; k++) {
            int kind = (int)(rnd(&s) * 8.0);
            double r = rnd(&s) * 2.0 - 1.0, e = rnd(&s);
            c[k] = (int64_t)(r * ldexp(1.0, sm + (int)(e * 31.0)));
            if (kind == 0) c[k] = 0;
            else if (kind == 1) c[k] = neg + (int64_t)(rnd(&s) * 3.0) - 1;
            else if (kind == 2) c[k] = (rnd(&s) < 0.5 ? -1 : 1) * (((int64_t)1 << sm) - 1);
            else if (kind == 3 && k > 0) c[k] = -c[k - 1];
            m[k] = asr_zero(c[k], sm);
            a[k] = (uint64_t)(m[k] < 0 ? -m[k] : m[k]);
        }
        if (!(a[0] + a[1] + a[2])) continue;
        want = tgi_oct_pack64(m[0], m[1], m[2], bits);
        got = tgi_oct_pack_abs(a[0], a[1], a[0] + a[1] + a[2], c[0] <= neg, c[1] <= neg, c[2] <= neg, bits);
        if (want != got && bad++ < 5)
            CHECK(0, "(%lld, %lld, %lld) >> %d at %d bits: 0x%x, tgi_oct_pack64 0x%x", (long long)c[0],
                  (long long)c[1], (long long)c[2], sm, bits, (unsigned)got, (unsigned)want);
    }
    CHECK(bad == 0, "%d of 400000 vectors differ", bad);
}
#endif

int main(void)
{
    RUN(depth_is_binary32_in_both_builds);
    RUN(depth_round_trip_and_order);
#if TG_FIXED
    RUN(depth_unpack_every_word);
    RUN(depth_unpack_forms_agree);
    RUN(depth_pack_matches_branchy_form);
    RUN(octahedral_pack_abs_matches);
#endif
    RUN(back_face_code);
    RUN(octahedral_normals);
    RUN(octahedral_unpack_matches_oracle);
#if !TG_FIXED
    RUN(octahedral_pack_matches_clamped_form);
#endif
    RUN(shared_exponent_rgb);
    RUN(shared_exponent_every_channel);
    RUN(unorm8_ao);
    RUN(geometry_gbuffer_without_material);
    return check_summary();
}
