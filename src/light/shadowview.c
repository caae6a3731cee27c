/* SPDX-License-Identifier: MIT */
/*
 * shadowview.c - the shadow size rule and face culling for a view (convex
 * regions by polygon clipping, projected areas by the shoelace formula),
 * the bounds of an animation, and the choice between shadow maps and
 * shadow rays.  See shadowview.h.
 */
#include <string.h>
#include "shadowview.h"
#include "../scene/anim.h"
#include "../core/text.h"

#if !TG_NO_SHADOW_MAPS /* the whole file is left out with TG_NO_SHADOW_MAPS=1 (tinygi.h "FEATURE SWITCHES") */

#define POLY_MAX 24                    /* a quad or triangle cut by up to 17 planes */
#define APEX_NEAR TG_R(0.001f)         /* the lookup's own nearest distance (lit nearer) */
#define PLANE_MAX_TAN TG_R(1.5f)       /* light-plane coordinates kept within 1.5 x the face */
#define CLIP_SLACK (16 * TG_EPS)       /* the clipping's own rounding */
/* A function whose locals stay out of its caller's stack frame, so that
 * they are not on the stack while the caller's other callees run (the
 * plan runs on the smallest cores' stacks: README "Porting"). */
#if defined(__GNUC__)
#define APART __attribute__((noinline))
#else
#define APART
#endif

/* Inside: n . p + d >= -margin. */
typedef struct halfspace { tg_vec3 n; tg_real d; } halfspace;

/* A convex hexahedron: corner k has bit 0 = the +x side, bit 1 = +y, bit 2 =
 * +z (of its own frame); h[] = the half-spaces -x +x -y +y -z +z. */
typedef struct hexa { tg_vec3 c[8]; halfspace h[6]; } hexa;

static tg_vec3 corner(tg_vec3 lo, tg_vec3 hi, int k)
{
    return tg_v3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
}

static halfspace plane(tg_vec3 n, tg_vec3 through)
{
    halfspace h;
    h.n = n;
    h.d = tg_neg(tgi_v3_dot(n, through));
    return h;
}

static void hexa_box(hexa *x, tg_vec3 lo, tg_vec3 hi)
{
    int k;
    for (k = 0; k < 8; k++) x->c[k] = corner(lo, hi, k);
    x->h[0] = plane(tg_v3(TG_ONE, 0, 0), lo); x->h[1] = plane(tg_v3(-TG_ONE, 0, 0), hi);
    x->h[2] = plane(tg_v3(0, TG_ONE, 0), lo); x->h[3] = plane(tg_v3(0, -TG_ONE, 0), hi);
    x->h[4] = plane(tg_v3(0, 0, TG_ONE), lo); x->h[5] = plane(tg_v3(0, 0, -TG_ONE), hi);
}

/* The frustum |x| <= z tx, |y| <= z ty, znear <= z <= zfar of the frame
 * (o; r, u, f), its side and far planes moved out by `grow` (world units):
 * |x| <= (z + ax) tx with ax = grow sqrt(1 + tx^2) / tx, the same in y,
 * z <= zfar + grow.  Still a hexahedron with planar faces. */
static void hexa_frustum(hexa *x, tg_vec3 o, tg_vec3 r, tg_vec3 u, tg_vec3 f, tg_real tx, tg_real ty,
                         tg_real znear, tg_real zfar, tg_real grow)
{
    tg_real lx = tg_sqrt(tg_add(TG_ONE, tg_mul(tx, tx))), ly = tg_sqrt(tg_add(TG_ONE, tg_mul(ty, ty)));
    tg_real ax = tg_div(tg_mul(grow, lx), tx), ay = tg_div(tg_mul(grow, ly), ty);
    tg_vec3 ftx = tgi_v3_scale(f, tx), fty = tgi_v3_scale(f, ty);
    tg_vec3 ox = tgi_v3_sub(o, tgi_v3_scale(f, ax)), oy = tgi_v3_sub(o, tgi_v3_scale(f, ay));
    int k;
    zfar = tg_add(zfar, grow);
    for (k = 0; k < 8; k++) {
        tg_real z = (k & 4) ? zfar : znear;
        tg_real hx = tg_mul(tg_add(z, ax), tx), hy = tg_mul(tg_add(z, ay), ty);
        tg_vec3 p = tgi_v3_add(o, tgi_v3_scale(f, z));
        p = tgi_v3_add(p, tgi_v3_scale(r, (k & 1) ? hx : tg_neg(hx)));
        x->c[k] = tgi_v3_add(p, tgi_v3_scale(u, (k & 2) ? hy : tg_neg(hy)));
    }
    /* the side planes through the apexes moved back by ax (x) and ay (y) */
    x->h[0] = plane(tgi_v3_scale(tgi_v3_add(ftx, r), tg_div(TG_ONE, lx)), ox);  /* x >= -(z + ax) tx */
    x->h[1] = plane(tgi_v3_scale(tgi_v3_sub(ftx, r), tg_div(TG_ONE, lx)), ox);  /* x <= (z + ax) tx */
    x->h[2] = plane(tgi_v3_scale(tgi_v3_add(fty, u), tg_div(TG_ONE, ly)), oy);
    x->h[3] = plane(tgi_v3_scale(tgi_v3_sub(fty, u), tg_div(TG_ONE, ly)), oy);
    x->h[4] = plane(f, tgi_v3_add(o, tgi_v3_scale(f, znear)));
    x->h[5] = plane(tgi_v3_neg(f), tgi_v3_add(o, tgi_v3_scale(f, zfar)));
}

/* Cut the convex polygon p[0..n) by half-spaces h[0..count) grown by
 * margin (Sutherland-Hodgman); returns the vertices left. */
static int clip(tg_vec3 *p, int n, const halfspace *h, int count, tg_real margin)
{
    tg_vec3 tmp[POLY_MAX];
    tg_real dist[POLY_MAX];   /* each vertex's signed distance, once: an edge's end is the next one's start */
    int k, i;
    for (k = 0; k < count && n > 0; k++) {
        int m = 0;
        for (i = 0; i < n; i++) dist[i] = tg_add(tg_add(tgi_v3_dot(h[k].n, p[i]), h[k].d), margin);
        for (i = 0; i < n; i++) {
            const int j = i + 1 == n ? 0 : i + 1;
            tg_vec3 a = p[i], b = p[j];
            tg_real da = dist[i], db = dist[j];
            if (da >= 0 && m < POLY_MAX) tmp[m++] = a;
            if ((da >= 0) != (db >= 0) && m < POLY_MAX)
                tmp[m++] = tgi_v3_lerp(a, b, tg_clamp(tg_div(da, tg_sub(da, db)), 0, TG_ONE));
        }
        n = m;
        memcpy(p, tmp, (size_t)n * sizeof *p);
    }
    return n;
}

/* ---- projections onto the image and the light plane ---- */

/* What one face of the light sees: its frame and how a point maps onto its
 * light plane (x/z, y/z; or, directional, the light basis's x, y relative
 * to `origin`, times `scale`). */
typedef struct light_face {
    int perspective;
    tg_vec3 o, r, u, f;
    tg_real tan_nominal, scale;
    hexa pyramid;                      /* perspective: the face's region from APEX_NEAR to the far bound */
} light_face;

static void light_plane(const light_face *lf, tg_vec3 p, tg_real *x, tg_real *y)
{
    tg_vec3 d = tgi_v3_sub(p, lf->o);
    tg_real lim;
    if (!lf->perspective) {
        *x = tg_mul(tgi_v3_dot(d, lf->r), lf->scale);
        *y = tg_mul(tgi_v3_dot(d, lf->u), lf->scale);
        return;
    }
    {
        tg_real inv = tg_div(TG_ONE, tg_max(tgi_v3_dot(d, lf->f), APEX_NEAR));
        lim = tg_mul(lf->tan_nominal, PLANE_MAX_TAN);
        *x = tg_clamp(tg_mul(tgi_v3_dot(d, lf->r), inv), tg_neg(lim), lim);
        *y = tg_clamp(tg_mul(tgi_v3_dot(d, lf->u), inv), tg_neg(lim), lim);
    }
}

static void image_plane(const tgi_view *v, tg_vec3 p, tg_real *x, tg_real *y)
{
    tg_vec3 d = tgi_v3_sub(p, v->eye);
    tg_real inv = tg_div(TG_ONE, tg_max(tgi_v3_dot(d, v->forward), tg_ldexp(v->znear, -1)));
    *x = tg_clamp(tg_mul(tg_mul(tgi_v3_dot(d, v->right), v->focal_x), inv), TG_R(-2.0f), TG_R(2.0f));
    *y = tg_clamp(tg_mul(tg_mul(tgi_v3_dot(d, v->up), v->focal_y), inv), TG_R(-2.0f), TG_R(2.0f));
}

/* Twice the signed area of a projected polygon (shoelace, about its first
 * vertex), a vertex at a time: no arrays of the polygon's projections on
 * the stack. */
typedef struct shoelace { tg_real x0, y0, px, py, s; } shoelace;

static void shoelace_add(shoelace *sl, int i, tg_real x, tg_real y)
{
    if (i == 0) {
        sl->x0 = x; sl->y0 = y; sl->s = 0;
    } else if (i > 1) {
        tg_real ax = tg_sub(sl->px, sl->x0), ay = tg_sub(sl->py, sl->y0);
        tg_real bx = tg_sub(x, sl->x0), by = tg_sub(y, sl->y0);
        sl->s = tg_add(sl->s, tg_sub(tg_mul(ax, by), tg_mul(ay, bx)));
    }
    sl->px = x; sl->py = y;
}

/* A polygon's areas: on the image (NDC units^2) and on the light plane. */
static void areas(const tgi_view *v, const light_face *lf, const tg_vec3 *p, int n,
                  tg_real *cam, tg_real *light)
{
    shoelace c, l;
    int i;
    c.s = l.s = 0;
    for (i = 0; i < n; i++) {
        tg_real x, y;
        image_plane(v, p[i], &x, &y);
        shoelace_add(&c, i, x, y);
        light_plane(lf, p[i], &x, &y);
        shoelace_add(&l, i, x, y);
    }
    *cam = tg_add(*cam, tg_ldexp(tg_abs(c.s), -1));
    *light = tg_add(*light, tg_ldexp(tg_abs(l.s), -1));
}

/* ---- the region of one face ---- */

/* What the region's boundary adds up: seen, the window, the volume's areas. */
typedef struct region {
    int seen;
    tg_real w[4];
    tg_real cam, light;
} region;

static void region_add(region *rg, const tgi_view *v, const light_face *lf, const tg_vec3 *p, int n)
{
    int i;
    for (i = 0; i < n; i++) {
        tg_real x, y;
        light_plane(lf, p[i], &x, &y);
        if (!rg->seen) { rg->w[0] = rg->w[2] = x; rg->w[1] = rg->w[3] = y; }
        rg->seen = 1;
        rg->w[0] = tg_min(rg->w[0], x); rg->w[2] = tg_max(rg->w[2], x);
        rg->w[1] = tg_min(rg->w[1], y); rg->w[3] = tg_max(rg->w[3], y);
    }
    areas(v, lf, p, n, &rg->cam, &rg->light);
}

/* The boundary of the intersection of hexahedra hx[0..count): each one's
 * faces cut by the others' half-spaces (grown by margin); every piece left
 * goes to the region.  Exact for convex hexahedra: the intersection is
 * empty exactly when no piece is left.  p: room for a polygon (POLY_MAX). */
static void intersect(region *rg, const hexa *const *hx, int count, tg_real margin,
                      const tgi_view *v, const light_face *lf, tg_vec3 *p)
{
    int a, b, face;
    for (a = 0; a < count; a++)
        for (face = 0; face < 6; face++) {
            int axis = face >> 1, side = face & 1, ua = (axis + 1) % 3, wa = (axis + 2) % 3, n = 4, k;
            static const int su[4] = { 0, 1, 1, 0 }, sw[4] = { 0, 0, 1, 1 };
            for (k = 0; k < 4; k++) p[k] = hx[a]->c[(side << axis) | (su[k] << ua) | (sw[k] << wa)];
            for (b = 0; b < count && n > 0; b++)
                if (b != a) n = clip(p, n, hx[b]->h, 6, margin);
            if (n > 0) region_add(rg, v, lf, p, n);
        }
}

/* ---- the rule ---- */

/* The camera's frustum, its far side cut at the bounds' farthest corner;
 * 0 when the bounds lie wholly behind its near plane. */
static int camera_hexa(hexa *x, const tgi_view *v, tg_vec3 lo, tg_vec3 hi, tg_real margin)
{
    tg_real zfar = 0, tx = tg_div(TG_ONE, v->focal_x), ty = tg_div(TG_ONE, v->focal_y);
    int k;
    for (k = 0; k < 8; k++) zfar = tg_max(zfar, tgi_v3_dot(tgi_v3_sub(corner(lo, hi, k), v->eye), v->forward));
    zfar = tg_min(tg_add(zfar, margin), v->zfar);
    if (zfar <= v->znear) return 0;
    hexa_frustum(x, v->eye, v->right, v->up, v->forward, tx, ty, v->znear, zfar, margin);
    return 1;
}

/* (lo + hi) / 2 and a triangle's centroid, the sums in tgi_wide (core/real.h:
 * tgi_v3_add and tgi_v3_scale's result where they do not saturate): in
 * Q16.16 the sums of a scene past 16384 (10922) units from the origin
 * saturated, and a ground at x = 30000 was measured about x = 16384, its
 * light-plane area rounded to 0 (an 8-texel map), its faces' sides wrong. */
static tg_vec3 mid_point(tg_vec3 lo, tg_vec3 hi)
{
    return tg_v3((tg_real)tgi_wide_mul((tgi_wide)lo.x + hi.x, TG_R(0.5f)), (tg_real)tgi_wide_mul((tgi_wide)lo.y + hi.y, TG_R(0.5f)),
                 (tg_real)tgi_wide_mul((tgi_wide)lo.z + hi.z, TG_R(0.5f)));
}
static tg_vec3 centroid(const tg_vec3 *t)
{
    const tg_real third = TG_R(1.0f / 3.0f);
    return tg_v3((tg_real)tgi_wide_mul((tgi_wide)t[0].x + t[1].x + t[2].x, third),
                 (tg_real)tgi_wide_mul((tgi_wide)t[0].y + t[1].y + t[2].y, third),
                 (tg_real)tgi_wide_mul((tgi_wide)t[0].z + t[1].z + t[2].z, third));
}

static void light_face_make(light_face *lf, const tgi_light *l, int face, tg_vec3 lo, tg_vec3 hi, tg_real margin)
{
    tg_real zfar = 0;
    int k;
    memset(lf, 0, sizeof *lf);
    lf->f = tgi_shadow_face_axis(l, face);
    tgi_shadow_basis(lf->f, &lf->r, &lf->u);
    lf->perspective = l->type != TG_LIGHT_DIRECTIONAL;
    lf->tan_nominal = tgi_shadow_nominal_tan(l);
    if (!lf->perspective) {
        /* light-plane coordinates about the bounds' centre, scaled to about 1 */
        tg_vec3 c = mid_point(lo, hi);
        lf->o = c;
        lf->scale = tg_div(TG_ONE, tg_max(tgi_v3_length(tgi_v3_sub(hi, c)), TG_R(0.001f)));
        return;
    }
    lf->o = l->pos;
    for (k = 0; k < 8; k++) zfar = tg_max(zfar, tgi_v3_dot(tgi_v3_sub(corner(lo, hi, k), lf->o), lf->f));
    hexa_frustum(&lf->pyramid, lf->o, lf->r, lf->u, lf->f, lf->tan_nominal, lf->tan_nominal,
                 APEX_NEAR, tg_max(zfar, tg_ldexp(APEX_NEAR, 1)), margin);
}

/* Facing both the camera and the light (the side the camera sees is the lit one). */
static int lit_and_seen(const tgi_light *l, const tgi_view *v, const tg_vec3 *t)
{
    tg_vec3 n, c = centroid(t);
    tg_real to_eye, to_light;
    if (!tgi_face_normal(t[0], t[1], t[2], &n)) return 0;
    to_eye = tgi_v3_dot(n, tgi_v3_sub(v->eye, c));
    to_light = l->type == TG_LIGHT_DIRECTIONAL ? tg_neg(tgi_v3_dot(n, l->dir)) : tgi_v3_dot(n, tgi_v3_sub(l->pos, c));
    return (to_eye > 0 && to_light > 0) || (to_eye < 0 && to_light < 0);
}

/* The triangles' areas on one face: cut to the frustum (and the face's
 * pyramid, both grown by the margin), projected on the image and the light
 * plane, for the triangles facing the camera and the light.  Every
 * triangle that leaves a piece, whichever way it faces (a shading normal
 * may face the light when the triangle does not), sets *hit.  Returns 1
 * when every triangle was visited (*hit is then exact).  p: room for a
 * polygon (POLY_MAX). */
static int triangle_areas(region *rg, int *hit, const light_face *lf, const tgi_light *l,
                          const tgi_view *v, const hexa *cam, const tg_vec3 *pos, int tri_count, tg_vec3 *p)
{
    int stride = tri_count / TG_SHADOW_RULE_TRIANGLES + 1, t;
    if (!rg->seen) return stride == 1;
    for (t = 0; t < tri_count; t += stride) {
        int n;
        memcpy(p, pos + 3 * (size_t)t, 3 * sizeof *p);
        n = clip(p, 3, cam->h, 6, CLIP_SLACK);
        if (n > 0 && lf->perspective) n = clip(p, n, lf->pyramid.h, 6, CLIP_SLACK);
        if (n == 0) continue;
        *hit = 1;
        if (lit_and_seen(l, v, pos + 3 * (size_t)t)) areas(v, lf, p, n, &rg->cam, &rg->light);
    }
    return stride == 1;
}

/* Texels per unit of the light plane: sqrt(A_cam W H / A_light), A_cam the
 * image fraction (NDC area / 4); 0 when nothing was measured. */
static tg_real rule_density(const region *rg, const tgi_view *v)
{
    tg_real cam = tg_ldexp(rg->cam, -2);
    if (!(rg->light > 0) || !(cam > 0)) return 0;
    return tg_mul(tg_mul(tg_div(tg_sqrt(cam), tg_sqrt(rg->light)), tg_sqrt(tg_from_int(v->width))),
                  tg_sqrt(tg_from_int(v->height)));
}

/* Merge one face's region into the need: seen, window (light-plane units),
 * density (the largest). */
static void need_merge(tgi_shadow_need *nd, int f, const region *rg, const light_face *lf, tg_real d)
{
    tg_real w[4];
    int k;
    if (!rg->seen) return;
    for (k = 0; k < 4; k++) {
        w[k] = rg->w[k];
        if (lf->perspective) w[k] = tg_clamp(w[k], tg_neg(lf->tan_nominal), lf->tan_nominal);
        else w[k] = tg_div(w[k], lf->scale);               /* back to world units */
    }
    if (!lf->perspective) {                               /* relative to the light basis's origin */
        tg_real ox = tgi_v3_dot(lf->o, lf->r), oy = tgi_v3_dot(lf->o, lf->u);
        w[0] = tg_add(w[0], ox); w[2] = tg_add(w[2], ox);
        w[1] = tg_add(w[1], oy); w[3] = tg_add(w[3], oy);
        d = tg_mul(d, lf->scale);                         /* per world unit */
    }
    if (nd->seen[f] && !nd->window_set[f]) {
        /* seen before without a window (tgi_shadow_need_all): it stays whole */
    } else if (!nd->window_set[f]) {
        memcpy(nd->window[f], w, sizeof w);
        nd->window_set[f] = 1;
    } else {
        nd->window[f][0] = tg_min(nd->window[f][0], w[0]); nd->window[f][1] = tg_min(nd->window[f][1], w[1]);
        nd->window[f][2] = tg_max(nd->window[f][2], w[2]); nd->window[f][3] = tg_max(nd->window[f][3], w[3]);
    }
    nd->seen[f] = 1;
    nd->density[f] = tg_max(nd->density[f], d);
}

/* The whole face's side on its light plane: the nominal face, or the
 * bounds' extent across a directional light (as the map's setup fits it). */
static tg_real nominal_side(const light_face *lf, tg_vec3 lo, tg_vec3 hi)
{
    tg_real x0 = TG_REAL_MAX, x1 = TG_REAL_MIN, y0 = TG_REAL_MAX, y1 = TG_REAL_MIN;
    int k;
    if (lf->perspective) return tg_ldexp(lf->tan_nominal, 1);
    for (k = 0; k < 8; k++) {
        tg_vec3 c = corner(lo, hi, k);
        x0 = tg_min(x0, tgi_v3_dot(c, lf->r)); x1 = tg_max(x1, tgi_v3_dot(c, lf->r));
        y0 = tg_min(y0, tgi_v3_dot(c, lf->u)); y1 = tg_max(y1, tgi_v3_dot(c, lf->u));
    }
    return tg_max(tg_sub(x1, x0), tg_sub(y1, y0));
}

void tgi_shadow_map_size_rule(tgi_shadow_need *nd, const tgi_light *l, const tgi_view *view,
                              tg_vec3 lo, tg_vec3 hi, const tg_vec3 *tri_pos, int tri_count)
{
    light_face lf;
    region rg;
    hexa box, cam;
    const hexa *hx[3];
    tg_vec3 poly[POLY_MAX];            /* the polygon being cut, for intersect and triangle_areas in turn */
    tg_real margin, extent = tgi_v3_length(tgi_v3_sub(hi, lo));
    int f, k;
    /* the G-buffer position's error bound at the bounds' deepest corner, and the arithmetic */
    tg_real zmax = 0;
    for (k = 0; k < 8; k++) zmax = tg_max(zmax, tgi_v3_dot(tgi_v3_sub(corner(lo, hi, k), view->eye), view->forward));
    margin = tg_add(tg_add(tg_ldexp(tg_mul(zmax, tgi_shadow_gbuffer_error(view)), 1), tg_ldexp(extent, -12)),
                    64 * TG_EPS);
    hexa_box(&box, tgi_v3_sub(lo, tg_v3(margin, margin, margin)), tgi_v3_add(hi, tg_v3(margin, margin, margin)));
    if (!camera_hexa(&cam, view, lo, hi, margin)) return;
    hx[0] = &box; hx[1] = &cam;
    /* The faces are independent: one at a time, so that one face's frame
     * and region are on the stack rather than six (the plan runs on the
     * smallest cores' stacks too: README "Porting"). */
    for (f = 0; f < nd->faces; f++) {
        memset(&rg, 0, sizeof rg);
        light_face_make(&lf, l, f, lo, hi, margin);
        nd->whole_side[f] = nominal_side(&lf, lo, hi);
        hx[2] = &lf.pyramid;
        intersect(&rg, hx, lf.perspective ? 3 : 2, CLIP_SLACK, view, &lf, poly);
        if (tri_pos && tri_count > 0) {
            /* the receivers' areas replace the region's volume; where every
             * triangle was visited at its place in this view, a face none of
             * them reaches is not seen either */
            int hit = 0;
            rg.cam = rg.light = 0;
            if (triangle_areas(&rg, &hit, &lf, l, view, &cam, tri_pos, tri_count, poly) && !nd->objects_move)
                rg.seen &= hit;
        }
        need_merge(nd, f, &rg, &lf, rule_density(&rg, view));
    }
}

/* ---- where one map is too coarse ---- */

/* The rule's density is an average over the receivers, and one map has
 * one: receivers that span depths far apart (a ground plane running from
 * the objects out to the horizon) get it where the near ones need many
 * times more.  A receiver is served coarsely where a texel of the map
 * spans more than TG_SHADOW_COARSE x TG_SHADOW_COARSE of its pixels. */

/* Texels per unit of face f's light plane (the rule's units: need_merge's
 * inverse) that the finished need's map has: its size less the border
 * across the window (or the whole face). */
static tg_real map_density(const tgi_shadow_need *nd, int f, const light_face *lf)
{
    const tg_real *w = nd->window[f];
    tg_real side = nd->window_set[f] ? tg_max(tg_sub(w[2], w[0]), tg_sub(w[3], w[1])) : nd->whole_side[f];
    tg_real d;
    if (!(side > 0) || nd->size[f] <= 2 * TG_SHADOW_BORDER) return 0;
    d = tg_div(tg_from_int(nd->size[f] - 2 * TG_SHADOW_BORDER), side);
    return lf->perspective ? d : tg_div(d, lf->scale);   /* directional: per world unit -> per light-plane unit */
}

/* The triangle t cut to the frustum, the face's pyramid and the nslab
 * half-spaces slab[] (a depth slab's sides, or none), into p; returns its
 * vertices. */
static int receiver_piece(tg_vec3 *p, const tg_vec3 *pos, int t, const hexa *cam, const light_face *lf,
                          const halfspace *slab, int nslab)
{
    int n;
    memcpy(p, pos + 3 * (size_t)t, 3 * sizeof *p);
    n = clip(p, 3, cam->h, 6, CLIP_SLACK);
    if (n > 0 && lf->perspective) n = clip(p, n, lf->pyramid.h, 6, CLIP_SLACK);
    return n > 0 && nslab > 0 ? clip(p, n, slab, nslab, 0) : n;
}

/* Depth slabs coarse_areas measures: [z0 2^k, z0 2^(k+1)) for k below the
 * last, which runs on to the far side (z0 = the near plane: 2^31 z0 is
 * past any depth either number type holds at a 0.001 near plane). */
#define COARSE_SLABS 32

/* The image areas (NDC units^2) of the receivers the rule measures on face
 * f (triangle_areas': lit and seen, cut to the frustum and the face's
 * pyramid) and of those served coarsely by a map of `density`: the pieces
 * cut into the view's depth slabs, within each of which a pixel's
 * footprint varies by at most 2, their areas summed per slab over the
 * triangles, and each slab's own density (rule_density) compared with the
 * map's; a slab with no area on the light plane (lit at grazing incidence)
 * no density serves.  p: room for a polygon. */
static void coarse_areas(const light_face *lf, const tgi_light *l, const tgi_view *v, const hexa *cam,
                         const tg_vec3 *pos, int tri_count, tg_real density, tg_real *all, tg_real *coarse,
                         tg_vec3 *p)
{
    const int stride = tri_count / TG_SHADOW_RULE_TRIANGLES + 1;
    const tg_real eye_z = tgi_v3_dot(v->eye, v->forward), z0 = tg_max(v->znear, TG_R(0.001f));
    const tg_real limit = tg_mul(density, tg_from_int(TG_SHADOW_COARSE));
    tg_real cam_area[COARSE_SLABS], light_area[COARSE_SLABS];
    int t, i, k, n;
    for (k = 0; k < COARSE_SLABS; k++) cam_area[k] = light_area[k] = 0;
    for (t = 0; t < tri_count; t += stride) {
        tg_real zmin = TG_REAL_MAX, zmax = 0, zlo;
        if (!lit_and_seen(l, v, pos + 3 * (size_t)t)) continue;
        n = receiver_piece(p, pos, t, cam, lf, NULL, 0);
        for (i = 0; i < n; i++) {
            tg_real z = tg_sub(tgi_v3_dot(p[i], v->forward), eye_z);
            zmin = tg_min(zmin, z);
            zmax = tg_max(zmax, z);
        }
        for (k = 0, zlo = z0; n > 0 && k < COARSE_SLABS && (k == 0 || zlo < zmax); k++, zlo = tg_ldexp(zlo, 1)) {
            const int last = k + 1 == COARSE_SLABS;
            const tg_real zhi = tg_ldexp(zlo, 1);
            halfspace slab[2];
            int m = n;
            if (!last && zhi <= zmin) continue;
            if ((k > 0 && zlo > zmin) || (!last && zhi < zmax)) {   /* the piece spans slabs: cut anew for this one */
                slab[0].n = v->forward; slab[0].d = tg_neg(tg_add(eye_z, zlo));                 /* z >= zlo */
                slab[1].n = tgi_v3_neg(v->forward); slab[1].d = tg_add(eye_z, zhi);              /* z <= zhi */
                m = receiver_piece(p, pos, t, cam, lf, k > 0 ? slab : slab + 1, (k > 0) + !last);
            }
            if (m >= 3) areas(v, lf, p, m, &cam_area[k], &light_area[k]);
        }
    }
    for (k = 0; k < COARSE_SLABS; k++) {
        region rg;
        if (!(cam_area[k] > 0)) continue;
        memset(&rg, 0, sizeof rg);
        rg.cam = cam_area[k];
        rg.light = light_area[k];
        *all = tg_add(*all, rg.cam);
        if (!(rg.light > 0) || rule_density(&rg, v) > limit) *coarse = tg_add(*coarse, rg.cam);
    }
}

/* APART: its polygon, frustum and slab sums stay off tgi_shadow_plan's frame */
APART int tgi_shadow_map_coarse(const tgi_shadow_need *nd, const tgi_light *l, const tgi_view *view,
                                tg_vec3 lo, tg_vec3 hi, const tg_vec3 *tri_pos, int tri_count)
{
    light_face lf;
    hexa cam;
    tg_vec3 p[POLY_MAX];
    tg_real margin = tg_add(tg_ldexp(tgi_v3_length(tgi_v3_sub(hi, lo)), -12), 64 * TG_EPS);
    int f;
    if (!tri_pos || tri_count <= 0 || !camera_hexa(&cam, view, lo, hi, margin)) return 0;
    for (f = 0; f < nd->faces; f++) {
        tg_real all = 0, coarse = 0, density;
        if (nd->size[f] == 0) continue;
        light_face_make(&lf, l, f, lo, hi, margin);
        density = map_density(nd, f, &lf);
        if (!(density > 0)) continue;
        coarse_areas(&lf, l, view, &cam, tri_pos, tri_count, density, &all, &coarse, p);
        if (tg_mul(coarse, tg_from_int(TG_SHADOW_COARSE_SHARE)) > all) return 1;
    }
    return 0;
}

size_t tgi_shadow_map_bytes_for_view(const tgi_light *l, const tgi_view *view, tg_vec3 lo, tg_vec3 hi,
                                     const tg_vec3 *tri_pos, int tri_count, int size_override)
{
    tgi_shadow_need nd;
    tgi_shadow_need_init(&nd, l);
    tgi_shadow_map_size_rule(&nd, l, view, lo, hi, tri_pos, tri_count);
    tgi_shadow_need_finish(&nd, size_override);
    return tgi_shadow_need_bytes(&nd);
}

void tgi_shadow_animation_bounds(const tg_scene *s, int frames, tg_vec3 *lo, tg_vec3 *hi)
{
    int o, t, k, frame;
    *lo = s->bounds_min;
    *hi = s->bounds_max;
    if (frames < 1) frames = 1;
    for (o = 0; o < s->object_count; o++) {
        tg_vec3 olo = tg_v3(0, 0, 0), ohi = olo;
        int any = 0;
        if (TG_NO_ANIMATION || !tgi_anim_object_moves(s, o)) continue;   /* no keys with TG_NO_ANIMATION=1 */
        for (t = 0; t < s->tri_count; t++) {       /* the object's rest bounds */
            if (s->tri_object[t] != o) continue;
            for (k = 0; k < 3; k++) {
                tg_vec3 p = s->tri_pos[3 * (size_t)t + (size_t)k];
                if (!any) olo = ohi = p;
                any = 1;
                olo = tg_v3(tg_min(olo.x, p.x), tg_min(olo.y, p.y), tg_min(olo.z, p.z));
                ohi = tg_v3(tg_max(ohi.x, p.x), tg_max(ohi.y, p.y), tg_max(ohi.z, p.z));
            }
        }
        if (!any) continue;
        for (frame = 0; frame < frames; frame++) {  /* carried by each frame's pose */
            tgi_mat4 m;
#if !TG_NO_ANIMATION
            tgi_anim_object_matrix(s, o, tgi_anim_time(s, frame, frames), &m);
#else
            m = tgi_m4_identity();
#endif
            for (k = 0; k < 8; k++) {
                tg_vec3 p = tgi_m4_point(&m, corner(olo, ohi, k));
                *lo = tg_v3(tg_min(lo->x, p.x), tg_min(lo->y, p.y), tg_min(lo->z, p.z));
                *hi = tg_v3(tg_max(hi->x, p.x), tg_max(hi->y, p.y), tg_max(hi->z, p.z));
            }
        }
    }
}

size_t tgi_shadow_light_budget(size_t pixels, int lights)
{
    size_t budget;
    if (tg_size_mul(pixels, TG_SHADOW_MAP_BYTES_PER_PIXEL, &budget)) return (size_t)-1;   /* past size_t: no limit */
    return budget / (size_t)(lights > 1 ? lights : 1);
}

int tgi_shadow_choose(size_t map_bytes, size_t bvh_bytes, size_t pixels, int lights)
{
    if (map_bytes <= tgi_shadow_light_budget(pixels, lights)) return TG_SHADOW_BY_MAP;
    return bvh_bytes < map_bytes ? TG_SHADOW_BY_RAYS : TG_SHADOW_BY_MAP;
}

/* ---- the plan ---- */

/* The camera of frame `frame` of the request: its keys' or the scene's. */
static void frame_view(tgi_view *v, const tg_scene *s, const tg_request *r, int frame)
{
    tg_vec3 pos = s->camera.pos, target = s->camera.target;
#if !TG_NO_ANIMATION /* the keys are left out with TG_NO_ANIMATION=1 (tinygi.h "FEATURE SWITCHES") */
    if (s->camera_key_count > 0) tgi_anim_camera(s, tgi_anim_time(s, frame, r->frames), &pos, &target);
#else
    (void)frame;
#endif
    tgi_view_make(v, pos, target, s->camera.up, s->camera.fov, s->camera.znear, s->camera.zfar, r->width, r->height);
}

/* A finished need well within its light's share of the budget
 * (tgi_shadow_light_budget): its densities raised by up to
 * TG_SHADOW_RULE_GAIN, as far as the maps still fit (in steps of 1/16; a
 * texel per pixel leaves 1-2 pixel bands along concave corners, where the
 * filter's footprint crosses onto the other surface, README "Shadows"). */
APART static void spend_the_budget(tgi_shadow_need *nd, size_t budget)
{
    tgi_shadow_need base = *nd;
    size_t bytes = tgi_shadow_need_bytes(nd);
    int step, f;
    if (bytes == 0 || bytes >= budget) return;
    for (step = 16 * TG_SHADOW_RULE_GAIN; step > 16; step--) {
        for (f = 0; f < nd->faces; f++) nd->density[f] = tg_mul(base.density[f], tg_ratio(step, 16));
        tgi_shadow_need_finish(nd, 0);
        bytes = tgi_shadow_need_bytes(nd);
        if (bytes > 0 && bytes <= budget) return;
    }
    *nd = base;
}

/* The lights that cast shadows (at least 1): their maps share the budget. */
static int shadowed_lights(const tg_scene *s)
{
    int i, n = 0;
    for (i = 0; i < s->light_count; i++) n += s->lights[i].shadows != 0;
    return n > 1 ? n : 1;
}

/* The frame of the plan's k-th of n views: every frame's, or n spread over
 * the `views` frames. */
static int plan_view_frame(int k, int n, int views)
{
    return n == views ? k : (int)((long)k * (views - 1) / (n > 1 ? n - 1 : 1));
}

/* Whether the views the rule sees are all the views the lookups come from. */
static int views_known(const tg_scene *s, const tg_request *r)
{
    int views = s->camera_key_count > 0 ? r->frames : 1;
    return !r->game_loop && r->technique != TG_TECH_REFERENCE && views <= TG_SHADOW_PLAN_VIEWS;
}

/* |p|_1, the largest dot product of p with a unit vector or more, without
 * saturation (tgi_wide). */
static tgi_wide reach_l1(tg_vec3 p)
{
    return (tgi_wide)tg_abs(p.x) + (tgi_wide)tg_abs(p.y) + (tgi_wide)tg_abs(p.z);
}

/* Whether a map's arithmetic cannot hold the scene of request r within the
 * bounds lo, hi: the rule's clip planes through the eye and a directional
 * map's light-plane coordinates (its window, its texels) are dot products of
 * positions from the origin with unit vectors, up to |p|_1 of the bounds'
 * corners and the views' eyes, and in Q16.16 they saturate past
 * TG_REAL_MAX (a box on a +-10 ground 25000 units from the origin on x and
 * z: the rule measured nothing and planned an 8-texel map that shadowed
 * the wrong pixels).  Never in float, whose range holds any scene. */
static int map_out_of_range(const tg_scene *s, const tg_request *r, tg_vec3 lo, tg_vec3 hi)
{
    tgi_view v;
    int views = s->camera_key_count > 0 ? r->frames : 1, n = views < TG_SHADOW_PLAN_VIEWS ? views : TG_SHADOW_PLAN_VIEWS, k;
    for (k = 0; k < 8; k++)
        if (reach_l1(corner(lo, hi, k)) > (tgi_wide)TG_REAL_MAX) return 1;
    for (k = 0; k < n && !r->game_loop; k++) {
        frame_view(&v, s, r, plan_view_frame(k, n, views));
        if (reach_l1(v.eye) > (tgi_wide)TG_REAL_MAX) return 1;
    }
    return 0;
}

int tgi_shadow_plan(const tg_scene *s, const tg_request *r, int light, size_t bvh_bytes,
                    tgi_shadow_need *nd, tg_vec3 *lo, tg_vec3 *hi)
{
    const tgi_light *l = &s->lights[light];
    int views = s->camera_key_count > 0 ? r->frames : 1, k, n, by;
    size_t bytes;
    tgi_view v;
    tgi_shadow_animation_bounds(s, r->frames, lo, hi);
    tgi_shadow_need_init(nd, l);
    if (r->shadow_method == TG_SHADOWS_RAYS) return TG_SHADOW_BY_RAYS;
    nd->objects_move = tgi_anim_has_posed_objects(s) || (r->game_loop && s->object_count > 0);
    if (!views_known(s, r)) tgi_shadow_need_all(nd);
    n = views < TG_SHADOW_PLAN_VIEWS ? views : TG_SHADOW_PLAN_VIEWS;
    for (k = 0; k < n; k++) {   /* every frame's view, or n spread over them */
        frame_view(&v, s, r, plan_view_frame(k, n, views));
        tgi_shadow_map_size_rule(nd, l, &v, *lo, *hi, s->tri_pos, s->tri_count);
    }
    tgi_shadow_need_finish(nd, r->shadow_map_size);
    if (r->shadow_map_size <= 0)
        spend_the_budget(nd, tgi_shadow_light_budget((size_t)r->width * (size_t)r->height, shadowed_lights(s)));
    if (r->shadow_method == TG_SHADOWS_MAPS || r->shadow_map_size > 0) return TG_SHADOW_BY_MAP;
    if (bvh_bytes != SIZE_MAX && map_out_of_range(s, r, *lo, *hi)) return TG_SHADOW_BY_RAYS;   /* a BVH is possible */
    bytes = tgi_shadow_need_bytes(nd);
    by = tgi_shadow_choose(bytes, bvh_bytes, (size_t)r->width * (size_t)r->height, shadowed_lights(s));
    if (by == TG_SHADOW_BY_MAP && bvh_bytes < bytes && views_known(s, r))
        for (k = 0; k < n && by == TG_SHADOW_BY_MAP; k++) {   /* one map too coarse for what a view sees */
            frame_view(&v, s, r, plan_view_frame(k, n, views));
            if (tgi_shadow_map_coarse(nd, l, &v, *lo, *hi, s->tri_pos, s->tri_count)) by = TG_SHADOW_BY_RAYS;
        }
    return by;
}

/* "  light I (TYPE): ..." for the plan's explanation. */
static void put_light(tgi_text *t, const tg_scene *s, const tg_request *r, int i, size_t bvh)
{
    static const char *const face_names[6] = { "+X", "-X", "+Y", "-Y", "+Z", "-Z" };
    static const char *const types[3] = { "directional", "point", "spot" };
    tgi_shadow_need nd;
    tg_vec3 lo, hi;
    int f, by = tgi_shadow_plan(s, r, i, bvh, &nd, &lo, &hi);
    tgi_text_put(t, "  light ");
    tgi_text_put_uint(t, (size_t)i);
    tgi_text_put(t, " (");
    tgi_text_put(t, types[s->lights[i].type]);
    if (by == TG_SHADOW_BY_RAYS) {
        tgi_text_put(t, "): shadow rays against the BVH of ");
        tgi_text_put_uint(t, (size_t)s->tri_count);
        tgi_text_put(t, " triangles");
        if (r->shadow_method == TG_SHADOWS_AUTO) {
            const size_t pixels = (size_t)r->width * (size_t)r->height, bytes = tgi_shadow_need_bytes(&nd);
            const int lights = shadowed_lights(s);
            if (map_out_of_range(s, r, lo, hi)) {
                tgi_text_put(t, " (the scene reaches past the number type's range from the origin, where a map's"
                                " coordinates would saturate)");
            } else if (tgi_shadow_choose(bytes, bvh, pixels, lights) == TG_SHADOW_BY_MAP) {   /* tgi_shadow_map_coarse's reason */
                tgi_text_put(t, " (one map would give over 1/");
                tgi_text_put_uint(t, TG_SHADOW_COARSE_SHARE);
                tgi_text_put(t, " of the receivers seen a texel for more than ");
                tgi_text_put_uint(t, TG_SHADOW_COARSE * TG_SHADOW_COARSE);
                tgi_text_put(t, " pixels)");
            } else {   /* the bytes' */
                tgi_text_put(t, " (its maps would take ");
                tgi_text_put_uint(t, bytes);
                tgi_text_put(t, " bytes, over its share of the maps' budget: ");
                tgi_text_put_uint(t, tgi_shadow_light_budget(pixels, lights));
                tgi_text_put(t, " bytes, ");
                if (lights > 1) {
                    tgi_text_put(t, "1/");
                    tgi_text_put_uint(t, (size_t)lights);
                    tgi_text_put(t, " of ");
                }
                tgi_text_put_uint(t, TG_SHADOW_MAP_BYTES_PER_PIXEL);
                tgi_text_put(t, " bytes a pixel)");
            }
        }
        tgi_text_put(t, "\n");
        return;
    }
    tgi_text_put(t, "): 16-bit map, texels per side");
    for (f = 0; f < nd.faces; f++) {
        tgi_text_put(t, nd.faces > 1 ? (f ? ", " : " ") : " ");
        if (nd.faces > 1) { tgi_text_put(t, face_names[f]); tgi_text_put(t, " "); }
        if (nd.size[f]) tgi_text_put_uint(t, (size_t)nd.size[f]);
        else tgi_text_put(t, "absent");
    }
    tgi_text_put(t, r->shadow_map_size > 0 || !views_known(s, r) ? " (whole faces)" : "");
    tgi_text_put(t, ": ");
    tgi_text_put_uint(t, tgi_shadow_need_bytes(&nd));
    tgi_text_put(t, " bytes\n");
}

void tgi_shadow_explain(tgi_text *t, const tg_scene *s, const tg_request *r, size_t bvh_bytes)
{
    int i;
    tgi_text_put(t, r->shadow_map_size > 0 ? "shadows (every face a view needs, whole, at --shadow-size):\n"
                                          : "shadows (size rule: about a texel per image pixel on what the camera sees; "
                                            "unseen faces absent):\n");
    for (i = 0; i < s->light_count; i++)
        if (s->lights[i].shadows) put_light(t, s, r, i, bvh_bytes);
}

#endif /* !TG_NO_SHADOW_MAPS */
