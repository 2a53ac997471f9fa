"""`ddc`: Distributional Clauses from the shell.

    ddc query FILE QUERY [--evidence E]... [--samples N] [--seed S] [--json]
    ddc filter PROGRAM OBSERVATIONS.jsonl [--particles N] [--seed S] [--query GOAL]...
               [--distribution TERM]... [--mean TERM]...
               [--resampling systematic|multinomial|residual] [--threshold F] [--json]
    ddc learn DATA.pl... --out LEARNED.pl [--target NAME]... [--json] [--seed S] [--plot F]
    ddc evaluate LEARNED.pl TEST.pl... [--target NAME]... [--json]   (see cli.ddc_learn_cli)

``ddc filter`` runs one filtering step per line of OBSERVATIONS.jsonl. A line is a JSON object
with the optional keys ``observations`` and ``actions`` (lists; missing means empty) and
``comment`` (ignored). A list item is either a string of Prolog term text
(``"observation(pos(ball_1)) ~= (0.31,0.12,0.05)"``, ``"observed(ball_1)"``,
``"action(move(box_1,(0.1,0,0)))"``) or, for an observation, an object
``{"observation": "pos(ball_1)", "value": [0.31, 0.12, 0.05]}`` meaning
``observation(pos(ball_1)) ~= (0.31,0.12,0.05)``: a JSON array value becomes a tuple, a string
an atom, a number a number. Blank lines are skipped. (The format has one reader, in the
engine: ``read_frame_file/2`` of prolog/ddc/filter/ddc_belief.pl, asked through ``bridge.frames``.)

It prints one row per step (step 0 is the prior) with the filter's time, the effective sample
size, whether it resampled, the running log-likelihood and the probability of each ``--query``
goal (``--json``: one JSON object per step). Exit status 1 with ``file:line: cause`` on a bad
program, query or line.
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import sys
import warnings
from pathlib import Path
from typing import Any

from probanchor.cli.ddc_learn_cli import add_learn_commands
from probanchor.cli.options import add_engine_option, add_threads_option


class CliError(Exception):
    """A message for the user (no traceback)."""


# --------------------------------------------------------------------------------------------
# ddc query


def run_query(args: argparse.Namespace) -> int:
    import bridge

    program_path = Path(args.file)
    if not program_path.is_file():
        raise CliError(f"{program_path}: no such file")
    evidence = None
    if args.evidence:
        evidence = args.evidence[0] if len(args.evidence) == 1 else ", ".join(
            f"({e})" for e in args.evidence
        )
    program = bridge.load(program_path)
    kwargs: dict[str, Any] = {"evidence": evidence}
    if args.samples is not None:
        kwargs["samples"] = args.samples
    if args.seed is not None:
        kwargs["seed"] = args.seed
    result = program.query(args.query, **kwargs)
    samples = getattr(result, "samples", args.samples)
    if args.json:
        print(json.dumps({
            "probability": float(result.probability),
            "stderr": _json_float(getattr(result, "stderr", math.nan)),
            "samples": samples,
        }))
    else:
        stderr = getattr(result, "stderr", None)
        extra = [f"stderr {float(stderr):.6g}"] if stderr is not None else []
        if samples is not None:
            extra.append(f"{samples} samples")
        if getattr(result, "ess", None) is not None:
            extra.append(f"ess {float(result.ess):.1f}")
        print(f"{float(result.probability):.6g}" + (f"  ({', '.join(extra)})" if extra else ""))
    return 0


def _json_float(value: Any) -> float | None:
    if value is None:
        return None
    value = float(value)
    return value if math.isfinite(value) else None


# --------------------------------------------------------------------------------------------
# ddc filter: the observations file


def read_frames(path: Path) -> list[Any]:
    """The frames (``bridge.frames.Frame``) of an observations file, read by the DDC system's
    reader of the format (prolog/ddc/filter/ddc_belief.pl, the one swipl users run); CliError
    naming file:line on a bad line."""
    from bridge.frames import FrameFileError
    from bridge.frames import read_frames as read_frame_file

    try:
        return read_frame_file(path)
    except FrameFileError as exc:
        raise CliError(str(exc)) from None


# --------------------------------------------------------------------------------------------
# ddc filter: running and printing


def _belief(f: Any, queries: list[str], distributions: list[str],
            means: list[str]) -> dict[str, Any]:
    from bridge import FilterError

    out: dict[str, Any] = {"probabilities": {}, "distributions": {}, "means": {}}
    for goal in queries:
        try:
            out["probabilities"][goal] = f.probability(goal)
        except FilterError as exc:
            raise CliError(f"--query {goal!r}: {exc}") from None
    for term in distributions:
        try:
            out["distributions"][term] = [[p, _jsonable(v)] for p, v in f.distribution(term)]
        except FilterError as exc:
            raise CliError(f"--distribution {term!r}: {exc}") from None
    for term in means:
        try:
            mean, cov = f.mean(term)
        except FilterError as exc:
            raise CliError(f"--mean {term!r}: {exc}") from None
        out["means"][term] = {"mean": _plain(mean), "covariance": _plain(cov)}
    return out


def _plain(value: Any) -> Any:
    return value.tolist() if hasattr(value, "tolist") else float(value)


def _jsonable(value: Any) -> Any:
    if isinstance(value, tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return value


def run_filter(args: argparse.Namespace) -> int:
    from bridge import Filter, FilterError

    program = Path(args.program)
    observations = Path(args.observations)
    if not program.is_file():
        raise CliError(f"{program}: no such file")
    if not observations.is_file():
        raise CliError(f"{observations}: no such file")
    frames = read_frames(observations)  # a bad line fails before any work is done
    try:
        f = Filter(program, particles=args.particles, seed=args.seed,
                   resample_threshold=args.threshold, resampling=args.resampling,
                   threads=args.threads, engine=args.engine)
    except FilterError as exc:
        raise CliError(str(exc)) from None
    printer: _JsonPrinter | _TablePrinter = (
        _JsonPrinter() if args.json else _TablePrinter(args.query, args.distribution, args.mean)
    )
    with f:
        row = {"step": 0, "line": None, "time": f.time, "ess": f.ess, "resampled": False,
               "zero_weight": False, "log_likelihood": 0.0, "ms": 0.0}
        printer.row({**row, **_belief(f, args.query, args.distribution, args.mean)})
        for step, frame in enumerate(frames, start=1):
            try:
                result = f.step(frame.observations, frame.actions)
            except FilterError as exc:
                raise CliError(f"{observations}:{frame.line}: {exc}") from None
            row = {"step": step, "line": frame.line, "time": result.time, "ess": result.ess,
                   "resampled": result.resampled, "zero_weight": result.zero_weight,
                   "log_likelihood": f.log_likelihood, "ms": 1000 * result.seconds}
            printer.row({**row, **_belief(f, args.query, args.distribution, args.mean)})
        steps = len(frames)
        mean_ms = 1000 * sum(f.step_seconds) / steps if steps else 0.0
        print(
            f"ddc filter: {steps} steps, {f.particles} particles, {mean_ms:.1f} ms/step, "
            f"{f.resample_count} resamplings, {f.zero_weight_events} zero-weight events, "
            f"log-likelihood {f.log_likelihood:.6g}",
            file=sys.stderr,
        )
    return 0


class _JsonPrinter:
    def row(self, row: dict[str, Any]) -> None:
        row = {k: (_json_float(v) if isinstance(v, float) else v) for k, v in row.items()}
        for key in ("distributions", "means"):
            if not row[key]:
                del row[key]
        print(json.dumps(row), flush=True)


def _short(value: Any) -> str:
    if isinstance(value, list):
        return "[" + ", ".join(_short(v) for v in value) + "]"
    return f"{value:.4g}"


_SHOWN = 8  # values of a --distribution shown per row in the table (all of them in JSON)


class _TablePrinter:
    def __init__(self, queries: list[str], distributions: list[str], means: list[str]) -> None:
        self.queries = queries
        self.distributions = distributions
        self.means = means
        self.header_done = False

    def row(self, row: dict[str, Any]) -> None:
        if not self.header_done:
            columns = ["step", "time", "ess", "resampled", "loglik"]
            print("  ".join(f"{c:>9}" for c in columns) + "".join(f"  {q}" for q in self.queries))
            self.header_done = True
        flag = "zero-w" if row["zero_weight"] else ("yes" if row["resampled"] else "no")
        cells = [f"{row['step']:>9}", f"{row['time']:>9}", f"{row['ess']:>9.1f}", f"{flag:>9}",
                 f"{row['log_likelihood']:>9.4g}"]
        line = "  ".join(cells)
        for q in self.queries:
            line += "  " + f"{row['probabilities'][q]:.6f}".rjust(len(q))
        print(line, flush=True)
        for term in self.distributions:
            dist = row["distributions"][term]
            pairs = ", ".join(f"{p:.4f}:{v}" for p, v in dist[:_SHOWN])
            if len(dist) > _SHOWN:
                pairs += f", ... ({len(dist) - _SHOWN} more values)"
            print(f"{'':>9}  {term} = [{pairs}]", flush=True)
        for term in self.means:
            stats = row["means"][term]
            print(f"{'':>9}  mean {term} = {_short(stats['mean'])}, "
                  f"covariance {_short(stats['covariance'])}", flush=True)


# --------------------------------------------------------------------------------------------


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="ddc", description="Distributional Clauses (DDC).")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", required=True)

    q = sub.add_parser("query", help="probability of a query in a DC program")
    q.add_argument("file", help="the DC program")
    q.add_argument("query", help="the query goal, e.g. 'coin ~= true'")
    q.add_argument("--evidence", action="append", default=[],
                   help="an evidence goal (repeat for a conjunction)")
    q.add_argument("--samples", type=int, default=None, help="number of samples")
    q.add_argument("--seed", type=int, default=None, help="random seed")
    q.add_argument("--json", action="store_true", help="print one JSON object")
    q.set_defaults(func=run_query)

    f = sub.add_parser("filter", help="run the particle filter over a JSONL observation file")
    f.add_argument("program", help="the DDC program")
    f.add_argument("observations", help="JSON Lines, one step per line")
    f.add_argument("--particles", type=_positive_int, default=1000)
    f.add_argument("--seed", type=int, default=0)
    add_threads_option(f, kind=_positive_int)
    add_engine_option(f, "")
    f.add_argument("--query", action="append", default=[], metavar="GOAL",
                   help="a goal whose probability is printed after each step (repeatable)")
    f.add_argument("--distribution", action="append", default=[], metavar="TERM",
                   help="a random variable whose distribution is printed (repeatable)")
    f.add_argument("--mean", action="append", default=[], metavar="TERM",
                   help="a numeric or tuple variable whose weighted mean and covariance are "
                        "printed (repeatable)")
    f.add_argument("--resampling", choices=["systematic", "multinomial", "residual"],
                   default="systematic")
    f.add_argument("--threshold", type=float, default=0.9,
                   help="resample when ESS < threshold * particles (default 0.9)")
    f.add_argument("--json", action="store_true", help="one JSON object per step")
    f.set_defaults(func=run_filter)

    add_learn_commands(sub, _positive_int)
    return parser


def _positive_int(text: str) -> int:
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {value}")
    return value


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="ddc: %(message)s")
    warnings.filterwarnings("ignore", message=".*every particle got weight 0")  # logged once
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return 0
    except Exception as exc:  # a clear message, not a traceback, for bad input
        if args.debug:
            raise
        print(f"ddc {args.command}: error: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
