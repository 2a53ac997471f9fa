"""Tuning the Stone Soup baselines: a small grid of settings scored on percept streams that the
evaluation does not use.

Every combination of :data:`GRID` (scikit-learn's ``ParameterGrid``: process noise,
measurement noise, gate probability; the other settings keep
:class:`~probanchor.evaluation.stonesoup_trackers.StoneSoupSettings`' defaults) runs on every
stream; a setting's score is the fraction of the streams' objects whose identity was kept (the
evaluation's headline), ties broken by the mean HOTA. ``anchoring baselines --tune`` runs it on
generated shell games whose seeds (1000 on by default) the evaluation's games (0 to 49) do not
use, and prints the ranking; the best settings go into ``stonesoup_trackers.TUNED``
(docs/evaluation.md says what was run and found). The grid is small because Stone Soup is slow
(its JPDA takes about 0.1 s per frame of a five-container game, MFA twice that): values around
those that did best in a first look at two streams of the evaluation's own (too small a process
noise loses a container at every turn of a swap; too small a measurement noise, the box, whose
percepts are noisier).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import Any

#: The grid searched for each tracker.
GRID: dict[str, list[float]] = {
    "process_noise": [0.1, 1.0],
    "measurement_noise": [0.01, 0.03],
    "prob_gate": [0.99, 0.9999],
}


@dataclass
class Score:
    """One setting of one tracker over the tuning streams."""

    method: str
    settings: dict[str, float]
    objects: int
    kept: int
    hota: float
    idf1: float

    @property
    def kept_fraction(self) -> float:
        return self.kept / self.objects if self.objects else 0.0

    def key(self) -> tuple[float, float]:
        """What is maximised: identity kept, then HOTA."""
        return self.kept_fraction, self.hota


def score_stream(method: str, settings: dict[str, float], stream: str,
                 lost_seconds: float = 60.0) -> dict[str, Any]:
    """One tracker with ``settings`` on one percept stream: objects, kept, HOTA, IDF1 (a job)."""
    import math

    from probanchor.evaluation.metrics import evaluate
    from probanchor.evaluation.stonesoup_trackers import StoneSoupSettings, run_stonesoup
    from probanchor.percepts import read_percepts

    records = run_stonesoup(method, read_percepts(stream), lost_seconds=lost_seconds,
                            settings=StoneSoupSettings().replace(**settings))
    ev = evaluate(records)
    assert ev.mot is not None and ev.hota is not None

    def finite(x: float) -> float:
        return x if math.isfinite(x) else 0.0

    return {"objects": len(ev.objects), "kept": ev.objects_kept,
            "hota": finite(ev.hota.hota), "idf1": finite(ev.mot.idf1)}


def tune(methods: Sequence[str], streams: Sequence[Path], *, jobs: int = 1,
         grid: dict[str, list[float]] | None = None, lost_seconds: float = 60.0,
         progress: bool = False, log: Path | None = None) -> dict[str, list[Score]]:
    """Score every setting of ``grid`` for each method on ``streams``.

    Parameters
    ----------
    methods : sequence of str
        Stone Soup trackers (``stonesoup_trackers.STONESOUP``).
    streams : sequence of Path
        Percept streams with ground truth.
    jobs : int
        Worker processes (:mod:`probanchor.jobs`).
    grid : dict, optional
        Setting name -> values (default :data:`GRID`).
    lost_seconds : float
        The trackers' patience, as in the evaluation.
    progress : bool
        Show progress (on standard error).
    log : Path, optional
        A JSON Lines file that gets each run's result the moment it finishes; runs already in
        it (the same method, settings, stream and patience) are not run again, so an
        interrupted search goes on where it stopped.

    Returns
    -------
    dict
        Method -> its scores, best first.

    Raises
    ------
    jobs.JobsFailed
        A run failed (named with its cause).
    """
    from sklearn.model_selection import ParameterGrid

    from probanchor.jobs import Job, parse_cluster, raise_failures, run_jobs

    settings = [dict(p) for p in ParameterGrid(grid or GRID)]
    wanted = [(m, p, str(s), lost_seconds) for m in methods for p in settings for s in streams]
    done = {_key(*args): value for args, value in _read_log(log)}
    work = [Job(f"{m} {settings.index(p)} {Path(s).stem}", score_stream, (m, p, s, patience))
            for m, p, s, patience in wanted if _key(m, p, s, patience) not in done]
    outcomes = []
    with open(log, "a", encoding="utf-8") if log is not None else nullcontext() as out:
        for outcome in run_jobs(work, parse_cluster(None, jobs), desc="tune", bar=progress):
            outcomes.append(outcome)
            if outcome.ok:
                done[_key(*outcome.job.args)] = outcome.value
                if out is not None:
                    out.write(json.dumps({"args": list(outcome.job.args),
                                          "value": outcome.value}) + "\n")
                    out.flush()
    raise_failures(outcomes, f"the finished are in {log}" if log is not None else "")
    totals: dict[tuple[str, int], list[dict[str, Any]]] = {}
    for args in wanted:
        method, index = args[0], settings.index(args[1])
        totals.setdefault((method, index), []).append(done[_key(*args)])
    ranking: dict[str, list[Score]] = {}
    for (method, index), runs in totals.items():
        ranking.setdefault(method, []).append(Score(
            method, dict(settings[index]), sum(r["objects"] for r in runs),
            sum(r["kept"] for r in runs), sum(r["hota"] for r in runs) / len(runs),
            sum(r["idf1"] for r in runs) / len(runs)))
    for scores in ranking.values():
        scores.sort(key=Score.key, reverse=True)
    return {m: ranking[m] for m in methods if m in ranking}


def _key(method: str, settings: dict[str, float], stream: str, lost_seconds: float) -> str:
    return json.dumps([method, sorted(settings.items()), str(stream), lost_seconds])


def _read_log(log: Path | None) -> list[tuple[list[Any], dict[str, Any]]]:
    if log is None or not log.exists():
        return []
    with open(log, encoding="utf-8") as lines:
        rows = [json.loads(line) for line in lines if line.strip()]
    return [(row["args"], row["value"]) for row in rows]


def format_ranking(ranking: dict[str, list[Score]], top: int = 5) -> str:
    """Markdown: the ``top`` settings of each method, best first."""
    names = list(GRID)
    lines = ["| method | " + " | ".join(names) + " | identity kept (objects) | HOTA | IDF1 |",
             "|---|" + "---:|" * (len(names) + 3)]
    for method, scores in ranking.items():
        for s in scores[:top]:
            cells = " | ".join(f"{s.settings.get(n, '-'):g}" for n in names)
            lines.append(f"| {method} | {cells} | {s.kept}/{s.objects} "
                         f"({100 * s.kept_fraction:.0f} %) | {s.hota:.3f} | {s.idf1:.3f} |")
    return "\n".join(lines) + "\n"
