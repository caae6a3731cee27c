/* SPDX-License-Identifier: MIT */
/*
 * path.h - file names as the scene refers to them (no file system: only
 * string arithmetic on '/'-separated paths).
 */
#ifndef TG_PATH_H
#define TG_PATH_H

#include "../tinygi.h"
#include "abi_names.h"

/* Join the directory of `base` (up to its last '/') and `rel` (rel_n bytes)
 * into out (TG_MAX_PATH bytes); an absolute `rel` ('/' first) is used as
 * is.  Returns the joined length in bytes (without the NUL): the path was
 * written when it is below TG_MAX_PATH, otherwise out is unchanged. */
size_t tgi_path_join(const char *base, const char *rel, size_t rel_n, char out[TG_MAX_PATH]);

#endif
