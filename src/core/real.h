/* SPDX-License-Identifier: MIT */
/*
 * real.h - the number type (tg_real, TG_R, the inline arithmetic and the
 * transcendentals) is public API and lives in src/tinygi.h, section "THE
 * NUMBER TYPE"; this header adds the core's internal integer helpers from
 * real.c that the kernels share.
 */
#ifndef TG_REAL_H
#define TG_REAL_H

#include "../tinygi.h"

/* Number of significant bits of v (0 for 0). */
int tgi_bit_length64(uint64_t v);
/* sqrt of a 64-bit integer, floor; used by fixed-point vector lengths. */
uint32_t tgi_isqrt64(uint64_t v);

#endif
