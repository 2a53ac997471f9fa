"""Metrics over a list of :class:`~probanchor.evaluation.record.TrackingRecord`.

Two views of identity:

- **Identity report** (from the runner's own percept-to-symbol assignments). For each
  ground-truth object that was perceived at least once, ``symbols`` lists the symbols its
  percepts were given, in order of first use. ``identity_kept`` is true when, and only when,
  (a) every frame that assigns the object's percept a symbol assigns the same one, the symbol
  of its first assignment (so also after every occlusion: a re-acquired object that comes back
  under a new symbol is not kept), and (b) that symbol is never given to the percept of another
  ground-truth object in any frame (two objects sharing one anchor do not keep theirs). An
  object never perceived is not reported (nothing could anchor it); one perceived but never
  given a symbol is reported with ``symbols == []`` and is not kept.

  *At the end*: the same report on the records as the run answers them at its end
  (:func:`~probanchor.evaluation.record.revised_records`: identities revised by later
  evidence rename the answers of the frames since the ambiguity), beside *every frame*, the
  report on the answers as given.

- **CLEAR-MOT / identity metrics** (py-motmetrics, matching by position). Per frame the
  ground truth is every object in ``record.truth``, visible *and hidden*, at its true position;
  the hypotheses are every anchor's point estimate. A ground-truth object and a hypothesis can
  be matched when they are at most ``threshold`` metres apart (Euclidean, 3-D). So an anchor
  that keeps a hidden object's position near the truth is credited, one that loses it is not.
  ``id_switches`` is motmetrics' ``num_switches``; ``idf1`` its IDF1 (global ID matching).

- **HOTA** (TrackEval, the same ground truth and hypotheses, similarity falling linearly from 1
  at the truth to 0 at ``threshold``): HOTA, DetA, AssA, LocA (:mod:`probanchor.evaluation.hota`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

import numpy as np

from probanchor.evaluation.beliefs import BeliefAccuracy, belief_accuracy
from probanchor.evaluation.hota import HotaMetrics, hota_metrics
from probanchor.evaluation.motmetrics_compat import mm
from probanchor.evaluation.record import TrackingRecord, revised_records

DEFAULT_THRESHOLD_M = 0.1


@dataclass
class ObjectIdentity:
    """The identity report of one ground-truth object."""

    id: str
    symbols: list[str]
    identity_kept: bool
    perceived_frames: int = 0
    assigned_frames: int = 0


@dataclass
class MotMetrics:
    """Position-based tracking metrics (py-motmetrics)."""

    id_switches: int
    idf1: float
    idp: float
    idr: float
    mota: float
    idtp: int
    idfp: int
    idfn: int
    threshold: float


@dataclass
class Evaluation:
    frames: int
    objects: list[ObjectIdentity] = field(default_factory=list)
    mot: MotMetrics | None = None
    #: the identity report on the answers as revised by the end of the run
    objects_at_end: list[ObjectIdentity] = field(default_factory=list)
    beliefs: BeliefAccuracy | None = None
    hota: HotaMetrics | None = None

    @property
    def objects_kept(self) -> int:
        return sum(o.identity_kept for o in self.objects)

    @property
    def all_kept(self) -> bool:
        """True when every reported object kept its identity in every frame's answer."""
        return bool(self.objects) and all(o.identity_kept for o in self.objects)

    @property
    def all_kept_at_end(self) -> bool:
        """True when every reported object has its own symbol in the answers as revised by
        the end of the run (falls back on :attr:`all_kept` when not computed)."""
        objects = self.objects_at_end or self.objects
        return bool(objects) and all(o.identity_kept for o in objects)


def identity_report(records: Iterable[TrackingRecord]) -> list[ObjectIdentity]:
    """Per ground-truth object: symbols in order of first use and whether identity was kept.

    Objects appear in order of first appearance in the records' ground truth (objects only
    assigned, never in the truth, come last). See the module doc for the exact definition.
    """
    order: dict[str, None] = {}
    perceived: dict[str, int] = {}
    symbols: dict[str, dict[str, None]] = {}
    first: dict[str, str] = {}
    consistent: dict[str, bool] = {}
    assigned: dict[str, int] = {}
    owners: dict[str, set[str]] = {}  # symbol -> ground-truth ids whose percepts it was given
    for rec in records:
        for oid, obj in rec.truth.items():
            order.setdefault(oid, None)
            if obj.visible or oid in rec.assignments:
                perceived[oid] = perceived.get(oid, 0) + 1
        for oid, sym in rec.assignments.items():
            order.setdefault(oid, None)
            if oid not in rec.truth:
                perceived[oid] = perceived.get(oid, 0) + 1
            symbols.setdefault(oid, {}).setdefault(sym, None)
            first.setdefault(oid, sym)
            consistent[oid] = consistent.get(oid, True) and sym == first[oid]
            assigned[oid] = assigned.get(oid, 0) + 1
            owners.setdefault(sym, set()).add(oid)
    report = []
    for oid in order:
        if perceived.get(oid, 0) == 0:
            continue
        syms = list(symbols.get(oid, {}))
        kept = (
            len(syms) == 1 and consistent.get(oid, False) and owners.get(syms[0], set()) == {oid}
        )
        report.append(ObjectIdentity(oid, syms, kept, perceived[oid], assigned.get(oid, 0)))
    return report


def _ids(mapping: dict[str, int], keys: Iterable[str]) -> list[int]:
    out = []
    for k in keys:
        if k not in mapping:
            mapping[k] = len(mapping) + 1
        out.append(mapping[k])
    return out


def mot_metrics(
    records: Sequence[TrackingRecord], threshold: float = DEFAULT_THRESHOLD_M
) -> MotMetrics:
    """ID switches, IDF1 and friends with py-motmetrics (see the module doc)."""
    if not threshold > 0:
        raise ValueError(f"distance threshold must be positive, got {threshold}")
    acc = mm.MOTAccumulator(auto_id=False)
    gt_ids: dict[str, int] = {}
    hyp_ids: dict[str, int] = {}
    for rec in records:
        gts = list(rec.truth)
        hyps = [s for s, h in rec.hypotheses.items() if np.all(np.isfinite(h.position))]
        if gts and hyps:
            g = np.stack([rec.truth[k].position for k in gts])
            h = np.stack([rec.hypotheses[k].position for k in hyps])
            dist = np.linalg.norm(g[:, None, :] - h[None, :, :], axis=2)
            dist[dist > threshold] = np.nan
        else:
            dist = np.empty((len(gts), len(hyps)))
        acc.update(_ids(gt_ids, gts), _ids(hyp_ids, hyps), dist, frameid=rec.frame)
    names = ["num_switches", "idf1", "idp", "idr", "mota", "idtp", "idfp", "idfn"]
    row = mm.metrics.create().compute(acc, metrics=names, name="run").iloc[0]

    def num(x: float) -> float:
        return float(x) if x is not None and math.isfinite(float(x)) else math.nan

    return MotMetrics(
        id_switches=int(row["num_switches"]),
        idf1=num(row["idf1"]),
        idp=num(row["idp"]),
        idr=num(row["idr"]),
        mota=num(row["mota"]),
        idtp=int(round(num(row["idtp"]) if math.isfinite(num(row["idtp"])) else 0)),
        idfp=int(round(num(row["idfp"]) if math.isfinite(num(row["idfp"])) else 0)),
        idfn=int(round(num(row["idfn"]) if math.isfinite(num(row["idfn"])) else 0)),
        threshold=threshold,
    )


def evaluate(
    records: Sequence[TrackingRecord], threshold: float = DEFAULT_THRESHOLD_M
) -> Evaluation:
    """The identity report (every frame and at the end), the motmetrics figures, HOTA and
    the belief accuracy of one run."""
    records = list(records)
    return Evaluation(len(records), identity_report(records), mot_metrics(records, threshold),
                      identity_report(revised_records(records)),
                      belief_accuracy(records, threshold), hota_metrics(records, threshold))
