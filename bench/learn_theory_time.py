"""Seconds to learn the whole theory of occlusion from collected games, perception cached.

    .venv/bin/python bench/learn_theory_time.py [--games 80] [--jobs 2] [--labels truth,hindsight]
        [--out out/learn_time]

For each kind of labels: ``anchoring collect`` of the first ``--games`` generated occlusion games
(as ``make learned-theory`` collects them; the percept streams cached in ``out/collect``, so that
perception is not timed: run it once first, or ``make learned-theory``), then ``anchoring
learn-theory`` on the data (the tree, the onset reach, the affordances; the theory written to
``--out``, not to prolog/). It prints the seconds of each stage, their sum and whether the sum is
within the target of 120 s per kind of labels (on the 2-core machine), and the seconds the first
run spent perceiving (0 when every stream was cached).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))

TARGET_S = 120.0


def main(argv: list[str] | None = None) -> int:
    from probanchor.learning.collect import CollectOptions, collect
    from probanchor.learning.learned_theory import learn_theory
    from probanchor.learning.occlusion_data import LabelOptions

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--games", type=int, default=80)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--labels", default="truth,hindsight")
    parser.add_argument("--cache", type=Path, default=Path("out/collect"))
    parser.add_argument("--out", type=Path, default=Path("out/learn_time"))
    args = parser.parse_args(argv)
    print(f"{args.games} games, {args.jobs} job(s), streams cached in {args.cache}")
    print(f"{'labels':>10} {'collect s':>10} {'perceive s':>11} {'learn s':>8} {'total s':>8}",
          flush=True)
    for source in args.labels.split(","):
        data = args.out / f"data_{source}.pl"
        started = time.perf_counter()
        report = collect(CollectOptions(out=data, games=args.games, seed=0, cache=args.cache,
                                        jobs=args.jobs, labels=LabelOptions(source=source)))
        collected = time.perf_counter() - started
        started = time.perf_counter()
        learn_theory([data], args.out / f"too_learned_{source}.pl", seed=0)
        learned = time.perf_counter() - started
        total = collected + learned
        verdict = "meets" if total <= TARGET_S else "misses"
        perceived = report.seconds_perception
        print(f"{source:>10} {collected:>10.1f} {perceived:>11.1f} {learned:>8.1f} "
              f"{total:>8.1f}  ({verdict} the {TARGET_S:.0f} s target)", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
