"""Table plane: RANSAC (open3d) on a subsample of the cloud, refined by least squares."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import open3d as o3d


@dataclass(frozen=True)
class Plane:
    """``normal . p + offset`` is the signed height of p above the plane (normal points up)."""

    normal: np.ndarray
    offset: float

    def height(self, points: np.ndarray) -> np.ndarray:
        return points @ self.normal.astype(points.dtype) + np.float32(self.offset)

    def z_at(self, x: float, y: float) -> float:
        """World z of the plane at (x, y)."""
        n = self.normal
        return float(-(n[0] * x + n[1] * y + self.offset) / n[2])


def fit_plane(points: np.ndarray, threshold: float = 0.01, iterations: int = 100,
              max_tilt_deg: float = 30.0, min_inlier_fraction: float = 0.3, seed: int = 0
              ) -> Plane | None:
    """The dominant plane of ``points`` (N, 3) if it is within ``max_tilt_deg`` of horizontal
    and holds at least ``min_inlier_fraction`` of the points; else None."""
    if len(points) < 50:
        return None
    o3d.utility.random.seed(seed)
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points.astype(np.float64)))
    model, inliers = cloud.segment_plane(distance_threshold=threshold, ransac_n=3,
                                         num_iterations=iterations)
    if len(inliers) < min_inlier_fraction * len(points):
        return None
    inl = points[np.asarray(inliers)].astype(np.float64)
    centre = inl.mean(axis=0)
    _, _, vt = np.linalg.svd(inl - centre, full_matrices=False)
    normal = vt[2]
    if normal[2] < 0:
        normal = -normal
    if normal[2] < np.cos(np.radians(max_tilt_deg)):
        return None
    del model
    return Plane(normal=normal, offset=float(-normal @ centre))
