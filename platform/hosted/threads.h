/* SPDX-License-Identifier: MIT */
/*
 * threads.h - a pool of POSIX threads that runs a frame's row ranges
 * (hosted).  The pool's threads are started once and reused by every pass
 * of every frame; tgp_pool_parallel gives the tg_parallel hook to pass to
 * tg_frame_set_parallel.  The thread that calls run works too, so a pool
 * of N threads starts N - 1.
 */
#ifndef TG_HOSTED_THREADS_H
#define TG_HOSTED_THREADS_H

#include <stddef.h>
#include "tinygi.h"

typedef struct tgp_pool tgp_pool;

/* Start a pool of `threads` threads in all (1..TG_MAX_THREADS; 1 starts
 * none: run calls fn on the calling thread).  0 and *pool set, or 1 with
 * *pool NULL and `why` saying why ("threads must be 1..64, got 0", "cannot
 * start a thread: Resource temporarily unavailable"). */
int tgp_pool_create(int threads, tgp_pool **pool, char *why, size_t why_size);
/* Stop and join the threads, free the pool (NULL is allowed).  Not while a
 * run is under way. */
void tgp_pool_destroy(tgp_pool *pool);
/* The hook: run(fn, job, rows) splits [0, rows) into ranges that the
 * threads take one at a time until none is left, long at first and a row
 * or two at the end (an uneven pass still balances), and returns when all
 * have returned.  A run started while
 * another is under way (from inside fn, or from a second thread) calls
 * fn(job, 0, rows) on its own thread. */
tg_parallel tgp_pool_parallel(tgp_pool *pool);
/* Threads in all, the calling one included. */
int tgp_pool_threads(const tgp_pool *pool);
/* The machine's online processors, clamped to 1..TG_MAX_THREADS (the
 * default of `tinygi render --threads`). */
int tgp_cores(void);

#endif
