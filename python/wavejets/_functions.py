"""The point-set functions and the single fit, on NumPy arrays.

Each function checks and converts its arguments here, then calls the C++ function of the same
name (``CGAL::wavejet_estimate_normals`` and so on, through ``wavejets._wavejets``) with
``Parallel_tag``. The defaults shown in the signatures are read from the C++ headers.
"""

import math
import numbers
import sys
import time
from dataclasses import dataclass

import numpy as np

from . import _wavejets

_DEFAULTS = {name: _wavejets.defaults(name) for name in
             ("estimate_normals", "estimate_curvatures", "enhance_positions", "enhance_normals")}


def _default(function, key):
    return _DEFAULTS[function][key]


# --------------------------------------------------------------------------------------------
# Documentation of the keyword arguments, shared by the functions that take them.
_DOC = {
    "points": "points : array_like, shape (N, 3)\n"
              "    The point coordinates. A float64 C-contiguous array is read in place (no copy);\n"
              "    any other real dtype or layout is converted once. Never modified.",
    "normals": "normals : array_like, shape (N, 3), optional\n"
               "    Input normals (need not be unit). When given they orient the frames, so the\n"
               "    results have the normals' side (curvature signs, heights, normal directions).",
    "k": "k : int, array_like of N ints, or 'auto', optional\n"
         "    Number of nearest neighbors of each fit (the point excluded); default 40, or 1.5 x the\n"
         "    (K+1)(K+2)/2 coefficients of order K when that is more. With neighbor_radius: the\n"
         "    maximum number of neighbors kept in the radius (0: no limit). An array gives each\n"
         "    point its own k (0: the default k of the highest order asked); 'auto' chooses each\n"
         "    point's k with estimate_scales(points, order=order) first.",
    "order": "order : int, or array_like of N ints\n"
             "    The Wavejet order K (>= 1), lowered per point where the neighbors cannot support it.\n"
             "    An array gives each point its own order (0: the function's default order).",
    "neighbor_radius": "neighbor_radius : float, or array_like of N floats\n"
                       "    A fixed neighborhood radius Rf (model units) instead of the k nearest neighbors;\n"
                       "    0 uses k nearest neighbors, Rf being the distance to the farthest. An array\n"
                       "    gives each point its own radius (0: its k nearest neighbors); each point's k\n"
                       "    caps the neighbors kept in its radius (k=0, one integer: no limit).",
    "neighbors_per_coefficient": "neighbors_per_coefficient : float\n"
                                 "    Adaptive order: K is lowered until a neighborhood has this many points per\n"
                                 "    coefficient (>= 1).",
    "minimum_order": "minimum_order : int\n"
                     "    Lowest acceptable order; a point that cannot be fitted at it is not fitted.",
    "correction_iterations": "correction_iterations : int\n"
                             "    Re-fits in the corrected tangent plane (0: none).",
    "tangent_plane_order": "tangent_plane_order : int\n"
                           "    Order of the fits that find the tangent plane (0: the full order).",
    "robust_iterations": "robust_iterations : int\n"
                         "    Tukey IRLS passes per fit, for outliers (0: plain least squares).",
    "seed_with_input_normals": "seed_with_input_normals : bool\n"
                               "    Do the first fit in the plane orthogonal to the input normal (needs normals).",
    "restrict_to_consistent_normals": "restrict_to_consistent_normals : bool\n"
                                      "    Leave out the neighbors whose input normal is more than 90 degrees from the\n"
                                      "    point's (the other side of a thin part; needs oriented normals).",
    "use_neighbor_normals": "use_neighbor_normals : bool\n"
                            "    Hermite fit: fit the heights and the slopes given by the neighbors' normals\n"
                            "    (the input normals; without them the function estimates them first). Several\n"
                            "    times more precise curvature on noisy scans.",
    "neighbor_normal_weight": "neighbor_normal_weight : float\n"
                              "    Weight of the slope equations of the Hermite fit (> 0).",
    "compact_weights": "compact_weights : bool\n"
                       "    Weight each neighbor by (1 - d^2/Rf^2)^2 instead of 1.",
    "curvature_frame": "curvature_frame : {'initial', 'tangent'}\n"
                       "    Read the curvatures from the first fit (PCA frame, as CGAL's Monge jets) or from\n"
                       "    the fit in the corrected tangent frame.",
    "gain": "gain : float\n"
            "    Filter gain: > 1 amplifies the details, 1 projects on the Wavejet, [0, 1) flattens,\n"
            "    < 0 inverts.",
    "complex_gain": "gain : complex\n"
                    "    Filter gain: > 1 exaggerates the shading detail, 0 blurs, < 0 inverts; an imaginary\n"
                    "    part twists the normals (2j: a twist of gain 2).",
    "evaluation_radius": "evaluation_radius : float\n"
                         "    Radius s of the enclosed-area coefficients a_n(s), model units (0: Rf of each point).",
    "maximum_displacement": "maximum_displacement : float, optional\n"
                            "    Clamp of each point's motion, model units (default: Rf/2 of each point;\n"
                            "    math.inf: no clamp).",
    "write_normals": "write_normals : bool\n"
                     "    Also return the Wavejet normals of the input points: (points, normals).",
    "move_along_input_normals": "move_along_input_normals : bool\n"
                                "    Move each point along its input normal instead of its Wavejet normal\n"
                                "    (needs normals; for noisy inputs, after enhance_normals(gain=0)).",
    "threads": "threads : int, optional\n"
               "    Worker threads (default: all cores). Every thread count gives the same bits.",
    "progress": "progress : bool or callable\n"
                "    True draws a progress bar on stderr; a callable is called with the fraction done.",
    "return_report": "return_report : bool\n"
                     "    Also return a wavejets.Report: counts of fitted, unfitted, reduced-order and\n"
                     "    clamped points, and the per-point `fitted` flags.",
}

_COMMON = ("k", "order", "neighbor_radius", "neighbors_per_coefficient", "minimum_order",
           "correction_iterations", "tangent_plane_order", "robust_iterations",
           "seed_with_input_normals", "restrict_to_consistent_normals", "use_neighbor_normals",
           "neighbor_normal_weight", "compact_weights")
_TAIL = ("threads", "progress", "return_report")


def _document(summary, arguments, returns, details=""):
    """Attaches a NumPy-style docstring built from _DOC to the decorated function."""
    def decorate(function):
        text = summary.strip() + "\n\n"
        if details:
            text += details.strip() + "\n\n"
        text += "Parameters\n----------\n" + "\n".join(_DOC[a] for a in arguments)
        text += "\n\nReturns\n-------\n" + returns.strip() + "\n\nRaises\n------\n" + \
            "ValueError\n    A bad shape, a NaN or infinite coordinate, a value out of range.\n" + \
            "TypeError\n    An argument of the wrong type (e.g. a complex gain for positions).\n" + \
            "KeyboardInterrupt\n    Ctrl-C stops the computation; nothing is returned.\n"
        function.__doc__ = text
        return function
    return decorate


# --------------------------------------------------------------------------------------------
# Checks and conversions.
def _coordinates(a, name, rows=None):
    """An (N, 3) float64 C-contiguous array: `a` itself when it is one, else one converted copy."""
    if a is None:
        raise TypeError(f"{name}: expected an (N, 3) array of numbers, got None")
    array = np.asarray(a)
    if array.dtype.kind not in "biuf":
        raise TypeError(f"{name}: expected real numbers, got dtype {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(f"{name}: expected an (N, 3) array, got shape {array.shape}")
    if rows is not None and array.shape[0] != rows:
        raise ValueError(f"{name}: expected {rows} rows (one per point), got {array.shape[0]}")
    if array.dtype != np.float64 or not array.flags.c_contiguous:
        array = np.ascontiguousarray(array, dtype=np.float64)
    return array


def _integer(value, name, minimum):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name}: expected an integer, got {type(value).__name__}")
    if value < minimum:
        raise ValueError(f"{name}: must be >= {minimum}, got {value}")
    return int(value)


def _real(value, name, minimum=None, allow_infinity=False):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name}: expected a real number, got {type(value).__name__}")
    value = float(value)
    if math.isnan(value) or (math.isinf(value) and not allow_infinity):
        raise ValueError(f"{name}: must be finite, got {value}")
    if minimum is not None and value < minimum:
        raise ValueError(f"{name}: must be >= {minimum}, got {value}")
    return value


def _flag(value, name):
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: expected True or False, got {type(value).__name__}")
    return bool(value)


class _ProgressBar:
    """The bar drawn on stderr with progress=True."""

    def __init__(self, label):
        self.label, self.start, self.last = label, time.monotonic(), -1

    def __call__(self, fraction):
        percent = int(100 * min(max(fraction, 0.0), 1.0))
        if percent == self.last:
            return
        self.last = percent
        full = percent * 30 // 100
        sys.stderr.write(f"\r{self.label:<30} [{'#' * full}{'.' * (30 - full)}] {percent:3d}%  "
                         f"{time.monotonic() - self.start:5.1f} s" + ("\n" if percent == 100 else ""))
        sys.stderr.flush()


def _per_point_counts(value, name, n):
    """A per-point k or order: an (N,) uint32 C-contiguous array of integers >= 0."""
    array = np.asarray(value)
    if array.dtype.kind not in "biu" or array.dtype.kind == "b":
        raise TypeError(f"{name}: expected integers, got dtype {array.dtype}")
    if array.shape != (n,):
        raise ValueError(f"{name}: expected one value per point, shape ({n},), got shape {array.shape}")
    if n > 0 and (array.min() < 0 or array.max() > np.iinfo(np.uint32).max):
        raise ValueError(f"{name}: every value must be >= 0 (0: the default) and fit in 32 bits")
    return np.ascontiguousarray(array, dtype=np.uint32)


def _per_point_radii(value, n):
    """A per-point neighbor_radius: an (N,) float64 C-contiguous array of finite reals >= 0."""
    array = np.asarray(value)
    if array.dtype.kind not in "iuf":
        raise TypeError(f"neighbor_radius: expected real numbers, got dtype {array.dtype}")
    if array.shape != (n,):
        raise ValueError(f"neighbor_radius: expected one value per point, shape ({n},), got shape {array.shape}")
    array = np.ascontiguousarray(array, dtype=np.float64)
    if n > 0 and not (np.isfinite(array).all() and array.min() >= 0):
        raise ValueError("neighbor_radius: every value must be finite and >= 0 (0: the k nearest neighbors)")
    return array


def _progress(progress, label):
    if progress is True:
        return _ProgressBar(label)
    if progress is False or progress is None:
        return None
    if not callable(progress):
        raise TypeError("progress: expected True, False or a callable taking the fraction done")
    return progress


def _check_count(k, n, name):
    if k < 2:
        raise ValueError(f"{name}: must be >= 2 (or give a neighbor_radius), got {k}")
    if n > 0 and k > n - 1:
        raise ValueError(f"{name}: {k} neighbors asked, but the {n} points give each point at most {n - 1}")


def _settings(function, points, normals, k, order, neighbor_radius, threads, progress, options):
    """The keyword arguments of the compiled call, checked. k='auto' is kept as is (see _auto_k)."""
    n = points.shape[0]
    settings = {}
    if np.ndim(order) == 0:
        order = _integer(order, "order", 1)
    else:
        settings["order_per_point"] = _per_point_counts(order, "order", n)
        order = _default(function, "order")
    if np.ndim(neighbor_radius) == 0:
        neighbor_radius = _real(neighbor_radius, "neighbor_radius", 0.0)
        uses_k = None if neighbor_radius == 0.0 else np.zeros(n, dtype=bool)   # None: every point
    else:
        settings["radius_per_point"] = _per_point_radii(neighbor_radius, n)
        neighbor_radius = 0.0
        uses_k = settings["radius_per_point"] == 0.0
    if isinstance(k, str):
        if k != "auto":
            raise ValueError(f"k: expected an integer, an array of integers or 'auto', got {k!r}")
        if neighbor_radius > 0 or "radius_per_point" in settings:
            raise ValueError("k: 'auto' chooses numbers of neighbors; it excludes neighbor_radius")
        if "order_per_point" in settings:
            raise ValueError("k: 'auto' chooses the neighbors for one order; give order as one integer")
        settings["k_auto"] = True
        k = None
    # The default k suits the highest order asked (with an order per point, that of every point).
    highest_order = max(order, int(settings["order_per_point"].max())) if "order_per_point" in settings and n > 0 \
        else order
    if k is None:
        k = _wavejets.default_k(highest_order)
    # The k of the points searched by k nearest neighbors (those without a radius) must be >= 2.
    if np.ndim(k) == 0:
        k = _integer(k, "k", 0)
        if uses_k is None or (n > 0 and uses_k.any()):
            _check_count(k, n, "k")
    else:
        counts = _per_point_counts(k, "k", n)
        settings["k_per_point"] = counts
        k = _wavejets.default_k(highest_order)
        effective = np.where(counts > 0, counts, k)   # 0: the default k
        if uses_k is not None:
            effective = effective[uses_k]
        if effective.size > 0:
            _check_count(int(effective.min()), n, "k")
            _check_count(int(effective.max()), n, "k")
    if threads is not None:
        threads = _integer(threads, "threads", 1)
    progress = _progress(progress, f"wavejets.{function}")
    settings.update(k=k, order=order, neighbor_radius=neighbor_radius, threads=threads, progress=progress)
    for name, value in options.items():
        if name in ("seed_with_input_normals", "restrict_to_consistent_normals", "use_neighbor_normals",
                    "compact_weights", "write_normals", "move_along_input_normals"):
            value = _flag(value, name)
            if value and normals is None and name in ("seed_with_input_normals", "restrict_to_consistent_normals",
                                                      "move_along_input_normals"):
                raise ValueError(f"normals: {name}=True needs the input normals")
        elif name in ("minimum_order", "correction_iterations", "tangent_plane_order", "robust_iterations"):
            value = _integer(value, name, 0)
        elif name == "neighbors_per_coefficient":
            value = _real(value, name, 1.0)
        elif name == "neighbor_normal_weight":
            value = _real(value, name)
            if not value > 0:
                raise ValueError(f"neighbor_normal_weight: must be > 0, got {value}")
        elif name == "evaluation_radius":
            value = _real(value, name, 0.0)
        settings[name] = value
    return settings


def _auto_k(points, settings, progress):
    """With k='auto': each point's k from estimate_scales at the call's order (as the tool's --k auto)."""
    if not settings.pop("k_auto", False):
        return settings
    scales = estimate_scales(points, order=settings["order"], threads=settings["threads"], progress=progress)
    settings["k_per_point"] = np.ascontiguousarray(scales.k, dtype=np.uint32)  # 0 (unfitted): the default k
    return settings


def _points_and_normals(points, normals):
    points = _coordinates(points, "points")
    if normals is not None:
        normals = _coordinates(normals, "normals", points.shape[0])
    return points, normals


def _with_report(result, report, return_report):
    return (result, report) if return_report else result


# --------------------------------------------------------------------------------------------
# The functions.
@_document("Estimates the normal of every point: the normal of its Wavejet at the point.",
           ("points", "normals") + _COMMON + _TAIL,
           "normals : ndarray, shape (N, 3)\n    Unit normals, oriented like `normals` when given (else each\n"
           "    has the arbitrary sign of its fit). A point that could not be fitted keeps its input\n"
           "    normal, or (0, 0, 0) without one (see return_report).",
           "The counterpart of CGAL's jet_estimate_normals, with the tangent-plane correction; the\n"
           "C++ function CGAL::wavejet_estimate_normals.")
def estimate_normals(points, normals=None, *, k=None, order=_default("estimate_normals", "order"),
                     neighbor_radius=0.0,
                     neighbors_per_coefficient=_default("estimate_normals", "neighbors_per_coefficient"),
                     minimum_order=_default("estimate_normals", "minimum_order"),
                     correction_iterations=_default("estimate_normals", "correction_iterations"),
                     tangent_plane_order=_default("estimate_normals", "tangent_plane_order"),
                     robust_iterations=_default("estimate_normals", "robust_iterations"),
                     seed_with_input_normals=False, restrict_to_consistent_normals=False,
                     use_neighbor_normals=False,
                     neighbor_normal_weight=_default("estimate_normals", "neighbor_normal_weight"),
                     compact_weights=_default("estimate_normals", "compact_weights"),
                     threads=None, progress=False, return_report=False):
    points, normals = _points_and_normals(points, normals)
    settings = _settings("estimate_normals", points, normals, k, order, neighbor_radius, threads, progress, dict(
        neighbors_per_coefficient=neighbors_per_coefficient, minimum_order=minimum_order,
        correction_iterations=correction_iterations, tangent_plane_order=tangent_plane_order,
        robust_iterations=robust_iterations, seed_with_input_normals=seed_with_input_normals,
        restrict_to_consistent_normals=restrict_to_consistent_normals, use_neighbor_normals=use_neighbor_normals,
        neighbor_normal_weight=neighbor_normal_weight, compact_weights=compact_weights))
    settings["orient_with_input_normals"] = normals is not None
    result, report = _wavejets.estimate_normals(points, normals, _auto_k(points, settings, progress))
    return _with_report(result, report, return_report)


@dataclass(frozen=True)
class Curvatures:
    """The curvatures of every point (`estimate_curvatures`). Signs are relative to the normal
    (the input normals' side when given): bending toward it is positive, so a sphere with
    outward normals has H = -1/R. Unfitted points have zeros and fitted[i] == False."""

    mean_curvature: np.ndarray       #: H = (k1 + k2) / 2, shape (N,)
    gaussian_curvature: np.ndarray   #: K = k1 k2, shape (N,)
    k1: np.ndarray                   #: maximal principal curvature, shape (N,)
    k2: np.ndarray                   #: minimal principal curvature, shape (N,)
    d1: np.ndarray                   #: unit direction of k1, shape (N, 3)
    d2: np.ndarray                   #: unit direction of k2, shape (N, 3)
    fitted: np.ndarray               #: whether a Wavejet was fitted, shape (N,), bool


@_document("Estimates the mean, Gaussian and principal curvatures and the principal directions.",
           ("points", "normals") + _COMMON + ("curvature_frame",) + _TAIL,
           "curvatures : wavejets.Curvatures\n    mean_curvature, gaussian_curvature, k1, k2 (N,), d1, d2 (N, 3), fitted (N,).",
           "The C++ function CGAL::wavejet_estimate_curvatures. With the default curvature_frame the\n"
           "curvature is read from the same least-squares problem as CGAL's Monge_via_jet_fitting.")
def estimate_curvatures(points, normals=None, *, k=None, order=_default("estimate_curvatures", "order"),
                        neighbor_radius=0.0,
                        neighbors_per_coefficient=_default("estimate_curvatures", "neighbors_per_coefficient"),
                        minimum_order=_default("estimate_curvatures", "minimum_order"),
                        correction_iterations=_default("estimate_curvatures", "correction_iterations"),
                        tangent_plane_order=_default("estimate_curvatures", "tangent_plane_order"),
                        robust_iterations=_default("estimate_curvatures", "robust_iterations"),
                        seed_with_input_normals=False, restrict_to_consistent_normals=False,
                        use_neighbor_normals=False,
                        neighbor_normal_weight=_default("estimate_curvatures", "neighbor_normal_weight"),
                        compact_weights=_default("estimate_curvatures", "compact_weights"),
                        curvature_frame=_default("estimate_curvatures", "curvature_frame"),
                        threads=None, progress=False, return_report=False):
    points, normals = _points_and_normals(points, normals)
    if curvature_frame not in ("initial", "tangent"):
        raise ValueError(f"curvature_frame: expected 'initial' or 'tangent', got {curvature_frame!r}")
    settings = _settings("estimate_curvatures", points, normals, k, order, neighbor_radius, threads, progress, dict(
        neighbors_per_coefficient=neighbors_per_coefficient, minimum_order=minimum_order,
        correction_iterations=correction_iterations, tangent_plane_order=tangent_plane_order,
        robust_iterations=robust_iterations, seed_with_input_normals=seed_with_input_normals,
        restrict_to_consistent_normals=restrict_to_consistent_normals, use_neighbor_normals=use_neighbor_normals,
        neighbor_normal_weight=neighbor_normal_weight, compact_weights=compact_weights))
    settings["curvature_frame"] = curvature_frame
    values, report = _wavejets.estimate_curvatures(points, normals, _auto_k(points, settings, progress))
    return _with_report(Curvatures(fitted=report.fitted, **values), report, return_report)


@_document("Enhances, flattens or inverts the surface details by moving every point along its normal.",
           ("points", "normals", "gain") + _COMMON + ("evaluation_radius", "maximum_displacement",
                                                      "write_normals", "move_along_input_normals") + _TAIL,
           "points : ndarray, shape (N, 3)\n    The moved points (a point that could not be fitted does not move);\n"
           "    with write_normals, (points, normals).",
           "p' = p + (f_00 - 2 pi (gain - 1) a_0(s) / Rf^2) n in the tangent frame of p (Bearzi et al. 2018,\n"
           "Algorithm 1); every motion is computed from the input, then all points move at once. The C++\n"
           "function CGAL::wavejet_enhance_positions.")
def enhance_positions(points, normals=None, k=None, gain=_default("enhance_positions", "gain"), *,
                      order=_default("enhance_positions", "order"), neighbor_radius=0.0,
                      neighbors_per_coefficient=_default("enhance_positions", "neighbors_per_coefficient"),
                      minimum_order=_default("enhance_positions", "minimum_order"),
                      correction_iterations=_default("enhance_positions", "correction_iterations"),
                      tangent_plane_order=_default("enhance_positions", "tangent_plane_order"),
                      robust_iterations=_default("enhance_positions", "robust_iterations"),
                      seed_with_input_normals=False, restrict_to_consistent_normals=False,
                      use_neighbor_normals=False,
                      neighbor_normal_weight=_default("enhance_positions", "neighbor_normal_weight"),
                      compact_weights=_default("enhance_positions", "compact_weights"),
                      evaluation_radius=0.0, maximum_displacement=None, write_normals=False,
                      move_along_input_normals=False, threads=None, progress=False, return_report=False):
    points, normals = _points_and_normals(points, normals)
    if isinstance(gain, numbers.Complex) and not isinstance(gain, numbers.Real):
        raise TypeError("gain: enhance_positions takes a real gain (complex gains twist normals: enhance_normals)")
    gain = _real(gain, "gain")
    if maximum_displacement is not None:
        maximum_displacement = _real(maximum_displacement, "maximum_displacement", allow_infinity=True)
        if not maximum_displacement > 0:
            raise ValueError(f"maximum_displacement: must be > 0 (math.inf: no clamp), got {maximum_displacement}")
    settings = _settings("enhance_positions", points, normals, k, order, neighbor_radius, threads, progress, dict(
        neighbors_per_coefficient=neighbors_per_coefficient, minimum_order=minimum_order,
        correction_iterations=correction_iterations, tangent_plane_order=tangent_plane_order,
        robust_iterations=robust_iterations, seed_with_input_normals=seed_with_input_normals,
        restrict_to_consistent_normals=restrict_to_consistent_normals, use_neighbor_normals=use_neighbor_normals,
        neighbor_normal_weight=neighbor_normal_weight, compact_weights=compact_weights,
        evaluation_radius=evaluation_radius, write_normals=write_normals,
        move_along_input_normals=move_along_input_normals))
    if write_normals and use_neighbor_normals and normals is None:
        raise ValueError("normals: use_neighbor_normals with write_normals needs the input normals")
    settings.update(gain=gain, maximum_displacement=maximum_displacement)
    moved, wavejet_normals, report = _wavejets.enhance_positions(points, normals, _auto_k(points, settings, progress))
    result = (moved, wavejet_normals) if write_normals else moved
    return _with_report(result, report, return_report)


@_document("Enhances, blurs, inverts or twists the shading detail by tilting every normal.",
           ("points", "normals", "complex_gain") + _COMMON + ("evaluation_radius",) + _TAIL,
           "normals : ndarray, shape (N, 3)\n    The filtered unit normals (a point that could not be fitted keeps its\n"
           "    input normal, or (0, 0, 0) without one).",
           "The C++ function CGAL::wavejet_enhance_normals: the normal of the Wavejet whose tilt is\n"
           "gain times a_{+-1}(s) (Bearzi et al. 2018, section 5).")
def enhance_normals(points, normals=None, k=None, gain=_default("enhance_normals", "gain"), *,
                    order=_default("enhance_normals", "order"), neighbor_radius=0.0,
                    neighbors_per_coefficient=_default("enhance_normals", "neighbors_per_coefficient"),
                    minimum_order=_default("enhance_normals", "minimum_order"),
                    correction_iterations=_default("enhance_normals", "correction_iterations"),
                    tangent_plane_order=_default("enhance_normals", "tangent_plane_order"),
                    robust_iterations=_default("enhance_normals", "robust_iterations"),
                    seed_with_input_normals=False, restrict_to_consistent_normals=False,
                    use_neighbor_normals=False,
                    neighbor_normal_weight=_default("enhance_normals", "neighbor_normal_weight"),
                    compact_weights=_default("enhance_normals", "compact_weights"),
                    evaluation_radius=0.0, threads=None, progress=False, return_report=False):
    points, normals = _points_and_normals(points, normals)
    if not isinstance(gain, numbers.Complex) or isinstance(gain, bool):
        raise TypeError(f"gain: expected a real or complex number, got {type(gain).__name__}")
    gain = complex(gain)
    if not (math.isfinite(gain.real) and math.isfinite(gain.imag)):
        raise ValueError(f"gain: must be finite, got {gain}")
    settings = _settings("enhance_normals", points, normals, k, order, neighbor_radius, threads, progress, dict(
        neighbors_per_coefficient=neighbors_per_coefficient, minimum_order=minimum_order,
        correction_iterations=correction_iterations, tangent_plane_order=tangent_plane_order,
        robust_iterations=robust_iterations, seed_with_input_normals=seed_with_input_normals,
        restrict_to_consistent_normals=restrict_to_consistent_normals, use_neighbor_normals=use_neighbor_normals,
        neighbor_normal_weight=neighbor_normal_weight, compact_weights=compact_weights,
        evaluation_radius=evaluation_radius))
    settings["gain"] = gain
    result, report = _wavejets.enhance_normals(points, normals, _auto_k(points, settings, progress))
    return _with_report(result, report, return_report)


@dataclass(frozen=True)
class Scales:
    """Each point's neighborhood size chosen from a ladder of sizes (`estimate_scales`).

    Pass `k` to any function as its k (with the same order): each point is then fitted with its own
    number of neighbors. Unfitted points have k == 0 (which the functions read as their default k)
    and fitted[i] == False."""

    k: np.ndarray                    #: the chosen number of neighbors of each point, shape (N,), int64
    neighborhood_sizes: np.ndarray   #: the ladder the sizes were chosen from, shape (J,), int64
    descriptor: np.ndarray           #: |f_2| (1/length) of each point's Wavejet at each size, shape (N, J)
    fitted: np.ndarray               #: whether a size was chosen, shape (N,), bool


def estimate_scales(points, *, order=_default("estimate_normals", "order"), neighborhood_sizes=None,
                    neighbors_per_coefficient=_default("estimate_normals", "neighbors_per_coefficient"),
                    minimum_order=_default("estimate_normals", "minimum_order"),
                    correction_iterations=_default("estimate_normals", "correction_iterations"),
                    tangent_plane_order=_default("estimate_normals", "tangent_plane_order"),
                    robust_iterations=_default("estimate_normals", "robust_iterations"),
                    compact_weights=_default("estimate_normals", "compact_weights"),
                    threads=None, progress=False, return_report=False):
    """Chooses each point's number of neighbors among a ladder of sizes.

    Each point is fitted to the nested prefixes of its nearest neighbors (one k-nearest query at
    the largest size); the size kept is the one of least estimated normal error: a variance term
    (the noise, the smallest residual variance over the ladder, over the size and radius) plus a
    bias term (the residual the noise does not explain, over the radius squared). Noisy parts get
    large sizes, fine details small ones. The C++ function CGAL::wavejet_estimate_scales; the
    functions' k='auto' calls it. What to expect (measured accuracy against one well-chosen k): the
    user manual, "Choosing the scale per point".

    Parameters
    ----------
    points : array_like, shape (N, 3)
        The point coordinates, as in estimate_normals.
    order : int
        The Wavejet order K of the fits (>= 1); use the same order in the function that takes the sizes.
    neighborhood_sizes : array_like of ints, optional
        The ladder: increasing numbers of neighbors, each >= 2 (default: 7 sizes growing by 2^(2/3)
        from max(10, 1.5 x the coefficients of order K): 10 ... 160 at order 2).
    neighbors_per_coefficient, minimum_order, correction_iterations, tangent_plane_order,
    robust_iterations, compact_weights
        The fit settings, as in estimate_normals.
    threads, progress, return_report
        As in estimate_normals.

    Returns
    -------
    scales : wavejets.Scales
        k (N,), neighborhood_sizes (J,), descriptor (N, J), fitted (N,).

    Raises
    ------
    ValueError
        A bad shape, a NaN or infinite coordinate, a ladder that is empty, not increasing or has a
        size below 2 or above N - 1.
    TypeError
        An argument of the wrong type.
    KeyboardInterrupt
        Ctrl-C stops the computation; nothing is returned.
    """
    points = _coordinates(points, "points")
    n = points.shape[0]
    order = _integer(order, "order", 1)
    settings = dict(order=order, threads=None if threads is None else _integer(threads, "threads", 1),
                    progress=_progress(progress, "wavejets.estimate_scales"),
                    neighbors_per_coefficient=_real(neighbors_per_coefficient, "neighbors_per_coefficient", 1.0),
                    minimum_order=_integer(minimum_order, "minimum_order", 0),
                    correction_iterations=_integer(correction_iterations, "correction_iterations", 0),
                    tangent_plane_order=_integer(tangent_plane_order, "tangent_plane_order", 0),
                    robust_iterations=_integer(robust_iterations, "robust_iterations", 0),
                    compact_weights=_flag(compact_weights, "compact_weights"))
    if neighborhood_sizes is not None:
        ladder = np.asarray(neighborhood_sizes)
        if ladder.size == 0:
            raise ValueError("neighborhood_sizes: expected a non-empty list of sizes")
        if ladder.dtype.kind not in "iu":
            raise TypeError(f"neighborhood_sizes: expected integers, got dtype {ladder.dtype}")
        if ladder.ndim != 1 or ladder.size == 0:
            raise ValueError(f"neighborhood_sizes: expected a non-empty list of sizes, got shape {ladder.shape}")
        if ladder.min() < 2 or np.any(np.diff(ladder) <= 0):
            raise ValueError(f"neighborhood_sizes: must increase, each >= 2, got {ladder.tolist()}")
        settings["neighborhood_sizes"] = [int(size) for size in ladder]
    if n > 0:
        largest = (settings.get("neighborhood_sizes") or _wavejets.default_neighborhood_sizes(order))[-1]
        if largest > n - 1:
            raise ValueError(f"neighborhood_sizes: {largest} neighbors asked, but the {n} points give each point "
                             f"at most {n - 1}")
    k, sizes, descriptor, report = _wavejets.estimate_scales(points, settings)
    return _with_report(Scales(k=k, neighborhood_sizes=sizes, descriptor=descriptor, fitted=report.fitted),
                        report, return_report)


def fit(neighbors, order=2, normal=None, neighbor_normals=None, *, neighborhood_radius=0.0,
        neighbors_per_coefficient=_default("estimate_curvatures", "neighbors_per_coefficient"),
        minimum_order=_default("estimate_curvatures", "minimum_order"),
        correction_iterations=_default("estimate_curvatures", "correction_iterations"),
        tangent_plane_order=_default("estimate_curvatures", "tangent_plane_order"),
        robust_iterations=_default("estimate_curvatures", "robust_iterations"),
        seed_with_input_normals=False,
        neighbor_normal_weight=_default("estimate_curvatures", "neighbor_normal_weight"),
        compact_weights=_default("estimate_curvatures", "compact_weights"),
        curvature_frame=_default("estimate_curvatures", "curvature_frame")):
    """Fits one Wavejet (CGAL::Wavejet_fitting) at the first of `neighbors`.

    Parameters
    ----------
    neighbors : array_like, shape (L, 3)
        The point where the Wavejet is computed (first row), then its neighbors.
    order : int
        The requested order K (>= 1), lowered while the L points cannot support it.
    normal : array_like, shape (3,), optional
        A normal at the first point: it orients the frame (or seeds it, with
        seed_with_input_normals=True).
    neighbor_normals : array_like, shape (L, 3), optional
        Normals of all L points: the Hermite fit (heights and slopes); the first one orients.
    neighborhood_radius : float
        Rf, the radius the coordinates are divided by (0: the distance to the farthest neighbor).
    neighbors_per_coefficient, minimum_order, correction_iterations, tangent_plane_order,
    robust_iterations, neighbor_normal_weight, compact_weights, curvature_frame
        As in estimate_curvatures.

    Returns
    -------
    wavejet : wavejets.Wavejet
        Its coefficients f_{k,n} (`coefficient(k, n)`), a_n(s) (`enclosed_area_coefficient(n, s)`),
        normal, tangent frame (u, v, frame_normal), curvatures and principal directions; `status`
        says why a fit failed (then `is_valid` is False). A failed fit is not an error.
    """
    neighbors = _coordinates(neighbors, "neighbors")
    if neighbors.shape[0] == 0:
        raise ValueError("neighbors: empty (the first row is the point where the Wavejet is computed)")
    order = _integer(order, "order", 1)
    if normal is not None:
        normal = np.ascontiguousarray(normal, dtype=np.float64)
        if normal.shape != (3,):
            raise ValueError(f"normal: expected 3 numbers, got shape {normal.shape}")
    if neighbor_normals is not None:
        neighbor_normals = _coordinates(neighbor_normals, "neighbor_normals", neighbors.shape[0])
    if curvature_frame not in ("initial", "tangent"):
        raise ValueError(f"curvature_frame: expected 'initial' or 'tangent', got {curvature_frame!r}")
    settings = dict(
        neighborhood_radius=_real(neighborhood_radius, "neighborhood_radius", 0.0),
        neighbors_per_coefficient=_real(neighbors_per_coefficient, "neighbors_per_coefficient", 1.0),
        minimum_order=_integer(minimum_order, "minimum_order", 0),
        correction_iterations=_integer(correction_iterations, "correction_iterations", 0),
        tangent_plane_order=_integer(tangent_plane_order, "tangent_plane_order", 0),
        robust_iterations=_integer(robust_iterations, "robust_iterations", 0),
        seed_with_input_normals=_flag(seed_with_input_normals, "seed_with_input_normals"),
        neighbor_normal_weight=_real(neighbor_normal_weight, "neighbor_normal_weight"),
        compact_weights=_flag(compact_weights, "compact_weights"), curvature_frame=curvature_frame)
    return _wavejets.fit(neighbors, order, normal, neighbor_normals, settings)
