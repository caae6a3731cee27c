#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/limits_test.sh - every documented limit, walked through the CLI, for
# both number types.  The limits are read from their one place, the block at
# the top of src/tinygi.h; for each one:
#  - `--help` and the README's "Command line" section state the range LO..HI;
#  - an option at each bound is accepted (--explain: parsed and planned by the
#    core, nothing rendered) and one step past it is refused with exit 2 and
#    "tinygi: error: option --NAME: [WHAT ]must be LO..HI, got V";
#  - the same limit in a scene file's `gi` line is accepted at the bound and
#    refused one step past with "FILE:LINE:COL: error: gi KEY must be LO..HI,
#    got V" (the parser's words are the CLI's).
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_build
sh_scratch limits

# the value of a limit macro in src/tinygi.h (plain integers, or (1L << N))
limit() {
    awk -v n="$1" '$1 == "#define" && $2 == n {
        v = $3; for (i = 4; i <= NF && $i != "/*"; i++) v = v " " $i; print v; exit }' src/tinygi.h |
        sed 's/L\b//g; s/^(\(.*\))$/\1/' | { read -r e; echo $((e)); }
}
SIDE=$(limit TG_MAX_IMAGE_SIDE); PIXELS=$(limit TG_MAX_IMAGE_PIXELS); FRAMES=$(limit TG_MAX_FRAMES)
SLICES=$(limit TG_MAX_SLICES); SAMPLES=$(limit TG_MAX_SAMPLES); BOUNCES=$(limit TG_MAX_BOUNCES)
RADIUS=$(limit TG_MAX_RADIUS); EXPOSURE=$(limit TG_MAX_EXPOSURE); THICKNESS=$(limit TG_MAX_THICKNESS)
SHADOW_MIN=$(limit TG_MIN_SHADOW_MAP); SHADOW_MAX=$(limit TG_MAX_SHADOW_MAP)
FILE_BYTES=$(limit TG_MAX_FILE_BYTES)
for v in SIDE PIXELS FRAMES SLICES SAMPLES BOUNCES RADIUS EXPOSURE THICKNESS SHADOW_MIN SHADOW_MAX FILE_BYTES; do
    case ${!v} in ''|*[!0-9]*) fail "header/$v" "cannot read it from src/tinygi.h: '${!v}'" ;; esac
done
# the square root of PIXELS (a square image at the pixel limit)
SQUARE=$(awk -v p="$PIXELS" 'BEGIN { s = int(sqrt(p)); while ((s + 1) * (s + 1) <= p) s++; print s }')

# the README's "Command line" section
awk '/^## Command line/ { on = 1; next } /^## / { on = 0 } on' README.md >"$T/readme"

# documented NAME RANGE: --help and the README both state RANGE for NAME
documented() {
    if grep -qF -- "$2" "$T/help"; then ok "$tag/help_states_$1_$2"; else fail "$tag/help_states_$1_$2"; fi
    if grep -qF -- "$2" "$T/readme"; then ok "$tag/readme_states_$1_$2"; else fail "$tag/readme_states_$1_$2"; fi
}

# accepted NAME ARGS...: exit 0 with --explain
accepted() {
    local name=$1; shift
    "$BIN" render builtin:cornell --explain "$@" >/dev/null 2>"$T/err"; local rc=$?
    if [ "$rc" -eq 0 ]; then ok "$tag/accepts_$name"; else fail "$tag/accepts_$name" "exit $rc: $(head -c 300 "$T/err")"; fi
}

# refused NAME MESSAGE ARGS...: exit 2, exactly MESSAGE on stderr
refused() {
    local name=$1 want=$2; shift 2
    "$BIN" render builtin:cornell --explain "$@" >/dev/null 2>"$T/err"; local rc=$?
    if [ "$rc" -ne 2 ]; then fail "$tag/refuses_$name" "exit $rc, expected 2: $(head -c 300 "$T/err")"
    elif [ "$(cat "$T/err")" != "$want" ]; then fail "$tag/refuses_$name" "'$(cat "$T/err")' is not '$want'"
    else ok "$tag/refuses_$name"; fi
}

# int_limit OPTION LO HI: accepted at LO and HI, refused at LO-1 and HI+1
int_limit() {
    local o=$1 lo=$2 hi=$3
    documented "$o" "$lo..$hi"
    accepted "${o}_$lo" "--$o" "$lo"
    accepted "${o}_$hi" "--$o" "$hi"
    refused "${o}_$((lo - 1))" "tinygi: error: option --$o: must be $lo..$hi, got $((lo - 1))" "--$o" $((lo - 1))
    refused "${o}_$((hi + 1))" "tinygi: error: option --$o: must be $lo..$hi, got $((hi + 1))" "--$o" $((hi + 1))
}

# real_limit OPTION HI: accepted at 0 and HI, refused a thousandth outside
real_limit() {
    local o=$1 hi=$2
    documented "$o" "0..$hi"
    accepted "${o}_0" "--$o" 0
    accepted "${o}_$hi" "--$o" "$hi"
    refused "${o}_-0.001" "tinygi: error: option --$o: must be 0..$hi, got -0.001" "--$o" -0.001
    refused "${o}_$hi.001" "tinygi: error: option --$o: must be 0..$hi, got $hi.001" "--$o" "$hi.001"
}

# scene_limit KEY LO HI: a gi line accepted at LO and HI, refused one step past
scene_limit() {
    local key=$1 lo=$2 hi=$3 v f rc
    for v in "$lo" "$hi" $((lo - 1)) $((hi + 1)); do
        f="$T/gi_${key}_$v.scene"
        printf 'camera pos 0 1 5 target 0 0 0\ngi %s %s\nmaterial m albedo 0.5 0.5 0.5\nsphere center 0 0 0 radius 1 material m\n' \
            "$key" "$v" >"$f"
        "$BIN" render "$f" --explain >/dev/null 2>"$T/err"; rc=$?
        if [ "$v" -ge "$lo" ] && [ "$v" -le "$hi" ]; then
            if [ "$rc" -eq 0 ]; then ok "$tag/scene_accepts_gi_${key}_$v"
            else fail "$tag/scene_accepts_gi_${key}_$v" "exit $rc: $(head -c 300 "$T/err")"; fi
        elif [ "$rc" -ne 2 ]; then fail "$tag/scene_refuses_gi_${key}_$v" "exit $rc, expected 2"
        elif ! grep -qx -- "$f:2:[0-9]*: error: gi $key must be $lo..$hi, got $v" "$T/err"; then
            fail "$tag/scene_refuses_gi_${key}_$v" "'$(cat "$T/err")' is not '$f:2:COL: error: gi $key must be $lo..$hi, got $v'"
        else ok "$tag/scene_refuses_gi_${key}_$v"; fi
    done
}

# every limit of one CLI ($BIN, named $1)
check_binary() {
    local tag=$1
    "$BIN" --help >"$T/help" 2>&1

    # --size: each side 1..SIDE, and at most PIXELS pixels
    documented size "1..$SIDE"
    documented pixels "$PIXELS"
    accepted "size_${SIDE}x1" --size "${SIDE}x1"
    accepted "size_1x${SIDE}" --size "1x${SIDE}"
    accepted "size_${SQUARE}x${SQUARE}" --size "${SQUARE}x${SQUARE}"
    refused "size_width_$((SIDE + 1))" "tinygi: error: option --size: width must be 1..$SIDE, got $((SIDE + 1))" --size "$((SIDE + 1))x1"
    refused "size_height_$((SIDE + 1))" "tinygi: error: option --size: height must be 1..$SIDE, got $((SIDE + 1))" --size "1x$((SIDE + 1))"
    refused "size_width_0" "tinygi: error: option --size: width must be 1..$SIDE, got 0" --size 0x1
    refused "size_16384x1024" "tinygi: error: option --size: width must be 1..$SIDE, got 16384" --size 16384x1024
    refused "size_pixels" "tinygi: error: option --size: pixels (width*height) must be 1..$PIXELS, got $((SQUARE * (SQUARE + 1)))" \
        --size "${SQUARE}x$((SQUARE + 1))"

    int_limit frames 1 "$FRAMES"
    int_limit slices 1 "$SLICES"
    int_limit samples 1 "$SAMPLES"
    int_limit bounces 0 "$BOUNCES"
    int_limit shadow-size "$SHADOW_MIN" "$SHADOW_MAX"
    real_limit radius "$RADIUS"
    real_limit exposure "$EXPOSURE"
    real_limit thickness "$THICKNESS"
    # input files: the help and the README say the size limit
    documented file_bytes "$FILE_BYTES"

    # the same limits in a scene file's gi line
    scene_limit slices 1 "$SLICES"
    scene_limit samples 1 "$SAMPLES"
    scene_limit bounces 0 "$BOUNCES"
    scene_limit radius 0 "$RADIUS"
}

each_cli check_binary
summary
