"""The kept fractions of the theory of occlusion and their jitter, fitted from the samples
``anchoring collect`` keeps (:mod:`probanchor.learning.motion_samples`).

The theory moves a hidden object as a first-order autoregression in the table plane,
``x(t+1) = k x(t) + e``, ``e ~ N(0, V)`` on each axis:

- under its occluder, x is its offset from the occluder's centre (``follow_keep``,
  ``follow_var``);
- under nothing, x is its velocity (``coast_keep``, ``wander_var``: the theory adds the
  velocity to where it was and spreads the belief by V).

Both are fitted as the conditional maximum-likelihood estimates of that model, which are the
least-squares ones: ``k = sum(x(t) x(t+1)) / sum(x(t)^2)`` over the samples and both axes,
``V`` the mean square of the residuals ``x(t+1) - k x(t)``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["ar1", "coast", "follow"]


def ar1(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(k, V, samples) of the AR(1) model for rows (x0, y0, x1, y1, ...).

    Raises
    ------
    ValueError
        No sample with x(t) other than 0 (nothing to fit k from).
    """
    a = np.asarray([r[:4] for r in rows], dtype=float).reshape(-1, 4)
    x0 = a[:, :2].ravel()
    x1 = a[:, 2:4].ravel()
    s = float(np.dot(x0, x0))
    if s <= 0.0:
        raise ValueError("no sample that moved: nothing to fit the kept fraction from")
    k = float(np.dot(x0, x1)) / s
    residual = x1 - k * x0
    return k, float(np.mean(residual * residual)), len(a)


def follow(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(follow_keep, follow_var, samples) from ``follow`` rows."""
    return ar1(rows)


def coast(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(coast_keep, wander_var, samples) from ``coast`` rows."""
    return ar1(rows)
