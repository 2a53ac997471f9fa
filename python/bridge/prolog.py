"""The one adapter between Python and Prolog: every call of the engine goes through here.

The filter (:mod:`bridge.filter`, :mod:`bridge.frames`), static programs
(:mod:`bridge.program`) and the learner (:mod:`bridge.learning`) call named Prolog
predicates with data, never Prolog source written in Python strings::

    from bridge import prolog
    from bridge.prolog import OUT
    prolog.ensure_loaded(prolog.PROLOG_DIR / "ddc/learn.pl")
    found = prolog.call("ddc_learn:learn_targets", M=module, Ts=OUT)
    found["Ts"]                                  # [{'name': ..., 'file': ..., 'line': ...}]

The arguments are given by name, in the predicate's order; each name is the name of the
argument's variable (the key of its value in the answer), an input's value a Python value that
janus converts (numbers, ``str`` as an atom, lists, dicts, tuples), an output's value
:data:`OUT`. A Prolog error arrives as the :class:`bridge.errors.DDCError` subclass of its
cause (read from the error term's formal part), its message the engine's one line (naming
``file:line`` where there is one); a goal that fails is an :class:`~bridge.errors.DDCError`
naming the predicate. This module also starts SWI-Prolog (through janus-swi) and loads the
engine's files, once each.
"""

from __future__ import annotations

import re
import threading
from pathlib import Path
from typing import Any

import janus_swi as janus

from bridge.errors import DDCError, ddc_error
from bridge.resources import prolog_dir

#: The project's Prolog files (package resources, see :mod:`bridge.resources`)
PROLOG_DIR = prolog_dir()

_lock = threading.Lock()
_consulted: set[Path] = set()
_PREDICATE = re.compile(r"[a-z][A-Za-z0-9_]*:[a-z][A-Za-z0-9_]*")
_VARIABLE = re.compile(r"_?[A-Z][A-Za-z0-9_]*")


class _Output:
    """The value of an output argument of :func:`call`."""

    def __repr__(self) -> str:
        return "OUT"


#: Marks an output argument of :func:`call` (an unbound variable in the call)
OUT: Any = _Output()


def ensure_loaded(path: str | Path, imports: bool = True) -> None:
    """Load a Prolog file once per process (``use_module`` semantics for module files;
    ``imports=False`` imports none of its predicates into ``user``)."""
    resolved = Path(path).resolve()
    with _lock:
        if resolved in _consulted:
            return
        try:
            if imports:
                janus.query_once("ensure_loaded(F)", {"F": str(resolved)})
            else:
                janus.query_once("use_module(F, [])", {"F": str(resolved)})
        except janus.PrologError as error:
            raise prolog_error(error, f"{resolved}: ") from None
        _consulted.add(resolved)


def call(predicate: str, /, **arguments: Any) -> dict[str, Any]:
    """Call ``module:name`` once with ``arguments`` (by name, in order; :data:`OUT` for an
    output); return the outputs by name (and ``truth``).

    Raises
    ------
    DDCError
        The subclass of the Prolog error's cause (:mod:`bridge.errors`), or the base class
        when the goal fails.
    ValueError
        ``predicate`` is not ``module:name`` or an argument's name is not a variable's.
    """
    if not _PREDICATE.fullmatch(predicate):
        raise ValueError(f"not a module-qualified predicate name: {predicate!r}")
    for name in arguments:
        if not _VARIABLE.fullmatch(name):
            raise ValueError(f"{predicate}: argument name {name!r} is not a Prolog variable's")
    goal = f"{predicate}({', '.join(arguments)})" if arguments else predicate
    bindings = {name: value for name, value in arguments.items() if value is not OUT}
    try:
        result = janus.query_once(goal, bindings)
    except janus.PrologError as error:
        raise prolog_error(error) from None
    if not result.get("truth", False):
        raise DDCError(f"{predicate}/{len(arguments)} failed")
    return result


def prolog_error(error: Exception, prefix: str = "") -> DDCError:
    """The :class:`~bridge.errors.DDCError` of a ``janus.PrologError``: its class picked by
    the name of the error term's formal part, its message ``prefix`` and the engine's."""
    cause = ""
    term = getattr(error, "term", None)
    if term is not None:
        found = janus.query_once("( E = error(_F, _), callable(_F) -> functor(_F, _N, _), "
                                 "atom_string(_N, C) ; C = \"\" )", {"E": term})
        cause = str(found.get("C", "")) if found.get("truth") else ""
    return ddc_error(cause, prefix + str(error).strip())


def query_once(goal: str, bindings: dict[str, Any] | None = None) -> dict[str, Any]:
    """Run the Prolog text ``goal`` once; return its bindings (``truth`` is False when it
    failed). For tests and diagnostics: the engine is called through :func:`call`."""
    return janus.query_once(goal, bindings or {})
