"""The command lines start light: asking for help (``anchoring --help``, ``anchoring run
--help``, ``ddc filter --help``) starts no Prolog and loads neither the simulator nor the point
cloud library; each sub-command imports what it needs when it runs. The thread default comes
from the cores available, from a module that starts no Prolog either."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from bridge.threads import MAX_DEFAULT_THREADS, available_cores, default_threads

HEAVY = ("janus_swi", "pybullet", "open3d")

#: Parses a command line (help exits), then prints which of HEAVY got imported.
RUNNER = """
import json, sys
from importlib import import_module
module, argv, heavy = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3])
main = import_module(module).main
try:
    main(argv)
except SystemExit:
    pass
print("IMPORTED " + json.dumps([m for m in heavy if m in sys.modules]))
"""


def imported_by(module: str, argv: list[str]) -> list[str]:
    proc = subprocess.run([sys.executable, "-c", RUNNER, module, json.dumps(argv),
                           json.dumps(HEAVY)], capture_output=True, text=True, timeout=120,
                          env=os.environ.copy(), check=True)
    line = [x for x in proc.stdout.splitlines() if x.startswith("IMPORTED ")][-1]
    assert "usage:" in proc.stdout
    return json.loads(line.removeprefix("IMPORTED "))


@pytest.mark.parametrize("argv", [["--help"], ["run", "--help"], ["evaluate", "--help"],
                                  ["baselines", "--help"], ["train-matching", "--help"]])
def test_anchoring_help_starts_no_prolog_nor_simulator(argv: list[str]) -> None:
    assert imported_by("probanchor.cli.anchoring_cli", argv) == []


@pytest.mark.parametrize("argv", [["--help"], ["filter", "--help"]])
def test_ddc_help_starts_no_prolog(argv: list[str]) -> None:
    assert imported_by("probanchor.cli.ddc_cli", argv) == []


def test_the_thread_default_is_one_per_available_core_capped() -> None:
    assert [default_threads(n) for n in (1, 2, 3, MAX_DEFAULT_THREADS, 64)] == \
        [1, 2, 3, MAX_DEFAULT_THREADS, MAX_DEFAULT_THREADS]
    assert default_threads(0) == 1
    if hasattr(os, "sched_getaffinity"):
        assert available_cores() == len(os.sched_getaffinity(0))
    import bridge
    from probanchor.cli.anchoring_cli import build_parser

    assert bridge.DEFAULT_THREADS == default_threads()
    assert build_parser().parse_args(["run", "x.yaml"]).threads == bridge.DEFAULT_THREADS
