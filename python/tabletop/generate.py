"""Random shell games, built with :class:`tabletop.ScenarioBuilder`.

K containers (mugs, boxes and cups, turned over, in a row), one ball; a hand covers the
camera while the ball goes under a random container; S random swaps of two containers (the
ball moves with its container); then the containers are lifted one by one in random order.
The same seed gives the same game.
"""

from __future__ import annotations

import numpy as np

from tabletop.builder import ScenarioBuilder

CONTAINER_KINDS = (
    ("mug", {"radius": 0.04, "height": 0.1}),
    ("box", {"size": [0.12, 0.12, 0.12]}),
    ("cup", {"radius": 0.04, "height": 0.1}),
)
COLOURS = ("blue", "green", "white", "purple", "yellow", "cyan", "black", "orange")


def shell_game(containers: int = 3, swaps: int = 3, seed: int = 0, fps: float = 15.0,
               swap_duration: float = 2.0) -> ScenarioBuilder:
    """A random shell game with ``containers`` (2..5) containers and ``swaps`` swaps."""
    if not 2 <= containers <= 5:
        raise ValueError(f"containers must be 2 to 5, got {containers}")
    if swaps < 0:
        raise ValueError(f"swaps must be >= 0, got {swaps}")
    rng = np.random.default_rng(seed)
    b = ScenarioBuilder(f"shell_game_k{containers}_s{swaps}_seed{seed}", fps=fps)
    b.add("ball_1", "ball", "red", position=(0.0, -0.17), radius=0.03)
    spacing = 0.18  # wide enough for two 12 cm boxes side by side (their footprints must not touch)
    xs = (np.arange(containers) - (containers - 1) / 2) * spacing
    colours = rng.permutation(COLOURS)[:containers]
    counts: dict[str, int] = {}
    ids = []
    for i, x in enumerate(xs):
        kind, params = CONTAINER_KINDS[int(rng.integers(len(CONTAINER_KINDS)))]
        if i == 0 and containers >= 2:
            kind, params = CONTAINER_KINDS[0]
        counts[kind] = counts.get(kind, 0) + 1
        oid = f"{kind}_{counts[kind]}"
        ids.append(oid)
        b.add(oid, kind, str(colours[i]), position=(float(x), 0.06), **params)
    hider = ids[int(rng.integers(containers))]
    # where each container stands: the row, and the ball's place for the one put over it
    spot = {oid: (float(x), 0.06) for oid, x in zip(ids, xs, strict=True)}
    spot[hider] = (0.0, -0.17)
    t = 1.0
    b.cover_camera(t, duration=2.6)
    b.put_under(t + 0.2, "ball_1", hider, duration=2.2)
    t += 3.2
    for _ in range(swaps):
        a, c = rng.choice(containers, size=2, replace=False)
        b.swap(t, ids[int(a)], ids[int(c)], duration=swap_duration)
        spot[ids[int(a)]], spot[ids[int(c)]] = spot[ids[int(c)]], spot[ids[int(a)]]
        t += swap_duration + 0.4
    for i in rng.permutation(containers):
        x, y = spot[ids[int(i)]]
        # set down 13 cm further back, clear of the row; the one on the ball's place (in
        # front of the row) 13 cm to the side instead: further back it would land on the
        # row's middle container (two boxes 10 cm apart), in front it would hide the ball
        to = (x, y + 0.13) if y > 0 else (x + 0.13, y)
        b.lift(t, ids[int(i)], to=to, duration=2.0)
        t += 2.5
    return b
