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

/* v >= 0, finite: "I[.DDD]" rounded to three decimals, or "M.MMMe+E" from 1e9 up. */
static void put_magnitude(tgi_text *t, float v)
{
    int e = 0;
    uint32_t whole, frac;
    char digits[5];
    int k;
    while (v >= 1e9f) { v /= 10.0f; e++; }
    if (e > 0) while (v >= 10.0f) { v /= 10.0f; e++; }
    whole = (uint32_t)v;
    frac = (uint32_t)((v - (float)whole) * 1000.0f + 0.5f);
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

void tgi_text_put_real(tgi_text *t, tg_real r)
{
    float v = tg_to_float(r);
    if (v != v) { tgi_text_put(t, "nan"); return; }
    if (v < 0) { tgi_text_put(t, "-"); v = -v; }
    if (v > 3.402823466e+38f) { tgi_text_put(t, "inf"); return; }
    put_magnitude(t, v);
}
