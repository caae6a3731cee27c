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

# the peer programs (tools/peers/) need the peers' sources, which this
# repository does not have: their shared main (peer_common.h, with
# raster_sphere.h) is compiled with a peer that draws nothing, and its line
# is the one tools/bench_time.py reads; build.sh refuses what is not a
# checkout
cat >"$T/peer_none.c" <<'PEER'
#include "peer_common.h"
static long drawn;
static const char *peer_name(void) { return "none"; }
static int peer_setup(int w, int h, const float *pos, int tris) { (void)pos; (void)tris; return w == 64 && h == 48; }
static void bench_clear(void) { drawn = 0; }
static void bench_draw(void) { drawn = 7; }
static long peer_covered(void) { return drawn; }
static void peer_done(void) {}
int main(int argc, char **argv) { return peer_main(argc, argv); }
PEER
if ${CC:-cc} -std=c99 -Wall -Wextra -Werror -Itools/peers "$T/peer_none.c" -lm -o "$T/peer_none" 2>"$T/peer.log"; then
    ok "tools/peers/peer_common.h compiles (-Wall -Wextra)"
    line=$("$T/peer_none" 64x48 --frames 2)
    expect "a peer program prints the result line (tris=49728 ... covered=7)" \
        sh -c 'printf "%s\n" "$1" | grep -Eq "^none 64x48 tris=49728 frames=2 draw_cpu_ms=[0-9.]+ draw_wall_ms=[0-9.]+ clear_cpu_ms=[0-9.]+ clear_wall_ms=[0-9.]+ covered=7$"' _ "$line"
    "$T/peer_none" 32x32 >/dev/null 2>&1; rc=$?
    expect "a peer program refuses a size it cannot draw (exit 2)" test "$rc" -eq 2
else
    fail "tools/peers/peer_common.h compiles (-Wall -Wextra)" "$(head -n 5 "$T/peer.log")"
fi
sh tools/peers/build.sh "$T" "$T" "$T/peers" >/dev/null 2>"$T/peers.log"; rc=$?
expect "tools/peers/build.sh refuses a directory that is not TinyGL (exit 2, says why)" \
    sh -c '[ "$1" -eq 2 ] && grep -q "is not a TinyGL checkout" "$2"' _ "$rc" "$T/peers.log"

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
