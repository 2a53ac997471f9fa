"""Learning data that include other files (``:- include(File).``, found relative to the including
file): the learner reads them with the engine's reader of DC files, so the clauses learned from
the occlusion example split over three files are those learned from the one file, and an error
in an included file names that file and its line."""

from __future__ import annotations

from pathlib import Path

import pytest

from bridge.errors import EngineError, LearningDataError, UnknownObjectError
from bridge.learning import LearningData
from ddc_cli_helpers import ddc

ROOT = Path(__file__).resolve().parents[1]
OCCLUDER = ROOT / "prolog" / "examples" / "learn" / "occluder.pl"


def _clauses(program: Path) -> str:
    """The learned clauses of a program: its text from the first target's comment on (the
    header and the record of the data name the files)."""
    text = program.read_text()
    return text[text.index("\n% occluder(Occluded, Occluder):t+1:"):]


def _split_occluder(folder: Path) -> Path:
    """occluder.pl as a main file (its bias and an include of the facts) whose facts are in
    ``facts/first.pl``, which includes its neighbour ``second.pl`` by its bare name."""
    lines = OCCLUDER.read_text().splitlines(keepends=True)
    bias_at = lines.index("% Declarative bias.\n")
    facts, bias = lines[:bias_at], lines[bias_at:]
    half = len(facts) // 2
    (folder / "facts").mkdir(parents=True)
    (folder / "facts" / "first.pl").write_text("".join(facts[:half]) + ":- include(second).\n")
    (folder / "facts" / "second.pl").write_text("".join(facts[half:]))
    main = folder / "main.pl"
    main.write_text(":- include('facts/first').\n" + "".join(bias))
    return main


def test_included_data_learn_the_same_clauses(tmp_path: Path) -> None:
    main = _split_occluder(tmp_path / "split")
    whole, split = tmp_path / "whole.pl", tmp_path / "split.pl"
    ddc("learn", "--seed", "0", "--quiet", OCCLUDER, "--out", whole, check=True)
    ddc("learn", "--seed", "0", "--quiet", main, "--out", split, check=True)
    assert _clauses(split) == _clauses(whole)


def test_an_error_in_an_included_file_names_it(tmp_path: Path) -> None:
    (tmp_path / "facts.pl").write_text("c(1) ~= 2.0.\n\nc(2) ~= high.\n")
    main = tmp_path / "main.pl"
    main.write_text("rv(c(_), continuous).\nlearn(c(X)).\n:- include(facts).\n")
    with pytest.raises(LearningDataError, match=rf"{tmp_path / 'facts.pl'}:3: c\(2\) ~= high"):
        LearningData([main])


def test_a_syntax_error_in_an_included_file_names_it(tmp_path: Path) -> None:
    (tmp_path / "facts.pl").write_text("c(1) ~= 2.0.\nc(2) ~= .\n")
    main = tmp_path / "main.pl"
    main.write_text("rv(c(_), continuous).\nlearn(c(X)).\n:- include(facts).\n")
    with pytest.raises(EngineError, match=rf"{tmp_path / 'facts.pl'}:2: syntax error"):
        LearningData([main])


def test_an_include_of_no_file(tmp_path: Path) -> None:
    main = tmp_path / "main.pl"
    main.write_text("rv(c(_), continuous).\n:- include(nowhere).\nlearn(c(X)).\nc(1) ~= 2.0.\n")
    with pytest.raises(UnknownObjectError, match=rf"{main}:2: no such file: nowhere"):
        LearningData([main])
    run = ddc("learn", main, "--out", tmp_path / "out.pl")
    assert run.returncode != 0 and f"{main}:2: no such file: nowhere" in run.stderr


def test_a_data_file_that_includes_itself(tmp_path: Path) -> None:
    main = tmp_path / "main.pl"
    main.write_text("learn(c(X)).\n:- include(main).\n")
    with pytest.raises(EngineError, match=rf"{main}:2: the file {main} includes itself"):
        LearningData([main])


def test_an_operator_of_the_data_applies_to_the_rest_of_its_file(tmp_path: Path) -> None:
    data = tmp_path / "data.pl"
    data.write_text(":- op(700, xfx, has).\nrv(c(_), continuous).\nlearn(c(X)).\n"
                    "c(1) ~= 2.0.\nc(2) ~= 3.0.\nc(1) has 2.\n")
    other = tmp_path / "other.pl"
    other.write_text("rv(c(_), continuous).\nlearn(c(X)).\nc(1) ~= 2.0.\nc(1) has 2.\n")
    LearningData([data]).free()
    with pytest.raises(EngineError, match=rf"{other}:4: syntax error"):
        LearningData([other])
