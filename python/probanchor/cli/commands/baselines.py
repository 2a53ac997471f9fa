"""`anchoring baselines PERCEPTS.jsonl...`: the baseline trackers on recorded percept streams.

Runs SORT, ByteTrack and OC-SORT (Roboflow's ``trackers``) and Stone Soup's JPDA and MHT
trackers on each stream, evaluates them against the stream's ground truth (``truth`` per frame)
and prints the Markdown results table. With ``--out DIR`` it also writes
``DIR/<stream>/<method>/summary.json`` and ``records.jsonl``. With ``--tune`` it searches the
Stone Soup trackers' settings instead (on the streams given, or on ``--games`` generated shell
games from seed ``--first-game-seed``, which the evaluation does not use) and prints the best.
"""

from __future__ import annotations

import argparse
from pathlib import Path


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "baselines",
        help="run the baseline trackers (SORT, ByteTrack, OC-SORT) on percept streams",
        description=__doc__.split("\n\n")[1] if __doc__ else None,
    )
    parser.add_argument("streams", nargs="*", type=Path, metavar="PERCEPTS.jsonl",
                        help="percept streams with ground truth (anchoring perceive --out ...)")
    # (the trackers' names and the threshold are evaluation's; not imported here, it is slow)
    parser.add_argument("--methods", default=None,
                        help="comma-separated subset of sort,bytetrack,ocsort,stonesoup-jpda,"
                             "stonesoup-mht (default: all; with --tune: the two Stone Soup)")
    parser.add_argument("--threshold", type=float, default=None,
                        help="match distance in metres for ID switches and IDF1 (default 0.1)")
    parser.add_argument("--lost-seconds", type=float, default=60.0,
                        help="how long a lost track is kept (default 60 s)")
    parser.add_argument("--ignore", default="",
                        help="comma-separated ground-truth ids left out (e.g. a hand)")
    parser.add_argument("--out", type=Path, help="write summaries and records under this folder")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    tuning = parser.add_argument_group("tuning the Stone Soup trackers (--tune)")
    tuning.add_argument("--tune", action="store_true",
                        help="search the Stone Soup trackers' settings (a grid) and print the "
                             "best, instead of the table")
    tuning.add_argument("--games", type=int, default=3,
                        help="without streams: generated shell games to tune on (default 3)")
    tuning.add_argument("--first-game-seed", type=int, default=1000,
                        help="their first seed (default 1000; the evaluation uses 0 to 49)")
    tuning.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from probanchor.evaluation.baselines import BASELINES, display_name, run_baseline
    from probanchor.evaluation.metrics import DEFAULT_THRESHOLD_M, evaluate
    from probanchor.evaluation.record import write_records
    from probanchor.evaluation.summary import make_summary, write_summary
    from probanchor.evaluation.table import results_table
    from probanchor.percepts import read_percepts

    if args.tune:
        return tune(args)
    if not args.streams:
        raise ValueError("give at least one percept stream (PERCEPTS.jsonl)")
    if args.threshold is None:
        args.threshold = DEFAULT_THRESHOLD_M
    methods = [m.strip() for m in (args.methods or ",".join(BASELINES)).split(",") if m.strip()]
    unknown = [m for m in methods if m not in BASELINES]
    if unknown:
        raise ValueError(f"unknown baseline(s) {', '.join(unknown)}; known: {', '.join(BASELINES)}")
    ignore = [i.strip() for i in args.ignore.split(",") if i.strip()]
    rows = []
    for path in args.streams:
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such percept stream")
        frames = list(read_percepts(path))
        if not any(fr.truth for fr in frames):
            raise ValueError(f"{path}: the stream has no ground truth ('truth' per frame)")
        for method in methods:
            records = run_baseline(method, frames, lost_seconds=args.lost_seconds, ignore=ignore)
            ev = evaluate(records, args.threshold)
            if args.out:
                folder = args.out / path.stem / method
                folder.mkdir(parents=True, exist_ok=True)
                write_summary(folder / "summary.json", records, ev, threshold=args.threshold,
                              extra={"scenario": path.stem, "method": display_name(method)})
                write_records(folder / "records.jsonl", records)
            rows.append((path.stem, display_name(method), make_summary(records, ev)))
    print(results_table(rows, args.threshold), end="")
    return 0


def tune(args: argparse.Namespace) -> int:
    """``--tune``: the Stone Soup trackers' grid search (evaluation.stonesoup_tuning)."""
    from probanchor.evaluation.stonesoup_trackers import STONESOUP
    from probanchor.evaluation.stonesoup_tuning import GRID, format_ranking
    from probanchor.evaluation.stonesoup_tuning import tune as search

    methods = [m.strip() for m in (args.methods or ",".join(STONESOUP)).split(",") if m.strip()]
    unknown = [m for m in methods if m not in STONESOUP]
    if unknown:
        raise ValueError(f"--tune: {', '.join(unknown)} not a Stone Soup tracker; known: "
                         f"{', '.join(STONESOUP)}")
    streams = list(args.streams)
    for path in streams:
        if not path.is_file():
            raise FileNotFoundError(f"{path}: no such percept stream")
    if not streams:
        from probanchor.experiments.sweep import game_scenarios
        from probanchor.loop.sources import percept_stream

        if args.games < 1:
            raise ValueError(f"--games: {args.games} is not a positive number of games")
        args.out = out = args.out or Path("results-tuning")
        games = game_scenarios(out, args.games, args.first_game_seed)
        streams = [percept_stream(game, 0, out / "percepts") for game in games]
    log = None
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        log = args.out / "tuning.jsonl"  # each run as it finishes; a rerun goes on from there
    ranking = search(methods, streams, jobs=args.jobs, lost_seconds=args.lost_seconds,
                     progress=True, log=log)
    text = format_ranking(ranking)
    grid = ", ".join(f"{k} {v}" for k, v in GRID.items())
    names = ", ".join(p.stem for p in streams)
    header = (f"Stone Soup settings on {len(streams)} streams ({names}); grid: {grid}; best "
              "first (identity kept, then HOTA):\n\n")
    print(header + text, end="")
    if args.out:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "tuning.md").write_text(header + text, encoding="utf-8")
    return 0
