"""Every plunit file under tests/prolog runs as one pytest test; a failing plunit test fails it."""

from __future__ import annotations

from pathlib import Path

import pytest

from plunit_runner import ROOT, run_plunit

PLUNIT_FILES = sorted((ROOT / "tests" / "prolog").glob("test_*.pl"))


@pytest.mark.parametrize("path", PLUNIT_FILES, ids=lambda p: p.name)
def test_plunit_file(path: Path) -> None:
    result = run_plunit(path)
    assert result.returncode == 0, f"plunit failed in {path}:\n{result.stdout}\n{result.stderr}"


def test_runner_reports_a_failing_plunit_test(tmp_path: Path) -> None:
    failing = tmp_path / "test_failing.pl"
    failing.write_text(
        ":- use_module(library(plunit)).\n"
        ":- begin_tests(meant_to_fail).\n"
        "test(one_is_two) :- 1 =:= 2.\n"
        ":- end_tests(meant_to_fail).\n"
    )
    result = run_plunit(failing)
    assert result.returncode != 0
    assert "one_is_two" in result.stdout + result.stderr


def test_runner_reports_a_plunit_file_that_does_not_load(tmp_path: Path) -> None:
    broken = tmp_path / "test_broken.pl"
    broken.write_text(
        ":- use_module(library(plunit)).\n"
        ":- begin_tests(half_loaded).\n"
        "test(loads) :- true.\n"
        "test(syntax_error) :- foo(.\n"
        ":- end_tests(half_loaded).\n"
    )
    result = run_plunit(broken)
    assert result.returncode != 0
    assert "Syntax error" in result.stdout + result.stderr


def test_runner_reports_a_passing_plunit_test(tmp_path: Path) -> None:
    passing = tmp_path / "test_passing.pl"
    passing.write_text(
        ":- use_module(library(plunit)).\n"
        ":- begin_tests(meant_to_pass).\n"
        "test(two) :- 2 =:= 1 + 1.\n"
        ":- end_tests(meant_to_pass).\n"
    )
    assert run_plunit(passing).returncode == 0
