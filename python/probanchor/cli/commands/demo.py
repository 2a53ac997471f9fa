"""`anchoring demo`: the multi-modal shell game (paper, section 5.1) with defaults."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any


def register(sub: Any) -> None:
    parser = sub.add_parser("demo", help="run the shell game and say where its video is",
                            description=__doc__)
    parser.add_argument("--out", type=Path, default=Path("out") / "demo",
                        help="output directory (default out/demo)")
    parser.add_argument("--particles", type=int, default=200,
                        help="particles of the filter (default 200)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--frames", action="store_true",
                        help="also a PNG per frame (OUT/frames/)")
    parser.add_argument("--quiet", action="store_true", help="no progress")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from probanchor.loop.runner import RunOptions, format_summary, run
    from probanchor.resources import scenario_file

    scenario = scenario_file("shell_game")
    output = run(RunOptions(scenario=scenario, particles=args.particles, seed=args.seed,
                            out=args.out, picture_every=1, frames=args.frames,
                            progress=not args.quiet))
    print(format_summary(output.summary))
    print(f"\nVideo: {output.video}"
          + (f"; pictures: {args.out}/frames/*.png" if output.pictures else ""))
    print(f"Ask the world model: anchoring shell {args.out}")
    return 0
