"""Depth image -> organised point cloud in the world frame (vectorised, cached rays)."""

from __future__ import annotations

import numpy as np


class Backprojector:
    """Turns depth images into world points; the pixel rays are computed once per camera."""

    def __init__(self) -> None:
        self._key: tuple[float, ...] | None = None
        self._rays: np.ndarray | None = None

    def rays(self, fx: float, fy: float, cx: float, cy: float, width: int, height: int
             ) -> np.ndarray:
        key = (fx, fy, cx, cy, float(width), float(height))
        if key != self._key or self._rays is None:
            u = (np.arange(width, dtype=np.float32) - cx) / fx
            v = (np.arange(height, dtype=np.float32) - cy) / fy
            rays = np.empty((height, width, 3), np.float32)
            rays[:, :, 0] = u[None, :]
            rays[:, :, 1] = v[:, None]
            rays[:, :, 2] = 1.0
            self._key, self._rays = key, rays
        return self._rays

    def world_points(self, depth: np.ndarray, intrinsics: object, pose: np.ndarray,
                     rows: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """World coordinates (N, 3) of the pixels (rows, cols), which must have depth."""
        k = intrinsics
        rays = self.rays(k.fx, k.fy, k.cx, k.cy, k.width, k.height)  # type: ignore[attr-defined]
        cam = rays[rows, cols] * depth[rows, cols][:, None]
        rot = pose[:3, :3].astype(np.float32)
        return cam @ rot.T + pose[:3, 3].astype(np.float32)
