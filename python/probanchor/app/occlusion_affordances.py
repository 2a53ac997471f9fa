"""Affordances read from the data ``anchoring collect`` writes, with their probabilities.

Per category of the perceived object O of a data point (a pair of a hidden A and O):

- *hides*: of all the pairs, the share in which O hides A (labelled covered at t+1): whether
  a kind affords hiding things. Balls and cans hide (nearly) nothing; containers and hands do.
- *carries*: of the occlusions going on (O known to hide A at t) with O's centre more than
  ``lift`` above where A stood (lifted well off the table), the share in which O still hides
  A at t+1: whether a kind carries what it hides through the air (a hand) or leaves it on the
  table when it is lifted (a mug, a box).

Each is a share of the data points' weights with a Beta(1, 1) prior (Laplace's rule: a kind
never seen to hide anything in n pairs hides with probability 1 / (n + 2)), and the number of
data points it was read from.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from probanchor.app.occlusion_reach import read_points

__all__ = ["LIFT", "Affordance", "affordances", "affordance_table"]

#: O is lifted off what it hid when its centre is more than this (m) above where A stood.
LIFT = 0.15


@dataclass(frozen=True)
class Affordance:
    """P(the kind hides, or carries) and the data points (weights summed) it was read from."""

    probability: float
    points: float


def affordances(data: Sequence[str | Path], lift: float = LIFT
                ) -> dict[str, dict[str, Affordance]]:
    """``{"hides": {kind: Affordance}, "carries": {kind: Affordance}}`` from data files (see
    the module docstring)."""
    d = read_points(data)
    hides: dict[str, list[float]] = {}
    carries: dict[str, list[float]] = {}
    for (a, o), p in d.label.items():
        if a.endswith("_c") or a not in d.pos_t or o not in d.pos_t1 or o not in d.kind:
            continue
        w = float(d.weight.get((a, o), 1))
        _count(hides, d.kind[o], p, w)
        if d.known.get((a, o), 0.0) > 0.5 and d.pos_t1[o][2] - d.pos_t[a][2] > lift:
            _count(carries, d.kind[o], p, w)
    return {"hides": _shares(hides), "carries": _shares(carries)}


def _count(counts: dict[str, list[float]], kind: str, p: float, w: float) -> None:
    c = counts.setdefault(kind, [0.0, 0.0])
    c[0] += p * w
    c[1] += w


def _shares(counts: dict[str, list[float]]) -> dict[str, Affordance]:
    return {k: Affordance((yes + 1.0) / (n + 2.0), n) for k, (yes, n) in sorted(counts.items())}


def affordance_table(found: dict[str, dict[str, Affordance]]) -> str:
    """A Markdown table of :func:`affordances`: per kind, P(hides) and P(carries) with the
    data points each was read from."""
    kinds = sorted(set(found["hides"]) | set(found["carries"]))

    def cell(a: Affordance | None) -> str:
        return "-" if a is None else f"{a.probability:.3g} ({a.points:,.0f})"

    lines = ["| kind of O | P(O hides a hidden A) (weight) | "
             "P(O carries what it hid when lifted off) (weight) |", "|---|---:|---:|"]
    lines += [f"| {k} | {cell(found['hides'].get(k))} | {cell(found['carries'].get(k))} |"
              for k in kinds]
    return "\n".join(lines) + "\n"
