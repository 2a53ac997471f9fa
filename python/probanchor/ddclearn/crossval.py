"""K-fold cross-validation of the structure learner, one fold per job (``ddc cross-validate``).

The data are split into K folds of separate worlds (``bridge.learning.fold_files``: the units of
``ddc split``, dealt out to the folds); fold ``i``'s job learns a program on the other folds
(:func:`probanchor.ddclearn.learn`) and scores it on fold ``i``
(:func:`probanchor.ddclearn.evaluate`). The jobs run through :mod:`probanchor.jobs` (local processes
or Ray); each job's arguments fix its files and seed, so the result is the same whichever back end
ran it.

    >>> result = cross_validate(["data.pl"], folds=5, out="out/cv")    # doctest: +SKIP
    >>> result.summary()["occluder:t+1"]["mean_log_likelihood"]         # doctest: +SKIP
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from bridge.learning import fold_files
from probanchor.ddclearn.files import write_atomically
from probanchor.ddclearn.learner import Form, evaluate, learn
from probanchor.ddclearn.search import SearchOptions
from probanchor.jobs import Cluster, Job, parse_cluster, raise_failures, run_jobs

__all__ = ["CrossValidation", "FoldResult", "cross_validate", "learn_fold"]

#: The summary written beside the folds.
SUMMARY_NAME = "cross-validation.json"


@dataclass
class FoldResult:
    """One fold: its split counts, the training report and the held-out scores.

    Parameters
    ----------
    fold : int
        1-based.
    split : dict
        ``train``, ``test``, ``cut``, ``both``, ``units``, ``test_units`` (``ddc split``'s
        counts for this fold).
    training : dict
        ``LearnResult.report()`` of the program learned on the other folds.
    scores : dict
        ``probanchor.ddclearn.evaluate`` of that program on this fold, keyed by target.
    program : str
        The learned program's file.
    """

    fold: int
    split: dict[str, int]
    training: dict[str, dict[str, Any]]
    scores: dict[str, dict[str, Any]]
    program: str


@dataclass
class CrossValidation:
    """The folds' results, in fold order, and where they are."""

    folds: list[FoldResult]
    out: Path
    seed: int
    unit: str | None = None
    cluster: str = ""
    warnings: list[str] = field(default_factory=list)

    def summary(self) -> dict[str, dict[str, Any]]:
        """Per target, over the folds: the held-out scores pooled and averaged.

        Returns
        -------
        dict
            Keyed by target: ``n`` (test groundings, all folds), ``mean_log_likelihood`` (the
            folds' log-likelihoods summed over their summed weights), ``fold_mean`` and
            ``fold_std`` (mean and standard deviation over the folds of their mean
            log-likelihood), ``uncovered`` (summed), ``accuracy`` (weighted by the folds'
            weights) or ``rmse`` (root of the weighted mean squared error), and ``folds`` (per
            fold its mean log-likelihood).
        """
        keys = sorted({k for f in self.folds for k in f.scores})
        out: dict[str, dict[str, Any]] = {}
        for key in keys:
            rows = [f.scores[key] for f in self.folds if key in f.scores]
            weight = sum(r["weight"] for r in rows)
            per_fold = [r["mean_log_likelihood"] for r in rows]
            mean = sum(per_fold) / len(per_fold)
            entry: dict[str, Any] = {
                "n": sum(r["n"] for r in rows),
                "mean_log_likelihood": (sum(r["log_likelihood"] for r in rows) / weight
                                        if weight > 0 else math.nan),
                "fold_mean": mean,
                "fold_std": (math.sqrt(sum((x - mean) ** 2 for x in per_fold)
                                       / (len(per_fold) - 1)) if len(per_fold) > 1 else 0.0),
                "uncovered": sum(r["uncovered"] for r in rows),
                "folds": per_fold,
            }
            if weight > 0 and all("accuracy" in r for r in rows):
                entry["accuracy"] = sum(r["accuracy"] * r["weight"] for r in rows) / weight
            if weight > 0 and all("rmse" in r for r in rows):
                entry["rmse"] = math.sqrt(sum(r["rmse"] ** 2 * r["weight"] for r in rows)
                                          / weight)
            out[key] = entry
        return out

    def to_json(self) -> dict[str, Any]:
        """Everything, as one JSON-able object (non-finite numbers as None)."""
        return _finite({"folds": len(self.folds), "seed": self.seed, "unit": self.unit,
                        "cluster": self.cluster, "summary": self.summary(),
                        "per_fold": [vars(f) for f in self.folds]})


def _finite(value: Any) -> Any:
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value


def learn_fold(train: str, test: str, program: str, targets: list[str] | None,
               seed: int, options: SearchOptions, samples: int,
               form: Form) -> dict[str, Any]:
    """One fold's job: learn on ``train``, write ``program``, score it on ``test``.

    Parameters
    ----------
    train, test : str
        The fold's training and test files.
    program : str
        Where the learned program is written.
    targets : list of str or None
        The targets (None: every declared one).
    seed : int
        The learner's seed (samples of continuous uncertain facts).
    options : SearchOptions
        The search's settings.
    samples : int
        Samples per continuous uncertain fact.
    form : "clauses" or "tree"
        The program's form.

    Returns
    -------
    dict
        ``training`` (the learner's report), ``scores`` (``evaluate``'s) and ``warnings``.
    """
    result = learn([train], targets, seed=seed, options=options, samples=samples)
    result.write(program, form=form)
    return {"training": result.report(), "scores": evaluate(program, [test], targets),
            "warnings": list(result.warnings)}


def cross_validate(
    files: Sequence[str | Path],
    folds: int,
    out: str | Path,
    *,
    targets: Sequence[str] | None = None,
    seed: int = 0,
    unit: str | None = None,
    options: SearchOptions | None = None,
    samples: int = 20,
    form: Form = "clauses",
    cluster: Cluster | None = None,
    progress: bool = False,
) -> CrossValidation:
    """K-fold cross-validation: learn on K-1 folds, score the held-out one, one job per fold.

    Writes ``OUT/fold-I/train.pl``, ``test.pl`` and ``learned.pl`` per fold and, once every
    fold finished, ``OUT/cross-validation.json`` (:meth:`CrossValidation.to_json`).

    Parameters
    ----------
    files : sequence of path
        The data files (facts, background, bias; one dialect).
    folds : int
        K, at least 2 and at most the number of units.
    out : path
        The output folder (made if missing). On a cluster of several machines, a path every
        node sees (a shared file system).
    targets : sequence of str, optional
        The targets (default: every declared one).
    seed : int, default=0
        Seeds the folds' order of units and the learner.
    unit : str, optional
        Split by the constants of this argument type (``ddc split --unit``).
    options : SearchOptions, optional
        The search's settings.
    samples : int, default=20
        Samples per continuous uncertain fact.
    form : "clauses" or "tree"
        The learned programs' form.
    cluster : Cluster, optional
        Where the folds run (default: one after the other in this process).
    progress : bool, default=False
        Draw one progress bar over the folds.

    Returns
    -------
    CrossValidation

    Raises
    ------
    ValueError
        Fewer than 2 folds.
    DDCError
        Bad data, or fewer units than folds (naming the file).
    jobs.JobsFailed
        Some folds failed (each named with its cause); the finished folds' programs stay in
        their folders and no summary is written.
    """
    if isinstance(folds, bool) or not isinstance(folds, int) or folds < 2:
        raise ValueError(f"--folds {folds!r}: cross-validation needs at least 2 folds")
    cluster = cluster or parse_cluster(None, 1)
    root = Path(out).resolve()
    dirs = [root / f"fold-{i}" for i in range(1, folds + 1)]
    for d in dirs:
        d.mkdir(parents=True, exist_ok=True)
    splits = fold_files(files, [(d / "train.pl", d / "test.pl") for d in dirs], seed=seed,
                        unit=unit)
    options = options or SearchOptions()
    wanted = list(targets) if targets else None
    work = [Job(f"fold {i}", learn_fold,
                (str(d / "train.pl"), str(d / "test.pl"), str(d / "learned.pl"), wanted, seed,
                 options, samples, form))
            for i, d in enumerate(dirs, start=1)]
    outcomes = {o.job.name: o for o in run_jobs(work, cluster, desc="cross-validate",
                                                 bar=progress)}
    ordered = [outcomes[j.name] for j in work]
    raise_failures(ordered, f"the finished folds' programs are in {root}/fold-*/learned.pl")
    results = [FoldResult(fold=i, split=s, training=o.value["training"],
                          scores=o.value["scores"], program=str(d / "learned.pl"))
               for i, (s, o, d) in enumerate(zip(splits, ordered, dirs, strict=True), start=1)]
    warnings = sorted({w.strip() for o in ordered for w in o.value["warnings"]})
    cv = CrossValidation(results, root, seed, unit, cluster.describe(), warnings)
    write_atomically(root / SUMMARY_NAME, json.dumps(cv.to_json(), indent=1) + "\n")
    return cv
