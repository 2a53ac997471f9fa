"""Every plunit file under tests/prolog (a folder per subsystem, as prolog/ddc/ has) runs as one
pytest test; a failing plunit test fails it."""

from __future__ import annotations

from pathlib import Path

import pytest

from plunit_runner import ROOT, run_plunit

PLUNIT_FILES = sorted((ROOT / "tests" / "prolog").rglob("test_*.pl"))


@pytest.mark.parametrize("path", PLUNIT_FILES,
                         ids=lambda p: str(p.relative_to(ROOT / "tests" / "prolog")))
def test_plunit_file(path: Path) -> None:
    result = run_plunit(path)
    assert result.returncode == 0, f"plunit failed in {path}:\n{result.stdout}\n{result.stderr}"


def plunit_file(folder: Path, unit: str, *clauses: str) -> Path:
    """A plunit file in ``folder`` with one unit of the given clauses (one a line)."""
    path = folder / f"test_{unit}.pl"
    path.write_text(":- use_module(library(plunit)).\n"
                    f":- begin_tests({unit}).\n"
                    + "".join(f"{clause}\n" for clause in clauses)
                    + f":- end_tests({unit}).\n")
    return path


def test_runner_reports_a_failing_plunit_test(tmp_path: Path) -> None:
    result = run_plunit(plunit_file(tmp_path, "meant_to_fail", "test(one_is_two) :- 1 =:= 2."))
    assert result.returncode != 0
    assert "one_is_two" in result.stdout + result.stderr


def test_runner_reports_a_plunit_file_that_does_not_load(tmp_path: Path) -> None:
    result = run_plunit(plunit_file(tmp_path, "half_loaded",
                                    "test(loads) :- true.", "test(syntax_error) :- foo(."))
    assert result.returncode != 0
    assert "Syntax error" in result.stdout + result.stderr


def test_runner_reports_a_passing_plunit_test(tmp_path: Path) -> None:
    passing = plunit_file(tmp_path, "meant_to_pass", "test(two) :- 2 =:= 1 + 1.")
    assert run_plunit(passing).returncode == 0
