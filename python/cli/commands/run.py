"""`anchoring run SCENARIO`: play a scenario (or a recorded percept stream) through
perception, anchoring and the occlusion reasoning, and report whether identities were kept."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from app.reasoning import DEFAULT_THEORY, DEFAULT_THREADS
from app.theories import theory_path
from cli.options import add_engine_option


def add_run_options(parser: argparse.ArgumentParser, particles: int = 1000) -> None:
    parser.add_argument("--particles", type=int, default=particles,
                        help=f"particles of the filter (default {particles})")
    parser.add_argument("--theory", type=theory_path, default=DEFAULT_THEORY,
                        help="theory of occlusion: hand (prolog/too.pl, the default), learned "
                             "(prolog/too_learned.pl), hindsight "
                             "(prolog/too_learned_hindsight.pl), or a DDC program's path")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument("--threads", type=int, default=DEFAULT_THREADS,
                        help=f"Prolog threads that step the particles (default "
                             f"{DEFAULT_THREADS}; the particles depend on the seed and it)")
    add_engine_option(parser, ", as prolog/too.pl is")
    parser.add_argument("--resample-threshold", type=float, default=0.9,
                        help="resample when ESS < this fraction of the particles (default 0.9)")
    parser.add_argument("--out", type=Path, default=None,
                        help="write summary.json, per-frame PNGs, run.gif and world.pl here")
    parser.add_argument("--every", type=int, default=1,
                        help="write a picture every N frames (default 1)")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    parser.add_argument("--sequential", action="store_true",
                        help="perceive each frame only after the previous one is processed "
                             "(by default the next frame is perceived while the current one "
                             "is reasoned about; the results are the same)")


def register(sub: Any) -> None:
    parser = sub.add_parser("run", help="play a scenario through anchoring and reasoning",
                            description=__doc__)
    parser.add_argument("scenario", type=Path, nargs="?",
                        help="scenario file (scenarios/*.yaml); or use --percepts")
    parser.add_argument("--percepts", type=Path, default=None,
                        help="a recorded percept stream (JSON Lines) instead of a scenario")
    parser.add_argument("--no-reasoning", action="store_true",
                        help="anchoring alone: hidden anchors keep their last position")
    parser.add_argument("--no-reid", action="store_true",
                        help="anchoring does not re-identify a percept by appearance alone "
                             "(a unique look-alike of an anchor left over)")
    add_run_options(parser)
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from app.runner import RunOptions, format_summary, run

    output = run(RunOptions(
        scenario=args.scenario, percepts=args.percepts, particles=args.particles,
        theory=args.theory, seed=args.seed, reasoning=not args.no_reasoning,
        resample_threshold=args.resample_threshold, reidentify=not args.no_reid, out=args.out,
        threads=args.threads, engine=args.engine, overlap=not args.sequential,
        picture_every=args.every, progress=not args.quiet,
    ))
    print(format_summary(output.summary))
    if output.out is not None:
        print(f"wrote {output.out}/summary.json, world.pl"
              + (f", {len(output.pictures)} pictures and {output.gif}" if output.gif else ""))
    return 0
