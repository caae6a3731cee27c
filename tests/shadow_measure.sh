#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# shadow_measure.sh - the numbers of README "Shadows": for each scene, the
# accuracy table of tests/shadow_measure.c (shadow maps at 512 texels in 32
# and 16 bits, by the size rule with each filter, shadow rays), then the
# instructions (callgrind; they do not depend on the machine's load) of the
# direct pass's shadow lookups per image pixel and of the set-up (map
# rendering, or the BVH build); then the whole frame as the plan makes it
# (tinygi render, one thread): the shadows' bytes from --explain and the
# instructions of tg_frame_render, of the shadow pass and of the direct
# pass, for --shadows auto (the default), maps and rays, and for the
# binary $BEFORE (e.g. a build of the previous commit) when given.
# Not a test: run by hand.
#
#   bash tests/shadow_measure.sh [SIZE] [SCENES...]     default 320x240 cornell columns spheres
#   NUMBER=fixed bash tests/shadow_measure.sh ...        Q16.16
#   BEFORE=/path/to/old/tinygi bash tests/shadow_measure.sh ...
set -eu
cd "$(dirname "$0")/.."
size=${1:-320x240}; shift || true
scenes=${*:-cornell columns spheres}
BUILD=${BUILD:-build}
CC=${CC:-cc}
if [ "${NUMBER:-float}" = fixed ]; then lib=$BUILD/libtinygi-fixed.a; def=-DTG_FIXED=1; tinygi=$BUILD/tinygi-fixed
else lib=$BUILD/libtinygi.a; def=; tinygi=$BUILD/tinygi; fi
make -s "$lib" "$tinygi"
bin=$BUILD/shadow_measure-${NUMBER:-float}
$CC -O2 -std=c99 $def -Isrc -Itests tests/shadow_measure.c "$lib" -lm -o "$bin"
command -v valgrind >/dev/null || { echo "valgrind is needed for the instruction counts" >&2; exit 1; }
w=${size%x*}; h=${size#*x}; pixels=$((w * h))
echo "load: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown) (instruction counts do not depend on it)"
for s in $scenes; do
    echo
    "$bin" "$s" "$size"
    echo
    echo "| method | lookups, instructions per pixel | set-up instructions (maps rendered, BVH built) |"
    echo "| --- | --- | --- |"
    for m in map16-512-tent rule16-tent rule16-bilinear plan-bilinear rays; do
        out=$(mktemp)
        valgrind --tool=callgrind --callgrind-out-file="$out" "$bin" "$s" "$size" "$m" >/dev/null 2>&1
        callgrind_annotate --inclusive=yes --threshold=100 "$out" >"$out.txt" 2>/dev/null
        get() { grep -E ":$1(_f32|_q16)? \[" "$out.txt" | head -1 | awk '{gsub(",", "", $1); print $1}'; }
        vis=$(get tgi_shadow_visibility_err); render=$(get tgi_shadow_map_render); bvh=$(get tgi_bvh_build)
        setup=${render:-${bvh:-0}}
        echo "| $m | $(( ${vis:-0} / pixels )) | $setup |"
        rm -f "$out" "$out.txt"
    done
    echo
    echo "| $s $size frame | shadow bytes | B/px | frame instructions | shadow pass | direct pass |"
    echo "| --- | --- | --- | --- | --- | --- |"
    for how in ${BEFORE:+before} auto maps rays; do
        exe=$tinygi; opt="--shadows $how"
        [ "$how" = before ] && { exe=$BEFORE; opt=; }
        bytes=$("$exe" render "builtin:$s" --size "$size" $opt --explain |
                awk -F': ' '/^  shadow maps \(depth\)|^  shadow rays: BVH/ {gsub(" bytes", "", $NF); b += $NF} END {print b + 0}')
        out=$(mktemp)
        valgrind --tool=callgrind --callgrind-out-file="$out" "$exe" render "builtin:$s" --size "$size" $opt \
            --threads 1 --quiet -o "$out.ppm" >/dev/null 2>&1
        callgrind_annotate --inclusive=yes --threshold=100 "$out" >"$out.txt" 2>/dev/null
        get() { grep -E ":$1(_f32|_q16)? \[" "$out.txt" | head -1 | awk '{gsub(",", "", $1); print $1}'; }
        echo "| $how | $bytes | $(awk -v b="$bytes" -v p="$pixels" 'BEGIN {printf "%.2f", b / p}') |" \
             "$(get tg_frame_render) | $(get tgi_pass_shadow_maps) | $(get tgi_pass_direct) |"
        rm -f "$out" "$out.txt" "$out.ppm"
    done
done
