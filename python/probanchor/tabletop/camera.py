"""The pinhole camera: pybullet view/projection matrices from intrinsics, pose, depth buffer."""

from __future__ import annotations

import numpy as np
import pybullet as pb

from probanchor.rgbd import CameraIntrinsics as Intrinsics
from probanchor.tabletop.scenario import CameraSpec

__all__ = ["Camera", "Intrinsics", "look_at_pose"]


def look_at_pose(position: tuple[float, ...], target: tuple[float, ...], up: tuple[float, ...]
                 ) -> np.ndarray:
    """4x4 camera-to-world transform, camera axes as in OpenCV (x right, y down, z forward)."""
    eye = np.asarray(position, dtype=float)
    forward = np.asarray(target, dtype=float) - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(up, dtype=float))
    norm = np.linalg.norm(right)
    if norm < 1e-9:
        raise ValueError("camera 'up' is parallel to its viewing direction")
    right /= norm
    image_up = np.cross(right, forward)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = right, -image_up, forward, eye
    return pose


class Camera:
    """Renders RGB, metric depth (z along the optical axis) and the segmentation mask."""

    def __init__(self, spec: CameraSpec, width: int | None = None, height: int | None = None
                 ) -> None:
        self.spec = spec
        self.width = int(width or spec.width)
        self.height = int(height or spec.height)
        fx, fy, cx, cy = spec.intrinsics(self.width, self.height)
        self.intrinsics = Intrinsics(fx, fy, cx, cy, self.width, self.height)
        self.pose = look_at_pose(spec.position, spec.target, spec.up)
        self.view_matrix = pb.computeViewMatrix(list(spec.position), list(spec.target),
                                                list(spec.up))
        self.projection_matrix = self._projection()

    def _projection(self) -> list[float]:
        w, h = self.width, self.height
        k = self.intrinsics
        n, f = self.spec.near, self.spec.far
        proj = np.array([
            [2 * k.fx / w, 0.0, 1.0 - (2 * k.cx + 1) / w, 0.0],
            [0.0, 2 * k.fy / h, (2 * k.cy + 1) / h - 1.0, 0.0],
            [0.0, 0.0, -(f + n) / (f - n), -2 * f * n / (f - n)],
            [0.0, 0.0, -1.0, 0.0],
        ])
        return proj.T.reshape(-1).tolist()  # column-major, as OpenGL and pybullet want

    def render(self, client: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(rgb uint8 HxWx3, depth float32 HxW in metres with 0 = no return, seg int32 HxW)."""
        _, _, rgba, buf, seg = pb.getCameraImage(
            self.width, self.height, self.view_matrix, self.projection_matrix,
            renderer=pb.ER_TINY_RENDERER, physicsClientId=client)
        rgb = np.asarray(rgba, dtype=np.uint8).reshape(self.height, self.width, 4)[:, :, :3]
        buf = np.asarray(buf, dtype=np.float32).reshape(self.height, self.width)
        seg = np.asarray(seg, dtype=np.int32).reshape(self.height, self.width)
        n, f = self.spec.near, self.spec.far
        depth = (f * n / (f - (f - n) * buf)).astype(np.float32)
        no_return = (buf >= 1.0) | (depth < self.spec.min_depth) | (depth > self.spec.max_depth)
        depth[no_return] = 0.0
        return np.ascontiguousarray(rgb), depth, seg

    def project(self, points_world: np.ndarray) -> np.ndarray:
        """Pixel coordinates (u, v) and depth z of world points, shape (N, 3)."""
        pts = np.atleast_2d(points_world)
        rot, t = self.pose[:3, :3], self.pose[:3, 3]
        cam = (pts - t) @ rot
        k = self.intrinsics
        z = cam[:, 2]
        u = k.cx + k.fx * cam[:, 0] / z
        v = k.cy + k.fy * cam[:, 1] / z
        return np.stack([u, v, z], axis=1)
