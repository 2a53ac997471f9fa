"""Python values -> Prolog term text (bridge.terms), checked by parsing the text in SWI-Prolog."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bridge import prolog, terms

_READ = "op(700, xfx, ddc_terms_test:'~='), term_string(_T, S, [module(ddc_terms_test)])"


def reads_as(text: str, expected: str) -> bool:
    """Does SWI-Prolog read ``text`` as the same term as the hand-written ``expected``?"""
    result = prolog.query_once(
        f"{_READ}, term_string(_E, X, [module(ddc_terms_test)]), (_T =@= _E -> R = 1 ; R = 0)",
        {"S": text, "X": expected},
    )
    return result["truth"] and result["R"] == 1


def atom_read(text: str) -> str:
    result = prolog.query_once(f"{_READ}, atom(_T), atom_string(_T, N)", {"S": text})
    assert result["truth"], text
    return result["N"]


def test_atoms_are_quoted_only_when_needed() -> None:
    assert terms.to_term("ball_1") == "ball_1"
    assert terms.to_term("Box 1") == "'Box 1'"
    assert terms.to_term("it's") == "'it\\'s'"
    assert terms.to_term("~=") == "'~='"
    for name in ["ball_1", "Box 1", "it's", "a\\b", "", "_x", "Xy", "new\nline"]:
        assert atom_read(terms.to_term(name)) == name


def test_numbers_tuples_and_lists_read_back_as_the_same_term() -> None:
    value = [1, -2, 0.5, 1e-05, -3.25e20, np.float64(2.5), np.int32(7), True, (1, 2.5, "a")]
    assert reads_as(terms.to_term(value), "[1,-2,0.5,0.00001,-3.25e20,2.5,7,true,(1,2.5,a)]")
    assert terms.to_term((4,)) == "4"
    assert terms.to_term(np.array([1.0, 2.0])) == "[1.0,2.0]"
    special = prolog.query_once("term_string(T, S)", {"S": terms.to_term([math.inf, -math.inf,
                                                                           math.nan])})["T"]
    assert special[0] == math.inf and special[1] == -math.inf and math.isnan(special[2])


def test_helpers_build_observations_facts_and_actions() -> None:
    obs = terms.observation(terms.fact("pos", "ball_1"), (0.31, 0.12, -0.05))
    assert terms.to_term(obs) == "observation(pos(ball_1)) ~= (0.31,0.12,-0.05)"
    assert reads_as(terms.to_term(obs), "'~='(observation(pos(ball_1)), ','(0.31,','(0.12,-0.05)))")
    assert terms.to_term(terms.observation("up", "wall")) == "observation(up) ~= wall"
    assert terms.to_term(terms.fact("observed", "ball_1")) == "observed(ball_1)"
    assert terms.fact("null") == "null"
    move = terms.action(terms.fact("move", "box_1", (0.1, 0, 0)))
    assert terms.to_term(move) == "action(move(box_1,(0.1,0,0)))"
    assert terms.to_term(terms.action("left")) == "action(left)"


def test_variables_text_and_operators() -> None:
    x = terms.Var("X")
    read = terms.fact("~=", terms.Text("pos(b):t"), (x, terms.Var("_"), terms.Var("_")))
    goal = terms.fact(",", read, terms.fact(">", x, 0.3))
    assert terms.to_term(goal) == "(pos(b):t ~= (X,_,_)),(X > 0.3)"
    assert reads_as(terms.to_term(goal), "','('~='(:(pos(b),t), (X,_,_)), >(X, 0.3))")
    assert terms.to_term(terms.fact("-", "a", -1)) == "a - -1"
    assert reads_as("a - -1", "-(a, -1)")
    with pytest.raises(ValueError):
        terms.Var("lower")


def test_list_text_takes_strings_as_term_text() -> None:
    items = ["observed(ball_1).", terms.fact("observed", "box_1")]
    assert terms.list_text(items) == "[observed(ball_1),observed(box_1)]"
    with pytest.raises(ValueError, match="empty"):
        terms.item_text("  ")
    with pytest.raises(TypeError, match="dict"):
        terms.to_term({"a": 1})
    with pytest.raises(ValueError):
        terms.to_term(())
