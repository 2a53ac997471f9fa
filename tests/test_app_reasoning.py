"""The theory of occlusion (prolog/too.pl) driven the way the runner drives it."""

from __future__ import annotations

import numpy as np
import pytest

from app.naming import symbol_atom
from app.reasoning import AnchorState, OcclusionReasoner

MUG = (0.0, 0.0, 0.05)
BALL = (0.05, 0.0, 0.03)


def step(reasoner: OcclusionReasoner, anchors: dict[str, tuple[str, tuple | None]]) -> None:
    reasoner.step([AnchorState(s, c, p) for s, (c, p) in anchors.items()])


def test_symbol_atoms() -> None:
    assert symbol_atom("ball-1") == "ball_1"
    assert symbol_atom("Mug-12") == "mug_12"
    assert symbol_atom("3d-thing") == "a_3d_thing"


def test_hidden_ball_follows_the_mug_that_covers_it() -> None:
    reasoner = OcclusionReasoner(particles=60, seed=1)
    try:
        for _ in range(2):
            step(reasoner, {"mug-1": ("mug", MUG), "ball-1": ("ball", BALL)})
        step(reasoner, {"mug-1": ("mug", MUG), "ball-1": ("ball", None)})
        assert reasoner.occluders("ball-1")[0][1] == "mug-1"
        assert reasoner.occluders("ball-1")[0][0] == pytest.approx(1.0)
        for k in range(1, 7):  # the mug slides 30 cm to the right
            step(reasoner, {"mug-1": ("mug", (0.05 * k, 0.0, 0.05)), "ball-1": ("ball", None)})
        belief = reasoner.belief("ball-1")
        assert belief is not None
        mean = belief.weights @ belief.positions
        # under the mug (within a few cm: picked at the mug's centre, then moved with it)
        assert abs(mean[0] - 0.30) < 0.03 and abs(mean[1]) < 0.03
        assert abs(mean[2] - 0.03) < 0.01  # stays on the table: a mug is not a carrier
    finally:
        reasoner.close()


def test_lifting_the_mug_ends_the_occlusion_and_leaves_the_ball_on_the_table() -> None:
    reasoner = OcclusionReasoner(particles=40, seed=2)
    try:
        step(reasoner, {"mug-1": ("mug", MUG), "ball-1": ("ball", BALL)})
        step(reasoner, {"mug-1": ("mug", MUG), "ball-1": ("ball", None)})
        assert reasoner.probability("occluded_by(ball_1, mug_1):t") == pytest.approx(1.0)
        step(reasoner, {"mug-1": ("mug", (0.0, 0.0, 0.25)), "ball-1": ("ball", None)})
        assert reasoner.probability("occluded_by(ball_1, _):t") == pytest.approx(0.0)
        belief = reasoner.belief("ball-1")
        assert belief is not None
        assert np.all(np.abs(belief.positions[:, :2]).max(axis=1) < 0.03)
    finally:
        reasoner.close()


def test_a_ball_is_never_the_occluder_and_a_far_box_is_not_a_candidate() -> None:
    reasoner = OcclusionReasoner(particles=50, seed=3)
    scene = {"ball-1": ("ball", (0.0, 0.0, 0.03)), "ball-2": ("ball", (0.06, 0.0, 0.03)),
             "box-1": ("box", (0.0, 0.08, 0.06)), "mug-1": ("mug", (0.5, 0.0, 0.05))}
    try:
        step(reasoner, scene)
        step(reasoner, {**scene, "ball-1": ("ball", None)})
        occluders = dict((s, p) for p, s in reasoner.occluders("ball-1"))
        assert occluders == {"box-1": pytest.approx(1.0)}
    finally:
        reasoner.close()


def test_a_ball_lost_while_the_camera_is_covered_may_be_under_any_container() -> None:
    n = 300
    reasoner = OcclusionReasoner(particles=n, seed=4)
    cups = {"mug-1": ("mug", (-0.2, 0.1, 0.05)), "box-1": ("box", (0.0, 0.1, 0.06)),
            "mug-2": ("mug", (0.2, 0.1, 0.05))}
    try:
        step(reasoner, {**cups, "ball-1": ("ball", (0.0, -0.15, 0.03))})
        blind = {s: (c, None) for s, (c, _) in {**cups, "ball-1": ("ball", None)}.items()}
        for _ in range(3):  # covered camera: nothing perceived
            step(reasoner, blind)
        step(reasoner, {**cups, "ball-1": ("ball", None)})
        occluders = dict((s, p) for p, s in reasoner.occluders("ball-1"))
        assert set(occluders) == {"mug-1", "box-1", "mug-2"}
        # uniform over three: each 1/3 within 4.5 standard errors of a proportion
        tolerance = 4.5 * np.sqrt((1 / 3) * (2 / 3) / n)
        for p in occluders.values():
            assert abs(p - 1 / 3) < tolerance
        belief = reasoner.belief("ball-1")
        assert belief is not None
        # one mode per container: every particle sits under one of them
        xs = belief.positions[:, 0]
        assert np.all(np.min(np.abs(xs[:, None] - np.array([-0.2, 0.0, 0.2])), axis=1) < 0.03)
        # when the ball shows up again under mug-2, the belief collapses there
        step(reasoner, {**cups, "mug-2": ("mug", (0.2, 0.25, 0.2)),
                        "ball-1": ("ball", (0.2, 0.1, 0.03))})
        belief = reasoner.belief("ball-1")
        assert belief is not None
        mean = belief.weights @ belief.positions
        assert abs(mean[0] - 0.2) < 0.02
    finally:
        reasoner.close()
