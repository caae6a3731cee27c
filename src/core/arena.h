/* SPDX-License-Identifier: MIT */
/*
 * arena.h - what code that plans arena carves ahead of tg_arena_alloc needs
 * to place them exactly as it will.
 */
#ifndef TG_ARENA_H
#define TG_ARENA_H

#include "../tinygi.h"
#include "abi_names.h"

/* Bytes from offset `used` of `base` to the next 16-byte aligned address:
 * tg_arena_alloc starts its next block at used + tgi_arena_pad(base, used). */
size_t tgi_arena_pad(const void *base, size_t used);

#endif
