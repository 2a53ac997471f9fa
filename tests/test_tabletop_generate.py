"""Random shell games: valid, reproducible, and the ball travels with its container."""

from __future__ import annotations

import pytest

from cli.anchoring_cli import main
from tabletop import Simulation, load_scenario
from tabletop.generate import shell_game


def test_same_seed_same_game_other_seed_other_game():
    a = shell_game(4, 5, seed=7).to_yaml()
    assert a == shell_game(4, 5, seed=7).to_yaml()
    assert a != shell_game(4, 5, seed=8).to_yaml()


@pytest.mark.parametrize(("k", "s"), [(2, 0), (3, 3), (5, 10)])
def test_generated_games_are_valid(k, s):
    scenario = shell_game(k, s, seed=1).build()
    kinds = [e.kind for e in scenario.events]
    assert kinds.count("swap") == s and kinds.count("lift") == k
    assert len(scenario.objects) == k + 1


def test_ball_follows_its_container_and_is_revealed():
    scenario = shell_game(3, 3, seed=2).build()
    hider = next(e.params["container"] for e in scenario.events if e.kind == "put_under")
    first_lift = min(e.at for e in scenario.events if e.kind == "lift")
    with Simulation(scenario, fps=2, noise=False) as sim:
        frames = list(sim)
    during = [f for f in frames if 4.5 <= f.time < first_lift]
    assert during
    for f in during:
        ball = f.truth["objects"]["ball_1"]
        cont = f.truth["objects"][hider]
        assert ball["hidden_by"] == hider and not ball["visible"]
        assert abs(ball["position"][0] - cont["position"][0]) < 0.02
    assert frames[-1].truth["objects"]["ball_1"]["visible"]


def test_generate_command_writes_a_loadable_file(tmp_path, capsys):
    out = tmp_path / "game.yaml"
    assert main(["generate", "shell-game", "--containers", "3", "--swaps", "4", "--seed",
                 "5", "--out", str(out)]) == 0
    scenario = load_scenario(out)
    assert [e.kind for e in scenario.events].count("swap") == 4
    assert main(["generate", "shell-game", "--containers", "9"]) == 1
    assert "containers must be 2 to 5" in capsys.readouterr().err
