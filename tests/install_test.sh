#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/install_test.sh - `make install` into a scratch PREFIX: libraries,
# the one header (and the scene header for baked scenes), the CLI, the bake
# tool and a pkg-config file per number type; a scene baked by the installed
# tinygi-bake builds against the installed library alone; the README's
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
expected="./bin/tinygi ./bin/tinygi-bake ./bin/tinygi-bake-fixed ./bin/tinygi-fixed ./include/tinygi.h ./include/tinygi_scene.h ./lib/libtinygi-fixed.a ./lib/libtinygi.a ./lib/pkgconfig/tinygi-fixed.pc ./lib/pkgconfig/tinygi.pc"
got=$(files_under "$P" | tr '\n' ' ')
expect "installed exactly: $expected" test "$got" = "$expected "
expect "the installed header includes no other tinygi header" test -z "$(grep '#include *"' "$P/include/tinygi.h")"
expect "the installed scene header includes tinygi.h alone" test "$(grep '#include *"' "$P/include/tinygi_scene.h")" = '#include "tinygi.h"'
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

# A scene baked by the installed tinygi-bake compiles against the installed
# headers and library (pkg-config alone, no source tree) and renders what
# the CLI renders from the scene's text.
cat >"$T/baked_app.c" <<'APP'
#include <stdio.h>
#include <stdlib.h>
#include "tinygi.h"
const tg_scene *tg_baked_scene(void);
int main(void)
{
    tg_request req;
    tg_plan plan;
    tg_frame *frame;
    tg_error err;
    void *memory;
    uint8_t *rgb;
    int y;
    tg_request_defaults(&req);
    if (tg_plan_make(&plan, tg_baked_scene(), &req, &err) != TG_OK) return 1;
    memory = malloc(plan.total_bytes);
    rgb = malloc((size_t)plan.request.width * 3);
    if (!memory || !rgb || tg_frame_create(&plan, memory, plan.total_bytes, &frame, &err) != TG_OK
        || tg_frame_render(frame, 0, &err) != TG_OK) return 1;
    printf("P6\n%d %d\n255\n", plan.request.width, plan.request.height);
    for (y = 0; y < plan.request.height; y++) {
        tg_frame_aov_row8(frame, TG_AOV_COLOR, y, rgb);
        fwrite(rgb, 3, (size_t)plan.request.width, stdout);
    }
    return fflush(stdout) != 0;
}
APP
for num in float fixed; do
    sfx=$(suffix $num)
    if ! "$P/bin/tinygi-bake$sfx" builtin:cornell -o "$T/baked-$num.c" 2>"$T/bake.err"; then
        fail "installed tinygi-bake$sfx bakes builtin:cornell" "$(head -c 300 "$T/bake.err")"; continue
    fi
    # shellcheck disable=SC2046,SC2086 # pkg-config's flags are split into words on purpose
    if $CC $TG_CFLAGS $(pc --cflags "tinygi$sfx") "$T/baked-$num.c" "$T/baked_app.c" $(pc --libs "tinygi$sfx") \
        $TG_LDLIBS -o "$T/baked-$num" 2>"$T/cc.err"; then ok "a scene baked by the installed tinygi-bake$sfx compiles against the installed library"
    else fail "a scene baked by the installed tinygi-bake$sfx compiles against the installed library" "$(head -n 10 "$T/cc.err")"; continue; fi
    same_as_cli "the installed baked scene renders what the CLI renders ($num)" "$T/baked-$num" $num
done

if sub_make uninstall PREFIX="$P" >"$T/log" 2>&1; then ok "make uninstall PREFIX=..."
else fail "make uninstall PREFIX=..." "$(tail -n 10 "$T/log")"; fi
expect "nothing left after uninstall" test -z "$(files_under "$P")"

S=$T/stage
sub_make install DESTDIR="$S" PREFIX=/opt/tinygi >"$T/log" 2>&1
expect "DESTDIR: everything under DESTDIR/PREFIX" test "$(files_under "$S/opt/tinygi" | wc -l)" -eq 10 -a "$(files_under "$S" | grep -vc '^\./opt/tinygi/')" -eq 0
expect "DESTDIR: the .pc names PREFIX, not DESTDIR" grep -qx 'prefix=/opt/tinygi' "$S/opt/tinygi/lib/pkgconfig/tinygi.pc"
sub_make uninstall DESTDIR="$S" PREFIX=/opt/tinygi >"$T/log" 2>&1
expect "DESTDIR: nothing left after uninstall" test -z "$(files_under "$S")"
summary
