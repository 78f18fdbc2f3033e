"""Wavejets: local surface analysis and detail enhancement of point clouds (CGAL Wavejets).

A Wavejet (Bearzi, Digne and Chaine, Eurographics 2018) describes the surface around each
point as a height field over its tangent plane, in the basis r^k e^{i n theta}. From it this
module estimates normals and curvatures, and enhances, flattens, inverts or twists surface
details, on NumPy arrays of shape (N, 3)::

    import numpy as np, wavejets
    points, normals, faces = wavejets.read("bunny.off")
    normals = wavejets.estimate_normals(points, normals)          # oriented like the input
    c = wavejets.estimate_curvatures(points, normals)             # c.mean_curvature, c.k1, ...
    moved = wavejets.enhance_positions(points, normals, gain=2)   # details doubled
    c = wavejets.estimate_curvatures(points, normals, k="auto")   # each point's k chosen
    wavejets.write("bunny_enhanced.ply", moved, normals, faces)

Every function is the C++ function of the same name of the CGAL package, called with
Parallel_tag: same results, bit for bit, for any number of threads. help(wavejets.<function>)
lists its keyword arguments and their defaults (the C++ defaults).
"""

from ._wavejets import __version__
from ._report import Report
from ._functions import (Curvatures, Scales, enhance_normals, enhance_positions, estimate_curvatures,
                         estimate_normals, estimate_scales, fit)
from ._wavejets import Wavejet
from ._io import read, render, write

__all__ = ["estimate_normals", "estimate_curvatures", "enhance_positions", "enhance_normals", "estimate_scales",
           "fit", "read", "write", "render", "Curvatures", "Report", "Scales", "Wavejet", "__version__"]
