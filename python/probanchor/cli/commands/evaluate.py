"""`anchoring evaluate`: the measured table of docs/evaluation.md (shipped scenarios over
seeds, random shell games; with reasoning, the learned theories, without reasoning, and
published trackers on the same percepts: SORT, ByteTrack, OC-SORT, Stone Soup's JPDA and MHT;
identity kept, ID switches, IDF1, HOTA, DetA, AssA, LocA)."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from probanchor.cli.options import add_cluster_options, add_engine_option, add_threads_option


def register(sub: Any) -> None:
    parser = sub.add_parser("evaluate", help="measure identity keeping over many runs",
                            description=__doc__)
    parser.add_argument("--out", type=Path, default=Path("results"),
                        help="output directory (percept cache, summaries, results.md)")
    parser.add_argument("--seeds", type=int, default=20, help="seeds per shipped scenario")
    parser.add_argument("--games", type=int, default=50, help="random shell games")
    parser.add_argument("--first-game-seed", type=int, default=0,
                        help="the first random game's seed (default 0: the games of "
                             "docs/evaluation.md; others are games it never used)")
    parser.add_argument("--particles", type=int, default=1000)
    add_threads_option(parser, "Prolog threads per filter")
    add_engine_option(parser, "; a run recorded with another engine is run again")
    parser.add_argument("--methods", default=None,
                        help="comma-separated methods: reasoning (the hand-written theory), "
                             "learned, learned-hindsight (the learned theories), no-reasoning, "
                             "sort, bytetrack, ocsort, stonesoup-jpda, stonesoup-mht (default: "
                             "reasoning, no-reasoning and the five trackers)")
    parser.add_argument("--scenarios", default=None,
                        help="comma-separated shipped scenarios (default all four)")
    add_cluster_options(parser, "(scenario, seed)", "; runs already in OUT/summaries.jsonl "
                        "are kept, not run again")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from probanchor.experiments.sweep import (
        ALL_METHODS,
        METHODS,
        SHIPPED,
        ExperimentOptions,
        run_experiment,
    )

    for option in ("seeds", "games", "first_game_seed"):
        if getattr(args, option) < 0:
            raise ValueError(f"--{option.replace('_', '-')} must be 0 or more, not "
                             f"{getattr(args, option)}")
    methods = args.methods.split(",") if args.methods else list(METHODS)
    unknown = sorted(set(methods) - set(ALL_METHODS))
    if unknown:
        raise ValueError(f"unknown methods {unknown}; choose from {', '.join(ALL_METHODS)}")
    scenarios = args.scenarios.split(",") if args.scenarios else list(SHIPPED)
    table = run_experiment(
        ExperimentOptions(out=args.out, seeds=args.seeds, games=args.games,
                          first_game_seed=args.first_game_seed, particles=args.particles,
                          methods=methods, scenarios=scenarios, jobs=args.jobs,
                          cluster=args.cluster, threads=args.threads, engine=args.engine),
        progress=True,
    )
    print(table)
    print(f"wrote {args.out}/results.md and {args.out}/summaries.jsonl")
    return 0
