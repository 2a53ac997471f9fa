"""bridge.includes: a DC file with the files it includes (transitively, each relative to the
file that includes it), as the DDC system's reader finds them, and a digest of them all."""

from __future__ import annotations

from pathlib import Path

import pytest

from bridge.errors import UnknownObjectError
from bridge.includes import digest_with_includes, with_includes

ROOT = Path(__file__).resolve().parents[1]


def _theory(tmp_path: Path) -> Path:
    """theory.pl includes parts/base.pl, which includes more.pl beside it (parts/more.pl)."""
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "more.pl").write_text("b:0 ~ val(2).\n")
    (tmp_path / "parts" / "base.pl").write_text("a:0 ~ val(1).\n:- include(more).\n")
    (tmp_path / "parts" / "notes.pl").write_text("c:0 ~ val(3).\n")   # included by nobody
    theory = tmp_path / "theory.pl"
    theory.write_text(":- include('parts/base').\nx:0 ~ val(0).\n")
    return theory


def test_the_files_are_the_theory_and_its_includes_in_reading_order(tmp_path: Path) -> None:
    theory = _theory(tmp_path)
    assert with_includes(theory) == [theory.resolve(), (tmp_path / "parts/base.pl").resolve(),
                                     (tmp_path / "parts/more.pl").resolve()]
    shipped = with_includes(ROOT / "prolog" / "too.pl")
    assert shipped[0].name == "too.pl"
    assert {p.name for p in shipped[1:]} >= {"too_base.pl", "too_motion.pl"}


def test_editing_an_included_file_changes_the_digest(tmp_path: Path) -> None:
    theory = _theory(tmp_path)
    before = digest_with_includes(theory)
    (tmp_path / "parts" / "notes.pl").write_text("c:0 ~ val(4).\n")   # not included
    assert digest_with_includes(theory) == before
    (tmp_path / "parts" / "more.pl").write_text("b:0 ~ val(3).\n")    # included by an included file
    assert digest_with_includes(theory) != before


def test_a_missing_include_names_the_directive(tmp_path: Path) -> None:
    theory = tmp_path / "theory.pl"
    theory.write_text("x:0 ~ val(0).\n:- include(nowhere).\n")
    with pytest.raises(UnknownObjectError, match=r"theory\.pl:2"):
        with_includes(theory)
