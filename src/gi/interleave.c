/* SPDX-License-Identifier: MIT */
/*
 * interleave.c - 4x4 split/merge into quarter-resolution sub-images (HBIL
 * sec. 3.3).  Layout in interleave.h.  A full-resolution row y belongs to
 * sub-image row y / 4 of the four sub-images (i, y & 3), so a row range of
 * the full image maps to disjoint destination rows: threads may split rows.
 */
#include "interleave.h"

static int sub_size(int n, int i) { return n > i ? (n - i + 3) / 4 : 0; }

/* Sub-images before (i, j) in the order k = j * 4 + i: the whole rows of
 * sub-images above (each row of four is w wide) and those left of it. */
void tgi_interleave_sub_rect(int w, int h, int i, int j, int *sw, int *sh, size_t *offset)
{
    size_t above = 0, left = 0;
    int k;
    for (k = 0; k < j; k++) above += (size_t)sub_size(h, k);
    for (k = 0; k < i; k++) left += (size_t)sub_size(w, k);
    if (sw) *sw = sub_size(w, i);
    if (sh) *sh = sub_size(h, j);
    if (offset) *offset = above * (size_t)w + left * (size_t)sub_size(h, j);
}

void tgi_interleave_row(int w, int h, int y, size_t start[4])
{
    int i, sw, sh;
    for (i = 0; i < 4; i++) {
        tgi_interleave_sub_rect(w, h, i, y & 3, &sw, &sh, &start[i]);
        start[i] += (size_t)(y >> 2) * (size_t)sw;
    }
}

#define TG_INTERLEAVE_BODY(SPLIT)                                         \
    int x, y;                                                             \
    size_t start[4];                                                      \
    if (y0 < 0) y0 = 0;                                                   \
    if (y1 > h) y1 = h;                                                   \
    for (y = y0; y < y1; y++) {                                           \
        size_t row = (size_t)y * (size_t)w;                               \
        tgi_interleave_row(w, h, y, start);                               \
        for (x = 0; x < w; x++) {                                         \
            size_t s = start[x & 3] + (size_t)(x >> 2);                   \
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
