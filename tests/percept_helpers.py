"""Percepts written by hand for tests that play a recorded stream."""

from __future__ import annotations

import numpy as np

from probanchor.percepts import Percept


def ball_percept(t: float, x: float) -> Percept:
    """A red ball percept at (x, 0, 0.03), time t."""
    hist = np.zeros(8)
    hist[0] = 1.0
    return Percept(time=t, position=np.array([x, 0.0, 0.03]), size=np.full(3, 0.06),
                   colour_histogram=hist, category={"ball": 0.9, "cup": 0.1})
