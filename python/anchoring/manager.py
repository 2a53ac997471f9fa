"""Bottom-up anchor management: acquire, re-acquire and track, one frame at a time.

Per frame (:meth:`AnchorManager.process`):

1. invalid percepts are rejected with their reason (``Percept.validate``; a colour histogram
   whose bin count differs from the anchors'), logged as warnings, never raised;
2. anchors acquired more than ``glitch_seconds`` ago and never re-acquired are dropped as
   glitches (the original's fading rule);
3. every (anchor, percept) pair gets its similarity vector and the learned matcher's score;
4. percepts and anchors are assigned jointly, one to one, by the Hungarian method
   (``scipy.optimize.linear_sum_assignment``): as many pairs as possible among those the
   matcher accepts (decision > 0), and among such assignments the one with the largest total
   mean similarity (monotone in every attribute; an RBF SVM's decision value is not, and it
   saturates for clear matches);
5. matched percepts re-acquire their anchor, unmatched percepts acquire a new anchor, and the
   anchors that were not perceived are *tracked* (their position is whatever the reasoning
   later supplies through :meth:`AnchorManager.set_position_particles`, else the last value);
6. except that an unmatched percept that is a plausible *partial or merged view* of anchors
   not perceived this frame is *withheld* (no symbol, reported in ``result.withheld``): its 3-D
   box overlaps such an anchor's box placed at the anchor's last perceived position or at one
   of its particles, and its colour is not unlike the anchor's. A mug's rim above the box in
   front of it, the first sliver of a mug coming out from behind a box, a container half
   revealed as its cover is lifted, two containers seen as one segment for a frame: these are
   views of objects that already have anchors, and a new anchor for them would give the
   object's percepts a second symbol. A percept withheld because of one anchor for longer than
   ``withhold_seconds`` in a row is acquired after all (a new object put where a hidden one is
   believed is not refused for ever).

What the matcher and the assignment leave unmatched may still be *re-identified by
appearance*: a percept that looks like exactly one of the anchors left over (category, colour
and size similarities of at least ``reid_similarity``, position not asked), an anchor not
perceived for ``reid_seconds`` that looks like no other percept left over, re-acquires it
(``score`` 0). The learned matcher refuses an object seen again 12 cm or more from where it
was believed (an identical-looking object elsewhere is another object); but when the camera
was covered while a container was carried over the ball, or a cup came out from behind a
passing container, the only black cup on the table is still the black cup. With two
look-alikes left over, nothing is decided by appearance.

A pair the matcher accepts is still refused when the percept is far larger than the anchor in
the table plane (``merge_ratio``: its largest horizontal extent more than that many times the
anchor's plus 2 cm), or when it holds the last positions of two anchors just perceived and is
larger than each (:meth:`AnchorManager._merged_views`): two objects seen as one segment must
not re-acquire one of them; such a percept is withheld.

Symbols are ``<category>-<k>``: the k-th anchor acquired with that best category. A symbol never
changes during the anchor's life, even when its category estimate changes later (the anchor's
``category`` / ``best_category`` give the current estimate); so the reasoner's atoms stay
stable. When a glitch is dropped and it holds the newest number of its category, the number is
given back, so a one-frame false detection leaves no gap.
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
from anchoring.features import pair_features
from anchoring.matcher import Matcher, load_default_matcher
from percepts import Percept, PerceptError

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
class Rejection:
    percept_index: int
    reason: str


@dataclass
class Withheld:
    """Percept ``percept_index`` was left without a symbol: it looks like a partial or merged
    view of the anchors ``symbols`` (not perceived this frame)."""

    percept_index: int
    symbols: list[str]


@dataclass
class FrameResult:
    time: float
    assignments: list[Assignment] = field(default_factory=list)
    tracked: list[str] = field(default_factory=list)  # anchors not perceived this frame
    dropped: list[str] = field(default_factory=list)  # glitches removed this frame
    rejected: list[Rejection] = field(default_factory=list)
    withheld: list[Withheld] = field(default_factory=list)  # partial / merged views, no symbol
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
    ) -> None:
        self.matcher: Matcher = matcher if matcher is not None else load_default_matcher()
        self.glitch_seconds = float(glitch_seconds)
        self.history_size = int(history_size)
        # partial / merged views (see the module doc); withhold_seconds <= 0 switches it off
        self.withhold_seconds = float(withhold_seconds)
        self.view_margin = float(view_margin)
        self.view_colour = float(view_colour)
        self.merge_ratio = float(merge_ratio)
        self.merge_seconds = float(merge_seconds)
        # re-identification of a unique look-alike (see _unique_lookalikes); <= 0: off
        self.reid_seconds = float(reid_seconds)
        self.reid_similarity = tuple(float(v) for v in reid_similarity)
        self._withholding: dict[str, float] = {}  # anchor symbol -> since when it withholds
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
        self, symbol: str, positions: np.ndarray, weights: np.ndarray | None = None
    ) -> None:
        """The anchor's position becomes the reasoning's weighted particles ((N, 3), (N,)).

        Matching then uses the maximum position similarity over the particles of positive
        weight; the next re-acquire replaces them by the percept's position.
        """
        self.get(symbol).set_position_particles(positions, weights, self.time)

    # --- one frame ----------------------------------------------------------------------
    def process(self, time: float, percepts: Sequence[Percept]) -> FrameResult:
        """Match one frame's percepts against the anchors (see the module docstring)."""
        with single_threaded_blas():
            return self._process(float(time), percepts)

    def _process(self, time: float, percepts: Sequence[Percept]) -> FrameResult:
        result = FrameResult(time)
        self.time = time

        valid: list[int] = []
        bins = self._histogram_bins(percepts)
        for i, percept in enumerate(percepts):
            reason = _invalid(percept, bins)
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

        anchors = list(self._anchors.values())
        frame = [percepts[i] for i in valid]
        features = pair_features(anchors, frame)
        result.features = features
        result.compared = [a.symbol for a in anchors]
        matched_anchor: dict[int, int] = {}  # index in frame -> index in anchors
        merged: dict[int, list[int]] = {}  # index in frame -> anchors seen as one segment
        refuse = np.zeros((len(anchors), len(frame)), bool)
        scores = np.zeros((len(anchors), len(frame)))
        if anchors and frame:
            scores = np.asarray(self.matcher.decision(features), dtype=float)
            refuse, merged = self._merged_views(anchors, frame, time)
            accept = (scores > 0) & ~refuse
            if accept.any():
                # the matcher decides which pairs may match; the assignment takes as many
                # accepted pairs as possible (1e9 per refused pair) and among those maximises
                # the total mean similarity: monotone in every attribute, unlike an RBF SVM's
                # decision value, which saturates and can rank a worse-fitting anchor higher
                cost = np.where(accept, -features.mean(axis=-1), 1e9)
                rows, cols = linear_sum_assignment(cost)
                for r, c in zip(rows, cols, strict=True):
                    if accept[r, c]:
                        matched_anchor[int(c)] = int(r)

        for j, k in self._unique_lookalikes(anchors, features, matched_anchor, refuse,
                                            time).items():
            matched_anchor[j] = k
            scores[k, j] = 0.0  # re-identified by appearance, not accepted by the matcher
        matched = {anchors[r].symbol for r in matched_anchor.values()}
        views = self._views(anchors, frame, features, matched_anchor, matched, merged, time)
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
        result.tracked = [a.symbol for a in anchors if a.symbol not in perceived]
        return result

    def _merged_views(self, anchors: list[Anchor], frame: list[Percept], time: float
                      ) -> tuple[np.ndarray, dict[int, list[int]]]:
        """Two objects seen as one segment: (A, P) pairs refused, and the percepts (index in
        ``frame``) judged merged -> the anchors (indices) merged in them.

        A pair is refused when the percept is far larger in the table plane than the anchor
        (``merge_ratio``), or when the percept's box holds the last perceived positions of two
        or more anchors perceived within ``merge_seconds`` and is larger than each of them
        (its largest horizontal extent over 1.2 times theirs plus 1 cm): a container lowered
        over a ball holds the ball's position too, but is not larger than itself."""
        a_ext = np.array([an.size.samples[0][:2].max() for an in anchors])
        p_ext = np.array([pc.size[:2].max() for pc in frame])
        refuse = p_ext[None, :] > self.merge_ratio * a_ext[:, None] + 0.02
        merged: dict[int, list[int]] = {}
        recent = [k for k, an in enumerate(anchors)
                  if an.history and time - an.last_seen <= self.merge_seconds]
        if len(recent) < 2:
            return refuse, merged
        centres = np.array([anchors[k].history[-1].position for k in recent])
        positions = np.array([pc.position for pc in frame])
        half = np.array([pc.size for pc in frame]) / 2
        inside = np.all(np.abs(centres[:, None, :] - positions[None]) <= half[None], axis=2)
        for j in np.nonzero(inside.sum(axis=0) >= 2)[0]:
            held = [recent[r] for r in np.nonzero(inside[:, j])[0]]
            if all(p_ext[j] > 1.2 * a_ext[k] + 0.01 for k in held):
                refuse[held, j] = True
                merged[int(j)] = held
        return refuse, merged

    def _unique_lookalikes(self, anchors: list[Anchor], features: np.ndarray,
                           matched_anchor: dict[int, int], refuse: np.ndarray, time: float
                           ) -> dict[int, int]:
        """Re-identification by appearance for what the matcher left unmatched: percept ->
        anchor (indices) where the percept looks like that anchor (category, colour and size
        similarities at least ``reid_similarity``), the anchor has not been perceived for
        ``reid_seconds`` or more, and neither has another such look-alike among the anchors
        and percepts left over. Position is not asked: after the camera was covered, or
        after a container was carried over something while unseen, an object may be anywhere
        on the table; but it is still the only black cup."""
        if self.reid_seconds <= 0 or not anchors or features.shape[1] == 0:
            return {}
        taken = set(matched_anchor.values())
        free_a = np.array([k not in taken and anchors[k].confirmed
                           and time - anchors[k].last_seen >= self.reid_seconds
                           for k in range(len(anchors))])
        free_p = np.array([j not in matched_anchor for j in range(features.shape[1])])
        cat, col, size = (np.asarray(self.reid_similarity, dtype=float))
        alike = ((features[..., 0] >= cat) & (features[..., 1] >= col)
                 & (features[..., 3] >= size) & ~refuse)
        # uniqueness counts every anchor and percept left over, even one too recent to take
        left_a = np.array([k not in taken for k in range(len(anchors))])
        alike_left = alike & left_a[:, None] & free_p[None, :]
        out: dict[int, int] = {}
        for j in np.nonzero(free_p)[0]:
            ks = np.nonzero(alike_left[:, j])[0]
            if len(ks) == 1 and free_a[ks[0]] and alike_left[ks[0]].sum() == 1:
                out[int(j)] = int(ks[0])
        return out

    def _views(self, anchors: list[Anchor], frame: list[Percept], features: np.ndarray,
               matched_anchor: dict[int, int], matched: set[str],
               merged: dict[int, list[int]], time: float) -> dict[int, list[str]]:
        """Unmatched percepts (index in ``frame``) that are partial or merged views of anchors
        not perceived this frame -> those anchors' symbols (see the module doc)."""
        views: dict[int, list[str]] = {}
        if self.withhold_seconds <= 0 or not anchors:
            self._withholding.clear()
            return views
        unseen = [k for k, an in enumerate(anchors) if an.symbol not in matched]
        still: dict[str, float] = {}
        for j, percept in enumerate(frame):
            if j in matched_anchor:
                continue
            hits = []
            for k in unseen:
                anchor = anchors[k]
                if k not in merged.get(j, ()):
                    if features[k, j, 1] < self.view_colour:
                        continue
                    if not _boxes_overlap(anchor, percept, self.view_margin):
                        continue
                since = self._withholding.get(anchor.symbol, time)
                still[anchor.symbol] = since
                if time - since <= self.withhold_seconds:
                    hits.append(anchor.symbol)
            if hits:
                views[j] = hits
        self._withholding = still
        return views

    def _histogram_bins(self, percepts: Sequence[Percept]) -> int | None:
        for anchor in self._anchors.values():
            return anchor.colour.dim
        for percept in percepts:
            if _invalid(percept, None) is None:
                return int(percept.colour_histogram.size)
        return None

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
            "symbol_counters": self.symbols.counters,
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
            )
            manager.time = None if record.get("time") is None else float(record["time"])
            manager.symbols = SymbolTable(
                {str(k): int(v) for k, v in record["symbol_counters"].items()}
            )
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


def _boxes_overlap(anchor: Anchor, percept: Percept, margin: float) -> bool:
    """Whether the percept's 3-D box overlaps (within ``margin``) the anchor's box placed at its
    last perceived position or at any of its particles of positive weight."""
    half = (anchor.size.samples[0] + percept.size) / 2 + margin
    centres = [anchor.history[-1].position[None, :]] if anchor.history else []
    if anchor.position.is_probabilistic:
        centres.append(anchor.position.samples[anchor.position.weights > 0])
    else:
        centres.append(anchor.position.samples)
    for c in centres:
        if np.any(np.all(np.abs(c - percept.position) <= half, axis=1)):
            return True
    return False


def _invalid(percept: Percept, bins: int | None) -> str | None:
    if not isinstance(percept, Percept):
        return f"not a Percept: {type(percept).__name__}"
    try:
        percept.validate()
    except PerceptError as exc:
        return str(exc)
    if bins is not None and percept.colour_histogram.size != bins:
        return f"colour histogram has {percept.colour_histogram.size} bins, anchors have {bins}"
    return None
