"""The examples a learned theory's filter asks its tree about, kept in the data it is learned from.

A learned theory draws ``occluder(A, O):t+1`` only for the pairs its glue's ``pair/2`` lets
through (``prolog/too/too_learned_glue.pl``): O already hid A at t, A was lost while the camera
saw nothing, or O is within the onset reach of its kind from where A was
(:mod:`probanchor.learning.occlusion_reach`). A data point beyond that reach, neither known nor
lost, is a question the filter never asks; learned from, it still shapes the leaf it falls in.
The ``_c`` copies ``anchoring collect`` writes (a particle that has lost a covered object, with
no occluder known, where the object was last seen) keep their label while the container carries
the object away, so they hold positives 15 cm to a metre from where the object was: a leaf's
logistic regression over the distance, fitted through them, gave a hidden ball a chance of a
third a frame to go under a mug standing still 10 cm away.

:func:`asked_data` writes copies of the data files without the examples the filter never asks
about: their ``pair/2`` fact, label and weight lines are blanked (the line numbers stay those of
the original file).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from probanchor.learning.occlusion_reach import DataPoints, OnsetReach, pair_of_line

__all__ = ["asked", "asked_data"]


def asked(points: DataPoints, reach: OnsetReach) -> set[tuple[str, str]]:
    """The pairs (A, O) of the data that the filter asks about: O hid A at t (with any
    probability), A was lost anywhere, or O is within the reach of its kind from where A was."""
    out = set()
    for a, o in points.label:
        if points.known.get((a, o), 0.0) > 0.0 or a in points.lost:
            out.add((a, o))
            continue
        if a not in points.pos_t or o not in points.pos_t1:
            continue
        (x, y, _), (xo, yo, _) = points.pos_t[a], points.pos_t1[o]
        r = reach.of(points.kind.get(o))
        if (x - xo) ** 2 + (y - yo) ** 2 < r * r:
            out.add((a, o))
    return out


def asked_data(data: Sequence[str | Path], points: DataPoints, reach: OnsetReach,
               folder: str | Path) -> tuple[list[Path], int]:
    """Copies of ``data`` in ``folder`` (same file names, one subfolder each) without the
    examples the filter never asks about (see the module docstring); ``points``: the data's
    points. Returns the copies and how many examples were left out."""
    keep = asked(points, reach)
    out, dropped = [], 0
    for number, path in enumerate(map(Path, data)):
        lines = path.read_text(encoding="utf-8").splitlines()
        for k, line in enumerate(lines):
            pair = pair_of_line(line.strip())
            if pair is not None and pair not in keep:
                dropped += line.startswith("pair(")
                lines[k] = ""
        copy = Path(folder) / str(number) / path.name
        copy.parent.mkdir(parents=True, exist_ok=True)
        copy.write_text("\n".join(lines) + "\n", encoding="utf-8")
        out.append(copy)
    return out, dropped
