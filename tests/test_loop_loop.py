"""run_frames: the next frame is perceived while the current one is processed (overlap), or
after it (sequential); either way the same frames go through the loop in the same order."""

from __future__ import annotations

import threading
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np
import pytest

from percept_helpers import ball_percept
from probanchor.evaluation import FrameTimings
from probanchor.loop.loop import run_frames
from probanchor.loop.runner import RunOptions, run
from probanchor.loop.sources import SourceFrame
from probanchor.percepts import PerceptFrame, write_percepts

FRAMES = 5


class FakeLoop:
    """Records the order of events; advance(k) can wait until frame k+1's perception began."""

    def __init__(self, wait_for_next: bool) -> None:
        self.log: list[str] = []
        self.lock = threading.Lock()
        self.perceiving = [threading.Event() for _ in range(FRAMES)]
        self.wait_for_next = wait_for_next
        self.overlapped: list[bool] = []

    def note(self, event: str) -> None:
        with self.lock:
            self.log.append(event)

    def pending(self, k: int):
        def perceive() -> SourceFrame:
            self.perceiving[k].set()
            self.note(f"perceive {k}")
            return SourceFrame(PerceptFrame(k, k / 5, []), perception_ms=1.0)
        return perceive

    def advance(self, source: SourceFrame) -> SimpleNamespace:
        k = source.percepts.frame
        self.note(f"advance {k}")
        if self.wait_for_next and k + 1 < FRAMES:
            # not timing: a sequential loop would never start frame k+1 before this returns
            self.overlapped.append(self.perceiving[k + 1].wait(timeout=30))
        return SimpleNamespace(frame=k, timings=FrameTimings(perception=1.0, anchoring=2.0,
                                                             filter=3.0))

    def finish(self, step: SimpleNamespace) -> SimpleNamespace:
        self.note(f"finish {step.frame}")
        return SimpleNamespace(record=SimpleNamespace(frame=step.frame, timings=step.timings))


def test_the_next_frame_is_perceived_while_the_current_one_is_processed() -> None:
    loop = FakeLoop(wait_for_next=True)
    records = run_frames([loop.pending(k) for k in range(FRAMES)], loop)  # type: ignore[arg-type]
    assert [r.frame for r in records] == list(range(FRAMES))
    assert loop.overlapped == [True] * (FRAMES - 1)
    # each frame's stage is timed as a whole, the last one (nothing to overlap) too: no record
    # leaves its total out
    assert all(r.timings.total is not None for r in records)


def test_sequential_perceives_each_frame_after_the_previous_one_is_processed() -> None:
    loop = FakeLoop(wait_for_next=False)
    records = run_frames([loop.pending(k) for k in range(FRAMES)], loop,  # type: ignore[arg-type]
                         overlap=False)
    expected = ["perceive 0"]
    for k in range(FRAMES):
        expected += [f"advance {k}"] + ([f"perceive {k + 1}"] if k + 1 < FRAMES else [])
        expected += [f"finish {k}"]
    assert loop.log == expected
    assert all(r.timings.total == 6.0 for r in records)  # the sum of the parts, recorded


def test_a_perception_error_stops_the_run() -> None:
    loop = FakeLoop(wait_for_next=False)

    def broken() -> SourceFrame:
        raise ValueError("camera frame unreadable")

    with pytest.raises(ValueError, match="unreadable"):
        run_frames([loop.pending(0), broken, loop.pending(2)], loop)  # type: ignore[arg-type]


def _ball_stream(path: Path) -> Path:
    # a ball that vanishes for three frames and comes back a little further on
    frames = [PerceptFrame(k, k / 5, [] if 3 <= k < 6 else [ball_percept(k / 5, 0.02 * k)])
              for k in range(9)]
    write_percepts(path, frames)
    return path


def test_overlap_changes_timing_only(tmp_path: Path) -> None:
    stream = _ball_stream(tmp_path / "stream.jsonl")
    outputs: dict[bool, Any] = {
        overlap: run(RunOptions(percepts=stream, particles=30, progress=False, overlap=overlap))
        for overlap in (True, False)
    }
    summaries = [{k: v for k, v in outputs[o].summary.items() if k != "ms_per_frame"}
                 for o in (True, False)]
    assert summaries[0] == summaries[1]
    for a, b in zip(outputs[True].records, outputs[False].records, strict=True):
        assert a.hypotheses.keys() == b.hypotheses.keys()
        for symbol in a.hypotheses:
            assert np.array_equal(a.hypotheses[symbol].position, b.hypotheses[symbol].position)
