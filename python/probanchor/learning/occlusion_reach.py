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
margin, the onsets far out (beyond Tukey's far fence, the upper quartile plus ``FAR``
interquartile ranges, as the grip reach's events) left out; onsets by occluders of the kinds
the theory never asks the tree about (a carrier, a kind that cannot occlude: ``exclude``) do
not count. It depends on the occluder's kind: a bowl 17 cm
across starts covering a ball up to 9 cm away, a mug within 3 cm. A kind with at least
``MIN_ONSETS`` onsets has a reach of its own, fitted from its onsets; the others have the
reach of all the onsets. (One reach for all, the bowls' and big boxes' onsets gave mugs a reach
of 23 cm, and the tree, asked about a mug that far from a ball hidden behind a bottle, put the
ball under it within seconds.) The few onsets beyond it are of objects that had
gone out of a particle's knowledge far from where they were last seen (behind something, then
covered while moved): a particle finds them again when they reappear, as with the hand-written
theory's ``occluder_reach``. A few such onsets at 23 to 26 cm among 35 boxes' (the others
within 7 cm) made the 90 % quantile of the boxes' onsets 24 cm and their reach 48 cm; the
far fence (10 cm there) leaves them out.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["FAR", "MARGIN", "MIN_ONSETS", "QUANTILE", "DataPoints", "OnsetReach", "not_far_out",
           "onset_reach", "pair_of_line", "read_points"]

#: The share of the onsets within the reach (before the margin).
QUANTILE = 0.9
#: The reach is the quantile's distance times this.
MARGIN = 2.0
#: A kind of occluder with at least this many onsets has a reach of its own.
MIN_ONSETS = 10
#: A reach leaves out events beyond the upper quartile plus this many interquartile ranges
#: (Tukey's "far out"; the grip reach too, :mod:`probanchor.learning.motion_grip`).
FAR = 3.0



def not_far_out(values: Iterable[float], far: float = FAR) -> np.ndarray:
    """The ``values`` (sorted) that are not far out: at most the upper quartile plus ``far``
    interquartile ranges (Tukey's far fence).

    Raises
    ------
    ValueError
        No value.
    """
    a = np.sort(np.asarray(list(values), dtype=float))
    if a.size == 0:
        raise ValueError("no samples")
    q1, q3 = np.quantile(a, [0.25, 0.75])
    return a[a <= q3 + far * (q3 - q1)]


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


def pair_of_line(line: str) -> tuple[str, str] | None:
    """The pair (A, O) a data line is about when it is the pair's example, label or weight
    (``pair(A, O):t+1.``, ``[P ::] occluder(A, O):t+1.``, ``weight(occluder(A, O):t+1, N).``),
    else None."""
    if m := _PAIR.match(line) or _WEIGHT.match(line):
        return m[1], m[2]
    if m := _TARGET.match(line):
        return m[2], m[3]
    return None


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
    """The fitted reach (m), the quantile's distance (m), how many onsets it was fitted
    from and how many of them were far out (left out); ``kinds``: the kinds of occluder with a
    reach of their own, each with its reach fitted the same way from its onsets alone."""

    reach: float
    quantile: float
    onsets: int
    far_out: int = 0
    kinds: dict[str, OnsetReach] = field(default_factory=dict)

    def of(self, kind: str | None) -> float:
        """The reach of an occluder of ``kind``: its own, else the reach of all onsets."""
        own = self.kinds.get(kind) if kind is not None else None
        return own.reach if own is not None else self.reach


def onset_reach(data: Sequence[str | Path] | DataPoints, exclude: Iterable[str] = (),
                margin: float = MARGIN, quantile: float = QUANTILE,
                min_onsets: int = MIN_ONSETS, far: float = FAR) -> OnsetReach:
    """The onset reach fitted from data files or their points (see the module docstring);
    ``exclude``: the occluders' categories whose onsets do not count; a kind with at least
    ``min_onsets`` onsets gets a reach of its own; onsets beyond Tukey's far fence (the upper
    quartile plus ``far`` interquartile ranges) are left out before the quantile.

    Raises
    ------
    ValueError
        The data hold no onset (nothing to fit the reach from).
    """
    points = data if isinstance(data, DataPoints) else read_points(data)
    onsets = list(_onsets(points, set(exclude)))
    if not onsets:
        where = "the data" if isinstance(data, DataPoints) else ", ".join(map(str, data))
        raise ValueError(f"no occlusion onset in {where}: no reach to fit")

    def fitted(distances: list[float]) -> OnsetReach:
        kept = not_far_out(distances, far)
        q = float(kept[min(len(kept) - 1, math.ceil(quantile * len(kept)) - 1)])
        return OnsetReach(round(margin * q, 4), q, len(distances), len(distances) - len(kept))

    by_kind: dict[str, list[float]] = {}
    for kind, distance in onsets:
        by_kind.setdefault(kind, []).append(distance)
    pooled = fitted([distance for _, distance in onsets])
    kinds = {kind: fitted(ds) for kind, ds in sorted(by_kind.items()) if len(ds) >= min_onsets}
    return OnsetReach(pooled.reach, pooled.quantile, pooled.onsets, pooled.far_out, kinds)


def _onsets(d: DataPoints, exclude: set[str]) -> Iterable[tuple[str, float]]:
    """(occluder's kind, distance) of every onset."""
    for (a, o), p in d.label.items():
        if (p <= 0.5 or d.known.get((a, o), 0.0) > 0.5 or a in d.lost or a.endswith("_c")
                or a not in d.pos_t or o not in d.pos_t1 or d.kind.get(o) in exclude):
            continue
        (x, y, _), (xo, yo, _) = d.pos_t[a], d.pos_t1[o]
        yield d.kind.get(o, "?"), ((x - xo) ** 2 + (y - yo) ** 2) ** 0.5
