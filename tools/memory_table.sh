#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tools/memory_table.sh - the README's memory tables ("Memory per frame" and
# "What fits where"), from the plans the core makes: every number is
# tg_plan.total_bytes as `tinygi render --explain` prints it, or the arena a
# parsed built-in scene takes (tools/memory_scene.c).  `make memory-table`
# runs it and rewrites the README between its markers.
#
#   bash tools/memory_table.sh [--readme README.md] [BUILD]
#
# BUILD holds tinygi and memory_scene (default build).  Without --readme the
# tables go to stdout.
set -eu
cd "$(dirname "$0")/.."
readme=
if [ "${1:-}" = --readme ]; then readme=$2; shift 2; fi
BUILD=${1:-build}
T=$BUILD/tinygi
SIZES="32x24 64x48 160x120 320x240 640x480"
STACK=4096          # the deepest stack measured on a Cortex-M or RV32 is 3.2 KB (README "Porting")
OTHER=2048          # the plan, the error, the command line (1.6 KB measured on the Cortex-M0)

# total SCENE ARGS...: the frame's bytes (tg_plan.total_bytes)
total() { local s=$1; shift; "$T" render "builtin:$s" "$@" --explain | awk '/^total:/ {print $2}'; }
# shadow SCENE ARGS...: the bytes of its shadow maps and their descriptors
shadow() {
    local s=$1; shift
    "$T" render "builtin:$s" "$@" --explain | awk '/^  shadow map/ {b += $(NF - 1)} END {print b + 0}'
}
human() { awk -v b="$1" 'BEGIN { if (b < 1024) printf "%d B", b; else if (b < 1048576) printf "%.1f KB", b / 1024;
                                 else printf "%.2f MB", b / 1048576 }'; }
# bytes per pixel at 320x240 of every buffer but the shadow maps
per_pixel() {
    local s=$1; shift
    awk -v t="$(total "$s" --size 320x240 "$@")" -v m="$(shadow "$s" --size 320x240 "$@")" 'BEGIN { printf "%.1f", (t - m) / 76800 }'
}

REQUESTS=("colour, 1 frame|" "colour, 10 frames (reprojection, temporal)|--frames 10"
          "AO only, 1 frame|--aov ao" "AO only, 10 frames (temporal)|--aov ao --frames 10")
MODES=("|" " --gi-quarter|--gi-quarter")

frame_table() {
    local r m name args line sz
    echo "| request (\`builtin:cornell\`) | ${SIZES// / | } | B/px at 320x240 without shadow maps: cornell (columns) |"
    echo "| --- | $(for sz in $SIZES; do printf -- '---: | '; done)---: |"
    for m in "${MODES[@]}"; do
        for r in "${REQUESTS[@]}"; do
            name=${r%%|*}${m%%|*}; args="${r#*|} ${m#*|}"
            line=""
            for sz in $SIZES; do
                # shellcheck disable=SC2086
                line="$line | $(human "$(total cornell --size "$sz" $args)")"
            done
            # shellcheck disable=SC2086
            echo "| $name$line | $(per_pixel cornell $args) ($(per_pixel columns $args)) |"
        done
    done
    line=""
    for sz in $SIZES; do line="$line | $(human "$(shadow cornell --size "$sz")")"; done
    echo "| of which shadow maps (colour, the default rule)$line | |"
}

# fits BYTES_OF_RAM SCENE_BYTES ARGS...: the largest 4:3 image (4k x 3k) whose
# scene, frame and two rows fit beside the stack and the rest, or "-"
fits() {
    local ram=$1 scene=$2 lo=0 hi=512 mid need; shift 2
    while [ $((hi - lo)) -gt 1 ]; do
        mid=$(((lo + hi) / 2))
        need=$(($(total cornell --size $((4 * mid))x$((3 * mid)) "$@") + scene + 24 * 4 * mid + 32 + STACK + OTHER))
        if [ "$need" -le "$ram" ]; then lo=$mid; else hi=$mid; fi
    done
    if [ $lo -eq 0 ]; then echo "-"; else echo "$((4 * lo))x$((3 * lo))"; fi
}

fits_table() {
    local scene r b args boards=(16384 65536 270336 532480 8388608)
    scene=$("$BUILD/memory_scene" cornell | awk '{print $2}')
    echo "| request (\`builtin:cornell\`, its scene $(human "$scene")) | 16 KB (Cortex-M0) | 64 KB | 264 KB (RP2040) | 520 KB (ESP32) | 8 MB (PSRAM) |"
    echo "| --- | --- | --- | --- | --- | --- |"
    for r in "colour, 1 frame|" "colour, 2 frames (reprojection)|--frames 2" "colour, 2 frames, --gi-quarter|--frames 2 --gi-quarter" \
             "colour, 1 frame, 8x8 shadow maps|--shadow-size 8" "colour, 2 frames, 8x8 shadow maps|--frames 2 --shadow-size 8" \
             "AO only|--aov ao" "AO only, 10 frames|--aov ao --frames 10"; do
        args=${r#*|}
        echo -n "| ${r%%|*}"
        # shellcheck disable=SC2086
        for b in "${boards[@]}"; do echo -n " | $(fits "$b" "$scene" $args)"; done
        echo " |"
    done
}

tables() {
    echo "<!-- memory-table: begin (make memory-table writes this part) -->"
    echo "Frame arena (\`tg_plan.total_bytes\`), float (Q16.16 the same but for the shadow maps, see below):"
    echo
    frame_table
    echo
    echo "What fits where: the largest 4:3 image (4k x 3k pixels) whose parsed scene, frame and two"
    echo "output rows fit in the RAM beside $((STACK / 1024)) KB of stack and $((OTHER / 1024)) KB for the plan, the error and the"
    echo "command line (- : not even 4x3):"
    echo
    fits_table
    echo
    echo "Scenes parsed (arena bytes): $("$BUILD/memory_scene" cornell columns spheres | awk '{printf "%s%s %s", (NR > 1 ? ", " : ""), $1, $2}')."
    echo "<!-- memory-table: end -->"
}

if [ -z "$readme" ]; then tables; exit 0; fi
grep -q '^<!-- memory-table: begin' "$readme" || { echo "memory_table.sh: $readme has no memory-table markers" >&2; exit 2; }
tmp=$(mktemp "$readme.XXXXXX")
tables >"$tmp.part"
awk -v part="$tmp.part" '
    /^<!-- memory-table: begin/ { while ((getline l < part) > 0) print l; skip = 1; next }
    /^<!-- memory-table: end/ { skip = 0; next }
    !skip { print }' "$readme" >"$tmp"
rm -f "$tmp.part"
mv "$tmp" "$readme"
echo "memory_table.sh: $readme updated"
