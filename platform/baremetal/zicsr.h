/* SPDX-License-Identifier: MIT */
/*
 * zicsr.h - ZICSR("csrr ...") wraps RISC-V inline assembly that reads or
 * writes a CSR.  Since binutils 2.38 the CSR instructions belong to the
 * Zicsr extension, which -march=rv32imac does not name; naming it
 * (rv32imac_zicsr) would make GCC 12 miss its rv32imac multilib (libgcc,
 * the C library).  So the extension is switched on for these lines only.
 */
#ifndef TG_ZICSR_H
#define TG_ZICSR_H

#define ZICSR(insns) ".option push\n\t.option arch, +zicsr\n\t" insns "\n\t.option pop"

#endif
