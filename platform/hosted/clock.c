/* SPDX-License-Identifier: MIT */
/*
 * clock.c - the monotonic clock (POSIX clock_gettime(CLOCK_MONOTONIC)).
 */
#include <time.h>
#include "clock.h"

double tgp_clock_seconds(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_MONOTONIC, &ts) != 0) return 0.0;
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}
