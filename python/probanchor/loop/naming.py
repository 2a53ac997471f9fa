"""Anchor symbols (``ball-1``) and the Prolog atoms the theory of occlusion sees (``ball_1``)."""

from __future__ import annotations

import re

_UNSAFE = re.compile(r"[^a-z0-9_]")


def symbol_atom(symbol: str) -> str:
    """``ball-1`` -> ``ball_1``: lower case, every other character than [a-z0-9_] becomes ``_``,
    and a leading digit or underscore is prefixed with ``a_`` so the atom needs no quotes."""
    atom = _UNSAFE.sub("_", symbol.lower())
    if not atom or not atom[0].isalpha():
        atom = "a_" + atom
    return atom


def category_atom(category: str) -> str:
    """A category name as an unquoted Prolog atom (``coffee mug`` -> ``coffee_mug``)."""
    return symbol_atom(category)
