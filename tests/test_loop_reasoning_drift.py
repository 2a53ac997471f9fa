"""The hidden ball's modes survive a long shuffle (no genetic drift from the perceived objects'
measurement noise), follow their containers, and collapse when the ball is seen again.

Driven with synthetic frames (no perception, no simulator): three containers and a ball; the
ball is lost while the camera is covered, then the containers are perceived again with noisy
positions and swapped along arcs for 120 frames."""

from __future__ import annotations

import numpy as np
import pytest

from probanchor.loop.reasoning import AnchorState, OcclusionReasoner

N = 100
NOISE = 0.004  # perceived centroids jitter by ~4 mm per axis (what perception gives)
HOME = {"mug-1": (-0.2, 0.1, 0.05), "box-1": (0.0, 0.1, 0.06), "mug-2": (0.2, 0.1, 0.05)}
CATEGORY = {"mug-1": "mug", "box-1": "box", "mug-2": "mug", "ball-1": "ball"}


def swap_paths(a: np.ndarray, b: np.ndarray, frames: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Two containers trade places along half circles on opposite sides (they never meet)."""
    centre, half = (a + b) / 2, (b - a) / 2
    out = []
    for k in range(1, frames + 1):
        angle = np.pi * k / frames
        normal = np.array([-half[1], half[0], 0.0])
        pa = centre - np.cos(angle) * half + np.sin(angle) * normal
        pb = centre + np.cos(angle) * half - np.sin(angle) * normal
        out.append((pa, pb))
    return out


def modes(reasoner: OcclusionReasoner, truth: dict[str, np.ndarray]) -> dict[str, float]:
    """The ball's belief mass near each container (within 4 cm in the table plane)."""
    belief = reasoner.belief("ball-1")
    assert belief is not None
    out = {}
    for name, p in truth.items():
        near = np.linalg.norm(belief.positions[:, :2] - p[:2], axis=1) < 0.04
        out[name] = float(belief.weights[near].sum())
    return out


def test_hidden_modes_survive_a_long_shuffle_and_collapse_on_reveal() -> None:
    rng = np.random.default_rng(7)
    reasoner = OcclusionReasoner(particles=N, seed=11)
    truth = {s: np.array(p) for s, p in HOME.items()}

    def frame(ball: tuple | None = None, blind: bool = False) -> None:
        anchors = []
        for s, p in truth.items():
            seen = None if blind else tuple(p + rng.normal(0, NOISE, 3))
            anchors.append(AnchorState(s, CATEGORY[s], seen))
        anchors.append(AnchorState("ball-1", "ball", ball))
        reasoner.step(anchors)

    try:
        for _ in range(3):
            frame(ball=(0.0, -0.15, 0.03))
        for _ in range(5):  # a hand covers the camera; the ball goes somewhere
            frame(blind=True)
        frame()
        start = modes(reasoner, truth)
        # a pick among three: each mode 1/3 within 4.5 standard errors of a proportion
        pick_tol = 4.5 * np.sqrt((1 / 3) * (2 / 3) / N)
        assert all(abs(m - 1 / 3) < pick_tol for m in start.values()), start
        assert sum(start.values()) == pytest.approx(1.0)

        for a, b in (("mug-1", "mug-2"), ("box-1", "mug-2"), ("mug-1", "box-1")):
            for pa, pb in swap_paths(truth[a].copy(), truth[b].copy(), 40):
                truth[a], truth[b] = pa, pb
                frame()
        end = modes(reasoner, truth)
        # the modes follow their containers: all the mass is under one of them ...
        assert sum(end.values()) == pytest.approx(1.0, abs=1e-9), end
        # ... and no observation said anything about the ball, so no mode may have drifted by
        # more than one resampling's noise (a filter that resamples every frame for the
        # perceived objects' noise drifts by ~sqrt(frames) times that and loses modes)
        one_resampling = 4.5 * np.sqrt((1 / 3) * (2 / 3) / N)
        for name in truth:
            assert abs(end[name] - start[name]) < one_resampling, (start, end)

        # mug-2 is lifted and the ball is seen where it stood: the belief collapses there
        lifted = truth["mug-2"].copy()
        truth["mug-2"] = lifted + np.array([0.0, 0.0, 0.15])
        frame()
        frame(ball=(lifted[0], lifted[1], 0.03))
        belief = reasoner.belief("ball-1")
        assert belief is not None
        mean = belief.weights @ belief.positions
        assert np.linalg.norm(mean[:2] - lifted[:2]) < 0.02
    finally:
        reasoner.close()
