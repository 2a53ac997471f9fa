"""Progress of a long task, shown as a bar on a terminal and as a few plain lines elsewhere.

On a terminal :func:`progress` gives a tqdm bar, redrawn in place. Anywhere else (a pipe, a
log file, CI) a bar's carriage-return redraws would fill the log with hundreds of lines, so it
gives a :class:`PlainProgress` instead: one line when the task starts, one each time another
tenth of it is done (or, when the total is not known, every ``interval`` seconds), and one at
the end, each complete with a newline::

    shell_game: 0/331 frames
    shell_game: 34/331 frames (10 %), 2.3 s
    ...
    shell_game: 331/331 frames (100 %), 21.8 s, done

Both have tqdm's ``update``, ``set_postfix_str`` and ``close``.
"""

from __future__ import annotations

import sys
import time
from typing import Any, TextIO


class PlainProgress:
    """Progress as at most about a dozen plain lines (see the module doc).

    Parameters
    ----------
    total : int or None
        Units to do (None when not known).
    desc : str
        What is done, at the start of each line.
    unit : str
        The unit's name (``frame``, ``job``); an ``s`` is added when counting.
    file : text stream
        Where the lines go (standard error by default).
    steps : int
        Lines between start and end when the total is known (10: one per tenth).
    interval : float
        Seconds between lines when the total is not known.
    """

    def __init__(self, total: int | None, desc: str = "", unit: str = "it",
                 file: TextIO | None = None, steps: int = 10, interval: float = 30.0) -> None:
        self.total = total
        self.desc = desc
        self.unit = unit
        self.file = file if file is not None else sys.stderr
        self.steps = max(1, steps)
        self.interval = interval
        self.n = 0
        self.postfix = ""
        self._start = time.monotonic()
        self._last_line = self._start
        self._next_step = 1
        self._closed = False
        self._line(self._count())

    def _count(self) -> str:
        units = f"{self.unit}s"
        if self.total is None:
            return f"{self.n} {units}"
        percent = f" ({100 * self.n // self.total} %)" if self.total else ""
        return f"{self.n}/{self.total} {units}{percent}"

    def _line(self, text: str) -> None:
        prefix = f"{self.desc}: " if self.desc else ""
        post = f", {self.postfix}" if self.postfix else ""
        print(f"{prefix}{text}{post}", file=self.file, flush=True)
        self._last_line = time.monotonic()

    def update(self, n: int = 1) -> None:
        """``n`` more units done."""
        self.n += n
        now = time.monotonic()
        if self.total:
            due = self.n * self.steps >= self._next_step * self.total
            if due and self.n < self.total:
                while self._next_step * self.total <= self.n * self.steps:
                    self._next_step += 1
                self._line(f"{self._count()}, {now - self._start:.1f} s")
        elif self.total is None and now - self._last_line >= self.interval:
            self._line(f"{self._count()}, {now - self._start:.1f} s")

    def set_postfix_str(self, text: str, refresh: bool = True) -> None:
        """Text added to the lines from now on (tqdm's; shown on the next line written)."""
        self.postfix = text

    def close(self) -> None:
        """The last line (once)."""
        if self._closed:
            return
        self._closed = True
        self._line(f"{self._count()}, {time.monotonic() - self._start:.1f} s, done")


class _Silent:
    """No progress at all (``show=False``)."""

    def update(self, n: int = 1) -> None:
        pass

    def set_postfix_str(self, text: str, refresh: bool = True) -> None:
        pass

    def close(self) -> None:
        pass


def progress(total: int | None, desc: str = "", unit: str = "it", show: bool = True,
             file: TextIO | None = None, **tqdm_options: Any) -> Any:
    """A progress display: a tqdm bar when ``file`` (standard error by default) is a terminal,
    else a :class:`PlainProgress`; nothing when ``show`` is false.

    ``tqdm_options`` go to the bar only (``leave``, ``dynamic_ncols``...).
    """
    if not show:
        return _Silent()
    stream = file if file is not None else sys.stderr
    isatty = getattr(stream, "isatty", None)
    if isatty is not None and isatty():
        from tqdm import tqdm

        return tqdm(total=total, desc=desc, unit=unit, file=stream, **tqdm_options)
    return PlainProgress(total, desc, unit, stream)
