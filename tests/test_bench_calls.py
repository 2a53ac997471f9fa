"""The measuring tools of bench/filter_step.py: the profiler's call counts (``--calls``) and the
batched prototype (``--batched``, bench/filter_batched_prototype.pl) on the bench's model."""

from __future__ import annotations

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))

import filter_numpy_reference as model  # noqa: E402
import filter_step  # noqa: E402
from bridge import Filter  # noqa: E402


def test_call_counts_count_the_engine_predicates_of_the_steps() -> None:
    few = filter_step.call_counts(particles=10, objects=3, steps=2, seed=1)
    more = filter_step.call_counts(particles=40, objects=3, steps=2, seed=1)
    lookups = "ddc_store:store_get/3"
    assert few[lookups] > 0 and any(name.startswith("ddc:read_key/") for name in few)
    # the steps' work grows with the particles: the counts are of those steps, not of a
    # fixed overhead (e.g. loading the program)
    assert more[lookups] > 2 * few[lookups]


def test_batched_prototype_agrees_with_the_engine_on_the_log_likelihood(tmp_path: Path) -> None:
    # 3 objects (a box and two small ones), 4 steps: the first small object is hidden under
    # the box from step 3 on, so the occluder choice and the follow clause run
    n, m, steps, seed = 1000, 3, 4, 2
    batched = filter_step.time_batched(n, m, steps, seed)
    assert batched is not None and batched["batched_ms_per_step"] > 0
    program = filter_step.write_program(str(tmp_path), m)
    names = model.object_names(m)
    inverse_ess = 0.0
    with Filter(program, particles=n, seed=seed) as f:
        for frame in model.scenario(m, steps, seed=seed):
            inverse_ess += 1 / f.step(frame.terms(names)).ess
        engine = f.log_likelihood
    # each run's log-likelihood estimate has a standard error of about sqrt(sum 1/ESS)
    tolerance = 5 * math.sqrt(2 * inverse_ess)
    assert abs(batched["log_likelihood"] - engine) < tolerance, (batched, engine, tolerance)
