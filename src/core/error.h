/* SPDX-License-Identifier: MIT */
/*
 * error.h - filling tg_error without stdio: set a message, then append
 * pieces (text, integers, reals) to it.
 */
#ifndef TG_ERROR_H
#define TG_ERROR_H

#include "../tinygi.h"
#include "abi_names.h"

void tgi_error_clear(tg_error *err);
void tgi_error_set(tg_error *err, tg_status status, const char *file, int line,
                  int col, const char *message);
void tgi_error_append(tg_error *err, const char *text);
void tgi_error_append_int(tg_error *err, long v);
void tgi_error_append_real(tg_error *err, tg_real v);   /* "1.5", "nan", "-inf" */
/* A value past a limit: TG_ERR_INPUT "NAME must be LO..HI, got " (no
 * file), for the caller to append the value. */
void tgi_error_range(tg_error *err, const char *name, long lo, long hi);

#endif
