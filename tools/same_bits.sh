#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/same_bits.sh - do two builds render the same bits?  The check every
# speed change that claims "the same bits" runs (not in CI: it compares two
# builds, typically main before and after a change, each built with `make`).
#
#   sh tools/same_bits.sh BUILD_A BUILD_B [WxH]      (default 96x72)
#
# Renders every built-in scene but plane, in float and Q16.16, under each
# setting below (HBIL's: every pixel, quarter resolution, full resolution,
# few and many samples, AO alone over one and three layers; and every other
# technique), 3 frames to PFM (linear, every bit), with build A on 1 thread
# and build B on 2 (the split must not matter either), and compares the
# files byte for byte.  Then the moving scenes of tools/same_bits/ (a camera
# and an object that move: reprojection, temporal accumulation, push/pull
# with motion; far depths, far world coordinates), 4 frames, under
# moving_settings.  Prints each difference and the count; exit 1 when any
# file differs or a render fails.
set -u
[ $# -ge 2 ] || { echo "usage: sh tools/same_bits.sh BUILD_A BUILD_B [WxH]" >&2; exit 2; }
a=$1 b=$2 size=${3:-96x72}
tmp=$(mktemp -d) || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
settings='-
--gi-quarter
--no-interleave
--slices 1 --samples 8
--slices 4 --samples 64
--aov ao
--aov ao --depth-layers 3
--aov ao --gi-quarter --depth-layers 2
--technique gtao --aov ao
--technique ssilvb --aov ao
--technique hbao --aov ao
--technique ssao --aov ao
--technique vo --aov ao
--technique ssdo
--technique bentcone
--technique reference --aov ao
--technique pathtrace --samples 4'
moving_settings='-
--gi-quarter
--no-interleave
--aov ao
--aov near
--aov bent'
here=$(dirname "$0")
echo "0 0" >"$tmp/count"
# compare SOURCE FRAMES ARGS...: one render by each build, counted
compare() {
    src=$1 frames=$2; shift 2
    read -r n bad <"$tmp/count"
    n=$((n + 1))
    if ! "$a/tinygi$sfx" render "$src" --size "$size" --frames "$frames" --threads 1 --quiet "$@" -o "$tmp/a.pfm" 2>"$tmp/err" \
        || ! "$b/tinygi$sfx" render "$src" --size "$size" --frames "$frames" --threads 2 --quiet "$@" -o "$tmp/b.pfm" 2>>"$tmp/err"; then
        bad=$((bad + 1)); echo "FAILED $num $src $*: $(head -c 200 "$tmp/err")"
    elif ! cmp -s "$tmp/a.pfm" "$tmp/b.pfm"; then
        bad=$((bad + 1)); echo "DIFFER $num $src $*"
    fi
    echo "$n $bad" >"$tmp/count"
}
for num in float fixed; do
    sfx=; [ $num = fixed ] && sfx=-fixed
    for scene in cornell columns spheres groove; do
        echo "$settings" | while read -r args; do
            [ "$args" = - ] && args=
            # shellcheck disable=SC2086 # the settings are split into words on purpose
            compare "builtin:$scene" 3 $args
        done
    done
    for scene in "$here"/same_bits/moving-*.scene; do
        echo "$moving_settings" | while read -r args; do
            [ "$args" = - ] && args=
            # shellcheck disable=SC2086
            compare "$scene" 4 $args
        done
    done
done
read -r n bad <"$tmp/count"
echo "same_bits: $n renders of $a and $b, $bad differ or failed"
[ "$bad" = 0 ]
