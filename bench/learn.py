"""Seconds of the structure learner (``probanchor.ddclearn.learn``) on a synthetic problem and on
Financial.

    .venv/bin/python bench/learn.py                # both parts, about a minute
    .venv/bin/python bench/learn.py --json         # stdout: one JSON object with the figures

(a) 10,000 groundings, 3 candidate features, a logistic leaf: a data file of the learner's own
dialect (numpy, fixed seed) with a Boolean target ``occ(O)``, ``P(true) = sigmoid(0.8 - 16.9 d)``
on a continuous feature ``d(O)`` in [0, 0.3], and two irrelevant features (a discrete
``colour(O)`` with 3 values, a Gaussian ``noise(O)``). It times ``learn`` on the file (the median
of ``--repeat`` runs; loading the file is part of it), and in the same run, as references, the
load alone (``LearningData``) and scikit-learn's ``LogisticRegression`` fitted on the same three
features (one-hot colour, standardised, the learner's L2 penalty 0.01) held in numpy arrays;
it prints the seconds, the ratios, the learned weights against the true ones, and whether
``learn`` is within the 10 s target.

(b) FinancialData.pl (``probanchor.ddclearn.datasets.financial()``, PKDD'99 Financial, DreaML's
input, 13 targets), every target: ``learn`` on 1/4, 1/2 and all of the facts (the subsets are the
test parts of ``bridge.learning.split_files(..., unit="d", fraction=0.25 / 0.5)``: whole districts
with their clients, accounts and loans, written to a temporary folder). For each it prints the
seconds, the groundings (summed over the targets) and the seconds per 1,000 groundings (equal
figures mean the cost grows linearly), and for all of it the ratio to the original DreaML's 543 s
(its deterministic mode, on this kind of machine) and to the target of 60 s.

Wall-clock seconds are reported with the process's CPU seconds beside them: on a shared machine
the wall time includes waiting for a CPU.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

from bridge.learning import LearningData  # noqa: E402
from probanchor.ddclearn import learn, target_key  # noqa: E402
from probanchor.ddclearn.datasets import financial  # noqa: E402

FINANCIAL = financial()
TARGET_LOGISTIC_S = 10.0
TARGET_FINANCIAL_S = 60.0
DREAML_FINANCIAL_S = 543.0
#: The true model of part (a): P(occ = true) = sigmoid(B0 + B1 d).
B0, B1 = 0.8, -16.9
COLOURS = ("red", "green", "blue")


def logistic_data(n: int, seed: int) -> dict[str, np.ndarray]:
    """Part (a)'s groundings: ``d`` in [0, 0.3], ``colour`` index, ``noise``, Boolean ``y``."""
    rng = np.random.default_rng(seed)
    d = rng.uniform(0.0, 0.3, n)
    colour = rng.integers(0, len(COLOURS), n)
    noise = rng.normal(0.0, 1.0, n)
    y = rng.random(n) < 1.0 / (1.0 + np.exp(-(B0 + B1 * d)))
    return {"d": d, "colour": colour, "noise": noise, "y": y}


def write_logistic_data(path: Path, data: dict[str, np.ndarray]) -> Path:
    """Write part (a)'s data file in the learner's own dialect (docs/learning.md)."""
    bias = [
        "type(occ(obj)).", "type(d(obj)).", "type(colour(obj)).", "type(noise(obj)).",
        "rv(occ(_), boolean).",
        "rv(d(_), continuous).",
        f"rv(colour(_), discrete([{', '.join(COLOURS)}])).",
        "rv(noise(_), continuous).",
        "learn(occ(O)).",
        "mode(occ(_), d(+)).", "mode(occ(_), colour(+)).", "mode(occ(_), noise(+)).",
    ]
    names = np.array(COLOURS)[data["colour"]]
    values = np.where(data["y"], "true", "false")
    facts = [
        f"occ(o{i}) ~= {v}. d(o{i}) ~= {d!r}. colour(o{i}) ~= {c}. noise(o{i}) ~= {z!r}."
        for i, (v, d, c, z) in enumerate(
            zip(values, data["d"].tolist(), names, data["noise"].tolist(), strict=True))
    ]
    path.write_text("\n".join(bias + facts) + "\n")
    return path


def timed(f: Callable[[], Any], repeat: int) -> tuple[float, float, Any]:
    """Median wall and CPU seconds of ``repeat`` calls of ``f``, and its last result."""
    wall, cpu, out = [], [], None
    for _ in range(repeat):
        c0, t0 = time.process_time(), time.perf_counter()
        out = f()
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
    return statistics.median(wall), statistics.median(cpu), out


def bench_logistic(n: int, repeat: int, seed: int, folder: Path) -> dict[str, Any]:
    """Part (a): seconds of ``learn``, of the load alone and of sklearn's logistic fit."""
    from sklearn.linear_model import LogisticRegression

    data = logistic_data(n, seed)
    path = write_logistic_data(folder / "logistic.pl", data)
    learn_s, learn_cpu, result = timed(lambda: learn([path], seed=0), repeat)

    def load() -> None:
        LearningData([path]).free()

    load_s, load_cpu, _ = timed(load, repeat)
    X = np.column_stack([data["d"], np.eye(len(COLOURS))[data["colour"]], data["noise"]])

    def fit() -> tuple[np.ndarray, float]:
        # as the learner's leaves: standardised columns, L2 0.01 on the standardised weights
        mean, sd = X.mean(axis=0), X.std(axis=0)
        m = LogisticRegression(C=1 / 0.01, max_iter=1000).fit((X - mean) / sd, data["y"])
        coef = m.coef_[0] / sd
        return coef, float(m.intercept_[0] - coef @ mean)

    fit_s, fit_cpu, (coef, bias) = timed(fit, max(repeat, 5))
    target = result.targets[0]
    leaf = max(target.leaves, key=lambda r: r.weight).leaf
    return {
        "groundings": target.groundings,
        "features": 3,
        "repeat": repeat,
        "learn_s": learn_s, "learn_cpu_s": learn_cpu,
        "load_s": load_s, "load_cpu_s": load_cpu,
        "search_s": target.seconds,
        "sklearn_fit_s": fit_s, "sklearn_fit_cpu_s": fit_cpu,
        "ratio_to_sklearn": learn_s / fit_s,
        "search_ratio_to_sklearn": target.seconds / fit_s,
        "ratio_to_load": learn_s / load_s,
        "clauses": target.clauses,
        "leaf": leaf.family,
        "weights": [float(v) for v in (leaf.weights if leaf.weights is not None else [])],
        # sklearn's P(true) = sigmoid(coef x + b); the learner's logistic is P(first value =
        # true), so its weights are comparable as they are (d's weight, the bias)
        "sklearn_weights": [float(coef[0]), bias],
        "target_s": TARGET_LOGISTIC_S,
        "meets_target": learn_s <= TARGET_LOGISTIC_S,
    }


def bench_financial(folder: Path, repeat: int) -> dict[str, Any]:
    """Part (b): ``learn`` on 1/4, 1/2 and all of Financial, every target."""
    from bridge.learning import split_files

    parts: list[tuple[str, float, list[Path]]] = []
    for fraction, name in ((0.25, "quarter"), (0.5, "half")):
        train, test = folder / f"{name}_rest.pl", folder / f"{name}.pl"
        split_files([FINANCIAL], train, test, fraction=fraction, seed=0, unit="d")
        parts.append((name, fraction, [test]))
    parts.append(("all", 1.0, [FINANCIAL]))
    rows = []
    for name, fraction, files in parts:
        wall, cpu, result = timed(lambda files=files: learn(files, seed=0), repeat)
        groundings = sum(t.groundings for t in result.targets)
        slowest = max(result.targets, key=lambda t: t.seconds)
        rows.append({"part": name, "fraction": fraction, "targets": len(result.targets),
                     "groundings": groundings, "seconds": wall, "cpu_seconds": cpu,
                     "s_per_1000_groundings": 1000 * wall / groundings,
                     "search_seconds": {target_key(t.name): t.seconds for t in result.targets},
                     "slowest": f"{target_key(slowest.name)} {slowest.seconds:.2f} s",
                     "file_bytes": sum(Path(f).stat().st_size for f in files)})
    full = rows[-1]["seconds"]
    return {"parts": rows, "repeat": repeat, "dreaml_s": DREAML_FINANCIAL_S,
            "ratio_to_dreaml": full / DREAML_FINANCIAL_S, "speed_up_over_dreaml":
            DREAML_FINANCIAL_S / full, "target_s": TARGET_FINANCIAL_S,
            "ratio_to_target": full / TARGET_FINANCIAL_S,
            "meets_target": full <= TARGET_FINANCIAL_S}


def print_logistic(r: dict[str, Any], out: Any) -> None:
    w = ", ".join(f"{v:.3g}" for v in r["weights"])
    sw = ", ".join(f"{v:.3g}" for v in r["sklearn_weights"])
    print(f"(a) {r['groundings']} groundings, {r['features']} candidate features, logistic "
          f"leaf (median of {r['repeat']} runs)", file=out)
    print(f"  learn:   {r['learn_s']:.2f} s wall ({r['learn_cpu_s']:.2f} s CPU); the tree search "
          f"alone {r['search_s']:.2f} s; {r['clauses']} clauses, largest leaf {r['leaf']} "
          f"[{w}] (true [{B1:g}, {B0:g}], sklearn [{sw}])", file=out)
    print(f"  reference, same run: load alone {r['load_s']:.2f} s, sklearn LogisticRegression "
          f"fit {1000 * r['sklearn_fit_s']:.1f} ms", file=out)
    print(f"  ratios: learn / load {r['ratio_to_load']:.2f}, learn / sklearn fit "
          f"{r['ratio_to_sklearn']:.0f}, search / sklearn fit "
          f"{r['search_ratio_to_sklearn']:.0f}", file=out)
    verdict = "within" if r["meets_target"] else "NOT within"
    print(f"  {r['learn_s']:.2f} s is {verdict} the {r['target_s']:g} s target on this "
          f"machine (ratio {r['learn_s'] / r['target_s']:.2f})", file=out)


def print_financial(r: dict[str, Any], out: Any) -> None:
    print(f"(b) FinancialData.pl, every target, by district (runs per part: {r['repeat']})",
          file=out)
    print(f"  {'part':<8} {'targets':>7} {'groundings':>10} {'seconds':>8} {'CPU s':>7} "
          f"{'s / 1000 groundings':>20}  slowest tree search", file=out)
    for p in r["parts"]:
        print(f"  {p['part']:<8} {p['targets']:>7} {p['groundings']:>10} {p['seconds']:>8.2f} "
              f"{p['cpu_seconds']:>7.2f} {p['s_per_1000_groundings']:>20.3f}  {p['slowest']}",
              file=out)
    full = r["parts"][-1]["seconds"]
    verdict = "meets" if r["meets_target"] else "misses"
    print(f"  all of it: {full:.1f} s, ratio to DreaML's {r['dreaml_s']:g} s "
          f"{r['ratio_to_dreaml']:.3f} ({r['speed_up_over_dreaml']:.0f}x faster); ratio to "
          f"the {r['target_s']:g} s target {r['ratio_to_target']:.2f} ({verdict} it)", file=out)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--groundings", type=int, default=10_000, help="part (a)'s groundings")
    parser.add_argument("--repeat", type=int, default=3, help="runs of part (a) (median)")
    parser.add_argument("--financial-repeat", type=int, default=1,
                        help="runs of each part of (b) (median)")
    parser.add_argument("--seed", type=int, default=0, help="part (a)'s data")
    parser.add_argument("--skip-financial", action="store_true", help="part (a) only")
    parser.add_argument("--json", action="store_true",
                        help="print one JSON object with the figures (the text goes to stderr)")
    args = parser.parse_args(argv)
    out = sys.stderr if args.json else sys.stdout
    load = os.getloadavg()[0]
    print(f"load average {load:.1f} on {os.cpu_count()} cores", file=out)
    figures: dict[str, Any] = {"load_average": load, "cores": os.cpu_count()}
    with tempfile.TemporaryDirectory(prefix="bench_learn_") as tmp:
        folder = Path(tmp)
        figures["logistic"] = bench_logistic(args.groundings, args.repeat, args.seed, folder)
        print_logistic(figures["logistic"], out)
        if not args.skip_financial:
            figures["financial"] = bench_financial(folder, args.financial_repeat)
            print_financial(figures["financial"], out)
    if args.json:
        print(json.dumps(figures))
    return 0


if __name__ == "__main__":
    sys.exit(main())
