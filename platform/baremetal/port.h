/* SPDX-License-Identifier: MIT */
/*
 * port.h - the few functions a target must provide for tinygi's render
 * driver (render.c): write a file, print a line, read a clock, count
 * instructions.  The core itself needs nothing at all; these are the
 * driver's.
 *
 *   port_stdio.c     any C library with stdio (Linux, newlib + librdimon)
 *   port_semihost.c  bare metal with no C library (semihosting calls)
 *   counter.c        the instruction counter, per machine (0 on Linux)
 */
#ifndef TG_PORT_H
#define TG_PORT_H

#include <stddef.h>
#include <stdint.h>

/* Open a file for binary writing; returns a handle >= 0, or -1. */
int port_open(const char *path);
/* Write n bytes; 0 on success. */
int port_write(int handle, const void *data, size_t n);
/* Close; 0 on success (an error means the file is incomplete). */
int port_close(int handle);
/* Print a line of text (a newline is added) to the console. */
void port_log(const char *line);
/* Centiseconds from some fixed start, for timing only (0 if unknown). */
long port_clock_cs(void);
/* Instructions executed since some fixed start, for measuring cost only;
 * 0 when the machine has no such counter.  Deterministic under QEMU with
 * -icount shift=0 (see counter.c). */
uint64_t port_insn_count(void);

#endif
