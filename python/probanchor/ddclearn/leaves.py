"""The statistical models at the leaves of a distributional logic tree.

A leaf of the tree holds the distribution of the head given the rows (groundings) that reach it
(Kumar, Kuželka and De Raedt, DreaML / DiceML). Each kind of head has a model without regressors
and one that uses the leaf's numeric regressors:

======================  =======================  ==========================================
kind                    without regressors       with regressors ``x`` (m of them)
======================  =======================  ==========================================
``"discrete"`` (K)      ``finite``               ``logistic`` (K = 2), ``softmax`` (K > 2)
``"continuous"``        ``gaussian``             ``linear_gaussian``
``"count"``             ``poisson``              ``poisson_log_linear``
======================  =======================  ==========================================

:func:`fit_leaf` fits both (the second only when there are regressors) on weighted rows and keeps
the one with the larger BIC score ``2 * log_likelihood - n_params * log_n``.

The weights of the regressions are stored bias last (``[w1, ..., wm, b]``), as the DC built-ins
``logistic/3`` and ``softmax/3`` of ``prolog/ddc/lang/ddc_models.pl`` take them. ``logistic`` gives
the probability of the FIRST class (index 0) of the domain, ``P(0 | x) = sigmoid(w.x + b)``, the
``P1`` of ``finite([P1:V1, P2:V2]) := ..., logistic(X, W, P1), P2 is 1 - P1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import gammaln, log_expit, logsumexp, xlogy

if TYPE_CHECKING:  # scikit-learn takes seconds to import: only the fits that need it load it
    from sklearn.linear_model import LogisticRegression, PoissonRegressor

__all__ = ["FAMILIES", "Kind", "Leaf", "LeafOptions", "fit_leaf", "fit_offset_leaf"]

Kind = Literal["discrete", "continuous", "count"]

#: The leaf families, and whether each uses regressors.
FAMILIES: dict[str, bool] = {
    "finite": False,
    "gaussian": False,
    "poisson": False,
    "linear_gaussian": True,
    "logistic": True,
    "softmax": True,
    "poisson_log_linear": True,
}

_KINDS: tuple[str, ...] = ("discrete", "continuous", "count")

#: Rate of a Poisson leaf whose rows all count 0 (the MLE 0 is not a valid Poisson parameter).
_MIN_RATE = 1e-9

#: Iterations and gradient tolerance of sklearn's lbfgs fits.
_MAX_ITER = 1000
_TOL = 1e-8


@dataclass(frozen=True)
class LeafOptions:
    """Settings of the leaf fits.

    Parameters
    ----------
    smoothing : float, default=1.0
        Additive (Laplace) pseudo-count per value of a discrete head, ``>= 0``. For ``finite``
        it is added to every class count; for ``logistic`` / ``softmax`` it is the weight of one
        pseudo-row per class at the (weighted) mean of the regressors.
    l2 : float, default=0.01
        L2 penalty ``l2 / 2 * ||beta||^2`` on the standardised coefficients of ``logistic``,
        ``softmax`` and ``poisson_log_linear`` (the intercept is not penalised), ``>= 0``.
    variance_floor : float, default=1e-12
        Smallest variance of a ``gaussian`` or ``linear_gaussian`` leaf, ``> 0``.
    """

    smoothing: float = 1.0
    l2: float = 0.01
    variance_floor: float = 1e-12

    def __post_init__(self) -> None:
        for name in ("smoothing", "l2", "variance_floor"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ValueError(f"LeafOptions.{name} must be a number, got {value!r}")
            if not math.isfinite(value):
                raise ValueError(f"LeafOptions.{name} must be finite, got {value!r}")
        if self.smoothing < 0:
            raise ValueError(f"LeafOptions.smoothing must be >= 0, got {self.smoothing!r}")
        if self.l2 < 0:
            raise ValueError(f"LeafOptions.l2 must be >= 0, got {self.l2!r}")
        if self.variance_floor <= 0:
            raise ValueError(f"LeafOptions.variance_floor must be > 0, got {self.variance_floor!r}")


@dataclass(frozen=True)
class Leaf:
    """A fitted leaf model.

    Parameters
    ----------
    family : str
        One of ``finite``, ``gaussian``, ``linear_gaussian``, ``logistic``, ``softmax``,
        ``poisson``, ``poisson_log_linear``.
    n_classes : int or None
        Size K of the domain of a discrete head; None otherwise.
    probs : tuple of float, optional
        ``finite``: one probability per class, summing to 1.
    mean : float, optional
        ``gaussian``: the mean.
    variance : float, optional
        ``gaussian``, ``linear_gaussian``: the variance.
    weights : tuple of float, optional
        ``linear_gaussian``, ``logistic``, ``poisson_log_linear``: ``[w1, ..., wm, b]``.
    weight_rows : tuple of tuple of float, optional
        ``softmax``: K rows ``[w1, ..., wm, b]``, row 0 all zeros.
    rate : float, optional
        ``poisson``: the rate.
    log_likelihood : float
        Weighted training log-likelihood ``sum_i w_i log f(y_i | x_i)`` (natural log).
    n_params : int
        Number of free parameters (for the BIC).
    weight : float
        Sum of the weights of the training rows.
    rows : int
        Number of training rows with positive weight.
    uses_regressors : bool
        True for the families with ``weights`` / ``weight_rows``.
    """

    family: str
    n_classes: int | None
    probs: tuple[float, ...] | None = None
    mean: float | None = None
    variance: float | None = None
    weights: tuple[float, ...] | None = None
    weight_rows: tuple[tuple[float, ...], ...] | None = None
    rate: float | None = None
    log_likelihood: float = 0.0
    n_params: int = 0
    weight: float = 0.0
    rows: int = 0
    uses_regressors: bool = False

    def __post_init__(self) -> None:
        if self.family not in FAMILIES:
            raise ValueError(f"unknown leaf family {self.family!r}; one of {sorted(FAMILIES)}")
        if FAMILIES[self.family] != self.uses_regressors:
            raise ValueError(
                f"family {self.family!r} has uses_regressors={FAMILIES[self.family]}, "
                f"got {self.uses_regressors}"
            )
        required = {
            "finite": ("probs",),
            "gaussian": ("mean", "variance"),
            "linear_gaussian": ("weights", "variance"),
            "logistic": ("weights",),
            "softmax": ("weight_rows",),
            "poisson": ("rate",),
            "poisson_log_linear": ("weights",),
        }[self.family]
        missing = [name for name in required if getattr(self, name) is None]
        if missing:
            raise ValueError(f"a {self.family!r} leaf needs {', '.join(missing)}")
        if self.family in ("finite", "logistic", "softmax") and not self.n_classes:
            raise ValueError(f"a {self.family!r} leaf needs n_classes")

    # ------------------------------------------------------------------ scoring

    def bic(self, log_n: float) -> float:
        """BIC score, larger is better.

        Parameters
        ----------
        log_n : float
            Log of the sample size used for the penalty.

        Returns
        -------
        float
            ``2 * log_likelihood - n_params * log_n``.
        """
        return 2.0 * self.log_likelihood - self.n_params * log_n

    def log_prob(self, y: ArrayLike, X: ArrayLike | None) -> np.ndarray:
        """Per-row log density / log probability of the head.

        Parameters
        ----------
        y : array-like of shape (n,)
            Values of the head: class indices ``0..K-1`` (discrete), reals (continuous) or
            non-negative integers (count).
        X : array-like of shape (n, m) or None
            Regressors; ignored (and may be None) when ``uses_regressors`` is False.

        Returns
        -------
        ndarray of shape (n,)
            ``log f(y_i | x_i)``, natural log.
        """
        kind = self.kind
        y_arr = _as_vector(y, "y")
        _check_finite(y_arr, "y")
        if kind == "discrete":
            k = _class_indices(y_arr, self._k)
            # log P(y_i | x_i): row i, column y_i of the log class probabilities.
            return self._log_class_probs(X, len(y_arr))[np.arange(len(y_arr)), k]
        if kind == "count":
            _check_counts(y_arr)
        if self.family == "gaussian":
            # log N(y; mu, var) = -0.5 log(2 pi var) - (y - mu)^2 / (2 var)
            return _gaussian_log_pdf(y_arr, self.mean, self.variance)  # type: ignore[arg-type]
        if self.family == "linear_gaussian":
            mean = self._linear_predictor(X, len(y_arr))
            return _gaussian_log_pdf(y_arr, mean, self.variance)  # type: ignore[arg-type]
        if self.family == "poisson":
            # log Poisson(y; r) = y log r - r - lgamma(y + 1)
            r = float(self.rate)  # type: ignore[arg-type]
            return xlogy(y_arr, r) - r - gammaln(y_arr + 1.0)
        # poisson_log_linear: log r = eta = w.x + b, so log f = y eta - exp(eta) - lgamma(y + 1)
        eta = self._linear_predictor(X, len(y_arr))
        return y_arr * eta - np.exp(eta) - gammaln(y_arr + 1.0)

    def predict(self, X: ArrayLike | None, n: int | None = None) -> np.ndarray:
        """Class probabilities (discrete) or mean (continuous, count) per row.

        Parameters
        ----------
        X : array-like of shape (n, m) or None
            Regressors. May be None when ``uses_regressors`` is False, then ``n`` gives the
            number of rows.
        n : int, optional
            Number of rows when ``X`` is None.

        Returns
        -------
        ndarray of shape (n, K) or (n,)
            Discrete: ``P(k | x_i)``; continuous: ``E[y | x_i]``; count: the rate.
        """
        rows = self._rows(X, n)
        if self.kind == "discrete":
            return np.exp(self._log_class_probs(X, rows))
        if self.family == "gaussian":
            return np.full(rows, float(self.mean))  # type: ignore[arg-type]
        if self.family == "poisson":
            return np.full(rows, float(self.rate))  # type: ignore[arg-type]
        eta = self._linear_predictor(X, rows)
        # linear_gaussian: E[y|x] = w.x + b;  poisson_log_linear: E[y|x] = exp(w.x + b)
        return eta if self.family == "linear_gaussian" else np.exp(eta)

    # ------------------------------------------------------------------ helpers

    @property
    def kind(self) -> Kind:
        """The kind of head the family models."""
        if self.family in ("finite", "logistic", "softmax"):
            return "discrete"
        if self.family in ("gaussian", "linear_gaussian"):
            return "continuous"
        return "count"

    @property
    def _k(self) -> int:
        assert self.n_classes is not None
        return int(self.n_classes)

    def _n_regressors(self) -> int:
        if self.weight_rows is not None:
            return len(self.weight_rows[0]) - 1
        return len(self.weights) - 1 if self.weights is not None else 0

    def _rows(self, X: ArrayLike | None, n: int | None) -> int:
        if X is not None:
            rows = _as_matrix(X, None).shape[0]
            if n is not None and n != rows:
                raise ValueError(f"n={n} but X has {rows} rows")
            return rows
        if self.uses_regressors:
            raise ValueError(f"a {self.family!r} leaf needs the regressors X")
        if n is None or n < 0:
            raise ValueError("give X or the number of rows n >= 0")
        return int(n)

    def _design(self, X: ArrayLike | None, rows: int) -> np.ndarray:
        if X is None:
            raise ValueError(f"a {self.family!r} leaf needs the regressors X")
        m = self._n_regressors()
        X_arr = _as_matrix(X, rows)
        if X_arr.shape[1] != m:
            raise ValueError(f"X has {X_arr.shape[1]} columns, the leaf has {m} regressors")
        _check_finite(X_arr, "X")
        return X_arr

    def _linear_predictor(self, X: ArrayLike | None, rows: int) -> np.ndarray:
        # eta_i = w . x_i + b  (weights stored as [w1..wm, b])
        X_arr = self._design(X, rows)
        coef = np.asarray(self.weights, dtype=float)
        return X_arr @ coef[:-1] + coef[-1]

    def _log_class_probs(self, X: ArrayLike | None, rows: int) -> np.ndarray:
        """(rows, K) log class probabilities."""
        if self.family == "finite":
            with np.errstate(divide="ignore"):
                log_p = np.log(np.asarray(self.probs, dtype=float))
            return np.broadcast_to(log_p, (rows, self._k))
        if self.family == "logistic":
            eta = self._linear_predictor(X, rows)
            # P(0|x) = sigmoid(eta), P(1|x) = 1 - sigmoid(eta) = sigmoid(-eta), in log space
            return np.column_stack([log_expit(eta), log_expit(-eta)])
        # softmax: log P(k|x) = eta_k - logsumexp_j eta_j, eta_k = w_k . x + b_k
        X_arr = self._design(X, rows)
        W = np.asarray(self.weight_rows, dtype=float)
        eta = X_arr @ W[:, :-1].T + W[:, -1]
        return eta - logsumexp(eta, axis=1, keepdims=True)


# ---------------------------------------------------------------------- fitting


def fit_leaf(
    kind: Kind,
    y: ArrayLike,
    w: ArrayLike,
    X: ArrayLike | None,
    *,
    log_n: float,
    n_classes: int | None = None,
    options: LeafOptions = LeafOptions(),  # noqa: B008 - frozen, hence safe as a default
    offsets: int = 0,
) -> Leaf:
    """Fit the leaf model of one node and choose among its models by BIC.

    Parameters
    ----------
    kind : {"discrete", "continuous", "count"}
        Kind of the head.
    y : array-like of shape (n,)
        Head values: class indices ``0..K-1`` (discrete), reals (continuous), non-negative
        integers (count).
    w : array-like of shape (n,)
        Non-negative row weights; rows of weight 0 are dropped before anything else (their
        ``y`` and ``X`` are not checked, so they may hold NaN).
    X : array-like of shape (n, m) or None
        Regressors; ``m`` may be 0. None means no regressors.
    log_n : float
        Log of the sample size in the BIC penalty.
    n_classes : int, optional
        Size K of the domain; required for a discrete head, must be None otherwise.
    options : LeafOptions
        Smoothing, penalty and variance floor.
    offsets : int, default=0
        The first ``offsets`` columns of ``X`` are a root model's scores, which a model takes
        as an offset (:func:`fit_offset_leaf`), never as regressors.

    Returns
    -------
    Leaf
        Of the model without regressors, the model with the regressors (the columns after the
        offsets, when there are some; its weights on the offsets are 0) and, with
        ``offsets``, the model on the offsets and the regressors (:func:`fit_offset_leaf`), the
        one with the largest ``bic(log_n)``, the first of them on a tie.

    Raises
    ------
    ValueError
        On mismatched lengths, negative or non-finite weights, total weight 0, non-finite ``y``
        or ``X``, bad class indices or counts, or a missing / superfluous ``n_classes``, or a
        number of offsets that does not fit the head.
    """
    y_arr, w_arr, X_arr, K = _validate(kind, y, w, X, n_classes, log_n)
    best = _fit_without_regressors(kind, y_arr, w_arr, K, options)
    if offsets:
        _check_offsets(kind, K, offsets, X_arr.shape[1])
        with_offset = _fit_offset(kind, y_arr, w_arr, X_arr, offsets, K, options)
        if with_offset is not None and with_offset.bic(log_n) > best.bic(log_n):
            best = with_offset
    if X_arr.shape[1] > offsets:
        regression = _fit_with_regressors(kind, y_arr, w_arr, X_arr[:, offsets:], K, options)
        if regression is not None and regression.bic(log_n) > best.bic(log_n):
            best = _padded(regression, offsets)
    return best


def _check_offsets(kind: str, K: int | None, offsets: int, m: int) -> None:
    want = max(int(K or 0) - 1, 1) if kind == "discrete" else 1
    if offsets != want or m < offsets:
        raise ValueError(f"a {kind} head with {K} classes has {want} offsets in X, got "
                         f"{offsets} (of {m} columns)")


def _padded(leaf: Leaf, q: int) -> Leaf:
    """A regression leaf with ``q`` leading columns of weight 0 (the scores it does not read)."""
    if q == 0:
        return leaf
    if leaf.weight_rows is not None:
        return replace(leaf, weight_rows=tuple((0.0,) * q + tuple(r) for r in leaf.weight_rows))
    assert leaf.weights is not None
    return replace(leaf, weights=(0.0,) * q + tuple(leaf.weights))


def fit_offset_leaf(
    kind: Kind,
    y: ArrayLike,
    w: ArrayLike,
    X: ArrayLike,
    *,
    offsets: int,
    n_classes: int | None = None,
    options: LeafOptions = LeafOptions(),  # noqa: B008 - frozen, hence safe as a default
) -> Leaf | None:
    """Fit a leaf whose linear predictors are a root model's scores plus a regression.

    The first ``offsets`` columns of ``X`` are a root model's scores
    (:mod:`probanchor.ddclearn.root_model`): a Boolean, continuous or count target's one linear
    predictor (the logit of its second class, its mean, its log rate), a K-class target's K - 1
    logits of classes 1..K-1 against class 0. They enter the model as an *offset*, with
    coefficient 1 (-1 in a ``logistic`` leaf, which gives the first class's probability), not
    fitted; the other columns are regressors as in :func:`fit_leaf`'s regression, and the
    intercepts are fitted (continuous: weighted least squares of ``y - score``; discrete and
    count: the penalised likelihood of :func:`fit_leaf`'s regressions, by L-BFGS).

    Parameters are those of :func:`fit_leaf` (no ``log_n``), and ``offsets``: 1 for a Boolean,
    continuous or count head, K - 1 for K > 2 classes.

    Returns
    -------
    Leaf or None
        A regression leaf with one weight per column of ``X`` (the family of :func:`fit_leaf`'s
        regressions), or None for a discrete head with fewer than 2 classes in the rows.
    """
    y_arr, w_arr, X_arr, K = _validate(kind, y, w, X, n_classes, 0.0)
    _check_offsets(kind, K, offsets, X_arr.shape[1])
    return _fit_offset(kind, y_arr, w_arr, X_arr, offsets, K, options)


def _fit_offset(
    kind: str,
    y: np.ndarray,
    w: np.ndarray,
    X: np.ndarray,
    q: int,
    K: int | None,
    options: LeafOptions,
) -> Leaf | None:
    """The model whose linear predictors are the ``q`` scores plus a regression on the rest.

    Continuous: weighted least squares of ``y - score`` on the other columns. Discrete and
    count: the penalised negative log-likelihood (``l2 / 2 ||beta||^2`` on the standardised
    coefficients, the intercepts free; discrete: one pseudo-row per class at the columns' mean
    and offset 0, of weight ``smoothing``) minimised by L-BFGS. None when a discrete head has
    fewer than 2 classes.
    """
    S, P = X[:, :q], X[:, q:]
    std = _Standardiser.fit(P, w)
    m = P.shape[1]
    common = {"weight": float(w.sum()), "rows": int(len(y)), "uses_regressors": True}
    if kind == "continuous":
        r = y - S[:, 0]
        if std.keep.any():
            path, var = _fit_wls(r, w, P, std, options.variance_floor)
        else:
            b = float(w @ r / w.sum())
            var = max(float(w @ (r - b) ** 2 / w.sum()), options.variance_floor)
            path = (0.0,) * m + (b,)
        weights = (1.0, *path)
        leaf = Leaf("linear_gaussian", None, weights=weights, variance=var,
                    n_params=int(std.keep.sum()) + 2, **common)
        return _with_log_likelihood(leaf, y, w, X)
    Z = std.transform(P)
    k_kept = Z.shape[1]
    if kind == "discrete":
        assert K is not None
        if (np.bincount(y.astype(np.intp), weights=w, minlength=K) > 0).sum() < 2:
            return None
        off = np.zeros((len(y), K))
        off[:, 1:] = S if K > 2 else S[:, :1]
        coef, icpt = _offset_softmax(y.astype(np.intp), w, Z, off, K, options)
        full, b = std.back(coef, icpt)          # (K-1, m), (K-1,)
        if K == 2:
            # P(class 0) = sigmoid(-(score + c.x + d))
            weights = (-1.0, *(-full[0]).tolist(), float(-b[0]))
            leaf = Leaf("logistic", K, weights=weights, n_params=k_kept + 1, **common)
        else:
            rows = [(0.0,) * (q + m + 1)]
            for k in range(1, K):
                unit = [0.0] * q
                unit[k - 1] = 1.0
                rows.append((*unit, *full[k - 1].tolist(), float(b[k - 1])))
            leaf = Leaf("softmax", K, weight_rows=tuple(rows),
                        n_params=(K - 1) * (k_kept + 1), **common)
        return _with_log_likelihood(leaf, y, w, X)
    coef, icpt = _offset_poisson(y, w, Z, S[:, 0], options)
    full, b = std.back(coef, icpt)
    weights = (1.0, *full[0].tolist(), float(b[0]))
    leaf = Leaf("poisson_log_linear", None, weights=weights, n_params=k_kept + 1, **common)
    return _with_log_likelihood(leaf, y, w, X)


def _offset_softmax(y: np.ndarray, w: np.ndarray, Z: np.ndarray, off: np.ndarray, K: int,
                    options: LeafOptions) -> tuple[np.ndarray, np.ndarray]:
    """Rows 1..K-1 of a softmax ``eta = off + [0 | Z C^T + d]``: C (K-1, m) and d (K-1,).

    Minimises ``-sum_i w_i log softmax(eta_i)[y_i] + l2 / 2 ||C||^2`` over the rows and one
    pseudo-row per class (z = 0, offset 0, weight ``smoothing``).
    """
    from scipy.optimize import minimize

    a = options.smoothing
    if a > 0:
        Z = np.vstack([Z, np.zeros((K, Z.shape[1]))])
        off = np.vstack([off, np.zeros((K, K))])
        y = np.concatenate([y, np.arange(K)])
        w = np.concatenate([w, np.full(K, a)])
    n, m = Z.shape
    A = np.column_stack([Z, np.ones(n)])
    Y = np.zeros((n, K))
    Y[np.arange(n), y] = 1.0
    pen = np.ones(m + 1) * options.l2
    pen[-1] = 0.0

    def f(theta: np.ndarray) -> tuple[float, np.ndarray]:
        B = theta.reshape(K - 1, m + 1)
        eta = off.copy()
        eta[:, 1:] += A @ B.T
        lp = eta - logsumexp(eta, axis=1, keepdims=True)
        loss = -float(w @ lp[np.arange(n), y]) + 0.5 * float((pen * B**2).sum())
        G = (w[:, None] * (np.exp(lp) - Y))[:, 1:].T @ A + pen * B
        return loss, G.ravel()

    res = minimize(f, np.zeros((K - 1) * (m + 1)), jac=True, method="L-BFGS-B",
                   options={"maxiter": _MAX_ITER, "gtol": 1e-8})
    B = res.x.reshape(K - 1, m + 1)
    return B[:, :m], B[:, m]


def _offset_poisson(y: np.ndarray, w: np.ndarray, Z: np.ndarray, o: np.ndarray,
                    options: LeafOptions) -> tuple[np.ndarray, np.ndarray]:
    """``log r = o + c.z + d``: minimises ``sum_i w_i (r_i - y_i log r_i) + l2 / 2 ||c||^2``."""
    from scipy.optimize import minimize

    n, m = Z.shape
    A = np.column_stack([Z, np.ones(n)])
    pen = np.ones(m + 1) * options.l2
    pen[-1] = 0.0

    def f(theta: np.ndarray) -> tuple[float, np.ndarray]:
        eta = o + A @ theta
        r = np.exp(np.minimum(eta, 700.0))
        loss = float(w @ (r - y * eta)) + 0.5 * float(pen @ theta**2)
        return loss, A.T @ (w * (r - y)) + pen * theta

    res = minimize(f, np.zeros(m + 1), jac=True, method="L-BFGS-B",
                   options={"maxiter": _MAX_ITER, "gtol": 1e-8})
    return res.x[None, :m], res.x[m:]


def _fit_without_regressors(
    kind: str, y: np.ndarray, w: np.ndarray, K: int | None, options: LeafOptions
) -> Leaf:
    """``finite`` / ``gaussian`` / ``poisson`` on validated rows of positive weight."""
    W = float(w.sum())
    common = {"weight": W, "rows": int(len(y))}
    if kind == "discrete":
        assert K is not None
        a = options.smoothing
        # p_k = (sum_{i: y_i = k} w_i + a) / (sum_i w_i + a K)
        counts = np.bincount(y.astype(np.intp), weights=w, minlength=K)
        probs = (counts + a) / (W + a * K)
        leaf = Leaf("finite", K, probs=tuple(probs.tolist()), n_params=K - 1, **common)
    elif kind == "continuous":
        # mu = sum(w y) / W ;  var = max(sum(w (y - mu)^2) / W, floor)  (MLE, no n-1)
        mu = float(w @ y / W)
        var = max(float(w @ (y - mu) ** 2 / W), options.variance_floor)
        leaf = Leaf("gaussian", None, mean=mu, variance=var, n_params=2, **common)
    else:
        # r = sum(w y) / W, kept strictly positive so log f(0) = -r stays finite
        rate = max(float(w @ y / W), _MIN_RATE)
        leaf = Leaf("poisson", None, rate=rate, n_params=1, **common)
    return _with_log_likelihood(leaf, y, w, None)


def _fit_with_regressors(
    kind: str,
    y: np.ndarray,
    w: np.ndarray,
    X: np.ndarray,
    K: int | None,
    options: LeafOptions,
) -> Leaf | None:
    """The regression leaf on validated rows of positive weight, or None if there is none.

    There is none when no regressor varies over the rows, when fewer than 2 classes have
    positive weight (discrete), when ``smoothing == 0`` and a class of a K > 2 domain has no
    rows (a softmax with finite weights cannot give it probability 0), or when every count is 0
    (the log-rate would go to minus infinity).
    """
    std = _Standardiser.fit(X, w)
    if not std.keep.any():
        return None
    m = X.shape[1]
    common = {"weight": float(w.sum()), "rows": int(len(y)), "uses_regressors": True}
    if kind == "discrete":
        assert K is not None
        present = np.bincount(y.astype(np.intp), weights=w, minlength=K) > 0
        if present.sum() < 2 or (K > 2 and options.smoothing == 0 and not present.all()):
            return None
        model = _fit_classifier(y, w, X, K, std, options)
        coef, intercept = std.back(model.coef_, model.intercept_)
        if K == 2:
            # sklearn's binary model: P(class 1 | z) = sigmoid(c.z + d), hence
            # P(class 0 | x) = sigmoid(-(c.z + d)), i.e. w = -c/s, b = -(d - sum c mu / s)
            weights = tuple(np.append(-coef[0], -intercept[0]).tolist())
            leaf = Leaf("logistic", K, weights=weights, n_params=m + 1, **common)
        else:
            # identifiable rows: subtract row 0, so that eta_0 = 0 (probabilities unchanged)
            rows = np.column_stack([coef, intercept])
            rows = rows - rows[0]
            weight_rows = tuple(tuple(r.tolist()) for r in rows)
            leaf = Leaf("softmax", K, weight_rows=weight_rows, n_params=(K - 1) * (m + 1), **common)
    elif kind == "continuous":
        weights, var = _fit_wls(y, w, X, std, options.variance_floor)
        leaf = Leaf(
            "linear_gaussian", None, weights=weights, variance=var, n_params=m + 2, **common
        )
    else:
        if not (y > 0).any():
            return None
        model = _fit_poisson(y, w, X, std, options)
        coef, intercept = std.back(model.coef_, model.intercept_)
        weights = tuple(np.append(coef, intercept).tolist())
        leaf = Leaf("poisson_log_linear", None, weights=weights, n_params=m + 1, **common)
    return _with_log_likelihood(leaf, y, w, X)


@dataclass(frozen=True)
class _Standardiser:
    """Weighted standardisation ``z_j = (x_j - mu_j) / s_j`` of the columns that vary.

    ``keep`` marks the columns with spread (``max - min > 0`` over the rows); the others are left
    out of the fit and get weight 0 in the result.
    """

    keep: np.ndarray  # (m,) bool
    mean: np.ndarray  # (m_kept,) weighted means mu_j
    scale: np.ndarray  # (m_kept,) weighted standard deviations s_j

    @classmethod
    def fit(cls, X: np.ndarray, w: np.ndarray) -> _Standardiser:
        keep = np.ptp(X, axis=0) > 0 if len(X) else np.zeros(X.shape[1], dtype=bool)
        Xk = X[:, keep]
        W = w.sum()
        # mu_j = sum_i w_i x_ij / W ;  s_j = sqrt(sum_i w_i (x_ij - mu_j)^2 / W)
        mean = w @ Xk / W
        scale = np.sqrt(w @ (Xk - mean) ** 2 / W)
        return cls(keep=keep, mean=mean, scale=scale)

    def transform(self, X: np.ndarray) -> np.ndarray:
        return (X[:, self.keep] - self.mean) / self.scale

    def back(
        self, coef_std: np.ndarray, intercept_std: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients in the original units, zero for the columns left out.

        ``c.z + d = sum_j c_j (x_j - mu_j) / s_j + d``, hence ``w_j = c_j / s_j`` and
        ``b = d - sum_j c_j mu_j / s_j``. Rows of ``coef_std`` are models (one per class).
        """
        c = np.atleast_2d(np.asarray(coef_std, dtype=float))
        d = np.atleast_1d(np.asarray(intercept_std, dtype=float))
        coef = np.zeros((c.shape[0], self.keep.size))
        coef[:, self.keep] = c / self.scale
        intercept = d - c @ (self.mean / self.scale)
        return coef, intercept


def _fit_classifier(
    y: np.ndarray,
    w: np.ndarray,
    X: np.ndarray,
    K: int,
    std: _Standardiser,
    options: LeafOptions,
) -> LogisticRegression:
    """sklearn logistic (K = 2) or multinomial (K > 2) regression on the standardised rows.

    Objective: ``C sum_i w_i loss_i + 0.5 ||beta||^2`` with ``C = 1 / l2``, i.e.
    ``sum_i w_i loss_i + l2 / 2 ||beta||^2``, over the real rows plus one pseudo-row per class
    at ``z = 0`` (the weighted mean) of weight ``smoothing``. The classes are the indices 0..K-1
    (``classes_`` is ``0..K-1`` whenever smoothing > 0).
    """
    Z = std.transform(X)
    labels = y.astype(np.intp)
    sample_weight = w
    if options.smoothing > 0:
        # pseudo-rows: (z = 0, label k, weight a) for k = 0..K-1
        Z = np.vstack([Z, np.zeros((K, Z.shape[1]))])
        labels = np.concatenate([labels, np.arange(K)])
        sample_weight = np.concatenate([w, np.full(K, options.smoothing)])
    C = 1.0 / options.l2 if options.l2 > 0 else np.inf
    # Two classes: sklearn fits the plain binary logistic (one coefficient row).
    from sklearn.linear_model import LogisticRegression

    model = LogisticRegression(C=C, solver="lbfgs", max_iter=_MAX_ITER, tol=_TOL)
    model.fit(Z, labels, sample_weight=sample_weight)
    return model


def _fit_poisson(
    y: np.ndarray, w: np.ndarray, X: np.ndarray, std: _Standardiser, options: LeafOptions
) -> PoissonRegressor:
    """sklearn Poisson regression ``log r = c.z + d`` on the standardised rows.

    sklearn minimises ``1 / (2 W) sum_i w_i dev_i + alpha / 2 ||c||^2`` where
    ``dev_i / 2 = -log f(y_i) + const``, i.e. ``(1/W) [sum_i w_i nll_i + alpha W / 2 ||c||^2]``;
    ``alpha = l2 / W`` gives ``sum_i w_i nll_i + l2 / 2 ||c||^2``.
    """
    alpha = options.l2 / float(w.sum())
    from sklearn.linear_model import PoissonRegressor

    model = PoissonRegressor(alpha=alpha, solver="lbfgs", max_iter=_MAX_ITER, tol=_TOL)
    model.fit(std.transform(X), y, sample_weight=w)
    return model


def _fit_wls(
    y: np.ndarray, w: np.ndarray, X: np.ndarray, std: _Standardiser, floor: float
) -> tuple[tuple[float, ...], float]:
    """Weighted least squares ``y = w.x + b``; returns ``([w1..wm, b], variance)``.

    Minimises ``sum_i w_i (y_i - c.z_i - d)^2`` by ordinary least squares on the rows scaled by
    ``sqrt(w_i)`` (standardised columns, for conditioning); ``var = max(RSS_w / W, floor)``.
    """
    Z = std.transform(X)
    sw = np.sqrt(w)
    design = np.column_stack([Z, np.ones(len(y))]) * sw[:, None]
    beta, *_ = np.linalg.lstsq(design, y * sw, rcond=None)
    coef, intercept = std.back(beta[:-1], beta[-1:])
    weights = np.append(coef[0], intercept[0])
    # weighted RSS = sum_i w_i (y_i - w.x_i - b)^2
    resid = y - (X @ weights[:-1] + weights[-1])
    var = max(float(w @ resid**2 / w.sum()), floor)
    return tuple(weights.tolist()), var


def _with_log_likelihood(leaf: Leaf, y: np.ndarray, w: np.ndarray, X: np.ndarray | None) -> Leaf:
    """The leaf with ``log_likelihood = sum_i w_i log f(y_i | x_i)`` on the given rows."""
    return replace(leaf, log_likelihood=float(w @ leaf.log_prob(y, X)))


# ---------------------------------------------------------------------- validation


def _validate(
    kind: str,
    y: ArrayLike,
    w: ArrayLike,
    X: ArrayLike | None,
    n_classes: int | None,
    log_n: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, int | None]:
    """Checked float arrays restricted to the rows of positive weight, and K."""
    if kind not in _KINDS:
        raise ValueError(f"kind must be one of {_KINDS}, got {kind!r}")
    if not isinstance(log_n, int | float) or not math.isfinite(log_n) or log_n < 0:
        raise ValueError(f"log_n must be a finite number >= 0, got {log_n!r}")
    K: int | None = None
    if kind == "discrete":
        if n_classes is None:
            raise ValueError("a discrete head needs n_classes (the size of its domain)")
        if isinstance(n_classes, bool) or not isinstance(n_classes, int | np.integer):
            raise ValueError(f"n_classes must be an int, got {n_classes!r}")
        if n_classes < 1:
            raise ValueError(f"n_classes must be >= 1, got {n_classes}")
        K = int(n_classes)
    elif n_classes is not None:
        raise ValueError(f"n_classes applies to discrete heads only, got {n_classes!r} for {kind}")
    y_arr = _as_vector(y, "y")
    w_arr = _as_vector(w, "w")
    n = len(y_arr)
    if len(w_arr) != n:
        raise ValueError(f"y has {n} rows but w has {len(w_arr)}")
    X_arr = np.empty((n, 0)) if X is None else _as_matrix(X, n)
    if not np.isfinite(w_arr).all():
        raise ValueError("the weights w must be finite")
    if (w_arr < 0).any():
        raise ValueError("the weights w must be >= 0")
    keep = w_arr > 0
    if not keep.any():
        raise ValueError("the total weight is 0: no row to fit")
    y_arr, w_arr, X_arr = y_arr[keep], w_arr[keep], X_arr[keep]
    _check_finite(y_arr, "y")
    _check_finite(X_arr, "X")
    if kind == "discrete":
        assert K is not None
        _class_indices(y_arr, K)
    elif kind == "count":
        _check_counts(y_arr)
    return y_arr, w_arr, X_arr, K


def _as_vector(a: ArrayLike, name: str) -> np.ndarray:
    arr = np.asarray(a, dtype=float)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional, got shape {arr.shape}")
    return arr


def _as_matrix(X: ArrayLike, n: int | None) -> np.ndarray:
    arr = np.asarray(X, dtype=float)
    if arr.ndim != 2:
        raise ValueError(f"X must be two-dimensional (n, m), got shape {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ValueError(f"y has {n} rows but X has {arr.shape[0]}")
    return arr


def _check_finite(a: np.ndarray, name: str) -> None:
    if not np.isfinite(a).all():
        raise ValueError(f"{name} must be finite (no NaN or infinity)")


def _class_indices(y: np.ndarray, K: int) -> np.ndarray:
    if ((y != np.round(y)) | (y < 0) | (y > K - 1)).any():
        raise ValueError(f"class indices must be integers in 0..{K - 1}")
    return y.astype(np.intp)


def _check_counts(y: np.ndarray) -> None:
    if ((y < 0) | (y != np.round(y))).any():
        raise ValueError("counts must be non-negative integers")


def _gaussian_log_pdf(y: np.ndarray, mean: float | np.ndarray, var: float) -> np.ndarray:
    # log N(y; mean, var) = -0.5 log(2 pi var) - (y - mean)^2 / (2 var)
    return -0.5 * np.log(2.0 * np.pi * var) - (y - mean) ** 2 / (2.0 * var)
