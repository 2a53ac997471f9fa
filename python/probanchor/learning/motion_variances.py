"""The variances of the theory of occlusion, fitted from the samples ``anchoring collect`` keeps
(:mod:`probanchor.learning.motion_samples`).

Each is the maximum-likelihood variance of a zero-mean Gaussian that is the same on every axis
(the theory's covariances are ``V`` times the identity): the mean of the squared components
of the samples, over the samples and the three axes.

- ``obs_var``: the measurement noise of a perceived position: half the mean square of the
  frame-to-frame change of the perceived position of objects that truly stood still (their
  true displacement under 1 mm; the difference of two independent noises has twice their
  variance);
- ``motion_var``: how far a perceived object moves in one frame: its true displacement;

  From what a robot perceives alone (no true displacement, ``--labels hindsight``): the
  objects that stood still are those perception saw stay within half a centimetre over
  eleven frames (the row's sixth field, :mod:`probanchor.learning.motion_hindsight`), and
  ``motion_var`` is the mean square of the perceived displacements less the noise in them
  (2 obs_var; at least a hundredth of obs_var);
- ``reappear_var``: where a hidden object is seen again around where an ideal particle
  believed it (under its occluder, or where it was last seen);
- ``lost_var``: where an object lost while the camera saw nothing (and under nothing since) is
  seen again: anywhere on the table. The particles cannot follow an unseen move (a lost
  object stays where it was in every particle), so this variance stands for the move: that of
  an object taken from one place on the table to another drawn independently, twice the
  variance of where the data's perceived objects stand, along the table's longer axis (the
  theory's variance is the same on every axis; averaged over both axes it lost two look-alike
  mugs swapped 60 cm apart along the long side). The lost objects' own reappearances are
  mostly where they were (the camera covered, nothing moved) and a few far off (look-alikes
  swapped): one Gaussian fitted to them, (6 cm)² from 80 games, would decide at the
  reappearance which of two swapped look-alikes is which, before anything tells them apart.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["STILL", "isotropic_variance", "lost_var", "motion_var", "obs_var", "reappear_var"]

#: An object whose true displacement in a frame is under this (m) stood still.
STILL = 0.001


def isotropic_variance(rows: Sequence[Sequence[float]]) -> float:
    """The maximum-likelihood variance of N(0, V I) for the vectors ``rows``.

    Raises
    ------
    ValueError
        No rows.
    """
    a = np.asarray(rows, dtype=float)
    if a.size == 0:
        raise ValueError("no samples")
    return float(np.mean(a * a))


def _without_truth(displacements: Sequence[Sequence[object]]) -> bool:
    return bool(displacements) and all(r[4] is None for r in displacements)


def obs_var(displacements: Sequence[Sequence[object]]) -> tuple[float, int]:
    """(obs_var, samples) from ``displacement`` rows (dx, dy, dz, category, true or None[,
    still as perceived])."""
    if _without_truth(displacements):
        still = [r[:3] for r in displacements if len(r) > 5 and r[5]]
        return isotropic_variance(still) / 2.0, len(still)   # type: ignore[arg-type]
    still = [r[:3] for r in displacements
             if r[4] is not None and float(np.linalg.norm(r[4])) < STILL]   # type: ignore[arg-type]
    return isotropic_variance(still) / 2.0, len(still)   # type: ignore[arg-type]


def motion_var(displacements: Sequence[Sequence[object]]) -> tuple[float, int]:
    """(motion_var, samples): the true displacements of the perceived objects (without
    truth: the perceived ones less their noise)."""
    if _without_truth(displacements):
        noise, n = obs_var(displacements)
        perceived = isotropic_variance([r[:3] for r in displacements])  # type: ignore[misc]
        return max(perceived - 2.0 * noise, noise / 100.0), len(displacements)
    moved = [r[4] for r in displacements if r[4] is not None]
    return isotropic_variance(moved), len(moved)   # type: ignore[arg-type]


def reappear_var(rows: Sequence[Sequence[float]]) -> tuple[float, int]:
    """(reappear_var, samples) from ``reappear`` rows (dx, dy, dz)."""
    return isotropic_variance(rows), len(rows)


def lost_var(places: Sequence[Sequence[float]]) -> tuple[float, int]:
    """(lost_var, samples) from ``places`` rows (x, y): twice the variance of where objects
    stand along the axis where it is largest.

    Raises
    ------
    ValueError
        Fewer than two places.
    """
    a = np.asarray(places, dtype=float)
    if len(a) < 2:
        raise ValueError("fewer than two places of objects")
    return 2.0 * float(np.max(np.var(a[:, :2], axis=0))), len(a)
