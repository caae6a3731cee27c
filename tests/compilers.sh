#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/compilers.sh - the body of `make compilers` (run by CI, not by make
# test: it builds tinygi once per compiler).  Each compiler in COMPILERS
# (default "gcc clang") builds everything in build-CC with the flags the
# Makefile chooses for it (printed), then renders every built-in scene with
# every AOV (linear PFM, every frame of a short animation, and the colour
# PPM) and every technique's AO, in float and in Q16.16; each file must be
# byte for byte the first compiler's (cmp).  Also checks that each compiler
# evaluates float arithmetic in float (FLT_EVAL_METHOD 0), the condition
# under which clang needs no -fexcess-precision.
# Ends with "N passed, N failed".  Knobs: COMPILERS, COMPILERS_SIZE (96x72),
# COMPILERS_FRAMES (3), COMPILERS_TECH_SIZE (64x48: the reference is slow).
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
COMPILERS=${COMPILERS:-gcc clang}
SIZE=${COMPILERS_SIZE:-96x72}
FRAMES=${COMPILERS_FRAMES:-3}
TECH_SIZE=${COMPILERS_TECH_SIZE:-64x48}
MAKE=${MAKE:-make}
OUT=build-compilers
rm -rf "$OUT"; mkdir -p "$OUT"

# render BIN DIR: every scene x AOV, and every technique's AO, into DIR
render() {
    local bin=$1 dir=$2 s a t rc=0 list
    list=$("$bin" list) || return 1
    mkdir -p "$dir"
    for s in $(echo "$list" | sed -n 's/^built-in scenes: //p' | sed 's/builtin://g'); do
        "$bin" render "builtin:$s" --size "$SIZE" --frames "$FRAMES" --quiet -o "$dir/$s-%d.ppm" || rc=1
        for a in $(echo "$list" | sed -n 's/^aovs: //p'); do
            "$bin" render "builtin:$s" --size "$SIZE" --frames "$FRAMES" --aov "$a" --quiet -o "$dir/$s-$a-%d.pfm" || rc=1
        done
        for t in $(echo "$list" | sed -n 's/^techniques: //p'); do
            "$bin" render "builtin:$s" --size "$TECH_SIZE" --frames 2 --technique "$t" --aov ao --quiet -o "$dir/$s-$t-ao.pfm" || rc=1
        done
    done
    return $rc
}

first=""
for c in $COMPILERS; do
    if ! command -v "$c" >/dev/null; then fail "$c: not installed"; continue; fi
    fem=$(printf '__FLT_EVAL_METHOD__\n' | "$c" -E -x c - 2>/dev/null | tail -n 1)
    expect "$c: float arithmetic in float (FLT_EVAL_METHOD $fem)" test "$fem" = 0
    start=$(date +%s)
    if ! "$MAKE" -s -j2 CC="$c" BUILD="build-$c" all >"$OUT/$c-build.log" 2>&1; then
        fail "$c: build" "$(grep -m 10 -E 'error|warning' "$OUT/$c-build.log")"; continue
    fi
    ok "$c: build ($(( $(date +%s) - start )) s): $(cat "build-$c/flags")"
    for num in float fixed; do
        bin=build-$c/tinygi; [ $num = fixed ] && bin=build-$c/tinygi-fixed
        start=$(date +%s)
        if render "$bin" "$OUT/$c/$num"; then ok "$c/$num: render ($(( $(date +%s) - start )) s)"
        else fail "$c/$num: render"; fi
    done
    if [ -z "$first" ]; then first=$c; continue; fi
    for num in float fixed; do
        a=$OUT/$first/$num; b=$OUT/$c/$num; n=0; differ=""
        for f in "$a"/*; do
            n=$((n + 1)); cmp -s "$f" "$b/${f##*/}" || differ="$differ ${f##*/}"
        done
        extra=$(for f in "$b"/*; do [ -e "$a/${f##*/}" ] || printf ' %s' "${f##*/}"; done)
        if [ -z "$differ" ] && [ -z "$extra" ] && [ "$n" -gt 1 ]; then ok "$c = $first, $num: $n files identical"
        else fail "$c = $first, $num" "differ:$(echo "$differ" | cut -c 1-300) ${extra:+only in $c:$extra}"; fi
    done
done
summary
