"""Each frame of a run into the Rerun viewer's log (``visualise.RerunLog``): the images, the
anchors as 3-D boxes, the particles of hidden anchors, the occlusion probabilities and the
timings."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from probanchor.loop.loop import AnchoringLoop, FrameOutcome
from probanchor.visualise.rerun_log import AnchorBox, FrameScene, RerunLog


class RerunFrames:
    """``on_frame`` callback of a run that logs it to Rerun.

    Parameters
    ----------
    path:
        The ``.rrd`` file (None: only the viewer).
    spawn:
        Open the viewer and stream to it.
    name:
        The recording's name (the scenario's or the bag's).
    """

    def __init__(self, path: Path | None, spawn: bool = False, name: str = "anchoring") -> None:
        self.log = RerunLog(path, spawn=spawn, name=name)

    def __call__(self, outcome: FrameOutcome, loop: AnchoringLoop) -> None:
        source, record = outcome.source, outcome.record
        boxes = []
        for anchor in loop.manager.anchors:
            hypothesis = record.hypotheses.get(anchor.symbol)
            if hypothesis is None:
                continue
            particles = outcome.hidden_beliefs.get(anchor.symbol)
            boxes.append(AnchorBox(
                anchor.symbol, np.asarray(hypothesis.position, dtype=float),
                np.asarray(anchor.size.mean(), dtype=float).reshape(-1), hypothesis.perceived,
                None if particles is None else particles[0],
                None if particles is None else particles[1]))
        occlusion: dict[tuple[str, str], float] = {}
        if loop.reasoner is not None:
            for symbol in outcome.result.tracked:
                for p, occluder in loop.reasoner.occluders(symbol):
                    occlusion[(symbol, occluder)] = float(p)
        t = record.timings
        timings = {"perception": t.perception, "anchoring": t.anchoring, "filter": t.filter}
        if t.total is not None:
            timings["total"] = t.total
        self.log.log(FrameScene(
            frame=source.percepts.frame, time=source.percepts.time, anchors=boxes,
            rgb=source.rgb, depth=getattr(source, "depth", None), intrinsics=source.intrinsics,
            camera_pose=source.camera_pose, occlusion=occlusion, timings=timings))

    def close(self) -> None:
        self.log.close()
