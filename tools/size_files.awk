# SPDX-License-Identifier: MIT
# tools/size_files.awk - .text bytes per object file of a program, from its
# GNU ld map (-Wl,-Map=FILE): the sections the linker kept, summed by the
# object (or archive member) they came from.  Used by tools/size_table.sh.
#   awk -f tools/size_files.awk program.map | sort -rn
/^Linker script and memory map/ { on = 1; next }
!on { next }
/^ \.text[^ ]*$/ { pending = 1; next }
{
    if ((pending || $1 ~ /^\.text/) && $0 ~ /0x[0-9a-f]+ +0x[0-9a-f]+ /) {
        n = split($0, w, " "); size = w[n - 1]; file = w[n]
        if (!pending) { size = w[3]; file = w[4] }
        sub(/.*\(/, "", file); sub(/\)$/, "", file); sub(/.*\//, "", file)
        bytes[file] += hex(size)
    }
    pending = 0
}
function hex(h,   i, c, v) {
    v = 0; h = tolower(substr(h, 3))
    for (i = 1; i <= length(h); i++) { c = index("0123456789abcdef", substr(h, i, 1)) - 1; v = v * 16 + c }
    return v
}
END { for (f in bytes) printf "%7d  %s\n", bytes[f], f }
