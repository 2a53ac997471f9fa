"""A flood of spurious percepts: anchors seen in one frame only stay out of the reasoning (a new
anchor is reasoned about once it is confirmed, perceived in a second frame), so the frames
after the flood cost what they cost without it, and the real objects keep their symbols."""

from __future__ import annotations

import numpy as np

from anchoring.synthetic import TrueObject, observe, random_object, spurious
from probanchor.loop.loop import AnchoringLoop, LoopConfig
from probanchor.loop.sources import SourceFrame
from probanchor.percepts import Percept, PerceptFrame

FPS = 15.0


def table(seed: int) -> tuple[np.random.Generator, TrueObject, TrueObject]:
    rng = np.random.default_rng(seed)
    box = random_object(rng, "box", "box")
    box.position = np.array([0.4, 0.3, box.size[2] / 2])
    ball = random_object(rng, "ball", "ball")
    ball.position = np.array([0.8, 0.35, ball.size[2] / 2])
    return rng, box, ball


def step(loop: AnchoringLoop, f: int, percepts: list[Percept]) -> dict[str, str]:
    """One frame through the loop; returns truth id -> symbol of the frame's assignments."""
    outcome = loop.process(SourceFrame(PerceptFrame(f, round(f / FPS, 6), percepts, {}), 0.0))
    return {percepts[a.percept_index].truth_id or "": a.symbol
            for a in outcome.result.assignments}


def test_spurious_anchors_stay_out_of_the_reasoning_and_identities_are_kept() -> None:
    rng, box, ball = table(3)
    loop = AnchoringLoop(LoopConfig(particles=50, seed=3))
    try:
        names: dict[str, set[str]] = {"box": set(), "ball": set()}
        flood: list[str] = []
        for f in range(21):
            t = round(f / FPS, 6)
            percepts = [observe(box, t, rng), observe(ball, t, rng)]
            if f == 4:
                percepts += [spurious(t, rng, f"spurious-{k}") for k in range(60)]
            symbols = step(loop, f, percepts)
            for truth in names:
                names[truth].add(symbols[truth])
            if f == 4:
                flood = [s for truth, s in symbols.items() if truth.startswith("spurious")]
            if 4 <= f < 20:
                # the 60 anchors live (glitches are dropped after a second) but are not
                # reasoned about
                assert len(loop.manager) == 62
                assert loop.reasoned_anchors == 2
                assert loop.reasoner is not None
                assert all(loop.reasoner.belief(s) is None for s in flood[:5])
        assert len(flood) == 60
        assert names == {"box": {"box-1"}, "ball": {"ball-1"}}
        # a second after the flood its anchors are dropped as glitches
        assert not any(s in loop.manager for s in flood)
    finally:
        loop.close()


def test_a_new_object_enters_the_reasoning_when_it_is_perceived_a_second_time() -> None:
    rng, box, ball = table(5)
    loop = AnchoringLoop(LoopConfig(particles=50, seed=5))
    try:
        step(loop, 0, [observe(box, 0.0, rng)])
        assert loop.reasoned_anchors == 0
        step(loop, 1, [observe(box, 1 / FPS, rng)])
        assert loop.reasoned_anchors == 1
        step(loop, 2, [observe(box, 2 / FPS, rng), observe(ball, 2 / FPS, rng)])
        assert loop.reasoned_anchors == 1
        step(loop, 3, [observe(box, 3 / FPS, rng), observe(ball, 3 / FPS, rng)])
        assert loop.reasoned_anchors == 2
        # hidden now, the confirmed ball is carried by the reasoning's particles
        step(loop, 4, [observe(box, 4 / FPS, rng)])
        assert loop.reasoner is not None
        belief = loop.reasoner.belief("ball-1")
        assert belief is not None
        assert np.allclose(np.average(belief.positions, axis=0, weights=belief.weights)[:2],
                           ball.position[:2], atol=0.05)
    finally:
        loop.close()
