"""Time the world-model store: writing a frame, and resuming a run by replaying its frames.

Plays a scenario with ``--store`` and prints, per frame, the median milliseconds of
``WorldStore.write_frame`` (the frame's transaction: history, anchors, manager state and the
whole particle set) beside the median of the filter step of the same frames (the reference,
measured in the same run); then resumes the finished store (replaying every frame through a
new filter) and prints its time per replayed frame. Run:

    .venv/bin/python bench/store.py [--scenario scenarios/shell_game.yaml] [--particles 1000]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

# bench/perception.py would shadow the perception package
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).resolve().parent]

import numpy as np  # noqa: E402

from probanchor.loop import store as store_module  # noqa: E402
from probanchor.loop.loop import AnchoringLoop  # noqa: E402
from probanchor.loop.runner import RunOptions, run  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenario", type=Path, default=Path("scenarios/shell_game.yaml"))
    ap.add_argument("--particles", type=int, default=1000)
    args = ap.parse_args()
    writes: list[float] = []
    original = store_module.WorldStore.write_frame

    def timed(self: store_module.WorldStore, outcome, loop) -> None:  # noqa: ANN001
        started = time.perf_counter()
        original(self, outcome, loop)
        writes.append((time.perf_counter() - started) * 1000)

    store_module.WorldStore.write_frame = timed  # type: ignore[method-assign]
    with tempfile.TemporaryDirectory() as tmp:
        db = Path(tmp) / "world.db"
        output = run(RunOptions(scenario=args.scenario, particles=args.particles, seed=0,
                                progress=False, store=db))
        filter_ms = np.median([r.timings.filter for r in output.records])
        size = db.stat().st_size / 1e6
        started = time.perf_counter()
        store = store_module.WorldStore.open(db)
        loop = AnchoringLoop(RunOptions(scenario=args.scenario, particles=args.particles,
                                        seed=0))
        try:
            stored = store.resume(loop)
        finally:
            loop.close()
            store.close()
        resume_ms = (time.perf_counter() - started) * 1000 / stored.next_frame
    n = len(output.records)
    print(f"{args.scenario.name}, {args.particles} particles, {n} frames, store {size:.1f} MB")
    print(f"write_frame: median {np.median(writes):.1f} ms per frame; filter step (reference, "
          f"same run): median {filter_ms:.1f} ms; ratio {np.median(writes) / filter_ms:.2f}")
    print(f"resume: {resume_ms:.1f} ms per stored frame (replayed through a new filter)")


if __name__ == "__main__":
    main()
