/* SPDX-License-Identifier: MIT */
/*
 * pathtrace.c - unbiased diffuse path tracing on the BVH: next-event
 * estimation of analytic lights and emissive triangles, cosine-distributed
 * continuation, the environment on escape, Russian roulette.  See
 * pathtrace.h.
 */
#include <string.h>
#include "pathtrace.h"
#include "../light/direct.h"
#include "../light/shadowmap.h"
#include "../light/sh.h"
#include "sampling.h"

#if !TG_NO_REFERENCE /* the whole file is left out with TG_NO_REFERENCE=1 (tinygi.h "FEATURE SWITCHES") */

#define HIT_EPS_REL TG_R(0.00006103515625f) /* 2^-14 of a point's coordinates: its ray's start offset */
#define HIT_EPS_ULPS 8
#define RR_MIN_SURVIVAL TG_R(0.0625f)

/* ---- random numbers: PCG32 (O'Neill 2014), one stream per path ---- */

typedef struct pcg32 { uint64_t state; } pcg32;

static uint32_t pcg_next(pcg32 *r)
{
    uint64_t old = r->state;
    uint32_t xorshifted = (uint32_t)(((old >> 18) ^ old) >> 27), rot = (uint32_t)(old >> 59);
    r->state = old * 6364136223846793005ULL + 1442695040888963407ULL;
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
}

/* splitmix64's finaliser: well-mixed bits from (seed, pixel, sample). */
static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static void pcg_seed(pcg32 *r, uint32_t seed, uint32_t pixel, uint32_t sample)
{
    r->state = mix64(((uint64_t)seed << 32 | pixel) ^ mix64((uint64_t)sample + 0x9E3779B97F4A7C15ULL));
    (void)pcg_next(r);
}

/* Uniform in [0, 1). */
static tg_real pcg_real(pcg32 *r)
{
#if TG_FIXED
    return (tg_real)(pcg_next(r) >> 16);
#else
    return (float)(pcg_next(r) >> 8) * (1.0f / 16777216.0f);
#endif
}

/* ---- the emitter table ---- */

static int is_emissive(const tgi_material *m)
{
    return m->emissive.x > 0 || m->emissive.y > 0 || m->emissive.z > 0;
}

int tgi_pathtrace_emitter_count(const uint16_t *tri_material, const tgi_material *materials, int tri_count)
{
    int i, n = 0;
    for (i = 0; i < tri_count; i++) n += is_emissive(&materials[tri_material[i]]);
    return n;
}

size_t tgi_pathtrace_emitter_bytes(int count)
{
    size_t bytes;
    if (count < 0 || tg_size_mul((size_t)count, sizeof(tgi_pt_emitter), &bytes)) return 0;
    return bytes;
}

/* Unit normal and area of a triangle; the cross product is taken on edges
 * scaled by a power of two into [1, 2) so Q16.16 keeps its bits for tiny
 * and large triangles alike. */
static tg_vec3 tri_normal_area(const tg_vec3 *v, tg_real *area)
{
    tg_vec3 e1 = tgi_v3_sub(v[1], v[0]), e2 = tgi_v3_sub(v[2], v[0]), c;
    tg_real m = tg_max(tg_max(tg_max(tg_abs(e1.x), tg_abs(e1.y)), tg_max(tg_abs(e1.z), tg_abs(e2.x))),
                       tg_max(tg_abs(e2.y), tg_abs(e2.z)));
    int k = 0;
    if (m == 0) { *area = 0; return tg_v3(0, 0, 0); }
    while (m < TG_ONE && k < 30) { m = tg_ldexp(m, 1); k++; }
    while (m >= TG_R(2.0f) && k > -30) { m = tg_ldexp(m, -1); k--; }
    e1 = tg_v3(tg_ldexp(e1.x, k), tg_ldexp(e1.y, k), tg_ldexp(e1.z, k));
    e2 = tg_v3(tg_ldexp(e2.x, k), tg_ldexp(e2.y, k), tg_ldexp(e2.z, k));
    c = tgi_v3_cross(e1, e2);
    *area = tg_ldexp(tgi_v3_length(c), -1 - 2 * k);
    return tgi_v3_normalize(c);
}

/* A ratio in (0, 1] as an integer weight in [1, 2^24]. */
static uint32_t weight_u24(tg_real ratio)
{
#if TG_FIXED
    uint32_t w = (uint32_t)(ratio > 0 ? ratio : 0) << 8;
#else
    uint32_t w = (uint32_t)(ratio * 16777216.0f);
#endif
    return w > 0 ? (w < (1u << 24) ? w : 1u << 24) : 1u;
}

/* area * 2^32 / share: the area over the selection probability share / 2^32. */
static tg_real area_over_share(tg_real area, uint64_t share)
{
#if TG_FIXED
    uint64_t v = ((uint64_t)(area > 0 ? area : 0) << 32) / share;
    return v > (uint64_t)TG_REAL_MAX ? TG_REAL_MAX : (tg_real)v;
#else
    return area * (4294967296.0f / (float)share);
#endif
}

int tgi_pathtrace_emitters(tgi_pt_emitter *out, const tg_vec3 *tri_pos, const uint16_t *tri_material,
                           const tgi_material *materials, int tri_count)
{
    tg_real power_max = 0;
    uint64_t total = 0, cum = 0;
    int i, n = 0, shift = 0;
    /* pass 1: each emitter's power (area * mean emitted radiance), the largest */
    for (i = 0; i < tri_count; i++) {
        const tgi_material *m = &materials[tri_material[i]];
        tg_real area, power;
        if (!is_emissive(m)) continue;
        tri_normal_area(tri_pos + 3 * (size_t)i, &area);
        power = tg_mul(area, tg_mul(tg_add(tg_add(m->emissive.x, m->emissive.y), m->emissive.z), TG_R(1.0f / 3.0f)));
        out[n].tri = i;
        out[n].area_over_pdf = area;        /* the area for now */
        out[n].start = 0;
        if (power > power_max) power_max = power;
        n++;
    }
    if (n == 0) return 0;
    /* pass 2: integer weights (no emitter below 2^-24 of the largest), then
     * starts in [0, 2^32) proportional to the running sum */
    for (i = 0; i < n; i++) {
        const tgi_material *m = &materials[tri_material[out[i].tri]];
        tg_real power = tg_mul(out[i].area_over_pdf,
                               tg_mul(tg_add(tg_add(m->emissive.x, m->emissive.y), m->emissive.z), TG_R(1.0f / 3.0f)));
        total += weight_u24(power_max > 0 ? tg_div(power, power_max) : TG_ONE);
    }
    while ((total >> shift) >= ((uint64_t)1 << 32)) shift++;
    for (i = 0; i < n; i++) {
        const tgi_material *m = &materials[tri_material[out[i].tri]];
        tg_real power = tg_mul(out[i].area_over_pdf,
                               tg_mul(tg_add(tg_add(m->emissive.x, m->emissive.y), m->emissive.z), TG_R(1.0f / 3.0f)));
        uint64_t start = ((cum >> shift) << 32) / (total >> shift);
        uint64_t lo = i > 0 ? (uint64_t)out[i - 1].start + 1 : 0, hi = ((uint64_t)1 << 32) - (uint64_t)(n - i);
        out[i].start = (uint32_t)(start < lo ? lo : start > hi ? hi : start);
        cum += weight_u24(power_max > 0 ? tg_div(power, power_max) : TG_ONE);
    }
    for (i = 0; i < n; i++) {   /* pass 3: area / probability, from the starts actually used */
        uint64_t next = i + 1 < n ? out[i + 1].start : ((uint64_t)1 << 32);
        out[i].area_over_pdf = area_over_share(out[i].area_over_pdf, next - out[i].start);
    }
    return n;
}

/* The emitter whose [start, next start) holds u (binary search). */
static const tgi_pt_emitter *pick_emitter(const tgi_pt_emitter *e, int n, uint32_t u)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (e[mid].start <= u) lo = mid; else hi = mid - 1;
    }
    return &e[lo];
}

/* ---- one path ---- */

typedef struct vertex {
    tg_vec3 p, n, ng;       /* position, shading normal, geometric normal (both facing the path) */
    tg_vec3 rho;            /* diffuse reflectance albedo (1 - F0) */
    tg_real eps;            /* how far rays start off the surface */
} vertex;

typedef struct tracer {
    const tgi_pathtrace_params *p;
    tg_real far;            /* longer than any ray inside the scene */
} tracer;

static tg_vec3 offset_origin(const vertex *v) { return tgi_v3_add(v->p, tgi_v3_scale(v->ng, v->eps)); }

static tg_real point_eps(tg_vec3 p)
{
    tg_real s = tg_add(tg_add(tg_add(tg_abs(p.x), tg_abs(p.y)), tg_abs(p.z)), TG_ONE);
    return tg_add(tg_mul(s, HIT_EPS_REL), HIT_EPS_ULPS * TG_EPS);
}

/* Irradiance from the analytic lights, each seen through a shadow ray. */
static tg_vec3 lights_nee(const tracer *t, const vertex *v)
{
    const tgi_pathtrace_params *p = t->p;
    tg_vec3 e = tg_v3(0, 0, 0), o = offset_origin(v);
    int k;
    for (k = 0; k < p->light_count; k++) {
        const tgi_light *l = &p->lights[k];
        tg_vec3 el = tgi_direct_irradiance(l, v->p, v->n), d;
        tg_real tmax;
        if (el.x <= 0 && el.y <= 0 && el.z <= 0) continue;
        if (l->type == TG_LIGHT_DIRECTIONAL) {
            d = tgi_v3_neg(tgi_v3_normalize_or(l->dir, tg_v3(0, tg_neg(TG_ONE), 0)));
            tmax = t->far;
        } else {
            d = tgi_v3_sub(l->pos, o);
            tmax = tgi_v3_length(d);
            d = tgi_v3_normalize(d);
        }
        if (!tgi_bvh_occluded(p->bvh, o, d, tmax)) e = tgi_v3_add(e, el);
    }
    return e;
}

/* Irradiance from the emissive triangles: one emitter, one point on it. */
static tg_vec3 emitters_nee(const tracer *t, const vertex *v, pcg32 *rng)
{
    const tgi_pathtrace_params *p = t->p;
    const tgi_pt_emitter *em;
    const tg_vec3 *tv;
    tg_vec3 o = offset_origin(v), y, w, ne;
    tg_real s, u2, dist, inv, cos_x, cos_y, area, g;
    if (p->emitter_count <= 0) return tg_v3(0, 0, 0);
    em = pick_emitter(p->emitters, p->emitter_count, pcg_next(rng));
    tv = p->bvh->tri_pos + 3 * (size_t)em->tri;
    s = tg_sqrt(pcg_real(rng)); u2 = pcg_real(rng);      /* uniform on the triangle */
    y = tgi_v3_add(tv[0], tgi_v3_add(tgi_v3_scale(tgi_v3_sub(tv[1], tv[0]), tg_mul(s, tg_sub(TG_ONE, u2))),
                                     tgi_v3_scale(tgi_v3_sub(tv[2], tv[0]), tg_mul(s, u2))));
    w = tgi_v3_sub(y, o);
    dist = tgi_v3_length(w);
    if (dist <= 0) return tg_v3(0, 0, 0);
    inv = tg_div(TG_ONE, dist);
    w = tgi_v3_scale(w, inv);
    cos_x = tgi_v3_dot(v->n, w);
    if (cos_x <= 0 || tgi_v3_dot(v->ng, w) <= 0) return tg_v3(0, 0, 0);
    ne = tri_normal_area(tv, &area);
    cos_y = tg_abs(tgi_v3_dot(ne, w));                    /* both faces emit */
    if (cos_y <= 0) return tg_v3(0, 0, 0);
    if (tgi_bvh_occluded(p->bvh, o, w, tg_sub(dist, point_eps(y)))) return tg_v3(0, 0, 0);
    g = tg_mul(tg_mul(tg_mul(cos_x, inv), tg_mul(cos_y, inv)), em->area_over_pdf); /* cos cos' / d^2 / pdf */
    return tgi_v3_scale(p->materials[p->tri_material[em->tri]].emissive, g);
}

/* Cosine-distributed direction about n (Malley's method, RTR sec. 11.3.4). */
static tg_vec3 cosine_direction(tg_vec3 n, pcg32 *rng)
{
    tg_real u1 = pcg_real(rng), phi = tg_mul(TG_TWO_PI, pcg_real(rng)), r = tg_sqrt(u1);
    tg_vec3 tx, ty;
    tgi_ao_basis(n, &tx, &ty);
    return tgi_ao_from_local(tg_v3(tg_mul(r, tg_cos(phi)), tg_mul(r, tg_sin(phi)), tg_sqrt(tg_sub(TG_ONE, u1))),
                             tx, ty, n);
}

/* The surface a continuation ray hit, its normals facing the ray's origin. */
static void hit_vertex(const tracer *t, tg_vec3 o, tg_vec3 d, const tgi_ray_hit *h, vertex *v)
{
    const tgi_pathtrace_params *p = t->p;
    const tgi_material *m = &p->materials[p->tri_material[h->tri]];
    tg_real area;
    v->p = tgi_v3_add(o, tgi_v3_scale(d, h->t));
    v->ng = tri_normal_area(p->bvh->tri_pos + 3 * (size_t)h->tri, &area);
    if (tgi_v3_dot(v->ng, d) > 0) v->ng = tgi_v3_neg(v->ng);
    v->n = v->ng;
    if (p->tri_nrm) {
        const tg_vec3 *vn = p->tri_nrm + 3 * (size_t)h->tri;
        tg_real w0 = tg_sub(tg_sub(TG_ONE, h->u), h->v);
        tg_vec3 n = tgi_v3_add(tgi_v3_add(tgi_v3_scale(vn[0], w0), tgi_v3_scale(vn[1], h->u)), tgi_v3_scale(vn[2], h->v));
        n = tgi_v3_normalize_or(n, v->ng);
        v->n = tgi_v3_dot(n, v->ng) < 0 ? tgi_v3_neg(n) : n;
    }
    v->rho = tgi_v3_scale(m->albedo, tg_sub(TG_ONE, m->f0));
    v->eps = point_eps(v->p);
}

static tg_real max3(tg_vec3 a) { return tg_max(tg_max(a.x, a.y), a.z); }

/* One path's estimate of the irradiance E at the primary vertex v0. */
static tg_vec3 path_irradiance(const tracer *t, const vertex *v0, pcg32 *rng)
{
    const tgi_pathtrace_params *p = t->p;
    tg_vec3 e = tgi_v3_add(lights_nee(t, v0), emitters_nee(t, v0, rng));
    tg_vec3 w = tg_v3(TG_ONE, TG_ONE, TG_ONE);  /* product of the reflectances so far */
    vertex v = *v0;
    int k;
    for (k = 0; k <= p->bounces; k++) {
        tg_vec3 d = cosine_direction(v.n, rng), o;
        tgi_ray_hit h;
        if (tgi_v3_dot(d, v.ng) <= 0) break;             /* below the true surface: absorbed */
        o = offset_origin(&v);
        if (!tgi_bvh_closest(p->bvh, o, d, t->far, &h)) {
            /* escaped: the environment, pi L for the cosine-sampled E */
            tg_vec3 env = p->env ? tgi_env_radiance(p->env, d) : tg_v3(0, 0, 0);
            e = tgi_v3_add(e, tgi_v3_mul(w, tgi_v3_scale(env, TG_PI)));
            break;
        }
        if (k == p->bounces) break;
        hit_vertex(t, o, d, &h, &v);
        w = tgi_v3_mul(w, v.rho);     /* pi * rho / pi: the next vertex's reflected light */
        e = tgi_v3_add(e, tgi_v3_mul(w, tgi_v3_add(lights_nee(t, &v), emitters_nee(t, &v, rng))));
        if (k + 1 >= p->rr_start) {   /* Russian roulette */
            tg_real q = tg_clamp(max3(w), RR_MIN_SURVIVAL, TG_ONE);
            if (pcg_real(rng) >= q) break;
            w = tgi_v3_scale(w, tg_div(TG_ONE, q));
        }
    }
    return e;
}

/* ---- rows ---- */

void tgi_pathtrace_defaults(tgi_pathtrace_params *p)
{
    memset(p, 0, sizeof *p);
    p->samples = TG_DEFAULT_PATHTRACE_SAMPLES;
    p->bounces = 1;
    p->rr_start = TG_MAX_BOUNCES + 1;
    p->seed = 1;
}

/* Sum of tg_real samples without losing bits (fixed point: 64-bit raw). */
#if TG_FIXED
typedef int64_t sample_sum;
static tg_real sum_mean(sample_sum s, int n) { return tgi_sat64(s / n); }
#else
typedef float sample_sum;
static tg_real sum_mean(sample_sum s, int n) { return s / (float)n; }
#endif

static tg_real scene_far(const tgi_bvh *bvh)
{
    tg_vec3 lo, hi;
    if (bvh->node_count == 0) return TG_ONE;
    lo = bvh->nodes[0].lo; hi = bvh->nodes[0].hi;
    return tg_add(tg_mul(tgi_v3_length(tgi_v3_sub(hi, lo)), TG_R(2.0f)), TG_ONE);
}

/* Mean irradiance at a G-buffer vertex over the pixel's samples. */
static tg_vec3 pixel_irradiance(const tracer *t, const vertex *v0, uint32_t pixel)
{
    const tgi_pathtrace_params *p = t->p;
    sample_sum sr = 0, sg = 0, sb = 0;
    int s, n = p->samples > 0 ? p->samples : 1;
    for (s = 0; s < n; s++) {
        pcg32 rng;
        tg_vec3 e;
        pcg_seed(&rng, p->seed, pixel, (uint32_t)s);
        e = path_irradiance(t, v0, &rng);
        sr += e.x; sg += e.y; sb += e.z;
    }
    return tg_v3(sum_mean(sr, n), sum_mean(sg, n), sum_mean(sb, n));
}

/* Lo and E of pixel i into the io's planes or colour storage. */
static void store(const tgi_pathtrace_io *io, size_t i, tg_vec3 lo, tg_vec3 e)
{
    if (io->color || io->irradiance) {
        if (tgi_rgb_present(io->color)) tgi_rgb_set(io->color, i, lo);
        if (tgi_rgb_present(io->irradiance)) tgi_rgb_set(io->irradiance, i, e);
        return;
    }
    io->out_r[i] = lo.x; io->out_g[i] = lo.y; io->out_b[i] = lo.z;
    if (io->irr_r) { io->irr_r[i] = e.x; io->irr_g[i] = e.y; io->irr_b[i] = e.z; }
}

void tgi_pathtrace_rows(const tgi_pathtrace_params *p, const tgi_pathtrace_io *io, int y0, int y1)
{
    const tgi_view *view = io->view;
    tgi_gview g;
    tracer t;
    tgi_pathtrace_params q = *p;
    tg_real half_w = tg_ldexp(tg_from_int(view->width), -1), half_h = tg_ldexp(tg_from_int(view->height), -1);
    tg_real gb_error = tgi_shadow_gbuffer_error(view);
    int x, y, w = io->gb->width;
    tgi_gview_of(&g, io->gb, view);
    if (q.bounces < 0) q.bounces = 0;
    if (q.bounces > TG_MAX_BOUNCES) q.bounces = TG_MAX_BOUNCES;
    t.p = &q;
    t.far = scene_far(p->bvh);
    for (y = y0; y < y1; y++) {
        /* pixel centre ray with view z = 1: forward + right kx + up ky (view.h) */
        tg_real ky = tg_div(tg_sub(half_h, tg_add(tg_from_int(y), TG_R(0.5f))), view->pixels_per_unit);
        tg_vec3 row_dir = tgi_v3_add(view->forward, tgi_v3_scale(view->up, ky));
        for (x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            tg_real kx = tg_div(tg_sub(tg_add(tg_from_int(x), TG_R(0.5f)), half_w), view->pixels_per_unit);
            tg_vec3 dir = tgi_v3_add(row_dir, tgi_v3_scale(view->right, kx)), e, lo;
            vertex v0;
            if (tgi_gv_is_sky(&g, i)) {
                lo = p->env ? tgi_env_radiance(p->env, tgi_v3_normalize(dir)) : tg_v3(0, 0, 0);
                store(io, i, lo, tg_v3(0, 0, 0));
                continue;
            }
            v0.p = tgi_v3_add(view->eye, tgi_v3_scale(dir, tgi_gv_depth(&g, i)));
            v0.n = v0.ng = tgi_gv_normal(&g, i);
            v0.rho = tgi_v3_scale(tgi_gv_albedo(&g, i), tg_sub(TG_ONE, tgi_gv_f0(&g, i)));
            v0.eps = tg_add(tg_mul(tgi_gv_depth(&g, i), gb_error), point_eps(v0.p));
            e = pixel_irradiance(&t, &v0, (uint32_t)i);
            lo = tgi_v3_scale(tgi_v3_mul(v0.rho, e), TG_INV_PI);   /* rho / pi E (HBIL eq. 14) */
            if (tgi_gv_has_emissive(&g)) lo = tgi_v3_add(lo, tgi_gv_emissive(&g, i));
            store(io, i, lo, e);
        }
    }
}

#endif /* !TG_NO_REFERENCE */
