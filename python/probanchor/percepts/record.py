"""The percept record and its validation."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: how far above 1 the category probabilities of a percept may sum (a writer that rounds them)
CATEGORY_SUM_TOLERANCE = 0.01


class PerceptError(ValueError):
    """A percept that cannot be used (NaN, empty histogram, wrong shape...)."""


@dataclass
class Percept:
    """One segmented object in one frame.

    ``position`` is the 3-D centroid in metres (world frame, z up), ``size`` the extents of the
    axis-aligned 3-D bounding box in metres, ``colour_histogram`` a normalised HSV histogram
    (flattened, sums to 1), ``colour_names`` the colour predicates grounded from it,
    ``category`` the top categories with their probabilities (best first), ``bbox`` the 2-D
    mask bounding box in pixels ``(x0, y0, x1, y1)``. ``source_id`` is free for a pipeline's
    own bookkeeping (e.g. a segment index); anchoring does not read it. ``truth_id`` is set only
    by simulators for evaluation; anchoring never reads it either. ``grip`` (optional, metres,
    world frame) is where a hand closes: set on skin percepts by a pipeline that finds the
    hand's end of an arm's segment (``position`` is then the centre of hand and forearm
    together); ``None`` for other percepts and in streams written before it existed.
    """

    time: float
    position: np.ndarray
    size: np.ndarray
    colour_histogram: np.ndarray
    category: dict[str, float]
    colour_names: list[str] = field(default_factory=list)
    bbox: tuple[int, int, int, int] = (0, 0, 0, 0)
    source_id: int | None = None
    truth_id: str | None = None
    grip: np.ndarray | None = None

    def __post_init__(self) -> None:
        self.position = np.asarray(self.position, dtype=float).reshape(-1)
        if self.grip is not None:
            self.grip = np.asarray(self.grip, dtype=float).reshape(-1)
        self.size = np.asarray(self.size, dtype=float).reshape(-1)
        self.colour_histogram = np.asarray(self.colour_histogram, dtype=float).reshape(-1)

    @property
    def best_category(self) -> str:
        return max(self.category.items(), key=lambda kv: kv[1])[0]

    def validate(self) -> None:
        """Raise :class:`PerceptError` naming the first thing wrong with this percept."""
        if not math.isfinite(self.time):
            raise PerceptError(f"time is {self.time}")
        vectors = [("position", self.position, 3), ("size", self.size, 3)]
        if self.grip is not None:
            vectors.append(("grip", self.grip, 3))
        for name, arr, n in vectors:
            if arr.shape != (n,):
                raise PerceptError(f"{name} has shape {arr.shape}, expected ({n},)")
            if not np.all(np.isfinite(arr)):
                raise PerceptError(f"{name} contains NaN or infinity: {arr.tolist()}")
        if np.any(self.size < 0):
            raise PerceptError(f"size is negative: {self.size.tolist()}")
        hist = self.colour_histogram
        if hist.size == 0 or not np.all(np.isfinite(hist)) or np.any(hist < 0):
            raise PerceptError("colour histogram is empty, negative or not finite")
        if hist.sum() <= 0:
            raise PerceptError("colour histogram is empty (all bins zero)")
        if not self.category:
            raise PerceptError("no category probabilities")
        for name, p in self.category.items():
            if not (isinstance(p, (int, float)) and math.isfinite(p) and 0 <= p <= 1):
                raise PerceptError(f"category {name!r} has probability {p!r}")
        total = math.fsum(self.category.values())
        if total > 1 + CATEGORY_SUM_TOLERANCE:
            raise PerceptError(f"category probabilities sum to {total:g}, more than 1")

    def to_json(self) -> dict[str, Any]:
        record: dict[str, Any] = {
            "time": self.time,
            "position": self.position.tolist(),
            "size": self.size.tolist(),
            "colour_histogram": self.colour_histogram.tolist(),
            "colour_names": list(self.colour_names),
            "category": dict(self.category),
            "bbox": list(self.bbox),
        }
        if self.source_id is not None:
            record["source_id"] = self.source_id
        if self.truth_id is not None:
            record["truth_id"] = self.truth_id
        if self.grip is not None:
            record["grip"] = self.grip.tolist()
        return record

    @classmethod
    def from_json(cls, record: dict[str, Any]) -> Percept:
        if not isinstance(record, dict):
            raise PerceptError(f"a percept is a JSON object, not {type(record).__name__}")
        if not isinstance(record.get("colour_names", []), list):
            raise PerceptError("'colour_names' must be a list of names, not "
                               f"{type(record.get('colour_names')).__name__}")
        if not isinstance(record.get("category"), dict):
            raise PerceptError("'category' must be an object of category -> probability, not "
                               f"{type(record.get('category')).__name__}")
        try:
            return cls(
                time=float(record["time"]),
                position=np.asarray(record["position"], dtype=float),
                size=np.asarray(record["size"], dtype=float),
                colour_histogram=np.asarray(record["colour_histogram"], dtype=float),
                category={str(k): float(v) for k, v in record["category"].items()},
                colour_names=[str(c) for c in record.get("colour_names", [])],
                bbox=tuple(int(v) for v in record.get("bbox", (0, 0, 0, 0))),  # type: ignore[arg-type]
                source_id=record.get("source_id"),
                truth_id=record.get("truth_id"),
                grip=(None if record.get("grip") is None
                      else np.asarray(record["grip"], dtype=float)),
            )
        except KeyError as exc:
            raise PerceptError(f"missing field {exc.args[0]!r}") from exc
        except (TypeError, ValueError) as exc:
            raise PerceptError(str(exc)) from exc
