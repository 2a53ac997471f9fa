"""Labels, particle states and facts of ``anchoring collect`` on hand-made episodes whose answer
is known: a ball covered by a mug (lowered over it, carried, lifted off), a ball behind a box,
a ball that is never seen again, two mugs near where a ball reappears."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from bridge.learning import LearningData
from probanchor.learning.experience import AnchorView, Episode, EpisodeFrame
from probanchor.learning.occlusion_data import (
    Collection,
    LabelOptions,
    data_text,
    episode_facts,
    hindsight_agreement,
    labels,
)

BALL = (0.0, 0.0, 0.03)


def frame(k: int, anchors: dict[str, tuple[bool, tuple[float, float, float]]],
          truth: dict[str, dict]) -> EpisodeFrame:
    cats = {"ball-1": "ball", "mug-1": "mug", "mug-2": "mug", "box-1": "box"}
    views = {s: AnchorView(s, cats[s], seen, pos) for s, (seen, pos) in anchors.items()}
    objects = {gt: {"position": list(info["position"]), "visible": info.get("visible", True),
                    "under": info.get("under"), "held_by": None}
               for gt, info in truth.items()}
    return EpisodeFrame(k, k / 15, views, {"objects": objects, "hands": {}})


def covered_ball_episode() -> Episode:
    """Frames 0-1 the ball is seen; 2 a mug being lowered hides it (the simulator's `under`
    not set yet); 3-6 under the mug, which is carried to x = 0.1 in 5-6; 7 the mug lifted
    (still over it, `under` ended); 8 the ball seen again at x = 0.1."""
    frames = []
    mug_x = [0.3, 0.1, 0.0, 0.0, 0.0, 0.05, 0.1, 0.1, 0.1]
    mug_z = [0.05, 0.14, 0.1, 0.05, 0.05, 0.05, 0.05, 0.1, 0.25]
    for k in range(9):
        ball_x = 0.1 if k >= 5 else 0.0
        seen = k in (0, 1, 8)
        under = "mug_1" if 3 <= k <= 6 else None
        truth = {"ball_1": {"position": (ball_x, 0.0, 0.03), "visible": seen, "under": under},
                 "mug_1": {"position": (mug_x[k], 0.0, mug_z[k])}}
        last_ball = (0.1, 0.0, 0.03) if k == 8 else BALL
        frames.append(frame(k, {"ball-1": (seen, last_ball),
                                "mug-1": (True, (mug_x[k], 0.0, mug_z[k]))}, truth))
    return Episode("covered", frames, {"ball-1": "ball_1", "mug-1": "mug_1"})


def test_truth_labels_cover_the_lowering_and_the_lift() -> None:
    lab = labels(covered_ball_episode(), LabelOptions(source="truth"))
    assert "ball-1" not in lab[0] and "ball-1" not in lab[1]          # seen: no label
    # frame 2: being lowered over it (10 cm above its centre... 7 cm: within the cover height)
    assert lab[2]["ball-1"] == {"mug-1": 1.0}
    assert all(lab[k]["ball-1"] == {"mug-1": 1.0} for k in range(3, 7))
    assert lab[7]["ball-1"] == {"mug-1": 1.0}      # lifted 7 cm: still over it, `under` ended


def test_hindsight_labels_the_whole_interval_from_where_it_emerged() -> None:
    ep = covered_ball_episode()
    lab = labels(ep, LabelOptions(source="hindsight"))
    assert all(lab[k]["ball-1"] == {"mug-1": 1.0} for k in range(2, 8))
    agree, n = hindsight_agreement(ep, LabelOptions())
    assert n == 6 and agree == pytest.approx(6.0)


def _approach_episode(mug_x: list[float]) -> Episode:
    """The ball seen in frames 0-1 and 7, hidden in 2-6 while the mug comes over it along
    ``mug_x`` (perceived all along) and is lifted off it in 6."""
    frames = []
    for k, x in enumerate(mug_x):
        z = 0.12 if k == 6 else 0.05
        frames.append(frame(k, {"ball-1": (k not in range(2, 7), BALL),
                                "mug-1": (True, (x, 0.0, z))}, {}))
    return Episode("approach", frames, {})


def test_hindsight_covers_from_when_the_occluder_arrives() -> None:
    """While the mug is still on its way (15 and 10 cm off where the ball was last seen) the
    ball is behind it, not under it; from the frame the mug is within arrival_reach on, under
    it."""
    ep = _approach_episode([0.4, 0.3, 0.15, 0.1, 0.02, 0.0, 0.0, 0.0])
    lab = labels(ep, LabelOptions(source="hindsight"))
    assert [lab[k]["ball-1"] for k in range(2, 7)] == [{}, {}] + [{"mug-1": 1.0}] * 3
    wide = labels(ep, LabelOptions(source="hindsight", arrival_reach=0.12))
    assert [wide[k]["ball-1"] for k in range(2, 7)] == [{}] + [{"mug-1": 1.0}] * 4


def test_hindsight_covers_the_whole_interval_when_the_occluder_never_comes_near() -> None:
    """An occluder whose percept never comes within arrival_reach of where the object was (a
    hand's grip point may stand 15 cm off what it holds) covers it from the start."""
    ep = _approach_episode([0.4, 0.3, 0.15, 0.12, 0.1, 0.1, 0.1, 0.1])
    ep.frames[7].anchors["ball-1"] = AnchorView("ball-1", "ball", True, (0.1, 0.0, 0.03))
    lab = labels(ep, LabelOptions(source="hindsight"))
    assert all(lab[k]["ball-1"] == {"mug-1": 1.0} for k in range(2, 7))


def test_an_anchor_never_seen_again_has_no_hindsight_label() -> None:
    ep = covered_ball_episode()
    ep.frames[8].anchors["ball-1"] = AnchorView("ball-1", "ball", False, BALL)
    lab = labels(ep, LabelOptions(source="hindsight"))
    assert all(lab[k]["ball-1"] is None for k in range(2, 9))
    collection = Collection()
    episode_facts(ep, 0, LabelOptions(source="hindsight"), collection)
    assert collection.pairs == 0


def test_two_candidates_share_the_hindsight_label_by_distance() -> None:
    frames = []
    for k in range(4):
        seen = k in (0, 3)
        z = 0.08 if k == 3 else 0.05            # both mugs lifted as the ball reappears
        anchors = {"ball-1": (seen, (0.0, 0.0, 0.03)), "mug-1": (True, (0.02, 0.0, z)),
                   "mug-2": (True, (0.0, 0.05, z)), "box-1": (True, (0.4, 0.0, 0.07))}
        frames.append(frame(k, anchors, {}))
    ep = Episode("two", frames, {})
    opts = LabelOptions(source="hindsight", sigma=0.04, steady_stride=1)
    lab = labels(ep, opts)[1]["ball-1"]
    w1, w2 = math.exp(-0.02 ** 2 / (2 * 0.04 ** 2)), math.exp(-0.05 ** 2 / (2 * 0.04 ** 2))
    assert set(lab) == {"mug-1", "mug-2"}                 # the box is out of reach
    assert lab["mug-1"] == pytest.approx(w1 / (w1 + w2))
    collection = Collection()
    episode_facts(ep, 0, opts, collection)
    text = "\n".join(collection.lines)
    assert f"{lab['mug-1']:.6g} :: occluder(ball_1_e0_f1, mug_1_e0_f1):t+1." in text


def test_behind_something_is_covered_by_nothing() -> None:
    """A ball hidden while a box stands in front of it (12 cm), seen again where it was."""
    frames = [frame(k, {"ball-1": (k != 1, BALL), "box-1": (True, (0.0, -0.12, 0.07))},
                    {"ball_1": {"position": BALL, "visible": k != 1}, "box_1":
                     {"position": (0.0, -0.12, 0.07)}}) for k in range(3)]
    ep = Episode("behind", frames, {"ball-1": "ball_1", "box-1": "box_1"})
    for source in ("truth", "hindsight"):
        assert labels(ep, LabelOptions(source=source))[1]["ball-1"] == {}


def test_facts_of_the_pairs() -> None:
    ep = covered_ball_episode()
    collection = Collection()
    episode_facts(ep, 3, LabelOptions(source="truth", steady_stride=1), collection)
    text = "\n".join(collection.lines)
    # frame 1 -> 2: the ball has just vanished (seen at t), the mug is lowered over it
    assert "pos(ball_1_e3_f1):t ~= (0.0000, 0.0000, 0.0300)." in text
    assert "seen(ball_1_e3_f1):t." in text
    assert "pos(mug_1_e3_f1):t+1 ~= (0.0000, 0.0000, 0.1000)." in text
    assert "pair(ball_1_e3_f1, mug_1_e3_f1):t+1.\noccluder(ball_1_e3_f1, mug_1_e3_f1):t+1." \
        in text
    # frame 5 -> 6: known under the mug at t: followed it (its place), occluded_by at t
    assert "occluded_by(ball_1_e3_f5, mug_1_e3_f5):t." in text
    assert "pos(ball_1_e3_f5):t ~= (0.0500, 0.0000, 0.0300)." in text
    # ... and as a particle that lost it: no occluder known, where it was last seen
    assert "pos(ball_1_e3_f5_c):t ~= (0.0000, 0.0000, 0.0300)." in text
    assert "occluded_by(ball_1_e3_f5_c" not in text
    assert "occluder(ball_1_e3_f5_c, mug_1_e3_f5):t+1." in text
    # hidden at t+1 = 2..7: six pairs; known under the mug at t = 2..6: five lost-track pairs
    assert collection.pairs == 6 + 5


def test_steady_points_are_thinned_with_weights() -> None:
    """A ball under a still mug for 12 frames: its steady pairs kept one in 3, weight 3."""
    frames = []
    for k in range(14):
        seen = k in (0, 13)
        truth = {"ball_1": {"position": BALL, "visible": seen, "under": None if seen else "mug_1"},
                 "mug_1": {"position": (0.0, 0.0, 0.05)}}
        frames.append(frame(k, {"ball-1": (seen, BALL), "mug-1": (True, (0.0, 0.0, 0.05))},
                            truth))
    ep = Episode("still", frames, {"ball-1": "ball_1", "mug-1": "mug_1"})
    full, thin = Collection(), Collection()
    episode_facts(ep, 0, LabelOptions(steady_stride=1), full)
    episode_facts(ep, 0, LabelOptions(steady_stride=3), thin)
    assert thin.pairs < full.pairs
    assert thin.weight == pytest.approx(full.weight, abs=3)
    assert thin.positive == pytest.approx(full.positive, abs=3)
    assert sum(line.startswith("weight(occluder(") and line.endswith(", 3).")
               for line in thin.lines) >= 3


def test_the_data_file_loads_and_learns(tmp_path: Path) -> None:
    ep = covered_ball_episode()
    collection = Collection()
    episode_facts(ep, 0, LabelOptions(), collection)
    path = tmp_path / "data.pl"
    path.write_text(data_text(collection, ["covered"], LabelOptions(), "anchoring collect ..."))
    with LearningData([path]) as data:
        targets = data.targets()
        assert [t["name"] for t in targets] == ["occluder(Occluded, Occluder):t+1"]
        root = data.root("occluder_t1")
        assert len(root.y) == collection.pairs


def test_label_options_are_checked() -> None:
    with pytest.raises(ValueError, match="truth"):
        LabelOptions(source="guess")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="steady_stride"):
        LabelOptions(steady_stride=0)


def test_hindsight_does_not_label_an_occluder_that_stood_still() -> None:
    """A ball rolls behind a mug that never moves and comes out 5 cm from it, within reach:
    the mug hid it from view, it did not cover it (it would have had to be lifted or slid
    off); the same episode with the mug lifted as the ball reappears labels the mug."""
    def episode(mug_lifted: bool) -> Episode:
        frames = []
        for k in range(6):
            seen = k in (0, 1, 5)
            ball = (0.04 * k / 5, 0.03, 0.03)
            mug_z = 0.05 + (0.1 if mug_lifted and k >= 5 else 0.0)
            truth = {"ball_1": {"position": ball, "visible": seen},
                     "mug_1": {"position": (0.0, 0.0, mug_z)}}
            frames.append(frame(k, {"ball-1": (seen, ball), "mug-1": (True, (0.0, 0.0, mug_z))},
                                truth))
        return Episode("behind", frames, {"ball-1": "ball_1", "mug-1": "mug_1"})

    still = labels(episode(False), LabelOptions(source="hindsight"))
    assert all(still[k]["ball-1"] == {} for k in range(2, 5))
    lifted = labels(episode(True), LabelOptions(source="hindsight"))
    assert all(lifted[k]["ball-1"] == {"mug-1": 1.0} for k in range(2, 5))


def test_hindsight_does_not_label_a_box_that_stood_in_front_and_moved_away() -> None:
    """A mug hidden behind a box whose centre stands 8 cm from it (a 15 cm box cannot cover a
    mug from there) is seen again where it was when the box moves away: not covered, although
    the box moved; the same box over the mug (1 cm off) and lifted off it labels it; slid
    away without rising, it would have taken the mug along: it was only in front of it."""
    def episode(offset: float, lift: float) -> Episode:
        frames = []
        for k in range(6):
            seen = k in (0, 5)
            box = (0.0 + (0.1 if k == 5 else 0.0), -offset, 0.075 + (lift if k == 5 else 0.0))
            frames.append(frame(k, {"mug-1": (seen, (0.0, 0.0, 0.04)), "box-1": (True, box)}, {}))
        return Episode("in front", frames, {})

    in_front = labels(episode(0.08, 0.05), LabelOptions(source="hindsight"))
    assert all(in_front[k]["mug-1"] == {} for k in range(1, 5))
    over = labels(episode(0.01, 0.05), LabelOptions(source="hindsight"))
    assert all(over[k]["mug-1"] == {"box-1": 1.0} for k in range(1, 5))
    slid = labels(episode(0.01, 0.0), LabelOptions(source="hindsight"))
    assert all(slid[k]["mug-1"] == {} for k in range(1, 5))


def test_the_covering_anchor_does_not_depend_on_dictionary_order() -> None:
    """Two perceived anchors of the same body (perception split a box into two): the label
    names the same one whatever order the anchors were met in (collect is deterministic)."""
    def episode(order: list[str]) -> Episode:
        frames = []
        for k in range(3):
            seen = k != 1
            truth = {"ball_1": {"position": BALL, "visible": seen,
                                "under": "box_1" if k == 1 else None},
                     "box_1": {"position": (0.0, 0.0, 0.06)}}
            views = {"ball-1": (seen, BALL)}
            views |= {s: (True, (0.0, 0.0, 0.06)) for s in order}
            frames.append(frame(k, views, truth))
        return Episode("split", frames, {"ball-1": "ball_1"} | {s: "box_1" for s in order})

    a = labels(episode(["mug-2", "box-1"]), LabelOptions(source="truth"))
    b = labels(episode(["box-1", "mug-2"]), LabelOptions(source="truth"))
    assert a[1]["ball-1"] == b[1]["ball-1"] == {"box-1": 1.0}


def test_a_hand_is_where_its_grip_is_in_the_data_as_in_the_filter() -> None:
    """An arm seen from the side: its segment's centre is 20 cm off its hand; the episode
    (and so the data's pos/1 and hindsight's distances) has the hand at its grip point, the
    position the runner tells the filter."""
    from probanchor.learning.experience import play
    from probanchor.percepts import Percept, PerceptFrame

    hist = np.zeros(216)
    hist[3] = 1.0
    grip = (0.1, 0.0, 0.12)
    frames = [PerceptFrame(k, k / 15, [Percept(
        time=k / 15, position=np.array([0.3, 0.0, 0.12]), size=np.array([0.5, 0.09, 0.08]),
        colour_histogram=hist, category={"skin": 1.0}, bbox=(100, 90, 320, 130),
        grip=np.array(grip))]) for k in range(3)]
    episode = play(frames, "arm")
    (view,) = episode.frames[-1].anchors.values()
    assert view.perceived and view.position == pytest.approx(grip)
