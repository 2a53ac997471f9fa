"""Table plane: RANSAC on a subsample of the cloud, refined by least squares.

The RANSAC is written here, vectorised over its hypotheses, because it must give the same plane
for the same points on every run: open3d's ``segment_plane`` draws its hypotheses in parallel
threads and keeps whichever best one a thread reports first, so two runs of one scenario and
seed could see slightly different tables (and different percepts); scikit-learn's
``RANSACRegressor`` is deterministic but fits one hypothesis per Python iteration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


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


def ransac_inliers(points: np.ndarray, threshold: float, iterations: int,
                   seed: int = 0) -> np.ndarray:
    """The inlier mask (N,) of the plane through three of ``points`` (N, 3) that has the most
    points within ``threshold`` of it, over ``iterations`` triples drawn with ``seed``.

    For a triple (p0, p1, p2): ``n = (p1 - p0) x (p2 - p0) / |...|``, ``d = -n . p0``; a point
    p is an inlier when ``|n . p + d| < threshold``. All hypotheses are scored in one
    (N, iterations) product; ties go to the first hypothesis drawn, so the answer depends only
    on the points and the seed."""
    rng = np.random.default_rng(seed)
    triples = points[rng.integers(0, len(points), size=(iterations, 3))]  # (K, 3, 3)
    normals = np.cross(triples[:, 1] - triples[:, 0], triples[:, 2] - triples[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    usable = lengths > 1e-12  # collinear or repeated points span no plane
    normals[usable] /= lengths[usable, None]
    offsets = -np.einsum("kj,kj->k", normals, triples[:, 0])
    inside = np.abs(points @ normals.T + offsets) < threshold  # (N, K)
    if not usable.any():
        return np.zeros(len(points), bool)
    counts = np.where(usable, inside.sum(axis=0), -1)
    return inside[:, int(np.argmax(counts))]


def fit_plane(points: np.ndarray, threshold: float = 0.01, iterations: int = 100,
              max_tilt_deg: float = 30.0, min_inlier_fraction: float = 0.3, seed: int = 0
              ) -> Plane | None:
    """The dominant plane of ``points`` (N, 3) if it is within ``max_tilt_deg`` of horizontal
    and holds at least ``min_inlier_fraction`` of the points; else None. Deterministic: the
    same points and seed give the same plane."""
    if len(points) < 50:
        return None
    pts = np.asarray(points, dtype=np.float64)
    inliers = ransac_inliers(pts, threshold, iterations, seed)
    if inliers.sum() < min_inlier_fraction * len(pts):
        return None
    inl = pts[inliers]
    centre = inl.mean(axis=0)
    _, _, vt = np.linalg.svd(inl - centre, full_matrices=False)
    normal = vt[2]
    if normal[2] < 0:
        normal = -normal
    if normal[2] < np.cos(np.radians(max_tilt_deg)):
        return None
    return Plane(normal=normal, offset=float(-normal @ centre))
