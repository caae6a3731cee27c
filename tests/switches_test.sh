#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# switches_test.sh - the feature switches (tinygi.h "FEATURE SWITCHES"):
# the core builds and links with each one set alone and with all six, in
# both number types, and tests/switches_check.c then renders what the build
# keeps and sees what it left out refused (TG_ERR_INPUT naming the switch).
# The linked program (--gc-sections) must hold no global symbol of a
# left-out file; the full CLI, which holds them all, shows the patterns find
# them.  Host builds at -O0 (fast to compile; nothing here is timed).
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
BUILD=${BUILD:-build}
CC=${CC:-cc}
TG_CFLAGS=${TG_CFLAGS:--std=c99}
TG_LDLIBS=${TG_LDLIBS:--lm}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

SWITCHES="TECHNIQUES REFERENCE OBJ BUILTIN_SCENES SHADOW_MAPS ENVIRONMENT"
# the global symbols (nm) of each switch's left-out files
pattern() {
    case $1 in
        TECHNIQUES)     echo ' T tgi_((ssao|vo|hbao|gtao|ssilvb|ssdo|bentcone)_|pass_(ssao|vo|hbao|gtao|ssilvb|ssdo|bentcone)$)' ;;
        REFERENCE)      echo ' T tgi_(reference_|bvh_|pathtrace_|ray_triangle|pass_reference)' ;;
        OBJ)            echo ' T tgi_obj_' ;;
        BUILTIN_SCENES) echo ' [a-zA-Z] scene_(plane|groove|cornell|spheres|columns)$' ;;
        SHADOW_MAPS)    echo ' T tgi_shadow_' ;;
        ENVIRONMENT)    echo ' T tgi_(sh9_|env_radiance|far_|cone_)' ;;
    esac
}

# the full CLI links every feature: each pattern must find something there
full=$BUILD/tinygi
for sw in $SWITCHES; do
    n=$(nm "$full" 2>/dev/null | grep -cE "$(pattern "$sw")")
    if [ "$n" -gt 0 ]; then ok "switches/full-cli-has-$sw"; else fail "switches/full-cli-has-$sw" "pattern finds nothing in $full"; fi
done

# the single-file build of the core (tools/amalgamate.sh): one translation
# unit per configuration compiles faster than 50, and checks the guards
# keep it whole
sh tools/amalgamate.sh "$tmp/amalg" src/*/*.c 2>/dev/null

# build one configuration: $1 name, $2 number-type define, $3... switches set to 1
build() {
    local name=$1 num=$2 defs="" sw; shift 2
    for sw in "$@"; do defs="$defs -DTG_NO_$sw=1"; done
    # shellcheck disable=SC2086
    $CC $TG_CFLAGS -O0 $num $defs -ffunction-sections -fdata-sections -I"$tmp/amalg" -Itests \
        tests/switches_check.c "$tmp/amalg/tinygi.c" -Wl,--gc-sections $TG_LDLIBS -o "$tmp/$name" >"$tmp/$name.log" 2>&1
    echo $? >"$tmp/$name.rc"
}

# check one configuration: it built, runs and passes, and left nothing of its switches in
check() {
    local name=$1 sw left; shift
    if [ "$(cat "$tmp/$name.rc")" != 0 ]; then fail "switches/$name: build" "$(head -c 600 "$tmp/$name.log")"; return; fi
    if "$tmp/$name" >"$tmp/$name.out" 2>&1; then ok "switches/$name: renders, refuses what is left out"
    else fail "switches/$name: run" "$(grep -v '^ok' "$tmp/$name.out" | head -n 8)"; fi
    for sw in "$@"; do
        left=$(nm "$tmp/$name" | grep -E "$(pattern "$sw")" | head -n 3 | tr '\n' ' ')
        if [ -z "$left" ]; then ok "switches/$name: nothing of TG_NO_$sw linked"
        else fail "switches/$name: nothing of TG_NO_$sw linked" "still there: $left"; fi
    done
}

# each switch alone and all six, both number types; two builds at a time
configs=""
for num in float fixed; do
    for sw in $SWITCHES all; do configs="$configs $num-$sw"; done
done
switches_of() { if [ "${1#*-}" = all ]; then echo "$SWITCHES"; else echo "${1#*-}"; fi; }
numdef_of() { [ "${1%%-*}" = fixed ] && echo -DTG_FIXED=1; }
running=0
for c in $configs; do
    # shellcheck disable=SC2046
    build "$c" "$(numdef_of "$c")" $(switches_of "$c") &
    running=$((running + 1))
    if [ "$running" -ge 2 ]; then wait; running=0; fi
done
wait
for c in $configs; do
    # shellcheck disable=SC2046
    check "$c" $(switches_of "$c")
done
summary
