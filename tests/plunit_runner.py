"""Run a plunit file through the project's ``swipl`` and report pass/fail with its output."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def swipl_executable() -> str:
    """The SWI-Prolog the project set up (beside the venv's python), else the one on PATH."""
    beside = Path(sys.executable).parent / "swipl"
    if beside.exists():
        return str(beside)
    found = shutil.which("swipl")
    if not found:
        raise RuntimeError("no swipl found: run `make setup`")
    return found


def run_plunit(path: Path, timeout: float = 600) -> subprocess.CompletedProcess[str]:
    """Load ``path`` and run all its plunit tests; exit status 0 only if every test passed and
    nothing printed an error (a clause that does not load, e.g. a syntax error in a test, is
    skipped by the loader: ``--on-error=status`` makes ``halt`` exit 1 after it)."""
    goal = "(catch(run_tests, E, (print_message(error, E), fail)) -> halt ; halt(1))"
    env = dict(os.environ)
    return subprocess.run(
        [swipl_executable(), "-q", "--on-error=status", "-g", goal, "-t", "halt(2)", str(path)],
        cwd=ROOT, env=env, capture_output=True, text=True, timeout=timeout,
    )
