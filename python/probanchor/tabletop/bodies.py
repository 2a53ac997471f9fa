"""pybullet bodies for the objects, the table, the hands and the camera cover.

All bodies are visual only (no collision shapes, mass 0): motions are scripted. A body's
position is the centre of its bounding box. Cups and mugs are open tubes with a closed end
(turned over by default, so that they can cover something); a mug has a handle on its +x side.
"""

from __future__ import annotations

import math

import numpy as np
import pybullet as pb

from probanchor.tabletop.colours import SKIN_RGB
from probanchor.tabletop.scenario import HANDLE, WALL, ObjectSpec

FAR_AWAY = (0.0, 0.0, -50.0)  # where removed or idle bodies are parked (behind the table)


def _rgba(rgb: tuple[float, float, float]) -> list[float]:
    return [float(rgb[0]), float(rgb[1]), float(rgb[2]), 1.0]


class _Mesh:
    def __init__(self) -> None:
        self.vertices: list[list[float]] = []
        self.indices: list[int] = []

    def quad(self, a: list[float], b: list[float], c: list[float], d: list[float]) -> None:
        """A double-sided quad a-b-c-d."""
        base = len(self.vertices)
        self.vertices.extend([a, b, c, d])
        for tri in ((0, 1, 2), (0, 2, 3), (0, 2, 1), (0, 3, 2)):
            self.indices.extend(base + i for i in tri)

    def box(self, centre: tuple[float, float, float], half: tuple[float, float, float]) -> None:
        cx, cy, cz = centre
        hx, hy, hz = half
        c = [[cx + sx * hx, cy + sy * hy, cz + sz * hz]
             for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        for a, b, cc, d in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6),
                            (0, 2, 6, 4), (1, 5, 7, 3)):
            self.quad(c[a], c[b], c[cc], c[d])

    def flip_z(self) -> None:
        self.vertices = [[x, y, -z] for x, y, z in self.vertices]


def container_mesh(radius: float, height: float, top_scale: float, handle: bool,
                   upside_down: bool, segments: int = 20) -> _Mesh:
    """An open tube with a closed bottom (closed top when turned over), centred at the origin."""
    mesh = _Mesh()
    h2 = height / 2
    r0, r1 = radius, radius * top_scale
    ri0, ri1 = r0 - WALL, r1 - WALL
    for i in range(segments):
        a0 = 2 * math.pi * i / segments
        a1 = 2 * math.pi * (i + 1) / segments
        c0, s0, c1, s1 = math.cos(a0), math.sin(a0), math.cos(a1), math.sin(a1)
        # outer wall, inner wall, rim
        mesh.quad([r0 * c0, r0 * s0, -h2], [r0 * c1, r0 * s1, -h2],
                  [r1 * c1, r1 * s1, h2], [r1 * c0, r1 * s0, h2])
        mesh.quad([ri0 * c0, ri0 * s0, -h2 + WALL], [ri0 * c1, ri0 * s1, -h2 + WALL],
                  [ri1 * c1, ri1 * s1, h2], [ri1 * c0, ri1 * s0, h2])
        mesh.quad([ri1 * c0, ri1 * s0, h2], [ri1 * c1, ri1 * s1, h2],
                  [r1 * c1, r1 * s1, h2], [r1 * c0, r1 * s0, h2])
        # closed bottom (outer face and inner face)
        for z, r in ((-h2, r0), (-h2 + WALL, ri0)):
            mesh.quad([0.0, 0.0, z], [r * c0, r * s0, z], [r * c1, r * s1, z], [0.0, 0.0, z])
    if handle:
        t = 0.006
        hx = HANDLE / 2
        mesh.box((radius + hx, 0.0, h2 * 0.55), (hx, t, t))
        mesh.box((radius + hx, 0.0, -h2 * 0.45), (hx, t, t))
        mesh.box((radius + 2 * hx - t, 0.0, 0.05 * h2), (t, t, h2 * 0.5 + t))
        mesh.vertices = [[x - hx, y, z] for x, y, z in mesh.vertices]  # origin = box centre
    if upside_down:
        mesh.flip_z()
    return mesh


def make_visual(client: int, obj: ObjectSpec) -> int:
    """Create the visual shape of an object; returns the visual shape index."""
    rgba = _rgba(obj.colour)
    if obj.shape == "sphere":
        return pb.createVisualShape(pb.GEOM_SPHERE, radius=obj.radius, rgbaColor=rgba,
                                    physicsClientId=client)
    if obj.shape == "cylinder":
        return pb.createVisualShape(pb.GEOM_CYLINDER, radius=obj.radius, length=obj.height,
                                    rgbaColor=rgba, physicsClientId=client)
    if obj.shape == "box":
        half = [s / 2 for s in obj.size]
        return pb.createVisualShape(pb.GEOM_BOX, halfExtents=half, rgbaColor=rgba,
                                    physicsClientId=client)
    if obj.shape in ("cup", "mug"):
        mesh = container_mesh(obj.radius, obj.height, 1.2 if obj.shape == "cup" else 1.0,
                              obj.shape == "mug", obj.upside_down)
        return pb.createVisualShape(pb.GEOM_MESH, vertices=mesh.vertices, indices=mesh.indices,
                                    rgbaColor=rgba, physicsClientId=client)
    if obj.shape == "mesh":
        s = obj.mesh_scale
        return pb.createVisualShape(pb.GEOM_MESH, fileName=obj.mesh, meshScale=[s, s, s],
                                    rgbaColor=rgba, physicsClientId=client)
    raise ValueError(f"unknown shape {obj.shape!r}")


def yaw_quaternion(yaw_deg: float) -> list[float]:
    return list(pb.getQuaternionFromEuler([0.0, 0.0, math.radians(yaw_deg)]))


def create_object(client: int, obj: ObjectSpec) -> int:
    visual = make_visual(client, obj)
    return pb.createMultiBody(baseMass=0, baseVisualShapeIndex=visual,
                              basePosition=list(obj.position),
                              baseOrientation=yaw_quaternion(obj.yaw), physicsClientId=client)


def create_table(client: int, size: tuple[float, float], rgb: tuple[float, float, float]
                 ) -> int:
    visual = pb.createVisualShape(pb.GEOM_BOX, halfExtents=[size[0] / 2, size[1] / 2, 0.01],
                                  rgbaColor=_rgba(rgb), physicsClientId=client)
    return pb.createMultiBody(baseMass=0, baseVisualShapeIndex=visual,
                              basePosition=[0.0, 0.0, -0.01], physicsClientId=client)


def create_hand(client: int, half: tuple[float, float, float]) -> int:
    """A skin-coloured hand (a box open underneath, so that it can hold an object) and a
    forearm reaching out of the view along +x."""
    hx, hy, hz = half
    mesh = _Mesh()
    t = 0.006
    mesh.box((0.0, 0.0, hz - t), (hx, hy, t))  # back of the hand
    for sy in (-1, 1):
        mesh.box((0.0, sy * (hy - t), 0.0), (hx, t, hz))  # fingers and thumb
    for sx in (-1, 1):
        mesh.box((sx * (hx - t), 0.0, 0.0), (t, hy - 2 * t, hz))
    arm_len = 0.45
    mesh.box((hx + arm_len / 2, 0.0, hz * 0.4), (arm_len / 2, hy * 0.75, hz * 0.6))
    visual = pb.createVisualShape(pb.GEOM_MESH, vertices=mesh.vertices, indices=mesh.indices,
                                  rgbaColor=_rgba(SKIN_RGB), physicsClientId=client)
    return pb.createMultiBody(baseMass=0, baseVisualShapeIndex=visual,
                              basePosition=list(FAR_AWAY), physicsClientId=client)


def create_cover(client: int) -> int:
    """The palm that covers the lens (placed in front of the camera by the simulation)."""
    visual = pb.createVisualShape(pb.GEOM_BOX, halfExtents=[0.3, 0.3, 0.004],
                                  rgbaColor=_rgba(SKIN_RGB), physicsClientId=client)
    return pb.createMultiBody(baseMass=0, baseVisualShapeIndex=visual,
                              basePosition=list(FAR_AWAY), physicsClientId=client)


def set_pose(client: int, body: int, position: np.ndarray | tuple[float, ...],
             orientation: list[float]) -> None:
    pb.resetBasePositionAndOrientation(body, [float(v) for v in position], orientation,
                                       physicsClientId=client)
