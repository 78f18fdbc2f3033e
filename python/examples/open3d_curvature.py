"""An Open3D point cloud coloured by Wavejet mean curvature: the cloud's arrays go to wavejets and
back without a copy of the points; the result is written as a coloured PLY (Open3D's writer) and
drawn into a PNG (the package's renderer, no display needed).

    python3 open3d_curvature.py [--input SCAN] [--out FOLDER]

Needs Open3D (Debian: apt-get install python3-open3d; elsewhere: pip install open3d).
"""

import argparse
import sys
from pathlib import Path

import numpy as np

import wavejets

try:
    import open3d as o3d
except ImportError:
    print("open3d is not installed (Debian: apt-get install python3-open3d): nothing to do")
    sys.exit(77)   # "skipped" for the project's tests

DATA = Path(__file__).resolve().parents[2] / "examples" / "Wavejets" / "data"

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--input", default=str(DATA / "kitten.xyz"),
                    help="a point cloud Open3D reads (default: the kitten scan, x y z nx ny nz)")
parser.add_argument("--out", default="out", help="output folder")
args = parser.parse_args()
out = Path(args.out)
out.mkdir(parents=True, exist_ok=True)

# The kitten's .xyz has normals after the coordinates: Open3D calls that format "xyzn".
cloud = o3d.io.read_point_cloud(args.input, format="xyzn" if args.input.endswith(".xyz") else "auto")
points = np.asarray(cloud.points)   # a view of Open3D's buffer: float64, (N, 3), C-contiguous
normals = np.asarray(cloud.normals) if cloud.has_normals() else None
print(f"{args.input}: {len(points)} points, {'with' if normals is not None else 'without'} normals")

# Wavejet normals (oriented like the scan's when it has some), then curvature at order 3.
normals = wavejets.estimate_normals(points, normals, k=18)
c = wavejets.estimate_curvatures(points, normals, order=3, k=40)
H = c.mean_curvature

# Colours: blue (H < 0) - white - red (H > 0), saturated at the 95th percentile of |H|. H > 0 where
# the surface bends toward its normals: with outward normals, bumps are blue and hollows red.
t = np.clip(H / np.percentile(np.abs(H), 95), -1, 1)[:, None]
white, blue, red = np.array([0.92, 0.92, 0.90]), np.array([0.17, 0.33, 0.80]), np.array([0.80, 0.10, 0.12])
cloud.normals = o3d.utility.Vector3dVector(normals)
cloud.colors = o3d.utility.Vector3dVector(np.where(t < 0, white + (-t) * (blue - white), white + t * (red - white)))
path = out / "curvature_open3d.ply"
o3d.io.write_point_cloud(str(path), cloud)
print("wrote", path, "(open it in MeshLab, CloudCompare or o3d.visualization.draw_geometries)")

picture = out / "curvature_open3d.png"
wavejets.render(picture, points, normals, values=H, view=(0.3, 0.2, 1.0))
print("wrote", picture)
