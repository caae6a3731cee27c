#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# platform/cross-run.sh - the body of `make cross` (see platform/cross.mk for
# the knobs).  Builds the core libraries and platform/baremetal/render.c for
# every target, runs them, and compares every output file with x86-64's
# using cmp: identical frames everywhere, float and fixed point alike.
# Prints "ok ..." / "FAIL ..." lines and ends with "N passed, N failed".
# Flag lists ($CFLAGS, $flags, $(numdef ...)) are split into words on purpose:
# shellcheck disable=SC2086,SC2046
set -u
cd "$(dirname "$0")/.." || exit 1
OUT=${CROSS_BUILD:-build-cross}
TARGETS=${CROSS_TARGETS:-"i686 s390x powerpc m3 m4f m0"}
SCENES=${CROSS_SCENES:-"cornell spheres columns"}
SIZE=${CROSS_SIZE:-64x48}
FRAMES=${CROSS_FRAMES:-2}
AOVS=${CROSS_AOVS:-color,depth,normal,albedo,ao,bent,cone,near,far,direct,irradiance,motion}
AOVS=${AOVS//,/+} # QEMU options take commas
M0_RUNS=${CROSS_M0_RUNS:-"4x3:color 6x4:ao+depth+normal"} # SIZE:AOVS, one frame each
M0_SCENES=${CROSS_M0_SCENES:-cornell}
M0_ARENA=${CROSS_M0_ARENA:-10496}
MAKE=${MAKE:-make}
HOST_CC=${HOST_CC:-cc}
SKIP=${SKIP:-}
QEMU_TIMEOUT=${CROSS_TIMEOUT:-300}
CLI_SCENES=${CROSS_CLI_SCENES:-cornell}
CLI_AOVS=${CROSS_CLI_AOVS:-"depth normal ao"} # besides colour
SHADOW=${CROSS_SHADOW:-64}
M0_SHADOW=${CROSS_M0_SHADOW:-8}
CROSS_TESTS=${CROSS_TESTS:-test_fbdev} # test programs run on the Linux targets ("all": every one)

CFLAGS="-std=c99 -ffp-contract=off -fexcess-precision=fast -O2 -Wall -Wextra -Wpedantic -Wshadow -Wdouble-promotion -Werror"
BM=platform/baremetal
passed=0; failed=0
ok()   { echo "ok $1 ($(( $(date +%s) - t0 )) s)"; passed=$((passed + 1)); }
fail() { echo "FAIL $1${2:+: $2}"; failed=$((failed + 1)); }
log()  { echo "cross: $*"; }
t0=$(date +%s)
mkdir -p "$OUT"
LOG="$OUT/log"; mkdir -p "$LOG"

# ---- toolchains ----
if bash platform/cross-install.sh; then ok "install toolchains"; else fail "install toolchains"; fi

# ---- per-target settings: compiler, flags, runner ----
target_cc() {
    case $1 in
        x86_64) echo "$HOST_CC" ;;
        i686) echo i686-linux-gnu-gcc ;;
        s390x) echo s390x-linux-gnu-gcc ;;
        powerpc) echo powerpc-linux-gnu-gcc ;;
        m3|m4f|m0) echo arm-none-eabi-gcc ;;
    esac
}
target_ar() { local cc; cc=$(target_cc "$1"); [ "$1" = x86_64 ] && echo ar || echo "${cc%gcc}ar"; }
target_flags() {
    case $1 in
        i686) echo "-msse2 -mfpmath=sse" ;; # x87 rounds differently
        m3) echo "-mcpu=cortex-m3 -mthumb -ffunction-sections -fdata-sections" ;;
        m4f) echo "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -ffunction-sections -fdata-sections" ;;
        m0) echo "-mcpu=cortex-m0 -mthumb -ffunction-sections -fdata-sections -fno-tree-loop-distribute-patterns" ;;
    esac
}
target_run() { # how to run a Linux binary
    case $1 in
        s390x) echo qemu-s390x ;;
        powerpc) echo qemu-ppc ;;
        i686) # natively, unless the kernel cannot run 32-bit programs
            "$OUT/i686/render-float" size=bad >/dev/null 2>&1; [ $? -eq 2 ] || echo qemu-i386 ;;
        *) echo "" ;;
    esac
}
target_machine() { case $1 in m3) echo mps2-an385 ;; m4f) echo mps2-an386 ;; m0) echo microbit ;; esac; }
target_opt() { [ "$1" = m0 ] && echo -Os || echo -O2; } # 256 KB of flash
target_nums() { # m0 has no FPU and little flash; m4f is there for its FPU
    case $1 in m0) echo fixed ;; m4f) echo float ;; *) echo "float fixed" ;; esac
}
is_bare() { case $1 in m3|m4f|m0) return 0 ;; *) return 1 ;; esac; }

lib_for() { [ "$2" = fixed ] && echo "$OUT/$1/libtinygi-fixed.a" || echo "$OUT/$1/libtinygi.a"; }
numdef() { [ "$1" = fixed ] && echo "-DTG_FIXED=1" || echo ""; }

# Build the core libraries with the top Makefile, then the driver.
build_target() {
    local t=$1 cc ar flags num lib
    cc=$(target_cc "$t"); ar=$(target_ar "$t"); flags=$(target_flags "$t")
    command -v "$cc" >/dev/null || { fail "$t: build" "$cc not installed"; return 1; }
    # Objects built with other flags are stale (make does not track flags).
    local stamp
    stamp="$cc $(target_opt "$t") $flags"
    if [ -d "$OUT/$t" ] && [ "$(cat "$OUT/$t/.flags" 2>/dev/null)" != "$stamp" ]; then rm -rf "${OUT:?}/$t"; fi
    mkdir -p "$OUT/$t"; echo "$stamp" >"$OUT/$t/.flags"
    if ! $MAKE -s -j2 BUILD="$OUT/$t" CC="$cc" AR="$ar" OPT="$(target_opt "$t")" EXTRA_CFLAGS="$flags" \
        SKIP="$SKIP" $(for num in $(target_nums "$t"); do lib_for "$t" "$num"; done) >"$LOG/$t-core.log" 2>&1; then
        fail "$t: build core" "see $LOG/$t-core.log"; tail -n 15 "$LOG/$t-core.log"; return 1
    fi
    for num in $(target_nums "$t"); do
        lib=$(lib_for "$t" "$num")
        if is_bare "$t"; then
            build_bare "$t" "$num" "$cc" "$flags" "$lib" || return 1
        else
            if ! $cc $CFLAGS $flags $(numdef "$num") -Isrc -I$BM $BM/render.c $BM/port_stdio.c "$lib" \
                $( [ "$t" = x86_64 ] || echo -static ) -o "$OUT/$t/render-$num" >"$LOG/$t-$num.log" 2>&1; then
                fail "$t/$num: build driver" "$(head -c 600 "$LOG/$t-$num.log")"; return 1
            fi
        fi
    done
    ok "$t: build"
}

build_bare() {
    local t=$1 num=$2 cc=$3 flags=$4 lib=$5 common
    common="-Wl,--gc-sections -Wl,--undefined=tgp_vectors -L$BM -Isrc -I$BM"
    if [ "$t" = m0 ]; then # no C library at all: raw semihosting, our memcpy, libgcc last
        $cc $CFLAGS -Os $flags $(numdef "$num") -DTG_BM_ARENA_BYTES="$M0_ARENA" -ffreestanding -nostdlib \
            $common -Tmicrobit.ld -Wl,-Map="$OUT/$t/render-$num.map" \
            $BM/startup.c $BM/semihost.c $BM/render.c $BM/port_semihost.c $BM/libc_mini.c "$lib" -lgcc \
            -o "$OUT/$t/render-$num.elf" >"$LOG/$t-$num.log" 2>&1
    else # newlib: stdio over semihosting (librdimon), our startup and vector table
        $cc $CFLAGS $flags $(numdef "$num") -DTG_BM_NEWLIB --specs=rdimon.specs -nostartfiles \
            $common -Tmps2.ld $BM/startup.c $BM/semihost.c $BM/render.c $BM/port_stdio.c "$lib" \
            -o "$OUT/$t/render-$num.elf" >"$LOG/$t-$num.log" 2>&1
    fi || { fail "$t/$num: build driver" "$(head -c 800 "$LOG/$t-$num.log")"; return 1; }
}

# The hosted CLI and test programs, static, for a Linux target.
build_hosted() {
    local t=$1 cc ar flags goals="" name
    cc=$(target_cc "$t"); ar=$(target_ar "$t"); flags=$(target_flags "$t")
    goals="$OUT/$t/tinygi $OUT/$t/tinygi-fixed"
    if [ "$CROSS_TESTS" = all ]; then goals="$goals tests-build"
    else for name in $CROSS_TESTS; do goals="$goals $OUT/$t/float/tests/$name $OUT/$t/fixed/tests/$name"; done; fi
    if ! $MAKE -s -j2 BUILD="$OUT/$t" CC="$cc" AR="$ar" EXTRA_CFLAGS="$flags" SKIP="$SKIP" \
        EXTRA_LDFLAGS="$( [ "$t" = x86_64 ] || echo -static )" $goals >"$LOG/$t-hosted.log" 2>&1; then
        fail "$t: build CLI and tests" "see $LOG/$t-hosted.log"; tail -n 15 "$LOG/$t-hosted.log"; return 1
    fi
}

# run_cli TARGET DIR: `tinygi render` of the CLI scenes, colour PPM and every AOV as PFM.
run_cli() {
    local t=$1 dir=$2 runner num exe s a rc=0
    runner=$(target_run "$t")
    rm -rf "$dir"; mkdir -p "$dir"
    for num in float fixed; do
        exe="$OUT/$t/tinygi"; [ $num = fixed ] && exe="$OUT/$t/tinygi-fixed"
        for s in $CLI_SCENES; do
            $runner "$exe" render "builtin:$s" --size "$SIZE" --frames "$FRAMES" --shadow-size "$SHADOW" --quiet -o "$dir/$s-$num.ppm" >>"$dir.log" 2>&1 || rc=1
            for a in color $CLI_AOVS; do
                $runner "$exe" render "builtin:$s" --size "$SIZE" --frames "$FRAMES" --shadow-size "$SHADOW" --quiet --aov "$a" \
                    -o "$dir/$s-$num.$a.pfm" >>"$dir.log" 2>&1 || rc=1
            done
        done
    done
    return $rc
}

# run_tests TARGET: the chosen test programs under the target's runner.
run_tests() {
    local t=$1 runner num exe out
    runner=$(target_run "$t")
    for num in float fixed; do
        for exe in "$OUT/$t/$num/tests/"test_*; do
            [ -x "$exe" ] || continue
            out="$LOG/$t-$num-$(basename "$exe").log"
            if timeout "$QEMU_TIMEOUT" $runner "$exe" >"$out" 2>&1; then ok "$t/$num/$(basename "$exe")"
            else fail "$t/$num/$(basename "$exe")" "$(grep -m3 FAIL "$out" | tr '\n' ' ')see $out"; fi
        done
    done
}

# run_driver TARGET NUM DIR SIZE SHADOW AOVS FRAMES SCENES...
run_driver() {
    local t=$1 num=$2 dir=$3 size=$4 shadow=$5 aovs=$6 frames=$7; shift 7
    local args runner
    rm -rf "$dir"; mkdir -p "$dir"
    if is_bare "$t"; then
        args="arg=render,arg=out=$dir,arg=size=$size,arg=frames=$frames,arg=aovs=$aovs,arg=shadow=$shadow"
        for s in "$@"; do args="$args,arg=$s"; done
        timeout "$QEMU_TIMEOUT" qemu-system-arm -M "$(target_machine "$t")" -nographic -monitor none \
            -serial none -semihosting-config "enable=on,target=native,$args" \
            -kernel "$OUT/$t/render-$num.elf" >"$dir.log" 2>&1
    else
        runner=$(target_run "$t")
        timeout "$QEMU_TIMEOUT" $runner "$OUT/$t/render-$num" "out=$dir" "size=$size" \
            "frames=$frames" "aovs=$aovs" "shadow=$shadow" "$@" >"$dir.log" 2>&1
    fi
}

# compare_dir NAME REFDIR DIR: every reference file present and identical.
compare_dir() {
    local name=$1 ref=$2 dir=$3 f bad="" n=0
    for f in "$ref"/*; do
        [ -f "$f" ] || continue
        n=$((n + 1))
        cmp -s "$f" "$dir/$(basename "$f")" || bad="$bad $(basename "$f")"
    done
    if [ "$n" -eq 0 ]; then fail "$name" "no reference files"
    elif [ -z "$bad" ]; then ok "$name: $n files identical to x86_64"
    else fail "$name" "differs from x86_64:$bad"; fi
}

check_run() { # NAME STATUS DIR
    if [ "$2" -eq 0 ]; then ok "$1: runs (exit 0)"
    else fail "$1: runs" "exit $2: $(tail -n 5 "$3.log" | tr '\n' ' ')"; fi
}

# ---- x86-64: the reference ----
build_target x86_64 || { echo "$passed passed, $failed failed"; exit 1; }
for num in float fixed; do
    if run_driver x86_64 "$num" "$OUT/out/x86_64/$num" "$SIZE" "$SHADOW" "$AOVS" "$FRAMES" $SCENES; then
        ok "x86_64/$num: render $(ls "$OUT/out/x86_64/$num" | wc -l) files"
    else fail "x86_64/$num: render" "$(tail -n 5 "$OUT/out/x86_64/$num.log")"; fi
done
if build_hosted x86_64; then
    if run_cli x86_64 "$OUT/out/x86_64/cli"; then ok "x86_64: tinygi render ($CLI_SCENES)"
    else fail "x86_64: tinygi render" "$(tail -n 5 "$OUT/out/x86_64/cli.log")"; fi
fi
i=0
for run in $M0_RUNS; do # references for the Cortex-M0's smaller frames
    i=$((i + 1))
    run_driver x86_64 fixed "$OUT/out/x86_64/m0-$i" "${run%%:*}" "$M0_SHADOW" "${run#*:}" 1 $M0_SCENES \
        || fail "x86_64/fixed $run: render" "$(tail -n 5 "$OUT/out/x86_64/m0-$i.log")"
done

# ---- the other targets ----
for t in $TARGETS; do
    build_target "$t" || continue
    if [ "$t" = m0 ]; then
        i=0
        for run in $M0_RUNS; do
            i=$((i + 1)); dir="$OUT/out/$t/fixed-$i"
                run_driver "$t" fixed "$dir" "${run%%:*}" "$M0_SHADOW" "${run#*:}" 1 $M0_SCENES
            check_run "$t/fixed $run" $? "$dir"
            compare_dir "$t/fixed $run" "$OUT/out/x86_64/m0-$i" "$dir"
            grep -h '^startup: stack\|fixed: frame' "$dir.log" | sed 's/^/cross: m0 /'
        done
        continue
    fi
    if [ "$t" = m4f ]; then # the float core must run on the FPU, not in soft float
        n=$(arm-none-eabi-objdump -d "$OUT/$t/render-float.elf" | grep -cE '\sv(add|sub|mul|div|sqrt)\.f32\s')
        s=$(arm-none-eabi-objdump -d "$OUT/$t/render-float.elf" | grep -c 'bl.*<__aeabi_f\(add\|mul\|div\)>')
        if [ "$n" -gt 100 ] && [ "$s" -eq 0 ]; then ok "m4f/float: on the FPU ($n VFP arithmetic instructions, no soft-float calls)"
        else fail "m4f/float: on the FPU" "$n VFP instructions, $s soft-float calls"; fi
    fi
    for num in $(target_nums "$t"); do
        dir="$OUT/out/$t/$num"
        run_driver "$t" "$num" "$dir" "$SIZE" "$SHADOW" "$AOVS" "$FRAMES" $SCENES
        check_run "$t/$num" $? "$dir"
        compare_dir "$t/$num" "$OUT/out/x86_64/$num" "$dir"
    done
    if ! is_bare "$t" && build_hosted "$t"; then
        run_cli "$t" "$OUT/out/$t/cli" || fail "$t: tinygi render" "$(tail -n 5 "$OUT/out/$t/cli.log")"
        compare_dir "$t/cli" "$OUT/out/x86_64/cli" "$OUT/out/$t/cli"
        run_tests "$t"
    fi
done

echo "cross: $(( $(date +%s) - t0 )) s; logs in $LOG and $OUT/out/*/*.log"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
