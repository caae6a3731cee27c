# SPDX-License-Identifier: MIT
# tinygi - build, test, install.
#
#   make                  core libraries (float and Q16.16), the CLI and the
#                         examples for both number types, into $(BUILD)
#   make test             every test, both number types; ends "N passed, N failed"
#   make DEV=1 ...        warnings are errors (development and CI; the default
#                         build never stops on a warning)
#   make install          library, header, pkg-config file (both number types)
#   make uninstall        and the CLI into $(DESTDIR)$(PREFIX)
#   make amalgamation     $(BUILD)/amalgamation/tinygi.c + tinygi.h
#   make examples         examples/*.c against the built library, or
#                         EXAMPLES_LIB=installed (pkg-config) or =amalgamation
#   make compilers        gcc and clang builds render the same files, bit for bit
#   make size-table       Cortex-M4 .text per configuration of the feature
#                         switches (TG_NO_* in src/tinygi.h; platform/cross.mk)
#   make size-check       fails if the colour or AO-only program is over its
#                         flash budget (48 / 24 KB; tools/size_check.sh)
#   make clean
#
# Standard variables are honoured: CC, CFLAGS (default -O2), CPPFLAGS,
# LDFLAGS, LDLIBS, AR, PREFIX (default /usr/local), DESTDIR; changing any flag
# rebuilds (the objects depend on $(BUILD)/flags, rewritten when a flag
# changes).  OPT, EXTRA_CFLAGS and EXTRA_LDFLAGS are older names still read
# (CFLAGS defaults to $(OPT); the EXTRA_ ones are added after CFLAGS/LDFLAGS).
#
# Sources are found by wildcard: a new file under src/<area>/ joins the core,
# a new tests/test_*.c becomes a test program, a new tests/*_test.sh a script,
# a new examples/*.c an example.

BUILD   ?= build
OPT     ?= -O2
CFLAGS  ?= $(OPT)
PREFIX  ?= /usr/local
DESTDIR ?=
BINDIR  ?= $(PREFIX)/bin
LIBDIR  ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
INSTALL ?= install
PKG_CONFIG ?= pkg-config

# ---- flags chosen per compiler ----
# Reproducible floats: no contraction into FMAs, and float arithmetic done in
# float.  gcc needs -fexcess-precision=fast for the second; clang has no such
# option before clang 16 (clang 14 rejects it) and evaluates float in float
# wherever FLT_EVAL_METHOD is 0 (x86-64, ARM, RISC-V, i686 with -msse2
# -mfpmath=sse); `make compilers` proves gcc and clang builds bit-identical.
CC_FAMILY := $(shell $(CC) -dM -E -x c /dev/null 2>/dev/null | sed -n 's/^.define __clang__ .*/clang/p; s/^.define __GNUC__ .*/gcc/p' | sort | head -n 1)
REPRO_gcc   := -ffp-contract=off -fexcess-precision=fast
REPRO_clang := -ffp-contract=off
WARN_gcc    := -Wall -Wextra -Wpedantic -Wshadow -Wdouble-promotion
WARN_clang  := $(WARN_gcc)
REPRO ?= $(REPRO_$(CC_FAMILY))
WARN  ?= $(WARN_$(CC_FAMILY))
DEV   ?=
WERROR ?= $(if $(filter 1,$(DEV)),-Werror)

# Every compile line, and every hosted link line (platform/bench.mk uses both).
CFLAGS_ALL  = -std=c99 $(REPRO) $(WARN) $(WERROR) $(CPPFLAGS) $(CFLAGS) $(EXTRA_CFLAGS)
LDLIBS_HOST = $(LDFLAGS) $(EXTRA_LDFLAGS) $(LDLIBS) -lm -lpthread
HOSTED_DEFS = -D_POSIX_C_SOURCE=200809L
FLAGS_STAMP = $(BUILD)/flags

SKIP      ?=
CORE_SRC   := $(filter-out $(SKIP),$(sort $(wildcard src/*.c src/*/*.c)))
CORE_HDR   := $(sort $(wildcard src/*.h src/*/*.h))
HOSTED_SRC := $(sort $(wildcard platform/hosted/*.c platform/fbdev/*.c))
TEST_SRC   := $(filter-out $(SKIP),$(sort $(wildcard tests/test_*.c)))
TEST_NAMES := $(patsubst tests/%.c,%,$(TEST_SRC))
EXAMPLE_SRC := $(sort $(wildcard examples/*.c))
EXAMPLES_LIB ?= built
AMALG      := $(BUILD)/amalgamation
VERSION    := $(shell sed -n 's/^.define TG_VERSION "\(.*\)".*/\1/p' src/tinygi.h)

.PHONY: all test clean tests-build golden examples amalgamation install uninstall compilers mutate FORCE
all: $(BUILD)/libtinygi.a $(BUILD)/libtinygi-fixed.a $(BUILD)/tinygi $(BUILD)/tinygi-fixed

FORCE:
# The flags every output was built with; rewritten only when they change.
$(FLAGS_STAMP): FORCE
	@mkdir -p $(@D)
	@printf '%s\n' '$(subst ','\'',$(strip $(CC) $(CFLAGS_ALL) | $(LDLIBS_HOST) | $(AR)))' >$@.new; \
	 if cmp -s $@.new $@; then rm -f $@.new; else mv $@.new $@; fi

# ---- one number type: $(1) float|fixed, $(2) file suffix, $(3) its defines ----
# Variables per number type (used by platform/bench.mk and platform/cross.mk):
#   NUMDEF_x, LIB_x, CORE_OBJ_x, HOST_OBJ_x, CLI_x, TESTS_x, EXAMPLES_x
define number_type
NUMDEF_$(1)   := $(3)
LIB_$(1)      := $$(BUILD)/libtinygi$(2).a
CLI_$(1)      := $$(BUILD)/tinygi$(2)
BAKE_$(1)     := $$(BUILD)/tinygi-bake$(2)
PC_$(1)       := tinygi$(2)
CORE_OBJ_$(1) := $$(patsubst src/%.c,$$(BUILD)/$(1)/core/%.o,$$(CORE_SRC))
HOST_OBJ_$(1) := $$(patsubst platform/%.c,$$(BUILD)/$(1)/platform/%.o,$$(HOSTED_SRC))
TESTS_$(1)    := $$(addprefix $$(BUILD)/$(1)/tests/,$$(TEST_NAMES))
EXAMPLES_$(1) := $$(patsubst examples/%.c,$$(BUILD)/$(1)/examples-$$(EXAMPLES_LIB)/%,$$(EXAMPLE_SRC))
all: $$(patsubst examples/%.c,$$(BUILD)/$(1)/examples-built/%,$$(EXAMPLE_SRC))
all: $$(BAKE_$(1))
examples: $$(EXAMPLES_$(1))

# the core: freestanding, no libc beyond stdint/stddef/string
$$(BUILD)/$(1)/core/%.o: src/%.c $$(FLAGS_STAMP)
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_ALL) $(3) -ffreestanding -MMD -MP -c $$< -o $$@
$$(LIB_$(1)): $$(CORE_OBJ_$(1))
	@rm -f $$@
	$$(AR) rcs $$@ $$^
# the hosted platform, the CLI and the tests
$$(BUILD)/$(1)/platform/%.o: platform/%.c $$(FLAGS_STAMP)
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_ALL) $(3) $$(HOSTED_DEFS) -Isrc -MMD -MP -c $$< -o $$@
$$(CLI_$(1)): tools/tinygi.c $$(HOST_OBJ_$(1)) $$(LIB_$(1))
	$$(CC) $$(CFLAGS_ALL) $(3) $$(HOSTED_DEFS) -Isrc -Iplatform $$< $$(HOST_OBJ_$(1)) $$(LIB_$(1)) -o $$@ $$(LDLIBS_HOST)
# tinygi-bake: a scene as C data, for builds with TG_NO_SCENE_TEXT (tools/scene_bake.c)
$$(BAKE_$(1)): tools/scene_bake.c $$(HOST_OBJ_$(1)) $$(LIB_$(1))
	$$(CC) $$(CFLAGS_ALL) $(3) $$(HOSTED_DEFS) -Isrc -Iplatform $$< $$(HOST_OBJ_$(1)) $$(LIB_$(1)) -o $$@ $$(LDLIBS_HOST)
$$(BUILD)/$(1)/tests/%: tests/%.c $$(wildcard tests/*.h) $$(HOST_OBJ_$(1)) $$(LIB_$(1))
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_ALL) $(3) $$(HOSTED_DEFS) -Isrc -Iplatform -Itests $$< $$(HOST_OBJ_$(1)) $$(LIB_$(1)) -o $$@ $$(LDLIBS_HOST)
# the examples, against the built library, the installed one or the amalgamation
$$(BUILD)/$(1)/examples-built/%: examples/%.c $$(LIB_$(1)) $$(CORE_HDR)
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_ALL) $(3) -Isrc $$< $$(LIB_$(1)) -o $$@ $$(LDLIBS_HOST)
$$(BUILD)/$(1)/examples-installed/%: examples/%.c FORCE
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_ALL) `$$(PKG_CONFIG) --cflags $$(PC_$(1))` $$< `$$(PKG_CONFIG) --libs $$(PC_$(1))` -o $$@ $$(LDLIBS_HOST)
$$(BUILD)/$(1)/examples-amalgamation/%: examples/%.c $$(AMALG)/tinygi.c $$(AMALG)/tinygi.h
	@mkdir -p $$(@D)
	$$(CC) $$(CFLAGS_ALL) $(3) -I$$(AMALG) $$< $$(AMALG)/tinygi.c -o $$@ $$(LDLIBS_HOST)
endef
$(eval $(call number_type,float,,))
$(eval $(call number_type,fixed,-fixed,-DTG_FIXED=1))

tests-build: all $(TESTS_float) $(TESTS_fixed)

# The scripts get the build's compiler and flags, and call make with them.
test: tests-build
	@BUILD=$(BUILD) CC="$(CC)" MAKE="$(MAKE)" REPRO='$(REPRO)' \
	 TG_CFLAGS='$(subst ','\'',$(CFLAGS_ALL))' TG_LDLIBS='$(subst ','\'',$(LDLIBS_HOST))' \
	 bash tests/run.sh

# ---- the single-file build ----
amalgamation: $(AMALG)/tinygi.c $(AMALG)/tinygi.h $(AMALG)/tinygi_scene.h
$(AMALG)/tinygi.c: tools/amalgamate.sh tools/amalgamate.awk $(CORE_SRC) $(CORE_HDR)
	sh tools/amalgamate.sh $(AMALG) $(CORE_SRC)
$(AMALG)/tinygi.h $(AMALG)/tinygi_scene.h: $(AMALG)/tinygi.c

# ---- install: both number types, each with its pkg-config file ----
# The installed header is the amalgamated one: src/tinygi.h with the headers
# it includes inlined, so one file is enough; tinygi_scene.h beside it is
# for scenes baked by the installed tinygi-bake (tools/scene_bake.c).
install: all $(AMALG)/tinygi.h $(AMALG)/tinygi_scene.h
	$(INSTALL) -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR) $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(PKGCONFIGDIR)
	$(INSTALL) -m 644 $(AMALG)/tinygi.h $(AMALG)/tinygi_scene.h $(DESTDIR)$(INCLUDEDIR)/
	$(INSTALL) -m 644 $(LIB_float) $(LIB_fixed) $(DESTDIR)$(LIBDIR)/
	$(INSTALL) -m 755 $(CLI_float) $(CLI_fixed) $(BAKE_float) $(BAKE_fixed) $(DESTDIR)$(BINDIR)/
	sed -e 's|@PREFIX@|$(PREFIX)|; s|@LIBDIR@|$(LIBDIR)|; s|@INCLUDEDIR@|$(INCLUDEDIR)|' \
	    -e 's|@VERSION@|$(VERSION)|; s|@NAME@|tinygi|; s|@NUMBER@|float|; s|@CFLAGS@||' \
	    tools/tinygi.pc.in >$(DESTDIR)$(PKGCONFIGDIR)/tinygi.pc
	sed -e 's|@PREFIX@|$(PREFIX)|; s|@LIBDIR@|$(LIBDIR)|; s|@INCLUDEDIR@|$(INCLUDEDIR)|' \
	    -e 's|@VERSION@|$(VERSION)|; s|@NAME@|tinygi-fixed|; s|@NUMBER@|Q16.16 fixed point|; s|@CFLAGS@| -DTG_FIXED=1|' \
	    tools/tinygi.pc.in >$(DESTDIR)$(PKGCONFIGDIR)/tinygi-fixed.pc
uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/tinygi.h $(DESTDIR)$(INCLUDEDIR)/tinygi_scene.h \
	      $(DESTDIR)$(LIBDIR)/libtinygi.a $(DESTDIR)$(LIBDIR)/libtinygi-fixed.a \
	      $(DESTDIR)$(BINDIR)/tinygi $(DESTDIR)$(BINDIR)/tinygi-fixed \
	      $(DESTDIR)$(BINDIR)/tinygi-bake $(DESTDIR)$(BINDIR)/tinygi-bake-fixed \
	      $(DESTDIR)$(PKGCONFIGDIR)/tinygi.pc $(DESTDIR)$(PKGCONFIGDIR)/tinygi-fixed.pc

# ---- gcc and clang agree bit for bit (CI; each compiler builds in build-CC) ----
COMPILERS ?= gcc clang
compilers:
	@COMPILERS="$(COMPILERS)" MAKE="$(MAKE)" bash tests/compilers.sh

# Measure the tests by mutation (tools/mutate.py, tests/mutants.txt; not in
# CI: 1.5-2 h on a loaded 2-core machine, ~30 s per caught mutant, ~8 min per
# missed one). MUTATE_FLAGS e.g. --only src/gi --workdir /tmp/tg-mutate --min 90.
mutate:
	python3 tools/mutate.py --jobs 2 $(MUTATE_FLAGS)

# Rewrite the golden images from the current renderer (look at them after).
golden: all
	@GOLDEN_UPDATE=1 BUILD=$(BUILD) bash tests/golden_test.sh | tail -n 1

# The README's memory tables ("Memory per frame"), from the plans the core makes.
$(BUILD)/memory_scene: tools/memory_scene.c $(BUILD)/libtinygi.a
	$(CC) $(CFLAGS_ALL) -Isrc $< $(BUILD)/libtinygi.a -o $@ $(LDLIBS_HOST)
memory-table: $(BUILD)/tinygi $(BUILD)/memory_scene
	@bash tools/memory_table.sh --readme README.md $(BUILD)
.PHONY: memory-table

-include platform/cross.mk
-include platform/bench.mk
-include platform/sanitize.mk

clean:
	rm -rf $(BUILD) build-*

-include $(patsubst %.o,%.d,$(CORE_OBJ_float) $(CORE_OBJ_fixed) $(HOST_OBJ_float) $(HOST_OBJ_fixed))
