/* SPDX-License-Identifier: MIT */
/*
 * threads.c - the row-range pool (POSIX threads).
 *
 * One job at a time: run() posts fn, job and rows under the pool's lock,
 * wakes the workers and works itself.  Every thread takes the next range
 * of rows under the lock (a counter), runs fn on it without the lock, and
 * counts its rows done under the lock.  run() returns when every row is
 * done: the lock orders every write of fn before the caller's next read.
 * Workers sleep on a condition variable between jobs and block every
 * signal, so a signal reaches the thread that started them.
 *
 * The ranges shrink as the rows run out (guided self-scheduling,
 * Polychronopoulos and Kuck 1987): each is ceil(left / (2 threads)) of the
 * `left` rows not yet taken, at most ceil(rows / (4 threads)), so the first
 * are long and few (240 rows on two threads: 19 ranges, 30 rows down to 1)
 * and a thread that draws costly rows near the end keeps the others
 * waiting for a row's time, not a chunk's; the cap keeps costly first rows
 * (columns' top rows, where push/pull fills most holes) out of one long
 * range.  Even chunks of ceil(rows / (8 threads)) rows, before, left one
 * thread a whole chunk alone at a pass's end (cornell --gi-quarter's kernel:
 * 15 chunks of 14M-21M instructions; columns' kernel: 0.9M sky chunks
 * beside 30M ones).  Shorter ranges throughout cost more instead: each
 * call of a pass sets itself up again (HBIL's kernel about 108K
 * instructions, its 16 sub-images'), so one row a range lost more than
 * the balance gained.
 */
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "threads.h"

struct tgp_pool {
    pthread_mutex_t lock;
    pthread_cond_t posted;          /* a new job, or stop */
    pthread_cond_t finished;        /* the job's last chunk is done */
    int threads, started;           /* in all; workers running */
    pthread_t workers[TG_MAX_THREADS];
    /* the job, read and written under lock */
    tg_rows_fn fn;
    void *job;
    int rows, next, done;
    int share, cap;                 /* a range: ceil(left / share) rows, at most cap */
    unsigned long generation;       /* jobs posted so far */
    int busy, stop;
};

/* Take ranges of the current job until no row is left; lock held on
 * entry and on return. */
static void work(tgp_pool *p)
{
    while (p->next < p->rows) {
        tg_rows_fn fn = p->fn;
        void *job = p->job;
        int left = p->rows - p->next;
        int y0 = p->next, n = left / p->share + (left % p->share != 0);   /* 1..left */
        if (n > p->cap) n = p->cap;                                        /* cap >= 1 */
        p->next = y0 + n;
        pthread_mutex_unlock(&p->lock);
        fn(job, y0, y0 + n);
        pthread_mutex_lock(&p->lock);
        p->done += n;
        if (p->done == p->rows) pthread_cond_signal(&p->finished);
    }
}

static void *worker_main(void *arg)
{
    tgp_pool *p = (tgp_pool *)arg;
    unsigned long seen;
    pthread_mutex_lock(&p->lock);
    seen = p->generation;
    for (;;) {
        while (!p->stop && p->generation == seen) pthread_cond_wait(&p->posted, &p->lock);
        if (p->stop) break;
        seen = p->generation;
        work(p);
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

static void pool_run(void *user, tg_rows_fn fn, void *job, int rows)
{
    tgp_pool *p = (tgp_pool *)user;
    if (rows <= 0) return;
    if (p->started == 0 || rows == 1) {
        fn(job, 0, rows);
        return;
    }
    pthread_mutex_lock(&p->lock);
    if (p->busy) { /* a run inside a run: this thread does it all */
        pthread_mutex_unlock(&p->lock);
        fn(job, 0, rows);
        return;
    }
    p->busy = 1;
    p->fn = fn;
    p->job = job;
    p->rows = rows;
    p->cap = rows / (2 * p->share) + (rows % (2 * p->share) != 0);
    p->next = p->done = 0;
    p->generation++;
    pthread_cond_broadcast(&p->posted);
    work(p);
    while (p->done < p->rows) pthread_cond_wait(&p->finished, &p->lock);
    p->busy = 0;
    pthread_mutex_unlock(&p->lock);
}

/* Stop and join the workers started so far. */
static void stop_workers(tgp_pool *p)
{
    int i;
    pthread_mutex_lock(&p->lock);
    p->stop = 1;
    pthread_cond_broadcast(&p->posted);
    pthread_mutex_unlock(&p->lock);
    for (i = 0; i < p->started; i++) pthread_join(p->workers[i], NULL);
    p->started = 0;
}

static void release(tgp_pool *p)
{
    pthread_cond_destroy(&p->finished);
    pthread_cond_destroy(&p->posted);
    pthread_mutex_destroy(&p->lock);
    free(p);
}

/* Start threads - 1 workers with every signal blocked; 0, or the error. */
static int start_workers(tgp_pool *p)
{
    sigset_t all, old;
    int rc = 0;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    while (p->started < p->threads - 1 && rc == 0) {
        rc = pthread_create(&p->workers[p->started], NULL, worker_main, p);
        if (rc == 0) p->started++;
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc;
}

int tgp_pool_create(int threads, tgp_pool **pool, char *why, size_t why_size)
{
    tgp_pool *p;
    int rc;
    *pool = NULL;
    if (threads < 1 || threads > TG_MAX_THREADS) {
        snprintf(why, why_size, "threads must be 1..%d, got %d", TG_MAX_THREADS, threads);
        return 1;
    }
    p = (tgp_pool *)calloc(1, sizeof *p);
    if (!p) {
        snprintf(why, why_size, "out of memory");
        return 1;
    }
    p->threads = threads;
    p->share = 2 * threads;
    rc = pthread_mutex_init(&p->lock, NULL);
    if (rc == 0 && (rc = pthread_cond_init(&p->posted, NULL)) != 0) pthread_mutex_destroy(&p->lock);
    if (rc == 0 && (rc = pthread_cond_init(&p->finished, NULL)) != 0) {
        pthread_cond_destroy(&p->posted);
        pthread_mutex_destroy(&p->lock);
    }
    if (rc != 0) {
        free(p);
        snprintf(why, why_size, "cannot create the pool's lock: %s", strerror(rc));
        return 1;
    }
    rc = start_workers(p);
    if (rc != 0) {
        stop_workers(p);
        release(p);
        snprintf(why, why_size, "cannot start a thread: %s", strerror(rc));
        return 1;
    }
    *pool = p;
    return 0;
}

void tgp_pool_destroy(tgp_pool *pool)
{
    if (!pool) return;
    stop_workers(pool);
    release(pool);
}

tg_parallel tgp_pool_parallel(tgp_pool *pool)
{
    tg_parallel h;
    h.user = pool;
    h.run = pool_run;
    return h;
}

int tgp_pool_threads(const tgp_pool *pool)
{
    return pool ? pool->threads : 1;
}

int tgp_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1) return 1;
    return n > TG_MAX_THREADS ? TG_MAX_THREADS : (int)n;
}
