"""The table plane: found among clutter, refused when tilted, the same on every call."""

from __future__ import annotations

import numpy as np
import pytest

from probanchor.perception.plane import fit_plane, ransac_inliers


def table_with_clutter(seed: int, tilt_deg: float = 0.0) -> np.ndarray:
    """2,000 points of a table 0.7 m up (1 mm noise), tilted about x, plus 600 of boxes."""
    rng = np.random.default_rng(seed)
    xy = rng.uniform(-0.5, 0.5, (2000, 2))
    z = 0.7 + np.tan(np.radians(tilt_deg)) * xy[:, 1] + rng.normal(0, 0.001, 2000)
    clutter = rng.uniform([-0.3, -0.3, 0.72], [0.3, 0.3, 0.9], (600, 3))
    return np.vstack([np.column_stack([xy, z]), clutter])


def test_the_table_is_found_under_the_clutter():
    plane = fit_plane(table_with_clutter(0))
    assert plane is not None
    assert plane.normal == pytest.approx([0, 0, 1], abs=0.01)
    assert plane.z_at(0.1, -0.2) == pytest.approx(0.7, abs=0.002)


def test_a_steep_plane_is_not_a_table():
    assert fit_plane(table_with_clutter(1, tilt_deg=40)) is None
    tilted = fit_plane(table_with_clutter(1, tilt_deg=10))
    assert tilted is not None and tilted.normal[2] == pytest.approx(np.cos(np.radians(10)),
                                                                   abs=0.01)


def test_the_same_points_give_the_same_plane_bit_for_bit():
    points = table_with_clutter(2)
    first = fit_plane(points)
    assert first is not None
    for _ in range(5):
        again = fit_plane(points)
        assert again is not None
        assert again.normal.tobytes() == first.normal.tobytes() and again.offset == first.offset
    mask = ransac_inliers(points, 0.01, 100, seed=3)
    assert np.array_equal(mask, ransac_inliers(points, 0.01, 100, seed=3))
    assert mask[:2000].mean() > 0.99 and mask[2000:].mean() < 0.2


def test_collinear_triples_are_never_chosen():
    line = np.column_stack([np.linspace(0, 1, 60), np.zeros(60), np.zeros(60)])
    assert not ransac_inliers(line, 0.01, 20).any()  # no plane through a line
