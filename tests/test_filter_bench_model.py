"""The benchmark's two implementations of one occlusion model agree: the generated DDC program
(filtered by bridge.Filter) and the vectorised numpy filter of bench/filter_numpy_reference.py."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))

import filter_numpy_reference as model  # noqa: E402
from bridge import Filter  # noqa: E402


@pytest.mark.parametrize("engine", ["per_particle", "batched"])
def test_ddc_program_and_numpy_filter_agree_on_the_occluder_choice(tmp_path: Path,
                                                                   engine: str) -> None:
    m, steps = 3, 3  # a box o1 and two small objects; o2 disappears at step 3
    frames = model.scenario(m, steps, seed=4)
    names = model.object_names(m)
    assert not frames[-1].seen[1] and frames[-1].seen[[0, 2]].all()
    program = tmp_path / "occlusion.pl"
    program.write_text(model.ddc_program(m))
    reference = model.NumpyOcclusionFilter(m, 40000, seed=4)
    with Filter(program, particles=1000, seed=4, engine=engine) as f:
        inverse_ess = 0.0
        for frame in frames:
            inverse_ess += 1 / f.step(frame.terms(names)).ess
            reference.step(frame)
        ess = f.last_step.ess
        ref_w = np.exp(reference.log_weights)
        ref_ess = 1 / float(ref_w @ ref_w)
        # o2 hides under the box o1, or under o3 when o3 happens to be above it in that particle,
        # or (rarely: where o2 drifted above both) under nothing
        dist = {v: p for p, v in f.distribution("hidden_under(o2):t")}
        assert set(dist) <= {"o1", "o3", "none"} and math.isclose(sum(dist.values()), 1.0)
        for h, name in [(0, "o1"), (2, "o3"), (-1, "none")]:
            p_ref = reference.occluded_by(1, h)
            p = dist.get(name, 0.0)
            var = max(p_ref * (1 - p_ref), 1e-3)
            assert abs(p - p_ref) < 5 * math.sqrt(var / ess + var / ref_ess), (name, p, p_ref)
        assert 0.2 < dist["o1"] < 0.95  # the choice is really uncertain
        # the seen box's filtered position agrees too (resampling noise of every step counts)
        mean, cov = f.mean("pos(o1):t")
        ref_mean = reference.mean_position(0)
        sd = np.sqrt(np.diag(cov))
        tolerance = 5 * sd * math.sqrt(inverse_ess + 1 / ref_ess)
        np.testing.assert_array_less(np.abs(mean - ref_mean), tolerance)
