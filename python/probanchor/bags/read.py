"""Reading RGB-D frames from a ROS 1 or ROS 2 bag.

Colour and depth images are paired by their header stamps (the nearest within
``BagTopics.max_skew`` seconds; an image left without a partner is skipped and counted); each
pair is one :class:`rgbd.RGBDFrame` at the colour image's stamp, in seconds from the
first pair's. The intrinsics are the first ``CameraInfo`` of the colour camera; the camera
pose is the chain of ``/tf_static`` and ``/tf`` transforms from the world frame to the colour
image's ``frame_id`` (each dynamic transform the latest at or before the frame's stamp), or
the extrinsic the caller gives. The simulator's ground truth, when the bag was written by
:func:`probanchor.bags.write_bag`, comes back on the frames for evaluation.
"""

from __future__ import annotations

import json
import logging
from collections import deque
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.highlevel import AnyReader, AnyReaderError

from probanchor.bags.messages import (
    CAMERA_INFO,
    IMAGE,
    STRING,
    TF,
    camera_matrix,
    colour_image,
    depth_image,
    is_ros1,
    label_image,
    stamp_ns,
    transform_matrix,
    typestore_for,
)
from probanchor.perception.camera import FrameError, check_frame
from probanchor.rgbd import CameraIntrinsics, RGBDFrame

logger = logging.getLogger(__name__)

COLOUR_TOPICS = ("/camera/color/image_raw", "/camera/rgb/image_raw", "/camera/image_raw")
DEPTH_TOPICS = ("/camera/aligned_depth_to_color/image_raw", "/camera/depth_registered/image_raw",
                "/camera/depth/image_raw", "/camera/depth/image_rect_raw")
TRUTH_TOPIC = "/anchoring/ground_truth"
SEGMENTATION_TOPIC = "/anchoring/segmentation"


class BagError(ValueError):
    """A bag that cannot be played; the message names the file and the cause."""


@dataclass
class BagTopics:
    """Which topics hold what; None takes the first of the usual names the bag has."""

    colour: str | None = None
    depth: str | None = None
    camera_info: str | None = None  # default: camera_info beside the colour topic
    world_frame: str = "world"
    camera_pose: np.ndarray | None = None  # 4x4 world-from-camera: no tf needed
    max_skew: float = 0.02  # seconds between the stamps of a colour and a depth image
    # seconds a colour image's stamp may be ahead of the time the bag recorded it (a camera
    # cannot stamp an image after it was recorded, but two machines' clocks may differ)
    max_lead: float = 60.0
    # images without a partner and frames with a bad stamp, skipped (filled in)
    skipped: list[str] = field(default_factory=list)


def bag_topics(path: str | Path) -> dict[str, str]:
    """The topics of a bag and their message types.

    Parameters
    ----------
    path:
        A ``.bag``, ``.db3`` or ``.mcap`` file or a rosbag2 directory.

    Returns
    -------
    Topic -> message type; a :class:`BagError` naming the file when it cannot be opened.
    """
    with _open(Path(path)) as reader:
        return {c.topic: c.msgtype for c in reader.connections}


@contextmanager
def _open(path: Path) -> Iterator[AnyReader]:
    if not path.exists():
        raise BagError(f"{path}: no such bag")
    try:
        reader = AnyReader([path], default_typestore=typestore_for(is_ros1(path)))
        reader.open()
    except (AnyReaderError, OSError, ValueError, KeyError) as exc:
        raise BagError(f"{path}: not a readable ROS bag: {exc}") from None
    try:
        yield reader
    finally:
        reader.close()


def _choose(path: Path, topics: dict[str, str], given: str | None, usual: tuple[str, ...],
            what: str, flag: str) -> str:
    images = [t for t, kind in topics.items() if kind == IMAGE]
    if given is not None:
        if topics.get(given) == IMAGE:
            return given
        cause = "is not in the bag" if given not in topics else f"is {topics[given]}"
        raise BagError(f"{path}: {what} topic {given} {cause}; {_listing(topics)}")
    for name in usual:
        if topics.get(name) == IMAGE:
            return name
    raise BagError(f"{path}: no {what} image topic ({' or '.join(usual)}); give one with "
                   f"{flag}; {_listing(topics)}" + ("" if images else "; the bag has no images"))


def _listing(topics: dict[str, str]) -> str:
    return "the bag has " + (", ".join(f"{t} ({k})" for t, k in sorted(topics.items()))
                             or "no topics")


class _Transforms:
    """The bag's transforms: static ones and, per child frame, the dynamic ones in time."""

    def __init__(self) -> None:
        self.static: dict[str, tuple[str, np.ndarray]] = {}
        self.dynamic: dict[str, list[tuple[int, str, np.ndarray]]] = {}

    def add(self, msg: Any, static: bool) -> None:
        for t in msg.transforms:
            parent, child = t.header.frame_id.lstrip("/"), t.child_frame_id.lstrip("/")
            if static:
                self.static[child] = (parent, transform_matrix(t.transform))
            else:
                self.dynamic.setdefault(child, []).append(
                    (stamp_ns(t.header), parent, transform_matrix(t.transform)))

    def lookup(self, world: str, frame: str, stamp: int) -> np.ndarray | None:
        """world-from-frame at ``stamp``, or None when no chain joins them."""
        pose = np.eye(4)
        seen = set()
        while frame != world:
            if frame in seen:
                return None
            seen.add(frame)
            if frame in self.static:
                parent, step = self.static[frame]
            elif frame in self.dynamic:
                times = [s for s, _, _ in self.dynamic[frame]]
                i = int(np.searchsorted(times, stamp, side="right")) - 1
                _, parent, step = self.dynamic[frame][max(i, 0)]
            else:
                return None
            pose = step @ pose
            frame = parent
        return pose

    def frames(self) -> list[str]:
        names = set(self.static) | set(self.dynamic)
        names |= {p for p, _ in self.static.values()}
        names |= {p for v in self.dynamic.values() for _, p, _ in v}
        return sorted(names)


def read_bag(path: str | Path, topics: BagTopics | None = None) -> Iterator[RGBDFrame]:
    """The RGB-D frames of a bag, at its time stamps.

    Parameters
    ----------
    path:
        A ``.bag`` (ROS 1), ``.db3`` or ``.mcap`` (ROS 2) file or a rosbag2 directory.
    topics:
        Topics, world frame, extrinsic and pairing tolerance (:class:`BagTopics`); images
        left without a partner are appended to its ``skipped``.

    Returns
    -------
    The frames in time order; a :class:`BagError` naming the file (and the frame and topic)
    for a missing topic, an unknown encoding, images of different sizes, a pose not in the
    bag or a ground-truth message that cannot be read. A frame whose colour image has a bad
    stamp is skipped and said in ``topics.skipped``, as a percept stream skips a line whose
    time is bad: a zero stamp, one that is not after the previous frame's (out of order or
    repeated), or one more than ``topics.max_lead`` seconds ahead of the time the bag
    recorded the image (a clock far off: a stamp in 2038).
    """
    path = Path(path)
    topics = topics or BagTopics()
    with _open(path) as reader:
        available = {c.topic: c.msgtype for c in reader.connections}
        colour = _choose(path, available, topics.colour, COLOUR_TOPICS, "colour",
                         "--colour-topic")
        depth = _choose(path, available, topics.depth, DEPTH_TOPICS, "depth", "--depth-topic")
        info_topic = topics.camera_info or colour.rsplit("/", 1)[0] + "/camera_info"
        if available.get(info_topic) != CAMERA_INFO:
            raise BagError(f"{path}: no camera info topic {info_topic} (sensor_msgs/CameraInfo)"
                           f"; give one with --info-topic; {_listing(available)}")
        intrinsics, transforms = _calibration(path, reader, info_topic, topics)
        yield from _frames(path, reader, colour, depth, intrinsics, transforms, topics)


def _calibration(path: Path, reader: AnyReader, info_topic: str, topics: BagTopics
                 ) -> tuple[CameraIntrinsics, _Transforms]:
    wanted = [c for c in reader.connections if c.topic in (info_topic, "/tf", "/tf_static")]
    intrinsics = None
    transforms = _Transforms()
    for connection, _, raw in reader.messages(connections=wanted):
        if connection.topic == info_topic:
            if intrinsics is None:
                msg = reader.deserialize(raw, connection.msgtype)
                k = camera_matrix(msg)
                intrinsics = CameraIntrinsics(float(k[0, 0]), float(k[1, 1]), float(k[0, 2]),
                                              float(k[1, 2]), int(msg.width), int(msg.height))
        elif topics.camera_pose is None and connection.msgtype == TF:
            transforms.add(reader.deserialize(raw, connection.msgtype),
                           static=connection.topic == "/tf_static")
    if intrinsics is None:
        raise BagError(f"{path}: camera info topic {info_topic} has no message")
    return intrinsics, transforms


def _frames(path: Path, reader: AnyReader, colour: str, depth: str,
            intrinsics: CameraIntrinsics, transforms: _Transforms, topics: BagTopics
            ) -> Iterator[RGBDFrame]:
    wanted = [c for c in reader.connections
              if c.topic in (colour, depth, TRUTH_TOPIC, SEGMENTATION_TOPIC)]
    colours: deque[tuple[int, Any]] = deque()
    depths: deque[tuple[int, Any]] = deque()
    truths: dict[int, dict[str, Any]] = {}
    labels: dict[int, Any] = {}
    ready: deque[tuple[int, tuple[tuple[int, Any], tuple[int, Any]]]] = deque()  # logged, pair
    skew = int(topics.max_skew * 1e9)
    lead = int(topics.max_lead * 1e9)
    first: int | None = None
    last: int | None = None  # the stamp of the last frame given
    index = 0

    def bad_stamp(stamp: int, logged: int) -> str | None:
        if stamp == 0:
            return "its stamp is zero (not set by the driver?)"
        if last is not None and stamp <= last:
            return (f"its stamp is {(stamp - last) / 1e9:+.3f} s from the previous frame's "
                    "(out of order or repeated)")
        if stamp - logged > lead:
            return (f"its stamp is {(stamp - logged) / 1e9:.3f} s ahead of the time the bag "
                    f"recorded it (more than {topics.max_lead:g} s: a clock far off)")
        return None

    def emit(logged: int, pair: tuple[tuple[int, Any], tuple[int, Any]]) -> RGBDFrame | None:
        nonlocal first, last, index
        (stamp, cmsg), (_, dmsg) = pair
        bad = bad_stamp(stamp, logged)
        if bad is not None:
            topics.skipped.append(f"{path}: {colour} image at stamp {stamp} ns, after frame "
                                  f"{index - 1}: {bad}")
            truths.pop(stamp, None)
            labels.pop(stamp, None)
            return None
        first = stamp if first is None else first
        last = stamp
        where = f"{path}: frame {index} ({colour} at {(stamp - first) / 1e9:.3f} s)"
        try:
            rgb, dep = colour_image(cmsg), depth_image(dmsg)
        except ValueError as exc:
            raise BagError(f"{where}: {exc}") from None
        pose = topics.camera_pose if topics.camera_pose is not None else \
            transforms.lookup(topics.world_frame, cmsg.header.frame_id.lstrip("/"), stamp)
        if pose is None:
            raise BagError(
                f"{where}: no transform from {topics.world_frame} to the camera's frame "
                f"{cmsg.header.frame_id!r} in /tf or /tf_static (frames: "
                f"{', '.join(transforms.frames()) or 'none'}); give the world frame with "
                "--world-frame or the pose with --camera-pose")
        truth = truths.pop(stamp, {})
        label = labels.pop(stamp, None)
        frame = RGBDFrame(index, (stamp - first) / 1e9, rgb, dep, intrinsics,
                          np.asarray(pose, dtype=float), truth.get("truth", {}),
                          label_image(label) if label is not None else None,
                          {int(k): v for k, v in truth.get("body_names", {}).items()})
        try:
            check_frame(frame)
        except FrameError as exc:
            raise BagError(f"{where}: {exc}") from None
        index += 1
        return frame

    for connection, logged, raw in reader.messages(connections=wanted):
        while ready and ready[0][0] < logged:  # its ground truth, logged with it, is in
            frame = emit(*ready.popleft())
            if frame is not None:
                yield frame
        msg = reader.deserialize(raw, connection.msgtype)
        if connection.topic == TRUTH_TOPIC and connection.msgtype == STRING:
            try:
                record = json.loads(msg.data)
                truths[int(record["stamp_ns"])] = record
            except (ValueError, KeyError, TypeError, AttributeError) as exc:
                raise BagError(f"{path}: frame {index + len(ready)} ({TRUTH_TOPIC}, recorded "
                               f"at {logged} ns): the ground truth is not a JSON object with "
                               f"stamp_ns: {type(exc).__name__}: {exc}") from None
            continue
        if connection.topic == SEGMENTATION_TOPIC:
            labels[stamp_ns(msg.header)] = msg
            continue
        (colours if connection.topic == colour else depths).append((stamp_ns(msg.header), msg))
        while colours and depths:
            (tc, _), (td, _) = colours[0], depths[0]
            if abs(tc - td) <= skew:
                ready.append((logged, (colours.popleft(), depths.popleft())))
            elif tc < td:
                colours.popleft()
                topics.skipped.append(f"{path}: {colour} at stamp {tc}: no depth image within "
                                      f"{topics.max_skew} s")
            else:
                depths.popleft()
                topics.skipped.append(f"{path}: {depth} at stamp {td}: no colour image within "
                                      f"{topics.max_skew} s")
    while ready:
        frame = emit(*ready.popleft())
        if frame is not None:
            yield frame
    topics.skipped.extend(f"{path}: {colour} at stamp {t}: no depth image" for t, _ in colours)
    topics.skipped.extend(f"{path}: {depth} at stamp {t}: no colour image" for t, _ in depths)
