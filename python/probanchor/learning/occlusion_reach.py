"""The reach of an occlusion's onset, fitted from the data ``anchoring collect`` writes.

A learned theory draws ``occluder(A, O):t+1`` only for the pairs that can matter: those where O
already hid A (the occlusion may go on), where A was lost while the camera saw nothing (any
occluder on the table may have it), and those where O is within the *onset reach* of where A
was (the table-plane distance from A's last belief to O's new position). Beyond the reach the
learned tree gives an onset a negligible probability, and drawing it in every particle for
every (hidden, perceived) pair is what makes a learned theory slower than the hand-written one.

The reach is not set by hand: it is the distance within which ``QUANTILE`` of the data's onsets
lie (pairs labelled covered at t+1, not known covered at t, A not lost anywhere, in the states an
ideal particle holds: not the ``_c`` copies of a particle that has lost the object), times a
margin; onsets by occluders of the kinds the theory never asks the tree about (a carrier, a kind
that cannot occlude: ``exclude``) do not count. The few onsets beyond it are of objects that had
gone out of a particle's knowledge far from where they were last seen (behind something, then
covered while moved): a particle finds them again when they reappear, as with the hand-written
theory's ``occluder_reach``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["MARGIN", "QUANTILE", "DataPoints", "OnsetReach", "onset_reach", "read_points"]

#: The share of the onsets within the reach (before the margin).
QUANTILE = 0.9
#: The reach is the quantile's distance times this.
MARGIN = 2.0

_POS_T = re.compile(r"^pos\((\w+)\):t ~= \(([-\d.e]+), ([-\d.e]+), ([-\d.e]+)\)\.$")
_POS_T1 = re.compile(r"^pos\((\w+)\):t\+1 ~= \(([-\d.e]+), ([-\d.e]+), ([-\d.e]+)\)\.$")
_KNOWN = re.compile(r"^(?:([\d.e-]+) :: )?occluded_by\((\w+), (\w+)\):t\.$")
_CATEGORY = re.compile(r"^category\((\w+), (\w+)\)\.$")
_SEEN = re.compile(r"^seen\((\w+)\):t\.$")
_LOST = re.compile(r"^lost_anywhere\((\w+)\):t\.$")
_PAIR = re.compile(r"^pair\((\w+), (\w+)\):t\+1\.$")
_TARGET = re.compile(r"^(?:([\d.e-]+) :: )?occluder\((\w+), (\w+)\):t\+1\.$")
_WEIGHT = re.compile(r"^weight\(occluder\((\w+), (\w+)\):t\+1, (\d+)\)\.$")

Point = tuple[float, float, float]


@dataclass
class DataPoints:
    """The facts of data files ``anchoring collect`` wrote, by constant: positions at t and at
    t+1, the categories, who was seen at t, lost anywhere at t, the pairs with what was known
    at t (the probability that O hid A), their label (the probability that O hides A at t+1)
    and their weight."""

    pos_t: dict[str, Point] = field(default_factory=dict)
    pos_t1: dict[str, Point] = field(default_factory=dict)
    kind: dict[str, str] = field(default_factory=dict)
    seen: set[str] = field(default_factory=set)
    lost: set[str] = field(default_factory=set)
    known: dict[tuple[str, str], float] = field(default_factory=dict)
    label: dict[tuple[str, str], float] = field(default_factory=dict)
    weight: dict[tuple[str, str], int] = field(default_factory=dict)


def read_points(data: Sequence[str | Path]) -> DataPoints:
    """The facts of the data files (see :class:`DataPoints`)."""
    d = DataPoints()
    for path in data:
        for line in Path(path).read_text(encoding="utf-8").splitlines():
            _read_line(line.strip(), d)
    return d


def _read_line(line: str, d: DataPoints) -> None:
    if m := _POS_T.match(line):
        d.pos_t[m[1]] = (float(m[2]), float(m[3]), float(m[4]))
    elif m := _POS_T1.match(line):
        d.pos_t1[m[1]] = (float(m[2]), float(m[3]), float(m[4]))
    elif m := _CATEGORY.match(line):
        d.kind[m[1]] = m[2]
    elif m := _SEEN.match(line):
        d.seen.add(m[1])
    elif m := _LOST.match(line):
        d.lost.add(m[1])
    elif m := _KNOWN.match(line):
        d.known[(m[2], m[3])] = 1.0 if m[1] is None else float(m[1])
    elif m := _PAIR.match(line):
        d.label.setdefault((m[1], m[2]), 0.0)
    elif m := _TARGET.match(line):
        d.label[(m[2], m[3])] = 1.0 if m[1] is None else float(m[1])
    elif m := _WEIGHT.match(line):
        d.weight[(m[1], m[2])] = int(m[3])


@dataclass(frozen=True)
class OnsetReach:
    """The fitted reach (m), the quantile's distance (m) and how many onsets it was fitted
    from."""

    reach: float
    quantile: float
    onsets: int


def onset_reach(data: Sequence[str | Path], exclude: Iterable[str] = (),
                margin: float = MARGIN, quantile: float = QUANTILE) -> OnsetReach:
    """The onset reach fitted from data files (see the module docstring); ``exclude``: the
    occluders' categories whose onsets do not count.

    Raises
    ------
    ValueError
        The data hold no onset (nothing to fit the reach from).
    """
    distances = sorted(_onset_distances(read_points(data), set(exclude)))
    if not distances:
        raise ValueError(f"no occlusion onset in {', '.join(map(str, data))}: "
                         "no reach to fit")
    q = distances[min(len(distances) - 1, math.ceil(quantile * len(distances)) - 1)]
    return OnsetReach(round(margin * q, 4), q, len(distances))


def _onset_distances(d: DataPoints, exclude: set[str]) -> Iterable[float]:
    for (a, o), p in d.label.items():
        if (p <= 0.5 or d.known.get((a, o), 0.0) > 0.5 or a in d.lost or a.endswith("_c")
                or a not in d.pos_t or o not in d.pos_t1 or d.kind.get(o) in exclude):
            continue
        (x, y, _), (xo, yo, _) = d.pos_t[a], d.pos_t1[o]
        yield ((x - xo) ** 2 + (y - yo) ** 2) ** 0.5
