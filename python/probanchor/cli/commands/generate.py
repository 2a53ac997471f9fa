"""`anchoring generate shell-game --containers K --swaps S --seed N`: a random shell game.

Writes the scenario as YAML (to ``--out FILE``, or to standard output) built with
``probanchor.tabletop.generate.shell_game``: K containers in a row, a ball hidden under one of them
while a hand covers the camera, S random swaps, then every container lifted in turn.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "generate", help="generate a scenario (a random shell game)",
        description=__doc__.split("\n\n")[1] if __doc__ else None)
    parser.add_argument("kind", choices=["shell-game"], help="what to generate")
    parser.add_argument("--containers", type=int, default=3, help="2 to 5 (default 3)")
    parser.add_argument("--swaps", type=int, default=3, help="number of swaps (default 3)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    parser.add_argument("--fps", type=float, default=15.0, help="frames per second (15)")
    parser.add_argument("--out", type=Path, default=None, help="YAML file (default: stdout)")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from probanchor.tabletop.generate import shell_game

    builder = shell_game(args.containers, args.swaps, args.seed, args.fps)
    scenario = builder.build()  # validates
    text = f"# anchoring generate shell-game --containers {args.containers} --swaps " \
           f"{args.swaps} --seed {args.seed}\n" + builder.to_yaml()
    if args.out is None:
        sys.stdout.write(text)
    else:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(text, encoding="utf-8")
        print(f"{scenario.name}: {len(scenario.objects)} objects, {len(scenario.events)} "
              f"events, {scenario.end_time():.1f} s -> {args.out}", file=sys.stderr)
    return 0
