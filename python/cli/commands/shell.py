"""`anchoring shell DIR`: a Prolog top level over the world model a run saved in DIR."""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[3]


def register(sub: Any) -> None:
    parser = sub.add_parser("shell", help="ask a saved world model questions in Prolog",
                            description=__doc__)
    parser.add_argument("dir", type=Path, help="output directory of `anchoring run`")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    world = args.dir / "world.pl" if args.dir.is_dir() else args.dir
    if not world.exists():
        raise FileNotFoundError(f"{world}: no world file (run `anchoring run ... --out DIR`)")
    swipl = str(Path(sys.executable).parent / "swipl")
    if not os.path.exists(swipl):
        swipl = shutil.which("swipl") or "swipl"
    argv = [swipl, "-g", "world:banner", str(ROOT / "prolog" / "world.pl"), str(world)]
    os.execv(swipl, argv)
    return 0  # pragma: no cover - execv does not return
