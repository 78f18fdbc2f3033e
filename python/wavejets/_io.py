"""Reading and writing point sets and meshes through CGAL's IO (the `wavejets` tool's reader and
writer)."""

import os

import numpy as np

from . import _wavejets
from ._functions import _coordinates


def read(path, properties=False):
    """Reads a point set or a mesh.

    Parameters
    ----------
    path : str or os.PathLike
        A point set (.xyz, .pwn, or .ply / .off without faces) or a mesh (.off, .obj, or .ply
        with faces).
    properties : bool
        Also return the file's other per-point numbers (PLY properties of type double, e.g. the
        ``mean_curvature`` that ``wavejets curvature`` writes), as a dict of (N,) arrays.

    Returns
    -------
    points : ndarray, shape (N, 3)
    normals : ndarray, shape (N, 3), or None when the file has none (all zero counts as none)
    faces : ndarray, shape (F, 3), int64 (triangles), a list of lists of vertex indices (other
        polygons), or None for a point set
    properties : dict (only with properties=True)

    Raises
    ------
    ValueError
        The file cannot be read, is malformed, truncated or empty, has a NaN or infinite
        coordinate, a face refers to a missing vertex, or all its points coincide; the message
        names the file and says why.
    """
    points, normals, faces, extra = _wavejets.read(os.fspath(path))
    return (points, normals, faces, extra) if properties else (points, normals, faces)


def write(path, points, normals=None, faces=None, properties=None, ascii=False):
    """Writes a point set or a mesh; on error the file at `path` is left untouched.

    Parameters
    ----------
    path : str or os.PathLike
        ``.ply`` (binary little-endian doubles, or ASCII with 17 digits with ascii=True; every
        property), or for a mesh ``.off`` or ``.obj`` (positions, normals and faces only).
    points : array_like, shape (N, 3)
    normals : array_like, shape (N, 3), optional
    faces : array_like of vertex indices, optional
        (F, 3) for triangles, or a sequence of sequences for any polygons.
    properties : dict of str to array_like of shape (N,), optional
        More per-point numbers, written as PLY properties of type double.
    ascii : bool
        ASCII PLY instead of binary.
    """
    points = _coordinates(points, "points")
    if normals is not None:
        normals = _coordinates(normals, "normals", points.shape[0])
    if faces is not None:
        faces = [[int(v) for v in face] for face in (faces.tolist() if isinstance(faces, np.ndarray) else faces)]
        if any(min(face, default=0) < 0 for face in faces):
            raise ValueError("faces: negative vertex index")
    _wavejets.write(os.fspath(path), points, normals, faces, dict(properties or {}), bool(ascii))
