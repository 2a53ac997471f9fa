"""Association likelihoods: how probable it is that a percept is a given anchor, a new object,
or clutter (the hypothesiser of the anchoring system).

For a percept ``j`` at position ``x`` and an anchor ``a`` whose position is a belief (the
reasoning's weighted particles ``s_i, w_i``: the anchor is hidden), the likelihood ratio of
"``j`` is ``a``" against "``j`` is an object never seen before" is the product of how ``a``
looks and where its belief puts it::

    LR(j, a) = A(j, a) * B(j, a)

    log A(j, a) = -log((1 - rho) exp(-(scale * f_app(j, a) + offset)) + rho)
                                                      (appearance; f_app: the learned matching
                                                       function with position and time taken
                                                       as agreeing, calibrated)
    B(j, a) = (1 - e_a) * p_a(x) / u + e_a            (belief)
    p_a(x)  = sum_i w_i N(x; s_i, r^2 I)              (the belief's predictive density)
    u       = 1 / V                                   (a new object: anywhere on the table, V m^3)

``A`` is how much likelier ``j``'s appearance is if ``j`` is ``a`` than if it is another
object: the different objects are distinct-looking ones, against which a Platt-scaled decision
``scale * f_app + offset`` is the log ratio, and, a share ``rho`` of them, look-alikes that look
as ``a`` does (``p(f | different) = (1 - rho) q(f) + rho p(f | same)``). So ``A`` is at most
``1 / rho``: an identical appearance is evidence only as strong as the world's rate of
look-alikes allows (``rho = 0``: the plain Platt ratio, unbounded).

``e_a`` is the probability that the belief does not explain why ``a`` is unseen
(:func:`unexplained_mass`): the mass of the particles that have ``a`` under no occluder with
nothing perceived in this frame within ``cover_radius`` of it in the table plane (nothing
there could stand in front of it: it is not where the particle says), and at least
``blind_doubt`` for an anchor lost while the camera saw nothing (what the camera did not see
may have moved it anywhere, or left it where the belief has it: a ball under a box that stood
still while the camera was covered is where the box is). Where a particle holds ``a`` under
a container or in a hand, or behind something in view, the belief is trusted; where the
place it names is in plain view and empty, ``a`` may have been moved anywhere unseen, and a
percept anywhere on the table is as likely under "``j`` is ``a``" as under "a new object".
The posterior of the hypotheses of one percept::

    P(a | j) = LR(j, a) / (sum_b LR(j, b) + lambda_new + lambda_clutter)
    P(new | j) = lambda_new / (...),   P(clutter | j) = lambda_clutter / (...)

``lambda_new`` and ``lambda_clutter`` are the prior odds of a new object, and of a spurious
percept, against the reappearance of a known hidden object anywhere on the table. So a
one-of-a-kind object whose belief was wrong is re-acquired (its appearance ratio outweighs the
new-object odds, and its unexplained belief does not argue against it), while a look-alike
far from a belief that explains the hidden object (every particle has it under a container in
view) stays a new object (``p_a(x)`` is about 0 there and ``e_a`` about 0).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np

from anchoring.matcher import Matcher
from anchoring.similarity import BELIEF_RADIUS, FEATURES

_POSITION = FEATURES.index("position")
_TIME = FEATURES.index("time")


@dataclass(frozen=True)
class AssociationModel:
    """The parameters of the association likelihoods (see the module docstring).

    Parameters
    ----------
    cover_radius : float
        How near (metres, in the table plane) a perceived object must be to a particle for it
        to explain a hidden object there that no occluder covers (it may stand in front of
        it; the theory of occlusion's occluder reach, 15 cm).
    table_volume : float
        ``V``: the volume (m^3) over which a new object, or a hidden object moved unseen, may
        appear (a 1.0 x 0.8 m table, 0.3 m high).
    new_odds : float
        ``lambda_new``: prior odds of a new object against a known hidden object reappearing.
    clutter_odds : float
        ``lambda_clutter``: prior odds of a spurious percept against the same.
    blind_doubt : float
        The least ``e_a`` of an anchor not perceived since the camera last saw nothing: the
        probability that it was moved unseen where its belief cannot follow (0.5; 1 ignores
        such a belief, 0 trusts it as any other).
    appearance_scale, appearance_offset : float
        The Platt calibration of the matching function's appearance decision into a log
        likelihood ratio against a distinct-looking object (``anchoring train-matching`` fits
        them; 1 and 0 otherwise).
    appearance_lookalike : float
        ``rho``: the share of other objects that look as an anchor does (the calibration fits
        it; 0 otherwise: an appearance ratio without bound). ``A <= 1 / rho``.
    """

    cover_radius: float = 0.15
    table_volume: float = 0.24
    new_odds: float = 1.0
    clutter_odds: float = 1.0
    blind_doubt: float = 0.5
    appearance_scale: float = 1.0
    appearance_offset: float = 0.0
    appearance_lookalike: float = 0.0

    def __post_init__(self) -> None:
        for name in ("cover_radius", "table_volume"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be positive, not {getattr(self, name)!r}")
        for name in ("new_odds", "clutter_odds"):
            if not getattr(self, name) >= 0:
                raise ValueError(f"{name} must be at least 0, not {getattr(self, name)!r}")
        if not 0.0 <= self.blind_doubt <= 1.0:
            raise ValueError(f"blind_doubt must be in [0, 1], not {self.blind_doubt!r}")
        if not math.isfinite(self.appearance_scale) or not math.isfinite(self.appearance_offset):
            raise ValueError("the appearance calibration must be finite")
        if not 0.0 <= self.appearance_lookalike < 1.0:
            raise ValueError(f"appearance_lookalike must be in [0, 1), not "
                             f"{self.appearance_lookalike!r}")

    @classmethod
    def for_matcher(cls, matcher: Matcher) -> AssociationModel:
        """The defaults, with the appearance calibration the matching model's file records
        (``info["appearance_calibration"]``: ``{"scale": .., "offset": .., "lookalike": ..}``;
        a calibration without ``lookalike`` has none) if it has one."""
        model = cls()
        info = getattr(matcher, "info", None) or {}
        calibration = info.get("appearance_calibration") if isinstance(info, dict) else None
        if isinstance(calibration, dict):
            model = replace(model, appearance_scale=float(calibration["scale"]),
                            appearance_offset=float(calibration["offset"]),
                            appearance_lookalike=float(calibration.get("lookalike", 0.0)))
        return model

    def to_json(self) -> dict[str, float]:
        return asdict(self)

    @classmethod
    def from_json(cls, record: Any) -> AssociationModel:
        if not isinstance(record, dict):
            raise ValueError(f"association: not a mapping: {record!r}")
        known = {f for f in cls.__dataclass_fields__}
        unknown = set(record) - known
        if unknown:
            raise ValueError(f"association: unknown field {sorted(unknown)[0]!r}")
        return cls(**{k: float(v) for k, v in record.items()})

    def density_ratio(self, radius: float = BELIEF_RADIUS) -> float:
        """``(2 pi r^2)^(-3/2) * V``: a belief's predictive density at a particle (blurred by
        ``radius``, r), against the uniform density of a new object."""
        return (2.0 * math.pi * radius ** 2) ** -1.5 * self.table_volume

    @property
    def rival_odds(self) -> float:
        """``lambda_new + lambda_clutter``: what a re-acquisition must outweigh."""
        return self.new_odds + self.clutter_odds


def appearance_log_ratio(matcher: Matcher, features: np.ndarray,
                         model: AssociationModel) -> np.ndarray:
    """``log A``: the matching function on the (..., 5) similarity vectors with the position
    and time similarities set to 1 (how the anchor looks, wherever and whenever it was),
    calibrated into a log likelihood ratio (:func:`calibrated_log_ratio`)."""
    x = np.array(features, dtype=float, copy=True)
    x[..., _POSITION] = 1.0
    x[..., _TIME] = 1.0
    return calibrated_log_ratio(np.asarray(matcher.decision(x), dtype=float),
                                model.appearance_scale, model.appearance_offset,
                                model.appearance_lookalike)


def calibrated_log_ratio(decision: np.ndarray, scale: float, offset: float,
                         lookalike: float) -> np.ndarray:
    """``log A`` of appearance decisions ``f``::

        log A0 = scale * f + offset                  (against a distinct-looking object)
        A      = 1 / ((1 - rho) / A0 + rho)          (a share rho of other objects look alike)
        log A  = -logaddexp(log(1 - rho) - log A0, log rho)

    ``rho = 0`` gives ``log A0``."""
    log_a0 = scale * np.asarray(decision, dtype=float) + offset
    if lookalike <= 0.0:
        return log_a0
    return -np.logaddexp(math.log1p(-lookalike) - log_a0, math.log(lookalike))


def unexplained_mass(anchor: Any, percepts: Sequence[Any], model: AssociationModel) -> float:
    """``e_a``: the weight of the particles of ``anchor``'s belief that have it under no
    occluder (``anchor.occluded``; all of them when the reasoning did not say) with no percept
    of this frame within ``cover_radius`` in the table plane. 0 for an anchor whose position
    is not a belief."""
    position = anchor.position
    if not position.is_probabilistic:
        return 0.0
    samples, weights = position.samples, position.weights
    free = np.ones(samples.shape[0], bool) if anchor.occluded is None \
        else ~np.asarray(anchor.occluded, bool)
    if not free.any():
        return 0.0
    if percepts:
        xy = np.array([p.position[:2] for p in percepts], dtype=float)
        near = np.zeros(samples.shape[0], bool)
        d2 = ((samples[free, None, :2] - xy[None, :, :]) ** 2).sum(axis=-1)
        near[free] = (d2 <= model.cover_radius ** 2).any(axis=1)
        free &= ~near
    total = float(weights.sum())
    return float(weights[free].sum() / total) if total > 0 else 0.0


def belief_ratio(mass: np.ndarray, unexplained: np.ndarray, model: AssociationModel,
                 radius: float = BELIEF_RADIUS) -> np.ndarray:
    """``B``, (A, P): from each anchor's belief mass near each percept (the predictive density
    blurred by ``radius`` divided by its peak, :func:`anchoring.similarity.position_evidence`)
    and each anchor's unexplained mass ``e_a`` (A,)."""
    e = np.clip(np.asarray(unexplained, dtype=float), 0.0, 1.0)[:, None]
    return (1.0 - e) * np.asarray(mass, dtype=float) * model.density_ratio(radius) + e


def reacquire_probability(log_appearance: np.ndarray, belief: np.ndarray,
                          model: AssociationModel) -> np.ndarray:
    """``P(a | j)`` of each (anchor, percept) pair taken on its own against a new object and
    clutter (the one-to-one constraint among anchors is the assignment's)."""
    with np.errstate(over="ignore"):
        ratio = np.exp(np.minimum(log_appearance, 700.0)) * belief
    return ratio / (ratio + model.rival_odds)


def percept_posteriors(log_appearance: np.ndarray, belief: np.ndarray, candidates: np.ndarray,
                       model: AssociationModel) -> np.ndarray:
    """(A + 2, P): for each percept, the posterior of each candidate anchor (rows where
    ``candidates`` is False get 0), then of a new object, then of clutter (columns sum to 1)."""
    with np.errstate(over="ignore"):
        ratio = np.where(candidates, np.exp(np.minimum(log_appearance, 700.0)) * belief, 0.0)
    p = ratio.shape[1]
    rows = np.vstack([ratio, np.full((1, p), model.new_odds), np.full((1, p), model.clutter_odds)])
    total = rows.sum(axis=0, keepdims=True)
    return np.divide(rows, total, out=np.zeros_like(rows), where=total > 0)
