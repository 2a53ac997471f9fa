"""Command-line options shared by several `anchoring` sub-commands."""

from __future__ import annotations

import argparse
from pathlib import Path


def add_frame_options(parser: argparse.ArgumentParser) -> None:
    """The scenario argument and how its frames are rendered (render, perceive)."""
    parser.add_argument("scenario", type=Path, help="scenario YAML file")
    parser.add_argument("--out", type=Path, required=True,
                        help="output (a folder for render, a .jsonl file for perceive)")
    parser.add_argument("--width", type=int, default=None, help="image width (default 320)")
    parser.add_argument("--height", type=int, default=None, help="image height (default 240)")
    parser.add_argument("--fps", type=float, default=None, help="frames per second of time")
    parser.add_argument("--seed", type=int, default=0, help="sensor noise seed")
