"""`anchoring shell DIR` (or `--store WORLD.db`, or `--connect PORT`): a Prolog top level over
the world model a run saved in DIR, keeps in a store (also while it runs: the last whole
frame), or serves while it runs (`anchoring run --serve PORT`); `--query` answers one query
as JSON instead."""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from bridge.resources import prolog_file  # (a pure module: no Prolog started)


def register(sub: Any) -> None:
    parser = sub.add_parser("shell", help="ask a world model questions in Prolog",
                            description=__doc__)
    parser.add_argument("dir", type=Path, nargs="?",
                        help="output directory of `anchoring run` (or its world.pl)")
    parser.add_argument("--store", type=Path, default=None, metavar="WORLD.db",
                        help="the world model kept by `anchoring run --store` instead (while "
                             "the run writes it: after its last whole frame)")
    parser.add_argument("--connect", type=int, default=None, metavar="PORT",
                        help="ask the run serving its live world model on this port "
                             "(`anchoring run --serve PORT`)")
    parser.add_argument("--query", default=None, metavar="QUERY",
                        help="answer this one query and print the answers as one line of "
                             "JSON (with the frame they are for), instead of the top level")
    parser.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    given = [x for x in (args.dir, args.store, args.connect) if x is not None]
    if len(given) != 1:
        raise ValueError("give a run's output directory, --store WORLD.db or --connect PORT")
    if args.connect is not None:
        return _connected(args.connect, args.query)
    if args.store is not None:
        from probanchor.loop.store import WorldStore

        store = WorldStore.open(args.store)
        try:
            frame, time, text = store.world()
        finally:
            store.close()
        world = Path(tempfile.mkdtemp(prefix="anchoring-shell-")) / "world.pl"
        world.write_text(text, encoding="utf-8")
        if args.query is None:
            print(f"{args.store}: the world model after frame {frame} ({time:.3f} s), the last "
                  "whole frame stored when read", file=sys.stderr, flush=True)
    else:
        world = args.dir / "world.pl" if args.dir.is_dir() else args.dir
    if not world.exists():
        raise FileNotFoundError(f"{world}: no world file (run `anchoring run ... --out DIR`)")
    from probanchor.loop.live import prolog_string, swipl_path

    swipl = swipl_path()
    if args.query is not None:
        query = prolog_string(args.query.strip().removesuffix("."))
        goal = (f"consult({prolog_string(str(prolog_file('shell', 'world_ask.pl')))}), "
                f"anchoring_world_ask:print_answers({query}, [])")
        done = subprocess.run([swipl, "-q", "-g", goal, "-t", "halt",
                               str(prolog_file("shell/world.pl")), str(world)],
                              capture_output=True, text=True)
        line = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else ""
        if done.returncode != 0 or not line:
            raise RuntimeError(f"{world}: swipl failed: {done.stderr.strip()}")
        print(line.strip())
        return 1 if "error" in json.loads(line) else 0
    argv = [swipl, "-g", "anchoring_world:banner", str(prolog_file("shell/world.pl")), str(world)]
    os.execv(swipl, argv)
    return 0  # pragma: no cover - execv does not return


def _connected(port: int, query: str | None) -> int:
    """Ask a run's query server: one query as JSON, or a prompt that asks each query typed."""
    from probanchor.loop.live import LiveError, ask

    if query is not None:
        try:
            reply = ask(query, port)
        except LiveError as exc:
            print(json.dumps({"error": str(exc)}))
            return 1
        print(json.dumps(reply))
        return 0 if "error" not in reply else 1
    print(f"Asking the run serving on port {port}; each answer is for its last whole frame. "
          "End with Ctrl-D.", file=sys.stderr)
    text = ""
    while True:
        try:
            line = input("?- " if not text else "|    ")
        except EOFError:
            print()
            return 0
        text += line + "\n"
        if not text.strip().endswith("."):
            continue
        query, text = text.strip(), ""
        try:
            reply = ask(query, port)
        except LiveError as exc:
            print(f"ERROR: {exc}")
            continue
        print(_toplevel_text(reply))


def _toplevel_text(reply: dict[str, Any]) -> str:
    """An answer as the Prolog top level writes it, under the frame it is for."""
    head = f"% frame {reply.get('frame')} ({reply.get('time', 0.0):.3f} s)"
    if "error" in reply:
        return f"{head}\nERROR: {reply['error']}"
    answers = reply.get("answers", [])
    if not answers:
        return f"{head}\nfalse."
    lines = [", ".join(f"{k} = {_value_text(v)}" for k, v in answer.items()) or "true"
             for answer in answers]
    more = " (more answers left out)" if reply.get("truncated") else ""
    return head + "\n" + " ;\n".join(lines) + "." + more


def _value_text(value: Any) -> str:
    """A JSON answer value as Prolog-like text: atoms bare, lists bracketed."""
    if isinstance(value, list):
        return "[" + ", ".join(_value_text(v) for v in value) + "]"
    return str(value)
