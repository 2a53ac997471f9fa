"""The DDC system from Python: bridge.load and Program.query/expectation/distribution."""

from __future__ import annotations

from pathlib import Path

import pytest

from bridge import DDCError, Program, QueryResult, load

EXAMPLES = Path(__file__).resolve().parents[1] / "prolog" / "examples"


def write(tmp_path: Path, name: str, text: str) -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def test_load_returns_a_program_handle() -> None:
    program = load(EXAMPLES / "tutorial.pl")
    assert isinstance(program, Program)
    assert program.path == (EXAMPLES / "tutorial.pl").resolve()
    result = program.query("coin ~= true", samples=100)
    assert isinstance(result, QueryResult)
    assert result.samples == 100
    assert result.probability == pytest.approx(0.2, abs=1e-12)


def test_same_seed_same_answer_bit_for_bit() -> None:
    program = load(EXAMPLES / "tutorial.pl")
    a = program.query("drawn(1) ~= X, color(X) ~= black", samples=500, seed=3)
    b = program.query("drawn(1) ~= X, color(X) ~= black", samples=500, seed=3)
    c = program.query("drawn(1) ~= X, color(X) ~= black", samples=500, seed=4)
    assert a == b
    assert a.probability != c.probability


def test_evidence_and_stderr_and_ess() -> None:
    program = load(EXAMPLES / "church.pl")
    result = program.query("breast_cancer ~= true", evidence="positive_mammogram ~= true",
                           samples=3000, seed=1)
    assert 0 < result.stderr < 0.02
    assert 0 < result.ess < 3000  # the evidence is weighted: the ESS shows its cost
    assert abs(result.probability - 0.0776397) < 5 * result.stderr


def test_programs_side_by_side(tmp_path: Path) -> None:
    a = load(write(tmp_path, "a.pl", "x ~ finite([0.25:1, 0.75:2]).\n"))
    b = load(write(tmp_path, "b.pl", "x ~ finite([0.5:1, 0.5:2]).\n"))
    assert a.query("x ~= 1", samples=10).probability == pytest.approx(0.25)
    assert b.query("x ~= 1", samples=10).probability == pytest.approx(0.5)


def test_bad_program_names_file_line_and_cause(tmp_path: Path) -> None:
    path = write(tmp_path, "bad.pl", "a ~ val(1).\nb ~ gaussian(0, -2).\n")
    with pytest.raises(DDCError, match=r"bad\.pl:2: .*variance"):
        load(path)
    path = write(tmp_path, "typo.pl", "a ~ val(1).\nb ~ gausian(0, 2).\n")
    with pytest.raises(DDCError, match=r"typo\.pl:2: .*unknown distribution"):
        load(path)
    path = write(tmp_path, "syntax.pl", "a ~ val(1).\nb ~ val(2) := a ~= 1\nc ~ val(3).\n")
    with pytest.raises(DDCError, match=r"syntax\.pl:\d: syntax error"):
        load(path)
    with pytest.raises(DDCError, match="no such file"):
        load(tmp_path / "missing.pl")


def test_bad_reload_keeps_the_previous_program(tmp_path: Path) -> None:
    path = write(tmp_path, "p.pl", "x ~ finite([0.25:1, 0.75:2]).\n")
    program = load(path)
    path.write_text("x ~ finite([0.25:1, 0.75:2).\n")
    with pytest.raises(DDCError, match=r"p\.pl:1"):
        program.reload()
    assert program.query("x ~= 1", samples=10).probability == pytest.approx(0.25)
    path.write_text("x ~ finite([0.5:1, 0.5:2]).\n")
    assert program.reload().query("x ~= 1", samples=10).probability == pytest.approx(0.5)


def test_query_errors() -> None:
    program = load(EXAMPLES / "tutorial.pl")
    with pytest.raises(DDCError, match="syntax error"):
        program.query("coin ~= ")
    with pytest.raises(DDCError, match="weight 0 in every sample"):
        program.query("coin ~= true", evidence="nballs ~= 11", samples=50)


def test_runtime_errors_name_the_clause(tmp_path: Path) -> None:
    program = load(write(tmp_path, "r.pl", "a ~ finite([0.5:1, 0.5:2]).\n"
                                           "b ~ val(1) := a ~= 1.\nb ~ val(2) := a ~= _.\n"))
    with pytest.raises(DDCError, match=r"r\.pl:2: two clauses define b .*r\.pl:3 "):
        program.query("b ~= X", samples=50, seed=1)


def test_expectation_and_distribution() -> None:
    program = load(EXAMPLES / "example1.pl")
    mean = program.expectation("X", "nballs ~= N, X is N * 2", samples=3000, seed=2)
    assert abs(mean.probability - 11.0) < 5 * mean.stderr
    dist = program.distribution("X", "n2 ~= X", samples=3000, seed=2)
    assert [v for _, v in dist] == ["1", "5", "6"]
    assert abs(sum(p for p, _ in dist) - 1.0) < 1e-9
