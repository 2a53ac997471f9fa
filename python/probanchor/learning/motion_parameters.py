"""The motion and carrying parameters a learned theory of occlusion reads, fitted from the samples
``anchoring collect`` keeps, and written into the theory as facts.

Which estimator fits which parameter (each in a module of its own):

- the variances (:mod:`probanchor.learning.motion_variances`): maximum likelihood;
- the kept fractions and their jitter (:mod:`probanchor.learning.motion_keep`): least squares of a
  first-order autoregression;
- the carriers' gates, thresholds and offset (:mod:`probanchor.learning.motion_grip`):
  quantiles and a mean.

The learned theory reads no other parameter: the hand-written theory's ``occluder_reach``,
``cover_height``, ``lowering_speed``, ``lowered_reach`` and ``behind_when_covered`` belong to
its hand-written occlusion rules, which the learned tree (with the fitted onset reach and the
learned affordances) replaces; its ``lift_margin``, ``release_margin`` and ``release_p`` to its
hand-written release (``too/too_release.pl``), which a learned tree replaces
(:mod:`probanchor.learning.release_data`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from probanchor.learning import motion_grip, motion_keep, motion_variances
from probanchor.learning.motion_samples import MotionSamples

__all__ = ["DESCRIPTIONS", "MIN_HEIGHTS", "Fitted", "fit", "hand_written", "kind_height_clauses",
           "kind_heights", "parameter_clauses",
           "parameter_rows"]

#: Every parameter a learned theory reads, what it is, and how it is fitted.
DESCRIPTIONS: dict[str, tuple[str, str]] = {
    "obs_var": ("the measurement noise of a perceived position (m², per axis)",
                "ML variance: half the mean square of the perceived displacement of objects "
                "that stood still (hindsight: still as perception saw them)"),
    "motion_var": ("how far a perceived object moves in a frame (m², per axis)",
                   "ML variance of the true displacements (hindsight: of the perceived ones, "
                   "less their noise)"),
    "reappear_var": ("where a hidden object is seen again, around its belief (m²)",
                     "ML variance of the reappearances against an ideal particle's belief"),
    "lost_var": ("the same for an object lost while the camera saw nothing (m²)",
                 "moved anywhere: 2 x the variance of where objects stand (longer axis)"),
    "follow_keep": ("the fraction of its offset from its occluder a hidden object keeps",
                    "least-squares AR(1) coefficient of the true offsets (hindsight: ML, with "
                    "a broad component for what it cannot explain, over the offsets as it "
                    "vanished and reappeared)"),
    "follow_var": ("the jitter of that offset per frame (m²)", "the AR(1)'s residual variance"),
    "coast_keep": ("the fraction of its velocity a hidden object under nothing keeps",
                   "ML over how far objects that moved as they vanished (no faster than 99 % of "
                   "the perceived steps) went while hidden (true ends; hindsight: perceived "
                   "ones)"),
    "wander_var": ("how far such an object may move besides (m²)",
                   "the same fit's variance per step"),
    "rest_var": ("how far one that stood still as it vanished may move (m²)",
                 "ML variance per step of how far objects that stood still as they vanished "
                 "went while hidden"),
    "height_var": ("how far a hidden object's height may move (m² a frame)",
                   "ML variance per step of how far hidden objects' heights went while "
                   "hidden, with a broad component for the jumps (put on or taken off "
                   "something)"),
    "grip_reach": ("how far (table plane) a hand's grip may be from what it takes (m)",
                   "2 x the largest grasp seen that is not far out (beyond the upper quartile "
                   "+ 3 interquartile ranges)"),
    "grip_height": ("how far above its top (m)",
                    "90 % quantile, moved off the median by its distance"),
    "occluder_rise": ("how far below its centre (m)",
                      "10 % quantile, moved off the median by its distance; 0 if above it"),
    "grip_drop": ("how far what a hand holds is below its grip (m)",
                  "mean (hindsight: of the grip over the object where the hand closed on it)"),
    "grip_rise": ("how far a hand's grip rises in a frame when it lifts (m)",
                  "the 10 % quantile of the rises while lifting, / 2"),
}


#: Parameters too_parameters.pl does not have, each with the hand-written rule too.pl reads
#: instead (too/too_motion.pl): left out of a theory whose samples cannot fit them (collected
#: before the samples kept what they are fitted from), which then reads that rule too.
OPTIONAL = {"height_var": "V / 100"}


@dataclass(frozen=True)
class Fitted:
    """One fitted parameter: its value and the number of samples it was fitted from."""

    name: str
    value: float
    samples: int


def fit(samples: MotionSamples, hand: dict[str, float]) -> list[Fitted]:
    """Every parameter of :data:`DESCRIPTIONS`, fitted from ``samples``.

    A parameter whose samples the data lack (a collection without hands has no carry) keeps
    its value of ``hand`` (too_parameters.pl's, :func:`hand_written`) with 0 samples: the
    theory's comment and the table say it was not fitted.

    Raises
    ------
    ValueError
        A parameter that cannot be fitted and has no value in ``hand``.
    """
    r = samples.rows
    out: dict[str, tuple[float, int]] = {}
    groups = (
        (("obs_var",), lambda: [motion_variances.obs_var(r["displacement"])]),
        (("motion_var",), lambda: [motion_variances.motion_var(r["displacement"])]),
        (("reappear_var",), lambda: [motion_variances.reappear_var(r["reappear"])]),
        (("lost_var",), lambda: [motion_variances.lost_var(r["places"])]),
        (("follow_keep", "follow_var"),
         lambda: _pair(motion_keep.follow(r["follow"]) if r["follow"]
                       else motion_keep.follow_gaps(r["follow_gap"]))),
        (("coast_keep", "wander_var"), lambda: _pair(_coasting(r))),
        (("rest_var",), lambda: [motion_keep.rest_gaps(r.get("coast_gap", []))]),
        (("height_var",), lambda: [motion_keep.height_gaps(r.get("coast_gap", []))]),
        (("grip_reach", "grip_height", "occluder_rise", "grip_drop"),
         lambda: list(motion_grip.grip(r["grasp"], r["hold"]).values())),
        (("grip_rise",), lambda: [motion_grip.rise(r["carries"])]),
    )
    for names, fitter in groups:
        try:
            values = fitter()
        except ValueError as error:
            missing = [n for n in names if n not in hand]
            if missing and all(n in OPTIONAL for n in missing):
                continue
            if missing:
                raise ValueError(f"the motion samples cannot fit {', '.join(missing)}: "
                                 f"{error}") from None
            values = [(hand[n], 0) for n in names]
        out.update(zip(names, values, strict=True))
    return [Fitted(name, out[name][0], out[name][1]) for name in DESCRIPTIONS if name in out]


def _coasting(r: dict[str, list]) -> tuple[float, float, int]:
    """The coasting fitted over whole times hidden (``coast_gap``, :func:`motion_keep.
    coast_gaps`: what the theory predicts), else, with no gap of an object that moved, over the
    steps of true velocities (``coast``)."""
    try:
        return motion_keep.coast_gaps(r.get("coast_gap", []),
                                      motion_keep.fastest(r.get("displacement", [])))
    except ValueError:
        if not r.get("coast"):
            raise
        return motion_keep.coast(r["coast"])


def _pair(kvn: tuple[float, float, int]) -> list[tuple[float, int]]:
    k, v, n = kvn
    return [(k, n), (v, n)]


def parameter_clauses(fitted: Sequence[Fitted]) -> str:
    """The parameters as facts, each with the samples it was fitted from in a comment."""
    lines = ["% " + "-" * 66 + " learned parameters",
             "% Fitted from the motion samples beside the data (python/probanchor/learning/",
             "% motion_parameters.py: maximum-likelihood variances, least-squares AR(1) kept",
             "% fractions, quantiles for reaches and heights, Laplace's rule for a probability);",
             "% variances per axis in square metres, one step is one camera frame."]
    for f in fitted:
        how = (f"{f.samples:,} samples" if f.samples else
               "NOT FITTED: no samples in the data, too_parameters.pl's value")
        lines.append(f"{f.name}({f.value:.4g}).  % {DESCRIPTIONS[f.name][0]}; {how}")
    lines.append(f"moving_speed({motion_keep.MOVING:g}).  % (m a frame) what the fits above "
                 "call moving as it vanished (wander_var) and still (rest_var)")
    return "\n".join(lines) + "\n"


#: A kind's height is fitted from at least this many perceived heights.
MIN_HEIGHTS = 20


def kind_heights(samples: MotionSamples, least: int = MIN_HEIGHTS
                 ) -> dict[str, tuple[float, int]]:
    """Each kind's height (m): the median of its perceived heights (``heights`` samples), with
    their count, for the kinds with at least ``least`` of them. The carriers' rules measure
    how high a grip is over an object from its top, half its kind's height above its centre:
    a hand's grip over a bottle 20 cm tall is 17 cm above its centre, over a ball 8 cm."""
    by_kind: dict[str, list[float]] = {}
    for kind, height in samples.rows.get("heights", []):
        by_kind.setdefault(str(kind), []).append(float(height))
    return {k: (float(np.median(v)), len(v)) for k, v in sorted(by_kind.items())
            if len(v) >= least}


def kind_height_clauses(heights: dict[str, tuple[float, int]]) -> str:
    """The kinds' heights as facts (``kind_height(Kind, Metres)``), each with its sample count."""
    lines = ["% The height of each kind (m): the median of its perceived heights; a grip's height",
             "% over an object is measured from its top (too/too_motion.pl)."]
    lines += [f"kind_height({k}, {h:.4g}).  % {n:,} samples" for k, (h, n) in heights.items()]
    return "\n".join(lines) + "\n"


def hand_written(base: str | Path) -> dict[str, float]:
    """The hand-written parameters of ``base``'s too_parameters.pl."""
    text = (Path(base) / "too_parameters.pl").read_text(encoding="utf-8")
    return {m[1]: float(m[2]) for m in re.finditer(r"^(\w+)\(([-\d.eE+]+)\)\.", text, re.M)}


def parameter_rows(fitted: Sequence[Fitted], base: str | Path) -> str:
    """A Markdown table: each fitted parameter beside the hand-written value of ``base``'s
    too_parameters.pl, its meaning, its estimator and its sample count."""
    hand = hand_written(base)
    lines = ["| parameter | learned | hand-written | what it is | fitted as | samples |",
             "|---|---:|---:|---|---|---:|"]
    for f in fitted:
        what, how = DESCRIPTIONS[f.name]
        h = hand.get(f.name)
        n = f"{f.samples:,}" if f.samples else "none: not fitted"
        written = OPTIONAL.get(f.name, "-") if h is None else f"{h:.3g}"
        lines.append(f"| `{f.name}` | {f.value:.3g} | {written} | "
                     f"{what} | {how} | {n} |")
    return "\n".join(lines) + "\n"
