/* SPDX-License-Identifier: MIT */
/*
 * error.c - errors as values a caller can show to a person.
 */
#include <string.h>
#include "error.h"
#include "text.h"

size_t tg_error_format(const tg_error *err, char *buf, size_t size)
{
    static const tg_error none;   /* NULL formats as a zeroed error */
    tgi_text t;
    if (!err) err = &none;
    tgi_text_init(&t, buf, size);
    if (err->file[0]) {
        tgi_text_put(&t, err->file);
        if (err->line > 0) {
            tgi_text_put(&t, ":");
            tgi_text_put_int(&t, err->line);
            tgi_text_put(&t, ":");
            tgi_text_put_int(&t, err->col > 0 ? err->col : 1);
        }
        tgi_text_put(&t, ": ");
    }
    tgi_text_put(&t, "error: ");
    tgi_text_put(&t, err->message);
    return t.at;
}

/* s into t with each control byte (below 0x20, and 0x7f) written as \xNN:
 * a message quotes what the input holds (a name, a file name), and an
 * escape sequence there (ESC [ 2 J) must not reach a terminal as one.
 * Bytes from 0x80 stay (UTF-8 names). */
static void put_escaped(tgi_text *t, const char *s)
{
    static const char hex[] = "0123456789abcdef";
    char one[2] = { 0, 0 }, esc[5] = { '\\', 'x', 0, 0, 0 };
    for (; *s; s++) {
        const unsigned char c = (unsigned char)*s;
        if (c < 0x20 || c == 0x7f) {
            esc[2] = hex[c >> 4];
            esc[3] = hex[c & 15];
            tgi_text_put(t, esc);
        } else {
            one[0] = (char)c;
            tgi_text_put(t, one);
        }
    }
}

void tgi_error_clear(tg_error *err)
{
    if (!err) return;
    memset(err, 0, sizeof *err);
}

void tgi_error_set(tg_error *err, tg_status status, const char *file, int line,
                  int col, const char *message)
{
    (void)status;
    if (!err) return;
    err->file[0] = '\0';
    if (file) {
        tgi_text t;
        tgi_text_init(&t, err->file, sizeof err->file);
        put_escaped(&t, file);
    }
    err->line = line;
    err->col = col;
    err->message[0] = '\0';
    tgi_error_append(err, message);
}

/* The message so far as a text to append to. */
static tgi_text message_text(tg_error *err)
{
    tgi_text t;
    t.buf = err->message;
    t.size = sizeof err->message;
    t.at = strlen(err->message);
    return t;
}

void tgi_error_append(tg_error *err, const char *text)
{
    tgi_text t;
    if (!err) return;
    t = message_text(err);
    put_escaped(&t, text);
}

void tgi_error_append_int(tg_error *err, long v)
{
    tgi_text t;
    if (!err) return;
    t = message_text(err);
    tgi_text_put_int(&t, v);
}

void tgi_error_append_real(tg_error *err, tg_real v)
{
    tgi_text t;
    if (!err) return;
    t = message_text(err);
    tgi_text_put_real(&t, v);
}

void tgi_error_range(tg_error *err, const char *name, long lo, long hi)
{
    tgi_error_set(err, TG_ERR_INPUT, NULL, 0, 0, name);
    tgi_error_append(err, " must be ");
    tgi_error_append_int(err, lo);
    tgi_error_append(err, "..");
    tgi_error_append_int(err, hi);
    tgi_error_append(err, ", got ");
}
