#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench_cost.py - the accuracy bench's configurations in instructions per
pixel (callgrind: the count does not depend on the machine's load).

    python3 tools/bench_cost.py [--build build] [--size 160x120]
        [--scenes a,b] [--types float,fixed] [--jobs 2] [--out build/bench]

For every built-in scene (or those of --scenes) and number type it runs

    valgrind --tool=callgrind --collect-atstart=no --toggle-collect=count_frame
             --dump-after=count_frame BUILD/bench-TYPE count --size WxH --scenes SCENE

`bench count` (tools/bench.c) sets up each configuration on the accuracy
bench's curves exactly as `bench run` times it (the same request, the same
first frame before it), prints its line and renders the timed frame once in
count_frame: callgrind counts that call alone and dumps it, so the k-th dump
is the k-th line's frame.  Writes OUT/cost-<type>.csv (scene, technique,
slices, samples, number, pixels, instructions of the frame); `bench report`
then adds instructions per pixel to bench.md and draws bench-cost.svg (AO
RMSE against instructions per pixel).
"""
import argparse
import concurrent.futures
import csv
import glob
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_count import Profile  # noqa: E402  (the callgrind reading, tested by its --self-test)

HEADER = ["scene", "technique", "slices", "samples", "number", "pixels", "instructions"]


def builtin_scenes(build):
    """The built-in scenes, as `tinygi list` names them (builtin:NAME ...)."""
    r = subprocess.run([os.path.join(build, "tinygi"), "list"], stdout=subprocess.PIPE, text=True, check=True)
    for line in r.stdout.splitlines():
        if line.startswith("built-in scenes:"):
            return [w[len("builtin:"):] for w in line.split()[2:] if w.startswith("builtin:")]
    sys.exit("bench_cost.py: `tinygi list` names no built-in scenes")


def count_scene(build, ntype, scene, size):
    """[(label fields..., instructions)] of one scene's configurations."""
    binary = os.path.join(build, "bench-" + ntype)
    with tempfile.TemporaryDirectory(prefix="bench-cost-") as tmp:
        out = os.path.join(tmp, "cg.out")
        cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, "--collect-atstart=no",
               "--toggle-collect=count_frame", "--dump-after=count_frame",
               binary, "count", "--size", size, "--scenes", scene]
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            raise RuntimeError("%s failed (%d):\n%s" % (" ".join(cmd), r.returncode, r.stderr[-2000:]))
        labels = [line[len("count: "):].split(",") for line in r.stdout.splitlines() if line.startswith("count: ")]
        dumps = sorted(glob.glob(out + ".*"), key=lambda p: int(p.rsplit(".", 1)[1]))
        profiles = [Profile(p) for p in dumps]
        if len(profiles) != len(labels) or any("dump-after" not in p.trigger for p in profiles):
            raise RuntimeError("%s: %d configurations but %d dumps after count_frame" % (scene, len(labels), len(profiles)))
        return [fields + [str(p.total)] for fields, p in zip(labels, profiles)]


def main():
    ap = argparse.ArgumentParser(description="the accuracy bench's configurations in instructions (callgrind)")
    ap.add_argument("--build", default="build")
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--scenes", default="", help="default: every built-in scene")
    ap.add_argument("--types", default="float,fixed")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default="build/bench")
    args = ap.parse_args()
    scenes = [s for s in args.scenes.replace(" ", ",").split(",") if s] or builtin_scenes(args.build)
    types = [t for t in args.types.replace(" ", ",").split(",") if t]
    for t in types:
        if t not in ("float", "fixed"):
            sys.exit("bench_cost.py: type must be float or fixed, got '%s'" % t)
    os.makedirs(args.out, exist_ok=True)
    jobs = [(t, s) for t in types for s in scenes]
    rows = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as ex:
        futs = {ex.submit(count_scene, args.build, t, s, args.size): (t, s) for t, s in jobs}
        for fut in concurrent.futures.as_completed(futs):
            t, s = futs[fut]
            rows[(t, s)] = fut.result()
            print("bench-cost: %s %s: %d configurations" % (s, t, len(rows[(t, s)])), flush=True)
    for t in types:
        path = os.path.join(args.out, "cost-%s.csv" % t)
        with open(path + ".new", "w", newline="") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(HEADER)
            for s in scenes:
                for r in rows[(t, s)]:
                    w.writerow(r)
        os.replace(path + ".new", path)
        print("bench-cost: wrote %s" % path)


if __name__ == "__main__":
    main()
