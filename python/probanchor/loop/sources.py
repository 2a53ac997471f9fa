"""Where frames come from: a simulated scenario (rendered and perceived here), a recorded
RGB-D bag (ROS 1 or 2, perceived here) or a recorded percept stream (JSON Lines, no images).

A source yields one *pending frame* per camera frame: the camera's image is there (the simulator has
rendered it), and calling the pending frame runs perception on it (timed) and gives the
:class:`SourceFrame`.  The loop can so perceive the next frame while it reasons about the current
one (:func:`probanchor.loop.loop.run_frames`); rendering, the simulator's stand-in for a camera, is
never timed nor overlapped.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import Any

from probanchor.percepts import PerceptFrame, read_percepts, write_percepts


@dataclass
class SourceFrame:
    percepts: PerceptFrame
    perception_ms: float
    rgb: Any = None  # uint8 HxWx3 when the source renders images
    intrinsics: Any = None
    camera_pose: Any = None  # 4x4 world-from-camera (OpenCV axes)
    depth: Any = None  # float32 HxW metres when the source renders images


PendingFrame = Callable[[], SourceFrame]


def scenario_frames(path: str | Path, seed: int = 0, width: int | None = None,
                    height: int | None = None, fps: float | None = None, start: int = 0
                    ) -> Iterator[PendingFrame]:
    """Render every frame of a scenario; each pending frame runs the perception pipeline on
    it (the pipeline's frames must be perceived in order, one at a time). Frames before
    ``start`` are rendered (the sensor noise follows the frames) but not given."""
    from probanchor.perception import Pipeline
    from probanchor.tabletop import Simulation, load_scenario

    scenario = load_scenario(path)
    pipeline = Pipeline()
    with Simulation(scenario, width=width, height=height, fps=fps, seed=seed) as sim:
        for frame in sim:
            if frame.index >= start:
                yield partial(_perceive, pipeline, frame)


def perceive_scenario(scenario: Any, width: int | None = None, height: int | None = None,
                      fps: float | None = None, seed: int = 0,
                      pipeline: Any = None) -> Iterator[PerceptFrame]:
    """The percept stream of a simulated scenario.

    Parameters
    ----------
    scenario:
        A :class:`tabletop.Scenario` or the path of a scenario file.
    width, height, fps, seed:
        The simulator's image size, frame rate and noise seed (the scenario's by default).
    pipeline:
        A :class:`perception.Pipeline` (a new one by default).

    Returns
    -------
    The frames' percepts with their ground truth, in order.
    """
    from probanchor.perception import Pipeline
    from probanchor.tabletop import Simulation, load_scenario

    if isinstance(scenario, (str, Path)):
        scenario = load_scenario(scenario)
    pipe = pipeline or Pipeline()
    with Simulation(scenario, width=width, height=height, fps=fps, seed=seed) as sim:
        for frame in sim:
            yield pipe.percept_frame(frame)


def _perceive(pipeline: Any, frame: Any) -> SourceFrame:
    started = time.perf_counter()
    percepts = pipeline.percept_frame(frame)
    ms = (time.perf_counter() - started) * 1000
    return SourceFrame(percepts, ms, frame.rgb, frame.intrinsics, frame.camera_pose,
                       frame.depth)


def scenario_length(path: str | Path, fps: float | None = None) -> int | None:
    """How many frames a scenario has (for a progress bar), if the simulator can tell."""
    try:
        from probanchor.tabletop import load_scenario

        scenario = load_scenario(path)
        rate = fps or scenario.fps
        return int(scenario.end_time() * rate + 1e-9) + 1
    except Exception:
        return None


def bag_frames(path: str | Path, topics: Any = None, start: int = 0
               ) -> Iterator[PendingFrame]:
    """The frames of a recorded RGB-D bag, at its time stamps; each pending frame runs the
    perception pipeline on it.

    Parameters
    ----------
    path:
        A ``.bag``, ``.db3`` or ``.mcap`` file (``probanchor.bags.read_bag``).
    topics:
        A :class:`bags.BagTopics` (the usual topic names by default).
    start:
        The first frame given (the earlier ones are read and skipped).

    Returns
    -------
    Pending frames, in the bag's time order.
    """
    from probanchor.bags import read_bag
    from probanchor.perception import Pipeline

    pipeline = Pipeline()
    for frame in read_bag(path, topics):
        if frame.index >= start:
            yield partial(_perceive, pipeline, frame)


def stream_frames(path: str | Path, skipped: list[str] | None = None, start: int = 0
                  ) -> Iterator[PendingFrame]:
    """A recorded percept stream: no images, perception time 0. With ``skipped``, a line that
    is not a frame is skipped and its error appended there (``probanchor.percepts.read_percepts``).
    Frames numbered below ``start`` are skipped."""
    for frame in read_percepts(path, skipped):
        if frame.frame >= start:
            yield partial(SourceFrame, frame, 0.0)


def percept_stream(scenario: Path, seed: int, cache: Path) -> Path:
    """The perceived stream of ``scenario`` with noise seed ``seed``, cached in ``cache`` as
    JSON Lines (perceived once; written whole or not at all).

    The file's name carries the digest of the category model that perceived it
    (``<scenario>_seed<seed>.<digest>.jsonl``): after the classifier is trained again the
    scenario is perceived again, and the streams of this scenario and seed perceived with
    another model are removed."""
    from probanchor.perception.classifier import model_digest

    stem = f"{scenario.stem}_seed{seed}"
    path = cache / f"{stem}.{model_digest()}.jsonl"
    if not path.exists():
        cache.mkdir(parents=True, exist_ok=True)
        partial = path.with_suffix(".partial")
        write_percepts(partial, perceive_scenario(scenario, seed=seed))
        for stale in (*cache.glob(f"{stem}.*.jsonl"), cache / f"{stem}.jsonl"):
            if stale != path:
                stale.unlink(missing_ok=True)
        partial.rename(path)
    return path
