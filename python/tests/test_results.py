"""What the functions compute: analytic surfaces with known normals and curvature, exact recovery
of a polynomial surface by one fit, the same bits for every thread count, inputs never modified."""

import math

import numpy as np
import pytest

import wavejets
from conftest import sphere


def test_sphere_normals_and_curvature():
    points, outward = sphere(20000, radius=2.0)
    normals, report = wavejets.estimate_normals(points, outward, k=30, return_report=True)
    assert report.number_of_unfitted_points == 0
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-12)
    angles = np.degrees(np.arccos(np.clip(np.sum(normals * outward, axis=1), -1, 1)))
    assert angles.max() < 0.5          # oriented like the input normals, and accurate
    c = wavejets.estimate_curvatures(points, outward, k=30)
    # Outward normals: the sphere bends away from them, H = -1/R, K = 1/R^2.
    assert np.all(c.fitted)
    assert np.allclose(c.mean_curvature, -0.5, rtol=0.02)
    assert np.allclose(c.gaussian_curvature, 0.25, rtol=0.04)
    assert np.all(c.k1 >= c.k2)


def test_unoriented_normals_without_input_normals():
    points, outward = sphere(5000)
    normals = wavejets.estimate_normals(points, k=20)
    assert np.allclose(np.abs(np.sum(normals * outward, axis=1)), 1.0, atol=1e-3)


def test_fit_recovers_a_polynomial_surface_exactly():
    # z = 0.3 x^2 - 0.2 y^2 + 0.1 x y + 0.05 x^3: an order-3 Wavejet reproduces it exactly.
    rng = np.random.default_rng(3)
    xy = rng.uniform(-0.5, 0.5, size=(60, 2))
    xy[0] = 0.0
    z = 0.3 * xy[:, 0] ** 2 - 0.2 * xy[:, 1] ** 2 + 0.1 * xy[:, 0] * xy[:, 1] + 0.05 * xy[:, 0] ** 3
    w = wavejets.fit(np.column_stack([xy, z]), order=3, normal=[0, 0, 1], seed_with_input_normals=True)
    assert w.is_valid and w.status == "success" and w.order == 3
    assert np.allclose(w.normal, [0, 0, 1], atol=1e-12)
    # Curvature at the origin: the Hessian [[0.6, 0.1], [0.1, -0.4]], normal +z.
    eig = np.linalg.eigvalsh([[0.6, 0.1], [0.1, -0.4]])
    assert w.principal_curvatures == pytest.approx((eig[1], eig[0]), abs=1e-10)
    assert w.mean_curvature == pytest.approx(0.1, abs=1e-10)
    # f_{2,0} = (0.3 - 0.2) / 2 (the mean of the second derivatives halved), whatever the frame's angle.
    assert w.coefficient(2, 0).real == pytest.approx(0.05, abs=1e-10)
    assert abs(w.coefficient(2, 2)) == pytest.approx(abs(complex(0.25, -0.05)) / 2, abs=1e-10)
    assert w.coefficient(5, 1) == 0


def test_fit_reports_degenerate_neighborhoods():
    line = np.column_stack([np.linspace(0, 1, 20), np.zeros(20), np.zeros(20)])
    w = wavejets.fit(line, order=2)
    assert not w.is_valid and w.status == "degenerate neighborhood"
    assert not wavejets.fit(line[:3], order=2).is_valid


@pytest.mark.parametrize("function", ["estimate_normals", "estimate_curvatures", "enhance_positions", "enhance_normals"])
def test_every_thread_count_gives_the_same_bits(function, kitten_path):
    points, normals, _ = wavejets.read(kitten_path)
    call = getattr(wavejets, function)

    def run(threads):
        result = call(points, normals, k=30, threads=threads)
        arrays = [result] if isinstance(result, np.ndarray) else \
            [result.mean_curvature, result.k1, result.k2, result.d1, result.d2]
        return b"".join(a.tobytes() for a in arrays)

    one = run(1)
    assert run(2) == one and run(3) == one and run(None) == one


def test_inputs_are_never_modified(kitten_path):
    points, normals, _ = wavejets.read(kitten_path)
    points_before, normals_before = points.copy(), normals.copy()
    wavejets.estimate_normals(points, normals)
    wavejets.enhance_positions(points, normals, gain=3, write_normals=True)
    wavejets.enhance_normals(points, normals, gain=2j)
    wavejets.estimate_curvatures(points, normals)
    assert np.array_equal(points, points_before) and np.array_equal(normals, normals_before)


def test_float32_and_fortran_order_give_the_same_result(kitten_path):
    points, normals, _ = wavejets.read(kitten_path)
    points32 = points.astype(np.float32)
    expected = wavejets.estimate_normals(points32.astype(np.float64), normals, k=20)
    assert np.array_equal(wavejets.estimate_normals(points32, normals, k=20), expected)
    assert np.array_equal(wavejets.estimate_normals(np.asfortranarray(points32.astype(np.float64)), normals, k=20),
                          expected)
    assert np.array_equal(wavejets.estimate_normals(points32.astype(np.float64).tolist(), normals, k=20), expected)


def test_enhancement_moves_details_and_gain_one_projects(kitten_path):
    points, normals, _ = wavejets.read(kitten_path)
    flattened = wavejets.enhance_positions(points, normals, gain=0)
    enhanced, report = wavejets.enhance_positions(points, normals, gain=2, return_report=True)
    assert report.moves_points and report.number_of_fitted_points == len(points)
    motion_enhanced = np.linalg.norm(enhanced - points, axis=1)
    motion_flattened = np.linalg.norm(flattened - points, axis=1)
    assert motion_enhanced.max() > 0 and motion_flattened.max() > 0
    # Gain 0 and gain 2 move the points by opposite detail displacements around the projection.
    projected = wavejets.enhance_positions(points, normals, gain=1, maximum_displacement=math.inf)
    both = wavejets.enhance_positions(points, normals, gain=0, maximum_displacement=math.inf) + \
        wavejets.enhance_positions(points, normals, gain=2, maximum_displacement=math.inf)
    assert np.allclose(both / 2, projected, atol=1e-12)


def test_empty_input_gives_empty_results():
    empty = np.zeros((0, 3))
    assert wavejets.estimate_normals(empty).shape == (0, 3)
    assert wavejets.enhance_positions(empty).shape == (0, 3)
    assert wavejets.enhance_normals(empty, empty).shape == (0, 3)
    assert wavejets.estimate_curvatures(empty).mean_curvature.shape == (0,)


def test_duplicates_and_far_coordinates_are_fitted_or_reported():
    points, outward = sphere(3000)
    points = np.vstack([points, points[:100]])          # 100 duplicated points
    normals, report = wavejets.estimate_normals(points + 1e7, k=20, return_report=True)
    assert np.all(np.isfinite(normals))
    assert report.number_of_fitted_points + report.number_of_unfitted_points == len(points)
    fitted = report.fitted
    assert np.allclose(np.linalg.norm(normals[fitted], axis=1), 1.0)
    assert np.all(normals[~fitted] == 0)


def test_render_writes_a_png_of_the_requested_size(kitten_path, tmp_path):
    """The binding of the tool's renderer (whose pixels the tool's tests check): a point set
    coloured by values, and a mesh without normals."""
    points, normals, _ = wavejets.read(kitten_path)
    curvature = wavejets.estimate_curvatures(points, normals, k=30).mean_curvature
    path = tmp_path / "kitten.png"
    wavejets.render(path, points, normals, values=curvature, width=300, height=200)
    png = path.read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert (width, height) == (300, 200)
    triangle = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    wavejets.render(tmp_path / "triangle.png", triangle, faces=[[0, 1, 2]], width=64, height=64)
    assert (tmp_path / "triangle.png").stat().st_size > 100
