#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""bench_time.py - timed benchmarks whose numbers can be reproduced: every
configuration runs once per round, the configurations interleaved (round
robin, the starting one rotating each round, so a burst of load elsewhere
falls on all of them alike), several rounds; the report gives the median
and the min..max of CPU time and of wall time, with the load average
(/proc/loadavg) at the start and at the end.

    python3 tools/bench_time.py frame  [--build build] [--scenes all] [--types float,fixed]
                                       [--modes default,quarter] [--size 320x240]
                                       [--frames 10] [--rounds 5] [--threads 1,2]
    python3 tools/bench_time.py raster [--build build] [--sizes 320x240,1280x720]
                                       [--frames 20] [--rounds 7] [--peer CMD]... [--no-count]

frame: whole frames through the CLI, `tinygi[-fixed] render builtin:SCENE
--size WxH --frames N --threads T [--gi-quarter]`; CPU time is the child's
user + system time (wait4, all its threads), wall time its elapsed time,
both divided by N (they include the start-up and the one written image,
under 2% of a 10-frame run by `make bench-count`).  With several thread
counts (--threads 1,2) a second table gives each one's speed-up over the
first in wall time: the median of the rounds' ratios (each round runs both
under the same load) and the ratio of the medians.

raster: tools/bench_raster.c (float and Q16.16), and any --peer programs,
on the 49,728-triangle sphere.  A program is run as `CMD WxH --frames N`
({size}, {w} and {h} in CMD are replaced first) and prints one line
`NAME WxH tris=T frames=N draw_cpu_ms=.. draw_wall_ms=.. clear_cpu_ms=..
clear_wall_ms=.. covered=..` (per-frame means of its N frames).  Mtri/s is
T / median draw CPU time.  Unless --no-count, each program is also run once
under callgrind and its functions bench_draw / bench_clear give the
instructions of one frame (inclusive cost / calls).

Results go to BUILD/bench-frame/ and BUILD/bench-raster/ (time.md, time.csv).
"""
import argparse
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_count  # noqa: E402  (the callgrind profile reader)


def loadavg():
    try:
        with open("/proc/loadavg") as fh:
            return " ".join(fh.read().split()[:3])
    except OSError:
        return "unknown"


def split_list(v):
    return [x for x in re.split(r"[,\s]+", v) if x]


def med_range(values, fmt="%.2f"):
    return (fmt + " (" + fmt + ".." + fmt + ")") % (statistics.median(values), min(values), max(values))


def run_rounds(configs, rounds, run_one, label):
    """run_one(config) -> dict of samples; returns {config index: [dict, ...]}."""
    samples = {i: [] for i in range(len(configs))}
    for r in range(rounds):
        order = list(range(len(configs)))
        k = r % len(order)
        order = order[k:] + order[:k]
        for i in order:
            samples[i].append(run_one(configs[i]))
        print("  round %d/%d done (load %s)" % (r + 1, rounds, loadavg()), flush=True)
    return samples


def write_atomic(path, text):
    with open(path + ".tmp", "w", newline="") as fh:
        fh.write(text)
    os.replace(path + ".tmp", path)


def csv_text(header, rows):
    import io
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(header)
    w.writerows(rows)
    return buf.getvalue()


# ---- frame ------------------------------------------------------------------

def speedup_lines(configs, samples, threads, key="wall", what="wall time"):
    """Speed-up in samples[key] of each thread count over the first, per scene, mode and type."""
    if len(threads) < 2:
        return []
    lines = ["", "Speed-up in %s over %s thread%s: median of the per-round ratios (ratio of "
             "the medians)." % (what, threads[0], "" if threads[0] == "1" else "s"), "",
             "| scene | mode | type | " + " | ".join("%s threads" % n for n in threads[1:]) + " |",
             "| --- | --- | --- | " + " | ".join("---:" for _ in threads[1:]) + " |"]
    index = {cfg: i for i, cfg in enumerate(configs)}
    for cfg in configs:
        if cfg[3] != threads[0]:
            continue
        base = [s[key] for s in samples[index[cfg]]]
        cells = []
        for n in threads[1:]:
            other = [s[key] for s in samples[index[cfg[:3] + (n,)]]]
            ratios = [b / o for b, o in zip(base, other) if o > 0]
            cells.append("%.2fx (%.2fx)" % (statistics.median(ratios),
                                            statistics.median(base) / statistics.median(other)))
        lines.append("| %s | %s | %s | %s |" % (cfg[0], cfg[1], cfg[2], " | ".join(cells)))
    return lines


def baseline_lines(configs, samples, threads, baseline):
    """CPU time of this build (its first thread count) against --baseline's, per configuration."""
    if not baseline:
        return []
    lines = ["", "Against the baseline build %s (the rows with threads 'before', run with this build's first "
             "thread count, or its default when it has no --threads): "
             "%s; CPU time this build / baseline, median of the per-round ratios (ratio of the medians)."
             % (baseline, bench_count.describe_source(baseline)), "",
             "| scene | mode | type | baseline CPU ms/frame | this CPU ms/frame | ratio |",
             "| --- | --- | --- | ---: | ---: | ---: |"]
    index = {cfg: i for i, cfg in enumerate(configs)}
    for cfg in configs:
        if cfg[3] != "before":
            continue
        old = [s["cpu"] for s in samples[index[cfg]]]
        new = [s["cpu"] for s in samples[index[cfg[:3] + (threads[0],)]]]
        ratios = [n / o for n, o in zip(new, old) if o > 0]
        lines.append("| %s | %s | %s | %.1f | %.1f | %.3f (%.3f) |"
                     % (cfg[0], cfg[1], cfg[2], statistics.median(old), statistics.median(new),
                        statistics.median(ratios), statistics.median(new) / statistics.median(old)))
    return lines


def takes_threads(binary):
    """Whether the tinygi at binary has --threads (its --help says so)."""
    try:
        out = subprocess.run([binary, "--help"], capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.TimeoutExpired):
        return False
    return "--threads" in out.stdout + out.stderr


def run_timed(cmd):
    """Run cmd; (CPU seconds of the child and its threads, wall seconds)."""
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd)
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.monotonic() - t0
    code = os.waitstatus_to_exitcode(status)
    if code != 0:
        sys.exit("bench_time: %s failed (%d)" % (" ".join(cmd), code))
    return ru.ru_utime + ru.ru_stime, wall


def frame_main(args):
    bench_count.check_frame_options(args, "bench_time")
    threads = split_list(args.threads)
    if not threads or not all(re.match(r"^[1-9][0-9]*$", n) for n in threads):
        sys.exit("bench_time: --threads: expected a list of thread counts, got '%s'" % args.threads)
    configs = [(s, m, t, n) for s in args.scenes for m in args.modes for t in args.types for n in threads]
    baseline_threads = []
    if args.baseline:
        # the same configurations run by an older build, with this build's first thread count
        # when it takes --threads (else it predates them and runs one thread): CPU times of one
        # thread against two would count the pool's waiting as the change's
        configs += [(s, m, t, "before") for s in args.scenes for m in args.modes for t in args.types]
        if takes_threads(os.path.join(args.baseline, "tinygi")):
            baseline_threads = ["--threads", threads[0]]
    tmp = tempfile.mkdtemp(prefix="bench-frame-")

    def run_one(cfg):
        scene, mode, ntype, nthreads = cfg
        build = args.baseline if nthreads == "before" else args.build
        binary = os.path.join(build, "tinygi" if ntype == "float" else "tinygi-fixed")
        cmd = [binary, "render", "builtin:" + scene, "--size", args.size, "--frames", str(args.frames),
               "-o", os.path.join(tmp, "out.ppm"), "--quiet"]
        cmd += ["--threads", nthreads] if nthreads != "before" else baseline_threads
        if mode == "quarter":
            cmd.append("--gi-quarter")
        cpu, wall = run_timed(cmd)
        sample = {"cpu": cpu * 1e3 / args.frames, "wall": wall * 1e3 / args.frames}
        if args.steady and args.frames > 1:
            # the same run with one frame: what is left is the N - 1 steady frames alone
            one = list(cmd)
            one[one.index("--frames") + 1] = "1"
            cpu1, wall1 = run_timed(one)
            sample["steady_cpu"] = (cpu - cpu1) * 1e3 / (args.frames - 1)
            sample["steady_wall"] = (wall - wall1) * 1e3 / (args.frames - 1)
        return sample

    start = loadavg()
    print("bench-frame: %d configurations x %d rounds, %s, %d frames; load average at start %s"
          % (len(configs), args.rounds, args.size, args.frames, start), flush=True)
    samples = run_rounds(configs, args.rounds, run_one, "frame")
    end = loadavg()
    shutil.rmtree(tmp, ignore_errors=True)

    lines = ["# make bench-frame", "",
             "%s; %s, %d frames a run, %d rounds interleaved; load average %s at start, %s at end."
             % (bench_count.describe_source(args.build), args.size, args.frames, args.rounds, start, end), "",
             "ms per frame, median (min..max) over the rounds; CPU = user + system time of the process."
             + (" Steady: the run's time less that of the same run with --frames 1, over the N - 1 frames"
                " it leaves (no start-up, first frame or written image)." if args.steady else ""), "",
             "| scene | mode | type | threads | CPU ms/frame | wall ms/frame |"
             + (" steady CPU ms/frame | steady wall ms/frame |" if args.steady else ""),
             "| --- | --- | --- | ---: | ---: | ---: |" + (" ---: | ---: |" if args.steady else "")]
    rows = []
    for i, (scene, mode, ntype, nthreads) in enumerate(configs):
        cpu = [s["cpu"] for s in samples[i]]
        wall = [s["wall"] for s in samples[i]]
        steady = ""
        if args.steady and "steady_wall" in samples[i][0]:
            steady = " %s | %s |" % (med_range([s["steady_cpu"] for s in samples[i]], "%.1f"),
                                     med_range([s["steady_wall"] for s in samples[i]], "%.1f"))
        elif args.steady:
            steady = " - | - |"
        lines.append("| %s | %s | %s | %s | %s | %s |%s" % (scene, mode, ntype, nthreads, med_range(cpu, "%.1f"),
                                                            med_range(wall, "%.1f"), steady))
        rows.append([scene, mode, ntype, nthreads, args.size, args.frames, len(cpu),
                     "%.2f" % statistics.median(cpu), "%.2f" % min(cpu), "%.2f" % max(cpu),
                     "%.2f" % statistics.median(wall), "%.2f" % min(wall), "%.2f" % max(wall), start, end]
                    + (["%.2f" % statistics.median([s["steady_cpu"] for s in samples[i]]),
                        "%.2f" % statistics.median([s["steady_wall"] for s in samples[i]])]
                       if "steady_wall" in samples[i][0] else ["", ""]))
    lines += speedup_lines(configs, samples, threads)
    if args.steady and args.frames > 1:
        lines += speedup_lines(configs, samples, threads, "steady_wall", "the steady frames' wall time")
    lines += baseline_lines(configs, samples, threads, args.baseline)
    out = args.out or os.path.join(args.build, "bench-frame")
    os.makedirs(out, exist_ok=True)
    write_atomic(os.path.join(out, "time.md"), "\n".join(lines) + "\n")
    write_atomic(os.path.join(out, "time.csv"), csv_text(
        ["scene", "mode", "type", "threads", "size", "frames", "rounds", "cpu_ms_median", "cpu_ms_min", "cpu_ms_max",
         "wall_ms_median", "wall_ms_min", "wall_ms_max", "load_start", "load_end",
         "steady_cpu_ms_median", "steady_wall_ms_median"], rows))
    print()
    print("\n".join(lines))
    print("\nload average at end %s; wrote %s/time.md and time.csv" % (end, out))


# ---- raster -----------------------------------------------------------------

LINE = re.compile(r"^(\S+) (\d+)x(\d+) (.*)$")


def parse_line(text, cmd):
    for line in text.splitlines():
        m = LINE.match(line.strip())
        if m and "draw_cpu_ms=" in m.group(4):
            kv = dict(x.split("=", 1) for x in m.group(4).split() if "=" in x)
            return m.group(1), kv
    sys.exit("bench_time: no result line from %s:\n%s" % (cmd, text[-1000:]))


def expand(cmd, size):
    w, h = size.split("x")
    return cmd.replace("{size}", size).replace("{w}", w).replace("{h}", h)


def raster_count(cmd, size):
    """Instructions of one frame's draw and clear (callgrind)."""
    with tempfile.TemporaryDirectory(prefix="bench-raster-") as tmp:
        out = os.path.join(tmp, "cg.out")
        argv = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out] + \
            expand(cmd, size).split() + [size, "--frames", "1"]
        r = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            sys.exit("bench_time: %s failed:\n%s" % (" ".join(argv), r.stderr[-1000:]))
        p = bench_count.Profile(out)
    res = {}
    for fn in ("bench_draw", "bench_clear"):
        n = p.calls_to(fn)
        res[fn] = p.inclusive(fn) / n if n else None
    return res


def raster_main(args):
    sizes = split_list(args.sizes)
    for s in sizes:
        if not re.match(r"^\d+x\d+$", s):
            sys.exit("bench_time: --sizes: expected WxH, got '%s'" % s)
    programs = [os.path.join(args.build, "bench_raster"), os.path.join(args.build, "bench_raster-fixed")]
    programs += args.peer or []
    programs += [p for p in os.environ.get("BENCH_PEERS", "").split(";") if p.strip()]
    configs = [(p, s) for s in sizes for p in programs]
    names = {}

    def run_one(cfg):
        cmd, size = cfg
        argv = expand(cmd, size).split() + [size, "--frames", str(args.frames)]
        r = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0:
            sys.exit("bench_time: %s failed (%d):\n%s" % (" ".join(argv), r.returncode, r.stdout[-1000:]))
        name, kv = parse_line(r.stdout, " ".join(argv))
        names[cfg] = name
        return {k: float(v) if re.match(r"^[0-9.eE+-]+$", v) else v for k, v in kv.items()}

    start = loadavg()
    print("bench-raster: %d configurations x %d rounds, %d frames a run; load average at start %s"
          % (len(configs), args.rounds, args.frames, start), flush=True)
    samples = run_rounds(configs, args.rounds, run_one, "raster")
    end = loadavg()
    counts = {}
    if args.count:
        if shutil.which("valgrind"):
            for cfg in configs:
                counts[cfg] = raster_count(*cfg)
        else:
            print("bench_time: valgrind not found, no instruction counts (make bench-count installs it)")

    lines = ["# make bench-raster", "",
             "%s; the 49,728-triangle sphere of tools/bench_raster.c, %d frames a run, %d rounds "
             "interleaved; load average %s at start, %s at end."
             % (bench_count.describe_source(args.build), args.frames, args.rounds, start, end), "",
             "ms per frame, median (min..max) over the rounds. draw = the rasterizer (tinygi: "
             "tgi_raster_gbuffer into the full G-buffer); clear = clearing the buffers before it. "
             "Mtri/s = triangles submitted (back faces included) / median draw CPU time. Instructions "
             "per frame from callgrind (bench_draw / bench_clear).", "",
             "| program | size | draw CPU ms | draw wall ms | Mtri/s (CPU) | clear CPU ms "
             "| draw + clear CPU ms | draw Ir/frame | clear Ir/frame | pixels covered |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    rows = []
    for i, cfg in enumerate(configs):
        ss = samples[i]
        dc = [s["draw_cpu_ms"] for s in ss]
        dw = [s["draw_wall_ms"] for s in ss]
        cc = [s["clear_cpu_ms"] for s in ss]
        fc = [s["draw_cpu_ms"] + s["clear_cpu_ms"] for s in ss]
        tris = ss[0]["tris"]
        mtri = tris / statistics.median(dc) / 1e3
        cnt = counts.get(cfg, {})

        def fmt_ir(v):
            return "%.1fM" % (v / 1e6) if v else "-"
        lines.append("| %s | %s | %s | %s | %.1f | %s | %s | %s | %s | %d |" % (
            names[cfg], cfg[1], med_range(dc), med_range(dw), mtri, med_range(cc), med_range(fc),
            fmt_ir(cnt.get("bench_draw")), fmt_ir(cnt.get("bench_clear")), ss[0]["covered"]))
        rows.append([names[cfg], cfg[1], int(tris), args.frames, len(dc),
                     "%.4f" % statistics.median(dc), "%.4f" % min(dc), "%.4f" % max(dc),
                     "%.4f" % statistics.median(dw), "%.4f" % min(dw), "%.4f" % max(dw),
                     "%.4f" % statistics.median(cc), "%.2f" % mtri,
                     "%.0f" % cnt["bench_draw"] if cnt.get("bench_draw") else "",
                     "%.0f" % cnt["bench_clear"] if cnt.get("bench_clear") else "",
                     int(ss[0]["covered"]), start, end])
    out = args.out or os.path.join(args.build, "bench-raster")
    os.makedirs(out, exist_ok=True)
    write_atomic(os.path.join(out, "time.md"), "\n".join(lines) + "\n")
    write_atomic(os.path.join(out, "time.csv"), csv_text(
        ["program", "size", "tris", "frames", "rounds", "draw_cpu_ms_median", "draw_cpu_ms_min",
         "draw_cpu_ms_max", "draw_wall_ms_median", "draw_wall_ms_min", "draw_wall_ms_max",
         "clear_cpu_ms_median", "mtri_s_cpu", "draw_ir_per_frame", "clear_ir_per_frame", "covered",
         "load_start", "load_end"], rows))
    print()
    print("\n".join(lines))
    print("\nload average at end %s; wrote %s/time.md and time.csv" % (end, out))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="what", required=True)
    f = sub.add_parser("frame")
    bench_count.add_frame_options(f, "all")
    f.add_argument("--rounds", type=int, default=5)
    f.add_argument("--threads", default="1", help="comma list of thread counts (tinygi --threads)")
    f.add_argument("--steady", action="store_true",
                   help="also run each configuration with --frames 1: the difference is the N - 1 steady frames alone")
    f.add_argument("--baseline", default="", help="an older build directory whose tinygi runs the same configurations, interleaved")
    r = sub.add_parser("raster")
    r.add_argument("--build", default="build")
    r.add_argument("--sizes", default="320x240,1280x720")
    r.add_argument("--frames", type=int, default=20)
    r.add_argument("--rounds", type=int, default=7)
    r.add_argument("--peer", action="append", help="another program following the same protocol")
    r.add_argument("--no-count", dest="count", action="store_false")
    r.add_argument("--out", default=None)
    args = ap.parse_args()
    if args.rounds < 1 or args.frames < 1:
        sys.exit("bench_time: --rounds and --frames must be at least 1")
    (frame_main if args.what == "frame" else raster_main)(args)


if __name__ == "__main__":
    main()
