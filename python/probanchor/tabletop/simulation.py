"""The simulated RGB-D camera over the table: frames and their ground truth."""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

import numpy as np
import pybullet as pb

from probanchor.rgbd import RGBDFrame
from probanchor.tabletop import bodies
from probanchor.tabletop.camera import Camera
from probanchor.tabletop.noise import GaussianBank, add_noise
from probanchor.tabletop.scenario import Scenario
from probanchor.tabletop.timeline import Timeline

COVER_DISTANCE = 0.06  # the palm over the lens, metres in front of the camera


#: One camera frame: ``rgb`` uint8 HxWx3, ``depth`` float32 HxW metres (0 = no return),
#: ``camera_pose`` 4x4 camera-to-world (OpenCV axes). ``truth`` is the JSON-able ground truth
#: (see scenarios/SCHEMA.md); ``segmentation`` (pybullet body per pixel) and ``body_names``
#: (body -> object id, hand id, ``table`` or ``camera_cover``) are ground truth too:
#: perception uses them only to label percepts with ``truth_id`` for evaluation.
Frame = RGBDFrame


def _hand_half(scenario: Scenario) -> tuple[float, float, float]:
    half = [s / 2 for s in scenario.hand_size]
    objs = {o.id: o for o in scenario.objects}
    for ev in scenario.events:
        if ev.kind == "pick_up" and ev.params.get("object") in objs:
            oh = objs[ev.params["object"]].half_extents()
            half = [max(h, o + 0.012) for h, o in zip(half, oh, strict=True)]
    return (half[0], half[1], half[2])


def _rotation_to_quaternion(rot: np.ndarray) -> list[float]:
    """(x, y, z, w) of a rotation matrix."""
    m = rot
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [(m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s, 0.25 * s]
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2]) * 2
        q = [0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s, (m[2, 1] - m[1, 2]) / s]
    elif m[1, 1] > m[2, 2]:
        s = math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2]) * 2
        q = [(m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s, (m[0, 2] - m[2, 0]) / s]
    else:
        s = math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1]) * 2
        q = [(m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s, (m[1, 0] - m[0, 1]) / s]
    return q


class Simulation:
    """Plays a scenario through a pybullet camera: ``for frame in Simulation(scn): ...``.

    ``width``/``height`` default to the scenario camera's (320x240), ``fps`` to the
    scenario's; ``seed`` fixes the sensor noise; ``noise=False`` gives clean frames.
    ``min_visible_pixels`` (scaled with the image area from 320x240) is how many pixels of an
    object must be seen for the ground truth to call it visible.
    """

    def __init__(self, scenario: Scenario, width: int | None = None, height: int | None = None,
                 fps: float | None = None, seed: int = 0, noise: bool = True,
                 min_visible_pixels: int = 20) -> None:
        self.scenario = scenario
        self.fps = float(fps or scenario.fps)
        self.rng = np.random.default_rng(seed)
        self.noise = noise and scenario.noise.enabled
        self._bank: GaussianBank | None = None
        self.camera = Camera(scenario.camera, width, height)
        area = self.camera.width * self.camera.height / (320 * 240)
        self.min_visible_pixels = max(1, int(round(min_visible_pixels * area)))
        self.client = pb.connect(pb.DIRECT)
        self.hand_half = _hand_half(scenario)
        self.timeline = Timeline(scenario, self.hand_half)
        c = self.client
        self.body_names: dict[int, str] = {}
        table = bodies.create_table(c, scenario.table_size, scenario.table_colour)
        self.body_names[table] = "table"
        self.bodies: dict[str, int] = {}
        for obj in scenario.objects:
            self.bodies[obj.id] = bodies.create_object(c, obj)
        for hand in self.timeline.hands:
            self.bodies[hand] = bodies.create_hand(c, self.hand_half)
        self.cover = bodies.create_cover(c)
        self.body_names.update({b: name for name, b in self.bodies.items()})
        self.body_names[self.cover] = "camera_cover"
        self._yaw = {o.id: bodies.yaw_quaternion(o.yaw) for o in scenario.objects}
        rot = self.camera.pose[:3, :3]
        self._cover_pose = (self.camera.pose[:3, 3] + rot[:, 2] * COVER_DISTANCE,
                            _rotation_to_quaternion(rot))
        self.n_frames = int(math.floor(scenario.end_time() * self.fps + 1e-9)) + 1
        self._index = 0

    # ------------------------------------------------------------------------------ frames
    def __len__(self) -> int:
        return self.n_frames

    def __iter__(self) -> Iterator[Frame]:
        while self._index < self.n_frames:
            yield self.step()

    def __enter__(self) -> Simulation:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        if self.client is not None and self.client >= 0:
            try:
                pb.disconnect(self.client)
            except pb.error:
                pass
            self.client = -1

    def __del__(self) -> None:
        try:
            self.close()
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass

    def step(self) -> Frame:
        """Render the next frame."""
        k = self._index
        t = k / self.fps
        state = self.timeline.advance(t)
        c = self.client
        identity = [0.0, 0.0, 0.0, 1.0]
        for oid, body in self.bodies.items():
            if oid in self._yaw:
                if oid in state.present:
                    bodies.set_pose(c, body, state.positions[oid], self._yaw[oid])
                else:
                    bodies.set_pose(c, body, bodies.FAR_AWAY, identity)
            else:
                bodies.set_pose(c, body, state.positions[oid], identity)
        if state.covered:
            bodies.set_pose(c, self.cover, self._cover_pose[0], self._cover_pose[1])
        else:
            bodies.set_pose(c, self.cover, bodies.FAR_AWAY, identity)
        rgb, depth, seg = self.camera.render(c)
        truth = self._truth(state, seg)
        if self.noise:
            if self._bank is None:
                self._bank = GaussianBank(self.rng, size=max(1 << 21, 2 * rgb.size))
            rgb, depth = add_noise(rgb, depth, self.scenario.noise, self.rng, self._bank)
        self._index += 1
        return Frame(index=k, time=t, rgb=rgb, depth=depth, intrinsics=self.camera.intrinsics,
                     camera_pose=self.camera.pose.copy(), truth=truth, segmentation=seg,
                     body_names=self.body_names)

    # ------------------------------------------------------------------------------ truth
    def _truth(self, state: Any, seg: np.ndarray) -> dict[str, Any]:
        ids, counts = np.unique(seg, return_counts=True)
        pixels = {self.body_names.get(int(i)): int(n) for i, n in zip(ids, counts, strict=True)
                  if int(i) in self.body_names}
        objects: dict[str, Any] = {}
        h, w = seg.shape
        for obj in self.scenario.objects:
            oid = obj.id
            pos = state.positions[oid]
            present = oid in state.present
            n = pixels.get(oid, 0) if present else 0
            visible = n >= self.min_visible_pixels
            hidden_by = None
            if present and not visible:
                parent = state.parent.get(oid)
                if parent is not None:
                    hidden_by = parent
                elif state.covered:
                    hidden_by = "camera_cover"
                else:
                    u, v, z = self.camera.project(pos[None, :])[0]
                    iu, iv = int(round(u)), int(round(v))
                    if z <= 0 or not (0 <= iu < w and 0 <= iv < h):
                        hidden_by = "out_of_view"
                    else:
                        hidden_by = self.body_names.get(int(seg[iv, iu]))
                        if hidden_by == "table" or hidden_by is None:
                            hidden_by = "out_of_view" if n == 0 else None
            objects[oid] = {
                "position": [round(float(v), 5) for v in pos],
                "category": obj.category,
                "size": [round(v, 5) for v in obj.world_extents()],
                "present": present,
                "visible": bool(visible),
                "pixels": int(n),
                "hidden_by": hidden_by,
                "under": state.parent.get(oid) if not str(state.parent.get(oid, "")
                                                          ).startswith("hand") else None,
                "held_by": state.parent.get(oid) if str(state.parent.get(oid, "")
                                                        ).startswith("hand") else None,
            }
        hands = {h_id: {"position": [round(float(v), 5) for v in state.positions[h_id]],
                        "pixels": pixels.get(h_id, 0)} for h_id in self.timeline.hands}
        return {"objects": objects, "hands": hands, "camera_covered": bool(state.covered)}


def render_frames(scenario: Scenario, **kwargs: Any) -> Iterator[Frame]:
    """All frames of a scenario (a generator; the simulation is closed at the end)."""
    sim = Simulation(scenario, **kwargs)
    try:
        yield from sim
    finally:
        sim.close()
