"""Run the ``ddc`` command in the test's own process: its argument parsing, output and exit
status, without starting Python and Prolog again for every call."""

from __future__ import annotations

import io
from contextlib import redirect_stderr, redirect_stdout
from dataclasses import dataclass
from pathlib import Path

from probanchor.cli.ddc_cli import main


@dataclass
class Run:
    """What one ``ddc`` command printed and returned."""

    returncode: int
    stdout: str
    stderr: str


def ddc(*args: str | Path, check: bool = False) -> Run:
    """``ddc ARGS``; with ``check``, a non-zero exit status fails the test."""
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        code = main([str(a) for a in args])
    result = Run(code, out.getvalue(), err.getvalue())
    if check:
        assert result.returncode == 0, result.stderr
    return result
