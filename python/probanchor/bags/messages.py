"""ROS messages <-> numpy: images, camera info, transforms; the type stores of ROS 1 and 2."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from rosbags.typesys import Stores, get_types_from_msg, get_typestore
from rosbags.typesys.store import Typestore
from scipy.spatial.transform import Rotation

IMAGE = "sensor_msgs/msg/Image"
CAMERA_INFO = "sensor_msgs/msg/CameraInfo"
TF = "tf2_msgs/msg/TFMessage"
STRING = "std_msgs/msg/String"

COLOUR_ENCODINGS = {"rgb8": (3, False), "bgr8": (3, True), "rgba8": (4, False),
                    "bgra8": (4, True)}  # channels, reversed
DEPTH_ENCODINGS = {"16UC1": "u2", "mono16": "u2", "32FC1": "f4"}


def is_ros1(path: Path) -> bool:
    """A ROS 1 bag (``.bag``) rather than a ROS 2 one (``.db3``, ``.mcap``, a directory)."""
    return path.suffix == ".bag"


def typestore_for(ros1: bool) -> Typestore:
    """The message types of ROS 1 Noetic or ROS 2 Humble, with ``tf2_msgs/TFMessage``."""
    store = get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_HUMBLE)
    if TF not in store.types:
        store.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", TF))
    return store


def stamp_ns(header: Any) -> int:
    """A header's time stamp in nanoseconds."""
    return int(header.stamp.sec) * 1_000_000_000 + int(header.stamp.nanosec)


def _pixels(msg: Any, dtype: str, channels: int) -> np.ndarray:
    order = ">" if msg.is_bigendian else "<"
    itemsize = np.dtype(dtype).itemsize
    row = np.frombuffer(bytes(msg.data), dtype=np.uint8).reshape(msg.height, msg.step)
    pixels = row[:, : msg.width * channels * itemsize].copy().view(order + dtype)
    return pixels.reshape(msg.height, msg.width, channels) if channels > 1 \
        else pixels.reshape(msg.height, msg.width)


def colour_image(msg: Any) -> np.ndarray:
    """An 8-bit colour image as uint8 HxWx3 RGB; ValueError for another encoding."""
    if msg.encoding not in COLOUR_ENCODINGS:
        raise ValueError(f"colour encoding {msg.encoding!r} is not one of "
                         f"{', '.join(COLOUR_ENCODINGS)}")
    channels, reverse = COLOUR_ENCODINGS[msg.encoding]
    rgb = _pixels(msg, "u1", channels)[:, :, :3]
    return np.ascontiguousarray(rgb[:, :, ::-1] if reverse else rgb)


def depth_image(msg: Any) -> np.ndarray:
    """A depth image as float32 HxW metres, 0 where there is no return; ValueError for an
    encoding that is not 16UC1 (millimetres) or 32FC1 (metres)."""
    if msg.encoding not in DEPTH_ENCODINGS:
        raise ValueError(f"depth encoding {msg.encoding!r} is not 16UC1 (millimetres) or "
                         "32FC1 (metres)")
    raw = _pixels(msg, DEPTH_ENCODINGS[msg.encoding], 1)
    depth = raw.astype(np.float32) / np.float32(1000.0) if raw.dtype.kind == "u" \
        else raw.astype(np.float32)
    depth[~np.isfinite(depth)] = 0.0
    return depth


def label_image(msg: Any) -> np.ndarray:
    """A 32SC1 label image (the simulator's body per pixel) as int32 HxW."""
    return _pixels(msg, "i4", 1)


def camera_matrix(msg: Any) -> np.ndarray:
    """The 3x3 K of a ``CameraInfo`` (``k`` in ROS 2, ``K`` in ROS 1)."""
    return np.asarray(getattr(msg, "k", None) if hasattr(msg, "k") else msg.K,
                      dtype=float).reshape(3, 3)


def transform_matrix(transform: Any) -> np.ndarray:
    """The 4x4 matrix of a ``geometry_msgs/Transform``."""
    q, t = transform.rotation, transform.translation
    out = np.eye(4)
    out[:3, :3] = Rotation.from_quat([q.x, q.y, q.z, q.w]).as_matrix()
    out[:3, 3] = (t.x, t.y, t.z)
    return out


def pose_matrix(values: list[float]) -> np.ndarray:
    """A 4x4 pose from ``x y z qx qy qz qw`` (the quaternion need not be normalised)."""
    if len(values) != 7:
        raise ValueError(f"a pose is 7 numbers 'x y z qx qy qz qw', got {len(values)}")
    out = np.eye(4)
    out[:3, :3] = Rotation.from_quat(values[3:]).as_matrix()
    out[:3, 3] = values[:3]
    return out


class MessageFactory:
    """Builds the messages of one type store (ROS 1 headers have a ``seq``)."""

    def __init__(self, store: Typestore) -> None:
        self.store = store
        self.types = store.types

    def header(self, stamp: int, frame_id: str) -> Any:
        time = self.types["builtin_interfaces/msg/Time"](sec=stamp // 1_000_000_000,
                                                         nanosec=stamp % 1_000_000_000)
        cls = self.types["std_msgs/msg/Header"]
        if "seq" in cls.__dataclass_fields__:
            return cls(seq=0, stamp=time, frame_id=frame_id)
        return cls(stamp=time, frame_id=frame_id)

    def image(self, stamp: int, frame_id: str, pixels: np.ndarray, encoding: str) -> Any:
        pixels = np.ascontiguousarray(pixels)
        h, w = pixels.shape[:2]
        data = pixels.view(np.uint8).reshape(-1)
        return self.types[IMAGE](header=self.header(stamp, frame_id), height=h, width=w,
                                 encoding=encoding, is_bigendian=0, step=data.size // h,
                                 data=data)

    def camera_info(self, stamp: int, frame_id: str, k: Any) -> Any:
        cls = self.types[CAMERA_INFO]
        kmat = np.array([k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0])
        pmat = np.array([k.fx, 0.0, k.cx, 0.0, 0.0, k.fy, k.cy, 0.0, 0.0, 0.0, 1.0, 0.0])
        roi = self.types["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0,
                                                            width=0, do_rectify=False)
        upper = "K" in cls.__dataclass_fields__
        matrices = {("D" if upper else "d"): np.zeros(5), ("K" if upper else "k"): kmat,
                    ("R" if upper else "r"): np.eye(3).reshape(-1),
                    ("P" if upper else "p"): pmat}
        return cls(header=self.header(stamp, frame_id), height=int(k.height),
                   width=int(k.width), distortion_model="plumb_bob", binning_x=0, binning_y=0,
                   roi=roi, **matrices)

    def tf(self, stamp: int, parent: str, child: str, pose: np.ndarray) -> Any:
        x, y, z, w = Rotation.from_matrix(pose[:3, :3]).as_quat()
        t = self.types
        transform = t["geometry_msgs/msg/Transform"](
            translation=t["geometry_msgs/msg/Vector3"](x=float(pose[0, 3]), y=float(pose[1, 3]),
                                                      z=float(pose[2, 3])),
            rotation=t["geometry_msgs/msg/Quaternion"](x=float(x), y=float(y), z=float(z),
                                                      w=float(w)))
        stamped = t["geometry_msgs/msg/TransformStamped"](
            header=self.header(stamp, parent), child_frame_id=child, transform=transform)
        return t[TF](transforms=[stamped])

    def string(self, text: str) -> Any:
        return self.types[STRING](data=text)
