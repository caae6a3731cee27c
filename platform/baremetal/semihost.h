/* SPDX-License-Identifier: MIT */
/*
 * semihost.h - ARM semihosting: the debugger (here QEMU) performs I/O for a
 * bare-metal program.  A call is `bkpt 0xAB` on Cortex-M with the operation
 * in r0 and a pointer to its argument block in r1 (ARM "Semihosting for
 * AArch32 and AArch64", version 2); on RISC-V it is the sequence
 * `slli x0,x0,0x1f; ebreak; srai x0,x0,7` with a0 and a1, and the same
 * operations (RISC-V Semihosting, version 0.2).  Only what tinygi's bare-metal driver
 * needs: write text, open/write/close a host file, read the command line,
 * read a clock, and exit with a status.
 *
 * QEMU must run with `-semihosting-config enable=on,target=native`, or the
 * first call is a lockup (Cortex-M) or a breakpoint trap (RISC-V: startup.c
 * reports it as a fault, which cannot be printed either).
 */
#ifndef TG_SEMIHOST_H
#define TG_SEMIHOST_H

#include <stddef.h>

/* Write a NUL-terminated string to the host's console (stderr of QEMU). */
void sh_write0(const char *s);
/* Open a host file for writing in binary ("wb"); returns a handle >= 0 or -1. */
int sh_open_write(const char *path);
/* Write n bytes; returns 0 when all were written. */
int sh_write(int handle, const void *buf, size_t n);
int sh_close(int handle);
/* The command line QEMU was given with -semihosting-config arg=...; the
 * first word is the program name.  Returns 0 on success. */
int sh_get_cmdline(char *buf, size_t size);
/* Centiseconds since the program started. */
long sh_clock(void);
/* End the program; QEMU exits with `status` (SYS_EXIT_EXTENDED). */
void sh_exit(int status);

#endif
