#!/usr/bin/env bash
# golden_test.sh - every built-in scene, both number types, rendered small
# (80x60, one frame, HBIL) and compared with the committed golden images by
# the same diff users run (`tinygi diff`).
#
# Tolerances (stated): colour PPM within 3 levels of 255 per channel;
# AO PFM within 0.02 absolute per pixel.  Renders are deterministic, so on
# the machine that made the goldens the difference is 0; the slack is for
# other compilers and targets.  Fixed and float AO must also agree within
# RMSE 0.02 on every scene, HBIL's and the visibility bitmask's (ssilvb).
# Regenerate after an intended change: `make golden`, then look at them.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
BUILD=${BUILD:-build}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
scenes="plane groove cornell spheres columns"

for num in float fixed; do
    bin=$BUILD/tinygi; [ $num = fixed ] && bin=$BUILD/tinygi-fixed
    for s in $scenes; do
        for aov in color ao; do
            ext=ppm; tol=3; [ $aov = ao ] && { ext=pfm; tol=0.02; }
            out=$tmp/$s-$aov-$num.$ext
            gold=tests/golden/$s-$aov-$num.$ext
            if ! "$bin" render builtin:$s --size 80x60 --aov $aov -o "$out" --quiet; then
                fail "golden $num $s $aov: render failed"; continue
            fi
            if [ "${GOLDEN_UPDATE:-0}" = 1 ]; then cp "$out" "$gold"; fi
            if [ ! -f "$gold" ]; then fail "golden $num $s $aov: missing $gold (make golden)"; continue; fi
            if "$BUILD/tinygi" diff "$gold" "$out" --tolerance $tol >"$tmp/diff.txt" 2>&1; then
                ok "golden $num $s $aov"
            else
                fail "golden $num $s $aov" "$(tr '\n' ' ' <"$tmp/diff.txt")"
            fi
        done
    done
done

for s in $scenes; do
    a=$tmp/$s-ao-float.pfm; b=$tmp/$s-ao-fixed.pfm
    [ -f "$a" ] && [ -f "$b" ] || { fail "fixed vs float ao $s: missing renders"; continue; }
    rmse=$("$BUILD/tinygi" diff "$a" "$b" --tolerance 1 2>/dev/null | awk '/^rmse/ {print $2}')
    if awk -v r="$rmse" 'BEGIN { exit !(r != "" && r <= 0.02) }'; then
        ok "fixed vs float ao $s (rmse $rmse)"
    else
        fail "fixed vs float ao $s" "rmse $rmse > 0.02"
    fi
    # the visibility bitmask (no golden: a comparison technique), fixed against float
    a=$tmp/$s-ssilvb-float.pfm; b=$tmp/$s-ssilvb-fixed.pfm
    if "$BUILD/tinygi" render builtin:$s --size 80x60 --aov ao --technique ssilvb -o "$a" --quiet &&
       "$BUILD/tinygi-fixed" render builtin:$s --size 80x60 --aov ao --technique ssilvb -o "$b" --quiet; then
        rmse=$("$BUILD/tinygi" diff "$a" "$b" --tolerance 1 2>/dev/null | awk '/^rmse/ {print $2}')
        if awk -v r="$rmse" 'BEGIN { exit !(r != "" && r <= 0.02) }'; then
            ok "fixed vs float ssilvb ao $s (rmse $rmse)"
        else
            fail "fixed vs float ssilvb ao $s" "rmse $rmse > 0.02"
        fi
    else
        fail "fixed vs float ssilvb ao $s: render failed"
    fi
done
summary
