# SPDX-License-Identifier: MIT
# platform/cross.mk - `make cross`: build tinygi for other machines, run it
# there (qemu-user, qemu-system-arm, or natively for i686) and compare every
# output file byte for byte against x86-64's.  Included by the top Makefile.
#
#   make cross            install what is missing, build, run, compare;
#                         ends with "N passed, N failed"
#   make cross-install    only the toolchain/emulator installs (apt-get)
#   make cross CROSS_TARGETS="s390x m3"   a subset (x86_64 always runs)
#
# Targets: x86_64 (reference), i686 (-msse2 -mfpmath=sse), s390x and
# powerpc (big-endian, 64- and 32-bit, qemu-user), m3 (Cortex-M3, QEMU
# mps2-an385, newlib + semihosting), m4f (Cortex-M4F, float on the FPU,
# mps2-an386), m0 (Cortex-M0, QEMU microbit, 16 KB RAM, -nostdlib, -Os,
# fixed point only; CROSS_M0_RUNS lists its SIZE:AOVS frames, because a
# full-colour 64x48 frame cannot fit in 16 KB).  The driver is platform/baremetal/render.c on all of
# them; the Linux targets also run the tinygi CLI and tests/test_fbdev.

CROSS_BUILD   ?= build-cross
CROSS_TARGETS ?= i686 s390x powerpc m3 m4f m0
CROSS_SCENES  ?= cornell spheres columns
CROSS_SIZE    ?= 64x48
CROSS_FRAMES  ?= 2
CROSS_AOVS    ?= color,depth,normal,albedo,ao,bent,cone,near,far,direct,irradiance,motion
CROSS_M0_RUNS ?= 4x3:color 6x4:ao+depth+normal
CROSS_M0_SCENES ?= cornell
CROSS_M0_ARENA ?= 10496
CROSS_SHADOW  ?= 64
CROSS_M0_SHADOW ?= 8

.PHONY: cross cross-install
cross:
	@CROSS_BUILD="$(CROSS_BUILD)" CROSS_TARGETS="$(CROSS_TARGETS)" \
	 CROSS_SCENES="$(CROSS_SCENES)" CROSS_SIZE="$(CROSS_SIZE)" \
	 CROSS_FRAMES="$(CROSS_FRAMES)" CROSS_AOVS="$(CROSS_AOVS)" \
	 CROSS_M0_RUNS="$(CROSS_M0_RUNS)" CROSS_M0_SCENES="$(CROSS_M0_SCENES)" \
	 CROSS_M0_ARENA="$(CROSS_M0_ARENA)" CROSS_SHADOW="$(CROSS_SHADOW)" \
	 CROSS_M0_SHADOW="$(CROSS_M0_SHADOW)" SKIP="$(SKIP)" MAKE="$(MAKE)" \
	 HOST_CC="$(CC)" bash platform/cross-run.sh
cross-install:
	@bash platform/cross-install.sh
