"""Leaf models of the distributional logic tree learner (python/probanchor/ddclearn/leaves.py).

Reference fits come from statsmodels (WLS, Logit, MNLogit, GLM Poisson), which estimate the
unpenalised maximum likelihood. The leaves carry a tiny L2 penalty (0.01 on standardised
coefficients) and one pseudo-row per class, so on thousands of rows they must agree with the
reference to a small fraction of its standard error, and with the generating parameters to within
4 standard errors.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import statsmodels.api as sm
from scipy.special import expit, log_expit
from scipy.stats import norm, poisson

from probanchor.ddclearn import leaves
from probanchor.ddclearn.leaves import Leaf, LeafOptions, fit_leaf

# ----------------------------------------------------------------------------- helpers


def _log_n(n: int) -> float:
    return math.log(n)


def _params(leaf: Leaf) -> np.ndarray:
    """All the numeric parameters of a leaf, flattened."""
    parts: list[float] = []
    for name in ("probs", "weights"):
        value = getattr(leaf, name)
        if value is not None:
            parts.extend(value)
    if leaf.weight_rows is not None:
        parts.extend(v for row in leaf.weight_rows for v in row)
    for name in ("mean", "variance", "rate"):
        value = getattr(leaf, name)
        if value is not None:
            parts.append(value)
    return np.asarray(parts)


def _softmax_sample(rng: np.random.Generator, X: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Class indices drawn from P(k|x) proportional to exp(w_k.x + b_k)."""
    eta = X @ rows[:, :-1].T + rows[:, -1]
    p = np.exp(eta - eta.max(axis=1, keepdims=True))
    p /= p.sum(axis=1, keepdims=True)
    u = rng.uniform(size=(len(X), 1))
    return (u > np.cumsum(p, axis=1)).sum(axis=1).astype(float)


def _logistic_data(n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """d ~ U(0, 0.3), P(class 0 | d) = sigmoid(0.8 - 16.9 d)."""
    rng = np.random.default_rng(seed)
    d = rng.uniform(0.0, 0.3, n)
    y = (rng.uniform(size=n) >= expit(0.8 - 16.9 * d)).astype(float)
    return y, d[:, None]


# ----------------------------------------------------------------------------- finite


def test_finite_against_hand_computation() -> None:
    y = np.array([0, 0, 1, 2, 0, 3])
    w = np.array([1.0, 2.0, 1.0, 0.5, 1.0, 0.0])  # the last row (class 3) weighs nothing
    leaf = fit_leaf("discrete", y, w, np.empty((6, 0)), log_n=_log_n(5), n_classes=4)
    # counts (4, 1, 0.5, 0), W = 5.5, a = 1: p = (5, 2, 1.5, 1) / 9.5
    expected = np.array([5.0, 2.0, 1.5, 1.0]) / 9.5
    assert leaf.family == "finite" and leaf.n_classes == 4 and not leaf.uses_regressors
    np.testing.assert_allclose(leaf.probs, expected, rtol=1e-14)
    assert leaf.n_params == 3 and leaf.rows == 5 and leaf.weight == pytest.approx(5.5)
    ll = 4.0 * math.log(5 / 9.5) + 1.0 * math.log(2 / 9.5) + 0.5 * math.log(1.5 / 9.5)
    assert leaf.log_likelihood == pytest.approx(ll, rel=1e-14)
    assert leaf.bic(2.0) == pytest.approx(2 * ll - 3 * 2.0, rel=1e-14)
    np.testing.assert_allclose(leaf.predict(None, n=2), np.tile(expected, (2, 1)), rtol=1e-14)
    np.testing.assert_allclose(leaf.log_prob([3, 0], None), np.log(expected[[3, 0]]), rtol=1e-14)

    half = fit_leaf(
        "discrete", y, w, None, log_n=1.0, n_classes=4, options=LeafOptions(smoothing=0.5)
    )
    np.testing.assert_allclose(half.probs, np.array([4.5, 1.5, 1.0, 0.5]) / 7.5, rtol=1e-14)

    raw = fit_leaf(
        "discrete", y, w, None, log_n=1.0, n_classes=4, options=LeafOptions(smoothing=0.0)
    )
    np.testing.assert_allclose(raw.probs, np.array([4.0, 1.0, 0.5, 0.0]) / 5.5, rtol=1e-14)
    assert raw.log_prob([3], None)[0] == -np.inf


def test_unseen_class_keeps_positive_probability() -> None:
    # a learned finite([1.0:false]) would make contrary evidence impossible in a particle filter
    y = np.ones(50)
    leaf = fit_leaf("discrete", y, np.ones(50), None, log_n=_log_n(50), n_classes=2)
    assert leaf.probs == pytest.approx((1 / 52, 51 / 52), rel=1e-14)
    assert np.isfinite(leaf.log_prob([0.0], None)).all()


# ----------------------------------------------------------------------------- weights


def _strong_data(family: str, n: int, seed: int) -> tuple[str, np.ndarray, np.ndarray, int | None]:
    """(kind, y, X, K) on which ``fit_leaf`` picks ``family``."""
    rng = np.random.default_rng(seed)
    x = rng.normal(size=(n, 2))
    if family in ("finite", "gaussian", "poisson"):
        x = np.empty((n, 0))
    if family == "finite":
        return "discrete", rng.integers(0, 3, n).astype(float), x, 3
    if family == "gaussian":
        return "continuous", rng.normal(2.0, 3.0, n), x, None
    if family == "poisson":
        return "count", rng.poisson(2.5, n).astype(float), x, None
    if family == "linear_gaussian":
        return "continuous", x @ [2.0, -1.0] + 0.5 + rng.normal(0, 0.5, n), x, None
    if family == "logistic":
        p0 = expit(x @ [2.0, -1.0] + 0.3)
        return "discrete", (rng.uniform(size=n) >= p0).astype(float), x, 2
    if family == "softmax":
        rows = np.array([[0.0, 0.0, 0.0], [2.0, -1.0, 0.3], [-1.5, 1.0, -0.2]])
        return "discrete", _softmax_sample(rng, x, rows), x, 3
    assert family == "poisson_log_linear"
    return "count", rng.poisson(np.exp(x @ [0.7, -0.4] + 0.2)).astype(float), x, None


@pytest.mark.parametrize("family", sorted(leaves.FAMILIES))
def test_weight_two_equals_row_twice(family: str) -> None:
    n = 300
    kind, y, X, K = _strong_data(family, n, seed=11)
    w = np.where(np.arange(n) % 3 == 0, 2.0, 1.0)
    weighted = fit_leaf(kind, y, w, X, log_n=_log_n(n), n_classes=K)
    twice = np.flatnonzero(w == 2.0)
    idx = np.concatenate([np.arange(n), twice])
    duplicated = fit_leaf(kind, y[idx], np.ones(len(idx)), X[idx], log_n=_log_n(n), n_classes=K)
    assert weighted.family == duplicated.family == family
    assert weighted.weight == pytest.approx(duplicated.weight, rel=1e-14)
    assert weighted.rows == n and duplicated.rows == len(idx)
    assert weighted.n_params == duplicated.n_params
    # closed forms agree to rounding; the lbfgs fits (gradient tolerance 1e-8) to ~1e-6
    tol = 1e-12 if family in ("finite", "gaussian", "poisson", "linear_gaussian") else 1e-6
    np.testing.assert_allclose(_params(weighted), _params(duplicated), rtol=tol, atol=tol)
    assert weighted.log_likelihood == pytest.approx(duplicated.log_likelihood, rel=tol)


# ----------------------------------------------------------------------------- gaussian


def test_gaussian_against_weighted_least_squares() -> None:
    rng = np.random.default_rng(3)
    n = 400
    y = rng.normal(5.0, 2.0, n)
    w = rng.uniform(0.2, 3.0, n)
    leaf = fit_leaf("continuous", y, w, np.empty((n, 0)), log_n=_log_n(n))
    res = sm.WLS(y, np.ones(n), weights=w).fit()
    assert leaf.family == "gaussian" and leaf.n_params == 2
    assert leaf.mean == pytest.approx(res.params[0], abs=1e-8)
    # maximum likelihood variance: weighted RSS / sum(w), not / (n - 1)
    assert leaf.variance == pytest.approx(res.ssr / w.sum(), rel=1e-10)
    ll = w @ norm.logpdf(y, leaf.mean, math.sqrt(leaf.variance))
    assert leaf.log_likelihood == pytest.approx(ll, rel=1e-12)
    np.testing.assert_allclose(leaf.predict(None, n=3), np.full(3, leaf.mean))


def test_gaussian_variance_floor() -> None:
    leaf = fit_leaf(
        "continuous",
        np.full(5, 2.0),
        np.ones(5),
        None,
        log_n=1.0,
        options=LeafOptions(variance_floor=1e-6),
    )
    assert leaf.variance == 1e-6 and leaf.mean == 2.0


def test_linear_gaussian_against_weighted_least_squares() -> None:
    rng = np.random.default_rng(4)
    n = 500
    # columns of very different scales and offsets, plus one that is constant over the leaf
    X = np.column_stack([rng.normal(0, 1, n), 50 + 1000 * rng.uniform(size=n), np.full(n, 7.0)])
    y = X[:, :2] @ [1.5, -0.002] + 3.0 + rng.normal(0, 0.3, n)
    w = rng.uniform(0.1, 2.0, n)
    leaf = fit_leaf("continuous", y, w, X, log_n=_log_n(n))
    res = sm.WLS(y, sm.add_constant(X[:, :2]), weights=w).fit()
    assert leaf.family == "linear_gaussian" and leaf.uses_regressors and leaf.n_params == 5
    ours = np.asarray(leaf.weights)
    assert ours[2] == 0.0  # the constant column is left out of the fit
    np.testing.assert_allclose(ours[[3, 0, 1]], res.params, rtol=1e-8, atol=1e-8)
    assert leaf.variance == pytest.approx(res.ssr / w.sum(), rel=1e-10)
    mean = X @ ours[:-1] + ours[-1]
    np.testing.assert_allclose(leaf.predict(X), mean, rtol=1e-14)
    ll = w @ norm.logpdf(y, mean, math.sqrt(leaf.variance))
    assert leaf.log_likelihood == pytest.approx(ll, rel=1e-12)


# ----------------------------------------------------------------------------- logistic


def test_logistic_against_statsmodels_and_sklearn() -> None:
    n = 20000
    y, X = _logistic_data(n, seed=0)
    w = np.ones(n)
    leaf = fit_leaf("discrete", y, w, X, log_n=_log_n(n), n_classes=2)
    assert leaf.family == "logistic" and leaf.n_params == 2 and leaf.uses_regressors
    slope, bias = leaf.weights

    # statsmodels Logit of the FIRST class: P(y = 0 | d) = sigmoid(b + w d)
    res = sm.Logit((y == 0).astype(float), sm.add_constant(X)).fit(disp=0)
    est = np.array([bias, slope])
    se = res.bse
    assert np.all(np.abs(est - [0.8, -16.9]) < 4 * se)  # the generating parameters
    assert np.all(np.abs(est - res.params) < 0.05 * se)  # penalty and pseudo-rows: negligible

    # the emitted sigmoid(w.x + b) is sklearn's predict_proba of class 0 of the internal fit
    std = leaves._Standardiser.fit(X, w)
    model = leaves._fit_classifier(y, w, X, 2, std, LeafOptions())
    assert model.coef_.shape == (1, 1) and list(model.classes_) == [0, 1]
    p0_sklearn = model.predict_proba(std.transform(X))[:, 0]
    p0_emitted = expit(X[:, 0] * slope + bias)
    np.testing.assert_allclose(p0_emitted, p0_sklearn, rtol=0, atol=1e-12)
    np.testing.assert_allclose(leaf.predict(X)[:, 0], p0_sklearn, rtol=0, atol=1e-12)
    np.testing.assert_allclose(leaf.predict(X).sum(axis=1), 1.0, rtol=0, atol=1e-12)

    eta = X[:, 0] * slope + bias
    ll = np.where(y == 0, log_expit(eta), log_expit(-eta)).sum()
    assert leaf.log_likelihood == pytest.approx(ll, rel=1e-12)
    assert 0.0 <= res.llf - leaf.log_likelihood < 1e-3  # the MLE is (barely) better


# ----------------------------------------------------------------------------- softmax


def test_softmax_against_mnlogit() -> None:
    rng = np.random.default_rng(5)
    n = 6000
    X = np.column_stack([rng.normal(0, 1, n), rng.uniform(-2, 2, n)])
    truth = np.array([[0.0, 0.0, 0.0], [1.5, -1.0, 0.3], [-1.0, 0.5, -0.2]])  # [w1, w2, b]
    y = _softmax_sample(rng, X, truth)
    leaf = fit_leaf("discrete", y, np.ones(n), X, log_n=_log_n(n), n_classes=3)
    assert leaf.family == "softmax" and leaf.n_params == 2 * 3
    rows = np.asarray(leaf.weight_rows)
    assert rows.shape == (3, 3) and np.all(rows[0] == 0.0)

    probs = leaf.predict(X)
    np.testing.assert_allclose(probs.sum(axis=1), 1.0, rtol=0, atol=1e-12)
    assert leaf.log_likelihood == pytest.approx(np.log(probs[np.arange(n), y.astype(int)]).sum())

    # MNLogit uses class 0 as the reference, as the leaf does; params: (const, x1, x2) x (1, 2)
    res = sm.MNLogit(y, sm.add_constant(X)).fit(disp=0, method="newton", maxiter=100)
    ref = np.asarray(res.params).T[:, [1, 2, 0]]  # rows k = 1, 2 as [w1, w2, b]
    se = np.asarray(res.bse).T[:, [1, 2, 0]]
    assert np.all(np.abs(rows[1:] - truth[1:]) < 4 * se)
    assert np.all(np.abs(rows[1:] - ref) < 0.05 * se)
    np.testing.assert_allclose(probs, res.predict(sm.add_constant(X)), rtol=0, atol=2e-3)


def test_softmax_class_without_rows_gets_positive_probability() -> None:
    rng = np.random.default_rng(6)
    n = 3000
    X = rng.normal(size=(n, 1))
    truth = np.array([[0.0, 0.0], [2.0, 0.1], [-2.0, 0.0]])
    y = _softmax_sample(rng, X, truth)  # classes 0..2; class 3 of the domain never occurs
    three = fit_leaf("discrete", y, np.ones(n), X, log_n=_log_n(n), n_classes=3)
    four = fit_leaf("discrete", y, np.ones(n), X, log_n=_log_n(n), n_classes=4)
    assert four.family == "softmax" and np.asarray(four.weight_rows).shape == (4, 2)
    p = four.predict(X)
    # one pseudo-row of weight 1 for class 3: its probability averages about 1 / (n + K)
    assert np.all(p[:, 3] > 0) and p[:, 3].mean() < 10 / n
    np.testing.assert_allclose(p[:, :3], three.predict(X), rtol=0, atol=20 / n)


def test_regression_needs_two_classes() -> None:
    X = np.arange(10.0)[:, None]
    leaf = fit_leaf("discrete", np.full(10, 2.0), np.ones(10), X, log_n=0.0, n_classes=3)
    assert leaf.family == "finite"
    np.testing.assert_allclose(leaf.probs, np.array([1.0, 1.0, 11.0]) / 13, rtol=1e-14)


# ----------------------------------------------------------------------------- poisson


def test_poisson_rate_and_zero_counts() -> None:
    y = np.array([0.0, 3.0, 1.0, 2.0])
    w = np.array([1.0, 0.5, 2.0, 1.5])
    leaf = fit_leaf("count", y, w, None, log_n=1.0)
    assert leaf.family == "poisson" and leaf.n_params == 1
    assert leaf.rate == pytest.approx((1.5 + 2.0 + 3.0) / 5.0, rel=1e-14)
    np.testing.assert_allclose(leaf.log_prob(y, None), poisson.logpmf(y, leaf.rate), rtol=1e-12)

    X = np.arange(4.0)[:, None]
    zero = fit_leaf("count", np.zeros(4), np.ones(4), X, log_n=0.0)
    assert zero.family == "poisson" and 0.0 < zero.rate <= 1e-9
    assert np.all(np.isfinite(zero.log_prob(np.zeros(4), None)))
    assert np.isfinite(zero.log_likelihood)


def test_poisson_log_linear_against_glm() -> None:
    rng = np.random.default_rng(7)
    n = 5000
    X = np.column_stack([rng.normal(0, 1, n), 10 + 5 * rng.uniform(size=n)])
    truth = np.array([0.5, -0.1, 1.2])  # [w1, w2, b]
    y = rng.poisson(np.exp(X @ truth[:2] + truth[2])).astype(float)
    leaf = fit_leaf("count", y, np.ones(n), X, log_n=_log_n(n))
    assert leaf.family == "poisson_log_linear" and leaf.n_params == 3
    res = sm.GLM(y, sm.add_constant(X), family=sm.families.Poisson()).fit()
    est = np.asarray(leaf.weights)[[2, 0, 1]]
    se = res.bse
    assert np.all(np.abs(est - truth[[2, 0, 1]]) < 4 * se)
    assert np.all(np.abs(est - res.params) < 0.05 * se)
    rate = np.exp(X @ np.asarray(leaf.weights)[:2] + leaf.weights[2])
    np.testing.assert_allclose(leaf.predict(X), rate, rtol=1e-12)
    assert leaf.log_likelihood == pytest.approx(poisson.logpmf(y, rate).sum(), rel=1e-12)


# ----------------------------------------------------------------------------- BIC


@pytest.mark.parametrize(
    ("kind", "plain", "regression"),
    [
        ("continuous", "gaussian", "linear_gaussian"),
        ("discrete", "finite", "logistic"),
        ("count", "poisson", "poisson_log_linear"),
    ],
)
def test_bic_choice(kind: str, plain: str, regression: str) -> None:
    rng = np.random.default_rng(8)
    n = 2000
    noise = rng.normal(size=(n, 1))
    signal = rng.normal(size=n)
    if kind == "continuous":
        y_noise, y_signal = rng.normal(1.0, 1.0, n), 1.0 + 2.0 * signal + rng.normal(0, 1, n)
    elif kind == "discrete":
        y_noise = (rng.uniform(size=n) < 0.4).astype(float)
        y_signal = (rng.uniform(size=n) >= expit(2.0 * signal)).astype(float)
    else:
        y_noise = rng.poisson(2.0, n).astype(float)
        y_signal = rng.poisson(np.exp(0.5 + 0.8 * signal)).astype(float)
    K = 2 if kind == "discrete" else None
    log_n = _log_n(n)
    w = np.ones(n)

    chosen = fit_leaf(kind, y_noise, w, noise, log_n=log_n, n_classes=K)
    assert chosen.family == plain
    # the regression fits the noise a little better, but not by the 0.5 log n its parameter costs
    other = leaves._fit_with_regressors(kind, y_noise, w, noise, K, LeafOptions())
    assert other is not None and other.family == regression
    assert other.log_likelihood > chosen.log_likelihood
    assert other.bic(log_n) < chosen.bic(log_n)

    assert fit_leaf(kind, y_signal, w, signal[:, None], log_n=log_n, n_classes=K).family == (
        regression
    )
    # a regressor that does not vary cannot help: the model without regressors
    constant = np.full((n, 1), 3.0)
    assert fit_leaf(kind, y_signal, w, constant, log_n=0.0, n_classes=K).family == plain


# ----------------------------------------------------------------------------- bad inputs

_Y = np.array([0.0, 1.0, 1.0])
_W = np.ones(3)
_X = np.zeros((3, 1))


@pytest.mark.parametrize(
    ("kind", "y", "w", "X", "K", "message"),
    [
        ("discrete", _Y, np.ones(2), _X, 2, "rows"),
        ("discrete", _Y, _W, np.zeros((2, 1)), 2, "rows"),
        ("discrete", _Y, _W, np.zeros(3), 2, "two-dimensional"),
        ("discrete", _Y, np.array([1.0, -1.0, 1.0]), _X, 2, ">= 0"),
        ("discrete", _Y, np.array([1.0, np.nan, 1.0]), _X, 2, "finite"),
        ("discrete", _Y, np.array([1.0, np.inf, 1.0]), _X, 2, "finite"),
        ("discrete", _Y, np.zeros(3), _X, 2, "total weight"),
        ("continuous", np.array([0.0, np.nan, 1.0]), _W, _X, None, "y must be finite"),
        ("continuous", _Y, _W, np.array([[0.0], [np.inf], [1.0]]), None, "X must be finite"),
        ("discrete", np.array([0.0, 2.0, 1.0]), _W, _X, 2, "class indices"),
        ("discrete", np.array([0.0, 0.5, 1.0]), _W, _X, 2, "class indices"),
        ("discrete", np.array([0.0, -1.0, 1.0]), _W, _X, 2, "class indices"),
        ("count", np.array([0.0, -1.0, 1.0]), _W, _X, None, "non-negative integers"),
        ("count", np.array([0.0, 1.5, 1.0]), _W, _X, None, "non-negative integers"),
        ("discrete", _Y, _W, _X, None, "n_classes"),
        ("discrete", _Y, _W, _X, 0, "n_classes"),
        ("continuous", _Y, _W, _X, 2, "n_classes"),
        ("binary", _Y, _W, _X, None, "kind"),
    ],
)
def test_bad_inputs_raise(
    kind: str, y: np.ndarray, w: np.ndarray, X: np.ndarray, K: int | None, message: str
) -> None:
    with pytest.raises(ValueError, match=message):
        fit_leaf(kind, y, w, X, log_n=1.0, n_classes=K)


def test_bad_log_n_and_options_raise() -> None:
    with pytest.raises(ValueError, match="log_n"):
        fit_leaf("continuous", _Y, _W, _X, log_n=float("nan"))
    for bad in ({"smoothing": -1.0}, {"l2": -0.1}, {"variance_floor": 0.0}, {"l2": math.inf}):
        with pytest.raises(ValueError, match=next(iter(bad))):
            LeafOptions(**bad)
    with pytest.raises(ValueError, match="family"):
        Leaf("beta", None)


def test_zero_weight_rows_are_dropped_unchecked() -> None:
    # rows of weight 0 (e.g. an undefined regressor) may hold anything
    y = np.array([1.0, np.nan, 2.0, 4.0])
    X = np.array([[0.0], [np.nan], [1.0], [2.0]])
    w = np.array([1.0, 0.0, 1.0, 1.0])
    leaf = fit_leaf("continuous", y, w, X, log_n=0.0)
    reference = fit_leaf("continuous", y[w > 0], w[w > 0], X[w > 0], log_n=0.0)
    assert leaf == reference and leaf.rows == 3


def test_regression_leaf_needs_x() -> None:
    n = 200
    kind, y, X, K = _strong_data("logistic", n, seed=2)
    leaf = fit_leaf(kind, y, np.ones(n), X, log_n=_log_n(n), n_classes=K)
    assert leaf.family == "logistic"
    with pytest.raises(ValueError, match="regressors"):
        leaf.log_prob(y, None)
    with pytest.raises(ValueError, match="columns"):
        leaf.predict(X[:, :1])
