"""Frame files (the observations and actions of ``ddc filter``, JSON Lines) read by the DDC system.

The format has one reader, ``read_frame_file/2`` in ``prolog/ddc/filter/ddc_belief.pl`` (swipl users
filter with it through ``belief_run/2``); this module asks it, through the bridge's helper
(``bridge_frames/2`` in ``prolog/ddc/filter/ddc_bridge.pl``), and hands the frames to Python as term
texts that :meth:`bridge.Filter.step` takes as they are. The format: docs/filter.md.

Example::

    from bridge.frames import read_frames
    for frame in read_frames("prolog/examples/filter/wumpus.jsonl"):
        f.step(frame.observations, frame.actions)
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from bridge.errors import FrameFileError
from bridge.filter import FilterError, call_helper
from bridge.prolog import OUT
from bridge.terms import Text

__all__ = ["Frame", "FrameFileError", "read_frames"]


@dataclass(frozen=True)
class Frame:
    """One line of a frame file: its 1-based number, observations and actions (term text)."""

    line: int
    observations: list[Text]
    actions: list[Text]


def read_frames(path: str | os.PathLike[str]) -> list[Frame]:
    """Every frame of the file at ``path`` (the whole file is read and checked first: a bad
    line raises :class:`FrameFileError` naming the file, the line and the cause)."""
    try:
        result = call_helper("bridge_frames", F=os.fspath(path), Frames=OUT)
    except FrameFileError:  # (ddc_belief(frame(File, Line, Cause)): "file:line: cause")
        raise
    except FilterError as error:  # (the file cannot be read: its message names it)
        raise FrameFileError(str(error), error.cause) from None
    return [
        Frame(int(line), [Text(str(t)) for t in observations], [Text(str(t)) for t in actions])
        for line, observations, actions in result["Frames"]
    ]
