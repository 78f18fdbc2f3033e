#!/usr/bin/env python3
"""wavejets.distributed (the tool's streamed steps as Dask tasks) against the streamed tool itself.

Writes benchmark/Wavejets/distributed.md: on this machine, the tool streaming one file with one
thread (and with two, the machine's own scaling), then wavejets.distributed on a LocalCluster of 1
and 2 worker processes (one thread each) on the same file and tiles: the speed-up of 2 workers over
1, Dask's overhead over the tool, the time of each step; then, from the measured per-point costs, the time of 10^9 and 10^10 points on 8,
64 and 512 workers and the storage bandwidth they need.

    PYTHONPATH=build/bench/python python3 benchmark/Wavejets/distributed_benchmark.py \\
        --tool build/bench/demo/Wavejets/wavejets --work /tmp/distributed --points 1e7

The input is written by make_large_ply.py (a bumpy torus with normals, binary PLY) into --work.
"""
import argparse
import filecmp
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def timed(f):
    t0 = time.monotonic()
    r = f()
    return time.monotonic() - t0, r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tool", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--points", type=float, default=1e7)
    ap.add_argument("--tile-size", type=int, default=500000)
    ap.add_argument("--repeat", type=int, default=3, help="runs of each configuration; the fastest is kept")
    ap.add_argument("--out", default=os.path.join(HERE, "distributed.md"))
    a = ap.parse_args()
    from distributed import Client, LocalCluster
    from wavejets import distributed as wd

    n = int(a.points)
    a.points_text = "%.0e" % a.points if a.points >= 1e6 else str(n)
    a.points_text = a.points_text.replace("e+0", "e").replace("e+", "e")
    os.makedirs(a.work, exist_ok=True)
    src = os.path.join(a.work, "torus_%d.ply" % n)
    if not os.path.exists(src):
        subprocess.run([sys.executable, os.path.join(HERE, "make_large_ply.py"), str(n), src], check=True)
    flags = ["--k", "18"]
    command = "normals"
    reference = os.path.join(a.work, "tool.ply")
    def tool(threads):
        return min((timed(lambda: subprocess.run(
            [a.tool, command, src, reference] + flags + ["--tile-size", str(a.tile_size), "--threads", str(threads)],
            check=True, capture_output=True, text=True).stdout) for _ in range(a.repeat)), key=lambda r: r[0])
    tool_seconds, tool_out = tool(1)
    print("tool, 1 thread: %.1f s" % tool_seconds, flush=True)
    tool2_seconds, tool2_out = tool(2)
    print("tool, 2 threads: %.1f s" % tool2_seconds, flush=True)

    runs = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1",
                          dashboard_address=None) as cluster, Client(cluster) as client:
            out = os.path.join(a.work, "distributed_%d.ply" % workers)
            seconds = float("inf")
            for _ in range(a.repeat):
                tiles = []
                s, _ = timed(lambda: wd.run(command, src, out, *flags, client=client, tile_size=a.tile_size,
                                            progress=False, _on_tile_done=tiles.append))
                seconds = min(seconds, s)
            runs[workers] = dict(seconds=seconds, same=filecmp.cmp(out, reference, shallow=False), tiles=len(tiles))
            os.remove(out)
            print("distributed, %d worker(s): %.1f s, same bytes: %s" % (workers, seconds, runs[workers]["same"]),
                  flush=True)
    os.remove(reference)
    write_report(a, n, tool_seconds, tool_out, tool2_seconds, tool2_out, runs)


def duration(seconds):
    if seconds >= 3600:
        return "%.1f h" % (seconds / 3600)
    return "%.0f min" % (seconds / 60) if seconds >= 60 else "%.0f s" % seconds


def number(text, key):
    m = re.search(key + r" ([\d.]+) s", text)
    return float(m.group(1)) if m else float("nan")


def write_report(a, n, tool_seconds, tool_out, tool2_seconds, tool2_out, runs):
    one, two = runs[1], runs[2]
    tiles = one["tiles"]
    scan = number(tool_out, "Reading and checking took")
    binning = number(tool_out, "binning")
    fitting = number(tool_out, "fitting")
    writing = number(tool_out, "writing")
    serial = scan + binning                         # the step that one task does for the whole file
    per_point_fit = fitting / n                     # one thread
    per_point_write = writing / n                   # one thread, spread over the workers in parts
    fitting2 = number(tool2_out, "fitting")         # the same tiles fitted by 2 threads of one process
    lines = []
    w = lines.append
    w("# Point sets larger than one machine: `wavejets.distributed` on Dask")
    w("")
    w("`wavejets.distributed.run(command, IN, OUT, *flags)` (or `python3 -m wavejets.distributed COMMAND IN OUT")
    w("[flags]`) runs the steps of the tool's streamed run as Dask tasks: one task reads IN and bins the")
    w("points, one task per tile fits it, one task per worker writes its part of OUT (binary PLY in and out;")
    w("else one task writes OUT). OUT is the in-core file, byte for byte.")
    w("Measured on this machine (%d cores) with %s points (a bumpy torus with normals, binary PLY)," % (os.cpu_count(), f"{n:,}"))
    w("`normals --k 18`, tiles of %s points (%d tiles), the fastest of %d runs each; the tool streams the same file" % (f"{a.tile_size:,}", tiles, a.repeat))
    w("with one thread (`--tile-size %d --threads 1`), the workers are processes of one thread. Command:" % a.tile_size)
    w("")
    w("    PYTHONPATH=build/bench/python python3 benchmark/Wavejets/distributed_benchmark.py \\")
    w("        --tool build/bench/demo/Wavejets/wavejets --work /tmp/distributed --points %s --tile-size %d" % (a.points_text, a.tile_size))
    w("")
    w("| run | time | vs the tool | same bytes as the tool |")
    w("|---|---|---|---|")
    w("| the tool, streamed, 1 thread | %.1f s | 1.00x | |" % tool_seconds)
    w("| wavejets.distributed, 1 worker | %.1f s | %.2fx | %s |" % (one["seconds"], one["seconds"] / tool_seconds, "yes" if one["same"] else "**no**"))
    w("| wavejets.distributed, 2 workers | %.1f s | %.2fx | %s |" % (two["seconds"], two["seconds"] / tool_seconds, "yes" if two["same"] else "**no**"))
    w("")
    w("- Speed-up of 2 workers over 1: **%.2fx**. Reading and binning (%.1f s here) are one task: with it," % (
        one["seconds"] / two["seconds"], serial))
    w("  2 workers can be at most %.2fx faster than 1 on this file. The machine itself bounds it too: the" % (
        one["seconds"] / (serial + (one["seconds"] - serial) / 2)))
    w("  same tiles fitted by 2 threads of one process (the tool, `--threads 2`) take %.1f s against %.1f s" % (fitting2, fitting))
    w("  with 1 thread, **%.2fx**; the two workers also share the two cores with the scheduler and the client." % (fitting / fitting2))
    w("- Dask on one worker against the tool (scheduling, each tile's step reading its plan and points):")
    w("  **%+.1f%%** of the tool's time, %+.2f s per tile." % (100 * (one["seconds"] / tool_seconds - 1),
                                                           (one["seconds"] - tool_seconds) / tiles))
    w("- The tool's split (1 thread): reading %.1f s, binning %.1f s, fitting %.1f s, writing %.1f s: reading and" % (scan, binning, fitting, writing))
    w("  binning are one task (they stream the whole file), fitting and writing are spread over the workers.")
    w("")
    w("## Sizing a cluster")
    w("")
    w("From these costs: a worker (one core) fits %.0f points per second (`normals`, k 18, order 2);" % (1 / per_point_fit))
    w("reading and binning take %.2f s per 10^6 points in one task, whatever the number of workers; writing" % (serial / n * 1e6))
    w("%.2f s per 10^6 points, spread over the workers. Time = serial part + (fitting + writing) / workers (tiles" % (per_point_write * 1e6))
    w("spread evenly; each tile reads its points and halo, about 1.2 x 64 bytes per point, and writes 64 bytes")
    w("per point of results, from shared storage).")
    w("")
    w("| points | workers | serial step | fitting and writing | total | storage bandwidth (all workers) |")
    w("|---|---|---|---|---|---|")
    for total in (1e9, 1e10):
        for workers in (8, 64, 512):
            s = serial / n * total
            f = (per_point_fit + per_point_write) * total / workers
            bandwidth = 1.2 * 64 + 64   # bytes per point fitted
            w("| 10^%d | %d | %s | %s | %s | %.0f MB/s |" % (
                round(math.log10(total)), workers, duration(s), duration(f), duration(s + f),
                bandwidth * workers / per_point_fit / 1e6))
    w("")
    w("The steps are timed here with the files in the page cache; once the files outgrow memory they read")
    w("and write the disk (at 10^8 points on this machine, `scale.md`, reading, binning and writing took")
    w("about twice as long per point): count on your storage's rate. Past a few dozen workers reading and")
    w("binning, one task, dominate the time: a faster disk is what helps then.")
    w("")
    with open(a.out, "w") as f:
        f.write("\n".join(lines))
    print("wrote", a.out)


if __name__ == "__main__":
    main()
