"""Published multi-object trackers run on the same percepts, for comparison.

:data:`BASELINES` are the 2-D box trackers below (:data:`BOX_TRACKERS`) and the probabilistic
3-D trackers of Stone Soup (``stonesoup-jpda``, ``stonesoup-mht``:
:mod:`probanchor.evaluation.stonesoup_trackers`); :func:`run_baseline` runs any of them.

SORT, ByteTrack and OC-SORT from Roboflow's ``trackers`` package (2.6.1). They track 2-D boxes: each
percept's mask bounding box ``Percept.bbox`` is a detection, with confidence 1 by default (our
segments are not scored; pass ``confidence`` to use e.g. the best category probability). A track id
``k`` of method ``m`` becomes the symbol ``"m-k"``, and each frame becomes a
:class:`~probanchor.evaluation.record.TrackingRecord`, so the metrics of
:mod:`probanchor.evaluation.metrics` apply unchanged.

Settings, chosen in the trackers' favour: the lost-track buffer is ``lost_seconds`` (60 s by
default, longer than any occlusion in our scenarios) instead of the usual 1 s; a track gets an id
from its first confirmed frame (``minimum_consecutive_frames=1``). The trackers are given each
frame's time stamp, so the buffer is in seconds of scenario time.

Positions: a track matched to a percept this frame is at that percept's 3-D position
(``perceived``). A track not matched this frame is, when ``hold_lost`` is on (the default), kept
at the 3-D position of its last percept for as long as the tracker still holds the track (and
at most ``lost_seconds``): the best a tracker without reasoning can do, the same as our
``--no-reasoning``. Otherwise it has no hypothesis until it is matched again.

Installation: ``trackers`` declares a dependency on ``opencv-python``, whose ``cv2`` would
overwrite the one of ``opencv-python-headless`` that the rest of the project uses. It runs fine
with the headless ``cv2``, so ``scripts/setup.sh`` installs the pinned version listed in
``requirements-nodeps.txt`` with ``pip --no-deps``, and ``pyproject.toml`` lists its other
dependencies (supervision, rich, pydeprecate, requests).
"""

from __future__ import annotations

import time as _time
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from probanchor.evaluation.record import FrameTimings, Hypothesis, TrackingRecord, record_for_frame
from probanchor.evaluation.stonesoup_trackers import NAMES as _STONESOUP_NAMES
from probanchor.evaluation.stonesoup_trackers import STONESOUP, run_stonesoup
from probanchor.percepts import Percept, PerceptFrame

BOX_TRACKERS = ("sort", "bytetrack", "ocsort")
BASELINES = (*BOX_TRACKERS, *STONESOUP)
_NAMES = {"sort": "SORT", "bytetrack": "ByteTrack", "ocsort": "OC-SORT", **_STONESOUP_NAMES}


class BaselineError(ValueError):
    """A baseline that cannot run (unknown method, no 2-D boxes in the stream...)."""


def display_name(method: str) -> str:
    """``"ocsort"`` -> ``"OC-SORT"`` (for tables)."""
    return _NAMES.get(method, method)


def make_tracker(method: str, lost_seconds: float = 60.0, frame_rate: float = 30.0, **kwargs: Any):
    """A fresh tracker of ``method`` (one of :data:`BOX_TRACKERS`) with generous buffers.

    ``kwargs`` go to the tracker's constructor and override the settings described above.
    """
    try:
        from trackers import ByteTrackTracker, OCSORTTracker, SORTTracker
    except ImportError as exc:  # pragma: no cover - setup installs it
        raise BaselineError(
            "the 'trackers' package is missing: run `make setup` (scripts/setup.sh installs it)"
        ) from exc
    classes = {"sort": SORTTracker, "bytetrack": ByteTrackTracker, "ocsort": OCSORTTracker}
    if method not in classes:
        raise BaselineError(f"unknown box tracker {method!r}; known: {', '.join(BOX_TRACKERS)}")
    # The trackers express the buffer in frames at 30 FPS, whatever the stream's rate.
    settings: dict[str, Any] = {
        "lost_track_buffer": max(1, int(round(30.0 * lost_seconds))),
        "frame_rate": frame_rate,
        "minimum_consecutive_frames": 1,
    }
    settings.update(kwargs)
    return classes[method](**settings)


def _valid_box(bbox: tuple[int, int, int, int]) -> bool:
    x0, y0, x1, y1 = bbox
    return x1 > x0 and y1 > y0


def _frame_rate(frames: list[PerceptFrame]) -> float:
    dts = np.diff([f.time for f in frames])
    dts = dts[dts > 0]
    return float(1.0 / np.median(dts)) if len(dts) else 30.0


def run_baseline(
    method: str,
    frames: Iterable[PerceptFrame],
    *,
    lost_seconds: float = 60.0,
    hold_lost: bool = True,
    confidence: Callable[[Percept], float] | None = None,
    ignore: Iterable[str] = (),
    **tracker_kwargs: Any,
) -> list[TrackingRecord]:
    """Run one baseline tracker over a percept stream; one record per frame.

    ``ignore`` lists ground-truth ids left out of the evaluation (e.g. the hand). For the box
    trackers, percepts whose bbox is empty are not given to the tracker; a stream with no usable
    bbox at all raises :class:`BaselineError` (the trackers need 2-D boxes). A Stone Soup
    tracker (:data:`STONESOUP`) takes the 3-D positions and no ``hold_lost``, ``confidence`` or
    tracker arguments (it coasts on its own motion model; its settings are
    ``stonesoup_trackers.TUNED``).
    """
    if method not in BASELINES:
        raise BaselineError(f"unknown baseline {method!r}; known: {', '.join(BASELINES)}")
    if method in STONESOUP:
        if tracker_kwargs:
            raise BaselineError(f"{method}: unknown arguments {sorted(tracker_kwargs)}")
        return run_stonesoup(method, frames, lost_seconds=lost_seconds, ignore=ignore)
    import supervision as sv

    frames = list(frames)
    ignore = tuple(ignore)
    if frames and not any(_valid_box(p.bbox) for f in frames for p in f.percepts):
        raise BaselineError("the percept stream has no 2-D bounding boxes (Percept.bbox)")
    tracker = make_tracker(method, lost_seconds, _frame_rate(frames), **tracker_kwargs)
    last_seen: dict[str, tuple[float, np.ndarray]] = {}  # symbol -> (time, position)
    records: list[TrackingRecord] = []
    for fr in frames:
        start = _time.perf_counter()
        usable = [i for i, p in enumerate(fr.percepts) if _valid_box(p.bbox)]
        if usable:
            xyxy = np.array([fr.percepts[i].bbox for i in usable], dtype=float)
            conf = np.array(
                [1.0 if confidence is None else float(confidence(fr.percepts[i])) for i in usable]
            )
            dets = sv.Detections(xyxy=xyxy, confidence=conf, data={"index": np.array(usable)})
        else:
            dets = sv.Detections.empty()
            dets.data = {"index": np.empty(0, dtype=int)}
        out = tracker.update(dets, timestamp=fr.time)
        elapsed = (_time.perf_counter() - start) * 1000.0
        hyps: dict[str, Hypothesis] = {}
        matches: list[tuple[Percept, str]] = []
        ids = out.tracker_id if out.tracker_id is not None else np.empty(0, dtype=int)
        indices = out.data.get("index", np.empty(0, dtype=int)) if len(out) else []
        for tid, idx in zip(ids, indices, strict=True):
            if int(tid) < 0:  # not (yet) a confirmed track
                continue
            percept = fr.percepts[int(idx)]
            symbol = f"{method}-{int(tid)}"
            hyps[symbol] = Hypothesis(percept.position.copy(), True)
            last_seen[symbol] = (fr.time, percept.position.copy())
            matches.append((percept, symbol))
        if hold_lost:
            alive = _alive_symbols(tracker, method)
            for symbol, (t, pos) in list(last_seen.items()):
                if symbol in hyps:
                    continue
                if fr.time - t <= lost_seconds and (alive is None or symbol in alive):
                    hyps[symbol] = Hypothesis(pos, False)
                else:
                    del last_seen[symbol]
        records.append(record_for_frame(fr, hyps, matches, FrameTimings(anchoring=elapsed), ignore))
    return records


def _alive_symbols(tracker: Any, method: str) -> set[str] | None:
    """Symbols of the tracks the tracker still holds (``None`` if it does not say)."""
    tracks = getattr(tracker, "tracks", None)
    if tracks is None:
        return None
    ids = (getattr(t, "tracker_id", -1) for t in tracks)
    return {f"{method}-{int(i)}" for i in ids if i is not None and int(i) >= 0}
