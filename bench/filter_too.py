"""Milliseconds per DDC filter step on prolog/too.pl (the theory of occlusion), runner workload.

    .venv/bin/python bench/filter_too.py            # N in {100, 1000} x M in {4, 10}
    .venv/bin/python bench/filter_too.py --json     # + last line {"ms_per_step": x} (N=1000, M=10)

Each step gets what ``OcclusionReasoner.step`` (python/probanchor/loop/reasoning.py) sends: facts
``object(a)``, ``category(a, C)`` for every object; for perceived ones ``observed(a)`` and
``observation(pos(a)) ~= (X,Y,Z)``.  Scene: M mugs/boxes/balls spread over a 0.6 m x 0.4 m
table, moving slowly; balls are hidden for a few frames at times (occluder picking and
following) and every 10th frame is blind (no observations).  Resampling is done by the
bridge as usual.  Target: N = 1000, M = 10 in at most 33 ms per step.

``--engine`` picks the engine timed, as ``bridge.Filter``'s (default auto: the batched one,
too.pl being in its fragment); the reference column, timed in the same run, is the
per-particle engine, and ``ratio`` is reference / timed. With ``--engine per_particle`` the
reference is the same engine with ``share=False`` (every value computed in every particle:
same particles, bit for bit).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

from bridge import Filter, terms  # noqa: E402
from bridge.engines import ENGINES  # noqa: E402

PROGRAM = HERE.parent / "prolog" / "too.pl"
TARGET_MS = 33.0
CATEGORIES = ("mug", "box", "ball")


def scene(objects: int, steps: int, seed: int) -> list[list[tuple[str, str, tuple | None]]]:
    """Per frame: (atom, category, position or None when not perceived)."""
    rng = np.random.default_rng(seed)
    names = [(f"{CATEGORIES[i % 3]}_{i}", CATEGORIES[i % 3]) for i in range(objects)]
    pos = np.column_stack([rng.uniform(-0.3, 0.3, objects), rng.uniform(-0.2, 0.2, objects),
                           np.where([c == "ball" for _, c in names], 0.03, 0.05)])
    # each ball sits near a mug or box, so that it has an occluder candidate when hidden
    for i, (_, c) in enumerate(names):
        if c == "ball" and i > 0:
            pos[i, :2] = pos[i - 1, :2] + rng.normal(0, 0.03, 2)
    balls = [i for i, (_, c) in enumerate(names) if c == "ball"]
    frames = []
    for t in range(steps):
        pos[:, :2] += rng.normal(0, 0.003, (objects, 2))
        hidden = set()
        for k, b in enumerate(balls[:2]):
            if (t + 4 * k) % 12 >= 6:
                hidden.add(b)
        blind = t % 10 == 9
        frame = []
        for i, (a, c) in enumerate(names):
            seen = not blind and i not in hidden
            p = tuple(float(round(v + rng.normal(0, 0.005), 4)) for v in pos[i]) if seen else None
            frame.append((a, c, p))
        frames.append(frame)
    return frames


def step_terms(frame):
    facts, observations = [], []
    for a, c, p in frame:
        facts.append(terms.fact("object", a))
        facts.append(terms.fact("category", a, c))
        if p is not None:
            observations.append(terms.fact("observed", a))
            observations.append(terms.observation(terms.fact("pos", a), p))
    return observations, facts


def time_filter(particles: int, objects: int, steps: int, seed: int, share: bool = True,
                engine: str = "auto") -> float:
    frames = scene(objects, steps + 2, seed)
    with Filter(str(PROGRAM), particles=particles, seed=seed, share=share, engine=engine) as f:
        times = []
        for k, frame in enumerate(frames):
            obs, facts = step_terms(frame)
            started = time.perf_counter()
            f.step(obs, actions=facts)
            if k >= 2:                      # the first two steps create the objects
                times.append(1000 * (time.perf_counter() - started))
    return statistics.fmean(times)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=int, nargs="*", default=[100, 1000])
    parser.add_argument("--objects", type=int, nargs="*", default=[4, 10])
    parser.add_argument("--steps", type=int, default=20, help="steps timed (default 20)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--json", action="store_true", help="end with a JSON line (N=1000, M=10)")
    parser.add_argument("--engine", choices=ENGINES, default="auto",
                        help="the engine timed (default auto: the batched one for too.pl); the "
                             "reference column is the per-particle engine, or for it the same "
                             "engine without shared values")
    args = parser.parse_args(argv)
    per_particle = args.engine == "per_particle"
    reference_name = "unshared" if per_particle else "per-part."
    print(f"engine: {args.engine}; reference: "
          + ("per-particle engine without shared values" if per_particle
             else "per-particle engine"))
    print(f"{'N':>6} {'M':>4} {'ms/step':>10} {'ms/particle':>12} {reference_name:>10} "
          f"{'ratio':>6}", flush=True)
    last = None
    for m in args.objects:
        for n in args.particles:
            ms = time_filter(n, m, args.steps, args.seed, engine=args.engine)
            if per_particle:
                reference = time_filter(n, m, args.steps, args.seed, share=False,
                                        engine="per_particle")
            else:
                reference = time_filter(n, m, args.steps, args.seed, engine="per_particle")
            print(f"{n:>6} {m:>4} {ms:>10.1f} {ms / n:>12.3f} {reference:>10.1f} "
                  f"{reference / ms:>5.1f}x", flush=True)
            if (n, m) == (1000, 10) or last is None:
                last = ms
            if (n, m) == (1000, 10):
                verdict = "meets" if ms <= TARGET_MS else "misses"
                print(f"  N=1000 M=10: {ms:.1f} ms/step {verdict} the {TARGET_MS:.0f} ms target "
                      f"({ms / TARGET_MS:.1f}x)", flush=True)
    if args.json and last is not None:
        print(json.dumps({"ms_per_step": last}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
