"""HOTA, DetA, AssA and LocA of a run (Luiten et al. 2021, "HOTA: A Higher Order Metric for
Evaluating Multi-Object Tracking"), computed by TrackEval (``trackeval``, the reference code of
the paper) on 3-D positions.

Per frame the ground truth is every object in ``record.truth``, visible *and hidden*, at its
true position, and the hypotheses are every anchor's (or track's) point estimate, as for the
py-motmetrics figures (:mod:`probanchor.evaluation.metrics`). The similarity of a ground-truth
object and a hypothesis ``d`` metres apart is TrackEval's Euclidean similarity::

    S = max(0, 1 - d / threshold)      (threshold: 0.1 m by default; S >= alpha to match)

so a hypothesis on the truth scores 1 and one ``threshold`` away or more scores 0. For each
localisation threshold alpha in 0.05, 0.10, ..., 0.95 (a match needs d <= (1 - alpha) threshold:
9.5 cm at alpha 0.05, 5 mm at 0.95), TrackEval matches ground truth and hypotheses per frame
(Hungarian, preferring pairs that are matched often over the whole run) and counts true positives
TP, false negatives FN and false positives FP; then

    DetA_alpha = |TP| / (|TP| + |FN| + |FP|)
    A(c)       = |TPA(c)| / (|TPA(c)| + |FNA(c)| + |FPA(c)|)   for a true positive c, where TPA
                 are the true positives with c's pair of ids, FNA the frames where c's object is
                 matched to another id or not at all, FPA the frames where c's hypothesis id is
                 matched to another object or not at all
    AssA_alpha = (1 / |TP|) sum over c in TP of A(c)
    HOTA_alpha = sqrt(DetA_alpha * AssA_alpha)
    LocA_alpha = (1 / |TP|) sum over c in TP of S(c)      (1 when there is no TP: TrackEval's)

and HOTA, DetA, AssA and LocA are the means over the 19 alphas. DetA measures finding the
objects (hidden ones included, at their places), AssA keeping each one's identity over the
whole run, LocA how close the matched estimates are.

TrackEval (1.3.0, numpy 2) declares a dependency on ``opencv-python``, which would overwrite the
``cv2`` of ``opencv-python-headless``: ``scripts/setup.sh`` installs it with ``pip --no-deps``
(``requirements-nodeps.txt``) and ``pyproject.toml`` lists what its import needs
(``pycocotools``, ``tabulate``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from probanchor.evaluation.record import TrackingRecord

#: The fields a run summary gets from :func:`hota_fields` (docs/evaluation.md).
HOTA_FIELDS = ("hota", "deta", "assa", "loca")


@dataclass
class HotaMetrics:
    """HOTA and its parts for one run (means over the alphas; NaN when undefined: no ground
    truth and no hypothesis in any frame)."""

    hota: float
    deta: float
    assa: float
    loca: float
    threshold: float


def similarity(truth: np.ndarray, hypotheses: np.ndarray, threshold: float) -> np.ndarray:
    """``max(0, 1 - d / threshold)`` for every pair of (G, 3) truth and (H, 3) hypothesis
    positions: a (G, H) array."""
    d = np.linalg.norm(truth[:, None, :] - hypotheses[None, :, :], axis=2)
    return np.maximum(0.0, 1.0 - d / threshold)


def trackeval_data(records: Sequence[TrackingRecord], threshold: float) -> dict:
    """The input of TrackEval's ``HOTA.eval_sequence`` for a run: ids numbered from 0 in order
    of first appearance, one similarity matrix per frame. Hypotheses without a finite
    position are left out."""
    gt_ids: dict[str, int] = {}
    hyp_ids: dict[str, int] = {}
    data: dict = {"gt_ids": [], "tracker_ids": [], "similarity_scores": []}
    n_gt = n_hyp = 0
    for rec in records:
        gts = list(rec.truth)
        hyps = [s for s, h in rec.hypotheses.items() if np.all(np.isfinite(h.position))]
        data["gt_ids"].append(np.array([gt_ids.setdefault(k, len(gt_ids)) for k in gts], int))
        data["tracker_ids"].append(
            np.array([hyp_ids.setdefault(k, len(hyp_ids)) for k in hyps], int))
        g = np.array([rec.truth[k].position for k in gts], float).reshape(-1, 3)
        h = np.array([rec.hypotheses[k].position for k in hyps], float).reshape(-1, 3)
        data["similarity_scores"].append(similarity(g, h, threshold))
        n_gt += len(gts)
        n_hyp += len(hyps)
    data.update(num_gt_ids=len(gt_ids), num_tracker_ids=len(hyp_ids), num_gt_dets=n_gt,
                num_tracker_dets=n_hyp, num_timesteps=len(records))
    return data


def hota_metrics(records: Sequence[TrackingRecord], threshold: float = 0.1) -> HotaMetrics:
    """HOTA, DetA, AssA and LocA of a run (see the module doc).

    Parameters
    ----------
    records : sequence of TrackingRecord
        The run, one record per frame.
    threshold : float
        Distance in metres at which the similarity falls to 0 (the project's match distance).

    Returns
    -------
    HotaMetrics

    Raises
    ------
    ValueError
        ``threshold`` is not positive.
    """
    if not threshold > 0:
        raise ValueError(f"distance threshold must be positive, got {threshold}")
    from trackeval.metrics import HOTA

    records = list(records)
    data = trackeval_data(records, threshold)
    if data["num_gt_dets"] == 0 and data["num_tracker_dets"] == 0:
        return HotaMetrics(math.nan, math.nan, math.nan, math.nan, threshold)
    res = HOTA().eval_sequence(data)
    return HotaMetrics(*(float(np.mean(res[k])) for k in ("HOTA", "DetA", "AssA", "LocA")),
                       threshold=threshold)


def hota_fields(metrics: HotaMetrics) -> dict[str, float | None]:
    """The summary fields ``hota``, ``deta``, ``assa``, ``loca`` (``None`` when undefined),
    rounded to 6 places."""
    values = (metrics.hota, metrics.deta, metrics.assa, metrics.loca)
    return {k: (round(v, 6) if math.isfinite(v) else None)
            for k, v in zip(HOTA_FIELDS, values, strict=True)}
