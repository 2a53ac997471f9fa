"""`anchoring`: the command-line app that wires perception, anchoring and reasoning together.

Each sub-command lives in its own module under ``probanchor.cli.commands`` and exposes
``register(subparsers)`` which adds its parser and sets ``func`` (taking the parsed args and
returning an exit status).
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from probanchor.cli import commands


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="anchoring", description="Probabilistic anchoring of objects on a table."
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for info in sorted(pkgutil.iter_modules(commands.__path__), key=lambda m: m.name):
        module = importlib.import_module(f"probanchor.cli.commands.{info.name}")
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt:
        return 130
    except Exception as exc:  # a clear message, not a traceback, for bad input
        if getattr(args, "debug", False):
            raise
        print(f"anchoring {args.command}: error: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
