"""bench/filter_step.py's model and tools: the profiler's call counts (``--calls``), and the
two engines it can time agree on the model's log-likelihood."""

from __future__ import annotations

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))

import filter_numpy_reference as model  # noqa: E402
import filter_step  # noqa: E402
from bridge import Filter  # noqa: E402


def test_call_counts_count_the_engine_predicates_of_the_steps() -> None:
    few = filter_step.call_counts(particles=10, objects=3, steps=2, seed=1, engine="per_particle")
    more = filter_step.call_counts(particles=40, objects=3, steps=2, seed=1,
                                   engine="per_particle")
    lookups = "ddc_store:store_get/3"
    assert few[lookups] > 0 and any(name.startswith("ddc_world:read_key/") for name in few)
    # the steps' work grows with the particles: the counts are of those steps, not of a
    # fixed overhead (e.g. loading the program)
    assert more[lookups] > 2 * few[lookups]


def test_batched_calls_are_counted_too() -> None:
    counts = filter_step.call_counts(particles=40, objects=3, steps=2, seed=1, engine="batched")
    assert any(name.startswith("ddc_batch_eval:eval_body/") for name in counts)
    assert not any(name.startswith("ddc_store:") for name in counts)


def test_the_engines_agree_on_the_log_likelihood(tmp_path: Path) -> None:
    # 3 objects (a box and two small ones), 4 steps: the first small object is hidden under
    # the box from step 3 on, so the occluder choice and the follow clause run
    n, m, steps, seed = 1000, 3, 4, 2
    program = filter_step.write_program(str(tmp_path), m)
    names = model.object_names(m)
    inverse_ess = 0.0
    log_likelihoods = {}
    for engine in ("per_particle", "batched"):
        with Filter(program, particles=n, seed=seed, engine=engine) as f:
            for frame in model.scenario(m, steps, seed=seed):
                inverse_ess += 1 / f.step(frame.terms(names)).ess
            log_likelihoods[engine] = f.log_likelihood
    # each run's log-likelihood estimate has a standard error of about sqrt(sum 1/ESS)
    tolerance = 5 * math.sqrt(inverse_ess)
    difference = abs(log_likelihoods["batched"] - log_likelihoods["per_particle"])
    assert difference < tolerance, (log_likelihoods, tolerance)
