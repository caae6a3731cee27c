#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tools/size_table.sh - `make size-table`: the flash a program built on
# tinygi takes on a Cortex-M4, per configuration of the feature switches
# (tinygi.h "FEATURE SWITCHES"), printed as the README's table.
#
# Each configuration builds the core with the top Makefile for
# arm-none-eabi-gcc -Os -mthumb -mcpu=cortex-m4 -ffunction-sections
# -fdata-sections, and links tools/size_app.c (parse a scene, plan, render,
# write display pixels) against it with --gc-sections and no C library but
# platform/baremetal/libc_mini.c, so the linker keeps only what is reached.
# Printed: the .text section of that program in bytes (the code; read-only
# data such as the built-in scenes' text is in .rodata, in the last column),
# for Q16.16, float in software (Cortex-M4 without FPU), and float on the
# FPU (Cortex-M4F, -mfpu=fpv4-sp-d16 -mfloat-abi=hard).
#
#   SIZE_LTO=1   also link with -flto (one more table)
#   SIZE_TOP=N   then list, for each configuration's Q16.16 program (without
#                -flto), the N largest source files (tools/size_files.awk
#                on the link map) and the N largest functions
#                (arm-none-eabi-nm --size-sort)
#   SIZE_BUILD=dir  where to build (default build-size)
#   SIZE_ROWS="0 3" only these rows (0-based; default all), SIZE_NUMS="fixed"
#                only these number types (of fixed soft fpu): for trying a
#                change (the README's tables have every row and column)
#   SIZE_BAKE="float-tool fixed-tool"  tinygi-bake for the host, both number
#                types (default build/tinygi-bake build/tinygi-bake-fixed):
#                a configuration with TG_NO_SCENE_TEXT links size_app's
#                scene baked into C data instead of parsing it
# Needs arm-none-eabi-gcc (`make cross-install` installs it).
set -u
cd "$(dirname "$0")/.." || exit 1
MAKE=${MAKE:-make}
OUT=${SIZE_BUILD:-build-size}
LTO=${SIZE_LTO:-0}
TOP=${SIZE_TOP:-0}
read -r BAKE_FLOAT BAKE_FIXED <<<"${SIZE_BAKE:-build/tinygi-bake build/tinygi-bake-fixed}"
HOSTCC=${HOSTCC:-cc}
CC=arm-none-eabi-gcc
if ! command -v $CC >/dev/null 2>&1 || ! command -v arm-none-eabi-size >/dev/null 2>&1; then
    echo "size-table: $CC not found; \`make cross-install\` installs it" >&2
    exit 1
fi
BM=platform/baremetal
CPU="-mthumb -mcpu=cortex-m4"
FPU="-mfpu=fpv4-sp-d16 -mfloat-abi=hard"
SECTIONS="-ffunction-sections -fdata-sections"
LEAN="-DTG_NO_TECHNIQUES=1 -DTG_NO_REFERENCE=1 -DTG_NO_OBJ=1 -DTG_NO_BUILTIN_SCENES=1"
BAKED="$LEAN -DTG_NO_ENVIRONMENT=1 -DTG_NO_SCENE_TEXT=1 -DTG_NO_WIDE_CLIP=1"
AO="$BAKED -DTG_NO_SHADOW_MAPS=1 -DTG_NO_COLOR=1 -DTG_NO_BENT_NORMALS=1"
ALONE="-DTG_NO_GI_QUARTER=1 -DTG_NO_TEMPORAL=1 -DTG_NO_ANIMATION=1"

# configurations: name | switches | what size_app asks for
CONFIGS=(
    "full (every feature)||colour"
    "HBIL colour, direct light, shadows, sky (no techniques, reference, OBJ, built-in scenes)|$LEAN|colour"
    "HBIL colour, direct light, shadows (the same without environment)|$LEAN -DTG_NO_ENVIRONMENT=1|colour"
    "HBIL colour, direct light, shadows, baked scene (the same without scene text)|$BAKED|colour"
    "AO only, baked scene (the same without colour, shadow maps and bent normals)|$AO|ao"
    "HBIL colour, direct light, shadows, baked scene, each frame alone (also no quarter resolution, temporal, keys)|$BAKED $ALONE|colour"
    "AO only, baked scene, each frame alone (every switch set)|$AO $ALONE -DTG_NO_FINE_HORIZON=1|ao"
)
NUMS=${SIZE_NUMS:-fixed soft fpu}
ROWS=${SIZE_ROWS:-${!CONFIGS[*]}}

# build one core library: $1 directory, $2 number type, $3 switches, $4 extra flags
build_lib() {
    local dir=$1 num=$2 defs=$3 extra=$4 flags lib
    flags="$CPU $SECTIONS $defs $extra"
    [ "$num" = fpu ] && flags="$flags $FPU"
    lib=$dir/libtinygi.a; [ "$num" = fixed ] && lib=$dir/libtinygi-fixed.a
    # shellcheck disable=SC2086
    $MAKE -s -j2 BUILD="$dir" CC=$CC AR=arm-none-eabi-gcc-ar CFLAGS=-Os EXTRA_CFLAGS="$flags" "$lib" \
        >"$dir.log" 2>&1 || { echo "size-table: building $dir failed, see $dir.log" >&2; return 1; }
    echo "$lib"
}

# link size_app against it; prints ".text .rodata+.data" in bytes
link_app() {
    local dir=$1 num=$2 defs=$3 extra=$4 lib=$5 want=$6 flags app
    flags="-std=c99 -Os $CPU $SECTIONS $defs $extra"
    [ "$num" = fixed ] && flags="$flags -DTG_FIXED=1"
    [ "$num" = fpu ] && flags="$flags $FPU"
    [ "$want" = ao ] && flags="$flags -DTG_SIZE_AO_ONLY=1"
    app=$dir/size_app-$num.elf
    baked=""
    case " $defs " in *" -DTG_NO_SCENE_TEXT=1 "*)
        # the scene size_app would parse, printed on the host and baked
        baked=$dir/baked-$num.c
        bake=$BAKE_FLOAT; [ "$num" = fixed ] && bake=$BAKE_FIXED
        # shellcheck disable=SC2086
        $HOSTCC -std=c99 -Isrc $defs -DTG_SIZE_PRINT_SCENE=1 -DTG_SIZE_AO_ONLY=$([ "$want" = ao ] && echo 1 || echo 0) \
            tools/size_app.c -o "$dir/print_scene" >>"$dir.log" 2>&1 &&
        "$dir/print_scene" >"$dir/size_app.scene" &&
        "$bake" --name tgs_baked_scene "$dir/size_app.scene" -o "$baked" >>"$dir.log" 2>&1 ||
            { echo "size-table: baking the scene for $app failed, see $dir.log" >&2; return 1; }
    esac
    # shellcheck disable=SC2086
    $CC $flags -fno-lto -fno-tree-loop-distribute-patterns -c $BM/libc_mini.c -o "$dir/libc_mini-$num.o" \
        >>"$dir.log" 2>&1 &&
    $CC $flags -ffreestanding -nostdlib -Isrc -e tgs_start -Wl,--gc-sections -Wl,-Map="$app.map" tools/size_app.c $baked "$lib" \
        "$dir/libc_mini-$num.o" -lgcc -o "$app" >>"$dir.log" 2>&1 ||
        { echo "size-table: linking $app failed, see $dir.log" >&2; return 1; }
    arm-none-eabi-size -A "$app" | awk '$1 == ".text" {t = $2} $1 == ".rodata" || $1 == ".data" {r += $2}
                                      END {print t, r + 0}'
    echo "$app" >"$dir/app-$num"
}

kb() { awk -v b="$1" 'BEGIN {printf "%.1f KB", b / 1024}'; }

table() {
    local extra=$1 title=$2 i cfg name defs want num dir lib sizes cells rodata
    echo "$title"
    echo
    echo "| configuration | Q16.16 | float, soft | float, FPU (M4F) | read-only data (Q16.16) |"
    echo "|---|---:|---:|---:|---:|"
    for i in $ROWS; do
        cfg=${CONFIGS[$i]}; name=${cfg%%|*}; defs=${cfg#*|}; want=${defs#*|}; defs=${defs%|*}
        cells=""; rodata=""
        for num in $NUMS; do
            dir=$OUT/c$i${extra:+-lto}-$num
            lib=$(build_lib "$dir" "$num" "$defs" "$extra") || return 1
            sizes=$(link_app "$dir" "$num" "$defs" "$extra" "$lib" "$want") || return 1
            cells="$cells | $(kb "${sizes% *}")"
            [ "$num" = fixed ] && rodata=$(kb "${sizes#* }")
        done
        echo "| $name$cells | $rodata |"
    done
    echo
}

mkdir -p "$OUT"
echo "Cortex-M4 .text of tools/size_app.c + the core ($($CC -dumpversion), -Os -mthumb -mcpu=cortex-m4,"
echo "-ffunction-sections -fdata-sections, --gc-sections; \`make size-table\`):"
echo
table "" "#### Linked with --gc-sections" || exit 1
if [ "$LTO" = 1 ]; then table "-flto" "#### ... and -flto" || exit 1; fi
if [ "$TOP" -gt 0 ]; then
    for i in $ROWS; do
        echo "#### largest files, Q16.16: ${CONFIGS[$i]%%|*}"
        awk -f tools/size_files.awk "$(cat "$OUT/c$i-fixed/app-fixed").map" | sort -rn | head -n "$TOP"
        echo "#### largest functions, Q16.16: ${CONFIGS[$i]%%|*}"
        arm-none-eabi-nm --size-sort -S -t d "$(cat "$OUT/c$i-fixed/app-fixed")" | grep -i ' t ' |
            tail -n "$TOP" | awk '{printf "  %6d  %s\n", $2, $4}' | sort -rn
    done
fi
