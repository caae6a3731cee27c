/* SPDX-License-Identifier: MIT */
/*
 * error.c - errors as values a caller can show to a person.
 */
#include <string.h>
#include "error.h"

static size_t append(char *buf, size_t size, size_t at, const char *s)
{
    size_t n = strlen(s);
    if (size == 0) return at + n;
    if (at < size - 1) {
        size_t room = size - 1 - at;
        memcpy(buf + at, s, n < room ? n : room);
        buf[at + (n < room ? n : room)] = '\0';
    }
    return at + n;
}

static void format_uint(char *out, unsigned long v)
{
    char tmp[24];
    int n = 0, i;
    do { tmp[n++] = (char)('0' + v % 10u); v /= 10u; } while (v && n < 23);
    for (i = 0; i < n; i++) out[i] = tmp[n - 1 - i];
    out[n] = '\0';
}

size_t tg_error_format(const tg_error *err, char *buf, size_t size)
{
    size_t at = 0;
    char num[24];
    if (size) buf[0] = '\0';
    if (err->file[0]) {
        at = append(buf, size, at, err->file);
        if (err->line > 0) {
            format_uint(num, (unsigned long)err->line);
            at = append(buf, size, at, ":");
            at = append(buf, size, at, num);
            format_uint(num, (unsigned long)(err->col > 0 ? err->col : 1));
            at = append(buf, size, at, ":");
            at = append(buf, size, at, num);
        }
        at = append(buf, size, at, ": ");
    }
    at = append(buf, size, at, "error: ");
    return append(buf, size, at, err->message);
}

void tgi_error_clear(tg_error *err)
{
    if (!err) return;
    memset(err, 0, sizeof *err);
}

void tgi_error_set(tg_error *err, tg_status status, const char *file, int line,
                  int col, const char *message)
{
    size_t n;
    (void)status;
    if (!err) return;
    err->file[0] = '\0';
    if (file) {
        n = strlen(file);
        if (n >= sizeof err->file) n = sizeof err->file - 1;
        memcpy(err->file, file, n);
        err->file[n] = '\0';
    }
    err->line = line;
    err->col = col;
    err->message[0] = '\0';
    append(err->message, sizeof err->message, 0, message);
}

void tgi_error_append(tg_error *err, const char *text)
{
    if (!err) return;
    append(err->message, sizeof err->message, strlen(err->message), text);
}

void tgi_error_append_int(tg_error *err, long v)
{
    char num[24];
    if (v < 0) { tgi_error_append(err, "-"); v = -v; }
    format_uint(num, (unsigned long)v);
    tgi_error_append(err, num);
}
