/* SPDX-License-Identifier: MIT */
/*
 * text.c - the text builder of text.h (error messages, the plan's
 * explanation).
 */
#include <string.h>
#include "text.h"

void tgi_text_init(tgi_text *t, char *buf, size_t size)
{
    t->buf = buf;
    t->size = buf ? size : 0;
    t->at = 0;
    if (t->size) buf[0] = '\0';
}

void tgi_text_put(tgi_text *t, const char *s)
{
    size_t n = strlen(s);
    if (t->size && t->at < t->size - 1) {
        size_t room = t->size - 1 - t->at, k = n < room ? n : room;
        memcpy(t->buf + t->at, s, k);
        t->buf[t->at + k] = '\0';
    }
    t->at += n;
}

void tgi_text_put_uint(tgi_text *t, size_t v)
{
    char tmp[24], out[24];
    int n = 0, i;
    do { tmp[n++] = (char)('0' + v % 10u); v /= 10u; } while (v && n < 23);
    for (i = 0; i < n; i++) out[i] = tmp[n - 1 - i];
    out[n] = '\0';
    tgi_text_put(t, out);
}

void tgi_text_put_int(tgi_text *t, long v)
{
    unsigned long m = (unsigned long)v;
    if (v < 0) { tgi_text_put(t, "-"); m = 0ul - m; }   /* LONG_MIN too */
    tgi_text_put_uint(t, (size_t)m);
}

/* "I[.DDD]" (the fraction FRAC/1000 without its trailing zeros), then
 * "e+E" when e > 0. */
static void put_decimal(tgi_text *t, uint32_t whole, uint32_t frac, int e)
{
    char digits[5];
    int k;
    if (frac >= 1000u) { whole++; frac -= 1000u; }
    tgi_text_put_uint(t, whole);
    if (frac) {
        digits[0] = '.';
        for (k = 3; k >= 1; k--) { digits[k] = (char)('0' + frac % 10u); frac /= 10u; }
        digits[4] = '\0';
        for (k = 3; k > 1 && digits[k] == '0'; k--) digits[k] = '\0';
        tgi_text_put(t, digits);
    }
    if (e > 0) { tgi_text_put(t, "e+"); tgi_text_put_uint(t, (size_t)e); }
}

#if TG_FIXED
/* The text the float code below gives for tg_to_float(r), in integers, so
 * that Q16.16 links no soft float (README "Flash size"): |r| rounded to 24
 * significant bits (the int-to-float conversion, to nearest, ties to even),
 * then WHOLE = the integer part and FRAC = the fraction m / 65536 times 1000
 * plus 0.5, truncated: (m * 125 + 4096) / 8192, every step of which the
 * float code computes exactly (m * 125 < 2^23).  |v| <= 32768, so never the
 * exponent form.  Checked against the float code for every r by
 * tests/test_text.c. */
void tgi_text_put_real(tgi_text *t, tg_real r)
{
    uint32_t a = r < 0 ? 0u - (uint32_t)r : (uint32_t)r;
    int s = 0;
    if (r < 0) tgi_text_put(t, "-");
    while ((a >> s) >= (1u << 24)) s++;
    if (s > 0) {
        uint32_t rem = a & ((1u << s) - 1u), half = 1u << (s - 1);
        a >>= s;
        if (rem > half || (rem == half && (a & 1u))) a++;
        a <<= s;
    }
    put_decimal(t, a >> 16, ((a & 0xffffu) * 125u + 4096u) >> 13, 0);
}
#else
/* v >= 0, finite: "I[.DDD]" rounded to three decimals, or "M.MMMe+E" from 1e9 up. */
static void put_magnitude(tgi_text *t, float v)
{
    int e = 0;
    uint32_t whole;
    while (v >= 1e9f) { v /= 10.0f; e++; }
    if (e > 0) while (v >= 10.0f) { v /= 10.0f; e++; }
    whole = (uint32_t)v;
    put_decimal(t, whole, (uint32_t)((v - (float)whole) * 1000.0f + 0.5f), e);
}

void tgi_text_put_real(tgi_text *t, tg_real r)
{
    float v = tg_to_float(r);
    if (v != v) { tgi_text_put(t, "nan"); return; }
    if (v < 0) { tgi_text_put(t, "-"); v = -v; }
    if (v > 3.402823466e+38f) { tgi_text_put(t, "inf"); return; }
    put_magnitude(t, v);
}
#endif
