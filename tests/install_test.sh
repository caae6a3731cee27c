#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/install_test.sh - `make install` into a scratch PREFIX: libraries,
# the one header, the CLI and a pkg-config file per number type; the README's
# pkg-config line compiles examples/minimal.c against the installed library
# (both number types) and it renders what the CLI renders; `make examples
# EXAMPLES_LIB=installed` builds; `make uninstall` leaves no file behind;
# DESTDIR stages under another root while the .pc files name PREFIX.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
. tests/build_check.sh
P=$T/prefix
PKG_CONFIG=${PKG_CONFIG:-pkg-config}
export PKG_CONFIG_PATH=$P/lib/pkgconfig

# pc --cflags|--libs NAME: pkg-config, or the .pc file read directly on a
# machine without pkg-config (CI has it)
pc() {
    if command -v "$PKG_CONFIG" >/dev/null; then "$PKG_CONFIG" "$1" "$2"; return; fi
    local f=$P/lib/pkgconfig/$2.pc field=Cflags
    [ "$1" = --libs ] && field=Libs
    sed -n "s/^$field: //p" "$f" | sed "s|\${includedir}|$(sed -n 's/^includedir=//p' "$f")|g; s|\${libdir}|$(sed -n 's/^libdir=//p' "$f")|g"
}
quiet() { "$@" >/dev/null 2>&1; }
files_under() { (cd "$1" 2>/dev/null && find . ! -type d | sort); }

if sub_make install PREFIX="$P" >"$T/log" 2>&1; then ok "make install PREFIX=..."
else fail "make install PREFIX=..." "$(tail -n 10 "$T/log")"; fi
expected="./bin/tinygi ./bin/tinygi-fixed ./include/tinygi.h ./lib/libtinygi-fixed.a ./lib/libtinygi.a ./lib/pkgconfig/tinygi-fixed.pc ./lib/pkgconfig/tinygi.pc"
got=$(files_under "$P" | tr '\n' ' ')
expect "installed exactly: $expected" test "$got" = "$expected "
expect "the installed header includes no other tinygi header" test -z "$(grep '#include *"' "$P/include/tinygi.h")"
command -v "$PKG_CONFIG" >/dev/null || echo "note: $PKG_CONFIG not found; the .pc files are read directly"
expect "tinygi-fixed.pc: -DTG_FIXED=1 in Cflags" grep -q -- '-DTG_FIXED=1' <(pc --cflags tinygi-fixed)
expect "tinygi.pc: no TG_FIXED" test -z "$(pc --cflags tinygi | grep TG_FIXED)"
expect "installed CLI runs" quiet "$P/bin/tinygi" list

line=$(readme_line pkg-config)
expect "README has the pkg-config line" test -n "$line"
for num in ${line:+float fixed}; do
    # the README's line, for this number type, with the build's flags (a
    # sanitizer build's library needs them at link time) and output in $T
    cmd=${line/pkg-config/$PKG_CONFIG}; cmd=${cmd//tinygi)/tinygi$(suffix $num))}
    cmd="${cmd/#cc /\$CC \$TG_CFLAGS } \$TG_LDLIBS"; cmd=${cmd/-o minimal/-o \$T/minimal-$num}
    command -v "$PKG_CONFIG" >/dev/null || cmd=${cmd//$PKG_CONFIG/pc}
    if eval "$cmd" 2>"$T/cc.err"; then ok "README pkg-config line compiles examples/minimal.c ($num)"
    else fail "README pkg-config line compiles examples/minimal.c ($num)" "$cmd: $(head -n 10 "$T/cc.err")"; continue; fi
    same_as_cli "installed library renders what the CLI renders ($num)" "$T/minimal-$num" $num
done
if command -v "$PKG_CONFIG" >/dev/null; then
    if sub_make examples EXAMPLES_LIB=installed >"$T/log" 2>&1; then ok "make examples EXAMPLES_LIB=installed"
    else fail "make examples EXAMPLES_LIB=installed" "$(tail -n 10 "$T/log")"; fi
    same_as_cli "examples-installed/minimal (fixed)" "$BUILD/fixed/examples-installed/minimal" fixed
fi

if sub_make uninstall PREFIX="$P" >"$T/log" 2>&1; then ok "make uninstall PREFIX=..."
else fail "make uninstall PREFIX=..." "$(tail -n 10 "$T/log")"; fi
expect "nothing left after uninstall" test -z "$(files_under "$P")"

S=$T/stage
sub_make install DESTDIR="$S" PREFIX=/opt/tinygi >"$T/log" 2>&1
expect "DESTDIR: everything under DESTDIR/PREFIX" test "$(files_under "$S/opt/tinygi" | wc -l)" -eq 7 -a "$(files_under "$S" | grep -vc '^\./opt/tinygi/')" -eq 0
expect "DESTDIR: the .pc names PREFIX, not DESTDIR" grep -qx 'prefix=/opt/tinygi' "$S/opt/tinygi/lib/pkgconfig/tinygi.pc"
sub_make uninstall DESTDIR="$S" PREFIX=/opt/tinygi >"$T/log" 2>&1
expect "DESTDIR: nothing left after uninstall" test -z "$(files_under "$S")"
summary
