/* SPDX-License-Identifier: MIT */
/*
 * interleave.c - 4x4 split/merge into quarter-resolution sub-images (HBIL
 * sec. 3.3).  Layout in interleave.h.  A full-resolution row y belongs to
 * sub-image row y / 4 of the four sub-images (i, y & 3), so a row range of
 * the full image maps to disjoint destination rows: threads may split rows.
 */
#include "interleave.h"

static int sub_size(int n, int i) { return n > i ? (n - i + 3) / 4 : 0; }

void tgi_interleave_sub_rect(int w, int h, int i, int j, int *sw, int *sh, size_t *offset)
{
    size_t off = 0;
    int k, kk = j * 4 + i;
    for (k = 0; k < kk; k++)
        off += (size_t)sub_size(w, k & 3) * (size_t)sub_size(h, k >> 2);
    if (sw) *sw = sub_size(w, i);
    if (sh) *sh = sub_size(h, j);
    if (offset) *offset = off;
}

/* Index in the sub-image layout of full-resolution pixel (x, y). */
typedef struct row_map { size_t base[4]; int sw[4]; } row_map;

static void row_map_make(row_map *m, int w, int h, int y)
{
    int i, sh;
    for (i = 0; i < 4; i++) {
        tgi_interleave_sub_rect(w, h, i, y & 3, &m->sw[i], &sh, &m->base[i]);
        m->base[i] += (size_t)(y >> 2) * (size_t)m->sw[i];
    }
}

#define TG_INTERLEAVE_BODY(SPLIT)                                         \
    int x, y;                                                             \
    row_map m;                                                            \
    if (y0 < 0) y0 = 0;                                                   \
    if (y1 > h) y1 = h;                                                   \
    for (y = y0; y < y1; y++) {                                           \
        size_t row = (size_t)y * (size_t)w;                               \
        row_map_make(&m, w, h, y);                                        \
        for (x = 0; x < w; x++) {                                         \
            size_t s = m.base[x & 3] + (size_t)(x >> 2);                  \
            if (SPLIT) dst[s] = src[row + (size_t)x];                     \
            else dst[row + (size_t)x] = src[s];                           \
        }                                                                 \
    }

void tgi_interleave_split_rows(const tg_real *src, int w, int h, tg_real *dst, int y0, int y1)
{ TG_INTERLEAVE_BODY(1) }
void tgi_interleave_merge_rows(const tg_real *src, int w, int h, tg_real *dst, int y0, int y1)
{ TG_INTERLEAVE_BODY(0) }
void tgi_interleave_split8_rows(const uint8_t *src, int w, int h, uint8_t *dst, int y0, int y1)
{ TG_INTERLEAVE_BODY(1) }
void tgi_interleave_merge8_rows(const uint8_t *src, int w, int h, uint8_t *dst, int y0, int y1)
{ TG_INTERLEAVE_BODY(0) }

void tgi_interleave_split(const tg_real *src, int w, int h, tg_real *dst) { tgi_interleave_split_rows(src, w, h, dst, 0, h); }
void tgi_interleave_merge(const tg_real *src, int w, int h, tg_real *dst) { tgi_interleave_merge_rows(src, w, h, dst, 0, h); }
void tgi_interleave_split8(const uint8_t *src, int w, int h, uint8_t *dst) { tgi_interleave_split8_rows(src, w, h, dst, 0, h); }
void tgi_interleave_merge8(const uint8_t *src, int w, int h, uint8_t *dst) { tgi_interleave_merge8_rows(src, w, h, dst, 0, h); }
