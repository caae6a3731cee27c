/* SPDX-License-Identifier: MIT */
/*
 * path.c - joining a file name to the directory of another (path.h).
 */
#include <string.h>
#include "path.h"

size_t tgi_path_join(const char *base, const char *rel, size_t rel_n, char out[TG_MAX_PATH])
{
    size_t dir = 0, i, n = base ? strlen(base) : 0;
    if (rel_n > 0 && rel[0] == '/') n = 0; /* absolute */
    for (i = 0; i < n; i++)
        if (base[i] == '/') dir = i + 1;
    if (rel_n >= TG_MAX_PATH || dir + rel_n >= TG_MAX_PATH) return dir + rel_n;
    memcpy(out, base, dir);
    memcpy(out + dir, rel, rel_n);
    out[dir + rel_n] = '\0';
    return dir + rel_n;
}
