"""The occlusion games ``anchoring collect`` plays are the generator's games of this version:
a game file written by an earlier version is written again, its cached percepts removed."""

from __future__ import annotations

from pathlib import Path

from probanchor.learning.collect import game_files
from probanchor.tabletop.generate import occlusion_game


def test_a_stale_game_is_written_again_and_its_percepts_dropped(tmp_path: Path) -> None:
    games, percepts = tmp_path / "games", tmp_path / "percepts"
    first = game_files(games, 2, 0)
    percepts.mkdir()
    for path in first:
        (percepts / f"{path.stem}_seed0.jsonl").write_text("{}\n")
    # game 1 as an earlier generator wrote it
    first[1].write_text(first[1].read_text().replace("occlusion_game_1", "an older game"))
    again = game_files(games, 2, 0)
    assert again == first
    assert again[1].read_text() == occlusion_game(1).to_yaml()
    assert (percepts / "occlusion_game_000_seed0.jsonl").exists()       # up to date: kept
    assert not (percepts / "occlusion_game_001_seed0.jsonl").exists()   # stale: perceived again
