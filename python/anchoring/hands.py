"""Hands: one anchor per hand in view, whatever skin segments it is seen as.

A hand is seen as skin percepts (best category ``skin`` or ``hand``) whose extent changes from
frame to frame: a few centimetres at the image's edge as it comes in, hand and forearm
together, two pieces when an object stands in front of the arm. Their centres jump by more
than the learned matcher accepts (it was trained on objects that do not change shape), so a
hand got a new symbol every time (``skin-1``, ``skin-2``, ...) and the one it had could not
carry anything. Hands are matched apart from the other anchors, by where they close: a skin
percept's *grip point* (``Percept.grip``, from perception; its position when a stream has
none).

Per frame (:func:`match_hands`):

- a skin percept may re-acquire a hand anchor when its grip point is within ``reach`` plus
  ``speed`` times the time since of one of the hand's grip points of the last second (a hand
  moving at up to ``speed`` m/s; one frame's wrong grip point, two arms seen as one segment,
  does not lose it); percepts and hands are assigned one to one, the likeliest first
  (Hungarian method on the negative log density of a Gaussian around the hand's last grip
  point whose spread grows with the time since it was seen);
- a skin percept left over, no longer than ``PIECE_LENGTH`` in the table plane, whose 3-D box
  is within ``piece_gap`` of the box of a percept that re-acquired or acquired a hand this
  frame is a piece of that hand (withheld: no symbol of its own; a forearm beside it is another
  arm);
- any other skin percept acquires a new hand anchor.

A hand that leaves the view and comes back re-acquires a hand anchor not in view (the
likeliest by the rule above, its gate and spread having grown with the time: the hand that
left last, unless another left nearer). Hands look alike: which hand came back is not told by
appearance; one anchor per hand the view has held at once keeps the theory of occlusion's
objects few and lets a hand carry what it held out of view back in.

Knows nothing of the reasoning or of the simulator.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linear_sum_assignment

from anchoring.anchor import Anchor
from probanchor.percepts import Percept

#: The categories of hands' percepts and anchors.
HAND_CATEGORIES = frozenset({"skin", "hand"})
#: A skin percept longer than this (metres, in the table plane) is an arm, never a piece.
PIECE_LENGTH = 0.15
#: A hand's grip points of the last this many seconds gate its matching.
RECENT = 1.0


@dataclass(frozen=True)
class HandRules:
    """How hands are matched (lengths in metres, ``speed`` in metres per second)."""

    speed: float = 6.0
    reach: float = 0.12
    piece_gap: float = 0.05

    def __post_init__(self) -> None:
        for name in ("speed", "reach", "piece_gap"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and np.isfinite(value) and value >= 0):
                raise ValueError(f"hand rule {name} must be a non-negative number, not {value!r}")


#: The rules an :class:`~anchoring.AnchorManager` matches hands by unless told otherwise.
DEFAULT_HAND_RULES = HandRules()


@dataclass
class HandMatch:
    """One frame's hands: indices into the skin percepts and the hand anchors given to
    :func:`match_hands`."""

    reacquire: dict[int, int] = field(default_factory=dict)  # percept -> hand anchor
    pieces: dict[int, int] = field(default_factory=dict)  # percept -> percept it is part of
    new: list[int] = field(default_factory=list)  # percepts that acquire a hand anchor


def is_hand_percept(percept: Percept) -> bool:
    return percept.best_category in HAND_CATEGORIES


def is_hand(anchor: Anchor) -> bool:
    """An anchor acquired as a hand (its symbol's category: it stays a hand)."""
    return anchor.symbol_category in HAND_CATEGORIES


def grip_of(percept: Percept) -> np.ndarray:
    """Where a hand's percept closes: its grip point, else its position."""
    return percept.position if percept.grip is None else percept.grip


def reasoning_position(percept: Percept) -> np.ndarray:
    """The position the reasoning is told for a perceived anchor: a hand's grip point (what
    it holds is there), any other percept's position."""
    return grip_of(percept) if is_hand_percept(percept) else percept.position


def last_grip(anchor: Anchor) -> np.ndarray:
    """The grip point of a hand anchor's last percept."""
    if anchor.history:
        return grip_of(anchor.history[-1])
    return np.asarray(anchor.position.mean(), dtype=float)


def _reach_needed(hand: Anchor, grips: np.ndarray, time: float, speed: float) -> np.ndarray:
    """For each grip point (P, 3): how far it is from the hand anchor's grip points of the
    last ``RECENT`` seconds, beyond what ``speed`` covers since each (the least over them), so
    that one frame's wrong grip point (two arms seen as one segment) does not lose the hand."""
    recent = [p for p in hand.history if time - p.time <= RECENT] or list(hand.history)[-1:]
    if not recent:
        return np.linalg.norm(grips - np.asarray(hand.position.mean()), axis=1)
    past = np.array([grip_of(p) for p in recent])
    ago = np.array([max(time - p.time, 0.0) for p in recent])
    dist = np.linalg.norm(past[:, None, :] - grips[None, :, :], axis=2) - speed * ago[:, None]
    return np.maximum(dist, 0.0).min(axis=0)


def _box_gap(a: Percept, b: Percept) -> float:
    """The distance between two percepts' 3-D boxes (0 when they overlap)."""
    gap = np.abs(a.position - b.position) - (a.size + b.size) / 2
    return float(np.linalg.norm(np.maximum(gap, 0.0)))


def match_hands(hands: Sequence[Anchor], percepts: Sequence[Percept], time: float,
                rules: HandRules) -> HandMatch:
    """Which skin percepts re-acquire which hand anchors, are pieces of another, or are new.

    Parameters
    ----------
    hands:
        The hand anchors (see :func:`is_hand`).
    percepts:
        The frame's valid skin percepts (see :func:`is_hand_percept`).
    time:
        The frame's time (seconds).
    rules:
        The gate and the piece gap.

    Returns
    -------
    A :class:`HandMatch` of indices into ``percepts`` and ``hands``.
    """
    out = HandMatch()
    if not percepts:
        return out
    taken: dict[int, int] = {}
    if hands:
        grips = np.array([grip_of(p) for p in percepts])
        gate = np.array([_reach_needed(h, grips, time, rules.speed) for h in hands]) \
            <= rules.reach
        lasts = np.array([last_grip(h) for h in hands])
        dist = np.linalg.norm(lasts[:, None, :] - grips[None, :, :], axis=2)
        since = np.array([max(time - h.last_seen, 0.0) for h in hands])
        if gate.any():
            # among as many gated pairs as possible, the likeliest: a hand is where it was last
            # seen, give or take a spread that grows with the time since (an isotropic Gaussian,
            # its negative log density); so a hand seen a frame ago takes a percept beside it
            # before one that left the view long ago, whose spread covers the whole table
            spread = (rules.reach / 2 + rules.speed * since)[:, None]
            cost = np.where(gate, 0.5 * (dist / spread) ** 2 + 3 * np.log(spread), 1e9)
            rows, cols = linear_sum_assignment(cost)
            for r, c in zip(rows, cols, strict=True):
                if gate[r, c]:
                    taken[int(c)] = int(r)
    out.reacquire = dict(taken)
    for j, percept in enumerate(percepts):
        if j in taken:
            continue
        owners = [k for k in taken if _box_gap(percept, percepts[k]) <= rules.piece_gap
                  and float(percept.size[:2].max()) <= PIECE_LENGTH]
        if owners:
            out.pieces[j] = min(owners, key=lambda k: _box_gap(percept, percepts[k]))
        else:
            out.new.append(j)
            taken[j] = -1  # a new hand: later pieces may belong to it
    return out


def _bboxes_touch(a: tuple[int, int, int, int], b: tuple[int, int, int, int],
                  pixels: int) -> bool:
    """Whether two image boxes (x0, y0, x1, y1) overlap or are within ``pixels``."""
    return (a[0] <= b[2] + pixels and b[0] <= a[2] + pixels
            and a[1] <= b[3] + pixels and b[1] <= a[3] + pixels)


def _footprints_overlap(anchor: Anchor, percept: Percept, margin: float) -> bool:
    """Whether the percept's box and the anchor's overlap in the table plane (heights left
    out), the anchor's placed at its last perceived position or at any particle of positive
    weight."""
    half = (anchor.size.samples[0][:2] + percept.size[:2]) / 2 + margin
    centres = [anchor.history[-1].position[None, :2]] if anchor.history else []
    position = anchor.position
    samples = position.samples[position.weights > 0] if position.is_probabilistic \
        else position.samples
    centres.append(samples[:, :2])
    return any(bool(np.any(np.all(np.abs(c - percept.position[:2]) <= half, axis=1)))
               for c in centres)


def _alike(anchor: Anchor, percept: Percept, colour: float, min_colour: float) -> bool:
    # a named colour in common is enough: in the arm's shadow a white mug's foot is 0.47
    # similar to it, where unrelated colours are 0.46-0.50 similar to each other
    named = bool(percept.colour_names) and percept.colour_names[0] in anchor.colour_names
    return colour >= min_colour or named


def views_under_hands(anchors: Sequence[Anchor], frame: Sequence[Percept],
                      colour: np.ndarray, left: Sequence[int], hands: Sequence[Percept],
                      margin: float = 0.05, min_colour: float = 0.7, pixels: int = 2
                      ) -> dict[int, list[str]]:
    """Percepts that are what an arm in front leaves in view of an anchor: withheld.

    An arm reaching over the table hides part of what it passes over; what is left in view
    (the top of a mug above the forearm, its foot below it) is described as an object of its
    own, at the height of the part seen, often of another category; left to the matcher it
    acquired a new anchor (``ball-2`` for the foot of ``mug-1``), and the object's identity was
    lost. A percept left unmatched whose image box touches a hand's percept's (within
    ``pixels``), whose footprint in the table plane overlaps (within ``margin``: the part in
    view may be the near rim of a mug whose far rim was seen last, 8 cm away) that of an
    anchor (at its last perceived position or at a particle; perceived this frame or not: the
    other part of it may be in view too) and whose
    colour is not unlike that anchor's (similarity >= ``min_colour``, or its first colour name
    one of the anchor's: the part of a mug below a forearm is in its shadow) is withheld: no symbol,
    reported with those anchors. Heights are left out: the part in view may be any slice of
    the object. Unlike :func:`anchoring.views.withheld_views` there is no time limit: it lasts
    while a hand is in front.

    Parameters
    ----------
    anchors, frame:
        The anchors and percepts the frame's matching compared.
    colour:
        (A, P) colour similarities of those anchors and percepts.
    left:
        The percepts (indices into ``frame``) left unmatched and not withheld otherwise.
    hands:
        The frame's hand percepts.

    Returns
    -------
    ``{percept index: [anchor symbols]}``.
    """
    out: dict[int, list[str]] = {}
    if not hands or not anchors:
        return out
    for j in left:
        percept = frame[j]
        if not any(_bboxes_touch(percept.bbox, h.bbox, pixels) for h in hands):
            continue
        hits = [anchors[k].symbol for k in range(len(anchors))
                if _alike(anchors[k], percept, float(colour[k, j]), min_colour)
                and _footprints_overlap(anchors[k], percept, margin)]
        if hits:
            out[j] = hits
    return out
