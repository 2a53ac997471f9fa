"""`anchoring collect`: before/after facts of occlusions from the robot's own experience.

    anchoring collect [SCENARIO ...] [--games K] [--seed S] --out DATA.pl
                      [--labels truth|hindsight] [--jobs J] [--cluster BACKEND]
                      [--cache DIR] [--json]

Plays scenarios and generated occlusion games through perception and anchoring alone and
writes the structure learner's input (facts, background knowledge and the declarative bias of
``occluder(A, O):t+1``), labelled from the simulator's ground truth or from hindsight.
"""

from __future__ import annotations

import argparse
import json
import shlex
import sys
from pathlib import Path
from typing import Any

from probanchor.cli.options import add_cluster_options


def register(sub: Any) -> None:
    parser = sub.add_parser("collect", help="collect before/after facts of occlusions",
                            description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("scenarios", type=Path, nargs="*", help="scenario files to play")
    parser.add_argument("--games", type=int, default=0,
                        help="generated occlusion games to play (seeds SEED, SEED+1, ...)")
    parser.add_argument("--seed", type=int, default=0,
                        help="first game's seed, and every episode's sensor noise (default 0)")
    parser.add_argument("--out", type=Path, required=True, help="the data file to write")
    parser.add_argument("--labels", choices=["truth", "hindsight"], default="truth",
                        help="labels from the simulator's ground truth (default) or from "
                             "hindsight (where re-acquired objects emerged), without it")
    parser.add_argument("--steady-stride", type=int, default=5,
                        help="keep one in N steady data points, with weight N (default 5)")
    add_cluster_options(parser, "episode")
    parser.add_argument("--cache", type=Path, default=Path("out/collect"),
                        help="percept streams and generated games (default out/collect)")
    parser.add_argument("--json", action="store_true", help="print the report as JSON")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from probanchor.learning.collect import CollectOptions, collect
    from probanchor.learning.occlusion_data import LabelOptions

    labels = LabelOptions(source=args.labels, steady_stride=args.steady_stride)
    command = "anchoring " + " ".join(shlex.quote(a) for a in sys.argv[1:])
    report = collect(CollectOptions(out=args.out, scenarios=args.scenarios, games=args.games,
                                    seed=args.seed, labels=labels, cache=args.cache,
                                    jobs=args.jobs, cluster=args.cluster, command=command,
                                    progress=not args.json),
                     progress=None if args.json else (lambda m: print(m, flush=True)))
    figures = {
        "episodes": report.episodes, "pairs": report.pairs, "covered": report.positive,
        "seconds": {"perception": round(report.seconds_perception, 2),
                    "facts": round(report.seconds_facts, 2),
                    "total": round(report.seconds_total, 2)},
        "hindsight_agreement": report.agreement, "agreement_pairs": report.agreement_pairs,
        "out": str(report.out),
    }
    if args.json:
        print(json.dumps(figures))
        return 0
    print(f"{report.episodes} episodes, {report.pairs} pairs ({report.positive:g} covered): "
          f"wrote {report.out}")
    if report.agreement is not None:
        print(f"hindsight labels agree with the ground truth on {100 * report.agreement:.1f} % "
              f"of {report.agreement_pairs} (frame, hidden anchor, other anchor) triples")
    print(f"seconds: perception {report.seconds_perception:.1f} (summed over workers), facts "
          f"{report.seconds_facts:.1f}, total {report.seconds_total:.1f}")
    return 0
