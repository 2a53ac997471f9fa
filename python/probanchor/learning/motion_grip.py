"""The carrying parameters of the theory of occlusion (a hand takes an object and carries it),
fitted from the samples ``anchoring collect`` keeps (:mod:`probanchor.learning.motion_samples`).
When the hand lets go is no parameter but a tree the structure learner learns
(:mod:`probanchor.learning.release_data`).

The carriers' rules (``prolog/too/too_motion.pl``) test thresholds. Three kinds, each fitted
from quantiles so that one odd carry does not move it, with the margin of the onset reach
(:data:`probanchor.learning.occlusion_reach.MARGIN`, 2):

- a *reach* every event seen falls within (``grip_reach``, how far from what it takes a hand's
  grip may be): the margin times the largest event, since a grasp outside it is a carry the
  particles do not follow (the object is lost), and the grasps of the generated games are
  tighter than others' (a quantile of them left a hand that grips 5 cm off out); but not a
  far-out event (beyond Tukey's far fence, the upper quartile plus ``FAR`` interquartile
  ranges): a hand grown to hold a cup had its grip point put 12 and 25 cm off the cup it took,
  and a reach of 50 cm would let a hand take whatever vanishes anywhere near it;
- a signed *gate* the events must fall within (how high the grip is over the object it
  takes): from the 10 % quantile to the 90 % one, each moved away from the median by its own
  distance from it (``grip_height`` above, ``occluder_rise``, how far the grip may be below
  the object's centre, below: 0 when the gate's lower end lies above the centre, since the
  rules ask that the grip be "not below" the object, and a clearance above it would make a
  hand lowering an object to the table let go of it and take it again as it rises);
- a *threshold* an event must exceed (``grip_rise``): the 10 % quantile of the events divided
  by the margin (nine events in ten exceed twice the threshold).

And one that is no threshold: ``grip_drop``, how far what a hand holds is below its grip
point: the mean over the frames a hand holds something out of view (the maximum-likelihood
location).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from probanchor.learning.occlusion_reach import FAR, MARGIN, not_far_out

__all__ = ["FAR", "GATE", "THRESHOLD", "grip", "reach", "rise", "signed_gate", "threshold"]

#: The quantile of a signed gate's upper end (1 - GATE: of its lower end).
GATE = 0.9
#: The quantile of a threshold.
THRESHOLD = 0.1


def _values(xs: Sequence[float]) -> np.ndarray:
    a = np.asarray(xs, dtype=float)
    if a.size == 0:
        raise ValueError("no samples")
    return a


def reach(xs: Sequence[float]) -> float:
    """The margin times the largest of the non-negative ``xs`` that is not far out (beyond the
    upper quartile plus ``FAR`` interquartile ranges): every other event seen within it."""
    return MARGIN * float(np.max(not_far_out(_values(xs), FAR)))


def signed_gate(xs: Sequence[float]) -> tuple[float, float]:
    """(low, high): the 10 % and 90 % quantiles of ``xs``, each moved away from the median by
    (margin - 1) times its distance from it."""
    a = _values(xs)
    lo, mid, hi = (float(q) for q in np.quantile(a, [1 - GATE, 0.5, GATE]))
    return mid - MARGIN * (mid - lo), mid + MARGIN * (hi - mid)


def threshold(xs: Sequence[float]) -> float:
    """The 10 % quantile of ``xs`` divided by the margin."""
    return float(np.quantile(_values(xs), THRESHOLD)) / MARGIN


def grip(grasps: Sequence[Sequence[float]], holds: Sequence[float]
         ) -> dict[str, tuple[float, int]]:
    """grip_reach, grip_height, occluder_rise and grip_drop with their sample counts, from the
    ``grasp`` rows (distance and height of the grip over the object as it vanishes under it,
    height as the hand closes on it) and the ``hold`` heights: the gate's upper end is read
    where the rules take the object (it vanishes under the grip), its lower end where the grip
    comes lowest (closing on it)."""
    if not grasps:
        raise ValueError("no hand took an object: no grip to fit")
    g = np.asarray(grasps, dtype=float)
    _, high = signed_gate(g[:, 1])                     # as the object vanishes under the grip
    low, _ = signed_gate(g[:, 2])                      # as the hand closes on it
    n = len(g)
    return {"grip_reach": (reach(g[:, 0]), n), "grip_height": (high, n),
            "occluder_rise": (max(-low, 0.0), n),
            "grip_drop": (float(np.mean(_values(holds))), len(holds))}


def rise(carries: Sequence[dict[str, Any]]) -> tuple[float, int]:
    """grip_rise with its sample count, from the ``carries`` (heights above where the object
    stood, grip heights): the threshold of the grip's rises in the frames the carried object
    went up."""
    rises = []
    for c in carries:
        hs, gs = c["heights"], c["grips"]
        for i in range(len(hs) - 1):
            if hs[i + 1] > hs[i] + 0.001 and gs[i] is not None and gs[i + 1] is not None:
                rises.append(gs[i + 1] - gs[i])
    if not rises:
        raise ValueError("no hand lifted what it carried: no rise to fit")
    return threshold(rises), len(rises)
