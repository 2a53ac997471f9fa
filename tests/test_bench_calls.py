"""bench/filter_step.py --calls: the profiler's call counts of the engine's predicates come back
through the bridge (a profile of a few particles and steps)."""

from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))

import filter_step  # noqa: E402


def test_call_counts_count_the_engine_predicates_of_the_steps() -> None:
    few = filter_step.call_counts(particles=10, objects=3, steps=2, seed=1)
    more = filter_step.call_counts(particles=40, objects=3, steps=2, seed=1)
    lookups = "ddc_store:store_get/3"
    assert few[lookups] > 0 and any(name.startswith("ddc:read_key/") for name in few)
    # the steps' work grows with the particles: the counts are of those steps, not of a
    # fixed overhead (e.g. loading the program)
    assert more[lookups] > 2 * few[lookups]
