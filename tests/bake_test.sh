#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# bake_test.sh - tinygi-bake (tools/scene_bake.c), both number types: a
# scene baked into C data renders the same images, bit for bit, as the
# scene parsed from its text (tests/bake_check.c: colour, direct, near,
# depth, normal, albedo, AO and bent normals over several frames), for the
# Cornell box, OBJ meshes, and a scene with camera and object keys, a
# shadowed spot light, spheres, a two-sided emitter and an SH9 environment.
# A baked file built for the other number type or another scene layout
# (TGI_SCENE_LAYOUT) stops with its #error, and
# bad input is FILE:LINE:COL: error:, exit 2.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_host_build

cat >"$tmp/keys.scene" <<'SCENE'
camera_key t 0  pos 0 2 -6  target 0 0.5 0
camera_key t 1  pos 1 2.2 -5.5  target 0 0.6 0
material floor albedo 0.7 0.7 0.7  f0 0.04
material red albedo 0.7 0.1 0.1
material glow albedo 0.5 0.5 0.5  emissive 2 1.5 1  twosided
quad p0 -4 0 -4  p1 -4 0 4  p2 4 0 4  p3 4 0 -4  material floor name floor
box min -0.5 0 -0.5  max 0.5 1 0.5  material red name block
sphere center 1.5 0.6 0  radius 0.6  material floor  segments 10  name ball
quad p0 -2 0.2 1  p1 -2 1.2 1  p2 -1 1.2 1  p3 -1 0.2 1  material glow name panel
object_key name block  t 0
object_key name block  t 1  translate 0.3 0 0  rotate 0 1 0 30
light spot pos 0 3 -1  dir 0 -1 0.3  angle 40  color 1 0.9 0.8  intensity 12  shadows
light directional dir -0.3 -1 0.2  color 0.4 0.5 0.6  intensity 1
env sh9 0.3 0.35 0.4  0.05 0.05 0.06  0.1 0.1 0.12  0 0 0  0.01 0.01 0.01  0 0 0  -0.02 -0.02 -0.02  0 0 0  0.01 0.01 0.01
gi radius 1.5 slices 2 samples 4
SCENE
printf 'camera pos 0 1 -3  target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nquad p0 0 0 0  p1 1 0 0  p2 1 1 0  p3 0 1 x  material m\n' >"$tmp/bad.scene"
printf 'camera pos 0 1 -3  target 0 0 0\nmaterial m albedo 0.5 0.5 0.5\nquad p0 0 0 0  p1 1 0 0  p2 1 1 0  p3 0 1 0  material m\n' >"$tmp/good.scene"

host_objs() { ls "$BUILD/$1"/platform/hosted/*.o "$BUILD/$1"/platform/fbdev/*.o 2>/dev/null | tr '\n' ' '; }
for num in float fixed; do
    bake=$BUILD/tinygi-bake lib=$BUILD/libtinygi.a def=""
    [ $num = fixed ] && { bake=$BUILD/tinygi-bake-fixed lib=$BUILD/libtinygi-fixed.a def=-DTG_FIXED=1; }
    i=0
    for scene in builtin:cornell tests/scenes/meshes.scene "$tmp/keys.scene"; do
        i=$((i + 1))
        name="$num: $(basename "$scene")"
        if ! "$bake" --name bake_scene "$scene" -o "$tmp/baked-$num-$i.c" 2>"$tmp/err"; then
            fail "bake/$name: bake" "$(head -c 400 "$tmp/err")"; continue
        fi
        # shellcheck disable=SC2086
        if ! $CC $TG_CFLAGS $def -D_POSIX_C_SOURCE=200809L -Isrc -Iplatform -Itests tests/bake_check.c \
                "$tmp/baked-$num-$i.c" $(host_objs $num) "$lib" $TG_LDLIBS -o "$tmp/check-$num-$i" 2>"$tmp/err"; then
            fail "bake/$name: build" "$(head -c 600 "$tmp/err")"; continue
        fi
        if "$tmp/check-$num-$i" "$scene" 3 >"$tmp/out" 2>&1; then ok "bake/$name: baked renders bit-identical to parsed"
        else fail "bake/$name: bit-identical" "$(grep -v '^ok' "$tmp/out" | head -n 6)"; fi
    done
    # the other number type's build stops at the #error
    other=-DTG_FIXED=1; [ $num = fixed ] && other=""
    # shellcheck disable=SC2086
    if $CC $TG_CFLAGS $other -Isrc -c "$tmp/baked-$num-1.c" -o "$tmp/x.o" 2>"$tmp/err"; then
        fail "bake/$num: built with the other number type" "compiled"
    elif grep -q "baked for $num" "$tmp/err"; then ok "bake/$num: the other number type stops at #error"
    else fail "bake/$num: the other number type" "$(head -c 300 "$tmp/err")"; fi
    # a file baked for another scene layout (tgi_material without its diffuse factor, say) stops at its #error
    sed 's/^#if TGI_SCENE_LAYOUT != \([0-9]*\)$/#if TGI_SCENE_LAYOUT != \1 + 1/' "$tmp/baked-$num-1.c" >"$tmp/old-layout.c"
    # shellcheck disable=SC2086
    if ! grep -q '^#if TGI_SCENE_LAYOUT != [0-9]* + 1$' "$tmp/old-layout.c"; then
        fail "bake/$num: scene layout" "the baked file has no layout check"
    elif $CC $TG_CFLAGS $def -Isrc -c "$tmp/old-layout.c" -o "$tmp/x.o" 2>"$tmp/err"; then
        fail "bake/$num: built for another scene layout" "compiled"
    elif grep -q "baked for scene layout" "$tmp/err"; then ok "bake/$num: another scene layout stops at #error"
    else fail "bake/$num: another scene layout" "$(head -c 300 "$tmp/err")"; fi
    # bad input: FILE:LINE:COL: error:, exit 2, no output file
    "$bake" "$tmp/bad.scene" -o "$tmp/bad.c" 2>"$tmp/err"; rc=$?
    if [ $rc = 2 ] && grep -q "bad.scene:3:[0-9]*: error:" "$tmp/err" && [ ! -e "$tmp/bad.c" ]; then
        ok "bake/$num: bad input is FILE:LINE:COL, exit 2"
    else fail "bake/$num: bad input" "exit $rc: $(head -c 300 "$tmp/err")"; fi
    # never over an input (the scene itself, or through a link to it): exit 2, the scene intact
    cp "$tmp/good.scene" "$tmp/in.scene"
    ln -sf in.scene "$tmp/in-link.c"
    "$bake" "$tmp/in.scene" -o "$tmp/in.scene" 2>"$tmp/err"; rc=$?
    "$bake" "$tmp/in.scene" -o "$tmp/in-link.c" 2>>"$tmp/err"; rc2=$?
    if [ $rc = 2 ] && [ $rc2 = 2 ] && cmp -s "$tmp/good.scene" "$tmp/in.scene" && grep -q "refusing to overwrite" "$tmp/err"; then
        ok "bake/$num: the output is the input: refused, exit 2"
    else fail "bake/$num: output over the input" "exit $rc, $rc2: $(head -c 300 "$tmp/err")"; fi
    # a source name holding "*/" stays inside the file's comment: the file compiles
    mkdir -p "$tmp/we*"
    cp "$tmp/good.scene" "$tmp/we*/s.scene"
    # shellcheck disable=SC2086
    if "$bake" "$tmp/we*/s.scene" -o "$tmp/star.c" 2>"$tmp/err" &&
       $CC $TG_CFLAGS $def -Isrc -c "$tmp/star.c" -o "$tmp/star.o" 2>>"$tmp/err"; then
        ok "bake/$num: a source path with */ compiles"
    else fail "bake/$num: a source path with */" "$(head -c 300 "$tmp/err")"; fi
done
summary
