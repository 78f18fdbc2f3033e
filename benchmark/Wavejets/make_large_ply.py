#!/usr/bin/env python3
"""Writes a large binary PLY point set with normals for the scale benchmark (scale.md):
N points on a bumpy torus (major radius 1, minor radius 0.35, bumps of amplitude 0.02), with their
exact unit normals, in random order (a scan's order is not spatial either), as
x y z nx ny nz (doubles, binary little-endian). Written in chunks of 10^6 points: memory stays
small whatever N. The points are a function of N and the seed only.

    python3 make_large_ply.py N OUT.ply [--seed S]
"""
import argparse
import sys

import numpy as np

R, r, bump, frequency = 1.0, 0.35, 0.02, 12


def torus_chunk(rng, n):
    """n points of the bumpy torus and their unit normals (rows)."""
    # Rejection-free sampling proportional to the area element (R + r cos v): v by inverse-CDF
    # on a fine table, u uniform.
    u = rng.uniform(0.0, 2.0 * np.pi, n)
    table = np.linspace(0.0, 2.0 * np.pi, 4097)
    cdf = table * R + r * np.sin(table)
    v = np.interp(rng.uniform(0.0, cdf[-1], n), cdf, table)
    h = r + bump * np.sin(frequency * u) * np.sin(frequency * v)   # tube radius with bumps
    cu, su, cv, sv = np.cos(u), np.sin(u), np.cos(v), np.sin(v)
    p = np.stack([(R + h * cv) * cu, (R + h * cv) * su, h * sv], axis=1)
    # Partial derivatives of the parametrization, their cross product: the normal.
    hu = bump * frequency * np.cos(frequency * u) * np.sin(frequency * v)
    hv = bump * frequency * np.sin(frequency * u) * np.cos(frequency * v)
    pu = np.stack([hu * cv * cu - (R + h * cv) * su, hu * cv * su + (R + h * cv) * cu, hu * sv], axis=1)
    pv = np.stack([(hv * cv - h * sv) * cu, (hv * cv - h * sv) * su, hv * sv + h * cv], axis=1)
    normal = np.cross(pu, pv)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    # Outward: away from the tube's axis.
    axis_point = np.stack([R * cu, R * su, np.zeros(n)], axis=1)
    flip = np.einsum("ij,ij->i", normal, p - axis_point) < 0
    normal[flip] *= -1
    return p, normal


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("n", type=float, help="number of points (1e7 is accepted)")
    parser.add_argument("out", help="output .ply")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    n = int(args.n)
    chunk = 1000000
    with open(args.out, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\ncomment bumpy torus, %d points, seed %d\n"
                 "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
                 "property double nx\nproperty double ny\nproperty double nz\nend_header\n" % (n, args.seed, n)).encode())
        for start in range(0, n, chunk):
            rng = np.random.default_rng([args.seed, start // chunk])
            p, normal = torus_chunk(rng, min(chunk, n - start))
            np.hstack([p, normal]).astype("<f8").tofile(f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
