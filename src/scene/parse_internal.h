/* SPDX-License-Identifier: MIT */
/*
 * parse_internal.h - what the scene parser (parse.c) and the OBJ/MTL loader
 * (obj.c) share: the limits, the line lexer, and the parser state that both
 * passes run over.
 *
 * The parse runs the same code twice.  Pass 1 (p->fill == 0) validates the
 * text and every OBJ/MTL file and counts what the scene needs; pass 2
 * (p->fill == 1) allocates exactly that from the arena and fills it,
 * resolving names (materials, objects) as it goes.
 */
#ifndef TG_PARSE_INTERNAL_H
#define TG_PARSE_INTERNAL_H

#include "scene.h"
#include "../core/error.h"

/* Limits (documented in format.md). */
#define TG_SCENE_MAX_TRIS 4000000
#define TG_SCENE_MAX_MATERIALS 1024
#define TG_SCENE_MAX_OBJECTS 65535
#define TG_SCENE_MAX_LIGHTS 64
#define TG_SCENE_MAX_KEYS 4096          /* camera keys; object keys likewise */
#define TG_SPHERE_SEG_MIN 4
#define TG_SPHERE_SEG_MAX 256
#define TG_SPHERE_SEG_DEFAULT 24
#define TG_PATH_MAX 256                 /* resolved mesh / MTL path, bytes incl. NUL */
#define TG_OBJ_MAX_VERTS 4000000        /* v, vn and vt lines each */
#define TG_OBJ_MAX_MTLLIB 8             /* mtllib files named per OBJ */
#define TG_GI_SLICES_MAX 64
#define TG_GI_SAMPLES_MAX 256
#define TG_GI_BOUNCES_MAX 100

/* ---- lexing: one line at a time, tokens split by blanks ---- */
typedef struct tgi_token {
    const char *s;
    size_t n;
    int col;                            /* 1-based byte column */
} tgi_token;

typedef struct tgi_lexer {
    const char *text, *end;             /* the whole input */
    const char *next;                   /* start of the next line */
    const char *line, *line_end;        /* the current line (no newline) */
    const char *cur;                    /* cursor within the line */
    int lineno;                         /* 1-based */
    const char *file;                   /* name used in messages */
} tgi_lexer;

void tgi_lex_init(tgi_lexer *lx, const char *text, size_t size, const char *file);
/* Advance to the next line; 0 at the end of input.  Rejects NUL bytes and
 * over-long lines (returns -1 with the error set). */
int tgi_lex_line(tgi_lexer *lx, tg_error *err);
/* Next token on the line ('#' ends it); 0 at the end of the line. */
int tgi_lex_token(tgi_lexer *lx, tgi_token *t);
int tgi_lex_peek(tgi_lexer *lx, tgi_token *t);
/* Column just past the last character of the line (for "missing" errors). */
int tgi_lex_eol_col(const tgi_lexer *lx);
/* The rest of the line trimmed (without a comment), as a token. */
int tgi_lex_rest(tgi_lexer *lx, tgi_token *t);
int tgi_tok_is(const tgi_token *t, const char *word);

/* Whole token as a number: 0 ok, 1 not a number, 2 out of range. */
int tgi_tok_real(const tgi_token *t, tg_real *out);
/* Whole token as a decimal integer (optional sign): 0 ok, 1 not, 2 range. */
int tgi_tok_int(const tgi_token *t, long *out);

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
    int have_camera, have_env, have_gi, have_effects;
} tgi_parser;

/* A token quoted for messages (at most 40 bytes, then "..."). */
const char *tgi_tok_str(const tgi_token *t, char buf[48]);
/* Whether a token equals a NUL-terminated name. */
int tgi_tok_eq_name(const tgi_token *t, const char *name);

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
/* Unit vector (exact for axis-aligned ones); zero when too short. */
tg_vec3 tgi_unit(tg_vec3 v);
/* Degrees to radians, precise in Q16.16 too. */
tg_real tgi_deg_to_rad(tg_real deg);
/* Face normal of a triangle, robust in fixed point; 0 if degenerate. */
int tgi_face_normal(tg_vec3 a, tg_vec3 b, tg_vec3 c, tg_vec3 *n);

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

/* Join dir(base) and rel into out (size TG_PATH_MAX); 0 ok, 1 too long. */
int tgi_path_join(const char *base, const char *rel, size_t rel_n, char *out);

#endif
