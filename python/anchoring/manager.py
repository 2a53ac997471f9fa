"""Bottom-up anchor management: acquire, re-acquire and track, one frame at a time.

Per frame (:meth:`AnchorManager.process`):

1. invalid percepts are rejected with their reason (:mod:`anchoring.validation`), logged as
   warnings, never raised;
2. anchors acquired more than ``glitch_seconds`` ago and never re-acquired are dropped as
   glitches (the original's fading rule);
3. every (anchor, percept) pair gets its similarity vector and the learned matcher's score;
   pairs where the percept is a merged view of two objects are refused
   (:func:`anchoring.views.merged_views`);
4. an anchor whose position is a belief (the reasoning's particles) may be re-acquired where,
   and only where, that is more probable than the percept being a new object or clutter (the
   matcher's decision is not asked again: it is one factor of it): how the anchor looks
   (the matching function's appearance decision, calibrated) times where its belief puts it,
   with the part of the belief that has the object under nothing (moved unseen, or lost while
   the camera saw nothing) spread over the whole table (:mod:`anchoring.likelihood`);
5. percepts and anchors are assigned one to one by the Hungarian method
   (``scipy.optimize.linear_sum_assignment``) in a two-level cascade (:func:`cascade_assignment`):
   first the anchors perceived until now, then those whose position is a belief, over the
   percepts left; at each level as many pairs as possible among those the matcher accepts
   (decision > 0) or step 4 does, and among such assignments, for the anchors in view, the
   one with the largest total mean similarity (monotone in every attribute; an RBF SVM's
   decision value is not, and it saturates for clear matches), for the hidden ones
   (``position_match="likelihood"``, the default) the most probable: the largest sum of
   their log likelihood ratios of step 4, so a weak mode counts as little as it weighs and
   a percept goes to the anchor it is likelier to be rather than to the one it is most similar
   to on average; ``"mass"`` ranks the hidden ones by the mean similarity too, with the
   belief's mass near the percept as the position term; ``"max"`` takes the best particle's
   similarity, as the paper's Algorithm 1;
6. what is left unmatched may still be the anchor it comes out of a view of: a percept that
   overlaps the view withheld a moment ago (step 8) of an anchor perceived just before it,
   and looks like that anchor alone, re-acquires it whatever its belief (the view was seen;
   :func:`anchoring.views.emerging_views`; ``score`` 0); or be re-identified by appearance,
   when it is the only look-alike of an anchor not perceived for a while
   (:mod:`anchoring.reidentify`; ``score`` 0), where the likelihood test of step 4 holds too;
7. matched percepts re-acquire their anchor, unmatched percepts acquire a new anchor, and the
   anchors that were not perceived are *tracked* (their position is whatever the reasoning
   later supplies through :meth:`AnchorManager.set_position_particles`, else the last value);
   a re-acquisition by an anchor with a belief where a look-alike anchor's belief has at least
   ``ambiguity_ratio`` times its mass near the percept is reported as ambiguous, with each
   candidate's probability (its share of the mass), in ``result.ambiguous``; so is one by an
   anchor not perceived since the camera last saw nothing while a look-alike is in the same
   case (they may have been exchanged unseen: equal probabilities); each ambiguity also carries
   the appearance log likelihood ratio of the percept against every candidate, for the
   identity hypotheses the reasoning keeps (:mod:`anchoring.identity`);
8. except that an unmatched percept that is a plausible *partial or merged view* of anchors
   not perceived this frame is *withheld* (no symbol, reported in ``result.withheld``; for at
   most ``withhold_seconds`` in a row per anchor; :mod:`anchoring.views`).

Hands (skin percepts and the anchors acquired from them) are matched apart from the rest, by
their grip points (:mod:`anchoring.hands`; ``hands=None`` matches them as any other object).

Symbols are ``<category>-<k>``: the k-th anchor acquired with that best category. A symbol
does not change when the anchor's category estimate changes later (the anchor's ``category`` /
``best_category`` give the current estimate), so the reasoner's atoms stay stable; only a
revision (:meth:`AnchorManager.relabel`, later evidence showing two look-alikes had each
other's symbols, :mod:`anchoring.identity`) makes anchors exchange their symbols. When a
glitch is dropped and it holds the newest number of its category, the number is given back,
so a one-frame false detection leaves no gap.
"""

from __future__ import annotations

import json
import logging
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from scipy.optimize import linear_sum_assignment

from anchoring.anchor import Anchor
from anchoring.blas import single_threaded_blas
from anchoring.features import pair_evidence
from anchoring.hands import (
    DEFAULT_HAND_RULES,
    HandRules,
    is_hand,
    is_hand_percept,
    match_hands,
    views_under_hands,
)
from anchoring.likelihood import (
    AssociationModel,
    appearance_log_ratio,
    belief_ratio,
    reacquire_probability,
    unexplained_mass,
)
from anchoring.matcher import Matcher, load_default_matcher
from anchoring.reidentify import looks_alike, unique_lookalikes
from anchoring.similarity import BELIEF_RADIUS
from anchoring.validation import histogram_bins, invalid_reason
from anchoring.views import (
    ViewTrack,
    Withheld,
    container_views,
    emerging_views,
    merged_views,
    track_views,
    withheld_views,
)
from probanchor.percepts import Percept, PerceptError

log = logging.getLogger("anchoring")

FORMAT = "anchoring-world/1"
_NUMBER_LIST = re.compile(r"\[\s+([-+0-9eE.,\s]+?)\s+\]")


@dataclass
class Assignment:
    """Percept ``percept_index`` (in the frame's input list) went to anchor ``symbol``."""

    percept_index: int
    symbol: str
    action: Literal["acquire", "reacquire"]
    score: float | None = None  # the matcher's decision value for a re-acquire


@dataclass
class Ambiguity:
    """Percept ``percept_index`` could be any of several look-alike anchors: ``candidates``
    maps each symbol to its probability (its share of the beliefs' mass near the percept, or
    an equal share after the camera saw nothing), the one given first; ``appearance`` maps each
    candidate to the log likelihood ratio of how it looks against the percept
    (:func:`anchoring.likelihood.appearance_log_ratio`)."""

    percept_index: int
    candidates: dict[str, float]
    appearance: dict[str, float] = field(default_factory=dict)


@dataclass
class Rejection:
    percept_index: int
    reason: str


@dataclass
class FrameResult:
    time: float
    assignments: list[Assignment] = field(default_factory=list)
    tracked: list[str] = field(default_factory=list)  # anchors not perceived this frame
    dropped: list[str] = field(default_factory=list)  # glitches removed this frame
    rejected: list[Rejection] = field(default_factory=list)
    withheld: list[Withheld] = field(default_factory=list)  # partial / merged views, no symbol
    ambiguous: list[Ambiguity] = field(default_factory=list)  # look-alike re-acquisitions
    # the similarity vectors of this frame: (A, P, 5), rows the anchors ``compared`` (in that
    # order), columns the valid percepts in input order (``rejected`` ones left out)
    features: np.ndarray | None = field(default=None, repr=False)
    compared: list[str] = field(default_factory=list)

    @property
    def symbols(self) -> dict[int, str]:
        """percept index -> anchor symbol."""
        return {a.percept_index: a.symbol for a in self.assignments}

    @property
    def acquired(self) -> list[str]:
        return [a.symbol for a in self.assignments if a.action == "acquire"]

    @property
    def reacquired(self) -> list[str]:
        return [a.symbol for a in self.assignments if a.action == "reacquire"]


class AnchorManagerError(ValueError):
    """A world-model file that cannot be loaded (names the file and the cause)."""


class SymbolTable:
    """Per-category counters: ``issue('ball')`` -> ``ball-1``, ``ball-2``..."""

    def __init__(self, counters: dict[str, int] | None = None) -> None:
        self.counters: dict[str, int] = dict(counters or {})

    def issue(self, category: str) -> str:
        k = self.counters.get(category, 0) + 1
        self.counters[category] = k
        return f"{category}-{k}"

    def release(self, symbol: str) -> None:
        """Give a dropped glitch's number back if it is still the newest of its category."""
        category, _, number = symbol.rpartition("-")
        if number.isdigit() and self.counters.get(category) == int(number):
            self.counters[category] = int(number) - 1


class AnchorManager:
    """Keeps the anchors; ``process(time, percepts)`` once per frame."""

    def __init__(
        self,
        matcher: Matcher | None = None,
        glitch_seconds: float = 1.0,
        history_size: int = 10,
        withhold_seconds: float = 1.0,
        view_margin: float = 0.01,
        view_colour: float = 0.7,
        merge_ratio: float = 1.5,
        merge_seconds: float = 0.5,
        reid_seconds: float = 0.3,
        reid_similarity: tuple[float, float, float] = (0.5, 0.9, 0.7),
        position_match: Literal["likelihood", "mass", "max"] = "likelihood",
        belief_radius: float = BELIEF_RADIUS,
        association: AssociationModel | None = None,
        ambiguity_ratio: float = 0.5,
        hands: HandRules | None = DEFAULT_HAND_RULES,
    ) -> None:
        self.matcher: Matcher = matcher if matcher is not None else load_default_matcher()
        self.glitch_seconds = float(glitch_seconds)
        self.history_size = int(history_size)
        # partial / merged views (anchoring.views); withhold_seconds <= 0 switches it off
        self.withhold_seconds = float(withhold_seconds)
        self.view_margin = float(view_margin)
        self.view_colour = float(view_colour)
        self.merge_ratio = float(merge_ratio)
        self.merge_seconds = float(merge_seconds)
        # re-identification of a unique look-alike (anchoring.reidentify); <= 0: off
        self.reid_seconds = float(reid_seconds)
        self.reid_similarity = tuple(float(v) for v in reid_similarity)
        # anchors whose position is a belief (anchoring.similarity.position_evidence): the
        # assignment's position term, the kernel's standard deviation (metres), the likelihoods
        # of re-acquiring against a new object (anchoring.likelihood), the mass ratio that is
        # ambiguous
        if position_match not in ("likelihood", "mass", "max"):
            raise ValueError("position_match must be 'likelihood', 'mass' or 'max', not "
                             f"{position_match!r}")
        if belief_radius <= 0:
            raise ValueError(f"belief_radius must be positive, not {belief_radius!r}")
        if not 0 < ambiguity_ratio <= 1:
            raise ValueError(f"ambiguity_ratio must be in (0, 1], not {ambiguity_ratio!r}")
        self.position_match: Literal["likelihood", "mass", "max"] = position_match
        self.belief_radius = float(belief_radius)
        self.association = (association if association is not None
                            else AssociationModel.for_matcher(self.matcher))
        self.ambiguity_ratio = float(ambiguity_ratio)
        self.hands = hands  # hands matched by their grip points (anchoring.hands); None: off
        self.blind_time: float | None = None  # the last frame with no valid percept
        self._withholding: dict[str, float] = {}  # anchor symbol -> since when it withholds
        self._view_tracks: dict[str, ViewTrack] = {}  # anchor symbol -> its last tracked view
        self.symbols = SymbolTable()
        self.time: float | None = None
        self._anchors: dict[str, Anchor] = {}

    # --- queries ------------------------------------------------------------------------
    @property
    def anchors(self) -> list[Anchor]:
        """Live anchors (confirmed and not yet confirmed), in order of acquisition."""
        return list(self._anchors.values())

    def get(self, symbol: str) -> Anchor:
        try:
            return self._anchors[symbol]
        except KeyError:
            raise KeyError(f"no anchor {symbol!r}") from None

    def __contains__(self, symbol: object) -> bool:
        return symbol in self._anchors

    def __len__(self) -> int:
        return len(self._anchors)

    # --- track: feedback from the reasoning ----------------------------------------------
    def set_position_particles(
        self, symbol: str, positions: np.ndarray, weights: np.ndarray | None = None,
        occluded: np.ndarray | None = None,
    ) -> None:
        """The anchor's position becomes the reasoning's weighted particles ((N, 3), (N,)).

        Matching then uses the maximum position similarity over the particles of positive
        weight; the next re-acquire replaces them by the percept's position. ``occluded`` (N,)
        says in which particles the reasoning has the object under an occluder (step 4).
        """
        self.get(symbol).set_position_particles(positions, weights, self.time, occluded)

    def relabel(self, mapping: dict[str, str]) -> None:
        """Revise identities: the anchor now named ``old`` is named ``mapping[old]`` (a
        permutation of existing symbols; later evidence showed the anchors had been given each
        other's symbols). Nothing else of the anchors changes."""
        olds, news = set(mapping), set(mapping.values())
        if olds != news:
            raise ValueError(f"not a permutation of symbols: {mapping!r}")
        missing = [s for s in olds if s not in self._anchors]
        if missing:
            raise KeyError(f"no anchor {missing[0]!r}")
        moved = {new: self._anchors[old] for old, new in mapping.items()}
        for new, anchor in moved.items():
            anchor.symbol = new
            anchor.symbol_category = new.rsplit("-", 1)[0]
        self._anchors = {s: moved.get(s, a) for s, a in self._anchors.items()}
        self._withholding = {mapping.get(s, s): t for s, t in self._withholding.items()}
        self._view_tracks = {mapping.get(s, s): v for s, v in self._view_tracks.items()}

    # --- one frame ----------------------------------------------------------------------
    def process(self, time: float, percepts: Sequence[Percept]) -> FrameResult:
        """Match one frame's percepts against the anchors (see the module docstring)."""
        with single_threaded_blas():
            return self._process(float(time), percepts)

    def _process(self, time: float, percepts: Sequence[Percept]) -> FrameResult:
        result = FrameResult(time)
        self.time = time

        valid: list[int] = []
        bins = histogram_bins(self._anchors.values(), percepts)
        for i, percept in enumerate(percepts):
            reason = invalid_reason(percept, bins)
            if reason is not None:
                log.warning("percept %d at t=%.3f rejected: %s", i, time, reason)
                result.rejected.append(Rejection(i, reason))
            else:
                valid.append(i)

        for anchor in list(self._anchors.values()):
            if not anchor.confirmed and time - anchor.created > self.glitch_seconds:
                del self._anchors[anchor.symbol]
                self.symbols.release(anchor.symbol)
                result.dropped.append(anchor.symbol)

        everyone = list(self._anchors.values())
        skin: list[int] = []  # valid hand percepts, matched apart (anchoring.hands)
        if self.hands is not None:
            skin = [i for i in valid if is_hand_percept(percepts[i])]
            valid = [i for i in valid if not is_hand_percept(percepts[i])]
        anchors = [a for a in everyone if self.hands is None or not is_hand(a)]
        frame = [percepts[i] for i in valid]
        features, mass = pair_evidence(anchors, frame, self.belief_radius)
        assert mass is not None
        result.features = features
        result.compared = [a.symbol for a in anchors]
        matched_anchor: dict[int, int] = {}  # index in frame -> index in anchors
        merged: dict[int, list[int]] = {}  # index in frame -> anchors seen as one segment
        refuse = np.zeros((len(anchors), len(frame)), bool)
        blocked = refuse  # the merged views' refusals (the beliefs' come on top)
        scores = np.zeros((len(anchors), len(frame)))
        believed = np.array([a.position.is_probabilistic for a in anchors], bool)
        log_appearance = np.zeros((len(anchors), len(frame)))
        # not perceived since the camera last saw nothing: the belief says where it was only
        lost_blind = np.array([self.blind_time is not None and a.last_seen < self.blind_time
                               for a in anchors], bool)
        if anchors and frame:
            scores = np.asarray(self.matcher.decision(features), dtype=float)
            refuse, merged = merged_views(anchors, frame, time, self.merge_ratio,
                                          self.merge_seconds, self._view_tracks)
            blocked = refuse.copy()
            log_appearance = appearance_log_ratio(self.matcher, features, self.association)
            unexplained = np.array(
                [max(unexplained_mass(a, frame, self.association),
                     self.association.blind_doubt if lost else 0.0)
                 for a, lost in zip(anchors, lost_blind, strict=True)])
            belief = belief_ratio(mass, unexplained, self.association, self.belief_radius)
            likely = reacquire_probability(log_appearance, belief, self.association) >= 0.5
            # a hidden anchor (its position a belief) is accepted by its likelihood, in which
            # the matcher's appearance decision is one factor; the others by the matcher
            refuse |= believed[:, None] & ~likely
            accept = np.where(believed[:, None], likely, scores > 0) & ~refuse
            if accept.any():
                # the matcher decides which pairs may match; the assignment takes as many
                # accepted pairs as possible (1e9 per refused pair) and among those maximises
                # the total mean similarity: monotone in every attribute, unlike an RBF SVM's
                # decision value, which saturates and can rank a worse-fitting anchor higher
                fit = features
                if self.position_match == "mass" and believed.any():
                    fit = features.copy()
                    fit[believed, :, 2] = mass[believed]
                cost = np.where(accept, -fit.mean(axis=-1), 1e9)
                if self.position_match == "likelihood" and believed.any():
                    # the hidden anchors (assigned apart, below) by the most probable joint
                    # assignment: the largest sum of log LR(j, a) = log A + log B
                    with np.errstate(divide="ignore"):
                        log_ratio = log_appearance + np.log(belief)
                    cost[believed] = np.where(accept[believed], -log_ratio[believed], 1e9)
                matched_anchor.update(cascade_assignment(accept, cost, believed))

        if self.withhold_seconds > 0:
            for j in container_views(anchors, frame, features, matched_anchor, time,
                                     self.merge_seconds, self.view_margin):
                del matched_anchor[j]
        if self.withhold_seconds > 0:  # out of a view the anchor was tracked through
            emerged = emerging_views(anchors, frame, features, matched_anchor, blocked,
                                     self._view_tracks, time, self.merge_seconds,
                                     self.view_margin, self.reid_similarity)
            for j, k in emerged.items():
                matched_anchor[j] = k
                scores[k, j] = 0.0  # re-acquired by the view, not accepted by the matcher
        lookalikes = unique_lookalikes(anchors, features, matched_anchor, refuse, time,
                                       self.reid_seconds, self.reid_similarity)
        for j, k in lookalikes.items():
            matched_anchor[j] = k
            scores[k, j] = 0.0  # re-identified by appearance, not accepted by the matcher
        if not frame and not skin:
            self.blind_time = time
        matched = {anchors[r].symbol for r in matched_anchor.values()}
        views, self._withholding = withheld_views(
            anchors, frame, features, matched_anchor, matched, merged, time,
            self._withholding, self.withhold_seconds, self.view_margin, self.view_colour)
        self._view_tracks = track_views(anchors, frame, views, self._view_tracks, matched,
                                        time, self.merge_seconds)
        if skin and self.withhold_seconds > 0:  # what an arm in front leaves in view
            views.update(views_under_hands(
                anchors, frame, features[:, :, 1],
                [j for j in range(len(frame)) if j not in matched_anchor and j not in views],
                [percepts[i] for i in skin], min_colour=self.view_colour))
        result.ambiguous = self._ambiguities(
            anchors, believed, lost_blind & np.array([a.confirmed for a in anchors], bool),
            features, mass, log_appearance,
            {j: k for j, k in matched_anchor.items() if j not in views}, valid)
        perceived: set[str] = set()
        for j, i in enumerate(valid):
            percept = percepts[i]
            if j in views:
                result.withheld.append(Withheld(i, views[j]))
            elif j in matched_anchor:
                anchor = anchors[matched_anchor[j]]
                anchor.reacquire(percept)
                anchor.confirmed = True
                perceived.add(anchor.symbol)
                score = float(scores[matched_anchor[j], j])
                result.assignments.append(Assignment(i, anchor.symbol, "reacquire", score))
            else:
                symbol = self.symbols.issue(percept.best_category)
                self._anchors[symbol] = Anchor.acquire(symbol, percept, self.history_size)
                perceived.add(symbol)
                result.assignments.append(Assignment(i, symbol, "acquire"))
        if skin:
            self._match_hands(time, percepts, skin, result, perceived)
        result.tracked = [a.symbol for a in everyone if a.symbol not in perceived]
        return result

    def _match_hands(self, time: float, percepts: Sequence[Percept], skin: list[int],
                     result: FrameResult, perceived: set[str]) -> None:
        """The frame's hand percepts (indices ``skin``) re-acquire or acquire hand anchors, or
        are withheld as pieces of a hand (:func:`anchoring.hands.match_hands`)."""
        assert self.hands is not None
        hands = [a for a in self._anchors.values() if is_hand(a) and a.symbol not in perceived]
        found = match_hands(hands, [percepts[i] for i in skin], time, self.hands)
        symbols: dict[int, str] = {}
        for j, i in enumerate(skin):
            if j in found.reacquire:
                anchor = hands[found.reacquire[j]]
                anchor.reacquire(percepts[i])
                anchor.confirmed = True
                result.assignments.append(Assignment(i, anchor.symbol, "reacquire"))
            elif j in found.new:
                anchor = Anchor.acquire(self.symbols.issue(percepts[i].best_category),
                                        percepts[i], self.history_size)
                self._anchors[anchor.symbol] = anchor
                result.assignments.append(Assignment(i, anchor.symbol, "acquire"))
            else:
                continue
            symbols[j] = anchor.symbol
            perceived.add(anchor.symbol)
        for j, k in found.pieces.items():
            result.withheld.append(Withheld(skin[j], [symbols[k]]))

    def _ambiguities(self, anchors: list[Anchor], believed: np.ndarray, lost_blind: np.ndarray,
                     features: np.ndarray, mass: np.ndarray, log_appearance: np.ndarray,
                     matched_anchor: dict[int, int], valid: list[int]) -> list[Ambiguity]:
        """Re-acquisitions that nothing the robot saw tells from a look-alike's (step 7): by
        the beliefs' masses within ``ambiguity_ratio``; or, for an anchor not perceived since
        the camera last saw nothing, any look-alike in the same case (the two may have been
        exchanged unseen; each is then equally likely)."""
        out: list[Ambiguity] = []
        alike = looks_alike(features, self.reid_similarity)
        for j, k in matched_anchor.items():
            looks = alike[:, j].copy()
            looks[k] = False
            if lost_blind[k]:
                others = np.nonzero(looks & lost_blind)[0]
                share = np.ones(len(others) + 1)
            elif believed[k] and mass[k, j] > 0:
                others = np.nonzero(looks & believed
                                    & (mass[:, j] >= self.ambiguity_ratio * mass[k, j]))[0]
                share = np.concatenate(([mass[k, j]], mass[others, j]))
            else:
                continue
            if len(others):
                share = share / share.sum()
                candidates = {anchors[k].symbol: float(share[0])}
                candidates.update((anchors[o].symbol, float(p))
                                  for o, p in zip(others, share[1:], strict=True))
                appearance = {anchors[o].symbol: float(log_appearance[o, j])
                              for o in (k, *others)}
                out.append(Ambiguity(valid[j], candidates, appearance))
        return out

    # --- persistence ----------------------------------------------------------------------
    def to_json(self) -> dict[str, Any]:
        return {
            "format": FORMAT,
            "time": self.time,
            "glitch_seconds": self.glitch_seconds,
            "history_size": self.history_size,
            "withhold_seconds": self.withhold_seconds,
            "view_margin": self.view_margin,
            "view_colour": self.view_colour,
            "merge_ratio": self.merge_ratio,
            "merge_seconds": self.merge_seconds,
            "reid_seconds": self.reid_seconds,
            "reid_similarity": list(self.reid_similarity),
            "position_match": self.position_match,
            "belief_radius": self.belief_radius,
            "association": self.association.to_json(),
            "ambiguity_ratio": self.ambiguity_ratio,
            "hands": None if self.hands is None else vars(self.hands),
            "blind_time": self.blind_time,
            "symbol_counters": self.symbols.counters,
            "withholding": dict(self._withholding),
            "view_tracks": {s: v.to_json() for s, v in self._view_tracks.items()},
            "anchors": [a.to_json() for a in self._anchors.values()],
        }

    def save(self, path: str | Path) -> None:
        """Write the world model as indented JSON (a person can read it): one anchor field per
        line, each list of numbers (a position, a particle, a histogram) on one line."""
        text = json.dumps(self.to_json(), indent=1)
        text = _NUMBER_LIST.sub(lambda m: "[" + " ".join(m.group(1).split()) + "]", text)
        Path(path).write_text(text + "\n", encoding="utf-8")

    @classmethod
    def load(cls, path: str | Path, matcher: Matcher | None = None) -> AnchorManager:
        try:
            record = json.loads(Path(path).read_text(encoding="utf-8"))
        except OSError as exc:
            raise AnchorManagerError(f"{path}: cannot read: {exc}") from exc
        except json.JSONDecodeError as exc:
            raise AnchorManagerError(
                f"{path}:{exc.lineno}: not JSON: {exc.msg}"
            ) from exc
        return cls.from_json(record, matcher, str(path))

    @classmethod
    def from_json(cls, record: Any, matcher: Matcher | None = None, path: str = "<json>"
                  ) -> AnchorManager:
        """The manager :meth:`to_json` described, anchors and counters as they were.

        Parameters
        ----------
        record:
            The decoded JSON.
        matcher:
            The matching model (the shipped one by default).
        path:
            Where the record came from, for the errors.

        Returns
        -------
        The manager; an :class:`AnchorManagerError` naming ``path`` for a bad record.
        """
        if not isinstance(record, dict) or record.get("format") != FORMAT:
            raise AnchorManagerError(f"{path}: not an anchoring world file (format {FORMAT})")
        try:
            manager = cls(
                matcher,
                glitch_seconds=float(record["glitch_seconds"]),
                history_size=int(record["history_size"]),
                withhold_seconds=float(record.get("withhold_seconds", 1.0)),
                view_margin=float(record.get("view_margin", 0.01)),
                view_colour=float(record.get("view_colour", 0.7)),
                merge_ratio=float(record.get("merge_ratio", 1.5)),
                merge_seconds=float(record.get("merge_seconds", 0.5)),
                reid_seconds=float(record.get("reid_seconds", 0.3)),
                reid_similarity=tuple(record.get("reid_similarity", (0.5, 0.9, 0.7))),
                position_match=record.get("position_match", "mass"),
                belief_radius=float(record.get("belief_radius", BELIEF_RADIUS)),
                association=(AssociationModel.from_json(record["association"])
                             if "association" in record else None),
                ambiguity_ratio=float(record.get("ambiguity_ratio", 0.5)),
                hands=_hand_rules(record.get("hands", {})),
            )
            blind = record.get("blind_time")
            manager.blind_time = None if blind is None else float(blind)
            manager.time = None if record.get("time") is None else float(record["time"])
            manager.symbols = SymbolTable(
                {str(k): int(v) for k, v in record["symbol_counters"].items()}
            )
            manager._withholding = {str(k): float(v)
                                    for k, v in record.get("withholding", {}).items()}
            manager._view_tracks = {str(k): ViewTrack.from_json(v)
                                    for k, v in record.get("view_tracks", {}).items()}
            for i, item in enumerate(record["anchors"]):
                try:
                    anchor = Anchor.from_json(item)
                except (KeyError, TypeError, ValueError, PerceptError) as exc:
                    raise AnchorManagerError(f"{path}: anchor {i}: {exc!r}") from exc
                manager._anchors[anchor.symbol] = anchor
        except (KeyError, TypeError, ValueError) as exc:
            if isinstance(exc, AnchorManagerError):
                raise
            raise AnchorManagerError(f"{path}: bad world file: {exc!r}") from exc
        return manager


def cascade_assignment(accept: np.ndarray, cost: np.ndarray, believed: np.ndarray
                       ) -> dict[int, int]:
    """Percept index -> anchor index: the anchors perceived until now first, one to one over
    the pairs ``accept`` allows (as many as possible, then the least total ``cost``), then the
    anchors whose position is a belief (``believed``) over the percepts left.

    A matching cascade (as DeepSORT's, by how long ago a track was last seen, in two levels):
    an anchor in view keeps its own percept even where another pair would make the assignment
    one pair larger. Joint, a fragment of a container seen beside it (which the container's
    anchor also accepts) made the container's anchor take the fragment so that a hidden
    anchor, with a few stray particles there, could take the container's own view.
    """
    out: dict[int, int] = {}
    free = np.ones(accept.shape[1], bool)
    for level in (~believed, believed):
        rows = np.nonzero(level)[0]
        cols = np.nonzero(free)[0]
        if not len(rows) or not len(cols) or not accept[np.ix_(rows, cols)].any():
            continue
        sub = cost[np.ix_(rows, cols)]
        for r, c in zip(*linear_sum_assignment(sub), strict=True):
            if accept[rows[r], cols[c]]:
                out[int(cols[c])] = int(rows[r])
                free[cols[c]] = False
    return out


def _hand_rules(record: Any) -> HandRules | None:
    """The hand rules of a world file (``null``: hands matched as other objects; absent, in
    files written before hands were matched apart: the default rules)."""
    return None if record is None else HandRules(**record)
