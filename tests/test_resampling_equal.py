"""The resampling rules are stated twice, in python/bridge/resampling.py (bridge.Filter's) and in
prolog/ddc/filter/ddc_belief.pl's resample_indices/4 (the swipl belief's): given the same weights
and the same uniforms, both pick the same ancestors, for every scheme, bit for bit."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import janus_swi as janus
import numpy as np
import pytest

from bridge import prolog
from bridge.resampling import (
    RESAMPLERS,
    indices_from_uniforms,
    resample_indices,
)

SCHEMES = sorted(RESAMPLERS)
RESAMPLING_PY = Path(__file__).resolve().parents[1] / "python" / "bridge" / "resampling.py"


@pytest.fixture(scope="module", autouse=True)
def belief_module() -> None:
    prolog.ensure_loaded(prolog.PROLOG_DIR / "ddc/filter/ddc_belief.pl")


def prolog_indices(scheme: str, weights: np.ndarray, uniforms: np.ndarray) -> list[int]:
    result = janus.query_once(
        "ddc_belief:resample_indices(S, W, U, I)",
        {"S": scheme, "W": [float(w) for w in weights], "U": [float(u) for u in uniforms]},
    )
    assert result["truth"], f"resample_indices/4 failed for {scheme}"
    return list(result["I"])


def weight_vectors(rng: np.random.Generator) -> list[tuple[str, np.ndarray]]:
    """Normalised weight vectors of many shapes and sizes."""
    out: list[tuple[str, np.ndarray]] = []
    for n in (1, 2, 3, 7, 8, 9, 16, 17, 100, 129, 257, 1000):
        raw = {
            "uniform random": rng.random(n),
            "log-normal (a few dominate)": np.exp(rng.normal(0.0, 12.0, n)),
            "one has all": np.eye(n)[rng.integers(n)],
            "ties": np.ones(n),
            "ties in small integers": rng.integers(1, 4, n).astype(float),
            "tiny beside one large": np.where(np.arange(n) == n // 2, 1.0,
                                              1e-300 * rng.random(n)),
            "zeros between": rng.random(n) * (rng.random(n) < 0.3),
        }
        for shape, w in raw.items():
            if w.sum() > 0:
                out.append((f"{shape}, N={n}", w / w.sum()))
    return out


@pytest.mark.parametrize("scheme", SCHEMES)
def test_python_and_prolog_pick_the_same_ancestors_from_the_same_uniforms(scheme: str) -> None:
    rng = np.random.default_rng(20261203)
    compared = 0
    for label, weights in weight_vectors(rng):
        n = len(weights)
        uniform_sets = [rng.random(n), rng.random(n),
                        np.zeros(n), np.full(n, 1.0 - 2.0**-53)]  # the ends of [0, 1)
        for uniforms in uniform_sets:
            python = indices_from_uniforms(weights, scheme, uniforms).tolist()  # type: ignore[arg-type]
            assert prolog_indices(scheme, weights, uniforms) == python, (label, uniforms[:3])
            compared += 1
    assert compared > 300


def test_residual_normalises_by_numpys_sum() -> None:
    """Where numpy's pairwise sum of the residuals differs from a left-to-right sum, a uniform
    on the cumulative residual weight that differs picks different ancestors: both sides
    take numpy's."""
    rng = np.random.default_rng(5)
    checked = 0
    while checked < 20:
        n = int(rng.integers(9, 300))
        weights = rng.random(n)
        weights /= weights.sum()
        scaled = n * weights
        residual = scaled - np.floor(scaled)
        left_to_right = 0.0
        for r in residual:
            left_to_right += r
        pairwise = np.cumsum(residual / residual.sum())
        sequential = np.cumsum(residual / left_to_right)
        differ = np.nonzero(pairwise[:-1] != sequential[:-1])[0]
        if not len(differ):
            continue
        at = differ[0]
        uniforms = np.full(n, min(pairwise[at], sequential[at]))
        python = indices_from_uniforms(weights, "residual", uniforms).tolist()
        assert prolog_indices("residual", weights, uniforms) == python
        checked += 1


def test_prologs_numpy_sum_is_numpys_sum() -> None:
    rng = np.random.default_rng(11)
    for n in [*range(1, 140), 255, 256, 257, 1000, 1001, 4097]:
        values = rng.random(n) * 10.0 ** rng.integers(-12, 3, n)
        result = janus.query_once("ddc_belief:numpy_sum(X, S)", {"X": values.tolist()})
        assert result["S"] == float(np.sum(values)), n


@pytest.mark.parametrize("scheme", SCHEMES)
def test_drawing_from_a_generator_is_giving_its_draws_as_uniforms(scheme: str) -> None:
    """The Generator entry point draws 1 (systematic), N (multinomial) or R (residual) numbers
    and picks as the uniforms entry point does with them."""
    for seed in range(30):
        draw = np.random.default_rng(seed)
        weights = draw.random(50) ** 4
        weights /= weights.sum()
        picked = resample_indices(weights, scheme, np.random.default_rng(seed + 1000))  # type: ignore[arg-type]
        replay = np.random.default_rng(seed + 1000)
        if scheme == "systematic":
            uniforms = np.array([replay.random()])
        elif scheme == "multinomial":
            uniforms = replay.random(50)
        else:
            remaining = 50 - int(np.floor(50 * weights).sum())
            uniforms = replay.random(remaining)
        assert picked.tolist() == indices_from_uniforms(weights, scheme, uniforms).tolist()  # type: ignore[arg-type]


def test_too_few_uniforms_is_an_error_in_prolog() -> None:
    with pytest.raises(janus.PrologError, match="enough_uniforms"):
        janus.query_once("ddc_belief:resample_indices(multinomial, [0.5, 0.5], [0.1], _)")


def test_the_resampling_module_imports_no_janus() -> None:
    """bridge/resampling.py loaded on its own (not through the bridge package, whose
    __init__ starts Prolog) leaves janus_swi unimported."""
    code = (
        "import importlib.util, sys\n"
        f"spec = importlib.util.spec_from_file_location('resampling', {str(RESAMPLING_PY)!r})\n"
        "module = importlib.util.module_from_spec(spec)\n"
        "spec.loader.exec_module(module)\n"
        "assert module.indices_from_uniforms([0.5, 0.5], 'systematic', [0.2]).tolist() == [0, 1]\n"
        "print('janus_swi' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_too_few_uniforms_is_an_error_in_python() -> None:
    with pytest.raises(ValueError, match="2 uniforms needed, 1 given"):
        indices_from_uniforms([0.5, 0.5], "multinomial", [0.1])
