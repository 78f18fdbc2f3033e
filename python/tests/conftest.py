"""Fixtures of the Python module's tests: the bundled data and a 100,000-point bunny sample."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(os.environ.get("WAVEJETS_DATA", ROOT / "examples" / "Wavejets" / "data"))
SAMPLE_MESH = Path(os.environ.get("WAVEJETS_SAMPLE_MESH", ROOT / "scripts" / "sample_mesh.py"))


@pytest.fixture(scope="session")
def kitten_path():
    """The kitten scan: 5,210 points with normals."""
    return DATA / "kitten.xyz"


@pytest.fixture(scope="session")
def bunny_sample_path(tmp_path_factory):
    """100,000 points sampled on the bunny mesh (no normals; the same file on every machine)."""
    path = tmp_path_factory.mktemp("bunny") / "bunny_100k.xyz"
    subprocess.run([sys.executable, str(SAMPLE_MESH), str(DATA / "bunny00.off"), "100000", "7", str(path)], check=True)
    return path


def sphere(n, radius=1.0, seed=1):
    """n points on a sphere of the given radius around (0.3, -0.2, 0.1), with outward normals."""
    rng = np.random.default_rng(seed)
    normals = rng.normal(size=(n, 3))
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    return np.array([0.3, -0.2, 0.1]) + radius * normals, normals
