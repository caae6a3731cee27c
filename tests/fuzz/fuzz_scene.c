/* SPDX-License-Identifier: MIT */
/*
 * fuzz_scene.c - libFuzzer target for the scene parser (tg_scene_parse):
 * input SCENE [~~~ OBJ [~~~ MTL]] (see fuzz_common.h); a scene that parses
 * is rendered at 12x9 and must give finite outputs.
 */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *p = (const char *)data, *rest, *rest2;
    size_t rest_n, rest2_n;
    fuzz_files files;
    size_t scene_n = fuzz_split(p, size, &rest, &rest_n);
    memset(&files, 0, sizeof files);
    if (rest) {
        files.obj = rest;
        files.obj_n = fuzz_split(rest, rest_n, &rest2, &rest2_n);
        files.mtl = rest2;
        files.mtl_n = rest2_n;
    }
    fuzz_run(p, scene_n, &files);
    return 0;
}
