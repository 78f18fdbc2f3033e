"""Every function's Python result equals the C++ function's, bit for bit (the C++ side:
reference.cpp, called as a C++ user calls the functions on a CGAL::Point_set_3)."""

import os
import subprocess

import numpy as np
import pytest

import wavejets

REFERENCE = os.environ.get("WAVEJETS_PYTHON_REFERENCE")
pytestmark = pytest.mark.skipif(not REFERENCE, reason="WAVEJETS_PYTHON_REFERENCE (the C++ reference program, "
                                                      "built by CMake) is not set")


def cpp_results(function, path, out, n, k, order, gain=2 + 0j):
    """The reference program's arrays: shapes as the Python function returns them, and the fitted flags."""
    subprocess.run([REFERENCE, function, str(path), str(out), str(k), str(order), repr(gain.real), repr(gain.imag)],
                   check=True)
    raw = out.read_bytes()
    values = np.frombuffer(raw[:len(raw) - n], dtype="<f8")
    fitted = np.frombuffer(raw[len(raw) - n:], dtype=np.uint8).astype(bool)
    return values, fitted


def assert_bitwise(python_arrays, cpp_values):
    flat = np.concatenate([np.ascontiguousarray(a, dtype=np.float64).ravel() for a in python_arrays])
    assert flat.shape == cpp_values.shape
    assert flat.tobytes() == cpp_values.tobytes(), \
        f"{np.count_nonzero(flat != cpp_values)} of {flat.size} values differ"


@pytest.fixture(params=["kitten", "bunny_100k"])
def data(request, kitten_path, bunny_sample_path):
    path = kitten_path if request.param == "kitten" else bunny_sample_path
    points, normals, _ = wavejets.read(path)
    return path, points, normals


def test_estimate_normals(data, tmp_path):
    path, points, normals = data
    result, report = wavejets.estimate_normals(points, normals, k=18, order=2, return_report=True)
    cpp, fitted = cpp_results("estimate_normals", path, tmp_path / "out", len(points), 18, 2)
    assert_bitwise([result], cpp)
    assert np.array_equal(report.fitted, fitted)
    assert report.number_of_fitted_points == np.count_nonzero(fitted) > 0.99 * len(points)


def test_estimate_curvatures(data, tmp_path):
    path, points, normals = data
    c = wavejets.estimate_curvatures(points, normals, k=40, order=3)
    cpp, fitted = cpp_results("estimate_curvatures", path, tmp_path / "out", len(points), 40, 3)
    assert_bitwise([c.mean_curvature, c.gaussian_curvature, c.k1, c.k2, c.d1, c.d2], cpp)
    assert np.array_equal(c.fitted, fitted)


def test_enhance_positions(data, tmp_path):
    path, points, normals = data
    if normals is None:
        result = [wavejets.enhance_positions(points, normals, k=40, gain=2.5, order=4)]
    else:
        result = list(wavejets.enhance_positions(points, normals, k=40, gain=2.5, order=4, write_normals=True))
    cpp, fitted = cpp_results("enhance_positions", path, tmp_path / "out", len(points), 40, 4, 2.5 + 0j)
    assert_bitwise(result, cpp)
    assert not np.array_equal(result[0], points)


def test_enhance_normals_complex_gain(data, tmp_path):
    path, points, normals = data
    result = wavejets.enhance_normals(points, normals, k=40, gain=1 + 2j, order=4)
    cpp, fitted = cpp_results("enhance_normals", path, tmp_path / "out", len(points), 40, 4, 1 + 2j)
    assert_bitwise([result], cpp)


def test_estimate_scales(data, tmp_path):
    path, points, _ = data
    scales, report = wavejets.estimate_scales(points, order=2, return_report=True)
    cpp, fitted = cpp_results("estimate_scales", path, tmp_path / "out", len(points), 0, 2)
    assert_bitwise([scales.k, scales.descriptor], cpp)
    assert np.array_equal(scales.fitted, fitted)
    assert report.number_of_fitted_points == np.count_nonzero(fitted) == len(points)
    assert set(np.unique(scales.k)) <= set(scales.neighborhood_sizes.tolist())
