"""`Filter.step` refuses what is not a step's input, naming the item, and keeps its particles:
values of a type no clause of the program weighs (an atom or a tuple where a number is weighed,
two numbers or a million where three are, the atom nan, a NaN), and items that are no terms (a
dict, a number, a list). A value of the right type outside a distribution's support is still a
zero-weight event, as before."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

from bridge import Filter, terms
from bridge.filter import FilterError, ZeroWeightWarning
from plunit_runner import ROOT

RANDOM_WALK = ROOT / "prolog" / "examples" / "filter" / "random_walk.pl"
TOO = ROOT / "prolog" / "too.pl"


def _unchanged(f: Filter) -> None:
    assert f.frames == 0 and f.time == 0 and f.zero_weight_events == 0
    assert np.allclose(f.weights, 1 / f.particles)


@pytest.mark.parametrize("value, shown", [
    ("foo", "foo"),
    ("nan", "nan"),                                   # the atom nan, not a number
    ((1.0, 2.0), r"\(1\.0,2\.0\)"),
    (float("nan"), r"1\.5NaN"),
    (float("inf"), r"1\.0Inf"),
    ([0.0] * 1_000_000, "a list of 1,000,000 values"),
])
def test_a_value_of_the_wrong_type_is_refused_naming_the_item(value, shown: str) -> None:
    with Filter(RANDOM_WALK, particles=50, seed=1, threads=1) as f, warnings.catch_warnings():
        warnings.simplefilter("error", ZeroWeightWarning)
        observation = f"observation(y) ~= {value}" if value == "nan" \
            else terms.observation("y", value)
        with pytest.raises(FilterError, match=r"random_walk\.pl: step 1: observation 2 "
                                              r"\(observation\(y\) ~= .*\): a value of the wrong "
                                              r"type: observation\(y\) takes a finite number "
                                              rf"\(random_walk\.pl:9\), not {shown}$"):
            f.step(["true", observation])
        _unchanged(f)
        f.step([terms.observation("y", 0.73)])       # and it steps on
        assert f.frames == 1


@pytest.mark.parametrize("value", ["foo", (0.1, 0.2), (0.1, 0.2, 0.3, 0.4), [0.0] * 1000])
def test_a_position_must_have_three_numbers_although_a_catch_all_clause_takes_anything(
        value) -> None:
    with Filter(TOO, particles=20, seed=1, threads=1) as f:
        with pytest.raises(FilterError, match=r"observation 3 .*: a value of the wrong type: "
                                              r"observation\(pos\(ball_1\)\) takes 3 finite "
                                              r"numbers, a tuple \(X1,\.\.\.\) or a list "
                                              r"\(too_base\.pl:\d+\)"):
            f.step(["object(ball_1)", "observed(ball_1)",
                    terms.observation(terms.fact("pos", "ball_1"), value)])
        _unchanged(f)


@pytest.mark.parametrize("observations, message", [
    ({"a": 1}, r"observations: \{'a': 1\} is a dict; give a list of terms"),
    ({"observed(a)"}, r"observations: \{'observed\(a\)'\} is a set"),
    (42, "observations: 42 is an int"),
    ([42], r"observation 1 \(42\): an int is not a term"),
    (["observed(a)", [1, 2]], r"observation 2 \(\[1, 2\]\): a list is not a term"),
    ([None], r"observation 1 \(None\): a NoneType is not a term"),
])
def test_items_that_are_no_terms_are_refused(observations, message: str) -> None:
    with Filter(RANDOM_WALK, particles=20, seed=1, threads=1) as f:
        with pytest.raises(FilterError, match=message):
            f.step(observations)
        with pytest.raises(FilterError, match=r"action 1 \(3\.5\): a float is not a term"):
            f.step([terms.observation("y", 0.5)], actions=[3.5])
        _unchanged(f)


def test_a_value_of_the_right_type_outside_the_support_is_still_weight_zero(
        tmp_path: Path) -> None:
    program = tmp_path / "coin.pl"
    program.write_text("side:0 ~ finite([0.5:heads, 0.5:tails]).\n"
                       "side:t+1 ~ val(S) := side:t ~= S.\n"
                       "observation(side):t+1 ~ finite([0.9:S, 0.1:edge]) := side:t+1 ~= S.\n"
                       "observation(count):t+1 ~ poisson(3) := true.\n")
    with Filter(program, particles=20, seed=1, threads=1) as f:
        with pytest.warns(ZeroWeightWarning):
            f.step(["observation(side) ~= rim"])          # any value: none has it
        with pytest.raises(FilterError, match="observation 1 .*takes a finite number"):
            f.step(["observation(count) ~= many"])
        f.step(["observation(count) ~= 2"])
        assert f.time == 1
