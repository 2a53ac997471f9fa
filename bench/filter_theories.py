"""The learned theory of occlusion against the hand-written one: ms per filter step, side by side.

    .venv/bin/python bench/filter_theories.py                   # M = 12 objects, N = 1000
    .venv/bin/python bench/filter_theories.py --objects 12 --particles 1000 --steps 30

The three theories (prolog/too.pl, written by hand; prolog/too_learned.pl and
prolog/too_learned_hindsight.pl, their occlusion rules a tree learned by ``anchoring
learn-theory`` from ground truth and from hindsight) filter the same frames of a generated table
(bench/filter_too.py's scene: mugs, boxes and balls, balls hidden for a few frames at times,
every 10th frame blind), in the same run, with the same seed and threads, one after the other in
each of ``--rounds`` rounds (the median round counts: a shared machine's load changes between
runs). It prints each one's wall and CPU ms per step (the CPU time of the whole process, every
Prolog thread's included: steadier on a shared machine) and the learned theories' ratios to
the hand-written one's. Target: each learned theory within 1.2x of the hand-written theory.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "python"))

from bridge import DEFAULT_THREADS, Filter  # noqa: E402
from filter_too import scene, step_terms  # noqa: E402

THEORIES = {"hand-written": HERE.parent / "prolog" / "too.pl",
            "learned": HERE.parent / "prolog" / "too_learned.pl",
            "hindsight": HERE.parent / "prolog" / "too_learned_hindsight.pl"}
TARGET_RATIO = 1.2
WARM_UP = 2  # the first steps create the objects


def time_theory(program: Path, particles: int, objects: int, steps: int, seed: int,
                threads: int) -> tuple[float, float]:
    """(wall, CPU) ms per step, the first WARM_UP steps left out."""
    frames = scene(objects, steps + WARM_UP, seed)
    with Filter(str(program), particles=particles, seed=seed, threads=threads) as f:
        wall, cpu = [], []
        for k, frame in enumerate(frames):
            obs, facts = step_terms(frame)
            started, cpu_started = time.perf_counter(), time.process_time()
            f.step(obs, actions=facts)
            if k >= WARM_UP:
                wall.append(1000 * (time.perf_counter() - started))
                cpu.append(1000 * (time.process_time() - cpu_started))
    return statistics.fmean(wall), statistics.fmean(cpu)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--particles", type=int, default=1000)
    parser.add_argument("--objects", type=int, default=12)
    parser.add_argument("--steps", type=int, default=30, help="steps timed (default 30)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=DEFAULT_THREADS)
    parser.add_argument("--rounds", type=int, default=3, help="rounds (default 3; the median "
                        "of each theory's counts)")
    args = parser.parse_args(argv)
    print(f"N={args.particles} M={args.objects}, {args.steps} steps, {args.threads} thread(s), "
          f"{args.rounds} round(s)")
    print(f"{'round':>5} {'theory':>14} {'wall ms/step':>13} {'CPU ms/step':>12}", flush=True)
    rounds: dict[str, list[tuple[float, float]]] = {name: [] for name in THEORIES}
    for r in range(args.rounds):
        for name, program in THEORIES.items():
            t = time_theory(program, args.particles, args.objects, args.steps, args.seed,
                            args.threads)
            rounds[name].append(t)
            print(f"{r + 1:>5} {name:>14} {t[0]:>13.1f} {t[1]:>12.1f}", flush=True)
    times = {name: (statistics.median(w for w, _ in ts), statistics.median(c for _, c in ts))
             for name, ts in rounds.items()}
    print(f"{'median':>5} {'hand-written':>14} {times['hand-written'][0]:>13.1f} "
          f"{times['hand-written'][1]:>12.1f}")
    for name in ("learned", "hindsight"):
        wall = times[name][0] / times["hand-written"][0]
        cpu = times[name][1] / times["hand-written"][1]
        verdict = "meets" if wall <= TARGET_RATIO else "misses"
        print(f"{'median':>5} {name:>14} {times[name][0]:>13.1f} {times[name][1]:>12.1f}   "
              f"/ hand-written: {wall:.2f}x wall ({verdict} the {TARGET_RATIO}x target), "
              f"{cpu:.2f}x CPU")
    return 0


if __name__ == "__main__":
    sys.exit(main())
