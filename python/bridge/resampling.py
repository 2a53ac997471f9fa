"""Resampling a weighted particle set, in numpy alone (no janus, no Prolog).

Three schemes pick N ancestor indices (0-based, ascending) for N normalised weights:

* ``systematic``: one uniform offset ``u``, positions ``(u + k) / N`` for k = 0..N-1: particle i
  is copied floor(N w_i) or ceil(N w_i) times (the default; the least added variance);
* ``multinomial``: N independent uniforms, sorted;
* ``residual``: floor(N w_i) copies of particle i, the R that remain drawn multinomially from the
  residuals N w_i - floor(N w_i) (R uniforms).

Each position p picks the first particle whose cumulative weight exceeds p, the last cumulative
weight counting as exactly 1 (so a position never falls past the end).

The rules are stated twice, here and in ``prolog/ddc/filter/ddc_belief.pl``
(``resample_indices/4``, for swipl users); ``tests/test_resampling_equal.py`` feeds both the same
uniforms and expects the same indices. The functions ``*_from_uniforms`` take the uniforms
explicitly; those taking a numpy ``Generator`` draw them (1, N and R numbers) and call them.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np
import numpy.typing as npt

Resampling = Literal["systematic", "multinomial", "residual"]
Uniforms = npt.ArrayLike

# --------------------------------------------------------------------------------------------
# From given uniforms


def _first(uniforms: Uniforms, k: int) -> np.ndarray:
    """The first ``k`` of ``uniforms`` (ValueError if there are fewer)."""
    values = np.asarray(uniforms, dtype=float).reshape(-1)
    if len(values) < k:
        raise ValueError(f"{k} uniforms needed, {len(values)} given")
    return values[:k]


def _walk(weights: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Per position, the first index whose cumulative weight exceeds it (last counts as 1)."""
    n = len(weights)
    cumulative = np.cumsum(weights)
    cumulative[-1] = 1.0
    return np.minimum(np.searchsorted(cumulative, positions, side="right"), n - 1)


def systematic_from_uniforms(weights: npt.ArrayLike, uniforms: Uniforms) -> np.ndarray:
    """Systematic resampling with the offset ``uniforms[0]`` (the others are not used)."""
    return _systematic(np.asarray(weights, dtype=float), float(_first(uniforms, 1)[0]))


def _systematic(w: np.ndarray, u: float) -> np.ndarray:
    n = len(w)
    return _walk(w, (u + np.arange(n)) / n)


def multinomial_from_uniforms(weights: npt.ArrayLike, uniforms: Uniforms) -> np.ndarray:
    """Multinomial resampling with the draws ``uniforms[:N]`` (sorted here)."""
    w = np.asarray(weights, dtype=float)
    return _walk(w, np.sort(_first(uniforms, len(w))))


def _residual_copies(w: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """(N w, floor(N w) as integers, R = N - sum of the floors)."""
    n = len(w)
    scaled = n * w
    copies = np.floor(scaled).astype(np.int64)
    return scaled, copies, n - int(copies.sum())


def residual_from_uniforms(weights: npt.ArrayLike, uniforms: Uniforms) -> np.ndarray:
    """Residual resampling; the R draws are ``uniforms[:R]`` (at most N are needed).

    The residuals are normalised by their numpy sum (pairwise summation, which
    ``prolog/ddc/filter/ddc_belief.pl`` reproduces)."""
    w = np.asarray(weights, dtype=float)
    scaled, copies, remaining = _residual_copies(w)
    return _residual(scaled, copies, _first(uniforms, remaining))


def _residual(scaled: np.ndarray, copies: np.ndarray, draws: np.ndarray) -> np.ndarray:
    """floor copies plus ``len(draws)`` (= R) picked from the residuals."""
    n = len(scaled)
    deterministic = np.repeat(np.arange(n), copies)
    if len(draws) == 0:
        return deterministic
    residual = scaled - copies
    extra = _walk(residual / residual.sum(), np.sort(draws))
    return np.sort(np.concatenate([deterministic, extra]))


FROM_UNIFORMS: dict[str, Callable[[npt.ArrayLike, Uniforms], np.ndarray]] = {
    "systematic": systematic_from_uniforms,
    "multinomial": multinomial_from_uniforms,
    "residual": residual_from_uniforms,
}


def _check_scheme(scheme: str) -> None:
    if scheme not in FROM_UNIFORMS:
        raise ValueError(
            f"unknown resampling scheme {scheme!r}; use one of {sorted(FROM_UNIFORMS)}"
        )


def indices_from_uniforms(
    weights: npt.ArrayLike, scheme: Resampling, uniforms: Uniforms
) -> np.ndarray:
    """N ancestor indices (int64, 0-based) for normalised ``weights`` under ``scheme``, from
    the given uniform numbers in [0, 1): the first 1 (systematic), N (multinomial) or R
    (residual) are used; N of them always suffice (ValueError if too few)."""
    _check_scheme(scheme)
    return FROM_UNIFORMS[scheme](weights, uniforms).astype(np.int64)


# --------------------------------------------------------------------------------------------
# Drawing the uniforms from a numpy Generator


def systematic_indices(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """One uniform offset, stride 1/N: particle i is copied floor(N w_i) or ceil(N w_i) times."""
    return _systematic(np.asarray(weights, dtype=float), rng.random())


def multinomial_indices(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """N independent draws from the weights (sorted, so copies sit together)."""
    return multinomial_from_uniforms(weights, rng.random(len(weights)))


def residual_indices(weights: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """floor(N w_i) copies of each particle, the remaining R drawn multinomially from the rest
    (R uniforms drawn, none when R is 0)."""
    scaled, copies, remaining = _residual_copies(np.asarray(weights, dtype=float))
    return _residual(scaled, copies, rng.random(remaining) if remaining else np.empty(0))


RESAMPLERS: dict[str, Callable[[np.ndarray, np.random.Generator], np.ndarray]] = {
    "systematic": systematic_indices,
    "multinomial": multinomial_indices,
    "residual": residual_indices,
}


def resample_indices(
    weights: np.ndarray, scheme: Resampling, rng: np.random.Generator
) -> np.ndarray:
    """N ancestor indices (int64, 0-based) for normalised ``weights`` under ``scheme``, the
    uniforms drawn from ``rng`` (1, N or R numbers)."""
    _check_scheme(scheme)
    return RESAMPLERS[scheme](np.asarray(weights, dtype=float), rng).astype(np.int64)


def effective_sample_size(log_weights: np.ndarray) -> float:
    """1 / sum(w_i^2) for normalised log weights."""
    w = np.exp(log_weights)
    return float(1.0 / np.dot(w, w))
