"""Where frames come from: a simulated scenario (rendered and perceived here) or a recorded
percept stream (JSON Lines, no images)."""

from __future__ import annotations

import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from percepts import PerceptFrame, read_percepts


@dataclass
class SourceFrame:
    percepts: PerceptFrame
    perception_ms: float
    rgb: Any = None  # uint8 HxWx3 when the source renders images
    intrinsics: Any = None
    camera_pose: Any = None  # 4x4 world-from-camera (OpenCV axes)


def scenario_frames(path: str | Path, seed: int = 0, width: int | None = None,
                    height: int | None = None, fps: float | None = None) -> Iterator[SourceFrame]:
    """Render every frame of a scenario and run the perception pipeline on it."""
    from perception import Pipeline
    from tabletop import Simulation, load_scenario

    scenario = load_scenario(path)
    pipeline = Pipeline()
    with Simulation(scenario, width=width, height=height, fps=fps, seed=seed) as sim:
        for frame in sim:
            started = time.perf_counter()
            percepts = pipeline.percept_frame(frame)
            ms = (time.perf_counter() - started) * 1000
            yield SourceFrame(percepts, ms, frame.rgb, frame.intrinsics, frame.camera_pose)


def scenario_length(path: str | Path, fps: float | None = None) -> int | None:
    """How many frames a scenario has (for a progress bar), if the simulator can tell."""
    try:
        from tabletop import load_scenario

        scenario = load_scenario(path)
        rate = fps or scenario.fps
        return int(scenario.end_time() * rate + 1e-9) + 1
    except Exception:
        return None


def stream_frames(path: str | Path) -> Iterator[SourceFrame]:
    """A recorded percept stream: no images, perception time 0."""
    for frame in read_percepts(path):
        yield SourceFrame(frame, 0.0)
