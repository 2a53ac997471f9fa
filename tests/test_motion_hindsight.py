"""The motion samples of a collection labelled in hindsight read no simulator truth
(probanchor.learning.motion_hindsight), and the estimators fitted from them recover what
generated them (probanchor.learning.motion_keep's gap fits, motion_variances without truth)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from probanchor.learning import motion_keep, motion_variances
from probanchor.learning.experience import AnchorView, Episode, EpisodeFrame
from probanchor.learning.motion_hindsight import LIFTED, hindsight_samples

CATS = {"ball-1": "ball", "mug-1": "mug", "box-1": "box", "ball-2": "ball", "skin-1": "skin"}


def frame(k: int, anchors: dict[str, tuple[bool, tuple[float, float, float]]],
          grips: dict[str, tuple[float, float, float]] | None = None) -> EpisodeFrame:
    """A frame with no truth at all (a robot's)."""
    grips = grips or {}
    views = {s: AnchorView(s, CATS[s], seen, pos, grips.get(s) if seen else None)
             for s, (seen, pos) in anchors.items()}
    return EpisodeFrame(k, k / 15, views, None)


def mug_over_ball() -> Episode:
    """The ball seen in 0-1 at the origin; the mug, lowered over it in 2, slides it 10 cm in
    4-6 and is lifted off in 7 (over it at x = 0.11); the ball seen again at x = 0.1 in 8."""
    mug_x = [0.3, 0.1, 0.0, 0.0, 0.03, 0.07, 0.1, 0.11, 0.11]
    mug_z = [0.05, 0.14, 0.1, 0.05, 0.05, 0.05, 0.05, 0.1, 0.25]
    frames = []
    for k in range(9):
        seen = k in (0, 1, 8)
        ball = (0.1, 0.0, 0.03) if k == 8 else (0.0, 0.0, 0.03)
        frames.append(frame(k, {"ball-1": (seen, ball),
                                "mug-1": (True, (mug_x[k], 0.0, mug_z[k]))}))
    return Episode("mug", frames, {})


def test_an_object_under_one_occluder_gives_one_gap_of_its_offsets() -> None:
    s = hindsight_samples(mug_over_ball())
    assert s.rows["follow"] == [] and s.rows["coast"] == []
    (gap,) = s.rows["follow_gap"]
    # offset from the mug as it vanished (mug at 0.0) and as it reappeared (mug at 0.11 in the
    # last frame it hid it), 5 steps apart (hidden in frames 2-7)
    assert gap[:4] == pytest.approx([0.0, 0.0, -0.01, 0.0]) and gap[4:] == [5, "mug"]
    # the mug's perceived displacements, with no true one, and whether it stood still
    assert s.rows["displacement"] and all(r[4] is None for r in s.rows["displacement"])
    assert all(r[5] is False for r in s.rows["displacement"])   # (nine frames: no window)


def rolling_ball(box: tuple[float, float, float] | None, partial: float = 0.0) -> Episode:
    """The ball rolls at 1 cm a frame along x at y = 0 (the camera looks along +y), is hidden
    in frames 4-8 and seen again; its two views before it vanishes and after it reappears are
    partial, their centres ``partial`` off towards the box; ``box``: where a box stands."""
    frames = []
    for k in range(12):
        seen = not 4 <= k <= 8
        x = 0.01 * k if seen else 0.03
        if k in (2, 3):
            x -= partial
        elif k in (9, 10):
            x += partial
        anchors = {"ball-1": (seen, (x, 0.0, 0.03))}
        if box is not None:
            anchors["box-1"] = (True, box)
        frames.append(frame(k, anchors))
    return Episode("behind", frames, {})


def test_an_object_behind_something_gives_a_coasting_gap() -> None:
    """The ball rolls at 1 cm a frame, passes behind the box in front of it in 4-8 and is
    seen again: a gap under nothing, measured from the views two frames before it vanished and
    after it reappeared (the views between may be partial), with the velocity it had there."""
    for partial in (0.0, 0.015):
        s = hindsight_samples(Episode("behind", rolling_ball((0.06, -0.1, 0.04),
                                                             partial).frames, {}))
        assert s.rows["follow_gap"] == []
        (gap,) = s.rows["coast_gap"]
        assert gap[:4] == pytest.approx([0.01, 0.0, 0.10, 0.0]) and gap[4] == 10


def test_an_object_with_nothing_in_front_of_it_left_the_view() -> None:
    """The same ball with the box behind it, or no box: nothing could hide it, it left the
    view (pushed out and back, perhaps elsewhere): no coasting gap."""
    for box in ((0.06, 0.1, 0.04), None):
        assert hindsight_samples(rolling_ball(box)).rows["coast_gap"] == []


def hand_carry(lift: float = 0.15) -> Episode:
    """A hand's grip comes down over the ball (seen up to frame 2), closes 2 cm above its centre,
    lifts it by ``lift``, carries it 30 cm, puts it down and rises; the ball is seen there in
    the last frame."""
    x0, x1 = 0.0, 0.3
    grips = [(x0, 0.0, 0.2), (x0, 0.0, 0.12), (x0, 0.0, 0.08), (x0, 0.0, 0.05),
             (x0, 0.0, 0.05)]
    grips += [(x0, 0.0, 0.05 + lift * f) for f in (0.3, 0.7, 1.0)]
    grips += [(x, 0.0, 0.05 + lift) for x in np.linspace(x0, x1, 6)[1:]]
    grips += [(x1, 0.0, 0.05 + lift * f) for f in (0.6, 0.2, 0.0)]
    grips += [(x1, 0.0, 0.08), (x1, 0.0, 0.14)]
    frames = []
    for k, g in enumerate(grips):
        seen = k <= 2
        frames.append(frame(k, {"ball-1": (seen, (x0, 0.0, 0.03)), "skin-1": (True, g)},
                            {"skin-1": g}))
    frames.append(frame(len(grips), {"ball-1": (True, (x1, 0.0, 0.03)),
                                     "skin-1": (True, (x1, 0.0, 0.2))},
                        {"skin-1": (x1, 0.0, 0.2)}))
    return Episode("carry", frames, {})


def test_a_carry_is_read_from_the_hands_grip_and_ends_where_it_put_the_object_down() -> None:
    s = hindsight_samples(hand_carry())
    (carry,) = s.rows["carries"]
    assert carry["released"]
    heights = carry["heights"]
    # it rose with the grip from where the grip closed (5 cm), 15 cm, and was let go at the
    # lowest after that (the two frames the hand rose empty are not held)
    assert max(heights) == pytest.approx(0.15)
    assert heights[-1] == pytest.approx(0.0) and heights[-2] > 0.0
    assert len(heights) == len(carry["grips"])
    assert s.rows["hold"] == [pytest.approx(0.02)]           # the grip over its centre
    (grasp,) = s.rows["grasp"]
    assert grasp[0] == pytest.approx(0.0) and grasp[2] == pytest.approx(0.02)
    # a hand that never rose with it carried nothing
    assert hindsight_samples(hand_carry(lift=LIFTED / 2)).rows["carries"] == []


def test_gap_fits_recover_the_autoregression_and_leave_out_what_it_cannot_explain() -> None:
    rng = np.random.default_rng(0)
    k, v, c = 0.83, 2.6e-5, 2e-5
    rows = []
    for _ in range(3000):
        n = int(rng.integers(1, 40))
        x0 = rng.normal(0, 0.02, 2)
        x = x0.copy()
        for _ in range(n):
            x = k * x + rng.normal(0, math.sqrt(v), 2)
        rows.append([*x0, *(x + rng.normal(0, math.sqrt(c), 2)), n, "box"])
    fk, fv, kept = motion_keep.follow_gaps(rows)
    assert fk == pytest.approx(k, abs=0.03) and fv == pytest.approx(v, rel=0.5)
    assert kept >= 0.99 * len(rows)
    k, v = 0.96, 1e-6
    rows = []
    for _ in range(1500):
        n = int(rng.integers(1, 40))
        vel = rng.normal(0, 0.01, 2)
        v0, p = vel.copy(), np.zeros(2)
        for _ in range(n):
            vel = k * vel
            p = p + vel + rng.normal(0, math.sqrt(v), 2)
        rows.append([*v0, *(p + rng.normal(0, math.sqrt(c), 2)), n])
    # objects that stood still as they vanished say nothing of the velocity kept: left out
    still = [[*rng.normal(0, 0.001, 2), *rng.normal(0, 0.002, 2), 8] for _ in range(1500)]
    movers = sum(math.hypot(r[0], r[1]) >= motion_keep.MOVING for r in rows)
    ck, cv, kept = motion_keep.coast_gaps(rows + still)
    assert ck == pytest.approx(k, abs=0.01) and cv == pytest.approx(v, rel=0.5)
    assert kept == movers
    with pytest.raises(ValueError, match="no gap"):
        motion_keep.coast_gaps(still)


def test_the_coasting_is_what_a_hidden_object_does_over_all_the_time_it_is_hidden() -> None:
    """Objects pushed at 2 cm a frame out of the view stop there after 10 frames and are seen
    again where they stopped, 20 to 40 frames after they vanished, a few of them (one in ten)
    having been pushed on 40 frames' worth: the coasting fitted over the whole times hidden
    coasts them on between the near ones' 10 and the far ones' 40 frames' worth of their
    velocity, about their mean (13), not a metre past where they stopped; a broad component
    would have left the far ones out (11)."""
    rng = np.random.default_rng(3)
    gaps = []
    for i in range(200):
        v = rng.normal(0, 1, 2)
        v = 0.02 * v / np.linalg.norm(v)
        n = int(rng.integers(20, 40))
        frames = 40 if i % 10 == 0 else 10
        gaps.append([*v, *(frames * v + rng.normal(0, 0.005, 2)), n])
    k, _, kept = motion_keep.coast_gaps(gaps)
    assert kept == len(gaps)
    assert 12 < k / (1 - k) < 18                    # how many frames' worth it coasts on
    with pytest.raises(ValueError, match="no gap"):
        motion_keep.coast_gaps([])


def test_a_vanishing_faster_than_what_perception_sees_move_is_no_motion() -> None:
    """Objects coasting on at 1.5 cm a frame (kept 0.9), and a third as many standing still
    whose perceived centre jumped 6 cm as they went behind something: with the cap at the
    99 % quantile of the perceived steps (objects at most 2 cm a frame; hands faster, left
    out), the fit finds the coasting; without it, the jumps pull the kept fraction down."""
    rng = np.random.default_rng(4)
    gaps = []
    for i in range(160):
        d = rng.normal(0, 1, 2)
        d /= np.linalg.norm(d)
        n = int(rng.integers(5, 20))
        if i % 4 == 3:
            gaps.append([*(0.06 * d), *rng.normal(0, 0.003, 2), n])
        else:
            k = 0.9
            gaps.append([*(0.015 * d), *(0.015 * d * k * (1 - k ** n) / (1 - k)
                                         + rng.normal(0, 0.003, 2)), n])
    steps = [[*(rng.uniform(0, 0.02) * rng.normal(0, 1, 2) / 1.5), 0.0, "mug", None, False]
             for _ in range(2000)] + [[0.1, 0.0, 0.0, "skin", None, False]] * 200
    cap = motion_keep.fastest(steps)
    assert 0.015 < cap < 0.06 and motion_keep.fastest([]) == math.inf
    k, _, kept = motion_keep.coast_gaps(gaps, cap)
    assert kept == 120 and k == pytest.approx(0.9, abs=0.05)
    k_all, _, _ = motion_keep.coast_gaps(gaps)
    assert k_all < 0.8


def test_variances_without_truth_come_from_what_perception_saw_stand_still() -> None:
    rng = np.random.default_rng(1)
    noise, motion = 2.5e-6, 3e-4
    still = [[*(rng.normal(0, math.sqrt(2 * noise), 3)), "mug", None, True] for _ in range(4000)]
    moving = [[*(rng.normal(0, math.sqrt(motion + 2 * noise), 3)), "ball", None, False]
              for _ in range(1000)]
    obs, n = motion_variances.obs_var(still + moving)
    assert n == 4000 and obs == pytest.approx(noise, rel=0.1)
    mv, _ = motion_variances.motion_var(still + moving)
    assert mv == pytest.approx(0.2 * motion, rel=0.15)   # one displacement in five moved
