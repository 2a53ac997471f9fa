"""RGB-D bags in and out: a scenario recorded as a bag and played from it gives the run the
scenario gives; other cameras' encodings, tf chains and unpaired images; bad bags name the
file and the cause."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2

from probanchor.bags import BagError, BagTopics, bag_topics, read_bag, write_bag
from probanchor.bags.messages import (
    CAMERA_INFO,
    IMAGE,
    STRING,
    TF,
    MessageFactory,
    typestore_for,
)
from probanchor.bags.read import TRUTH_TOPIC
from probanchor.cli.anchoring_cli import main as anchoring
from probanchor.loop.runner import RunOptions, run
from probanchor.perception import CameraIntrinsics
from probanchor.tabletop import Simulation, load_scenario
from scenario_helpers import scenario_file


@pytest.fixture(scope="module")
def scenario(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return scenario_file(tmp_path_factory)


@pytest.fixture(scope="module")
def frames(scenario: Path) -> list:
    with Simulation(load_scenario(scenario), seed=0) as sim:
        return list(sim)


@pytest.mark.parametrize("suffix", [".mcap", ".db3", ".bag"])
def test_frames_come_back_from_each_format_as_they_were_written(tmp_path: Path, frames: list,
                                                                suffix: str) -> None:
    path = tmp_path / f"run{suffix}"
    assert write_bag(path, frames[:4]) == 4
    assert not (tmp_path / f"run{suffix}.part").exists()
    back = list(read_bag(path))
    assert len(back) == 4
    for a, b in zip(frames, back, strict=False):
        assert np.array_equal(a.rgb, b.rgb) and np.array_equal(a.depth, b.depth)
        assert np.array_equal(a.segmentation, b.segmentation)
        assert np.allclose(a.camera_pose, b.camera_pose, atol=1e-12)
        assert abs(a.time - b.time) < 1e-9 and a.index == b.index
        assert a.truth == b.truth and a.body_names == b.body_names
        assert (b.intrinsics.fx, b.intrinsics.width) == (a.intrinsics.fx, a.intrinsics.width)


def test_a_recorded_run_played_from_its_bag_gives_the_scenarios_run(tmp_path: Path,
                                                                     scenario: Path) -> None:
    bag = tmp_path / "recorded.mcap"
    assert anchoring(["record", str(scenario), "--bag", str(bag)]) == 0
    from_bag = run(RunOptions(bag=bag, particles=60, seed=0, progress=False))
    direct = run(RunOptions(scenario=scenario, particles=60, seed=0, progress=False))
    assert len(from_bag.records) == len(direct.records) == 46
    for a, b in zip(from_bag.records, direct.records, strict=True):
        assert a.assignments == b.assignments and set(a.hypotheses) == set(b.hypotheses)
    symbols = {o["id"]: o["symbols"] for o in from_bag.summary["objects"]}
    assert symbols == {o["id"]: o["symbols"] for o in direct.summary["objects"]}
    kept = {o["id"]: o["identity_kept"] for o in from_bag.summary["objects"]}
    assert kept["ball_1"] and len(symbols["ball_1"]) == 1  # re-acquired under the moved mug


def _write(path: Path, messages: list[tuple[str, str, int, object]]) -> Path:
    """A bag of hand-made messages: (topic, type, stamp, message)."""
    ros1 = path.suffix == ".bag"
    store = typestore_for(ros1)
    serialize = store.serialize_ros1 if ros1 else store.serialize_cdr
    writer = Writer1(path) if ros1 else Writer2(path, version=9,
                                                 storage_plugin=StoragePlugin.MCAP)
    with writer:
        conns: dict[str, object] = {}
        for topic, msgtype, stamp, msg in messages:
            if topic not in conns:
                conns[topic] = writer.add_connection(topic, msgtype, typestore=store)
            writer.write(conns[topic], stamp, serialize(msg, msgtype))
    return path if ros1 else next(path.glob("*.mcap"))


K = CameraIntrinsics(300.0, 300.0, 159.5, 119.5, 320, 240)


def _camera_bag(path: Path, frames: list, depth_size: tuple[int, int] | None = None,
                depth: bool = True, tf: bool = True, drop_depth_of: int = -1) -> Path:
    """A bag as a RealSense driver writes it: bgr8 colour, 16UC1 aligned depth, the optical
    frame under camera_link under world (one static and one dynamic transform)."""
    make = MessageFactory(typestore_for(path.suffix == ".bag"))
    pose = frames[0].camera_pose
    link = np.eye(4)
    link[:3, 3] = (0.0, 0.0, 0.05)
    messages: list[tuple[str, str, int, object]] = []
    base = 5 * 10**9
    if tf:
        messages.append(("/tf_static", TF, base, make.tf(base, "camera_link",
                                                         "camera_color_optical_frame", link)))
    for i, frame in enumerate(frames):
        stamp = base + i * 100_000_000
        if i == 0:
            messages.append(("/camera/color/camera_info", CAMERA_INFO, stamp,
                             make.camera_info(stamp, "camera_color_optical_frame", K)))
        if tf:
            messages.append(("/tf", TF, stamp, make.tf(stamp, "world", "camera_link",
                                                       pose @ np.linalg.inv(link))))
        messages.append(("/camera/color/image_raw", IMAGE, stamp,
                         make.image(stamp, "camera_color_optical_frame",
                                    frame.rgb[:, :, ::-1], "bgr8")))
        if depth and i != drop_depth_of:
            mm = np.round(frame.depth * 1000).astype("<u2")
            if depth_size is not None:
                mm = mm[: depth_size[1], : depth_size[0]]
            messages.append(("/camera/aligned_depth_to_color/image_raw", IMAGE, stamp + 3_000_000,
                             make.image(stamp + 3_000_000, "camera_color_optical_frame", mm,
                                        "16UC1")))
    return _write(path, messages)


@pytest.mark.parametrize("suffix", [".mcap", ".bag"])
def test_a_driver_bag_bgr_millimetres_tf_chain_and_stamps(tmp_path: Path, frames: list,
                                                          suffix: str) -> None:
    path = _camera_bag(tmp_path / f"driver{suffix}", frames[:5], drop_depth_of=2)
    topics = BagTopics()
    back = list(read_bag(path, topics))
    assert [f.index for f in back] == [0, 1, 2, 3]
    assert [round(f.time, 6) for f in back] == [0.0, 0.1, 0.3, 0.4]  # the bag's stamps
    assert len(topics.skipped) == 1 and "no depth image" in topics.skipped[0]
    assert np.array_equal(back[0].rgb, frames[0].rgb)
    assert np.abs(back[0].depth - frames[0].depth).max() <= 0.0005 + 1e-6  # millimetres
    assert np.allclose(back[0].camera_pose, frames[0].camera_pose, atol=1e-9)
    assert back[0].intrinsics == K and back[0].truth == {}


def test_a_given_extrinsic_replaces_tf(tmp_path: Path, frames: list) -> None:
    path = _camera_bag(tmp_path / "notf.mcap", frames[:2], tf=False)
    with pytest.raises(BagError, match=r"notf.*\.mcap: frame 0 .*no transform from world"):
        list(read_bag(path))
    pose = np.eye(4)
    back = list(read_bag(path, BagTopics(camera_pose=pose)))
    assert np.array_equal(back[1].camera_pose, pose)


def test_a_bag_without_depth_names_the_file_and_lists_its_topics(tmp_path: Path,
                                                                 frames: list) -> None:
    path = _camera_bag(tmp_path / "nodepth.mcap", frames[:2], depth=False)
    with pytest.raises(BagError) as error:
        list(read_bag(path))
    message = str(error.value)
    assert str(path) in message and "no depth image topic" in message
    assert "/camera/color/image_raw (sensor_msgs/msg/Image)" in message
    assert "--depth-topic" in message
    with pytest.raises(BagError, match="depth topic /nothing is not in the bag"):
        list(read_bag(path, BagTopics(depth="/nothing")))
    # the run says so too, before any frame
    assert anchoring(["run", "--bag", str(path), "--quiet", "--no-reasoning"]) == 1


def test_mismatched_image_sizes_name_the_file_and_frame(tmp_path: Path, frames: list) -> None:
    path = _camera_bag(tmp_path / "sizes.mcap", frames[:2], depth_size=(160, 120))
    with pytest.raises(BagError, match=r"sizes\.mcap\.mcap: frame 0 .*colour image is "
                                       r"320x240 but depth image is 160x120"):
        list(read_bag(path))


def test_a_file_that_is_not_a_bag(tmp_path: Path) -> None:
    path = tmp_path / "junk.mcap"
    path.write_bytes(b"not a bag at all")
    with pytest.raises(BagError, match=r"junk\.mcap: not a readable ROS bag"):
        bag_topics(path)
    with pytest.raises(BagError, match="no such bag"):
        bag_topics(tmp_path / "missing.bag")


def test_writing_never_overwrites(tmp_path: Path, frames: list) -> None:
    path = tmp_path / "kept.mcap"
    write_bag(path, frames[:1])
    size = path.stat().st_size
    with pytest.raises(BagError, match="exists already"):
        write_bag(path, frames[:2])
    assert path.stat().st_size == size and len(list(read_bag(path))) == 1


def _stamped_bag(path: Path, frames: list, stamps: list[int], truths: list[str] | None = None,
                 sizes: dict[int, tuple[int, int]] | None = None) -> Path:
    """A bag whose i-th colour image has header stamp ``stamps[i]`` (its depth 3 ms later),
    each recorded 0.1 s after the one before; ``truths``: the ground-truth message of each
    frame; ``sizes``: frame -> the depth image's (width, height)."""
    make = MessageFactory(typestore_for(False))
    messages: list[tuple[str, str, int, object]] = []
    for i, (frame, stamp) in enumerate(zip(frames, stamps, strict=True)):
        logged = 1_700_000_000 * 10**9 + i * 100_000_000
        if i == 0:
            messages.append(("/camera/color/camera_info", CAMERA_INFO, logged,
                             make.camera_info(stamp, "cam", K)))
        if truths is not None:
            messages.append((TRUTH_TOPIC, STRING, logged, make.string(truths[i])))
        messages.append(("/camera/color/image_raw", IMAGE, logged,
                         make.image(stamp, "cam", frame.rgb, "rgb8")))
        depth = np.asarray(frame.depth, dtype="<f4")
        if sizes and i in sizes:
            depth = depth[: sizes[i][1], : sizes[i][0]]
        messages.append(("/camera/depth/image_raw", IMAGE, logged + 1,
                         make.image(stamp + 3_000_000, "cam", depth, "32FC1")))
    return _write(path, messages)


def test_frames_with_bad_stamps_are_skipped_and_named(tmp_path: Path, frames: list) -> None:
    base = 1_700_000_000 * 10**9
    good = [base + i * 100_000_000 for i in range(8)]
    stamps = list(good)
    stamps[2] = 0                                       # a stamp the driver never set
    stamps[4] = 2_145_916_800 * 10**9                   # 2038
    stamps[6] = good[4]                                 # before frame 5's: out of order
    path = _stamped_bag(tmp_path / "stamps.mcap", frames[:8], stamps)
    topics = BagTopics(camera_pose=np.eye(4))
    back = list(read_bag(path, topics))
    times = [round(f.time, 6) for f in back]
    assert times == [0.0, 0.1, 0.3, 0.5, 0.7]           # frames 0, 1, 3, 5, 7 of the bag
    assert [f.index for f in back] == [0, 1, 2, 3, 4]
    assert len(topics.skipped) == 3
    assert all(str(path) in m and "/camera/color/image_raw" in m for m in topics.skipped)
    zero, future, early = topics.skipped
    assert "after frame 1: its stamp is zero" in zero
    assert "after frame 2:" in future and "ahead of the time the bag recorded it" in future
    assert "after frame 3:" in early and "out of order or repeated" in early
    run_output = run(RunOptions(bag=path, bag_topics=BagTopics(camera_pose=np.eye(4)),
                                reasoning=False, progress=False))
    assert run_output.summary["skipped_frames"] == 3 and len(run_output.records) == 5
    assert [r.time for r in run_output.records] == pytest.approx([0.0, 0.1, 0.3, 0.5, 0.7])


def test_an_image_size_that_changes_stops_the_run_after_the_frame_before(
        tmp_path: Path, frames: list) -> None:
    base = 1_700_000_000 * 10**9
    path = _stamped_bag(tmp_path / "resized.mcap", frames[:10],
                        [base + i * 100_000_000 for i in range(10)], sizes={8: (160, 120)})
    out = tmp_path / "out"
    with pytest.raises(BagError, match=r"resized.*\.mcap: frame 8 \(/camera/color/image_raw "
                                       r"at 0\.800 s\): colour image is 320x240 but depth"):
        run(RunOptions(bag=path, bag_topics=BagTopics(camera_pose=np.eye(4)), reasoning=False,
                       progress=False, out=out))
    assert len((out / "records.jsonl").read_text().splitlines()) == 8   # frames 0-7 kept
    assert "stopped" in (out / "summary.json").read_text()


def test_a_ground_truth_that_is_not_json_names_file_topic_and_frame(tmp_path: Path,
                                                                   frames: list) -> None:
    base = 1_700_000_000 * 10**9
    stamps = [base + i * 100_000_000 for i in range(6)]
    truths = [json.dumps({"stamp_ns": s, "frame": i, "truth": frames[i].truth,
                          "body_names": {}}) for i, s in enumerate(stamps)]
    truths[4] = "{'not': json"
    path = _stamped_bag(tmp_path / "truth.mcap", frames[:6], stamps, truths=truths)
    out = tmp_path / "out"
    with pytest.raises(BagError, match=r"truth.*\.mcap: frame 4 \(/anchoring/ground_truth, "
                                       r"recorded at \d+ ns\): the ground truth is not a JSON "
                                       r"object with stamp_ns: JSONDecodeError"):
        run(RunOptions(bag=path, bag_topics=BagTopics(camera_pose=np.eye(4)), reasoning=False,
                       progress=False, out=out))
    records = (out / "records.jsonl").read_text().splitlines()
    assert len(records) == 4 and json.loads(records[3])["frame"] == 3  # frame 3 kept


def test_a_bag_run_resumes_from_its_store_alone_with_its_topics_and_bytes(
        tmp_path: Path, frames: list) -> None:
    from probanchor.loop.store import StoreError

    base = 1_700_000_000 * 10**9
    path = _stamped_bag(tmp_path / "kept.mcap", frames[:4],
                        [base + i * 100_000_000 for i in range(4)])
    db = tmp_path / "world.db"
    topics = BagTopics(camera_pose=np.eye(4), max_lead=5.0)
    first = run(RunOptions(bag=path, bag_topics=topics, reasoning=False, progress=False,
                           store=db))
    again = run(RunOptions(resume=db, progress=False))  # the stored topics and pose adopted
    assert len(again.records) == len(first.records) == 4
    with pytest.raises(StoreError, match=r"not this run's store: it has bag_topics .*"
                                         r"\"max_lead\": 5\.0"):
        run(RunOptions(resume=db, bag=path, bag_topics=BagTopics(camera_pose=np.eye(4)),
                       progress=False))
    with open(path, "ab") as data:  # the recording changed since
        data.write(b"\0")
    with pytest.raises(StoreError, match=r"a store from another bag: .*kept.*\.mcap changed"):
        run(RunOptions(resume=db, progress=False))
