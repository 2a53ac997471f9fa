"""`anchoring record SCENARIO --bag OUT.mcap`: the simulator's RGB-D frames as a ROS bag.

Writes what a real camera's driver would record (colour, depth, camera info, the camera pose
on /tf_static) plus the ground truth on topics of its own, in ROS 1 (.bag) or ROS 2 (.mcap,
.db3) format by the suffix, so that `anchoring run --bag OUT.mcap` plays the scenario from its
recording.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from probanchor.cli.options import add_render_options


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "record", help="write a scenario's RGB-D frames and ground truth as a ROS bag",
        description=__doc__.split("\n\n")[1] if __doc__ else None)
    parser.add_argument("scenario", type=Path, help="scenario YAML file")
    parser.add_argument("--bag", type=Path, required=True,
                        help="the bag to write: OUT.mcap or OUT.db3 (ROS 2), OUT.bag (ROS 1)")
    add_render_options(parser)
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from probanchor.bags import write_bag
    from probanchor.tabletop import Simulation, load_scenario

    scenario = load_scenario(args.scenario)
    started = time.perf_counter()
    with Simulation(scenario, width=args.width, height=args.height, fps=args.fps,
                    seed=args.seed) as sim:
        n = write_bag(args.bag, sim)
    print(f"{n} frames in {time.perf_counter() - started:.1f} s, "
          f"{args.bag.stat().st_size / 1e6:.1f} MB -> {args.bag}")
    return 0
