#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/tools_test.sh - the programs and commands the README names keep
# working where no other test runs them:
#  - every C program in tools/ is built by `make all`, by make size-check
#    (size_app.c) or here: the host programs no other test builds (the
#    benches, memory_scene) against today's library, in both number types,
#    so none rots unbuilt (tools/bench_hbil.c had: it called functions the
#    core no longer has, and `make bench-hbil`, which the README named,
#    failed to compile);
#  - every make target the README names in a command (a code block's line or
#    a `...` span starting with "make") is a target of the Makefile.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh

# the programs of tools/ and who builds them: `make all` (and so every test)
# the CLI and the baker, tools/size_table.sh (make size-check) size_app.c,
# and this test the host programs no other test builds, in both types
built_by_all="tinygi.c scene_bake.c" built_by_size="size_app.c"
host_programs="bench.c:bench-float,bench-fixed bench_raster.c:bench_raster,bench_raster-fixed memory_scene.c:memory_scene"
for src in tools/*.c; do
    name=$(basename "$src")
    case " $built_by_all $built_by_size " in *" $name "*) ok "$src is built by make all or make size-check"; continue ;; esac
    progs=$(for hp in $host_programs; do [ "${hp%%:*}" = "$name" ] && echo "${hp#*:}"; done)
    if [ -z "$progs" ]; then fail "$src is built by a test" "no test builds it: add it to tests/tools_test.sh or remove it"; continue; fi
    for prog in $(echo "$progs" | tr ',' ' '); do
        if sub_make "$BUILD/$prog" >"$T/make-$prog.log" 2>&1 && [ -x "$BUILD/$prog" ]; then ok "make $BUILD/$prog ($src)"
        else fail "make $BUILD/$prog ($src)" "$(grep -E 'error|undefined|No rule' "$T/make-$prog.log" | head -n 5)"; fi
    done
done
expect "tools/size_app.c is linked by tools/size_table.sh" grep -q "size_app.c" tools/size_table.sh

# the make targets the README's commands name
awk '
function targets(cmd,    n, w, i, started) {
    n = split(cmd, w, /[ \t]+/)
    started = 0
    for (i = 1; i <= n; i++) {
        if (!started) {
            if (w[i] == "make") started = 1
            else if (w[i] != "sudo" && w[i] != "$" && w[i] !~ /^[A-Z_][A-Z0-9_]*=/ && w[i] != "") return
            continue
        }
        if (w[i] ~ /^[;&|#]/) return
        if (w[i] ~ /^-/ || w[i] ~ /=/) continue
        if (w[i] ~ /^[a-z][-a-z0-9_.]*$/) print w[i]
        else return
    }
}
/^```/ { code = !code; next }
code { targets($0); next }
{
    line = $0
    while (match(line, /`[^`]*`/)) {
        targets(substr(line, RSTART + 1, RLENGTH - 2))
        line = substr(line, RSTART + RLENGTH)
    }
}' README.md | sort -u >"$T/readme-targets"
# the Makefile's targets from make's database (-p; -q and the goal ":"
# run no recipe)
"${MAKE:-make}" -pRrq -f Makefile : 2>/dev/null \
    | awk -F: '/^[a-zA-Z0-9][^$#\/\t=]*:([^=]|$)/ { n = split($1, a, / /); for (i = 1; i <= n; i++) if (a[i] != "") print a[i] }' \
    | sort -u >"$T/make-targets"
expect "the README names make targets (found $(wc -l <"$T/readme-targets"))" test "$(wc -l <"$T/readme-targets")" -ge 10
missing=$(comm -23 "$T/readme-targets" "$T/make-targets" | tr '\n' ' ')
expect "every make target the README names exists${missing:+ (missing: $missing)}" test -z "$missing"
summary
