# SPDX-License-Identifier: MIT
# platform/sanitize.mk - sanitizer and fuzzing targets (included by the Makefile).
#
#   make sanitize                 every test (both number types, the shell tests
#                                 too) rebuilt with AddressSanitizer and
#                                 UndefinedBehaviorSanitizer in $(SAN_BUILD);
#                                 any report aborts the test that hit it
#   make fuzz [FUZZ_SECONDS=30]   libFuzzer targets (tests/fuzz/fuzz_*.c) for the
#                                 scene parser, the OBJ/MTL loader and the whole
#                                 API (request + scene, planned and rendered in
#                                 a small arena), float and Q16.16, each run
#                                 FUZZ_SECONDS from the seed corpus
#                                 tests/fuzz/corpus_<target>/
#   make fuzz-build               only build them (into $(FUZZ_BUILD))
#   make soak [SOAK_LAPS=8]       tests/soak.c under ASan + UBSan (built in
#                                 $(SAN_BUILD), the libraries `make sanitize`
#                                 built), float and Q16.16: SOAK_LAPS x 256 + 1
#                                 frames of an animated scene with reprojection
#                                 at 32x24, every output bounded, laps that
#                                 repeat, the frame's memory guarded
#
# The core is compiled -ffreestanding; gcc and clang still instrument it.
# libFuzzer needs clang and its runtime (Debian: packages clang and
# libclang-rt-NN-dev); `make fuzz` says what is missing.  The fuzz build takes
# clang's flags from the Makefile (REPRO_clang, WARN_clang; -Werror with
# DEV=1).  New crashes are written to $(FUZZ_BUILD)/crashes/; turn each into a
# regression test.

SAN_BUILD   ?= build-san
SAN_FLAGS   ?= -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g
# gcc at -O1 with ASan reports "may be used uninitialized" where -O2 does not
# (malloc'd buffers in tests); it is not a finding of the sanitizers.
SAN_WARN    ?= -Wno-maybe-uninitialized
FUZZ_BUILD  ?= build-fuzz
FUZZ_CC     ?= clang
FUZZ_SECONDS ?= 30
FUZZ_TARGETS := scene obj api
FUZZ_FLAGS  = -std=c99 $(REPRO_clang) $(WARN_clang) $(WERROR) -O1 -g \
              -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all
FUZZ_BINS   := $(foreach t,$(FUZZ_TARGETS),$(FUZZ_BUILD)/fuzz_$(t) $(FUZZ_BUILD)/fuzz_$(t)-fixed)
FUZZ_CORE   = $(filter-out $(SKIP),$(sort $(wildcard src/*.c src/*/*.c)))

SOAK_LAPS   ?= 8
SAN_ENV     = ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

.PHONY: sanitize fuzz fuzz-build fuzz-check soak
sanitize:
	@start=$$(date +%s); \
	$(SAN_ENV) $(MAKE) --no-print-directory BUILD=$(SAN_BUILD) \
	    CFLAGS="-O1 $(SAN_FLAGS) $(SAN_WARN)" LDFLAGS="$(SAN_FLAGS)" test; rc=$$?; \
	echo "sanitize: $$(( $$(date +%s) - start )) s"; exit $$rc

# tests/soak.c is built by the tests' rule of the Makefile (not a test_*.c,
# so `make test` does not run it).
soak:
	@$(MAKE) --no-print-directory BUILD=$(SAN_BUILD) CFLAGS="-O1 $(SAN_FLAGS) $(SAN_WARN)" \
	    LDFLAGS="$(SAN_FLAGS)" $(SAN_BUILD)/float/tests/soak $(SAN_BUILD)/fixed/tests/soak
	@start=$$(date +%s); rc=0; \
	for n in float fixed; do $(SAN_ENV) $(SAN_BUILD)/$$n/tests/soak $(SOAK_LAPS) || rc=1; done; \
	echo "soak: $$(( $$(date +%s) - start )) s"; exit $$rc

fuzz-check:
	@command -v $(FUZZ_CC) >/dev/null || { echo "make fuzz: $(FUZZ_CC) not found; install it: apt-get install -y --no-install-recommends clang libclang-rt-dev (or libclang-rt-14-dev)"; exit 2; }
	@echo 'int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { (void)d; (void)n; return 0; }' \
	    | $(FUZZ_CC) -x c -fsanitize=fuzzer - -o /dev/null 2>/dev/null \
	    || { echo "make fuzz: $(FUZZ_CC) cannot link -fsanitize=fuzzer; install libclang-rt-dev (Debian 12: libclang-rt-14-dev)"; exit 2; }

fuzz-build: fuzz-check $(FUZZ_BINS)

# The core is compiled once per number type (objects in $(FUZZ_BUILD)/float
# and /fixed, rebuilt when a source, a header or the flags change) and
# linked into every target.
FUZZ_OBJ_float = $(patsubst src/%.c,$(FUZZ_BUILD)/float/%.o,$(FUZZ_CORE))
FUZZ_OBJ_fixed = $(patsubst src/%.c,$(FUZZ_BUILD)/fixed/%.o,$(FUZZ_CORE))
FUZZ_STAMP     = $(FUZZ_BUILD)/flags
$(FUZZ_STAMP): FORCE
	@mkdir -p $(@D)
	@printf '%s\n' '$(FUZZ_CC) $(FUZZ_FLAGS)' >$@.new; if cmp -s $@.new $@; then rm -f $@.new; else mv $@.new $@; fi
$(FUZZ_BUILD)/float/%.o: src/%.c $(FUZZ_STAMP)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) -MMD -MP -c $< -o $@
$(FUZZ_BUILD)/fixed/%.o: src/%.c $(FUZZ_STAMP)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_FLAGS) -DTG_FIXED=1 -MMD -MP -c $< -o $@
-include $(patsubst %.o,%.d,$(FUZZ_OBJ_float) $(FUZZ_OBJ_fixed))

$(FUZZ_BUILD)/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_common.h $(FUZZ_OBJ_float)
	$(FUZZ_CC) $(FUZZ_FLAGS) -Isrc $< $(FUZZ_OBJ_float) -o $@
$(FUZZ_BUILD)/fuzz_%-fixed: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_common.h $(FUZZ_OBJ_fixed)
	$(FUZZ_CC) $(FUZZ_FLAGS) -DTG_FIXED=1 -Isrc $< $(FUZZ_OBJ_fixed) -o $@

# Each target runs from a scratch copy of its seed corpus (new inputs stay in
# the build dir, the repository's seeds are not touched).
fuzz: fuzz-build
	@mkdir -p $(FUZZ_BUILD)/crashes; rc=0; \
	for b in $(FUZZ_BINS); do \
	    t=$$(basename $$b); base=$${t%-fixed}; base=$${base#fuzz_}; \
	    mkdir -p $(FUZZ_BUILD)/corpus/$$t; \
	    cp -n tests/fuzz/corpus_$$base/* $(FUZZ_BUILD)/corpus/$$t/ 2>/dev/null; \
	    echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	    $$b -max_total_time=$(FUZZ_SECONDS) -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
	        -artifact_prefix=$(FUZZ_BUILD)/crashes/$$t- -print_final_stats=1 \
	        $(FUZZ_BUILD)/corpus/$$t >$(FUZZ_BUILD)/$$t.log 2>&1 \
	        || { rc=1; echo "fuzz: $$t FAILED"; grep -A30 'ERROR\|runtime error\|deadly' $(FUZZ_BUILD)/$$t.log | head -n 60; }; \
	    grep -E 'stat::number_of_executed_units|Done [0-9]+ runs' $(FUZZ_BUILD)/$$t.log | head -n 2; \
	done; \
	[ $$rc -eq 0 ] && echo "fuzz: no crashes" || { echo "fuzz: crash inputs in $(FUZZ_BUILD)/crashes/"; exit 1; }
