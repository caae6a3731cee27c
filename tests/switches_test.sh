#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# switches_test.sh - the feature switches (tinygi.h "FEATURE SWITCHES"):
# the core builds and links with each one set alone and with all of them, in
# both number types, and tests/switches_check.c then renders what the build
# keeps and sees what it left out refused (TG_ERR_INPUT naming the switch).
# A build without scene text renders the same scenes baked into C data by
# $BUILD/tinygi-bake (and -fixed).
# The linked program (--gc-sections) must hold no global symbol of a
# left-out file; the full CLI, which holds them all, shows the patterns find
# them.  Host builds at -O0 (fast to compile; nothing here is timed).
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_host_build

SWITCHES="TECHNIQUES REFERENCE OBJ BUILTIN_SCENES SHADOW_MAPS ENVIRONMENT SCENE_TEXT COLOR GI_QUARTER TEMPORAL ANIMATION FINE_HORIZON WIDE_CLIP BENT_NORMALS"
# the global symbols (nm; each ends in _f32 or _q16, src/core/abi_names.h) of
# each switch's left-out files, and (COLOR) the HBIL kernel's near-field
# gather, a local function left out of a kept file
pattern() {
    case $1 in
        TECHNIQUES)     echo ' T tgi_((ssao|vo|hbao|gtao|ssilvb|ssdo|bentcone)_|pass_(ssao|vo|hbao|gtao|ssilvb|ssdo|bentcone)_(f32|q16)$)' ;;
        REFERENCE)      echo ' T tgi_(reference_|bvh_|pathtrace_|ray_triangle|pass_reference)' ;;
        OBJ)            echo ' T tgi_obj_' ;;
        BUILTIN_SCENES) echo ' [a-zA-Z] scene_(plane|groove|cornell|spheres|columns)$' ;;
        SHADOW_MAPS)    echo ' T tgi_(shadow_|raster_depth)' ;;
        ENVIRONMENT)    echo ' T tgi_(sh9_|env_radiance|far_|cone_)' ;;
        SCENE_TEXT)     echo ' T tgi_(lex_|tok_|parse_|obj_)' ;;
        COLOR)          echo ' T tgi_(direct_rows|pushpull_|reproject_gather|compose_|tonemap_row8|raster_depth|pass_(direct|reproject|push_pull(_down|_fill)?|shadow_maps)_(f32|q16)$)| t gather_rise$' ;;
        GI_QUARTER)     echo ' T tgi_(downsample_rows|upsample_pixel|pass_(downsample|filter_quarter)_(f32|q16)$)' ;;
        TEMPORAL)       echo ' T tgi_(temporal_|motion_|pushpull_|reproject_gather|pass_(temporal|motion|keep_history|reproject|push_pull(_down|_fill)?)_(f32|q16)$)' ;;
        ANIMATION)      echo ' T tgi_(anim_camera|anim_object_matrix|q_slerp)_(f32|q16)$' ;;
        # no file: the HBIL kernel's refinement on the fine image (local functions)
        FINE_HORIZON)   echo ' t (refine_fine|fine_sample)' ;;
        # no file: the kernel's and the frame's bent-normal storage, a local
        # (static inline) function at -O0; the techniques keep their own
        # (TG_NO_TECHNIQUES, TG_NO_REFERENCE), so it is checked with them gone
        BENT_NORMALS)   echo ' t tgi_gr_set_bent$' ;;
        # no file: Q16.16's 64-bit clipper (a local function; none in float)
        WIDE_CLIP)      echo ' t gbuffer_wide_triangle$' ;;
    esac
}

# the full CLI links every feature: each pattern must find something there
# (BENT_NORMALS's static function is inlined at -O2: a switch build keeping
# it, below)
full=$BUILD/tinygi
for sw in ${SWITCHES% WIDE_CLIP BENT_NORMALS}; do
    n=$(nm "$full" 2>/dev/null | grep -cE "$(pattern "$sw")")
    if [ "$n" -gt 0 ]; then ok "switches/full-cli-has-$sw"; else fail "switches/full-cli-has-$sw" "pattern finds nothing in $full"; fi
done

# the single-file build of the core (tools/amalgamate.sh): one translation
# unit per configuration compiles faster than 50, and checks the guards
# keep it whole
sh tools/amalgamate.sh "$tmp/amalg" src/*/*.c 2>/dev/null

# switches_check's scenes baked for the builds without scene text: the
# check built with SWITCHES_PRINT=1 prints them, tinygi-bake bakes them
baked_float="" baked_fixed=""
# shellcheck disable=SC2086
if $CC $TG_CFLAGS -DSWITCHES_PRINT=1 -Isrc -Itests tests/switches_check.c $BUILD/libtinygi.a $TG_LDLIBS \
       -o "$tmp/print" >"$tmp/print.log" 2>&1; then
    for scene in plain rich sky_no_far keyed; do
        "$tmp/print" $scene >"$tmp/$scene.scene" || fail "switches/print $scene" "exit $?"
        for num in float fixed; do
            bake=$BUILD/tinygi-bake; [ $num = fixed ] && bake=$BUILD/tinygi-bake-fixed
            if "$bake" --name switches_$scene "$tmp/$scene.scene" -o "$tmp/baked-$num-$scene.c" 2>"$tmp/bake.log"; then
                eval "baked_$num=\"\$baked_$num $tmp/baked-$num-$scene.c\""
            else fail "switches/bake $scene ($num)" "$(head -c 400 "$tmp/bake.log")"; fi
        done
    done
else fail "switches/print build" "$(head -c 600 "$tmp/print.log")"; fi

# build one configuration: $1 name, $2 number-type define, $3... switches set to 1
build() {
    local name=$1 num=$2 defs="" sw; shift 2
    local baked=""
    for sw in "$@"; do defs="$defs -DTG_NO_$sw=1"; done
    case " $* " in *" SCENE_TEXT "*) if [ -n "$num" ]; then baked=$baked_fixed; else baked=$baked_float; fi ;; esac
    # shellcheck disable=SC2086
    $CC $TG_CFLAGS -O0 $num $defs -ffunction-sections -fdata-sections -I"$tmp/amalg" -Itests -Isrc \
        tests/switches_check.c "$tmp/amalg/tinygi.c" $baked -Wl,--gc-sections $TG_LDLIBS -o "$tmp/$name" >"$tmp/$name.log" 2>&1
    echo $? >"$tmp/$name.rc"
}

# check one configuration: it built, runs and passes, and left nothing of its switches in
check() {
    local name=$1 sw left; shift
    if [ "$(cat "$tmp/$name.rc")" != 0 ]; then fail "switches/$name: build" "$(head -c 600 "$tmp/$name.log")"; return; fi
    if "$tmp/$name" >"$tmp/$name.out" 2>&1; then ok "switches/$name: renders, refuses what is left out"
    else fail "switches/$name: run" "$(grep -v '^ok' "$tmp/$name.out" | head -n 8)"; fi
    for sw in "$@"; do
        case $sw in BENT_NORMALS)
            case " $* " in *" TECHNIQUES "*" REFERENCE "*) ;; *) continue ;; esac ;;
        esac
        left=$(nm "$tmp/$name" | grep -E "$(pattern "$sw")" | head -n 3 | tr '\n' ' ')
        if [ -z "$left" ]; then ok "switches/$name: nothing of TG_NO_$sw linked"
        else fail "switches/$name: nothing of TG_NO_$sw linked" "still there: $left"; fi
    done
}

# each switch alone and all of them, both number types; two builds at a time
configs=""
for num in float fixed; do
    for sw in $SWITCHES all; do configs="$configs $num-$sw"; done
done
switches_of() { if [ "${1#*-}" = all ]; then echo "$SWITCHES"; else echo "${1#*-}"; fi; }
numdef_of() { [ "${1%%-*}" = fixed ] && echo -DTG_FIXED=1; }
running=0
for c in $configs; do
    # shellcheck disable=SC2046
    build "$c" "$(numdef_of "$c")" $(switches_of "$c") &
    running=$((running + 1))
    if [ "$running" -ge 2 ]; then wait; running=0; fi
done
wait
for c in $configs; do
    # shellcheck disable=SC2046
    check "$c" $(switches_of "$c")
done

# BENT_NORMALS's pattern finds the function in a build that keeps bent
# normals, WIDE_CLIP's in a Q16.16 build that keeps the wide clipper
for num in float fixed; do
    n=$(nm "$tmp/$num-TECHNIQUES" 2>/dev/null | grep -cE "$(pattern BENT_NORMALS)")
    if [ "$n" -gt 0 ]; then ok "switches/$num-TECHNIQUES has BENT_NORMALS's pattern"
    else fail "switches/$num-TECHNIQUES has BENT_NORMALS's pattern" "nothing in $tmp/$num-TECHNIQUES"; fi
done
n=$(nm "$tmp/fixed-TECHNIQUES" 2>/dev/null | grep -cE "$(pattern WIDE_CLIP)")
if [ "$n" -gt 0 ]; then ok "switches/fixed-TECHNIQUES has WIDE_CLIP's pattern"
else fail "switches/fixed-TECHNIQUES has WIDE_CLIP's pattern" "nothing in $tmp/fixed-TECHNIQUES"; fi

# every build of a number type renders the same AO, bit for bit, but those
# without the fine horizon (FINE_HORIZON, all), which render the same as
# each other and not as the rest (the refinement changes the AO)
for num in float fixed; do
    want=$(grep -m 1 '^ao-digest' "$tmp/$num-TECHNIQUES.out")
    want_coarse=$(grep -m 1 '^ao-digest' "$tmp/$num-FINE_HORIZON.out")
    differ=""
    for sw in $SWITCHES all; do
        got=$(grep -m 1 '^ao-digest' "$tmp/$num-$sw.out")
        case $sw in FINE_HORIZON|all) [ "$got" = "$want_coarse" ] || differ="$differ $sw ($got, not $want_coarse)" ;;
                    *) [ "$got" = "$want" ] || differ="$differ $sw ($got)" ;; esac
    done
    case $want in "ao-digest "[0-9a-f]*) ;; *) differ="no digest: $want" ;; esac
    [ "$want" != "$want_coarse" ] || differ="$differ FINE_HORIZON renders what the others do: no refinement to leave out"
    if [ -z "$differ" ]; then ok "switches/$num: every build renders the same AO ($want; without the fine horizon $want_coarse)"
    else fail "switches/$num: every build renders the same AO" "$want; differ:$differ"; fi
done

# A development build (-Werror in TG_CFLAGS: DEV=1, as CI) compiles each
# source file of the core on its own, as an embedder's build does, without
# a warning: every file that names a switch with that switch set (at -O0
# and at -Os: clang -Os float with TG_NO_FINE_HORIZON once found hbil.c's
# floor_small unused), every file with all of them, and every file at -Os (a build for size:
# TG_OUTLINE_HELPERS's second forms) (the amalgamation above silences clang's unused
# static functions, which a file on its own shows: a helper used only by
# code a switch leaves out).  A user's build (no -Werror) skips this: a
# newer compiler's new warning must not fail it.
case " $TG_CFLAGS " in
*" -Werror "*)
    for num in float fixed; do
        numdef=$(numdef_of "$num-")
        for sw in $SWITCHES all size; do
            opts="-O0 -Os"   # -Os: a switch with the builds for size's forms too
            case $sw in
            all)  files=$(ls src/*/*.c); defs=""; opts=-O0; for s in $SWITCHES; do defs="$defs -DTG_NO_$s=1"; done ;;
            size) files=$(ls src/*/*.c); defs=""; opts=-Os ;;   # TG_OUTLINE_HELPERS's forms (tinygi.h)
            *)    files=$(grep -l "TG_NO_$sw\b" src/*/*.c); defs="-DTG_NO_$sw=1" ;;
            esac
            bad=""
            for f in $files; do
                for opt in $opts; do
                    # shellcheck disable=SC2086
                    $CC $TG_CFLAGS $opt $numdef $defs -Isrc -c "$f" -o "$tmp/alone.o" >"$tmp/alone.log" 2>&1 ||
                        bad="$bad $f ($opt): $(grep -m 1 -E 'error|warning' "$tmp/alone.log")"
                done
            done
            if [ -z "$bad" ]; then ok "switches/$num-$sw: each file alone compiles without a warning"
            else fail "switches/$num-$sw: each file alone compiles without a warning" "$bad"; fi
        done
    done ;;
esac
summary
