/* SPDX-License-Identifier: MIT */
/*
 * semihost.c - the semihosting calls of semihost.h, for any Cortex-M
 * (ARMv6-M and ARMv7-M both have `bkpt`) and for 32-bit RISC-V (the RISC-V
 * semihosting spec uses ARM's operations and argument blocks).  No libc:
 * this file is what the Cortex-M0 and RISC-V targets use for all their I/O.
 */
#include "semihost.h"

#include <stdint.h>

enum {
    SYS_OPEN = 0x01, SYS_CLOSE = 0x02, SYS_WRITE0 = 0x04, SYS_WRITE = 0x05,
    SYS_CLOCK = 0x10, SYS_GET_CMDLINE = 0x15, SYS_EXIT = 0x18,
    SYS_EXIT_EXTENDED = 0x20
};
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u
#define SH_OPEN_MODE_WB 5 /* fopen modes: r, rb, r+, r+b, w, wb, ... */

#if defined(__riscv)
/* RISC-V: a0 = operation, a1 = argument block; the trap is an `ebreak`
 * between two no-op shifts, all three uncompressed (RISC-V Semihosting,
 * version 0.2, sec. 2.1), so the debugger can tell it from a breakpoint. */
static int sh_call(int op, const void *arg)
{
    register int a0 __asm__("a0") = op;
    register const void *a1 __asm__("a1") = arg;
    __asm__ volatile(".option push\n\t.option norvc\n\t"
                     "slli x0, x0, 0x1f\n\tebreak\n\tsrai x0, x0, 7\n\t"
                     ".option pop"
                     : "+r"(a0) : "r"(a1) : "memory");
    return a0;
}
#else
/* Cortex-M: r0 = operation, r1 = argument block, `bkpt 0xAB`. */
static int sh_call(int op, const void *arg)
{
    register int r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}
#endif

static size_t sh_strlen(const char *s)
{
    size_t n = 0;
    while (s[n]) n++;
    return n;
}

void sh_write0(const char *s) { sh_call(SYS_WRITE0, s); }

int sh_open_write(const char *path)
{
    uintptr_t block[3];
    block[0] = (uintptr_t)path;
    block[1] = SH_OPEN_MODE_WB;
    block[2] = sh_strlen(path);
    return sh_call(SYS_OPEN, block);
}

int sh_write(int handle, const void *buf, size_t n)
{
    uintptr_t block[3];
    block[0] = (uintptr_t)handle;
    block[1] = (uintptr_t)buf;
    block[2] = n;
    return sh_call(SYS_WRITE, block) == 0 ? 0 : -1; /* returns bytes NOT written */
}

int sh_close(int handle)
{
    uintptr_t block[1];
    block[0] = (uintptr_t)handle;
    return sh_call(SYS_CLOSE, block);
}

int sh_get_cmdline(char *buf, size_t size)
{
    uintptr_t block[2];
    block[0] = (uintptr_t)buf;
    block[1] = size;
    return sh_call(SYS_GET_CMDLINE, block);
}

long sh_clock(void) { return sh_call(SYS_CLOCK, 0); }

void sh_exit(int status)
{
    uintptr_t block[2];
    block[0] = ADP_STOPPED_APPLICATION_EXIT;
    block[1] = (uintptr_t)status;
    sh_call(SYS_EXIT_EXTENDED, block);
    /* Hosts without the extension: plain exit (status 0 or 1 only). */
    sh_call(SYS_EXIT, (const void *)(uintptr_t)(status == 0 ? ADP_STOPPED_APPLICATION_EXIT : 0x20024u));
    for (;;) {
    }
}
