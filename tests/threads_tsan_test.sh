#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/threads_tsan_test.sh - the thread pool and frames rendered through it
# under ThreadSanitizer: tests/test_threads.c (its quick set: three built-in
# scenes and the moving scene, 2 and 7 threads), the core and
# platform/hosted/threads.c built with -fsanitize=thread, float and Q16.16.
# A data race between two row ranges of a pass, or in the pool, is a
# report and a failure.  Where $CC cannot build a ThreadSanitizer program
# the test says so and checks nothing.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
CC=${CC:-cc}
sh_scratch tsan
FLAGS="-std=c99 ${REPRO:-} -O1 -g -fsanitize=thread -D_POSIX_C_SOURCE=200809L"

printf '#include <pthread.h>\nstatic void *f(void *a) { return a; }\nint main(void) { pthread_t t; return pthread_create(&t, 0, f, 0) || pthread_join(t, 0); }\n' >"$T/probe.c"
if ! $CC $FLAGS "$T/probe.c" -o "$T/probe" -lpthread >"$T/probe.log" 2>&1 || ! "$T/probe" >>"$T/probe.log" 2>&1; then
    echo "# note: $CC cannot build or run a -fsanitize=thread program here; nothing checked"
    head -n 3 "$T/probe.log" | sed 's/^/#   /'
    summary
    exit
fi

for num in float fixed; do
    def=; [ $num = fixed ] && def=-DTG_FIXED=1
    # shellcheck disable=SC2086 # FLAGS holds several flags
    if ! $CC $FLAGS $def -Isrc -Iplatform -Itests tests/test_threads.c platform/hosted/threads.c \
        src/*/*.c -o "$T/test_threads-$num" -lm -lpthread 2>"$T/cc.log"; then
        fail "tsan/$num/builds" "$(head -n 5 "$T/cc.log")"; continue
    fi
    ok "tsan/$num/builds"
    TSAN_OPTIONS="halt_on_error=1 exitcode=66" "$T/test_threads-$num" quick >"$T/run.log" 2>&1; rc=$?
    if [ $rc -eq 0 ] && ! grep -q 'ThreadSanitizer' "$T/run.log"; then ok "tsan/$num/no_race"
    else fail "tsan/$num/no_race" "exit $rc: $(grep -v '^ok ' "$T/run.log" | head -n 30)"; fi
done
summary
