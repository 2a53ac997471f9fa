"""The particle weights and resampling: their one place, prolog/ddc/filter/ddc_weights.pl, which
the swipl belief (ddc_belief.pl) and bridge.Filter both call; here through the bridge's adapter,
with the uniforms drawn from numpy as bridge.Filter draws them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bridge import EngineError, prolog
from bridge.errors import BadArgumentError
from bridge.prolog import OUT

WEIGHTS = np.array([0.5, 0.25, 0.125, 0.0625, 0.0375, 0.025, 0.0, 0.0])  # sums to 1
SCHEMES = ["systematic", "multinomial", "residual"]


@pytest.fixture(scope="module", autouse=True)
def weights_module() -> None:
    prolog.ensure_loaded(prolog.PROLOG_DIR / "ddc/filter/ddc_weights.pl", imports=False)


def weights(name: str, **arguments: object) -> dict:
    return prolog.call(f"ddc_weights:{name}", **arguments)


def resample(ws: np.ndarray, scheme: str, rng: np.random.Generator) -> np.ndarray:
    """The ancestors picked by ``resample_indices/4``, the uniforms drawn from ``rng`` as
    bridge.Filter draws them (``resample_draws/3`` of them)."""
    draws = weights("resample_draws", S=scheme, W=ws.tolist(), K=OUT)["K"]
    uniforms = rng.random(draws)
    found = weights("resample_indices", S=scheme, W=ws.tolist(), U=uniforms.tolist(), I=OUT)
    return np.asarray(found["I"], dtype=np.int64)


def counts(indices: np.ndarray, n: int) -> np.ndarray:
    return np.bincount(indices, minlength=n)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_every_scheme_returns_n_sorted_valid_indices_and_never_picks_zero_weight(
        scheme: str) -> None:
    rng = np.random.default_rng(1)
    for _ in range(200):
        idx = resample(WEIGHTS, scheme, rng)
        assert idx.shape == (len(WEIGHTS),)
        assert idx.min() >= 0 and idx.max() < len(WEIGHTS)
        assert (np.diff(idx) >= 0).all()
        assert not np.isin(idx, [6, 7]).any()


@pytest.mark.parametrize("scheme", SCHEMES)
def test_expected_counts_are_n_times_the_weights(scheme: str) -> None:
    rng = np.random.default_rng(2)
    n, reps = len(WEIGHTS), 3000
    total = np.zeros(n)
    for _ in range(reps):
        total += counts(resample(WEIGHTS, scheme, rng), n)
    mean = total / reps
    # multinomial count variance is N w (1 - w): the mean of reps has sd sqrt(N w (1-w) / reps).
    tolerance = 5 * np.sqrt(n * WEIGHTS * (1 - WEIGHTS) / reps) + 1e-12
    np.testing.assert_array_less(np.abs(mean - n * WEIGHTS), tolerance)


def test_systematic_and_residual_copy_each_particle_at_least_floor_n_w_times() -> None:
    rng = np.random.default_rng(3)
    n = len(WEIGHTS)
    floor, ceil = np.floor(n * WEIGHTS), np.ceil(n * WEIGHTS)
    for _ in range(300):
        sys_counts = counts(resample(WEIGHTS, "systematic", rng), n)
        assert (sys_counts >= floor).all() and (sys_counts <= ceil).all()
        res_counts = counts(resample(WEIGHTS, "residual", rng), n)
        assert (res_counts >= floor).all()


def test_multinomial_counts_vary_more_than_systematic() -> None:
    rng = np.random.default_rng(4)
    w = np.full(100, 0.01)
    sys_var = np.var([counts(resample(w, "systematic", rng), 100) for _ in range(100)])
    mul_var = np.var([counts(resample(w, "multinomial", rng), 100) for _ in range(100)])
    assert sys_var == 0.0  # equal weights: systematic copies every particle exactly once
    assert mul_var > 0.5  # binomial(100, 0.01) variance is 0.99


def test_the_draws_are_one_n_or_the_residual_count() -> None:
    w = WEIGHTS.tolist()
    assert weights("resample_draws", S="systematic", W=w, K=OUT)["K"] == 1
    assert weights("resample_draws", S="multinomial", W=w, K=OUT)["K"] == 8
    # floor(8 w) = 4, 2, 1, 0, 0, 0, 0, 0: 7 copies kept, 1 drawn
    assert weights("resample_draws", S="residual", W=w, K=OUT)["K"] == 1
    uniform = [0.1] * 10
    assert weights("resample_draws", S="residual", W=uniform, K=OUT)["K"] == 0
    found = weights("resample_indices", S="residual", W=uniform, U=[], I=OUT)
    assert found["I"] == list(range(10))


def test_systematic_positions_from_a_given_offset() -> None:
    found = weights("resample_indices", S="systematic", W=[0.5, 0.25, 0.25], U=[0.2], I=OUT)
    # positions 0.2/3, 1.2/3, 2.2/3 against the cumulative weights 0.5, 0.75, 1
    assert found["I"] == [0, 0, 1]
    # the last cumulative weight counts as 1: a position past a sum short of 1 takes the last
    found = weights("resample_indices", S="systematic", W=[0.3, 0.3, 0.3999999], U=[0.9999999],
                    I=OUT)
    assert found["I"] == [1, 2, 2]  # (positions 0.33, 0.67, 0.99999997)


def test_too_few_uniforms_and_an_unknown_scheme_are_errors() -> None:
    with pytest.raises(BadArgumentError, match="enough_uniforms"):
        weights("resample_indices", S="multinomial", W=[0.5, 0.5], U=[0.1], I=OUT)
    with pytest.raises(BadArgumentError, match="stratified"):
        weights("resample_draws", S="stratified", W=[0.5, 0.5], K=OUT)


def test_a_step_normalises_adds_the_likelihood_and_gives_the_ess() -> None:
    n = 4
    uniform = weights("weights_uniform", N=n, LW=OUT)["LW"]
    assert uniform == [-math.log(n)] * n
    step = [math.log(0.1), math.log(0.2), math.log(0.3), -math.inf]
    found = weights("weights_update", LW0=uniform, S=step, LW=OUT, Inc=OUT, ESS=OUT, Inf=OUT)
    # the weighted mean likelihood: (0.1 + 0.2 + 0.3 + 0) / 4
    assert found["Inc"] == pytest.approx(math.log(0.15))
    new = np.exp(found["LW"])
    np.testing.assert_allclose(new, [1 / 6, 2 / 6, 3 / 6, 0.0])
    assert found["ESS"] == pytest.approx(1 / np.dot(new, new))
    assert found["Inf"] == "false" or found["Inf"] is False


def test_nan_is_weight_zero_and_infinite_likelihoods_keep_only_those() -> None:
    uniform = weights("weights_uniform", N=3, LW=OUT)["LW"]
    found = weights("weights_update", LW0=uniform, S=[math.nan, 0.0, 0.0], LW=OUT, Inc=OUT,
                    ESS=OUT, Inf=OUT)
    np.testing.assert_allclose(np.exp(found["LW"]), [0.0, 0.5, 0.5])
    found = weights("weights_update", LW0=uniform, S=[math.inf, 0.0, math.inf], LW=OUT,
                    Inc=OUT, ESS=OUT, Inf=OUT)
    assert found["Inf"] in (True, "true")
    np.testing.assert_allclose(np.exp(found["LW"]), [0.5, 0.0, 0.5])
    assert found["ESS"] == pytest.approx(2.0)


def test_every_weight_zero_gives_increment_minus_infinity_and_keeps_the_weights() -> None:
    uniform = weights("weights_uniform", N=3, LW=OUT)["LW"]
    found = weights("weights_update", LW0=uniform, S=[-math.inf] * 3, LW=OUT, Inc=OUT,
                    ESS=OUT, Inf=OUT)
    assert found["Inc"] == -math.inf and found["LW"] == uniform and found["ESS"] == 0.0


def test_the_ess_of_uniform_and_one_hot_weights() -> None:
    n = 50
    uniform = weights("weights_uniform", N=n, LW=OUT)["LW"]
    assert weights("weights_ess", LW=uniform, E=OUT)["E"] == pytest.approx(n)
    one_hot = [-math.inf] * n
    one_hot[3] = 0.0
    assert weights("weights_ess", LW=one_hot, E=OUT)["E"] == pytest.approx(1.0)


def test_lists_of_other_lengths_are_an_error() -> None:
    with pytest.raises(EngineError, match="same_length"):
        weights("weights_update", LW0=[0.0], S=[0.0, 0.0], LW=OUT, Inc=OUT, ESS=OUT, Inf=OUT)


def test_prologs_pairwise_sum_is_numpys_sum() -> None:
    """The residuals are normalised by a pairwise sum (as numpy sums an array)."""
    rng = np.random.default_rng(11)
    for n in [*range(1, 140), 255, 256, 257, 1000, 1001, 4097]:
        values = rng.random(n) * 10.0 ** rng.integers(-12, 3, n)
        assert weights("numpy_sum", X=values.tolist(), S=OUT)["S"] == float(np.sum(values)), n
