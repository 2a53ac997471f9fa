"""How good the world model's answer is while an object is hidden: belief accuracy.

Over the frames in which a ground-truth object is on the table but hidden (``visible`` false)
and has been anchored before (so the anchor that stands for it is known: the symbol its
percepts were last given, as the run gave it then):

- ``within``: the fraction of those frames in which the anchor's point estimate (the record's
  hypothesis, e.g. :func:`~probanchor.evaluation.record.point_estimate` of its particles) is
  within ``threshold`` metres (3-D) of the object's true position;
- ``true_occluder_probability``: over the frames in which the ground truth names what hides
  the object (``hidden_by``) and that object has been anchored too, the mean probability the
  belief gave to it (``Hypothesis.occluders``; 0 when the belief names other occluders or
  none).

An object hidden in a frame where its anchor has no hypothesis counts as not within. Runs
without reasoning (no occluder probabilities) report ``true_occluder_probability`` as None.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from probanchor.evaluation.record import TrackingRecord


@dataclass
class BeliefAccuracy:
    """Belief accuracy of one run (see the module docstring)."""

    hidden_frames: int
    within: float | None
    occluder_frames: int
    true_occluder_probability: float | None
    threshold: float

    def to_json(self) -> dict[str, object]:
        def rounded(x: float | None) -> float | None:
            return None if x is None or not math.isfinite(x) else round(float(x), 6)

        return {"hidden_frames": self.hidden_frames, "within": rounded(self.within),
                "occluder_frames": self.occluder_frames,
                "true_occluder_probability": rounded(self.true_occluder_probability),
                "threshold": self.threshold}


def belief_accuracy(records: Sequence[TrackingRecord], threshold: float = 0.1
                    ) -> BeliefAccuracy:
    """The belief accuracy of a run's records (see the module docstring)."""
    last: dict[str, str] = {}  # ground-truth id -> the symbol last given its percept
    hidden = within = 0
    occluder_frames = 0
    occluder_mass = 0.0
    occluders_known = False
    for rec in records:
        for oid, obj in rec.truth.items():
            if obj.visible or oid not in last:
                continue
            hidden += 1
            hyp = rec.hypotheses.get(last[oid])
            if hyp is not None and np.all(np.isfinite(hyp.position)):
                within += float(np.linalg.norm(hyp.position - obj.position)) <= threshold
            if hyp is not None and hyp.occluders is not None:
                occluders_known = True
            if obj.hidden_by is not None and obj.hidden_by in last:
                occluder_frames += 1
                if hyp is not None and hyp.occluders is not None:
                    occluder_mass += hyp.occluders.get(last[obj.hidden_by], 0.0)
        last.update(rec.assignments)
    return BeliefAccuracy(
        hidden_frames=hidden,
        within=within / hidden if hidden else None,
        occluder_frames=occluder_frames,
        true_occluder_probability=(occluder_mass / occluder_frames
                                   if occluder_frames and occluders_known else None),
        threshold=threshold,
    )
