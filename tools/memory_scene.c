/* SPDX-License-Identifier: MIT */
/*
 * memory_scene.c - the arena bytes a parsed built-in scene takes (it shares
 * the arena with the frame): one line "NAME BYTES" per scene named, for
 * tools/memory_table.sh.
 *
 *     memory_scene cornell columns spheres
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"

#define ARENA_BYTES ((size_t)64 << 20)

int main(int argc, char **argv)
{
    void *mem = malloc(ARENA_BYTES);
    int k, status = 0;
    if (!mem) return 2;
    for (k = 1; k < argc; k++) {
        const char *text = tg_builtin_scene(argv[k]);
        tg_arena arena;
        tg_scene *scene;
        tg_error err;
        memset(&err, 0, sizeof err);
        tg_arena_init(&arena, mem, ARENA_BYTES);
        if (!text || tg_scene_parse(text, strlen(text), argv[k], NULL, &arena, &scene, &err) != TG_OK) {
            fprintf(stderr, "memory_scene: %s: not a built-in scene that parses\n", argv[k]);
            status = 2;
            continue;
        }
        printf("%s %lu\n", argv[k], (unsigned long)arena.used);
    }
    free(mem);
    return status;
}
