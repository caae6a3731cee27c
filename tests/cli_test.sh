#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/cli_test.sh - the command line, end to end, for both number types
# ($BUILD/tinygi and $BUILD/tinygi-fixed):
#  - bad options and a table of malformed scenes / OBJ files: exit 2, one line
#    "FILE:LINE:COL: error: ..." (scenes) or "tinygi: error: option ..."
#    (usage), no output file created, an existing output file untouched, no
#    temporary files left behind;
#  - render: PPM header "P6 W H 255" and byte size, PFM header (Pf / PF,
#    little-endian scale -1.0) and byte size, frame numbering with %d/%03d,
#    --explain, --quiet, determinism, unwritable output (exit 1);
#  - view: framebuffer errors exit 1, usage errors exit 2;
#  - diff: exit 0/1/2, its numbers, the -o difference image;
#  - --help, --version, list.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_build
MAX_THREADS=$(awk '$1 == "#define" && $2 == "TG_MAX_THREADS" { print $3; exit }' src/tinygi.h)
sh_scratch cli
S=$T/s          # scenes and OBJ files
O=$T/o          # outputs (must stay empty after a refused run)
mkdir -p "$S" "$O"

# run ARGS...: run the CLI under test in $O (so a default out.ppm would land
# there); sets rc, stdout in $T/out, stderr in $T/err
run() { (cd "$O" && exec "$BIN" "$@") >"$T/out" 2>"$T/err"; rc=$?; }
err_lines() { wc -l <"$T/err" | tr -d ' '; }
empty_outdir() { [ -z "$(ls -A "$O")" ]; }
has() { grep -qiF -- "$1" "$2"; }

# refused NAME REGEX ARGS...: exit 2, one stderr line matching REGEX, and
# nothing written to $O - both when the output does not exist and when it does
# (with ONCE=1: ARGS are run as given, without "-o $O/out.ppm" appended).
refused() {
    local name=$1 re=$2; shift 2
    rm -rf "${O:?}"/*
    if [ "${ONCE:-0}" = 1 ]; then run "$@"; else run "$@" -o "$O/out.ppm"; fi
    if [ "$rc" -ne 2 ]; then fail "$name" "exit $rc, expected 2: $(head -c 300 "$T/err")"; return; fi
    if [ "$(err_lines)" -ne 1 ]; then fail "$name" "expected one stderr line, got: $(cat "$T/err")"; return; fi
    if ! grep -Eq -- "$re" "$T/err"; then fail "$name" "message '$(cat "$T/err")' !~ /$re/"; return; fi
    if ! empty_outdir; then fail "$name" "created: $(ls -A "$O")"; return; fi
    if [ "${ONCE:-0}" = 1 ]; then ok "$name"; return; fi
    printf 'precious' >"$O/out.ppm"
    run "$@" -o "$O/out.ppm"
    if [ "$rc" -ne 2 ] || [ "$(cat "$O/out.ppm")" != precious ] || [ "$(ls -A "$O")" != out.ppm ]; then
        fail "$name" "existing output touched or temporaries left (exit $rc): $(ls -A "$O")"; return
    fi
    rm -f "$O/out.ppm"
    ok "$name"
}

# ---- the malformed scenes (written once, shared by both binaries) ----
HEAD='camera pos 0 1 5 target 0 0 0\nmaterial white albedo 0.8 0.8 0.8\n'
QUAD='quad p0 -1 0 -1 p1 -1 0 1 p2 1 0 1 p3 1 0 -1 material white'
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$S/good.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n' >"$S/badindex.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -5\n' >"$S/badneg.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n' >"$S/badzero.obj"
printf 'v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n' >"$S/badnum.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n' >"$S/badface.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//7 3//1\n' >"$S/badnormal.obj"
LONG=$(printf '%*s' 5000 '' | tr ' ' x)

# case NAME LINE MUST-CONTAIN TEXT (printf %b escapes; "" = no substring check)
CASES=()
case_() { CASES+=("$1"); printf '%b' "$4" >"$S/$1.scene"; eval "line_$1=$2; want_$1=\$3"; }
case_ unknown_keyword 3 frobnicate "${HEAD}frobnicate 1 2 3\n"
case_ unknown_key 1 zoom 'camera pos 0 1 5 target 0 0 0 zoom 2\n'
case_ missing_target 1 target 'camera pos 0 1 5\n'
case_ missing_p3 3 p3 "${HEAD}quad p0 0 0 0 p1 1 0 0 p2 1 1 0 material white\n"
case_ too_few_numbers 1 "" 'camera pos 0 1 target 0 0 0\n'
case_ too_many_numbers 1 "" 'camera pos 0 1 5 7 target 0 0 0\n'
case_ not_a_number 2 abc 'camera pos 0 1 5 target 0 0 0\nmaterial m albedo 0.5 abc 0.5\n'
case_ nan_value 2 "" 'camera pos 0 1 5 target 0 0 0\nmaterial m albedo nan 0.5 0.5\n'
case_ huge_value 3 "" "${HEAD}sphere center 0 0 0 radius 1e40 material white\n"
case_ negative_albedo 2 albedo 'camera pos 0 1 5 target 0 0 0\nmaterial m albedo -0.5 0.5 0.5\n'
case_ negative_radius 3 radius "${HEAD}sphere center 0 0 0 radius -1 material white\n"
case_ negative_gi_radius 3 radius "${HEAD}gi radius -1\n"
case_ fov_zero 1 fov 'camera pos 0 1 5 target 0 0 0 fov 0\n'
case_ fov_180 1 fov 'camera pos 0 1 5 target 0 0 0 fov 180\n'
case_ near_zero 1 near 'camera pos 0 1 5 target 0 0 0 near 0\n'
case_ camera_pos_is_target 1 "" 'camera pos 1 1 1 target 1 1 1\n'
case_ zero_light_dir 3 "" "${HEAD}light directional dir 0 0 0 color 1 1 1\n"
case_ unknown_light_type 3 laser "${HEAD}light laser pos 0 1 0 color 1 1 1\n"
case_ spot_without_angle 3 angle "${HEAD}light spot pos 0 1 0 dir 0 -1 0 color 1 1 1\n"
case_ duplicate_material 3 white "${HEAD}material white albedo 0.1 0.1 0.1\n"
case_ undefined_material 3 nosuch "${HEAD}quad p0 -1 0 -1 p1 -1 0 1 p2 1 0 1 p3 1 0 -1 material nosuch\n"
case_ undefined_object_key 4 ghost "${HEAD}${QUAD} name floor\nobject_key name ghost t 0 translate 0 1 0\n"
case_ object_key_bad_t 4 "" "${HEAD}${QUAD} name floor\nobject_key name floor t abc translate 0 1 0\n"
case_ sphere_segments_low 3 segments "${HEAD}sphere center 0 0 0 radius 1 material white segments 1\n"
case_ sh9_short 3 "" "${HEAD}env sh9 $(printf '0.1 %.0s' $(seq 26))\n"
case_ unknown_effect 3 sparkles "${HEAD}effects direct sparkles\n"
case_ unknown_env 3 nebula "${HEAD}env nebula 1 1 1\n"
case_ nul_byte 3 "" "${HEAD}${QUAD}\0 \n"
case_ long_line 3 "" "${HEAD}# ${LONG}\n"
case_ mesh_missing 3 missing.obj "${HEAD}mesh file missing.obj material white\n"
case_ mesh_zero_axis 3 "" "${HEAD}mesh file good.obj material white rotate 0 0 0 45\n"

# OBJ errors are reported at the OBJ file's line: name OBJ LINE
OBJ_CASES="badindex:4 badneg:4 badzero:4 badnum:2 badface:4 badnormal:5"
for oc in $OBJ_CASES; do
    printf '%b' "${HEAD}mesh file ${oc%%:*}.obj material white\n" >"$S/mesh_${oc%%:*}.scene"
done

# pfm_vs_ppm W H NORMAL.pfm NORMAL.ppm: the largest |0.5 n + 0.5 - ppm/255|
# with the PFM's rows read bottom to top (od reads host byte order: the
# caller checks the host is little-endian)
pfm_vs_ppm() {
    local w=$1 h=$2 hp hq
    hp=$(printf 'PF\n%d %d\n-1.0\n' "$w" "$h" | wc -c)
    hq=$(printf 'P6\n%d %d\n255\n' "$w" "$h" | wc -c)
    { tail -c +$((hp + 1)) "$3" | od -An -v -tf4 | tr -s ' ' '\n' | grep -v '^$' | sed 's/^/f /'
      tail -c +$((hq + 1)) "$4" | od -An -v -tu1 | tr -s ' ' '\n' | grep -v '^$' | sed 's/^/b /'
    } | awk -v w="$w" -v h="$h" '$1 == "f" { f[nf++] = $2 } $1 == "b" { b[nb++] = $2 }
        END { if (nf != w * h * 3 || nb != w * h * 3) { print 99; exit }
              for (y = 0; y < h; y++) for (x = 0; x < w * 3; x++) {
                  d = f[(h - 1 - y) * w * 3 + x] * 0.5 + 0.5 - b[y * w * 3 + x] / 255
                  if (d < 0) d = -d; if (d > m) m = d }
              print m + 0 }'
}
little_endian() { [ "$(printf '\001\000' | od -An -tu2 | tr -d ' ')" = 1 ]; }

check_binary() {
    local tag=$1 c f line want col re oc obj
    # ---- --help, --version, list, no arguments ----
    run --help
    expect "$tag/help" [ "$rc" -eq 0 ]
    expect "$tag/help_lists_options" grep -q -- '--size WxH' "$T/out"
    run --version
    expect "$tag/version" grep -Eq '^tinygi [0-9]+\.[0-9]+\.[0-9]+ ' "$T/out"
    run
    expect "$tag/no_arguments_is_usage_error" [ "$rc" -eq 2 ]
    run frobnicate
    expect "$tag/unknown_command" [ "$rc" -eq 2 -a "$(err_lines)" -eq 1 ]
    run list
    expect "$tag/list" [ "$rc" -eq 0 ]
    expect "$tag/list_names" grep -q 'builtin:cornell' "$T/out"
    expect "$tag/list_aovs" grep -Eq 'color.*depth.*normal.*albedo' "$T/out"
    expect "$tag/list_techniques" grep -q 'hbil' "$T/out"

    # ---- bad options: exit 2, "tinygi: error: option NAME: ...", nothing written ----
    local U='^tinygi: error: '
    refused "$tag/opt_size_word" "${U}option --size: .*'abc'" render builtin:cornell --size abc
    # control bytes in what a message quotes are written as \xNN, as the core's are: one line, no escape
    # sequence reaches the terminal (they were written raw: an outside probe)
    refused "$tag/opt_size_control_bytes" "${U}option --size: .*'3\\\\x1bx4'" render builtin:cornell --size "$(printf '3\033x4')"
    ONCE=1 refused "$tag/scene_name_control_bytes" 'nope\\x1b\[2J\\x0ax\.scene: error: cannot read' render "$(printf 'nope\033[2J\nx').scene" -o "$O/out.ppm"
    ONCE=1 refused "$tag/list_takes_no_argument" "${U}list: unexpected argument 'extra'" list extra
    ONCE=1 refused "$tag/version_takes_no_argument" "${U}--version: unexpected argument 'x'" --version x
    refused "$tag/opt_size_zero" "${U}option --size" render builtin:cornell --size 0x10
    refused "$tag/opt_size_negative" "${U}option --size" render builtin:cornell --size -5x5
    refused "$tag/opt_size_half" "${U}option --size" render builtin:cornell --size 10x
    refused "$tag/opt_size_side_limit" "${U}option --size" render builtin:cornell --size 16385x1
    refused "$tag/opt_size_pixel_limit" "${U}option --size" render builtin:cornell --size 4097x4097
    refused "$tag/opt_size_overflow" "${U}option --size" render builtin:cornell --size 99999999999x99999999999
    refused "$tag/opt_frames_zero" "${U}option --frames" render builtin:cornell --frames 0
    refused "$tag/opt_frames_fraction" "${U}option --frames" render builtin:cornell --frames 1.5
    refused "$tag/opt_frames_limit" "${U}option --frames" render builtin:cornell --frames 100001
    refused "$tag/opt_aov" "${U}option --aov: .*color.*'sparkle'" render builtin:cornell --aov sparkle
    refused "$tag/opt_technique" "${U}option --technique: .*hbil.*'magic'" render builtin:cornell --technique magic
    refused "$tag/opt_slices" "${U}option --slices" render builtin:cornell --slices 0
    refused "$tag/opt_slices_above_8" "${U}option --slices" render builtin:cornell --slices 9
    run render builtin:cornell --size 16x12 --pcf-bilinear -o "$O/pcf.ppm" --quiet
    expect "$tag/render_pcf_bilinear" [ "$rc" -eq 0 -a -s "$O/pcf.ppm" ]
    refused "$tag/opt_samples" "${U}option --samples" render builtin:cornell --samples 257
    refused "$tag/opt_radius_negative" "${U}option --radius" render builtin:cornell --radius -1
    refused "$tag/opt_radius_nan" "${U}option --radius" render builtin:cornell --radius nan
    refused "$tag/opt_radius_inf" "${U}option --radius" render builtin:cornell --radius inf
    # hex is not a number in a scene file, nor on the command line (strtod read it: radius 16)
    refused "$tag/opt_radius_hex" "${U}option --radius" render builtin:cornell --radius 0x10
    refused "$tag/opt_exposure_hex_float" "${U}option --exposure" render builtin:cornell --exposure 0x1p-1
    refused "$tag/opt_bounces" "${U}option --bounces" render builtin:cornell --bounces -1
    refused "$tag/opt_exposure" "${U}option --exposure" render builtin:cornell --exposure -2
    refused "$tag/opt_shadow_size" "${U}option --shadow-size" render builtin:cornell --shadow-size 4
    refused "$tag/opt_threads_zero" "${U}option --threads: must be 1\\.\\.$MAX_THREADS, got 0\$" render builtin:cornell --threads 0
    refused "$tag/opt_threads_limit" "${U}option --threads: must be 1\\.\\.$MAX_THREADS, got $((MAX_THREADS + 1))\$" \
        render builtin:cornell --threads $((MAX_THREADS + 1))
    refused "$tag/opt_depth_layers" "${U}option --depth-layers: must be 1\\.\\.3, got 4\$" \
        render builtin:cornell --technique ssilvb --depth-layers 4
    refused "$tag/opt_depth_layers_unread" "${U}option --depth-layers: must be 1 for technique gtao .*got 2\$" \
        render builtin:cornell --technique gtao --depth-layers 2
    refused "$tag/opt_depth_layers_unread_any_order" "${U}option --depth-layers: must be 1 for technique ssao .*got 3\$" \
        render builtin:cornell --depth-layers 3 --technique ssao
    refused "$tag/opt_unknown" "${U}unknown option '--sparkle'" render builtin:cornell --sparkle
    ONCE=1 refused "$tag/opt_missing_value" "${U}option --frames: missing value" render builtin:cornell --frames
    ONCE=1 refused "$tag/opt_extension" "${U}option -o: expected a file name ending in .ppm, .png or .pfm" render builtin:cornell -o "$O/out.jpg"
    ONCE=1 refused "$tag/opt_pattern_bad" "${U}option -o" render builtin:cornell -o "$O/f%s.ppm"
    ONCE=1 refused "$tag/opt_pattern_twice" "${U}option -o" render builtin:cornell -o "$O/f%d_%d.ppm"
    ONCE=1 refused "$tag/opt_no_scene" "${U}render: missing SCENE" render
    refused "$tag/opt_two_scenes" "${U}render: unexpected argument" render builtin:cornell builtin:plane
    refused "$tag/unknown_builtin" "${U}unknown built-in scene 'nowhere'" render builtin:nowhere
    refused "$tag/scene_missing_file" "^$S/nothere.scene: error: cannot read: no such file or directory$" render "$S/nothere.scene"
    refused "$tag/scene_is_directory" "^$S: error: cannot read: is a directory$" render "$S"

    # ---- malformed scenes: FILE:LINE:COL: error: ..., nothing written ----
    for c in "${CASES[@]}"; do
        f="$S/$c.scene"; eval "line=\$line_$c; want=\$want_$c"
        refused "$tag/scene_$c" "^$f:$line:[1-9][0-9]*: error: .+" render "$f"
        if [ -n "$want" ] && [ "$rc" -eq 2 ] && ! has "$want" "$T/err"; then
            fail "$tag/scene_${c}_names_it" "message does not mention '$want': $(cat "$T/err")"
        fi
    done
    # the column points at the offending token
    run render "$S/unknown_keyword.scene" -o "$O/x.ppm"
    expect "$tag/column_of_keyword" grep -q "^$S/unknown_keyword.scene:3:1: error: " "$T/err"
    col=$(awk '{print index($0, "zoom")}' "$S/unknown_key.scene")
    run render "$S/unknown_key.scene" -o "$O/x.ppm"
    expect "$tag/column_of_key" grep -q "^$S/unknown_key.scene:1:$col: error: " "$T/err"
    for oc in $OBJ_CASES; do
        obj=${oc%%:*}
        refused "$tag/obj_$obj" "^$S/$obj.obj:${oc##*:}:[1-9][0-9]*: error: .+" render "$S/mesh_$obj.scene"
    done

    # ---- render (needs the core's frame) ----
    rm -rf "${O:?}"/*
    run render builtin:cornell --size 40x30 -o "$O/a.ppm" --quiet
    expect "$tag/render_ppm" [ "$rc" -eq 0 -a -f "$O/a.ppm" ]
    expect "$tag/render_quiet_is_quiet" [ ! -s "$T/err" ]
    expect "$tag/ppm_header" [ "$(head -c 13 "$O/a.ppm" 2>/dev/null | od -An -c | tr -d ' \n')" = 'P6\n4030\n255\n' ]
    expect "$tag/ppm_size" [ "$(wc -c <"$O/a.ppm" 2>/dev/null)" -eq $((13 + 40 * 30 * 3)) ]
    run render builtin:cornell --size 40x30 -o "$O/b.ppm" --quiet
    run diff "$O/a.ppm" "$O/b.ppm"
    expect "$tag/render_deterministic" [ "$rc" -eq 0 ]
    run render builtin:cornell --size 40x30 --aov depth -o "$O/d.pfm" --quiet
    expect "$tag/render_pfm_depth" [ "$rc" -eq 0 ]
    expect "$tag/pfm_header_Pf" [ "$(head -c 14 "$O/d.pfm" 2>/dev/null | od -An -c | tr -d ' \n')" = 'Pf\n4030\n-1.0\n' ]
    expect "$tag/pfm_size_Pf" [ "$(wc -c <"$O/d.pfm" 2>/dev/null)" -eq $((14 + 40 * 30 * 4)) ]
    for a in normal albedo color; do
        run render builtin:cornell --size 20x10 --aov $a -o "$O/$a.pfm" --quiet
        expect "$tag/pfm_${a}_PF" [ "$rc" -eq 0 -a "$(head -c 3 "$O/$a.pfm" 2>/dev/null)" = "$(printf 'PF\n')" \
            -a "$(wc -c <"$O/$a.pfm" 2>/dev/null)" -eq $((14 + 20 * 10 * 12)) ]
    done
    if little_endian; then # the same normals in both files: PFM rows really go bottom to top
        run render builtin:cornell --size 16x12 --aov normal -o "$O/n.pfm" --quiet
        run render builtin:cornell --size 16x12 --aov normal -o "$O/n.ppm" --quiet
        expect "$tag/pfm_rows_bottom_to_top" awk -v m="$(pfm_vs_ppm 16 12 "$O/n.pfm" "$O/n.ppm")" 'BEGIN { exit !(m < 0.01) }'
    fi
    run render builtin:cornell --size 16x12 --frames 3 -o "$O/f%03d.ppm" --quiet
    expect "$tag/frames_numbered_%03d" [ "$rc" -eq 0 -a -f "$O/f000.ppm" -a -f "$O/f001.ppm" -a -f "$O/f002.ppm" -a ! -e "$O/f003.ppm" ]
    run render builtin:cornell --size 16x12 --frames 2 -o "$O/g%d.ppm" --quiet
    expect "$tag/frames_numbered_%d" [ "$rc" -eq 0 -a -f "$O/g0.ppm" -a -f "$O/g1.ppm" -a ! -e "$O/g2.ppm" ]
    rm -rf "${O:?}"/*
    run render builtin:cornell --size 16x12 --frames 2 -o "$O/last.ppm" --quiet
    expect "$tag/frames_unnumbered_writes_last" [ "$rc" -eq 0 -a "$(ls -A "$O")" = last.ppm ]
    rm -rf "${O:?}"/*
    run render builtin:cornell --size 16x12 --explain -o "$O/e.ppm"
    expect "$tag/explain" [ "$rc" -eq 0 -a -s "$T/out" ]
    expect "$tag/explain_renders_nothing" empty_outdir
    for s in $("$BIN" list 2>/dev/null | grep -o 'builtin:[a-z0-9_]*'); do
        run render "$s" --size 32x24 -o "$O/s.ppm" --quiet
        expect "$tag/render_$s" [ "$rc" -eq 0 ]
    done
    for wh in 1x1 3x5 5x3 4097x3; do
        run render builtin:cornell --size "$wh" -o "$O/odd.ppm" --quiet
        expect "$tag/render_size_$wh" [ "$rc" -eq 0 -a "$(wc -c <"$O/odd.ppm" 2>/dev/null)" -eq \
            $(( $(printf 'P6\n%s %s\n255\n' "${wh%x*}" "${wh#*x}" | wc -c) + ${wh%x*} * ${wh#*x} * 3 )) ]
    done
    run render builtin:cornell --size 16x12 --technique hbil --slices 1 --samples 1 --radius 0 \
        --bounces 0 --exposure 2 --shadow-size 64 --no-interleave --no-temporal -o "$O/opts.ppm" --quiet
    expect "$tag/render_every_option_accepted" [ "$rc" -eq 0 -a -s "$O/opts.ppm" ]
    run render builtin:spheres --size 17x13 --gi-quarter --far-f0 -o "$O/q.ppm" --quiet
    expect "$tag/render_gi_quarter_far_f0" [ "$rc" -eq 0 -a -s "$O/q.ppm" ]
    run render builtin:spheres --size 17x13 --gi-quarter --explain
    expect "$tag/explain_gi_quarter_lists_upsample" grep -q "upsample" "$T/out"
    run render builtin:spheres --size 17x13 --gi-quarter --depth-layers 3 --explain
    expect "$tag/explain_gi_quarter_lists_the_half_layers" eval "grep -q 'quarter-res back-face depth' '$T/out' &&
        grep -q 'quarter-res depth behind the back face' '$T/out'"
    # AO alone keeps no material: no line of the plan may say it does (the
    # G-buffer pass named a material: an outside probe)
    run render builtin:spheres --size 17x13 --aov ao --explain
    expect "$tag/explain_ao_alone_names_no_material" eval "grep -q 'G-buffer, no material' '$T/out' &&
        ! grep -v 'no material' '$T/out' | grep -q 'material'"
    run render builtin:spheres --size 17x13 --gi-quarter --depth-layers 3 --frames 2 -o "$O/ql.ppm" --quiet
    expect "$tag/render_gi_quarter_depth_layers" [ "$rc" -eq 0 -a -s "$O/ql.ppm" ]
    run render builtin:cornell --size=16x12 --frames=2 --aov=depth -o "$O/eq.pfm" --quiet
    expect "$tag/render_option_equals_form" [ "$rc" -eq 0 -a "$(head -c 2 "$O/eq.pfm" 2>/dev/null)" = Pf ]
    run render builtin:cornell --size 16x12 --frames 3 -o "$O/np.ppm"
    expect "$tag/summary_without_quiet" [ "$rc" -eq 0 -a -n "$(cat "$T/err")" ]
    expect "$tag/no_progress_without_terminal" eval "! grep -q 'frame 1/3' '$T/err'"
    if command -v script >/dev/null 2>&1; then # a pseudo-terminal: progress shows
        script -qec "'$BIN' render builtin:cornell --size 16x12 --frames 3 -o '$O/p%d.ppm'" /dev/null \
            >"$T/tty" 2>&1 </dev/null
        expect "$tag/progress_on_terminal" grep -q 'frame 3/3, elapsed .* ETA' "$T/tty"
    fi
    if command -v timeout >/dev/null 2>&1; then # interrupted: only whole files, no temporaries
        rm -rf "${O:?}"/*
        (cd "$O" && timeout -s TERM 0.5 "$BIN" render builtin:cornell --size 64x48 --frames 100000 \
            -o "$O/k%05d.ppm" --quiet) >/dev/null 2>&1
        expect "$tag/interrupt_leaves_no_temporary" [ -z "$(ls -A "$O" | grep -v '^k[0-9]*\.ppm$')" ]
        expect "$tag/interrupt_leaves_whole_files" [ -z "$(find "$O" -name 'k*.ppm' ! -size $((13 + 64 * 48 * 3))c)" ]
        rm -rf "${O:?}"/*
    fi
    # --aov near / far on a frame without that light: a warning says why it is black
    run render builtin:cornell --size 16x12 --aov near --technique gtao -o "$O/n.ppm" --quiet
    expect "$tag/aov_near_without_near_field_warns" [ "$rc" -eq 0 -a -s "$O/n.ppm" ]
    expect "$tag/aov_near_warning_says_why" grep -q '^tinygi: warning: --aov near (technique gtao) is black: this technique computes no near field' "$T/err"
    run render builtin:cornell --size 16x12 --aov near --bounces 0 -o "$O/n.ppm" --quiet
    expect "$tag/aov_near_bounces_0_warns" grep -q '^tinygi: warning: --aov near (technique hbil) is black: bounces are 0$' "$T/err"
    run render builtin:cornell --size 16x12 --aov far -o "$O/f.ppm" --quiet
    expect "$tag/aov_far_without_environment_warns" grep -q '^tinygi: warning: --aov far is black: the scene has no environment light' "$T/err"
    run render builtin:cornell --size 16x12 --aov near -o "$O/n.ppm" --quiet
    expect "$tag/aov_near_with_near_field_is_quiet" [ "$rc" -eq 0 -a ! -s "$T/err" ]
    run render builtin:spheres --size 16x12 --aov far -o "$O/f.ppm" --quiet
    expect "$tag/aov_far_with_environment_is_quiet" [ "$rc" -eq 0 -a ! -s "$T/err" ]
    # --aov ao from the path tracer: white, and a warning says why (it was silent: an outside probe)
    run render builtin:cornell --size 16x12 --aov ao --technique pathtrace -o "$O/a.ppm" --quiet
    expect "$tag/aov_ao_pathtrace_warns" grep -q '^tinygi: warning: --aov ao holds no occlusion (AO 1): technique pathtrace' "$T/err"
    run render builtin:cornell --size 16x12 --aov ao --technique reference -o "$O/a.ppm" --quiet
    expect "$tag/aov_ao_reference_is_quiet" [ "$rc" -eq 0 -a ! -s "$T/err" ]
    # options the frame reads nowhere: a warning each (they were silent: an outside probe)
    run render builtin:cornell --size 16x12 --thickness 0.5 -o "$O/t.ppm" --quiet
    expect "$tag/thickness_unread_by_hbil_warns" grep -q '^tinygi: warning: --thickness is unread: hbil reads it only over depth layers' "$T/err"
    run render builtin:cornell --size 16x12 --thickness 0.5 --technique gtao -o "$O/t.ppm" --quiet
    expect "$tag/thickness_unread_by_gtao_warns" grep -q '^tinygi: warning: --thickness is unread: only ssilvb' "$T/err"
    run render builtin:cornell --size 16x12 --thickness 0.5 --technique ssilvb -o "$O/t.ppm" --quiet
    expect "$tag/thickness_read_by_ssilvb_is_quiet" [ "$rc" -eq 0 -a ! -s "$T/err" ]
    run render builtin:cornell --size 16x12 --thickness 0.5 --depth-layers 2 -o "$O/t.ppm" --quiet
    expect "$tag/thickness_read_over_layers_is_quiet" [ "$rc" -eq 0 -a ! -s "$T/err" ]
    run render builtin:cornell --size 16x12 --ao-multibounce -o "$O/m.ppm" --quiet
    expect "$tag/ao_multibounce_unread_warns" grep -q '^tinygi: warning: --ao-multibounce is unread: .* this render writes color$' "$T/err"
    expect "$tag/ao_multibounce_unread_still_renders" [ "$rc" -eq 0 -a -s "$O/m.ppm" ]
    run render builtin:cornell --size 16x12 --ao-multibounce --aov ao -o "$O/m.ppm" --quiet
    expect "$tag/ao_multibounce_read_is_quiet" [ "$rc" -eq 0 -a ! -s "$T/err" ]
    rm -rf "${O:?}"/*
    run render builtin:cornell --size 16x12 -o "$T/no/such/dir/x.ppm"
    expect "$tag/unwritable_output_exit_1" [ "$rc" -eq 1 -a "$(err_lines)" -eq 1 ]
    expect "$tag/unwritable_output_message" grep -q 'error: cannot write' "$T/err"
    rm -rf "${O:?}"/*

    # ---- --threads: the same bits for every thread count (PFM: every bit of
    # the linear values), every built-in scene, 3 frames (reprojection), full
    # and quarter-resolution GI; 40 threads is more than the 24 rows ----
    for s in $("$BIN" list 2>/dev/null | grep -o 'builtin:[a-z0-9_]*'); do
        for mode in "" --gi-quarter; do
            same=1
            for n in 1 2 3 7 40; do
                run render "$s" --size 32x24 --frames 3 $mode --aov color --threads $n -o "$O/t$n.pfm" --quiet
                [ "$rc" -eq 0 ] && cmp -s "$O/t1.pfm" "$O/t$n.pfm" || { same=0; break; }
            done
            expect "$tag/threads_same_bits_${s#builtin:}${mode:+_quarter}" [ "$same" -eq 1 ]
        done
    done
    run render builtin:columns --size 32x24 --frames 2 --aov near -o "$O/default.pfm" --quiet
    run render builtin:columns --size 32x24 --frames 2 --aov near --threads 1 -o "$O/one.pfm" --quiet
    expect "$tag/threads_default_same_bits" cmp -s "$O/default.pfm" "$O/one.pfm"
    run --help
    expect "$tag/threads_in_help" grep -q -- "--threads N .*1\.\.$MAX_THREADS" "$T/out"
    rm -rf "${O:?}"/*

    # ---- view (framebuffer): device errors exit 1, usage errors exit 2 ----
    run view builtin:cornell --size 16x12 --fbdev "$T/no_such_fb"
    expect "$tag/view_missing_device_exit_1" [ "$rc" -eq 1 -a "$(err_lines)" -eq 1 ]
    expect "$tag/view_missing_device_message" grep -q "^$T/no_such_fb: error: " "$T/err"
    reason=$(sed "s|^$T/no_such_fb: error: ||" "$T/err")
    # a device path longer than the platform's message buffer (256 bytes):
    # still PATH: error: REASON, the whole path and the same reason (the
    # CLI once looked for the path at the front of "PATH: REASON", which
    # was cut short, and printed "tinygi: error: PATH...")
    long="$T/no_such_dir/$(printf '%0150d' 1)/$(printf '%0150d' 2)"
    run view builtin:cornell --size 16x12 --fbdev "$long"
    expect "$tag/view_long_device_path_exit_1" [ "$rc" -eq 1 -a "$(err_lines)" -eq 1 ]
    expect "$tag/view_long_device_path_message" [ -n "$reason" -a "$(cat "$T/err")" = "$long: error: $reason" ]
    run view builtin:cornell --fbdev /dev/null
    expect "$tag/view_not_a_framebuffer_exit_1" [ "$rc" -eq 1 -a "$(err_lines)" -eq 1 ]
    ONCE=1 refused "$tag/view_refuses_output" "^tinygi: error: option -o: not used by tinygi view" view builtin:cornell -o "$O/v.ppm"
    refused "$tag/render_refuses_fbdev" "^tinygi: error: option --fbdev: not used by tinygi render" render builtin:cornell --fbdev /dev/fb0
    ONCE=1 refused "$tag/view_missing_scene" "^tinygi: error: view: missing SCENE" view
    ONCE=1 refused "$tag/view_bad_scene" "^$S/unknown_keyword.scene:3:1: error: " view "$S/unknown_keyword.scene"

    # ---- diff ----
    printf 'P6\n2 2\n255\n\012\024\036\050\062\074\106\120\132\144\156\170' >"$T/d1.ppm"
    printf 'P6\n2 2\n255\n\012\024\036\050\065\074\106\120\132\144\156\170' >"$T/d2.ppm"  # (1,0) g +3
    printf 'P6\n1 1\n255\n\000\000\000' >"$T/d3.ppm"
    printf 'Pf\n1 2\n-1.0\n\000\000\000\077\000\000\200\077' >"$T/p1.pfm"   # bottom 0.5, top 1.0
    printf 'Pf\n1 2\n-1.0\n\000\000\200\077\000\000\200\077' >"$T/p2.pfm"   # bottom 1.0, top 1.0
    printf 'P6\n2 2\n255\n\001' >"$T/trunc.ppm"
    printf 'Pf\n2 1\n-1.0\n\000\000\300\177\000\000\200\077' >"$T/nan.pfm"    # NaN, 1.0
    printf 'Pf\n2 1\n-1.0\n\000\000\200\077\000\000\200\177' >"$T/inf.pfm"    # 1.0, +inf
    run diff "$T/d1.ppm" "$T/d1.ppm"
    expect "$tag/diff_identical_exit_0" [ "$rc" -eq 0 ]
    expect "$tag/diff_identical_numbers" grep -q '^rmse 0$' "$T/out"
    expect "$tag/diff_identical_psnr_inf" grep -q '^psnr inf dB$' "$T/out"
    run diff "$T/d1.ppm" "$T/d2.ppm"
    expect "$tag/diff_outside_exit_1" [ "$rc" -eq 1 ]
    expect "$tag/diff_rmse" grep -q '^rmse 0.866025$' "$T/out"            # sqrt(9/12)
    expect "$tag/diff_psnr" grep -q '^psnr 49.38 dB$' "$T/out"            # 20 log10(255/0.866)
    expect "$tag/diff_max_where" grep -q '^max 3 at 1,0 channel g$' "$T/out"
    expect "$tag/diff_over_count" grep -q '^over 1 of 4 pixels' "$T/out"
    run diff "$T/d1.ppm" "$T/d2.ppm" --tolerance=3
    expect "$tag/diff_within_tolerance_exit_0" [ "$rc" -eq 0 ]
    run diff "$T/d1.ppm" "$T/d2.ppm" --tolerance 2.9
    expect "$tag/diff_just_outside_exit_1" [ "$rc" -eq 1 ]
    run diff "$T/d1.ppm" "$T/d2.ppm" -o "$T/dd.ppm"
    expect "$tag/diff_image_written" [ "$rc" -eq 1 -a "$(od -An -tu1 "$T/dd.ppm" 2>/dev/null | tr -s ' \n' ' ')" \
        = " 80 54 10 50 32 50 10 50 53 53 10 0 0 0 0 255 0 0 0 0 0 0 0 " ]
    run diff "$T/p1.pfm" "$T/p2.pfm" --tolerance 0.5
    expect "$tag/diff_pfm_within" [ "$rc" -eq 0 ]
    expect "$tag/diff_pfm_bottom_row_is_y1" grep -q '^max 0.5 at 0,1' "$T/out"
    run diff "$T/p1.pfm" "$T/p2.pfm" --tolerance 0.49
    expect "$tag/diff_pfm_outside" [ "$rc" -eq 1 ]
    # a NaN or an infinity is a difference, even against itself, and is reported
    run diff "$T/nan.pfm" "$T/nan.pfm" --tolerance 1e30
    expect "$tag/diff_nan_vs_nan_is_a_difference" [ "$rc" -eq 1 ]
    expect "$tag/diff_nan_reported" grep -q '^not finite in A: 1 NaN, 0 inf values, first at 0,0$' "$T/out"
    expect "$tag/diff_nan_max" grep -q '^max inf at 0,0 channel v$' "$T/out"
    run diff "$T/inf.pfm" "$T/inf.pfm"
    expect "$tag/diff_inf_vs_inf_is_a_difference" [ "$rc" -eq 1 ]
    expect "$tag/diff_inf_reported" grep -q '^not finite in B: 0 NaN, 1 inf values, first at 1,0$' "$T/out"
    run diff "$T/p1.pfm" "$T/p1.pfm"
    expect "$tag/diff_finite_says_nothing_of_nan" [ "$rc" -eq 0 -a -z "$(grep 'not finite' "$T/out")" ]
    run diff "$T/d1.ppm" "$T/d3.ppm" -o "$T/bad_diff.ppm"
    expect "$tag/diff_size_mismatch_exit_2" [ "$rc" -eq 2 -a "$(err_lines)" -eq 1 -a ! -e "$T/bad_diff.ppm" ]
    expect "$tag/diff_size_mismatch_message" grep -q 'sizes differ: 2x2 and 1x1' "$T/err"
    run diff "$T/d1.ppm" "$T/p1.pfm"
    expect "$tag/diff_format_mismatch_exit_2" [ "$rc" -eq 2 ]
    run diff "$T/d1.ppm" "$T/missing.ppm"
    expect "$tag/diff_missing_exit_2" [ "$rc" -eq 2 ]
    expect "$tag/diff_missing_message" grep -q "^$T/missing.ppm: error: cannot read: no such file or directory$" "$T/err"
    run diff "$T/trunc.ppm" "$T/d1.ppm"
    expect "$tag/diff_truncated_exit_2" [ "$rc" -eq 2 ]
    expect "$tag/diff_truncated_message" grep -q "^$T/trunc.ppm: error: PPM data truncated" "$T/err"
    run diff "$T/d1.ppm"
    expect "$tag/diff_one_image_exit_2" [ "$rc" -eq 2 ]
    run diff "$T/d1.ppm" "$T/d2.ppm" --tolerance -1
    expect "$tag/diff_bad_tolerance_exit_2" [ "$rc" -eq 2 ]
    run diff "$T/d1.ppm" "$T/d2.ppm" -o "$T/x.pfm"
    expect "$tag/diff_output_must_be_ppm_or_png" [ "$rc" -eq 2 -a ! -e "$T/x.pfm" ]
}

each_cli check_binary
summary
