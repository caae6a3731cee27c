/* SPDX-License-Identifier: MIT */
/*
 * denoise.h - the depth- and normal-aware spatial filter over the 4x4
 * neighbourhood of the interleaved kernel's results (HBIL sec. 3.3-3.4).
 *
 * A 5x5 window with 1-D weights (1/2, 1, 1, 1, 1/2), which gives each of
 * the 16 interleaved direction patterns the same total weight (the 32
 * directions are merged evenly, and the window is symmetric), times
 *   w_depth  = 1 - |z_j - z_i| / (tol z_i), clamped at 0
 *   w_normal = max(0, n_i . n_j)^8
 * AO, bent normal and near-field irradiance are filtered; the bent normal is
 * renormalised (the cone is HBIL eq. 12 of the filtered AO when read).
 *
 * The filter reads the unfiltered results and gives filtered values
 * elsewhere, so it needs no scratch and any split of the rows gives the same
 * result: per pixel where they are used (tgi_denoise_pixel: the frame's
 * compose), or rows into another results view (tgi_denoise_rows).  Sky
 * pixels keep their values.
 */
#ifndef TG_DENOISE_H
#define TG_DENOISE_H

#include "../raster/gview.h"

typedef struct tgi_denoise_params {
    tg_real depth_tolerance;   /* relative; default 0.1 */
} tgi_denoise_params;

void tgi_denoise_defaults(tgi_denoise_params *p);

/* tgi_gr_get and tgi_gr_put (raster/gview.h) for the channels the build
 * keeps: a build with TG_NO_BENT_NORMALS has no bent normal, one with
 * TG_NO_COLOR no near field (tinygi.h "FEATURE SWITCHES"; the plan never
 * gives results those planes), and their storage code is not compiled in.
 * The same values as tgi_gr_get and tgi_gr_put otherwise. */
static inline tgi_gr_value tgi_gr_get_kept(const tgi_gresult *r, size_t i)
{
    tgi_gr_value v;
    v.ao = r->ao ? tgi_gr_ao(r, i) : TG_ONE;
    v.bent = !TG_NO_BENT_NORMALS && tgi_gr_has_bent(r) ? tgi_gr_bent(r, i) : tg_v3(0, 0, 0);
    v.near = !TG_NO_COLOR && tgi_gr_has_near(r) ? tgi_gr_near(r, i) : tg_v3(0, 0, 0);
    return v;
}
static inline void tgi_gr_put_kept(const tgi_gresult *r, size_t i, const tgi_gr_value *v)
{
    if (r->ao) tgi_gr_set_ao(r, i, v->ao);
    if (!TG_NO_BENT_NORMALS && tgi_gr_has_bent(r)) tgi_gr_set_bent(r, i, v->bent);
    if (!TG_NO_COLOR && tgi_gr_has_near(r)) tgi_gr_set_near(r, i, v->near);
}

/* The 5x5 windows of a band of TGI_DENOISE_BAND rows, walked along the
 * band: the columns a pixel shares with the pixels before it are not
 * decoded again, in its own row nor in the band's other rows (each pixel
 * (TGI_DENOISE_BAND + 4) / TGI_DENOISE_BAND times instead of 5, once for
 * each row whose window holds it).  The bands are the rows base + TGI_DENOISE_BAND b, base the first
 * row the walk is asked for.  Any order of calls gives the same values; the
 * fast one is band by band, in each band column by column (x increasing),
 * the band's rows in any order (tgi_denoise_band gives a band's rows).
 * Tap (column xx, row yy) is entry (yy - band + 2) * 5 + xx % 5 of the
 * planes below, one plane per value, so that a pixel's 25 taps are
 * contiguous entries (from (y - band) * 5: denoise.c), the weights of all
 * taps one loop over contiguous values and a tap's sums read contiguous
 * values in float (in Q16.16 on 64-bit cores the results too a plane per
 * value, on x86-64 an entry's values together: v below) (TGI_DENOISE_TAPS: the band's entries and 3 more, which stay 0,
 * so that a pixel's entries and the 3 after them are 28, a multiple of 4). */
#ifndef TGI_DENOISE_BAND
/* 4 rows on 32-bit cores: the walk is 2080 bytes of stack in float and
 * 2088 in Q16.16 (its normals' words, and 7 values an entry, not 8), 1360
 * with 1 row (a build for size, TG_OUTLINE_HELPERS, keeps that, as before:
 * README "Porting").  16 rows on 64-bit hosts (pointers past 32 bits, as
 * tinygi.h's TGI_CORE64, which only Q16.16 defines), whose stacks
 * are large (the rasterizer's vertex cache alone takes 54-65 KB there):
 * 4960 bytes in float, 4968 in Q16.16 (5392 on x86-64: TGI_DENOISE_LANES'
 * 8 lanes an entry), and each pixel decoded (16 + 4) /
 * 16 times, not (4 + 4) / 4; a thread's row range, which starts its own
 * bands, is then mostly one band (callgrind, render --size 160x120
 * --frames 2, --threads 1: cornell float 492.10M -> 489.32M, Q16.16
 * 677.39M -> 674.13M, columns 211.52M -> 208.59M, 304.58M -> 300.87M;
 * --threads 2: cornell 494.67M -> 492.72M, 680.62M -> 678.37M, columns
 * 216.74M -> 214.75M, 311.28M -> 308.74M; 8 rows, 3040 bytes, took about
 * half of that: 490.21M, 675.17M, 209.38M, 301.88M with one thread). */
#define TGI_DENOISE_BAND (TG_OUTLINE_HELPERS ? 1 : UINTPTR_MAX > 0xFFFFFFFFu ? 16 : 4)
#endif
#define TGI_DENOISE_TAPS ((TGI_DENOISE_BAND + 4) * 5 + 3)
#define TGI_DENOISE_VALUES 7        /* AO, bent normal x y z, near field r g b */
/* TGI_DENOISE_LANES: Q16.16 on x86-64 (whose SSE2 every such core has),
 * where the filter's sums take two exact 64-bit products of 32-bit lanes
 * an instruction (pmuludq, a GCC and clang builtin, no header: denoise.c
 * weigh_entry; __builtin_shufflevector: clang, GCC 12 on); elsewhere a
 * product an instruction */
#if TGI_Q16_WIDE && defined(__GNUC__) && defined(__SSE2__) && defined(__x86_64__) && (defined(__clang__) || __GNUC__ >= 12)
#define TGI_DENOISE_LANES 1
#else
#define TGI_DENOISE_LANES 0
#endif
typedef struct tgi_denoise_walk {
    int base, band, lo, next;       /* the band's first row; its columns [lo, next) are decoded */
    tg_real z[TGI_DENOISE_TAPS];    /* view depth; 0 on sky, which no centre's depth test passes */
    tg_real nx[TGI_DENOISE_TAPS], ny[TGI_DENOISE_TAPS], nz[TGI_DENOISE_TAPS];   /* G-buffer normal (0 on sky) */
#if TGI_Q16_WIDE && !TG_WIDE_STORAGE
    /* the normal's stored code (tgi_gv_normal_word, below 2^22); UINT32_MAX,
     * which no code is, on sky.  4 bytes as z's: one base register for both */
    uint32_t nkey[TGI_DENOISE_TAPS];
    uint32_t same_key, same;        /* a centre's code and its own normal weight (denoise.c) */
#elif TGI_Q16_WIDE
    uint64_t nkey[TGI_DENOISE_TAPS];    /* the normal as one word (denoise.c normal_key) */
#endif
#if TGI_DENOISE_LANES
    /* the kept results as tgi_gr_get_kept reads them, an entry's 7 values
     * as unsigned 32-bit lanes biased by 2^31 (value + 2^31: lane ^
     * 2^31), then 1 (the weights' sum's lane): two vectors of 4, whose
     * products by a tap's weight are SSE2's 32 x 32 -> 64-bit multiplies
     * (denoise.c weigh_entry) */
    uint32_t v[TGI_DENOISE_TAPS][TGI_DENOISE_VALUES + 1] __attribute__((aligned(16)));
#elif TGI_Q16_WIDE
    /* the kept results as tgi_gr_get_kept reads them, a plane per value
     * (value c of entry j at v[c][j]): indexed as z is, one base register
     * for all the planes a tap reads; the planes of a channel the results
     * lack are left as they are (denoise.c tap_load) */
    tg_real v[TGI_DENOISE_VALUES][TGI_DENOISE_TAPS];
#else
    /* the kept results as tgi_gr_get_kept reads them; an 8th value makes an
     * entry two of the float build's vectors of 4: 1 there (a tap's weight
     * times it is its weight, the weights' sum), unused (0) in Q16.16 */
    tg_real v[TGI_DENOISE_TAPS][TGI_DENOISE_VALUES + 1];
#endif
} tgi_denoise_walk;

/* The first row of the band of row y (bands from row base), and the end
 * of the band of row y within y1: rows [y, end) are the rows to filter
 * together, column by column, for the fewest decodes. */
static inline int tgi_denoise_band_of(int base, int y)
{
    int m = (y - base) % TGI_DENOISE_BAND;
    return y - (m < 0 ? m + TGI_DENOISE_BAND : m);
}
static inline int tgi_denoise_band(const tgi_denoise_walk *k, int y, int y1)
{
    int end = tgi_denoise_band_of(k->base < 0 ? y : k->base, y) + TGI_DENOISE_BAND;
    return end < y1 ? end : y1;
}

void tgi_denoise_walk_start(tgi_denoise_walk *k);

/* The G-buffer normal of surface pixel (x, y) as tgi_denoise_pixel, just
 * called for it, decoded it into the walk (its window's centre entry):
 * tgi_gv_normal's, without decoding it again. */
static inline tg_vec3 tgi_denoise_centre_normal(const tgi_denoise_walk *k, int x, int y)
{
    int e = (y - k->band + 2) * 5 + x % 5;
    return tg_v3(k->nx[e], k->ny[e], k->nz[e]);
}

/* The filtered values of pixel (x, y) of view g from the results r (indexed
 * like g); k: the walk (tgi_denoise_walk_start), kept between calls. */
tgi_gr_value tgi_denoise_pixel(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r,
                               tgi_denoise_walk *k, int x, int y);

/* Rows [y0, y1) of the filtered results of r into out (indexed like g, not r). */
void tgi_denoise_rows(const tgi_denoise_params *p, const tgi_gview *g, const tgi_gresult *r, const tgi_gresult *out,
                      int y0, int y1);

#endif
