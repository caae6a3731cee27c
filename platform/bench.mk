# SPDX-License-Identifier: MIT
# platform/bench.mk - accuracy vs time (issue 5): `make bench` sweeps every
# technique x setting (samples, slices, radius) over the built-in scenes in
# float and Q16.16 fixed, times whole frames (median of BENCH_RUNS) and
# measures them against the ray-traced reference; results in BENCH_DIR
# (bench.md, bench.csv, bench.svg, contact.ppm/.png).  `make bench-publish`
# copies them to tools/bench-results/ (the README's copy).
#
#   make bench BENCH_SIZE=160x120 BENCH_RUNS=5 [BENCH_ARGS="--scenes columns"]

BENCH_SIZE ?= 160x120
BENCH_RUNS ?= 5
BENCH_DIR  ?= $(BUILD)/bench
BENCH_ARGS ?=

.PHONY: bench bench-build bench-publish
$(BUILD)/bench-float: tools/bench.c $(HOST_OBJ_float) $(BUILD)/libtinygi.a
	$(CC) $(CFLAGS_ALL) -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_float) $(BUILD)/libtinygi.a -o $@ $(LDLIBS_HOST)
$(BUILD)/bench-fixed: tools/bench.c $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a
	$(CC) $(CFLAGS_ALL) -DTG_FIXED=1 -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform $< $(HOST_OBJ_fixed) $(BUILD)/libtinygi-fixed.a -o $@ $(LDLIBS_HOST)

bench-build: $(BUILD)/bench-float $(BUILD)/bench-fixed

# float first: it renders the reference once per scene and radius and caches
# it in BENCH_DIR/ref for every row and for the fixed run; the cache is
# cleared first so a changed renderer never meets a stale reference
bench: bench-build
	rm -rf $(BENCH_DIR)/ref
	$(BUILD)/bench-float run --size $(BENCH_SIZE) --runs $(BENCH_RUNS) --out $(BENCH_DIR) $(BENCH_ARGS)
	$(BUILD)/bench-fixed run --size $(BENCH_SIZE) --runs $(BENCH_RUNS) --out $(BENCH_DIR) $(BENCH_ARGS)
	$(BUILD)/bench-float report --size $(BENCH_SIZE) --out $(BENCH_DIR)

bench-publish:
	@mkdir -p tools/bench-results
	cp $(BENCH_DIR)/bench.svg $(BENCH_DIR)/bench.md $(BENCH_DIR)/bench.csv $(BENCH_DIR)/contact.png tools/bench-results/
