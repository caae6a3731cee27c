/* SPDX-License-Identifier: MIT */
/*
 * startup.c - what runs before main() on a bare-metal core, and after it:
 * the entry (a Cortex-M vector table, or a RISC-V entry and trap vector),
 * copy .data from flash, zero .bss, switch the FPU on when there is one,
 * argv from the semihosting command line, main(), and the exit status back
 * to the host.
 *
 *   Cortex-M  boots from address 0: word 0 is the initial stack pointer,
 *             word 1 the reset handler (tgp_vectors, section .vectors).
 *   RISC-V    starts at the ELF entry (QEMU virt, -bios none), the first
 *             code in .vectors: it sets sp and gp and the trap vector in
 *             assembly, then enters C; runs in machine mode.
 *
 * Symbols come from the linker script (sections.ld): __stack_top and
 * __stack_limit, __data_start/__data_end/__data_load, __bss_start__ and
 * __bss_end__ (and __global_pointer$ on RISC-V).  The stack is painted
 * before main() and the deepest use is reported after it ("startup: stack
 * N of M bytes used").  Keep the entry under --gc-sections with
 * -Wl,--undefined=tgp_vectors (Cortex-M) or =Reset_Handler (RISC-V).
 */
#include <stdint.h>
#include <stddef.h>

#include "semihost.h"

int main(int argc, char **argv);
void Reset_Handler(void);
void tgp_fault_handler(void);
void tgp_start(void);

extern uint32_t __stack_top, __data_start, __data_end, __data_load;
extern uint32_t __bss_start__, __bss_end__, __stack_limit;

#define STACK_PAINT 0x5AC35AC3u

#ifdef TG_BM_NEWLIB
#include <stdio.h>
extern void initialise_monitor_handles(void); /* newlib's librdimon */
#endif

/* Append the decimal digits of v to line at *at. */
static void put_decimal(char *line, int *at, uint32_t v)
{
    char digits[12];
    int n = 0;
    do {
        digits[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    while (n) line[(*at)++] = digits[--n];
}

static void put_text(char *line, int *at, const char *s)
{
    while (*s) line[(*at)++] = *s++;
}

#if defined(__riscv)
/* ---- RISC-V (machine mode) ---- */
#include "zicsr.h"

/* sp to the top of RAM, gp for the linker's gp-relative relaxation (set
 * with relaxation off, or it would be relaxed against itself), every trap
 * to tgp_fault_handler, then C. */
__asm__(".section .vectors, \"ax\"\n"
        ".globl Reset_Handler\n"
        "Reset_Handler:\n"
        "    la sp, __stack_top\n"
        "    .option push\n"
        "    .option norelax\n"
        "    la gp, __global_pointer$\n"
        "    .option pop\n"
        "    la t0, tgp_fault_handler\n"
        "    .option push\n"
        "    .option arch, +zicsr\n" /* CSR access is an extension for binutils >= 2.38 */
        "    csrw mtvec, t0\n"
        "    .option pop\n"
        "    j tgp_start\n"
        ".text\n");

/* mtvec in direct mode needs a 4-byte aligned handler.  A trap while the
 * handler runs (semihosting disabled: its ebreak traps too) just stops. */
__attribute__((aligned(4))) void tgp_fault_handler(void)
{
    static int entered;
    char line[64];
    int at = 0;
    uint32_t cause;
    if (entered++)
        for (;;) __asm__ volatile("wfi");
    __asm__ volatile(ZICSR("csrr %0, mcause") : "=r"(cause));
    put_text(line, &at, "tinygi: fault (trap, mcause ");
    put_decimal(line, &at, cause);
    put_text(line, &at, ")\n");
    line[at] = 0;
    sh_write0(line);
    sh_exit(4);
}

static void fpu_on(void)
{
#if defined(__riscv_flen)
    /* mstatus.FS = Initial: with FS Off, the first float instruction is an
     * illegal-instruction trap.  fcsr 0: round to nearest even. */
    __asm__ volatile(ZICSR("csrs mstatus, %0\n\tcsrw fcsr, zero") : : "r"(1u << 13) : "memory");
#endif
}

#else
/* ---- Cortex-M ---- */
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

static void fpu_on(void)
{
#if defined(__ARM_FP)
    /* CPACR: full access to coprocessors 10 and 11 (the FPU) before the
     * first float instruction, which would otherwise fault. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
#endif
}

void Reset_Handler(void) { tgp_start(); }
#endif

/* ---- both ---- */
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
    char line[64];
    uint32_t *p = &__stack_limit;
    uint32_t used, size = (uint32_t)((uintptr_t)&__stack_top - (uintptr_t)&__stack_limit);
    int at = 0;
    while (p < &__stack_top && *p == STACK_PAINT) p++;
    used = (uint32_t)((uintptr_t)&__stack_top - (uintptr_t)p);
    put_text(line, &at, "startup: stack ");
    put_decimal(line, &at, used);
    put_text(line, &at, " of ");
    put_decimal(line, &at, size);
    put_text(line, &at, " bytes used\n");
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

/* From reset to exit, once the stack pointer is set. */
void tgp_start(void)
{
    static char cmdline[256];
    static char *argv[16];
    uint32_t *src = &__data_load, *dst;
    int argc, status;

    fpu_on();
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
