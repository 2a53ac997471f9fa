"""Pinhole projection of world points into the image, vectorised over points.

Conventions (the same as ``tabletop``): camera axes as in OpenCV (x right, y down, z forward
along the optical axis), pixel centres at integer coordinates, world frame with z up. The pose
is a 4x4 rigid transform, by default **world-from-camera** (the camera's pose in the world:
its columns are the camera axes and position in world coordinates, ``tabletop.Frame.camera_pose``);
pass ``convention="camera_from_world"`` for the inverse (an extrinsic matrix ``[R | t]``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

CONVENTIONS = ("world_from_camera", "camera_from_world")


@dataclass(frozen=True)
class CameraView:
    """Intrinsics in pixels and the camera pose, world-from-camera (OpenCV axes)."""

    fx: float
    fy: float
    cx: float
    cy: float
    world_from_camera: np.ndarray

    def __post_init__(self) -> None:
        pose = np.asarray(self.world_from_camera, dtype=float)
        if pose.shape != (4, 4) or not np.all(np.isfinite(pose)):
            raise ValueError(f"camera pose must be a finite 4x4 matrix, got shape {pose.shape}")
        object.__setattr__(self, "world_from_camera", pose)

    @classmethod
    def make(
        cls,
        intrinsics: Any,
        pose: np.ndarray,
        convention: str = "world_from_camera",
    ) -> CameraView:
        """From ``intrinsics`` (an object with ``fx, fy, cx, cy``, e.g. ``tabletop.Intrinsics``,
        or a tuple ``(fx, fy, cx, cy)``) and a 4x4 ``pose`` in the given convention."""
        if convention not in CONVENTIONS:
            raise ValueError(f"unknown pose convention {convention!r}; use one of {CONVENTIONS}")
        if hasattr(intrinsics, "fx"):
            fx, fy, cx, cy = intrinsics.fx, intrinsics.fy, intrinsics.cx, intrinsics.cy
        else:
            fx, fy, cx, cy = intrinsics
        pose = np.asarray(pose, dtype=float)
        if convention == "camera_from_world":
            pose = np.linalg.inv(pose)
        return cls(float(fx), float(fy), float(cx), float(cy), pose)

    @property
    def camera_from_world(self) -> np.ndarray:
        rot, t = self.world_from_camera[:3, :3], self.world_from_camera[:3, 3]
        out = np.eye(4)
        out[:3, :3] = rot.T
        out[:3, 3] = -rot.T @ t
        return out

    def project(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates ``uv`` (N, 2) and depth ``z`` (N,) of world points (N, 3).

        Points behind the camera (``z <= 0``) get ``uv = NaN``.
        """
        pts = np.asarray(points, dtype=float).reshape(-1, 3)
        rot, t = self.world_from_camera[:3, :3], self.world_from_camera[:3, 3]
        cam = (pts - t) @ rot  # = R^T (p - t) for every row
        z = cam[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            u = self.cx + self.fx * cam[:, 0] / z
            v = self.cy + self.fy * cam[:, 1] / z
        uv = np.stack([u, v], axis=1)
        uv[~(z > 0)] = np.nan
        return uv, z
