#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/amalgamate.sh - the single-file build (`make amalgamation`).
#
#   sh tools/amalgamate.sh OUTDIR SRC.c...      (run from the repository root)
#
# Writes OUTDIR/tinygi.h (src/tinygi.h with every header it includes inlined),
# OUTDIR/tinygi_scene.h (src/tinygi_scene.h, the scene's tables for files
# baked by tinygi-bake, with the core headers it needs inlined, on top of
# tinygi.h) and OUTDIR/tinygi.c (every SRC.c in the order given, which includes
# "tinygi.h" once and inlines each internal header the first time a source
# includes it; later includes of it are dropped).  Quoted includes are looked
# up beside the including file, then in src/; <system> includes are kept.
# To keep one translation unit equal to the separate files:
#  - every macro a .c file defines is #undef'd after that file;
#  - a file-scope static name defined by more than one .c file is renamed in
#    each file after the first (#define NAME tgi_DIR_FILE_NAME ... #undef);
#    stderr says how many, and lists them with AMALGAMATE_VERBOSE=1 (rename
#    one in src/ and it leaves the list);
#  - an internal include inside #if/#ifdef (other than a header's own include
#    guard) is refused, since it is inlined only once.
# #line directives in tinygi.c keep compiler messages pointing at src/.
set -eu
[ $# -ge 2 ] || { echo "usage: sh tools/amalgamate.sh OUTDIR SRC.c..." >&2; exit 2; }
out=$1; shift
mkdir -p "$out"
version=$(sed -n 's/^#define TG_VERSION "\(.*\)".*/\1/p' src/tinygi.h)

awk -v out="$out" -v version="$version" -v verbose="${AMALGAMATE_VERBOSE:-0}" -f "$(dirname "$0")/amalgamate.awk" "$@"
