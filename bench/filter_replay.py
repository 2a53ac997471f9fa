"""Milliseconds per filter step on a real run's frames: shared values on and off, same run.

    .venv/bin/python bench/filter_replay.py                      # shell game, N = 1000
    .venv/bin/python bench/filter_replay.py --scenario scenarios/transitive.yaml --particles 300

First plays the scenario once through the whole loop (simulator, perception, anchoring, the
theory of occlusion at 100 particles) and records what the loop sends the filter in every frame
(facts and observations, exactly as ``OcclusionReasoner.step`` writes them).  Then replays those
frames on ``bridge.Filter(prolog/too.pl)`` at N particles twice: with the engine's shared values
(the default) and with ``share=False`` (every value computed in every particle).  Both use the
same seed, so they hold the same particles; the bench checks that their log-likelihoods are equal.
Prints the mean time of the Prolog step per frame, overall and by kind of frame (every anchor
perceived / some hidden / none perceived), and the ratio; with sharing, also the time per step
by the number of objects perceived and the time of the runner's belief read
(``Filter.samples("pos(A):t")``) of every anchor hidden in a frame, as the loop makes it after
each step.  ``--shared-only`` leaves the run without sharing out (quicker; no ratio, no
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

from app.reasoning import DEFAULT_THEORY  # noqa: E402
from app.runner import RunOptions, run  # noqa: E402
from bridge import DEFAULT_THREADS, Filter  # noqa: E402

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


def replay(frames: list[Frame], particles: int, seed: int, share: bool,
           threads: int) -> tuple[list[float], float, list[float]]:
    """Prolog milliseconds per step, the final log-likelihood, and milliseconds per belief
    read of a hidden anchor."""
    reads: list[float] = []
    with Filter(DEFAULT_THEORY, particles=particles, seed=seed, share=share,
                threads=threads) as f:
        for frame in frames:
            f.step(frame[0], actions=frame[1])
            for atom in hidden_atoms(frame):
                started = time.perf_counter()
                f.samples(f"pos({atom}):t")
                reads.append(1000 * (time.perf_counter() - started))
        return [1000 * s for s in f.step_prolog_seconds], f.log_likelihood, reads


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenario", type=Path,
                        default=HERE.parent / "scenarios" / "shell_game.yaml")
    parser.add_argument("--particles", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=DEFAULT_THREADS,
                        help="Prolog threads stepping the particles (default: bridge.Filter's)")
    parser.add_argument("--shared-only", action="store_true",
                        help="leave out the replay without sharing")
    args = parser.parse_args(argv)

    frames = record_frames(args.scenario, args.seed)
    kinds = [kind(frame) for frame in frames]
    print(f"{args.scenario.name}: {len(frames)} frames "
          + ", ".join(f"{k} {kinds.count(k)}" for k in sorted(set(kinds))), flush=True)
    shared, shared_ll, reads = replay(frames, args.particles, args.seed, True, args.threads)
    if args.shared_only:
        unshared, unshared_ll = None, shared_ll
    else:
        unshared, unshared_ll, _ = replay(frames, args.particles, args.seed, False, args.threads)
    print(f"N = {args.particles}, {args.threads} thread(s): ms per step"
          f"   {'shared':>8} {'unshared':>9} {'ratio':>6}")
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
    print("ms per step by objects perceived (shared): "
          + ", ".join(f"{k}: {statistics.fmean(v):.1f} ({len(v)} frames)"
                      for k, v in sorted(by_perceived.items())))
    if reads:
        print(f"belief read of a hidden anchor (Filter.samples): {statistics.fmean(reads):.2f} ms"
              f" mean, {statistics.median(reads):.2f} median over {len(reads)} reads")
    if unshared is None:
        return 0
    same = "equal" if shared_ll == unshared_ll else f"DIFFER ({shared_ll} vs {unshared_ll})"
    print(f"log-likelihood of the run, shared vs unshared: {same}")
    return 0 if shared_ll == unshared_ll else 1


if __name__ == "__main__":
    sys.exit(main())
