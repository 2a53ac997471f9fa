"""The perception pipeline against the simulator's ground truth."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest

from probanchor.loop.sources import perceive_scenario
from probanchor.perception import Pipeline
from probanchor.perception.colour import DEFAULT_BINS, colour_names, histogram, hsv_image
from probanchor.percepts import read_percepts, write_percepts
from probanchor.tabletop import ScenarioBuilder, Simulation, load_scenario

ROOT = Path(__file__).resolve().parents[1]


def true_box(obj) -> np.ndarray:
    """World axis-aligned extents of an object (its yaw turns boxes and mugs)."""
    return np.asarray(obj.world_extents())


@pytest.fixture(scope="module")
def static_frames():
    scenario = load_scenario(ROOT / "scenarios" / "static.yaml")
    pipe = Pipeline()
    out = []
    for seed in (0, 1):
        with Simulation(scenario, seed=seed) as sim:
            frame = sim.step()
        out.append((frame, pipe.process(frame)))
    return scenario, out


def test_static_scene_one_percept_per_visible_object(static_frames):
    scenario, frames = static_frames
    for frame, percepts in frames:
        visible = {k for k, v in frame.truth["objects"].items() if v["visible"]}
        assert visible == set(scenario.object_ids)
        ids = [p.truth_id for p in percepts]
        assert sorted(ids, key=str) == sorted(visible), ids  # exactly one each, nothing else


def test_static_scene_position_size_colour(static_frames):
    scenario, frames = static_frames
    for frame, percepts in frames:
        for p in percepts:
            obj = scenario.object(p.truth_id)
            truth = frame.truth["objects"][p.truth_id]
            error = np.linalg.norm(p.position - np.asarray(truth["position"]))
            assert error < 0.01, f"{p.truth_id}: centroid {error * 1000:.1f} mm off"
            rel = p.size / true_box(obj) - 1
            assert np.all(np.abs(rel) < 0.15), f"{p.truth_id}: size off by {rel}"
            assert p.colour_names and p.colour_names[0] == obj.colour_name, \
                (p.truth_id, p.colour_names)
            p.validate()


def test_static_scene_categories(static_frames):
    scenario, frames = static_frames
    right = total = 0
    for _, percepts in frames:
        for p in percepts:
            assert len(p.category) == 3 and abs(sum(p.category.values()) - 1) < 0.05
            assert list(p.category.values()) == sorted(p.category.values(), reverse=True)
            total += 1
            right += p.best_category == scenario.object(p.truth_id).category
    assert right >= total - 2  # the classifier may confuse similar categories, rarely


def test_ball_under_cup_gives_no_percept():
    b = ScenarioBuilder("hidden", duration=0.1)
    b.add("cup_1", "cup", "purple", position=(0.0, 0.05), radius=0.04, height=0.09)
    b.add("ball_1", "ball", "red", under="cup_1", radius=0.03)
    with Simulation(b.build(), seed=2) as sim:
        frame = sim.step()
    percepts = Pipeline().process(frame)
    assert [p.truth_id for p in percepts] == ["cup_1"]
    assert frame.truth["objects"]["ball_1"]["hidden_by"] == "cup_1"


def test_covered_camera_gives_no_percepts():
    b = ScenarioBuilder("covered", duration=0.4)
    b.add("ball_1", "ball", "red", position=(0.0, 0.0))
    b.cover_camera(0.0, duration=1.0)
    with Simulation(b.build(), fps=5) as sim:
        frame = sim.step()
    assert frame.truth["camera_covered"]
    assert Pipeline().process(frame) == []


def test_frame_without_depth_does_not_crash(static_frames):
    frame, _ = static_frames[1][0]
    blind = type(frame)(index=0, time=0.0, rgb=frame.rgb, depth=np.zeros_like(frame.depth),
                        intrinsics=frame.intrinsics, camera_pose=frame.camera_pose)
    assert Pipeline().process(blind) == []
    nan = blind.depth.copy()
    nan[:] = np.nan
    blind.depth = nan
    assert Pipeline().process(blind) == []


def test_hand_is_a_skin_segment_and_hides_what_it_holds():
    b = ScenarioBuilder("hand", fps=5)
    b.add("ball_1", "ball", "red", position=(0.0, 0.0))
    b.add("box_1", "box", "green", position=(-0.2, 0.1), size=[0.1, 0.1, 0.1])
    b.pick_up(0.2, "ball_1", duration=1.5)
    with Simulation(b.build(), fps=5) as sim:
        frames = list(sim)
    frame = next(f for f in frames if abs(f.time - 2.0) < 1e-6)
    assert frame.truth["objects"]["ball_1"]["held_by"] == "hand_1"
    percepts = Pipeline().process(frame)
    skin = [p for p in percepts if p.best_category == "skin"]
    assert skin and all(p.truth_id is None for p in skin)
    assert "ball_1" not in [p.truth_id for p in percepts]
    assert "box_1" in [p.truth_id for p in percepts]


def test_stream_round_trip(tmp_path):
    b = ScenarioBuilder("stream", fps=5, duration=0.4)
    b.add("ball_1", "ball", "blue", position=(0.0, 0.0))
    frames = list(perceive_scenario(b.build()))
    assert len(frames) == 3
    path = tmp_path / "p.jsonl"
    write_percepts(path, frames)
    back = list(read_percepts(path))
    assert [len(f.percepts) for f in back] == [1, 1, 1]
    assert back[0].percepts[0].truth_id == "ball_1" and not back[0].rejected
    assert back[0].truth["objects"]["ball_1"]["visible"] is True
    assert back[0].percepts[0].colour_names[0] == "blue"


@pytest.mark.parametrize(("rgb", "name"), [
    ((220, 20, 20), "red"), ((20, 180, 30), "green"), ((20, 60, 220), "blue"),
    ((240, 220, 20), "yellow"), ((250, 250, 250), "white"), ((15, 15, 15), "black"),
    ((110, 110, 110), "gray"), ((130, 40, 190), "purple"), ((255, 128, 0), "orange"),
])
def test_colour_names_from_histogram_peaks(rgb, name):
    image = np.zeros((20, 20, 3), np.uint8)
    image[:] = rgb
    image[:5] = (250, 250, 250)  # a minority of another colour is not named
    mask = np.full((20, 20), 255, np.uint8)
    hist = histogram(hsv_image(image), mask)
    assert hist.shape == (int(np.prod(DEFAULT_BINS)),) and hist.sum() == pytest.approx(1.0)
    assert colour_names(hist)[0] == name
    if name != "white":
        assert "white" not in colour_names(hist)


def test_histogram_bins_are_configurable_and_masked():
    image = np.zeros((10, 10, 3), np.uint8)
    image[:, :5] = (220, 20, 20)
    image[:, 5:] = (20, 60, 220)
    mask = np.zeros((10, 10), np.uint8)
    mask[:, :5] = 255
    bins = (12, 2, 2)
    hist = histogram(hsv_image(image, bins), mask, bins)
    assert hist.shape == (48,) and colour_names(hist, bins) == ["red"]
    assert cv2.countNonZero(mask) == 50


def test_infinite_depth_is_ignored(static_frames):
    frame, clean = static_frames[1][0]
    depth = frame.depth.copy()
    depth[::7, ::5] = np.inf
    noisy = type(frame)(index=0, time=0.0, rgb=frame.rgb, depth=depth,
                        intrinsics=frame.intrinsics, camera_pose=frame.camera_pose,
                        truth=frame.truth, segmentation=frame.segmentation,
                        body_names=frame.body_names)
    percepts = Pipeline().process(noisy)
    assert sorted(str(p.truth_id) for p in percepts) == sorted(str(p.truth_id) for p in clean)
    for p in percepts:
        p.validate()


def test_bigger_frames_give_the_same_percepts():
    scenario = load_scenario(ROOT / "scenarios" / "static.yaml")
    with Simulation(scenario, width=640, height=480, seed=5) as sim:
        frame = sim.step()
    percepts = Pipeline().process(frame)
    assert sorted(p.truth_id for p in percepts) == sorted(scenario.object_ids)
    for p in percepts:
        truth = frame.truth["objects"][p.truth_id]
        assert np.linalg.norm(p.position - np.asarray(truth["position"])) < 0.01
        assert np.all(np.abs(p.size / np.asarray(truth["size"]) - 1) < 0.15)


def test_perception_never_imports_the_simulator() -> None:
    """Any camera's frames go through the pipeline: nothing in perception/ imports tabletop."""
    import ast

    root = Path(__file__).resolve().parents[1] / "python" / "probanchor" / "perception"
    imported = []
    for path in root.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                imported += [(path.name, a.name) for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.module:
                imported.append((path.name, node.module))
    assert imported and not [(f, m) for f, m in imported
        if m.split(".")[:2] == ["probanchor", "tabletop"]]


def test_a_frame_of_another_camera_size_is_perceived_and_a_bad_one_is_a_frame_error() -> None:
    from probanchor.perception import CameraIntrinsics, FrameError, RGBDFrame

    scene = ScenarioBuilder("one_ball", duration=0.1).add("ball_1", "ball", "red",
                                                          position=(0.0, 0.0), radius=0.03)
    with Simulation(scene.build(), width=400, height=300, seed=0) as sim:
        frame = sim.step()
    k = frame.intrinsics
    own = RGBDFrame(0, 0.0, frame.rgb, frame.depth,
                    CameraIntrinsics(k.fx, k.fy, k.cx, k.cy, 400, 300), frame.camera_pose)
    percepts = Pipeline().process(own)
    assert len(percepts) == 1 and percepts[0].category.get("ball", 0) > 0.5
    assert np.allclose(percepts[0].position[:2], (0.0, 0.0), atol=0.01)
    with pytest.raises(FrameError, match="colour image is 400x300 but depth image is 200x150"):
        Pipeline().process(RGBDFrame(0, 0.0, frame.rgb, frame.depth[:150, :200], own.intrinsics,
                                     frame.camera_pose))
    with pytest.raises(FrameError, match="intrinsics are for 320x240 images"):
        Pipeline().process(RGBDFrame(0, 0.0, frame.rgb, frame.depth,
                                     CameraIntrinsics(k.fx, k.fy, k.cx, k.cy, 320, 240),
                                     frame.camera_pose))
