"""Anchoring on the simulator's percept stream: with no occlusion, every ground-truth object
keeps one symbol for the whole stream (and no two objects share one)."""

from __future__ import annotations

import pytest

tabletop = pytest.importorskip("probanchor.tabletop")
sources = pytest.importorskip("probanchor.loop.sources")

from anchoring import AnchorManager  # noqa: E402


def scene():
    b = tabletop.ScenarioBuilder("no_occlusion", fps=15, duration=7.0)
    b.add("ball_1", "ball", "red", position=(-0.2, -0.02), radius=0.03)
    b.add("ball_2", "ball", "red", position=(0.2, 0.08), radius=0.03)  # a look-alike
    b.add("mug_1", "mug", "blue", position=(0.0, 0.17), radius=0.04, height=0.1)
    b.add("box_1", "box", "green", position=(0.22, -0.13), size=[0.12, 0.1, 0.08])
    # the two red balls pass each other 10 cm apart, then the mug is pushed across the table
    b.move(0.5, "ball_1", to=(0.2, -0.02), speed=0.15)
    b.move(0.5, "ball_2", to=(-0.2, 0.08), speed=0.15)
    b.move(4.0, "mug_1", to=(-0.2, 0.15), speed=0.15)
    return b.build()


def test_simulated_stream_without_occlusion_keeps_every_symbol():
    manager = AnchorManager()
    used: dict[str, list[str]] = {}
    frames = 0
    for frame in sources.perceive_scenario(scene(), seed=3):
        frames += 1
        result = manager.process(frame.time, frame.percepts)
        for i, symbol in result.symbols.items():
            truth = frame.percepts[i].truth_id
            if truth is None:
                continue
            seq = used.setdefault(truth, [])
            if not seq or seq[-1] != symbol:
                seq.append(symbol)
    assert frames >= 100
    assert set(used) == {"ball_1", "ball_2", "mug_1", "box_1"}
    for truth, symbols in used.items():
        assert len(symbols) == 1, f"{truth} was given {symbols}"
    assert used["ball_1"] != used["ball_2"]
    assert used["mug_1"] == ["mug-1"] and used["box_1"] == ["box-1"]
