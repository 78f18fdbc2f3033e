"""Reading and writing point sets and meshes through CGAL's IO (the `wavejets` tool's reader and
writer), and drawing them into PNG pictures (the tool's renderer)."""

import os

import numpy as np

from . import _wavejets
from ._functions import _coordinates, _integer, _real, estimate_normals


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
    _wavejets.write(os.fspath(path), points, normals, _faces(faces, points.shape[0]), dict(properties or {}), bool(ascii))


def _faces(faces, number_of_points):
    """`faces` as lists of vertex indices, checked against the number of points (None stays None)."""
    if faces is None:
        return None
    faces = [[int(v) for v in face] for face in (faces.tolist() if isinstance(faces, np.ndarray) else faces)]
    for f, face in enumerate(faces):
        if any(v < 0 or v >= number_of_points for v in face):
            raise ValueError(f"faces: face {f} refers to a vertex outside 0..{number_of_points - 1}: {face}")
    return faces


def _direction(value, name):
    direction = np.asarray(value, dtype=np.float64)
    if direction.shape != (3,) or not np.all(np.isfinite(direction)) or not np.any(direction):
        raise ValueError(f"{name}: expected three finite numbers, not all zero, got {value!r}")
    return [float(x) for x in direction]


def render(path, points, normals=None, faces=None, values=None, *, width=800, height=800,
           view=(0.0, 0.0, 1.0), up=(0.0, 1.0, 0.0), splat=1.2):
    """Draws a point set or a mesh into a PNG picture (the renderer of the ``wavejets render`` tool).

    An orthographic view with one light: a mesh as smooth-shaded triangles, a point set as splats
    on its tangent planes. With `values`, the surface is coloured by them with a diverging map
    symmetric around 0 (blue negative, red positive, white 0, saturated at the 95th percentile of
    |value|), e.g. a mean curvature; without, one material colour. The file at `path` is replaced
    only once the picture is complete.

    Parameters
    ----------
    path : str or os.PathLike
        The PNG file to write.
    points : array_like, shape (N, 3)
    normals : array_like, shape (N, 3), optional
        Used for shading only (their orientation does not matter). Without them: the faces' vertex
        normals for a mesh, ``estimate_normals(points, k=18)`` for a point set.
    faces : array_like of vertex indices, optional
        (F, 3) for triangles, or a sequence of sequences for any polygons: the points are then the
        vertices of a mesh.
    values : array_like, shape (N,), optional
        One finite number per point, mapped to colours.
    width, height : int
        Size of the picture in pixels.
    view : 3 numbers
        Direction from the object toward the camera (the default looks down the -z axis).
    up : 3 numbers
        World direction shown upward.
    splat : float
        Splat radius in average point spacings (point sets).

    Raises
    ------
    ValueError
        A wrong shape, a NaN or infinite number, a face outside the points, an unwritable path.
    """
    points = _coordinates(points, "points")
    n = points.shape[0]
    if n == 0:
        raise ValueError("points: nothing to draw (0 points)")
    faces = _faces(faces, n)
    if normals is not None:
        normals = _coordinates(normals, "normals", n)
    elif faces is None:
        normals = estimate_normals(points, k=min(18, n - 1)) if n > 1 else np.array([[0.0, 0.0, 1.0]])
    if values is not None:
        values = np.ascontiguousarray(values, dtype=np.float64)
        if values.shape != (n,):
            raise ValueError(f"values: expected {n} numbers (one per point), got shape {values.shape}")
        if not np.all(np.isfinite(values)):
            raise ValueError(f"values: NaN or infinite at point {int(np.flatnonzero(~np.isfinite(values))[0])}")
        values = values.tolist()
    _wavejets.render(os.fspath(path), points, normals, faces, values, _integer(width, "width", 1),
                     _integer(height, "height", 1), _direction(view, "view"), _direction(up, "up"),
                     _real(splat, "splat", 0.0))
