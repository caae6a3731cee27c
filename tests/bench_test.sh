#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/bench_test.sh - the accuracy-vs-time bench (tools/bench.c) end to end
# at a tiny size (32x24, one run, 17 reference samples, two scenes), float
# then fixed then the report:
#  - rows-float.csv / rows-fixed.csv / bench.csv: the header, one row per
#    configuration and scene in each number type, every number finite and in
#    range (AO errors in [0, 1], bent angle in [0, 180], near error >= 0 or
#    empty where the technique has no near field, ms > 0);
#  - the error columns are deterministic (a second float run gives the same);
#  - bench.md: the summary, frontier, every paper claim with a verdict, the
#    HBIL pass breakdown, the interreflection row, and Markdown tables whose
#    rows all have their header's column count;
#  - bench.svg: well-formed XML (python3 or xmllint when present, else a tag
#    balance check), one polyline per technique, no NaN coordinates;
#  - contact.ppm: P6 header and exact byte size of a 5x3 sheet; contact.png:
#    PNG signature and the same size in IHDR, 8-bit greyscale;
#  - colour against the path tracer: color-float.csv / color-fixed.csv /
#    bench-color.csv, one row per scene and technique (thirteen), RMSE in [0, 1],
#    energy > 0, the reference's noise >= 0, deterministic; bench.md's colour
#    section; bench-color.svg parses, a dot per technique and number type;
#    contact-color.png: a 5x3 sheet, 8-bit RGB;
#  - multi-bounce AO: multibounce-float.csv / -fixed.csv, two AO sources per
#    scene, RMSEs in [0, 1], biases in [-1, 1]; bench.md's section;
#  - instructions (where valgrind is installed): tools/bench_cost.py's
#    cost-float.csv / cost-fixed.csv, a count per curve point and scene, SSAO's
#    growing with its samples; the report's table of every curve setting with
#    both number types' counts; bench-cost.svg parses, a polyline per curve;
#  - bad usage exits 2.
# Timings are printed by the bench, never asserted here.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
BUILD=${BUILD:-build}
sh_scratch bench
W=32; H=24
ARGS="--size ${W}x${H} --runs 1 --ref-samples 17 --scenes groove,columns --pt-samples 4 --color-frames 2"

if ! make -s BUILD="$BUILD" bench-build >"$T/make.log" 2>&1; then
    fail "bench builds" "$(tail -n 5 "$T/make.log")"; summary; exit 1
fi
ok "bench builds"
F="$BUILD/bench-float"; X="$BUILD/bench-fixed"

expect "float run" "$F" run $ARGS --out "$T/o" >"$T/float.log" 2>&1
expect "fixed run" "$X" run $ARGS --out "$T/o" >"$T/fixed.log" 2>&1
expect "report" "$F" report --size ${W}x${H} --out "$T/o" >"$T/report.log" 2>&1

header="scene,technique,slices,samples,radius,interleave,number,median_ms,cpu_ms,ao_rmse,ao_max,bent_deg,near_rel,default,curve"
for f in rows-float.csv rows-fixed.csv bench.csv; do
    expect "$f header" test "$(head -n 1 "$T/o/$f" 2>/dev/null)" = "$header"
done
nf=$(($(wc -l <"$T/o/rows-float.csv") - 1)); nx=$(($(wc -l <"$T/o/rows-fixed.csv") - 1))
nb=$(($(wc -l <"$T/o/bench.csv") - 1))
expect "float rows: 2 scenes x the sweep ($nf)" test "$nf" -gt 40 -a $((nf % 2)) -eq 0
expect "fixed rows match float rows ($nx)" test "$nx" -eq "$nf"
expect "bench.csv has both ($nb)" test "$nb" -eq $((nf + nx))

# every row: 14 fields, finite numbers in range
bad=$(awk -F, 'NR > 1 {
    num = "^-?[0-9]+(\\.[0-9]+)?$"
    if (NF != 15) { print "fields " NR; next }
    for (i = 8; i <= 12; i++) if ($i !~ num) print "not a finite number: line " NR " field " i " = " $i
    if ($13 != "" && $13 !~ num) print "near not finite: line " NR
    if ($8 + 0 <= 0) print "ms <= 0: line " NR
    if ($9 + 0 < 0) print "cpu ms < 0: line " NR
    if ($10 < 0 || $10 > 1 || $11 < 0 || $11 > 1) print "AO error out of [0,1]: line " NR
    if ($12 < 0 || $12 > 180) print "bent angle out of [0,180]: line " NR
    if ($13 != "" && $13 < 0) print "near error < 0: line " NR
    if ($7 != "float" && $7 != "fixed") print "number type: line " NR
}' "$T/o/bench.csv")
expect "every row finite and in range${bad:+: $bad}" test -z "$bad"
near_techs=$(awk -F, 'NR > 1 && $13 != "" {print $2}' "$T/o/bench.csv" | sort -u | tr '\n' ' ')
expect "near error for hbil, ssdo, gtao+ir, ssilvb only ($near_techs)" \
    test "$near_techs" = "gtao+ir hbil hbil-1x hbil-3l hbil-full ssdo ssilvb ssilvb-3l "
for t in hbil hbil-1x hbil-full hbil-3l hbil-ao gtao hbao ssao vo ssdo bentcone ssdo-do gtao+ir ssilvb ssilvb-3l; do
    expect "technique $t in the table" grep -q "^[a-z]*,$t," "$T/o/bench.csv"
done

# errors are deterministic: a second float run (fresh reference cache) agrees
"$F" run $ARGS --out "$T/o2" >/dev/null 2>&1
cut -d, -f1-7,10-15 "$T/o/rows-float.csv" >"$T/a"; cut -d, -f1-7,10-15 "$T/o2/rows-float.csv" >"$T/b"
expect "error columns deterministic" cmp -s "$T/a" "$T/b"
cut -d, -f1-4,6-9 "$T/o/color-float.csv" >"$T/a"; cut -d, -f1-4,6-9 "$T/o2/color-float.csv" >"$T/b"
expect "colour error columns deterministic" cmp -s "$T/a" "$T/b"

# colour against the path tracer
cheader="scene,technique,frames,number,cpu_ms,color_rmse,energy,ref_noise,ref_paths"
for f in color-float.csv color-fixed.csv bench-color.csv; do
    expect "$f header" test "$(head -n 1 "$T/o/$f" 2>/dev/null)" = "$cheader"
done
cf=$(($(wc -l <"$T/o/color-float.csv") - 1)); cb=$(($(wc -l <"$T/o/bench-color.csv") - 1))
expect "colour rows: 2 scenes x 13 techniques ($cf)" test "$cf" -eq 26
expect "bench-color.csv has both number types ($cb)" test "$cb" -eq 52
bad=$(awk -F, 'NR > 1 {
    num = "^-?[0-9]+(\\.[0-9]+)?$"
    if (NF != 9) { print "fields " NR; next }
    for (i = 5; i <= 8; i++) if ($i !~ num) print "not a finite number: line " NR " field " i " = " $i
    if ($6 < 0 || $6 > 1) print "colour RMSE out of [0,1]: line " NR
    if ($7 <= 0) print "energy <= 0: line " NR
    if ($8 < 0) print "noise < 0: line " NR
    if ($9 != 4) print "paths: line " NR
    if ($2 ~ /^hbil/ && $3 != 2) print "hbil frames: line " NR
}' "$T/o/bench-color.csv")
expect "every colour row finite and in range${bad:+: $bad}" test -z "$bad"
for t in hbil hbil-1x hbil-full hbil-3l gtao hbao ssao vo ssdo bentcone reference; do
    expect "colour of $t" grep -q "^[a-z]*,$t,.*,float," "$T/o/bench-color.csv"
done

# multi-bounce AO under a white sky
mheader="scene,ao,number,plain_rmse,multibounce_rmse,interreflection_rmse,plain_bias,multibounce_bias"
for f in multibounce-float.csv multibounce-fixed.csv; do
    expect "$f header" test "$(head -n 1 "$T/o/$f" 2>/dev/null)" = "$mheader"
    expect "$f: 2 scenes x 2 AO sources" test "$(($(wc -l <"$T/o/$f") - 1))" -eq 4
    bad=$(awk -F, 'NR > 1 { if (NF != 8) print "fields " NR
        for (i = 4; i <= 6; i++) if (!($i >= 0 && $i <= 1)) print "RMSE out of [0,1]: line " NR
        for (i = 7; i <= 8; i++) if (!($i >= -1 && $i <= 1)) print "bias out of [-1,1]: line " NR }' "$T/o/$f")
    expect "$f in range${bad:+: $bad}" test -z "$bad"
done

# bench.md
md="$T/o/bench.md"
for s in "## Default setting" "## Colour against the path-traced reference" "## Multi-bounce AO (GTAO" "## Frontier" "Loos & Sloan table 1" "Klehm fig. 8" "Ritschel table 1" \
         "HBIL pass breakdown" "Interreflection (RTR eq. 11.12-11.13)" "## Every row"; do
    expect "bench.md: $s" grep -qF "$s" "$md"
done
verdicts=$(grep -c "verdict: \*\*\|Verdict.*: \*\*\|Verdict (" "$md")
expect "bench.md: a verdict per claim ($verdicts)" test "$verdicts" -ge 8
badtab=$(awk -F'|' '/^\|/ { if (!inhdr) { cols = NF; inhdr = 1 } else if (NF != cols) print NR } !/^\|/ { inhdr = 0 }' "$md")
expect "bench.md tables well-formed${badtab:+ (bad lines $badtab)}" test -z "$badtab"
expect "bench.md: no nan" sh -c "! grep -qiw 'nan\|inf' '$md'"

# bench.svg
svg="$T/o/bench.svg"
if command -v python3 >/dev/null 2>&1; then
    expect "bench.svg parses (python3)" python3 -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" "$svg"
elif command -v xmllint >/dev/null 2>&1; then
    expect "bench.svg parses (xmllint)" xmllint --noout "$svg"
else
    opens=$(grep -o '<[a-z][a-z]*' "$svg" | wc -l); closes=$(grep -o '</[a-z]*>\|/>' "$svg" | wc -l)
    expect "bench.svg tags balance ($opens/$closes)" test "$opens" -eq "$closes"
fi
expect "bench.svg: <svg ... </svg>" sh -c "head -n 1 '$svg' | grep -q '^<svg' && tail -n 1 '$svg' | grep -q '^</svg>'"
lines=$(grep -c '<polyline fill="none" stroke="#[0-9a-f]*" stroke-width="2"' "$svg")
expect "bench.svg: a polyline per technique and number type ($lines)" test "$lines" -eq 26
expect "bench.svg: no NaN/inf coordinates" sh -c "! grep -qi 'nan\|inf' '$svg'"

# contact sheet: 5x3 tiles (thirteen techniques and the reference) with 2-pixel borders
cw=$((5 * W + 12)); ch=$((3 * H + 8))
ppm="$T/o/contact.ppm"
expect "contact.ppm header" test "$(head -c 20 "$ppm" | tr '\n' ' ' | cut -d' ' -f1-4)" = "P6 $cw $ch 255"
hdr=$(printf 'P6\n%d %d\n255\n' $cw $ch | wc -c)
expect "contact.ppm size" test "$(wc -c <"$ppm")" -eq $((hdr + cw * ch * 3))
# png_is NAME WIDTH HEIGHT COLOUR_TYPE: the signature, and IHDR's size, 8 bits, colour type
png_is() {
    expect "$(basename "$1") signature" test "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a"
    expect "$(basename "$1") size in IHDR, 8 bits, colour type $4" test "$(od -An -tu1 -j16 -N10 "$1" | tr -s ' ' | sed 's/^ //')" = \
        "0 0 $(($2 >> 8)) $(($2 & 255)) 0 0 $(($3 >> 8)) $(($3 & 255)) 8 $4"
}
png_is "$T/o/contact.png" $cw $ch 0

# colour plot and sheet
csvg="$T/o/bench-color.svg"
if command -v python3 >/dev/null 2>&1; then
    expect "bench-color.svg parses (python3)" python3 -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" "$csvg"
fi
dots=$(grep -c '<circle' "$csvg")
expect "bench-color.svg: a dot per technique and number type ($dots)" test "$dots" -eq 26
expect "bench-color.svg: no NaN/inf" sh -c "! grep -qi 'nan\|inf' '$csvg'"
png_is "$T/o/contact-color.png" $((5 * W + 12)) $((3 * H + 8)) 2

# instructions per pixel of each configuration on the curves (tools/bench_cost.py,
# callgrind) and the report with them, where valgrind is installed (not
# under the sanitizers: valgrind cannot run their programs)
if command -v valgrind >/dev/null 2>&1 && [ -z "${ASAN_OPTIONS:-}" ]; then
    expect "bench_cost.py runs" python3 tools/bench_cost.py --build "$BUILD" --size ${W}x${H} --scenes groove,columns \
        --out "$T/o" >"$T/cost.log" 2>&1
    expect "report with the counts" "$F" report --size ${W}x${H} --out "$T/o" >"$T/report2.log" 2>&1
    on_curve=$(awk -F, 'NR > 1 && $1 == "groove" && $15 == 1' "$T/o/rows-float.csv" | wc -l)
    for n in float fixed; do
        f="$T/o/cost-$n.csv"
        expect "cost-$n.csv header" test "$(head -n 1 "$f" 2>/dev/null)" = "scene,technique,slices,samples,number,pixels,instructions"
        expect "cost-$n.csv: every curve point of both scenes ($on_curve each)" test $(($(wc -l <"$f") - 1)) -eq $((2 * on_curve))
        bad=$(awk -F, -v n=$n -v px=$((W * H)) 'NR > 1 { if (NF != 7 || $5 != n || $6 != px || $7 !~ /^[0-9]+$/ || $7 < 200 * px) print NR }' "$f")
        expect "cost-$n.csv: a frame of at least 200 instructions a pixel${bad:+ (bad lines $bad)}" test -z "$bad"
        # the counts belong to their configurations: SSAO's grow with its samples (4 to 64)
        grows=$(awk -F, '$1 == "columns" && $2 == "ssao" { if (n && $7 <= last) bad = 1; last = $7; n++ } END { print (n == 6 && !bad) ? "yes" : "no" }' "$f")
        expect "cost-$n.csv: ssao's instructions grow with its samples" test "$grows" = yes
    done
    expect "bench.md: every curve setting with its instructions" grep -qF "## Every setting on the curves" "$md"
    counted=$(awk -F'|' '/^## Every setting on the curves/ { on = 1; next } /^## / { on = 0 } on && /^\| [a-z]/ && $5 ~ /[0-9]/ && $7 ~ /[0-9]/' "$md" | wc -l)
    expect "bench.md: float and Q16.16 counts on every curve setting ($counted of $on_curve)" test "$counted" -eq "$on_curve"
    badtab=$(awk -F'|' '/^\|/ { if (!inhdr) { cols = NF; inhdr = 1 } else if (NF != cols) print NR } !/^\|/ { inhdr = 0 }' "$md")
    expect "bench.md tables well-formed with the counts${badtab:+ (bad lines $badtab)}" test -z "$badtab"
    csvg="$T/o/bench-cost.svg"
    expect "bench-cost.svg parses" python3 -c "import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])" "$csvg"
    lines=$(grep -c '<polyline fill="none" stroke="#[0-9a-f]*" stroke-width="2"' "$csvg")
    expect "bench-cost.svg: a polyline per technique and number type ($lines)" test "$lines" -eq 26
    expect "bench-cost.svg: no NaN/inf coordinates" sh -c "! grep -qi 'nan\|inf' '$csvg'"
else
    echo "skip: tools/bench_cost.py not run: valgrind is not installed (make bench-valgrind installs it), or the programs are the sanitizers'"
fi

# usage
"$F" >/dev/null 2>&1; expect "no command: exit 2" test $? -eq 2
"$F" run --size 2x2 >/dev/null 2>&1; expect "bad size: exit 2" test $? -eq 2
"$F" frobnicate --out "$T/x" >/dev/null 2>&1; expect "unknown command: exit 2" test $? -eq 2
"$F" report --out "$T/empty" >/dev/null 2>&1; expect "report without rows: exit 2" test $? -eq 2
"$F" run --pt-samples 1 --out "$T/x" >/dev/null 2>&1; expect "bad pt-samples: exit 2" test $? -eq 2
"$F" run --pt-samples 1000 --out "$T/x" >/dev/null 2>&1; expect "pt-samples past 512 not a multiple of 512: exit 2" test $? -eq 2

# --only ao: the sweep alone, no colour and no multi-bounce rows
"$F" run --size 16x12 --runs 1 --ref-samples 17 --scenes groove --only ao --out "$T/aoonly" >/dev/null 2>&1
expect "--only ao: the sweep's rows, no colour or multi-bounce rows" \
    sh -c "test \$(wc -l <'$T/aoonly/rows-float.csv') -gt 40 && test \$(wc -l <'$T/aoonly/color-float.csv') -eq 1 && test \$(wc -l <'$T/aoonly/multibounce-float.csv') -eq 1"
"$F" run --only shadows --out "$T/x" >/dev/null 2>&1; expect "--only shadows: exit 2" test $? -eq 2

# a reference of more paths than a frame takes: traced over frames (two halves of two)
"$F" run --size 16x12 --runs 1 --scenes cornell --pt-samples 1024 --color-frames 2 --only color --out "$T/big" >/dev/null 2>&1
expect "--pt-samples 1024: traced, every row says 1024 paths" \
    sh -c "test \$(awk -F, 'NR > 1 && \$9 != 1024' '$T/big/color-float.csv' | wc -l) -eq 0 && test \$(wc -l <'$T/big/color-float.csv') -gt 1"
summary
