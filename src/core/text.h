/* SPDX-License-Identifier: MIT */
/*
 * text.h - building text into a caller's buffer without stdio: pieces
 * (strings, integers, reals) are appended front to back; the buffer always
 * ends in a NUL and never overflows, and `at` counts the whole text, so a
 * caller can tell that it was cut (at >= size) and how much room it needs
 * (at + 1), as with snprintf.
 */
#ifndef TG_TEXT_H
#define TG_TEXT_H

#include <stddef.h>
#include "real.h"

typedef struct tgi_text {
    char *buf;      /* may be NULL when size is 0: only count */
    size_t size;    /* bytes of buf, the NUL included */
    size_t at;      /* length of the whole text appended so far */
} tgi_text;

void tgi_text_init(tgi_text *t, char *buf, size_t size);
void tgi_text_put(tgi_text *t, const char *s);
void tgi_text_put_uint(tgi_text *t, size_t v);
void tgi_text_put_int(tgi_text *t, long v);
/* A real as a person reads it: "20", "-1.5", "0.001", "nan", "inf",
 * "3.403e+38" (at most three decimals, trailing zeros dropped). */
void tgi_text_put_real(tgi_text *t, tg_real v);

#endif
