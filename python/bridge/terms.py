"""Python values -> Prolog term text, so that callers never hand-build Prolog strings.

The mapping (Python -> Prolog text), used by :func:`to_term`:

=====================================  =============================================
Python                                 Prolog
=====================================  =============================================
``bool``                               the atoms ``true`` / ``false``
``int``, numpy integer                 integer
``float``, numpy float                 float (``1.0Inf``, ``-1.0Inf``, ``1.5NaN`` for
                                       the special values)
``str``                                an atom, quoted when needed (``ball_1`` stays
                                       ``ball_1``; ``"Box 1"`` becomes ``'Box 1'``)
``tuple`` of 2 or more                 a comma term ``(A,B,C)`` (DDC's multivariate
                                       values); a 1-tuple is its element
``list``, 1-D numpy array              a list ``[A,B,C]``
:class:`Var` (``Var("X")``)            the variable ``X``
:class:`Text` (``Text("f(X) > 0")``)   the text itself, unchanged
:class:`Compound`                      ``name(Arg,...)``; the operators in
                                       :data:`INFIX` print infix: ``A ~= B``
=====================================  =============================================

Helpers build the usual filter inputs::

    observation(fact("pos", "ball_1"), (0.31, 0.12, 0.05))
        -> observation(pos(ball_1))~=(0.31,0.12,0.05)
    fact("observed", "ball_1")               -> observed(ball_1)
    action(fact("move", "box_1", (0.1, 0, 0))) -> action(move(box_1,(0.1,0,0)))

Where a *list of terms* is expected (``Filter.step``), a plain ``str`` item is taken as Prolog
term text as written (``"observed(ball_1)"``); any other item goes through :func:`to_term`.
Strings *inside* structured values are atoms.

The reverse direction (Prolog values read back from particles) is documented in
:mod:`bridge.filter`.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from dataclasses import dataclass
from numbers import Integral, Real
from typing import Any

import numpy as np

#: Binary operators printed infix (``A op B``) by :func:`to_term`.
INFIX = frozenset(
    {"~=", "~", ":=", "<-", ":", "=", "\\=", "==", "\\==", "is", "<", ">", "=<", ">=",
     "=:=", "=\\=", "+", "-", "*", "/", "//", "**", "^", "mod", ",", ";", "->"}
)

_PLAIN_ATOM = re.compile(r"[a-z][A-Za-z0-9_]*\Z")
_VARIABLE = re.compile(r"[A-Z_][A-Za-z0-9_]*\Z")


@dataclass(frozen=True)
class Var:
    """A Prolog variable in a goal (``Var("X")`` -> ``X``)."""

    name: str

    def __post_init__(self) -> None:
        if not _VARIABLE.match(self.name):
            raise ValueError(f"not a Prolog variable name: {self.name!r}")

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True)
class Text:
    """Prolog term text used verbatim inside a structured value."""

    text: str

    def __str__(self) -> str:
        return self.text


@dataclass(frozen=True)
class Compound:
    """A compound term ``name(args...)``; build it with :func:`fact`."""

    name: str
    args: tuple[Any, ...]

    def __post_init__(self) -> None:
        if not self.args:
            raise ValueError(f"compound {self.name!r} needs at least one argument (use an atom)")

    def __str__(self) -> str:
        return to_term(self)


def quote_atom(name: str) -> str:
    """The atom ``name`` as Prolog text, quoted only when it has to be."""
    if _PLAIN_ATOM.match(name):
        return name
    escaped = name.replace("\\", "\\\\").replace("'", "\\'").replace("\n", "\\n")
    escaped = escaped.replace("\t", "\\t")
    return f"'{escaped}'"


def _float(value: float) -> str:
    if math.isnan(value):
        return "1.5NaN"
    if math.isinf(value):
        return "1.0Inf" if value > 0 else "-1.0Inf"
    text = repr(float(value))
    if "e" in text and "." not in text.split("e")[0]:  # 1e-05 -> 1.0e-05 (Prolog needs the dot)
        mantissa, exponent = text.split("e")
        text = f"{mantissa}.0e{exponent}"
    return text


def _arg(value: Any) -> str:
    """An argument position: operators and negative numbers need brackets to parse back."""
    text = to_term(value)
    if isinstance(value, Compound) and value.name in INFIX and len(value.args) == 2:
        return f"({text})"
    return text


def to_term(value: Any) -> str:
    """Prolog text for a Python value (see the module docstring for the mapping)."""
    if isinstance(value, Var | Text):
        return str(value)
    if isinstance(value, bool | np.bool_):
        return "true" if value else "false"
    if isinstance(value, Integral):
        return str(int(value))
    if isinstance(value, Real):
        return _float(float(value))
    if isinstance(value, str):
        return quote_atom(value)
    if isinstance(value, tuple):
        if not value:
            raise ValueError("an empty tuple has no Prolog term")
        if len(value) == 1:
            return to_term(value[0])
        return "(" + ",".join(_arg(v) for v in value) + ")"
    if isinstance(value, np.ndarray):
        if value.ndim != 1:
            raise ValueError(f"only 1-D arrays map to Prolog lists, got shape {value.shape}")
        return to_term(value.tolist())
    if isinstance(value, list):
        return "[" + ",".join(_arg(v) for v in value) + "]"
    if isinstance(value, Compound):
        if value.name in INFIX and len(value.args) == 2:
            left, right = value.args
            if value.name == ",":
                return f"{_arg(left)},{_arg(right)}"
            return f"{_arg(left)} {value.name} {_arg(right)}"
        return quote_atom(value.name) + "(" + ",".join(_arg(a) for a in value.args) + ")"
    raise TypeError(f"no Prolog term for a {type(value).__name__}: {value!r}")


def item_text(item: Any) -> str:
    """One element of an observation/action list: ``str`` is term text, else :func:`to_term`."""
    if isinstance(item, str):
        text = item.strip()
        if text.endswith("."):
            text = text[:-1].rstrip()
        if not text:
            raise ValueError("empty term text")
        return text
    return to_term(item)


def list_text(items: Iterable[Any]) -> str:
    """Prolog list text for a sequence of terms given as text or as structured values."""
    return "[" + ",".join(item_text(i) for i in items) + "]"


def fact(name: str, *args: Any) -> Compound | str:
    """``fact("observed", "ball_1")`` -> ``observed(ball_1)``; no args gives the atom."""
    if not args:
        return name
    return Compound(name, tuple(args))


def observation(term: Any, value: Any) -> Compound:
    """``observation(Term) ~= Value``, the evidence literal the filter weights by."""
    inner = Text(item_text(term)) if isinstance(term, str) else term
    return Compound("~=", (Compound("observation", (inner,)), value))


def action(term: Any) -> Compound:
    """``action(Term)``; ``term`` is term text or a structured value."""
    inner = Text(item_text(term)) if isinstance(term, str) else term
    return Compound("action", (inner,))
