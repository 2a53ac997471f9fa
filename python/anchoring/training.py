"""Labelled pairs for the matching function, and its training (the analogue of the original's
annotation interface, with the simulator's ground truth as the annotator).

This module is the only part of ``anchoring`` that reads ``Percept.truth_id``, and only to
label training pairs: an *oracle* keeps one anchor per ground-truth object, updated with the
same acquire / re-acquire rules as :class:`~anchoring.manager.AnchorManager` (and the same
glitch rule), and every percept of a frame is paired with every anchor that existed before the
frame: label 1 when both are the same object. The matching logic itself never sees truth.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from anchoring.anchor import Anchor
from anchoring.features import pair_features
from anchoring.matcher import RbfSvm
from anchoring.similarity import FEATURES
from percepts import PerceptFrame


@dataclass
class PairSet:
    x: np.ndarray  # (n, 5) similarity vectors
    y: np.ndarray  # (n,) 1 = same object
    group: np.ndarray  # (n,) stream index, for held-out splits by stream

    def __len__(self) -> int:
        return int(self.y.shape[0])

    @staticmethod
    def concat(sets: Iterable[PairSet]) -> PairSet:
        sets = list(sets)
        if not sets:
            return PairSet(np.zeros((0, len(FEATURES))), np.zeros(0, int), np.zeros(0, int))
        return PairSet(np.concatenate([s.x for s in sets]), np.concatenate([s.y for s in sets]),
                       np.concatenate([s.group for s in sets]))


def labelled_pairs(frames: Iterable[PerceptFrame], group: int = 0,
                   glitch_seconds: float = 1.0, history_size: int = 10) -> PairSet:
    """All (anchor, percept) pairs of a stream with their same-object labels.

    Percepts without ``truth_id`` cannot be labelled and are skipped.
    """
    oracle: dict[str, Anchor] = {}
    xs: list[np.ndarray] = []
    ys: list[np.ndarray] = []
    for frame in frames:
        percepts = [p for p in frame.percepts if p.truth_id is not None]
        for ident, anchor in list(oracle.items()):
            if not anchor.confirmed and frame.time - anchor.created > glitch_seconds:
                del oracle[ident]
        if not percepts:
            continue
        idents = list(oracle)
        if idents:
            feats = pair_features([oracle[i] for i in idents], percepts)
            labels = np.array([[a == p.truth_id for p in percepts] for a in idents], dtype=int)
            xs.append(feats.reshape(-1, len(FEATURES)))
            ys.append(labels.reshape(-1))
        for p in percepts:
            anchor = oracle.get(p.truth_id)  # type: ignore[arg-type]
            if anchor is None:
                oracle[p.truth_id] = Anchor.acquire(str(p.truth_id), p, history_size)  # type: ignore[index]
            else:
                anchor.reacquire(p)
                anchor.confirmed = True
    if not xs:
        return PairSet.concat([])
    y = np.concatenate(ys)
    return PairSet(np.concatenate(xs), y, np.full(y.shape[0], group))


def balanced_subsample(pairs: PairSet, max_pairs: int, rng: np.random.Generator) -> PairSet:
    """At most ``max_pairs`` pairs, half of each label where possible (uniform within label)."""
    keep: list[np.ndarray] = []
    for label in (0, 1):
        idx = np.flatnonzero(pairs.y == label)
        n = min(idx.size, max_pairs // 2)
        keep.append(rng.choice(idx, n, replace=False) if n < idx.size else idx)
    sel = np.sort(np.concatenate(keep))
    return PairSet(pairs.x[sel], pairs.y[sel], pairs.group[sel])


def fit_svm(pairs: PairSet, c: float = 10.0, gamma: float = 2.0) -> RbfSvm:
    """An RBF C-SVC (scikit-learn) exported as a numpy-evaluated :class:`RbfSvm`."""
    from sklearn.svm import SVC

    svc = SVC(C=c, kernel="rbf", gamma=gamma, class_weight="balanced")
    svc.fit(pairs.x, pairs.y)
    sign = 1.0 if svc.classes_[1] == 1 else -1.0
    return RbfSvm(
        support_vectors=svc.support_vectors_.copy(),
        coefficients=sign * svc.dual_coef_.reshape(-1),
        intercept=float(sign * svc.intercept_[0]),
        gamma=float(gamma),
        features=FEATURES,
        info={"trainer": "sklearn.svm.SVC", "C": c, "gamma": gamma,
              "class_weight": "balanced", "train_pairs": len(pairs),
              "train_positives": int(pairs.y.sum())},
    )


def scores(model: RbfSvm, pairs: PairSet) -> dict[str, float]:
    """Accuracy, and recall on each label (same / different object)."""
    pred = model.predict(pairs.x)
    same = pairs.y == 1
    return {
        "pairs": len(pairs),
        "accuracy": float((pred == pairs.y).mean()) if len(pairs) else float("nan"),
        "same_recall": float((pred[same] == 1).mean()) if same.any() else float("nan"),
        "different_recall": float((pred[~same] == 0).mean()) if (~same).any() else float("nan"),
    }
