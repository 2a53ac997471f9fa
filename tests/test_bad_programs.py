"""Bad programs: every error names the file, the line and the cause, on both filter engines,
and nothing a refused program did stays behind (its operators, a crashed process)."""

from __future__ import annotations

import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import bridge
from bridge import Filter, FilterError
from ddc_cli_helpers import ddc

ROOT = Path(__file__).resolve().parents[1]
WUMPUS = ROOT / "prolog" / "examples" / "filter" / "wumpus.pl"

# (program text, query, the message after "FILE:LINE: ", its line)
STATIC_CASES = [
    ("x ~ D := true.\n", "x ~= 1", r"the distribution is unbound", 1),
    ("x ~ val(1).\np := x ~= V, V >= pos.\n", "p", r"`pos/0' is not a function", 2),
    ("x, y.\n", "x", r"No permission to modify static procedure `\(','\)/2'", 1),
    ("p := observed().\n", "p", r"observed\(\) has no arguments", 1),
    ("p := X is 1/0, X > 0.\n", "p", r"zero_divisor", 1),
    ("a ~ val(1).\n\nq := a ~= V, Y is V/0, Y > 1.\n", "q", r"zero_divisor", 3),
    ("p := throw(foo).\n", "p", r"the program threw foo", 1),
    ("p := atom_length(1, a).\n", "p", r"Type error: `integer' expected", 1),
    ("p := p.\n", "p", r"the body of p starts by proving p itself", 1),
    ("q(1) := true.\np(X) := p(X), q(X).\n", "p(1)", r"starts by proving p\(.*\) itself", 2),
    ("h:t+1 := h:t+1.\n", "true", r"starts by proving h:t\+1 itself", 1),
    (":- op(0, xfx, ~).\nx ~ val(1).\n", "x ~= 1", r"syntax error", 2),
    (":- op(700, zfz, foo).\n", "true", r"Domain error: `operator_specifier'", 1),
    ("observed(a):t+1.\n", "true", r"not a clause head: observed\(a\):t\+1", 1),
]


@pytest.mark.parametrize(("text", "query", "cause", "line"), STATIC_CASES,
                         ids=[c[0].splitlines()[-1][:30] for c in STATIC_CASES])
def test_a_bad_program_is_an_error_naming_file_line_and_cause(
        tmp_path: Path, text: str, query: str, cause: str, line: int) -> None:
    program = tmp_path / "bad.pl"
    program.write_text(text)
    run = ddc("query", program, query)
    assert run.returncode == 1, run.stdout
    assert re.search(re.escape(f"{program}:{line}: ") + ".*" + cause, run.stderr), run.stderr


def test_a_query_of_a_predicate_the_program_does_not_define_is_an_error(tmp_path: Path) -> None:
    empty = tmp_path / "empty.pl"
    empty.write_text("")
    run = ddc("query", empty, "p")
    assert run.returncode == 1 and "Unknown procedure: p/0" in run.stderr


def test_a_refused_program_leaves_the_reader_as_it_was(tmp_path: Path) -> None:
    bad, good = tmp_path / "bad.pl", tmp_path / "good.pl"
    bad.write_text(":- op(0, xfx, ~).\nx ~ val(1).\n")
    good.write_text("x ~ val(1).\n")
    with pytest.raises(bridge.DDCError, match=r"bad.pl:2: syntax error"):
        bridge.load(bad)
    assert bridge.load(good).query("x ~= 1").probability == 1.0


def test_an_operator_of_a_program_applies_to_the_rest_of_its_file_only(tmp_path: Path) -> None:
    own, other = tmp_path / "own.pl", tmp_path / "other.pl"
    own.write_text(":- op(700, xfx, likes).\nmary likes wine := true.\n")
    other.write_text("p := true.\nq := mary likes wine.\n")
    assert bridge.load(own).query("likes(mary, wine)").probability == 1.0
    with pytest.raises(bridge.DDCError, match=r"other.pl:2: syntax error"):
        bridge.load(other)


def test_a_call_to_a_predicate_defined_nowhere_is_a_warning_with_its_line(
        tmp_path: Path, capfd: pytest.CaptureFixture[str]) -> None:
    program = tmp_path / "typo.pl"
    program.write_text("q(1) := true.\np := qq(1).\n")
    assert bridge.load(program).query("p").probability == 0.0
    err = capfd.readouterr().err
    assert f"{program}:2: qq/1 is called here but defined nowhere" in err
    program.write_text(":- dynamic(qq/1).\nq(1) := true.\np := qq(1).\n")
    bridge.load(program)
    assert "defined nowhere" not in capfd.readouterr().err


def test_the_programs_own_catch_handles_its_own_error(tmp_path: Path) -> None:
    program = tmp_path / "catching.pl"
    program.write_text("p := catch(X is 1/0, _, fail), X > 0.\np := true.\n"
                       # the catcher asks for the error as Prolog raises it, in another clause
                       "half(X, Y) :- Y is X/0.\n"
                       "r := catch(half(1, _), error(evaluation_error(zero_divisor), _), true).\n")
    loaded = bridge.load(program)
    assert loaded.query("p").probability == 1.0
    assert loaded.query("r").probability == 1.0


# Run-time errors inside a filter step: the same message from both engines.
FILTER_CASES = [
    ("x:0 ~ val(1).\nx:t+1 ~ val(Y) := x:t ~= X, Y is X/0.\n", 2, r"zero_divisor"),
    ("x:0 ~ val(1).\nx:t+1 ~ val(Y) := x:t ~= X, atom_length(X, bad), Y = X.\n", 2,
     r"Type error: `integer' expected, found `bad'"),
    ("x:0 ~ val(1).\nx:t+1 ~ val(1) := throw(oops).\n", 2, r"the program threw oops"),
    ("x:0 ~ val(1).\nx:t+1 ~ D := true.\n", 2, r"the distribution is unbound"),
    ("x:0 ~ val(1).\nflag(W):t+1 ~ val(1) := true.\n", 2, r"is not ground"),
    ("x:0 ~ val(1).\nbad:t+1 := x:t ~= X, Y is X/0, Y > 0.\n"
     "x:t+1 ~ val(X) := x:t ~= X, \\+ bad:t+1.\n", 2, r"zero_divisor"),
    ("x:0 ~ val(1).\nx:t+1 ~ gaussian(X, V) := x:t ~= X, V is X - 2.\n", 2,
     r"Invalid distribution gaussian\(1,-1\): the variance is negative"),
    ("x:0 ~ val(1).\nx:t+1 ~ finite([P:a, 0.6:b]) := x:t ~= 1, P is 0.5.\n", 2,
     r"the probabilities sum to 1.1"),
    ("x:0 ~ val(1).\nx:t+1 ~ val(2) := x:t ~= 1.\nx:t+1 ~ val(3) := x:t ~= X, X > 0.\n", 2,
     r"two clauses define x:1 in the same world: this one and the one at .*:3"),
]


@pytest.mark.parametrize(("text", "line", "cause"), FILTER_CASES,
                         ids=[c[0].splitlines()[1][:30] for c in FILTER_CASES])
def test_an_error_at_run_time_names_its_clause_on_both_engines(
        tmp_path: Path, text: str, line: int, cause: str) -> None:
    program = tmp_path / "theory.pl"
    program.write_text(text)
    messages = []
    for engine in ("per_particle", "batched"):
        f = Filter(program, particles=20, seed=3, threads=1, engine=engine)
        assert f.engine == engine
        with pytest.raises(FilterError) as error:
            f.step([])
        message = str(error.value)
        assert re.search(re.escape(f"{program}:{line}: ") + ".*(" + cause + ")", message), message
        assert f.time == 0                     # the step was undone: the filter is usable
        messages.append(re.sub(r"_[0-9]+", "_", message))   # variable names aside
    assert messages[0] == messages[1]


def _run_python(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=300, cwd=ROOT)


def test_brackets_nested_too_deep_are_an_error_not_a_crash(tmp_path: Path) -> None:
    """In a subprocess: without the guard the process dies with SIGSEGV."""
    deep, fine = tmp_path / "deep.pl", tmp_path / "fine.pl"
    deep.write_text("x ~ val(" + "f(" * 20000 + "1" + ")" * 20000 + ").\n")
    fine.write_text("x ~ val(" + "(" * 9999 + "1" + ")" * 9999 + ").\n")   # 10,000 deep
    result = _run_python(f"""
        import bridge
        from bridge import Filter, FilterError
        deep = "f(" * 20000 + "1" + ")" * 20000
        try:
            bridge.load({str(deep)!r})
        except bridge.DDCError as e:
            print("program:", e)
        print("fine:", bridge.load({str(fine)!r}).query("x ~= 1").probability)
        program = bridge.load({str(fine)!r})
        try:
            program.query(deep)
        except bridge.DDCError as e:
            print("query:", e)
        f = Filter({str(WUMPUS)!r}, particles=50, seed=1)
        try:
            f.step(["observation(up) ~= " + deep], actions=["action(null)"])
        except FilterError as e:
            print("observation:", str(e)[-80:])
        f.step(["observation(up) ~= wall"], actions=["action(null)"])
        print("after:", f.time)
    """)
    assert result.returncode == 0, result.stderr[-2000:]
    out = result.stdout
    assert f"program: {deep}:1: brackets nest deeper than 10,000" in out
    assert "fine: 1.0" in out
    assert "query: query: brackets nest deeper than 10,000" in out
    assert "observation:" in out and "brackets nest deeper than 10,000" in out
    assert "after: 1" in out
