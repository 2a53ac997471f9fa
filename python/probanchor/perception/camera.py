"""Any RGB-D camera, as the pipeline sees it: intrinsics, pose and one frame's images.

The pipeline needs nothing of where a frame comes from (the simulator, a recorded bag, a live
driver): :class:`rgbd.RGBDFrame` holds what it reads, and :func:`check_frame` says what is wrong
with a frame that it could not perceive (images of different sizes, intrinsics of another
image size, a pose that is not a rigid transform).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from probanchor.rgbd import CameraIntrinsics, RGBDFrame

__all__ = ["CameraIntrinsics", "FrameError", "RGBDFrame", "check_frame"]


class FrameError(ValueError):
    """A frame the pipeline cannot perceive; the message names the cause."""


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
