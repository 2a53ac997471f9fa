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
from probanchor.percepts import PerceptFrame


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
                   glitch_seconds: float = 1.0, history_size: int = 10,
                   track_hidden: bool = True, seed: int = 0) -> PairSet:
    """All (anchor, percept) pairs of a stream with their same-object labels.

    Percepts without ``truth_id`` cannot be labelled and are skipped. With ``track_hidden``,
    an anchor whose object the frame's ground truth (``truth["objects"][id]``) says is present
    but not visible gets, as in the running system, a position particle cloud (100 particles,
    1.5 cm spread) around the true position, standing in for a reasoner that found it; so
    re-acquisitions after an occlusion are labelled as the closed loop would see them, and the
    classifier does not learn that a far-away percept is the same object. Without ground truth
    (or with ``track_hidden=False``) a hidden anchor keeps its last position.
    """
    rng = np.random.default_rng(seed)
    oracle: dict[str, Anchor] = {}
    xs: list[np.ndarray] = []
    ys: list[np.ndarray] = []
    for frame in frames:
        percepts = [p for p in frame.percepts if p.truth_id is not None]
        for ident, anchor in list(oracle.items()):
            if not anchor.confirmed and frame.time - anchor.created > glitch_seconds:
                del oracle[ident]
        if not percepts:
            if track_hidden:
                _track_hidden(oracle, set(), frame, rng)
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
        if track_hidden:
            _track_hidden(oracle, {p.truth_id for p in percepts}, frame, rng)
    if not xs:
        return PairSet.concat([])
    y = np.concatenate(ys)
    return PairSet(np.concatenate(xs), y, np.full(y.shape[0], group))


def _track_hidden(oracle: dict[str, Anchor], perceived: set[str | None], frame: PerceptFrame,
                  rng: np.random.Generator) -> None:
    objects = frame.truth.get("objects", {}) if isinstance(frame.truth, dict) else {}
    for ident, anchor in oracle.items():
        info = objects.get(ident)
        if ident in perceived or not isinstance(info, dict) or "position" not in info:
            continue
        if info.get("visible", True) or not info.get("present", True):
            continue
        true = np.asarray(info["position"], dtype=float)
        anchor.set_position_particles(true + rng.normal(0.0, 0.015, (100, 3)), None, frame.time)


def lookalike_negatives(pairs: PairSet, rng: np.random.Generator, fraction: float = 0.5,
                        min_distance: float = 0.12, max_distance: float = 0.6) -> PairSet:
    """Hard negatives: an identical-looking *other* object somewhere else.

    Streams rarely show two indistinguishable objects, so the learned boundary is left to
    extrapolation exactly where position must decide (two red balls 30 cm apart). For a random
    ``fraction`` of the same-object pairs this makes a copy labelled "different" whose position
    similarity is that of a look-alike ``min_distance`` to ``max_distance`` away (uniform),
    every other similarity unchanged. ``min_distance`` is the matching radius this teaches:
    farther than that, an object is only re-acquired through the reasoning's particles.
    """
    same = np.flatnonzero(pairs.y == 1)
    pick = rng.choice(same, int(round(fraction * same.size)), replace=False)
    x = pairs.x[pick].copy()
    x[:, FEATURES.index("position")] = np.exp(-rng.uniform(min_distance, max_distance, pick.size))
    return PairSet(x, np.zeros(pick.size, int), pairs.group[pick])


def stale_positives(pairs: PairSet, rng: np.random.Generator, fraction: float = 0.3,
                    min_gap: float = 1.0, max_gap: float = 30.0) -> PairSet:
    """Same-object pairs seen again after a long gap (the reasoning kept the object).

    Long occlusions are few in any stream, so the boundary at a small time similarity is left
    to extrapolation, and an SVM may refuse a perfect match only because the object was hidden
    for a while: exactly the re-acquisition through the reasoning's particles that anchoring is
    for. For a random ``fraction`` of the same-object pairs this makes a copy, still labelled
    "same", whose time similarity is that of a gap of ``min_gap`` to ``max_gap`` seconds
    (uniform); every other similarity unchanged.
    """
    same = np.flatnonzero(pairs.y == 1)
    pick = rng.choice(same, int(round(fraction * same.size)), replace=False)
    x = pairs.x[pick].copy()
    gap = rng.uniform(min_gap, max_gap, pick.size)
    x[:, FEATURES.index("time")] = 2.0 * np.exp(-gap) / (1.0 + np.exp(-gap))
    return PairSet(x, np.ones(pick.size, int), pairs.group[pick])


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


def appearance_calibration(model: RbfSvm, pairs: PairSet) -> dict[str, float]:
    """The appearance decision's log likelihood ratio, fitted on labelled pairs.

    The appearance decision ``f`` is the matching function on a pair's similarities with
    position and time taken as agreeing (:func:`anchoring.likelihood.appearance_log_ratio` with
    the identity calibration). The different-object pairs are of two kinds: distinct-looking
    objects, against which Platt scaling gives the ratio ``log A0 = a f + b``, and a share
    ``rho`` of look-alikes whose decisions fall as the same object's do::

        p(f | different) = (1 - rho) q(f) + rho p(f | same)
        A = p(f | same) / p(f | different) = 1 / ((1 - rho) / A0 + rho)
        logit P(same | f) = logit(prior) + log A              (Bayes' rule)

    ``a``, ``b`` and ``rho`` maximise the likelihood of the pairs' labels under the last line
    (``scipy.optimize.minimize``, from the plain Platt fit, scikit-learn's
    ``LogisticRegression``, with ``rho`` small). A linear log ratio alone grows without bound
    with ``f``, where look-alikes are as common among the most similar pairs as the same object
    is: identical twins were given ``A`` of about 1e4. Returns ``{"scale": a, "offset": b,
    "lookalike": rho, "pairs": n}`` (:class:`anchoring.likelihood.AssociationModel`).
    """
    from scipy.optimize import minimize
    from scipy.special import expit, log_expit, logit
    from sklearn.linear_model import LogisticRegression

    from anchoring.likelihood import AssociationModel, appearance_log_ratio, calibrated_log_ratio

    if len(pairs) == 0 or pairs.y.min() == pairs.y.max():
        raise ValueError("appearance calibration needs pairs of both labels")
    d = appearance_log_ratio(model, pairs.x, AssociationModel())
    y = pairs.y.astype(bool)
    prior_logit = float(logit(y.mean()))
    platt = LogisticRegression(C=100.0).fit(d.reshape(-1, 1), y)

    def loss(theta: np.ndarray) -> float:
        # negative log likelihood of the labels; theta = (a, b, logit rho)
        s = prior_logit + calibrated_log_ratio(d, theta[0], theta[1], float(expit(theta[2])))
        return -float(log_expit(np.where(y, s, -s)).sum())

    start = np.array([platt.coef_[0, 0], platt.intercept_[0] - prior_logit, logit(1e-3)])
    fit = minimize(loss, start, method="Nelder-Mead",
                   options={"maxiter": 4000, "xatol": 1e-6, "fatol": 1e-6})
    a, b, r = (float(v) for v in fit.x)
    return {"scale": a, "offset": b, "lookalike": float(expit(r)), "pairs": len(pairs)}
