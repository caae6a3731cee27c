#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""screen_limits.py - what screen space cannot see: HBIL's AO error split
into the part any kernel on one depth layer shares and the part that is the
kernel's own.

    python3 tools/screen_limits.py [--build build] [--scenes spheres,columns,cornell]
        [--size 160x120] [--frames 8] [--out build/screen-limits]

For every scene it renders, with BUILD/tinygi (float):

  reference   --technique reference --aov ao: ray-traced AO on the BVH, 256
              directions a pixel, the same cut-off distance as the kernel's
              radius; it sees every surface of the scene, on screen or not;
  hbil        --aov ao --frames N --depth-layers 1: the default kernel on
              one depth layer, as a colour frame has it (4x4-interleaved, 2
              slices x 32 samples), after N frames of temporal accumulation
              (AO alone in a scene with an environment takes two layers by
              default, README "AO alone takes two layers in the open");
  one layer   --aov ao --depth-layers 1 --no-interleave --slices 8
              --samples 128: the
              full-resolution kernel with 4x the slices and samples a
              side: the horizon over the depth buffer as a height field (each
              pixel's surface taken as infinitely thick), as closely as the
              kernel gets to it; what any estimator that reads one depth
              layer converges to;
  hbil three layers  --aov ao --frames N --depth-layers 3: HBIL as a frame
              gives it over three depth layers (its kernel the visibility
              bitmask below at the default 2 slices x 32 samples, the 4x4
              sub-images' angles, filter and temporal accumulation);
  three layers --technique ssilvb --depth-layers 3 --slices 8 --samples
              128: the visibility bitmask over the depth buffer, the nearest
              back face behind it and the surface behind that (the
              rasterizer's further layers, raster.h): each sample solid from
              its front to its back face, open behind it, solid again from
              the next surface on; what the hidden surfaces cost one layer;
  depth       --aov depth: the geometry mask (depth 0 is sky).

The layered columns are compared with the reference at their own radius
(`--explain` prints it; a second reference run where it differs: until
this round's thirteenth session AO over further layers got a longer
radius, now AO alone has the same over any number of layers).

and reports over the geometry pixels the RMSE and the mean difference
(bias) of hbil, of one layer, of hbil over three layers and of three
layers against the reference.
What one layer misses, hbil misses too: hidden surfaces (the floor under a
sphere, the far side of a column) and surfaces off the screen (the room's
walls between the camera and the image's edge).  The rest, hbil against one
layer, is the interleaved kernel's own error.  Three layers give back the
hidden surfaces; the surfaces off the screen stay missing.

Results: OUT/screen-limits.md (the table) and OUT/screen-limits.png: a row
per scene of reference | hbil | one layer | hbil three layers | three layers
| hbil - reference | one layer - reference | hbil three layers - reference
| three layers - reference, the differences red
where brighter (less occluded) than the reference and blue where darker,
full colour at +-0.25.
"""
import argparse
import math
import os
import struct
import subprocess
import sys
import zlib

DIFF_FULL_SCALE = 0.25


def read_pfm(path):
    """One-channel PFM -> (w, h, rows top to bottom)."""
    with open(path, "rb") as f:
        data = f.read()
    kind, dims, scale, body = data.split(b"\n", 3)
    if kind != b"Pf":
        sys.exit("screen_limits: %s: expected a one-channel PFM" % path)
    w, h = map(int, dims.split())
    order = "<" if float(scale) < 0 else ">"
    v = struct.unpack(order + "%df" % (w * h), body[:4 * w * h])
    rows = [list(v[y * w:(y + 1) * w]) for y in range(h)]
    rows.reverse()   # PFM rows run bottom to top
    return w, h, rows


def write_png(path, w, h, rgb_rows):
    """8-bit RGB PNG from rows of (r, g, b) byte triples."""
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rgb_rows)

    def chunk(tag, body):
        return struct.pack(">I", len(body)) + tag + body + struct.pack(">I", zlib.crc32(tag + body) & 0xffffffff)
    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, path)


def grey(v):
    c = int(round(255 * max(0.0, min(1.0, v))))
    return (c, c, c)


def signed(d):
    """red: brighter than the reference, blue: darker; full at DIFF_FULL_SCALE."""
    t = max(-1.0, min(1.0, d / DIFF_FULL_SCALE))
    c = int(round(255 * abs(t)))
    return (c, 0, 0) if t > 0 else (0, 0, c)


def error(a, ref, depth):
    se = bias = 0.0
    n = 0
    for ra, rr, rd in zip(a, ref, depth):
        for x, y, z in zip(ra, rr, rd):
            if z <= 0:
                continue
            se += (x - y) ** 2
            bias += x - y
            n += 1
    return (math.sqrt(se / n), bias / n) if n else (0.0, 0.0)


def gather_radius(exe, scene, size, extra):
    """The radius the plan takes (`--explain`'s 'gather radius R')."""
    cmd = [exe, "render", "builtin:" + scene, "--size", size, "--explain"] + extra
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    for line in r.stdout.splitlines():
        if line.startswith("gather radius "):
            return line.split()[2]
    sys.exit("screen_limits: %s: no gather radius in the plan" % " ".join(cmd))


def render(exe, scene, size, out, extra):
    cmd = [exe, "render", "builtin:" + scene, "--size", size, "-o", out] + extra
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    if r.returncode != 0:
        sys.exit("screen_limits: %s failed: %s" % (" ".join(cmd), r.stderr.strip()))
    return " ".join(cmd)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--scenes", default="spheres,columns,cornell")
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--frames", type=int, default=8)
    ap.add_argument("--out", default=os.path.join("build", "screen-limits"))
    args = ap.parse_args()
    exe = os.path.join(args.build, "tinygi")
    if not os.access(exe, os.X_OK):
        sys.exit("screen_limits: %s: not built (make first)" % exe)
    os.makedirs(args.out, exist_ok=True)
    runs = {
        "reference": ["--technique", "reference", "--aov", "ao"],
        "hbil": ["--aov", "ao", "--frames", str(args.frames), "--depth-layers", "1"],
        "one layer": ["--aov", "ao", "--depth-layers", "1", "--no-interleave", "--slices", "8", "--samples", "128"],
        "hbil three layers": ["--aov", "ao", "--frames", str(args.frames), "--depth-layers", "3"],
        "three layers": ["--aov", "ao", "--technique", "ssilvb", "--depth-layers", "3", "--slices", "8",
                         "--samples", "128"],
        "depth": ["--aov", "depth"],
    }
    table = ["| scene | radius: one layer / three | hbil: RMSE / bias | one layer: RMSE / bias "
             "| hbil against one layer: RMSE | hbil, three layers: RMSE / bias | three layers: RMSE / bias |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    sheet = []
    for scene in args.scenes.split(","):
        img = {}
        r1 = gather_radius(exe, scene, args.size, ["--aov", "ao", "--depth-layers", "1"])
        r3 = gather_radius(exe, scene, args.size, ["--aov", "ao", "--depth-layers", "3"])
        runs["reference, layers"] = ["--technique", "reference", "--aov", "ao", "--radius", r3]
        for name, extra in runs.items():
            path = os.path.join(args.out, "%s-%s.pfm" % (scene, name.replace(" ", "-")))
            render(exe, scene, args.size, path, extra)
            img[name] = read_pfm(path)
        w, h = img["depth"][0], img["depth"][1]
        ref, hb, one, dep = img["reference"][2], img["hbil"][2], img["one layer"][2], img["depth"][2]
        three, hb3, ref3 = img["three layers"][2], img["hbil three layers"][2], img["reference, layers"][2]
        e_h, e_o, e_ho = error(hb, ref, dep), error(one, ref, dep), error(hb, one, dep)
        e_3, e_h3 = error(three, ref3, dep), error(hb3, ref3, dep)
        table.append("| %s %s | %s / %s | %.3f / %+.3f | %.3f / %+.3f | %.3f | %.3f / %+.3f | %.3f / %+.3f |"
                     % (scene, args.size, r1, r3, e_h[0], e_h[1], e_o[0], e_o[1], e_ho[0], e_h3[0], e_h3[1], e_3[0],
                        e_3[1]))
        print("%-8s hbil %.3f / %+.3f   one layer %.3f / %+.3f   hbil vs one layer %.3f   hbil three layers "
              "%.3f / %+.3f   three layers %.3f / %+.3f"
              % (scene, e_h[0], e_h[1], e_o[0], e_o[1], e_ho[0], e_h3[0], e_h3[1], e_3[0], e_3[1]))
        gap = [(255, 255, 255)] * 4
        for y in range(h):
            row = []
            for panel in (ref, hb, one, hb3, three):
                row += [grey(v) if d > 0 else (40, 40, 40) for v, d in zip(panel[y], dep[y])] + gap
            for panel, against in ((hb, ref), (one, ref), (hb3, ref3), (three, ref3)):
                row += [signed(v - r) if d > 0 else (40, 40, 40) for v, r, d in zip(panel[y], against[y], dep[y])] + gap
            sheet.append(row[:-4])
        sheet += [[(255, 255, 255)] * (9 * w + 32)] * 4
    sheet = sheet[:-4]
    write_png(os.path.join(args.out, "screen-limits.png"), len(sheet[0]), len(sheet), sheet)
    md = ["# What screen space cannot see", "",
          "`python3 tools/screen_limits.py --size %s --frames %d` (AO against `--technique reference`, "
          "over geometry pixels; hbil: `--depth-layers 1`; one layer: `--depth-layers 1 --no-interleave --slices 8 "
          "--samples 128`; hbil, three layers: "
          "`--frames %d --depth-layers 3`; three layers: `--technique ssilvb --depth-layers 3 --slices 8 "
          "--samples 128`; the layered columns against the reference at their own radius)."
          % (args.size, args.frames, args.frames),
          ""] + table
    with open(os.path.join(args.out, "screen-limits.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("screen_limits: wrote %s/screen-limits.md and screen-limits.png" % args.out)


if __name__ == "__main__":
    main()
