"""The errors of the DDC system, as Python sees them: one base class, a subclass per cause.

Every error that comes from Prolog (an exception a call through the adapter
:mod:`bridge.prolog` raises) is a :class:`DDCError`; its class says what kind of thing went
wrong, read from the Prolog error term's formal part (:attr:`DDCError.cause`):

- :class:`ProgramError`: ``ddc(Cause, File:Line)``, a DC program (what a clause says, or a
  clause that misbehaved as it ran);
- :class:`LearningDataError`: ``ddc_learn(Cause, Where)``, learning data;
- :class:`FrameFileError`: ``ddc_belief(frame(File, Line, Cause))``, a frame file (also a
  ``ValueError``);
- :class:`UnknownObjectError`: ``existence_error/2``, a filter freed or never made, a program
  not loaded;
- :class:`BadArgumentError`: ``instantiation_error``, ``type_error/2``, ``domain_error/2``,
  ``syntax_error/1``, ...: what was asked (a text that does not parse or is not ground, a value
  of the wrong type; also a ``ValueError``: the filter's input texts, ``ddc_bridge.pl``, raise
  ``syntax_error/1``, ``instantiation_error`` and ``type_error(weighed_observation, Obs)``
  with a message naming the item); a program or data file that does not parse is
  ``syntax_error/1`` too (the reader of DC files, ``ddc/lang/ddc_source.pl``), its message
  ``file:line: syntax error: ...``;
- :class:`NotPermittedError`: ``permission_error/3``, e.g. a second undo.

Anything else (a Prolog goal that failed, a resource error) is the base class itself. The
message is the DDC system's, one line, naming ``file:line`` where there is one. The names the
bridge used before, :class:`bridge.FilterError` (the filter) and :class:`EngineError`, are the
base class ("engine" names the filter's batched or per-particle implementation alone:
docs/architecture.md, Words). A pure module: it does not start Prolog.
"""

from __future__ import annotations


class DDCError(RuntimeError):
    """An error of the DDC system; :attr:`cause` is the Prolog error's formal name
    (``"ddc"``, ``"existence_error"``, ...; ``""`` when there is no Prolog error term)."""

    def __init__(self, message: str, cause: str = "") -> None:
        super().__init__(message)
        self.cause = cause


#: The base class's earlier name (kept for code that catches it by that name)
EngineError = DDCError


class ProgramError(DDCError):
    """An error in a DC program (its text, or one of its clauses as it ran): ``file:line``."""


class LearningDataError(DDCError):
    """An error in learning data (facts, background knowledge, declarative bias)."""


class FrameFileError(DDCError, ValueError):
    """A frame file that cannot be read; the message is ``file:line: cause``."""


class UnknownObjectError(DDCError, LookupError):
    """Something named does not exist: a filter freed or never made, a program, a file."""


class BadArgumentError(DDCError, ValueError):
    """An argument the DDC system cannot take: a text that does not parse, a term that is not
    ground, a value of the wrong type or outside its domain."""


class NotPermittedError(DDCError):
    """An operation the DDC system refuses in the state it is in (e.g. a second undo)."""


#: the Prolog error's formal name -> the class of its Python error
CAUSES: dict[str, type[DDCError]] = {
    "ddc": ProgramError,
    "ddc_learn": LearningDataError,
    "ddc_belief": FrameFileError,
    "existence_error": UnknownObjectError,
    "permission_error": NotPermittedError,
    **dict.fromkeys(("instantiation_error", "uninstantiation_error", "type_error",
                     "domain_error", "representation_error", "syntax_error"),
                    BadArgumentError),
}


def error_class(cause: str) -> type[DDCError]:
    """The class of an error whose Prolog formal name is ``cause`` (the base for others)."""
    return CAUSES.get(cause, DDCError)


def ddc_error(cause: str, message: str) -> DDCError:
    """The error of class :func:`error_class` (``cause``) with ``message``."""
    return error_class(cause)(message, cause)


def prefixed(error: BaseException, prefix: str) -> DDCError:
    """``error`` with ``prefix`` before its message (what was being done: ``"query: "``), of
    the same class and cause; an exception that is no :class:`DDCError` (janus could not
    convert a value) becomes the base class."""
    if isinstance(error, DDCError):
        return type(error)(prefix + str(error), error.cause)
    return DDCError(prefix + str(error))
