"""The simulated world: events move what they should, ground truth says what is hidden."""

from __future__ import annotations

import cv2
import numpy as np
import pytest

from probanchor.perception.segments import SkinWindow
from probanchor.tabletop import ScenarioBuilder, ScenarioError, Simulation


def frames_at(scenario, times, **kw):
    """Frames nearest to the given times (fps 5 to keep it quick)."""
    kw.setdefault("fps", 5)
    out = {}
    with Simulation(scenario, **kw) as sim:
        for frame in sim:
            for t in times:
                if abs(frame.time - t) < 1e-6:
                    out[t] = frame
    return out


def shell(**kw) -> ScenarioBuilder:
    b = ScenarioBuilder("shell", **kw)
    b.add("ball_1", "ball", "red", position=(0.0, -0.15))
    b.add("mug_1", "mug", "blue", position=(-0.18, 0.05))
    b.add("box_1", "box", "green", position=(0.0, 0.05), size=[0.12, 0.12, 0.12])
    b.add("mug_2", "mug", "white", position=(0.18, 0.05))
    return b


def test_frame_shapes_and_camera():
    scn = shell(duration=0.2).build()
    with Simulation(scn, fps=5) as sim:
        frame = sim.step()
    assert frame.rgb.shape == (240, 320, 3) and frame.rgb.dtype == np.uint8
    assert frame.depth.shape == (240, 320) and frame.depth.dtype == np.float32
    assert frame.intrinsics.width == 320
    # the camera looks down at the table from about 1 m
    valid = frame.depth[frame.depth > 0]
    assert 0.6 < np.median(valid) < 1.4
    assert frame.camera_pose[2, 3] > 0.5 and frame.camera_pose[2, 2] < -0.5


def test_bigger_frames_on_request():
    scn = shell(duration=0.1).build()
    with Simulation(scn, width=640, height=480) as sim:
        frame = sim.step()
    assert frame.rgb.shape == (480, 640, 3)
    assert frame.truth["objects"]["ball_1"]["visible"]


def test_noise_is_deterministic_per_seed():
    scn = shell(duration=0.1).build()
    a = frames_at(scn, [0.0], seed=3)[0.0]
    b = frames_at(scn, [0.0], seed=3)[0.0]
    c = frames_at(scn, [0.0], seed=4)[0.0]
    assert np.array_equal(a.depth, b.depth) and np.array_equal(a.rgb, b.rgb)
    assert not np.array_equal(a.depth, c.depth)


def test_put_under_hides_and_swaps_carry_what_is_hidden():
    b = shell()
    b.put_under(0.5, "ball_1", "mug_1", duration=1.5)
    b.swap(2.5, "mug_1", "mug_2", duration=2.0)
    b.lift(5.0, "mug_1", duration=1.5)
    fr = frames_at(b.build(), [0.0, 2.2, 4.6, 7.0])
    start = fr[0.0].truth["objects"]
    assert start["ball_1"]["visible"] and start["ball_1"]["hidden_by"] is None
    hidden = fr[2.2].truth["objects"]["ball_1"]
    assert not hidden["visible"] and hidden["hidden_by"] == "mug_1" and hidden["pixels"] == 0
    # mug_1 went over the ball (its cavity, 12.5 mm behind its handle-inclusive centre);
    # after the swap the ball is under mug_1, which stands where mug_2 stood
    over_ball = 0.0 + 0.0125
    after = fr[4.6].truth["objects"]
    assert after["ball_1"]["hidden_by"] == "mug_1"
    assert after["mug_1"]["position"][0] == pytest.approx(0.18, abs=1e-6)
    assert after["mug_2"]["position"][0] == pytest.approx(over_ball, abs=1e-6)
    assert after["ball_1"]["position"][:2] == pytest.approx([0.18 - 0.0125, 0.05], abs=1e-6)
    revealed = fr[7.0].truth["objects"]["ball_1"]
    assert revealed["visible"] and revealed["hidden_by"] is None


def test_shuffle_permutes_containers_with_their_contents():
    b = shell()
    b.put_under(0.5, "ball_1", "box_1", duration=1.5)
    b.shuffle(2.5, ["mug_1", "box_1", "mug_2"], ["box_1", "mug_2", "mug_1"], duration=3.0)
    fr = frames_at(b.build(), [6.0])[6.0].truth["objects"]
    assert fr["mug_1"]["position"][0] == pytest.approx(0.0, abs=1e-6)
    assert fr["box_1"]["position"][0] == pytest.approx(0.18, abs=1e-6)
    assert fr["mug_2"]["position"][0] == pytest.approx(-0.18, abs=1e-6)
    assert fr["ball_1"]["position"][0] == pytest.approx(0.18, abs=1e-6)
    assert fr["ball_1"]["hidden_by"] == "box_1"


def test_transitive_containers_move_together():
    b = ScenarioBuilder("transitive")
    b.add("ball_1", "ball", "red", position=(0.0, -0.1))
    b.add("mug_1", "mug", "blue", position=(-0.22, 0.05))
    b.add("box_1", "box", "green", position=(0.22, 0.08), size=[0.14, 0.14, 0.14])
    b.put_under(0.2, "ball_1", "mug_1", duration=1.0)
    b.put_under(1.4, "mug_1", "box_1", duration=1.0)
    b.move(2.6, "box_1", (-0.2, 0.1), duration=1.0)
    fr = frames_at(b.build(), [2.4, 4.0])
    before, after = fr[2.4].truth["objects"], fr[4.0].truth["objects"]
    assert after["mug_1"]["hidden_by"] == "box_1" and after["ball_1"]["hidden_by"] == "mug_1"
    shift = np.subtract(after["box_1"]["position"], before["box_1"]["position"])
    for oid in ("mug_1", "ball_1"):
        moved = np.subtract(after[oid]["position"], before[oid]["position"])
        assert moved == pytest.approx(shift, abs=1e-9)


def test_hand_picks_up_carries_and_puts_down():
    b = ScenarioBuilder("hand")
    b.add("can_1", "can", "yellow", position=(-0.1, 0.0), radius=0.033, height=0.12)
    b.add("ball_1", "ball", "red", position=(0.2, 0.1))
    b.pick_up(0.5, "can_1", duration=2.0)
    b.put_down(3.0, "can_1", (0.15, -0.15), duration=2.0)
    fr = frames_at(b.build(), [2.6, 6.0])
    held = fr[2.6].truth["objects"]["can_1"]
    assert held["held_by"] == "hand_1" and not held["visible"] and held["hidden_by"] == "hand_1"
    assert fr[2.6].truth["hands"]["hand_1"]["pixels"] > 200  # the hand is in view
    placed = fr[6.0].truth["objects"]["can_1"]
    assert placed["visible"] and placed["held_by"] is None
    assert placed["position"] == pytest.approx([0.15, -0.15, 0.06], abs=1e-6)
    assert fr[6.0].truth["hands"]["hand_1"]["pixels"] == 0  # gone home, out of view


def test_cover_camera_and_remove():
    b = shell()
    b.cover_camera(0.4, duration=1.0)
    b.remove(2.0, "ball_1")
    fr = frames_at(b.build(), [0.8, 2.4])
    covered = fr[0.8]
    assert covered.truth["camera_covered"]
    assert np.count_nonzero(covered.depth) == 0  # the palm is closer than the sensor's range
    assert all(o["hidden_by"] == "camera_cover" for o in covered.truth["objects"].values())
    # the frame is almost all skin (the pipeline's skin window, in HSV)
    hsv = cv2.cvtColor(covered.rgb, cv2.COLOR_RGB2HSV)
    assert np.mean(SkinWindow().mask(hsv) > 0) > 0.95
    gone = fr[2.4].truth["objects"]["ball_1"]
    assert gone["present"] is False and not gone["visible"]


def test_runtime_error_names_the_event_line():
    b = shell()
    b.put_down(1.0, "ball_1", (0.1, 0.1))  # never picked up
    with pytest.raises(ScenarioError, match="not held by a hand"):
        frames_at(b.build(), [2.0])


def test_a_container_covers_one_thing_at_a_time():
    b = shell()
    b.put_under(0.2, "ball_1", "box_1", duration=1.0)
    b.put_under(1.4, "mug_1", "box_1", duration=1.0)
    with pytest.raises(ScenarioError, match="already covers") as info:
        frames_at(b.build(), [3.0])
    assert info.value.line is None or info.value.line > 0


def test_put_under_can_slide_the_object_under_a_container_in_place():
    b = shell()
    b.put_under(0.2, "ball_1", "box_1", duration=1.0, move="object")
    fr = frames_at(b.build(), [1.6])[1.6].truth["objects"]
    assert fr["box_1"]["position"] == pytest.approx([0.0, 0.05, 0.06], abs=1e-9)
    assert fr["ball_1"]["position"][:2] == pytest.approx([0.0, 0.05], abs=1e-9)
    assert fr["ball_1"]["hidden_by"] == "box_1"


def test_an_object_let_go_above_the_table_falls_and_settles():
    b = ScenarioBuilder("drop")
    b.add("ball_1", "ball", "red", position=(0.0, 0.0))
    b.move(0.2, "ball_1", (0.1, 0.0, 0.3), duration=1.0)
    fr = frames_at(b.build(), [1.2, 1.4, 2.0])
    assert fr[1.2].truth["objects"]["ball_1"]["position"][2] == pytest.approx(0.3, abs=1e-6)
    # after 0.2 s of free fall it has dropped g t^2 / 2 = 0.196 m
    assert fr[1.4].truth["objects"]["ball_1"]["position"][2] == pytest.approx(0.104, abs=2e-3)
    assert fr[2.0].truth["objects"]["ball_1"]["position"] == pytest.approx([0.1, 0.0, 0.03])


def test_picking_up_a_container_leaves_what_it_covered():
    b = ScenarioBuilder("reveal")
    b.add("cup_1", "cup", "orange", position=(0.0, 0.05), radius=0.04, height=0.09)
    b.add("ball_1", "ball", "red", under="cup_1")
    b.pick_up(0.2, "cup_1", duration=1.5)
    fr = frames_at(b.build(), [0.0, 2.0])
    assert fr[0.0].truth["objects"]["ball_1"]["hidden_by"] == "cup_1"
    ball = fr[2.0].truth["objects"]["ball_1"]
    assert ball["visible"] and ball["under"] is None
    assert ball["position"] == pytest.approx([0.0, 0.05, 0.03], abs=1e-9)
    assert fr[2.0].truth["objects"]["cup_1"]["held_by"] == "hand_1"
