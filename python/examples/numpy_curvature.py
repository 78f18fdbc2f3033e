"""Normals and curvature of a scan on NumPy arrays, written as a PLY that MeshLab or CloudCompare
colours by curvature (property mean_curvature), and drawn coloured by it into a PNG.

    python3 numpy_curvature.py [--input SCAN] [--out FOLDER]
"""

import argparse
from pathlib import Path

import numpy as np

import wavejets

DATA = Path(__file__).resolve().parents[2] / "examples" / "Wavejets" / "data"

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--input", default=str(DATA / "kitten.xyz"), help="a point set or a mesh (default: the kitten scan)")
parser.add_argument("--out", default="out", help="output folder")
args = parser.parse_args()
out = Path(args.out)
out.mkdir(parents=True, exist_ok=True)

points, normals, faces = wavejets.read(args.input)
print(f"{args.input}: {len(points)} points, {'with' if normals is not None else 'without'} normals")

# Wavejet normals, oriented like the scan's normals when it has some.
normals, report = wavejets.estimate_normals(points, normals, k=18, return_report=True)
print("normals:", report)

# Curvatures at order 3 over the 40 nearest neighbors (signs relative to the normals).
c = wavejets.estimate_curvatures(points, normals, order=3, k=40)
H = c.mean_curvature[c.fitted]
print(f"mean curvature, 5% / median / 95%: {np.percentile(H, 5):.3g} / {np.median(H):.3g} / {np.percentile(H, 95):.3g}")

path = out / "curvature.ply"
wavejets.write(path, points, normals, faces,
               properties={"mean_curvature": c.mean_curvature, "gaussian_curvature": c.gaussian_curvature,
                           "k1": c.k1, "k2": c.k2})
print("wrote", path)
picture = out / "curvature.png"
wavejets.render(picture, points, normals, faces, values=c.mean_curvature)
# H > 0 where the surface bends toward its normals: with outward normals, bumps are blue (H < 0)
# and hollows red.
print("wrote", picture, "(blue: H < 0, red: H > 0)")

# Read back: the same numbers.
back, back_normals, _, properties = wavejets.read(path, properties=True)
assert np.array_equal(back, points) and np.array_equal(properties["mean_curvature"], c.mean_curvature)
