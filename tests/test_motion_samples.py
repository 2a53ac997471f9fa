"""The motion samples of a collection labelled from ground truth (motion_samples)."""

from __future__ import annotations

import pytest

from probanchor.learning.experience import AnchorView, Episode, EpisodeFrame
from probanchor.learning.motion_samples import episode_samples


def rolling(under: str | None) -> Episode:
    """A ball rolling 1 cm a frame along x, hidden in frames 4-8 (behind the box, or under it
    when ``under`` names it) and seen again in 9-10; the box stands still in front of it."""
    frames = []
    for k in range(11):
        x = 0.01 * k if under is None else 0.03
        seen = not 4 <= k <= 8
        truth = {"objects": {
            "ball_1": {"position": [x, 0.0, 0.03], "visible": seen,
                       "under": under if not seen else None},
            "box_1": {"position": [0.06, -0.1, 0.06], "visible": True}}}
        views = {"ball-1": AnchorView("ball-1", "ball", seen, (x, 0.0, 0.03)),
                 "box-1": AnchorView("box-1", "box", True, (0.06, -0.1, 0.06))}
        frames.append(EpisodeFrame(k, k / 15, views, truth))
    return Episode("rolling", frames, {"ball-1": "ball_1", "box-1": "box_1"})


def test_an_object_hidden_under_nothing_gives_a_coasting_gap_from_its_true_ends() -> None:
    """Behind the box: its true velocity before it vanished (1 cm a frame), how far it truly
    went until it was seen again (6 cm) and the frames between (6): what the theory must
    predict over the whole time it is hidden."""
    (gap,) = episode_samples(rolling(None)).rows["coast_gap"]
    assert gap[:4] == pytest.approx([0.01, 0.0, 0.06, 0.0]) and gap[4] == 6


def test_an_object_under_a_container_gives_no_coasting_gap() -> None:
    assert episode_samples(rolling("box_1")).rows["coast_gap"] == []


def test_a_data_file_that_does_not_exist_is_named_as_such(tmp_path) -> None:
    from probanchor.learning.motion_samples import read_samples

    with pytest.raises(FileNotFoundError, match=r"nope\.pl: no such data file"):
        read_samples([tmp_path / "nope.pl"])
    (tmp_path / "old.pl").write_text("% data without samples beside it\n")
    with pytest.raises(FileNotFoundError, match=r"old\.motion\.json: no motion samples beside"):
        read_samples([tmp_path / "old.pl"])


def test_a_malformed_samples_file_names_the_file_and_the_row(tmp_path) -> None:
    """A row not of its kind's shape is an error naming the file, the kind and the row (fitted
    around, it made the coasting "NOT FITTED: no samples"); a file that is not JSON names its
    line; a coasting gap written before the change of height was kept still reads."""
    import json

    from probanchor.learning.motion_samples import read_samples

    data = tmp_path / "d.pl"
    data.write_text("% data\n")
    samples = tmp_path / "d.motion.json"
    good = {"coast_gap": [[0.0, 0.0, 0.01, 0.0, 5, 0.001], [0.0, 0.0, 0.01, 0.0, 5]],
            "reappear": [[0.01, 0.0, 0.0]], "hold": [0.03], "heights": [["mug", 0.1]]}
    samples.write_text(json.dumps(good))
    assert len(read_samples([data]).rows["coast_gap"]) == 2
    samples.write_text(json.dumps({**good, "coast_gap": [good["coast_gap"][0],
                                                        [0.0, 0.0, 0.01, "x", 5, 0.001]]}))
    with pytest.raises(ValueError, match=r"d\.motion\.json: coast_gap row 1: .*'x'.* is not"):
        read_samples([data])
    samples.write_text(json.dumps({**good, "hold": [None]}))
    with pytest.raises(ValueError, match=r"d\.motion\.json: hold row 0: None is not a number"):
        read_samples([data])
    samples.write_text('{"coast_gap": [1,\n')
    with pytest.raises(ValueError, match=r"d\.motion\.json:2: not JSON"):
        read_samples([data])
