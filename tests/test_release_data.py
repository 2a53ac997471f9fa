"""When a hand lets go of what it carries: the data ``anchoring collect`` writes from its
carries (``DATA.release.pl``) and the tree the structure learner learns from them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from probanchor.ddclearn import learn
from probanchor.ddclearn.learner import evaluate
from probanchor.learning.release_data import release_path, release_points, release_text


def _carry(rng: np.random.Generator, released: bool = True) -> dict:
    """A hand closes on the object (a few frames at 0), lifts it 10-20 cm, carries it, puts it
    back down and holds it there one or two frames before it lets go."""
    top = float(rng.uniform(0.1, 0.2))
    up = list(np.linspace(0.0, top, int(rng.integers(5, 9))))
    down = list(np.linspace(top, 0.003, int(rng.integers(5, 9))))
    heights = [0.0] * int(rng.integers(1, 4)) + up + [top] * int(rng.integers(2, 10)) + down \
        + [0.002] * int(rng.integers(0, 2))
    return {"heights": [round(h, 5) for h in heights], "released": released,
            "grips": [None] * len(heights)}


def test_the_data_has_a_point_per_frame_held_and_a_release_after_the_last() -> None:
    carries = [{"heights": [0.0, 0.1, 0.0], "released": True, "grips": [None] * 3},
               {"heights": [0.0, 0.05], "released": False, "grips": [None] * 2}]
    text = release_text(carries, "anchoring collect ...")
    assert "% Command: anchoring collect ..." in text
    # three frames of the first carry, the second's last frame censored (the episode ended)
    assert sum(line.startswith("carried(") for line in text.splitlines()) == 4
    assert "released(held_0_f2):t+1." in text
    assert "released(held_0_f1)" not in text and "released(held_1_" not in text
    assert "top(held_0_f2):t ~= 0.10000." in text       # the highest it had been
    assert "pos(held_0_f1):t ~= (0.0, 0.0, 0.10000)." in text
    assert release_path("out/data.pl").name == "data.release.pl"
    # a collection's own constants, so that several can be learned from together
    assert "carried(held_games_b_0_f0):t+1." in release_text(carries, name="held_games_b")


def test_no_carry_gives_no_data_point(tmp_path) -> None:
    path = tmp_path / "d.release.pl"
    path.write_text(release_text([]))
    assert release_points(path) == 0


def test_the_learned_release_lets_go_where_the_object_was_put_back_down(tmp_path) -> None:
    """Learned from 60 random carries (nine in ten let go after one or two frames at the
    bottom: 2/3 a frame), the tree gives a release at the bottom of a carry more than an even
    chance, and one while the object is up (or not yet lifted) almost none."""
    rng = np.random.default_rng(0)
    train = tmp_path / "train.release.pl"
    train.write_text(release_text([_carry(rng, released=k % 10 != 0) for k in range(60)]))
    result = learn([train], ["released:t+1"], seed=0)
    program = tmp_path / "release.pl"
    result.write(program)
    test = tmp_path / "test.release.pl"
    # one carry: taken (0 cm), up at 15 cm, back down (2 mm) and let go
    test.write_text(release_text([{"heights": [0.0, 0.15, 0.002], "released": True,
                                   "grips": [None] * 3}]))
    scores = evaluate(program, [test], examples=True)["released:t+1"]
    taken, up, put_down = (math.exp(v) for v in scores["example_log_likelihood"])
    assert put_down > 0.5                 # P(released | back down after a lift)
    assert up > 0.99 and taken > 0.9      # P(held on | up there), P(held on | just taken)


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__, "-q"]))
