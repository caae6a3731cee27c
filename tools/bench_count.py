#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench_count.py - what a frame costs in instructions (callgrind), per frame,
per pixel and per pass.  The count does not depend on the machine's load: the
same binary, scene and options give the same numbers on every run.

    python3 tools/bench_count.py [--build build] [--scenes cornell,columns]
        [--types float,fixed] [--modes default,quarter] [--size 320x240]
        [--frames 10] [--jobs 2] [--out build/bench-count]

For every scene x number type x mode it runs

    valgrind --tool=callgrind --dump-before=tg_frame_render --dump-after=tg_frame_render
             BUILD/tinygi[-fixed] render builtin:SCENE --size WxH --frames N --threads 1 [--gi-quarter]

so callgrind writes one profile per call of tg_frame_render (one frame),
one for what comes before the first (start-up, scene, plan) and one for
what follows the last (the output image).  From those it reports, per
configuration:

  * mean frame: all N frames' instructions / N (what the frame loop costs
    on average, including the first frame's extra work: shadow maps, the
    cut with no history);
  * steady frame: the mean of frames 1..N-1 (every frame after the first);
  * first frame: frame 0 alone;
  * setup: everything before the first frame (process start, built-in
    scene, plan, arena);
  * output: tonemap + sRGB conversion of the one written image
    (tg_frame_aov_row8 inclusive; file writing and exit are not counted);
  * per pass, per pixel (instructions / (W x H), full-resolution pixels even
    for quarter-resolution stages): the inclusive cost of each pass's
    function in the steady frames.

Passes are found automatically: every function named tgi_pass_<name> is a
pass (its inclusive cost).  When the binary has none, the table LEGACY_PASSES
below maps today's functions to passes; delete it once the pass table lands.
Whatever the passes do not cover is reported as "(rest)", so the rows always
add up to the frame.

Results: OUT/count.md (Markdown tables) and OUT/count.csv.
"""
import argparse
import concurrent.futures
import csv
import fnmatch
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

# ---- callgrind profile parsing ------------------------------------------

_SUFFIX = re.compile(r"(\.(part|isra|constprop|cold|lto_priv)(\.\d+)?)+$")
_ABI = re.compile(r"^(tgi?_\w+)_(f32|q16)$")  # symbols carry the number type (TG_ABI: tinygi.h, core/abi_names.h)


def base_name(fn):
    """gcc's clones (foo.part.0, foo.isra.0, foo.cold) count as foo."""
    return _ABI.sub(r"\1", _SUFFIX.sub("", fn))


class Profile:
    """One callgrind dump: self cost and outgoing call costs per function."""

    def __init__(self, path):
        self.total = 0
        self.trigger = ""
        self.fn_ids = {}        # fn -> callgrind's number for it (grows in order of first execution)
        self.self_cost = {}     # fn -> Ir
        self.calls = {}         # (caller, callee) -> [Ir inclusive, count]
        self._parse(path)

    def _parse(self, path):
        names = {}
        fn = None
        cfn = None
        pending_call = 0        # the next cost line is a call's inclusive cost
        call_count = 0

        def name_of(value):
            m = re.match(r"\((\d+)\)(?:\s+(.*))?$", value)
            if not m:
                return value
            if m.group(2) is not None:
                names[m.group(1)] = m.group(2)
                self.fn_ids.setdefault(base_name(m.group(2)), int(m.group(1)))
            return names.get(m.group(1), "?" + m.group(1))

        with open(path, encoding="utf-8", errors="replace") as fh:
            for line in fh:
                line = line.rstrip("\n")
                if not line:
                    continue
                c = line[0]
                if c.isdigit() or c in "+-*":
                    parts = line.split()
                    ir = int(parts[1]) if len(parts) > 1 else 0
                    if pending_call:
                        key = (fn, cfn)
                        acc = self.calls.setdefault(key, [0, 0])
                        acc[0] += ir
                        acc[1] += call_count
                        pending_call = 0
                    else:
                        self.self_cost[fn] = self.self_cost.get(fn, 0) + ir
                    continue
                if line.startswith("fn="):
                    fn = base_name(name_of(line[3:]))
                elif line.startswith("cfn="):
                    cfn = base_name(name_of(line[4:]))
                elif line.startswith("calls="):
                    call_count = int(line[6:].split()[0])
                    pending_call = 1
                elif line.startswith("desc: Trigger:"):
                    self.trigger = line.split(":", 2)[2].strip()
                elif line.startswith("totals:") or line.startswith("summary:"):
                    self.total = int(line.split(":", 1)[1].split()[0])

    def functions(self):
        fns = set(self.self_cost)
        for caller, callee in self.calls:
            fns.add(caller)
            fns.add(callee)
        return fns

    def inclusive(self, fn):
        """Self cost plus the cost of every call it makes (recursive calls
        to itself are already in its self cost)."""
        cost = self.self_cost.get(fn, 0)
        for (caller, callee), (ir, _) in self.calls.items():
            if caller == fn and callee != fn:
                cost += ir
        return cost

    def call_cost(self, caller, callee_pattern):
        return sum(ir for (a, b), (ir, _) in self.calls.items()
                   if a == caller and fnmatch.fnmatch(b, callee_pattern))

    def calls_to(self, fn):
        return sum(n for (_, b), (_, n) in self.calls.items() if b == fn)


# ---- passes ----------------------------------------------------------------

# Today's functions, pass by pass, in frame order (src/frame/frame.c and
# src/frame/technique.c).  Each entry is a function (its inclusive cost) or
# "caller>callee-glob" (only that caller's calls to it).  The functions must
# not call one another, or their costs would be counted twice.
# Delete this table once the frame runs tgi_pass_* functions.
LEGACY_PASSES = [
    ("animate", ["tgi_anim_time", "tgi_view_make", "tgi_anim_camera", "tgi_anim_pose",
                 "tgi_anim_object_delta"]),
    ("gbuffer clear", ["tgi_gbuffer_clear_rows"]),
    ("raster", ["tgi_raster_gbuffer"]),
    ("motion vectors", ["tgi_motion_rows"]),
    ("shadow maps", ["tgi_shadow_map_render", "tgi_shadow_map_setup", "tgi_anim_bounds"]),
    ("direct light", ["tgi_direct_rows"]),
    ("reproject", ["tgi_reproject_scatter"]),
    ("push/pull", ["tgi_pushpull_fill"]),
    ("downsample", ["tgi_downsample_rows", "tgi_downsample8_rows"]),
    ("split", ["tgi_interleave_split", "tgi_interleave_split8"]),
    ("hbil kernel", ["tgi_hbil_rows"]),
    ("merge", ["tgi_interleave_merge"]),
    ("filter", ["tgi_denoise_begin", "tgi_denoise_rows"]),
    ("upsample", ["tgi_upsample_rows"]),
    ("temporal", ["tgi_temporal_rows"]),
    ("cone from AO", ["tgi_frame_technique>tg_acos"]),
    ("far field", ["tgi_far_rows"]),
    ("compose", ["tgi_compose_rows"]),
    ("keep history", ["tg_frame_render>*mem*"]),
]

PASS_PREFIX = "tgi_pass_"
NOT_PASSES = {"tgi_pass_row_count"}     # the pass runner's helpers that share the prefix


def discovered_passes(profiles):
    """tgi_pass_<name> functions, in the order they first ran (callgrind
    numbers functions as it meets them)."""
    first = {}
    for p in profiles:
        for fn in p.functions():
            if fn.startswith(PASS_PREFIX) and fn not in NOT_PASSES:
                first[fn] = min(first.get(fn, 1 << 60), p.fn_ids.get(fn, 1 << 59))
    order = sorted(first, key=lambda fn: (first[fn], fn))
    return [(fn[len(PASS_PREFIX):], [fn]) for fn in order]


def entry_cost(profile, entry):
    if ">" in entry:
        caller, callee = entry.split(">", 1)
        return profile.call_cost(caller, callee)
    return profile.inclusive(entry)


def pass_costs(profile, passes):
    """[(pass, Ir)] plus "(rest)" so the rows add up to the profile total."""
    rows = [(name, sum(entry_cost(profile, e) for e in entries)) for name, entries in passes]
    rest = profile.total - sum(ir for _, ir in rows)
    return rows + [("(rest)", rest)]


# ---- running callgrind ------------------------------------------------------

def run_config(binary, scene, size, frames, quarter, workdir, render_fn="tg_frame_render"):
    """Profiles of every frame (index order), of the setup before the first
    and of what follows the last (the output image).  render_fn: the
    symbol of tg_frame_render (TG_ABI in tinygi.h names it per number type)."""
    out = os.path.join(workdir, "cg.out")
    img = os.path.join(workdir, "out.ppm")
    cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out,
           "--dump-before=" + render_fn, "--dump-after=" + render_fn,
           binary, "render", "builtin:" + scene, "--size", size,
           "--frames", str(frames), "--threads", "1", "-o", img, "--quiet"]
    if quarter:
        cmd.append("--gi-quarter")
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d):\n%s" % (" ".join(cmd), r.returncode, r.stderr[-2000:]))
    dumps = sorted(glob.glob(out + ".*"), key=lambda p: int(p.rsplit(".", 1)[1]))
    profiles = [Profile(p) for p in dumps]
    per_frame = [p for p in profiles if "dump-after" in p.trigger]
    if len(per_frame) != frames or not profiles or "dump-before" not in profiles[0].trigger:
        raise RuntimeError("expected %d per-frame dumps from callgrind, got %d" % (frames, len(per_frame)))
    return per_frame, profiles[0], Profile(out)


def measure(args, scene, ntype, mode):
    binary = os.path.join(args.build, "tinygi" if ntype == "float" else "tinygi-fixed")
    with tempfile.TemporaryDirectory(prefix="bench-count-") as tmp:
        frames, setup, final = run_config(binary, scene, args.size, args.frames, mode == "quarter", tmp,
                                          "tg_frame_render_" + ("f32" if ntype == "float" else "q16"))
    return scene, ntype, mode, frames, setup, final


# ---- report -----------------------------------------------------------------

def summarize(frames, setup, final, passes_fn):
    n = len(frames)
    steady = frames[1:] if n > 1 else frames
    passes = passes_fn(frames)
    names = [name for name, _ in passes] + ["(rest)"]
    per_pass = {name: 0 for name in names}
    for p in steady:
        for name, ir in pass_costs(p, passes):
            per_pass[name] += ir
    for name in names:
        per_pass[name] /= len(steady)
    first_pass = dict(pass_costs(frames[0], passes))
    return {
        "first_pass": first_pass,
        "frames": n,
        "mean": sum(p.total for p in frames) / n,
        "steady": sum(p.total for p in steady) / len(steady),
        "first": frames[0].total,
        "setup": setup.total,
        "output": final.inclusive("tg_frame_aov_row8"),
        "passes": names,
        "per_pass": per_pass,
    }


def warn_coverage(s, what):
    """The passes should account for the frame; if they do not, the table
    of today's functions is stale (or the tgi_pass_* functions were inlined)."""
    rest = s["per_pass"].get("(rest)", 0)
    if s["steady"] and abs(rest) > 0.05 * s["steady"]:
        print("bench_count: warning: %s: %.0f%% of the frame is in no pass; name the passes "
              "tgi_pass_* (not inlined) or update LEGACY_PASSES in %s"
              % (what, 100.0 * rest / s["steady"], os.path.relpath(__file__)), file=sys.stderr)


def fmt_m(ir):
    return "%.1fM" % (ir / 1e6)


def fmt_px(ir):
    return "%.0f" % ir


def passes_for(frames):
    found = discovered_passes(frames)
    return found if found else LEGACY_PASSES


def write_reports(args, results, outdir, header):
    w, h = (int(v) for v in args.size.split("x"))
    px = w * h
    os.makedirs(outdir, exist_ok=True)
    csv_path = os.path.join(outdir, "count.csv")
    md_path = os.path.join(outdir, "count.md")
    with open(csv_path + ".tmp", "w", newline="") as fh:
        cw = csv.writer(fh)
        cw.writerow(["scene", "type", "mode", "size", "frames", "row", "ir_per_frame", "ir_per_pixel"])
        for (scene, ntype, mode), s in results.items():
            for row in ("mean", "steady", "first", "setup", "output"):
                cw.writerow([scene, ntype, mode, args.size, s["frames"], "frame:" + row,
                             "%.0f" % s[row], "%.1f" % (s[row] / px)])
            for name in s["passes"]:
                ir = s["per_pass"][name]
                cw.writerow([scene, ntype, mode, args.size, s["frames"], "pass:" + name,
                             "%.0f" % ir, "%.1f" % (ir / px)])
            for name in s["passes"]:
                ir = s["first_pass"].get(name, 0)
                cw.writerow([scene, ntype, mode, args.size, s["frames"], "first-frame pass:" + name,
                             "%.0f" % ir, "%.1f" % (ir / px)])
    os.replace(csv_path + ".tmp", csv_path)

    lines = [header, ""]
    lines.append("Instructions per frame (callgrind Ir; M = 10^6). mean = all %d frames / %d; "
                 "steady = frames 1..%d; first = frame 0; setup = before frame 0 (start-up, scene, "
                 "plan); output = tonemap + sRGB of the written image (outside the frame)." % (args.frames, args.frames, args.frames - 1))
    lines.append("")
    lines.append("| scene | mode | type | mean frame | steady frame | first frame | per pixel (steady) "
                 "| setup | output | Q16.16 / float (steady) |")
    lines.append("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for scene in args.scenes:
        for mode in args.modes:
            for ntype in args.types:
                s = results.get((scene, ntype, mode))
                if not s:
                    continue
                ratio = ""
                fl, fx = results.get((scene, "float", mode)), results.get((scene, "fixed", mode))
                if ntype == "fixed" and fl and fx:
                    ratio = "%.2fx" % (fx["steady"] / fl["steady"])
                lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    scene, mode, ntype, fmt_m(s["mean"]), fmt_m(s["steady"]), fmt_m(s["first"]),
                    fmt_px(s["steady"] / px), fmt_m(s["setup"]), fmt_m(s["output"]), ratio))
    lines.append("")
    for scene in args.scenes:
        cols = [(ntype, mode) for mode in args.modes for ntype in args.types
                if (scene, ntype, mode) in results]
        if not cols:
            continue
        names = []
        for c in cols:
            for name in results[(scene,) + c]["passes"]:
                if name not in names:
                    names.append(name)
        if "(rest)" in names:       # the rest always last
            names.remove("(rest)")
            names.append("(rest)")
        lines.append("**%s**, instructions per pixel per pass (steady frame, %s = %d pixels):"
                     % (scene, args.size, px))
        lines.append("")
        lines.append("| pass | " + " | ".join("%s %s" % (t, m) for t, m in cols) + " |")
        lines.append("| --- |" + " ---: |" * len(cols))
        totals = [0.0] * len(cols)
        for name in names:
            vals = []
            for k, c in enumerate(cols):
                ir = results[(scene,) + c]["per_pass"].get(name, 0)
                totals[k] += ir
                vals.append(fmt_px(ir / px))
            if all(v == "0" for v in vals):
                continue
            lines.append("| %s | %s |" % (name, " | ".join(vals)))
        lines.append("| **frame** | %s |" % " | ".join("**%s**" % fmt_px(t / px) for t in totals))
        lines.append("")
        extra = []
        for name in names:
            d = [(results[(scene,) + c]["first_pass"].get(name, 0) - results[(scene,) + c]["per_pass"].get(name, 0))
                 / px for c in cols]
            if any(abs(v) >= 5 for v in d):
                extra.append("%s %s" % (name, " / ".join("%+.0f" % v for v in d)))
        if extra:
            lines.append("Frame 0 differs (per pixel, same columns): " + "; ".join(extra) + ".")
            lines.append("")
    with open(md_path + ".tmp", "w") as fh:
        fh.write("\n".join(lines))
    os.replace(md_path + ".tmp", md_path)
    return md_path, csv_path


def describe_source(build):
    tree = os.path.dirname(os.path.abspath(build))  # the checkout the build directory belongs to
    try:
        rev = subprocess.run(["git", "rev-parse", "--short=12", "HEAD"], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, text=True, cwd=tree).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], stdout=subprocess.PIPE,
                               stderr=subprocess.DEVNULL, text=True, cwd=tree).stdout.strip()
    except OSError:
        rev, dirty = "", ""
    cc = subprocess.run([os.environ.get("CC", "cc"), "--version"], stdout=subprocess.PIPE,
                        stderr=subprocess.DEVNULL, text=True).stdout.split("\n")[0]
    vg = subprocess.run(["valgrind", "--version"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                        text=True).stdout.strip() if shutil.which("valgrind") else "no valgrind"
    return "commit %s%s, %s, %s, binaries in %s/" % (
        rev or "?", " (with uncommitted changes)" if dirty else "", cc, vg, build)


SELF_TEST_C = r"""
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
static volatile unsigned sink;
static void __attribute__((noinline)) spin(unsigned n) { unsigned i; for (i = 0; i < n; i++) sink += i; }
/* the library's internal symbols carry the number type (core/abi_names.h) */
void __attribute__((noinline)) tgi_pass_alpha_q16(int i) { spin(i == 0 ? 50000 : 10000); }
void __attribute__((noinline)) tgi_pass_beta_q16(void) { spin(30000); }
void __attribute__((noinline)) tg_frame_render(int i) { tgi_pass_alpha_q16(i); tgi_pass_beta_q16(); spin(1000); }
void __attribute__((noinline)) tg_frame_aov_row8(void) { spin(7000); }
int main(int argc, char **argv)
{
    int i, frames = 1;
    for (i = 1; i + 1 < argc; i++) if (!strcmp(argv[i], "--frames")) frames = atoi(argv[i + 1]);
    spin(20000);
    for (i = 0; i < frames; i++) tg_frame_render(i);
    tg_frame_aov_row8();
    return 0;
}
"""


def self_test():
    """A fake renderer with two tgi_pass_* functions: the passes must be
    found, and their per-frame costs must be in the ratio the program sets."""
    with tempfile.TemporaryDirectory(prefix="bench-count-test-") as tmp:
        src = os.path.join(tmp, "fake.c")
        with open(src, "w") as fh:
            fh.write(SELF_TEST_C)
        subprocess.run([os.environ.get("CC", "cc"), "-O1", src, "-o", os.path.join(tmp, "tinygi")], check=True)
        frames, setup, final = run_config(os.path.join(tmp, "tinygi"), "x", "4x4", 3, False, tmp)
        s = summarize(frames, setup, final, passes_for)
        p = dict(alpha=0, beta=1, **{"(rest)": 0})
        p.update(s["per_pass"])
        p["beta"] = p["beta"] or 1
        p["alpha"] = p["alpha"] or 1
        checks = [
            ("passes found", s["passes"] == ["alpha", "beta", "(rest)"]),
            ("alpha:beta = 1:3 in steady frames", abs(p["alpha"] * 3 / p["beta"] - 1) < 0.01),
            ("frame 0 alpha 5x steady", abs(s["first_pass"].get("alpha", 0) / p["alpha"] / 5 - 1) < 0.01),
            ("rest small", 0 < p["(rest)"] < 0.05 * s["steady"]),
            ("rows add up", abs(sum(p.values()) - s["steady"]) < 1),
            ("output counted", abs(s["output"] / p["beta"] * 30000 / 7000 - 1) < 0.02),
            ("setup before frame 0", s["setup"] > 20000 * 2),
        ]
    bad = [name for name, ok in checks if not ok]
    for name, ok in checks:
        print("  %s %s" % ("ok  " if ok else "FAIL", name))
    print("bench_count self-test: %s" % ("passed" if not bad else "FAILED"))
    return 1 if bad else 0


def split_list(v):
    return [x for x in re.split(r"[,\s]+", v) if x]


def add_frame_options(ap, scenes):
    """The options naming the frames to run (bench_count and bench_time frame)."""
    ap.add_argument("--build", default="build")
    ap.add_argument("--scenes", default=scenes, help="comma list, or 'all'")
    ap.add_argument("--types", default="float,fixed")
    ap.add_argument("--modes", default="default,quarter")
    ap.add_argument("--size", default="320x240")
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--out", default=None)


def check_frame_options(args, prog):
    """Lists from the options; exits with a message on a bad value."""
    args.scenes = split_list(args.scenes)
    if args.scenes == ["all"]:
        args.scenes = ["plane", "groove", "cornell", "spheres", "columns"]
    args.types = split_list(args.types)
    args.modes = split_list(args.modes)
    for t in args.types:
        if t not in ("float", "fixed"):
            sys.exit("%s: type must be float or fixed, got '%s'" % (prog, t))
    for m in args.modes:
        if m not in ("default", "quarter"):
            sys.exit("%s: mode must be default or quarter, got '%s'" % (prog, m))
    if not re.match(r"^\d+x\d+$", args.size):
        sys.exit("%s: --size: expected WxH, got '%s'" % (prog, args.size))
    if args.frames < 1:
        sys.exit("%s: --frames must be at least 1" % prog)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    add_frame_options(ap, "cornell,columns")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--self-test", action="store_true",
                    help="check the callgrind reading and pass discovery on a small fake program")
    args = ap.parse_args()
    if args.self_test:
        sys.exit(self_test())
    check_frame_options(args, "bench_count")
    if args.frames < 2:
        sys.exit("bench_count: --frames must be at least 2 (frame 0 and a steady frame)")
    if not shutil.which("valgrind"):
        sys.exit("bench_count: valgrind not found (make bench-count installs it)")
    out = args.out or os.path.join(args.build, "bench-count")
    header = "# make bench-count\n\n%s; %s, %d frames, scenes %s." % (
        describe_source(args.build), args.size, args.frames, ", ".join(args.scenes))
    print(header.replace("# ", "", 1), flush=True)

    jobs = [(s, t, m) for s in args.scenes for m in args.modes for t in args.types]
    results = {}
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, min(args.jobs, 2))) as pool:
        futs = {pool.submit(measure, args, *j): j for j in jobs}
        for fut in concurrent.futures.as_completed(futs):
            scene, ntype, mode, frames, setup, final = fut.result()
            results[(scene, ntype, mode)] = summarize(frames, setup, final, passes_for)
            s = results[(scene, ntype, mode)]
            print("  %-8s %-5s %-7s mean %8s  steady %8s  first %8s" % (
                scene, ntype, mode, fmt_m(s["mean"]), fmt_m(s["steady"]), fmt_m(s["first"])), flush=True)
            warn_coverage(s, "%s %s %s" % (scene, ntype, mode))
    md, cs = write_reports(args, results, out, header)
    print()
    print(open(md).read())
    print("\nwrote %s and %s" % (md, cs))


if __name__ == "__main__":
    main()
