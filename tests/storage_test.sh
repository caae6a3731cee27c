#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/storage_test.sh - what the compact storage formats (raster/gview.h:
# binary32 depth, octahedral normals with a material index, 8-bit AO,
# octahedral 8-bit bent normals, RGB9E5 radiance) cost in accuracy: every
# built-in scene, both number types, rendered with them and with the wide
# tg_real planes (a second build, TG_WIDE_STORAGE=1, in $BUILD/wide), and
# compared by `tinygi diff`.  Bounds (stated): AO RMSE <= 0.005 and colour
# PSNR >= 45 dB, one frame and four (reprojection and temporal
# accumulation), at 160x120.  The bench measures the same at full size.
# And what the formats buy (--explain at 320x240, cornell and columns, every
# buffer but the shadow maps and the frame's fixed state): colour with
# reprojection and temporal accumulation <= 32 bytes a pixel, one colour
# frame <= 24, AO only <= 8.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh
WIDE=$BUILD/wide
scenes="plane groove cornell spheres columns"

if sub_make BUILD="$WIDE" CPPFLAGS=-DTG_WIDE_STORAGE=1 "$WIDE/tinygi" "$WIDE/tinygi-fixed" >"$T/log" 2>&1; then
    ok "the wide-storage build (TG_WIDE_STORAGE=1)"
else
    fail "the wide-storage build (TG_WIDE_STORAGE=1)" "$(grep -m 10 -E 'error|warning' "$T/log")"
    summary; exit
fi

# within NAME KIND VALUE: VALUE (rmse or psnr, "inf" when identical) within the bound
within() {
    local name=$1 kind=$2 v=$3
    if [ "$kind" = rmse ] && awk -v r="$v" 'BEGIN { exit !(r != "" && r + 0 <= 0.005) }'; then ok "$name (AO RMSE $v)"
    elif [ "$kind" = psnr ] && awk -v p="$v" 'BEGIN { exit !(p == "inf" || (p != "" && p + 0 >= 45)) }'; then ok "$name ($v dB)"
    else fail "$name" "$kind $v outside the bound (AO RMSE <= 0.005, colour PSNR >= 45 dB)"; fi
}

for num in float fixed; do
    sfx=$(suffix $num)
    for s in $scenes; do
        for frames in 1 4; do
            for aov in ao color; do
                ext=ppm kind=psnr; [ $aov = ao ] && { ext=pfm; kind=rmse; }
                a=$T/$s-$aov-$frames-compact.$ext; b=$T/$s-$aov-$frames-wide.$ext
                name="compact vs wide storage: $num $s $aov, $frames frame(s)"
                if ! "$BUILD/tinygi$sfx" render builtin:$s --size 160x120 --frames $frames --aov $aov -o "$a" --quiet ||
                   ! "$WIDE/tinygi$sfx" render builtin:$s --size 160x120 --frames $frames --aov $aov -o "$b" --quiet; then
                    fail "$name" "render failed"; continue
                fi
                v=$("$BUILD/tinygi" diff "$b" "$a" --tolerance 1000 2>/dev/null | awk -v k=$kind '$1 == k {print $2}')
                within "$name" $kind "$v"
            done
        done
    done
done
# per_pixel SCENE ARGS...: bytes a pixel of the plan's buffers but the shadow maps and the frame state
per_pixel() {
    local s=$1; shift
    "$BUILD/tinygi" render "builtin:$s" --size 320x240 "$@" --explain |
        awk '/^total:/ {exit} /^  / && / bytes$/ && !/^  shadow map/ && !/^  frame state/ {b += $(NF - 1)} END {printf "%.2f", b / 76800}'
}
for s in cornell columns; do
    for goal in "32|colour, 10 frames|--frames 10" "24|colour, 1 frame|" "8|AO only|--aov ao"; do
        bound=${goal%%|*}; rest=${goal#*|}; name=${rest%%|*}; args=${rest#*|}
        # shellcheck disable=SC2086
        b=$(per_pixel $s $args)
        if awk -v b="$b" -v m="$bound" 'BEGIN { exit !(b != "" && b + 0 > 0 && b + 0 <= m) }'; then
            ok "memory: $s $name, $b bytes a pixel (<= $bound)"
        else
            fail "memory: $s $name" "$b bytes a pixel, over $bound"
        fi
    done
done
summary
