"""The error raised for a scenario that cannot be used."""

from __future__ import annotations


class ScenarioError(ValueError):
    """A bad scenario: the message names the file, the line and the cause."""

    def __init__(self, cause: str, source: str | None = None, line: int | None = None) -> None:
        self.cause = cause
        self.source = source
        self.line = line
        where = source or "<scenario>"
        if line is not None:
            where = f"{where}:{line}"
        super().__init__(f"{where}: {cause}")
