"""prolog/ddc/lang/ddc_dist.pl against scipy.stats: log densities at chosen points, samplers by KS
tests.

The Prolog module is reached through janus (python/bridge). Distribution terms are passed as
text and parsed in Prolog; values are numbers or lists (the module accepts a list wherever a
multivariate value is a comma tuple).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from scipy import stats

from bridge import prolog

DIST_FILE = prolog.PROLOG_DIR / "ddc/lang/ddc_dist.pl"


@pytest.fixture(scope="module", autouse=True)
def _load() -> None:
    prolog.ensure_loaded(DIST_FILE)


def log_density(dist: str, value: Any) -> float:
    result = prolog.query_once(
        "term_string(_D, DS), ddc_dist:dist_check(_D), ddc_dist:dist_log_density(_D, X, LP)",
        {"DS": dist, "X": value},
    )
    assert result["truth"], f"dist_log_density failed for {dist} at {value!r}"
    return float(result["LP"])


def samples(dist: str, n: int, seed: int) -> np.ndarray:
    """n draws as an (n, k) array (k = 1 for scalars); tuples are turned into lists in Prolog."""
    result = prolog.query_once(
        "term_string(_D, DS), ddc_dist:dist_check(_D), set_random(seed(Seed)),"
        "findall(_L, (between(1, N, _), ddc_dist:dist_sample(_D, _X),"
        "             ( is_list(_X) -> _L = _X ; comma_list(_X, _L) )), Ls)",
        {"DS": dist, "N": n, "Seed": seed},
    )
    assert result["truth"]
    return np.asarray(result["Ls"], dtype=float)


def assert_close(ours: float, expected: float) -> None:
    if math.isinf(expected):
        assert ours == expected
    else:
        assert ours == pytest.approx(expected, rel=1e-9, abs=1e-9)


# (distribution term, scipy frozen distribution, points); scipy's log density is the reference.
CONTINUOUS_1D = [
    ("gaussian(1.5, 4)", stats.norm(1.5, 2.0), [-3.0, 0.0, 1.5, 2.7, 9.0]),
    ("gaussian(0, 0.01)", stats.norm(0.0, 0.1), [0.0, 0.1, -0.25]),
    ("contUniform(-1, 3)", stats.uniform(-1, 4), [-2.0, -1.0, 0.3, 3.0, 3.5]),
    ("beta(2, 3)", stats.beta(2, 3), [-0.1, 0.0, 0.2, 0.5, 0.99, 1.0, 1.2]),
    ("beta(0.5, 0.7)", stats.beta(0.5, 0.7), [0.01, 0.5, 0.93]),
    ("beta(1, 4)", stats.beta(1, 4), [0.0, 0.3, 1.0]),
    ("gamma(2.5, 1.5)", stats.gamma(2.5, scale=1.5), [-1.0, 0.0, 0.4, 3.0, 12.0]),
    ("gamma(0.6, 2)", stats.gamma(0.6, scale=2.0), [0.05, 1.0, 7.0]),
    ("gamma(1, 2)", stats.gamma(1, scale=2.0), [0.0, 1.0]),
    ("invgamma(3, 2)", stats.invgamma(3, scale=2.0), [-1.0, 0.0, 0.3, 1.0, 5.0]),
    ("student(4, 1, 9)", stats.t(4, loc=1.0, scale=3.0), [-10.0, 0.0, 1.0, 4.2]),
    ("student(2.5)", stats.t(2.5), [-3.0, 0.0, 0.7]),
    ("exponential(2.5)", stats.expon(scale=1 / 2.5), [-0.5, 0.0, 0.3, 4.0]),
]

DISCRETE_1D = [
    ("poisson(4)", stats.poisson(4), [-1, 0, 1, 4, 9, 30]),
    ("poisson(250)", stats.poisson(250), [200, 250, 301]),
    ("uniform(2:7)", stats.randint(2, 8), [1, 2, 5, 7, 8]),
]


@pytest.mark.parametrize(("dist", "frozen", "points"), CONTINUOUS_1D, ids=lambda x: str(x))
def test_continuous_log_density_matches_scipy(dist: str, frozen: Any, points: list[float]) -> None:
    for x in points:
        assert_close(log_density(dist, x), float(frozen.logpdf(x)))


@pytest.mark.parametrize(("dist", "frozen", "points"), DISCRETE_1D, ids=lambda x: str(x))
def test_discrete_log_mass_matches_scipy(dist: str, frozen: Any, points: list[int]) -> None:
    for k in points:
        assert_close(log_density(dist, k), float(frozen.logpmf(k)))


def test_multivariate_gaussian_matches_scipy() -> None:
    mean = [1.0, -2.0, 0.5]
    cov = np.array([[2.0, 0.3, -0.4], [0.3, 1.0, 0.2], [-0.4, 0.2, 0.5]])
    dist = f"gaussian({mean}, {cov.flatten().tolist()})"
    ref = stats.multivariate_normal(mean, cov)
    for x in ([1.0, -2.0, 0.5], [0.0, 0.0, 0.0], [3.1, -1.2, 1.7]):
        assert_close(log_density(dist, x), float(ref.logpdf(x)))


def test_one_dimensional_multivariate_gaussian_takes_a_number() -> None:
    assert_close(log_density("gaussian([2], [0.25])", 2.3), float(stats.norm(2, 0.5).logpdf(2.3)))


def test_indep_gaussians_is_the_product_of_its_blocks() -> None:
    dist = "indepGaussians([(0, 1), ([1, 2], [1, 0.5, 0.5, 2]), (3, 0.04)])"
    x = [0.4, 1.5, 1.0, 3.1]
    expected = (
        stats.norm(0, 1).logpdf(0.4)
        + stats.multivariate_normal([1, 2], [[1, 0.5], [0.5, 2]]).logpdf([1.5, 1.0])
        + stats.norm(3, 0.2).logpdf(3.1)
    )
    assert_close(log_density(dist, x), float(expected))


def test_dirichlet_matches_scipy() -> None:
    alpha = [1.5, 2.0, 3.0]
    for x in ([0.2, 0.3, 0.5], [0.6, 0.1, 0.3]):
        assert_close(log_density(f"dirichlet({alpha})", x), float(stats.dirichlet(alpha).logpdf(x)))
    assert log_density(f"dirichlet({alpha})", [0.2, 0.3, 0.6]) == -math.inf  # off the simplex


def test_finite_families_match_their_normalised_weights() -> None:
    assert_close(log_density("finite([0.2:1, 0.5:2, 0.3:1])", 1.0), math.log(0.5))
    assert_close(log_density("propfinite([2:a, 6:b])", "b"), math.log(0.75))
    weights = np.array([0.3, -1.2, 2.0])
    logz = float(np.log(np.exp(weights).sum()))
    assert_close(log_density("logfinite([0.3:a, -1.2:b, 2.0:c])", "b"), -1.2 - logz)
    assert_close(log_density("uniform([a, b, a, c])", "a"), math.log(0.5))
    assert_close(log_density("bool(0.3)", "false"), math.log(0.7))
    assert log_density("finite([0.2:1, 0.8:2])", 3) == -math.inf


# (distribution term, scipy frozen distribution): a KS test of 4,000 draws at a fixed seed.
KS_CASES = [
    ("gaussian(1.5, 4)", stats.norm(1.5, 2.0)),
    ("contUniform(-1, 3)", stats.uniform(-1, 4)),
    ("beta(2, 3)", stats.beta(2, 3)),
    ("beta(0.4, 0.6)", stats.beta(0.4, 0.6)),
    ("gamma(2.5, 1.5)", stats.gamma(2.5, scale=1.5)),
    ("gamma(0.3, 2)", stats.gamma(0.3, scale=2.0)),
    ("invgamma(3, 2)", stats.invgamma(3, scale=2.0)),
    ("student(4, 1, 9)", stats.t(4, loc=1.0, scale=3.0)),
    ("exponential(2.5)", stats.expon(scale=1 / 2.5)),
]


@pytest.mark.parametrize(("dist", "frozen"), KS_CASES, ids=lambda x: str(x))
def test_sampler_passes_ks_test(dist: str, frozen: Any) -> None:
    draws = samples(dist, 4000, seed=11)[:, 0]
    assert stats.kstest(draws, frozen.cdf).pvalue > 1e-3


@pytest.mark.parametrize("lam", [3.0, 25.0, 400.0])
def test_poisson_sampler_matches_pmf(lam: float) -> None:
    n = 6000
    draws = samples(f"poisson({lam})", n, seed=5)[:, 0].astype(int)
    ref = stats.poisson(lam)
    lo, hi = int(ref.ppf(0.001)), int(ref.ppf(0.999))
    edges = np.arange(lo, hi + 2)
    counts, _ = np.histogram(np.clip(draws, lo, hi), bins=edges)
    probs = ref.pmf(edges[:-1])
    probs[0] += ref.cdf(lo - 1)
    probs[-1] += ref.sf(hi)
    # pool bins with expected count < 5 into their neighbour so the chi-square test is valid
    observed, expected, acc_o, acc_e = [], [], 0.0, 0.0
    for o, e in zip(counts, probs * n, strict=True):
        acc_o, acc_e = acc_o + o, acc_e + e
        if acc_e >= 5:
            observed.append(acc_o)
            expected.append(acc_e)
            acc_o = acc_e = 0.0
    observed[-1] += acc_o
    expected[-1] += acc_e
    expected_arr = np.array(expected) * n / sum(expected)
    assert stats.chisquare(observed, expected_arr).pvalue > 1e-3


def test_multivariate_sampler_has_the_covariance() -> None:
    cov = np.array([[2.0, 0.6], [0.6, 0.5]])
    n = 6000
    draws = samples(f"gaussian([1, -1], {cov.flatten().tolist()})", n, seed=3)
    assert draws.shape == (n, 2)
    se_mean = np.sqrt(np.diag(cov) / n)
    assert np.all(np.abs(draws.mean(axis=0) - [1, -1]) < 5 * se_mean)
    # standard error of a sample covariance entry: sqrt((s_ii s_jj + s_ij^2) / n)
    emp = np.cov(draws.T)
    se_cov = np.sqrt((np.outer(np.diag(cov), np.diag(cov)) + cov**2) / n)
    assert np.all(np.abs(emp - cov) < 5 * se_cov)


def test_dirichlet_sampler_marginals_are_beta() -> None:
    alpha = [1.5, 2.0, 3.0]
    draws = samples(f"dirichlet({alpha})", 4000, seed=9)
    assert np.allclose(draws.sum(axis=1), 1.0)
    total = sum(alpha)
    for i, a in enumerate(alpha):
        assert stats.kstest(draws[:, i], stats.beta(a, total - a).cdf).pvalue > 1e-3
