"""Malformed percept streams: the project's own error with file and line, never a Python one."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from percept_helpers import ball_percept
from probanchor.percepts import PerceptError, read_percepts


def stream(tmp_path: Path, *lines: object) -> Path:
    path = tmp_path / "s.jsonl"
    path.write_text("\n".join(json.dumps(line) for line in lines) + "\n")
    return path


def good_percept() -> dict:
    return ball_percept(0.0, 0.1).to_json()


def test_percepts_that_are_not_a_list_name_the_line(tmp_path: Path) -> None:
    path = stream(tmp_path, {"frame": 0, "time": 0, "percepts": [good_percept()]},
                  {"frame": 1, "time": 0.1, "percepts": 5})
    with pytest.raises(PerceptError, match=rf"{path}:2: .*'percepts' must be a list, not int"):
        list(read_percepts(path))
    skipped: list[str] = []
    assert [f.frame for f in read_percepts(path, skipped)] == [0]
    assert len(skipped) == 1 and f"{path}:2" in skipped[0]


@pytest.mark.parametrize(("bad", "cause"), [
    ({"category": ["ball", "cup"]}, "'category' must be an object"),
    ({"category": None}, "'category' must be an object"),
    ({"position": "here"}, "could not convert"),
])
def test_a_bad_percept_is_dropped_with_its_line_and_cause(tmp_path: Path, bad: dict,
                                                          cause: str) -> None:
    path = stream(tmp_path, {"frame": 0, "time": 0,
                             "percepts": [good_percept(), {**good_percept(), **bad}, 7]})
    (frame,) = read_percepts(path)
    assert len(frame.percepts) == 1
    assert len(frame.rejected) == 2
    assert f"{path}:1: percept 1:" in frame.rejected[0] and cause in frame.rejected[0]
    assert "a percept is a JSON object, not int" in frame.rejected[1]


@pytest.mark.parametrize(("bad", "cause"), [
    ({"category": {"ball": 0.9, "cup": 0.9, "box": 0.9}}, "category probabilities sum to 2.7"),
    ({"colour_names": "blue"}, "'colour_names' must be a list of names, not str"),
])
def test_a_percept_that_claims_too_much_is_dropped(tmp_path: Path, bad: dict,
                                                   cause: str) -> None:
    path = stream(tmp_path, {"frame": 0, "time": 0,
                             "percepts": [good_percept(), {**good_percept(), **bad}]})
    (frame,) = read_percepts(path)
    assert len(frame.percepts) == 1 and cause in frame.rejected[0], frame.rejected


@pytest.mark.parametrize(("second", "cause"), [
    ({"frame": 0, "time": 0.0}, "frame 0 follows frame 0: frame numbers must increase"),
    ({"frame": 1, "time": -0.1}, "time -0.1 is before the previous frame's 0.0"),
    ({"frame": 1, "time": "NaN"}, "time is nan"),
])
def test_a_duplicated_or_reordered_frame_is_skipped_with_its_line(
        tmp_path: Path, second: dict, cause: str) -> None:
    path = stream(tmp_path, {"frame": 0, "time": 0.0, "percepts": [good_percept()]},
                  {**second, "percepts": [good_percept()]},
                  {"frame": 2, "time": 0.2, "percepts": [good_percept()]})
    with pytest.raises(PerceptError, match=rf"{path}:2: not a percept frame: {cause}"):
        list(read_percepts(path))
    skipped: list[str] = []
    assert [f.frame for f in read_percepts(path, skipped)] == [0, 2]
    assert len(skipped) == 1 and cause in skipped[0]
