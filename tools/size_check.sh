#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# size_check.sh - the flash budgets of README "Flash size", checked (`make
# size-check`, run by .ci/run after `make cross` has installed the ARM
# toolchain): the Cortex-M4 .text of tools/size_app.c + the core in Q16.16
# with -flto, as tools/size_table.sh builds it, for
#   row 5, HBIL colour with direct light and shadows, baked scene, each
#          frame alone: at most 49152 bytes (48 KB);
#   row 6, AO only, every switch set: at most 24576 bytes (24 KB).
# Prints each row's bytes against its budget; exits 1 if one is over.
set -eu
cd "$(dirname "$0")/.."
OUT=${SIZE_BUILD:-build-size}
mkdir -p "$OUT"
SIZE_ROWS="5 6" SIZE_NUMS=fixed SIZE_LTO=1 bash tools/size_table.sh >"$OUT/check.log" 2>&1 ||
    { cat "$OUT/check.log" >&2; exit 1; }
fail=0
for rb in "5 49152 colour" "6 24576 AO-only"; do
    set -- $rb
    elf=$OUT/c$1-lto-fixed/size_app-fixed.elf
    text=$(arm-none-eabi-size -A "$elf" | awk '$1 == ".text" {print $2}')
    if [ "$text" -le "$2" ]; then verdict=ok; else verdict=OVER; fail=1; fi
    echo "size-check: $3 program (row $1, Q16.16, -flto): $text bytes of .text, budget $2: $verdict"
done
exit $fail
