"""The only place that talks to Prolog (janus-swi): the DDC filter and static programs.

Importing the package does not start Prolog: :data:`DEFAULT_THREADS` (:mod:`bridge.threads`),
the filter engines' names (:mod:`bridge.engines`) and the places of the Prolog files
(:mod:`bridge.resources`) come from pure modules, and the names that need Prolog
(:class:`Filter`, :func:`load`, ...) are imported when first used, so that a command line can
be parsed (``anchoring --help``) without starting Prolog.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from bridge.threads import DEFAULT_THREADS

#: name -> the module that defines it (imported, and with it Prolog started, on first use)
_LAZY = {
    "terms": "bridge.terms",  # the module itself (Python value -> Prolog term text)
    "Filter": "bridge.filter",
    "FilterError": "bridge.filter",
    "StepResult": "bridge.filter",
    "ZeroWeightWarning": "bridge.filter",
    "DDCError": "bridge.errors",  # the base of the DDC system's errors; a subclass per cause
    "EngineError": "bridge.errors",  # (DDCError's earlier name)
    "errors": "bridge.errors",
    "Program": "bridge.program",
    "QueryResult": "bridge.program",
    "load": "bridge.program",
}

__all__ = ["DEFAULT_THREADS", "DDCError", "EngineError", "Filter", "FilterError", "Program",
           "QueryResult", "StepResult", "ZeroWeightWarning", "errors", "load", "terms"]


def __getattr__(name: str) -> Any:
    if name not in _LAZY:
        raise AttributeError(f"module 'bridge' has no attribute {name!r}")
    module = importlib.import_module(_LAZY[name])
    value = module if module.__name__ == f"bridge.{name}" else getattr(module, name)
    globals()[name] = value
    return value


if TYPE_CHECKING:
    from bridge import errors, terms
    from bridge.errors import DDCError, EngineError
    from bridge.filter import Filter, FilterError, StepResult, ZeroWeightWarning
    from bridge.program import Program, QueryResult, load
