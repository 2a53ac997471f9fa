"""Fuzzing the program loader: whatever the text, loading it, querying it and stepping a
filter over it gives a program or the project's own error naming the file, never another
exception, a crash or a changed reader.

Deterministic (``derandomize``): the same few hundred programs on every run.
"""

from __future__ import annotations

import re
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import bridge
from bridge import Filter, FilterError

# Pieces of DC programs, put together at random ("token soup") ...
TOKENS = ["x", "y", "p(X)", "q(1)", "h:t+1", "h:t", "h:0", "~", "~=", ":=", "val(1)",
          "gaussian(0, 1)", "finite([0.5:a, 0.5:b])", "uniform([1,2])", "D", "X", "Y", ",",
          ";", "->", "\\+", "is", "1/0", "X+1", "(", ")", "[", "]", "{", "}", ":-", ".",
          "op(700, xfx, ~)", "op(0, xfx, :=)", "dynamic(q/1)", "persistent(h/0)",
          "first_applicable(x/0)", "findall(A, q(A), L)", "true(0.5)", "true", "fail",
          "observation(x)", "throw(e)", "'quoted atom'", '"a string"', "0'a", "% c\n", "\n",
          "/* c */", "f()", "f(f(f(1)))", "p := p", "pos", "V >= pos", "atom_length(X, Y)"]
soup = st.lists(st.sampled_from(TOKENS), min_size=1, max_size=30).map(" ".join)

# ... and clauses that are nearly right (a head, an arrow, a body of literals).
HEADS = ["x", "y", "p(A)", "h:t+1", "h:0", "h:t", "q(A):t+1", "A", "1", "f()", "observed(a):t"]
DISTS = ["val(1)", "val(A)", "gaussian(0, 1)", "gaussian(A, -1)", "finite([0.5:a, 0.5:b])",
         "finite([2:a])", "uniform([])", "D", "poisson(A)", "beta(1, 1)", "nonsense(1)"]
LITERALS = ["true", "x ~= 1", "y ~= A", "h:t ~= A", "q(A)", "p(A)", "A is 1/0", "A > 1",
            "\\+ x ~= 1", "(x ~= 1 ; y ~= 2)", "findall(B, q(B), L)", "length(L, A)",
            "A = D", "throw(oops)", "atom_length(A, 3)", "undefined_thing(A)",
            "observation(x) ~= A", "true(0.3)", "A >= pos", "between(1, 3, A)"]
clause = st.builds(
    lambda head, kind, dist, body: (
        f"{head} ~ {dist}" if kind == "rv" else head)
    + (f" := {', '.join(body)}." if body else "."),
    st.sampled_from(HEADS), st.sampled_from(["rv", "der"]), st.sampled_from(DISTS),
    st.lists(st.sampled_from(LITERALS), max_size=4))
clauses = st.lists(clause, min_size=1, max_size=6).map("\n".join)

LINE_ERROR = re.compile(r":\d+: ")


def check_program(path: Path, text: str) -> None:
    path.write_text(text)
    try:
        program = bridge.load(path)
    except bridge.DDCError as error:
        message = str(error)
        assert str(path) in message and LINE_ERROR.search(message), message
        return
    for query in ("true", "x ~= 1", "h:t ~= A"):
        try:
            program.query(query, samples=20, seed=0)
        except bridge.DDCError:
            pass
    for engine in ("auto", "per_particle"):
        try:
            f = Filter(path, particles=8, seed=0, threads=1, engine=engine)
        except FilterError:
            continue
        try:
            f.step(["observation(x) ~= 1"])
        except FilterError:
            assert f.time == 0                 # a failed step changes nothing
        f.close()


def check_reader_unchanged(path: Path) -> None:
    path.write_text("x ~ val(1).\nsure := x ~= 1.\n")
    assert bridge.load(path).query("sure").probability == 1.0


FUZZ = settings(max_examples=250, deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture,
                                       HealthCheck.too_slow])


@FUZZ
@given(text=st.one_of(soup, clauses))
def test_any_program_text_loads_or_is_an_error_naming_file_and_line(
        tmp_path: Path, text: str) -> None:
    check_program(tmp_path / "fuzzed.pl", text)
    check_reader_unchanged(tmp_path / "sentinel.pl")
