/* SPDX-License-Identifier: MIT */
/*
 * clock.h - a monotonic clock for progress and benchmarks (hosted).
 */
#ifndef TG_HOSTED_CLOCK_H
#define TG_HOSTED_CLOCK_H

/* Seconds since an arbitrary fixed point; never goes backwards. */
double tgp_clock_seconds(void);

#endif
