#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# limits_doc_test.sh - src/scene/format.md cites the limits of the block at
# the top of src/tinygi.h: every row "| `TG_...` | VALUE |" of its Limits
# table holds the header's value (compiled, so expressions such as
# (1L << 30) count), and every TG_MAX_/TG_MIN_ macro the parser uses has a row.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
CC=${CC:-cc}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

rows=$(sed -n 's/^| `\(TG_[A-Z_0-9]*\)` | \([0-9.]*\) |.*/\1 \2/p' src/scene/format.md)
expect "format.md has a Limits table" test -n "$rows"
{
    echo '#include <stdio.h>'
    echo '#include "tinygi.h"'
    echo 'int main(void) {'
    echo "$rows" | while read -r name value; do
        echo "    printf(\"%s %.10g\\n\", \"$name\", (double)($name));"
    done
    echo '    return 0; }'
} >"$tmp/values.c"
if $CC -std=c99 -Isrc "$tmp/values.c" -o "$tmp/values" 2>"$tmp/err"; then
    "$tmp/values" >"$tmp/header.txt"
    while read -r name value; do
        hv=$(awk -v n="$name" '$1 == n {print $2}' "$tmp/header.txt")
        if awk -v a="$hv" -v b="$value" 'BEGIN { exit !(a != "" && (a - b <= 1e-6 * b && b - a <= 1e-6 * b)) }'; then ok "format.md: $name = $value"
        else fail "format.md: $name" "the table says $value, tinygi.h says $hv"; fi
    done <<<"$rows"
else
    fail "format.md's limits compile against tinygi.h" "$(head -3 "$tmp/err")"
fi
used=$(grep -ohE '\bTG_(MAX|MIN|DEFAULT)_[A-Z_0-9]+' src/scene/*.c | sort -u)
for m in $used; do
    expect "format.md cites $m (used by the parser)" grep -q "^| \`$m\` |" src/scene/format.md
done
summary
