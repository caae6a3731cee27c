#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/file_test.sh - what the CLI does with files, for both number types:
#  - inputs are never overwritten: an output that is the scene, a mesh, an
#    MTL or a diff image (same device and inode: through hard and symbolic
#    links, numbered frames too) is refused with exit 2 before any work;
#  - outputs: written through symbolic links, an existing file's mode kept,
#    a read-only file refused (exit 1), names checked before the render
#    (too long: exit 2; the longest allowed name works);
#  - inputs: only regular files (a FIFO never blocks, /dev/zero is not read),
#    at most 1 GiB (refused by size), the reason in the message, out of
#    memory while reading is exit 1;
#  - signals inherited as ignored (nohup, `trap '' INT`) stay ignored;
#  - stale temporaries of dead processes are removed, live ones kept.
# "Before any work" is shown by a run that would render for minutes ending at
# once: each such run is bounded by `timeout`, whose 124 fails the test.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_build
sh_scratch file
SCENE='camera pos 0 3 3 target 0 0 0
material m albedo 0.8 0.8 0.8
light point pos 0 3 0 color 1 1 1 intensity 5
quad p0 -1 0 -1 p1 -1 0 1 p2 1 0 1 p3 1 0 -1 material m
'
OBJ='v 0 0 0
v 1 0 0
v 0 1 0
f 1 2 3
'
LONG_RUN="--size 1024x1024 --frames 100000"   # minutes of work if it ever starts

# run ARGS...: the CLI under test, at most 60 s; rc, $T/out, $T/err
run() { timeout "${RUN_TIMEOUT:-60}" "$BIN" "$@" >"$T/out" 2>"$T/err"; rc=$?; }
msg() { head -c 400 "$T/err"; }
same() { cmp -s "$1" "$2"; }
# failed_with NAME RC REGEX: the last run exited RC with REGEX on stderr
failed_with() {
    if [ "$rc" -ne "$2" ]; then fail "$1" "exit $rc, expected $2: $(msg)"
    elif ! grep -q -- "$3" "$T/err"; then fail "$1" "message '$(msg)' !~ /$3/"
    else ok "$1"; fi
}

# signal_until_done SIG PID FIRST: once FIRST exists, send SIG to PID every
# 10 ms until it ends; rc its exit status, sent how many were sent
signal_until_done() {
    local i=0
    sent=0
    while [ ! -e "$3" ] && kill -0 "$2" 2>/dev/null && [ $i -lt 3000 ]; do sleep 0.01; i=$((i + 1)); done
    while kill -0 "$2" 2>/dev/null && [ $sent -lt 3000 ]; do
        kill -"$1" "$2" 2>/dev/null && sent=$((sent + 1)); sleep 0.01
    done
    wait "$2"; rc=$?
}

check_binary() {
    local tag=$1 D=$T/$1 dead live i n name
    mkdir -p "$D"
    printf '%s' "$SCENE" >"$D/scene.ppm"        # a scene file that happens to end in .ppm
    cp "$D/scene.ppm" "$D/scene.keep"
    printf '%s' "$OBJ" >"$D/mesh.ppm"
    printf 'newmtl m\nKd 0.5 0.5 0.5\n' >"$D/lib.ppm"
    printf 'mtllib lib.ppm\nusemtl m\n%s' "$OBJ" >"$D/withmtl.obj"
    printf '%smesh file mesh.ppm material m\nmesh file withmtl.obj material m\n' "$SCENE" >"$D/meshes.scene"

    # ---- inputs are never overwritten (exit 2, before any work) ----
    run render "$D/scene.ppm" -o "$D/scene.ppm" $LONG_RUN
    expect "$tag/output_is_the_scene" [ "$rc" -eq 2 ]
    expect "$tag/output_is_the_scene_message" grep -q "^$D/scene.ppm: error: the output is the input file '$D/scene.ppm'; refusing to overwrite it$" "$T/err"
    expect "$tag/output_is_the_scene_untouched" same "$D/scene.ppm" "$D/scene.keep"
    ln -s scene.ppm "$D/symlink.ppm"; ln "$D/scene.ppm" "$D/hardlink.ppm"
    run render "$D/scene.ppm" -o "$D/symlink.ppm" $LONG_RUN
    expect "$tag/output_links_to_the_scene" [ "$rc" -eq 2 ]
    run render "$D/scene.ppm" -o "$D/hardlink.ppm" $LONG_RUN
    expect "$tag/output_hard_link_of_the_scene" [ "$rc" -eq 2 ]
    expect "$tag/scene_still_intact" same "$D/scene.ppm" "$D/scene.keep"
    cp "$D/scene.ppm" "$D/f3.ppm"
    run render "$D/f3.ppm" -o "$D/f%d.ppm" --size 16x12 --frames 5
    expect "$tag/numbered_frame_is_the_scene" [ "$rc" -eq 2 -a ! -e "$D/f0.ppm" ]
    cp "$D/mesh.ppm" "$D/mesh.keep"
    run render "$D/meshes.scene" -o "$D/mesh.ppm" $LONG_RUN
    expect "$tag/output_is_a_mesh" [ "$rc" -eq 2 ]
    expect "$tag/output_is_a_mesh_message" grep -q "the output is the input file '$D/mesh.ppm'" "$T/err"
    expect "$tag/mesh_untouched" same "$D/mesh.ppm" "$D/mesh.keep"
    run render "$D/meshes.scene" -o "$D/lib.ppm" $LONG_RUN
    expect "$tag/output_is_an_mtl" [ "$rc" -eq 2 ]
    run render "$D/meshes.scene" --size 16x12 -o "$D/fine.ppm" --quiet
    expect "$tag/meshes_scene_renders" [ "$rc" -eq 0 -a -s "$D/fine.ppm" ]
    expect "$tag/meshes_scene_not_black" [ -n "$(od -An -tu1 -j 13 "$D/fine.ppm" | tr -s ' ' '\n' | grep -v '^0*$')" ]
    cp "$D/fine.ppm" "$D/a.ppm"; cp "$D/fine.ppm" "$D/b.ppm"; cp "$D/a.ppm" "$D/a.keep"
    run diff "$D/a.ppm" "$D/b.ppm" -o "$D/a.ppm"
    expect "$tag/diff_output_is_image_a" [ "$rc" -eq 2 ]
    expect "$tag/diff_image_a_untouched" same "$D/a.ppm" "$D/a.keep"
    ln -s b.ppm "$D/b_link.ppm"
    run diff "$D/a.ppm" "$D/b.ppm" -o "$D/b_link.ppm"
    expect "$tag/diff_output_links_to_image_b" [ "$rc" -eq 2 ]
    expect "$tag/diff_output_message" grep -q "the output is the input file '$D/b.ppm'" "$T/err"

    # ---- outputs: through links, modes kept, read-only refused ----
    printf 'old' >"$D/target.ppm"; ln -s target.ppm "$D/out_link.ppm"
    run render builtin:cornell --size 16x12 -o "$D/out_link.ppm" --quiet
    expect "$tag/write_through_symlink" [ "$rc" -eq 0 -a -L "$D/out_link.ppm" ]
    expect "$tag/symlink_target_written" [ "$(head -c 2 "$D/target.ppm")" = P6 ]
    printf 'old' >"$D/private.ppm"; chmod 600 "$D/private.ppm"
    run render builtin:cornell --size 16x12 -o "$D/private.ppm" --quiet
    expect "$tag/mode_kept_0600" [ "$rc" -eq 0 -a "$(stat -c %a "$D/private.ppm")" = 600 ]
    printf 'keep' >"$D/ro.ppm"; chmod 444 "$D/ro.ppm"
    run render builtin:cornell $LONG_RUN -o "$D/ro.ppm"
    expect "$tag/read_only_output_refused" [ "$rc" -eq 1 ]
    expect "$tag/read_only_output_message" grep -q "^$D/ro.ppm: error: cannot write: the existing file is read-only" "$T/err"
    expect "$tag/read_only_output_untouched" [ "$(cat "$D/ro.ppm")" = keep ]
    printf 'keep' >"$D/g2.ppm"; chmod 444 "$D/g2.ppm"
    run render builtin:cornell --size 16x12 --frames 4 -o "$D/g%d.ppm"
    expect "$tag/read_only_later_frame_refused_first" [ "$rc" -eq 1 -a ! -e "$D/g0.ppm" ]

    # ---- output names: checked before the render ----
    n=$(getconf NAME_MAX "$D" 2>/dev/null || echo 255)
    name=$(printf "%$((n - 4))s" '' | tr ' ' n).ppm
    run render builtin:cornell --size 16x12 -o "$D/$name" --quiet
    expect "$tag/longest_name_written" [ "$rc" -eq 0 -a -s "$D/$name" ]
    run render builtin:cornell $LONG_RUN -o "$D/x$name"
    expect "$tag/name_too_long_refused_first" [ "$rc" -eq 2 ]
    expect "$tag/name_too_long_message" grep -q ": error: cannot write: .*too long" "$T/err"
    run render builtin:cornell $LONG_RUN -o "$D/no/such/dir/x.ppm"
    expect "$tag/missing_directory_refused_first" [ "$rc" -eq 1 ]

    # ---- inputs: regular files only, within the limit, reasons given ----
    mkfifo "$D/fifo.scene"
    run render "$D/fifo.scene" -o "$D/x.ppm"
    expect "$tag/fifo_scene_refused" [ "$rc" -eq 2 ]
    expect "$tag/fifo_scene_message" grep -q "^$D/fifo.scene: error: cannot read: not a regular file$" "$T/err"
    printf '%smesh file fifo.scene material m\n' "$SCENE" >"$D/fifo_mesh.scene"
    run render "$D/fifo_mesh.scene" -o "$D/x.ppm"
    expect "$tag/fifo_mesh_refused" [ "$rc" -eq 2 ]
    expect "$tag/fifo_mesh_reason" grep -q "^$D/fifo_mesh.scene:5:[0-9]*: error: cannot read mesh file '$D/fifo.scene': not a regular file$" "$T/err"
    if [ -r /dev/zero ]; then
        run render /dev/zero -o "$D/x.ppm"
        failed_with "$tag/dev_zero_scene_refused" 2 "not a regular file"
        printf '%smesh file /dev/zero material m\n' "$SCENE" >"$D/zero_mesh.scene"
        run render "$D/zero_mesh.scene" -o "$D/x.ppm"
        failed_with "$tag/dev_zero_mesh_refused" 2 "cannot read mesh file '/dev/zero': not a regular file$"
    fi
    truncate -s 1073741825 "$D/huge.scene"
    run render "$D/huge.scene" -o "$D/x.ppm"
    failed_with "$tag/huge_scene_refused_by_size" 2 "^$D/huge.scene: error: cannot read: larger than the 1 GiB limit$"
    printf '%smesh file huge.scene material m\n' "$SCENE" >"$D/huge_mesh.scene"
    run render "$D/huge_mesh.scene" -o "$D/x.ppm"
    failed_with "$tag/huge_mesh_refused_by_size" 2 "cannot read mesh file '$D/huge.scene': larger than the 1 GiB limit$"
    printf '%smesh file . material m\n' "$SCENE" >"$D/dir_mesh.scene"
    run render "$D/dir_mesh.scene" -o "$D/x.ppm"
    expect "$tag/directory_mesh_reason" grep -q "cannot read mesh file '$D/.': is a directory$" "$T/err"
    printf '%smesh file nothere.obj material m\n' "$SCENE" >"$D/missing_mesh.scene"
    run render "$D/missing_mesh.scene" -o "$D/x.ppm"
    expect "$tag/missing_mesh_reason" grep -q "cannot read mesh file '$D/nothere.obj': no such file or directory$" "$T/err"
    printf 'mtllib gone.mtl\nusemtl m\n%s' "$OBJ" >"$D/gone_mtl.obj"
    printf '%smesh file gone_mtl.obj material m\n' "$SCENE" >"$D/gone_mtl.scene"
    run render "$D/gone_mtl.scene" -o "$D/x.ppm"
    expect "$tag/missing_mtl_reason" grep -q "cannot read MTL file '$D/gone.mtl': no such file or directory$" "$T/err"
    if [ "$(id -u)" = 0 ] && command -v setpriv >/dev/null 2>&1; then
        # root reads anything: ask as nobody
        cp "$D/mesh.ppm" "$D/secret.obj"; chmod 600 "$D/secret.obj"
        printf '%smesh file secret.obj material m\n' "$SCENE" >"$D/secret.scene"
        chmod 755 "$T" "$D"; chmod 644 "$D/secret.scene"
        setpriv --reuid=65534 --regid=65534 --clear-groups timeout 60 "$BIN" render "$D/secret.scene" \
            --explain >"$T/out" 2>"$T/err"; rc=$?
        failed_with "$tag/permission_denied_reason" 2 "cannot read mesh file '$D/secret.obj': permission denied$"
        chmod 700 "$T"
    fi
    # out of memory while reading: a runtime failure, exit 1 (not 2); not
    # under the sanitizers, whose shadow memory does not fit such a limit
    if [ -z "${ASAN_OPTIONS:-}" ]; then
        truncate -s 600M "$D/big.obj"
        printf '%smesh file big.obj material m\n' "$SCENE" >"$D/big_mesh.scene"
        (ulimit -v 400000 && exec timeout 60 "$BIN" render "$D/big.obj" -o "$D/x.ppm") >"$T/out" 2>"$T/err"; rc=$?
        failed_with "$tag/out_of_memory_scene_exit_1" 1 "out of memory"
        (ulimit -v 400000 && exec timeout 60 "$BIN" render "$D/big_mesh.scene" -o "$D/x.ppm") >"$T/out" 2>"$T/err"; rc=$?
        failed_with "$tag/out_of_memory_mesh_exit_1" 1 "cannot read mesh file '$D/big.obj': out of memory"
        rm -f "$D/big.obj"
    fi

    # ---- signals inherited as ignored stay ignored ----
    # (the signals start once the first frame is out: tinygi runs by then)
    (cd "$D" && exec nohup "$BIN" render builtin:cornell --size 32x24 --frames 100 -o "$D/hup%d.ppm" \
        --quiet) >"$T/out" 2>&1 &
    signal_until_done HUP $! "$D/hup0.ppm"
    expect "$tag/nohup_survives_sighup" [ "$rc" -eq 0 -a "$sent" -ge 3 -a -s "$D/hup99.ppm" ]
    (trap '' INT; exec "$BIN" render builtin:cornell --size 32x24 --frames 100 -o "$D/int%d.ppm" --quiet) \
        >"$T/out" 2>&1 &
    signal_until_done INT $! "$D/int0.ppm"
    expect "$tag/ignored_sigint_stays_ignored" [ "$rc" -eq 0 -a "$sent" -ge 3 -a -s "$D/int99.ppm" ]

    # ---- stale temporaries: a dead process's go, a live one's stay ----
    mkdir -p "$D/st"
    dead=$(sh -c 'echo $$')          # a process that has ended
    sleep 60 & live=$!
    : >"$D/st/.a.ppm.tinygi-tmp-$dead-0"
    : >"$D/st/.b.ppm.tinygi-tmp-$live-0"
    : >"$D/st/.c.ppm.tmp-$dead-0"    # not ours: another program's name
    run render builtin:cornell --size 16x12 -o "$D/st/out.ppm" --quiet
    expect "$tag/stale_temporary_removed" [ "$rc" -eq 0 -a ! -e "$D/st/.a.ppm.tinygi-tmp-$dead-0" ]
    expect "$tag/live_temporary_kept" [ -e "$D/st/.b.ppm.tinygi-tmp-$live-0" ]
    expect "$tag/foreign_name_kept" [ -e "$D/st/.c.ppm.tmp-$dead-0" ]
    kill "$live" 2>/dev/null; wait "$live" 2>/dev/null
}

each_cli check_binary
summary
