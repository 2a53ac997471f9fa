"""bridge.Filter's preserving resampling (``strata``): each stratum of the particles is
resampled on its own and keeps its mass with at least ``keep`` particles.

The program: a hidden coin ``h`` (a or b, even odds) that never changes; each frame's
observation ``o`` is x with probability 0.99 under a and 1e-4 under b. After one x, b holds
about 1e-4 of the weight, less than one of 200 particles: plain resampling drops it, and the
ys that follow (each 100 times likelier under b) can no longer bring it back. Resampled by the
coin's value, b keeps its particles and its weight, and three ys make it nearly certain, as
the exact posterior says.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bridge import Filter

COIN = """\
h:0 ~ finite([0.5:a, 0.5:b]) := true.
h:t+1 ~ val(H) := h:t ~= H.
observation(o):t+1 ~ finite([0.99:x, 0.01:y]) := h:t+1 ~= a.
observation(o):t+1 ~ finite([0.0001:x, 0.9999:y]) := h:t+1 ~= b.
"""
N = 200
LIKELIHOOD = {"a": {"x": 0.99, "y": 0.01}, "b": {"x": 1e-4, "y": 0.9999}}


def exact_b(seen: list[str], prior: float = 0.5) -> float:
    """P(h = b | seen) from P(h = b) = prior."""
    a = (1 - prior) * math.prod(LIKELIHOOD["a"][o] for o in seen)
    b = prior * math.prod(LIKELIHOOD["b"][o] for o in seen)
    return b / (a + b)


@pytest.fixture
def coin(tmp_path: Path) -> Path:
    path = tmp_path / "coin.pl"
    path.write_text(COIN)
    return path


def run(coin: Path, seen: list[str], preserve: bool,
        engine: str = "auto") -> tuple[float, list[float]]:
    """The share of b among the initial particles, and P(h = b) after each observation."""
    out = []
    with Filter(coin, particles=N, seed=11, resample_threshold=0.9, engine=engine) as f:
        prior = f.probability("h:t ~= b")
        for o in seen:
            strata = f.holds("h:t ~= b").astype(np.int64) if preserve else None
            f.step([f"observation(o) ~= {o}"], strata=strata, keep=5)
            out.append(f.probability("h:t ~= b"))
    return prior, out


@pytest.mark.parametrize("engine", ["per_particle", "batched"])
def test_a_stratum_of_small_weight_keeps_its_mass_and_comes_back(coin: Path,
                                                                 engine: str) -> None:
    seen = ["x", "y", "y", "y"]
    prior, kept = run(coin, seen, preserve=True, engine=engine)
    assert 0.3 < prior < 0.7
    # its mass is the exact posterior's from the particles' prior after each step (only the
    # coin's value weighs, and a resampling keeps each value's mass)
    for k, p in enumerate(kept):
        assert p == pytest.approx(exact_b(seen[:k + 1], prior), rel=1e-6)
    assert kept[0] < 2e-4 and kept[-1] > 0.98
    _, plain = run(coin, seen, preserve=False, engine=engine)
    assert plain[0] == 0.0 and plain[-1] == 0.0  # dropped at the first resampling


def test_after_a_preserving_resampling_the_weights_are_the_strata_masses(coin: Path) -> None:
    with Filter(coin, particles=N, seed=3) as f:
        f.step(["observation(o) ~= y"])   # b: 0.99, a: 0.01 -- ESS falls, resampled
        prior = f.probability("h:t ~= b")
        strata = f.holds("h:t ~= b").astype(np.int64)
        result = f.step(["observation(o) ~= x"], strata=strata, keep=7)
        assert result.resampled
        b = f.holds("h:t ~= b").astype(bool)
        assert b.sum() >= 7 and (~b).sum() >= 7
        assert f.weights[b].sum() == pytest.approx(exact_b(["x"], prior), rel=1e-6)
        # the weights within a stratum are equal, and the ESS is that of the weights
        assert np.ptp(f.weights[b]) < 1e-12 and np.ptp(f.weights[~b]) < 1e-12
        assert f.ess == pytest.approx(1.0 / np.sum(f.weights ** 2))


@pytest.mark.parametrize(("strata", "keep", "cause"), [
    (np.zeros(N - 1, dtype=np.int64), 1, "one per particle"),
    (np.zeros(N, dtype=float), 1, "one per particle"),
    (np.zeros(N, dtype=np.int64), 0, "positive integer"),
])
def test_bad_strata_are_refused_before_the_step(coin: Path, strata: np.ndarray, keep: int,
                                                cause: str) -> None:
    with Filter(coin, particles=N, seed=3) as f:
        with pytest.raises(ValueError, match=cause):
            f.step(["observation(o) ~= x"], strata=strata, keep=keep)
        assert f.frames == 0
