"""Partial and merged views: percepts that must not get a symbol of their own (yet).

*Merged views* (:func:`merged_views`): a pair the matcher accepts is still refused when the
percept is far larger than the anchor in the table plane (``merge_ratio``: its largest
horizontal extent more than that many times the anchor's plus 2 cm), or when it holds the last
positions of two anchors just perceived and is larger than each: two objects seen as one
segment must not re-acquire one of them.

*Withheld views* (:func:`withheld_views`): an unmatched percept that is a plausible partial or
merged view of anchors not perceived this frame is withheld (no symbol, reported as
:class:`Withheld`): its 3-D box overlaps such an anchor's box placed at the anchor's last
perceived position or at one of its particles (:func:`boxes_overlap`), and its colour is not
unlike the anchor's; a merged view is withheld on account of the anchors merged in it. A mug's
rim above the box in front of it, the first sliver of a mug coming out from behind a box, a
container half revealed as its cover is lifted, two containers seen as one segment for a
frame: these are views of objects that already have anchors, and a new anchor for them would
give the object's percepts a second symbol. A percept withheld because of one anchor for longer
than ``withhold_seconds`` in a row is acquired after all (a new object put where a hidden one is
believed is not refused for ever).

*Views of a container over a hidden object* (:func:`container_views`): a hidden object the
reasoning has under an occluder is not re-acquired by a percept that overlaps an anchor that
was perceived within the last ``merge_seconds`` (half a second), is not perceived now, and
looks more like that percept (colour) than the hidden object does. Under a container that stood
there a moment ago, the hidden object can be seen only once the container has moved away,
which would be seen; what is seen there is a partial view of the container (its lower part
under something carried over it, which the classifier may take for a ball). The percept is
then left to the withheld views.

*Tracks through views* (:func:`track_views`, :func:`emerging_views`): a view withheld for an
anchor perceived a moment before (within ``recent_seconds``), or itself tracked through such a
view, is where that anchor was: its track goes on through the view. A percept left unmatched
that overlaps the box of that view, seen within ``recent_seconds`` before, and looks like that
anchor (:func:`anchoring.reidentify.looks_alike`) and like no other anchor so tracked there,
re-acquires it: a mug that passed behind a cup and was seen as one segment with it comes out
of the segment as the mug, wherever the reasoning had guessed it. The view is seen evidence;
the belief that would refuse the mug is a guess made while it was unseen (it turned inside
the segment, and the belief had coasted on).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from anchoring.anchor import Anchor
from anchoring.reidentify import looks_alike, one_to_one
from probanchor.percepts import Percept


@dataclass
class Withheld:
    """Percept ``percept_index`` was left without a symbol: it looks like a partial or merged
    view of the anchors ``symbols`` (not perceived this frame)."""

    percept_index: int
    symbols: list[str]


@dataclass
class ViewTrack:
    """An anchor's track through withheld views: the last view's ``time`` and 3-D box
    (``position``, its centre, and ``size``)."""

    time: float
    position: np.ndarray
    size: np.ndarray

    def to_json(self) -> dict[str, object]:
        return {"time": self.time, "position": self.position.tolist(),
                "size": self.size.tolist()}

    @classmethod
    def from_json(cls, record: dict[str, object]) -> ViewTrack:
        return cls(float(record["time"]),  # type: ignore[arg-type]
                   np.asarray(record["position"], dtype=float).reshape(3),
                   np.asarray(record["size"], dtype=float).reshape(3))


def merged_views(anchors: list[Anchor], frame: list[Percept], time: float,
                 merge_ratio: float, merge_seconds: float,
                 tracks: dict[str, ViewTrack] | None = None
                 ) -> tuple[np.ndarray, dict[int, list[int]]]:
    """Two objects seen as one segment: (A, P) pairs refused, and the percepts (index in
    ``frame``) judged merged -> the anchors (indices) merged in them.

    A pair is refused when the percept is far larger in the table plane than the anchor
    (``merge_ratio``), or when the percept's box holds the last perceived positions of two
    or more anchors perceived within ``merge_seconds`` and is larger than each of them
    (its largest horizontal extent over 1.2 times theirs plus 1 cm): a container lowered
    over a ball holds the ball's position too, but is not larger than itself. An anchor
    tracked through a view (``tracks``, :func:`track_views`) counts as perceived, and is held
    also where the percept's box holds the centre of that view: two objects that have moved
    on since they were last seen apart are still seen as one segment."""
    a_ext = np.array([an.size.samples[0][:2].max() for an in anchors])
    p_ext = np.array([pc.size[:2].max() for pc in frame])
    refuse = p_ext[None, :] > merge_ratio * a_ext[:, None] + 0.02
    merged: dict[int, list[int]] = {}
    tracks = tracks or {}
    recent = [k for k, an in enumerate(anchors)
              if an.history and (time - an.last_seen <= merge_seconds or an.symbol in tracks)]
    if len(recent) < 2:
        return refuse, merged
    positions = np.array([pc.position for pc in frame])
    half = np.array([pc.size for pc in frame]) / 2

    def holds(centres: np.ndarray) -> np.ndarray:  # (R, 3) -> (R, P)
        return np.all(np.abs(centres[:, None, :] - positions[None]) <= half[None], axis=2)

    inside = holds(np.array([anchors[k].history[-1].position for k in recent]))
    viewed = [r for r, k in enumerate(recent) if anchors[k].symbol in tracks]
    if viewed:
        inside[viewed] |= holds(np.array([tracks[anchors[recent[r]].symbol].position
                                          for r in viewed]))
    for j in np.nonzero(inside.sum(axis=0) >= 2)[0]:
        held = [recent[r] for r in np.nonzero(inside[:, j])[0]]
        if all(p_ext[j] > 1.2 * a_ext[k] + 0.01 for k in held):
            refuse[held, j] = True
            merged[int(j)] = held
    return refuse, merged


def withheld_views(anchors: list[Anchor], frame: list[Percept], features: np.ndarray,
                   matched_anchor: dict[int, int], matched: set[str],
                   merged: dict[int, list[int]], time: float, withholding: dict[str, float],
                   withhold_seconds: float, view_margin: float, view_colour: float
                   ) -> tuple[dict[int, list[str]], dict[str, float]]:
    """Unmatched percepts (index in ``frame``) that are partial or merged views of anchors
    not perceived this frame -> those anchors' symbols (see the module doc); and the new
    ``withholding`` (anchor symbol -> since when it withholds a percept), to pass in next
    frame. ``withhold_seconds`` <= 0 switches withholding off."""
    views: dict[int, list[str]] = {}
    if withhold_seconds <= 0 or not anchors:
        return views, {}
    unseen = [k for k, an in enumerate(anchors) if an.symbol not in matched]
    still: dict[str, float] = {}
    for j, percept in enumerate(frame):
        if j in matched_anchor:
            continue
        hits = []
        for k in unseen:
            anchor = anchors[k]
            if k not in merged.get(j, ()):
                if features[k, j, 1] < view_colour:
                    continue
                if not boxes_overlap(anchor, percept, view_margin):
                    continue
            since = withholding.get(anchor.symbol, time)
            still[anchor.symbol] = since
            if time - since <= withhold_seconds:
                hits.append(anchor.symbol)
        if hits:
            views[j] = hits
    return views, still


def container_views(anchors: list[Anchor], frame: list[Percept], features: np.ndarray,
                    matched_anchor: dict[int, int], time: float, recent_seconds: float,
                    view_margin: float) -> list[int]:
    """The percepts (index in ``frame``) that ``matched_anchor`` gives to a hidden anchor under
    an occluder (its particles' occluded mass at least 1/2) but that are partial views of an
    anchor perceived within ``recent_seconds`` and not matched now (see the module doc): they
    are to be unmatched."""
    taken = set(matched_anchor.values())
    vanished = [m for m, an in enumerate(anchors)
                if m not in taken and an.history and time - an.last_seen <= recent_seconds]
    out = []
    for j, k in matched_anchor.items():
        hidden = anchors[k]
        if not hidden.position.is_probabilistic or hidden.occluded is None:
            continue
        if float(np.sum(hidden.position.weights[hidden.occluded])) < 0.5:
            continue
        if any(features[m, j, 1] > features[k, j, 1]
               and boxes_overlap(anchors[m], frame[j], view_margin) for m in vanished):
            out.append(j)
    return out


def boxes_overlap(anchor: Anchor, percept: Percept, margin: float) -> bool:
    """Whether the percept's 3-D box overlaps (within ``margin``) the anchor's box placed at its
    last perceived position or at any of its particles of positive weight."""
    centres = [anchor.history[-1].position[None, :]] if anchor.history else []
    if anchor.position.is_probabilistic:
        centres.append(anchor.position.samples[anchor.position.weights > 0])
    else:
        centres.append(anchor.position.samples)
    return any(_boxes_meet(c, anchor.size.samples[0], percept, margin) for c in centres)


def _boxes_meet(centres: np.ndarray, size: np.ndarray, percept: Percept, margin: float) -> bool:
    """Whether a box of ``size`` at any of ``centres`` (N, 3) overlaps the percept's box
    within ``margin`` (per axis: centres apart by at most the half sizes' sum plus it)."""
    half = (size + percept.size) / 2 + margin
    return bool(np.any(np.all(np.abs(centres - percept.position) <= half, axis=1)))


def track_views(anchors: list[Anchor], frame: list[Percept], views: dict[int, list[str]],
                tracks: dict[str, ViewTrack], perceived: set[str], time: float,
                recent_seconds: float) -> dict[str, ViewTrack]:
    """The tracks through views after this frame (anchor symbol -> its last view): an anchor
    withheld in a view (``views``: index in ``frame`` -> symbols) goes on being tracked through
    it when it was perceived, or seen in a tracked view, within ``recent_seconds``; an older
    track ends, and so does the track of an anchor ``perceived`` in this frame."""
    by_symbol = {a.symbol: a for a in anchors}
    out = {s: v for s, v in tracks.items()
           if s in by_symbol and s not in perceived and time - v.time <= recent_seconds}
    for j, symbols in views.items():
        for symbol in symbols:
            anchor = by_symbol.get(symbol)
            if anchor is None:
                continue
            if time - anchor.last_seen <= recent_seconds or symbol in out:
                out[symbol] = ViewTrack(time, np.asarray(frame[j].position, dtype=float),
                                        np.asarray(frame[j].size, dtype=float))
    return out


def emerging_views(anchors: list[Anchor], frame: list[Percept], features: np.ndarray,
                   matched_anchor: dict[int, int], blocked: np.ndarray,
                   tracks: dict[str, ViewTrack], time: float, recent_seconds: float,
                   view_margin: float, reid_similarity: tuple[float, ...]) -> dict[int, int]:
    """Percepts (index in ``frame``) that come out of an anchor's tracked view -> that anchor
    (index in ``anchors``), see the module doc: the percept is unmatched, its box overlaps
    (within ``view_margin``) the box of the anchor's view of the last ``recent_seconds``, it
    looks like the anchor (``reid_similarity``), the pair is not ``blocked`` (a merged view),
    and it is the only such pair of either."""
    taken = set(matched_anchor.values())
    rows = [k for k, a in enumerate(anchors)
            if k not in taken and a.symbol in tracks
            and 0.0 < time - tracks[a.symbol].time <= recent_seconds]
    if not rows or features.shape[1] == 0:
        return {}
    alike = looks_alike(features, reid_similarity) & ~blocked
    pairs = np.zeros((len(anchors), len(frame)), bool)
    for k in rows:
        view = tracks[anchors[k].symbol]
        for j, percept in enumerate(frame):
            if j not in matched_anchor and alike[k, j]:
                pairs[k, j] = _boxes_meet(view.position[None, :], view.size, percept,
                                          view_margin)
    return one_to_one(pairs)
