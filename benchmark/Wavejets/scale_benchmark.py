#!/usr/bin/env python3
"""Streamed (out-of-core) runs of the `wavejets` tool against in-core runs, from 10^6 to 10^8 points.

Writes benchmark/Wavejets/scale.md: for each size and command, the wall time, the points per second,
the peak resident memory and the time split of the streamed run (--max-memory), the in-core run
beside it where it fits in memory, whether both outputs are the same bytes, and a projection to
10^9 and 10^10 points from the measured per-point costs.

    python3 benchmark/Wavejets/scale_benchmark.py --tool build/bench/demo/Wavejets/wavejets \\
        --work /tmp/scale --sizes 1e6,1e7,1e8 --in-core-max 1e7

The input files (a bumpy torus with exact normals, binary PLY) are written by make_large_ply.py
into --work, which needs about 110 bytes per point per size for the input, the outputs and the
streamed run's scratch files. The runs use every core.
"""
import argparse
import filecmp
import os
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))

COMMANDS = [
    ("K 2 normals", ["normals", "--k", "18"]),
    ("K 4 enhance-positions", ["enhance-positions", "--k", "18"]),
]


def run_timed(argv):
    """Runs argv under /usr/bin/time; returns (stdout, wall seconds, peak RSS in bytes)."""
    t0 = time.monotonic()
    p = subprocess.run(["/usr/bin/time", "-f", "PEAK_RSS_KB %M"] + argv, capture_output=True, text=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit("failed: %s\n%s%s" % (" ".join(argv), p.stdout, p.stderr))
    rss = int(re.search(r"PEAK_RSS_KB (\d+)", p.stderr).group(1)) * 1024
    return p.stdout, wall, rss


def number(pattern, text):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else float("nan")


def fmt_n(n):
    e = len(str(n)) - 1
    return "10^%d" % e if n == 10 ** e else str(n)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tool", required=True, help="the wavejets executable")
    ap.add_argument("--work", required=True, help="folder for the inputs, outputs and scratch files")
    ap.add_argument("--sizes", default="1e6,1e7,1e8")
    ap.add_argument("--in-core-max", default="1e7", help="largest size also run in core")
    ap.add_argument("--max-memory", default="2G")
    ap.add_argument("--out", default=os.path.join(HERE, "scale.md"))
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    sizes = [int(float(s)) for s in a.sizes.split(",")]
    rows = []
    for n in sizes:
        src = os.path.join(a.work, "torus_%d.ply" % n)
        if not os.path.exists(src):
            subprocess.run([sys.executable, os.path.join(HERE, "make_large_ply.py"), str(n), src], check=True)
        for name, args in COMMANDS:
            row = {"n": n, "command": name}
            st = os.path.join(a.work, "streamed.ply")
            out, wall, rss = run_timed([a.tool] + args[:1] + [src, st] + args[1:] + ["--max-memory", a.max_memory])
            row.update(wall=wall, rss=rss, scan=number(r"Reading and checking took ([\d.]+) s", out),
                       binning=number(r"binning ([\d.]+) s", out), fitting=number(r"fitting ([\d.]+) s", out),
                       writing=number(r"writing ([\d.]+) s", out), tiles=int(number(r"\((\d+) tiles", out)),
                       rerun=int(number(r"; (\d+) points fitted again", out)))
            if n <= float(a.in_core_max):
                ic = os.path.join(a.work, "in_core.ply")
                out, wall, rss = run_timed([a.tool] + args[:1] + [src, ic] + args[1:])
                row.update(ic_wall=wall, ic_rss=rss, ic_read=number(r" in ([\d.]+) s; neighborhoods", out),
                           ic_fitting=number(r"Fitting took ([\d.]+) s", out),
                           ic_writing=number(r"properties: [^)]*\) in ([\d.]+) s", out),
                           same=filecmp.cmp(st, ic, shallow=False))
                os.remove(ic)
            os.remove(st)
            rows.append(row)
            print(row, flush=True)
    write_report(a, rows)


def write_report(a, rows):
    cores = os.cpu_count()
    lines = []
    w = lines.append
    w("# Point sets larger than memory: streamed runs of the `wavejets` tool")
    w("")
    w("`wavejets COMMAND IN OUT --max-memory %s` reads IN in passes, processes it in spatial tiles with a" % a.max_memory)
    w("halo, and writes OUT in input order: the same bytes as the in-core run (checked below where the")
    w("in-core run fits). Input: a bumpy torus with exact normals, binary PLY (`make_large_ply.py`),")
    w("k = 18 neighbors; all %d cores of the machine; one run each (machines are shared and noisy: compare" % cores)
    w("the ratios, not the seconds). Command:")
    w("")
    w("    python3 benchmark/Wavejets/scale_benchmark.py --tool build/bench/demo/Wavejets/wavejets \\")
    w("        --work /tmp/scale --sizes %s --in-core-max %s" % (a.sizes, a.in_core_max))
    w("")
    w("## Streamed and in-core runs")
    w("")
    in_core_rows = [r for r in rows if "ic_wall" in r]
    per_point = {r["command"]: r["ic_rss"] / r["n"] for r in sorted(in_core_rows, key=lambda r: r["n"])}
    largest = max(in_core_rows, key=lambda r: r["n"])["n"] if in_core_rows else 0
    for r in rows:
        if r["n"] == largest:
            w("- %s points, %s: the streamed run takes **%.2fx** the in-core time, in %.0f%% of its memory." % (
                fmt_n(r["n"]), r["command"], r["wall"] / r["ic_wall"], 100 * r["rss"] / r["ic_rss"]))
    biggest = max(r["n"] for r in rows)
    w("- %s points: peak memory %s, where the in-core run would need about %s." % (
        fmt_n(biggest), " and ".join("%.2f GB (%s)" % (r["rss"] / 1e9, r["command"]) for r in rows if r["n"] == biggest),
        " and ".join("%.0f GB" % (per_point[r["command"]] * biggest / 1e9) for r in rows if r["n"] == biggest and r["command"] in per_point)))
    w("- With one tile (10^6 points here) the streamed run pays its binning and copies for nothing: below the")
    w("  memory budget, run in memory (no --max-memory).")
    w("- Past the page cache (here 10^8 points: the input, the scratch files and OUT take about 20 GB), binning")
    w("  and writing read and write the disk, and their time per point grows; fitting's grows little.")
    w("")
    w("| points | command | streamed | points/s | peak memory | in core | peak memory | streamed / in core | same bytes |")
    w("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        ic = "ic_wall" in r
        w("| %s | %s | %.1f s | %.2g | %.2f GB | %s | %s | %s | %s |" % (
            fmt_n(r["n"]), r["command"], r["wall"], r["n"] / r["wall"], r["rss"] / 1e9,
            "%.1f s" % r["ic_wall"] if ic else "not run", "%.2f GB" % (r["ic_rss"] / 1e9) if ic else "",
            "%.2fx" % (r["wall"] / r["ic_wall"]) if ic else "", ("yes" if r["same"] else "**no**") if ic else ""))
    w("")
    w("## Where the time goes")
    w("")
    w("Streamed: reading and checking the input (and, unless it is a binary PLY of float or double")
    w("coordinates, writing its records to a scratch file), binning the records into tiles on disk,")
    w("fitting (per tile: reading its points and halo back, k-NN and fits in the library, the points whose")
    w("neighborhood leaves the halo run again with a larger one), writing OUT (the input read again, merged")
    w("with the results). In core: reading, fitting, writing.")
    w("")
    w("| points | command | tiles | refitted points | read + check | binning | fitting | writing | in core: read | fitting | writing |")
    w("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        ic = "ic_wall" in r
        w("| %s | %s | %d | %d | %.1f s | %.1f s | %.1f s | %.1f s | %s | %s | %s |" % (
            fmt_n(r["n"]), r["command"], r["tiles"], r["rerun"], r["scan"], r["binning"], r["fitting"], r["writing"],
            *(("%.1f s" % r[k]) if ic else "" for k in ("ic_read", "ic_fitting", "ic_writing"))))
    w("")
    big = max(rows, key=lambda r: r["n"])["n"]
    w("## Projection to 10^9 and 10^10 points")
    w("")
    w("From the per-point costs of the %s-point runs: the streamed run's time grows with N (each tile" % fmt_n(big))
    w("costs the same per point; the passes over the scratch files are sequential reads and writes), its")
    w("memory does not (tiles of a fixed size; the grid of cells is at most 200^3). Disk: the input, OUT,")
    w("and at most three scratch files of 64 bytes per point at a time (152 for the curvature command's")
    w("results), next to OUT.")
    w("")
    w("| command | seconds per 10^6 points | 10^9 points | 10^10 points | scratch disk at 10^10 |")
    w("|---|---|---|---|---|")
    for r in rows:
        if r["n"] != big:
            continue
        per = r["wall"] / r["n"]
        w("| %s | %.1f | %.1f h | %.0f h | %.1f TB |" % (r["command"], per * 1e6, per * 1e9 / 3600, per * 1e10 / 3600,
                                                       3 * 64 * 1e10 / 1e12))
    w("")
    w("These are one machine's figures (%d cores); the tiles are independent tasks, so more cores or" % cores)
    w("machines divide the fitting time (see the distributed runs).")
    w("")
    with open(a.out, "w") as f:
        f.write("\n".join(lines))
    print("wrote", a.out)


if __name__ == "__main__":
    main()
