"""Milliseconds per filter step on a real run's frames: the engine against a reference, same run.

    .venv/bin/python bench/filter_replay.py                      # shell game, N = 1000
    .venv/bin/python bench/filter_replay.py --scenario scenarios/transitive.yaml --particles 300
    .venv/bin/python bench/filter_replay.py --engine per_particle   # shared values on and off

First plays the scenario once through the whole loop (simulator, perception, anchoring, the
theory of occlusion at 100 particles) and records what the loop sends the filter in every frame
(facts and observations, exactly as ``OcclusionReasoner.step`` writes them).  Then replays those
frames on ``bridge.Filter(prolog/too.pl)`` at N particles twice: with ``--engine`` (default auto,
the batched engine for too.pl) and with the per-particle engine; with ``--engine per_particle``,
with its shared values (the default) and with ``share=False`` (every value computed in every
particle). Both replays use the same seed: two engines draw other particles, so the bench
checks that their log-likelihoods agree within five standard errors (sqrt of the sum of 1/ESS
of each run); sharing or not, the particles are the same, so they must be equal.
Prints the mean time of the Prolog step per frame, overall and by kind of frame (every anchor
perceived / some hidden / none perceived), and the ratio; for the engine timed, also the time
per step by the number of objects perceived and the time of the runner's belief read
(``Filter.samples("pos(A):t")``) of every anchor hidden in a frame, as the loop makes it after
each step.  ``--shared-only`` leaves the reference replay out (quicker; no ratio, no
log-likelihood check).  Issue 7's target: 15 frames per second end to end at N = 1000, i.e.
about 55 ms for the filter.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

from bridge import DEFAULT_THREADS, Filter  # noqa: E402
from bridge.engines import ENGINES  # noqa: E402
from probanchor.loop.reasoning import DEFAULT_THEORY  # noqa: E402
from probanchor.loop.runner import RunOptions, run  # noqa: E402

Frame = tuple[list[str], list[str]]


def record_frames(scenario: Path, seed: int) -> list[Frame]:
    """The filter inputs of one run of the scenario (observations, facts), as Prolog text."""
    frames: list[Frame] = []
    original = Filter.step

    def recording_step(self: Filter, observations, actions=()):  # type: ignore[no-untyped-def]
        frames.append((self._texts("observation", observations),
                       self._texts("action", actions)))
        return original(self, observations, actions)

    Filter.step = recording_step  # type: ignore[method-assign]
    try:
        run(RunOptions(scenario=scenario, particles=100, seed=seed, progress=False))
    finally:
        Filter.step = original  # type: ignore[method-assign]
    return frames


def kind(frame: Frame) -> str:
    observed = sum(text.startswith("observed(") for text in frame[0])
    objects = sum(text.startswith("object(") for text in frame[1])
    if observed == 0:
        return "none perceived"
    return "all perceived" if observed == objects else "some hidden"


def hidden_atoms(frame: Frame) -> list[str]:
    """The anchors (as atoms) that exist but are not perceived in a frame."""
    def atoms(texts: list[str], name: str) -> set[str]:
        return {t[len(name) + 1:-1] for t in texts if t.startswith(name + "(")}
    return sorted(atoms(frame[1], "object") - atoms(frame[0], "observed"))


def replay(frames: list[Frame], particles: int, seed: int, share: bool, threads: int,
           engine: str = "auto") -> tuple[list[float], float, list[float], float]:
    """Prolog milliseconds per step, the final log-likelihood, milliseconds per belief read of
    a hidden anchor, and the sum over steps of 1/ESS (the log-likelihood's variance)."""
    reads: list[float] = []
    inverse_ess = 0.0
    with Filter(DEFAULT_THEORY, particles=particles, seed=seed, share=share,
                threads=threads, engine=engine) as f:
        for frame in frames:
            inverse_ess += 1 / f.step(frame[0], actions=frame[1]).ess
            for atom in hidden_atoms(frame):
                started = time.perf_counter()
                f.samples(f"pos({atom}):t")
                reads.append(1000 * (time.perf_counter() - started))
        return [1000 * s for s in f.step_prolog_seconds], f.log_likelihood, reads, inverse_ess


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenario", type=Path,
                        default=HERE.parent / "scenarios" / "shell_game.yaml")
    parser.add_argument("--particles", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=DEFAULT_THREADS,
                        help="Prolog threads stepping the particles (default: bridge.Filter's)")
    parser.add_argument("--shared-only", action="store_true",
                        help="leave out the reference replay")
    parser.add_argument("--engine", choices=ENGINES, default="auto",
                        help="the engine timed (default auto: the batched one for too.pl); the "
                             "reference is the per-particle engine, or for it the same engine "
                             "without shared values")
    args = parser.parse_args(argv)
    per_particle = args.engine == "per_particle"
    names = ("shared", "unshared") if per_particle else ("timed", "per-part.")

    frames = record_frames(args.scenario, args.seed)
    kinds = [kind(frame) for frame in frames]
    print(f"{args.scenario.name}: {len(frames)} frames "
          + ", ".join(f"{k} {kinds.count(k)}" for k in sorted(set(kinds))), flush=True)
    shared, shared_ll, reads, shared_ie = replay(frames, args.particles, args.seed, True,
                                                 args.threads, args.engine)
    if args.shared_only:
        unshared, unshared_ll, unshared_ie = None, shared_ll, 0.0
    else:
        unshared, unshared_ll, _, unshared_ie = replay(
            frames, args.particles, args.seed, not per_particle, args.threads, "per_particle")
    print(f"engine {args.engine}, N = {args.particles}, {args.threads} thread(s): ms per step"
          f"   {names[0]:>8} {names[1]:>9} {'ratio':>6}")
    rows = [("all frames", list(range(len(frames))))]
    rows += [(k, [i for i, x in enumerate(kinds) if x == k]) for k in sorted(set(kinds))]
    for label, index in rows:
        a = statistics.fmean(shared[i] for i in index)
        if unshared is None:
            print(f"  {label:<16} {a:>16.1f}")
        else:
            b = statistics.fmean(unshared[i] for i in index)
            print(f"  {label:<16} {a:>16.1f} {b:>9.1f} {b / a:>5.1f}x")
    by_perceived: dict[int, list[float]] = {}
    for frame, ms in zip(frames, shared, strict=True):
        perceived = sum(text.startswith("observed(") for text in frame[0])
        by_perceived.setdefault(perceived, []).append(ms)
    print(f"ms per step by objects perceived ({names[0]}): "
          + ", ".join(f"{k}: {statistics.fmean(v):.1f} ({len(v)} frames)"
                      for k, v in sorted(by_perceived.items())))
    if reads:
        print(f"belief read of a hidden anchor (Filter.samples): {statistics.fmean(reads):.2f} ms"
              f" mean, {statistics.median(reads):.2f} median over {len(reads)} reads")
    if unshared is None:
        return 0
    if per_particle:  # the same particles: the same log-likelihood
        ok = shared_ll == unshared_ll
        verdict = "equal" if ok else f"DIFFER ({shared_ll} vs {unshared_ll})"
    else:             # other draws: within 5 standard errors, sqrt(sum 1/ESS) each
        tolerance = 5 * (shared_ie + unshared_ie) ** 0.5
        ok = abs(shared_ll - unshared_ll) < tolerance
        verdict = (f"{shared_ll:.3f} vs {unshared_ll:.3f}, "
                   f"{'within' if ok else 'NOT within'} {tolerance:.2f}")
    print(f"log-likelihood of the run, {names[0]} vs {names[1]}: {verdict}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
