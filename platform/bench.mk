# SPDX-License-Identifier: MIT
# platform/bench.mk - accuracy vs time (issue 5): `make bench` sweeps every
# technique x setting (samples, slices, radius) over the built-in scenes in
# float and Q16.16 fixed, times whole frames (median of BENCH_RUNS) and
# measures them against the ray-traced reference; every technique's colour
# (HBIL converged) against the path tracer (technique pathtrace); results in
# BENCH_DIR (bench.md, bench.csv, bench.svg, contact.ppm/.png,
# bench-color.csv/.svg, contact-color.ppm/.png).  `make bench-publish`
# copies them to tools/bench-results/ (the README's copy).
#
#   make bench BENCH_SIZE=160x120 BENCH_RUNS=5 [BENCH_ARGS="--scenes columns"]
#   make bench-cost   then each configuration on the curves in instructions
#                     per pixel (callgrind; BENCH_COST_SCENES="a b" narrows it):
#                     bench.md gains the counts, bench-cost.svg plots them

BENCH_SIZE ?= 160x120
BENCH_RUNS ?= 5
BENCH_DIR  ?= $(BUILD)/bench
BENCH_ARGS ?=

.PHONY: bench bench-build bench-publish bench-cost

# The bench programs, once per number type ($(1) float|fixed, $(2) file
# suffix): bench-float/-fixed (tools/bench.c), bench_raster[-fixed].  They
# link the hosted platform and the core library.
BENCH_LINK = -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform
define bench_programs
$$(BUILD)/bench-$(1): tools/bench.c $$(HOST_OBJ_$(1)) $$(BUILD)/libtinygi$(2).a
	$$(CC) $$(CFLAGS_ALL) $$(NUMDEF_$(1)) $$(BENCH_LINK) $$< $$(HOST_OBJ_$(1)) $$(BUILD)/libtinygi$(2).a -o $$@ $$(LDLIBS_HOST)
$$(BUILD)/bench_raster$(2): tools/bench_raster.c $$(HOST_OBJ_$(1)) $$(BUILD)/libtinygi$(2).a
	$$(CC) $$(CFLAGS_ALL) $$(NUMDEF_$(1)) $$(BENCH_LINK) $$< $$(HOST_OBJ_$(1)) $$(BUILD)/libtinygi$(2).a -o $$@ $$(LDLIBS_HOST)
endef
$(eval $(call bench_programs,float,))
$(eval $(call bench_programs,fixed,-fixed))

bench-build: $(BUILD)/bench-float $(BUILD)/bench-fixed

# float first: it renders the reference once per scene and radius and caches
# it in BENCH_DIR/ref for every row and for the fixed run; the cache is
# cleared first so a changed renderer never meets a stale reference
bench: bench-build
	rm -rf $(BENCH_DIR)/ref
	$(BUILD)/bench-float run --size $(BENCH_SIZE) --runs $(BENCH_RUNS) --out $(BENCH_DIR) $(BENCH_ARGS)
	$(BUILD)/bench-fixed run --size $(BENCH_SIZE) --runs $(BENCH_RUNS) --out $(BENCH_DIR) $(BENCH_ARGS)
	$(BUILD)/bench-float report --size $(BENCH_SIZE) --out $(BENCH_DIR)

# The accuracy bench's configurations (the curves) in instructions per pixel:
# callgrind counts each one's timed frame (tools/bench_cost.py, `bench
# count`); then the report again, which adds them to bench.md and draws
# bench-cost.svg.  Run after `make bench` (same BENCH_SIZE and BENCH_DIR);
# load does not matter.
bench-cost: all bench-build bench-valgrind
	python3 tools/bench_cost.py --build $(BUILD) --size $(BENCH_SIZE) --out $(BENCH_DIR) --jobs $(BENCH_JOBS) \
	  $(if $(BENCH_COST_SCENES),--scenes "$(BENCH_COST_SCENES)")
	$(BUILD)/bench-float report --size $(BENCH_SIZE) --out $(BENCH_DIR)

bench-publish:
	@mkdir -p tools/bench-results
	cp $(BENCH_DIR)/bench.svg $(BENCH_DIR)/bench.md $(BENCH_DIR)/bench.csv $(BENCH_DIR)/contact.png tools/bench-results/
	cp $(BENCH_DIR)/bench-color.svg $(BENCH_DIR)/bench-color.csv $(BENCH_DIR)/contact-color.png tools/bench-results/
	cp $(BENCH_DIR)/multibounce-float.csv tools/bench-results/multibounce.csv
	if [ -f $(BENCH_DIR)/bench-cost.svg ]; then cp $(BENCH_DIR)/bench-cost.svg $(BENCH_DIR)/cost-float.csv $(BENCH_DIR)/cost-fixed.csv tools/bench-results/; fi

# ---- cost and speed benches (speed is measured here, never in tests) ----
#
#   make bench-count    instructions per frame and per pixel per pass (callgrind;
#                       deterministic, load does not matter).  Narrow it with
#                       BENCH_SCENES="cornell columns" (or all), BENCH_TYPES="float fixed",
#                       BENCH_MODES="default quarter", BENCH_FRAMES=10, BENCH_FRAME_SIZE=320x240
#   make bench-count-check   bench_count.py's own check (a fake program with passes)
#   make bench-frame    whole frames through the CLI, timed: every configuration
#                       once per round, interleaved, BENCH_ROUNDS rounds, medians
#                       (min..max) of CPU and wall time, load average at start and end;
#                       one thread (BENCH_THREADS="1 2" adds configurations);
#                       BENCH_BASELINE=DIR also runs DIR/tinygi[-fixed] (an older
#                       checkout's build directory) in the same rounds, for before/after,
#                       with the first of BENCH_THREADS when it takes --threads
#   make bench-threads  the same for --threads 1 and 2 (BENCH_THREADS), cornell and
#                       columns (BENCH_FRAME_SCENES), and the wall-time speed-up of
#                       each thread count over one, paired round by round, of the
#                       whole run and of its steady frames (each configuration run
#                       again with --frames 1: the difference is the N - 1 frames
#                       after the first, without start-up and written image)
#   make bench-raster   the 49,728-triangle sphere at 320x240 and 1280x720, float and
#                       Q16.16, timed the same way, Mtri/s, and callgrind's count per
#                       frame; BENCH_PEERS="CMD;CMD" adds programs that print the same
#                       line (tools/bench_time.py describes it)
# Results: $(BUILD)/bench-count/, $(BUILD)/bench-frame/, $(BUILD)/bench-threads/, $(BUILD)/bench-raster/
# (count.md/.csv, time.md/.csv).

BENCH_SCENES     ?= cornell columns
BENCH_TYPES      ?= float fixed
BENCH_MODES      ?= default quarter
BENCH_FRAMES     ?= 10
BENCH_FRAME_SIZE ?= 320x240
BENCH_JOBS       ?= 2
BENCH_ROUNDS     ?=
BENCH_FRAME_SCENES ?=
BENCH_THREADS    ?=
BENCH_RASTER_FRAMES ?= 20
BENCH_PEERS      ?=

.PHONY: bench-count bench-count-check bench-frame bench-threads bench-raster bench-valgrind
# valgrind (callgrind), installed from Debian packages only if it is missing
bench-valgrind:
	@command -v valgrind >/dev/null 2>&1 || { \
	  command -v apt-get >/dev/null 2>&1 || { echo "bench: install valgrind (callgrind)" >&2; exit 1; }; \
	  echo "bench: installing valgrind"; sudo=""; [ "$$(id -u)" -ne 0 ] && sudo=sudo; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  $$sudo apt-get install -y -qq --no-install-recommends valgrind >/dev/null 2>&1 || \
	  { $$sudo apt-get update -qq && $$sudo apt-get install -y -qq --no-install-recommends valgrind; } || \
	  { echo "bench: apt-get install valgrind failed" >&2; exit 1; }; }

bench-count: all bench-valgrind
	python3 tools/bench_count.py --build $(BUILD) --scenes "$(BENCH_SCENES)" --types "$(BENCH_TYPES)" \
	  --modes "$(BENCH_MODES)" --frames $(BENCH_FRAMES) --size $(BENCH_FRAME_SIZE) --jobs $(BENCH_JOBS)

# the callgrind reading and the tgi_pass_* discovery, on a small fake program
bench-count-check: bench-valgrind
	python3 tools/bench_count.py --self-test

BENCH_FRAME_RUN = python3 tools/bench_time.py frame --build $(BUILD) $(if $(BENCH_BASELINE),--baseline $(BENCH_BASELINE)) --types "$(BENCH_TYPES)" \
	  --modes "$(BENCH_MODES)" --frames $(BENCH_FRAMES) --size $(BENCH_FRAME_SIZE) \
	  --rounds $(or $(BENCH_ROUNDS),5)
bench-frame: all
	$(BENCH_FRAME_RUN) --scenes "$(or $(BENCH_FRAME_SCENES),all)" --threads "$(or $(BENCH_THREADS),1)"

# one thread against two: the pool's speed-up in wall time (platform/hosted/threads.c)
bench-threads: all
	$(BENCH_FRAME_RUN) --scenes "$(or $(BENCH_FRAME_SCENES),cornell columns)" \
	  --threads "$(or $(BENCH_THREADS),1 2)" --steady --out $(BUILD)/bench-threads

bench-raster: $(BUILD)/bench_raster $(BUILD)/bench_raster-fixed bench-valgrind
	BENCH_PEERS="$(BENCH_PEERS)" python3 tools/bench_time.py raster --build $(BUILD) \
	  --frames $(BENCH_RASTER_FRAMES) --rounds $(or $(BENCH_ROUNDS),7)
