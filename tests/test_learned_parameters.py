"""The motion and carrying parameters of the learned theories: each estimator recovers what
it should from samples of a known model, and the shipped learned theories hold every parameter
they read as a learned fact (no hand-written one included), within ranges derived from the
simulator's settings."""

from __future__ import annotations

import re

import numpy as np
import pytest

from probanchor.learning.learned_theory import TheoryError, learn_theory
from probanchor.learning.motion_grip import grip, reach, rise, signed_gate, threshold
from probanchor.learning.motion_keep import ar1
from probanchor.learning.motion_parameters import DESCRIPTIONS, fit, parameter_clauses
from probanchor.learning.motion_samples import MotionSamples, samples_path
from probanchor.learning.motion_variances import STILL, isotropic_variance, lost_var, obs_var
from probanchor.loop.theories import THEORIES
from probanchor.tabletop.scenario import CameraSpec, NoiseSpec, Scenario

# ------------------------------------------------------------------ the estimators


def test_the_isotropic_variance_is_the_maximum_likelihood_one() -> None:
    rng = np.random.default_rng(0)
    x = rng.normal(0.0, 0.02, size=(20000, 3))
    # the standard error of a variance from n normal values is V sqrt(2 / n)
    assert isotropic_variance(x) == pytest.approx(0.0004, rel=4 * np.sqrt(2 / x.size))


def test_obs_var_is_half_the_variance_of_a_still_object_s_perceived_steps() -> None:
    rng = np.random.default_rng(1)
    noise = rng.normal(0.0, 0.003, size=(20001, 3))
    steps = np.diff(noise, axis=0)
    rows = [[*d, "ball", [0.0, 0.0, 0.0]] for d in steps]
    rows += [[0.5, 0.5, 0.5, "ball", [0.01, 0.0, 0.0]]]        # it moved: not counted
    v, n = obs_var(rows)
    assert n == len(steps)
    assert v == pytest.approx(0.003 ** 2, rel=0.05)
    assert STILL < 0.01


def test_lost_var_is_the_variance_of_a_move_between_two_places() -> None:
    rng = np.random.default_rng(3)
    places = rng.uniform([-0.5, -0.3], [0.5, 0.3], size=(20000, 2))   # a 1 m x 0.6 m table
    v, n = lost_var(places)
    moves = places[rng.permutation(len(places))] - places
    assert n == len(places)
    assert v == pytest.approx(float(np.mean(moves[:, 0] ** 2)), rel=0.05)   # the long side
    assert v == pytest.approx(2 * 1.0 ** 2 / 12, rel=0.05)
    with pytest.raises(ValueError, match="fewer than two"):
        lost_var([[0.0, 0.0]])


def test_ar1_recovers_the_kept_fraction_and_the_jitter() -> None:
    rng = np.random.default_rng(2)
    k, sd = 0.9, 0.002
    x = np.zeros((5000, 2))
    x[0] = [0.03, -0.02]
    for t in range(1, len(x)):
        x[t] = k * x[t - 1] + rng.normal(0.0, sd, 2)
    rows = [[*x[t], *x[t + 1]] for t in range(len(x) - 1)]
    k_hat, v_hat, n = ar1(rows)
    assert n == len(rows)
    assert k_hat == pytest.approx(k, abs=0.02)
    assert v_hat == pytest.approx(sd ** 2, rel=0.06)
    with pytest.raises(ValueError, match="nothing to fit"):
        ar1([[0.0, 0.0, 0.0, 0.0]])


def test_a_gate_and_a_threshold_are_quantiles_with_the_margin() -> None:
    xs = np.linspace(0.0, 1.0, 101)
    assert threshold(xs) == pytest.approx(0.1 / 2)
    low, high = signed_gate(xs)
    assert (low, high) == (pytest.approx(0.5 - 2 * 0.4), pytest.approx(0.5 + 2 * 0.4))
    assert reach(np.array([0.01, 0.02, 0.05])) == pytest.approx(2 * 0.05)  # every grasp within
    assert reach(np.array([0.01, 0.012, 0.014, 0.016, 0.02, 0.25])) == pytest.approx(2 * 0.02)


def test_the_grip_may_be_below_the_object_by_the_gate_or_not_at_all() -> None:
    """Grips that close 1-4 cm above what they take: the grip may not be below it (0, not a
    clearance above: a hand putting an object down comes within a centimetre of its centre);
    grips that close as low as 2 cm below it: down to the gate's lower end."""
    above = [[0.01, 0.09, 0.01 + 0.001 * i] for i in range(31)]
    assert grip(above, [0.02])["occluder_rise"][0] == 0.0
    below = [[0.01, 0.09, -0.02 + 0.002 * i] for i in range(31)]
    low = grip(below, [0.02])["occluder_rise"][0]
    assert 0.02 < low < 0.06


def test_the_grip_reach_holds_every_grasp_seen_but_a_far_out_one() -> None:
    """Grasps 0.5 to 3.4 cm off and one 4.6 cm off: the hand's reach still takes that one (a
    quantile of the grasps would leave that carry out, and its object lost); one 25 cm off (a
    grip point put beside a big hand's cup) is far out, and a reach that held it would let a
    hand take whatever vanishes anywhere near it."""
    grasps = [[0.005 + 0.001 * i, 0.09, 0.02] for i in range(30)] + [[0.046, 0.09, 0.02]]
    assert grip(grasps, [0.02])["grip_reach"][0] == pytest.approx(2 * 0.046)
    fitted = grip([*grasps, [0.25, 0.09, 0.02]], [0.02])
    assert fitted["grip_reach"][0] == pytest.approx(2 * 0.046)


def test_the_grip_rise_is_read_from_the_frames_a_carried_object_went_up() -> None:
    """Three frames the object rose with the grip seen (5 cm each), one without a grip seen."""
    up = [0.0, 0.05, 0.1, 0.15, 0.1, 0.05]
    carries = [{"heights": [*up, 0.0, 0.0], "released": True, "grips": [None] * 8},
               {"heights": [*up, 0.0, 0.0, 0.0, 0.0], "released": True,
                "grips": [0.02, 0.07, 0.12, 0.17, None, None, None, None, None, None]}]
    assert rise(carries) == (pytest.approx(0.05 / 2), 3)
    with pytest.raises(ValueError, match="no rise"):
        rise([{"heights": [0.0, 0.0], "released": True, "grips": [0.1, 0.1]}])


def test_a_parameter_without_samples_keeps_the_hand_written_value_marked() -> None:
    hand = {name: 0.5 for name in DESCRIPTIONS}
    fitted = fit(MotionSamples(), hand)
    assert [(f.name, f.value, f.samples) for f in fitted] == [(n, 0.5, 0) for n in DESCRIPTIONS]
    assert parameter_clauses(fitted).count("NOT FITTED") == len(DESCRIPTIONS)
    with pytest.raises(ValueError, match="cannot fit obs_var: no samples"):
        fit(MotionSamples(), {})


def test_learn_theory_without_motion_samples_is_an_error(tmp_path) -> None:
    data = tmp_path / "data.pl"
    data.write_text("pair(a, o):t+1.\n")
    with pytest.raises(TheoryError, match=re.escape(str(samples_path(data)))):
        learn_theory([data], tmp_path / "too_learned.pl")


# ------------------------------------------------------------------ the shipped theories

FPS = Scenario.__dataclass_fields__["fps"].default                  # frames per second
#: The simulator's fastest motion of an object (generated games: up to 0.25 m/s) and a hand's.
FASTEST = 0.25
#: Depth noise at the camera's distance from the table (NoiseSpec), per axis.
_cam = CameraSpec()
_distance = float(np.linalg.norm(np.subtract(_cam.position, _cam.target)))
_noise = NoiseSpec()
DEPTH_SIGMA = _noise.depth_sigma_base + _noise.depth_sigma_quadratic * _distance ** 2
#: How high the simulator lifts a container or a carried object (timeline's default).
LIFT = 0.15


def _facts(name: str) -> dict[str, float]:
    text = THEORIES[name].read_text()
    found: dict[str, list[float]] = {}
    for m in re.finditer(r"^(\w+)\(([-\d.eE+]+)\)\.", text, re.M):
        found.setdefault(m[1], []).append(float(m[2]))
    return {k: v[0] for k, v in found.items() if len(v) == 1}


@pytest.mark.parametrize("name", ["learned", "hindsight"])
def test_the_shipped_learned_theories_have_no_hand_written_constant(name: str) -> None:
    text = THEORIES[name].read_text()
    includes = re.findall(r"^:- include\('([^']+)'\)\.", text, re.M)
    assert not any("too_parameters" in i or "too_affordances" in i for i in includes)
    assert "NOT FITTED" not in text
    facts = _facts(name)
    for parameter in DESCRIPTIONS:
        assert parameter in facts, f"{parameter} is no learned fact of {THEORIES[name]}"


@pytest.mark.parametrize("name", ["learned", "hindsight"])
def test_the_learned_parameters_are_within_the_simulator_s_ranges(name: str) -> None:
    p = _facts(name)
    step = FASTEST / FPS                  # the farthest an object moves in a frame (m)
    # perception averages many depth points (its depth noise is below one point's, not far
    # below); a segment's outline adds a jitter of the same order to its centre
    assert (DEPTH_SIGMA / 10) ** 2 < p["obs_var"] < (3 * DEPTH_SIGMA) ** 2
    # most objects stand still most of the time; none moves faster than the fastest
    assert (step / 30) ** 2 < p["motion_var"] < step ** 2
    # a reappearance is centimetres off its belief, less than the table is wide
    assert 0.01 ** 2 < p["reappear_var"] < 0.3 ** 2
    # lost: moved anywhere on the table (the generated games' tables are about a metre wide)
    assert 0.1 ** 2 < p["lost_var"] < 0.6 ** 2
    # an object under a container stays within its footprint (4 cm radius)
    assert 0.5 < p["follow_keep"] < 1.0 and 0 < p["follow_var"] < 0.04 ** 2
    # a hidden object moving on keeps most of its velocity; in a frame it strays from where
    # coasting puts it by at most the change of its velocity: two frames' worth of the fastest
    # motion (a reversal)
    assert 0.5 < p["coast_keep"] < 1.0 and 0 < p["wander_var"] < (2 * step) ** 2
    # one that stood still as it vanished stays about where it stood: it strays less
    assert 0 < p["rest_var"] < p["wander_var"] and p["moving_speed"] < step
    # a hand closes over what it takes: within a few centimetres of it, from above
    assert 0.005 < p["grip_reach"] < 0.15
    assert 0.02 < p["grip_height"] < 0.2 and 0.0 <= p["occluder_rise"] < 0.05
    assert 0.0 < p["grip_drop"] < 0.05
    assert 0.0 < p["grip_rise"] < step


def test_each_kind_s_height_is_the_median_of_its_perceived_heights() -> None:
    """The carriers' rules measure a grip from an object's top: half its kind's height, the
    median of the perceived heights of that kind (a kind seen too few times has none, and its
    grip is measured from its centre)."""
    from probanchor.learning.motion_parameters import kind_height_clauses, kind_heights

    s = MotionSamples()
    s.rows["heights"] = ([["bottle", 0.2]] * 15 + [["bottle", 0.05]] * 5 + [["ball", 0.06]] * 19)
    assert kind_heights(s) == {"bottle": (0.2, 20)}
    assert kind_heights(s, least=19) == {"ball": (0.06, 19), "bottle": (0.2, 20)}
    assert "kind_height(bottle, 0.2).  % 20 samples" in kind_height_clauses(kind_heights(s))


def test_rest_var_is_the_spread_of_the_objects_that_stood_still_as_they_vanished() -> None:
    """Gaps of n frames of objects still as they vanished, d ~ N(0, n V + C) per axis, among
    gaps of objects that moved (which do not count): the maximum-likelihood V and their count."""
    from probanchor.learning.motion_keep import MOVING, rest_gaps

    rng = np.random.default_rng(4)
    v, c = 0.002 ** 2, 0.004 ** 2
    n = rng.integers(1, 60, 4000)
    d = rng.normal(0.0, 1.0, (4000, 2)) * np.sqrt(n * v + c)[:, None]
    rows = [[0.0005, -0.001, *d[k], int(n[k])] for k in range(4000)]
    rows += [[MOVING * 3, 0.0, 0.5, 0.5, 10]] * 50                   # moving: not counted
    fitted, count = rest_gaps(rows)
    assert count == 4000
    # the standard error of V over ~8000 axis-values spread over n: a few per cent
    assert fitted == pytest.approx(v, rel=0.15)
    with pytest.raises(ValueError, match="stood still"):
        rest_gaps([[MOVING * 3, 0.0, 0.1, 0.1, 5]])


def test_height_var_is_the_spread_of_hidden_objects_heights() -> None:
    """Gaps of n frames whose heights went dz ~ N(0, n V + C): the maximum-likelihood V and the
    count of the rows that have dz; samples collected before dz was kept fit no height_var,
    and the fit leaves it out (the theory reads too.pl's rule) rather than failing."""
    from probanchor.learning.motion_keep import height_gaps
    from probanchor.learning.motion_parameters import OPTIONAL

    rng = np.random.default_rng(5)
    v, c = 0.001 ** 2, 0.003 ** 2
    n = rng.integers(1, 60, 3000)
    dz = rng.normal(0.0, 1.0, 3000) * np.sqrt(n * v + c)
    rows = [[0.0, 0.0, 0.01, -0.01, int(n[k]), float(dz[k])] for k in range(3000)]
    fitted, count = height_gaps(rows + [[0.0, 0.0, 0.01, 0.01, 5]])  # one without dz
    assert count == 3000
    # the standard error of V from 3,000 values spread over n: a few per cent
    assert fitted == pytest.approx(v, rel=0.15)
    with pytest.raises(ValueError, match="change of height"):
        height_gaps([[0.0, 0.0, 0.01, 0.01, 5]])
    old = MotionSamples()
    old.rows["coast_gap"] = [[0.0, 0.0, 0.01, 0.01, 5]]
    hand = {name: 0.5 for name in DESCRIPTIONS if name not in OPTIONAL}
    assert "height_var" not in {f.name for f in fit(old, hand)}
