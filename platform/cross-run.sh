#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# platform/cross-run.sh - the body of `make cross` and `make cross-count`
# (see platform/cross.mk for the knobs).
#
# check (make cross): builds the core libraries and platform/baremetal/render.c
#   for every target, runs them, and compares every output file with
#   x86-64's using cmp: identical frames everywhere, float and fixed point
#   alike.  The bare-metal targets run under QEMU with -icount and print
#   each frame's instruction count (platform/baremetal/counter.c).
# count (make cross-count): one request (CROSS_COUNT_RUN) on every bare-metal
#   core and number type, instructions per frame as a table.
# Both print "ok ..." / "FAIL ..." lines and end with "N passed, N failed".
# Flag lists ($CFLAGS, $flags, $(numdef ...)) are split into words on purpose:
# shellcheck disable=SC2086,SC2046
set -u
cd "$(dirname "$0")/.." || exit 1
MODE=${1:-check}
OUT=${CROSS_BUILD:-build-cross}
TARGETS=${CROSS_TARGETS:-"i686 s390x powerpc m3 m4f m0 m0mps2 rv32 rv32f"}
SCENES=${CROSS_SCENES:-"cornell spheres columns"}
SIZE=${CROSS_SIZE:-64x48}
FRAMES=${CROSS_FRAMES:-2}
AOVS=${CROSS_AOVS:-color,depth,normal,albedo,ao,bent,cone,near,far,direct,irradiance,motion}
AOVS=${AOVS//,/+} # QEMU options take commas
SHADOW=${CROSS_SHADOW:-64}
# A run is the driver's arguments joined by commas (render.c's usage): the
# same request on x86-64 and on the target, outputs compared file by file.
RUN=${CROSS_RUN:-"size=$SIZE,frames=$FRAMES,shadow=$SHADOW,aovs=$AOVS,${SCENES// /,}"}
M0_RUNS=${CROSS_M0_RUNS:-"size=12x9,frames=2,shadow=8,aovs=color,cornell size=24x18,frames=1,shadow=8,aovs=ao+depth+normal,cornell"}
COUNT_RUN=${CROSS_COUNT_RUN:-"size=160x120,frames=2,shadow=64,aovs=color,cornell"}
MAKE=${MAKE:-make}
HOST_CC=${HOST_CC:-cc}
SKIP=${SKIP:-}
QEMU_TIMEOUT=${CROSS_TIMEOUT:-300}
CLI_SCENES=${CROSS_CLI_SCENES:-cornell}
CLI_AOVS=${CROSS_CLI_AOVS:-"depth normal ao"} # besides colour
# the other techniques, each in colour and AO (the CLI's names; the list is
# platform/cross.mk's CROSS_CLI_TECHNIQUES, none when run without make)
CLI_TECHNIQUES=${CROSS_CLI_TECHNIQUES:-}
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
BIN=$OUT # where the bare-metal drivers go

# ---- toolchains ----
if bash platform/cross-install.sh; then ok "install toolchains"; else fail "install toolchains"; fi

# ---- per-target settings: compiler, flags, runner, memory, requests ----
target_cc() {
    case $1 in
        x86_64) echo "$HOST_CC" ;;
        i686) echo i686-linux-gnu-gcc ;;
        s390x) echo s390x-linux-gnu-gcc ;;
        powerpc) echo powerpc-linux-gnu-gcc ;;
        m3|m4f|m0|m0mps2) echo arm-none-eabi-gcc ;;
        rv32|rv32f) echo riscv64-unknown-elf-gcc ;;
    esac
}
target_ar() { local cc; cc=$(target_cc "$1"); [ "$1" = x86_64 ] && echo ar || echo "${cc%gcc}ar"; }
target_flags() { # for the core and the driver
    local rv="--specs=picolibc.specs -ffunction-sections -fdata-sections"
    case $1 in
        i686) echo "-msse2 -mfpmath=sse" ;; # x87 rounds differently
        m3) echo "-mcpu=cortex-m3 -mthumb -ffunction-sections -fdata-sections" ;;
        m4f) echo "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -ffunction-sections -fdata-sections" ;;
        m0|m0mps2) echo "-mcpu=cortex-m0 -mthumb -ffunction-sections -fdata-sections -fno-tree-loop-distribute-patterns" ;;
        rv32) echo "-march=rv32imac -mabi=ilp32 $rv" ;;    # soft float
        rv32f) echo "-march=rv32imafc -mabi=ilp32f $rv" ;; # float on the F extension
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
# QEMU for a bare-metal target: the machine, with a deterministic
# instruction count (platform/baremetal/counter.c): -icount makes QEMU's
# virtual clock advance 2^shift ns per instruction, sleep=off keeps it from
# catching up with the host's.  The MPS2 counter ticks every 40 ns, so one
# instruction there is 128 ns (shift=7); RISC-V's instret reads the clock
# in ns, so one instruction is one ns there.
target_qemu() {
    case $1 in
        m3|m0mps2) echo "qemu-system-arm -M mps2-an385 -icount shift=7,sleep=off" ;;
        m4f) echo "qemu-system-arm -M mps2-an386 -icount shift=7,sleep=off" ;;
        m0) echo "qemu-system-arm -M microbit" ;; # no counter
        rv32|rv32f) echo "qemu-system-riscv32 -M virt -bios none -icount shift=0,sleep=off" ;;
    esac
}
target_opt() { case $1 in m0|m0mps2) echo -Os ;; *) echo -O2 ;; esac; } # M0: 256 KB of flash
target_nums() { # m0 has no FPU and little flash; m4f and rv32f are there for their FPU
    case $1 in m0|m0mps2) echo fixed ;; m4f|rv32f) echo float ;; *) echo "float fixed" ;; esac
}
is_bare() { case $1 in m3|m4f|m0|m0mps2|rv32|rv32f) return 0 ;; *) return 1 ;; esac; }
# The driver's static arena (TG_BM_ARENA_BYTES), per target.
target_arena() {
    [ "$MODE" = count ] && { echo "${CROSS_COUNT_ARENA:-14680064}"; return; }
    case $1 in
        m0) echo "${CROSS_M0_ARENA:-10240}" ;;
        m3) echo "${CROSS_M3_ARENA:-2097152}" ;;
        m0mps2) echo "${CROSS_M0MPS2_ARENA:-2097152}" ;;
        m4f) echo "${CROSS_M4F_ARENA:-2097152}" ;;
        rv32|rv32f) echo "${CROSS_RV32_ARENA:-2097152}" ;;
    esac
}
# The requests a target renders (runs, see RUN above).
target_runs() {
    case $1 in
        m0) echo "$M0_RUNS" ;;
        m3) echo "${CROSS_M3_RUNS:-$RUN}" ;;
        m0mps2) echo "${CROSS_M0MPS2_RUNS:-$RUN}" ;;
        m4f) echo "${CROSS_M4F_RUNS:-$RUN}" ;;
        rv32|rv32f) echo "${CROSS_RV32_RUNS:-$RUN}" ;;
        *) echo "$RUN" ;;
    esac
}

lib_for() { [ "$2" = fixed ] && echo "$OUT/$1/libtinygi-fixed.a" || echo "$OUT/$1/libtinygi.a"; }
numdef() { [ "$1" = fixed ] && echo "-DTG_FIXED=1" || echo ""; }
lib_dir() { [ "$1" = m0mps2 ] && echo m0 || echo "$1"; } # the same M0 code, another board

# Build the core libraries with the top Makefile, then the driver.
build_target() {
    local t=$1 lt cc ar flags num lib
    lt=$(lib_dir "$t"); cc=$(target_cc "$t"); ar=$(target_ar "$t"); flags=$(target_flags "$t")
    command -v "$cc" >/dev/null || { fail "$t: build" "$cc not installed"; return 1; }
    # Objects built with other flags are stale (make does not track flags).
    local stamp
    stamp="$cc $(target_opt "$t") $flags"
    if [ -d "$OUT/$lt" ] && [ "$(cat "$OUT/$lt/.flags" 2>/dev/null)" != "$stamp" ]; then rm -rf "${OUT:?}/$lt"; fi
    mkdir -p "$OUT/$lt" "$BIN/$t"; echo "$stamp" >"$OUT/$lt/.flags"
    if ! $MAKE -s -j2 BUILD="$OUT/$lt" CC="$cc" AR="$ar" OPT="$(target_opt "$t")" EXTRA_CFLAGS="$flags" \
        SKIP="$SKIP" $(for num in $(target_nums "$t"); do lib_for "$lt" "$num"; done) >"$LOG/$t-core.log" 2>&1; then
        fail "$t: build core" "see $LOG/$t-core.log"; tail -n 15 "$LOG/$t-core.log"; return 1
    fi
    for num in $(target_nums "$t"); do
        lib=$(lib_for "$lt" "$num")
        if is_bare "$t"; then
            build_bare "$t" "$num" "$cc" "$flags" "$lib" || return 1
        else
            if ! $cc $CFLAGS $flags $(numdef "$num") -Isrc -I$BM $BM/render.c $BM/port_stdio.c $BM/counter.c "$lib" \
                $( [ "$t" = x86_64 ] || echo -static ) -o "$OUT/$t/render-$num" >"$LOG/$t-$num.log" 2>&1; then
                fail "$t/$num: build driver" "$(head -c 600 "$LOG/$t-$num.log")"; return 1
            fi
        fi
    done
    ok "$t: build"
}

# The bare-metal driver: startup code, semihosting, render.c, the core.
build_bare() {
    local t=$1 num=$2 cc=$3 flags=$4 lib=$5 common
    common="-Wl,--gc-sections -L$BM -Isrc -I$BM -DTG_BM_ARENA_BYTES=$(target_arena "$t") $(numdef "$num")"
    common="$common $BM/startup.c $BM/semihost.c $BM/render.c $BM/counter.c"
    case $t in
        m0|m0mps2) # no C library at all: raw semihosting, our memcpy, libgcc last
            local board="-Tmicrobit.ld"
            # m0mps2: the same M0 code on the MPS2 board (ARMv6-M is a subset of ARMv7-M), in its
            # 16 MB PSRAM: full-size frames and an instruction counter
            [ "$t" = m0mps2 ] && board="-Tmps2.ld -DTG_BM_MPS2 -Wl,--defsym=RAM_ORIGIN=0x21000000 -Wl,--defsym=RAM_SIZE=16M"
            $cc $CFLAGS -Os $flags -ffreestanding -nostdlib -Wl,--undefined=tgp_vectors $board \
                -Wl,-Map="$BIN/$t/render-$num.map" $common $BM/port_semihost.c $BM/libc_mini.c "$lib" -lgcc \
                -o "$BIN/$t/render-$num.elf" ;;
        m3|m4f) # newlib: stdio over semihosting (librdimon), our startup and vector table
            $cc $CFLAGS $flags -DTG_BM_NEWLIB -DTG_BM_MPS2 --specs=rdimon.specs -nostartfiles \
                -Wl,--undefined=tgp_vectors -Tmps2.ld $(count_ram "$t") $common $BM/port_stdio.c "$lib" \
                -o "$BIN/$t/render-$num.elf" ;;
        rv32|rv32f) # picolibc for the string functions, our startup and semihosting
            $cc $CFLAGS $flags -nostartfiles -Trv32_virt.ld $(count_ram "$t") $common $BM/port_semihost.c "$lib" \
                -o "$BIN/$t/render-$num.elf" ;;
    esac >"$LOG/$t-$num.log" 2>&1 || { fail "$t/$num: build driver" "$(head -c 800 "$LOG/$t-$num.log")"; return 1; }
}
# Counting builds (make cross-count) need room for a bigger frame: the
# MPS2's 16 MB PSRAM, 16 MB of the virt board's DRAM.
count_ram() {
    [ "$MODE" = count ] || return 0
    case $1 in
        m3|m4f) echo "-Wl,--defsym=RAM_ORIGIN=0x21000000 -Wl,--defsym=RAM_SIZE=16M" ;;
        rv32|rv32f) echo "-Wl,--defsym=RAM_SIZE=16M" ;;
    esac
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

# run_cli TARGET DIR: `tinygi render` of the CLI scenes, colour PPM and every AOV as PFM,
# and each other technique's colour and AO.
run_cli() {
    local t=$1 dir=$2 runner num exe s a tech rc=0
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
            for tech in $CLI_TECHNIQUES; do
                $runner "$exe" render "builtin:$s" --size "$SIZE" --frames "$FRAMES" --shadow-size "$SHADOW" --quiet --technique "$tech" \
                    -o "$dir/$s-$num.$tech.ppm" >>"$dir.log" 2>&1 || rc=1
                $runner "$exe" render "builtin:$s" --size "$SIZE" --frames "$FRAMES" --shadow-size "$SHADOW" --quiet --technique "$tech" \
                    --aov ao -o "$dir/$s-$num.$tech.ao.pfm" >>"$dir.log" 2>&1 || rc=1
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

# run_driver TARGET NUM DIR RUN: the driver with RUN's arguments, writing into DIR.
run_driver() {
    local t=$1 num=$2 dir=$3 run=$4 args a
    rm -rf "$dir"; mkdir -p "$dir"
    if is_bare "$t"; then
        args="arg=render,arg=out=$dir"
        for a in ${run//,/ }; do args="$args,arg=$a"; done
        timeout "$QEMU_TIMEOUT" $(target_qemu "$t") -nographic -monitor none \
            -serial none -semihosting-config "enable=on,target=native,$args" \
            -kernel "$BIN/$t/render-$num.elf" >"$dir.log" 2>&1
    else
        timeout "$QEMU_TIMEOUT" $(target_run "$t") "$OUT/$t/render-$num" "out=$dir" ${run//,/ } >"$dir.log" 2>&1
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

# Every distinct run gets a number; x86-64 renders each once per number type.
ALL_RUNS=()
run_index() { # RUN -> its number (1-based) in ALL_RUNS
    local i
    for i in "${!ALL_RUNS[@]}"; do [ "${ALL_RUNS[$i]}" = "$1" ] && { echo $((i + 1)); return; }; done
}
add_runs() { local r; for r in "$@"; do [ -n "$(run_index "$r")" ] || ALL_RUNS+=("$r"); done; }

# The frame counts the bare-metal logs printed, one line each.
print_counts() { # TARGET NUM LOG
    grep -h ' instructions, ' "$3" | sed "s|^|cross: $1/$2 |"
}

# The instruction counts are the same in a second run of the target's
# first run (QEMU's virtual clock, never the host's).
check_count_repeats() { # TARGET NUM
    local t=$1 num=$2 run i dir
    run=$(target_runs "$t" | cut -d' ' -f1); i=$(run_index "$run"); dir="$OUT/out/$t/$num-$i"
    run_driver "$t" "$num" "$dir-again" "$run"
    if [ -z "$(print_counts "$t" "$num" "$dir.log")" ]; then fail "$t/$num: instruction counts" "none printed"
    elif [ "$(print_counts "$t" "$num" "$dir.log")" = "$(print_counts "$t" "$num" "$dir-again.log")" ]; then
        ok "$t/$num: instruction counts identical in a second run"
    else fail "$t/$num: instruction counts" "differ between two runs: $dir.log $dir-again.log"; fi
}

# The floating-point builds for an FPU must not fall back to soft float.
check_fpu() { # TARGET ELF
    local n s
    case $1 in
        m4f) n=$(arm-none-eabi-objdump -d "$2" | grep -cE '\sv(add|sub|mul|div|sqrt)\.f32\s')
             s=$(arm-none-eabi-objdump -d "$2" | grep -cE 'bl.*<__aeabi_f(add|sub|mul|div)>') ;;
        rv32f) n=$(riscv64-unknown-elf-objdump -d "$2" | grep -cE '\sf(add|sub|mul|div|sqrt)\.s\s')
               s=$(riscv64-unknown-elf-objdump -d "$2" | grep -cE 'call.*<__(add|sub|mul|div)sf3>') ;;
        *) return 0 ;;
    esac
    if [ "$n" -gt 100 ] && [ "$s" -eq 0 ]; then ok "$1/float: on the FPU ($n float arithmetic instructions, no soft-float calls)"
    else fail "$1/float: on the FPU" "$n float instructions, $s soft-float calls"; fi
}

check_mode() {
    local t num run i dir
    add_runs "$RUN"
    for t in $TARGETS; do is_bare "$t" && add_runs $(target_runs "$t"); done
    for i in "${!ALL_RUNS[@]}"; do log "run $((i + 1)): ${ALL_RUNS[$i]}"; done

    # ---- x86-64: the reference ----
    build_target x86_64 || { echo "$passed passed, $failed failed"; exit 1; }
    for num in float fixed; do
        for i in "${!ALL_RUNS[@]}"; do
            dir="$OUT/out/x86_64/$num-$((i + 1))"
            if run_driver x86_64 "$num" "$dir" "${ALL_RUNS[$i]}"; then
                ok "x86_64/$num run $((i + 1)): render $(find "$dir" -type f | wc -l) files"
            else fail "x86_64/$num run $((i + 1)): render" "$(tail -n 5 "$dir.log")"; fi
        done
    done
    if build_hosted x86_64; then
        if run_cli x86_64 "$OUT/out/x86_64/cli"; then ok "x86_64: tinygi render ($CLI_SCENES)"
        else fail "x86_64: tinygi render" "$(tail -n 5 "$OUT/out/x86_64/cli.log")"; fi
    fi

    # ---- the other targets ----
    for t in $TARGETS; do
        build_target "$t" || continue
        check_fpu "$t" "$BIN/$t/render-float.elf"
        for num in $(target_nums "$t"); do
            for run in $(target_runs "$t"); do
                i=$(run_index "$run"); dir="$OUT/out/$t/$num-$i"
                run_driver "$t" "$num" "$dir" "$run"
                check_run "$t/$num run $i" $? "$dir"
                compare_dir "$t/$num run $i" "$OUT/out/x86_64/$num-$i" "$dir"
                if is_bare "$t"; then
                    print_counts "$t" "$num" "$dir.log"
                    grep -h '^startup: stack' "$dir.log" | sed "s|^|cross: $t/$num |"
                    case $t in m0|m0mps2) grep -h 'arena used' "$dir.log" | sed "s|^|cross: $t/$num |" ;; esac
                fi
            done
        done
        case $t in m3|rv32f) check_count_repeats "$t" "$(target_nums "$t" | cut -d' ' -f1)" ;; esac
        if ! is_bare "$t" && build_hosted "$t"; then
            run_cli "$t" "$OUT/out/$t/cli" || fail "$t: tinygi render" "$(tail -n 5 "$OUT/out/$t/cli.log")"
            compare_dir "$t/cli" "$OUT/out/x86_64/cli" "$OUT/out/$t/cli"
            run_tests "$t"
        fi
    done
}

# make cross-count: COUNT_RUN on every bare-metal core, a table of
# instructions per frame.  The core libraries are make cross's; the
# drivers are linked for more RAM, into their own directory.
count_mode() {
    local t num dir n table=""
    BIN="$OUT/count"; LOG="$BIN/log"; mkdir -p "$LOG"
    for t in m3 m4f m0mps2 rv32 rv32f; do
        build_target "$t" || continue
        for num in $(target_nums "$t"); do
            dir="$BIN/out/$t/$num"
            run_driver "$t" "$num" "$dir" "$COUNT_RUN"
            check_run "$t/$num $COUNT_RUN" $? "$dir"
            print_counts "$t" "$num" "$dir.log"
            n=$(grep -h ' instructions, ' "$dir.log" | tail -n 1 | sed 's/.*: \([0-9]*\) instructions.*/\1/')
            table="$table$(count_row "$(core_name "$t")" "$(number_name "$t" "$num")" "${n:-0}")"$'\n'
        done
    done
    echo "cross: the last frame of $COUNT_RUN (QEMU -icount, platform/baremetal/counter.c);"
    echo "cross: frames per second if one instruction takes one cycle"
    echo "| core | number | instructions per frame | per pixel | fps at 100 MHz | fps at 480 MHz |"
    echo "| --- | --- | --- | --- | --- | --- |"
    printf '%s' "$table"
}
core_name() {
    case $1 in m3) echo Cortex-M3 ;; m4f) echo Cortex-M4F ;; m0mps2) echo "Cortex-M0 (-Os)" ;;
               rv32) echo "RISC-V RV32IMAC" ;; rv32f) echo "RISC-V RV32IMAFC" ;; *) echo "$1" ;; esac
}
number_name() { # TARGET NUM
    case $1/$2 in */fixed) echo Q16.16 ;; m4f/float|rv32f/float) echo "float on the FPU" ;; *) echo "soft float" ;; esac
}
count_row() { # CORE NUMBER INSTRUCTIONS
    local px size
    size=$(echo "$COUNT_RUN" | sed -n 's/.*size=\([0-9]*\)x\([0-9]*\).*/\1 \2/p')
    px=$(echo "$size" | awk '{ print $1 * $2 }')
    awk -v c="$1" -v t="$2" -v n="$3" -v px="$px" 'BEGIN {
        if (n == 0) { printf "| %s | %s | ? | ? | ? | ? |", c, t; exit }
        printf "| %s | %s | %.1fM | %d | %.2f | %.2f |", c, t, n / 1e6, n / px, 100e6 / n, 480e6 / n }'
}

if [ "$MODE" = count ]; then count_mode; else check_mode; fi
echo "cross: $(( $(date +%s) - t0 )) s; logs in $LOG and $BIN/out/*/*.log"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
