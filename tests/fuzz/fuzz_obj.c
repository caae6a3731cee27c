/* SPDX-License-Identifier: MIT */
/*
 * fuzz_obj.c - libFuzzer target for the OBJ/MTL loader: input OBJ [~~~ MTL]
 * (see fuzz_common.h), loaded as a mesh of a fixed scene; a mesh that loads
 * is rendered at 12x9 and must give finite outputs.
 */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char fuzz_obj_scene[] =
    "camera pos 0 1 -4 target 0 0.5 0\n"
    "material m albedo 0.6 0.6 0.6\n"
    "material lamp albedo 0.5 0.5 0.5 emissive 2 2 2\n"
    "quad p0 -3 0 -3 p1 -3 0 3 p2 3 0 3 p3 3 0 -3 material m\n"
    "mesh file in.obj material m name thing\n"
    "object_key name thing t 0\n"
    "object_key name thing t 1 translate 0.3 0 0 rotate 0 1 0 20\n"
    "light point pos 0 3 -1 color 1 1 1 intensity 3 shadows\n"
    "env sky 0.3 0.4 0.5 ground 0.1 0.1 0.1\n";

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *p = (const char *)data, *rest;
    size_t rest_n;
    fuzz_files files;
    files.obj = p;
    files.obj_n = fuzz_split(p, size, &rest, &rest_n);
    files.mtl = rest;
    files.mtl_n = rest_n;
    fuzz_run(fuzz_obj_scene, sizeof fuzz_obj_scene - 1, &files);
    return 0;
}
