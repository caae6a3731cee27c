#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# tests/png_test.sh - `tinygi render -o x.png` (and `tinygi diff -o d.png`),
# both number types, decoded by an independent reader: Python's zlib.  Each
# PNG must have the signature, IHDR 8-bit RGB, every chunk's CRC-32 right,
# IDATs that zlib inflates (which checks the Adler-32) into height scanlines
# of filter 0, and exactly the pixels of the PPM of the same frame.  Sizes
# from 1x1 to a row of 8192 pixels (the largest scanline a stored deflate
# block holds), several AOVs, frame numbering with %d.
set -u
cd "$(dirname "$0")/.."
. tests/shcheck.sh
sh_build
sh_scratch png
if ! command -v python3 >/dev/null 2>&1; then
    fail "python3" "python3 is needed to decode the PNG files"; summary; exit 1
fi

# png_matches_ppm PNG PPM: decode both, say what differs (nothing: exit 0)
cat >"$T/check.py" <<'EOF'
import struct, sys, zlib

def ppm(path):
    d = open(path, 'rb').read()
    parts = d.split(b'\n', 3)
    assert parts[0] == b'P6' and parts[2] == b'255', 'not an 8-bit P6'
    w, h = map(int, parts[1].split())
    return w, h, parts[3]

def png(path):
    d = open(path, 'rb').read()
    assert d[:8] == b'\x89PNG\r\n\x1a\n', 'signature'
    p, chunks = 8, []
    while p < len(d):
        n, = struct.unpack('>I', d[p:p + 4])
        kind, data = d[p + 4:p + 8], d[p + 8:p + 8 + n]
        crc, = struct.unpack('>I', d[p + 8 + n:p + 12 + n])
        assert zlib.crc32(kind + data) & 0xffffffff == crc, 'CRC of chunk %d (%r)' % (len(chunks), kind)
        chunks.append((kind, data))
        p += 12 + n
    assert p == len(d), 'bytes after the last chunk'
    assert chunks[0][0] == b'IHDR' and chunks[-1] == (b'IEND', b''), 'IHDR first, IEND last'
    w, h, depth, colour, comp, filt, inter = struct.unpack('>IIBBBBB', chunks[0][1])
    assert (depth, colour, comp, filt, inter) == (8, 2, 0, 0, 0), 'IHDR: 8-bit RGB'
    kinds = [k for k, _ in chunks[1:-1]]
    assert set(kinds) == {b'IDAT'}, 'only IDAT between: %r' % kinds
    raw = zlib.decompress(b''.join(c for k, c in chunks if k == b'IDAT'))  # checks Adler-32
    row = 1 + 3 * w
    assert len(raw) == h * row, 'scanlines: %d bytes for %dx%d' % (len(raw), w, h)
    assert all(raw[y * row] == 0 for y in range(h)), 'filter type 0 on every row'
    return w, h, b''.join(raw[y * row + 1:(y + 1) * row] for y in range(h))

try:
    a, b = png(sys.argv[1]), ppm(sys.argv[2])
    assert a[:2] == b[:2], 'size %dx%d vs %dx%d' % (a[0], a[1], b[0], b[1])
    assert a[2] == b[2], 'pixels differ from the PPM'
except Exception as e:  # one line for the test log
    print('%s: %s' % (sys.argv[1], e))
    sys.exit(1)
EOF
png_matches_ppm() { python3 "$T/check.py" "$1" "$2" >"$T/why" 2>&1; }

# every PNG of one CLI ($BIN, named $1)
check_binary() {
    local tag=$1
    for c in "cornell 1x1 color" "cornell 17x13 color" "spheres 200x150 color" "columns 64x48 normal" \
             "cornell 40x30 depth" "groove 33x20 ao" "plane 8192x1 color"; do
        set -- $c
        "$BIN" render "builtin:$1" --size "$2" --aov "$3" -o "$T/x.png" --quiet &&
            "$BIN" render "builtin:$1" --size "$2" --aov "$3" -o "$T/x.ppm" --quiet
        if [ $? -ne 0 ]; then fail "$tag/render_$1_$2_$3"; continue; fi
        if png_matches_ppm "$T/x.png" "$T/x.ppm"; then ok "$tag/png_$1_$2_$3"
        else fail "$tag/png_$1_$2_$3" "$(cat "$T/why")"; fi
    done
    # frame numbering: every frame a valid PNG of that frame
    "$BIN" render builtin:spheres --size 24x18 --frames 3 -o "$T/f%02d.png" --quiet &&
        "$BIN" render builtin:spheres --size 24x18 --frames 3 -o "$T/f%02d.ppm" --quiet
    expect "$tag/png_frames_numbered" [ -f "$T/f00.png" -a -f "$T/f01.png" -a -f "$T/f02.png" -a ! -e "$T/f03.png" ]
    for i in 00 01 02; do
        if png_matches_ppm "$T/f$i.png" "$T/f$i.ppm"; then ok "$tag/png_frame_$i"
        else fail "$tag/png_frame_$i" "$(cat "$T/why")"; fi
    done
    # diff -o d.png: the same difference image as d.ppm
    "$BIN" diff "$T/f00.ppm" "$T/f02.ppm" -o "$T/d.png" >/dev/null
    "$BIN" diff "$T/f00.ppm" "$T/f02.ppm" -o "$T/d.ppm" >/dev/null
    if png_matches_ppm "$T/d.png" "$T/d.ppm"; then ok "$tag/png_diff_image"
    else fail "$tag/png_diff_image" "$(cat "$T/why")"; fi
    rm -f "$T"/*.png "$T"/*.ppm
}

each_cli check_binary
summary
