/* SPDX-License-Identifier: MIT */
/*
 * counter.c - port_insn_count(): instructions executed so far, for the
 * per-frame cost that render.c reports.  Under QEMU the counts come from
 * its virtual clock, which with `-icount shift=N,sleep=off` advances 2^N ns
 * per guest instruction and never follows the host's clock: the same
 * binary gives the same count on any host, under any load.
 *
 *   RISC-V        the instret counter (rdinstret/rdinstreth): instructions
 *                 retired on hardware; under QEMU the virtual clock in ns,
 *                 so run it with -icount shift=0 (without -icount QEMU
 *                 returns host time stamps).
 *   MPS2 boards   (-DTG_BM_MPS2: Cortex-M3 AN385, M4F AN386, and the M0
 *                 code counted there) the FPGAIO counters, 25 MHz of
 *                 virtual time; run with -icount shift=7 (below).  QEMU
 *                 emulates no DWT cycle counter; on a real Cortex-M3/M4
 *                 read DWT->CYCCNT (cycles) instead.
 *   anything else 0: no counter (Linux targets, the micro:bit).
 */
#include "port.h"

#if defined(__riscv) && __riscv_xlen == 32
#include "zicsr.h"

uint64_t port_insn_count(void)
{
    uint32_t hi, lo, again;
    do { /* the low word can carry into the high one between the reads */
        __asm__ volatile(ZICSR("rdinstreth %0") : "=r"(hi));
        __asm__ volatile(ZICSR("rdinstret %0") : "=r"(lo));
        __asm__ volatile(ZICSR("rdinstreth %0") : "=r"(again));
    } while (hi != again);
    return ((uint64_t)hi << 32) | lo;
}
#elif defined(TG_BM_MPS2)
#define MPS2_FPGAIO_CLK1HZ (*(volatile const uint32_t *)0x40028010u)
#define MPS2_FPGAIO_COUNTER (*(volatile const uint32_t *)0x40028018u)
#define MPS2_TICKS_PER_SECOND 25000000 /* COUNTER: 40 ns a tick */
#define MPS2_NS_PER_TICK 40u
#define MPS2_NS_PER_INSN 128u /* -icount shift=7 */
#define MPS2_CALIBRATION_INSNS 501u /* MPS2_CALIBRATION_LOOP */
#if defined(__thumb2__) /* GCC's inline assembly: unified syntax */
#define MPS2_CALIBRATION_LOOP "movs r0, #250\n1:\tsubs r0, #1\n\tbne 1b"
#else /* Thumb-1 (the M0 code): divided syntax, where mov and sub set the flags */
#define MPS2_CALIBRATION_LOOP "mov r0, #250\n1:\tsub r0, #1\n\tbne 1b"
#endif

/* COUNTER ticks since reset in 64 bits: the 32-bit COUNTER wraps every
 * 172 s of virtual time (1.3G instructions), so the wraps are counted from
 * CLK1HZ, the whole seconds since reset. */
static uint64_t mps2_ticks(void)
{
    int64_t seconds = (int64_t)MPS2_FPGAIO_CLK1HZ;
    int64_t ticks = (int64_t)MPS2_FPGAIO_COUNTER;
    /* the true count is ticks + k 2^32, at most one second past seconds */
    int64_t wraps = (seconds * MPS2_TICKS_PER_SECOND - ticks + ((int64_t)1 << 31)) >> 32;
    return (uint64_t)ticks + ((uint64_t)wraps << 32);
}

/* Whether QEMU runs with -icount shift=7: a loop of a known number of
 * instructions takes 3.2 ticks each (plus the reads around it). */
static int mps2_counting(uint64_t *first)
{
    uint64_t ticks;
    *first = mps2_ticks();
    __asm__ volatile(MPS2_CALIBRATION_LOOP ::: "r0", "cc");
    ticks = mps2_ticks() - *first;
    return ticks * MPS2_NS_PER_TICK >= MPS2_CALIBRATION_INSNS * MPS2_NS_PER_INSN &&
           ticks * MPS2_NS_PER_TICK <= (MPS2_CALIBRATION_INSNS + 100u) * MPS2_NS_PER_INSN;
}

/* Instructions since the first call.  A tick (40 ns) is less than half an
 * instruction (128 ns), so rounding the ticks since one reading gives the
 * exact instructions since that reading, whatever the phase of the tick
 * clock against the instructions (that phase moved between runs when one
 * instruction was one ns). */
uint64_t port_insn_count(void)
{
    static int state; /* 0 not yet known, 1 counting, -1 no usable counter */
    static uint64_t first;
    if (state == 0) state = mps2_counting(&first) ? 1 : -1;
    if (state < 0) return 0;
    return ((mps2_ticks() - first) * MPS2_NS_PER_TICK + MPS2_NS_PER_INSN / 2u) / MPS2_NS_PER_INSN;
}
#else
uint64_t port_insn_count(void) { return 0; }
#endif
