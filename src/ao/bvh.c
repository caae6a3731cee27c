/* SPDX-License-Identifier: MIT */
/*
 * bvh.c - bounding-volume hierarchy over triangles for the ray-traced AO
 * reference: build (median split, deterministic, no recursion), closest-hit
 * and any-hit traversal (iterative, fixed stack), and the ray/triangle test.
 *
 * Fixed-point care:
 *  - slab tests use 1/d with |d| clamped to >= 2^-12; the boxes are
 *    enlarged by extent / 4096 so the clamped ray stays conservative;
 *  - the traversal's triangle test (tgi_bvh_tri_hit) uses triangles prepared
 *    at build time: unit plane normal, and dual vectors of the edges scaled
 *    by a power of two into [2, 4), so the barycentrics u = a . h, v = b . h
 *    keep ~17 bits whatever the triangle's size; per ray and triangle it is
 *    three dot products and one division;
 *  - the independent Moller-Trumbore test (tgi_ray_triangle, used by the
 *    tests as a check) first slides the origin along the ray to the point
 *    nearest vertex 0, then works in coordinates relative to vertex 0 scaled
 *    into [4, 8): every cross and triple product stays inside Q16.16.
 */
#include "bvh.h"
#include "../tinygi.h"

#if !TG_NO_REFERENCE /* the whole file is left out with TG_NO_REFERENCE=1 (tinygi.h "FEATURE SWITCHES") */

typedef struct bvh_task { int32_t node, begin, end; } bvh_task;

#define DIR_MIN TG_R(0.000244140625f)  /* 2^-12 */
#define EDGE_EPS TG_R(0.000244140625f) /* 2^-12 */

static size_t align16(size_t n) { return (n + 15u) & ~(size_t)15u; }

size_t tgi_bvh_bytes(int tri_count)
{
    size_t nodes, idx, tris, total;
    size_t n = tri_count > 0 ? (size_t)tri_count : 1u;
    if (tri_count < 0) return 0;
    if (tg_size_mul(2u * n, sizeof(tgi_bvh_node), &nodes)) return SIZE_MAX;
    if (tg_size_mul(n, sizeof(int32_t), &idx)) return SIZE_MAX;
    if (tg_size_mul(n, sizeof(tgi_bvh_tri), &tris)) return SIZE_MAX;
    if (tg_size_add(align16(nodes), align16(idx), &total)) return SIZE_MAX;
    if (tg_size_add(total, align16(tris), &total)) return SIZE_MAX;
    if (tg_size_add(total, 16u, &total)) return SIZE_MAX;
    return total;
}

/* Three times the centroid along an axis. */
static tg_real tri_key(const tg_vec3 *pos, int32_t tri, int axis)
{
    const tg_vec3 *v = pos + 3 * (size_t)tri;
    if (axis == 0) return tg_add(tg_add(v[0].x, v[1].x), v[2].x);
    if (axis == 1) return tg_add(tg_add(v[0].y, v[1].y), v[2].y);
    return tg_add(tg_add(v[0].z, v[1].z), v[2].z);
}

/* Strict total order: key, then triangle index (determinism). */
static int tri_less(const tg_vec3 *pos, int32_t a, int32_t b, int axis)
{
    tg_real ka = tri_key(pos, a, axis), kb = tri_key(pos, b, axis);
    return ka < kb || (ka == kb && a < b);
}

static void swap_i32(int32_t *a, int32_t *b) { int32_t t = *a; *a = *b; *b = t; }

/* Quickselect: put the k-th smallest of idx[lo, hi) at k, smaller before it. */
static void select_kth(const tg_vec3 *pos, int32_t *idx, int lo, int hi, int k, int axis)
{
    while (hi - lo > 1) {
        int mid = lo + (hi - lo) / 2, i, store;
        int32_t p;
        /* median of three as the pivot, moved to hi - 1 */
        if (tri_less(pos, idx[mid], idx[lo], axis)) swap_i32(&idx[mid], &idx[lo]);
        if (tri_less(pos, idx[hi - 1], idx[lo], axis)) swap_i32(&idx[hi - 1], &idx[lo]);
        if (tri_less(pos, idx[mid], idx[hi - 1], axis)) swap_i32(&idx[mid], &idx[hi - 1]);
        p = idx[hi - 1];
        for (i = store = lo; i < hi - 1; i++)
            if (tri_less(pos, idx[i], p, axis)) swap_i32(&idx[i], &idx[store++]);
        swap_i32(&idx[store], &idx[hi - 1]);
        if (k == store) return;
        if (k < store) hi = store; else lo = store + 1;
    }
}

static void bounds_of(const tgi_bvh *b, int begin, int end, tg_vec3 *lo, tg_vec3 *hi,
                      tg_vec3 *clo, tg_vec3 *chi)
{
    int i, j;
    *lo = *clo = tg_v3(TG_REAL_MAX, TG_REAL_MAX, TG_REAL_MAX);
    *hi = *chi = tg_v3(TG_REAL_MIN, TG_REAL_MIN, TG_REAL_MIN);
    for (i = begin; i < end; i++) {
        int32_t t = b->tri_index[i];
        const tg_vec3 *v = b->tri_pos + 3 * (size_t)t;
        tg_vec3 c = tg_v3(tri_key(b->tri_pos, t, 0), tri_key(b->tri_pos, t, 1), tri_key(b->tri_pos, t, 2));
        for (j = 0; j < 3; j++) {
            lo->x = tg_min(lo->x, v[j].x); lo->y = tg_min(lo->y, v[j].y); lo->z = tg_min(lo->z, v[j].z);
            hi->x = tg_max(hi->x, v[j].x); hi->y = tg_max(hi->y, v[j].y); hi->z = tg_max(hi->z, v[j].z);
        }
        clo->x = tg_min(clo->x, c.x); clo->y = tg_min(clo->y, c.y); clo->z = tg_min(clo->z, c.z);
        chi->x = tg_max(chi->x, c.x); chi->y = tg_max(chi->y, c.y); chi->z = tg_max(chi->z, c.z);
    }
}

int tgi_bvh_build(tgi_bvh *bvh, const tg_vec3 *tri_pos, int tri_count, void *memory, size_t size)
{
    bvh_task stack[TG_BVH_STACK];
    int sp = 0, i;
    tg_real margin = 0;
    uintptr_t base = (uintptr_t)memory;
    size_t need = tgi_bvh_bytes(tri_count), n = tri_count > 0 ? (size_t)tri_count : 1u;
    if (tri_count < 0 || need == 0 || size < need || !memory) return -1;
    base = (base + 15u) & ~(uintptr_t)15u;
    bvh->nodes = (tgi_bvh_node *)base;
    bvh->tri_index = (int32_t *)(base + align16(2u * n * sizeof(tgi_bvh_node)));
    bvh->tris = (tgi_bvh_tri *)((uintptr_t)bvh->tri_index + align16(n * sizeof(int32_t)));
    bvh->tri_pos = tri_pos;
    bvh->tri_count = tri_count;
    bvh->node_count = 0;
    if (tri_count == 0) return 0;
    for (i = 0; i < tri_count; i++) bvh->tri_index[i] = i;
    bvh->node_count = 1;
    stack[sp].node = 0; stack[sp].begin = 0; stack[sp].end = tri_count; sp++;
    while (sp > 0) {
        bvh_task task = stack[--sp];
        tgi_bvh_node *node = &bvh->nodes[task.node];
        tg_vec3 lo, hi, clo, chi, ext;
        int axis, mid;
        bounds_of(bvh, task.begin, task.end, &lo, &hi, &clo, &chi);
        if (task.node == 0) { /* one margin for the whole tree, from the scene extent */
            tg_real e = tg_max(tg_max(tg_sub(hi.x, lo.x), tg_sub(hi.y, lo.y)), tg_sub(hi.z, lo.z));
            margin = tg_add(tg_ldexp(e, -12), TG_R(0.0001f));
        }
        node->lo = tg_v3(tg_sub(lo.x, margin), tg_sub(lo.y, margin), tg_sub(lo.z, margin));
        node->hi = tg_v3(tg_add(hi.x, margin), tg_add(hi.y, margin), tg_add(hi.z, margin));
        if (task.end - task.begin <= TG_BVH_LEAF_MAX || sp + 2 > TG_BVH_STACK) {
            node->first = task.begin;
            node->count = task.end - task.begin;
            continue;
        }
        ext = tgi_v3_sub(chi, clo);
        axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
        mid = task.begin + (task.end - task.begin) / 2;
        select_kth(tri_pos, bvh->tri_index, task.begin, task.end, mid, axis);
        node->first = bvh->node_count;
        node->count = 0;
        bvh->node_count += 2;
        stack[sp].node = node->first + 1; stack[sp].begin = mid; stack[sp].end = task.end; sp++;
        stack[sp].node = node->first; stack[sp].begin = task.begin; stack[sp].end = mid; sp++;
    }
    for (i = 0; i < tri_count; i++)
        tgi_bvh_tri_prepare(&bvh->tris[i], tri_pos + 3 * (size_t)bvh->tri_index[i]);
    return 0;
}

/* ---- ray / triangle (Moller-Trumbore in scaled relative coordinates) ---- */

static tg_real bvh_max_abs3(tg_vec3 a) { return tg_max(tg_max(tg_abs(a.x), tg_abs(a.y)), tg_abs(a.z)); }

int tgi_ray_triangle(const tg_vec3 *v, tg_vec3 o, tg_vec3 d, tg_real tmax,
                    tg_real *t_out, tg_real *u_out, tg_real *w_out)
{
    tg_vec3 e1 = tgi_v3_sub(v[1], v[0]), e2 = tgi_v3_sub(v[2], v[0]), s, p, q;
    tg_real emax = tg_max(bvh_max_abs3(e1), bvh_max_abs3(e2)), m, det, uu, ww, tt, t;
    tg_real t_shift = tg_max(tgi_v3_dot(tgi_v3_sub(v[0], o), d), 0);
    int k = 0, neg;
    /* slide the origin to the ray point nearest vertex 0: a hit then lies
     * within one edge length of it, so |s| <= |hit - v0| <= sqrt(3) emax */
    s = tgi_v3_sub(tgi_v3_add(o, tgi_v3_scale(d, t_shift)), v[0]);
    m = bvh_max_abs3(s);
    if (emax <= 0 || m > tg_add(tg_ldexp(emax, 1), TG_R(0.0001f))) return 0;
    m = tg_max(m, emax);
    while (m < TG_R(4.0f) && k < 24) { m = tg_ldexp(m, 1); k++; }
    while (m >= TG_R(8.0f) && k > -24) { m = tg_ldexp(m, -1); k--; }
    e1 = tg_v3(tg_ldexp(e1.x, k), tg_ldexp(e1.y, k), tg_ldexp(e1.z, k));
    e2 = tg_v3(tg_ldexp(e2.x, k), tg_ldexp(e2.y, k), tg_ldexp(e2.z, k));
    s = tg_v3(tg_ldexp(s.x, k), tg_ldexp(s.y, k), tg_ldexp(s.z, k));
    p = tgi_v3_cross(d, e2);
    det = tgi_v3_dot(e1, p);
    neg = det < 0;
    if (neg) det = tg_neg(det);
    if (det <= TG_R(0.0001f)) return 0;        /* ray parallel to the plane */
    uu = tgi_v3_dot(s, p);
    if (neg) uu = tg_neg(uu);
    if (uu < 0 || uu > det) return 0;
    q = tgi_v3_cross(s, e1);
    ww = tgi_v3_dot(d, q);
    if (neg) ww = tg_neg(ww);
    if (ww < 0 || tg_add(uu, ww) > det) return 0;
    tt = tgi_v3_dot(e2, q);
    if (neg) tt = tg_neg(tt);
    t = tg_add(t_shift, tg_ldexp(tg_div(tt, det), -k));
    if (t <= 0 || t >= tmax) return 0;
    *t_out = t;
    *u_out = tg_div(uu, det);
    *w_out = tg_div(ww, det);
    return 1;
}

/* ---- prepared triangles: plane, then dual-vector barycentrics ---- */

static tg_vec3 v3_ldexp(tg_vec3 a, int k) { return tg_v3(tg_ldexp(a.x, k), tg_ldexp(a.y, k), tg_ldexp(a.z, k)); }

void tgi_bvh_tri_prepare(tgi_bvh_tri *tr, const tg_vec3 *v)
{
    tg_vec3 e1 = tgi_v3_sub(v[1], v[0]), e2 = tgi_v3_sub(v[2], v[0]), nn, a, b;
    tg_real m = tg_max(bvh_max_abs3(e1), bvh_max_abs3(e2)), len2;
    int k = 0;
    tr->v0 = v[0];
    tr->n = tr->a = tr->b = tg_v3(0, 0, 0);
    tr->k = 0;
    if (m <= 0) return;
    while (m < TG_R(2.0f) && k < 24) { m = tg_ldexp(m, 1); k++; }
    while (m >= TG_R(4.0f) && k > -24) { m = tg_ldexp(m, -1); k--; }
    e1 = v3_ldexp(e1, k);
    e2 = v3_ldexp(e2, k);
    nn = tgi_v3_cross(e1, e2);                  /* |nn| <= 48: |nn|^2 fits Q16.16 */
    len2 = tgi_v3_dot(nn, nn);
    if (len2 <= TG_R(0.0001f)) return;         /* degenerate: never hit */
    tr->n = tgi_v3_scale(nn, tg_rsqrt(len2));
    a = tgi_v3_cross(e2, nn);                   /* a . e1 = |nn|^2, a . e2 = 0 */
    b = tgi_v3_cross(nn, e1);                   /* b . e2 = |nn|^2, b . e1 = 0 */
    /* divide each component (not times 1/len2: that would keep few bits in Q16.16) */
    tr->a = tg_v3(tg_div(a.x, len2), tg_div(a.y, len2), tg_div(a.z, len2));
    tr->b = tg_v3(tg_div(b.x, len2), tg_div(b.y, len2), tg_div(b.z, len2));
    tr->k = k;
}

int tgi_bvh_tri_hit(const tgi_bvh_tri *tr, tg_vec3 o, tg_vec3 d, tg_real tmax,
                   tg_real *t_out, tg_real *u_out, tg_real *w_out)
{
    tg_real nd = tgi_v3_dot(tr->n, d), t, u, w;
    tg_vec3 ov = tgi_v3_sub(o, tr->v0), h;
    if (tg_abs(nd) <= TG_R(0.0001f)) return 0;  /* parallel (or degenerate: n = 0) */
    t = tg_div(tg_neg(tgi_v3_dot(tr->n, ov)), nd);  /* the plane */
    if (t <= 0 || t >= tmax) return 0;
    h = v3_ldexp(tgi_v3_add(ov, tgi_v3_scale(d, t)), tr->k);   /* hit - v0, scaled like the edges */
    /* edges widened by 2^-12 of the triangle: neighbours sharing an edge
     * overlap a hair instead of letting rounding open a crack (a ray through
     * a crack would see the sky from inside a closed box) */
    u = tgi_v3_dot(tr->a, h);
    if (u < tg_neg(EDGE_EPS) || u > TG_R(1.000244140625f)) return 0;
    w = tgi_v3_dot(tr->b, h);
    if (w < tg_neg(EDGE_EPS) || tg_add(u, w) > TG_R(1.000244140625f)) return 0;
    u = tg_saturate(u);
    w = tg_min(tg_saturate(w), tg_sub(TG_ONE, u));
    *t_out = t; *u_out = u; *w_out = w;
    return 1;
}

/* ---- traversal ---- */

typedef struct bvh_ray { tg_vec3 o, d, inv; } bvh_ray;

static tg_real safe_inv(tg_real c)
{
    if (tg_abs(c) < DIR_MIN) c = c < 0 ? tg_neg(DIR_MIN) : DIR_MIN;
    return tg_div(TG_ONE, c);
}

static bvh_ray ray_make(tg_vec3 o, tg_vec3 d)
{
    bvh_ray r;
    r.o = o; r.d = d;
    r.inv = tg_v3(safe_inv(d.x), safe_inv(d.y), safe_inv(d.z));
    return r;
}

static int slab(tg_real lo, tg_real hi, tg_real o, tg_real inv, tg_real *tn, tg_real *tf)
{
    tg_real t0 = tg_mul(tg_sub(lo, o), inv), t1 = tg_mul(tg_sub(hi, o), inv);
    if (t0 > t1) { tg_real t = t0; t0 = t1; t1 = t; }
    if (t0 > *tn) *tn = t0;
    if (t1 < *tf) *tf = t1;
    return *tn <= *tf;
}

/* Entry distance of the ray into the node's box, or -1 if missed before tmax. */
static tg_real box_entry(const tgi_bvh_node *n, const bvh_ray *r, tg_real tmax)
{
    tg_real tn = 0, tf = tmax;
    if (!slab(n->lo.x, n->hi.x, r->o.x, r->inv.x, &tn, &tf)) return -1;
    if (!slab(n->lo.y, n->hi.y, r->o.y, r->inv.y, &tn, &tf)) return -1;
    if (!slab(n->lo.z, n->hi.z, r->o.z, r->inv.z, &tn, &tf)) return -1;
    return tn;
}

/* Walk the tree for the ray o + t d, t in [0, hit->t): every hit nearer
 * than the nearest so far goes into *hit, children nearer first; with
 * any_hit the first hit found ends the walk (children in tree order).
 * 1 when it hit. */
static inline int bvh_walk(const tgi_bvh *bvh, tg_vec3 o, tg_vec3 d, int any_hit, tgi_ray_hit *hit)
{
    int32_t stack[TG_BVH_STACK];
    int sp = 0;
    bvh_ray r = ray_make(o, d);
    if (bvh->node_count == 0 || box_entry(&bvh->nodes[0], &r, hit->t) < 0) return 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const tgi_bvh_node *n = &bvh->nodes[stack[--sp]];
        if (n->count > 0) {
            int i;
            for (i = 0; i < n->count; i++) {
                tg_real t, u, w;
                if (tgi_bvh_tri_hit(&bvh->tris[n->first + i], o, d, hit->t, &t, &u, &w)) {
                    if (any_hit) return 1;
                    hit->t = t; hit->u = u; hit->v = w; hit->tri = bvh->tri_index[n->first + i];
                }
            }
        } else if (any_hit) {
            if (box_entry(&bvh->nodes[n->first], &r, hit->t) >= 0) stack[sp++] = n->first;
            if (box_entry(&bvh->nodes[n->first + 1], &r, hit->t) >= 0) stack[sp++] = n->first + 1;
        } else {
            tg_real ta = box_entry(&bvh->nodes[n->first], &r, hit->t);
            tg_real tb = box_entry(&bvh->nodes[n->first + 1], &r, hit->t);
            int32_t a = n->first, b = n->first + 1;
            if (ta >= 0 && tb >= 0 && tb < ta) { int32_t x = a; a = b; b = x; }
            /* push the farther first so the nearer is visited first */
            if (ta >= 0 && tb >= 0) { stack[sp++] = b; stack[sp++] = a; }
            else if (ta >= 0) stack[sp++] = a;
            else if (tb >= 0) stack[sp++] = b;
        }
    }
    return hit->tri >= 0;
}

int tgi_bvh_closest(const tgi_bvh *bvh, tg_vec3 o, tg_vec3 d, tg_real tmax, tgi_ray_hit *hit)
{
    hit->t = tmax; hit->u = hit->v = 0; hit->tri = -1;
    return bvh_walk(bvh, o, d, 0, hit);
}

int tgi_bvh_occluded(const tgi_bvh *bvh, tg_vec3 o, tg_vec3 d, tg_real tmax)
{
    tgi_ray_hit hit;
    hit.t = tmax; hit.u = hit.v = 0; hit.tri = -1;
    return bvh_walk(bvh, o, d, 1, &hit);
}

/* The ray's start off the surface: what the plane tests against a
 * triangle (n . (o - v0), a unit normal times a distance within the
 * triangle, at most the scene's extent) and the point's own
 * reconstruction may err by.  Q16.16 holds every coordinate to 2^-16
 * wherever it lies and a unit normal in 16 bits: 2^-14 of the scene's
 * extent (the BVH's root box).  Float holds 24 bits of each coordinate:
 * 2^-19 of the point's coordinates.  (Both took 2^-14 of the point's
 * coordinates: 2.4 units at 20000 from the origin, over a 2-unit box,
 * whose shadow vanished; test_shadow_plan rays_far_from_the_origin.) */
#if TG_FIXED
#define SHADOW_EPS_REL TG_R(0.00006103515625f) /* 2^-14 */
#else
#define SHADOW_EPS_REL TG_R(0.0000019073486328125f) /* 2^-19 */
#endif
#define SHADOW_EPS_ULPS 8

/* What SHADOW_EPS_REL is relative to (plus a unit). */
static tg_real shadow_eps_scale(const tgi_bvh *bvh, tg_vec3 p)
{
#if TG_FIXED
    const tgi_bvh_node *root = &bvh->nodes[0];
    (void)p;
    return tg_add(tg_max(tg_max(tg_sub(root->hi.x, root->lo.x), tg_sub(root->hi.y, root->lo.y)),
                         tg_sub(root->hi.z, root->lo.z)), TG_ONE);
#else
    (void)bvh;
    return tg_add(tg_add(tg_add(tg_abs(p.x), tg_abs(p.y)), tg_abs(p.z)), TG_ONE);
#endif
}

tg_real tgi_bvh_light_visibility(const void *tracer, const tgi_light *l, tg_vec3 p, tg_vec3 n, tg_real err)
{
    const tgi_bvh *bvh = (const tgi_bvh *)tracer;
    tg_real eps, tmax;
    tg_vec3 o, d;
    if (bvh->node_count == 0) return TG_ONE;
    eps = tg_add(tg_mul(shadow_eps_scale(bvh, p), SHADOW_EPS_REL), SHADOW_EPS_ULPS * TG_EPS);
    o = tgi_v3_add(p, tgi_v3_scale(n, tg_add(tg_max(err, 0), eps)));
    if (l->type == TG_LIGHT_DIRECTIONAL) {
        /* out of the root box: |o - centre| + its half diagonal, and a unit */
        const tgi_bvh_node *root = &bvh->nodes[0];
        tg_vec3 c = tgi_v3_scale(tgi_v3_add(root->lo, root->hi), TG_R(0.5f));
        d = tgi_v3_neg(tgi_v3_normalize_or(l->dir, tg_v3(0, tg_neg(TG_ONE), 0)));
        tmax = tg_add(tg_add(tgi_v3_length(tgi_v3_sub(o, c)), tgi_v3_length(tgi_v3_sub(root->hi, c))), TG_ONE);
    } else {
        d = tgi_v3_sub(l->pos, o);
        tmax = tg_sub(tgi_v3_length(d), eps);
        if (tmax <= 0) return TG_ONE;
        d = tgi_v3_normalize(d);
    }
    return tgi_bvh_occluded(bvh, o, d, tmax) ? 0 : TG_ONE;
}

#endif /* !TG_NO_REFERENCE */
