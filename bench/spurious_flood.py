"""Time the frames after a flood of spurious percepts, against frames without one.

A box and a ball on the table, seen at 15 frames per second through anchoring and the
occlusion reasoning (``prolog/too.pl``); in one frame K percepts of nothing (random sizes,
colours and places, seen once) come with them. Prints, for each K, the median ms per frame of
the 15 frames after the flood (the time spurious anchors live before they are dropped as
glitches), the reference measured in the same run (the median of the 15 frames before it), the
ratio, the anchors that entered the reasoning in the frame after the flood, and whether the
box and the ball kept their symbols. Run:

    .venv/bin/python bench/spurious_flood.py [--floods 0 50 200] [--particles 300]
"""

from __future__ import annotations

import argparse
import statistics
import time

import numpy as np

from anchoring.synthetic import observe, random_object, spurious
from probanchor.loop.loop import AnchoringLoop, LoopConfig
from probanchor.loop.sources import SourceFrame
from probanchor.percepts import PerceptFrame

FPS = 15.0
BEFORE = 15  # frames timed before the flood
AFTER = 15  # frames timed after it (the 1 s a glitch lives, at 15 fps)


def run(flood: int, particles: int, seed: int) -> tuple[float, float, int, bool]:
    """One run with a flood of ``flood`` spurious percepts; returns (median ms after,
    median ms before, anchors in the reasoning after the flood, identities kept)."""
    rng = np.random.default_rng(seed)
    box = random_object(rng, "box", "box")
    box.position = np.array([0.4, 0.3, box.size[2] / 2])
    ball = random_object(rng, "ball", "ball")
    ball.position = np.array([0.8, 0.35, ball.size[2] / 2])
    loop = AnchoringLoop(LoopConfig(particles=particles, seed=seed))
    symbols: dict[str, set[str]] = {"box": set(), "ball": set()}
    times: list[float] = []
    entered = 0
    try:
        for f in range(1 + BEFORE + 1 + AFTER):
            t = round(f / FPS, 6)
            percepts = [observe(box, t, rng), observe(ball, t, rng)]
            if f == 1 + BEFORE:
                percepts += [spurious(t, rng, f"spurious-{k}") for k in range(flood)]
            frame = PerceptFrame(f, t, percepts, {})
            started = time.perf_counter()
            outcome = loop.process(SourceFrame(frame, 0.0))
            times.append((time.perf_counter() - started) * 1000)
            for a in outcome.result.assignments:
                truth = percepts[a.percept_index].truth_id
                if truth in symbols:
                    symbols[truth].add(a.symbol)
            if f == 1 + BEFORE + 1:
                entered = loop.reasoned_anchors
    finally:
        loop.close()
    before = statistics.median(times[1:1 + BEFORE])
    after = statistics.median(times[2 + BEFORE:])
    kept = all(len(s) == 1 for s in symbols.values())
    return after, before, entered, kept


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--floods", type=int, nargs="+", default=[0, 50, 200])
    ap.add_argument("--particles", type=int, default=300)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    print(f"{'K':>5} {'ms after':>9} {'ms before':>10} {'ratio':>6} {'reasoned':>9} kept")
    for k in args.floods:
        after, before, entered, kept = run(k, args.particles, args.seed)
        print(f"{k:5d} {after:9.1f} {before:10.1f} {after / before:6.2f} {entered:9d} {kept}")


if __name__ == "__main__":
    main()
