"""The carrying parameters of the theory of occlusion (a hand takes an object, carries it,
puts it down), fitted from the samples ``anchoring collect`` keeps
(:mod:`probanchor.learning.motion_samples`).

The carriers' rules (``prolog/too/too_motion.pl``) test thresholds. Two kinds, each fitted
from quantiles so that one odd carry does not move it, with the margin of the onset reach
(:data:`probanchor.learning.occlusion_reach.MARGIN`, 2):

- a *reach* every event seen falls within (``grip_reach``, how far from what it takes a hand's
  grip may be): the margin times the largest event, since a grasp outside it is a carry the
  particles do not follow (the object is lost), and the grasps of the generated games are
  tighter than others' (a quantile of them left a hand that grips 5 cm off out);
- a *gate* the events must fall within: a non-negative one (``release_margin``) is the margin
  times the 90 % quantile of the events; a signed one (how
  high the grip is over the object it takes) runs from the 10 % quantile to the 90 % one,
  each moved away from the median by its own distance from it (``grip_height`` above,
  ``occluder_rise``, how far the grip may be below the object's centre, below);
- a *threshold* an event must exceed (``lift_margin``, ``grip_rise``): the 10 % quantile of
  the events divided by the margin (nine events in ten exceed twice the threshold).

And two that are no thresholds:

- ``grip_drop``, how far what a hand holds is below its grip point: the mean over the frames
  a hand holds something out of view (the maximum-likelihood location);
- ``release_p``, the probability per frame that a hand lets go of what it carried back down to
  where it stood: of the frames it held the object there, the share after which it let go,
  with Laplace's rule ((releases + 1) / (frames + 2)).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from probanchor.learning.occlusion_reach import MARGIN

__all__ = ["GATE", "THRESHOLD", "gate", "grip", "reach", "release", "signed_gate", "threshold"]

#: The quantile of a gate (and, 1 - GATE, of a signed gate's lower end).
GATE = 0.9
#: The quantile of a threshold.
THRESHOLD = 0.1


def _values(xs: Sequence[float]) -> np.ndarray:
    a = np.asarray(xs, dtype=float)
    if a.size == 0:
        raise ValueError("no samples")
    return a


def gate(xs: Sequence[float]) -> float:
    """The margin times the 90 % quantile of the non-negative ``xs``."""
    return MARGIN * float(np.quantile(_values(xs), GATE))


def reach(xs: Sequence[float]) -> float:
    """The margin times the largest of the non-negative ``xs``: every event seen within it."""
    return MARGIN * float(np.max(_values(xs)))


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
            "occluder_rise": (-low, n), "grip_drop": (float(np.mean(_values(holds))), len(holds))}


def release(carries: Sequence[dict[str, Any]]) -> dict[str, tuple[float, int]]:
    """lift_margin, release_margin, release_p and grip_rise with their sample counts, from the
    ``carries`` (heights above where the object stood, released or not, grip heights)."""
    if not carries:
        raise ValueError("no hand carried an object: no carrying to fit")
    lifts = [max(c["heights"]) for c in carries]
    lift = threshold(lifts)
    raised = [c for c in carries if max(c["heights"]) > lift]
    put_down = [c["heights"][-1] for c in raised if c["released"]]
    margin = gate(put_down)
    frames = releases = 0
    for c in raised:
        up = False
        hs = c["heights"]
        for i, h in enumerate(hs):
            up = up or h > lift
            if not up or h > margin:
                continue
            last = i == len(hs) - 1
            if last and not c["released"]:
                continue                      # the episode ended: censored
            frames += 1
            releases += int(last)
    rises = []
    for c in carries:
        hs, gs = c["heights"], c["grips"]
        for i in range(len(hs) - 1):
            if hs[i + 1] > hs[i] + 0.001 and gs[i] is not None and gs[i + 1] is not None:
                rises.append(gs[i + 1] - gs[i])
    return {"lift_margin": (lift, len(lifts)), "release_margin": (margin, len(put_down)),
            "release_p": ((releases + 1) / (frames + 2), frames),
            "grip_rise": (threshold(rises), len(rises))}
