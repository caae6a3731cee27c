/* SPDX-License-Identifier: MIT */
/*
 * parse_internal.h - what the scene parser (parse.c) and the OBJ/MTL loader
 * (obj.c) share: the parser state that both passes run over, and the
 * tables both add to (the lexer is lex.h; the limits are tinygi.h's).
 *
 * The parse runs the same code twice.  Pass 1 (p->fill == 0) validates the
 * text and every OBJ/MTL file and counts what the scene needs; pass 2
 * (p->fill == 1) allocates exactly that from the arena and fills it,
 * resolving names (materials, objects) as it goes.
 */
#ifndef TG_PARSE_INTERNAL_H
#define TG_PARSE_INTERNAL_H

#include "scene.h"
#include "lex.h"
#include "../core/error.h"

/* ---- the parser state ---- */
typedef struct tgi_parser {
    int fill;                           /* 0: count pass, 1: fill pass */
    const char *file;                   /* scene file name for messages */
    const tg_io *io;
    tg_error *err;
    tg_scene *scene;                    /* pass 2 only */

    /* counts: pass 1 totals, pass 2 running indices */
    size_t tris, materials, objects, object_keys, camera_keys, lights;
    size_t usemtl_bound;                /* pass 1: usemtl lines (materials they may add) */
    size_t material_cap;                /* pass 2: allocated materials */
    size_t obj_scratch;                 /* largest (v + vn) count of one OBJ */
    tg_vec3 *scratch;                   /* pass 2: room for obj_scratch vec3 */
    uint16_t *key_owner;                /* pass 2: object of each object key */
    int have_camera;
    int line_col;                       /* column of the error set on the current
                                         * scene line, 0: none (parse.c, "errors") */
} tgi_parser;

/* Set an input error at (file, line, col): message built from up to three
 * pieces (NULL pieces are skipped).  Returns TG_ERR_INPUT. */
tg_status tgi_parse_fail(tgi_parser *p, const char *file, int line, int col,
                        const char *a, const char *b, const char *c);

/* Start an object (pass 2: checks the name is unique), add triangles to it,
 * and add a material.  Each returns TG_OK or an error already set. */
tg_status tgi_parse_begin_object(tgi_parser *p, const tgi_lexer *lx, int col,
                                const tgi_token *name);
/* Count (pass 1) or store (pass 2) one triangle.  n may be NULL: face normal. */
tg_status tgi_parse_emit_tri(tgi_parser *p, const tgi_lexer *lx, int col,
                            const tg_vec3 pos[3], const tg_vec3 *nrm,
                            int material);
/* Count (pass 1) or append (pass 2) a material; *index gets its index. */
tg_status tgi_parse_add_material(tgi_parser *p, const tgi_lexer *lx, int col,
                                const tgi_material *m, int *index);

/* A rigid mesh transform: p' = R (s p) + t. */
typedef struct tgi_xform {
    tgi_mat4 rot;
    tg_real scale;
    tg_vec3 translate;
} tgi_xform;

/* Load the OBJ named by `path_tok` (relative to the scene file) as the
 * current object, with `material` for faces before any usemtl.  `objname`
 * prefixes usemtl material names ("objname/mtlname"). */
tg_status tgi_obj_mesh(tgi_parser *p, const tgi_lexer *lx, const tgi_token *path_tok,
                      const tgi_xform *xf, int material, const char *objname);

#endif
