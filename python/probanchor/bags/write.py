"""Writing RGB-D frames (the simulator's, with their ground truth) as a ROS bag.

Per frame: ``/camera/color/image_raw`` (rgb8), ``/camera/depth/image_raw`` (32FC1 metres, so that
the recorded frame is the rendered one to the bit; :func:`probanchor.bags.read_bag` reads 16UC1 as
well), ``/camera/color/camera_info``, the camera pose on ``/tf_static`` (from ``world`` to
``camera_color_optical_frame``, again whenever it changes) and, on topics of their own, the ground
truth: ``/anchoring/ground_truth`` (``std_msgs/String``, JSON with the frame's stamp, its truth and
the names of the label image's bodies) and ``/anchoring/segmentation`` (32SC1, the body seen at each
pixel).
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
from rosbags.rosbag1 import Writer as Writer1
from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Writer2

from probanchor.bags.messages import (
    CAMERA_INFO,
    IMAGE,
    STRING,
    TF,
    MessageFactory,
    is_ros1,
    typestore_for,
)
from probanchor.bags.read import SEGMENTATION_TOPIC, TRUTH_TOPIC, BagError

COLOUR_TOPIC = "/camera/color/image_raw"
DEPTH_TOPIC = "/camera/depth/image_raw"
INFO_TOPIC = "/camera/color/camera_info"
CAMERA_FRAME = "camera_color_optical_frame"
WORLD_FRAME = "world"
START_NS = 1_700_000_000 * 1_000_000_000  # the first frame's stamp (any fixed time will do)


def write_bag(path: str | Path, frames: Iterable[Any]) -> int:
    """Write frames as a bag; its format follows the suffix.

    Parameters
    ----------
    path:
        ``OUT.bag`` (ROS 1), ``OUT.mcap`` or ``OUT.db3`` (ROS 2, one file); it must not
        exist.
    frames:
        :class:`rgbd.RGBDFrame` or alike (``tabletop.Frame``); ``truth``,
        ``segmentation`` and ``body_names`` are written when there.

    Returns
    -------
    How many frames were written. Should writing stop half-way, the frames written so far
    are a readable bag.
    """
    path = Path(path)
    if path.suffix not in (".bag", ".mcap", ".db3"):
        raise BagError(f"{path}: a bag is .bag (ROS 1), .mcap or .db3 (ROS 2)")
    if path.exists():
        raise BagError(f"{path}: exists already, not overwriting")
    path.parent.mkdir(parents=True, exist_ok=True)
    ros1 = is_ros1(path)
    store = typestore_for(ros1)
    factory = MessageFactory(store)
    serialize = store.serialize_ros1 if ros1 else store.serialize_cdr
    staging = path.with_name(path.name + ".part")
    if staging.exists():
        shutil.rmtree(staging) if staging.is_dir() else staging.unlink()
    if ros1:
        writer: Any = Writer1(staging)
    else:
        plugin = StoragePlugin.MCAP if path.suffix == ".mcap" else StoragePlugin.SQLITE3
        writer = Writer2(staging, version=9, storage_plugin=plugin)
    count = 0
    with writer:
        def connect(topic: str, msgtype: str) -> Any:
            return writer.add_connection(topic, msgtype, typestore=store)

        conns = {"colour": connect(COLOUR_TOPIC, IMAGE), "depth": connect(DEPTH_TOPIC, IMAGE),
                 "info": connect(INFO_TOPIC, CAMERA_INFO), "tf": connect("/tf_static", TF),
                 "truth": connect(TRUTH_TOPIC, STRING),
                 "labels": connect(SEGMENTATION_TOPIC, IMAGE)}

        def put(kind: str, stamp: int, msg: Any) -> None:
            writer.write(conns[kind], stamp, serialize(msg, msg.__msgtype__))

        last_pose: np.ndarray | None = None
        for frame in frames:
            stamp = START_NS + int(round(float(frame.time) * 1e9))
            pose = np.asarray(frame.camera_pose, dtype=float)
            if last_pose is None or not np.array_equal(pose, last_pose):
                put("tf", stamp, factory.tf(stamp, WORLD_FRAME, CAMERA_FRAME, pose))
                last_pose = pose
            names = {str(k): v for k, v in (getattr(frame, "body_names", None) or {}).items()}
            record = {"stamp_ns": stamp, "frame": int(frame.index),
                      "truth": getattr(frame, "truth", None) or {}, "body_names": names}
            put("truth", stamp, factory.string(json.dumps(record)))
            labels = getattr(frame, "segmentation", None)
            if labels is not None:
                put("labels", stamp, factory.image(stamp, CAMERA_FRAME,
                                                   np.asarray(labels, dtype="<i4"), "32SC1"))
            if count == 0:
                put("info", stamp, factory.camera_info(stamp, CAMERA_FRAME, frame.intrinsics))
            put("colour", stamp, factory.image(stamp, CAMERA_FRAME, frame.rgb, "rgb8"))
            put("depth", stamp, factory.image(stamp, CAMERA_FRAME,
                                              np.asarray(frame.depth, dtype="<f4"), "32FC1"))
            count += 1
    _settle(staging, path)
    return count


def _settle(staging: Path, path: Path) -> None:
    """Move the written bag to its name: a ROS 1 file as it is, a rosbag2 directory's one
    storage file (which holds the schemas it needs) without its directory."""
    if staging.is_file():
        staging.rename(path)
        return
    files = [f for f in staging.iterdir() if f.suffix == path.suffix]
    if len(files) != 1:
        raise BagError(f"{path}: the writer made {len(files)} storage files in {staging}")
    files[0].rename(path)
    shutil.rmtree(staging)
