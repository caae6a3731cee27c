#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/orbit_test.sh - examples/orbit.c (the game loop) runs, both number
# types, at 32x24 for 4 frames: it writes 4 PPM files of that size, each
# frame differs from the one before (the camera moves), every frame's mean
# radiance is a finite positive number, frame 0 is a first frame and
# frames 1-3 are reprojected from the one before (no cut detected in a
# smooth orbit); the builds from the amalgamation and the installed library
# write the same frames; a bad option is refused with exit status 2; the
# README's game-loop snippet compiles.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh

for num in float fixed; do
    prog=$BUILD/$num/examples-built/orbit
    if [ ! -x "$prog" ]; then fail "orbit ($num): $prog is not built (make)"; continue; fi
    if ! "$prog" -n 4 -s 32x24 -o "$T/$num-" >"$T/$num.out" 2>"$T/$num.err"; then
        fail "orbit ($num) runs" "$(head -c 300 "$T/$num.err")"; continue
    fi
    ok "orbit ($num) runs"
    sizes=ok; differ=ok
    for i in 0 1 2 3; do
        f=$T/$num-00$i.ppm
        header=$(head -n 3 "$f" 2>/dev/null | tr '\n' ' ')
        [ "$header" = "P6 32 24 255 " ] && [ "$(wc -c <"$f")" -eq $((13 + 32 * 24 * 3)) ] ||
            sizes="frame $i is not a 32x24 PPM ($header)"
        [ $i -gt 0 ] && cmp -s "$f" "$T/$num-00$((i - 1)).ppm" && differ="frame $i equals frame $((i - 1))"
    done
    expect "orbit ($num): 4 PPM frames of 32x24" test "$sizes" = ok
    [ "$sizes" = ok ] || echo "  $sizes"
    expect "orbit ($num): each frame differs from the one before" test "$differ" = ok
    [ "$differ" = ok ] || echo "  $differ"
    means=$(awk '{ print $(NF - 2), $(NF - 1), $NF }' "$T/$num.out" | tr '\n' ' ')
    expect "orbit ($num): finite positive mean radiance ($means)" \
        awk 'NR <= 4 { for (i = NF - 2; i <= NF; i++) if (!($i + 0 > 0 && $i + 0 < 1000)) bad = 1; n++ }
             END { exit bad || n != 4 }' "$T/$num.out"
    expect "orbit ($num): frame 0 is a first frame, frames 1-3 are reprojected" \
        test "$(cut -d, -f1 "$T/$num.out" | sed 's/.*: //' | tr '\n' ' ')" = "first frame reprojected reprojected reprojected "
    # the builds from the amalgamation and the installed library (made by
    # amalgamation_test.sh and install_test.sh, which run before) write the same frames
    for lib in amalgamation installed; do
        other=$BUILD/$num/examples-$lib/orbit
        [ -x "$other" ] || { echo "# orbit ($num, $lib): not built, not compared"; continue; }
        same=yes
        "$other" -n 4 -s 32x24 -o "$T/$num-$lib-" >/dev/null 2>&1 || same=no
        for i in 0 1 2 3; do cmp -s "$T/$num-00$i.ppm" "$T/$num-$lib-00$i.ppm" || same=no; done
        expect "orbit ($num) built from the $lib library writes the same frames" test $same = yes
    done
done

"$BUILD/float/examples-built/orbit" -n 2 -s wide -o "$T/x-" >/dev/null 2>&1
expect "orbit refuses a bad size (exit status 2)" test $? -eq 2

# README "A game loop": its C block compiles against tinygi.h, every name
# declared, in a function that gives its free variables
awk '/^### A game loop/ { on = 1 } on && /^```c/ { c = 1; next } c && /^```/ { exit } c' README.md >"$T/loop.inc"
{
    echo '#include "tinygi.h"'
    echo 'int loop(tg_request req, tg_scene *scene, tg_frame *frame, int running, int teleported,'
    echo '         const tg_real eye[3], const tg_real target[3], const tg_real up[3], tg_real fov,'
    echo '         const tg_real where[3], const tg_real axis[3], tg_real angle, const tg_real rgb[3],'
    echo '         tg_real intensity, const tg_real lamp_pos[3], const tg_real sky[3], const tg_real ground[3])'
    echo '{'
    echo '    tg_error err;'
    echo '    int i;'
    cat "$T/loop.inc"
    echo '    return req.frames + i;'
    echo '}'
} >"$T/loop.c"
expect "README has the game-loop snippet" test -s "$T/loop.inc"
# shellcheck disable=SC2086
if $CC $TG_CFLAGS -Werror=implicit-function-declaration -Wno-unused-parameter -Isrc -c "$T/loop.c" -o "$T/loop.o" 2>"$T/loop.err"; then
    ok "README game-loop snippet compiles"
else fail "README game-loop snippet compiles" "$(head -n 10 "$T/loop.err")"; fi
summary
