"""Categories of the views that occur while objects hide one another: containers lifted into
the air (they were taken for boxes in nearly every frame of the shipped scenarios' lifts), and
the shape features of a segment that does not reach the table."""

from __future__ import annotations

import numpy as np

from probanchor.perception import Pipeline
from probanchor.perception.features import shape_features
from probanchor.tabletop import ScenarioBuilder, Simulation


def cylinder_points(radius: float, height: float, n: int = 4000, seed: int = 0
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Points of an upright cylinder's side and top as a camera above sees them."""
    rng = np.random.default_rng(seed)
    a = rng.uniform(-np.pi / 2, np.pi / 2, n)  # the near half of the side
    z = rng.uniform(0.008, height, n)
    side = np.c_[radius * np.cos(a), radius * np.sin(a), z]
    r = radius * np.sqrt(rng.uniform(0, 1, n // 2))
    b = rng.uniform(0, 2 * np.pi, n // 2)
    top = np.c_[r * np.cos(b), r * np.sin(b), np.full(n // 2, height)]
    pts = np.vstack([side, top])
    return pts, pts[:, 2].copy()


def test_a_lifted_segment_has_the_shape_features_of_a_standing_one():
    pts, h = cylinder_points(0.04, 0.1)
    area = 0.004
    standing = shape_features(pts, h, area)
    lifted = shape_features(pts + [0.0, 0.0, 0.15], h + 0.15, area)
    assert np.allclose(lifted, standing, rtol=0.02, atol=0.003)  # robust lowest point
    assert lifted[0] < 0.11  # measured from the table its top would be at 0.25 m
    # a segment that reaches the table is measured from the table, as before
    low = shape_features(pts + [0.0, 0.0, 0.005], h + 0.005, area)
    assert low[0] > standing[0] + 0.004


def test_lifted_mug_and_cup_keep_their_categories():
    """A mug and a cup lifted 12 cm and carried: every frame in the air gives the right best
    category (the previous classifier said box for most of them)."""
    b = ScenarioBuilder("lifted", fps=5)
    b.add("mug_1", "mug", "blue", position=(-0.15, 0.05), radius=0.04, height=0.1)
    b.add("cup_1", "cup", "yellow", position=(0.15, 0.05), radius=0.04, height=0.09)
    b.lift(0.0, "mug_1", to=(-0.15, 0.2), height=0.12, duration=3.0)
    b.lift(0.0, "cup_1", to=(0.15, 0.2), height=0.12, duration=3.0)
    pipe = Pipeline()
    seen: dict[str, list[str]] = {"mug_1": [], "cup_1": []}
    with Simulation(b.build(), fps=5, seed=3) as sim:
        for frame in sim:
            objects = frame.truth["objects"]
            for p in pipe.process(frame):
                if p.truth_id in seen and objects[p.truth_id]["position"][2] > 0.1:
                    seen[p.truth_id].append(p.best_category)
    for oid, categories in seen.items():
        assert len(categories) >= 4, oid
        right = categories.count(oid.split("_")[0])
        assert right >= len(categories) - 1, (oid, categories)
