"""What the identity layer costs a frame: the loop with and without it, in one run.

    .venv/bin/python bench/identity_layer.py                  # shell game + identity_revealed
    .venv/bin/python bench/identity_layer.py --particles 1000 --repeats 3

Each scene is perceived once (its percept stream is kept in memory), then played through the
anchoring loop (anchoring + filter, the timed work of a frame; perception is the same either
way and left out) with the identity hypotheses (``LoopConfig.identity``, the default) and
without them (``--no-identity``: look-alikes' identities decided once), alternately
``--repeats`` times; it prints each one's median milliseconds per frame, the layer's share
of the frame ((with - without) / with) against the 20 % target, and whether every object
ended with its own symbol either way. ``shell_game`` opens no ambiguity group (what the layer
costs a frame that does not need it); ``identity_revealed`` opens one and revises it.
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

from probanchor.evaluation import evaluate  # noqa: E402
from probanchor.loop.loop import AnchoringLoop, LoopConfig, run_frames  # noqa: E402
from probanchor.loop.sources import SourceFrame, perceive_scenario  # noqa: E402
from probanchor.tabletop import load_scenario  # noqa: E402

TARGET = 0.20


def play(frames: list, identity: bool, particles: int, seed: int) -> tuple[float, bool]:
    """Median ms per frame of anchoring + filter, and whether every object ended with its
    own symbol (at the end of the run)."""
    loop = AnchoringLoop(LoopConfig(particles=particles, seed=seed, threads=1,
                                    identity=identity))
    times: list[float] = []

    def source(frame):  # noqa: ANN001, ANN202
        return lambda: SourceFrame(frame, 0.0)

    def timed(outcome, loop):  # noqa: ANN001, ANN202
        t = outcome.record.timings
        times.append(t.anchoring + t.filter)

    try:
        records = run_frames((source(f) for f in frames), loop, timed, overlap=False)
    finally:
        loop.close()
    return statistics.median(times), evaluate(records).all_kept_at_end


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenarios", default="shell_game,identity_revealed")
    parser.add_argument("--particles", type=int, default=1000)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    print(f"identity layer: anchoring + filter ms per frame (median), {args.particles} "
          f"particles, 1 thread, {args.repeats} alternating repeats")
    print("| scene | with the layer ms | without ms | share of the frame | target | "
          "kept at the end (with / without) |")
    print("|---|---:|---:|---:|---:|---|")
    worst = 0.0
    for name in args.scenarios.split(","):
        scenario = load_scenario(HERE.parent / "scenarios" / f"{name}.yaml")
        frames = list(perceive_scenario(scenario, seed=args.seed))
        with_ms: list[float] = []
        without_ms: list[float] = []
        kept = {True: True, False: True}
        for _ in range(args.repeats):
            for identity, into in ((True, with_ms), (False, without_ms)):
                ms, ok = play(frames, identity, args.particles, args.seed)
                into.append(ms)
                kept[identity] &= ok
        w, wo = statistics.median(with_ms), statistics.median(without_ms)
        share = (w - wo) / w if w > 0 else 0.0
        worst = max(worst, share)
        print(f"| {name} | {w:.1f} | {wo:.1f} | {100 * share:+.1f} % | "
              f"{100 * TARGET:.0f} % | {kept[True]} / {kept[False]} |")
    print(f"largest share {100 * worst:+.1f} % (target at most {100 * TARGET:.0f} %): "
          f"{'met' if worst <= TARGET else 'NOT met'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
