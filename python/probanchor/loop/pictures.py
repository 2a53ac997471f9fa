"""Per-frame pictures of a run: the camera image with each anchor's symbol at its position and
the particles of hidden anchors as dots (the paper's figures), as a video of the run and, on
request, a PNG per frame."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from probanchor.loop.loop import AnchoringLoop, FrameOutcome
from probanchor.visualise import AnchorView, CameraView, VideoWriter, draw_anchors, save_png

VIDEO_NAME = "run.mp4"


class FramePictures:
    """Draws every ``every``-th frame into ``DIR/run.mp4`` (shown at the frames' own times, so
    the video plays in real time) and, with ``frames``, also ``DIR/frames/frame_00012.png``.

    Parameters
    ----------
    out : Path
        The run's output folder.
    every : int
        Draw every ``every``-th frame.
    frames : bool
        Also write a PNG per frame drawn.
    video : str or None
        The video's file name in ``out`` (``.mp4`` or ``.webm``); None for no video.
    fps : float
        Frame rate assumed for frames without a time.
    """

    def __init__(self, out: Path, every: int = 1, frames: bool = False,
                 video: str | None = VIDEO_NAME, fps: float = 15.0) -> None:
        self.dir = out / "frames"
        self.frames = frames
        if frames:
            self.dir.mkdir(parents=True, exist_ok=True)
        self.every = max(1, every)
        self.video = VideoWriter(out / video, fps) if video else None
        self.paths: list[Path] = []
        self.drawn = 0

    def __call__(self, outcome: FrameOutcome, loop: AnchoringLoop) -> None:
        source = outcome.source
        index = source.percepts.frame
        if source.rgb is None or index % self.every:
            return
        camera = CameraView.make(source.intrinsics, source.camera_pose)
        percepts = source.percepts.percepts
        boxes = {a.symbol: percepts[a.percept_index].bbox for a in outcome.result.assignments}
        views = []
        for anchor in loop.manager.anchors:
            hypothesis = outcome.record.hypotheses.get(anchor.symbol)
            particles = outcome.hidden_beliefs.get(anchor.symbol)
            views.append(AnchorView(
                symbol=anchor.symbol,
                position=None if hypothesis is None else np.asarray(hypothesis.position),
                perceived=anchor.symbol in boxes,
                particles=None if particles is None else particles[0],
                weights=None if particles is None else particles[1],
                bbox=boxes.get(anchor.symbol),
            ))
        picture = draw_anchors(source.rgb, camera, views)
        self.drawn += 1
        if self.video is not None:
            self.video.add(picture, time=source.percepts.time)
        if self.frames:
            path = self.dir / f"frame_{index:05d}.png"
            save_png(path, picture)
            self.paths.append(path)

    def finish(self) -> Path | None:
        """Close the video; its path (None without one, or when no frame had an image)."""
        return self.video.close() if self.video is not None else None
