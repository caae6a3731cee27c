# SPDX-License-Identifier: MIT
# tests/build_check.sh - sourced by the build tests (install, amalgamation,
# README snippet), after tests/shcheck.sh: sets $BUILD (absolute) and a
# scratch directory $T, removed on exit.
# `make test` hands the scripts its compiler and flags: CC, TG_CFLAGS (every
# compile flag), TG_LDLIBS (link flags and libraries), MAKE and MAKEFLAGS.
sh_build
sh_scratch build
CC=${CC:-cc}
TG_CFLAGS=${TG_CFLAGS:--std=c99 -O2}
TG_LDLIBS=${TG_LDLIBS:-}
numdef() { [ "$1" = fixed ] && echo "-DTG_FIXED=1"; }
suffix() { [ "$1" = fixed ] && echo "-fixed"; }

# sub_make ARGS...: make with the caller's variables (CC=, DEV=, CFLAGS= ... in
# MAKEFLAGS) but without its job server, so nothing is rebuilt with other flags.
sub_make() {
    MAKEFLAGS=$(printf '%s' "${MAKEFLAGS:-}" | sed 's/--jobserver-[a-z]*=[^ ]*//g; s/-j[0-9]*//g') \
        "${MAKE:-make}" --no-print-directory BUILD="$BUILD" "$@"
}

# same_as_cli NAME PROGRAM NUM: PROGRAM (a build of examples/minimal.c) writes
# on stdout the very PPM that `tinygi render builtin:cornell` writes.
same_as_cli() {
    local name=$1 prog=$2 num=$3
    [ -f "$T/cli-$num.ppm" ] || "$BUILD/tinygi$(suffix "$num")" render builtin:cornell --quiet -o "$T/cli-$num.ppm"
    if "$prog" >"$T/example.ppm" 2>"$T/example.err" && cmp -s "$T/example.ppm" "$T/cli-$num.ppm"; then ok "$name"
    else fail "$name" "$(head -c 300 "$T/example.err")"; fi
}

# readme_line WORD: the README's command line (in a code block, starting with
# "cc ") that contains WORD.
readme_line() { awk -v w="$1" '/^```/ { code = !code; next } code && /^cc / && index($0, w) { print; exit }' README.md; }
