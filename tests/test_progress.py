"""Progress: a bar on a terminal, a few whole lines elsewhere (a pipe, a log file)."""

from __future__ import annotations

import io

from probanchor.progress import PlainProgress, progress


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_plain_lines_for_a_known_total():
    out = io.StringIO()
    bar = progress(331, desc="shell_game", unit="frame", file=out)
    assert isinstance(bar, PlainProgress)
    for _ in range(331):
        bar.update(1)
    bar.close()
    bar.close()  # once
    lines = out.getvalue().splitlines()
    assert "\r" not in out.getvalue()
    assert lines[0] == "shell_game: 0/331 frames (0 %)"
    assert len(lines) == 11  # start, 10 % ... 90 %, end
    assert lines[1].startswith("shell_game: 34/331 frames (10 %), ")
    assert lines[-1].startswith("shell_game: 331/331 frames (100 %), ")
    assert lines[-1].endswith(" s, done")


def test_plain_lines_for_an_unknown_total_and_a_postfix():
    out = io.StringIO()
    bar = PlainProgress(None, "bag", "frame", out, interval=0.0)
    bar.set_postfix_str("running 2, failed 0")
    for _ in range(3):
        bar.update(1)
    bar.close()
    lines = out.getvalue().splitlines()
    assert lines[0] == "bag: 0 frames"
    assert lines[1].startswith("bag: 1 frames, ") and lines[1].endswith(", running 2, failed 0")
    assert len(lines) == 5 and lines[-1].startswith("bag: 3 frames, ")
    # with the default interval (30 s), a quick task writes only its first and last line
    out = io.StringIO()
    bar = PlainProgress(None, "bag", "frame", out)
    for _ in range(1000):
        bar.update(1)
    bar.close()
    assert len(out.getvalue().splitlines()) == 2


def test_a_bar_on_a_terminal_and_nothing_when_not_shown():
    term = Terminal()
    bar = progress(10, desc="evaluate", unit="job", file=term)
    assert not isinstance(bar, PlainProgress)
    bar.update(10)
    bar.close()
    assert "\r" in term.getvalue() and "10/10" in term.getvalue()
    quiet = io.StringIO()
    silent = progress(10, file=quiet, show=False)
    silent.update(10)
    silent.set_postfix_str("x")
    silent.close()
    assert quiet.getvalue() == ""
