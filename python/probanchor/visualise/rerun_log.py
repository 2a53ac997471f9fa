"""A run in the Rerun 3-D viewer (``rerun-sdk``): a person scrubs through it frame by frame.

Entities, all on the ``frame`` timeline (and ``time``, seconds of the recording):

- ``world/camera``: the camera's pose and pinhole; ``world/camera/image`` the colour image (JPEG),
  ``world/camera/depth`` the depth image (millimetres);
- ``world/cloud``: the points the camera sees (the table and what stands on it), every
  ``cloud_stride``-th pixel, in their colours;
- ``world/anchors``: each anchor as a 3-D box at its point estimate with its size, labelled
  with its symbol (and "hidden"), in its colour (``probanchor.visualise.anchor_colour``, as in
  the PNGs);
- ``world/particles/<symbol>``: the position particles of a hidden anchor, in its colour, more
  opaque the heavier;
- ``occlusion/<anchor>/<occluder>``: P(occluded_by(anchor, occluder)) as a time series (0 once
  the relation has no mass left);
- ``timings/<part>``: milliseconds per frame of perception, anchoring, the filter, the total.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import rerun as rr

from probanchor.visualise.overlay import anchor_colour, particle_alpha


@dataclass
class AnchorBox:
    """One anchor in one frame: where it is believed (point estimate), its size (3 extents,
    metres), whether it is perceived, and the particles of a hidden one."""

    symbol: str
    position: np.ndarray
    size: np.ndarray
    perceived: bool
    particles: np.ndarray | None = None
    weights: np.ndarray | None = None


@dataclass
class FrameScene:
    """What one frame shows: images and camera (optional: a percept stream has none), the
    anchors, occlusion probabilities ``(anchor, occluder) -> P`` and timings (ms)."""

    frame: int
    time: float
    anchors: Sequence[AnchorBox] = ()
    rgb: np.ndarray | None = None
    depth: np.ndarray | None = None
    intrinsics: Any = None
    camera_pose: np.ndarray | None = None
    occlusion: dict[tuple[str, str], float] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)


class RerunLog:
    """Logs :class:`FrameScene` objects to an ``.rrd`` file and/or a spawned viewer.

    Parameters
    ----------
    path:
        The ``.rrd`` file to write (None: none).
    spawn:
        Start the Rerun viewer and stream to it as well.
    name:
        The recording's application id (shown by the viewer).
    cloud_stride:
        Every how many pixels (in rows and columns) a point of the cloud is logged.
    """

    def __init__(self, path: Path | None = None, spawn: bool = False,
                 name: str = "anchoring", cloud_stride: int = 3) -> None:
        if path is None and not spawn:
            raise ValueError("a Rerun log needs a file or the viewer (spawn)")
        self.path = path
        self.stream = rr.RecordingStream(name)
        sinks: list[Any] = []
        if path is not None:
            path.parent.mkdir(parents=True, exist_ok=True)
            sinks.append(rr.FileSink(str(path)))
        if spawn:
            self.stream.spawn(connect=False)
            sinks.append(rr.GrpcSink())
        self.stream.set_sinks(*sinks)
        self.stream.log("world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
        self.cloud_stride = max(1, int(cloud_stride))
        self._relations: set[tuple[str, str]] = set()
        self._hidden: set[str] = set()

    def log(self, scene: FrameScene) -> None:
        """Log one frame.

        Parameters
        ----------
        scene:
            The frame's images, anchors, occlusion probabilities and timings.

        Returns
        -------
        None.
        """
        s = self.stream
        s.set_time("frame", sequence=int(scene.frame))
        s.set_time("time", duration=float(scene.time))
        if scene.rgb is not None and scene.camera_pose is not None:
            self._camera(scene)
        self._anchors(scene.anchors)
        for pair in self._relations - set(scene.occlusion):
            s.log(f"occlusion/{pair[0]}/{pair[1]}", rr.Scalars(0.0))
        for (anchor, occluder), p in scene.occlusion.items():
            s.log(f"occlusion/{anchor}/{occluder}", rr.Scalars(float(p)))
        self._relations = {pair for pair, p in scene.occlusion.items() if p > 0}
        for part, ms in scene.timings.items():
            s.log(f"timings/{part}", rr.Scalars(float(ms)))

    def _camera(self, scene: FrameScene) -> None:
        s, k, pose = self.stream, scene.intrinsics, np.asarray(scene.camera_pose, float)
        s.log("world/camera", rr.Transform3D(translation=pose[:3, 3], mat3x3=pose[:3, :3]))
        s.log("world/camera", rr.Pinhole(focal_length=[k.fx, k.fy],
                                         principal_point=[k.cx, k.cy],
                                         resolution=[k.width, k.height],
                                         camera_xyz=rr.ViewCoordinates.RDF))
        s.log("world/camera/image", rr.Image(scene.rgb).compress(jpeg_quality=90))
        if scene.depth is None:
            return
        depth = np.asarray(scene.depth, dtype=np.float32)
        s.log("world/camera/depth", rr.DepthImage(
            np.round(depth * 1000).clip(0, 65535).astype(np.uint16), meter=1000.0))
        st = self.cloud_stride
        z = depth[::st, ::st]
        rows, cols = np.mgrid[0:depth.shape[0]:st, 0:depth.shape[1]:st]
        ok = z > 0
        z, u, v = z[ok], cols[ok], rows[ok]
        camera = np.stack([(u - k.cx) * z / k.fx, (v - k.cy) * z / k.fy, z], axis=1)
        world = camera @ pose[:3, :3].T + pose[:3, 3]
        s.log("world/cloud", rr.Points3D(world, colors=scene.rgb[::st, ::st][ok],
                                         radii=0.002))

    def _anchors(self, anchors: Sequence[AnchorBox]) -> None:
        s = self.stream
        shown = [a for a in anchors if np.all(np.isfinite(a.position))]
        s.log("world/anchors", rr.Boxes3D(
            centers=[a.position for a in shown], half_sizes=[np.asarray(a.size) / 2
                                                             for a in shown],
            colors=[anchor_colour(a.symbol) for a in shown],
            labels=[a.symbol if a.perceived else f"{a.symbol} hidden" for a in shown]))
        hidden = set()
        for a in anchors:
            if a.perceived or a.particles is None or len(a.particles) == 0:
                continue
            hidden.add(a.symbol)
            alpha = particle_alpha(a.weights, len(a.particles))
            colours = np.empty((len(a.particles), 4), np.uint8)
            colours[:, :3] = anchor_colour(a.symbol)
            colours[:, 3] = np.round(alpha * 255).astype(np.uint8)
            s.log(f"world/particles/{a.symbol}", rr.Points3D(a.particles, colors=colours,
                                                             radii=0.003))
        for symbol in self._hidden - hidden:  # seen again: its particles go
            s.log(f"world/particles/{symbol}", rr.Clear(recursive=False))
        self._hidden = hidden

    def close(self) -> None:
        """Flush and close the sinks (the ``.rrd`` file is complete then)."""
        self.stream.flush()
        self.stream.disconnect()
