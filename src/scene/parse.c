/* SPDX-License-Identifier: MIT */
/*
 * parse.c - scene format v1 (documented in format.md beside this file):
 * text in a memory buffer to a tg_scene in the caller's arena.
 *
 * Two passes over the same statement code.  Pass 1 validates every line
 * (and every OBJ/MTL file a mesh names, through tg_io) and counts triangles,
 * materials, objects, keys and lights.  The exact byte total is then checked
 * against the arena (TG_ERR_MEMORY with bytes_needed when it does not fit),
 * the arrays are carved out, and pass 2 fills them, resolving material and
 * object names.  Geometry is flattened to triangles here: quads, boxes,
 * spheres and meshes all end up as 3 positions + 3 unit normals each.
 *
 * Every input error names FILE:LINE:COL of the offending token and says what
 * was expected.  A line reports its first error in the text (the smallest
 * column): its checks do not stop at the first that fails, and each error
 * replaces the one set only when it stands further left (line_error).
 */
#include <string.h>
#include "parse_internal.h"
#include "../core/arena.h"

#if !TG_NO_SCENE_TEXT /* the whole file is left out with TG_NO_SCENE_TEXT=1 (tinygi.h "FEATURE SWITCHES"; scene_text.c refuses) */

/* ===================================================================== */
/* errors                                                                */
/* ===================================================================== */

tg_status tgi_parse_fail(tgi_parser *p, const char *file, int line, int col,
                        const char *a, const char *b, const char *c)
{
    tgi_error_set(p->err, TG_ERR_INPUT, file, line, col, a ? a : "");
    if (b) tgi_error_append(p->err, b);
    if (c) tgi_error_append(p->err, c);
    return TG_ERR_INPUT;
}

/* An error at `col` of the current line: where to write its message, or
 * NULL (the tgi_error_* calls then write nothing) when the line already has
 * an error at that column or further left, which stands.  run_pass starts
 * each line with none (p->line_col = 0). */
static tg_error *line_error(tgi_parser *p, const tgi_lexer *lx, int col)
{
    if (p->line_col > 0 && p->line_col <= col) return NULL;
    p->line_col = col;
    tgi_error_set(p->err, TG_ERR_INPUT, lx->file, lx->lineno, col, "");
    return p->err;
}

/* TG_ERR_INPUT when the current line has an error, else TG_OK: a statement
 * checks all it can, then stops here before it adds anything to the scene. */
static tg_status line_status(const tgi_parser *p)
{
    return p->line_col ? TG_ERR_INPUT : TG_OK;
}

/* An error at `col` of the current line, its message begun with up to three
 * pieces (NULL pieces are skipped): returns where to append the rest (NULL
 * when an error further left stands, as line_error). */
static tg_error *fail_begin(tgi_parser *p, const tgi_lexer *lx, int col,
                            const char *a, const char *b, const char *c)
{
    tg_error *e = line_error(p, lx, col);
    if (a) tgi_error_append(e, a);
    if (b) tgi_error_append(e, b);
    if (c) tgi_error_append(e, c);
    return e;
}

static tg_status fail(tgi_parser *p, const tgi_lexer *lx, int col,
                      const char *a, const char *b, const char *c)
{
    fail_begin(p, lx, col, a, b, c);
    return TG_ERR_INPUT;
}

/* "NAME must be LO..HI, got GOT" (lex.h), GOT a count or a token's text. */
static tg_status limit(tgi_parser *p, const tgi_lexer *lx, int col, const char *name,
                       long lo, long hi, size_t got)
{
    char buf[24];
    return tgi_limit_fail(line_error(p, lx, col), lx->file, lx->lineno, col, name, lo, hi,
                          tgi_number_text(got, buf));
}

static tg_status limit_tok(tgi_parser *p, const tgi_lexer *lx, const tgi_token *t,
                           const char *name, long lo, long hi)
{
    char buf[48];
    return tgi_limit_fail(line_error(p, lx, t->col), lx->file, lx->lineno, t->col, name, lo, hi,
                          tgi_tok_str(t, buf));
}

static tg_status fail_runtime(tgi_parser *p, const char *what)
{
    tgi_error_set(p->err, TG_ERR_RUNTIME, p->file, 0, 0, what);
    return TG_ERR_RUNTIME;
}

/* ===================================================================== */
/* statements as "key value..." pairs                                    */
/* ===================================================================== */

enum { K_FLAG, K_NAME, K_PATH, K_REAL, K_INT, K_VEC3, K_ROT };

typedef struct key_spec {
    const char *key;
    unsigned char kind, required;
} key_spec;

typedef struct key_val {
    int present;
    tgi_token key;
    tgi_token tok[4];    /* the value tokens (name/path in tok[0]) */
    tg_real v[4];
    long i;             /* K_INT */
} key_val;

#define MAX_SPEC 8

static int kind_numbers(int kind)
{
    return kind == K_REAL || kind == K_INT ? 1 : kind == K_VEC3 ? 3 : kind == K_ROT ? 4 : 0;
}

static int find_key(const key_spec *spec, int n, const tgi_token *t)
{
    int i;
    for (i = 0; i < n; i++)
        if (tgi_tok_is(t, spec[i].key)) return i;
    return -1;
}

/* Read `count` numbers for `what`; stops (wrong count) at a key of `spec`.
 * On an error toks[] holds the numbers read before it. */
static tg_status read_numbers(tgi_parser *p, tgi_lexer *lx, const key_spec *spec,
                              int nspec, const char *what, int count, int integer,
                              tgi_token *toks, tg_real *v, long *iv)
{
    tgi_token t;
    tg_error *e;
    char buf[48];
    int i, r;
    for (i = 0; i < count; i++) {
        int more = tgi_lex_peek(lx, &t);
        if (!more || (spec && find_key(spec, nspec, &t) >= 0)) {
            e = fail_begin(p, lx, more ? t.col : tgi_lex_eol_col(lx), "'", what, "' expects ");
            tgi_error_append_int(e, count);
            tgi_error_append(e, count == 1 ? " number, got " : " numbers, got ");
            tgi_error_append_int(e, i);
            return TG_ERR_INPUT;
        }
        tgi_lex_token(lx, &t);
        r = integer ? tgi_tok_int(&t, iv) : tgi_tok_real(&t, &v[i]);
        if (r == 1) {
            e = fail_begin(p, lx, t.col, integer ? "expected an integer for '" : "expected a number for '",
                           what, "', got '");
            tgi_error_append(e, tgi_tok_str(&t, buf));
            tgi_error_append(e, "'");
            return TG_ERR_INPUT;
        }
        if (r == 2) {
            e = fail_begin(p, lx, t.col, "number out of range for '", what, "': '");
            tgi_error_append(e, tgi_tok_str(&t, buf));
            tgi_error_append(e, "'" TGI_RANGE_NOTE);
            return TG_ERR_INPUT;
        }
        toks[i] = t;
    }
    return TG_OK;
}

/* The keys of a statement, left to right, into val[] in spec's order.  A key
 * is present once its value is read whole.  At an error the rest of the line
 * is not read (so no key is reported missing): the statement then checks the
 * values read before it, each of which stands further left. */
static tg_status parse_keys(tgi_parser *p, tgi_lexer *lx, const tgi_token *stmt,
                            const key_spec *spec, int nspec, key_val *val)
{
    tgi_token t;
    tg_error *e;
    char buf[48];
    int k, i, prev = -1;
    memset(val, 0, sizeof(key_val) * (size_t)nspec);
    while (tgi_lex_token(lx, &t)) {
        k = find_key(spec, nspec, &t);
        if (k < 0) {
            tg_real dummy;
            if (prev >= 0 && tgi_tok_real(&t, &dummy) != 1) {
                e = fail_begin(p, lx, t.col, "too many numbers for '", spec[prev].key, "' (expects ");
                tgi_error_append_int(e, kind_numbers(spec[prev].kind));
                tgi_error_append(e, ")");
                return TG_ERR_INPUT;
            }
            e = fail_begin(p, lx, t.col, "unknown key '", tgi_tok_str(&t, buf), "' in '");
            tgi_error_append(e, tgi_tok_str(stmt, buf));
            tgi_error_append(e, "'; expected one of:");
            for (i = 0; i < nspec; i++) {
                tgi_error_append(e, " ");
                tgi_error_append(e, spec[i].key);
            }
            return TG_ERR_INPUT;
        }
        if (val[k].present) return fail(p, lx, t.col, "duplicate key '", spec[k].key, "'");
        val[k].key = t;
        if (spec[k].kind == K_NAME || spec[k].kind == K_PATH) {
            if (!tgi_lex_token(lx, &val[k].tok[0]))
                return fail(p, lx, tgi_lex_eol_col(lx), "'", spec[k].key,
                            spec[k].kind == K_NAME ? "' expects a name" : "' expects a file path");
            if (spec[k].kind == K_NAME && val[k].tok[0].n > TG_MAX_NAME)
                return limit(p, lx, val[k].tok[0].col, "name length in bytes", 1, TG_MAX_NAME,
                             val[k].tok[0].n);
        } else if (spec[k].kind != K_FLAG) {
            if (read_numbers(p, lx, spec, nspec, spec[k].key, kind_numbers(spec[k].kind),
                             spec[k].kind == K_INT, val[k].tok, val[k].v, &val[k].i))
                return TG_ERR_INPUT;
        }
        val[k].present = 1;
        prev = kind_numbers(spec[k].kind) ? k : -1;
    }
    for (k = 0; k < nspec; k++)
        if (spec[k].required && !val[k].present) {
            e = fail_begin(p, lx, stmt->col, "'", tgi_tok_str(stmt, buf), "' is missing the required key '");
            tgi_error_append(e, spec[k].key);
            tgi_error_append(e, "'");
            return TG_ERR_INPUT;
        }
    return TG_OK;
}

/* Nothing may follow a positional statement's values. */
static tg_status expect_end(tgi_parser *p, tgi_lexer *lx, const char *what, int count)
{
    tgi_token t;
    tg_real dummy;
    char buf[48];
    if (!tgi_lex_token(lx, &t)) return TG_OK;
    if (count > 0 && tgi_tok_real(&t, &dummy) != 1) {
        tg_error *e = fail_begin(p, lx, t.col, "too many numbers for '", what, "' (expects ");
        tgi_error_append_int(e, count);
        tgi_error_append(e, ")");
        return TG_ERR_INPUT;
    }
    return fail(p, lx, t.col, "unexpected '", tgi_tok_str(&t, buf), "' at the end of the line");
}

/* ---- value checks ----
 * Each checks a key only when it is present (read whole), so a statement
 * runs them all, whatever failed before, and then asks line_status. */
#define LO_OPEN 1
#define HI_OPEN 2

static tg_status check_range(tgi_parser *p, const tgi_lexer *lx, const key_val *kv,
                             const char *key, tg_real lo, tg_real hi, int open,
                             const char *expect)
{
    char buf[48];
    int i, n = kv->tok[3].s ? 4 : kv->tok[2].s ? 3 : 1;
    for (i = 0; kv->present && i < n; i++) {
        tg_real v = kv->v[i];
        if (v < lo || v > hi || ((open & LO_OPEN) && v == lo) || ((open & HI_OPEN) && v == hi)) {
            tg_error *e = fail_begin(p, lx, kv->tok[i].col, "'", key, "' must be ");
            tgi_error_append(e, expect);
            tgi_error_append(e, ", got '");
            tgi_error_append(e, tgi_tok_str(&kv->tok[i], buf));
            tgi_error_append(e, "'");
            if (tgi_tok_rounds_to_zero(&kv->tok[i], v)) tgi_error_append(e, TGI_ZERO_NOTE);
            return TG_ERR_INPUT;
        }
    }
    return TG_OK;
}

static tg_vec3 kv_vec3(const key_val *kv) { return tg_v3(kv->v[0], kv->v[1], kv->v[2]); }

static int is_zero_vec(tg_vec3 v) { return v.x == 0 && v.y == 0 && v.z == 0; }

/* The unit direction of a vec3 value into *out (unchanged when the key is
 * absent); zero length is an error. */
static tg_status kv_dir(tgi_parser *p, const tgi_lexer *lx, const key_val *kv,
                        const char *key, tg_vec3 *out)
{
    tg_vec3 d;
    if (!kv->present) return TG_OK;
    d = tgi_unit(kv_vec3(kv));
    if (is_zero_vec(d)) {
        tg_error *e = fail_begin(p, lx, kv->tok[0].col, "'", key, "' must be a direction of non-zero length");
        if (tgi_tok_rounds_to_zero(&kv->tok[0], kv->v[0]) || tgi_tok_rounds_to_zero(&kv->tok[1], kv->v[1]) ||
            tgi_tok_rounds_to_zero(&kv->tok[2], kv->v[2]))
            tgi_error_append(e, TGI_ZERO_NOTE);
        return TG_ERR_INPUT;
    }
    *out = d;
    return TG_OK;
}

/* A key whose value must be greater than 0 (near, scale, radius): its value
 * in *out when present; *out unchanged when absent. */
static tg_status kv_positive(tgi_parser *p, const tgi_lexer *lx, const key_val *kv, const char *key, tg_real *out)
{
    tg_status st;
    if (!kv->present) return TG_OK;
    if ((st = check_range(p, lx, kv, key, 0, TG_REAL_MAX, LO_OPEN, "greater than 0"))) return st;
    *out = kv->v[0];
    return TG_OK;
}

/* ===================================================================== */
/* scene tables: materials, objects, triangles                          */
/* ===================================================================== */

tg_status tgi_parse_add_material(tgi_parser *p, const tgi_lexer *lx, int col,
                                const tgi_material *m, int *index)
{
    if (p->materials >= TG_MAX_MATERIALS)
        return limit(p, lx, col, "material count", 0, TG_MAX_MATERIALS, p->materials + 1);
    if (p->fill) {
        if (p->materials >= p->material_cap) return fail_runtime(p, "a mesh file changed while parsing");
        p->scene->materials[p->materials] = *m;
        tgi_material_finish(&p->scene->materials[p->materials]);
    }
    *index = (int)p->materials++;
    return TG_OK;
}

static int find_material(const tgi_parser *p, const tgi_token *name)
{
    size_t i;
    for (i = 0; i < p->materials; i++)
        if (tgi_tok_eq_name(name, p->scene->materials[i].name)) return (int)i;
    return -1;
}

static int find_object(const tgi_parser *p, const tgi_token *name)
{
    size_t i;
    for (i = 0; i < p->objects; i++)
        if (p->scene->objects[i].name[0] && tgi_tok_eq_name(name, p->scene->objects[i].name))
            return (int)i;
    return -1;
}

static void copy_name(char dst[TG_MAX_NAME + 1], const tgi_token *t)
{
    size_t n = t->n < TG_MAX_NAME ? t->n : TG_MAX_NAME;
    memcpy(dst, t->s, n);
    dst[n] = '\0';
}

tg_status tgi_parse_begin_object(tgi_parser *p, const tgi_lexer *lx, int col,
                                const tgi_token *name)
{
    char buf[48];
    tgi_object *o;
    if (p->objects >= TG_MAX_OBJECTS)
        return limit(p, lx, col, "object count", 0, TG_MAX_OBJECTS, p->objects + 1);
    if (p->fill) {
        if (name && find_object(p, name) >= 0)
            return fail(p, lx, name->col, "duplicate object name '", tgi_tok_str(name, buf),
                        "'; object names must be unique");
        o = &p->scene->objects[p->objects];
        memset(o, 0, sizeof *o);
        if (name) copy_name(o->name, name);
        o->first_tri = (int)p->tris;
    }
    p->objects++;
    return TG_OK;
}

static tg_status count_tris(tgi_parser *p, const tgi_lexer *lx, int col, size_t n)
{
    if (n > TG_MAX_TRIANGLES || p->tris > TG_MAX_TRIANGLES - n)
        return limit(p, lx, col, "triangle count", 0, TG_MAX_TRIANGLES, p->tris + n);
    p->tris += n;
    return TG_OK;
}

static void grow_bounds(tg_scene *s, tg_vec3 v, int first)
{
    if (first) { s->bounds_min = v; s->bounds_max = v; return; }
    s->bounds_min = tg_v3(tg_min(s->bounds_min.x, v.x), tg_min(s->bounds_min.y, v.y),
                          tg_min(s->bounds_min.z, v.z));
    s->bounds_max = tg_v3(tg_max(s->bounds_max.x, v.x), tg_max(s->bounds_max.y, v.y),
                          tg_max(s->bounds_max.z, v.z));
}

tg_status tgi_parse_emit_tri(tgi_parser *p, const tgi_lexer *lx, int col,
                            const tg_vec3 pos[3], const tg_vec3 *nrm, int material)
{
    tg_scene *s = p->scene;
    tg_vec3 fn;
    size_t t = p->tris;
    int i;
    if (!p->fill) return count_tris(p, lx, col, 1);
    if (t >= (size_t)s->tri_count) return fail_runtime(p, "a mesh file changed while parsing");
    fn = tg_v3(0, TG_ONE, 0); /* for zero area: the rasterizer skips it */
    if (!nrm) tgi_face_normal(pos[0], pos[1], pos[2], &fn);
    for (i = 0; i < 3; i++) {
        s->tri_pos[3 * t + (size_t)i] = pos[i];
        s->tri_nrm[3 * t + (size_t)i] = nrm ? nrm[i] : fn;
        grow_bounds(s, pos[i], t == 0 && i == 0);
    }
    s->tri_material[t] = (uint16_t)material;
    s->tri_object[t] = (uint16_t)(p->objects - 1);
    s->objects[p->objects - 1].tri_count++;
    p->tris++;
    return TG_OK;
}

/* Two triangles (p0 p1 p2) (p0 p2 p3); n: one normal for all, or NULL. */
static tg_status emit_quad(tgi_parser *p, const tgi_lexer *lx, int col, const tg_vec3 q[4],
                           const tg_vec3 *n, int material)
{
    tg_vec3 a[3], b[3], nn[3];
    tg_status st;
    a[0] = q[0]; a[1] = q[1]; a[2] = q[2];
    b[0] = q[0]; b[1] = q[2]; b[2] = q[3];
    if (n) nn[0] = nn[1] = nn[2] = *n;
    st = tgi_parse_emit_tri(p, lx, col, a, n ? nn : NULL, material);
    return st ? st : tgi_parse_emit_tri(p, lx, col, b, n ? nn : NULL, material);
}

/* The object name key, or NULL. */
static const tgi_token *name_of(const key_val *kv) { return kv->present ? &kv->tok[0] : NULL; }

/* A geometry line, once its values are checked: the material it names
 * (resolved in pass 2) into *index, and its object begun.  Both name errors
 * (an undefined material, a duplicate object name) are looked for, and the
 * line reports the one further left. */
static tg_status begin_geometry(tgi_parser *p, const tgi_lexer *lx, const tgi_token *kw,
                                const key_val *material, const key_val *name, int *index)
{
    char buf[48];
    tg_status st;
    *index = 0;
    if ((st = line_status(p))) return st;
    if (p->fill && (*index = find_material(p, &material->tok[0])) < 0)
        fail(p, lx, material->tok[0].col, "undefined material '", tgi_tok_str(&material->tok[0], buf),
             "'; define it with a 'material' line before its use");
    st = tgi_parse_begin_object(p, lx, kw->col, name_of(name));
    return st ? st : line_status(p);
}

/* ===================================================================== */
/* the statements                                                        */
/* ===================================================================== */

/* A statement after its keyword (and, when it has a key table, its keys
 * parsed into v in the table's order; NULL when it parses its own). */
typedef tg_status (*statement_fn)(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v);

#define NSPEC(a) ((int)(sizeof(a) / sizeof((a)[0])))

static tg_status st_camera(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tgi_scene_camera cam;
    tg_status st;
    tg_real fov = TG_R(TG_DEFAULT_FOV);
    int whole = !p->line_col; /* parse_keys read the whole line: an absent key has its default */
    (void)kw;
    cam.pos = kv_vec3(&v[0]);
    cam.target = kv_vec3(&v[1]);
    if (v[0].present && v[1].present && is_zero_vec(tgi_v3_sub(cam.target, cam.pos)))
        fail(p, lx, v[1].tok[0].col, "camera 'target' must differ from 'pos'", NULL, NULL);
    cam.up = tg_v3(0, TG_ONE, 0);
    kv_dir(p, lx, &v[2], "up", &cam.up);
    if (v[3].present && !check_range(p, lx, &v[3], "fov", 0, TG_R(180.0f), LO_OPEN | HI_OPEN,
                                     "between 0 and 180 degrees (exclusive)"))
        fov = v[3].v[0];
    cam.fov = tgi_deg_to_rad(fov);
    cam.znear = TG_R(TG_DEFAULT_NEAR);
    cam.zfar = TG_R(TG_DEFAULT_FAR);
    st = kv_positive(p, lx, &v[4], "near", &cam.znear);
    if (v[5].present) cam.zfar = v[5].v[0];
    if (!st && (whole || (v[4].present && v[5].present)) && cam.zfar <= cam.znear)
        fail(p, lx, v[5].present ? v[5].tok[0].col : v[4].tok[0].col,
             "camera 'far' must be greater than 'near'", NULL, NULL);
    if ((st = line_status(p))) return st;
    p->have_camera = 1;
    if (p->fill) p->scene->camera = cam;
    return TG_OK;
}

static tg_status st_camera_key(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tgi_camera_key key, *k;
    size_t i;
    key.t = v[0].v[0];
    key.pos = kv_vec3(&v[1]);
    key.target = kv_vec3(&v[2]);
    if (v[1].present && v[2].present && is_zero_vec(tgi_v3_sub(key.target, key.pos)))
        fail(p, lx, v[2].tok[0].col, "camera_key 'target' must differ from 'pos'", NULL, NULL);
    if (line_status(p)) return TG_ERR_INPUT;
    if (p->camera_keys >= TG_MAX_KEYS)
        return limit(p, lx, kw->col, "camera_key count", 0, TG_MAX_KEYS, p->camera_keys + 1);
    if (p->fill) { /* insert sorted by t */
        k = p->scene->camera_keys;
        for (i = 0; i < p->camera_keys; i++)
            if (k[i].t == key.t)
                return fail(p, lx, v[0].tok[0].col, "duplicate camera_key time 't'; each key needs its own time", NULL, NULL);
        for (i = p->camera_keys; i > 0 && k[i - 1].t > key.t; i--) k[i] = k[i - 1];
        k[i] = key;
    }
    p->camera_keys++;
    return TG_OK;
}

static tg_status st_material(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *parsed)
{
    static const key_spec spec[] = {
        {"albedo", K_VEC3, 1}, {"f0", K_REAL, 0}, {"emissive", K_VEC3, 0}, {"twosided", K_FLAG, 0}};
    key_val v[MAX_SPEC];
    tgi_token name;
    tgi_material m;
    tg_status st;
    char buf[48];
    int index;
    int have = tgi_lex_token(lx, &name);
    (void)parsed;
    if (!have || find_key(spec, NSPEC(spec), &name) >= 0)
        return fail(p, lx, have ? name.col : tgi_lex_eol_col(lx),
                    "'material' expects a name first: material NAME albedo R G B ...", NULL, NULL);
    if (name.n > TG_MAX_NAME) return limit(p, lx, name.col, "name length in bytes", 1, TG_MAX_NAME, name.n);
    parse_keys(p, lx, kw, spec, NSPEC(spec), v);
    check_range(p, lx, &v[0], "albedo", 0, TG_ONE, 0, "in [0, 1]");
    check_range(p, lx, &v[1], "f0", 0, TG_ONE, 0, "in [0, 1]");
    check_range(p, lx, &v[2], "emissive", 0, TG_REAL_MAX, 0, "0 or more");
    if ((st = line_status(p))) return st;
    memset(&m, 0, sizeof m);
    copy_name(m.name, &name);
    m.albedo = kv_vec3(&v[0]);
    m.f0 = v[1].present ? v[1].v[0] : TG_R(TG_DEFAULT_F0);
    if (v[2].present) m.emissive = kv_vec3(&v[2]);
    m.twosided = v[3].present;
    if (p->fill && find_material(p, &name) >= 0)
        return fail(p, lx, name.col, "duplicate material '", tgi_tok_str(&name, buf),
                    "'; material names must be unique");
    return tgi_parse_add_material(p, lx, name.col, &m, &index);
}

static tg_status st_quad(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tg_vec3 q[4], n;
    tg_status st;
    int i, mat;
    for (i = 0; i < 4; i++) q[i] = kv_vec3(&v[i]);
    if (v[0].present && v[1].present && v[2].present && v[3].present &&
        (!tgi_face_normal(q[0], q[1], q[2], &n) || !tgi_face_normal(q[0], q[2], q[3], &n)))
        fail(p, lx, v[0].tok[0].col,
             "quad has zero area; expected four corners p0 p1 p2 p3 around a polygon", NULL, NULL);
    if ((st = begin_geometry(p, lx, kw, &v[4], &v[5], &mat))) return st;
    return emit_quad(p, lx, kw->col, q, NULL, mat);
}

/* Box faces as corner indices (bit 0: x, bit 1: y, bit 2: z at max),
 * counter-clockwise seen from outside, and their outward normal axes. */
static const unsigned char box_faces[6][4] = {
    {0, 4, 6, 2}, {5, 1, 3, 7}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

static tg_status st_box(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tg_vec3 lo, hi, c[8], q[4], n;
    tg_status st;
    int i, f, mat, inward;
    for (i = 0; v[0].present && v[1].present && i < 3; i++)
        if (!(v[0].v[i] < v[1].v[i])) {
            fail(p, lx, v[1].tok[i].col, "box 'max' must be greater than 'min' on every axis", NULL, NULL);
            break;
        }
    if ((st = begin_geometry(p, lx, kw, &v[2], &v[4], &mat))) return st;
    if (!p->fill) return count_tris(p, lx, kw->col, 12);
    lo = kv_vec3(&v[0]);
    hi = kv_vec3(&v[1]);
    inward = v[3].present;
    for (i = 0; i < 8; i++)
        c[i] = tg_v3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
    for (f = 0; f < 6; f++) {
        tg_real s = (f & 1) ? TG_ONE : tg_neg(TG_ONE);
        if (inward) s = tg_neg(s);
        n = tg_v3(f / 2 == 0 ? s : 0, f / 2 == 1 ? s : 0, f / 2 == 2 ? s : 0);
        for (i = 0; i < 4; i++) q[i] = c[box_faces[f][inward ? (4 - i) & 3 : i]];
        if ((st = emit_quad(p, lx, kw->col, q, &n, mat))) return st;
    }
    return TG_OK;
}

/* UV sphere vertex at ring i (0 = north pole) and segment j. */
static void sphere_vertex(tg_vec3 c, tg_real r, int i, int j, int rings, int segs,
                          tg_vec3 *pos, tg_vec3 *nrm)
{
    tg_vec3 n;
    if (i == 0) n = tg_v3(0, TG_ONE, 0);
    else if (i == rings) n = tg_v3(0, tg_neg(TG_ONE), 0);
    else {
        tg_real theta = tg_mul(TG_PI, tg_ratio(i, rings));
        tg_real phi = tg_mul(TG_TWO_PI, tg_ratio(j % segs, segs));
        tg_real st = tg_sin(theta);
        n = tgi_unit(tg_v3(tg_mul(st, tg_cos(phi)), tg_cos(theta), tg_mul(st, tg_sin(phi))));
    }
    *nrm = n;
    *pos = tgi_v3_add(c, tgi_v3_scale(n, r));
}

static tg_status st_sphere(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tg_vec3 c, pa[4], na[4], tp[3], tn[3];
    tg_status st;
    tg_real r;
    int mat, segs = TG_DEFAULT_SPHERE_SEGMENTS, rings, i, j, k;
    check_range(p, lx, &v[1], "radius", 0, TG_REAL_MAX, LO_OPEN, "greater than 0");
    if (v[3].present) {
        if (v[3].i < TG_MIN_SPHERE_SEGMENTS || v[3].i > TG_MAX_SPHERE_SEGMENTS)
            limit_tok(p, lx, &v[3].tok[0], "sphere segments", TG_MIN_SPHERE_SEGMENTS,
                      TG_MAX_SPHERE_SEGMENTS);
        else
            segs = (int)v[3].i;
    }
    rings = segs / 2;
    if ((st = begin_geometry(p, lx, kw, &v[2], &v[4], &mat))) return st;
    if (!p->fill) return count_tris(p, lx, kw->col, (size_t)(2 * segs * (rings - 1)));
    c = kv_vec3(&v[0]);
    r = v[1].v[0];
    for (i = 0; i < rings; i++)
        for (j = 0; j < segs; j++) {
            /* corners (i,j) (i,j+1) (i+1,j+1) (i+1,j): counter-clockwise from outside */
            sphere_vertex(c, r, i, j, rings, segs, &pa[0], &na[0]);
            sphere_vertex(c, r, i, j + 1, rings, segs, &pa[1], &na[1]);
            sphere_vertex(c, r, i + 1, j + 1, rings, segs, &pa[2], &na[2]);
            sphere_vertex(c, r, i + 1, j, rings, segs, &pa[3], &na[3]);
            if (i > 0) { /* (0 1 2): degenerate at the north pole */
                for (k = 0; k < 3; k++) { tp[k] = pa[k]; tn[k] = na[k]; }
                if ((st = tgi_parse_emit_tri(p, lx, kw->col, tp, tn, mat))) return st;
            }
            if (i < rings - 1) { /* (0 2 3): degenerate at the south pole */
                tp[0] = pa[0]; tp[1] = pa[2]; tp[2] = pa[3];
                tn[0] = na[0]; tn[1] = na[2]; tn[2] = na[3];
                if ((st = tgi_parse_emit_tri(p, lx, kw->col, tp, tn, mat))) return st;
            }
        }
    return TG_OK;
}

/* File name without directory and extension, for "objname/mtlname". */
static void base_name(const tgi_token *path, char out[TG_MAX_NAME + 1])
{
    size_t s = 0, e = path->n, i, n;
    for (i = 0; i < path->n; i++)
        if (path->s[i] == '/' || path->s[i] == '\\') s = i + 1;
    for (i = path->n; i > s; i--)
        if (path->s[i - 1] == '.') { e = i - 1; break; }
    n = e - s < TG_MAX_NAME ? e - s : TG_MAX_NAME;
    memcpy(out, path->s + s, n);
    out[n] = '\0';
}

static tg_status st_mesh(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tgi_xform xf;
    tg_status st;
    char objname[TG_MAX_NAME + 1];
    int mat;
    xf.translate = v[2].present ? kv_vec3(&v[2]) : tg_v3(0, 0, 0);
    xf.scale = TG_ONE;
    kv_positive(p, lx, &v[3], "scale", &xf.scale);
    xf.rot = tgi_m4_identity();
    if (v[4].present) {
        tg_vec3 axis;
        if (!kv_dir(p, lx, &v[4], "rotate", &axis)) xf.rot = tgi_m4_rotate(axis, tgi_deg_to_rad(v[4].v[3]));
    }
    if ((st = begin_geometry(p, lx, kw, &v[1], &v[5], &mat))) return st;
    if (v[5].present) copy_name(objname, &v[5].tok[0]);
    else base_name(&v[0].tok[0], objname);
#if TG_NO_OBJ
    (void)xf;
    return fail(p, lx, kw->col, "'mesh': OBJ files are left out of this build (TG_NO_OBJ=1)", NULL, NULL);
#else
    return tgi_obj_mesh(p, lx, &v[0].tok[0], &xf, mat, objname);
#endif
}

static tg_status st_object_key(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tgi_key key, *k;
    tg_status st;
    uint16_t *own;
    char buf[48];
    int obj;
    size_t i;
    memset(&key, 0, sizeof key);
    key.t = v[1].v[0];
    if (v[2].present) key.translate = kv_vec3(&v[2]);
    key.axis = tg_v3(0, TG_ONE, 0);
    if (v[3].present) {
        kv_dir(p, lx, &v[3], "rotate", &key.axis);
        key.angle = tgi_deg_to_rad(v[3].v[3]);
    }
    if ((st = line_status(p))) return st;
    if (p->object_keys >= TG_MAX_KEYS)
        return limit(p, lx, kw->col, "object_key count", 0, TG_MAX_KEYS, p->object_keys + 1);
    if (p->fill) {
        obj = find_object(p, &v[0].tok[0]);
        if (obj < 0)
            return fail(p, lx, v[0].tok[0].col, "undefined object '", tgi_tok_str(&v[0].tok[0], buf),
                        "' in object_key; give an object 'name ID' before its keys");
        k = p->scene->object_keys;
        own = p->key_owner;
        for (i = 0; i < p->object_keys; i++)
            if (own[i] == obj && k[i].t == key.t)
                return fail(p, lx, v[1].tok[0].col, "duplicate object_key time 't' for object '",
                            tgi_tok_str(&v[0].tok[0], buf), "'");
        /* insert sorted by (object, t) so each object's keys are contiguous */
        for (i = p->object_keys; i > 0 && (own[i - 1] > obj || (own[i - 1] == obj && k[i - 1].t > key.t)); i--) {
            k[i] = k[i - 1];
            own[i] = own[i - 1];
        }
        k[i] = key;
        own[i] = (uint16_t)obj;
    }
    p->object_keys++;
    return TG_OK;
}

static tg_status check_color(tgi_parser *p, const tgi_lexer *lx, const key_val *kv, const char *key)
{
    return check_range(p, lx, kv, key, 0, TG_REAL_MAX, 0, "0 or more");
}

static tg_status st_light(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *parsed)
{
    static const key_spec dir_spec[] = {
        {"dir", K_VEC3, 1}, {"color", K_VEC3, 1}, {"intensity", K_REAL, 0}, {"shadows", K_FLAG, 0}};
    static const key_spec point_spec[] = {
        {"pos", K_VEC3, 1}, {"color", K_VEC3, 1}, {"intensity", K_REAL, 0}, {"shadows", K_FLAG, 0}};
    static const key_spec spot_spec[] = {
        {"pos", K_VEC3, 1}, {"color", K_VEC3, 1}, {"intensity", K_REAL, 0}, {"shadows", K_FLAG, 0},
        {"dir", K_VEC3, 1}, {"angle", K_REAL, 1}};
    key_val v[MAX_SPEC];
    tgi_light l;
    tgi_token type;
    tg_status st;
    char buf[48];
    (void)parsed;
    memset(&l, 0, sizeof l);
    if (!tgi_lex_token(lx, &type))
        return fail(p, lx, tgi_lex_eol_col(lx), "'light' expects a type: directional, point or spot", NULL, NULL);
    if (tgi_tok_is(&type, "directional")) {
        l.type = TG_LIGHT_DIRECTIONAL;
        parse_keys(p, lx, kw, dir_spec, NSPEC(dir_spec), v);
    } else if (tgi_tok_is(&type, "point")) {
        l.type = TG_LIGHT_POINT;
        parse_keys(p, lx, kw, point_spec, NSPEC(point_spec), v);
    } else if (tgi_tok_is(&type, "spot")) {
        l.type = TG_LIGHT_SPOT;
        parse_keys(p, lx, kw, spot_spec, NSPEC(spot_spec), v);
    } else
        return fail(p, lx, type.col, "unknown light type '", tgi_tok_str(&type, buf),
                    "'; expected directional, point or spot");
    if (l.type == TG_LIGHT_DIRECTIONAL) kv_dir(p, lx, &v[0], "dir", &l.dir);
    else l.pos = kv_vec3(&v[0]);
    check_color(p, lx, &v[1], "color");
    check_range(p, lx, &v[2], "intensity", 0, TG_REAL_MAX, 0, "0 or more");
    if (l.type == TG_LIGHT_SPOT) {
        kv_dir(p, lx, &v[4], "dir", &l.dir);
        check_range(p, lx, &v[5], "angle", 0, TG_R(90.0f), LO_OPEN,
                    "in (0, 90] degrees (the cone's half angle)");
        l.angle = tgi_deg_to_rad(v[5].v[0]);
    }
    if ((st = line_status(p))) return st;
    l.color = kv_vec3(&v[1]);
    l.intensity = v[2].present ? v[2].v[0] : TG_ONE;
    l.shadows = v[3].present;
    if (p->lights >= TG_MAX_LIGHTS)
        return limit(p, lx, kw->col, "light count", 0, TG_MAX_LIGHTS, p->lights + 1);
    if (p->fill) p->scene->lights[p->lights] = l;
    p->lights++;
    return TG_OK;
}

/* `count` positional numbers, none negative when nonneg is set. */
static tg_status positional(tgi_parser *p, tgi_lexer *lx, const char *what, int count,
                            int nonneg, tg_real *out)
{
    tgi_token toks[27];
    char buf[48];
    int i;
    memset(toks, 0, sizeof toks);
    if (!read_numbers(p, lx, NULL, 0, what, count, 0, toks, out, NULL))
        expect_end(p, lx, what, count);
    for (i = 0; nonneg && i < count && toks[i].s; i++) /* the numbers read */
        if (out[i] < 0) {
            tg_error *e = fail_begin(p, lx, toks[i].col, "'", what, "' must be 0 or more, got '");
            tgi_error_append(e, tgi_tok_str(&toks[i], buf));
            tgi_error_append(e, "'");
            break;
        }
    return line_status(p);
}

static tg_status st_env(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *parsed)
{
    static const key_spec sky_spec[] = {{"sky", K_VEC3, 1}, {"ground", K_VEC3, 1}, {"up", K_VEC3, 0}};
    key_val v[MAX_SPEC];
    tgi_env env;
    tgi_token type;
    tg_status st;
    tg_real num[27];
    char buf[48];
    int i;
    (void)parsed;
    memset(&env, 0, sizeof env);
    if (!tgi_lex_peek(lx, &type))
        return fail(p, lx, tgi_lex_eol_col(lx), "'env' expects a type: uniform, sky or sh9", NULL, NULL);
    if (tgi_tok_is(&type, "uniform")) {
        tgi_lex_token(lx, &type);
        if ((st = positional(p, lx, "uniform", 3, 1, num))) return st;
        env.type = TG_ENV_UNIFORM;
        env.uniform = tg_v3(num[0], num[1], num[2]);
    } else if (tgi_tok_is(&type, "sky")) {
        parse_keys(p, lx, kw, sky_spec, NSPEC(sky_spec), v);
        check_color(p, lx, &v[0], "sky");
        check_color(p, lx, &v[1], "ground");
        env.up = tg_v3(0, TG_ONE, 0);
        kv_dir(p, lx, &v[2], "up", &env.up);
        if ((st = line_status(p))) return st;
        env.type = TG_ENV_SKY;
        env.sky = kv_vec3(&v[0]);
        env.ground = kv_vec3(&v[1]);
    } else if (tgi_tok_is(&type, "sh9")) {
        tgi_lex_token(lx, &type);
        if ((st = positional(p, lx, "sh9", 27, 0, num))) return st;
        env.type = TG_ENV_SH9;
        for (i = 0; i < 9; i++) env.sh9[i] = tg_v3(num[3 * i], num[3 * i + 1], num[3 * i + 2]);
    } else
        return fail(p, lx, type.col, "unknown env type '", tgi_tok_str(&type, buf),
                    "'; expected uniform, sky or sh9");
    if (p->fill) p->scene->env = env;
    return TG_OK;
}

/* An integer value within a limit of tinygi.h's block (or absent). */
static tg_status int_limit(tgi_parser *p, const tgi_lexer *lx, const key_val *kv,
                           const char *name, long lo, long hi)
{
    if (!kv->present || (kv->i >= lo && kv->i <= hi)) return TG_OK;
    return limit_tok(p, lx, &kv->tok[0], name, lo, hi);
}

static tg_status st_gi(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *v)
{
    tgi_gi_settings gi;
    tg_status st;
    (void)kw;
    if (v[0].present && (v[0].v[0] < 0 || v[0].v[0] > TG_R(TG_MAX_RADIUS)))
        limit_tok(p, lx, &v[0].tok[0], "gi radius", 0, TG_MAX_RADIUS);
    int_limit(p, lx, &v[1], "gi slices", 1, TG_MAX_SLICES);
    int_limit(p, lx, &v[2], "gi samples", 1, TG_MAX_SAMPLES);
    int_limit(p, lx, &v[3], "gi bounces", 0, TG_MAX_BOUNCES);
    if ((st = line_status(p))) return st;
    gi.radius = v[0].present ? v[0].v[0] : TG_R(-1.0f);
    gi.slices = v[1].present ? (int)v[1].i : 0;
    gi.samples = v[2].present ? (int)v[2].i : 0;
    gi.bounces = v[3].present ? (int)v[3].i : -1;
    if (p->fill) p->scene->gi = gi;
    return TG_OK;
}

static const struct { const char *word; uint32_t bit; } effect_words[] = {
    {"direct", TG_EFFECT_DIRECT}, {"shadows", TG_EFFECT_SHADOWS}, {"far", TG_EFFECT_FAR},
    {"near", TG_EFFECT_NEAR}, {"ao", TG_EFFECT_AO}, {"reprojection", TG_EFFECT_REPROJECTION}};

static tg_status st_effects(tgi_parser *p, tgi_lexer *lx, const tgi_token *kw, const key_val *parsed)
{
    static const char expect[] = "; expected 'auto' or a list of: direct shadows far near ao reprojection";
    tgi_token t;
    uint32_t bits = 0;
    char buf[48];
    size_t i;
    int n = 0, is_auto = 0;
    (void)kw; (void)parsed;
    while (tgi_lex_token(lx, &t)) {
        if (tgi_tok_is(&t, "auto")) {
            if (n > 0) return fail(p, lx, t.col, "'auto' cannot be mixed with a list of effects", NULL, NULL);
            is_auto = 1;
        } else {
            if (is_auto) return fail(p, lx, t.col, "'auto' cannot be mixed with a list of effects", NULL, NULL);
            for (i = 0; i < sizeof effect_words / sizeof effect_words[0]; i++)
                if (tgi_tok_is(&t, effect_words[i].word)) break;
            if (i == sizeof effect_words / sizeof effect_words[0]) {
                tg_error *e = fail_begin(p, lx, t.col, "unknown effect '", tgi_tok_str(&t, buf), "'");
                tgi_error_append(e, expect);
                return TG_ERR_INPUT;
            }
            bits |= effect_words[i].bit;
        }
        n++;
    }
    if (n == 0) return fail(p, lx, tgi_lex_eol_col(lx), "'effects' expects a value", expect, NULL);
    if (p->fill) {
        p->scene->effects_auto = is_auto;
        p->scene->effects = is_auto ? 0 : bits;
    }
    return TG_OK;
}

/* The statements' keys, in the order each statement reads them in v[]
 * (key, kind, required). */
static const key_spec keys_camera[] = {
    {"pos", K_VEC3, 1}, {"target", K_VEC3, 1}, {"up", K_VEC3, 0},
    {"fov", K_REAL, 0}, {"near", K_REAL, 0}, {"far", K_REAL, 0}};
static const key_spec keys_camera_key[] = {{"t", K_REAL, 1}, {"pos", K_VEC3, 1}, {"target", K_VEC3, 1}};
static const key_spec keys_quad[] = {
    {"p0", K_VEC3, 1}, {"p1", K_VEC3, 1}, {"p2", K_VEC3, 1}, {"p3", K_VEC3, 1},
    {"material", K_NAME, 1}, {"name", K_NAME, 0}};
static const key_spec keys_box[] = {
    {"min", K_VEC3, 1}, {"max", K_VEC3, 1}, {"material", K_NAME, 1},
    {"inward", K_FLAG, 0}, {"name", K_NAME, 0}};
static const key_spec keys_sphere[] = {
    {"center", K_VEC3, 1}, {"radius", K_REAL, 1}, {"material", K_NAME, 1},
    {"segments", K_INT, 0}, {"name", K_NAME, 0}};
static const key_spec keys_mesh[] = {
    {"file", K_PATH, 1}, {"material", K_NAME, 1}, {"translate", K_VEC3, 0},
    {"scale", K_REAL, 0}, {"rotate", K_ROT, 0}, {"name", K_NAME, 0}};
static const key_spec keys_object_key[] = {
    {"name", K_NAME, 1}, {"t", K_REAL, 1}, {"translate", K_VEC3, 0}, {"rotate", K_ROT, 0}};
static const key_spec keys_gi[] = {
    {"radius", K_REAL, 0}, {"slices", K_INT, 0}, {"samples", K_INT, 0}, {"bounces", K_INT, 0}};

/* The statements: keyword, function, the keys the dispatcher parses for it
 * (NULL: it reads its own, after a name or a type), and whether it may
 * stand only once in a file. */
#define KEYS(t) t, NSPEC(t)
static const struct {
    const char *kw;
    statement_fn fn;
    const key_spec *keys;
    int nkeys, once;
} statements[] = {
    {"camera", st_camera, KEYS(keys_camera), 1},
    {"camera_key", st_camera_key, KEYS(keys_camera_key), 0},
    {"material", st_material, NULL, 0, 0},
    {"quad", st_quad, KEYS(keys_quad), 0},
    {"box", st_box, KEYS(keys_box), 0},
    {"sphere", st_sphere, KEYS(keys_sphere), 0},
    {"mesh", st_mesh, KEYS(keys_mesh), 0},
    {"object_key", st_object_key, KEYS(keys_object_key), 0},
    {"light", st_light, NULL, 0, 0},
    {"env", st_env, NULL, 0, 1},
    {"gi", st_gi, KEYS(keys_gi), 1},
    {"effects", st_effects, NULL, 0, 1}};
#define NSTATEMENTS ((int)(sizeof statements / sizeof statements[0]))

/* ===================================================================== */
/* the passes                                                            */
/* ===================================================================== */

static void reset_counts(tgi_parser *p)
{
    p->tris = p->materials = p->objects = p->object_keys = p->camera_keys = p->lights = 0;
    p->usemtl_bound = 0;
    p->have_camera = 0;
}

static tg_status run_pass(tgi_parser *p, const char *text, size_t size)
{
    tgi_lexer lx;
    tgi_token kw;
    tg_status st;
    char buf[48];
    key_val v[MAX_SPEC];
    unsigned char seen[NSTATEMENTS];
    size_t i, n = sizeof statements / sizeof statements[0];
    int r;
    memset(seen, 0, sizeof seen);
    reset_counts(p);
    tgi_lex_init(&lx, text, size, p->file);
    while ((r = tgi_lex_line(&lx, p->err)) > 0) {
        p->line_col = 0;
        if (!tgi_lex_token(&lx, &kw)) continue;
        for (i = 0; i < n; i++)
            if (tgi_tok_is(&kw, statements[i].kw)) break;
        if (i == n) {
            tg_error *e = fail_begin(p, &lx, kw.col, "unknown keyword '", tgi_tok_str(&kw, buf), "'; expected one of:");
            for (i = 0; i < n; i++) {
                tgi_error_append(e, " ");
                tgi_error_append(e, statements[i].kw);
            }
            return TG_ERR_INPUT;
        }
        if (statements[i].once && seen[i]++)
            return fail(p, &lx, kw.col, "duplicate '", statements[i].kw, "' statement; only one is allowed");
        /* an error in the keys leaves the statement to check the values read before it */
        if (statements[i].keys) parse_keys(p, &lx, &kw, statements[i].keys, statements[i].nkeys, v);
        if ((st = statements[i].fn(p, &lx, &kw, statements[i].keys ? v : NULL))) return st;
        if ((st = line_status(p))) return st;   /* an error its statement did not stop at */
    }
    if (r < 0) return TG_ERR_INPUT;
    if (!p->have_camera && p->camera_keys == 0)
        return tgi_parse_fail(p, p->file, lx.lineno > 0 ? lx.lineno : 1, 1,
                             "the scene has no 'camera' statement; expected "
                             "'camera pos X Y Z target X Y Z' (or camera_key lines)", NULL, NULL);
    return TG_OK;
}

static void scene_defaults(tg_scene *s)
{
    s->camera.up = tg_v3(0, TG_ONE, 0);
    s->camera.fov = tgi_deg_to_rad(TG_R(TG_DEFAULT_FOV));
    s->camera.znear = TG_R(TG_DEFAULT_NEAR);
    s->camera.zfar = TG_R(TG_DEFAULT_FAR);
    s->env.type = TG_ENV_NONE;
    s->gi.radius = TG_R(-1.0f);
    s->gi.slices = s->gi.samples = 0;
    s->gi.bounces = -1;
    s->effects_auto = 1;
    s->effects = 0;
}

/* After pass 2: counts, key ranges per object, a camera from the keys. */
static void finish_scene(tgi_parser *p)
{
    tg_scene *s = p->scene;
    size_t i;
    s->material_count = (int)p->materials;
    s->object_count = (int)p->objects;
    s->object_key_count = (int)p->object_keys;
    s->camera_key_count = (int)p->camera_keys;
    s->light_count = (int)p->lights;
    s->tri_count = (int)p->tris;
    for (i = 0; i < p->object_keys; i++) {
        tgi_object *o = &s->objects[p->key_owner[i]];
        if (o->key_count == 0) o->first_key = (int)i;
        o->key_count++;
    }
    if (!p->have_camera && p->camera_keys > 0) {
        s->camera.pos = s->camera_keys[0].pos;
        s->camera.target = s->camera_keys[0].target;
    }
}

/* Offsets of one arena carve, as tg_arena_alloc will place them (aligned
 * addresses: the padding depends on where the arena's memory starts). */
static int plan_add(const tg_arena *a, size_t *at, size_t count, size_t elem)
{
    size_t bytes, start;
    if (tg_size_mul(count, elem, &bytes) || tg_size_add(*at, tgi_arena_pad(a->base, *at), &start)) return 1;
    return tg_size_add(start, bytes, at);
}

tg_status tg_scene_parse(const char *text, size_t size, const char *filename,
                         const tg_io *io, tg_arena *arena, tg_scene **scene,
                         tg_error *err)
{
    tgi_parser p;
    tg_scene *s;
    tg_status st;
    size_t at, perm_end, used0 = arena ? arena->used : 0, tris3 = 0;
    int bad = 0;

    tgi_error_clear(err);
    if (scene) *scene = NULL;
    memset(&p, 0, sizeof p);
    p.file = filename ? filename : "<scene>";
    p.io = io;
    p.err = err;
    if (!arena || !scene || (!text && size)) return fail_runtime(&p, "tg_scene_parse: missing argument");
    if (size > (size_t)TG_MAX_FILE_BYTES) {
        char got[24];
        return tgi_limit_fail(err, p.file, 0, 0, "scene size in bytes", 0, TG_MAX_FILE_BYTES,
                              tgi_number_text(size, got));
    }

    /* pass 1: validate and count */
    if ((st = run_pass(&p, text, size))) return st;

    /* the arena: the scene's arrays, then scratch released at the end */
    p.material_cap = p.materials + (p.usemtl_bound < TG_MAX_MATERIALS ? p.usemtl_bound : TG_MAX_MATERIALS);
    if (p.material_cap > TG_MAX_MATERIALS) p.material_cap = TG_MAX_MATERIALS;
    at = used0;
    bad |= tg_size_mul(p.tris, 3, &tris3);
    bad |= plan_add(arena, &at, 1, sizeof(tg_scene));
    bad |= plan_add(arena, &at, p.material_cap, sizeof(tgi_material));
    bad |= plan_add(arena, &at, p.objects, sizeof(tgi_object));
    bad |= plan_add(arena, &at, p.object_keys, sizeof(tgi_key));
    bad |= plan_add(arena, &at, p.camera_keys, sizeof(tgi_camera_key));
    bad |= plan_add(arena, &at, tris3, sizeof(tg_vec3));
    bad |= plan_add(arena, &at, tris3, sizeof(tg_vec3));
    bad |= plan_add(arena, &at, p.tris, sizeof(uint16_t));
    bad |= plan_add(arena, &at, p.tris, sizeof(uint16_t));
    bad |= plan_add(arena, &at, p.lights, sizeof(tgi_light));
    perm_end = at;
    bad |= plan_add(arena, &at, p.object_keys, sizeof(uint16_t));
    bad |= plan_add(arena, &at, p.obj_scratch, sizeof(tg_vec3));
    (void)perm_end;
    if (bad || at > arena->size) {
        tgi_error_set(err, TG_ERR_MEMORY, p.file, 0, 0, "the arena is too small for the scene");
        if (err) err->bytes_needed = bad ? (size_t)-1 : at;
        return TG_ERR_MEMORY;
    }

    s = (tg_scene *)tg_arena_alloc(arena, sizeof(tg_scene));
    s->materials = (tgi_material *)tg_arena_alloc(arena, p.material_cap * sizeof(tgi_material));
    s->objects = (tgi_object *)tg_arena_alloc(arena, p.objects * sizeof(tgi_object));
    s->object_keys = (tgi_key *)tg_arena_alloc(arena, p.object_keys * sizeof(tgi_key));
    s->camera_keys = (tgi_camera_key *)tg_arena_alloc(arena, p.camera_keys * sizeof(tgi_camera_key));
    s->tri_pos = (tg_vec3 *)tg_arena_alloc(arena, tris3 * sizeof(tg_vec3));
    s->tri_nrm = (tg_vec3 *)tg_arena_alloc(arena, tris3 * sizeof(tg_vec3));
    s->tri_material = (uint16_t *)tg_arena_alloc(arena, p.tris * sizeof(uint16_t));
    s->tri_object = (uint16_t *)tg_arena_alloc(arena, p.tris * sizeof(uint16_t));
    s->lights = (tgi_light *)tg_arena_alloc(arena, p.lights * sizeof(tgi_light));
    perm_end = arena->used;
    p.key_owner = (uint16_t *)tg_arena_alloc(arena, p.object_keys * sizeof(uint16_t));
    p.scratch = (tg_vec3 *)tg_arena_alloc(arena, p.obj_scratch * sizeof(tg_vec3));
    if (!s || !s->materials || !s->objects || !s->object_keys || !s->camera_keys ||
        !s->tri_pos || !s->tri_nrm || !s->tri_material || !s->tri_object || !s->lights ||
        !p.key_owner || !p.scratch) {
        arena->used = used0;
        return fail_runtime(&p, "arena carve failed");
    }
    s->tri_count = (int)p.tris; /* the capacity, checked by emit */
    scene_defaults(s);

    /* pass 2: fill */
    p.fill = 1;
    p.scene = s;
    if ((st = run_pass(&p, text, size))) {
        arena->used = used0;
        return st;
    }
    if (p.tris != (size_t)s->tri_count) {
        arena->used = used0;
        return fail_runtime(&p, "a mesh file changed while parsing");
    }
    finish_scene(&p);
    arena->used = perm_end; /* release the scratch */
    *scene = s;
    return TG_OK;
}

#endif /* !TG_NO_SCENE_TEXT */
