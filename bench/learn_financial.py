"""Held-out quality of the learned program on Financial, against propositional baselines.

    .venv/bin/python bench/learn_financial.py [--out TABLE.md] [--fraction 0.2] [--seed 0] [--json]

FinancialData.pl (PKDD'99 Financial, DreaML's input, 13 targets;
``probanchor.ddclearn.datasets.financial()``) is split by district
(``bridge.learning.split_files(..., unit="d")``: a district goes to the test part with its clients,
accounts and loans; ``--fraction`` of the facts, 0.2 by default). Every target is learned on the
training part (``probanchor.ddclearn.learn``) and the learned program is scored on the test part
(``probanchor.ddclearn.evaluate``: exact held-out log-likelihood per grounding, accuracy or RMSE).
On the same split, ``probanchor.ddclearn.baselines`` fits per target three propositional models on
the training part's feature table (the root candidates the tree search sees: each aggregate,
attribute and count as columns) and scores them on the test part's:

- ``constant``: class frequencies with add-one smoothing, or a Gaussian with the mean and
  variance (what knowing none of the features gives);
- ``linear``: logistic regression (multinomial for more than 2 classes), or linear regression
  with the Gaussian residual variance;
- ``boosting``: histogram gradient boosting (scikit-learn's defaults), with the Gaussian residual
  variance of its training fit for a continuous target.

It prints a Markdown table: per target its kind, test groundings, the learned program's clauses,
then the mean log-likelihood (nats per grounding, higher is better) and accuracy or RMSE of the
learned program and of each baseline; the best mean log-likelihood of a row is in bold. With
``--out`` the table is written to a file as well (Markdown, with the command that made it).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

from bridge.learning import LearningData, split_files  # noqa: E402
from probanchor.ddclearn import evaluate, learn, target_key  # noqa: E402
from probanchor.ddclearn.baselines import (  # noqa: E402
    BASELINES,
    feature_table,
    fit_baselines,
    score,
)
from probanchor.ddclearn.datasets import financial  # noqa: E402
from probanchor.ddclearn.search import SearchOptions  # noqa: E402

FINANCIAL = financial()
MODELS: tuple[str, ...] = ("learned", *BASELINES)
TITLES: dict[str, str] = {"learned": "learned", "constant": "constant",
                          "linear": "linear/logistic", "boosting": "gradient boosting"}


def compare(train: Sequence[str | Path], test: Sequence[str | Path], folder: str | Path,
            targets: Sequence[str] | None = None, seed: int = 0,
            options: SearchOptions | None = None) -> list[dict[str, Any]]:
    """Learn on ``train``, score the program and the baselines on ``test``, per target.

    Parameters
    ----------
    train, test : sequence of path
        The training and test data files.
    folder : path
        Where the learned program is written (``learned.pl``).
    targets : sequence of str, optional
        The targets (default: every target of the data).
    seed : int, default=0
        The learner's seed.
    options : SearchOptions, optional
        The learner's settings (default: its defaults).

    Returns
    -------
    list of dict
        One per target: ``target`` (short name), ``predicate``, ``kind``, ``clauses``,
        ``train_groundings``, ``test_groundings``, ``uncovered``, ``seconds`` (the tree
        search), and for each model of ``MODELS`` its scores (``n``, ``mean_log_likelihood``,
        ``accuracy`` or ``rmse``; the baselines' also ``log_likelihood_sd``, the weighted
        standard deviation of their per-grounding log-likelihood).
    """
    result = learn(list(train), targets, seed=seed, options=options)
    program = result.write(Path(folder) / "learned.pl")
    held = evaluate(program, list(test), [target_key(t.name) for t in result.targets],
                    examples=True)
    rows: list[dict[str, Any]] = []
    with LearningData(list(train)) as tr_data, LearningData(list(test)) as te_data:
        for t in result.targets:
            key = target_key(t.name)
            learned = held.get(key, {"n": 0, "mean_log_likelihood": math.nan, "uncovered": 0})
            tr = feature_table(tr_data, t.predicate)
            te = feature_table(te_data, t.predicate, columns=tr.names)
            row: dict[str, Any] = {
                "target": key, "predicate": t.predicate, "kind": t.kind,
                "clauses": t.clauses, "train_groundings": t.groundings,
                "test_groundings": int(learned["n"]), "uncovered": int(learned["uncovered"]),
                "seconds": t.seconds, "features": len(tr.names), "learned": learned,
            }
            per_row = {}
            for b in fit_baselines(tr):
                row[b.name] = score(b, te)
                per_row[b.name] = b.log_likelihood(te.X, _classes(b, te))
            row.update(_paired(learned, row, per_row))
            row["root_model"] = t.root_model is not None
            learned.pop("example_weight", None)
            learned.pop("example_log_likelihood", None)
            rows.append(row)
    return rows


def _classes(b: Any, te: Any) -> Any:
    """The test table's values as the baseline's class indices (discrete) or as they are."""
    if b.kind == "discrete" and te.domain and te.domain != b.domain:
        index = {v: i for i, v in enumerate(b.domain)}
        return np.array([index.get(te.domain[k], -1) for k in te.y], dtype=np.int64)
    return te.y


def _paired(learned: dict[str, Any], row: dict[str, Any],
            per_row: dict[str, Any]) -> dict[str, Any]:
    """The learned program's held-out mean log-likelihood minus the best baseline's, and the
    standard error of that difference from the per-grounding differences (paired: the same
    test groundings)."""
    best = best_baseline(row)
    w = np.asarray(learned.get("example_weight", []), dtype=float)
    ll = np.asarray(learned.get("example_log_likelihood", []), dtype=float)
    base = np.asarray(per_row[best], dtype=float)
    if len(ll) != len(base) or len(ll) == 0 or w.sum() <= 0:
        return {"best": best, "gap": math.nan, "gap_se": math.nan}
    d = ll / np.where(w > 0, w, 1.0) - base
    gap = float(w @ d / w.sum())
    sd = math.sqrt(float(w @ (d - gap) ** 2 / w.sum()))
    return {"best": best, "gap": gap, "gap_se": sd / math.sqrt(len(d))}


def best_baseline(row: dict[str, Any]) -> str:
    """The baseline with the highest held-out mean log-likelihood of a row."""
    return max(BASELINES, key=lambda m: row[m]["mean_log_likelihood"])


def markdown(rows: list[dict[str, Any]]) -> str:
    """The comparison as a Markdown table (one row per target)."""
    head = ["target", "kind", "test groundings", "clauses", "root model"]
    for m in MODELS:
        head += [f"{TITLES[m]} LL", f"{TITLES[m]} acc / RMSE"]
    head += ["learned − best baseline (± 2 SE)"]
    lines = ["| " + " | ".join(head) + " |",
             "|" + "|".join(["---", "---"] + ["---:"] * (len(head) - 2)) + "|"]
    for r in rows:
        top = max(r[m]["mean_log_likelihood"] for m in MODELS)
        cells = [r["target"], r["kind"], str(r["test_groundings"]), str(r["clauses"]),
                 "yes" if r.get("root_model") else "no"]
        for m in MODELS:
            s = r[m]
            ll = f"{s['mean_log_likelihood']:.3f}"
            if s["mean_log_likelihood"] == top:
                ll = f"**{ll}**"
            quality = (f"{s['accuracy']:.3f}" if "accuracy" in s
                       else f"{s['rmse']:.4g}" if "rmse" in s else "–")
            cells += [ll, quality]
        cells.append(f"{r['gap']:+.4f} ± {2 * r['gap_se']:.4f}" if math.isfinite(r["gap"])
                     else "–")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def level(row: dict[str, Any], z: float = 2.0) -> bool:
    """Whether the learned program is at or above the best baseline but for the test's noise.

    It is, unless its held-out mean log-likelihood trails the best baseline's by more than ``z``
    standard errors of the paired difference, and by more than one nat over all the test
    groundings (``1 / n`` per grounding: two nearly equal models have a tiny standard error).
    """
    n = max(int(row["test_groundings"]), 1)
    return bool(row["gap"] >= -max(z * row["gap_se"], 1.0 / n))


def summary(rows: list[dict[str, Any]]) -> dict[str, int]:
    """How many targets the learned program is at or above the best baseline on.

    ``above``: its held-out mean log-likelihood is at least the best baseline's; ``level``:
    at or above but for the noise of the test groundings (:func:`level`); ``targets``: all.
    """
    return {
        "targets": len(rows),
        "above": sum(r["gap"] >= 0 for r in rows),
        "level": sum(level(r) for r in rows),
    }


#: The markers of the table's section in a Markdown file (``--out``): the bench replaces what
#: lies between them and leaves the rest of the file as it is.
BEGIN = "<!-- begin: table written by bench/learn_financial.py -->"
END = "<!-- end: table written by bench/learn_financial.py -->"


def write_section(path: Path, text: str) -> None:
    """Put ``text`` between the markers of ``path`` (the whole file if it has none)."""
    old = path.read_text(encoding="utf-8") if path.is_file() else ""
    if BEGIN in old and END in old:
        head, rest = old.split(BEGIN, 1)
        _, tail = rest.split(END, 1)
        path.write_text(f"{head}{BEGIN}\n{text}{END}{tail}", encoding="utf-8")
    else:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data", type=Path, default=FINANCIAL)
    parser.add_argument("--fraction", type=float, default=0.2, help="test share of the facts")
    parser.add_argument("--seed", type=int, default=0, help="the split's and learner's seed")
    parser.add_argument("--target", action="append", help="one target (repeatable)")
    parser.add_argument("--out", type=Path,
                        help="also write the table to this Markdown file (between its markers "
                             "if it has them, e.g. docs/learning.md)")
    parser.add_argument("--json", action="store_true", help="end with one JSON line of figures")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="learn_financial_") as tmp:
        train, test = Path(tmp) / "train.pl", Path(tmp) / "test.pl"
        split = split_files([args.data], train, test, fraction=args.fraction, seed=args.seed,
                            unit="d")
        rows = compare([train], [test], tmp, args.target, seed=args.seed)
    seconds = time.perf_counter() - start
    command = ".venv/bin/python bench/learn_financial.py" + "".join(
        f" {a}" for a in (argv if argv is not None else sys.argv[1:]))
    intro = (f"{args.data.name}, split by district (`split_files(..., unit=\"d\", "
             f"fraction={args.fraction:g}, seed={args.seed})`: {split['test_units']} of "
             f"{split['units']} districts, {split['test']} test facts, {split['train']} "
             f"training facts, {split['cut']} facts across the cut dropped). Held-out mean "
             f"log-likelihood per grounding (LL, nats; higher is better, the best of a row in "
             f"bold) and accuracy or RMSE; the baselines are fitted in the same run on the "
             f"root candidates' features (probanchor.ddclearn.baselines); the last column is "
             f"the learned program's LL minus the best baseline's, with two standard errors of "
             f"that difference over the test groundings (paired).")
    table = markdown(rows)
    counts = summary(rows)
    line = (f"The learned program is at or above the best baseline on {counts['above']} of "
            f"{counts['targets']} targets, and above or behind by less than the test's noise "
            f"(two standard errors of the paired difference, at least one nat in all) on "
            f"{counts['level']}; {seconds:.0f} s in all (learning "
            f"{sum(r['seconds'] for r in rows):.0f} s).")
    print(intro + "\n")
    print(table)
    print(line)
    if args.out:
        write_section(args.out, f"<!-- made by `{command.strip()}` -->\n\n{intro}\n\n{table}"
                                f"\n{line}\n")
        print(f"wrote {args.out}")
    if args.json:
        print(json.dumps({"split": split, "seconds": seconds, "summary": counts,
                          "targets": rows}, default=float))
    return 0


if __name__ == "__main__":
    sys.exit(main())
