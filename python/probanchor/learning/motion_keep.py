"""The kept fractions of the theory of occlusion and their jitter, fitted from the samples
``anchoring collect`` keeps (:mod:`probanchor.learning.motion_samples`).

The theory moves a hidden object as a first-order autoregression in the table plane,
``x(t+1) = k x(t) + e``, ``e ~ N(0, V)`` on each axis:

- under its occluder, x is its offset from the occluder's centre (``follow_keep``,
  ``follow_var``);
- under nothing, x is its velocity (``coast_keep``, ``wander_var``: the theory adds the
  velocity to where it was and spreads the belief by V).

From ground truth (x seen at every step) the offset under an occluder is fitted as the
conditional maximum-likelihood estimates of that model, which are the least-squares ones:
``k = sum(x(t) x(t+1)) / sum(x(t)^2)`` over the samples and both axes, ``V`` the mean square of
the residuals ``x(t+1) - k x(t)``.

The theory predicts a hidden object over the whole time it is hidden, with no observation in
between, and an object's motion is no AR(1) (it goes on at one speed, then stops; pushed out of
the view, it stops there and comes back): fitted step by step from true velocities, k was 0.975
with a jitter of 1 mm, which coasted a mug pushed out of the view a metre past the view's edge.
So the coasting is fitted over whole times hidden, from both kinds of labels: an object seen
as it vanishes and as it reappears, n steps later (true positions from ground truth, perceived
ones from hindsight, :mod:`probanchor.learning.motion_hindsight`), where the model says, on
each axis:

- under nothing, of the displacement d = p(n) - p(0) given the velocity v(0) as it vanished
  (``coast_gap`` rows; the velocity is kept deterministically, the position spreads)::

      d ~ N(v(0) k (1 - k^n) / (1 - k), n V + C)

- under its occluder, of the offset (``follow_gap`` rows, hindsight only)::

      x(n) ~ N(k^n x(0), V (1 - k^(2n)) / (1 - k^2) + C)

where ``C`` is the noise of where an object is perceived as it vanishes and reappears (a
partial view's centre is centimetres off; the theory has it in ``reappear_var``), told apart
from the motion by the gaps' lengths; ``(k, V, C)`` are the maximum-likelihood estimates
(scipy.optimize, k in [0, 0.999], V and C at least (0.1 mm)²). The offsets under an occluder
seen in hindsight have gaps the model cannot explain (hindsight labels miss an occluder now and
then, and the object it moved is no jitter): each is the model's with weight w, else drawn from
a broad Gaussian with the gaps' own spread, w fitted with the rest. (Leaving out the gaps
beyond the fitted model's 99.73 % region and fitting again until none was, as this did before,
narrowed the model step by step until it explained no moving object: the gaps have heavier
tails than the model.) The coasting has no broad component (:func:`coast_gaps`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from scipy.optimize import minimize
from scipy.special import expit

__all__ = ["FASTEST", "ar1", "coast", "coast_gaps", "fastest", "follow", "follow_gaps",
           "height_gaps", "rest_gaps"]

#: The largest kept fraction the gap fits consider.
K_MAX = 0.999
#: The least variance (m², per axis) the gap fits consider for V and C: (0.1 mm)², no
#: measurable jitter.
V_MIN = 1e-8
#: A coasting gap's object moved as it vanished when its perceived velocity was at least this
#: (m a frame): above what perception's noise gives an object standing still (about 3 mm).
MOVING = 0.004


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


def _gap_fit(a: np.ndarray, moments, x_scale: float, broad: bool, axes: slice = slice(2, 4)
             ) -> tuple[float, float, float, float]:
    """(k, V, C, w): the maximum-likelihood fit of the gap rows ``a`` (see the module
    docstring; the displacements in the columns ``axes``, the table plane's by default) over
    k in [0, K_MAX], V, C > 0 (searched in logs) and, with ``broad``, the
    weight w in (0, 1) of the model's component of a mixture with a broad Gaussian of the
    gaps' own spread (searched in logits; without, w = 1), from a few starts."""
    d = a[:, axes]
    spread = float(np.mean(d ** 2)) + V_MIN               # the gaps' own spread, per axis

    def nll(theta: np.ndarray) -> float:
        k = K_MAX * float(expit(theta[0]))
        v, c = V_MIN + math.exp(theta[1]), V_MIN + math.exp(theta[2])
        mean, var = moments(a, k, v)
        var = var + c
        model = -0.5 * np.sum(np.log(2 * math.pi * var) + (d - mean) ** 2 / var, axis=1)
        if not broad:
            return -float(np.sum(model))
        other = -0.5 * np.sum(np.log(2 * math.pi * spread) + d ** 2 / spread, axis=1)
        w = float(expit(theta[3]))
        return -float(np.sum(np.logaddexp(math.log(w) + model,
                                          math.log(max(1.0 - w, 1e-300)) + other)))

    best = None
    scale = math.log(max(x_scale, 1e-12))
    for k0 in (0.5, 0.9, 0.99):
        for c0 in (scale - 4.0, scale):
            start = np.array([math.log(k0 / (K_MAX - k0)), scale - 2.0, c0, math.log(19.0)])
            r = minimize(nll, start if broad else start[:3], method="Nelder-Mead",
                         options={"xatol": 1e-6, "fatol": 1e-9, "maxiter": 8000})
            if best is None or r.fun < best.fun:
                best = r
    assert best is not None
    x = best.x
    return (K_MAX * float(expit(x[0])), V_MIN + math.exp(x[1]), V_MIN + math.exp(x[2]),
            float(expit(x[3])) if broad else 1.0)


def _robust(a: np.ndarray, moments, scale: float) -> tuple[float, float, int]:
    """(k, V, gaps explained): the fit of gap rows ``a`` (x0, y0, x1, y1, n) as a mixture of
    the model, ``moments(rows, k, V)`` giving its mean and variance of x1, y1 (each (m, 2))
    but for the noise C of the ends, and of a broad component with the gaps' own spread (the
    gaps the model cannot explain); the gaps explained are the model's expected share of them
    (its weight times their number)."""
    k, v, _, w = _gap_fit(a, moments, scale, broad=True)
    return k, v, int(round(w * len(a)))


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

    return _robust(a, moments, float(np.mean(a[:, 2:4] ** 2)))


def coast_gaps(rows: Sequence[Sequence[object]], fastest: float = math.inf
               ) -> tuple[float, float, int]:
    """(coast_keep, wander_var, samples) from ``coast_gap`` rows (vx0, vy0, dx, dy, n): the
    maximum-likelihood coasting of displacements n steps apart, of the objects that moved as
    they vanished (at least :data:`MOVING` a frame, at most ``fastest``).

    ``fastest``: the speed (m a frame) above which a vanishing velocity is no motion but a view
    cut by what hides the object (its perceived centre jumps as it goes): :func:`fastest` of
    the perceived steps. Perceived ends (hindsight) had gaps of objects "moving" 5 to 9 cm a
    frame that stood still, and the fit kept 0.39 of a velocity with a 2.4 cm jitter a frame.

    Only those: an object standing still behind something that passed in front of it says
    nothing of the velocity kept, and, the most of the gaps and the tightest, it made the
    moving ones look like gaps the model cannot explain, at a kept fraction of 0.

    With no broad component, unlike :func:`follow_gaps`: what a moving object does while
    hidden, stopping out of the view and coming back included, is what the theory must
    predict over a whole time hidden. (With one, the broad component took the objects that
    stopped out of the view, and the model left kept 0.999 of the velocity: a theory that
    coasted a mug pushed out of the view a metre past the view's edge.)

    Raises
    ------
    ValueError
        No gap of a moving object.
    """
    a = np.asarray([r[:5] for r in rows], dtype=float).reshape(-1, 5)
    speed = np.hypot(a[:, 0], a[:, 1])
    a = a[(speed >= MOVING) & (speed <= fastest)]
    if not len(a):
        raise ValueError("no object that moved hidden under nothing throughout: no gap to fit")

    def moments(rows: np.ndarray, k: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        n = np.maximum(rows[:, 4:5], 1.0)
        gain = k * (1 - k ** n) / max(1 - k, 1e-12) if k > 1e-9 else np.zeros_like(n)
        return gain * rows[:, :2], np.repeat(v * n, 2, axis=1)

    k, v, _, _ = _gap_fit(a, moments, float(np.mean(a[:, 2:4] ** 2 / np.maximum(a[:, 4:5], 1.0))),
                          broad=False)
    return k, v, len(a)


def rest_gaps(rows: Sequence[Sequence[object]]) -> tuple[float, int]:
    """(rest_var, samples) from ``coast_gap`` rows (vx0, vy0, dx, dy, n) of the objects that
    stood still as they vanished (slower than :data:`MOVING` a frame): the maximum-likelihood
    V of a displacement n steps apart, per axis::

        d ~ N(0, n V + C)

    with ``C`` the noise of the ends, as :func:`coast_gaps`. An object standing still behind
    something stays where it stood: the 928 such gaps of 80 games moved 0 cm at the median and
    3.4 cm at the 99th percentile (V about (2.6 mm)² a frame), where the moving objects' wander
    is (1.3 cm)²; spread by the latter, the belief of a still object grew by 4 cm in ten frames,
    and the particles that had it stay behind as a hand closed on it could wander out of the
    hand's reach before it rose (a cup a hand took while it started to move, and so coasting,
    still does).

    Raises
    ------
    ValueError
        No gap of an object that stood still.
    """
    a = np.asarray([r[:5] for r in rows], dtype=float).reshape(-1, 5)
    a = a[np.hypot(a[:, 0], a[:, 1]) < MOVING]
    if not len(a):
        raise ValueError("no object that stood still hidden under nothing throughout: "
                         "no gap to fit")

    def moments(rows: np.ndarray, k: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        # the coasting model without a velocity: k plays no part
        return np.zeros((len(rows), 2)), np.repeat(v * np.maximum(rows[:, 4:5], 1.0), 2, axis=1)

    _, v, _, _ = _gap_fit(a, moments, float(np.mean(a[:, 2:4] ** 2 / np.maximum(a[:, 4:5], 1.0))),
                          broad=False)
    return v, len(a)


def height_gaps(rows: Sequence[Sequence[object]]) -> tuple[float, int]:
    """(height_var, samples) from ``coast_gap`` rows (vx0, vy0, dx, dy, n, dz) that have the
    change of height: the maximum-likelihood V of how far a hidden object's height goes n
    steps apart::

        dz ~ N(0, n V + C)

    with ``C`` the noise of the ends' heights, as :func:`rest_gaps` in the table plane, and a
    broad component for what the model cannot explain, as :func:`follow_gaps`: the median gap
    of 80 games (ground truth) went 0 mm up or down, 22 of 1,170 went 2 to 14 cm (an object
    put on another or taken off it while hidden: no jitter), which alone made V (3.5 mm)² a
    frame. The theory spreads a hidden object's height by it.

    Raises
    ------
    ValueError
        No gap with its change of height (samples collected before it was kept).
    """
    a = np.asarray([[0.0, 0.0, r[5], 0.0, r[4]] for r in rows if len(r) > 5],
                   dtype=float).reshape(-1, 5)
    if not len(a):
        raise ValueError("no hidden object's change of height in the samples: no gap to fit "
                         "(collected before the samples kept it)")

    def moments(rows: np.ndarray, k: float, v: float) -> tuple[np.ndarray, np.ndarray]:
        return np.zeros((len(rows), 1)), v * np.maximum(rows[:, 4:5], 1.0)

    _, v, _, _ = _gap_fit(a, moments, float(np.mean(a[:, 2] ** 2 / np.maximum(a[:, 4], 1.0))),
                          broad=True, axes=slice(2, 3))
    return v, len(a)


#: The quantile of the perceived objects' steps that :func:`fastest` reads.
FASTEST = 0.99


def fastest(displacements: Sequence[Sequence[object]]) -> float:
    """The speed (m a frame, table plane) that :data:`FASTEST` of the perceived steps of
    objects (not hands) stay within, from ``displacement`` rows (dx, dy, dz, category, ...);
    infinite without any."""
    speeds = [math.hypot(float(r[0]), float(r[1]))  # type: ignore[arg-type]
              for r in displacements if r[3] != "skin"]
    return float(np.quantile(speeds, FASTEST)) if speeds else math.inf


def follow(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(follow_keep, follow_var, samples) from ``follow`` rows."""
    return ar1(rows)


def coast(rows: Sequence[Sequence[object]]) -> tuple[float, float, int]:
    """(coast_keep, wander_var, samples) from ``coast`` rows."""
    return ar1(rows)
