/* SPDX-License-Identifier: MIT */
/*
 * error.h - filling tg_error without stdio: set a message, then append
 * pieces (text, integers) to it.
 */
#ifndef TG_ERROR_H
#define TG_ERROR_H

#include "../tinygi.h"

void tgi_error_clear(tg_error *err);
void tgi_error_set(tg_error *err, tg_status status, const char *file, int line,
                  int col, const char *message);
void tgi_error_append(tg_error *err, const char *text);
void tgi_error_append_int(tg_error *err, long v);

#endif
