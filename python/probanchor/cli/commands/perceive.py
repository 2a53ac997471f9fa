"""`anchoring perceive SCENARIO --out percepts.jsonl`: the percept stream of a scenario.

Renders the scenario and runs the perception pipeline on every frame; writes one JSON line
per frame with its percepts and the frame's ground truth (``truth``; anchoring never reads
it). Prints the frame count, percepts per frame and the pipeline's time per frame.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from probanchor.cli.options import add_frame_options


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "perceive", help="run perception on a scenario and write the percept stream (JSONL)",
        description=__doc__.split("\n\n")[1] if __doc__ else None)
    add_frame_options(parser)
    parser.add_argument("--model", type=Path, default=None, help="category model (JSON)")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from probanchor.perception import Pipeline
    from probanchor.percepts import PerceptFrame, write_percepts
    from probanchor.tabletop import Simulation, load_scenario

    scenario = load_scenario(args.scenario)
    pipeline = Pipeline(model=args.model)
    frames: list[PerceptFrame] = []
    spent = 0.0
    with Simulation(scenario, width=args.width, height=args.height, fps=args.fps,
                    seed=args.seed) as sim:
        for frame in sim:
            t0 = time.perf_counter()
            frames.append(pipeline.percept_frame(frame))
            spent += time.perf_counter() - t0
    args.out.parent.mkdir(parents=True, exist_ok=True)
    write_percepts(args.out, frames)
    n = len(frames)
    total = sum(len(f.percepts) for f in frames)
    print(f"{n} frames, {total} percepts ({total / max(n, 1):.1f} per frame), perception "
          f"{1000 * spent / max(n, 1):.1f} ms per frame -> {args.out}")
    return 0
