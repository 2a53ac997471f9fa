"""The DDC particle filter driven from Python against the real engine.

Exact answers come from the models by hand (prolog/examples/filter/*.pl state them) or from a
Kalman filter computed here; tolerances are a few standard errors derived from the number of
particles and the effective sample sizes the filter reports.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bridge import Filter, FilterError, ZeroWeightWarning, terms

EXAMPLES = Path(__file__).resolve().parents[1] / "prolog" / "examples" / "filter"
WUMPUS = EXAMPLES / "wumpus.pl"
PIT_WORLD = EXAMPLES / "pit_world.pl"
RANDOM_WALK = EXAMPLES / "random_walk.pl"
OCCLUDER = EXAMPLES / "follow_the_occluder.pl"

#: Both engines answer the conformance tests (prolog/ddc/filter/ddc_filter.pl particle by particle,
#: prolog/ddc/batch/ddc_batch.pl clause by clause over batches of particles).
ENGINES = pytest.mark.parametrize("engine", ["per_particle", "batched"])

PIT_FRAMES = [("null", "false"), ("up", "true"), ("down", "false"), ("right", "true")]


def binomial_tolerance(p: float, effective: float, k: float = 5.0) -> float:
    return k * math.sqrt(max(p * (1 - p), 1e-4) / effective)


def pit_world_step(f: Filter, move: str, breeze: str) -> None:
    f.step([terms.observation("breeze", terms.Text(breeze))], actions=[terms.action(move)])


# --------------------------------------------------------------------------------------------
# conformance: the original system's filter examples


@ENGINES
def test_wumpus_maze_step_gives_p_wall_0_857143(engine: str) -> None:
    n = 1500
    with Filter(WUMPUS, particles=n, seed=11, engine=engine) as f:
        assert f.time == 0
        result = f.step(["observation(up) ~= wall", terms.observation("right", "free")],
                        actions=["action(null)"])
        assert f.time == 1 and result.time == 1
        exact = 0.4 * 0.9 / (0.4 * 0.9 + 0.6 * 0.1)
        p = f.probability("maze(0,1):t ~= wall")
        assert abs(p - exact) < binomial_tolerance(exact, 1 / (1 / result.ess + 1 / n))
        # the right-hand cell was read as free: P(wall) = 0.4*0.1/(0.4*0.1+0.6*0.9)
        exact_right = 0.04 / 0.58
        p_right = f.probability("maze(1,0):t ~= wall")
        assert abs(p_right - exact_right) < binomial_tolerance(exact_right, result.ess)
        dist = dict((v, p) for p, v in f.distribution("maze(0,1):t"))
        assert set(dist) == {"wall", "free"}
        assert dist["wall"] == pytest.approx(p) and sum(dist.values()) == pytest.approx(1.0)


@ENGINES
def test_pit_world_four_steps_joint_and_marginals(engine: str) -> None:
    n = 2000
    with Filter(PIT_WORLD, particles=n, seed=5, engine=engine) as f:
        smallest_ess = float(n)
        for move, breeze in PIT_FRAMES:
            pit_world_step(f, move, breeze)
            smallest_ess = min(smallest_ess, f.last_step.ess)
        assert f.time == 4 and f.zero_weight_events == 0
        # the 0/1 likelihoods leave at worst smallest_ess distinct ancestors, then resampling
        effective = 1 / (1 / smallest_ess + 1 / n)
        joint = {value: p for p, value in f.distribution(
            "(A,B,C)", "maze(0,2):t ~= A, maze(1,1):t ~= B, maze(2,0):t ~= C")}
        exact = {("pit", "pit", "pit"): 1 / 29, ("pit", "pit", "free"): 4 / 29,
                 ("pit", "free", "pit"): 4 / 29, ("free", "pit", "pit"): 4 / 29,
                 ("free", "pit", "free"): 16 / 29}
        assert set(joint) <= set(exact)  # the other combinations are impossible: weight 0
        for value, p in exact.items():
            assert abs(joint.get(value, 0.0) - p) < binomial_tolerance(p, effective), value
        for cell, p in [("(1,1)", 4 / 29), ("(2,0)", 20 / 29), ("(0,2)", 20 / 29)]:
            x, y = cell.strip("()").split(",")
            estimate = f.probability(f"maze({x},{y}):t ~= free")
            assert abs(estimate - p) < binomial_tolerance(p, effective), cell
        assert f.probability("maze(0,1):t ~= free") == pytest.approx(1.0)
        assert f.probability("position:t ~= (1,0)") == pytest.approx(1.0)


# --------------------------------------------------------------------------------------------
# a linear Gaussian model against the Kalman filter


def kalman(ys: list[float], m: float = 0.0, p: float = 1.0, q: float = 0.5, r: float = 1.0):
    out = []
    for y in ys:
        p = p + q
        gain = p / (p + r)
        m, p = m + gain * (y - m), (1 - gain) * p
        out.append((m, p))
    return out


@pytest.mark.parametrize(("threads", "engine"),
                         [(1, "per_particle"), (2, "per_particle"), (1, "batched")])
def test_random_walk_matches_the_kalman_filter_for_20_steps(threads: int, engine: str) -> None:
    rng = np.random.default_rng(2024)
    x, ys = rng.normal(0.0, 1.0), []
    for _ in range(20):
        x += rng.normal(0.0, math.sqrt(0.5))
        ys.append(float(x + rng.normal(0.0, 1.0)))
    n = 1000
    with Filter(RANDOM_WALK, particles=n, seed=3, threads=threads, engine=engine) as f:
        for step, (y, (m, p)) in enumerate(zip(ys, kalman(ys), strict=True), start=1):
            result = f.step([terms.observation("y", y)])
            mean, var = f.mean("x:t")
            # standard errors of a weighted sample of effective size ess, plus resampling noise
            effective = 1 / (1 / result.ess + 1 / n)
            assert abs(mean - m) < 6 * math.sqrt(p / effective), (step, mean, m)
            assert abs(var - p) < 6 * p * math.sqrt(2 / effective), (step, var, p)
        values, weights = f.samples("x:t")
        assert values.shape == (n,) and weights.shape == (n,)
        assert float(weights @ values) == pytest.approx(mean)
        assert f.log_likelihood < 0 and math.isfinite(f.log_likelihood)


# --------------------------------------------------------------------------------------------
# a theory of occlusion: the hidden ball follows the box


def occluder_frame(ball: tuple[float, float, float] | None, box: tuple[float, float, float]):
    obs = [terms.fact("observed", "box_1"), terms.observation(terms.fact("pos", "box_1"), box)]
    if ball is not None:
        obs += [terms.fact("observed", "ball_1"),
                terms.observation(terms.fact("pos", "ball_1"), ball)]
    return obs


@ENGINES
def test_hidden_ball_follows_the_box(engine: str) -> None:
    n = 400
    ball, box = (0.0, 0.0, 0.02), (0.05, 0.0, 0.12)
    with Filter(OCCLUDER, particles=n, seed=9, engine=engine) as f:
        for _ in range(3):
            f.step(occluder_frame(ball, box))
        assert f.probability("occluded_by(ball_1, _):t") == 0.0
        f.step(occluder_frame(None, box))  # the ball disappears under the box
        assert f.probability("occluded_by(ball_1, box_1):t") == pytest.approx(1.0)
        ball_at_hiding, _ = f.mean("pos(ball_1):t")
        box_at_hiding, _ = f.mean("pos(box_1):t")
        offsets_at_hiding, _ = f.samples(OFFSET, OFFSET_GOAL)
        for k in range(1, 7):  # the box slides 2 cm per step along x and 1 cm along y
            box = (0.05 + 0.02 * k, 0.01 * k, 0.12)
            f.step(occluder_frame(None, box))
        assert f.probability("occluded_by(ball_1, box_1):t") == pytest.approx(1.0)
        # every particle's ball kept the offset to its box that some particle had at hiding
        offsets_now, _ = f.samples(OFFSET, OFFSET_GOAL)
        gaps = np.abs(offsets_now[:, None, :] - offsets_at_hiding[None, :, :]).max(axis=2)
        assert gaps.min(axis=1).max() < 1e-9
        # so the ball's belief moved with the box (the box's filtered motion, up to the
        # re-weighting of the box's position at hiding by the later observations)
        ball_now, _ = f.mean("pos(ball_1):t")
        box_now, _ = f.mean("pos(box_1):t")
        box_moved = box_now - box_at_hiding
        assert box_moved[0] > 0.06 and box_moved[1] > 0.03
        np.testing.assert_allclose(ball_now - ball_at_hiding, box_moved, atol=0.025)
        # the box never came near enough to anything else: the ball stayed hidden under it
        assert f.probability("seen(ball_1):t ~= false") == pytest.approx(1.0)


OFFSET = "(DX,DY,DZ)"
OFFSET_GOAL = ("pos(ball_1):t ~= (X,Y,Z), pos(box_1):t ~= (A,B,C), "
               "DX is X - A, DY is Y - B, DZ is Z - C")


# --------------------------------------------------------------------------------------------
# determinism, zero-weight frames, bad input


def run_random_walk(seed: int, threads: int = 2,
                    engine: str = "per_particle") -> tuple[np.ndarray, np.ndarray, float]:
    with Filter(RANDOM_WALK, particles=300, seed=seed, threads=threads, engine=engine) as f:
        for y in [0.3, -0.2, 1.1, 0.7, 2.0]:
            f.step([f"observation(y) ~= {y}"])
        values, weights = f.samples("x:t")
        return values, weights, f.log_likelihood


@pytest.mark.parametrize("threads", [1, 2, 3])
def test_same_seed_same_particles_bit_for_bit(threads: int) -> None:
    a, b = run_random_walk(17, threads), run_random_walk(17, threads)
    c = run_random_walk(18, threads)
    assert a[0].tobytes() == b[0].tobytes()
    assert a[1].tobytes() == b[1].tobytes()
    assert a[2] == b[2]
    assert a[0].tobytes() != c[0].tobytes()
    # the groups draw from streams of their own: another thread count, other particles
    other = run_random_walk(17, threads % 3 + 1)
    assert a[0].tobytes() != other[0].tobytes()


def test_the_batched_engine_same_seed_same_particles_bit_for_bit() -> None:
    a, b = run_random_walk(17, 1, "batched"), run_random_walk(17, 1, "batched")
    c = run_random_walk(18, 1, "batched")
    assert a[0].tobytes() == b[0].tobytes() and a[1].tobytes() == b[1].tobytes()
    assert a[2] == b[2]
    assert a[0].tobytes() != c[0].tobytes()


@ENGINES
def test_a_value_none_is_not_a_missing_value(tmp_path: Path, engine: str) -> None:
    program = tmp_path / "none.pl"
    program.write_text("x:0 ~ uniform([none, some]) := true.\n"
                       "y:0 ~ val(1) := x:0 ~= some.\n")
    with Filter(program, particles=200, seed=5, engine=engine) as f:
        dist = dict((v, p) for p, v in f.distribution("x:t"))
        assert set(dist) == {"none", "some"} and sum(dist.values()) == pytest.approx(1.0)
        xs = f.values("X", "x:t ~= X")
        ys = f.values("Y", "y:t ~= Y")
        assert [y is None for y in ys] == [x == "none" for x in xs]


@ENGINES
def test_samples_are_float_rows_with_nan_where_undefined(tmp_path: Path, engine: str) -> None:
    program = tmp_path / "rows.pl"
    program.write_text("x:0 ~ uniform([none, some]) := true.\n"
                       "y:0 ~ val(1) := x:0 ~= some.\n"
                       "z:0 ~ val((1, 2.5, -3)) := x:0 ~= some.\n")
    with Filter(program, particles=50, seed=5, engine=engine) as f:
        undefined = np.array([x == "none" for x in f.values("X", "x:t ~= X")])
        assert 0 < undefined.sum() < 50
        y, weights = f.samples("y:t")
        assert y.shape == (50,) and weights.shape == (50,)
        np.testing.assert_array_equal(np.isnan(y), undefined)
        assert (y[~undefined] == 1.0).all()
        z, _ = f.samples("z:t")
        assert z.shape == (50, 3)
        np.testing.assert_array_equal(np.isnan(z).all(axis=1), undefined)
        assert (z[~undefined] == [1.0, 2.5, -3.0]).all()
        pairs, _ = f.samples("(A, B)", "z:t ~= (A, _, B)")   # a template over a goal
        assert pairs.shape == (50, 2) and (pairs[~undefined] == [1.0, -3.0]).all()
        names, _ = f.samples("x:t")                          # not numbers: the values as objects
        assert names.dtype == object and set(names) == {"none", "some"}


@ENGINES
def test_every_particle_weight_zero_keeps_the_pre_step_particles(engine: str) -> None:
    n = 200
    with Filter(PIT_WORLD, particles=n, seed=2, engine=engine) as f:
        pit_world_step(f, "null", "false")
        before = f.values("(A,B)", "maze(1,0):t ~= A, maze(0,1):t ~= B")
        loglik = f.log_likelihood
        with pytest.warns(ZeroWeightWarning, match="weight 0"):
            result = f.step(["observation(breeze) ~= maybe"], actions=["action(null)"])
        assert result.zero_weight and f.zero_weight_events == 1
        assert f.time == 1 and f.frames == 2
        assert f.values("(A,B)", "maze(1,0):t ~= A, maze(0,1):t ~= B") == before
        np.testing.assert_allclose(f.weights, np.full(n, 1 / n))
        assert f.log_likelihood == loglik
        for move, breeze in PIT_FRAMES[1:]:  # and it carries on as if the frame had not been
            pit_world_step(f, move, breeze)
        assert f.time == 4 and f.zero_weight_events == 1
        assert f.probability("maze(1,1):t ~= free") < 0.5


@ENGINES
def test_bad_observations_raise_and_leave_the_filter_usable(engine: str) -> None:
    with Filter(PIT_WORLD, particles=300, seed=4, engine=engine) as f:
        pit_world_step(f, "null", "false")
        held = f.values("V", "maze(2,0):t ~= V")
        with pytest.raises(FilterError, match=r"observation 1 .*[Ss]yntax"):
            f.step(["observation(breeze ~= true"], actions=["action(up)"])
        with pytest.raises(FilterError, match="not ground"):
            f.step(["observation(breeze) ~= X"], actions=["action(up)"])
        with pytest.raises(FilterError, match="step 2"):  # no clause for this observation
            f.step(["observation(smell) ~= true"], actions=["action(up)"])
        with pytest.raises(FilterError, match="query"):
            f.probability("maze(1,1):t ~=")
        assert f.time == 1 and f.frames == 1 and f.zero_weight_events == 0
        assert f.values("V", "maze(2,0):t ~= V") == held
        for move, breeze in PIT_FRAMES[1:]:
            pit_world_step(f, move, breeze)
        assert f.time == 4
        assert f.probability("maze(1,1):t ~= free") < 0.5


def test_auto_takes_the_batched_engine_for_programs_in_its_fragment(tmp_path: Path) -> None:
    too = Path(__file__).resolve().parents[1] / "prolog" / "too.pl"
    outside = tmp_path / "inline_draw.pl"   # sample/2 in a body: outside the fragment
    outside.write_text("x:0 ~ val(0.0).\n"
                       "x:t+1 ~ val(Y) := x:t ~= X, sample(gaussian(X, 1.0), Y).\n")
    for program in (RANDOM_WALK, too):
        with Filter(program, particles=20) as f:
            assert f.engine == "batched"
    with Filter(outside, particles=20) as f:
        assert f.engine == "per_particle"
        f.step([])
    with Filter(RANDOM_WALK, particles=20, engine="per_particle") as f:
        assert f.engine == "per_particle"
    with pytest.raises(FilterError, match=r"inline_draw\.pl:2: outside what the batched filter"):
        Filter(outside, particles=20, engine="batched")
    with pytest.raises(ValueError, match="engine"):
        Filter(RANDOM_WALK, engine="fast")  # type: ignore[arg-type]


def test_constructor_errors_are_clear(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="no_such.pl"):
        Filter(tmp_path / "no_such.pl")
    with pytest.raises(ValueError, match="resampling"):
        Filter(WUMPUS, resampling="stratified")  # type: ignore[arg-type]
    broken = tmp_path / "broken.pl"
    broken.write_text("x:0 ~ gaussian(0.0, 1.0).\nx:t+1 ~ gaussian(X, 0.5 := x:t ~= X.\n")
    with pytest.raises(FilterError, match="broken.pl"):
        Filter(broken, particles=10)
    for bad in (1.5, "10", True):  # int() would quietly take each of them
        with pytest.raises(TypeError, match="particles must be an integer"):
            Filter(WUMPUS, particles=bad)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="threads"):
        Filter(WUMPUS, threads=2.0)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="seed"):
        Filter(WUMPUS, seed="1")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="particles must be >= 1"):
        Filter(WUMPUS, particles=0)


@pytest.mark.parametrize("scheme", ["multinomial", "residual"])
def test_other_resampling_schemes_filter_the_wumpus_step(scheme: str) -> None:
    n = 1000
    with Filter(WUMPUS, particles=n, seed=1, resampling=scheme, resample_threshold=1.0) as f:
        result = f.step(["observation(up) ~= wall", "observation(right) ~= free"],
                        actions=["action(null)"])
        assert result.resampled and f.ess == pytest.approx(n)
        exact = 0.36 / 0.42
        p = f.probability("maze(0,1):t ~= wall")
        assert abs(p - exact) < binomial_tolerance(exact, 1 / (1 / result.ess + 1 / n))
