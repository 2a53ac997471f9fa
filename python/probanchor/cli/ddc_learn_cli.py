"""`ddc learn`, `ddc evaluate` and `ddc split`: the structure learner from the shell.

    ddc learn DATA.pl [MORE.pl ...] --out LEARNED.pl [--target NAME]... [--json] [--seed S]
              [--plot TREE.png|TREE.svg] [--min-leaf N] [--max-depth D] [--min-gain G]
              [--smoothing A] [--l2 L] [--no-lookahead] [--root-model auto|always|never]
              [--form clauses|tree] [--quiet]
    ddc evaluate LEARNED.pl TEST.pl [MORE.pl ...] [--target NAME]... [--bias TRAIN.pl] [--json]
    ddc split DATA.pl [MORE.pl ...] --train TRAIN.pl --test TEST.pl [--fraction F] [--seed S]
              [--unit TYPE] [--json]
    ddc cross-validate DATA.pl [MORE.pl ...] --out DIR [--folds K] [--seed S] [--unit TYPE]
              [--jobs N] [--cluster local|ray|auto|ray://HOST:PORT] [learn's search options]

``ddc learn`` reads background knowledge, training facts and declarative bias from the data files,
learns one distributional logic tree per target and writes the DC program they make (``--out`` is
replaced only once the program is complete and loads in the DDC system): one clause per path of a
tree (``--form clauses``, the default) or one clause per tree, its body the tree as nested
if-then-else goals (``--form tree``: the same program, faster in the filter). It prints per target
the clauses, groundings, seconds and training log-likelihood (``--json``: one JSON object keyed by
target). ``ddc evaluate`` scores a DC program on held-out facts: per target the number of test
groundings, the mean log-likelihood per grounding (natural log) and the accuracy (discrete) or RMSE
(continuous); test files of facts only (DreaML's held-out files) are read in the dialect and with
the declarations of the data the program was learned from, or of ``--bias`` files. ``ddc split``
writes a training and a test file whose test facts form worlds of their own (docs/learning.md,
"Held-out data"). ``ddc cross-validate`` splits the data into K folds of separate worlds and, one
fold per job (local processes or Ray, docs/cluster.md), learns on the other folds and scores the
held-out one: per fold and over all folds, the columns of ``ddc evaluate``.
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
    """Add ``learn``, ``evaluate``, ``split`` and ``cross-validate`` to ``ddc``'s parser."""
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
    _add_search_options(learn)
    learn.add_argument("--form", choices=["clauses", "tree"], default="clauses",
                       help="one clause per path (default) or per tree (nested if-then-else)")
    learn.add_argument("--quiet", action="store_true", help="no progress bar")
    learn.set_defaults(func=run_learn)

    cv = sub.add_parser("cross-validate",
                        help="K-fold cross-validation of the learner (one fold per job)")
    cv.add_argument("data", nargs="+", help="data files: facts, background, bias (one dialect)")
    cv.add_argument("--folds", type=positive_int, default=5, help="K (at least 2; default 5)")
    cv.add_argument("--out", required=True, type=Path,
                    help="a folder: fold-I/{train,test,learned}.pl and cross-validation.json")
    cv.add_argument("--target", action="append", default=[], metavar="NAME",
                    help="a target to learn (repeatable; default: every declared target)")
    cv.add_argument("--seed", type=int, default=0,
                    help="seed of the folds and of the learner's samples (default 0)")
    cv.add_argument("--unit", default=None, metavar="TYPE",
                    help="fold by the constants of this argument type (as ddc split --unit)")
    cv.add_argument("--form", choices=["clauses", "tree"], default="clauses",
                    help="the learned programs' form (default clauses)")
    _add_search_options(cv)
    from probanchor.cli.options import add_cluster_options

    add_cluster_options(cv, "fold")
    cv.add_argument("--json", action="store_true", help="print one JSON object")
    cv.add_argument("--quiet", action="store_true", help="no progress bar")
    cv.set_defaults(func=run_cross_validate)

    ev = sub.add_parser("evaluate", help="held-out scores of a DC program on test facts")
    ev.add_argument("program", type=Path, help="the DC program (e.g. from ddc learn)")
    ev.add_argument("data", nargs="+", help="test data: facts in the training data's format")
    ev.add_argument("--target", action="append", default=[], metavar="NAME",
                    help="a target to score (repeatable; default: every one with facts)")
    ev.add_argument("--bias", action="append", default=[], type=Path, metavar="TRAIN.pl",
                    help="test files of facts only: read them with this file's declarations "
                         "(repeatable; default: those of the data the program was learned "
                         "from, which a learned program records)")
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


def _add_search_options(parser: argparse.ArgumentParser) -> None:
    """The search's settings (:class:`ddclearn.SearchOptions`), for learn and cross-validate."""
    parser.add_argument("--min-leaf", type=float, default=10.0,
                        help="smallest weight of a branch with a model of its own (default 10)")
    parser.add_argument("--max-depth", type=int, default=8, help="longest path (default 8)")
    parser.add_argument("--min-gain", type=float, default=0.0,
                        help="a split must raise the BIC by more than this (default 0)")
    parser.add_argument("--smoothing", type=float, default=1.0,
                        help="pseudo-count per value of a discrete head (default 1)")
    parser.add_argument("--l2", type=float, default=0.01,
                        help="L2 penalty on standardised regression weights (default 0.01)")
    parser.add_argument("--no-lookahead", action="store_true",
                        help="score literals that introduce variables by themselves")
    parser.add_argument("--root-model", choices=["auto", "always", "never"], default="auto",
                        help="whether the tree reads a regression over every root feature "
                             "(default auto: when held-out examples say it predicts better)")


def _search_options(args: argparse.Namespace) -> Any:
    """The :class:`ddclearn.SearchOptions` that the options name; CliError when out of range."""
    from probanchor.cli.ddc_cli import CliError
    from probanchor.ddclearn import LeafOptions, SearchOptions

    try:
        return SearchOptions(min_leaf=args.min_leaf, max_depth=args.max_depth,
                             min_gain=args.min_gain, lookahead=not args.no_lookahead,
                             root_model=args.root_model,
                             leaf=LeafOptions(smoothing=args.smoothing, l2=args.l2))
    except ValueError as exc:
        raise CliError(str(exc)) from None


def run_learn(args: argparse.Namespace) -> int:
    from probanchor.cli.ddc_cli import CliError
    from probanchor.ddclearn import learn

    if args.plot is not None and args.plot.suffix.lower() not in (".png", ".svg"):
        raise CliError(f"--plot {args.plot}: the picture must be .png or .svg")
    options = _search_options(args)
    command = "ddc " + " ".join(shlex.quote(a) for a in sys.argv[1:]) if sys.argv else None
    result = learn(args.data, args.target or None, seed=args.seed, options=options,
                   command=command, progress=not args.quiet and sys.stderr.isatty())
    for w in result.warnings:
        print(f"ddc learn: warning: {w.strip()}", file=sys.stderr)
    result.write(args.out, form=args.form)
    if args.plot is not None:
        from probanchor.ddclearn.plot import plot_trees

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
    from probanchor.cli.ddc_cli import CliError
    from probanchor.ddclearn import evaluate

    if not args.program.is_file():
        raise CliError(f"{args.program}: no such file")
    for b in args.bias:
        if not b.is_file():
            raise CliError(f"--bias {b}: no such file")
    scores = evaluate(args.program, args.data, args.target or None, bias=args.bias or None)
    if args.json:
        print(json.dumps({k: _jsonable(v) for k, v in scores.items()}))
        return 0
    print(f"{'target':<28} {'n':>8} {'mean log-lik':>13} {'accuracy':>9} {'rmse':>12} "
          f"{'uncovered':>9}")
    for key, s in scores.items():
        print(_score_row(key, None, s))
    return 0


def run_cross_validate(args: argparse.Namespace) -> int:
    """``ddc cross-validate``: the folds' held-out scores, per fold and over the folds."""
    from probanchor.cli.ddc_cli import CliError
    from probanchor.ddclearn.crossval import SUMMARY_NAME, cross_validate
    from probanchor.jobs import ClusterError, parse_cluster

    if args.folds < 2:
        raise CliError(f"--folds {args.folds}: cross-validation needs at least 2 folds")
    if args.out.exists() and not args.out.is_dir():
        raise CliError(f"--out {args.out}: not a folder")
    try:
        cluster = parse_cluster(args.cluster, args.jobs)
    except ClusterError as exc:
        raise CliError(str(exc)) from None
    result = cross_validate(args.data, args.folds, args.out, targets=args.target or None,
                            seed=args.seed, unit=args.unit, options=_search_options(args),
                            form=args.form, cluster=cluster,
                            progress=not args.quiet and sys.stderr.isatty())
    for w in result.warnings:
        print(f"ddc cross-validate: warning: {w}", file=sys.stderr)
    if args.json:
        print(json.dumps(result.to_json()))
        return 0
    print(f"{'target':<28} {'fold':>4} {'n':>8} {'mean log-lik':>13} {'accuracy':>9} "
          f"{'rmse':>12} {'uncovered':>9}")
    summary = result.summary()
    for key, s in summary.items():
        for f in result.folds:
            if key in f.scores:
                print(_score_row(key, str(f.fold), f.scores[key]))
        print(_score_row(key, "all", s) + f"   (fold mean {s['fold_mean']:.5g} "
              f"± {s['fold_std']:.2g})")
    print(f"{len(result.folds)} folds on {result.cluster}: wrote "
          f"{args.out}/fold-*/learned.pl and {args.out / SUMMARY_NAME}")
    return 0


def _score_row(key: str, fold: str | None, s: dict[str, Any]) -> str:
    """One line of held-out scores (``ddc evaluate``'s columns; a fold column unless None)."""
    acc = f"{s['accuracy']:.4f}" if "accuracy" in s else "-"
    rmse = f"{s['rmse']:.6g}" if "rmse" in s else "-"
    where = "" if fold is None else f" {fold:>4}"
    return (f"{key:<28}{where} {s['n']:>8} {s['mean_log_likelihood']:>13.5g} {acc:>9} "
            f"{rmse:>12} {s['uncovered']:>9}")


def run_split(args: argparse.Namespace) -> int:
    """``ddc split``: write the training and test parts and print their counts."""
    from bridge.learning import split_files
    from probanchor.cli.ddc_cli import CliError

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
