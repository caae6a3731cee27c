# SPDX-License-Identifier: MIT
# platform/cross.mk - `make cross`: build tinygi for other machines, run it
# there (qemu-user, qemu-system-arm/-riscv32, or natively for i686) and
# compare every output file byte for byte against x86-64's.  Included by the
# top Makefile.
#
#   make cross            install what is missing, build, run, compare;
#                         ends with "N passed, N failed"
#   make cross-count      instructions per frame of one request (CROSS_COUNT_RUN)
#                         on every bare-metal core, as a table (it shares make
#                         cross's core libraries)
#   make cross-install    only the toolchain/emulator installs (apt-get)
#   make size-table       the Cortex-M4 .text per configuration of the
#                         feature switches, as README "Flash size" shows it
#                         (tools/size_table.sh; SIZE_LTO=1 adds -flto,
#                         SIZE_TOP=N lists the N largest functions)
#   make size-check       the flash budgets (colour program <= 48 KB, AO-only
#                         <= 24 KB of .text, Q16.16 -flto; tools/size_check.sh)
#   make cross CROSS_TARGETS="s390x m3"   a subset (x86_64 always runs)
#
# Targets: x86_64 (reference), i686 (-msse2 -mfpmath=sse), s390x and
# powerpc (big-endian, 64- and 32-bit, qemu-user), m3 (Cortex-M3, QEMU
# mps2-an385, newlib + semihosting), m4f (Cortex-M4F, float on the FPU,
# mps2-an386), m0 (Cortex-M0, QEMU microbit, 16 KB RAM, -nostdlib, -Os,
# fixed point only), m0mps2 (the same M0 code on mps2-an385, in its 16 MB
# PSRAM: full-size frames, instruction counts), rv32 (RV32IMAC, soft float and fixed, QEMU virt,
# picolibc + our semihosting) and rv32f (RV32IMAFC, float on the F
# extension).  The driver is platform/baremetal/render.c on all of them; the
# Linux targets also run the tinygi CLI and tests/test_fbdev.  The
# bare-metal runs print each frame's instruction count (QEMU -icount).
#
# A run is the driver's arguments joined by commas (see render.c); each
# target renders its runs, x86-64 renders every run once per number type,
# and the files are compared.  Per target: the runs (CROSS_<T>_RUNS) and the
# driver's static arena (CROSS_<T>_ARENA, bytes).

comma := ,
space := $() $()
CROSS_BUILD   ?= build-cross
CROSS_TARGETS ?= i686 s390x powerpc m3 m4f m0 m0mps2 rv32 rv32f
CROSS_SCENES  ?= cornell spheres columns
CROSS_SIZE    ?= 64x48
CROSS_FRAMES  ?= 2
CROSS_AOVS    ?= color,depth,normal,albedo,ao,bent,cone,near,far,direct,irradiance,motion
CROSS_SHADOW  ?= 64
# the run of every target (the Linux ones render only this one)
CROSS_RUN     ?= size=$(CROSS_SIZE),frames=$(CROSS_FRAMES),shadow=$(CROSS_SHADOW),aovs=$(subst $(comma),+,$(CROSS_AOVS)),$(subst $(space),$(comma),$(strip $(CROSS_SCENES)))
# every other technique, colour and AO, on the 32-bit cores (soft float,
# the FPU, Q16.16 on ARM and RISC-V); the path tracer only through the CLI
# on the Linux targets (in soft float under QEMU it took 2 minutes of
# RV32 at 32x24)
CROSS_TECHNIQUES ?= gtao hbao ssao vo ssdo bentcone ssilvb reference
CROSS_CLI_TECHNIQUES ?= $(CROSS_TECHNIQUES) pathtrace
CROSS_TECH_RUNS ?= $(foreach t,$(CROSS_TECHNIQUES),size=32x24,frames=2,shadow=32,aovs=color+ao,technique=$(t),cornell)
CROSS_M3_RUNS   ?= $(CROSS_RUN) size=320x240,frames=2,shadow=64,aovs=color,cornell $(CROSS_TECH_RUNS)
CROSS_M4F_RUNS  ?= $(CROSS_RUN) $(CROSS_TECH_RUNS)
CROSS_RV32_RUNS ?= $(CROSS_RUN) $(CROSS_TECH_RUNS)
CROSS_M0MPS2_RUNS ?= $(CROSS_RUN)
# 16 KB of RAM: a full-colour 64x48 frame cannot fit; cornell colour over two
# frames (reprojection) at 12x9, and AO at 24x18
CROSS_M0_RUNS   ?= size=12x9,frames=2,shadow=8,aovs=color,cornell size=24x18,frames=1,shadow=8,aovs=ao+depth+normal,cornell
CROSS_M3_ARENA   ?= 2359296
CROSS_M4F_ARENA  ?= 2097152
CROSS_RV32_ARENA ?= 2097152
CROSS_M0_ARENA   ?= 10240
CROSS_M0MPS2_ARENA ?= 2097152
# make cross-count: every frame's instructions (the M0 code on the MPS2 board)
CROSS_COUNT_RUN   ?= size=160x120,frames=2,shadow=64,aovs=color,cornell
CROSS_COUNT_ARENA ?= 14680064

CROSS_ENV = CROSS_BUILD="$(CROSS_BUILD)" CROSS_TARGETS="$(CROSS_TARGETS)" \
	 CROSS_SCENES="$(CROSS_SCENES)" CROSS_SIZE="$(CROSS_SIZE)" \
	 CROSS_FRAMES="$(CROSS_FRAMES)" CROSS_AOVS="$(CROSS_AOVS)" CROSS_SHADOW="$(CROSS_SHADOW)" \
	 CROSS_RUN="$(CROSS_RUN)" CROSS_M3_RUNS="$(CROSS_M3_RUNS)" CROSS_M4F_RUNS="$(CROSS_M4F_RUNS)" \
	 CROSS_RV32_RUNS="$(CROSS_RV32_RUNS)" CROSS_M0_RUNS="$(CROSS_M0_RUNS)" \
	 CROSS_M3_ARENA="$(CROSS_M3_ARENA)" CROSS_M4F_ARENA="$(CROSS_M4F_ARENA)" \
	 CROSS_RV32_ARENA="$(CROSS_RV32_ARENA)" CROSS_M0_ARENA="$(CROSS_M0_ARENA)" \
	 CROSS_M0MPS2_RUNS="$(CROSS_M0MPS2_RUNS)" CROSS_M0MPS2_ARENA="$(CROSS_M0MPS2_ARENA)" \
	 CROSS_COUNT_RUN="$(CROSS_COUNT_RUN)" CROSS_COUNT_ARENA="$(CROSS_COUNT_ARENA)" \
	 CROSS_CLI_TECHNIQUES="$(CROSS_CLI_TECHNIQUES)" \
	 SKIP="$(SKIP)" MAKE="$(MAKE)" HOST_CC="$(CC)"

.PHONY: cross cross-count cross-install
cross:
	@$(CROSS_ENV) bash platform/cross-run.sh check
cross-count:
	@$(CROSS_ENV) bash platform/cross-run.sh count
cross-install:
	@bash platform/cross-install.sh

.PHONY: size-table size-check
size-check: $(BAKE_float) $(BAKE_fixed)
	@MAKE="$(MAKE)" SIZE_BAKE="$(BAKE_float) $(BAKE_fixed)" bash tools/size_check.sh
SIZE_LTO ?= 0
SIZE_TOP ?= 0
size-table: $(BAKE_float) $(BAKE_fixed)
	@MAKE="$(MAKE)" SIZE_LTO="$(SIZE_LTO)" SIZE_TOP="$(SIZE_TOP)" SIZE_ROWS="$(SIZE_ROWS)" SIZE_NUMS="$(SIZE_NUMS)" \
	 SIZE_BAKE="$(BAKE_float) $(BAKE_fixed)" \
	 bash tools/size_table.sh
