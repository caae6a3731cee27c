/* SPDX-License-Identifier: MIT */
/*
 * test_interleave.c - 4x4 split/merge (HBIL sec. 3.3): exact round trips for
 * odd sizes, sub-image sizes, the layout, and the 8-bit variant.
 */
#include <stdlib.h>
#include "check.h"
#include "gi/interleave.h"

static void round_trip(int w, int h)
{
    size_t n = (size_t)w * h, i, total = 0;
    tg_real *a = malloc(n * sizeof(tg_real)), *s = malloc(n * sizeof(tg_real)), *b = malloc(n * sizeof(tg_real));
    uint8_t *a8 = malloc(n), *s8 = malloc(n), *b8 = malloc(n);
    int ii, jj, bad = 0;
    for (i = 0; i < n; i++) { a[i] = tg_from_int((int)i * 7 - 3); a8[i] = (uint8_t)(i * 13 + 1); b[i] = TG_REAL_MAX; b8[i] = 0; }
    tgi_interleave_split(a, w, h, s);
    tgi_interleave_merge(s, w, h, b);
    tgi_interleave_split8(a8, w, h, s8);
    tgi_interleave_merge8(s8, w, h, b8);
    for (i = 0; i < n; i++) bad += a[i] != b[i] || a8[i] != b8[i];
    CHECK(bad == 0, "%dx%d: %d pixels differ after split/merge", w, h, bad);
    /* sub (i, j) holds full-res (4x + i, 4y + j) */
    for (jj = 0; jj < 4; jj++)
        for (ii = 0; ii < 4; ii++) {
            int sw, sh, x, y;
            size_t off;
            tgi_interleave_sub_rect(w, h, ii, jj, &sw, &sh, &off);
            CHECK(off == total, "%dx%d sub (%d,%d) offset %zu, expected %zu", w, h, ii, jj, off, total);
            CHECK(sw == (w > ii ? (w - ii + 3) / 4 : 0) && sh == (h > jj ? (h - jj + 3) / 4 : 0), "%dx%d sub size", w, h);
            for (y = 0; y < sh; y++)
                for (x = 0; x < sw; x++)
                    CHECK(s[off + (size_t)y * sw + x] == a[(size_t)(4 * y + jj) * w + 4 * x + ii], "%dx%d layout", w, h);
            total += (size_t)sw * sh;
        }
    CHECK(total == n, "%dx%d: sub-images hold %zu of %zu pixels", w, h, total, n);
    free(a); free(s); free(b); free(a8); free(s8); free(b8);
}

TEST(round_trip_odd_sizes)
{
    round_trip(1, 1); round_trip(3, 5); round_trip(5, 3); round_trip(17, 9);
    round_trip(2, 7); round_trip(320, 240); round_trip(321, 243);
}

/* Row ranges compose: split in two halves equals one split. */
TEST(row_ranges)
{
    int w = 17, h = 9;
    size_t n = (size_t)w * h, i;
    tg_real a[17 * 9], s1[17 * 9], s2[17 * 9];
    for (i = 0; i < n; i++) a[i] = tg_from_int((int)i);
    tgi_interleave_split(a, w, h, s1);
    memset(s2, 0, sizeof s2);
    tgi_interleave_split_rows(a, w, h, s2, 5, 9);
    tgi_interleave_split_rows(a, w, h, s2, 0, 5);
    CHECK(memcmp(s1, s2, sizeof s1) == 0, "split by row ranges differs");
}

int main(void)
{
    RUN(round_trip_odd_sizes);
    RUN(row_ranges);
    return check_summary();
}
