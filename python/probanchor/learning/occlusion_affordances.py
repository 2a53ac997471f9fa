"""Affordances read from the data ``anchoring collect`` writes, with their probabilities.

Per category of the perceived object O of a data point (a pair of a hidden A and O):

- *hides*: of all the pairs, the share in which O hides A (labelled covered at t+1): whether
  a kind affords hiding things. Balls and cans hide (nearly) nothing; containers and hands do.
- *hidden*: per category of the hidden object A, the share of its pairs in which something
  hides it: whether a kind can be hidden at all (a hand is never under anything).
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

from probanchor.learning.occlusion_reach import DataPoints, read_points

__all__ = ["LIFT", "MIN_CARRIES", "MIN_SHARE", "Affordance", "affordance_clauses", "affordances",
           "affordance_table", "carriers", "never_occluders"]

#: O is lifted off what it hid when its centre is more than this (m) above where A stood.
LIFT = 0.15
#: A kind that hides fewer than this share of the hidden objects it is paired with is not asked
#: about as an occluder (the tree would give it about that probability per pair and frame: with
#: a thousand particles, a few of them would put a ball under a ball every frame); one hidden in
#: fewer than this share of its pairs is not asked about as hidden.
MIN_SHARE = 0.01
#: A carrier holds what it hid when lifted off with a probability above 1/2, read from at least
#: this weight of data points: hindsight labels keep a lifted box covering until what it covered
#: is seen, a few frames of a lift, while a hand holds what it carries for seconds.
MIN_CARRIES = 50


@dataclass(frozen=True)
class Affordance:
    """P(the kind hides, or carries) and the data points (weights summed) it was read from."""

    probability: float
    points: float


def affordances(data: Sequence[str | Path] | DataPoints, lift: float = LIFT
                ) -> dict[str, dict[str, Affordance]]:
    """``{"hides": {kind: Affordance}, "hidden": {...}, "carries": {...}}`` from data files or
    their points (see the module docstring)."""
    d = data if isinstance(data, DataPoints) else read_points(data)
    hides: dict[str, list[float]] = {}
    hidden: dict[str, list[float]] = {}
    carries: dict[str, list[float]] = {}
    for (a, o), p in d.label.items():
        if a.endswith("_c") or a not in d.pos_t or o not in d.pos_t1 or o not in d.kind:
            continue
        w = float(d.weight.get((a, o), 1))
        _count(hides, d.kind[o], p, w)
        if a in d.kind:
            _count(hidden, d.kind[a], p, w)
        if d.known.get((a, o), 0.0) > 0.5 and d.pos_t1[o][2] - d.pos_t[a][2] > lift:
            _count(carries, d.kind[o], p, w)
    return {"hides": _shares(hides), "hidden": _shares(hidden), "carries": _shares(carries)}


def _count(counts: dict[str, list[float]], kind: str, p: float, w: float) -> None:
    c = counts.setdefault(kind, [0.0, 0.0])
    c[0] += p * w
    c[1] += w


def _shares(counts: dict[str, list[float]]) -> dict[str, Affordance]:
    return {k: Affordance((yes + 1.0) / (n + 2.0), n) for k, (yes, n) in sorted(counts.items())}


def affordance_table(found: dict[str, dict[str, Affordance]]) -> str:
    """A Markdown table of :func:`affordances`: per kind, P(hides), P(hidden) and P(carries)
    with the weight of the data points each was read from."""
    kinds = sorted(set(found["hides"]) | set(found["hidden"]) | set(found["carries"]))

    def cell(a: Affordance | None) -> str:
        return "-" if a is None else f"{a.probability:.3g} ({a.points:,.0f})"

    lines = ["| kind | P(it hides a hidden object) (weight) | P(something hides it) (weight) | "
             "P(it carries what it hid when lifted off) (weight) |", "|---|---:|---:|---:|"]
    lines += [f"| {k} | {cell(found['hides'].get(k))} | {cell(found['hidden'].get(k))} | "
              f"{cell(found['carries'].get(k))} |" for k in kinds]
    return "\n".join(lines) + "\n"


def never_occluders(found: dict[str, dict[str, Affordance]]) -> list[str]:
    """The kinds the theory written from ``found`` never asks the tree about as occluders:
    those that hide less than MIN_SHARE, and carriers."""
    return sorted({k for k, a in found["hides"].items() if a.probability < MIN_SHARE}
                  | set(carriers(found)))


def carriers(found: dict[str, dict[str, Affordance]]) -> list[str]:
    """The kinds that carry what they hide: P(carries) above 1/2 from at least MIN_CARRIES."""
    return sorted(k for k, a in found["carries"].items()
                  if a.probability > 0.5 and a.points >= MIN_CARRIES)


def affordance_clauses(found: dict[str, dict[str, Affordance]]) -> str:
    """The affordances as clauses of a theory: the probabilities as facts, and the
    can_occlude/1, is_carrier/1, hand_known/0 and can_be_occluded/1 the rules read."""
    out = ["% " + "-" * 66 + " learned affordances",
           "% Read from the data (python/probanchor/learning/occlusion_affordances.py): the share",
           "% of the hidden objects a kind hides, of the pairs in which it is hidden itself,",
           "% and of the occlusions going on in which it still holds what it hid when lifted",
           "% off (Laplace's rule; the data points' weight in the comment).  A kind is asked",
           f"% about as an occluder when it hides at least {MIN_SHARE:g} of them and is no",
           f"% carrier, as hidden when it is at least {MIN_SHARE:g} of the time; a carrier holds",
           "% what it hid when lifted off with a probability above 1/2, read from a weight of",
           f"% at least {MIN_CARRIES} data points (too/too_motion.pl's carriers' rules apply to",
           "% it).",
           ]
    for name, key in (("hides", "hides"), ("hidden_share", "hidden"), ("carries", "carries")):
        out += [f"{name}({k}, {a.probability:.4g}).  % {a.points:,.0f}"
                for k, a in found[key].items()]
    kinds = carriers(found)
    out += [f"carrier({k})." for k in kinds]
    out += [f"can_occlude(O) := category(O, C), hides(C, P), P >= {MIN_SHARE:g}, "
            "\\+ is_carrier(O).",
            "is_carrier(O) := category(O, C), carrier(C)." if kinds else
            "is_carrier(_) := false.  % no kind carries in the data",
            "hand_known := object(O), is_carrier(O).",
            f"can_be_occluded(A) := category(A, C), hidden_share(C, P), P >= {MIN_SHARE:g}."]
    return "\n".join(out) + "\n"
