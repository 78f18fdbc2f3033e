"""Bad input raises ValueError or TypeError with a message naming the argument: never a crash,
never a silent NaN."""

import math

import numpy as np
import pytest

import wavejets
from conftest import sphere

POINTS, NORMALS = sphere(500)
WITH_NAN = POINTS.copy()
WITH_NAN[17, 1] = np.nan
WITH_INF = POINTS.copy()
WITH_INF[3, 2] = np.inf
NORMALS_NAN = NORMALS.copy()
NORMALS_NAN[5, 0] = np.nan

CASES = [
    # (function, args, kwargs, exception, words the message must contain)
    ("estimate_normals", (POINTS[:, :2],), {}, ValueError, "points: expected an (N, 3) array"),
    ("estimate_normals", (POINTS.ravel(),), {}, ValueError, "points: expected an (N, 3) array"),
    ("estimate_normals", (POINTS[None],), {}, ValueError, "points: expected an (N, 3) array"),
    ("estimate_normals", (POINTS.astype(str),), {}, TypeError, "points: expected real numbers"),
    ("estimate_normals", (POINTS.astype(complex),), {}, TypeError, "points: expected real numbers"),
    ("estimate_normals", (None,), {}, TypeError, "points"),
    ("estimate_normals", (WITH_NAN,), {}, ValueError, "points: row 17 has a NaN"),
    ("estimate_curvatures", (WITH_INF,), {}, ValueError, "points: row 3 has a NaN or infinite"),
    ("estimate_normals", (POINTS, NORMALS[:-1]), {}, ValueError, "normals: expected 500 rows"),
    ("enhance_normals", (POINTS, NORMALS[:, :2]), {}, ValueError, "normals: expected an (N, 3) array"),
    ("enhance_positions", (POINTS, NORMALS_NAN), {}, ValueError, "normals: row 5 has a NaN"),
    ("estimate_normals", (POINTS,), {"k": 1}, ValueError, "k: must be >= 2"),
    ("estimate_normals", (POINTS,), {"k": 500}, ValueError, "k: 500 neighbors asked"),
    ("estimate_normals", (POINTS,), {"k": -3}, ValueError, "k: must be >= 0"),
    ("estimate_normals", (POINTS,), {"k": 2.5}, TypeError, "k: expected an integer"),
    ("estimate_normals", (POINTS,), {"order": 0}, ValueError, "order: must be >= 1"),
    ("estimate_curvatures", (POINTS,), {"order": "2"}, TypeError, "order: expected an integer"),
    ("estimate_normals", (POINTS,), {"neighbor_radius": -1.0}, ValueError, "neighbor_radius: must be >= 0"),
    ("estimate_normals", (POINTS,), {"neighbor_radius": math.nan}, ValueError, "neighbor_radius: must be finite"),
    ("estimate_normals", (POINTS,), {"neighbors_per_coefficient": 0.5}, ValueError, "neighbors_per_coefficient"),
    ("estimate_normals", (POINTS,), {"threads": 0}, ValueError, "threads: must be >= 1"),
    ("estimate_normals", (POINTS,), {"progress": "yes"}, TypeError, "progress"),
    ("estimate_normals", (POINTS,), {"seed_with_input_normals": True}, ValueError, "normals: seed_with_input_normals"),
    ("estimate_normals", (POINTS,), {"compact_weights": 1}, TypeError, "compact_weights: expected True or False"),
    ("estimate_curvatures", (POINTS,), {"curvature_frame": "pca"}, ValueError, "curvature_frame"),
    ("enhance_positions", (POINTS,), {"gain": 2j}, TypeError, "gain: enhance_positions takes a real gain"),
    ("enhance_positions", (POINTS,), {"gain": math.inf}, ValueError, "gain: must be finite"),
    ("enhance_positions", (POINTS,), {"maximum_displacement": 0.0}, ValueError, "maximum_displacement: must be > 0"),
    ("enhance_positions", (POINTS,), {"move_along_input_normals": True}, ValueError, "normals: move_along_input_normals"),
    ("enhance_positions", (POINTS,), {"evaluation_radius": -0.1}, ValueError, "evaluation_radius: must be >= 0"),
    ("enhance_normals", (POINTS, NORMALS), {"gain": complex(math.nan, 1)}, ValueError, "gain: must be finite"),
    ("enhance_normals", (POINTS, NORMALS), {"gain": "2"}, TypeError, "gain: expected a real or complex number"),
    ("estimate_normals", (POINTS,), {"unknown_option": 1}, TypeError, "unknown_option"),
    ("fit", (POINTS[:10],), {"order": 0}, ValueError, "order: must be >= 1"),
    ("fit", (np.zeros((0, 3)),), {}, ValueError, "neighbors: empty"),
    ("fit", (POINTS[:10],), {"normal": [0, 1]}, ValueError, "normal: expected 3 numbers"),
    ("fit", (POINTS[:10],), {"neighbor_normals": NORMALS[:9]}, ValueError, "neighbor_normals: expected 10 rows"),
    ("read", ("/nonexistent/cloud.ply",), {}, ValueError, "cloud.ply: cannot open"),
    ("read", ("cloud.abc",), {}, ValueError, "unsupported format"),
    ("write", ("out.ply", POINTS[:, :2]), {}, ValueError, "points: expected an (N, 3) array"),
    ("write", ("out.ply", POINTS), {"faces": [[0, 1, 500]]}, ValueError, "faces: face 0 refers to a vertex outside 0..499"),
    ("write", ("out.off", POINTS), {}, ValueError, "a point set (no faces) is written as .ply"),
    ("render", ("out.png", WITH_NAN), {}, ValueError, "points: row 17 has a NaN"),
    ("render", ("out.png", POINTS), {"values": np.ones(499)}, ValueError, "values: expected 500 numbers"),
    ("render", ("out.png", POINTS), {"values": np.full(500, np.inf)}, ValueError, "values: NaN or infinite at point 0"),
    ("render", ("out.png", POINTS), {"faces": [[0, 1, -1]]}, ValueError, "faces: face 0 refers to a vertex outside"),
    ("render", ("out.png", POINTS), {"view": (0, 0, 0)}, ValueError, "view: expected three finite numbers"),
    ("render", ("out.png", POINTS), {"width": 0}, ValueError, "width: must be >= 1"),
    ("render", ("/nonexistent/out.png", POINTS), {}, ValueError, "out.png: cannot create a file"),
]


@pytest.mark.parametrize("function, args, kwargs, exception, message", CASES,
                         ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
def test_bad_input_raises_a_clear_error(function, args, kwargs, exception, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(exception) as error:
        getattr(wavejets, function)(*args, **kwargs)
    assert message in str(error.value)


def test_too_few_neighbors_in_a_radius_is_reported_not_raised():
    normals, report = wavejets.estimate_normals(POINTS, neighbor_radius=1e-6, k=0, return_report=True)
    assert report.number_of_unfitted_points == len(POINTS)
    assert not report.fitted.any() and np.all(normals == 0)


def test_collinear_and_coplanar_points():
    line = np.column_stack([np.linspace(0, 1, 100), np.zeros(100), np.zeros(100)])
    normals, report = wavejets.estimate_normals(line, k=10, return_report=True)
    assert report.number_of_unfitted_points == 100 and np.all(np.isfinite(normals))
    plane = np.column_stack([np.random.default_rng(0).uniform(size=(300, 2)), np.zeros(300)])
    c = wavejets.estimate_curvatures(plane, k=20)
    assert np.all(c.fitted) and np.allclose(c.mean_curvature, 0, atol=1e-9)
