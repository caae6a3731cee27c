/*
 * error.h - filling tg_error without stdio: set a message, then append
 * pieces (text, integers) to it.
 */
#ifndef TG_ERROR_H
#define TG_ERROR_H

#include "../tinygi.h"

void tg_error_clear(tg_error *err);
void tg_error_set(tg_error *err, tg_status status, const char *file, int line,
                  int col, const char *message);
void tg_error_append(tg_error *err, const char *text);
void tg_error_append_int(tg_error *err, long v);

#endif
