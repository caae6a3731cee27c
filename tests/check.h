/* SPDX-License-Identifier: MIT */
/*
 * check.h - the tests' tiny harness (hosted code: stdio and libm allowed).
 *
 *   TEST(name) { CHECK(cond, "fmt", ...); CHECK_NEAR(a, b, tol); }
 *   int main(void) { RUN(name); ...; return check_summary(); }
 *
 * Each RUN prints "ok NUMBER/FILE/name" or "FAIL NUMBER/FILE/name"; the last
 * line "TESTS passed N failed M" is summed by tests/run.sh.
 */
#ifndef TG_CHECK_H
#define TG_CHECK_H

#include <stdio.h>
#include <math.h>
#include <string.h>
#include "tinygi.h"

static int check_tests_passed, check_tests_failed, check_current_failures;
static const char *check_current_name = "";

#define TEST(name) static void name(void)

#define CHECK(cond, ...)                                                      \
    do {                                                                      \
        if (!(cond)) {                                                        \
            check_current_failures++;                                         \
            if (check_current_failures <= 10) {                               \
                fprintf(stderr, "%s:%d: %s: check failed: %s: ", __FILE__,    \
                        __LINE__, check_current_name, #cond);                 \
                fprintf(stderr, __VA_ARGS__);                                 \
                fputc('\n', stderr);                                          \
            }                                                                 \
        }                                                                     \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                 \
    CHECK(fabs((double)(a) - (double)(b)) <= (double)(tol),                   \
          "%.9g vs %.9g (tolerance %.3g)", (double)(a), (double)(b), (double)(tol))

#define RUN(name)                                                             \
    do {                                                                      \
        check_current_name = #name;                                           \
        check_current_failures = 0;                                           \
        name();                                                               \
        if (check_current_failures == 0) {                                    \
            check_tests_passed++;                                             \
            printf("ok %s/%s/%s\n", TG_NUMBER_NAME, check_file_name(__FILE__), #name); \
        } else {                                                              \
            check_tests_failed++;                                             \
            printf("FAIL %s/%s/%s (%d checks failed)\n", TG_NUMBER_NAME,      \
                   check_file_name(__FILE__), #name, check_current_failures); \
        }                                                                     \
        fflush(stdout);                                                       \
    } while (0)

static inline const char *check_file_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

static inline int check_summary(void)
{
    printf("TESTS passed %d failed %d\n", check_tests_passed, check_tests_failed);
    return check_tests_failed ? 1 : 0;
}

/* tg_real to double, for comparisons in tests. */
static inline double check_d(tg_real r) { return (double)tg_to_float(r); }

/* tg_real to double exactly (check_d goes through float: 24 bits). */
static inline double check_exact(tg_real r)
{
#if TG_FIXED
    return (double)r / 65536.0;
#else
    return (double)r;
#endif
}

#define CHECK_PI 3.14159265358979323846

/* A unit in the last place of the build's number near 1. */
#if TG_FIXED
#define CHECK_ULP (1.0 / 65536.0)
#else
#define CHECK_ULP 1.2e-7
#endif

/* The tests' linear congruential generator: the next value in [0, 1) of
 * the sequence *state seeds. */
static inline double check_rnd(unsigned *state)
{
    *state = *state * 1103515245u + 12345u;
    return (double)((*state >> 8) & 0xffffff) / 16777216.0;
}

#endif
