"""Per-frame pictures of a run: the camera image with each anchor's symbol at its position and
the particles of hidden anchors as dots (the paper's figures), and a GIF of them."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from probanchor.app.loop import AnchoringLoop, FrameOutcome
from probanchor.visualise import AnchorView, CameraView, draw_anchors, save_png, write_gif


class FramePictures:
    """Writes ``DIR/frames/frame_00012.png`` every ``every`` frames, then ``DIR/run.gif``."""

    def __init__(self, out: Path, every: int = 1, fps: float = 10.0) -> None:
        self.dir = out / "frames"
        self.dir.mkdir(parents=True, exist_ok=True)
        self.every = max(1, every)
        self.fps = fps
        self.paths: list[Path] = []

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
        path = self.dir / f"frame_{index:05d}.png"
        save_png(path, draw_anchors(source.rgb, camera, views))
        self.paths.append(path)

    def finish(self, gif: Path) -> Path | None:
        if not self.paths:
            return None
        write_gif(gif, self.paths, fps=self.fps)
        return gif
