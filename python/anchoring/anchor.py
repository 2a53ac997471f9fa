"""The anchor: a symbol and the attributes of one physical object, maintained over time.

Update rules on re-acquire (docs/anchoring.md):

- position: *replaced* by the percept's position (deterministic again, particles dropped): the
  newest measurement is the best estimate of where a moving object is;
- size and colour histogram: the *mean over the bounded percept history* (the last
  ``history_size`` percepts), which smooths segmentation noise and follows slow changes;
- colour names: those named by at least half of the percepts in the history;
- category: probabilities *accumulated* (running sums and a count, as the original): the
  estimate is the average over every percept of the anchor;
- last seen: the percept's time.

Track (not perceived): the position becomes the particles the reasoning supplies
(:meth:`Anchor.set_position_particles`), otherwise it keeps its last value.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from anchoring.attribute import Attribute
from probanchor.percepts import Percept


@dataclass
class Anchor:
    """One anchored object. ``symbol`` is stable for the anchor's whole life (``ball-1``)."""

    symbol: str
    symbol_category: str
    created: float
    last_seen: float
    position: Attribute
    size: Attribute
    colour: Attribute
    colour_names: list[str]
    category_sums: dict[str, float]
    category_count: int
    history: deque[Percept]
    confirmed: bool = False
    observations: int = 1
    history_size: int = field(default=10, repr=False)
    # while tracked: per position particle, whether the reasoning has the object under an
    # occluder there (anchoring.likelihood); None while perceived or when not told
    occluded: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        # window sums over the history, for the mean size and colour (re-acquire hot path)
        self._hists = deque((_normalised(p.colour_histogram) for p in self.history),
                            maxlen=self.history.maxlen)
        self._size_sum = np.sum([p.size for p in self.history], axis=0) if self.history \
            else np.zeros(3)
        self._hist_sum = np.sum(self._hists, axis=0) if self.history else np.zeros(self.colour.dim)

    # --- creation and update -------------------------------------------------------------
    @classmethod
    def acquire(cls, symbol: str, percept: Percept, history_size: int = 10) -> Anchor:
        t = percept.time
        return cls(
            symbol=symbol,
            symbol_category=symbol.rsplit("-", 1)[0],
            created=t,
            last_seen=t,
            position=Attribute.deterministic(percept.position, t),
            size=Attribute.deterministic(percept.size, t),
            colour=Attribute.deterministic(_normalised(percept.colour_histogram), t),
            colour_names=list(percept.colour_names),
            category_sums=dict(percept.category),
            category_count=1,
            history=deque([percept], maxlen=history_size),
            history_size=history_size,
        )

    def reacquire(self, percept: Percept) -> None:
        """Update with a (validated) percept of this anchor's object."""
        t = percept.time
        if len(self.history) == self.history.maxlen:
            self._size_sum -= self.history[0].size
            self._hist_sum -= self._hists[0]
        hist = _normalised(percept.colour_histogram)
        self.history.append(percept)
        self._hists.append(hist)
        self._size_sum += percept.size
        self._hist_sum += hist
        n = len(self.history)
        self.position = Attribute.deterministic(percept.position, t, checked=False)
        self.size = Attribute.deterministic(self._size_sum / n, t, checked=False)
        self.colour = Attribute.deterministic(self._hist_sum / n, t, checked=False)
        counts: dict[str, int] = {}
        for p in self.history:
            for name in set(p.colour_names):
                counts[name] = counts.get(name, 0) + 1
        self.colour_names = sorted(c for c, k in counts.items() if 2 * k >= n)
        for name, prob in percept.category.items():
            self.category_sums[name] = self.category_sums.get(name, 0.0) + prob
        self.category_count += 1
        self.last_seen = t
        self.observations += 1
        self.occluded = None

    def set_position_particles(
        self, positions: np.ndarray, weights: np.ndarray | None = None, time: float | None = None,
        occluded: np.ndarray | None = None,
    ) -> None:
        """Track: the position becomes the reasoning's weighted particles (N, 3);
        ``occluded`` (N,): whether each particle has the object under an occluder."""
        positions = np.asarray(positions, dtype=float)
        if positions.ndim != 2 or positions.shape[1] != 3:
            raise ValueError(f"{self.symbol}: positions must be (N, 3), got {positions.shape}")
        if occluded is not None:
            occluded = np.asarray(occluded, dtype=bool).reshape(-1)
            if occluded.shape[0] != positions.shape[0]:
                raise ValueError(f"{self.symbol}: {occluded.shape[0]} occluded flags for "
                                 f"{positions.shape[0]} particles")
        self.occluded = occluded
        t = self.position.time if time is None else time
        self.position = Attribute.probabilistic(positions, weights, t)
        self.position.augmented_support()  # the matching form, prepared once per update

    # --- views ---------------------------------------------------------------------------
    def category_average(self) -> dict[str, float]:
        """The category estimate (average over all percepts), unsorted."""
        n = self.category_count
        return {k: v / n for k, v in self.category_sums.items()}

    @property
    def category(self) -> dict[str, float]:
        """The current category estimate (average over all percepts), best first."""
        return dict(sorted(self.category_average().items(), key=lambda kv: (-kv[1], kv[0])))

    @property
    def best_category(self) -> str:
        return next(iter(self.category))

    def to_json(self) -> dict[str, Any]:
        return {
            "symbol": self.symbol,
            "symbol_category": self.symbol_category,
            "created": self.created,
            "last_seen": self.last_seen,
            "confirmed": self.confirmed,
            "observations": self.observations,
            "category": self.category,
            "category_sums": self.category_sums,
            "category_count": self.category_count,
            "colour_names": self.colour_names,
            "position": self.position.to_json(),
            "size": self.size.to_json(),
            "colour_histogram": self.colour.to_json(),
            "history_size": self.history_size,
            "history": [p.to_json() for p in self.history],
            "occluded": None if self.occluded is None else self.occluded.astype(int).tolist(),
        }

    @classmethod
    def from_json(cls, record: dict[str, Any]) -> Anchor:
        history_size = int(record.get("history_size", 10))
        return cls(
            symbol=str(record["symbol"]),
            symbol_category=str(record["symbol_category"]),
            created=float(record["created"]),
            last_seen=float(record["last_seen"]),
            position=Attribute.from_json(record["position"]),
            size=Attribute.from_json(record["size"]),
            colour=Attribute.from_json(record["colour_histogram"]),
            colour_names=[str(c) for c in record.get("colour_names", [])],
            category_sums={str(k): float(v) for k, v in record["category_sums"].items()},
            category_count=int(record["category_count"]),
            history=deque(
                (Percept.from_json(p) for p in record.get("history", [])), maxlen=history_size
            ),
            confirmed=bool(record.get("confirmed", False)),
            observations=int(record.get("observations", 1)),
            history_size=history_size,
            occluded=(None if record.get("occluded") is None
                      else np.asarray(record["occluded"], dtype=bool)),
        )


def _normalised(hist: np.ndarray) -> np.ndarray:
    hist = np.asarray(hist, dtype=float)
    total = hist.sum()
    return hist / total if total > 0 else hist
