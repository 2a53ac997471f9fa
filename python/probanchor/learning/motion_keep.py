"""The kept fractions of the theory of occlusion and their jitter, fitted from the samples
``anchoring collect`` keeps (:mod:`probanchor.learning.motion_samples`).

The theory moves a hidden object as a first-order autoregression in the table plane,
``x(t+1) = k x(t) + e``, ``e ~ N(0, V)`` on each axis:

- under its occluder, x is its offset from the occluder's centre (``follow_keep``,
  ``follow_var``);
- under nothing, x is its velocity (``coast_keep``, ``wander_var``: the theory adds the
  velocity to where it was and spreads the belief by V).

From ground truth (x seen at every step) both are fitted as the conditional maximum-likelihood
estimates of that model, which are the least-squares ones: ``k = sum(x(t) x(t+1)) /
sum(x(t)^2)`` over the samples and both axes, ``V`` the mean square of the residuals
``x(t+1) - k x(t)``.

From what a robot perceives (:mod:`probanchor.learning.motion_hindsight`) x is seen only as the
object vanishes and as it reappears, n steps later; the model then says, on each axis:

- under its occluder, of the offset (``follow_gap`` rows)::

      x(n) ~ N(k^n x(0), V (1 - k^(2n)) / (1 - k^2) + C)

- under nothing, of the displacement d = p(n) - p(0) given the velocity v(0) as it vanished
  (``coast_gap`` rows; the velocity is kept deterministically, the position spreads)::

      d ~ N(v(0) k (1 - k^n) / (1 - k), n V + C)

where ``C`` is the noise of where an object is perceived as it vanishes and reappears (a
partial view's centre is centimetres off; the theory has it in ``reappear_var``), told apart
from the motion by the gaps' lengths; ``(k, V, C)`` are the maximum-likelihood estimates over
the gaps (scipy.optimize, k in [0, 0.999], V and C at least (0.1 mm)²), trimmed: a gap the
fitted model puts beyond its 99.73 % region (the squared standardised residual of both axes
above the chi-square quantile, 11.83) is left out and the model fitted again, until none is
(hindsight labels miss an occluder now and then, and the object it moved is no coasting or
jitter; from ground truth such gaps do not occur).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from scipy.optimize import minimize
from scipy.special import expit

__all__ = ["ar1", "coast", "coast_gaps", "follow", "follow_gaps"]

#: The largest kept fraction the gap fits consider.
K_MAX = 0.999
#: The least variance (m², per axis) the gap fits consider for V and C: (0.1 mm)², no
#: measurable jitter.
V_MIN = 1e-8


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


def _gap_fit(nll, x_scale: float) -> tuple[float, float, float]:
    """(k, V, C) minimising ``nll(k, V, C)`` over k in [0, K_MAX], V, C > 0 (searched in
    logs), from a few starts."""
    def objective(theta: np.ndarray) -> float:
        k = K_MAX * float(expit(theta[0]))
        return nll(k, V_MIN + math.exp(theta[1]), V_MIN + math.exp(theta[2]))

    best = None
    scale = math.log(max(x_scale, 1e-12))
    for k0 in (0.5, 0.9, 0.99):
        for c0 in (scale - 4.0, scale):
            start = np.array([math.log(k0 / (K_MAX - k0)), scale - 2.0, c0])
            r = minimize(objective, start, method="Nelder-Mead",
                         options={"xatol": 1e-6, "fatol": 1e-9, "maxiter": 6000})
            if best is None or r.fun < best.fun:
                best = r
    assert best is not None
    return (K_MAX * float(expit(best.x[0])), V_MIN + math.exp(best.x[1]),
            V_MIN + math.exp(best.x[2]))


def _gaussian_nll(x: np.ndarray, mean: np.ndarray, var: np.ndarray) -> float:
    return float(0.5 * np.sum(np.log(2 * math.pi * var) + (x - mean) ** 2 / var))


#: The chi-square quantile (2 degrees of freedom) beyond which a gap is left out: 99.73 %.
TRIM = 11.83


def _trimmed(a: np.ndarray, moments, scale: float) -> tuple[float, float, int]:
    """(k, V, gaps kept): the ML fit of gap rows ``a`` (x0, y0, x1, y1, n), ``moments(rows, k,
    V)`` giving the model's mean and variance of x1, y1 (each (m, 2)) but for the noise C of
    the ends, refitted without the gaps beyond :data:`TRIM` until none is."""
    keep = np.ones(len(a), dtype=bool)
    for _ in range(20):
        rows = a[keep]

        def nll(k: float, v: float, c: float, rows: np.ndarray = rows) -> float:
            mean, var = moments(rows, k, v)
            return _gaussian_nll(rows[:, 2:4], mean, np.maximum(var + c, 1e-300))

        k, v, c = _gap_fit(nll, scale)
        mean, var = moments(a, k, v)
        var = var + c
        z2 = np.sum((a[:, 2:4] - mean) ** 2 / np.maximum(var, 1e-300), axis=1)
        kept = z2 <= TRIM
        if np.array_equal(kept, keep) or kept.sum() < 2:
            break
        keep = kept
    return k, v, int(keep.sum())


def follow_gaps(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(follow_keep, follow_var, samples) from ``follow_gap`` rows (ox0, oy0, ox1, oy1, n):
    the maximum-likelihood AR(1) of offsets seen n steps apart.

    Raises
    ------
    ValueError
        No gap.
    """
    if not rows:
        raise ValueError("no object hidden under one occluder throughout: no gap to fit")
    a = np.asarray([r[:5] for r in rows], dtype=float)

    def moments(rows: np.ndarray, k: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        n = np.maximum(rows[:, 4:5], 1.0)
        kn = k ** n
        var = v * ((1 - kn * kn) / (1 - k * k) if k > 1e-9 else np.ones_like(n))
        return kn * rows[:, :2], np.repeat(var, 2, axis=1)

    return _trimmed(a, moments, float(np.mean(a[:, 2:4] ** 2)))


def coast_gaps(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(coast_keep, wander_var, samples) from ``coast_gap`` rows (vx0, vy0, dx, dy, n): the
    maximum-likelihood coasting of displacements n steps apart.

    Raises
    ------
    ValueError
        No gap.
    """
    if not rows:
        raise ValueError("no object hidden under nothing throughout: no gap to fit")
    a = np.asarray([r[:5] for r in rows], dtype=float)

    def moments(rows: np.ndarray, k: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        n = np.maximum(rows[:, 4:5], 1.0)
        gain = k * (1 - k ** n) / max(1 - k, 1e-12) if k > 1e-9 else np.zeros_like(n)
        return gain * rows[:, :2], np.repeat(v * n, 2, axis=1)

    return _trimmed(a, moments, float(np.mean(a[:, 2:4] ** 2 / np.maximum(a[:, 4:5], 1.0))))


def follow(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(follow_keep, follow_var, samples) from ``follow`` rows."""
    return ar1(rows)


def coast(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(coast_keep, wander_var, samples) from ``coast`` rows."""
    return ar1(rows)
