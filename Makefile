# SPDX-License-Identifier: MIT
# tinygi - build, test and benchmark.
#
#   make            core libraries (float and Q16.16) and the CLI for both
#   make test       every test, both number types; ends "N passed, N failed"
#   make clean
#
# Sources are found by wildcard: a new file under src/<area>/ joins the core,
# a new tests/test_*.c becomes a test program, a new tests/*_test.sh a script.

CC      ?= cc
BUILD   ?= build
OPT     ?= -O2
CSTD     = -std=c99 -ffp-contract=off -fexcess-precision=fast
WARN     = -Wall -Wextra -Wpedantic -Wshadow -Wdouble-promotion -Werror
CFLAGS_ALL = $(CSTD) $(OPT) $(WARN) $(EXTRA_CFLAGS)
LDLIBS_HOST = -lm $(EXTRA_LDFLAGS)

SKIP      ?=
CORE_SRC   := $(filter-out $(SKIP),$(sort $(wildcard src/*.c src/*/*.c)))
HOSTED_SRC := $(sort $(wildcard platform/hosted/*.c platform/fbdev/*.c))
TEST_SRC   := $(filter-out $(SKIP),$(sort $(wildcard tests/test_*.c)))
TEST_NAMES := $(patsubst tests/%.c,%,$(TEST_SRC))

CORE_OBJ_float := $(patsubst src/%.c,$(BUILD)/float/core/%.o,$(CORE_SRC))
CORE_OBJ_fixed := $(patsubst src/%.c,$(BUILD)/fixed/core/%.o,$(CORE_SRC))
HOST_OBJ_float := $(patsubst platform/%.c,$(BUILD)/float/platform/%.o,$(HOSTED_SRC))
HOST_OBJ_fixed := $(patsubst platform/%.c,$(BUILD)/fixed/platform/%.o,$(HOSTED_SRC))

NUMDEF_float :=
NUMDEF_fixed := -DTG_FIXED=1

TESTS_float := $(addprefix $(BUILD)/float/tests/,$(TEST_NAMES))
TESTS_fixed := $(addprefix $(BUILD)/fixed/tests/,$(TEST_NAMES))

.PHONY: all test clean tests-build golden
all: $(BUILD)/libtinygi.a $(BUILD)/libtinygi-fixed.a $(BUILD)/tinygi $(BUILD)/tinygi-fixed

# ---- the core: freestanding, no libc beyond stdint/stddef/string ----
$(BUILD)/float/core/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -ffreestanding -MMD -MP -c $< -o $@
$(BUILD)/fixed/core/%.o: src/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -DTG_FIXED=1 -ffreestanding -MMD -MP -c $< -o $@

$(BUILD)/libtinygi.a: $(CORE_OBJ_float)
	@rm -f $@
	$(AR) rcs $@ $^
$(BUILD)/libtinygi-fixed.a: $(CORE_OBJ_fixed)
	@rm -f $@
	$(AR) rcs $@ $^

# ---- the hosted platform ----
$(BUILD)/float/platform/%.o: platform/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -D_POSIX_C_SOURCE=200809L -Isrc -MMD -MP -c $< -o $@
$(BUILD)/fixed/platform/%.o: platform/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc -MMD -MP -c $< -o $@

# ---- the CLI ----
$(BUILD)/tinygi: tools/tinygi.c $(HOST_OBJ_float) $(BUILD)/libtinygi.a
	$(CC) $(CFLAGS_ALL) -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_float) $(BUILD)/libtinygi.a -o $@ $(LDLIBS_HOST)
$(BUILD)/tinygi-fixed: tools/tinygi.c $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a
	$(CC) $(CFLAGS_ALL) -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a -o $@ $(LDLIBS_HOST)

# ---- tests: every tests/test_*.c, once per number type ----
$(BUILD)/float/tests/%: tests/%.c $(wildcard tests/*.h) $(HOST_OBJ_float) $(BUILD)/libtinygi.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform -Itests $< $(HOST_OBJ_float) $(BUILD)/libtinygi.a -o $@ $(LDLIBS_HOST)
$(BUILD)/fixed/tests/%: tests/%.c $(wildcard tests/*.h) $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform -Itests $< $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a -o $@ $(LDLIBS_HOST)

tests-build: all $(TESTS_float) $(TESTS_fixed)

test: tests-build
	@BUILD=$(BUILD) CC="$(CC)" bash tests/run.sh

# ---- micro-benchmarks (speed is measured here, never in tests) ----
.PHONY: bench-raster bench-hbil
$(BUILD)/bench_raster: tools/bench_raster.c $(HOST_OBJ_float) $(BUILD)/libtinygi.a
	$(CC) $(CFLAGS_ALL) -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_float) $(BUILD)/libtinygi.a -o $@ $(LDLIBS_HOST)
$(BUILD)/bench_raster-fixed: tools/bench_raster.c $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a
	$(CC) $(CFLAGS_ALL) -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a -o $@ $(LDLIBS_HOST)
$(BUILD)/bench_hbil: tools/bench_hbil.c $(HOST_OBJ_float) $(BUILD)/libtinygi.a
	$(CC) $(CFLAGS_ALL) -Wno-double-promotion -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_float) $(BUILD)/libtinygi.a -o $@ $(LDLIBS_HOST)
$(BUILD)/bench_hbil-fixed: tools/bench_hbil.c $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a
	$(CC) $(CFLAGS_ALL) -Wno-double-promotion -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a -o $@ $(LDLIBS_HOST)
# 50k-triangle sphere into a full G-buffer at 320x240 and 1280x720 (Mtri/s)
bench-raster: $(BUILD)/bench_raster $(BUILD)/bench_raster-fixed
	$(BUILD)/bench_raster
	$(BUILD)/bench_raster-fixed
# the HBIL chain (split, kernel, merge, filter) at 320x240 (ms)
bench-hbil: $(BUILD)/bench_hbil $(BUILD)/bench_hbil-fixed
	$(BUILD)/bench_hbil
	$(BUILD)/bench_hbil-fixed
# whole frames of every built-in scene through the CLI (ms per frame, float and
# fixed, the paper's every-pixel kernel and --gi-quarter)
bench-frame: all
	@for s in plane groove cornell spheres columns; do for b in tinygi tinygi-fixed; do for m in "" --gi-quarter; do \
	  printf '%-8s %-13s %-13s ' $$s $$b "$$m"; $(BUILD)/$$b render builtin:$$s -o $(BUILD)/bench-frame.ppm --frames 10 $$m 2>&1 | sed 's/.*, //'; done; done; done

# Rewrite the golden images from the current renderer (look at them after).
golden: all
	@GOLDEN_UPDATE=1 BUILD=$(BUILD) bash tests/golden_test.sh | tail -n 1

-include platform/cross.mk
-include platform/bench.mk
-include platform/sanitize.mk

clean:
	rm -rf $(BUILD) build-*

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
