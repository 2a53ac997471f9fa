"""`anchoring shell DIR` (or `--store WORLD.db`): a Prolog top level over the world model a
run saved in DIR, or kept in a store."""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
from pathlib import Path
from typing import Any

from bridge.resources import prolog_file  # (a pure module: no Prolog started)


def register(sub: Any) -> None:
    parser = sub.add_parser("shell", help="ask a saved world model questions in Prolog",
                            description=__doc__)
    parser.add_argument("dir", type=Path, nargs="?",
                        help="output directory of `anchoring run` (or its world.pl)")
    parser.add_argument("--store", type=Path, default=None, metavar="WORLD.db",
                        help="the world model kept by `anchoring run --store` instead")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    if (args.dir is None) == (args.store is None):
        raise ValueError("give a run's output directory or --store WORLD.db")
    if args.store is not None:
        from probanchor.app.store import WorldStore

        store = WorldStore.open(args.store)
        try:
            text = store.world_text()
        finally:
            store.close()
        world = Path(tempfile.mkdtemp(prefix="anchoring-shell-")) / "world.pl"
        world.write_text(text, encoding="utf-8")
    else:
        world = args.dir / "world.pl" if args.dir.is_dir() else args.dir
    if not world.exists():
        raise FileNotFoundError(f"{world}: no world file (run `anchoring run ... --out DIR`)")
    swipl = str(Path(sys.executable).parent / "swipl")
    if not os.path.exists(swipl):
        swipl = shutil.which("swipl") or "swipl"
    argv = [swipl, "-g", "world:banner", str(prolog_file("world.pl")), str(world)]
    os.execv(swipl, argv)
    return 0  # pragma: no cover - execv does not return
