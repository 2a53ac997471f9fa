"""Swap paths go around the other objects standing on the table, not through them."""

from __future__ import annotations

import numpy as np

from probanchor.tabletop import ScenarioBuilder
from probanchor.tabletop.timeline import Timeline


def closest_approach(builder: ScenarioBuilder, movers: tuple[str, str], still: str) -> float:
    """Smallest distance over the scenario between ``still`` and either mover, as a fraction
    of 0.9 times the sum of their footprint radii (>= 1: clear)."""
    scenario = builder.build()
    specs = {o.id: o for o in scenario.objects}
    timeline = Timeline(scenario, (0.05, 0.05, 0.05))
    worst = np.inf
    for t in np.arange(0.0, scenario.end_time() + 1e-9, 0.02):
        state = timeline.advance(float(t))
        for m in movers:
            d = float(np.linalg.norm(state.positions[m][:2] - state.positions[still][:2]))
            worst = min(worst, d / (0.9 * (specs[m].footprint_radius()
                                           + specs[still].footprint_radius())))
    return worst


def test_a_swap_between_the_row_and_the_front_goes_around_the_row_neighbour():
    """The layout of a generated shell game after the ball went under a container: one
    container in front of the row. The symmetric arcs put one of the two 6.6 cm from the
    row's next mug, inside it (seen as one segment with it for 0.7 s)."""
    b = ScenarioBuilder("around", duration=3.0)
    b.add("mug_1", "mug", "green", position=(-0.25, 0.06), radius=0.04, height=0.1)
    b.add("mug_2", "mug", "yellow", position=(-0.087, 0.06), radius=0.04, height=0.1)
    b.add("mug_3", "mug", "white", position=(0.0, -0.17), radius=0.04, height=0.1)
    b.swap(0.5, "mug_1", "mug_3", duration=2.0)
    assert closest_approach(b, ("mug_1", "mug_3"), "mug_2") >= 1.0


def test_a_swap_with_nothing_in_the_way_keeps_its_symmetric_arcs():
    b = ScenarioBuilder("clear", duration=3.0)
    b.add("mug_1", "mug", "green", position=(-0.09, 0.06), radius=0.04, height=0.1)
    b.add("box_1", "box", "white", position=(0.09, 0.06), size=[0.12, 0.12, 0.12])
    b.add("cup_1", "cup", "blue", position=(0.4, 0.3), radius=0.04, height=0.1)
    b.swap(0.5, "mug_1", "box_1", duration=2.0)
    scenario = b.build()
    timeline = Timeline(scenario, (0.05, 0.05, 0.05))
    state = timeline.advance(1.5)  # half way: at the waypoints, mirror images of each other
    a, c = state.positions["mug_1"][:2], state.positions["box_1"][:2]
    assert np.allclose((a + c) / 2, [0.0, 0.06], atol=1e-6)
