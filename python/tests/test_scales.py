"""Per-point scales: a k, an order and a radius per point (bitwise those of whole runs at that k,
order and radius), estimate_scales (known choices on a noisy plane and a clean sphere), k='auto', and bad arguments."""

import numpy as np
import pytest

import wavejets
from conftest import sphere


@pytest.fixture(scope="module")
def kitten(kitten_path):
    points, normals, _ = wavejets.read(kitten_path)
    return points, normals


def test_per_point_k_and_order_give_the_bits_of_whole_runs(kitten):
    points, normals = kitten
    rng = np.random.default_rng(3)
    k = rng.choice([0, 18, 30], size=len(points))     # 0: the default k (40 at orders 2 and 3)
    order = rng.choice([2, 3], size=len(points))
    normals_per_point = wavejets.estimate_normals(points, normals, k=k, order=order)
    curvatures_per_point = wavejets.estimate_curvatures(points, normals, k=k, order=order)
    for k_value, whole_k in ((0, 40), (18, 18), (30, 30)):
        for order_value in (2, 3):
            mask = (k == k_value) & (order == order_value)
            assert np.count_nonzero(mask) > 100
            whole = wavejets.estimate_normals(points, normals, k=whole_k, order=order_value)
            assert whole[mask].tobytes() == normals_per_point[mask].tobytes()
            c = wavejets.estimate_curvatures(points, normals, k=whole_k, order=order_value)
            assert c.mean_curvature[mask].tobytes() == curvatures_per_point.mean_curvature[mask].tobytes()


def test_the_default_k_suits_the_highest_order_per_point(kitten):
    points, normals = kitten
    order = np.where(np.arange(len(points)) % 2 == 0, 2, 8)   # order 8: 45 coefficients, default k 67 (1.5 x 45, rounded down)
    per_point = wavejets.estimate_normals(points, normals, order=order)
    whole = wavejets.estimate_normals(points, normals, k=67, order=8)
    assert per_point[order == 8].tobytes() == whole[order == 8].tobytes()


def test_per_point_k_in_the_enhancements(kitten):
    points, normals = kitten
    k = np.where(points[:, 0] > np.median(points[:, 0]), 20, 50)
    moved = wavejets.enhance_positions(points, normals, k=k, gain=2)
    tilted = wavejets.enhance_normals(points, normals, k=k, gain=2)
    for value in (20, 50):
        mask = k == value
        assert moved[mask].tobytes() == wavejets.enhance_positions(points, normals, k=value, gain=2)[mask].tobytes()
        assert tilted[mask].tobytes() == wavejets.enhance_normals(points, normals, k=value, gain=2)[mask].tobytes()


def kth_neighbor_distance(points, k, samples=64):
    """The median distance from a sample of the points to their k-th nearest neighbor."""
    picked = points[:: max(1, len(points) // samples)]
    d = np.linalg.norm(points[None, :, :] - picked[:, None, :], axis=2)
    return float(np.median(np.sort(d, axis=1)[:, k]))


def test_per_point_radius_gives_the_bits_of_whole_runs(kitten):
    points, normals = kitten
    r = kth_neighbor_distance(points, 20)
    n = len(points)
    # Each point's k caps its neighbors in its radius (0 in an array of k: the default k, 40).
    radius = np.resize([r, 1.5 * r, 0.0], n)    # 0: the k nearest neighbors
    k = np.resize([30, 0, 20], n)
    per_point = wavejets.estimate_normals(points, normals, k=k, neighbor_radius=radius)
    curvatures, report = wavejets.estimate_curvatures(points, normals, k=k, neighbor_radius=radius,
                                                      return_report=True)
    assert report.number_of_fitted_points > 0.95 * n
    for group, whole in enumerate((dict(k=30, neighbor_radius=r), dict(k=40, neighbor_radius=1.5 * r), dict(k=20))):
        mask = np.arange(n) % 3 == group
        assert per_point[mask].tobytes() == wavejets.estimate_normals(points, normals, **whole)[mask].tobytes()
        c = wavejets.estimate_curvatures(points, normals, **whole)
        assert curvatures.mean_curvature[mask].tobytes() == c.mean_curvature[mask].tobytes()
    # k = 0 (one integer): every neighbor in each point's radius.
    radius = np.resize([r, 1.5 * r], n)
    moved = wavejets.enhance_positions(points, normals, k=0, neighbor_radius=radius, gain=2)
    for group, value in enumerate((r, 1.5 * r)):
        mask = np.arange(n) % 2 == group
        whole = wavejets.enhance_positions(points, normals, k=0, neighbor_radius=value, gain=2)
        assert moved[mask].tobytes() == whole[mask].tobytes()


def test_a_noisy_plane_chooses_the_largest_size():
    rng = np.random.default_rng(5)
    n = 6000
    xy = rng.uniform(-1, 1, size=(n, 2))
    points = np.column_stack([xy, 0.01 * rng.normal(size=n)])
    scales = wavejets.estimate_scales(points)
    interior = np.all(np.abs(xy) < 0.6, axis=1)
    assert np.all(scales.fitted)
    assert scales.neighborhood_sizes.tolist() == [10, 16, 25, 40, 63, 101, 160]
    assert scales.descriptor.shape == (n, 7)
    assert np.mean(scales.k[interior] == 160) > 0.95


def test_a_clean_sphere_chooses_small_sizes_and_its_descriptor_is_its_curvature():
    points, _ = sphere(10000, radius=1.0)     # random (clumpy) sampling, no noise
    scales = wavejets.estimate_scales(points)
    assert np.all(scales.k <= 25) and np.mean(scales.k <= 16) > 0.95   # the 3 smallest of the 7 sizes
    # |f_2| = |H| = 1/2 on the unit sphere, up to the order-2 fit's bias (the r^4 term of the
    # sphere), which grows as R^2: within 0.005 up to 40 neighbors, 0.02 up to 160.
    assert np.allclose(scales.descriptor[:, :4], 0.5, atol=0.005)
    assert np.allclose(scales.descriptor, 0.5, atol=0.02)


def test_k_auto_is_estimate_scales_then_the_function(kitten):
    points, normals = kitten
    scales = wavejets.estimate_scales(points, order=2)
    auto = wavejets.estimate_curvatures(points, normals, k="auto")
    given = wavejets.estimate_curvatures(points, normals, k=scales.k)
    assert auto.mean_curvature.tobytes() == given.mean_curvature.tobytes()
    assert len(np.unique(scales.k)) > 1
    ladder = [12, 24, 48]
    auto = wavejets.enhance_positions(points, normals, k="auto", order=3)
    given = wavejets.enhance_positions(points, normals, k=wavejets.estimate_scales(points, order=3).k, order=3)
    assert auto.tobytes() == given.tobytes()
    custom = wavejets.estimate_scales(points, neighborhood_sizes=ladder, threads=1)
    assert set(np.unique(custom.k)) <= set(ladder)
    assert custom.k.tobytes() == wavejets.estimate_scales(points, neighborhood_sizes=ladder).k.tobytes()


def test_bad_scale_arguments_are_errors(kitten):
    points, normals = kitten
    n = len(points)
    with pytest.raises(ValueError, match="one value per point"):
        wavejets.estimate_normals(points, k=np.full(n - 1, 20))
    with pytest.raises(ValueError, match=">= 0"):
        wavejets.estimate_normals(points, k=np.full(n, -3))
    with pytest.raises(ValueError, match="must be >= 2"):
        wavejets.estimate_normals(points, k=np.full(n, 1))
    with pytest.raises(TypeError, match="integers"):
        wavejets.estimate_normals(points, k=np.full(n, 20.0))
    with pytest.raises(ValueError, match="'auto'"):
        wavejets.estimate_normals(points, k="automatic")
    with pytest.raises(ValueError, match="neighbor_radius"):
        wavejets.estimate_normals(points, k="auto", neighbor_radius=0.1)
    with pytest.raises(ValueError, match="neighbor_radius"):
        wavejets.estimate_normals(points, k="auto", neighbor_radius=np.full(n, 0.1))
    with pytest.raises(ValueError, match="one value per point"):
        wavejets.estimate_normals(points, neighbor_radius=np.full(n + 1, 0.1))
    with pytest.raises(ValueError, match="finite and >= 0"):
        wavejets.estimate_normals(points, neighbor_radius=np.resize([0.1, -0.1], n))
    with pytest.raises(ValueError, match="finite and >= 0"):
        wavejets.estimate_normals(points, neighbor_radius=np.resize([0.1, np.nan], n))
    with pytest.raises(TypeError, match="real numbers"):
        wavejets.estimate_normals(points, neighbor_radius=np.full(n, "0.1"))
    with pytest.raises(ValueError, match="must be >= 2"):   # the points without a radius need k >= 2
        wavejets.estimate_normals(points, k=0, neighbor_radius=np.resize([0.1, 0.0], n))
    with pytest.raises(ValueError, match="one integer"):
        wavejets.estimate_normals(points, k="auto", order=np.full(n, 2))
    with pytest.raises(ValueError, match="must increase"):
        wavejets.estimate_scales(points, neighborhood_sizes=[20, 10])
    with pytest.raises(ValueError, match="must increase"):
        wavejets.estimate_scales(points, neighborhood_sizes=[1, 10])
    with pytest.raises(ValueError, match="non-empty"):
        wavejets.estimate_scales(points, neighborhood_sizes=[])
    with pytest.raises(ValueError, match="at most"):
        wavejets.estimate_scales(points[:50])
    with_nan = points.copy()
    with_nan[7, 2] = np.nan
    with pytest.raises(ValueError, match="row 7 has a NaN"):
        wavejets.estimate_scales(with_nan)


def test_empty_input_gives_empty_scales():
    scales = wavejets.estimate_scales(np.zeros((0, 3)))
    assert scales.k.shape == (0,) and scales.descriptor.shape == (0, 7) and scales.fitted.shape == (0,)
