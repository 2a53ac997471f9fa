"""The per-frame tracking record that a runner (ours or a baseline tracker) fills for evaluation.

One :class:`TrackingRecord` per frame holds what was true (ground truth from the simulator),
what the system believed (one hypothesis per anchor symbol) and which symbol the system gave
to the percept of each ground-truth object. Every metric in this package is computed from a
list of such records, so the anchoring system and the baseline trackers are measured alike.

Records can be saved as JSON Lines (one record per line) and read back.
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np


class RecordError(ValueError):
    """A tracking record (or ground truth) that cannot be used."""


def _vec3(value: Any, what: str) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=float).reshape(-1)
    except (TypeError, ValueError) as exc:
        raise RecordError(f"{what}: not a 3-D position: {value!r}") from exc
    if arr.shape != (3,):
        raise RecordError(f"{what}: position has {arr.size} values, expected 3")
    return arr


@dataclass
class TruthObject:
    """A ground-truth object in one frame: true position (metres, world frame), visibility and
    what hides it (``None`` when visible or unknown)."""

    position: np.ndarray
    visible: bool
    hidden_by: str | None = None

    def __post_init__(self) -> None:
        self.position = _vec3(self.position, "truth object")


@dataclass
class Hypothesis:
    """What the system believes about one anchor (or track) in one frame.

    ``position`` is a point estimate in metres: the perceived position when ``perceived``, else
    e.g. :func:`point_estimate` of the anchor's particles. A position with NaN means "no
    estimate" and the hypothesis is ignored by the metrics. ``occluders``: for a hidden anchor
    whose belief the reasoning gave, the probability of each occluder symbol (the rest of the
    mass: under nothing); None when not known.
    """

    position: np.ndarray
    perceived: bool
    occluders: dict[str, float] | None = None

    def __post_init__(self) -> None:
        self.position = _vec3(self.position, "hypothesis")


@dataclass
class FrameTimings:
    """Wall-clock milliseconds spent on one frame. ``total`` defaults to the sum of the parts."""

    perception: float = 0.0
    anchoring: float = 0.0
    filter: float = 0.0
    total: float | None = None

    def total_ms(self) -> float:
        if self.total is not None:
            return self.total
        return self.perception + self.anchoring + self.filter


@dataclass
class TrackingRecord:
    """One frame of a run, as the metrics see it.

    - ``frame``, ``time``: frame index and scenario time in seconds.
    - ``truth``: ground-truth id -> :class:`TruthObject`, for *every* object on the table, hidden
      ones included (at their true positions), so that keeping a hidden object is credited.
    - ``hypotheses``: anchor symbol -> :class:`Hypothesis`, for every anchor the system holds.
    - ``assignments``: ground-truth id of a percept (``Percept.truth_id``) -> the symbol the
      system gave that percept in this frame. Only perceived objects appear here. Should the
      perception split one object into several percepts (a mug's handle segmented on its own
      for a frame), the symbol of its main view, the largest of them, stands for the object: a
      fragment given a symbol of its own is a phantom anchor (a false positive for the
      position metrics), not the object changing its identity.
    - ``timings``: where the time of this frame went.
    - ``rejected_percepts``: percepts of this frame dropped as bad input (NaN, empty histogram).
    - ``ambiguous``: re-acquisitions the beliefs could not tell from a look-alike's: the symbol
      given -> each candidate symbol's probability (``{"ball-2": {"ball-2": 0.52, "ball-1":
      0.48}}``).
    - ``revised``: the identity revisions made in this frame (``anchoring.identity.Revision``
      as JSON: ``frame``, ``mapping`` old -> new symbol, ``since`` per old symbol, ``probability``,
      ``before``, ``evidence``): this frame's symbols are already the new ones; the answers of
      the frames from ``since`` to this one are revised by :func:`revised_records`.
    """

    frame: int
    time: float
    truth: dict[str, TruthObject] = field(default_factory=dict)
    hypotheses: dict[str, Hypothesis] = field(default_factory=dict)
    assignments: dict[str, str] = field(default_factory=dict)
    timings: FrameTimings = field(default_factory=FrameTimings)
    rejected_percepts: int = 0
    ambiguous: dict[str, dict[str, float]] = field(default_factory=dict)
    revised: list[dict[str, Any]] = field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        return {
            "frame": self.frame,
            "time": self.time,
            "truth": {
                k: {"position": v.position.tolist(), "visible": v.visible, "hidden_by": v.hidden_by}
                for k, v in self.truth.items()
            },
            "hypotheses": {
                k: _hypothesis_json(v) for k, v in self.hypotheses.items()
            },
            "assignments": dict(self.assignments),
            "timings": {
                "perception": self.timings.perception,
                "anchoring": self.timings.anchoring,
                "filter": self.timings.filter,
                "total": self.timings.total,
            },
            "rejected_percepts": self.rejected_percepts,
            "ambiguous": {k: dict(v) for k, v in self.ambiguous.items()},
            "revised": [dict(r) for r in self.revised],
        }

    @classmethod
    def from_json(cls, data: Mapping[str, Any]) -> TrackingRecord:
        try:
            hyps = {}
            for k, v in data.get("hypotheses", {}).items():
                pos = [math.nan if x is None else x for x in v["position"]]
                occ = v.get("occluders")
                hyps[str(k)] = Hypothesis(pos, bool(v["perceived"]),
                                          None if occ is None
                                          else {str(s): float(p) for s, p in occ.items()})
            t = data.get("timings", {})
            return cls(
                frame=int(data["frame"]),
                time=float(data["time"]),
                truth=truth_from_dict({"objects": data.get("truth", {})}),
                hypotheses=hyps,
                assignments={str(k): str(v) for k, v in data.get("assignments", {}).items()},
                timings=FrameTimings(
                    float(t.get("perception", 0.0)),
                    float(t.get("anchoring", 0.0)),
                    float(t.get("filter", 0.0)),
                    None if t.get("total") is None else float(t["total"]),
                ),
                rejected_percepts=int(data.get("rejected_percepts", 0)),
                ambiguous={str(k): {str(s): float(p) for s, p in v.items()}
                           for k, v in data.get("ambiguous", {}).items()},
                revised=[dict(r) for r in data.get("revised", [])],
            )
        except KeyError as exc:
            raise RecordError(f"missing field {exc.args[0]!r}") from exc
        except (TypeError, ValueError, AttributeError) as exc:
            raise RecordError(str(exc)) from exc


def _hypothesis_json(h: Hypothesis) -> dict[str, Any]:
    out: dict[str, Any] = {"position": [None if math.isnan(x) else x for x in h.position.tolist()],
                           "perceived": h.perceived}
    if h.occluders is not None:
        out["occluders"] = {s: round(float(p), 6) for s, p in h.occluders.items()}
    return out


def revised_records(records: Sequence[TrackingRecord]) -> list[TrackingRecord]:
    """The records with every frame's answers as the run answers them at its end: each
    revision (``TrackingRecord.revised``, made at frame ``r``) renames, in the frames from its
    ``since`` up to ``r``, the symbols it revised (its ``mapping``); revisions apply in the
    order they were made. Records without revisions are returned as they are (copies of the
    records that change)."""
    revisions = sorted((r for rec in records for r in rec.revised), key=lambda r: int(r["frame"]))
    if not revisions:
        return list(records)
    out: list[TrackingRecord] = []
    for rec in records:
        renames = [r for r in revisions
                   if any(int(s) <= rec.frame < int(r["frame"]) for s in r["since"].values())]
        if not renames:
            out.append(rec)
            continue

        def rename(symbol: str, frame: int = rec.frame, renames: list = renames) -> str:
            for r in renames:
                since = r["since"].get(symbol)
                if since is not None and int(since) <= frame < int(r["frame"]):
                    symbol = str(r["mapping"][symbol])
            return symbol

        out.append(dataclasses.replace(
            rec,
            assignments={oid: rename(sym) for oid, sym in rec.assignments.items()},
            hypotheses={rename(sym): h for sym, h in rec.hypotheses.items()},
            ambiguous={rename(sym): {rename(c): p for c, p in cands.items()}
                       for sym, cands in rec.ambiguous.items()},
        ))
    return out


def truth_from_dict(
    truth: Mapping[str, Any], ignore: Iterable[str] = ()
) -> dict[str, TruthObject]:
    """Ground truth of one frame from the simulator's per-frame ``truth`` dictionary.

    The format is the one ``PerceptFrame.truth`` carries: ``{"objects": {id: {"position":
    [x, y, z], "visible": bool, "hidden_by": id or null}}}``. Objects in ``ignore`` (e.g. a hand
    or the camera cover) and objects whose position is null or that are marked
    ``"present": false`` (taken off the table) are left out.
    """
    skip = set(ignore)
    objects = truth.get("objects", {}) if isinstance(truth, Mapping) else None
    if not isinstance(objects, Mapping):
        raise RecordError(f"truth 'objects' is not a mapping: {type(objects).__name__}")
    result: dict[str, TruthObject] = {}
    for oid, item in objects.items():
        if oid in skip:
            continue
        if not isinstance(item, Mapping) or "position" not in item:
            raise RecordError(f"truth object {oid!r}: no position")
        if item["position"] is None or item.get("present", True) is False:
            continue
        position = _vec3(item["position"], f"truth object {oid!r}")
        if not np.all(np.isfinite(position)):
            raise RecordError(f"truth object {oid!r}: position is not finite: {position.tolist()}")
        hidden_by = item.get("hidden_by")
        result[str(oid)] = TruthObject(
            position, bool(item.get("visible", True)), None if hidden_by is None else str(hidden_by)
        )
    return result


def record_for_frame(
    frame: Any,
    hypotheses: Mapping[str, Hypothesis],
    matches: Iterable[tuple[Any, str]],
    timings: FrameTimings | None = None,
    ignore: Iterable[str] = (),
    rejected_percepts: int | None = None,
    ambiguous: Mapping[str, Mapping[str, float]] | None = None,
) -> TrackingRecord:
    """The record of one ``percepts.PerceptFrame`` as a runner has processed it.

    ``matches`` are the ``(percept, symbol)`` pairs the runner decided this frame (acquired,
    re-acquired or tracked); percepts without ``truth_id`` are left out of the assignments.
    Ground truth comes from ``frame.truth`` (see :func:`truth_from_dict`); ``rejected_percepts``
    defaults to ``len(frame.rejected)``; ``ambiguous`` is the frame's ambiguous
    re-acquisitions (see :class:`TrackingRecord`).
    """
    skip = set(ignore)
    main_view: dict[str, tuple[float, str]] = {}  # truth id -> (view area, symbol)
    for p, sym in matches:
        tid = getattr(p, "truth_id", None)
        if tid is None or tid in skip:
            continue
        area = view_area(p)
        if str(tid) not in main_view or area > main_view[str(tid)][0]:
            main_view[str(tid)] = (area, str(sym))
    assignments = {tid: sym for tid, (_, sym) in main_view.items()}
    try:
        truth = truth_from_dict(frame.truth or {}, skip)
    except RecordError as exc:
        raise RecordError(f"frame {frame.frame}: {exc}") from exc
    return TrackingRecord(
        frame=int(frame.frame),
        time=float(frame.time),
        truth=truth,
        hypotheses=dict(hypotheses),
        assignments=assignments,
        timings=timings if timings is not None else FrameTimings(),
        rejected_percepts=len(frame.rejected) if rejected_percepts is None else rejected_percepts,
        ambiguous={str(k): {str(s): float(p) for s, p in v.items()}
                   for k, v in (ambiguous or {}).items()},
    )


def view_area(percept: Any) -> float:
    """How much of its object a percept shows: its bounding box's area in pixels, or without
    one the area of its 3-D size's largest face."""
    bbox = getattr(percept, "bbox", None)
    if bbox is not None and len(bbox) == 4:
        area = float(max(bbox[2] - bbox[0], 0) * max(bbox[3] - bbox[1], 0))
        if area > 0:
            return area
    size = getattr(percept, "size", None)
    if size is None:
        return 0.0
    a, b, c = (float(v) for v in size)
    return max(a * b, a * c, b * c)


def point_estimate(
    particles: np.ndarray,
    weights: np.ndarray | None = None,
    method: str = "mode",
    cell: float = 0.05,
) -> np.ndarray:
    """A point estimate (3,) of a weighted particle set (N, 3).

    ``method="mean"`` is the weighted mean; ``method="mode"`` (the default) bins the particles
    into cubes of side ``cell`` metres, takes the heaviest cube and returns the weighted mean of
    its particles: for a multi-modal belief (a ball under one of three mugs) this lands on one
    of the mugs instead of between them. Vectorised; no per-particle loop.
    """
    pts = np.asarray(particles, dtype=float).reshape(-1, 3)
    if len(pts) == 0:
        return np.full(3, np.nan)
    w = np.ones(len(pts)) if weights is None else np.asarray(weights, dtype=float).reshape(-1)
    if w.shape != (len(pts),):
        raise RecordError(f"{len(w)} weights for {len(pts)} particles")
    if not np.all(np.isfinite(w)) or np.any(w < 0) or w.sum() <= 0:
        raise RecordError("particle weights must be finite, non-negative and not all zero")
    if method == "mean":
        return (pts * w[:, None]).sum(axis=0) / w.sum()
    if method != "mode":
        raise RecordError(f"unknown point estimate {method!r} (use 'mode' or 'mean')")
    # Mass of each occupied cube together with its 26 neighbours (so that a mode lying on a cube
    # boundary is not split), found by binary search over the cubes' integer codes.
    keys = np.floor(pts / cell).astype(np.int64)
    keys -= keys.min(axis=0) - 1
    dims = keys.max(axis=0) + 2

    def code(k: np.ndarray) -> np.ndarray:
        return (k[..., 0] * dims[1] + k[..., 1]) * dims[2] + k[..., 2]

    # Each cube by one integer code (in the cubes' lexicographic order, since every key lies
    # in 1..dims-2): a sort of N integers, not of N rows.
    codes, first, inverse = np.unique(code(keys), return_index=True, return_inverse=True)
    cubes = keys[first]
    mass = np.bincount(inverse.reshape(-1), weights=w)
    offsets = np.stack(np.meshgrid([-1, 0, 1], [-1, 0, 1], [-1, 0, 1]), -1).reshape(-1, 3)
    neighbours = code(cubes[None, :, :] + offsets[:, None, :])  # (27, M)
    at = np.clip(np.searchsorted(codes, neighbours), 0, len(codes) - 1)
    smoothed = np.where(codes[at] == neighbours, mass[at], 0.0).sum(axis=0)
    best = cubes[int(np.argmax(smoothed))]
    members = np.all(np.abs(keys - best) <= 1, axis=1)
    centre = (pts[members] * w[members, None]).sum(axis=0) / w[members].sum()
    # One mean-shift step: the particles within one cube side of that centre.
    near = np.linalg.norm(pts - centre, axis=1) <= cell
    if w[near].sum() <= 0:
        return centre
    return (pts[near] * w[near, None]).sum(axis=0) / w[near].sum()


def write_records(path: str | Path, records: Iterable[TrackingRecord]) -> None:
    """Write records as JSON Lines, one frame per line."""
    with open(path, "w", encoding="utf-8") as out:
        for rec in records:
            out.write(json.dumps(rec.to_json()) + "\n")


def read_records(path: str | Path) -> Iterator[TrackingRecord]:
    """Read records written by :func:`write_records`; a bad line raises :class:`RecordError`
    naming the file and line."""
    with open(path, encoding="utf-8") as src:
        for lineno, text in enumerate(src, start=1):
            if not text.strip():
                continue
            try:
                yield TrackingRecord.from_json(json.loads(text))
            except (json.JSONDecodeError, RecordError) as exc:
                raise RecordError(f"{path}:{lineno}: not a tracking record: {exc}") from exc
