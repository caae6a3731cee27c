/* SPDX-License-Identifier: MIT */
/*
 * obj.c - Wavefront OBJ meshes and their MTL materials, for the scene's
 * `mesh` statement (format.md, "OBJ and MTL").
 *
 * OBJ: `v x y z [w | r g b]`, `vn x y z`, `vt u [v [w]]`, `f` with v, v/vt,
 * v//vn, v/vt/vn references (1-based, or negative: counted back from the
 * last vertex so far), polygons fan-triangulated, `usemtl NAME`,
 * `mtllib FILE...`.  Everything else (o, g, s, l, p, ...) is ignored.
 * MTL: `newmtl NAME` blocks with `Kd` (albedo) and `Ke` (emission); other
 * MTL statements are ignored.
 *
 * The file is read through tg_io in both passes.  Pass 1 validates and
 * counts v + vn (the scratch this mesh needs); pass 2 keeps the transformed
 * positions at the front of the parser's scratch and the rotated normals at
 * its back, and emits the triangles.
 */
#include <string.h>
#include "parse_internal.h"
#include "../core/path.h"

#if !TG_NO_OBJ && !TG_NO_SCENE_TEXT /* the whole file is left out with TG_NO_OBJ=1 or TG_NO_SCENE_TEXT=1 (tinygi.h "FEATURE SWITCHES") */

typedef struct mtllib_ref {
    tgi_token name;          /* points into the OBJ text */
    char path[TG_MAX_PATH];  /* resolved against the OBJ's directory */
    const char *data;        /* the MTL file, read at its mtllib line */
    size_t size;
} mtllib_ref;

typedef struct obj_state {
    tgi_parser *p;
    const char *path;       /* resolved OBJ path: messages and MTL paths */
    const tgi_xform *xf;
    int base_material;      /* the mesh statement's material */
    int material;           /* the current one (usemtl) */
    size_t first_material;  /* pass 2: materials this mesh adds start here */
    const char *objname;
    size_t nv, nvt, nvn;
    int nlib;
    mtllib_ref lib[TG_MAX_MTLLIBS];
} obj_state;

typedef struct obj_ref {
    size_t v, vn;
    int has_vn;
} obj_ref;

/* Resolve `name` (a token at FILE:LINE) against the directory of `base`
 * and read that file (an OBJ, or an MTL when `mtl`) through tg_io.  An
 * error names the file and why it cannot be read ("cannot read mesh file
 * 'a.obj': permission denied"), or the path length or file size against
 * TG_MAX_PATH and TG_MAX_FILE_BYTES. */
static tg_status load_file(tgi_parser *p, const char *file, int line, const tgi_token *name,
                           const char *base, int mtl, char path[TG_MAX_PATH],
                           const char **data, size_t *size)
{
    const char *reason = NULL;
    char got[24];
    size_t n = tgi_path_join(base, name->s, name->n, path);
    *data = NULL;
    *size = 0;
    if (n >= TG_MAX_PATH) {
        tgi_limit_fail(p->err, file, line, name->col,
                       mtl ? "MTL path length in bytes" : "mesh path length in bytes",
                       1, TG_MAX_PATH - 1, tgi_number_text(n, got));
        tgi_error_append(p->err, " (joined to the directory of the file naming it)");
        return TG_ERR_INPUT;
    }
    if (!p->io || !p->io->read_file) reason = "no tg_io to read files with";
    else if (p->io->read_file(p->io->user, path, data, size, &reason) == 0 && (*data || !*size)) {
        if (!*data) *data = "";
        if (*size <= (size_t)TG_MAX_FILE_BYTES) return TG_OK;
        return tgi_limit_fail(p->err, file, line, name->col,
                              mtl ? "MTL file size in bytes" : "mesh file size in bytes",
                              0, TG_MAX_FILE_BYTES, tgi_number_text(*size, got));
    }
    tgi_parse_fail(p, file, line, name->col, "cannot read ", mtl ? "MTL" : "mesh", " file '");
    tgi_error_append(p->err, path);
    tgi_error_append(p->err, "'");
    if (reason) {
        tgi_error_append(p->err, ": ");
        tgi_error_append(p->err, reason);
    }
    return TG_ERR_INPUT;
}

static tg_status ofail(obj_state *o, const tgi_lexer *lx, int col,
                       const char *a, const char *b, const char *c)
{
    return tgi_parse_fail(o->p, lx->file, lx->lineno, col, a, b, c);
}

static tg_status changed(obj_state *o)
{
    tgi_error_set(o->p->err, TG_ERR_RUNTIME, o->path, 0, 0, "the mesh file changed while parsing");
    return TG_ERR_RUNTIME;
}

static tg_status bad_number(obj_state *o, const tgi_lexer *lx, const tgi_token *t,
                            const char *what, int r)
{
    char buf[48];
    ofail(o, lx, t->col, r == 2 ? "number out of range in '" : "expected a number in '", what, "', got '");
    tgi_error_append(o->p->err, tgi_tok_str(t, buf));
    tgi_error_append(o->p->err, r == 2 ? "'" TGI_RANGE_NOTE : "'");
    return TG_ERR_INPUT;
}

/* Up to `max` numbers (at least `min`) after the keyword. */
static tg_status numbers(obj_state *o, tgi_lexer *lx, const char *what, int min, int max,
                         tg_real *out, int *count)
{
    tgi_token t;
    tg_real x;
    int n = 0, r;
    while (tgi_lex_token(lx, &t)) {
        if ((r = tgi_tok_real(&t, &x))) return bad_number(o, lx, &t, what, r);
        if (n >= max) {
            ofail(o, lx, t.col, "too many numbers for '", what, "' (expects ");
            tgi_error_append_int(o->p->err, max);
            tgi_error_append(o->p->err, ")");
            return TG_ERR_INPUT;
        }
        out[n++] = x;
    }
    if (n < min) {
        ofail(o, lx, tgi_lex_eol_col(lx), "'", what, "' expects ");
        tgi_error_append_int(o->p->err, min);
        tgi_error_append(o->p->err, min == 1 ? " number, got " : " numbers, got ");
        tgi_error_append_int(o->p->err, n);
        return TG_ERR_INPUT;
    }
    *count = n;
    return TG_OK;
}

/* v (normal == 0) or vn (normal == 1): stored transformed in pass 2. */
static tg_status obj_vertex(obj_state *o, tgi_lexer *lx, const tgi_token *kw, int normal)
{
    tgi_parser *p = o->p;
    tg_real x[7];
    tg_vec3 v;
    tg_status st;
    size_t *count = normal ? &o->nvn : &o->nv;
    int n;
    if ((st = numbers(o, lx, normal ? "vn" : "v", 3, normal ? 3 : 7, x, &n))) return st;
    if (*count >= TG_MAX_OBJ_VERTICES) {
        char got[24];
        return tgi_limit_fail(p->err, lx->file, lx->lineno, kw->col,
                              normal ? "vn count per OBJ file" : "v count per OBJ file",
                              0, TG_MAX_OBJ_VERTICES, tgi_number_text(*count + 1, got));
    }
    if (p->fill) {
        if (o->nv + o->nvn >= p->obj_scratch) return changed(o);
        v = tg_v3(x[0], x[1], x[2]);
        if (normal) /* rotated with the mesh; zero stays zero (face normal then) */
            p->scratch[p->obj_scratch - 1 - o->nvn] =
                tgi_unit(tgi_m4_dir(&o->xf->rot, v));
        else /* p' = R (s p) + t */
            p->scratch[o->nv] = tgi_v3_add(tgi_m4_point(&o->xf->rot, tgi_v3_scale(v, o->xf->scale)),
                                          o->xf->translate);
    }
    (*count)++;
    return TG_OK;
}

static tg_status obj_texcoord(obj_state *o, tgi_lexer *lx)
{
    tg_real x[3];
    int n;
    tg_status st = numbers(o, lx, "vt", 1, 3, x, &n);
    if (st) return st;
    if (o->nvt < TG_MAX_OBJ_VERTICES) o->nvt++;
    return TG_OK;
}

/* One OBJ index (1-based or negative) against `count` defined so far. */
static tg_status obj_index(obj_state *o, const tgi_lexer *lx, const tgi_token *ref,
                           const tgi_token *part, size_t count, const char *what, size_t *out)
{
    char buf[48];
    long i;
    int r = tgi_tok_int(part, &i);
    if (r == 1) {
        ofail(o, lx, ref->col, "bad face vertex '", tgi_tok_str(ref, buf),
              "'; expected v, v/vt, v//vn or v/vt/vn with integer indices");
        return TG_ERR_INPUT;
    }
    if (r == 0 && i == 0)
        return ofail(o, lx, ref->col, "OBJ ", what,
                     " index 0 is invalid; indices start at 1 (or count back from -1)");
    if (r == 2 || (i > 0 && (size_t)i > count) || (i < 0 && (size_t)-i > count)) {
        ofail(o, lx, ref->col, "OBJ ", what, " index ");
        tgi_error_append(o->p->err, tgi_tok_str(part, buf));
        tgi_error_append(o->p->err, " is out of range (");
        tgi_error_append_int(o->p->err, (long)count);
        tgi_error_append(o->p->err, " defined so far)");
        return TG_ERR_INPUT;
    }
    *out = i > 0 ? (size_t)i - 1 : count - (size_t)-i;
    return TG_OK;
}

static tg_status obj_ref_parse(obj_state *o, const tgi_lexer *lx, const tgi_token *t, obj_ref *r)
{
    tgi_token part[3];
    size_t i, k = 0, at = 0, dummy;
    tg_status st;
    char buf[48];
    for (i = 0; i <= t->n; i++) {
        if (i == t->n || t->s[i] == '/') {
            if (k >= 3) {
                return ofail(o, lx, t->col, "bad face vertex '", tgi_tok_str(t, buf),
                             "'; expected v, v/vt, v//vn or v/vt/vn");
            }
            part[k].s = t->s + at;
            part[k].n = i - at;
            part[k].col = t->col + (int)at;
            k++;
            at = i + 1;
        }
    }
    if ((st = obj_index(o, lx, t, &part[0], o->nv, "vertex", &r->v))) return st;
    if (k >= 2 && (part[1].n > 0 || k == 2) &&
        (st = obj_index(o, lx, t, &part[1], o->nvt, "texture", &dummy)))
        return st;
    r->has_vn = k == 3;
    if (r->has_vn && (st = obj_index(o, lx, t, &part[2], o->nvn, "normal", &r->vn))) return st;
    return TG_OK;
}

static tg_status obj_triangle(obj_state *o, const tgi_lexer *lx, int col, const obj_ref r[3])
{
    tgi_parser *p = o->p;
    tg_vec3 pos[3], nrm[3];
    int i, smooth = 1;
    for (i = 0; i < 3; i++) {
        pos[i] = nrm[i] = tg_v3(0, 0, 0);
        if (!p->fill) continue;
        pos[i] = p->scratch[r[i].v];
        if (r[i].has_vn) nrm[i] = p->scratch[p->obj_scratch - 1 - r[i].vn];
        if (!r[i].has_vn || (nrm[i].x == 0 && nrm[i].y == 0 && nrm[i].z == 0)) smooth = 0;
    }
    return tgi_parse_emit_tri(p, lx, col, pos, smooth ? nrm : NULL, o->material);
}

/* f: a polygon, fan-triangulated (r0 r[k-1] r[k]). */
static tg_status obj_face(obj_state *o, tgi_lexer *lx)
{
    tgi_token t;
    obj_ref tri[3], first, prev, cur;
    tg_status st;
    int n = 0;
    memset(&first, 0, sizeof first);
    prev = first;
    while (tgi_lex_token(lx, &t)) {
        if ((st = obj_ref_parse(o, lx, &t, &cur))) return st;
        if (n == 0) first = cur;
        if (n >= 2) {
            tri[0] = first; tri[1] = prev; tri[2] = cur;
            if ((st = obj_triangle(o, lx, t.col, tri))) return st;
        }
        prev = cur;
        n++;
    }
    if (n < 3) {
        ofail(o, lx, tgi_lex_eol_col(lx), "a face needs at least 3 vertices, got ", NULL, NULL);
        tgi_error_append_int(o->p->err, n);
        return TG_ERR_INPUT;
    }
    return TG_OK;
}

/* mtllib FILE...: each file is read here, so a missing one is an error
 * whether or not a usemtl needs it (format.md). */
static tg_status obj_mtllib(obj_state *o, tgi_lexer *lx, const tgi_token *kw)
{
    tgi_token t;
    tg_status st;
    char got[24];
    int n = 0;
    while (tgi_lex_token(lx, &t)) {
        mtllib_ref *lib = &o->lib[o->nlib];
        if (o->nlib >= TG_MAX_MTLLIBS)
            return tgi_limit_fail(o->p->err, lx->file, lx->lineno, t.col, "mtllib count per OBJ file",
                                  0, TG_MAX_MTLLIBS, tgi_number_text((size_t)o->nlib + 1, got));
        memset(lib, 0, sizeof *lib);
        lib->name = t;
        if ((st = load_file(o->p, lx->file, lx->lineno, &t, o->path, 1, lib->path, &lib->data, &lib->size)))
            return st;
        o->nlib++;
        n++;
    }
    if (n == 0) return ofail(o, lx, kw->col + 6, "'mtllib' expects a file name", NULL, NULL);
    return TG_OK;
}

/* Kd (albedo, in [0,1]) or Ke (emission, >= 0): 1 or 3 numbers. */
static tg_status mtl_color(obj_state *o, tgi_lexer *ml, const char *what, int unit, tg_vec3 *out)
{
    tgi_token t[3], extra;
    tg_real x[3];
    char buf[48];
    int n = 0, i, r;
    while (n < 3 && tgi_lex_token(ml, &t[n])) {
        if ((r = tgi_tok_real(&t[n], &x[n]))) return bad_number(o, ml, &t[n], what, r);
        n++;
    }
    if (n == 2 || n == 0 || tgi_lex_peek(ml, &extra)) {
        ofail(o, ml, n == 3 || n == 1 ? extra.col : tgi_lex_eol_col(ml), "'", what,
              "' expects 3 numbers (r g b) or 1 (grey)");
        return TG_ERR_INPUT;
    }
    if (n == 1) { x[1] = x[2] = x[0]; t[1] = t[2] = t[0]; }
    for (i = 0; i < 3; i++)
        if (x[i] < 0 || (unit && x[i] > TG_ONE)) {
            ofail(o, ml, t[i].col, "'", what, unit ? "' must be in [0, 1], got '" : "' must be 0 or more, got '");
            tgi_error_append(o->p->err, tgi_tok_str(&t[i], buf));
            tgi_error_append(o->p->err, "'");
            return TG_ERR_INPUT;
        }
    *out = tg_v3(x[0], x[1], x[2]);
    return TG_OK;
}

/* Find `name` in one MTL file; 1 found (m updated), 0 not, -1 error. */
static int mtl_search(obj_state *o, const mtllib_ref *lib, const tgi_token *name, tgi_material *m)
{
    tgi_lexer ml;
    tgi_token kw, rest;
    int r, in_block = 0;
    tgi_lex_init(&ml, lib->data, lib->size, lib->path);
    while ((r = tgi_lex_line(&ml, o->p->err)) > 0) {
        if (!tgi_lex_token(&ml, &kw)) continue;
        if (tgi_tok_is(&kw, "newmtl")) {
            if (in_block) return 1;
            in_block = tgi_lex_rest(&ml, &rest) && rest.n == name->n &&
                       memcmp(rest.s, name->s, name->n) == 0;
        } else if (in_block && tgi_tok_is(&kw, "Kd")) {
            if (mtl_color(o, &ml, "Kd", 1, &m->albedo)) return -1;
        } else if (in_block && tgi_tok_is(&kw, "Ke")) {
            if (mtl_color(o, &ml, "Ke", 0, &m->emissive)) return -1;
        }
    }
    if (r < 0) return -1;
    return in_block;
}

/* Look `name` up in the mtllib files named so far; m starts as the mesh's
 * material and gets the MTL's Kd / Ke. */
static tg_status mtl_find(obj_state *o, const tgi_lexer *lx, const tgi_token *name, tgi_material *m)
{
    char buf[48];
    int i, r;
    for (i = 0; i < o->nlib; i++) {
        r = mtl_search(o, &o->lib[i], name, m);
        if (r < 0) return TG_ERR_INPUT;
        if (r > 0) return TG_OK;
    }
    if (o->nlib == 0)
        return ofail(o, lx, name->col, "'usemtl ", tgi_tok_str(name, buf),
                     "' but no 'mtllib' names an MTL file before it");
    return ofail(o, lx, name->col, "material '", tgi_tok_str(name, buf),
                 "' is not defined in the mtllib files");
}

static int same_vec(tg_vec3 a, tg_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
/* The same name and values (diffuse follows from albedo and f0: set when added) */
static int same_material(const tgi_material *a, const tgi_material *b)
{
    return strcmp(a->name, b->name) == 0 && same_vec(a->albedo, b->albedo) && a->f0 == b->f0
        && same_vec(a->emissive, b->emissive) && a->twosided == b->twosided;
}

static tg_status obj_usemtl(obj_state *o, tgi_lexer *lx, const tgi_token *kw)
{
    tgi_parser *p = o->p;
    tgi_token name;
    tgi_material m;
    tg_status st;
    char full[TG_MAX_NAME + 1];
    size_t n = strlen(o->objname), k, i;
    int index;
    if (!tgi_lex_rest(lx, &name))
        return ofail(o, lx, kw->col + 6, "'usemtl' expects a material name", NULL, NULL);
    if (!p->fill) {
        p->usemtl_bound++;
        memset(&m, 0, sizeof m);
        return mtl_find(o, lx, &name, &m);
    }
    /* "objname/mtlname", cut to the name limit */
    memcpy(full, o->objname, n);
    if (n < TG_MAX_NAME) full[n++] = '/';
    k = name.n < TG_MAX_NAME - n ? name.n : TG_MAX_NAME - n;
    memcpy(full + n, name.s, k);
    full[n + k] = '\0';
    m = p->scene->materials[o->base_material];
    memcpy(m.name, full, sizeof full);
    if ((st = mtl_find(o, lx, &name, &m))) return st;
    /* a material this OBJ added already is reused: the same name and the
     * same values.  The name alone is not enough: two MTL names cut to the
     * same prefix (a long object or MTL name) are two materials (they were
     * one, every face in the first's colour). */
    for (i = o->first_material; i < p->materials; i++)
        if (same_material(&p->scene->materials[i], &m)) {
            o->material = (int)i;
            return TG_OK;
        }
    if ((st = tgi_parse_add_material(p, lx, name.col, &m, &index))) return st;
    o->material = index;
    return TG_OK;
}

static tg_status obj_line(obj_state *o, tgi_lexer *lx, const tgi_token *kw)
{
    if (tgi_tok_is(kw, "v")) return obj_vertex(o, lx, kw, 0);
    if (tgi_tok_is(kw, "vn")) return obj_vertex(o, lx, kw, 1);
    if (tgi_tok_is(kw, "vt")) return obj_texcoord(o, lx);
    if (tgi_tok_is(kw, "f")) return obj_face(o, lx);
    if (tgi_tok_is(kw, "usemtl")) return obj_usemtl(o, lx, kw);
    if (tgi_tok_is(kw, "mtllib")) return obj_mtllib(o, lx, kw);
    return TG_OK; /* o, g, s, l, p, ...: ignored */
}

tg_status tgi_obj_mesh(tgi_parser *p, const tgi_lexer *lx, const tgi_token *path_tok,
                      const tgi_xform *xf, int material, const char *objname)
{
    char path[TG_MAX_PATH];
    const char *data;
    size_t size, tris0 = p->tris;
    obj_state o;
    tgi_lexer ol;
    tgi_token kw;
    tg_status st;
    int r;
    if ((st = load_file(p, lx->file, lx->lineno, path_tok, p->file, 0, path, &data, &size))) return st;
    memset(&o, 0, sizeof o);
    o.p = p;
    o.path = path;
    o.xf = xf;
    o.base_material = o.material = material;
    o.first_material = p->materials;
    o.objname = objname;
    tgi_lex_init(&ol, data, size, path);
    while ((r = tgi_lex_line(&ol, p->err)) > 0) {
        if (!tgi_lex_token(&ol, &kw)) continue;
        if ((st = obj_line(&o, &ol, &kw))) return st;
    }
    if (r < 0) return TG_ERR_INPUT;
    if (p->tris == tris0)
        return tgi_parse_fail(p, lx->file, lx->lineno, path_tok->col, "mesh file '", path,
                              "' has no faces; expected an OBJ file with 'v' and 'f' lines");
    if (!p->fill && o.nv + o.nvn > p->obj_scratch) p->obj_scratch = o.nv + o.nvn;
    return TG_OK;
}

#endif /* !TG_NO_OBJ && !TG_NO_SCENE_TEXT */
