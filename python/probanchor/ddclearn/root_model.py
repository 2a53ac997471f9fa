"""A target's root model: one regularised regression over every feature the bias allows at the root.

A tree's leaf reads the values its path tested; a propositional model reads every feature at
once (the mean of one related entity's attribute beside the count of another's, the attributes
of both entities of a pair). The root model gives the tree that view: a generalised linear model
over the *root features* of a target (each candidate literal that reads only the head's
variables: a numeric value, with its mean where undefined and an "undefined" indicator beside
it; a count; an indicator per branch of a discrete attribute, an aggregate's mode, a threshold
test or a relation, but one), with an L2 penalty of scikit-learn's default strength. Its linear
predictors, the *scores* (one for a Boolean, continuous or count target, K - 1 for K classes),
are regressors that every node of the tree starts with and that a leaf's model takes as an
*offset* (:func:`probanchor.ddclearn.leaves.fit_offset_leaf`): a leaf shifts the root model's
prediction and adds its path's own values where the tree found it wrong, and a tree without
splits is the root model itself. Whether a tree reads the root model at all is decided on
held-out examples (:class:`probanchor.ddclearn.search.SearchOptions`, ``root_model``).

The scores the search sees are *cross-fitted*: a row's score comes from the model fitted on the
other folds (by example), so that a leaf weighs the score by how well it predicts rows it was not
fitted on. The learned clause computes the root model fitted on every row.

==========  =======================================  ========================================
kind        model (on standardised features)         score
==========  =======================================  ========================================
discrete    logistic (K = 2) or multinomial (K > 2)  the logit of each class against the first
            regression, penalty ``l2 / 2 ||w||^2``
continuous  ridge regression                         the predicted mean
count       Poisson regression                       the log of the predicted rate
==========  =======================================  ========================================

Example::

    features = root_features(candidates, outcomes, n_rows)
    model = fit_root_model("discrete", y, w, example, features, n_classes=3)
    model.term()          # "root_model([value(12, 0.5), branch(14, 0), ...], [[...], [...]])"
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.special import gammaln, log_softmax

__all__ = ["Feature", "RootFeatures", "RootModel", "block_of", "fit_root_model", "fold_of",
           "root_features"]

#: Candidate kinds whose value is a feature (with an "undefined" indicator when it can be).
VALUE_KINDS: frozenset[str] = frozenset({"numeric", "agg_numeric", "count"})
#: Candidate kinds whose branches are indicator features.
BRANCH_KINDS: frozenset[str] = frozenset({"discrete", "agg_discrete", "threshold", "test"})

#: The L2 penalty of the root model, ``l2 / 2 ||w||^2`` on the standardised weights against
#: the summed log-likelihood: scikit-learn's default for its logistic regression (C = 1).
#: A penalty chosen by cross-validation from (0.3, 3, 30) was no better on held-out data (the
#: choice is noisy where it matters, on a few hundred examples) and three times as slow.
L2: float = 1.0
#: Folds of the cross-validation (by example).
FOLDS: int = 5
#: Fewest examples for a root model (each fold needs enough rows to fit on).
MIN_EXAMPLES: int = 50
_MAX_ITER = 500
_TOL = 1e-6
_DIGITS = 10


@dataclass(frozen=True)
class Feature:
    """One input of the root model.

    Attributes
    ----------
    candidate : int
        The candidate literal's id (``learn_candidates/3``).
    part : {"value", "branch"}
        Its value (``fill`` where it is undefined), or the indicator of one of its branches.
    branch : int
        The branch of an indicator (the value's is 0).
    fill : float
        Where the value is undefined, the training rows' mean.
    label : str
        What it is, for reports (the literal's text).
    """

    candidate: int
    part: str
    branch: int = 0
    fill: float = 0.0
    label: str = ""

    def term(self) -> str:
        """The Prolog text of the feature (``learn_root_model/3``)."""
        if self.part == "value":
            return f"value({self.candidate}, {_num(self.fill)})"
        return f"branch({self.candidate}, {self.branch})"


@dataclass(frozen=True)
class RootFeatures:
    """The root features of a target's rows: one column per :class:`Feature`."""

    X: np.ndarray
    features: list[Feature]


def root_features(candidates: Sequence[dict], branch: Sequence[np.ndarray],
                  x: Sequence[np.ndarray], w: np.ndarray) -> RootFeatures:
    """The feature columns of the root candidates whose outcome is certain in every row.

    Parameters
    ----------
    candidates : sequence of dict
        The root candidates (``LearningData.candidates``, ``root`` true).
    branch, x : sequence of ndarray
        Per candidate, each row's branch (-1 where the outcome is not one certain branch: the
        candidate is left out) and value.
    w : ndarray
        The rows' weights (for the fill values).

    Returns
    -------
    RootFeatures
        Columns that vary over the rows of positive weight, each once (a column equal to an
        earlier one is left out); of a candidate's branches, every one that occurs but the
        last (the indicators of all would sum to 1, the intercept's column).
    """
    cols: list[np.ndarray] = []
    feats: list[Feature] = []
    seen: set[bytes] = set()
    live = w > 0

    def add(col: np.ndarray, f: Feature) -> None:
        c = col[live]
        if len(c) == 0 or np.ptp(c) == 0:
            return
        key = np.ascontiguousarray(col).tobytes()
        if key in seen:
            return
        seen.add(key)
        cols.append(col)
        feats.append(f)

    for c, b, v in zip(candidates, branch, x, strict=True):
        if (b < 0).any():
            continue
        kind = str(c["kind"])
        cid = int(c["id"])
        label = str(c["labels"][0])
        n_branches = int(c["branches"])
        if kind in VALUE_KINDS:
            defined = b == 0
            if not defined[live].any():
                continue
            fill = float(np.average(v[defined & live], weights=w[defined & live]))
            add(np.where(defined, v, fill), Feature(cid, "value", 0, fill, label))
            if n_branches > 1:
                add((~defined).astype(float),
                    Feature(cid, "branch", n_branches - 1, 0.0, f"{label} [undefined]"))
        elif kind in BRANCH_KINDS:
            # one indicator per branch that occurs but the last: they sum to 1
            seen_branches = [k for k in range(n_branches) if (b[live] == k).any()]
            for k in seen_branches[:-1]:
                add((b == k).astype(float),
                    Feature(cid, "branch", k, 0.0, str(c["labels"][k])))
    X = np.column_stack(cols) if cols else np.zeros((len(w), 0))
    return RootFeatures(X=X, features=feats)


@dataclass(frozen=True)
class RootModel:
    """A fitted root model and the cross-fitted scores of the training rows.

    Attributes
    ----------
    features : list of Feature
        Its inputs.
    rows : list of list of float
        Per score, the weights over the features in their own units and the bias last.
    l2 : float
        Its penalty.
    cv_log_likelihood : float
        Its cross-validated log-likelihood per unit of weight.
    plain_cv_log_likelihood : float
        The same for the model without features (class frequencies, a Gaussian, a Poisson).
    scores : ndarray of shape (n, q)
        The training rows' cross-fitted scores.
    """

    features: list[Feature]
    rows: list[list[float]]
    l2: float
    cv_log_likelihood: float
    plain_cv_log_likelihood: float
    scores: np.ndarray

    @property
    def n_scores(self) -> int:
        return len(self.rows)

    def term(self) -> str:
        """``root_model(Features, Rows)`` as Prolog text (``learn_root_model/3``)."""
        fs = ", ".join(f.term() for f in self.features)
        rows = ", ".join("[" + ", ".join(_num(v) for v in r) + "]" for r in self.rows)
        return f"root_model([{fs}], [{rows}])"


def _num(x: float) -> str:
    x = float(x)
    if not math.isfinite(x):
        raise ValueError(f"a root model's parameter is not finite: {x!r}")
    return repr(float(f"{x:.{_DIGITS}g}"))


def fold_of(example: np.ndarray, k: int = FOLDS) -> np.ndarray:
    """A fold index per row: the examples, shuffled with a fixed seed, dealt out in turn.

    The rows of one example (its partial worlds) are in one fold; the same examples give the
    same folds.
    """
    uniq, inv = np.unique(example, return_inverse=True)
    order = np.random.default_rng(0).permutation(len(uniq))
    fold_of = np.empty(len(uniq), dtype=np.int64)
    fold_of[order] = np.arange(len(uniq)) % k
    return fold_of[inv]


def block_of(example: np.ndarray, k: int) -> np.ndarray:
    """A block index per row: the examples cut into ``k`` runs of consecutive examples.

    Example ``e`` of ``E`` (examples are numbered in the order of the data) is in block
    ``e * k // E``, so the rows of one example, and examples written together (one world's),
    are in one block.
    """
    uniq, inv = np.unique(example, return_inverse=True)
    return (np.arange(len(uniq)) * k // max(len(uniq), 1))[inv]


class _Standard:
    """Weighted standardisation of the columns (each varies over the rows)."""

    def __init__(self, X: np.ndarray, w: np.ndarray) -> None:
        W = w.sum()
        self.mean = w @ X / W
        sd = np.sqrt(w @ (X - self.mean) ** 2 / W)
        self.scale = np.where(sd > 0, sd, 1.0)

    def __call__(self, X: np.ndarray) -> np.ndarray:
        return (X - self.mean) / self.scale

    def back(self, coef: np.ndarray, intercept: np.ndarray) -> np.ndarray:
        """Rows [w_1..w_p, b] in the features' own units from standardised ones."""
        c = np.atleast_2d(coef) / self.scale
        b = np.atleast_1d(intercept) - c @ self.mean
        return np.column_stack([c, b])


def _fit(kind: str, Z: np.ndarray, y: np.ndarray, w: np.ndarray, K: int | None,
         l2: float, smoothing: float) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients (one row per linear predictor) and intercepts on standardised features.

    Discrete: one row per class (a class without rows has intercept -inf), with one pseudo-row
    per class at the features' mean of weight ``smoothing``, as the leaves' regressions have.
    Continuous: the mean's. Count: the log rate's.
    """
    from sklearn.exceptions import ConvergenceWarning

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        if kind == "discrete":
            from sklearn.linear_model import LogisticRegression

            model = LogisticRegression(C=1.0 / l2, max_iter=_MAX_ITER, tol=_TOL)
            if smoothing > 0:
                Z = np.vstack([Z, np.zeros((int(K or 0), Z.shape[1]))])
                y = np.concatenate([y, np.arange(int(K or 0))])
                w = np.concatenate([w, np.full(int(K or 0), smoothing)])
            model.fit(Z, y, sample_weight=w)
            coef = np.zeros((int(K or 0), Z.shape[1]))
            icpt = np.full(int(K or 0), -np.inf)
            cls = model.classes_.astype(np.int64)
            if len(cls) == 2:   # sklearn's binary model: the logit of classes_[1]
                coef[cls[1]], icpt[cls[1]] = model.coef_[0], model.intercept_[0]
                coef[cls[0]], icpt[cls[0]] = 0.0, 0.0
            else:
                coef[cls], icpt[cls] = model.coef_, model.intercept_
            return coef, icpt
        if kind == "continuous":
            W = w.sum()
            mu = w @ y / W
            A = np.column_stack([Z, np.ones(len(y))]) * np.sqrt(w)[:, None]
            P = np.eye(A.shape[1]) * l2
            P[-1, -1] = 0.0
            # ridge on the standardised target: its penalty is on the scale of a class's logit
            sd = math.sqrt(max(float(w @ (y - mu) ** 2 / W), 1e-300))
            beta = np.linalg.solve(A.T @ A + P, A.T @ (np.sqrt(w) * (y - mu) / sd))
            return beta[None, :-1] * sd, np.array([beta[-1] * sd + mu])
        from sklearn.linear_model import PoissonRegressor

        model = PoissonRegressor(alpha=l2 / float(w.sum()), max_iter=_MAX_ITER)
        model.fit(Z, y, sample_weight=w)
        return model.coef_[None, :], np.array([model.intercept_])


def _log_likelihood(kind: str, eta: np.ndarray, y: np.ndarray, var: float) -> np.ndarray:
    """Per row: the log-likelihood of y under the linear predictors eta (n x K or n x 1)."""
    if kind == "discrete":
        lp = log_softmax(eta, axis=1)
        return lp[np.arange(len(y)), y.astype(np.int64)]
    if kind == "continuous":
        return -0.5 * (math.log(2 * math.pi * var) + (y - eta[:, 0]) ** 2 / var)
    return y * eta[:, 0] - np.exp(eta[:, 0]) - gammaln(y + 1.0)


def _plain_cv(kind: str, y: np.ndarray, w: np.ndarray, folds: np.ndarray, K: int | None,
              smoothing: float) -> float:
    """The cross-validated log-likelihood (per unit weight) of the model without features."""
    total = 0.0
    for f in np.unique(folds):
        tr, te = folds != f, folds == f
        if kind == "discrete":
            counts = np.bincount(y[tr].astype(np.int64), weights=w[tr], minlength=int(K or 0))
            p = (counts + smoothing) / (w[tr].sum() + smoothing * int(K or 0))
            total += float(w[te] @ np.log(np.maximum(p[y[te].astype(np.int64)], 1e-300)))
        elif kind == "continuous":
            mu = w[tr] @ y[tr] / w[tr].sum()
            var = max(float(w[tr] @ (y[tr] - mu) ** 2 / w[tr].sum()), 1e-12)
            total += float(w[te] @ _log_likelihood(kind, np.full((te.sum(), 1), mu), y[te], var))
        else:
            rate = max(float(w[tr] @ y[tr] / w[tr].sum()), 1e-9)
            total += float(w[te] @ _log_likelihood(kind, np.full((te.sum(), 1), math.log(rate)),
                                                   y[te], 0.0))
    return total / float(w.sum())


def fit_root_model(kind: str, y: np.ndarray, w: np.ndarray, example: np.ndarray,
                   features: RootFeatures, n_classes: int | None = None,
                   smoothing: float = 1.0, l2: float = L2) -> RootModel | None:
    """Fit a target's root model and cross-fit its scores.

    The scores of the training rows are out-of-fold (``FOLDS`` folds of the examples), and
    so is the log-likelihood that decides whether the model is worth having (a continuous
    target's variance is each fold's mean squared out-of-fold residual). None when there are
    no features, fewer than ``MIN_EXAMPLES`` examples, a discrete target with one class in a
    fold, or when the model does not do better in cross-validation than the model without
    features.

    Parameters
    ----------
    kind : {"discrete", "continuous", "count"}
    y : ndarray
        The rows' values (class indices for a discrete target).
    w : ndarray
        The rows' weights.
    example : ndarray
        Each row's example (the rows of one example are in one fold).
    features : RootFeatures
    n_classes : int, optional
        K for a discrete target.
    smoothing : float, default=1.0
        The pseudo-count of the model without features (``LeafOptions.smoothing``).
    l2 : float, default=L2
        The penalty ``l2 / 2 ||w||^2`` on the standardised weights.

    Returns
    -------
    RootModel or None
    """
    live = w > 0
    X = features.X
    if X.shape[1] == 0 or len(np.unique(example[live])) < MIN_EXAMPLES:
        return None
    y_all = y
    if kind == "discrete" and len(np.unique(y[live])) < 2:
        return None
    Xl, yl, wl, el = X[live], y[live], w[live], example[live]
    k = min(FOLDS, len(np.unique(el)))
    folds = fold_of(el, k)
    plain = _plain_cv(kind, yl, wl, folds, n_classes, smoothing)
    eta = np.zeros((len(yl), int(n_classes) if kind == "discrete" else 1))
    total = 0.0
    for f in range(k):
        tr, te = folds != f, folds == f
        if kind == "discrete" and len(np.unique(yl[tr])) < 2:
            return None
        std = _Standard(Xl[tr], wl[tr])
        coef, icpt = _fit(kind, std(Xl[tr]), yl[tr], wl[tr], n_classes, l2, smoothing)
        eta[te] = std(Xl[te]) @ coef.T + icpt
        if kind == "continuous":
            r = yl[te] - eta[te, 0]
            var = max(float(wl[te] @ r**2 / wl[te].sum()), 1e-12)
            total += float(wl[te] @ _log_likelihood(kind, eta[te], yl[te], var))
    if not np.isfinite(eta).all():
        return None
    if kind != "continuous":
        total = float(wl @ _log_likelihood(kind, eta, yl, 0.0))
    cv = total / float(wl.sum())
    if not cv > plain:
        return None
    std = _Standard(Xl, wl)
    coef, icpt = _fit(kind, std(Xl), yl, wl, n_classes, l2, smoothing)
    if kind == "discrete":
        present = np.isfinite(icpt)
        ref = int(np.flatnonzero(present)[0])
        rows = std.back(coef - coef[ref], icpt - icpt[ref])[present][1:]
        oof = (eta - eta[:, [ref]])[:, present][:, 1:]
    else:
        rows = std.back(coef, icpt)
        oof = eta[:, :1]
    scores = np.zeros((len(y_all), oof.shape[1]))
    scores[live] = oof
    return RootModel(features=list(features.features), rows=[list(map(float, r)) for r in rows],
                     l2=l2, cv_log_likelihood=cv, plain_cv_log_likelihood=plain, scores=scores)
