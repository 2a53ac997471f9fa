"""The robot's experience of occlusions: episodes played through perception and anchoring alone.

An *episode* is one scenario (a shipped one or a generated game) perceived frame by frame and
anchored with no reasoning (:class:`anchoring.AnchorManager`, which re-identifies a percept by
appearance when it looks like exactly one anchor left over). Per frame it keeps, for every
anchor, whether it was perceived and where it was last seen, and, from the simulator, the
ground truth: which body covers or holds which object.
:mod:`probanchor.learning.occlusion_data` turns episodes into the learner's before/after facts.

The anchors' ground-truth identities come from their percepts' ``truth_id`` (the object
whose pixels make up most of the segment; a skin segment has none, and a hand anchor is the
hand nearest to it). Anchoring never reads the ground truth; only the truth labels and the
report of how often hindsight agrees with them do.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from anchoring import AnchorManager
from anchoring.hands import reasoning_position
from probanchor.percepts import PerceptFrame

__all__ = ["AnchorView", "Episode", "EpisodeFrame", "play"]

#: A skin anchor is the ground-truth hand within this distance of its percepts (m).
HAND_REACH = 0.2


@dataclass(frozen=True)
class AnchorView:
    """One anchor in one frame, as anchoring alone knows it."""

    symbol: str
    category: str
    perceived: bool
    #: where the reasoning is told it is (a hand's grip point) when perceived now, or where it
    #: was last perceived
    position: tuple[float, float, float]
    #: a perceived hand's grip point (where the reasoning is told it is), else None
    grip: tuple[float, float, float] | None = None
    #: its height (m) as anchoring knows it (the mean of its last percepts' sizes)
    height: float = 0.0


@dataclass
class EpisodeFrame:
    """One frame: the anchors that exist and the simulator's ground truth."""

    index: int
    time: float
    anchors: dict[str, AnchorView]
    truth: dict[str, Any] | None

    @property
    def blind(self) -> bool:
        """No anchor is perceived (the camera covered, or nothing on the table)."""
        return not any(v.perceived for v in self.anchors.values())

    def perceived(self, symbol: str) -> bool:
        view = self.anchors.get(symbol)
        return view is not None and view.perceived


@dataclass
class Episode:
    """A played scenario: its frames and each anchor's ground-truth object (or None)."""

    name: str
    frames: list[EpisodeFrame]
    truth_of: dict[str, str | None] = field(default_factory=dict)

    def owners(self) -> list[dict[str, str]]:
        """Per frame, each ground-truth object -> the anchor that showed it last (perceived
        in that frame or before). A hidden anchor that is not its object's owner is a
        duplicate: anchoring alone acquired the object anew where it came back (out of a
        hand, into the view), and the duplicate's place is stale."""
        owner: dict[str, str] = {}
        out = []
        for frame in self.frames:
            for symbol, view in frame.anchors.items():
                obj = self.truth_of.get(symbol)
                if view.perceived and obj is not None:
                    owner[obj] = symbol
            out.append(dict(owner))
        return out

    def covering(self, frame: int, symbol: str) -> str | None:
        """The anchor whose ground-truth body covers or holds ``symbol``'s object in
        ``frame`` (the ``under`` / ``held_by`` of the simulator), if it is an anchor."""
        truth = self.frames[frame].truth
        obj = self.truth_of.get(symbol)
        if truth is None or obj is None:
            return None
        info = truth.get("objects", {}).get(obj)
        if info is None:
            return None
        parent = info.get("under") or info.get("held_by")
        if parent is None:
            return None
        anchors = self.frames[frame].anchors
        found = [o for o, gt in self.truth_of.items()
                 if gt == parent and o != symbol and o in anchors]
        found.sort(key=lambda o: (not anchors[o].perceived, o))   # a perceived one first
        return found[0] if found else None


def play(frames: Iterable[PerceptFrame], name: str) -> Episode:
    """Anchor a percept stream with anchoring alone and keep what each frame knew.

    Parameters
    ----------
    frames : iterable of PerceptFrame
        The perceived stream (with the simulator's ground truth, when there is one).
    name : str
        The episode's name (the scenario's).

    Returns
    -------
    Episode
    """
    manager = AnchorManager()
    out: list[EpisodeFrame] = []
    votes: dict[str, Counter[str]] = defaultdict(Counter)
    hand_votes: dict[str, Counter[str]] = defaultdict(Counter)
    for k, frame in enumerate(frames):
        result = manager.process(frame.time, frame.percepts)
        perceived = {a.symbol: frame.percepts[a.percept_index] for a in result.assignments}
        hands = (frame.truth or {}).get("hands", {})
        views: dict[str, AnchorView] = {}
        for anchor in manager.anchors:
            percept = perceived.get(anchor.symbol)
            grip = None
            if percept is not None:
                # where the reasoning is told it is (a hand's grip point): the data's positions
                # mean what the filter's do
                position = tuple(float(v) for v in reasoning_position(percept))
                if percept.grip is not None:
                    grip = tuple(float(v) for v in percept.grip)
                if percept.truth_id is not None:
                    votes[anchor.symbol][percept.truth_id] += 1
                elif hands:
                    hand = _nearest_hand(np.asarray(position), hands)
                    if hand is not None:
                        hand_votes[anchor.symbol][hand] += 1
            else:
                position = tuple(float(v) for v in np.asarray(anchor.position.mean()))
            views[anchor.symbol] = AnchorView(anchor.symbol, anchor.best_category,
                                              percept is not None, position,  # type: ignore[arg-type]
                                              grip,  # type: ignore[arg-type]
                                              float(np.asarray(anchor.size.mean())[2]))
        out.append(EpisodeFrame(k, float(frame.time), views, frame.truth))
    truth_of: dict[str, str | None] = {}
    for symbol in sorted({s for f in out for s in f.anchors}):   # (an order of its own)
        counts = votes.get(symbol) or hand_votes.get(symbol)
        truth_of[symbol] = counts.most_common(1)[0][0] if counts else None
    return Episode(name, out, truth_of)


def _nearest_hand(position: np.ndarray, hands: dict[str, Any]) -> str | None:
    best, best_d = None, HAND_REACH
    for hid, info in hands.items():
        d = float(np.linalg.norm(np.asarray(info["position"], dtype=float) - position))
        if d < best_d:
            best, best_d = hid, d
    return best
