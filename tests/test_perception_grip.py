"""Arms and grip points (probanchor.perception.grip), on made-up segments and on the simulator."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from probanchor.perception import Pipeline
from probanchor.perception.grip import GripConfig, arms, join_across_arms
from probanchor.perception.segments import Segment
from probanchor.percepts import Percept, PerceptError
from probanchor.tabletop import Simulation, load_scenario

ROOT = Path(__file__).resolve().parents[1]
SHAPE = (240, 320)
WORKSPACE = (-0.6, 0.6, -0.5, 0.5)


def arm(x0: float, x1: float, y: float, col0: int, hand_at: str = "low", z: float = 0.15,
        step: float = 0.005) -> Segment:
    """A made-up arm along x from x0 to x1 at y: the 10 cm at ``hand_at``'s end reach 3 cm
    lower (the fingers) than the rest; image columns from ``col0`` on, one per point column."""
    xs = np.arange(x0, x1 + 1e-9, step)
    pts, rows, cols = [], [], []
    for i, x in enumerate(xs):
        near_low = (x - x0 < 0.1) if hand_at == "low" else (x1 - x < 0.1)
        bottom = z - (0.035 if near_low else 0.005)
        for dz in np.linspace(bottom, z + 0.035, 5):
            for dy in (-0.03, 0.0, 0.03):
                pts.append((x, y + dy, dz))
                rows.append(100 + int(dy * 100))
                cols.append(col0 + i)
    pts_a = np.array(pts)
    rows_a, cols_a = np.array(rows), np.clip(np.array(cols), 0, SHAPE[1] - 1)
    bbox = (int(cols_a.min()), int(rows_a.min()), int(cols_a.max()) + 1, int(rows_a.max()) + 1)
    return Segment("skin", rows_a, cols_a, pts_a, pts_a[:, 2].copy(), bbox)


def test_an_arm_entering_at_the_image_border_grips_at_its_far_end() -> None:
    # from x = -0.2 (hand) to 0.3, its last column at the image's right border
    seg = arm(-0.2, 0.3, 0.0, col0=SHAPE[1] - 101, hand_at="high")  # fingers at the wrong end
    [(_, grip)] = arms([seg], SHAPE, WORKSPACE, 0.5, GripConfig())
    # the entry decides, not the heights: the hand is the end away from the border
    assert grip[0] == pytest.approx(-0.15, abs=0.01)
    assert grip[1] == pytest.approx(0.0, abs=0.005)
    assert grip[2] == pytest.approx(0.15, abs=0.02)


def test_an_arm_in_full_view_grips_at_the_end_that_reaches_lower() -> None:
    for hand_at, expected in (("low", -0.15), ("high", 0.25)):
        seg = arm(-0.2, 0.3, 0.0, col0=50, hand_at=hand_at)
        [(_, grip)] = arms([seg], SHAPE, WORKSPACE, 0.5, GripConfig())
        assert grip[0] == pytest.approx(expected, abs=0.01), hand_at


def test_a_short_skin_segment_alone_grips_at_its_centre() -> None:
    seg = arm(0.0, 0.08, 0.1, col0=50)
    [(_, grip)] = arms([seg], SHAPE, WORKSPACE, 0.5, GripConfig())
    assert grip[0] == pytest.approx(0.04, abs=0.005)


def test_the_hand_beyond_an_object_in_front_is_joined_to_its_arm() -> None:
    forearm = arm(0.05, 0.3, 0.0, col0=SHAPE[1] - 51)           # enters at the border
    hand = arm(-0.2, -0.05, 0.0, col0=100)                       # 10 cm beyond, enters nowhere
    out = arms([forearm, hand], SHAPE, WORKSPACE, 0.5, GripConfig())
    assert len(out) == 1
    seg, grip = out[0]
    assert len(seg.rows) == len(forearm.rows)  # (joined in place)
    assert grip[0] == pytest.approx(-0.15, abs=0.01)
    # too far beyond: two hands
    far = arm(-0.4, -0.25, 0.0, col0=20)
    assert len(arms([arm(0.05, 0.3, 0.0, col0=SHAPE[1] - 51), far], SHAPE, WORKSPACE, 0.5,
                    GripConfig())) == 2


def test_two_arms_that_both_enter_the_view_are_never_joined() -> None:
    one = arm(-0.1, 0.3, 0.0, col0=SHAPE[1] - 81)
    two = arm(-0.1, 0.3, 0.08, col0=SHAPE[1] - 81)
    out = arms([one, two], SHAPE, WORKSPACE, 0.5, GripConfig())
    assert len(out) == 2
    assert all(g[0] == pytest.approx(-0.05, abs=0.01) for _, g in out)


def piece(x: float, y0: float, y1: float, z0: float, z1: float, rows: tuple[int, int],
          cols: tuple[int, int]) -> Segment:
    rr, cc = np.mgrid[rows[0]:rows[1], cols[0]:cols[1]]
    rr, cc = rr.ravel(), cc.ravel()
    n = len(rr)
    t = np.linspace(0, 1, n)
    pts = np.column_stack([x - 0.04 + 0.08 * ((cc - cols[0]) / max(cols[1] - cols[0] - 1, 1)),
                           y0 + (y1 - y0) * t, z0 + (z1 - z0) * t])
    return Segment("object", rr, cc, pts, pts[:, 2].copy(),
                   (cols[0], rows[0], cols[1], rows[1]))


def hsv_with(colours: dict[tuple[int, int, int, int], tuple[int, int, int]]) -> np.ndarray:
    hsv = np.zeros((*SHAPE, 3), np.uint8)
    hsv[:] = (0, 0, 120)  # grey table
    for (r0, r1, c0, c1), value in colours.items():
        hsv[r0:r1, c0:c1] = value
    return hsv


def test_the_top_and_foot_of_a_mug_either_side_of_a_forearm_are_one_segment() -> None:
    top = piece(0.1, 0.11, 0.14, 0.09, 0.10, (80, 86), (190, 215))     # far rim, above the arm
    foot = piece(0.1, 0.05, 0.07, 0.01, 0.04, (113, 119), (190, 214))  # near rim, below it
    skin = np.zeros(SHAPE, np.uint8)
    skin[86:113, 90:270] = 255
    blue = hsv_with({(80, 86, 190, 215): (110, 200, 150), (113, 119, 190, 214): (112, 180, 90)})
    pixels = len(top.rows) + len(foot.rows)
    out = join_across_arms([top, foot], skin, blue)
    assert len(out) == 1 and len(out[0].rows) == pixels
    # ... not when the pieces differ in hue (a red ball in front of a blue mug) ...
    top, foot = (piece(0.1, 0.11, 0.14, 0.09, 0.10, (80, 86), (190, 215)),
                 piece(0.1, 0.05, 0.07, 0.01, 0.04, (113, 119), (190, 214)))
    mixed = hsv_with({(80, 86, 190, 215): (110, 200, 150), (113, 119, 190, 214): (0, 200, 150)})
    assert len(join_across_arms([top, foot], skin, mixed)) == 2
    # ... nor without an arm between them, nor when they stand in different columns
    assert len(join_across_arms([top, foot], np.zeros(SHAPE, np.uint8), blue)) == 2
    aside = piece(0.3, 0.05, 0.07, 0.01, 0.04, (113, 119), (190, 214))
    assert len(join_across_arms([top, aside], skin, blue)) == 2


def test_a_percept_keeps_its_grip_point_in_streams_and_old_records_load() -> None:
    record = {"time": 1.0, "position": [0.1, 0.0, 0.2], "size": [0.5, 0.09, 0.08],
              "colour_histogram": [1.0] + [0.0] * 215, "category": {"skin": 1.0}}
    old = Percept.from_json(record)
    assert old.grip is None and "grip" not in old.to_json()
    new = Percept.from_json({**record, "grip": [-0.15, 0.0, 0.18]})
    new.validate()
    assert json.loads(json.dumps(new.to_json()))["grip"] == [-0.15, 0.0, 0.18]
    assert Percept.from_json(new.to_json()).grip.tolist() == [-0.15, 0.0, 0.18]
    with pytest.raises(PerceptError, match="grip"):
        Percept.from_json({**record, "grip": [0.0, float("nan"), 0.1]}).validate()
    with pytest.raises(PerceptError, match="grip"):
        Percept.from_json({**record, "grip": [0.0, 0.1]}).validate()


@pytest.fixture(scope="module")
def carry_frames():
    """The percepts of a hand that picks a ball up and carries it 40 cm (every 2nd frame)."""
    scenario = load_scenario(ROOT / "scenarios" / "hand_carries_past_others.yaml")
    pipe = Pipeline()
    out = []
    with Simulation(scenario, seed=0) as sim:
        for frame in sim:
            percepts = pipe.process(frame)
            out.append((frame.truth, percepts))
    return out


def test_the_grip_point_is_where_the_simulated_hand_is(carry_frames) -> None:
    errors, centres = [], []
    for truth, percepts in carry_frames:
        hand = truth["hands"]["hand_1"]
        skins = [p for p in percepts if p.best_category == "skin"]
        if hand["pixels"] < 2000 or len(skins) != 1:  # fully in view, one segment
            continue
        true = np.asarray(hand["position"])
        errors.append(float(np.linalg.norm(skins[0].grip[:2] - true[:2])))
        centres.append(float(np.linalg.norm(skins[0].position[:2] - true[:2])))
    assert len(errors) > 40
    # the grip point is within 2 cm of the hand's centre in the table plane; the segment's
    # centre (hand and forearm) is 10 cm or more off in most of those frames
    assert max(errors) < 0.02, max(errors)
    assert np.median(centres) > 0.1
