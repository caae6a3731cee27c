/* SPDX-License-Identifier: MIT */
/*
 * arena.c - the caller's one block of memory, carved front to back, and the
 * overflow-checked size arithmetic every buffer size goes through.
 */
#include <string.h>
#include "arena.h"

void tg_arena_init(tg_arena *a, void *memory, size_t size)
{
    a->base = (unsigned char *)memory;
    a->size = memory ? size : 0;
    a->used = 0;
    a->failed_request = 0;
}

size_t tgi_arena_pad(const void *base, size_t used)
{
    return (size_t)(16u - (((uintptr_t)base + used) & 15u)) & 15u;
}

void *tg_arena_alloc(tg_arena *a, size_t bytes)
{
    size_t start = a->used + tgi_arena_pad(a->base, a->used);
    void *p;
    if (!a->base || start < a->used || start > a->size || bytes > a->size - start) {
        if (bytes > a->failed_request) a->failed_request = bytes;
        return NULL;
    }
    p = a->base + start;
    memset(p, 0, bytes);
    a->used = start + bytes;
    return p;
}

int tg_size_mul(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > (size_t)-1 / a) return 1;
    *out = a * b;
    return 0;
}

int tg_size_add(size_t a, size_t b, size_t *out)
{
    if (b > (size_t)-1 - a) return 1;
    *out = a + b;
    return 0;
}
