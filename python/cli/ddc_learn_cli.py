"""`ddc learn`, `ddc evaluate` and `ddc split`: the structure learner from the shell.

    ddc learn DATA.pl [MORE.pl ...] --out LEARNED.pl [--target NAME]... [--json] [--seed S]
              [--plot TREE.png|TREE.svg] [--min-leaf N] [--max-depth D] [--min-gain G]
              [--smoothing A] [--l2 L] [--no-lookahead] [--form clauses|tree] [--quiet]
    ddc evaluate LEARNED.pl TEST.pl [MORE.pl ...] [--target NAME]... [--json]
    ddc split DATA.pl [MORE.pl ...] --train TRAIN.pl --test TEST.pl [--fraction F] [--seed S]
              [--unit TYPE] [--json]

``ddc learn`` reads background knowledge, training facts and declarative bias from the data
files, learns one distributional logic tree per target and writes the DC program they make
(``--out`` is replaced only once the program is complete and loads in the engine): one clause per
path of a tree (``--form clauses``, the default) or one clause per tree, its body the tree as
nested if-then-else goals (``--form tree``: the same program, faster in the filter). It prints per
target the clauses, groundings, seconds and training log-likelihood (``--json``: one JSON object
keyed by target). ``ddc evaluate`` scores a DC program on held-out facts: per target the number of
test groundings, the mean log-likelihood per grounding (natural log) and the accuracy (discrete)
or RMSE (continuous). ``ddc split`` writes a training and a test file whose test facts form
worlds of their own (docs/learning.md, "Held-out data").
"""

from __future__ import annotations

import argparse
import json
import math
import shlex
import sys
from pathlib import Path
from typing import Any


def add_learn_commands(sub: Any, positive_int: Any) -> None:
    """Add ``learn``, ``evaluate`` and ``split`` to the ``ddc`` sub-command parser."""
    learn = sub.add_parser("learn", help="learn a DC program (one tree per target) from data")
    learn.add_argument("data", nargs="+", help="data files: facts, background, bias")
    learn.add_argument("--out", required=True, type=Path, help="the learned program (.pl)")
    learn.add_argument("--target", action="append", default=[], metavar="NAME",
                       help="a target to learn (repeatable; default: every declared target)")
    learn.add_argument("--json", action="store_true", help="print one JSON object")
    learn.add_argument("--seed", type=int, default=0,
                       help="seed of the samples of continuous uncertain facts (default 0)")
    learn.add_argument("--plot", type=Path, default=None, metavar="TREE.png",
                       help="draw the learned trees (PNG or SVG)")
    learn.add_argument("--min-leaf", type=float, default=10.0,
                       help="smallest weight of a branch with a model of its own (default 10)")
    learn.add_argument("--max-depth", type=int, default=8, help="longest path (default 8)")
    learn.add_argument("--min-gain", type=float, default=0.0,
                       help="a split must raise the BIC by more than this (default 0)")
    learn.add_argument("--smoothing", type=float, default=1.0,
                       help="pseudo-count per value of a discrete head (default 1)")
    learn.add_argument("--l2", type=float, default=0.01,
                       help="L2 penalty on standardised regression weights (default 0.01)")
    learn.add_argument("--no-lookahead", action="store_true",
                       help="score literals that introduce variables by themselves")
    learn.add_argument("--form", choices=["clauses", "tree"], default="clauses",
                       help="one clause per path (default) or per tree (nested if-then-else)")
    learn.add_argument("--quiet", action="store_true", help="no progress bar")
    learn.set_defaults(func=run_learn)

    ev = sub.add_parser("evaluate", help="held-out scores of a DC program on test facts")
    ev.add_argument("program", type=Path, help="the DC program (e.g. from ddc learn)")
    ev.add_argument("data", nargs="+", help="test data: facts in the training data's format")
    ev.add_argument("--target", action="append", default=[], metavar="NAME",
                    help="a target to score (repeatable; default: every one with facts)")
    ev.add_argument("--json", action="store_true", help="print one JSON object")
    ev.set_defaults(func=run_evaluate)

    sp = sub.add_parser("split", help="split data into training and test files of separate worlds")
    sp.add_argument("data", nargs="+", help="data files: facts, background, bias (one dialect)")
    sp.add_argument("--train", required=True, type=Path, help="the training part (.pl)")
    sp.add_argument("--test", required=True, type=Path, help="the test part (.pl)")
    sp.add_argument("--fraction", type=float, default=0.2,
                    help="the test part's share of the facts, 0 < F < 1 (default 0.2)")
    sp.add_argument("--seed", type=int, default=0, help="seed of the units' order (default 0)")
    sp.add_argument("--unit", default=None, metavar="TYPE",
                    help="split by the constants of this argument type (every other constant "
                         "follows the nearest one); default: by connected worlds")
    sp.add_argument("--json", action="store_true", help="print one JSON object")
    sp.set_defaults(func=run_split)


def run_learn(args: argparse.Namespace) -> int:
    from cli.ddc_cli import CliError
    from ddclearn import LeafOptions, SearchOptions, learn

    if args.plot is not None and args.plot.suffix.lower() not in (".png", ".svg"):
        raise CliError(f"--plot {args.plot}: the picture must be .png or .svg")
    try:
        options = SearchOptions(min_leaf=args.min_leaf, max_depth=args.max_depth,
                                min_gain=args.min_gain, lookahead=not args.no_lookahead,
                                leaf=LeafOptions(smoothing=args.smoothing, l2=args.l2))
    except ValueError as exc:
        raise CliError(str(exc)) from None
    command = "ddc " + " ".join(shlex.quote(a) for a in sys.argv[1:]) if sys.argv else None
    result = learn(args.data, args.target or None, seed=args.seed, options=options,
                   command=command, progress=not args.quiet and sys.stderr.isatty())
    for w in result.warnings:
        print(f"ddc learn: warning: {w.strip()}", file=sys.stderr)
    result.write(args.out, form=args.form)
    if args.plot is not None:
        from ddclearn.plot import plot_trees

        plot_trees([t.tree for t in result.targets], args.plot)
    report = result.report()
    if args.json:
        print(json.dumps({k: _jsonable(v) for k, v in report.items()}))
    else:
        print(f"{'target':<28} {'clauses':>7} {'groundings':>10} {'seconds':>8} "
              f"{'log-likelihood':>15} {'mean':>9}")
        for key, r in report.items():
            print(f"{key:<28} {r['clauses']:>7} {r['groundings']:>10} {r['seconds']:>8.2f} "
                  f"{r['log_likelihood']:>15.6g} {r['mean_log_likelihood']:>9.4g}")
        print(f"wrote {args.out}" + (f" and {args.plot}" if args.plot else ""))
    return 0


def run_evaluate(args: argparse.Namespace) -> int:
    from cli.ddc_cli import CliError
    from ddclearn import evaluate

    if not args.program.is_file():
        raise CliError(f"{args.program}: no such file")
    scores = evaluate(args.program, args.data, args.target or None)
    if args.json:
        print(json.dumps({k: _jsonable(v) for k, v in scores.items()}))
        return 0
    print(f"{'target':<28} {'n':>8} {'mean log-lik':>13} {'accuracy':>9} {'rmse':>12} "
          f"{'uncovered':>9}")
    for key, s in scores.items():
        acc = f"{s['accuracy']:.4f}" if "accuracy" in s else "-"
        rmse = f"{s['rmse']:.6g}" if "rmse" in s else "-"
        print(f"{key:<28} {s['n']:>8} {s['mean_log_likelihood']:>13.5g} {acc:>9} {rmse:>12} "
              f"{s['uncovered']:>9}")
    return 0


def run_split(args: argparse.Namespace) -> int:
    """``ddc split``: write the training and test parts and print their counts."""
    from bridge.learning import split_files
    from cli.ddc_cli import CliError

    if not 0.0 < args.fraction < 1.0:
        raise CliError(f"--fraction {args.fraction:g}: must be between 0 and 1 (exclusive)")
    stats = split_files(args.data, args.train, args.test, fraction=args.fraction,
                        seed=args.seed, unit=args.unit)
    if args.json:
        print(json.dumps(stats))
        return 0
    print(f"train {stats['train']} facts, test {stats['test']} facts ({stats['test_units']} of "
          f"{stats['units']} units), {stats['cut']} cut, {stats['both']} in both: "
          f"wrote {args.train} and {args.test}")
    return 0


def _jsonable(d: dict[str, Any]) -> dict[str, Any]:
    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
            for k, v in d.items()}
