"""The results table: runs grouped by (scenario, method), as Markdown.

Each input row is ``(scenario, method, run)`` where ``run`` is one run's list of
:class:`~probanchor.evaluation.record.TrackingRecord`, its
:class:`~probanchor.evaluation.metrics.Evaluation`, its summary dictionary
(:func:`~probanchor.evaluation.summary.make_summary`) or the path of its ``summary.json``. Runs with
the same scenario and method (e.g. 20 seeds, or 50 generated games under one scenario name) make one
line of the table:

- identity kept, objects: objects that kept their identity / objects, over all the runs;
- identity kept, runs: runs in which every object kept its identity in every frame's answer /
  runs;
- at the end, runs: runs in which every object has its own symbol in the answers as revised by
  the end of the run (``identity_kept_at_end``) / runs;
- ID switches: mean per run (motmetrics);
- IDF1: mean over the runs that define it;
- HOTA, DetA, AssA, LocA: means over the runs that define them (``summary.json``'s ``hota``,
  ``deta``, ``assa``, ``loca``; ``-`` for runs summarised before they existed);
- ambiguous: runs that reported at least one ambiguous re-acquisition (``summary.json``'s
  ``ambiguous_reacquisitions``: a hidden object seen again that nothing observed tells from a
  look-alike's) / runs;
- belief within 10 cm: over all the runs' frames in which an object is hidden, the fraction in
  which its anchor's point estimate is within the threshold of it; P(true occluder): the mean
  probability the belief gave to the object that truly hides it
  (:mod:`probanchor.evaluation.beliefs`; "-" when not known, e.g. trackers).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TextIO

from probanchor.evaluation.hota import HOTA_FIELDS, hota_fields
from probanchor.evaluation.metrics import DEFAULT_THRESHOLD_M, Evaluation
from probanchor.evaluation.record import TrackingRecord
from probanchor.evaluation.summary import make_summary, read_summary

Run = Sequence[TrackingRecord] | Evaluation | dict[str, Any] | str | Path


@dataclass
class TableRow:
    scenario: str
    method: str
    runs: int
    runs_kept: int
    objects: int
    objects_kept: int
    id_switches_mean: float
    idf1_mean: float | None
    runs_ambiguous: int = 0
    runs_kept_at_end: int = 0
    belief_within: float | None = None
    true_occluder: float | None = None
    hota: dict[str, float | None] | None = None  # HOTA_FIELDS -> mean over the runs (_hota_means)


def _as_summary(run: Run, threshold: float) -> dict[str, Any]:
    if isinstance(run, (str, Path)):
        return read_summary(run)
    if isinstance(run, dict):
        return run
    if isinstance(run, Evaluation):
        assert run.mot is not None
        at_end = {o.id: o.identity_kept for o in run.objects_at_end}
        return {
            "objects": [{"id": o.id, "identity_kept": o.identity_kept,
                         "identity_kept_at_end": at_end.get(o.id, o.identity_kept)}
                        for o in run.objects],
            "beliefs": None if run.beliefs is None else run.beliefs.to_json(),
            "id_switches": run.mot.id_switches,
            "idf1": run.mot.idf1,
            "ambiguous_reacquisitions": 0,
            **(hota_fields(run.hota) if run.hota is not None else {}),
        }
    return make_summary(list(run), threshold=threshold)


def _mean_defined(values: Sequence[Any]) -> float | None:
    finite = [float(v) for v in values if v is not None and math.isfinite(float(v))]
    return sum(finite) / len(finite) if finite else None


def _hota_means(summaries: Sequence[dict[str, Any]]) -> dict[str, float | None]:
    """HOTA, DetA, AssA, LocA: each the mean over the runs that define it."""
    return {k: _mean_defined([s.get(k) for s in summaries]) for k in HOTA_FIELDS}


def aggregate(
    rows: Sequence[tuple[str, str, Run]], threshold: float = DEFAULT_THRESHOLD_M
) -> list[TableRow]:
    """Group runs by (scenario, method), in order of first appearance, and count."""
    groups: dict[tuple[str, str], list[dict[str, Any]]] = {}
    for scenario, method, run in rows:
        groups.setdefault((scenario, method), []).append(_as_summary(run, threshold))
    table = []
    for (scenario, method), summaries in groups.items():
        objects = sum(len(s["objects"]) for s in summaries)
        kept = sum(bool(o["identity_kept"]) for s in summaries for o in s["objects"])
        runs_kept = sum(
            bool(s["objects"]) and all(o["identity_kept"] for o in s["objects"])
            for s in summaries
        )
        runs_kept_at_end = sum(
            bool(s["objects"]) and all(o.get("identity_kept_at_end", o["identity_kept"])
                                       for o in s["objects"])
            for s in summaries
        )
        within, occluder = _belief_means(summaries)
        idf1s = [
            float(s["idf1"])
            for s in summaries
            if s.get("idf1") is not None and math.isfinite(float(s["idf1"]))
        ]
        table.append(
            TableRow(
                scenario=scenario,
                method=method,
                runs=len(summaries),
                runs_kept=runs_kept,
                objects=objects,
                objects_kept=kept,
                id_switches_mean=sum(int(s["id_switches"]) for s in summaries) / len(summaries),
                idf1_mean=sum(idf1s) / len(idf1s) if idf1s else None,
                runs_ambiguous=sum(int(s.get("ambiguous_reacquisitions", 0)) > 0
                                   for s in summaries),
                runs_kept_at_end=runs_kept_at_end,
                belief_within=within,
                true_occluder=occluder,
                hota=_hota_means(summaries),
            )
        )
    return table


def _belief_means(summaries: Sequence[dict[str, Any]]) -> tuple[float | None, float | None]:
    """Pooled over the runs' hidden frames: the fraction within the threshold, the mean
    probability of the true occluder (None where no run says)."""
    hidden = within = 0.0
    frames = mass = 0.0
    any_occluder = False
    for s in summaries:
        b = s.get("beliefs") or {}
        if b.get("within") is not None and b.get("hidden_frames"):
            hidden += b["hidden_frames"]
            within += b["within"] * b["hidden_frames"]
        if b.get("true_occluder_probability") is not None and b.get("occluder_frames"):
            any_occluder = True
            frames += b["occluder_frames"]
            mass += b["true_occluder_probability"] * b["occluder_frames"]
    return (within / hidden if hidden else None,
            mass / frames if any_occluder and frames else None)


def _fraction(k: int, n: int) -> str:
    return f"{k}/{n} ({100.0 * k / n:.0f} %)" if n else "-"


def _number(x: float | None) -> str:
    return "-" if x is None else f"{x:.3f}"


def _hota_header() -> tuple[str, str]:
    return " HOTA | DetA | AssA | LocA |", "---:|---:|---:|---:|"


def _hota_cells(row: TableRow) -> str:
    means = row.hota or {}
    return "".join(f" {_number(means.get(k))} |" for k in HOTA_FIELDS)


def format_table(table: Sequence[TableRow]) -> str:
    """Markdown for rows made by :func:`aggregate`."""
    hota_names, hota_rule = _hota_header()
    lines = [
        "| scenario | method | runs | identity kept (objects) | identity kept (runs) "
        "| at the end (runs) | ID switches per run | IDF1 |" + hota_names
        + " ambiguous (runs) | belief within 10 cm | P(true occluder) |",
        "|---|---|---:|---:|---:|---:|---:|---:|" + hota_rule + "---:|---:|---:|",
    ]
    for r in table:
        within = "-" if r.belief_within is None else f"{100 * r.belief_within:.0f} %"
        occluder = "-" if r.true_occluder is None else f"{r.true_occluder:.2f}"
        lines.append(
            f"| {r.scenario} | {r.method} | {r.runs} | {_fraction(r.objects_kept, r.objects)} "
            f"| {_fraction(r.runs_kept, r.runs)} | {_fraction(r.runs_kept_at_end, r.runs)} "
            f"| {r.id_switches_mean:.2f} | {_number(r.idf1_mean)} |" + _hota_cells(r)
            + f" {r.runs_ambiguous}/{r.runs} | {within} | {occluder} |"
        )
    return "\n".join(lines) + "\n"


def results_table(
    rows: Sequence[tuple[str, str, Run]], threshold: float = DEFAULT_THRESHOLD_M
) -> str:
    """The Markdown results table of ``(scenario, method, run)`` rows."""
    return format_table(aggregate(rows, threshold))


def print_table(
    rows: Sequence[tuple[str, str, Run]],
    threshold: float = DEFAULT_THRESHOLD_M,
    file: TextIO | None = None,
) -> None:
    print(results_table(rows, threshold), end="", file=file or sys.stdout)


def rows_from_summaries(paths: Sequence[str | Path]) -> list[tuple[str, str, dict[str, Any]]]:
    """``(scenario, method, summary)`` rows from ``summary.json`` files. Scenario and method
    come from the summary's own ``scenario`` and ``method`` fields when it has them (a runner
    can add them through ``make_summary(..., extra=...)``), else from the folders, as laid out
    by ``anchoring baselines --out DIR``: ``DIR/<scenario>/<method>/summary.json``."""
    rows = []
    for p in paths:
        path = Path(p)
        summary = read_summary(path)
        scenario = str(summary.get("scenario") or path.parent.parent.name or "-")
        method = str(summary.get("method") or path.parent.name or "-")
        rows.append((scenario, method, summary))
    return rows


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m probanchor.evaluation SUMMARY.json...``: the results table of saved runs."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m probanchor.evaluation",
                                     description=main.__doc__)
    parser.add_argument("summaries", nargs="+", type=Path, metavar="SUMMARY.json")
    args = parser.parse_args(argv)
    try:
        print_table(rows_from_summaries(args.summaries))
    except (OSError, ValueError) as exc:
        print(f"python -m probanchor.evaluation: error: {exc}", file=sys.stderr)
        return 1
    return 0
