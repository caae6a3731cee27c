#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# platform/memory-table.sh - the frame memory table of the README's Porting section, from the
# plans the core makes (`tinygi render ... --explain`), so it can be
# regenerated whenever the core changes:
#   make && bash platform/memory-table.sh [build/tinygi] [SCENE]
set -eu
cd "$(dirname "$0")/.."
T=${1:-build/tinygi}
SCENE=${2:-builtin:cornell}
SHADOW=64
total() { "$T" render "$SCENE" --shadow-size $SHADOW "$@" --explain | awk '/^total:/ {print $2}'; }
kb() { awk -v b="$1" 'BEGIN { printf (b < 1048576 ? "%.1f KB" : "%.2f MB"), (b < 1048576 ? b / 1024 : b / 1048576) }'; }
echo "Frame arena (tg_plan.total_bytes) for $SCENE, shadow maps $SHADOW texels per side:"
echo
echo "| request | 16x12 | 64x48 | 160x120 | 320x240 | bytes/pixel at 320x240 |"
echo "| --- | --- | --- | --- | --- | --- |"
row() {
    local name=$1 sz line="" b; shift
    for sz in 16x12 64x48 160x120 320x240; do
        b=$(total --size "$sz" "$@"); line="$line | $(kb "$b")"
    done
    echo "| $name$line | $((b / 76800)) |"
}
row "colour, HBIL, 1 frame" 
row "colour, HBIL, animation (--frames 2)" --frames 2
row "colour, HBIL, full-res kernel (--no-interleave)" --no-interleave
row "colour, no bounce (--bounces 0)" --bounces 0
row "AO only (--aov ao)" --aov ao
row "AO only, SSAO (--aov ao --technique ssao)" --aov ao --technique ssao
row "depth only (--aov depth)" --aov depth
echo
sm=$("$T" render "$SCENE" --size 64x48 --shadow-size $SHADOW --explain | awk '/shadow maps \(depth\)/ {print $4}')
echo "Of which shadow maps: $(kb "${sm:-0}") at $SHADOW texels per side (they grow with the square of --shadow-size)."
