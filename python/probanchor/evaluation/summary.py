"""The run summary (``DIR/summary.json``): what a run writes.

Fields, exactly: ``frames``; ``objects`` (a list of ``{"id", "symbols", "identity_kept",
"identity_kept_at_end"}``: kept in every frame's answer as given, and in the answers as revised
by the end of the run); ``revisions`` (every identity revision of the run, see
``TrackingRecord.revised``); ``beliefs`` (belief accuracy while hidden,
:mod:`probanchor.evaluation.beliefs`);
``id_switches``; ``idf1`` (``null`` when undefined: no ground truth and no hypothesis);
``ms_per_frame`` with ``perception``, ``anchoring``, ``filter``, ``total`` (means over frames);
``rejected_percepts`` (bad percepts dropped over the run); ``ambiguous_reacquisitions`` (how
many times a hidden anchor was re-acquired where a look-alike's belief was about as strong,
``TrackingRecord.ambiguous``). A caller may add its own fields
through ``extra`` (they never replace these).

Also, when the evaluation has them (:func:`~probanchor.evaluation.metrics.evaluate` computes
them): ``hota``, ``deta``, ``assa``, ``loca`` (:mod:`probanchor.evaluation.hota`; ``null`` when
undefined). They are not required of a summary read back (summaries written before them have
none).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from probanchor.evaluation.hota import hota_fields
from probanchor.evaluation.metrics import DEFAULT_THRESHOLD_M, Evaluation, evaluate
from probanchor.evaluation.record import TrackingRecord

SUMMARY_FIELDS = ("frames", "objects", "revisions", "beliefs", "id_switches", "idf1",
                  "ms_per_frame", "rejected_percepts", "ambiguous_reacquisitions")
#: the fields every summary has, also one written before revisions and beliefs were reported
READ_FIELDS = ("frames", "objects", "id_switches", "idf1", "ms_per_frame", "rejected_percepts",
               "ambiguous_reacquisitions")


def _finite_or_none(x: float) -> float | None:
    return None if x is None or not math.isfinite(x) else round(float(x), 6)


def ms_per_frame(records: Sequence[TrackingRecord]) -> dict[str, float]:
    """Mean milliseconds per frame of perception, anchoring, filter and in total."""
    n = len(records)
    if n == 0:
        return {"perception": 0.0, "anchoring": 0.0, "filter": 0.0, "total": 0.0}
    return {
        "perception": round(sum(r.timings.perception for r in records) / n, 3),
        "anchoring": round(sum(r.timings.anchoring for r in records) / n, 3),
        "filter": round(sum(r.timings.filter for r in records) / n, 3),
        "total": round(sum(r.timings.total_ms() for r in records) / n, 3),
    }


def make_summary(
    records: Sequence[TrackingRecord],
    evaluation: Evaluation | None = None,
    *,
    threshold: float = DEFAULT_THRESHOLD_M,
    extra: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """The summary dictionary of one run (evaluating the records unless given ``evaluation``)."""
    records = list(records)
    ev = evaluation if evaluation is not None else evaluate(records, threshold)
    assert ev.mot is not None
    at_end = {o.id: o for o in ev.objects_at_end}
    summary: dict[str, Any] = {
        "frames": ev.frames,
        "objects": [
            {"id": o.id, "symbols": list(o.symbols), "identity_kept": bool(o.identity_kept),
             "identity_kept_at_end": bool(at_end[o.id].identity_kept if o.id in at_end
                                          else o.identity_kept)}
            for o in ev.objects
        ],
        "revisions": [dict(r) for rec in records for r in rec.revised],
        "beliefs": None if ev.beliefs is None else ev.beliefs.to_json(),
        "id_switches": int(ev.mot.id_switches),
        "idf1": _finite_or_none(ev.mot.idf1),
        "ms_per_frame": ms_per_frame(records),
        "rejected_percepts": int(sum(r.rejected_percepts for r in records)),
        "ambiguous_reacquisitions": int(sum(len(r.ambiguous) for r in records)),
    }
    if ev.hota is not None:
        summary.update(hota_fields(ev.hota))
    for key, value in (extra or {}).items():
        if key in summary:
            raise ValueError(f"extra field {key!r} would replace a summary field")
        summary[key] = value
    return summary


def write_summary(
    path: str | Path,
    records: Sequence[TrackingRecord],
    evaluation: Evaluation | None = None,
    *,
    threshold: float = DEFAULT_THRESHOLD_M,
    extra: Mapping[str, Any] | None = None,
) -> dict[str, Any]:
    """Write ``summary.json`` (creating its folder) and return the dictionary written."""
    summary = make_summary(records, evaluation, threshold=threshold, extra=extra)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(summary, indent=2) + "\n", encoding="utf-8")
    return summary


def read_summary(path: str | Path) -> dict[str, Any]:
    """Read a ``summary.json``, checking it has the summary fields (error names the file)."""
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise ValueError(f"{path}:{exc.lineno}: not JSON: {exc.msg}") from exc
    missing = [f for f in READ_FIELDS if not isinstance(data, dict) or f not in data]
    if missing:
        raise ValueError(f"{path}: not a run summary, missing {', '.join(missing)}")
    return data
