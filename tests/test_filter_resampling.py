"""Resampling schemes and weight arithmetic of the filter bridge (bridge.resampling: pure numpy,
no engine)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bridge.resampling import (
    effective_sample_size,
    multinomial_indices,
    resample_indices,
    residual_indices,
    systematic_indices,
)

WEIGHTS = np.array([0.5, 0.25, 0.125, 0.0625, 0.0375, 0.025, 0.0, 0.0])  # sums to 1


def counts(indices: np.ndarray, n: int) -> np.ndarray:
    return np.bincount(indices, minlength=n)


@pytest.mark.parametrize("scheme", ["systematic", "multinomial", "residual"])
def test_every_scheme_returns_n_valid_indices_and_never_picks_zero_weight(scheme: str) -> None:
    rng = np.random.default_rng(1)
    for _ in range(200):
        idx = resample_indices(WEIGHTS, scheme, rng)
        assert idx.shape == (len(WEIGHTS),) and idx.dtype == np.int64
        assert idx.min() >= 0 and idx.max() < len(WEIGHTS)
        assert not np.isin(idx, [6, 7]).any()


@pytest.mark.parametrize("scheme", ["systematic", "multinomial", "residual"])
def test_expected_counts_are_n_times_the_weights(scheme: str) -> None:
    rng = np.random.default_rng(2)
    n, reps = len(WEIGHTS), 20000
    total = np.zeros(n)
    for _ in range(reps):
        total += counts(resample_indices(WEIGHTS, scheme, rng), n)
    mean = total / reps
    # multinomial count variance is N w (1 - w): the mean of reps has sd sqrt(N w (1-w) / reps).
    tolerance = 5 * np.sqrt(n * WEIGHTS * (1 - WEIGHTS) / reps) + 1e-12
    np.testing.assert_array_less(np.abs(mean - n * WEIGHTS), tolerance)


def test_systematic_and_residual_copy_each_particle_at_least_floor_n_w_times() -> None:
    rng = np.random.default_rng(3)
    n = len(WEIGHTS)
    floor, ceil = np.floor(n * WEIGHTS), np.ceil(n * WEIGHTS)
    for _ in range(500):
        sys_counts = counts(systematic_indices(WEIGHTS, rng), n)
        assert (sys_counts >= floor).all() and (sys_counts <= ceil).all()
        res_counts = counts(residual_indices(WEIGHTS, rng), n)
        assert (res_counts >= floor).all()


def test_multinomial_counts_vary_more_than_systematic() -> None:
    rng = np.random.default_rng(4)
    w = np.full(100, 0.01)
    sys_var = np.var([counts(systematic_indices(w, rng), 100) for _ in range(200)])
    mul_var = np.var([counts(multinomial_indices(w, rng), 100) for _ in range(200)])
    assert sys_var == 0.0  # equal weights: systematic copies every particle exactly once
    assert mul_var > 0.5  # binomial(100, 0.01) variance is 0.99


def test_uniform_weights_residual_is_identity() -> None:
    w = np.full(10, 0.1)
    assert residual_indices(w, np.random.default_rng(0)).tolist() == list(range(10))


def test_unknown_scheme_is_rejected() -> None:
    with pytest.raises(ValueError, match="unknown resampling"):
        resample_indices(WEIGHTS, "stratified", np.random.default_rng(0))  # type: ignore[arg-type]


def test_effective_sample_size() -> None:
    n = 50
    assert effective_sample_size(np.full(n, -math.log(n))) == pytest.approx(n)
    one_hot = np.full(n, -np.inf)
    one_hot[3] = 0.0
    assert effective_sample_size(one_hot) == pytest.approx(1.0)
