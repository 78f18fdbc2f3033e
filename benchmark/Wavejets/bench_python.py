#!/usr/bin/python3
"""The Python module against the C++ functions and against Open3D (report: python.md).

  PYTHONPATH=build/dev/python /usr/bin/python3 benchmark/Wavejets/bench_python.py \
      --reference build/dev/python/tests/wavejets_python_reference [--points 1000000] [--threads 2] [--quick]

Measures, and writes as csv/python.*.csv (make_reports.py turns them into python.md):
1. overhead: each function called from Python on the (N, 3) arrays of an N-point torus, against the
   same C++ function called on a CGAL::Point_set_3 by the reference program (which times its call
   only); the runs alternate, medians of 5;
2. no copy: the peak of NumPy's allocations during a call (tracemalloc) for float64 C-contiguous
   input against float32 input, and the result's size;
3. Open3D: `PointCloud.estimate_normals(KDTreeSearchParamKNN(k + 1))` (Open3D counts the query point
   in its k, the package does not: the same neighborhoods) against `wavejets.estimate_normals(k=k,
   order=2)` on sphere, torus and ellipsoid samples with Gaussian noise of 0, 0.25% and 0.5% of the
   bounding box diagonal: time and the unoriented angle to the exact normals (both outputs are
   unoriented without input normals);
4. the grid: order 1 to 4 and k from 10 to 100 on the same surfaces (on --grid-points points), to find
   the order and k with the lowest error at the time Open3D takes.
"""

import argparse
import csv
import os
import platform
import subprocess
import sys
import tempfile
import time
import tracemalloc

HERE = os.path.dirname(os.path.abspath(__file__))


def arguments():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--reference", required=True, help="the wavejets_python_reference program (built with the module)")
    parser.add_argument("--points", type=int, default=1000000, help="points of each sample (default 10^6)")
    parser.add_argument("--grid-points", type=int, default=200000, help="points of the order-and-k grid's samples")
    parser.add_argument("--threads", type=int, default=os.cpu_count(), help="threads of both libraries (default: all)")
    parser.add_argument("--repeats", type=int, default=5, help="runs of each timing (the median is kept)")
    parser.add_argument("--grid-repeats", type=int, default=1, help="runs of each timing of the grid")
    parser.add_argument("--csv-dir", default=os.path.join(HERE, "csv"))
    parser.add_argument("--quick", action="store_true", help="a smoke test: 20,000 points, 1 run, a small grid")
    parser.add_argument("--only", default="overhead,copies,open3d,grid",
                        help="the measurements to run (comma-separated; the others' CSV files are left as they are)")
    return parser.parse_args()


ARGS = arguments()
if ARGS.quick:
    ARGS.points, ARGS.grid_points, ARGS.repeats, ARGS.grid_repeats = 20000, 20000, 1, 1
# Open3D runs its loops with OpenMP: its thread count is read when it is loaded.
os.environ["OMP_NUM_THREADS"] = str(ARGS.threads)

import numpy as np  # noqa: E402

import wavejets  # noqa: E402

try:
    import open3d  # noqa: E402
except ImportError:
    open3d = None

NOISES = [0.0, 0.0025, 0.005]   # sigma / bounding box diagonal


# ------------------------------------------------------------------------------------------ surfaces

def sphere(n, rng):
    normals = rng.normal(size=(n, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    return normals.copy(), normals


def torus(n, rng, R=1.0, r=0.3):
    """Uniform by area: v drawn with density proportional to R + r cos v (rejection)."""
    u = rng.uniform(0, 2 * np.pi, n)
    v = np.empty(0)
    while v.size < n:
        c = rng.uniform(0, 2 * np.pi, 2 * n)
        v = np.concatenate([v, c[rng.uniform(0, R + r, 2 * n) < R + r * np.cos(c)]])
    v = v[:n]
    normals = np.column_stack([np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)])
    points = np.column_stack([(R + r * np.cos(v)) * np.cos(u), (R + r * np.cos(v)) * np.sin(u), r * np.sin(v)])
    return points, normals


def ellipsoid(n, rng, axes=(1.0, 0.7, 0.5)):
    """Directions uniform on the sphere, scaled by the axes (denser near the short axis)."""
    d = rng.normal(size=(n, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    a = np.asarray(axes)
    points = d * a
    normals = points / a ** 2
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    return points, normals


SURFACES = {"sphere": sphere, "torus": torus, "ellipsoid": ellipsoid}


def sample(surface, n, noise, seed=1):
    rng = np.random.default_rng(seed)
    points, normals = SURFACES[surface](n, rng)
    diagonal = np.linalg.norm(points.max(axis=0) - points.min(axis=0))
    return np.ascontiguousarray(points + rng.normal(scale=noise * diagonal, size=points.shape)), normals


def angle_error(estimated, exact):
    """Mean unoriented angle in degrees (the points with a zero normal, unfitted, count as 90)."""
    length = np.linalg.norm(estimated, axis=1)
    cosine = np.abs(np.sum(estimated * exact, axis=1)) / np.where(length > 0, length, 1.0)
    return float(np.degrees(np.arccos(np.clip(cosine, 0.0, 1.0))).mean())


def timed(call):
    start = time.perf_counter()
    result = call()
    return time.perf_counter() - start, result


def median_time(call, repeats):
    times, result = [], None
    for _ in range(repeats):
        t, result = timed(call)
        times.append(t)
    return float(np.median(times)), result


def write_csv(name, header, rows):
    os.makedirs(ARGS.csv_dir, exist_ok=True)
    with open(os.path.join(ARGS.csv_dir, f"python.{name}.csv"), "w", newline="") as f:
        writer = csv.writer(f, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)
    print("wrote", os.path.join(ARGS.csv_dir, f"python.{name}.csv"))


def fmt(x, digits=3):
    return f"{x:.{digits}g}" if abs(x) < 10 ** digits else f"{x:.0f}"


# ------------------------------------------------------------------------------------------ 1. overhead

OVERHEAD_CALLS = [
    # (function, order, k, Python call, reference arguments)
    ("estimate_normals", 2, 18, lambda p, n, t: wavejets.estimate_normals(p, k=18, order=2, threads=t), []),
    ("estimate_curvatures", 2, 18, lambda p, n, t: wavejets.estimate_curvatures(p, k=18, order=2, threads=t), []),
    ("enhance_positions", 4, 40, lambda p, n, t: wavejets.enhance_positions(p, k=40, order=4, gain=2.0, threads=t), ["2", "0"]),
    ("enhance_normals", 4, 40, lambda p, n, t: wavejets.enhance_normals(p, k=40, order=4, gain=2.0, threads=t), ["2", "0"]),
]


def reference_seconds(function, path, k, order, extra, folder):
    env = dict(os.environ, WAVEJETS_REFERENCE_TIME="1")
    if ARGS.threads != os.cpu_count():
        sys.exit("the overhead is measured with all cores (the reference program uses TBB's default)")
    out = subprocess.run([ARGS.reference, function, path, os.path.join(folder, "reference.out"), str(k), str(order)] + extra,
                         env=env, capture_output=True, text=True, check=True).stdout
    return float(out.split()[-1])


def measure_overhead(folder):
    points, _ = sample("torus", ARGS.points, 0.0)
    path = os.path.join(folder, "torus.ply")
    wavejets.write(path, points)
    points, _, _ = wavejets.read(path)   # the same doubles as the reference reads
    rows = []
    for function, order, k, call, extra in OVERHEAD_CALLS:
        python, cpp = [], []
        for _ in range(ARGS.repeats):   # alternate, so that a slow phase of the machine hits both
            python.append(timed(lambda: call(points, None, ARGS.threads))[0])
            cpp.append(reference_seconds(function, path, k, order, extra, folder))
        p, c = float(np.median(python)), float(np.median(cpp))
        rows.append([function, f"K {order}, k {k}", fmt(c), fmt(p), f"{100 * (p / c - 1):+.1f}%",
                     f"{100 * (min(python) / min(cpp) - 1):+.1f}%", f"{100 * (max(cpp) / min(cpp) - 1):.0f}%"])
        print(rows[-1], flush=True)
    write_csv("overhead", ["function", "order, k", "C++ call (s)", "Python call (s)", "overhead (medians)",
                           "overhead (fastest runs)", "C++ runs: slowest / fastest - 1"], rows)


def measure_copies():
    points, _ = sample("torus", 200000, 0.0)
    rows = []
    for label, array in [("float64, C-contiguous", points), ("float32", points.astype(np.float32)),
                         ("float64, Fortran order", np.asfortranarray(points))]:
        tracemalloc.start()
        wavejets.estimate_normals(array, k=10, threads=1)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        rows.append([label, f"{peak / points.nbytes:.2f}"])
    write_csv("copies", ["input (200,000 points)", "peak NumPy allocations / size of the (N, 3) result"], rows)


# ------------------------------------------------------------------------------------------ 3-4. Open3D

def open3d_normals(points, k, repeats):
    """A new cloud for each run (Open3D orients new normals like the ones a cloud has)."""
    times = []
    for _ in range(repeats):
        cloud = open3d.geometry.PointCloud()
        cloud.points = open3d.utility.Vector3dVector(points)
        times.append(timed(lambda: cloud.estimate_normals(open3d.geometry.KDTreeSearchParamKNN(k + 1)))[0])
    return float(np.median(times)), np.asarray(cloud.normals)


def wavejets_normals(points, k, order, repeats):
    return median_time(lambda: wavejets.estimate_normals(points, k=k, order=order, threads=ARGS.threads), repeats)


def measure_open3d():
    rows = []
    for surface in SURFACES:
        for noise in NOISES:
            points, exact = sample(surface, ARGS.points, noise)
            t_o3d, n_o3d = open3d_normals(points, 18, ARGS.repeats)
            t_wj, n_wj = wavejets_normals(points, 18, 2, ARGS.repeats)
            e_o3d, e_wj = angle_error(n_o3d, exact), angle_error(n_wj, exact)
            rows.append([surface, f"{100 * noise:g}%", fmt(t_o3d), fmt(t_wj), f"{t_o3d / t_wj:.2f}", fmt(e_o3d), fmt(e_wj),
                         f"{e_o3d / e_wj:.2f}"])
            print(rows[-1], flush=True)
    write_csv("open3d", ["surface", "noise", "Open3D (s)", "wavejets K 2 (s)", "x faster", "Open3D error (deg)",
                         "wavejets K 2 error (deg)", "x lower error"], rows)


GRID_ORDERS = [1, 2, 3, 4]
GRID_K = [10, 18, 30, 60, 100]


def measure_grid():
    rows, best = [], []
    orders, ks = (GRID_ORDERS, [10, 30]) if ARGS.quick else (GRID_ORDERS, GRID_K)
    for surface in SURFACES:
        for noise in NOISES:
            points, exact = sample(surface, ARGS.grid_points, noise, seed=2)
            t_o3d, n_o3d = open3d_normals(points, 18, ARGS.grid_repeats)
            e_o3d = angle_error(n_o3d, exact)
            rows.append([surface, f"{100 * noise:g}%", "Open3D", 18, fmt(t_o3d), fmt(e_o3d)])
            candidates = []
            for order in orders:
                for k in ks:
                    t, n = wavejets_normals(points, k, order, ARGS.grid_repeats)
                    candidates.append((angle_error(n, exact), t, order, k))
                    rows.append([surface, f"{100 * noise:g}%", f"wavejets K {order}", k, fmt(t), fmt(candidates[-1][0])])
            within = [c for c in candidates if c[1] <= t_o3d] or [min(candidates, key=lambda c: c[1])]
            e, t, order, k = min(within)
            overall = min(candidates)
            best.append([surface, f"{100 * noise:g}%", fmt(e_o3d), f"K {order}, k {k}", fmt(e), f"{e_o3d / e:.2f}",
                         f"K {overall[2]}, k {overall[3]}", fmt(overall[0]), fmt(overall[1] / t_o3d)])
            print(best[-1], flush=True)
    write_csv("grid", ["surface", "noise", "method", "k", "time (s)", "error (deg)"], rows)
    write_csv("best", ["surface", "noise", "Open3D k 18 error (deg)", "best wavejets within Open3D's time",
                       "its error (deg)", "x lower error", "lowest error at any time", "its error (deg)",
                       "its time / Open3D's"], best)


def main():
    start = time.perf_counter()
    only = ARGS.only.split(",")
    if "overhead" in only:
        with tempfile.TemporaryDirectory() as folder:
            measure_overhead(folder)
    if "copies" in only:
        measure_copies()
    if open3d is None:
        print("open3d is not installed (Debian: apt-get install python3-open3d): the comparison with Open3D is skipped")
    else:
        if "open3d" in only:
            measure_open3d()
        if "grid" in only:
            measure_grid()
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    write_csv("context", ["key", "value"], [
        ["machine", f"{cpu}, {os.cpu_count()} hardware threads"],
        ["threads", ARGS.threads], ["points", f"{ARGS.points:,}"], ["grid points", f"{ARGS.grid_points:,}"], ["repeats", ARGS.repeats], ["grid repeats", ARGS.grid_repeats],
        ["wavejets", wavejets.__version__], ["open3d", open3d.__version__ if open3d else "not installed"],
        ["numpy", np.__version__], ["python", platform.python_version()],
        ["run time (s)", f"{time.perf_counter() - start:.0f}"]])


if __name__ == "__main__":
    main()
