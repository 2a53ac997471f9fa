"""Propositional baselines on the aggregate features the structure learner sees at the root.

A learned distributional logic tree is only as good as the literals its bias allows. To tell
how much the tree's structure search adds, the same features can be given to propositional
models: :func:`feature_table` turns each candidate literal of a target's root node that reads
only the head's variables into columns of a table (one row per grounding), and
:func:`fit_baselines` fits three models on such a table:

==============  ==============================  ========================================
name            discrete target (K classes)     continuous (count) target
==============  ==============================  ========================================
``constant``    class frequencies, add-one      Gaussian mean and variance (Poisson rate)
``linear``      ``LogisticRegression``          ``LinearRegression`` + residual variance
                (multinomial for K > 2)         (``PoissonRegressor``)
``boosting``    ``HistGradientBoosting-``       ``HistGradientBoostingRegressor`` +
                ``Classifier``                  residual variance (Poisson loss)
==============  ==============================  ========================================

:func:`score` gives a fitted baseline's held-out figures in the form of
:func:`probanchor.ddclearn.evaluate`'s: the weighted mean log-likelihood per grounding (natural log)
and the accuracy (discrete) or RMSE.

Example::

    from bridge.learning import LearningData
    from probanchor.ddclearn.baselines import feature_table, fit_baselines, score

    with LearningData(["train.pl"]) as train, LearningData(["test.pl"]) as test:
        tr = feature_table(train, "gender")
        te = feature_table(test, "gender", columns=tr.names)   # the same columns, in order
        for b in fit_baselines(tr):
            print(b.name, score(b, te))
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.special import gammaln
from sklearn.ensemble import HistGradientBoostingClassifier, HistGradientBoostingRegressor
from sklearn.exceptions import ConvergenceWarning
from sklearn.linear_model import LinearRegression, LogisticRegression, PoissonRegressor
from threadpoolctl import threadpool_limits

from bridge.learning import LearningData, Outcome

__all__ = [
    "BASELINES",
    "Baseline",
    "BoostingBaseline",
    "ConstantBaseline",
    "FeatureTable",
    "LinearBaseline",
    "feature_table",
    "fit_baselines",
    "score",
]

#: Candidate kinds whose outcome is a number (a value column and an "undefined" indicator).
NUMERIC_KINDS: frozenset[str] = frozenset({"numeric", "count", "agg_numeric"})
#: Candidate kinds that become a one-hot block of their branch index.
ONE_HOT_KINDS: frozenset[str] = frozenset({"discrete", "agg_discrete", "threshold", "test"})

#: Suffix of the column that is 1 where a candidate is undefined (its last branch: undefined,
#: empty, does not hold; for a value, the indicator that it has none).
UNDEFINED = " [undefined]"
_BRANCH = re.compile(r" \[branch \d+\]$")

#: Log-probabilities of the baselines are clipped below at this value, only so that a class
#: (or a count) the model gives probability 0 does not make the mean -inf.
LOG_FLOOR: float = math.log(1e-12)

#: Smallest variance of a Gaussian baseline (a model that fits the training rows exactly).
VARIANCE_FLOOR: float = 1e-12

#: The baselines :func:`fit_baselines` fits, in order.
BASELINES: tuple[str, ...] = ("constant", "linear", "boosting")

_MAX_ITER = 2000
_POISSON_ALPHA = 0.01

#: OpenMP threads of the gradient-boosting fits: the tables are small, and on a shared machine
#: OpenMP's busy-waiting threads made a fit up to 20 times slower than one thread.
THREADS: int = 1


@dataclass(frozen=True)
class FeatureTable:
    """A target's groundings as a propositional table.

    Attributes
    ----------
    X : ndarray of shape (n, p)
        The features (float; NaN where a value is undefined).
    y : ndarray of shape (n,)
        The target: the class index in ``domain`` (int) for a discrete target, else the value.
    weight : ndarray of shape (n,)
        The weight of each row (1 for a certain grounding; partial worlds share an example's).
    names : list of str
        The column names: a candidate's branch-0 label (DC text), with the suffix
        ``" [undefined]"`` or ``" [branch k]"`` for its indicator and one-hot columns.
    kind : {"discrete", "continuous", "count"}
        The target's kind.
    n_classes : int or None
        K for a discrete target.
    domain : list of str
        The target's values (discrete), in class-index order.
    predicate : str
        The target's internal predicate name.
    """

    X: np.ndarray
    y: np.ndarray
    weight: np.ndarray
    names: list[str]
    kind: str
    n_classes: int | None
    domain: list[str] = field(default_factory=list)
    predicate: str = ""

    @property
    def n(self) -> int:
        """The number of rows (groundings, one per partial world)."""
        return int(self.X.shape[0])


def _true(v: object) -> bool:
    return v is True or v == "true"


def _target(data: LearningData, predicate: str) -> dict[str, Any]:
    targets = data.targets()
    for t in targets:
        if str(t["predicate"]) == predicate:
            return t
    names = ", ".join(str(t["predicate"]) for t in targets)
    raise ValueError(f"no target {predicate!r} in the data (targets: {names})")


def _block(cand: dict[str, Any], o: Outcome, n: int, label: str) -> list[tuple[str, np.ndarray]]:
    """The columns of one candidate from its outcome (entries per row and partial world).

    A row whose entries are several partial worlds (an uncertain fact the literal reads) gets
    the expectation over them: the factor-weighted mean of the value over the worlds where it
    is defined, and the weight of the worlds in each branch (so the indicator and one-hot
    columns are then fractions). A row without entries is undefined.
    """
    kind = str(cand["kind"])
    n_branches = int(cand["branches"])
    total = np.bincount(o.row, weights=o.factor, minlength=n)
    none = total <= 0
    safe = np.where(none, 1.0, total)
    if kind in NUMERIC_KINDS:
        regressor = np.array([_true(r) for r in cand["regressor"]], dtype=bool)
        defined = regressor[o.branch]
        rows, f = o.row[defined], o.factor[defined]
        w_def = np.bincount(rows, weights=f, minlength=n)
        sum_x = np.bincount(rows, weights=f * o.x[defined], minlength=n)
        has = w_def > 0
        value = np.full(n, np.nan)
        value[has] = sum_x[has] / w_def[has]
        undefined = np.where(none, 1.0, 1.0 - w_def / safe)
        return [(label, value), (label + UNDEFINED, np.clip(undefined, 0.0, 1.0))]
    # one-hot of the branch index (ONE_HOT_KINDS, and any other kind without a value)
    flat = np.bincount(o.row * n_branches + o.branch, weights=o.factor,
                       minlength=n * n_branches).reshape(n, n_branches)
    flat = flat / safe[:, None]
    flat[none, n_branches - 1] = 1.0
    names = [f"{label} [branch {b}]" for b in range(n_branches - 1)] + [label + UNDEFINED]
    return list(zip(names, flat.T, strict=True))


def _missing(name: str, n: int) -> np.ndarray:
    """A column of a candidate the data does not have: undefined everywhere."""
    if name.endswith(UNDEFINED):
        return np.ones(n)
    if _BRANCH.search(name):
        return np.zeros(n)
    return np.full(n, np.nan)


def feature_table(data: LearningData, predicate: str,
                  columns: Sequence[str] | None = None) -> FeatureTable:
    """The propositional table of a target: its root rows and root candidates' outcomes.

    Each candidate literal that the bias allows at the target's root node and that reads only
    the head's variables (``root`` true) gives one block of columns, named by its branch-0
    label (the DC text of the literal):

    - ``numeric``, ``count``, ``agg_numeric``: its value (NaN where undefined) and a 0/1
      column ``"<label> [undefined]"``;
    - ``discrete``, ``agg_discrete``, ``threshold``, ``test``: a one-hot of the branch index,
      ``"<label> [branch k]"`` for every branch but the last, whose column (undefined, empty
      or does not hold) is ``"<label> [undefined]"``.

    Parameters
    ----------
    data : LearningData
        The data (training or test), loaded with its targets.
    predicate : str
        The target's internal predicate name (``TargetResult.predicate``, e.g. ``gender``).
    columns : sequence of str, optional
        The columns to build, in this order (a training table's ``names``), so that a test
        table aligns with the training table: a column the data has no candidate for is that
        candidate undefined (value NaN, ``[undefined]`` 1, other one-hot columns 0); the
        data's other columns are left out. Default: every column of the data's candidates.

    Returns
    -------
    FeatureTable
    """
    target = _target(data, predicate)
    kind = str(target["kind"])
    domain = [str(v) for v in target.get("domain", [])]
    root = data.root(predicate)
    try:
        n = len(root.y)
        cands = [c for c in data.candidates(root.node) if _true(c["root"])]
        outcomes = data.evaluate(root.node, [int(c["id"]) for c in cands])
    finally:
        data.forget([root.node])
    built: dict[str, np.ndarray] = {}
    seen: dict[str, int] = {}
    for c, o in zip(cands, outcomes, strict=True):
        label = str(c["labels"][0])
        seen[label] = seen.get(label, 0) + 1
        if seen[label] > 1:  # two candidates print alike: keep both, apart
            label = f"{label} #{seen[label]}"
        built.update(_block(c, o, n, label))
    names = list(built) if columns is None else [str(c) for c in columns]
    cols = [built[name] if name in built else _missing(name, n) for name in names]
    X = np.column_stack(cols) if cols else np.zeros((n, 0))
    y = root.y.astype(np.int64) if kind == "discrete" else root.y.astype(float)
    return FeatureTable(X=X.astype(float), y=y, weight=root.weight.astype(float), names=names,
                        kind=kind, n_classes=len(domain) if kind == "discrete" else None,
                        domain=domain, predicate=predicate)


# -- the baselines -----------------------------------------------------------------------------


def _gaussian_log_pdf(y: np.ndarray, mean: np.ndarray | float, var: float) -> np.ndarray:
    return -0.5 * (math.log(2 * math.pi * var) + (y - mean) ** 2 / var)


def _poisson_log_pmf(y: np.ndarray, rate: np.ndarray | float) -> np.ndarray:
    rate = np.maximum(np.asarray(rate, dtype=float), 1e-300)
    return np.maximum(y * np.log(rate) - rate - gammaln(y + 1.0), LOG_FLOOR)


def _full_proba(proba: np.ndarray, classes: np.ndarray, k: int) -> np.ndarray:
    """``predict_proba``'s columns (the classes seen in training) spread over all K classes."""
    out = np.zeros((proba.shape[0], k))
    out[:, classes.astype(np.int64)] = proba
    return out


class Baseline:
    """A fitted propositional model of one target (see :func:`fit_baselines`).

    Attributes
    ----------
    name : str
        ``"constant"``, ``"linear"`` or ``"boosting"``.
    label : str
        What the model is, for tables (``"logistic regression"``, ...).
    kind : str
        The target's kind.
    n_classes : int or None
        K for a discrete target.
    domain : list of str
        The discrete target's values, in class-index order.
    names : list of str
        The training table's columns (a test table must have the same).
    variance : float or None
        The Gaussian variance of a continuous target's model (the residual variance).
    """

    name: str = ""

    def __init__(self, train: FeatureTable) -> None:
        self.kind = train.kind
        self.n_classes = train.n_classes
        self.domain = list(train.domain)
        self.names = list(train.names)
        self.variance: float | None = None
        self.label = self.name

    # subclasses: the model's prediction on features X
    def _proba(self, X: np.ndarray) -> np.ndarray:  # (n, K), discrete
        raise NotImplementedError

    def _mean(self, X: np.ndarray) -> np.ndarray:  # (n,), continuous and count
        raise NotImplementedError

    def log_likelihood(self, X: np.ndarray, y: np.ndarray) -> np.ndarray:
        """Per row: the log-probability (discrete, count) or log-density (continuous) of ``y``.

        For a discrete target ``y`` is the class index (``-1`` for a value outside the training
        domain: probability 0). Probabilities are clipped below at 1e-12 (``LOG_FLOOR``) only to
        avoid ``-inf``; :func:`probanchor.ddclearn.evaluate` scores the learned program exactly.
        """
        if self.kind == "discrete":
            p = self._proba(X)
            y = np.asarray(y, dtype=np.int64)
            ok = (y >= 0) & (y < p.shape[1])
            picked = np.zeros(len(y))
            picked[ok] = p[np.flatnonzero(ok), y[ok]]
            return np.log(np.maximum(picked, math.exp(LOG_FLOOR)))
        mean = self._mean(X)
        if self.kind == "count":
            return _poisson_log_pmf(np.asarray(y, dtype=float), mean)
        assert self.variance is not None
        return _gaussian_log_pdf(np.asarray(y, dtype=float), mean, self.variance)

    def predict(self, X: np.ndarray) -> np.ndarray:
        """The point prediction per row: the most probable class index, or the mean."""
        if self.kind == "discrete":
            return np.argmax(self._proba(X), axis=1)
        return self._mean(X)

    def _residual_variance(self, train: FeatureTable) -> float:
        r = train.y - self._mean(train.X)
        return max(float(train.weight @ r**2 / train.weight.sum()), VARIANCE_FLOOR)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.kind!r}, {len(self.names)} columns)"


class ConstantBaseline(Baseline):
    """The model that knows nothing of the features.

    Discrete: class frequencies with add-one smoothing, ``p_k = (W_k + 1) / (W + K)``.
    Continuous: a Gaussian with the weighted mean and (maximum-likelihood) variance.
    Count: a Poisson with the weighted mean as its rate.
    """

    name = "constant"

    def __init__(self, train: FeatureTable) -> None:
        super().__init__(train)
        self.label = "constant"
        w, W = train.weight, float(train.weight.sum())
        if self.kind == "discrete":
            k = int(self.n_classes or 0)
            counts = np.bincount(train.y, weights=w, minlength=k)[:k]
            self.probs = (counts + 1.0) / (W + k)
        else:
            self.mean = float(w @ train.y / W)
            if self.kind == "continuous":
                self.variance = max(float(w @ (train.y - self.mean) ** 2 / W), VARIANCE_FLOOR)

    def _proba(self, X: np.ndarray) -> np.ndarray:
        return np.broadcast_to(self.probs, (X.shape[0], len(self.probs)))

    def _mean(self, X: np.ndarray) -> np.ndarray:
        return np.full(X.shape[0], self.mean)


class LinearBaseline(Baseline):
    """A generalised linear model on standardised features.

    NaN is imputed with the training column's weighted mean (0 for a column without any value),
    then each column is standardised by its weighted mean and standard deviation (1 for a
    constant column). Discrete: scikit-learn's ``LogisticRegression`` (lbfgs, its default L2
    penalty ``C=1``; multinomial for K > 2). Continuous: ``LinearRegression`` and a Gaussian whose
    variance is the weighted mean squared training residual. Count: ``PoissonRegressor``
    (``alpha=0.01``). A discrete target with a single class in training falls back to the
    constant model.
    """

    name = "linear"

    def __init__(self, train: FeatureTable) -> None:
        super().__init__(train)
        w = train.weight
        W = float(w.sum())
        X = train.X
        have = ~np.isnan(X)
        w_have = w @ have
        sums = w @ np.where(have, X, 0.0)
        self.fill = np.divide(sums, w_have, out=np.zeros(X.shape[1]), where=w_have > 0)
        Z = np.where(have, X, self.fill)
        self.center = w @ Z / W
        sd = np.sqrt(w @ (Z - self.center) ** 2 / W)
        self.scale = np.where(sd > 1e-12 * (1.0 + np.abs(self.center)), sd, 1.0)
        Z = self._design(X)
        self.fallback: ConstantBaseline | None = None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ConvergenceWarning)
            if self.kind == "discrete":
                self.label = "logistic regression"
                if len(np.unique(train.y[w > 0])) < 2:
                    self.fallback = ConstantBaseline(train)
                else:
                    self.model: Any = LogisticRegression(max_iter=_MAX_ITER)
                    self.model.fit(Z, train.y, sample_weight=w)
            elif self.kind == "count":
                self.label = "Poisson regression"
                self.model = PoissonRegressor(alpha=_POISSON_ALPHA, max_iter=_MAX_ITER)
                self.model.fit(Z, train.y, sample_weight=w)
            else:
                self.label = "linear regression"
                self.model = LinearRegression()
                self.model.fit(Z, train.y, sample_weight=w)
                self.variance = self._residual_variance(train)

    def _design(self, X: np.ndarray) -> np.ndarray:
        if X.shape[1] == 0:  # no features: one constant column (the model is the intercept)
            return np.zeros((X.shape[0], 1))
        return (np.where(np.isnan(X), self.fill, X) - self.center) / self.scale

    def _proba(self, X: np.ndarray) -> np.ndarray:
        if self.fallback is not None:
            return self.fallback._proba(X)  # noqa: SLF001 (a Baseline hook, of its fallback)
        p = self.model.predict_proba(self._design(X))
        return _full_proba(p, self.model.classes_, int(self.n_classes or 0))

    def _mean(self, X: np.ndarray) -> np.ndarray:
        return np.asarray(self.model.predict(self._design(X)), dtype=float)


class BoostingBaseline(Baseline):
    """Histogram gradient boosting on the raw features (it handles NaN itself).

    Discrete: scikit-learn's ``HistGradientBoostingClassifier``. Continuous:
    ``HistGradientBoostingRegressor`` and a Gaussian whose variance is the weighted mean squared
    training residual (optimistic: the trees fit the training rows closely). Count: the
    regressor with the Poisson loss. Default settings, ``random_state=0``, ``THREADS`` OpenMP
    threads. A discrete target with a single class in training falls back to the constant
    model.
    """

    name = "boosting"

    def __init__(self, train: FeatureTable) -> None:
        super().__init__(train)
        w = train.weight
        self.fallback: ConstantBaseline | None = None
        if self.kind == "discrete":
            self.label = "gradient boosting"
            if len(np.unique(train.y[w > 0])) < 2:
                self.fallback = ConstantBaseline(train)
                return
            self.model: Any = HistGradientBoostingClassifier(random_state=0)
        elif self.kind == "count":
            self.label = "gradient boosting (Poisson)"
            self.model = HistGradientBoostingRegressor(loss="poisson", random_state=0)
        else:
            self.label = "gradient boosting"
            self.model = HistGradientBoostingRegressor(random_state=0)
        with threadpool_limits(limits=THREADS, user_api="openmp"):
            self.model.fit(self._input(train.X), train.y, sample_weight=w)
        if self.kind == "continuous":
            self.variance = self._residual_variance(train)

    def _input(self, X: np.ndarray) -> np.ndarray:
        return X if X.shape[1] else np.zeros((X.shape[0], 1))

    def _proba(self, X: np.ndarray) -> np.ndarray:
        if self.fallback is not None:
            return self.fallback._proba(X)  # noqa: SLF001 (a Baseline hook, of its fallback)
        with threadpool_limits(limits=THREADS, user_api="openmp"):
            p = self.model.predict_proba(self._input(X))
        return _full_proba(p, self.model.classes_, int(self.n_classes or 0))

    def _mean(self, X: np.ndarray) -> np.ndarray:
        with threadpool_limits(limits=THREADS, user_api="openmp"):
            return np.asarray(self.model.predict(self._input(X)), dtype=float)


def fit_baselines(train: FeatureTable) -> list[Baseline]:
    """Fit the constant, linear (logistic) and gradient-boosting baselines on a table.

    Parameters
    ----------
    train : FeatureTable
        The training table (:func:`feature_table`); rows are weighted by ``train.weight``.

    Returns
    -------
    list of Baseline
        ``[ConstantBaseline, LinearBaseline, BoostingBaseline]`` (names in ``BASELINES``).
    """
    if train.n == 0 or float(train.weight.sum()) <= 0:
        raise ValueError(f"no training rows for {train.predicate or 'the target'}")
    return [ConstantBaseline(train), LinearBaseline(train), BoostingBaseline(train)]


def _class_map(train: list[str], test: list[str]) -> np.ndarray:
    index = {v: i for i, v in enumerate(train)}
    return np.array([index.get(v, -1) for v in test], dtype=np.int64)


def score(baseline: Baseline, test: FeatureTable) -> dict[str, Any]:
    """Held-out figures of a fitted baseline, as :func:`probanchor.ddclearn.evaluate` gives them.

    Parameters
    ----------
    baseline : Baseline
        A model from :func:`fit_baselines`.
    test : FeatureTable
        The test table, built with ``columns=`` the training table's ``names``.

    Returns
    -------
    dict
        ``n`` (rows), ``weight``, ``log_likelihood`` (weighted sum, natural log),
        ``mean_log_likelihood`` (per unit of weight, i.e. per grounding), ``log_likelihood_sd``
        (the weighted standard deviation of the per-grounding log-likelihood), and ``accuracy``
        (discrete: the most probable class) or ``rmse`` (the mean). Log-probabilities are
        clipped below at ``log(1e-12)`` only to avoid ``-inf`` (see ``LOG_FLOOR``).
    """
    if test.kind != baseline.kind:
        raise ValueError(f"a {baseline.kind} baseline scored on a {test.kind} table")
    if list(test.names) != baseline.names:
        raise ValueError("the test table's columns differ from the training table's: build it "
                         "with feature_table(..., columns=train.names)")
    y = test.y
    if baseline.kind == "discrete" and test.domain and test.domain != baseline.domain:
        y = _class_map(baseline.domain, test.domain)[test.y]
    w = test.weight
    W = float(w.sum())
    per_row = baseline.log_likelihood(test.X, y)
    ll = float(w @ per_row) if test.n else 0.0
    mean = ll / W if W > 0 else math.nan
    out: dict[str, Any] = {
        "n": test.n,
        "weight": W,
        "log_likelihood": ll,
        "mean_log_likelihood": mean,
        "log_likelihood_sd": math.sqrt(float(w @ (per_row - mean) ** 2 / W)) if W > 0
        else math.nan,
    }
    if test.n == 0 or W <= 0:
        out["accuracy" if baseline.kind == "discrete" else "rmse"] = math.nan
        return out
    pred = baseline.predict(test.X)
    if baseline.kind == "discrete":
        out["accuracy"] = float(w @ (pred == y) / W)
    else:
        out["rmse"] = math.sqrt(float(w @ (pred - y) ** 2 / W))
    return out
