#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/bench_time_test.sh - tools/bench_time.py frame's runs, with fake
# programs that record their arguments (no rendering, no timing asserted):
#  - this build's runs pass --threads N for each configuration;
#  - a --baseline build whose --help lists --threads runs with this build's
#    first thread count (with its default, two threads on a 2-core machine,
#    its CPU time, the pool's waiting included, was compared with one
#    thread's);
#  - a baseline without --threads (older than the option) runs without it;
#  - the report names the baseline rows and their ratio.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_scratch bench_time
if ! command -v python3 >/dev/null 2>&1; then
    ok "bench_time: python3 absent, skipped"; summary; exit 0
fi

# fake DIR HELP: DIR/tinygi and DIR/tinygi-fixed append their arguments to
# DIR/args, print HELP for --help, and write the -o file
fake() {
    mkdir -p "$1"
    for p in tinygi tinygi-fixed; do
        cat >"$1/$p" <<EOF
#!/bin/sh
if [ "\$1" = "--help" ]; then echo "$2"; exit 0; fi
echo "\$*" >>"$1/args"
while [ \$# -gt 0 ]; do if [ "\$1" = "-o" ]; then : >"\$2"; fi; shift; done
exit 0
EOF
        chmod +x "$1/$p"
    done
}
fake "$T/new" "usage: tinygi render SCENE [options] --threads N"
fake "$T/old2" "usage: tinygi render SCENE [options] --threads N  threads that share each pass's rows"
fake "$T/old1" "usage: tinygi render SCENE [options]"

run() {   # run BASELINE OUT: one round, one configuration per thread count
    python3 tools/bench_time.py frame --build "$T/new" --baseline "$1" --scenes cornell --types float \
        --modes default --frames 2 --rounds 1 --threads "1,2" --out "$2" >"$2.log" 2>&1
}
expect "runs with a baseline that takes --threads" run "$T/old2" "$T/out2"
expect "this build: --threads 1 and 2" \
    test "$(grep -c -- '--threads 1$' "$T/new/args")" -eq 1 -a "$(grep -c -- '--threads 2$' "$T/new/args")" -eq 1
expect "the baseline: one run, with this build's first thread count" \
    test "$(wc -l <"$T/old2/args")" -eq 1 -a "$(grep -c -- '--threads 1$' "$T/old2/args")" -eq 1
expect "the report: the baseline's row and ratio" grep -q "| cornell | default | float | before |" "$T/out2/time.md"
expect "the report: against the baseline" grep -q "^Against the baseline build" "$T/out2/time.md"

rm -f "$T/new/args"
expect "runs with a baseline older than --threads" run "$T/old1" "$T/out1"
expect "that baseline: one run, without --threads" \
    test "$(wc -l <"$T/old1/args")" -eq 1 -a "$(grep -c -- '--threads' "$T/old1/args")" -eq 0
summary
