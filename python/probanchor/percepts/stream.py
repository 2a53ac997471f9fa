"""JSON Lines percept streams: one frame per line, ``{"frame": k, "time": t, "percepts": [...]}``.

A recorded stream (or another robot's pipeline) can feed the anchoring system through this
format without the simulator. Optional ``"truth"`` per frame carries simulator ground truth for
evaluation; anchoring never reads it.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from probanchor.percepts.record import Percept, PerceptError


@dataclass
class PerceptFrame:
    frame: int
    time: float
    percepts: list[Percept]
    truth: dict[str, Any] = field(default_factory=dict)
    rejected: list[str] = field(default_factory=list)  # why percepts of this frame were dropped


def write_percepts(path: str | Path, frames: Iterable[PerceptFrame]) -> None:
    with open(path, "w", encoding="utf-8") as out:
        for fr in frames:
            line: dict[str, Any] = {
                "frame": fr.frame,
                "time": fr.time,
                "percepts": [p.to_json() for p in fr.percepts],
            }
            if fr.truth:
                line["truth"] = fr.truth
            out.write(json.dumps(line) + "\n")


def read_percepts(path: str | Path, skipped: list[str] | None = None
                  ) -> Iterator[PerceptFrame]:
    """Yield frames; a bad percept is dropped with its reason in ``frame.rejected``.

    A line that is not JSON, or not a frame (a truncated last line, a time that is not a
    finite number, a frame number that does not increase or a time earlier than the previous
    frame's: a duplicated or reordered line) raises :class:`PerceptError` naming file and
    line; with ``skipped``, that message is appended to it instead and the line is skipped.
    """
    last: tuple[int, float] | None = None          # the frame number and time of the last frame
    with open(path, encoding="utf-8") as src:
        for lineno, text in enumerate(src, start=1):
            if not text.strip():
                continue
            try:
                record = json.loads(text)
                frame = int(record["frame"])
                time = float(record["time"])
                raw = record["percepts"]
                if not isinstance(raw, list):
                    raise TypeError(f"'percepts' must be a list, not {type(raw).__name__}")
                _check_order(frame, time, last)
            except (json.JSONDecodeError, KeyError, TypeError, ValueError,
                    RecursionError) as exc:
                error = PerceptError(f"{path}:{lineno}: not a percept frame: {exc}")
                if skipped is None:
                    raise error from exc
                skipped.append(str(error))
                continue
            kept: list[Percept] = []
            rejected: list[str] = []
            for i, item in enumerate(raw):
                try:
                    percept = Percept.from_json(item)
                    percept.validate()
                except PerceptError as exc:
                    rejected.append(f"{path}:{lineno}: percept {i}: {exc}")
                    continue
                kept.append(percept)
            last = (frame, time)
            yield PerceptFrame(frame, time, kept, record.get("truth", {}), rejected)


def _check_order(frame: int, time: float, last: tuple[int, float] | None) -> None:
    """Raise ValueError unless a frame with this number and time may follow ``last``."""
    if not math.isfinite(time):
        raise ValueError(f"time is {time}")
    if last is None:
        return
    if frame <= last[0]:
        raise ValueError(f"frame {frame} follows frame {last[0]}: frame numbers must increase "
                         "(a duplicated or reordered line?)")
    if time < last[1]:
        raise ValueError(f"time {time} is before the previous frame's {last[1]}")
