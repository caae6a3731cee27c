# SPDX-License-Identifier: MIT
# tests/shcheck.sh - sourced by the script tests: ok/fail counting that
# matches check.h ("ok NAME" / "FAIL NAME", then "TESTS passed N failed M").
sh_passed=0; sh_failed=0
ok()   { echo "ok $1"; sh_passed=$((sh_passed + 1)); }
fail() { echo "FAIL $1${2:+: $2}"; sh_failed=$((sh_failed + 1)); }
# expect NAME COND-EXIT-STATUS...: run "$@" after the name; pass when it succeeds
expect() { local name=$1; shift; if "$@"; then ok "$name"; else fail "$name"; fi; }
summary() { echo "TESTS passed $sh_passed failed $sh_failed"; [ "$sh_failed" -eq 0 ]; }
# sh_build: $BUILD (default build) as an absolute path.
sh_build() { BUILD=${BUILD:-build}; case $BUILD in /*) ;; *) BUILD=$PWD/$BUILD ;; esac; }
# sh_scratch NAME: $T, a fresh directory ${TMPDIR:-/tmp}/tgi_NAME_XXXXXX,
# removed on exit (made writable first: some tests make read-only files).
sh_scratch() {
    T=$(mktemp -d "${TMPDIR:-/tmp}/tgi_$1_XXXXXX")
    trap 'chmod -R u+w "$T" 2>/dev/null; rm -rf "$T"' EXIT
}
# sh_host_build: what a script that compiles the core itself uses: BUILD,
# CC, TG_CFLAGS, TG_LDLIBS as make passes them (or the defaults) and $tmp, a
# scratch directory removed on exit.
sh_host_build() {
    BUILD=${BUILD:-build}
    CC=${CC:-cc}
    TG_CFLAGS=${TG_CFLAGS:--std=c99}
    TG_LDLIBS=${TG_LDLIBS:--lm}
    tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
}
# each_cli FN: FN TAG for each CLI ($BUILD/tinygi, $BUILD/tinygi-fixed) with
# $BIN the program and $tag its name; a CLI not built fails TAG/built.
each_cli() {
    for BIN in "$BUILD/tinygi" "$BUILD/tinygi-fixed"; do
        tag=$(basename "$BIN")
        if [ ! -x "$BIN" ]; then fail "$tag/built" "$BIN missing"; continue; fi
        "$1" "$tag"
    done
}
