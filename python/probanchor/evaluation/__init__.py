"""Evaluation of a run: tracking records, identity report, py-motmetrics figures, HOTA
(TrackEval), the run summary (``summary.json``), baseline trackers and the results table.

A runner fills one :class:`TrackingRecord` per frame; everything else is computed from a list
of records. See docs/evaluation.md.
"""

from probanchor.evaluation.hota import HOTA_FIELDS, HotaMetrics, hota_metrics
from probanchor.evaluation.metrics import (
    DEFAULT_THRESHOLD_M,
    Evaluation,
    MotMetrics,
    ObjectIdentity,
    evaluate,
    identity_report,
    mot_metrics,
)
from probanchor.evaluation.record import (
    FrameTimings,
    Hypothesis,
    RecordError,
    TrackingRecord,
    TruthObject,
    point_estimate,
    read_records,
    record_for_frame,
    truth_from_dict,
    write_records,
)
from probanchor.evaluation.summary import SUMMARY_FIELDS, make_summary, read_summary, write_summary
from probanchor.evaluation.table import (
    TableRow,
    aggregate,
    format_table,
    print_table,
    results_table,
    rows_from_summaries,
)

__all__ = [
    "DEFAULT_THRESHOLD_M",
    "HOTA_FIELDS",
    "SUMMARY_FIELDS",
    "Evaluation",
    "FrameTimings",
    "HotaMetrics",
    "Hypothesis",
    "MotMetrics",
    "ObjectIdentity",
    "RecordError",
    "TableRow",
    "TrackingRecord",
    "TruthObject",
    "aggregate",
    "evaluate",
    "format_table",
    "hota_metrics",
    "identity_report",
    "make_summary",
    "mot_metrics",
    "point_estimate",
    "print_table",
    "read_records",
    "read_summary",
    "record_for_frame",
    "results_table",
    "rows_from_summaries",
    "truth_from_dict",
    "write_records",
    "write_summary",
]
