/* SPDX-License-Identifier: MIT */
/*
 * scene_bake.c - `tinygi-bake`: parse a scene on the host and write the
 * parsed scene (src/scene/scene.h) as C data, so that a device program
 * built with TG_NO_SCENE_TEXT=1 (tinygi.h "FEATURE SWITCHES") links no scene
 * parser: the triangles, materials, lights and keys are const arrays in
 * flash, and the program plans and renders them as it would the parsed
 * scene (tests/bake_test.sh checks the images are bit-identical).
 *
 *   tinygi-bake [--name NAME] SCENE|builtin:NAME -o FILE.c
 *
 * The file defines `const tg_scene *NAME(void)` (default tg_baked_scene)
 * and holds the values of this tool's number type (tinygi-bake float,
 * tinygi-bake-fixed Q16.16), exactly as the parser made them; built with
 * the other number type, or against a core whose scene layout differs
 * (TGI_SCENE_LAYOUT), it stops with #error.  It includes "tinygi_scene.h":
 * compile it with the core's src/ on the include path, or against the
 * installed library (make install puts tinygi_scene.h beside tinygi.h),
 * and bake again when the core changes.  Exit 0, 2 on bad input (FILE:LINE:COL: error:),
 * 3 when the output cannot be written.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "tinygi.h"
#include "scene/scene.h"
#include "hosted/file.h"

#define BAKE_ARENA (256u << 20)

static FILE *out;

static void real(tg_real v)
{
#if TG_FIXED
    if (v == INT32_MIN) fputs("(-2147483647 - 1)", out);
    else fprintf(out, "%ld", (long)v);
#else
    fprintf(out, "%af", (double)v);   /* hex: exact */
#endif
}

static void comma_real(tg_real v)
{
    fputs(", ", out);
    real(v);
}

static void vec3(tg_vec3 v)
{
    fputs("{", out);
    real(v.x);
    comma_real(v.y);
    comma_real(v.z);
    fputs("}", out);
}

static void comma_vec3(tg_vec3 v)
{
    fputs(", ", out);
    vec3(v);
}

static void name(const char *s)
{
    const char *const start = s;
    fputs("\"", out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        /* '/' after '*' too: the source's name stands in a comment as well,
         * which "*" "/" would end (the string's value is the same) */
        if (c >= 32 && c < 127 && c != '"' && c != '\\' && c != '?' && !(c == '/' && s[-1] == '*' && s != start)) fputc(c, out);
        else fprintf(out, "\\%03o", c);
    }
    fputs("\"", out);
}

/* "static const TYPE NAME[] = {" ... one element per call of `put` ...
 * "};"; an empty array gets one zero element (C has no empty arrays) and
 * the scene's count says 0. */
#define ARRAY(type, var, count, put)                                            \
    do {                                                                        \
        int i_;                                                                 \
        fprintf(out, "static const %s %s[] = {\n", type, var);                  \
        if ((count) == 0) fputs("    {0}\n", out);                              \
        for (i_ = 0; i_ < (count); i_++) {                                      \
            fputs("    ", out);                                                 \
            put;                                                                \
            fputs(",\n", out);                                                  \
        }                                                                       \
        fputs("};\n", out);                                                     \
    } while (0)

static void bake(const tg_scene *s, const char *fn, const char *source)
{
    int i;
    fprintf(out, "/* Baked by tinygi-bake (tools/scene_bake.c) from ");
    name(source);
    fprintf(out, ",\n * number type %s: the parsed scene as C data.  Do not edit; bake it again. */\n",
            TG_NUMBER_NAME);
    fputs("#include \"tinygi_scene.h\"\n", out);
    fprintf(out, "#if %sTG_FIXED\n#error \"baked for %s: bake it with tinygi-bake%s\"\n#endif\n\n",
            TG_FIXED ? "!" : "", TG_NUMBER_NAME, TG_FIXED ? "-fixed" : "");
    fprintf(out, "#if TGI_SCENE_LAYOUT != %d\n#error \"baked for scene layout %d: bake it again with this tinygi's "
                 "tinygi-bake\"\n#endif\n\n", TGI_SCENE_LAYOUT, TGI_SCENE_LAYOUT);
    ARRAY("tgi_camera_key", "camera_keys", s->camera_key_count,
          (fputs("{", out), real(s->camera_keys[i_].t), comma_vec3(s->camera_keys[i_].pos),
           comma_vec3(s->camera_keys[i_].target), fputs("}", out)));
    ARRAY("tgi_material", "materials", s->material_count,
          (fputs("{", out), name(s->materials[i_].name), comma_vec3(s->materials[i_].albedo),
           comma_real(s->materials[i_].f0), comma_vec3(s->materials[i_].emissive),
           fprintf(out, ", %d", s->materials[i_].twosided), comma_vec3(s->materials[i_].diffuse), fputs("}", out)));
    ARRAY("tgi_object", "objects", s->object_count,
          (fputs("{", out), name(s->objects[i_].name),
           fprintf(out, ", %d, %d, %d, %d}", s->objects[i_].first_tri, s->objects[i_].tri_count,
                   s->objects[i_].first_key, s->objects[i_].key_count)));
    ARRAY("tgi_key", "object_keys", s->object_key_count,
          (fputs("{", out), real(s->object_keys[i_].t), comma_vec3(s->object_keys[i_].translate),
           comma_vec3(s->object_keys[i_].axis), comma_real(s->object_keys[i_].angle),
           fputs("}", out)));
    ARRAY("tg_vec3", "tri_pos", 3 * s->tri_count, vec3(s->tri_pos[i_]));
    ARRAY("tg_vec3", "tri_nrm", 3 * s->tri_count, vec3(s->tri_nrm[i_]));
    ARRAY("uint16_t", "tri_material", s->tri_count, fprintf(out, "%u", (unsigned)s->tri_material[i_]));
    ARRAY("uint16_t", "tri_object", s->tri_count, fprintf(out, "%u", (unsigned)s->tri_object[i_]));
    ARRAY("tgi_light", "lights", s->light_count,
          (fprintf(out, "{(tgi_light_type)%d, ", (int)s->lights[i_].type), vec3(s->lights[i_].pos),
           comma_vec3(s->lights[i_].dir), comma_vec3(s->lights[i_].color),
           comma_real(s->lights[i_].intensity), comma_real(s->lights[i_].angle),
           fprintf(out, ", %d}", s->lights[i_].shadows)));

    /* the arrays are const (flash); the scene's pointers are not, and no
     * pass writes through them (tg_plan_make takes a const tg_scene) */
    fputs("\nstatic const tg_scene scene = {\n    .camera = {", out);
    vec3(s->camera.pos);
    comma_vec3(s->camera.target);
    comma_vec3(s->camera.up);
    comma_real(s->camera.fov);
    comma_real(s->camera.znear);
    comma_real(s->camera.zfar);
    fprintf(out, "},\n    .camera_key_count = %d, .camera_keys = (tgi_camera_key *)camera_keys,\n",
            s->camera_key_count);
    fprintf(out, "    .material_count = %d, .materials = (tgi_material *)materials,\n", s->material_count);
    fprintf(out, "    .object_count = %d, .objects = (tgi_object *)objects,\n", s->object_count);
    fprintf(out, "    .object_key_count = %d, .object_keys = (tgi_key *)object_keys,\n", s->object_key_count);
    fprintf(out, "    .tri_count = %d, .tri_pos = (tg_vec3 *)tri_pos, .tri_nrm = (tg_vec3 *)tri_nrm,\n",
            s->tri_count);
    fputs("    .tri_material = (uint16_t *)tri_material, .tri_object = (uint16_t *)tri_object,\n", out);
    fprintf(out, "    .light_count = %d, .lights = (tgi_light *)lights,\n", s->light_count);
    fprintf(out, "    .env = {(tgi_env_type)%d, ", (int)s->env.type);
    vec3(s->env.uniform);
    comma_vec3(s->env.sky);
    comma_vec3(s->env.ground);
    comma_vec3(s->env.up);
    fputs(", {", out);
    vec3(s->env.sh9[0]);
    for (i = 1; i < 9; i++) comma_vec3(s->env.sh9[i]);
    fputs("}},\n    .gi = {", out);
    real(s->gi.radius);
    fprintf(out, ", %d, %d, %d},\n", s->gi.slices, s->gi.samples, s->gi.bounces);
    fprintf(out, "    .effects_auto = %d, .effects = %luu,\n    .bounds_min = ", s->effects_auto,
            (unsigned long)s->effects);
    vec3(s->bounds_min);
    fputs(", .bounds_max = ", out);
    vec3(s->bounds_max);
    fprintf(out, "\n};\n\nconst tg_scene *%s(void);\nconst tg_scene *%s(void) { return &scene; }\n", fn, fn);
}

static int usage(void)
{
    fputs("usage: tinygi-bake [--name NAME] SCENE|builtin:NAME -o FILE.c\n", stderr);
    return 2;
}

static int is_c_name(const char *s)
{
    const char *p = s;
    if (!*s || (*s >= '0' && *s <= '9')) return 0;
    for (; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '_'))
            return 0;
    return 1;
}

int main(int argc, char **argv)
{
    const char *in = NULL, *path = NULL, *fn = "tg_baked_scene", *text;
    char *data = NULL, *baked = NULL, msg[512];
    size_t size, baked_size = 0;
    void *mem;
    tg_arena arena;
    tg_scene *s = NULL;
    tg_error err;
    tgp_host_io io;
    tg_status st;
    int i;
    for (i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") && i + 1 < argc) path = argv[++i];
        else if (!strcmp(argv[i], "--name") && i + 1 < argc) fn = argv[++i];
        else if (argv[i][0] == '-' || in) return usage();
        else in = argv[i];
    }
    if (!in || !path) return usage();
    if (!is_c_name(fn)) {
        fprintf(stderr, "tinygi-bake: error: --name %s is not a C identifier\n", fn);
        return 2;
    }
    if (!strncmp(in, "builtin:", 8)) {
        text = tg_builtin_scene(in + 8);
        if (!text) {
            fprintf(stderr, "tinygi-bake: error: no built-in scene '%s'\n", in + 8);
            return 2;
        }
        size = strlen(text);
    } else {
        int r = tgp_file_read(in, &data, &size, msg, sizeof msg);
        if (r) {
            fprintf(stderr, "%s: error: %s\n", in, msg);
            return r == TG_ERR_INPUT ? 2 : 3;
        }
        text = data;
    }
    mem = malloc(BAKE_ARENA);
    if (!mem) {
        fputs("tinygi-bake: error: out of memory\n", stderr);
        return 3;
    }
    tg_arena_init(&arena, mem, BAKE_ARENA);
    tgp_host_io_init(&io);
    memset(&err, 0, sizeof err);
    st = tg_scene_parse(text, size, in, &io.io, &arena, &s, &err);
    if (st != TG_OK) {
        tgp_host_io_free(&io);
        tg_error_format(&err, msg, sizeof msg);
        fprintf(stderr, "%s\n", msg);
        return st == TG_ERR_INPUT ? 2 : 3;
    }
    {   /* never over an input: the scene, or a mesh or MTL it read (device and inode) */
        const char *input = NULL;
        tgp_file_id id;
        const tgp_host_io_file *f;
        if (!tgp_file_identify(path, &id)) {
            if (data && tgp_file_is(in, &id)) input = in;   /* the scene's file (not builtin:) */
            for (f = io.files; f && !input; f = f->next)
                if (f->id.dev == id.dev && f->id.ino == id.ino) input = f->path;
        }
        if (input) {
            fprintf(stderr, "%s: error: the output is the input file '%s'; refusing to overwrite it\n", path, input);
            tgp_host_io_free(&io);
            return 2;
        }
    }
    tgp_host_io_free(&io);
    if (tgp_outfile_check(path, msg, sizeof msg)) {
        fprintf(stderr, "%s: error: %s\n", path, msg);
        return 3;
    }
    /* the C text in memory, then written to a temporary file and renamed
     * over the output: a failed write leaves the old file as it was */
    out = open_memstream(&baked, &baked_size);
    if (!out) {
        fputs("tinygi-bake: error: out of memory\n", stderr);
        return 3;
    }
    bake(s, fn, in);
    if (fclose(out) != 0) {
        fputs("tinygi-bake: error: out of memory\n", stderr);
        return 3;
    }
    if (tgp_file_write_atomic(path, baked, baked_size, msg, sizeof msg)) {
        fprintf(stderr, "%s: error: %s\n", path, msg);
        return 3;
    }
    free(baked);
    free(mem);
    free(data);
    return 0;
}
