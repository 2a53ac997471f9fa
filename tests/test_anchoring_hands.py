"""Hand anchors (anchoring.hands): one anchor per hand, matched by grip point."""

from __future__ import annotations

import numpy as np
import pytest

from anchoring import AnchorManager, HandRules
from anchoring.features import pair_evidence
from anchoring.hands import match_hands, reasoning_position
from probanchor.percepts import Percept

DT = 1 / 15
BINS = 216


def skin(t: float, grip: tuple[float, float, float], length: float = 0.5,
         bbox: tuple[int, int, int, int] = (100, 90, 320, 130)) -> Percept:
    """An arm from the right edge: its hand at ``grip``, its segment ``length`` long along x
    (the centre half-way), as perception describes it."""
    hist = np.zeros(BINS)
    hist[3] = 1.0
    x, y, z = grip
    return Percept(time=t, position=np.array([x - 0.05 + length / 2, y, z]),
                   size=np.array([length, 0.09, 0.08]), colour_histogram=hist,
                   category={"skin": 1.0}, bbox=bbox, grip=np.array(grip))


def thing(t: float, position: tuple[float, float, float], size: tuple[float, float, float],
          colour_bin: int, category: str, bbox: tuple[int, int, int, int] = (0, 0, 1, 1)
          ) -> Percept:
    hist = np.zeros(BINS)
    hist[colour_bin] = 1.0
    return Percept(time=t, position=np.array(position), size=np.array(size),
                   colour_histogram=hist, category={category: 0.9, "box": 0.1},
                   colour_names=["blue"], bbox=bbox)


def symbols_of_hands(manager: AnchorManager, frames: list[list[Percept]]) -> list[dict]:
    out = []
    for k, percepts in enumerate(frames):
        result = manager.process(k * DT, percepts)
        out.append({i: s for i, s in result.symbols.items()
                    if percepts[i].best_category == "skin"})
    return out


def test_a_fast_hand_coming_in_at_the_edge_is_one_anchor() -> None:
    """A hand comes in (a 7 cm sliver at the edge first, then hand and forearm growing), moves
    14 cm per frame (2.1 m/s) to the ball, closes, lifts and carries it back: the segment's
    centre jumps by up to 25 cm between frames; one symbol throughout."""
    frames = []
    xs = [0.47, 0.37, 0.23, 0.09, -0.05, -0.18, -0.2, -0.2, -0.2, -0.1, 0.0, 0.1, 0.2]
    lengths = [0.07, 0.13, 0.27, 0.41, 0.5, 0.54, 0.54, 0.54, 0.54, 0.54, 0.5, 0.4, 0.3]
    for x, length in zip(xs, lengths, strict=True):
        frames.append([skin(0, (x, 0.0, 0.2), length)])
    manager = AnchorManager()
    seen = symbols_of_hands(manager, [[skin(k * DT, p.grip, p.size[0]) for p in f]
                                      for k, f in enumerate(frames)])
    assert {s for f in seen for s in f.values()} == {"skin-1"}
    assert manager.get("skin-1").confirmed


def test_without_hand_rules_the_same_hand_gets_several_symbols() -> None:
    """The learned matcher on the segments' centres (hands=None) loses the hand: the reason
    hands are matched apart."""
    xs = [0.47, 0.37, 0.23, 0.09, -0.05, -0.18, -0.2]
    lengths = [0.07, 0.13, 0.27, 0.41, 0.5, 0.54, 0.54]
    manager = AnchorManager(hands=None)
    seen = symbols_of_hands(manager, [[skin(k * DT, (x, 0.0, 0.2), n)]
                                      for k, (x, n) in enumerate(zip(xs, lengths, strict=True))])
    assert len({s for f in seen for s in f.values()}) > 1


def test_two_hands_keep_their_anchors_while_they_cross_the_table() -> None:
    manager = AnchorManager()
    frames = []
    for k in range(12):
        a = (0.3 - 0.05 * k, -0.1, 0.2)
        b = (0.3 - 0.04 * k, 0.15, 0.2)
        frames.append([skin(k * DT, b, bbox=(150, 40, 320, 80)),
                       skin(k * DT, a, bbox=(120, 100, 320, 140))])
    seen = symbols_of_hands(manager, frames)
    assert all(f == {0: "skin-1", 1: "skin-2"} for f in seen), seen


def test_a_piece_of_the_hand_is_withheld_and_an_arm_far_off_is_another_hand() -> None:
    manager = AnchorManager()
    manager.process(0.0, [skin(0.0, (0.0, 0.0, 0.2))])
    piece = thing(DT, (-0.12, 0.0, 0.2), (0.06, 0.08, 0.07), 3, "skin")
    piece.category = {"skin": 1.0}
    result = manager.process(DT, [skin(DT, (0.0, 0.0, 0.2)), piece])
    assert result.symbols == {0: "skin-1"}
    assert [(w.percept_index, w.symbols) for w in result.withheld] == [(1, ["skin-1"])]
    far = skin(2 * DT, (0.0, 0.35, 0.2))
    result = manager.process(2 * DT, [skin(2 * DT, (0.0, 0.0, 0.2)), far])
    assert result.symbols == {0: "skin-1", 1: "skin-2"}


def test_a_hand_that_leaves_and_comes_back_is_the_same_anchor() -> None:
    manager = AnchorManager()
    for k in range(5):
        manager.process(k * DT, [skin(k * DT, (0.1 + 0.08 * k, 0.0, 0.2))])
    result = manager.process(5 * DT, [])
    assert result.tracked == ["skin-1"]
    back = 3.0
    result = manager.process(back, [skin(back, (-0.2, 0.1, 0.2))])
    assert result.symbols == {0: "skin-1"}
    assert [a.action for a in result.assignments] == ["reacquire"]
    # two hands come back, one anchor out of view: it takes one, the other is new
    result = manager.process(back + 5.0, [skin(back + 5.0, (-0.2, 0.1, 0.2)),
                                          skin(back + 5.0, (0.2, 0.2, 0.2))])
    assert sorted(result.symbols.values()) == ["skin-1", "skin-2"]


def test_the_gate_grows_with_the_time_unseen() -> None:
    rules = HandRules(speed=3.0, reach=0.12)
    manager = AnchorManager()
    manager.process(0.0, [skin(0.0, (0.0, 0.0, 0.2))])
    hand = manager.get("skin-1")
    near, far = skin(DT, (0.3, 0.0, 0.2)), skin(DT, (0.4, 0.0, 0.2))
    found = match_hands([hand], [near], DT, rules)
    assert found.reacquire == {0: 0}                 # 0.30 m <= 0.12 + 3 * 1/15
    found = match_hands([hand], [far], DT, rules)
    assert found.reacquire == {} and found.new == [0]
    found = match_hands([hand], [far], 0.2, rules)
    assert found.reacquire == {0: 0}


def test_what_the_reasoning_is_told_of_a_hand_is_its_grip_point() -> None:
    arm = skin(0.0, (-0.2, 0.0, 0.1))
    assert reasoning_position(arm).tolist() == [-0.2, 0.0, 0.1]
    ball = thing(0.0, (0.1, 0.0, 0.03), (0.06, 0.06, 0.06), 0, "ball")
    assert reasoning_position(ball).tolist() == [0.1, 0.0, 0.03]
    old = skin(0.0, (-0.2, 0.0, 0.1))
    old.grip = None                                 # a stream written before grip points
    assert reasoning_position(old).tolist() == old.position.tolist()


MUG = ((0.1, 0.0, 0.05), (0.09, 0.09, 0.1))


def test_what_an_arm_leaves_in_view_of_a_mug_is_withheld() -> None:
    """The foot of mug-1 seen below a forearm, after its top was seen above it (another
    category, 6 cm lower than that top, in shadow: a colour less alike) is withheld with mug-1,
    not a new ball; without the arm it is a new object; a red thing there, or a blue one 20 cm
    away, is not the mug."""
    def start() -> AnchorManager:
        manager = AnchorManager()
        for k in range(3):
            manager.process(k * DT, [thing(k * DT, *MUG, 10, "mug", (170, 100, 210, 140))])
        # the arm comes over it: only the mug's top is seen (it re-acquires mug-1)
        top = thing(3 * DT, (0.1, 0.02, 0.1), (0.09, 0.05, 0.01), 10, "mug",
                    (174, 104, 202, 117))
        result = manager.process(3 * DT, [top, skin(3 * DT, (-0.1, -0.05, 0.18),
                                                    bbox=(60, 110, 280, 150))])
        assert result.symbols[0] == "mug-1"
        return manager

    hist = np.zeros(BINS)
    hist[10], hist[11] = 0.55, 0.45                 # correlates about 0.6 with the mug's
    foot = thing(4 * DT, (0.1, -0.02, 0.02), (0.07, 0.06, 0.03), 10, "ball",
                 (175, 136, 197, 142))
    foot.colour_histogram = hist
    arm = skin(4 * DT, (-0.1, -0.05, 0.18), bbox=(60, 100, 280, 146))
    manager = start()
    result = manager.process(4 * DT, [foot, arm])
    assert [(w.percept_index, w.symbols) for w in result.withheld] == [(0, ["mug-1"])]
    assert "mug-1" in result.tracked
    # deeper in shadow (a white mug's foot): less alike than unrelated colours are, but
    # named as the mug is
    dark = np.zeros(BINS)
    dark[120] = 1.0
    shadowed = thing(4 * DT, (0.1, -0.02, 0.02), (0.07, 0.06, 0.03), 10, "ball",
                     (175, 136, 197, 142))
    shadowed.colour_histogram = dark
    manager = start()
    features, _ = pair_evidence([manager.get("mug-1")], [shadowed], 0.05)
    assert features[0, 0, 1] < 0.5
    result = manager.process(4 * DT, [shadowed, arm])
    assert [(w.percept_index, w.symbols) for w in result.withheld] == [(0, ["mug-1"])]
    manager = start()
    result = manager.process(4 * DT, [foot])         # no arm in front: the usual rules
    assert result.symbols == {0: "ball-1"}
    red = thing(4 * DT, (0.1, -0.02, 0.02), (0.07, 0.06, 0.03), 0, "ball", (175, 136, 197, 142))
    red.colour_names = ["red"]
    aside = thing(4 * DT, (0.3, -0.02, 0.02), (0.07, 0.06, 0.03), 10, "ball",
                  (175, 136, 197, 142))
    for other in (red, aside):
        manager = start()
        result = manager.process(4 * DT, [other, skin(4 * DT, (-0.1, -0.05, 0.18),
                                                      bbox=(60, 100, 280, 146))])
        assert result.symbols[0] == "ball-1", other.position


def test_hand_rules_are_saved_and_old_world_files_load(tmp_path) -> None:
    manager = AnchorManager(hands=HandRules(speed=2.0, reach=0.1, piece_gap=0.04))
    manager.process(0.0, [skin(0.0, (0.0, 0.0, 0.2))])
    path = tmp_path / "world.json"
    manager.save(path)
    loaded = AnchorManager.load(path)
    assert loaded.hands == HandRules(speed=2.0, reach=0.1, piece_gap=0.04)
    assert loaded.get("skin-1").history[-1].grip.tolist() == [0.0, 0.0, 0.2]
    record = manager.to_json()
    del record["hands"]
    assert AnchorManager.from_json(record).hands == HandRules()
    record["hands"] = None
    assert AnchorManager.from_json(record).hands is None
    with pytest.raises(ValueError, match="speed"):
        HandRules(speed=-1.0)
