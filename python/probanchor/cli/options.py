"""Command-line options shared by several `anchoring` sub-commands."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from bridge.engines import ENGINES  # (pure modules: no Prolog started)
from bridge.threads import DEFAULT_THREADS, MAX_DEFAULT_THREADS


def add_engine_option(parser: argparse.ArgumentParser, what: str) -> None:
    """``--engine``: the filter's engine (bridge.Filter's ``engine``)."""
    parser.add_argument("--engine", choices=ENGINES, default="auto",
                        help="the filter's engine: batched (each clause evaluated once for a "
                             "batch of particles), per_particle, or auto (the default: batched "
                             f"when the program is in its fragment){what}")


def add_threads_option(parser: argparse.ArgumentParser,
                       what: str = "Prolog threads that step the particles",
                       kind: Callable[[str], int] = int) -> None:
    """``--threads``: the filter's Prolog threads (bridge.Filter's ``threads``)."""
    parser.add_argument("--threads", type=kind, default=DEFAULT_THREADS,
                        help=f"{what} (default {DEFAULT_THREADS}: one per core available to "
                             f"this process, at most {MAX_DEFAULT_THREADS}; the particles depend "
                             "on the seed and this number, so give it where runs on different "
                             "machines must agree)")


def add_cluster_options(parser: argparse.ArgumentParser, what: str, extra: str = "") -> None:
    """``--jobs`` and ``--cluster``: where the independent jobs run (:mod:`probanchor.jobs`)."""
    parser.add_argument("--jobs", type=int, default=1,
                        help=f"worker processes, one {what} each (default 1: in this process); "
                             f"with --cluster ray, the CPUs of the local Ray{extra}")
    parser.add_argument("--cluster", default=None, metavar="BACKEND",
                        help="local (the default: spawned worker processes), ray (a local Ray "
                             "started for the run), auto or ray://HOST:PORT (an existing Ray "
                             "cluster); Ray is the optional extra: pip install '.[cluster]'")


def add_frame_options(parser: argparse.ArgumentParser) -> None:
    """The scenario argument and how its frames are rendered (render, perceive)."""
    parser.add_argument("scenario", type=Path, help="scenario YAML file")
    parser.add_argument("--out", type=Path, required=True,
                        help="output (a folder for render, a .jsonl file for perceive)")
    add_render_options(parser)


def add_render_options(parser: argparse.ArgumentParser) -> None:
    """How a scenario's frames are rendered: image size, frame rate, sensor noise seed."""
    parser.add_argument("--width", type=int, default=None, help="image width (default 320)")
    parser.add_argument("--height", type=int, default=None, help="image height (default 240)")
    parser.add_argument("--fps", type=float, default=None, help="frames per second of time")
    parser.add_argument("--seed", type=int, default=0, help="sensor noise seed")
