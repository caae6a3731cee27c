#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/peers/build.sh - build the peer rasterizers' bench programs, for
# `make bench-raster BENCH_PEERS=...` (tools/bench_time.py raster).
#
#   sh tools/peers/build.sh TINYGL_DIR SMALL3DLIB_DIR [OUT_DIR] [SIZES]
#
# TINYGL_DIR: a checkout of github.com/C-Chads/tinygl (measured: 36a7987);
# SMALL3DLIB_DIR: one of github.com/viteo/small3dlib (measured: 1611353, or
# drummyfish's small3dlib); neither is part of this repository or fetched
# by it.  OUT_DIR (default build/peers) gets tinygl, tinygl-list and
# small3dlib-WxH for each of SIZES (default "320x240 1280x720": small3dlib
# fixes its resolution when compiled).  The peers are compiled as their
# own builds compile them, less -march=native and OpenMP (one core, the
# baseline's x86-64): CC (default cc) with -std=c99 -O3 -DNDEBUG.  Prints
# the BENCH_PEERS value on stdout:
#
#   make bench-raster BENCH_PEERS="$(sh tools/peers/build.sh ../tinygl ../small3dlib)"
set -eu
[ $# -ge 2 ] || { echo "usage: sh tools/peers/build.sh TINYGL_DIR SMALL3DLIB_DIR [OUT_DIR] [SIZES]" >&2; exit 2; }
tgl=$1 s3l=$2 out=${3:-build/peers} sizes=${4:-"320x240 1280x720"}
here=$(cd "$(dirname "$0")" && pwd)
CC=${CC:-cc}
flags="-std=c99 -O3 -DNDEBUG"
[ -f "$tgl/include/GL/gl.h" ] && [ -f "$tgl/src/ztriangle.c" ] || { echo "build.sh: $tgl is not a TinyGL checkout" >&2; exit 2; }
[ -f "$s3l/small3dlib.h" ] || { echo "build.sh: $s3l has no small3dlib.h" >&2; exit 2; }
mkdir -p "$out/tinygl-obj"
# TinyGL's library: the objects its src/Makefile lists, compiled here (its tree untouched)
objs=$(sed -n '/^OBJS *=/,/^$/p' "$tgl/src/Makefile" | sed 's/^OBJS *=//; s/\\//g' | tr -s ' \t\n' ' ')
[ -n "$objs" ] || { echo "build.sh: no OBJS in $tgl/src/Makefile" >&2; exit 2; }
lib="$out/tinygl-obj/libTinyGL.a"
rm -f "$lib"
for o in $objs; do
    $CC $flags -w -I"$tgl/include" -c "$tgl/src/${o%.o}.c" -o "$out/tinygl-obj/$o"
done
(cd "$out/tinygl-obj" && ar rcs libTinyGL.a $objs)
$CC $flags -I"$tgl/include" "$here/peer_tinygl.c" "$lib" -lm -o "$out/tinygl"
$CC $flags -DPEER_LIST=1 -I"$tgl/include" "$here/peer_tinygl.c" "$lib" -lm -o "$out/tinygl-list"
for s in $sizes; do
    w=${s%x*} h=${s#*x}
    $CC $flags -DPEER_W="$w" -DPEER_H="$h" -I"$s3l" "$here/peer_s3l.c" -lm -o "$out/small3dlib-$s"
done
echo "built $out/tinygl, $out/tinygl-list, $out/small3dlib-{$(echo $sizes | tr ' ' ,)}" >&2
printf '%s;%s;%s\n' "$out/small3dlib-{size}" "$out/tinygl" "$out/tinygl-list"
