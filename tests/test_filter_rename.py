"""bridge.Filter's rename, reweight and particle_data against the real engine.

The program: two mugs and a ball hidden under one of them (mug_1 with probability 0.8); a mug
moves where an action says; the ball keeps its mug and is where its mug is. Renaming mug_1 and
mug_2 in a particle swaps everything it holds about them.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bridge import Filter, FilterError, ZeroWeightWarning, terms

ENGINES = pytest.mark.parametrize("engine", ["per_particle", "batched"])
PIT_WORLD = Path(__file__).resolve().parents[1] / "prolog" / "examples" / "filter" / "pit_world.pl"

MUGS = """\
:- dynamic(move/2).
mug(mug_1) := true.
mug(mug_2) := true.
ball(ball_1) := true.
start(mug_1, 0.0) := true.
start(mug_2, 1.0) := true.
pos(M):0 ~ val(X) := mug(M), start(M, X).
hidden_under(B):0 ~ finite([0.8:mug_1, 0.2:mug_2]) := ball(B).
pos(B):0 ~ val(X) := ball(B), hidden_under(B):0 ~= M, pos(M):0 ~= X.
under(B, M):t := hidden_under(B):t ~= M.
pos(M):t+1 ~ val(X) := mug(M), move(M, X).
pos(M):t+1 ~ val(X) := mug(M), \\+ move(M, _), pos(M):t ~= X.
hidden_under(B):t+1 ~ val(M) := ball(B), under(B, M):t.
pos(B):t+1 ~ val(X) := ball(B), hidden_under(B):t+1 ~= M, pos(M):t+1 ~= X.
observation(pos(M)):t+1 ~ gaussian(X, 0.01) := pos(M):t+1 ~= X.
"""

SWAP = {"mug_1": "mug_2", "mug_2": "mug_1"}
OTHER = {"mug_1": "mug_2", "mug_2": "mug_1"}
STATE = ("(H,P,M1,M2)",
         "hidden_under(ball_1):t ~= H, pos(ball_1):t ~= P, pos(mug_1):t ~= M1, pos(mug_2):t ~= M2")


@pytest.fixture
def mugs(tmp_path: Path) -> Path:
    path = tmp_path / "mugs.pl"
    path.write_text(MUGS)
    return path


def swapped(state: tuple[str, float, float, float]) -> tuple[str, float, float, float]:
    hidden, ball, mug_1, mug_2 = state
    return OTHER[hidden], ball, mug_2, mug_1


@ENGINES
@pytest.mark.parametrize("particles", [[0, 2, 2, 5], np.array([0, 2, 5]),
                                       np.isin(np.arange(8), [0, 2, 5])])
def test_rename_swaps_the_values_of_exactly_the_particles_given(
        mugs: Path, engine: str, particles: object) -> None:
    with Filter(mugs, particles=8, seed=3, engine=engine, threads=2) as f:
        f.step()
        before = f.values(*STATE)
        f.rename(SWAP, particles)
        after = f.values(*STATE)
        for i, (old, new) in enumerate(zip(before, after, strict=True)):
            assert new == (swapped(old) if i in (0, 2, 5) else old)
        # and the next step goes on from the renamed worlds: the ball follows its mug's new name
        f.step(actions=[terms.fact("move", "mug_1", 5.0)])
        for hidden, ball, mug_1, mug_2 in f.values(*STATE):
            assert mug_1 == 5.0 and ball == (mug_1 if hidden == "mug_1" else mug_2)


@ENGINES
def test_rename_of_all_particles_and_identity_pairs(mugs: Path, engine: str) -> None:
    with Filter(mugs, particles=6, seed=4, engine=engine) as f:
        before = f.values(*STATE)
        f.rename({"mug_1": "mug_1", "mug_2": "mug_2"})
        f.rename({})
        f.rename(SWAP, [])
        assert f.values(*STATE) == before
        f.rename(SWAP)
        assert f.values(*STATE) == [swapped(s) for s in before]


@pytest.mark.parametrize(("mapping", "particles", "cause"), [
    ({"mug_1": "mug_2"}, None, "not a permutation"),
    ({"mug_1": "mug_2", "mug_2": "mug_2"}, None, "not a permutation"),
    ({"mug_1": 2, "mug_2": "mug_1"}, None, "names are strings"),
    ([("mug_1", "mug_2")], None, "must map old names"),
    (SWAP, [6], "index 6 is outside 0..5"),
    (SWAP, [-1], "index -1 is outside"),
    (SWAP, [0.5], "integer indices"),
    (SWAP, [[0, 1]], "integer indices"),
    (SWAP, np.ones(5, dtype=bool), r"shape \(6,\)"),
])
def test_rename_errors_name_the_cause_and_change_nothing(
        mugs: Path, mapping: object, particles: object, cause: str) -> None:
    with Filter(mugs, particles=6, seed=5) as f:
        before = f.values(*STATE)
        with pytest.raises(FilterError, match=cause):
            f.rename(mapping, particles)  # type: ignore[arg-type]
        assert f.values(*STATE) == before


def test_reweight_multiplies_the_weights_and_resampling_waits_for_the_step(mugs: Path) -> None:
    n = 10
    with Filter(mugs, particles=n, seed=6, resample_threshold=0.5) as f:
        factors = np.full(n, -math.inf)
        factors[3] = 0.0
        factors[7] = math.log(3.0)
        before = f.values(*STATE)
        f.reweight(factors)
        expected = np.zeros(n)
        expected[3], expected[7] = 0.25, 0.75
        np.testing.assert_allclose(f.weights, expected)
        assert f.ess == pytest.approx(1 / (0.25**2 + 0.75**2))
        assert f.log_likelihood == pytest.approx(math.log(4.0 / n))
        assert f.values(*STATE) == before          # no resampling yet
        result = f.step()
        assert result.resampled and result.ess == pytest.approx(1.6)
        assert set(f.values(*STATE)) <= {before[3], before[7]}
        np.testing.assert_allclose(f.weights, np.full(n, 1 / n))


@pytest.mark.parametrize(("factors", "cause"), [
    (np.zeros(5), r"shape \(6,\)"),
    (np.array([0, 0, 0, 0, 0, math.nan]), "log factor 5 is nan"),
    (np.array([0, math.inf, 0, 0, 0, 0]), "log factor 1 is inf"),
    (np.full(6, -math.inf), "every log factor is -inf"),
    (["a"] * 6, "must be numbers"),
])
def test_reweight_errors_change_nothing(mugs: Path, factors: object, cause: str) -> None:
    with Filter(mugs, particles=6, seed=7) as f:
        weights = f.weights
        with pytest.raises(FilterError, match=cause):
            f.reweight(factors)  # type: ignore[arg-type]
        np.testing.assert_array_equal(f.weights, weights)
        assert f.log_likelihood == 0.0


def test_reweight_that_leaves_no_weight_is_refused(mugs: Path) -> None:
    with Filter(mugs, particles=4, seed=8) as f:
        f.reweight(np.array([0.0, -math.inf, -math.inf, -math.inf]))
        with pytest.raises(FilterError, match="weight 0 to every particle"):
            f.reweight(np.array([-math.inf, 0.0, 0.0, 0.0]))
        np.testing.assert_array_equal(f.weights, [1.0, 0.0, 0.0, 0.0])


@ENGINES
def test_particle_data_follows_the_particles_through_a_resampling(mugs: Path, engine: str) -> None:
    n = 200
    with Filter(mugs, particles=n, seed=9, engine=engine, resample_threshold=1.0) as f:
        renamed = np.arange(n) % 3 == 0
        f.rename(SWAP, renamed)
        state = ("(H,M1)", "hidden_under(ball_1):t ~= H, pos(mug_1):t ~= M1")
        held = np.array(f.values(*state), dtype=object)
        f.particle_data["hidden"] = held[:, 0].astype(str)
        f.particle_data["mug_1_at"] = np.where(renamed, 1.0, 0.0)
        f.particle_data["origin"] = np.stack([np.arange(n), np.arange(n) * 2], axis=1)
        np.testing.assert_array_equal(held[:, 1].astype(float), f.particle_data["mug_1_at"])
        f.reweight(np.where(held[:, 0] == "mug_2", 0.0, -1.0))   # favour balls under mug_2
        result = f.step(actions=[terms.fact("move", "mug_2", 3.0)])
        assert result.resampled
        origin = f.particle_data["origin"]
        assert origin.shape == (n, 2) and (origin[:, 1] == 2 * origin[:, 0]).all()
        assert len(set(origin[:, 0].tolist())) < n        # some particles were copied
        now = np.array(f.values(*state), dtype=object)
        np.testing.assert_array_equal(now[:, 0].astype(str), f.particle_data["hidden"])
        np.testing.assert_array_equal(now[:, 1].astype(float), f.particle_data["mug_1_at"])
        np.testing.assert_array_equal(f.particle_data["hidden"], held[origin[:, 0], 0].astype(str))
        assert len(set(map(tuple, now.tolist()))) == 4    # every kind of particle is there


def test_particle_data_checks_shapes_and_names(mugs: Path) -> None:
    with Filter(mugs, particles=5, seed=10) as f:
        with pytest.raises(ValueError, match="the 5 particles, got shape \\(4,\\)"):
            f.particle_data["x"] = np.zeros(4)
        with pytest.raises(ValueError, match="got shape \\(\\)"):
            f.particle_data["x"] = 1.0
        with pytest.raises(TypeError, match="names are strings"):
            f.particle_data[3] = np.zeros(5)  # type: ignore[index]
        f.particle_data["x"] = [1, 2, 3, 4, 5]
        assert list(f.particle_data) == ["x"] and f.particle_data["x"].dtype.kind == "i"
        del f.particle_data["x"]
        assert len(f.particle_data) == 0


def test_a_step_undone_for_zero_weight_leaves_particle_data_as_it_was() -> None:
    with Filter(PIT_WORLD, particles=50, seed=2, resample_threshold=1.0) as f:
        f.particle_data["row"] = np.arange(50)
        with pytest.warns(ZeroWeightWarning):
            f.step(["observation(breeze) ~= maybe"], actions=["action(null)"])
        np.testing.assert_array_equal(f.particle_data["row"], np.arange(50))
