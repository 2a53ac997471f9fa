"""The RGB-D frame record: the contract between cameras (the simulator, recorded bags, a live
driver) and perception, as ``percepts`` is the one between perception and anchoring.

    from probanchor.rgbd import CameraIntrinsics, RGBDFrame
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np


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

    @property
    def K(self) -> np.ndarray:  # noqa: N802 - the usual name
        """The 3x3 camera matrix."""
        return np.array([[self.fx, 0.0, self.cx], [0.0, self.fy, self.cy], [0.0, 0.0, 1.0]])


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


__all__ = ["CameraIntrinsics", "RGBDFrame"]
