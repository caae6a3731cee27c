/* SPDX-License-Identifier: MIT */
/*
 * gstore.c - the storage of G-buffers, GI results and colour planes carved
 * from one block of memory, in this build's formats (gview.h): for callers
 * that own a block (tests, tools, an embedder's own passes).  Each part is
 * 16-byte aligned; with mem NULL the functions only measure.
 */
#include "gview.h"

/* n elements of `size` bytes at offset *at of base (NULL when measuring);
 * *at moves past them, rounded up to 16. */
static void *part(unsigned char *base, size_t *at, size_t n, size_t size)
{
    void *p = base ? base + *at : NULL;
    *at += (n * size + 15) & ~(size_t)15;
    return p;
}

#if TG_WIDE_STORAGE
/* A vector plane stored wide: three tg_real planes x, y, z of n elements. */
static void part_vec3(unsigned char *base, size_t *at, size_t n, tg_real **x, tg_real **y, tg_real **z)
{
    *x = (tg_real *)part(base, at, n, sizeof(tg_real));
    *y = (tg_real *)part(base, at, n, sizeof(tg_real));
    *z = (tg_real *)part(base, at, n, sizeof(tg_real));
}
#endif

size_t tgi_gbuffer_carve(tgi_gbuffer *g, int w, int h, void *mem)
{
    unsigned char *base = (unsigned char *)mem;
    size_t n = (size_t)w * (size_t)h, at = 0;
    memset(g, 0, sizeof *g);
    g->width = w;
    g->height = h;
#if TG_WIDE_STORAGE
    g->depth = (tg_real *)part(base, &at, n, sizeof(tg_real));
    part_vec3(base, &at, n, &g->nx, &g->ny, &g->nz);
    g->material = (uint16_t *)part(base, &at, n, sizeof(uint16_t));
#else
    g->depth = (uint32_t *)part(base, &at, n, sizeof(uint32_t));
    g->nm = (uint32_t *)part(base, &at, n, sizeof(uint32_t));
#endif
    return at;
}

size_t tgi_gbuffer_carve_geometry(tgi_gbuffer *g, int w, int h, void *mem)
{
#if TG_WIDE_STORAGE
    return tgi_gbuffer_carve(g, w, h, mem);
#else
    unsigned char *base = (unsigned char *)mem;
    size_t n = (size_t)w * (size_t)h, at = 0;
    memset(g, 0, sizeof *g);
    g->width = w;
    g->height = h;
    g->depth = (uint32_t *)part(base, &at, n, sizeof(uint32_t));
    g->n8 = (uint16_t *)part(base, &at, n, sizeof(uint16_t));
    return at;
#endif
}

size_t tgi_rgb_carve(tgi_rgb *c, size_t n, void *mem)
{
    unsigned char *base = (unsigned char *)mem;
    size_t at = 0;
    *c = tgi_rgb_none();
#if TG_WIDE_STORAGE
    part_vec3(base, &at, n, &c->r, &c->g, &c->b);
#else
    c->p = (uint32_t *)part(base, &at, n, sizeof(uint32_t));
#endif
    return at;
}

size_t tgi_gresult_carve(tgi_gresult *r, size_t n, int bent, int cone, int near, void *mem)
{
    unsigned char *base = (unsigned char *)mem;
    size_t at = 0;
    memset(r, 0, sizeof *r);
#if TG_WIDE_STORAGE
    r->ao = (tg_real *)part(base, &at, n, sizeof(tg_real));
    if (bent) part_vec3(base, &at, n, &r->bent_x, &r->bent_y, &r->bent_z);
    if (cone) r->cone = (tg_real *)part(base, &at, n, sizeof(tg_real));
#else
    r->ao = (uint8_t *)part(base, &at, n, 1);
    if (bent) r->bent = (uint16_t *)part(base, &at, n, sizeof(uint16_t));
    if (cone) r->cone = (uint8_t *)part(base, &at, n, 1);
#endif
    if (near) at += tgi_rgb_carve(&r->near, n, base ? base + at : NULL);
    return at;
}

size_t tgi_prev_carve(tgi_prev_geometry *h, size_t n, void *mem)
{
    unsigned char *base = (unsigned char *)mem;
    size_t at = 0;
#if TG_WIDE_STORAGE
    h->depth = (tg_real *)part(base, &at, n, sizeof(tg_real));
    part_vec3(base, &at, n, &h->nx, &h->ny, &h->nz);
#else
    h->dn = (uint32_t *)part(base, &at, n, sizeof(uint32_t));
#endif
    return at;
}
