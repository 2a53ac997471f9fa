"""Any RGB-D camera, as the pipeline sees it: intrinsics, pose and one frame's images.

The pipeline needs nothing of where a frame comes from (the simulator, a recorded bag, a live
driver): :class:`RGBDFrame` holds what it reads, and :func:`check_frame` says what is wrong
with a frame that it could not perceive (images of different sizes, intrinsics of another
image size, a pose that is not a rigid transform).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np


class FrameError(ValueError):
    """A frame the pipeline cannot perceive; the message names the cause."""


@dataclass(frozen=True)
class CameraIntrinsics:
    """Pinhole intrinsics in pixels (OpenCV convention: pixel centres at integer coordinates)
    and the image size they belong to."""

    fx: float
    fy: float
    cx: float
    cy: float
    width: int
    height: int


@dataclass
class RGBDFrame:
    """One registered RGB-D frame: ``rgb`` uint8 HxWx3, ``depth`` float32 HxW metres along the
    optical axis (0 = no return), ``camera_pose`` 4x4 world-from-camera (OpenCV axes: x right,
    y down, z forward). ``truth``, ``segmentation`` and ``body_names`` are optional ground
    truth, used only to label percepts with ``truth_id`` for evaluation."""

    index: int
    time: float
    rgb: np.ndarray
    depth: np.ndarray
    intrinsics: CameraIntrinsics
    camera_pose: np.ndarray
    truth: dict[str, Any] = field(default_factory=dict)
    segmentation: np.ndarray | None = None
    body_names: dict[int, str] = field(default_factory=dict)


def check_frame(frame: Any) -> None:
    """Raise :class:`FrameError` when a frame cannot be perceived.

    Parameters
    ----------
    frame:
        An :class:`RGBDFrame` or anything with its ``rgb``, ``depth``, ``intrinsics`` and
        ``camera_pose``.

    Returns
    -------
    None; the frame is fit for :meth:`perception.Pipeline.process`.
    """
    rgb, depth = np.asarray(frame.rgb), np.asarray(frame.depth)
    if rgb.ndim != 3 or rgb.shape[2] != 3 or rgb.dtype != np.uint8:
        raise FrameError(f"colour image is {rgb.dtype} of shape {rgb.shape}, "
                         "not 8-bit HxWx3 RGB")
    if depth.ndim != 2:
        raise FrameError(f"depth image has shape {depth.shape}, not HxW")
    if rgb.shape[:2] != depth.shape:
        raise FrameError(f"colour image is {rgb.shape[1]}x{rgb.shape[0]} but depth image is "
                         f"{depth.shape[1]}x{depth.shape[0]}: the depth must be registered "
                         "to the colour camera")
    k = frame.intrinsics
    if (int(k.width), int(k.height)) != (rgb.shape[1], rgb.shape[0]):
        raise FrameError(f"intrinsics are for {k.width}x{k.height} images, the images are "
                         f"{rgb.shape[1]}x{rgb.shape[0]}")
    if not (k.fx > 0 and k.fy > 0):
        raise FrameError(f"focal lengths fx={k.fx}, fy={k.fy} must be positive")
    pose = np.asarray(frame.camera_pose, dtype=float)
    if pose.shape != (4, 4) or not np.all(np.isfinite(pose)) or not np.allclose(
            pose[:3, :3] @ pose[:3, :3].T, np.eye(3), atol=1e-4):
        raise FrameError("camera pose is not a 4x4 rigid transform")
