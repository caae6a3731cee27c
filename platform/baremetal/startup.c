/* SPDX-License-Identifier: MIT */
/*
 * startup.c - what runs before main() on a Cortex-M: the vector table (the
 * core boots from address 0: word 0 is the initial stack pointer, word 1
 * the reset handler), the reset handler (copy .data from flash, zero .bss,
 * switch the FPU on when there is one), argv from the semihosting command
 * line, and the exit status back to the host.
 *
 * Symbols come from the linker script (sections.ld): __stack_top and
 * __stack_limit, __data_start/__data_end/__data_load, __bss_start__ and
 * __bss_end__.  The stack is painted before main() and the deepest use is
 * reported after it ("startup: stack N of M bytes used").
 * Keep the table under --gc-sections with -Wl,--undefined=tgp_vectors.
 */
#include <stdint.h>
#include <stddef.h>

#include "semihost.h"

int main(int argc, char **argv);
void Reset_Handler(void);
void tgp_fault_handler(void);

extern uint32_t __stack_top, __data_start, __data_end, __data_load;
extern uint32_t __bss_start__, __bss_end__, __stack_limit;

#define STACK_PAINT 0x5AC35AC3u

#ifdef TG_BM_NEWLIB
#include <stdio.h>
extern void initialise_monitor_handles(void); /* newlib's librdimon */
#endif

typedef void (*tgp_vector)(void);

/* 16 system vectors; tinygi uses no peripheral interrupts. */
__attribute__((section(".vectors"), used))
const tgp_vector tgp_vectors[16] = {
    (tgp_vector)(uintptr_t)&__stack_top, /* 0: initial SP */
    Reset_Handler,                      /* 1: reset */
    tgp_fault_handler,                   /* 2: NMI */
    tgp_fault_handler,                   /* 3: HardFault */
    tgp_fault_handler,                   /* 4: MemManage (v7-M) */
    tgp_fault_handler,                   /* 5: BusFault (v7-M) */
    tgp_fault_handler,                   /* 6: UsageFault (v7-M) */
    0, 0, 0, 0,                         /* 7-10: reserved */
    tgp_fault_handler,                   /* 11: SVCall */
    tgp_fault_handler,                   /* 12: debug monitor */
    0,                                  /* 13: reserved */
    tgp_fault_handler,                   /* 14: PendSV */
    tgp_fault_handler                    /* 15: SysTick */
};

void tgp_fault_handler(void)
{
    sh_write0("tinygi: fault (hard fault, bus fault or usage fault)\n");
    sh_exit(4);
}

/* Fill the unused stack with a pattern, to find the deepest use later.
 * Leaves the 256 bytes below the current stack pointer alone. */
static void paint_stack(void)
{
    uint32_t *p = &__stack_limit, here;
    uint32_t *top = (uint32_t *)(((uintptr_t)&here - 256u) & ~(uintptr_t)3);
    while (p < top) *p++ = STACK_PAINT;
}

/* "startup: stack N of M bytes used" on the console; returns 1 when the
 * whole stack was used (it has probably overflowed into .bss). */
static int report_stack(void)
{
    char line[64], digits[12];
    const char *head = "startup: stack ", *mid = " of ", *tail = " bytes used\n";
    uint32_t *p = &__stack_limit;
    uint32_t used, size = (uint32_t)((uintptr_t)&__stack_top - (uintptr_t)&__stack_limit);
    int n, at = 0, k;
    while (p < &__stack_top && *p == STACK_PAINT) p++;
    used = (uint32_t)((uintptr_t)&__stack_top - (uintptr_t)p);
    for (k = 0; head[k]; k++) line[at++] = head[k];
    for (k = 0; k < 2; k++) {
        uint32_t v = k == 0 ? used : size;
        n = 0;
        do { digits[n++] = (char)('0' + v % 10u); v /= 10u; } while (v);
        while (n) line[at++] = digits[--n];
        if (k == 0) { const char *m = mid; while (*m) line[at++] = *m++; }
    }
    for (k = 0; tail[k]; k++) line[at++] = tail[k];
    line[at] = 0;
    sh_write0(line);
    if (used < size) return 0;
    sh_write0("startup: stack overflow: raise STACK_SIZE in the linker script\n");
    return 1;
}

/* argv from "prog arg1 arg2 ..." (QEMU's -semihosting-config arg=...). */
static int split_cmdline(char *line, char **argv, int max)
{
    int argc = 0;
    char *p = line;
    while (*p && argc < max - 1) {
        while (*p == ' ') *p++ = 0;
        if (!*p) break;
        argv[argc++] = p;
        while (*p && *p != ' ') p++;
    }
    argv[argc] = 0;
    return argc;
}

void Reset_Handler(void)
{
    static char cmdline[256];
    static char *argv[16];
    uint32_t *src = &__data_load, *dst;
    int argc, status;

#if defined(__ARM_FP)
    /* CPACR: full access to coprocessors 10 and 11 (the FPU) before the
     * first float instruction, which would otherwise fault. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
    for (dst = &__data_start; dst < &__data_end;) *dst++ = *src++;
    for (dst = &__bss_start__; dst < &__bss_end__;) *dst++ = 0;
    paint_stack();

#ifdef TG_BM_NEWLIB
    initialise_monitor_handles();
#endif
    if (sh_get_cmdline(cmdline, sizeof cmdline) != 0) cmdline[0] = 0;
    argc = split_cmdline(cmdline, argv, 16);
    if (argc == 0) { argv[0] = (char *)"tinygi"; argv[1] = 0; argc = 1; }
    status = main(argc, argv);
#ifdef TG_BM_NEWLIB
    fflush(0);
#endif
    if (report_stack() && status == 0) status = 5;
    sh_exit(status);
}
